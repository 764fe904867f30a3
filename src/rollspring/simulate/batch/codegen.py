"""Code generation: the kernel module of one plan (topology, per-run and common fields, stop mode).

Runs are processed in blocks of :data:`BLOCK` lanes; every loop over the lanes is straight-line
code for one lane that LLVM vectorises, and no lane reads another lane's state: a block's OR of
the lanes' event conditions only decides whether the scalar event pass runs, and that pass
recomputes each lane's own conditions (a lane's motion and metrics are the same in any batch).

The force terms are not written here: the generated code calls the scalar functions of
:mod:`rollspring.simulate.kernels.law` (the spring's pull and length, torques, the generalised
force, friction and normal force, a constant force's work), which Numba inlines into each lane
loop with its ``fastmath`` flags; the generated module's source carries the law's hash, so its
cache follows the law (docs/force-law.md).
"""

from __future__ import annotations

import hashlib
import re
import threading
from functools import cache
from pathlib import Path

from rollspring.simulate.batch.plan import Plan
from rollspring.simulate.kernels import law
from rollspring.simulate.kernels.stepping import STATUS_LIFTOFF, STATUS_NONFINITE, STATUS_SLIP

__all__ = [
    "BLOCK",
    "LINE",
    "OUT_BODY",
    "OUT_COLUMNS",
    "OUT_EVENT_TIME",
    "SINCOS",
    "Source",
    "kernel_source",
]

#: Runs per block (lanes of the vectorised inner loops).
BLOCK = 256
#: Bytes of a cache line: a block's buffers start on one (``Source.buffers``).
LINE = 64
_RS = BLOCK + 8  # row stride of the block-local arrays; padding avoids 4 KiB store/load aliasing
assert (_RS * 8) % LINE == 0  # every row starts on a cache line

# columns of OUT: event time, E0, max |E - E0|, CM and X-hat extremes, crossings, then per body
# (best |f|, its N, min N, final x, final v)
OUT_EVENT_TIME = 0
OUT_COLUMNS = {
    "E0": 1,
    "DE": 2,
    "CMLO": 3,
    "CMHI": 4,
    "XHLO": 5,
    "XHHI": 6,
    "CF": 7,
    "CL": 8,
    "CN": 9,
}
OUT_BODY = 10
_C_TEV, _OUT_ROWS, _C_BODY = OUT_EVENT_TIME, OUT_COLUMNS, OUT_BODY

_MAX = "{dst} = {x} if {x} > {old} else {old} + 0.0"  # +0.0: an unconditional store (no masks)
_MIN = "{dst} = {x} if {x} < {old} else {old} + 0.0"
_FASTMATH = '{"contract"}'


class Source:
    """The generated kernel module for one plan (topology, varying fields, stop mode).

    Every loop over the lanes is a small compiled function of its own (LLVM vectorises each
    cleanly); ``block`` strings them together for one block of runs and ``run`` spreads the
    blocks over the cores.
    """

    def __init__(self, plan: Plan, varying: list[str], constant: list[str], stop: bool):
        self.p = plan
        self.n = plan.n
        self.varying = {name: r for r, name in enumerate(varying)}
        self.constant = {name: c for c, name in enumerate(constant)}
        self.stop = stop
        n = self.n
        rows = [f"y{i}" for i in range(n)] + [f"u{i}" for i in range(n)]
        rows += ["E0", "DE", "CMLO", "CMHI", "XHLO", "XHHI", "CP", "CF", "CL", "CN", "ACT", "LIVE"]
        for i in range(n):
            rows += [f"FB{i}", f"NB{i}", f"NMIN{i}"]
        # a body on one horizontal centre spring: |f| = |m s^2/J - 1| |T|, so the largest |T|
        # of that spring gives its largest |f| (N is constant)
        self.tension_of = {i: k for k, members in plan.simple.items() for i in members}
        rows += [f"TM{k}" for k in sorted(plan.simple)]
        self.rows = {name: r * _RS for r, name in enumerate(rows)}
        self.n_rows = len(rows)
        self.used: set[str] = set()
        self.used_const: set[str] = set()
        self.period = bool(plan.springs)
        # bodies whose generalised force has a torque about the centre (off-centre points)
        self.torqued = {
            i
            for sp in plan.springs
            for i, kind in zip(sp.ends, sp.kinds, strict=True)
            if kind == "off"
        }
        self.torqued |= {i for i, off in plan.forces if off}

    # -- helpers -------------------------------------------------------------------------
    def fld(self, name: str) -> str:
        """A per-run field: a block constant, or this lane's value (loaded at the loop top)."""
        if name in self.constant:
            self.used_const.add(name)
            return f"c_{name}"
        self.used.add(name)
        return f"p_{name}"

    def row(self, name: str, lane: str) -> str:
        return f"S[{self.rows[name]} + {lane}]"

    def function(
        self, name: str, args: str, body: list[str], returns: str | None = None
    ) -> list[str]:
        """A compiled function: the block constants it uses, then ``body``."""
        consts = [f"c_{c} = C[{self.constant[c]}]" for c in sorted(self.used_const)]
        self.used_const = set()
        lines = [
            "",
            "",
            f'@njit(cache=True, error_model="numpy", fastmath={_FASTMATH})',
            f"def {name}({args}):",
            *_indent(consts + body),
        ]
        if returns is not None:
            lines.append(f"    return {returns}")
        return lines

    def lane_loop(self, body: list[str]) -> list[str]:
        """``for j in range(B)`` over ``body`` (straight-line code for lane ``j``), after the
        loads of this lane's varying fields."""
        return ["for j in range(B):", *_indent(self.loads("j") + body)]

    def loads(self, lane: str) -> list[str]:
        lines = [
            f"p_{name} = Pl[{self.varying[name] * _RS} + {lane}]" for name in sorted(self.used)
        ]
        self.used = set()
        return lines

    # -- physics -------------------------------------------------------------------------
    def forces(self, y: list[str], energy: bool, lever: bool, acc: bool = True) -> list[str]:
        """Lines defining, for the displacements named in ``y``: gx{i} (:math:`Q_i/s_i`, (M7)),
        acc{i} (centre acceleration :math:`\\ddot y_i = (s_i^2/J_i)\\,Q_i/s_i`, with ``acc``),
        fx{i} (horizontal applied force),
        fy{i} (vertical; bodies whose normal force varies), U (potential energy, with
        ``energy``) and lba/lbb (rate of the first spring's length per unit centre velocity of
        its ends, with ``lever``)."""
        p, F = self.p, self.fld
        n = self.n
        lines: list[str] = []
        fx: dict[int, list[str]] = {i: [] for i in range(n)}
        fy: dict[int, list[str]] = {i: [] for i in range(n)}
        tau: dict[int, list[str]] = {i: [] for i in range(n)}  # clockwise torque about centre
        energy_terms: list[str] = []
        for k, sp in enumerate(p.springs):
            stiff, rest = F(f"k_{k}"), F(f"L_{k}")
            # per end: x, y, arm (x, y of P - C, for torques) and velocity factors (wx, wy)
            ends: list[tuple[str | None, str | None, str | None, str | None, str, str]] = []
            general = sp.geometry == "general"  # (positions needed; else offsets at rest)
            for e, (i, kind) in enumerate(zip(sp.ends, sp.kinds, strict=True)):
                if kind == "anchor":
                    ends.append(
                        (
                            F(f"ax_{k}_{e}") if general else None,
                            F(f"ay_{k}_{e}") if general else None,
                            None,
                            None,
                            "0.0",
                            "0.0",
                        )
                    )
                elif kind == "centre":
                    ends.append(
                        (
                            f"({F(f'x0_{i}')} + {y[i]})" if general else None,
                            F(f"cy_{i}") if general else None,
                            None,
                            None,
                            "1.0",
                            "0.0",
                        )
                    )
                else:
                    r = F(f"r_{k}_{e}")
                    lines += [
                        f"sn, cs = sincos({F(f'al_{k}_{e}')} + {y[i]} * {F(f'is_{i}')})",
                        f"ox{k}_{e} = {r} * sn",
                        f"oy{k}_{e} = {r} * cs",
                    ]
                    ends.append(
                        (
                            f"({F(f'x0_{i}')} + {y[i]} + ox{k}_{e})",
                            f"({F(f'cy_{i}')} + oy{k}_{e})",
                            f"ox{k}_{e}",
                            f"oy{k}_{e}",
                            f"(1.0 + oy{k}_{e} * {F(f'is_{i}')})",
                            f"(-ox{k}_{e} * {F(f'is_{i}')})",
                        )
                    )
            (ax, ay, aox, aoy, awx, awy), (bx, by, box, boy, bwx, bwy) = ends
            ia, ib = sp.ends
            if sp.geometry == "general":
                lines.append(f"d{k} = {bx} - {ax}")
            else:  # ends at centres or anchors: the x-offset at rest plus the displacements
                shift = " ".join(
                    t
                    for t in (f"+ {y[ib]}" if ib >= 0 else "", f"- {y[ia]}" if ia >= 0 else "")
                    if t
                )
                lines.append(f"d{k} = {F(f'dx_{k}')} {shift}")
            if sp.geometry == "flat":
                lines.append(f"tx{k} = level_pull({stiff}, {rest}, d{k})")
                ty = None
                if energy:
                    lines.append(f"ext{k} = abs(d{k}) - {rest}")
                if lever and k == 0:
                    lines.append(f"ex{k} = math.copysign(1.0, d{k})")
                    ex, ey = f"ex{k}", None
            else:
                dy = F(f"dy_{k}") if sp.geometry == "fixed" else f"({by} - {ay})"
                lines += [
                    f"e{k} = {dy}",
                    f"l{k} = distance(d{k}, e{k})",
                    f"ext{k} = l{k} - {rest}",
                    f"tn{k} = elastic_tension({stiff}, {rest}, l{k})",
                    f"tx{k}, ty{k} = pull(tn{k}, d{k}, e{k}, l{k})",
                ]
                ty = f"ty{k}"
                if lever and k == 0:
                    lines += [f"ex{k} = d{k} / l{k}", f"ey{k} = e{k} / l{k}"]
                    ex, ey = f"ex{k}", f"ey{k}"
            if energy:
                energy_terms.append(f"+ 0.5 * {stiff} * ext{k} * ext{k}")
            # force on end a: +T e, on end b: -T e (docs/physics.md section 2)
            for i, sign, ox, oy in ((ia, "+", aox, aoy), (ib, "-", box, boy)):
                if i < 0:
                    continue
                fx[i].append(f"{sign} tx{k}")
                if ty is not None:
                    fy[i].append(f"{sign} {ty}")
                if ox is not None:  # clockwise torque of (tx, ty) at arm (ox, oy)
                    tau[i].append(f"{sign} arm_torque({ox}, {oy}, tx{k}, {ty})")
            if lever and k == 0:
                for i, sign, wx, wy, name in ((ia, "-", awx, awy, "a"), (ib, "", bwx, bwy, "b")):
                    if i < 0:
                        continue
                    term = f"{ex} * {wx}"
                    if ey is not None:
                        term += f" + {ey} * {wy}"
                    lines.append(f"lb{name} = {sign}({term})")
        for j, (i, off) in enumerate(p.forces):
            fxj, fyj = F(f"Fx_{j}"), F(f"Fy_{j}")
            if off:
                r = F(f"fr_{j}")
                lines += [
                    f"sn, cs = sincos({F(f'fal_{j}')} + {y[i]} * {F(f'is_{i}')})",
                    f"fox{j} = {r} * sn",
                    f"foy{j} = {r} * cs",
                ]
                tau[i].append(f"+ arm_torque(fox{j}, foy{j}, {fxj}, {fyj})")
                if energy:
                    energy_terms.append(
                        f"- work({fxj}, {fyj}, {y[i]} + fox{j} - {F(f'frs_{j}')},"
                        f" foy{j} - {F(f'frc_{j}')})"
                    )
            elif energy:
                energy_terms.append(f"- {fxj} * {y[i]}")
        has_force = {i for i, _ in p.forces}
        for i in range(n):
            ext_x = [F(f"efx_{i}")] if i in has_force else []
            lines.append(f"fx{i} = {_sum(ext_x + fx[i])}")
            if not p.normal_const[i]:
                ext_y = [F(f"efy_{i}")] if i in has_force else []
                lines.append(f"fy{i} = {_sum(ext_y + fy[i])}")
            if tau[i]:  # Q/s = F_x + tau/s (M7)
                lines.append(f"gx{i} = reduced_force(fx{i}, {_sum(tau[i])}, {F(f'is_{i}')})")
            else:
                lines.append(f"gx{i} = fx{i}")
            if acc:
                lines.append(f"acc{i} = {F(f'xa_{i}')} * gx{i}")
        if energy:
            lines.append(f"U = {_sum(energy_terms)}")
        return lines

    def contact(self) -> list[str]:
        """f{i} (friction needed, (M8): m a - F_x) and N{i} (normal force, (M9))."""
        F, lines = self.fld, []
        for i in range(self.n):
            if self.p.rolls[i]:
                lines.append(f"f{i} = rolling_friction({F(f'm_{i}')}, acc{i}, fx{i})")
            else:
                lines.append(f"f{i} = 0.0")
            if self.p.normal_const[i]:
                lines.append(f"N{i} = {F(f'nn_{i}')}")
            else:
                lines.append(f"N{i} = normal_force({F(f'wt_{i}')}, fy{i})")
        return lines

    def condition(self) -> str:
        """The per-step event condition (slip or lift-off), a bool expression."""
        F, terms = self.fld, []
        simple = {i for members in self.p.simple.values() for i in members}
        for k in sorted(self.p.simple):
            terms.append(f"(abs(tx{k}) > {F(f'tth_{k}')})")
        for i in range(self.n):
            if self.p.slip_check[i] and i not in simple:
                if self.p.normal_const[i]:
                    terms.append(f"(abs(f{i}) > {F(f'mn_{i}')})")
                else:
                    terms.append(f"(abs(f{i}) > {F(f'mu_{i}')} * N{i})")
            if not self.p.normal_const[i]:
                terms.append(f"(N{i} < 0.0)")
        return " | ".join(terms) if terms else "False"

    def energy(self, ve: list[str]) -> str:
        F = self.fld
        return "E = U + " + " + ".join(f"{F(f'ku_{i}')} * {ve[i]} * {ve[i]}" for i in range(self.n))

    def ldot(self, ve: list[str]) -> str:
        ia, ib = self.p.springs[0].ends
        terms = []
        if ia >= 0:
            terms.append(f"lba * {ve[ia]}")
        if ib >= 0:
            terms.append(f"lbb * {ve[ib]}")
        return " + ".join(terms)

    def metrics(self, lane: str, ve: list[str], y: list[str], crossing: bool) -> list[str]:
        """Update the sampled metrics of ``lane`` (needs forces, contact, E, t, dT)."""
        F = self.fld

        def S(name: str) -> str:
            return self.row(name, lane)

        lines = [
            f"dE = abs(E - {S('E0')})",
            f"o = {S('DE')}",
            _MAX.format(dst=S("DE"), x="dE", old="o"),
        ]
        cm = " + ".join(f"{F(f'cq_{i}')} * {y[i]}" for i in range(self.n))
        xh = " + ".join(f"{F(f'xq_{i}')} * {y[i]}" for i in range(self.n))
        lines += [f"cm = {cm}", f"xh = {xh} - {F('vhat')} * t"]
        for name, x, fmt in (
            ("CMLO", "cm", _MIN),
            ("CMHI", "cm", _MAX),
            ("XHLO", "xh", _MIN),
            ("XHHI", "xh", _MAX),
        ):
            lines += [f"o = {S(name)}", fmt.format(dst=S(name), x=x, old="o")]
        for k in sorted(self.p.simple):
            lines += [
                f"at = abs(tx{k})",
                f"o = {S(f'TM{k}')}",
                _MAX.format(dst=S(f"TM{k}"), x="at", old="o"),
            ]
        for i in range(self.n):
            if self.p.rolls[i] and i not in self.tension_of:
                lines.append(f"af = abs(f{i})")
                if self.p.normal_const[i]:
                    lines += [f"o = {S(f'FB{i}')}", _MAX.format(dst=S(f"FB{i}"), x="af", old="o")]
                else:  # the best |f|/N as a pair: compare by cross-multiplication
                    lines += [
                        f"fb = {S(f'FB{i}')}",
                        f"nb = {S(f'NB{i}')}",
                        # (0, 0) stored, |f|/N undefined (f and N both 0 at the start):
                        # any later pair is better
                        f"better = (N{i} >= 0.0) & ((af * nb > fb * N{i})"
                        " | ((fb == 0.0) & (nb == 0.0)))",
                        f"{S(f'FB{i}')} = af if better else fb + 0.0",
                        f"{S(f'NB{i}')} = N{i} if better else nb + 0.0",
                    ]
            if not self.p.normal_const[i]:
                lines += [
                    f"o = {S(f'NMIN{i}')}",
                    _MIN.format(dst=S(f"NMIN{i}"), x=f"N{i}", old="o"),
                ]
        if crossing and self.period:
            lines += [
                f"ld = {self.ldot(ve)}",
                f"pv = {S('CP')}",
                "up = (pv < 0.0) & (ld >= 0.0)",
                "tc = t - dT * ld / (ld - pv)",
                f"cn = {S('CN')}",
                f"cf = {S('CF')}",
                f"cl = {S('CL')}",
                f"{S('CF')} = tc if (up & (cn == 0.0)) else cf + 0.0",
                f"{S('CL')} = tc if up else cl + 0.0",
                f"{S('CN')} = cn + 1.0 if up else cn + 0.0",
                f"{S('CP')} = ld",
            ]
        return lines

    # -- functions -----------------------------------------------------------------------
    def _drift(self) -> list[str]:
        lines = []
        for i in range(self.n):
            lines += [
                f"u{i} = {self.row(f'u{i}', 'j')}",
                f"y{i} = {self.row(f'y{i}', 'j')} + dk * u{i}",
            ]
        return lines

    def _kicks(self, coefficient: str) -> tuple[list[str], list[str]]:
        """``u{i} + coefficient * acc{i}`` for every body, with ``coefficient * xa`` hoisted out
        of the lane loop where ``xa`` is a block constant: (lines before the loop, kicked
        velocity expressions)."""
        before, kicked = [], []
        for i in range(self.n):
            if f"xa_{i}" in self.constant:
                before.append(f"kx{i} = {coefficient} * {self.fld(f'xa_{i}')}")
                kicked.append(f"u{i} + kx{i} * gx{i}")
            else:
                kicked.append(f"u{i} + {coefficient} * acc{i}")
        return before, kicked

    def stage(self) -> list[str]:
        """One inner stage of the composition for every lane: drift, forces, merged kick."""
        n = self.n
        body = self._drift()
        body += self.forces([f"y{i}" for i in range(n)], energy=False, lever=False)
        before, kicked = self._kicks("ck")
        for i in range(n):
            body += [f"{self.row(f'u{i}', 'j')} = {kicked[i]}", f"{self.row(f'y{i}', 'j')} = y{i}"]
        loop = [*before, *self.lane_loop(body)]
        return self.function("stage", "S, Pl, C, dk, ck", loop)

    def last(self, sample: bool) -> list[str]:
        """The last stage of a step: drift, forces, the closing half-kick merged with the next
        step's opening one, the event checks; with ``sample`` the half-kicks are separate (the
        velocities at the step's end) and the metrics are sampled. Returns the OR of the lanes'
        event conditions."""
        n = self.n
        y = [f"y{i}" for i in range(n)]
        ve = [f"ve{i}" for i in range(n)]
        body = self._drift()
        body += self.forces(y, energy=sample, lever=sample and self.period)
        # the stored velocity is the same in both (a run's motion does not depend on when the
        # metrics are sampled, hence on the other runs); ve is the velocity at the step's end
        before, kicked = self._kicks("ck")
        for i in range(n):
            if sample:
                body.append(f"ve{i} = u{i} + kl * acc{i}")
            body += [f"{self.row(f'u{i}', 'j')} = {kicked[i]}", f"{self.row(f'y{i}', 'j')} = y{i}"]
        body += self.contact()
        cond = self.condition()
        if sample:
            body.append(self.energy(ve))
            body += self.metrics("j", ve, y, crossing=True)
        # (a lane that overflows to NaN meets no condition: it is found at the end)
        if self.stop:
            body.append(f"ev |= {cond}")
        else:
            body.append(f"ev |= ({cond}) & ({self.row('ACT', 'j')} > 0.0)")
        loop = ["ev = 0", *before, *self.lane_loop(body)]
        if sample:
            return self.function("last_sample", "S, Pl, C, dk, ck, kl, t, dT", loop, "ev")
        return self.function("last_check", "S, Pl, C, dk, ck", loop, "ev")

    def prologue(self) -> list[str]:
        """Initial state, first metric sample and checks at t = 0, opening half-kick."""
        n, F = self.n, self.fld
        y = [f"y{i}" for i in range(n)]
        ve = [f"ve{i}" for i in range(n)]

        def S(name: str) -> str:
            return self.row(name, "j")

        body = [f"y{i} = 0.0" for i in range(n)] + [f"ve{i} = {F(f'u0_{i}')}" for i in range(n)]
        body += self.forces(y, energy=True, lever=self.period)
        body += self.contact()
        body.append(self.energy(ve))
        for i in range(n):
            body += [f"{S(f'y{i}')} = 0.0", f"{S(f'u{i}')} = ve{i} + k0 * acc{i}"]
        body += [
            f"{S('E0')} = E",
            f"{S('DE')} = 0.0",
            f"{S('CMLO')} = 0.0",
            f"{S('CMHI')} = 0.0",
            f"{S('XHLO')} = 0.0",
            f"{S('XHHI')} = 0.0",
            f"{S('CF')} = np.nan",
            f"{S('CL')} = np.nan",
            f"{S('CN')} = 0.0",
            f"{S('ACT')} = 1.0",
            f"{S('LIVE')} = 1.0",
        ]
        body.append(f"{S('CP')} = {self.ldot(ve)}" if self.period else f"{S('CP')} = 0.0")
        for i in range(n):
            body += [
                f"{S(f'FB{i}')} = abs(f{i})",
                f"{S(f'NB{i}')} = N{i}",
                f"{S(f'NMIN{i}')} = N{i}",
            ]
        body += [f"{S(f'TM{k}')} = abs(tx{k})" for k in sorted(self.p.simple)]
        # at t = 0 every body is checked, lift-off included
        terms = [f"(N{i} < 0.0)" for i in range(n)]
        terms += [f"(abs(f{i}) > {F(f'mu_{i}')} * N{i})" for i in range(n) if self.p.rolls[i]]
        terms.append("(not (abs(E) <= 1e308))")
        body.append(f"ev |= {' | '.join(terms)}")
        loop = ["ev = 0", "for j in range(B):", *_indent(self.loads("j") + body)]
        return self.function("prologue", "S, Pl, C, k0", loop, "ev")

    def _outputs(self, suffix: str = "") -> str:
        n = self.n
        names = [f"acc{i}" for i in range(n)] + [f"f{i}" for i in range(n)]
        names += [f"N{i}" for i in range(n)] + [f"tx{k}" for k in sorted(self.p.simple)] + ["U"]
        return ", ".join(_rename_names(names, suffix))

    def lane_state(self) -> list[str]:
        """One lane's centre accelerations, needed frictions, normal forces and potential
        energy at displacements y (scalar code for the cold paths)."""
        n = self.n
        y = [f"y{i}" for i in range(n)]
        body = self.forces(y, energy=True, lever=False) + self.contact()
        body = self.loads("jj") + body
        return self.function("lane_state", "Pl, C, jj, " + ", ".join(y), body, self._outputs())

    def events(self) -> list[str]:
        """The scalar pass over the lanes of a block after a step in which some lane met the
        event condition: classify, locate the instant, record, stop. Returns the number of
        lanes stopped."""
        n, F = self.n, self.fld

        def S(name: str) -> str:
            return self.row(name, "jj")

        y = [f"y{i}" for i in range(n)]
        ve = [f"ve{i}" for i in range(n)]
        ys = ", ".join(y)
        body = [f"if not ({S('LIVE')} > 0.0):", "    continue"]
        inner = [f"y{i} = {S(f'y{i}')}" for i in range(n)]
        inner.append(f"{self._outputs()} = lane_state(Pl, C, jj, {ys})")
        inner += [f"ve{i} = {S(f'u{i}')} - k0 * acc{i}" for i in range(n)]
        inner.append(self.energy(ve))
        # a lane's first event (the conditions are recomputed here, so lanes that did not
        # trigger the pass are left alone): of the bodies whose condition holds (lift-off
        # N < 0, slip 0 <= mu_s N < |f|), the one whose margin crossed zero first in this step, the
        # margins interpolated linearly between this step and the previous one, reconstructed
        # by a step backwards (the compositions are time-reversible)
        candidates = []  # (condition, margin now, margin before, status, body)
        for i in range(n):
            candidates.append((f"N{i} < 0.0", f"-N{i}", f"-Nb{i}", STATUS_LIFTOFF, i))
            if self.p.rolls[i]:
                mu = F(f"mu_{i}")
                candidates.append(
                    (
                        f"(N{i} >= 0.0 and abs(f{i}) > {mu} * N{i})",
                        f"abs(f{i}) - {mu} * N{i}",
                        f"abs(fb{i}) - {mu} * Nb{i}",
                        STATUS_SLIP,
                        i,
                    )
                )
        inner += [
            "kind = 0",
            "who = -1",
            "tev = np.inf",
            f"if not (abs(E - {S('E0')}) <= 1e308):",
            f"    kind = {STATUS_NONFINITE}",
            "    tev = t",
            f"elif {S('ACT')} > 0.0 and ({' or '.join(c[0] for c in candidates)}):",
        ]
        yb = ", ".join(f"yb{i}" for i in range(n))
        back = [f"yb{i} = y{i}" for i in range(n)]
        back += [f"vb{i} = ve{i} - k0 * acc{i}" for i in range(n)]
        back += [f"accb{i} = acc{i}" for i in range(n)]
        back += [f"fb{i} = f{i}" for i in range(n)] + [f"Nb{i} = N{i}" for i in range(n)]
        loop = [f"yb{i} = yb{i} - dr[kk] * vb{i}" for i in range(n)]
        loop.append(f"{self._outputs('b')} = lane_state(Pl, C, jj, {yb})")
        loop += [f"vb{i} = vb{i} - kc[kk] * accb{i}" for i in range(n)]
        back += ["for kk in range(nst):", *_indent(loop)]
        pick = ["if t > 0.0:", *_indent(back)]
        for cond, now, before, code, i in candidates:
            pick += [
                f"if {cond}:",
                "    tc = 0.0",
                "    if t > 0.0:",
                f"        now = {now}",
                f"        before = {before}",
                "        tc = t",
                "        if before <= 0.0 and now > before:",
                "            tc = t - h * (now / (now - before))",
                "    if tc < tev:",
                "        tev = tc",
                f"        kind = {code}",
                f"        who = {i}",
            ]
        inner += _indent(pick)
        inner += ["if kind == 0:", "    continue"]
        inner += [
            f"if kind == {STATUS_NONFINITE}:",
            "    OUTI[lo + jj, 0] = kind",
            "else:",
            "    OUTI[lo + jj, 0] = kind",
            "    OUTI[lo + jj, 1] = who",
            f"    OUT[lo + jj, {_C_TEV}] = tev",
        ]
        stop = [
            f"if kind != {STATUS_NONFINITE}:",
            *_indent(self.metrics("jj", ve, y, crossing=False)),
        ]
        stop += self.write_out("jj")
        for i in range(n):
            stop += [f"{S(f'y{i}')} = np.nan", f"{S(f'u{i}')} = np.nan"]
        stop += [f"{S('ACT')} = 0.0", f"{S('LIVE')} = 0.0", "stopped += 1"]
        if self.stop:
            inner += stop
        else:
            inner += [
                f"if kind == {STATUS_NONFINITE}:",
                *_indent(stop),
                "else:",
                f"    {S('ACT')} = 0.0",
            ]
        body += self.loads("jj") + inner
        loop = [
            "nst = dr.shape[0]",
            "k0 = 0.5 * dr[0]",
            "stopped = 0",
            "for jj in range(B):",
            *_indent(body),
        ]
        return self.function("events", "lo, S, Pl, C, dr, kc, h, t, OUT, OUTI", loop, "stopped")

    def write_out(self, lane: str) -> list[str]:
        """Copy the metrics of ``lane`` and its final state (needs y{i}, ve{i}) to OUT."""

        def S(name: str) -> str:
            return self.row(name, lane)

        F = self.fld
        lines = [f"OUT[lo + {lane}, {col}] = {S(name)}" for name, col in _OUT_ROWS.items()]
        for i in range(self.n):
            base = _C_BODY + 5 * i
            if i in self.tension_of:
                k = self.tension_of[i]
                lines.append(
                    f"{S(f'FB{i}')} = abs({F(f'm_{i}')} * {F(f'xa_{i}')} - 1.0) * {S(f'TM{k}')}"
                )
            # the body's five columns: max |f|/N and its N, min N, final position and velocity
            body = (S(f"FB{i}"), S(f"NB{i}"), S(f"NMIN{i}"), f"{F(f'x0_{i}')} + y{i}", f"ve{i}")
            lines += [f"OUT[lo + {lane}, {base + c}] = {value}" for c, value in enumerate(body)]
        return lines

    def epilogue(self) -> list[str]:
        """Undo the last opening half-kick and copy every live lane's results to OUT."""
        n = self.n

        def S(name: str) -> str:
            return self.row(name, "jj")

        inner = [f"y{i} = {S(f'y{i}')}" for i in range(n)]
        inner.append(
            f"{self._outputs()} = lane_state(Pl, C, jj, {', '.join(f'y{i}' for i in range(n))})"
        )
        inner += [f"ve{i} = {S(f'u{i}')} - k0 * acc{i}" for i in range(n)]
        state = " + ".join(f"abs(y{i}) + abs(ve{i})" for i in range(n))
        inner += [f"if not ({state} <= 1e308):", f"    OUTI[lo + jj, 0] = {STATUS_NONFINITE}"]
        inner += self.write_out("jj")
        body = [f"if {S('LIVE')} > 0.0:", *_indent(self.loads("jj") + inner)]
        loop = ["for jj in range(B):", *_indent(body)]
        return self.function("epilogue", "lo, S, Pl, C, k0, OUT, OUTI", loop)

    def sample(self) -> list[str]:
        """Centre positions of every lane into row ``row`` of the trajectories."""
        F = self.fld
        body = [
            f"traj[lo + j, row, {i}] = {F(f'x0_{i}')} + {self.row(f'y{i}', 'j')}"
            for i in range(self.n)
        ]
        loop = ["for j in range(B):", *_indent(self.loads("j") + body)]
        return self.function("sample", "lo, row, S, Pl, C, traj", loop)

    def buffers(self) -> list[str]:
        """``buffers()``: a block's state ``S`` and its lanes' varying fields ``Pl``, one
        allocation, each starting on a cache line (:data:`LINE` bytes; every row too, the row
        stride being a whole number of lines). NumPy and Numba align an array to 32 bytes
        only; the lane loops' 64-byte vectors then straddle two lines at every access on
        half of the allocations, which made a batch 1.5x slower at random (bench/README.md)."""
        lanes = LINE // 8
        n_state, n_fields = self.n_rows * _RS, max(len(self.varying), 1) * _RS
        body = [
            f"W = np.empty({n_state + n_fields + lanes})",
            f"a = ({lanes} - (W.ctypes.data % {LINE}) // 8) % {lanes}",
            f"return W[a:a + {n_state}], W[a + {n_state}:a + {n_state + n_fields}]",
        ]
        return ["", "", "@njit(cache=True)", "def buffers():", *_indent(body)]

    # -- the module ----------------------------------------------------------------------
    def module(self) -> str:
        block = [
            "lo = blk * B",
            "S, Pl = buffers()",
            f"for r in range({len(self.varying)}):",
            "    for j in range(B):",
            f"        Pl[r * {_RS} + j] = P[r, lo + j]",
            "nst = dr.shape[0]",
            "k0 = 0.5 * dr[0]",
            "kl = 0.5 * dr[nst - 1]",
            "n_live = B",
            "if prologue(S, Pl, C, k0) != 0:",
            "    n_live -= events(lo, S, Pl, C, dr, kc, dt, 0.0, OUT, OUTI)",
            "if stride > 0:",
            "    sample(lo, 0, S, Pl, C, traj)",
            "last = 0",
            "for step in range(n_steps):",
            "    for kk in range(nst - 1):",
            "        stage(S, Pl, C, dr[kk], kc[kk])",
            "    t = (step + 1) * dt",
            "    if (step + 1) % every == 0 or step + 1 == n_steps:",
            "        ev = last_sample(S, Pl, C, dr[nst - 1], kl + k0, kl, t,",
            "                         (step + 1 - last) * dt)",
            "        last = step + 1",
            "    else:",
            "        ev = last_check(S, Pl, C, dr[nst - 1], kl + k0)",
            "    if ev != 0:",
            "        n_live -= events(lo, S, Pl, C, dr, kc, dt, t, OUT, OUTI)",
            "    if stride > 0 and (step + 1) % stride == 0:",
            "        sample(lo, (step + 1) // stride, S, Pl, C, traj)",
            "    if n_live == 0:",
            "        break",
            "epilogue(lo, S, Pl, C, k0, OUT, OUTI)",
        ]
        parts = [
            '"""Generated by rollspring.simulate.batch.codegen (source hash in the file name). '
            'Do not edit."""',
            "import math",
            "import numpy as np",
            "from numba import njit, prange",
            _LAW_IMPORT,
            f"# the force law: rollspring.simulate.kernels.law, sha256 {_law_digest()}",
            f"B = {BLOCK}",
            SINCOS,
            *self.stage(),
            *self.last(sample=False),
            *self.last(sample=True),
            *self.prologue(),
            *self.lane_state(),
            *self.events(),
            *self.epilogue(),
            *self.sample(),
            *self.buffers(),
            "",
            "",
            '@njit(nogil=True, cache=True, error_model="numpy")',
            "def block(blk, P, C, dr, kc, dt, n_steps, every, stride, traj, OUT, OUTI):",
            *_indent(block),
            "",
            "",
            "# every block on Numba's threads (one launch at a time in a process: the caller",
            "# holds rollspring.simulate.batch.api's lock)",
            '@njit(parallel=True, nogil=True, cache=True, error_model="numpy")',
            "def run(n_blocks, P, C, dr, kc, dt, n_steps, every, stride, traj, OUT, OUTI):",
            "    for blk in prange(n_blocks):",
            "        block(blk, P, C, dr, kc, dt, n_steps, every, stride, traj, OUT, OUTI)",
            "",
            "",
            "# every block on the calling thread, the GIL released: several Python threads can",
            "# each run one (the same block code as run's, so the same numbers bit for bit)",
            '@njit(nogil=True, cache=True, error_model="numpy")',
            "def run_serial(n_blocks, P, C, dr, kc, dt, n_steps, every, stride, traj, OUT, OUTI):",
            "    for blk in range(n_blocks):",
            "        block(blk, P, C, dr, kc, dt, n_steps, every, stride, traj, OUT, OUTI)",
            "",
        ]
        return "\n".join(parts)


#: Generated modules kept by :func:`kernel_source` (at most this many, the oldest dropped).
_KEPT_MODULES = 64
_MODULES: dict[tuple[object, ...], str] = {}
_MODULES_LOCK = threading.Lock()  # a sweep's threads ask at once


def kernel_source(plan: Plan, varying: list[str], constant: list[str], stop: bool) -> str:
    """:meth:`Source.module` of ``plan``, generated once per key and kept: the key is what
    :class:`Source` reads of a plan (its bodies, springs, forces, checks and slip thresholds,
    never the runs' values), the varying and constant fields and the stop mode (a sweep's
    batch calls share one module)."""
    key = (
        plan.n,
        plan.rolls,
        plan.springs,
        plan.forces,
        plan.normal_const,
        plan.slip_check,
        tuple((k, tuple(members)) for k, members in sorted(plan.simple.items())),
        tuple(varying),
        tuple(constant),
        stop,
    )
    with _MODULES_LOCK:
        source = _MODULES.get(key)
        if source is None:
            source = Source(plan, varying, constant, stop).module()
            while len(_MODULES) >= _KEPT_MODULES:
                del _MODULES[next(iter(_MODULES))]
            _MODULES[key] = source
    return source


#: sin and cos in straight-line code LLVM can vectorise (``math.sin`` is a libm call, which
#: keeps a loop scalar without Intel's SVML): reduction by the nearest multiple of pi/2 in three
#: parts (Cody-Waite, exact for |x| < 2^20 pi/2) and fdlibm's minimax polynomials on
#: [-pi/4, pi/4] (errors of about one unit in the last place).
SINCOS = """

@njit(error_model="numpy", fastmath={"contract"})
def sincos(x):
    k = np.floor(x * 0.6366197723675814 + 0.5)
    r = ((x - k * 1.57079632673412561417e+00) - k * 6.07710050630396597660e-11) \\
        - k * 2.02226624871116645580e-21
    z = r * r
    sn = r + r * z * (-1.66666666666666324348e-01 + z * (8.33333333332248946124e-03
         + z * (-1.98412698298579493134e-04 + z * (2.75573137070700676789e-06
         + z * (-2.50507602534068634195e-08 + z * 1.58969099521155010221e-10)))))
    cs = 1.0 - 0.5 * z + z * z * (4.16666666666666019037e-02 + z * (-1.38888888888741095749e-03
         + z * (2.48015872894767294178e-05 + z * (-2.75573143513906633035e-07
         + z * (2.08757232129817482790e-09 + z * -1.13596475577881948265e-11)))))
    quadrant = k - 4.0 * np.floor(0.25 * k)
    odd = (quadrant == 1.0) | (quadrant == 3.0)
    s = cs if odd else sn
    c = sn if odd else cs
    s = -s if quadrant >= 2.0 else s
    c = -c if (quadrant == 1.0) | (quadrant == 2.0) else c
    return s, c"""


#: the law's terms the generated code calls (Numba inlines them: ``inline="always"``)
_LAW_TERMS = (
    "arm_torque",
    "distance",
    "elastic_tension",
    "level_pull",
    "normal_force",
    "pull",
    "reduced_force",
    "rolling_friction",
    "work",
)
_LAW_IMPORT = f"from rollspring.simulate.kernels.law import {', '.join(_LAW_TERMS)}"


@cache
def _law_digest() -> str:
    """The hash of the law's source: in the generated source, so its name (the cache key of
    :mod:`.cache`) changes with the law (Numba's cache of a module sees only its own file)."""
    return hashlib.sha256(Path(law.__file__).read_bytes()).hexdigest()[:20]


def _sum(terms: list[str]) -> str:
    """Terms (each optionally led by '+ ' or '- ') as one expression; '0.0' for none."""
    if not terms:
        return "0.0"
    first = terms[0]
    if first.startswith("+ "):
        first = first[2:]
    elif first.startswith("- "):
        first = f"-({first[2:]})"
    return " ".join([first, *terms[1:]])


def _indent(lines: list[str], by: str = "    ") -> list[str]:
    return [by + line for line in lines]


def _rename_names(names: list[str], suffix: str) -> list[str]:
    """``acc0`` -> ``accb0`` for suffix ``b`` (``U`` -> ``Ub``)."""
    return [re.sub(r"^([A-Za-z]+)(\d*)$", rf"\1{suffix}\2", name) for name in names]

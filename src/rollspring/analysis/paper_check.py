r"""Every quantitative claim of the paper, checked by the derivation engine.

Paper: G. Nyitray, *On the edge of complexity: the simplest not simple coupled mechanical system*
(arXiv 2508.01379); equation labels are the paper's LaTeX labels. Each :class:`Claim` holds

* ``location``: section and equation of the paper;
* ``latex``: the claim as the paper's LaTeX source writes it (transcribed);
* ``paper``: the same claim as a SymPy expression (or a tuple of them): the value the paper gives
  for one **quantity** (``quantity``, LaTeX), written in the symbols the derivation engine uses
  (:math:`m_1, m_2, R, R_1, R_2, k, \varphi_i, \dot\varphi_i, \ddot\varphi_i, \dots`);
* ``system``: which system(s) it is checked on (keys of :data:`SYSTEMS`, comma-separated: the
  paper's Fig. 1, 2, 3 and Sec. 4 systems built as rollspring systems and turned symbolic by
  :func:`rollspring.analysis.derivation.symbolic_system` with ``symbols=True``);
* ``derive``: the recipe: computes, from the engine's SymPy objects (M, K, V, the Lagrangian,
  the friction and force expressions, the zero mode, the closed-form frequencies), the same
  quantity, and, where the paper's claim depends on a condition, the quantity under that
  condition.

The verdict is computed (:func:`check_claim`): ``simplify(paper - derived) == 0`` gives
``"verified"``; otherwise, if the recipe names a condition (equal radii, centres level, a start
from rest, an angle counted the other way, small angles, ...) and the two agree under it,
``"holds-only-if"``; otherwise ``"wrong"``, with the derived expression as the correction.
Nothing in a verdict is typed in: the words (``reason``) explain, the engine decides.

Sign conventions (docs/physics.md): :math:`\varphi_i` clockwise positive (rolling to the right), in
one common orientation for all bodies, measured from the equilibrium; friction :math:`f_i` is
the force of the floor on body i, positive along +x.
"""

from __future__ import annotations

import functools
import math
from collections.abc import Callable, Iterable, Sequence
from dataclasses import dataclass, field
from typing import Any

import sympy as sp

from rollspring.analysis.derivation import SymbolicSystem, symbolic_system
from rollspring.analysis.derivation.frequencies import normal_frequencies
from rollspring.model import System, system_from_dict

__all__ = [
    "HOLDS_ONLY_IF",
    "SYSTEMS",
    "VERDICTS",
    "VERIFIED",
    "WRONG",
    "Claim",
    "ClaimCheck",
    "Derived",
    "check_claim",
    "check_claims",
    "check_paper",
    "paper_claims",
    "paper_figure",
    "paper_system",
]

VERIFIED = "verified"
WRONG = "wrong"
HOLDS_ONLY_IF = "holds-only-if"
#: The three verdicts, in the order they are counted.
VERDICTS = (VERIFIED, HOLDS_ONLY_IF, WRONG)

# -- the symbols (the same names and assumptions as the derivation engine's) ---------------------
m, m1, m2 = sp.symbols("m m_1 m_2", positive=True)
R, R1, R2 = sp.symbols("R R_1 R_2", positive=True)
k, k1, k2 = sp.symbols("k k_1 k_2", positive=True)
gamma, y = sp.symbols("gamma y", positive=True)
F = sp.Symbol("F", real=True)
phi, phi1, phi2 = sp.symbols("phi phi_1 phi_2", real=True)
phid1, phid2 = sp.symbols("phidot_1 phidot_2", real=True)
phidd, phidd1, phidd2 = sp.symbols("phiddot phiddot_1 phiddot_2", real=True)
x1, x2 = sp.symbols("x_1 x_2", real=True)
xd1, xd2 = sp.symbols("xdot_1 xdot_2", real=True)
# the paper's own symbols (not the engine's)
A = sp.Symbol("A", positive=True)  # amplitude of the spring's deformation (Sec. 4.2)
Phid1, Phid2 = sp.symbols("Phidot_1 Phidot_2", positive=True)  # maximal angular velocities
q1, q2, q3, q4 = sp.symbols("q_1 q_2 q_3 q_4", real=True)  # canonical coordinates
p1, p2, p3, p4 = sp.symbols("p_1 p_2 p_3 p_4", real=True)  # canonical momenta
Fx1, Fx2 = sp.symbols("F_1x F_2x", real=True)  # horizontal spring force on body 1, 2
ell_total = sp.Symbol("l", positive=True)  # the spring's length (Sec. 4.3)
# constants of the motion (fixed by the start): the conserved combination and its integral
P0 = sp.Symbol("P_0", real=True)
D0 = sp.Symbol("D_0", real=True)
t = sp.Symbol("t", real=True)
a = sp.Symbol("a", real=True)  # amplitude along a mode shape

half = sp.Rational(1, 2)


# -- the systems -------------------------------------------------------------------------------


def _body(
    id_: str, shape: str, mass: float, radius: float, x: float, **extra: Any
) -> dict[str, Any]:
    return {"id": id_, "shape": shape, "mass": mass, "radius": radius, "x": x, **extra}


def _pair(
    shape1: str,
    shape2: str,
    *,
    r1: float = 0.1,
    r2: float = 0.1,
    track1: float = 0.0,
    at: list[dict[str, Any]] | None = None,
) -> dict[str, Any]:
    """Two bodies joined by one spring (k = 100 N/m); distinct masses 1.3 kg and 0.7 kg so that
    no equality of masses is assumed by accident."""
    spring: dict[str, Any] = {"ends": ["b1", "b2"], "stiffness": 100.0, "rest_length": 0.5}
    if at is not None:
        spring["at"] = at
        spring.pop("rest_length")  # at rest length in the initial placement
        return {
            "bodies": [
                _body("b1", shape1, 1.3, r1, 0.0, track_height=track1),
                _body("b2", shape2, 0.7, r2, 0.5),
            ],
            "springs": [spring],
        }
    return {
        "bodies": [
            _body("b1", shape1, 1.3, r1, 0.0, track_height=track1),
            _body("b2", shape2, 0.7, r2, 0.49),
        ],
        "springs": [spring],
    }


def _pulled(shape: str, **extra: Any) -> dict[str, Any]:
    """One body pulled horizontally by a constant force at height 0.137 m (paper App. A, Fig. 5);
    0.137/R is no simple ratio, so the engine names the height y."""
    return {
        "bodies": [_body("b", shape, 1.3, 0.1, 0.0, **extra)],
        "forces": [{"body": "b", "at": {"height": 0.137}, "fx": 2.0}],
    }


#: The systems the claims are checked on, as system files (dictionaries).
SYSTEMS: dict[str, dict[str, Any]] = {
    # Fig. 1: two point masses, compressed and released
    "fig1": {
        "bodies": [_body("b1", "slider", 1.3, 0.05, 0.0), _body("b2", "slider", 0.7, 0.05, 0.49)],
        "springs": [{"ends": ["b1", "b2"], "stiffness": 100.0, "rest_length": 0.5}],
    },
    # Fig. 2: hoop (m1) and cylinder (m2) of equal radius R, centres joined
    "fig2": _pair("hoop", "cylinder"),
    # Fig. 2 with different radii, the hoop's track raised so that the centres stay level
    "fig2-radii": _pair("hoop", "cylinder", r1=0.08, track1=0.02),
    "two-hoops": _pair("hoop", "hoop"),
    "two-cylinders": _pair("cylinder", "cylinder"),
    # Fig. 3 as the paper sizes it: R1 = R2/2, centres level (the hoop's track raised by R1),
    # the spring from the hoop's top (2R1) to the cylinder at 1.5 R2: horizontal
    "fig3": _pair(
        "hoop", "cylinder", r1=0.05, r2=0.1, track1=0.05, at=[{"height": 0.1}, {"height": 0.15}]
    ),
    # Fig. 4 (a): a wall spring on the hoop, the hoop-cylinder spring (for the sum rule)
    "fig4a": {
        "anchors": [{"id": "wall", "x": -0.5, "y": 0.1}],
        "bodies": [_body("b1", "hoop", 1.3, 0.1, 0.0), _body("b2", "cylinder", 0.7, 0.1, 0.49)],
        "springs": [
            {"ends": ["wall", "b1"], "stiffness": 80.0, "rest_length": 0.5},
            {"ends": ["b1", "b2"], "stiffness": 100.0, "rest_length": 0.5},
        ],
    },
    # App. A: a body with I = gamma m R^2 pulled at height y; and a hoop, a cylinder
    "pulled": _pulled("custom", inertia_factor=0.3),
    "pulled-hoop": _pulled("hoop"),
    "pulled-cylinder": _pulled("cylinder"),
}


def paper_system(key: str) -> System:
    """One of :data:`SYSTEMS` as a validated rollspring system."""
    return system_from_dict(SYSTEMS[key])


# -- claims, derivations, verdicts ---------------------------------------------------------------


@dataclass(frozen=True)
class Derived:
    """What a recipe derives: ``value`` (the quantity, SymPy or a tuple); ``how`` (one line:
    from which engine objects). Where the paper's claim needs a condition: ``condition`` (words),
    ``value_if`` (the derived quantity under it) and ``paper_if`` (a map applied to the paper's
    expression under it, e.g. an angle counted the other way; identity when None).
    ``paper_subs`` substitutes the paper's auxiliary symbols (a force, a moment of inertia) by
    the engine's expressions before comparing; ``why`` explains a difference."""

    value: Any
    how: str
    why: str = ""
    condition: str | None = None
    value_if: Any = None
    paper_if: Callable[[Any], Any] | None = None
    paper_subs: dict[str, Any] = field(default_factory=dict)
    correction: str | None = None  # LaTeX, when the plain derived value is not the best display


@dataclass(frozen=True)
class Claim:
    """One quantitative claim of the paper (see the module docstring)."""

    key: str
    location: str
    statement: str
    latex: str
    quantity: str
    paper: Any
    system: str
    derive: Callable[[_Bench], Derived] = field(repr=False, compare=False)


@dataclass(frozen=True)
class ClaimCheck:
    """A claim with its computed verdict."""

    claim: Claim
    verdict: str
    correction: str | None
    reason: str
    paper: Any
    derived: Any

    def to_dict(self) -> dict[str, Any]:
        """The JSON form: ``location``, ``claim`` (LaTeX), ``verdict``, ``correction`` (LaTeX or
        None), ``reason``."""
        return {
            "location": self.claim.location,
            "claim": self.claim.latex,
            "verdict": self.verdict,
            "correction": self.correction,
            "reason": self.reason,
        }


class _Bench:
    """The symbolic systems and the derived objects they share, built once each."""

    def __init__(self) -> None:
        self._cache: dict[tuple[Any, ...], Any] = {}

    def _cached(self, key: tuple[Any, ...], build: Callable[[], Any]) -> Any:
        if key not in self._cache:
            self._cache[key] = build()
        return self._cache[key]

    def sym(self, key: str) -> SymbolicSystem:
        result: SymbolicSystem = self._cached(
            ("sym", key), lambda: symbolic_system(paper_system(key), symbols=True)
        )
        return result

    def omega2(self, key: str) -> list[sp.Expr]:
        """Closed forms of the squared frequencies of the oscillating modes (the engine's
        det(K - Omega^2 M) = 0)."""

        def build() -> list[sp.Expr]:
            found = normal_frequencies(self.sym(key), budget=None)
            if not found.complete:
                raise RuntimeError(f"{key}: no closed-form frequencies")
            return list(found.omega2)

        result: list[Any] = self._cached(("omega2", key), build)
        return result

    def mode(self, key: str) -> sp.Matrix:
        """The one oscillating mode shape (in phi), the null vector of K - Omega^2 M."""

        def build() -> sp.Matrix:
            sym = self.sym(key)
            (w2,) = self.omega2(key)
            (v,) = (sym.stiffness_matrix - w2 * sym.mass_matrix).nullspace(simplify=True)
            return v.applyfunc(_tidy)

        return self._cached(("mode", key), build)

    def zero_mode(self, key: str) -> sp.Matrix:
        def build() -> sp.Matrix:
            v0 = self.sym(key).zero_mode()
            if v0 is None:
                raise RuntimeError(f"{key}: no single zero mode")
            return v0

        return self._cached(("zero", key), build)

    def lever(self, key: str, spring: int = 0) -> list[sp.Expr]:
        """b_i = dl/dq_i at the reference: the spring's deformation is b . q (linear)."""

        def build() -> list[sp.Expr]:
            sym = self.sym(key)
            (length,) = sym.linearized([sym.springs[spring].length])
            return [_tidy(sp.diff(length, q)) for q in sym.q]

        result: list[Any] = self._cached(("lever", key, spring), build)
        return result

    def friction_linear(self, key: str) -> list[sp.Expr]:
        """The required friction (M8) to first order in q, positive along +x."""

        def build() -> list[sp.Expr]:
            sym = self.sym(key)
            return [sp.expand(f) for f in sym.linearized(sym.friction_configuration)]

        result: list[Any] = self._cached(("friction", key), build)
        return result

    def weights(self, key: str) -> list[sp.Expr]:
        """Stationary-point weights w_i = J_i v0_i / s_i, normalised (docs/physics.md (M14))."""

        def build() -> list[sp.Expr]:
            sym = self.sym(key)
            v0 = self.zero_mode(key)
            raw = [b.J * v0[i] / b.s for i, b in enumerate(sym.bodies)]
            total = sp.Add(*raw)
            return [_tidy(w / total) for w in raw]

        result: list[Any] = self._cached(("weights", key), build)
        return result

    def conserved(self, key: str) -> list[sp.Expr]:
        """Coefficients c = v0^T M of the conserved combination c . qdot (M14)."""
        sym = self.sym(key)
        v0 = self.zero_mode(key)
        return [_tidy(v0[i] * sym.mass_matrix[i, i]) for i in range(sym.n)]

    def accelerations(self, key: str, *, linear: bool = False) -> list[sp.Expr]:
        """qdd_i = Q_i / J_i from the engine's equations of motion (M7)."""
        sym = self.sym(key)
        return [
            _tidy(eq.rhs / b.J)
            for eq, b in zip(sym.equations_of_motion(linear=linear), sym.bodies, strict=True)
        ]

    def along_mode(self, exprs: Sequence[sp.Expr], key: str) -> list[sp.Expr]:
        """Linear forms of q evaluated on the oscillating mode shape."""
        sym = self.sym(key)
        v = self.mode(key)
        sub = {q: v[i] for i, q in enumerate(sym.q)}
        return [_tidy(sp.sympify(e).xreplace(sub)) for e in exprs]

    def amplitudes(self, key: str) -> list[sp.Expr]:
        """Centre amplitudes A_i in the oscillating mode whose spring deformation is A."""
        sym = self.sym(key)
        v = self.mode(key)
        deformation = sp.Abs(_tidy(sum(b * v[i] for i, b in enumerate(self.lever(key)))))
        return [_tidy(A * sp.Abs(body.s * v[i]) / deformation) for i, body in enumerate(sym.bodies)]

    def canonical(self, key: str) -> list[sp.Expr]:
        r""":math:`q_i = \sqrt{J_i/m_i}\,\varphi_i`: the point transformation that turns
        :math:`T = \sum J_i\dot\varphi_i^2/2` into :math:`\sum m_i\dot q_i^2/2`."""
        sym = self.sym(key)
        return [sp.sqrt(b.J / b.m) * b.q for b in sym.bodies]

    def hamiltonian(
        self, key: str, qs: Sequence[sp.Symbol], ps: Sequence[sp.Symbol]
    ) -> tuple[sp.Expr, sp.Expr]:
        """(H, V) in the canonical coordinates: H = sum p^2/(2m) + V, V the engine's quadratic
        potential with phi_i = sqrt(m_i/J_i) q_i."""
        sym = self.sym(key)
        to_q = {b.q: sp.sqrt(b.m / b.J) * qq for b, qq in zip(sym.bodies, qs, strict=True)}
        V = sp.expand(sym.quadratic_potential.xreplace(to_q))
        T = sp.Add(*[pp**2 / (2 * b.m) for b, pp in zip(sym.bodies, ps, strict=True)])
        return T + V, V


def _same(left: Any, right: Any) -> bool:
    """True when the two (expressions, or sequences of them of equal length) are identical:
    ``simplify(left - right) == 0``. A difference that is not zero at a random rational point
    (exact arithmetic) is not identically zero, which spares the simplification."""
    if isinstance(left, Sequence | sp.MatrixBase) or isinstance(right, Sequence | sp.MatrixBase):
        left_items, right_items = list(left), list(right)
        return len(left_items) == len(right_items) and all(
            _same(a_, b_) for a_, b_ in zip(left_items, right_items, strict=True)
        )
    difference = sp.sympify(left) - sp.sympify(right)
    if difference == 0:
        return True
    if _nonzero_somewhere(difference):
        return False
    if sp.cancel(sp.expand(difference)) == 0:
        return True
    result: bool = sp.simplify(difference) == 0 or sp.simplify(sp.expand(difference)) == 0
    return result


def _tidy(expr: Any) -> Any:
    """A cheap normal form: cancel for rational expressions, simplify where radicals, absolute
    values or signs appear."""
    expr = sp.sympify(expr)
    if expr.has(sp.Abs, sp.sign) or any(
        p_.exp.is_Rational and not p_.exp.is_Integer for p_ in expr.atoms(sp.Pow)
    ):
        return sp.simplify(expr)
    return sp.factor(sp.cancel(expr)) if expr.free_symbols else expr


def _nonzero_somewhere(expr: sp.Expr) -> bool:
    """True when ``expr`` is clearly non-zero at a rational point (positive symbols get values
    in (1/2, 3), real ones in (-2, 2) but not 0)."""
    point = {}
    for n, symbol in enumerate(sorted(expr.free_symbols, key=lambda s_: s_.name)):
        value = sp.Rational(53 + 37 * n % 101, 47 + 13 * n % 29)  # deterministic, generic
        if not symbol.is_positive:
            value = value - 2 if n % 2 else 2 - value
            if value == 0:
                value = sp.Rational(1, 3)
        point[symbol] = value
    number = sp.N(expr.xreplace(point), 30)
    if not number.is_number or number.is_finite is not True:
        return False  # undecided: leave it to simplify
    return bool(abs(number) > sp.Float("1e-20"))


def _latex(value: Any) -> str:
    if isinstance(value, Sequence) and not isinstance(value, str):
        return r"\left(" + r",\ ".join(_latex(v) for v in value) + r"\right)"
    result: str = sp.latex(value)
    return result


def _subs(value: Any, mapping: dict[Any, Any]) -> Any:
    if not mapping:
        return value
    if isinstance(value, Sequence) and not isinstance(value, str):
        return tuple(_subs(v, mapping) for v in value)
    return sp.sympify(value).subs(mapping)


def check_claim(claim: Claim, bench: _Bench | None = None) -> ClaimCheck:
    """Derive the claim's quantity with the engine and compare (see the module docstring)."""
    bench = bench or _Bench()
    derived = claim.derive(bench)
    paper = _subs(claim.paper, derived.paper_subs)
    quantity = claim.quantity
    if _same(paper, derived.value):
        return ClaimCheck(claim, VERIFIED, None, derived.how, paper, derived.value)
    correction = derived.correction or f"{quantity} = {_latex(derived.value)}"
    if derived.condition is not None:
        paper_if = derived.paper_if(paper) if derived.paper_if is not None else paper
        value_if = derived.value_if if derived.value_if is not None else derived.value
        if _same(paper_if, value_if):
            reason = f"holds only if {derived.condition}"
            if derived.why:
                reason += f"; {derived.why}"
            return ClaimCheck(claim, HOLDS_ONLY_IF, correction, reason, paper, derived.value)
    reason = derived.why or derived.how
    return ClaimCheck(claim, WRONG, correction, reason, paper, derived.value)


def check_claims(claims: Iterable[Claim]) -> tuple[ClaimCheck, ...]:
    """Each of ``claims`` with its verdict; the claims share the symbolic systems they are
    derived on (each built once)."""
    bench = _Bench()
    return tuple(check_claim(claim, bench) for claim in claims)


@functools.cache
def check_paper() -> tuple[ClaimCheck, ...]:
    """Every claim of :func:`paper_claims` with its verdict (computed once per process)."""
    return check_claims(paper_claims())


def paper_figure(system: System) -> tuple[str, set[str]] | None:
    """Which of the paper's systems ``system`` is, as ``(label, keys of`` :data:`SYSTEMS` ``)``,
    or None.

    By structure, not by numbers (the paper's claims are symbolic): two sliders joined at their
    centres (Fig. 1); a hoop and a solid cylinder, or two hoops, or two cylinders, joined at
    their centres, centres level (Fig. 2); a hoop and a cylinder joined at their percussion
    heights (1 + γ)R (Fig. 3); a wall spring on a hoop that is joined to a cylinder at the centres
    (Fig. 4 (a)). No constant forces in any of them.
    """
    if system.forces:
        return None
    bodies = {b.id: b for b in system.bodies}
    shapes = sorted(b.shape for b in system.bodies)
    springs = system.springs

    def centres(spring: Any) -> bool:
        return all(at.is_centre_form for at in spring.attachments)

    level = len({round(b.track_height + b.radius, 12) for b in system.bodies}) == 1
    if len(bodies) == 2 and len(springs) == 1 and not system.anchors:
        (spring,) = springs
        if shapes == ["slider", "slider"] and centres(spring):
            return "Fig. 1 (two point masses)", {"fig1"}
        if centres(spring) and level:
            if shapes == ["cylinder", "hoop"]:
                return "Fig. 2 (hoop and cylinder joined at their centres)", {"fig2", "fig2-radii"}
            if shapes == ["hoop", "hoop"]:
                return "Sec. 2 variant with two hoops", {"two-hoops"}
            if shapes == ["cylinder", "cylinder"]:
                return "Sec. 2 variant with two cylinders", {"two-cylinders"}
        if shapes == ["cylinder", "hoop"] and all(
            at.height is not None
            and math.isclose(at.height, bodies[end].percussion_height, rel_tol=1e-9)
            for end, at in zip(spring.ends, spring.attachments, strict=True)
        ):
            return "Fig. 3 (springs at the percussion points, no friction)", {"fig3"}
    if (
        len(bodies) == 2
        and len(system.anchors) == 1
        and len(springs) == 2
        and shapes == ["cylinder", "hoop"]
        and all(centres(s) for s in springs)
    ):
        anchor = system.anchors[0].id
        wall = [s for s in springs if anchor in s.ends]
        if len(wall) == 1 and any(bodies[e].shape == "hoop" for e in wall[0].ends if e in bodies):
            return "Fig. 4 (a) (a wall spring on the hoop)", {"fig4a"}
    return None


# -- the recipes -------------------------------------------------------------------------------


def _flip_first(expr: Any) -> Any:
    """The paper's expression read in the paper's Sec. 4.3 orientation, where body 1's angle is
    counted the other way (epsilon_1 = X-hat - x_1): phi_1 -> -phi_1 (and its rates)."""
    flip = {phi1: -phi1, phid1: -phid1, phidd1: -phidd1, q1: -q1, p1: -p1, q3: -q3}
    if isinstance(expr, Sequence) and not isinstance(expr, str):
        return tuple(sp.sympify(e).xreplace(flip) for e in expr)
    return sp.sympify(expr).xreplace(flip)


def _flip_first_rate(expr: Any) -> Any:
    """As :func:`_flip_first` for a pair whose first entry is itself odd in phi_1 (an
    acceleration, a momentum rate of body 1)."""
    first, second = _flip_first(expr)
    return (-first, second)


_ORIENTATION = (
    "body 1's angle is counted anticlockwise (epsilon_1 = X-hat - x_1, as Fig. 2 "
    "draws it), while the paper defines epsilon_1 = x_1 - X-hat; in one common "
    "orientation the spring's deformation is epsilon_2 - epsilon_1"
)


_CANONICAL_ORIENTATION = (
    "the first canonical coordinate is counted the other way (body 1 "
    "anticlockwise, from the Lagrangian (l)); in one common orientation "
    "the coefficients are (-Omega_1/sqrt(k/m_1), +Omega_2/sqrt(k/m_2))"
)


def _fig1_eom(b: _Bench) -> Derived:
    sym = b.sym("fig1")
    return Derived(
        tuple(eq.rhs for eq in sym.equations_of_motion()),
        "m_i xddot_i = Q_i = -dV/dx_i from the engine's potential (M7)",
    )


def _fig1_potential(b: _Bench) -> Derived:
    return Derived(
        b.sym("fig1").potential,
        "the engine's exact spring potential (M5), displacements from the equilibrium",
    )


def _cm_velocity(key: str, how: str) -> Callable[[_Bench], Derived]:
    def derive(b: _Bench) -> Derived:
        sym = b.sym(key)
        w = b.weights(key)
        masses = [body.m for body in sym.bodies]
        total = sp.Add(*masses)
        is_cm = _same(w, [mm / total for mm in masses])
        value = (
            P0 / total
            if is_cm
            else sp.Add(
                *[mm * body.s * body.qd for mm, body in zip(masses, sym.bodies, strict=True)]
            )
            / total
        )
        return Derived(
            value,
            how,
            condition="the bodies start with zero total momentum "
            "(released from rest), as the paper's release does",
            value_if=_subs(value, {P0: 0}),
            why="the conserved combination (zero mode of K, M14) is the total "
            "momentum sum m_i xdot_i = P_0, fixed by the start",
        )

    return derive


def _steiner(b: _Bench) -> Derived:
    sym = b.sym("fig2")
    return Derived(
        tuple(sym.mass_matrix[i, i] for i in range(2)),
        "diagonal of the engine's mass matrix M = diag(J_i), J = I + mR^2 (M4)",
    )


def _fig2_eom(b: _Bench) -> Derived:
    return Derived(
        tuple(b.accelerations("fig2")),
        "phiddot_i = Q_i/J_i from the engine's exact equations of motion (M7)",
    )


def _momentum(b: _Bench) -> Derived:
    sym = b.sym("fig2")
    c = b.conserved("fig2")
    J = [body.J for body in sym.bodies]
    scaled = [_tidy(ci * J[0] / c[0]) for ci in c]
    value = P0 if _same(scaled, J) else J[0] * phid1 + J[1] * phid2
    return Derived(
        value,
        "the zero mode v0 of K gives the conserved v0^T M phidot (M14)",
        condition="the bodies are released from rest (then P_0 = 0)",
        value_if=_subs(value, {P0: 0}),
        why="I'_1 phidot_1 + I'_2 phidot_2 = P_0 is conserved (zero mode v0 = (1, 1) "
        "of K, M14), its value fixed by the initial velocities",
    )


def _phase_opposition(b: _Bench) -> Derived:
    v = b.mode("fig2")
    return Derived(
        sp.sign(_tidy(v[1] / v[0])),
        "sign of phi_2/phi_1 in the oscillating mode (null vector of K - Omega^2 M)",
    )


def _cm_moves(b: _Bench) -> Derived:
    sym = b.sym("fig2")
    v = b.mode("fig2")
    ratio = _tidy(sym.bodies[1].s * v[1] / (sym.bodies[0].s * v[0]))
    masses = [body.m for body in sym.bodies]
    cm = _tidy((masses[0] + masses[1] * ratio) / (masses[0] + masses[1]))
    return Derived(
        ratio, f"xdot_2/xdot_1 in the oscillating mode; then Xdot = {sp.sstr(cm)} xdot_1, not 0"
    )


def _stationary_general(b: _Bench) -> Derived:
    w = tuple(b.weights("fig2-radii"))
    return Derived(
        w,
        "X-hat weights w_i = J_i v0_i / R_i from the zero mode of K (M14)",
        condition="the radii are equal (R_1 = R_2, as in Fig. 2)",
        value_if=_subs(w, {R2: R1}),
        paper_if=lambda e: _subs(e, {R2: R1}),
        why="for different radii the weights are (1 + gamma_i) m_i = J_i/R_i^2, not "
        "I'_i = J_i (docs/physics.md (M11))",
    )


def _stationary(key: str) -> Callable[[_Bench], Derived]:
    def derive(b: _Bench) -> Derived:
        return Derived(
            tuple(b.weights(key)),
            "X-hat weights w_i = J_i v0_i / R_i from the zero mode of K (M14)",
        )

    return derive


def _friction_ratio(b: _Bench) -> Derived:
    f1, f2 = b.along_mode(b.friction_linear("fig2"), "fig2")
    ratio = _tidy(f1 / f2)
    return Derived(
        ratio,
        "ratio of the engine's friction (M8), linearised, in the mode",
        condition="f_1, f_2 are magnitudes: in the mode the two frictions point opposite ways",
        value_if=sp.Abs(ratio),
        paper_if=sp.Abs,
        why="signed along +x, f_1/f_2 = -3/2 and f_1 + f_2 != 0: the resultant "
        "external force that moves the centre of mass",
    )


def _same_inertia(b: _Bench) -> Derived:
    sym = b.sym("fig2")
    total = sp.factor(sp.Add(*b.friction_linear("fig2")))
    # equal moments of inertia, I_1 = I_2: m_1 R^2 = m_2 R^2 / 2
    b1, b2 = sym.bodies
    (solution,) = sp.solve(sp.Eq(b1.I, b2.I), m2)
    with_equal_inertia = sp.factor(total.subs(m2, solution))
    hoops = _tidy(sp.Add(*b.friction_linear("two-hoops")))
    cylinders = _tidy(sp.Add(*b.friction_linear("two-cylinders")))
    note = (
        "it vanishes for two hoops and for two cylinders (equal inertia factors gamma = I/(mR^2))"
        if hoops == 0 and cylinders == 0
        else ""
    )
    return Derived(
        with_equal_inertia,
        "sum of the engine's linearised frictions (M8) with I_1 = I_2 imposed",
        why="with I_1 = I_2 (m_2 = 2 m_1) a hoop and a cylinder still need "
        f"f_1 + f_2 = {sp.sstr(with_equal_inertia)} != 0; {note}".rstrip("; "),
        correction=r"f_1+f_2="
        + sp.latex(total)
        + r"\neq 0\ \text{unless}\ \frac{I_1}{m_1R_1^2}=\frac{I_2}{m_2R_2^2}",
    )


def _fric(b: _Bench) -> Derived:
    sym = b.sym("pulled")
    (f,) = sym.friction_configuration
    body = sym.bodies[0]
    at_rest = _tidy(-f.subs(body.q, 0))
    return Derived(
        at_rest,
        "minus the engine's friction (M8) of the pulled body at phi = 0 (the "
        "paper counts f opposite to F)",
        paper_subs={sp.Symbol("I"): body.I},
    )


def _fric_coupled(b: _Bench) -> Derived:
    sym = b.sym("fig2")
    forces = [F_[0] for F_ in sym.body_forces]
    exact = tuple(_tidy(f) for f in sym.friction_configuration)
    return Derived(
        exact,
        "the engine's exact friction (M8) of the coupled bodies at every configuration",
        paper_subs={Fx1: forces[0], Fx2: forces[1]},
    )


def _zero_friction_height(b: _Bench, key: str) -> sp.Expr:
    """y with f(y) = 0 for the pulled body ``key``: the engine's friction at phi = 0, solved."""
    sym = b.sym(key)
    (f,) = sym.friction_configuration
    (height,) = sp.solve(sp.Eq(f.subs(sym.bodies[0].q, 0), 0), y)
    return height


def _heights(b: _Bench) -> Derived:
    return Derived(
        (_zero_friction_height(b, "pulled-hoop"), _zero_friction_height(b, "pulled-cylinder")),
        "solving the engine's friction f(y) = 0 (M8) for a pulled hoop and cylinder",
    )


def _geometry(b: _Bench) -> Derived:
    hoop = _zero_friction_height(b, "pulled-hoop")
    cylinder = _zero_friction_height(b, "pulled-cylinder")
    h1 = sp.Symbol("h_1", real=True)  # height of the hoop's track above the cylinder's
    hoop_end = h1 + hoop.subs(R, R1)
    cylinder_end = cylinder.subs(R, R2)
    (one_floor,) = sp.solve(sp.Eq(hoop_end.subs(h1, 0), cylinder_end), R1)
    level = sp.solve([sp.Eq(hoop_end, cylinder_end), sp.Eq(h1 + R1, R2)], [R1, h1], dict=True)
    (level_solution,) = level
    return Derived(
        one_floor,
        "the spring joins the zero-friction heights (solved from the "
        "engine's f(y) = 0): horizontal iff h_1 + 2R_1 = 3R_2/2",
        condition="the centres are level: the hoop's track raised by R_2 - R_1 = R_1",
        value_if=level_solution[R1],
        why="on one floor a horizontal spring needs R_1 = 3R_2/4; R_1 = R_2/2 there "
        "tilts the spring (ends at R_2 and 3R_2/2), scales Omega^2 by cos^2(tilt) and "
        "makes N oscillate",
        correction=r"R_1=\frac{3}{4}R_2\ \text{(one floor)}",
    )


def _fig3_eom(b: _Bench) -> Derived:
    return Derived(
        tuple(b.accelerations("fig3", linear=True)),
        "phiddot_i = (Q(0) - K phi)_i / J_i: the engine's equations of motion "
        "linearised (small angles, as the paper says)",
    )


def _fig3_cm_acceleration(b: _Bench) -> Derived:
    sym = b.sym("fig3")
    acc = b.accelerations("fig3", linear=True)
    value = _tidy(sum(body.m * body.s * acc[i] for i, body in enumerate(sym.bodies)))
    return Derived(value, "sum m_i R_i phiddot_i with the engine's linearised equations of motion")


def _fig3_friction(b: _Bench) -> Derived:
    sym = b.sym("fig3")
    v = b.mode("fig3")
    v = v / v[1]  # amplitude a of phi_2
    along = {q: a * v[i] for i, q in enumerate(sym.q)}
    orders = []
    for f in sym.friction_configuration:
        d = f.xreplace(along)
        terms = []
        for n in (1, 2, 3):
            d = sp.diff(d, a)
            terms.append(sp.factor(sp.cancel(d.subs(a, 0))) / sp.factorial(n))
        orders.append(terms)
    linear = tuple(terms[0] for terms in orders)
    leading = tuple(terms[0] * a + terms[1] * a**2 + terms[2] * a**3 for terms in orders)
    correction = r",\quad ".join(
        f"f_{i + 1}={sp.latex(sp.factor(value))}+O(a^4)" for i, value in enumerate(leading)
    )
    return Derived(
        leading,
        "the engine's exact friction (M8) expanded along the mode phi = a v to third order in a",
        condition="to first order in the amplitude (small angles)",
        value_if=linear,
        why="the attachment points leave the percussion heights as the bodies turn: "
        "friction is O(a^3), so the CM is at rest only to first order",
        correction=correction + r"\quad(\varphi_2=a)",
    )


def _fig3_angular_momentum(b: _Bench) -> Derived:
    sym = b.sym("fig3")
    acc = b.accelerations("fig3", linear=True)
    # centre heights above the lower floor: the paper's Fig. 3 has the centres level, at R_2
    centre = [R2, R2]
    model = paper_system("fig3").bodies
    if abs(model[0].track_height + model[0].radius - model[1].radius) > 1e-12:
        raise RuntimeError("fig3: the centres are expected level")
    rate = sum((body.I + body.m * centre[i] * body.s) * acc[i] for i, body in enumerate(sym.bodies))
    value = _tidy(rate.subs(R1, R2 / 2))
    return Derived(
        value,
        "dL_O/dt for L_O = sum (I_i phidot_i + m_i y_ci xdot_i) about a fixed "
        "point on the floor, with the engine's linearised equations of motion",
        paper_subs={R1: R2 / 2},
        why="the total angular momentum about a fixed point is conserved (no external "
        "torque: friction vanishes to first order, N_i = m_i g); sum I'_i phidot_i is "
        "not the angular momentum when the tracks differ, and on one floor a "
        "horizontal spring has 2R_1 = 3R_2/2: equal torques",
        correction=r"\dot L_O=0",
    )


def _qq2(b: _Bench) -> Derived:
    (w2,) = b.omega2("fig2")
    v0 = b.zero_mode("fig2")
    c = b.conserved("fig2")
    norm = sp.Add(*[ci * v0[i] for i, ci in enumerate(c)])
    drift = (P0 * t + D0) / norm  # the zero-mode coordinate: c . phi = P_0 t + D_0
    value = _tidy(w2 * drift * v0[0])
    return Derived(
        value,
        "phiddot_1 + Omega^2 phi_1 for the general motion: zero mode "
        "(P_0 t + D_0) v0 plus the oscillating mode",
        condition="the zero mode is not excited: released from rest, angles measured "
        "from the equilibrium about X-hat",
        value_if=_subs(value, {P0: 0, D0: 0}),
        why="in general phi_1 also holds the uniform motion of X-hat and a constant offset",
    )


def _phi_relation(b: _Bench, *, flip: bool) -> Derived:
    c = b.conserved("fig2")
    value = _tidy((P0 * t + D0 - c[0] * phi1) / c[1])
    condition = (
        "the bodies are released from rest and the angles are measured from the "
        "equilibrium about X-hat (P_0 = D_0 = 0)"
    )
    if flip:
        condition = f"{_ORIENTATION}; and {condition}"
    return Derived(
        value,
        "integrating the conserved c . phidot = P_0 (zero mode of K) twice",
        condition=condition,
        value_if=_subs(value, {P0: 0, D0: 0}),
        paper_if=_flip_first if flip else None,
        why="in general c . phi = P_0 t + D_0 with c = v0^T M = (I'_1, I'_2)",
    )


def _omega2(key: str) -> Callable[[_Bench], Derived]:
    def derive(b: _Bench) -> Derived:
        (w2,) = b.omega2(key)
        return Derived(w2, "the non-zero root of det(K - Omega^2 M) = 0 (engine's M, K)")

    return derive


def _energy(b: _Bench) -> Derived:
    sym = b.sym("fig2")
    (w2,) = b.omega2("fig2")
    v = b.mode("fig2")
    deformation = sp.Abs(_tidy(sum(bb * v[i] for i, bb in enumerate(b.lever("fig2")))))
    scale = A / deformation
    kinetic = _tidy(w2 * scale**2 * (v.T * sym.mass_matrix * v)[0, 0] / 2)
    return Derived(
        kinetic,
        "largest kinetic energy sum J_i (Omega a v_i)^2 / 2 in the mode whose "
        "spring deformation is A",
    )


def _nu(b: _Bench) -> Derived:
    v = b.mode("fig2")
    ratio = _tidy(v[1] / v[0])
    return Derived(
        ratio * Phid1,
        "Phidot_2 in terms of Phidot_1 in the oscillating mode",
        condition="Phidot_1, Phidot_2 are magnitudes (maximal angular speeds): "
        "signed in one orientation the combination is a sum, as in (rel1)",
        value_if=sp.Abs(ratio) * Phid1,
        paper_if=lambda e: e,
        why="the signed angular velocities have opposite signs",
    )


def _speeds(b: _Bench) -> Derived:
    (w2,) = b.omega2("fig2")
    return Derived(
        tuple(_tidy(sp.sqrt(w2) * amp) for amp in b.amplitudes("fig2")),
        "v_i = Omega A_i: the mode's centre amplitudes times the derived Omega",
    )


def _omega(b: _Bench) -> Derived:
    (w2,) = b.omega2("fig2")
    return Derived(sp.sqrt(w2), "square root of the non-zero root of det(K - Omega^2 M) = 0")


def _amplitudes(b: _Bench) -> Derived:
    return Derived(
        tuple(b.amplitudes("fig2")),
        "centre amplitudes R|v_i| of the mode scaled to "
        "a spring deformation A (deformation b . v, b the engine's lever arms)",
    )


def _amplitude_sum(b: _Bench) -> Derived:
    return Derived(_tidy(sum(b.amplitudes("fig2"))), "sum of the derived centre amplitudes")


def _amplitudes_equal_masses(b: _Bench) -> Derived:
    return Derived(
        tuple(_tidy(amp.subs(m2, m1)) for amp in b.amplitudes("fig2")),
        "the derived A_i with m_1 = m_2",
    )


def _lagrangian(b: _Bench) -> Derived:
    return Derived(
        sp.expand(b.sym("fig2").lagrangian),
        "the engine's Lagrangian T - V (M5)",
        condition=_ORIENTATION,
        paper_if=_flip_first,
        why="",
    )


def _split(b: _Bench) -> list[sp.Expr]:
    """The paper's k_i, from (Q1), (Q2): -k_i (R phi_i) R = I'_i phiddot_i in the mode, so
    k_i = J_i Omega^2 / R^2."""
    sym = b.sym("fig2")
    (w2,) = b.omega2("fig2")
    return [sp.factor(_tidy(body.J * w2 / body.s**2)) for body in sym.bodies]


def _k_parts(b: _Bench) -> Derived:
    return Derived(
        tuple(_split(b)),
        "k_i = J_i Omega^2 / R^2 from (Q1), (Q2) with the derived "
        "Omega^2 (the mode obeys phiddot = -Omega^2 phi)",
    )


def _k_series(b: _Bench) -> Derived:
    first, second = _split(b)
    return Derived(_tidy(1 / first + 1 / second), "1/k_1 + 1/k_2 with the derived k_i")


def _k_equal_masses(b: _Bench) -> Derived:
    return Derived(
        tuple(_tidy(v.subs(m2, m1)) for v in _split(b)), "the derived k_i with m_1 = m_2"
    )


def _k_equal(b: _Bench) -> Derived:
    first, second = _split(b)
    (from_k,) = sp.solve(sp.Eq(first, second), m1)
    amp1, amp2 = b.amplitudes("fig2")
    (from_a,) = sp.solve(sp.Eq(amp1, amp2), m1)
    return Derived(
        (_tidy(from_k / m2), _tidy(from_a / m2)),
        "m_1/m_2 solving k_1 = k_2 and A_1 = A_2 with the derived k_i, A_i",
    )


def _xhat_three_sevenths(b: _Bench) -> Derived:
    w = b.weights("fig2")
    # x_1 = 0, x_2 = l: X-hat = w_2 l, the length of the left part, whose stiffness is k l/X-hat
    xhat = _tidy(w[1].subs(m2, m1) * ell_total)
    part = _tidy(k * ell_total / xhat)
    first = _tidy(_split(b)[0].subs(m2, m1))
    agrees = "equal to" if _same(part, first) else "unlike"
    return Derived(
        (xhat, part),
        f"X-hat = w_2 l with the derived weights (m_1 = m_2); the "
        f"left part's stiffness k l/X-hat is {agrees} the derived k_1",
    )


def _eom_flipped(b: _Bench) -> Derived:
    sym = b.sym("fig2")
    Q = tuple(eq.rhs for eq in sym.equations_of_motion())
    return Derived(
        Q,
        "J_i phiddot_i = Q_i from the engine's Lagrangian (M7)",
        condition=_ORIENTATION,
        paper_if=_flip_first_rate,
    )


def _ga(b: _Bench) -> Derived:
    acc = b.accelerations("fig2")
    ratio = _tidy(acc[1] / acc[0])
    return Derived(
        ratio * phidd1,
        "phiddot_2 in terms of phiddot_1 from the engine's equations of motion",
        condition=_ORIENTATION,
        paper_if=_flip_first,
    )


def _sum_rule_fig2(b: _Bench) -> Derived:
    sym = b.sym("fig2")
    (w2,) = b.omega2("fig2")
    clamped = sp.Add(*[sym.stiffness_matrix[i, i] / body.J for i, body in enumerate(sym.bodies)])
    return Derived(
        _tidy(w2 - clamped),
        "Omega^2 minus the sum of the clamped frequencies "
        "K_ii/J_ii (each body alone, the other held), all from the engine's M, K",
    )


def _eigenvalues_2x2(M: sp.Matrix, K: sp.Matrix) -> list[sp.Expr]:
    """The non-zero eigenvalues of M^-1 K (2 x 2, M diagonal)."""
    trace = _tidy(K[0, 0] / M[0, 0] + K[1, 1] / M[1, 1])
    det = _tidy((K[0, 0] * K[1, 1] - K[0, 1] * K[1, 0]) / (M[0, 0] * M[1, 1]))
    if det == 0:
        return [trace] if trace != 0 else []
    root = sp.sqrt(sp.factor(trace**2 - 4 * det))
    return [_tidy((trace - root) / 2), _tidy((trace + root) / 2)]


def _sum_rule_general(b: _Bench) -> Derived:
    sym = b.sym("fig4a")
    roots = b.omega2("fig4a")
    M, K = sym.mass_matrix, sym.stiffness_matrix
    wall = sym.springs[0].k
    without_wall = _eigenvalues_2x2(M, K.subs(wall, 0))
    clamped = sp.Add(*[K[i, i] / body.J for i, body in enumerate(sym.bodies)])
    trace_ok = _same(sp.Add(*roots), clamped)
    correction = r"\omega_{1,2}^2=" + r",\ ".join(sp.latex(r) for r in roots)
    if trace_ok:
        correction += r";\quad \omega_1^2+\omega_2^2=\Omega_1^2+\Omega_2^2"
    return Derived(
        tuple(roots),
        "the roots of det(K - omega^2 M) = 0 for the wall-hoop-cylinder "
        "chain (Fig. 4 (a)), against the clamped sum K_11/J_1 + K_22/J_2",
        condition="two bodies joined by one spring, no wall or chain (K of rank 1)",
        value_if=tuple(_tidy(r) for r in without_wall),
        paper_if=lambda e: _subs(e, {k1: 0}),
        why="with a wall neither mode has omega^2 = Omega_1^2 + Omega_2^2"
        + ("; only the trace identity sum omega_n^2 = sum Omega_i^2 holds" if trace_ok else ""),
        correction=correction,
    )


def _clamped(key: str, *, roots: bool) -> Callable[[_Bench], Derived]:
    def derive(b: _Bench) -> Derived:
        sym = b.sym(key)
        values = [sym.stiffness_matrix[i, i] / body.J for i, body in enumerate(sym.bodies)]
        values = [sp.sqrt(v) if roots else v for v in values]
        return Derived(
            tuple(_tidy(v) for v in values),
            "clamped frequencies sqrt(K_ii/J_i): each body alone, the other held (engine's M, K)",
        )

    return derive


def _alpha_beta(b: _Bench) -> Derived:
    sym = b.sym("fig2")
    return Derived(
        (
            sym.mass_matrix[0, 0],
            sym.stiffness_matrix[0, 0],
            sym.mass_matrix[1, 1],
            sym.stiffness_matrix[1, 1],
        ),
        "alpha_i = J_i and beta_i = K_ii of the engine's M and K",
    )


def _sum_rule_fig3(b: _Bench) -> Derived:
    sym = b.sym("fig3")
    (w2,) = b.omega2("fig3")
    clamped = sp.Add(*[sym.stiffness_matrix[i, i] / body.J for i, body in enumerate(sym.bodies)])
    return Derived(
        (w2, _tidy(w2 - clamped)),
        "the non-zero root of det(K - Omega^2 M) = 0 and its difference from the "
        "clamped sum K_11/J_1 + K_22/J_2 (engine's M, K)",
    )


def _lagrangian45(b: _Bench) -> Derived:
    return _lagrangian(b)


def _canonical(b: _Bench) -> Derived:
    return Derived(
        tuple(b.canonical("fig2")),
        "q_i = sqrt(J_i/m_i) phi_i makes the engine's T = sum J_i phidot_i^2/2 equal "
        "to sum m_i qdot_i^2/2 (p_i = m_i qdot_i)",
    )


def _hamiltonian(b: _Bench) -> Derived:
    H, _ = b.hamiltonian("fig2", (q1, q2), (p1, p2))
    return Derived(
        H,
        "H = sum p_i^2/(2m_i) + V with the engine's V in q_i = sqrt(J_i/m_i) phi_i",
        condition=_CANONICAL_ORIENTATION,
        paper_if=_flip_first,
        why="in one common orientation the coefficients are (-1/sqrt(2), +sqrt(2/3))",
    )


def _hamilton_equations(b: _Bench) -> Derived:
    H, _ = b.hamiltonian("fig2", (q1, q2), (p1, p2))
    return Derived(
        (sp.expand(sp.diff(H, q1)), sp.expand(sp.diff(H, q2))),
        "-pdot_i = dH/dq_i with the derived H",
        condition=_CANONICAL_ORIENTATION,
        paper_if=_flip_first_rate,
    )


def _q_ratio(b: _Bench) -> Derived:
    v = b.mode("fig2")
    canon = b.canonical("fig2")
    sym = b.sym("fig2")
    sub = {qq: v[i] for i, qq in enumerate(sym.q)}
    ratio = _tidy(canon[1].xreplace(sub) / canon[0].xreplace(sub))
    return Derived(
        ratio * q1,
        "q_2/q_1 in the oscillating mode (q_i = sqrt(J_i/m_i) phi_i)",
        condition=_CANONICAL_ORIENTATION
        + ", and the motion is the pure mode (released from rest about X-hat)",
        paper_if=_flip_first,
    )


def _hamilton_final(b: _Bench) -> Derived:
    (w2,) = b.omega2("fig2")
    return Derived(
        sp.expand(m1 * w2) * q1,
        "-pdot_1 = m_1 Omega^2 q_1 in the mode (qddot_1 = -Omega^2 q_1) with the derived Omega^2",
    )


def _potential_q(key: str, qs: tuple[Any, ...], ps: tuple[Any, ...]) -> Callable[[_Bench], Derived]:
    def derive(b: _Bench) -> Derived:
        _, V = b.hamiltonian(key, qs, ps)
        return Derived(
            V,
            "the engine's V in q_i = sqrt(J_i/m_i) phi_i",
            condition=_CANONICAL_ORIENTATION,
            paper_if=_flip_first,
            why="the coefficients' magnitudes are Omega_i/sqrt(k/m_i); in one common "
            "orientation the first is negative",
        )

    return derive


def _coefficients(b: _Bench) -> Derived:
    _, V = b.hamiltonian("fig2", (q1, q2), (p1, p2))
    return Derived(
        tuple(_tidy(sp.sqrt(sp.diff(V, qq, 2) / k)) for qq in (q1, q2)),
        "|c_i| = sqrt(d2V/dq_i^2 / k) of the engine's V in canonical coordinates",
    )


def _app_a_friction(index: int) -> Callable[[_Bench], Derived]:
    def derive(b: _Bench) -> Derived:
        sym = b.sym("fig2")
        v = b.mode("fig2")
        f = b.along_mode(b.friction_linear("fig2"), "fig2")[index]
        body = sym.bodies[index]
        coefficient = _tidy(f / (body.s * v[index]))
        return Derived(
            coefficient * body.s * body.q,
            "the engine's linearised friction (M8) in the mode, per R phi_i",
            why=""
            if index == 0
            else "the cylinder's I_2 = m_2R^2/2 gives "
            "f_2 = m_2 R phiddot_2 / 2 ... = (k_2/3) R phi_2, not k_2/2",
            correction=None
            if index == 0
            else r"f_2=\frac{k_2}{3}R\phi_2=" + sp.latex(coefficient * body.s * body.q),
        )

    return derive


def _app_a_eqs(b: _Bench) -> Derived:
    sym = b.sym("pulled")
    (eq,) = sym.equations_of_motion()
    body = sym.bodies[0]
    return Derived(
        _tidy((eq.rhs / body.J).subs(body.q, 0)),
        "phiddot = Q/J at phi = 0 from the engine's equation of motion (M7)",
        paper_subs={sp.Symbol("I"): body.I},
    )


def _app_a_origin(b: _Bench) -> Derived:
    sym = b.sym("pulled")
    (f,) = sym.friction_configuration
    (eq,) = sym.equations_of_motion()
    body = sym.bodies[0]
    friction = _tidy(-f.subs(body.q, 0).subs(y, 0))
    acceleration = _tidy((body.s * eq.rhs / body.J).subs(body.q, 0).subs(y, 0))
    return Derived(
        (friction, acceleration),
        "minus the engine's friction and the centre's "
        "acceleration R Q/J of the body pulled at y = 0",
    )


def _fig5_cylinder(b: _Bench) -> Derived:
    sym = b.sym("pulled-cylinder")
    (f,) = sym.friction_configuration
    body = sym.bodies[0]
    return Derived(
        _tidy(-f.subs(body.q, 0).subs(y, 2 * R)),
        "minus the engine's friction of a cylinder pulled at y = 2R",
    )


def _fig5_labels(b: _Bench) -> Derived:
    lines = []
    for key in ("pulled-hoop", "pulled-cylinder"):
        sym = b.sym(key)
        (f,) = sym.friction_configuration
        lines.append(_tidy(-f.subs(sym.bodies[0].q, 0)))
    return Derived(
        tuple(lines),
        "the engine's f(y) of a hoop (body 1 in the paper) and a cylinder (body 2)",
        why="the labels are swapped: everywhere else body 1 is the hoop; f_1(y) "
        "(zero at 2R) is the hoop's line, f_2(y) (zero at 3R/2) the cylinder's",
    )


# -- the catalogue -----------------------------------------------------------------------------


def _hoop_cylinder_hamiltonian(
    qa: sp.Symbol, qb: sp.Symbol, pa: sp.Symbol, pb: sp.Symbol, ca: sp.Expr, cb: sp.Expr
) -> sp.Expr:
    return pa**2 / (2 * m1) + pb**2 / (2 * m2) + k / 2 * (ca * qa + cb * qb) ** 2


_J1, _J2 = 2 * m1 * R**2, sp.Rational(3, 2) * m2 * R**2  # the paper's I'_1, I'_2 (Fig. 2)
_Omega1, _Omega2 = sp.sqrt(k / (2 * m1)), sp.sqrt(2 * k / (3 * m2))
_Omega3, _Omega4 = sp.sqrt(2 * k / m1), sp.sqrt(3 * k / (2 * m2))
_k1_paper = k * (3 * m2 + 4 * m1) / (3 * m2)
_k2_paper = k * (3 * m2 + 4 * m1) / (4 * m1)
_F3 = k * (sp.Rational(3, 2) * R2 * phi2 - 2 * R1 * phi1)  # the spring force of Fig. 3


def paper_claims() -> list[Claim]:
    """Every quantitative claim of the paper, in the paper's order."""
    c = Claim
    return [
        # ---- Sec. 2: two point masses (Fig. 1)
        c(
            "fig1-equations",
            "Sec. 2, eqs. (f1), (f2)",
            "equations of motion of two point masses joined by a spring",
            r"k\left(x_2-x_1\right)=m_1\ddot{x_1},\quad -k\left(x_2-x_1\right)=m_2\ddot{x_2}",
            r"\left(m_1\ddot x_1,\ m_2\ddot x_2\right)",
            (k * (x2 - x1), -k * (x2 - x1)),
            "fig1",
            _fig1_eom,
        ),
        c(
            "fig1-potential",
            "Sec. 2",
            "potential energy of the spring",
            r"U=\frac{k}{2}\left(x_2-x_1\right)^2",
            "U",
            k / 2 * (x2 - x1) ** 2,
            "fig1",
            _fig1_potential,
        ),
        c(
            "fig1-cm-at-rest",
            "Sec. 2",
            "the centre of mass of two point masses stays at rest",
            r"\dot{X}=0",
            r"\dot X",
            sp.Integer(0),
            "fig1",
            _cm_velocity(
                "fig1", "the zero mode of K gives sum m_i xdot_i = P_0 (M14); X-hat is the CM"
            ),
        ),
        # ---- Sec. 2 (3 in the paper's numbering): hoop and cylinder (Fig. 2)
        c(
            "steiner",
            "Sec. 2 (Steiner's theorem)",
            "moments of inertia about the contact lines",
            r"I'_1=m_1R^2+m_1d^2=2m_1R^2,\quad I'_2=\frac{1}{2}m_2R^2+m_2d^2=\frac{3}{2}m_2R^2",
            r"\left(I'_1,\ I'_2\right)",
            (_J1, _J2),
            "fig2",
            _steiner,
        ),
        c(
            "fig2-equations",
            "Sec. 2, eqs. (w2), (w22)",
            "equations of rotation about the contact lines",
            r"k\left(R\varphi_2-R\varphi_1\right)R=2m_1R^2\ddot{\varphi_1},\quad "
            r"-k\left(R\varphi_2-R\varphi_1\right)R=\frac{3}{2}m_2R^2\ddot{\varphi_2}",
            r"\left(\ddot\varphi_1,\ \ddot\varphi_2\right)",
            (k * (R * phi2 - R * phi1) * R / _J1, -k * (R * phi2 - R * phi1) * R / _J2),
            "fig2",
            _fig2_eom,
        ),
        c(
            "angular-momentum",
            "Sec. 2, eqs. (rel1), (g)",
            "conservation of angular momentum about the contact lines: L_1 = -L_2",
            r"I'_1\dot{\varphi_1}+I'_2\dot{\varphi_2}=0,\quad "
            r"\boldsymbol{L}_1+\boldsymbol{L}_2=0",
            r"I'_1\dot\varphi_1+I'_2\dot\varphi_2",
            sp.Integer(0),
            "fig2",
            _momentum,
        ),
        c(
            "phase-opposition",
            "Sec. 2, after eq. (g)",
            "the bodies oscillate in phase opposition",
            r"\boldsymbol{L}_1=-\boldsymbol{L}_2\ \Rightarrow\ \text{phase opposition}",
            r"\operatorname{sign}\left(\varphi_2/\varphi_1\right)",
            sp.Integer(-1),
            "fig2",
            _phase_opposition,
        ),
        c(
            "cm-moves",
            "Sec. 2, eq. (w)",
            "the centre of mass moves: its role goes to X-hat",
            r"2m_1\dot{x_1}+\frac{3}{2}m_2\dot{x_2}=0\,\rightarrow\,\dot{X}\neq 0",
            r"\dot x_2/\dot x_1",
            -4 * m1 / (3 * m2),
            "fig2",
            _cm_moves,
        ),
        c(
            "stationary-point",
            "Sec. 2, eq. (c)",
            "the stationary point X-hat",
            r"\hat{X}=\frac{I'_1x_1+I'_2x_2}{I'_1+I'_2}",
            r"\left(w_1,\ w_2\right)",
            (
                2 * m1 * R1**2 / (2 * m1 * R1**2 + sp.Rational(3, 2) * m2 * R2**2),
                sp.Rational(3, 2) * m2 * R2**2 / (2 * m1 * R1**2 + sp.Rational(3, 2) * m2 * R2**2),
            ),
            "fig2-radii",
            _stationary_general,
        ),
        c(
            "two-hoops",
            "Sec. 2",
            "for two hoops X-hat is the centre of mass",
            r"\hat{X}=\frac{2m_1R^2x_1+2m_2R^2x_2}{2m_1R^2+2m_2R^2}=\frac{m_1x_1+m_2x_2}{m_1+m_2}",
            r"\left(w_1,\ w_2\right)",
            (m1 / (m1 + m2), m2 / (m1 + m2)),
            "two-hoops",
            _stationary("two-hoops"),
        ),
        c(
            "two-cylinders",
            "Sec. 2",
            "the same is true for two cylinders",
            r"\hat{X}=\frac{m_1x_1+m_2x_2}{m_1+m_2}\ \text{(two cylinders)}",
            r"\left(w_1,\ w_2\right)",
            (m1 / (m1 + m2), m2 / (m1 + m2)),
            "two-cylinders",
            _stationary("two-cylinders"),
        ),
        c(
            "friction-ratio",
            "Sec. 2; App. A",
            "ratio of the static friction forces",
            r"\frac{f_1}{f_2}=\frac{3}{2}\,\rightarrow\,f_1>f_2",
            r"f_1/f_2",
            sp.Rational(3, 2),
            "fig2",
            _friction_ratio,
        ),
        c(
            "same-inertia",
            "Abstract; Sec. 2",
            "the resultant friction disappears when the bodies have the same moment of inertia",
            r"f_1+f_2=0\ \text{when}\ I_1=I_2",
            r"f_1+f_2",
            sp.Integer(0),
            "fig2, two-hoops, two-cylinders",
            _same_inertia,
        ),
        # ---- Sec. 3: the frictionless system (Fig. 3)
        c(
            "fric",
            "Sec. 3, eq. (fric); App. A",
            "static friction of a body pulled horizontally at height y",
            r"f(y)=F\left(1-\frac{mR}{I+mR^2}\,y\right)",
            "f(y)",
            F * (1 - m * R * y / (sp.Symbol("I") + m * R**2)),
            "pulled",
            _fric,
        ),
        c(
            "fric-coupled",
            "Sec. 3",
            "(fric) remains valid for the coupled system, with the varying spring force",
            r"f_i=-F_{ix}\left(1-\frac{m_iR\,y_i}{I_i+m_iR^2}\right),\quad y_i=R",
            r"\left(f_1,\ f_2\right)",
            (
                -Fx1 * (1 - m1 * R * R / (m1 * R**2 + m1 * R**2)),
                -Fx2 * (1 - m2 * R * R / (m2 * R**2 / 2 + m2 * R**2)),
            ),
            "fig2",
            _fric_coupled,
        ),
        c(
            "zero-friction-heights",
            "Sec. 3",
            "heights of a pull that needs no friction",
            r"y_1=2R,\quad y_2=3/2R",
            r"\left(y_1,\ y_2\right)",
            (2 * R, sp.Rational(3, 2) * R),
            "pulled-hoop, pulled-cylinder",
            _heights,
        ),
        c(
            "fig3-geometry",
            "Sec. 3 (Fig. 3)",
            "a horizontal spring between the zero-friction heights needs R1 = R2/2",
            r"R_1=R_2/2",
            "R_1",
            R2 / 2,
            "pulled-hoop, pulled-cylinder",
            _geometry,
        ),
        c(
            "fig3-equations",
            "Sec. 3, eqs. (a), (b)",
            "equations of rotation of the frictionless system (small angles)",
            r"F\left(2R_1\right)=I'_1\ddot{\varphi_1},\quad -F\left(\frac{3}{2}R_2\right)="
            r"I'_2\ddot{\varphi_2},\quad F=k\left(\frac{3}{2}R_2\varphi_2-2R_1\varphi_1\right)",
            r"\left(\ddot\varphi_1,\ \ddot\varphi_2\right)",
            (
                _F3 * 2 * R1 / (2 * m1 * R1**2),
                -_F3 * sp.Rational(3, 2) * R2 / (sp.Rational(3, 2) * m2 * R2**2),
            ),
            "fig3",
            _fig3_eom,
        ),
        c(
            "fig3-cm-acceleration",
            "Sec. 3",
            "the spring forces cancel: m1 x1'' + m2 x2'' = 0",
            r"m_1R_1\ddot{\varphi_1}+m_2R_2\ddot{\varphi_2}=0",
            r"m_1R_1\ddot\varphi_1+m_2R_2\ddot\varphi_2",
            sp.Integer(0),
            "fig3",
            _fig3_cm_acceleration,
        ),
        c(
            "fig3-cm-at-rest",
            "Sec. 3, eq. (bb)",
            "the centre of mass is stationary",
            r"m_1\dot{x_1}+m_2\dot{x_2}=0\,\rightarrow\,\dot{X}=0",
            r"\dot X",
            sp.Integer(0),
            "fig3",
            _cm_velocity(
                "fig3", "the zero mode of the engine's K gives sum m_i xdot_i = P_0 (M14)"
            ),
        ),
        c(
            "fig3-no-friction",
            "Sec. 3 (Fig. 3)",
            "no static friction acts during the oscillation, yet the bodies do not slip",
            r"f_1=f_2=0",
            r"\left(f_1,\ f_2\right)",
            (sp.Integer(0), sp.Integer(0)),
            "fig3",
            _fig3_friction,
        ),
        c(
            "fig3-angular-momentum",
            "Sec. 3 (end)",
            "the torques differ, so angular momentum is not conserved",
            r"F\left(2R_1\right)\neq F\left(\tfrac{3}{2}R_2\right)\ \Rightarrow\ "
            r"\boldsymbol{L}\ \text{not constant}",
            r"\dot L",
            _F3 * (2 * R1 - sp.Rational(3, 2) * R2),
            "fig3",
            _fig3_angular_momentum,
        ),
        # ---- Sec. 4: the coupled system by several methods
        c(
            "qq2",
            "Sec. 4, eq. (QQ2)",
            "every coordinate oscillates harmonically",
            r"\ddot{q}+\Omega^2 q=0",
            r"\ddot\varphi_1+\Omega^2\varphi_1",
            sp.Integer(0),
            "fig2",
            _qq2,
        ),
        c(
            "phi-relation",
            "Sec. 4.1",
            "integrating the conserved combination gives the angle relation",
            r"2m_1\varphi_1=-\frac{3}{2}m_2\varphi_2,\,\rightarrow\,"
            r"\varphi_2=-\frac{4m_1}{3m_2}\varphi_1",
            r"\varphi_2",
            -4 * m1 / (3 * m2) * phi1,
            "fig2",
            lambda b: _phi_relation(b, flip=False),
        ),
        c(
            "qq1",
            "Sec. 4.1, eq. (QQ1); Sec. 4.3, eq. (ep)",
            "equation of motion of the coupled system",
            r"\ddot{\varphi_1}+\frac{k}{2m_1}\left(1+\frac{4m_1}{3m_2}\right)\varphi_1=0",
            r"\Omega^2",
            k / (2 * m1) * (1 + 4 * m1 / (3 * m2)),
            "fig2",
            _omega2("fig2"),
        ),
        c(
            "omega2-fig2",
            "Sec. 4.1, eq. (QQQ1)",
            "angular frequency of the coupled system",
            r"\Omega^2=\left(\frac{k}{2m_1}+\frac{2k}{3m_2}\right)",
            r"\Omega^2",
            k / (2 * m1) + 2 * k / (3 * m2),
            "fig2",
            _omega2("fig2"),
        ),
        c(
            "energy",
            "Sec. 4.2, eq. (mu)",
            "conservation of energy at the largest speeds",
            r"\frac{k}{2}A^2=\frac{1}{2}\left(2m_1R^2\right)\dot{\Phi_1}^2+\frac{1}{2}"
            r"\left(\frac{3}{2}m_2R^2\right)\dot{\Phi_2}^2",
            r"\tfrac12 I'_1\dot\Phi_1^2+\tfrac12 I'_2\dot\Phi_2^2",
            k / 2 * A**2,
            "fig2",
            _energy,
        ),
        c(
            "nu",
            "Sec. 4.2, eq. (nu)",
            "angular momentum at the largest speeds",
            r"0=2m_1R^2\dot{\Phi_1}-\frac{3}{2}m_2R^2\dot{\Phi_2}",
            r"\dot\Phi_2",
            4 * m1 / (3 * m2) * Phid1,
            "fig2",
            _nu,
        ),
        c(
            "speeds",
            "Sec. 4.2, eqs. (om), (pi)",
            "largest speeds of the centres",
            r"v_1=A\left[\frac{3km_2}{2m_1\left(4m_1+3m_2\right)}\right]^{1/2},\quad "
            r"v_2=A\left[\frac{8km_1}{3m_2\left(4m_1+3m_2\right)}\right]^{1/2}",
            r"\left(v_1,\ v_2\right)",
            (
                A * sp.sqrt(3 * k * m2 / (2 * m1 * (4 * m1 + 3 * m2))),
                A * sp.sqrt(8 * k * m1 / (3 * m2 * (4 * m1 + 3 * m2))),
            ),
            "fig2",
            _speeds,
        ),
        c(
            "omega-from-speeds",
            "Sec. 4.2",
            "Omega from the largest speeds",
            r"\Omega=\frac{v_1+v_2}{A}=\left(\sqrt{\frac{3m_2}{2m_1}}+\sqrt{\frac{8m_1}{3m_2}}"
            r"\right)\frac{\sqrt{k}}{\sqrt{4m_1+3m_2}}=\left[\frac{k}{2m_1}+\frac{2k}{3m_2}"
            r"\right]^{1/2}",
            r"\Omega",
            (sp.sqrt(3 * m2 / (2 * m1)) + sp.sqrt(8 * m1 / (3 * m2)))
            * sp.sqrt(k)
            / sp.sqrt(4 * m1 + 3 * m2),
            "fig2",
            _omega,
        ),
        c(
            "amplitudes",
            "Sec. 4.2",
            "amplitudes of the centres about X-hat",
            r"A_1=A\frac{3m_2}{4m_1+3m_2},\quad A_2=A\frac{4m_1}{4m_1+3m_2}",
            r"\left(A_1,\ A_2\right)",
            (A * 3 * m2 / (4 * m1 + 3 * m2), A * 4 * m1 / (4 * m1 + 3 * m2)),
            "fig2",
            _amplitudes,
        ),
        c(
            "amplitude-sum",
            "Sec. 4.2",
            "the amplitudes add up to the spring's deformation",
            r"A=A_1+A_2",
            r"A_1+A_2",
            A,
            "fig2",
            _amplitude_sum,
        ),
        c(
            "amplitudes-equal-masses",
            "Sec. 4.2",
            "amplitudes for equal masses",
            r"A_1=(3/7)A,\quad A_2=(4/7)A",
            r"\left(A_1,\ A_2\right)",
            (sp.Rational(3, 7) * A, sp.Rational(4, 7) * A),
            "fig2",
            _amplitudes_equal_masses,
        ),
        c(
            "lagrangian",
            "Sec. 4.3",
            "the Lagrangian about X-hat",
            r"\mathcal{L}=\frac{1}{2}I'_1\dot{\phi_1}^2+\frac{1}{2}I'_2\dot{\phi_2}^2-"
            r"\frac{1}{2}k\left(\varepsilon_1+\varepsilon_2\right)^2,\quad "
            r"\varepsilon_i=R\phi_i",
            r"\mathcal{L}",
            _J1 * phid1**2 / 2 + _J2 * phid2**2 / 2 - k / 2 * (R * phi1 + R * phi2) ** 2,
            "fig2",
            _lagrangian,
        ),
        c(
            "spring-parts",
            "Sec. 4.3, eq. (part)",
            "the two spring parts in series",
            r"\frac{1}{k}=\frac{1}{k_1}+\frac{1}{k_2}",
            r"\frac{1}{k_1}+\frac{1}{k_2}",
            1 / k,
            "fig2",
            _k_series,
        ),
        c(
            "lagrange-equations",
            "Sec. 4.3, eqs. (al), (be)",
            "Euler-Lagrange equations",
            r"I'_1\ddot{\phi_1}=-k\left(R\phi_1+R\phi_2\right)R,\quad "
            r"I'_2\ddot{\phi_2}=-k\left(R\phi_1+R\phi_2\right)R",
            r"\left(I'_1\ddot\phi_1,\ I'_2\ddot\phi_2\right)",
            (-k * (R * phi1 + R * phi2) * R, -k * (R * phi1 + R * phi2) * R),
            "fig2",
            _eom_flipped,
        ),
        c(
            "ga",
            "Sec. 4.3, eq. (ga)",
            "the right-hand sides are equal",
            r"2m_1R^2\ddot{\phi_1}=\frac{3}{2}m_2R^2\ddot{\phi_2}",
            r"\ddot\phi_2",
            4 * m1 / (3 * m2) * phidd1,
            "fig2",
            _ga,
        ),
        c(
            "de",
            "Sec. 4.3, eq. (de); App. A",
            "integrated twice",
            r"2m_1\phi_1=\frac{3}{2}m_2\phi_2\,\rightarrow\,\phi_2=\frac{4m_1}{3m_2}\phi_1",
            r"\phi_2",
            4 * m1 / (3 * m2) * phi1,
            "fig2",
            lambda b: _phi_relation(b, flip=True),
        ),
        c(
            "k1-k2",
            "Sec. 4.3, eqs. (k1), (k2)",
            "stiffnesses of the spring parts about X-hat",
            r"k_1=k\frac{3m_2+4m_1}{3m_2},\quad k_2=k\frac{3m_2+4m_1}{4m_1}",
            r"\left(k_1,\ k_2\right)",
            (_k1_paper, _k2_paper),
            "fig2",
            _k_parts,
        ),
        c(
            "k-equal-masses",
            "Sec. 4.3",
            "spring parts for equal masses",
            r"k_1=\frac{7k}{3},\quad k_2=\frac{7k}{4}",
            r"\left(k_1,\ k_2\right)",
            (7 * k / 3, 7 * k / 4),
            "fig2",
            _k_equal_masses,
        ),
        c(
            "k-equal",
            "Sec. 4.3",
            "k1 = k2 (and A1 = A2) if m1/m2 = 3/4",
            r"k_1=k_2\ (A_1=A_2)\ \text{if}\ m_1/m_2=3/4",
            r"m_1/m_2\ \text{from}\ k_1=k_2,\ A_1=A_2",
            (sp.Rational(3, 4), sp.Rational(3, 4)),
            "fig2",
            _k_equal,
        ),
        c(
            "xhat-three-sevenths",
            "Sec. 4.3",
            "for m1 = m2 and x1 = 0, X-hat = (3/7) l, the length of the stiffer left part",
            r"\hat{X}=(3/7)l,\quad k_1=\frac{7k}{3}=k\frac{l}{\hat X}",
            r"\left(\hat X,\ k\,l/\hat X\right)",
            (sp.Rational(3, 7) * ell_total, 7 * k / 3),
            "fig2",
            _xhat_three_sevenths,
        ),
        c(
            "sum-rule",
            "Sec. 4.4; App. B",
            "Omega squared is the sum of the subsystems' squared frequencies",
            r"\Omega_{f}^2=\frac{k}{2m_1}+\frac{2k}{3m_2}\equiv\Omega_1^2+\Omega_2^2",
            r"\Omega^2-\left(\Omega_1^2+\Omega_2^2\right)",
            sp.Integer(0),
            "fig2",
            _sum_rule_fig2,
        ),
        c(
            "sum-rule-general",
            "Sec. 4.4",
            "the angular frequency squared of a coupled system must equal the sum of the parts'",
            r"\Omega^2=\Omega_1^2+\Omega_2^2\ \text{(any coupled system; Fig. 4 (a))}",
            r"\omega^2",
            ((k1 + k2) / (2 * m1) + 2 * k2 / (3 * m2),),
            "fig4a",
            _sum_rule_general,
        ),
        c(
            "alpha-beta",
            "App. B",
            "parameters of the subsystems' energies",
            r"\alpha_1=2m_1R^2,\ \beta_1=kR^2,\quad \alpha_2=\frac{3}{2}m_2R^2,\ \beta_2=kR^2",
            r"\left(\alpha_1,\ \beta_1,\ \alpha_2,\ \beta_2\right)",
            (_J1, k * R**2, _J2, k * R**2),
            "fig2",
            _alpha_beta,
        ),
        c(
            "omega1-omega2",
            "App. B",
            "natural frequencies of the subsystems of Fig. 2",
            r"\Omega_1=\sqrt{\frac{k}{2m_1}},\quad \Omega_2=\sqrt{\frac{2k}{3m_2}}",
            r"\left(\Omega_1,\ \Omega_2\right)",
            (_Omega1, _Omega2),
            "fig2",
            _clamped("fig2", roots=True),
        ),
        c(
            "omega2-fig3",
            "App. B",
            "angular frequency of the frictionless system (Fig. 3)",
            r"\Omega_{\bcancel{f}}^2=\frac{2k}{m_1}+\frac{3k}{2m_2}\equiv\Omega_3^2+\Omega_4^2",
            r"\left(\Omega^2,\ \Omega^2-\Omega_3^2-\Omega_4^2\right)",
            (2 * k / m1 + 3 * k / (2 * m2), sp.Integer(0)),
            "fig3",
            _sum_rule_fig3,
        ),
        c(
            "omega3-omega4",
            "App. C",
            "natural frequencies of the subsystems of Fig. 3",
            r"\Omega_{3}=\sqrt{2k/m_1},\quad \Omega_4=\sqrt{3k/2m_2}",
            r"\left(\Omega_3,\ \Omega_4\right)",
            (_Omega3, _Omega4),
            "fig3",
            _clamped("fig3", roots=True),
        ),
        c(
            "lagrangian-hamilton",
            "Sec. 4.5, eq. (l)",
            "the Lagrangian compared with H",
            r"\mathcal{L}=m_1R^2\dot{\phi_1}^2+\frac{3}{4}m_2R^2\dot{\phi_2}^2-"
            r"\frac{k}{2}\left(R\phi_1+R\phi_2\right)^2",
            r"\mathcal{L}",
            m1 * R**2 * phid1**2
            + sp.Rational(3, 4) * m2 * R**2 * phid2**2
            - k / 2 * (R * phi1 + R * phi2) ** 2,
            "fig2",
            _lagrangian45,
        ),
        c(
            "canonical-coordinates",
            "Sec. 4.5",
            "the canonical coordinates",
            r"q_1=\sqrt{2}R\phi_1,\quad q_2=\sqrt{3/2}R\phi_2",
            r"\left(q_1,\ q_2\right)",
            (sp.sqrt(2) * R * phi1, sp.sqrt(sp.Rational(3, 2)) * R * phi2),
            "fig2",
            _canonical,
        ),
        c(
            "hamiltonian",
            "Sec. 4.5, eq. (k); App. C, eq. (k0)",
            "the Hamiltonian",
            r"\mathcal{H}=\frac{p_1^2}{2m_1}+\frac{p_2^2}{2m_2}+\frac{k}{2}\left(\frac{q_1}"
            r"{\sqrt{2}}+\frac{\sqrt{2}q_2}{\sqrt{3}}\right)^2",
            r"\mathcal{H}",
            _hoop_cylinder_hamiltonian(q1, q2, p1, p2, 1 / sp.sqrt(2), sp.sqrt(2) / sp.sqrt(3)),
            "fig2",
            _hamiltonian,
        ),
        c(
            "hamilton-equations",
            "Sec. 4.5, eq. (h)",
            "Hamilton's equations",
            r"-\dot{p_1}=k\left(\frac{q_1}{\sqrt{2}}+\frac{\sqrt{2}q_2}{\sqrt{3}}\right)"
            r"\frac{1}{\sqrt{2}},\quad -\dot{p_2}=k\left(\frac{q_1}{\sqrt{2}}+\frac{\sqrt{2}q_2}"
            r"{\sqrt{3}}\right)\frac{\sqrt{2}}{\sqrt{3}}",
            r"\left(-\dot p_1,\ -\dot p_2\right)",
            (
                sp.expand(k * (q1 / sp.sqrt(2) + sp.sqrt(2) * q2 / sp.sqrt(3)) / sp.sqrt(2)),
                sp.expand(
                    k * (q1 / sp.sqrt(2) + sp.sqrt(2) * q2 / sp.sqrt(3)) * sp.sqrt(2) / sp.sqrt(3)
                ),
            ),
            "fig2",
            _hamilton_equations,
        ),
        c(
            "canonical-ratio",
            "Sec. 4.5",
            "the canonical coordinates in the mode",
            r"\dot{p_2}=\dot{p_1}\frac{2}{\sqrt{3}}\,\rightarrow\,q_2=\frac{m_1}{m_2}"
            r"\frac{2}{\sqrt{3}}q_1",
            r"q_2",
            m1 / m2 * 2 / sp.sqrt(3) * q1,
            "fig2",
            _q_ratio,
        ),
        c(
            "hamilton-motion",
            "Sec. 4.5",
            "the equation of motion in canonical coordinates is (ep)",
            r"-\dot{p_1}=k\left(\frac{q_1}{2}+\frac{2m_1}{3m_2}q_1\right)",
            r"-\dot p_1",
            sp.expand(k * (q1 / 2 + 2 * m1 / (3 * m2) * q1)),
            "fig2",
            _hamilton_final,
        ),
        c(
            "potential-fig2",
            "App. C, eq. (k0)",
            "the Hamiltonian's potential from the subsystems' natural frequencies",
            r"U_{f}=\frac{k}{2}\left(\frac{\Omega_1}{\sqrt{k/m_1}}\,q_1+\frac{\Omega_2}"
            r"{\sqrt{k/m_2}}\,q_2\right)^2",
            r"U_f",
            k / 2 * (_Omega1 / sp.sqrt(k / m1) * q1 + _Omega2 / sp.sqrt(k / m2) * q2) ** 2,
            "fig2",
            _potential_q("fig2", (q1, q2), (p1, p2)),
        ),
        c(
            "potential-coefficients",
            "App. C",
            "the coefficients 1/sqrt(2), sqrt(2/3) are Omega_i / sqrt(k/m_i)",
            r"\frac{1}{\sqrt{2}}=\frac{\Omega_1}{\sqrt{k/m_1}},\quad \sqrt{\frac{2}{3}}="
            r"\frac{\Omega_2}{\sqrt{k/m_2}}",
            r"\left(\lvert c_1\rvert,\ \lvert c_2\rvert\right)",
            (_Omega1 / sp.sqrt(k / m1), _Omega2 / sp.sqrt(k / m2)),
            "fig2",
            _coefficients,
        ),
        c(
            "potential-fig3",
            "App. C, eq. (k02)",
            "the frictionless system's potential from its natural frequencies",
            r"U_{\bcancel{f}}=\frac{k}{2}\left(\frac{\Omega_3}{\sqrt{k/m_1}}\,q_3+\frac{\Omega_4}"
            r"{\sqrt{k/m_2}}\,q_4\right)^2",
            r"U_{\bcancel{f}}",
            k / 2 * (_Omega3 / sp.sqrt(k / m1) * q3 + _Omega4 / sp.sqrt(k / m2) * q4) ** 2,
            "fig3",
            _potential_q("fig3", (q3, q4), (p3, p4)),
        ),
        # ---- App. A: static friction
        c(
            "friction-hoop",
            "App. A",
            "friction on the hoop in the mode",
            r"f_1=\frac{k_1}{2}R\phi_1=k\frac{3m_2+4m_1}{6m_2}R\phi_1",
            r"f_1",
            _k1_paper / 2 * R * phi1,
            "fig2",
            _app_a_friction(0),
        ),
        c(
            "friction-cylinder-k2",
            "App. A",
            "friction on the cylinder, via k2",
            r"f_2=\frac{k_2}{2}R\phi_2",
            r"f_2",
            _k2_paper / 2 * R * phi2,
            "fig2",
            _app_a_friction(1),
        ),
        c(
            "friction-cylinder",
            "App. A",
            "friction on the cylinder, final form",
            r"f_2=k\frac{3m_2+4m_1}{12m_1}R\phi_2",
            r"f_2",
            k * (3 * m2 + 4 * m1) / (12 * m1) * R * phi2,
            "fig2",
            _app_a_friction(1),
        ),
        c(
            "pull-equations",
            "App. A, eqs. (a1), (a2)",
            "rotation of the pulled body about its contact line",
            r"F-f=ma,\quad Fy=\left(I+mR^2\right)\ddot{\varphi}",
            r"\ddot\varphi",
            F * y / (sp.Symbol("I") + m * R**2),
            "pulled",
            _app_a_eqs,
        ),
        c(
            "pull-at-floor",
            "App. A",
            "a pull at y = 0 is all taken by friction",
            r"y=0:\quad f=F,\ a=0",
            r"\left(f,\ a\right)",
            (F, sp.Integer(0)),
            "pulled",
            _app_a_origin,
        ),
        c(
            "fig5-cylinder",
            "App. A, Fig. 5",
            "the cylinder's friction at the top, y = 2R",
            r"f(2R)=-\frac{F}{3}\ \text{(cylinder)}",
            r"f(2R)",
            -F / 3,
            "pulled-cylinder",
            _fig5_cylinder,
        ),
        c(
            "fig5-labels",
            "App. A, Fig. 5",
            "the lines of Fig. 5",
            r"f_1(y)\ \text{(cylinder)},\quad f_2(y)\ \text{(hoop)}",
            r"\left(f_1(y),\ f_2(y)\right)",
            (F * (1 - 2 * y / (3 * R)), F * (1 - y / (2 * R))),
            "pulled-hoop, pulled-cylinder",
            _fig5_labels,
        ),
    ]

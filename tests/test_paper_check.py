"""``rollspring paper-check``: every quantitative statement of the paper, with its computed verdict.

Each verdict is pinned by an independent computation (:data:`INDEPENDENT`): the paper's systems
are written down here by hand — positions of the centres and of the spring's ends, T, V, Newton's
law for the friction — in SymPy, without the derivation engine, and each claim's transcription
(``claim.paper``) is compared with what they give, numerically at random points; the verdict that
follows must be the engine's. Each claim's quote must occur verbatim in the paper's LaTeX source
(G. Nyitray, arXiv 2508.01379, ``../shared/paper/``), within the section its location names; where
the source is not at hand (a clean clone), against ``tests/data/paper-quotes.json``, the record of
what was verified against it (with the source's sha256), so no quote changes unverified.
"""

from __future__ import annotations

import enum
import hashlib
import json
import os
import random
import re
import tomllib
from collections.abc import Callable
from importlib import resources
from pathlib import Path
from typing import Any

import numpy as np
import pytest
import sympy as sp
from scipy.integrate import solve_ivp
from sympy.logic.boolalg import BooleanAtom
from typer.testing import CliRunner

from rollspring.analysis.paper import (
    HOLDS_ONLY_IF,
    HOLDS_STATED,
    VERDICTS,
    VERIFIED,
    WRONG,
    Assumption,
    Claim,
    Derived,
    Verdict,
    check_claim,
    check_paper,
    paper_claims,
    quote_key,
)
from rollspring.analysis.paper.catalogue import claim_tables, paper_value, recipe
from rollspring.cli import app
from rollspring.cli.commands import paper_check as cli_paper_check

V, S, H, W = VERIFIED, HOLDS_STATED, HOLDS_ONLY_IF, WRONG

# -- the paper's source ----------------------------------------------------------------------------


def _paper_path() -> Path | None:
    given = os.environ.get("ROLLSPRING_PAPER")
    if given:
        return Path(given)
    folder = Path(__file__).resolve().parents[2] / "shared" / "paper"
    found = sorted(folder.glob("*.txt")) if folder.is_dir() else []
    return found[0] if found else None


PAPER = _paper_path()


def _spans(source: str) -> dict[str, str]:
    """The paper's parts by the names locations use: 'Abstract', 'Sec. 3', 'Sec. 5.2', 'App. A'
    (each up to the next heading), 'Fig. 2 caption'."""
    spans: dict[str, str] = {}
    heads = list(re.finditer(r"\\(section|subsection)(\*?)\{([^}]*)\}", source))
    section = subsection = 0
    for i, head in enumerate(heads):
        kind, star, title = head.groups()
        end = heads[i + 1].start() if i + 1 < len(heads) else len(source)
        if star:
            name = "Abstract" if title == "Abstract" else f"App. {title.split()[1][0]}"
        elif kind == "section":
            section, subsection = section + 1, 0
            name = f"Sec. {section}"
        else:
            subsection += 1
            name = f"Sec. {section}.{subsection}"
        spans[name] = source[head.start() : end]
    for caption in re.finditer(r"\\caption\{(.*?)\}\s*\\label\{fig(\d)\}", source, re.S):
        spans[f"Fig. {caption.group(2)} caption"] = caption.group(1)
    return spans


_PART = re.compile(r"^(Abstract|Sec\. \d(?:\.\d)?|App\. [ABC]|Fig\. \d caption)\b")


# -- numbers: comparing expressions at random points ----------------------------------------------

_rng = random.Random(20250801)
POINTS = [
    {
        "positive": [sp.Rational(_rng.randint(30, 300), _rng.randint(20, 90)) for _ in range(40)],
        "real": [
            sp.Rational(_rng.randint(-300, 300) or 7, _rng.randint(20, 90)) for _ in range(40)
        ],
    }
    for _ in range(3)
]
_NAMES: dict[str, int] = {}


def _value(symbol: sp.Symbol, point: dict[str, list[sp.Rational]]) -> sp.Rational:
    index = _NAMES.setdefault(symbol.name, len(_NAMES) % 40)
    return point["positive" if symbol.is_positive else "real"][index]


def same(left: Any, right: Any) -> bool:
    """Equal as functions of their symbols (matched by name): at three random points; truth values
    and tuples compare item by item."""
    truth = (bool, BooleanAtom)
    if isinstance(left, truth) or isinstance(right, truth):
        return isinstance(left, truth) and isinstance(right, truth) and bool(left) == bool(right)
    if isinstance(left, tuple) or isinstance(right, tuple):
        return (
            isinstance(left, tuple)
            and isinstance(right, tuple)
            and len(left) == len(right)
            and all(same(a, b) for a, b in zip(left, right, strict=True))
        )
    difference = sp.sympify(left) - sp.sympify(right)
    for point in POINTS:
        at = difference.xreplace({s: _value(s, point) for s in difference.free_symbols})
        number = complex(sp.N(at, 30))
        scale = 1 + abs(
            complex(
                sp.N(
                    sp.sympify(left).xreplace(
                        {s: _value(s, point) for s in sp.sympify(left).free_symbols}
                    ),
                    30,
                )
            )
        )
        if abs(number) > 1e-15 * scale:
            return False
    return True


def verdict(
    paper: Any,
    truth: Any,
    *,
    stated: tuple[Any, Any] | None = None,
    unstated: tuple[Any, Any] | None = None,
) -> str:
    """The verdict that follows from the hand computation: ``truth`` in general, ``stated`` =
    (paper read under the paper's stated assumption, truth under it), ``unstated`` = (paper read
    under a condition the paper does not state, truth under it and the stated assumption)."""
    if same(paper, truth):
        return V
    if stated is not None and same(*stated):
        return S
    if unstated is not None and same(*unstated):
        return H
    return W


def by_name(expr: Any, mapping: dict[str, Any]) -> Any:
    """``expr`` with its symbols named in ``mapping`` replaced (names, not assumptions)."""
    if isinstance(expr, tuple):
        return tuple(by_name(e, mapping) for e in expr)
    expr = sp.sympify(expr)
    return expr.xreplace({s: mapping[s.name] for s in expr.free_symbols if s.name in mapping})


def flip_first(expr: Any) -> Any:
    """Body 1's angle counted the other way (and its rates, its canonical pair)."""
    return by_name(
        expr,
        {
            n: -sp.Symbol(n, real=True)
            for n in ("phi_1", "phidot_1", "phiddot_1", "q_1", "p_1", "pdot_1", "q_3")
        },
    )


# -- the paper's systems, by hand ------------------------------------------------------------------

pos = {"positive": True}
m, m1, m2, R, R1, R2, k, k1, k2, A, L, g = sp.symbols(
    "m m_1 m_2 R R_1 R_2 k k_1 k_2 A ell g", **pos
)
Omega_, Phid1, I_, y, ell = sp.symbols("Omega Phidot_1 I y l", **pos)
phi1, phi2, phid1, phid2, phidd1, phidd2 = sp.symbols(
    "phi_1 phi_2 phidot_1 phidot_2 phiddot_1 phiddot_2", real=True
)
x1, x2, xd1, xd2, F, f, f1s, f2s, P0, D0, t = sp.symbols(
    "x_1 x_2 xdot_1 xdot_2 F f f_1 f_2 P_0 D_0 t", real=True
)
q1, q2, q3, q4, p1, p2, pd1 = sp.symbols("q_1 q_2 q_3 q_4 p_1 p_2 pdot_1", real=True)


class Fig1:
    """Two point masses on ice, x_i their displacements from a placement at the spring's rest
    length."""

    extension = x2 - x1
    U = k / 2 * extension**2
    forces = (k * extension, -k * extension)  # on mass 1, mass 2, along +x
    normal_minus_weight = (0, 0)  # the spring stays horizontal
    friction = (0, 0)  # frictionless floor


class Fig2:
    """The hoop (m1, I = m1 R^2) and the cylinder (m2, I = m2 R^2/2), radius R, centres joined;
    phi_i clockwise, x_i = R phi_i, measured from a placement at the spring's rest length."""

    I1, I2 = m1 * R**2, m2 * R**2 / 2
    J1, J2 = I1 + m1 * R**2, I2 + m2 * R**2  # about the contact line (Steiner)
    T = (m1 * (R * phid1) ** 2 + I1 * phid1**2 + m2 * (R * phid2) ** 2 + I2 * phid2**2) / 2
    V = k / 2 * (R * phi2 - R * phi1) ** 2
    Q = (-sp.diff(V, phi1), -sp.diff(V, phi2))  # torques about the contact lines
    acc = (Q[0] / J1, Q[1] / J2)
    spring = (k * (R * phi2 - R * phi1), -k * (R * phi2 - R * phi1))  # force on each centre
    friction = (m1 * R * acc[0] - spring[0], m2 * R * acc[1] - spring[1])  # Newton: m a = F + f
    omega2 = k * R**2 * (1 / J1 + 1 / J2)  # det(K - w M) = 0, K = k R^2 [[1, -1], [-1, 1]]
    ratio = -J1 / J2  # phi_2/phi_1 in the mode: (K - omega2 M) v = 0
    weights = (J1 / (J1 + J2), J2 / (J1 + J2))  # of the conserved J_1 phidot_1 + J_2 phidot_2

    @staticmethod
    def in_mode(expr: Any) -> Any:
        return by_name(expr, {"phi_2": Fig2.ratio * phi1})

    @staticmethod
    def amplitudes() -> tuple[sp.Expr, sp.Expr]:
        """Centre amplitudes for a spring deformation A: phi = a (1, ratio), deformation
        R a (ratio - 1)."""
        a = A / (R * (1 - Fig2.ratio))
        return (R * a, -R * a * Fig2.ratio)

    @staticmethod
    def parts() -> tuple[sp.Expr, sp.Expr]:
        """The spring cut at X-hat: the part at body i has the length w_j l, stiffness k/w_j."""
        return (k / Fig2.weights[1], k / Fig2.weights[0])


def _same_shapes(gamma: sp.Expr) -> sp.Expr:
    """f_1 + f_2 for two bodies of one shape (I = gamma m R^2) joined at their centres."""
    J = [(gamma + 1) * mm * R**2 for mm in (m1, m2)]
    force = k * (R * phi2 - R * phi1)
    acc = [force * R / J[0], -force * R / J[1]]
    return sp.simplify(m1 * R * acc[0] - force + m2 * R * acc[1] + force)


class Fig3:
    """The paper's Fig. 3: a hoop of radius R2/2 on a track raised by R2/2 (centres level at R2),
    the spring from the hoop's top to the cylinder's point 3R2/2 high; exact geometry."""

    r1 = R2 / 2
    J1, J2 = 2 * m1 * r1**2, sp.Rational(3, 2) * m2 * R2**2
    end1 = (r1 * phi1 + r1 * sp.sin(phi1), R2 + r1 * sp.cos(phi1))
    end2 = (L + R2 * phi2 + R2 / 2 * sp.sin(phi2), R2 + R2 / 2 * sp.cos(phi2))
    length = sp.sqrt((end2[0] - end1[0]) ** 2 + (end2[1] - end1[1]) ** 2)
    V = k / 2 * (length - L) ** 2
    acc = (-sp.diff(V, phi1) / J1, -sp.diff(V, phi2) / J2)
    pull = k * (length - L) * (end2[0] - end1[0]) / length  # the spring on the hoop, along x
    friction = (m1 * r1 * acc[0] - pull, m2 * R2 * acc[1] + pull)

    @staticmethod
    def linear(expr: sp.Expr) -> sp.Expr:
        """First order in the angles."""
        e = sp.sympify(expr)
        zero = {phi1: 0, phi2: 0}
        return sp.simplify(e.subs(zero) + sum(sp.diff(e, q).subs(zero) * q for q in (phi1, phi2)))

    @staticmethod
    def b() -> tuple[sp.Expr, sp.Expr]:
        """Lever arms of the spring about the contact lines: d(length)/d(phi_i) at rest."""
        zero = {phi1: 0, phi2: 0}
        return tuple(sp.simplify(sp.diff(Fig3.length, q).subs(zero)) for q in (phi1, phi2))


class Fig3Tilted:
    """Fig. 3 on one floor: the hoop (radius R2/2, centre at R2/2), the spring from its top (R2
    high) to the cylinder's point 3R2/2 high, the centres L apart: tilted at rest; exact."""

    r1 = R2 / 2
    J1, J2 = 2 * m1 * r1**2, sp.Rational(3, 2) * m2 * R2**2
    end1 = (r1 * phi1 + r1 * sp.sin(phi1), r1 + r1 * sp.cos(phi1))
    end2 = (L + R2 * phi2 + R2 / 2 * sp.sin(phi2), R2 + R2 / 2 * sp.cos(phi2))
    length = sp.sqrt((end2[0] - end1[0]) ** 2 + (end2[1] - end1[1]) ** 2)
    rest = sp.sqrt(L**2 + (R2 / 2) ** 2)
    V = k / 2 * (length - rest) ** 2
    acc = (-sp.diff(V, phi1) / J1, -sp.diff(V, phi2) / J2)
    pull = k * (length - rest) * (end2[0] - end1[0]) / length  # the spring on the hoop, along x
    friction = (m1 * r1 * acc[0] - pull, m2 * R2 * acc[1] + pull)  # Newton: m a = F + f


class Radii:
    """The Sec. 3 pair with unequal radii R1, R2 (centres level, spring horizontal at the
    centres): the torques about the contact lines and what they conserve."""

    J1, J2 = 2 * m1 * R1**2, sp.Rational(3, 2) * m2 * R2**2
    V = k / 2 * (R2 * phi2 - R1 * phi1) ** 2
    Q = (-sp.diff(V, phi1), -sp.diff(V, phi2))

    @staticmethod
    def conserved() -> tuple[sp.Expr, sp.Expr]:
        """d/dt of sum J_i phidot_i (the paper's (rel1)) and of sum J_i phidot_i / R_i."""
        q1, q2 = Radii.Q
        return (sp.simplify(q1 + q2), sp.simplify(q1 / R1 + q2 / R2))


def _fig3_numbers() -> dict[sp.Symbol, sp.Rational]:
    return {m1: sp.Rational(13, 10), m2: sp.Rational(7, 10), k: 100, R2: sp.Rational(1, 10), L: 1}


def _fig3_friction_orders() -> list[list[sp.Expr]]:
    """Fig. 3's exact friction along the mode phi = a (v1, 1), coefficients of a, a^2, a^3."""
    a = sp.Symbol("a", real=True)
    b1, b2 = Fig3.b()
    v = (b1 / Fig3.J1) / (b2 / Fig3.J2)  # mode shape of a rank-one K = k b b^T: M^-1 b
    numbers = _fig3_numbers()
    out = []
    for friction in Fig3.friction:
        e = friction.subs({phi1: a * v, phi2: a}).subs(numbers)
        series = sp.series(e, a, 0, 4).removeO()
        out.append([sp.nsimplify(sp.N(series.coeff(a, n), 20), rational=False) for n in (1, 2, 3)])
    return out


def _pulled(inertia: sp.Expr) -> tuple[sp.Expr, sp.Expr]:
    """A body (mass m, radius R, moment of inertia ``inertia``) pulled by F at height y: Newton
    m a = F - f (f counted against F) and (I + m R^2) phiddot = F y about the contact line,
    a = R phiddot: (f, phiddot)."""
    phidd = F * y / (inertia + m * R**2)
    return (sp.simplify(F - m * R * phidd), phidd)


def _isotonic_periods() -> tuple[float, float]:
    """Periods of x'' = -x + 1/x^3 (V = x^2/2 + 1/(2x^2), not harmonic) from two amplitudes."""

    def period(x0: float) -> float:
        def rhs(_t: float, s: np.ndarray) -> list[float]:
            return [s[1], -s[0] + 1 / s[0] ** 3]

        def turn(_t: float, s: np.ndarray) -> float:
            return s[1]

        turn.direction = -1  # type: ignore[attr-defined]
        sol = solve_ivp(rhs, (0, 20), [x0, 0.0], events=turn, rtol=1e-11, atol=1e-12)
        return float(sol.t_events[0][1] - sol.t_events[0][0])

    return period(1.2), period(2.5)


def _consequently_roots() -> list[sp.Expr]:
    """A hoop tied to a wall (k_1) and joined to the cylinder (k_2): its two normal modes."""
    w = sp.Symbol("w")
    M = sp.diag(Fig2.J1, Fig2.J2)
    K = R**2 * sp.Matrix([[k1 + k2, -k2], [-k2, k2]])
    return sp.solve((K - w * M).det(), w)


# -- each claim's verdict, from the hand computation --------------------------------------------

Check = Callable[[Claim], str]


def _plain(truth: Callable[[], Any]) -> Check:
    return lambda c: verdict(c.paper, truth())


def _fig1_at_rest(c: Claim) -> str:
    momentum = P0 / (m1 + m2)  # sum m_i xdot_i = P_0 is conserved: sum of the forces is 0
    assert sp.simplify(sum(Fig1.forces)) == 0
    return verdict(c.paper, momentum, stated=(c.paper, momentum.subs(P0, 0)))


def _fig3_at_rest(c: Claim) -> str:
    total = Fig3.linear(m1 * Fig3.r1 * Fig3.acc[0] + m2 * R2 * Fig3.acc[1])
    assert total == 0  # to first order the momentum is conserved
    return verdict(c.paper, P0 / (m1 + m2), stated=(c.paper, 0))


def _magnitudes(truth: Any) -> Check:
    def check(c: Claim) -> str:
        t = truth()
        size = tuple(sp.Abs(e) for e in t) if isinstance(t, tuple) else sp.Abs(t)
        paper = tuple(sp.Abs(e) for e in c.paper) if isinstance(c.paper, tuple) else sp.Abs(c.paper)
        return verdict(c.paper, t, stated=(paper, size))

    return check


def _friction_ratio() -> sp.Expr:
    first, second = (Fig2.in_mode(e) for e in Fig2.friction)
    return sp.simplify(first / second)


def _same_inertia(c: Claim) -> str:
    assert _same_shapes(sp.Integer(1)) == 0 and _same_shapes(sp.Rational(1, 2)) == 0
    total = sum(Fig2.friction).subs(m2, 2 * m1)  # I_1 = m_1 R^2 = I_2 = m_2 R^2/2
    return verdict(c.paper, sp.simplify(total))


def _fig3_stated(exact: Callable[[], Any], *, subs: dict[Any, Any] | None = None) -> Check:
    """A Fig. 3 claim: exact in general, first order under the paper's small angles."""

    def check(c: Claim) -> str:
        paper = by_name(c.paper, {"R_1": R2 / 2}) if subs is None else by_name(c.paper, subs)
        e = exact()
        lin = tuple(Fig3.linear(x) for x in e) if isinstance(e, tuple) else Fig3.linear(e)
        return verdict(paper, e, stated=(paper, lin))

    return check


def _fig3_no_friction(c: Claim) -> str:
    orders = _fig3_friction_orders()
    for first, second, third in orders:
        assert abs(first) < 1e-12 and abs(second) < 1e-12 and abs(third) > 1e-6
    a = sp.Symbol("a", real=True)
    third_order = tuple(third * a**3 for _, _, third in orders)  # the exact friction, O(a^3)
    return verdict(c.paper, third_order, stated=(c.paper, (0, 0)))


def _fric_coupled(c: Claim) -> str:
    """(fric) with the spring's varying force on Fig. 2 (at the centres): Newton at one instant,
    exact at every configuration (no assumption on F(t))."""
    paper = by_name(c.paper, {"F_1x": Fig2.spring[0], "F_2x": Fig2.spring[1]})
    return verdict(paper, Fig2.friction)


def _geometry(c: Claim) -> str:
    h = sp.Symbol("h", real=True)  # the hoop's track above the cylinder's
    hoop_top, cylinder_pull = h + 2 * R1, sp.Rational(3, 2) * R2  # zero-friction heights
    one_floor = sp.solve(sp.Eq(hoop_top.subs(h, 0), cylinder_pull), R1)[0]
    level = sp.solve([sp.Eq(hoop_top, cylinder_pull), sp.Eq(h + R1, R2)], [R1, h], dict=True)[0]
    return verdict(c.paper, one_floor, stated=(c.paper, level[R1]))


def _radii_momentum(c: Claim) -> str:
    """(rel1): sum J_i phidot_i is conserved only with equal radii (then zero from rest); in general
    sum J_i phidot_i / R_i is."""
    rate, kept = Radii.conserved()
    assert rate != 0 and kept == 0 and sp.simplify(rate.subs(R1, R2)) == 0
    return verdict(c.paper, Radii.J1 * phid1 + Radii.J2 * phid2, stated=(c.paper, 0))


def _radii_stationary(c: Claim) -> str:
    """(c): the rate of (J_1 x_1 + J_2 x_2)/(J_1 + J_2), x_i = R_i phi_i: a multiple of the
    conserved sum J_i phidot_i / R_i only with equal radii (then zero from rest)."""
    rate = (Radii.J1 * R1 * phid1 + Radii.J2 * R2 * phid2) / (Radii.J1 + Radii.J2)
    kept = Radii.J1 * phid1 / R1 + Radii.J2 * phid2 / R2
    assert sp.simplify((rate / kept).subs(R1, R2)).free_symbols.isdisjoint({phid1, phid2})
    assert not sp.simplify(rate / kept).free_symbols.isdisjoint({phid1, phid2})
    return verdict(c.paper, rate, stated=(c.paper, 0))


def _spring_horizontal(c: Claim) -> str:
    """A tilted spring between the percussion heights: no first-order friction, so the paper's
    "must be horizontal" (first-order friction when tilted) is wrong."""
    zero = {phi1: 0, phi2: 0}
    first = [
        sp.simplify(sum(sp.diff(f_, q).subs(zero) for q in (phi1, phi2)) + f_.subs(zero))
        for f_ in Fig3Tilted.friction
    ]
    return verdict(c.paper, sp.true if any(f_ != 0 for f_ in first) else sp.false)


def _fig3_equations(c: Claim) -> str:
    return _fig3_stated(lambda: Fig3.acc)(c)


def _fig3_force(c: Claim) -> str:
    return _fig3_stated(lambda: Fig3.pull)(c)


def _fig3_forces(c: Claim) -> str:
    return _fig3_stated(
        lambda: (
            Fig3.J1 * Fig3.acc[0] / (2 * Fig3.r1),
            Fig3.J2 * Fig3.acc[1] / (sp.Rational(3, 2) * R2),
        )
    )(c)


def _fig3_sums(c: Claim) -> str:
    combination = Fig3.J1 * Fig3.acc[0] / (2 * Fig3.r1) + Fig3.J2 * Fig3.acc[1] / (
        sp.Rational(3, 2) * R2
    )
    return _fig3_stated(lambda: (combination, combination))(c)


def _fig3_cm_acceleration(c: Claim) -> str:
    return _fig3_stated(lambda: m1 * Fig3.r1 * Fig3.acc[0] + m2 * R2 * Fig3.acc[1])(c)


def _fig3_x(c: Claim) -> str:
    paper = by_name(c.paper, {"R_1": R2 / 2})
    exact = (Fig3.r1 * phi1, R2 * phi2, m1 * Fig3.r1 * Fig3.acc[0] + m2 * R2 * Fig3.acc[1])
    linear = (exact[0], exact[1], Fig3.linear(exact[2]))
    return verdict(paper, exact, stated=(paper, linear))


def _fig3_torques(c: Claim) -> str:
    b1, b2 = Fig3.b()
    return verdict(c.paper, sp.true if sp.simplify(sp.Abs(b1) - sp.Abs(b2)) != 0 else sp.false)


def _fig3_angular_momentum(c: Claim) -> str:
    # L about a fixed point on the lower floor: sum (I_i phidot_i + m_i y_ci xdot_i), y_ci = R2
    lin = [Fig3.linear(a_) for a_ in Fig3.acc]
    rate = (m1 * Fig3.r1**2 + m1 * R2 * Fig3.r1) * lin[0] + (m2 * R2**2 / 2 + m2 * R2 * R2) * lin[1]
    return verdict(by_name(c.paper, {"R_1": R2 / 2}), sp.simplify(rate))


def _qq2(c: Claim) -> str:
    # c . phi = P_0 t + D_0 (c = (J1, J2), zero mode (1, 1)): phi_1 holds (P_0 t + D_0)/(J1 + J2)
    zero_part = (P0 * t + D0) / (Fig2.J1 + Fig2.J2)
    truth = Fig2.omega2 * zero_part
    return verdict(
        c.paper,
        truth,
        stated=(c.paper, truth.subs(P0, 0)),
        unstated=(c.paper, truth.subs({P0: 0, D0: 0})),
    )


def _phi_relation(c: Claim) -> str:
    truth = (P0 * t + D0 - Fig2.J1 * phi1) / Fig2.J2
    return verdict(
        c.paper,
        truth,
        stated=(c.paper, truth.subs(P0, 0)),
        unstated=(c.paper, truth.subs({P0: 0, D0: 0})),
    )


def _de(c: Claim) -> str:
    truth = (P0 * t + D0 - Fig2.J1 * phi1) / Fig2.J2
    under = truth.subs({P0: 0, D0: 0})  # released from rest, about X-hat: both stated
    return verdict(c.paper, truth, stated=(c.paper, under), unstated=(flip_first(c.paper), under))


def _app_a_ratio(c: Claim) -> str:
    truth = (P0 * t + D0 - Fig2.J2 * phi2) / (Fig2.J1 * phi2)
    under = truth.subs({P0: 0, D0: 0})
    return verdict(c.paper, truth, stated=(c.paper, under), unstated=(-c.paper, under))


def _oriented(truth: Callable[[], Any], *, rate: bool = False) -> Check:
    """Holds only with body 1's angle counted the other way (the paper's Sec. 5.3)."""

    def check(c: Claim) -> str:
        flipped = flip_first(c.paper)
        if rate:
            flipped = (-flipped[0], flipped[1])
        return verdict(c.paper, truth(), unstated=(flipped, truth()))

    return check


def _canonical_h(key: str = "fig2") -> tuple[sp.Expr, sp.Expr]:
    """(H, V) in q_i = sqrt(J_i/m_i) phi_i."""
    if key == "fig2":
        J, V_ = (Fig2.J1, Fig2.J2), Fig2.V
        qs = (q1, q2)
    else:
        J, V_ = (Fig3.J1, Fig3.J2), Fig3.linear_potential()  # type: ignore[attr-defined]
        qs = (q3, q4)
    to_q = {phi1: qs[0] * sp.sqrt(m1 / J[0]), phi2: qs[1] * sp.sqrt(m2 / J[1])}
    Vq = sp.expand(V_.subs(to_q))
    return p1**2 / (2 * m1) + p2**2 / (2 * m2) + Vq, Vq


def _fig3_quadratic() -> sp.Expr:
    b1, b2 = Fig3.b()
    return k / 2 * (b1 * phi1 + b2 * phi2) ** 2


Fig3.linear_potential = staticmethod(_fig3_quadratic)  # type: ignore[attr-defined]


def _potential_fig3(c: Claim) -> str:
    """App. C (k02): Fig. 3's exact potential in q_i = sqrt(J_i/m_i) phi_i, its quadratic form
    under the paper's small angles, and the first coordinate counted the other way."""
    to_q = {phi1: q3 * sp.sqrt(m1 / Fig3.J1), phi2: q4 * sp.sqrt(m2 / Fig3.J2)}
    exact = Fig3.V.subs(to_q)
    quadratic = _canonical_h("fig3")[1]
    return verdict(
        c.paper, exact, stated=(c.paper, quadratic), unstated=(flip_first(c.paper), quadratic)
    )


def _canonical_ratio(c: Claim) -> str:
    ratio = sp.sqrt(Fig2.J2 / m2) / sp.sqrt(Fig2.J1 / m1) * Fig2.ratio  # q_2/q_1 in the mode
    truth = (m2 * ratio / m1 * pd1, ratio * q1)
    return verdict(c.paper, truth, stated=(c.paper, truth), unstated=(flip_first(c.paper), truth))


def _in_mode_acc(index: int) -> sp.Expr:
    return -Fig2.omega2 * (phi1, phi2)[index]


def _parts_subs(c: Claim) -> Any:
    return by_name(c.paper, dict(zip(("k_1", "k_2"), Fig2.parts(), strict=True)))


def _friction_in_mode(index: int) -> sp.Expr:
    """The hand friction on body ``index`` in the mode, in its own angle."""
    f_ = Fig2.friction[index]
    if index == 0:
        return sp.simplify(Fig2.in_mode(f_))
    return sp.simplify(by_name(f_, {"phi_1": phi2 / Fig2.ratio}))


def _friction_torque(index: int) -> Check:
    def check(c: Claim) -> str:
        name = ("f_1", "f_2")[index]
        paper = by_name(c.paper, {name: _friction_in_mode(index)})
        return verdict(paper, (_in_mode_acc(index),) * 2)

    return check


def _fig5_labels(c: Claim) -> str:
    hoop = _pulled(m * R**2)[0].subs(m, m1)
    cylinder = _pulled(m * R**2 / 2)[0].subs(m, m2)
    return verdict(c.paper, (sp.simplify(hoop), sp.simplify(cylinder)))


def _reversal(c: Claim) -> str:
    hoop, cylinder = (sp.simplify(_pulled(inertia)[0]) for inertia in (m * R**2, m * R**2 / 2))
    zero = sp.solve(cylinder, y)[0]
    top = sp.sign(sp.simplify(cylinder.subs(y, 2 * R) / F))
    ys = np.linspace(0, 2, 41)
    hoop_values = [float((hoop / F).subs({y: v * R})) for v in ys]
    return verdict(c.paper, (zero, top, sp.true if min(hoop_values) >= 0 else sp.false))


def _isotonic(c: Claim) -> str:
    first, second = _isotonic_periods()
    depends = abs(first - second) > 1e-6 * first
    assert abs(first - np.pi) < 1e-6  # T = pi/omega at every amplitude
    return verdict(c.paper, sp.true if depends else sp.false)


def _oscillates(alpha: float, beta: float) -> bool:
    """Does q stay bounded and return through zero, for L = alpha qdot^2/2 - beta q^2/2 from
    q(0) = 1 at rest (solved numerically, no SymPy)?"""

    def rhs(_t: float, s: np.ndarray) -> list[float]:
        return [s[1], -beta / alpha * s[0]]

    sol = solve_ivp(rhs, (0, 20), [1.0, 0.0], rtol=1e-10, atol=1e-12, max_step=0.05)
    return bool(np.max(np.abs(sol.y[0])) < 1.5 and np.min(sol.y[0]) < -0.5)


def _quadratic_energy(c: Claim) -> str:
    # constant alpha, beta of either sign (beta < 0: an inverted pendulum's energy) against
    # alpha, beta > 0: only the latter all oscillate
    every_constant = all(_oscillates(a_, b_) for a_, b_ in ((1.0, 2.0), (0.5, 3.0), (1.0, -2.0)))
    same_sign = all(_oscillates(a_, b_) for a_, b_ in ((1.0, 2.0), (0.5, 3.0), (2.0, 0.1)))
    return verdict(
        c.paper,
        sp.true if every_constant else sp.false,
        unstated=(c.paper, sp.true if same_sign else sp.false),
    )


def _friction_sum_without_zeros() -> Any:
    """Sec. 4: does a stationary centre of mass need f_1 = f_2 = 0? A hoop of radius
    r_1 = 3R_2/4 beside the cylinder on one floor, the spring horizontal at the height h = r_1
    on both (the hoop's centre): Newton m a = F + f and I' phiddot = F h about the contact line,
    to first order (a point at height h moves by h phi)."""
    r1, h = sp.Rational(3, 4) * R2, sp.Rational(3, 4) * R2
    J1_, J2_ = 2 * m1 * r1**2, sp.Rational(3, 2) * m2 * R2**2
    pull = k * (h * phi2 - h * phi1)  # the spring on the hoop, along x
    acc = (pull * h / J1_, -pull * h / J2_)
    friction = (m1 * r1 * acc[0] - pull, m2 * R2 * acc[1] + pull)
    cancel = sp.simplify(sum(friction)) == 0  # (m_1 + m_2) Xddot = f_1 + f_2 = 0
    # two hoops at their centres, the paper's own Sec. 3: the same
    hoops = [(2 * mm * R**2) for mm in (m1, m2)]
    force = k * (R * phi2 - R * phi1)
    hoop_friction = (m1 * R * force * R / hoops[0] - force, -m2 * R * force * R / hoops[1] + force)
    hoops_cancel = sp.simplify(sum(hoop_friction)) == 0
    needed = not (
        (cancel and sp.simplify(friction[0]) != 0)
        or (hoops_cancel and sp.simplify(hoop_friction[0]) != 0)
    )
    return sp.true if needed else sp.false


def _fig2_vertical_pull() -> Any:
    """The spring between the centres (R phi_1, R) and (l + R phi_2, R), l its rest length: the
    vertical component of its pull on each body."""
    d = (L + R * phi2 - R * phi1, R - R)
    length = sp.sqrt(d[0] ** 2 + d[1] ** 2)
    pull = k * (length - L) / length
    return (sp.simplify(pull * d[1]), sp.simplify(-pull * d[1]))


def _contact_axis() -> Any:
    """About the contact line the spring's torque R F alone gives I' phiddot: Newton about the
    centre, I phiddot = -f R and m R phiddot = F + f, gives (I + m R^2) phiddot = R F."""
    out = []
    for index, inertia, mass in ((0, Fig2.I1, m1), (1, Fig2.I2, m2)):
        force = Fig2.spring[index]
        f_, acc = sp.symbols("f acc", real=True)
        solved = sp.solve([inertia * acc + f_ * R, mass * R * acc - force - f_], [f_, acc])
        out.append(sp.simplify((inertia + mass * R**2) * solved[acc] - R * force))
    return tuple(out)


def _undeformed() -> sp.Expr:
    tau = sp.Symbol("tau", real=True)
    # phi = (1, ratio) cos(tau): the speeds are largest at sin(tau) = 1
    return R * (Fig2.ratio - 1) * sp.cos(tau).subs(tau, sp.pi / 2)


def _shorter_stiffer() -> Any:
    w = [sp.simplify(x.subs(m2, m1)) for x in Fig2.weights]
    parts = [sp.simplify(x.subs(m2, m1)) for x in Fig2.parts()]
    lengths = (w[1] * ell, w[0] * ell)
    return (
        sp.simplify(parts[0] * lengths[0] / (k * ell)),
        sp.simplify(parts[1] * lengths[1] / (k * ell)),
        sp.true if sp.simplify(parts[0] - parts[1]).is_positive else sp.false,
    )


def _cm_moves() -> Any:
    velocity = m1 * R * 1 + m2 * R * Fig2.ratio  # in the mode, per phidot_1
    return sp.true if sp.simplify(velocity) != 0 else sp.false


def _friction_cause() -> Any:
    acc_sum = m1 * R * Fig2.acc[0] + m2 * R * Fig2.acc[1]
    in_mode = sp.simplify(Fig2.in_mode(sum(Fig2.friction)))
    return (sp.simplify(acc_sum - sum(Fig2.friction)), sp.true if in_mode != 0 else sp.false)


def _k_equal() -> Any:
    k_1, k_2 = Fig2.parts()
    a_1, a_2 = Fig2.amplitudes()
    return (
        sp.solve(sp.Eq(k_1, k_2), m1)[0] / m2,
        sp.solve(sp.Eq(a_1, a_2), m1)[0] / m2,
    )


def _sum_rule_consequently(c: Claim) -> str:
    roots = [r for r in _consequently_roots() if r != 0]
    clamped = (k1 + k2) / (2 * m1) + 2 * k2 / (3 * m2)
    assert same(sum(roots), clamped)  # only the trace identity
    return verdict(c.paper, tuple(sorted(roots, key=sp.default_sort_key)))


def _clamped_is_coupled(c: Claim) -> str:
    clamped = [k * R**2 / Fig2.J1, k * R**2 / Fig2.J2]
    among = any(same(x, w) for x in clamped for w in (0, Fig2.omega2))
    return verdict(c.paper, sp.true if among else sp.false)


def _hamilton_to_ep() -> Any:
    H_, _ = _canonical_h()
    return (sp.diff(H_, p1), Fig2.omega2)


def _subsystem(index: int) -> Any:
    J = (Fig2.J1, Fig2.J2)[index]
    root = sp.sqrt(k * R**2 / J)
    return (J, k * R**2, root, root, root)


def _subsystem_energy(index: int) -> Any:
    held = {phi2: 0, phid2: 0} if index == 0 else {phi1: 0, phid1: 0}
    return sp.expand((Fig2.T + Fig2.V).subs(held))


def _fig3_clamped(roots: bool) -> Any:
    b1, b2 = Fig3.b()
    values = (k * b1**2 / Fig3.J1, k * b2**2 / Fig3.J2)
    return tuple(sp.sqrt(v) for v in values) if roots else values


def _fig3_omega2() -> Any:
    b1, b2 = Fig3.b()
    w = k * (b1**2 / Fig3.J1 + b2**2 / Fig3.J2)  # the non-zero root for a rank-one K
    return (sp.simplify(w), sp.simplify(w - sum(_fig3_clamped(False))))


def _relative_rates(c: Claim) -> str:
    # X-hat = (J1 x1 + J2 x2)/(J1 + J2) with x_i = R phi_i; J1 phidot_1 + J2 phidot_2 = P_0
    xhat_rate = R * P0 / (Fig2.J1 + Fig2.J2)
    truth = (R * phid1 - xhat_rate, R * phid2 - xhat_rate)
    return verdict(c.paper, truth, stated=(c.paper, (R * phid1, R * phid2)))


def _methods() -> Any:
    return (Fig2.omega2,) * 4


def _omega_symbol(c: Claim) -> Any:
    return by_name(c.paper, {"Omega": sp.sqrt(Fig2.omega2)})


#: key -> the verdict the hand computation gives (the claim is passed in for its transcription).
INDEPENDENT: dict[str, Check] = {
    "abstract.cm-moves": _plain(_cm_moves),
    "abstract.friction-cause": _plain(_friction_cause),
    "abstract.same-inertia": _same_inertia,
    "abstract.fig3": _fig3_at_rest,
    "abstract.methods": _plain(_methods),
    "sec1.cm-theorem": _plain(lambda: sp.simplify(sum(Fig1.forces) / (m1 + m2))),
    "sec2.fig1-caption": _plain(lambda: (sum(Fig1.friction), sum(Fig1.normal_minus_weight))),
    "sec2.fig1-cm-at-rest-text": _fig1_at_rest,
    "sec2.fig1-equal-forces": _magnitudes(lambda: Fig1.forces[1] / Fig1.forces[0]),
    "sec2.fig1-equations": _plain(lambda: Fig1.forces),
    "sec2.fig1-potential": _plain(lambda: Fig1.U),
    "sec2.fig1-forces-from-u": _plain(lambda: Fig1.forces),
    "sec2.fig1-momentum-sum": _plain(lambda: (sum(Fig1.forces), sum(Fig1.forces))),
    "sec2.fig1-cm-at-rest": _fig1_at_rest,
    "sec2.fig1-vertical": _plain(lambda: Fig1.normal_minus_weight),
    "sec3.fig2-horizontal": _plain(_fig2_vertical_pull),
    "sec3.fig2-dof": _plain(lambda: 2),
    "sec3.fig2-constraints": _plain(lambda: (R * phi1, R * phi2)),
    "sec3.contact-axis": _plain(_contact_axis),
    "sec3.fig2-rotation": _plain(lambda: Fig2.acc),
    "sec3.fig2-spring-force": _plain(lambda: (Fig2.spring[0], sp.Abs(Fig2.spring[1]))),
    "sec3.steiner": _plain(lambda: (Fig2.J1, Fig2.J1, Fig2.J2, Fig2.J2)),
    "sec3.fig2-equations": _plain(lambda: Fig2.acc),
    "sec3.fig2-sum": _plain(lambda: sp.simplify(Fig2.J1 * Fig2.acc[0] + Fig2.J2 * Fig2.acc[1])),
    "sec3.angular-momentum": _radii_momentum,
    "sec3.phase-opposition": _plain(lambda: sp.sign(Fig2.ratio)),
    "sec3.w-relation": lambda c: verdict(c.paper, (P0 / R, P0 / R), stated=(c.paper, (0, 0))),
    "sec3.cm-moves": _plain(_cm_moves),
    "sec3.stationary-point": _radii_stationary,
    "sec3.different-inertia": _same_inertia,
    "sec3.same-spring-forces": _magnitudes(
        lambda: (Fig2.spring[1] / Fig2.spring[0], sp.simplify(Fig2.Q[1] / Fig2.Q[0]))
    ),
    "sec3.friction-ratio": _magnitudes(_friction_ratio),
    "sec3.two-hoops": _plain(lambda: (m1 / (m1 + m2), m2 / (m1 + m2))),
    "sec3.two-cylinders": _plain(lambda: (m1 / (m1 + m2), m2 / (m1 + m2))),
    "sec3.steady-cm": _fig3_at_rest,
    "sec3.fig2-caption": _plain(
        lambda: sp.true if Fig2.in_mode(Fig2.friction[0]) != 0 else sp.false
    ),
    "sec4.friction-must-vanish": _plain(_friction_sum_without_zeros),
    "sec4.fric": lambda c: verdict(
        c.paper,
        (
            _pulled(I_)[0],
            sp.diff(_pulled(I_)[0], y, 2),
            sp.sign(sp.simplify(-sp.diff(_pulled(I_)[0], y) / F)),
        ),
    ),
    "sec4.zero-friction-heights": _plain(
        lambda: tuple(sp.solve(_pulled(i)[0], y)[0] for i in (m * R**2, m * R**2 / 2))
    ),
    "sec4.fric-coupled": _fric_coupled,
    "sec4.fig3-no-friction": _fig3_no_friction,
    "sec4.fig3-geometry": _geometry,
    "sec4.spring-horizontal": _spring_horizontal,
    "sec4.small-angles-why": _spring_horizontal,
    "sec4.fig3-caption": _fig3_no_friction,
    "sec4.fig3-equations": _fig3_equations,
    "sec4.fig3-spring-force": _fig3_force,
    "sec4.fig3-forces": _fig3_forces,
    "sec4.fig3-sum": _fig3_sums,
    "sec4.fig3-cm-acceleration": _fig3_cm_acceleration,
    "sec4.fig3-cm-acceleration-x": _fig3_x,
    "sec4.fig3-cm-at-rest": _fig3_at_rest,
    "sec4.fig3-cm-stationary-again": _fig3_at_rest,
    "sec4.fig3-equal-spring-forces": _plain(lambda: sp.Abs(sp.simplify(-Fig3.pull / Fig3.pull))),
    "sec4.fig3-torques-differ": _fig3_torques,
    "sec4.fig3-angular-momentum": _fig3_angular_momentum,
    "sec5.qq2": _qq2,
    "sec5.1.phi-relation": _phi_relation,
    "sec5.1.phi-substituted": _plain(lambda: Fig2.in_mode(Fig2.Q[0])),
    "sec5.1.qq1": _plain(lambda: Fig2.omega2),
    "sec5.1.omega2-fig2": _plain(lambda: Fig2.omega2),
    "sec5.1.omega2-terms": _plain(lambda: (k * R**2 / Fig2.J1, k * R**2 / Fig2.J2)),
    "sec5.2.speeds-kinematics": lambda c: verdict(_omega_symbol(c), (sp.sqrt(Fig2.omega2),) * 2),
    "sec5.2.amplitude-sum": _plain(lambda: sum(Fig2.amplitudes())),
    "sec5.2.omega-from-sum": lambda c: verdict(
        _omega_symbol(c),
        (
            sp.sqrt(Fig2.omega2) * sum(Fig2.amplitudes()),
            sp.sqrt(Fig2.omega2) * sum(Fig2.amplitudes()) / A,
        ),
    ),
    "sec5.2.relative-coordinates": _relative_rates,
    "sec5.2.energy": _plain(
        lambda: sum(
            J * (sp.sqrt(Fig2.omega2) * amp / R) ** 2 / 2
            for J, amp in zip((Fig2.J1, Fig2.J2), Fig2.amplitudes(), strict=True)
        )
    ),
    "sec5.2.nu": _magnitudes(lambda: Fig2.ratio * Phid1),
    "sec5.2.undeformed-at-top-speed": _plain(_undeformed),
    "sec5.2.kinetic-rotational": _plain(lambda: Fig2.T),
    "sec5.2.orbital-spin": _plain(lambda: (m2 * R**2, Fig2.I2)),
    "sec5.2.phidot-relation": _magnitudes(lambda: Fig2.ratio * Phid1),
    "sec5.2.speeds-from-rates": _plain(lambda: (R, R)),
    "sec5.2.speeds": _plain(lambda: tuple(sp.sqrt(Fig2.omega2) * a_ for a_ in Fig2.amplitudes())),
    "sec5.2.omega-from-speeds": _plain(lambda: (sp.sqrt(Fig2.omega2),) * 4),
    "sec5.2.omega-identical": _plain(lambda: Fig2.omega2),
    "sec5.2.isochronism": _plain(
        lambda: (
            sp.true if sp.diff(Fig2.amplitudes()[0], A) != 0 else sp.false,
            sp.diff(sp.sqrt(Fig2.omega2), A),
        )
    ),
    "sec5.2.isochronism-unique": _isotonic,
    "sec5.2.amplitudes": _plain(Fig2.amplitudes),
    "sec5.2.amplitudes-equal-masses": _plain(
        lambda: tuple(a_.subs(m2, m1) for a_ in Fig2.amplitudes())
    ),
    "sec5.2.cm-not-stationary-equal-masses": _plain(
        lambda: (
            sp.true
            if sp.simplify((Fig2.amplitudes()[0] - Fig2.amplitudes()[1]).subs(m2, m1)) != 0
            else sp.false
        )
    ),
    "sec5.3.lagrangian": _oriented(lambda: sp.expand(Fig2.T - Fig2.V)),
    "sec5.3.spring-part-equations": lambda c: verdict(
        _parts_subs(c), (_in_mode_acc(0), _in_mode_acc(1))
    ),
    "sec5.3.spring-parts": _plain(lambda: 1 / Fig2.parts()[0] + 1 / Fig2.parts()[1]),
    "sec5.3.lagrange-equations": _oriented(lambda: Fig2.Q, rate=True),
    "sec5.3.ga": _oriented(lambda: Fig2.acc[1] / Fig2.acc[0] * phidd1),
    "sec5.3.de": _de,
    "sec5.3.ep0": _plain(lambda: -Fig2.omega2 * Fig2.J1 * phi1),
    "sec5.3.ep": _plain(lambda: Fig2.omega2),
    "sec5.3.ep-identical": _plain(lambda: Fig2.omega2),
    "sec5.3.pe": _plain(lambda: -Fig2.omega2 * Fig2.J2 * phi2),
    "sec5.3.phi1-from-de": _app_a_ratio,
    "sec5.3.k1-k2": _plain(Fig2.parts),
    "sec5.3.part-satisfied": _plain(lambda: 1 / k),
    "sec5.3.k-equal": _plain(_k_equal),
    "sec5.3.k-equal-masses": _plain(lambda: tuple(x.subs(m2, m1) for x in Fig2.parts())),
    "sec5.3.xhat-three-sevenths": _plain(lambda: Fig2.weights[1].subs(m2, m1) * ell),
    "sec5.3.right-part": _plain(lambda: ell - Fig2.weights[1].subs(m2, m1) * ell),
    "sec5.3.shorter-stiffer": _plain(_shorter_stiffer),
    "sec5.4.normal-oscillation": _plain(lambda: sp.true if Fig2.ratio.is_real else sp.false),
    "sec5.4.sum-rule-consequently": _sum_rule_consequently,
    "sec5.4.clamped-is-coupled": _clamped_is_coupled,
    "sec5.4.quadratic-energy": _quadratic_energy,
    "sec5.4.sum-rule": _plain(lambda: Fig2.omega2 - k * R**2 / Fig2.J1 - k * R**2 / Fig2.J2),
    "sec5.5.frequencies-detect-errors": _plain(
        lambda: Fig2.omega2 - k * R**2 / Fig2.J1 - k * R**2 / Fig2.J2
    ),
    "sec5.6.lagrangian-hamilton": _oriented(lambda: sp.expand(Fig2.T - Fig2.V)),
    "sec5.6.hamiltonian": _oriented(lambda: _canonical_h()[0]),
    "sec5.6.canonical-coordinates": _plain(
        lambda: (sp.sqrt(Fig2.J1 / m1) * phi1, sp.sqrt(Fig2.J2 / m2) * phi2)
    ),
    "sec5.6.hamilton-equations": _oriented(
        lambda: tuple(sp.expand(sp.diff(_canonical_h()[0], q)) for q in (q1, q2)), rate=True
    ),
    "sec5.6.factor-two-over-root-three": _plain(lambda: sp.sqrt(2) / sp.sqrt(3) * sp.sqrt(2)),
    "sec5.6.canonical-ratio": _canonical_ratio,
    "sec5.6.hamilton-motion": _plain(lambda: m1 * Fig2.omega2 * q1),
    "sec5.6.hamilton-is-ep": _plain(_hamilton_to_ep),
    "sec5.6.qdot": _plain(lambda: tuple(sp.diff(_canonical_h()[0], p) for p in (p1, p2))),
    "sec5.6.point-masses-canonical": _plain(lambda: (x1, x2)),
    "sec7.cm-moves": _plain(_cm_moves),
    "sec7.friction-cause": _plain(_friction_cause),
    "sec7.same-inertia": _same_inertia,
    "sec7.fig3": _fig3_at_rest,
    "sec7.methods": _plain(_methods),
    "sec7.check": _plain(lambda: Fig2.omega2 - k * R**2 / Fig2.J1 - k * R**2 / Fig2.J2),
    "app-a.relative-coordinates": _relative_rates,
    "app-a.hoop-rotation": lambda c: verdict(_parts_subs(c), (_in_mode_acc(0),) * 2),
    "app-a.hoop-friction-torque": _friction_torque(0),
    "app-a.cylinder-rotation": lambda c: verdict(_parts_subs(c), (_in_mode_acc(1),) * 2),
    "app-a.cylinder-friction-torque": _friction_torque(1),
    "app-a.friction-hoop": lambda c: verdict(_parts_subs(c), (_friction_in_mode(0),) * 2),
    "app-a.friction-cylinder-k2": lambda c: verdict(_parts_subs(c), _friction_in_mode(1)),
    "app-a.friction-cylinder": _plain(lambda: _friction_in_mode(1)),
    "app-a.phi-ratio": _app_a_ratio,
    "app-a.friction-ratio": _magnitudes(_friction_ratio),
    "app-a.pull-equations": _plain(lambda: (_pulled(I_)[1], _pulled(I_)[0])),
    "app-a.pull-phiddot": lambda c: verdict(
        by_name(c.paper, {"f": _pulled(I_)[0]}), (R, _pulled(I_)[1], _pulled(I_)[1])
    ),
    "app-a.pull-eliminated": lambda c: verdict(by_name(c.paper, {"f": _pulled(I_)[0]}), 0),
    "app-a.fric": _plain(lambda: _pulled(I_)[0]),
    "app-a.fig5-labels": _fig5_labels,
    "app-a.friction-reversal": _reversal,
    "app-a.pull-at-floor": _plain(
        lambda: (_pulled(I_)[0].subs(y, 0), R * _pulled(I_)[1].subs(y, 0))
    ),
    # the contact point: the centre's R phidot plus the rim's -R phidot relative to the centre
    "app-a.friction-no-work": _plain(lambda: R * phid1 + (-R) * phid1),
    "app-a.fig5-cylinder": _plain(lambda: _pulled(m * R**2 / 2)[0].subs(y, 2 * R)),
    "app-b.energy-1": _plain(lambda: _subsystem_energy(0)),
    "app-b.subsystem-1": _plain(lambda: _subsystem(0)),
    "app-b.mass-m": _plain(lambda: m2),
    "app-b.energy-2": _plain(lambda: _subsystem_energy(1)),
    "app-b.subsystem-2": _plain(lambda: _subsystem(1)),
    "app-b.sum-rule": _plain(lambda: Fig2.omega2 - k * R**2 / Fig2.J1 - k * R**2 / Fig2.J2),
    "app-b.omega2-fig3": _plain(_fig3_omega2),
    "app-c.hamiltonian": _oriented(lambda: _canonical_h()[0]),
    "app-c.potential-coefficients": _plain(lambda: (1 / sp.sqrt(2), sp.sqrt(sp.Rational(2, 3)))),
    "app-c.potential-fig2": _oriented(lambda: _canonical_h()[1]),
    "app-c.omega1-omega2": _plain(
        lambda: (sp.sqrt(k * R**2 / Fig2.J1), sp.sqrt(k * R**2 / Fig2.J2))
    ),
    "app-c.potential-fig3": _potential_fig3,
    "app-c.omega3-omega4": _plain(lambda: _fig3_clamped(True)),
}


# -- the tests -----------------------------------------------------------------------------------


@pytest.fixture(scope="module")
def checks():
    return {c.claim.key: c for c in check_paper()}


def test_every_claim_has_an_independent_verdict(checks) -> None:
    assert set(checks) == set(INDEPENDENT), (
        set(checks) ^ set(INDEPENDENT),
        "every claim has an independent check, and only those",
    )
    assert len(checks) == len(paper_claims())  # keys are unique


@pytest.mark.parametrize("key", sorted(INDEPENDENT))
def test_verdict_agrees_with_the_hand_computation(checks, key: str) -> None:
    check = checks[key]
    expected = INDEPENDENT[key](check.claim)
    assert check.verdict == expected, (key, check.reason, check.correction)
    assert check.reason
    if check.verdict in (VERIFIED, HOLDS_STATED):
        assert check.correction is None, key  # nothing to correct
    else:
        assert check.correction, key  # a corrected expression in LaTeX
    if check.verdict == HOLDS_STATED:
        assert check.reason.startswith("holds under the paper's stated assumption: ")
        assert check.claim.assumptions and check.assumption
    if check.verdict == HOLDS_ONLY_IF:
        assert check.reason.startswith("holds only if ")
    if check.verdict == VERIFIED:
        assert check.assumption is None


def test_the_false_alarms_of_the_review_are_stated_assumptions(checks) -> None:
    # issue 13: released from rest and "maximal" (magnitudes) are the paper's own words
    for key in (
        "sec2.fig1-cm-at-rest",
        "sec2.fig1-cm-at-rest-text",
        "sec3.angular-momentum",
        "sec3.w-relation",
        "sec3.stationary-point",
        "sec4.fig3-cm-at-rest",
        "sec5.2.nu",
        "sec5.2.phidot-relation",
        "sec3.friction-ratio",
        "app-a.friction-ratio",
        "sec4.fig3-geometry",
        "sec4.fig3-no-friction",
    ):
        assert checks[key].verdict == HOLDS_STATED, key
    # the correction for (nu) was negative: with magnitudes there is none
    assert checks["sec5.2.nu"].correction is None
    assert "maximal" in checks["sec5.2.nu"].assumption


def test_corrections_are_in_the_papers_own_terms(checks) -> None:
    m1_, m2_ = sp.symbols("m_1 m_2", positive=True)
    phi1_ = sp.Symbol("phi_1", real=True)
    # (de): with the origin at X-hat and a start from rest (both stated) only the sign remains
    assert checks["sec5.3.de"].correction == r"\phi_2 = - \frac{4 m_{1} \phi_{1}}{3 m_{2}}"
    general = by_name(checks["sec5.3.de"].derived, {"P_0": 0, "D_0": 0})
    assert sp.simplify(general + 4 * m1_ * phi1_ / (3 * m2_)) == 0
    # App. A: f2 = (k2/3) R phi2
    assert checks["app-a.friction-cylinder-k2"].correction.startswith(r"f_2=\frac{k_2}{3}R\phi_2=")
    # Fig. 3: the total angular momentum is conserved
    assert checks["sec4.fig3-angular-momentum"].correction == r"\dot L_O=0"
    # (QQ2): about the equilibrium value, the paper's q itself does not oscillate about zero
    assert "q_e" in checks["sec5.qq2"].correction and "P_0" not in checks["sec5.qq2"].correction


def test_the_subsystem_frequencies_are_named_clamped(checks) -> None:
    assert "clamped" in checks["sec5.1.omega2-terms"].reason
    assert checks["sec5.4.clamped-is-coupled"].verdict == WRONG
    assert "partial" in checks["sec5.4.clamped-is-coupled"].reason
    consequently = checks["sec5.4.sum-rule-consequently"]
    assert consequently.verdict == WRONG and consequently.reason.startswith("does not follow")
    assert "rank one" in consequently.reason
    assert "any coupled system" not in " ".join(c.claim.latex for c in checks.values())


def _quote_record() -> dict[str, Any]:
    """What the quote tests verify against the paper, as recorded in
    ``tests/data/paper-quotes.json``: each claim's location, quote and stated assumptions."""
    claims = {}
    for claim in paper_claims():
        claims[claim.key] = {
            "location": claim.location,
            "quote": quote_key(claim.quote),
            "assumptions": [[a.location, quote_key(a.quote)] for a in claim.assumptions],
        }
    return claims


def _verify_quotes_in(source: str) -> None:
    """Every claim's quote (and each stated assumption's) occurs verbatim in the part of the
    paper its location names (the sentence, when it names one); every labelled equation the
    location names is in that part; every labelled equation of the paper is some claim's."""
    spans = _spans(source)
    assert {
        "Abstract",
        "Sec. 1",
        "Sec. 5.6",
        "Sec. 7",
        "App. A",
        "App. C",
        "Fig. 5 caption",
    } <= set(spans)
    for claim in paper_claims():
        assert claim.quote.strip(), claim.key
        part = _PART.match(claim.location)
        assert part, (claim.key, claim.location)
        span = spans[part.group(1)]
        assert quote_key(claim.quote) in quote_key(span), (claim.key, claim.location)
        for label in re.findall(r"\(([A-Za-z0-9]+)\)", claim.location):
            assert f"\\label{{{label}}}" in span, (claim.key, label)  # the equation is there
        sentence = re.search(r"sentence (\d)", claim.location)
        if sentence:
            text = re.sub(r"\\(begin|end)\{[a-z]+\}|\\section\*?\{[^}]*\}", " ", span)
            sentences = re.split(r"(?<=\.)\s+(?=[A-Z])", text.strip())
            assert quote_key(claim.quote) in quote_key(sentences[int(sentence.group(1)) - 1]), (
                claim.key
            )
        for assumption in claim.assumptions:
            where = spans[assumption.location]
            assert quote_key(assumption.quote) in quote_key(where), (claim.key, assumption)
    labels = set(re.findall(r"\\label\{([^}]*)\}", source))
    equations = labels - {"absence", "external", "stationary", "solutions", "teaching"}
    equations -= {f"s{i}" for i in range(1, 6)} | {f"fig{i}" for i in range(1, 6)}
    equations -= {f"sec:appendix{i}" for i in range(1, 4)}
    cited = set()
    for claim in paper_claims():
        cited |= set(re.findall(r"\(([A-Za-z0-9]+)\)", claim.location))
    assert equations <= cited, sorted(equations - cited)


QUOTE_RECORD = Path(__file__).parent / "data" / "paper-quotes.json"


def test_every_quote_is_the_papers_words_where_the_location_says() -> None:
    """Against the paper's source when it is here (``../shared/paper/`` or ``ROLLSPRING_PAPER``;
    the record must then be current: regenerate it with ``ROLLSPRING_WRITE_QUOTES=1``); else
    (a clean clone on CI) against the record of what was verified against that source, whose
    digest it carries: a quote or location changed since is not verified, and fails."""
    record = json.loads(QUOTE_RECORD.read_text(encoding="utf-8"))
    now = _quote_record()
    if PAPER is not None and PAPER.is_file():
        source = PAPER.read_text(encoding="utf-8")
        _verify_quotes_in(source)
        digest = hashlib.sha256(source.encode("utf-8")).hexdigest()
        if os.environ.get("ROLLSPRING_WRITE_QUOTES"):
            record = {"paper_sha256": digest, "claims": now, "sections": _sections(source)}
            QUOTE_RECORD.write_text(
                json.dumps(record, indent=1, sort_keys=True) + "\n", encoding="utf-8"
            )
        assert record["paper_sha256"] == digest, "the record was verified against another source"
    assert len(record["paper_sha256"]) == 64
    assert record["claims"] == now, (
        "claims changed since their quotes were verified against the paper: rerun this test "
        "with the paper's source present and ROLLSPRING_WRITE_QUOTES=1"
    )


def _sections(source: str) -> list[str]:
    """The paper's parts as it numbers them ('Abstract', 'Sec. 1', ..., 'Sec. 5.6', 'App. C')."""
    return sorted(name for name in _spans(source) if not name.startswith("Fig."))


def printed_sections() -> set[str]:
    """The numbers the paper prints for its parts ('1', ..., '5.6', 'A', 'B', 'C'), from the
    record that :func:`test_every_section_the_check_cites_is_one_the_paper_prints` checks against
    the paper's LaTeX when the source is here."""
    record = json.loads(QUOTE_RECORD.read_text(encoding="utf-8"))
    return {name.split(" ", 1)[1] for name in record["sections"] if name != "Abstract"}


#: A section or appendix cited in words: "Sec. 5.2", "App. A".
_CITED = re.compile(r"\b(Sec\. \d+(?:\.\d+)?|App\. [A-Z])\b")


def test_every_section_the_check_cites_is_one_the_paper_prints() -> None:
    """Locations, reasons, corrections, stated assumptions and counterexamples cite the paper's
    sections by the numbers it prints (the record's sectioning is the paper's, read from its
    LaTeX when the source is here)."""
    record = json.loads(QUOTE_RECORD.read_text(encoding="utf-8"))
    if PAPER is not None and PAPER.is_file():
        assert record["sections"] == _sections(PAPER.read_text(encoding="utf-8"))
    printed = set(record["sections"])
    assert {"Sec. 4", "Sec. 5.6", "App. C"} <= printed and "Sec. 4.5" not in printed
    for check in check_paper():
        text = json.dumps(check.to_dict(), ensure_ascii=False)
        text += " ".join(a.location for a in check.claim.assumptions)
        cited = set(_CITED.findall(text))
        assert cited <= printed, (check.claim.key, sorted(cited - printed))


def test_the_verdict_is_computed_not_typed_in() -> None:
    k_, m1_ = sp.symbols("k m_1", positive=True)
    c_ = sp.Symbol("c", positive=True)
    stated = Assumption("c is 1", "c = 1", "Sec. 9")

    def claim(paper, derived: Derived, *assumptions: Assumption) -> Claim:
        return Claim(
            "test",
            "nowhere",
            "a test claim",
            "x",
            "x",
            paper,
            "fig2",
            lambda bench: derived,
            "quote",
            assumptions,
        )

    right = Derived(k_ / (2 * m1_), "by hand")
    assert check_claim(claim(k_ / (2 * m1_), right)).verdict == VERIFIED
    assert check_claim(claim(k_ / m1_, right)).verdict == WRONG
    assert check_claim(claim(k_ / m1_, right)).correction == r"x = \frac{k}{2 m_{1}}"
    conditional = Derived(c_ * k_ / m1_, "by hand", condition="c = 1", value_if=k_ / m1_)
    assert check_claim(claim(k_ / m1_, conditional)).verdict == HOLDS_ONLY_IF
    assert check_claim(claim(2 * k_ / m1_, conditional)).verdict == WRONG
    # an assumption the paper states: the same comparison, a different verdict, no correction
    assumed = Derived(c_ * k_ / m1_, "by hand", assumed=k_ / m1_)
    result = check_claim(claim(k_ / m1_, assumed, stated))
    assert (result.verdict, result.correction) == (HOLDS_STATED, None)
    assert result.assumption == 'c is 1 (Sec. 9: "c = 1")'
    assert check_claim(claim(2 * k_ / m1_, assumed, stated)).correction == r"x = \frac{k}{m_{1}}"
    with pytest.raises(RuntimeError):  # a stated assumption needs the value under it
        check_claim(claim(k_ / m1_, conditional, stated))
    # sequences compare entry by entry
    pair = Derived((k_, m1_), "by hand")
    assert check_claim(claim((k_, m1_), pair)).verdict == VERIFIED
    assert check_claim(claim((m1_, k_), pair)).verdict == WRONG
    # an identity that needs simplification (radicals) is still recognised
    root = Derived(sp.sqrt(k_ / (2 * m1_)), "by hand")
    assert check_claim(claim(sp.sqrt(k_) / sp.sqrt(2 * m1_), root)).verdict == VERIFIED
    # truth values compare as such
    assert check_claim(claim(sp.true, Derived(sp.false, "by hand"))).verdict == WRONG


def test_every_claim_compares_in_known_symbols() -> None:
    # a paper expression in symbols the engine does not use would never verify by accident
    known = {
        *("m", "m_1", "m_2", "R", "R_1", "R_2", "k", "k_1", "k_2", "gamma", "y", "F", "I"),
        *("f", "f_1", "f_2", "phi", "phi_1", "phi_2", "phidot_1", "phidot_2", "phiddot"),
        *("phiddot_1", "phiddot_2", "x_1", "x_2", "A", "Omega", "Phidot_1", "q_1", "q_2"),
        *("q_3", "q_4", "p_1", "p_2", "pdot_1", "F_1x", "F_2x", "l"),
    }
    for claim in paper_claims():
        values = claim.paper if isinstance(claim.paper, tuple) else (claim.paper,)
        names = {s.name for v in values for s in sp.sympify(v).free_symbols}
        assert names <= known, (claim.key, names - known)


runner = CliRunner()


#: The fields of a claim's record (``paper-check --json``, the web's and the report's claims).
CLAIM_KEYS = {
    "key",
    "location",
    "claim",
    "quote",
    "verdict",
    "assumption",
    "correction",
    "reason",
    "counterexample",
}


def test_cli_json_is_a_list_of_the_documented_records(checks) -> None:
    result = runner.invoke(app, ["paper-check", "--json"])
    assert result.exit_code == 0, result.output
    data = json.loads(result.stdout)
    assert isinstance(data, list) and len(data) == len(INDEPENDENT)
    for record in data:
        assert set(record) == CLAIM_KEYS
        assert record["verdict"] in VERDICTS
        assert isinstance(record["claim"], str) and record["claim"]
        assert isinstance(record["quote"], str) and record["quote"]
        assert record["correction"] is None or isinstance(record["correction"], str)
        assert (record["correction"] is None) == (record["verdict"] in (VERIFIED, HOLDS_STATED))
        if record["verdict"] == VERIFIED:
            assert record["assumption"] is None
        if record["verdict"] == HOLDS_STATED:
            assert record["assumption"]
        assert isinstance(record["reason"], str) and record["reason"]
    by_quote = {(r["location"], r["quote"]): r["verdict"] for r in data}
    for check in checks.values():
        assert by_quote[(check.claim.location, check.claim.quote)] == check.verdict


def test_cli_text_table_marks_and_counts() -> None:
    result = runner.invoke(app, ["paper-check"])
    assert result.exit_code == 0, result.output
    counts = {v: sum(1 for c in check_paper() if c.verdict == v) for v in VERDICTS}
    for mark in "✔☑⚠✘":
        assert mark in result.stdout
    assert (
        f"{len(INDEPENDENT)} claims: {counts[VERIFIED]} verified, {counts[HOLDS_STATED]} hold "
        f"under an assumption the paper states, {counts[HOLDS_ONLY_IF]} hold only under a "
        f"condition the paper does not state, {counts[WRONG]} wrong"
    ) in " ".join(result.stdout.split())
    assert "R₁=R₂/2" in result.stdout  # the LaTeX shown as readable text


def test_cli_markdown_table() -> None:
    result = runner.invoke(app, ["paper-check", "--format", "markdown"])
    assert result.exit_code == 0, result.output
    rows = [
        line for line in result.stdout.splitlines() if line.startswith(("| ✔", "| ☑", "| ✘", "| ⚠"))
    ]
    assert len(rows) == len(INDEPENDENT)
    assert all(line.count(" | ") == 6 for line in rows)  # 7 cells, no stray pipes
    assert r"$\frac{f_1}{f_2}=\frac{3}{2}" in result.stdout
    assert "“different amounts of static friction forces (f₁/f₂=3/2)”" in result.stdout


def test_cli_unknown_format_is_one_line_and_exit_2() -> None:
    result = runner.invoke(app, ["paper-check", "--format", "html"])
    assert result.exit_code == 2
    assert result.stderr.strip() == (
        "error: --format: unknown format 'html' (formats: text, markdown)"
    )


def test_cli_verdict_colours_are_keyed_by_the_librarys_verdicts() -> None:
    # the CLI keys its colours by the words, so that importing it does not import SymPy
    assert list(cli_paper_check._STYLE) == [VERIFIED, HOLDS_STATED, HOLDS_ONLY_IF, WRONG]


def test_plain_text_keeps_a_backslash_that_starts_no_command() -> None:
    # a trailing backslash (or one before a newline) matches no command: kept, not a crash
    assert cli_paper_check.plain("x\\") == "x\\"
    assert cli_paper_check.plain(r"\frac{1}{2}") == "(1/2)"


def test_quotes_read_as_text() -> None:
    assert (
        cli_paper_check.quote_text(
            r"According to the equation (\ref{g}), as Fig.~\ref{fig2} shows $F_1=F_2$"
        )
        == "According to the equation (g), as Fig. 2 shows F₁=F₂"
    )


def test_the_readme_counts_are_the_checks() -> None:
    readme = (Path(__file__).resolve().parents[1] / "README.md").read_text(encoding="utf-8")
    section = " ".join(readme[readme.index("* **`paper-check`**") :].split("\n* ")[0].split())
    counts = {v: sum(1 for c in check_paper() if c.verdict == v) for v in VERDICTS}
    assert f"{len(INDEPENDENT)} claims" in section
    assert (
        f"{counts[VERIFIED]} verified, {counts[HOLDS_STATED]} hold under an assumption" in section
    )
    assert (
        f"{counts[HOLDS_ONLY_IF]} hold only under a condition the paper does not state" in section
    )
    assert f"{counts[WRONG]} wrong" in section


def test_the_second_review_findings(checks) -> None:
    # Sec. 4: "We need to ensure that there is no static friction force": sufficient, not
    # necessary (the frictions need only cancel: two hoops, or a hoop of radius 3R2/4)
    need = checks["sec4.friction-must-vanish"]
    assert need.verdict == WRONG and "sufficient, not necessary" in need.reason
    assert "3*R_2*k*(phi_1 - phi_2)/8" in need.reason  # f_1 = -F/2, F = k(3R2/4)(phi2 - phi1)
    # Sec. 5.4: a quadratic energy oscillates only for beta/alpha > 0
    energy_check = checks["sec5.4.quadratic-energy"]
    assert energy_check.verdict == HOLDS_ONLY_IF and "β/α > 0" in energy_check.reason
    # the sentences that assert them, not the one next to them
    assert checks["sec3.friction-ratio"].claim.location == "Sec. 3, paragraph after eq. (c)"
    assert checks["sec5.3.k-equal"].claim.location == "Sec. 5.3, second sentence after eq. (k2)"
    assert "not equal for the same masses" in checks["sec5.3.k-equal-masses"].claim.quote
    assert checks["sec3.contact-axis"].verdict == VERIFIED
    assert checks["sec5.5.frequencies-detect-errors"].verdict == VERIFIED


# -- the catalogue: code plus the paper's words (claims.toml), joined by key ----------------------


def test_every_claim_has_a_short_stable_key_and_the_json_carries_it(checks) -> None:
    keys = [claim.key for claim in paper_claims()]
    assert len(set(keys)) == len(keys) == len(INDEPENDENT)
    for key in keys:  # the section as the paper numbers it, then what the claim says
        assert re.fullmatch(r"(abstract|sec[1-7](\.[1-6])?|app-[abc])\.[a-z0-9]+(-[a-z0-9]+)*", key)
        assert len(key) <= 40, key
    section = {"abstract": "Abstract", "app-a": "App. A", "app-b": "App. B", "app-c": "App. C"}
    for claim in paper_claims():
        where = claim.key.rsplit(".", 1)[0]
        expected = section.get(where, f"Sec. {where[3:]}")
        assert claim.location.startswith((expected, "Fig.")), claim.key
    data = [check.to_dict() for check in check_paper()]
    assert [record["key"] for record in data] == keys
    assert all(next(iter(record)) == "key" for record in data)


def test_verdicts_are_an_enum_written_as_their_words() -> None:
    assert issubclass(Verdict, enum.StrEnum)
    assert (
        VERDICTS
        == tuple(Verdict)
        == ("verified", "holds-under-stated-assumption", "holds-only-if", "wrong")
    )
    assert all(isinstance(check.verdict, Verdict) for check in check_paper())
    assert json.dumps([Verdict.HOLDS_ONLY_IF]) == '["holds-only-if"]'


def test_the_catalogue_is_the_claims_file_a_table_per_claim_in_the_papers_order() -> None:
    words = tomllib.loads(
        (resources.files("rollspring.analysis.paper") / "claims.toml").read_text(encoding="utf-8")
    )
    assert words == claim_tables()
    assert list(words) == [claim.key for claim in paper_claims()]
    claims = {claim.key: claim for claim in paper_claims()}
    seen: set[str] = set()
    restated = 0
    for key, table in words.items():
        if "restates" not in table:  # a claim of its own: all (LaTeX: else the quote)
            words_and_code = {"location", "quote", "statement", "quantity", "paper", "system"}
            assert (
                words_and_code | {"recipe"}
                <= set(table)
                <= words_and_code
                | {
                    "recipe",
                    "latex",
                    "assumptions",
                    "counterexample",
                }
            ), key
            assert table.get("latex") != table["quote"], key
        else:  # a restatement gives only what differs from the claim it repeats, an earlier one
            restated += 1
            assert table["restates"] in seen, key
            original = words[table["restates"]]
            for name, value in table.items():
                assert name == "restates" or value != original.get(name), (key, name)
        seen.add(key)
    assert restated >= 20  # the abstract's claims again in Sec. 7, the equations again in App. A-C
    steiner = (2 * m1 * R**2, 2 * m1 * R**2, sp.Rational(3, 2) * m2 * R**2)
    assert claims["sec3.steiner"].paper == (*steiner, steiner[2])  # I'_i = I_i + m_i R^2


def test_the_papers_values_are_read_in_the_engines_symbols() -> None:
    from rollspring.analysis.paper.notation import Omega, q1
    from rollspring.analysis.paper.symbols import phi1

    assert paper_value("3*R**2*m_2/2") == sp.Rational(3, 2) * m2 * R**2
    assert paper_value(["True", "0"]) == (sp.true, sp.Integer(0))
    assert paper_value("Omega**2*phi_1 + q_1") == Omega**2 * phi1 + q1
    assert paper_value("m_1").assumptions0 == m1.assumptions0  # the symbol, not a new one
    for claim in paper_claims():  # every value printed and read again is the same expression
        values = claim.paper if isinstance(claim.paper, tuple) else (claim.paper,)
        for value in values:
            assert paper_value(sp.sstr(value, order=None)) == value, claim.key


def test_a_recipe_is_a_name_or_a_factory_call_with_literal_arguments() -> None:
    from rollspring.analysis.paper.recipes.sec3 import steiner

    assert recipe("steiner") is steiner
    assert callable(recipe("app_a_friction(1, middle=True)"))
    with pytest.raises(ValueError, match="no recipe of that name"):
        recipe("print")
    with pytest.raises(ValueError, match="no recipe of that name"):
        recipe("os.system('x')")
    with pytest.raises(ValueError, match="arguments must be literals"):
        recipe("app_a_friction(steiner)")


def test_a_restatement_takes_what_it_does_not_give_from_the_claim_it_repeats() -> None:
    claims = {claim.key: claim for claim in paper_claims()}
    again, first = claims["sec7.fig3"], claims["abstract.fig3"]
    assert (again.quantity, again.system, again.derive, again.assumptions, again.latex) == (
        first.quantity,
        first.system,
        first.derive,
        first.assumptions,
        first.latex,
    )
    assert again.location == "Sec. 7, sentence 3" and again.quote != first.quote
    assert claim_tables()["sec7.fig3"]["restates"] == "abstract.fig3"


# -- the counterexamples: the exact motion of the systems the verdicts name ------------------------

#: Wrong or holds-only-if verdicts with no system the engine can run, and why.
NO_SYSTEM = {
    "sec5.2.isochronism-unique": "the isotonic oscillator is a potential, not a rolling system "
    "(its periods are computed above)",
    "sec5.4.quadratic-energy": "beta < 0 needs a negative stiffness, which no system file takes",
    "app-a.fig5-labels": "a figure's labels",
    "app-b.mass-m": "a symbol's name",
}


@pytest.fixture(scope="module")
def runs(checks):
    from rollspring.service.paper_runs import run_counterexamples

    return run_counterexamples(list(checks.values()))


def test_every_wrong_or_unstated_verdict_has_a_counterexample_run(checks) -> None:
    without = {
        key
        for key, check in checks.items()
        if check.verdict in (WRONG, HOLDS_ONLY_IF) and check.claim.counterexample is None
    }
    assert without == set(NO_SYSTEM)


def test_every_counterexample_disagrees_with_the_papers_statement(checks, runs) -> None:
    assert set(runs) == {key for key, c in checks.items() if c.claim.counterexample is not None}
    for key, run in runs.items():
        cx = run.counterexample
        assert run.disagrees, (key, run.measured, cx.paper, cx.tolerance)
        assert abs(run.measured - cx.paper) > cx.tolerance
        assert checks[key].verdict != VERIFIED, key  # a verified claim needs no counterexample
        assert cx.words and run.details, key


def test_the_measures_agree_with_the_paper_where_it_is_right() -> None:
    """No false alarm: each measure, on a system where the paper's statement holds, finds it."""
    from rollspring.analysis.paper import Counterexample
    from rollspring.service.paper_runs import run_counterexample

    def measured(system: str, measure: str, **start: Any) -> float:
        return run_counterexample(Counterexample(system, measure, 0.0, 1.0, "-", **start)).measured

    # the paper's equal radii: X-hat of (c) and (rel1) stay put
    assert measured("fig2", "stationary_point_paper") < 1e-9
    assert measured("fig2", "contact_momentum") < 1e-9
    # two hoops joined at their centres (Sec. 3): the centre of mass stays
    assert measured("two-hoops", "cm_motion") < 1e-9
    # a spring level with the hoop's centre (y = R, not its percussion height 2R): first-order
    # frictions, as (fric) says
    assert abs(measured("zero-sum", "friction_order", start="mode", amplitude=0.02) - 1) < 0.05
    # the paper's Fig. 3: the static friction is third order, and the motion needs little
    assert abs(measured("fig3", "friction_order", start="mode", amplitude=0.02) - 3) < 0.1
    # the canonical ratio of Sec. 5.6 counted as the engine counts (both angles one way): the
    # paper's magnitude
    assert abs(abs(measured("fig2", "canonical_ratio")) - 2 / sp.sqrt(3) * 13 / 7) < 1e-3
    # App. A's f_2 with the cylinder's I_2 = m_2 R^2/2: (k_2/3) R phi_2
    assert abs(measured("fig2", "cylinder_friction_k2") - sp.Rational(2, 3)) < 1e-3


def test_the_fig3_pair_drifts_away_beyond_first_order(runs) -> None:
    """Sec. 4: the centre of mass of Fig. 3 is at rest only to first order. Beyond it the
    oscillation drives the linear zero mode (both spring ends moving alike), which is unstable:
    the pair's slow drift grows as exp(lambda t), lambda proportional to the amplitude; the
    motion needs a small mu_s at first (the friction is O(a^3)), then ever more."""
    from rollspring.analysis.paper import Counterexample
    from rollspring.service.paper_runs import drift_rate, run_counterexample

    long = runs["sec4.fig3-cm-at-rest"]
    short = run_counterexample(
        Counterexample("fig3", "cm_drift", 0.0, 1e-5, "-", start="mode", amplitude=0.05, periods=10)
    )
    assert long.measured > 1000 * short.measured > 0  # 60 periods against 10: not linear
    small = run_counterexample(
        Counterexample("fig3", "mu_needed", 0.0, 1e-6, "-", start="mode", amplitude=0.025)
    )
    big = runs["sec4.fig3-no-friction"]
    assert 6 < big.measured / small.measured < 10  # third order: 2^3
    rates = [
        drift_rate(
            Counterexample("fig3", "cm_drift", 0.0, 1.0, "-", start="mode", amplitude=a, periods=p)
        )
        for a, p in ((0.025, 200.0), (0.05, 100.0))
    ]
    assert rates[0] is not None and rates[1] is not None
    assert 1.8 < rates[1] / rates[0] < 2.4  # the growth rate proportional to the amplitude


def test_the_tilted_pair_keeps_no_first_order_friction_and_only_its_frequency_changes() -> None:
    """Sec. 4's "the spring must be horizontal": on one floor (the spring tilted by theta) the
    frictions are second order and Omega^2 is the level pair's times cos^2(theta)."""
    import rollspring
    from rollspring.analysis.paper import paper_system

    level = rollspring.analyze(paper_system("fig3")).oscillating[0].omega
    tilted = rollspring.analyze(paper_system("fig3-tilted")).oscillating[0].omega
    cos2 = 0.5**2 / (0.5**2 + 0.05**2)
    assert abs((tilted / level) ** 2 - cos2) < 1e-12

"""Recipe helpers shared by several sections: orientations, Fig. 3's geometry, split springs.

The paper counts body 1's angle the other way in Sec. 5.3 and App. A (:func:`flip_first`);
Fig. 3 sizes its bodies so that the spring is horizontal at rest (:func:`fig3_geometry`); the
spring cut at the stationary point X-hat gives two springs (:func:`split`).
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

import sympy as sp

from rollspring.analysis.paper.algebra import substitute, tidy
from rollspring.analysis.paper.bench import Bench
from rollspring.analysis.paper.notation import P0, p1, pd1, q1, q3
from rollspring.analysis.paper.symbols import phi1, phid1, phidd1, y
from rollspring.analysis.paper.types import Derived


def from_rest(value: Any, how: str, **more: Any) -> Derived:
    """What a recipe derives in general (``value``) and, under the paper's stated start from
    rest, with the conserved momentum P_0 = 0 (M14) (``assumed``); ``more`` as
    :class:`~rollspring.analysis.paper.types.Derived` takes it."""
    return Derived(value, how, assumed=substitute(value, {P0: 0}), **more)


def flip_first(expr: Any) -> Any:
    """The paper's expression read in the orientation of its Sec. 5.3, where body 1's angle is
    counted the other way (epsilon_1 = X-hat - x_1): phi_1 -> -phi_1 (and its rates)."""
    flip = {phi1: -phi1, phid1: -phid1, phidd1: -phidd1, q1: -q1, p1: -p1, pd1: -pd1, q3: -q3}
    if isinstance(expr, Sequence) and not isinstance(expr, str):
        return tuple(sp.sympify(e).xreplace(flip) for e in expr)
    return sp.sympify(expr).xreplace(flip)


def flip_first_rate(expr: Any) -> Any:
    """As :func:`flip_first` for a pair whose first entry is itself odd in phi_1 (an
    acceleration, a momentum rate of body 1)."""
    first, second = flip_first(expr)
    return (-first, second)


ORIENTATION = (
    "ε₁ and ε₂ are each body's outward displacement from its equilibrium position (ε₁ = x₁⁰ − "
    "x₁, leftward; ε₂ = x₂ − x₂⁰), so that ε₁ + ε₂ is the spring's deformation: the paper "
    "defines ε₁ = x₁ − X̂ (Sec. 5.2, App. A), with which the deformation is ε₂ − ε₁, and "
    "counting body 1 the other way from X̂ (ε₁ = X̂ − x₁) is not enough either: then ε₁ + ε₂ = "
    "x₂ − x₁ is the centres' separation, not the deformation; the paper refers the orientation "
    "to Fig. 2, whose drawing is not in the source, and its Sec. 5.1 counts both angles one way "
    "(φ₂ = −(4m₁/3m₂)φ₁)"
)


CANONICAL_ORIENTATION = (
    "the first canonical coordinate is counted the other way (q₁ with body 1 anticlockwise, as "
    "the Lagrangian (l) does); with both angles counted one way, as Sec. 5.1 counts them, the "
    "coefficients are (−Ω₁/√(k/m₁), +Ω₂/√(k/m₂)) = (−1/√2, +√(2/3))"
)


def fig3_geometry(b: Bench) -> dict[Any, Any]:
    """The paper's Fig. 3: the centres level (the hoop's track at h_1 = R_2 - R_1) and
    R_1 = R_2/2, so that the spring is horizontal at rest (the engine's symbols)."""
    names = {p_.name: p_ for p_ in b.sym("fig3").parameters}
    return {names["h_1"]: names["R_2"] / 2, names["R_1"]: names["R_2"] / 2}


def split(b: Bench, key: str = "fig2") -> list[sp.Expr]:
    """The stiffnesses of the two parts of the spring cut at the stationary point X-hat: the part
    between body i and X-hat has the length w_j l (j the other body, w the engine's X-hat
    weights), so k_i = k l / (w_j l) = k / w_j (a spring's stiffness is inversely proportional to
    its length)."""
    w = b.weights(key)
    spring_k = b.sym(key).springs[0].k
    return [tidy(spring_k / w[1]), tidy(spring_k / w[0])]


def mode_ratio(b: Bench, key: str = "fig2") -> sp.Expr:
    """phi_2/phi_1 in the oscillating mode (the engine's null vector of K - Omega^2 M)."""
    v = b.mode(key)
    result: sp.Expr = tidy(v[1] / v[0])
    return result


def pulled_friction(b: Bench, key: str) -> sp.Expr:
    """The paper's f (counted against F) of the pulled body ``key`` at phi = 0."""
    sym = b.sym(key)
    (f,) = sym.friction_configuration
    result: sp.Expr = tidy(-f.subs(sym.bodies[0].q, 0))
    return result


def zero_friction_height(b: Bench, key: str) -> sp.Expr:
    """y with f(y) = 0 for the pulled body ``key``: the engine's friction at phi = 0, solved."""
    (height,) = sp.solve(sp.Eq(pulled_friction(b, key), 0), y)
    result: sp.Expr = height
    return result


def clamped_sum(b: Bench, key: str) -> Any:
    """K_11/J_1 + K_22/J_2 + ...: the squared frequencies of each body alone, the others held
    (clamped, partial frequencies), summed; from the engine's M and K."""
    sym = b.sym(key)
    return sp.Add(*[sym.stiffness_matrix[i, i] / body.J for i, body in enumerate(sym.bodies)])

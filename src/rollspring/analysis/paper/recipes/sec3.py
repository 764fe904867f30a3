"""Recipes for Sec. 3: the hoop and the cylinder joined at their centres (Fig. 2).

From the engine's Fig. 2 system (and two hoops, two cylinders): constraints, the mass matrix
(Steiner), the accelerations, the conserved combination (zero mode of K), the mode shape, the
stationary point's weights and the linear static frictions in the mode.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from typing import Any

import sympy as sp

from rollspring.analysis.paper.algebra import same, tidy
from rollspring.analysis.paper.bench import Bench
from rollspring.analysis.paper.notation import P0
from rollspring.analysis.paper.recipes.common import mode_ratio
from rollspring.analysis.paper.symbols import R
from rollspring.analysis.paper.types import Derived


def _magnitudes(expr: Any) -> Any:
    if isinstance(expr, Sequence) and not isinstance(expr, str):
        return tuple(sp.Abs(e) for e in expr)
    return sp.Abs(expr)


def fig2_horizontal(b: Bench) -> Derived:
    return Derived(
        tuple(tidy(force[1]) for force in b.sym("fig2").body_forces),
        "the vertical components of the engine's spring forces on the two bodies (M7) at every "
        "configuration: the centres, both at height R, stay level",
    )


def fig2_dof(b: Bench) -> Derived:
    return Derived(
        sp.Integer(b.sym("fig2").n), "the engine's generalised coordinates of the rolling pair"
    )


def fig2_constraints(b: Bench) -> Derived:
    sym = b.sym("fig2")
    return Derived(
        tuple(body.s * body.q for body in sym.bodies),
        "centre displacement s_i phi_i of the engine's rolling bodies (M2), s_i the radius",
    )


def fig2_spring_force(b: Bench) -> Derived:
    sym = b.sym("fig2")
    (first, _), (second, _) = sym.body_forces
    return Derived(
        (tidy(first), sp.Abs(tidy(second))),
        "the engine's spring force on body 1 and the size of the one on body 2",
    )


def steiner(b: Bench) -> Derived:
    sym = b.sym("fig2")
    J = [sym.mass_matrix[i, i] for i in range(2)]
    return Derived(
        (J[0], J[0], J[1], J[1]),
        "diagonal of the engine's mass matrix M = diag(J_i), J = I + mR^2 (M4)",
    )


def fig2_eom(b: Bench) -> Derived:
    return Derived(
        tuple(b.accelerations("fig2")),
        "phiddot_i = Q_i/J_i from the engine's exact equations of motion (M7)",
    )


def fig2_sum(b: Bench) -> Derived:
    sym = b.sym("fig2")
    return Derived(
        tidy(sp.Add(*[eq.rhs for eq in sym.equations_of_motion()])),
        "sum of the engine's J_i phiddot_i = Q_i (M7)",
    )


def _equal_radii(b: Bench) -> dict[Any, Any]:
    """The Sec. 3 pair with unequal radii (``fig2-radii``: the hoop's track raised by
    R_2 - R_1, centres level) made the paper's Fig. 2: R_1 = R_2 = R, the track on the floor."""
    names = {p_.name: p_ for p_ in b.sym("fig2-radii").parameters}
    return {names["R_1"]: R, names["R_2"]: R, names["h_1"]: 0}


def _in_conserved(b: Bench, expr: Any) -> Any:
    """``expr`` (linear in the rates) of the Fig. 2 pair as a multiple of the conserved
    combination c . phidot = P_0 (M14) when it is one, else None; radii equal."""
    sym = b.sym("fig2-radii")
    equal = _equal_radii(b)
    c = [ci.xreplace(equal) for ci in b.conserved("fig2-radii")]
    rates = [body.qd for body in sym.bodies]
    scale = tidy(sp.sympify(expr).xreplace(equal).diff(rates[0]) / c[0])
    residual = tidy(
        sp.sympify(expr).xreplace(equal)
        - scale * sp.Add(*[ci * r for ci, r in zip(c, rates, strict=True)])
    )
    return scale * P0 if residual == 0 else None


#: Why the paper's weights I'_i rely on its equal radii (Sec. 3, eqs. (rel1), (c)).
_RADII = (
    "the weights I'ᵢ rely on the equal radii: in general the conserved quantity is "
    "Σ(1 + γᵢ)mᵢẋᵢ = ΣI'ᵢφ̇ᵢ/Rᵢ (the zero mode of K, M14) and X̂'s weights are I'ᵢ/Rᵢ²; with "
    "R₁ ≠ R₂, ΣI'ᵢφ̇ᵢ changes and (c) moves"
)


def momentum(b: Bench) -> Derived:
    """(rel1): I'_1 phidot_1 + I'_2 phidot_2, on the pair with unequal radii; conserved (and zero
    from rest) with the paper's equal radii."""
    sym = b.sym("fig2-radii")
    value = sp.Add(*[body.J * body.qd for body in sym.bodies])
    conserved = _in_conserved(b, value)
    if conserved is None:
        raise RuntimeError("fig2: with equal radii sum J_i phidot_i is expected conserved")
    return Derived(
        value,
        "sum J_i phidot_i of the pair with unequal radii, against the engine's conserved "
        "combination v0^T M phidot = P_0 (zero mode of K, M14)",
        assumed=tidy(conserved.xreplace({P0: 0})),
        why=_RADII + "; with equal radii I'₁φ̇₁ + I'₂φ̇₂ = P₀, fixed by the initial velocities",
    )


def w_relation(b: Bench) -> Derived:
    sym = b.sym("fig2")
    c = b.conserved("fig2")
    J = [body.J for body in sym.bodies]
    if not same([tidy(ci * J[0] / c[0]) for ci in c], J):
        raise RuntimeError("fig2: the conserved combination is expected to be sum J_i phidot_i")
    radius = sym.bodies[0].s
    value = (P0 / radius, P0 / radius)
    return Derived(
        value,
        "the conserved sum J_i phidot_i = P_0 (zero mode of K, M14) divided by R, with "
        "xdot_i = R phidot_i",
        assumed=(sp.Integer(0), sp.Integer(0)),
        why="the combination is conserved; its value P₀/R is fixed by the start",
    )


def phase_opposition(b: Bench) -> Derived:
    return Derived(
        sp.sign(mode_ratio(b)),
        "sign of phi_2/phi_1 in the oscillating mode (null vector of K - Omega^2 M)",
    )


def cm_moves(key: str) -> Callable[[Bench], Derived]:
    def derive(b: Bench) -> Derived:
        sym = b.sym(key)
        v = b.mode(key)
        masses = [body.m for body in sym.bodies]
        cm = tidy(
            sp.Add(
                *[
                    mm * body.s * v[i]
                    for i, (mm, body) in enumerate(zip(masses, sym.bodies, strict=True))
                ]
            )
            / (sp.Add(*masses) * sym.bodies[0].s * v[0])
        )
        return Derived(
            sp.true if cm != 0 else sp.false,
            f"in the oscillating mode Xdot = ({sp.sstr(cm)}) xdot_1 (engine's mode shape)",
        )

    return derive


def stationary_point(b: Bench) -> Derived:
    """X-hat of eq. (c) with the paper's weights I'_i: its velocity on the pair with unequal
    radii; with the paper's equal radii a multiple of the engine's conserved combination (zero
    from rest)."""
    sym = b.sym("fig2-radii")
    J = [body.J for body in sym.bodies]
    value = sp.Add(*[j * body.s * body.qd for j, body in zip(J, sym.bodies, strict=True)]) / (
        sp.Add(*J)
    )
    conserved = _in_conserved(b, value)
    if conserved is None:
        raise RuntimeError("fig2: with equal radii X-hat's rate is expected conserved")
    return Derived(
        value,
        "d/dt of (I'_1 x_1 + I'_2 x_2)/(I'_1 + I'_2) on the pair with unequal radii, against "
        "the engine's conserved combination v0^T M phidot = P_0 (M14)",
        assumed=tidy(conserved.xreplace({P0: 0})),
        why=_RADII + "; with equal radii X̂ moves uniformly, at rest only for a start from rest",
    )


def stationary(key: str) -> Callable[[Bench], Derived]:
    def derive(b: Bench) -> Derived:
        return Derived(
            tuple(b.weights(key)),
            "X-hat weights w_i = J_i v0_i / R_i from the zero mode of K (M14)",
        )

    return derive


def same_spring_forces(b: Bench) -> Derived:
    sym = b.sym("fig2")
    (first, _), (second, _) = sym.body_forces
    Q = sym.generalized_forces
    value = (tidy(second / first), tidy(Q[1] / Q[0]))
    return Derived(
        value,
        "F_2x/F_1x and the ratio of the torques Q_i about the contact lines (engine, M7)",
        assumed=_magnitudes(value),
        why="signed, the forces and their torques are opposite",
    )


def friction_ratio(b: Bench) -> Derived:
    first, second = b.along_mode(b.friction_linear("fig2"), "fig2")
    ratio = tidy(first / second)
    return Derived(
        ratio,
        "ratio of the engine's friction (M8), linearised, in the mode",
        assumed=sp.Abs(ratio),
        paper_assumed=sp.Abs,
        why=f"signed along +x the frictions point opposite ways, f₁/f₂ = {sp.sstr(ratio)}, so "
        "f₁ + f₂ ≠ 0: the resultant external force that moves the centre of mass",
    )


def friction_in_mode(b: Bench) -> Derived:
    friction = b.along_mode(b.friction_linear("fig2"), "fig2")
    return Derived(
        sp.true if any(f_ != 0 for f_ in friction) else sp.false,
        f"the engine's linearised frictions (M8) in the mode: {sp.sstr(tuple(friction))}",
    )


def contact_axis(b: Bench) -> Derived:
    """Sec. 3: about the contact line z' the friction has no arm: I'_i phiddot_i is the spring's
    torque alone (the engine's M7, derived without the friction)."""
    sym = b.sym("fig2")
    accelerations = b.accelerations("fig2")
    forces = [force[0] for force in sym.body_forces]
    value = tuple(
        tidy(body.J * acc - body.s * force)
        for body, acc, force in zip(sym.bodies, accelerations, forces, strict=True)
    )
    return Derived(
        value,
        "I'_i phiddot_i - R F_ix with the engine's equations of motion (M7, Lagrange's, in which "
        "no friction appears) and its spring forces: the friction's torque about z' is zero (its "
        "line passes through z'), and z' may be used although it accelerates (its acceleration "
        "R phidot^2 points through the centre)",
    )

"""Recipes for Sec. 4: the spring at the percussion heights (Fig. 3) and eq. (fric).

From the engine's Fig. 3 and pulled-body systems: the friction of a body pulled at a height, the
heights where it vanishes, Fig. 3's exact and linearised equations combined by the paper's
weights, its torques and angular momenta.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import replace
from typing import Any

import sympy as sp

from rollspring.analysis.derivation import SymbolicSystem
from rollspring.analysis.paper.algebra import same, tidy
from rollspring.analysis.paper.bench import Bench
from rollspring.analysis.paper.notation import I_, Fx1, Fx2, a
from rollspring.analysis.paper.recipes.common import (
    fig3_geometry,
    pulled_friction,
    zero_friction_height,
)
from rollspring.analysis.paper.symbols import R1, R2, F, R, m1, m2, y
from rollspring.analysis.paper.systems import paper_system
from rollspring.analysis.paper.types import Derived


def _exact_accelerations(b: Bench, key: str, subs: dict[Any, Any] | None = None) -> list[Any]:
    """phiddot_i = Q_i/J_i from the engine's exact equations of motion (not simplified)."""
    sym = b.sym(key)
    out = [eq.rhs / body.J for eq, body in zip(sym.equations_of_motion(), sym.bodies, strict=True)]
    return [e.xreplace(subs) for e in out] if subs else out


def fric(b: Bench) -> Derived:
    body = b.sym("pulled").bodies[0]
    f = pulled_friction(b, "pulled")
    slope = sp.diff(f, y)
    return Derived(
        (f, tidy(sp.diff(f, y, 2)), sp.sign(tidy(-slope / F))),
        "minus the engine's friction (M8) of the pulled body at phi = 0 (the paper counts f "
        "opposite to F), its curvature in y and the sign of its slope against F",
        paper_subs={I_: body.I},
    )


def fric_coupled(b: Bench) -> Derived:
    """Sec. 4: (fric) with the spring's varying force: the engine's friction (M8) is Newton's
    second law and the rotation about the contact line at one instant, so it holds for any F(t);
    on Fig. 2 (the spring at the centres, y = R, always horizontal) exactly, at every
    configuration."""
    sym = b.sym("fig2")
    forces = [F_[0] for F_ in sym.body_forces]
    return Derived(
        tuple(tidy(f) for f in sym.friction_configuration),
        "the engine's exact friction (M8) of the coupled bodies at every configuration (Newton's "
        "laws at one instant: no assumption on how F varies in time). No assumption is needed: "
        "(fric) holds instant by instant; on Fig. 3 only the ends' heights (2R₁ → R₁(1 + cos φ₁)) "
        "and the spring's direction change with the angles, at second order",
        paper_subs={Fx1: forces[0], Fx2: forces[1]},
    )


def heights(b: Bench) -> Derived:
    return Derived(
        (zero_friction_height(b, "pulled-hoop"), zero_friction_height(b, "pulled-cylinder")),
        "solving the engine's friction f(y) = 0 (M8) for a pulled hoop and cylinder",
    )


def geometry(b: Bench) -> Derived:
    hoop = zero_friction_height(b, "pulled-hoop")
    cylinder = zero_friction_height(b, "pulled-cylinder")
    track = sp.Symbol("h", real=True)  # height of the hoop's track above the cylinder's
    hoop_end = track + hoop.subs(R, R1)
    cylinder_end = cylinder.subs(R, R2)
    (one_floor,) = sp.solve(sp.Eq(hoop_end.subs(track, 0), cylinder_end), R1)
    level = sp.solve([sp.Eq(hoop_end, cylinder_end), sp.Eq(track + R1, R2)], [R1, track], dict=True)
    (level_solution,) = level
    return Derived(
        one_floor,
        "the spring joins the zero-friction heights (solved from the engine's f(y) = 0): "
        "horizontal iff h + 2R_1 = 3R_2/2",
        assumed=level_solution[R1],
        why="the level centres need the hoop's track raised by R₂ − R₁ = R₁; on one floor a "
        "horizontal spring would need R₁ = 3R₂/4",
    )


def horizontal_needed(b: Bench) -> Derived:
    """Sec. 4's "the spring must be horizontal": Fig. 3 on one floor (R_1 = R_2/2, the spring from
    the hoop's top to the cylinder's point 3R_2/2 high, tilted): the engine's linearised
    frictions (M8), and its Omega^2 against the level pair's times cos^2 of the tilt."""
    friction = b.friction_linear("fig3-tilted")
    sym = b.sym("fig3-tilted")
    names = {p_.name: p_ for p_ in sym.parameters}
    r1, r2, ell, spring = names["R_1"], names["R_2"], names["ell"], names["k"]
    cos2 = ell**2 / (ell**2 + (sp.Rational(3, 2) * r2 - 2 * r1) ** 2)
    level = spring * sp.Add(*[body.percussion_height**2 / body.J for body in sym.bodies])
    (w2,) = b.omega2("fig3-tilted")
    ratio = tidy(w2 / (cos2 * level))
    shown = "Ω² = cos²θ · k(2/m₁ + 3/(2m₂))" if ratio == 1 else f"Ω²/(cos²θ Ω²_level) = {ratio}"
    return Derived(
        sp.true if any(f_ != 0 for f_ in friction) else sp.false,
        "the engine's linearised frictions (M8) of Fig. 3 on one floor, the spring tilted",
        why="not needed: each end at its body's percussion height (1 + γ)R is enough, for any "
        "radii (R₁ = R₂ too: the Abstract's 'proper positioning the two fixed end points of the "
        "spring vertically' needs neither R₁ = R₂/2 nor a raised track); the "
        "spring's vertical pull has no lever arm about the contact line at rest, so only its "
        f"horizontal part enters (fric), and the frictions are O(φ²) ({sp.sstr(tuple(friction))} "
        f"to first order); the tilt θ only changes {shown} and makes the normal forces "
        "oscillate (Nᵢ = mᵢg ∓ F sin θ)",
        correction=r"f_1=f_2=O(\varphi^2)\ \text{with the spring tilted (one floor, }R_1=R_2/2"
        r"\text{): horizontality is not needed}",
    )


def small_angles_why(b: Bench) -> Derived:
    """Sec. 4's reason for the small angles ("for the spring to maintain its horizontal
    orientation"): horizontality is not needed (:func:`horizontal_needed`); what the small angles
    keep is each end at its body's percussion height, which it leaves at second order."""
    found = horizontal_needed(b)
    return replace(
        found,
        why=found.why + "; what the small angles keep is each end at its percussion height: as "
        "the bodies turn the ends drop (2R₁ → R₁(1 + cos φ₁), 3R₂/2 → R₂(1 + cos φ₂ /2)), and the "
        "frictions are O(φ³) even when the spring stays level",
    )


def fig3_eom(b: Bench) -> Derived:
    return Derived(
        tuple(_exact_accelerations(b, "fig3", fig3_geometry(b))),
        "phiddot_i = Q_i/J_i from the engine's exact equations of motion (M7) of the paper's "
        "Fig. 3; linearised (small angles) they are (Q(0) - K phi)_i / J_i",
        assumed=tuple(b.accelerations("fig3", linear=True)),
        why="the exact equations differ at third order in the angles: the spring turns with the "
        "bodies",
    )


def fig3_combination(
    weights: Callable[[SymbolicSystem], Sequence[sp.Expr]], how: str
) -> Callable[[Bench], Derived]:
    """sum w_i phiddot_i for the weights ``weights(sym)`` (tuples of them), exact and
    linearised."""

    def derive(b: Bench) -> Derived:
        sym = b.sym("fig3")
        exact = _exact_accelerations(b, "fig3", fig3_geometry(b))
        linear = b.accelerations("fig3", linear=True)
        rows = weights(sym)
        value = tuple(
            sp.Add(*[w_ * acc for w_, acc in zip(row, exact, strict=True)]) for row in rows
        )
        assumed = tuple(
            tidy(sp.Add(*[w_ * acc for w_, acc in zip(row, linear, strict=True)])) for row in rows
        )
        return Derived(
            value if len(rows) > 1 else value[0],
            how,
            assumed=assumed if len(rows) > 1 else assumed[0],
            why="with the exact equations of motion the sum is O(φ³), not zero: the spring turns "
            "with the bodies",
        )

    return derive


_J31, _J32 = 2 * m1 * R1**2, sp.Rational(3, 2) * m2 * R2**2  # the paper's I'_1, I'_2 of Fig. 3

#: Eq. (fig3) divided by the lever arms: I'_i phiddot_i over 2R_1 and 3R_2/2 (Sec. 4).
fig3_forces = fig3_combination(
    lambda sym: [
        (sym.bodies[0].J / (2 * R1), 0),
        (0, sym.bodies[1].J / (sp.Rational(3, 2) * R2)),
    ],
    "I'_i phiddot_i over the lever arms 2R_1, 3R_2/2, with the engine's equations of "
    "motion (exact, and linearised)",
)
#: The sum of the two, with the engine's inertias and with the paper's (Sec. 4).
fig3_sum = fig3_combination(
    lambda sym: [
        (sym.bodies[0].J / (2 * R1), sym.bodies[1].J / (sp.Rational(3, 2) * R2)),
        (_J31 / (2 * R1), _J32 / (sp.Rational(3, 2) * R2)),
    ],
    "the two sums with the engine's equations of motion (exact, and linearised)",
)
#: The centre of mass's acceleration times the mass: sum m_i R_i phiddot_i (Sec. 4).
fig3_cm_acceleration = fig3_combination(
    lambda sym: [(sym.bodies[0].m * R1, sym.bodies[1].m * R2)],
    "sum m_i R_i phiddot_i with the engine's equations of motion (exact, and linearised)",
)


def fig3_x(b: Bench) -> Derived:
    sym = b.sym("fig3")
    exact = _exact_accelerations(b, "fig3", fig3_geometry(b))
    linear = b.accelerations("fig3", linear=True)
    centres = tuple(body.s * body.q for body in sym.bodies)
    return Derived(
        (
            *centres,
            sp.Add(*[body.m * body.s * acc for body, acc in zip(sym.bodies, exact, strict=True)]),
        ),
        "the engine's centre displacements s_i phi_i and sum m_i s_i phiddot_i, exact",
        assumed=(
            *centres,
            tidy(
                sp.Add(
                    *[body.m * body.s * acc for body, acc in zip(sym.bodies, linear, strict=True)]
                )
            ),
        ),
        why="with the exact equations of motion m₁ẍ₁ + m₂ẍ₂ is O(φ³), not zero",
    )


def fig3_friction(b: Bench) -> Derived:
    sym = b.sym("fig3")
    geometry = fig3_geometry(b)
    v = b.mode("fig3").xreplace(geometry)
    v = v / v[1]  # amplitude a of phi_2
    along = {q: a * v[i] for i, q in enumerate(sym.q)}
    orders = []
    for f in sym.friction_configuration:
        d = f.xreplace(fig3_geometry(b)).xreplace(along)
        terms = []
        for n in (1, 2, 3):
            d = sp.diff(d, a)
            terms.append(sp.factor(sp.cancel(d.subs(a, 0))) / sp.factorial(n))
        orders.append(terms)
    linear = tuple(terms[0] * a for terms in orders)
    leading = tuple(terms[0] * a + terms[1] * a**2 + terms[2] * a**3 for terms in orders)
    shown = ", ".join(
        f"f{i + 1} = {sp.sstr(sp.factor(v_))} + O(a^4)" for i, v_ in enumerate(leading)
    )
    return Derived(
        leading,
        "the engine's exact friction (M8) of the paper's Fig. 3 expanded along the mode "
        "phi = a v to third order in a",
        assumed=linear,
        why="the attachment points leave the percussion heights as the bodies turn: beyond first "
        f"order {shown} (φ₂ = a)",
    )


def fig3_torques_differ(b: Bench) -> Derived:
    levers = [tidy(sp.Abs(lever)) for lever in b.lever("fig3")]
    ratio = tidy((levers[0] / levers[1]).xreplace(fig3_geometry(b)))
    return Derived(
        sp.true if ratio != 1 else sp.false,
        f"the lever arms of the spring about the contact lines (engine's dl/dphi_i): |b_1|/|b_2| "
        f"= {sp.sstr(ratio)} with the paper's R_1 = R_2/2",
    )


def fig3_angular_momentum(b: Bench) -> Derived:
    sym = b.sym("fig3")
    acc = b.accelerations("fig3", linear=True)
    # centre heights above the lower floor: the paper's Fig. 3 has the centres level, at R_2
    centre = [R2, R2]
    model = paper_system("fig3").bodies
    if abs(model[0].track_height + model[0].radius - model[1].radius) > 1e-12:
        raise RuntimeError("fig3: the centres are expected level")
    rate = sum((body.I + body.m * centre[i] * body.s) * acc[i] for i, body in enumerate(sym.bodies))
    value = tidy(rate.subs(R1, R2 / 2))
    return Derived(
        value,
        "dL_O/dt for L_O = sum (I_i phidot_i + m_i y_ci xdot_i) about a fixed point on the "
        "floor, with the engine's linearised equations of motion",
        paper_subs={R1: R2 / 2},
        why="ΣI'ᵢφ̇ᵢ does change (the torques differ), but it is not the angular momentum here: "
        "the contact lines are at different heights; the angular momentum about any fixed axis "
        "is conserved (no external torque: friction vanishes to first order, Nᵢ = mᵢg)",
        correction=r"\dot L_O=0",
    )


_ZERO_SUM_NAMES = {
    "two-hoops": "two hoops joined at their centres (Sec. 3)",
    "zero-sum": "a hoop of radius 3R₂/4 beside the cylinder on one floor, the spring level with "
    "the hoop's centre",
}


def friction_not_needed(b: Bench) -> Derived:
    """Sec. 4's "We need to ensure that there is no static friction force on rigid bodies": the
    centre of mass stays at rest when the frictions cancel (M8, (m_1 + m_2) Xddot = f_1 + f_2),
    which does not need each to vanish: two hoops joined at their centres (the paper's own
    Sec. 3) and a hoop of radius 3R_2/4 beside the cylinder, the spring level with the hoop's
    centre."""
    found = []
    for key in ("two-hoops", "zero-sum"):
        sym = b.sym(key)
        friction = b.friction_linear(key)
        if key == "zero-sum":  # the engine names the radii: the hoop's is 3R_2/4
            radius = sym.bodies[0].s
            friction = [sp.factor(f_.subs(radius, sp.Rational(3, 4) * R2)) for f_ in friction]
        if same(sp.Add(*friction), 0) and friction[0] != 0:
            found.append((key, friction[0]))
    return Derived(
        sp.false if found else sp.true,
        "the engine's linearised frictions (M8) of two hoops joined at their centres and of a "
        "hoop of radius 3R_2/4 beside the cylinder with the spring level with the hoop's centre: "
        "their sum (m_1 + m_2) Xddot, and f_1",
        why="not needed: the centre of mass stays at rest when f₁ + f₂ = 0 ((m₁ + m₂)Ẍ = f₁ + f₂), "
        "which does not need each friction to vanish: "
        + "; ".join(
            f"{_ZERO_SUM_NAMES[key]}: f₁ = −f₂ = {sp.sstr(sp.factor(f_))}" for key, f_ in found
        )
        + "; f₁ = f₂ = 0 is sufficient, not necessary",
        correction=r"\dot X=0\ \Leftrightarrow\ f_1+f_2=0\ \text{(each}\ f_i=0\ \text{is "
        r"sufficient, not necessary)}",
    )


def fig3_equal_forces(b: Bench) -> Derived:
    sym = b.sym("fig3")
    (first, _), (second, _) = sym.body_forces
    ratio = sp.Abs(tidy(second / first))
    return Derived(
        ratio,
        "|F_2x/F_1x| of the engine's exact spring forces on the two bodies (Fig. 3): the two "
        "ends of one spring",
    )


def fig3_spring_force(b: Bench) -> Derived:
    sym = b.sym("fig3")
    geometry = fig3_geometry(b)
    exact = sym.body_forces[0][0].xreplace(geometry)
    (linear,) = sym.linearized([exact])
    return Derived(
        exact,
        "the engine's exact spring force on the hoop along x (M7) in the paper's Fig. 3",
        assumed=tidy(linear),
        paper_subs=geometry,
        why="the exact force differs at third order in the angles: the spring turns with the "
        "bodies",
    )

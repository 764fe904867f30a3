"""Recipes for App. A (static friction), App. B (frequencies) and App. C (the Hamiltonian).

From the engine's friction (M8) on each body of Fig. 2 and on a body pulled at a height (Fig. 5),
the subsystems' energies and frequencies (App. B), and the clamped frequencies of Fig. 2 and
Fig. 3 (App. C).
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

import sympy as sp

from rollspring.analysis.paper.algebra import tidy
from rollspring.analysis.paper.bench import Bench
from rollspring.analysis.paper.notation import I_, f1, f2, fpull, p1, p2, p3, p4, q1, q2, q3, q4
from rollspring.analysis.paper.recipes.common import (
    CANONICAL_ORIENTATION,
    clamped_sum,
    fig3_geometry,
    flip_first,
    mode_ratio,
    pulled_friction,
    split,
    zero_friction_height,
)
from rollspring.analysis.paper.symbols import F, R, k, k1, k2, phi1, phi2, y
from rollspring.analysis.paper.types import Derived


def fric_app_a(b: Bench) -> Derived:
    body = b.sym("pulled").bodies[0]
    return Derived(
        pulled_friction(b, "pulled"),
        "minus the engine's friction (M8) of the pulled body at phi = 0",
        paper_subs={I_: body.I},
    )


def potential_q(key: str, qs: tuple[Any, ...], ps: tuple[Any, ...]) -> Callable[[Bench], Derived]:
    def derive(b: Bench) -> Derived:
        _, V = b.hamiltonian(key, qs, ps)
        return Derived(
            V,
            "the engine's V in q_i = sqrt(J_i/m_i) phi_i",
            condition=CANONICAL_ORIENTATION,
            paper_if=flip_first,
            why="the coefficients' magnitudes are Ωᵢ/√(k/mᵢ); counted one way, the first is "
            "negative",
        )

    return derive


#: App. C (k01): the Fig. 2 potential in q_1, q_2.
potential_fig2 = potential_q("fig2", (q1, q2), (p1, p2))


def potential_fig3(b: Bench) -> Derived:
    """App. C (k02): the Fig. 3 potential in q_3, q_4: exact (the spring turns with the bodies)
    and quadratic (the paper's small angles)."""
    sym = b.sym("fig3")
    _, V = b.hamiltonian("fig3", (q3, q4), (p3, p4))
    to_q = {
        body.q: sp.sqrt(body.m / body.J) * qq for body, qq in zip(sym.bodies, (q3, q4), strict=True)
    }
    exact = sym.potential.xreplace(to_q).xreplace(fig3_geometry(b))
    return Derived(
        exact,
        "the engine's exact V of Fig. 3 in q_i = sqrt(J_i/m_i) phi_i, and its quadratic form",
        assumed=V,
        condition="the first canonical coordinate is counted the other way (q₃ with the hoop "
        "anticlockwise); the paper's own Sec. 4 spring force F = k(3R₂φ₂/2 − 2R₁φ₁) counts both "
        "angles one way, which gives the coefficients (−Ω₃/√(k/m₁), +Ω₄/√(k/m₂))",
        paper_if=flip_first,
    )


def coefficients(b: Bench) -> Derived:
    _, V = b.hamiltonian("fig2", (q1, q2), (p1, p2))
    return Derived(
        tuple(tidy(sp.sqrt(sp.diff(V, qq, 2) / k)) for qq in (q1, q2)),
        "|c_i| = sqrt(d2V/dq_i^2 / k) of the engine's V in canonical coordinates",
    )


def clamped(key: str, *, roots: bool) -> Callable[[Bench], Derived]:
    def derive(b: Bench) -> Derived:
        sym = b.sym(key)
        values = [sym.stiffness_matrix[i, i] / body.J for i, body in enumerate(sym.bodies)]
        values = [sp.sqrt(v) if roots else v for v in values]
        return Derived(
            tuple(tidy(v) for v in values),
            "clamped (partial) frequencies sqrt(K_ii/J_i): each body alone, the other held "
            "(engine's M, K)",
        )

    return derive


def subsystem(index: int) -> Callable[[Bench], Derived]:
    """App. B: (alpha_i, beta_i) and Omega_i = sqrt(beta_i/alpha_i) in its three forms."""

    def derive(b: Bench) -> Derived:
        sym = b.sym("fig2")
        J = sym.mass_matrix[index, index]
        K = sym.stiffness_matrix[index, index]
        root = tidy(sp.sqrt(K / J))
        return Derived(
            (J, K, root, root, root),
            f"alpha = J_{index + 1} and beta = K_{index + 1}{index + 1} of the engine's M and K; "
            "Omega = sqrt(K_ii/J_i), body i alone with the other held (a clamped frequency)",
        )

    return derive


def subsystem_energy(index: int) -> Callable[[Bench], Derived]:
    def derive(b: Bench) -> Derived:
        sym = b.sym("fig2")
        held = {}
        for j, body in enumerate(sym.bodies):
            if j != index:
                held.update({body.q: 0, body.qd: 0})
        energy_ = sym.kinetic + sym.quadratic_potential
        return Derived(
            sp.expand(energy_.xreplace(held)),
            "the engine's T + V (quadratic) with the other body held (its angle and rate zero)",
        )

    return derive


def second_subsystem_mass(b: Bench) -> Derived:
    return Derived(
        b.sym("fig2").bodies[1].m,
        "the mass of the engine's body 2, the cylinder",
        why="the cylinder is body 2, of mass m₂, as the paper's own α₂ = (3/2)m₂R² writes it; "
        "m is the pulled body of App. A",
        correction="m_2",
    )


def app_a_rotation(index: int) -> Callable[[Bench], Derived]:
    """App. A: -k_i (R phi_i) R = I'_i phiddot_i in the mode, k_i the spring part's stiffness."""

    def derive(b: Bench) -> Derived:
        (w2,) = b.omega2("fig2")
        body = b.sym("fig2").bodies[index]
        value = -w2 * body.q
        return Derived(
            (value, value),
            "phiddot_i = -Omega^2 phi_i in the engine's mode, against the paper's forms with "
            "k_i = k/w_j, the spring part's stiffness",
            paper_subs=dict(zip((k1, k2), split(b), strict=True)),
        )

    return derive


def app_a_friction_torque(index: int) -> Callable[[Bench], Derived]:
    """App. A: -f_i R = I_i phiddot_i: the friction's torque about the centre turns the body
    (the spring acts at the centre)."""

    def derive(b: Bench) -> Derived:
        (w2,) = b.omega2("fig2")
        body = b.sym("fig2").bodies[index]
        friction = b.friction_linear("fig2")[index]
        value = -w2 * body.q
        return Derived(
            (value, value),
            "phiddot_i = -Omega^2 phi_i in the engine's mode, against -f_i R/I_i with the "
            "engine's friction (M8, positive along +x) in the mode",
            paper_subs={(f1, f2)[index]: tidy(friction.subs(phi2, mode_ratio(b) * phi1))}
            if index == 0
            else {(f1, f2)[index]: tidy(friction.subs(phi1, phi2 / mode_ratio(b)))},
        )

    return derive


def app_a_friction(index: int, *, middle: bool = False) -> Callable[[Bench], Derived]:
    def derive(b: Bench) -> Derived:
        sym = b.sym("fig2")
        v = b.mode("fig2")
        f = b.along_mode(b.friction_linear("fig2"), "fig2")[index]
        body = sym.bodies[index]
        coefficient = tidy(f / (body.s * v[index]))
        value = coefficient * body.s * body.q
        return Derived(
            (value, value) if index == 0 else value,
            "the engine's linearised friction (M8) in the mode, per R phi_i"
            + (", against the spring part's k_1 = k/w_2" if index == 0 else ""),
            why="the cylinder's I₂ = m₂R²/2 gives, with (A.3) and (A.4), f₂ = (k₂/3)Rφ₂, "
            "not (k₂/2)Rφ₂"
            if middle
            else "",
            correction=r"f_2=\frac{k_2}{3}R\phi_2=" + sp.latex(value) if middle else None,
            paper_subs={k1: split(b)[0], k2: split(b)[1]},
        )

    return derive


def _pulled_acceleration(b: Bench) -> tuple[Any, Any]:
    """The pulled body (I = gamma m R^2) and its phiddot = Q/J at phi = 0 (engine, M7)."""
    sym = b.sym("pulled")
    (eq,) = sym.equations_of_motion()
    body = sym.bodies[0]
    return body, tidy((eq.rhs / body.J).subs(body.q, 0))


def pull_equations(b: Bench) -> Derived:
    body, acc = _pulled_acceleration(b)
    return Derived(
        (acc, pulled_friction(b, "pulled")),
        "phiddot = Q/J at phi = 0 from the engine's equation of motion (M7), and minus the "
        "engine's friction (M8)",
        paper_subs={I_: body.I},
    )


def pull_phiddot(b: Bench) -> Derived:
    body, acc = _pulled_acceleration(b)
    return Derived(
        (body.s, acc, acc),
        "the engine's rolling constraint a = s phiddot (M2) and phiddot = Q/J at phi = 0 (M7)",
        paper_subs={I_: body.I, fpull: pulled_friction(b, "pulled")},
    )


def pull_at_floor(b: Bench) -> Derived:
    sym = b.sym("pulled")
    (eq,) = sym.equations_of_motion()
    body = sym.bodies[0]
    friction = tidy(pulled_friction(b, "pulled").subs(y, 0))
    acceleration = tidy((body.s * eq.rhs / body.J).subs(body.q, 0).subs(y, 0))
    return Derived(
        (friction, acceleration),
        "minus the engine's friction and the centre's acceleration R Q/J of the body (I = "
        "gamma m R^2, any gamma) pulled at y = 0",
    )


def reversal(b: Bench) -> Derived:
    cylinder = zero_friction_height(b, "pulled-cylinder")
    hoop = zero_friction_height(b, "pulled-hoop")
    top = 2 * R  # the point of application moves along the vertical diameter AB, 0 <= y <= 2R
    sign_at_top = sp.sign(tidy(pulled_friction(b, "pulled-cylinder").subs(y, top) / F))
    unchanged = (hoop - top).is_nonnegative
    return Derived(
        (cylinder, sign_at_top, sp.true if unchanged else sp.false),
        "the engine's f(y) of a pulled cylinder: its zero and its sign (against F) at the top; "
        f"a pulled hoop's f(y) vanishes only at y = {sp.sstr(hoop)}, the top of the diameter AB",
    )


def no_work(b: Bench) -> Derived:
    body = b.sym("pulled").bodies[0]
    return Derived(
        tidy((body.s - R) * body.qd),
        "velocity of the contact point s phidot - R phidot of the engine's rolling body (M2): "
        "the friction's power is f times it",
    )


def fig5_cylinder(b: Bench) -> Derived:
    return Derived(
        tidy(pulled_friction(b, "pulled-cylinder").subs(y, 2 * R)),
        "minus the engine's friction of a cylinder pulled at y = 2R",
    )


def fig5_labels(b: Bench) -> Derived:
    return Derived(
        (pulled_friction(b, "pulled-hoop"), pulled_friction(b, "pulled-cylinder")),
        "the engine's f(y) of a hoop (body 1 in the paper) and a cylinder (body 2)",
        why="the labels are swapped: everywhere else body 1 is the hoop; f₁(y) (zero at 2R) is "
        "the hoop's line, f₂(y) (zero at 3R/2) the cylinder's",
    )


def sum_rule_fig3(b: Bench) -> Derived:
    (w2,) = b.omega2("fig3")
    clamped = clamped_sum(b, "fig3")
    return Derived(
        (w2, tidy(w2 - clamped)),
        "the non-zero root of det(K - Omega^2 M) = 0 and its difference from the clamped sum "
        "K_11/J_1 + K_22/J_2 (engine's M, K)",
    )


def pull_eliminated(b: Bench) -> Derived:
    body = b.sym("pulled").bodies[0]
    return Derived(
        sp.Integer(0),
        "the paper's equation with f the engine's friction (M8) at phi = 0: the two sides agree",
        paper_subs={I_: body.I, fpull: pulled_friction(b, "pulled")},
    )

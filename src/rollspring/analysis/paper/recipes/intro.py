"""Recipes for the abstract, Sec. 1 and Sec. 2: two point masses (Fig. 1) and the abstract.

From the engine's Fig. 1 system: equations of motion, potential, floor forces, the centre-of-mass
theorem; and for the abstract's claims, the centre of mass in a normal mode, the friction behind
it and the four methods' Omega^2.
"""

from __future__ import annotations

from collections.abc import Callable

import sympy as sp

from rollspring.analysis.paper.algebra import same, tidy
from rollspring.analysis.paper.bench import Bench
from rollspring.analysis.paper.notation import P0
from rollspring.analysis.paper.recipes.common import from_rest
from rollspring.analysis.paper.symbols import m1, m2
from rollspring.analysis.paper.types import Derived


def fig1_eom(b: Bench) -> Derived:
    sym = b.sym("fig1")
    return Derived(
        tuple(eq.rhs for eq in sym.equations_of_motion()),
        "m_i xddot_i = Q_i = -dV/dx_i from the engine's potential (M7)",
    )


def fig1_potential(b: Bench) -> Derived:
    return Derived(
        b.sym("fig1").potential,
        "the engine's exact spring potential (M5), displacements from the equilibrium",
    )


def fig1_no_external(b: Bench) -> Derived:
    sym = b.sym("fig1")
    friction = sp.Add(*sym.friction_configuration)
    vertical = tidy(
        sp.Add(*[n - body.m * sym.g for n, body in zip(sym.normal, sym.bodies, strict=True)])
    )
    return Derived(
        (friction, vertical),
        "the engine's floor forces on the two masses: friction (frictionless floor) and "
        "N_i - m_i g (M9) summed",
    )


def fig1_vertical(b: Bench) -> Derived:
    sym = b.sym("fig1")
    return Derived(
        tuple(tidy(n - body.m * sym.g) for n, body in zip(sym.normal, sym.bodies, strict=True)),
        "N_i - m_i g from the engine's normal forces (M9): the spring stays horizontal",
    )


def fig1_end_forces(b: Bench) -> Derived:
    sym = b.sym("fig1")
    (first, _), (second, _) = sym.body_forces
    ratio = tidy(second / first)
    return Derived(
        ratio,
        "F_2x/F_1x of the engine's spring forces on the two masses",
        assumed=sp.Abs(ratio),
        why="signed along +x the two forces are opposite, F₂ = −F₁, as (f1), (f2) write them",
    )


def fig1_forces_from_u(b: Bench) -> Derived:
    sym = b.sym("fig1")
    return Derived(
        tuple(sp.expand(q) for q in sym.generalized_forces),
        "the engine's generalised forces Q_i (M7), its own -dV/dx_i",
    )


def fig1_momentum_sum(b: Bench) -> Derived:
    sym = b.sym("fig1")
    total = tidy(sp.Add(*[eq.rhs for eq in sym.equations_of_motion()]))
    return Derived((total, total), "sum of the engine's m_i xddot_i = Q_i (M7)")


def cm_theorem(b: Bench) -> Derived:
    sym = b.sym("fig1")
    masses = sp.Add(*[body.m for body in sym.bodies])
    return Derived(
        tidy(sp.Add(*[eq.rhs for eq in sym.equations_of_motion()]) / masses),
        "Xddot = sum Q_i / sum m_i for the two masses of Fig. 1, with the engine's Q_i (M7)",
    )


def cm_velocity(key: str, how: str, *, small: bool = False) -> Callable[[Bench], Derived]:
    def derive(b: Bench) -> Derived:
        sym = b.sym(key)
        w = b.weights(key)
        masses = [body.m for body in sym.bodies]
        total = sp.Add(*masses)
        if not same(w, [mm / total for mm in masses]):
            raise RuntimeError(f"{key}: the stationary point is expected at the centre of mass")
        value = P0 / total
        why = (
            "the conserved combination (zero mode of K, M14) is the total momentum "
            "Σ mᵢẋᵢ = P₀, fixed by the start"
        )
        if small:
            why += (
                "; beyond first order the frictions are O(a³) (the attachment points leave the "
                "percussion heights as the bodies turn) and the centre of mass drifts"
            )
        return from_rest(value, how, why=why)

    return derive


def friction_cause(b: Bench) -> Derived:
    sym = b.sym("fig2")
    acc = b.accelerations("fig2", linear=True)
    friction = b.friction_linear("fig2")
    newton = tidy(
        sp.Add(*[body.m * body.s * acc[i] for i, body in enumerate(sym.bodies)]) - sp.Add(*friction)
    )
    in_mode = tidy(sp.Add(*b.along_mode(friction, "fig2")))
    return Derived(
        (newton, sp.true if in_mode != 0 else sp.false),
        "(m_1 + m_2) Xddot minus the sum of the engine's frictions (M8), and that sum in the "
        f"mode (= {sp.sstr(in_mode)} per unit of the mode shape)",
    )


def same_inertia(b: Bench) -> Derived:
    sym = b.sym("fig2")
    total = sp.factor(sp.Add(*b.friction_linear("fig2")))
    # equal moments of inertia, I_1 = I_2: m_1 R^2 = m_2 R^2 / 2
    b1, b2 = sym.bodies
    (solution,) = sp.solve(sp.Eq(b1.I, b2.I), m2)
    with_equal_inertia = sp.factor(total.subs(m2, solution))
    hoops = tidy(sp.Add(*b.friction_linear("two-hoops")))
    cylinders = tidy(sp.Add(*b.friction_linear("two-cylinders")))
    note = (
        "it vanishes for two hoops and for two cylinders, the same inertia factor I/(mR²), "
        "whatever their moments of inertia"
        if hoops == 0 and cylinders == 0
        else ""
    )
    (contact,) = sp.solve(sp.Eq(b1.J, b2.J), m1)  # I'_1 = I'_2: m_1 = 3 m_2 / 4
    with_equal_contact = sp.factor(total.subs(m1, contact))
    return Derived(
        with_equal_inertia,
        "sum of the engine's linearised frictions (M8) with I_1 = I_2 imposed",
        why="with I₁ = I₂ (m₂ = 2m₁) a hoop and a cylinder still need "
        f"f₁ + f₂ = {sp.sstr(with_equal_inertia)} ≠ 0; read as the inertias about the contact "
        f"lines, I'₁ = I'₂ (m₁ = {sp.sstr(contact)}, where Sec. 5.3 has k₁ = k₂), f₁ + f₂ = "
        f"{sp.sstr(with_equal_contact)} ≠ 0 too: X̂ is the midpoint, the centre of mass is not; "
        f"{note}".rstrip("; "),
        correction=r"f_1+f_2="
        + sp.latex(total)
        + r"\neq 0\ \text{unless}\ \frac{I_1}{m_1R_1^2}=\frac{I_2}{m_2R_2^2}",
    )


def methods_agree(b: Bench) -> Derived:
    (w2,) = b.omega2("fig2")
    return Derived(
        (w2,) * 4,
        "the engine's Omega^2 (non-zero root of det(K - Omega^2 M) = 0), against the paper's "
        "Omega^2 of (QQ1), of the speeds' display (Sec. 5.2), of (ep) and of Sec. 5.6",
    )

r"""The Euler-Lagrange derivation of :math:`\mathcal L = T - V` (paper Sec. 5.3; docs/physics.md
(M5), (M7)), checked against ``sympy.physics.mechanics.LagrangesMethod``.

The generalised momenta :math:`p_i = \partial\mathcal L/\partial\dot\varphi_i = J_i\dot\varphi_i`
and forces :math:`\partial\mathcal L/\partial\varphi_i = -\partial V/\partial\varphi_i` give each
body's exact equation of motion; linearised, :mod:`.whole_system` takes them to the equation of
the whole system (with the paper's labels of Sec. 5.3). For one spring between two bodies with a
zero mode the derivation ends with the stiffnesses of the spring's two parts on either side of
the stationary point (paper (k1), (k2)). :func:`mechanics_lagrange_check` forms the same
equations with SymPy's ``LagrangesMethod`` and checks that the residual vanishes.
"""

from __future__ import annotations

from typing import Any

import sympy as sp

from rollspring.analysis.derivation.frequencies import BudgetExceeded, Frequencies, time_budget
from rollspring.analysis.derivation.method import (
    TITLES,
    MethodResult,
    cached_frequencies,
    method_section,
    short,
)
from rollspring.analysis.derivation.resistance import resistance_step
from rollspring.analysis.derivation.setup import setup_tags
from rollspring.analysis.derivation.steps import DEFINE, How, Section, Step, eq, inline, named
from rollspring.analysis.derivation.symbolic import SymbolicSystem
from rollspring.analysis.derivation.whole_system import linearise_in_angles

__all__ = ["lagrange", "mechanics_lagrange_check"]


def lagrange(sym: SymbolicSystem, budget: float | None) -> MethodResult:
    """Euler-Lagrange equations of L = T - V; the structure route and LagrangesMethod."""
    section = method_section(sym, "lagrange")
    tags = setup_tags(sym)
    tsym, vsym = sp.Symbol("T"), sp.Symbol("V")
    lag = named("Lag", r"\mathcal{L}", "ℒ")
    p = [sp.Symbol(f"p_{b.label}" if sym.n > 1 else "p", real=True) for b in sym.bodies]
    pdot = [sp.Symbol(f"pdot_{b.label}" if sym.n > 1 else "pdot", real=True) for b in sym.bodies]
    for a, b in zip(p, pdot, strict=True):
        section.rates[a] = b
    lagrangian = section.add(
        eq(lag, sym.kinetic - vsym),
        f"The Lagrangian L = T - V with T of ({tags['kinetic']}) and V of ({tags['potential']}).",
        "paper (l); (M5)",
        how=How("substitute", (tags["kinetic"],), args=(tsym,), law=eq(lag, tsym - vsym)),
    )
    momenta = section.add(
        [eq(p[i], b.J * b.qd) for i, b in enumerate(sym.bodies)],
        f"The generalised momenta p_i = dL/dphi_i', differentiating ({lagrangian.tag}).",
        "(M6)",
        how=How("differentiate", (lagrangian.tag,), args=tuple(sym.qd)),
        latex=_aligned_pairs(
            [
                (
                    rf"p_{{{b.label}}} = \frac{{\partial\mathcal{{L}}}}{{\partial "
                    rf"{sp.latex(b.qd)}}}",
                    sp.latex(b.J * b.qd),
                )
                for b in sym.bodies
            ]
        ),
    )
    momentum_rates = section.add(
        [eq(pdot[i], b.J * b.qdd) for i, b in enumerate(sym.bodies)],
        f"Differentiating ({momenta.tag}) in time (I' is constant: the mass matrix does not "
        "depend on the angles).",
        "",
        how=How("differentiate in time", (momenta.tag,)),
    )
    gradient = sym.potential_gradient
    forces_names = [
        named(
            f"dLag/dphi_{b.label}",
            rf"\frac{{\partial\mathcal{{L}}}}{{\partial {sp.latex(b.q)}}}",
            f"∂ℒ/∂{inline(b.q)}",
        )
        for b in sym.bodies
    ]
    forces = section.add(
        [eq(forces_names[i], short(-gradient[i])) for i in range(sym.n)],
        f"The generalised forces dL/dphi_i = -dV/dphi_i, differentiating ({lagrangian.tag}) "
        f"with V of ({tags['potential']}).",
        "(M7)",
        how=How("differentiate", (lagrangian.tag, tags["potential"]), args=tuple(sym.q)),
    )
    nonlinear = [eq(b.J * b.qdd, short(-gradient[i])) for i, b in enumerate(sym.bodies)]
    exact = section.add(
        nonlinear,
        f"The Euler-Lagrange equations d/dt(dL/dphi_i') = dL/dphi_i, with ({momentum_rates.tag}) "
        f"and ({forces.tag}): each body's equation of motion, exact.",
        "paper (al), (be); (M7)",
        how=How(
            "substitute",
            (momentum_rates.tag, forces.tag),
            args=(*pdot, *forces_names),
            law=[eq(pdot[i], forces_names[i]) for i in range(sym.n)],
        ),
    )
    resistance_step(section, sym, "lagrange", nonlinear, exact.tag)
    result = MethodResult("lagrange", TITLES["lagrange"], True, "", section, nonlinear=nonlinear)
    result.extras["mechanics"] = mechanics_lagrange_check(sym, budget=budget)
    linearised = linearise_in_angles(
        result,
        sym,
        exact.tag,
        budget,
        labels=(
            "paper (ga)",
            "paper (ga) integrated; (M14)",
            "paper (c); (M14)",
            "paper (ep)",
            "paper (QQQ1)",
            "paper (ep0)",
        ),
    )
    if not linearised:
        return result
    split = _spring_split(sym, cached_frequencies(sym, budget))
    solved = result.extras.get("solved_step")
    if split is not None:
        shares = _shares(section, sym, solved) if isinstance(solved, Step) else None
        section.add(
            [eq(sp.Symbol(f"k_{sym.bodies[i].label}", positive=True), split[i]) for i in range(2)],
            "The stiffnesses of the spring's two parts (the paper's k_1, k_2): both parts carry "
            "the spring's force F = k delta = k_i delta_i, so k_i = k / sigma_i with the shares "
            f"of ({shares}); 1/k = 1/k_1 + 1/k_2 because the shares add up to 1."
            if shares
            else "The stiffnesses of the spring's two parts, on either side of the stationary "
            "point (the paper's k_1, k_2): both parts carry the spring's force F, part i takes "
            "the share Omega_i^2 / Omega^2 of the deformation (Omega_i^2 = K_ii/I'_i, body i's "
            "frequency with the other clamped; Omega^2 = Omega_1^2 + Omega_2^2), so k_i = k "
            "Omega^2 / Omega_i^2, and 1/k = 1/k_1 + 1/k_2 because the shares add up to 1.",
            "paper (k1), (k2), (part)",
            how=DEFINE,
        )
        result.extras["spring_split"] = split
    return result


def mechanics_lagrange_check(sym: SymbolicSystem, *, budget: float | None = 30.0) -> dict[str, Any]:
    r"""The exact equations from ``sympy.physics.mechanics.LagrangesMethod`` against the
    structure route :math:`J_i\ddot\varphi_i + \partial V/\partial\varphi_i = 0`: the residual,
    expanded (and simplified if needed), must vanish."""
    from sympy.physics.mechanics import LagrangesMethod

    lag = sym.in_time(sym.lagrangian)
    try:
        with time_budget(budget):
            method = LagrangesMethod(lag, sym.functions)
            forms = list(method.form_lagranges_equations())
            ours = [
                sym.in_time(b.J * b.qdd + dV)
                for b, dV in zip(sym.bodies, sym.potential_gradient, strict=True)
            ]
            residual = [sp.expand(a - b) for a, b in zip(forms, ours, strict=True)]
            if any(r != 0 for r in residual):
                residual = [sp.simplify(r) for r in residual]
    except BudgetExceeded:
        return {
            "agrees": None,
            "residual": None,
            "equations": None,
            "message": f"did not finish within the {budget:g} s budget",
        }
    agrees = all(r == 0 for r in residual)
    return {
        "agrees": agrees,
        "residual": sp.Matrix(residual),
        "equations": forms,
        "message": "agrees" if agrees else "the residual does not simplify to zero",
    }


def _shares(section: Section, sym: SymbolicSystem, solved: Step) -> str | None:
    r"""The deformation's shares :math:`\sigma_i = \delta_i/\delta` of the spring's two parts,
    derived: the definition (the deformation to first order, :math:`\delta = b_1\varphi_1 +
    b_2\varphi_2` with the lever arms :math:`b_i = \partial l/\partial\varphi_i`, part i
    takes :math:`\delta_i = b_i\varphi_i`), then their values with the stationary point fixed
    (the relation of the angles ``solved``), which are :math:`\Omega_i^2/\Omega^2`
    (:math:`\Omega_i^2 = K_{ii}/I'_i`). Returns the tag of the values' step (None, and no
    step, where the shares are not those ratios: a spring under tension at the reference)."""
    at_reference = dict.fromkeys(sym.q, 0)
    levers = sym.lever_arms[0]
    arms = [sp.cancel(sp.sympify(levers.get(i, 0)).xreplace(at_reference)) for i in range(2)]
    sigma = [sp.Symbol(f"sigma_{b.label}", positive=True) for b in sym.bodies]
    phi = sym.q
    deformation = arms[0] * phi[0] + arms[1] * phi[1]
    ratio = solved.equations[0].rhs
    values = [
        sp.factor(sp.cancel((a * p / deformation).subs(phi[1], ratio)))
        for a, p in zip(arms, phi, strict=True)
    ]
    K = sym.stiffness_matrix
    clamped = [sp.cancel(K[i, i] / sym.bodies[i].J) for i in range(2)]
    if any(a == 0 for a in arms) or any(
        sp.cancel(sym.apply_conditions(values[i] - clamped[i] / (clamped[0] + clamped[1]))) != 0
        for i in range(2)
    ):
        return None
    defined = section.add(
        [eq(sigma[i], arms[i] * phi[i] / deformation) for i in range(2)],
        "The spring's deformation to first order, delta = b_1 phi_1 + b_2 phi_2 (b_i = ∂l/∂φᵢ "
        f"at the reference, the lever arms, as in K = k b b^T of ({setup_tags(sym)['stiffness']})"
        "), splits at the stationary point into two "
        "parts: part i, between body i and that point, is stretched by delta_i = b_i phi_i. "
        "Define each part's share sigma_i = delta_i / delta.",
        "paper (k1), (k2)",
        how=DEFINE,
    )
    shown = section.add(
        [eq(sigma[i], values[i]) for i in range(2)],
        f"With the stationary point fixed, {inline(phi[1])} of ({solved.tag}) in ({defined.tag}): "
        "phi_1 cancels, the shares are constants. They are Omega_i^2 / Omega^2, with Omega_i^2 = "
        "K_ii/I'_i (body i's frequency with the other clamped) and Omega^2 = Omega_1^2 + "
        f"Omega_2^2: here Omega_1^2 / (Omega_1^2 + Omega_2^2) = {inline(clamped[0])} / "
        f"({inline(clamped[0])} + {inline(clamped[1])}), the same.",
        "paper (k1), (k2)",
        how=How("substitute", (defined.tag, solved.tag), args=(phi[1],)),
    )
    return shown.tag


def _aligned_pairs(pairs: list[tuple[str, str]]) -> str:
    return r"\begin{aligned}" + r" \\ ".join(f"{a} &= {b}" for a, b in pairs) + r"\end{aligned}"


def _spring_split(sym: SymbolicSystem, freq: Frequencies) -> list[sp.Expr] | None:
    """k_i = k / sigma_i, sigma_i = Omega_i^2 / Omega^2 (paper (k1), (k2))."""
    if sym.n != 2 or len(sym.springs) != 1 or freq.n_zero != 1 or sym.forces:
        return None
    if any(a is None for a in sym.springs[0].attachments):
        return None
    K = sym.stiffness_matrix
    clamped = [sp.cancel(K[i, i] / sym.bodies[i].J) for i in range(2)]
    if any(c == 0 for c in clamped):
        return None
    total = clamped[0] + clamped[1]
    k = sym.springs[0].k
    return [sp.factor(sp.cancel(k * total / c)) for c in clamped]

r"""The derivation by the subsystems' natural frequencies (paper Sec. 5.4, App. B and C;
docs/physics.md (M15)).

With every other body clamped, body i oscillates alone with :math:`\Omega_i^2 = K_{ii}/J_i` (its
quadratic energy :math:`\tfrac12\alpha_i\dot\varphi_i^2 + \tfrac12\beta_i\varphi_i^2`). For two
bodies with a zero mode (K of rank 1) the coupled frequency is their sum, :math:`\Omega^2 =
\Omega_1^2 + \Omega_2^2`, and rank 1 fixes the coupling :math:`K_{12} = \pm\sqrt{K_{11}K_{22}}`
from the subsystems (App. C), so each body's equation is rebuilt from them. Any other system
gets only the trace identity, stated as the reason the method does not apply.
"""

from __future__ import annotations

import sympy as sp

from rollspring.analysis.derivation.frequencies import OMEGA2
from rollspring.analysis.derivation.method import TITLES, MethodResult, method_section, short, tidy
from rollspring.analysis.derivation.setup import setup_tags
from rollspring.analysis.derivation.steps import DEFINE, How, eq, named
from rollspring.analysis.derivation.symbolic import SymbolicSystem
from rollspring.analysis.derivation.whole_system import linear_equations, why_not_linear

__all__ = ["natural_frequencies"]


def natural_frequencies(sym: SymbolicSystem, budget: float | None) -> MethodResult:
    """Subsystem frequencies (one body clamped) and the sum rule, for rank-1 K."""
    section = method_section(sym, "natural-frequencies")
    result = MethodResult("natural-frequencies", TITLES["natural-frequencies"], False, "", section)
    reason = why_not_linear(sym)
    if not reason:
        n_zero = sym.zero_mode_count()
        if sym.n > 2:
            reason = (
                f"{sym.n} bodies: the subsystem frequencies do not add up to a normal "
                "frequency (the sum rule needs two bodies and a rank-1 K); only the trace "
                "identity holds: the sum of the normal modes' Omega_(n)^2 is the sum of the "
                "subsystem frequencies Omega_i^2 = K_ii/I'_i"
            )
        elif sym.n == 2 and n_zero != 1:
            reason = (
                "no zero mode (a wall or a pre-tensioned spring): K has rank 2 and "
                "no normal mode's Omega^2 is Omega_1^2 + Omega_2^2 (Omega_i^2 = K_ii/I'_i, body "
                "i's frequency with the other clamped); only the trace identity holds: "
                "Omega_(1)^2 + Omega_(2)^2 = Omega_1^2 + Omega_2^2"
            )
    if reason:
        result.reason = reason
        return result
    result.applies = True
    tags = setup_tags(sym)
    K = sym.stiffness_matrix
    J = [b.J for b in sym.bodies]
    tsym, vsym = sp.Symbol("T"), sp.Symbol("V")
    alphas = [sp.Symbol(f"alpha_{b.label}", positive=True) for b in sym.bodies]
    betas = [sp.Symbol(f"beta_{b.label}", positive=True) for b in sym.bodies]
    omegas2 = [sp.Symbol(f"Omega_{b.label}^2", positive=True) for b in sym.bodies]
    clamped = [tidy(sp.cancel(K[i, i] / J[i])) for i in range(sym.n)]
    energies = [sp.Symbol(f"E_{b.label}") for b in sym.bodies]
    sub_steps = []
    for i, b in enumerate(sym.bodies):
        others = [j for j in range(sym.n) if j != i]
        held = [eq(sym.q[j], 0) for j in others] + [eq(sym.qd[j], 0) for j in others]
        quad_i = sym.quadratic_potential.subs({sym.q[j]: 0 for j in others})
        sub_steps.append(
            section.add(
                eq(energies[i], J[i] * b.qd**2 / 2 + short(quad_i)),
                f"Subsystem {b.label}: body {b.label} alone, "
                + (
                    f"the other clamped (angle and rate zero) in E = T + V of ({tags['kinetic']}) "
                    f"and ({tags['quadratic']})."
                    if others
                    else f"E = T + V of ({tags['kinetic']}) and ({tags['quadratic']})."
                ),
                "paper (qee), App. B",
                how=How(
                    "substitute",
                    (tags["kinetic"], tags["quadratic"]),
                    args=(tsym, vsym, *[sym.q[j] for j in others], *[sym.qd[j] for j in others]),
                    law=eq(energies[i], tsym + vsym),
                    given=tuple(held),
                ),
            )
        )
    read = section.add(
        [eq(alphas[i], J[i]) for i in range(sym.n)] + [eq(betas[i], K[i, i]) for i in range(sym.n)],
        "Reading off the quadratic energies E_i = (1/2) alpha_i phi_i'^2 + (1/2) beta_i "
        f"phi_i^2 of ({', '.join(s.tag for s in sub_steps)}).",
        "paper (qee), App. B",
        how=How(
            "read off",
            tuple(s.tag for s in sub_steps),
            law=[
                eq(energies[i], alphas[i] * b.qd**2 / 2 + betas[i] * b.q**2 / 2)
                for i, b in enumerate(sym.bodies)
            ],
        ),
    )
    natural = section.add(
        [eq(omegas2[i], clamped[i]) for i in range(sym.n)],
        f"A quadratic energy (1/2) alpha q'^2 + (1/2) beta q^2 oscillates with Omega^2 = "
        f"beta/alpha: the subsystems' natural frequencies, with ({read.tag}).",
        "paper App. B",
        how=How(
            "substitute",
            (read.tag,),
            args=(*alphas, *betas),
            law=[eq(omegas2[i], betas[i] / alphas[i]) for i in range(sym.n)],
        ),
    )
    result.extras["clamped"] = clamped
    if sym.n == 1:
        omega2 = clamped[0]
        result.system_equation = eq(sym.qdd[0] + omega2 * sym.q[0], 0)
        section.add(
            result.system_equation,
            f"One body: the subsystem is the system; its equation of motion with ({natural.tag}).",
            "",
            how=How(
                "substitute",
                (natural.tag,),
                args=(omegas2[0],),
                law=eq(sym.qdd[0] + omegas2[0] * sym.q[0], 0),
            ),
        )
        result.omega2 = [omega2]
        result.equations = linear_equations(sym)
        return result
    det_name = named("det K", r"\det K", "det K")
    determinant = section.add(
        eq(det_name, sp.cancel(K.det())),
        f"The determinant of K ({tags['stiffness']}) vanishes: the system has a zero mode "
        "(K has rank 1).",
        "(M15)",
        how=How("evaluate", (tags["stiffness"],)),
        latex=rf"\det K = K_{{11}}K_{{22}} - K_{{12}}^2 = {sp.latex(sp.cancel(K.det()))}",
    )
    mass = sp.diag(*J)
    characteristic = sp.expand(sp.cancel((K - OMEGA2 * mass).det()))
    char = section.add(
        eq(sp.collect(characteristic, OMEGA2, sp.factor), 0),
        "Normal modes: q = v cos(Omega t) in M q'' + K q = 0 gives det(K - Omega^2 M) = 0, "
        f"with M, K of ({tags['mass']}), ({tags['stiffness']}); its constant term is det K = 0 "
        f"({determinant.tag}).",
        "(M15)",
        how=How("characteristic equation", (tags["mass"], tags["stiffness"]), args=(mass, K)),
    )
    omega2 = tidy(clamped[0] + clamped[1])
    section.add(
        eq(OMEGA2, sp.Add(omegas2[0], omegas2[1], evaluate=False)),
        f"The non-zero root of ({char.tag}): dividing by I'_1 I'_2 Omega^2 leaves Omega^2 = "
        f"K_11/I'_1 + K_22/I'_2, the sum of the subsystems' ({natural.tag}).",
        "paper Omega_f^2 = Omega_1^2 + Omega_2^2; (M15)",
        how=How("solve", (char.tag, natural.tag), args=(OMEGA2,)),
    )
    total = section.add(
        eq(OMEGA2, omega2),
        f"With ({natural.tag}): the squared frequency of the coupled system.",
        "paper (QQQ1), App. B",
        how=How(
            "substitute",
            (natural.tag,),
            args=tuple(omegas2),
            law=eq(OMEGA2, omegas2[0] + omegas2[1]),
        ),
    )
    # App. C: rank 1 fixes K from its diagonal up to the sign of K_12 (from the geometry)
    sign = 1 if sym.numeric(K[0, 1]) >= 0 else -1
    off = sp.factor(sp.powdenest(sp.sqrt(sp.factor(K[0, 0] * K[1, 1])), force=False)) * sign
    k12 = sp.Symbol("K_12")
    k11, k22 = sp.Symbol("K_11"), sp.Symbol("K_22")
    coupling = section.add(
        eq(k12, off),
        f"Rank 1 fixes the coupling from the subsystems: det K = 0 ({determinant.tag}) "
        "solved for K_12 = ±sqrt(K_11 K_22); the sign from the lever arms (ends on opposite "
        "sides of the bodies: -).",
        "paper App. C",
        how=How(
            "solve",
            (),
            args=(k12,),
            law=eq(k11 * k22 - k12**2, 0),
            given=(eq(k11, K[0, 0]), eq(k22, K[1, 1])),
        ),
    )
    if len(sym.springs) == 1 and not sym.forces:
        m = [b.m for b in sym.bodies]
        k = sym.springs[0].k
        coefficients = [sp.Symbol(f"c_{b.label}") for b in sym.bodies]
        values = [sp.sqrt(sp.cancel(K[i, i] * m[i] / (J[i] * k))) for i in range(2)]
        values = [-values[0] if sign < 0 else values[0], values[1]]
        section.add(
            [eq(coefficients[i], values[i]) for i in range(2)],
            "Coefficients of the Hamiltonian potential (k/2)(c1 q1 + c2 q2)^2 in the canonical "
            "coordinates q_i = sqrt(I'_i/m_i) phi_i of Hamilton's method (paper Sec. 5.6, App. "
            "C), defined by |c_i| = Omega_i / sqrt(k/m_i) with Omega_i of "
            f"({natural.tag}); in a common orientation of the angles they have opposite signs "
            "here.",
            "paper (k0), App. C (sign-corrected)",
            how=DEFINE,
        )
        result.extras["c"] = values
    rebuilt = sp.Matrix([[K[0, 0], off], [off, K[1, 1]]])
    equations = [
        eq(J[i] * sym.qdd[i], -sp.expand((rebuilt * sp.Matrix(sym.q))[i])) for i in range(2)
    ]
    law = [
        eq(J[0] * sym.qdd[0], -(K[0, 0] * sym.q[0] + k12 * sym.q[1])),
        eq(J[1] * sym.qdd[1], -(k12 * sym.q[0] + K[1, 1] * sym.q[1])),
    ]
    section.add(
        equations,
        "Each body's equation of motion I'_i phi_i'' = -(K phi)_i rebuilt from the subsystems: "
        f"the diagonal of K from them, K_12 from ({coupling.tag}).",
        "",
        how=How("substitute", (coupling.tag,), args=(k12,), law=law),
    )
    result.equations = equations
    result.system_equation = eq(sym.qdd[0] + omega2 * sym.q[0], 0)
    section.add(
        result.system_equation,
        "The equation of motion of the whole system (angles about the stationary point): a "
        f"harmonic oscillation q'' + Omega^2 q = 0 with Omega^2 of ({total.tag}).",
        "paper (QQ1)",
        how=How(
            "substitute",
            (total.tag,),
            args=(OMEGA2,),
            law=eq(sym.qdd[0] + OMEGA2 * sym.q[0], 0),
        ),
    )
    result.omega2 = [omega2]
    return result

r"""Hamilton's derivation in the canonical coordinates :math:`q_i = \sqrt{J_i/m_i}\,\varphi_i`,
:math:`p_i = m_i\dot q_i` (paper Sec. 5.6; docs/physics.md (M6)).

These coordinates make the kinetic energy :math:`\sum_i p_i^2/2m_i` (a point transformation,
hence canonical), so :math:`\mathcal H` is separable. Hamilton's equations give Newton's law in
q and, multiplied back, :math:`J_i\ddot\varphi_i = -\partial V/\partial\varphi_i`. To second
order V is :math:`\tfrac12 q^TK_qq` with :math:`K_q = D^{-1}KD^{-1}`, :math:`D =
\mathrm{diag}(\sqrt{J_i/m_i})`, written as the paper's :math:`(k/2)(c_1q_1 + c_2q_2)^2` for one
spring (sign-corrected); :mod:`.whole_system` takes the linear equations to the whole system's
(:math:`M_q^{-1}K_q` is similar to :math:`M^{-1}K`: the same roots).
"""

from __future__ import annotations

import sympy as sp

from rollspring.analysis.derivation.method import (
    TITLES,
    MethodResult,
    cached_frequencies,
    method_section,
    names_momentum,
    normalised,
    short,
    single_spring_lever,
    tuple_text,
    zero_mode_2,
    zero_mode_in_angles,
)
from rollspring.analysis.derivation.setup import setup_tags
from rollspring.analysis.derivation.steps import DEFINE, How, eq, named
from rollspring.analysis.derivation.symbolic import SymbolicSystem
from rollspring.analysis.derivation.whole_system import to_whole_system, why_not_linear

__all__ = ["hamilton"]


def hamilton(sym: SymbolicSystem, budget: float | None) -> MethodResult:
    """Canonical coordinates q_i = sqrt(J_i/m_i) phi_i, p_i = m_i q_i'."""
    section = method_section(sym, "hamilton")
    tags = setup_tags(sym)
    n = sym.n
    J = [b.J for b in sym.bodies]
    m = [b.m for b in sym.bodies]
    scale = [sp.sqrt(sp.cancel(J[i] / m[i])) for i in range(n)]  # q = scale * phi

    def names(base: str, **assumptions: bool) -> list[sp.Symbol]:
        return [
            sp.Symbol(f"{base}_{b.label}" if n > 1 else base, **assumptions) for b in sym.bodies
        ]

    qs, ps = names("q", real=True), names("p", real=True)
    qdots, pdots, qdds = (
        names("qdot", real=True),
        names("pdot", real=True),
        names("qddot", real=True),
    )
    for a, b, c in zip(qs, qdots, qdds, strict=True):
        section.rates[a] = b
        section.rates[b] = c
    for a, b in zip(ps, pdots, strict=True):
        section.rates[a] = b
    coordinates = section.add(
        [eq(qs[i], scale[i] * sym.q[i]) for i in range(n)],
        "Canonical coordinates chosen so that the kinetic energy reads sum p^2/(2m): "
        "q_i = sqrt(I'_i/m_i) phi_i (a point transformation, hence canonical).",
        "paper q1 = sqrt(2) R phi1, q2 = sqrt(3/2) R phi2",
        how=DEFINE,
    )
    momenta = section.add(
        [eq(ps[i], m[i] * qdots[i]) for i in range(n)],
        "Their momenta: T = sum (1/2) m_i q_i'^2, so p_i = dT/dq_i' = m_i q_i'.",
        "(M6)",
        how=DEFINE,
    )
    hsym = named("Ham", r"\mathcal{H}", "ℋ")
    vsym = sp.Symbol("V")
    back = {sym.q[i]: qs[i] / scale[i] for i in range(n)}
    potential_q = sym.potential.xreplace(back)
    kinetic_q = sp.Add(*[ps[i] ** 2 / (2 * m[i]) for i in range(n)])
    hamiltonian = section.add(
        eq(hsym, kinetic_q + short(potential_q)),
        f"The Hamiltonian H = sum p_i^2/(2m_i) + V, exactly, with V of ({tags['potential']}) in "
        f"the new coordinates ({coordinates.tag}): separable, the kinetic part in p only.",
        "(M6)",
        how=How(
            "substitute",
            (tags["potential"], coordinates.tag),
            args=(vsym, *sym.q),
            law=eq(hsym, kinetic_q + vsym),
        ),
    )
    dV = [
        sp.diff(potential_q, qs[i]) if potential_q.has(qs[i]) else sp.Integer(0) for i in range(n)
    ]
    canonical = section.add(
        [eq(qdots[i], ps[i] / m[i]) for i in range(n)]
        + [eq(-pdots[i], short(dV[i])) for i in range(n)],
        f"Hamilton's equations q_i' = dH/dp_i and -p_i' = dH/dq_i, differentiating "
        f"({hamiltonian.tag}).",
        "paper (h)",
        how=How("differentiate", (hamiltonian.tag,), args=(*ps, *qs)),
    )
    momentum_rates = section.add(
        [eq(pdots[i], m[i] * qdds[i]) for i in range(n)],
        f"Differentiating ({momenta.tag}) in time.",
        "paper p1' = m1 q1''",
        how=How("differentiate in time", (momenta.tag,)),
    )
    in_q = section.add(
        [eq(m[i] * qdds[i], short(-dV[i])) for i in range(n)],
        f"Substituting ({momentum_rates.tag}) into the second half of ({canonical.tag}) "
        "(and changing the sign of both sides): Newton's law in the canonical coordinates.",
        "",
        how=How(
            "substitute",
            (f"{canonical.tag}:{','.join(str(n + i + 1) for i in range(n))}", momentum_rates.tag),
            args=tuple(pdots),
        ),
    )
    nonlinear = []
    for i, b in enumerate(sym.bodies):
        # m_i q_i'' = -dV/dq_i with q = s phi: m s phi'' = -(1/s) dV/dphi; times s: J phi''
        rhs = -(scale[i] * dV[i]).xreplace({qs[j]: scale[j] * sym.q[j] for j in range(n)})
        if sp.count_ops(rhs) < 120:  # the roots of J_i/m_i cancel once multiplied out
            rhs = sp.expand(rhs)
        nonlinear.append(eq(b.J * b.qdd, short(sp.powsimp(rhs))))
    section.add(
        nonlinear,
        f"Back in the angles: q_i = sqrt(I'_i/m_i) phi_i ({coordinates.tag}) in ({in_q.tag}), "
        "multiplied by sqrt(I'_i/m_i), is I'_i phi_i'' = -dV/dphi_i.",
        "(M7)",
        how=How("substitute", (in_q.tag, coordinates.tag), args=(*qs, *qdds)),
    )
    result = MethodResult("hamilton", TITLES["hamilton"], True, "", section, nonlinear=nonlinear)
    reason = why_not_linear(sym)
    if reason:
        result.reason = "linearisation: " + reason
        return result
    D = sp.diag(*scale)
    Dinv = sp.diag(*[1 / s for s in scale])
    Kq = (Dinv * sym.stiffness_matrix * Dinv).applyfunc(_compact_entry)
    qvec = sp.Matrix(qs)
    quadratic = sp.expand((qvec.T * Kq * qvec)[0, 0] / 2)
    constant = _at_zero_q(sym.quadratic_potential, sym)
    linear_term = sp.expand(-sum(sym.reference_forces[i] * qs[i] / scale[i] for i in range(n)))
    lever = single_spring_lever(sym)
    how_quadratic = How("substitute", (tags["quadratic"], coordinates.tag), args=tuple(sym.q))
    if lever is not None and constant == 0 and linear_term == 0:
        k = sym.springs[0].k
        c = [sp.factor(sp.cancel(lever[i] / scale[i])) for i in range(2)]
        form = k / 2 * (c[0] * qs[0] + c[1] * qs[1]) ** 2
        second = section.add(
            eq(vsym, form),
            f"V to second order ({tags['quadratic']}) in the canonical coordinates "
            f"({coordinates.tag}), as the paper writes it: (k/2)(c1 q1 + c2 q2)^2, c_i = b_i "
            "sqrt(m_i/I'_i) with the lever arms b_i; in a common orientation of the angles c1 "
            "and c2 have opposite signs.",
            "paper (k), (k0) (sign-corrected)",
            how=how_quadratic,
        )
        result.extras["c"] = c
        result.extras["potential_form"] = form
    else:
        second = section.add(
            eq(vsym, constant + linear_term + quadratic),
            f"V to second order ({tags['quadratic']}) in the canonical coordinates "
            f"({coordinates.tag}): (1/2) q^T K_q q with K_q = D^-1 K D^-1, D = "
            "diag(sqrt(I'_i/m_i)).",
            "(M12)",
            how=how_quadratic,
        )
    linear_p = [
        eq(-pdots[i], sp.expand((Kq * qvec)[i] - sym.reference_forces[i] / scale[i]))
        for i in range(n)
    ]
    derivative = section.add(
        linear_p,
        f"Hamilton's equations -p_i' = dH/dq_i with V of ({second.tag}): linear.",
        "paper (h)",
        how=How("differentiate", (second.tag,), args=tuple(qs)),
    )
    mass_q = list(m)
    linear_eqs = [
        eq(m[i] * qdds[i], sp.expand(sym.reference_forces[i] / scale[i] - (Kq * qvec)[i]))
        for i in range(n)
    ]
    newton_q = section.add(
        linear_eqs,
        f"With p_i' = m_i q_i'' ({momentum_rates.tag}) in ({derivative.tag}) (and changing the "
        "sign of both sides).",
        "paper (h) with p1' = m1 q1''",
        how=How("substitute", (derivative.tag, momentum_rates.tag), args=tuple(pdots)),
    )
    equations = []
    for i, body in enumerate(sym.bodies):
        rhs = -(scale[i] * (Kq * qvec)[i]).xreplace({qs[j]: scale[j] * sym.q[j] for j in range(n)})
        rhs = sym.reference_forces[i] + sp.expand(sp.powsimp(sp.expand(rhs)))
        equations.append(eq(body.J * body.qdd, rhs))
    result.equations = equations
    v0 = zero_mode_in_angles(sym)
    v0q = (D * v0).applyfunc(sp.cancel) if v0 is not None else None
    if v0q is not None and n == 2:
        v0q = normalised(zero_mode_2(Kq)) or v0q
    # M_q^-1 K_q = D M^-1 K D^-1 is similar to M^-1 K: the same polynomial and roots
    freq = cached_frequencies(sym, budget)
    out = to_whole_system(
        section,
        sym,
        eqs_tag=newton_q.tag,
        eqs=linear_eqs,
        coords=qs,
        velocities=qdots,
        accels=qdds,
        masses=mass_q,
        K=Kq,
        v0=v0q,
        frequencies=freq,
        in_angles=False,
        momentum_words=(
            "in the original coordinates it is proportional to sum I'_i v0_i phi_i' with v0 = "
            f"{tuple_text(v0)} (q_i = sqrt(I'_i/m_i) phi_i): "
            + names_momentum(sym, v0).replace("P̂ is", "that sum is")
            if v0 is not None
            else ""
        ),
        names="coordinates",
        labels=(
            "paper p2' = (2/sqrt3) p1' (sign-corrected)",
            "paper q2 = (m1/m2)(2/sqrt3) q1 (sign-corrected)",
            "",
            "paper p1' = m1 q1''",
            "paper (QQQ1)",
            "paper -p1' = k(q1/2 + 2 m1 q1/(3 m2))",
        ),
    )
    result.record(out)
    result.extras["Kq"] = Kq
    return result


def _at_zero_q(expr: sp.Expr, sym: SymbolicSystem) -> sp.Expr:
    return sp.expand(sp.sympify(expr).subs(dict.fromkeys(sym.q, 0)))


def _compact_entry(expr: sp.Expr) -> sp.Expr:
    """A matrix entry: cancelled and factored unless it holds transcendental constants."""
    expr = sp.cancel(expr)
    if expr.has(sp.sin, sp.cos, sp.atan2) or sp.count_ops(expr) > 80:
        return expr
    return sp.factor(expr)

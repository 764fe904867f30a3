r"""The derivation by conservation laws: energy and the conserved momentum of the zero mode (paper
Sec. 5.2; docs/physics.md (M6), (M14)).

It needs one oscillating degree of freedom: one body, or two bodies with one zero mode
:math:`v_0` (:math:`Kv_0 = 0`). The momentum :math:`\hat P = v_0^T M\dot\varphi` is conserved (the
total angular momentum about a point of the floor when the bodies roll on one floor with equal
weights) and ties the second angle to the first; the energy :math:`E = T + V` then depends on one
coordinate, and :math:`dE/dt = 0` gives :math:`\ddot\varphi_1 + \Omega^2\varphi_1 = 0`. For one
unstressed spring between the two bodies the paper's own route follows: the largest speeds from
the two conservation laws, :math:`\Omega = (v_1 + v_2)/A` and the amplitudes.
"""

from __future__ import annotations

import sympy as sp

from rollspring.analysis.derivation.frequencies import OMEGA2
from rollspring.analysis.derivation.method import (
    TITLES,
    MethodResult,
    content_free,
    coordinates_word,
    is_papers_fig2,
    method_section,
    names_momentum,
    short,
    shown_scaled,
    single_spring_lever,
    tidy,
    tuple_text,
    zero_mode_in_angles,
)
from rollspring.analysis.derivation.setup import setup_tags
from rollspring.analysis.derivation.steps import GIVEN, How, Section, eq, inline
from rollspring.analysis.derivation.symbolic import SymbolicSystem
from rollspring.analysis.derivation.whole_system import why_not_linear

__all__ = ["conservation"]


def conservation(sym: SymbolicSystem, budget: float | None) -> MethodResult:
    """Energy and the conserved momentum of the zero mode (one oscillating degree of
    freedom)."""
    section = method_section(sym, "conservation")
    result = MethodResult("conservation", TITLES["conservation"], False, "", section)
    reason = why_not_linear(sym)
    n_zero = sym.zero_mode_count() if not reason else 0
    if not reason:
        oscillating = sym.n - n_zero
        if n_zero == 0 and sym.n > 1:
            reason = (
                "no zero mode (a wall or a pre-tensioned spring holds the system): no "
                "conserved momentum, and energy alone cannot fix "
                f"{sym.n} coordinates"
            )
        elif n_zero > 1:
            reason = (
                f"{n_zero} zero modes: parts of the system move freely, and energy with "
                "the conserved momenta does not single out one oscillation"
            )
        elif oscillating > 1:
            reason = (
                f"{oscillating} oscillating modes: energy and the one conserved "
                f"momentum give two equations for {sym.n} coordinates"
            )
    v0 = zero_mode_in_angles(sym) if not reason and sym.n == 2 else None
    if not reason and sym.n == 2 and (v0 is None or v0[0] == 0 or v0[1] == 0):
        reason = "the zero mode moves one body only: no exchange between the two bodies"
    if reason:
        result.reason = reason
        return result
    result.applies = True
    tags = setup_tags(sym)
    J = [b.J for b in sym.bodies]
    K = sym.stiffness_matrix
    quad = sym.quadratic_potential
    esym, edot = sp.Symbol("E"), sp.Symbol("Edot")
    conserved_energy = eq(edot, 0)
    rolls = [b.rolls for b in sym.bodies]
    energy_words = "energy is conserved, dE/dt = 0, because " + (
        "static friction acts at a contact point at rest and does no work"
        if all(rolls)
        else "the floor is frictionless (no force but the springs' does work)"
        if not any(rolls)
        else "static friction acts at a contact point at rest and the sliders' floor is "
        "frictionless: neither does work"
    )
    energy = section.add(
        eq(esym, sym.kinetic + short(quad)),
        f"The mechanical energy E = T + V with T of ({tags['kinetic']})"
        + (
            " (about the contact lines a rolling body's kinetic energy is purely rotational)"
            if any(rolls)
            else ""
        )
        + f" and V to second order ({tags['quadratic']}).",
        "paper (mu); (M6)",
        how=How(
            "substitute",
            (tags["kinetic"], tags["quadratic"]),
            args=(sp.Symbol("T"), sp.Symbol("V")),
            law=eq(esym, sp.Symbol("T") + sp.Symbol("V")),
        ),
    )
    if sym.n == 1:
        section.title = "Conservation of energy"
        result.title = section.title
        b = sym.bodies[0]
        derivative = sp.expand(
            sp.diff(sym.kinetic + quad, b.qd) * b.qdd + sp.diff(quad, b.q) * b.qd
        )
        rate = section.add(
            eq(sp.factor(derivative), 0),
            f"Differentiating ({energy.tag}) in time: {energy_words}.",
            "(M6)",
            how=How("differentiate in time", (energy.tag,), given=(conserved_energy,)),
        )
        equation = eq(b.J * b.qdd, sym.reference_forces[0] - K[0, 0] * b.q)
        divided = section.add(
            equation,
            f"Dividing ({rate.tag}) by the rate {inline(b.qd)} (not zero while the body moves).",
            "",
            how=How("divide", (rate.tag,), args=(b.qd,)),
        )
        result.equations = [equation]
        omega2 = tidy(sp.cancel(K[0, 0] / J[0]))
        result.system_equation = eq(b.qdd + omega2 * b.q, 0)
        standard = section.add(
            result.system_equation,
            f"Dividing ({divided.tag}) by I' and bringing every term to the left: the equation "
            "of motion.",
            "",
            how=How("rearrange", (divided.tag,)),
        )
        section.add(
            eq(OMEGA2, omega2),
            f"Reading off the coefficient of ({standard.tag}): the squared frequency.",
            "",
            how=How("read off", (standard.tag,), law=eq(b.qdd + OMEGA2 * b.q, 0)),
        )
        result.omega2 = [omega2]
        return result
    assert v0 is not None
    angular = names_momentum(sym, v0)
    if angular.startswith("here the weights v0_i are equal"):
        section.title = "Conservation of energy and angular momentum"
    else:
        section.title = "Conservation of energy and of the zero mode's momentum"
    result.title = section.title
    p1, p2 = sym.q
    w1, w2 = sym.qd
    a1 = sym.qdd[0]
    momentum = sp.Add(*[J[i] * v0[i] * sym.qd[i] for i in range(2)])
    shown = content_free(momentum, sym.qd)
    scaled = shown_scaled("P̂", sp.factor(sp.cancel(momentum / shown)))
    conserved = section.add(
        eq(shown, 0),
        f"The momentum P̂ = v0^T M phi' with the zero mode v0 = {tuple_text(v0)} (K v0 = 0) "
        "is conserved: its rate is v0^T Q = -v0^T K phi = 0, the "
        + ("torques about the contact points" if any(rolls) else "spring forces")
        + f" cancel in it. It is zero for a start from rest{scaled}; {angular}.",
        "paper (nu), (rel1); (M14)",
        how=GIVEN,
    )
    again = section.add(
        eq(content_free(sp.Add(*[J[i] * v0[i] * sym.q[i] for i in range(2)]), sym.q), 0),
        f"Integrating ({conserved.tag}) over time. The constant is the left side's value at "
        f"the start; a uniform shift along the zero mode is an equilibrium too, and of these "
        f"equilibria the {coordinates_word(sym)} are measured from the one that makes it zero "
        "(the stationary point at the origin).",
        "",
        how=How("integrate in time", (conserved.tag,)),
    )
    ratio = sp.cancel(-J[0] * v0[0] / (J[1] * v0[1]))
    solved = section.add(
        [eq(p2, ratio * p1), eq(w2, ratio * w1)],
        f"Solving ({again.tag}) and ({conserved.tag}) for {inline(p2)} and {inline(w2)}.",
        "",
        how=How("solve", (again.tag, conserved.tag), args=(p2, w2)),
    )
    alpha = sp.factor(sp.cancel(J[0] + J[1] * ratio**2))
    beta = sp.factor(sp.cancel(K[0, 0] + 2 * K[0, 1] * ratio + K[1, 1] * ratio**2))
    one = section.add(
        eq(esym, alpha * w1**2 / 2 + beta * p1**2 / 2),
        f"Substituting ({solved.tag}) into ({energy.tag}): the energy of one coordinate, "
        f"(1/2) alpha phi1'^2 + (1/2) beta phi1^2 with alpha = {inline(alpha)} and beta = "
        f"{inline(beta)}.",
        "",
        how=How("substitute", (energy.tag, solved.tag), args=(p2, w2)),
    )
    rate = section.add(
        eq(w1 * (alpha * a1 + beta * p1), 0),
        f"Differentiating ({one.tag}) in time: {energy_words}.",
        "(M6)",
        how=How("differentiate in time", (one.tag,), given=(conserved_energy,)),
    )
    divided = section.add(
        eq(alpha * a1 + beta * p1, 0),
        f"Dividing ({rate.tag}) by {inline(w1)} (not zero while the bodies move).",
        "",
        how=How("divide", (rate.tag,), args=(w1,)),
    )
    omega2 = tidy(sp.cancel(beta / alpha))
    result.system_equation = eq(a1 + omega2 * p1, 0)
    standard = section.add(
        result.system_equation,
        f"Dividing ({divided.tag}) by alpha: the equation of motion of the whole system.",
        "paper (QQ1)",
        how=How("rearrange", (divided.tag,)),
    )
    section.add(
        eq(OMEGA2, omega2),
        f"Reading off the coefficient of ({standard.tag}): the squared frequency.",
        "paper (QQQ1)",
        how=How("read off", (standard.tag,), law=eq(a1 + OMEGA2 * p1, 0)),
    )
    result.omega2 = [omega2]
    result.extras["ratio"] = ratio
    result.extras["conserved"] = momentum
    lever = single_spring_lever(sym)
    if lever is not None:
        _paper_route(section, sym, result, lever, ratio, solved.tag)
    return result


def _paper_route(
    section: Section,
    sym: SymbolicSystem,
    result: MethodResult,
    lever: list[sp.Expr],
    ratio: sp.Expr,
    solved_tag: str,
) -> None:
    """The paper's route: the largest speeds from the two conservation laws, then
    Omega = (v1 + v2)/A and the amplitudes."""
    tags = setup_tags(sym)
    J = [b.J for b in sym.bodies]
    amplitude = sp.Symbol("A", positive=True)
    rates = [sp.Symbol("Phidot_" + b.label, positive=True) for b in sym.bodies]
    k = sym.springs[0].k
    ratio_abs = sp.Abs(ratio)
    turning = all(b.rolls for b in sym.bodies)
    speeds_word = "angular velocities" if turning else "rates (speeds for a slider)"
    balance = section.add(
        eq(k * amplitude**2 / 2, J[0] * rates[0] ** 2 / 2 + J[1] * rates[1] ** 2 / 2),
        "The paper's route. Energy is conserved between two instants: at the largest "
        "deformation A of the spring the bodies stop (all energy in the spring); at the "
        "undeformed spring all of it is kinetic, and the rates are largest (Phi').",
        "paper (mu)",
        how=GIVEN,
    )
    reduced = section.add(
        eq(k * amplitude**2 / 2, sp.factor(J[0] + J[1] * ratio**2) * rates[0] ** 2 / 2),
        (
            f"Substituting Phi2' = {inline(ratio_abs)} Phi1', the relation of ({solved_tag}) for "
            if ratio_abs != 1
            else f"Substituting Phi2' = Phi1', the relation of ({solved_tag}) for "
        )
        + f"the largest {speeds_word} (in magnitude), into ({balance.tag}).",
        "paper (nu)",
        how=How(
            "substitute",
            (balance.tag,),
            args=(rates[1],),
            given=(eq(rates[1], ratio_abs * rates[0]),),
        ),
    )
    rate1 = _sqrt_form(sp.factor(amplitude * sp.sqrt(sp.cancel(k / (J[0] + J[1] * ratio**2)))))
    top = section.add(
        eq(rates[0], rate1),
        f"Solving ({reduced.tag}) for Phi1' (the positive root).",
        "",
        how=How("solve", (reduced.tag,), args=(rates[0],)),
    )
    speeds = [
        _sqrt_form(sp.factor(sp.cancel(sym.bodies[0].s * rate1))),
        _sqrt_form(sp.factor(sp.cancel(sym.bodies[1].s * ratio_abs * rate1))),
    ]
    v_syms = [sp.Symbol(f"v_{b.label}", positive=True) for b in sym.bodies]
    speed_law = [
        eq(v_syms[0], sym.bodies[0].s * rates[0]),
        eq(v_syms[1], sym.bodies[1].s * ratio_abs * rates[0]),
    ]
    fast = section.add(
        [eq(v_syms[i], _root_display(speeds[i], amplitude)) for i in range(2)],
        f"The largest centre speeds v_i = R_i Phi_i'{_ref(tags, 'rates')}"
        + ("" if turning else " (a slider: v_i = Phi_i', its largest speed)")
        + ", with Phi2' = "
        + (f"{inline(ratio_abs)} Phi1'" if ratio_abs != 1 else "Phi1'")
        + f" and Phi1' of ({top.tag}).",
        "paper (om), (pi)",
        how=How("substitute", (top.tag,), args=(rates[0],), law=speed_law),
    )
    deformation = sp.Add(*[sp.Abs(lever[i]) / sym.bodies[i].s * v_syms[i] for i in range(2)])
    omega = _sqrt_form(
        sp.factor(sp.cancel(deformation.subs(dict(zip(v_syms, speeds, strict=True))) / amplitude))
    )
    omega_sym = sp.Symbol("Omega", positive=True)
    centres = is_papers_fig2(sym)
    summed = fast
    if centres:
        # the algebra from (om), (pi) to Omega: v2 = rho v1 with rho rational (the ratio of the
        # rates times R2/R1), so v1 + v2 = (1 + rho) v1 and (1 + rho) goes under v1's root
        rho = sp.cancel(speeds[1] / speeds[0])
        if not rho.has(sp.Pow) or all(p.exp.is_Integer for p in rho.atoms(sp.Pow)):
            one_plus = sp.factor(1 + rho)
            summed = section.add(
                eq(v_syms[0] + v_syms[1], sp.Mul(one_plus, v_syms[0], evaluate=False)),
                f"Adding the speeds of ({fast.tag}): their ratio v2/v1 = {inline(rho)} is that of "
                f"the rates ({solved_tag}) times R_2/R_1, a ratio free of roots, so the sum is "
                "(1 + v2/v1) v1, the deformation's rate at the undeformed spring (the centres "
                "approach each other).",
                "paper Ω = (v1+v2)/A",
                how=How("evaluate", (fast.tag,)),
            )
            under_root = sp.factor(sp.cancel(one_plus**2 * speeds[0] ** 2 / amplitude**2))
            section.add(
                [
                    eq(
                        omega_sym,
                        sp.Mul(
                            one_plus,
                            sp.Pow(
                                sp.factor(speeds[0] ** 2 / amplitude**2), sp.S.Half, evaluate=False
                            ),
                            evaluate=False,
                        ),
                    ),
                    eq(omega_sym, sp.Pow(under_root, sp.S.Half, evaluate=False)),
                    eq(OMEGA2, tidy(under_root)),
                ],
                "In a harmonic motion the largest rate of a coordinate is its amplitude times "
                "Omega: the spring's deformation has amplitude A and largest rate v1 + v2, so "
                f"Omega = (v1 + v2)/A, with ({summed.tag}) and v1 of ({fast.tag}); the factor "
                "squared goes under the root, and the root's content simplifies to the "
                "(QQQ1) of the other methods. Isochronous: A drops out.",
                "paper Ω = (v1+v2)/A, (QQQ1)",
                how=How(
                    "substitute",
                    (summed.tag, fast.tag),
                    args=(v_syms[0] + v_syms[1], v_syms[0]),
                    law=[eq(omega_sym, (v_syms[0] + v_syms[1]) / amplitude)] * 2
                    + [eq(OMEGA2, ((v_syms[0] + v_syms[1]) / amplitude) ** 2)],
                ),
            )
    if summed is fast:
        section.add(
            eq(omega_sym, omega),
            "In a harmonic motion the largest rate of a coordinate is its amplitude times Omega; "
            "the spring's deformation has amplitude A and, at the undeformed spring, the rate "
            + (
                "v1 + v2 (the centres approach each other): Omega = (v1 + v2)/A"
                if centres
                else "sum |b_i| v_i / R_i (b_i the lever arms about the contacts): Omega = that / A"
            )
            + f", with v_i of ({fast.tag}). Isochronous: A drops out.",
            "paper Omega = (v1+v2)/A",
            how=How(
                "substitute",
                (fast.tag,),
                args=tuple(v_syms),
                law=eq(omega_sym, deformation / amplitude),
            ),
        )
    amplitudes = [sp.factor(sp.cancel(v / omega)) for v in speeds]
    a_syms = [sp.Symbol(f"A_{b.label}", positive=True) for b in sym.bodies]
    section.add(
        [eq(a_syms[i], amplitudes[i]) for i in range(2)],
        "The centres' amplitudes about the stationary point, A_i = v_i / Omega (harmonic "
        "motion again).",
        "paper A1, A2 (Sec. 5.2)",
        how=How(
            "substitute",
            (fast.tag,),
            args=(*v_syms, omega_sym),
            law=[eq(a_syms[i], v_syms[i] / omega_sym) for i in range(2)],
            given=(eq(omega_sym, omega),),
        ),
    )
    result.extras.update(speeds=speeds, omega=omega, amplitudes=amplitudes, amplitude=amplitude)


def _ref(tags: dict[str, str], key: str) -> str:
    """' (S5)': a reference to a setup step, or '' when the system has none of that kind."""
    return f" ({tags[key]})" if key in tags else ""


def _root_display(expr: sp.Expr, factor: sp.Symbol) -> sp.Expr:
    """``factor * sqrt(rest)`` kept as one unevaluated root, as the paper prints (om), (pi)."""
    rest = sp.factor(sp.cancel(sp.expand(expr**2) / factor**2))
    return sp.Mul(factor, sp.Pow(rest, sp.S.Half, evaluate=False), evaluate=False)


def _sqrt_form(expr: sp.Expr) -> sp.Expr:
    """A positive expression as one square root, sqrt(expr^2) (SymPy takes positive factors
    out again): A sqrt(3 k m2/(2 m1 (4 m1 + 3 m2))) rather than a product of roots."""
    expr = sp.sympify(expr)
    if expr.is_positive is False:
        return expr
    squared = sp.factor(sp.cancel(sp.expand(expr**2)))
    return sp.sqrt(squared)

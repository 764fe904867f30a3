r"""From each body's equations to the whole system's: the steps Newton, Lagrange and Hamilton share.

:func:`linearised_step` linearises the exact equations about the equilibrium (nothing to do when
they are linear already; :func:`why_not_linear` says when there is no oscillation to linearise
about). :func:`to_whole_system` then takes the bodies' linear equations to the equation of motion
of the whole system: with one zero mode, adding the equations weighted by it gives the conserved
momentum (paper (rel1), (g); (M14)) and the point that stays at rest, and for two bodies the
elimination of the second coordinate gives :math:`\ddot\varphi_1 + \Omega^2\varphi_1 = 0` (paper
(QQ1), (QQQ1)); otherwise the matrix form :math:`M\ddot q + Kq = 0` and the roots of the
characteristic equation :math:`\det(K - \Omega^2 M) = 0` (M12), in closed form where SymPy
finds them, else as numbers with the reason why.
Newton and Lagrange, whose equations are in the bodies' own coordinates, do both steps through
:func:`linearise_in_angles`; Hamilton calls :func:`to_whole_system` in its canonical coordinates.
"""

from __future__ import annotations

from typing import Any

import sympy as sp

from rollspring.analysis.derivation.frequencies import (
    MAX_FACTORED,
    OMEGA2,
    Frequencies,
    exact_values,
)
from rollspring.analysis.derivation.method import (
    MethodResult,
    cached_frequencies,
    content_free,
    coordinates_word,
    names_momentum,
    shown_scaled,
    tidy,
    tuple_text,
    zero_mode_in_angles,
)
from rollspring.analysis.derivation.setup import setup_tags, x_symbol, xdot_symbol
from rollspring.analysis.derivation.steps import (
    DEFINE,
    How,
    Section,
    eq,
    inline,
    named,
    pretty_name,
)
from rollspring.analysis.derivation.symbolic import SymbolicSystem

__all__ = [
    "PHAT",
    "linear_equations",
    "linearise_in_angles",
    "linearised_step",
    "to_whole_system",
    "why_not_linear",
]


#: The conserved momentum of the zero mode and its rate.
PHAT = sp.Symbol("Phat")


def _is_linear(sym: SymbolicSystem) -> bool:
    """The exact equations are linear in the coordinates (e.g. centre springs, level)."""
    if "linear" not in sym._cache:
        exact = sym.generalized_forces
        linear = sym.reference_forces - sym.stiffness_matrix * sp.Matrix(sym.q)
        sym._cache["linear"] = not sym.conditions and all(
            sp.expand(exact[i] - linear[i]) == 0 for i in range(sym.n)
        )
    result: bool = sym._cache["linear"]
    return result


def linear_equations(sym: SymbolicSystem) -> list[sp.Eq]:
    """J_i qdd_i = Q_i(0) - (K q)_i."""
    return sym.equations_of_motion(linear=True)


def why_not_linear(sym: SymbolicSystem) -> str:
    """Why a linearised derivation is not possible ('' when it is)."""
    if sym.reference != "equilibrium":
        return (
            "the system has no equilibrium near its initial placement, so there are no "
            "oscillations to linearise about"
        )
    n_zero = sym.zero_mode_count()
    if sym._cache.get("n_unstable"):
        return "the equilibrium is unstable (a negative stiffness): there is no oscillation"
    if n_zero == sym.n:
        return "nothing restores the equilibrium (every mode is a free motion): no oscillation"
    return ""


def linearised_step(
    section: Section, sym: SymbolicSystem, exact_tag: str, method: str
) -> tuple[str, list[sp.Eq]]:
    """The linear equations: the exact ones when they are linear, else their Taylor expansion."""
    equations = linear_equations(sym)
    if _is_linear(sym):
        return exact_tag, equations
    conditions = f", with the condition ({setup_tags(sym)['conditions']})" if sym.conditions else ""
    step = section.add(
        equations,
        f"Linearising ({exact_tag}) about the equilibrium (small angles: first order in the "
        f"coordinates){conditions}; the coefficients are the stiffness matrix K.",
        "(M12), (M13)" if method != "lagrange" else "paper (al), (be) (sign-corrected); (M12)",
        how=How("linearise", (exact_tag,)),
    )
    return step.tag, equations


def to_whole_system(
    section: Section,
    sym: SymbolicSystem,
    *,
    eqs_tag: str,
    eqs: list[sp.Eq],
    coords: list[sp.Symbol],
    velocities: list[sp.Symbol],
    accels: list[sp.Symbol],
    masses: list[sp.Expr],
    K: sp.Matrix,
    v0: sp.Matrix | None,
    frequencies: Frequencies,
    in_angles: bool,
    momentum_words: str = "",
    labels: tuple[str, ...] = (),
    names: str = "angles",
) -> dict[str, Any]:
    r"""From each body's linear equation (step ``eqs_tag``) to the whole system's: the conserved
    combination, the stationary point, the elimination and :math:`\Omega^2` (paper (rel1),
    (QQ1), (QQQ1)); or the matrix form and :math:`\det(K - \Omega^2 M) = 0`."""
    n = len(coords)
    out: dict[str, Any] = {}
    refs = labels or (
        "paper (w2)+(w22)",
        "paper (rel1), (g); (M14)",
        "paper (c); (M14)",
        "paper (QQ1)",
        "paper (QQQ1)",
        "paper (QQ1), first line",
    )
    tags = setup_tags(sym)
    section.rates[PHAT] = sp.Symbol("Phatdot")
    single_zero = v0 is not None and frequencies.n_zero == 1
    if single_zero:
        assert v0 is not None
        weighted = sp.Add(*[masses[i] * v0[i] * accels[i] for i in range(n)])
        shown = content_free(weighted, accels)
        factor = sp.factor(sp.cancel(weighted / shown))
        divided = shown_scaled("the sum", factor)
        added = section.add(
            eq(shown, 0),
            f"Adding the equations ({eqs_tag}) multiplied by v0 = {tuple_text(v0)}, the zero "
            "mode (K v0 = 0: moving along it stretches no spring): the spring terms cancel"
            f"{divided}.",
            refs[0],
            how=How("add", (eqs_tag,), args=tuple(v0)),
        )
        momentum = sp.Add(*[masses[i] * v0[i] * velocities[i] for i in range(n)])
        out["conserved"] = momentum
        integrated = section.add(
            eq(content_free(momentum, velocities), 0),
            f"Integrating ({added.tag}) over time: the momentum P̂ = v0^T M q' "
            + ("(the left side)" if factor == 1 else f"= {inline(factor)} times the left side")
            + " is conserved; the constant is its value at the start, zero for a start from "
            f"rest. {momentum_words[:1].upper() + momentum_words[1:]}.",
            refs[1],
            how=How("integrate in time", (added.tag,)),
        )
        if in_angles:
            weights = [sp.cancel(masses[i] * v0[i] / sym.bodies[i].s) for i in range(n)]
            common = _symbolic_gcd(weights)
            weights = [sp.cancel(w / common) for w in weights]
            out["weights"] = weights
            xs = [x_symbol(sym, i) for i in range(n)]
            xdots = [xdot_symbol(sym, i) for i in range(n)]
            rolling = [i for i, b in enumerate(sym.bodies) if b.rolls]
            centre = integrated
            if rolling:
                centre = section.add(
                    eq(sp.Add(*[w * x for w, x in zip(weights, xdots, strict=True)]), 0),
                    f"With the centres' velocities ({tags['rates']}) in ({integrated.tag}): a "
                    "weighted sum of the centre velocities vanishes.",
                    "",
                    how=How(
                        "substitute",
                        (integrated.tag, tags["rates"]),
                        args=tuple(sym.bodies[i].qd for i in rolling),
                    ),
                )
            per_mass = [sp.cancel(w / sym.bodies[i].m) for i, w in enumerate(weights)]
            is_cm = all(sp.cancel(sym.apply_conditions(r - per_mass[0])) == 0 for r in per_mass[1:])
            verdict = (
                "this point stays at rest; here it is the centre of mass (the weights are "
                "proportional to the masses)"
                if is_cm
                else "this point, not the centre of mass, stays at rest"
            )
            section.add(
                eq(
                    sp.Symbol("Xhat"),
                    sp.Add(*[w * x for w, x in zip(weights, xs, strict=True)]) / sp.Add(*weights),
                ),
                f"Define the point X̂ whose velocity is the left side of ({centre.tag}) over the "
                f"sum of the weights: {verdict}.",
                refs[2],
                how=DEFINE,
            )
        if n == 2 and v0[0] != 0 and v0[1] != 0:
            position = sp.Add(*[masses[i] * v0[i] * coords[i] for i in range(n)])
            again = section.add(
                eq(content_free(position, coords), 0),
                f"Integrating ({integrated.tag}) again. The constant is the left side's value "
                "at the start; a uniform shift along the zero mode is an equilibrium too, and of "
                f"these equilibria the {names} are measured from the one that makes it zero "
                "(the stationary point at the origin).",
                "",
                how=How("integrate in time", (integrated.tag,)),
            )
            ratio = sp.cancel(-masses[0] * v0[0] / (masses[1] * v0[1]))
            out["ratio"] = ratio
            solved = out["solved_step"] = section.add(
                eq(coords[1], ratio * coords[0]),
                f"Solving ({again.tag}) for {inline(coords[1])}.",
                "",
                how=How("solve", (again.tag,), args=(coords[1],)),
            )
            rhs = sp.factor(eqs[0].rhs.subs(coords[1], ratio * coords[0]))
            substituted = section.add(
                eq(eqs[0].lhs, rhs),
                f"Substituting ({solved.tag}) into the first equation of ({eqs_tag}).",
                refs[5],
                how=How("substitute", (f"{eqs_tag}:1", solved.tag), args=(coords[1],)),
            )
            omega2 = tidy(sp.cancel((K[0, 0] + K[0, 1] * ratio) / masses[0]))
            out["system_equation"] = eq(accels[0] + omega2 * coords[0], 0)
            standard = section.add(
                out["system_equation"],
                _to_the_left(substituted.tag, masses[0])
                + ": the equation of motion of the whole system, a simple harmonic oscillation.",
                refs[3],
                how=How("rearrange", (substituted.tag,)),
            )
            out["omega2"] = [omega2]
            section.add(
                eq(OMEGA2, omega2),
                f"Reading off the coefficient: ({standard.tag}) has the form q'' + Omega^2 q = 0.",
                refs[4],
                how=How(
                    "read off",
                    (standard.tag,),
                    law=eq(accels[0] + OMEGA2 * coords[0], 0),
                ),
            )
            return out
    if n == 1:
        omega2 = tidy(sp.cancel(K[0, 0] / masses[0]))
        out["system_equation"] = eq(accels[0] + omega2 * coords[0], 0)
        out["omega2"] = [omega2] if frequencies.n_zero == 0 else []
        standard = section.add(
            out["system_equation"],
            "One body: "
            + _to_the_left(eqs_tag, masses[0], lower=True)
            + " gives the equation of motion.",
            "",
            how=How("rearrange", (eqs_tag,)),
        )
        section.add(
            eq(OMEGA2, omega2),
            f"Reading off the coefficient: ({standard.tag}) has the form q'' + Omega^2 q = 0.",
            "",
            how=How("read off", (standard.tag,), law=eq(accels[0] + OMEGA2 * coords[0], 0)),
        )
        return out
    mass = sp.diag(*masses)
    qvec, avec = sp.Matrix(coords), sp.Matrix(accels)
    constant = sp.Matrix(
        [sp.expand(item.lhs - item.rhs).subs(dict.fromkeys(coords + accels, 0)) for item in eqs]
    )
    full = eq(
        sp.MatAdd(
            sp.MatMul(mass, avec, evaluate=False),
            sp.MatMul(K, qvec, evaluate=False),
            evaluate=False,
        ),
        -constant if any(c != 0 for c in constant) else sp.zeros(n, 1),
        evaluate=False,
    )
    out["system_equation"] = eq(mass * avec + K * qvec, -constant)
    if n <= 8:
        matrix = section.add(
            full,
            f"The equations ({eqs_tag}) as one matrix equation: the equation of motion of the "
            "whole system.",
            "(M12)",
            how=How("matrix form", (eqs_tag,)),
            latex=rf"{sp.latex(mass)}{sp.latex(avec)} + {sp.latex(K)}{sp.latex(qvec)}"
            + (" = 0" if all(c == 0 for c in constant) else rf" = {sp.latex(-constant)}"),
        )
    else:
        matrix = section.add(
            full,
            f"The equations ({eqs_tag}) as one matrix equation, M q'' + K q = 0 ({n} coupled "
            f"equations; M and K of ({tags['mass']}), ({tags['stiffness']})).",
            "(M12)",
            how=How("matrix form", (eqs_tag,)),
            latex=r"M\ddot{q} + K q = 0",
        )
    if frequencies.characteristic is not None:
        # det(K - Omega^2 M) = (-1)^n det(M) det(Omega^2 I - M^-1 K), in powers of Omega^2
        scale = sp.Mul(*masses) * (-1) ** n
        polynomial = sp.expand(scale * frequencies.characteristic)
        if n <= 4:
            polynomial = sp.collect(polynomial, OMEGA2, sp.factor)
        char = section.add(
            eq(polynomial, 0),
            f"Normal modes: q = v cos(Omega t) in ({matrix.tag}) gives (K - Omega^2 M) v = 0, "
            "which has a solution v != 0 only where det(K - Omega^2 M) = 0, the characteristic "
            "equation.",
            "(M12)",
            how=How("characteristic equation", (matrix.tag,), args=(mass, K)),
        )
    else:
        char = section.add(
            eq(sp.Function("det")(sp.Symbol("K") - OMEGA2 * sp.Symbol("M")), 0),
            f"Normal modes: q = v cos(Omega t) in ({matrix.tag}) gives det(K - Omega^2 M) = 0, "
            f"a polynomial of degree {n} in Omega^2 "
            + (
                "(not expanded here: with the parameters as symbols it is a polynomial in "
                "every one of them)."
                if sym.symbolic
                else "(not expanded here)."
            ),
            "(M12)",
            how=How("characteristic equation", (matrix.tag,), args=(mass, K)),
        )
        if frequencies.at_values is not None and "values" in tags:
            values = exact_values(sym)
            mass_at, K_at = mass.xreplace(values), K.xreplace(values)
            scale = sp.Mul(*mass_at.diagonal()) * (-1) ** n
            char = section.add(
                eq(sp.expand(scale * frequencies.at_values), 0),
                f"The characteristic equation ({char.tag}) at the parameters' values "
                f"({tags['values']}): det(K - Omega^2 M) with the numbers in M and K.",
                "(M12)",
                how=How(
                    "characteristic equation", (char.tag, tags["values"]), args=(mass_at, K_at)
                ),
            )
    closed = [w for w in frequencies.omega2 if w is not None]
    roots = [eq(_mode_omega2(0), 0)] * (frequencies.n_zero > 0) + [
        eq(
            _mode_omega2(j + 1),
            w if w is not None else sp.Float(frequencies.numeric[j], 12),
        )
        for j, w in enumerate(frequencies.omega2)
    ]
    words = (
        f"The roots of ({char.tag}), the squared frequencies of the normal modes, numbered in "
        "parentheses (Omega_(n); Omega_i without them is body i's subsystem frequency)"
    )
    if frequencies.n_zero:
        words += (
            "; Omega_(0)^2 = 0 ("
            + ("a zero mode" if frequencies.n_zero == 1 else f"{frequencies.n_zero} zero modes")
            + ") is a free, uniform rolling with no restoring force"
        )
    words += _roots_words(frequencies, char.tag, len(closed))
    section.add(roots, words + ".", "", how=How("solve", (char.tag,), args=(OMEGA2,)))
    out["omega2"] = list(frequencies.omega2)
    return out


def linearise_in_angles(
    result: MethodResult,
    sym: SymbolicSystem,
    exact_tag: str,
    budget: float | None,
    labels: tuple[str, ...] = (),
) -> bool:
    """The end of the methods whose exact equations (step ``exact_tag``) are in the bodies' own
    coordinates (angles, lengths for sliders) with the inertias about the contact lines (Newton,
    Lagrange): :func:`linearised_step`, then :func:`to_whole_system`, kept in ``result``. False,
    with the reason in ``result.reason``, where there is no oscillation to linearise about."""
    reason = why_not_linear(sym)
    if reason:
        result.reason = "linearisation: " + reason
        return False
    section = result.section
    eqs_tag, equations = linearised_step(section, sym, exact_tag, result.name)
    result.equations = equations
    v0 = zero_mode_in_angles(sym)
    whole = to_whole_system(
        section,
        sym,
        eqs_tag=eqs_tag,
        eqs=equations,
        coords=sym.q,
        velocities=sym.qd,
        accels=sym.qdd,
        masses=[b.J for b in sym.bodies],
        K=sym.stiffness_matrix,
        v0=v0,
        frequencies=cached_frequencies(sym, budget),
        in_angles=True,
        momentum_words=names_momentum(sym, v0),
        names=coordinates_word(sym),
        labels=labels,
    )
    result.record(whole)
    return True


def _mode_omega2(n: int) -> sp.Symbol:
    """The squared frequency of normal mode n, printed Ω₍ₙ₎² (the paper's Ω_i are the
    subsystems' frequencies)."""
    return named(f"Omega_({n})^2", rf"\Omega_{{({n})}}^2", pretty_name(f"Omega_({n})^2"))


def _roots_words(frequencies: Frequencies, tag: str, closed: int) -> str:
    """What the roots step says about closed forms: none needed, why there are none, or which
    roots are exact (the factors of degree one or two of the characteristic polynomial)."""
    total = len(frequencies.omega2)
    if closed == total:
        return ""
    numbers = "given as numbers (the eigenvalues of M^-1 K, to 12 digits)"
    degree = frequencies.degree
    if frequencies.characteristic is None and degree > MAX_FACTORED:
        return (
            f". No closed form in the parameters: det(K - Omega^2 M) has degree {degree} in "
            "Omega^2 (zero roots taken out), and a polynomial of degree five or more has no "
            f"general formula for its roots; they are {numbers}"
        )
    if frequencies.factors:
        listed = ", ".join(map(str, frequencies.factors))
        if closed:
            return (
                f". ({tag}) factors over the rationals into factors of degree {listed}: the "
                "roots of those of degree one or two are exact, the others (no closed form "
                f"offered beyond degree two) {numbers}"
            )
        shape = (
            "is irreducible over the rationals"
            if len(frequencies.factors) == 1
            else f"factors over the rationals only into factors of degree {listed}"
        )
        general = (
            "a polynomial of degree five or more has no general formula for its roots"
            if max(frequencies.factors) > 4
            else "no closed form is offered beyond degree two"
        )
        return f". No closed form: ({tag}) has degree {degree} in Omega^2 and {shape}; " + (
            f"{general}, so its roots are {numbers}"
        )
    return " (closed forms where SymPy finds them, else the numbers)"


def _to_the_left(tag: str, factor: sp.Expr, *, lower: bool = False) -> str:
    """'Dividing (N10) by 2·R²·m₁ and bringing every term to the left'; 'Multiplying (N10)
    by 50 ...' for a number 1/50; 'Bringing every term of (N10) to the left' for 1."""
    factor = sp.sympify(factor)
    if factor == 1:
        words = f"Bringing every term of ({tag}) to the left"
    elif factor.is_Rational and factor.p == 1:
        words = f"Multiplying ({tag}) by {inline(1 / factor)} and bringing every term to the left"
    else:
        words = f"Dividing ({tag}) by {inline(factor)} and bringing every term to the left"
    return words[:1].lower() + words[1:] if lower else words


def _symbolic_gcd(values: list[sp.Expr]) -> sp.Expr:
    """The symbolic (non-numeric) common factor of expressions."""
    nonzero = [v for v in values if v != 0]
    if not nonzero:
        return sp.Integer(1)
    common = nonzero[0]
    for v in nonzero[1:]:
        common = sp.gcd(common, v)
    _, rest = sp.factor_terms(common).as_coeff_Mul()
    return rest if rest != 0 else sp.Integer(1)

r"""The five derivations of the equations of motion, in the paper's order of ideas.

Each method builds a :class:`MethodResult`: a numbered :class:`~.steps.Section` of steps, each
one following from earlier ones by one named operation (:class:`~.steps.How`), and its results
in a common form, so that they can be compared (:mod:`.crosscheck`): the linearised equations
:math:`J_i\ddot\varphi_i = \dots` of every body (in the angles), the exact ones where the method
gives them, and the squared frequencies. The constraint relations, the inertias about the
contact lines, T, V, M and K are derived once, in the setup (:mod:`.setup`), and referred to.

* ``newton``: torques about the contact points (paper Sec. 2, 4.1; (M7));
* ``conservation``: energy and the conserved momentum of the zero mode (Sec. 4.2); needs a
  single oscillating degree of freedom;
* ``lagrange``: Euler-Lagrange equations of :math:`\mathcal L = T - V` (Sec. 4.3; (M5)),
  checked against ``sympy.physics.mechanics.LagrangesMethod``;
* ``natural-frequencies``: subsystem frequencies :math:`\Omega_i^2 = K_{ii}/J_i` and the sum
  rule (Sec. 4.4, App. B, C); needs two bodies with a zero mode (rank-1 K);
* ``hamilton``: canonical coordinates :math:`q_i = \sqrt{J_i/m_i}\,\varphi_i`,
  :math:`p_i = m_i\dot q_i` (Sec. 4.5; (M6)).
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass, field, replace
from typing import Any

import sympy as sp

from rollspring.analysis.derivation.frequencies import (
    MAX_FACTORED,
    OMEGA2,
    BudgetExceeded,
    Frequencies,
    exact_values,
    normal_frequencies,
    time_budget,
)
from rollspring.analysis.derivation.setup import (
    length_symbols,
    rate_symbols,
    setup_tags,
    x_symbol,
    xdot_symbol,
)
from rollspring.analysis.derivation.steps import (
    DEFINE,
    GIVEN,
    How,
    Section,
    Step,
    eq,
    inline,
    named,
    pretty_name,
)
from rollspring.analysis.derivation.symbolic import SymbolicSystem, _derivatives_at_reference

__all__ = ["METHODS", "MethodResult", "run_method"]

#: Method names, in the paper's order.
METHODS = ("newton", "conservation", "lagrange", "natural-frequencies", "hamilton")

TITLES = {
    "newton": "Dynamic equations (Newton: torques about the contact points)",
    "conservation": "Conservation laws (energy and the zero mode's momentum)",
    "lagrange": "Euler-Lagrange equations",
    "natural-frequencies": "Natural frequencies of the subsystems",
    "hamilton": "Hamilton's equations",
}

PREFIXES = {
    "newton": "N",
    "conservation": "E",
    "lagrange": "L",
    "natural-frequencies": "F",
    "hamilton": "H",
}

PAPER_SECTIONS = {
    "newton": "paper Sec. 2 and 4.1",
    "conservation": "paper Sec. 4.2",
    "lagrange": "paper Sec. 4.3",
    "natural-frequencies": "paper Sec. 4.4, App. B and C",
    "hamilton": "paper Sec. 4.5",
}

#: The conserved momentum of the zero mode and its rate.
PHAT = sp.Symbol("Phat")


@dataclass
class MethodResult:
    r"""One method's derivation and its results.

    ``equations``: the linearised equations of motion :math:`J_i\ddot\varphi_i = \dots` of every
    body (in the angles; None where the method does not give them); ``nonlinear``: the exact
    ones (None where the method is linear only); ``system_equation``: the equation of motion of
    the whole system (:math:`\ddot\varphi_1 + \Omega^2\varphi_1 = 0`, or the matrix form);
    ``omega2``: the squared frequencies of the oscillating modes (closed forms; None entries
    where there is none); ``extras``: named intermediate results (tests, paper checks).
    """

    name: str
    title: str
    applies: bool
    reason: str
    section: Section
    equations: list[sp.Eq] | None = None
    nonlinear: list[sp.Eq] | None = None
    system_equation: Any = None
    omega2: list[sp.Expr | None] = field(default_factory=list)
    extras: dict[str, Any] = field(default_factory=dict)

    @property
    def steps(self) -> list[Step]:
        """The steps of the derivation."""
        return self.section.steps


def _section(sym: SymbolicSystem, name: str, title: str | None = None) -> Section:
    return Section(title or TITLES[name], prefix=PREFIXES[name], rates=dict(rate_symbols(sym)))


# -- shared pieces ---------------------------------------------------------------------------------


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


def _frequencies(sym: SymbolicSystem, budget: float | None) -> Frequencies:
    key = "frequencies"
    if key not in sym._cache:
        sym._cache[key] = normal_frequencies(sym, budget=budget)
    result: Frequencies = sym._cache[key]
    return result


def _ref(tags: dict[str, str], key: str) -> str:
    """' (S5)': a reference to a setup step, or '' when the system has none of that kind."""
    return f" ({tags[key]})" if key in tags else ""


def _coordinates_word(sym: SymbolicSystem) -> str:
    """'angles' when every body rolls, else 'coordinates' (a slider's is a displacement)."""
    return "angles" if all(b.rolls for b in sym.bodies) else "coordinates"


def _tuple_text(values: Sequence[sp.Expr]) -> str:
    return "(" + ", ".join(inline(v) for v in values) + ")"


def _names_momentum(sym: SymbolicSystem, v0: sp.Matrix | None) -> str:
    """What the conserved momentum v0^T M qdot (v0 in the angles) is, in words: the total
    angular momentum about a point of the floor only when every body rolls on one floor and
    the weights v0_i are equal (docs/physics.md Sec. 6)."""
    if v0 is None:
        return ""
    bodies = sym.bodies
    tracks = {b.track_height for b in sym.system.bodies}
    ratios = [sp.cancel(v0[i] / v0[0]) for i in range(sym.n)]
    plain = all(sp.cancel(r - 1) == 0 for r in ratios)
    equal = plain or all(sp.cancel(sym.apply_conditions(r) - 1) == 0 for r in ratios)
    condition = (
        ""
        if plain or not equal
        else f" (they are, with the condition ({setup_tags(sym)['conditions']}))"
    )
    if equal and all(b.rolls for b in bodies) and len(tracks) == 1:
        return (
            f"here the weights v0_i are equal{condition} and the bodies roll on one floor, so "
            "P̂ is the total angular momentum about any fixed point O of the floor, L_O = "
            f"sum J_i phi_i' (clockwise; {_paper_sum(sym.n)})"
        )
    if equal and not any(b.rolls for b in bodies):
        return (
            f"here every body slides and the weights are equal{condition}: P̂ is the total momentum"
        )
    why = (
        "the weights v0_i are not all equal"
        if not equal
        else "the bodies roll on floors of different heights"
        if len(tracks) > 1
        else "not every body rolls"
    )
    return (
        "P̂ is not the total angular momentum L_O = sum J_i phi_i' about a point of the floor "
        f"({why}): it is the momentum of the free rolling motion along v0"
    )


def _mode_omega2(n: int) -> sp.Symbol:
    """The squared frequency of normal mode n, printed Ω₍ₙ₎² (the paper's Ω_i are the
    subsystems' frequencies)."""
    return named(f"Omega_({n})^2", rf"\Omega_{{({n})}}^2", pretty_name(f"Omega_({n})^2"))


def _paper_sum(n: int) -> str:
    """The paper's L_1 + L_2 for two bodies; L_1 + L_2 + L_3 (and so on) otherwise."""
    terms = " + ".join(f"L_{i + 1}" for i in range(n)) if n <= 4 else f"L_1 + ... + L_{n}"
    return "the paper's L_1 + L_2" if n == 2 else f"{terms}, the paper's L_1 + L_2 for {n} bodies"


def _whole_system(
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
        shown = _content_free(weighted, accels)
        factor = sp.factor(sp.cancel(weighted / shown))
        divided = _shown_scaled("the sum", factor)
        added = section.add(
            eq(shown, 0),
            f"Adding the equations ({eqs_tag}) multiplied by v0 = {_tuple_text(v0)}, the zero "
            "mode (K v0 = 0: moving along it stretches no spring): the spring terms cancel"
            f"{divided}.",
            refs[0],
            how=How("add", (eqs_tag,), args=tuple(v0)),
        )
        momentum = sp.Add(*[masses[i] * v0[i] * velocities[i] for i in range(n)])
        out["conserved"] = momentum
        integrated = section.add(
            eq(_content_free(momentum, velocities), 0),
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
                eq(_content_free(position, coords), 0),
                f"Integrating ({integrated.tag}) again; the constant is zero when the "
                f"{names} are measured from the stationary point (its choice of origin).",
                "",
                how=How("integrate in time", (integrated.tag,)),
            )
            ratio = sp.cancel(-masses[0] * v0[0] / (masses[1] * v0[1]))
            out["ratio"] = ratio
            solved = section.add(
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
            omega2 = _tidy(sp.cancel((K[0, 0] + K[0, 1] * ratio) / masses[0]))
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
        omega2 = _tidy(sp.cancel(K[0, 0] / masses[0]))
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


def _whole_system_in_angles(
    section: Section,
    sym: SymbolicSystem,
    eqs_tag: str,
    equations: list[sp.Eq],
    budget: float | None,
    labels: tuple[str, ...] = (),
) -> dict[str, Any]:
    """:func:`_whole_system` for the methods whose equations are in the bodies' own coordinates
    (angles, lengths for sliders) with the inertias about the contact lines (Newton, Lagrange)."""
    v0 = _v0(sym)
    return _whole_system(
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
        frequencies=_frequencies(sym, budget),
        in_angles=True,
        momentum_words=_names_momentum(sym, v0),
        names=_coordinates_word(sym),
        labels=labels,
    )


def _shown_scaled(what: str, factor: sp.Expr) -> str:
    """'; the sum is shown multiplied by 200' when the displayed equation is ``what``/factor
    (an equation = 0 freed of its constant factor), '' when the factor is 1."""
    if factor == 1:
        return ""
    if factor.is_Rational and factor.p == 1:
        return f"; {what} is shown multiplied by {inline(1 / factor)}"
    return f"; {what} is shown divided by its common factor {inline(factor)}"


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


def _content_free(expr: sp.Expr, variables: list[sp.Symbol]) -> sp.Expr:
    """expr with its variable-free factor dropped (an expression equated to zero)."""
    expr = sp.factor_terms(sp.expand(expr))
    if isinstance(expr, sp.Mul):
        kept = [f for f in expr.args if f.has(*variables)]
        return sp.Mul(*kept) if kept else expr
    return expr


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


def _tidy(expr: sp.Expr) -> sp.Expr:
    """A short form of a parameter expression (Omega^2 and the like)."""
    expr = sp.sympify(expr)
    if sp.count_ops(expr) > 200:
        return expr
    first = _first_symbol(expr)
    candidates = [
        expr,
        sp.factor(expr),
        sp.apart(sp.cancel(expr), first) if first is not None else expr,
        sp.expand(expr),
    ]
    return min(candidates, key=lambda e: (sp.count_ops(e), len(str(e))))


def _first_symbol(expr: sp.Expr) -> sp.Symbol | None:
    masses = sorted((s for s in expr.free_symbols if s.name.startswith("m")), key=str)
    return masses[0] if masses else None


def _zero_mode_2(K: sp.Matrix) -> sp.Matrix | None:
    """The null vector of a rank-1 symmetric 2x2 matrix, normalised to v/(v_1 v_2)."""
    if K[1, 1] != 0:
        v = sp.Matrix([K[1, 1], -K[0, 1]])
    elif K[0, 0] != 0:
        v = sp.Matrix([-K[0, 1], K[0, 0]])
    else:
        return None
    if v[0] != 0 and v[1] != 0:
        v = sp.Matrix([sp.cancel(1 / v[1]), sp.cancel(1 / v[0])])
    return v


def _v0(sym: SymbolicSystem) -> sp.Matrix | None:
    """The zero mode (K v0 = 0) in the angles, its first non-zero entry 1 (None unless there
    is exactly one)."""
    if sym.zero_mode_count() != 1:
        return None
    if sym.n == 2:
        return _normalised(_zero_mode_2(sym.stiffness_matrix))
    return _normalised(sym.zero_mode())


def _normalised(v: sp.Matrix | None) -> sp.Matrix | None:
    """v scaled so that its first non-zero entry is 1."""
    if v is None:
        return None
    first = next((x for x in v if x != 0), sp.Integer(1))
    return v.applyfunc(lambda x: sp.factor(sp.cancel(x / first)))


def _applicable_linear(sym: SymbolicSystem) -> str:
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


def _linearised_step(
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


# -- the methods -----------------------------------------------------------------------------------


def newton(sym: SymbolicSystem, budget: float | None) -> MethodResult:
    """Torques of the applied forces about the contact points."""
    section = _section(sym, "newton")
    tags = setup_tags(sym)
    lengths = length_symbols(sym)
    forces = [
        sp.Symbol("F" if len(sym.springs) == 1 else f"F_{s.index + 1}", real=True)
        for s in sym.springs
    ]
    if sym.springs:
        tension = section.add(
            [
                eq(F, s.k * sp.factor_terms(s.length - s.L))
                for F, s in zip(forces, sym.springs, strict=True)
            ],
            "Spring forces by Hooke's law, F = k(l - L) (positive when stretched: it pulls "
            f"both ends towards each other), with the lengths l of ({tags['lengths']}).",
            "paper F = k(R phi2 - R phi1)",
            how=How(
                "substitute",
                (tags["lengths"],),
                args=tuple(lengths),
                law=[
                    eq(F, s.k * (name - s.L))
                    for F, name, s in zip(forces, lengths, sym.springs, strict=True)
                ],
            ),
        )
    law = []
    for i, b in enumerate(sym.bodies):
        terms = []
        for F, levers in zip(forces, sym.lever_arms, strict=True):
            if i in levers:
                terms.append(-F * _short(levers[i]))
        for f in sym.forces:
            if f.body == i:
                dx, dy = f.attachment.velocity_per_rate(b)
                terms.append(f.Fx * dx + f.Fy * dy)
        law.append(eq(b.J * b.qdd, sp.Add(*terms)))
    rolling = any(b.rolls for b in sym.bodies)
    why = (
        "For each rolling body, the torque equation about its contact point K: J phi'' = the "
        f"clockwise torque of the applied forces, with J of ({tags.get('inertia', '')}). It "
        "holds although K accelerates, because K's acceleration (R phi'^2, straight up) points "
        "through the centre, the centre of mass; friction and the normal force act at K and "
        "have no torque about it. The spring's torque is its force times its lever arm about K."
        if rolling
        else "Newton's second law for each slider: m x'' = the horizontal applied force."
    )
    if rolling and any(not b.rolls for b in sym.bodies):
        why += " A slider: m x'' = the horizontal applied force."
    law_step = section.add(law, why, "paper (e), (f), (a), (b); (M7)", how=GIVEN)
    torques = sym.contact_torques
    nonlinear = [eq(b.J * b.qdd, _short(torques[i])) for i, b in enumerate(sym.bodies)]
    exact_tag = law_step.tag
    if sym.springs:
        exact_tag = section.add(
            nonlinear,
            f"Substituting the spring forces ({tension.tag}) into ({law_step.tag}): each "
            "body's equation of motion, exact at any amplitude"
            + (" (while the bodies roll)." if rolling else "."),
            "paper (w2), (w22); (M7)",
            how=How("substitute", (law_step.tag, tension.tag), args=tuple(forces)),
        ).tag
    result = MethodResult("newton", TITLES["newton"], True, "", section, nonlinear=nonlinear)
    reason = _applicable_linear(sym)
    if reason:
        result.reason = "linearisation: " + reason
        return result
    eqs_tag, equations = _linearised_step(section, sym, exact_tag, "newton")
    result.equations = equations
    out = _whole_system_in_angles(section, sym, eqs_tag, equations, budget)
    result.system_equation = out.get("system_equation")
    result.omega2 = out.get("omega2", [])
    result.extras.update(out)
    return result


def conservation(sym: SymbolicSystem, budget: float | None) -> MethodResult:
    """Energy and the conserved momentum of the zero mode (one oscillating degree of
    freedom)."""
    section = _section(sym, "conservation")
    result = MethodResult("conservation", TITLES["conservation"], False, "", section)
    reason = _applicable_linear(sym)
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
    v0 = _v0(sym) if not reason and sym.n == 2 else None
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
        eq(esym, sym.kinetic + _short(quad)),
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
        omega2 = _tidy(sp.cancel(K[0, 0] / J[0]))
        result.system_equation = eq(b.qdd + omega2 * b.q, 0)
        standard = section.add(
            result.system_equation,
            f"Dividing ({divided.tag}) by J and bringing every term to the left: the equation "
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
    angular = _names_momentum(sym, v0)
    if angular.startswith("here the weights v0_i are equal"):
        section.title = "Conservation of energy and angular momentum"
    else:
        section.title = "Conservation of energy and of the zero mode's momentum"
    result.title = section.title
    p1, p2 = sym.q
    w1, w2 = sym.qd
    a1 = sym.qdd[0]
    momentum = sp.Add(*[J[i] * v0[i] * sym.qd[i] for i in range(2)])
    shown = _content_free(momentum, sym.qd)
    scaled = _shown_scaled("P̂", sp.factor(sp.cancel(momentum / shown)))
    conserved = section.add(
        eq(shown, 0),
        f"The momentum P̂ = v0^T M phi' with the zero mode v0 = {_tuple_text(v0)} (K v0 = 0) "
        "is conserved: its rate is v0^T Q = -v0^T K phi = 0, the "
        + ("torques about the contact points" if any(rolls) else "spring forces")
        + f" cancel in it. It is zero for a start from rest{scaled}; {angular}.",
        "paper (nu), (rel1); (M14)",
        how=GIVEN,
    )
    again = section.add(
        eq(_content_free(sp.Add(*[J[i] * v0[i] * sym.q[i] for i in range(2)]), sym.q), 0),
        f"Integrating ({conserved.tag}) over time; the constant is zero when the "
        f"{_coordinates_word(sym)} are measured from the stationary point.",
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
    omega2 = _tidy(sp.cancel(beta / alpha))
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
    lever = _single_spring_lever(sym)
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
    centres = _is_papers_fig2(sym)
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
        "paper A1, A2 (Sec. 4.2)",
        how=How(
            "substitute",
            (fast.tag,),
            args=(*v_syms, omega_sym),
            law=[eq(a_syms[i], v_syms[i] / omega_sym) for i in range(2)],
            given=(eq(omega_sym, omega),),
        ),
    )
    result.extras.update(speeds=speeds, omega=omega, amplitudes=amplitudes, amplitude=amplitude)


def _single_spring_lever(sym: SymbolicSystem) -> list[sp.Expr] | None:
    """Lever arms b_i = dl/dphi_i at the reference for one unstressed spring between the two
    bodies (else None): e . dP/dphi_i with e the spring's direction there (M2)."""
    if len(sym.springs) != 1 or sym.forces or sym.n != 2:
        return None
    spring = sym.springs[0]
    if not spring.relaxed or any(a is None for a in spring.attachments):
        return None
    ex, ey = spring.e0
    out = [sp.Integer(0), sp.Integer(0)]
    for sign, at in zip((-1, 1), spring.attachments, strict=True):
        assert at is not None
        (dx, dy), _ = _derivatives_at_reference(at, sym.bodies[at.body])
        out[at.body] += sign * (ex * dx + ey * dy)
    return [sp.factor(b) for b in out]


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


def lagrange(sym: SymbolicSystem, budget: float | None) -> MethodResult:
    """Euler-Lagrange equations of L = T - V; the structure route and LagrangesMethod."""
    section = _section(sym, "lagrange")
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
        f"Differentiating ({momenta.tag}) in time (J is constant: the mass matrix does not "
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
        [eq(forces_names[i], _short(-gradient[i])) for i in range(sym.n)],
        f"The generalised forces dL/dphi_i = -dV/dphi_i, differentiating ({lagrangian.tag}) "
        f"with V of ({tags['potential']}).",
        "(M7)",
        how=How("differentiate", (lagrangian.tag, tags["potential"]), args=tuple(sym.q)),
    )
    nonlinear = [eq(b.J * b.qdd, _short(-gradient[i])) for i, b in enumerate(sym.bodies)]
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
    result = MethodResult("lagrange", TITLES["lagrange"], True, "", section, nonlinear=nonlinear)
    result.extras["mechanics"] = mechanics_lagrange_check(sym, budget=budget)
    reason = _applicable_linear(sym)
    if reason:
        result.reason = "linearisation: " + reason
        return result
    eqs_tag, equations = _linearised_step(section, sym, exact.tag, "lagrange")
    result.equations = equations
    out = _whole_system_in_angles(
        section,
        sym,
        eqs_tag,
        equations,
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
    result.system_equation = out.get("system_equation")
    result.omega2 = out.get("omega2", [])
    result.extras.update(out)
    split = _spring_split(sym, _frequencies(sym, budget))
    if split is not None:
        section.add(
            [eq(sp.Symbol(f"k_{sym.bodies[i].label}", positive=True), split[i]) for i in range(2)],
            "The stiffnesses of the spring's two parts, on either side of the stationary point "
            "(the paper's k_1, k_2). Both parts carry the spring force F; with the stationary "
            "point fixed (the relation of the angles above), part i takes the share Omega_i^2 / "
            "Omega^2 of the deformation, where Omega_i^2 = K_ii/J_i is body i's frequency with "
            "the other body clamped (the subsystem frequency of the next method) and Omega^2 = "
            "Omega_1^2 + Omega_2^2. So k_i = F / (share_i x deformation) = k Omega^2 / Omega_i^2, "
            "and 1/k = 1/k_1 + 1/k_2 because the shares add up to 1.",
            "paper (k1), (k2), (part)",
            how=DEFINE,
        )
        result.extras["spring_split"] = split
    return result


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


def natural_frequencies(sym: SymbolicSystem, budget: float | None) -> MethodResult:
    """Subsystem frequencies (one body clamped) and the sum rule, for rank-1 K."""
    section = _section(sym, "natural-frequencies")
    result = MethodResult("natural-frequencies", TITLES["natural-frequencies"], False, "", section)
    reason = _applicable_linear(sym)
    if not reason:
        n_zero = sym.zero_mode_count()
        if sym.n > 2:
            reason = (
                f"{sym.n} bodies: the subsystem frequencies do not add up to a normal "
                "frequency (the sum rule needs two bodies and a rank-1 K); only the trace "
                "identity holds: the sum of the normal modes' Omega_(n)^2 is the sum of the "
                "subsystem frequencies Omega_i^2 = K_ii/J_i"
            )
        elif sym.n == 2 and n_zero != 1:
            reason = (
                "no zero mode (a wall or a pre-tensioned spring): K has rank 2 and "
                "no normal mode's Omega^2 is Omega_1^2 + Omega_2^2 (Omega_i^2 = K_ii/J_i, body "
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
    clamped = [_tidy(sp.cancel(K[i, i] / J[i])) for i in range(sym.n)]
    energies = [sp.Symbol(f"E_{b.label}") for b in sym.bodies]
    sub_steps = []
    for i, b in enumerate(sym.bodies):
        others = [j for j in range(sym.n) if j != i]
        held = [eq(sym.q[j], 0) for j in others] + [eq(sym.qd[j], 0) for j in others]
        quad_i = sym.quadratic_potential.subs({sym.q[j]: 0 for j in others})
        sub_steps.append(
            section.add(
                eq(energies[i], J[i] * b.qd**2 / 2 + _short(quad_i)),
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
    omega2 = _tidy(clamped[0] + clamped[1])
    section.add(
        eq(OMEGA2, sp.Add(omegas2[0], omegas2[1], evaluate=False)),
        f"The non-zero root of ({char.tag}): dividing by J_1 J_2 Omega^2 leaves Omega^2 = "
        f"K_11/J_1 + K_22/J_2, the sum of the subsystems' ({natural.tag}).",
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
            "coordinates q_i = sqrt(J_i/m_i) phi_i of Hamilton's method (paper Sec. 4.5, App. "
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
        "Each body's equation of motion J_i phi_i'' = -(K phi)_i rebuilt from the subsystems: "
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


def hamilton(sym: SymbolicSystem, budget: float | None) -> MethodResult:
    """Canonical coordinates q_i = sqrt(J_i/m_i) phi_i, p_i = m_i q_i'."""
    section = _section(sym, "hamilton")
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
        "q_i = sqrt(J_i/m_i) phi_i (a point transformation, hence canonical).",
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
        eq(hsym, kinetic_q + _short(potential_q)),
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
        + [eq(-pdots[i], _short(dV[i])) for i in range(n)],
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
        [eq(m[i] * qdds[i], _short(-dV[i])) for i in range(n)],
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
        nonlinear.append(eq(b.J * b.qdd, _short(sp.powsimp(rhs))))
    section.add(
        nonlinear,
        f"Back in the angles: q_i = sqrt(J_i/m_i) phi_i ({coordinates.tag}) in ({in_q.tag}), "
        "multiplied by sqrt(J_i/m_i), is J_i phi_i'' = -dV/dphi_i.",
        "(M7)",
        how=How("substitute", (in_q.tag, coordinates.tag), args=(*qs, *qdds)),
    )
    result = MethodResult("hamilton", TITLES["hamilton"], True, "", section, nonlinear=nonlinear)
    reason = _applicable_linear(sym)
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
    lever = _single_spring_lever(sym)
    how_quadratic = How("substitute", (tags["quadratic"], coordinates.tag), args=tuple(sym.q))
    if lever is not None and constant == 0 and linear_term == 0:
        k = sym.springs[0].k
        c = [sp.factor(sp.cancel(lever[i] / scale[i])) for i in range(2)]
        form = k / 2 * (c[0] * qs[0] + c[1] * qs[1]) ** 2
        second = section.add(
            eq(vsym, form),
            f"V to second order ({tags['quadratic']}) in the canonical coordinates "
            f"({coordinates.tag}), as the paper writes it: (k/2)(c1 q1 + c2 q2)^2, c_i = b_i "
            "sqrt(m_i/J_i) with the lever arms b_i; in a common orientation of the angles c1 "
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
            "diag(sqrt(J_i/m_i)).",
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
    v0 = _v0(sym)
    v0q = (D * v0).applyfunc(sp.cancel) if v0 is not None else None
    if v0q is not None and n == 2:
        v0q = _normalised(_zero_mode_2(Kq)) or v0q
    # M_q^-1 K_q = D M^-1 K D^-1 is similar to M^-1 K: the same polynomial and roots
    freq = _frequencies(sym, budget)
    out = _whole_system(
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
            "in the original coordinates it is proportional to sum J_i v0_i phi_i' with v0 = "
            f"{_tuple_text(v0)} (q_i = sqrt(J_i/m_i) phi_i): "
            + _names_momentum(sym, v0).replace("P̂ is", "that sum is")
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
    result.system_equation = out.get("system_equation")
    result.omega2 = out.get("omega2", [])
    result.extras.update(out)
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


def _short(expr: sp.Expr) -> sp.Expr:
    """A compact form for display: factor small expressions, leave big ones alone."""
    expr = sp.sympify(expr)
    if any(not p.exp.is_Integer for p in expr.atoms(sp.Pow)):
        return expr  # roots (sqrt 2, a spring's length): factoring is slow and gains little
    if expr.count_ops() <= 60:
        try:
            return min([expr, sp.factor(expr)], key=sp.count_ops)
        except Exception:  # noqa: BLE001 - display only
            return expr
    return expr


_RUNNERS: dict[str, Callable[[SymbolicSystem, float | None], MethodResult]] = {
    "newton": newton,
    "conservation": conservation,
    "lagrange": lagrange,
    "natural-frequencies": natural_frequencies,
    "hamilton": hamilton,
}


def run_method(sym: SymbolicSystem, name: str, *, budget: float | None = 10.0) -> MethodResult:
    """Run one method by name (see :data:`METHODS`). The paper's equation labels name its
    Fig. 2 formulas (centres joined by a horizontal spring); for any other system they are
    shown as "cf. paper ... (Fig. 2 there)": the step is the same idea, not the paper's
    expression."""
    result = _RUNNERS[name](sym, budget)
    if not _is_papers_fig2(sym):
        result.section.steps[:] = [
            replace(step, ref=_compare_ref(step.ref)) for step in result.section.steps
        ]
    return result


def _is_papers_fig2(sym: SymbolicSystem) -> bool:
    """Two rolling bodies joined at their centres by one horizontal spring (the paper's Fig. 2),
    nothing else."""
    return (
        sym.n == 2
        and len(sym.springs) == 1
        and sym.springs[0].bodies == (0, 1)
        and sym.springs[0].stays_horizontal
        and all(b.rolls for b in sym.bodies)
        and not sym.forces
    )


def _compare_ref(ref: str) -> str:
    """'paper (QQQ1); (M12)' -> 'cf. paper (QQQ1) (Fig. 2 there); (M12)'."""
    parts = [part.strip() for part in ref.split(";")]
    return "; ".join(
        f"cf. {part} (Fig. 2 there)" if part.startswith("paper") else part for part in parts if part
    )

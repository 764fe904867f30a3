r"""What the five derivations share: the :class:`MethodResult` each one returns, their titles and
step prefixes, and the small pieces several of them use (tidy display forms, the zero mode, what
its conserved momentum is in words).

One module per method, as ``sympy.physics.mechanics`` keeps ``kane.py`` and ``lagrange.py`` apart:

* :mod:`.newton`: torques about the contact points (paper Sec. 2, 3, 5.1; (M7));
* :mod:`.conservation`: energy and the conserved momentum of the zero mode (Sec. 5.2); needs a
  single oscillating degree of freedom;
* :mod:`.lagrange`: Euler-Lagrange equations of :math:`\mathcal L = T - V` (Sec. 5.3; (M5)),
  checked against ``sympy.physics.mechanics.LagrangesMethod``;
* :mod:`.natural_frequencies`: subsystem frequencies :math:`\Omega_i^2 = K_{ii}/J_i` and the sum
  rule (Sec. 5.4, App. B, C); needs two bodies with a zero mode (rank-1 K);
* :mod:`.hamilton`: canonical coordinates :math:`q_i = \sqrt{J_i/m_i}\,\varphi_i`,
  :math:`p_i = m_i\dot q_i` (Sec. 5.6; (M6)).

Each builds a :class:`MethodResult`: a numbered :class:`~.steps.Section` of steps, each one
following from earlier ones by one named operation (:class:`~.steps.How`), and its results in a
common form, so that they can be compared (:mod:`.crosscheck`): the linearised equations
:math:`J_i\ddot\varphi_i = \dots` of every body (in the angles), the exact ones where the method
gives them, and the squared frequencies. The constraint relations, the inertias about the
contact lines, T, V, M and K are derived once, in the setup (:mod:`.setup`), and referred to;
the steps from the bodies' equations to the whole system's are in :mod:`.whole_system`.
:func:`~.derive.run_method` runs one method by name.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, field
from typing import Any

import sympy as sp

from rollspring.analysis.derivation.frequencies import Frequencies, normal_frequencies
from rollspring.analysis.derivation.parts import derivatives_at_reference
from rollspring.analysis.derivation.setup import rate_symbols, setup_tags
from rollspring.analysis.derivation.steps import Section, Step, inline
from rollspring.analysis.derivation.symbolic import SymbolicSystem

__all__ = [
    "METHODS",
    "PREFIXES",
    "TITLES",
    "MethodResult",
    "cached_frequencies",
    "content_free",
    "coordinates_word",
    "is_papers_fig2",
    "method_section",
    "names_momentum",
    "normalised",
    "short",
    "shown_scaled",
    "sign_inside",
    "single_spring_lever",
    "tidy",
    "tuple_text",
    "zero_mode_2",
    "zero_mode_in_angles",
]


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

#: The paper's sections each method follows, numbered as the paper prints them.
PAPER_SECTIONS = {
    "newton": "paper Sec. 2, 3 and 5.1",
    "conservation": "paper Sec. 5.2",
    "lagrange": "paper Sec. 5.3",
    "natural-frequencies": "paper Sec. 5.4, 5.5, App. B and C",
    "hamilton": "paper Sec. 5.6",
}


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

    def record(self, whole: dict[str, Any]) -> None:
        """Keep the whole system's results (:func:`~.whole_system.to_whole_system`): its
        equation, the squared frequencies, and every named intermediate in ``extras``."""
        self.system_equation = whole.get("system_equation")
        self.omega2 = whole.get("omega2", [])
        self.extras.update(whole)


def method_section(sym: SymbolicSystem, name: str, title: str | None = None) -> Section:
    """The empty section of method ``name``: its title, its step prefix (``N``, ``E``, ...)
    and the rates of the coordinates (so that steps can say what differentiates into what)."""
    return Section(
        title or TITLES[name],
        prefix=PREFIXES[name],
        rates=dict(rate_symbols(sym)),
        cites=PAPER_SECTIONS[name],
    )


def cached_frequencies(sym: SymbolicSystem, budget: float | None) -> Frequencies:
    """:func:`~.frequencies.normal_frequencies` of ``sym``, computed once per system."""
    key = "frequencies"
    if key not in sym._cache:
        sym._cache[key] = normal_frequencies(sym, budget=budget)
    result: Frequencies = sym._cache[key]
    return result


def coordinates_word(sym: SymbolicSystem) -> str:
    """'angles' when every body rolls, else 'coordinates' (a slider's is a displacement)."""
    return "angles" if all(b.rolls for b in sym.bodies) else "coordinates"


def tuple_text(values: Sequence[sp.Expr]) -> str:
    """'(1, -m_1/m_2)': the entries inline, as a tuple in the text of a step."""
    return "(" + ", ".join(inline(v) for v in values) + ")"


def names_momentum(sym: SymbolicSystem, v0: sp.Matrix | None) -> str:
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
            f"sum I'_i phi_i' (clockwise; {_paper_sum(sym.n)})"
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
        "P̂ is not the total angular momentum L_O = sum I'_i phi_i' about a point of the floor "
        f"({why}): it is the momentum of the free rolling motion along v0"
    )


def _paper_sum(n: int) -> str:
    """The paper's L_1 + L_2 for two bodies; L_1 + L_2 + L_3 (and so on) otherwise."""
    terms = " + ".join(f"L_{i + 1}" for i in range(n)) if n <= 4 else f"L_1 + ... + L_{n}"
    return "the paper's L_1 + L_2" if n == 2 else f"{terms}, the paper's L_1 + L_2 for {n} bodies"


def shown_scaled(what: str, factor: sp.Expr) -> str:
    """'; the sum is shown multiplied by 200' when the displayed equation is ``what``/factor
    (an equation = 0 freed of its constant factor), '' when the factor is 1."""
    if factor == 1:
        return ""
    if factor.is_Rational and factor.p == 1:
        return f"; {what} is shown multiplied by {inline(1 / factor)}"
    return f"; {what} is shown divided by its common factor {inline(factor)}"


def content_free(expr: sp.Expr, variables: list[sp.Symbol]) -> sp.Expr:
    """expr with its variable-free factor dropped (an expression equated to zero)."""
    expr = sp.factor_terms(sp.expand(expr))
    if isinstance(expr, sp.Mul):
        kept = [f for f in expr.args if f.has(*variables)]
        return sp.Mul(*kept) if kept else expr
    return expr


def tidy(expr: sp.Expr) -> sp.Expr:
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


def short(expr: sp.Expr) -> sp.Expr:
    """A compact form for display: factor small expressions, leave big ones alone. The
    factored form is preferred where it is not longer, its sign taken into the bracket
    (:func:`sign_inside`): the two bodies' equations then read alike, ``R²k(φ₂ - φ₁)`` and
    ``R²k(φ₁ - φ₂)``, not one of them factored and the other not."""
    expr = sp.sympify(expr)
    if any(not p.exp.is_Integer for p in expr.atoms(sp.Pow)):
        return expr  # roots (sqrt 2, a spring's length): factoring is slow and gains little
    if expr.count_ops() <= 60:
        try:
            factored = sign_inside(sp.factor(expr))
        except Exception:  # noqa: BLE001 - display only
            return expr
        return factored if sp.count_ops(factored) <= sp.count_ops(expr) else expr
    return expr


def sign_inside(expr: sp.Expr) -> sp.Expr:
    """``-c (a - b)`` as ``c (b - a)``: a product's minus sign taken into its one sum."""
    if not isinstance(expr, sp.Mul) or not expr.could_extract_minus_sign():
        return expr
    sums = [f for f in expr.args if isinstance(f, sp.Add)]
    if len(sums) != 1:
        return expr
    rest = [f for f in expr.args if f is not sums[0]]
    return sp.Mul(*rest) * -1 * sp.Mul(-1, sums[0])


def zero_mode_2(K: sp.Matrix) -> sp.Matrix | None:
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


def zero_mode_in_angles(sym: SymbolicSystem) -> sp.Matrix | None:
    """The zero mode (K v0 = 0) in the angles, its first non-zero entry 1 (None unless there
    is exactly one)."""
    if sym.zero_mode_count() != 1:
        return None
    if sym.n == 2:
        return normalised(zero_mode_2(sym.stiffness_matrix))
    return normalised(sym.zero_mode())


def normalised(v: sp.Matrix | None) -> sp.Matrix | None:
    """v scaled so that its first non-zero entry is 1."""
    if v is None:
        return None
    first = next((x for x in v if x != 0), sp.Integer(1))
    return v.applyfunc(lambda x: sp.factor(sp.cancel(x / first)))


def single_spring_lever(sym: SymbolicSystem) -> list[sp.Expr] | None:
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
        (dx, dy), _ = derivatives_at_reference(at, sym.bodies[at.body])
        out[at.body] += sign * (ex * dx + ey * dy)
    return [sp.factor(b) for b in out]


def is_papers_fig2(sym: SymbolicSystem) -> bool:
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

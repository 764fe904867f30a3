r"""``derive(system, method=...)``: the symbolic system, every method's derivation, the forces and
the cross-check, as one :class:`Derivation` (rendered as text, Markdown or LaTeX, and as math in
Jupyter); :func:`run_method` runs one method (:mod:`.newton`, :mod:`.conservation`,
:mod:`.lagrange`, :mod:`.natural_frequencies`, :mod:`.hamilton`) by name. :func:`derive` is
:func:`derivation_request` (the arguments checked once), the cost guard, then
:func:`run_derivation`, which an interface that estimated the cost itself calls directly."""

from __future__ import annotations

import math
import os
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field, replace
from typing import Any

import numpy as np
import sympy as sp

from rollspring.analysis.derivation.build import symbolic_system
from rollspring.analysis.derivation.conservation import conservation
from rollspring.analysis.derivation.crosscheck import CrossCheck, cross_check
from rollspring.analysis.derivation.forces import appendix_a_friction, contact_force_section
from rollspring.analysis.derivation.frequencies import Frequencies, normal_frequencies
from rollspring.analysis.derivation.hamilton import hamilton
from rollspring.analysis.derivation.lagrange import lagrange
from rollspring.analysis.derivation.method import METHODS, MethodResult, is_papers_fig2
from rollspring.analysis.derivation.natural_frequencies import natural_frequencies
from rollspring.analysis.derivation.newton import newton
from rollspring.analysis.derivation.notation import Entry, notation_table
from rollspring.analysis.derivation.render import latex_document, markdown, text
from rollspring.analysis.derivation.setup import setup_section
from rollspring.analysis.derivation.steps import Section
from rollspring.analysis.derivation.symbolic import SymbolicSystem
from rollspring.analysis.derivation.values import with_your_values
from rollspring.errors import DerivationError
from rollspring.model import System

__all__ = [
    "ALL",
    "Derivation",
    "DerivationError",
    "DerivationRequest",
    "derivation_request",
    "derive",
    "parse_methods",
    "run_derivation",
    "run_method",
    "setup_section",
]

#: ``method="all"`` runs every method in :data:`METHODS`.
ALL = "all"


@dataclass
class Derivation:
    """The result of :func:`derive`.

    ``symbolic``: the :class:`SymbolicSystem`; ``setup``: its parameters, M, V and K as steps;
    ``methods``: each requested method's :class:`MethodResult` (``applies``, ``reason``,
    ``steps``, ``equations``, ``omega2``...); ``forces``: friction and normal forces;
    ``appendix``: the paper's App. A friction law (with ``method="all"``); ``frequencies``:
    the reference closed forms of Omega^2; ``cross_check``: the comparison of the methods.
    """

    system: System
    symbolic: SymbolicSystem
    setup: Section
    methods: dict[str, MethodResult]
    forces: Section
    frequencies: Frequencies
    cross_check: CrossCheck
    appendix: Section | None = None
    extras: dict[str, object] = field(default_factory=dict)

    @property
    def title(self) -> str:
        """'Derivation: <system name>'."""
        return f"Derivation: {self.system.name or 'system'}"

    @property
    def subtitle(self) -> str:
        """What the parameters are (symbols or exact numbers) and the reference."""
        kind = (
            "parameters as symbols"
            if self.symbolic.symbolic
            else "parameters as exact numbers (SI units)"
        )
        extra = "; ".join(self.symbolic.notes)
        n, springs = self.symbolic.n, len(self.symbolic.springs)
        rolls = [b.rolls for b in self.symbolic.bodies]
        coordinates = (
            "angles" if all(rolls) else "displacements" if not any(rolls) else "coordinates"
        )
        return (
            f"{n} {'body' if n == 1 else 'bodies'}, "
            f"{springs} {'spring' if springs == 1 else 'springs'}; {kind}; "
            f"{coordinates} measured from the {self.symbolic.reference}"
            + (
                " (the system can move as a whole, along its zero mode: of its equilibria, "
                "the one that puts the stationary point at the origin)"
                if self.symbolic.reference == "equilibrium" and self.symbolic.zero_mode_count()
                else ""
            )
            + (f"; {extra}" if extra else "")
            + "."
        )

    @property
    def sections(self) -> list[Section]:
        """Every section in display order."""
        out = [self.setup]
        for result in self.methods.values():
            if result.applies:
                out.append(result.section)
            else:
                section = Section(
                    result.title,
                    list(result.section.steps),
                    note=f"Does not apply: {result.reason}.",
                    prefix=result.section.prefix,
                    rates=result.section.rates,
                    cites=result.section.cites,
                )
                out.append(section)
        out.append(self.forces)
        if self.appendix is not None:
            out.append(self.appendix)
        out.append(self.cross_check.section())
        return out

    @property
    def notation(self) -> list[Entry]:
        """The notation table: every symbol the steps display, defined once (its meaning and
        unit, and its value for a parameter of the system), and the names the words use (the
        rest length L, the contact line z')."""
        if "notation" not in self.extras:
            self.extras["notation"] = notation_table(self.sections, self.symbolic)
        table: list[Entry] = self.extras["notation"]  # type: ignore[assignment]
        return table

    @property
    def omega2(self) -> list[sp.Expr | None]:
        """Closed forms of the squared frequencies of the oscillating modes (reference)."""
        return list(self.frequencies.omega2)

    def to_text(self) -> str:
        """Plain text (Unicode pretty-printing)."""
        return text(self.title, self.subtitle, self.sections, notation=self.notation)

    def to_markdown(self) -> str:
        """Markdown with ``$$…$$`` math."""
        return markdown(self.title, self.subtitle, self.sections, notation=self.notation)

    def to_latex(self) -> str:
        """A complete LaTeX document (compiles with pdflatex; amsmath only)."""
        return latex_document(self.title, self.subtitle, self.sections, notation=self.notation)

    def render(self, format: str = "text") -> str:  # noqa: A002 - mirrors --format
        """``text``, ``markdown`` or ``latex``."""
        if format == "text":
            return self.to_text()
        if format == "markdown":
            return self.to_markdown()
        if format == "latex":
            return self.to_latex()
        raise DerivationError(f"format: unknown format '{format}' (text, markdown, latex)")

    def _repr_markdown_(self) -> str:
        return self.to_markdown()

    def _repr_latex_(self) -> str:
        lines = []
        for section in self.sections:
            for step in section.steps:
                lines.append(step.math)
        return r"$$\begin{gathered}" + r" \\ ".join(lines[:60]) + r"\end{gathered}$$"


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
    if not is_papers_fig2(sym):
        result.section.steps[:] = [
            replace(step, ref=_compare_ref(step.ref)) for step in result.section.steps
        ]
    return result


def _compare_ref(ref: str) -> str:
    """'paper (QQQ1); (M12)' -> 'cf. paper (QQQ1) (Fig. 2 there); (M12)'."""
    parts = [part.strip() for part in ref.split(";")]
    return "; ".join(
        f"cf. {part} (Fig. 2 there)" if part.startswith("paper") else part for part in parts if part
    )


def parse_methods(method: str | Sequence[str]) -> list[str]:
    """``"all"``, one name or a list of names -> method names (validated, paper order)."""
    if isinstance(method, str):
        names = [method]
    elif isinstance(method, Sequence | set | frozenset) and all(
        isinstance(name, str) for name in method
    ):
        names = list(method)
    else:
        raise DerivationError(
            f"method: must be a method name or a list of them "
            f"(methods: {', '.join(METHODS)}, {ALL}), got {_shown(method)}"
        )
    if not names:  # an empty list derived nothing, and said nothing
        raise DerivationError(
            f"method: give at least one method (methods: {', '.join(METHODS)}, {ALL})"
        )
    if ALL in names:
        return list(METHODS)
    for name in names:
        if name not in METHODS:
            raise DerivationError(
                f"method: unknown method '{name}' (methods: {', '.join(METHODS)}, {ALL})"
            )
    return [name for name in METHODS if name in names]


def _check_flag(name: str, value: object) -> None:
    if not isinstance(value, bool | np.bool_):
        raise DerivationError(f"{name}: must be True or False, got {_shown(value)}")


def _shown(value: object) -> str:
    """``repr(value)``, at most 60 characters (a message stays one short line)."""
    text = repr(value)
    return text if len(text) <= 60 else f"{text[:50]}… ({type(value).__name__})"


def derive(
    system: System | dict[str, Any] | str | os.PathLike[str],
    method: str | Sequence[str] = ALL,
    *,
    symbols: bool = True,
    budget: float | None = 10.0,
    confirm: bool = False,
) -> Derivation:
    r"""Derive the equations of motion of ``system`` step by step, by each ``method``.

    ``system``: a :class:`~rollspring.model.System` or a preset name / file path;
    ``method``: ``"all"`` or one or more of ``newton``, ``conservation``, ``lagrange``,
    ``natural-frequencies``, ``hamilton``; ``symbols``: parameters as symbols
    (:math:`m_1, R, k, \dots`, the default: a textbook's derivation, the system's numbers
    in the notation table and in each method's final "with your values" step), or
    ``symbols=False`` for exact numbers throughout; ``budget``: seconds allowed for each
    open-ended symbolic step (factoring, simplifying residuals), where SymPy can be slow.

    ``system`` may also be its JSON form (a dict); anything else is a one-line
    :class:`~rollspring.errors.ModelError` (:func:`rollspring.model.as_system`). A derivation
    estimated at more than 5 minutes (:func:`~rollspring.analysis.costs.derivation_cost`: many
    bodies) is refused with its estimate (:class:`~rollspring.errors.CostTooHigh`) unless
    ``confirm=True`` (``--yes`` on the command line). Every check comes before any work.

    Parameters
    ----------
    system
        A :class:`~rollspring.model.System`, its JSON form, a file path or a preset name.
    method
        ``"all"``, or one or more of the five methods.
    symbols
        Parameters as symbols (default) instead of exact numbers.
    budget
        Seconds for each open-ended symbolic step (None: no limit).
    confirm
        Start even when the estimated time is above the bound.

    Returns
    -------
    Derivation
        Each method's steps and results and their cross-check; ``to_markdown()``,
        ``to_latex()``.
    """
    from rollspring.analysis.costs import CONFIRM, check_cost, derivation_cost
    from rollspring.model import as_system

    system = as_system(system)
    request = derivation_request(method, symbols=symbols, budget=budget)
    _check_flag("confirm", confirm)
    check_cost(derivation_cost(system), confirmed=bool(confirm), flag=CONFIRM)
    return run_derivation(system, request)


@dataclass(frozen=True, slots=True)
class DerivationRequest:
    """The checked arguments of one :func:`derive` of a system (see there)."""

    #: the method names, in the paper's order (every one for ``"all"``)
    methods: tuple[str, ...]
    #: parameters as symbols instead of exact numbers
    symbols: bool
    #: seconds for each open-ended symbolic step, None for no limit
    budget: float | None


def derivation_request(
    method: str | Sequence[str] = ALL, *, symbols: bool = True, budget: float | None = 10.0
) -> DerivationRequest:
    """The arguments of :func:`derive` checked, in this order (the first bad one is the error,
    a one-line :class:`~rollspring.errors.DerivationError` naming it): ``method``, ``symbols``,
    ``budget``."""
    names = parse_methods(method)
    _check_flag("symbols", symbols)
    if budget is not None and (
        isinstance(budget, bool)
        or not isinstance(budget, int | float)
        or not math.isfinite(budget)
        or budget <= 0
    ):
        raise DerivationError(
            f"budget: must be a positive number of seconds or None, got {budget!r}"
        )
    return DerivationRequest(tuple(names), symbols, budget)


def run_derivation(system: System, request: DerivationRequest) -> Derivation:
    """The derivation :func:`derive` makes of a request checked already
    (:func:`derivation_request`), without estimating its cost (the caller's: :func:`derive`, or
    an interface that estimated it once)."""
    names, symbols, budget = list(request.methods), request.symbols, request.budget
    sym = symbolic_system(system, symbols=symbols)
    setup = setup_section(sym)
    frequencies = normal_frequencies(sym, budget=budget)
    sym._cache["frequencies"] = frequencies
    results = {name: run_method(sym, name, budget=budget) for name in names}
    for result in results.values():  # applies, but only in part (no linearisation)
        if result.applies and result.reason:
            result.section.note = f"Note: {result.reason}."
        with_your_values(result, sym, frequencies)  # the numbers come in at the end
    forces, force_results = contact_force_section(sym)
    appendix = appendix_a_friction()[0] if names == list(METHODS) else None
    check = cross_check(sym, results, frequencies, budget=budget)
    return Derivation(
        system,
        sym,
        setup,
        results,
        forces,
        frequencies,
        check,
        appendix,
        extras={"forces": force_results},
    )

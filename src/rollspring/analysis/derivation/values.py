r"""The last step of every method: its result "with your values".

A derivation is written in symbols (:math:`m_1, R, k, g, I'`); the system's numbers come in
only here, in decimals: the squared frequency the method derived (for the paper's Fig. 2,
:math:`\Omega^2 = k/(2m_1) + 2k/(3m_2)`, its (QQQ1)) with the values of the notation table,
and the angular frequency :math:`\Omega = \sqrt{\Omega^2}` of every oscillating mode. With
``symbols=False`` the parameters were numbers all along and the step gives the decimals of
the exact result.
"""

from __future__ import annotations

import math

import sympy as sp

from rollspring.analysis.derivation.frequencies import OMEGA2, Frequencies
from rollspring.analysis.derivation.method import MethodResult
from rollspring.analysis.derivation.steps import How, Named, Step, inline, latex_of, named
from rollspring.analysis.derivation.symbolic import SymbolicSystem

__all__ = ["DIGITS", "OMEGA", "decimal", "mode_omega", "with_your_values"]

#: Significant digits of the decimals shown.
DIGITS = 4

#: The angular frequency of the one oscillating mode.
OMEGA = sp.Symbol("Omega", positive=True)


def decimal(value: float) -> sp.Float:
    """``value`` to :data:`DIGITS` significant digits (``75.0`` -> ``75.00``, shown so)."""
    return sp.Float(value, DIGITS)


def mode_omega(n: int) -> Named:
    """The angular frequency of normal mode n, printed Ω₍ₙ₎."""
    digits = "".join("₀₁₂₃₄₅₆₇₈₉"[int(c)] for c in str(n))
    return named(f"Omega_({n})", rf"\Omega_{{({n})}}", f"Ω₍{digits}₎", positive=True)


def _squared_steps(result: MethodResult) -> tuple[Step, list[sp.Eq]] | None:
    """The method's last step that displays its squared frequencies, and those equations."""
    for step in reversed(result.section.steps):
        found = [
            e
            for e in step.equations
            if isinstance(e, sp.Eq)
            and (e.lhs == OMEGA2 or str(getattr(e.lhs, "name", "")).startswith("Omega_("))
            and str(getattr(e.lhs, "name", "")).endswith("^2")
        ]
        if found:
            return step, found
    return None


def with_your_values(result: MethodResult, sym: SymbolicSystem, frequencies: Frequencies) -> None:
    """Append the step "with your values" to ``result``'s section: each squared frequency of
    its last Omega^2 step with the system's numbers, in decimals, and its Omega (oscillating
    modes only; a zero mode's Omega^2 = 0 is left as shown)."""
    if not result.applies:
        return
    found = _squared_steps(result)
    if found is None:
        return
    step, squared = found
    shown: list[sp.Eq] = []
    latex: list[str] = []
    used: set[sp.Symbol] = set()
    for equation in squared:
        if equation.rhs == 0:
            continue
        value = sym.numeric(equation.rhs)
        if not math.isfinite(value):
            continue
        used |= {s for s in equation.rhs.free_symbols if s in sym.values}
        omega = OMEGA if equation.lhs == OMEGA2 else mode_omega(_mode(equation.lhs))
        shown.append(sp.Eq(equation.lhs, decimal(value), evaluate=False))
        line = rf"{latex_of(equation.lhs)} &= "
        if equation.rhs.free_symbols and sp.count_ops(equation.rhs) <= 40:
            line += rf"{latex_of(equation.rhs)} = "
        line += rf"{latex_of(decimal(value))}\ \mathrm{{s^{{-2}}}}"
        latex.append(line)
        if value > 0:
            shown.append(sp.Eq(omega, decimal(math.sqrt(value)), evaluate=False))
            latex.append(
                rf"{latex_of(omega)} &= {latex_of(decimal(math.sqrt(value)))}\ \mathrm{{s^{{-1}}}}"
            )
    if not shown:
        return
    from rollspring.analysis.derivation.notation import parameter_value

    single = [e for e in squared if e.lhs == OMEGA2 and e.rhs.free_symbols]
    formula = (
        f"Omega^2 = {inline(single[0].rhs)} of ({step.tag})"
        if len(single) == 1 and sp.count_ops(single[0].rhs) <= 40
        else f"({step.tag})"
    )
    if used:
        values = ", ".join(
            f"{inline(s)} = {parameter_value(s, sym)}" for s in sorted(used, key=lambda s: s.name)
        )
        words = f"With your values (the notation table's): {values} in {formula}, in decimals"
    else:
        words = f"With your values: {formula} in decimals"
    words += "; Omega = √(Omega^2), the angular frequency (Omega^2 in 1/s², Omega in 1/s)."
    result.section.add(
        shown,
        words,
        "",
        how=How("with your values", (step.tag,)),
        latex=r"\begin{aligned}" + r" \\ ".join(latex) + r"\end{aligned}",
    )


def _mode(symbol: sp.Basic) -> int:
    name = str(getattr(symbol, "name", ""))
    return int(name[len("Omega_(") : name.index(")")])

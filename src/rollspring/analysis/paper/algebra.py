"""The exact comparisons the verdicts rest on: two expressions identical, a cheap normal form.

:func:`same` decides ``simplify(left - right) == 0`` (a random rational point first, which spares
the simplification where the two differ); :func:`tidy` is the normal form the recipes display.
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

import sympy as sp
from sympy.logic.boolalg import BooleanAtom


def same(left: Any, right: Any) -> bool:
    """True when the two (expressions, or sequences of them of equal length) are identical:
    ``simplify(left - right) == 0``; truth values compare as such. A difference that is not
    zero at a random rational point (exact arithmetic) is not identically zero, which spares the
    simplification."""
    truth = (bool, BooleanAtom)
    if isinstance(left, truth) or isinstance(right, truth):  # a claim "X differs from Y"
        return isinstance(left, truth) and isinstance(right, truth) and bool(left) == bool(right)
    if isinstance(left, Sequence | sp.MatrixBase) or isinstance(right, Sequence | sp.MatrixBase):
        left_items, right_items = list(left), list(right)
        return len(left_items) == len(right_items) and all(
            same(a_, b_) for a_, b_ in zip(left_items, right_items, strict=True)
        )
    difference = sp.sympify(left) - sp.sympify(right)
    if difference == 0:
        return True
    if _nonzero_somewhere(difference):
        return False
    if sp.cancel(sp.expand(difference)) == 0:
        return True
    result: bool = sp.simplify(difference) == 0 or sp.simplify(sp.expand(difference)) == 0
    return result


def tidy(expr: Any) -> Any:
    """A cheap normal form: cancel for rational expressions, simplify where radicals, absolute
    values or signs appear."""
    expr = sp.sympify(expr)
    if expr.has(sp.Abs, sp.sign) or any(
        p_.exp.is_Rational and not p_.exp.is_Integer for p_ in expr.atoms(sp.Pow)
    ):
        return sp.simplify(expr)
    return sp.factor(sp.cancel(expr)) if expr.free_symbols else expr


def _nonzero_somewhere(expr: sp.Expr) -> bool:
    """True when ``expr`` is clearly non-zero at a rational point (positive symbols get values
    in (1/2, 3), real ones in (-2, 2) but not 0)."""
    point = {}
    for n, symbol in enumerate(sorted(expr.free_symbols, key=lambda s_: s_.name)):
        value = sp.Rational(53 + 37 * n % 101, 47 + 13 * n % 29)  # deterministic, generic
        if not symbol.is_positive:
            value = value - 2 if n % 2 else 2 - value
            if value == 0:
                value = sp.Rational(1, 3)
        point[symbol] = value
    number = sp.N(expr.xreplace(point), 30)
    if not number.is_number or number.is_finite is not True:
        return False  # undecided: leave it to simplify
    return bool(abs(number) > sp.Float("1e-20"))


def latex_of(value: Any) -> str:
    if isinstance(value, Sequence) and not isinstance(value, str):
        return r"\left(" + r",\ ".join(latex_of(v) for v in value) + r"\right)"
    result: str = sp.latex(value)
    return result


def substitute(value: Any, mapping: dict[Any, Any]) -> Any:
    if not mapping:
        return value
    if isinstance(value, Sequence) and not isinstance(value, str):
        return tuple(substitute(v, mapping) for v in value)
    return sp.sympify(value).subs(mapping)

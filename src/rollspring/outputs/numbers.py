"""Numbers as text for HTML pages and tables (the report, the Jupyter views)."""

from __future__ import annotations

import math

__all__ = ["html_number", "short_number"]


def short_number(value: float | None, digits: int = 6) -> str:
    """A number as short plain text (fit for LaTeX too): ``digits`` significant digits,
    ``∞``/``−∞``, ``–`` for None or NaN, ``0``."""
    if value is None:
        return "–"
    value = float(value)
    if math.isnan(value):
        return "–"
    if math.isinf(value):
        return "∞" if value > 0 else "−∞"
    if value == 0:
        return "0"
    return f"{value:.{digits}g}"


def html_number(value: float | None, digits: int = 6) -> str:
    """:func:`short_number` for HTML: powers of ten as ``×10<sup>n</sup>``, a true minus."""
    text = short_number(value, digits)
    if "e" in text:
        mantissa, exponent = text.split("e")
        text = f"{mantissa}×10<sup>{int(exponent)}</sup>"
    return text.replace("-", "−")

"""Numbers (and attachments) as text for HTML pages and tables (the report, the Jupyter
views)."""

from __future__ import annotations

import math
from typing import Any

__all__ = ["attachment_words", "html_number", "integrator_words", "short_number"]


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


def attachment_words(at: Any) -> str:
    """Where a spring end sits on its body: ``centre``, ``height 0.15 m`` or
    ``r = 0.05 m at 40°`` (an :class:`~rollspring.model.Attachment`)."""
    if at.height is not None:
        return f"height {short_number(at.height)} m"
    if at.radius is not None:
        return f"r = {short_number(at.radius)} m at {short_number(at.angle or 0.0)}°"
    return "centre"


def integrator_words(
    steps_by_integrator: dict[str, int], step: float | None, fallback: str = ""
) -> str:
    """The integrators a run used and their steps: ``kahanli8, 1130 steps of 0.00885 s`` or,
    for a run that switched, ``kahanli8, 400 steps of 0.005 s; dop853, 34 adaptive steps``
    (``fallback``, the chosen scheme, with 0 steps when none was taken)."""
    if not steps_by_integrator:
        return f"{fallback}, 0 steps"
    parts = []
    for name, count in steps_by_integrator.items():
        if name == "dop853":
            parts.append(f"{name}, {count} adaptive steps")
        else:
            of = f" of {short_number(step)} s" if step else ""
            parts.append(f"{name}, {count} steps{of}")
    return "; ".join(parts)

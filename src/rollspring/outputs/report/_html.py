"""HTML building blocks of the report: escaped text, numbers, tables, MathML.

Everything returns :class:`Markup` (a ``str`` that is already HTML); plain ``str`` arguments are
escaped. Numbers in tables carry their full value in ``data-value`` (``repr`` of the float), so a
reader (or a test) can take them back out exactly; the text shows 6 significant digits.
"""

from __future__ import annotations

import html
import math
import re
from collections.abc import Iterable, Sequence
from dataclasses import dataclass

import latex2mathml.converter

from rollspring.errors import MathConversionError, ReportError
from rollspring.outputs.numbers import html_number as fmt

__all__ = [
    "Markup",
    "MathConversionError",
    "Num",
    "ReportError",
    "esc",
    "fmt",
    "latex_to_mathml",
    "math_or_source",
    "table",
]


class Markup(str):
    """A string that is already HTML (never escaped again)."""

    __slots__ = ()


def esc(value: object) -> Markup:
    """HTML-escape ``value`` unless it is :class:`Markup` already."""
    if isinstance(value, Markup):
        return value
    return Markup(html.escape(str(value), quote=True))


def join(parts: Iterable[object], sep: str = "") -> Markup:
    """Concatenate escaped parts."""
    return Markup(sep.join(esc(p) for p in parts))


@dataclass(frozen=True)
class Num:
    """A table cell holding a number: shown with :func:`fmt`, exact in ``data-value``."""

    value: float | None
    digits: int = 6

    def html(self) -> Markup:
        if self.value is None or (isinstance(self.value, float) and math.isnan(self.value)):
            return Markup('<td class="num">–</td>')
        value = float(self.value)
        shown = fmt(value, self.digits)  # only digits, signs and <sup>: safe as is
        return Markup(f'<td class="num" data-value="{value!r}">{shown}</td>')


def _cell(value: object) -> Markup:
    if isinstance(value, Num):
        return value.html()
    if isinstance(value, int | float) and not isinstance(value, bool):
        return Num(float(value)).html()
    return Markup(f"<td>{esc(value)}</td>")


def table(
    headers: Sequence[object],
    rows: Iterable[Sequence[object]],
    *,
    caption: object = "",
    table_id: str = "",
    css_class: str = "",
) -> Markup:
    """A ``<table>``: headers (text or Markup), rows of cells (text, Markup or :class:`Num`)."""
    attributes = ""
    if table_id:
        attributes += f' id="{html.escape(table_id)}"'
    if css_class:
        attributes += f' class="{html.escape(css_class)}"'
    parts = [f"<table{attributes}>"]
    if caption:
        parts.append(f"<caption>{esc(caption)}</caption>")
    parts.append(
        "<thead><tr>" + "".join(f"<th>{esc(h)}</th>" for h in headers) + "</tr></thead><tbody>"
    )
    for row in rows:
        parts.append("<tr>" + "".join(_cell(c) for c in row) + "</tr>")
    parts.append("</tbody></table>")
    return Markup("".join(parts))


# -- MathML ------------------------------------------------------------------------------------

# A command latex2mathml does not know comes out as the literal text of the command
# (e.g. <mi>\foo</mi>), an alignment mark outside a table as <mi>&</mi>, a line break outside
# a table as <mspace linebreak>, which browsers ignore: failed conversions, not math.
_UNCONVERTED = re.compile(r"<m(?:i|o|n|text)>(?:\\[A-Za-z]+|&</)|<mspace linebreak=")
# latex2mathml 3.81 reads \begin{aligned} as a plain row (the & and \\ are lost); its
# \begin{split} is the same two-column right/left table, which it converts properly.
_ALIGNED = re.compile(r"\\(begin|end)\{aligned\}")


def latex_to_mathml(latex: str, *, display: bool = True) -> Markup:
    r"""The MathML of a LaTeX formula, via ``latex2mathml`` (Chromium renders MathML natively).

    Raises :class:`MathConversionError` when the formula does not parse or uses a command
    latex2mathml does not know (it would otherwise show the command's name as text).
    """
    try:
        mathml = latex2mathml.converter.convert(
            _ALIGNED.sub(r"\\\1{split}", latex), display="block" if display else "inline"
        )
    except Exception as exc:  # noqa: BLE001 - latex2mathml raises its own types, and IndexError
        raise MathConversionError(
            f"cannot convert LaTeX to MathML ({type(exc).__name__}): {latex[:80]}"
        ) from None
    unknown = _UNCONVERTED.search(mathml)
    if unknown:
        token = unknown.group(0)
        what = (
            "a line break outside an aligned environment"
            if "mspace" in token
            else "an alignment mark & outside an aligned environment"
            if "&<" in token
            else token.split(">", 1)[1]
        )
        raise MathConversionError(f"latex2mathml does not know {what} in: {latex[:80]}")
    return Markup(mathml)


def math_or_source(
    latex: str, *, display: bool = True, failures: list[str] | None = None
) -> Markup:
    """MathML of ``latex``; if it cannot be converted, the LaTeX source itself, visibly marked as
    such (and the reason appended to ``failures``) — never a silent blank."""
    try:
        return latex_to_mathml(latex, display=display)
    except MathConversionError as exc:
        if failures is not None:
            failures.append(str(exc))
        tag = "pre" if display else "code"
        return Markup(
            f'<{tag} class="tex-source" title="LaTeX not converted to MathML">{esc(latex)}</{tag}>'
        )

"""The frame of the report page: :class:`Page` (what every section reads: the system, its
analysis and run, the MathML failures, the table of contents), the helpers the sections share
(numbers in LaTeX, embedded JSON, figures as SVG images, verdict marks) and
:func:`page_document`, the whole HTML document with the style sheet and the player inlined
(:mod:`~rollspring.outputs.report._assets`).
"""

from __future__ import annotations

import base64
import json
import math
from typing import Any

import numpy as np

from rollspring.analysis import LinearAnalysis
from rollspring.model import System
from rollspring.outputs import figures
from rollspring.outputs.report._assets import player_script, style_sheet
from rollspring.outputs.report._html import Markup, esc, math_or_source
from rollspring.outputs.trajectory import json_ready
from rollspring.simulate import Trajectory

# -- numbers in LaTeX ----------------------------------------------------------------------------


def _tex_number(value: float, digits: int = 6) -> str:
    if math.isinf(value):
        return r"\infty" if value > 0 else r"-\infty"
    if value == 0:
        return "0"
    text = f"{value:.{digits}g}"
    if "e" in text:
        mantissa, exponent = text.split("e")
        return rf"{mantissa}\times 10^{{{int(exponent)}}}"
    return text


def _tex_id(name: str) -> str:
    """A body id as a LaTeX subscript text."""
    return r"\text{" + name.replace("_", r"\_") + "}"


def _tex_matrix(matrix: np.ndarray, digits: int = 6) -> str:
    rows = [" & ".join(_tex_number(float(v), digits) for v in row) for row in matrix]
    return r"\begin{pmatrix}" + r"\\".join(rows) + r"\end{pmatrix}"


def _json_script(element_id: str, data: Any) -> Markup:
    text = json.dumps(json_ready(data), ensure_ascii=False, allow_nan=False, separators=(",", ":"))
    text = text.replace("<", "\\u003c")  # no "</script" or "<!--" inside the script element
    return Markup(f'<script type="application/json" id="{element_id}">{text}</script>')


def _round(values: Any, digits: int = 7) -> list:
    """Values rounded to ``digits`` significant digits (small JSON, plenty for drawing);
    non-finite values become 0."""
    array = np.asarray(values, dtype=float)
    array = np.where(np.isfinite(array), array, 0.0)
    flat = [float(f"{v:.{digits}g}") for v in array.ravel().tolist()]
    return np.array(flat).reshape(array.shape).tolist()


def _figure(figure: Any, caption: str, figure_id: str) -> Markup:
    """A Matplotlib figure (or the figure of an Axes) as an embedded SVG image."""
    figure = getattr(figure, "figure", figure)
    svg = figures.figure_svg(figure)
    data = base64.b64encode(svg.encode("utf-8")).decode("ascii")
    return Markup(
        f'<figure id="{esc(figure_id)}"><img alt="{esc(caption)}" '
        f'src="data:image/svg+xml;base64,{data}"><figcaption>{esc(caption)}'
        "</figcaption></figure>"
    )


def _verdict(ok: bool | None, yes: str, no: str) -> Markup:
    if ok is None:
        return Markup('<span class="verdict-other">–</span>')
    return Markup(f'<span class="verdict-{"ok" if ok else "bad"}">{esc(yes if ok else no)}</span>')


class Page:
    """What the sections of one report share: the analysis, the run and the list of MathML
    conversion failures; :meth:`section` records each section for the table of contents."""

    def __init__(
        self, system: System, analysis: LinearAnalysis, trajectory: Trajectory, failures: list[str]
    ) -> None:
        self.system = system
        self.analysis = analysis
        self.trajectory = trajectory
        self.arrays = analysis.arrays
        self.failures = failures
        self.section_ids: list[str] = []
        self.titles: list[tuple[str, str]] = []

    def math(self, latex: str, *, display: bool = True) -> Markup:
        return math_or_source(latex, display=display, failures=self.failures)

    def section(self, section_id: str, title: str, *parts: object) -> Markup:
        self.section_ids.append(section_id)
        self.titles.append((section_id, title))
        return Markup(
            f'<section id="{section_id}"><h2>{esc(title)}</h2>'
            + "".join(esc(p) for p in parts if p)
            + "</section>"
        )


def page_document(system: System, titles: list[tuple[str, str]], sections: list[Markup]) -> str:
    """The whole page: head (no request allowed), title, table of contents and ``sections``."""
    from rollspring._version import version

    __version__ = version()
    title = system.name or "system"
    toc = " ".join(f'<a href="#{sid}">{esc(t)}</a>' for sid, t in titles)
    description = f"<p>{esc(system.description)}</p>" if system.description else ""
    return (
        '<!DOCTYPE html>\n<html lang="en"><head><meta charset="utf-8">'
        # nothing may be fetched: images and data are embedded, scripts and styles inline
        '<meta http-equiv="Content-Security-Policy" content="default-src \'none\'; '
        "img-src data:; style-src 'unsafe-inline'; script-src 'unsafe-inline'\">"
        '<meta name="viewport" content="width=device-width, initial-scale=1">'
        f'<meta name="generator" content="rollspring {esc(__version__)}">'
        '<link rel="icon" href="data:,">'
        f"<title>rollspring report: {esc(title)}</title><style>{style_sheet()}</style></head><body>"
        f'<main><header class="page"><h1>{esc(title)}</h1>{description}'
        f'<nav class="toc">{toc}</nav></header>'
        + "".join(sections)
        + f"<footer>Made by rollspring {esc(__version__)}. One file, no network: every "
        "image, formula (MathML) and data set is in it.</footer></main>"
        f"<script>{player_script()}</script></body></html>\n"
    )

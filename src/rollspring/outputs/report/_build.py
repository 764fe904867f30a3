r"""Assemble the report page from results already computed (an analysis, a simulation, a
derivation, the paper's claims checked) and their pictures.

Each ``section_*`` function of a :class:`~rollspring.outputs.report._page.Page` returns one
``<section>`` of the page (Markup); they live by page section in ``_system_sections`` (overview,
diagram, parameters, equilibrium), ``_mode_sections`` (modes, stationary point, friction),
``_motion_sections`` (animation, plots), ``_lab_section`` (the model fitted to a recording)
and ``_check_sections`` (derivation, paper check, warnings, data), and :func:`render_report`
puts them in order. What the page shows is computed by
:func:`rollspring.service.documents.build_report`, which calls it.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING

from rollspring.analysis import LinearAnalysis
from rollspring.analysis.derivation import Derivation
from rollspring.analysis.paper import (
    ClaimCheck,
)
from rollspring.model import System
from rollspring.outputs.atomic import atomic_write_text
from rollspring.outputs.report._check_sections import (
    section_data,
    section_derivation,
    section_paper_check,
    section_warnings,
)
from rollspring.outputs.report._html import ReportError
from rollspring.outputs.report._lab_section import section_lab
from rollspring.outputs.report._mode_sections import (
    section_friction,
    section_modes,
    section_stationary_point,
)
from rollspring.outputs.report._motion_sections import (
    section_animation,
    section_plots,
)
from rollspring.outputs.report._page import Page, page_document
from rollspring.outputs.report._pdf import html_to_pdf
from rollspring.outputs.report._system_sections import (
    section_diagram,
    section_equilibrium,
    section_overview,
    section_parameters,
)
from rollspring.simulate import Trajectory

if TYPE_CHECKING:
    from rollspring.lab.fit import FitResult

__all__ = [
    "FORMATS",
    "Report",
    "animation_frames",
    "default_duration",
    "render_report",
    "write_report",
]

#: Values of ``format`` that :func:`write_report` accepts.
FORMATS = ("html", "pdf")
#: Stored animation frames per simulated second (the player interpolates between them).
FRAMES_PER_SECOND = 60
_MAX_FRAMES = 1200
#: Output rows of the simulation per animation frame (the plots use every row).
_ROWS_PER_FRAME = 4


@dataclass
class Report:
    """A finished report: the page (``html``), what it was made from, and how long each stage
    took (``timings``, s). ``math_failures`` lists formulas shown as LaTeX source because
    latex2mathml could not convert them (empty when every formula is MathML)."""

    system: System
    #: None for a long chain's report (:func:`~rollspring.outputs.report.render_chain_report`)
    analysis: LinearAnalysis | None
    trajectory: Trajectory
    html: str
    sections: list[str] = field(default_factory=list)
    math_failures: list[str] = field(default_factory=list)
    timings: dict[str, float] = field(default_factory=dict)


def default_duration(analysis: LinearAnalysis) -> float:
    """Simulated time of a report: four periods of the slowest oscillating mode, within
    [1, 20] s; 2 s when nothing oscillates."""
    periods = [m.period for m in analysis.oscillating if math.isfinite(m.period)]
    if not periods:
        return 2.0
    return float(min(max(4.0 * max(periods), 1.0), 20.0))


def animation_frames(duration: float) -> tuple[int, int]:
    """``(frames, rows)`` for a report of ``duration`` simulated seconds: the frames the player
    stores (:data:`FRAMES_PER_SECOND`, 50 to 1200) and the output rows the simulation needs
    for them (the plots use every row)."""
    frames = int(min(max(math.ceil(duration * FRAMES_PER_SECOND), 50), _MAX_FRAMES))
    return frames, _ROWS_PER_FRAME * (frames - 1) + 1


def render_report(
    system: System,
    analysis: LinearAnalysis,
    trajectory: Trajectory,
    *,
    frames: int,
    derivation: Derivation | None = None,
    derivation_error: str | None = None,
    paper: tuple[str, Sequence[ClaimCheck]] | None = None,
    lab: FitResult | None = None,
    stage: Callable[[str, float], None] | None = None,
) -> Report:
    """The self-contained report page of ``system`` from its ``analysis`` and ``trajectory``.

    ``frames``: animation frames the player stores (:func:`animation_frames`); ``derivation``:
    the symbolic derivation to show, or ``derivation_error`` (why there is none) — with neither
    the page has no derivation; ``paper``: ``(label of the paper's figure, its claims checked)``
    when the system is one of the paper's; ``lab``: the system fitted to a recording
    (:func:`rollspring.fit`), shown in a lab section; ``stage`` is called after each stage of the
    rendering with its name and the fraction of the rendering done (0..1).
    """

    def done(name: str, fraction: float) -> None:
        if stage is not None:
            stage(name, fraction)

    failures: list[str] = []
    page = Page(system, analysis, trajectory, failures)
    sections = [
        section_overview(page),
        section_diagram(page),
        section_parameters(page),
        section_equilibrium(page),
        section_modes(page),
        section_stationary_point(page),
        section_friction(page),
    ]
    done("tables and figures", 0.5)
    sections.append(section_animation(page, frames))
    sections.append(section_plots(page))
    done("animation and plots", 0.75)
    if derivation is not None or derivation_error is not None:
        sections.append(section_derivation(page, derivation, derivation_error))
        done("derivation", 0.9)
    if paper is not None:
        sections.append(section_paper_check(page, *paper))
        done("paper check", 0.95)
    if lab is not None:
        sections.append(section_lab(page, lab))
    sections.append(section_warnings(page))
    sections.append(section_data(page))
    html = page_document(system, page.titles, [s for s in sections if s])
    done("assemble", 1.0)
    return Report(
        system=system,
        analysis=analysis,
        trajectory=trajectory,
        html=html,
        sections=page.section_ids,
        math_failures=failures,
    )


#: The names a report of each format may take (its bytes are that format's).
REPORT_SUFFIXES = {"html": (".html", ".htm"), "pdf": (".pdf",)}


def check_report_name(path: str | Path, format: str) -> None:  # noqa: A002
    """A report's file name ends in its format's suffix (a PDF written under .html misleads
    every program that opens it): a one-line :class:`ReportError` otherwise."""
    suffixes = REPORT_SUFFIXES.get(format, ())
    if Path(path).suffix.lower() not in suffixes:
        raise ReportError(
            f"--out {path}: the {format} report's name must end in {' or '.join(suffixes)}"
        )


def write_report(
    report: Report,
    path: str | Path,
    *,
    format: str = "html",  # noqa: A002
    chromium: str | None = None,
) -> Path:
    """Write the report to ``path`` atomically: the HTML page, or (``format="pdf"``) the same
    page printed by headless Chromium (:func:`~rollspring.outputs.report.find_chromium`)."""
    if format not in FORMATS:
        raise ReportError(f"--format: unknown format '{format}' (formats: {', '.join(FORMATS)})")
    target = Path(path)
    check_report_name(target, format)
    if format == "pdf":
        return html_to_pdf(report.html, target, chromium=chromium)
    try:
        atomic_write_text(target, report.html)
    except OSError as exc:
        raise ReportError(f"{target}: cannot write ({exc.strerror or exc})") from None
    return target

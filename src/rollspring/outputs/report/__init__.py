"""The report: one self-contained offline HTML page about a system (``rollspring report``).

The page holds the system's parameters, the equilibrium with M and K, the modal table, the
stationary point X̂, the friction each body needs against μs, the simulated motion with an
animation player (Play/Pause, speed, frame slider), the warnings, and the analysis and trajectory
as embedded data; every formula is MathML (converted from LaTeX by ``latex2mathml``; Chromium
renders MathML natively). Nothing is fetched: styles and scripts are inline, images and data are
``data:`` URLs, and a Content-Security-Policy forbids every request. ``format="pdf"`` prints the
same page with headless Chromium.

This package renders results computed elsewhere: :func:`rollspring.service.documents.build_report`
(``rollspring.build_report``) analyses, simulates and derives, then calls :func:`render_report`.

Public API::

    report = render_report(system, analysis, trajectory, frames=frames,
                           derivation=derivation, paper=(label, checks))  # -> Report
    render_chain_report(system, trajectory, waves)                # a long chain: a summary
    write_report(report, "report.html")                           # atomic
    write_report(report, "report.pdf", format="pdf")              # headless Chromium
    find_chromium()                                               # path, or ReportError
    latex_to_mathml(r"\\Omega^2 = k/(2m_1)")                      # MathML markup
    tex_text_html(r"the force $F_1=F_2$ \\emph{is} ...")          # text and MathML
    claim_html(check)                                  # a paper claim's quote, formula, correction
"""

from rollspring.outputs.report._build import (
    FORMATS,
    Report,
    animation_frames,
    check_report_name,
    default_duration,
    render_report,
    write_report,
)
from rollspring.outputs.report._chain import CHAIN_FRAMES, render_chain_report
from rollspring.outputs.report._check_sections import derivation_sections
from rollspring.outputs.report._html import MathConversionError, ReportError, latex_to_mathml
from rollspring.outputs.report._motion_sections import animation_data
from rollspring.outputs.report._pdf import CHROMIUM_ENV, find_chromium, html_to_pdf
from rollspring.outputs.report._tex_text import claim_html, tex_text_html

__all__ = [
    "CHAIN_FRAMES",
    "CHROMIUM_ENV",
    "FORMATS",
    "MathConversionError",
    "Report",
    "ReportError",
    "animation_data",
    "animation_frames",
    "check_report_name",
    "claim_html",
    "default_duration",
    "derivation_sections",
    "find_chromium",
    "html_to_pdf",
    "latex_to_mathml",
    "render_chain_report",
    "render_report",
    "tex_text_html",
    "write_report",
]

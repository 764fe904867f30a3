"""The report's lab section (``rollspring report SYSTEM --data tracks.csv``): the measured
table over the fitted model with the residuals, the fitted values ± standard errors, and the
paper's claims measured. Renders a :class:`~rollspring.lab.fit.FitResult`; computes nothing."""

from __future__ import annotations

from typing import TYPE_CHECKING

from rollspring.outputs.figures import plot_fit
from rollspring.outputs.lab import format_value
from rollspring.outputs.report._html import Markup, esc, table
from rollspring.outputs.report._page import Page, _figure

if TYPE_CHECKING:
    from rollspring.lab.fit import FitResult

__all__ = ["section_lab"]

_CLAIMS = (
    ("cm_peak_to_peak", "the centre of mass's peak-to-peak motion", " m"),
    ("stationary_peak_to_peak", "X̂'s peak-to-peak motion (the paper: it stays put)", " m"),
    ("friction_ratio", "the frictions' amplitude ratio (the paper: 3 : 2)", ""),
)


def section_lab(page: Page, fit: FitResult) -> Markup:
    """The lab section: the data over the fitted model, the fitted values, the claims."""
    out = fit.to_dict()
    intro = Markup(
        f"<p>The system fitted to the measured table <code>{esc(fit.data.source)}</code> "
        f"({out['points']} positions of {esc(', '.join(fit.data.bodies))}) by least squares on "
        f"the {esc(out['motion'])}: {esc(fit.message)}. The residuals' RMS is "
        + esc(", ".join(f"{body} {1e3 * v:.3g} mm" for body, v in out["residual_rms"].items()))
        + ".</p>"
    )
    values = table(
        ["parameter", "fitted value", "unit"],
        [
            [name, format_value(p["value"], p["stderr"]), p["unit"]]
            for name, p in out["parameters"].items()
        ],
        caption="Fitted values ± standard errors (held values marked)",
        table_id="lab-values",
    )
    parts: list[object] = [
        intro,
        _figure(
            plot_fit(fit),
            "The measured positions over the fitted model, and the residuals",
            "lab-figure",
        ),
        values,
    ]
    claims = out["claims"]
    if claims:
        rows = [
            [label, format_value(claims[key]["value"], claims[key]["stderr"]) + unit]
            for key, label, unit in _CLAIMS
            if key in claims
        ]
        for body, check in claims.get("rolled", {}).items():
            rows.append(
                [
                    f"{body} rolled",
                    f"{'yes' if check['rolled'] else 'no'}: slip {1e3 * check['slip_rms']:.2g} mm "
                    f"RMS against noise {1e3 * check['noise']:.2g} mm",
                ]
            )
        parts.append(
            table(
                ["the paper's claim", "measured"],
                rows,
                caption="The paper's claims measured on the recording",
                table_id="lab-claims",
            )
        )
    for warning in fit.warnings:
        parts.append(Markup(f'<p class="verdict-bad">warning: {esc(warning)}</p>'))
    return page.section("lab", "Lab: the model fitted to a recording", *parts)

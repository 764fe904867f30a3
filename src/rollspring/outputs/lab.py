"""The lab's results rendered: a fit as an HTML table with its figure (Jupyter), the fitted
system as TOML. Reads :class:`~rollspring.lab.fit.FitResult`; computes nothing."""

from __future__ import annotations

import base64
import html
import math
from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:
    from rollspring.lab.fit import FitResult

__all__ = ["fit_figure_png", "fit_html", "fitted_toml", "format_value"]


def format_value(value: float | None, stderr: float | None) -> str:
    """``value ± stderr`` with the error's two significant digits setting the precision
    (``99.96 ± 0.093``); ``value`` alone for a held parameter (stderr 0)."""
    if value is None:
        return "—"
    if stderr is None or not math.isfinite(stderr):
        return f"{value:.6g} ± ∞"
    if stderr == 0:
        return f"{value:.6g} (held)"
    digits = max(0, 1 - int(math.floor(math.log10(stderr))))
    magnitude = int(math.floor(math.log10(abs(value)))) if value != 0 else 0
    # fixed point while its digits fit a double's 16 (an epoch time of 1.7e9 s known to 4e-5 s
    # is 1700000000.000000 ± 0.000040), else the mantissa's digits the error sets
    if magnitude + 1 + digits > 16 or (value != 0 and abs(value) < 1e-3 and digits > 8):
        mantissa = min(max(magnitude - int(math.floor(math.log10(stderr))) + 1, 1), 14)
        return f"{value:.{mantissa}e} ± {stderr:.2e}"
    return f"{value:.{digits}f} ± {stderr:.{digits}f}"


def fitted_toml(result: FitResult) -> str:
    """The fitted system as a system file (TOML), with a comment saying where it came from."""
    from rollspring.model.files import system_to_toml

    head = (
        f"# fitted by rollspring fit to {result.data.source} ({result.status}); initial state "
        f"at t0 = {float(result.parameters['t0'].value)!r} s of the data\n"
    )
    return head + system_to_toml(result.system)


def fit_figure_png(result: FitResult, dpi: float = 100.0) -> bytes:
    """:func:`rollspring.outputs.figures.plot_fit` as PNG bytes."""
    from rollspring.outputs.figures import figure_png, plot_fit, theme

    with theme():
        return figure_png(plot_fit(result), dpi=dpi)


def _rows(entries: dict[str, Any]) -> str:
    return "".join(
        f"<tr><td><code>{html.escape(name)}</code></td><td>{html.escape(text)}</td></tr>"
        for name, text in entries.items()
    )


def fit_html(result: FitResult, *, figure: bool = True) -> str:
    """The Jupyter view of a fit: status, parameters ± standard errors, residual RMS per body,
    the paper's claims measured, the warnings and the figure."""
    out = result.to_dict()
    parameters = {
        name: f"{format_value(p['value'], p['stderr'])} {p['unit']}"
        for name, p in out["parameters"].items()
    }
    rms = {body: f"{1e3 * value:.3g} mm" for body, value in out["residual_rms"].items()}
    claims = {
        name: format_value(entry["value"], entry["stderr"]) + ("" if "ratio" in name else " m")
        for name, entry in out["claims"].items()
        if isinstance(entry, dict) and "value" in entry
    }
    for body, check in out["claims"].get("rolled", {}).items():
        claims[f"{body} rolled"] = (
            f"{'yes' if check['rolled'] else 'no'} (slip {1e3 * check['slip_rms']:.2g} mm RMS, "
            f"noise {1e3 * check['noise']:.2g} mm)"
        )
    parts = [
        f"<div><p><b>Fit</b> to <code>{html.escape(result.data.source)}</code>: "
        f"{html.escape(result.message)} ({html.escape(out['motion'])}, {out['points']} points)</p>",
        f"<table><tr><th>parameter</th><th>value</th></tr>{_rows(parameters)}</table>",
        f"<table><tr><th>body</th><th>residual RMS</th></tr>{_rows(rms)}</table>",
    ]
    if claims:
        parts.append(
            f"<table><tr><th>the paper's claim</th><th>measured</th></tr>{_rows(claims)}</table>"
        )
    parts += [f"<p>warning: {html.escape(w)}</p>" for w in result.warnings]
    if figure:
        encoded = base64.b64encode(fit_figure_png(result)).decode("ascii")
        parts.append(f'<img alt="data and model" src="data:image/png;base64,{encoded}">')
    return "".join(parts) + "</div>"

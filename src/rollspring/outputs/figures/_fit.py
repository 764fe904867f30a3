"""The figure of a fit: the measured positions over the fitted model, and the residuals."""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np
from matplotlib.figure import Figure

from rollspring.outputs.figures._style import BODY_COLORS, new_figure, theme

if TYPE_CHECKING:
    from rollspring.lab.fit import FitResult


def plot_fit(result: FitResult, fig: Figure | None = None) -> Figure:
    r"""Two panels sharing the time axis: above, each measured body's centre position (dots,
    displacement from the model's first value) over the fitted model (line); below, the
    residuals :math:`x^{\rm data} - x^{\rm model}` in millimetres with the fit's noise band
    :math:`\pm s`. Reads :attr:`~rollspring.lab.fit.FitResult.model_x` and the data: nothing is
    recomputed."""
    data = result.data
    with theme():
        if fig is None:
            fig = new_figure(7.2, 5.0)
        top, bottom = fig.subplots(
            2, 1, sharex=True, gridspec_kw={"height_ratios": [2.2, 1.0], "hspace": 0.08}
        )
        fig.subplots_adjust(left=0.12, right=0.97, bottom=0.1, top=0.88)
        t = data.t
        for column, body in enumerate(data.bodies):
            color = BODY_COLORS[data.index[column] % len(BODY_COLORS)]
            measured = data.x[:, column]
            model = result.model_x[:, column]
            ok = np.isfinite(measured)
            origin = model[0]
            top.plot(
                t[ok],
                measured[ok] - origin,
                ".",
                ms=3,
                color=color,
                alpha=0.55,
                label=f"{body} (data)",
            )
            top.plot(t, model - origin, "-", lw=1.2, color=color, label=f"{body} (model)")
            bottom.plot(t[ok], 1e3 * (measured[ok] - model[ok]), ".", ms=2.5, color=color)
        noise = 1e3 * result.noise
        bottom.axhspan(-noise, noise, color="0.85", zorder=0, lw=0)
        bottom.axhline(0.0, color="0.4", lw=0.8)
        top.set_ylabel("displacement (m)")
        bottom.set_ylabel("residual (mm)")
        bottom.set_xlabel("t (s)")
        status = "" if result.converged else " (not converged)"
        top.set_title(f"Fit to {_short(data.source)}{status}", loc="left")
        top.legend(
            fontsize=7.5,
            ncols=2,
            loc="lower right",
            bbox_to_anchor=(1.0, 1.0),
            frameon=False,
            borderaxespad=0.2,
        )
    return fig


def _short(source: str) -> str:
    name = source.replace("\\", "/").rsplit("/", 1)[-1]
    return name if len(name) <= 48 else name[:45] + "..."

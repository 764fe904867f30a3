r"""The figure of a chain's dispersion (:class:`~rollspring.analysis.dispersion.Dispersion`).

Two panels over the Brillouin zone :math:`|q| \le \pi/a`: the branches :math:`\omega_b(q)`
(solid, band gaps shaded) with the closed form of the lattice with masses
:math:`(1 + \gamma)m` overlaid (dashed) where the springs join centres, and the static friction
each body of the cell needs per metre of wave amplitude on each branch. Nothing is recomputed
here: every number is read from the result.
"""

from __future__ import annotations

import os
from pathlib import Path

from matplotlib.figure import Figure

from rollspring.analysis.dispersion import Dispersion
from rollspring.errors import OutputError
from rollspring.outputs.figures import figure_png, figure_svg, new_figure, theme

__all__ = ["FIGURE_FORMATS", "plot_dispersion", "write_dispersion_figure"]

#: File extensions :func:`write_dispersion_figure` writes.
FIGURE_FORMATS = (".png", ".svg")

_BRANCH_COLOURS = ("#1f3b57", "#d95f02", "#1a9641", "#7570b3", "#e7298a", "#66a61e")
_LINE_STYLES = ("-", "--", ":", "-.")


def plot_dispersion(result: Dispersion, fig: Figure | None = None) -> Figure:
    """Draw the branches and the friction per unit amplitude on ``fig`` (a new 7 x 6.5 in
    figure when None) and return it."""
    with theme():
        if fig is None:
            fig = new_figure(7.0, 6.5)
        top, bottom = fig.subplots(2, 1, sharex=True)
        q = result.q
        for _branch, lo, hi in result.gaps:
            top.axhspan(lo, hi, color="#eeeeee", zorder=0)
            top.text(
                q[-1],
                0.5 * (lo + hi),
                f" gap {lo:.4g}…{hi:.4g} rad/s ",
                ha="right",
                va="center",
                fontsize=8,
            )
        n_branches = result.omega.shape[1]
        for b in range(n_branches):
            colour = _BRANCH_COLOURS[b % len(_BRANCH_COLOURS)]
            top.plot(q, result.omega[:, b], color=colour, lw=1.8, label=f"branch {b + 1}")
            if result.closed_form is not None:
                top.plot(
                    q,
                    result.closed_form[:, b],
                    color="black",
                    lw=0.9,
                    ls="--",
                    label="closed form, masses (1 + γ)m" if b == 0 else None,
                )
            for r, body in enumerate(result.cell.ids):
                bottom.plot(
                    q,
                    result.friction[:, b, r],
                    color=colour,
                    ls=_LINE_STYLES[r % len(_LINE_STYLES)],
                    lw=1.2,
                    label=f"branch {b + 1}, {body}",
                )
        top.set_ylabel("ω (rad/s)")
        top.set_title(
            f"{result.system.name}: a = {result.cell.a:g} m, cell {', '.join(result.cell.ids)}"
        )
        top.legend(loc="upper left", fontsize=8)
        top.set_ylim(bottom=0.0)
        bottom.set_ylabel("|f| per m of amplitude (N/m)")
        bottom.set_xlabel("q (rad/m)")
        bottom.set_xlim(q[0], q[-1])
        bottom.set_ylim(bottom=0.0)
        bottom.legend(loc="upper left", fontsize=7, ncol=max(1, n_branches))
        fig.tight_layout()
    return fig


def write_dispersion_figure(result: Dispersion, path: str | os.PathLike[str]) -> Path:
    """Write the figure to ``path`` (.png or .svg, atomically) and return the path."""
    from rollspring.outputs.atomic import atomic_write_bytes, atomic_write_text

    target = Path(path)
    suffix = target.suffix.lower()
    if suffix not in FIGURE_FORMATS:
        raise OutputError(
            f"--figure: {target.name}: give a file ending in {' or '.join(FIGURE_FORMATS)}"
        )
    fig = plot_dispersion(result)
    try:
        if suffix == ".png":
            atomic_write_bytes(target, figure_png(fig))
        else:
            atomic_write_text(target, figure_svg(fig))
    except OSError as exc:
        raise OutputError(f"--figure: {target}: cannot write ({exc.strerror or exc})") from None
    return target

"""The figures' palette and Matplotlib settings, and saving a figure as PNG, SVG or pixels.

:data:`COLORS` names the colours of the drawings (``mark``, the radius mark of every rolling
body, is used for nothing else: tests find it in the pixels); :data:`BODY_COLORS` the line colour
of each body in time plots. Every figure is built and saved inside :func:`theme` (Matplotlib's
defaults plus DejaVu Sans, fixed DPI, fixed SVG hash salt, no dates in metadata), so the same
input gives the same pixels whatever the user's matplotlibrc.
"""

from __future__ import annotations

import contextlib
import io
from collections.abc import Iterator
from types import MappingProxyType
from typing import Any

import matplotlib
import numpy as np
from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.figure import Figure

#: Colours of the drawings. ``mark`` (the radius mark of rolling bodies) is used for nothing else.
COLORS = MappingProxyType(
    {
        "floor": "#7f7f7f",
        "edge": "#1f3b57",
        "hoop": "#1f3b57",
        "cylinder": "#a6c8e0",
        "sphere": "#c9b8dc",
        "shell": "#d9e7c3",
        "custom": "#e8d3a9",
        "slider": "#bdbdbd",
        "mark": "#e0007f",
        "spring": "#333333",
        "spring_force": "#1a9641",
        "friction": "#e66101",
        "normal": "#2c7bb6",
        "applied": "#a50026",
        "cm": "#000000",
        "xhat": "#7b3294",
        "mode": "#7b3294",
        "wall": "#7f7f7f",
    }
)

#: Line colours of the bodies in time plots, in body order (repeats after ten).
BODY_COLORS = (
    "#1f77b4",
    "#d62728",
    "#2ca02c",
    "#9467bd",
    "#8c564b",
    "#17becf",
    "#bcbd22",
    "#7f7f7f",
    "#ff7f0e",
    "#e377c2",
)

_RC: dict[str, Any] = {
    "font.family": ["DejaVu Sans"],
    "font.size": 9.0,
    "mathtext.fontset": "dejavusans",
    "axes.titlesize": 9.0,
    "axes.labelsize": 9.0,
    "legend.fontsize": 8.0,
    "legend.frameon": False,
    "xtick.labelsize": 8.0,
    "ytick.labelsize": 8.0,
    "axes.spines.top": False,
    "axes.spines.right": False,
    "axes.formatter.useoffset": False,
    "axes.formatter.limits": (-3, 4),
    "lines.linewidth": 1.3,
    "figure.dpi": 100.0,
    "savefig.dpi": 100.0,
    "savefig.bbox": None,
    "savefig.facecolor": "white",
    "figure.facecolor": "white",
    "svg.hashsalt": "rollspring",
    "svg.fonttype": "path",
    "hatch.linewidth": 0.8,
    "hatch.color": "#7f7f7f",
}


@contextlib.contextmanager
def theme() -> Iterator[None]:
    """Matplotlib's default rcParams plus rollspring's (DejaVu Sans 9 pt, 100 dpi, fixed SVG hash
    salt), for the duration of the block; the caller's rcParams are restored afterwards. Every
    figure function builds its figure inside it, and :func:`figure_png` saves inside it, so a
    user's matplotlibrc or style does not change the pixels."""
    with matplotlib.rc_context():
        matplotlib.rcdefaults()
        # matplotlib's stubs type the keys as a Literal of every rc name: _RC's are str
        matplotlib.rcParams.update(_RC)  # type: ignore[arg-type]
        yield


def new_figure(width: float, height: float, *, dpi: float = 100.0) -> Figure:
    """A Figure (inches) with an Agg canvas, outside pyplot (no display, no global registry)."""
    with theme():
        fig = Figure(figsize=(width, height), dpi=dpi)
    FigureCanvasAgg(fig)
    return fig


def figure_png(fig: Figure, dpi: float = 100.0) -> bytes:
    """The figure as PNG bytes at ``dpi``; no software name or date in the metadata, so the
    bytes depend only on the pixels."""
    buffer = io.BytesIO()
    with theme():
        fig.savefig(buffer, format="png", dpi=dpi, metadata={"Software": None})
    return buffer.getvalue()


def figure_svg(fig: Figure) -> str:
    """The figure as an SVG document (text as paths, fixed hash salt, no date)."""
    buffer = io.StringIO()
    with theme():
        fig.savefig(buffer, format="svg", metadata={"Date": None, "Creator": None})
    return buffer.getvalue()


def figure_rgba(fig: Figure) -> np.ndarray:
    """Draw the figure on its Agg canvas and return a copy of the pixels, (H, W, 4) uint8, row 0
    at the top."""
    canvas = fig.canvas if isinstance(fig.canvas, FigureCanvasAgg) else FigureCanvasAgg(fig)
    with theme():
        canvas.draw()
    return np.array(canvas.buffer_rgba())

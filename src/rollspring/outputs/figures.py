r"""Figures of systems, analyses and trajectories (Matplotlib's object-oriented API, Agg).

Every function takes a result and an optional ``ax`` (or ``fig`` for multi-panel figures) and
returns it; nothing here recomputes physics: positions, forces, modes, the CM and
:math:`\hat X` are read from the model, :class:`~rollspring.analysis.LinearAnalysis` and
:class:`~rollspring.simulate.Trajectory` objects (drawing a body point from ``x`` and ``phi``,
docs/physics.md (M1), is geometry). No pyplot: figures are :class:`matplotlib.figure.Figure` objects
with an Agg canvas, so nothing needs a display and no global state changes. Every figure is
built and saved inside :func:`theme` (Matplotlib's defaults, DejaVu Sans, fixed DPI, fixed SVG
hash salt, no dates in metadata), so the same input gives the same pixels.

Public functions
----------------
* :func:`plot_system` ``(result, ax=None, *, time=None, at="initial", forces=False,
  title=True) -> Axes``: floor and tracks, bodies (hoop: ring with spokes; cylinder, sphere,
  shell: discs with a radius mark; slider: a block), springs as zigzags, hatched walls and
  anchors, the CM and :math:`\hat X` on the floor; ``result`` is a System, a LinearAnalysis or a
  Trajectory (at ``time``).
* :func:`plot_positions` ``(trajectory, ax=None, *, relative=True) -> Axes``: centre
  positions with the CM and :math:`\hat X`.
* :func:`plot_contact_forces` ``(trajectory, fig=None) -> Figure``: friction with the
  :math:`\pm\mu_s N` band and the normal force, one row per body.
* :func:`plot_friction_ratio` ``(trajectory, ax=None) -> Axes``: :math:`|f|/(\mu_s N)` with
  the first slip (and lift-off) marked.
* :func:`plot_energy` ``(trajectory, ax=None) -> Axes``: kinetic, potential and total energy.
* :func:`plot_phase_portraits` ``(trajectory, fig=None) -> Figure``: displacement against
  velocity, one panel per body.
* :func:`plot_modes` ``(analysis, fig=None) -> Figure``: one panel per normal mode, arrows on
  the diagram, with :math:`\omega`.
* Long chains (more than :data:`LONG_CHAIN` bodies), summarised instead of one curve per body:
  :func:`plot_space_time` ``(trajectory, waves, fig=None) -> Figure``: space–time images (body
  position against time) of the displacement, of the signed friction ratio
  :math:`f/(\mu_s N)` and of the energy per body with the energy centroid's path and the
  group-velocity line (a :class:`~rollspring.analysis.waves.Waves`); :func:`signed_friction_ratio`.
* :func:`new_figure` ``(width, height, *, dpi=100) -> Figure``; :func:`theme` (context manager).
* :func:`figure_png` ``(fig, dpi=100) -> bytes``, :func:`figure_svg` ``(fig) -> str``,
  :func:`figure_rgba` ``(fig) -> ndarray`` of shape (H, W, 4), uint8.
* For animations: :class:`SystemScene` (the artists of one drawing, moved by
  ``update(SceneState)``), :func:`scene_for_trajectory`, :func:`states_at` (a trajectory's
  :class:`SceneState` at any times), :class:`ForceScale` (the fixed arrow scales).

:data:`COLORS` names the colours; the radius mark of every rolling body is drawn in
``COLORS["mark"]``, a colour used for nothing else (tests find it in the pixels).
"""

from __future__ import annotations

import contextlib
import io
import math
from collections.abc import Iterator
from dataclasses import dataclass
from types import MappingProxyType
from typing import Any

import matplotlib
import numpy as np
from matplotlib.artist import Artist
from matplotlib.axes import Axes
from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.collections import LineCollection
from matplotlib.figure import Figure
from matplotlib.offsetbox import AnchoredOffsetbox, AuxTransformBox, HPacker, TextArea
from matplotlib.patches import Circle, FancyArrowPatch, Rectangle
from matplotlib.ticker import MaxNLocator
from matplotlib.transforms import ScaledTranslation

from rollspring.analysis import LinearAnalysis
from rollspring.analysis.waves import Waves
from rollspring.model import System
from rollspring.physics import SystemArrays, centre_of_mass, centre_positions, system_arrays
from rollspring.physics.arrays import FloatArray
from rollspring.simulate import Trajectory

__all__ = [
    "COLORS",
    "LONG_CHAIN",
    "ForceScale",
    "SceneState",
    "SystemScene",
    "figure_png",
    "figure_rgba",
    "figure_svg",
    "new_figure",
    "plot_contact_forces",
    "plot_energy",
    "plot_friction_ratio",
    "plot_modes",
    "plot_phase_portraits",
    "plot_positions",
    "plot_space_time",
    "plot_system",
    "scene_for_trajectory",
    "signed_friction_ratio",
    "states_at",
    "theme",
]

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


# -- geometry (docs/physics.md (M1)) -----------------------------------------------------------


@dataclass(frozen=True)
class _Geometry:
    """What drawing needs from a system, as arrays."""

    arrays: SystemArrays
    shapes: tuple[str, ...]

    @classmethod
    def of(cls, system: System) -> _Geometry:
        return cls(system_arrays(system), tuple(b.shape for b in system.bodies))

    @property
    def n(self) -> int:
        return self.arrays.n_bodies

    @property
    def centre_height(self) -> FloatArray:
        return self.arrays.track + self.arrays.radius

    def end_points(self, x: FloatArray, phi: FloatArray) -> FloatArray:
        r"""Spring end positions (..., S, 2 ends, 2) for centre positions ``x`` and rotations
        ``phi`` (..., n): :math:`P = (x + r\sin\theta, h + R + r\cos\theta)`,
        :math:`\theta = \alpha + \varphi` (M1), with the actual ``x`` (also while a body
        slips); anchors are fixed."""
        a = self.arrays
        body = np.where(a.end_body >= 0, a.end_body, 0)
        theta = a.end_alpha + a.rolls[body] * phi[..., body]
        px = x[..., body] + a.end_r * np.sin(theta)
        py = self.centre_height[body] + a.end_r * np.cos(theta)
        points = np.stack([px, py], axis=-1)
        return np.where((a.end_body < 0)[..., None], a.end_anchor, points)

    def force_points(self, x: FloatArray, phi: FloatArray) -> FloatArray:
        """Points of application of the constant external forces, (F, 2)."""
        a = self.arrays
        body = a.force_body
        theta = a.force_alpha + a.rolls[body] * phi[body]
        return np.stack(
            [
                x[body] + a.force_r * np.sin(theta),
                self.centre_height[body] + a.force_r * np.cos(theta),
            ],
            axis=-1,
        )


@dataclass(frozen=True)
class _Extent:
    """Data limits of a scene and the levels it is drawn against (m)."""

    xmin: float
    xmax: float
    ymin: float
    ymax: float
    floor: float
    size: float  # the largest body radius: the unit of every drawing length
    track_spans: tuple[tuple[float, float, float], ...]  # (height, x from, x to) raised tracks
    walls: tuple[tuple[float, float, float, float], ...]  # rectangles (x, y, width, height)


def _extent(
    geometry: _Geometry,
    xs: FloatArray,
    phis: FloatArray,
    *,
    top_extra: float = 0.0,
    side_extra: float = 0.0,
) -> _Extent:
    """Limits covering the states ``xs``, ``phis`` (k, n), the anchors, walls and labels."""
    a = geometry.arrays
    radius, track = a.radius, a.track
    size = float(np.max(radius))
    floor = float(min(np.min(track), 0.0)) if np.any(track <= 0.0) else float(np.min(track))
    lefts = np.min(xs - radius, axis=0)
    rights = np.max(xs + radius, axis=0)
    xmin, xmax = float(np.min(lefts)), float(np.max(rights))
    top = float(np.max(track + 2 * radius))
    if a.n_springs:
        ends = geometry.end_points(xs, phis)
        xmin = min(xmin, float(np.min(ends[..., 0])))
        xmax = max(xmax, float(np.max(ends[..., 0])))
        top = max(top, float(np.max(ends[..., 1])))
    spans = []
    for i in range(geometry.n):
        if track[i] > floor:
            spans.append(
                (
                    float(track[i]),
                    float(lefts[i] - 0.5 * radius[i]),
                    float(rights[i] + 0.5 * radius[i]),
                )
            )
    walls = []
    thickness = 0.25 * size
    left_end, right_end = float(np.min(lefts)), float(np.max(rights))
    anchor_points = {
        (float(p[0]), float(p[1]))
        for p in a.end_anchor.reshape(-1, 2)[(a.end_body < 0).reshape(-1)]
    }
    for ax_, ay in sorted(anchor_points):
        height = max(ay + 0.6 * size, floor + size) - floor
        if ax_ <= left_end:  # a wall on the left, from the floor up past the hook
            walls.append((ax_ - thickness, floor, thickness, height))
            xmin = min(xmin, ax_ - thickness)
            top = max(top, floor + height)
        elif ax_ >= right_end:  # on the right
            walls.append((ax_, floor, thickness, height))
            xmax = max(xmax, ax_ + thickness)
            top = max(top, floor + height)
        else:  # above the bodies' range: a ceiling block
            walls.append((ax_ - 0.75 * size, ay, 1.5 * size, thickness))
            xmin, xmax = min(xmin, ax_ - 0.75 * size), max(xmax, ax_ + 0.75 * size)
            top = max(top, ay + thickness)
    for _height, left, right in spans:
        xmin, xmax = min(xmin, left), max(xmax, right)
    pad = 0.3 * size + side_extra
    return _Extent(
        xmin=xmin - pad,
        xmax=xmax + pad,
        ymin=floor - 1.05 * size,  # the floor band with the CM and X-hat markers and labels
        ymax=top + 0.45 * size + top_extra,  # body labels
        floor=floor,
        size=size,
        track_spans=tuple(spans),
        walls=tuple(walls),
    )


def _zigzag(start: FloatArray, end: FloatArray, half_width: float, teeth: int) -> FloatArray:
    """Points of a zigzag spring from ``start`` to ``end``: straight leads (15% each), then
    ``teeth`` zigzags of constant width, stretched with the spring."""
    d = end - start
    length = math.hypot(float(d[0]), float(d[1]))
    if length <= 0.0:
        return np.array([start, end])
    e = d / length
    normal = np.array([-e[1], e[0]])
    s = np.concatenate([[0.0], 0.15 + 0.7 * (np.arange(2 * teeth + 1) / (2 * teeth)), [1.0]])
    offset = np.zeros_like(s)
    offset[2:-2:2] = half_width
    offset[3:-2:2] = -half_width
    return start + s[:, None] * d + offset[:, None] * normal


def _nice(value: float) -> float:
    """The largest of 1, 2, 5 times a power of ten that is at most ``value`` (> 0)."""
    power = 10.0 ** math.floor(math.log10(value))
    for factor in (5.0, 2.0, 1.0):
        if factor * power <= value * (1 + 1e-12):
            return factor * power
    return power


@dataclass(frozen=True)
class ForceScale:
    """Fixed arrow scales (m of drawing per N): one for springs, friction and applied forces,
    one for normal forces (usually ten times larger); ``*_reference`` are the round forces
    shown in the legend (0 when there is nothing to show)."""

    horizontal: float
    normal: float
    horizontal_reference: float
    normal_reference: float

    @classmethod
    def fit(
        cls, size: float, horizontal_max: float, normal_max: float, legend_length: float = math.inf
    ) -> ForceScale:
        """The largest spring/friction/applied force drawn as long as the largest radius, the
        largest normal force 0.9 of it; the legend's round forces are drawn at most
        ``legend_length`` long."""

        def one(largest: float, length: float) -> tuple[float, float]:
            if not (math.isfinite(largest) and largest > 0.0):
                return 1.0, 0.0
            scale = length / largest
            return scale, _nice(min(largest, legend_length / scale))

        h, h_ref = one(horizontal_max, size)
        n, n_ref = one(normal_max, 0.9 * size)
        return cls(h, n, h_ref, n_ref)


def _finite_max(values: FloatArray) -> float:
    values = np.abs(np.asarray(values, dtype=float))
    values = values[np.isfinite(values)]
    return float(np.max(values)) if values.size else 0.0


# -- the scene ----------------------------------------------------------------------------------


@dataclass(frozen=True)
class SceneState:
    """One configuration to draw: per body ``x`` (m) and ``phi`` (rad), optionally per body
    ``friction`` and ``normal`` (N), per spring ``tension`` (N), the CM and X-hat (m), the time
    (s) and a status line."""

    x: FloatArray
    phi: FloatArray
    friction: FloatArray | None = None
    normal: FloatArray | None = None
    tension: FloatArray | None = None
    cm: float | None = None
    xhat: float | None = None
    time: float | None = None
    note: str = ""


class SystemScene:
    """The artists of a system drawing, created once and moved by :meth:`update` (the static
    figures draw one state, the animation many). ``forces`` (a :class:`ForceScale`) adds force
    arrows and their legend; ``clock`` a time display and a line for slips and events;
    ``labels`` the body ids; ``show_xhat`` the stationary point's marker."""

    def __init__(
        self,
        ax: Axes,
        system: System,
        extent: _Extent,
        *,
        forces: ForceScale | None = None,
        clock: bool = False,
        labels: bool = True,
        show_xhat: bool = True,
    ) -> None:
        self.ax = ax
        self.system = system
        self.geometry = _Geometry.of(system)
        self.extent = extent
        self.forces = forces
        self.labels = labels
        g, a = self.geometry, self.geometry.arrays
        size = extent.size
        ax.set_xlim(extent.xmin, extent.xmax)
        ax.set_ylim(extent.ymin, extent.ymax)
        ax.set_aspect("equal", adjustable="box")
        ax.set_axis_off()
        self._draw_ground()
        # bodies
        self.bodies: list[dict[str, Any]] = []
        for i, shape in enumerate(g.shapes):
            self.bodies.append(self._make_body(i, shape))
        # springs
        self.springs = []
        for s in range(a.n_springs):
            rest = float(a.rest_length[s])
            half_width = 0.12 * size
            teeth = int(np.clip(round(rest / (2.5 * half_width)), 5, 16))
            (line,) = ax.plot(
                [], [], color=COLORS["spring"], lw=1.2, zorder=5, solid_joinstyle="miter"
            )
            self.springs.append((line, half_width, teeth))
        (self.ends,) = ax.plot([], [], "o", ms=3.0, color=COLORS["spring"], zorder=6)
        for anchor in system.anchors:
            ax.plot(
                [anchor.x],
                [anchor.y],
                "o",
                ms=4.5,
                mfc="white",
                mec=COLORS["spring"],
                mew=1.2,
                zorder=7,
            )
        # CM and X-hat on the floor
        marker: dict[str, Any] = {"ms": 7, "zorder": 8, "clip_on": False, "mew": 0.0}
        (self.cm,) = ax.plot([], [], "^", color=COLORS["cm"], **marker)
        (self.xhat,) = ax.plot([], [], "^", color=COLORS["xhat"], **marker)
        text: dict[str, Any] = {"ha": "center", "va": "top", "fontsize": 7.5, "zorder": 8}
        self.cm_label = ax.text(0, extent.floor - 0.42 * size, "CM", color=COLORS["cm"], **text)
        self.xhat_label = ax.text(
            0, extent.floor - 0.70 * size, r"$\hat{X}$", color=COLORS["xhat"], **text
        )
        self.show_xhat = show_xhat
        # forces
        self.arrows: dict[str, list[FancyArrowPatch]] = {
            "spring": [],
            "friction": [],
            "normal": [],
            "applied": [],
        }
        if forces is not None:
            self._make_force_artists(forces)
        self.clock = self.note = None
        if clock:  # above the scene on the right: the time, and above it the latest event
            self.clock = ax.annotate(
                "",
                (1.0, 1.0),
                xycoords="axes fraction",
                xytext=(0, 3),
                textcoords="offset points",
                ha="right",
                va="bottom",
                fontsize=8.5,
                family="DejaVu Sans Mono",
            )
            self.note = ax.annotate(
                "",
                (1.0, 1.0),
                xycoords="axes fraction",
                xytext=(0, 16),
                textcoords="offset points",
                ha="right",
                va="bottom",
                fontsize=7.5,
                color=COLORS["applied"],
            )

    # construction -------------------------------------------------------------------------
    def _draw_ground(self) -> None:
        ax, e = self.ax, self.extent
        band = 0.22 * e.size
        ax.add_patch(
            Rectangle(
                (e.xmin, e.floor - band),
                e.xmax - e.xmin,
                band,
                facecolor="none",
                edgecolor=COLORS["floor"],
                hatch="////",
                lw=0.0,
                zorder=1,
            )
        )
        ax.plot([e.xmin, e.xmax], [e.floor, e.floor], color=COLORS["floor"], lw=1.4, zorder=2)
        for height, left, right in e.track_spans:
            ax.add_patch(
                Rectangle(
                    (left, e.floor),
                    right - left,
                    height - e.floor,
                    facecolor="white",
                    edgecolor=COLORS["floor"],
                    hatch="\\\\\\\\",
                    lw=1.0,
                    zorder=1.5,
                )
            )
            ax.plot([left, right], [height, height], color=COLORS["floor"], lw=1.4, zorder=2)
        for x, y, width, height in e.walls:
            ax.add_patch(
                Rectangle(
                    (x, y),
                    width,
                    height,
                    facecolor="white",
                    edgecolor=COLORS["wall"],
                    hatch="////",
                    lw=1.0,
                    zorder=1.5,
                )
            )

    def _make_body(self, i: int, shape: str) -> dict[str, Any]:
        ax, a = self.ax, self.geometry.arrays
        radius = float(a.radius[i])
        parts: dict[str, Any] = {"shape": shape, "radius": radius}
        if shape == "slider":
            block = Rectangle(
                (0.0, 0.0),
                2.4 * radius,
                2.0 * radius,
                facecolor=COLORS["slider"],
                edgecolor=COLORS["edge"],
                lw=1.4,
                zorder=3,
            )
            ax.add_patch(block)
            parts["block"] = block
        elif shape == "hoop":
            ring = Circle(
                (0.0, 0.0), radius, fill=False, edgecolor=COLORS["hoop"], lw=2.4, zorder=3
            )
            ax.add_patch(ring)
            spokes = LineCollection([], colors=COLORS["hoop"], linewidths=0.9, zorder=3)
            ax.add_collection(spokes)
            parts.update(disc=ring, spokes=spokes)
        else:
            lw = 4.0 if shape == "shell" else 1.4
            disc = Circle(
                (0.0, 0.0),
                radius,
                facecolor=COLORS.get(shape, COLORS["custom"]),
                edgecolor=COLORS["edge"],
                lw=lw,
                zorder=3,
            )
            ax.add_patch(disc)
            parts["disc"] = disc
            if shape == "custom":  # the radius of gyration: I = m (sqrt(gamma) R)^2
                gyration = Circle(
                    (0.0, 0.0),
                    math.sqrt(float(a.gamma[i])) * radius,
                    fill=False,
                    edgecolor=COLORS["edge"],
                    lw=0.8,
                    ls="--",
                    zorder=3,
                )
                ax.add_patch(gyration)
                parts["gyration"] = gyration
        if shape != "slider":
            (mark,) = ax.plot([], [], color=COLORS["mark"], lw=2.2, solid_capstyle="butt", zorder=4)
            parts["mark"] = mark
            (hub,) = ax.plot([], [], "o", ms=2.5, color=COLORS["edge"], zorder=4)
            parts["hub"] = hub
        parts["label"] = ax.text(
            0.0,
            0.0,
            self.geometry.arrays.ids[i],
            ha="center",
            va="bottom",
            fontsize=8,
            zorder=8,
            visible=self.labels,
        )
        return parts

    def _arrow(self, color: str, alpha: float = 1.0, zorder: float = 9) -> FancyArrowPatch:
        arrow = FancyArrowPatch(
            (0.0, 0.0),
            (1.0, 0.0),
            arrowstyle="-|>",
            mutation_scale=9,
            color=color,
            lw=1.6,
            shrinkA=0.0,
            shrinkB=0.0,
            alpha=alpha,
            zorder=zorder,
        )
        self.ax.add_patch(arrow)
        return arrow

    def _make_force_artists(self, forces: ForceScale) -> None:
        a = self.geometry.arrays
        for s in range(a.n_springs):
            for j in range(2):
                if a.end_body[s, j] >= 0:
                    self.arrows["spring"].append(self._arrow(COLORS["spring_force"]))
        for _ in range(a.n_bodies):
            self.arrows["normal"].append(self._arrow(COLORS["normal"], alpha=0.85))
            self.arrows["friction"].append(self._arrow(COLORS["friction"]))
        for _ in range(a.force.shape[0]):
            self.arrows["applied"].append(self._arrow(COLORS["applied"]))
        # the legend: arrows of round forces at the fixed scales, in a row above the scene
        entries = []
        a_forces = a.force.shape[0] > 0
        if forces.horizontal_reference > 0:
            length = forces.horizontal_reference * forces.horizontal
            label = f"{forces.horizontal_reference:g} N"
            entries.append((length, COLORS["spring_force"], f"spring {label}"))
            if np.any(a.rolls > 0):
                entries.append((length, COLORS["friction"], f"friction {label}"))
            if a_forces:
                entries.append((length, COLORS["applied"], f"applied {label}"))
        if forces.normal_reference > 0:
            entries.append(
                (
                    forces.normal_reference * forces.normal,
                    COLORS["normal"],
                    f"normal {forces.normal_reference:g} N",
                )
            )
        children: list[Artist] = []
        for length, color, text in entries:
            box = AuxTransformBox(self.ax.transData)
            box.add_artist(
                FancyArrowPatch(
                    (0.0, 0.0),
                    (length, 0.0),
                    arrowstyle="-|>",
                    mutation_scale=9,
                    color=color,
                    lw=1.6,
                    shrinkA=0,
                    shrinkB=0,
                )
            )
            children.append(
                HPacker(
                    children=[box, TextArea(text, textprops={"fontsize": 7.5})],
                    align="center",
                    pad=0,
                    sep=3,
                )
            )
        if children:
            legend = AnchoredOffsetbox(
                loc="lower left",
                child=HPacker(children=children, align="center", pad=0, sep=12),
                bbox_to_anchor=(0.0, 1.0),
                bbox_transform=self.ax.transAxes,
                frameon=False,
                pad=0.0,
                borderpad=0.25,
            )
            legend.set_clip_on(False)
            self.ax.add_artist(legend)

    # update ---------------------------------------------------------------------------------
    def update(self, state: SceneState) -> None:
        """Move every artist to ``state``."""
        g, a = self.geometry, self.geometry.arrays
        x = np.asarray(state.x, dtype=float)
        phi = np.asarray(state.phi, dtype=float)
        heights = g.centre_height
        for i, parts in enumerate(self.bodies):
            cx, cy, radius = float(x[i]), float(heights[i]), parts["radius"]
            if parts["shape"] == "slider":
                parts["block"].set_xy((cx - 1.2 * radius, cy - radius))
                top = cy + radius
            else:
                parts["disc"].set_center((cx, cy))
                if "gyration" in parts:
                    parts["gyration"].set_center((cx, cy))
                turn = float(phi[i])
                if "spokes" in parts:
                    angles = turn + np.arange(1, 6) * (math.pi / 3)
                    ends = np.stack(
                        [cx + radius * np.sin(angles), cy + radius * np.cos(angles)], axis=-1
                    )
                    centres = np.broadcast_to([cx, cy], ends.shape)
                    parts["spokes"].set_segments(np.stack([centres, ends], axis=1))
                # the radius mark: the body's material radius that was straight up at phi = 0
                parts["mark"].set_data(
                    [cx, cx + radius * math.sin(turn)], [cy, cy + radius * math.cos(turn)]
                )
                parts["hub"].set_data([cx], [cy])
                top = cy + radius
            parts["label"].set_position((cx, top + 0.08 * self.extent.size))
        # springs
        if a.n_springs:
            ends = g.end_points(x, phi)
            for s, (line, half_width, teeth) in enumerate(self.springs):
                points = _zigzag(ends[s, 0], ends[s, 1], half_width, teeth)
                line.set_data(points[:, 0], points[:, 1])
            body_ends = ends[a.end_body >= 0]
            self.ends.set_data(body_ends[:, 0], body_ends[:, 1])
        # CM and X-hat
        floor = self.extent.floor
        if state.cm is not None and math.isfinite(state.cm):
            self.cm.set_data([state.cm], [floor - 0.33 * self.extent.size])
            self.cm_label.set_x(state.cm)
            self.cm_label.set_visible(True)
        else:
            self.cm.set_data([], [])
            self.cm_label.set_visible(False)
        if self.show_xhat and state.xhat is not None and math.isfinite(state.xhat):
            size = self.extent.size
            self.xhat.set_data([state.xhat], [floor - 0.33 * size])
            close = state.cm is not None and abs(state.xhat - state.cm) < 0.45 * size
            self.xhat_label.set_position((state.xhat, floor - (0.66 if close else 0.42) * size))
            self.xhat_label.set_visible(True)
        else:
            self.xhat.set_data([], [])
            self.xhat_label.set_visible(False)
        if self.forces is not None:
            self._update_forces(state, x, phi)
        if self.clock is not None and state.time is not None:
            self.clock.set_text(f"t = {state.time:7.3f} s")
            if self.note is not None:
                self.note.set_text(state.note)

    def _update_forces(self, state: SceneState, x: FloatArray, phi: FloatArray) -> None:
        g, a, scale = self.geometry, self.geometry.arrays, self.forces
        assert scale is not None
        tiny = 1e-3 * self.extent.size

        def put(arrow: FancyArrowPatch, start, vector) -> None:
            length = math.hypot(float(vector[0]), float(vector[1]))
            if not (math.isfinite(length) and length > tiny):
                arrow.set_visible(False)
                return
            arrow.set_visible(True)
            arrow.set_positions(
                (float(start[0]), float(start[1])),
                (float(start[0] + vector[0]), float(start[1] + vector[1])),
            )

        k = 0
        if a.n_springs and state.tension is not None:
            ends = g.end_points(x, phi)
            for s in range(a.n_springs):
                d = ends[s, 1] - ends[s, 0]
                length = math.hypot(float(d[0]), float(d[1]))
                e = d / length if length > 0 else np.zeros(2)
                pull = float(state.tension[s]) * e  # on end a; -pull on end b (docs/physics.md §2)
                for j, sign in ((0, 1.0), (1, -1.0)):
                    if a.end_body[s, j] >= 0:
                        put(self.arrows["spring"][k], ends[s, j], sign * pull * scale.horizontal)
                        k += 1
        else:
            for arrow in self.arrows["spring"]:
                arrow.set_visible(False)
        heights = a.track
        for i in range(a.n_bodies):
            contact = (float(x[i]), float(heights[i]))
            if state.normal is not None:
                put(self.arrows["normal"][i], contact, (0.0, float(state.normal[i]) * scale.normal))
            else:
                self.arrows["normal"][i].set_visible(False)
            if state.friction is not None and a.rolls[i] > 0:
                put(
                    self.arrows["friction"][i],
                    contact,
                    (float(state.friction[i]) * scale.horizontal, 0.0),
                )
            else:
                self.arrows["friction"][i].set_visible(False)
        if a.force.shape[0]:
            points = g.force_points(x, phi)
            for f in range(a.force.shape[0]):
                put(self.arrows["applied"][f], points[f], a.force[f] * scale.horizontal)


# -- states from results ------------------------------------------------------------------------


def states_at(
    trajectory: Trajectory, times: FloatArray, *, forces: bool = True
) -> list[SceneState]:
    """The trajectory's states at ``times`` (clipped to its span), ready for
    :meth:`SystemScene.update`: centre positions and rotations by cubic Hermite interpolation
    with their own velocities, forces, the CM and X-hat linearly, and the latest event."""
    return _Sampler(trajectory).states(np.asarray(times, dtype=float), forces=forces)


class _Sampler:
    """A trajectory at any time in [t0, t_end]: centre positions and rotations by cubic Hermite
    interpolation with their own derivatives (v, omega), forces, CM and X-hat linearly."""

    def __init__(self, trajectory: Trajectory) -> None:
        self.trajectory = trajectory
        self.t = np.asarray(trajectory.t, dtype=float)

    def _hermite(self, values: FloatArray, rates: FloatArray, times: FloatArray) -> FloatArray:
        t = self.t
        if t.size == 1:
            return np.broadcast_to(values[0], (times.size, *values.shape[1:])).copy()
        k = np.clip(np.searchsorted(t, times, side="right") - 1, 0, t.size - 2)
        h = (t[k + 1] - t[k])[:, None]
        s = np.clip((times - t[k])[:, None] / h, 0.0, 1.0)
        s2, s3 = s * s, s * s * s
        return (
            (2 * s3 - 3 * s2 + 1) * values[k]
            + (s3 - 2 * s2 + s) * h * rates[k]
            + (-2 * s3 + 3 * s2) * values[k + 1]
            + (s3 - s2) * h * rates[k + 1]
        )

    def _linear(self, values: FloatArray, times: FloatArray) -> FloatArray:
        values = np.asarray(values, dtype=float)
        if values.ndim == 1:
            return np.interp(times, self.t, values)
        return np.stack(
            [np.interp(times, self.t, values[:, j]) for j in range(values.shape[1])], axis=-1
        ).reshape(times.size, values.shape[1])

    def states(self, times: FloatArray, *, forces: bool = True) -> list[SceneState]:
        tr = self.trajectory
        times = np.clip(np.atleast_1d(np.asarray(times, dtype=float)), self.t[0], self.t[-1])
        x = self._hermite(tr.x, tr.v, times)
        phi = self._hermite(tr.phi, tr.omega, times)
        cm = self._linear(tr.cm_x, times)
        xhat = self._linear(tr.stationary_x, times) if tr.stationary_x is not None else None
        if forces:
            friction = self._linear(tr.friction, times)
            normal = self._linear(tr.normal, times)
            tension = self._linear(tr.spring_tension, times) if tr.spring_tension.size else None
        out = []
        for k, time in enumerate(times):
            out.append(
                SceneState(
                    x=x[k],
                    phi=phi[k],
                    friction=friction[k] if forces else None,
                    normal=normal[k] if forces else None,
                    tension=(tension[k] if tension is not None else None) if forces else None,
                    cm=float(cm[k]),
                    xhat=float(xhat[k]) if xhat is not None else None,
                    time=float(time),
                    note=_event_note(tr, float(time)),
                )
            )
        return out


def _event_note(trajectory: Trajectory, time: float) -> str:
    """One line for the clock: the bodies slipping at ``time`` and the latest event (slip,
    stick, reverse, lift-off) at or before it; the run's status at its early end."""
    parts = []
    k = int(np.searchsorted(trajectory.t, time + 1e-12, side="right")) - 1
    if 0 <= k < trajectory.t.size and np.any(trajectory.slipping[k]):
        names = [n for n, s in zip(trajectory.ids, trajectory.slipping[k], strict=True) if s]
        parts.append("slipping: " + ", ".join(names))
    latest = None
    for event in trajectory.events:
        if event["time"] <= time + 1e-12:
            latest = event
    if latest is not None:
        parts.append(f"{latest['kind']}: {latest['body']} at {latest['time']:.4g} s")
    if trajectory.status != "finished" and time >= trajectory.t[-1] - 1e-12:
        parts.append(f"run ended: {trajectory.status}")
    return "   ".join(parts)


def _trajectory_force_scale(
    trajectory: Trajectory, size: float, legend_length: float = math.inf
) -> ForceScale:
    horizontal = max(_finite_max(trajectory.spring_tension), _finite_max(trajectory.friction))
    a = system_arrays(trajectory.system)
    if a.force.shape[0]:
        horizontal = max(horizontal, _finite_max(np.hypot(a.force[:, 0], a.force[:, 1])))
    return ForceScale.fit(size, horizontal, _finite_max(trajectory.normal), legend_length)


def _cover(trajectory: Trajectory, samples: int = 400) -> tuple[FloatArray, FloatArray]:
    """States spread over the run (for limits that fit the whole motion)."""
    step = max(1, trajectory.t.size // samples)
    index = np.unique(
        np.concatenate([np.arange(0, trajectory.t.size, step), [trajectory.t.size - 1]])
    )
    return trajectory.x[index], trajectory.phi[index]


def _header_points(forces: bool, clock: bool) -> float:
    """Height (points) of the rows above a scene: the force legend and the clock (16), the
    event line above the clock (13 more)."""
    return 29.0 if clock else 16.0 if forces else 0.0


_TITLE_POINTS = 15.0


def _scene_figure(
    extent: _Extent, *, width: float, header: float, title: bool, dpi: float = 100.0
) -> tuple[Figure, Axes]:
    """A figure whose axes fits ``extent`` at equal scale, with ``header`` points above it
    (legend, clock) and room for a title."""
    dx, dy = extent.xmax - extent.xmin, extent.ymax - extent.ymin
    margin = 0.08
    top = (header + (_TITLE_POINTS if title else 0.0)) / 72.0 + margin
    inner_width = width - 2 * margin
    height = float(np.clip(inner_width * dy / dx + top + margin, 1.0, 3.0 * width))
    fig = new_figure(width, height, dpi=dpi)
    with theme():
        ax = fig.add_axes(
            (margin / width, margin / height, inner_width / width, (height - top - margin) / height)
        )
    return fig, ax


def scene_for_trajectory(
    trajectory: Trajectory,
    ax: Axes | None = None,
    *,
    forces: bool = True,
    clock: bool = True,
    title: bool = False,
    width: float = 8.0,
    dpi: float = 100.0,
) -> SystemScene:
    """A scene sized for the whole run of ``trajectory`` (the animation's, and
    :func:`plot_system`'s for a trajectory), not yet updated to any time."""
    geometry = _Geometry.of(trajectory.system)
    extent = _extent(geometry, *_cover(trajectory))
    scale = (
        _trajectory_force_scale(trajectory, extent.size, 0.15 * (extent.xmax - extent.xmin))
        if forces
        else None
    )
    with theme():
        if ax is None:
            _, ax = _scene_figure(
                extent, width=width, header=_header_points(forces, clock), title=title, dpi=dpi
            )
        return SystemScene(
            ax,
            trajectory.system,
            extent,
            forces=scale,
            clock=clock,
            show_xhat=trajectory.stationary_x is not None,
        )


# -- figures ------------------------------------------------------------------------------------


def plot_system(
    result: System | LinearAnalysis | Trajectory,
    ax: Axes | None = None,
    *,
    time: float | None = None,
    at: str = "initial",
    forces: bool = False,
    title: bool = True,
) -> Axes:
    r"""The system diagram: floor and tracks, bodies, springs, walls, anchors, the CM and
    :math:`\hat X` on the floor.

    ``result`` is a :class:`~rollspring.model.System` (its initial placement; the CM, no
    :math:`\hat X`), a :class:`~rollspring.analysis.LinearAnalysis` (``at="initial"`` or
    ``"equilibrium"``; :math:`\hat X` from its weights; ``forces`` draws the equilibrium
    friction, normal forces and tensions) or a :class:`~rollspring.simulate.Trajectory` at
    ``time`` (default its start; the limits fit the whole run; ``forces`` draws spring,
    friction and normal forces to the trajectory's fixed scales).
    """
    if at not in ("initial", "equilibrium"):
        raise ValueError(f"at: must be 'initial' or 'equilibrium', got {at!r}")
    with theme():
        if isinstance(result, Trajectory):
            scene = scene_for_trajectory(
                result, ax, forces=forces, clock=False, title=title, width=6.4
            )
            t = float(result.t[0] if time is None else time)
            state = _Sampler(result).states(np.array([t]), forces=forces)[0]
            scene.update(state)
            ax = scene.ax
            if title:
                ax.set_title(
                    f"{result.system.name or 'system'}   t = {t:.3f} s",
                    loc="left",
                    pad=_header_points(forces, False) + 3,
                )
            return ax
        system = result.system if isinstance(result, LinearAnalysis) else result
        geometry = _Geometry.of(system)
        a = geometry.arrays
        q = np.zeros(a.n_bodies)
        if isinstance(result, LinearAnalysis) and at == "equilibrium":
            q = np.asarray(result.equilibrium.q, dtype=float)
        x, phi = centre_positions(a, q), a.rolls * q
        extent = _extent(geometry, x[None, :], phi[None, :])
        xhat = None
        scale = None
        state_forces: dict[str, Any] = {}
        if isinstance(result, LinearAnalysis):
            if result.stationary_weights is not None:
                xhat = float(result.stationary_weights @ x)
            if forces and at == "equilibrium":
                scale = ForceScale.fit(
                    extent.size,
                    max(
                        _finite_max(result.spring_tension),
                        _finite_max(result.equilibrium_friction),
                        _finite_max(np.hypot(a.force[:, 0], a.force[:, 1])),
                    ),
                    _finite_max(result.equilibrium_normal),
                    0.15 * (extent.xmax - extent.xmin),
                )
                state_forces = {
                    "friction": result.equilibrium_friction,
                    "normal": result.equilibrium_normal,
                    "tension": result.spring_tension,
                }
        if ax is None:
            _, ax = _scene_figure(
                extent, width=6.4, header=_header_points(scale is not None, False), title=title
            )
        scene = SystemScene(ax, system, extent, forces=scale, show_xhat=xhat is not None)
        cm = float(centre_of_mass(a, q))
        scene.update(SceneState(x=x, phi=phi, cm=cm, xhat=xhat, **state_forces))
        if title:
            where = (
                " (equilibrium)"
                if at == "equilibrium" and isinstance(result, LinearAnalysis)
                else ""
            )
            ax.set_title(
                (system.name or "system") + where,
                loc="left",
                pad=_header_points(scale is not None, False) + 3,
            )
        return ax


def _time_axes(ax: Axes | None, width: float = 6.4, height: float = 3.0) -> Axes:
    if ax is not None:
        return ax
    fig = new_figure(width, height)
    ax = fig.add_subplot()
    fig.subplots_adjust(left=0.13, right=0.97, bottom=0.15, top=0.9)
    return ax


def _first_event(trajectory: Trajectory, kind: str) -> dict[str, Any] | None:
    return next((e for e in trajectory.events if e["kind"] == kind), None)


def plot_positions(
    trajectory: Trajectory, ax: Axes | None = None, *, relative: bool = True
) -> Axes:
    r"""Centre positions against time, with the centre of mass (dashed) and the stationary point
    :math:`\hat X` (dotted). ``relative`` (default) plots each displacement from its initial
    value, so oscillations of millimetres are visible next to bodies half a metre apart."""
    with theme():
        ax = _time_axes(ax)
        t = trajectory.t
        for i, name in enumerate(trajectory.ids):
            x = trajectory.x[:, i]
            ax.plot(t, x - x[0] if relative else x, color=BODY_COLORS[i % 10], label=name)
        cm = trajectory.cm_x
        ax.plot(t, cm - cm[0] if relative else cm, color=COLORS["cm"], ls="--", lw=1.1, label="CM")
        if trajectory.stationary_x is not None:
            xh = trajectory.stationary_x
            ax.plot(
                t,
                xh - xh[0] if relative else xh,
                color=COLORS["xhat"],
                ls=":",
                lw=1.8,
                label=r"$\hat{X}$",
            )
        ax.set_xlabel("t (s)")
        ax.set_ylabel("displacement from start (m)" if relative else "position (m)")
        ax.set_title("Centre positions", loc="left")
        ax.legend(
            loc="lower right",
            bbox_to_anchor=(1.0, 1.0),
            borderaxespad=0.2,
            ncols=len(trajectory.ids) + 2,
        )
        ax.margins(x=0)
        return ax


def _rows_figure(
    fig: Figure | None, rows: int, columns: int, *, width: float = 7.0, row_height: float = 1.9
) -> tuple[Figure, np.ndarray]:
    if fig is None:
        fig = new_figure(width, row_height * rows + 0.7)
    axes = np.atleast_2d(fig.subplots(rows, columns, squeeze=False, sharex=True))
    fig.subplots_adjust(
        left=0.14,
        right=0.97,
        bottom=0.5 / (row_height * rows + 0.7),
        top=1 - 0.35 / (row_height * rows + 0.7),
        hspace=0.35,
        wspace=0.3,
    )
    return fig, axes


def plot_contact_forces(trajectory: Trajectory, fig: Figure | None = None) -> Figure:
    r"""Friction :math:`f` (positive along +x) with the band :math:`\pm\mu_s N` inside which the
    body rolls, and the normal force :math:`N` (lift-off at 0); one row per body."""
    with theme():
        n = len(trajectory.ids)
        fig, axes = _rows_figure(fig, n, 2)
        t = trajectory.t
        mu = [b.mu_static for b in trajectory.system.bodies]
        rolls = [b.rolls for b in trajectory.system.bodies]
        for i, name in enumerate(trajectory.ids):
            left, right = axes[i]
            color = BODY_COLORS[i % 10]
            normal = trajectory.normal[:, i]
            if rolls[i] and math.isfinite(mu[i]):
                limit = mu[i] * normal
                left.fill_between(t, -limit, limit, color=color, alpha=0.12, lw=0)
                left.plot(t, limit, color=color, lw=0.6, alpha=0.5)
                left.plot(t, -limit, color=color, lw=0.6, alpha=0.5)
            left.plot(t, trajectory.friction[:, i], color=color, label="f")
            left.axhline(0.0, color="0.6", lw=0.6)
            note = (
                "slider: no friction"
                if not rolls[i]
                else r"$\mu_s = \infty$ (rolling enforced)"
                if not math.isfinite(mu[i])
                else rf"$\mu_s = {mu[i]:g}$"
            )
            left.text(
                0.99, 0.96, note, transform=left.transAxes, ha="right", va="top", fontsize=7.5
            )
            left.set_ylabel(f"{name}\nf (N)")
            right.plot(t, normal, color=color)
            right.axhline(0.0, color="0.6", lw=0.6)
            top = _finite_max(normal)
            finite = normal[np.isfinite(normal)]
            lowest = min(0.0, float(np.min(finite, initial=0.0)))
            right.set_ylim(1.15 * lowest, max(top * 1.15, 1e-9))
            right.set_ylabel("N (N)")
            if i == 0:
                left.set_title(
                    r"Friction $f$ (line), rolling while inside $\pm\mu_s N$ (band)", loc="left"
                )
                right.set_title("Normal force (lift-off at 0)", loc="left")
            for ax in (left, right):
                ax.margins(x=0)
        axes[-1, 0].set_xlabel("t (s)")
        axes[-1, 1].set_xlabel("t (s)")
        return fig


def plot_friction_ratio(trajectory: Trajectory, ax: Axes | None = None) -> Axes:
    r""":math:`|f|/(\mu_s N)` of every body that can slip (rolling, finite :math:`\mu_s`): slip
    starts where it reaches 1. The first slip (and lift-off) is marked with its time and body."""
    with theme():
        ax = _time_axes(ax)
        t = trajectory.t
        drawn = 0
        for i, body in enumerate(trajectory.system.bodies):
            if not body.rolls or not math.isfinite(body.mu_static):
                continue
            ratio = trajectory.friction_ratio[:, i]
            ratio = np.where(np.isfinite(ratio), ratio, np.nan)
            ax.plot(t, ratio, color=BODY_COLORS[i % 10], label=body.id)
            drawn += 1
        ax.axhline(1.0, color=COLORS["applied"], ls="--", lw=1.0, label=r"slip: $|f| = \mu_s N$")
        ax.set_ylim(0.0, max(1.1, 1.1 * _finite_max(trajectory.friction_ratio)))
        for kind, marker in (("slip", "o"), ("liftoff", "s")):
            event = _first_event(trajectory, kind)
            if event is None:
                continue
            ax.axvline(event["time"], color="0.3", ls=":", lw=1.0)
            y = 1.0 if kind == "slip" else 0.05
            ax.plot([event["time"]], [y], marker, ms=6, mfc="white", mec="black", mew=1.3, zorder=5)
            ax.annotate(
                f"first {'slip' if kind == 'slip' else 'lift-off'}: {event['body']}, "
                f"t = {event['time']:.4g} s",
                (event["time"], y),
                xytext=(6, 8),
                textcoords="offset points",
                fontsize=7.5,
            )
        if not drawn:
            ax.text(
                0.5,
                0.5,
                "no body can slip (sliders, or rolling enforced)",
                transform=ax.transAxes,
                ha="center",
                va="center",
            )
        ax.set_xlabel("t (s)")
        ax.set_ylabel(r"$|f| / (\mu_s N)$")
        ax.set_title("Friction used", loc="left")
        ax.legend(loc="lower right", bbox_to_anchor=(1.0, 1.0), borderaxespad=0.2, ncols=drawn + 1)
        ax.margins(x=0)
        return ax


def plot_energy(trajectory: Trajectory, ax: Axes | None = None) -> Axes:
    """Kinetic, potential (springs and applied forces) and total energy against time; gravity,
    a constant while the bodies roll, is left out."""
    with theme():
        ax = _time_axes(ax)
        t = trajectory.t
        ax.plot(t, trajectory.kinetic, color="#d95f02", label="kinetic")
        ax.plot(t, trajectory.potential, color="#1b9e77", label="potential")
        ax.plot(t, trajectory.energy, color="black", lw=1.6, label="total")
        error = trajectory.summary.get("energy_error")
        if error is not None:
            ax.text(
                0.99,
                0.03,
                f"relative energy error {error:.2g}",
                transform=ax.transAxes,
                ha="right",
                va="bottom",
                fontsize=7.5,
            )
        ax.set_xlabel("t (s)")
        ax.set_ylabel("energy (J)")
        ax.set_title("Energy", loc="left")
        ax.set_ylim(bottom=min(0.0, float(np.nanmin(trajectory.potential))))
        ax.legend(loc="lower right", bbox_to_anchor=(1.0, 1.0), borderaxespad=0.2, ncols=3)
        ax.margins(x=0)
        return ax


def plot_phase_portraits(trajectory: Trajectory, fig: Figure | None = None) -> Figure:
    """Velocity against displacement from the start, one panel per body; the start is marked."""
    with theme():
        n = len(trajectory.ids)
        columns = min(n, 3)
        rows = math.ceil(n / columns)
        if fig is None:
            fig = new_figure(2.6 * columns + 0.4, 2.5 * rows + 0.3)
        axes = np.atleast_1d(fig.subplots(rows, columns, squeeze=False).ravel())
        fig.subplots_adjust(
            left=0.5 / (2.6 * columns + 0.4) + 0.06,
            right=0.97,
            bottom=0.55 / (2.5 * rows + 0.3),
            top=1 - 0.35 / (2.5 * rows + 0.3),
            wspace=0.45,
            hspace=0.5,
        )
        for i, name in enumerate(trajectory.ids):
            ax = axes[i]
            x = trajectory.x[:, i] - trajectory.x[0, i]
            v = trajectory.v[:, i]
            ax.plot(x, v, color=BODY_COLORS[i % 10], lw=1.0)
            ax.plot([x[0]], [v[0]], "o", ms=4, color=BODY_COLORS[i % 10])
            ax.set_title(name, loc="left")
            ax.xaxis.set_major_locator(MaxNLocator(4))
            ax.set_xlabel("x − x(0) (m)")
            ax.set_ylabel("v (m/s)")
        for ax in axes[n:]:
            ax.set_visible(False)
        return fig


def plot_modes(analysis: LinearAnalysis, fig: Figure | None = None) -> Figure:
    r"""One panel per normal mode: the system at equilibrium with an arrow above each body for
    its centre displacement in the mode (largest = 1, drawn 1.2 radii long), titled with
    :math:`\omega`, the frequency and the period; a zero mode is the free motion that moves
    :math:`\hat X`."""
    with theme():
        system = analysis.system
        geometry = _Geometry.of(system)
        a = geometry.arrays
        q = np.asarray(analysis.equilibrium.q, dtype=float)
        x, phi = centre_positions(a, q), a.rolls * q
        size = float(np.max(a.radius))
        length = 1.2 * size  # the drawn length of a unit displacement
        extent = _extent(geometry, x[None, :], phi[None, :], side_extra=length + 0.6 * size)
        # the arrows go 14 points above each body's label: room for them, in metres
        metres_per_point = (extent.xmax - extent.xmin) / (6.14 * 72.0)
        extent = _extent(
            geometry,
            x[None, :],
            phi[None, :],
            side_extra=length + 0.6 * size,
            top_extra=20.0 * metres_per_point,
        )
        modes = analysis.modes
        if fig is None:
            dx, dy = extent.xmax - extent.xmin, extent.ymax - extent.ymin
            panel = 6.2 * dy / dx + 0.35
            fig = new_figure(6.4, panel * len(modes) + 0.1)
        height = fig.get_figheight()
        panel_fraction = 1.0 / max(len(modes), 1)
        xhat = (
            float(analysis.stationary_weights @ x)
            if analysis.stationary_weights is not None
            else None
        )
        cm = float(centre_of_mass(a, q))
        for k, mode in enumerate(modes):
            bottom = 1.0 - (k + 1) * panel_fraction
            ax = fig.add_axes((0.02, bottom + 0.02 / height, 0.96, panel_fraction - 0.32 / height))
            scene = SystemScene(ax, system, extent, show_xhat=xhat is not None)
            scene.update(SceneState(x=x, phi=phi, cm=cm, xhat=xhat))
            above = ax.transData + ScaledTranslation(0.0, 14.0 / 72.0, fig.dpi_scale_trans)
            for i in range(a.n_bodies):
                value = float(mode.shape_x[i])
                top = float(a.track[i] + 2 * a.radius[i]) + 0.08 * size  # the label's foot
                if abs(value) > 1e-9:
                    ax.add_patch(
                        FancyArrowPatch(
                            (x[i], top),
                            (x[i] + value * length, top),
                            arrowstyle="-|>",
                            mutation_scale=10,
                            color=COLORS["mode"],
                            lw=2.0,
                            shrinkA=0,
                            shrinkB=0,
                            zorder=9,
                            transform=above,
                            clip_on=False,
                        )
                    )
                ax.text(
                    x[i] + value * length + math.copysign(0.08 * size, value or 1.0),
                    top,
                    f"{value:+.3g}",
                    ha="left" if value >= 0 else "right",
                    va="center",
                    fontsize=7.5,
                    color=COLORS["mode"],
                    transform=above,
                )
            if mode.kind == "oscillating":
                heading = (
                    rf"mode {k + 1}:  $\omega$ = {mode.omega:.6g} rad/s,  "
                    f"f = {mode.frequency:.4g} Hz,  T = {mode.period:.4g} s"
                )
            elif mode.kind == "zero":
                heading = rf"mode {k + 1}:  $\omega$ = 0  (zero mode: a free motion" + (
                    r"; $\hat{X}$ moves)" if xhat is not None else ")"
                )
            else:
                heading = f"mode {k + 1}:  unstable, growth rate {mode.omega:.6g} 1/s"
            ax.set_title(heading, loc="left", pad=3)
        return fig


# -- long chains ---------------------------------------------------------------------------------

#: More bodies than this are a long chain: the report and the animation summarise them (space–time
#: images, the friction pattern as colours) instead of drawing every body.
LONG_CHAIN = 20
#: At most this many time rows in a space–time image (rows are picked evenly).
_IMAGE_ROWS = 600


def signed_friction_ratio(trajectory: Trajectory) -> FloatArray:
    r""":math:`f/(\mu_s N)` with the sign of the friction (positive along +x), (T, n): the
    trajectory's :math:`|f|/(\mu_s N)` signed; 0 for a slider and where it is not finite."""
    ratio = np.nan_to_num(np.asarray(trajectory.friction_ratio, dtype=float), posinf=0.0)
    result: FloatArray = np.sign(np.asarray(trajectory.friction, dtype=float)) * ratio
    return result


def _even_rows(count: int, most: int = _IMAGE_ROWS) -> np.ndarray:
    return np.unique(np.linspace(0, count - 1, min(count, most)).round().astype(int))


def _symmetric(values: FloatArray) -> float:
    top = float(np.max(np.abs(values), initial=0.0))
    return top if top > 0 else 1.0


def plot_space_time(trajectory: Trajectory, waves: Waves, fig: Figure | None = None) -> Figure:
    r"""Three space–time images of a long chain (rest position x across, time up): the centre
    displacement :math:`x_i - x_{i,\mathrm{rest}}`, the signed friction ratio
    :math:`f_i/(\mu_s N_i)` (slip at ±1) and the energy per body :math:`e_i`, the last with the
    energy centroid :math:`X_E(t)` and, for a packet, the line :math:`X_E(0) + v_g t` of the
    group velocity (for a struck end, the front and :math:`\max|v_g|\,t`); the clear window
    is marked."""
    with theme():
        if fig is None:
            fig = new_figure(7.2, 7.4)
        axes = fig.subplots(3, 1, sharex=True)
        fig.subplots_adjust(left=0.1, right=0.86, bottom=0.07, top=0.95, hspace=0.32)
        rows = _even_rows(trajectory.t.size)
        t = trajectory.t[rows]
        x_rest = waves.reference
        order = np.argsort(x_rest, kind="stable")
        edges = (float(x_rest.min()), float(x_rest.max()))
        span = (edges[0], edges[1], float(t[0]), float(t[-1]) if t.size > 1 else float(t[0]) + 1)
        displacement = (np.asarray(trajectory.x)[rows] - x_rest)[:, order]
        friction = signed_friction_ratio(trajectory)[rows][:, order]
        energy = waves.energies[rows][:, order]
        panels = (
            (displacement, "RdBu_r", "displacement from rest (m)", True),
            (friction, "PuOr_r", "f / (μs N), signed", True),
            (energy, "viridis", "energy per body (J)", False),
        )
        for ax, (values, cmap, label, symmetric) in zip(axes, panels, strict=True):
            top = _symmetric(values)
            image = ax.imshow(
                values,
                origin="lower",
                aspect="auto",
                extent=span,
                cmap=cmap,
                vmin=-top if symmetric else 0.0,
                vmax=top,
                interpolation="nearest",
            )
            bar = fig.colorbar(image, ax=ax, fraction=0.04, pad=0.02)
            bar.set_label(label, fontsize=7.5)
            ax.set_ylabel("t (s)")
        axes[0].set_title("Displacement", loc="left")
        axes[1].set_title("Friction the rolling needs, against μs N", loc="left")
        ax = axes[2]
        ax.set_title("Energy, its centroid and the group velocity", loc="left")
        ax.plot(waves.centroid[rows], t, color="white", lw=1.4, label="energy centroid X_E")
        full = trajectory.t
        if waves.kind == "packet" and math.isfinite(waves.group_velocity):
            line = waves.centroid[0] + waves.group_velocity * (full - full[0])
            ax.plot(line, full, color="#e7298a", lw=1.2, ls="--", label="X_E(0) + v_g t")
        if waves.kind == "front" and waves.front is not None:
            sign = 1.0 if waves.start <= edges[0] else -1.0
            ax.plot(waves.start + sign * waves.front[rows], t, color="white", lw=1.0, ls=":")
            if math.isfinite(waves.max_group_velocity):
                line = waves.start + sign * waves.max_group_velocity * (full - full[0])
                ax.plot(line, full, color="#e7298a", lw=1.2, ls="--", label="max |v_g| t")
        if waves.window >= 1:
            for panel in axes:
                panel.axhline(waves.window_end, color="#666666", lw=0.8, ls="-.")
        ax.set_xlim(*edges)
        ax.set_ylim(span[2], span[3])
        ax.set_xlabel("rest position x (m)")
        ax.legend(loc="upper right", fontsize=7, framealpha=0.8)
        return fig

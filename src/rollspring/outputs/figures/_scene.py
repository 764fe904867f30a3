"""The scene: the artists of one drawing of a system (floor and tracks, bodies, zigzag springs,
walls and anchors, force arrows with their legend, the CM and X-hat markers, a clock), created
once by :class:`SystemScene` and moved by :meth:`SystemScene.update` with a :class:`SceneState`
(the static figures draw one state, the animation many).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np
from matplotlib.artist import Artist
from matplotlib.axes import Axes
from matplotlib.collections import LineCollection
from matplotlib.offsetbox import AnchoredOffsetbox, AuxTransformBox, HPacker, TextArea
from matplotlib.patches import Circle, FancyArrowPatch, Rectangle

from rollspring.model import System
from rollspring.outputs.figures._geometry import ForceScale, _Extent, _Geometry, _zigzag
from rollspring.outputs.figures._style import COLORS
from rollspring.physics.arrays import FloatArray


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
            self.clock = _corner_text(ax, 3, fontsize=8.5, family="DejaVu Sans Mono")
            self.note = _corner_text(ax, 16, fontsize=7.5, color=COLORS["applied"])

    # construction -------------------------------------------------------------------------
    def _draw_ground(self) -> None:
        ax, e = self.ax, self.extent
        band = 0.22 * e.size
        _hatched(ax, (e.xmin, e.floor - band), e.xmax - e.xmin, band, "none", "floor", 0.0, 1)
        ax.plot([e.xmin, e.xmax], [e.floor, e.floor], color=COLORS["floor"], lw=1.4, zorder=2)
        for height, left, right in e.track_spans:
            raised = (left, e.floor), right - left, height - e.floor
            _hatched(ax, *raised, "white", "floor", 1.0, 1.5, hatch="\\\\\\\\")
            ax.plot([left, right], [height, height], color=COLORS["floor"], lw=1.4, zorder=2)
        for x, y, width, height in e.walls:
            _hatched(ax, (x, y), width, height, "white", "wall", 1.0, 1.5)

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


def _corner_text(ax: Any, above: float, **style: Any) -> Any:
    """An empty text ``above`` points over the axes' top right corner (the clock, the note)."""
    return ax.annotate(
        "",
        (1.0, 1.0),
        xycoords="axes fraction",
        xytext=(0, above),
        textcoords="offset points",
        ha="right",
        va="bottom",
        **style,
    )


def _hatched(
    ax: Any,
    corner: tuple[float, float],
    width: float,
    height: float,
    face: str,
    edge: str,
    lw: float,
    zorder: float,
    hatch: str = "////",
) -> None:
    """A hatched rectangle (the floor's band, a raised track, a wall), edged in ``COLORS[edge]``."""
    ax.add_patch(
        Rectangle(
            corner,
            width,
            height,
            facecolor=face,
            edgecolor=COLORS[edge],
            hatch=hatch,
            lw=lw,
            zorder=zorder,
        )
    )

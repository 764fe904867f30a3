"""Drawings of the system from results: :func:`plot_system` (a System, a LinearAnalysis or a
Trajectory at a time), :func:`scene_for_trajectory` (a scene sized for a whole run, the
animation's) and :func:`states_at` (a trajectory's :class:`SceneState` at any times: Hermite
interpolation of positions and rotations with their own rates, forces linearly).
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np
from matplotlib.axes import Axes
from matplotlib.figure import Figure

from rollspring.analysis import LinearAnalysis
from rollspring.model import System
from rollspring.outputs.figures._geometry import (
    ForceScale,
    _Extent,
    _extent,
    _finite_max,
    _Geometry,
)
from rollspring.outputs.figures._scene import SceneState, SystemScene
from rollspring.outputs.figures._style import new_figure, theme
from rollspring.physics import centre_of_mass, centre_positions, system_arrays
from rollspring.physics.arrays import FloatArray
from rollspring.simulate import Trajectory


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

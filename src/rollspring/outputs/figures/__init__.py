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
* :func:`plot_fit` ``(fit, fig=None) -> Figure``: a measured table over the fitted model, and
  the residuals (:class:`~rollspring.lab.fit.FitResult`).
* Long chains (more than :data:`~rollspring.model.chains.LONG_CHAIN` bodies), summarised
  instead of one curve per body:
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

Modules, by figure kind: ``_style`` (palette, :func:`theme`, saving), ``_geometry`` (end points,
extent, the zigzag, :class:`ForceScale`), ``_scene`` (:class:`SystemScene`), ``_system``
(:func:`plot_system`, :func:`scene_for_trajectory`, :func:`states_at`), ``_time`` (the time
plots), ``_modes`` (:func:`plot_modes`), ``_fit`` (:func:`plot_fit`) and ``_chain`` (long
chains); this package re-exports their public names.
"""

from __future__ import annotations

from rollspring.outputs.figures._chain import plot_space_time, signed_friction_ratio
from rollspring.outputs.figures._fit import plot_fit
from rollspring.outputs.figures._geometry import ForceScale
from rollspring.outputs.figures._modes import plot_modes
from rollspring.outputs.figures._scene import SceneState, SystemScene
from rollspring.outputs.figures._style import (
    BODY_COLORS,
    COLORS,
    figure_png,
    figure_rgba,
    figure_svg,
    new_figure,
    theme,
)
from rollspring.outputs.figures._system import plot_system, scene_for_trajectory, states_at
from rollspring.outputs.figures._time import (
    plot_contact_forces,
    plot_energy,
    plot_friction_ratio,
    plot_phase_portraits,
    plot_positions,
)

__all__ = [
    "BODY_COLORS",
    "COLORS",
    "ForceScale",
    "SceneState",
    "SystemScene",
    "figure_png",
    "figure_rgba",
    "figure_svg",
    "new_figure",
    "plot_contact_forces",
    "plot_energy",
    "plot_fit",
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

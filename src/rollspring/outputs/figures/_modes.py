"""The normal modes drawn on the system: one panel per mode, an arrow over each body for its
displacement in the mode, titled with its frequency and period.
"""

from __future__ import annotations

import math

import numpy as np
from matplotlib.figure import Figure
from matplotlib.patches import FancyArrowPatch
from matplotlib.transforms import ScaledTranslation

from rollspring.analysis import LinearAnalysis
from rollspring.outputs.figures._geometry import _extent, _Geometry
from rollspring.outputs.figures._scene import SceneState, SystemScene
from rollspring.outputs.figures._style import COLORS, new_figure, theme
from rollspring.physics import centre_of_mass, centre_positions


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

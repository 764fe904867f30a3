"""Long chains (more than :data:`~rollspring.model.chains.LONG_CHAIN` bodies), summarised
instead of drawn body by body: space–time images of the displacement, the signed friction ratio
and the energy per body, with the energy centroid and the group-velocity line.
"""

from __future__ import annotations

import math

import numpy as np
from matplotlib.figure import Figure

from rollspring.analysis.waves import Waves
from rollspring.outputs.figures._style import new_figure, theme
from rollspring.physics.arrays import FloatArray
from rollspring.simulate import Trajectory

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

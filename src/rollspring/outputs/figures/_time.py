"""Time plots of a trajectory: centre positions with the CM and X-hat, contact forces against
the friction band, the friction ratio with the first slip, energies, and phase portraits.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np
from matplotlib.axes import Axes
from matplotlib.figure import Figure
from matplotlib.ticker import MaxNLocator

from rollspring.outputs.figures._geometry import _finite_max
from rollspring.outputs.figures._style import BODY_COLORS, COLORS, new_figure, theme
from rollspring.simulate import Trajectory


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

"""The analysis of a long chain on the terminal: summaries instead of a row per body and a
column per mode (a 1000-body chain would print a million cells)."""

from __future__ import annotations

from collections import Counter
from typing import TYPE_CHECKING

import numpy as np

from rollspring.analysis.conventions import CONVENTIONS
from rollspring.cli.tables import _g
from rollspring.cli.text import markup, plain

if TYPE_CHECKING:
    from rich.console import Console

    from rollspring.analysis.linear import LinearAnalysis, Mode

__all__ = ["print_long_analysis"]

#: Modes listed at each end of the spectrum, warnings listed in full, of a long system.
_EDGE_MODES, _WARNINGS = 8, 10


def print_long_analysis(console: Console, result: LinearAnalysis) -> None:
    """The analysis of a long chain (more than :data:`~rollspring.model.chains.LONG_CHAIN`
    bodies): bodies by kind, the extremes of the equilibrium forces, the ends of the
    spectrum, the response's extremes (which body), the springs' ranges; ``analyze --json``
    and the Python API hold every number."""
    from rich.table import Table

    arrays = result.arrays
    system = result.system
    ids = arrays.ids
    n = arrays.n_bodies
    console.print(f"[bold]{markup(system.name or 'system')}[/bold]: {n} bodies")
    if system.description:
        console.print(plain(system.description), markup=False)
    console.print()

    kinds = Counter(
        (b.shape, b.mass, b.radius, b.mu_static if b.rolls else None) for b in system.bodies
    )
    bodies = Table(title="Bodies, by kind", title_justify="left")
    for col in ("count", "shape", "m (kg)", "R (m)", "μs"):
        bodies.add_column(col, justify="right" if col != "shape" else "left")
    for (shape, mass, radius, mu), count in kinds.most_common():
        bodies.add_row(
            str(count), shape, _g(mass, 4), _g(radius, 4), "-" if mu is None else _g(mu, 3)
        )
    console.print(bodies)
    friction, normal = result.equilibrium_friction, result.equilibrium_normal
    console.print(
        f"At equilibrium: |f| ≤ {_g(float(np.max(np.abs(friction))), 4)} N "
        f"({ids[int(np.argmax(np.abs(friction)))]}), N from {_g(float(normal.min()), 5)} to "
        f"{_g(float(normal.max()), 5)} N",
        markup=False,
    )
    console.print()

    modes = Table(
        title=f"Normal modes: {len(result.modes)} computed"
        + (f" of {n}" if len(result.modes) < n else ""),
        title_justify="left",
    )
    for col in ("mode", "ω (rad/s)", "f (Hz)", "period (s)", "peak |f| (N/m)"):
        modes.add_column(col, justify="right" if col != "mode" else "left")
    listed: list[tuple[int, Mode | None]] = list(enumerate(result.modes, 1))
    if len(listed) > 2 * _EDGE_MODES:
        listed = [*listed[:_EDGE_MODES], (0, None), *listed[-_EDGE_MODES:]]
    for number, mode in listed:
        if mode is None:
            modes.add_row(f"… {len(result.modes) - 2 * _EDGE_MODES} more", "", "", "", "")
            continue
        label = {"zero": f"{number} (zero)", "unstable": f"{number} UNSTABLE"}.get(
            mode.kind, str(number)
        )
        modes.add_row(
            label,
            _g(mode.omega, 8),
            _g(mode.frequency),
            _g(mode.period),
            _g(float(np.max(np.abs(mode.friction), initial=0.0)), 4),
        )
    console.print(modes)
    console.print(
        "[dim]peak |f|: the largest friction change along the mode, per metre of its largest "
        "centre displacement; shapes: analyze --json, or analysis.modes\\[k].shape_x.[/dim]"
    )
    if result.stationary_weights is not None:
        console.print(
            f"Stationary point X̂ = {_g(result.stationary_position or 0.0)} m", markup=False
        )
    console.print()

    if result.amplitude is not None:
        assert result.friction_amplitude is not None and result.required_mu is not None
        assert result.normal_force_range is not None
        resp = Table(
            title="Response to the initial conditions (linear, exact modal superposition)",
            title_justify="left",
        )
        for col in ("largest", "value", "body"):
            resp.add_column(col, justify="right" if col == "value" else "left")
        rolling = arrays.rolls > 0
        need = np.where(rolling, result.required_mu, 0.0)
        rows = [
            ("amplitude (m)", result.amplitude),
            ("|f| (N)", result.friction_amplitude),
            ("μ needed", need),
        ]
        for label, values in rows:
            k = int(np.argmax(values))
            resp.add_row(label, _g(float(values[k]), 5), ids[k])
        lowest = int(np.argmin(result.normal_force_range[:, 0]))
        resp.add_row(
            "smallest N (N)", _g(float(result.normal_force_range[lowest, 0]), 5), ids[lowest]
        )
        console.print(resp)
        slipping = int(np.sum(rolling & (need > arrays.mu_static)))
        console.print(
            f"{slipping} of {int(rolling.sum())} rolling bodies need more than their μs"
            f"; CM amplitude {_g(result.cm_amplitude or 0.0)} m",
            markup=False,
        )
    if arrays.n_springs:
        console.print(
            f"Springs: {arrays.n_springs}, tension from {_g(float(result.spring_tension.min()))} "
            f"to {_g(float(result.spring_tension.max()))} N, tilt up to "
            f"{_g(float(np.max(np.abs(result.spring_tilt_deg))), 4)}°",
            markup=False,
        )
    console.print(f"[dim]Signs: φ {CONVENTIONS['phi']}; friction: {CONVENTIONS['friction']}.[/dim]")
    for warning in result.warnings[:_WARNINGS]:
        console.print(f"[yellow]warning:[/yellow] {markup(warning)}", highlight=False)
    if len(result.warnings) > _WARNINGS:
        console.print(
            f"[yellow]warning:[/yellow] … and {len(result.warnings) - _WARNINGS} more "
            "(analyze --json lists them all)",
            highlight=False,
        )

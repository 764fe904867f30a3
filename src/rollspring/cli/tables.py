"""Rich tables for ``rollspring analyze``."""

from __future__ import annotations

import math
from typing import Any

import numpy as np
from rich.console import Console
from rich.table import Table

from rollspring.analysis import LinearAnalysis
from rollspring.analysis.conventions import CONVENTIONS
from rollspring.cli.text import markup, plain
from rollspring.model.chains import LONG_CHAIN
from rollspring.outputs.numbers import integrator_words

__all__ = ["print_analysis"]


def _g(value: float, digits: int = 6) -> str:
    if value is None or (isinstance(value, float) and math.isnan(value)):
        return "-"
    if math.isinf(value):
        return "∞"
    if value == 0:
        return "0"
    return f"{value:.{digits}g}"


def print_analysis(console: Console, result: LinearAnalysis) -> None:
    """Print the whole analysis as a few readable tables."""
    arrays = result.arrays
    system = result.system
    ids = arrays.ids
    console.print(f"[bold]{markup(system.name or 'system')}[/bold]")
    if system.description:  # the user's text: printed as it reads, never as markup
        console.print(plain(system.description), markup=False)
    console.print()

    bodies = Table(title="Bodies at equilibrium", title_justify="left")
    for col in ("body", "shape", "m (kg)", "R (m)", "J (kg m²)", "μs", "x (m)", "f (N)", "N (N)"):
        bodies.add_column(col, justify="right" if col != "body" else "left")
    x_eq = arrays.x0 + arrays.scale * result.equilibrium.q
    for i, body in enumerate(system.bodies):
        bodies.add_row(
            body.id,
            body.shape,
            _g(body.mass, 4),
            _g(body.radius, 4),
            _g(float(arrays.inertia[i]), 4),
            _g(body.mu_static, 3) if body.rolls else "-",
            _g(float(x_eq[i]), 5),
            _g(float(result.equilibrium_friction[i]), 4),
            _g(float(result.equilibrium_normal[i]), 5),
        )
    console.print(bodies)

    modes = Table(title="Normal modes", title_justify="left")
    for col in ("mode", "ω (rad/s)", "f (Hz)", "period (s)", "ω² (1/s²)"):
        modes.add_column(col, justify="right" if col != "mode" else "left")
    labels = []
    for n, mode in enumerate(result.modes, 1):
        label = {"zero": f"{n} (zero)", "unstable": f"{n} UNSTABLE"}.get(mode.kind, str(n))
        labels.append(str(n))
        modes.add_row(
            label, _g(mode.omega, 8), _g(mode.frequency), _g(mode.period), _g(mode.eigenvalue, 8)
        )
    console.print(modes)
    shapes = Table(
        title="Mode shapes: centre displacement x (largest = 1) and friction f (N) along it",
        title_justify="left",
    )
    shapes.add_column("body")
    for label in labels:
        shapes.add_column(f"x{label}", justify="right")
        shapes.add_column(f"f{label}", justify="right")
    for i, body_id in enumerate(ids):
        cells: list[str] = []
        for mode in result.modes:
            cells += [_g(float(mode.shape_x[i]), 4), _g(float(mode.friction[i]), 4)]
        shapes.add_row(body_id, *cells)
    console.print(shapes)

    if result.stationary_weights is not None:
        weights = ", ".join(
            f"{w:.6g}·x_{b}" for b, w in zip(ids, result.stationary_weights, strict=True)
        )
        is_cm = np.allclose(result.stationary_weights, arrays.mass / arrays.mass.sum())
        console.print(
            f"Stationary point X̂ = {weights} = {_g(result.stationary_position or 0.0)} m"
            + (" (the centre of mass)" if is_cm else " (not the centre of mass)"),
            markup=False,
        )
    else:
        console.print("Stationary point: none (no single zero mode)")
    console.print()

    if result.amplitude is not None:
        resp = Table(
            title="Response to the initial conditions (linear, exact modal superposition)",
            title_justify="left",
        )
        for col in (
            "body",
            "amplitude (m)",
            "max speed (m/s)",
            "|f| max (N)",
            "N range (N)",
            "μ needed",
            "μs",
        ):
            resp.add_column(col, justify="right" if col != "body" else "left")
        assert result.friction_amplitude is not None and result.normal_force_range is not None
        assert result.required_mu is not None
        for i, body in enumerate(system.bodies):
            lo, hi = result.normal_force_range[i]
            assert result.velocity_amplitude is not None
            resp.add_row(
                body.id,
                _g(float(result.amplitude[i])),
                _g(float(result.velocity_amplitude[i])),
                _g(float(result.friction_amplitude[i])),
                f"{_g(lo, 5)} … {_g(hi, 5)}",
                _g(float(result.required_mu[i]), 4) if body.rolls else "-",
                _g(body.mu_static) if body.rolls else "-",
            )
        console.print(resp)
        line = f"CM amplitude: {_g(result.cm_amplitude or 0.0)} m"
        if result.stationary_amplitude is not None:
            line += f";  X̂ amplitude: {_g(result.stationary_amplitude)} m"
        console.print(line, markup=False)
    if result.spring_split is not None:
        split = result.spring_split
        parts = ", ".join(
            f"k_{b} = {_g(float(k))} N/m" for b, k in zip(ids, split["k"], strict=True)
        )
        console.print(f"Spring split about X̂ (paper's k1, k2): {parts}", markup=False)
    if arrays.n_springs:
        springs = Table(title="Springs at equilibrium", title_justify="left")
        for col in ("spring", "length (m)", "rest (m)", "tension (N)", "tilt (°)"):
            springs.add_column(col, justify="right" if col != "spring" else "left")
        for s, name in enumerate(arrays.spring_names):
            springs.add_row(
                name,
                _g(float(result.spring_length[s])),
                _g(float(arrays.rest_length[s])),
                _g(float(result.spring_tension[s])),
                _g(float(result.spring_tilt_deg[s]), 4),
            )
        console.print(springs)
    console.print(f"[dim]Signs: φ {CONVENTIONS['phi']}; friction: {CONVENTIONS['friction']}.[/dim]")
    for warning in result.warnings:
        console.print(f"[yellow]warning:[/yellow] {markup(warning)}", highlight=False)


def print_simulation(console: Console, trajectory, written) -> None:
    """The summary of a run as Rich tables."""
    from rich.table import Table

    summary = trajectory.summary
    title = f"{trajectory.system.name}: simulated {summary['duration']:g} s"
    head = Table(
        title=markup(title),
        title_justify="left",
        show_header=False,
        # a long chain's name ("Chain of 1000 bodies (...)") on one line, not wrapped
        min_width=len(title) if len(trajectory.ids) > LONG_CHAIN else None,
    )
    head.add_column("quantity", style="bold")
    head.add_column("value")
    head.add_row(
        "status",
        markup(summary["status"] + (f" ({summary['message']})" if summary["message"] else "")),
    )
    head.add_row(
        "integrator",
        integrator_words(summary["steps_by_integrator"], summary["step"], summary["integrator"]),
    )
    energy = f"{_g(summary['energy'])}, error {summary['energy_error']:.2e}"
    if summary.get("energy_dissipated"):  # damping, kinetic friction: E + W = E0 is checked
        energy += f", dissipated {_g(summary['energy_dissipated'])}"
    head.add_row("energy (J)", energy)
    if summary["period_linear"] is not None:
        measured = summary["period_measured"]
        head.add_row(
            "period (s)",
            f"measured {_g(measured, 12) if measured else '-'}, "
            f"linear {_g(summary['period_linear'], 12)}",
        )
    for kind in ("first_slip", "first_liftoff"):
        event = summary[kind]
        head.add_row(
            kind.replace("_", " "),
            "none" if event is None else f"'{event['body']}' at t = {_g(event['time'], 12)} s",
        )
    console.print(head)
    if len(trajectory.ids) > LONG_CHAIN:
        console.print(_body_extremes(trajectory))
    else:
        console.print(_body_rows(trajectory))
    for path in written:
        console.print(f"wrote {plain(path)}", markup=False)


def _body_rows(trajectory: Any) -> Table:
    """One row per body: max |f|/N, min N and the final state."""
    summary = trajectory.summary
    bodies = Table(title="bodies", title_justify="left")
    for column in (
        "body",
        "max |f|/N",
        "min N (N)",
        "final x (m)",
        "final v (m/s)",
        "final phi (rad)",
    ):
        bodies.add_column(column, justify="right" if column != "body" else "left")
    final = summary["final"]["bodies"]
    for name in trajectory.ids:
        ratio = summary["max_friction_ratio"].get(name)
        bodies.add_row(
            name,
            "-" if ratio is None else _g(ratio),
            _g(summary["min_normal_force"][name]),
            _g(final[name]["x"]),
            _g(final[name]["v"]),
            _g(final[name]["phi"]),
        )
    return bodies


def _body_extremes(trajectory: Any) -> Table:
    """A long chain's bodies summarised: per quantity the smallest and the largest over the
    bodies and which body has it (the per-body values are in ``--json`` and ``--out``)."""
    summary = trajectory.summary
    ids = list(trajectory.ids)
    final = summary["final"]["bodies"]
    start = {name: float(trajectory.x[0, i]) for i, name in enumerate(ids)}
    quantities: list[tuple[str, dict[str, float]]] = [
        ("max |f|/N over the run", dict(summary["max_friction_ratio"])),
        ("min N over the run (N)", dict(summary["min_normal_force"])),
        ("final x − initial x (m)", {b: final[b]["x"] - start[b] for b in ids}),
        ("final v (m/s)", {b: final[b]["v"] for b in ids}),
        ("final phi (rad)", {b: final[b]["phi"] for b in ids}),
    ]
    table = Table(title=f"bodies ({len(ids)}: the extremes over them)", title_justify="left")
    for column in ("quantity", "smallest", "body", "largest", "body"):
        table.add_column(column, justify="left" if column in ("quantity", "body") else "right")
    for label, values in quantities:
        # NaN is nobody's extreme, nor None (a body that never rolled has no |f|/N rolling)
        finite = {b: v for b, v in values.items() if v is not None and v == v}
        if not finite:
            table.add_row(label, "-", "", "-", "")
            continue
        low = min(finite, key=finite.__getitem__)
        high = max(finite, key=finite.__getitem__)
        table.add_row(label, _g(finite[low]), markup(low), _g(finite[high]), markup(high))
    return table

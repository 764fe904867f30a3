"""``rollspring simulate SYSTEM``: the exact nonlinear motion, with energy, period, friction,
slip and lift-off (:func:`rollspring.simulate`, run by
:func:`rollspring.service.runs.run_request`).

``--out DIR`` writes ``trajectory.csv``, ``trajectory.npz`` and ``summary.json`` as a set;
``--json`` prints the summary as one JSON object; otherwise Rich tables
(:func:`rollspring.cli.tables.print_simulation`). A run that takes more than a second shows a
progress bar on stderr.
"""

from __future__ import annotations

from typing import Annotated

import typer

from rollspring.cli.common import (
    ProgressBar,
    add_command,
    confirm_cost,
    load,
    print_json,
    say,
    stdout_console,
)
from rollspring.cli.options import JsonOpt, SystemArg, YesOpt, out_option
from rollspring.model import DEFAULT_PRESET

__all__ = ["register", "simulate"]


def simulate(
    system: SystemArg = DEFAULT_PRESET,
    duration: Annotated[float, typer.Option("--duration", "-T", help="Simulated time, s.")] = 10.0,
    rtol: Annotated[
        float, typer.Option(help="Relative accuracy of the motion over the run.")
    ] = 1e-8,
    integrator: Annotated[
        str,
        typer.Option(
            help="auto, verlet, yoshida4, yoshida6, kahanli8 (symplectic, compiled) or dop853."
        ),
    ] = "auto",
    on_slip: Annotated[
        str,
        typer.Option(
            "--on-slip",
            help="stop: end the run when a body starts to slip; continue: run on "
            "with kinetic friction (stick-slip).",
        ),
    ] = "stop",
    outputs: Annotated[int, typer.Option("--outputs", help="Number of output times.")] = 2001,
    out: Annotated[
        str | None, out_option("Write trajectory.csv, trajectory.npz and summary.json here.")
    ] = None,
    as_json: JsonOpt = False,
    yes: YesOpt = False,
) -> None:
    """Integrate the exact nonlinear motion; report energy, period, friction, slip, lift-off."""
    if out is not None:  # an unwritable --out fails now, not after the run
        from rollspring.outputs.atomic import writable_directory

        writable_directory(out)
    from rollspring.service.costs import request_cost
    from rollspring.service.runs import run_request
    from rollspring.simulate.request import simulation_request

    model = load(system)
    # the arguments checked once, the cost estimated once: the run checks nothing again
    request = simulation_request(
        duration, rtol=rtol, integrator=integrator, on_slip=on_slip, n_output=outputs
    )
    confirm_cost(request_cost(model, request, written=out is not None), yes=yes)
    with ProgressBar("simulating") as progress:
        trajectory = run_request(model, request, progress=progress).trajectory
    written = []
    if out is not None:
        from rollspring.outputs import write_trajectory

        written = write_trajectory(trajectory, out)
    if trajectory.status != "finished":
        say(f"note: {trajectory.message}")
    if as_json:
        from rollspring.outputs import summary_json

        for path in written:
            say(f"wrote {path}")
        print_json(summary_json(trajectory))
        return
    from rollspring.cli.tables import print_simulation

    print_simulation(stdout_console(), trajectory, written)


def register(app: typer.Typer) -> None:
    """Add the ``simulate`` command to ``app`` (with rollspring's one-line error handling)."""
    add_command(app, simulate, "simulate")

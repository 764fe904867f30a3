"""``rollspring sweep SYSTEM --vary PATH=... --duration T --out sweep.zarr``: a grid of runs.

The grid is the outer product of the ``--vary`` values; the metrics go to a Zarr v3 store
(docs/sweeps.md), chunk by chunk, in this process or on a Dask cluster (``--scheduler``), and a
rerun of the same command resumes. The work is :func:`rollspring.service.sweeps.sweep`; the
command is added to an app by :func:`register`.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Annotated

import typer

from rollspring.cli.common import ProgressBar, add_command, confirm_cost, say
from rollspring.cli.options import SystemArg, out_option, yes_option
from rollspring.model import DEFAULT_PRESET

if TYPE_CHECKING:
    from rich.progress import ProgressColumn

    from rollspring.service.sweeps import SweepProgress

__all__ = ["register", "sweep"]


def sweep(
    system: SystemArg = DEFAULT_PRESET,
    vary: Annotated[
        list[str] | None,
        typer.Option(
            "--vary",
            help="PATH=START:STOP:NUM[:log] or PATH=v1,v2,... (repeatable; the grid is "
            "their outer product, in this order). PATHs: bodies.<id>.mass|radius|mu_static|"
            "mu_kinetic|x|v, springs.<i>.stiffness|rest_length, springs.<i>.at.<end>.height|radius|"
            "angle, modes.<n>.amplitude, gravity.",
            show_default=False,
        ),
    ] = None,
    duration: Annotated[
        float | None,
        typer.Option(
            "--duration", "-T", help="Simulated time of every run, s.", show_default=False
        ),
    ] = None,
    metric: Annotated[
        list[str] | None,
        typer.Option(
            "--metric",
            help="Keep only this variable (repeatable; status is always kept).",
            show_default=False,
        ),
    ] = None,
    on_slip: Annotated[
        str,
        typer.Option(
            "--on-slip",
            help="stop: a run ends at its first slip; continue: stick-slip with "
            "kinetic friction (single runs, slower).",
        ),
    ] = "stop",
    out: Annotated[str | None, out_option("The Zarr store to write (a rerun resumes it).")] = None,
    scheduler: Annotated[
        str | None,
        typer.Option(
            "--scheduler",
            help="A Dask scheduler, tcp://HOST:PORT (default: in this process, every core).",
            show_default=False,
        ),
    ] = None,
    threads: Annotated[
        int | None,
        typer.Option(
            "--threads",
            help="In this process: chunks computed at once, a thread each, while the finished "
            "ones are written (default: one for each core).",
            show_default=False,
        ),
    ] = None,
    chunk: Annotated[
        int | None,
        typer.Option(
            "--chunk",
            help="Runs per chunk (default 16384, or the chunks of the store resumed).",
            show_default=False,
        ),
    ] = None,
    rtol: Annotated[float, typer.Option(help="Relative accuracy of each run.")] = 1e-8,
    step: Annotated[
        float | None,
        typer.Option(
            "--step",
            help="Fix the integration step of the whole grid, s (default: from --rtol).",
            show_default=False,
        ),
    ] = None,
    integrator: Annotated[
        str,
        typer.Option(help="auto, verlet, yoshida4 or yoshida6 (with --step, auto means yoshida4)."),
    ] = "auto",
    refine_slip: Annotated[
        bool,
        typer.Option(
            "--refine-slip/--no-refine-slip",
            help="Root-find each first slip instant with a single "
            "run (default) instead of the batch's interpolation between steps.",
        ),
    ] = True,
    overwrite: Annotated[
        bool, typer.Option("--overwrite", help="Replace a store that holds another sweep.")
    ] = False,
    yes: Annotated[bool, yes_option("time or store size")] = False,
) -> None:
    """Run a grid of variations of a system (batched, in-process or on a Dask cluster) into a
    Zarr store: frequencies, X-hat weights, friction needed, periods, slip, lift-off."""
    from rollspring.service.sweeps import SweepError, parse_vary_spec, sweep_cost
    from rollspring.service.sweeps import sweep as run_sweep

    if not vary:
        raise SweepError("--vary: give at least one PATH=START:STOP:NUM or PATH=v1,v2,...")
    if duration is None:
        raise SweepError("--duration: missing (the simulated time of every run, s)")
    if out is None:
        raise SweepError("--out: missing (the Zarr store to write, e.g. sweep.zarr)")
    grid: dict[str, list[float]] = {}
    for spec in vary:
        path, values = parse_vary_spec(spec)
        if path in grid:
            raise SweepError(f"--vary {spec}: {path} is already varied")
        grid[path] = values
    from rollspring.model import load_system  # pydantic: not for --help

    model = load_system(system)
    cost = sweep_cost(
        model,
        grid,
        duration,
        rtol=rtol,
        integrator=integrator,
        out=out,
        smaller="fewer --vary values, a shorter --duration",
    )
    confirm_cost(cost, yes=yes)  # before the grid's values are checked one by one
    with ProgressBar(columns=_columns) as bar:
        reports = _Reports(bar)
        dataset = run_sweep(
            model,
            grid,
            duration,
            metrics=metric,
            on_slip=on_slip,
            out=out,
            scheduler=scheduler,
            chunk=chunk,
            overwrite=overwrite,
            rtol=rtol,
            progress=reports,
            step=step,
            integrator=integrator,
            refine_slip=refine_slip,
            confirm=True,  # confirmed above (--yes, or below the bound)
            threads=threads,
        )
    first = reports.first
    total = int(dataset.attrs["n_chunks"])
    ran = reports.last.chunks_run if reports.last is not None else 0
    skipped = first.chunks_skipped if first is not None else total
    runs = first.total_runs if first is not None else 0
    say(f"ran {ran} of {total} chunks ({skipped} already done; {runs} runs); wrote {out}")


class _Reports:
    """The sweep's progress reports on a progress bar (runs done, runs/s, time left); the first
    and the last are kept for the closing line."""

    def __init__(self, bar: ProgressBar) -> None:
        self.bar = bar
        self.first: SweepProgress | None = None
        self.last: SweepProgress | None = None

    def __call__(self, progress: SweepProgress) -> None:
        if self.first is None:
            self.first = progress
            self.bar.start(
                "sweep", total=progress.total_runs, completed=progress.done_runs, rate=""
            )
        self.last = progress
        rate = (progress.done_runs - self.first.done_runs) / max(self.bar.elapsed, 1e-9)
        self.bar(progress.done_runs, rate=f"{rate:,.0f} runs/s")


def _columns() -> tuple[ProgressColumn, ...]:
    """The sweep's progress bar: runs done of all, runs per second and the time left."""
    from rich.progress import BarColumn, MofNCompleteColumn, TextColumn, TimeRemainingColumn

    return (
        TextColumn("sweep"),
        BarColumn(),
        MofNCompleteColumn(),
        TextColumn("runs {task.fields[rate]}"),
        TimeRemainingColumn(),
    )


def register(app: typer.Typer) -> None:
    """Add the ``sweep`` command to ``app`` (with rollspring's one-line error handling)."""
    add_command(app, sweep, "sweep", extras="sweep")

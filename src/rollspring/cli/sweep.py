"""``rollspring sweep SYSTEM --vary PATH=... --duration T --out sweep.zarr``: a grid of runs.

The grid is the outer product of the ``--vary`` values; the metrics go to a Zarr v3 store
(docs/sweeps.md), chunk by chunk, in this process or on a Dask cluster (``--scheduler``), and a
rerun of the same command resumes. The work is :func:`rollspring.service.sweeps.sweep`; the
command is added to an app by :func:`register` (called by ``rollspring.cli.app``).
"""

from __future__ import annotations

import time
from typing import TYPE_CHECKING, Annotated

import typer

from rollspring.cli.text import say
from rollspring.model import DEFAULT_PRESET, preset_names

if TYPE_CHECKING:
    from rich.progress import Progress, TaskID

    from rollspring.service.sweeps import SweepProgress

__all__ = ["register", "sweep"]


def sweep(
    system: Annotated[
        str,
        typer.Argument(
            help=f"A system file (.toml or .json) or a preset name ({', '.join(preset_names())}).",
            show_default=False,
        ),
    ] = DEFAULT_PRESET,
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
    out: Annotated[
        str | None,
        typer.Option(
            "--out", "-o", help="The Zarr store to write (a rerun resumes it).", show_default=False
        ),
    ] = None,
    scheduler: Annotated[
        str | None,
        typer.Option(
            "--scheduler",
            help="A Dask scheduler, tcp://HOST:PORT (default: in this process, every core).",
            show_default=False,
        ),
    ] = None,
    chunk: Annotated[
        int | None,
        typer.Option("--chunk", help="Runs per chunk (default 4096).", show_default=False),
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
) -> None:
    """Run a grid of variations of a system (batched, in-process or on a Dask cluster) into a
    Zarr store: frequencies, X-hat weights, friction needed, periods, slip, lift-off."""
    from rollspring.service.sweeps import SweepError, parse_vary_spec
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
    with _Bar() as bar:
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
            progress=bar,
            step=step,
            integrator=integrator,
            refine_slip=refine_slip,
        )
    first = bar.first
    total = int(dataset.attrs["n_chunks"])
    ran = bar.last.chunks_run if bar.last is not None else 0
    skipped = first.chunks_skipped if first is not None else total
    runs = first.total_runs if first is not None else 0
    _say(f"ran {ran} of {total} chunks ({skipped} already done; {runs} runs); wrote {out}")


class _Bar:
    """A Rich progress bar on stderr: runs done, runs/s, time left (shown after a second)."""

    def __init__(self) -> None:
        self.bar: Progress | None = None
        self.task: TaskID | None = None
        self.first: SweepProgress | None = None
        self.last: SweepProgress | None = None
        self.started = 0.0

    def __enter__(self) -> _Bar:
        self.started = time.perf_counter()
        return self

    def __call__(self, progress) -> None:
        if self.first is None:
            self.first = progress
        self.last = progress
        if self.bar is None:
            if time.perf_counter() - self.started < 1.0:
                return
            from rich.console import Console
            from rich.progress import (
                BarColumn,
                MofNCompleteColumn,
                Progress,
                TextColumn,
                TimeRemainingColumn,
            )

            self.bar = Progress(
                TextColumn("sweep"),
                BarColumn(),
                MofNCompleteColumn(),
                TextColumn("runs {task.fields[rate]}"),
                TimeRemainingColumn(),
                console=Console(stderr=True),
                transient=True,
            )
            self.bar.start()
            self.task = self.bar.add_task(
                "sweep", total=progress.total_runs, rate="", completed=self.first.done_runs
            )
        elapsed = max(time.perf_counter() - self.started, 1e-9)
        rate = (progress.done_runs - self.first.done_runs) / elapsed
        if self.task is not None:  # set with the bar
            self.bar.update(self.task, completed=progress.done_runs, rate=f"{rate:,.0f} runs/s")

    def __exit__(self, *exc_info) -> None:
        if self.bar is not None:
            self.bar.stop()


def register(app: typer.Typer) -> None:
    """Add the ``sweep`` command to ``app`` (with rollspring's one-line error handling)."""
    from rollspring.cli.app import friendly_errors, needs_extra  # not at the top: app imports us

    app.command(name="sweep")(friendly_errors(needs_extra("sweep", "sweep")(sweep)))


def _say(line: str) -> None:
    """One unwrapped line on stderr, never mixed into stdout (:func:`rollspring.cli.text.say`)."""
    say(line)

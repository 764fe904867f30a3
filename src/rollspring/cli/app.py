"""``rollspring`` commands (Typer). A thin layer: parse, call the library, format.

Every error rollspring raises on purpose is printed as one line on stderr, with exit code 2;
with ``--json``, stdout holds exactly one JSON object and everything else goes to stderr.
"""

from __future__ import annotations

import functools
import json
import os
import sys
from collections.abc import Callable
from typing import TYPE_CHECKING, Annotated, Any, TypeVar

import typer
import typer.core

from rollspring.cli.text import say
from rollspring.errors import RollspringError, require_extra
from rollspring.model import DEFAULT_PRESET, preset_names, preset_path

if TYPE_CHECKING:
    from rich.console import Console
    from rich.progress import Progress, TaskID

    from rollspring.model import System

# Only what every command needs is imported here (Typer and the presets' names):
# each command imports its own (pydantic's model, SciPy, the compiled kernels, SymPy,
# Matplotlib, ...), so --help and the light commands start fast.

__all__ = ["app", "main"]


class _OneLineErrors(typer.core.TyperGroup):
    """The command group, whose usage errors (an unknown option, ``-T abc``, a missing value)
    are one line on stderr and exit code 2, like rollspring's own errors, instead of a usage
    panel; ``rollspring`` alone still prints the help."""

    def main(  # type: ignore[override]
        self,
        args: Any = None,
        prog_name: str | None = None,
        complete_var: str | None = None,
        standalone_mode: bool = True,
        **extra: Any,
    ) -> Any:
        # Typer vendors Click as typer._click: its exceptions are Typer's, not click's
        from typer._click import exceptions as click

        if not standalone_mode:
            return super().main(args, prog_name, complete_var, standalone_mode, **extra)
        try:
            code = super().main(args, prog_name, complete_var, False, **extra)
        except click.NoArgsIsHelpError as exc:  # the help is printed already
            sys.exit(exc.exit_code)
        except click.ClickException as exc:
            context = getattr(exc, "ctx", None)
            where = context.command_path if context is not None else "rollspring"
            say(f"error: {where}: {exc.format_message()} (see {where} --help)")
            sys.exit(exc.exit_code)
        except typer.Abort:
            say("aborted")
            sys.exit(1)
        sys.exit(code if isinstance(code, int) else 0)


app = typer.Typer(
    name="rollspring",
    cls=_OneLineErrors,
    help="Coupled rolling oscillators: exact rolling physics, normal modes, friction and "
    "normal forces.",
    no_args_is_help=True,
    add_completion=False,
    pretty_exceptions_enable=False,
)


def _print_version(value: bool) -> None:
    if value:
        from rollspring._version import version

        typer.echo(f"rollspring {version()}")
        raise typer.Exit()


@app.callback()
def _options(
    version: Annotated[
        bool,
        typer.Option(
            "--version",
            help="Print rollspring's version and exit.",
            is_eager=True,
            callback=_print_version,
        ),
    ] = False,
) -> None:
    """Coupled rolling oscillators: exact rolling physics, normal modes, friction and normal
    forces."""


SystemArg = Annotated[
    str,
    typer.Argument(
        help=f"A system file (.toml or .json) or a preset name ({', '.join(preset_names())}).",
        show_default=False,
    ),
]
JsonOpt = Annotated[bool, typer.Option("--json", help="Print one JSON object on stdout.")]
YesOpt = Annotated[
    bool,
    typer.Option(
        "--yes",
        "-y",
        help="Start even when the estimated time or memory is above the bound (a larger run "
        "is refused with its estimate).",
    ),
]


F = TypeVar("F", bound=Callable[..., Any])


def friendly_errors(command: F) -> F:
    """Turn rollspring's errors into one line on stderr and exit code 2 (never a traceback).

    An unexpected exception (a bug) is reported in one line with exit code 1; set
    ``ROLLSPRING_DEBUG=1`` to see its traceback. Running out of memory is one line and exit
    code 2 too (the request was too large); Ctrl-C ends the command with exit code 130, every
    temporary file removed (the writers clean up on any exception).
    """

    @functools.wraps(command)
    def wrapper(*args: Any, **kwargs: Any) -> Any:
        try:
            return command(*args, **kwargs)
        except RollspringError as exc:
            _say(f"error: {exc}")
            raise typer.Exit(2) from None
        except (typer.Exit, typer.Abort):
            raise
        except KeyboardInterrupt:
            _say("interrupted: nothing more was written")
            raise typer.Exit(130) from None
        except MemoryError:
            _say(
                "error: out of memory: ask for less (fewer --outputs, a shorter --duration, "
                "fewer bodies)"
            )
            raise typer.Exit(2) from None
        except Exception as exc:
            if os.environ.get("ROLLSPRING_DEBUG"):
                raise
            _say(
                f"internal error: {type(exc).__name__}: {exc} (please report it; "
                "ROLLSPRING_DEBUG=1 shows the traceback)"
            )
            raise typer.Exit(1) from None

    return wrapper  # type: ignore[return-value]


def needs_extra(extras: str | tuple[str, ...], name: str) -> Callable[[F], F]:
    """A command that needs an optional extra: before anything else it checks that the extra is
    installed, else ``error: rollspring NAME needs the 'EXTRA' extra: pip install
    'rollspring[EXTRA]'`` and exit code 2 (with :func:`friendly_errors`)."""

    def decorate(command: F) -> F:
        @functools.wraps(command)
        def wrapper(*args: Any, **kwargs: Any) -> Any:
            with require_extra(extras, f"rollspring {name}"):
                return command(*args, **kwargs)

        return wrapper  # type: ignore[return-value]

    return decorate


def _stdout() -> Console:
    # a terminal's own width; 110 columns when piped to a file or a pager
    from rich.console import Console

    width = None if sys.stdout.isatty() else 110
    return Console(highlight=False, soft_wrap=False, width=width)


def _say(line: str) -> None:
    """One unwrapped line on stderr (errors, warnings): never mixed into stdout; control
    characters written out, at most :data:`rollspring.cli.text.MAX_LINE` characters."""
    say(line)


def load(system: str) -> System:
    """The system a command was given (a file or a preset), with a warning on stderr for each
    pair of bodies that overlap in its initial placement."""
    from rollspring.model import load_system

    model = load_system(system)
    for warning in model.overlaps:
        _say(f"warning: {warning}")
    return model


def _print_json(data: Any) -> None:
    sys.stdout.write(json.dumps(data, indent=2, ensure_ascii=False, allow_nan=False) + "\n")
    sys.stdout.flush()


@app.command()
@friendly_errors
def analyze(
    system: SystemArg = DEFAULT_PRESET,
    as_json: JsonOpt = False,
    yes: YesOpt = False,
    modes: Annotated[
        str | None,
        typer.Option(
            "--modes",
            help="Which normal modes: K (the lowest K) or FIRST-LAST (1-based, a band); "
            "default every mode up to 2000 bodies, the lowest 20 beyond.",
            show_default=False,
        ),
    ] = None,
) -> None:
    """Linear analysis: equilibrium, M and K, normal modes, stationary point, friction needed."""
    from rollspring.errors import AnalysisError
    from rollspring.service.costs import analysis_cost, check_cost
    from rollspring.service.runs import analysis_payload

    chosen = _mode_selection(modes, AnalysisError)
    model = load(system)
    cost = analysis_cost(model, modes=chosen)
    check_cost(cost, confirmed=yes)
    if cost.long:
        _say(f"note: the analysis will take {cost.describe()}")
    if as_json:
        payload, warnings = analysis_payload(model, chosen)
        for warning in warnings:
            _say(f"warning: {warning}")
        _print_json(payload)
        return
    from rollspring.analysis import analyze as run_analysis

    result = run_analysis(model, confirm=True, modes=chosen)  # checked above (--yes)
    if len(model.bodies) > 20:  # cli.long_tables.LONG: summaries, not a row per body
        from rollspring.cli.long_tables import print_long_analysis

        print_long_analysis(_stdout(), result)
    else:
        from rollspring.cli.tables import print_analysis

        print_analysis(_stdout(), result)


def _mode_selection(text: str | None, error: type[Exception]) -> int | tuple[int, int] | None:
    """``--modes``: "K" -> K, "FIRST-LAST" -> (FIRST, LAST); checked against the system by
    :func:`rollspring.analyze` (the numbers' range), here their form."""
    if text is None:
        return None
    first, dash, last = text.strip().partition("-")
    try:
        if dash:
            return int(first), int(last)
        return int(first)
    except ValueError:
        raise error(
            f"--modes: a count K or a band FIRST-LAST of whole numbers, got {text!r}"
        ) from None


@app.command()
@friendly_errors
def schema() -> None:
    """Print the JSON Schema of a system file (TOML files have the same structure)."""
    from rollspring.model import system_json_schema

    _print_json(system_json_schema())


@app.command()
@friendly_errors
def presets(as_json: JsonOpt = False) -> None:
    """List the built-in systems (each is also a file in examples/)."""
    from rollspring.model import load_system

    rows: list[dict[str, Any]] = []
    for name in preset_names():
        system = load_system(name)
        rows.append(
            {
                "name": name,
                "title": system.name,
                "file": str(preset_path(name)),
                "default": name == DEFAULT_PRESET,
            }
        )
    if as_json:
        _print_json(rows)
        return
    from rich.table import Table

    table = Table(title="rollspring presets", title_justify="left")
    table.add_column("name", style="bold")
    table.add_column("system")
    for row in rows:
        table.add_row(row["name"] + (" (default)" if row["default"] else ""), row["title"])
    _stdout().print(table)


@app.command()
@friendly_errors
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
        str | None,
        typer.Option(
            "--out", "-o", help="Write trajectory.csv, trajectory.npz and summary.json here."
        ),
    ] = None,
    as_json: JsonOpt = False,
    yes: YesOpt = False,
) -> None:
    """Integrate the exact nonlinear motion; report energy, period, friction, slip, lift-off."""
    if out is not None:  # an unwritable --out fails now, not after the run
        from rollspring.outputs.files import writable_directory

        writable_directory(out)
    from rollspring.service.costs import check_cost, simulation_cost
    from rollspring.service.runs import run_simulation
    from rollspring.simulate.arguments import ON_SLIP, check_choice

    model = load(system)
    check_choice("on_slip", on_slip, ON_SLIP, "on_slip")
    cost = simulation_cost(
        model, duration, rtol=rtol, integrator=integrator, outputs=outputs, written=out is not None
    )
    check_cost(cost, confirmed=yes)
    if cost.long:
        _say(f"note: this run will take {cost.describe()}; Ctrl-C stops it")
    with _progress_after_a_second("simulating") as progress:
        trajectory = run_simulation(
            model,
            duration,
            rtol=rtol,
            integrator=integrator,
            outputs=outputs,
            on_slip=on_slip,
            progress=progress,
        ).trajectory
    written = []
    if out is not None:
        from rollspring.outputs import write_trajectory

        written = write_trajectory(trajectory, out)
    if trajectory.status != "finished":
        _say(f"note: {trajectory.message}")
    if as_json:
        from rollspring.outputs import summary_json

        for path in written:
            _say(f"wrote {path}")
        _print_json(summary_json(trajectory))
        return
    from rollspring.cli.tables import print_simulation

    print_simulation(_stdout(), trajectory, written)


class _progress_after_a_second:  # noqa: N801 - used as a context manager
    """A Rich progress bar on stderr that appears only once a run has taken a second."""

    def __init__(self, label: str) -> None:
        self.label = label
        self.bar: Progress | None = None
        self.task: TaskID | None = None
        self.started = 0.0

    def __enter__(self):
        import time

        self.started = time.perf_counter()
        return self

    def __call__(self, fraction: float) -> None:
        import time

        if self.bar is None:
            if time.perf_counter() - self.started < 1.0:
                return
            from rich.console import Console
            from rich.progress import Progress

            self.bar = Progress(console=Console(stderr=True), transient=True)
            self.bar.start()
            self.task = self.bar.add_task(self.label, total=1.0)
        if self.task is not None:  # set with the bar
            self.bar.update(self.task, completed=fraction)

    def __exit__(self, *exc_info) -> None:
        if self.bar is not None:
            self.bar.stop()


def main(argv: list[str] | None = None) -> None:
    """Entry point of the ``rollspring`` console command. A termination signal (SIGTERM,
    SIGHUP: ``kill``, a closed terminal) ends the command as Ctrl-C does, so that its writers
    remove their temporary files (SIGKILL cannot be caught: the next run into the same place
    removes what it left)."""
    import signal

    def stop(signum: int, frame: object) -> None:
        raise KeyboardInterrupt

    for name in ("SIGTERM", "SIGHUP"):
        if hasattr(signal, name):
            signal.signal(getattr(signal, name), stop)
    try:
        app(args=argv)
    finally:
        _leave_objects_to_the_exit()


def _leave_objects_to_the_exit() -> None:
    """The command is done; the process ends next. Python's exit would still run its garbage
    collector, more than once, over every object the imports made (NumPy, Numba and LLVM,
    pydantic, Rich: about 0.15 s of CPU after ``simulate``, a fifth of the command) only to free
    memory that the operating system takes back anyway. Frozen (:func:`gc.freeze`), those
    objects are left to it; exit handlers (``atexit``, temporary files) still run, and files are
    closed by the commands themselves."""
    import gc

    gc.freeze()


#: Modules of further commands; each has ``register(app)``.
_COMMAND_MODULES = (
    "export",
    "derive",
    "paper_check",
    "worksheet",
    "animate",
    "report",
    "serve",
    "sweep",
    "sweep_plot",
    "chain",
    "dispersion",
)


def _register_subcommands() -> None:
    import importlib

    for name in _COMMAND_MODULES:
        importlib.import_module(f"rollspring.cli.{name}").register(app)


_register_subcommands()

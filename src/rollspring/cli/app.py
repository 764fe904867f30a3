"""The ``rollspring`` application: builds the Typer app and registers every command.

A thin layer: each command (one module each under :mod:`rollspring.cli.commands`) parses its
arguments, calls the library and formats the result, with the pieces they share in
:mod:`rollspring.cli.options` (declared) and :mod:`rollspring.cli.common` (run). This module
imports the commands, never the other way round. Usage errors (an unknown option, a missing
value) are one line on stderr with exit code 2, like rollspring's own errors.
"""

from __future__ import annotations

import sys
from typing import Annotated, Any

import typer
import typer.core

from rollspring.cli.commands import (
    analyze,
    animate,
    chain,
    derive,
    dispersion,
    export,
    fit,
    paper_check,
    presets,
    report,
    schema,
    serve,
    simulate,
    sweep,
    sweep_plot,
    track,
    worksheet,
)
from rollspring.cli.text import say

# Only what every command needs is imported here (Typer and the presets' names):
# each command imports its own (pydantic's model, SciPy, the compiled kernels, SymPy,
# Matplotlib, ...) when it runs, so --help and the light commands start fast.

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


#: The commands, in the order ``rollspring --help`` lists them.
COMMANDS = (
    analyze,
    schema,
    presets,
    simulate,
    export,
    derive,
    paper_check,
    worksheet,
    animate,
    report,
    serve,
    sweep,
    sweep_plot,
    chain,
    dispersion,
    track,
    fit,
)


def _register_commands() -> None:
    """Add every command to :data:`app` (each module's ``register``)."""
    for command in COMMANDS:
        command.register(app)


_register_commands()

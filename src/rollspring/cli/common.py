"""What every ``rollspring`` command does alike when it runs, written once: adding it to the
app with the one-line error handling and the check for an optional extra, loading its system,
the cost guard's confirmation (``--yes``), the progress bar on stderr, and the console helpers
(text or JSON on stdout, a file written atomically). What the commands declare alike (the
SYSTEM argument, ``--json``, ``--yes``, ``--out``, ``--format``) is
:mod:`rollspring.cli.options`.

The command modules (:mod:`rollspring.cli.commands`) import from here and from
:mod:`~rollspring.cli.options`, never from :mod:`rollspring.cli.app`, which builds the
application and registers them: the imports run one way (app -> commands -> common, options).
Only Typer is imported at the top; everything heavier (pydantic, Rich, the computations) when a
command runs, so ``--help`` and the light commands start fast.

Every error rollspring raises on purpose is printed as one line on stderr, with exit code 2;
with ``--json``, stdout holds exactly one JSON object and everything else goes to stderr.
"""

from __future__ import annotations

import functools
import json
import os
import sys
import time
from collections.abc import Callable, Sequence
from typing import TYPE_CHECKING, Any, TypeVar

import typer

from rollspring.cli.text import say
from rollspring.errors import RollspringError, require_extra

if TYPE_CHECKING:
    from pathlib import Path

    from rich.console import Console
    from rich.progress import Progress, ProgressColumn, TaskID

    from rollspring.analysis.costs import Cost
    from rollspring.model import System

__all__ = [
    "ProgressBar",
    "add_command",
    "confirm_cost",
    "friendly_errors",
    "load",
    "needs_extra",
    "print_json",
    "print_text",
    "say",
    "stdout_console",
    "write_text",
]

F = TypeVar("F", bound=Callable[..., Any])

# -- errors -------------------------------------------------------------------------------------


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
            say(f"error: {exc}")
            raise typer.Exit(2) from None
        except (typer.Exit, typer.Abort):
            raise
        except KeyboardInterrupt:
            say("interrupted: nothing more was written")
            raise typer.Exit(130) from None
        except MemoryError:
            say(
                "error: out of memory: ask for less (fewer --outputs, a shorter --duration, "
                "fewer bodies)"
            )
            raise typer.Exit(2) from None
        except Exception as exc:
            if os.environ.get("ROLLSPRING_DEBUG"):
                raise
            say(
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


def add_command(
    app: typer.Typer,
    command: Callable[..., Any],
    name: str,
    *,
    extras: str | tuple[str, ...] | None = None,
) -> None:
    """Add ``command`` to ``app`` as ``rollspring NAME``, with the one-line errors of
    :func:`friendly_errors` and, for a command that needs optional ``extras``, their check
    (:func:`needs_extra`)."""
    if extras is not None:
        command = needs_extra(extras, name)(command)
    app.command(name=name)(friendly_errors(command))


# -- the console --------------------------------------------------------------------------------


def stdout_console() -> Console:
    """A Rich console on stdout: a terminal's own width; 110 columns when piped to a file or a
    pager."""
    from rich.console import Console

    width = None if sys.stdout.isatty() else 110
    return Console(highlight=False, soft_wrap=False, width=width)


def print_json(data: Any) -> None:
    """``data`` as one JSON document on stdout (indented; NaN and infinity refused)."""
    sys.stdout.write(json.dumps(data, indent=2, ensure_ascii=False, allow_nan=False) + "\n")
    sys.stdout.flush()


def print_text(text: str) -> None:
    """``text`` on stdout as it is (a document: Markdown, LaTeX, XML)."""
    sys.stdout.write(text)
    sys.stdout.flush()


def write_text(path: str | Path, text: str, error: type[RollspringError]) -> None:
    """``text`` written to ``--out`` ``path`` atomically (:mod:`rollspring.outputs.atomic`),
    then ``wrote PATH`` on stderr; a failure is ``error`` with the one line ``--out: PATH:
    cannot write (why)``. The place is checked first, as for every output
    (:func:`~rollspring.outputs.atomic.writable_file`: a device, FIFO, socket or folder is
    refused, never replaced)."""
    from rollspring.outputs.atomic import atomic_write_text, writable_file

    writable_file(path, "--out")
    try:
        atomic_write_text(path, text)
    except OSError as exc:
        raise error(f"--out: {path}: cannot write ({exc.strerror or exc})") from None
    say(f"wrote {path}")


def confirm_cost(cost: Cost, *, yes: bool, stoppable: bool = True) -> None:
    """The cost guard of a command with ``--yes``: ``cost`` (estimated once, by the command)
    refused above the bound unless ``yes`` (:func:`rollspring.analysis.costs.check_cost`), and a
    long one announced on stderr (``note: the derivation will take about 6 min: ...``, with
    ``; Ctrl-C stops it`` for a ``stoppable`` run)."""
    from rollspring.analysis.costs import check_cost

    check_cost(cost, confirmed=yes)
    if cost.long:
        stop = "; Ctrl-C stops it" if stoppable else ""
        say(f"note: {cost.what} will take {cost.describe()}{stop}")


def load(system: str) -> System:
    """The system a command was given (a file or a preset), with a warning on stderr for each
    pair of bodies that overlap in its initial placement."""
    from rollspring.model import load_system  # pydantic: not for --help

    model = load_system(system)
    for warning in model.overlaps:
        say(f"warning: {warning}")
    return model


class ProgressBar:
    """A transient Rich progress bar on stderr, one task at a time, that appears only once the
    work has taken ``delay`` seconds (a short run shows none; ``delay=0``: at once), and only
    when stderr is a terminal.

    Used as a context manager; the bar is the ``progress`` callback of the library's long
    computations: ``bar(completed, **fields)`` moves the current task (of ``total`` 1 unless
    :meth:`start` says otherwise). ``label`` starts a first task on entry; ``columns`` makes the
    bar's Rich columns (Rich's default: description, bar, percentage, time left).
    """

    def __init__(
        self,
        label: str | None = None,
        *,
        delay: float = 1.0,
        columns: Callable[[], Sequence[ProgressColumn]] | None = None,
    ) -> None:
        self.label = label
        self.delay = delay
        self.columns = columns
        self.bar: Progress | None = None
        self.task: TaskID | None = None
        self.pending: dict[str, Any] | None = None  # the current task's description, total, ...
        self.started = 0.0

    def __enter__(self) -> ProgressBar:
        self.started = time.perf_counter()
        if self.delay <= 0:
            self._show()
        if self.label is not None:
            self.start(self.label)
        return self

    @property
    def elapsed(self) -> float:
        """Seconds since the bar was entered."""
        return time.perf_counter() - self.started

    def start(self, label: str, total: float = 1.0, completed: float = 0.0, **fields: Any) -> None:
        """A new task (it replaces the previous one): ``label``, ``total``, ``completed`` so far
        and the columns' ``fields``."""
        self.pending = {"description": label, "total": total, "completed": completed, **fields}
        if self.bar is not None:
            if self.task is not None:
                self.bar.remove_task(self.task)
            self.task = self.bar.add_task(**self.pending)

    def __call__(self, completed: float, **fields: Any) -> None:
        if self.bar is None:
            if self.elapsed < self.delay:
                return
            bar = self._show()
            if self.pending is not None:
                self.task = bar.add_task(**self.pending)
        if self.task is not None and self.bar is not None:  # set with the bar
            self.bar.update(self.task, completed=completed, **fields)

    def _show(self) -> Progress:
        from rich.console import Console
        from rich.progress import Progress

        columns = self.columns() if self.columns is not None else ()
        console = Console(stderr=True)
        # not on a terminal (a log, a pipe, a test's capture) the bar is not drawn: its last
        # frame and a newline would land in the log before the next message
        self.bar = Progress(
            *columns, console=console, transient=True, disable=not console.is_terminal
        )
        self.bar.start()
        return self.bar

    def __exit__(self, *exc_info: object) -> None:
        if self.bar is not None:
            self.bar.stop()

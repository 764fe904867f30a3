"""``rollspring worksheet --level N --seed S``: an exercise sheet and its solutions.

``--format markdown|latex`` (latex: complete documents that ``pdflatex`` compiles); ``-o FILE``
writes the sheet to FILE and the solutions to FILE with ``-solutions`` before its suffix
(``sheet.md`` -> ``sheet-solutions.md``), each atomically; without ``-o`` both are printed,
separated by a marked line. The same level and seed always give the same sheet
(:func:`rollspring.service.documents.worksheet`, rendered by :mod:`rollspring.outputs.worksheet`).
The command is added to an app by :func:`register`.
"""

from __future__ import annotations

from pathlib import Path
from typing import Annotated

import typer

from rollspring.cli.common import add_command, print_text, write_text
from rollspring.cli.options import Formats, out_option
from rollspring.errors import WorksheetOptionError

__all__ = [
    "FORMATS",
    "LEVELS",
    "SEPARATORS",
    "WorksheetOptionError",
    "register",
    "solutions_path",
    "worksheet_command",
]

# as in rollspring.outputs.worksheet (imported when the command runs: SymPy, the engine)
FORMATS = Formats("markdown", "latex")
LEVELS = {
    1: "Two masses and a spring",
    2: "Two rolling bodies joined at their centres",
    3: "Walls and chains",
    4: "Off-centre attachments",
}


#: The line printed between the sheet and its solutions on stdout, per format.
SEPARATORS = {
    "markdown": "\n---\n\n<!-- rollspring worksheet: solutions -->\n\n",
    "latex": "\n% " + "=" * 70 + "\n% rollspring worksheet: solutions\n% " + "=" * 70 + "\n\n",
}


def _integer(option: str, value: str | None, allowed: str) -> int:
    if value is None:
        raise WorksheetOptionError(f"{option}: required ({allowed})")
    try:
        return int(value.strip())
    except ValueError:
        raise WorksheetOptionError(f"{option}: must be {allowed} (got '{value}')") from None


def solutions_path(path: str) -> Path:
    """Where the solutions go: ``-solutions`` inserted before the suffix of ``path``."""
    target = Path(path)
    return target.with_name(f"{target.stem}-solutions{target.suffix}")


def worksheet_command(
    level: Annotated[
        str | None,
        typer.Option(
            "--level",
            "-l",
            help=f"1-4: {'; '.join(f'{n} {t}' for n, t in LEVELS.items())}.",
            show_default=False,
        ),
    ] = None,
    seed: Annotated[
        str | None,
        typer.Option(
            "--seed",
            "-s",
            help="A non-negative integer: the same seed gives the same sheet.",
            show_default=False,
        ),
    ] = None,
    format: Annotated[str, FORMATS.option("latex: documents for pdflatex")] = "markdown",  # noqa: A002
    out: Annotated[
        str | None,
        out_option(
            "Write the sheet here and the solutions to FILE-solutions (atomically); default: "
            "print both."
        ),
    ] = None,
) -> None:
    """An exercise sheet on coupled rolling oscillators, from two masses to off-centre springs
    (the paper's Fig. 4), with random parameters from the seed, and its solutions (derivation and
    numbers)."""
    number = _integer("--level", level, "1, 2, 3 or 4")
    if number not in LEVELS:
        raise WorksheetOptionError(f"--level: must be 1, 2, 3 or 4 (got {number})")
    value = _integer("--seed", seed, "a non-negative integer")
    if value < 0:
        raise WorksheetOptionError(f"--seed: must be a non-negative integer (got {value})")
    FORMATS.check(format, WorksheetOptionError)
    from rollspring.outputs.atomic import writable_file
    from rollspring.outputs.worksheet import render_sheet, render_solutions
    from rollspring.service.documents import worksheet

    if out is not None:  # both places, before anything is made or written
        for path in (out, solutions_path(out)):
            writable_file(path, "--out")
    sheet = worksheet(number, value)
    text = render_sheet(sheet, format)
    solutions = render_solutions(sheet, format)
    if out is None:
        print_text(text + SEPARATORS[format] + solutions)
        return
    for path, content in ((Path(out), text), (solutions_path(out), solutions)):
        write_text(path, content, WorksheetOptionError)


def register(app: typer.Typer) -> None:
    """Add the ``worksheet`` command to ``app`` (with rollspring's one-line error handling)."""
    add_command(app, worksheet_command, "worksheet", extras="report")

"""What the ``rollspring`` commands declare alike, written once: the SYSTEM argument, the
options ``--json``, ``--yes``, ``--out`` and the ``--format`` a command accepts (:class:`Formats`:
the option and the check of its value), as Typer declarations with their help texts — what
``rollspring COMMAND --help`` shows.

A command declares each in one line: ``system: SystemArg``, ``as_json: JsonOpt = False``,
``yes: Annotated[bool, yes_option()] = False``, ``format: Annotated[str, FORMATS.option()]``;
what the commands do alike when they run is :mod:`rollspring.cli.common`. Only Typer and the
presets' names are imported here (``--help`` starts without pydantic).
"""

from __future__ import annotations

from typing import Annotated, Any

import typer

from rollspring.errors import RollspringError
from rollspring.model import preset_names

__all__ = [
    "SYSTEM_HELP",
    "Formats",
    "JsonOpt",
    "SystemArg",
    "YesOpt",
    "json_option",
    "out_option",
    "system_argument",
    "yes_option",
]

#: The help of the SYSTEM argument: a file, or one of the presets (named).
SYSTEM_HELP = f"A system file (.toml or .json) or a preset name ({', '.join(preset_names())})."


def system_argument(text: str = SYSTEM_HELP) -> Any:
    """The SYSTEM argument (a system file or a preset name; ``text`` its help)."""
    return typer.Argument(help=text, show_default=False)


def json_option(text: str = "Print one JSON object on stdout.") -> Any:
    """``--json``: the result as JSON on stdout (``text`` its help)."""
    return typer.Option("--json", help=text)


def yes_option(bound: str = "time or memory", note: str = "") -> Any:
    """``--yes``/``-y`` of a command with a cost guard
    (:func:`rollspring.cli.common.confirm_cost` refuses a run whose estimated ``bound`` is above
    the bound, unless confirmed)."""
    return typer.Option(
        "--yes", "-y", help=f"Start even when the estimated {bound} is above the bound{note}."
    )


def out_option(text: str, *, show_default: bool = False) -> Any:
    """``--out``/``-o``: where a command writes (``text`` its help)."""
    return typer.Option("--out", "-o", help=text, show_default=show_default)


class Formats(tuple[str, ...]):
    """The formats a command's ``--format``/``-f`` accepts, in the order its help names them:
    the option's declaration (:meth:`option`) and the check of its value (:meth:`check`) in one
    place. A tuple of the names (``Formats("text", "markdown") == ("text", "markdown")``)."""

    def __new__(cls, *names: str) -> Formats:
        return super().__new__(cls, names)

    def option(self, note: str = "", *, text: str | None = None, show_default: bool = True) -> Any:
        """``--format``/``-f``, its help "Output format: a, b (``note``)." unless ``text`` words
        it otherwise."""
        if text is None:
            text = f"Output format: {', '.join(self)}" + (f" ({note})." if note else ".")
        return typer.Option("--format", "-f", help=text, show_default=show_default)

    def check(self, value: str, error: type[RollspringError]) -> str:
        """``value`` if it is one of the formats, else ``error`` with the one line
        ``--format: unknown format 'X' (formats: a, b)``."""
        if value not in self:
            raise error(f"--format: unknown format '{value}' (formats: {', '.join(self)})")
        return value


#: A system file or a preset name.
SystemArg = Annotated[str, system_argument()]
#: ``--json`` (one JSON object on stdout).
JsonOpt = Annotated[bool, json_option()]
#: ``--yes`` of the runs a cost estimate can refuse (analyze, simulate).
YesOpt = Annotated[bool, yes_option(note=" (a larger run is refused with its estimate)")]

"""``rollspring export SYSTEM --format mjcf -o PATH``: a system in another simulator's format.

Only MuJoCo's MJCF for now (:mod:`rollspring.outputs.mjcf`). The command is added to an app by
:func:`register`; the app module calls it at its bottom, so this module never imports
``rollspring.cli.app`` at import time (no circular import).
"""

from __future__ import annotations

import math
import sys
from typing import Annotated

import typer

from rollspring.cli.text import say
from rollspring.model import preset_names

__all__ = ["FORMATS", "export", "register"]

#: Formats ``--format`` accepts.
FORMATS = ("mjcf",)
#: The longest time step ``--timestep`` accepts, s.
MAX_TIMESTEP = 0.1


def export(
    system: Annotated[
        str,
        typer.Argument(
            help=f"A system file (.toml or .json) or a preset name ({', '.join(preset_names())}).",
            show_default=False,
        ),
    ],
    format: Annotated[  # noqa: A002 - the option is called --format
        str,
        typer.Option("--format", "-f", help=f"Output format: {', '.join(FORMATS)} (MuJoCo XML)."),
    ] = "mjcf",
    out: Annotated[
        str | None,
        typer.Option(
            "--out", "-o", help="Output file (required); '-' prints to stdout.", show_default=False
        ),
    ] = None,
    timestep: Annotated[
        float | None,
        typer.Option(
            help="Simulation time step written into the model, s (default 1e-4).",
            show_default=False,
        ),
    ] = None,
) -> None:
    """Export a system for another simulator: mjcf is a MuJoCo model (planar bodies on planes
    with contact friction, springs as tendons) to compare exact rolling with soft contact."""
    # here, not at the top: the writer needs the physics layer, which --help does not
    from rollspring.outputs.mjcf import ExportError, mjcf_warnings, system_to_mjcf, write_mjcf

    if format not in FORMATS:
        raise ExportError(f"--format: unknown format '{format}' (formats: {', '.join(FORMATS)})")
    if out is None:
        raise ExportError("--out/-o is required: a file path, or '-' for stdout")
    if timestep is not None and not (math.isfinite(timestep) and 0 < timestep <= MAX_TIMESTEP):
        raise ExportError(
            f"timestep: must be a positive number of seconds up to {MAX_TIMESTEP:g} "
            f"(MuJoCo steps a model in far less), not {timestep!r}"
        )
    if out != "-":
        from rollspring.outputs.files import writable_file

        writable_file(out)  # an unwritable --out fails now, before the system is read
    from rollspring.cli.app import load  # pydantic: not for --help

    model = load(system)
    if out == "-":
        text = system_to_mjcf(model, timestep=timestep)
        sys.stdout.write(text)
        sys.stdout.flush()
    else:
        try:
            write_mjcf(model, out, timestep=timestep)
        except OSError as exc:
            raise ExportError(f"{out}: cannot write ({exc.strerror or exc})") from None
    for warning in mjcf_warnings(model):
        _say(f"warning: {warning}")
    if out != "-":
        _say(f"wrote {out}")


def register(app: typer.Typer) -> None:
    """Add the ``export`` command to ``app`` (with rollspring's one-line error handling)."""
    from rollspring.cli.app import friendly_errors  # here, not at the top: app.py imports us

    app.command(name="export")(friendly_errors(export))


def _say(line: str) -> None:
    """One unwrapped line on stderr, never mixed into stdout (:func:`rollspring.cli.text.say`)."""
    say(line)

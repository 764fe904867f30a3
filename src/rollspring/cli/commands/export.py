"""``rollspring export SYSTEM --format mjcf -o PATH``: a system in another simulator's format.

Only MuJoCo's MJCF for now (:mod:`rollspring.outputs.mjcf`). The command is added to an app by
:func:`register`.
"""

from __future__ import annotations

import math
from typing import Annotated

import typer

from rollspring.cli.common import add_command, load, print_text, say
from rollspring.cli.options import Formats, SystemArg, out_option

__all__ = ["FORMATS", "export", "register"]

#: Formats ``--format`` accepts.
FORMATS = Formats("mjcf")
#: The longest time step ``--timestep`` accepts, s.
MAX_TIMESTEP = 0.1


def export(
    system: SystemArg,
    format: Annotated[str, FORMATS.option("MuJoCo XML")] = "mjcf",  # noqa: A002
    out: Annotated[str | None, out_option("Output file (required); '-' prints to stdout.")] = None,
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

    FORMATS.check(format, ExportError)
    if out is None:
        raise ExportError("--out/-o is required: a file path, or '-' for stdout")
    if timestep is not None and not (math.isfinite(timestep) and 0 < timestep <= MAX_TIMESTEP):
        raise ExportError(
            f"timestep: must be a positive number of seconds up to {MAX_TIMESTEP:g} "
            f"(MuJoCo steps a model in far less), not {timestep!r}"
        )
    if out != "-":
        from rollspring.outputs.atomic import writable_file

        writable_file(out)  # an unwritable --out fails now, before the system is read
        if not out.lower().endswith(".xml"):  # MJCF is XML: a .json name would mislead
            raise ExportError(f"--out {out}: an MJCF model's name must end in .xml")
    model = load(system)
    if out == "-":
        print_text(system_to_mjcf(model, timestep=timestep))
    else:
        try:
            write_mjcf(model, out, timestep=timestep)
        except OSError as exc:
            raise ExportError(f"{out}: cannot write ({exc.strerror or exc})") from None
    for warning in mjcf_warnings(model):
        say(f"warning: {warning}")
    if out != "-":
        say(f"wrote {out}")


def register(app: typer.Typer) -> None:
    """Add the ``export`` command to ``app`` (with rollspring's one-line error handling)."""
    add_command(app, export, "export")

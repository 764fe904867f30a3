"""``rollspring chain``: write the system file of a chain (:func:`rollspring.chain`).

A repeating unit of shapes (``--pattern hoop,cylinder``) with masses, radii, attachment heights
and stiffnesses per element of the unit, ``--n`` bodies ``--spacing`` apart, walls, and at
most one initial condition (``--pluck``, ``--packet``, ``--mode``); the file goes to ``--out``
(TOML, or JSON for a ``.json`` name) or, without it, to stdout. Added to an app by
:func:`register`.
"""

from __future__ import annotations

import math
import sys
from typing import Annotated

import typer

from rollspring.cli.common import add_command, say
from rollspring.cli.options import json_option, out_option
from rollspring.errors import ModelError

__all__ = ["chain", "register"]

#: The options whose names begin the generator's messages (``mass: ...`` -> ``--mass: ...``).
_OPTIONS = (
    "pattern",
    "n",
    "mass",
    "radius",
    "height",
    "stiffness",
    "spacing",
    "walls",
    "pluck",
    "packet",
    "mode",
    "branch",
    "amplitude",
)


def _numbers(option: str, text: str | None) -> list[float] | None:
    """``1,2.5`` -> [1.0, 2.5]; a one-line error naming the option otherwise."""
    if text is None:
        return None
    try:
        values = [float(part) for part in text.split(",")]
    except ValueError:
        raise ModelError(f"--{option}: '{text}' is not a comma-separated list of numbers") from None
    if not all(math.isfinite(v) for v in values):
        raise ModelError(f"--{option}: '{text}' holds a number that is not finite")
    return values


def chain(
    pattern: Annotated[
        str, typer.Option(help="The repeating unit: shapes separated by commas.")
    ] = "hoop,cylinder",
    n: Annotated[int, typer.Option("--n", help="Number of bodies.")] = 10,
    mass: Annotated[str, typer.Option(help="kg: one value, or one per element.")] = "1",
    radius: Annotated[str, typer.Option(help="m: one value, or one per element.")] = "0.1",
    height: Annotated[
        str | None,
        typer.Option(
            help="m above the track where the springs attach, one value or one per element "
            "(default: the centres).",
            show_default=False,
        ),
    ] = None,
    stiffness: Annotated[
        str, typer.Option(help="N/m of the spring after each element: one value or one each.")
    ] = "100",
    spacing: Annotated[float, typer.Option(help="m between neighbouring centres.")] = 0.5,
    walls: Annotated[str, typer.Option(help="none, left or both.")] = "none",
    pluck: Annotated[
        int | None, typer.Option(help="Displace body I (1-based).", show_default=False)
    ] = None,
    packet: Annotated[
        str | None,
        typer.Option(
            help="q,width: a Gaussian wave packet of wavenumber q (rad/m) and width (m), "
            "travelling on --branch.",
            show_default=False,
        ),
    ] = None,
    mode: Annotated[
        int | None,
        typer.Option(help="Displace along the N-th oscillating normal mode.", show_default=False),
    ] = None,
    branch: Annotated[int, typer.Option(help="The packet's branch (1 the lowest).")] = 1,
    amplitude: Annotated[float, typer.Option(help="m: the largest displacement.")] = 0.01,
    name: Annotated[str | None, typer.Option(help="The system's name.", show_default=False)] = None,
    out: Annotated[
        str | None,
        out_option("Write the file here (.toml or .json); default: print TOML on stdout."),
    ] = None,
    as_json: Annotated[
        bool, json_option("Print the JSON form instead of TOML (no --out).")
    ] = False,
) -> None:
    """Write a chain: a repeating unit of bodies joined by springs, with walls and an initial
    condition (a plucked body, a wave packet or a normal mode)."""
    from rollspring.service.chains import SYSTEM_FORMATS, chain_file, system_text
    from rollspring.service.chains import chain as make_chain

    if out is not None and as_json:
        raise ModelError("--json: prints the file on stdout; with --out its extension chooses")
    if out is not None:
        from pathlib import Path

        from rollspring.outputs.atomic import writable_file

        if Path(out).suffix.lower() not in SYSTEM_FORMATS:
            raise ModelError(
                f"--out: {Path(out).name}: a system file ends in {' or '.join(SYSTEM_FORMATS)}"
            )
        writable_file(out)
    numbers = {
        "mass": _numbers("mass", mass),
        "radius": _numbers("radius", radius),
        "height": _numbers("height", height),
        "stiffness": _numbers("stiffness", stiffness),
    }
    wave = _numbers("packet", packet)
    if wave is not None and len(wave) != 2:
        raise ModelError(f"--packet: give q,width (two numbers), not '{packet}'")
    try:
        system = make_chain(
            pattern,
            n,
            mass=numbers["mass"] or 1.0,
            radius=numbers["radius"] or 0.1,
            height=numbers["height"],
            stiffness=numbers["stiffness"] or 100.0,
            spacing=spacing,
            walls=walls,
            pluck=pluck,
            packet=None if wave is None else (wave[0], wave[1]),
            mode=mode,
            branch=branch,
            amplitude=amplitude,
            name=name,
        )
    except ModelError as exc:
        message = str(exc)
        if message.split(":")[0].split(" ")[0] in _OPTIONS:
            raise ModelError(f"--{message}") from None
        raise
    for warning in system.overlaps:
        say(f"warning: {warning}")
    if out is None:
        sys.stdout.write(system_text(system, "json" if as_json else "toml"))
        sys.stdout.flush()
        return
    say(f"wrote {chain_file(system, out)}")


def register(app: typer.Typer) -> None:
    """Add the ``chain`` command to ``app`` (with rollspring's one-line error handling)."""
    add_command(app, chain, "chain")

"""``rollspring sweep-plot STORE --x PATH --y PATH --metric NAME -o map.png``: a map of a sweep.

One metric of a sweep store (``rollspring sweep``, ``docs/sweeps.md``) over two of its varied
PATHs, the other PATHs fixed with ``--sel PATH=value``, the linear theory's prediction dashed
over it where it has one (:mod:`rollspring.outputs.maps`). Every bad input is one line on stderr
and exit code 2. The command is added to an app by :func:`register`.
"""

from __future__ import annotations

from typing import Annotated

import typer

from rollspring.cli.common import add_command, say
from rollspring.cli.options import out_option
from rollspring.errors import SweepPlotError

__all__ = ["SweepPlotError", "register", "sweep_plot"]


def _parse_sel(items: list[str]) -> dict[str, str]:
    chosen: dict[str, str] = {}
    for item in items:
        path, equals, value = item.rpartition("=")
        path, value = path.strip(), value.strip()
        if not equals or not path or not value:
            raise SweepPlotError(
                f"--sel {item}: expected PATH=VALUE, e.g. --sel bodies.hoop.mass=1.5"
            )
        if path in chosen:
            raise SweepPlotError(f"--sel {path}: given twice")
        chosen[path] = value
    return chosen


def sweep_plot(
    store: Annotated[
        str,
        typer.Argument(
            help="A sweep store written by rollspring sweep (a .zarr directory).",
            show_default=False,
        ),
    ],
    x: Annotated[
        str,
        typer.Option("--x", help="The varied PATH along the horizontal axis.", show_default=False),
    ],
    y: Annotated[
        str,
        typer.Option("--y", help="The varied PATH along the vertical axis.", show_default=False),
    ],
    metric: Annotated[
        str,
        typer.Option(
            "--metric",
            "-m",
            help="The variable to map (status, first_slip_time, "
            "max_friction_ratio, period_measured, …).",
            show_default=False,
        ),
    ],
    sel: Annotated[
        list[str] | None,
        typer.Option(
            "--sel",
            help="PATH=VALUE: fix another varied PATH at a grid value (repeatable; a value "
            "between grid values takes the nearest).",
            show_default=False,
        ),
    ] = None,
    body: Annotated[
        str | None,
        typer.Option(
            "--body",
            help="Body of a per-body metric and of the linear slip boundary (default: "
            "the extreme over the bodies).",
            show_default=False,
        ),
    ] = None,
    mode: Annotated[
        int | None,
        typer.Option(
            "--mode",
            help="Mode of omega (0 … n-1, sorted by ω) and of the linear period.",
            show_default=False,
        ),
    ] = None,
    linear: Annotated[
        bool,
        typer.Option(
            "--linear/--no-linear",
            help="Draw the linear theory's prediction (the slip boundary "
            "μ needed = μs; the period 2π/ω).",
        ),
    ] = True,
    out: Annotated[
        str, out_option("Image file: .png, .svg or .pdf.", show_default=True)
    ] = "map.png",
    dpi: Annotated[float, typer.Option(help="Resolution of a PNG, dots per inch.")] = 150.0,
) -> None:
    """Map one metric of a sweep over two varied PATHs (colour bar or legend, labelled axes
    with units), with the linear theory's prediction dashed where it has one."""
    from rollspring.outputs.maps import (
        check_map_output,
        open_sweep,
        plot_map,
        prepare_map,
        write_map,
    )

    check_map_output(out, dpi)  # --dpi, the format and the place, before the store is read
    chosen = _parse_sel(sel or [])
    dataset = open_sweep(store)
    data = prepare_map(dataset, x, y, metric, sel=chosen, body=body, mode=mode, linear=linear)
    for note in data.notes:
        say(f"note: {note}")
    written = write_map(plot_map(data), out, dpi=dpi)
    say(f"wrote {written}")


def register(app: typer.Typer) -> None:
    """Add the ``sweep-plot`` command to ``app`` (with rollspring's one-line error handling)."""
    add_command(app, sweep_plot, "sweep-plot", extras=("sweep", "plot"))

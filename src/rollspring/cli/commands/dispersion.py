"""``rollspring dispersion SYSTEM``: a chain read as a periodic lattice — its branches over the
Brillouin zone, band edges and gaps, group velocities, and the friction and normal force each
body needs per metre of wave amplitude (:mod:`rollspring.analysis.dispersion`); ``--json``
prints one JSON object, ``--figure`` draws the branches (the ``plot`` extra). Added to an app
by :func:`register`.
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING, Annotated, Any

import typer

from rollspring.cli.common import add_command, load, print_json, say, stdout_console
from rollspring.cli.options import JsonOpt, system_argument
from rollspring.cli.text import markup
from rollspring.model import preset_names

if TYPE_CHECKING:
    from rollspring.analysis.dispersion import Dispersion

__all__ = ["dispersion", "register"]


def dispersion(
    system: Annotated[
        str,
        system_argument(
            f"A chain's system file (.toml or .json) or a preset name "
            f"({', '.join(name for name in preset_names() if name.startswith('chain'))}, ...)."
        ),
    ],
    as_json: JsonOpt = False,
    points: Annotated[
        int, typer.Option("--points", help="Wavenumbers over the Brillouin zone (ends included).")
    ] = 201,
    figure: Annotated[
        str | None,
        typer.Option(
            "--figure", help="Draw the branches into this .png or .svg file.", show_default=False
        ),
    ] = None,
) -> None:
    """Dispersion of a chain read as a periodic lattice: branches, gaps, group velocities,
    friction and normal force per unit wave amplitude."""
    from rollspring.service.chains import chain_dispersion

    if figure is not None:
        from pathlib import Path

        from rollspring.errors import OutputError, require_extra
        from rollspring.outputs.atomic import writable_file

        with require_extra("plot", "rollspring dispersion --figure"):
            import matplotlib  # noqa: F401 - the extra's check, before any work
        if Path(figure).suffix.lower() not in (".png", ".svg"):
            raise OutputError(f"--figure: {Path(figure).name}: give a file ending in .png or .svg")
        writable_file(figure, "--figure")
    from rollspring.analysis.dispersion import MAX_POINTS
    from rollspring.errors import AnalysisError

    if not 3 <= points <= MAX_POINTS:  # in the command line's words, before the system is read
        raise AnalysisError(
            f"--points: must be a whole number from 3 to {MAX_POINTS} (got {points})"
        )
    model = load(system)
    result, payload, warnings = chain_dispersion(model, points)
    for warning in warnings:
        say(f"warning: {warning}")
    if figure is not None:
        from rollspring.service.chains import dispersion_figure

        say(f"wrote {dispersion_figure(result, figure)}")
    if as_json:
        print_json(payload)
        return
    _print_table(result)


def _g(value: float, digits: int = 6) -> str:
    if math.isinf(value):
        return "∞"
    return "0" if value == 0 else f"{value:.{digits}g}"


def _print_table(result: Dispersion) -> None:
    from rich.table import Table

    console = stdout_console()
    cell = result.cell
    console.print(f"[bold]{markup(result.system.name or 'chain')}[/bold]")
    console.print(
        f"Unit cell: {markup(', '.join(cell.ids))}; a = {_g(cell.a)} m; Brillouin zone "
        f"|q| ≤ π/a = {_g(math.pi / cell.a)} rad/m; rolling masses (1 + γ)m: "
        + ", ".join(
            f"{markup(i)} {_g(float(m), 5)} kg"
            for i, m in zip(cell.ids, result.rolling_mass, strict=True)
        )
    )
    data: dict[str, Any] = result.to_dict()
    table = Table(title="Branches", title_justify="left")
    for column in ("branch", "ω min (rad/s)", "ω max (rad/s)", "max |dω/dq| (m/s)"):
        table.add_column(column, justify="right" if column != "branch" else "left")
    for ids in cell.ids:
        table.add_column(f"|f| {ids} (N/m)", justify="right")
        table.add_column(f"μ {ids} (1/m)", justify="right")
    for b, branch in enumerate(data["branches"]):
        row = [
            f"{b + 1} ({branch['name']})" if branch["name"] != f"branch {b + 1}" else str(b + 1),
            _g(float(result.band_edges[b, 0])),
            _g(float(result.band_edges[b, 1])),
            _g(float(abs(result.group_velocity[:, b]).max())),
        ]
        for r in range(cell.p):
            row.append(_g(float(result.friction[:, b, r].max()), 5))
            row.append(_g(float(result.required_mu[b, r]), 4))
        table.add_row(*row)
    console.print(table)
    console.print(
        "|f|: the largest static friction over the zone per metre of wave amplitude; μ: the "
        "friction coefficient that needs, per metre (|f|/N, first order)"
    )
    if result.gaps:
        for b, lo, hi in result.gaps:
            console.print(f"Gap between branches {b} and {b + 1}: {_g(lo)} … {_g(hi)} rad/s")
    else:
        console.print("No gap between the branches")
    if result.closed_form is not None:
        deviation = float(abs(result.omega - result.closed_form).max())
        console.print(
            "Closed form of the lattice with masses (1 + γ)m: largest difference "
            f"{deviation:.2g} rad/s"
        )


def register(app: typer.Typer) -> None:
    """Add the ``dispersion`` command to ``app`` (with rollspring's one-line error handling)."""
    add_command(app, dispersion, "dispersion")

"""``rollspring presets``: the built-in systems (each also a file in ``examples/``), as a table
or, with ``--json``, a JSON list of {``name``, ``title``, ``file``, ``default``}."""

from __future__ import annotations

from typing import Any

import typer

from rollspring.cli.common import add_command, print_json, stdout_console
from rollspring.cli.options import JsonOpt
from rollspring.model import DEFAULT_PRESET, preset_names, preset_path

__all__ = ["presets", "register"]


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
        print_json(rows)
        return
    from rich.table import Table

    table = Table(title="rollspring presets", title_justify="left")
    table.add_column("name", style="bold")
    table.add_column("system")
    for row in rows:
        table.add_row(row["name"] + (" (default)" if row["default"] else ""), row["title"])
    stdout_console().print(table)


def register(app: typer.Typer) -> None:
    """Add the ``presets`` command to ``app`` (with rollspring's one-line error handling)."""
    add_command(app, presets, "presets")

"""``rollspring schema``: the JSON Schema of a system file (TOML files have the same structure;
:func:`rollspring.model.system_json_schema`)."""

from __future__ import annotations

import typer

from rollspring.cli.common import add_command, print_json

__all__ = ["register", "schema"]


def schema() -> None:
    """Print the JSON Schema of a system file (TOML files have the same structure)."""
    from rollspring.model import system_json_schema

    print_json(system_json_schema())


def register(app: typer.Typer) -> None:
    """Add the ``schema`` command to ``app`` (with rollspring's one-line error handling)."""
    add_command(app, schema, "schema")

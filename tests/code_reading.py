"""Reading the package's source for the structure tests (tests/test_layers.py,
tests/test_architecture.py): what a call calls, by name."""

from __future__ import annotations

import ast

__all__ = ["called_name"]


def called_name(call: ast.Call) -> str | None:
    """The name a call calls: ``f`` for ``f(...)``, ``attr`` for ``x.attr(...)``, else None."""
    function = call.func
    if isinstance(function, ast.Name):
        return function.id
    if isinstance(function, ast.Attribute):
        return function.attr
    return None

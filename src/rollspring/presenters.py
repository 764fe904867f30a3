"""The registry of a result's views that live in a higher layer than the result.

``Trajectory.to_pandas``, ``to_xarray`` and ``animate`` are drawn by
:mod:`rollspring.outputs.jupyter` (pandas, xarray, Matplotlib), a layer above the simulation
that the simulation must not import. They are found here by name instead: the package root
(:mod:`rollspring`, the composition root above every layer) fills :data:`PRESENTERS` when it is
imported, with callables that load the outputs layer only when they are called. This module
imports nothing (not even :mod:`typing`): it sits at the bottom, beside :mod:`rollspring.errors`.
"""

from __future__ import annotations

TYPE_CHECKING = False  # as typing.TYPE_CHECKING, without importing typing
if TYPE_CHECKING:
    from collections.abc import Callable
    from typing import Any

__all__ = ["PRESENTERS"]

#: view name (``"to_pandas"``, ``"to_xarray"``, ``"animate"``) -> the callable that draws it,
#: called with the trajectory and the view's options
PRESENTERS: dict[str, Callable[..., Any]] = {}

"""A catalogue entry: the code half of a claim, written with keyword arguments.

:func:`claim` writes a claim (its quantity, the paper's expression, the systems, the recipe, the
stated assumptions); :func:`restates` writes a claim the paper repeats, pointing to the first by
its key and giving only what differs. The other half, the paper's words, is in ``claims.toml``.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:
    from rollspring.analysis.paper.bench import Bench
    from rollspring.analysis.paper.types import Assumption, Derived


@dataclass(frozen=True, kw_only=True)
class Entry:
    """A claim's code half; None (a restatement's) takes the restated claim's value."""

    key: str
    quantity: str | None = None
    paper: Any = None
    system: str | None = None
    derive: Callable[[Bench], Derived] | None = None
    assumptions: tuple[Assumption, ...] | None = None
    restates: str | None = None


def claim(
    *,
    key: str,
    quantity: str,
    paper: Any,
    system: str,
    derive: Callable[[Bench], Derived],
    assumptions: tuple[Assumption, ...] = (),
) -> Entry:
    """One claim: ``key`` (its name, ``claims.toml``'s table for its words), ``quantity`` (LaTeX
    of what it gives a value for), ``paper`` (that value as SymPy, in the symbols of
    :mod:`rollspring.analysis.paper.symbols`), ``system`` (keys of
    :data:`~rollspring.analysis.paper.systems.SYSTEMS`, comma-separated), ``derive`` (the recipe)
    and ``assumptions`` (those the paper states that it relies on)."""
    return Entry(
        key=key,
        quantity=quantity,
        paper=paper,
        system=system,
        derive=derive,
        assumptions=assumptions,
    )


def restates(original: str, /, *, key: str, **changes: Any) -> Entry:
    """A claim the paper makes again (``original``: the key of the claim it repeats, earlier in
    the catalogue): the original's quantity, expression, systems, recipe and assumptions, but for
    those given in ``changes`` (by those names, as :func:`claim` takes them)."""
    return Entry(key=key, restates=original, **changes)

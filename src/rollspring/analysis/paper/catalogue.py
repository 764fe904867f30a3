"""The catalogue: every quantitative statement of the paper, in the paper's order, as data.

The claims are the tables of ``claims.toml``, one per claim key, in the paper's order. A table
holds the paper's words (``location``; ``quote``, verbatim from its LaTeX source; ``statement``,
in our words; ``latex``, the claim as a formula, or none where the quote is the formula) and what
the check needs: ``quantity`` (LaTeX of what the claim gives a value for), ``paper`` (that value as
the paper gives it: SymPy text in the symbols of :mod:`~rollspring.analysis.paper.symbols` and
:mod:`~rollspring.analysis.paper.notation`, a list for several), ``system`` (keys of
:data:`~rollspring.analysis.paper.systems.SYSTEMS`, comma-separated), ``recipe`` (how the engine
derives it: the name of a recipe of :mod:`rollspring.analysis.paper.recipes`, or a call of a
recipe factory with literal arguments, ``app_a_friction(1, middle=True)``) and ``assumptions``
(names from :mod:`~rollspring.analysis.paper.assumptions`, those the paper states the claim relies
on). A claim the paper makes again names the first (``restates = "key"``, an earlier claim) and
gives only what differs. :func:`paper_claims` reads the file once and checks every table.
"""

from __future__ import annotations

import ast
import functools
import tomllib
from collections.abc import Callable
from importlib import resources
from types import ModuleType
from typing import Any

import sympy as sp

from rollspring.analysis.paper import assumptions, notation, symbols
from rollspring.analysis.paper.recipes import (
    appendices,
    common,
    intro,
    sec3,
    sec4,
    sec5_1_2,
    sec5_3_5,
    sec5_6_7,
)
from rollspring.analysis.paper.systems import SYSTEMS
from rollspring.analysis.paper.types import Assumption, Claim, Counterexample

__all__ = ["claim_tables", "paper_claims", "paper_value", "recipe"]

_RECIPE_MODULES = (common, intro, sec3, sec4, sec5_1_2, sec5_3_5, sec5_6_7, appendices)
_WORDS = ("location", "quote", "statement", "latex")
_CODE = ("quantity", "paper", "system", "recipe", "assumptions", "counterexample")
_FIELDS = {"restates", *_WORDS, *_CODE}


def _public(module: ModuleType) -> dict[str, Any]:
    """The recipes and recipe factories a recipe module defines (public callables of its own)."""
    return {
        name: value
        for name, value in vars(module).items()
        if not name.startswith("_")
        and callable(value)
        and getattr(value, "__module__", "").startswith("rollspring.analysis.paper.recipes")
    }


@functools.cache
def _recipes() -> dict[str, Any]:
    """Every recipe and factory by name; a name two modules define differently is an error."""
    found: dict[str, Any] = {}
    for module in _RECIPE_MODULES:
        for name, value in _public(module).items():
            if found.setdefault(name, value) is not value:
                raise RuntimeError(f"recipes: two recipes named {name}")
    return found


@functools.cache
def _symbols() -> dict[str, Any]:
    """The names ``paper`` is written in: the symbols by their SymPy names (``m_1``, ``phi_1``)."""
    found: dict[str, Any] = {}
    for module in (symbols, notation):
        for value in vars(module).values():
            if isinstance(value, sp.Symbol) and found.setdefault(value.name, value) != value:
                raise RuntimeError(f"paper check: two symbols named {value.name}")
    return found


def paper_value(text: str | list[str]) -> Any:
    """The paper's value from its text in ``claims.toml``: a SymPy expression (``True`` is
    :data:`sympy.true`), or a tuple of them for a list."""
    if isinstance(text, list):
        return tuple(paper_value(item) for item in text)
    return sp.sympify(sp.parse_expr(text, local_dict=dict(_symbols())))


def recipe(text: str) -> Callable[..., Any]:
    """The recipe ``text`` names: a recipe's name (``fig2_dof``), or a factory called with
    literal arguments (``app_a_friction(1, middle=True)``); anything else is refused."""
    node = ast.parse(text, mode="eval").body
    call = node if isinstance(node, ast.Call) else None
    name = call.func if call is not None else node
    if not isinstance(name, ast.Name) or name.id not in _recipes():
        raise ValueError(f"recipe {text!r}: no recipe of that name")
    found = _recipes()[name.id]
    if call is None:
        return found  # type: ignore[no-any-return]
    try:
        args = [ast.literal_eval(arg) for arg in call.args]
        kwargs = {word.arg: ast.literal_eval(word.value) for word in call.keywords if word.arg}
    except ValueError:
        raise ValueError(f"recipe {text!r}: arguments must be literals") from None
    if len(kwargs) != len(call.keywords):
        raise ValueError(f"recipe {text!r}: arguments must be literals")
    return found(*args, **kwargs)  # type: ignore[no-any-return]


def _assumptions(names: list[str]) -> tuple[Assumption, ...]:
    """The stated assumptions of these names (constants of the assumptions module)."""
    found = tuple(getattr(assumptions, name, None) for name in names)
    if not all(isinstance(item, Assumption) for item in found):
        raise ValueError(f"assumptions {names}: not all are stated assumptions")
    return found  # type: ignore[return-value]


def _counterexample(table: dict[str, Any]) -> Counterexample:
    """The run that shows a verdict (:class:`Counterexample`), its system one of the paper's."""
    found = Counterexample(**table)
    if found.system not in SYSTEMS:
        raise ValueError(f"counterexample: no system {found.system!r}")
    if found.start not in ("file", "mode"):
        raise ValueError(f"counterexample: start {found.start!r} is neither 'file' nor 'mode'")
    return found


@functools.cache
def claim_tables() -> dict[str, dict[str, Any]]:
    """``claims.toml``: each claim's table by key, in the paper's order."""
    text = (resources.files("rollspring.analysis.paper") / "claims.toml").read_text(
        encoding="utf-8"
    )
    tables: dict[str, dict[str, Any]] = tomllib.loads(text)
    return tables


def _claim(key: str, table: dict[str, Any], original: Claim | None) -> Claim:
    """One claim from its table; what a restatement does not give is the original's."""

    def given(name: str, read: Callable[[Any], Any] = lambda value: value) -> Any:
        if name in table:
            return read(table[name])
        if original is not None:
            return getattr(original, name)
        if name == "latex":  # the quote is the formula
            return table["quote"]
        if name == "assumptions":
            return ()
        if name == "counterexample":
            return None
        raise ValueError(f"claims.toml [{key}]: no {name}")

    return Claim(
        key=key,
        location=given("location"),
        statement=given("statement"),
        latex=given("latex"),
        quantity=given("quantity"),
        paper=given("paper", paper_value),
        system=given("system"),
        derive=original.derive if original and "recipe" not in table else recipe(table["recipe"]),
        quote=given("quote"),
        assumptions=given("assumptions", _assumptions),
        counterexample=given("counterexample", _counterexample),
    )


def paper_claims() -> list[Claim]:
    """Every quantitative statement of the paper, in the paper's order."""
    claims: dict[str, Claim] = {}
    for key, table in claim_tables().items():
        unknown = set(table) - _FIELDS
        if unknown:
            raise ValueError(f"claims.toml [{key}]: unknown fields {sorted(unknown)}")
        restated = table.get("restates")
        if restated is not None and restated not in claims:
            raise ValueError(f"claims.toml [{key}] restates {restated!r}, no earlier claim")
        claims[key] = _claim(key, table, claims[restated] if restated is not None else None)
    return list(claims.values())

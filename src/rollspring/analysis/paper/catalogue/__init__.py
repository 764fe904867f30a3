"""The catalogue: every quantitative statement of the paper, in the paper's order.

Its code half (:mod:`~.entry`: what each claim gives a value for, the paper's expression, the
systems, the recipe) is one module per section or group of sections; its words (location,
verbatim quote, statement, LaTeX: the quote where it is itself the formula) are in
``claims.toml``, one table per claim key.
:func:`paper_claims` joins the two.
"""

from __future__ import annotations

import functools
import tomllib
from importlib import resources
from typing import Any

from rollspring.analysis.paper.catalogue import (
    appendices,
    intro,
    sec3,
    sec4,
    sec5_1_2,
    sec5_3_5,
    sec5_6_7,
)
from rollspring.analysis.paper.catalogue.entry import Entry
from rollspring.analysis.paper.types import Claim

__all__ = ["entries", "paper_claims"]

_SECTIONS = (intro, sec3, sec4, sec5_1_2, sec5_3_5, sec5_6_7, appendices)
_WORDS = ("location", "quote", "statement", "latex")


@functools.cache
def _words() -> dict[str, dict[str, str]]:
    """``claims.toml``: the paper's words for each claim, by key."""
    text = (resources.files("rollspring.analysis.paper") / "claims.toml").read_text(
        encoding="utf-8"
    )
    words: dict[str, dict[str, str]] = tomllib.loads(text)
    return words


def _claim(entry: Entry, words: dict[str, str], original: Claim | None) -> Claim:
    def given(name: str) -> Any:
        value = getattr(entry, name)
        if value is not None:
            return value
        if original is None:
            raise RuntimeError(f"{entry.key}: no {name}")
        return getattr(original, name)

    def said(name: str) -> str:
        if name in words:
            return words[name]
        if original is None and name == "latex":  # the quote is the formula
            return words["quote"]
        if original is None:
            raise RuntimeError(f"{entry.key}: claims.toml gives no {name}")
        text: str = getattr(original, name)
        return text

    return Claim(
        key=entry.key,
        location=said("location"),
        statement=said("statement"),
        latex=said("latex"),
        quantity=given("quantity"),
        paper=given("paper"),
        system=given("system"),
        derive=given("derive"),
        quote=said("quote"),
        assumptions=given("assumptions"),
    )


def entries() -> list[Entry]:
    """The catalogue's entries (the claims' code halves), in the paper's order."""
    return [entry for section in _SECTIONS for entry in section.claims()]


def paper_claims() -> list[Claim]:
    """Every quantitative statement of the paper, in the paper's order."""
    words = _words()
    claims: dict[str, Claim] = {}
    for entry in entries():
        if entry.key in claims:
            raise RuntimeError(f"{entry.key}: two claims of one key")
        unknown = set(words.get(entry.key, {})) - set(_WORDS)
        if entry.key not in words or unknown:
            raise RuntimeError(f"{entry.key}: claims.toml has no such table, or {unknown}")
        if entry.restates is not None and entry.restates not in claims:
            raise RuntimeError(f"{entry.key} restates {entry.restates}, no earlier claim")
        original = claims[entry.restates] if entry.restates is not None else None
        claims[entry.key] = _claim(entry, words[entry.key], original)
    if set(words) != set(claims):
        raise RuntimeError(f"claims.toml: no claim has the keys {sorted(set(words) - set(claims))}")
    return list(claims.values())

r"""The exercise sheet's data: the levels, a numeric answer, the sheet and the numbers its
solutions give.

A :class:`Worksheet` is made by :func:`rollspring.service.documents.worksheet` (a seeded random
system of the level, its analysis and questions, and its derivation by the Lagrange method with
the parameters as symbols, made when the solutions need it) and rendered by
:mod:`rollspring.outputs.worksheet`. Every number of the solutions is in
:attr:`Worksheet.answers` (structured, each with the question it answers), computed by
:func:`rollspring.analyze` on :attr:`Worksheet.system`, except the closed-form
:math:`\Omega^2` values and the percussion heights, which come from the derivation.
"""

from __future__ import annotations

import re
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

from rollspring.analysis.linear import LinearAnalysis
from rollspring.model import System

if TYPE_CHECKING:
    from rollspring.analysis.derivation import Derivation

__all__ = ["LEVELS", "SHAPE_WORDS", "Answer", "Worksheet", "end_words"]

#: The levels and their titles.
LEVELS = {
    1: "Two masses and a spring",
    2: "Two rolling bodies joined at their centres",
    3: "Walls and chains",
    4: "Off-centre attachments",
}

#: Each shape in words and its moment of inertia (LaTeX).
SHAPE_WORDS = {
    "hoop": ("thin hoop", r"I = mR^2"),
    "cylinder": ("solid cylinder", r"I = \tfrac12 mR^2"),
    "sphere": ("solid sphere", r"I = \tfrac25 mR^2"),
    "shell": ("thin spherical shell", r"I = \tfrac23 mR^2"),
    "slider": ("block", r"\text{no rotation}"),
}


@dataclass(frozen=True)
class Answer:
    """One numeric answer: ``question`` (1-based), ``label`` (words, may hold ``$math$``),
    ``values`` with their ``names`` (a body id, a mode, a matrix entry), ``unit``, and ``key``
    naming the quantity of :func:`rollspring.analyze` it comes from."""

    key: str
    question: int
    label: str
    values: tuple[float, ...]
    unit: str
    names: tuple[str, ...] = ()


@dataclass(eq=False)
class Worksheet:
    r"""A generated exercise and everything its solutions need.

    ``numeric_answers`` come from :func:`rollspring.analyze` (``analysis``); ``solve`` makes
    the derivation the solutions show (given by the maker of the sheet:
    :func:`rollspring.analysis.derivation.derive`, the Lagrange method with the parameters as
    symbols), called when first needed: :attr:`derivation`, and :attr:`answers`, which adds the
    closed-form :math:`\Omega^2` and (level 4) the percussion heights from it. ``notes``:
    answers in words, by question number.
    """

    level: int
    seed: int
    variant: str
    title: str
    data: dict[str, Any]
    system: System
    setting: list[str]
    questions: list[str]
    numeric_answers: list[Answer]
    analysis: LinearAnalysis = field(repr=False)
    solve: Callable[[], Derivation] = field(repr=False)
    notes: dict[int, str] = field(default_factory=dict)
    _derivation: Derivation | None = field(default=None, repr=False)

    @property
    def derivation(self) -> Derivation:
        """The symbolic derivation (Lagrange; setup, equations, frequencies, forces): what
        ``solve()`` returns, made once, on first use."""
        if self._derivation is None:
            self._derivation = self.solve()
        return self._derivation

    @property
    def answers(self) -> list[Answer]:
        """Every numeric answer of the solutions, by question."""
        derivation = self.derivation
        closed = list(derivation.omega2)
        exact = (
            [derivation.symbolic.numeric(w) for w in closed]
            if closed
            and all(w is not None for w in closed)
            and len(closed) == len(self.analysis.oscillating)
            else []
        )
        out = []
        for answer in self.numeric_answers:
            if answer.key == "omega2_exact":
                if not exact:
                    continue
                names = tuple(f"mode {n + 1}" for n in range(len(exact))) if len(exact) > 1 else ()
                answer = Answer(
                    answer.key, answer.question, answer.label, tuple(exact), answer.unit, names
                )
            elif answer.key == "percussion":
                heights = tuple(
                    derivation.symbolic.numeric(b.percussion_height)
                    for b in derivation.symbolic.bodies
                )
                answer = Answer(
                    answer.key, answer.question, answer.label, heights, answer.unit, answer.names
                )
            out.append(answer)
        return out


def end_words(end: str) -> str:
    """'body 2' for a body id b2; 'the left wall', 'the wall' for an anchor."""
    if re.fullmatch(r"b\d+", end):
        return f"body {end[1:]}"
    return f"the {end} wall" if end in ("left", "right") else f"the {end}"

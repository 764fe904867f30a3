r"""Steps and sections of a derivation: a displayed equation with one line of words.

A :class:`Step` holds the SymPy object (an ``Eq``, an expression, a list of them or a matrix),
its LaTeX, the words, and where it comes from (``ref``: the paper's equation label or a
docs/physics.md tag). A :class:`Section` is a titled list of steps.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, field
from typing import Any

import sympy as sp

__all__ = [
    "MAX_SHOWN",
    "Named",
    "Section",
    "Step",
    "latex_of",
    "make_step",
    "matrix_equation",
    "named",
]

#: Matrices larger than this are shown by their non-zero entries, lists by their first entries.
MAX_SHOWN = 8
_MAX_LIST = 12


class Named(sp.Symbol):
    """A display symbol with its own LaTeX (e.g. a calligraphic L), printed by name in text."""

    _forms: dict[str, str] = {}  # noqa: RUF012 - a registry shared by all instances

    def _latex(self, printer: Any) -> str:  # SymPy's printer hook (printer unused)
        name: str = self.name
        return self._forms.get(name, name)


def named(text: str, latex: str) -> Named:
    """A :class:`Named` symbol printed as ``text`` in plain text and ``latex`` in LaTeX."""
    Named._forms[text] = latex
    return Named(text)


def matrix_equation(name: str, matrix: sp.MatrixBase) -> sp.Eq:
    """``name = matrix`` as an unevaluated equation (``Eq(Symbol, Matrix)`` would be False)."""
    rows, cols = matrix.shape
    return sp.Eq(sp.MatrixSymbol(name, rows, cols), sp.ImmutableMatrix(matrix), evaluate=False)


@dataclass(frozen=True)
class Step:
    """One step: ``equation`` (SymPy), its ``latex``, one line of ``words``, and ``ref`` (the
    paper's label such as ``"paper (QQQ1)"`` or a docs/physics.md tag such as ``"(M7)"``)."""

    equation: Any
    latex: str
    words: str
    ref: str = ""

    def _repr_latex_(self) -> str:
        return f"$\\displaystyle {self.latex}$"


@dataclass
class Section:
    """A titled list of steps (one method's derivation, the setup, the cross-check, ...)."""

    title: str
    steps: list[Step] = field(default_factory=list)
    note: str = ""

    def add(self, equation: Any, words: str, ref: str = "", *, latex: str | None = None) -> Step:
        """Append a step (LaTeX from the equation unless given) and return it."""
        step = make_step(equation, words, ref, latex=latex)
        self.steps.append(step)
        return step


def make_step(equation: Any, words: str, ref: str = "", *, latex: str | None = None) -> Step:
    """A :class:`Step` with LaTeX generated from ``equation`` unless ``latex`` is given."""
    return Step(equation, latex if latex is not None else latex_of(equation), words, ref)


def latex_of(obj: Any) -> str:
    """LaTeX of an equation, an expression, a matrix, or a list of them (one per line)."""
    if isinstance(obj, sp.MatrixBase):
        return _matrix_latex(obj)
    if isinstance(obj, Sequence) and not isinstance(obj, str):
        items = list(obj)
        shown = items if len(items) <= _MAX_LIST else [*items[: _MAX_LIST - 2], items[-1]]
        lines = [_aligned(latex_of(item)) for item in shown]
        if len(items) > _MAX_LIST:
            lines.insert(
                _MAX_LIST - 2, rf"&\;\;\vdots \quad\text{{({len(items)} equations in all)}}"
            )
        return r"\begin{aligned}" + r" \\ ".join(lines) + r"\end{aligned}"
    if isinstance(obj, str):
        return obj
    if isinstance(obj, sp.Eq) and isinstance(obj.rhs, sp.MatrixBase):
        return f"{sp.latex(obj.lhs)} = {_matrix_latex(obj.rhs)}"
    result: str = sp.latex(obj)
    return result


def _aligned(line: str) -> str:
    """Put the alignment point before the first top-level '=' of a line."""
    depth = 0
    for i, char in enumerate(line):
        if char in "{(":
            depth += 1
        elif char in "})":
            depth -= 1
        elif char == "=" and depth == 0:
            return line[:i] + "&=" + line[i + 1 :]
    return "&" + line


def _matrix_latex(matrix: sp.MatrixBase) -> str:
    rows, cols = matrix.shape
    if rows <= MAX_SHOWN and cols <= MAX_SHOWN:
        result: str = sp.latex(matrix, mat_delim="", mat_str="pmatrix")
        return result
    entries = [
        (i, j, matrix[i, j])
        for i in range(rows)
        for j in range(cols)
        if matrix[i, j] != 0 and j >= i
    ]
    shown = entries[:6]
    body = r",\; ".join(f"({i + 1},{j + 1}):\\ {sp.latex(v)}" for i, j, v in shown)
    more = (
        rf",\;\dots\ \text{{({len(entries)} non-zero entries on and above the diagonal)}}"
        if len(entries) > len(shown)
        else ""
    )
    return rf"\text{{a }}{rows}\times{cols}\text{{ matrix; entries }}{body}{more}"

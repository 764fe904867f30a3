r"""Steps and sections of a derivation: a displayed equation, one line of words, and how it follows.

A :class:`Step` holds the SymPy object (an ``Eq``, an expression, a list of them or a matrix),
its LaTeX, the words, where it comes from (``ref``: the paper's equation label or a
docs/physics.md tag), its ``tag`` (``"N3"``: the third step of the Newton section, shown as
the equation's number) and ``how`` it follows from earlier steps: a :class:`How`, one operation
a student can name (:data:`OPERATIONS`) applied to the steps it names by their tags. A
:class:`Section` is a titled list of steps; it numbers them with its ``prefix``.

Names print as a textbook would (:func:`pretty_text`, :func:`latex_of`): subscripts and
superscripts in their places (:math:`y^*_1`, :math:`\Omega_1^2`), :math:`\ell` for ``ell``, and
display-only symbols (:func:`named`) with their own plain-text and LaTeX forms.
"""

from __future__ import annotations

import re
from collections.abc import Sequence
from dataclasses import dataclass, field
from functools import cached_property
from typing import Any

import sympy as sp
from sympy.printing.conventions import split_super_sub
from sympy.printing.latex import LatexPrinter
from sympy.printing.precedence import PRECEDENCE
from sympy.printing.pretty.pretty import PrettyPrinter
from sympy.printing.pretty.pretty_symbology import pretty_symbol
from sympy.printing.pretty.stringpict import prettyForm
from sympy.printing.str import StrPrinter

__all__ = [
    "DEFINE",
    "GIVEN",
    "MAX_SHOWN",
    "OPERATIONS",
    "How",
    "Named",
    "Section",
    "Step",
    "eq",
    "inline",
    "latex_of",
    "make_step",
    "matrix_equation",
    "named",
    "pretty_name",
    "pretty_text",
]

#: Matrices larger than this are shown by their non-zero entries, lists by their first entries.
MAX_SHOWN = 8
_MAX_LIST = 12

#: The operations a step may apply, with what each means. Every displayed step names one.
OPERATIONS: dict[str, str] = {
    "given": "a law of physics, or the system's data, stated (the words say which)",
    "define": "a name for an expression",
    "substitute": "replace the named quantities using the equations of other steps",
    "solve": "solve the equations of earlier steps for the quantities on the left",
    "add": "add the equations of a step, each multiplied by its weight",
    "differentiate in time": "take d/dt of both sides",
    "integrate in time": "integrate both sides over time (the constant is stated)",
    "differentiate": "take the partial derivative with respect to the named variable",
    "rearrange": "multiply or divide by a factor that is not zero, and move terms across",
    "divide": "divide by a factor that is not zero during the motion",
    "linearise": "keep the first order in the coordinates (Taylor about the reference)",
    "expand to second order": "keep the second order in the coordinates (Taylor)",
    "second derivative": "the matrix of second derivatives at the reference q = 0",
    "matrix form": "write the equations as one matrix equation",
    "characteristic equation": "put q = v cos(Omega t): det(K - Omega^2 M) = 0",
    "read off": "compare with a standard form and read off its coefficient",
    "evaluate": "compute: both sides are equal",
    "with your values": "put the system's numbers (the notation table's) into a result: "
    "decimals, rounded",
    "check": "a comparison of results, not a step of a derivation",
}


@dataclass(frozen=True)
class How:
    """How a step follows: ``op`` (a key of :data:`OPERATIONS`) applied to the steps ``uses``
    names by their tags (``"N3"``; ``"N3:1"`` for its first equation only), with ``args``
    (weights, variables, a factor), ``law``: an equation (or a list) the words state that the
    operation applies to (a law such as Hooke's, or the standard form read off), and ``given``:
    equations the words state that the operation uses as well (such as dE/dt = 0).

    ``substitute`` works on ``law`` if there is one, else on the first step used, and
    eliminates the quantities ``args`` with the other equations (their time derivatives
    included); ``solve``: the displayed values satisfy the equations used (``args``: the
    unknowns); ``add``: ``args`` are the weights; ``divide``: ``args[0]`` is the factor;
    ``differentiate``: ``args`` are the variables, one per displayed equation;
    ``second derivative``, ``expand to second order`` and ``read off`` a matrix: ``args[0]``
    is the vector of coordinates (or rates)."""

    op: str
    uses: tuple[str, ...] = ()
    args: tuple[Any, ...] = ()
    law: Any = None
    given: tuple[Any, ...] = ()

    def __post_init__(self) -> None:
        if self.op not in OPERATIONS:
            raise ValueError(f"unknown operation {self.op!r}")  # a programming error


GIVEN = How("given")
DEFINE = How("define")


class Named(sp.Symbol):
    """A display symbol with its own plain-text (Unicode) and LaTeX forms (e.g. a calligraphic
    L, a partial derivative written out)."""

    _forms: dict[str, tuple[str, str]] = {}  # noqa: RUF012 - a registry shared by all instances

    def _latex(self, printer: Any) -> str:  # SymPy's printer hook (printer unused)
        name: str = self.name
        return self._forms.get(name, (name, name))[1]

    @property
    def text(self) -> str:
        """The plain-text (Unicode) form."""
        name: str = self.name
        return self._forms.get(name, (name, name))[0]


def named(name: str, latex: str, text: str | None = None, **assumptions: bool) -> Named:
    """A :class:`Named` symbol printed as ``text`` (default: ``name``) in plain text and
    ``latex`` in LaTeX."""
    Named._forms[name] = (text if text is not None else name, latex)
    return Named(name, **assumptions)


def eq(lhs: Any, rhs: Any, **_: Any) -> sp.Eq:
    """``lhs = rhs`` unevaluated: SymPy does not try to decide it (costly on large
    expressions, and a displayed equation is never to become True or False)."""
    return sp.Eq(lhs, rhs, evaluate=False)


def matrix_equation(name: str, matrix: sp.MatrixBase) -> sp.Eq:
    """``name = matrix`` as an unevaluated equation (``Eq(Symbol, Matrix)`` would be False)."""
    rows, cols = matrix.shape
    return sp.Eq(sp.MatrixSymbol(name, rows, cols), sp.ImmutableMatrix(matrix), evaluate=False)


# -- printing names as a textbook does ----------------------------------------------------------

_SUBSCRIPTS = dict(
    zip("0123456789+-=()aehijklmnoprstuvx", "₀₁₂₃₄₅₆₇₈₉₊₋₌₍₎ₐₑₕᵢⱼₖₗₘₙₒₚᵣₛₜᵤᵥₓ", strict=True)
)
_SUPERSCRIPTS = dict(zip("0123456789+-=()in*", "⁰¹²³⁴⁵⁶⁷⁸⁹⁺⁻⁼⁽⁾ⁱⁿ*", strict=True))
_BASES = {"ell": "ℓ"}
_STAR = "\ue000"  # a private-use character: the * of a name such as y*, while printing


def pretty_name(name: str) -> str:
    """A symbol name in plain text as a textbook prints it: ``y^*_1`` -> ``y₁*``,
    ``Omega_1^2`` -> ``Ω₁²``, ``ell_1`` -> ``ℓ₁``, ``phiddot_2`` -> ``φ̈₂``, ``r_1,2`` ->
    ``r₁,₂``; a subscript letter that Unicode cannot lower follows on the line (``F_1y`` ->
    ``F₁y``)."""
    base, sups, subs = split_super_sub(name)
    head = _BASES.get(base) or pretty_symbol(base)

    def script(text: str, table: dict[str, str]) -> str:
        out: list[str] = []
        for i, c in enumerate(text):
            if c not in table and c != ",":
                return "".join(out) + text[i:]
            out.append(table.get(c, c))
        return "".join(out)

    return head + script("".join(subs), _SUBSCRIPTS) + script("".join(sups), _SUPERSCRIPTS)


def _rank(term: sp.Expr) -> int:
    """How a textbook orders the terms of a sum: second derivatives first, then rates and
    momenta (the kinetic part), then the rest."""
    names = [split_super_sub(s.name)[0] for s in term.free_symbols if isinstance(s, sp.Symbol)]
    if any(n.endswith("ddot") for n in names):
        return 2
    if any(n.endswith("dot") or n == "p" for n in names):
        return 1
    return 0


def _index(term: sp.Expr) -> float:
    """The lowest body number among the subscripts of a term's symbols (inf if none)."""
    found = []
    for s in term.free_symbols:
        if isinstance(s, sp.Symbol):
            subs = split_super_sub(s.name)[2]
            digits = re.match(r"\d+", subs[0]) if subs else None
            if digits:
                found.append(int(digits.group(0)))
    return min(found) if found else float("inf")


def textbook_order(terms: list[sp.Expr]) -> list[sp.Expr]:
    """The terms of a sum in a textbook's order: :func:`_rank` first (``φ̈ + Ω²φ``, the kinetic
    part before the potential), then by body number (``p₁`` before ``p₂``), else SymPy's
    order; a difference of two terms with its positive term first (``φ₂ - φ₁``, ``1 - x``)."""
    ordered = sorted(terms, key=lambda t: (-_rank(t), _index(t)))
    if (
        len(ordered) == 2
        and _rank(ordered[0]) == _rank(ordered[1])
        and ordered[0].could_extract_minus_sign()
        and not ordered[1].could_extract_minus_sign()
    ):
        ordered.reverse()
    return ordered


def _merged_power(expr: sp.Expr) -> sp.Symbol | None:
    """``(Omega^2)**3`` as the symbol ``Omega^6`` (a squared name raised to a power prints as
    one power, Ω⁶, not Ω²³); None for any other expression."""
    base, exponent = expr.as_base_exp()
    if not (isinstance(base, sp.Symbol) and not isinstance(base, Named) and exponent.is_Integer):
        return None
    head, sups, subs = split_super_sub(base.name)
    if len(sups) != 1 or not sups[0].isdigit() or int(exponent) < 2:
        return None
    sub = f"_{''.join(subs)}" if subs else ""
    return sp.Symbol(f"{head}{sub}^{int(sups[0]) * int(exponent)}")


class _TextbookOrder:
    """Printer mixin: the terms of a sum in :func:`textbook_order`; a power of a squared
    name as one power (:func:`_merged_power`)."""

    def _print_Pow(self, expr: sp.Pow, *args: Any, **kwargs: Any) -> Any:
        merged = _merged_power(expr)
        if merged is not None:
            return self._print(merged)  # type: ignore[attr-defined]
        return super()._print_Pow(expr, *args, **kwargs)  # type: ignore[misc]

    def _as_ordered_terms(self, expr: sp.Expr, order: Any = None) -> list[sp.Expr]:
        terms: list[sp.Expr] = super()._as_ordered_terms(expr, order=order)  # type: ignore[misc]
        return textbook_order(list(terms))


class _TextbookPretty(_TextbookOrder, PrettyPrinter):
    """SymPy's pretty printer with names printed by :func:`pretty_name`."""

    def _print_Symbol(self, e: sp.Symbol, bold_name: bool = False) -> prettyForm:
        if isinstance(e, Named):
            return prettyForm(e.text)
        return prettyForm(pretty_name(e.name))

    def _print_MatrixSymbol(self, e: sp.MatrixSymbol) -> prettyForm:
        return prettyForm(pretty_name(str(e.name)))


class _TextbookStr(_TextbookOrder, StrPrinter):
    """One-line plain text with textbook names (for words)."""

    def _print_Symbol(self, expr: sp.Symbol) -> str:
        name = expr.text if isinstance(expr, Named) else pretty_name(expr.name)
        return name.replace("*", _STAR)  # kept apart from the multiplication signs

    def _print_Pow(self, expr: sp.Pow, rational: bool = False) -> str:
        merged = _merged_power(expr)
        if merged is not None:
            return self._print_Symbol(merged)
        base, exponent = expr.as_base_exp()
        if exponent.is_Integer and int(exponent) > 1:
            text: str = self.parenthesize(base, PRECEDENCE["Pow"])
            return text + "".join(_SUPERSCRIPTS[c] for c in str(exponent))
        if exponent == sp.S.Half:
            inner = self._print(base)
            return f"√{inner}" if base.is_Atom else f"√({inner})"
        result: str = super()._print_Pow(expr, rational)
        return result.replace("**", "^")

    def _print_Mul(self, expr: sp.Mul) -> str:
        result: str = super()._print_Mul(expr)
        return result.replace("*", "·")

    def _print_Equality(self, expr: sp.Eq) -> str:
        """``lhs = rhs`` (not SymPy's ``Eq(lhs, rhs)``)."""
        return f"{self._print(expr.lhs)} = {self._print(expr.rhs)}"


def inline(obj: Any) -> str:
    """``obj`` as one line of plain text with textbook names (``R_2/R_1`` -> ``R₂/R₁``)."""
    result: str = _TextbookStr({"order": None}).doprint(obj)
    return result.replace(_STAR, "*")


class _TextbookLatex(_TextbookOrder, LatexPrinter):
    """SymPy's LaTeX printer (names: ``ell`` is ``\\ell``, ``y^*_1`` is ``y^{*}_{1}``)."""


def paper_surds(obj: Any) -> Any:
    """Surd coefficients as the paper writes them, roots left in the denominator:
    ``√2/2 q₁`` -> ``q₁/√2``, ``√6/3 q₂`` -> ``√2 q₂/√3`` (the paper's (k), (h)), ``√6/2`` ->
    ``√3/√2``. A coefficient c with c² = p/q in lowest terms becomes √p/√q where q is not a
    square (where it is, SymPy's form is the paper's too: 5√42/3). Display only: the value is
    the same, the tree is left unevaluated."""
    if isinstance(obj, list | tuple):
        return type(obj)(paper_surds(item) for item in obj)
    if isinstance(obj, sp.MatrixBase) or not isinstance(obj, sp.Basic) or obj.is_Atom:
        return obj
    if isinstance(obj, sp.Mul):
        numbers = [a for a in obj.args if a.is_number]
        others = [paper_surds(a) for a in obj.args if not a.is_number]
        if numbers and others:
            surd = _surd(sp.Mul(*numbers))
            if surd is not None:
                sign, top, root = surd
                return sp.Mul(*sign, *top, *others, root, evaluate=False)
        return obj.func(*[paper_surds(a) for a in obj.args], evaluate=False)
    if isinstance(obj, sp.Add | sp.Pow | sp.Equality):
        return obj.func(*[paper_surds(a) for a in obj.args], evaluate=False)
    return obj


def _surd(number: sp.Expr) -> tuple[list[sp.Expr], list[sp.Expr], sp.Expr] | None:
    """``a√n/b`` as ``√p/√q``: its sign, numerator and denominator factors (None where it is
    not a surd with a root to move down)."""
    if number.is_Rational or not number.is_real:
        return None
    square = sp.nsimplify(number**2) if not (number**2).is_Rational else number**2
    if not square.is_Rational or square <= 0:
        return None
    p, q = int(square.p), int(square.q)
    if q == 1 or sp.sqrt(q).is_Integer:
        return None
    sign: list[sp.Expr] = [sp.S.NegativeOne] if number.is_negative else []
    top = sp.sqrt(p)
    return sign, ([] if top == 1 else [top]), sp.Pow(sp.sqrt(q), -1, evaluate=False)


def pretty_text(obj: Any, *, columns: int = 100) -> str:
    """Unicode pretty-printing with textbook names (:func:`pretty_name`) and the paper's
    surds (:func:`paper_surds`)."""
    printer = _TextbookPretty({"use_unicode": True, "num_columns": columns})
    result: str = printer.doprint(paper_surds(obj))
    return result


def _latex(obj: Any, **settings: Any) -> str:
    result: str = _TextbookLatex(settings).doprint(paper_surds(obj))
    return result


# -- steps and sections -------------------------------------------------------------------------


@dataclass(frozen=True)
class Step:
    """One step: ``equation`` (SymPy), one line of ``words``, ``ref`` (the paper's label such
    as ``"paper (QQQ1)"`` or a docs/physics.md tag such as ``"(M7)"``), ``tag`` (its number,
    e.g. ``"N3"``; empty for the cross-check), ``how`` it follows from earlier steps, and
    ``source``: its LaTeX where it is written by hand (else :attr:`math` prints the
    equation, when first asked: plain text never needs it); ``plain``: its plain text where
    it is written by hand (the physics' order of factors, m a = F - f, which SymPy would
    print a⋅m), else the equation is pretty-printed."""

    equation: Any
    words: str
    ref: str = ""
    tag: str = ""
    how: How | None = None
    source: str | None = None
    plain: str | None = None

    @cached_property
    def math(self) -> str:
        """The equation's LaTeX, without its number."""
        return self.source if self.source is not None else latex_of(self.equation)

    @property
    def latex(self) -> str:
        """The LaTeX shown: the equation with its number (``\\tag{N3}``)."""
        return self.math + (rf" \qquad \tag{{{self.tag}}}" if self.tag else "")

    @property
    def equations(self) -> list[Any]:
        """The displayed equation(s) as a list."""
        eq = self.equation
        return list(eq) if isinstance(eq, list | tuple) else [eq]

    def _repr_latex_(self) -> str:
        return f"$\\displaystyle {self.math}$"


@dataclass
class Section:
    """A titled list of steps (one method's derivation, the setup, the cross-check, ...);
    ``prefix`` numbers its steps (``N1``, ``N2``, ...); ``rates`` maps each symbol that
    changes in time to the symbol of its rate (``phi_1 -> phidot_1``), for the steps that
    differentiate or integrate in time; ``cites``: the paper's sections it follows, as the
    paper numbers them (``"paper Sec. 5.3"``), shown under the title."""

    title: str
    steps: list[Step] = field(default_factory=list)
    note: str = ""
    prefix: str = ""
    rates: dict[sp.Symbol, sp.Symbol] = field(default_factory=dict)
    cites: str = ""

    def add(
        self,
        equation: Any,
        words: str,
        ref: str = "",
        *,
        how: How | None = None,
        latex: str | None = None,
        plain: str | None = None,
    ) -> Step:
        """Append a step (LaTeX and plain text from the equation unless given), numbered, and
        return it."""
        tag = f"{self.prefix}{len(self.steps) + 1}" if self.prefix else ""
        step = make_step(equation, words, ref, latex=latex, tag=tag, how=how, plain=plain)
        self.steps.append(step)
        return step


def make_step(
    equation: Any,
    words: str,
    ref: str = "",
    *,
    latex: str | None = None,
    tag: str = "",
    how: How | None = None,
    plain: str | None = None,
) -> Step:
    """A :class:`Step`; its LaTeX is ``latex`` if given, else generated from ``equation`` when
    first needed; its plain text ``plain`` if given, else pretty-printed."""
    return Step(equation, words, ref, tag, how, latex, plain)


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
        return f"{_latex(obj.lhs)} = {_matrix_latex(obj.rhs)}"
    return _latex(obj)


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
        return _latex(matrix, mat_delim="", mat_str="pmatrix")
    entries = [
        (i, j, matrix[i, j])
        for i in range(rows)
        for j in range(cols)
        if matrix[i, j] != 0 and j >= i
    ]
    shown = entries[:6]
    body = r",\; ".join(f"({i + 1},{j + 1}):\\ {_latex(v)}" for i, j, v in shown)
    more = (
        rf",\;\dots\ \text{{({len(entries)} non-zero entries on and above the diagonal)}}"
        if len(entries) > len(shown)
        else ""
    )
    return rf"\text{{a }}{rows}\times{cols}\text{{ matrix; entries }}{body}{more}"

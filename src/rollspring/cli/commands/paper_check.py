"""``rollspring paper-check``: every quantitative statement of the paper, with its verdict.

``--json`` prints a list of {``location``, ``claim`` (LaTeX), ``quote`` (the paper's words,
verbatim from its LaTeX source), ``verdict`` (``verified`` | ``holds-under-stated-assumption`` |
``holds-only-if`` | ``wrong``), ``assumption`` (the paper's stated assumptions the verdict relies
on, with the paper's words, or null), ``correction`` (LaTeX or null), ``reason``}; ``--format
text`` (default) a Rich table with ✔/☑/⚠/✘ marks, ``--format markdown`` a Markdown table with the
LaTeX in ``$...$``. The verdicts come from :mod:`rollspring.analysis.paper` (the
derivation engine), through :func:`rollspring.service.documents.paper_checks`. The command is
added to an app by :func:`register`.
"""

from __future__ import annotations

import json
import re
from typing import TYPE_CHECKING, Annotated, Any

import typer

from rollspring.cli.common import add_command, print_text, stdout_console
from rollspring.cli.options import Formats, json_option
from rollspring.errors import PaperCheckError

if TYPE_CHECKING:
    from rollspring.analysis.paper import ClaimCheck

__all__ = [
    "FORMATS",
    "PaperCheckError",
    "markdown_table",
    "paper_check",
    "plain",
    "quote_text",
    "register",
    "run_text",
    "summary",
]

#: Formats ``--format`` accepts.
FORMATS = Formats("text", "markdown")

#: The terminal colour of each verdict (by its word: rollspring.analysis.paper, SymPy, is
#: imported when the command runs).
_STYLE = {
    "verified": "green",
    "holds-under-stated-assumption": "cyan",
    "holds-only-if": "yellow",
    "wrong": "red",
}


def paper_check(
    as_json: Annotated[bool, json_option("Print one JSON list on stdout.")] = False,
    format: Annotated[str, FORMATS.option()] = "text",  # noqa: A002
) -> None:
    """Check every quantitative statement of the paper against the symbolic derivation: ✔
    verified, ☑ holds under an assumption the paper states, ⚠ holds only under a condition the
    paper does not state (named), ✘ wrong (with the correction); each with the paper's words."""
    FORMATS.check(format, PaperCheckError)
    if as_json and format != "text":
        raise PaperCheckError(f"--format {format}: not with --json (one JSON list is printed)")
    from rollspring.service.documents import claims_json, paper_checks, paper_runs

    checks = paper_checks()
    runs = paper_runs(checks)
    if as_json:
        print_text(json.dumps(claims_json(checks, runs), indent=2, ensure_ascii=False) + "\n")
        return
    if format == "markdown":
        print_text(markdown_table(checks, runs))
        return
    _print_table(checks, runs)


def summary(checks: tuple[ClaimCheck, ...] | list[ClaimCheck]) -> str:
    """'N claims: a verified, b hold under an assumption the paper states, c hold only under a
    condition the paper does not state, d wrong'."""
    from rollspring.analysis.paper import verdict_counts

    return f"{len(checks)} claims: {verdict_counts(c.verdict for c in checks)}"


def quote_text(quote: str) -> str:
    """The paper's words (LaTeX source) as readable text: references and environments dropped,
    the mathematics through :func:`plain`."""
    text = re.sub(r"\\ref\{fig(\d+)\}", r"\1", quote)
    text = re.sub(r"\\ref\{([^}]*)\}", r"\1", text)
    text = re.sub(r"\\(begin|end)\{[a-z*]+\}", " ", text)
    text = text.replace("~", " ").replace("$", "")
    return plain(text)


def markdown_table(
    checks: tuple[ClaimCheck, ...] | list[ClaimCheck], runs: dict[str, Any] | None = None
) -> str:
    """The checks as a Markdown table (LaTeX in ``$...$``), with a summary line; a claim's
    counterexample run (``runs``, by claim key) follows its reason."""
    runs = runs or {}
    lines = [
        "# The paper's claims, checked by rollspring's derivation engine",
        "",
        summary(checks) + ".",
        "",
        "| | where | the paper says | claim | verdict | correction | reason |",
        "|---|---|---|---|---|---|---|",
    ]
    for check in checks:
        correction = f"${_cell_math(check.correction)}$" if check.correction else ""
        lines.append(
            f"| {check.verdict.mark} | {_cell(check.claim.location)} | "
            f"“{_cell(quote_text(check.claim.quote))}” | ${_cell_math(check.claim.latex)}$ | "
            f"{check.verdict.words} | {correction} | {_cell(check.reason)}"
            + (f" {_cell(run_text(runs[check.claim.key]))}" if check.claim.key in runs else "")
            + " |"
        )
    return "\n".join(lines) + "\n"


def _cell(text: str) -> str:
    return text.replace("|", "\\|").replace("\n", " ")


def _cell_math(latex: str) -> str:
    return latex.replace("|", r"\vert ").replace("\n", " ")


def run_text(run: Any) -> str:
    """A counterexample run in one line: what the system shows, measured against the paper."""
    cx = run.counterexample
    verdict = "disagrees with" if run.disagrees else "agrees with"
    return (
        f"run ({cx.system}): {cx.words}: {run.measured:.4g} against the paper's {cx.paper:.4g} "
        f"({verdict} it, tolerance {cx.tolerance:g}); {run.details}"
    )


def _print_table(checks: tuple[ClaimCheck, ...], runs: dict[str, Any]) -> None:
    from rich.table import Table
    from rich.text import Text

    from rollspring.analysis.paper import Verdict

    table = Table(
        title="The paper's statements, checked by the derivation engine",
        title_justify="left",
        show_lines=True,
    )
    table.add_column("", no_wrap=True)
    table.add_column("where", ratio=2, overflow="fold")
    table.add_column("claim", ratio=4, overflow="fold")
    table.add_column("verdict", ratio=4, overflow="fold")
    for check in checks:
        verdict = check.verdict.words
        if check.verdict in (Verdict.HOLDS_STATED, Verdict.HOLDS_ONLY_IF):
            verdict = check.reason
        elif check.verdict == Verdict.WRONG:
            verdict = f"wrong: {check.reason}"
        if check.verdict != Verdict.VERIFIED:
            for assumption in check.claim.assumptions:
                verdict += f"\nstated ({assumption.location}): “{quote_text(assumption.quote)}”"
        if check.correction:
            verdict += f"\ncorrect: {plain(check.correction)}"
        if check.claim.key in runs:
            verdict += f"\n{run_text(runs[check.claim.key])}"
        mark = f"[{_STYLE[check.verdict]}]{check.verdict.mark}[/]"
        table.add_row(
            mark,
            Text(check.claim.location),
            Text(f"{plain(check.claim.latex)}\n“{quote_text(check.claim.quote)}”"),
            Text(verdict, style=_STYLE[check.verdict] if check.verdict != Verdict.VERIFIED else ""),
        )
    console = stdout_console()
    console.print(table)
    console.print(summary(checks), markup=False)


# -- LaTeX to readable text (for the terminal) ---------------------------------------------------

_SYMBOLS = {
    r"\varphi": "φ",
    r"\phi": "φ",
    r"\Phi": "Φ",
    r"\Omega": "Ω",
    r"\omega": "ω",
    r"\varepsilon": "ε",
    r"\gamma": "γ",
    r"\alpha": "α",
    r"\beta": "β",
    r"\pi": "π",
    r"\rightarrow": "→",
    r"\Rightarrow": "⇒",
    r"\neq": "≠",
    r"\equiv": "≡",
    r"\cdot": "·",
    r"\quad": "  ",
    r"\qquad": "   ",
    r"\,": " ",
    r"\;": " ",
    r"\ ": " ",
    r"\!": "",
    r"\left": "",
    r"\right": "",
    r"\lvert": "|",
    r"\rvert": "|",
    r"\vert": "|",
    r"\sum": "Σ",
    r"\infty": "∞",
    r"\leq": "≤",
    r"\geq": "≥",
    r"\iff": "⇔",
    r"\vdots": "⋮",
}
_SUPERSCRIPT = str.maketrans("0123456789+-", "⁰¹²³⁴⁵⁶⁷⁸⁹⁺⁻")
_SUBSCRIPT = str.maketrans("0123456789", "₀₁₂₃₄₅₆₇₈₉")


def _group(text: str, start: int) -> tuple[str, int]:
    """The brace group (or single character) at ``start``: its content and the end index."""
    while start < len(text) and text[start] == " ":
        start += 1
    if start >= len(text):
        return "", start
    if text[start] != "{":
        if text[start] == "\\":
            match = re.match(r"\\[A-Za-z]+", text[start:])
            if match:
                return match.group(0), start + match.end()
        return text[start], start + 1
    depth = 0
    for i in range(start, len(text)):
        if text[i] == "{":
            depth += 1
        elif text[i] == "}":
            depth -= 1
            if depth == 0:
                return text[start + 1 : i], i + 1
    return text[start + 1 :], len(text)


def plain(latex: str) -> str:
    """A LaTeX formula as readable Unicode text (fractions as a/b, roots as √, dots as
    combining accents, Greek letters, sub- and superscripts of digits)."""
    out: list[str] = []
    i = 0
    text = latex
    while i < len(text):
        char = text[i]
        if char == "\\":
            match = re.match(r"\\([A-Za-z]+|.)", text[i:])
            if match is None:  # a backslash at the very end: kept as it is
                out.append(char)
                i += 1
                continue
            name = "\\" + match.group(1)
            i += match.end()
            if name in (r"\frac", r"\tfrac", r"\dfrac"):
                num, i = _group(text, i)
                den, i = _group(text, i)
                fraction = f"{_wrap(plain(num))}/{_wrap(plain(den))}"
                rest = re.sub(r"^(\s|\\right|\\quad|\\,|\\;|\\ )+", "", text[i:])
                before = "".join(out).rstrip()[-1:]
                joined = (
                    rest[:1].isalnum()
                    or (rest[:1] != "" and rest[:1] in "\\(")
                    or before.isalnum()
                    or before in ")̇̈₀₁₂₃₄₅₆₇₈₉²³"
                )
                out.append(f"({fraction})" if joined else fraction)
            elif name == r"\sqrt":
                arg, i = _group(text, i)
                out.append(f"√{_wrap(plain(arg))}")
            elif name in (r"\dot", r"\ddot", r"\hat", r"\bcancel"):
                arg, i = _group(text, i)
                accent = {
                    r"\dot": "\u0307",
                    r"\ddot": "\u0308",
                    r"\hat": "\u0302",
                    r"\bcancel": "\u0338",
                }[name]
                inner = plain(arg)
                if len(inner) == 1 or (
                    inner[:1].isalpha() and all(c in "₀₁₂₃₄₅₆₇₈₉" for c in inner[1:])
                ):
                    out.append(inner[0] + accent + inner[1:])
                else:
                    out.append(f"({inner}){accent}")
            elif name in (
                r"\text",
                r"\mathrm",
                r"\operatorname",
                r"\mathcal",
                r"\boldsymbol",
                r"\mathbf",
            ):
                arg, i = _group(text, i)
                out.append(plain(arg) if name != r"\text" else arg)
            elif name in _SYMBOLS:
                out.append(_SYMBOLS[name])
            else:
                out.append(name[1:])
            continue
        if char in "^_":
            arg, i = _group(text, i + 1)
            rendered = plain(arg)
            table = _SUPERSCRIPT if char == "^" else _SUBSCRIPT
            converted = rendered.translate(table)
            if all(c in "⁰¹²³⁴⁵⁶⁷⁸⁹⁺⁻₀₁₂₃₄₅₆₇₈₉" for c in converted):
                out.append(converted)
            else:
                out.append(f"{char}{_wrap(rendered)}" if char == "^" else f"_{rendered}")
            continue
        if char in "{}":
            i += 1
            continue
        out.append(char)
        i += 1
    return re.sub(r" {2,}", "  ", "".join(out)).strip()


def _wrap(text: str) -> str:
    """Parenthesise a compound operand."""
    text = text.strip()
    atom = r"(\d+(\.\d+)?|√\d+|[A-Za-zφΦΩωεγαβπ][\u0307\u0308\u0302']?[₀-₉]*[⁰-⁹]*)"
    if len(text) <= 1 or re.fullmatch(atom, text):
        return text
    if text.startswith("(") and text.endswith(")") and text.count("(") == 1:
        return text
    return f"({text})"


def register(app: typer.Typer) -> None:
    """Add the ``paper-check`` command to ``app`` (with rollspring's one-line error handling)."""
    add_command(app, paper_check, "paper-check", extras="report")

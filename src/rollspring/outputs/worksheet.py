r"""Exercise sheets that build up complexity as the paper's Fig. 4 suggests, and their solutions,
rendered.

A :class:`~rollspring.analysis.exercises.Worksheet` (the sheet's data and its answers, made by
:func:`rollspring.service.documents.worksheet`) is written here: :func:`render_sheet` and
:func:`render_solutions` give the exercise and its solutions as Markdown or as a LaTeX document
that ``pdflatex`` compiles (amsmath only). The system is printed as a TOML file in the
solutions, so that ``rollspring analyze`` can be run on it.
"""

from __future__ import annotations

import math
import re
import unicodedata
from typing import Any

from rollspring.analysis.derivation import Section
from rollspring.analysis.derivation.render import LATEX_PREAMBLE, latex_text
from rollspring.analysis.exercises import SHAPE_WORDS, Answer, Worksheet, end_words
from rollspring.errors import WorksheetError

__all__ = [
    "FORMATS",
    "WorksheetError",
    "format_number",
    "render_sheet",
    "render_solutions",
    "system_toml",
]

#: Output formats.
FORMATS = ("markdown", "latex")


def format_number(value: float) -> str:
    """Six significant digits; an exact zero as 0, infinity as inf."""
    if math.isinf(value):
        return "inf"
    if value == 0:
        return "0"
    return f"{value:.6g}"


def system_toml(data: dict[str, Any]) -> str:
    """The system file (a dictionary of the schema's structure) as TOML."""
    lines = []
    for key in ("name", "description", "gravity"):
        if key in data:
            lines.append(f"{key} = {_toml_value(data[key])}")
    for table in ("anchors", "bodies", "springs", "forces"):
        for item in data.get(table, []):
            lines += ["", f"[[{table}]]"]
            lines += [f"{key} = {_toml_value(value)}" for key, value in item.items()]
    return "\n".join(lines) + "\n"


def _toml_value(value: Any) -> str:
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, int | float):
        if isinstance(value, float) and math.isinf(value):
            return "inf"
        return repr(float(value))
    if isinstance(value, str):
        return '"' + value.replace("\\", "\\\\").replace('"', '\\"') + '"'
    if isinstance(value, list):
        return "[" + ", ".join(_toml_value(v) for v in value) + "]"
    if isinstance(value, dict):
        return "{" + ", ".join(f"{k} = {_toml_value(v)}" for k, v in value.items()) + "}"
    raise TypeError(f"cannot write {type(value).__name__} as TOML")


def _tables(sheet: Worksheet) -> list[tuple[str, list[str], list[list[str]]]]:
    """(title, header, rows) of the bodies, anchors and springs."""
    bodies = []
    for i, b in enumerate(sheet.system.bodies):
        bodies.append(
            [
                str(i + 1),
                SHAPE_WORDS[b.shape][0],
                format_number(b.mass),
                format_number(b.radius) if b.rolls else "-",
                format_number(b.x),
                format_number(b.v),
            ]
        )
    out = [("Bodies", ["body", "shape", "m (kg)", "R (m)", "x (m)", "v (m/s)"], bodies)]
    if sheet.system.anchors:
        out.append(
            (
                "Walls",
                ["wall", "x (m)", "y (m)"],
                [[a.id, format_number(a.x), format_number(a.y)] for a in sheet.system.anchors],
            )
        )
    springs = []
    for s, spring in enumerate(sheet.system.springs):
        ends = " - ".join(end_words(e) for e in spring.ends)
        heights = []
        for end, at in zip(spring.ends, spring.attachments, strict=True):
            if end in sheet.system.body_map:
                if at.is_centre_form:
                    heights.append("centre")
                else:
                    assert at.height is not None  # the exercises attach springs by height
                    heights.append(f"{format_number(at.height)} m")
        springs.append(
            [
                str(s + 1),
                ends,
                format_number(spring.stiffness),
                format_number(sheet.system.rest_lengths[s]),
                ", ".join(heights),
            ]
        )
    out.append(("Springs", ["spring", "ends", "k (N/m)", "L (m)", "attached at (height)"], springs))
    return out


def render_sheet(sheet: Worksheet, format: str = "markdown") -> str:  # noqa: A002
    """The exercise sheet as Markdown or as a LaTeX document."""
    _check_format(format)
    if format == "latex":
        return _latex_sheet(sheet)
    lines = [
        f"# rollspring worksheet, {_md(sheet.title)}",
        "",
        f"*Seed {sheet.seed}. SI units; $g = {sheet.system.gravity:g}$ m/s$^2$.*",
        "",
        "## The system",
        "",
    ]
    for paragraph in sheet.setting:
        lines += [paragraph, ""]
    for title, header, rows in _tables(sheet):
        lines += [f"**{title}**", "", "| " + " | ".join(header) + " |", "|" + "---|" * len(header)]
        lines += ["| " + " | ".join(row) + " |" for row in rows]
        lines.append("")
    lines += ["## Questions", ""]
    lines += [f"{n}. {q}" for n, q in enumerate(sheet.questions, 1)]
    lines += ["", "*The solutions are on a separate sheet.*"]
    return "\n".join(lines) + "\n"


def render_solutions(sheet: Worksheet, format: str = "markdown") -> str:  # noqa: A002
    """The solutions: the system file, the derivation (Lagrange, from the derivation engine)
    and the numbers (from ``rollspring.analyze``), as Markdown or as a LaTeX document."""
    _check_format(format)
    if format == "latex":
        return _latex_solutions(sheet)
    lines = [
        f"# Solutions: rollspring worksheet, {_md(sheet.title)}",
        "",
        f"*Seed {sheet.seed}.*",
        "",
        "## The system as a rollspring file",
        "",
        "Save it as `system.toml` and run `rollspring analyze system.toml` to check the numbers.",
        "",
        "```toml",
        system_toml(sheet.data).rstrip(),
        "```",
        "",
        "## Derivation",
        "",
        _md(sheet.derivation.subtitle),
    ]
    for section in _sections(sheet):
        lines += ["", f"### {_md(section.title)}"]
        if section.note:
            lines += ["", _md(section.note)]
        for step in section.steps:
            ref = f" *({_md(step.ref)})*" if step.ref else ""
            lines += ["", _md(step.words) + ref, "", "$$", " ".join(step.latex.split()), "$$"]
    lines += ["", "## Answers (rollspring analyze)", ""]
    answers = sheet.answers
    for number, question in enumerate(sheet.questions, 1):
        lines.append(f"{number}. {question}")
        for answer in (a for a in answers if a.question == number):
            lines.append(f"   - {answer.label}: {_values_text(answer)}")
        if number in sheet.notes:
            lines.append(f"   - {sheet.notes[number]}")
    for warning in sheet.analysis.warnings:
        lines += ["", f"*Note (rollspring analyze): {_md(warning)}*"]
    return "\n".join(lines) + "\n"


def _values_text(answer: Answer, *, latex: bool = False) -> str:
    """The values with their names and unit (Markdown, or LaTeX text)."""

    def words(text: str) -> str:
        return latex_text(text) if latex else text

    unit = ""
    if answer.unit:
        squared = answer.unit.endswith("^2")
        base = answer.unit.removesuffix("^2")
        unit = " " + words(base) + (("$^2$" if latex else "²") if squared else "")
    if answer.names and len(answer.names) == len(answer.values):
        return "; ".join(
            f"{words(name)} {format_number(v)}{unit}"
            for name, v in zip(answer.names, answer.values, strict=True)
        )
    return ", ".join(format_number(v) for v in answer.values) + unit


def _sections(sheet: Worksheet) -> list[Section]:
    derivation = sheet.derivation
    out = [derivation.setup]
    result = derivation.methods.get("lagrange")
    if result is not None:
        out.append(result.section)
    if sheet.level > 1:
        out.append(derivation.forces)
    return out


def _check_format(format: str) -> None:  # noqa: A002
    if format not in FORMATS:
        raise WorksheetError(f"--format: unknown format '{format}' (formats: {', '.join(FORMATS)})")


def _md(words: str) -> str:
    """Words for Markdown (math in $...$ kept)."""
    return re.sub(r"([`*_\[\]<>|])", r"\\\1", words) if "$" not in words else words


# -- LaTeX ---------------------------------------------------------------------------------------


def _latex_words(text: str) -> str:
    """Text with ``$math$`` for LaTeX: the words escaped, the math kept (both in ASCII)."""
    parts = text.split("$")
    out = []
    for n, part in enumerate(parts):
        out.append(f"${_ascii(part)}$" if n % 2 else latex_text(part))
    return "".join(out)


def _ascii(value: str) -> str:
    decomposed = unicodedata.normalize("NFKD", value.replace("\u2212", "-"))
    kept = "".join(c for c in decomposed if not unicodedata.combining(c))
    return kept.encode("ascii", "replace").decode("ascii")


def _latex_tables(sheet: Worksheet) -> list[str]:
    lines = []
    for title, header, rows in _tables(sheet):
        lines += [
            rf"\paragraph{{{title}}}",
            "",
            r"\begin{tabular}{" + "l" * len(header) + "}",
            r"\hline",
            " & ".join(latex_text(h) for h in header) + r" \\",
            r"\hline",
        ]
        lines += [" & ".join(latex_text(c) for c in row) + r" \\" for row in rows]
        lines += [r"\hline", r"\end{tabular}", ""]
    return lines


def _latex_sheet(sheet: Worksheet) -> str:
    lines = list(LATEX_PREAMBLE)
    lines += [
        rf"\section*{{rollspring worksheet, {latex_text(sheet.title)}}}",
        rf"\emph{{Seed {sheet.seed}. SI units; $g = {sheet.system.gravity:g}$\,m/s$^2$.}}",
        r"\subsection*{The system}",
    ]
    for paragraph in sheet.setting:
        lines += [_latex_words(paragraph), ""]
    lines += _latex_tables(sheet)
    lines += [r"\subsection*{Questions}", r"\begin{enumerate}"]
    lines += [rf"\item {_latex_words(q)}" for q in sheet.questions]
    lines += [
        r"\end{enumerate}",
        r"\emph{The solutions are on a separate sheet.}",
        r"\end{document}",
    ]
    return "\n".join(lines) + "\n"


def _latex_solutions(sheet: Worksheet) -> str:
    lines = list(LATEX_PREAMBLE)
    lines += [
        rf"\section*{{Solutions: rollspring worksheet, {latex_text(sheet.title)}}}",
        rf"\emph{{Seed {sheet.seed}.}}",
        r"\subsection*{The system as a rollspring file}",
        latex_text("Save it as system.toml and run: rollspring analyze system.toml"),
        r"\begin{verbatim}",
        _ascii(system_toml(sheet.data)).rstrip(),
        r"\end{verbatim}",
        r"\subsection*{Derivation}",
        latex_text(sheet.derivation.subtitle),
    ]
    for section in _sections(sheet):
        lines.append(rf"\subsubsection*{{{latex_text(section.title)}}}")
        if section.note:
            lines.append(latex_text(section.note))
        for step in section.steps:
            ref = rf" \hfill{{\small ({latex_text(step.ref)})}}" if step.ref else ""
            lines += [
                "",
                latex_text(step.words) + ref,
                r"\begin{equation*}",
                _ascii(step.latex),
                r"\end{equation*}",
            ]
    lines += [r"\subsection*{Answers (rollspring analyze)}", r"\begin{enumerate}"]
    answers = sheet.answers
    for number, question in enumerate(sheet.questions, 1):
        lines.append(rf"\item {_latex_words(question)}")
        given = [
            rf"\item {_latex_words(a.label)}: {_values_text(a, latex=True)}"
            for a in answers
            if a.question == number
        ]
        if number in sheet.notes:
            given.append(rf"\item {_latex_words(sheet.notes[number])}")
        if given:
            lines += [r"\begin{itemize}", *given, r"\end{itemize}"]
    lines.append(r"\end{enumerate}")
    for warning in sheet.analysis.warnings:
        lines += [r"\emph{" + latex_text(f"Note (rollspring analyze): {warning}") + "}", ""]
    lines.append(r"\end{document}")
    return "\n".join(lines) + "\n"

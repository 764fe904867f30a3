r"""LaTeX that mixes text and math (the paper's words, quoted from its source) as HTML: the text
escaped, its text-mode markup as HTML (``\emph``, ``~``, ``--``, ``\%``, ``\cite``, ``\ref`` ...),
every formula as MathML (:func:`~rollspring.outputs.report._html.latex_to_mathml`).

A formula is what stands between ``$...$``, ``$$...$$``, ``\(...\)``, ``\[...\]`` or inside a math
environment (``equation``, ``align``, ``eqnarray`` ... starred or not; a quote may begin inside one,
before its ``\end``, or stop inside one, after its ``\begin``). A quote with none of these is a
formula when it could only be one (``_``, ``^``, ``=`` or a command text mode does not have: a
quote taken from inside an equation of the paper), text otherwise. What cannot be converted is
shown as its LaTeX source in a marked ``<code class="tex-source">`` and its reason appended to
``failures`` (as :func:`~rollspring.outputs.report._html.math_or_source` does): never a crash.

:func:`tex_text_html` is the one conversion of such a string; :func:`claim_html` gives a claim's
quote, formula and correction as the report and the page (through ``POST /api/derive``) show them.
"""

from __future__ import annotations

import re
import unicodedata
from typing import TYPE_CHECKING

from rollspring.outputs.report._html import Markup, esc, math_or_source

if TYPE_CHECKING:
    from rollspring.analysis.paper import ClaimCheck

__all__ = ["claim_html", "tex_text_html"]

_MATH_ENVIRONMENTS = (
    "equation",
    "align",
    "alignat",
    "eqnarray",
    "gather",
    "multline",
    "flalign",
    "displaymath",
    "math",
)
_ENV = r"(?:" + "|".join(_MATH_ENVIRONMENTS) + r")\*?"
_BEGIN = re.compile(r"\\begin\{(" + _ENV + r")\}")
_END = re.compile(r"\\end\{(" + _ENV + r")\}")
_OPENERS = (("$$", "$$"), ("\\[", "\\]"), ("\\(", "\\)"), ("$", "$"))

# Text-mode commands with one argument, as HTML around the argument (converted in turn).
_WRAPPERS = {
    "emph": ("<em>", "</em>"),
    "textit": ("<i>", "</i>"),
    "textsl": ("<i>", "</i>"),
    "textbf": ("<strong>", "</strong>"),
    "textsc": ('<span class="tex-sc">', "</span>"),
    "texttt": ("<code>", "</code>"),
    "underline": ("<u>", "</u>"),
    "text": ("", ""),
    "textrm": ("", ""),
    "textnormal": ("", ""),
    "textup": ("", ""),
    "mbox": ("", ""),
    "hbox": ("", ""),
    "footnote": (' <small class="tex-footnote">(', ")</small>"),
}
# Cross-references: the label (the paper's numbering of equations is not at hand), marked as a
# reference.
_REFERENCES = {"ref": ("", ""), "eqref": ("(", ")"), "cite": ("[", "]"), "citep": ("[", "]")}
_DROPPED_WITH_ARGUMENT = {"label", "index", "vspace", "hspace", "phantom"}
_SYMBOLS = {
    "dots": "…",
    "ldots": "…",
    "textendash": "–",
    "textemdash": "—",
    "S": "§",
    "P": "¶",
    "ss": "ß",
    "o": "ø",
    "O": "Ø",
    "ae": "æ",
    "AE": "Æ",
    "l": "ł",
    "L": "Ł",
    "i": "ı",
    "LaTeX": "LaTeX",
    "TeX": "TeX",
    "quad": "\u2003",
    "qquad": "\u2003\u2003",
    "noindent": "",
    "nonumber": "",
    "notag": "",
    "par": " ",
    "newline": " ",
    "linebreak": " ",
    "centering": "",
    "small": "",
    "footnotesize": "",
    "normalsize": "",
}
_ESCAPES = {
    ",": "\u2009",
    ";": "\u2005",
    ":": "\u2005",
    "!": "",
    " ": " ",
    "%": "%",
    "&": "&",
    "#": "#",
    "_": "_",
    "$": "$",
    "{": "{",
    "}": "}",
    "\\": " ",
    "/": "",
    "-": "",
}
_ACCENTS = {
    "'": "\u0301",
    "`": "\u0300",
    '"': "\u0308",
    "^": "\u0302",
    "~": "\u0303",
    "=": "\u0304",
    ".": "\u0307",
    "H": "\u030b",
    "v": "\u030c",
    "u": "\u0306",
    "c": "\u0327",
    "k": "\u0328",
}
_TEXT_COMMANDS = (
    set(_WRAPPERS) | set(_REFERENCES) | _DROPPED_WITH_ARGUMENT | set(_SYMBOLS) | {"psfrag"}
)
_COMMAND = re.compile(r"\\([A-Za-z]+)\*?|\\(.)", re.DOTALL)


def tex_text_html(source: str, *, failures: list[str] | None = None) -> Markup:
    r"""``source`` (LaTeX: text with formulas, or one formula) as HTML with MathML formulas.

    Text-mode markup becomes HTML (``\emph{x}`` *x*, ``~`` a no-break space, ``--`` an en dash,
    ``\ref{g}`` the label g ...); each formula becomes inline MathML. A formula latex2mathml
    cannot convert, or a command this does not know, is shown as its LaTeX source in a marked
    ``<code class="tex-source">`` and the reason appended to ``failures``.
    """
    parts: list[str] = []
    for is_math, body in _segments(source):
        parts.append(_math_html(body, failures) if is_math else _text_html(body, failures))
    return Markup("".join(parts))


def claim_html(check: ClaimCheck, *, failures: list[str] | None = None) -> dict[str, Markup]:
    """A checked claim as the report and the page show it: ``quote`` (the paper's words, text
    and MathML), ``claim`` (its formula, MathML) and ``correction`` (MathML, empty when there is
    none)."""
    return {
        "quote": tex_text_html(check.claim.quote, failures=failures),
        "claim": math_or_source(check.claim.latex, display=False, failures=failures),
        "correction": math_or_source(check.correction, display=False, failures=failures)
        if check.correction
        else Markup(""),
    }


# -- splitting text from math --------------------------------------------------------------------


def _segments(source: str) -> list[tuple[bool, str]]:
    """``(is_math, LaTeX)`` pieces of ``source`` in order."""
    segments: list[tuple[bool, str]] = []
    begin, end = _BEGIN.search(source), _END.search(source)
    if end and (begin is None or end.start() < begin.start()):  # starts inside an environment
        segments.append((True, source[: end.start()]))
        source = source[end.end() :]
    elif not _has_math_marks(source) and _only_math(source):
        return [(True, source)]
    text_start = position = 0
    while position < len(source):
        found = _next_opening(source, position)
        if found is None:
            break
        start, body_start, closing = found
        close = _closing(source, body_start, closing)
        segments.append((False, source[text_start:start]))
        segments.append((True, source[body_start:close]))
        position = text_start = min(len(source), close + len(closing))
    segments.append((False, source[text_start:]))
    return [(is_math, body) for is_math, body in segments if body.strip() or (body and not is_math)]


def _has_math_marks(source: str) -> bool:
    delimiter = re.search(r"\\[([]|(?<!\\)\$", source)
    return bool(delimiter or _BEGIN.search(source) or _END.search(source))


def _only_math(source: str) -> bool:
    """Whether ``source`` (no math delimiter in it) can only be a formula: a subscript, a
    superscript, an equals sign or a command text mode does not have."""
    if re.search(r"(?<!\\)[_^=]", source):
        return True
    return any(
        word and word not in _TEXT_COMMANDS and word not in _ACCENTS
        for word, _symbol in _COMMAND.findall(source)
    )


def _next_opening(source: str, position: int) -> tuple[int, int, str] | None:
    """The next formula's opening at or after ``position`` outside any ``{...}`` group (a
    command's argument, converted with it): (its start, its body's start, the text that closes
    it); None when there is none. An escaped ``\\$`` opens nothing."""
    index, depth = position, 0
    while index < len(source):
        char = source[index]
        if char in "{}":
            depth = max(0, depth + (1 if char == "{" else -1))
        elif depth:
            pass
        elif char == "\\":
            environment = _BEGIN.match(source, index)
            if environment:
                return index, environment.end(), f"\\end{{{environment.group(1)}}}"
            if source.startswith(("\\[", "\\("), index):
                return index, index + 2, "\\]" if source[index + 1] == "[" else "\\)"
            index += 2
            continue
        elif char == "$":
            opening = "$$" if source.startswith("$$", index) else "$"
            return index, index + len(opening), opening
        index += 2 if char == "\\" else 1
    return None


def _closing(source: str, start: int, closing: str) -> int:
    """Where ``closing`` ends the formula whose body starts at ``start`` (the end of ``source``
    when the quote stops inside it); an escaped ``\\$`` closes nothing."""
    index = start
    while True:
        found = source.find(closing, index)
        if found < 0:
            return len(source)
        if closing.startswith("$") and _escaped(source, found):
            index = found + 1
            continue
        return found


def _escaped(source: str, index: int) -> bool:
    backslashes = len(source[:index]) - len(source[:index].rstrip("\\"))
    return backslashes % 2 == 1


# -- math ----------------------------------------------------------------------------------------


def _math_html(latex: str, failures: list[str] | None) -> str:
    r"""A formula as inline MathML (in a ``<span class="tex-math">``, which a style sheet lets
    scroll sideways inside a narrow column); the rows of an ``eqnarray``/``align`` body
    (``\\``) each as their own formula, without ``&``, ``\label`` and ``\nonumber``."""
    latex = re.sub(r"\\label\{[^}]*\}|\\nonumber\b|\\notag\b", "", latex)
    if "\\begin{" in latex:  # an environment of its own (a matrix ...): latex2mathml reads it
        rows = [latex]
    else:
        rows = [row.replace("&", "") for row in re.split(r"\\\\", latex) if row.strip()]
    return "<br>".join(
        f'<span class="tex-math">{math_or_source(row.strip(), display=False, failures=failures)}'
        "</span>"
        for row in rows
    )


# -- text ----------------------------------------------------------------------------------------


def _text_html(text: str, failures: list[str] | None) -> str:
    out: list[str] = []
    index = 0
    while index < len(text):
        char = text[index]
        if char == "\\":
            index = _command_html(text, index, out, failures)
            continue
        if char == "{":  # a group in text mode: only its contents show
            group = _group(text, index)
            if group is None:
                index += 1
                continue
            out.append(tex_text_html(group[0], failures=failures))
            index = group[1]
            continue
        if char == "}":
            index += 1
            continue
        if text.startswith("---", index):
            out.append("—")
            index += 3
            continue
        if text.startswith("--", index):
            out.append("–")
            index += 2
            continue
        if text.startswith("``", index) or text.startswith("''", index):
            out.append("“" if char == "`" else "”")
            index += 2
            continue
        if char == "%":  # a comment, to the end of the line
            newline = text.find("\n", index)
            index = len(text) if newline < 0 else newline + 1
            continue
        out.append("\u00a0" if char == "~" else str(esc(char)))
        index += 1
    return re.sub(r"[ \t\r\n]+", " ", "".join(out))


def _command_html(text: str, index: int, out: list[str], failures: list[str] | None) -> int:
    """The HTML of the text-mode command at ``index`` appended to ``out``; where it ends."""
    match = _COMMAND.match(text, index)
    if match is None:  # a lone backslash at the end
        return _unknown(text, index, len(text), out, failures)
    word, symbol = match.group(1), match.group(2)
    end = match.end()
    if word is None:
        if symbol in _ACCENTS:
            return _accent(text, end, _ACCENTS[symbol], out)
        out.append(str(esc(_ESCAPES[symbol])) if symbol in _ESCAPES else str(esc(symbol)))
        return end
    if word in _ACCENTS:  # \H{o}, \v{c} ...
        return _accent(text, end, _ACCENTS[word], out)
    if word in _SYMBOLS:
        out.append(str(esc(_SYMBOLS[word])))
        return _skip_empty_group(text, end)
    if word in _WRAPPERS or word in _REFERENCES or word in _DROPPED_WITH_ARGUMENT:
        argument = _group(text, _skip_options(text, end))
        if argument is None:
            return _unknown(text, index, end, out, failures)
        body, after = argument
        if word in _WRAPPERS:
            before, behind = _WRAPPERS[word]
            out.append(before + tex_text_html(body, failures=failures) + behind)
        elif word in _REFERENCES:
            before, behind = _REFERENCES[word]
            # a figure's label names its number (fig5: Fig. 5), as paper-check's text shows it
            labels = ", ".join(
                re.sub(r"^fig(\d+)$", r"\1", label.strip()) for label in body.split(",")
            )
            out.append(
                f'<span class="tex-ref" title="\\{word}{{{esc(body)}}} in the paper\'s source">'
                f"{esc(before + labels + behind)}</span>"
            )
        return after
    if word == "psfrag":  # \psfrag{tag}[pos][pos]{replacement}: what the figure shows
        tag = _group(text, end)
        replacement = None if tag is None else _group(text, _skip_options(text, tag[1]))
        if replacement is None:
            return _unknown(text, index, end, out, failures)
        out.append(tex_text_html(replacement[0], failures=failures))
        return replacement[1]
    return _unknown(text, index, end, out, failures)


def _unknown(text: str, start: int, end: int, out: list[str], failures: list[str] | None) -> int:
    """A command text mode does not have: MathML when it is a symbol of math (``\\alpha``
    written in text), its source marked as not converted otherwise."""
    source = text[start:end]
    converted = math_or_source(source, display=False, failures=None) if end > start + 1 else None
    if converted is not None and not converted.startswith("<code"):
        out.append(str(converted))
    else:
        if failures is not None:
            failures.append(f"unknown text-mode command {source!r} in: {text[:80]}")
        out.append(f'<code class="tex-source" title="LaTeX not converted">{esc(source)}</code>')
    return end


def _accent(text: str, index: int, mark: str, out: list[str]) -> int:
    group = _group(text, index)
    if group is not None:
        letter, after = group
    else:
        letter, after = text[index : index + 1], index + 1
    out.append(str(esc(unicodedata.normalize("NFC", letter + mark))))
    return after


def _skip_empty_group(text: str, index: int) -> int:
    return index + 2 if text.startswith("{}", index) else index


def _skip_options(text: str, index: int) -> int:
    """Past any ``[...]`` options (and the spaces before them) at ``index``."""
    while True:
        stripped = len(text) - len(text[index:].lstrip())
        if stripped < len(text) and text[stripped : stripped + 1] == "[":
            close = text.find("]", stripped)
            if close < 0:
                return index
            index = close + 1
        else:
            return index


def _group(text: str, index: int) -> tuple[str, int] | None:
    """The ``{...}`` group at ``index`` (spaces before it skipped): its contents and where it
    ends; None when there is none or it is not closed."""
    while index < len(text) and text[index] in " \t\n":
        index += 1
    if index >= len(text) or text[index] != "{":
        return None
    depth = 0
    for position in range(index, len(text)):
        char = text[position]
        if char == "\\":
            continue
        if char == "{" and not _escaped(text, position):
            depth += 1
        elif char == "}" and not _escaped(text, position):
            depth -= 1
            if depth == 0:
                return text[index + 1 : position], position + 1
    return None

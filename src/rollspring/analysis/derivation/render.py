r"""Render sections of steps as plain text, Markdown (``$$…$$`` math) or a LaTeX document.

The LaTeX document needs only ``amsmath`` and ``amssymb`` (Debian's texlive-latex-base), and
is pure ASCII: words are escaped, other characters transliterated.
"""

from __future__ import annotations

import re
import unicodedata
from collections.abc import Sequence

import sympy as sp

from rollspring.analysis.derivation.notation import Entry, width
from rollspring.analysis.derivation.steps import Section, Step, inline, pretty_text

__all__ = [
    "FORMATS",
    "LATEX_PREAMBLE",
    "latex_document",
    "latex_ref",
    "latex_text",
    "latex_words",
    "markdown",
    "text",
    "text_words",
]

#: Output formats.
FORMATS = ("text", "markdown", "latex")


#: The title of the notation table.
NOTATION = "Notation"


def text(
    title: str,
    subtitle: str,
    sections: Sequence[Section],
    *,
    notation: Sequence[Entry] = (),
) -> str:
    """Plain text: the notation table, then each step's number and words, then its equation
    pretty-printed (Unicode, names as a textbook prints them)."""
    lines = [title, "=" * len(title)]
    if subtitle:
        lines += [subtitle]
    if notation:
        lines += ["", NOTATION, "-" * len(NOTATION)]
        columns = max(width(entry.text) for entry in notation)
        for entry in notation:
            value = f" = {entry.value}" if entry.value else ""
            pad = " " * (columns - width(entry.text))
            lines.append(f"  {entry.text}{pad}  {entry.meaning}{value}")
    for section in sections:
        lines += ["", section.title, "-" * len(section.title)]
        if section.cites:
            lines.append(f"({section.cites})")
        if section.note:
            lines.append(text_words(section.note))
        for step in section.steps:
            ref = f"   [{_text_ref(step.ref)}]" if step.ref else ""
            tag = f"({step.tag}) " if step.tag else "* "
            lines.append(f"{tag}{text_words(step.words)}{ref}")
            lines.extend("    " + line for line in _pretty(step).splitlines())
    return "\n".join(lines) + "\n"


def _pretty(step: Step) -> str:
    if step.plain is not None:
        return step.plain
    equation = step.equation
    items = equation if isinstance(equation, list | tuple) else [equation]
    if len(items) > 12:
        items = [*items[:10], sp.Symbol("..."), items[-1]]
    out = []
    for item in items:
        try:
            if isinstance(item, sp.MatrixBase) and max(item.shape) > 8:
                out.append(f"<{item.shape[0]}x{item.shape[1]} matrix>")
            elif isinstance(item, sp.Basic | sp.MatrixBase) and sp.count_ops(item) > 200:
                out.append(inline(item))
            else:
                out.append(pretty_text(item, columns=100))
        except Exception:  # noqa: BLE001 - a printer limitation must not lose the step
            out.append(str(item))
    return "\n".join(out)


def markdown(
    title: str,
    subtitle: str,
    sections: Sequence[Section],
    *,
    notation: Sequence[Entry] = (),
) -> str:
    """Markdown with display math ``$$…$$`` (one per step), the notation as a table."""
    lines = [f"# {_md_escape(title)}"]
    if subtitle:
        lines += ["", _md_escape(subtitle)]
    if notation:
        lines += ["", f"## {NOTATION}", "", "| symbol | meaning | value |", "|---|---|---|"]
        for entry in notation:
            lines.append(
                f"| ${_one_line(entry.latex)}$ | {_md_escape(entry.meaning)} "
                f"| {_md_escape(entry.value)} |"
            )
    for section in sections:
        lines += ["", f"## {_md_escape(section.title)}"]
        if section.cites:
            lines += ["", f"*({_md_escape(section.cites)})*"]
        if section.note:
            lines += ["", _md_escape(text_words(section.note))]
        for step in section.steps:
            ref = f" *({_md_escape(_text_ref(step.ref))})*" if step.ref else ""
            words = _md_escape(text_words(step.words))
            lines += ["", words + ref, "", "$$", _one_line(step.latex), "$$"]
    return "\n".join(lines) + "\n"


#: The preamble of every LaTeX document rollspring writes (article, amsmath; A4-ish text block),
#: up to and including ``\begin{document}``.
LATEX_PREAMBLE = (
    r"\documentclass[11pt]{article}",
    r"\usepackage[T1]{fontenc}",
    r"\usepackage{amsmath}",
    r"\usepackage{amssymb}",
    r"\setcounter{MaxMatrixCols}{20}",
    r"\allowdisplaybreaks",
    r"\setlength{\textwidth}{16cm}",
    r"\setlength{\oddsidemargin}{0cm}",
    r"\setlength{\textheight}{23cm}",
    r"\setlength{\topmargin}{-1cm}",
    r"\setlength{\parindent}{0pt}",
    r"\setlength{\parskip}{4pt}",
    r"\begin{document}",
)


def latex_document(
    title: str,
    subtitle: str,
    sections: Sequence[Section],
    *,
    notation: Sequence[Entry] = (),
) -> str:
    """A complete, compilable LaTeX document (article, amsmath), the notation as a list."""
    body = [*LATEX_PREAMBLE, rf"\section*{{{latex_text(title)}}}"]
    if subtitle:
        body.append(latex_text(subtitle))
    if notation:
        body.append(rf"\subsection*{{{NOTATION}}}")
        for entry in notation:
            value = f" $=$ {latex_text(entry.value)}" if entry.value else ""
            body.append(
                rf"\noindent ${_ascii(entry.latex)}$ \quad {latex_text(entry.meaning)}{value}\par"
            )
    for section in sections:
        body.append(rf"\subsection*{{{latex_text(section.title)}}}")
        if section.cites:
            body.append(rf"{{\small ({latex_text(section.cites)})}}")
        if section.note:
            body.append(latex_words(section.note))
        for step in section.steps:
            ref = rf" \hfill{{\small ({latex_ref(step.ref)})}}" if step.ref else ""
            body.append("")
            body.append(latex_words(step.words) + ref)
            body.append(r"\begin{equation*}")
            body.append(_ascii(step.latex))
            body.append(r"\end{equation*}")
    body.append(r"\end{document}")
    return "\n".join(body) + "\n"


_LATEX_SPECIAL = {
    "\\": r"\textbackslash{}",
    "&": r"\&",
    "%": r"\%",
    "$": r"\$",
    "#": r"\#",
    "_": r"\_",
    "{": r"\{",
    "}": r"\}",
    "~": r"\textasciitilde{}",
    "^": r"\textasciicircum{}",
    "<": r"\textless{}",
    ">": r"\textgreater{}",
}


#: Characters of names in words, as LaTeX math (a combining hat is taken with its letter).
_MATH_CHARACTERS = {
    "P\u0302": r"$\hat P$",
    "X\u0302": r"$\hat X$",
    "±": r"$\pm$",
    "∂": r"$\partial$",
    "δ": r"$\delta$",
    "σ": r"$\sigma$",
    "·": r"$\cdot$",
    "√": r"$\surd$",
    "ℓ": r"$\ell$",
    "ℒ": r"$\mathcal{L}$",
    "ℋ": r"$\mathcal{H}$",
    "φ": r"$\varphi$",
    "θ": r"$\theta$",
    "γ": r"$\gamma$",
    "λ": r"$\lambda$",
    "η": r"$\eta$",
    "α": r"$\alpha$",
    "β": r"$\beta$",
    "Ω": r"$\Omega$",
    "ω": r"$\omega$",
    "Φ": r"$\Phi$",
}
_MATH_PATTERN = re.compile("|".join(re.escape(k) for k in _MATH_CHARACTERS))


_SUB = "₀₁₂₃₄₅₆₇₈₉₍₎"
_SUP = "⁰¹²³⁴⁵⁶⁷⁸⁹"
_ACCENTS = {"\u0302": r"\hat", "\u0307": r"\dot", "\u0308": r"\ddot"}
_GREEK_LETTERS = {k: v.strip("$") for k, v in _MATH_CHARACTERS.items() if len(k) == 1}
#: A name as :func:`~.steps.inline` prints it in words: a letter with an accent (φ̇, P̂),
#: subscript digits (m₁, Ω₍₁₎) or superscript digits (R²).
_UNICODE_NAME = re.compile(
    "(?P<base>[A-Za-z" + "".join(_GREEK_LETTERS) + "])"
    "(?P<accent>[" + "".join(_ACCENTS) + "]?)"
    f"(?P<sub>[{_SUB}]*)(?P<sup>[{_SUP}]*)"
)


def _unicode_name(match: re.Match[str]) -> str | None:
    """A name of :data:`_UNICODE_NAME` as inline LaTeX math (None: plain text)."""
    base, accent, sub, sup = match.group("base", "accent", "sub", "sup")
    if base not in _GREEK_LETTERS and not (accent or sub or sup):
        return None
    math = _GREEK_LETTERS.get(base, base)
    if accent:
        math = f"{_ACCENTS[accent]}{{{math}}}"
    if sub:
        math += "_{" + "".join("0123456789()"[_SUB.index(c)] for c in sub) + "}"
    if sup:
        math += "^{" + "".join(str(_SUP.index(c)) for c in sup) + "}"
    return f"${math}$"


def latex_text(words: str) -> str:
    """Words as LaTeX text: special characters escaped, names as :func:`~.steps.inline`
    prints them (φ̇₁, m₁, R², P̂), Greek letters and the like as math, other non-ASCII
    characters transliterated."""
    out = []
    position = 0
    for match in _UNICODE_NAME.finditer(words):
        math = _unicode_name(match)
        if math is None:
            continue
        out.append(_symbols_text(words[position : match.start()]))
        out.append(math)
        position = match.end()
    out.append(_symbols_text(words[position:]))
    return _joined_math("".join(out))


def _joined_math(latex: str) -> str:
    """Adjacent inline formulas as one (``$R^{2}$$\\cdot$`` -> ``$R^{2} \\cdot$``)."""
    return re.sub(r"(?<!\\)\$\$", " ", latex)


def _symbols_text(words: str) -> str:
    out = []
    position = 0
    for match in _MATH_PATTERN.finditer(words):
        out.append(_escape(words[position : match.start()]))
        out.append(_MATH_CHARACTERS[match.group(0)])
        position = match.end()
    out.append(_escape(words[position:]))
    return "".join(out)


_GREEK = {
    "Omega": r"\Omega",
    "omega": r"\omega",
    "Phi": r"\Phi",
    "phi": r"\varphi",
    "alpha": r"\alpha",
    "beta": r"\beta",
    "gamma": r"\gamma",
    "lambda": r"\lambda",
    "eta": r"\eta",
    "sigma": r"\sigma",
    "delta": r"\delta",
}
#: A name written in ASCII in the words: a Greek name or a letter, with digits (lower-case
#: letters only: "(M12)" is an equation tag), a subscript, primes, a superscript or a star.
_ASCII_NAME = re.compile(
    r"(?<![A-Za-z_])(?P<base>" + "|".join(_GREEK) + r"|[A-Za-z])"
    r"(?P<digits>(?<=[a-z])[0-9]+)?"
    r"(?P<inertia>(?<=I)'(?=_))?"
    r"(?P<sub>_(?:\([A-Za-z0-9]+\)|[A-Za-z0-9]+))?"
    r"(?P<primes>'+)?"
    r"(?P<sup>\^(?:[0-9]+|T|\*|-1)|\*)?"
    r"(?![A-Za-z0-9'])"
    r"|(?<=\))\^(?P<power>[0-9]+|T)"
)


#: Partial derivatives the words write in ASCII, as LaTeX (the same forms as
#: :data:`_DERIVATIVES`).
_LATEX_DERIVATIVES = {
    "dL/dphi_i'": r"\partial\mathcal{L}/\partial\dot\varphi_i",
    "dL/dphi_i": r"\partial\mathcal{L}/\partial\varphi_i",
    "dV/dphi_i": r"\partial V/\partial\varphi_i",
    "dV/dphi": r"\partial V/\partial\varphi",
    "dT/dq_i'": r"\partial T/\partial\dot q_i",
    "dH/dp_i": r"\partial\mathcal{H}/\partial p_i",
    "dH/dq_i": r"\partial\mathcal{H}/\partial q_i",
    "dE/dt": r"\mathrm{d}E/\mathrm{d}t",
    "d/dt": r"\mathrm{d}/\mathrm{d}t",
}
_LATEX_DERIVATIVE = re.compile(
    "|".join(re.escape(k) for k in sorted(_LATEX_DERIVATIVES, key=len, reverse=True))
)


#: Names whose prime is part of the name, not a time derivative: the paper's I' (the inertia
#: about the contact line) and z' (the contact line).
_PRIMED = ("I", "z")


def latex_words(words: str) -> str:
    """:func:`latex_text` with the names the words write in ASCII (``Omega_i^2``,
    ``phi_1'``, ``v0^T``, ``K_11``, ``q'``, ``y*``) as inline math: a student reading the
    document sees Omega_i^2 typeset, not its spelling; a prime is a time derivative (a dot),
    except on I (the paper's I'), and ``dV/dphi`` is the partial derivative it stands for."""
    pieces = []
    position = 0
    for match in _LATEX_DERIVATIVE.finditer(words):
        pieces.append(_latex_names(words[position : match.start()]))
        pieces.append(f"${_LATEX_DERIVATIVES[match.group(0)]}$")
        position = match.end()
    pieces.append(_latex_names(words[position:]))
    return _joined_math("".join(pieces))


def _latex_names(words: str) -> str:
    out = []
    position = 0
    for match in _ASCII_NAME.finditer(words):
        base, digits, sub, primes, sup = match.group("base", "digits", "sub", "primes", "sup")
        if match.group("power"):  # (l - L)^2
            math = "^{" + match.group("power") + "}"
        elif base not in _GREEK and not (digits or sub or primes or sup):
            continue  # a plain letter or word stays text
        else:
            index = ",".join(part for part in (digits, sub[1:] if sub else "") if part)
            math = _GREEK.get(base, base) + (match.group("inertia") or "")
            if primes and base not in _PRIMED and len(primes) <= 2:
                math = (r"\dot{" if len(primes) == 1 else r"\ddot{") + math + "}"
                primes = ""
            if index:
                math += f"_{{{index}}}"
            math += primes or ""
            if sup:
                math += "^{" + sup.lstrip("^") + "}"
        out.append(latex_text(words[position : match.start()]))
        out.append(f"${math}$")
        position = match.end()
    out.append(latex_text(words[position:]))
    return _joined_math("".join(out))


_GREEK_UNICODE = {
    "Omega": "Ω",
    "omega": "ω",
    "Phi": "Φ",
    "phi": "φ",
    "alpha": "α",
    "beta": "β",
    "gamma": "γ",
    "lambda": "λ",
    "eta": "η",
    "sigma": "σ",
    "delta": "δ",
}
_TEXT_SUB = dict(zip("0123456789()aehijklmnoprstuvx", "₀₁₂₃₄₅₆₇₈₉₍₎ₐₑₕᵢⱼₖₗₘₙₒₚᵣₛₜᵤᵥₓ", strict=True))
#: Partial derivatives the words write in ASCII, as the equations print them.
_DERIVATIVES = {
    "dL/dphi_i'": "∂ℒ/∂φ̇ᵢ",
    "dL/dphi_i": "∂ℒ/∂φᵢ",
    "dV/dphi_i": "∂V/∂φᵢ",
    "dV/dphi": "∂V/∂φ",
    "dT/dq_i'": "∂T/∂q̇ᵢ",
    "dH/dp_i": "∂ℋ/∂pᵢ",
    "dH/dq_i": "∂ℋ/∂qᵢ",
}
_TEXT_SUP = dict(zip("0123456789T*-", "⁰¹²³⁴⁵⁶⁷⁸⁹ᵀ*⁻", strict=True))


def text_words(words: str) -> str:
    """The words of a step in plain text with the names they write in ASCII printed as the
    equations print them: ``Omega_i^2`` -> ``Ωᵢ²``, ``phi''`` -> ``φ̈``, ``v0^T`` -> ``v₀ᵀ``,
    ``K_11`` -> ``K₁₁``, ``(l - L)^2`` -> ``(l - L)²``; a prime is a time derivative (a dot)
    except on I (the paper's I', the inertia about the contact line)."""
    for ascii_form, printed in _DERIVATIVES.items():
        words = words.replace(ascii_form, printed)
    out = []
    position = 0
    for match in _ASCII_NAME.finditer(words):
        base, digits, sub, primes, sup = match.group("base", "digits", "sub", "primes", "sup")
        if match.group("power"):
            text = "".join(_TEXT_SUP.get(c, c) for c in match.group("power"))
            if text == match.group("power"):
                continue
            out.append(words[position : match.start()] + text)
            position = match.end()
            continue
        if base not in _GREEK and not (digits or sub or primes or sup):
            continue
        index = (digits or "") + (sub[1:] if sub else "")
        lowered = len(index)
        for position_in_index, c in enumerate(index):
            if c not in _TEXT_SUB:
                lowered = position_in_index
                break
        if lowered == 0 and index:
            continue  # a subscript Unicode cannot lower (L_O): left as written
        name = _GREEK_UNICODE.get(base, base) + ("\u2032" if match.group("inertia") else "")
        if primes and base not in _PRIMED and len(primes) <= 2:
            name += "\u0307" if len(primes) == 1 else "\u0308"
        elif primes:  # the paper's I' and z': a prime (U+2032), as the equations print it
            name += "\u2032" * len(primes) if base in _PRIMED else primes
        # the letters Unicode cannot lower follow on the line, as the equations print them (F₁y)
        name += "".join(_TEXT_SUB[c] for c in index[:lowered]) + index[lowered:]
        if sup:
            name += "".join(_TEXT_SUP.get(c, c) for c in sup.lstrip("^"))
        out.append(words[position : match.start()] + name)
        position = match.end()
    out.append(words[position:])
    return "".join(out)


_LABEL = re.compile(r"\([A-Za-z0-9']+\)")  # an equation label: (w2), (I'1), (M12)


def _text_ref(ref: str) -> str:
    """A reference in plain text: labels as written, the formulas beside them as
    :func:`text_words`."""
    out = []
    position = 0
    for match in _LABEL.finditer(ref):
        out.append(text_words(ref[position : match.start()]) + match.group(0))
        position = match.end()
    out.append(text_words(ref[position:]))
    return "".join(out)


def latex_ref(ref: str) -> str:
    """A step's reference: the paper's and the docs' equation labels (``(w2)``, ``(I'1)``,
    ``(M12)``) as text, the formulas quoted beside them as :func:`latex_words`."""
    out = []
    position = 0
    for match in _LABEL.finditer(ref):
        out.append(latex_words(ref[position : match.start()]))
        out.append(latex_text(match.group(0)))
        position = match.end()
    out.append(latex_words(ref[position:]))
    return "".join(out)


def _escape(words: str) -> str:
    return "".join(_LATEX_SPECIAL.get(char, char) for char in _ascii(words))


def _ascii(value: str) -> str:
    replaced = (
        value.replace("\u2014", "---")
        .replace("\u2013", "--")
        .replace("\u2019", "'")
        .replace("\u2018", "'")
        .replace("\u201c", '"')
        .replace("\u201d", '"')
        .replace("\u2212", "-")
        .replace("\u2032", "'")
        .replace("\u00d7", "x")
        .replace("\u00b7", ".")
    )
    decomposed = unicodedata.normalize("NFKD", replaced)
    kept = "".join(c for c in decomposed if not unicodedata.combining(c))
    return kept.encode("ascii", "replace").decode("ascii")


def _md_escape(words: str) -> str:
    return re.sub(r"([\\`*_\[\]<>|$])", r"\\\1", words)


def _one_line(latex: str) -> str:
    return " ".join(latex.split())

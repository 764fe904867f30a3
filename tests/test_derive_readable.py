"""``derive`` reads like a textbook (issue 25, point 2): the paper's sections cited as the paper
numbers them, no SymPy class names or ASCII derivatives in any format, one notation table per
derivation that names every displayed symbol once, symbols first with the numbers in a final
"with your values" line, and LaTeX that compiles for every preset."""

from __future__ import annotations

import re
import shutil
from pathlib import Path

import pytest

from rollspring.analysis.derivation import Derivation, derive
from rollspring.model import preset_names
from tests.test_paper_check import printed_sections

# -- the paper's sectioning: tests/test_paper_check.py's record, checked there against the LaTeX --


# -- every preset, derived once, in every format -------------------------------------------------

FORMATS = ("text", "markdown", "latex")


@pytest.fixture(scope="module")
def derivations() -> dict[tuple[str, bool], Derivation]:
    """Every preset by every method, symbols first (the default) and with numbers only."""
    out = {}
    for name in preset_names():
        out[name, True] = derive(name)
        out[name, False] = derive(name, symbols=False)
    return out


@pytest.fixture(scope="module")
def rendered(derivations: dict[tuple[str, bool], Derivation]) -> dict[tuple[str, bool, str], str]:
    return {
        (name, symbols, fmt): result.render(fmt)
        for (name, symbols), result in derivations.items()
        for fmt in FORMATS
    }


#: "Sec. 5.2", "Sec. 2, 3 and 5.1", "Secs. 5.4, 5.5"; "App. B and C", "App. B, C" (in LaTeX the
#: words are the same). A docs/physics.md section is the documentation's, not the paper's.
_SECTIONS = re.compile(
    r"(?<!physics\.md )\b(?:Sec|Secs|Section|Sections)\.?\s+"
    r"(?P<list>\d+(?:\.\d+)?(?:(?:,\s*|\s+and\s+)\d+(?:\.\d+)?)*)"
)
_APPENDICES = re.compile(
    r"\b(?:App|Apps|Appendix|Appendices)\.?\s+(?P<list>[A-Z](?:(?:,\s*|\s+and\s+|-)[A-Z])*)\b"
)


def cited_sections(output: str) -> set[str]:
    """Every section and appendix number an output cites."""
    cited: set[str] = set()
    for match in _SECTIONS.finditer(output):
        cited.update(re.findall(r"\d+(?:\.\d+)?", match.group("list")))
    for match in _APPENDICES.finditer(output):
        cited.update(re.findall(r"[A-Z]", match.group("list")))
    return cited


def test_cited_sections_are_read_from_the_words() -> None:
    words = "paper Sec. 2, 3 and 5.1; [docs/physics.md Sec. 1] (paper Sec. 5.6, App. B and C)"
    assert cited_sections(words) == {"2", "3", "5.1", "5.6", "B", "C"}


def test_every_cited_section_exists_in_the_paper(
    rendered: dict[tuple[str, bool, str], str],
) -> None:
    printed = printed_sections()
    assert {"1", "4", "5.1", "5.6", "7", "A", "C"} <= printed
    assert "4.5" not in printed
    cited_anywhere: set[str] = set()
    for key, output in rendered.items():
        cited = cited_sections(output)
        assert cited <= printed, (key, sorted(cited - printed))
        cited_anywhere |= cited
    # the methods cite their sections (5.1 Newton ... 5.6 Hamilton), the forces Sec. 4
    assert {"4", "5.1", "5.2", "5.3", "5.4", "5.6", "A", "B", "C"} <= cited_anywhere


# -- no SymPy class names, no ASCII derivatives ----------------------------------------------------

_CLASS_NAMES = re.compile(
    r"\b(?:LagrangesMethod|KanesMethod|Symbol|Function|Derivative|Integral|Matrix|"
    r"MatrixSymbol|ImmutableMatrix|Rational|Integer|Float|Mul|Add|Pow|Eq|Piecewise|"
    r"dynamicsymbols|UnevaluatedExpr|Named)\b"
)
#: d/dphi, dV/dphi, dL/dq, phi', phi_1'', q' (a derivative or rate spelled in ASCII; the
#: time derivative d/dt, dE/dt is a textbook's notation)
_ASCII_DERIVATIVES = re.compile(
    r"\bd[A-Za-z]*/d(?:phi|q|p|x)|\b(?:phi|q|p|x|Phi)(?:_?[0-9i])?'|φ′|\bd2V/dq2\b"
)


def test_no_class_names_or_ascii_derivatives(rendered: dict[tuple[str, bool, str], str]) -> None:
    for key, output in rendered.items():
        prose = output
        if key[2] == "latex":  # only the words: the math is LaTeX's own (\frac{d}{dt} ...)
            prose = re.sub(r"\\begin\{equation\*\}.*?\\end\{equation\*\}", "", output, flags=re.S)
        assert not _CLASS_NAMES.search(output), (key, _CLASS_NAMES.search(output))
        found = _ASCII_DERIVATIVES.search(prose)
        assert found is None, (key, prose[max(0, found.start() - 80) : found.end() + 40])


@pytest.mark.parametrize(
    "words",
    ["LagrangesMethod: exact", "the Symbol phi", "-dV/dphi", "phi_1'' = 0", "d/dphi", "q' = p"],
)
def test_the_patterns_catch_what_they_are_for(words: str) -> None:
    assert _CLASS_NAMES.search(words) or _ASCII_DERIVATIVES.search(words)


# -- LaTeX compiles for every preset -------------------------------------------------------------


def test_latex_compiles_for_every_preset(
    rendered: dict[tuple[str, bool, str], str], tmp_path: Path
) -> None:
    from tests.test_derive_cli import compile_latex

    assert shutil.which("pdflatex"), "pdflatex is needed (make test installs texlive-latex-base)"
    for name in preset_names():
        directory = tmp_path / name
        directory.mkdir()
        compile_latex(rendered[name, True, "latex"], directory)


# -- one notation table per derivation -------------------------------------------------------------


def test_every_displayed_symbol_has_exactly_one_notation_entry(
    derivations: dict[tuple[str, bool], Derivation],
) -> None:
    """The free symbols of every displayed expression, in their printed form, each have exactly
    one entry, which says what the symbol stands for; a printed name with two meanings would
    show as two entries of one name."""
    from collections import Counter

    from rollspring.analysis.derivation.notation import UNDESCRIBED, displayed_symbols, printed

    for key, result in derivations.items():
        table = result.notation
        counts = Counter(entry.text for entry in table)
        assert all(n == 1 for n in counts.values()), (key, counts.most_common(3))
        shown = {printed(symbol) for symbol in displayed_symbols(result.sections)}
        assert shown, key
        missing = shown - set(counts)
        assert not missing, (key, sorted(missing))
        assert not [e.text for e in table if e.meaning == UNDESCRIBED], key
        if result.symbolic.springs:  # the rest length the words use is defined
            assert any(
                entry.text.startswith("L") and "rest length" in entry.meaning for entry in table
            )
        names = {entry.text: entry.meaning for entry in table}
        if "K" in names:  # K is the stiffness matrix only: the contact line is z'
            assert names["K"].startswith("stiffness matrix"), key
            text = result.to_text()
            assert "contact point K" not in text and "about K" not in text, key


def test_the_notation_is_rendered_in_every_format(
    derivations: dict[tuple[str, bool], Derivation],
) -> None:
    result = derivations["hoop-cylinder", True]
    text, markdown, latex = result.to_text(), result.to_markdown(), result.to_latex()
    assert "\nNotation\n--------\n" in text and "## Notation" in markdown
    assert r"\subsection*{Notation}" in latex
    assert text.index("Notation") < text.index("(S1)")
    for entry in result.notation:
        assert f"  {entry.text} " in text
    # the paper's notation: I' for the inertia about the contact line, its value as a symbol
    names = {entry.text: entry for entry in result.notation}
    assert "I′₁" in names and "J₁" not in names and "J₁" not in text
    assert names["k"].value == "100 N/m" and names["m₁"].value == "1 kg"
    assert names["L"].meaning.endswith("so L = ℓ (m)")


# -- symbols first, the numbers at the end ---------------------------------------------------------


def test_symbols_are_the_default_and_numbers_come_last(
    derivations: dict[tuple[str, bool], Derivation],
) -> None:
    """By default the parameters are symbols (the paper's m₁, R, k, I'); the system's numbers
    enter each method only in its last step, "with your values", in decimals: for Fig. 2 of the
    paper (k = 100 N/m, m₁ = m₂ = 1 kg) Ω² = k/(2m₁) + 2k/(3m₂) = 50 + 200/3 s⁻²."""
    import math

    import sympy as sp

    result = derivations["hoop-cylinder", True]
    assert result.symbolic.symbolic and "parameters as symbols" in result.subtitle
    omega2 = 50 + 200 / 3
    for name, method in result.methods.items():
        last = method.section.steps[-1]
        assert last.how is not None and last.how.op == "with your values", name
        assert last.words.startswith("With your values"), name
        values = {str(e.lhs): float(e.rhs) for e in last.equations}
        assert math.isclose(values["Omega^2"], omega2, rel_tol=5e-4), name
        assert math.isclose(values["Omega"], math.sqrt(omega2), rel_tol=5e-4), name
        for step in method.section.steps[:-1]:  # no number of the system before it
            for item in step.equations:
                if isinstance(item, sp.Basic):
                    assert not item.atoms(sp.Float), (name, step.tag, item)
    text = result.to_text()
    assert "φ̈₁/50" not in text and "981/100" not in text
    assert "N₁ = g⋅m₁ - F₁y" in text or "N₁ = -F₁y + g⋅m₁" in text
    # with numbers throughout (--numbers), the same last step gives the decimals
    numbers = derivations["hoop-cylinder", False]
    assert not numbers.symbolic.symbolic
    last = numbers.methods["newton"].section.steps[-1]
    assert last.how is not None and last.how.op == "with your values"


def test_an_off_centre_system_shows_decimals(derivations) -> None:
    """Three bodies: the normal modes' squared frequencies are long surds; each method ends
    with their decimals."""
    for symbols in (True, False):
        result = derivations["three-bodies", symbols]
        for method in result.methods.values():
            if not method.applies:
                continue
            last = method.section.steps[-1]
            assert last.how is not None and last.how.op == "with your values"
            assert len(last.equations) == 4  # two oscillating modes: Ω² and Ω of each

"""Names print as a textbook would: no SymPy artefacts (``y_1__*`` for a starred name, ``k_1'``
from renaming, ``F_{1x}`` printed raw, ``_{`` nesting) in any displayed symbol, in the plain
text, the Markdown or the LaTeX of a derivation."""

from __future__ import annotations

import re
from collections.abc import Iterator

import pytest
import sympy as sp

from rollspring.analysis.derivation import Derivation, derive
from rollspring.analysis.derivation.steps import Named, pretty_name, pretty_text
from rollspring.analysis.paper import paper_system
from rollspring.model import load_system, preset_names
from tests.test_derive_steps import pulled_slider_pair, wall_chain

#: A textbook name: a base (Latin letters, a Greek name, with dot/ddot/hat), an optional
#: subscript of letters, digits and commas, an optional superscript of digits or *.
NAME = re.compile(
    r"(?P<base>[A-Za-z]+)(_(?P<sub>[A-Za-z0-9,]+))?(\^(?P<sup>[0-9*]+))?"
    r"|(?P<star>[A-Za-z]+\^\*_[A-Za-z0-9,]+)"
)
ARTEFACTS = ("__", "'", "{", "}", "_", "^", "\\")


def systems() -> Iterator[tuple[str, object, bool]]:
    for name in preset_names():
        yield name, load_system(name), True
    yield "hoop-cylinder (numbers)", load_system("hoop-cylinder"), False
    yield "paper Fig. 3", paper_system("fig3"), True
    yield "wall chain", wall_chain(), True
    yield "slider and cylinder", pulled_slider_pair(), True


@pytest.fixture(scope="module")
def derivations() -> list[tuple[str, Derivation]]:
    return [(label, derive(system, symbols=symbols)) for label, system, symbols in systems()]


def displayed_symbols(derivation: Derivation) -> Iterator[tuple[str, sp.Basic]]:
    for section in derivation.sections:
        for step in section.steps:
            for item in step.equations:
                if not isinstance(item, sp.Basic | sp.MatrixBase):
                    continue
                for atom in sp.sympify(item).atoms(sp.Symbol, sp.MatrixSymbol):
                    yield f"{step.tag or section.title}", atom


def test_no_displayed_name_carries_a_sympy_artefact(derivations) -> None:
    for label, derivation in derivations:
        for where, symbol in displayed_symbols(derivation):
            if isinstance(symbol, Named):
                text = symbol.text
            else:
                name = str(symbol.name)
                assert NAME.fullmatch(name), f"{label} {where}: the name {name!r}"
                text = pretty_name(name)
            for artefact in ARTEFACTS:
                assert artefact not in text, f"{label} {where}: {symbol.name!r} prints {text!r}"


def test_the_text_markdown_and_latex_carry_no_artefacts(derivations) -> None:
    for label, derivation in derivations:
        text = derivation.to_text()
        equations = "\n".join(
            line for line in text.splitlines() if line.startswith("    ")
        )  # the pretty-printed equations (the words may quote names)
        # an underscore or caret between name characters (y_1__*, F_1y, k^2), braces, primes;
        # a square root's bar is a run of underscores between spaces and strokes
        found = re.search(r"[A-Za-z0-9][_^]+[A-Za-z0-9*{]|_\{|\^\{|'", equations)
        assert found is None, f"{label}: {found.group(0) if found else ''!r} in the text"
        latex = derivation.to_latex()
        assert not re.search(r"_\{[^{}]*'", latex), f"{label}: a prime inside a subscript"
        assert "__" not in latex and r"\_\{" not in latex


def test_names_print_as_a_textbook_does() -> None:
    assert pretty_name("y^*_1") == "y₁*"
    assert pretty_name("Omega_1^2") == "Ω₁²"
    assert pretty_name("ell_2") == "ℓ₂"
    assert pretty_name("phiddot_1") == "φ̈₁"
    assert pretty_name("F_1x") == "F₁ₓ"
    assert pretty_name("r_1,2") == "r₁,₂"
    assert pretty_text(sp.Symbol("y^*_1") + sp.Symbol("ell")) in ("y₁* + ℓ", "ℓ + y₁*")
    assert sp.latex(sp.Symbol("y^*_1")) == "y^{*}_{1}"

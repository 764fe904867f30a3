"""Fixes from a review of ``derive`` by a reader who did not write it (issue 13.3): what a
student stumbled on in the paper's system, a wall chain and three bodies stays fixed."""

from __future__ import annotations

import re

import pytest
import sympy as sp

from rollspring.analysis.derivation import Derivation, derive
from rollspring.analysis.derivation.steps import Step, inline, pretty_text
from rollspring.model import load_system

CASES = {
    "hoop-cylinder": ("hoop-cylinder", False),
    "hoop-cylinder (symbols)": ("hoop-cylinder", True),
    "wall-hoop-cylinder": ("wall-hoop-cylinder", False),
    "three-bodies": ("three-bodies", False),
}


@pytest.fixture(scope="module")
def derivations() -> dict[str, Derivation]:
    return {
        label: derive(load_system(name), symbols=symbols)
        for label, (name, symbols) in CASES.items()
    }


def steps(derivation: Derivation) -> dict[str, Step]:
    return {s.tag: s for section in derivation.sections for s in section.steps if s.tag}


def test_the_equation_of_motion_reads_as_the_papers(derivations) -> None:
    """q'' + Omega^2 q = 0 with the second derivative first, Omega^2 = k/(2m1) + 2k/(3m2) in
    the paper's order (QQQ1), F = k(R phi2 - R phi1) with its positive term first, and the
    friction of App. A as F(1 - ...)."""
    text = derivations["hoop-cylinder"].to_text()
    assert re.search(r"\n    φ̈₁ \+ ", text)
    assert "F = 10⋅(φ₂ - φ₁)" in text
    symbolic = steps(derivations["hoop-cylinder (symbols)"])
    assert inline(symbolic["N12"].equation.rhs) == "k/(2·m₁) + 2·k/(3·m₂)"
    assert inline(symbolic["N1"].equation[0].rhs) == "R·k·(φ₂ - φ₁)"
    assert "1 - " in pretty_text(symbolic["A5"].equation)
    hamiltonian = inline(symbolic["H3"].equation.rhs)
    assert hamiltonian.startswith("p₁²/(2·m₁) + p₂²/(2·m₂) + ")  # the kinetic part first


def test_a_scaled_sum_says_so_and_names_its_factor(derivations) -> None:
    """The weighted sum of the equations is displayed freed of a constant factor; the words
    say which, and the momentum is that factor times the left side."""
    numbers = steps(derivations["hoop-cylinder"])
    assert "shown multiplied by 200" in numbers["N4"].words
    assert "P̂ = v0^T M q' = 1/200 times the left side" in numbers["N5"].words
    assert "shown multiplied by 200" in numbers["E2"].words
    symbols = steps(derivations["hoop-cylinder (symbols)"])
    assert "divided by its common factor R²" in symbols["N4"].words
    assert "proportional to sum I'_i v0_i phi_i'" in symbols["H12"].words
    assert "P̂ is the total" not in symbols["H12"].words


def test_no_division_by_one_and_numbers_multiply(derivations) -> None:
    for derivation in derivations.values():
        for step in steps(derivation).values():
            assert not re.search(r"by 1 |by 1/\d", step.words), (step.tag, step.words)
    numbers = steps(derivations["hoop-cylinder"])
    assert numbers["N11"].words.startswith("Multiplying (N10) by 50 ")
    assert numbers["H16"].words.startswith("Bringing every term of (H15) to the left")


def test_normal_mode_frequencies_are_not_the_subsystem_frequencies(derivations) -> None:
    """The paper's Omega_1, Omega_2 are the clamped subsystems' frequencies: the normal modes'
    roots are Omega_(n), and the subsystem names appear only in their own section."""
    for label, derivation in derivations.items():
        for tag, step in steps(derivation).items():
            for item in step.equations:
                if isinstance(item, sp.Eq) and isinstance(item.lhs, sp.Symbol):
                    name = item.lhs.name
                    if re.fullmatch(r"Omega_\d+\^2", name):
                        assert tag.startswith("F"), (label, tag, name)
    text = derivations["wall-hoop-cylinder"].to_text()
    equations = "\n".join(line for line in text.splitlines() if line.startswith("    "))
    assert "Ω₍₁₎² = " in equations and "Ω₁²" not in equations
    assert "omega" not in text and "ω" not in text


def test_the_sum_of_angular_momenta_counts_the_bodies(derivations) -> None:
    three = steps(derivations["three-bodies"])
    assert "L_1 + L_2 + L_3" in three["N5"].words
    two = steps(derivations["hoop-cylinder"])
    assert "the paper's L_1 + L_2)" in two["N5"].words


def test_words_fit_the_system(derivations) -> None:
    numbers = steps(derivations["hoop-cylinder"])
    assert "slider" not in numbers["E13"].words
    assert "hoop: hoop" not in numbers["S1"].words
    assert "(paper Sec. 5.6" in numbers["F10"].words and "(F4)" in numbers["F10"].words
    # the shares of the spring's parts (L16) are derived, then named: Omega_i^2 = K_ii/I'_i
    assert "Omega_i^2 = K_ii/I'_i" in numbers["L16"].words  # defined where it is used
    assert numbers["L15"].words.startswith("The spring's deformation to first order")
    assert numbers["H10"].ref == "paper (h) with p1' = m1 q1''"
    assert "zero mode(s)" not in derivations["three-bodies"].to_text()


def test_the_words_print_names_as_the_equations_do(derivations) -> None:
    """In plain text the words write Ω², φ̈, v₀ᵀ, ∂ℒ/∂φ̇ᵢ as the equations print them; the
    paper's I' keeps its prime (it is not a rate) and equation labels stay as written."""
    from rollspring.analysis.derivation.render import text_words

    assert text_words("J phi'' = torque, R phi'^2, v0^T M q', Omega_(n)^2, K_11/J_1") == (
        "J φ̈ = torque, R φ̇², v₀ᵀ M q̇, Ω₍ₙ₎², K₁₁/J₁"
    )
    assert text_words("the paper's I'; body i's (l - L)^2; d/dt(dL/dphi_i')") == (
        "the paper's I′; body i's (l - L)²; d/dt(∂ℒ/∂φ̇ᵢ)"
    )
    text = derivations["hoop-cylinder"].to_text()
    assert "Omega" not in text.split("Cross-check")[0].replace("Omega_f", "")
    assert "[paper (w2), (w22); (M7)]" in text


def test_powers_of_a_squared_name_print_as_one_power(derivations) -> None:
    text = derivations["hoop-cylinder"].to_text()
    assert "3⋅Ω⁴" in text
    latex = derivations["hoop-cylinder"].to_latex()
    assert r"\Omega^{4}" in latex and r"\Omega^{2}^{2}" not in latex
    assert inline(sp.Symbol("R") ** 10) == "R¹⁰"


def test_names_in_the_words_are_typeset_in_latex(derivations) -> None:
    """In the LaTeX document the words' names are math: Omega^2 typeset, a rate keeps its dot
    (it was transliterated to a bare phi), R² its exponent; equation tags such as (M12) and
    possessives (body i's) stay text."""
    from rollspring.analysis.derivation.render import latex_text, latex_words

    assert (
        latex_text("by φ̇₁ and 2·R²·m₁") == r"by $\dot{\varphi}_{1}$ and 2$\cdot R^{2} \cdot m_{1}$"
    )
    words = latex_words("det(K - Omega^2 M), v0^T M q', body i's K_11/J_1 (M12), Omega_(n)")
    # a prime is a time derivative, typeset as a dot (the paper's I' keeps its prime)
    assert r"$\Omega^{2}$" in words and r"$v_{0}^{T}$" in words and r"$\dot{q}$" in words
    assert "$I'_{1}$" in latex_words("I'_1")
    assert "body i's" in words and r"$K_{11}$" in words and "(M12)" in words
    assert r"$\Omega_{(n)}$" in words
    latex = derivations["hoop-cylinder"].to_latex()
    assert r"\textasciicircum" not in latex
    assert r"Dividing (E6) by $\dot{\varphi}_{1}$" in latex

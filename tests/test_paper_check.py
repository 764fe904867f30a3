"""``rollspring paper-check``: every quantitative claim of the paper, with its computed verdict.

Each expected verdict below is justified from the paper (G. Nyitray, arXiv 2508.01379; labels
are its LaTeX labels) and docs/physics.md, independently of the code: the test fails if the
derivation engine reaches a different verdict.
"""

from __future__ import annotations

import json

import pytest
import sympy as sp
from typer.testing import CliRunner

from rollspring.analysis.paper_check import (
    HOLDS_ONLY_IF,
    VERDICTS,
    VERIFIED,
    WRONG,
    Claim,
    Derived,
    check_claim,
    check_paper,
    paper_claims,
)
from rollspring.cli import app
from rollspring.cli import paper_check as cli_paper_check

V, H, W = VERIFIED, HOLDS_ONLY_IF, WRONG

EXPECTED = {
    # Sec. 2, Fig. 1: U = k/2 (x2 - x1)^2 gives F_i = -dU/dx_i, i.e. (f1), (f2).
    "fig1-equations": V,
    "fig1-potential": V,
    # the total momentum is conserved; it is zero (CM at rest) only for a start from rest
    # (the paper: "the solution corresponding to the initial conditions").
    "fig1-cm-at-rest": H,
    # Steiner: I' = I + mR^2 = (1 + gamma) m R^2 (M4): 2 m1 R^2, 1.5 m2 R^2.
    "steiner": V,
    # J_i phi_i'' = Q_i (M7) with Q_1 = k R (R phi2 - R phi1) for a centre spring.
    "fig2-equations": V,
    # sum J_i phidot_i is the conserved pseudo-momentum (M11, equal radii); it is zero only
    # for a release from rest (review notes: Sec. 2 (rel1), (g)).
    "angular-momentum": H,
    # mode phi ~ (b1/J1, b2/J2) with b = (-R, R) (M15): opposite signs.
    "phase-opposition": V,
    # in the mode xdot2/xdot1 = -J1/J2 = -4 m1/(3 m2): the CM moves (docs/physics.md 7.1).
    "cm-moves": V,
    # X-hat weights are (1 + gamma_i) m_i (M11); I'_i = J_i only for equal radii (review notes).
    "stationary-point": H,
    # two hoops / two cylinders: equal gamma, X-hat is the CM (M11).
    "two-hoops": V,
    "two-cylinders": V,
    # f1/f2 = -(1 - lambda1)/(1 - lambda2) = -3/2 signed (M17): 3/2 only as magnitudes.
    "friction-ratio": H,
    # sum f vanishes iff lambda1 = lambda2, i.e. equal gamma, not equal I (review notes,
    # "same moment of inertia" -> same inertia factor): a hoop and a cylinder with I1 = I2
    # still need sum f != 0.
    "same-inertia": W,
    # (M10): f = -F_x (1 - lambda), lambda = y/((1 + gamma) R): the paper's (fric) with f
    # counted against F, exact (review notes: "exact at every instant").
    "fric": V,
    "fric-coupled": V,
    # y* = (1 + gamma) R: 2R (hoop), 1.5R (cylinder) (docs/physics.md 5).
    "zero-friction-heights": V,
    # a horizontal spring needs h1 + 2R1 = 1.5 R2: R1 = R2/2 needs the hoop's track raised by
    # R1 (centres level); on one floor R1 = 0.75 R2 (review notes; README table).
    "fig3-geometry": H,
    # (a), (b) are the linearised (M7) with lever arms 2R1, 1.5R2 (M15).
    "fig3-equations": V,
    # b = (-2R1, 1.5R2): m1 R1 phi1'' + m2 R2 phi2'' = -k(b.phi)(2R1 m1 R1/J1 - 1.5R2 m2 R2/J2)
    # = 0 (J1 = 2 m1 R1^2, J2 = 1.5 m2 R2^2).
    "fig3-cm-acceleration": V,
    # the conserved total momentum is zero only for a start from rest (and the CM is at rest
    # only to first order, docs/physics.md 8).
    "fig3-cm-at-rest": H,
    # friction vanishes only to first order: O(phi^3) for a horizontal spring (docs/physics.md 8,
    # review notes).
    "fig3-no-friction": H,
    # no external torque to first order: L about a fixed point is conserved, so "L is not a
    # constant of motion" is wrong (review notes: Sec. 3 (end)).
    "fig3-angular-momentum": W,
    # phi1'' + Omega^2 phi1 = 0 only without the zero-mode part (uniform motion of X-hat and an
    # offset); review notes (QQ2).
    "qq2": H,
    # integrating twice needs both integration constants zero (start from rest, origin at X-hat)
    "phi-relation": H,
    # eq. (QQ1)/(ep): k/(2m1)(1 + 4m1/(3m2)) = k/(2m1) + 2k/(3m2) = Omega^2 (M15).
    "qq1": V,
    "omega2-fig2": V,
    # largest kinetic energy equals the largest potential energy k A^2/2.
    "energy": V,
    # (nu) has a minus sign where (rel1) has a plus: it holds for magnitudes (review notes).
    "nu": H,
    # v_i = Omega A_i with A1/A = 3m2/(4m1 + 3m2) (docs/physics.md 7.1, README table).
    "speeds": V,
    "omega-from-speeds": V,
    "amplitudes": V,
    "amplitude-sum": V,
    "amplitudes-equal-masses": V,
    # the deformation is epsilon2 - epsilon1 with the paper's epsilon_1 = x_1 - X-hat: the
    # Lagrangian and (al), (be), (ga), (de) hold only with epsilon_1 = X-hat - x_1 (review
    # notes, Sec. 4.3).
    "lagrangian": H,
    "lagrange-equations": H,
    "ga": H,
    "de": H,
    # k_i = k Omega^2/Omega_i^2 (docs/physics.md 7.1), 1/k = 1/k1 + 1/k2.
    "spring-parts": V,
    "k1-k2": V,
    "k-equal-masses": V,
    "k-equal": V,
    # m1 = m2: X-hat = 1.5/3.5 l = 3l/7; a spring part of length 3l/7 has stiffness 7k/3 = k1.
    "xhat-three-sevenths": V,
    # (M15): Omega^2 = Omega_1^2 + Omega_2^2 for two bodies and one spring.
    "sum-rule": V,
    # with walls or chains only the trace identity holds (docs/physics.md 7.2, review notes 4.4).
    "sum-rule-general": H,
    # App. B: alpha_i = J_i, beta_i = k R^2, Omega_i^2 = k b_i^2/J_i (M15).
    "alpha-beta": V,
    "omega1-omega2": V,
    # Fig. 3 (centres level, horizontal spring): Omega^2 = 2k/m1 + 3k/(2m2) (docs/physics.md 7.1).
    "omega2-fig3": V,
    "omega3-omega4": V,
    # (l), (k), (h), (k0), (k02): the same sign convention as Sec. 4.3; in one orientation
    # c = (-1/sqrt2, +sqrt(2/3)) (docs/physics.md 7.1, review notes 4.4 (k), (k0)).
    "lagrangian-hamilton": H,
    "hamiltonian": H,
    "hamilton-equations": H,
    "canonical-ratio": H,
    "potential-fig2": H,
    "potential-fig3": H,
    # q_i = sqrt(J_i/m_i) phi_i: q1 = sqrt2 R phi1, q2 = sqrt(3/2) R phi2 (docs/physics.md 7.1).
    "canonical-coordinates": V,
    # |c_i| = Omega_i/sqrt(k/m_i) (docs/physics.md 7.1).
    "potential-coefficients": V,
    # -pdot1 = m1 Omega^2 q1 in the mode: k(1/2 + 2m1/(3m2)) q1.
    "hamilton-motion": V,
    # App. A: f1 = (k1/2) R phi1 is right; f2 = (k2/2) R phi2 is not (k2/3: review notes), the
    # final k(3m2 + 4m1)/(12 m1) R phi2 is right.
    "friction-hoop": V,
    "friction-cylinder-k2": W,
    "friction-cylinder": V,
    # (a1), (a2): J phi'' = F y about the contact line (M7).
    "pull-equations": V,
    # y = 0: f = F (lambda = 0), a = 0.
    "pull-at-floor": V,
    # cylinder at y = 2R: f = F(1 - 2R/(1.5R)) = -F/3.
    "fig5-cylinder": V,
    # Fig. 5 labels f1 (cylinder), f2 (hoop) are swapped against the rest of the paper
    # (review notes).
    "fig5-labels": W,
}


@pytest.fixture(scope="module")
def checks():
    return {c.claim.key: c for c in check_paper()}


def test_every_claim_of_the_issue_is_in_the_list(checks) -> None:
    # issue 4, item 4: Omega^2 of Figs. 2 and 3, v1, v2, A1, A2, k1, k2, f1/f2, X-hat, f(y),
    # the Hamiltonian's canonical coordinates, Omega_1..4, the Fig. 3 geometry R1 = R2/2
    required = {
        "omega2-fig2": r"\Omega^2",
        "omega2-fig3": r"\Omega_{\bcancel{f}}^2",
        "speeds": "v_1",
        "amplitudes": "A_1",
        "k1-k2": "k_1",
        "friction-ratio": r"\frac{f_1}{f_2}",
        "stationary-point": r"\hat{X}",
        "fric": "f(y)",
        "canonical-coordinates": r"q_1=\sqrt{2}R\phi_1",
        "omega1-omega2": r"\Omega_1",
        "omega3-omega4": r"\Omega_{3}",
        "fig3-geometry": "R_1=R_2/2",
    }
    for key, fragment in required.items():
        assert key in checks, key
        assert fragment in checks[key].claim.latex.replace(" ", ""), key
    assert "v_2" in checks["speeds"].claim.latex and "A_2" in checks["amplitudes"].claim.latex
    assert "k_2" in checks["k1-k2"].claim.latex
    assert r"\Omega_2" in checks["omega1-omega2"].claim.latex
    assert r"\Omega_4" in checks["omega3-omega4"].claim.latex
    assert set(checks) == set(EXPECTED), "every claim has an expected verdict, and only those"


@pytest.mark.parametrize("key", sorted(EXPECTED))
def test_verdict(checks, key: str) -> None:
    check = checks[key]
    assert check.verdict == EXPECTED[key], (key, check.reason, check.correction)
    if check.verdict == VERIFIED:
        assert check.correction is None
    else:
        assert check.correction, key  # a corrected expression in LaTeX
    if check.verdict == HOLDS_ONLY_IF:
        assert check.reason.startswith("holds only if ")
    assert check.reason


def test_corrections_are_the_physics_md_expressions(checks) -> None:
    m1, m2, R2 = sp.symbols("m_1 m_2 R_2", positive=True)
    # (M17): signed friction ratio -3/2
    assert checks["friction-ratio"].derived == sp.Rational(-3, 2)
    assert "-" in checks["friction-ratio"].correction
    # one floor: 2 R1 = 1.5 R2
    assert checks["fig3-geometry"].derived == sp.Rational(3, 4) * R2
    # (M11): X-hat weights (1 + gamma) m for any radii
    weights = checks["stationary-point"].derived
    assert sp.simplify(weights[0] - 4 * m1 / (4 * m1 + 3 * m2)) == 0
    assert sp.simplify(weights[1] - 3 * m2 / (4 * m1 + 3 * m2)) == 0
    # the total angular momentum of Fig. 3 is conserved
    assert checks["fig3-angular-momentum"].derived == 0
    assert checks["fig3-angular-momentum"].correction == r"\dot L_O=0"
    # App. A: f2 = (k2/3) R phi2 with k2 = k(3m2 + 4m1)/(4m1)
    k, R = sp.symbols("k R", positive=True)
    phi2 = sp.Symbol("phi_2", real=True)
    k2 = k * (3 * m2 + 4 * m1) / (4 * m1)
    assert sp.simplify(checks["friction-cylinder-k2"].derived - k2 / 3 * R * phi2) == 0
    # Fig. 3 friction is O(a^3): no linear or quadratic term
    a = sp.Symbol("a", real=True)
    for f in checks["fig3-no-friction"].derived:
        poly = sp.Poly(sp.expand(f), a)
        assert poly.degree() == 3 and poly.coeff_monomial(a) == 0
        assert poly.coeff_monomial(a**2) == 0


def test_the_verdict_is_computed_not_typed_in() -> None:
    k, m1 = sp.symbols("k m_1", positive=True)
    c = sp.Symbol("c", positive=True)

    def claim(paper, derived: Derived) -> Claim:
        return Claim(
            "test", "nowhere", "a test claim", "x", "x", paper, "fig2", lambda bench: derived
        )

    right = Derived(k / (2 * m1), "by hand")
    assert check_claim(claim(k / (2 * m1), right)).verdict == VERIFIED
    assert check_claim(claim(k / m1, right)).verdict == WRONG
    assert check_claim(claim(k / m1, right)).correction == r"x = \frac{k}{2 m_{1}}"
    conditional = Derived(c * k / m1, "by hand", condition="c = 1", value_if=k / m1)
    assert check_claim(claim(k / m1, conditional)).verdict == HOLDS_ONLY_IF
    assert check_claim(claim(2 * k / m1, conditional)).verdict == WRONG
    # sequences compare entry by entry
    pair = Derived((k, m1), "by hand")
    assert check_claim(claim((k, m1), pair)).verdict == VERIFIED
    assert check_claim(claim((m1, k), pair)).verdict == WRONG
    # an identity that needs simplification (radicals) is still recognised
    root = Derived(sp.sqrt(k / (2 * m1)), "by hand")
    assert check_claim(claim(sp.sqrt(k) / sp.sqrt(2 * m1), root)).verdict == VERIFIED


def test_every_claim_compares_in_the_engines_symbols() -> None:
    # a paper expression in symbols the engine does not use would never be verified by accident,
    # but would never verify either: every claim's symbols are known names
    known = {
        "m",
        "m_1",
        "m_2",
        "R",
        "R_1",
        "R_2",
        "k",
        "k_1",
        "k_2",
        "gamma",
        "y",
        "F",
        "I",
        "phi",
        "phi_1",
        "phi_2",
        "phidot_1",
        "phidot_2",
        "phiddot",
        "phiddot_1",
        "phiddot_2",
        "x_1",
        "x_2",
        "A",
        "Phidot_1",
        "Phidot_2",
        "q_1",
        "q_2",
        "q_3",
        "q_4",
        "p_1",
        "p_2",
        "F_1x",
        "F_2x",
        "l",
    }
    for claim in paper_claims():
        values = claim.paper if isinstance(claim.paper, tuple) else (claim.paper,)
        names = {s.name for v in values for s in sp.sympify(v).free_symbols}
        assert names <= known, (claim.key, names - known)


runner = CliRunner()


def test_cli_json_is_a_list_of_the_documented_records(checks) -> None:
    result = runner.invoke(app, ["paper-check", "--json"])
    assert result.exit_code == 0, result.output
    data = json.loads(result.stdout)
    assert isinstance(data, list) and len(data) == len(EXPECTED)
    for record in data:
        assert set(record) == {"location", "claim", "verdict", "correction", "reason"}
        assert record["verdict"] in VERDICTS
        assert isinstance(record["claim"], str) and record["claim"]
        assert record["correction"] is None or isinstance(record["correction"], str)
        assert (record["correction"] is None) == (record["verdict"] == VERIFIED)
        assert isinstance(record["reason"], str) and record["reason"]
    by_claim = {(r["location"], r["claim"]): r["verdict"] for r in data}
    for check in checks.values():
        assert by_claim[(check.claim.location, check.claim.latex)] == check.verdict


def test_cli_text_table_marks_and_counts() -> None:
    result = runner.invoke(app, ["paper-check"])
    assert result.exit_code == 0, result.output
    counts = {v: sum(1 for e in EXPECTED.values() if e == v) for v in VERDICTS}
    assert "✔" in result.stdout and "✘" in result.stdout and "⚠" in result.stdout
    assert (
        f"{len(EXPECTED)} claims: {counts[VERIFIED]} verified, {counts[HOLDS_ONLY_IF]} hold "
        f"only under a condition, {counts[WRONG]} wrong"
    ) in result.stdout
    assert "R₁=R₂/2" in result.stdout  # the LaTeX shown as readable text
    assert "correct: f₁/f₂ = - 3/2" in result.stdout


def test_cli_markdown_table() -> None:
    result = runner.invoke(app, ["paper-check", "--format", "markdown"])
    assert result.exit_code == 0, result.output
    rows = [line for line in result.stdout.splitlines() if line.startswith(("| ✔", "| ✘", "| ⚠"))]
    assert len(rows) == len(EXPECTED)
    assert all(line.count(" | ") == 5 for line in rows)  # 6 cells, no stray pipes
    assert r"$\frac{f_1}{f_2}=\frac{3}{2}" in result.stdout


def test_cli_unknown_format_is_one_line_and_exit_2() -> None:
    result = runner.invoke(app, ["paper-check", "--format", "html"])
    assert result.exit_code == 2
    assert result.stderr.strip() == (
        "error: --format: unknown format 'html' (formats: text, markdown)"
    )


def test_cli_verdict_names_are_the_librarys() -> None:
    # the CLI module keeps its own copies so that importing it does not import SymPy
    assert (cli_paper_check.VERIFIED, cli_paper_check.WRONG, cli_paper_check.HOLDS_ONLY_IF) == (
        VERIFIED,
        WRONG,
        HOLDS_ONLY_IF,
    )


def test_plain_text_keeps_a_backslash_that_starts_no_command() -> None:
    # a trailing backslash (or one before a newline) matches no command: kept, not a crash
    assert cli_paper_check.plain("x\\") == "x\\"
    assert cli_paper_check.plain(r"\frac{1}{2}") == "(1/2)"

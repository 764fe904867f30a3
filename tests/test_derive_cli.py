"""``rollspring derive``: renderers (LaTeX compiled by pdflatex, Markdown math parsed by
latex2mathml), the cross-check report, methods that do not apply, the CLI's exit codes and
one-line errors, and the Python API's Jupyter representations."""

from __future__ import annotations

import re
import shutil
import subprocess
from pathlib import Path

import pytest
import typer
from latex2mathml.converter import convert
from typer.testing import CliRunner

from rollspring.analysis.derivation import (
    METHODS,
    Derivation,
    DerivationError,
    derive,
)
from rollspring.cli.commands.derive import register
from tests.conftest import body, make_system, spring

runner = CliRunner()


@pytest.fixture(scope="module")
def app() -> typer.Typer:
    application = typer.Typer()
    register(application)

    @application.command()
    def other() -> None:  # a second command, so that "derive" is a subcommand
        """Unused."""

    return application


@pytest.fixture(scope="module")
def fig2() -> Derivation:
    return derive("hoop-cylinder", symbols=True)


@pytest.fixture(scope="module")
def chain() -> Derivation:
    return derive("three-bodies")


def compile_latex(source: str, directory: Path) -> None:
    (directory / "derivation.tex").write_text(source, encoding="ascii")
    result = subprocess.run(
        [
            shutil.which("pdflatex") or "pdflatex",
            "-interaction=nonstopmode",
            "-halt-on-error",
            "derivation.tex",
        ],
        cwd=directory,
        capture_output=True,
        text=True,
        timeout=120,
        check=False,
    )
    assert result.returncode == 0, result.stdout[-3000:]
    pdf = directory / "derivation.pdf"
    assert pdf.exists() and pdf.read_bytes().startswith(b"%PDF")


def test_latex_document_compiles_with_pdflatex(
    fig2: Derivation, chain: Derivation, tmp_path: Path
) -> None:
    for name, result in (("fig2", fig2), ("chain", chain)):
        source = result.to_latex()
        assert source.startswith(r"\documentclass") and source.rstrip().endswith(r"\end{document}")
        assert "amsmath" in source
        directory = tmp_path / name
        directory.mkdir()
        compile_latex(source, directory)


def test_latex_escapes_words_and_names(tmp_path: Path) -> None:
    system = make_system(
        [body("a_1", "hoop", x=0.0), body("b_2", "sphere", x=0.5)],
        [spring("a_1", "b_2")],
        name="Odd & 100% #1 {x}_y ~ ^ \\ — φ",
    )
    compile_latex(derive(system, "newton").to_latex(), tmp_path)


def test_markdown_math_parses_and_matches_the_steps(fig2: Derivation) -> None:
    markdown = fig2.to_markdown()
    blocks = re.findall(r"^\$\$\n(.*?)\n\$\$$", markdown, flags=re.M | re.S)
    steps = [step for section in fig2.sections for step in section.steps]
    assert len(blocks) == len(steps) > 40
    for block in blocks:
        assert "<math" in convert(block)
    assert markdown.startswith("# Derivation: Hoop and cylinder")
    for method in METHODS:
        assert f"## {fig2.methods[method].title}" in markdown
    assert fig2._repr_markdown_() == markdown
    assert fig2._repr_latex_().startswith("$$")
    assert steps[0]._repr_latex_().startswith("$\\displaystyle")


def test_text_output_has_words_and_paper_references(fig2: Derivation) -> None:
    text = fig2.to_text()
    assert "Steiner" in text and "[paper (QQQ1)]" in text
    assert "Cross-check of the methods" in text and "all methods agree" in text
    # every step has one line of words
    for section in fig2.sections:
        for step in section.steps:
            assert step.words and "\n" not in step.words


def test_methods_that_do_not_apply_say_why(chain: Derivation) -> None:
    check = chain.cross_check
    assert check.applied == ["newton", "lagrange", "hamilton"]
    assert "2 oscillating modes" in check.not_applicable["conservation"]
    assert "3 bodies" in check.not_applicable["natural-frequencies"]
    assert check.agree and check.checks
    wall = derive("wall-hoop-cylinder", ["conservation", "natural-frequencies", "lagrange"])
    assert "no zero mode" in wall.cross_check.not_applicable["conservation"]
    assert "rank 2" in wall.cross_check.not_applicable["natural-frequencies"]
    assert "does not apply" in wall.to_text()


def test_no_equilibrium_is_reported_not_raised() -> None:
    pulled = make_system(
        [body("c", "cylinder", x=0.0)],
        [],
        forces=[{"body": "c", "at": {"height": 0.05}, "fx": 1.0}],
    )
    result = derive(pulled, ["newton", "conservation"])
    assert result.symbolic.reference == "initial placement"
    assert not result.methods["conservation"].applies
    assert "no equilibrium" in result.methods["conservation"].reason
    assert result.methods["newton"].nonlinear is not None  # the exact equation is still derived


def test_unknown_method_and_format_raise_one_line_errors() -> None:
    with pytest.raises(DerivationError, match="method: unknown method 'euler'"):
        derive("hoop-cylinder", "euler")
    with pytest.raises(DerivationError, match="format: unknown format 'pdf'"):
        derive("two-masses", "newton").render("pdf")


def test_cli_prints_a_derivation(app: typer.Typer) -> None:
    result = runner.invoke(app, ["derive", "two-masses", "--method", "newton", "--symbols"])
    assert result.exit_code == 0, result.output
    assert "Dynamic equations" in result.stdout and "m₁" in result.stdout


def test_cli_markdown_and_latex_to_a_file(app: typer.Typer, tmp_path: Path) -> None:
    target = tmp_path / "out" / "fig2.tex"
    result = runner.invoke(
        app,
        [
            "derive",
            "hoop-cylinder",
            "-m",
            "lagrange",
            "-m",
            "hamilton",
            "-f",
            "latex",
            "-o",
            str(target),
        ],
    )
    assert result.exit_code == 0, result.output
    text = target.read_text()
    assert text.startswith(r"\documentclass") and "Hamilton" in text
    assert "Dynamic equations" not in text  # only the methods asked for
    assert result.stdout == ""
    assert f"wrote {target}" in result.stderr
    md = runner.invoke(app, ["derive", "two-hoops", "-m", "newton", "--format", "markdown"])
    assert md.exit_code == 0 and md.stdout.startswith("# Derivation")


@pytest.mark.parametrize(
    ("args", "message"),
    [
        (
            ["derive", "hoop-cylinder", "--method", "euler"],
            "error: --method: unknown method 'euler'",
        ),
        (["derive", "hoop-cylinder", "--format", "pdf"], "error: --format: unknown format 'pdf'"),
        (["derive", "no-such-system"], "error: 'no-such-system' is neither a file nor a preset"),
    ],
)
def test_cli_bad_input_exit_2_with_one_line(
    app: typer.Typer, args: list[str], message: str
) -> None:
    result = runner.invoke(app, args)
    assert result.exit_code == 2
    lines = result.stderr.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith(message)
    assert result.stdout == ""


def test_cli_unwritable_output_is_a_one_line_error(app: typer.Typer, tmp_path: Path) -> None:
    blocker = tmp_path / "file"
    blocker.write_text("")
    result = runner.invoke(
        app, ["derive", "two-masses", "-m", "newton", "-o", str(blocker / "x.txt")]
    )
    assert result.exit_code == 2
    # checked before the derivation, as every command checks its --out
    assert result.stderr.strip().startswith(f"error: --out {blocker / 'x.txt'}: cannot write")
    assert len(result.stderr.strip().splitlines()) == 1


def test_the_rollspring_app_has_the_derive_command() -> None:
    from rollspring.cli import app as rollspring_app

    result = runner.invoke(
        rollspring_app, ["derive", "two-hoops", "-m", "natural-frequencies", "--symbols"]
    )
    assert result.exit_code == 0, result.output
    assert "Natural frequencies of the subsystems" in result.stdout
    assert "all methods agree" in result.stdout


def test_the_help_names_the_engines_methods_and_formats():
    from rollspring.analysis.derivation import ALL, FORMATS, METHODS
    from rollspring.cli.commands.derive import FORMAT_NAMES, METHOD_NAMES

    assert METHOD_NAMES == (*METHODS, ALL)
    assert FORMAT_NAMES == FORMATS


def test_the_cross_check_shows_each_residual_not_a_truth_value():
    from rollspring.analysis.derivation import derive
    from rollspring.model import load_system

    section = derive(load_system("hoop-cylinder")).cross_check.section()
    residuals = [step.latex for step in section.steps if "residual" in step.latex]
    assert len(residuals) >= 5
    for latex in residuals:
        assert "False" not in latex and "True" not in latex
        assert latex.startswith(r"\mathrm{residual} = ")


@pytest.mark.parametrize(
    ("preset", "is_cm"), [("two-hoops", True), ("two-masses", True), ("hoop-cylinder", False)]
)
def test_the_stationary_point_is_called_the_centre_of_mass_only_when_it_is(preset, is_cm):
    """Equal inertia factors give weights (1 + gamma) m_i proportional to m_i: X-hat is the CM
    (docs/physics.md (M14)); a hoop and a cylinder weigh 2 m1 : 1.5 m2, not the CM."""
    from rollspring.analysis.derivation import derive
    from rollspring.model import load_system

    text = derive(load_system(preset), "newton").to_text()
    assert ("here it is the centre of mass" in text) is is_cm
    assert ("not the centre of mass, stays at rest" in text) is not is_cm

"""``rollspring worksheet``: seeded exercise sheets (levels 1-4) and their solutions.

The same seed gives the same sheet; every number of the solutions is what ``rollspring analyze``
finds for the system printed in the solutions (read back from its TOML); the closed-form Omega^2
of the derivation equals the analysis' eigenvalues; the LaTeX documents compile.
"""

from __future__ import annotations

import math
import re
import shutil
import subprocess
import tomllib
from pathlib import Path

import numpy as np
import pytest
from typer.testing import CliRunner

from rollspring.analysis import LinearAnalysis, analyze
from rollspring.analysis.exercises import LEVELS, Worksheet
from rollspring.cli import app
from rollspring.cli.commands import worksheet as cli_worksheet
from rollspring.cli.commands.worksheet import SEPARATORS, solutions_path
from rollspring.errors import RollspringError
from rollspring.model import system_from_dict
from rollspring.outputs.worksheet import FORMATS, format_number, render_sheet, render_solutions
from rollspring.service.documents import worksheet

#: (level, seed) covering every level and variant: level 3 chain, two walls, one wall; level 4
#: wall hook and free pair.
CASES = [(1, 0), (2, 0), (3, 0), (3, 1), (3, 11), (4, 0), (4, 1)]
_SHEETS: dict[tuple[int, int], Worksheet] = {}


def sheet_for(level: int, seed: int) -> Worksheet:
    """One generated sheet per case, shared by the tests (the derivation takes a second)."""
    if (level, seed) not in _SHEETS:
        _SHEETS[(level, seed)] = worksheet(level, seed)
    return _SHEETS[(level, seed)]


def test_cases_cover_every_level_and_variant() -> None:
    variants = {(level, sheet_for(level, seed).variant) for level, seed in CASES}
    assert {level for level, _ in variants} == set(LEVELS)
    assert {(3, "chain"), (3, "two-walls"), (3, "wall"), (4, "wall"), (4, "pair")} <= variants


@pytest.mark.parametrize("level", sorted(LEVELS))
def test_same_seed_gives_the_same_sheet(level: int) -> None:
    first, second = worksheet(level, 5), worksheet(level, 5)
    assert first.data == second.data
    for fmt in ("markdown", "latex"):
        assert render_sheet(first, fmt) == render_sheet(second, fmt)
    assert [(a.key, a.values) for a in first.numeric_answers] == [
        (a.key, a.values) for a in second.numeric_answers
    ]


def test_same_seed_gives_the_same_solutions() -> None:
    assert render_solutions(worksheet(2, 9)) == render_solutions(worksheet(2, 9))


@pytest.mark.parametrize("level", sorted(LEVELS))
def test_different_seeds_give_different_sheets(level: int) -> None:
    sheets = {render_sheet(worksheet(level, seed)) for seed in range(6)}
    assert len(sheets) == 6


def _toml_of(solutions: str) -> dict:
    (block,) = re.findall(r"```toml\n(.*?)```", solutions, flags=re.S)
    return tomllib.loads(block)


def _expected(key: str, analysis: LinearAnalysis) -> list[float]:
    """What rollspring.analyze says for each kind of answer."""
    osc = analysis.oscillating
    J = np.diag(analysis.mass)
    n = len(J)
    table = {
        "inertia": list(J),
        "stiffness": [analysis.stiffness[i, j] for i in range(n) for j in range(i, n)],
        "omega": [m.omega for m in osc],
        "omega2_exact": [m.eigenvalue for m in osc],
        "period": [m.period for m in osc],
        "weights": list(analysis.stationary_weights)
        if analysis.stationary_weights is not None
        else [],
        "cm_weights": list(analysis.arrays.mass / analysis.arrays.mass.sum()),
        "trace": [sum(m.eigenvalue for m in osc), float(np.sum(np.diag(analysis.stiffness) / J))],
        "amplitude": list(analysis.amplitude),
        "max_speed": list(analysis.velocity_amplitude),
        "cm_amplitude": [analysis.cm_amplitude],
        "friction_amplitude": list(analysis.friction_amplitude),
        "required_mu": list(analysis.required_mu),
    }
    for number, mode in enumerate(osc, 1):
        table[f"shape{number}"] = list(mode.shape_x)
        table[f"friction{number}"] = list(mode.friction)
    return table[key]


def _percussion_needs_no_friction(body: dict, height: float) -> bool:
    """A body pulled by a horizontal wall spring attached ``height`` above its floor: no
    friction in its mode exactly when ``height`` is its percussion height (analyze)."""
    lone = {**body, "x": 0.0, "v": 0.05}
    system = system_from_dict(
        {
            "bodies": [lone],
            "anchors": [{"id": "w", "x": -0.5, "y": height}],
            "springs": [
                {"ends": ["w", lone["id"]], "stiffness": 100.0, "at": [{}, {"height": height}]}
            ],
        }
    )
    (mode,) = analyze(system).oscillating
    return abs(mode.friction[0]) < 1e-9 * 100.0


@pytest.mark.parametrize(("level", "seed"), CASES)
def test_every_number_of_the_solutions_is_what_analyze_finds(level: int, seed: int) -> None:
    sheet = sheet_for(level, seed)
    text = render_solutions(sheet, "markdown")
    data = _toml_of(text)
    assert data == sheet.data  # the file printed is the system of the sheet
    analysis = analyze(system_from_dict(data))  # afresh, from the printed file
    answers = sheet.answers
    keys = {a.key for a in answers}
    assert {"omega", "period", "amplitude", "max_speed", "omega2_exact"} <= keys
    if level > 1:
        assert {"inertia", "friction_amplitude", "required_mu"} <= keys
    checked = 0
    for answer in answers:
        assert answer.values, answer.key
        if answer.key == "percussion":
            for body, height in zip(data["bodies"], answer.values, strict=True):
                assert _percussion_needs_no_friction(body, height), (body, height)
        else:
            np.testing.assert_allclose(
                answer.values,
                _expected(answer.key, analysis),
                rtol=1e-9,
                atol=1e-12,
                err_msg=answer.key,
            )
        for value in answer.values:  # and each number is printed, as the answer says
            assert format_number(value) in text, (answer.key, value)
            checked += 1
        # each answer sits under its question
        question = sheet.questions[answer.question - 1]
        block = text.split(f"{answer.question}. {question}")[-1]
        assert answer.label in block.split("\n" + f"{answer.question + 1}. ")[0]
    assert checked >= 8


def test_numbers_are_printed_with_six_digits() -> None:
    assert format_number(0.0) == "0"
    assert format_number(math.inf) == "inf"
    assert format_number(1.0 / 3.0) == "0.333333"
    assert format_number(-1234567.0) == "-1.23457e+06"


@pytest.mark.parametrize("level", sorted(LEVELS))
def test_latex_documents_compile(level: int, tmp_path: Path) -> None:
    pdflatex = shutil.which("pdflatex")
    assert pdflatex, "pdflatex is needed (make test installs texlive-latex-base)"
    seed = {1: 0, 2: 0, 3: 1, 4: 1}[level]
    sheet = sheet_for(level, seed)
    for name, document in (
        ("sheet", render_sheet(sheet, "latex")),
        ("solutions", render_solutions(sheet, "latex")),
    ):
        source = tmp_path / f"{name}.tex"
        source.write_text(document, encoding="ascii")  # pure ASCII
        run = subprocess.run(
            [pdflatex, "-interaction=nonstopmode", "-halt-on-error", source.name],
            cwd=tmp_path,
            capture_output=True,
            text=True,
            timeout=120,
        )
        assert run.returncode == 0, run.stdout[-2000:]
        assert (tmp_path / f"{name}.pdf").stat().st_size > 1000


def test_markdown_sheet_has_the_system_and_the_questions() -> None:
    sheet = sheet_for(2, 0)
    text = render_sheet(sheet)
    assert text.startswith("# rollspring worksheet, Level 2: Two rolling bodies")
    assert "## Questions" in text and "| body | shape |" in text
    assert len(re.findall(r"^\d+\. ", text, flags=re.M)) == len(sheet.questions)
    assert "Solutions" not in text.split("## Questions")[0]


def test_bad_arguments_raise_one_line_errors() -> None:
    for level, seed, message in ((0, 1, "--level"), (5, 1, "--level"), (2, -1, "--seed")):
        with pytest.raises(RollspringError, match=message):
            worksheet(level, seed)
    with pytest.raises(RollspringError, match="--format"):
        render_sheet(sheet_for(1, 0), "html")


runner = CliRunner()


def test_cli_writes_the_sheet_and_the_solutions(tmp_path: Path) -> None:
    out = tmp_path / "week1.md"
    result = runner.invoke(app, ["worksheet", "--level", "1", "--seed", "0", "-o", str(out)])
    assert result.exit_code == 0, result.output
    sheet = sheet_for(1, 0)
    assert out.read_text() == render_sheet(sheet)
    assert solutions_path(str(out)) == tmp_path / "week1-solutions.md"
    assert (tmp_path / "week1-solutions.md").read_text() == render_solutions(sheet)
    assert f"wrote {out}" in result.stderr
    assert not list(tmp_path.glob(".*.part"))  # atomic: no temporary file left


def test_cli_prints_both_separated_without_out() -> None:
    result = runner.invoke(app, ["worksheet", "--level", "1", "--seed", "0", "--format", "latex"])
    assert result.exit_code == 0, result.output
    sheet = sheet_for(1, 0)
    first, second = result.stdout.split(SEPARATORS["latex"])
    assert first == render_sheet(sheet, "latex")
    assert second == render_solutions(sheet, "latex")


@pytest.mark.parametrize(
    ("args", "message"),
    [
        (["--level", "0", "--seed", "1"], "error: --level: must be 1, 2, 3 or 4 (got 0)"),
        (["--level", "5", "--seed", "1"], "error: --level: must be 1, 2, 3 or 4 (got 5)"),
        (["--level", "two", "--seed", "1"], "error: --level: must be 1, 2, 3 or 4 (got 'two')"),
        (["--seed", "1"], "error: --level: required (1, 2, 3 or 4)"),
        (
            ["--level", "2", "--seed", "-1"],
            "error: --seed: must be a non-negative integer (got -1)",
        ),
        (["--level", "2"], "error: --seed: required (a non-negative integer)"),
        (
            ["--level", "2", "--seed", "1", "--format", "html"],
            "error: --format: unknown format 'html' (formats: markdown, latex)",
        ),
    ],
)
def test_cli_bad_options_are_one_line_errors_with_exit_2(args: list[str], message: str) -> None:
    result = runner.invoke(app, ["worksheet", *args])
    assert result.exit_code == 2
    assert result.stderr.strip() == message
    assert result.stdout == ""


def test_cli_constants_are_the_librarys() -> None:
    # the CLI module keeps its own copies so that importing it does not import SymPy
    assert cli_worksheet.FORMATS == FORMATS
    assert cli_worksheet.LEVELS == LEVELS


def test_level_3_starts_as_its_words_say_only_body_2_displaced():
    """'Body 2 is pushed A to the left (every spring at rest before)': all springs have one rest
    length L, so every body but body 2 sits at its rest place (i - 1) L, body 2 at L - A."""
    seen = set()
    for seed in range(12):
        sheet = worksheet(3, seed)
        seen.add(sheet.variant)
        rest = {spring["rest_length"] for spring in sheet.data["springs"]}
        assert len(rest) == 1
        (length,) = rest
        xs = [body["x"] for body in sheet.data["bodies"]]
        for i, x in enumerate(xs):
            if i != 1:
                assert x == pytest.approx(i * length, abs=1e-12)
        assert 0 < length - xs[1] < 0.1 * length and "pushed" in " ".join(sheet.setting)
    assert seen == {"wall", "two-walls", "chain"}

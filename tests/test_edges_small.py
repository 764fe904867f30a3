"""Small edges a hostile session found: a subnormal duration reported as a numerical failure,
an animation's frame count that overflowed (an internal error) or was printed with 300 digits,
and the web's derivation refusing the comma-separated methods its schema documents (asked of
the real server, `rollspring serve` on loopback)."""

from __future__ import annotations

import pytest
import requests
from typer.testing import CliRunner

import rollspring
from rollspring.cli import app
from rollspring.errors import RollspringError
from rollspring.model import load_system, system_to_json
from rollspring.simulate.arguments import MIN_DURATION


def _cli(*args: str) -> tuple[int, str]:
    result = CliRunner().invoke(app, list(args))
    return result.exit_code, result.output


@pytest.mark.parametrize("duration", ["1e-310", "1e-320", "5e-10"])
def test_a_duration_below_a_nanosecond_is_refused(duration: str) -> None:
    code, output = _cli("simulate", "hoop-cylinder", "-T", duration)
    assert code == 2, output
    assert output.startswith("error: duration: must be at least 1e-09 s"), output
    assert output.count("\n") == 1
    with pytest.raises(RollspringError, match="must be at least 1e-09 s"):
        rollspring.simulate("hoop-cylinder", float(duration))
    assert rollspring.simulate("hoop-cylinder", MIN_DURATION).status == "finished"


@pytest.mark.parametrize(
    ("args", "count"),
    [
        (["--speed", "1e-320"], "inf"),
        (["--speed", "1e-300"], "2.5e+301"),
        (["-T", "600", "--speed", "1e-308"], "inf"),
    ],
)
def test_an_animation_of_too_many_frames_is_one_short_line(
    tmp_path, args: list[str], count: str
) -> None:
    code, output = _cli("animate", "hoop-cylinder", "-T", "1", *args, "-o", str(tmp_path / "a.gif"))
    assert code == 2 and output.count("\n") == 1 and len(output) < 200, output
    assert f"is {count} frames (at most 10000)" in output
    assert not (tmp_path / "a.gif").exists()


def test_the_web_derives_by_comma_separated_methods(server: str) -> None:
    system = system_to_json(load_system("hoop-cylinder"))
    answer = requests.post(
        f"{server}/api/derive", json={"system": system, "method": "newton, lagrange"}, timeout=300
    )
    assert answer.status_code == 200, answer.text
    titles = [section["title"] for section in answer.json()["sections"]]
    assert any(title.startswith("Dynamic equations (Newton") for title in titles), titles
    assert "Euler-Lagrange equations" in titles and not any("Hamilton" in t for t in titles)
    wrong = requests.post(
        f"{server}/api/derive", json={"system": system, "method": "newton,euler"}, timeout=300
    )
    assert wrong.status_code == 422 and "euler" in wrong.text


def test_the_web_refuses_a_subnormal_duration(server: str) -> None:
    system = system_to_json(load_system("hoop-cylinder"))
    answer = requests.post(
        f"{server}/api/simulate", json={"system": system, "duration": 1e-320}, timeout=300
    )
    assert answer.status_code == 422 and "duration" in answer.text


@pytest.mark.parametrize(
    ("args", "words"),
    [
        (["report", "hoop-cylinder", "-f", "pdf", "-o", "{tmp}/r.html"], "the pdf report's name"),
        (["report", "hoop-cylinder", "-o", "{tmp}/r.txt"], "the html report's name must end in"),
        (["report", "hoop-cylinder", "--free", "springs.0.stiffness"], "--free: only with --data"),
        (["export", "hoop-cylinder", "-o", "{tmp}/m.json"], "an MJCF model's name must end in"),
        (["paper-check", "--json", "-f", "markdown"], "--format markdown: not with --json"),
        (["worksheet", "--level", "1", "--seed", "1", "-o", "{tmp}/w/"], "ends in '/', a folder"),
        (["dispersion", "chain-diatomic", "--points", "1"], "--points: must be a whole number"),
    ],
)
def test_options_that_would_mislead_are_refused(tmp_path, args: list[str], words: str) -> None:
    """A PDF written under .html, MJCF under .json, a folder name taken as a file's, options
    silently ignored: each now one line, exit 2, nothing written."""
    code, output = _cli(*(arg.format(tmp=tmp_path) for arg in args))
    assert code == 2 and words in output and output.count("\n") == 1, output
    assert not any(tmp_path.iterdir())


def test_the_api_s_pages_load_nothing_from_elsewhere(server: str) -> None:
    """FastAPI's /docs and /redoc load Swagger UI, ReDoc and fonts from CDNs: not served."""
    assert requests.get(f"{server}/docs", timeout=60).status_code == 404
    assert requests.get(f"{server}/redoc", timeout=60).status_code == 404
    assert (
        requests.get(f"{server}/openapi.json", timeout=60).json()["info"]["title"] == "rollspring"
    )


def test_the_report_writer_refuses_a_name_of_another_format(tmp_path) -> None:
    """The Python API wrote a PDF under .html too; .htm is an HTML name."""
    from rollspring.outputs.report import ReportError, check_report_name

    with pytest.raises(ReportError, match=r"the pdf report's name must end in \.pdf"):
        check_report_name(tmp_path / "r.html", "pdf")
    check_report_name(tmp_path / "r.htm", "html")
    check_report_name(tmp_path / "r.PDF", "pdf")

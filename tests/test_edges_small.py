"""Small edges a hostile session found: a subnormal duration reported as a numerical failure,
an animation's frame count that overflowed (an internal error) or was printed with 300 digits,
and the web's derivation refusing the comma-separated methods its schema documents."""

from __future__ import annotations

from collections.abc import Iterator

import pytest
from fastapi.testclient import TestClient
from typer.testing import CliRunner

import rollspring
from rollspring.cli import app
from rollspring.errors import RollspringError
from rollspring.model import load_system, system_to_json
from rollspring.simulate.arguments import MIN_DURATION
from rollspring.web import create_app


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


@pytest.fixture(scope="module")
def client() -> Iterator[TestClient]:
    with TestClient(create_app(workers=1, budget=600.0)) as test_client:
        yield test_client


def test_the_web_derives_by_comma_separated_methods(client: TestClient) -> None:
    system = system_to_json(load_system("hoop-cylinder"))
    answer = client.post("/api/derive", json={"system": system, "method": "newton, lagrange"})
    assert answer.status_code == 200, answer.text
    titles = [section["title"] for section in answer.json()["sections"]]
    assert any(title.startswith("Dynamic equations (Newton") for title in titles), titles
    assert "Euler-Lagrange equations" in titles and not any("Hamilton" in t for t in titles)
    wrong = client.post("/api/derive", json={"system": system, "method": "newton,euler"})
    assert wrong.status_code == 422 and "euler" in wrong.text


def test_the_web_refuses_a_subnormal_duration(client: TestClient) -> None:
    system = system_to_json(load_system("hoop-cylinder"))
    answer = client.post("/api/simulate", json={"system": system, "duration": 1e-320})
    assert answer.status_code == 422 and "duration" in answer.text

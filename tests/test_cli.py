"""The command-line interface, in-process (Typer's CliRunner) and once as a real process."""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

import pytest
from typer.testing import CliRunner

from rollspring.cli import app
from rollspring.model import preset_names

runner = CliRunner()
REQUIRED_KEYS = {
    "coordinates",
    "matrices",
    "equilibrium",
    "modes",
    "stationary_point",
    "response",
    "springs",
    "warnings",
}


def run(*args: str):
    return runner.invoke(app, list(args))


def test_analyze_default_prints_the_papers_frequency() -> None:
    result = run("analyze")
    assert result.exit_code == 0, result.output
    assert "Hoop and cylinder" in result.stdout
    assert "10.801234" in result.stdout  # sqrt(k/(2 m1) + 2k/(3 m2)) for the default system


def test_analyze_json_is_one_object_with_the_documented_fields() -> None:
    result = run("analyze", "hoop-cylinder", "--json")
    assert result.exit_code == 0
    data = json.loads(result.stdout)
    assert REQUIRED_KEYS <= set(data)
    assert data["coordinates"] == ["hoop", "cylinder"]
    assert data["matrices"]["M"] == [[pytest.approx(0.02), 0.0], [0.0, pytest.approx(0.015)]]
    assert set(data["equilibrium"]) >= {"phi", "friction", "normal_force"}
    zero, mode = data["modes"]
    assert zero["omega"] == 0.0
    assert mode["omega"] == pytest.approx((100 / 2 + 200 / 3) ** 0.5, rel=1e-12)
    assert set(mode) >= {"shape", "shape_phi", "spring_extension", "friction", "normal_force"}
    assert sum(data["stationary_point"]["weights"].values()) == pytest.approx(1.0)
    assert set(data["response"]) >= {
        "amplitude",
        "cm_amplitude",
        "friction_amplitude",
        "normal_force_range",
        "required_mu",
    }
    assert data["springs"][0]["tilt_deg"] == 0.0
    assert data["springs"][0]["tension"] == 0.0


def test_analyze_json_keeps_warnings_off_stdout(tmp_path: Path) -> None:
    path = tmp_path / "paper-fig3.toml"
    path.write_text(
        'name = "Fig. 3 as the paper sizes it"\n'
        '[[bodies]]\nid = "hoop"\nshape = "hoop"\nmass = 1.0\nradius = 0.05\nx = 0.0\n'
        '[[bodies]]\nid = "cyl"\nshape = "cylinder"\nmass = 1.0\nradius = 0.1\nx = 0.5\n'
        '[[springs]]\nends = ["hoop", "cyl"]\nstiffness = 100.0\n'
        "at = [{ height = 0.1 }, { height = 0.15 }]\n"
    )
    result = run("analyze", str(path), "--json")
    assert result.exit_code == 0
    data = json.loads(result.stdout)  # stdout is exactly one JSON object
    assert data["warnings"] and "tilted" in data["warnings"][0]
    assert "warning:" in result.stderr
    assert data["springs"][0]["tilt_deg"] == pytest.approx(5.710593137499643, rel=1e-12)


@pytest.mark.parametrize("name", preset_names())
def test_every_preset_analyses(name: str) -> None:
    result = run("analyze", name, "--json")
    assert result.exit_code == 0, result.output
    data = json.loads(result.stdout)
    assert all(m["omega"] >= 0 for m in data["modes"])
    table = run("analyze", name)
    assert table.exit_code == 0
    assert "Normal modes" in table.stdout


def test_presets_lists_all_nine_and_marks_the_default() -> None:
    result = run("presets", "--json")
    rows = json.loads(result.stdout)
    assert {r["name"] for r in rows} == {
        "chain-monatomic",
        "chain-diatomic",
        "two-masses",
        "hoop-cylinder",
        "frictionless",
        "two-hoops",
        "two-cylinders",
        "wall-hoop-cylinder",
        "three-bodies",
    }
    assert [r["name"] for r in rows if r["default"]] == ["hoop-cylinder"]
    assert "hoop-cylinder (default)" in run("presets").stdout


def test_schema_is_a_json_schema_of_a_system() -> None:
    schema = json.loads(run("schema").stdout)
    assert schema["type"] == "object"
    assert {"bodies", "springs", "anchors", "forces", "gravity"} <= set(schema["properties"])
    assert "bodies" in schema["required"]


def test_unknown_preset_is_a_one_line_error_with_exit_code_2() -> None:
    result = run("analyze", "hoop-cilinder")
    assert result.exit_code == 2
    assert result.stdout == ""
    assert result.stderr.count("\n") == 1
    assert "neither a file nor a preset" in result.stderr


def test_unknown_option_exits_with_code_2() -> None:
    assert run("analyze", "--frobnicate").exit_code == 2


def test_console_script_runs_as_a_process() -> None:
    exe = Path(sys.executable).with_name("rollspring")
    done = subprocess.run(
        [str(exe), "analyze", "two-hoops", "--json"], capture_output=True, text=True, check=False
    )
    assert done.returncode == 0, done.stderr
    assert json.loads(done.stdout)["stationary_point"]["is_centre_of_mass"] is True


def test_version_prints_the_installed_version() -> None:
    from importlib.metadata import version

    result = runner.invoke(app, ["--version"])
    assert result.exit_code == 0
    assert result.stdout == f"rollspring {version('rollspring')}\n"

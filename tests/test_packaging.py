"""The package as a user gets it (issue 12, point 1): ``python -m build`` makes an sdist and a
wheel; the wheel holds the presets, the page and the two uPlot files it loads, the report's style
sheet and player, and no tests; it installs into a fresh virtual environment with only the core
(no extra; versions from constraints.txt, from PyPI or pip's cache), where ``analyze --json`` and
``simulate --json`` run and ``rollspring report`` says in one line which extra to install.

Slow (a build and an install, about a minute; most of it pip and Numba's first compilation).
"""

from __future__ import annotations

import json
import os
import shutil
import subprocess
import sys
import tomllib
import venv
import zipfile
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
STATIC = ROOT / "src" / "rollspring" / "web" / "static"
UPLOT = ("node_modules/uplot/dist/uPlot.esm.js", "node_modules/uplot/dist/uPlot.min.css")
PROJECT = tomllib.loads((ROOT / "pyproject.toml").read_text(encoding="utf-8"))["project"]

pytestmark = pytest.mark.slow


def _env() -> dict[str, str]:
    """The environment without this virtual environment's traces."""
    env = {
        k: v
        for k, v in os.environ.items()
        if k not in {"VIRTUAL_ENV", "PYTHONPATH", "PYTHONHOME", "PIP_REQUIRE_VIRTUALENV"}
    }
    env["PIP_DISABLE_PIP_VERSION_CHECK"] = "1"
    return env


def _run(argv: list[str | Path], **kwargs) -> subprocess.CompletedProcess[str]:
    return subprocess.run(
        [str(a) for a in argv], capture_output=True, text=True, check=False, env=_env(), **kwargs
    )


def _source_copy(target: Path) -> Path:
    """What the build reads (pyproject.toml, README, LICENSE, src/ with only uPlot of
    node_modules), copied so that building never writes into the work tree."""

    def skip(folder: str, names: list[str]) -> set[str]:
        ignored = {n for n in names if n == "__pycache__" or n.endswith(".egg-info")}
        if Path(folder).name == "node_modules":
            ignored |= {n for n in names if n != "uplot"}
        return ignored

    target.mkdir()
    for name in ("pyproject.toml", "README.md", "LICENSE"):
        shutil.copy2(ROOT / name, target / name)
    shutil.copytree(ROOT / "src", target / "src", ignore=skip)
    return target


@pytest.fixture(scope="module")
def dist(tmp_path_factory) -> Path:
    missing = [name for name in UPLOT if not (STATIC / name).is_file()]
    if missing:
        pytest.fail(
            f"{', '.join(missing)} missing in {STATIC}: run `npm ci --prefix "
            f"{STATIC.relative_to(ROOT)}` (make test does)"
        )
    work = tmp_path_factory.mktemp("packaging")
    source = _source_copy(work / "source")
    built = _run([sys.executable, "-m", "build", "--outdir", work / "dist", source])
    assert built.returncode == 0, built.stdout[-3000:] + built.stderr[-3000:]
    return work / "dist"


@pytest.fixture(scope="module")
def wheel(dist) -> Path:
    (path,) = dist.glob("rollspring-*-py3-none-any.whl")
    return path


@pytest.fixture(scope="module")
def core_env(wheel, tmp_path_factory) -> Path:
    """A fresh virtual environment with the wheel and its core dependencies only."""
    env = tmp_path_factory.mktemp("core-venv") / "venv"
    venv.EnvBuilder(with_pip=True, clear=True).create(env)
    python = env / "bin" / "python"
    installed = _run(
        [python, "-m", "pip", "install", "--quiet", "-c", ROOT / "constraints.txt", wheel]
    )
    assert installed.returncode == 0, installed.stdout[-3000:] + installed.stderr[-3000:]
    return env


def test_build_makes_an_sdist_and_a_wheel(dist) -> None:
    version = PROJECT["version"]
    assert sorted(p.name for p in dist.iterdir()) == [
        f"rollspring-{version}-py3-none-any.whl",
        f"rollspring-{version}.tar.gz",
    ]


def test_the_wheel_holds_presets_page_and_uplot_and_no_tests(wheel) -> None:
    names = set(zipfile.ZipFile(wheel).namelist())
    presets = {p.name for p in (ROOT / "src/rollspring/model/presets").glob("*.toml")}
    assert presets and {f"rollspring/model/presets/{p}" for p in presets} <= names
    page = {
        str(p.relative_to(STATIC))
        for p in STATIC.rglob("*")
        if p.is_file() and "node_modules" not in p.parts and p.name != ".gitignore"
    }
    assert "index.html" in page and any(p.startswith("js/") for p in page)
    assert {f"rollspring/web/static/{p}" for p in (*page, *UPLOT)} <= names
    # only uPlot's two files and its licence from node_modules
    assert {n for n in names if "node_modules" in n} == {
        f"rollspring/web/static/{p}" for p in (*UPLOT, "node_modules/uplot/LICENSE")
    }
    assert "rollspring/py.typed" in names
    # the report's style sheet and player, inlined into every report (with the shared geometry.js)
    assets = {p.name for p in (ROOT / "src/rollspring/outputs/report/assets").iterdir()}
    assert {"player.js", "report.css"} <= assets
    assert {f"rollspring/outputs/report/assets/{a}" for a in assets} <= names
    assert "rollspring/outputs/js/geometry.js" in names
    assert "rollspring/analysis/paper/claims.toml" in names  # the paper check's words
    assert any(n.endswith(".dist-info/licenses/LICENSE") for n in names)
    assert not [
        n
        for n in names
        if n.startswith("tests/")
        or "/tests/" in n
        or Path(n).name.startswith("test_")
        or "__pycache__" in n
    ]


def test_the_core_install_has_no_extra(core_env) -> None:
    probe = (
        "import importlib.util as u; print(','.join(m for m in ('matplotlib', 'sympy', "
        "'fastapi', 'dask', 'xarray', 'pandas', 'pytest') if u.find_spec(m)))"
    )
    done = _run([core_env / "bin" / "python", "-c", probe])
    assert done.returncode == 0 and done.stdout.strip() == "", done.stdout + done.stderr


def test_the_version_comes_from_the_metadata(core_env) -> None:
    done = _run(
        [core_env / "bin" / "python", "-c", "import rollspring; print(rollspring.__version__)"]
    )
    assert done.stdout.strip() == PROJECT["version"], done.stderr


def test_analyze_and_simulate_run_from_the_core_install(core_env, tmp_path) -> None:
    rollspring = core_env / "bin" / "rollspring"
    analyzed = _run([rollspring, "analyze", "hoop-cylinder", "--json"], cwd=tmp_path)
    assert analyzed.returncode == 0, analyzed.stderr
    modes = json.loads(analyzed.stdout)["modes"]
    assert modes[1]["omega"] == pytest.approx(10.801234, abs=1e-6)
    simulated = _run([rollspring, "simulate", "hoop-cylinder", "-T", "1", "--json"], cwd=tmp_path)
    assert simulated.returncode == 0, simulated.stderr
    summary = json.loads(simulated.stdout)
    assert summary["status"] == "finished" and summary["energy_error"] < 1e-6


def test_report_without_its_extra_says_which_to_install(core_env, tmp_path) -> None:
    done = _run([core_env / "bin" / "rollspring", "report", "hoop-cylinder"], cwd=tmp_path)
    assert done.returncode == 2
    assert done.stdout == ""
    assert done.stderr == (
        "error: rollspring report needs the 'report' extra: pip install 'rollspring[report]'\n"
    )
    assert list(tmp_path.iterdir()) == []

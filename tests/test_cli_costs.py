"""Each command checks its arguments and estimates its cost once: the estimate the ``--yes``
guard confirms is the only one; the work it guards (the analysis, the run, the derivation, the
report's stages) estimates nothing again. Every estimator is counted wherever it is looked up
(:mod:`rollspring.analysis.costs`, :mod:`rollspring.simulate.costs` and the names
:mod:`rollspring.service.costs` gathers for the command line)."""

from __future__ import annotations

from collections import Counter
from collections.abc import Callable
from pathlib import Path
from typing import Any

import pytest
from typer.testing import CliRunner

import rollspring
from rollspring.analysis import costs as analysis_costs
from rollspring.cli import app
from rollspring.service import costs as service_costs

runner = CliRunner()


@pytest.fixture
def estimates(monkeypatch: pytest.MonkeyPatch) -> Counter[str]:
    """How many times each estimator ran (by name), from here on."""
    from rollspring.simulate import costs as simulate_costs

    counts: Counter[str] = Counter()

    def counted(name: str, estimate: Callable[..., Any]) -> Callable[..., Any]:
        def wrapper(*args: Any, **kwargs: Any) -> Any:
            counts[name] += 1
            return estimate(*args, **kwargs)

        return wrapper

    for name in ("analysis_cost", "derivation_cost"):
        wrapper = counted(name, getattr(analysis_costs, name))
        monkeypatch.setattr(analysis_costs, name, wrapper)
        monkeypatch.setattr(service_costs, name, wrapper)
    monkeypatch.setattr(
        simulate_costs, "request_cost", counted("request_cost", simulate_costs.request_cost)
    )
    monkeypatch.setattr(
        service_costs, "report_cost", counted("report_cost", service_costs.report_cost)
    )
    return counts


def run(*args: str) -> None:
    result = runner.invoke(app, list(args))
    assert result.exit_code == 0, result.output


def test_analyze_estimates_once(estimates: Counter[str]) -> None:
    run("analyze", "hoop-cylinder")
    assert estimates == {"analysis_cost": 1}


def test_analyze_json_estimates_once(estimates: Counter[str]) -> None:
    run("analyze", "hoop-cylinder", "--json", "--modes", "1")
    assert estimates == {"analysis_cost": 1}


def test_simulate_estimates_once(estimates: Counter[str], tmp_path: Path) -> None:
    run("simulate", "hoop-cylinder", "-T", "0.5", "--outputs", "51", "--out", str(tmp_path))
    assert estimates == {"request_cost": 1}


def test_animate_estimates_once(estimates: Counter[str], tmp_path: Path) -> None:
    pytest.importorskip("matplotlib")
    run("animate", "hoop-cylinder", "-T", "0.2", "--fps", "5", "-o", str(tmp_path / "a.html"))
    assert estimates == {"request_cost": 1}


def test_derive_estimates_once(estimates: Counter[str], tmp_path: Path) -> None:
    pytest.importorskip("sympy")
    run("derive", "hoop-cylinder", "-m", "newton", "-o", str(tmp_path / "d.md"))
    assert estimates == {"derivation_cost": 1}


def test_report_estimates_once(estimates: Counter[str], tmp_path: Path) -> None:
    """The report's estimate is its analysis', run's and derivation's, once each; its stages
    estimate nothing again."""
    pytest.importorskip("matplotlib")
    run("report", "hoop-cylinder", "-T", "0.5", "-o", str(tmp_path / "r.html"))
    assert estimates == {
        "report_cost": 1,
        "analysis_cost": 1,
        "request_cost": 1,
        "derivation_cost": 1,
    }


def test_report_without_derivation_estimates_once(estimates: Counter[str], tmp_path: Path):
    pytest.importorskip("matplotlib")
    run("report", "hoop-cylinder", "-T", "0.5", "--no-derivation", "-o", str(tmp_path / "r.html"))
    assert estimates == {"report_cost": 1, "analysis_cost": 1, "request_cost": 1}


def test_the_library_estimates_once_too(estimates: Counter[str]) -> None:
    """The Python entry points refuse a run too large with one estimate each."""
    system = rollspring.load_system("hoop-cylinder")
    rollspring.analyze(system)
    assert estimates == {"analysis_cost": 1}
    rollspring.simulate(system, 0.5, n_output=51)
    assert estimates == {"analysis_cost": 1, "request_cost": 1}
    estimates.clear()
    rollspring.build_report(system, duration=0.5, derivation=False)
    assert estimates == {"report_cost": 1, "analysis_cost": 1, "request_cost": 1}


def test_a_checked_run_estimates_nothing(estimates: Counter[str]) -> None:
    """service.runs.run_request (what simulate, animate and the web page run) estimates
    nothing, nor the analyses of a run from a mode or beside the linear motion."""
    from rollspring.service.runs import ModeStart, run_request
    from rollspring.simulate.request import simulation_request

    system = rollspring.load_system("hoop-cylinder")
    request = simulation_request(0.5, n_output=51)
    run = run_request(system, request, start=ModeStart(1, 0.01), linear=True)
    assert run.linear is not None
    assert estimates == {}

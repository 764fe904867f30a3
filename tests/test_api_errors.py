"""The Python API raises the same RollspringErrors, with the same messages, as the CLI prints
(issue 13.4): every public entry point that takes a system takes a System, its JSON form (a
dict), a file path or a preset name, and anything else is a one-line error, never an
AttributeError from deep inside; a run estimated above the bound is refused with the CLI's
estimate unless ``confirm=True`` (the CLI's ``--yes``), before any work.

The comparisons run the CLI in-process (Typer's CliRunner) on the same mistake: the API's message
is the CLI's line without its ``error: `` prefix; where the CLI names an option (``--yes``,
``--duration``, ``--outputs``) the API names its argument (``confirm=True``, ``duration``,
``n_output``), and a dict's mistakes are located at ``system`` where a file's are at its path.
Nothing here measures time: a refusal before the work is shown by work that fails if reached.
"""

from __future__ import annotations

import importlib
import json
from collections.abc import Callable
from pathlib import Path
from typing import Any

import numpy as np
import pytest
from typer.testing import CliRunner

import rollspring
from rollspring.cli import app
from rollspring.errors import (
    CostTooHigh,
    DerivationError,
    ModelError,
    ReportError,
    RollspringError,
    SimulationError,
    WorksheetError,
)

runner = CliRunner()

#: the CLI's words for the API's: the confirmation, and how to make a run smaller
CLI_TO_API = (
    ("--yes", "confirm=True"),
    ("a shorter --duration, fewer --outputs", "a shorter duration, fewer n_output"),
    ("a shorter --duration, fewer bodies", "a shorter duration, fewer bodies"),
)

WRONG_DICT = {"bodies": 1}
NOT_A_SYSTEM = "system: must be a System, its JSON form (a dict), a file path or a preset name"


class Reached(Exception):
    """Raised by work that a refusal must come before."""


def cli_error(*args: str) -> str:
    """The one line the CLI prints for ``rollspring ARGS`` (exit code 2), without ``error: ``."""
    result = runner.invoke(app, list(args))
    assert result.exit_code == 2, (result.exit_code, result.output)
    lines = result.stderr.strip().splitlines()
    errors = [line for line in lines if line.startswith("error: ")]
    assert len(errors) == 1, result.stderr
    return errors[0].removeprefix("error: ")


def in_api_words(message: str) -> str:
    for cli, api in CLI_TO_API:
        message = message.replace(cli, api)
    return message


def api_error(call: Callable[[], object], kind: type[RollspringError] = RollspringError) -> str:
    with pytest.raises(kind) as caught:
        call()
    message = str(caught.value)
    assert "\n" not in message
    return message


def chain(n: int) -> dict[str, Any]:
    """``n`` cylinders in a row joined by springs (as tests/test_hostile_inputs.py's)."""
    return {
        "bodies": [
            {"id": f"b{i}", "shape": "cylinder", "mass": 1.0, "radius": 0.1, "x": 0.5 * i}
            for i in range(n)
        ],
        "springs": [
            {"ends": [f"b{i}", f"b{i + 1}"], "stiffness": 100.0, "rest_length": 0.49}
            for i in range(n - 1)
        ],
    }


def write(folder: Path, name: str, data: object) -> str:
    path = folder / name
    path.write_text(json.dumps(data), encoding="utf-8")
    return str(path)


@pytest.fixture(scope="module")
def system() -> rollspring.System:
    return rollspring.load_system("hoop-cylinder")


# ------------------------------------------------------------------- the system argument

#: entry point -> a call of it on a system, as cheap as it can be
ENTRY_POINTS: dict[str, Callable[[Any], object]] = {
    "simulate": lambda s: rollspring.simulate(s, 0.05, n_output=11),
    "simulate_batch": lambda s: rollspring.simulate_batch(
        s, {"springs.0.stiffness": [100.0, 120.0]}, 0.05, n_output=3
    ),
    "find_equilibrium": lambda s: rollspring.find_equilibrium(s),
    "derive": lambda s: rollspring.derive(s, "newton"),
    "build_report": lambda s: rollspring.build_report(s, duration=0.05, derivation=False),
}

ENTRY_POINTS.update(
    {
        "analyze": lambda s: rollspring.analyze(s),
        "system_arrays": lambda s: rollspring.system_arrays(s),
        "symbolic_system": lambda s: rollspring.symbolic_system(s),
        "system_to_mjcf": lambda s: importlib.import_module(
            "rollspring.outputs.mjcf"
        ).system_to_mjcf(s),
    }
)
#: a sweep takes a while even for two runs: only its refusals are compared
SWEEP = {"sweep": lambda s: rollspring.sweep(s, {"springs.0.stiffness": [100.0, 120.0]}, 0.05)}


def _points(*, errors: bool = False) -> list[Any]:
    calls = {**ENTRY_POINTS, **(SWEEP if errors else {})}
    return [pytest.param(call, id=name) for name, call in calls.items()]


def _refused(call: Callable[[Any], object], value: object) -> str:
    try:
        call(value)
    except RollspringError as exc:
        return str(exc)
    except Exception as exc:  # what this test is about
        raise AssertionError(f"{type(exc).__name__} leaked: {exc}") from exc
    raise AssertionError(f"{value!r} was accepted")


@pytest.mark.parametrize("call", _points())
def test_a_preset_name_a_path_and_a_dict_are_systems(call, tmp_path: Path) -> None:
    try:
        call("two-hoops")
        call(Path(rollspring.model.preset_path("two-hoops")))
        call(rollspring.model.system_to_json(rollspring.load_system("two-hoops")))
    except Exception as exc:  # an AttributeError is the failure looked for
        raise AssertionError(f"{type(exc).__name__}: {exc}") from exc


@pytest.mark.parametrize("call", _points(errors=True))
@pytest.mark.parametrize("value", [None, 3, 2.5, b"hoop-cylinder", ["hoop-cylinder"]])
def test_what_is_not_a_system_is_a_one_line_model_error(call, value) -> None:
    message = _refused(call, value)
    assert message == f"{NOT_A_SYSTEM} (got {type(value).__name__})"


@pytest.mark.parametrize("call", [*_points(), pytest.param(SWEEP["sweep"], id="sweep")])
def test_an_unknown_preset_is_the_clis_message(call) -> None:
    assert _refused(call, "no-such-preset") == cli_error("analyze", "no-such-preset")


@pytest.mark.parametrize("call", _points(errors=True))
def test_a_wrong_dict_is_the_clis_message_for_that_file(call, tmp_path: Path) -> None:
    path = write(tmp_path, "bad.json", WRONG_DICT)
    cli = cli_error("analyze", path)
    assert cli.startswith(f"{path}: ")
    assert _refused(call, path) == cli
    assert _refused(call, WRONG_DICT) == "system: " + cli.removeprefix(f"{path}: ")


def test_the_system_errors_are_model_errors(system) -> None:
    for value in (None, 3, WRONG_DICT, "no-such-preset"):
        with pytest.raises(ModelError):
            rollspring.simulate(value, 1.0)


# -------------------------------------------------------------------- simulate's arguments


@pytest.mark.parametrize(
    ("cli", "api"),
    [
        (["-T", "0"], {"duration": 0.0}),
        (["-T", "-1"], {"duration": -1.0}),
        (["-T", "nan"], {"duration": float("nan")}),
        (["--rtol", "0"], {"rtol": 0.0}),
        (["--rtol", "1e-300"], {"rtol": 1e-300}),
        (["--rtol", "0.5"], {"rtol": 0.5}),
        (["--outputs", "1"], {"n_output": 1}),
        (["--outputs", "-5"], {"n_output": -5}),
        (["--integrator", "euler"], {"integrator": "euler"}),
        (["--on-slip", "skid"], {"on_slip": "skid"}),
    ],
    ids=lambda value: " ".join(value) if isinstance(value, list) else None,
)
def test_simulate_says_what_the_cli_says(system, cli, api) -> None:
    arguments = {"duration": 1.0, **api}
    duration = arguments.pop("duration")
    message = api_error(lambda: rollspring.simulate(system, duration, **arguments))
    assert message == cli_error("simulate", "hoop-cylinder", *cli)


@pytest.mark.parametrize(
    "arguments",
    [
        {"duration": True},
        {"n_output": True},
        {"n_output": 100.0},
        {"rtol": True},
        {"rtol": "1e-8"},
        {"confirm": "yes"},
        {"confirm": 1},
    ],
    ids=repr,
)
def test_simulate_refuses_bools_as_numbers_and_numbers_as_bools(system, arguments) -> None:
    arguments = {"duration": 0.05, **arguments}
    duration = arguments.pop("duration")
    message = api_error(lambda: rollspring.simulate(system, duration, **arguments), SimulationError)
    assert message.startswith(f"{next(iter(arguments), 'duration')}: ")


def test_simulate_takes_numpy_numbers(system) -> None:
    run = rollspring.simulate(
        system, np.float64(0.05), n_output=np.int64(11), rtol=np.float64(1e-8)
    )
    assert run.t.shape == (11,)
    run = rollspring.simulate(system, np.int64(1), n_output=np.int32(3), confirm=np.bool_(False))
    assert run.t[-1] == 1.0


def test_simulate_batch_takes_numpy_counts_and_refuses_bools(system) -> None:
    result = rollspring.simulate_batch(
        system, {"springs.0.stiffness": [100.0]}, np.float64(0.05), n_output=np.int64(3)
    )
    assert result.n_runs == 1
    for arguments in ({"n_output": True}, {"metric_every": False}, {"stop_on_slip": "no"}):
        message = api_error(
            lambda arguments=arguments: rollspring.simulate_batch(
                system, {"springs.0.stiffness": [100.0]}, 0.05, **arguments
            ),
            SimulationError,
        )
        assert message.startswith(f"{next(iter(arguments))}: ")
    api_error(lambda: rollspring.simulate_batch(system, {}, True), SimulationError)


# --------------------------------------------------------------------- the cost guard


def _never(*args: object, **kwargs: object) -> object:
    raise Reached


def test_simulate_refuses_a_long_run_with_the_clis_estimate(system, monkeypatch) -> None:
    from rollspring.simulate import run

    monkeypatch.setattr(run, "system_arrays", _never)  # the run's first work
    message = api_error(lambda: rollspring.simulate(system, 1e9), CostTooHigh)
    assert message == in_api_words(cli_error("simulate", "hoop-cylinder", "-T", "1e9"))
    assert "confirm it with confirm=True" in message
    with pytest.raises(Reached):  # confirmed, the run starts
        rollspring.simulate(system, 1e9, confirm=True)


def test_simulate_refuses_outputs_that_cannot_fit_even_confirmed(system, monkeypatch) -> None:
    from rollspring.simulate import run

    monkeypatch.setattr(run, "system_arrays", _never)
    for confirm in (False, True):
        message = api_error(
            lambda confirm=confirm: rollspring.simulate(
                system, 1.0, n_output=10**12, confirm=confirm
            ),
            CostTooHigh,
        )
        assert "cannot fit in memory" in message
    cli = cli_error("simulate", "hoop-cylinder", "-T", "1", "--outputs", str(10**12), "--yes")
    assert message == in_api_words(cli)


def test_a_fixed_step_counts_in_the_estimate(system, monkeypatch) -> None:
    from rollspring.simulate import run

    monkeypatch.setattr(run, "system_arrays", _never)
    message = api_error(lambda: rollspring.simulate(system, 1e3, step=1e-9), CostTooHigh)
    assert "1e+12 yoshida4 steps" in message


def test_a_confirmed_run_runs(system, monkeypatch) -> None:
    """With a bound of 0 s every run needs confirming: a tiny run shows both sides."""
    from rollspring.analysis import costs

    monkeypatch.setattr(costs, "MAX_SECONDS", 0.0)
    message = api_error(lambda: rollspring.simulate(system, 0.05, n_output=11), CostTooHigh)
    assert message.endswith("or confirm it with confirm=True")
    run = rollspring.simulate(system, 0.05, n_output=11, confirm=True)
    assert run.status == "finished"


def test_derive_refuses_a_long_derivation_with_the_clis_estimate(tmp_path, monkeypatch) -> None:
    module = importlib.import_module("rollspring.analysis.derivation.derive")

    data = chain(200)
    monkeypatch.setattr(module, "symbolic_system", _never)
    message = api_error(lambda: rollspring.derive(data), CostTooHigh)
    assert message == in_api_words(cli_error("derive", write(tmp_path, "c.json", data)))
    with pytest.raises(Reached):
        rollspring.derive(data, confirm=True)


def test_derive_checks_its_arguments_before_the_work(system, monkeypatch) -> None:
    module = importlib.import_module("rollspring.analysis.derivation.derive")

    monkeypatch.setattr(module, "symbolic_system", _never)
    for arguments, start in [
        ({"method": "euler"}, "method: unknown method 'euler'"),
        ({"method": 5}, "method: must be a method name or a list of them"),
        ({"method": None}, "method: must be a method name or a list of them"),
        ({"symbols": "yes"}, "symbols: must be True or False"),
        ({"confirm": 1}, "confirm: must be True or False"),
        ({"budget": -1.0}, "budget: must be a positive number of seconds or None"),
        ({"budget": True}, "budget: must be a positive number of seconds or None"),
    ]:
        message = api_error(
            lambda arguments=arguments: rollspring.derive(system, **arguments), DerivationError
        )
        assert message.startswith(start), message


def test_build_report_refuses_a_long_report_with_the_clis_estimate(system, tmp_path, monkeypatch):
    from rollspring.service import documents

    monkeypatch.setattr(documents, "run_analysis", _never)  # the report's first work
    message = api_error(lambda: rollspring.build_report(system, duration=1e9), CostTooHigh)
    cli = cli_error("report", "hoop-cylinder", "-T", "1e9", "-o", str(tmp_path / "r.html"))
    assert message == in_api_words(cli)
    with pytest.raises(Reached):
        rollspring.build_report(system, duration=1e9, confirm=True)


def test_build_report_checks_its_arguments_before_the_work(system, monkeypatch) -> None:
    from rollspring.service import documents

    monkeypatch.setattr(documents, "run_analysis", _never)
    for arguments, kind, start in [
        ({"duration": 0.0}, ReportError, "duration: must be a positive number of seconds"),
        ({"duration": True}, ReportError, "duration: must be a positive number of seconds"),
        ({"duration": "1"}, ReportError, "duration: must be a positive number of seconds"),
        ({"rtol": 1e-300}, SimulationError, "rtol: must be between 1e-14 and 0.1"),
        ({"derivation": "no"}, ReportError, "derivation: must be True or False"),
        ({"confirm": 1}, ReportError, "confirm: must be True or False"),
    ]:
        message = api_error(
            lambda arguments=arguments: rollspring.build_report(system, **arguments), kind
        )
        assert message.startswith(start), message
    with pytest.raises(Reached):  # NumPy numbers are numbers
        rollspring.build_report(system, duration=np.int64(2))


def test_the_cli_keeps_its_words(system) -> None:
    """The estimate moved down a layer; the command line's message is what it was."""
    message = cli_error("simulate", "hoop-cylinder", "-T", "1e9")
    assert message.startswith("this run would take about ")
    assert message.endswith(
        "make it smaller (a shorter --duration, fewer --outputs) or confirm it with --yes"
    )
    from rollspring.service import costs

    assert costs.check_cost is rollspring.analysis.costs.check_cost
    assert costs.RTOL_RANGE == (1e-14, 0.1)


# ------------------------------------------------------------------------- worksheets


def test_worksheet_takes_numpy_integers_and_refuses_bools() -> None:
    sheet = rollspring.worksheet(np.int64(1), np.int64(7))
    assert (sheet.level, sheet.seed) == (1, 7)
    assert type(sheet.level) is int and type(sheet.seed) is int
    assert sheet.system == rollspring.worksheet(1, 7).system
    for level, seed in [(True, 1), (1, False), (1.0, 1), (1, -1), (5, 1)]:
        api_error(lambda level=level, seed=seed: rollspring.worksheet(level, seed), WorksheetError)


# ----------------------------------------------------------------------- the analysis' guard


def test_analyze_refuses_a_large_system_with_the_clis_estimate(tmp_path, monkeypatch) -> None:
    from rollspring.analysis import modal

    data = chain(6000)  # every mode of 6000 bodies: 6000 x 6000 shapes and forces
    monkeypatch.setattr(modal, "system_arrays", _never)
    message = api_error(lambda: rollspring.analyze(data, modes=6000), CostTooHigh)
    path = write(tmp_path, "c.json", data)
    assert message == in_api_words(cli_error("analyze", path, "--modes", "6000"))
    with pytest.raises(Reached):
        rollspring.analyze(data, confirm=True, modes=6000)
    with pytest.raises(Reached):  # its lowest modes need no confirming
        rollspring.analyze(data)


# ------------------------------------------------- the command line's --yes still reaches the work


def _reaches_the_work(args: list[str], module: str, name: str, monkeypatch) -> None:
    monkeypatch.delenv("ROLLSPRING_DEBUG", raising=False)
    monkeypatch.setattr(importlib.import_module(module), name, _never)
    result = runner.invoke(app, args)
    assert "confirm=True" not in result.output, result.output  # not refused by the API
    assert isinstance(result.exception, Reached) or "internal error: Reached" in result.stderr, (
        result.output
    )


def test_the_clis_yes_reaches_the_analysis(tmp_path, monkeypatch) -> None:
    path = write(tmp_path, "c.json", chain(1000))
    _reaches_the_work(
        ["analyze", path, "--yes"], "rollspring.analysis.modal", "system_arrays", monkeypatch
    )


@pytest.mark.parametrize(
    ("args", "module", "name"),
    [
        (["simulate", "hoop-cylinder", "-T", "1e9"], "rollspring.simulate.run", "system_arrays"),
        (["report", "hoop-cylinder", "-T", "1e9"], "rollspring.service.documents", "run_analysis"),
        (["derive", "CHAIN"], "rollspring.analysis.derivation.derive", "symbolic_system"),
    ],
    ids=["simulate", "report", "derive"],
)
def test_the_clis_yes_reaches_the_work(args, module, name, tmp_path, monkeypatch) -> None:
    args = [write(tmp_path, "c.json", chain(200)) if a == "CHAIN" else a for a in args]
    if args[0] == "report":
        args += ["-o", str(tmp_path / "r.html")]
    _reaches_the_work([*args, "--yes"], module, name, monkeypatch)

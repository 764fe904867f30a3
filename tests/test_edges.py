"""Trust at the edges (issue 24): the reproducers a hostile user found, each on the surface where
it was found (the command line, the Python API, HTTP).

``--on-slip continue`` when a body slips at once or early: before, SciPy's empty output lists
reached the stick-slip segment and every surface failed with ``'list' object has no attribute
'size'`` (CLI exit 1, a raw ``AttributeError`` from the API, HTTP 500).
"""

from __future__ import annotations

import json
import os
import stat
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import numpy as np
import pytest
from fastapi.testclient import TestClient
from typer.testing import CliRunner

import rollspring
from rollspring.cli import app
from rollspring.errors import CostTooHigh
from rollspring.model import load_system, preset_path, system_to_json
from rollspring.outputs.trajectory import summary_json
from rollspring.web import create_app

runner = CliRunner()
GOOD = preset_path("hoop-cylinder").read_text(encoding="utf-8")
HOOP_CYLINDER = load_system("hoop-cylinder")

#: Systems in which a body slips at t = 0 or soon after (issue 24, point 2), with the status
#: the run ends in and the first body to slip.
EARLY_SLIPS: dict[str, tuple[str, str, str]] = {
    # no gravity: N = 0, so any friction exceeds mu_s N at once; the bodies also leave the track
    "gravity-0": (GOOD.replace("gravity = 9.81", "gravity = 0.0"), "liftoff", "hoop"),
    # a light, stiff pair: the needed friction is about 5e5 N at once
    "light-stiff": (
        GOOD.replace("stiffness = 100.0", "stiffness = 1e6").replace("mass = 1.0", "mass = 1e-3"),
        "finished",
        "hoop",
    ),
    # a pull of 1e9 N on the cylinder's centre
    "force-1e9": (GOOD + '\n[[forces]]\nbody = "cylinder"\nfx = 1e9\n', "finished", "cylinder"),
    # a hoop rolling through the anchor its spring is fixed to
    "through-anchor": (
        'name = "through"\ngravity = 9.81\n'
        '[[anchors]]\nid = "post"\nx = 0.3\ny = 0.1\n'
        '[[bodies]]\nid = "hoop"\nshape = "hoop"\nmass = 1.0\nradius = 0.1\nx = 0.0\nv = 2.0\n'
        "mu_static = 1.0\n"
        '[[springs]]\nends = ["post", "hoop"]\nstiffness = 100.0\nrest_length = 0.0\n',
        "finished",
        "hoop",
    ),
}


@pytest.fixture(scope="module")
def client() -> Iterator[TestClient]:
    with TestClient(create_app(workers=1, budget=600.0)) as test_client:
        yield test_client


def _system(text: str, tmp_path: Path) -> rollspring.System:
    path = tmp_path / "system.toml"
    path.write_text(text, encoding="utf-8")
    return load_system(path)


def _check(summary: dict[str, Any], status: str, body: str) -> None:
    """A clean end: the expected status, the first slip at the right body, finite energy."""
    assert summary["status"] == status, summary["message"]
    assert summary["first_slip"]["body"] == body
    assert np.isfinite(summary["energy"])


@pytest.mark.parametrize("case", sorted(EARLY_SLIPS))
def test_on_slip_continue_from_an_early_slip_on_the_command_line(case: str, tmp_path: Path) -> None:
    text, status, body = EARLY_SLIPS[case]
    path = tmp_path / f"{case}.toml"
    path.write_text(text, encoding="utf-8")
    result = runner.invoke(
        app, ["simulate", str(path), "-T", "0.01", "--on-slip", "continue", "--json"]
    )
    assert result.exit_code == 0, result.output
    _check(json.loads(result.stdout), status, body)


@pytest.mark.parametrize("case", sorted(EARLY_SLIPS))
def test_on_slip_continue_from_an_early_slip_in_python(case: str, tmp_path: Path) -> None:
    text, status, body = EARLY_SLIPS[case]
    run = rollspring.simulate(_system(text, tmp_path), 0.01, on_slip="continue")
    _check(summary_json(run), status, body)
    assert run.t[0] == 0.0 and np.all(np.isfinite(run.x))


@pytest.mark.parametrize("case", sorted(EARLY_SLIPS))
def test_on_slip_continue_from_an_early_slip_over_http(
    case: str, client: TestClient, tmp_path: Path
) -> None:
    text, status, body = EARLY_SLIPS[case]
    system = system_to_json(_system(text, tmp_path))
    answer = client.post(
        "/api/simulate", json={"system": system, "duration": 0.01, "on_slip": "continue"}
    )
    assert answer.status_code == 200, answer.text
    _check(answer.json()["summary"], status, body)


# -- energy_tolerance has a floor (issue 24, point 8) --------------------------------------------


@pytest.mark.parametrize("tolerance", [1e-300, 1e-13, 5e-324])
def test_an_energy_tolerance_below_double_precision_is_refused_with_the_attainable_value(
    tolerance: float,
) -> None:
    """Before, 1e-300 hung: every retry shrank the step again and never passed."""
    with pytest.raises(rollspring.SimulationError) as raised:
        rollspring.simulate(HOOP_CYLINDER, 1.0, energy_tolerance=tolerance)
    message = str(raised.value)
    assert message.startswith(f"energy_tolerance: {tolerance!r} is below what double precision")
    assert message.endswith("the attainable relative energy error is about 1e-12")
    assert "\n" not in message


def test_the_energy_tolerance_floor_itself_is_accepted() -> None:
    run = rollspring.simulate(HOOP_CYLINDER, 0.5, energy_tolerance=1e-12)
    assert run.status in ("finished", "energy_error")


# -- numbers too large to print (issue 24, point 10) ---------------------------------------------


def test_an_integer_of_5000_digits_in_a_dict_is_a_one_line_error_naming_the_field() -> None:
    """Before, the error's own formatter failed (Python converts at most 4300 digits)."""
    data = system_to_json(HOOP_CYLINDER)
    data["gravity"] = 10**5000
    with pytest.raises(rollspring.ModelError) as raised:
        rollspring.system_from_dict(data)
    assert str(raised.value) == (
        "system: gravity: must be a number (got an integer of about 5001 digits)"
    )


def test_a_json_number_of_5000_digits_shows_no_python_advice(tmp_path: Path) -> None:
    path = tmp_path / "big.json"
    text = json.dumps(system_to_json(HOOP_CYLINDER))
    path.write_text(text.replace('"gravity": 9.81', '"gravity": ' + "9" * 5000))
    result = runner.invoke(app, ["analyze", str(path)])
    assert result.exit_code == 2
    assert result.stderr == f"error: {path}: a number has too many digits (at most 4300 are read)\n"


# -- durations beyond double precision, bad callbacks and patterns (issue 24, points 6 and 10) ----


@pytest.mark.parametrize(
    ("duration", "confirm"), [(1e308, False), (1e300, True), (1e15, True), (1e12, False)]
)
def test_a_duration_double_precision_cannot_resolve_is_refused_even_when_confirmed(
    duration: float, confirm: bool
) -> None:
    """Before: 1e308 a ZeroDivisionError, 1e300 with confirm an OverflowError."""
    with pytest.raises(rollspring.SimulationError) as raised:
        rollspring.simulate(HOOP_CYLINDER, duration, confirm=confirm)
    message = str(raised.value)
    assert message.startswith(f"duration: {duration:.3g} s needs ")
    assert message.endswith("whose times double precision resolves; a shorter duration")


def test_a_fixed_step_too_fine_for_the_duration_is_refused_even_when_confirmed() -> None:
    with pytest.raises(rollspring.SimulationError, match=r"about 1e\+15 steps of 0.001 s"):
        rollspring.simulate(HOOP_CYLINDER, 1e12, step=1e-3, confirm=True)


def test_progress_that_is_not_a_function_is_refused_before_the_run() -> None:
    """Before, ``simulate(progress=5)`` failed mid-run ('int' object is not callable)."""
    with pytest.raises(rollspring.SimulationError) as raised:
        rollspring.simulate(HOOP_CYLINDER, 0.1, progress=5)
    assert str(raised.value) == "progress: must be a function or None, got int"
    with pytest.raises(rollspring.RollspringError, match="progress: must be a function"):
        rollspring.sweep(HOOP_CYLINDER, {"springs.0.stiffness": [50.0]}, 0.1, progress="yes")


@pytest.mark.parametrize("pattern", [None, 3, {"hoop": 1}])
def test_a_chain_pattern_of_the_wrong_type_is_a_one_line_error(pattern: Any) -> None:
    """Before, ``chain(pattern=None)``: 'NoneType' object is not iterable."""
    with pytest.raises(rollspring.ModelError) as raised:
        rollspring.chain(pattern=pattern)
    assert str(raised.value).startswith("pattern: give one or more shapes, e.g. hoop,cylinder")


# -- chain starts (issue 24, point 10) ----------------------------------------------------------


@pytest.mark.parametrize(
    ("options", "expected"),
    [
        (  # was a pydantic message with its URL (an internal error)
            ["--pluck", "1", "--amplitude", "1e6"],
            "error: --amplitude: 1e+06 m moves the chain out of what a system file may hold "
            "(bodies[0].x: must be between -10000 and 10000 m",
        ),
        (  # was an OverflowError
            ["--packet", "1,1e308"],
            "error: --packet width: must be from 0.0005 m (a thousandth of the spacing; "
            "narrower is a pluck) to 20000 m, got 1e+308",
        ),
        (  # was a RuntimeWarning, then a chain with no initial condition and exit 0
            ["--packet", "1,1e-300"],
            "error: --packet width: must be from 0.0005 m",
        ),
    ],
)
def test_a_chain_start_out_of_range_is_a_one_line_error(
    options: list[str], expected: str, tmp_path: Path
) -> None:
    out = tmp_path / "c.toml"
    result = runner.invoke(app, ["chain", "--n", "8", *options, "--out", str(out)])
    assert result.exit_code == 2, result.output
    assert result.stderr.startswith(expected) and result.stderr.count("\n") == 1
    assert "pydantic" not in result.stderr and not out.exists()


def test_a_packet_width_within_range_still_makes_its_chain() -> None:
    at_rest = rollspring.chain(n=8)
    system = rollspring.chain(n=8, packet=(1.0, 2.0), amplitude=0.01)
    moved = np.array([b.x - r.x for b, r in zip(system.bodies, at_rest.bodies, strict=True)])
    assert 0.001 < np.max(np.abs(moved)) <= 0.01 + 1e-15  # displaced, never beyond the amplitude


# -- batches (issue 24, points 3 and 10) --------------------------------------------------------


def test_a_batch_step_too_fine_for_its_duration_is_a_one_line_error() -> None:
    """Before: 'Int value is too large' from the compiled kernel's step count."""
    with pytest.raises(rollspring.SimulationError) as raised:
        rollspring.simulate_batch(
            HOOP_CYLINDER, {"springs.0.stiffness": [100.0, 200.0]}, 1.0, step=1e-300
        )
    assert str(raised.value) == (
        "step: 1e-300 s takes about 1e+300 steps over 1 s; a batch takes at most 1e+08 "
        "(a longer step, or a shorter duration)"
    )


@pytest.mark.parametrize("values", [[True], True, [1.0, False], np.array([True, False])])
def test_a_batch_takes_no_bools_for_numbers(values: Any) -> None:
    with pytest.raises(rollspring.ModelError) as raised:
        rollspring.simulate_batch(HOOP_CYLINDER, {"bodies.hoop.mass": values}, 0.1)
    assert str(raised.value) == "parameters['bodies.hoop.mass']: must be numbers, not true/false"


# -- sweeps: counted, estimated and confirmed before any run (issue 24, points 3 and 4) ----------


_BILLION = {"bodies.hoop.mass": range(1, 10**9 + 1)}  # a range: nothing of 1e9 numbers is made


@pytest.mark.parametrize(
    ("run", "expected"),
    [
        (  # was NumPy's raw _ArrayMemoryError
            lambda: rollspring.simulate_batch(HOOP_CYLINDER, _BILLION, 1.0),
            "parameters['bodies.hoop.mass']: 1e+09 runs, more than one batch holds (1e+08); "
            "split the batch",
        ),
        (  # was a raw MemoryError (the API) or a store growing past 12 GB (the CLI)
            lambda: rollspring.sweep(HOOP_CYLINDER, _BILLION, 1.0),
            "--vary bodies.hoop.mass: the grid reaches 1e+09 runs, more than a sweep holds "
            "(1e+08); sweep it in parts",
        ),
    ],
    ids=["batch", "sweep"],
)
def test_a_billion_runs_are_refused_before_any_array_of_their_size(run: Any, expected: str) -> None:
    with pytest.raises(rollspring.RollspringError) as raised:
        run()
    assert str(raised.value) == expected


@pytest.mark.parametrize(
    ("run", "what", "steps"),
    [
        (
            lambda: rollspring.simulate_batch(HOOP_CYLINDER, {"bodies.hoop.mass": [1.0, 2.0]}, 1e9),
            "batch",
            "2 runs × about 7.2e+11 kahanli8 steps × 2 bodies",
        ),
        (  # was: sweep -T 1e9 started silently
            lambda: rollspring.sweep(HOOP_CYLINDER, {"springs.0.stiffness": [50.0, 100.0]}, 1e9),
            "sweep",
            "2 runs × about 7.2e+11 kahanli8 steps × 2 bodies",
        ),
    ],
    ids=["batch", "sweep"],
)
def test_runs_above_the_bound_are_estimated_and_need_confirming(
    run: Any, what: str, steps: str
) -> None:
    with pytest.raises(CostTooHigh) as raised:
        run()
    message = str(raised.value)
    assert message.startswith(f"this {what} would take about ")
    assert steps in message
    assert message.endswith("or confirm it with confirm=True")


@pytest.mark.parametrize("count", ["1000000000", "99999999999999999999"])
def test_a_range_of_too_many_values_is_refused_on_the_command_line(
    count: str, tmp_path: Path
) -> None:
    out = tmp_path / "s.zarr"
    spec = f"bodies.hoop.mass=1:2:{count}"
    result = runner.invoke(
        app, ["sweep", "hoop-cylinder", "-T", "1", "--vary", spec, "--out", str(out)]
    )
    assert result.exit_code == 2, result.output
    assert result.stderr.startswith(f"error: --vary {spec}: ")
    assert "more than a sweep holds (1e+08 runs)" in result.stderr
    assert not out.exists()


# -- the web takes numbers as numbers (issue 24, point 10) ----------------------------------------


@pytest.mark.parametrize(
    ("field", "value", "words"),
    [
        ("duration", True, "duration: must be a number (got true)"),
        ("duration", "1", "duration: must be a number (got '1')"),
        ("outputs", 11.5, "outputs: must be a whole number (got 11.5)"),
        ("linear", 1, "linear: must be true or false (got 1)"),  # JSON's words (issue 26)
    ],
)
def test_the_web_refuses_a_bool_or_text_for_a_number_with_422(
    client: TestClient, field: str, value: Any, words: str
) -> None:
    """Before, ``"duration": true`` was taken as 1 s."""
    request = {"system": system_to_json(HOOP_CYLINDER), "duration": 0.5, field: value}
    answer = client.post("/api/simulate", json=request)
    assert answer.status_code == 422
    assert answer.json()["message"] == words


# -- a long chain's mode start: seconds, not minutes (issue 24, point 4) --------------------------


@pytest.mark.parametrize(("mode", "walls"), [(1, "none"), (299, "none"), (150, "both")])
def test_a_long_chains_mode_from_the_tridiagonal_solver_is_the_dense_ones(
    mode: int, walls: str, monkeypatch: pytest.MonkeyPatch
) -> None:
    """Beyond 500 bodies a chain's mode comes from the tridiagonal eigensolver, one vector
    (before: K assembled as a sum of n x n outer products and a dense eigh: --n 3000 took 75 s,
    --n 20000 over two minutes; now 1 s and 4 s)."""
    from rollspring.model import chains

    options = {"n": 600, "pattern": "hoop,cylinder", "walls": walls, "mode": mode}
    fast = rollspring.chain(**options)
    monkeypatch.setattr(chains, "_DENSE_MODES", 10**9)
    dense = rollspring.chain(**options)
    x_fast = np.array([b.x for b in fast.bodies])
    x_dense = np.array([b.x for b in dense.bodies])
    assert np.max(np.abs(x_fast - x_dense)) < 1e-10 * 0.01  # of the 0.01 m amplitude
    assert np.max(np.abs(x_fast - x_fast.round(1))) > 1e-3  # displaced along the mode


# -- every output place decided by one function (issue 24, point 1) ------------------------------


@pytest.mark.parametrize("which", ["sheet", "solutions"])
def test_worksheet_out_refuses_a_fifo_and_writes_nothing(which: str, tmp_path: Path) -> None:
    """Before, ``worksheet --out`` replaced a FIFO (or a device node) by a regular file."""
    out = tmp_path / "sheet.md"
    fifo = out if which == "sheet" else tmp_path / "sheet-solutions.md"
    os.mkfifo(fifo)
    result = runner.invoke(app, ["worksheet", "--level", "1", "--seed", "1", "--out", str(out)])
    assert result.exit_code == 2, result.output
    assert result.stderr == (
        f"error: --out {fifo}: cannot write there (it is not a regular file: a device, FIFO "
        "or socket)\n"
    )
    assert sorted(p.name for p in tmp_path.iterdir()) == [fifo.name]
    assert stat.S_ISFIFO(fifo.stat().st_mode)


@pytest.fixture(scope="module")
def small_store(tmp_path_factory: pytest.TempPathFactory) -> Path:
    store = tmp_path_factory.mktemp("store") / "s.zarr"
    vary = {"springs.0.stiffness": [50.0, 100.0], "bodies.hoop.mass": [1.0, 2.0]}
    rollspring.sweep(HOOP_CYLINDER, vary, 0.5, out=store)
    return store


@pytest.mark.parametrize(
    ("options", "error"),
    [
        (["--dpi", "1e9"], "error: --dpi: must be a number > 0 up to 1200, got 1000000000.0\n"),
        (["-o", "FIFO.png"], "cannot write there (it is not a regular file: a device, FIFO"),
    ],
)
def test_sweep_plot_checks_dpi_and_its_place_first(
    options: list[str], error: str, small_store: Path, tmp_path: Path
) -> None:
    """Before: --dpi 1e9 reached Matplotlib's renderer (an internal error), and -o replaced a
    FIFO by a regular file."""
    fifo = tmp_path / "FIFO.png"
    os.mkfifo(fifo)
    options = [str(fifo) if option == "FIFO.png" else option for option in options]
    if "-o" not in options:
        options += ["-o", str(tmp_path / "map.png")]
    args = ["sweep-plot", str(small_store), "--x", "springs.0.stiffness"]
    result = runner.invoke(app, [*args, "--y", "bodies.hoop.mass", "-m", "status", *options])
    assert result.exit_code == 2, result.output
    assert error in result.stderr and result.stderr.count("\n") == 1
    assert sorted(p.name for p in tmp_path.iterdir()) == ["FIFO.png"]


def test_sweep_estimates_and_asks_for_yes_on_the_command_line(tmp_path: Path) -> None:
    out = tmp_path / "s.zarr"
    args = ["sweep", "hoop-cylinder", "-T", "1e9", "--vary", "springs.0.stiffness=50,100"]
    result = runner.invoke(app, [*args, "--out", str(out)])
    assert result.exit_code == 2, result.output
    assert result.stderr.startswith("error: this sweep would take about ")
    assert result.stderr.endswith(
        "make it smaller (fewer --vary values, a shorter --duration) or confirm it with --yes\n"
    )
    assert not out.exists()


def test_analyze_takes_sparse_as_a_bool_or_none() -> None:
    """Before, ``analyze(sparse="yes")`` took any truthy value."""
    with pytest.raises(rollspring.AnalysisError) as raised:
        rollspring.analyze(HOOP_CYLINDER, sparse="yes")
    assert str(raised.value) == "sparse: must be True, False or None (by size), got 'yes'"


def test_derive_needs_at_least_one_method() -> None:
    """Before, ``derive(method=[])`` returned an empty derivation without a word."""
    with pytest.raises(rollspring.RollspringError, match="method: give at least one method"):
        rollspring.derive(HOOP_CYLINDER, method=[])


def test_the_progress_bar_is_not_drawn_off_a_terminal(capsys: pytest.CaptureFixture[str]) -> None:
    """A command's error after its bar appeared (a slow track under load) came after a blank
    line: the bar's last frame went to the captured stderr. Off a terminal it is not drawn."""
    from rollspring.cli.common import ProgressBar

    with ProgressBar("working", delay=0.0) as bar:
        bar(0.5)
        bar(1.0)
    assert capsys.readouterr().err == ""


#: Three bodies of one radius joined by springs of rest length 0 (a reviewer's random draw):
#: at the equilibrium every spring's ends meet, where its direction is undefined but its force
#: k d and stiffness k (dP/dq_i . dP/dq_j) are smooth.
ZERO_LENGTH = {
    "gravity": 9.81,
    "bodies": [
        {
            "id": "hoop",
            "shape": "hoop",
            "mass": 0.9287020701322124,
            "radius": 0.1,
            "x": 0.1220011694981521,
        },
        {
            "id": "cylinder",
            "shape": "cylinder",
            "mass": 1.0,
            "radius": 0.1,
            "x": 0.6231763158945975,
        },
        {"id": "sphere", "shape": "sphere", "mass": 1.0, "radius": 0.1, "x": 1.0061302244168568},
    ],
    "springs": [
        {"ends": ["hoop", "cylinder"], "stiffness": 20.24683345251472, "rest_length": 0.0},
        {"ends": ["cylinder", "sphere"], "stiffness": 82.84008734924846, "rest_length": 0.0},
    ],
}


def test_springs_of_rest_length_zero_whose_ends_meet_at_the_equilibrium(tmp_path: Path) -> None:
    """Before: ``analyze`` and ``simulate`` of this valid system printed RuntimeWarnings (0/0 in
    the spring's direction and tension per length) and ended in an internal error. Now the
    equilibrium has the ends meeting, the modes are those of K_ij = sum_s k_s s_i s_j sigma_si
    sigma_sj (a zero-length spring's stiffness k dP/dq_i . dP/dq_j, whatever its direction),
    and a run conserves its energy."""
    system = rollspring.system_from_dict(ZERO_LENGTH)
    analysis = rollspring.analyze(system)
    positions = np.array([b["x"] for b in ZERO_LENGTH["bodies"]]) + 0.1 * analysis.equilibrium.q
    assert np.allclose(positions, positions[0], rtol=0, atol=1e-12)  # the ends meet
    k1, k2 = (s["stiffness"] for s in ZERO_LENGTH["springs"])
    stiffness = 0.01 * np.array([[k1, -k1, 0.0], [-k1, k1 + k2, -k2], [0.0, -k2, k2]])
    inertia = np.array(
        [
            (1 + g) * b["mass"] * 0.01
            for g, b in zip((1.0, 0.5, 0.4), ZERO_LENGTH["bodies"], strict=True)
        ]
    )
    root = 1.0 / np.sqrt(inertia)
    expected = np.linalg.eigvalsh(root[:, None] * stiffness * root)  # omega^2, ascending
    got = np.sort([m.omega for m in analysis.modes]) ** 2
    assert np.allclose(got, expected, rtol=1e-9, atol=1e-9 * expected[-1])
    run = rollspring.simulate(system, 2.0)
    assert np.all(np.isfinite(run.energy))
    assert abs(run.energy[-1] - run.energy[0]) <= 1e-8 * abs(run.energy[0])
    path = tmp_path / "zero.json"
    path.write_text(json.dumps(ZERO_LENGTH))
    result = runner.invoke(app, ["analyze", str(path)])
    assert result.exit_code == 0, result.output
    assert "Warning" not in result.output and "internal error" not in result.output


def test_a_stiffness_matrix_that_is_not_finite_is_a_one_line_analysis_error() -> None:
    """The eigensolver's check of a non-finite K (a spring of non-zero rest length squeezed to
    zero length: tension per length -inf) was a bare ``ValueError`` ("array must not contain
    infs or NaNs"), an internal error on the command line; now a one-line AnalysisError (still a
    ValueError, as SciPy's check raises)."""
    from rollspring.errors import AnalysisError, NotFiniteError

    stiffness = np.array([[1.0, -np.inf], [-np.inf, 2.0]])
    with pytest.raises(NotFiniteError, match="not finite in this configuration") as raised:
        rollspring.normal_modes(np.diag([1.0, 2.0]), stiffness)
    assert isinstance(raised.value, AnalysisError) and isinstance(raised.value, ValueError)
    assert "\n" not in str(raised.value)

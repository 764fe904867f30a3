"""A generated hostile-input suite (issue 24, point 7): Hypothesis draws the arguments of the
Python entry points and the command line's options from sets of ordinary, extreme and wrong
values (bools for numbers, text, NaN, infinities, 1e300, negative counts), 600 cases in all.

Every case ends one of two ways: a clean result, or one :class:`~rollspring.errors.RollspringError`
of one line (on the command line: ``error: ...``, exit code 2, nothing on stdout). Never another
exception, a traceback, an "internal error", a warning (warnings are errors in this suite) or a
file left behind. Runs that would be long are refused by their cost estimate (nothing here
confirms), so every case is quick.
"""

from __future__ import annotations

import math
from pathlib import Path
from typing import Any

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st
from typer.testing import CliRunner

import rollspring
from rollspring.cli import app
from rollspring.errors import RollspringError
from rollspring.model import load_system
from tests.conftest import moving_hoop_cylinder
from tests.fit_data import Truth, recording, write_csv

runner = CliRunner()
SYSTEMS = {name: load_system(name) for name in ("hoop-cylinder", "two-masses", "frictionless")}

#: Values every numeric argument is drawn from: good ones (kept small, so that a run is quick)
#: and bad ones of every kind.
NUMBERS = st.sampled_from(
    [
        1e-3,
        0.05,
        1.0,
        0.0,
        -1.0,
        math.nan,
        math.inf,
        -math.inf,
        1e300,
        1e-300,
        5e-324,
        True,
        False,
        "1",
        None,
        [1.0],
        10**400,
    ]
)
COUNTS = st.sampled_from([2, 11, 101, 0, 1, -5, 1.5, True, "11", None, 10**12, 2**63])
CHOICES = st.sampled_from(["stop", "continue", "auto", "verlet", "dop853", "x", "", None, 1, True])
SETTINGS = settings(max_examples=200, deadline=None, suppress_health_check=[HealthCheck.too_slow])


def _clean(call: Any) -> Any:
    """Run ``call``: its result, or None when it raised one one-line RollspringError."""
    try:
        return call()
    except RollspringError as exc:
        message = str(exc)
        assert message and "\n" not in message, repr(message)
        assert "Traceback" not in message and "internal error" not in message
        return None


@SETTINGS
@given(
    system=st.sampled_from(sorted(SYSTEMS)),
    duration=NUMBERS,
    rtol=st.sampled_from([1e-8, 1e-4, 1e-14, 0.1, 0.0, 1.0, -1e-8, math.nan, True, "1e-8"]),
    integrator=CHOICES,
    on_slip=CHOICES,
    n_output=COUNTS,
    energy_tolerance=st.sampled_from([None, 1e-6, 1e-12, 1e-300, -1.0, math.nan, True]),
    step=st.sampled_from([None, 1e-3, 1e-300, 10.0, -1.0, math.inf, True, "0.001"]),
)
def test_simulate_any_arguments(
    system: str,
    duration: Any,
    rtol: Any,
    integrator: Any,
    on_slip: Any,
    n_output: Any,
    energy_tolerance: Any,
    step: Any,
) -> None:
    options = {"rtol": rtol, "integrator": integrator, "on_slip": on_slip, "step": step}
    options |= {"n_output": n_output, "energy_tolerance": energy_tolerance}
    run = _clean(lambda: rollspring.simulate(SYSTEMS[system], duration, **options))
    if run is not None:
        assert run.status in ("finished", "slip", "liftoff", "energy_error", "nonfinite")
        assert run.t[0] == 0.0 and np.all(np.diff(run.t) > 0)


@SETTINGS
@given(
    values=st.sampled_from(
        [
            [1.0, 2.0],
            [1.0],
            1.5,
            [],
            [[1.0]],
            [True],
            ["a"],
            [math.nan],
            [1e308],
            [-1.0],
            np.array([0.5, 2.0]),
            range(3),
            None,
            "1,2",
        ]
    ),
    path=st.sampled_from(["bodies.hoop.mass", "springs.0.stiffness", "gravity", "bodies.x.mass"]),
    duration=NUMBERS,
    step=st.sampled_from([None, 1e-3, 1e-300, -1.0, True]),
    integrator=CHOICES,
    n_output=COUNTS,
)
def test_simulate_batch_any_arguments(
    values: Any, path: str, duration: Any, step: Any, integrator: Any, n_output: Any
) -> None:
    result = _clean(
        lambda: rollspring.simulate_batch(
            SYSTEMS["hoop-cylinder"],
            {path: values},
            duration,
            step=step,
            integrator=integrator,
            n_output=n_output,
        )
    )
    if result is not None:
        assert len(result.status_names) >= 1


@SETTINGS
@given(
    n=COUNTS,
    pattern=st.sampled_from(["hoop", "hoop,cylinder", "ghost", "", None, 3, ["sphere", "shell"]]),
    spacing=NUMBERS,
    amplitude=NUMBERS,
    start=st.sampled_from(
        [
            {},
            {"pluck": 1},
            {"pluck": 0},
            {"pluck": True},
            {"packet": (1.0, 2.0)},
            {"packet": (1.0, 1e-300)},
            {"packet": (1e9, 1.0)},
            {"packet": "1,2"},
            {"mode": 1},
        ]
    ),
)
def test_chain_any_arguments(
    n: Any, pattern: Any, spacing: Any, amplitude: Any, start: dict[str, Any]
) -> None:
    if isinstance(n, int) and not isinstance(n, bool) and n > 300:
        n = 300  # the chain itself is the subject here, not its size (bounded elsewhere)
    system = _clean(
        lambda: rollspring.chain(
            n=n, pattern=pattern, spacing=spacing, amplitude=amplitude, **start
        )
    )
    if system is not None:
        assert len(system.bodies) == n


@settings(max_examples=100, deadline=None)
@given(
    command=st.sampled_from(["simulate", "analyze", "animate", "report", "derive", "export"]),
    option=st.sampled_from(
        [
            "-T",
            "--duration",
            "--rtol",
            "--outputs",
            "--on-slip",
            "--format",
            "--dpi",
            "--fps",
            "--method",
            "--speed",
        ]
    ),
    value=st.sampled_from(
        ["0", "-1", "nan", "inf", "1e300", "1e-300", "true", "", "abc", "0.05", "1", "x" * 300]
    ),
)
def test_the_command_line_with_any_option(
    command: str, option: str, value: str, tmp_path_factory: Any
) -> None:
    folder: Path = tmp_path_factory.mktemp("out")
    args = [command, "hoop-cylinder", option, value]
    if command in ("report", "animate", "export"):
        args += ["-o", str(folder / {"report": "r.html", "animate": "a.gif"}.get(command, "m.xml"))]
    result = runner.invoke(app, args)
    assert result.exit_code in (0, 2), (args, result.output)
    assert "Traceback" not in result.output and "internal error" not in result.output
    if result.exit_code == 2:
        assert result.stdout == "" and result.stderr.startswith("error: "), result.output
        assert result.stderr.count("\n") == 1, result.stderr
        assert list(folder.iterdir()) == [], args  # nothing written, not even half


@pytest.fixture(scope="module")
def measured(tmp_path_factory: Any) -> Path:
    """A short recording of the paper's hoop and cylinder (closed form, 1 mm of noise)."""
    t, x, phi = recording(Truth(c=0.2), duration=1.0, fps=30.0, seed=2)
    return write_csv(tmp_path_factory.mktemp("lab") / "tracks.csv", t, x, phi)


PATHS = st.sampled_from(
    [
        "springs.0.stiffness",
        "springs.0.damping",
        "bodies.hoop.mass",
        "bodies.cylinder.rolling_resistance",
        "springs.9.stiffness",
        "bodies.nobody.mass",
        "bodies.hoop.shape",
        "bodies.hoop.x",
        "gravity",
        "",
        "springs..stiffness",
        1,
        None,
        True,
    ]
)


@settings(max_examples=60, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(
    free=st.one_of(st.lists(PATHS, max_size=3), PATHS, st.none()),
    mapping=st.sampled_from([None, {}, {"hoop": "hoop"}, {"x": "hoop"}, {"hoop": 1}, "hoop", 3]),
    fix_initial=st.sampled_from([False, True, "yes", 1, None, 0.0]),
    claims=st.sampled_from([True, False, "no", 1]),
    seed=st.sampled_from([0, 7, -1, 1.5, True, "1", None, 2**70]),
    confirm=st.sampled_from([False, True, "yes", 1, None]),
)
def test_fit_any_arguments(
    measured: Path,
    free: Any,
    mapping: Any,
    fix_initial: Any,
    claims: Any,
    seed: Any,
    confirm: Any,
) -> None:
    _clean(
        lambda: rollspring.fit(
            measured,
            "hoop-cylinder",
            free=free,
            mapping=mapping,
            fix_initial=fix_initial,
            claims=claims,
            seed=seed,
            confirm=confirm,
        )
    )


@pytest.fixture(scope="module")
def filmed(tmp_path_factory: Any) -> Path:
    """Half a second of the paper's hoop and cylinder rolling, 640×360 at 30 fps (16 frames)."""
    from rollspring.lab.synthetic import Camera, exact_motion, write_video

    camera = Camera(fps=30, seed=3)
    motion = exact_motion(MOVING, camera.frame_times(0.5))
    return write_video(tmp_path_factory.mktemp("film") / "film.mp4", MOVING, motion, camera)


MOVING = moving_hoop_cylinder()


@settings(max_examples=30, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(
    start=st.sampled_from([None, 0.0, 0.1, 0.4, 5.0, -1.0, math.nan, math.inf, True, "0"]),
    stop=st.sampled_from([None, 0.3, 0.05, 0.0, 1e300, -1.0, math.nan, True, "1"]),
    scale=st.sampled_from([None, 700.0, 0.0, -1.0, math.inf, math.nan, True, "700"]),
    confirm=st.sampled_from([False, True, "yes", 1, None]),
)
def test_track_any_arguments(filmed: Path, start: Any, stop: Any, scale: Any, confirm: Any) -> None:
    """The estimate from the header comes after the arguments are checked: any of them is one
    line or a result, and a tracking estimated above the bound (every one here, the bound
    lowered) is refused unless confirmed."""
    from rollspring.analysis import costs

    with pytest.MonkeyPatch.context() as patch:
        patch.setattr(costs, "MAX_SECONDS", 1e-9)
        result = _clean(
            lambda: rollspring.track(
                filmed, MOVING, start=start, stop=stop, scale=scale, confirm=confirm
            )
        )
    if result is not None:
        assert confirm is True and result.t.size >= 1


@settings(max_examples=40, deadline=None)
@given(
    option=st.sampled_from(["--free", "--map", "--figure", "-o", "--system"]),
    value=st.sampled_from(
        ["", "springs.0.stiffness", "nope", "hoop=cylinder", "=", "x" * 300, "a.png", "nan"]
    ),
)
def test_the_fit_command_with_any_option(
    measured: Path, option: str, value: str, tmp_path_factory: Any
) -> None:
    folder: Path = tmp_path_factory.mktemp("fitout")
    args = ["fit", str(measured), "--free", "springs.0.stiffness", option, value]
    if option in ("--figure", "-o"):
        args[-1] = str(folder / value) if value else value
    result = runner.invoke(app, args)
    assert result.exit_code in (0, 2), (args, result.output)
    assert "Traceback" not in result.output and "internal error" not in result.output
    if result.exit_code == 2:
        assert result.stderr.startswith("error: "), result.output
        assert result.stderr.count("\n") == 1, result.stderr
        assert list(folder.iterdir()) == [], args  # nothing written, not even half

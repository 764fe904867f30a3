"""Runs of a batch are independent (issue 11): every run equals the same run alone, bit for bit
with the same step, integrator and metric sampling, including batches that mix ordinary runs
with extreme ones (tiny or huge masses and stiffnesses), which get their own status and message
without touching their neighbours. Also: the one status enum, the one argument validator and
the integrator objects shared by single runs and batches."""

from __future__ import annotations

import math
import re

import numpy as np
import pytest

import rollspring
from rollspring.errors import ModelError, SimulationError
from rollspring.simulate import Status, kernels, simulate, simulate_batch
from rollspring.simulate.batch import SCHEMES, STATUS_NAMES
from rollspring.simulate.integrators import INTEGRATORS, Integrator
from rollspring.simulate.status import FLAG_MEANINGS, FLAG_VALUES
from tests.conftest import body, make_system, spring

#: Every per-run array of a BatchResult.
PER_RUN = (
    "status",
    "first_slip_time",
    "first_slip_body",
    "period_measured",
    "cm_amplitude",
    "stationary_amplitude",
    "max_friction_ratio",
    "min_normal_force",
    "energy_error",
    "final_x",
    "final_v",
    "omega",
)


def bits(values) -> np.ndarray:
    """The exact bits of numbers (so -0.0 differs from 0.0 and NaN equals NaN)."""
    values = np.asarray(values)
    return values.view(np.uint64) if values.dtype == np.float64 else values


def alone(system, parameters, run, duration, like, **kwargs):
    """Run ``run`` of ``parameters`` as a batch of its own, with the step, integrator and metric
    sampling of the batch ``like``."""
    one = {
        key: np.atleast_1d(np.asarray(value, dtype=float))[run : run + 1]
        if np.ndim(value)
        else value
        for key, value in parameters.items()
    }
    return simulate_batch(
        system,
        one,
        duration,
        step=like.step,
        integrator=like.integrator,
        metric_every=like.metric_every,
        **kwargs,
    )


def assert_same_plan(a, b):
    """Two batches stepped with the same step, step count, metric sampling and integrator."""
    assert (a.step, a.n_steps, a.metric_every, a.integrator) == (
        b.step,
        b.n_steps,
        b.metric_every,
        b.integrator,
    )


def assert_same_batch(a, b):
    """Every run of ``a`` is bit for bit the same run of ``b``."""
    assert_same_plan(a, b)
    for name in PER_RUN:
        mine, theirs = getattr(a, name), getattr(b, name)
        assert mine.dtype == theirs.dtype and mine.shape == theirs.shape, name
        assert np.array_equal(bits(mine), bits(theirs)), name


def assert_same_run(batch, run, single):
    """Row ``run`` of ``batch`` is bit for bit the only row of ``single``."""
    assert single.n_runs == 1
    assert_same_plan(single, batch)
    for name in PER_RUN:
        mine, theirs = getattr(batch, name)[run], getattr(single, name)[0]
        assert np.array_equal(bits(mine), bits(theirs)), (name, run, mine, theirs)
    assert single.messages[0] == re.sub(r"^run \d+", "run 0", batch.messages[run])
    if batch.x is not None:
        assert np.array_equal(bits(batch.x[run]), bits(single.x[0]))


# --------------------------------------------------------------------------------------------
# the examples


def test_a_value_a_system_file_refuses_is_refused():
    """Issue 24: a batch took a mass of 1e308 (or 1e-308: issue 11 then gave that run the status
    ``invalid``) that a system file refuses; now every value is held to the file's range, with
    the key, the range and the first run outside it."""
    system = rollspring.load_system("hoop-cylinder")
    for value in (1e308, 1e-308, 1e-320):
        with pytest.raises(ModelError) as raised:
            simulate_batch(system, {"bodies.hoop.mass": [1.0, value]}, 2.0)
        assert str(raised.value) == (
            "parameters['bodies.hoop.mass']: must be between 1e-06 and 1e+06 kg, the verified "
            f"range a system file takes (run 1 has {value!r})"
        )
    with pytest.raises(ModelError, match=r"springs.0.stiffness'\]: must be between 1e-06 and"):
        simulate_batch(system, {"springs.0.stiffness": [100.0, 1e300]}, 2.0)
    with pytest.raises(ModelError, match=r"must be between 0 and 1e\+06, the verified range"):
        simulate_batch(system, {"bodies.hoop.mu_static": [math.inf, 1e7]}, 2.0)


@pytest.mark.parametrize(
    ("values", "words"),
    [
        (
            {"bodies.hoop.mass": 1e-6, "springs.0.stiffness": 1e9},
            ["bodies.hoop.mass = 1e-06", "springs.0.stiffness = 1e+09", "rad/s", "resolved"],
        ),
        (
            {"bodies.cylinder.mass": 1e-5, "springs.0.stiffness": 1e9},
            ["bodies.cylinder.mass = 1e-05", "rad/s", "steps"],
        ),
    ],
)
def test_an_extreme_run_gets_its_own_status_not_an_exception(values, words):
    """Issue 11: a run far faster than its neighbours (here within the file's ranges) is
    ``unresolved`` with a one-line message, and its neighbour is itself alone (floating-point
    errors raised, tests/conftest.py)."""
    system = rollspring.load_system("hoop-cylinder")
    base = {"bodies.hoop.mass": 1.0, "bodies.cylinder.mass": 1.0, "springs.0.stiffness": 100.0}
    mixed = simulate_batch(system, {k: [base[k], v] for k, v in values.items()}, 2.0)
    single = simulate_batch(system, {k: [base[k]] for k in values}, 2.0)
    assert list(mixed.status) == [Status.FINISHED, Status.UNRESOLVED]
    assert_same_run(mixed, 0, single)
    for word in words:
        assert word in mixed.messages[1]
    assert "\n" not in mixed.messages[1]


# --------------------------------------------------------------------------------------------
# mixed batches, run by run


def mixed_parameters():
    """Ordinary runs of the paper's pair interleaved with extreme ones."""
    mass = [1.0, 1e-6, 1.3, 1e-5, 0.7, 1e6, 1e-6, 1.0, 2.0, 1.0]
    stiffness = [100.0, 1e9, 150.0, 1e9, 80.0, 100.0, 3e8, 1e-6, 120.0, 100.0]
    mu = [1.0, 1.0, 0.04, 1.0, 1.0, 1.0, 1.0, 1.0, math.inf, 0.02]
    return {"bodies.hoop.mass": mass, "springs.0.stiffness": stiffness, "bodies.hoop.mu_static": mu}


ORDINARY = [0, 2, 4, 8, 9]  # 2 and 9 slip, 8 cannot


def test_every_run_of_a_mixed_batch_equals_itself_alone():
    system = rollspring.load_system("hoop-cylinder")
    parameters = mixed_parameters()
    duration = 1.5
    mixed = simulate_batch(system, parameters, duration, keep_trajectories=True, n_output=31)
    names = list(mixed.status_names)
    assert names[1] == names[3] == names[6] == "unresolved"
    assert {names[i] for i in ORDINARY} == {"finished", "slip"}
    assert names[2] == names[9] == "slip" and names[8] == "finished"
    # the extremes take no part in the choice of the step: that of the ordinary runs
    ordinary = simulate_batch(
        system,
        {k: np.asarray(v)[ORDINARY] for k, v in parameters.items()},
        duration,
        keep_trajectories=True,
        n_output=31,
    )
    assert (mixed.step, mixed.integrator, mixed.metric_every) == (
        ordinary.step,
        ordinary.integrator,
        ordinary.metric_every,
    )
    for row, run in enumerate(ORDINARY):
        for name in PER_RUN:
            assert np.array_equal(
                bits(getattr(mixed, name)[run]), bits(getattr(ordinary, name)[row])
            ), name
    # every run, ordinary or not, is itself alone (a huge mass or a tiny stiffness is integrated)
    for run in range(mixed.n_runs):
        if names[run] == "unresolved":  # relative to a step chosen from rtol: alone, too
            single = simulate_batch(
                system, {k: np.asarray(v)[run : run + 1] for k, v in parameters.items()}, duration
            )
            assert single.status[0] == Status.UNRESOLVED
            assert single.messages[0] == mixed.messages[run].replace(f"run {run}", "run 0", 1)
            assert np.all(np.isnan(single.final_x)) and np.all(np.isnan(mixed.final_x[run]))
            continue
        single = alone(
            system, parameters, run, duration, mixed, keep_trajectories=True, n_output=31
        )
        assert_same_run(mixed, run, single)
        assert bool(single.messages[0]) == (names[run] == "invalid")


def test_a_fixed_step_integrates_extreme_runs_by_themselves():
    """With ``step=`` nothing is unresolved: a run the step cannot follow is integrated anyway
    (here it slips or overflows at once) and its neighbours do not notice."""
    system = rollspring.load_system("hoop-cylinder")
    parameters = mixed_parameters()
    mixed = simulate_batch(system, parameters, 1.0, step=2e-3, metric_every=3)
    assert mixed.metric_every == 3 and mixed.integrator == "yoshida4"
    # the runs far too fast for the step slip at once (their frictions swing past mu_s N)
    assert [mixed.status_names[run] for run in (1, 3, 6)] == ["slip", "slip", "slip"]
    assert np.all(mixed.first_slip_time[[1, 3, 6]] <= 2e-3)
    assert not np.any(mixed.status == Status.UNRESOLVED)
    for run in range(mixed.n_runs):
        assert_same_run(mixed, run, alone(system, parameters, run, 1.0, mixed))


def test_the_kernel_does_not_depend_on_the_values_of_the_other_runs():
    """Choices that used to follow the values of all the runs now follow the keys: an end at
    a height equal to the radius (at the centre) in one run and off it in another, a body that
    cannot slip (mu_s = inf) in one run only, two bodies of one radius (a horizontal spring) in
    one run only, and a sweep cut into chunks."""
    system = make_system(
        [
            body("a", "hoop", radius=0.1, x=0.0),
            body("b", "cylinder", radius=0.1, x=0.6),
            body("c", "sphere", radius=0.08, x=1.2, v=0.1),
        ],
        [
            spring("a", "b", stiffness=90.0, rest_length=0.55, at=[{"height": 0.1}, {}]),
            spring("b", "c", stiffness=60.0, rest_length=0.6),
        ],
    )
    parameters = {
        "bodies.a.radius": [0.1, 0.12, 0.1, 0.09],
        "bodies.b.radius": [0.1, 0.1, 0.11, 0.1],
        "bodies.a.mu_static": [math.inf, 0.5, 0.05, math.inf],
        "springs.1.stiffness": [60.0, 70.0, 50.0, 65.0],
    }
    whole = simulate_batch(system, parameters, 2.0, rtol=1e-9)
    assert whole.status[2] == Status.SLIP
    for run in range(whole.n_runs):
        assert_same_run(whole, run, alone(system, parameters, run, 2.0, whole))
    # a sweep fixes the step and sampling once and runs the grid in chunks
    first = simulate_batch(
        system,
        {k: v[:2] for k, v in parameters.items()},
        2.0,
        step=whole.step,
        integrator=whole.integrator,
        metric_every=whole.metric_every,
    )
    for run in range(2):
        for name in PER_RUN:
            assert np.array_equal(
                bits(getattr(first, name)[run]), bits(getattr(whole, name)[run])
            ), name


# --------------------------------------------------------------------------------------------
# one status, one validator, one set of integrators


def test_one_status_enum_with_messages():
    assert [int(s) for s in Status] == list(range(7))
    assert FLAG_VALUES == tuple(range(7))
    assert FLAG_MEANINGS == "finished nonfinite slip liftoff energy_error invalid unresolved"
    assert STATUS_NAMES == {int(s): s.label for s in Status}
    for status in Status:
        assert status.message and "\n" not in status.message
        assert Status.from_label(status.label) is status
    with pytest.raises(ValueError, match="unknown status 'lost'"):
        Status.from_label("lost")
    trajectory = simulate(rollspring.load_system("hoop-cylinder"), 0.5, n_output=11)
    assert trajectory.status == Status.FINISHED.label == "finished"
    assert isinstance(trajectory.status, str)


@pytest.mark.parametrize("call", ["simulate", "simulate_batch"])
def test_one_argument_validator(call):
    system = rollspring.load_system("hoop-cylinder")

    def run(**kwargs):
        arguments = {"duration": 0.2, **kwargs}
        if call == "simulate":
            return simulate(system, **arguments)
        return simulate_batch(system, {}, **arguments)

    for kwargs, field in (
        ({"duration": True}, "duration"),
        ({"rtol": True}, "rtol"),
        ({"step": True}, "step"),
        ({"n_output": True}, "n_output"),
        ({"n_output": 2.0}, "n_output"),
        ({"duration": "1"}, "duration"),
        ({"integrator": "rk4"}, "integrator"),
        ({"step": 0.3}, "step"),
    ):
        with pytest.raises(SimulationError, match=f"^{field}: "):
            run(**kwargs)
    # NumPy numbers are numbers
    extra = {"keep_trajectories": True} if call == "simulate_batch" else {}
    result = run(duration=np.float64(0.2), n_output=np.int64(5), rtol=np.float32(1e-6), **extra)
    assert len(result.t) == 5
    assert run(integrator="kahanli8", step=np.float64(0.01)).integrator == "kahanli8"
    if call == "simulate_batch":
        for bad in (True, 0, 1.5):
            with pytest.raises(SimulationError, match=r"^metric_every: "):
                run(metric_every=bad)
        assert run(metric_every=np.int64(4)).metric_every == 4


def test_the_integrators_are_shared():
    assert list(INTEGRATORS) == ["verlet", "yoshida4", "yoshida6", "kahanli8"]
    for name, scheme in INTEGRATORS.items():
        assert isinstance(scheme, Integrator) and scheme.name == name
        order, weights, constant = kernels.SCHEMES[name]
        assert (order, constant) == (scheme.order, scheme.error_constant)
        assert np.array_equal(weights, scheme.weights)
        assert math.isclose(sum(scheme.coefficients), 1.0, rel_tol=1e-15)
        assert scheme.stages == len(scheme.coefficients)
        if name in SCHEMES:
            assert SCHEMES[name] == (scheme.order, scheme.coefficients, scheme.error_constant)
    assert set(SCHEMES) == {"verlet", "yoshida4", "yoshida6"}  # what auto chooses from


def test_kahanli8_in_a_batch_is_the_single_runs_kahanli8():
    """The same scheme and step in both engines: the same motion, to rounding."""
    system = make_system(
        [
            body("a", "hoop", x=0.0, mu_static=math.inf),
            body("b", "sphere", radius=0.08, x=0.5, v=0.3, mu_static=math.inf),
        ],
        [
            spring(
                "a",
                "b",
                stiffness=120.0,
                rest_length=0.45,
                at=[{"radius": 0.05, "angle": 40.0}, {"height": 0.12}],
            )
        ],
    )
    h, duration = 0.01, 3.0
    batch = simulate_batch(
        system, {"springs.0.stiffness": [120.0]}, duration, integrator="kahanli8", step=h
    )
    single = simulate(system, duration, integrator="kahanli8", step=h, n_output=31)
    assert batch.integrator == single.integrator == "kahanli8"
    assert batch.n_steps == single.n_steps == 300
    np.testing.assert_allclose(batch.final_x[0], single.x[-1], rtol=0, atol=1e-12)
    np.testing.assert_allclose(batch.final_v[0], single.v[-1], rtol=0, atol=1e-11)


def test_runs_sharing_their_linear_configuration_share_one_computation_of_it():
    """``run_omegas`` computes each distinct set of the numbers it reads once (a grid of
    initial speeds and friction coefficients over a few stiffnesses and masses): every run's
    frequency is bit for bit the one computed for it alone, -0.0 is not 0.0, and every run of
    the batch equals itself alone."""
    from rollspring.simulate.batch.parameters import parse_parameters
    from rollspring.simulate.batch.plan import (
        _omegas,
        distinct_rows,
        make_plan,
        omega_inputs,
        probe,
        run_omegas,
    )

    first, inverse = distinct_rows(
        [np.array([0.0, -0.0, 0.0, np.nan, np.nan]), np.array([1.0, 1.0, 1.0, 2.0, 2.0])], 5
    )
    assert (
        first.size == 3 and list(inverse) == [inverse[0], inverse[1], inverse[0]] + [inverse[3]] * 2
    )
    assert len({inverse[0], inverse[1], inverse[3]}) == 3
    assert distinct_rows([np.array([1.0, 2.0, 3.0])], 3) is None  # every row its own

    system = rollspring.load_system("wall-hoop-cylinder")
    rng = np.random.default_rng(11)
    n = 60
    parameters = {
        "springs.0.stiffness": np.repeat([40.0, 80.0, 1e-6, 80.0], n // 4),
        "bodies.hoop.mass": np.tile([0.5, 1.0, 2.0], n // 3),
        "bodies.cylinder.x": np.where(np.arange(n) % 5 == 0, 0.6, 0.6 + 0.0),
        "bodies.hoop.x": np.where(np.arange(n) % 7 == 0, -0.0, 0.0),
        "bodies.cylinder.v": rng.normal(0.0, 0.2, n),
        "bodies.hoop.mu_static": rng.uniform(0.05, 1.0, n),
    }
    runs = parse_parameters(system, parameters)
    topology, _ = probe(system, runs.targets)
    plan = make_plan(system, runs, topology)
    shared = run_omegas(plan)
    own = _omegas(plan, omega_inputs(plan), plan.scale, plan.inertia, 1 << 15)
    assert np.array_equal(bits(shared), bits(own))
    assert np.unique(shared).size < n // 4  # shared: a few configurations, many runs
    batch = simulate_batch(system, parameters, 1.0)
    for run in range(0, n, 7):
        assert_same_run(batch, run, alone(system, parameters, run, 1.0, batch))

"""analysis.batch_linear: the linear metrics of arrays of runs agree with ``analyze`` run by run
(1e-12 relative) where it handles a run, and it hands the others back (the fallback criteria)."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

import rollspring
from rollspring.analysis import analyze, batch_linear
from rollspring.model import system_from_dict, system_to_json
from rollspring.service.sweeps.grid import apply_values

RTOL = 1e-12

#: Presets of the flat centre class (walls, three bodies, sliders) and a system with an
#: external force at a centre held by a wall spring.
FLAT = [
    "hoop-cylinder",
    "three-bodies",
    "two-masses",
    "wall-hoop-cylinder",
    "two-hoops",
    "two-cylinders",
]


def _forced() -> rollspring.System:
    data = system_to_json(rollspring.load_system("wall-hoop-cylinder"))
    data["forces"] = [{"body": "cylinder", "fx": 3.0, "fy": -2.0}]
    return system_from_dict(data)


def _system(name: str) -> rollspring.System:
    return _forced() if name == "forced" else rollspring.load_system(name)


def _reference(system, values: dict[str, np.ndarray], r: int):
    one = apply_values(system_to_json(system), system, {k: float(v[r]) for k, v in values.items()})
    a = analyze(one)
    n = len(system.bodies)
    omega = np.array([m.omega for m in a.modes])
    weights = a.stationary_weights if a.stationary_weights is not None else np.full(n, np.nan)
    need = a.required_mu if a.required_mu is not None else np.full(n, np.nan)
    return a, omega, weights, need


def _close(expected: np.ndarray, got: np.ndarray) -> bool:
    if not np.array_equal(np.isnan(expected), np.isnan(got)):
        return False
    if not np.array_equal(np.isinf(expected), np.isinf(got)):
        return False
    fine = np.isfinite(expected)
    return bool(
        np.all(
            np.abs(got[fine] - expected[fine])
            <= RTOL * np.maximum(np.abs(expected[fine]), 1e-300) + 1e-15 * (expected[fine] == 0)
        )
    )


def _random_runs(system, rng: np.random.Generator, n_runs: int) -> dict[str, np.ndarray]:
    """Random values of every batch path that keeps springs horizontal (one radius for all
    rolling bodies, per run)."""
    values: dict[str, np.ndarray] = {}
    radius = rng.uniform(0.04, 0.3, n_runs)
    for body in system.bodies:
        values[f"bodies.{body.id}.mass"] = rng.uniform(0.2, 5.0, n_runs)
        values[f"bodies.{body.id}.v"] = rng.uniform(-0.5, 0.5, n_runs)
        values[f"bodies.{body.id}.x"] = body.x + rng.uniform(-0.03, 0.03, n_runs)
        values[f"bodies.{body.id}.mu_static"] = rng.uniform(0.1, 1.0, n_runs)
        if body.rolls and not system.anchors:
            values[f"bodies.{body.id}.radius"] = radius
    for k in range(len(system.springs)):
        values[f"springs.{k}.stiffness"] = rng.uniform(20.0, 400.0, n_runs)
        values[f"springs.{k}.rest_length"] = rng.uniform(0.45, 0.55, n_runs)
    values["gravity"] = rng.uniform(1.0, 20.0, n_runs)
    # some runs share their masses, radii and stiffnesses (the distinct-configuration path)
    for key, column in values.items():
        if key.endswith((".mass", ".radius", ".stiffness")):
            column[n_runs // 2 :] = column[0]
    return values


@settings(max_examples=30, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(
    name=st.sampled_from([*FLAT, "forced"]),
    seed=st.integers(0, 2**32 - 1),
    n_runs=st.integers(1, 6),
)
def test_agrees_with_analyze(name: str, seed: int, n_runs: int) -> None:
    system = _system(name)
    values = _random_runs(system, np.random.default_rng(seed), n_runs)
    result = batch_linear(system, values)
    assert result.reason == ""
    assert result.handled.all()
    for r in range(n_runs):
        _, omega, weights, need = _reference(system, values, r)
        assert _close(omega, result.omega[r]), (r, omega, result.omega[r])
        assert _close(weights, result.stationary_weight[r]), (
            r,
            weights,
            result.stationary_weight[r],
        )
        assert _close(need, result.required_mu[r]), (r, need, result.required_mu[r])


@pytest.mark.parametrize("name", FLAT)
def test_grid_of_presets(name: str) -> None:
    """A sweep-like outer product (stiffness x the last body's speed), no values given for the
    rest: the system's own."""
    system = rollspring.load_system(name)
    last = system.bodies[-1].id
    k, v = np.meshgrid(np.linspace(50, 150, 5), np.linspace(0.0, 0.3, 4), indexing="ij")
    values = {"springs.0.stiffness": k.ravel(), f"bodies.{last}.v": v.ravel()}
    result = batch_linear(system, values)
    assert result.handled.all()
    for r in range(k.size):
        _, omega, weights, need = _reference(system, values, r)
        assert _close(omega, result.omega[r])
        assert _close(weights, result.stationary_weight[r])
        assert _close(need, result.required_mu[r])


def test_results_do_not_depend_on_the_other_runs() -> None:
    system = rollspring.load_system("three-bodies")
    values = _random_runs(system, np.random.default_rng(7), 9)
    whole = batch_linear(system, values)
    for r in range(9):
        alone = batch_linear(system, {k: v[r : r + 1] for k, v in values.items()})
        for name in ("omega", "stationary_weight", "required_mu"):
            assert np.array_equal(getattr(whole, name)[r], getattr(alone, name)[0], equal_nan=True)


# --------------------------------------------------------------------------------------------
# the fallback: runs and systems left to analyze


def test_off_centre_system_is_not_handled() -> None:
    system = rollspring.load_system("frictionless")
    result = batch_linear(system, {"springs.0.stiffness": [50.0, 100.0]})
    assert "off a centre" in result.reason
    assert not result.handled.any()
    assert np.isnan(result.omega).all()


def test_force_off_centre_is_not_handled() -> None:
    data = system_to_json(rollspring.load_system("hoop-cylinder"))
    data["forces"] = [{"body": "hoop", "fx": 1.0, "at": {"height": 0.15}}]
    result = batch_linear(system_from_dict(data), {"springs.0.stiffness": [50.0]})
    assert "forces[0]" in result.reason and not result.handled.any()


def test_tilted_spring_runs_are_not_handled() -> None:
    """Different radii put the centres at different heights: the spring tilts (geometric
    stiffness, a normal force that varies), so analyze decides those runs."""
    system = rollspring.load_system("hoop-cylinder")
    radius = np.array([0.1, 0.12, 0.1, 0.08])
    result = batch_linear(system, {"bodies.hoop.radius": radius})
    assert result.handled.tolist() == [True, False, True, False]
    assert np.isnan(result.required_mu[~result.handled]).all()


def test_no_equilibrium_is_not_handled() -> None:
    """A net constant force along the free (zero) mode: no equilibrium, analyze says so."""
    data = system_to_json(rollspring.load_system("hoop-cylinder"))
    data["forces"] = [{"body": "hoop", "fx": 0.5}]
    system = system_from_dict(data)
    assert not analyze(system).equilibrium.found
    result = batch_linear(system, {"springs.0.stiffness": [50.0, 100.0]})
    assert not result.handled.any()


def test_ends_crossing_at_the_equilibrium_are_not_handled() -> None:
    """A strong wall spring pushes the body past the other wall: the affine model's spring
    would pass through zero length, so analyze (on the real geometry) decides."""
    data = {
        "gravity": 9.81,
        "anchors": [{"id": "left", "x": -1.0, "y": 0.1}, {"id": "right", "x": 1.0, "y": 0.1}],
        "bodies": [{"id": "hoop", "shape": "hoop", "mass": 1.0, "radius": 0.1, "x": 0.9}],
        "springs": [
            {"ends": ["left", "hoop"], "stiffness": 100.0, "rest_length": 2.5},
            {"ends": ["hoop", "right"], "stiffness": 1.0, "rest_length": 0.05},
        ],
    }
    system = system_from_dict(data)
    result = batch_linear(system, {"springs.1.stiffness": [1.0, 10000.0]})
    assert result.handled.tolist() == [False, True]


def test_ends_meeting_at_the_equilibrium_are_not_handled() -> None:
    """Rest lengths 0 (or subnormal): at the equilibrium every spring's ends meet, where the
    sign of its vector is rounding's, so those runs go to analyze (found by a review: the sign
    test alone decided them one way or the other by the order of a sum); 1 mm is handled."""
    system = rollspring.load_system("three-bodies")
    values = {
        "springs.0.rest_length": np.array([0.0, 1e-320, 0.3, 1e-3]),
        "springs.1.rest_length": np.array([0.0, 0.0, 0.3, 1e-3]),
    }
    result = batch_linear(system, values)
    assert result.handled.tolist() == [False, False, True, True]
    assert np.all(np.isnan(result.omega[:2])) and np.all(np.isnan(result.required_mu[:2]))
    rng = np.random.default_rng(5)
    n = 400
    placed = {
        "springs.0.rest_length": np.zeros(n),
        "springs.1.rest_length": np.zeros(n),
        "bodies.hoop.x": rng.uniform(-0.2, 0.2, n),
        "bodies.cylinder.x": rng.uniform(0.3, 0.7, n),
        "bodies.sphere.x": rng.uniform(0.8, 1.2, n),
        "bodies.hoop.mass": rng.uniform(0.5, 2.0, n),
        "springs.0.stiffness": rng.uniform(10.0, 200.0, n),
        "springs.1.stiffness": rng.uniform(10.0, 200.0, n),
    }
    assert not np.any(batch_linear(system, placed).handled)
    for r in (2, 3):
        _, omega, weights, need = _reference(system, values, r)
        assert _close(omega, result.omega[r]) and _close(need, result.required_mu[r])
        assert _close(weights, result.stationary_weight[r])


def test_ill_conditioned_runs_are_not_handled() -> None:
    """Eigenvalues 1e-6 apart in scale: two correct computations of the small one can differ
    by more than 1e-12, so those runs go to analyze."""
    system = rollspring.load_system("three-bodies")
    result = batch_linear(system, {"springs.1.stiffness": [100.0, 1e-4]})
    assert result.handled.tolist() == [True, False]


def test_unknown_path_is_refused() -> None:
    with pytest.raises(ValueError, match="not a batch path"):
        batch_linear(rollspring.load_system("hoop-cylinder"), {"bodies.nobody.mass": [1.0]})

"""The compiled linear setup of small level systems (rollspring.simulate.small_setup) against
the analysis it stands in for: find_equilibrium's numbers, bit for bit, or the general search."""

from __future__ import annotations

from typing import Any

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from rollspring.analysis import find_equilibrium, linear
from rollspring.model import load_system
from rollspring.physics import system_arrays
from rollspring.simulate import kernels, simulate, small_setup
from rollspring.simulate.run import _small_level_equilibrium
from tests.conftest import body, make_system, spring

SHAPES = ("hoop", "cylinder", "sphere", "shell", "slider")
#: the centres' common height, m (radii k/64 m: the track heights sum back to it exactly)
HEIGHT = 0.5


def reference(arrays: Any, model: Any) -> Any:
    """find_equilibrium as the simulator called it before the compiled setup."""
    return find_equilibrium(
        arrays, forces=lambda q: kernels.generalized_forces(model, np.asarray(q, float))
    )


def python_level_branch(arrays: Any, model: Any) -> Any:
    """find_equilibrium's level branch alone (linear._level_equilibrium, called as it calls
    it): its Equilibrium, or None where its general search goes on."""
    zeros = np.zeros(arrays.n_bodies)

    def residual_of(q: Any) -> float:
        force = kernels.generalized_forces(model, q)
        return float(np.sqrt((force**2 / arrays.inertia).sum()))

    force_0 = kernels.generalized_forces(model, zeros)
    initial = residual_of(zeros)
    dx, dy = linear._placement_vectors(arrays)
    lengths = np.sqrt(dx**2 + dy**2)
    target = 1e-13 * max(initial, linear._force_scale(arrays, lengths))
    stiffness = linear._level_stiffness(arrays, dx, lengths)
    return linear._level_equilibrium(
        arrays.inertia, stiffness, force_0, initial, target, residual_of
    )


def assert_same(fast: Any, ref: Any) -> None:
    """Every number of the two equilibria and their modes equal, bit for bit."""
    assert fast.found and ref.found
    np.testing.assert_array_equal(fast.q, ref.q)
    assert fast.residual == ref.residual
    np.testing.assert_array_equal(fast.stiffness, ref.stiffness)
    for mine, theirs in ((fast.modes, ref.modes), (fast.placement_modes, ref.placement_modes)):
        np.testing.assert_array_equal(mine[0], theirs[0])
        np.testing.assert_array_equal(mine[1], theirs[1])
        assert mine[2].tolist() == theirs[2].tolist()
        assert mine[2].dtype == theirs[2].dtype


@st.composite
def level_systems(draw: Any) -> Any:
    """One or two bodies whose centres are at one height, a spring between them or to walls at
    that height (or both), and sometimes a force at a centre, tiny or not."""
    n = draw(st.integers(1, 2))
    bodies = []
    for i in range(n):
        radius = draw(st.integers(2, 16)) / 64
        bodies.append(
            body(
                f"b{i}",
                draw(st.sampled_from(SHAPES)),
                mass=draw(st.floats(0.1, 8.0)),
                radius=radius,
                x=0.8 * i + draw(st.floats(-0.1, 0.1)),
                track_height=HEIGHT - radius,
            )
        )
    springs, anchors = [], []
    stiffness = st.floats(0.5, 500.0)
    rest = st.floats(0.1, 1.5)
    if n == 2:
        springs.append(spring("b0", "b1", stiffness=draw(stiffness), rest_length=draw(rest)))
    if n == 1 or draw(st.booleans()):
        anchors.append({"id": "left", "x": -0.7, "y": HEIGHT})
        springs.append(spring("left", "b0", stiffness=draw(stiffness), rest_length=draw(rest)))
    if draw(st.booleans()):
        anchors.append({"id": "right", "x": 0.8 * n + 0.4, "y": HEIGHT})
        springs.append(
            spring(f"b{n - 1}", "right", stiffness=draw(stiffness), rest_length=draw(rest))
        )
    extra: dict[str, Any] = {"anchors": anchors} if anchors else {}
    if draw(st.booleans()):
        size = draw(st.sampled_from([1e-9, 1.0]))
        extra["forces"] = [
            {
                "body": f"b{draw(st.integers(0, n - 1))}",
                "fx": size * draw(st.floats(-3.0, 3.0)),
                "fy": draw(st.floats(-3.0, 3.0)),
            }
        ]
    return make_system(bodies, springs, **extra)


@settings(max_examples=60, deadline=None)
@given(level_systems())
def test_the_compiled_setup_is_find_equilibrium_bit_for_bit(system) -> None:
    arrays = system_arrays(system)
    model = kernels.kernel_model(arrays)
    fast = _small_level_equilibrium(arrays, model)
    ref = reference(arrays, model)
    assert arrays.level_centre_springs
    if fast is None:  # the general search decided: the level branch found nothing either
        assert small_setup.level_setup(model, 1e-13)[0] == small_setup.GENERAL
        assert python_level_branch(arrays, model) is None
        return
    assert_same(fast, ref)


@pytest.mark.parametrize(
    "name", ["hoop-cylinder", "two-hoops", "two-cylinders", "two-masses", "wall-hoop-cylinder"]
)
def test_the_paper_systems_take_the_compiled_setup(name) -> None:
    """The paper's level systems: the compiled setup decides, with find_equilibrium's numbers."""
    arrays = system_arrays(load_system(name))
    model = kernels.kernel_model(arrays)
    fast = _small_level_equilibrium(arrays, model)
    assert fast is not None
    assert_same(fast, reference(arrays, model))


def test_a_pull_along_the_free_motion_goes_to_the_general_search() -> None:
    """A free pair pulled along its zero mode has no equilibrium: the level step cannot hold,
    the general search decides (and reports it) as before."""
    system = make_system(
        [body("a", x=0.0), body("b", "cylinder", x=0.6)],
        [spring("a", "b", rest_length=0.5)],
        forces=[{"body": "a", "fx": 2.0, "fy": 0.0}],
    )
    arrays = system_arrays(system)
    model = kernels.kernel_model(arrays)
    assert small_setup.level_setup(model, 1e-13)[0] == small_setup.GENERAL
    assert _small_level_equilibrium(arrays, model) is None
    assert not reference(arrays, model).found


def test_an_off_centre_spring_or_three_bodies_is_not_taken() -> None:
    """Springs that tilt, or more than MOST_BODIES bodies: the Python search, untouched."""
    tilted = make_system(
        [body("a", x=0.0), body("b", "cylinder", x=0.6)],
        [spring("a", "b", rest_length=0.5, at=[{"radius": 0.05, "angle": 90.0}, {}])],
    )
    arrays = system_arrays(tilted)
    assert _small_level_equilibrium(arrays, kernels.kernel_model(arrays)) is None
    three = system_arrays(load_system("three-bodies"))
    assert three.n_bodies > small_setup.MOST_BODIES
    assert _small_level_equilibrium(three, kernels.kernel_model(three)) is None
    model = kernels.kernel_model(three)
    assert small_setup.level_setup(model, 1e-13)[0] == small_setup.GENERAL


def test_the_simulation_runs_on_the_compiled_setup_unchanged() -> None:
    """simulate() of the paper's system: the same trajectory and summary whether its setup is
    compiled or the Python search's (the numbers are the same bits)."""
    system = load_system("wall-hoop-cylinder")
    fast = simulate(system, 2.0)
    import rollspring.simulate.run as run

    original = run._small_level_equilibrium
    run._small_level_equilibrium = lambda arrays, model: None  # the Python search instead
    try:
        slow = simulate(system, 2.0)
    finally:
        run._small_level_equilibrium = original
    np.testing.assert_array_equal(fast.x, slow.x)
    np.testing.assert_array_equal(fast.friction, slow.friction)
    for key in ("period_measured", "period_linear", "max_friction_ratio", "steps", "step"):
        assert fast.summary[key] == slow.summary[key]

"""The compiled linear setup of small level systems (rollspring.simulate.kernels.level_setup)
against the analysis it stands in for: find_equilibrium's numbers, bit for bit, or the general
search."""

from __future__ import annotations

from typing import Any

import numpy as np
import pytest
from hypothesis import event, given, settings
from hypothesis import strategies as st

from rollspring.analysis import find_equilibrium, linear
from rollspring.analysis.linear import _LAPACK_EPS, EQUILIBRIUM_TOLERANCE, ZERO_MODE_TOLERANCE
from rollspring.model import load_system
from rollspring.physics import system_arrays
from rollspring.simulate import kernels, simulate
from rollspring.simulate.setup import _small_level_equilibrium
from tests.conftest import body, make_system, spring

SHAPES = ("hoop", "cylinder", "sphere", "shell", "slider")
#: the centres' common height, m (radii k/64 m: the track heights sum back to it exactly)
HEIGHT = 0.5


def verdict(model: Any) -> int:
    """level_setup's verdict, LEVEL or GENERAL, with find_equilibrium's constants."""
    result = kernels.level_setup(model, EQUILIBRIUM_TOLERANCE, ZERO_MODE_TOLERANCE, _LAPACK_EPS)
    return int(result[0])


def reference(arrays: Any, model: Any) -> Any:
    """find_equilibrium as the simulator called it before the compiled setup."""
    return find_equilibrium(
        arrays, forces=lambda q: kernels.generalized_forces(model, np.asarray(q, float))
    )


def python_level_branch(arrays: Any, model: Any) -> Any:
    """find_equilibrium's level branch alone (linear._level_equilibrium, called as it calls
    it): its Equilibrium, or None where its general search goes on."""
    zeros = np.zeros(arrays.n_bodies)
    inv_mass = 1.0 / arrays.inertia

    def residual_of(q: Any) -> float:
        force = kernels.generalized_forces(model, q)
        return float(np.sqrt((force**2 * inv_mass).sum()))

    force_0 = kernels.generalized_forces(model, zeros)
    initial = residual_of(zeros)
    dx, dy = linear._placement_vectors(arrays)
    lengths = np.sqrt(dx**2 + dy**2)
    target = EQUILIBRIUM_TOLERANCE * max(initial, linear._force_scale(arrays, lengths))
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
    """One or two bodies whose centres are at one height, springs between them and to walls at
    that height (some at their placement's length: already in equilibrium), and forces at
    centres, tiny or not: up to 7 springs and 3 forces, the most level_setup takes."""
    n = draw(st.integers(1, 2))
    scale = 10.0 ** draw(st.integers(-2, 2))
    bodies = []
    for i in range(n):
        radius = draw(st.integers(2, 16)) / 64
        bodies.append(
            body(
                f"b{i}",
                draw(st.sampled_from(SHAPES)),
                mass=scale * draw(st.floats(0.1, 8.0)),
                radius=radius,
                x=0.8 * i + draw(st.floats(-0.1, 0.1)),
                track_height=HEIGHT - radius,
            )
        )
    anchors = [
        {"id": "left", "x": -0.7, "y": HEIGHT},
        {"id": "right", "x": 0.8 * n + 0.4, "y": HEIGHT},
    ]
    pairs = [("b0", "b1")] if n == 2 else []
    pairs += [("left", "b0"), (f"b{n - 1}", "right")] + ([("left", "b1")] if n == 2 else [])
    chosen = draw(st.lists(st.sampled_from(pairs), min_size=1, max_size=7))
    springs = []
    for ends in chosen:
        extra = {} if draw(st.booleans()) else {"rest_length": draw(st.floats(0.1, 1.5))}
        springs.append(spring(*ends, stiffness=scale * draw(st.floats(0.5, 500.0)), **extra))
    forces = []
    for _ in range(draw(st.integers(0, 3))):
        size = draw(st.sampled_from([1e-10, 1e-3, 1.0, 100.0]))
        forces.append(
            {
                "body": f"b{draw(st.integers(0, n - 1))}",
                "fx": size * draw(st.floats(-3.0, 3.0)),
                "fy": draw(st.floats(-3.0, 3.0)),
            }
        )
    return make_system(bodies, springs, anchors=anchors, forces=forces)


@settings(max_examples=60, deadline=None)
@given(level_systems())
def test_the_compiled_setup_is_find_equilibrium_bit_for_bit(system) -> None:
    arrays = system_arrays(system)
    model = kernels.kernel_model(arrays)
    fast = _small_level_equilibrium(arrays, model)
    ref = reference(arrays, model)
    assert arrays.level_centre_springs
    event("general search" if fast is None else "compiled setup")
    if fast is None:  # the general search decided: the level branch found nothing either
        assert verdict(model) == kernels.GENERAL
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
    assert verdict(model) == kernels.GENERAL
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
    assert three.n_bodies > kernels.MOST_BODIES
    assert _small_level_equilibrium(three, kernels.kernel_model(three)) is None
    assert verdict(kernels.kernel_model(three)) == kernels.GENERAL


def test_the_simulation_runs_on_the_compiled_setup_unchanged() -> None:
    """simulate() of the paper's system: the same trajectory and summary whether its setup is
    compiled or the Python search's (the numbers are the same bits)."""
    system = load_system("wall-hoop-cylinder")
    fast = simulate(system, 2.0)
    import rollspring.simulate.setup as run

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


def test_an_ulp_of_the_eigenvalues_found_by_review_is_gone() -> None:
    """A system where Python's ``x ** 2`` in linear._laev2 (the C library's pow) was an ulp
    from the product Fortran and Numba compute: q and the eigenvalues differed in the last
    bit. The analysis squares by a product now, so both agree, and agree with SciPy."""
    import scipy.linalg

    system = make_system(
        [
            body("a", "sphere", mass=3.485, radius=0.1, x=0.0),
            body("b", "slider", mass=0.752, radius=0.1, x=0.6),
        ],
        [
            spring("w", "a", stiffness=308.2, rest_length=0.45),
            spring("a", "b", stiffness=473.5, rest_length=0.5),
        ],
        anchors=[{"id": "w", "x": -0.5, "y": 0.1}],
    )
    arrays = system_arrays(system)
    model = kernels.kernel_model(arrays)
    fast = _small_level_equilibrium(arrays, model)
    assert fast is not None
    ref = reference(arrays, model)
    assert_same(fast, ref)
    np.testing.assert_array_equal(
        ref.modes[0], scipy.linalg.eigh(ref.stiffness, np.diag(arrays.inertia))[0]
    )


def test_more_numbers_than_numpy_sums_in_order_go_to_the_python_search() -> None:
    """NumPy sums 8 numbers or more pairwise: the force scale of 4 forces (8 components), or of
    8 springs, would differ from level_setup's sum in order by an ulp (a review found a system
    whose residual fell between the two tolerances), so such systems take the Python search."""
    forces = [{"body": "a", "fx": 3.1590880355047e-10, "fy": 918.2693449746259}] + [
        {"body": "a", "fx": 0.0, "fy": fy}
        for fy in (-32.550933474909925, 149.14249085989513, 733.0513356044446)
    ]
    system = make_system(
        [body("a", "hoop", mass=1.0, radius=0.1, x=0.0)],
        [spring("w", "a", stiffness=100.0)],
        anchors=[{"id": "w", "x": -0.5, "y": 0.1}],
        forces=forces,
    )
    arrays = system_arrays(system)
    assert arrays.level_centre_springs
    assert verdict(kernels.kernel_model(arrays)) == kernels.GENERAL
    three_forces = system.model_copy(update={"forces": system.forces[:3]})
    assert verdict(kernels.kernel_model(system_arrays(three_forces))) == kernels.LEVEL
    walls = [{"id": f"w{k}", "x": -0.5 - 0.1 * k, "y": 0.1} for k in range(8)]
    many = make_system(
        [body("a", "hoop", mass=1.0, radius=0.1, x=0.0)],
        [spring(f"w{k}", "a", stiffness=100.0 + k) for k in range(8)],
        anchors=walls,
    )
    assert verdict(kernels.kernel_model(system_arrays(many))) == kernels.GENERAL

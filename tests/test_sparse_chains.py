"""The sparse path of long chains (issue 14.1): the physics by spring end, the banded
eigensolvers, the sparse equilibrium search, against closed forms and against the dense path
(the reference) on random chains."""

from __future__ import annotations

import math

import numpy as np
import pytest

import rollspring
from rollspring.analysis.banded import ALL_MODES_LIMIT, DENSE_LIMIT, banded_modes
from rollspring.analysis.costs import analysis_cost
from rollspring.errors import AnalysisError
from rollspring.model import INERTIA_FACTORS, System
from rollspring.model.chains import chain
from rollspring.physics import (
    body_forces,
    body_forces_jacobian,
    contact_forces,
    contact_forces_jacobian,
    damping_matrix,
    generalized_forces,
    spring_state,
    stiffness_matrix,
    system_arrays,
)

SHAPES = ("hoop", "cylinder", "sphere", "shell", "slider")


def _lattice(shape: str, n: int, seed: int) -> tuple[System, float]:
    """Equal bodies between two walls and the lattice's sqrt(k/M), M = (1 + gamma) m."""
    rng = np.random.default_rng(seed)
    mass, radius, k = rng.uniform(0.2, 5.0), rng.uniform(0.02, 0.2), rng.uniform(10.0, 1e4)
    system = chain(shape, n, mass=mass, radius=radius, stiffness=k, spacing=0.5, walls="both")
    gamma = 0.0 if shape == "slider" else INERTIA_FACTORS[shape]
    return system, math.sqrt(k / ((1.0 + gamma) * mass))


def _exact(root: float, n: int, which: np.ndarray) -> np.ndarray:
    """omega_j = 2 sqrt(k/M) sin(j pi / (2 (N + 1))), j = which (1-based)."""
    return 2.0 * root * np.sin(which * math.pi / (2 * (n + 1)))


@pytest.mark.parametrize(
    ("shape", "n"), [("hoop", 100), ("slider", 500), ("sphere", 1000), ("cylinder", 2000)]
)
def test_equal_bodies_between_walls_have_the_lattice_frequencies_on_the_sparse_path(
    shape: str, n: int
) -> None:
    system, root = _lattice(shape, n, n)
    result = rollspring.analyze(system)
    assert hasattr(result.stiffness, "tocoo")  # the sparse path
    omegas = np.array([m.omega for m in result.modes])
    assert [m.kind for m in result.modes] == ["oscillating"] * n
    np.testing.assert_allclose(omegas, _exact(root, n, np.arange(1, n + 1)), rtol=1e-10, atol=0)


def test_beyond_every_mode_the_lowest_and_a_band_have_the_lattice_frequencies() -> None:
    n = 5000
    system, root = _lattice("sphere", n, 7)
    lowest = rollspring.analyze(system)
    assert len(lowest.modes) == 20 and lowest.amplitude is None
    assert any("modes 1 to 20 of 5000" in w for w in lowest.warnings)
    np.testing.assert_allclose(
        [m.omega for m in lowest.modes], _exact(root, n, np.arange(1, 21)), rtol=1e-10
    )
    band = rollspring.analyze(system, modes=(2500, 2510))
    np.testing.assert_allclose(
        [m.omega for m in band.modes], _exact(root, n, np.arange(2500, 2511)), rtol=1e-10
    )
    shape = band.modes[0].shape_x  # a standing wave sin(j pi i/(N+1)), largest +1
    i = np.arange(1, n + 1)
    expected = np.sin(2500 * math.pi * i / (n + 1))
    expected /= expected[np.argmax(np.abs(expected))]
    np.testing.assert_allclose(shape, expected, atol=1e-9)


def test_a_count_and_a_band_are_slices_of_every_mode() -> None:
    system = chain("hoop,cylinder,sphere", 150, height=[0.15, 0.02, 0.1], walls="left", pluck=3)
    every = rollspring.analyze(system)
    lowest = rollspring.analyze(system, modes=5)
    band = rollspring.analyze(system, modes=(40, 44))
    for part, first in ((lowest, 0), (band, 39)):
        assert part.amplitude is None  # a partial set: no response
        for k, mode in enumerate(part.modes):
            reference = every.modes[first + k]
            assert mode.omega == pytest.approx(reference.omega, rel=1e-12)
            np.testing.assert_allclose(mode.shape_x, reference.shape_x, atol=1e-9)
            scale = np.max(np.abs(reference.friction))
            np.testing.assert_allclose(mode.friction, reference.friction, atol=1e-9 * scale)


@pytest.mark.parametrize(
    ("modes", "message"),
    [
        (0, "modes: need 1 to 12"),
        (13, "modes: need 1 to 12"),
        ((3, 2), "need 1 <= first <= last <= 12"),
        ((1, 2, 3), "a (first, last) pair"),
        ("all", "a count or a (first, last) pair"),
        (True, "a count or a (first, last) pair"),
    ],
)
def test_a_bad_choice_of_modes_is_a_one_line_error(modes: object, message: str) -> None:
    with pytest.raises(AnalysisError, match=r"^modes: ") as caught:
        rollspring.analyze(chain("hoop", 12), modes=modes)  # type: ignore[arg-type]
    assert message in str(caught.value) and "\n" not in str(caught.value)


def _random_chain(seed: int) -> System:
    """A chain of mixed shapes and masses, off-centre attachments, walls, and springs whose
    rest lengths differ from the placement (pre-tension: a non-trivial equilibrium)."""
    rng = np.random.default_rng(seed)
    p = int(rng.integers(1, 4))
    shapes = [str(s) for s in rng.choice(["hoop", "cylinder", "sphere", "shell"], p)]
    radius = rng.uniform(0.05, 0.2, p)
    system = chain(
        shapes,
        int(rng.integers(5, 51)),
        mass=list(rng.uniform(0.3, 3.0, p)),
        radius=list(radius),
        height=list(radius * rng.uniform(0.2, 1.9, p)),
        stiffness=list(rng.uniform(20.0, 500.0, p)),
        spacing=float(rng.uniform(0.3, 0.8)),
        walls=str(rng.choice(["left", "both"])),
        pluck=1,
    )
    data = system.model_dump(mode="json", exclude_none=True)
    for spring in data["springs"]:
        spring["rest_length"] *= float(rng.uniform(0.9, 1.1))
    return System.model_validate(data)


@pytest.mark.parametrize("seed", range(8))
def test_the_sparse_and_the_dense_path_agree_on_random_chains(seed: int) -> None:
    system = _random_chain(seed)
    sparse = rollspring.analyze(system, sparse=True)
    dense = rollspring.analyze(system, sparse=False)
    assert hasattr(sparse.stiffness, "tocoo") and isinstance(dense.stiffness, np.ndarray)
    assert sparse.equilibrium.found and dense.equilibrium.found
    np.testing.assert_allclose(sparse.equilibrium.q, dense.equilibrium.q, rtol=0, atol=1e-10)
    k_scale = np.max(np.abs(dense.stiffness))
    np.testing.assert_allclose(sparse.stiffness.toarray(), dense.stiffness, atol=1e-10 * k_scale)
    assert [m.kind for m in sparse.modes] == [m.kind for m in dense.modes]
    for a, b in zip(sparse.modes, dense.modes, strict=True):
        assert a.omega == pytest.approx(b.omega, rel=1e-10)
        np.testing.assert_allclose(a.shape_x, b.shape_x, atol=1e-10)
        for field in ("friction", "normal_force", "spring_extension"):
            x, y = getattr(a, field), getattr(b, field)
            np.testing.assert_allclose(x, y, atol=1e-10 * max(np.max(np.abs(y)), 1e-300))
    for field in ("amplitude", "friction_amplitude", "required_mu", "velocity_amplitude"):
        x, y = getattr(sparse, field), getattr(dense, field)
        finite = np.isfinite(y)  # a body that can lift off needs mu = inf on both paths
        np.testing.assert_array_equal(np.isfinite(x), finite)
        scale = np.max(np.abs(y[finite]), initial=0.0)
        np.testing.assert_allclose(x[finite], y[finite], rtol=1e-10, atol=1e-10 * scale)
    ranges = dense.normal_force_range  # N_c -/+ amplitude: 1e-10 of their scale
    np.testing.assert_allclose(
        sparse.normal_force_range, ranges, rtol=1e-10, atol=1e-10 * np.max(np.abs(ranges))
    )


def test_a_free_chain_has_its_stationary_point_on_both_paths() -> None:
    system = chain("hoop,cylinder", 80, pluck=5)  # no walls, springs at centres: a zero mode
    sparse = rollspring.analyze(system)
    dense = rollspring.analyze(system, sparse=False)
    assert sparse.modes[0].kind == "zero" and dense.modes[0].kind == "zero"
    assert sparse.stationary_weights is not None and dense.stationary_weights is not None
    np.testing.assert_allclose(sparse.stationary_weights, dense.stationary_weights, atol=1e-12)
    assert sparse.stationary_amplitude == pytest.approx(dense.stationary_amplitude, abs=1e-12)


@pytest.mark.parametrize("seed", range(4))
def test_the_per_end_physics_equals_the_dense_matrices(seed: int) -> None:
    arrays = system_arrays(_random_chain(seed))
    rng = np.random.default_rng(seed)
    q = rng.normal(0.0, 0.3, arrays.n_bodies)
    qdot = rng.normal(0.0, 1.0, arrays.n_bodies)
    dense_k = stiffness_matrix(arrays, q)
    np.testing.assert_array_equal(stiffness_matrix(arrays, q, sparse=True).toarray(), dense_k)
    np.testing.assert_array_equal(dense_k, dense_k.T)
    d_force = body_forces_jacobian(arrays, q)
    dx, dy = body_forces_jacobian(arrays, q, sparse=True)
    np.testing.assert_array_equal(dx.toarray(), d_force[:, 0, :])
    np.testing.assert_array_equal(dy.toarray(), d_force[:, 1, :])
    d_friction, d_normal = contact_forces_jacobian(arrays, q)
    s_friction, s_normal = contact_forces_jacobian(arrays, q, sparse=True)
    np.testing.assert_allclose(s_friction.toarray(), d_friction, rtol=1e-14, atol=1e-12)
    np.testing.assert_allclose(s_normal.toarray(), d_normal, rtol=1e-14, atol=1e-12)
    np.testing.assert_array_equal(
        damping_matrix(arrays, q, sparse=True).toarray(), damping_matrix(arrays, q)
    )
    # K is the Jacobian of -Q, and the dense lever arms are the per-end ones in place
    h = 1e-6
    for i in rng.choice(arrays.n_bodies, 3, replace=False):
        step = np.zeros(arrays.n_bodies)
        step[i] = h
        column = -(generalized_forces(arrays, q + step) - generalized_forces(arrays, q - step))
        np.testing.assert_allclose(
            column / (2 * h), dense_k[:, i], atol=1e-6 * np.abs(dense_k).max()
        )
    springs = spring_state(arrays, q, qdot)
    lever = springs.lever
    for j in (0, 1):
        on_body = arrays.end_body[:, j] >= 0
        rows = np.flatnonzero(on_body)
        np.testing.assert_array_equal(
            lever[rows, arrays.end_body[rows, j]], springs.end_lever[rows, j]
        )
    # batched states give each state's forces
    states = np.stack([q, 0.5 * q])
    forces = body_forces(arrays, states, np.stack([qdot, qdot]))
    np.testing.assert_allclose(forces[1], body_forces(arrays, 0.5 * q, qdot), rtol=1e-15)
    friction, normal = contact_forces(arrays, states)
    np.testing.assert_allclose(friction[0], contact_forces(arrays, q)[0], rtol=1e-15)
    np.testing.assert_allclose(normal[1], contact_forces(arrays, 0.5 * q)[1], rtol=1e-15)


def test_the_banded_solver_handles_springs_beyond_neighbours() -> None:
    """Springs joining bodies two apart make a pentadiagonal K: ``eig_banded``."""
    system = chain("hoop", 70, walls="both", pluck=2)
    data = system.model_dump(mode="json", exclude_none=True)
    ids = [b["id"] for b in data["bodies"]]
    data["springs"] += [
        {"ends": [ids[i], ids[i + 2]], "stiffness": 30.0} for i in range(0, len(ids) - 2, 3)
    ]
    wider = System.model_validate(data)
    arrays = system_arrays(wider)
    assert arrays.bandwidth == 2
    sparse = rollspring.analyze(wider)
    dense = rollspring.analyze(wider, sparse=False)
    np.testing.assert_allclose(
        [m.omega for m in sparse.modes], [m.omega for m in dense.modes], rtol=1e-10
    )
    _, vectors, _, _ = banded_modes(
        arrays, stiffness_matrix(arrays, sparse.equilibrium.q, sparse=True)
    )
    assert vectors is not None
    # M-orthonormal
    np.testing.assert_allclose(
        vectors.T @ (arrays.inertia[:, None] * vectors), np.eye(70), atol=1e-12
    )


def test_the_analysis_cost_follows_the_path() -> None:
    small, middle, large = (chain("hoop", n) for n in (DENSE_LIMIT, 1000, ALL_MODES_LIMIT + 1))
    assert analysis_cost(small).seconds < 2.0
    assert analysis_cost(middle).seconds < 10.0
    assert analysis_cost(large).seconds < 10.0 and analysis_cost(large).memory < 1e8
    every = analysis_cost(large, modes=ALL_MODES_LIMIT + 1)
    assert every.memory > 1e8  # every mode's shapes: n² numbers


def test_the_command_line_summarises_a_long_chain(tmp_path) -> None:
    import json

    from typer.testing import CliRunner

    from rollspring.cli.app import app
    from rollspring.service.chains import chain_file

    path = chain_file(chain("hoop,cylinder", 100, walls="both", pluck=1), tmp_path / "c.toml")
    runner = CliRunner()
    shown = runner.invoke(app, ["analyze", str(path)])
    assert shown.exit_code == 0, shown.output
    assert "Bodies, by kind" in shown.output and "… 84 more" in shown.output
    assert "hoop50" not in shown.output  # no row per body
    printed = runner.invoke(app, ["analyze", str(path), "--json"])
    assert printed.exit_code == 0, printed.output
    payload = json.loads(printed.stdout)
    analysis = rollspring.analyze(path)
    assert len(payload["matrices"]["M_diagonal"]) == 100
    entries = payload["matrices"]["K_entries"]
    assert len(entries) == 100 + 2 * 99  # tridiagonal
    for i, j, value in entries[:20]:
        assert value == analysis.stiffness[i, j]
    assert [m["omega"] for m in payload["modes"]] == [m.omega for m in analysis.modes]
    assert "shape" not in payload["modes"][0] and payload["response"] is not None
    band = runner.invoke(app, ["analyze", str(path), "--json", "--modes", "10-12"])
    assert band.exit_code == 0, band.output
    chosen = json.loads(band.stdout)
    assert [m["omega"] for m in chosen["modes"]] == pytest.approx(
        [m.omega for m in analysis.modes[9:12]], rel=1e-12
    )
    assert chosen["response"] is None and "modes 10 to 12 of 100" in band.stderr


@pytest.mark.parametrize("n", [100, 3000])
def test_a_free_chain_struck_finds_the_valley_point_sparsely(n: int) -> None:
    """No walls, centre springs: K is singular (the chain rolls as a whole). The bordered
    sparse Newton holds the zero-mode coordinate at the placement's, as the dense search does;
    beyond the dense search's reach too."""
    arrays = system_arrays(chain("hoop,cylinder", n, pluck=1, amplitude=0.05))
    found = rollspring.find_equilibrium(arrays)
    assert found.found and found.stiffness is None  # the sparse path
    assert np.max(np.abs(generalized_forces(arrays, found.q))) <= 1e-10
    # the zero mode of level centre springs, v_i = 1/s_i (every centre moved alike), held:
    # V0^T M q = sum J_i q_i / s_i = 0, as in the placement
    weights = arrays.inertia / arrays.scale
    held = abs(float(weights @ found.q))
    assert held <= 1e-12 * float(weights.sum()) * float(np.max(np.abs(found.q)))
    assert np.max(np.abs(found.q)) > 0.1  # a real displacement (the struck body)
    if n <= ALL_MODES_LIMIT:
        dense = rollspring.find_equilibrium(arrays, sparse=False)
        np.testing.assert_allclose(found.q, dense.q, rtol=0, atol=1e-12)

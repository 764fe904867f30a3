"""Long chains through ``rollspring.simulate`` (issue 14.1): beyond
:data:`~rollspring.analysis.banded.DENSE_LIMIT` bodies the run is set up from the sparse
stiffness matrix (banded eigensolvers) and keeps each extreme's state over its body's ball only
(:func:`~rollspring.simulate.kernels.spring_balls`); these tests hold that path to the dense
one (the reference), to the accuracy contract and to the closed form of the monatomic lattice.

Closed form (docs/physics.md (M6), (M7)): springs of stiffness k joining the centres of equal
bodies rolling without slipping give each body the equation (1 + γ) m ẍ_j = k (x_{j+1} - 2 x_j
+ x_{j-1}) (the rolling mass is J/R² = (1 + γ) m), so N of them between walls have the modes
sin(j n π/(N + 1)) with ω_n = 2 √(k/M) sin(n π/(2(N + 1))), M = (1 + γ) m. With the springs
level and at the centres the equations are exactly linear: the motion started in mode n is
that shape times cos(ω_n t).
"""

from __future__ import annotations

import math
import tracemalloc

import numpy as np
import pytest

import rollspring
from rollspring.model.chains import chain
from rollspring.physics import system_arrays
from rollspring.simulate import kernels
from rollspring.simulate import setup as run
from rollspring.simulate.integrators import INTEGRATORS, refinement_radius


def _dense(monkeypatch: pytest.MonkeyPatch) -> None:
    """Force the dense setup (every mode, the reference) and full states for every extreme."""
    monkeypatch.setattr(run, "DENSE_LIMIT", 10**9)


@pytest.fixture(scope="module")
def offcentre() -> rollspring.System:
    """200 hoops and cylinders between walls, the springs raised 0.15 m above the centres
    (the normal forces vary and the equations are nonlinear), the first body plucked."""
    return chain(pattern="hoop,cylinder", n=200, walls="both", pluck=1, height=0.15)


def test_sparse_setup_agrees_with_the_dense_one(offcentre, monkeypatch) -> None:
    sparse = rollspring.simulate(offcentre, 3.0)
    _dense(monkeypatch)
    dense = rollspring.simulate(offcentre, 3.0)
    assert sparse.integrator == dense.integrator
    assert sparse.step == pytest.approx(dense.step, rel=1e-12)
    assert sparse.summary["period_linear"] == pytest.approx(
        dense.summary["period_linear"], rel=1e-10
    )
    for name in ("x", "phi", "v", "omega", "friction", "normal"):
        a, b = getattr(sparse, name), getattr(dense, name)
        scale = float(np.max(np.abs(b)))
        assert np.max(np.abs(a - b)) <= 1e-12 * scale, name
    # the extremes refined over each body's ball are those refined over the whole chain
    for key in ("max_friction_ratio", "min_normal_force"):
        windowed, whole = sparse.summary[key], dense.summary[key]
        assert windowed.keys() == whole.keys()
        for body, value in whole.items():
            assert windowed[body] == pytest.approx(value, rel=1e-12, abs=1e-300), (key, body)
    assert sparse.summary["energy_error"] <= 100 * 1e-8 + 1e-12


@pytest.mark.parametrize("scheme", sorted(INTEGRATORS))
def test_a_windowed_refinement_is_the_whole_models_to_the_bit(offcentre, scheme: str) -> None:
    """The light-cone argument of :func:`kernels.refine_windowed`: a body's ball reaches
    further than the refinement's force evaluations carry any change, so its extreme comes
    out of the ball's model exactly as out of the whole chain's."""
    arrays = system_arrays(offcentre)
    model = kernels.kernel_model(arrays)
    n = arrays.n_bodies
    coeffs = INTEGRATORS[scheme].weights
    rng = np.random.default_rng(7)
    q0 = rng.normal(scale=0.05, size=(2 * n, n))
    v0 = rng.normal(scale=0.2, size=(2 * n, n))
    kinds = np.repeat(np.array([0, 1], dtype=np.int64), n)
    bodies = np.tile(np.arange(n, dtype=np.int64), 2)
    best = np.full(2 * n, -np.inf)
    spans = np.full(2 * n, 0.02)
    whole = kernels.refine_extremes(model, coeffs, 0.01, q0, v0, kinds, bodies, best, spans)
    links = kernels.body_links(n, model[2], model[4])
    radius = refinement_radius(coeffs.size)
    ptr, idx = kernels.spring_balls(n, model[2], links[0], links[1], radius)
    # a chain's ball: the 2 radius + 1 nearest bodies (fewer at the ends)
    sizes = np.diff(ptr)
    assert sizes.max() == 2 * radius + 1 and sizes.min() == radius + 1
    balls = [idx[ptr[b] : ptr[b + 1]] for b in bodies]
    offsets = np.concatenate([[0], np.cumsum([ball.size for ball in balls])])
    windowed = kernels.refine_windowed(
        model,
        coeffs,
        0.01,
        np.concatenate([q0[j, ball] for j, ball in enumerate(balls)]),
        np.concatenate([v0[j, ball] for j, ball in enumerate(balls)]),
        offsets,
        np.concatenate(balls),
        kinds,
        bodies,
        best,
        links,
        spans,
    )
    np.testing.assert_array_equal(windowed, whole)


def test_a_long_nonlinear_chain_keeps_its_energy_to_the_contract() -> None:
    system = chain(pattern="hoop,cylinder", n=300, walls="none", pluck=150, height=0.15)
    for rtol in (1e-6, 1e-9):
        result = rollspring.simulate(system, 4.0, rtol=rtol)
        assert result.status == "finished"
        assert result.summary["energy_error"] <= 100 * rtol + 1e-12
        assert result.summary["retries"] == 0


@pytest.mark.parametrize(("n_bodies", "mode"), [(120, 1), (150, 4)])
def test_a_monatomic_chain_in_its_mode_oscillates_at_the_lattice_frequency(
    n_bodies: int, mode: int
) -> None:
    mass, stiffness, gamma = 1.0, 100.0, 1.0  # hoops
    rolling_mass = (1 + gamma) * mass
    omega = (
        2 * math.sqrt(stiffness / rolling_mass) * math.sin(mode * math.pi / (2 * (n_bodies + 1)))
    )
    system = chain(
        pattern="hoop", n=n_bodies, walls="both", mode=mode, mass=mass, stiffness=stiffness
    )
    rest = system_arrays(chain(pattern="hoop", n=n_bodies, walls="both")).x0
    rtol = 1e-8
    duration = 0.75 * 2 * math.pi / omega  # three quarters of a period: every phase
    result = rollspring.simulate(system, duration, rtol=rtol)
    assert result.status == "finished"
    # the initial displacement is the lattice's mode shape
    shape = np.sin(np.arange(1, n_bodies + 1) * mode * math.pi / (n_bodies + 1))
    start = result.x[0] - rest
    np.testing.assert_allclose(start, shape * (start @ shape) / (shape @ shape), atol=1e-12)
    # the motion is that shape times cos(omega t), within the accuracy contract
    exact_x = start[None, :] * np.cos(omega * result.t)[:, None]
    exact_v = -omega * start[None, :] * np.sin(omega * result.t)[:, None]
    for measured, exact in ((result.x - rest, exact_x), (result.v, exact_v)):
        scale = np.max(np.abs(exact))
        bound = rtol * np.abs(exact) + rtol / 10 * scale
        assert np.all(np.abs(measured - exact) <= bound)
    if mode == 1:  # the lowest mode's linear period, from the banded eigensolver
        assert result.summary["period_linear"] == pytest.approx(2 * math.pi / omega, rel=1e-10)


def _peak_memory(n_bodies: int) -> int:
    """The peak of NumPy's (traced) memory of a 1 s run of a chain of ``n_bodies``, 11 outputs."""
    system = chain(pattern="hoop,cylinder", n=n_bodies, walls="both", pluck=1, height=0.15)
    rollspring.simulate(system, 0.05, n_output=3)  # compiled and loaded before measuring
    tracemalloc.start()
    try:
        result = rollspring.simulate(system, 1.0, n_output=11)
        _, peak = tracemalloc.get_traced_memory()
    finally:
        tracemalloc.stop()
    assert result.status == "finished"
    return peak


def test_a_long_chains_memory_grows_as_its_length() -> None:
    """No dense n x n array (nor the kernel's states of every body for every body's extreme,
    (2, n, 2, n)): twice the bodies, about twice the memory (a dense array: four times)."""
    small, large = _peak_memory(1000), _peak_memory(2000)
    assert large < 2.5 * small


def test_the_command_line_summarises_a_long_chains_bodies(tmp_path) -> None:
    """More than 20 bodies: one row per quantity with its extremes over the bodies and which
    body, the numbers of the run's summary (the same run as ``--json``'s)."""
    from typer.testing import CliRunner

    from rollspring.cli import app
    from rollspring.model.files import system_to_toml

    system = chain(pattern="hoop,cylinder", n=30, walls="both", pluck=1, height=0.15)
    path = tmp_path / "chain.toml"
    path.write_text(system_to_toml(system))
    done = CliRunner().invoke(app, ["simulate", str(path), "-T", "1", "--outputs", "101"])
    assert done.exit_code == 0, done.output
    summary = rollspring.simulate(system, 1.0, n_output=101).summary
    lines = done.output.splitlines()
    assert any("bodies (30: the extremes over them)" in line for line in lines)
    assert not any(line.startswith("│ hoop3 ") for line in lines)  # no row per body
    ratios = summary["max_friction_ratio"]
    top = max(ratios, key=ratios.__getitem__)
    row = next(line for line in lines if "max |f|/N over the run" in line)
    assert f"{ratios[top]:.6g}" in row and f" {top} " in row
    normals = summary["min_normal_force"]
    low = min(normals, key=normals.__getitem__)
    row = next(line for line in lines if "min N over the run" in line)
    assert f"{normals[low]:.6g}" in row and f" {low} " in row

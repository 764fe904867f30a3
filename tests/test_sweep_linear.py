"""The sweep engine's fast paths: the vectorised linear metrics (and their fallback to analyze),
chunks computed together in one batch call, and the planning shortcut, each against the
per-run / per-chunk computation it replaces."""

from __future__ import annotations

import numpy as np
import pytest

import rollspring
from rollspring.analysis import analyze
from rollspring.model import system_to_json
from rollspring.service.sweeps import sweep
from rollspring.service.sweeps.compute import (
    SweepPlan,
    compute_chunk,
    compute_chunks,
    grid_omega,
    plan_omega,
)
from rollspring.service.sweeps.engine import _choose_step
from rollspring.service.sweeps.grid import Grid, apply_values, chunk_shape

LINEAR = ("omega", "stationary_weight", "required_mu_linear")


def _per_run_linear(system, ds, paths):
    """analyze of every run's start (friction coefficients left out, as the engine does)."""
    grids = np.meshgrid(*(ds[p].values for p in paths), indexing="ij")
    flat = {p: g.ravel() for p, g in zip(paths, grids, strict=True)}
    base = system_to_json(system)
    n = grids[0].size
    out = {name: np.full((n, len(system.bodies)), np.nan) for name in LINEAR}
    for r in range(n):
        values = {p: float(v[r]) for p, v in flat.items() if not p.endswith(("mu_static",))}
        a = analyze(apply_values(base, system, values))
        out["omega"][r] = [m.omega for m in a.modes]
        if a.stationary_weights is not None:
            out["stationary_weight"][r] = a.stationary_weights
        if a.required_mu is not None:
            out["required_mu_linear"][r] = a.required_mu
    return out


@pytest.mark.parametrize(
    ("name", "vary"),
    [
        (
            "hoop-cylinder",
            {
                "springs.0.stiffness": [50.0, 100.0, 150.0],
                "bodies.cylinder.v": [0.0, 0.2],
                "bodies.hoop.mu_static": [0.3, 1.0],
            },
        ),
        # radii differ in some runs: the spring tilts there and those runs go to analyze
        (
            "hoop-cylinder",
            {"bodies.hoop.radius": [0.08, 0.1, 0.12], "bodies.cylinder.v": [0.0, 0.1]},
        ),
        (
            "wall-hoop-cylinder",
            {"springs.1.stiffness": [50.0, 200.0], "bodies.cylinder.x": [0.45, 0.52]},
        ),
        ("three-bodies", {"bodies.sphere.mass": [0.5, 2.0], "bodies.hoop.v": [0.0, 0.1, 0.2]}),
    ],
)
def test_linear_metrics_equal_analyze_per_run(name, vary) -> None:
    system = rollspring.load_system(name)
    ds = sweep(system, vary, 0.2, metrics=[*LINEAR], chunk=5)
    expected = _per_run_linear(system, ds, list(vary))
    for metric in LINEAR:
        got = ds[metric].values.reshape(-1, len(system.bodies))
        want = expected[metric]
        assert np.array_equal(np.isnan(got), np.isnan(want)), metric
        fine = np.isfinite(want)
        assert np.allclose(got[fine], want[fine], rtol=1e-12, atol=0), metric


def test_fallback_runs_are_analyze_exactly() -> None:
    """Runs outside the flat centre class (here a tilted spring) get analyze's numbers, bit for
    bit."""
    system = rollspring.load_system("hoop-cylinder")
    ds = sweep(system, {"bodies.hoop.radius": [0.12]}, 0.2, metrics=[*LINEAR])
    a = analyze(apply_values(system_to_json(system), system, {"bodies.hoop.radius": 0.12}))
    assert ds["omega"].values[0].tolist() == [m.omega for m in a.modes]
    assert ds["required_mu_linear"].values[0].tolist() == a.required_mu.tolist()


def _plan(name: str, vary: dict, chunk: int, **kwargs) -> SweepPlan:
    system = rollspring.load_system(name)
    paths = tuple(vary)
    values = tuple(tuple(float(x) for x in v) for v in vary.values())
    grid = Grid(paths, values, chunk_shape(tuple(len(v) for v in values), chunk))
    plan = SweepPlan(
        system=system_to_json(system),
        grid=grid,
        duration=0.5,
        rtol=1e-8,
        on_slip="stop",
        metrics=tuple(
            kwargs.pop("metrics", ("omega", "status", "period_measured", "first_slip_time"))
        ),
        refine_slip=True,
    )
    return _choose_step(plan, None)


GRIDS = [
    (
        "hoop-cylinder",
        {
            "springs.0.stiffness": np.linspace(50, 150, 13),
            "bodies.cylinder.v": np.linspace(0, 0.3, 11),
        },
        7,
    ),
    (
        "hoop-cylinder",
        {
            "bodies.hoop.mu_static": [0.01, 0.5, np.inf],
            "bodies.hoop.mass": np.geomspace(0.1, 10, 9),
            "bodies.cylinder.v": [0.0, 1.0],
        },
        5,
    ),
    (
        "three-bodies",
        {
            "bodies.sphere.v": [0.0, 0.1],
            "springs.1.stiffness": np.linspace(1, 500, 17),
            "bodies.sphere.radius": [0.05, 0.1, 0.2],
        },
        4,
    ),
    (
        "frictionless",
        {"bodies.hoop.radius": [0.05, 0.07, 0.08], "springs.0.stiffness": [10.0, 100.0, 1000.0]},
        2,
    ),
]


@pytest.mark.parametrize(("name", "vary", "chunk"), GRIDS)
def test_planning_shortcut_equals_the_pass_over_the_chunks(name, vary, chunk) -> None:
    plan = _plan(name, vary, chunk)
    best = (-1.0, None)
    for index in range(plan.grid.n_chunks):
        omega, sample = plan_omega(plan, index)
        if sample is not None and omega > best[0]:
            best = (omega, sample)
    fast = grid_omega(plan)
    assert fast is not None
    assert fast[0] == best[0]
    assert list(fast[1][1]) == list(best[1][1])
    for key, values in best[1][1].items():
        assert np.array_equal(fast[1][1][key], values)


@pytest.mark.parametrize(("name", "vary", "chunk"), GRIDS[:3])
def test_chunks_together_equal_chunks_alone(name, vary, chunk) -> None:
    plan = _plan(name, vary, chunk)
    indices = list(range(plan.grid.n_chunks))
    together = compute_chunks(plan, indices)
    for index, arrays in zip(indices, together, strict=True):
        alone = compute_chunk(plan, index)
        assert list(arrays) == list(alone)
        for key, values in alone.items():
            assert np.array_equal(arrays[key], values, equal_nan=values.dtype.kind == "f"), key

"""Generated batch kernels against rollspring.physics on random system layouts (Hypothesis):
shapes, sliders, walls, off-centre and raised attachments, raised tracks, constant forces and
varied parameters. The generated code's accelerations, needed frictions, normal forces and
potential energy equal physics' generalised and contact forces (M7)-(M9) and energy (M5), and a
batch's motion equals that of ``simulate`` with the same integrator and step."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import HealthCheck, assume, given, settings
from hypothesis import strategies as st

from rollspring.physics import contact_forces, generalized_forces, potential_energy, system_arrays
from rollspring.simulate import simulate, simulate_batch
from rollspring.simulate.batch import cache
from rollspring.simulate.batch.api import kernel_fields
from rollspring.simulate.batch.codegen import _RS, BLOCK, LINE, Source
from rollspring.simulate.batch.parameters import parse_parameters
from rollspring.simulate.batch.plan import make_plan, probe
from tests.conftest import make_system

SHAPES = ("hoop", "cylinder", "sphere", "shell", "slider")
finite = {"allow_nan": False, "allow_infinity": False}


@st.composite
def layouts(draw):
    """A valid system of 1-3 bodies (rolling enforced: mu_s = inf) and its batch parameters
    (two runs)."""
    n = draw(st.integers(1, 3))
    bodies = []
    for i in range(n):
        shape = draw(st.sampled_from(SHAPES)) if i else draw(st.sampled_from(SHAPES[:4]))
        bodies.append(
            {
                "id": f"b{i}",
                "shape": shape,
                "mass": draw(st.floats(0.3, 3.0, **finite)),
                "radius": draw(st.floats(0.05, 0.2, **finite)),
                "track_height": draw(st.sampled_from([0.0, 0.0, 0.05, 0.12])),
                "x": 0.7 * i,
                "v": draw(st.floats(-0.3, 0.3, **finite)),
                **({} if shape == "slider" else {"mu_static": math.inf}),
            }
        )
    anchors = [{"id": "w", "x": -0.6, "y": draw(st.floats(0.0, 0.4, **finite))}]

    def attachment(i):
        if i < 0 or bodies[i]["shape"] == "slider":
            return {}
        kind = draw(st.sampled_from(["centre", "polar", "height"]))
        if kind == "polar":
            return {
                "radius": draw(st.floats(0.01, 0.9, **finite)) * bodies[i]["radius"],
                "angle": draw(st.floats(-180.0, 180.0, **finite)),
            }
        if kind == "height":  # on the centre vertical: below, at or above the centre
            return {"height": draw(st.sampled_from([0.3, 1.0, 1.6])) * bodies[i]["radius"]}
        return {}

    springs = []
    pairs = [(i, i + 1) for i in range(n - 1)] + [(-1, 0)]
    chosen = draw(st.lists(st.sampled_from(pairs), min_size=1, max_size=3, unique=True))
    for a, b in chosen:
        ends = ["w" if a < 0 else f"b{a}", f"b{b}"]
        entry = {
            "ends": ends,
            "stiffness": draw(st.floats(20.0, 200.0, **finite)),
            "at": [attachment(a), attachment(b)],
        }
        if draw(st.booleans()):
            entry["rest_length"] = draw(st.floats(0.3, 0.8, **finite))
        springs.append(entry)
    forces = []
    rolling = [i for i in range(n) if bodies[i]["shape"] != "slider"]
    if draw(st.booleans()):
        i = draw(st.sampled_from(rolling))
        forces.append(
            {
                "body": f"b{i}",
                "at": attachment(i),
                "fx": draw(st.floats(-1.0, 1.0, **finite)),
                "fy": draw(st.floats(-1.0, 1.0, **finite)),
            }
        )
    system = make_system(bodies, springs, anchors=anchors, forces=forces)
    keys = [f"bodies.b{i}.mass" for i in range(n)] + [f"bodies.b{i}.radius" for i in rolling]
    keys += [f"springs.{k}.stiffness" for k in range(len(springs))] + ["gravity"]
    varied = draw(st.lists(st.sampled_from(keys), max_size=3, unique=True))
    parameters = {}
    for key in varied:
        scale = draw(st.floats(0.8, 1.25, **finite))
        base = _value(system, key)
        parameters[key] = [base, base * scale]
    return system, parameters


def _value(system, key):
    parts = key.split(".")
    if parts[0] == "gravity":
        return system.gravity
    if parts[0] == "springs":
        return getattr(system.springs[int(parts[1])], parts[2])
    return getattr(next(b for b in system.bodies if b.id == parts[1]), parts[2])


def _run_system(system, parameters, run):
    """The system of one run, its parameters applied."""
    data = system.model_dump(exclude_none=True)
    for key, values in parameters.items():
        parts = key.split(".")
        if parts[0] == "gravity":
            data["gravity"] = values[run]
        elif parts[0] == "springs":
            data["springs"][int(parts[1])][parts[2]] = values[run]
        else:
            entry = next(b for b in data["bodies"] if b["id"] == parts[1])
            entry[parts[2]] = values[run]
    return make_system(data.pop("bodies"), data.pop("springs"), **data)


@settings(max_examples=15, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(layout=layouts(), seed=st.integers(0, 2**32 - 1))
def test_generated_forces_equal_the_physics(layout, seed):
    system, parameters = layout
    runs = parse_parameters(system, parameters)
    topology, fields = probe(system, runs.targets)
    plan = make_plan(system, runs, topology)
    included = np.arange(runs.n_runs)
    varying, constant, P, C = kernel_fields(plan, fields, included, BLOCK)
    module = cache.load_module(Source(plan, varying, constant, True).module())
    Pl = np.zeros(max(len(varying), 1) * _RS)
    for r in range(len(varying)):
        Pl[r * _RS : r * _RS + BLOCK] = P[r, :BLOCK]
    rng = np.random.default_rng(seed)
    n = plan.n
    for run in range(runs.n_runs):
        arrays = system_arrays(_run_system(system, parameters, run))
        for _ in range(3):
            q = rng.uniform(-0.8, 0.8, n) * np.where(arrays.rolls > 0, 1.0, 0.1)
            y = arrays.scale * q  # the kernel's state: centre displacements
            out = module.lane_state(Pl, C, run, *y)
            acc, friction, normal = (np.array(out[k * n : (k + 1) * n]) for k in range(3))
            energy = out[-1]
            expected = arrays.scale * generalized_forces(arrays, q) / arrays.inertia
            f_ref, n_ref = contact_forces(arrays, q)
            scale = np.max(np.abs(expected)) + 1e-300
            np.testing.assert_allclose(acc, expected, rtol=0, atol=1e-12 * scale)
            np.testing.assert_allclose(
                friction, f_ref, rtol=0, atol=1e-12 * (np.max(np.abs(f_ref)) + 1.0)
            )
            np.testing.assert_allclose(normal, n_ref, rtol=1e-12, atol=1e-12)
            u_ref = float(potential_energy(arrays, q))
            assert abs(energy - u_ref) <= 1e-11 * (abs(u_ref) + 1e-3)


@settings(max_examples=4, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(layout=layouts())
def test_a_batch_moves_as_simulate_with_the_same_step(layout):
    system, parameters = layout
    duration, h = 0.6, 2e-3
    batch = simulate_batch(system, parameters, duration, integrator="yoshida4", step=h)
    for run in range(batch.n_runs):
        single = simulate(
            _run_system(system, parameters, run),
            duration,
            integrator="yoshida4",
            step=h,
            n_output=7,
        )
        assume(single.status == "finished")
        assert batch.status_names[run] == "finished"
        assert single.n_steps == batch.n_steps
        span = np.max(np.abs(single.x - single.x[0])) + 1e-3
        np.testing.assert_allclose(batch.final_x[run], single.x[-1], rtol=0, atol=1e-10 * span)


@settings(max_examples=5, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(layout=layouts(), sizes=st.lists(st.integers(1, 20_000), min_size=1, max_size=40))
def test_a_blocks_buffers_start_on_cache_lines_whatever_the_heap(layout, sizes):
    """A block's state and varying fields start on a cache line (every row too), wherever the
    allocator puts the buffer: NumPy and Numba align arrays to 32 bytes only, and the lane
    loops ran 1.5 times slower on half of the heap's states (64-byte vectors straddling lines)."""
    system, parameters = layout
    runs = parse_parameters(system, parameters)
    topology, fields = probe(system, runs.targets)
    plan = make_plan(system, runs, topology)
    varying, constant, _, _ = kernel_fields(plan, fields, np.arange(runs.n_runs), BLOCK)
    source = Source(plan, varying, constant, True)
    module = cache.load_module(source.module())
    held = []  # the heap's state changed between calls: arrays of the drawn sizes kept alive
    for size in sizes:
        held.append(np.empty(size))
        state, fields_ = module.buffers()
        assert state.size == source.n_rows * _RS
        assert fields_.size == max(len(varying), 1) * _RS
        for array in (state, fields_):
            assert array.ctypes.data % LINE == 0
        assert fields_.ctypes.data >= state.ctypes.data + state.nbytes  # no overlap
    assert (_RS * 8) % LINE == 0  # so every row starts on a line


@settings(max_examples=8, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(layout=layouts())
def test_each_runs_linear_frequency_is_the_physics_one(layout):
    """``simulate_batch``'s ``omega`` (the step is chosen from it; ``plan._omegas`` writes the
    stiffness (M12)-(M13) vectorised over runs) is, run by run, the highest frequency of
    physics' stiffness at the initial placement, :math:`\\max|\\lambda|` of
    :math:`K v = \\lambda M v`, for the full stiffness and for its elastic part
    :math:`\\sum_s k_s b_s b_s^T` alone (off-centre ends, anchors, sliders, raised tracks and
    constant forces included)."""
    from scipy.linalg import eigh

    from rollspring.physics import mass_matrix, spring_state, stiffness_matrix

    system, parameters = layout
    batch = simulate_batch(system, parameters, 0.01, integrator="verlet", step=1e-3)
    assert batch.omega is not None
    for run in range(batch.n_runs):
        arrays = system_arrays(_run_system(system, parameters, run))
        q = np.zeros(arrays.n_bodies)
        mass = mass_matrix(arrays)
        lever = spring_state(arrays, q).lever
        elastic = np.einsum("s,si,sj->ij", arrays.stiffness, lever, lever)
        full = stiffness_matrix(arrays, q)
        highest = max(
            float(np.max(np.abs(eigh(0.5 * (k + k.T), mass, eigvals_only=True))))
            for k in (full, elastic)
        )
        assert batch.omega[run] == pytest.approx(math.sqrt(highest), rel=1e-9, abs=1e-9)

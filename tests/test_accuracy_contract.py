"""The accuracy contract of ``simulate(..., rtol)`` on random nonlinear systems.

The contract (README, "Accuracy"): every reported position (x, phi) and velocity (v, omega) at
every output time is within ``rtol |value| + rtol/10 scale`` of the exact motion, ``scale``
being that quantity's largest |value| over the run, for the default rtol and any rtol >= 1e-12.
The exact motion is a reference at a much finer step (Kahan-Li 8 at omega h <= 0.05, below the
phase step of rtol 1e-13, its outputs at step ends: no interpolation), itself cross-checked
against SciPy's DOP853 at rtol 1e-13 on the same equations of motion
(:func:`rollspring.physics.accelerations`).

The systems are random, seeded and deterministic (:func:`random_system`): 1-5 bodies of mixed
shapes (hoops, cylinders, spheres, shells, custom inertia, sliders), springs between neighbours
and across, walls (anchors, raised: tilted springs), off-centre and raised attachments, tracks at
different heights, springs released stretched or compressed by up to 20 % and bodies launched at
up to 1.5 m/s (rotations of several radians), friction high enough not to slip, a few periods of
motion. The contract's scope (:func:`in_scope`, stated in the README): motions whose stiffest
local frequency stays within :data:`LOCAL_FREQUENCY` of the linear one the step is chosen from,
and that are not chaotic over the run (a small change of the initial velocities is amplified by
at most :data:`AMPLIFICATION`); the candidates outside it are skipped, and counted.
"""

from __future__ import annotations

import math
from functools import cache
from typing import Any

import numpy as np
import pytest

from rollspring.model import System, system_from_dict
from rollspring.physics import (
    accelerations,
    spring_state,
    stiffness_matrix,
    system_arrays,
)
from rollspring.simulate import Trajectory, choose_scheme, simulate
from rollspring.simulate.integrators import INTEGRATORS, output_omega_step

#: quantities the contract covers: positions and velocities, per body
QUANTITIES = ("x", "phi", "v", "omega")
#: the contract's scope: the stiffest local frequency along the motion at most this many times
#: the linear one, and a perturbation of the initial velocities amplified at most this much
LOCAL_FREQUENCY, AMPLIFICATION = 1.5, 100.0
SEED = 20260413
N_SYSTEMS = 32  # systems in scope the test checks
N_OUTPUT = 301
RTOLS = (1e-8, 1e-6, 1e-10)  # the default first
REFERENCE_OMEGA_STEP = 0.05

_SHAPES = ("hoop", "cylinder", "sphere", "shell", "custom", "slider")
_SHAPE_WEIGHTS = (0.22, 0.22, 0.22, 0.12, 0.12, 0.10)


def _attachment(rng: np.random.Generator, shape: str, radius: float) -> dict[str, float]:
    """Off centre anywhere in the disc (60 %), on the centre vertical (25 %) or the centre."""
    if shape == "slider":
        return {}
    kind = rng.random()
    if kind < 0.6:
        return {
            "radius": float(radius * rng.uniform(0.2, 1.0)),
            "angle": float(rng.uniform(-180.0, 180.0)),
        }
    if kind < 0.85:
        return {"height": float(radius * rng.uniform(0.0, 2.0))}
    return {}


def linear_omegas(system: System, q: np.ndarray | None = None) -> np.ndarray:
    """sqrt|eigenvalues| of M^-1 K(q) (rad/s) at each row of ``q`` (default: the placement)."""
    arrays = system_arrays(system)
    rows = np.zeros((1, arrays.n_bodies)) if q is None else np.atleast_2d(q)
    root = 1.0 / np.sqrt(arrays.inertia)
    k = np.array([stiffness_matrix(arrays, row) for row in rows])
    scaled = k * root[None, :, None] * root[None, None, :]
    scaled = 0.5 * (scaled + np.swapaxes(scaled, 1, 2))
    return np.sqrt(np.abs(np.linalg.eigvalsh(scaled)))


def random_system(seed: int) -> tuple[System, float]:
    """A random nonlinear system and its duration (a few periods), from ``seed``."""
    rng = np.random.default_rng(seed)
    n = int(rng.integers(1, 6))
    bodies: list[dict[str, Any]] = []
    x = 0.0
    for i in range(n):
        shape = str(rng.choice(_SHAPES, p=_SHAPE_WEIGHTS))
        radius = float(rng.uniform(0.05, 0.2))
        entry: dict[str, Any] = {
            "id": f"b{i}",
            "shape": shape,
            "mass": float(math.exp(rng.uniform(math.log(0.3), math.log(3.0)))),
            "radius": radius,
            "x": x,
            "track_height": float(rng.choice([0.0, rng.uniform(-0.1, 0.1)])),
            "v": float(rng.uniform(-1.5, 1.5)),
            "mu_static": math.inf if rng.random() < 0.7 else 1000.0,
        }
        if shape == "custom":
            entry["inertia_factor"] = float(rng.uniform(0.1, 1.0))
        bodies.append(entry)
        x += float(rng.uniform(0.4, 0.7))
    # one body sits near x = 0, so positions pass near zero too
    shift = bodies[int(rng.integers(n))]["x"] + float(rng.uniform(-0.02, 0.02))
    for entry in bodies:
        entry["x"] -= shift
    anchors: list[dict[str, Any]] = []
    springs: list[dict[str, Any]] = []

    def add(a: int | str, b: int | str) -> None:
        ends = [bodies[e]["id"] if isinstance(e, int) else e for e in (a, b)]
        at = [
            _attachment(rng, bodies[e]["shape"], bodies[e]["radius"]) if isinstance(e, int) else {}
            for e in (a, b)
        ]
        stiffness = float(math.exp(rng.uniform(math.log(30.0), math.log(300.0))))
        springs.append({"ends": ends, "stiffness": stiffness, "at": at})

    if n == 1 or rng.random() < 0.6:  # a wall on the left, its hook raised: a tilted spring
        wall = {"id": "left", "x": bodies[0]["x"] - float(rng.uniform(0.4, 0.7))}
        anchors.append({**wall, "y": float(rng.uniform(0.0, 0.35))})
        add("left", 0)
    for i in range(n - 1):
        add(i, i + 1)
    for i in range(n - 2):
        if rng.random() < 0.25:
            add(i, i + 2)
    if rng.random() < 0.4:
        wall = {"id": "right", "x": bodies[-1]["x"] + float(rng.uniform(0.4, 0.7))}
        anchors.append({**wall, "y": float(rng.uniform(0.0, 0.35))})
        add(n - 1, "right")
    # gravity does not act on the rolling motion (no torque about the contact point): a strong
    # one keeps every body on its track however hard the springs pull up
    data: dict[str, Any] = {
        "bodies": bodies,
        "anchors": anchors,
        "springs": springs,
        "gravity": 200.0,
    }
    # each spring released stretched or compressed by up to 20 % of its initial length
    lengths = spring_state(system_arrays(system_from_dict(data)), np.zeros(n)).length
    for entry, length in zip(springs, lengths, strict=True):
        entry["rest_length"] = float(length * rng.uniform(0.8, 1.2))
    system = system_from_dict(data)
    omegas = linear_omegas(system)[0]
    fastest = float(np.max(omegas))
    slowest = float(np.min(omegas[omegas > 0.05 * fastest]))
    # three periods of the slowest mode, at most fifteen of the fastest
    duration = min(3 * 2 * math.pi / slowest, 15 * 2 * math.pi / fastest)
    return system, duration


def reference(
    system: System, duration: float, n_output: int = N_OUTPUT, finer: int = 0
) -> Trajectory:
    """The motion by Kahan-Li 8 at omega h <= 0.05 (omega: the fastest linear frequency; a
    phase error below 1e-14 after a hundred radians, a step below the phase step of rtol 1e-13),
    rounded down so that every output lands on a step end (no interpolation), with ``finer``
    more steps per output interval. Finer steps only add rounding: runs at omega h = 0.01 ...
    0.1 agree to a few 1e-13 of each quantity's scale."""
    omega = float(np.max(linear_omegas(system)))
    spacing = duration / (n_output - 1)
    step = spacing / (math.ceil(spacing * omega / REFERENCE_OMEGA_STEP) + finer)
    return simulate(
        system, duration, step=step, integrator="kahanli8", n_output=n_output, energy_tolerance=1e-6
    )


def independent(run: Trajectory, exact: Trajectory, duration: float) -> Trajectory:
    """``exact``, or when ``run`` took the reference's very scheme and step (bit for bit the
    same motion: no check at all), a reference one step per output interval finer."""
    if run.integrator != exact.integrator or not math.isclose(run.step or 0.0, exact.step or 0.0):
        return exact
    return reference(exact.system, duration, len(exact.t), finer=1)


def _q(system: System, trajectory: Trajectory) -> np.ndarray:
    arrays = system_arrays(system)
    return np.where(arrays.rolls > 0, trajectory.phi, trajectory.x - arrays.x0)


def in_scope(system: System, duration: float, exact: Trajectory) -> bool:
    """Whether the motion is in the contract's scope (see the module docstring)."""
    if exact.status != "finished":
        return False
    omegas = np.max(linear_omegas(system, _q(system, exact)), axis=1)
    if np.max(omegas) > LOCAL_FREQUENCY * omegas[0]:
        return False
    data = system.model_dump()
    eps = 1e-7
    for entry in data["bodies"]:
        entry["v"] = entry["v"] * (1 + eps) + 0.1 * eps
    moved = simulate(
        system_from_dict(data),
        duration,
        step=exact.step,
        integrator="kahanli8",
        n_output=len(exact.t),
        energy_tolerance=1e-6,
    )
    if moved.status != "finished":
        return False
    amplified = 0.0
    for name in ("phi", "v"):
        exact_values = getattr(exact, name)
        scale = np.max(np.abs(exact_values), axis=0)
        scale = np.where(scale > 0, scale, 1.0)
        change = np.abs(getattr(moved, name) - exact_values) / scale
        amplified = max(amplified, float(np.max(change)) / eps)
    return amplified <= AMPLIFICATION


def contract_ratio(run: Trajectory, exact: Trajectory, rtol: float) -> np.ndarray:
    """err / (rtol |exact| + rtol/10 scale) per output time, the worst over every quantity and
    body (<= 1: the contract holds at that time)."""
    worst = np.zeros(len(exact.t))
    for name in QUANTITIES:
        value, truth = getattr(run, name), getattr(exact, name)
        assert value.shape == truth.shape
        bound = rtol * np.abs(truth) + rtol / 10 * np.max(np.abs(truth), axis=0)
        error = np.abs(value - truth)
        ratio = np.divide(error, bound, out=np.where(error > 0, np.inf, 0.0), where=bound > 0)
        worst = np.maximum(worst, np.max(ratio, axis=1))
    return worst


@cache
def contract_systems(count: int = N_SYSTEMS, seed: int = SEED) -> tuple[list[Any], int]:
    """The first ``count`` random systems in scope (system, duration, reference) and how many
    candidates were skipped."""
    chosen: list[Any] = []
    skipped = 0
    index = 0
    while len(chosen) < count:
        system, duration = random_system(seed + index)
        index += 1
        exact = reference(system, duration)
        if in_scope(system, duration, exact):
            chosen.append((system, duration, exact))
        else:
            skipped += 1
    return chosen, skipped


@cache
def references(n_output: int) -> list[Trajectory]:
    """The references of :func:`contract_systems` at ``n_output`` outputs."""
    systems, _ = contract_systems()
    if n_output == N_OUTPUT:
        return [exact for _, _, exact in systems]
    return [reference(system, duration, n_output) for system, duration, _ in systems]


# the default rtol first; 301 and the default 2001 outputs (the phase sets the step and the
# outputs are interpolated inside the steps; outputs on step ends where that takes fewer steps:
# tests/test_simulate.py)
@pytest.mark.parametrize("n_output", [N_OUTPUT, 2001])
@pytest.mark.parametrize("rtol", RTOLS)
def test_every_output_is_within_the_contract(rtol, n_output):
    systems, skipped = contract_systems()
    assert len(systems) >= 30 and skipped < len(systems)
    worst = 0.0
    on_step_ends = 0
    for (system, duration, _), exact in zip(systems, references(n_output), strict=True):
        run = simulate(system, duration, rtol=rtol, n_output=n_output)
        assert run.status == "finished"
        np.testing.assert_array_equal(run.t, exact.t)
        ratio = contract_ratio(run, independent(run, exact, duration), rtol)
        assert np.all(ratio <= 1.0), (system.model_dump(), float(np.max(ratio)))
        worst = max(worst, float(np.max(ratio)))
        on_step_ends += run.n_steps % (n_output - 1) == 0
    assert worst > 0.0  # the runs are not the reference itself
    if rtol == RTOLS[0]:  # at the default rtol the phase sets the step: outputs interpolated
        assert len(systems) - on_step_ends > 0


def test_the_reference_agrees_with_scipy_dop853():
    """The reference against SciPy's DOP853 at rtol 1e-13 on the NumPy equations of motion: the
    two agree to 1e-11 of each quantity's scale (measured: a few 1e-12, mostly DOP853's own
    error; the reference at steps 0.4 and 2 times its own moves by a few 1e-13)."""
    import scipy.integrate

    systems, _ = contract_systems()
    for system, duration, exact in systems[:4]:
        arrays = system_arrays(system)
        n = arrays.n_bodies

        def rhs(_t, y, arrays=arrays, n=n):
            return np.concatenate([y[n:], accelerations(arrays, y[:n])])

        y0 = np.concatenate([np.zeros(n), arrays.v0 / arrays.scale])
        solution = scipy.integrate.solve_ivp(
            rhs, (0.0, duration), y0, method="DOP853", t_eval=exact.t, rtol=1e-13, atol=1e-15
        )
        assert solution.success
        q, qdot = solution.y[:n].T, solution.y[n:].T
        scipy_values = {
            "x": arrays.x0 + arrays.scale * q,
            "phi": arrays.rolls * q,
            "v": arrays.scale * qdot,
            "omega": arrays.rolls * qdot,
        }
        for name in QUANTITIES:
            truth = getattr(exact, name)
            scale = np.max(np.abs(truth), axis=0)
            error = np.abs(scipy_values[name] - truth)
            assert np.all(error <= 1e-11 * scale + 1e-300), name


def test_the_step_puts_outputs_on_step_ends_when_that_takes_fewer_steps():
    """The contract's step: interpolated outputs within rtol/10 (with their safety factor), or
    a whole fraction of the output spacing within the phase bound, whichever is fewer steps."""
    scheme = INTEGRATORS["kahanli8"]
    # a short run at a tight rtol, where the interpolant, not the phase, sets the step: 3 steps
    # per output beat the interpolated ones
    omega, rtol, duration = 10.0, 1e-12, 1.0
    radians = max(omega * duration, 2 * math.pi)
    assert output_omega_step(rtol) < scheme.phase_omega_step(rtol, radians)
    n_output = 51
    spacing = duration / (n_output - 1)
    step = scheme.contract_step(omega, duration, rtol, n_output)
    per_output = spacing / step
    assert per_output == pytest.approx(round(per_output), rel=1e-12) and round(per_output) == 3
    assert omega * step <= scheme.phase_omega_step(rtol, radians)
    assert omega * spacing / (round(per_output) - 1) > scheme.phase_omega_step(rtol, radians)
    interpolated = scheme.contract_step(omega, duration, rtol)
    assert omega * interpolated == pytest.approx(output_omega_step(rtol), rel=1e-12)
    assert (n_output - 1) * round(per_output) < math.ceil(duration / interpolated)
    assert choose_scheme(omega, duration, rtol, "kahanli8", n_output) == ("kahanli8", step)
    # dense outputs: interpolating inside fewer, longer steps is cheaper
    n_output = 2001
    step = scheme.contract_step(omega, duration, rtol, n_output)
    assert step == scheme.contract_step(omega, duration, rtol) > duration / (n_output - 1)
    # where the phase sets the step (most runs: the septic interpolant rarely binds), outputs
    # are interpolated inside steps of the phase bound
    rtol, duration = 1e-8, 100.0
    radians = omega * duration
    step = scheme.contract_step(omega, duration, rtol, n_output)
    assert omega * step == pytest.approx(scheme.phase_omega_step(rtol, radians), rel=1e-12)
    # the safety factors shrink omega h below the phase error of rtol/10 and the sine's
    # interpolation error of rtol/10
    for name, integrator in INTEGRATORS.items():
        unsafe = (0.1 * rtol / (integrator.error_constant * radians)) ** (1 / integrator.order)
        assert integrator.phase_omega_step(rtol, radians) < unsafe, name
    assert output_omega_step(rtol) < (2.71e6 * 0.1 * rtol) ** (1 / 7)

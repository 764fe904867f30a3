"""The accuracy contract of ``simulate(..., rtol)``: the error of every output against a fine
reference on random nonlinear systems, the safety factors of the step that make the contract
hold, and what they cost in steps.

The contract (README, "Accuracy"): every output position (x, phi) and velocity (v, omega) within
``rtol |value| + rtol/10 scale`` of the exact motion (``scale``: that quantity's largest |value|
over the run). The systems and the reference are those of ``tests/test_accuracy_contract.py``
(random, seeded, in the contract's scope; the reference: Kahan-Li 8 at omega h <= 0.05, its
outputs at step ends, a different step from the run's).
An output has two errors, measured apart:

* **A, the integration** (the state at step ends): each scheme at the step of a phase error of
  rtol/10 (``Integrator.phase_omega_step`` without its safety factor), its
  outputs on step ends. The ratio error / contract falls as h^p: the safety factor of a scheme
  is the largest factor on omega h that brings every ratio to TARGET or below.
* **B, the interpolated outputs** (septic Hermite inside a step, ``kernels.stepping._hermite``):
  evaluated here on the reference itself, its states, accelerations and jerks at step ends,
  against the reference between them, at the step of ``output_omega_step`` without its safety
  factor. Its error / contract is the same at every rtol (the step goes as rtol^(1/7)); it
  falls as h^7 (the velocity's; the position's as h^8).
* **C, end to end**: ``simulate(system, T, rtol=rtol)`` as it is now against the rule before
  the contract (the phase error and the interpolant within rtol, no safety factors): the worst
  ratio and the steps taken, over the test set (rtol 1e-11 and 1e-12 show the rounding floor
  of double precision, a few 1e-13 of the scale) and on runs of the hoop-cylinder preset.

Run: ``python bench/bench_accuracy.py`` (two to four minutes; ``--systems 40``).
"""

from __future__ import annotations

import argparse
import math
import sys
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
sys.path.insert(0, str(Path(__file__).resolve().parent.parent))

from common import machine_note, print_table

from rollspring import load_system
from rollspring.analysis import find_equilibrium
from rollspring.physics import accelerations, stiffness_matrix, system_arrays
from rollspring.simulate import Trajectory, simulate
from rollspring.simulate.integrators import (
    CONTRACT_SHARE,
    INTEGRATORS,
    MAX_OMEGA_STEP,
    OUTPUT_SAFETY,
    output_omega_step,
)
from tests.test_accuracy_contract import (
    QUANTITIES,
    contract_ratio,
    contract_systems,
    independent,
    linear_omegas,
    reference,
)

#: each error (A, B) at most this share of the contract: together at most 0.8 of it
TARGET = 0.4
RTOLS = (1e-4, 1e-6, 1e-8, 1e-10, 1e-11, 1e-12)
#: the safety factors are fitted on these (tighter ones approach the round-off floor)
FITTED = (1e-4, 1e-6, 1e-8, 1e-10)
N_OUTPUT = 301
MAX_STEPS = 2_000_000  # skip a scheme at an rtol that needs more steps than this
#: the interpolant before the contract: quintic Hermite, (omega h)^6/46080 of the amplitude in
#: position and (omega h)^5/13420 in velocity
LEGACY_POSITION, LEGACY_VELOCITY = 46080.0, 13420.0


def omega_max(system) -> float:
    """The fastest linear frequency, as ``simulate`` takes it: at the placement and at the
    equilibrium."""
    arrays = system_arrays(system)
    q_eq = find_equilibrium(arrays).q
    return float(np.max(linear_omegas(system, np.stack([np.zeros(arrays.n_bodies), q_eq]))))


def _radians(omega: float, duration: float) -> float:
    return max(omega * duration, 2 * math.pi)


def legacy_choice(omega: float, duration: float, rtol: float) -> tuple[str, float]:
    """The step rule before the contract: phase error and interpolant within rtol of the
    amplitude, no safety factors; the scheme with the fewest force evaluations."""
    best = None
    for name, scheme in INTEGRATORS.items():
        omega_step = min(
            scheme.omega_step(rtol, _radians(omega, duration)),
            (LEGACY_POSITION * rtol) ** (1.0 / 6.0),
            (LEGACY_VELOCITY * rtol) ** (1.0 / 5.0),
        )
        cost = scheme.stages * omega * duration / omega_step
        if best is None or cost < best[2]:
            best = (name, omega_step / omega, cost)
    assert best is not None
    return best[0], best[1]


def phase_omega_step(name: str, omega: float, duration: float, rtol: float) -> float:
    """omega h of a phase error of rtol/10 over the run, without safety factor or cap."""
    scheme = INTEGRATORS[name]
    radians = _radians(omega, duration)
    result: float = (CONTRACT_SHARE * rtol / (scheme.error_constant * radians)) ** (
        1.0 / scheme.order
    )
    return result


# -- A: the integration, outputs on step ends ----------------------------------------------------


def integration_ratio(system, duration: float, name: str, h: float, rtol: float):
    """Worst contract ratio of scheme ``name`` at about step ``h`` (at most h), every output on
    a step end; returns (ratio, steps) or None past MAX_STEPS."""
    steps = math.ceil(duration / h * (1 - 1e-12))
    if steps > MAX_STEPS:
        return None
    every = max(1, math.ceil(steps / 3000))
    intervals = math.ceil(steps / every)
    n_output = intervals + 1
    step = duration / (intervals * every)
    run = simulate(
        system, duration, step=step, integrator=name, n_output=n_output, energy_tolerance=1.0
    )
    exact = independent(run, reference(system, duration, n_output), duration)
    if run.status != "finished":
        return math.inf, run.n_steps
    return float(np.max(contract_ratio(run, exact, rtol))), run.n_steps


def part_a(systems, omegas) -> dict[str, float]:
    rows = []
    factors: dict[str, float] = {}
    for name, scheme in INTEGRATORS.items():
        needed = math.inf
        worst_ratio = {}
        for rtol in RTOLS:
            worst = 0.0
            for (system, duration, _), omega in zip(systems, omegas, strict=True):
                phase = phase_omega_step(name, omega, duration, rtol)
                used = min(phase, MAX_OMEGA_STEP)
                measured = integration_ratio(system, duration, name, used / omega, rtol)
                if measured is None:
                    worst = math.nan
                    break
                ratio, _ = measured
                worst = max(worst, ratio)
                if ratio > 0 and rtol in FITTED:
                    needed = min(needed, used / phase * (TARGET / ratio) ** (1 / scheme.order))
            worst_ratio[rtol] = worst
        factors[name] = needed
        rows.append(
            [name, *(f"{worst_ratio[r]:.3g}" for r in RTOLS), f"{needed:.3f}", f"{scheme.safety:g}"]
        )
    print_table(
        "A. Integration (outputs on step ends), the step of a phase error of rtol/10 without "
        f"safety: worst error / contract over {len(systems)} systems, and the factor on omega h "
        f"that brings every ratio to {TARGET} (error ~ h^p)",
        ["scheme", *(f"rtol {r:.0e}" for r in RTOLS), "factor needed", "safety in use"],
        rows,
    )
    return factors


# -- B: the interpolated outputs -----------------------------------------------------------------


def hermite_ratio(system, exact: Trajectory, every: int, rtol: float) -> float:
    """Worst contract ratio of the septic Hermite outputs of steps ``every`` output spacings
    long, built from the reference's states, accelerations and jerks (-K(q) qdot / J) at the
    step ends."""
    arrays = system_arrays(system)
    rolls = arrays.rolls > 0
    q = np.where(rolls, exact.phi, exact.x - arrays.x0)
    qdot = np.where(rolls, exact.omega, exact.v)
    acc = accelerations(arrays, q)
    t = exact.t
    h = t[every] - t[0]
    n_steps = (len(t) - 1) // every
    last = n_steps * every
    ends = np.arange(0, last + 1, every)
    jerk = np.zeros_like(q)
    for row in ends:
        jerk[row] = -(stiffness_matrix(arrays, q[row]) @ qdot[row]) / arrays.inertia
    index = np.arange(last + 1)
    start = np.minimum(index // every, n_steps - 1) * every
    end = start + every
    t1 = ((index - start) / every)[:, None]
    t2 = t1 * t1
    t3 = t2 * t1
    t4 = t3 * t1
    hq0 = 1 + t4 * (-35 + t1 * (84 + t1 * (-70 + 20 * t1)))
    hv0 = t1 + t4 * (-20 + t1 * (45 + t1 * (-36 + 10 * t1)))
    ha0 = 0.5 * t2 + t4 * (-5 + t1 * (10 + t1 * (-7.5 + 2 * t1)))
    hj0 = t3 / 6 + t4 * (-2 / 3 + t1 * (1 + t1 * (-2 / 3 + t1 / 6)))
    hv1 = t4 * (-15 + t1 * (39 + t1 * (-34 + 10 * t1)))
    ha1 = t4 * (2.5 + t1 * (-7 + t1 * (6.5 - 2 * t1)))
    hj1 = t4 * (-1 / 6 + t1 * (0.5 + t1 * (-0.5 + t1 / 6)))
    dq0 = t3 * (-140 + t1 * (420 + t1 * (-420 + 140 * t1)))
    dv0 = 1 + t3 * (-80 + t1 * (225 + t1 * (-216 + 70 * t1)))
    da0 = t1 + t3 * (-20 + t1 * (50 + t1 * (-45 + 14 * t1)))
    dj0 = 0.5 * t2 + t3 * (-8 / 3 + t1 * (5 + t1 * (-4 + 7 / 6 * t1)))
    dv1 = t3 * (-60 + t1 * (195 + t1 * (-204 + 70 * t1)))
    da1 = t3 * (10 + t1 * (-35 + t1 * (39 - 14 * t1)))
    dj1 = t3 * (-2 / 3 + t1 * (2.5 + t1 * (-3 + 7 / 6 * t1)))
    q0, q1, v0, v1 = q[start], q[end], qdot[start], qdot[end]
    a0, a1, j0, j1 = acc[start], acc[end], jerk[start], jerk[end]
    q_h = (
        hq0 * q0
        + (1 - hq0) * q1
        + h * (hv0 * v0 + hv1 * v1)
        + h * h * (ha0 * a0 + ha1 * a1 + h * (hj0 * j0 + hj1 * j1))
    )
    v_h = (
        dq0 * (q0 - q1) / h
        + dv0 * v0
        + dv1 * v1
        + h * (da0 * a0 + da1 * a1 + h * (dj0 * j0 + dj1 * j1))
    )
    values = {
        "x": arrays.x0 + arrays.scale * q_h,
        "phi": arrays.rolls * q_h,
        "v": arrays.scale * v_h,
        "omega": arrays.rolls * v_h,
    }
    worst = 0.0
    for name in QUANTITIES:
        truth = getattr(exact, name)[: last + 1]
        scale = np.max(np.abs(getattr(exact, name)), axis=0)
        bound = rtol * np.abs(truth) + rtol / 10 * scale
        error = np.abs(values[name] - truth)
        ratio = np.divide(error, bound, out=np.where(error > 0, np.inf, 0.0), where=bound > 0)
        worst = max(worst, float(np.max(ratio)))
    return worst


def part_b(systems, omegas) -> float:
    unsafe = {rtol: output_omega_step(rtol) / OUTPUT_SAFETY for rtol in RTOLS}
    finest = min(min(unsafe.values()), MAX_OMEGA_STEP)
    worst = dict.fromkeys(RTOLS, 0.0)
    needed = math.inf
    for (system, duration, _), omega in zip(systems, omegas, strict=True):
        # outputs at least 6 per step at the finest rtol
        n_output = math.ceil(omega * duration / (finest / 6)) + 1
        exact = reference(system, duration, n_output)
        spacing = omega * duration / (n_output - 1)  # omega * output spacing
        for rtol in RTOLS:
            target = min(unsafe[rtol], MAX_OMEGA_STEP)
            every = math.ceil(target / spacing)  # a step at least the rule's (conservative)
            ratio = hermite_ratio(system, exact, every, rtol)
            # scaled to the rule's step as h^7
            ratio_at_rule = ratio * (target / (every * spacing)) ** 7
            worst[rtol] = max(worst[rtol], ratio_at_rule)
            if ratio > 0 and unsafe[rtol] <= MAX_OMEGA_STEP and rtol in FITTED:
                needed = min(needed, every * spacing / unsafe[rtol] * (TARGET / ratio) ** (1 / 7))
    print_table(
        "B. Interpolated outputs (septic Hermite from the reference's step ends) at the step of "
        "an interpolation error of rtol/10 without safety: worst error / contract over "
        f"{len(systems)} systems, and the factor on omega h that brings it to {TARGET}",
        [*(f"rtol {r:.0e}" for r in RTOLS), "factor needed", "OUTPUT_SAFETY in use"],
        [[*(f"{worst[r]:.3g}" for r in RTOLS), f"{needed:.3f}", f"{OUTPUT_SAFETY:g}"]],
    )
    return needed


# -- C: end to end, before and after -------------------------------------------------------------


def part_c(systems, omegas) -> None:
    rows = []
    for rtol in RTOLS:
        worst = [0.0, 0.0]  # before, now
        steps_old = steps_new = force_old = force_new = 0
        on_step_ends = 0
        schemes_old: set[str] = set()
        schemes_new: set[str] = set()
        for (system, duration, exact), omega in zip(systems, omegas, strict=True):
            name, h = legacy_choice(omega, duration, rtol)
            old = simulate(system, duration, rtol=rtol, step=h, integrator=name, n_output=N_OUTPUT)
            new = simulate(system, duration, rtol=rtol, n_output=N_OUTPUT)
            for run in (old, new):
                assert run.status == "finished", run.message
            for run, slot in ((old, 0), (new, 1)):
                ratio = contract_ratio(run, independent(run, exact, duration), rtol)
                worst[slot] = max(worst[slot], float(np.max(ratio)))
            steps_old += old.n_steps
            steps_new += new.n_steps
            force_old += old.n_steps * INTEGRATORS[old.integrator].stages
            force_new += new.n_steps * INTEGRATORS[new.integrator].stages
            schemes_old.add(old.integrator)
            schemes_new.add(new.integrator)
            on_step_ends += new.n_steps % (N_OUTPUT - 1) == 0
        rows.append(
            [
                f"{rtol:.0e}",
                f"{worst[0]:.3g}",
                f"{worst[1]:.3g}",
                steps_old,
                steps_new,
                f"{steps_new / steps_old:.2f}",
                f"{force_new / force_old:.2f}",
                ", ".join(sorted(schemes_new)),
                on_step_ends,
            ]
        )
    print_table(
        f"C. simulate() end to end on the {len(systems)} systems ({N_OUTPUT} outputs): worst "
        "error / contract and steps, before the contract (no safety) and now",
        [
            "rtol",
            "worst before",
            "worst now",
            "steps before",
            "steps now",
            "ratio",
            "force evaluations ratio",
            "schemes now",
            "runs with outputs on step ends",
        ],
        rows,
    )
    # long runs of the paper's system: the phase error, not the interpolant, sets the step
    system = load_system("hoop-cylinder")
    omega = omega_max(system)
    rows = []
    for duration in (10.0, 100.0, 1000.0):
        for rtol in (1e-6, 1e-8, 1e-10):
            name, h = legacy_choice(omega, duration, rtol)
            old = simulate(system, duration, rtol=rtol, step=h, integrator=name)
            new = simulate(system, duration, rtol=rtol)  # the default 2001 outputs
            rows.append(
                [
                    f"{duration:g}",
                    f"{rtol:.0e}",
                    f"{old.integrator} {old.n_steps}",
                    f"{new.integrator} {new.n_steps}",
                    f"{new.n_steps * INTEGRATORS[new.integrator].stages / (old.n_steps * INTEGRATORS[old.integrator].stages):.2f}",  # noqa: E501
                ]
            )
    print_table(
        "C'. The hoop-cylinder preset, the default 2001 outputs: steps before and now (ratio in "
        "force evaluations)",
        ["T (s)", "rtol", "before", "now", "ratio"],
        rows,
    )


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--systems", type=int, default=40, help="random systems in scope")
    args = parser.parse_args()
    print(machine_note())
    began = time.perf_counter()
    systems, skipped = contract_systems(args.systems)
    print(f"{len(systems)} systems in scope ({skipped} candidates outside it skipped)")
    omegas = [omega_max(system) for system, _, _ in systems]
    part_a(systems, omegas)
    part_b(systems, omegas)
    part_c(systems, omegas)
    print(f"{time.perf_counter() - began:.0f} s")


if __name__ == "__main__":
    main()

"""The JSON summary of a run (README, "Summary"): status, energies, periods, extremes, events.

:func:`summary` is what ``rollspring simulate --json`` prints (with the columns' units, see
:func:`rollspring.outputs.summary_json`): the energy error (against the energy at release; the
growth above the running minimum once energy is lost), the measured and linear periods, each
body's largest friction ratio and smallest normal force over the whole run
(:mod:`rollspring.simulate.extremes`), the first slip and lift-off, the events and the final
state. :func:`singular_springs` explains an energy error no step can cure.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from rollspring.analysis import stationary_weights
from rollspring.simulate.dissipation import dissipated_energy
from rollspring.simulate.extremes import continuous_extremes, measured_period
from rollspring.simulate.run_state import RunState
from rollspring.simulate.trajectory import Trajectory

__all__ = ["singular_springs", "summary"]


def summary(trajectory: Trajectory, run: RunState) -> dict[str, Any]:
    """The JSON summary (see the README): status, energies, periods, extremes, events. Sets
    ``trajectory.stationary_x`` (X̂) when the zero modes are known."""
    arrays = run.arrays
    linear = run.plan.linear
    q_eq = linear.equilibrium.q
    lowest = linear.vectors[:, linear.oscillating[0]] if linear.oscillating else None
    mass = arrays.inertia  # the diagonal of M
    period_linear = linear.period
    # the modes at equilibrium, when every zero mode is among them (the stationary point)
    modes = (linear.vectors, linear.kinds) if linear.complete else None
    n = arrays.n_bodies
    ids = arrays.ids
    extremes = continuous_extremes(run, trajectory)
    conservative = (
        not run.plan.damped
        and not arrays.resisted
        and not any(e["kind"] == "slip" for e in run.events)
    )
    energy = trajectory.energy
    e0 = float(energy[0])
    high, low = float(energy.max()), float(energy.min())  # NaN if any is
    # relative to the energy at release, as the run's own check (a blow-up to 385 E0 is an
    # error of 384, not ~1); the largest |E| only when E0 is 0
    scale = abs(e0) or max(max(abs(high), abs(low)) if high == high else math.nan, 1e-300)
    # what damping, kinetic friction and rolling resistance turned into heat (0 for a
    # conservative run)
    dissipated = dissipated_energy(run, trajectory.t)
    if conservative:  # the largest |E - E0|: at the largest or the smallest E
        energy_error = (max(high - e0, e0 - low) if high == high else math.nan) / scale
    else:  # the balance E + W = E0 at every output time, relative to the energies exchanged
        exchanged = max(
            scale, float(np.max(trajectory.kinetic)), float(np.max(np.abs(trajectory.potential)))
        )
        balance = float(np.max(np.abs(energy + dissipated.sum(axis=1) - e0)))
        energy_error = balance / exchanged if math.isfinite(exchanged) else math.nan
    # weights of the stationary point (M14) at equilibrium, from the normal modes there (None
    # when the zero modes are not all known: more zero and unstable modes than were computed)
    weights = stationary_weights(arrays, *modes) if modes is not None else None
    if weights is not None:
        trajectory.stationary_x = trajectory.x @ weights
    period = measured_period(run, trajectory, lowest, mass, q_eq) if lowest is not None else None
    first = {
        kind: next(
            ({"time": e["time"], "body": e["body"]} for e in run.events if e["kind"] == kind), None
        )
        for kind in ("slip", "liftoff")
    }
    final = {
        "time": float(trajectory.t[-1]),
        "cm_x": float(trajectory.cm_x[-1]),
        "bodies": {
            name: {
                "x": float(trajectory.x[-1, i]),
                "phi": float(trajectory.phi[-1, i]),
                "v": float(trajectory.v[-1, i]),
                "omega": float(trajectory.omega[-1, i]),
            }
            for i, name in enumerate(ids)
        },
    }
    return {
        "status": trajectory.status,
        "message": trajectory.message,
        "duration": float(run.grid[-1]),
        "integrator": run.integrators_used,
        "step": run.symplectic_step,
        "steps": int(run.n_steps),
        "steps_by_integrator": dict(run.steps_by_integrator),
        "retries": run.plan.retries,
        "energy": e0,
        "energy_error": energy_error,
        "energy_dissipated": float(dissipated[-1].sum()),
        "dissipated_by": {
            "damping": float(dissipated[-1, 0]),
            "kinetic_friction": float(dissipated[-1, 1]),
            "rolling_resistance": float(dissipated[-1, 2]),
        },
        "period_measured": period,
        "period_linear": period_linear,
        # per rolling body (a slider has none); None for one that never rolled in the run
        # (it slipped from the release to the end)
        "max_friction_ratio": {
            ids[i]: extremes["ratio"][i] if extremes["ratio"][i] > -math.inf else None
            for i in range(n)
            if arrays.rolls[i] > 0
        },
        "min_normal_force": {ids[i]: extremes["normal"][i] for i in range(n)},
        "first_slip": first["slip"],
        "first_liftoff": first["liftoff"],
        "events": trajectory.events,
        "final": final,
    }


def singular_springs(trajectory: Trajectory) -> str:
    """Why a run may not keep its energy whatever the step: a spring whose length passes
    through (nearly) zero, where the direction of its force turns over at once (the motion is
    not smooth there). Empty when no spring does."""
    lengths = trajectory.spring_length
    if lengths.size == 0:
        return ""
    shortest = np.nanmin(lengths, axis=0)
    longest = np.nanmax(lengths, axis=0)
    near_zero = np.flatnonzero(shortest <= 1e-2 * longest)
    if near_zero.size == 0:
        return ""
    k = int(near_zero[0])
    return (
        f"; spring {k} passes through (nearly) zero length (down to {shortest[k]:.3g} m), "
        "where its force turns direction at once: the motion is not smooth there"
    )

r"""The energy a run dissipates, so that damped, slipping and resisted runs check their energy
honestly.

Spring damping, kinetic friction and rolling resistance turn mechanical energy into heat at the
rate :math:`P` of :func:`rollspring.physics.mechanics.dissipated_power`, and the exact motion
keeps :math:`E(t) + W(t) = E_0` with :math:`W(t) = \int_0^t P\,dt`. :func:`dissipated_energy`
integrates :math:`P` along the computed motion itself: on every segment of the run that can
dissipate (a damped spring, a slipping body, a body with rolling resistance), between the
integrator's own step ends and the output times, by 5-point Gauss-Legendre quadrature on the
integrator's dense output (exact for polynomials of degree 9, above DOP853's interpolant; a
resisted body's power :math:`C_{rr} N R|\omega|` is smooth inside a segment, whose ends are
the instants it stops or turns), so that the balance error
:math:`\max_t |E + W - E_0|` (relative to the energies exchanged) measures the integration, not
the quadrature.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from rollspring.physics.arrays import FloatArray
from rollspring.physics.mechanics import dissipated_power
from rollspring.simulate.run_state import slip_velocities

if TYPE_CHECKING:
    from rollspring.simulate.run_state import RunState, Segment

__all__ = ["dissipated_energy", "power_at"]

#: The kinds of dissipation, a column each: spring damping, kinetic friction, rolling resistance.
_KINDS = 3

#: Gauss-Legendre nodes and weights on [-1, 1]: 5 points, exact to degree 9.
_NODES, _WEIGHTS = np.polynomial.legendre.leggauss(5)


def power_at(
    run: RunState,
    states: FloatArray,
    slipping: np.ndarray,
    sign: np.ndarray,
    spin: np.ndarray | None = None,
) -> FloatArray:
    """The power dissipated at rows of general states ``[x, phi, u, omega]`` of a segment with
    ``slipping`` bodies (W, shape ``(rows, 3)``: by damping, by kinetic friction, by rolling
    resistance): :func:`~rollspring.physics.mechanics.dissipated_power` of what the kernel
    observes there."""
    a, n = run.arrays, run.arrays.n_bodies
    rows = states.shape[0]
    slip = np.broadcast_to(slipping, (rows, n))
    observed = run.observe(states, slip, np.broadcast_to(sign, (rows, n)), spin)
    # a slipping body's slip velocity; a rolling body's is zero (its friction does no work)
    slip_velocity = slip_velocities(states, a.radius, n) * slip
    return dissipated_power(
        a,
        observed.length,
        observed.tension,
        observed.friction,
        slip_velocity,
        observed.normal,
        states[:, 3 * n : 4 * n],
    )


def _segment_work(
    run: RunState, segment: Segment, times: FloatArray
) -> tuple[FloatArray, FloatArray]:
    """The energy dissipated in ``segment`` (by damping, by friction, by rolling resistance: a
    column each) from its start to each of ``times`` (inside it), and over the whole
    segment."""
    if not segment.t1 > segment.t0:  # an empty segment (an event at its start)
        return np.zeros((times.size, _KINDS)), np.zeros(_KINDS)
    inside = segment.samples[(segment.samples > segment.t0) & (segment.samples < segment.t1)]
    nodes = np.unique(np.concatenate([[segment.t0, segment.t1], inside, times]))
    start, end = nodes[:-1], nodes[1:]
    half = 0.5 * (end - start)
    points = (0.5 * (start + end))[:, None] + half[:, None] * _NODES[None, :]
    states = np.atleast_2d(segment.evaluate(points.ravel()))
    power = power_at(run, states, segment.slipping, segment.sign, segment.spin)
    pieces = half[:, None] * np.einsum(
        "rpc,p->rc", power.reshape(-1, _NODES.size, _KINDS), _WEIGHTS
    )
    cumulative = np.concatenate([np.zeros((1, _KINDS)), np.cumsum(pieces, axis=0)])
    return cumulative[np.searchsorted(nodes, times)], cumulative[-1]


def dissipated_energy(run: RunState, times: FloatArray) -> FloatArray:
    r""":math:`W(t) = \int_0^t P\,dt` (J) at the output ``times`` (module docstring), shape
    ``(times, 3)``: by spring damping, by kinetic friction and by rolling resistance; zero for a
    run without damped springs or rolling resistance that never slipped."""
    work = np.zeros((times.size, _KINDS))
    lossy = run.plan.damped or run.arrays.resisted
    if not lossy and not any(segment.slipping.any() for segment in run.segments):
        return work
    done = np.zeros(_KINDS)  # dissipated before the current segment
    for segment in sorted(run.segments, key=lambda s: s.t0):
        if not lossy and not segment.slipping.any():
            continue
        within = (times > segment.t0) & (times <= segment.t1)
        partial, total = _segment_work(run, segment, times[within])
        work[within] = done + partial
        work[times > segment.t1] += total
        done += total
    return work

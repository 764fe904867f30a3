r"""The continuous extremes of a run and the period of its lowest mode.

:func:`continuous_extremes`: per body, :math:`\max |f|/N` while rolling and :math:`\min N` over
the whole run, not at output rows only: the candidates (the rows, the kernel's extremes over
every step, the adaptive steps) are refined on the integrator's own interpolant, in one
compiled call for the kernel's (:func:`_refine_together`), by nested grids and a parabola for
the others (:func:`_refine`). :func:`measured_period`: the mean period of the lowest mode's
coordinate from its first and last upward crossings, located by root-finding on the
interpolant.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from rollspring.physics.arrays import FloatArray
from rollspring.simulate import kernels
from rollspring.simulate.run_state import RunState, Segment
from rollspring.simulate.trajectory import Trajectory

__all__ = ["continuous_extremes", "measured_period"]


def continuous_extremes(run: RunState, trajectory: Trajectory) -> dict[str, list[float]]:
    r"""max |f|/N (while rolling) and min N per body over the whole run.

    Candidates are the output rows, the compiled kernel's extremes over every step, and the
    adaptive integrator's steps; the best candidate is refined by bounded Brent minimisation on
    the integrator's own interpolant over the neighbouring interval: the instant to 3e-5 of
    the interval (at most 0.5/omega), so the value, quadratic about the extreme, to about
    1e-9 relative."""
    n = run.n
    spacing = float(run.grid[1] - run.grid[0])
    # per body: the largest |f|/N over the rows while rolling, the smallest N, and their rows
    # (|f|/N, inf where N <= 0, -inf while slipping; the first row of each, as argmax/argmin)
    if run.grid_rows and len(run.observed) == 1 and run.block_extremes is not None:
        ratio, ratio_row, normal, normal_row = run.block_extremes.tolist()  # one rolling block
        ratio_row, normal_row = [int(r) for r in ratio_row], [int(r) for r in normal_row]
    else:
        found = kernels.row_extremes(trajectory.friction, trajectory.normal, trajectory.slipping)
        ratio, ratio_row, normal, normal_row = (values.tolist() for values in found)
    best: dict[tuple[str, int], tuple[float, float, float, Segment | None]] = {}

    def offer(
        kind: str, i: int, value: float, t: float, width: float, local: Segment | None = None
    ) -> None:
        old = best.get((kind, i))
        better = old is None or (value > old[0] if kind == "ratio" else value < old[0])
        if better:
            best[(kind, i)] = (value, t, width, local)

    # the kernel's extremes first: on a tie they win, as they carry their state
    for (kind, i), (value, t, width, kept) in run.step_extremes.items():
        offer(kind, i, value, t, width, kept)
    times = trajectory.t
    for i in range(n):
        if run.rolls[i]:
            offer("ratio", i, float(ratio[i]), float(times[ratio_row[i]]), spacing)
        offer("normal", i, float(normal[i]), float(times[normal_row[i]]), spacing)
    for segment in run.segments:
        if segment.samples.size < 2 or segment.slipping.all():
            continue
        states = segment.evaluate(segment.samples)
        slip = np.broadcast_to(segment.slipping, states[:, :n].shape)
        sign = np.broadcast_to(segment.sign, states[:, :n].shape)
        friction, normal, *_ = run.observe(states, slip, sign, segment.spin)
        width = float(np.max(np.diff(segment.samples)))
        for i in range(n):
            if run.rolls[i] and not segment.slipping[i]:
                with np.errstate(divide="ignore", invalid="ignore"):
                    r = np.where(normal[:, i] > 0, np.abs(friction[:, i]) / normal[:, i], np.inf)
                k = int(np.argmax(r))
                offer("ratio", i, float(r[k]), float(segment.samples[k]), width)
            k = int(np.argmin(normal[:, i]))
            offer("normal", i, float(normal[k, i]), float(segment.samples[k]), width)

    result = {"ratio": [0.0] * n, "normal": [math.inf] * n}
    # level centre springs (physics.springs_stay_level): N is the same at every instant,
    # exactly, so its smallest value is every row's and there is nothing to refine
    fixed = {key for key in best if key[0] == "normal" and run.constant_normal}
    for kind, i in fixed:
        result[kind][i] = float(best[(kind, i)][0])
    batched = {
        key: entry
        for key, entry in best.items()
        if key not in fixed
        and entry[3] is not None
        and getattr(entry[3], "start", None) is not None
        and math.isfinite(entry[0])
    }
    groups: dict[int, dict[tuple[str, int], Any]] = {}  # one per rolling segment (its model)
    for key, entry in batched.items():
        start = entry[3].start if entry[3] is not None else None
        assert start is not None  # batched: only segments with the state they start from
        groups.setdefault(id(start.model), {})[key] = entry
    for group in groups.values():
        for (kind, i), value in _refine_together(group, run).items():
            result[kind][i] = value
    for (kind, i), (value, t, width, local) in best.items():
        if (kind, i) in batched or (kind, i) in fixed:
            continue
        if np.isfinite(value):
            value = _refine(run, kind, i, value, t, width, local)
        result[kind][i] = float(value)
    return result


def _refine_together(
    entries: dict[tuple[str, int], Any], run: RunState
) -> dict[tuple[str, int], float]:
    """:func:`_refine` for many extremes at once, each on its own two-step segment from the
    state the kernel kept (one compiled call for all of them; in a large system each on the
    model of its body's ball, :func:`kernels.refine_windowed`)."""
    keys = list(entries)
    first = entries[keys[0]][3].start
    kinds = np.array([0 if kind == "ratio" else 1 for kind, _ in keys], dtype=np.int64)
    bodies = np.array([i for _, i in keys], dtype=np.int64)
    sign = [1.0 if kind == "ratio" else -1.0 for kind, _ in keys]
    best = np.array([entries[k][0] * sign[j] for j, k in enumerate(keys)])
    starts = [entries[k][3].start for k in keys]
    spans = np.array([min(2.0 * start.h, start.span) for start in starts])
    if first.ball is None:
        q0 = np.array([start.q for start in starts])
        v0 = np.array([start.v for start in starts])
        refined = kernels.refine_extremes(
            first.model, first.coeffs, first.h, q0, v0, kinds, bodies, best, spans
        ).tolist()
    else:
        offsets = np.zeros(len(starts) + 1, dtype=np.int64)
        np.cumsum([start.ball.size for start in starts], out=offsets[1:])
        refined = kernels.refine_windowed(
            first.model,
            first.coeffs,
            first.h,
            np.concatenate([start.q for start in starts]),
            np.concatenate([start.v for start in starts]),
            offsets,
            np.concatenate([start.ball for start in starts]),
            kinds,
            bodies,
            best,
            run.links(),
            spans,
        ).tolist()
    return {key: refined[j] * sign[j] for j, key in enumerate(keys)}


def _refine(
    run: RunState,
    kind: str,
    i: int,
    value: float,
    t: float,
    width: float,
    segment: Segment | None = None,
) -> float:
    """The extreme near ``t`` (within ``width``), on the interpolant of ``segment`` (by default
    the segment holding ``t``)."""
    if segment is None:
        segment = next((s for s in run.segments if s.t0 <= t <= s.t1), None)
    if segment is None or (segment.slipping[i] and kind == "ratio"):
        return value
    lo, hi = max(segment.t0, t - width), min(segment.t1, t + width)
    if not hi > lo:
        return value

    def values_at(times: FloatArray) -> FloatArray:
        states = segment.evaluate(times)
        slipping = np.broadcast_to(segment.slipping, (len(times), run.n))
        sign = np.broadcast_to(segment.sign, (len(times), run.n))
        f, nn, *_ = run.observe(states, slipping, sign, segment.spin)
        if kind == "ratio":
            with np.errstate(divide="ignore", invalid="ignore"):
                return np.where(nn[:, i] > 0, np.abs(f[:, i]) / nn[:, i], np.inf)
        return -nn[:, i]  # maximise -N

    # three grids of 9 points, each spanning the best point's neighbours on the last (spacing
    # width/256 at the end, omega * spacing < 0.004), then the vertex of the parabola through
    # the best point and its neighbours: the extreme to about 1e-10 relative
    for _ in range(3):
        times = np.linspace(lo, hi, 9)
        values = values_at(times)
        k = int(np.clip(np.argmax(values), 1, 7))
        if not np.all(np.isfinite(values[k - 1 : k + 2])):
            best = float(np.max(values))
            break
        a, b, c = values[k - 1 : k + 2]
        curvature = a - 2 * b + c
        best = float(np.max(values))
        if curvature < 0 and abs(a - c) <= -2 * curvature:  # the vertex lies between a and c
            best = max(best, float(b - (c - a) ** 2 / (8 * curvature)))
        lo, hi = times[k - 1], times[k + 1]
    refined = best if kind == "ratio" else -best
    return max(value, refined) if kind == "ratio" else min(value, refined)


def measured_period(
    run: RunState, trajectory: Trajectory, mode: FloatArray, mass: FloatArray, q_eq: FloatArray
) -> float | None:
    r"""Mean period of the lowest mode's coordinate :math:`s = v_1^T M (q - q^*)`, from its
    upward crossings of its mean, each located by root-finding on the integrator's interpolant.
    ``mass``: the diagonal of M."""
    arrays = run.arrays
    weights = mode * mass

    def signal_of(states: FloatArray) -> FloatArray:
        n = run.n
        q = np.where(run.rolls, states[..., n : 2 * n], states[..., :n] - arrays.x0)
        return (q - q_eq) @ weights

    if len(run.crossings) == 1 and len(run.segments) == 1 and run.crossings[0][0] >= 2:
        # one rolling segment: the kernel counted the upward zero crossings of the signal at
        # every step and kept the states before the first and the last
        count, (first, last) = run.crossings[0]
        starts = [seg.start for seg in (first, last) if seg.start is not None]
        assert len(starts) == 2  # the kernel kept both states
        times = [
            start.t
            + kernels.signal_zero(
                start.model,
                start.coeffs,
                start.h,
                start.q,
                start.v,
                run.plan.mode_weights,
                run.plan.q_ref,
            )
            for start in starts
        ]
        result: float | None = (times[1] - times[0]) / (count - 1)
        return result
    signal = signal_of(np.concatenate([trajectory.x, trajectory.phi], axis=1))  # q of them
    level = 0.5 * (float(np.max(signal)) + float(np.min(signal)))
    values = signal - level
    upward = np.flatnonzero((values[:-1] < 0) & (values[1:] >= 0))
    if upward.size < 2:
        return None
    import scipy.optimize  # on demand, as above

    crossings = []
    for k in (upward[0], upward[-1]):  # the mean period needs only the first and the last
        lo, hi = float(trajectory.t[k]), float(trajectory.t[k + 1])
        segment = next((s for s in run.segments if s.t0 <= lo and hi <= s.t1 + 1e-15), None)
        if segment is None:
            return None
        crossings.append(
            scipy.optimize.brentq(
                lambda tt, seg=segment: float(signal_of(seg.evaluate(tt))) - level,
                lo,
                hi,
                xtol=1e-15,
                rtol=4 * np.finfo(float).eps,
            )
        )
    period: float = (crossings[-1] - crossings[0]) / (upward.size - 1)
    return period

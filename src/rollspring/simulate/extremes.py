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


#: At most this many peaks of the output rows or the adaptive steps are refined per body and
#: kind: those whose parabolas could be the highest.
PEAKS_REFINED = 8
#: An adaptive step is looked at in this many parts (its interpolant evaluated there).
SUBSTEPS = 4


def continuous_extremes(run: RunState, trajectory: Trajectory) -> dict[str, list[float]]:
    r"""max |f|/N (while rolling) and min N per body over the whole run.

    Candidates: the peak the compiled kernel chose in each rolling segment (by the vertex of
    the parabola through three step ends, :func:`kernels.run_fixed_step`); from the output
    rows and the adaptive integrator's steps (each looked at in :data:`SUBSTEPS` parts), the
    highest sample and the peaks whose three-point parabolas could be the highest
    (:func:`_peak_keys`); and mu_s for a body that began to slip while rolling (reached at that
    instant exactly). The kernel's peaks are refined on the integrator itself (a grid search
    over each window of two steps, the last grid's parabola: about 1e-9 relative); the others
    on the interpolant of their own segment (a row: of every segment holding it) where they
    could be higher: always without a kernel peak, else where a row's sample, or an adaptive
    peak's parabola with its margin, is above the kernel peaks' refined value. The largest
    (smallest) value reached is the result. Choosing by the samples alone, two
    near-equal peaks were told apart only to :math:`(\omega h)^2/8` relative (0.2 % at the
    long steps of the 8th-order scheme)."""
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
    # candidates other than the kernel's: (kind, body) -> {(t, width, segment): (value, key,
    # margin)}, maximised (|f|/N, -N); segment: the index in run.segments of the segment whose
    # steps they are, -1 for an output row (refined in every segment holding it: a row at an
    # event belongs to both sides); a peak's key is its parabola's vertex, margin the key's
    # lift over the sample (what the parabola adds: the key's own error is a small part of it)
    others: dict[tuple[str, int], dict[tuple[float, float, int], tuple[float, float, float]]]
    others = {}
    # per kind, the largest value reached of each body (maximised; offered so far, then every
    # adaptive segment's samples): peaks whose parabolas stay below it are not offered
    floors = {kind: np.full(n, -np.inf) for kind in ("ratio", "normal")}
    for (kind, i), entries in run.step_extremes.items():
        for entry in entries:
            floors[kind][i] = max(floors[kind][i], entry[0] if kind == "ratio" else -entry[0])

    def offer(
        kind: str,
        i: int,
        value: float,
        t: float,
        width: float,
        key: float,
        margin: float,
        segment: int = -1,
    ) -> None:
        place = others.setdefault((kind, i), {})
        old = place.get((t, width, segment))
        if old is None or key > old[1]:
            place[(t, width, segment)] = (value, key, margin)
        if value > floors[kind][i]:
            floors[kind][i] = value

    def offer_peaks(
        kind: str,
        at: FloatArray,
        values: FloatArray,
        width: float,
        segment: int = -1,
        bodies: np.ndarray | None = None,
    ) -> None:
        """Of each body (``values`` (samples, n), maximised, at times ``at``) whose samples'
        parabolas could reach its floor (or of ``bodies``, a mask): the highest sample, and
        the peaks whose parabolas could be the highest (at most :data:`PEAKS_REFINED`)."""
        keys, margins, upper = _reach(at, values)
        reaching = ~(upper < floors[kind]) if bodies is None else bodies
        for i in np.flatnonzero(reaching & np.any(values > -np.inf, axis=0)).tolist():
            offer_body(kind, i, at, values[:, i], keys[:, i], margins[:, i], width, segment)

    def offer_body(
        kind: str,
        i: int,
        at: FloatArray,
        values: FloatArray,
        keys: FloatArray,
        margins: FloatArray,
        width: float,
        segment: int,
    ) -> None:
        k = int(np.argmax(values))
        offer(kind, i, float(values[k]), float(at[k]), width, float(values[k]), 0.0, segment)
        if values.size < 3:
            return
        top = int(np.argmax(keys))
        reach = keys[top] - margins[top]
        near = np.flatnonzero(keys + margins >= reach)
        for k in near[np.argsort(-keys[near], kind="stable")][:PEAKS_REFINED].tolist():
            offer(kind, i, float(values[k]), float(at[k]), width, keys[k], margins[k], segment)

    times = trajectory.t
    for i in range(n):
        if run.rolls[i]:
            ratio_i = float(ratio[i])
            offer("ratio", i, ratio_i, float(times[ratio_row[i]]), spacing, ratio_i, 0.0)
        normal_i = -float(normal[i])
        offer("normal", i, normal_i, float(times[normal_row[i]]), spacing, normal_i, 0.0)
    if times.size >= 3 and not run.step_extremes:
        # rows alone (no kernel peak): the peaks of their parabolas too
        with np.errstate(divide="ignore", invalid="ignore"):
            row_ratio = np.where(
                trajectory.slipping,
                -np.inf,
                np.where(
                    trajectory.normal > 0, np.abs(trajectory.friction) / trajectory.normal, np.inf
                ),
            )
        row_ratio[:, ~run.rolls] = -np.inf
        offer_peaks("ratio", times, row_ratio, spacing)
        offer_peaks("normal", times, -trajectory.normal, spacing)
    # the adaptive segments in two passes: first every segment's samples raise the floors
    # (values reached) and give each body's highest parabola there; then the segments are
    # looked at again, and a body offered only where its parabolas reach its floor, in the
    # segment whose sample set the floor, and where a sample is NaN (reported as such). A
    # floor raised segment by segment let most bodies of a long chain through.
    looked: list[tuple[int, dict[str, FloatArray]]] = []
    setter = {kind: np.full(n, -1) for kind in floors}  # the segment whose sample set a floor
    for index, segment in enumerate(run.segments):
        if segment.samples.size < 2:
            continue
        at, width, sampled = _segment_samples(run, segment)
        wanted = {}
        for kind, values in sampled.items():
            upper = _reach(at, values)[2]
            highest = np.fmax.reduce(values, axis=0)
            with np.errstate(invalid="ignore"):
                raised = highest > floors[kind]
            setter[kind][raised] = index
            floors[kind] = np.where(raised, highest, floors[kind])
            # a body whose samples here are all alike cannot rise above them: its tie with
            # the floor is not asked again (a long chain's bodies at rest)
            alike = np.all(values == values[:1], axis=0)
            upper = np.where(alike, np.nextafter(upper, -np.inf), upper)
            wanted[kind] = np.where(np.any(np.isnan(values), axis=0), np.inf, upper)
        looked.append((index, wanted))
    for index, wanted in looked:
        asked = {kind: (wanted[kind] >= floors[kind]) | (setter[kind] == index) for kind in wanted}
        if not any(np.any(mask) for mask in asked.values()):
            continue
        at, width, sampled = _segment_samples(run, run.segments[index])
        for kind, values in sampled.items():
            offer_peaks(kind, at, values, width, index, asked[kind])

    result = {"ratio": [0.0] * n, "normal": [math.inf] * n}
    maximised: dict[tuple[str, int], float] = {}  # the best so far (|f|/N, -N)
    kernel: dict[tuple[str, int], float] = {}  # the best of the kernel's peaks, refined

    def reached(kind: str, i: int, value: float, into: dict[tuple[str, int], float]) -> None:
        best = into.get((kind, i))
        if best is None or value > best or math.isnan(value):
            into[(kind, i)] = value

    # the values reached at step ends and rows, and mu_s where a body began to slip
    for i, mu in run.slip_ratios.items():
        reached("ratio", i, mu, maximised)
    for (kind, i), entries in run.step_extremes.items():
        for entry in entries:
            reached(kind, i, entry[0] if kind == "ratio" else -entry[0], maximised)
    for (kind, i), place in others.items():
        for value, _, _ in place.values():
            reached(kind, i, value, maximised)
    # level centre springs (physics.springs_stay_level): N is the same at every instant,
    # exactly, so its smallest value is every row's and there is nothing to refine
    constant = {("normal", i) for i in range(n)} if run.constant_normal else set()
    # the kernel's peaks, one per rolling segment, each refined from the state it kept (in one
    # compiled call per segment's model)
    groups: dict[int, list[tuple[tuple[str, int], Any]]] = {}
    for (kind, i), entries in run.step_extremes.items():
        if (kind, i) in constant:
            continue
        for value, t, width, local, _ in entries:
            if not math.isfinite(value):
                continue
            start = None if local is None else local.start
            if start is not None:
                groups.setdefault(id(start.model), []).append(((kind, i), (value, t, width, local)))
            else:
                sign = 1.0 if kind == "ratio" else -1.0
                reached(kind, i, sign * _refine(run, kind, i, value, t, width, local), kernel)
    for group in groups.values():
        for ((kind, i), _), value in zip(group, _refine_together(group, run), strict=True):
            reached(kind, i, value if kind == "ratio" else -value, kernel)
    for (kind, i), value in kernel.items():
        reached(kind, i, value, maximised)
    # the other candidates where they could be higher than the kernel's peak: always without
    # one, else where the sample (a row) or the parabola with its margin (a step) beats it
    for (kind, i), place in others.items():
        if (kind, i) in constant:
            continue
        sign = 1.0 if kind == "ratio" else -1.0
        top = kernel.get((kind, i))
        # the highest sample, and the peaks whose parabolas reach the highest's less its margin
        ranked = sorted(place, key=lambda c: place[c][1], reverse=True)
        reach = place[ranked[0]][1] - place[ranked[0]][2]
        chosen = [c for c in ranked if place[c][1] + place[c][2] >= reach][:PEAKS_REFINED]
        highest = max(place, key=lambda c: place[c][0])
        for t, width, index in [*chosen, *([highest] if highest not in chosen else [])]:
            value, key, margin = place[(t, width, index)]
            if not math.isfinite(value):
                continue
            if top is not None and not (value if index < 0 else key + margin) > top:
                continue  # below the kernel peak's refined value
            holding: list[Segment | None] = (
                [run.segments[index]]
                if index >= 0
                else [s for s in run.segments if s.t0 <= t <= s.t1] or [None]
            )
            for holder in holding:
                refined = sign * _refine(run, kind, i, sign * value, t, width, holder)
                reached(kind, i, refined, maximised)
    for (kind, i), value in maximised.items():
        result[kind][i] = float(value if kind == "ratio" else -value)
    return result


def _reach(times: FloatArray, values: FloatArray) -> tuple[FloatArray, FloatArray, FloatArray]:
    """Of samples ``values`` (samples, n) at ``times``: each sample's key
    (:func:`_peak_keys`), its margin (the key's lift over the sample, 0 where the key is not
    finite) and, per body, the highest key plus its margin (what its parabolas could reach;
    NaN keys left out)."""
    keys = _peak_keys(times, values)
    with np.errstate(invalid="ignore"):
        margins = np.where(np.isfinite(keys), keys - values, 0.0)
        upper = np.max(np.where(np.isnan(keys), -np.inf, keys + margins), axis=0)
    return keys, margins, upper


def _segment_samples(
    run: RunState, segment: Segment
) -> tuple[FloatArray, float, dict[str, FloatArray]]:
    """An adaptive segment's samples: each step looked at in :data:`SUBSTEPS` parts on its
    interpolant (a peak inside a long step shows there; its steps' ends alone can all lie far
    down its flanks), the widest part, and per kind the maximised values ((samples, n): |f|/N
    of the bodies rolling here, -inf for the others, inf where N <= 0; -N)."""
    n = run.n
    at = _subdivided(segment.samples, SUBSTEPS)
    states = segment.evaluate(at)
    slip = np.broadcast_to(segment.slipping, states[:, :n].shape)
    signs = np.broadcast_to(segment.sign, states[:, :n].shape)
    friction, normal, *_ = run.observe(states, slip, signs, segment.spin)
    with np.errstate(divide="ignore", invalid="ignore"):
        ratio = np.where(normal > 0, np.abs(friction) / normal, np.inf)
    ratio[:, ~(run.rolls & ~segment.slipping)] = -np.inf  # |f|/N only of bodies rolling here
    return at, float(np.max(np.diff(at))), {"ratio": ratio, "normal": -normal}


def _subdivided(times: FloatArray, parts: int) -> FloatArray:
    """``times`` (ascending) with each interval cut into ``parts`` equal ones."""
    fractions = np.arange(parts) / parts
    inner = times[:-1, None] + np.diff(times)[:, None] * fractions[None, :]
    return np.append(inner.ravel(), times[-1])


def _peak_keys(times: FloatArray, values: FloatArray) -> FloatArray:
    r"""Each sample's key for the highest peak: its value, and where it is a peak of its two
    neighbours (at least both; at an end, where the peak of the parabola through the first or
    last three lies between it and its neighbour), the vertex of the parabola through the three
    (times
    :math:`t_0 < t_1 < t_2`): :math:`p(t) = y_0 + d_{01}(t - t_0) + a(t - t_0)(t - t_1)`,
    at :math:`p'(t^*) = 0`. Near-equal peaks are then told apart to :math:`O(h^4)`, not
    :math:`O(h^2)`."""
    keys = np.array(values, dtype=np.float64)
    if keys.shape[0] < 3:
        return keys
    at = times if values.ndim == 1 else times[:, None]
    t0, t1, t2 = at[:-2], at[1:-1], at[2:]
    y0, y1, y2 = values[:-2], values[1:-1], values[2:]
    with np.errstate(all="ignore"):
        d01 = (y1 - y0) / (t1 - t0)
        a = ((y2 - y1) / (t2 - t1) - d01) / (t2 - t0)
        peak = (y1 >= y0) & (y1 >= y2) & np.isfinite(y0) & np.isfinite(y1) & np.isfinite(y2)
        peak &= a < 0
        vertex_t = 0.5 * (t0 + t1) - d01 / (2 * a)
        vertex = y0 + d01 * (vertex_t - t0) + a * (vertex_t - t0) * (vertex_t - t1)
        inner = keys[1:-1]
        inner[peak] = np.maximum(inner[peak], vertex[peak])
        # the ends: a peak between the first two samples (the last two) of the first (last)
        # three
        for end, triple, lo, hi in ((0, 0, t0[0], t1[0]), (-1, -1, t1[-1], t2[-1])):
            inside = (a[triple] < 0) & (lo <= vertex_t[triple]) & (vertex_t[triple] <= hi)
            inside &= np.isfinite(vertex[triple])
            keys[end] = np.where(inside, np.maximum(keys[end], vertex[triple]), keys[end])
    return keys


def _refine_together(entries: list[tuple[tuple[str, int], Any]], run: RunState) -> list[float]:
    """:func:`_refine` for many extremes at once, each ((kind, body), (value, t, width,
    segment)) on its own two-step segment from the state the kernel kept (one compiled call
    for all of them; in a large system each on the model of its body's ball,
    :func:`kernels.refine_windowed`); the refined values in order."""
    keys = [key for key, _ in entries]
    kept = [entry for _, entry in entries]
    first = kept[0][3].start
    kinds = np.array([0 if kind == "ratio" else 1 for kind, _ in keys], dtype=np.int64)
    bodies = np.array([i for _, i in keys], dtype=np.int64)
    sign = [1.0 if kind == "ratio" else -1.0 for kind, _ in keys]
    best = np.array([entry[0] * sign[j] for j, entry in enumerate(kept)])
    starts = [entry[3].start for entry in kept]
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
    return [refined[j] * sign[j] for j in range(len(keys))]


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

        def offset(tt: float, seg: Segment = segment) -> float:
            return float(signal_of(seg.evaluate(tt))) - level

        below, above = offset(lo), offset(hi)
        if below == 0.0 or above == 0.0:
            crossings.append(lo if below == 0.0 else hi)
            continue
        if (below < 0) == (above < 0):
            # the rows' crossing is not the interpolant's (a signal at the rounding level,
            # as the lowest mode of a symmetric motion that does not excite it): no period
            return None
        crossings.append(
            scipy.optimize.brentq(offset, lo, hi, xtol=1e-15, rtol=4 * np.finfo(float).eps)
        )
    period: float = (crossings[-1] - crossings[0]) / (upward.size - 1)
    return period

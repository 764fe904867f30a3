"""Refinement on the integrator itself: extremes between step ends, the period signal's zero,
and the windows (balls of bodies) that keep both O(1) per body on a long chain.
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

from rollspring.simulate.kernels.forces import _contact, _workspace
from rollspring.simulate.kernels.stepping import _advance_into

__all__ = ["body_links", "refine_extremes", "refine_windowed", "signal_zero", "spring_balls"]


@njit(cache=True, error_model="numpy")
def refine_extremes(model, coeffs, h, q0, v0, kinds, bodies, best, spans):
    r"""The extremes the kernel found at step ends, refined on the integrator itself: for
    extreme j (``kinds[j]`` 0: max :math:`|f|/N`, 1: min :math:`N`, of body ``bodies[j]``) over
    the two steps from the state (q0[j], v0[j]) (cut at ``spans[j]``), three grids of 9 points,
    each spanning the best point's neighbours on the last (spacing span/256 at the end, the span
    2h or less; the three points a grid shares
    with the last are not evaluated again), then the vertex of the parabola through the best
    point and its neighbours: the value to about 1e-10 relative. The state at
    :math:`\tau \le h` is one step of :math:`\tau` from the start, beyond it one step of
    :math:`\tau - h` from the kernel's step end. ``best`` holds the values found so far as
    maximised quantities (:math:`|f|/N` or :math:`-N`); returns the refined ones in the same
    form. ``spans[j]`` (at most 2h) cuts extreme j's window where its rolling motion ends (a
    step end that is the run's end, or an event's step: nothing after it is looked at)."""
    m, n = q0.shape
    out = best.copy()
    work = _refine_work(model, n)
    for j in range(m):
        out[j] = _refine_one(
            model, coeffs, h, q0[j], v0[j], kinds[j], bodies[j], out[j], work, spans[j]
        )
    return out


@njit(cache=True, error_model="numpy")
def _refine_work(model, n):
    """The work arrays of :func:`_refine_one` for a model of n bodies."""
    scratch, gen, fx, fy = _workspace(model, n)
    states = np.empty((4, n))  # q, v, q_mid, v_mid
    return scratch, gen, fx, fy, states, np.empty(9), np.empty(9)


@njit(cache=True, error_model="numpy")
def _refine_one(model, coeffs, h, q0, v0, kind, b, best, work, span):
    """:func:`refine_extremes` of one extreme (kind 0: max |f|/N, 1: min N as -N) of body
    ``b`` over the two steps from (q0, v0), cut at ``span``; returns the refined value (at
    least ``best``)."""
    scratch, gen, fx, fy, states, values, times = work
    q, v, q_mid, v_mid = states[0], states[1], states[2], states[3]
    out = best
    _advance_into(model, coeffs, h, q0, v0, h, q_mid, v_mid, scratch, gen, fx, fy)
    lo, hi = 0.0, min(2.0 * h, span)
    k = -1
    for _level in range(3):
        if k >= 0:  # the last grid's best point and neighbours: this grid's 0, 4 and 8
            values[0], values[4], values[8] = values[k - 1], values[k], values[k + 1]
            times[0], times[4], times[8] = times[k - 1], times[k], times[k + 1]
        for p in range(9):
            if k >= 0 and p % 4 == 0:
                continue
            times[p] = lo + (hi - lo) * p / 8.0
            if times[p] <= h:
                _advance_into(model, coeffs, h, q0, v0, times[p], q, v, scratch, gen, fx, fy)
            else:
                _advance_into(
                    model, coeffs, h, q_mid, v_mid, times[p] - h, q, v, scratch, gen, fx, fy
                )
            friction, normal = _contact(model, b, gen[b], fx[b], fy[b])
            if kind == 0:
                values[p] = abs(friction) / normal if normal > 0.0 else np.inf
            else:
                values[p] = -normal
        k = min(max(int(np.argmax(values)), 1), 7)
        a, c = values[k - 1], values[k + 1]
        middle = values[k]
        out = max(out, np.max(values))  # values the motion reaches
        # the vertex of the last grid's parabola only: on the coarser grids (a spacing of h/4
        # and h/32) it is an estimate that can lie past the peak (1e-3 at a sharp one)
        curvature = a - 2.0 * middle + c
        vertex = -np.inf
        if math.isfinite(a + middle + c) and curvature < 0.0 and abs(a - c) <= -2.0 * curvature:
            vertex = middle - (c - a) ** 2 / (8.0 * curvature)
        lo, hi = times[k - 1], times[k + 1]
    return max(out, vertex)


@njit(cache=True, error_model="numpy")
def body_links(n, ends, force_body):
    """Each body's springs and constant forces, ascending, as two CSR pairs
    ``(spring_ptr, spring_ids, force_ptr, force_ids)`` (a spring with both ends on one body is
    listed once)."""
    n_springs = ends.shape[0]
    spring_ptr = np.zeros(n + 1, dtype=np.int64)
    for s in range(n_springs):
        ia, ib = ends[s, 0], ends[s, 1]
        if ia >= 0:
            spring_ptr[ia + 1] += 1
        if ib >= 0 and ib != ia:
            spring_ptr[ib + 1] += 1
    for i in range(n):
        spring_ptr[i + 1] += spring_ptr[i]
    spring_ids = np.empty(spring_ptr[n], dtype=np.int64)
    fill = spring_ptr[:n].copy()
    for s in range(n_springs):  # ascending s: each body's list comes out sorted
        ia, ib = ends[s, 0], ends[s, 1]
        if ia >= 0:
            spring_ids[fill[ia]] = s
            fill[ia] += 1
        if ib >= 0 and ib != ia:
            spring_ids[fill[ib]] = s
            fill[ib] += 1
    force_ptr = np.zeros(n + 1, dtype=np.int64)
    for j in range(force_body.shape[0]):
        force_ptr[force_body[j] + 1] += 1
    for i in range(n):
        force_ptr[i + 1] += force_ptr[i]
    force_ids = np.empty(force_ptr[n], dtype=np.int64)
    fill = force_ptr[:n].copy()
    for j in range(force_body.shape[0]):
        force_ids[fill[force_body[j]]] = j
        fill[force_body[j]] += 1
    return spring_ptr, spring_ids, force_ptr, force_ids


@njit(cache=True, error_model="numpy")
def spring_balls(n, ends, spring_ptr, spring_ids, radius):
    """Per body i the bodies within ``radius`` springs of it (itself included), ascending, as
    CSR ``(ball_ptr, ball_idx)``: breadth-first over the springs, O(ball size x links) per body
    -- 2 radius + 1 bodies for a chain, whatever its length."""
    stamp = np.full(n, -1, dtype=np.int64)
    queue = np.empty(n, dtype=np.int64)
    depth = np.empty(n, dtype=np.int64)
    ptr = np.zeros(n + 1, dtype=np.int64)
    chunks = []
    for i in range(n):
        stamp[i] = i
        queue[0] = i
        depth[0] = 0
        head, tail = 0, 1
        while head < tail:
            body = queue[head]
            d = depth[head]
            head += 1
            if d == radius:
                continue
            for p in range(spring_ptr[body], spring_ptr[body + 1]):
                s = spring_ids[p]
                for e in range(2):
                    other = ends[s, e]
                    if other >= 0 and stamp[other] != i:
                        stamp[other] = i
                        queue[tail] = other
                        depth[tail] = d + 1
                        tail += 1
        chunks.append(np.sort(queue[:tail]))
        ptr[i + 1] = ptr[i] + tail
    idx = np.empty(ptr[n], dtype=np.int64)
    for i in range(n):
        idx[ptr[i] : ptr[i + 1]] = chunks[i]
    return ptr, idx


@njit(cache=True, error_model="numpy")
def _listed(ball, ptr, ids):
    """The entries ``ids[ptr[i] : ptr[i + 1]]`` of the bodies ``i`` of ``ball``, one body's
    after another's."""
    total = 0
    for a in range(ball.shape[0]):
        total += ptr[ball[a] + 1] - ptr[ball[a]]
    out = np.empty(total, dtype=np.int64)
    c = 0
    for a in range(ball.shape[0]):
        for p in range(ptr[ball[a]], ptr[ball[a] + 1]):
            out[c] = ids[p]
            c += 1
    return out


@njit(cache=True, error_model="numpy")
def _window_model(model, ball, local, spring_ptr, spring_ids, force_ptr, force_ids, stamp, tag):
    """The model of the bodies ``ball`` (ascending; ``local`` maps them to 0, 1, ... and every
    other body to -1): their springs whose other end is in the ball or an anchor, and their
    forces, each in its order in ``model`` -- so each body's loads are summed in the same order
    as in the whole model, to the bit. Springs to bodies outside are left out: their effect
    reaches the ball's centre only after as many force evaluations as the ball's radius."""
    bodies, springs, ends, forces, force_body, g = model
    w = ball.shape[0]
    links = _listed(ball, spring_ptr, spring_ids)
    picked = np.empty(links.shape[0], dtype=np.int64)
    count = 0
    for s in links:
        if stamp[s] == tag:
            continue
        stamp[s] = tag
        ia, ib = ends[s, 0], ends[s, 1]
        if (ia < 0 or local[ia] >= 0) and (ib < 0 or local[ib] >= 0):
            picked[count] = s
            count += 1
    chosen = np.sort(picked[:count])
    sub_springs = np.empty((count, springs.shape[1]))
    sub_ends = np.empty((count, 2), dtype=np.int64)
    for c in range(count):
        s = chosen[c]
        sub_springs[c] = springs[s]
        for e in range(2):
            sub_ends[c, e] = local[ends[s, e]] if ends[s, e] >= 0 else ends[s, e]
    listed = np.sort(_listed(ball, force_ptr, force_ids))
    n_forces = listed.shape[0]
    sub_forces = np.empty((n_forces, forces.shape[1]))
    sub_force_body = np.empty(n_forces, dtype=np.int64)
    for c in range(n_forces):
        sub_forces[c] = forces[listed[c]]
        sub_force_body[c] = local[force_body[listed[c]]]
    sub_bodies = np.empty((w, bodies.shape[1]))
    for a in range(w):
        sub_bodies[a] = bodies[ball[a]]
    return sub_bodies, sub_springs, sub_ends, sub_forces, sub_force_body, g


@njit(cache=True, error_model="numpy")
def refine_windowed(model, coeffs, h, q0, v0, offsets, balls, kinds, bodies, best, links, spans):
    r""":func:`refine_extremes` of a large system, each extreme on the model of its body's ball
    (:func:`spring_balls` of radius
    :func:`~rollspring.simulate.integrators.refinement_radius`, :func:`_window_model`): entry j's
    ball is ``balls[offsets[j]:offsets[j + 1]]`` (global body numbers, ascending) and its
    state ``q0``/``v0`` over the same slice. The refinement sees body ``bodies[j]`` after at
    most 2 stages + 1 force evaluations, so the ball's edge never reaches it: the same numbers
    as on the whole model, each in O(ball) instead of O(n)."""
    spring_ptr, spring_ids, force_ptr, force_ids = links
    n = model[0].shape[0]
    local = np.full(n, -1, dtype=np.int64)
    stamp = np.full(model[1].shape[0], -1, dtype=np.int64)
    out = best.copy()
    for j in range(kinds.shape[0]):
        ball = balls[offsets[j] : offsets[j + 1]]
        for a in range(ball.shape[0]):
            local[ball[a]] = a
        sub = _window_model(
            model, ball, local, spring_ptr, spring_ids, force_ptr, force_ids, stamp, j
        )
        work = _refine_work(sub, ball.shape[0])
        out[j] = _refine_one(
            sub,
            coeffs,
            h,
            q0[offsets[j] : offsets[j + 1]],
            v0[offsets[j] : offsets[j + 1]],
            kinds[j],
            local[bodies[j]],
            out[j],
            work,
            spans[j],
        )
        for a in range(ball.shape[0]):
            local[ball[a]] = -1
    return out


@njit(cache=True, error_model="numpy")
def signal_zero(model, coeffs, h, q0, v0, weights, q_ref):
    r"""The instant :math:`\tau \in [0, h]` at which the signal
    :math:`s = w \cdot (q - q_{ref})`, negative at (q0, v0) and not negative one step later,
    crosses zero: Newton with the exact rate :math:`\dot s = w \cdot \dot q`, safeguarded by
    bisection, on the integrator's own step, to rounding."""
    n = q0.shape[0]
    scratch, gen, fx, fy = _workspace(model, n)
    q = np.empty(n)
    v = np.empty(n)
    lo, hi = 0.0, h
    s_lo = 0.0
    for i in range(n):
        s_lo += weights[i] * (q0[i] - q_ref[i])
    _advance_into(model, coeffs, h, q0, v0, hi, q, v, scratch, gen, fx, fy)
    s_hi = 0.0
    for i in range(n):
        s_hi += weights[i] * (q[i] - q_ref[i])
    t = lo - s_lo * (hi - lo) / (s_hi - s_lo) if s_hi != s_lo else hi
    for _ in range(60):
        _advance_into(model, coeffs, h, q0, v0, t, q, v, scratch, gen, fx, fy)
        value = 0.0
        rate = 0.0
        for i in range(n):
            value += weights[i] * (q[i] - q_ref[i])
            rate += weights[i] * v[i]
        if value < 0.0:
            lo = t
        else:
            hi = t
        step = value / rate if rate != 0.0 else np.inf
        if abs(step) <= 1e-12 * h:
            return t - step
        candidate = t - step
        if not (lo < candidate < hi):
            candidate = 0.5 * (lo + hi)
        if hi - lo <= 1e-16 * max(h, 1.0):
            return candidate
        t = candidate
    return t

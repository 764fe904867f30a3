r"""The explicit symplectic stepping of the all-rolling state, and its outputs inside a step.

While every body rolls the Hamiltonian is separable, :math:`H = \sum p_i^2/(2J_i) + U(q)` with a
constant diagonal mass matrix (docs/physics.md (M6)), so compositions of the kick-drift-kick
leapfrog

.. math:: v \mathrel{+}= \tfrac{h_k}{2} Q(q)/J,\quad q \mathrel{+}= h_k v,\quad
          v \mathrel{+}= \tfrac{h_k}{2} Q(q)/J, \qquad h_k = w_k h

are explicit and symplectic; the weights :math:`w_k` (Yoshida 1990; Kahan and Li 1997) give
orders 2, 4, 6 and 8. The force at the end of a stage is reused at the start of the next.
:func:`run_fixed_step` is the run's loop: steps, contact checks, septic Hermite outputs inside
the steps (:func:`_hermite`), the extremes and the crossings of the period signal.
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

from rollspring.simulate.integrators import INTEGRATORS
from rollspring.simulate.kernels import model as col
from rollspring.simulate.kernels.forces import _contact, _workspace, force_rates, rolling_forces
from rollspring.simulate.status import Status

__all__ = [
    "NEAR_REACH",
    "SCHEMES",
    "STATUS_FINISHED",
    "STATUS_LIFTOFF",
    "STATUS_NEAR",
    "STATUS_NONFINITE",
    "STATUS_SLIP",
    "advance",
    "advance_many",
    "dip_vertex",
    "run_fixed_step",
]

STATUS_FINISHED = int(Status.FINISHED)
STATUS_NONFINITE = int(Status.NONFINITE)
STATUS_SLIP = int(Status.SLIP)
STATUS_LIFTOFF = int(Status.LIFTOFF)
#: :func:`run_fixed_step` stopped before a step whose contact margin may dip below zero inside
#: it (a graze between two step ends): the caller looks inside that step (not a run status)
STATUS_NEAR = -2
#: A margin's dip inside a step is looked for when the parabola through its last three
#: step-end values has its minimum in the step (or within this fraction of a step of it) and
#: that minimum is below the parabola's curvature term A (A = m'' h^2 / 2: a step's dip below
#: its ends is at most A / 4, and the parabola's error a fraction omega h of A)
NEAR_REACH = 0.1

#: name -> (order p, stage weights, C_p): the relative frequency error is C_p (omega h)^p
#: (:data:`rollspring.simulate.integrators.INTEGRATORS`, as the kernels take them).
SCHEMES: dict[str, tuple[int, np.ndarray, float]] = {
    name: (scheme.order, scheme.weights, scheme.error_constant)
    for name, scheme in INTEGRATORS.items()
}


@njit(cache=True, inline="always", error_model="numpy")
def _stages(model, coeffs, h, q, v, scratch, gen, fx, fy):
    """One step: the stages of the composition, the closing half-kick of each stage merged
    with the opening half-kick of the next (they use the same force)."""
    bodies = model[0]
    n = q.shape[0]
    m = coeffs.shape[0]
    kick = 0.5 * h * coeffs[0]
    for i in range(n):
        v[i] += kick * gen[i] * bodies[i, col.INV_INERTIA]
    for k in range(m):
        hw = h * coeffs[k]
        for i in range(n):
            q[i] += hw * v[i]
        rolling_forces(model, q, scratch, gen, fx, fy)
        kick = 0.5 * h * (coeffs[k] + coeffs[k + 1]) if k + 1 < m else 0.5 * hw
        for i in range(n):  # kick / J off the chain force -> velocity -> position
            v[i] += gen[i] * (kick * bodies[i, col.INV_INERTIA])


@njit(cache=True, error_model="numpy")
def advance(model, coeffs, q, v, duration, n_steps):
    """Integrate ``n_steps`` equal steps over ``duration`` (may be 0) from (q, v); returns new
    arrays (q, v, friction, normal) at the end."""
    q = q.copy()
    v = v.copy()
    n = q.shape[0]
    scratch, gen, fx, fy = _workspace(model, n)
    friction = np.empty(n)
    normal = np.empty(n)
    rolling_forces(model, q, scratch, gen, fx, fy)
    h = duration / max(n_steps, 1)
    for _ in range(n_steps):
        _stages(model, coeffs, h, q, v, scratch, gen, fx, fy)
    for i in range(n):
        friction[i], normal[i] = _contact(model, i, gen[i], fx[i], fy[i])
    return q, v, friction, normal


@njit(cache=True, error_model="numpy")
def advance_many(model, coeffs, q_rows, v_rows, spans, pieces):
    """``advance`` from row j of (q_rows, v_rows) over spans[j] in pieces[j] equal steps, for
    every j at once; returns the arrays (q, v)."""
    q_out = np.empty_like(q_rows)
    v_out = np.empty_like(v_rows)
    for j in range(q_rows.shape[0]):
        q, v, _, _ = advance(model, coeffs, q_rows[j], v_rows[j], spans[j], pieces[j])
        q_out[j] = q
        v_out[j] = v
    return q_out, v_out


@njit(cache=True, inline="always", error_model="numpy")
def _hermite_coefficients(model, h, q0, v0, g0, r0, q1, v1, g1, r1, coef):
    r"""The septic Hermite interpolant of one step, per body as :math:`q(\theta) =
    \sum_{k=0}^{7} c_k\theta^k` (:math:`\theta = s/h \in [0, 1]`), from positions,
    velocities, accelerations :math:`a = Q/J` and jerks :math:`j = \dot Q/J` at both ends
    (``g``: Q, ``r``: :math:`\dot Q`), into ``coef[:, :8]`` and those of its derivative divided
    by h, the velocity, into ``coef[:, 8:]`` (n, 15). With :math:`V = h\dot q`,
    :math:`A = h^2 a`, :math:`\mathcal{J} = h^3 j` and :math:`D = q_1 - q_0`: :math:`c_0 = q_0`,
    :math:`c_1 = V_0`, :math:`c_2 = A_0/2`, :math:`c_3 = \mathcal{J}_0/6` and

    .. math::
        c_4 &= 35D - 20V_0 - 15V_1 - 5A_0 + \tfrac52 A_1 - \tfrac23\mathcal{J}_0
               - \tfrac16\mathcal{J}_1,\\
        c_5 &= -84D + 45V_0 + 39V_1 + 10A_0 - 7A_1 + \mathcal{J}_0 + \tfrac12\mathcal{J}_1,\\
        c_6 &= 70D - 36V_0 - 34V_1 - \tfrac{15}2 A_0 + \tfrac{13}2 A_1 - \tfrac23\mathcal{J}_0
               - \tfrac12\mathcal{J}_1,\\
        c_7 &= -20D + 10V_0 + 10V_1 + 2A_0 - 2A_1 + \tfrac16(\mathcal{J}_0 + \mathcal{J}_1).

    Its error is at most :math:`h^8\max|q^{(8)}|/10321920` in position (and, through its
    derivative, :math:`(\omega h)^7/2710000` of the velocity amplitude on a sine)."""
    bodies = model[0]
    hh = h * h
    hhh = hh * h
    inv_h = 1.0 / h
    sixth = 1.0 / 6.0
    for i in range(q0.shape[0]):
        inv = bodies[i, col.INV_INERTIA]
        d = q1[i] - q0[i]
        w0 = h * v0[i]
        w1 = h * v1[i]
        a0 = hh * (g0[i] * inv)
        a1 = hh * (g1[i] * inv)
        j0 = hhh * (r0[i] * inv)
        j1 = hhh * (r1[i] * inv)
        c4 = 35.0 * d - 20.0 * w0 - 15.0 * w1 - 5.0 * a0 + 2.5 * a1 - (4.0 * j0 + j1) * sixth
        c5 = -84.0 * d + 45.0 * w0 + 39.0 * w1 + 10.0 * a0 - 7.0 * a1 + j0 + 0.5 * j1
        c6 = 70.0 * d - 36.0 * w0 - 34.0 * w1 - 7.5 * a0 + 6.5 * a1 - (4.0 * j0 + 3.0 * j1) * sixth
        c7 = -20.0 * d + 10.0 * (w0 + w1) + 2.0 * (a0 - a1) + (j0 + j1) * sixth
        coef[i, 0] = q0[i]
        coef[i, 1] = w0
        coef[i, 2] = 0.5 * a0
        coef[i, 3] = j0 * sixth
        coef[i, 4] = c4
        coef[i, 5] = c5
        coef[i, 6] = c6
        coef[i, 7] = c7
        # the derivative's, divided by h: the velocity
        coef[i, 8] = v0[i]
        coef[i, 9] = a0 * inv_h
        coef[i, 10] = 0.5 * j0 * inv_h
        coef[i, 11] = 4.0 * c4 * inv_h
        coef[i, 12] = 5.0 * c5 * inv_h
        coef[i, 13] = 6.0 * c6 * inv_h
        coef[i, 14] = 7.0 * c7 * inv_h


@njit(cache=True, inline="always", error_model="numpy")
def _hermite(coef, theta, row, out_q, out_v):
    """The interpolant of :func:`_hermite_coefficients` at ``theta`` and its derivative (the
    velocity), by Estrin's scheme (short dependency chains), into row ``row`` of
    ``out_q``/``out_v``."""
    t = theta
    t2 = t * t
    t4 = t2 * t2
    for i in range(coef.shape[0]):
        out_q[row, i] = (
            (coef[i, 0] + coef[i, 1] * t)
            + t2 * (coef[i, 2] + coef[i, 3] * t)
            + t4 * ((coef[i, 4] + coef[i, 5] * t) + t2 * (coef[i, 6] + coef[i, 7] * t))
        )
        out_v[row, i] = (
            (coef[i, 8] + coef[i, 9] * t)
            + t2 * (coef[i, 10] + coef[i, 11] * t)
            + t4 * ((coef[i, 12] + coef[i, 13] * t) + t2 * coef[i, 14])
        )


@njit(cache=True, error_model="numpy")
def run_fixed_step(
    model,
    coeffs,
    q,
    v,
    t0,
    h,
    n_steps,
    check_contacts,
    out_times,
    out_q,
    out_v,
    extremes,
    extreme_states,
    ball_ptr,
    ball_idx,
    weights,
    q_ref,
    crossing,
    crossing_states,
    before,
    earlier,
    samples,
    near_margins,
    near_flags,
    first_step,
    skip_near,
):
    r"""Integrate ``n_steps`` steps of size ``h`` from (q, v) at time ``t0`` (updated in place),
    checking rolling validity after every step. The state at each of the sorted ``out_times``
    (within (t0, t0 + n_steps h]) is interpolated from the step holding it (``_hermite``,
    septic: with the jerks of :func:`force_rates` at the step's ends) into
    the rows of ``out_q``/``out_v``: the output spacing never limits the step.

    Kept across calls (the caller seeds them):

    * ``extremes`` (6, n): per body the largest |f|/N over the step ends (row 0) and the
      smallest N (row 2): values the motion reaches; and the peak to refine, of each kind: its
      key (rows 4 and 5, as maximised quantities |f|/N and -N) and the start of its window of
      two steps (rows 1 and 3). A step end's own value is a key (its window the step before
      and after it); where the parabola through the last three peaks between the first and
      the last of them (the middle one the highest; or a peak beside a segment's first or
      last sample), its vertex,
      :math:`y_1 + (y_2 - y_0)^2 / (8 (2 y_1 - y_0 - y_2))`, is its key, its window the two
      steps around it: between near-equal peaks the key picks the higher to :math:`O(h^4)`,
      where the samples alone are off by up to :math:`(\omega h)^2/8` relative. ``samples``
      (2, 2, n) the maximised quantities at the last two step ends (the older first; NaN where
      not known), ``earlier`` (2, n) the state at the start of the step before the last.
      ``extreme_states`` (2, 2, B) the state (q, v) at the start of those windows, from which
      the peak is refined: for body i
      (kind k) only the bodies of its ball ``ball_idx[ball_ptr[i]:ball_ptr[i + 1]]``
      (:func:`spring_balls`: all that can reach it within the refinement's force evaluations;
      every body for a small system), into ``extreme_states[k, :, ball_ptr[i]:ball_ptr[i + 1]]``
      -- O(1) per body for a chain, no (n, n) array.
    * ``crossing`` (4,): upward zero crossings of the signal s = weights . (q - q_ref): their
      count, the start times of the steps holding the first and the last, and the last value of
      s; ``crossing_states`` (2, 2, n) the states at the start of those two steps.

    * ``near_margins`` (2, 2, n): each body's contact margins at the last two step ends,
      the slip margin :math:`\mu_s N - |f|` (row 0; NaN where a body cannot slip) and the
      normal force :math:`N` (row 1), the older first; NaN where not yet known.

    A contact margin that stays positive at the step ends can still dip below zero inside a
    step (a friction that grazes :math:`\mu_sN`). After each step, the parabola through a
    margin's last three step-end values is looked at: when its minimum falls in this step
    (:data:`NEAR_REACH`) and is below its curvature term, the run stops before the step
    (status :data:`STATUS_NEAR`, the "body" the number of margins flagged, each marked 1 in
    ``near_flags`` (2n): ``j`` < n the slip margin of body j, else the normal force of body
    j - n) so that the caller looks inside it for every one of them. A call may start at step
    ``first_step`` + 1 of the ``n_steps`` (from the state at the start of that step: the
    times stay ``t0 + (step - 1) h``, bit for bit those of a call that took every step) and
    look at no step up to ``skip_near`` (a step just looked inside and found clear, run
    again).

    ``before`` (2, n) receives the state at the start of the last step taken. Returns
    (status, step, body, rows): for an event the step in which it happened and the body; the
    number of output rows written (those before the event).
    """
    bodies = model[0]
    n = q.shape[0]
    scratch, gen, fx, fy = _workspace(model, n)
    gen_before = np.empty(n)
    # the force rates (jerks) at the step's ends, computed only for steps holding outputs
    rate = np.empty(n)
    rate_before = np.empty(n)
    rate_valid = False  # rate holds the current state's
    coef = np.empty((n, 15))  # the interpolant of the current step
    rolling_forces(model, q, scratch, gen, fx, fy)
    margin = np.empty((2, n))  # this step end's contact margins
    rows = 0
    n_out = out_times.shape[0]
    for step in range(first_step + 1, n_steps + 1):
        for i in range(n):
            before[0, i] = q[i]
            before[1, i] = v[i]
            gen_before[i] = gen[i]
            rate_before[i] = rate[i]
        before_valid = rate_valid
        _stages(model, coeffs, h, q, v, scratch, gen, fx, fy)
        rate_valid = False
        event = -1
        event_body = -1
        for i in range(n):
            if not (math.isfinite(q[i]) and math.isfinite(v[i])):
                return STATUS_NONFINITE, step, i, rows
            if not check_contacts:
                continue
            friction, normal = _contact(model, i, gen[i], fx[i], fy[i])
            if normal < 0.0:
                event = STATUS_LIFTOFF
                event_body = i
                break
            if bodies[i, col.ROLLS] > 0.0 and abs(friction) > bodies[i, col.MU_S] * normal:
                event = STATUS_SLIP
                event_body = i
                break
            can_slip = bodies[i, col.ROLLS] > 0.0 and math.isfinite(bodies[i, col.MU_S])
            margin[0, i] = bodies[i, col.MU_S] * normal - abs(friction) if can_slip else np.nan
            margin[1, i] = normal
        if event >= 0:  # the state after this step is past the event: not an extreme
            return event, step, event_body, rows
        if check_contacts and step > skip_near:
            flagged = 0
            for kind in range(2):
                for i in range(n):
                    older, last = near_margins[kind, 0, i], near_margins[kind, 1, i]
                    if _dips_here(older, last, margin[kind, i]):
                        flagged += 1
            if flagged:  # rare: the flags written only then
                for kind in range(2):
                    for i in range(n):
                        older, last = near_margins[kind, 0, i], near_margins[kind, 1, i]
                        dips = _dips_here(older, last, margin[kind, i])
                        near_flags[i + kind * n] = 1 if dips else 0
                return STATUS_NEAR, step, flagged, rows
        t_start = t0 + (step - 1) * h
        # outputs inside this step; the last step also takes any left by rounding
        t_end = t_start + h if step < n_steps else np.inf
        # the interpolant, for a step holding an output before its end (outputs on step ends,
        # the only ones of some runs, need none); theta grows with the sorted outputs, so the
        # first output's tells
        if rows < n_out and out_times[rows] <= t_end and (out_times[rows] - t_start) / h < 1.0:
            if not before_valid:
                force_rates(model, before[0], before[1], rate_before)
            force_rates(model, q, v, rate)
            rate_valid = True
            _hermite_coefficients(
                model, h, before[0], before[1], gen_before, rate_before, q, v, gen, rate, coef
            )
        while rows < n_out and out_times[rows] <= t_end:
            theta = min(max((out_times[rows] - t_start) / h, 0.0), 1.0)
            if theta < 1.0:
                _hermite(coef, theta, rows, out_q, out_v)
            else:  # the step end itself
                for i in range(n):
                    out_q[rows, i] = q[i]
                    out_v[rows, i] = v[i]
            rows += 1
        for i in range(n):
            friction, normal = _contact(model, i, gen[i], fx[i], fy[i])
            if normal < extremes[2, i]:
                extremes[2, i] = normal
            # a peak offered (_peak, not inlined: rare, a new best or a peak of the samples;
            # inlined, its branches made every step twice as slow), the samples shifted (NaN
            # samples compare false)
            for kind in range(2):
                if kind == 0:
                    if bodies[i, col.ROLLS] <= 0.0:
                        continue
                    now = abs(friction) / normal if normal > 0.0 else np.nan  # N = 0: none
                    if now > extremes[0, i]:
                        extremes[0, i] = now
                else:
                    now = -normal
                y0, y1 = samples[kind, 0, i], samples[kind, 1, i]
                # a peak of the parabola through the three inside the last two steps (the
                # middle sample the highest, or a peak next to the first sample of a segment
                # or the last); a flat run of samples, a constant N, is none
                # (its vertex is at most y1 + |now - y0|/4: only one that can beat the key)
                curvature = y0 - 2.0 * y1 + now
                best = extremes[4 + kind, i]
                if now > best or (
                    y1 + 0.25 * abs(now - y0) > best
                    and curvature < 0.0
                    and abs(now - y0) <= -2.0 * curvature
                ):
                    _peak(
                        kind,
                        i,
                        y0,
                        y1,
                        now,
                        t_start,
                        h,
                        extremes,
                        extreme_states,
                        before,
                        earlier,
                        ball_ptr,
                        ball_idx,
                    )
                samples[kind, 0, i] = y1
                samples[kind, 1, i] = now
        for j in range(2):  # the step taken: its start is the state before the next one's
            for i in range(n):
                earlier[j, i] = before[j, i]
        signal = 0.0
        for i in range(n):
            signal += weights[i] * (q[i] - q_ref[i])
        if crossing[3] < 0.0 <= signal:
            slot = 0 if crossing[0] == 0 else 1
            crossing[0] += 1
            crossing[1 + slot] = t_start
            if slot == 0:
                crossing[2] = t_start
            for j in range(n):
                crossing_states[slot, 0, j] = before[0, j]
                crossing_states[slot, 1, j] = before[1, j]
                if slot == 0:
                    crossing_states[1, 0, j] = before[0, j]
                    crossing_states[1, 1, j] = before[1, j]
        crossing[3] = signal
        if check_contacts:
            for kind in range(2):
                for i in range(n):
                    near_margins[kind, 0, i] = near_margins[kind, 1, i]
                    near_margins[kind, 1, i] = margin[kind, i]
    return STATUS_FINISHED, n_steps, -1, rows


@njit(cache=True, error_model="numpy")
def _peak(kind, i, y0, y1, now, t_start, h, extremes, extreme_states, before, earlier, ptr, idx):
    """:func:`run_fixed_step`'s peak of ``kind`` (0: |f|/N, 1: -N) of body ``i``, sampled
    ``y0``, ``y1``, ``now`` at the last three step ends, the last at the end of the step from
    ``t_start``: ``now`` as its own key (window from that step's start, ``before``), or, where
    the parabola through the three peaks inside the last two steps, its vertex (window from
    the start of the step before, ``earlier``), kept where it beats the key so far."""
    key = 4 + kind
    if now > extremes[key, i]:
        extremes[key, i] = now
        extremes[1 + 2 * kind, i] = t_start
        for p in range(ptr[i], ptr[i + 1]):
            extreme_states[kind, 0, p] = before[0, idx[p]]
            extreme_states[kind, 1, p] = before[1, idx[p]]
        return
    curvature = y0 - 2.0 * y1 + now  # < 0; |now - y0| <= -2 curvature: inside the steps
    vertex = y1 - (now - y0) ** 2 / (8.0 * curvature)
    if vertex > extremes[key, i]:
        extremes[key, i] = vertex
        extremes[1 + 2 * kind, i] = t_start - h
        for p in range(ptr[i], ptr[i + 1]):
            extreme_states[kind, 0, p] = earlier[0, idx[p]]
            extreme_states[kind, 1, p] = earlier[1, idx[p]]


@njit(cache=True, error_model="numpy")
def dip_vertex(older, last, now, spans):
    r"""(vertex, A) of a margin sampled ``older``, ``last``, ``now`` at three equally spaced
    instants ending at a step's end (all positive), ``spans`` of their spacings making up the
    step: the parabola through them, :math:`m(\tau) = A\tau^2 + B\tau + C` (:math:`\tau` in
    spacings from the step's end), and its minimum's place :math:`\tau^* = -B/2A` when the
    margin may dip below zero inside the step there, that minimum :math:`C - B^2/4A` below
    :math:`A` within :data:`NEAR_REACH` spacings of the step; else vertex NaN."""
    if not (math.isfinite(older) and math.isfinite(last) and math.isfinite(now)):
        return np.nan, 0.0
    curvature = 0.5 * (older - 2.0 * last + now)
    if not curvature > 0.0:
        return np.nan, curvature
    slope = 0.5 * (older - 4.0 * last + 3.0 * now)
    vertex = -slope / (2.0 * curvature)
    if vertex < -spans - NEAR_REACH or vertex > NEAR_REACH:
        return np.nan, curvature
    if not now - slope * slope / (4.0 * curvature) < curvature:
        return np.nan, curvature
    return vertex, curvature


@njit(cache=True, inline="always", error_model="numpy")
def _dips_here(older, last, now):
    """Whether a margin sampled at three step ends may dip below zero inside the last step
    (:func:`dip_vertex`)."""
    return not math.isnan(dip_vertex(older, last, now, 1.0)[0])


@njit(cache=True, inline="always", error_model="numpy")
def _advance_into(model, coeffs, h, q0, v0, span, q, v, scratch, gen, fx, fy):
    """``advance`` without allocations: (q, v) and the loads after ``span`` from (q0, v0), in
    ceil(span/h) equal steps."""
    for i in range(q0.shape[0]):
        q[i] = q0[i]
        v[i] = v0[i]
    rolling_forces(model, q, scratch, gen, fx, fy)
    if span > 0.0:
        pieces = max(1, math.ceil(span / h * (1.0 - 1e-12)))
        for _ in range(pieces):
            _stages(model, coeffs, span / pieces, q, v, scratch, gen, fx, fy)

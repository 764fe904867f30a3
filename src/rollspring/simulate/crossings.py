r"""Event crossings inside an adaptive integrator's steps.

SciPy's ``solve_ivp`` looks for an event where its function changes sign **between the ends of
a step**. A function that crosses zero and comes back inside one step has the same sign at both
ends, and the event is never seen: a held body whose drive only grazes :math:`C_{rr} N R`
(docs/physics.md (M22)) for 36 ms inside one 49 ms DOP853 step was released 18 ms late, at the
next event of another body. :func:`first_crossing` looks inside the steps, on the integrator's
interpolant (its dense output), as event location with interpolation points does (like the
``interp_points`` of DifferentialEquations.jl's continuous callbacks): each event function is
sampled at ``per_step`` equal parts of every step, and an excursion shorter than a part is found
from the samples' local maxima.
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np

from rollspring.physics.arrays import FloatArray

__all__ = ["PER_STEP", "ROOT_TOLERANCE", "first_crossing"]

#: the equal parts each step is sampled at (its ends and ``PER_STEP - 1`` points between)
PER_STEP = 8
#: a sampled local maximum of :math:`d\,g` is maximised on the interpolant when it is within
#: this many times its larger difference to its neighbours of zero: a parabola through three
#: samples peaks above the middle one by at most 1/8 of that difference for equal spacings,
#: and by at most 2.3 times it for neighbouring spacings in a ratio up to 10 (the most a DOP853
#: step grows by from one step to the next)
_NEAR = 4.0
#: the relative tolerance to which SciPy's events and :func:`first_crossing` locate a root
ROOT_TOLERANCE = 4 * float(np.finfo(float).eps)
_TINY = float(np.finfo(float).tiny)


def first_crossing(
    values: Callable[[FloatArray], FloatArray],
    step_ends: FloatArray,
    direction: FloatArray,
    *,
    before: float | None = None,
    per_step: int = PER_STEP,
    rounding: FloatArray | None = None,
) -> tuple[float, int] | None:
    r"""The first instant at which an event function crosses zero in its direction, looking
    inside the steps: ``(t, k)`` of event ``k``, or None.

    Event :math:`k`, of function :math:`g_k(t)` (``values(times)[:, k]``, each column evaluated
    on the integrator's interpolant) and direction :math:`d_k = \pm 1`, is due where

    .. math:: d_k\, g_k(t) \le 0 \ \text{just before } t, \qquad d_k\, g_k(t) > 0 \ \text{just
        after}

    (SciPy's ``direction``: -1 for a function falling through zero). Every step
    :math:`[t_j, t_{j+1}]` of ``step_ends`` is cut into ``per_step`` equal parts; the function is
    sampled at their ends, and a crossing between two samples is located by Brent's method
    (``brentq``, to :math:`4\epsilon` as SciPy's events). An excursion above zero shorter than a
    part leaves every sample at or below zero: a sampled local maximum of :math:`d_k g_k`
    within :data:`_NEAR` times its larger difference to its neighbours of zero is maximised by
    bounded Brent on the two parts around it, and a maximum above zero brackets the crossing
    before it. The earliest crossing of all events is returned (the lowest ``k`` of equal
    times). A function exactly at zero where the samples start is taken as just below it (by
    the smallest float): it crosses where it comes back to zero, not at the start. With
    ``before`` (an event the integrator found itself), only one earlier than it by
    more than 16 times the roots' tolerance (the same root found twice is no new event). A
    function already above zero where the samples start has no crossing there (it
    is due at once, before integrating, or is rounding of a function that starts at zero).
    ``rounding`` (per event, default 0): a function that starts below zero by at most this
    much starts at zero, for the look just after the start (a slip velocity set a few ulps off
    zero, which grows away from it: no bounded search there, as for a function exactly at 0).
    """
    from scipy.optimize import brentq, minimize_scalar  # on demand, as SciPy's integrator

    ends = np.asarray(step_ends, dtype=float)
    if ends.size < 2 or not ends[-1] > ends[0]:
        return None
    parts = np.arange(per_step) / per_step
    times = np.append((ends[:-1, None] + np.diff(ends)[:, None] * parts).ravel(), ends[-1])
    times = times[np.concatenate([[True], np.diff(times) > 0])]  # a step of no length: once
    sign = np.asarray(direction, dtype=float)
    due = np.asarray(values(times), dtype=float) * sign  # > 0: event k is past due

    def signed(t: float, k: int) -> float:
        value = float(values(np.array([t]))[0, k] * sign[k])
        return -_TINY if value == 0.0 and t == times[0] else value

    # per event: the crossings between samples, and the sampled local maxima near zero (the
    # first sample, with one neighbour, where the function falls after it: not one exactly at
    # zero, a function that starts there and falls, as a rotation set turning at the start)
    crossing = (due[:-1] <= 0.0) & (due[1:] > 0.0)
    middle, left_of, right_of = due[1:-1], due[:-2], due[2:]
    rise = np.maximum(middle - left_of, middle - right_of)
    peak = (middle >= left_of) & (middle >= right_of) & (middle <= 0.0)
    peak &= middle + _NEAR * rise > 0.0
    below = 0.0 if rounding is None else -np.asarray(rounding, dtype=float)
    start = (below > due[0]) & (due[0] >= due[1]) & (due[0] + _NEAR * (due[0] - due[1]) > 0.0)
    candidates = np.flatnonzero(crossing.any(axis=0) | peak.any(axis=0) | start)
    best: tuple[float, int] | None = None
    for k in (int(c) for c in candidates):
        first = np.flatnonzero(crossing[:, k])
        # the bracket of the first crossing between samples, then every window around a
        # sampled local maximum near zero before it
        bracket = (int(first[0]), int(first[0]) + 1) if first.size else None
        windows = [(int(j), int(j) + 2) for j in np.flatnonzero(peak[:, k])]
        if start[k]:
            windows.insert(0, (0, 1))
        found: tuple[float, float] | None = None  # (left, right): v(left) <= 0 < v(right)
        for lo, hi in windows:
            if bracket is not None and lo >= bracket[0]:
                break
            highest = minimize_scalar(
                lambda t, k=k: -signed(t, k),
                bounds=(times[lo], times[hi]),
                method="bounded",
                options={"xatol": 1e-12 * (times[hi] - times[lo])},
            )
            if -float(highest.fun) > 0.0:
                found = (float(times[lo]), float(highest.x))
                break
        if found is None and bracket is not None:
            found = (float(times[bracket[0]]), float(times[bracket[1]]))
        if found is None:
            continue
        left, right = found
        root = left
        if signed(left, k) < 0.0:
            tolerance = {"xtol": ROOT_TOLERANCE, "rtol": ROOT_TOLERANCE}
            root = float(brentq(lambda t, k=k: signed(t, k), left, right, **tolerance))
        if best is None or root < best[0]:
            best = (root, k)
    if best is None or before is None:
        return best
    return best if best[0] < before - 16 * ROOT_TOLERANCE * (1.0 + abs(before)) else None

r"""The rolling segment of a run: every body rolls and no spring is damped.

The motion is :math:`J_i\ddot\varphi_i = Q_i(\varphi)` (docs/physics.md (M7)), integrated by
the compiled explicit symplectic scheme of the plan (:data:`~rollspring.simulate.kernels.SCHEMES`)
with equal steps that land on the segment's end, in chunks of about 2e5 steps (progress
reports and energy checks). The kernel interpolates the outputs inside the steps, keeps the
extremes of :math:`|f|/N` and :math:`N` over every step with the state before each (refined
later, :mod:`rollspring.simulate.extremes`) and counts the crossings of the lowest mode's
coordinate (the period). A slip or a lift-off is located to the instant by root-finding on the
step itself (:meth:`RollingSegments._locate`: the scheme run with a shorter step is the step's
interpolant).
"""

from __future__ import annotations

import math
import time
from collections.abc import Callable
from typing import Any

import numpy as np

from rollspring.errors import SimulationError
from rollspring.physics.arrays import FloatArray
from rollspring.simulate import kernels
from rollspring.simulate.crossings import first_crossing
from rollspring.simulate.run_state import NO_SAMPLES, Handover, Observed, RunState, Segment, Start
from rollspring.simulate.status import RunStatus, Status

__all__ = ["RollingSegments"]


class RollingSegments(RunState):
    """A run's rolling segments (symplectic, compiled): :meth:`_rolling_segment` and what it
    hands over (recorded rows, extremes with their states, crossings, located events)."""

    def _rolling_segment(
        self,
        t: float,
        state: FloatArray,
        energy: float | None = None,
        rolling: tuple[FloatArray, FloatArray, FloatArray] | None = None,
    ) -> Handover:
        """Integrate from the all-rolling ``state`` at ``t`` to the end or the next event.
        From the release, ``energy`` is its energy and ``rolling`` its (q, qdot, x0), and the
        release's row is recorded with the segment's first rows (:attr:`pending`)."""
        q, qdot, x0 = self.rolling_state(state) if rolling is None else rolling
        # energy is conserved from here on: the reference is its value now (slip lost some)
        if energy is None:
            energy = self._energy(
                state[None, :], np.zeros((1, self.n), dtype=bool), np.zeros((1, self.n))
            )[0]
        self.e_segment = energy
        # the reference positions move only when a body slipped: the same model as the run's
        same = rolling is not None or np.array_equal(x0, self.arrays.x0)
        model = self.packed if same else kernels.kernel_model(self.arrays, x0)
        slipping = np.zeros(self.n, dtype=bool)
        sign = np.zeros(self.n)
        grid = self.grid
        span = float(grid[-1]) - t
        if span <= 1e-12 * grid[-1]:
            self._flush_pending()
            return float(grid[-1]), self.general_state(q, qdot, x0), slipping, sign
        # equal steps that land on the end; outputs are interpolated inside the steps
        assert self.step is not None  # rolling segments run with a fixed-step scheme only
        n_total = max(1, math.ceil(span / self.step * (1 - 1e-12)))
        h = self.h = span / n_total
        first = int(np.searchsorted(grid, t + 1e-12 * grid[-1], side="right"))
        # the release's row goes first in the first block (its row of the grid is t = 0)
        lead = 1 if self.pending is not None and first == 1 and grid[0] == t else 0
        if not lead:
            self._flush_pending()
        # chunks of about 2e5 steps: progress reports and energy checks a few times a second
        chunk = 200_000
        row_times = [np.array([t])]
        row_q = [q[None, :].copy()]
        row_v = [qdot[None, :].copy()]
        n = self.n
        # seeded with the segment's first state: the extremes include its start
        if rolling is not None:  # observed at release already (no Numba kernel to load)
            friction0, normal0 = self.release_forces
        else:
            _, _, friction0, normal0 = kernels.advance(model, self.coeffs, q, qdot, 0.0, 0)
        ratio0 = [  # |f|/N of rolling bodies (inf where N <= 0), a few plain floats
            (abs(f) / nn if nn > 0 else math.inf) if rolls else -math.inf
            for f, nn, rolls in zip(
                friction0.tolist(), normal0.tolist(), self.rolls.tolist(), strict=True
            )
        ]
        negative_normal0 = [-nn for nn in normal0.tolist()]
        extremes = np.array([ratio0, [t] * n, normal0, [t] * n, ratio0, negative_normal0])
        # the peaks' last two samples (|f|/N, -N; run_fixed_step's docstring): the segment's
        # start, the one before unknown; the state before the last step's start
        samples = np.full((2, 2, n), np.nan)
        samples[0, 1] = np.where(self.rolls, ratio0, np.nan)
        samples[1, 1] = negative_normal0
        earlier = np.zeros((2, n))
        # the contact margins at the last two step ends (the kernel looks for a dip inside a
        # step from them): the segment's start, the one before unknown
        near_margins = np.full((2, 2, n), np.nan)
        near_margins[:, 1] = self._contact_margins(np.asarray(friction0), np.asarray(normal0))
        near_flags = np.zeros(2 * n, dtype=np.int64)
        offset = skip_near = 0  # steps of this chunk taken before a step looked inside
        ball_ptr, ball_idx = self.balls()
        extreme_states = np.empty((2, 2, ball_idx.size))
        extreme_states[:, 0, :] = q[ball_idx]
        extreme_states[:, 1, :] = qdot[ball_idx]
        crossing = np.array([0.0, 0.0, 0.0, float(self.plan.mode_weights @ (q - self.plan.q_ref))])
        crossing_states = np.zeros((2, 2, n))
        before = np.empty((2, n))
        # what the kernel keeps across the chunks (run_fixed_step's docstring), seeded above;
        # the period signal is weights . (q - q_ref)
        signal = (self.plan.mode_weights, self.plan.q_ref)
        kept = (extremes, extreme_states, ball_ptr, ball_idx, *signal, crossing, crossing_states)
        q, qdot = q.copy(), qdot.copy()
        # the kernel looks at a step from the two step ends before it: the segment's first step
        # is looked at here (each margin at its start, middle and end)
        root = self._first_step_dip(model, q, qdot, near_margins[:, 1].copy())
        if root is not None:
            self._flush_pending()
            self.segments.append(self._rolling_evaluator(model, [t], [q], [qdot], h, x0))
            self._offer_steps(
                model, x0, extremes, extreme_states, crossing, crossing_states, h, t + root[0]
            )
            return self._event_at(model, t, q.copy(), qdot.copy(), *root, x0)
        done = 0
        while done < n_total:
            steps = min(chunk, n_total - done)
            t_chunk = t + done * h
            if done + steps == n_total:
                last = grid.size
            else:
                last = int(np.searchsorted(grid, t + (done + steps) * h, side="right"))
            out_times = grid[first:last]
            # rows [lead:] for the kernel; row 0 the release's when it leads
            block_q = np.empty((out_times.size + lead, n))
            block_v = np.empty((out_times.size + lead, n))
            if lead:
                block_q[0] = q
                block_v[0] = qdot
            out_q, out_v = block_q[lead:], block_v[lead:]
            outputs = (out_times, out_q, out_v)
            began = time.perf_counter()
            status, taken, body, filled = kernels.run_fixed_step(
                model,
                self.coeffs,
                q,
                qdot,
                t_chunk,
                h,
                steps,
                True,
                *outputs,
                *kept,
                before,
                earlier,
                samples,
                near_margins,
                near_flags,
                offset,
                skip_near,
            )
            self.integrate_time += time.perf_counter() - began
            # a step the kernel stopped before, to look inside it, is counted when taken
            self._count_steps(self.plan.scheme, taken - offset - (status == kernels.STATUS_NEAR))
            row_times.append(out_times[:filled])
            row_q.append(out_q[:filled])
            row_v.append(out_v[:filled])
            if lead:
                self.pending = None
                block_times = grid[first - 1 : first + filled]
            else:
                block_times = out_times[:filled]
            if lead + filled and not self._energy_within(
                self._record_rolling(
                    block_times.copy(), block_q[: lead + filled], block_v[: lead + filled], x0
                )
            ):
                self.segments.append(self._rolling_evaluator(model, row_times, row_q, row_v, h, x0))
                ended = float(self.times[-1][-1])
                self._offer_steps(
                    model, x0, extremes, extreme_states, crossing, crossing_states, h, ended
                )
                return ended, self.rows[-1][-1], slipping, sign
            if status == kernels.STATUS_NEAR:
                # a contact margin may dip below zero inside the next step, between its ends
                t_before = t_chunk + (taken - 1) * h
                root = self._earliest_dip(
                    model, before[0], before[1], h, np.flatnonzero(near_flags), near_margins
                )
                if root is not None:
                    row_times.append(np.array([t_before]))
                    row_q.append(before[0][None, :].copy())
                    row_v.append(before[1][None, :].copy())
                    self.segments.append(
                        self._rolling_evaluator(model, row_times, row_q, row_v, h, x0)
                    )
                    self._offer_steps(
                        model,
                        x0,
                        extremes,
                        extreme_states,
                        crossing,
                        crossing_states,
                        h,
                        t_before + root[0],
                    )
                    return self._event_at(
                        model, t_before, before[0].copy(), before[1].copy(), *root, x0
                    )
                # it stays clear: the chunk goes on from the step's start, that step taken
                # again (the same numbers as had the kernel not stopped)
                q[:], qdot[:] = before[0], before[1]
                first += filled
                offset, skip_near = taken - 1, taken
                lead = 0
                continue
            if status != Status.FINISHED:
                t_before = t_chunk + (taken - 1) * h
                row_times.append(np.array([t_before]))
                row_q.append(before[0][None, :].copy())
                row_v.append(before[1][None, :].copy())
                self.segments.append(self._rolling_evaluator(model, row_times, row_q, row_v, h, x0))

                def reached(until: float) -> None:
                    """The steps' extremes handed over, their windows cut where the motion
                    ends (at the event inside the step after t_before, once located)."""
                    self._offer_steps(
                        model, x0, extremes, extreme_states, crossing, crossing_states, h, until
                    )

                if status == Status.NONFINITE:
                    reached(t_before)
                    self.status = RunStatus.NONFINITE
                    self.message = (
                        f"the state became non-finite at t = {t_before + h:.6g} s "
                        f"('{self.arrays.ids[body]}'); the step cannot resolve the "
                        f"motion"
                    )
                    return t_before, self.general_state(before[0], before[1], x0), slipping, sign
                return self._locate(
                    model, t_before, before[0].copy(), before[1].copy(), h, 1, x0, reached
                )
            first += filled
            done += steps
            offset = skip_near = 0
            lead = 0
            self._report(t + done * h)
        self.segments.append(self._rolling_evaluator(model, row_times, row_q, row_v, h, x0))
        end = float(grid[-1])
        self._offer_steps(model, x0, extremes, extreme_states, crossing, crossing_states, h, end)
        if self.grid_rows and self.times and float(self.times[-1][-1]) == end:
            # the run is over (nothing steps on from the handover): the last row, the state
            # at the end to rounding, instead of building it again
            return end, self.rows[-1][-1].copy(), slipping, sign
        return end, self.general_state(q, qdot, x0), slipping, sign

    def _record_rolling(
        self, times: FloatArray, q: FloatArray, v: FloatArray, x0: FloatArray
    ) -> float:
        """:meth:`_record_block` of all-rolling rows (q, qdot) with reference positions x0,
        states and observations by one compiled pass (:func:`kernels.observe_rolling`);
        returns the largest |E - E_segment| over the rows."""
        rows, n = q.shape
        ns = self.arrays.n_springs
        states = np.empty((rows, 4 * n))
        out = Observed(
            np.empty((rows, n)),
            np.empty((rows, n)),
            np.empty((rows, n)),
            np.empty((rows, ns)),
            np.empty((rows, ns)),
            np.empty(rows),
            np.empty(rows),
        )
        extremes = np.empty((4, n))
        deviation = kernels.observe_rolling(
            self.packed,
            x0,
            q,
            v,
            self.central,
            self.e_segment,
            states,
            out.friction,
            out.normal,
            out.length,
            out.tension,
            out.potential,
            out.kinetic,
            out.ratio,
            extremes,
        )
        self.block_extremes = extremes
        self.times.append(times)
        self.rows.append(states)
        self.row_slipping.append(np.zeros((rows, n), dtype=bool))
        self.row_sign.append(np.zeros((rows, n)))
        self.observed.append(out)
        return float(deviation)

    def _local(
        self,
        model: tuple[Any, ...],
        x0: FloatArray,
        t_start: float,
        q: FloatArray,
        v: FloatArray,
        h: float,
        ball: np.ndarray | None = None,
        until: float = math.inf,
    ) -> Segment:
        """A segment of two steps from the state (q, v) at ``t_start``, cut at ``until`` (where
        the rolling motion ends: the run's end or an event). Its interpolant is built on first
        use: most are refined from their ``start`` in one compiled call. With ``ball``, (q, v)
        are the states of those bodies alone (an extreme of a large system): such a segment is
        refined from its start only (:func:`_refine_together`)."""
        t_end = min(t_start + 2 * h, until)
        start = Start(t_start, q.copy(), v.copy(), model, self.coeffs, h, x0, ball, t_end - t_start)
        built: list[Segment] = []
        slipping, sign = self.all_rolling

        def evaluate(t: float | FloatArray) -> FloatArray:
            if ball is not None:
                raise SimulationError(
                    "internal: a windowed extreme's segment has no interpolant (refine it "
                    "from its start)"
                )
            if not built:
                built.append(
                    self._rolling_evaluator(
                        model, [t_start], [start.q], [start.v], h, x0, t_end=t_end
                    )
                )
            return built[0].evaluate(t)

        return Segment(t_start, t_end, slipping, sign, evaluate, NO_SAMPLES, start)

    def _offer_steps(
        self,
        model: tuple[Any, ...],
        x0: FloatArray,
        extremes: FloatArray,
        extreme_states: FloatArray,
        crossing: FloatArray,
        crossing_states: FloatArray,
        h: float,
        until: float,
    ) -> None:
        """Hand the kernel's extremes and crossings over, each with the state it starts from
        and its window cut at ``until``, where the segment's rolling motion ends."""
        found = extremes.tolist()
        ball_ptr, ball_idx = self.balls()
        for i in range(self.n):
            for kind, row in (("ratio", 0), ("normal", 2)):
                value = found[row][i]
                k = 0 if kind == "ratio" else 1
                key = found[4 + k][i]  # the peak to refine (maximised: |f|/N, -N)
                if not (math.isfinite(value) and math.isfinite(key)) or (
                    kind == "ratio" and not self.rolls[i]
                ):
                    continue
                # every rolling segment's peak is kept, each refined after the run
                t_start = found[row + 1][i]
                # a normal force that cannot change is never refined: no segment for it
                lo, hi = ball_ptr[i], ball_ptr[i + 1]
                local = (
                    None
                    if kind == "normal" and self.constant_normal
                    else self._local(
                        model,
                        x0,
                        t_start,
                        extreme_states[k, 0, lo:hi],
                        extreme_states[k, 1, lo:hi],
                        h,
                        ball_idx[lo:hi] if self.plan.windowed else None,
                        until,
                    )
                )
                self.step_extremes.setdefault((kind, i), []).append(
                    (value, t_start + h, h, local, key)
                )
        self.crossings.append(
            (
                int(crossing[0]),
                [
                    self._local(
                        model,
                        x0,
                        float(crossing[1 + j]),
                        crossing_states[j, 0],
                        crossing_states[j, 1],
                        h,
                        until=until,
                    )
                    for j in range(2)
                ],
            )
        )

    def _rolling_evaluator(
        self,
        model: tuple[Any, ...],
        times: list[Any],
        qs: list[Any],
        vs: list[Any],
        h: float,
        x0: FloatArray,
        t_end: float | None = None,
    ) -> Segment:
        """A segment whose state at any t is the integrator run on from the row before t.
        ``times``/``qs``/``vs`` are lists of rows or of blocks of rows (joined on first use:
        most segments are never evaluated)."""
        first = float(np.atleast_1d(np.asarray(times[0], dtype=float))[0])
        last = float(np.atleast_1d(np.asarray(times[-1], dtype=float))[-1])
        coeffs = self.coeffs
        rows_of: list[tuple[FloatArray, FloatArray, FloatArray]] = []

        def evaluate(t: float | FloatArray) -> FloatArray:
            """The state at time(s) ``t``: (4n,) for a number, (m, 4n) for an array."""
            if not rows_of:
                rows_of.append(
                    (
                        np.concatenate([np.atleast_1d(np.asarray(x, dtype=float)) for x in times]),
                        np.concatenate([np.atleast_2d(np.asarray(x, dtype=float)) for x in qs]),
                        np.concatenate([np.atleast_2d(np.asarray(x, dtype=float)) for x in vs]),
                    )
                )
            row_t, row_q, row_v = rows_of[0]
            at = np.atleast_1d(np.asarray(t, dtype=float))
            if len(row_t) == 1:
                rows = np.zeros(at.size, dtype=np.int64)
            else:
                rows = np.clip(np.searchsorted(row_t, at, side="right") - 1, 0, len(row_t) - 1)
            spans = at - row_t[rows]
            pieces = np.where(spans > 0, np.maximum(1, np.ceil(spans / h * (1 - 1e-12))), 0)
            q, v = kernels.advance_many(
                model, coeffs, row_q[rows], row_v[rows], spans, pieces.astype(np.int64)
            )
            states = self.general_state(q, v, x0)
            return states if np.ndim(t) else states[0]

        # extremes: the output rows and the kernel's extremes over every step cover it
        slipping, sign = self.all_rolling
        end = last if t_end is None else float(t_end)
        return Segment(first, end, slipping, sign, evaluate, NO_SAMPLES)

    def _locate(
        self,
        model: tuple[Any, ...],
        t_before: float,
        q: FloatArray,
        v: FloatArray,
        span: float,
        pieces: int,
        x0: FloatArray,
        reached: Callable[[float], None] | None = None,
    ) -> Handover:
        """An event happened within ``span`` after ``t_before``: find its instant; ``reached``
        is called with the instant where the motion ends (the event's, or where the state
        stops being finite) before the event is taken."""
        slipping = np.zeros(self.n, dtype=bool)
        sign = np.zeros(self.n)
        h = span / pieces
        # find the piece, then the instant inside it
        for _ in range(pieces):
            q1, v1, f1, n1 = kernels.advance(model, self.coeffs, q, v, h, 1)
            if self._violation(f1, n1) is not None or not np.all(np.isfinite(q1)):
                break
            q, v, t_before = q1, v1, t_before + h

        def margins(tau: float) -> FloatArray:
            return self._margins(model, q, v, tau)

        end = margins(h)  # NaN where a body cannot slip: never below zero
        start = margins(0.0)
        best = None
        import scipy.optimize  # on demand: an event to locate (SciPy's optimizers take ~0.1 s)

        for j in np.flatnonzero((end < 0) | ((end == 0) & (start > 0))):
            if start[j] == 0.0:  # at zero where the piece starts: its side is where it goes

                def margin(tau: float, j: int = int(j)) -> float:
                    return float(margins(tau)[j])

                root = _first_fall(margin, h)
            elif not np.isfinite(start[j]) or start[j] < 0:
                root = 0.0
            else:
                root = scipy.optimize.brentq(
                    lambda tau, j=j: margins(tau)[j],
                    0.0,
                    h,
                    xtol=1e-15,
                    rtol=4 * np.finfo(float).eps,
                )
            if best is None or root < best[0]:
                best = (root, j)
        if best is None:  # non-finite state
            if reached is not None:
                reached(t_before)
            self.status = RunStatus.NONFINITE
            self.message = f"the state became non-finite near t = {t_before:.6g} s"
            return t_before, self.general_state(q, v, x0), slipping, sign
        root, j = best
        if reached is not None:
            reached(t_before + root)
        return self._event_at(model, t_before, q, v, root, int(j), x0)

    def _margins(
        self, model: tuple[Any, ...], q: FloatArray, v: FloatArray, tau: float
    ) -> FloatArray:
        r"""The contact margins ``tau`` into a step from (q, v), on the step's interpolant (the
        scheme run with a step of ``tau``): the slip margins :math:`\mu_sN_i - |f_i|` (NaN
        where a body cannot slip), then the normal forces :math:`N_i`."""
        _, _, f, nn = kernels.advance(model, self.coeffs, q, v, tau, 1 if tau > 0 else 0)
        return self._contact_margins(f, nn).ravel()

    def _contact_margins(self, friction: FloatArray, normal: FloatArray) -> FloatArray:
        r"""(2, n): the slip margins :math:`\mu_sN_i - |f_i|` (docs/physics.md §9; NaN where a
        body cannot slip: it does not roll, or :math:`\mu_s = \infty`) and the normal forces
        :math:`N_i`, for the needed frictions and normal forces (M8), (M9)."""
        mu = self.arrays.mu_static
        can_slip = self.rolls & np.isfinite(mu)
        slip = np.where(can_slip, np.where(can_slip, mu, 0.0) * normal - np.abs(friction), np.nan)
        return np.stack([slip, normal])

    def _earliest_dip(
        self,
        model: tuple[Any, ...],
        q: FloatArray,
        v: FloatArray,
        h: float,
        flagged: np.ndarray,
        near_margins: FloatArray,
    ) -> tuple[float, int] | None:
        """The earliest instant (from the step's start, and its margin) at which one of the
        margins ``flagged`` (:meth:`_margins`' order) falls below zero inside the step of
        length ``h`` from (q, v), whose two step ends before it are ``near_margins`` (older,
        last): each looked at by :meth:`_dip_inside`; None when all stay clear."""
        n = self.n
        end = self._margins(model, q, v, h)
        best: tuple[float, int] | None = None
        for j in flagged.tolist():
            kind, body = divmod(j, n)
            samples = (near_margins[kind, 0, body], near_margins[kind, 1, body], end[j])
            root = self._dip_inside(model, q, v, h, j, samples, 1.0)
            if root is not None and (best is None or root < best[0]):
                best = (root, j)
        return best

    def _first_step_dip(
        self, model: tuple[Any, ...], q: FloatArray, v: FloatArray, start: FloatArray
    ) -> tuple[float, int] | None:
        """:meth:`_earliest_dip` for a segment's first step (no step end before it): each
        margin sampled at the step's start (``start``, (2, n)), middle and end, the parabola
        through the three looked at over the whole step."""
        assert self.h is not None
        h, n = self.h, self.n
        middle, end = self._margins(model, q, v, 0.5 * h), self._margins(model, q, v, h)
        first = np.concatenate([start[0], start[1]])
        best: tuple[float, int] | None = None
        for j in range(2 * n):
            samples = (first[j], middle[j], end[j])
            root = self._dip_inside(model, q, v, h, j, samples, 2.0)
            if root is not None and (best is None or root < best[0]):
                best = (root, j)
        return best

    def _dip_inside(
        self,
        model: tuple[Any, ...],
        q: FloatArray,
        v: FloatArray,
        h: float,
        j: int,
        samples: tuple[float, float, float],
        spans: float,
    ) -> float | None:
        r"""Where contact margin ``j`` (:meth:`_margins`' order) first falls below zero inside
        the step of length ``h`` from (q, v), or None when it stays clear. ``samples``: the
        margin at three equally spaced instants ending at the step's end, ``spans`` of their
        spacings making up the step (1: two step ends before and this one's; 2: the step's
        start, middle and end). The parabola through them, :math:`A\tau^2 + B\tau + C`, has its
        minimum :math:`C - B^2/4A` at :math:`\tau^*`; when that is in the step and below
        :math:`A`, the margin is evaluated at :math:`\tau^*` on the interpolant: above
        :math:`A/20` the step is clear (the parabola's vertex is off by a small fraction of a
        spacing, so the true minimum is within :math:`A/100` of it); else the minimum over the
        step is found (bounded Brent) and, below zero, the root before it."""
        older, last, now = samples
        vertex, curvature = kernels.dip_vertex(float(older), float(last), float(now), spans)
        if math.isnan(vertex):  # in spacings from the step's end
            return None

        def margin(tau: float) -> float:
            return float(self._margins(model, q, v, tau)[j])

        at_vertex = min(max(h * (1.0 + vertex / spans), 0.0), h)
        if margin(at_vertex) > 0.05 * curvature:
            return None
        import scipy.optimize  # on demand: a graze to look at

        lowest = scipy.optimize.minimize_scalar(
            margin, bounds=(0.0, h), method="bounded", options={"xatol": 1e-12 * h}
        )
        low_tau, low = float(lowest.x), float(lowest.fun)
        if margin(at_vertex) < low:
            low_tau, low = at_vertex, margin(at_vertex)
        if not low < 0.0:
            return None
        if margin(0.0) == 0.0:
            return _first_fall(margin, low_tau)
        if not margin(0.0) > 0.0:
            return 0.0
        return float(
            scipy.optimize.brentq(margin, 0.0, low_tau, xtol=1e-15, rtol=4 * np.finfo(float).eps)
        )

    def _event_at(
        self,
        model: tuple[Any, ...],
        t_before: float,
        q: FloatArray,
        v: FloatArray,
        root: float,
        j: int,
        x0: FloatArray,
    ) -> Handover:
        """The event of contact margin ``j`` (< n: a slip of body j, else a lift-off of body
        j - n) ``root`` after ``t_before``, from the state (q, v) there: the segment to it
        recorded, the event taken."""
        slipping = np.zeros(self.n, dtype=bool)
        sign = np.zeros(self.n)
        kind = "slip" if j < self.n else "liftoff"
        body = j % self.n
        q_e, v_e, _, _ = kernels.advance(model, self.coeffs, q, v, root, 1 if root > 0 else 0)
        t_event = t_before + root
        self._record_to_event(model, t_before, q, v, t_event, x0)
        state = self.general_state(q_e, v_e, x0)
        self.segments.append(
            self._rolling_evaluator(
                model, [t_before, t_event], [q, q_e], [v, v_e], max(root, 1e-300), x0
            )
        )
        if self._event(kind, body, t_event, state, slipping, sign):
            self._record(t_event, state, slipping, sign)
            return t_event, state, slipping, sign
        return t_event, state, slipping, sign

    def _record_to_event(
        self,
        model: tuple[Any, ...],
        t_before: float,
        q: FloatArray,
        v: FloatArray,
        t_event: float,
        x0: FloatArray,
    ) -> None:
        """Record the output times from the step that holds the event, which starts at
        ``t_before`` in the state (q, v), to the event at ``t_event``: each one step of the
        scheme from (q, v), as the event's own state (the steps before recorded theirs; the
        segment after the event takes the output times more than ``1e-12`` of the run after
        it, as every segment does from its start)."""
        grid = self.grid
        last = float(self.times[-1][-1]) if self.times else -math.inf
        taus = grid[(grid > last) & (grid >= t_before) & (grid <= t_event + 1e-12 * grid[-1])]
        if not taus.size:
            return
        spans = taus - t_before
        q_rows, v_rows = kernels.advance_many(
            model,
            self.coeffs,
            np.tile(q, (taus.size, 1)),
            np.tile(v, (taus.size, 1)),
            spans,
            (spans > 0).astype(np.int64),
        )
        self._record_rolling(taus.copy(), q_rows, v_rows, x0)


def _first_fall(margin: Callable[[float], float], until: float) -> float:
    r"""Where a contact margin that is exactly zero at :math:`\tau = 0` and below zero at
    ``until`` first falls through zero, by :func:`~rollspring.simulate.crossings.first_crossing`
    (which takes a function at zero where it starts as on its side before the crossing): 0 when
    it falls at once, else after it has risen (a normal force or a friction margin that starts
    at zero, as a spring's pull that exactly balances the weight). Taking every such margin as
    crossing at 0 lost the whole motion of a body whose normal force starts at zero when the
    first step was longer than the time it stays positive."""

    def values(times: FloatArray) -> FloatArray:
        return np.array([[margin(float(tau))] for tau in times])

    found = first_crossing(values, np.array([0.0, until]), np.array([-1.0]))
    return 0.0 if found is None else found[0]

r"""The general segment of a run: SciPy's adaptive DOP853 on :math:`[x, \varphi, u, \omega]`.

Used while a spring is damped, a body slips (kinetic friction, docs/physics.md (M19), with
``on_slip="continue"``), a body has rolling resistance ((M21), (M22)) or ``integrator="dop853"``
is asked for. The events are SciPy's terminal events, located to the instant on the step: a
rolling body's needed friction reaching :math:`\mu_s N` (slip), a slipping body's contact speed
reaching zero (stick, or reverse when static friction cannot hold it), a normal force falling to
zero (lift-off), a resisted body's rotation reaching zero (``rest`` when the torque driving it is
within :math:`C_{rr} N R`, else it turns back) and a resting body's drive exceeding that bound
(``release``), each looked for inside the steps too, where SciPy compares signs at their ends
only (:func:`~rollspring.simulate.crossings.first_crossing`: a drive that grazes the bound);
between events each resisted body's resistance keeps its direction
(:attr:`~rollspring.simulate.run_state.RunState.spin`), so the right-hand side is smooth, and at
every event every resisted body is decided (several stop at one instant when a mode moves
alone). The segment's dense output is its interpolant (extremes and period,
:mod:`rollspring.simulate.extremes`).
"""

from __future__ import annotations

import time
from typing import Any

import numpy as np

from rollspring.physics.arrays import FloatArray
from rollspring.simulate import kernels
from rollspring.simulate.crossings import ROOT_TOLERANCE, first_crossing
from rollspring.simulate.run_state import (
    SLIP_OFF,
    BoolArray,
    Handover,
    RunState,
    Segment,
    slip_rounding,
    slip_velocities,
)
from rollspring.simulate.status import RunStatus

__all__ = ["GeneralSegments"]

_TINY = float(np.finfo(float).tiny)


def _past_the_root(
    t_root: float,
    y_root: FloatArray,
    value: Any,
    state_at: Any,
    direction: float,
    limit: float,
) -> tuple[float, FloatArray]:
    """An event's instant and state moved just past its root, where its function (``value``,
    of direction ``direction``) has crossed zero: the root found to a few ulps may lie on the
    near side of it. There the body's state would still be on the old side (a needed friction
    a rounding short of mu_s N, with positions that a step of 1e-14 s leaves unchanged), the
    segment that starts from it would find the same root an instant later, and the run would
    stall for ever (two bodies at their limits took turns). The root is moved by doubling
    steps from one ulp, up to 8 times the roots' tolerance (the root is within one of it;
    less than the 16 within which an event counts as at its segment's start), to the first
    time found past it; it is left where none is found there (a function that only touches
    zero)."""
    if direction * float(value(np.array([t_root]))[0]) > 0.0:
        return t_root, y_root
    gap = float(np.spacing(t_root))
    widest = 8 * ROOT_TOLERANCE * (1.0 + abs(t_root))
    while gap <= widest and t_root + gap <= limit:
        if direction * float(value(np.array([t_root + gap]))[0]) > 0.0:
            return t_root + gap, state_at(t_root + gap)
        gap *= 2.0
    return t_root, y_root


def _off_zero_at(start: float, event: Any, side: float) -> Any:
    """``event(t, y)``, but the smallest float on the ``side`` (+1 or -1) of zero where it is
    exactly zero at ``t == start``."""

    def shifted(t: float, y: FloatArray) -> float:
        value = float(event(t, y))
        return side * _TINY if value == 0.0 and t == start else value

    return shifted


class GeneralSegments(RunState):
    """A run's general segments (DOP853): damping, slipping, stick and reverse events."""

    def _general_segment(
        self, t: float, state: FloatArray, slipping: BoolArray, sign: FloatArray
    ) -> Handover:
        """Integrate from the general ``state`` at ``t`` with DOP853 to the end or the next
        event, recording the output rows; ``slipping`` bodies feel kinetic friction of sign
        ``sign``."""
        n, a, model, damped = self.n, self.arrays, self.packed, self.plan.damped
        slipping = slipping.copy()
        sign = sign.copy()
        # a rolling body already beyond its friction limit (or a normal force below zero) where
        # the segment starts: at release beside another one, or one whose event fell at the
        # same instant as the last segment's, or whose resistance has just turned: it slips (or
        # lifts off) here, its event function being past zero already
        # A resisted body past its bound where the segment starts is decided here too: one held
        # while its |D| exceeds C_rr N R (its drive changed with a slip taken just above, or
        # with the other bodies' resistances decided at the last event) is released, one turning
        # against its resistance stops: its event function, past zero already, would never
        # cross zero in this segment. Each pass settles one body for good: it ends.
        verdict = self._contact_verdict(state, slipping)
        # The release's row (at a run's first segment) shows the bodies that slip from it
        # slipping: it is recorded once they are decided, or before an event that ends the run
        while verdict is not None or self._resistance_violated(t, state, slipping, sign):
            if verdict is None:
                self._flush_pending(slipping, sign)
                self._resistance_events(t, state, slipping, sign, np.zeros(n))
            else:
                if self._ends_run(verdict[0]):
                    self._release_before_the_end(t, state, slipping, sign)
                if self._event(*verdict, t, state, slipping, sign):
                    self._record(t, state, slipping, sign)
                    return t, state, slipping, sign
            verdict = self._contact_verdict(state, slipping)
        self._flush_pending(slipping, sign)
        spin = self.spin.copy()  # the rolling resistance's directions (M21), (M22)
        mu_s = a.mu_static

        def rhs(_t: float, y: FloatArray) -> FloatArray:
            out = np.empty(4 * n)
            kernels.slipping_derivatives(model, y, slipping, sign, spin, damped, out)
            return out

        labels = []  # the events: (kind, body), their functions in :meth:`_event_values`
        for i in range(n):
            if self.rolls[i] and not slipping[i] and np.isfinite(mu_s[i]):
                labels.append(("slip", i))
            if self.rolls[i] and slipping[i]:
                labels.append(("stick", i))
            labels.append(("liftoff", i))
            if self.rolls[i] and a.rolling_resistance[i] > 0:
                # turning: the rotation stops (M21); held at rest: the drive exceeds what the
                # resistance holds (M22)
                labels.append(("turn" if spin[i] != 0.0 else "release", i))

        # A body held at this instant with its drive at the bound (a "hold", M22) may start
        # the segment with its release function past zero by rounding: read as it is, the
        # function would be "due already" and its crossing where the drive leaves the bound
        # for real never seen (SciPy and first_crossing both take a function past zero where
        # they start as having no crossing there), and the body would stay held for good. Its
        # function is measured from its value here instead, zero where the segment starts.
        offsets = self._held_offsets(t, state, labels, slipping, sign, spin)

        def values_at(states: FloatArray) -> FloatArray:
            return self._event_values(states, labels, slipping, sign, spin) - offsets

        # SciPy calls every event function with the same state array after a step: all of them
        # evaluated once for it (O(n) per step, not O(n) per body), by the function the search
        # inside the steps uses too
        last: list[Any] = [None, None]

        def event_values(y: FloatArray) -> FloatArray:
            if last[0] is not y:
                last[:] = [y, values_at(y[None, :])[0]]
            values: FloatArray = last[1]
            return values

        events: list[Any] = [
            lambda _t, y, j=j: float(event_values(y)[j]) for j in range(len(labels))
        ]
        direction = np.array([-sign[i] if kind == "stick" else -1.0 for kind, i in labels])
        # A function exactly at zero where the segment starts (a rotation set at rest and
        # turning from this instant, a slip velocity made 0 where a slip reverses) is taken as
        # on its side before a crossing, by the smallest float: SciPy would otherwise take the
        # start itself as the root whenever the function is past zero at the end of the first
        # step, even after it first left zero the other way (a body released where its drive
        # grazes the bound turns and stops again inside that step)
        events = [
            _off_zero_at(t, event, -float(falling))
            for event, falling in zip(events, direction, strict=True)
        ]
        for event, falling in zip(events, direction, strict=True):
            event.terminal = True
            event.direction = float(falling)
        t_eval = self.grid[(self.grid > t + 1e-12 * self.grid[-1])]
        scale = max(float(np.max(np.abs(state))), float(np.max(a.radius)))
        import scipy.integrate  # on demand: only the general (DOP853) segments need it

        began = time.perf_counter()
        solution = scipy.integrate.solve_ivp(
            rhs,
            (t, self.grid[-1]),
            state,
            method="DOP853",
            t_eval=t_eval,
            rtol=max(self.plan.rtol, 1e-13),
            atol=max(self.plan.rtol, 1e-13) * scale * 1e-2,
            events=events,
            dense_output=True,
        )
        self.integrate_time += time.perf_counter() - began
        if solution.sol is not None:  # the adaptive steps taken
            self._count_steps("dop853", len(solution.sol.ts) - 1)
        if solution.status == -1:
            self.status = RunStatus.NONFINITE
            self.message = f"the adaptive integrator failed: {solution.message}"
            return self.grid[-1], state, slipping, sign
        # SciPy leaves t and y as empty lists when no output time falls before the first event
        # (a body that slips at once, an early slip): arrays of no columns then
        times = np.asarray(solution.t, dtype=float)
        values = np.asarray(solution.y, dtype=float).reshape(state.size, times.size)
        dense = solution.sol
        which: int | None = None  # the event that ends the segment, None at the run's end
        t_end = self.grid[-1]
        y_event = state
        if solution.status == 1:
            which = next(j for j, te in enumerate(solution.t_events) if len(te))
            t_end = float(solution.t_events[which][0])
            y_event = np.asarray(solution.y_events[which][0], dtype=float)
        # SciPy sees an event only where its function's sign differs at the two ends of a step:
        # an excursion past zero and back inside one step (a drive that grazes C_rr N R, a
        # rotation that touches 0) is looked for inside the steps, on the interpolant
        # (:func:`first_crossing`); the segment then ends at the earliest one, its rows after it
        # dropped (they were integrated on a motion that no longer holds)
        steps = np.asarray(dense.ts)
        if events:
            inside = first_crossing(
                lambda tt: values_at(np.asarray(dense(tt)).T),
                steps,
                direction,
                before=t_end,
                rounding=self._stick_rounding(state, labels),
            )
            if inside is not None:
                t_end, which = inside
                y_event = np.asarray(dense(t_end), dtype=float)
            if which is not None:
                t_end, y_event = _past_the_root(
                    t_end,
                    y_event,
                    lambda tt: values_at(np.asarray(dense(tt)).T)[:, which],
                    lambda tt: np.asarray(dense(tt), dtype=float),
                    float(direction[which]),
                    float(steps[-1]),
                )
            if inside is not None:
                kept = times <= t_end
                times, values = times[kept], values[:, kept]
                steps = np.append(steps[steps < t_end], t_end)
        if times.size:
            self._record_block(times, values.T, slipping, sign)

        def dense_state(tt: float | FloatArray, d: Any = dense) -> FloatArray:
            return np.asarray(d(tt)).T

        self.segments.append(
            Segment(
                t,
                t_end,
                slipping.copy(),
                sign.copy(),
                dense_state,
                steps,
                spin=spin.copy() if a.resisted else None,
            )
        )
        self._report(t_end)
        if which is None:
            return self.grid[-1], values[:, -1] if times.size else state, slipping, sign
        kind, body = labels[which]
        at_start = t_end - t <= 16 * ROOT_TOLERANCE * (1.0 + abs(t))
        if kind == "turn" and at_start and state[3 * n + body] == 0.0:
            # a rotation set turning where the segment starts turned back against its
            # resistance at once: its drive was at the bound, not beyond it; it is held
            kind = "hold"
        acceleration = np.zeros(n)
        if a.resisted:
            # the rotations' scale over the run so far, and the accelerations at the event
            # with this segment's directions: which other resisted bodies stop here too
            peaks = np.abs(dense(steps))[3 * n :].max(axis=1)
            self.omega_peak = np.maximum(self.omega_peak, peaks)
            acceleration = rhs(t_end, y_event)[3 * n :]
        was_slipping = slipping.copy()  # the bodies slipping before the event
        # the slip accelerations before the event (a body's own, whatever the others do):
        # which slipping bodies are arriving at v_s = 0, below
        slip_acceleration = slip_velocities(rhs(t_end, y_event), a.radius, n)
        if kind == "stick":
            self._stick_or_reverse(body, t_end, y_event, slipping, sign)
        elif kind not in ("turn", "hold", "release") and self._event(
            kind, body, t_end, y_event, slipping, sign
        ):
            self._record(t_end, y_event, slipping, sign)
            return t_end, y_event, slipping, sign
        # every other body is decided at this instant too: one whose event is due here as well
        # (a mode moving alone stops, sticks or slips its bodies together) would otherwise be
        # lost, its event function already at zero or past it when the next segment starts.
        # A slipping body whose slip velocity has reached zero, arriving there (its slip
        # decelerating), sticks or reverses. One whose slip grows has just begun: a v_s past
        # zero is then the integrator's rounding of a slip still ~0 (with mu_k = mu_s, v_s
        # grows as t^2 from onset), and deciding it would stick it only to slip it again an
        # instant later, for ever (two bodies at their limits took turns every 1e-14 s).
        slip_velocity = slip_velocities(y_event, a.radius, n)
        for i in range(n):
            if (
                was_slipping[i]
                and (kind, body) != ("stick", i)
                and sign[i] * slip_velocity[i] < 0
                and sign[i] * slip_acceleration[i] <= 0
            ):
                self._stick_or_reverse(i, t_end, y_event, slipping, sign)
        if a.resisted:  # every resisted body stopping here rests or turns; a driven one releases
            trigger = (kind, body) if kind in ("turn", "hold", "release") else None
            self._resistance_events(t_end, y_event, slipping, sign, acceleration, trigger)
        return t_end, y_event, slipping, sign

    def _stick_rounding(self, state: FloatArray, labels: list[tuple[str, int]]) -> FloatArray:
        """Per event, how far below zero its function may start and still be at zero: for a
        stick, the few ulps a slip is set off :math:`v_s = 0` by
        (:meth:`~rollspring.simulate.run_state.RunState._slip_off`); 0 for the others."""
        n, radius = self.n, self.arrays.radius
        out = np.zeros(len(labels))
        for k, (kind, i) in enumerate(labels):
            if kind == "stick":  # (twice the roundings it is set off by)
                out[k] = 2 * SLIP_OFF * slip_rounding(state, radius, n, i)
        return out

    def _stick_or_reverse(
        self, body: int, t: float, state: FloatArray, slipping: BoolArray, sign: FloatArray
    ) -> None:
        r"""A slipping body whose slip velocity :math:`u - R\omega` reached zero at ``t``
        (docs/physics.md (M19)): ``state`` made exact there; it sticks (event ``stick``) when the
        static friction rolling needs is within :math:`\mu_s N`, else it slips on the other way
        (``reverse``). A resisted body whose rotation was held while it slipped is then wholly
        at rest: held, or driven, by (M22)."""
        n, a = self.n, self.arrays
        state[2 * n + body] = a.radius[body] * state[3 * n + body]  # v_s = 0 exactly
        trial = slipping.copy()
        trial[body] = False
        if a.rolling_resistance[body] > 0 and self.spin[body] == 0.0:
            self.spin[body] = self._resting_spin(state, trial, sign, body)
        friction, normal, *_ = self.observe(
            state[None, :], trial[None], sign[None], self.spin[None]
        )
        if abs(friction[0, body]) <= a.mu_static[body] * normal[0, body]:
            slipping[body] = False
            sign[body] = 0.0
            self.events.append({"kind": "stick", "time": t, "body": a.ids[body]})
            return
        # it slips on the way the static friction needed drives it, as at onset: the other
        # way where v_s came back to zero, the same way where a v_s of rounding's size only
        # touched zero (a slip just begun): no event then
        onward = -float(np.sign(friction[0, body])) or -sign[body]
        if onward != sign[body]:
            sign[body] = onward
            self.events.append({"kind": "reverse", "time": t, "body": a.ids[body]})
        self._slip_off(state, body, onward)

    def _resistance_drive(
        self, state: FloatArray, slipping: BoolArray, sign: FloatArray
    ) -> tuple[FloatArray, FloatArray]:
        """:func:`kernels.resistance_drives` of a general state: per body the torque driving
        its rotation and the most the rolling resistance holds it against, :math:`C_{rr} N R`."""
        drive, limit = np.empty(self.n), np.empty(self.n)
        kernels.resistance_drives(
            self.packed, state, slipping, sign, self.plan.damped, drive, limit
        )
        return drive, limit

    def _resistance_violated(
        self, t: float, state: FloatArray, slipping: BoolArray, sign: FloatArray
    ) -> bool:
        r"""Whether a resisted body is past its bound in ``state`` at ``t``: held (:attr:`spin`
        0) with :math:`|D| > C_{rr} N R` (M22) (unless held at ``t`` with its drive at the bound,
        :attr:`~rollspring.simulate.run_state.RunState.held_at`), or turning against its
        resistance (:math:`\mathrm{spin}\,\omega < 0`, (M21))."""
        resisted = self.rolls & (self.arrays.rolling_resistance > 0)
        if not resisted.any():
            return False
        drive, limit = self._resistance_drive(state, slipping, sign)
        held = resisted & (self.spin == 0.0) & (self.held_at != t)
        turning = resisted & (self.spin != 0.0)
        omega = state[3 * self.n :]
        return bool(
            (held & (np.abs(drive) > limit)).any() or (turning & (self.spin * omega < 0.0)).any()
        )

    def _held_offsets(
        self,
        t: float,
        state: FloatArray,
        labels: list[tuple[str, int]],
        slipping: BoolArray,
        sign: FloatArray,
        spin: FloatArray,
    ) -> FloatArray:
        r"""Per event of ``labels``, the value its function is measured from in a segment that
        starts at ``t`` in ``state``: the release function :math:`C_{rr} N R - |D|` (M22) of a
        body held at ``t`` (:attr:`~rollspring.simulate.run_state.RunState.held_at`) where it
        is below zero, 0 for every other event. A body is held only at the bound (its rotation,
        set turning, turned back at once), so a value below zero there is rounding: of the
        terms of :math:`D`, which can be far larger than the bound (a constant force 10^6 times
        :math:`C_{rr} N`), so it is not bounded by a fraction of :math:`C_{rr} N R`. The
        crossing is then where :math:`|D|` exceeds the bound by that rounding."""
        offsets = np.zeros(len(labels))
        held = [
            j for j, (kind, i) in enumerate(labels) if kind == "release" and self.held_at[i] == t
        ]
        if not held:
            return offsets
        start = self._event_values(state[None, :], labels, slipping, sign, spin)[0]
        for j in held:
            if start[j] < 0.0:
                offsets[j] = start[j]
        return offsets

    def _event_values(
        self,
        states: FloatArray,
        labels: list[tuple[str, int]],
        slipping: BoolArray,
        sign: FloatArray,
        spin: FloatArray,
    ) -> FloatArray:
        r"""The general segment's event functions at rows of ``states`` (rows, 4n), one column
        per ``labels`` entry, the values its ``solve_ivp`` events take: ``slip``
        :math:`\mu_s N - |f|`, ``stick`` :math:`u - R\omega`, ``liftoff`` :math:`N`, ``turn``
        :math:`\mathrm{spin}\,\omega`, ``release`` :math:`C_{rr} N R - |D|` (M22)."""
        n = self.n
        states = np.ascontiguousarray(states)
        rows = states.shape[0]
        out = np.empty((rows, len(labels)))
        kinds = {kind for kind, _ in labels}
        friction = normal = drive = limit = np.empty((0, n))
        if kinds & {"slip", "liftoff"}:
            friction, normal, *_ = self.observe(
                states, np.tile(slipping, (rows, 1)), np.tile(sign, (rows, 1)), spin[None]
            )
        if "release" in kinds:
            drive, limit = np.empty((rows, n)), np.empty((rows, n))
            for r in range(rows):
                drive[r], limit[r] = self._resistance_drive(states[r], slipping, sign)
        a = self.arrays
        slip = slip_velocities(states, a.radius, n) if "stick" in kinds else states
        for column, (kind, i) in enumerate(labels):
            if kind == "slip":
                out[:, column] = a.mu_static[i] * normal[:, i] - np.abs(friction[:, i])
            elif kind == "stick":
                out[:, column] = slip[:, i]
            elif kind == "liftoff":
                out[:, column] = normal[:, i]
            elif kind == "turn":
                out[:, column] = spin[i] * states[:, 3 * n + i]
            else:
                out[:, column] = limit[:, i] - np.abs(drive[:, i])
        return out

    def _resting_spin(
        self, state: FloatArray, slipping: BoolArray, sign: FloatArray, i: int
    ) -> float:
        """The rolling resistance's direction for body ``i`` whose rotation is at rest in
        ``state``: 0 (held) while the drive is within :math:`C_{rr} N R` (M22), else the
        drive's sign (it turns that way)."""
        drive, limit = self._resistance_drive(state, slipping, sign)
        return 0.0 if abs(drive[i]) <= limit[i] else float(np.sign(drive[i]))

    def _resistance_events(
        self,
        t: float,
        state: FloatArray,
        slipping: BoolArray,
        sign: FloatArray,
        acceleration: FloatArray,
        trigger: tuple[str, int] | None = None,
    ) -> None:
        r"""Every resisted body's rolling resistance settled at an event at ``t`` (docs/physics.md
        (M22)): each whose rotation stops here -- the ``trigger`` of a ``turn`` event and every
        other turning body whose :math:`\mathrm{spin}\,\omega` has reached 0, or is within the
        integration's tolerance of it (``rtol`` times the body's largest :math:`|\omega|` so
        far) and falling (``acceleration``, :math:`\dot\omega` with the directions before the
        event) -- has its rotation, and a rolling body's centre, made exactly at rest and then
        rests (``rest``) while its own drive :math:`|D| \le C_{rr} N R`, else turns the way
        :math:`D` drives it; each resting body whose drive exceeds that bound (the trigger of a
        ``release`` event, or any other at the same instant) starts to turn its way
        (``release``). Bodies whose rotations stop at the same instant (two bodies released from
        rest in one normal mode reverse together) are all decided here, from their own drives:
        an event already past when another is handled could never be seen again. Events are
        recorded in the bodies' order. A ``hold`` trigger is a ``turn`` at the very start of a
        segment: a rotation set turning there that turned back against its resistance at once,
        its drive at the bound and not beyond it; it rests whatever its drive measures by
        rounding, and no body held so is released again at that instant
        (:attr:`~rollspring.simulate.run_state.RunState.held_at`)."""
        n, a = self.n, self.arrays
        spin = self.spin
        resisted = self.rolls & (a.rolling_resistance > 0)
        omega = state[3 * n :]
        heading = spin * omega  # > 0 while a turning body turns the way its resistance opposes
        tolerance = max(self.plan.rtol, 1e-13) * self.omega_peak
        stopping = (
            resisted
            & (spin != 0.0)
            & ((heading <= 0.0) | ((heading <= tolerance) & (spin * acceleration < 0.0)))
        )
        released = np.zeros(self.n, dtype=bool)
        if trigger is not None:
            kind, body = trigger
            if kind in ("turn", "hold"):
                stopping[body] = True
            else:
                released[body] = True
        for i in np.flatnonzero(stopping):  # at rest exactly, before any drive is measured
            state[3 * n + i] = 0.0
            if not slipping[i]:
                state[2 * n + i] = 0.0
        drive, limit = self._resistance_drive(state, slipping, sign)
        if trigger is not None and trigger[0] == "hold":
            self.held_at[trigger[1]] = t
        beyond = (np.abs(drive) > limit) & (self.held_at != t)
        for i in np.flatnonzero(resisted):
            if stopping[i]:
                spin[i] = float(np.sign(drive[i])) if beyond[i] else 0.0
                if spin[i] == 0.0:
                    self.events.append({"kind": "rest", "time": t, "body": a.ids[i]})
            elif spin[i] == 0.0 and (released[i] or beyond[i]):
                spin[i] = float(np.sign(drive[i])) or 1.0
                self.events.append({"kind": "release", "time": t, "body": a.ids[i]})

r"""The state of one run of :func:`rollspring.simulate` and what it records.

:class:`RunState` is built from the run's frozen :class:`~rollspring.simulate.setup.Plan` and
holds what the run accumulates: the output rows (general states :math:`[x, \varphi, u, \omega]`
at output times) with the forces and energies observed at them (:class:`Observed`), the
segments of the run with their interpolants (:class:`Segment`, for the extremes and the
period), the events, the status and the steps each integrator took. The two kinds of segment
step it on (:mod:`rollspring.simulate.rolling`, :mod:`rollspring.simulate.general`);
:meth:`RunState.trajectory` turns the records into the
:class:`~rollspring.simulate.trajectory.Trajectory`.
"""

from __future__ import annotations

import math
import time
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any, NamedTuple

import numpy as np
from numpy.typing import NDArray

from rollspring.model import System
from rollspring.physics import SystemArrays, springs_stay_level
from rollspring.physics.arrays import FloatArray
from rollspring.simulate import kernels
from rollspring.simulate.integrators import refinement_radius
from rollspring.simulate.kernels import SCHEMES
from rollspring.simulate.setup import Plan
from rollspring.simulate.status import RunStatus
from rollspring.simulate.trajectory import Trajectory

__all__ = [
    "NO_SAMPLES",
    "BoolArray",
    "Handover",
    "Observed",
    "RunState",
    "Segment",
    "Start",
    "general_state",
    "slip_rounding",
    "slip_velocities",
]

BoolArray = NDArray[np.bool_]
#: what a segment hands on: (t, general state, slipping, sign)
Handover = tuple[float, FloatArray, BoolArray, FloatArray]
#: a segment's times to look for extremes at: none (the kernel's extremes cover it)
NO_SAMPLES = np.empty(0)
#: a slip's |f|/N within this relative margin of mu_s is its limit reached (the root of
#: mu_s N - |f|, located to rounding); beyond it, a body that never rolled with it (at release)
_AT_THE_LIMIT = 1e-6
_TINY = float(np.finfo(float).tiny)
#: the roundings (:func:`slip_rounding`) a slip's v_s is set off 0 by (:meth:`RunState._slip_off`)
SLIP_OFF = 4


def _rows_of(values: np.ndarray, rows: int, dtype: type) -> np.ndarray:
    """``values`` (n,) repeated on ``rows`` rows, a new (rows, n) array (zeros without
    broadcasting when they are all zero, the usual case: NumPy broadcasts slowly over a last
    axis of a few bodies)."""
    values = np.asarray(values, dtype=dtype)
    if not values.any():
        return np.zeros((rows, values.shape[-1]), dtype=dtype)
    return np.broadcast_to(values, (rows, values.shape[-1])).copy()


class Observed(NamedTuple):
    """What the kernel observes at rows of states (see :func:`kernels.observe`)."""

    friction: FloatArray
    normal: FloatArray
    ratio: FloatArray
    length: FloatArray
    tension: FloatArray
    potential: FloatArray
    kinetic: FloatArray


class Start(NamedTuple):
    """A rolling state (q, v) at time t with what the kernel needs to step on from it (a
    tuple: a run makes a few of them for every segment)."""

    t: float
    q: FloatArray
    v: FloatArray
    model: tuple[Any, ...]
    coeffs: FloatArray
    h: float
    x0: FloatArray
    #: the bodies (ascending) whose states ``q``, ``v`` hold, when not every body's: the ball
    #: of an extreme's body in a large system (:func:`kernels.spring_balls`)
    ball: np.ndarray | None = None
    #: how far from ``t`` the rolling motion holds (at most the two steps a refinement looks
    #: at: less where the segment ends, at the run's end or an event)
    span: float = math.inf


@dataclass
class Segment:
    """A piece of the run with one integrator; ``evaluate(t)`` gives the general state."""

    t0: float
    t1: float
    slipping: np.ndarray
    sign: np.ndarray
    evaluate: Callable[[float | FloatArray], FloatArray]
    samples: FloatArray  # times inside the segment at which to look for extremes
    #: for a two-step segment around a kernel extreme: the state it starts from
    start: Start | None = None
    #: the rolling resistance's direction per body (:attr:`RunState.spin`), None without it
    spin: np.ndarray | None = None


def general_state(arrays: SystemArrays, q: FloatArray, v: FloatArray, x0: FloatArray) -> FloatArray:
    """[x, phi, u, omega] of an all-rolling state (q, qdot) with reference positions x0
    (rows of states for 2-D ``q``, ``v``)."""
    a, n = arrays, arrays.n_bodies
    q, v, x0 = (np.asarray(values, dtype=float) for values in (q, v, x0))
    if q.ndim == 1:
        return np.concatenate([x0 + a.scale * q, a.rolls * q, a.scale * v, a.rolls * v])
    # rows: computed as (4n, rows) and transposed once, as NumPy broadcasts slowly over a
    # last axis of a few bodies
    out = np.empty((4 * n, q.shape[0]))
    scale, rolls = a.scale[:, None], a.rolls[:, None]
    np.multiply(scale, q.T, out=out[:n])
    np.add(x0[:, None], out[:n], out=out[:n])
    np.multiply(rolls, q.T, out=out[n : 2 * n])
    np.multiply(scale, v.T, out=out[2 * n : 3 * n])
    np.multiply(rolls, v.T, out=out[3 * n :])
    states: FloatArray = out.T.copy()
    return states


def slip_velocities(states: FloatArray, radius: FloatArray, n: int) -> FloatArray:
    r"""The contact points' slip velocities :math:`v_s = u - R\omega` of general states
    :math:`[x, \varphi, u, \omega]` (one, or rows of them; given their derivatives, the rates
    :math:`\dot v_s`)."""
    result: FloatArray = states[..., 2 * n : 3 * n] - radius * states[..., 3 * n : 4 * n]
    return result


def slip_rounding(state: FloatArray, radius: FloatArray, n: int, body: int) -> float:
    r"""A rounding of body ``body``'s slip velocity in the general ``state``: one ulp of the
    larger of :math:`|u|` and :math:`|R\omega|` (the smallest normal float at rest)."""
    u, rolled = abs(state[2 * n + body]), abs(radius[body] * state[3 * n + body])
    return float(np.spacing(max(u, rolled, _TINY)))


class RunState:
    """The state of one run: what it recorded so far, its events and status (the segments of
    :mod:`rollspring.simulate.rolling` and :mod:`rollspring.simulate.general` step it on)."""

    def __init__(self, plan: Plan) -> None:
        self.plan = plan
        arrays = plan.arrays
        # the plan's fields read at every turn, by their short names
        self.arrays = arrays
        #: the kernel model of the initial placement: by name, and as the kernels take it
        self.model = plan.model
        self.packed = plan.packed
        self.grid = plan.grid
        n = arrays.n_bodies
        self.n = n
        #: the nominal step; ``h`` is the step actually taken (each rolling segment rounds the
        #: nominal step down so that whole steps land on the end)
        self.step = plan.step
        self.h = plan.step
        scheme = plan.scheme
        #: the stage weights of the symplectic scheme (Kahan-Li 8's in a DOP853 run)
        self.coeffs = SCHEMES[scheme][1] if scheme in SCHEMES else SCHEMES["kahanli8"][1]
        self.rows: list[FloatArray] = []  # general states at output times
        self.observed: list[Observed] = []  # forces, energies, ... at those rows
        #: every row recorded so far is a row of the grid, in order
        #: (:meth:`~rollspring.simulate.rolling.RollingSegments._record_rolling`)
        self.grid_rows = True
        #: :func:`kernels.row_extremes` of the last block
        #: :meth:`~rollspring.simulate.rolling.RollingSegments._record_rolling` recorded, as rows
        #: (ratio, its row, normal, its row)
        self.block_extremes: FloatArray | None = None
        self.central = np.ascontiguousarray(arrays.gamma * arrays.mass * arrays.radius**2)
        self.row_slipping: list[np.ndarray] = []
        self.row_sign: list[np.ndarray] = []
        #: per body with rolling resistance (docs/physics.md (M21), (M22)), the sign of the
        #: rotation it opposes, +1 or -1, or 0 while it holds the body at rest; 0 for every body
        #: without it. Only the general segments change it (a resisted run has no other).
        self.spin = np.zeros(n)
        #: per body the largest :math:`|\omega|` the general segments have seen so far: the
        #: scale of the tolerance within which a rotation is taken to stop at another body's
        #: event (:meth:`~rollspring.simulate.general.GeneralSegments._resistance_events`)
        self.omega_peak = np.zeros(n)
        #: per body the instant it was last held by its resistance because its rotation, set
        #: turning there, turned back against it at once (its drive at the bound, not beyond
        #: it): it is not released again at that instant on a drive past the bound by rounding
        #: (:meth:`~rollspring.simulate.general.GeneralSegments._resistance_events`)
        self.held_at = np.full(n, np.nan)
        self.times: list[FloatArray] = []
        self.segments: list[Segment] = []
        self.events: list[dict[str, Any]] = []
        self.status = RunStatus.FINISHED
        self.message = ""
        #: steps per integrator actually used, in order of first use
        self.steps_by_integrator: dict[str, int] = {}
        self.integrate_time = 0.0
        self.started = time.perf_counter()
        self.rolls = arrays.rolls > 0
        self.e0 = 0.0  # the energy at release (set when the run starts)
        self.energy_error = 0.0  # the relative energy error that ended the run, if one did
        self.e_segment = 0.0  # the energy at the start of the current rolling segment
        #: body -> mu_s: bodies that began to slip while rolling, where |f|/N reaches mu_s
        #: at the event's instant, exactly (the root of mu_s N - |f|): no step end or row need
        #: fall there, and a rise into the slip is the segment's highest |f|/N
        self.slip_ratios: dict[int, float] = {}
        #: (kind, body) -> per rolling segment (value, time, width, segment, key): the
        #: kernel's extremes over its steps, the value reached at a step end (the largest
        #: |f|/N, the smallest N) and the peak chosen by its key (run_fixed_step's docstring)
        #: with the two-step segment around it to refine it on
        self.step_extremes: dict[
            tuple[str, int], list[tuple[float, float, float, Segment | None, float]]
        ] = {}
        #: per rolling segment: (upward crossings of the mode signal, [first, last] segments)
        self.crossings: list[tuple[int, list[Segment]]] = []
        #: the release's general state until it is recorded (:meth:`_flush_pending`)
        self.pending: FloatArray | None = None
        self.release_forces = (np.zeros(self.n), np.zeros(self.n))
        #: a rolling segment's (slipping, sign): nobody slips (shared, never written)
        self.all_rolling = (np.zeros(self.n, dtype=bool), np.zeros(self.n))
        #: the normal forces cannot change (level centre springs, forces at centres)
        self.constant_normal = springs_stay_level(arrays)
        self._balls: tuple[np.ndarray, np.ndarray] | None = None
        self._links: tuple[np.ndarray, ...] | None = None

    def balls(self) -> tuple[np.ndarray, np.ndarray]:
        """(ball_ptr, ball_idx): per body the bodies whose states are kept with its extremes,
        CSR (:func:`kernels.run_fixed_step`): every body for a small system; for a large one
        those within :func:`~rollspring.simulate.integrators.refinement_radius` springs
        (:func:`kernels.spring_balls`), O(1) per body for a chain."""
        if self._balls is None:
            n = self.n
            if self.plan.windowed:
                radius = refinement_radius(len(self.coeffs))
                links = self.links()
                self._balls = kernels.spring_balls(
                    n, self.model.spring_ends, links[0], links[1], radius
                )
            else:
                ptr = np.arange(n + 1, dtype=np.int64) * n
                self._balls = (ptr, np.arange(n * n, dtype=np.int64) % n)  # n copies of 0..n-1
        return self._balls

    def links(self) -> tuple[np.ndarray, ...]:
        """:func:`kernels.body_links` of the model (each body's springs and forces)."""
        if self._links is None:
            self._links = tuple(
                kernels.body_links(self.n, self.model.spring_ends, self.model.force_body)
            )
        return self._links

    def general_state(self, q: FloatArray, v: FloatArray, x0: FloatArray) -> FloatArray:
        """:func:`general_state` of this run's system."""
        return general_state(self.arrays, q, v, x0)

    def rolling_state(self, state: FloatArray) -> tuple[FloatArray, FloatArray, FloatArray]:
        """(q, qdot, x0) of a general state in which every body rolls."""
        a, n = self.arrays, self.n
        x, phi, u = state[:n], state[n : 2 * n], state[2 * n : 3 * n]
        q = np.where(self.rolls, phi, x - a.x0)
        qdot = np.where(self.rolls, state[3 * n :], u)
        x0 = np.where(self.rolls, x - a.scale * phi, a.x0)
        return q, qdot, x0

    def _flush_pending(
        self, slipping: BoolArray | None = None, sign: FloatArray | None = None
    ) -> None:
        """Record the first output row (the release) if it is not recorded yet: every body
        rolling, or ``slipping`` those that slip from the release (with kinetic friction of
        the directions ``sign``), as the motion starts."""
        if self.pending is not None:
            state, self.pending = self.pending, None
            if slipping is None or sign is None:
                slipping, sign = np.zeros(self.n, dtype=bool), np.zeros(self.n)
            self._record(0.0, state, slipping, sign)

    def _release_before_the_end(
        self, t: float, state: FloatArray, slipping: BoolArray, sign: FloatArray
    ) -> None:
        """The release's row recorded (if it is not yet) before an event that ends the run at
        its first instant: with ``on_slip="continue"`` every rolling body beyond mu_s N there
        slips first (an event each), so that the row shows them slipping, as the motion
        would start, not rolling with a friction no floor gives."""
        if self.pending is not None and self.plan.on_slip == "continue":
            while (verdict := self._contact_verdict(state, slipping, slips_only=True)) is not None:
                self._event("slip", verdict[1], t, state, slipping, sign)
        self._flush_pending(slipping, sign)

    def _ends_run(self, kind: str) -> bool:
        """Whether a contact event of ``kind`` ends the run (a lift-off, or a slip with
        ``on_slip="stop"``): its state is then the last row, the release's recorded first."""
        return kind == "liftoff" or (kind == "slip" and self.plan.on_slip == "stop")

    def _record(
        self, t: float, state: FloatArray, slipping: BoolArray, sign: FloatArray
    ) -> Observed:
        return self._record_block(
            np.array([t]), np.asarray(state, dtype=float)[None, :], slipping, sign
        )

    def _record_block(
        self, times: FloatArray, states: FloatArray, slipping: BoolArray, sign: FloatArray
    ) -> Observed:
        """Keep output rows with everything observed at them; returns what was observed."""
        self.grid_rows = False
        rows = len(times)
        self.times.append(np.array(times, dtype=float))
        self.rows.append(np.array(states, dtype=float, order="C"))
        self.row_slipping.append(_rows_of(slipping, rows, bool))
        self.row_sign.append(_rows_of(sign, rows, float))
        observed = self.observe(
            self.rows[-1], self.row_slipping[-1], self.row_sign[-1], self.spin[None]
        )
        self.observed.append(observed)
        return observed

    def _energy(self, states: FloatArray, slipping: BoolArray, sign: FloatArray) -> FloatArray:
        observed = self.observe(states, slipping, sign)
        return observed.potential + observed.kinetic

    def observe(
        self,
        states: FloatArray,
        slipping: BoolArray,
        sign: FloatArray,
        spin: FloatArray | None = None,
    ) -> Observed:
        """:func:`kernels.observe` of rows of general states with, per row, the bodies
        slipping, their slip directions and the rolling resistance's directions (``spin``, as
        :attr:`spin`; none by default)."""
        rows = states.shape[0]
        if spin is None or not self.arrays.resisted:
            spin = np.zeros((rows, self.n))
        else:
            spin = np.broadcast_to(np.asarray(spin, dtype=float), (rows, self.n))
        ns = self.arrays.n_springs
        out = Observed(
            np.empty((rows, self.n)),
            np.empty((rows, self.n)),
            np.empty((rows, self.n)),
            np.empty((rows, ns)),
            np.empty((rows, ns)),
            np.empty(rows),
            np.empty(rows),
        )
        kernels.observe(
            self.packed,
            np.ascontiguousarray(states),
            np.asarray(slipping),
            np.asarray(sign, dtype=float),
            spin,
            self.plan.damped,
            out.friction,
            out.normal,
            out.length,
            out.tension,
            out.potential,
            self.central,
            out.ratio,
            out.kinetic,
        )
        return out

    def _contact_verdict(
        self,
        state: FloatArray,
        slipping: BoolArray,
        observed: Observed | None = None,
        *,
        slips_only: bool = False,
    ) -> tuple[str, int] | None:
        """('liftoff' | 'slip', body) if a rolling body violates its contact now, else None
        (``slips_only``: slips alone). ``observed``: the state observed already (with no slip
        direction)."""
        if observed is None:
            observed = self.observe(
                state[None, :], slipping[None], np.zeros((1, self.n)), self.spin[None]
            )
        friction, normal = observed.friction, observed.normal
        mu = self.arrays.mu_static
        for i in range(self.n):
            if normal[0, i] < 0 and not slips_only:
                return "liftoff", i
        for i in range(self.n):
            if (
                self.rolls[i]
                and not slipping[i]
                and math.isfinite(mu[i])  # (inf * a normal force of 0 would be NaN)
                and abs(friction[0, i]) > mu[i] * normal[0, i]
                and friction[0, i] != 0.0
                and not (slips_only and normal[0, i] < 0)  # (it lifts off)
            ):
                return "slip", i
        return None

    def _event(
        self,
        kind: str,
        body: int | np.integer[Any],
        t: float,
        state: FloatArray,
        slipping: BoolArray,
        sign: FloatArray,
    ) -> bool:
        """Record an event; returns True when the run ends here."""
        name = self.arrays.ids[body]
        self.events.append({"kind": kind, "time": t, "body": name})
        if kind == "slip":
            # |f|/N reached mu_s here (its event's root) where the body rolled up to it; not
            # where it is beyond it at once (at release): that body never rolled with it
            friction, normal, *_ = self.observe(
                state[None, :], slipping[None], sign[None], self.spin[None]
            )
            mu = float(self.arrays.mu_static[body])
            if abs(friction[0, body]) <= mu * normal[0, body] * (1.0 + _AT_THE_LIMIT):
                self.slip_ratios[int(body)] = mu
        if kind == "liftoff":
            self.status = RunStatus.LIFTOFF
            self.message = (
                f"'{name}' leaves its track at t = {t:.12g} s (N = 0); flight is "
                f"not modelled, the run ends here"
            )
            return True
        if kind == "slip" and self.plan.on_slip == "stop":
            self.status = RunStatus.SLIP
            self.message = (
                f"'{name}' starts to slip at t = {t:.12g} s (|f| = mu_s N); "
                f"the run ends here (on_slip='continue' runs on with kinetic "
                f"friction)"
            )
            return True
        if kind == "slip":
            slipping[body] = True
            # the kinetic friction takes the sign of the static friction that was needed
            sign[body] = -np.sign(friction[0, body]) or 1.0
            self._slip_off(state, int(body), float(sign[body]))
        return False

    def _slip_off(self, state: FloatArray, body: int, direction: float) -> None:
        r"""A body that starts to slip (or slips on) the way ``direction`` (+1, -1) at
        :math:`v_s = u - R\omega = 0`: its :math:`v_s` set a few ulps to that side, not at 0.
        Where mu_k = mu_s and the friction needed exceeds mu_s N only by a rounding, :math:`v_s`
        grows from 0 no faster than rounding moves it, and a stick event function starting at 0
        was found crossing again an ulp later, for ever (segments of 1e-15 s, or of no length).
        The state changes by :data:`SLIP_OFF` ulps of :math:`u`."""
        n, radius = self.n, self.arrays.radius
        state[2 * n + body] = radius[body] * state[3 * n + body] + direction * SLIP_OFF * (
            slip_rounding(state, radius, n, body)
        )

    def _report(self, t: float) -> None:
        if self.plan.progress is not None:
            self.plan.progress(min(1.0, t / self.grid[-1]))

    def _count_steps(self, integrator: str, taken: int) -> None:
        if taken > 0:
            self.steps_by_integrator[integrator] = (
                self.steps_by_integrator.get(integrator, 0) + taken
            )

    @property
    def n_steps(self) -> int:
        """The steps taken, every integrator's."""
        return sum(self.steps_by_integrator.values())

    @property
    def integrators_used(self) -> str:
        """The integrators that took steps, joined by "+" in order of first use (the chosen
        scheme when none took a step)."""
        return "+".join(self.steps_by_integrator) or self.plan.scheme

    @property
    def symplectic_step(self) -> float | None:
        """The symplectic step taken, None when no symplectic step was taken."""
        used = any(name != "dop853" for name in self.steps_by_integrator)
        return self.h if used or not self.steps_by_integrator else None

    def _violation(self, friction: FloatArray, normal: FloatArray) -> tuple[str, int] | None:
        mu = self.arrays.mu_static
        for i in range(self.n):
            if normal[i] < 0:
                return "liftoff", i
            if self.rolls[i] and abs(friction[i]) > mu[i] * normal[i]:
                return "slip", i
        return None

    def _energy_within(self, deviation: float) -> bool:
        """Whether the largest |E - E_segment| over the rows just recorded is within the
        energy tolerance (relative to the energy at release); sets the status if not."""
        scale = max(abs(self.e0), 1e-300)
        error = deviation / scale
        if not math.isfinite(error):
            self.status = RunStatus.NONFINITE
            self.message = "the energy became non-finite; the step cannot resolve the motion"
            return False
        if error > self.plan.tolerance and abs(self.e0) > 0:
            self.energy_error = error
            self.status = RunStatus.ENERGY_ERROR
            self.message = (
                f"the energy error {error:.3g} exceeds its tolerance "
                f"{self.plan.tolerance:.3g} (at t = {float(self.times[-1][-1]):.6g} s): "
                f"the step "
                f"does not resolve the motion; lower rtol or use a higher-order "
                f"integrator"
            )
            return False
        return True

    def trajectory(self, system: System) -> Trajectory:
        a, n = self.arrays, self.n
        times = self.times[0] if len(self.times) == 1 else np.concatenate(self.times)
        pick = None  # rows in time order, each time once (events can repeat a time)
        # rows of rolling segments alone are consecutive slices of the grid: in order already
        if not self.grid_rows and times.size > 1 and not (times[1:] > times[:-1]).all():
            order = np.argsort(times, kind="stable")
            keep = np.concatenate([[True], np.diff(times[order]) > 0])
            pick = order[keep]

        def column(parts: list[Any]) -> Any:
            joined = parts[0] if len(parts) == 1 else np.concatenate(parts)
            return joined if pick is None else joined[pick]

        times = times if pick is None else times[pick]
        states = column(self.rows)
        observed = {
            name: column([getattr(o, name) for o in self.observed]) for name in Observed._fields
        }
        kinetic, potential = observed["kinetic"], observed["potential"]
        x = states[:, :n]
        return Trajectory(
            system=system,
            ids=a.ids,
            spring_names=a.spring_names,
            t=times,
            x=x,
            phi=states[:, n : 2 * n],
            v=states[:, 2 * n : 3 * n],
            omega=states[:, 3 * n :],
            friction=observed["friction"],
            normal=observed["normal"],
            friction_ratio=observed["ratio"],
            slipping=column(self.row_slipping),
            spring_length=observed["length"],
            spring_tension=observed["tension"],
            kinetic=kinetic,
            potential=potential,
            energy=kinetic + potential,
            cm_x=x @ a.mass / np.sum(a.mass),
            stationary_x=None,
            status=self.status,
            message=self.message,
            integrator=self.integrators_used,
            step=self.symplectic_step,
            n_steps=self.n_steps,
            events=list(self.events),
            steps_by_integrator=dict(self.steps_by_integrator),
        )

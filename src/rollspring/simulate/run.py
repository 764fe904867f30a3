r"""``simulate``: the exact nonlinear motion, with every force, slip and lift-off to the instant.

While every body rolls and no spring is damped, the motion is integrated by an explicit
symplectic composition (:data:`~rollspring.simulate.kernels.SCHEMES`) compiled with Numba, with
a fixed step chosen from the highest linear frequency :math:`\omega` and ``rtol``: the relative
frequency error of an order-p scheme is :math:`C_p(\omega h)^p`, and the step keeps the phase
error over the run, :math:`\omega T C_p (\omega h)^p`, and the outputs within the accuracy
contract (:mod:`rollspring.simulate.integrators`, README "Accuracy"). Damped springs, a
slipping body (docs/physics.md (M19)), rolling resistance ((M21): the instants a resisted body
stops, turns back or is released located like a slip, (M22)) or ``integrator="dop853"`` use
SciPy's adaptive DOP853 on the general state :math:`[x, \varphi, u, \omega]`.

Events are found to the instant: after every step the friction each body needs and its normal
force are checked (:math:`|f_i| \ge \mu_s N_i` slip, :math:`N_i < 0` lift-off) and the crossing
is located by root-finding on the step itself (the integrator run with a shorter step is the
step's interpolant). Extremes of :math:`|f|/N` and :math:`N` are refined the same way, so they are
the continuous extremes over :math:`[0, T]`, not values at steps.

The pipeline, one module per step: the arguments checked once
(:mod:`~rollspring.simulate.request`), the cost estimated once
(:mod:`~rollspring.simulate.costs`), the frozen plan (:mod:`~rollspring.simulate.setup`), the
run (:class:`_Run`: its records in :mod:`~rollspring.simulate.run_state`, its segments in
:mod:`~rollspring.simulate.rolling` and :mod:`~rollspring.simulate.general`), then the
:class:`~rollspring.simulate.trajectory.Trajectory` and its summary
(:mod:`~rollspring.simulate.summary`, :mod:`~rollspring.simulate.extremes`).
"""

from __future__ import annotations

import dataclasses
import time
from collections.abc import Callable

import numpy as np

from rollspring.model import System
from rollspring.physics import system_arrays
from rollspring.simulate import arguments, setup
from rollspring.simulate.crossings import ROOT_TOLERANCE
from rollspring.simulate.general import GeneralSegments
from rollspring.simulate.integrators import INTEGRATORS as SCHEME_REGISTRY
from rollspring.simulate.request import INTEGRATORS, SimulationRequest, simulation_request
from rollspring.simulate.rolling import RollingSegments
from rollspring.simulate.status import RunStatus
from rollspring.simulate.summary import singular_springs, summary
from rollspring.simulate.trajectory import Trajectory

__all__ = ["INTEGRATORS", "run_request", "simulate"]

#: How many times a run whose energy error exceeds its tolerance is started again with a
#: smaller step, when the step is the contract's choice (not the caller's ``step``).
_ENERGY_RETRIES = 3


def simulate(
    system: arguments.SystemLike,
    duration: float,
    *,
    rtol: float = 1e-8,
    integrator: str = "auto",
    n_output: int | None = None,
    step: float | None = None,
    on_slip: str = "stop",
    energy_tolerance: float | None = None,
    progress: Callable[[float], None] | None = None,
    confirm: bool = False,
) -> Trajectory:
    r"""Integrate the exact nonlinear equations of ``system`` for ``duration`` seconds.

    :math:`J_i\ddot\varphi_i = Q_i(\varphi)` while every body rolls (docs/physics.md (M7)); a body
    whose needed friction exceeds :math:`\mu_s N` slips ((M19), with ``on_slip="continue"``;
    ``"stop"`` ends the run at that instant); lift-off (:math:`N < 0`) ends the run.
    ``rtol`` is an accuracy contract (README, "Accuracy"): while every body rolls and no spring
    is damped, every output position (``x``, ``phi``) and velocity (``v``, ``omega``) is within
    ``rtol * |value| + rtol / 10 * scale`` of the exact motion, ``scale`` being that quantity's
    largest ``|value|`` over the run (values passing near zero included). The step is chosen
    for it from the fastest linear frequency (at the placement and the equilibrium) with
    safety factors measured on random nonlinear systems (:mod:`rollspring.simulate.integrators`,
    ``bench/bench_accuracy.py``): checked there for 1e-10 <= rtol <= 1e-2 (much below, the
    rounding of double precision, a few 1e-13 of the scale, takes over), on motions whose
    stiffest local frequency stays within 1.5 times the linear one and that are not chaotic
    over the run. Damped and slipping stretches (DOP853) take ``rtol`` as SciPy's local
    tolerance. The energy error is checked against ``energy_tolerance`` (default
    ``100 rtol + 1e-12``): a run that exceeds it with the step the contract chose (a swing
    stiffer than its linear frequencies) is started again with the step its error asks for,
    up to three times (``summary["retries"]``); one that still exceeds it, or goes
    non-finite, stops with that status (naming a spring that passes through zero length).
    ``n_output`` output times, evenly spaced (default 2001), on step ends or interpolated
    inside the steps (septic Hermite), whichever takes fewer steps within the contract;
    ``step`` fixes the step of a symplectic scheme (``auto`` then means Yoshida-4; rounded down
    so that whole steps fill each rolling stretch); ``progress`` is called with the fraction
    done.

    ``system`` is a :class:`~rollspring.model.System`, its JSON form (a dict) or a file path or
    preset name. Every bad argument is a one-line :class:`~rollspring.errors.RollspringError`
    (the command line's message for the same mistake), raised before any work; ``rtol`` must lie
    within :data:`~rollspring.analysis.costs.RTOL_RANGE`. A run estimated at more than 5
    minutes or 2 GiB (:func:`~rollspring.simulate.costs.simulation_cost`) is refused with its
    estimate (:class:`~rollspring.errors.CostTooHigh`) unless ``confirm=True`` (``--yes`` on
    the command line); outputs that cannot fit in memory are refused even then.

    Parameters
    ----------
    system
        A :class:`~rollspring.model.System`, its JSON form, a file path or a preset name.
    duration
        The simulated time (s).
    rtol, integrator, step, energy_tolerance
        The accuracy contract, the scheme (``auto``, ``verlet``, ``yoshida4``, ``yoshida6``,
        ``kahanli8``, ``dop853``), a fixed step (s) and the energy error allowed.
    n_output
        The number of evenly spaced output times (default 2001).
    on_slip
        ``"stop"`` at the first slip, or ``"continue"`` with kinetic friction.
    progress, confirm
        Called with the fraction done; start even when the estimate is above the bound.

    Returns
    -------
    Trajectory
        Positions, velocities, friction and normal forces at the output times, the events,
        ``status`` and the ``summary``.
    """
    from rollspring.analysis.costs import CONFIRM, check_cost
    from rollspring.model import as_system
    from rollspring.simulate.costs import API_SMALLER, request_cost

    system = as_system(system)
    request = simulation_request(
        duration,
        rtol=rtol,
        integrator=integrator,
        on_slip=on_slip,
        n_output=n_output,
        energy_tolerance=energy_tolerance,
        step=step,
    )
    cost = request_cost(system, request, smaller=API_SMALLER)
    check_cost(cost, confirmed=arguments.check_flag("confirm", confirm), flag=CONFIRM)
    return run_request(system, request, arguments.check_callback("progress", progress))


def run_request(
    system: System,
    request: SimulationRequest,
    progress: Callable[[float], None] | None = None,
) -> Trajectory:
    """The run :func:`simulate` makes of a request whose arguments are checked already
    (:func:`~rollspring.simulate.request.simulation_request`), without estimating its cost (the
    caller's: :func:`simulate`, or an interface that checked it)."""
    clock = time.perf_counter()
    plan = setup.plan(system_arrays(system), request, progress)
    while True:
        run = _Run(plan)
        run.execute()
        if not (
            plan.chosen and run.status == RunStatus.ENERGY_ERROR and plan.retries < _ENERGY_RETRIES
        ):
            break
        # The motion is stiffer than its linear frequencies say (a large nonlinear swing):
        # the step chosen from them does not keep the energy. Run again with the step that
        # the error seen asks for (the energy error of an order-p scheme grows as h^p).
        assert plan.step is not None
        order = SCHEME_REGISTRY[plan.scheme].order
        tolerance = plan.tolerance
        shrink = min(0.5, 0.8 * (tolerance / max(run.energy_error, tolerance)) ** (1.0 / order))
        plan = dataclasses.replace(plan, step=plan.step * shrink, retries=plan.retries + 1)
    timings = {"setup": run.started - clock, "integrate": run.integrate_time}
    trajectory = run.trajectory(system)
    if run.status == RunStatus.ENERGY_ERROR:
        trajectory.message += singular_springs(trajectory)
    trajectory.summary = summary(trajectory, run)
    timings["total"] = time.perf_counter() - clock
    trajectory.timings = timings
    return trajectory


class _Run(RollingSegments, GeneralSegments):
    """One run: from the release, rolling (symplectic) and general (DOP853) segments in turn
    until the end, a lift-off or a slip that stops it."""

    def execute(self) -> None:
        """Run from the release to the end: a body beyond its friction limit at release slips
        from the start; then a rolling segment while every body rolls undamped, a general one
        otherwise, each handing its end state to the next, until the end or an event that
        ends the run."""
        a = self.arrays
        initial = (np.zeros(self.n), a.v0 / a.scale, a.x0)  # (q, qdot, x0) at release
        state = self.general_state(*initial)
        slipping = np.zeros(self.n, dtype=bool)
        sign = np.zeros(self.n)
        if a.resisted:  # each resisted body turns the way it moves, or rests, or is driven
            self.spin = np.where(a.rolling_resistance > 0, np.sign(a.v0), 0.0)
            for i in np.flatnonzero((a.rolling_resistance > 0) & (a.v0 == 0)):
                self.spin[i] = self._resting_spin(state, slipping, sign, int(i))
        observed = self.observe(state[None, :], slipping[None], sign[None], self.spin[None])
        # the first output row: recorded with the first rolling segment's rows (one block),
        # or on its own before anything else happens
        self.pending = state
        #: the release's friction and normal forces (the same numbers as the kernel's)
        self.release_forces = (observed.friction[0], observed.normal[0])
        self.e0 = observed.potential[0] + observed.kinetic[0]
        t = 0.0
        # segments of no length in a row before a run is stopped: each settles one body's
        # event (a rest, turn, release, stick, slip), so a few a body are all a run can need
        max_stalled = 16 + 8 * self.n
        # a body already beyond its friction limit at release slips from the start
        verdict = self._contact_verdict(state, slipping, observed)
        if verdict is not None:
            kind, body = verdict
            if self._ends_run(kind):  # else the release is recorded with it slipping
                self._release_before_the_end(0.0, state, slipping, sign)
            done = self._event(kind, body, 0.0, state, slipping, sign)
            if done:
                return
        stalled = 0  # segments in a row that ended where they started
        while t < self.grid[-1] and self.status == RunStatus.FINISHED:
            began = t
            if not (
                slipping.any() or self.plan.damped or a.resisted or self.plan.scheme == "dop853"
            ):
                if self.pending is not None:  # from the release: its state and energy known
                    t, state, slipping, sign = self._rolling_segment(t, state, self.e0, initial)
                else:
                    t, state, slipping, sign = self._rolling_segment(t, state)
            else:  # (which records the release once what slips from it is decided)
                t, state, slipping, sign = self._general_segment(t, state, slipping, sign)
            # (no length: shorter than the roots' tolerance tells apart; events that repeat
            # a rounding's width apart are no progress either)
            stalled = stalled + 1 if t - began <= 64 * ROOT_TOLERANCE * (1.0 + abs(began)) else 0
            if stalled > max_stalled:
                # each segment of no length settles a body's event for good, so a run that
                # keeps making them repeats its events: it is stopped, never left to hang
                recent = ", ".join(
                    f"{e['kind']} of {e['body']}" for e in self.events[-4:] if "body" in e
                )
                self.status = RunStatus.NONFINITE
                self.message = (
                    f"the events at t = {t:.17g} s repeat without the time advancing "
                    f"({stalled} segments of no length; the last: {recent or 'none'}): the "
                    "run cannot go on past them; a smaller rtol may resolve them"
                )
        self._flush_pending()

"""``simulate_batch`` and its result, :class:`BatchResult`."""

from __future__ import annotations

import contextlib
import math
import threading
import time
from collections.abc import Callable, Iterator, Mapping
from dataclasses import dataclass, field
from typing import Any

import numpy as np
from numpy.typing import ArrayLike

from rollspring.analysis.costs import CONFIRM, check_cost
from rollspring.errors import ModelError, SimulationError
from rollspring.model import System
from rollspring.physics.arrays import FloatArray
from rollspring.simulate import arguments
from rollspring.simulate.batch import cache
from rollspring.simulate.batch.codegen import BLOCK, OUT_BODY, OUT_EVENT_TIME, kernel_source
from rollspring.simulate.batch.parameters import count_runs, parse_parameters
from rollspring.simulate.batch.plan import (
    MAX_STEPS,
    Plan,
    batch_schedule,
    check_runs,
    make_plan,
    omega_limit,
    probe,
    run_omegas,
    steps_needed,
)
from rollspring.simulate.costs import batch_cost
from rollspring.simulate.integrators import INTEGRATORS as SCHEME_REGISTRY
from rollspring.simulate.status import Status

__all__ = ["INTEGRATORS", "BatchResult", "kernel_fields", "simulate_batch"]

#: Accepted values of ``integrator``.
INTEGRATORS = ("auto", *SCHEME_REGISTRY)


@dataclass
class BatchResult:
    r"""Per-run summary of a batch (arrays of length ``n_runs``; per body: ``(n_runs, n_bodies)``,
    columns in the order of ``ids``). SI units.

    * ``status`` (int8): the values of :class:`~rollspring.simulate.status.Status`:
      ``FINISHED`` (0: rolled throughout), ``SLIP`` (2) or ``LIFTOFF`` (3) (the run's first
      event), ``NONFINITE`` (1: the state overflowed, which overrides an earlier event),
      ``INVALID`` (5: its values overflow double precision; not integrated) or ``UNRESOLVED``
      (6: the run alone would need more than :data:`~rollspring.simulate.batch.plan.MAX_STEPS`
      steps at ``rtol``; left out of the step choice and not integrated); ``status_names``
      gives the names and ``messages`` says, per run, why a run was not integrated ("" for the
      others). The metrics of a run that was not integrated are NaN (``first_slip_body`` -1).
    * ``first_slip_time``, ``first_slip_body``: instant (s) and body index of the first slip
      or lift-off (whichever ``status`` says; the margin :math:`|f| - \mu_s N` or :math:`-N`
      interpolated linearly between steps); NaN and -1 if none. With ``stop_on_slip`` the run
      stops there and its metrics cover the motion up to the end of the step in which it
      happened (so ``max_friction_ratio`` may exceed :math:`\mu_s` and ``min_normal_force`` be
      negative by that step's overshoot); without, the run continues with rolling enforced.
    * ``period_measured``: mean interval between upward zero crossings of the rate of change of
      the first spring's length (the instants of its minima; for a single-mode motion the same
      as the upward crossings of the length through its mean), linearly interpolated between
      samples; NaN with fewer than two crossings or no spring.
    * ``cm_amplitude``: half of max - min of the centre-of-mass position
      :math:`X = \sum m_i x_i/\sum m_i` over the run.
    * ``stationary_amplitude``: the same for :math:`\hat X - \hat V t`,
      :math:`\hat X = \sum w_i x_i/\sum w_i`, :math:`w_i = (1+\gamma_i) m_i` (a slider: m), with
      its uniform motion :math:`\hat V = \sum w_i v_{i0}/\sum w_i` removed. Exactly stationary
      when every spring joins two centres and there are no anchors or forces (M11); for other
      systems it is this weighted mean, not the zero mode of (M14), unless
      ``stationary_weights`` gives the weights (what :func:`rollspring.sweep` does).
    * ``max_friction_ratio``: max over the samples of :math:`|f_i|/N_i` ((M8), (M9); 0 for a
      slider, inf if :math:`N_i` reached 0 with :math:`f_i \ne 0`); ``min_normal_force``: min
      :math:`N_i`.
    * ``energy_error``: max over the samples of :math:`|E - E_0|/|E_0|`,
      :math:`E = \sum \tfrac12 J_i\dot\varphi_i^2 + \sum\tfrac12 k(l-L_0)^2 - \sum F\cdot(P-P_0)`
      (0 if E stayed exactly at :math:`E_0 = 0`, inf if it left it).
    * ``final_x``, ``final_v``: centre positions and velocities at the end (for a run that
      stopped: at the end of the step in which it stopped).
    * ``t`` (n_output,) and ``x`` (n_runs, n_output, n_bodies) with ``keep_trajectories``:
      centre positions at evenly spaced times (NaN after a run stopped); otherwise None.

    ``parameters`` holds the broadcast parameter arrays; ``integrator``, ``step`` (s),
    ``n_steps`` and ``metric_every`` (steps between metric samples) describe the integration;
    ``omega_max`` is the highest linear frequency over the integrated runs (rad/s) the step was
    chosen for and ``omega`` each run's own (inf where not finite);
    ``timings`` (s): ``prepare`` (parameters, plan, step), ``compile`` (generating, compiling or
    loading the kernel), ``integrate``, ``total``. :meth:`columns`, :meth:`to_dict` and
    :meth:`summary_table` give flat, JSON and text views.
    """

    ids: tuple[str, ...]
    parameters: dict[str, FloatArray]
    duration: float
    integrator: str
    step: float
    n_steps: int
    metric_every: int
    omega_max: float
    status: np.ndarray
    first_slip_time: FloatArray
    first_slip_body: np.ndarray
    period_measured: FloatArray
    cm_amplitude: FloatArray
    stationary_amplitude: FloatArray
    max_friction_ratio: FloatArray
    min_normal_force: FloatArray
    energy_error: FloatArray
    final_x: FloatArray
    final_v: FloatArray
    t: FloatArray | None = None
    x: FloatArray | None = None
    timings: dict[str, float] = field(default_factory=dict)
    omega: FloatArray | None = None
    messages: np.ndarray | None = None

    @property
    def n_runs(self) -> int:
        """Number of runs."""
        return int(self.status.shape[0])

    @property
    def status_names(self) -> np.ndarray:
        """``status`` as names (:attr:`Status.label <rollspring.simulate.status.Status.label>`:
        ``finished``, ``slip``, ``liftoff``, ``nonfinite``, ``invalid``, ``unresolved``)."""
        names = np.array([s.label for s in Status], dtype=object)
        labels: np.ndarray = names[self.status]
        return labels

    def columns(self) -> dict[str, np.ndarray]:
        """Every per-run quantity as a flat column (per-body quantities as ``<id>.<name>``),
        parameters first; the rows are the runs."""
        out: dict[str, np.ndarray] = dict(self.parameters)
        out["status"] = self.status_names
        if self.messages is not None:
            out["message"] = self.messages
        out["first_slip_time"] = self.first_slip_time
        out["first_slip_body"] = np.array(
            [self.ids[b] if b >= 0 else "" for b in self.first_slip_body], dtype=object
        )
        out["period_measured"] = self.period_measured
        out["cm_amplitude"] = self.cm_amplitude
        out["stationary_amplitude"] = self.stationary_amplitude
        out["energy_error"] = self.energy_error
        for i, name in enumerate(self.ids):
            out[f"{name}.max_friction_ratio"] = self.max_friction_ratio[:, i]
            out[f"{name}.min_normal_force"] = self.min_normal_force[:, i]
            out[f"{name}.final_x"] = self.final_x[:, i]
            out[f"{name}.final_v"] = self.final_v[:, i]
        return out

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready form: the integration settings and every column as a list."""

        def plain(values: np.ndarray) -> list[Any]:
            """Numbers as floats/ints (None where not finite), names as strings."""
            if values.dtype.kind in "iu":
                return [int(v) for v in values]
            if values.dtype.kind == "f":
                return [float(v) if math.isfinite(v) else None for v in values]
            return [str(v) for v in values]

        return {
            "ids": list(self.ids),
            "n_runs": self.n_runs,
            "duration": self.duration,
            "integrator": self.integrator,
            "step": self.step,
            "n_steps": self.n_steps,
            "metric_every": self.metric_every,
            "omega_max": self.omega_max,
            "columns": {name: plain(np.asarray(values)) for name, values in self.columns().items()},
        }

    def summary_table(self, max_rows: int = 20) -> str:
        """A plain-text table of the first ``max_rows`` runs (parameters, status, period,
        amplitudes, friction ratios, energy error)."""
        cols = self.columns()
        keep = [
            *self.parameters,
            "status",
            "first_slip_time",
            "period_measured",
            "cm_amplitude",
            "stationary_amplitude",
            *(f"{i}.max_friction_ratio" for i in self.ids),
            "energy_error",
        ]
        rows = min(self.n_runs, max_rows)

        def cell(v: Any) -> str:
            return v if isinstance(v, str) else f"{v:.6g}"

        table = [keep] + [[cell(cols[k][r]) for k in keep] for r in range(rows)]
        widths = [max(len(row[c]) for row in table) for c in range(len(keep))]
        lines = ["  ".join(s.rjust(w) for s, w in zip(row, widths, strict=True)) for row in table]
        if rows < self.n_runs:
            lines.append(f"... {self.n_runs - rows} more runs")
        return "\n".join(lines)


def kernel_fields(
    plan: Plan, given: set[str] | None, included: np.ndarray, n_pad: int
) -> tuple[list[str], list[str], FloatArray, FloatArray]:
    """The fields the kernel reads per lane (``varying``: those the parameter keys change, see
    :func:`~rollspring.simulate.batch.plan.probe`) and once per block (``constant``), with
    their values: ``P`` (n_varying, n_pad) for the runs ``included`` (padded with the last)
    and ``C`` (n_constant,)."""
    n_live = included.size
    every = n_live == plan.scale.shape[0]  # every run included: ``included`` is 0, 1, ...
    live = {key: v if every else v[included] for key, v in plan.fields.items()}
    varying: list[str] = []
    constant: list[str] = []
    for key in sorted(live):
        values = live[key]
        per_run = given is None or key in given or bool(values.size and np.any(values != values[0]))
        (varying if per_run else constant).append(key)
    P = np.empty((len(varying), n_pad))
    for r, key in enumerate(varying):
        if n_live:
            P[r, :n_live] = live[key]
            P[r, n_live:] = live[key][-1]
    C = np.array([live[key][0] if n_live else 0.0 for key in constant], dtype=np.float64)
    return varying, constant, P, C


def simulate_batch(
    system: arguments.SystemLike,
    parameters: Mapping[str, ArrayLike],
    duration: float,
    *,
    rtol: float = 1e-8,
    integrator: str = "auto",
    step: float | None = None,
    keep_trajectories: bool = False,
    n_output: int = 201,
    stop_on_slip: bool = True,
    metric_every: int | None = None,
    confirm: bool = False,
    threads: int | None = None,
    on_stepping: Callable[[], None] | None = None,
    stationary_weights: ArrayLike | None = None,
) -> BatchResult:
    r"""Run ``system`` once per set of parameter values, all runs in parallel, for ``duration`` s.

    ``parameters`` maps paths to numbers or 1-D arrays, broadcast to one run count:
    ``"bodies.<id>.mass"``, ``.radius``, ``.mu_static``, ``.mu_kinetic``, ``.x`` (initial centre
    position), ``.v`` (initial centre velocity); ``"springs.<index>.stiffness"``,
    ``.rest_length`` (springs numbered in file order); ``"gravity"``. Every one may vary,
    radii included: a radius moves the centre height, the ``height`` attachments (their distance
    from the centre) and the inertia. A spring without a ``rest_length`` in the system keeps its
    default, the initial length, in every run. The topology (bodies, shapes, springs, anchors,
    attachments, forces) is the system's. Unknown paths, wrong lengths and values outside the
    range a system file takes (``rollspring.model.RANGES``) raise
    :class:`~rollspring.errors.ModelError` naming the key and the first run; damped springs are
    refused, and so is rolling resistance (``bodies.<id>.rolling_resistance`` > 0 in the system,
    or as a path: the batch integrators are symplectic: use :func:`rollspring.simulate`).
    ``system`` is a
    :class:`~rollspring.model.System`, its JSON form (a dict) or a file path or preset name
    (:func:`rollspring.model.as_system`).

    Each run starts at the system's placement (``phi = 0``) with its velocities and follows the
    rolling equations (M7) with an integrator of
    :data:`rollspring.simulate.integrators.INTEGRATORS` (``"verlet"``, ``"yoshida4"``,
    ``"yoshida6"``, ``"kahanli8"``); ``"auto"`` picks the cheapest for the accuracy. The step is
    common to all runs, chosen from the highest linear frequency over the runs :math:`\omega` so
    that the phase error :math:`C_p(\omega h)^p\,\omega T` is at most ``rtol``
    (:math:`\omega h\le 0.5`), and rounded so that ``duration`` is a whole number of steps;
    ``step`` fixes it instead (``auto`` then means Yoshida-4). Every step checks every run for
    slip (:math:`|f_i|\ge\mu_s N_i`) and lift-off (:math:`N_i < 0`); with ``stop_on_slip`` a
    run stops at its first event, without it the run continues with rolling enforced (the event
    is still reported). A run whose state overflows (a step far too long, a diverging system)
    ends with status ``nonfinite`` and meaningless metrics.

    **Runs are independent.** A run whose numbers still overflow double precision (a frequency
    or an inertia that is not finite) gets status ``invalid``; with the step chosen from ``rtol``, a
    run that alone would need more than :data:`~rollspring.simulate.batch.plan.MAX_STEPS` steps
    gets ``unresolved`` (``messages`` says which value and what range works). Neither is
    integrated nor takes part in the choice of the step. The summary metrics are sampled every
    ``metric_every`` steps (by default so that the fastest resolved mode turns by at most
    :data:`~rollspring.simulate.batch.plan.METRIC_PHASE` rad). Given the same ``step``,
    ``integrator`` and ``metric_every``, every run's result is bit for bit that of the same run
    alone: ``simulate_batch(system, {k: [v_i]}, T, step=r.step, integrator=r.integrator,
    metric_every=r.metric_every)`` equals row i of ``r`` (the kernel depends on the keys, never
    on the other runs' values), so a sweep can fix them once for a whole grid.

    ``keep_trajectories`` also returns the centre positions at ``n_output`` evenly spaced times
    (the number of steps is then rounded up to a multiple of ``n_output - 1``). Returns a
    :class:`BatchResult` of per-run metrics.

    The kernel is generated for the system, the set of parameter keys (not their values) and
    ``stop_on_slip``; the first call for a new combination compiles it (several seconds, see
    ``timings["compile"]``), later calls, in this process or another, load it from the cache
    (:mod:`rollspring.simulate.batch.cache`, ``ROLLSPRING_CACHE_DIR``).

    Example::

        system = rollspring.load_system("hoop-cylinder")
        k = np.linspace(50.0, 150.0, 100_000)
        result = simulate_batch(system, {"springs.0.stiffness": k,
                                         "bodies.hoop.mu_static": 0.04}, 10.0)
        result.period_measured, result.first_slip_time, result.status_names

    Parameters
    ----------
    system
        A :class:`~rollspring.model.System`, its JSON form, a file path or a preset name.
    parameters
        ``{path: value or 1-D array}``, broadcast to one count of runs.
    duration
        The simulated time of every run (s).
    rtol, integrator, step
        The accuracy, the scheme (``auto``, ``verlet``, ``yoshida4``, ``yoshida6``) and a fixed
        step (s) for the whole batch.
    keep_trajectories, n_output
        Keep every run's angles at ``n_output`` evenly spaced times.
    stop_on_slip, metric_every
        End a run at its first slip; sample the metrics every so many steps.
    confirm
        Start even when the estimate (:func:`~rollspring.simulate.costs.batch_cost`) is above
        the bound; at most :data:`~rollspring.simulate.costs.MAX_RUNS` runs either way.
    threads
        None: the runs on every Numba thread (``numba.get_num_threads()``); 1: on the calling
        thread alone, with the GIL released, so that several Python threads can each run a
        batch at once (what :func:`rollspring.sweep` does); k > 1: on k of Numba's threads.
        The numbers are the same bit for bit whatever the threads.
    stationary_weights
        None, or the weights :math:`w_i` of :math:`\hat X` per run ((n_runs, n_bodies), or
        (n_bodies,) for all): ``stationary_amplitude`` is then measured on
        :math:`\sum w_i x_i/\sum w_i` with its uniform motion removed, NaN for a run whose
        weights are not finite (no zero mode: walls). :func:`rollspring.sweep` passes those of
        (M14) (``analyze``'s ``stationary_weights``) for a system where they are not the
        (1 + gamma) m of (M11): springs off a centre, anchors, forces.
    on_stepping
        None, or a function called once, on the calling thread, when the runs are set up and
        the stepping starts (with ``threads=1`` the GIL is then released until the stepping
        ends; also called when no run is integrated): a caller running batches on several
        threads puts its own Python work there, where it does not hold up another batch's
        setup (what :func:`rollspring.sweep` does with its store's template).

    Returns
    -------
    BatchResult
        Per run: status, periods, extremes, friction needed, first slip and lift-off times.
    """
    from rollspring.model import as_system

    clock = time.perf_counter()
    system = as_system(system)
    duration = arguments.check_duration(duration)
    rtol = arguments.check_rtol(rtol)
    arguments.check_choice("integrator", integrator, INTEGRATORS, "integrator")
    step = arguments.check_step(step, duration)
    if step is not None and not duration / step <= MAX_STEPS:
        raise SimulationError(
            f"step: {step:g} s takes about {duration / step:.3g} steps over {duration:g} s; a "
            f"batch takes at most {MAX_STEPS:.0e} (a longer step, or a shorter duration)"
        )
    n_output = arguments.check_count("n_output", n_output, 2)
    metric_every = arguments.check_count("metric_every", metric_every, 1, optional=True)
    arguments.check_flag("keep_trajectories", keep_trajectories)
    arguments.check_flag("stop_on_slip", stop_on_slip)
    threads = _check_threads(threads)
    on_stepping = arguments.check_callback("on_stepping", on_stepping)
    damped = [k for k, s in enumerate(system.springs) if s.damping > 0]
    if damped:
        raise ModelError(
            f"springs[{damped[0]}].damping: batch runs need undamped springs "
            "(symplectic integrators); use rollspring.simulate"
        )
    resisted = [b.id for b in system.bodies if b.rolling_resistance > 0]
    if resisted:
        raise ModelError(
            f"bodies.{resisted[0]}.rolling_resistance: batch runs need bodies without rolling "
            "resistance (symplectic integrators, no stick events); use rollspring.simulate"
        )
    n_runs = count_runs(parameters)  # before any array of the runs' size is made
    cost = batch_cost(
        system,
        n_runs,
        duration,
        rtol=rtol,
        integrator=integrator,
        numbers_per_run=_numbers_per_run(system, n_output if keep_trajectories else 0),
        smaller="fewer runs, a shorter duration",
    )
    check_cost(cost, confirmed=arguments.check_flag("confirm", confirm), flag=CONFIRM)
    with np.errstate(all="ignore"):  # extreme values are found below, run by run
        runs = parse_parameters(system, parameters)
        topology, given = probe(system, runs.targets)
        plan = make_plan(system, runs, topology)
        no_stationary = _stationary_weights(plan, runs, stationary_weights)
        if stationary_weights is not None and given is not None:
            given = given | {f"xq_{i}" for i in range(plan.n)} | {"vhat"}
        omegas = run_omegas(plan)
        invalid, reasons = check_runs(plan, omegas)
    n_runs = runs.n_runs
    status = np.zeros(n_runs, dtype=np.int8)
    messages = np.array(reasons, dtype=object)
    status[invalid] = Status.INVALID

    def describe(run: int | np.integer) -> str:
        values = ", ".join(f"{key} = {float(v[run]):g}" for key, v in runs.parameters.items())
        return f"run {run}" + (f" ({values})" if values else "")

    for run in np.flatnonzero(invalid):
        messages[run] = (
            f"{describe(run)}: {reasons[run]}; its values overflow double "
            "precision (not integrated)"
        )
    if step is None:
        need = steps_needed(np.where(invalid, 0.0, omegas), duration, rtol, integrator)
        unresolved = ~invalid & (need > MAX_STEPS)
        if np.any(unresolved):
            limit = omega_limit(duration, rtol, integrator)
            for run in np.flatnonzero(unresolved):
                messages[run] = (
                    f"{describe(run)}: its linear frequency {float(omegas[run]):.4g} rad/s "
                    f"would need {float(need[run]):.3g} steps over {duration:g} s at rtol "
                    f"{rtol:g} (at most {MAX_STEPS:.0e}; frequencies up to {limit:.4g} rad/s "
                    "are resolved); not integrated, or pass step= to force it"
                )
            status[unresolved] = Status.UNRESOLVED
    included = np.flatnonzero(status == 0)
    omega, name, n_steps, every = batch_schedule(
        omegas[included],
        duration,
        rtol,
        integrator,
        step,
        metric_every,
        multiple=n_output - 1 if keep_trajectories else 1,
    )
    h = duration / n_steps
    weights = SCHEME_REGISTRY[name].weights
    drift = weights * h
    kick = np.append(0.5 * (weights[:-1] + weights[1:]) * h, 0.5 * weights[-1] * h)

    n = plan.n
    n_live = included.size
    n_blocks = -(-n_live // BLOCK)
    n_pad = n_blocks * BLOCK
    varying, constant, P, C = kernel_fields(plan, given, included, n_pad)
    source = kernel_source(plan, varying, constant, bool(stop_on_slip)) if n_live else ""
    prepared = time.perf_counter()

    out_live = np.full((n_pad, OUT_BODY + 5 * n), np.nan)
    outi_live = np.zeros((n_pad, 2), dtype=np.int64)
    outi_live[:, 1] = -1
    stride = n_steps // (n_output - 1) if keep_trajectories else 0
    traj_live = np.full((n_pad, n_output, n) if keep_trajectories else (1, 1, 1), np.nan)
    if n_live:
        kernel = cache.load_kernel(source, serial=threads == 1)
        args = (
            n_blocks,
            P,
            C,
            drift,
            kick,
            h,
            n_steps,
            every,
            stride,
            traj_live,
            out_live,
            outi_live,
        )
        if not kernel.signatures:
            import numba

            # numba.typeof has no annotations in numba's own typing
            kernel.compile(tuple(numba.typeof(a) for a in args))  # type: ignore[no-untyped-call]
        compiled = time.perf_counter()
        if on_stepping is not None:
            on_stepping()
        if threads == 1:
            kernel(*args)
        else:
            with _numba_threads(threads):
                kernel(*args)
    else:
        compiled = time.perf_counter()
        if on_stepping is not None:
            on_stepping()
    finished = time.perf_counter()

    out = np.full((n_runs, OUT_BODY + 5 * n), np.nan)
    out[included] = out_live[:n_live]
    outi = np.zeros((n_runs, 2), dtype=np.int64)
    outi[:, 1] = -1
    outi[included] = outi_live[:n_live]
    status[included] = outi[included, 0]
    with np.errstate(all="ignore"):
        count = out[:, 9]
        period = np.where(count >= 2, (out[:, 8] - out[:, 7]) / np.maximum(count - 1, 1), np.nan)
        e0, de = np.abs(out[:, 1]), out[:, 2]
        energy_error = np.where(
            e0 > 0, de / np.where(e0 > 0, e0, 1.0), np.where(de == 0, 0.0, np.inf)
        )
        energy_error = np.where(np.isnan(de), np.nan, energy_error)
        fb = out[:, OUT_BODY::5][:, :n]
        nb = out[:, OUT_BODY + 1 :: 5][:, :n]
        ratio = np.where(fb == 0, 0.0, np.where(nb > 0, fb / np.where(nb > 0, nb, 1.0), np.inf))
        ratio = np.where(np.isnan(fb) | np.isnan(nb), np.nan, ratio)
        ratio[np.ix_(included, ~np.array(plan.rolls))] = 0.0
        cm_amplitude = 0.5 * (out[:, 4] - out[:, 3])
        stationary_amplitude = 0.5 * (out[:, 6] - out[:, 5])
        stationary_amplitude[no_stationary] = np.nan
    if keep_trajectories:
        traj = np.full((n_runs, n_output, n), np.nan)
        traj[included] = traj_live[:n_live]
    t_out = np.linspace(0.0, duration, n_output) if keep_trajectories else None
    return BatchResult(
        ids=tuple(b.id for b in system.bodies),
        parameters=runs.parameters,
        duration=duration,
        integrator=name,
        step=h,
        n_steps=n_steps,
        metric_every=every,
        omega_max=omega,
        status=status,
        first_slip_time=out[:, OUT_EVENT_TIME].copy(),
        first_slip_body=outi[:, 1].copy(),
        period_measured=period,
        cm_amplitude=cm_amplitude,
        stationary_amplitude=stationary_amplitude,
        max_friction_ratio=ratio,
        min_normal_force=out[:, OUT_BODY + 2 :: 5][:, :n].copy(),
        energy_error=energy_error,
        final_x=out[:, OUT_BODY + 3 :: 5][:, :n].copy(),
        final_v=out[:, OUT_BODY + 4 :: 5][:, :n].copy(),
        t=t_out,
        x=traj if keep_trajectories else None,
        timings={
            "prepare": prepared - clock,
            "compile": compiled - prepared,
            "integrate": finished - compiled,
            "total": time.perf_counter() - clock,
        },
        omega=omegas,
        messages=messages,
    )


def _stationary_weights(plan: Plan, runs: Any, weights: ArrayLike | None) -> np.ndarray:
    r"""The plan's :math:`\hat X` weights (``xq_i``) and its uniform velocity (``vhat``) from
    the ``weights`` given per run (normalised to a sum of 1); returns the mask of the runs
    whose weights are not finite (their X-hat fields 0, their amplitude NaN). Without
    ``weights``, the plan's (1 + gamma) m (M11) stay and no run is masked."""
    n_runs, n = runs.n_runs, plan.n
    if weights is None:
        return np.zeros(n_runs, dtype=bool)
    try:
        given = np.asarray(weights)
        if given.dtype.kind not in "iuf" or given.shape not in ((n,), (n_runs, n)):
            raise TypeError  # a bool, a string or an object is not a weight; one per body
        w = np.broadcast_to(given.astype(np.float64), (n_runs, n))
    except (TypeError, ValueError):
        raise ModelError(
            f"stationary_weights: expected numbers of shape ({n_runs}, {n}) or ({n},), got "
            f"{np.shape(weights)}"
        ) from None
    total = w.sum(axis=1)
    bad: np.ndarray = ~(np.all(np.isfinite(w), axis=1) & np.isfinite(total) & (total != 0))
    normal = np.where(bad[:, None], 0.0, w / np.where(bad, 1.0, total)[:, None])
    for i in range(n):
        plan.fields[f"xq_{i}"] = np.ascontiguousarray(normal[:, i])
    plan.fields["vhat"] = np.sum(normal * runs.v, axis=1)
    return bad


#: One launch of a parallel kernel at a time in this process: Numba's default threading layer
#: (workqueue) aborts the process when two Python threads launch parallel kernels at once, and
#: the kernels release the GIL, which no longer keeps them apart.
_PARALLEL = threading.Lock()


def _check_threads(threads: Any) -> int | None:
    """None, or a whole number from 1 to Numba's thread count (``NUMBA_NUM_THREADS``)."""
    count = arguments.check_count("threads", threads, 1, optional=True)
    if count is not None and count > 1:
        import numba

        # numba.config sets NUMBA_NUM_THREADS at import: mypy cannot see it
        limit = int(numba.config.NUMBA_NUM_THREADS)  # type: ignore[attr-defined]
        if count > limit:
            raise SimulationError(
                f"threads: {count} is more than Numba's {limit} threads (NUMBA_NUM_THREADS)"
            )
    return count


@contextlib.contextmanager
def _numba_threads(threads: int | None) -> Iterator[None]:
    """Hold the launch lock and, for ``threads`` k, run on k of Numba's threads (Numba's
    count is per calling thread; restored after)."""
    with _PARALLEL:
        if threads is None:
            yield
            return
        import numba

        before = numba.get_num_threads()
        numba.set_num_threads(threads)
        try:
            yield
        finally:
            numba.set_num_threads(before)


def _numbers_per_run(system: System, n_output: int) -> int:
    """The numbers a run of a batch keeps: its parameters, metrics and status (about 12 per
    body, 4 per spring), and ``n_output`` rows of 4 per body with trajectories."""
    bodies, springs = len(system.bodies), len(system.springs)
    return 16 + 12 * bodies + 4 * springs + n_output * 4 * bodies

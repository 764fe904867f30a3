r"""One chunk of a sweep: a pure function of (the sweep's plan, the chunk's index) -> arrays.

:func:`compute_chunk` is what runs in-process or as a task on a Dask worker; it reads nothing
but its arguments and writes nothing, so the result of a chunk does not depend on where, when or
next to which other chunks it runs.

* **The simulated metrics** come from :func:`rollspring.simulate_batch` with the plan's one
  integrator, step and metric sampling for the whole grid (``integrator=``, ``step=``,
  ``metric_every=``): with those given, every run's numbers are those it has alone (runs are
  independent in a batch), so a chunk's arrays do not depend on which runs share its call.
  Only the varied numbers travel per run.
* **The first slip / lift-off instant**: the batch interpolates the contact margin linearly
  between steps (error about :math:`c\,h^2`); with ``refine_slip`` every run that slipped or
  lifted off is run again alone by :func:`rollspring.simulate` (``on_slip="stop"``, which
  root-finds the instant on the step), and its instant and body are stored.
* **``on_slip="continue"``**: the batch cannot go on after a slip with kinetic friction, so
  every run goes through :func:`rollspring.simulate` (``on_slip="continue"``), one by one.
* **The linear metrics** (``omega``, ``stationary_weight``, ``required_mu_linear``) are those
  of :func:`rollspring.analyze` of each run's starting system: computed for all the runs of a
  call at once by :func:`rollspring.analysis.batch_linear` (once per distinct linear
  configuration, the friction coefficients left out; to 1e-12 of ``analyze``) for the runs of
  its flat centre class, and by ``analyze`` run by run (once per distinct configuration) for
  the others (off-centre attachments, tilted springs, mode amplitudes, no equilibrium, ...).
  When no varied value moves a spring end (every run's start is then a valid system) they are
  computed in a thread while the batch runs, if a core is to spare (``linear_aside``: not in an
  in-process pool with a thread a core, where they are computed by the pool's thread itself).
* **Several chunks in one call** (:func:`compute_chunks`, in-process): their runs are
  concatenated into one batch call and split again; every run's numbers are those it has alone,
  so each chunk's arrays equal :func:`compute_chunk`'s.
* **The step of the grid** (:func:`grid_omega`): the batch's per-run linear frequencies
  (``run_omegas``, the functions :func:`simulate_batch` uses) on the grid with its velocity and
  friction axes collapsed (they do not enter them), read chunk by chunk as the pass of
  :func:`plan_omega` over the chunks would, without a batch call per chunk.
"""

from __future__ import annotations

import contextlib
import copy
import functools
import json
import math
import os
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np

from rollspring.analysis import LinearAnalysis, analyze, batch_linear
from rollspring.errors import RollspringError
from rollspring.model import System, rolled, system_from_dict
from rollspring.physics import pseudo_momentum_conserved, system_arrays
from rollspring.service.sweeps.grid import Grid, apply_values, path_kind
from rollspring.simulate import simulate, simulate_batch
from rollspring.simulate.batch.plan import distinct_rows
from rollspring.simulate.status import Status

__all__ = [
    "STATUS_CODES",
    "SweepPlan",
    "batch_omegas",
    "compute_chunk",
    "compute_chunks",
    "grid_omega",
    "plan_omega",
    "prepare_worker",
]

#: Status name -> code (:class:`rollspring.simulate.status.Status`; the store's
#: ``flag_values`` / ``flag_meanings``).
STATUS_CODES = {status.label: int(status) for status in Status}

#: Duration and step of the one-step calls that only read the batch's highest frequency.
_TINY = 1e-9


@dataclass(frozen=True)
class SweepPlan:
    """Everything a chunk needs (picklable; the system travels as its JSON form)."""

    system: dict[str, Any]
    grid: Grid
    duration: float
    rtol: float
    on_slip: str
    metrics: tuple[str, ...]
    refine_slip: bool
    integrator: str = "auto"  # the user's; ``scheme`` is the one chosen for the grid
    scheme: str = ""
    step: float = 0.0
    metric_every: int = 0
    omega_max: float = 0.0
    numba_threads: int = 0  # 0: leave Numba's thread count alone
    #: the batch calls' ``threads``: None every Numba thread (a Dask worker), 1 the calling
    #: thread with the GIL released (the in-process pool; the same numbers bit for bit)
    batch_threads: int | None = None
    #: the linear metrics computed in a thread of their own while the batch runs (a core to
    #: spare: a Dask worker's batch, an in-process pool with fewer threads than cores), else
    #: in the calling thread (the pool's threads already keep every core busy)
    linear_aside: bool = True


@functools.lru_cache(maxsize=8)
def _system_of(text: str) -> System:
    return system_from_dict(json.loads(text))


def plan_system(plan: SweepPlan) -> System:
    return _system_of(json.dumps(plan.system, sort_keys=True))


# --------------------------------------------------------------------------------------------
# per-run systems


_MU = ("mu_static", "mu_kinetic")


class _Runs:
    """The runs of one chunk: their values, starting systems and linear analyses (cached per
    distinct linear configuration)."""

    def __init__(self, plan: SweepPlan, indices: int | list[int]) -> None:
        self.plan = plan
        self.system = plan_system(plan)
        indices = [indices] if isinstance(indices, int) else list(indices)
        parts = [plan.grid.chunk_values(i) for i in indices]
        self.locals = [local for local, _ in parts]
        if len(parts) == 1:
            self.values = parts[0][1]
        else:  # several chunks in one call: their runs one after the other
            self.values = {
                p: np.concatenate([values[p] for _, values in parts]) for p in plan.grid.paths
            }
        self.n = sum(int(np.prod(local)) for local in self.locals)
        self.kinds = {p: path_kind(self.system, p) for p in plan.grid.paths}
        self.structural = any(k != "batch" for k, _ in self.kinds.values())
        self._starts: dict[tuple[float, ...], tuple[System | None, Any, str]] = {}

    def linear_key(self, r: int) -> tuple[float, ...]:
        return tuple(
            float(self.values[p][r]) for p in self.plan.grid.paths if p.split(".")[-1] not in _MU
        )

    def start(self, r: int, *, linear: bool) -> tuple[System | None, Any, str]:
        """(starting system without the varied friction coefficients, its analysis or None,
        problem or '') of run ``r``."""
        key = self.linear_key(r)
        cached = self._starts.get(key)
        if cached is not None and (cached[1] is not None or not linear or cached[0] is None):
            return cached
        scalars = {
            p: self.values[p][r]
            for p in self.plan.grid.paths
            if self.kinds[p][0] != "mode" and p.split(".")[-1] not in _MU
        }
        modes = {
            self.kinds[p][1][0]: float(self.values[p][r])
            for p in self.plan.grid.paths
            if self.kinds[p][0] == "mode"
        }
        try:
            system = apply_values(self.plan.system, self.system, scalars)
            if modes:
                analysis = analyze(system, confirm=True)
                if not analysis.equilibrium.found:
                    raise RollspringError(f"no equilibrium: {analysis.equilibrium.reason}")
                q = analysis.equilibrium.q.copy()
                for n, amplitude in modes.items():
                    mode = analysis.modes[n]
                    if mode.kind != "oscillating":
                        raise RollspringError(f"mode {n} is a {mode.kind} mode")
                    q = q + amplitude * mode.shape_q
                system = rolled(system, q, velocities=np.zeros(len(system.bodies)))
            result: tuple[System | None, LinearAnalysis | None, str] = (
                system,
                analyze(system, confirm=True) if linear else None,
                "",
            )
        except RollspringError as exc:
            result = (None, None, str(exc))
        except (ValueError, ArithmeticError, np.linalg.LinAlgError) as exc:
            result = (None, None, f"{type(exc).__name__}: {exc}")
        self._starts[key] = result
        return result

    def run_system(self, r: int) -> System | None:
        """Run ``r``'s full system (start placement and its friction coefficients)."""
        system, _, _ = self.start(r, linear=False)
        if system is None:
            return None
        mu = {p: self.values[p][r] for p in self.plan.grid.paths if p.split(".")[-1] in _MU}
        if not mu:
            return system
        from rollspring.model import system_to_json

        try:
            return apply_values(system_to_json(system), system, mu)
        except RollspringError:
            return None


# --------------------------------------------------------------------------------------------
# batch calls


_BODY_FIELDS = ("mass", "radius", "mu_static", "x", "v")


def _full_parameters(system: System, varied: set[str]) -> list[str]:
    """Every scalar batch path of ``system`` (for structural sweeps, where each run's system
    is one of several): all bodies' and springs' numbers and gravity (``mu_kinetic`` only
    when varied: its default follows ``mu_static``)."""
    keys = [f"bodies.{b.id}.{q}" for b in system.bodies for q in _BODY_FIELDS]
    keys += [
        f"bodies.{b.id}.mu_kinetic" for b in system.bodies if f"bodies.{b.id}.mu_kinetic" in varied
    ]
    keys += [
        f"springs.{k}.{q}" for k in range(len(system.springs)) for q in ("stiffness", "rest_length")
    ]
    return [*keys, "gravity"]


def _value_of(system: System, key: str) -> float:
    parts = key.split(".")
    if parts[0] == "gravity":
        return float(system.gravity)
    if parts[0] == "bodies":
        body = system.body_map[parts[1]]
        value = getattr(body, parts[2])
        if value is None:  # mu_kinetic default
            return float(body.mu_static) if math.isfinite(body.mu_static) else 0.0
        return float(value)
    k = int(parts[1])
    if parts[2] == "rest_length":
        return float(system.rest_lengths[k])
    return float(getattr(system.springs[k], parts[2]))


def _structure_key(system: System, keys: list[str]) -> str:
    """The system with every number given per run removed: runs with equal keys share a
    batch call."""
    from rollspring.model import system_to_json

    data = system_to_json(system)
    for key in keys:
        parts = key.split(".")
        if parts[0] == "gravity":
            data.pop("gravity", None)
        elif parts[0] == "bodies":
            for body in data["bodies"]:
                if body["id"] == parts[1]:
                    body.pop(parts[2], None)
        else:
            data["springs"][int(parts[1])].pop(parts[2], None)
    return json.dumps(data, sort_keys=True, default=str)


def _batch(
    plan: SweepPlan,
    system: System,
    params: dict[str, np.ndarray],
    *,
    duration: float,
    step: float,
    scheme: str,
    metric_every: int,
    stepping: Callable[[], None] | None = None,
    stationary_weights: np.ndarray | None = None,
) -> Any:
    """One :func:`simulate_batch` call with the grid's integrator, step and metric sampling
    (all fixed by the plan, so no run's numbers depend on the other runs of the call);
    ``stepping``: its ``on_stepping``."""
    return simulate_batch(
        system,
        params,
        duration,
        rtol=plan.rtol,
        integrator=scheme,
        step=step,
        metric_every=metric_every,
        stop_on_slip=True,
        threads=plan.batch_threads,
        confirm=True,  # the sweep's cost is checked once, for the whole grid
        on_stepping=stepping,
        stationary_weights=stationary_weights,
    )


def _groups(
    runs: _Runs, alive: np.ndarray
) -> list[tuple[System, np.ndarray, dict[str, np.ndarray]]]:
    """The batch calls of a chunk: (system, run indices, parameters)."""
    plan, system = runs.plan, runs.system
    if not runs.structural:
        # only the varied numbers per run (at least one: a batch's run count is its arrays')
        keys = list(plan.grid.paths) or [f"bodies.{system.bodies[0].id}.mass"]
        idx = np.flatnonzero(alive)
        params = {}
        for key in keys:
            if key in runs.values:
                params[key] = np.asarray(runs.values[key][idx], dtype=np.float64)
            else:
                params[key] = np.full(idx.size, _value_of(system, key))
        return [(system, idx, params)] if idx.size else []
    keys = _full_parameters(system, set(plan.grid.paths))
    by_key: dict[str, tuple[System, list[int]]] = {}
    for r in np.flatnonzero(alive):
        run_system = runs.run_system(int(r))
        if run_system is None:
            continue
        key = _structure_key(run_system, keys)
        by_key.setdefault(key, (run_system, []))[1].append(int(r))
    out = []
    for group_system, members in by_key.values():
        systems: list[System] = []
        for member in members:
            member_system = runs.run_system(member)
            assert member_system is not None  # grouped above: every member has its system
            systems.append(member_system)
        params = {key: np.array([_value_of(s, key) for s in systems]) for key in keys}
        out.append((group_system, np.array(members, dtype=np.int64), params))
    return out


def plan_omega(plan: SweepPlan, index: int) -> tuple[float, Any]:
    """The highest linear frequency the batch sees among the runs of chunk ``index`` (its
    initial placements), and a (system, parameters) of one run of that group, for the step of
    the whole grid."""
    runs = _Runs(plan, index)
    best: tuple[float, Any] = (0.0, None)
    alive = np.ones(runs.n, dtype=bool)
    for system, _, params in _groups(runs, alive):
        try:
            omega = simulate_batch(
                system, params, _TINY, step=_TINY, integrator="yoshida4", stop_on_slip=True
            ).omega_max
        except RollspringError:
            omega = 0.0
            for r in range(next(iter(params.values())).size):
                one = {k: v[r : r + 1] for k, v in params.items()}
                try:
                    value = simulate_batch(
                        system, one, _TINY, step=_TINY, integrator="yoshida4", stop_on_slip=True
                    ).omega_max
                except RollspringError:
                    continue
                if value > omega:
                    omega = value
        if omega > best[0] or best[1] is None:
            best = (omega, (system, {k: v[:1] for k, v in params.items()}))
    return best


#: Body quantities that do not enter the batch's linear frequencies (``run_omegas``: the
#: stiffness at the initial placement and the inertias), only fields that stay finite for
#: moderate values.
_NO_OMEGA = ("mu_static", "mu_kinetic", "v")
#: "Moderate": the grid's velocities and every mass within this magnitude.
_MODERATE = 1e100
#: Runs per call of the planning shortcut.
_PLAN_BLOCK = 1 << 16


def batch_omegas(system: System, params: dict[str, np.ndarray]) -> np.ndarray:
    """Each run's linear frequency as :func:`simulate_batch` computes it before integrating
    (the same functions in the same order), -inf for a run it would not integrate
    (``invalid``); its ``omega_max`` with ``step`` given is the largest of these (0 if none)."""
    from rollspring.simulate.batch.parameters import parse_parameters
    from rollspring.simulate.batch.plan import check_runs, make_plan, probe, run_omegas

    with np.errstate(all="ignore"):
        runs = parse_parameters(system, params)
        topology, _ = probe(system, runs.targets)
        batch_plan = make_plan(system, runs, topology)
        omegas = run_omegas(batch_plan)
        invalid, _ = check_runs(batch_plan, omegas)
    return np.where(invalid, -np.inf, omegas)


def grid_omega(plan: SweepPlan) -> tuple[float, Any] | None:
    """What the planning pass over the chunks (:func:`plan_omega` of each chunk, the first
    chunk of the largest ``omega`` kept) finds, ``(omega, sample)``, without a batch call per
    chunk: the batch's per-run frequencies are computed once on the grid with the axes of
    velocities and friction coefficients collapsed to their first value (they do not enter
    them), and each chunk's maximum and first run read from that. None where this shortcut
    does not apply (structural PATHs, extreme values, a batch refusing a run): then the pass
    over the chunks decides."""
    system = plan_system(plan)
    grid = plan.grid
    kinds = [path_kind(system, p)[0] for p in grid.paths]
    if any(kind != "batch" for kind in kinds):
        return None
    collapse = [p.startswith("bodies.") and p.split(".")[-1] in _NO_OMEGA for p in grid.paths]
    masses = [b.mass for b in system.bodies]
    for p, values in zip(grid.paths, grid.values, strict=True):
        quantity = p.split(".")[-1]
        if quantity in ("v", "mass"):
            masses_or_v = np.asarray(values)
            if np.any(np.abs(masses_or_v) > _MODERATE):
                return None
    if max(masses) > _MODERATE:
        return None
    keys = list(grid.paths) or [f"bodies.{system.bodies[0].id}.mass"]  # as _groups has them
    sub_shape = tuple(1 if c else n for c, n in zip(collapse, grid.shape, strict=True))
    n_sub = math.prod(sub_shape)
    omegas = np.empty(n_sub)
    for lo in range(0, n_sub, _PLAN_BLOCK):
        flat = np.arange(lo, min(lo + _PLAN_BLOCK, n_sub))
        position = np.unravel_index(flat, sub_shape)
        params = {}
        for key in keys:
            if key in grid.paths:
                d = grid.paths.index(key)
                params[key] = np.asarray(grid.values[d], dtype=np.float64)[position[d]]
            else:
                params[key] = np.full(flat.size, _value_of(system, key))
        try:
            omegas[flat] = batch_omegas(system, params)
        except RollspringError:
            return None
    omegas = omegas.reshape(sub_shape)
    best: tuple[float, Any] = (-1.0, None)
    for index in range(grid.n_chunks):
        region = grid.region(index)
        part = omegas[tuple(slice(0, 1) if c else s for c, s in zip(collapse, region, strict=True))]
        top = float(np.max(part))
        omega = top if top > -np.inf else 0.0
        if omega > best[0] or best[1] is None:
            sample = {}
            for key in keys:
                if key in grid.paths:
                    d = grid.paths.index(key)
                    sample[key] = np.asarray([grid.values[d][region[d].start]], dtype=np.float64)
                else:
                    sample[key] = np.full(1, _value_of(system, key))
            best = (omega, (system, sample))
    return best


# --------------------------------------------------------------------------------------------
# the chunk


def _empty(plan: SweepPlan, n: int, n_bodies: int) -> dict[str, np.ndarray]:
    def f(*shape: int) -> np.ndarray:
        return np.full((n, *shape), np.nan)

    out = {
        "omega": f(n_bodies),
        "stationary_weight": f(n_bodies),
        "required_mu_linear": f(n_bodies),
        "period_measured": f(),
        "max_friction_ratio": f(n_bodies),
        "min_normal_force": f(n_bodies),
        "first_slip_time": f(),
        "first_slip_body": np.full(n, -1, dtype=np.int16),
        "first_liftoff_time": f(),
        "cm_amplitude": f(),
        "stationary_amplitude": f(),
        "energy_error": f(),
        "status": np.full(n, STATUS_CODES["invalid"], dtype=np.int8),
    }
    if plan.on_slip == "continue":
        out["energy_dissipated"] = f()
        out["time_slipping"] = f()
    return out


def compute_chunk(plan: SweepPlan, index: int) -> dict[str, np.ndarray]:
    """The variables of chunk ``index``, each shaped as its region (plus ``mode``/``body``)."""
    return compute_chunks(plan, [index])[0]


def compute_chunks(
    plan: SweepPlan, indices: list[int], stepping: Callable[[], None] | None = None
) -> list[dict[str, np.ndarray]]:
    """:func:`compute_chunk` of each of ``indices``, computed together (one batch call for
    all their runs; every run's numbers are those it has alone, so the result of a chunk does
    not depend on the chunks computed with it). ``stepping``: called when a batch call starts
    stepping (:func:`rollspring.simulate_batch`'s ``on_stepping``), or before the first run
    when there is no batch call (``on_slip="continue"``: each run alone)."""
    prepare_worker(plan.numba_threads)
    runs = _Runs(plan, indices)
    ids = [b.id for b in runs.system.bodies]
    nb = len(ids)
    out = _empty(plan, runs.n, nb)
    # X-hat's weights are (1 + gamma) m (M11) only with centre springs and no anchors or forces;
    # else the batch measures X-hat on the weights of (M14), from the linear metrics first
    weighted = (
        "stationary_amplitude" in plan.metrics
        and plan.on_slip == "stop"
        and (runs.structural or not pseudo_momentum_conserved(system_arrays(runs.system)))
    )
    linear = weighted or bool(
        {"omega", "stationary_weight", "required_mu_linear"} & set(plan.metrics)
    )
    alive = np.ones(runs.n, dtype=bool)
    single = np.ones(runs.n, dtype=bool)  # runs whose start goes through analyze alone
    overlap = None
    if linear and not runs.structural:
        if (
            plan.linear_aside
            and plan.on_slip == "stop"
            and not weighted
            and not any(p.split(".")[-1] in _PLACEMENT for p in plan.grid.paths)
        ):
            # every run's start is a valid system (no varied value moves a spring end), so
            # the batch call need not wait for the linear metrics: they are computed in a
            # thread meanwhile (its NumPy work overlaps the batch's preparation)
            overlap = _overlap_pool().submit(_batch_linear_metrics, runs, out)
            single[:] = False
        else:
            single = ~_batch_linear_metrics(runs, out)
    if linear or runs.structural:
        for r in np.flatnonzero(single):
            system, analysis, _ = runs.start(int(r), linear=linear)
            if system is None:
                alive[r] = False
                continue
            if analysis is not None:
                _linear_metrics(out, int(r), analysis)
    if plan.on_slip == "continue":
        if stepping is not None:
            stepping()
        for r in np.flatnonzero(alive):
            _single_run(plan, runs, out, int(r), on_slip="continue")
    else:
        for system, members, params in _groups(runs, alive):
            _batch_group(plan, runs, out, system, members, params, stepping)
        if plan.refine_slip:
            events = (out["status"] == STATUS_CODES["slip"]) | (
                out["status"] == STATUS_CODES["liftoff"]
            )
            for r in np.flatnonzero(events):
                _refine_event(plan, runs, out, int(r))
    if overlap is not None:
        for r in np.flatnonzero(~overlap.result()):
            system, analysis, _ = runs.start(int(r), linear=True)
            if system is not None and analysis is not None:
                _linear_metrics(out, int(r), analysis)
    results = []
    offset = 0
    for local in runs.locals:
        size = int(np.prod(local))
        shaped = {}
        for name, values in out.items():
            if name not in plan.metrics and name != "status":
                continue
            shaped[name] = values[offset : offset + size].reshape(*local, *values.shape[1:])
        results.append(shaped)
        offset += size
    return results


#: Batch paths that move a spring end in the initial placement (a combination of their values
#: can make an invalid system).
_PLACEMENT = ("x", "radius")
_POOL: list[Any] = []


def _overlap_pool() -> Any:
    """One worker thread of this process for the linear metrics."""
    if not _POOL:
        from concurrent.futures import ThreadPoolExecutor

        _POOL.append(ThreadPoolExecutor(1, thread_name_prefix="rollspring-linear"))
    return _POOL[0]


def _batch_linear_metrics(runs: _Runs, out: dict[str, np.ndarray]) -> np.ndarray:
    """The linear metrics of the runs :func:`rollspring.analysis.batch_linear` handles (the
    flat centre class), computed once per distinct linear configuration (the friction
    coefficients left out); returns the mask of the runs it filled."""
    paths = [p for p in runs.plan.grid.paths if p.split(".")[-1] not in _MU]
    if paths and len(paths) == len(runs.plan.grid.paths):
        # no friction axis: the runs are points of an outer product of distinct values, so
        # every run is a distinct linear configuration
        first = inverse = None
    elif paths:  # runs alike in all but their friction share one computation
        rows = distinct_rows([np.asarray(runs.values[p], dtype=np.float64) for p in paths], runs.n)
        first, inverse = (None, None) if rows is None else rows
    else:
        first, inverse = np.zeros(1, dtype=np.int64), np.zeros(runs.n, dtype=np.int64)
    try:
        result = batch_linear(
            runs.system,
            {p: runs.values[p] if first is None else runs.values[p][first] for p in paths},
            n_runs=runs.n if first is None else first.size,
        )
    except (ValueError, ArithmeticError, np.linalg.LinAlgError):
        return np.zeros(runs.n, dtype=bool)
    n_modes = result.omega.shape[1]
    if inverse is None:
        inverse = np.arange(runs.n)
        if np.all(result.handled):  # row r is run r's, all filled at once
            out["omega"][:, :n_modes] = result.omega
            out["stationary_weight"][:] = result.stationary_weight
            out["required_mu_linear"][:] = result.required_mu
            return result.handled
    handled = result.handled[inverse]
    out["omega"][handled, :n_modes] = result.omega[inverse[handled]]
    out["stationary_weight"][handled] = result.stationary_weight[inverse[handled]]
    out["required_mu_linear"][handled] = result.required_mu[inverse[handled]]
    return handled


def _linear_metrics(out: dict[str, np.ndarray], r: int, analysis: Any) -> None:
    omegas = [m.omega for m in analysis.modes]
    out["omega"][r, : len(omegas)] = omegas
    if analysis.stationary_weights is not None:
        out["stationary_weight"][r] = analysis.stationary_weights
    if analysis.required_mu is not None:
        out["required_mu_linear"][r] = analysis.required_mu


def _batch_group(
    plan: SweepPlan,
    runs: _Runs,
    out: dict[str, np.ndarray],
    system: System,
    members: np.ndarray,
    params: dict[str, np.ndarray],
    stepping: Callable[[], None] | None = None,
) -> None:
    weights = None
    if "stationary_amplitude" in plan.metrics and not pseudo_momentum_conserved(
        system_arrays(system)
    ):
        weights = out["stationary_weight"][members]  # X-hat of (M14), not (M11)'s
    try:
        result = _batch(
            plan,
            system,
            params,
            duration=plan.duration,
            step=plan.step,
            scheme=plan.scheme,
            metric_every=plan.metric_every,
            stepping=stepping,
            stationary_weights=weights,
        )
    except RollspringError:
        if members.size == 1:
            out["status"][members[0]] = STATUS_CODES["invalid"]
            return
        for j in range(len(members)):  # one bad combination: find it, run the others
            _batch_group(
                plan,
                runs,
                out,
                system,
                members[j : j + 1],
                {k: v[j : j + 1] for k, v in params.items()},
                stepping,
            )
        return
    if (
        not math.isclose(result.step, plan.step, rel_tol=1e-12)
        or result.integrator != plan.scheme
        or result.metric_every != plan.metric_every
    ):
        raise RollspringError(
            f"internal: the batch ran with {result.integrator}, step {result.step!r}, "
            f"metric_every {result.metric_every}, not the sweep's {plan.scheme}, "
            f"{plan.step!r}, {plan.metric_every}"
        )
    k = members.size
    status = result.status[:k]
    out["status"][members] = status
    event = result.first_slip_time[:k]
    out["first_slip_time"][members] = np.where(status == STATUS_CODES["slip"], event, np.nan)
    out["first_slip_body"][members] = np.where(
        status == STATUS_CODES["slip"], result.first_slip_body[:k], -1
    )
    out["first_liftoff_time"][members] = np.where(status == STATUS_CODES["liftoff"], event, np.nan)
    out["period_measured"][members] = result.period_measured[:k]
    out["cm_amplitude"][members] = result.cm_amplitude[:k]
    out["stationary_amplitude"][members] = result.stationary_amplitude[:k]
    out["energy_error"][members] = result.energy_error[:k]
    out["max_friction_ratio"][members] = result.max_friction_ratio[:k]
    out["min_normal_force"][members] = result.min_normal_force[:k]


def _refine_event(plan: SweepPlan, runs: _Runs, out: dict[str, np.ndarray], r: int) -> None:
    """The instant (and body) of run ``r``'s first slip or lift-off, root-found by
    :func:`rollspring.simulate` on the step (which stops there)."""
    system = runs.run_system(r)
    if system is None:
        return
    try:
        trajectory = simulate(
            system, plan.duration, rtol=plan.rtol, on_slip="stop", n_output=2, confirm=True
        )
    except RollspringError:
        return
    ids = [b.id for b in system.bodies]
    slip, lift = trajectory.summary["first_slip"], trajectory.summary["first_liftoff"]
    if out["status"][r] == STATUS_CODES["slip"] and slip is not None:
        out["first_slip_time"][r] = slip["time"]
        out["first_slip_body"][r] = ids.index(slip["body"])
    elif out["status"][r] == STATUS_CODES["liftoff"] and lift is not None:
        out["first_liftoff_time"][r] = lift["time"]


def _single_run(
    plan: SweepPlan, runs: _Runs, out: dict[str, np.ndarray], r: int, *, on_slip: str
) -> None:
    """Run ``r`` alone through :func:`rollspring.simulate` (stick-slip with kinetic
    friction)."""
    system = runs.run_system(r)
    if system is None:
        return
    try:
        trajectory = simulate(system, plan.duration, rtol=plan.rtol, on_slip=on_slip, confirm=True)
    except RollspringError:
        out["status"][r] = STATUS_CODES["invalid"]
        return
    summary = trajectory.summary
    ids = [b.id for b in system.bodies]
    out["status"][r] = STATUS_CODES.get(trajectory.status, STATUS_CODES["nonfinite"])
    if summary["first_slip"] is not None:
        out["first_slip_time"][r] = summary["first_slip"]["time"]
        out["first_slip_body"][r] = ids.index(summary["first_slip"]["body"])
    if summary["first_liftoff"] is not None:
        out["first_liftoff_time"][r] = summary["first_liftoff"]["time"]
    period = summary["period_measured"]
    out["period_measured"][r] = np.nan if period is None else period
    out["energy_error"][r] = summary["energy_error"]
    for i, name in enumerate(ids):
        ratio = summary["max_friction_ratio"].get(name, 0.0)  # None: it never rolled
        out["max_friction_ratio"][r, i] = np.nan if ratio is None else ratio
        out["min_normal_force"][r, i] = summary["min_normal_force"][name]
    out["cm_amplitude"][r] = 0.5 * float(np.ptp(trajectory.cm_x))
    if trajectory.stationary_x is not None:
        v0 = np.array([b.v for b in system.bodies])
        analysis = runs.start(r, linear=True)[1]
        drift = (
            float(analysis.stationary_weights @ v0)
            if analysis is not None and analysis.stationary_weights is not None
            else 0.0
        )
        out["stationary_amplitude"][r] = 0.5 * float(
            np.ptp(trajectory.stationary_x - drift * trajectory.t)
        )
    out["energy_dissipated"][r] = float(trajectory.energy[0] - trajectory.energy[-1])
    out["time_slipping"][r] = _time_slipping(trajectory.events, float(trajectory.t[-1]))


def _time_slipping(events: Sequence[Mapping[str, Any]], end: float) -> float:
    """Total time during which at least one body slips (from the exact event instants)."""
    intervals = []
    since: dict[str, float] = {}
    for event in events:
        if event["kind"] == "slip":
            since.setdefault(event["body"], float(event["time"]))
        elif event["kind"] == "stick" and event["body"] in since:
            intervals.append((since.pop(event["body"]), float(event["time"])))
    intervals += [(t, end) for t in since.values()]
    total, reach = 0.0, -math.inf
    for lo, hi in sorted(intervals):
        if hi <= reach:
            continue
        total += hi - max(lo, reach)
        reach = hi
    return total


# --------------------------------------------------------------------------------------------
# worker processes


_PREPARED: dict[str, Any] = {}


def prepare_worker(numba_threads: int = 0, *, on_worker: bool | None = None) -> None:
    """On a Dask worker: give this process its own Numba cache directory (processes sharing
    one have crashed, numba/numba#4807) — one of a pool of slots, each held by a lock for the
    process' life, so a restarted worker reuses a compiled slot — and cap Numba's threads
    (``numba_threads``; several workers on one machine). Idempotent; a no-op outside a
    worker."""
    if numba_threads > 0:
        import numba

        # numba.config sets NUMBA_NUM_THREADS at import: mypy cannot see it
        limit = numba.config.NUMBA_NUM_THREADS  # type: ignore[attr-defined]
        numba.set_num_threads(min(numba_threads, limit))
    if "cache" in _PREPARED:
        return
    if on_worker is None:
        try:
            from distributed import get_worker

            get_worker()
        except (ImportError, ValueError):
            return
    elif not on_worker:
        return
    import fcntl
    import tempfile
    from pathlib import Path

    base = Path(
        os.environ.get("ROLLSPRING_WORKER_CACHE")
        or Path(tempfile.gettempdir()) / f"rollspring-numba-{os.getuid()}"
    )
    for slot in range(256):
        folder = base / f"worker-{slot}"
        folder.mkdir(parents=True, exist_ok=True)
        handle = open(folder / ".lock", "w")  # noqa: SIM115 - held for the process' life
        try:
            fcntl.flock(handle, fcntl.LOCK_EX | fcntl.LOCK_NB)
        except OSError:
            handle.close()
            continue
        os.environ["NUMBA_CACHE_DIR"] = str(folder)
        import numba.core.config

        numba.core.config.reload_config()
        _PREPARED["cache"] = (folder, handle)
        return
    _PREPARED["cache"] = None


def warm_up(plan: SweepPlan, dask_worker: Any = None) -> str:
    """Prepare this worker and compile (or load) the batch kernel of the sweep: run by
    ``client.run`` on every worker before the chunks."""
    prepare_worker(plan.numba_threads, on_worker=dask_worker is not None)
    if plan.on_slip != "continue":
        runs = _Runs(plan, [0])
        alive = np.zeros(runs.n, dtype=bool)
        alive[0] = True
        for system, _, params in _groups(runs, alive):
            with contextlib.suppress(RollspringError):
                simulate_batch(
                    system, params, _TINY, step=_TINY, integrator="yoshida4", stop_on_slip=True
                )
    return os.environ.get("NUMBA_CACHE_DIR", "")


def copy_plan(plan: SweepPlan, **changes: Any) -> SweepPlan:
    """``plan`` with some fields changed."""
    data = {name: getattr(plan, name) for name in plan.__dataclass_fields__}
    data.update(changes)
    data["system"] = copy.deepcopy(data["system"])
    return SweepPlan(**data)

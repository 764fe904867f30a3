"""``rollspring.sweep``: a grid of runs of one system, in-process or on a Dask cluster, into a
Zarr store that a rerun resumes (docs/sweeps.md is the contract).

Order of work: validate the grid; open the store (refuse another sweep's store unless
``overwrite``; on a rerun read the plan back from its attrs); choose one integrator, step and
metric sampling for the whole grid (from the batch's linear frequencies of every run, computed
once on the grid with its velocity and friction axes collapsed; a pass over the chunks with one
cheap batch call each where that does not apply); write the template; run the chunks without a
done marker — in this process on a pool of threads (one a core by default), each taking a group
of consecutive chunks as one batch call on the serial kernel, which releases the GIL, or as
tasks on a Dask cluster, a bounded number in flight — writing each into its region as it arrives
(in this thread, while the others step), then its marker.
"""

from __future__ import annotations

import contextlib
import functools
import logging
import math
import numbers
import os
import threading
import time
from collections.abc import Callable, Iterator, Mapping, Sequence
from concurrent.futures import FIRST_COMPLETED, Future, ThreadPoolExecutor, wait
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np

from rollspring.analysis.costs import CONFIRM, RTOL_RANGE, Cost, check_cost
from rollspring.model import System, as_system, system_to_json, system_to_toml
from rollspring.service.sweeps.compute import (
    STATUS_CODES,
    SweepPlan,
    compute_chunk,
    compute_chunks,
    copy_plan,
    grid_omega,
    plan_omega,
    warm_up,
)
from rollspring.service.sweeps.grid import (
    Grid,
    SweepError,
    check_grid,
    chunk_shape,
    count_grid,
    path_kind,
)
from rollspring.service.sweeps.store import (
    VARIABLES,
    RegionWriter,
    StoreMismatchError,
    check_place,
    discard,
    done_chunks,
    fingerprint,
    read_attrs,
    store_lock,
    verified_done,
    write_template,
)
from rollspring.simulate.batch.plan import MAX_STEPS, batch_schedule, omega_limit, steps_needed
from rollspring.simulate.costs import available_cores, batch_cost
from rollspring.simulate.status import FLAG_MEANINGS, FLAG_VALUES

__all__ = ["DEFAULT_CHUNK", "MAX_THREADS_PER_CORE", "METRICS", "SweepProgress", "sweep"]

#: Runs per chunk unless ``chunk`` says otherwise (or a store resumed was made with another):
#: 16384, a Zarr chunk of about 128 KiB a variable (4096 before 29 Nov 2026: four times the
#: files, and a store's writes cost a third of the stepping).
DEFAULT_CHUNK = 16384
#: In-process, consecutive chunks are computed together, up to this many runs a batch call
#: (fewer calls; every run's numbers are those it has alone).
IN_PROCESS_RUNS = 1 << 16
#: In-process, the grid is cut into about this many batch calls a thread (a finished one is
#: written while the others step).
TASKS_PER_THREAD = 8
#: The in-process pool's threads, at most this many a core.
MAX_THREADS_PER_CORE = 4
#: On a cluster, a chunk whose key is cancelled under it (a worker lost with its result) is
#: submitted again, up to this many submissions in all.
CHUNK_ATTEMPTS = 4
#: Metrics (variables) a sweep can store; ``energy_dissipated`` and ``time_slipping`` only
#: with ``on_slip="continue"``.
METRICS = tuple(VARIABLES)
_CONTINUE_ONLY = ("energy_dissipated", "time_slipping")
_log = logging.getLogger(__name__)


@dataclass
class SweepProgress:
    """What a progress callback receives: once before the first chunk (``chunks_run`` 0),
    then after each chunk. ``chunks_skipped``: chunks a previous run finished."""

    done_runs: int
    total_runs: int
    chunks_run: int
    chunks_to_run: int
    chunks_skipped: int


#: The revision of how a chunk's numbers are computed, part of the grid fingerprint: a store
#: written by another revision is refused (its numbers could differ in the last bits from this
#: one's, so resuming it would mix the two). 2: only the varied numbers are given per run
#: (revision 1 also gave every body's mass).
ENGINE_REVISION = 2


@functools.lru_cache(maxsize=1)
def _version() -> str:
    try:
        from importlib.metadata import version

        return version("rollspring")
    except Exception:  # noqa: BLE001 - not installed as a distribution
        return "unknown"


def _check_arguments(duration: Any, rtol: Any, on_slip: Any, chunk: Any, step: Any) -> None:
    if (
        isinstance(duration, bool)
        or not isinstance(duration, int | float)
        or not math.isfinite(duration)
        or duration <= 0
    ):
        raise SweepError(f"--duration: must be a positive number of seconds, got {duration!r}")
    if isinstance(rtol, bool) or not isinstance(rtol, int | float) or not 0 < rtol < 1:
        raise SweepError(f"--rtol: must be a number in (0, 1), got {rtol!r}")
    low, high = RTOL_RANGE
    if not low <= rtol <= high:  # what simulate and every run of the batch take
        raise SweepError(
            f"--rtol: must be between {low:g} and {high:g} (finer is below what double "
            f"precision delivers), got {rtol!r}"
        )
    if on_slip not in ("stop", "continue"):
        raise SweepError(f"--on-slip: must be stop or continue, got {on_slip!r}")
    if chunk is not None and (isinstance(chunk, bool) or not isinstance(chunk, int) or chunk < 1):
        raise SweepError(f"--chunk: must be a whole number of runs >= 1, got {chunk!r}")
    if step is not None and (
        isinstance(step, bool)
        or not isinstance(step, int | float)
        or not math.isfinite(step)
        or not 0 < step <= duration
    ):
        raise SweepError(
            f"--step: must be a positive number of seconds up to the duration, got {step!r}"
        )
    if step is not None and not duration / step <= MAX_STEPS:
        raise SweepError(
            f"--step: {step:g} s takes about {duration / step:.3g} steps over {duration:g} s; "
            f"a run takes at most {MAX_STEPS:.0e} (a longer step, or a shorter duration)"
        )


def _check_integrator(integrator: Any) -> None:
    if integrator not in ("auto", "verlet", "yoshida4", "yoshida6"):
        raise SweepError(
            f"--integrator: unknown integrator {integrator!r} (auto, verlet, yoshida4, yoshida6)"
        )


def _metrics(metrics: Sequence[str] | None, on_slip: str) -> tuple[str, ...]:
    available = [m for m in METRICS if on_slip == "continue" or m not in _CONTINUE_ONLY]
    if metrics is None:
        return tuple(available)
    if isinstance(metrics, str):
        metrics = [metrics]
    for name in metrics:
        if name in _CONTINUE_ONLY and on_slip != "continue":
            raise SweepError(f"--metric {name}: only with --on-slip continue")
        if name not in METRICS:
            raise SweepError(f"--metric {name}: unknown metric (one of {', '.join(available)})")
    chosen = set(metrics) | {"status"}
    return tuple(m for m in METRICS if m in chosen)


def sweep_cost(
    system: System,
    vary: Mapping[str, Sequence[float]],
    duration: float,
    *,
    rtol: float = 1e-8,
    integrator: str = "auto",
    out: str | os.PathLike[str] | None = None,
    what: str = "this sweep",
    smaller: str = "fewer values to vary, a shorter duration",
) -> Cost:
    """The estimated cost of :func:`sweep` (before any run: the grid counted from its lengths,
    :func:`~rollspring.service.sweeps.grid.count_grid`): its runs in the batch kernels
    (:func:`~rollspring.simulate.costs.batch_cost`) and the metrics they keep, in the store
    (``out``) or in memory. The arguments are checked as :func:`sweep` checks them."""
    _check_arguments(duration, rtol, "stop", None, None)
    _check_integrator(integrator)
    runs = count_grid(vary)
    bodies = len(system.bodies)
    return batch_cost(
        system,
        runs,
        duration,
        rtol=min(max(float(rtol), 1e-14), 0.1),  # the estimate's range (the sweep takes (0, 1))
        integrator=integrator,
        numbers_per_run=24 + 16 * bodies,  # the metrics, per body and the modes' frequencies
        what=what,
        smaller=smaller,
        holds="a store" if out is not None else "memory",
    )


def sweep(
    system: System | str,
    vary: Mapping[str, Sequence[float]],
    duration: float,
    *,
    metrics: Sequence[str] | None = None,
    on_slip: str = "stop",
    out: str | os.PathLike[str] | None = None,
    scheduler: Any = None,
    chunk: int | None = None,
    overwrite: bool = False,
    rtol: float = 1e-8,
    progress: Callable[[SweepProgress], None] | None = None,
    step: float | None = None,
    integrator: str = "auto",
    refine_slip: bool = True,
    confirm: bool = False,
    threads: int | None = None,
) -> Any:
    r"""Run ``system`` once per point of the grid ``vary`` (``{PATH: values}``, the outer
    product in the given order) for ``duration`` s and return the metrics as an
    ``xarray.Dataset`` (docs/sweeps.md: dims named by the PATHs, ``mode``, ``body``).

    ``out``: a Zarr v3 store written chunk by chunk (``xarray.open_zarr(out)`` gives the
    result, which is also returned, lazily); a rerun with the same arguments runs only the
    chunks without a done marker, and another sweep's store is refused
    (:class:`StoreMismatchError`) unless ``overwrite``. ``scheduler``: None (in this process,
    every core), a Dask scheduler address ``"tcp://host:port"`` or a ``distributed.Client``.
    ``chunk``: runs per chunk (default :data:`DEFAULT_CHUNK`, or the chunks of the store
    resumed). ``step`` fixes the integration
    step of the whole grid (default: chosen from ``rtol`` and the grid's highest frequency);
    ``integrator``: the batch's (``auto``, ``verlet``, ``yoshida4``, ``yoshida6``; with
    ``step``, ``auto`` means Yoshida-4, as in :func:`rollspring.simulate_batch`);
    ``refine_slip`` (default True) root-finds each first slip / lift-off instant with a single
    :func:`rollspring.simulate` run instead of the batch's linear interpolation between steps.
    ``progress`` is called with a :class:`SweepProgress` after each chunk.

    Parameters
    ----------
    system
        A :class:`~rollspring.model.System`, a file path or a preset name.
    vary
        ``{PATH: values}``: the grid, e.g. ``{"springs.0.stiffness": [50, 100]}``.
    duration
        The simulated time of every run (s).
    metrics, on_slip, rtol, step, integrator, refine_slip
        What is measured, and how each run is integrated.
    out, overwrite, chunk
        The Zarr store (resumable), whether another sweep's store may be replaced, runs a chunk.
    scheduler
        None (this process), a Dask scheduler address or a ``distributed.Client``.
    progress
        Called with a :class:`SweepProgress` after each chunk.
    confirm
        Start even when the estimate (:func:`sweep_cost`: the runs × a run's steps, the store)
        is above the bound; at most :data:`~rollspring.simulate.costs.MAX_RUNS` runs either way.
    threads
        In this process: the chunks computed at once, each on a thread of its own (default:
        every core this process may use; at most :data:`MAX_THREADS_PER_CORE` a core), while
        this thread writes those finished. The numbers are the same bit for bit whatever the
        threads, and the same as on a cluster. Not with ``scheduler`` (a cluster's workers
        have their own threads).

    Returns
    -------
    xarray.Dataset
        The metrics over the grid.
    """
    system = as_system(system)
    _check_arguments(duration, rtol, on_slip, chunk, step)
    if progress is not None and not callable(progress):
        raise SweepError(f"progress: must be a function or None, got {type(progress).__name__}")
    _check_integrator(integrator)
    threads = _check_threads(threads, scheduler)
    if any(s.damping > 0 for s in system.springs) and on_slip == "stop":
        raise SweepError(
            "system: a damped spring needs --on-slip continue (single runs); the "
            "batch integrators are symplectic"
        )
    chosen = _metrics(metrics, on_slip)
    if out is not None:
        out = check_place(out, bool(overwrite))
    cost = sweep_cost(system, vary, duration, rtol=rtol, integrator=integrator, out=out)
    check_cost(cost, confirmed=bool(confirm), flag=CONFIRM)  # before the grid's values
    paths, values = check_grid(system, vary)
    _check_modes(system, paths)
    shape = tuple(len(v) for v in values)
    grid = Grid(paths, values, chunk_shape(shape, chunk or DEFAULT_CHUNK))
    if chunk is None and out is not None and not overwrite:  # a store to resume, perhaps
        grid = _resumed_chunks(Path(out), grid)
    toml = system_to_toml(system)
    extra = {
        "engine": ENGINE_REVISION,
        "refine_slip": bool(refine_slip),
        "integrator": integrator,
        "step": None if step is None else float(step).hex(),
    }
    print_ = fingerprint(toml, grid, duration, rtol, on_slip, chosen, extra)
    plan = SweepPlan(
        system=system_to_json(system),
        grid=grid,
        duration=float(duration),
        rtol=float(rtol),
        on_slip=on_slip,
        metrics=chosen,
        refine_slip=bool(refine_slip),
        integrator=integrator,
    )

    path = None if out is None else Path(out)
    with contextlib.ExitStack() as held:
        if path is not None:  # one sweep at a time writes a store
            held.enter_context(store_lock(path))
        done: set[int] = set()
        stored = None
        replace = False  # an earlier store at path, removed just before the template is written
        if path is not None and overwrite:
            replace = path.exists() or path.is_symlink()  # whatever is there (nothing read)
        elif path is not None:
            attrs = read_attrs(path)
            if attrs is not None:
                if attrs.get("grid_fingerprint") != print_:
                    raise StoreMismatchError(
                        f"--out {path}: holds another sweep (grid fingerprint "
                        f"{str(attrs.get('grid_fingerprint'))[:12]}…, this one {print_[:12]}…); "
                        "use --overwrite to replace it"
                    )
                stored = attrs
                done = verified_done(path, grid, done_chunks(path))
            elif path.exists():
                raise StoreMismatchError(
                    f"--out {path}: exists and is not a rollspring sweep "
                    "store; use --overwrite to replace it"
                )

        client, own_client = _client(scheduler)
        removals: list[threading.Thread] = []  # an overwritten store's removal
        try:
            if stored is not None:
                plan = copy_plan(
                    plan,
                    scheme=stored["integrator"],
                    step=float(stored["step"]),
                    metric_every=int(stored["metric_every"]),
                    omega_max=float(stored["omega_max"]),
                )
            else:
                plan = _choose_step(plan, step)
            if client is not None:
                plan = copy_plan(plan, numba_threads=_threads_per_worker(client))
            ids = [b["id"] for b in plan.system["bodies"]]
            attrs = {
                "system": toml,
                "rollspring_version": _version(),
                "grid_fingerprint": print_,
                "duration": float(duration),
                "rtol": float(rtol),
                "on_slip": on_slip,
                "integrator": plan.scheme,
                "step": plan.step,
                "metric_every": plan.metric_every,
                "omega_max": plan.omega_max,
                "metrics": list(chosen),
                "chunk": int(math.prod(grid.chunks)),
                "chunk_shape": list(grid.chunks),
                "n_chunks": grid.n_chunks,
                "refine_slip": bool(refine_slip),
            }
            todo = [i for i in range(grid.n_chunks) if i not in done]
            memory = None if path is not None else _memory(grid, chosen, len(ids))
            writer: list[RegionWriter] = []
            opened: list[Any] = []  # the dataset returned, opened once the template is there

            def ready() -> None:
                """The store made ready for the first write: run once, while the first chunks
                step."""
                if path is None or writer:
                    return
                arrays = None  # read back from the store resumed
                if stored is None:
                    if replace:
                        removal = discard(path)
                        if removal is not None:
                            removals.append(removal)
                    arrays = write_template(path, grid, ids, len(ids), chosen, attrs)
                writer.append(RegionWriter(path, grid, arrays))

            def returned() -> None:
                """The dataset returned, opened (lazily: its metadata only, which the chunks do
                not change) once the store is ready: in-process on a thread the last groups
                leave free, while the others end."""
                if path is not None and writer and not opened:
                    import xarray as xr

                    # the template written here is consolidated: opened as such, xarray
                    # does not first look for it (a third of the opening's CPU)
                    fresh = True if stored is None else None
                    opened.append(xr.open_zarr(str(path), consolidated=fresh))

            def store(items: list[tuple[int, dict[str, np.ndarray]]]) -> None:
                if path is not None:  # each chunk's data written before its marker
                    writer[0].write(items)
                else:
                    assert memory is not None  # kept in memory when there is no store
                    for index, arrays in items:
                        region = grid.region(index)
                        for name, values in arrays.items():
                            memory[name][region] = values

            counted = sum(_runs_in(grid, i) for i in done)
            if progress is not None:
                progress(SweepProgress(counted, grid.n_runs, 0, len(todo), len(done)))
            k = 0
            for items in _results(plan, todo, client, threads, ready, returned):
                store(items)
                for index, _ in items:
                    counted += _runs_in(grid, index)
                    k += 1
                    if progress is not None:
                        progress(SweepProgress(counted, grid.n_runs, k, len(todo), len(done)))
            ready()  # no chunk left to run
            returned()
        finally:
            if own_client and client is not None:
                client.close()
            for removal in removals:
                removal.join()
        if path is not None:
            return opened[0]
        assert memory is not None  # kept in memory when there is no store
        return _dataset(grid, chosen, ids, memory, attrs)


def _resumed_chunks(path: Path, grid: Grid) -> Grid:
    """``grid`` chunked as the store at ``path`` is when it holds this grid's shape (a rerun
    without ``chunk`` resumes a store whatever chunk size made it: an earlier default); else
    ``grid``."""
    try:
        attrs = read_attrs(path)
    except StoreMismatchError:
        return grid  # refused below, with the other checks of the store
    stored = None if attrs is None else attrs.get("chunk_shape")
    if (
        isinstance(stored, list)
        and len(stored) == len(grid.shape)
        and all(isinstance(c, int) and 1 <= c <= n for c, n in zip(stored, grid.shape, strict=True))
    ):
        return Grid(grid.paths, grid.values, tuple(stored))
    return grid


def _check_modes(system: System, paths: tuple[str, ...]) -> None:
    modes = [path_kind(system, p)[1][0] for p in paths if path_kind(system, p)[0] == "mode"]
    if not modes:
        return
    from rollspring.analysis import analyze

    analysis = analyze(system, confirm=True)
    oscillating = [str(i) for i, m in enumerate(analysis.modes) if m.kind == "oscillating"]
    for n in modes:
        if analysis.modes[n].kind != "oscillating":
            raise SweepError(
                f"--vary modes.{n}.amplitude: mode {n} is a "
                f"{analysis.modes[n].kind} mode (the oscillating ones: "
                f"{', '.join(oscillating) or 'none'})"
            )


def _runs_in(grid: Grid, index: int) -> int:
    return math.prod(s.stop - s.start for s in grid.region(index))


def _choose_step(plan: SweepPlan, step: float | None) -> SweepPlan:
    """One integrator, step and metric sampling for the whole grid, from its highest linear
    frequency (read chunk by chunk): what the batch chooses for a call holding every run
    (:func:`~rollspring.simulate.batch.plan.batch_schedule` of that frequency). A grid whose
    fastest run would need more than :data:`~rollspring.simulate.batch.plan.MAX_STEPS` steps
    is refused (the batch would leave that run out and choose a step too long for it)."""
    if plan.on_slip == "continue":
        return copy_plan(plan, scheme="single runs", step=0.0, metric_every=0, omega_max=0.0)
    best: tuple[float, Any] | None = grid_omega(plan)
    if best is None:
        best = (-1.0, None)
        for index in range(plan.grid.n_chunks):
            omega, sample = plan_omega(plan, index)
            if sample is not None and omega > best[0]:
                best = (omega, sample)
    omega, sample = best
    if sample is None:
        raise SweepError("--vary: no run of the grid is a valid system")
    omega = max(omega, 0.0)
    if step is None:
        need = float(steps_needed(np.array([omega]), plan.duration, plan.rtol, plan.integrator)[0])
        if need > MAX_STEPS:
            limit = omega_limit(plan.duration, plan.rtol, plan.integrator)
            raise SweepError(
                f"--vary: the grid's fastest run (linear frequency {omega:.4g} rad/s) would "
                f"need {need:.3g} steps over {plan.duration:g} s at rtol {plan.rtol:g} (at most "
                f"{MAX_STEPS:.0e}; frequencies up to {limit:.4g} rad/s are resolved); pass "
                "--step to force it"
            )
    _, scheme, n_steps, every = batch_schedule(
        np.array([omega]) if omega > 0 else np.zeros(0),
        plan.duration,
        plan.rtol,
        plan.integrator,
        step,
    )
    return copy_plan(
        plan,
        scheme=scheme,
        step=plan.duration / n_steps,
        metric_every=every,
        omega_max=omega,
    )


def _client(scheduler: Any) -> tuple[Any, bool]:
    if scheduler is None:
        return None, False
    try:
        from distributed import Client
    except ImportError:  # pragma: no cover - pinned
        raise SweepError("--scheduler: needs dask[distributed]") from None
    if isinstance(scheduler, Client):
        return scheduler, False
    if not isinstance(scheduler, str) or "://" not in scheduler:
        raise SweepError(
            f"--scheduler: expected tcp://HOST:PORT or a distributed.Client, got {scheduler!r}"
        )
    try:
        return Client(scheduler, timeout=30, set_as_default=False), True
    except (OSError, TimeoutError) as exc:
        raise SweepError(f"--scheduler {scheduler}: cannot connect ({exc})") from None


def _threads_per_worker(client: Any) -> int:
    """Numba threads per worker: the cores of its machine shared by the workers on it."""
    from urllib.parse import urlparse

    cores = client.run(os.cpu_count)
    hosts: dict[str, list[int]] = {}
    for address, count in cores.items():
        hosts.setdefault(urlparse(address).hostname or address, []).append(count or 1)
    shares = [max(1, max(c) // len(c)) for c in hosts.values()]
    return min(shares) if shares else 1


def _check_threads(threads: Any, scheduler: Any) -> int:
    """The in-process pool's threads: a whole number from 1 to :data:`MAX_THREADS_PER_CORE`
    a core (None: one a core); only without a scheduler."""
    cores = available_cores()
    if threads is None:
        return cores
    if scheduler is not None:
        raise SweepError(
            "--threads: only for a sweep in this process (a cluster's workers have their own "
            "threads: dask worker --nthreads)"
        )
    most = MAX_THREADS_PER_CORE * cores
    if (
        isinstance(threads, bool | np.bool_)
        or not isinstance(threads, numbers.Integral)
        or not 1 <= int(threads) <= most
    ):
        raise SweepError(
            f"--threads: must be a whole number from 1 to {most} ({MAX_THREADS_PER_CORE} for "
            f"each of the {cores} cores), got {threads!r}"
        )
    return int(threads)


def _tasks(grid: Grid, todo: list[int], threads: int) -> list[list[int]]:
    """``todo`` as groups of consecutive chunks, one batch call each: about
    :data:`TASKS_PER_THREAD` groups a thread (the threads kept busy, the writes of the first
    overlapping the stepping of the next), each of at least one chunk and at most
    :data:`IN_PROCESS_RUNS` runs."""
    total = sum(_runs_in(grid, index) for index in todo)
    size_bound = min(IN_PROCESS_RUNS, max(1, total // (TASKS_PER_THREAD * threads)))
    groups: list[list[int]] = []
    group: list[int] = []
    size = 0
    for index in todo:
        runs = _runs_in(grid, index)
        if group and (size + runs > size_bound or index != group[-1] + 1):
            groups.append(group)
            group, size = [], 0
        group.append(index)
        size += runs
    if group:
        groups.append(group)
    return groups


def _in_process(
    plan: SweepPlan,
    todo: list[int],
    threads: int,
    ready: Callable[[], None],
    tail: Callable[[], None] | None = None,
) -> Iterator[list[tuple[int, dict[str, np.ndarray]]]]:
    """The chunks of ``todo`` computed by a pool of ``threads`` threads, each group
    (:func:`_tasks`) by one batch call on the serial kernel, which releases the GIL while it
    steps; finished groups are yielded as they come (the caller writes them while the pool
    steps the next), at most ``2 threads`` groups in flight. ``ready`` is called once the first
    groups are stepping (each thread's batch call has set its runs up, or a group has ended):
    before, its Python work would hold the GIL against their setup, and delay the stepping of
    every core. For the same reason a finished group is yielded (written) once the groups that
    took the freed threads step. ``tail`` (work the caller needs before it returns) runs right
    after ``ready`` when a core is left free (fewer threads than cores), else on a pool thread
    left idle for good (no group left to start) once the group that freed it is written, beside
    the last groups' stepping (else here, at the end); it is waited for before the generator
    ends. The serial kernel is the parallel one's block code: the numbers do not depend on the
    threads."""
    spare_core = threads < available_cores()
    serial = copy_plan(plan, batch_threads=1, linear_aside=spare_core)
    groups = iter(_tasks(plan.grid, todo, threads))
    started = threading.Condition()
    begun: set[int] = set()  # the groups (their first chunk) a pool thread has taken
    stepped: set[int] = set()  # the groups whose batch call has started stepping

    def steps(first: int) -> None:
        with started:
            stepped.add(first)
            started.notify_all()

    def task(group: list[int]) -> list[dict[str, np.ndarray]]:
        with started:
            begun.add(group[0])
        return compute_chunks(serial, group, functools.partial(steps, group[0]))

    def ended(_: Future[Any]) -> None:
        with started:
            started.notify_all()

    def settled() -> bool:
        """Every pool thread with a group to run has taken one, and each taken group steps
        (or has ended)."""
        running = [pending[f][0] for f in pending if not f.done()]
        taken = [first for first in running if first in begun]
        return len(taken) >= min(threads, len(running)) and all(first in stepped for first in taken)

    with ThreadPoolExecutor(threads, thread_name_prefix="rollspring-sweep") as pool:
        pending: dict[Future[list[dict[str, np.ndarray]]], list[int]] = {}
        left = [True]  # groups left to start
        tailing: list[Future[None]] = []

        def submit() -> None:
            group = next(groups, None)
            if group is None:
                left[0] = False
                return
            future = pool.submit(task, group)
            pending[future] = group
            future.add_done_callback(ended)

        for _ in range(2 * threads):
            submit()
        try:
            with started:  # each thread's first group steps (or has ended)
                started.wait_for(settled)
            ready()  # the store's template written while the first groups step
            if tail is not None and spare_core:  # here, on the core the pool leaves free
                tail()
                tail = None
            while pending:
                finished, _ = wait(pending, return_when=FIRST_COMPLETED)
                for future in sorted(finished, key=lambda f: pending[f][0]):
                    group = pending.pop(future)
                    arrays = future.result()
                    submit()  # the pool kept full while this thread writes
                    with started:  # written once the freed threads' next groups step
                        started.wait_for(settled)
                    yield list(zip(group, arrays, strict=True))
                    # written: once a pool thread is idle for good, the tail runs there
                    # while the last groups step (not beside the write: three threads on
                    # two cores)
                    if (
                        tail is not None
                        and not tailing
                        and not left[0]
                        and 0 < len(pending) < threads
                    ):
                        tailing.append(pool.submit(tail))
            if tail is not None and not tailing:
                tail()
            for tailed in tailing:
                tailed.result()
        finally:  # an error here or in the caller: nothing more is started
            for future in pending:
                future.cancel()


def _results(
    plan: SweepPlan,
    todo: list[int],
    client: Any,
    threads: int,
    ready: Callable[[], None],
    tail: Callable[[], None] | None = None,
) -> Iterator[list[tuple[int, dict[str, np.ndarray]]]]:
    """Finished chunks, (index, arrays), a list at a time: in-process a group of chunks as
    each thread of the pool finishes it, on Dask one chunk as each task completes. ``ready``
    (the store's template) is called before the first is yielded; in-process, ``tail`` runs on
    a pool thread left idle for good, or at the end (see :func:`_in_process`)."""
    if client is None:
        yield from _in_process(plan, todo, threads, ready, tail)
        return
    ready()
    from distributed import KilledWorker, as_completed
    from distributed.client import FutureCancelledError

    if not todo:
        return
    client.run(warm_up, plan)
    shared = [client.scatter(plan, broadcast=True, hash=False)]  # scattered again if lost
    workers = max(1, len(client.scheduler_info().get("workers", {})))
    window = 2 * workers + 2
    pending = iter(todo)
    futures: dict[str, int] = {}
    attempts: dict[int, int] = {}

    def submit(index: int | None) -> Any:
        if index is None:
            return None
        attempts[index] = attempts.get(index, 0) + 1
        future = client.submit(
            compute_chunk,
            shared[0],
            index,
            pure=False,  # a new key for every submission (the index last)
            key=f"rollspring-sweep-{time.time_ns()}-a{attempts[index]}-{index}",
        )
        futures[future.key] = index
        return future

    first = [f for f in (submit(next(pending, None)) for _ in range(window)) if f is not None]
    queue = as_completed(first, loop=client.loop)
    for future in queue:
        index = futures.pop(future.key)
        try:
            arrays = future.result()
        except FutureCancelledError as exc:
            # A worker lost with the chunk's result can leave its key cancelled on the
            # scheduler (distributed's "Couldn't gather ..., rescheduling" race), or the workers
            # holding the scattered plan can all be gone ("lost dependencies"): the chunk is
            # computed again under a new key (chunks are pure), the plan scattered again if it
            # was lost. A client cut off from the scheduler cannot resubmit: an error.
            if client.status != "running":
                raise SweepError(
                    f"--scheduler: the connection to the scheduler was lost ({exc.reason}); "
                    "a store given by --out keeps the chunks finished, and a new run resumes it"
                ) from None
            if attempts[index] >= CHUNK_ATTEMPTS:
                raise SweepError(
                    f"chunk {index}: cancelled on the cluster {attempts[index]} times (the last: "
                    f"{exc.reason}); a store given by --out keeps the chunks finished, and a new "
                    "run resumes it"
                ) from None
            if shared[0].status != "finished":
                try:  # workers replaced (restarted, scaled) may take a while to join
                    shared[0] = client.scatter(plan, broadcast=True, hash=False, timeout=120)
                except (TimeoutError, OSError) as lost:
                    raise SweepError(
                        f"--scheduler: the workers holding the sweep's plan were lost and no "
                        f"worker took it again ({lost}); a store given by --out keeps the "
                        "chunks finished, and a new run resumes it"
                    ) from None
            _log.warning(
                "chunk %d: cancelled on the cluster (%s); computing it again (attempt %d of %d)",
                index,
                exc.reason,
                attempts[index] + 1,
                CHUNK_ATTEMPTS,
            )
            queue.add(submit(index))
            continue
        except KilledWorker as exc:
            raise SweepError(
                f"chunk {index}: the workers computing it died ({exc}); "
                "a store given by --out keeps the chunks finished, and a new run resumes it"
            ) from None
        future.release()
        following = submit(next(pending, None))
        if following is not None:
            queue.add(following)
        yield [(index, arrays)]


def _memory(grid: Grid, metrics: tuple[str, ...], n_bodies: int) -> dict[str, np.ndarray]:
    out = {}
    for name in metrics:
        extra = VARIABLES[name][0]
        shape = (*grid.shape, *([n_bodies] if extra else []))
        if name == "status":
            out[name] = np.full(shape, STATUS_CODES["invalid"], dtype=np.int8)
        elif name == "first_slip_body":
            out[name] = np.full(shape, -1, dtype=np.int16)
        else:
            out[name] = np.full(shape, np.nan)
    return out


def _dataset(
    grid: Grid,
    metrics: tuple[str, ...],
    ids: list[str],
    memory: dict[str, np.ndarray],
    attrs: dict[str, Any],
) -> Any:
    import xarray as xr

    from rollspring.service.sweeps.grid import unit_of

    coords: dict[str, Any] = {
        p: (p, np.asarray(v, dtype=np.float64), {"units": unit_of(p), "long_name": p})
        for p, v in zip(grid.paths, grid.values, strict=True)
    }
    coords["mode"] = (
        "mode",
        np.arange(len(ids), dtype=np.int64),
        {"units": "1", "long_name": "mode, sorted by omega"},
    )
    coords["body"] = ("body", np.array(ids, dtype=str), {"units": "1", "long_name": "body id"})
    data = {}
    for name in metrics:
        extra, units, long_name = VARIABLES[name]
        var_attrs: dict[str, Any] = {"units": units, "long_name": long_name}
        if name == "status":
            var_attrs["flag_values"] = list(FLAG_VALUES)
            var_attrs["flag_meanings"] = FLAG_MEANINGS
        data[name] = ((*grid.paths, *([extra] if extra else [])), memory[name], var_attrs)
    return xr.Dataset(data, coords=coords, attrs=attrs)

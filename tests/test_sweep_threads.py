"""Sweeps on every core (issue 24, point 6): the generated batch kernels release the GIL, the
serial kernel steps every run bit for bit as the parallel one, an in-process sweep computes its
chunks on a pool of threads and writes the same store whatever the threads, parallel launches
from several Python threads wait for each other instead of aborting the process, and the bounds
of ``threads`` / ``--threads``."""

from __future__ import annotations

from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

import numba
import numpy as np
import pytest
import xarray as xr
from hypothesis import HealthCheck, given, settings
from typer.testing import CliRunner

import rollspring
from rollspring.errors import CostTooHigh, SimulationError
from rollspring.service.sweeps import SweepError, sweep
from rollspring.simulate import simulate_batch
from rollspring.simulate.batch.codegen import BLOCK
from rollspring.simulate.costs import available_cores
from tests.test_batch_independence import assert_same_batch
from tests.test_batch_layouts import layouts
from tests.test_sweep import same

SYSTEM = "hoop-cylinder"


def spread(parameters: dict[str, list[float]], runs: int) -> dict[str, np.ndarray]:
    """Each varied value spread over ``runs`` runs between its two values (several blocks)."""
    return {key: np.linspace(low, high, runs) for key, (low, high) in parameters.items()}


@settings(max_examples=4, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(layout=layouts())
def test_the_serial_kernel_steps_every_run_as_the_parallel_one(layout):
    """Random layouts (off-centre and raised attachments, sliders, walls, forces), several
    blocks of runs: one thread, every thread and two threads give the same numbers bit for
    bit."""
    system, parameters = layout
    varied = spread(parameters, 3 * BLOCK + 5) if parameters else {"gravity": np.full(5, 9.81)}
    kwargs = {"integrator": "yoshida4", "step": 2e-3, "stop_on_slip": False}
    serial = simulate_batch(system, varied, 0.5, threads=1, **kwargs)
    assert serial.n_runs == next(iter(varied.values())).size
    assert_same_batch(serial, simulate_batch(system, varied, 0.5, **kwargs))
    if numba.config.NUMBA_NUM_THREADS >= 2:
        assert_same_batch(serial, simulate_batch(system, varied, 0.5, threads=2, **kwargs))


def test_the_serial_kernel_on_the_papers_pair_with_slips():
    """The paper's pair over a friction range where some runs slip and stop: the events are the
    same too."""
    parameters = {
        "springs.0.stiffness": np.linspace(50.0, 150.0, 2 * BLOCK + 3),
        "bodies.hoop.mu_static": np.geomspace(0.02, 1.0, 2 * BLOCK + 3),
    }
    serial = simulate_batch(SYSTEM, parameters, 3.0, threads=1)
    assert 0 < np.count_nonzero(serial.status == 2) < serial.n_runs  # some slip, some roll
    assert_same_batch(serial, simulate_batch(SYSTEM, parameters, 3.0))


def test_parallel_launches_from_several_threads_wait_for_each_other():
    """The parallel kernel releases the GIL; Numba's workqueue layer aborts the process when two
    threads launch parallel kernels at once, so simulate_batch keeps them apart (a lock): four
    concurrent batches finish, each with the serial kernel's numbers."""
    parameters = {"springs.0.stiffness": np.linspace(50.0, 150.0, BLOCK + 1)}
    serial = simulate_batch(SYSTEM, parameters, 2.0, threads=1)
    with ThreadPoolExecutor(4) as pool:
        results = list(pool.map(lambda _: simulate_batch(SYSTEM, parameters, 2.0), range(4)))
    for result in results:
        assert_same_batch(serial, result)


@pytest.mark.parametrize(
    ("threads", "words"),
    [
        (0, "threads: must be an integer >= 1, got 0"),
        (True, "threads: must be an integer >= 1, got True"),
        (2.0, "threads: must be an integer >= 1, got 2.0"),
        (
            numba.config.NUMBA_NUM_THREADS + 1,
            f"threads: {numba.config.NUMBA_NUM_THREADS + 1} is more than Numba's "
            f"{numba.config.NUMBA_NUM_THREADS} threads (NUMBA_NUM_THREADS)",
        ),
    ],
)
def test_batch_threads_are_checked(threads, words):
    with pytest.raises(SimulationError) as raised:
        simulate_batch(SYSTEM, {"springs.0.stiffness": [50.0, 60.0]}, 1.0, threads=threads)
    assert str(raised.value) == words


# -- the sweep's pool ------------------------------------------------------------------------

VARY = {
    "springs.0.stiffness": np.linspace(50.0, 150.0, 7),
    "bodies.hoop.mu_static": np.geomspace(0.02, 1.0, 9),
    "bodies.cylinder.v": [0.0, 0.2],
}


def test_one_thread_two_and_three_give_the_same_sweep(tmp_path):
    """A grid where some runs slip (their instants refined by single runs) and every run has its
    own linear analysis, in chunks of 5 runs (many groups for the pool): stores written with one
    and two threads, and the sweep in memory with three and in one chunk, bit for bit."""
    one = sweep(SYSTEM, VARY, 2.0, chunk=5, out=tmp_path / "one.zarr", threads=1).load()
    two = sweep(SYSTEM, VARY, 2.0, chunk=5, out=tmp_path / "two.zarr", threads=2).load()
    three = sweep(SYSTEM, VARY, 2.0, chunk=5, threads=3)
    whole = sweep(SYSTEM, VARY, 2.0, chunk=10_000, threads=1)
    statuses = np.bincount(one["status"].values.ravel(), minlength=7)
    assert statuses[0] > 0 and statuses[2] > 0  # some roll throughout, some slip
    same(one, two)
    same(one, three)
    same(one, whole)
    done = sorted(int(p.name) for p in (tmp_path / "two.zarr" / ".rollspring-done").iterdir())
    assert done == list(range(int(two.attrs["n_chunks"])))


def test_progress_counts_every_chunk_once_with_a_pool():
    seen: list[rollspring.service.sweeps.SweepProgress] = []
    sweep(SYSTEM, VARY, 1.0, chunk=4, threads=2, progress=seen.append)
    assert [p.chunks_run for p in seen] == list(range(len(seen)))
    assert seen[-1].done_runs == seen[-1].total_runs == 7 * 9 * 2
    assert seen[-1].chunks_run == seen[0].chunks_to_run


def test_a_confirmed_sweep_runs_every_chunk_whatever_one_batch_call_would_cost(monkeypatch):
    """The cost is checked once, for the grid: before, a confirmed sweep whose chunk alone was
    above the bound had its batch calls refused one by one and stored every run as
    ``invalid``."""
    import rollspring.simulate.costs as costs

    monkeypatch.setattr(costs, "_BATCH_BODY_STEP", 1e3)  # every batch call far above the bound
    vary = {"springs.0.stiffness": [50.0, 100.0, 150.0]}
    with pytest.raises(CostTooHigh):
        sweep(SYSTEM, vary, 1.0)
    result = sweep(SYSTEM, vary, 1.0, confirm=True)
    assert result["status"].values.tolist() == [0, 0, 0]


def test_on_stepping_is_called_once_on_the_calling_thread_before_the_stepping():
    """``simulate_batch(on_stepping=...)``: once, on the calling thread, after the runs are set
    up (the kernel not yet called), also when no run is integrated; a non-function is refused
    on one line before anything runs."""
    import threading

    import rollspring.simulate.batch.api as api

    calls: list[tuple[int, int]] = []
    stepped: list[int] = []
    real = api.cache.load_kernel

    def counted(*args, **kwargs):
        kernel = real(*args, **kwargs)

        class Counted:
            signatures = kernel.signatures

            def compile(self, *a):
                return kernel.compile(*a)

            def __call__(self, *a):
                stepped.append(len(calls))  # how many on_stepping calls came before
                return kernel(*a)

        return Counted()

    api.cache.load_kernel = counted
    try:
        result = simulate_batch(
            SYSTEM,
            {"springs.0.stiffness": [50.0, 80.0]},
            0.5,
            threads=1,
            on_stepping=lambda: calls.append((threading.get_ident(), len(stepped))),
        )
    finally:
        api.cache.load_kernel = real
    assert calls == [(threading.get_ident(), 0)]  # once, here, before the kernel
    assert stepped == [1]
    assert list(result.status_names) == ["finished", "finished"]
    # no run integrated (too fast to resolve in 1e8 steps): still called, once
    calls.clear()
    fast = {
        "springs.0.stiffness": [1e9],
        "bodies.hoop.mass": [1e-6],
        "bodies.cylinder.mass": [1e-6],
    }
    nothing = simulate_batch(SYSTEM, fast, 1000.0, on_stepping=lambda: calls.append((0, 0)))
    assert list(nothing.status_names) == ["unresolved"] and calls == [(0, 0)]
    with pytest.raises(SimulationError) as raised:
        simulate_batch(SYSTEM, {"springs.0.stiffness": [50.0]}, 0.5, on_stepping=3)
    assert str(raised.value).splitlines()[0].startswith("on_stepping: must be a function")


def test_the_store_is_made_once_every_thread_steps(tmp_path, monkeypatch):
    """The store's template (Python work that holds the GIL) is written once each thread's
    first batch call has started stepping (before, it held up their setup, and every core
    started late); the returned dataset is opened on a thread the last groups leave free."""
    import threading

    import rollspring.service.sweeps.compute as compute
    import rollspring.service.sweeps.engine as engine

    order: list[str] = []
    real_batch, real_template = compute.simulate_batch, engine.write_template

    def batch(*args, on_stepping=None, **kwargs):
        def stepping():
            order.append("stepping")
            if on_stepping is not None:
                on_stepping()

        return real_batch(*args, on_stepping=stepping, **kwargs)

    def template(*args, **kwargs):
        order.append("template")
        return real_template(*args, **kwargs)

    opened_on: list[str] = []
    real_open = xr.open_zarr

    def open_zarr(*args, **kwargs):
        opened_on.append(threading.current_thread().name)
        return real_open(*args, **kwargs)

    real_chunks = engine.compute_chunks

    def chunks(*args, **kwargs):
        try:
            return real_chunks(*args, **kwargs)
        finally:
            order.append("ended")

    monkeypatch.setattr(compute, "simulate_batch", batch)
    monkeypatch.setattr(engine, "write_template", template)
    monkeypatch.setattr(engine, "compute_chunks", chunks)
    monkeypatch.setattr(xr, "open_zarr", open_zarr)
    monkeypatch.setattr(engine, "available_cores", lambda: 2)  # a thread a core: none spare
    vary = {"springs.0.stiffness": np.linspace(50.0, 150.0, 40).tolist()}
    result = sweep(SYSTEM, vary, 1.0, chunk=5, threads=2, out=tmp_path / "s.zarr")
    # after both threads' first batch calls stepped, or one of them ended (tiny groups)
    before = order[: order.index("template")]
    assert before.count("stepping") >= 2 or "ended" in before
    assert order.count("stepping") == order.count("ended") == 8  # a batch call a chunk
    assert len(opened_on) == 1 and opened_on[0].startswith("rollspring-sweep")
    same(result.load(), sweep(SYSTEM, vary, 1.0, chunk=5, threads=1))


def _sweep_events(monkeypatch, tmp_path, threads: int, cores: int) -> list[tuple[str, object]]:
    """The events of a store sweep of 8 one-chunk groups on ``threads`` threads, as if the
    machine had ``cores`` cores: ("stepping", chunk index) when a group's batch call steps,
    ("write", chunk index) when the main thread writes a group, ("template", None) and
    ("open", thread name)."""
    import threading

    import rollspring.service.sweeps.engine as engine

    events: list[tuple[str, object]] = []
    lock = threading.Lock()

    def log(kind: str, what: object) -> None:
        with lock:
            events.append((kind, what))

    real_chunks, real_template = engine.compute_chunks, engine.write_template
    real_write, real_open = engine.RegionWriter.write, xr.open_zarr

    def chunks(plan, group, stepping=None):
        def steps():
            log("stepping", group[0])
            if stepping is not None:
                stepping()

        return real_chunks(plan, group, steps)

    def template(*args, **kwargs):
        log("template", None)
        return real_template(*args, **kwargs)

    def write(self, items):
        log("write", items[0][0])
        return real_write(self, items)

    def open_zarr(*args, **kwargs):
        log("open", threading.current_thread().name)
        return real_open(*args, **kwargs)

    monkeypatch.setattr(engine, "compute_chunks", chunks)
    monkeypatch.setattr(engine, "write_template", template)
    monkeypatch.setattr(engine.RegionWriter, "write", write)
    monkeypatch.setattr(xr, "open_zarr", open_zarr)
    monkeypatch.setattr(engine, "available_cores", lambda: cores)
    vary = {"springs.0.stiffness": np.linspace(50.0, 150.0, 40).tolist()}
    result = sweep(SYSTEM, vary, 1.0, chunk=5, threads=threads, out=tmp_path / "s.zarr")
    monkeypatch.undo()
    same(result.load(), sweep(SYSTEM, vary, 1.0, chunk=5, threads=1))
    return events


@pytest.mark.parametrize(("threads", "cores"), [(1, 2), (2, 2), (2, 3)])
def test_a_group_is_written_once_the_freed_thread_steps_its_next(
    tmp_path, monkeypatch, threads, cores
):
    """A finished group is written (Python work that holds the GIL) once the thread it freed
    steps its next group, not while that group's batch call sets its runs up: the write and
    the setup took turns on the GIL and the kernel started late."""
    events = _sweep_events(monkeypatch, tmp_path, threads, cores)
    written = [what for kind, what in events if kind == "write"]
    assert sorted(written) == list(range(8))  # every group (a chunk each) written once
    for k, first in enumerate(written):
        at = events.index(("write", first))
        stepped = {what for kind, what in events[:at] if kind == "stepping"}
        # the groups ended by then (k + 1) and those the threads took next all step
        assert len(stepped) >= min(k + 1 + threads, 8)


def test_with_a_core_to_spare_the_result_is_opened_as_soon_as_the_store_is_made(
    tmp_path, monkeypatch
):
    """With fewer threads than cores the returned dataset is opened on the main thread right
    after the template, beside the first group's stepping (not after the last group: the
    end of the sweep waited for it); with a thread a core, on a pool thread left idle."""
    spare = _sweep_events(monkeypatch, tmp_path / "spare", threads=1, cores=2)
    kinds = [kind for kind, _ in spare]
    assert kinds.index("template") < kinds.index("open") < kinds.index("write")
    assert [what for kind, what in spare if kind == "open"] == ["MainThread"]
    full = _sweep_events(monkeypatch, tmp_path / "full", threads=2, cores=2)
    opened = [what for kind, what in full if kind == "open"]
    assert len(opened) == 1 and str(opened[0]).startswith("rollspring-sweep")


@pytest.mark.parametrize(
    ("threads", "words"),
    [
        (0, "got 0"),
        (True, "got True"),
        (1.5, "got 1.5"),
        (4 * available_cores() + 1, f"got {4 * available_cores() + 1}"),
    ],
)
def test_sweep_threads_are_checked(threads, words):
    with pytest.raises(SweepError) as raised:
        sweep(SYSTEM, {"springs.0.stiffness": [50.0, 60.0]}, 1.0, threads=threads)
    most = 4 * available_cores()
    assert str(raised.value) == (
        f"--threads: must be a whole number from 1 to {most} (4 for each of the "
        f"{available_cores()} cores), {words}"
    )


def test_threads_are_for_a_sweep_in_this_process():
    with pytest.raises(SweepError) as raised:
        sweep(
            SYSTEM,
            {"springs.0.stiffness": [50.0, 60.0]},
            1.0,
            threads=2,
            scheduler="tcp://127.0.0.1:1",
        )
    assert str(raised.value).startswith("--threads: only for a sweep in this process")


def test_threads_on_the_command_line(tmp_path: Path):
    from rollspring.cli.app import app

    runner = CliRunner()
    out = tmp_path / "s.zarr"
    args = ["sweep", SYSTEM, "-T", "1", "--vary", "springs.0.stiffness=50:150:6"]
    result = runner.invoke(app, [*args, "--threads", "2", "--chunk", "2", "--out", str(out)])
    assert result.exit_code == 0, result.output
    assert "ran 3 of 3 chunks" in result.output
    single = sweep(SYSTEM, {"springs.0.stiffness": np.linspace(50, 150, 6)}, 1.0, threads=1)
    same(xr.open_zarr(out).load(), single)
    bad = runner.invoke(app, [*args, "--threads", "0", "--out", str(tmp_path / "t.zarr")])
    assert bad.exit_code == 2
    assert bad.output.startswith("error: --threads: must be a whole number from 1 to ")
    assert bad.output.count("\n") == 1
    assert not (tmp_path / "t.zarr").exists()

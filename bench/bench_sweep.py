"""Sweeps (issue 11): in-process throughput against the bare batch kernel, scaling from one to
two Dask workers, and the peak memory of the client and the workers for a sweep of 10^7 runs.

Run: ``.venv/bin/python bench/bench_sweep.py [--runs 65536] [--duration 10] [--repeat 3]
[--cluster-runs 65536] [--memory-runs 10000000] [--memory-duration 1]
[--json build/bench/sweep.json] [--parts abc] [--scratch build/bench]``; ``--parts ab``
leaves (c) out. The stores and the cluster's files go in a temporary folder under
``--scratch`` (default ``build/bench``, where a user's sweep would write, not the system's
temporary folder); what a file and a folder cost the file system there is measured and
printed first.

The system is the ``hoop-cylinder`` preset. Parts:

(a) In-process sweeps on two grids of ``--runs`` runs (about square): ``springs.0.stiffness`` x
    ``bodies.hoop.mu_static`` (the linear metrics shared along the friction axis) and
    ``springs.0.stiffness`` x ``bodies.cylinder.v`` (every run its own linear configuration).
    The baseline is the bare batch kernel on one core, ``simulate_batch(..., threads=1)`` on
    exactly the same runs (the flattened grid) with the sweep's integrator and step. Timed: the
    batch on one core and on every core; the sweep with ``threads=1`` and with one thread a core,
    in memory and written to a new Zarr store (the previous round's removed before the round,
    and the file system's pending work flushed before each call, untimed). The calls are
    interleaved (a round of all six, ``--repeat`` rounds after a warm-up
    round; the best of each), so that load from other work hits them alike. Targets: the sweep
    written to a store >= 0.90x the one-core batch with one thread, and >= 0.85 x cores (1.7
    on two cores) with one thread a core. The two stores are also compared bit for bit. Each
    call's CPU time (the process's, every thread) is printed too, with its ratio to the
    one-core batch's: on a machine shared with other work, the steadier figure of what a call
    costs (the wall-time targets need the cores to themselves).
(b) A real loopback cluster started as a user starts one: ``dask scheduler --host 127.0.0.1``
    and ``dask worker ADDRESS --nthreads 1 --no-nanny`` (``NUMBA_NUM_THREADS=1``: one core per
    worker, the machine has two), the sweep given the scheduler's address. Runs/s with one
    worker, then with a second one started; efficiency = rate(2) / (2 rate(1)), target >= 80 %
    per worker. Client, scheduler and workers share the two cores, so this is the most this
    machine can show.
(c) On that two-worker cluster, sweeps of a hundredth, a tenth and all of ``--memory-runs``
    runs (default 10^7; a grid of stiffness (100) x mu_static (100) x initial speed of the hoop,
    ``--memory-duration`` s each, no slip refinement: the single-run refinement of the quarter of
    the runs that slip would take hours at 10^7 and holds nothing between runs) written to a
    store; the resident set size (psutil) of the client (this process) and of each worker is
    sampled every 50 ms, and its peak reported for the whole sweep and for the first and the
    second half of the samples. Target: each peak < 1 GB, and flat in the run count.

Every figure is measured in this run; the table prints the targets with ✔/✘ and everything is
also written as JSON (``--json``).
"""

from __future__ import annotations

import argparse
import contextlib
import json
import math
import os
import shutil
import signal
import subprocess
import sys
import tempfile
import threading
import time
from pathlib import Path
from typing import Any

import numpy as np
import psutil

sys.path.insert(0, str(Path(__file__).resolve().parent))

from common import best_of, machine_note, print_table

import rollspring
from rollspring.service.sweeps import sweep
from rollspring.simulate import simulate_batch

ROOT = Path(__file__).resolve().parents[1]
SYSTEM = "hoop-cylinder"
GB = 1e9
#: The metrics the batch kernel itself gives (no linear analysis per run).
BATCH_METRICS = [
    "period_measured",
    "max_friction_ratio",
    "min_normal_force",
    "first_slip_time",
    "first_slip_body",
    "first_liftoff_time",
    "cm_amplitude",
    "stationary_amplitude",
    "energy_error",
]


def square_grid(runs: int) -> dict[str, np.ndarray]:
    """Stiffness x hoop mu_static, about sqrt(runs) values each (exactly ``runs`` when it is
    a product of the two)."""
    n1 = max(1, int(math.sqrt(runs)))
    n2 = max(1, runs // n1)
    return {
        "springs.0.stiffness": np.linspace(50.0, 150.0, n1),
        "bodies.hoop.mu_static": np.geomspace(0.1, 1.0, n2),
    }


def speed_grid(runs: int) -> dict[str, np.ndarray]:
    """Stiffness x the cylinder's initial speed, about sqrt(runs) values each: every run has
    its own linear configuration (the linear metrics cannot be shared along a friction
    axis)."""
    n1 = max(1, int(math.sqrt(runs)))
    n2 = max(1, runs // n1)
    return {
        "springs.0.stiffness": np.linspace(50.0, 150.0, n1),
        "bodies.cylinder.v": np.linspace(0.0, 0.3, n2),
    }


GRIDS = {"k x mu_s": square_grid, "k x v": speed_grid}


def cube_grid(runs: int) -> dict[str, np.ndarray]:
    """Stiffness (100) x hoop mu_static (100) x hoop initial speed (runs / 10^4)."""
    n3 = max(1, runs // 10_000)
    return {
        "springs.0.stiffness": np.linspace(50.0, 150.0, 100),
        "bodies.hoop.mu_static": np.geomspace(0.02, 1.0, 100),
        "bodies.hoop.v": np.linspace(0.0, 0.3, n3),
    }


def n_runs(vary: dict[str, np.ndarray]) -> int:
    return math.prod(len(v) for v in vary.values())


def flat(vary: dict[str, np.ndarray]) -> dict[str, np.ndarray]:
    """The grid's runs as flat arrays, C order (last PATH fastest), as the sweep orders them."""
    grids = np.meshgrid(*vary.values(), indexing="ij")
    return {path: g.ravel() for path, g in zip(vary, grids, strict=True)}


# -- peak memory ------------------------------------------------------------------------------


class PeakRSS:
    """Sample the resident set size of some processes every ``every`` s in a thread; ``peak``
    maps each label to its largest sample (bytes)."""

    def __init__(self, processes: dict[str, int], every: float = 0.05) -> None:
        self.processes = {label: psutil.Process(pid) for label, pid in processes.items()}
        self.peak = dict.fromkeys(processes, 0)
        self.samples = 0
        self.every = every
        self._stop = threading.Event()
        self._thread = threading.Thread(target=self._run, daemon=True)

    def _run(self) -> None:
        self.began = time.perf_counter()
        self.series: list[tuple[float, dict[str, int]]] = []
        while not self._stop.is_set():
            sample = {}
            for label, process in self.processes.items():
                with contextlib.suppress(psutil.Error):
                    sample[label] = process.memory_info().rss
                    self.peak[label] = max(self.peak[label], sample[label])
            self.series.append((time.perf_counter() - self.began, sample))
            self.samples += 1
            self._stop.wait(self.every)

    def halves(self) -> dict[str, tuple[int, int]]:
        """Per process, the peak over the first and over the second half of the samples (a
        footprint that grows with the runs done shows as a larger second half)."""
        half = len(self.series) // 2
        out = {}
        for label in self.processes:
            first = [s.get(label, 0) for _, s in self.series[:half]] or [0]
            second = [s.get(label, 0) for _, s in self.series[half:]] or [0]
            out[label] = (max(first), max(second))
        return out

    def __enter__(self) -> PeakRSS:
        self._thread.start()
        return self

    def __exit__(self, *exc: object) -> None:
        self._stop.set()
        self._thread.join()


# -- a loopback cluster from the command lines -------------------------------------------------


class Cluster:
    """``dask scheduler`` and ``dask worker`` processes on 127.0.0.1, one core per worker."""

    def __init__(self, directory: Path) -> None:
        self.directory = directory
        self.dask = str(Path(sys.executable).with_name("dask"))
        self.env = dict(
            os.environ,
            NUMBA_NUM_THREADS="1",
            OMP_NUM_THREADS="1",
            OPENBLAS_NUM_THREADS="1",
            MKL_NUM_THREADS="1",
            PYTHONWARNINGS="ignore",
        )
        self.workers: list[subprocess.Popen] = []
        self.logs: list[Any] = []
        scheduler_file = directory / "scheduler.json"
        self.scheduler = self._start(
            [
                self.dask,
                "scheduler",
                "--host",
                "127.0.0.1",
                "--port",
                "0",
                "--no-dashboard",
                "--scheduler-file",
                str(scheduler_file),
            ],
            "scheduler",
        )
        deadline = time.monotonic() + 60
        while not scheduler_file.exists() or not scheduler_file.read_text().strip():
            if self.scheduler.poll() is not None or time.monotonic() > deadline:
                raise RuntimeError(f"dask scheduler did not start; see {directory}/scheduler.log")
            time.sleep(0.1)
        time.sleep(0.2)  # the file is written in one go, but let it finish
        self.address = json.loads(scheduler_file.read_text())["address"]
        from distributed import Client

        self.client = Client(self.address, timeout="60s")

    def _start(self, command: list[str], name: str) -> subprocess.Popen:
        log = open(self.directory / f"{name}.log", "w")  # noqa: SIM115 - closed in stop()
        self.logs.append(log)
        return subprocess.Popen(
            command, stdout=log, stderr=subprocess.STDOUT, env=self.env, cwd=self.directory
        )

    def add_worker(self) -> int:
        """Start one more worker and wait until the scheduler has it; returns its pid."""
        name = f"worker-{len(self.workers)}"
        worker = self._start(
            [
                self.dask,
                "worker",
                self.address,
                "--nthreads",
                "1",
                "--no-nanny",
                "--no-dashboard",
                "--memory-limit",
                "0",
                "--name",
                name,
                "--local-directory",
                str(self.directory),
            ],
            name,
        )
        self.workers.append(worker)
        self.client.wait_for_workers(len(self.workers), timeout=120)
        return worker.pid

    def stop(self) -> None:
        with contextlib.suppress(Exception):
            self.client.close()
        for process in [*self.workers, self.scheduler]:
            if process.poll() is None:
                process.send_signal(signal.SIGINT)
        for process in [*self.workers, self.scheduler]:
            try:
                process.wait(timeout=20)
            except subprocess.TimeoutExpired:
                process.kill()
                process.wait()
        for log in self.logs:
            log.close()


def file_system_cost(folder: Path, count: int = 200) -> dict[str, float]:
    """The CPU (this process's, s) the file system takes to make a folder, and a 64 KiB file
    as a store's chunk is written (a ``.partial`` file renamed over its name), in ``folder``:
    the most of what a store costs beyond encoding. Median of ``count`` each."""
    data = bytes(65536)
    probe = folder / "file-system-probe"
    probe.mkdir()
    folders, files = [], []
    try:
        for i in range(count):
            began = time.process_time()
            (probe / f"d{i}").mkdir()
            folders.append(time.process_time() - began)
            began = time.process_time()
            partial = probe / f"f{i}.partial"
            with open(partial, "wb") as handle:
                handle.write(data)
            os.replace(partial, probe / f"f{i}")
            files.append(time.process_time() - began)
    finally:
        shutil.rmtree(probe, ignore_errors=True)
    return {"folder_s": float(np.median(folders)), "file_s": float(np.median(files))}


def describe_file_system(cost: dict[str, float], folder: Path) -> str:
    return (
        f"stores written in {folder}: the file system takes {cost['file_s'] * 1e3:.3f} ms of CPU "
        f"a file, {cost['folder_s'] * 1e3:.3f} ms a folder (median of 200)"
    )


# -- the parts ---------------------------------------------------------------------------------


def part_a(system, runs: int, duration: float, repeats: int, scratch: Path) -> dict[str, Any]:
    return {
        label: part_a_grid(system, make(runs), duration, repeats, scratch)
        for label, make in GRIDS.items()
    }


def settle_disk() -> None:
    """The file system's pending work flushed (untimed) before a timed call: the writeback of
    the stores of earlier calls (and the removal of the previous round's) then never lands in
    a later call's time. A call's own writeback still comes after it returns, as for any
    program writing through the page cache."""
    if hasattr(os, "sync"):
        os.sync()


def part_a_grid(
    system, vary: dict[str, np.ndarray], duration: float, repeats: int, scratch: Path
) -> dict[str, Any]:
    """The calls interleaved, ``repeats`` rounds after a warm-up round, best of each: a load
    that comes and goes on a shared machine then hits them alike. The baseline is the bare
    batch kernel on one core: ``simulate_batch(..., threads=1)`` on the flattened grid with the
    sweep's integrator, step and metric sampling."""
    count = n_runs(vary)
    cores = os.cpu_count() or 1
    sweep(system, {k: v[:2] for k, v in vary.items()}, duration / 100)  # compile
    dataset = sweep(system, vary, duration, confirm=True)
    integrator, step = str(dataset.attrs["integrator"]), float(dataset.attrs["step"])
    parameters = flat(vary)
    stores = {threads: scratch / f"a-{threads}.zarr" for threads in (1, cores)}

    def batch(threads: int | None) -> Any:
        return simulate_batch(
            system,
            parameters,
            duration,
            integrator=integrator,
            step=step,
            threads=threads,
            confirm=True,
        )

    def to_store(threads: int) -> Any:
        return sweep(system, vary, duration, out=stores[threads], threads=threads, confirm=True)

    def fresh() -> None:
        """The stores of the previous round removed (untimed): each timed call writes a new
        store, as a sweep to a new ``--out`` does (replacing one, ``overwrite=True``, also
        removes the old one's files: tens of ms of the file system's CPU for this grid)."""
        for path in stores.values():
            shutil.rmtree(path, ignore_errors=True)

    calls = {
        "batch_1": lambda: batch(1),
        "batch_all": lambda: batch(None),
        "memory_1": lambda: sweep(system, vary, duration, threads=1, confirm=True),
        "memory_all": lambda: sweep(system, vary, duration, threads=cores, confirm=True),
        "store_1": lambda: to_store(1),
        "store_all": lambda: to_store(cores),
    }
    times: dict[str, list[float]] = {name: [] for name in calls}
    cpu: dict[str, list[float]] = {name: [] for name in calls}
    results: dict[str, Any] = {}
    for round_ in range(repeats + 1):
        fresh()
        for name, call in calls.items():
            settle_disk()
            began, began_cpu = time.perf_counter(), time.process_time()
            results[name] = call()
            if round_:
                times[name].append(time.perf_counter() - began)
                cpu[name].append(time.process_time() - began_cpu)
    import xarray as xr

    one, every = (xr.open_zarr(stores[t]).load() for t in (1, cores))
    # the same runs, the same answers: the sweep's status is the batch's, and the store
    # written by one thread is the store written by all, bit for bit
    same_status = bool(
        np.array_equal(np.asarray(one["status"].values).ravel(), results["batch_1"].status)
        and np.array_equal(results["batch_1"].status, results["batch_all"].status)
    )
    identical = all(
        np.array_equal(one[name].values, every[name].values, equal_nan=True)
        for name in one.data_vars
    )
    for path in stores.values():
        shutil.rmtree(path, ignore_errors=True)
    best = {name: min(values) for name, values in times.items()}
    best_cpu = {name: min(values) for name, values in cpu.items()}
    base = best["batch_1"]
    return {
        "runs": count,
        "duration": duration,
        "cores": cores,
        "integrator": integrator,
        "step": step,
        "n_steps": int(results["batch_1"].n_steps),
        "best_s": best,
        "runs_per_s": {name: count / t for name, t in best.items()},
        "vs_one_core_batch": {name: base / t for name, t in best.items()},
        "best_cpu_s": best_cpu,
        "cpu_vs_one_core_batch": {name: best_cpu["batch_1"] / t for name, t in best_cpu.items()},
        "same_status": same_status,
        "identical_stores": identical,
        "batch_integrate_s": results["batch_1"].timings.get("integrate"),
        "times": times,
        "cpu_times": cpu,
    }


def timed_cluster_sweep(system, vary, duration, cluster: Cluster, repeats: int) -> float:
    """Best wall time of the sweep on the cluster, after a warm-up run of the same grid."""
    t, _ = best_of(
        lambda: sweep(system, vary, duration, scheduler=cluster.client, confirm=True), repeats
    )
    return t


def part_b(system, cluster: Cluster, runs: int, duration: float, repeats: int) -> dict[str, Any]:
    vary = square_grid(runs)
    count = n_runs(vary)
    cluster.add_worker()
    t1 = timed_cluster_sweep(system, vary, duration, cluster, repeats)
    cluster.add_worker()
    t2 = timed_cluster_sweep(system, vary, duration, cluster, repeats)
    rate1, rate2 = count / t1, count / t2
    return {
        "runs": count,
        "duration": duration,
        "one_worker_s": t1,
        "two_workers_s": t2,
        "one_worker_runs_per_s": rate1,
        "two_workers_runs_per_s": rate2,
        "speedup": rate2 / rate1,
        "efficiency": rate2 / (2 * rate1),
    }


def memory_counts(runs: int) -> list[int]:
    """The run counts of (c): a hundredth, a tenth and all of ``runs`` (at least 10^4 each)."""
    return sorted({max(10_000, runs // 100), max(10_000, runs // 10), max(10_000, runs)})


def part_c(
    system, cluster: Cluster, runs: int, duration: float, scratch: Path
) -> list[dict[str, Any]]:
    """Without slip refinement (``refine_slip=False``): the single-run refinement of every
    slipping run (a quarter of this grid) would take hours at 10^7 runs on two cores, and it
    holds nothing between runs; the memory question is the footprint against the run count."""
    out = []
    for count in memory_counts(runs):
        vary = cube_grid(count)
        store = scratch / f"c-{count}.zarr"
        processes = {"client": os.getpid()}
        processes.update({f"worker {i}": w.pid for i, w in enumerate(cluster.workers)})
        began = time.perf_counter()
        with PeakRSS(processes) as sampler:
            dataset = sweep(
                system,
                vary,
                duration,
                scheduler=cluster.client,
                out=store,
                overwrite=True,
                refine_slip=False,
                confirm=True,
            )
        elapsed = time.perf_counter() - began
        size = sum(p.stat().st_size for p in store.rglob("*") if p.is_file())
        statuses = np.bincount(np.asarray(dataset["status"].values).ravel(), minlength=7)
        entry = {
            "runs": n_runs(vary),
            "duration": duration,
            "wall_s": elapsed,
            "runs_per_s": n_runs(vary) / elapsed,
            "store_bytes": size,
            "chunk": dataset.attrs.get("chunk"),
            "samples": sampler.samples,
            "peak_rss": dict(sampler.peak),
            "halves": sampler.halves(),
            "status_counts": statuses.tolist(),
        }
        out.append(entry)
        print(
            f"(c) {entry['runs']:,} runs in {elapsed:.0f} s: "
            + ", ".join(
                f"{k} {v / 1e6:.0f} MB (halves {h[0] / 1e6:.0f} / {h[1] / 1e6:.0f})"
                for (k, v), h in zip(
                    entry["peak_rss"].items(), entry["halves"].values(), strict=True
                )
            ),
            flush=True,
        )
        del dataset
        shutil.rmtree(store, ignore_errors=True)
    return out


def mark(ok: bool) -> str:
    return "✔" if ok else "✘"


def show_a(results: dict[str, dict[str, Any]], repeats: int) -> None:
    for label, a in results.items():
        show_a_grid(label, a, repeats)


#: (a)'s rows: call, label, target ratio to the one-core batch kernel (None: none)
A_ROWS = [
    ("batch_1", "simulate_batch, threads=1 (the bare one-core batch kernel)", None),
    ("batch_all", "simulate_batch, every core", None),
    ("memory_1", "sweep, threads=1, in memory", None),
    ("memory_all", "sweep, every core, in memory", None),
    ("store_1", "sweep, threads=1, to a Zarr store", 0.90),
    ("store_all", "sweep, every core, to a Zarr store", "cores"),
]


def show_a_grid(label: str, a: dict[str, Any], repeats: int) -> None:
    rows = []
    for name, words, target in A_ROWS:
        ratio = a["vs_one_core_batch"][name]
        goal = 0.85 * a["cores"] if target == "cores" else target
        rows.append(
            [
                words,
                a["best_s"][name],
                a["runs_per_s"][name],
                ratio,
                "" if goal is None else f">= {goal:.2f} {mark(ratio >= goal)}",
                a["best_cpu_s"][name],
                a["cpu_vs_one_core_batch"][name],
            ]
        )
    print_table(
        f"(a) in-process, grid {label}: {a['runs']:,} runs of {a['duration']:g} s, "
        f"{a['integrator']} step {a['step']:.4g} s ({a['n_steps']} steps), {a['cores']} cores, "
        f"best of {repeats}",
        ["call", "wall (s)", "runs/s", "vs one-core batch", "target", "CPU (s)", "CPU ratio"],
        rows,
    )
    print(
        f"same status in every run: {mark(a['same_status'])}; the store of one thread is the "
        f"store of {a['cores']}, bit for bit: {mark(a['identical_stores'])}"
    )


def show_b(b: dict[str, Any]) -> None:
    print_table(
        f"(b) Dask: {b['runs']:,} runs of {b['duration']:g} s on a loopback cluster "
        "(dask scheduler + dask worker --nthreads 1 --no-nanny, NUMBA_NUM_THREADS=1)",
        ["workers", "wall (s)", "runs/s", "speed-up", "per worker", "target"],
        [
            [1, b["one_worker_s"], b["one_worker_runs_per_s"], 1.0, 1.0, ""],
            [
                2,
                b["two_workers_s"],
                b["two_workers_runs_per_s"],
                b["speedup"],
                b["efficiency"],
                f">= 0.80 {mark(b['efficiency'] >= 0.8)}",
            ],
        ],
    )


def show_c(c: list[dict[str, Any]], duration: float) -> None:
    rows = []
    for entry in c:
        for label, peak in entry["peak_rss"].items():
            first, second = entry["halves"][label]
            rows.append(
                [
                    f"{entry['runs']:,} runs: {label}",
                    peak / 1e6,
                    first / 1e6,
                    second / 1e6,
                    entry["wall_s"],
                    f"< 1000 MB {mark(peak < GB)}",
                ]
            )
    print_table(
        f"(c) peak RSS, two workers, runs of {duration:g} s written to a store, no "
        "slip refinement (sampled every 50 ms)",
        ["process", "peak RSS (MB)", "1st half", "2nd half", "sweep wall (s)", "target"],
        rows,
    )


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--runs", type=int, default=1 << 16)
    parser.add_argument("--duration", type=float, default=10.0)
    parser.add_argument("--repeat", type=int, default=3)
    parser.add_argument("--cluster-runs", type=int, default=1 << 16)
    parser.add_argument("--memory-runs", type=int, default=10_000_000)
    parser.add_argument("--memory-duration", type=float, default=1.0)
    parser.add_argument("--parts", default="abc", help="which parts to run (default abc)")
    parser.add_argument("--json", default=str(ROOT / "build" / "bench" / "sweep.json"))
    parser.add_argument(
        "--scratch",
        default=str(ROOT / "build" / "bench"),
        help="folder for the stores and the cluster's files (default build/bench: a store "
        "written where a user works, not the system's temporary folder)",
    )
    args = parser.parse_args()

    print(machine_note())
    system = rollspring.load_system(SYSTEM)
    report: dict[str, Any] = {"machine": machine_note(), "system": SYSTEM, "args": vars(args)}
    Path(args.scratch).mkdir(parents=True, exist_ok=True)
    with tempfile.TemporaryDirectory(prefix="bench-sweep-", dir=args.scratch) as tmp:
        scratch = Path(tmp)
        report["file_system"] = file_system_cost(scratch)
        print(describe_file_system(report["file_system"], scratch))
        if "a" in args.parts:
            report["in_process"] = part_a(system, args.runs, args.duration, args.repeat, scratch)
            show_a(report["in_process"], args.repeat)
        if "b" in args.parts or "c" in args.parts:
            cluster = Cluster(scratch)
            try:
                if "b" in args.parts:
                    report["dask_scaling"] = part_b(
                        system, cluster, args.cluster_runs, args.duration, args.repeat
                    )
                    show_b(report["dask_scaling"])
                if "c" in args.parts:
                    while len(cluster.workers) < 2:
                        cluster.add_worker()
                    report["memory"] = part_c(
                        system, cluster, args.memory_runs, args.memory_duration, scratch
                    )
                    show_c(report["memory"], args.memory_duration)
            finally:
                cluster.stop()
    report["load_average_at_end"] = os.getloadavg()[0]
    print(f"load average at the end: {report['load_average_at_end']:.2f}")
    target = Path(args.json)
    target.parent.mkdir(parents=True, exist_ok=True)
    target.write_text(json.dumps(report, indent=2) + "\n")
    print(f"\nwrote {target}")


if __name__ == "__main__":
    main()

"""rollspring sweep on a real Dask cluster on loopback: a scheduler and two workers started
from their command lines (one cluster for the module), compared bit for bit with the
in-process sweep; a worker killed mid-sweep; every worker replaced mid-sweep (the scattered
plan lost); chunks' keys cancelled on the scheduler; the client killed mid-sweep and the
command rerun (only the unfinished chunks run); another sweep's store refused."""

from __future__ import annotations

import json
import os
import re
import signal
import subprocess
import sys
import time
from collections.abc import Iterator
from pathlib import Path

import numpy as np
import pytest
import xarray as xr

import rollspring
from rollspring.service.sweeps import sweep

pytestmark = pytest.mark.slow

DASK = str(Path(sys.executable).with_name("dask"))
SYSTEM = "hoop-cylinder"
#: 10 x 10 x 20 = 2000 runs, some slipping (refined one by one), 10 s each
VARY = {
    "bodies.hoop.mass": np.linspace(0.5, 2.0, 10).tolist(),
    "bodies.hoop.mu_static": [0.02, 0.03, 0.04, 0.05, 0.06, 0.08, 0.1, 0.2, 0.5, 1.0],
    "springs.0.stiffness": np.linspace(50.0, 200.0, 20).tolist(),
}
SPECS = [
    "--vary",
    "bodies.hoop.mass=0.5:2.0:10",
    "--vary",
    "bodies.hoop.mu_static=0.02,0.03,0.04,0.05,0.06,0.08,0.1,0.2,0.5,1.0",
    "--vary",
    "springs.0.stiffness=50:200:20",
]
DURATION = 10.0
CHUNK = 40  # 50 chunks
#: The rollspring command.
CLI = [
    sys.executable,
    "-c",
    "import sys; from rollspring.cli.app import app; app(args=sys.argv[1:])",
]


class Cluster:
    """A scheduler and workers, each a ``dask`` command-line process."""

    def __init__(self, folder: Path) -> None:
        self.folder = folder
        self.file = folder / "scheduler.json"
        self.env = {**os.environ, "PYTHONWARNINGS": "ignore"}
        self.scheduler = self._start(
            [
                DASK,
                "scheduler",
                "--host",
                "127.0.0.1",
                "--port",
                "0",
                "--scheduler-file",
                str(self.file),
                "--no-dashboard",
            ],
            "scheduler",
        )
        deadline = time.monotonic() + 60
        while not self.file.exists() or not self.file.read_text().strip():
            assert time.monotonic() < deadline, "the scheduler did not start"
            assert self.scheduler.poll() is None, "the scheduler exited"
            time.sleep(0.2)
        time.sleep(0.2)
        self.address = json.loads(self.file.read_text())["address"]
        self.workers = [self.start_worker() for _ in range(2)]
        self.wait_for_workers(2)

    def _start(self, args: list[str], name: str) -> subprocess.Popen:
        with open(self.folder / f"{name}-{time.monotonic_ns()}.log", "w") as log:
            return subprocess.Popen(
                args, stdout=log, stderr=subprocess.STDOUT, env=self.env, cwd=self.folder
            )

    def start_worker(self) -> subprocess.Popen:
        return self._start(
            [
                DASK,
                "worker",
                "--scheduler-file",
                str(self.file),
                "--nthreads",
                "1",
                "--no-dashboard",
            ],
            "worker",
        )

    def wait_for_workers(self, n: int) -> None:
        from distributed import Client

        with Client(self.address, timeout=30, set_as_default=False) as client:
            client.wait_for_workers(n, timeout=120)

    def close(self) -> None:
        for process in [*self.workers, self.scheduler]:
            if process.poll() is None:
                process.terminate()
        for process in [*self.workers, self.scheduler]:
            try:
                process.wait(timeout=20)
            except subprocess.TimeoutExpired:
                process.kill()
                process.wait()


@pytest.fixture(scope="module")
def cluster(tmp_path_factory):
    cluster = Cluster(tmp_path_factory.mktemp("cluster"))
    try:
        yield cluster
    finally:
        cluster.close()


@pytest.fixture(scope="module")
def reference(tmp_path_factory):
    """The same sweep in this process (in memory)."""
    return sweep(rollspring.load_system(SYSTEM), VARY, DURATION, chunk=CHUNK)


def same(a: xr.Dataset, b: xr.Dataset) -> None:
    assert sorted(a.data_vars) == sorted(b.data_vars)
    for name in a.data_vars:
        x, y = np.asarray(a[name].values), np.asarray(b[name].values)
        assert x.dtype == y.dtype and x.shape == y.shape, name
        assert np.array_equal(x, y, equal_nan=x.dtype.kind == "f"), name


def markers(store: Path) -> set[int]:
    folder = store / ".rollspring-done"
    return {int(p.name) for p in folder.iterdir() if p.name.isdigit()} if folder.is_dir() else set()


#: every sweep command started, so that a failed test leaves none running (nor its pipes
#: open) into the next tests
STARTED: list[subprocess.Popen] = []


@pytest.fixture(autouse=True)
def no_leftover_sweeps() -> Iterator[None]:
    yield
    while STARTED:
        process = STARTED.pop()
        if process.poll() is None:
            process.kill()
        process.communicate()


def run_cli(store: Path, address: str, *extra: str) -> subprocess.Popen:
    process = subprocess.Popen(
        [
            *CLI,
            "sweep",
            SYSTEM,
            *SPECS,
            "-T",
            str(DURATION),
            "--chunk",
            str(CHUNK),
            "--out",
            str(store),
            "--scheduler",
            address,
            *extra,
        ],
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
    )
    STARTED.append(process)
    return process


def wait_for_markers(store: Path, process: subprocess.Popen, at_least: int) -> None:
    deadline = time.monotonic() + 300
    while len(markers(store)) < at_least:
        if process.poll() is not None:
            pytest.fail(f"the sweep ended early: {process.communicate()}")
        assert time.monotonic() < deadline
        time.sleep(0.05)


def test_grid_size(reference):
    assert reference["status"].size >= 2000
    status = reference["status"].values
    assert (status == 2).sum() > 100 and (status == 0).sum() > 100  # slips and full runs


def test_cluster_equals_in_process(cluster, reference, tmp_path):
    from distributed import Client

    with Client(cluster.address, timeout=30, set_as_default=False) as client:
        result = sweep(
            rollspring.load_system(SYSTEM),
            VARY,
            DURATION,
            chunk=CHUNK,
            scheduler=client,
            out=tmp_path / "c.zarr",
        )
        # each worker has its own Numba cache directory
        caches = client.run(lambda: os.environ.get("NUMBA_CACHE_DIR"))
    assert len(set(caches.values())) == 2 and all(caches.values())
    same(result.load(), reference)
    assert markers(tmp_path / "c.zarr") == set(range(50))


def test_worker_killed_mid_sweep(cluster, reference, tmp_path):
    store = tmp_path / "k.zarr"
    process = run_cli(store, cluster.address)
    wait_for_markers(store, process, 5)
    victim = cluster.workers.pop(0)
    victim.send_signal(signal.SIGKILL)
    victim.wait()
    _out, err = process.communicate(timeout=600)
    assert process.returncode == 0, err
    cluster.workers.append(cluster.start_worker())
    same(xr.open_zarr(store).load(), reference)
    assert markers(store) == set(range(50))
    cluster.wait_for_workers(2)


def test_every_worker_replaced_mid_sweep(cluster, reference, tmp_path):
    """Both workers SIGKILLed mid-sweep and two new ones started: the scattered plan died with
    them (its dependents are cancelled, "lost dependencies"), so it is scattered again and the
    chunks in flight computed again; the store is the in-process sweep's, bit for bit."""
    store = tmp_path / "replaced.zarr"
    process = run_cli(store, cluster.address)
    wait_for_markers(store, process, 5)
    victims, cluster.workers = cluster.workers, []
    for victim in victims:
        victim.send_signal(signal.SIGKILL)
    for victim in victims:
        victim.wait()
    cluster.workers = [cluster.start_worker() for _ in range(2)]
    _out, err = process.communicate(timeout=600)
    assert process.returncode == 0, err
    assert re.search(r"chunk \d+: cancelled on the cluster \(.+\); computing it again", err), err
    assert markers(store) == set(range(50))
    same(xr.open_zarr(store).load(), reference)
    cluster.wait_for_workers(2)


def test_chunk_cancelled_on_the_cluster_is_computed_again(cluster, reference, tmp_path):
    """A chunk's key cancelled under the sweep (what distributed does when a worker is lost
    with a result in a race: "Couldn't gather ..., rescheduling", then the key cancelled) is
    submitted again, and the store is the in-process sweep's, bit for bit."""
    from distributed import Client

    store = tmp_path / "cancel.zarr"
    process = run_cli(store, cluster.address)
    wait_for_markers(store, process, 2)

    def cancel_wanted(dask_scheduler, client_id):
        """Cancel every chunk the sweep still wants (in flight, or computed but not yet taken
        by it), in one go on the scheduler's loop: none can be taken in between."""
        keys = sorted(
            key
            for key, task in dask_scheduler.tasks.items()
            if str(key).startswith("rollspring-sweep-") and task.who_wants
        )
        dask_scheduler.stimulus_cancel(
            keys, client_id, force=True, reason="test", msg="cancelled by the test"
        )
        return keys

    with Client(cluster.address, timeout=30, set_as_default=False) as other:
        keys = other.run_on_scheduler(cancel_wanted, client_id=other.id)
    assert keys  # up to 2 x workers + 2 chunks are wanted at any moment of the sweep
    _out, err = process.communicate(timeout=600)
    assert process.returncode == 0, err
    again = {int(i) for i in re.findall(r"chunk (\d+): cancelled on the cluster", err)}
    assert again and again <= {int(k.rsplit("-", 1)[1]) for k in keys}, (again, keys)
    assert "(attempt 2 of 4)" in err
    assert markers(store) == set(range(50))
    same(xr.open_zarr(store).load(), reference)


def test_client_killed_mid_sweep_then_resumed(cluster, reference, tmp_path):
    store = tmp_path / "resume.zarr"
    process = run_cli(store, cluster.address)
    wait_for_markers(store, process, 8)
    process.send_signal(signal.SIGKILL)
    process.communicate()
    finished = markers(store)
    assert 8 <= len(finished) < 50
    process = run_cli(store, cluster.address)
    _out, err = process.communicate(timeout=600)
    assert process.returncode == 0, err
    ran = re.search(r"ran (\d+) of (\d+) chunks \((\d+) already done", err)
    assert ran is not None, err
    # every marker the kill left counts, but one it cut short (created, its list of chunks
    # left out unwritten: store.mark_done), whose chunk runs again
    done_before = int(ran.group(3))
    assert len(finished) - 1 <= done_before <= len(finished)
    assert int(ran.group(1)) == 50 - done_before and int(ran.group(2)) == 50
    assert markers(store) == set(range(50))
    same(xr.open_zarr(store).load(), reference)
    # a third run has nothing left to do
    process = run_cli(store, cluster.address)
    _out, err = process.communicate(timeout=600)
    assert process.returncode == 0 and "ran 0 of 50 chunks (50 already done" in err


def test_other_sweep_refused_on_the_cluster(cluster, tmp_path):
    store = tmp_path / "m.zarr"
    process = run_cli(store, cluster.address, "--metric", "period_measured")
    _out, err = process.communicate(timeout=600)
    assert process.returncode == 0, err
    process = run_cli(store, cluster.address)  # other metrics: another sweep
    _out, err = process.communicate(timeout=600)
    assert process.returncode == 2
    assert err.startswith("error: ") and err.count("\n") == 1 and "holds another sweep" in err
    assert "Traceback" not in err

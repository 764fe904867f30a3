"""A pool of worker processes that run the web API's computations under a time budget.

An endpoint (a plain ``def``, run in FastAPI's thread pool) hands its job to an idle worker
process and waits for the answer. A job that runs past its budget cannot be stopped inside a
thread, so its worker *process* is killed and replaced, and the request gets HTTP 503 while the
other workers go on serving. When every worker is busy for longer than the budget, a request is
refused the same way instead of waiting in an unbounded queue (uvicorn's concurrency limit
refuses the excess at once before that).

Workers are forked from a ``forkserver`` that has already imported the scientific stack and
rollspring and compiled the kernels (``PRELOAD``), so a replacement starts warm in milliseconds;
a worker takes jobs only once it has said it is ready, and the pool starts (the server answers)
only once every first worker has.
"""

from __future__ import annotations

import contextlib
import multiprocessing
import os
import queue
import threading
from collections.abc import Callable
from multiprocessing.connection import Connection
from typing import Any

from rollspring.errors import JobFailed, OverBudget, Overloaded, ServeError

__all__ = [
    "MAX_BUDGET",
    "PRELOAD",
    "ComputePool",
    "JobFailed",
    "OverBudget",
    "Overloaded",
    "check_pool",
    "max_workers",
    "pool_size",
]

#: Modules the forkserver imports once, so that every worker starts with them loaded and with
#: the compiled kernels warm (:mod:`rollspring.web.warm`).
PRELOAD = ["rollspring.web.warm"]
#: How long a new worker may take to become ready (a cold Numba cache compiles the kernels).
READY_TIMEOUT = 300.0
#: The longest time budget of one computation (s): a day; an unbounded one is no budget.
MAX_BUDGET = 86400.0
#: Worker processes per core at the most (a computation keeps a core busy: more only queue).
WORKERS_PER_CORE = 4


def max_workers() -> int:
    """The most worker processes a pool may have: :data:`WORKERS_PER_CORE` per core."""
    return WORKERS_PER_CORE * (os.cpu_count() or 1)


def pool_size(workers: int | None) -> int:
    """How many worker processes a pool of ``workers`` has (None or 0: one per core)."""
    return max(1, workers or os.cpu_count() or 1)


def check_pool(workers: Any, budget: Any, *, option: str = "") -> tuple[int | None, float]:
    """``workers`` (None or 0: one per core; at most :func:`max_workers`) and ``budget``
    (seconds, positive, at most :data:`MAX_BUDGET`) checked: one-line
    :class:`~rollspring.errors.ServeError` naming ``option + name`` (``--`` on the command
    line) before a process starts."""
    if workers is not None and (isinstance(workers, bool) or not isinstance(workers, int)):
        raise ServeError(f"{option}workers: must be a whole number, got {workers!r}")
    if workers is not None and not 0 <= workers <= max_workers():
        raise ServeError(
            f"{option}workers: must be 0 (one per core) to {max_workers()} "
            f"({WORKERS_PER_CORE} per core), got {workers}"
        )
    if isinstance(budget, bool) or not isinstance(budget, int | float):
        raise ServeError(f"{option}budget: must be a number of seconds, got {budget!r}")
    if not 0 < budget <= MAX_BUDGET:
        raise ServeError(
            f"{option}budget: must be a positive number of seconds up to {MAX_BUDGET:g} "
            f"(a day), got {budget:g}"
        )
    return workers or None, float(budget)


class _Worker:
    def __init__(self, context: Any) -> None:
        self.connection, child = context.Pipe()
        self.process = context.Process(
            target=_serve, args=(child,), daemon=True, name="rollspring-worker"
        )
        self.process.start()
        child.close()

    def wait_ready(self, timeout: float = READY_TIMEOUT) -> bool:
        """Wait for the worker's "ready" (sent once it is warm); False if it never came."""
        try:
            return bool(self.connection.poll(timeout)) and self.connection.recv() == "ready"
        except (OSError, EOFError):
            return False

    def kill(self) -> None:
        with contextlib.suppress(Exception):
            self.process.kill()
        with contextlib.suppress(Exception):
            self.process.join(timeout=5)
        with contextlib.suppress(Exception):
            self.connection.close()


class ComputePool:
    """``size`` worker processes; :meth:`run` runs one job with a time budget (s).
    ``progress(ready, size)`` is called as each first worker becomes ready (warm)."""

    def __init__(
        self,
        size: int | None = None,
        budget: float = 10.0,
        *,
        progress: Callable[[int, int], None] | None = None,
    ) -> None:
        size, budget = check_pool(size, budget)
        self.size = pool_size(size)
        self.budget = float(budget)
        self._context = multiprocessing.get_context("forkserver")
        self._context.set_forkserver_preload(PRELOAD)
        self._idle: queue.Queue[_Worker] = queue.Queue()
        self._all: set[_Worker] = set()
        self._lock = threading.Lock()
        self._closed = False
        self.replaced = 0  # workers killed for running past the budget (or dying)
        try:
            starting = [self._start() for _ in range(self.size)]
            for ready, worker in enumerate(starting, 1):  # serve only once warm: no request
                if not worker.wait_ready():  # pays for a compilation
                    raise RuntimeError("a worker process did not start (see its error above)")
                self._idle.put(worker)
                if progress is not None:
                    progress(ready, self.size)
        except BaseException:  # a failure, Ctrl-C or SIGTERM while starting: no worker is left
            self.close()
            raise

    def _start(self) -> _Worker:
        worker = _Worker(self._context)
        with self._lock:
            self._all.add(worker)
        return worker

    def _replace(self, worker: _Worker) -> None:
        worker.kill()
        with self._lock:
            self._all.discard(worker)
            self.replaced += 1
            closed = self._closed
        if not closed:
            fresh = self._start()
            # it joins the idle workers once warm, without holding up the request that failed
            threading.Thread(target=self._join_when_ready, args=(fresh,), daemon=True).start()

    def _join_when_ready(self, worker: _Worker) -> None:
        if worker.wait_ready():
            self._idle.put(worker)
        else:
            self._replace(worker)

    def run(self, job: str, payload: Any, *, budget: float | None = None) -> Any:
        """Run ``rollspring.web.jobs.<job>(payload)`` in a worker and return its result.

        Raises :class:`Overloaded` when no worker is free within the budget,
        :class:`OverBudget` when the job runs past it (the worker is replaced) and
        :class:`JobFailed` when the job raises."""
        limit = self.budget if budget is None else budget
        try:
            worker = self._idle.get(timeout=limit)
        except queue.Empty:
            raise Overloaded(
                f"the server is busy: no worker was free within {limit:g} s; try again"
            ) from None
        try:
            worker.connection.send((job, payload))
            ready = worker.connection.poll(limit)
        except (OSError, EOFError, BrokenPipeError):
            self._replace(worker)
            raise JobFailed("crash", "a worker process died; try again") from None
        if not ready:
            self._replace(worker)
            raise OverBudget(
                f"the computation ran past its time budget of {limit:g} s and was "
                "abandoned; ask for less (a shorter duration, fewer outputs, a "
                "larger rtol)"
            )
        try:
            status, value = worker.connection.recv()
        except (OSError, EOFError):
            self._replace(worker)
            raise JobFailed("crash", "a worker process died; try again") from None
        self._idle.put(worker)
        if status == "ok":
            return value
        kind, message, loc = value
        raise JobFailed(kind, message, tuple(loc))

    def close(self) -> None:
        """Stop every worker."""
        with self._lock:
            self._closed = True
            workers = list(self._all)
            self._all.clear()
        for worker in workers:
            worker.kill()


def _serve(connection: Connection) -> None:
    """A worker's loop: warm up, then answer ``(job, payload)`` messages until the pipe
    closes."""
    from rollspring.web import jobs

    jobs.warm_up()  # already warm when forked from the forkserver (PRELOAD): then instant
    connection.send("ready")
    while True:
        try:
            job, payload = connection.recv()
        except (EOFError, OSError, KeyboardInterrupt):
            return
        connection.send(jobs.execute(job, payload))

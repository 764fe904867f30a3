"""What a run will cost, known before it starts, and the bound above which it needs confirming.

The estimates themselves live with what they estimate, so that each public function can refuse
a run too large to start unasked: :func:`analysis_cost` and :func:`derivation_cost` here (for
:func:`rollspring.analyze` and :func:`rollspring.derive`), the simulation's in
:mod:`rollspring.simulate.costs`, the report's in :mod:`rollspring.service.costs` (which
gathers them all for the command line). :func:`check_cost` refuses a run above
:data:`MAX_SECONDS` or :data:`MAX_MEMORY` unless it is confirmed: ``--yes`` on the command line,
``confirm=True`` (:data:`CONFIRM`) in Python, with the same one-line message otherwise.

The constants are measurements on a laptop core (``bench/``), rounded up: an estimate is meant
to be right within a factor of a few, enough to tell seconds from days.
"""

from __future__ import annotations

import os
from dataclasses import dataclass

from rollspring.errors import CostTooHigh
from rollspring.model import System

__all__ = [
    "CONFIRM",
    "MAX_MEMORY",
    "MAX_SECONDS",
    "RTOL_RANGE",
    "Cost",
    "analysis_cost",
    "check_cost",
    "derivation_cost",
    "describe_bytes",
    "describe_duration",
]

#: A run estimated to take longer than this (seconds) needs confirming.
MAX_SECONDS = 300.0
#: A run whose outputs need more memory than this (bytes) needs confirming.
MAX_MEMORY = 2 * 1024**3
#: The relative accuracies a simulation can be asked for: finer than 1e-14 is below what double
#: precision delivers over a run (a step too small to move t), coarser than 0.1 is no accuracy.
RTOL_RANGE = (1e-14, 0.1)
#: How a Python caller confirms a run above the bound (the command line's ``--yes``).
CONFIRM = "confirm=True"

#: an analysis of n bodies: seconds ≈ 1 + this × n³
_ANALYSIS_PER_BODY_CUBED = 3.5e-7
#: the banded path, n bodies and k modes: seconds ≈ 1 + this × n + the next × n k
_ANALYSIS_PER_BODY = 5e-4
_ANALYSIS_PER_BODY_AND_MODE = 2e-6
#: analysis.banded.DENSE_LIMIT and ALL_MODES_LIMIT (this leaf module imports nothing of them)
_DENSE_LIMIT, _ALL_MODES_LIMIT = 64, 2000
#: a derivation of n bodies: seconds ≈ 10 + this × n^1.5
_DERIVATION_PER_BODY = 0.15


@dataclass(frozen=True)
class Cost:
    """An estimate: ``what`` it is of ("this run"), ``steps`` (None for an analysis),
    ``bodies``, ``seconds`` and ``memory`` (bytes)."""

    what: str
    bodies: int
    seconds: float
    memory: float = 0.0
    steps: float | None = None
    integrator: str = ""
    #: how to make it smaller (for the message)
    smaller: str = "fewer bodies"
    #: runs of a batch or sweep (``steps`` then counts a run's steps)
    runs: int | None = None
    #: what the memory holds ("outputs"; "a store" for a sweep written to disk)
    holds: str = "outputs"

    def describe(self) -> str:
        """One line: the time, then what it comes from (steps × bodies, runs) and the memory."""
        bodies = f"{self.bodies} bod{'y' if self.bodies == 1 else 'ies'}"
        line = f"about {describe_duration(self.seconds)}: "
        if self.runs is not None:
            line += f"{_count(self.runs)} runs × "
        if self.steps is not None:
            line += f"about {_count(self.steps)} {self.integrator} steps × {bodies}"
        else:
            line += bodies
        if self.memory:
            line += f", {describe_bytes(self.memory)} of {self.holds}"
        return line

    @property
    def long(self) -> bool:
        """Whether the estimate is worth telling before the run (over half a minute)."""
        return self.seconds > 30.0


def check_cost(cost: Cost, *, confirmed: bool, flag: str = "--yes") -> None:
    """Raise :class:`~rollspring.errors.CostTooHigh` when ``cost`` is above :data:`MAX_SECONDS`
    or :data:`MAX_MEMORY` and the run is not ``confirmed`` (the message says to confirm it with
    ``flag``: ``--yes``, or :data:`CONFIRM` in Python), or (confirmed or not) when its outputs
    cannot fit in this machine's memory at all. Made before any long work."""
    physical = _physical_memory()
    if physical is not None and cost.memory > physical:
        raise CostTooHigh(
            f"{cost.what} cannot fit in memory: {describe_bytes(cost.memory)} of outputs, more "
            f"than this machine's {describe_bytes(physical)} ({cost.describe()}); make it smaller "
            f"({cost.smaller})"
        )
    if confirmed:
        return
    if cost.seconds > MAX_SECONDS or cost.memory > MAX_MEMORY:
        raise CostTooHigh(
            f"{cost.what} would take {cost.describe()}, above the bound of "
            f"{describe_duration(MAX_SECONDS)} and {describe_bytes(MAX_MEMORY)}; make it smaller "
            f"({cost.smaller}) or confirm it with {flag}"
        )


def analysis_cost(
    system: System, what: str = "the analysis", modes: int | tuple[int, int] | None = None
) -> Cost:
    """The estimated cost of :func:`rollspring.analyze` on ``system`` (with its ``modes``
    argument), measured on chains: with dense matrices (up to 64 bodies) it grows with the cube
    of the number of bodies; on the banded path with n times the modes computed (every mode:
    about 2 s for 1000 bodies, 6 s for 2000, the lowest 20 beyond 2000 bodies), whose shapes
    and forces take some 80 bytes per body and mode."""
    n = len(system.bodies)
    if n <= _DENSE_LIMIT:
        return Cost(what, n, 1.0 + _ANALYSIS_PER_BODY_CUBED * n**3)
    if modes is None:
        count = n if n <= _ALL_MODES_LIMIT else min(n, 20)
    elif isinstance(modes, tuple):
        count = max(0, int(modes[-1]) - int(modes[0]) + 1)
    else:
        count = max(0, int(modes))
    return Cost(
        what,
        n,
        1.0 + _ANALYSIS_PER_BODY * n + _ANALYSIS_PER_BODY_AND_MODE * n * count,
        memory=80.0 * n * count,
        smaller="fewer bodies or fewer modes",
    )


def derivation_cost(system: System, what: str = "the derivation") -> Cost:
    """The estimated cost of :func:`rollspring.derive` on ``system`` (every method, SymPy): it
    grows as n^1.5."""
    n = len(system.bodies)
    return Cost(what, n, 10.0 + _DERIVATION_PER_BODY * n**1.5)


def _physical_memory() -> float | None:
    try:
        return float(os.sysconf("SC_PAGE_SIZE") * os.sysconf("SC_PHYS_PAGES"))
    except (AttributeError, ValueError, OSError):
        return None


def _count(value: float) -> str:
    return f"{value:.0f}" if value < 1e6 else f"{value:.2g}"


def describe_duration(seconds: float) -> str:
    """A duration for a message: the largest unit that gives at least 2 (years, days, hours,
    min), else seconds to two significant digits (at least 0.1 s)."""
    for size, unit in ((86400 * 365, "years"), (86400, "days"), (3600, "hours"), (60, "min")):
        if seconds >= 2 * size:
            value = seconds / size
            return f"{value:.3g} {unit}" if value < 1e6 else f"{value:.2g} {unit}"
    return f"{max(seconds, 0.1):.2g} s"


def describe_bytes(value: float) -> str:
    """A size for a message in binary units (TiB, GiB, MiB, KiB) to three digits, or bytes."""
    for size, unit in ((1024**4, "TiB"), (1024**3, "GiB"), (1024**2, "MiB"), (1024, "KiB")):
        if value >= size:
            return f"{value / size:.3g} {unit}"
    return f"{value:.0f} bytes"

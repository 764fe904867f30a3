"""What a run will cost, known before it starts: steps × bodies, seconds, memory.

The command line refuses a run whose estimate is above a sane bound unless the user confirms it
(``--yes``), and says how long a confirmed long run should take; the estimate is made in well
under a second, before any long work.

* A simulation (:func:`simulation_cost`): its step comes from the highest linear frequency at the
  initial placement and ``rtol``, exactly as :func:`rollspring.simulate.choose_scheme` chooses it
  (the compiled symplectic schemes); damped springs run DOP853, whose adaptive steps are
  estimated from the same frequency. Seconds follow from steps × (bodies + springs) at the
  measured cost of a body and step (docs/system-files.md), memory from the output arrays (and
  the CSV text when files are written).
* An analysis (:func:`analysis_cost`): its time grows with the cube of the number of bodies
  (dense matrices of the modes and the friction each body needs), measured on chains: 1 s for
  100 bodies, 6 min for 1000.
* A derivation (:func:`derivation_cost`, SymPy) as n^1.5; a report (:func:`report_cost`) is an
  analysis, a simulation of at most 20 s and, unless left out, a derivation.

The constants are measurements on a laptop core (``bench/``), rounded up: an estimate is meant
to be right within a factor of a few, enough to tell seconds from days.
"""

from __future__ import annotations

import math
import os
from dataclasses import dataclass
from typing import Any

import numpy as np

from rollspring.errors import CostTooHigh, SimulationError
from rollspring.model import System

__all__ = [
    "MAX_MEMORY",
    "MAX_SECONDS",
    "RTOL_RANGE",
    "Cost",
    "analysis_cost",
    "check_cost",
    "derivation_cost",
    "report_cost",
    "simulation_cost",
]

#: A run estimated to take longer than this (seconds) needs confirming.
MAX_SECONDS = 300.0
#: A run whose outputs need more memory than this (bytes) needs confirming.
MAX_MEMORY = 2 * 1024**3
#: The relative accuracies a simulation can be asked for: finer than 1e-14 is below what double
#: precision delivers over a run (a step too small to move t), coarser than 0.1 is no accuracy.
RTOL_RANGE = (1e-14, 0.1)

#: seconds per body (or spring) and step of a compiled symplectic step, all its stages
_SYMPLECTIC_BODY_STEP = 1.5e-6
#: seconds per DOP853 step (SciPy's Python loop), and per body of it
_DOP853_STEP, _DOP853_BODY_STEP = 1e-3, 3e-5
#: DOP853 steps per radian of the fastest mode at rtol 1e-8, and how they grow as rtol falls
_DOP853_STEPS_PER_RADIAN, _DOP853_ORDER = 1.5, 7.0
#: the largest step × decay rate DOP853 stays stable at (its stability region on the real axis)
_DOP853_STABILITY = 3.0
#: setup (equilibrium, stiffness matrices, eigensolvers) of a simulation of n bodies: this many
#: seconds × (n/1000)² (the stiffness matrix is O(n²) Python work)
_SETUP_PER_SQUARED_THOUSAND = 150.0
#: an analysis of n bodies: seconds ≈ 1 + this × n³
_ANALYSIS_PER_BODY_CUBED = 3.5e-7
#: a derivation of n bodies: seconds ≈ 10 + this × n^1.5
_DERIVATION_PER_BODY = 0.15
#: the longest simulation a report makes by itself (its default duration), s
_REPORT_DURATION = 20.0
#: bytes per output number: the arrays and their copies; with files, the CSV text and the table
_BYTES_IN_MEMORY, _BYTES_WRITTEN = 16, 40


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

    def describe(self) -> str:
        """One line: the time, then what it comes from (steps × bodies) and the memory."""
        bodies = f"{self.bodies} bod{'y' if self.bodies == 1 else 'ies'}"
        line = f"about {_duration(self.seconds)}: "
        if self.steps is not None:
            line += f"about {_count(self.steps)} {self.integrator} steps × {bodies}"
        else:
            line += bodies
        if self.memory:
            line += f", {_bytes(self.memory)} of outputs"
        return line

    @property
    def long(self) -> bool:
        """Whether the estimate is worth telling before the run (over half a minute)."""
        return self.seconds > 30.0


def check_cost(cost: Cost, *, confirmed: bool, flag: str = "--yes") -> None:
    """Raise :class:`~rollspring.errors.CostTooHigh` when ``cost`` is above :data:`MAX_SECONDS`
    or :data:`MAX_MEMORY` and the run is not ``confirmed``, or (confirmed or not) when its
    outputs cannot fit in this machine's memory at all."""
    physical = _physical_memory()
    if physical is not None and cost.memory > physical:
        raise CostTooHigh(
            f"{cost.what} cannot fit in memory: {_bytes(cost.memory)} of outputs, more than "
            f"this machine's {_bytes(physical)} ({cost.describe()}); make it smaller "
            f"({cost.smaller})"
        )
    if confirmed:
        return
    if cost.seconds > MAX_SECONDS or cost.memory > MAX_MEMORY:
        raise CostTooHigh(
            f"{cost.what} would take {cost.describe()}, above the bound of "
            f"{_duration(MAX_SECONDS)} and {_bytes(MAX_MEMORY)}; make it smaller "
            f"({cost.smaller}) or confirm it with {flag}"
        )


def simulation_cost(
    system: System,
    duration: Any,
    *,
    rtol: Any = 1e-8,
    integrator: Any = "auto",
    outputs: Any = 2001,
    written: bool = False,
    what: str = "this run",
) -> Cost:
    """The estimated cost of ``simulate(system, duration, rtol=..., integrator=...,
    n_output=outputs)``, its files too when ``written``. The arguments are checked first,
    with the messages of :func:`rollspring.simulate` (:class:`~rollspring.errors.SimulationError`
    naming the argument); ``rtol`` must also be within :data:`RTOL_RANGE`."""
    from rollspring.simulate import INTEGRATORS, choose_scheme
    from rollspring.simulate.arguments import check_choice, check_count, check_duration, check_rtol

    duration = check_duration(duration)
    rtol = check_rtol(rtol)
    low, high = RTOL_RANGE
    if not low <= rtol <= high:
        raise SimulationError(
            f"rtol: must be between {low:g} and {high:g} (finer is below what double precision "
            f"delivers), got {rtol!r}"
        )
    check_choice("integrator", integrator, INTEGRATORS, "integrator")
    n_output = check_count("n_output", outputs, 2)
    n = len(system.bodies)
    springs = len(system.springs)
    omega, rate = _highest_rates(system)
    damped = any(spring.damping > 0 for spring in system.springs)
    setup = 0.05 + _SETUP_PER_SQUARED_THOUSAND * (n / 1000.0) ** 2
    if damped or integrator == "dop853":
        name = "dop853"
        radians = max(omega * duration, 2 * math.pi)
        steps = radians * _DOP853_STEPS_PER_RADIAN * (1e-8 / rtol) ** (1.0 / _DOP853_ORDER)
        # an explicit scheme is stable only for steps below ~3.3/rate of the fastest damping
        steps = max(steps, rate * duration / _DOP853_STABILITY)
        seconds = setup + steps * (_DOP853_STEP + _DOP853_BODY_STEP * n)
    else:
        name, step = choose_scheme(omega, duration, rtol, integrator)
        steps = max(1.0, duration / step)
        from rollspring.simulate.integrators import INTEGRATORS as SCHEMES

        stages = SCHEMES[name].stages / SCHEMES["kahanli8"].stages  # measured on kahanli8
        seconds = setup + steps * stages * _SYMPLECTIC_BODY_STEP * (n + springs)
    numbers = n_output * (8 * n + 2 * springs + 6)
    memory = numbers * (_BYTES_IN_MEMORY + (_BYTES_WRITTEN if written else 0))
    return Cost(
        what, n, seconds, float(memory), steps, name, "a shorter --duration, fewer --outputs"
    )


def analysis_cost(system: System, what: str = "the analysis") -> Cost:
    """The estimated cost of :func:`rollspring.analyze` on ``system``."""
    n = len(system.bodies)
    return Cost(what, n, 1.0 + _ANALYSIS_PER_BODY_CUBED * n**3)


def derivation_cost(system: System, what: str = "the derivation") -> Cost:
    """The estimated cost of :func:`rollspring.derive` on ``system`` (every method)."""
    n = len(system.bodies)
    return Cost(what, n, 10.0 + _DERIVATION_PER_BODY * n**1.5)


def report_cost(
    system: System,
    *,
    duration: Any = None,
    derivation: bool = True,
    what: str = "the report",
) -> Cost:
    """The estimated cost of :func:`rollspring.build_report` on ``system``: the analysis, the
    simulation (``duration``, default at most 20 s) and, with ``derivation``, the derivation."""
    run = simulation_cost(system, _REPORT_DURATION if duration is None else duration, what=what)
    seconds = 5.0 + analysis_cost(system).seconds + run.seconds
    if derivation:
        seconds += derivation_cost(system).seconds
    return Cost(what, run.bodies, seconds, run.memory, smaller="a shorter --duration, fewer bodies")


def _highest_rates(system: System) -> tuple[float, float]:
    r"""Upper bounds of the highest linear frequency (rad/s) at the initial placement, what sets
    the step, and of the fastest decay rate of the springs' damping (1/s), what bounds an
    explicit scheme's step in a damped run. Gershgorin's bound on :math:`M^{-1/2} K M^{-1/2}`,
    with each spring's share of :math:`K` bounded by its stiffness and tension
    (:math:`(k + |T|/L)\,\ell_i \ell_j`, plus :math:`|T| r_i` on the diagonal,
    :math:`\ell = s + r` the most a point of the body moves per unit of its coordinate) and each
    force's by :math:`|F| r`: within a few per cent of the exact frequency for springs at the
    centres, in O(springs) where the exact one costs O(n²) Python work (a minute for 1000
    bodies); the damping's the same way, :math:`c\,\ell_i \ell_j`."""
    bodies = system.body_map
    anchors = system.anchor_map
    index = {body.id: i for i, body in enumerate(system.bodies)}
    inertia = np.array([body.contact_inertia for body in system.bodies])
    diagonal = np.zeros(len(system.bodies))
    rows = np.zeros(len(system.bodies))
    damping = np.zeros(len(system.bodies))
    for spring, rest in zip(system.springs, system.rest_lengths, strict=True):
        ends = []
        for end, at in zip(spring.ends, spring.attachments, strict=True):
            if end in bodies:
                body = bodies[end]
                r, _ = at.polar(body)
                lever = (body.radius if body.rolls else 1.0) + r
                ends.append((index[end], lever, r, body.point_at_rest(at)))
            else:
                ends.append((-1, 0.0, 0.0, (anchors[end].x, anchors[end].y)))
        (_, _, _, (xa, ya)), (_, _, _, (xb, yb)) = ends
        length = math.hypot(xb - xa, yb - ya)
        tension = abs(spring.stiffness * (length - rest))
        share = spring.stiffness + tension / length
        for i, lever, r, _ in ends:
            if i >= 0:
                diagonal[i] += share * lever**2 + tension * r
                damping[i] += spring.damping * lever**2 / inertia[i]
        (i, li, _, _), (j, lj, _, _) = ends
        if i >= 0 and j >= 0:
            root = math.sqrt(inertia[i] * inertia[j])
            coupling = share * li * lj / root
            rows[i] += coupling
            rows[j] += coupling
            damping[i] += spring.damping * li * lj / root
            damping[j] += spring.damping * li * lj / root
    for force in system.forces:
        r, _ = force.at.polar(bodies[force.body])
        diagonal[index[force.body]] += math.hypot(force.fx, force.fy) * r
    bound = float(np.max(diagonal / inertia + rows))
    rate = float(np.max(damping))
    omega = math.sqrt(bound) if math.isfinite(bound) and bound > 0 else 0.0
    return omega, rate if math.isfinite(rate) else 0.0


def _physical_memory() -> float | None:
    try:
        return float(os.sysconf("SC_PAGE_SIZE") * os.sysconf("SC_PHYS_PAGES"))
    except (AttributeError, ValueError, OSError):
        return None


def _count(value: float) -> str:
    return f"{value:.0f}" if value < 1e6 else f"{value:.2g}"


def _duration(seconds: float) -> str:
    for size, unit in ((86400 * 365, "years"), (86400, "days"), (3600, "hours"), (60, "min")):
        if seconds >= 2 * size:
            value = seconds / size
            return f"{value:.3g} {unit}" if value < 1e6 else f"{value:.2g} {unit}"
    return f"{max(seconds, 0.1):.2g} s"


def _bytes(value: float) -> str:
    for size, unit in ((1024**4, "TiB"), (1024**3, "GiB"), (1024**2, "MiB"), (1024, "KiB")):
        if value >= size:
            return f"{value / size:.3g} {unit}"
    return f"{value:.0f} bytes"

"""What a simulation will cost, known before it starts: steps × bodies, seconds, memory.

:func:`simulation_cost`: the step comes from the highest linear frequency at the initial
placement and ``rtol``, as :func:`~rollspring.simulate.integrators.choose_scheme` picks it (the
compiled symplectic schemes), or is the ``step`` asked for; damped springs run DOP853, whose
adaptive steps are estimated from the same frequency. Seconds follow from steps × (bodies +
springs) at the measured cost of a body and step (docs/system-files.md), the output rows
observed, the extremes refined (each over its body's ball in a large system) and the setup (the
linear model: dense up to :data:`~rollspring.analysis.banded.DENSE_LIMIT` bodies, O(n) beyond);
memory from the output arrays (and the CSV text when files are written). All of it O(bodies +
springs): the estimate of a 1000-body chain is within a factor of a few of the run.
:func:`rollspring.simulate` refuses a run above the bound
(:func:`rollspring.analysis.costs.check_cost`) unless called with ``confirm=True``; the command
line with ``--yes`` (:mod:`rollspring.service.costs`). :func:`request_cost` estimates a
:class:`~rollspring.simulate.request.SimulationRequest` whose arguments are checked already.
"""

from __future__ import annotations

import math
import os
from typing import Any

from rollspring.analysis.costs import Cost
from rollspring.model import System
from rollspring.simulate.integrators import INTEGRATORS as SCHEMES
from rollspring.simulate.integrators import pick_scheme, refinement_radius
from rollspring.simulate.request import SimulationRequest, simulation_request

__all__ = [
    "API_SMALLER",
    "CLI_SMALLER",
    "MAX_RUNS",
    "available_cores",
    "batch_cost",
    "request_cost",
    "simulation_cost",
]

#: The most runs one batch or sweep holds: beyond, its per-run arrays alone (a few dozen numbers
#: a run) pass tens of GiB; a larger grid is several sweeps.
MAX_RUNS = 10**8

#: how to make a simulation smaller, in the command line's words and in Python's
CLI_SMALLER = "a shorter --duration, fewer --outputs"
API_SMALLER = "a shorter duration, fewer n_output"

#: seconds per step of a compiled symplectic step (all the stages of Kahan-Li 8) apart from its
#: bodies, and per body (or spring) of it: 1.5e-6 per body or spring for the paper's two bodies
#: and their spring, about 2e-7 for a long chain (bench/bench_chains.py)
_SYMPLECTIC_STEP, _SYMPLECTIC_BODY_STEP = 3.75e-6, 2.5e-7
#: core-seconds per run, body (or spring) and step (all the stages of Kahan-Li 8) in the batch
#: kernels, which step many runs together in SIMD lanes: 4.4e-9 measured for the paper's pair
#: (65 536 runs, bench/bench_sweep.py), the bound three times that for the off-centre springs'
#: trigonometry
_BATCH_BODY_STEP = 1.5e-8
#: seconds per output row and body (or spring) observed (forces, energies, extremes)
_OBSERVE_BODY_ROW = 1e-7
#: steps of the scheme each refined extreme takes (three grids of 9 points over two steps)
_REFINE_STEPS = 33
#: seconds per DOP853 step (SciPy's Python loop), and per body of it
_DOP853_STEP, _DOP853_BODY_STEP = 1e-3, 3e-5
#: DOP853 steps per radian of the fastest mode at rtol 1e-8, and how they grow as rtol falls
_DOP853_STEPS_PER_RADIAN, _DOP853_ORDER = 1.5, 7.0
#: the largest step × decay rate DOP853 stays stable at (its stability region on the real axis)
_DOP853_STABILITY = 3.0
#: setup (equilibrium, stiffness matrices, eigensolvers) of a simulation of n bodies: up to
#: DENSE_LIMIT bodies (dense matrices) this many seconds × (n/1000)², beyond (sparse
#: matrices, banded eigensolvers) this many per body
_SETUP_PER_SQUARED_THOUSAND = 150.0
_SETUP_PER_BODY = 5e-5
#: bytes per output number: the arrays and their copies; with files, the CSV text and the table
_BYTES_IN_MEMORY, _BYTES_WRITTEN = 16, 40


def simulation_cost(
    system: System,
    duration: Any,
    *,
    rtol: Any = 1e-8,
    integrator: Any = "auto",
    outputs: Any = 2001,
    step: Any = None,
    written: bool = False,
    what: str = "this run",
    smaller: str = CLI_SMALLER,
) -> Cost:
    """The estimated cost of ``simulate(system, duration, rtol=..., integrator=...,
    n_output=outputs, step=...)``, its files too when ``written``. The arguments are checked
    first, with the messages of :func:`rollspring.simulate`
    (:func:`~rollspring.simulate.request.simulation_request`:
    :class:`~rollspring.errors.SimulationError` naming the argument); ``rtol`` must also be
    within :data:`~rollspring.analysis.costs.RTOL_RANGE`. ``smaller`` says how to make the run
    smaller, for the message (:data:`CLI_SMALLER`, :data:`API_SMALLER`)."""
    request = simulation_request(
        duration, rtol=rtol, integrator=integrator, n_output=outputs, step=step
    )
    return request_cost(system, request, written=written, what=what, smaller=smaller)


def request_cost(
    system: System,
    request: SimulationRequest,
    *,
    written: bool = False,
    what: str = "this run",
    smaller: str = CLI_SMALLER,
) -> Cost:
    """:func:`simulation_cost` of a request checked already (nothing is checked again)."""
    from rollspring.analysis.banded import DENSE_LIMIT

    duration, rtol, integrator = request.duration, request.rtol, request.integrator
    n_output, step = request.outputs, request.step
    n = len(system.bodies)
    springs = len(system.springs)
    omega, rate = _highest_rates(system)
    # dissipative (damped springs, rolling resistance): DOP853 with its events
    damped = any(spring.damping > 0 for spring in system.springs) or any(
        body.rolling_resistance > 0 for body in system.bodies
    )
    if n <= DENSE_LIMIT:
        setup = 0.05 + _SETUP_PER_SQUARED_THOUSAND * (n / 1000.0) ** 2
    else:
        setup = 0.05 + _SETUP_PER_BODY * n
    name, chosen = pick_scheme(integrator, step, damped, omega, duration, rtol)
    if name == "dop853":
        radians = max(omega * duration, 2 * math.pi)
        steps = radians * _DOP853_STEPS_PER_RADIAN * (1e-8 / rtol) ** (1.0 / _DOP853_ORDER)
        # an explicit scheme is stable only for steps below ~3.3/rate of the fastest damping
        steps = max(steps, rate * duration / _DOP853_STABILITY)
        seconds = setup + steps * (_DOP853_STEP + _DOP853_BODY_STEP * n)
    else:
        assert chosen is not None  # a symplectic scheme has its step
        steps = max(1.0, duration / chosen)
        stages = SCHEMES[name].stages / SCHEMES["kahanli8"].stages  # measured on kahanli8
        step_seconds = stages * (_SYMPLECTIC_STEP + _SYMPLECTIC_BODY_STEP * (n + springs))
        # each body's extremes (|f|/N and N) refined over the bodies and springs of its ball:
        # every one up to DENSE_LIMIT bodies, about 2 radius + 1 of each along a chain
        radius = refinement_radius(SCHEMES[name].stages)
        ball = n + springs if n <= DENSE_LIMIT else min(n + springs, 2 * (2 * radius + 1))
        refine = 2 * n * _REFINE_STEPS * stages * _SYMPLECTIC_BODY_STEP * ball
        observe = n_output * _OBSERVE_BODY_ROW * (n + springs)
        seconds = setup + steps * step_seconds + observe + refine
    numbers = n_output * (8 * n + 2 * springs + 6)
    memory = numbers * (_BYTES_IN_MEMORY + (_BYTES_WRITTEN if written else 0))
    return Cost(what, n, seconds, float(memory), steps, name, smaller)


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
    # a few numbers per body and spring: plain floats (NumPy's per-call cost dominates here)
    inertia = [body.contact_inertia for body in system.bodies]
    diagonal = [0.0] * len(inertia)
    rows = [0.0] * len(inertia)
    damping = [0.0] * len(inertia)
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
    bound = _largest([d / j + r for d, j, r in zip(diagonal, inertia, rows, strict=True)])
    rate = _largest(damping)
    omega = math.sqrt(bound) if math.isfinite(bound) and bound > 0 else 0.0
    return omega, rate if math.isfinite(rate) else 0.0


def _largest(values: list[float]) -> float:
    """``np.max`` of a list of floats: NaN if any is (Python's ``max`` may skip a NaN)."""
    if any(v != v for v in values):
        return math.nan
    return max(values)


def batch_cost(
    system: System,
    runs: int,
    duration: Any,
    *,
    rtol: Any = 1e-8,
    integrator: Any = "auto",
    numbers_per_run: int = 40,
    what: str = "this batch",
    smaller: str = "fewer runs, a shorter duration",
    holds: str = "outputs",
) -> Cost:
    r"""The estimated cost of ``runs`` runs of ``system`` for ``duration`` s in the compiled
    batch kernels (:func:`rollspring.simulate_batch`, a sweep): each run takes the steps a single
    run of the system takes (:func:`simulation_cost`), each step costs
    :math:`(n + S)\,t_{\text{batch}}` core-seconds (the runs stepped together in SIMD lanes,
    with no per-step overhead), spread over the machine's cores, and each run keeps
    ``numbers_per_run`` numbers (8 bytes each)."""
    one = simulation_cost(
        system, duration, rtol=rtol, integrator=integrator, outputs=2, what=what, smaller=smaller
    )
    size = len(system.bodies) + len(system.springs)
    name = one.integrator if one.integrator in SCHEMES else "yoshida4"
    stages = SCHEMES[name].stages / SCHEMES["kahanli8"].stages
    steps = float(one.steps or 1.0)
    seconds = runs * steps * stages * _BATCH_BODY_STEP * size / available_cores()
    return Cost(
        what,
        len(system.bodies),
        seconds,
        float(runs) * numbers_per_run * 8,
        steps,
        name,
        smaller,
        runs=runs,
        holds=holds,
    )


def available_cores() -> int:
    """The cores this process may run on."""
    try:
        return max(1, len(os.sched_getaffinity(0)))
    except AttributeError:  # pragma: no cover - not on Linux
        return max(1, os.cpu_count() or 1)

r"""``simulate``: the exact nonlinear motion, with every force, slip and lift-off to the instant.

While every body rolls and no spring is damped, the motion is integrated by an explicit
symplectic composition (:data:`~rollspring.simulate.kernels.SCHEMES`) compiled with Numba, with
a fixed step chosen from the highest linear frequency :math:`\omega` and ``rtol``: the relative
frequency error of an order-p scheme is :math:`C_p(\omega h)^p`, and the step keeps the phase
error over the run, :math:`\omega T C_p (\omega h)^p`, and the outputs within the accuracy
contract (:mod:`rollspring.simulate.integrators`, README "Accuracy"). Damped springs, a
slipping body (docs/physics.md (M19)) or ``integrator="dop853"`` use SciPy's adaptive DOP853
on the general state :math:`[x, \varphi, u, \omega]`.

Events are found to the instant: after every step the friction each body needs and its normal
force are checked (:math:`|f_i| \ge \mu_s N_i` slip, :math:`N_i < 0` lift-off) and the crossing
is located by root-finding on the step itself (the integrator run with a shorter step is the
step's interpolant). Extremes of :math:`|f|/N` and :math:`N` are refined the same way, so they are
the continuous extremes over :math:`[0, T]`, not values at steps.
"""

from __future__ import annotations

import math
import time
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any, NamedTuple

import numpy as np
from numpy.typing import NDArray

from rollspring.analysis import find_equilibrium, normal_modes, stationary_weights
from rollspring.analysis.banded import DENSE_LIMIT
from rollspring.analysis.linear import (
    _LAPACK_EPS,
    EQUILIBRIUM_TOLERANCE,
    ZERO_MODE_TOLERANCE,
    Equilibrium,
)
from rollspring.errors import SimulationError
from rollspring.model import System
from rollspring.physics import (
    SystemArrays,
    springs_stay_level,
    stiffness_matrix,
    system_arrays,
)
from rollspring.physics.arrays import FloatArray
from rollspring.simulate import arguments, kernels
from rollspring.simulate.arguments import ON_SLIP
from rollspring.simulate.integrators import INTEGRATORS as SCHEME_REGISTRY
from rollspring.simulate.integrators import refinement_radius
from rollspring.simulate.kernels import SCHEMES
from rollspring.simulate.status import Status

BoolArray = NDArray[np.bool_]
#: what a segment hands on: (t, general state, slipping, sign)
_Handover = tuple[float, FloatArray, BoolArray, FloatArray]

__all__ = ["INTEGRATORS", "Trajectory", "simulate"]

#: How many times a run whose energy error exceeds its tolerance is started again with a
#: smaller step, when the step is the contract's choice (not the caller's ``step``).
_ENERGY_RETRIES = 3

#: Accepted values of ``integrator`` (the symplectic schemes are
#: :data:`rollspring.simulate.integrators.INTEGRATORS`).
INTEGRATORS = ("auto", *SCHEME_REGISTRY, "dop853")
_DEFAULT_OUTPUTS = 2001
_NO_SAMPLES = np.empty(0)


@dataclass
class Trajectory:
    """The simulated motion at output times ``t`` (s), SI units throughout.

    Per body (columns in the order of ``ids``): ``x`` centre position (m), ``phi`` rotation from
    the initial placement (rad, clockwise positive), ``v`` centre velocity (m/s), ``omega``
    angular velocity (rad/s), ``friction`` (N, positive along +x: the static friction needed to
    roll, or the kinetic friction while slipping), ``normal`` (N), ``friction_ratio``
    :math:`|f|/(\\mu_s N)` (slip when it reaches 1), ``slipping`` (bool). Per spring:
    ``spring_length`` (m), ``spring_tension`` (N). Energies (J; gravity, a constant while
    rolling, left out): ``kinetic``, ``potential``, ``energy``. ``cm_x`` and ``stationary_x``
    (X̂, when the system has a single zero mode). ``summary`` is the JSON summary.
    """

    system: System
    ids: tuple[str, ...]
    spring_names: tuple[str, ...]
    t: FloatArray
    x: FloatArray
    phi: FloatArray
    v: FloatArray
    omega: FloatArray
    friction: FloatArray
    normal: FloatArray
    friction_ratio: FloatArray
    slipping: np.ndarray
    spring_length: FloatArray
    spring_tension: FloatArray
    kinetic: FloatArray
    potential: FloatArray
    energy: FloatArray
    cm_x: FloatArray
    stationary_x: FloatArray | None
    status: str
    message: str
    integrator: str
    step: float | None
    n_steps: int
    events: list[dict[str, Any]] = field(default_factory=list)
    #: the steps each integrator took, in the order they were first used (a run that slipped
    #: goes on with DOP853: ``{"kahanli8": 1130, "dop853": 34}``); ``integrator`` names them
    #: joined by "+", ``n_steps`` is their sum
    steps_by_integrator: dict[str, int] = field(default_factory=dict)
    summary: dict[str, Any] = field(default_factory=dict)
    timings: dict[str, float] = field(default_factory=dict)

    def to_pandas(self) -> Any:
        """The trajectory as a ``pandas.DataFrame`` indexed by t (needs pandas; see
        :func:`rollspring.outputs.jupyter.trajectory_to_pandas`)."""
        return _presenter("to_pandas")(self)

    def to_xarray(self) -> Any:
        """The trajectory as an ``xarray.Dataset`` with dimensions time, body and spring (needs
        xarray; see :func:`rollspring.outputs.jupyter.trajectory_to_xarray`)."""
        return _presenter("to_xarray")(self)

    def animate(self, **options: Any) -> Any:
        """An inline animation for Jupyter (see
        :func:`rollspring.outputs.jupyter.animate_inline` for the options)."""
        return _presenter("animate")(self, **options)

    def columns(self) -> dict[str, tuple[str, FloatArray]]:
        """Every output as ``name -> (unit, values)``, named ``<body>.<quantity>``,
        ``<spring>.<quantity>`` or the quantity alone (the CSV columns)."""
        out: dict[str, tuple[str, FloatArray]] = {"t": ("s", self.t)}
        per_body = [
            ("x", "m", self.x),
            ("phi", "rad", self.phi),
            ("v", "m/s", self.v),
            ("omega", "rad/s", self.omega),
            ("friction", "N", self.friction),
            ("normal_force", "N", self.normal),
            ("friction_ratio", "1", self.friction_ratio),
            ("slipping", "1", self.slipping.astype(float)),
        ]
        for i, name in enumerate(self.ids):
            for quantity, unit, values in per_body:
                out[f"{name}.{quantity}"] = (unit, values[:, i])
        for s, name in enumerate(self.spring_names):
            out[f"{name}.length"] = ("m", self.spring_length[:, s])
            out[f"{name}.tension"] = ("N", self.spring_tension[:, s])
        out["kinetic_energy"] = ("J", self.kinetic)
        out["potential_energy"] = ("J", self.potential)
        out["energy"] = ("J", self.energy)
        out["cm_x"] = ("m", self.cm_x)
        if self.stationary_x is not None:
            out["stationary_x"] = ("m", self.stationary_x)
        return out


#: Views of a trajectory that live in a higher layer (tables, animations): the outputs package
#: registers them when it is imported (on a trajectory's first view, see :func:`_presenter`).
#: Keeps this layer free of Matplotlib and pandas.
PRESENTERS: dict[str, Callable[..., Any]] = {}


def _presenter(name: str) -> Callable[..., Any]:
    if not PRESENTERS:
        # the outputs layer registers the views when it is imported (``import rollspring`` no
        # longer imports it, to start fast): load it by name on first use, as a plug-in
        import importlib

        importlib.import_module("rollspring.outputs")
    try:
        return PRESENTERS[name]
    except KeyError:
        raise SimulationError(
            f"Trajectory.{name} is provided by rollspring.outputs: "
            "it was not registered (import rollspring.outputs)"
        ) from None


def _linspace(end: float, count: int) -> FloatArray:
    """``np.linspace(0.0, end, count)`` operation for operation (``arange * step``, the last
    set to ``end``) without its generic overhead."""
    if count < 2:
        return np.linspace(0.0, end, count)
    grid = np.arange(count, dtype=float)
    grid *= end / (count - 1)
    grid[-1] = end
    return grid


def _rows_of(values: np.ndarray, rows: int, dtype: type) -> np.ndarray:
    """``values`` (n,) repeated on ``rows`` rows, a new (rows, n) array (zeros without
    broadcasting when they are all zero, the usual case: NumPy broadcasts slowly over a last
    axis of a few bodies)."""
    values = np.asarray(values, dtype=dtype)
    if not values.any():
        return np.zeros((rows, values.shape[-1]), dtype=dtype)
    return np.broadcast_to(values, (rows, values.shape[-1])).copy()


class _Observed(NamedTuple):
    """What the kernel observes at rows of states (see :func:`kernels.observe`)."""

    friction: FloatArray
    normal: FloatArray
    ratio: FloatArray
    length: FloatArray
    tension: FloatArray
    potential: FloatArray
    kinetic: FloatArray


class _Start(NamedTuple):
    """A rolling state (q, v) at time t with what the kernel needs to step on from it (a
    tuple: a run makes a few of them for every segment)."""

    t: float
    q: FloatArray
    v: FloatArray
    model: tuple[Any, ...]
    coeffs: FloatArray
    h: float
    x0: FloatArray
    #: the bodies (ascending) whose states ``q``, ``v`` hold, when not every body's: the ball
    #: of an extreme's body in a large system (:func:`kernels.spring_balls`)
    ball: np.ndarray | None = None


@dataclass
class _Segment:
    """A piece of the run with one integrator; ``evaluate(t)`` gives the general state."""

    t0: float
    t1: float
    slipping: np.ndarray
    sign: np.ndarray
    evaluate: Callable[[float | FloatArray], FloatArray]
    samples: FloatArray  # times inside the segment at which to look for extremes
    #: for a two-step segment around a kernel extreme: the state it starts from
    start: _Start | None = None


def _check_arguments(
    duration: float,
    rtol: float,
    integrator: str,
    on_slip: str,
    n_output: int | None,
    energy_tolerance: float | None,
    step: float | None = None,
) -> tuple[float, float, float | None]:
    """The shared validator (:mod:`rollspring.simulate.arguments`): (duration, rtol, step)."""
    duration = arguments.check_duration(duration)
    rtol = arguments.check_rtol_range(rtol)
    arguments.check_choice("integrator", integrator, INTEGRATORS, "integrator")
    arguments.check_choice("on_slip", on_slip, ON_SLIP, "on_slip")
    arguments.check_count("n_output", n_output, 2, optional=True)
    arguments.check_positive("energy_tolerance", energy_tolerance, optional=True)
    return duration, rtol, arguments.check_step(step, duration)


def choose_scheme(
    omega: float,
    duration: float,
    rtol: float,
    integrator: str = "auto",
    n_output: int | None = None,
) -> tuple[str, float]:
    r"""The scheme and step for a run, within the accuracy contract (README, "Accuracy"):
    :meth:`~rollspring.simulate.integrators.Integrator.contract_step` -- a phase error of
    rtol/10 after :math:`\omega T` radians and outputs interpolated inside the steps within
    rtol/10 (or, with ``n_output`` evenly spaced outputs, outputs on step ends when that takes
    fewer steps), each shrunk by its measured safety factor; :math:`\omega h` at most 0.5.
    ``auto`` takes the scheme with the fewest force evaluations, counting the force rates a step
    holding interpolated outputs takes as one more (the septic interpolant's jerks). Returns
    ``(name, h)``."""
    names = list(SCHEMES) if integrator == "auto" else [integrator]
    best: tuple[str, float, float] | None = None
    for name in names:
        scheme = SCHEME_REGISTRY[name]
        step = scheme.contract_step(omega, duration, rtol, n_output)
        per_output = duration / (n_output - 1) / step if n_output and n_output > 1 else 0.5
        on_step_ends = abs(per_output - round(per_output)) <= 1e-9 * per_output
        cost = (scheme.stages + (0 if on_step_ends else 1)) * duration / step
        if best is None or cost < best[2]:
            best = (name, step, cost)
    assert best is not None  # names is never empty
    return best[0], best[1]


class _Linear(NamedTuple):
    """What a run takes from the linear model: the equilibrium, the fastest frequency (at the
    equilibrium and at the placement: the step suits both), the modes at the equilibrium (all
    of them for a small system; for a large one the lowest, up to the first oscillating one:
    every zero and unstable mode), the oscillating modes' columns and the linear period of the
    lowest (when the equilibrium was found)."""

    equilibrium: Any
    omega_max: float
    vectors: FloatArray
    kinds: np.ndarray
    oscillating: list[int]
    period: float | None
    #: every zero mode is among ``kinds`` (so their number is known: the stationary point)
    complete: bool = True


def _linear_setup(arrays: SystemArrays, model: tuple[Any, ...], *, sparse: bool) -> _Linear:
    """:class:`_Linear` of a system: with dense matrices (every mode, O(n³): the reference, up
    to :data:`~rollspring.analysis.banded.DENSE_LIMIT` bodies) or, with ``sparse``, from the
    sparse stiffness matrix by the banded eigensolvers of :mod:`rollspring.analysis.banded`
    (the largest eigenvalue and the lowest modes, O(n) each for a chain), never forming an
    n x n array."""
    n = arrays.n_bodies
    mass = arrays.inertia  # the diagonal of M
    equilibrium = _small_level_equilibrium(arrays, model) if not sparse else None
    if equilibrium is None:
        equilibrium = find_equilibrium(
            arrays,
            forces=lambda q: kernels.generalized_forces(model, np.asarray(q, float)),
            sparse=sparse,
        )
    complete = True
    if sparse and equilibrium.modes is None:
        omegas_eq, vectors_eq, kinds_eq, largest = _lowest_modes(arrays, equilibrium.q)
        complete = kinds_eq.size == n or kinds_eq[-1] == "oscillating"
        if np.any(equilibrium.q):  # the placement's largest eigenvalue too
            from rollspring.analysis.banded import banded_modes

            placement = stiffness_matrix(arrays, np.zeros(n), sparse=True)
            largest = max(largest, banded_modes(arrays, placement, select=(0, 0), vectors=False)[3])
        omega_max = math.sqrt(largest)
    else:
        # the modes at the equilibrium and at the placement (the step suits both): those the
        # search computed, else computed here (without an equilibrium q is the placement)
        modes_0 = equilibrium.placement_modes
        if modes_0 is None:
            modes_0 = normal_modes(mass, stiffness_matrix(arrays, np.zeros(n)))
        modes_eq = equilibrium.modes
        if modes_eq is None:
            modes_eq = (
                modes_0
                if not np.any(equilibrium.q)
                else normal_modes(mass, stiffness_matrix(arrays, equilibrium.q))
            )
        omegas_eq, vectors_eq, kinds_eq = modes_eq
        # a few numbers: plain floats
        omega_max = math.sqrt(max(map(abs, omegas_eq.tolist() + modes_0[0].tolist()), default=0.0))
    oscillating = [k for k, kind in enumerate(kinds_eq.tolist()) if kind == "oscillating"]
    period_linear = (
        2 * math.pi / math.sqrt(omegas_eq[oscillating[0]])
        if equilibrium.found and oscillating
        else None
    )
    return _Linear(
        equilibrium, omega_max, vectors_eq, kinds_eq, oscillating, period_linear, complete
    )


def _small_level_equilibrium(arrays: SystemArrays, model: tuple[Any, ...]) -> Equilibrium | None:
    """:func:`~rollspring.analysis.find_equilibrium` of a system of level centre springs of at
    most :data:`~rollspring.simulate.kernels.MOST_BODIES` bodies, with its modes, in one
    compiled call (:func:`~rollspring.simulate.kernels.level_setup`: the same numbers); None
    for any other system, or where the general search decides."""
    if arrays.n_bodies > kernels.MOST_BODIES or not arrays.level_centre_springs:
        return None
    verdict, q, residual, stiffness, values, vectors, codes = kernels.level_setup(
        model, EQUILIBRIUM_TOLERANCE, ZERO_MODE_TOLERANCE, _LAPACK_EPS
    )
    if verdict != kernels.LEVEL:
        return None
    kinds = np.array([kernels.KIND_NAMES[c] for c in codes.tolist()], dtype=object)
    modes = (values, vectors, kinds)
    return Equilibrium(q, True, residual, "", stiffness, modes, modes)


def _lowest_modes(
    arrays: SystemArrays, q: FloatArray
) -> tuple[FloatArray, FloatArray, np.ndarray, float]:
    """The lowest modes at ``q`` by the banded eigensolvers, enough of them to hold every
    unstable and zero mode and the first oscillating one (4, then twice as many until the
    last is oscillating, at most :data:`DENSE_LIMIT` of them: never n vectors of n), and the
    largest |eigenvalue|: (eigenvalues, M-orthonormal vectors, kinds, largest)."""
    from rollspring.analysis.banded import banded_modes

    n = arrays.n_bodies
    stiffness = stiffness_matrix(arrays, q, sparse=True)
    most = min(n, DENSE_LIMIT)
    count = min(most, 4)
    while True:
        values, vectors, kinds, largest = banded_modes(
            arrays, stiffness, select=(0, count - 1), vectors=True
        )
        if count == most or kinds[-1] == "oscillating":
            assert vectors is not None  # asked for
            return values, vectors, kinds, largest
        count = min(most, 2 * count)


def simulate(
    system: arguments.SystemLike,
    duration: float,
    *,
    rtol: float = 1e-8,
    integrator: str = "auto",
    n_output: int | None = None,
    step: float | None = None,
    on_slip: str = "stop",
    energy_tolerance: float | None = None,
    progress: Callable[[float], None] | None = None,
    confirm: bool = False,
) -> Trajectory:
    r"""Integrate the exact nonlinear equations of ``system`` for ``duration`` seconds.

    :math:`J_i\ddot\varphi_i = Q_i(\varphi)` while every body rolls (docs/physics.md (M7)); a body
    whose needed friction exceeds :math:`\mu_s N` slips ((M19), with ``on_slip="continue"``;
    ``"stop"`` ends the run at that instant); lift-off (:math:`N < 0`) ends the run.
    ``rtol`` is an accuracy contract (README, "Accuracy"): while every body rolls and no spring
    is damped, every output position (``x``, ``phi``) and velocity (``v``, ``omega``) is within
    ``rtol * |value| + rtol / 10 * scale`` of the exact motion, ``scale`` being that quantity's
    largest ``|value|`` over the run (values passing near zero included). The step is chosen
    for it from the fastest linear frequency (at the placement and the equilibrium) with
    safety factors measured on random nonlinear systems (:mod:`rollspring.simulate.integrators`,
    ``bench/bench_accuracy.py``): checked there for 1e-10 <= rtol <= 1e-2 (much below, the
    rounding of double precision, a few 1e-13 of the scale, takes over), on motions whose
    stiffest local frequency stays within 1.5 times the linear one and that are not chaotic
    over the run. Damped and slipping stretches (DOP853) take ``rtol`` as SciPy's local
    tolerance. The energy error is checked against ``energy_tolerance`` (default
    ``100 rtol + 1e-12``): a run that exceeds it with the step the contract chose (a swing
    stiffer than its linear frequencies) is started again with the step its error asks for,
    up to three times (``summary["retries"]``); one that still exceeds it, or goes
    non-finite, stops with that status (naming a spring that passes through zero length).
    ``n_output`` output times, evenly spaced (default 2001), on step ends or interpolated
    inside the steps (septic Hermite), whichever takes fewer steps within the contract;
    ``step`` fixes the step of a symplectic scheme (``auto`` then means Yoshida-4; rounded down
    so that whole steps fill each rolling stretch); ``progress`` is called with the fraction
    done.

    ``system`` is a :class:`~rollspring.model.System`, its JSON form (a dict) or a file path or
    preset name. Every bad argument is a one-line :class:`~rollspring.errors.RollspringError`
    (the command line's message for the same mistake), raised before any work; ``rtol`` must lie
    within :data:`~rollspring.analysis.costs.RTOL_RANGE`. A run estimated at more than 5
    minutes or 2 GiB (:func:`~rollspring.simulate.costs.simulation_cost`) is refused with its
    estimate (:class:`~rollspring.errors.CostTooHigh`) unless ``confirm=True`` (``--yes`` on
    the command line); outputs that cannot fit in memory are refused even then.
    """
    from rollspring.analysis.costs import CONFIRM, check_cost
    from rollspring.model import as_system
    from rollspring.simulate.costs import API_SMALLER, simulation_cost

    system = as_system(system)
    duration, rtol, step = _check_arguments(
        duration, rtol, integrator, on_slip, n_output, energy_tolerance, step
    )
    cost = simulation_cost(
        system,
        duration,
        rtol=rtol,
        integrator=integrator,
        outputs=2001 if n_output is None else n_output,
        step=step,
        smaller=API_SMALLER,
        choose=choose_scheme,
    )
    check_cost(cost, confirmed=arguments.check_flag("confirm", confirm), flag=CONFIRM)
    user_step = step
    n_output = None if n_output is None else int(n_output)
    clock = time.perf_counter()
    duration = float(duration)
    arrays = system_arrays(system)
    n = arrays.n_bodies
    mass = arrays.inertia  # the diagonal of M
    model = kernels.kernel_model(arrays)  # the initial placement's: the run's reference
    linear = _linear_setup(arrays, model, sparse=n > DENSE_LIMIT)
    equilibrium, omega_max = linear.equilibrium, linear.omega_max
    vectors_eq, kinds_eq, oscillating = linear.vectors, linear.kinds, linear.oscillating
    period_linear = linear.period
    damped = bool((arrays.damping > 0).any())
    if damped or integrator == "dop853":
        name, step = "dop853", None
    elif step is not None:
        name = "yoshida4" if integrator == "auto" else integrator
    else:
        outputs = n_output or _DEFAULT_OUTPUTS  # the step suits them (on step ends or between)
        name, step = choose_scheme(omega_max, duration, rtol, integrator, outputs)
    n_output = n_output or _DEFAULT_OUTPUTS
    grid = _linspace(duration, n_output)
    tolerance = energy_tolerance if energy_tolerance is not None else 100 * rtol + 1e-12

    chosen = step is not None and user_step is None  # the step is the contract's choice
    retries = 0
    while True:
        run = _Run(arrays, grid, name, step, rtol, on_slip, damped, tolerance, progress, model)
        if oscillating and equilibrium.found:  # the lowest mode's coordinate, for its period
            run.mode_weights = arrays.inertia * vectors_eq[:, oscillating[0]]  # M v (M diagonal)
            run.q_ref = np.ascontiguousarray(equilibrium.q, dtype=float)
        run.execute()
        if not (chosen and run.status == Status.ENERGY_ERROR.label and retries < _ENERGY_RETRIES):
            break
        # The motion is stiffer than its linear frequencies say (a large nonlinear swing):
        # the step chosen from them does not keep the energy. Run again with the step that
        # the error seen asks for (the energy error of an order-p scheme grows as h^p).
        assert step is not None
        order = SCHEME_REGISTRY[name].order
        step *= min(0.5, 0.8 * (tolerance / max(run.energy_error, tolerance)) ** (1.0 / order))
        retries += 1
    run.retries = retries
    timings = {"setup": run.started - clock, "integrate": run.integrate_time}
    trajectory = run.trajectory(system)
    if run.status == Status.ENERGY_ERROR.label:
        trajectory.message += _singular_springs(trajectory)
    lowest = vectors_eq[:, oscillating[0]] if oscillating else None
    trajectory.summary = _summary(
        trajectory,
        run,
        arrays,
        equilibrium.q,
        lowest,
        mass,
        period_linear,
        (vectors_eq, kinds_eq) if linear.complete else None,
    )
    timings["total"] = time.perf_counter() - clock
    trajectory.timings = timings
    return trajectory


def _singular_springs(trajectory: Trajectory) -> str:
    """Why a run may not keep its energy whatever the step: a spring whose length passes
    through (nearly) zero, where the direction of its force turns over at once (the motion is
    not smooth there). Empty when no spring does."""
    lengths = trajectory.spring_length
    if lengths.size == 0:
        return ""
    shortest = np.nanmin(lengths, axis=0)
    longest = np.nanmax(lengths, axis=0)
    near_zero = np.flatnonzero(shortest <= 1e-2 * longest)
    if near_zero.size == 0:
        return ""
    k = int(near_zero[0])
    return (
        f"; spring {k} passes through (nearly) zero length (down to {shortest[k]:.3g} m), "
        "where its force turns direction at once: the motion is not smooth there"
    )


class _Run:
    """The state machine of one run: rolling (symplectic) and general (DOP853) segments."""

    def __init__(
        self,
        arrays: SystemArrays,
        grid: FloatArray,
        scheme: str,
        step: float | None,
        rtol: float,
        on_slip: str,
        damped: bool,
        tolerance: float,
        progress: Callable[[float], None] | None,
        model: tuple[Any, ...] | None = None,
    ) -> None:
        self.arrays = arrays
        #: the kernel model of the initial placement (``model``, when the caller has it)
        self.model = kernels.kernel_model(arrays) if model is None else model
        self.grid = grid
        self.scheme = scheme
        self.rtol = rtol
        self.on_slip = on_slip
        self.damped = damped
        self.tolerance = tolerance
        self.progress = progress
        n = arrays.n_bodies
        self.n = n
        #: the nominal step; ``h`` is the step actually taken (each rolling segment rounds the
        #: nominal step down so that whole steps land on the end)
        self.step = step
        self.h = step
        self.coeffs = SCHEMES[scheme][1] if scheme in SCHEMES else SCHEMES["kahanli8"][1]
        self.rows: list[FloatArray] = []  # general states at output times
        self.observed: list[_Observed] = []  # forces, energies, ... at those rows
        #: every row recorded so far is a row of the grid, in order (:meth:`_record_rolling`)
        self.grid_rows = True
        #: :func:`kernels.row_extremes` of the last block :meth:`_record_rolling` recorded, as
        #: rows (ratio, its row, normal, its row)
        self.block_extremes: FloatArray | None = None
        self.central = np.ascontiguousarray(arrays.gamma * arrays.mass * arrays.radius**2)
        self.row_slipping: list[np.ndarray] = []
        self.row_sign: list[np.ndarray] = []
        self.times: list[FloatArray] = []
        self.segments: list[_Segment] = []
        self.events: list[dict[str, Any]] = []
        self.status = Status.FINISHED.label
        self.message = ""
        #: steps per integrator actually used, in order of first use
        self.steps_by_integrator: dict[str, int] = {}
        self.integrate_time = 0.0
        self.started = time.perf_counter()
        self.rolls = arrays.rolls > 0
        self.e0 = 0.0  # the energy at release (set by execute)
        self.energy_error = 0.0  # the relative energy error that ended the run, if one did
        #: how many times the run was started again with a smaller step (its energy error)
        self.retries = 0
        self.e_segment = 0.0  # the energy at the start of the current rolling segment
        #: (kind, body) -> (value, time, width, segment): the kernel's extremes over its steps,
        #: each with a two-step segment around it to refine it on
        self.step_extremes: dict[tuple[str, int], tuple[float, float, float, _Segment | None]] = {}
        #: per rolling segment: (upward crossings of the mode signal, [first, last] segments)
        self.crossings: list[tuple[int, list[_Segment]]] = []
        self.mode_weights = np.zeros(self.n)
        self.q_ref = np.zeros(self.n)
        #: the release's general state until it is recorded (:meth:`_flush_pending`)
        self.pending: FloatArray | None = None
        self.release_forces = (np.zeros(self.n), np.zeros(self.n))
        #: a rolling segment's (slipping, sign): nobody slips (shared, never written)
        self.all_rolling = (np.zeros(self.n, dtype=bool), np.zeros(self.n))
        #: the normal forces cannot change (level centre springs, forces at centres)
        self.constant_normal = springs_stay_level(arrays)
        #: beyond DENSE_LIMIT bodies the kernel keeps, for each body's extreme, only the
        #: states of its ball (the bodies a refinement of it can feel, :meth:`balls`)
        self.windowed = n > DENSE_LIMIT
        self._balls: tuple[np.ndarray, np.ndarray] | None = None
        self._links: tuple[np.ndarray, ...] | None = None

    def balls(self) -> tuple[np.ndarray, np.ndarray]:
        """(ball_ptr, ball_idx): per body the bodies whose states are kept with its extremes,
        CSR (:func:`kernels.run_fixed_step`): every body for a small system; for a large one
        those within :func:`~rollspring.simulate.integrators.refinement_radius` springs
        (:func:`kernels.spring_balls`), O(1) per body for a chain."""
        if self._balls is None:
            n = self.n
            if self.windowed:
                radius = refinement_radius(len(self.coeffs))
                links = self.links()
                self._balls = kernels.spring_balls(n, self.model[2], links[0], links[1], radius)
            else:
                ptr = np.arange(n + 1, dtype=np.int64) * n
                self._balls = (ptr, np.arange(n * n, dtype=np.int64) % n)  # n copies of 0..n-1
        return self._balls

    def links(self) -> tuple[np.ndarray, ...]:
        """:func:`kernels.body_links` of the model (each body's springs and forces)."""
        if self._links is None:
            self._links = tuple(kernels.body_links(self.n, self.model[2], self.model[4]))
        return self._links

    # -- state conversions ---------------------------------------------------------------
    def general_state(self, q: FloatArray, v: FloatArray, x0: FloatArray) -> FloatArray:
        """[x, phi, u, omega] of an all-rolling state (q, qdot) with reference positions x0
        (rows of states for 2-D ``q``, ``v``)."""
        a, n = self.arrays, self.n
        q, v, x0 = (np.asarray(values, dtype=float) for values in (q, v, x0))
        if q.ndim == 1:
            return np.concatenate([x0 + a.scale * q, a.rolls * q, a.scale * v, a.rolls * v])
        # rows: computed as (4n, rows) and transposed once, as NumPy broadcasts slowly over a
        # last axis of a few bodies
        out = np.empty((4 * n, q.shape[0]))
        scale, rolls = a.scale[:, None], a.rolls[:, None]
        np.multiply(scale, q.T, out=out[:n])
        np.add(x0[:, None], out[:n], out=out[:n])
        np.multiply(rolls, q.T, out=out[n : 2 * n])
        np.multiply(scale, v.T, out=out[2 * n : 3 * n])
        np.multiply(rolls, v.T, out=out[3 * n :])
        states: FloatArray = out.T.copy()
        return states

    def rolling_state(self, state: FloatArray) -> tuple[FloatArray, FloatArray, FloatArray]:
        """(q, qdot, x0) of a general state in which every body rolls."""
        a, n = self.arrays, self.n
        x, phi, u = state[:n], state[n : 2 * n], state[2 * n : 3 * n]
        q = np.where(self.rolls, phi, x - a.x0)
        qdot = np.where(self.rolls, state[3 * n :], u)
        x0 = np.where(self.rolls, x - a.scale * phi, a.x0)
        return q, qdot, x0

    # -- the run ---------------------------------------------------------------------------
    def execute(self) -> None:
        a = self.arrays
        initial = (np.zeros(self.n), a.v0 / a.scale, a.x0)  # (q, qdot, x0) at release
        state = self.general_state(*initial)
        slipping = np.zeros(self.n, dtype=bool)
        sign = np.zeros(self.n)
        observed = self._observe(state[None, :], slipping[None], sign[None])
        # the first output row: recorded with the first rolling segment's rows (one block),
        # or on its own before anything else happens
        self.pending = state
        #: the release's friction and normal forces (the same numbers as the kernel's)
        self.release_forces = (observed.friction[0], observed.normal[0])
        self.e0 = observed.potential[0] + observed.kinetic[0]
        t = 0.0
        # a body already beyond its friction limit at release slips from the start
        verdict = self._contact_verdict(state, slipping, observed)
        if verdict is not None:
            self._flush_pending()
            kind, body = verdict
            done = self._event(kind, body, 0.0, state, slipping, sign)
            if done:
                return
        while t < self.grid[-1] and self.status == Status.FINISHED.label:
            if not slipping.any() and not self.damped and self.scheme != "dop853":
                if self.pending is not None:  # from the release: its state and energy known
                    t, state, slipping, sign = self._rolling_segment(t, state, self.e0, initial)
                else:
                    t, state, slipping, sign = self._rolling_segment(t, state)
            else:
                self._flush_pending()
                t, state, slipping, sign = self._general_segment(t, state, slipping, sign)
        self._flush_pending()

    def _flush_pending(self) -> None:
        """Record the first output row (the release) if it is not recorded yet."""
        if self.pending is not None:
            state, self.pending = self.pending, None
            self._record(0.0, state, np.zeros(self.n, dtype=bool), np.zeros(self.n))

    def _record(
        self, t: float, state: FloatArray, slipping: BoolArray, sign: FloatArray
    ) -> _Observed:
        return self._record_block(
            np.array([t]), np.asarray(state, dtype=float)[None, :], slipping, sign
        )

    def _record_block(
        self, times: FloatArray, states: FloatArray, slipping: BoolArray, sign: FloatArray
    ) -> _Observed:
        """Keep output rows with everything observed at them; returns what was observed."""
        self.grid_rows = False
        rows = len(times)
        self.times.append(np.array(times, dtype=float))
        self.rows.append(np.array(states, dtype=float, order="C"))
        self.row_slipping.append(_rows_of(slipping, rows, bool))
        self.row_sign.append(_rows_of(sign, rows, float))
        observed = self._observe(self.rows[-1], self.row_slipping[-1], self.row_sign[-1])
        self.observed.append(observed)
        return observed

    def _record_rolling(
        self, times: FloatArray, q: FloatArray, v: FloatArray, x0: FloatArray
    ) -> float:
        """:meth:`_record_block` of all-rolling rows (q, qdot) with reference positions x0,
        states and observations by one compiled pass (:func:`kernels.observe_rolling`);
        returns the largest |E - E_segment| over the rows."""
        rows, n = q.shape
        ns = self.arrays.n_springs
        states = np.empty((rows, 4 * n))
        out = _Observed(
            np.empty((rows, n)),
            np.empty((rows, n)),
            np.empty((rows, n)),
            np.empty((rows, ns)),
            np.empty((rows, ns)),
            np.empty(rows),
            np.empty(rows),
        )
        extremes = np.empty((4, n))
        deviation = kernels.observe_rolling(
            self.model,
            x0,
            q,
            v,
            self.central,
            self.e_segment,
            states,
            out.friction,
            out.normal,
            out.length,
            out.tension,
            out.potential,
            out.kinetic,
            out.ratio,
            extremes,
        )
        self.block_extremes = extremes
        self.times.append(times)
        self.rows.append(states)
        self.row_slipping.append(np.zeros((rows, n), dtype=bool))
        self.row_sign.append(np.zeros((rows, n)))
        self.observed.append(out)
        return float(deviation)

    def _energy(self, states: FloatArray, slipping: BoolArray, sign: FloatArray) -> FloatArray:
        observed = self._observe(states, slipping, sign)
        return observed.potential + observed.kinetic

    def _observe(self, states: FloatArray, slipping: BoolArray, sign: FloatArray) -> _Observed:
        rows = states.shape[0]
        ns = self.arrays.n_springs
        out = _Observed(
            np.empty((rows, self.n)),
            np.empty((rows, self.n)),
            np.empty((rows, self.n)),
            np.empty((rows, ns)),
            np.empty((rows, ns)),
            np.empty(rows),
            np.empty(rows),
        )
        kernels.observe(
            self.model,
            np.ascontiguousarray(states),
            np.asarray(slipping),
            np.asarray(sign, dtype=float),
            self.damped,
            out.friction,
            out.normal,
            out.length,
            out.tension,
            out.potential,
            self.central,
            out.ratio,
            out.kinetic,
        )
        return out

    def _contact_verdict(
        self, state: FloatArray, slipping: BoolArray, observed: _Observed | None = None
    ) -> tuple[str, int] | None:
        """('liftoff' | 'slip', body) if a rolling body violates its contact now, else None.
        ``observed``: the state observed already (with no slip direction)."""
        if observed is None:
            observed = self._observe(state[None, :], slipping[None], np.zeros((1, self.n)))
        friction, normal = observed.friction, observed.normal
        mu = self.arrays.mu_static
        for i in range(self.n):
            if normal[0, i] < 0:
                return "liftoff", i
        for i in range(self.n):
            if (
                self.rolls[i]
                and not slipping[i]
                and abs(friction[0, i]) > mu[i] * normal[0, i]
                and friction[0, i] != 0.0
            ):
                return "slip", i
        return None

    def _event(
        self,
        kind: str,
        body: int | np.integer[Any],
        t: float,
        state: FloatArray,
        slipping: BoolArray,
        sign: FloatArray,
    ) -> bool:
        """Record an event; returns True when the run ends here."""
        name = self.arrays.ids[body]
        self.events.append({"kind": kind, "time": t, "body": name})
        if kind == "liftoff":
            self.status = Status.LIFTOFF.label
            self.message = (
                f"'{name}' leaves its track at t = {t:.12g} s (N = 0); flight is "
                f"not modelled, the run ends here"
            )
            return True
        if kind == "slip" and self.on_slip == "stop":
            self.status = Status.SLIP.label
            self.message = (
                f"'{name}' starts to slip at t = {t:.12g} s (|f| = mu_s N); "
                f"the run ends here (on_slip='continue' runs on with kinetic "
                f"friction)"
            )
            return True
        if kind == "slip":
            friction, *_ = self._observe(state[None, :], slipping[None], sign[None])
            slipping[body] = True
            # the kinetic friction takes the sign of the static friction that was needed
            sign[body] = -np.sign(friction[0, body]) or 1.0
        return False

    def _report(self, t: float) -> None:
        if self.progress is not None:
            self.progress(min(1.0, t / self.grid[-1]))

    # -- symplectic (all rolling, undamped) -------------------------------------------------
    def _rolling_segment(
        self,
        t: float,
        state: FloatArray,
        energy: float | None = None,
        rolling: tuple[FloatArray, FloatArray, FloatArray] | None = None,
    ) -> _Handover:
        """Integrate from the all-rolling ``state`` at ``t`` to the end or the next event.
        From the release, ``energy`` is its energy and ``rolling`` its (q, qdot, x0), and the
        release's row is recorded with the segment's first rows (:attr:`pending`)."""
        q, qdot, x0 = self.rolling_state(state) if rolling is None else rolling
        # energy is conserved from here on: the reference is its value now (slip lost some)
        if energy is None:
            energy = self._energy(
                state[None, :], np.zeros((1, self.n), dtype=bool), np.zeros((1, self.n))
            )[0]
        self.e_segment = energy
        # the reference positions move only when a body slipped: the same model as the run's
        same = rolling is not None or np.array_equal(x0, self.arrays.x0)
        model = self.model if same else kernels.kernel_model(self.arrays, x0)
        slipping = np.zeros(self.n, dtype=bool)
        sign = np.zeros(self.n)
        grid = self.grid
        span = float(grid[-1]) - t
        if span <= 1e-12 * grid[-1]:
            self._flush_pending()
            return float(grid[-1]), self.general_state(q, qdot, x0), slipping, sign
        # equal steps that land on the end; outputs are interpolated inside the steps
        assert self.step is not None  # rolling segments run with a fixed-step scheme only
        n_total = max(1, math.ceil(span / self.step * (1 - 1e-12)))
        h = self.h = span / n_total
        first = int(np.searchsorted(grid, t + 1e-12 * grid[-1], side="right"))
        # the release's row goes first in the first block (its row of the grid is t = 0)
        lead = 1 if self.pending is not None and first == 1 and grid[0] == t else 0
        if not lead:
            self._flush_pending()
        # chunks of about 2e5 steps: progress reports and energy checks a few times a second
        chunk = 200_000
        row_times = [np.array([t])]
        row_q = [q[None, :].copy()]
        row_v = [qdot[None, :].copy()]
        n = self.n
        # seeded with the segment's first state: the extremes include its start
        if rolling is not None:  # observed at release already (no Numba kernel to load)
            friction0, normal0 = self.release_forces
        else:
            _, _, friction0, normal0 = kernels.advance(model, self.coeffs, q, qdot, 0.0, 0)
        ratio0 = [  # |f|/N of rolling bodies (inf where N <= 0), a few plain floats
            (abs(f) / nn if nn > 0 else math.inf) if rolls else -math.inf
            for f, nn, rolls in zip(
                friction0.tolist(), normal0.tolist(), self.rolls.tolist(), strict=True
            )
        ]
        extremes = np.array([ratio0, [t] * n, normal0, [t] * n])
        ball_ptr, ball_idx = self.balls()
        extreme_states = np.empty((2, 2, ball_idx.size))
        extreme_states[:, 0, :] = q[ball_idx]
        extreme_states[:, 1, :] = qdot[ball_idx]
        crossing = np.array([0.0, 0.0, 0.0, float(self.mode_weights @ (q - self.q_ref))])
        crossing_states = np.zeros((2, 2, n))
        before = np.empty((2, n))
        q, qdot = q.copy(), qdot.copy()
        done = 0
        while done < n_total:
            steps = min(chunk, n_total - done)
            t_chunk = t + done * h
            if done + steps == n_total:
                last = grid.size
            else:
                last = int(np.searchsorted(grid, t + (done + steps) * h, side="right"))
            out_times = grid[first:last]
            # rows [lead:] for the kernel; row 0 the release's when it leads
            block_q = np.empty((out_times.size + lead, n))
            block_v = np.empty((out_times.size + lead, n))
            if lead:
                block_q[0] = q
                block_v[0] = qdot
            out_q, out_v = block_q[lead:], block_v[lead:]
            began = time.perf_counter()
            status, taken, body, filled = kernels.run_fixed_step(
                model,
                self.coeffs,
                q,
                qdot,
                t_chunk,
                h,
                steps,
                True,
                out_times,
                out_q,
                out_v,
                extremes,
                extreme_states,
                ball_ptr,
                ball_idx,
                self.mode_weights,
                self.q_ref,
                crossing,
                crossing_states,
                before,
            )
            self.integrate_time += time.perf_counter() - began
            self._count_steps(self.scheme, taken)
            row_times.append(out_times[:filled])
            row_q.append(out_q[:filled])
            row_v.append(out_v[:filled])
            if lead:
                self.pending = None
                block_times = grid[first - 1 : first + filled]
            else:
                block_times = out_times[:filled]
            if lead + filled and not self._energy_within(
                self._record_rolling(
                    block_times.copy(), block_q[: lead + filled], block_v[: lead + filled], x0
                )
            ):
                self.segments.append(self._rolling_evaluator(model, row_times, row_q, row_v, h, x0))
                self._offer_steps(model, x0, extremes, extreme_states, crossing, crossing_states, h)
                return float(self.times[-1][-1]), self.rows[-1][-1], slipping, sign
            if status != kernels.STATUS_FINISHED:
                t_before = t_chunk + (taken - 1) * h
                row_times.append(np.array([t_before]))
                row_q.append(before[0][None, :].copy())
                row_v.append(before[1][None, :].copy())
                self.segments.append(self._rolling_evaluator(model, row_times, row_q, row_v, h, x0))
                self._offer_steps(model, x0, extremes, extreme_states, crossing, crossing_states, h)
                if status == kernels.STATUS_NONFINITE:
                    self.status = Status.NONFINITE.label
                    self.message = (
                        f"the state became non-finite at t = {t_before + h:.6g} s "
                        f"('{self.arrays.ids[body]}'); the step cannot resolve the "
                        f"motion"
                    )
                    return t_before, self.general_state(before[0], before[1], x0), slipping, sign
                return self._locate(model, t_before, before[0].copy(), before[1].copy(), h, 1, x0)
            first += filled
            done += steps
            lead = 0
            self._report(t + done * h)
        self.segments.append(self._rolling_evaluator(model, row_times, row_q, row_v, h, x0))
        self._offer_steps(model, x0, extremes, extreme_states, crossing, crossing_states, h)
        end = float(grid[-1])
        if self.grid_rows and self.times and float(self.times[-1][-1]) == end:
            # the run is over (nothing steps on from the handover): the last row, the state
            # at the end to rounding, instead of building it again
            return end, self.rows[-1][-1].copy(), slipping, sign
        return end, self.general_state(q, qdot, x0), slipping, sign

    def _local(
        self,
        model: tuple[Any, ...],
        x0: FloatArray,
        t_start: float,
        q: FloatArray,
        v: FloatArray,
        h: float,
        ball: np.ndarray | None = None,
    ) -> _Segment:
        """A segment of two steps from the state (q, v) at ``t_start``. Its interpolant is
        built on first use: most are refined from their ``start`` in one compiled call. With
        ``ball``, (q, v) are the states of those bodies alone (an extreme of a large system):
        such a segment is refined from its start only (:func:`_refine_together`)."""
        start = _Start(t_start, q.copy(), v.copy(), model, self.coeffs, h, x0, ball)
        built: list[_Segment] = []
        slipping, sign = self.all_rolling

        def evaluate(t: float | FloatArray) -> FloatArray:
            if ball is not None:
                raise SimulationError(
                    "internal: a windowed extreme's segment has no interpolant (refine it "
                    "from its start)"
                )
            if not built:
                built.append(
                    self._rolling_evaluator(
                        model, [t_start], [start.q], [start.v], h, x0, t_end=t_start + 2 * h
                    )
                )
            return built[0].evaluate(t)

        return _Segment(t_start, t_start + 2 * h, slipping, sign, evaluate, _NO_SAMPLES, start)

    def _offer_steps(
        self,
        model: tuple[Any, ...],
        x0: FloatArray,
        extremes: FloatArray,
        extreme_states: FloatArray,
        crossing: FloatArray,
        crossing_states: FloatArray,
        h: float,
    ) -> None:
        """Hand the kernel's extremes and crossings over, each with the state it starts from."""
        found = extremes.tolist()
        ball_ptr, ball_idx = self.balls()
        for i in range(self.n):
            for kind, row in (("ratio", 0), ("normal", 2)):
                value = found[row][i]
                if not math.isfinite(value) or (kind == "ratio" and not self.rolls[i]):
                    continue
                old = self.step_extremes.get((kind, i))
                if old is None or (value > old[0] if kind == "ratio" else value < old[0]):
                    k = 0 if kind == "ratio" else 1
                    t_start = found[row + 1][i]
                    # a normal force that cannot change is never refined: no segment for it
                    lo, hi = ball_ptr[i], ball_ptr[i + 1]
                    local = (
                        None
                        if kind == "normal" and self.constant_normal
                        else self._local(
                            model,
                            x0,
                            t_start,
                            extreme_states[k, 0, lo:hi],
                            extreme_states[k, 1, lo:hi],
                            h,
                            ball_idx[lo:hi] if self.windowed else None,
                        )
                    )
                    self.step_extremes[(kind, i)] = (value, t_start + h, h, local)
        self.crossings.append(
            (
                int(crossing[0]),
                [
                    self._local(
                        model,
                        x0,
                        float(crossing[1 + j]),
                        crossing_states[j, 0],
                        crossing_states[j, 1],
                        h,
                    )
                    for j in range(2)
                ],
            )
        )

    def _count_steps(self, integrator: str, taken: int) -> None:
        if taken > 0:
            self.steps_by_integrator[integrator] = (
                self.steps_by_integrator.get(integrator, 0) + taken
            )

    @property
    def n_steps(self) -> int:
        """The steps taken, every integrator's."""
        return sum(self.steps_by_integrator.values())

    @property
    def integrators_used(self) -> str:
        """The integrators that took steps, joined by "+" in order of first use (the chosen
        scheme when none took a step)."""
        return "+".join(self.steps_by_integrator) or self.scheme

    @property
    def symplectic_step(self) -> float | None:
        """The symplectic step taken, None when no symplectic step was taken."""
        used = any(name != "dop853" for name in self.steps_by_integrator)
        return self.h if used or not self.steps_by_integrator else None

    def _violation(self, friction: FloatArray, normal: FloatArray) -> tuple[str, int] | None:
        mu = self.arrays.mu_static
        for i in range(self.n):
            if normal[i] < 0:
                return "liftoff", i
            if self.rolls[i] and abs(friction[i]) > mu[i] * normal[i]:
                return "slip", i
        return None

    def _energy_ok(self, observed: _Observed) -> bool:
        energy = observed.potential + observed.kinetic
        return self._energy_within(float(np.max(np.abs(energy - self.e_segment))))

    def _energy_within(self, deviation: float) -> bool:
        """Whether the largest |E - E_segment| over the rows just recorded is within the
        energy tolerance (relative to the energy at release); sets the status if not."""
        scale = max(abs(self.e0), 1e-300)
        error = deviation / scale
        if not math.isfinite(error):
            self.status = Status.NONFINITE.label
            self.message = "the energy became non-finite; the step cannot resolve the motion"
            return False
        if error > self.tolerance and abs(self.e0) > 0:
            self.energy_error = error
            self.status = Status.ENERGY_ERROR.label
            self.message = (
                f"the energy error {error:.3g} exceeds its tolerance "
                f"{self.tolerance:.3g} (at t = {float(self.times[-1][-1]):.6g} s): "
                f"the step "
                f"does not resolve the motion; lower rtol or use a higher-order "
                f"integrator"
            )
            return False
        return True

    def _rolling_evaluator(
        self,
        model: tuple[Any, ...],
        times: list[Any],
        qs: list[Any],
        vs: list[Any],
        h: float,
        x0: FloatArray,
        t_end: float | None = None,
    ) -> _Segment:
        """A segment whose state at any t is the integrator run on from the row before t.
        ``times``/``qs``/``vs`` are lists of rows or of blocks of rows (joined on first use:
        most segments are never evaluated)."""
        first = float(np.atleast_1d(np.asarray(times[0], dtype=float))[0])
        last = float(np.atleast_1d(np.asarray(times[-1], dtype=float))[-1])
        coeffs = self.coeffs
        rows_of: list[tuple[FloatArray, FloatArray, FloatArray]] = []

        def evaluate(t: float | FloatArray) -> FloatArray:
            """The state at time(s) ``t``: (4n,) for a number, (m, 4n) for an array."""
            if not rows_of:
                rows_of.append(
                    (
                        np.concatenate([np.atleast_1d(np.asarray(x, dtype=float)) for x in times]),
                        np.concatenate([np.atleast_2d(np.asarray(x, dtype=float)) for x in qs]),
                        np.concatenate([np.atleast_2d(np.asarray(x, dtype=float)) for x in vs]),
                    )
                )
            row_t, row_q, row_v = rows_of[0]
            at = np.atleast_1d(np.asarray(t, dtype=float))
            if len(row_t) == 1:
                rows = np.zeros(at.size, dtype=np.int64)
            else:
                rows = np.clip(np.searchsorted(row_t, at, side="right") - 1, 0, len(row_t) - 1)
            spans = at - row_t[rows]
            pieces = np.where(spans > 0, np.maximum(1, np.ceil(spans / h * (1 - 1e-12))), 0)
            q, v = kernels.advance_many(
                model, coeffs, row_q[rows], row_v[rows], spans, pieces.astype(np.int64)
            )
            states = self.general_state(q, v, x0)
            return states if np.ndim(t) else states[0]

        # extremes: the output rows and the kernel's extremes over every step cover it
        slipping, sign = self.all_rolling
        end = last if t_end is None else float(t_end)
        return _Segment(first, end, slipping, sign, evaluate, _NO_SAMPLES)

    def _locate(
        self,
        model: tuple[Any, ...],
        t_before: float,
        q: FloatArray,
        v: FloatArray,
        span: float,
        pieces: int,
        x0: FloatArray,
    ) -> _Handover:
        """An event happened within ``span`` after ``t_before``: find its instant."""
        slipping = np.zeros(self.n, dtype=bool)
        sign = np.zeros(self.n)
        h = span / pieces
        # find the piece, then the instant inside it
        for _ in range(pieces):
            q1, v1, f1, n1 = kernels.advance(model, self.coeffs, q, v, h, 1)
            if self._violation(f1, n1) is not None or not np.all(np.isfinite(q1)):
                break
            q, v, t_before = q1, v1, t_before + h
        mu = self.arrays.mu_static
        checked = self.rolls & np.isfinite(mu)  # mu_s = inf: never slips (no inf * N)
        mu_finite = np.where(checked, mu, 0.0)

        def margins(tau: float) -> FloatArray:
            _, _, f, nn = kernels.advance(model, self.coeffs, q, v, tau, 1 if tau > 0 else 0)
            slip = np.where(checked, mu_finite * nn - np.abs(f), np.inf)
            return np.concatenate([slip, nn])

        end = margins(h)
        start = margins(0.0)
        best = None
        import scipy.optimize  # on demand: an event to locate (SciPy's optimizers take ~0.1 s)

        for j in np.flatnonzero((end < 0) | ((end == 0) & (start > 0))):
            if not np.isfinite(start[j]) or start[j] <= 0:
                root = 0.0
            else:
                root = scipy.optimize.brentq(
                    lambda tau, j=j: margins(tau)[j],
                    0.0,
                    h,
                    xtol=1e-15,
                    rtol=4 * np.finfo(float).eps,
                )
            if best is None or root < best[0]:
                best = (root, j)
        if best is None:  # non-finite state
            self.status = Status.NONFINITE.label
            self.message = f"the state became non-finite near t = {t_before:.6g} s"
            return t_before, self.general_state(q, v, x0), slipping, sign
        root, j = best
        kind = "slip" if j < self.n else "liftoff"
        body = j % self.n
        q_e, v_e, _, _ = kernels.advance(model, self.coeffs, q, v, root, 1 if root > 0 else 0)
        t_event = t_before + root
        state = self.general_state(q_e, v_e, x0)
        self.segments.append(
            self._rolling_evaluator(
                model, [t_before, t_event], [q, q_e], [v, v_e], max(root, 1e-300), x0
            )
        )
        if self._event(kind, body, t_event, state, slipping, sign):
            self._record(t_event, state, slipping, sign)
            return t_event, state, slipping, sign
        return t_event, state, slipping, sign

    # -- general (DOP853): damping, slipping ------------------------------------------------
    def _general_segment(
        self, t: float, state: FloatArray, slipping: BoolArray, sign: FloatArray
    ) -> _Handover:
        n, a, model = self.n, self.arrays, self.model
        slipping = slipping.copy()
        sign = sign.copy()
        mu_s = a.mu_static

        def rhs(_t: float, y: FloatArray) -> FloatArray:
            out = np.empty(4 * n)
            kernels.slipping_derivatives(model, y, slipping, sign, self.damped, out)
            return out

        # SciPy calls every event function with the same state array after a step: observed
        # once for all of them (O(n) per step, not O(n) per body)
        last: list[Any] = [None, None]

        def contacts(y: FloatArray) -> tuple[FloatArray, FloatArray]:
            if last[0] is not y:
                friction, normal, *_ = self._observe(y[None, :], slipping[None], sign[None])
                last[:] = [y, (friction[0], normal[0])]
            result: tuple[FloatArray, FloatArray] = last[1]
            return result

        def slip_margin(y: FloatArray, i: int) -> float:
            friction, normal = contacts(y)
            return float(mu_s[i] * normal[i] - abs(friction[i]))

        events: list[Any] = []  # solve_ivp's events: functions with .terminal, .direction
        labels = []
        for i in range(n):
            if self.rolls[i] and not slipping[i] and np.isfinite(mu_s[i]):
                events.append(lambda _t, y, i=i: slip_margin(y, i))
                labels.append(("slip", i))
            if self.rolls[i] and slipping[i]:
                events.append(lambda _t, y, i=i: y[2 * n + i] - a.radius[i] * y[3 * n + i])
                labels.append(("stick", i))
            events.append(lambda _t, y, i=i: contacts(y)[1][i])
            labels.append(("liftoff", i))
        for event, (kind, i) in zip(events, labels, strict=True):
            event.terminal = True
            event.direction = (sign[i] * -1.0) if kind == "stick" else -1.0
        t_eval = self.grid[(self.grid > t + 1e-12 * self.grid[-1])]
        scale = max(float(np.max(np.abs(state))), float(np.max(a.radius)))
        import scipy.integrate  # on demand: only the general (DOP853) segments need it

        began = time.perf_counter()
        solution = scipy.integrate.solve_ivp(
            rhs,
            (t, self.grid[-1]),
            state,
            method="DOP853",
            t_eval=t_eval,
            rtol=max(self.rtol, 1e-13),
            atol=max(self.rtol, 1e-13) * scale * 1e-2,
            events=events,
            dense_output=True,
        )
        self.integrate_time += time.perf_counter() - began
        if solution.sol is not None:  # the adaptive steps taken
            self._count_steps("dop853", len(solution.sol.ts) - 1)
        if solution.status == -1:
            self.status = Status.NONFINITE.label
            self.message = f"the adaptive integrator failed: {solution.message}"
            return self.grid[-1], state, slipping, sign
        if solution.t.size:
            self._record_block(solution.t, solution.y.T, slipping, sign)
        dense = solution.sol
        t_end = float(
            solution.t_events
            and max((float(te[0]) for te in solution.t_events if len(te)), default=self.grid[-1])
            if solution.status == 1
            else self.grid[-1]
        )

        def dense_state(tt: float | FloatArray, d: Any = dense) -> FloatArray:
            return np.asarray(d(tt)).T

        self.segments.append(
            _Segment(
                t,
                t_end,
                slipping.copy(),
                sign.copy(),
                dense_state,
                np.asarray(dense.ts),
            )
        )
        self._report(t_end)
        if solution.status != 1:
            return self.grid[-1], solution.y[:, -1] if solution.y.size else state, slipping, sign
        which = next(j for j, te in enumerate(solution.t_events) if len(te))
        kind, body = labels[which]
        y_event = np.asarray(solution.y_events[which][0], dtype=float)
        if kind == "stick":
            y_event[2 * n + body] = a.radius[body] * y_event[3 * n + body]  # v_s = 0 exactly
            trial = slipping.copy()
            trial[body] = False
            friction, normal, *_ = self._observe(y_event[None, :], trial[None], sign[None])
            if abs(friction[0, body]) <= mu_s[body] * normal[0, body]:
                slipping[body] = False
                sign[body] = 0.0
                self.events.append({"kind": "stick", "time": t_end, "body": a.ids[body]})
            else:
                sign[body] = -sign[body]
                self.events.append({"kind": "reverse", "time": t_end, "body": a.ids[body]})
            return t_end, y_event, slipping, sign
        if self._event(kind, body, t_end, y_event, slipping, sign):
            self._record(t_end, y_event, slipping, sign)
        return t_end, y_event, slipping, sign

    # -- results ----------------------------------------------------------------------------
    def trajectory(self, system: System) -> Trajectory:
        a, n = self.arrays, self.n
        times = self.times[0] if len(self.times) == 1 else np.concatenate(self.times)
        pick = None  # rows in time order, each time once (events can repeat a time)
        # rows of rolling segments alone are consecutive slices of the grid: in order already
        if not self.grid_rows and times.size > 1 and not (times[1:] > times[:-1]).all():
            order = np.argsort(times, kind="stable")
            keep = np.concatenate([[True], np.diff(times[order]) > 0])
            pick = order[keep]

        def column(parts: list[Any]) -> Any:
            joined = parts[0] if len(parts) == 1 else np.concatenate(parts)
            return joined if pick is None else joined[pick]

        times = times if pick is None else times[pick]
        states = column(self.rows)
        observed = {
            name: column([getattr(o, name) for o in self.observed]) for name in _Observed._fields
        }
        kinetic, potential = observed["kinetic"], observed["potential"]
        x = states[:, :n]
        return Trajectory(
            system=system,
            ids=a.ids,
            spring_names=a.spring_names,
            t=times,
            x=x,
            phi=states[:, n : 2 * n],
            v=states[:, 2 * n : 3 * n],
            omega=states[:, 3 * n :],
            friction=observed["friction"],
            normal=observed["normal"],
            friction_ratio=observed["ratio"],
            slipping=column(self.row_slipping),
            spring_length=observed["length"],
            spring_tension=observed["tension"],
            kinetic=kinetic,
            potential=potential,
            energy=kinetic + potential,
            cm_x=x @ a.mass / np.sum(a.mass),
            stationary_x=None,
            status=self.status,
            message=self.message,
            integrator=self.integrators_used,
            step=self.symplectic_step,
            n_steps=self.n_steps,
            events=list(self.events),
            steps_by_integrator=dict(self.steps_by_integrator),
        )


def _summary(
    trajectory: Trajectory,
    run: _Run,
    arrays: SystemArrays,
    q_eq: FloatArray,
    lowest: FloatArray | None,
    mass: FloatArray,
    period_linear: float | None,
    modes: tuple[FloatArray, Any] | None,
) -> dict[str, Any]:
    """The JSON summary (see the README): status, energies, periods, extremes, events."""
    n = arrays.n_bodies
    ids = arrays.ids
    extremes = _continuous_extremes(run, trajectory)
    conservative = not run.damped and not any(e["kind"] == "slip" for e in run.events)
    energy = trajectory.energy
    e0 = float(energy[0])
    high, low = float(energy.max()), float(energy.min())  # NaN if any is
    # relative to the energy at release, as the run's own check (a blow-up to 385 E0 is an
    # error of 384, not ~1); the largest |E| only when E0 is 0
    scale = abs(e0) or max(max(abs(high), abs(low)) if high == high else math.nan, 1e-300)
    if conservative:  # the largest |E - E0|: at the largest or the smallest E
        energy_error = (max(high - e0, e0 - low) if high == high else math.nan) / scale
    else:  # spurious growth above the running minimum
        energy_error = float(np.max(energy - np.minimum.accumulate(energy))) / scale
    # weights of the stationary point (M14) at equilibrium, from the normal modes there (None
    # when the zero modes are not all known: more zero and unstable modes than were computed)
    weights = stationary_weights(arrays, *modes) if modes is not None else None
    if weights is not None:
        trajectory.stationary_x = trajectory.x @ weights
    period = _measured_period(run, trajectory, lowest, mass, q_eq) if lowest is not None else None
    first = {
        kind: next(
            ({"time": e["time"], "body": e["body"]} for e in run.events if e["kind"] == kind), None
        )
        for kind in ("slip", "liftoff")
    }
    final = {
        "time": float(trajectory.t[-1]),
        "cm_x": float(trajectory.cm_x[-1]),
        "bodies": {
            name: {
                "x": float(trajectory.x[-1, i]),
                "phi": float(trajectory.phi[-1, i]),
                "v": float(trajectory.v[-1, i]),
                "omega": float(trajectory.omega[-1, i]),
            }
            for i, name in enumerate(ids)
        },
    }
    return {
        "status": trajectory.status,
        "message": trajectory.message,
        "duration": float(run.grid[-1]),
        "integrator": run.integrators_used,
        "step": run.symplectic_step,
        "steps": int(run.n_steps),
        "steps_by_integrator": dict(run.steps_by_integrator),
        "retries": run.retries,
        "energy": e0,
        "energy_error": energy_error,
        "period_measured": period,
        "period_linear": period_linear,
        "max_friction_ratio": {
            ids[i]: extremes["ratio"][i] for i in range(n) if arrays.rolls[i] > 0
        },
        "min_normal_force": {ids[i]: extremes["normal"][i] for i in range(n)},
        "first_slip": first["slip"],
        "first_liftoff": first["liftoff"],
        "events": trajectory.events,
        "final": final,
    }


def _continuous_extremes(run: _Run, trajectory: Trajectory) -> dict[str, list[float]]:
    r"""max |f|/N (while rolling) and min N per body over the whole run.

    Candidates are the output rows, the compiled kernel's extremes over every step, and the
    adaptive integrator's steps; the best candidate is refined by bounded Brent minimisation on
    the integrator's own interpolant over the neighbouring interval: the instant to 3e-5 of
    the interval (at most 0.5/omega), so the value, quadratic about the extreme, to about
    1e-9 relative."""
    n = run.n
    spacing = float(run.grid[1] - run.grid[0])
    # per body: the largest |f|/N over the rows while rolling, the smallest N, and their rows
    # (|f|/N, inf where N <= 0, -inf while slipping; the first row of each, as argmax/argmin)
    if run.grid_rows and len(run.observed) == 1 and run.block_extremes is not None:
        ratio, ratio_row, normal, normal_row = run.block_extremes.tolist()  # one rolling block
        ratio_row, normal_row = [int(r) for r in ratio_row], [int(r) for r in normal_row]
    else:
        found = kernels.row_extremes(trajectory.friction, trajectory.normal, trajectory.slipping)
        ratio, ratio_row, normal, normal_row = (values.tolist() for values in found)
    best: dict[tuple[str, int], tuple[float, float, float, _Segment | None]] = {}

    def offer(
        kind: str, i: int, value: float, t: float, width: float, local: _Segment | None = None
    ) -> None:
        old = best.get((kind, i))
        better = old is None or (value > old[0] if kind == "ratio" else value < old[0])
        if better:
            best[(kind, i)] = (value, t, width, local)

    # the kernel's extremes first: on a tie they win, as they carry their state
    for (kind, i), (value, t, width, kept) in run.step_extremes.items():
        offer(kind, i, value, t, width, kept)
    times = trajectory.t
    for i in range(n):
        if run.rolls[i]:
            offer("ratio", i, float(ratio[i]), float(times[ratio_row[i]]), spacing)
        offer("normal", i, float(normal[i]), float(times[normal_row[i]]), spacing)
    for segment in run.segments:
        if segment.samples.size < 2 or segment.slipping.all():
            continue
        states = segment.evaluate(segment.samples)
        slip = np.broadcast_to(segment.slipping, states[:, :n].shape)
        sign = np.broadcast_to(segment.sign, states[:, :n].shape)
        friction, normal, *_ = run._observe(states, slip, sign)
        width = float(np.max(np.diff(segment.samples)))
        for i in range(n):
            if run.rolls[i] and not segment.slipping[i]:
                with np.errstate(divide="ignore", invalid="ignore"):
                    r = np.where(normal[:, i] > 0, np.abs(friction[:, i]) / normal[:, i], np.inf)
                k = int(np.argmax(r))
                offer("ratio", i, float(r[k]), float(segment.samples[k]), width)
            k = int(np.argmin(normal[:, i]))
            offer("normal", i, float(normal[k, i]), float(segment.samples[k]), width)

    result = {"ratio": [0.0] * n, "normal": [math.inf] * n}
    # level centre springs (physics.springs_stay_level): N is the same at every instant,
    # exactly, so its smallest value is every row's and there is nothing to refine
    fixed = {key for key in best if key[0] == "normal" and run.constant_normal}
    for kind, i in fixed:
        result[kind][i] = float(best[(kind, i)][0])
    batched = {
        key: entry
        for key, entry in best.items()
        if key not in fixed
        and entry[3] is not None
        and getattr(entry[3], "start", None) is not None
        and math.isfinite(entry[0])
    }
    groups: dict[int, dict[tuple[str, int], Any]] = {}  # one per rolling segment (its model)
    for key, entry in batched.items():
        start = entry[3].start if entry[3] is not None else None
        assert start is not None  # batched: only segments with the state they start from
        groups.setdefault(id(start.model), {})[key] = entry
    for group in groups.values():
        for (kind, i), value in _refine_together(group, run).items():
            result[kind][i] = value
    for (kind, i), (value, t, width, local) in best.items():
        if (kind, i) in batched or (kind, i) in fixed:
            continue
        if np.isfinite(value):
            value = _refine(run, kind, i, value, t, width, local)
        result[kind][i] = float(value)
    return result


def _refine_together(
    entries: dict[tuple[str, int], Any], run: _Run
) -> dict[tuple[str, int], float]:
    """:func:`_refine` for many extremes at once, each on its own two-step segment from the
    state the kernel kept (one compiled call for all of them; in a large system each on the
    model of its body's ball, :func:`kernels.refine_windowed`)."""
    keys = list(entries)
    first = entries[keys[0]][3].start
    kinds = np.array([0 if kind == "ratio" else 1 for kind, _ in keys], dtype=np.int64)
    bodies = np.array([i for _, i in keys], dtype=np.int64)
    sign = [1.0 if kind == "ratio" else -1.0 for kind, _ in keys]
    best = np.array([entries[k][0] * sign[j] for j, k in enumerate(keys)])
    starts = [entries[k][3].start for k in keys]
    if first.ball is None:
        q0 = np.array([start.q for start in starts])
        v0 = np.array([start.v for start in starts])
        refined = kernels.refine_extremes(
            first.model, first.coeffs, first.h, q0, v0, kinds, bodies, best
        ).tolist()
    else:
        offsets = np.zeros(len(starts) + 1, dtype=np.int64)
        np.cumsum([start.ball.size for start in starts], out=offsets[1:])
        refined = kernels.refine_windowed(
            first.model,
            first.coeffs,
            first.h,
            np.concatenate([start.q for start in starts]),
            np.concatenate([start.v for start in starts]),
            offsets,
            np.concatenate([start.ball for start in starts]),
            kinds,
            bodies,
            best,
            run.links(),
        ).tolist()
    return {key: refined[j] * sign[j] for j, key in enumerate(keys)}


def _refine(
    run: _Run,
    kind: str,
    i: int,
    value: float,
    t: float,
    width: float,
    segment: _Segment | None = None,
) -> float:
    """The extreme near ``t`` (within ``width``), on the interpolant of ``segment`` (by default
    the segment holding ``t``)."""
    if segment is None:
        segment = next((s for s in run.segments if s.t0 <= t <= s.t1), None)
    if segment is None or (segment.slipping[i] and kind == "ratio"):
        return value
    lo, hi = max(segment.t0, t - width), min(segment.t1, t + width)
    if not hi > lo:
        return value

    def values_at(times: FloatArray) -> FloatArray:
        states = segment.evaluate(times)
        slipping = np.broadcast_to(segment.slipping, (len(times), run.n))
        sign = np.broadcast_to(segment.sign, (len(times), run.n))
        f, nn, *_ = run._observe(states, slipping, sign)
        if kind == "ratio":
            with np.errstate(divide="ignore", invalid="ignore"):
                return np.where(nn[:, i] > 0, np.abs(f[:, i]) / nn[:, i], np.inf)
        return -nn[:, i]  # maximise -N

    # three grids of 9 points, each spanning the best point's neighbours on the last (spacing
    # width/256 at the end, omega * spacing < 0.004), then the vertex of the parabola through
    # the best point and its neighbours: the extreme to about 1e-10 relative
    for _ in range(3):
        times = np.linspace(lo, hi, 9)
        values = values_at(times)
        k = int(np.clip(np.argmax(values), 1, 7))
        if not np.all(np.isfinite(values[k - 1 : k + 2])):
            best = float(np.max(values))
            break
        a, b, c = values[k - 1 : k + 2]
        curvature = a - 2 * b + c
        best = float(np.max(values))
        if curvature < 0 and abs(a - c) <= -2 * curvature:  # the vertex lies between a and c
            best = max(best, float(b - (c - a) ** 2 / (8 * curvature)))
        lo, hi = times[k - 1], times[k + 1]
    refined = best if kind == "ratio" else -best
    return max(value, refined) if kind == "ratio" else min(value, refined)


def _measured_period(
    run: _Run, trajectory: Trajectory, mode: FloatArray, mass: FloatArray, q_eq: FloatArray
) -> float | None:
    r"""Mean period of the lowest mode's coordinate :math:`s = v_1^T M (q - q^*)`, from its
    upward crossings of its mean, each located by root-finding on the integrator's interpolant.
    ``mass``: the diagonal of M."""
    arrays = run.arrays
    weights = mode * mass

    def signal_of(states: FloatArray) -> FloatArray:
        n = run.n
        q = np.where(run.rolls, states[..., n : 2 * n], states[..., :n] - arrays.x0)
        return (q - q_eq) @ weights

    if len(run.crossings) == 1 and len(run.segments) == 1 and run.crossings[0][0] >= 2:
        # one rolling segment: the kernel counted the upward zero crossings of the signal at
        # every step and kept the states before the first and the last
        count, (first, last) = run.crossings[0]
        starts = [seg.start for seg in (first, last) if seg.start is not None]
        assert len(starts) == 2  # the kernel kept both states
        times = [
            start.t
            + kernels.signal_zero(
                start.model, start.coeffs, start.h, start.q, start.v, run.mode_weights, run.q_ref
            )
            for start in starts
        ]
        result: float | None = (times[1] - times[0]) / (count - 1)
        return result
    signal = signal_of(np.concatenate([trajectory.x, trajectory.phi], axis=1))  # q of them
    level = 0.5 * (float(np.max(signal)) + float(np.min(signal)))
    values = signal - level
    upward = np.flatnonzero((values[:-1] < 0) & (values[1:] >= 0))
    if upward.size < 2:
        return None
    import scipy.optimize  # on demand, as above

    crossings = []
    for k in (upward[0], upward[-1]):  # the mean period needs only the first and the last
        lo, hi = float(trajectory.t[k]), float(trajectory.t[k + 1])
        segment = next((s for s in run.segments if s.t0 <= lo and hi <= s.t1 + 1e-15), None)
        if segment is None:
            return None
        crossings.append(
            scipy.optimize.brentq(
                lambda tt, seg=segment: float(signal_of(seg.evaluate(tt))) - level,
                lo,
                hi,
                xtol=1e-15,
                rtol=4 * np.finfo(float).eps,
            )
        )
    period: float = (crossings[-1] - crossings[0]) / (upward.size - 1)
    return period

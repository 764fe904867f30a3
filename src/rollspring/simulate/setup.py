r"""The set-up of a run of :func:`rollspring.simulate`: linear model, scheme and step, the plan.

:func:`plan` makes, once per run, the frozen :class:`Plan` the run is built from: the kernel model
of the initial placement (:class:`KernelModel`), the linear model (:class:`Linear`: the
equilibrium, the fastest linear frequency at it and at the placement, the modes; dense
matrices up to :data:`~rollspring.analysis.banded.DENSE_LIMIT` bodies, the banded eigensolvers
beyond, and one compiled call for the paper's small level systems,
:func:`_small_level_equilibrium`), the integrator and its step within the accuracy contract
(:func:`~rollspring.simulate.integrators.choose_scheme`), the output times and the energy
tolerance. A run that does not keep its energy is started again from the same plan with a
smaller step (``dataclasses.replace``).
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any, NamedTuple

import numpy as np

from rollspring.analysis import find_equilibrium, normal_modes
from rollspring.analysis.banded import DENSE_LIMIT
from rollspring.analysis.linear import (
    _LAPACK_EPS,
    EQUILIBRIUM_TOLERANCE,
    ZERO_MODE_TOLERANCE,
    Equilibrium,
)
from rollspring.physics import SystemArrays, stiffness_matrix
from rollspring.physics.arrays import FloatArray
from rollspring.simulate import kernels
from rollspring.simulate.integrators import pick_scheme
from rollspring.simulate.request import SimulationRequest

__all__ = ["KernelModel", "Linear", "Plan", "linear_setup", "plan"]


class KernelModel(NamedTuple):
    """The model the compiled kernels take (:func:`~rollspring.simulate.kernels.kernel_model`),
    by name; the columns of the packed arrays are named by the kernels' module constants. The
    kernels are called with the plain tuple (:attr:`Plan.packed`): Numba dispatches a named
    tuple about three times slower (9 µs against 3 µs a call, a few dozen calls a run)."""

    #: (n, 12) per body: reference x, scale, rolls, centre height, inertia, mass, mu_s, ...
    bodies: FloatArray
    #: (S, 11) per spring: its ends' attachments and anchors, stiffness, rest length, damping
    springs: FloatArray
    #: (S, 2) int: the body at each end of each spring (-1: an anchor)
    spring_ends: np.ndarray
    #: (F, 4) per external force: its attachment (r, alpha) and (Fx, Fy)
    forces: FloatArray
    #: (F,) int: the body each force acts on
    force_body: np.ndarray
    #: g (m/s²)
    gravity: float


class Linear(NamedTuple):
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


def linear_setup(arrays: SystemArrays, model: tuple[Any, ...], *, sparse: bool) -> Linear:
    """:class:`Linear` of a system: with dense matrices (every mode, O(n³): the reference, up
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
    return Linear(
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


def _linspace(end: float, count: int) -> FloatArray:
    """``np.linspace(0.0, end, count)`` operation for operation (``arange * step``, the last
    set to ``end``) without its generic overhead."""
    if count < 2:
        return np.linspace(0.0, end, count)
    grid = np.arange(count, dtype=float)
    grid *= end / (count - 1)
    grid[-1] = end
    return grid


@dataclass(frozen=True, slots=True)
class Plan:
    """Everything a run is made from, decided before it starts (:func:`plan`)."""

    arrays: SystemArrays
    #: the kernel model of the initial placement (the run's reference), by name
    model: KernelModel
    #: ``model`` as the plain tuple the compiled kernels take
    packed: tuple[Any, ...]
    linear: Linear
    #: the output times (s), evenly spaced from 0 to the duration
    grid: FloatArray
    #: the integrator: a symplectic scheme of :data:`~rollspring.simulate.kernels.SCHEMES`, or
    #: ``"dop853"``
    scheme: str
    #: the nominal symplectic step (s); None for DOP853
    step: float | None
    #: the step is the accuracy contract's choice (not the caller's): a run that does not keep
    #: its energy may be started again with a smaller one
    chosen: bool
    rtol: float
    on_slip: str
    #: a spring is damped (the run goes on DOP853 from the start)
    damped: bool
    #: the relative energy error the run may reach
    tolerance: float
    progress: Callable[[float], None] | None
    #: the lowest oscillating mode's coordinate, for its period: M v (M diagonal) and the
    #: equilibrium it is measured from (zeros when there is none)
    mode_weights: FloatArray
    q_ref: FloatArray
    #: beyond :data:`~rollspring.analysis.banded.DENSE_LIMIT` bodies: the run is set up from the
    #: sparse stiffness matrix, and the kernel keeps, for each body's extreme, only the states
    #: of its ball (the bodies a refinement of it can feel,
    #: :meth:`~rollspring.simulate.run_state.RunState.balls`)
    windowed: bool
    #: how many times the run was started again with a smaller step (its energy error)
    retries: int = 0


def plan(
    arrays: SystemArrays,
    request: SimulationRequest,
    progress: Callable[[float], None] | None = None,
) -> Plan:
    """The :class:`Plan` of a run of ``request`` on the system of ``arrays``: the kernel model,
    the linear model, then the integrator and step (DOP853 when a spring is damped or it is
    asked for; a fixed ``step`` with ``auto`` means Yoshida-4; else
    :func:`~rollspring.simulate.integrators.choose_scheme` for the fastest linear frequency and
    the output times)."""
    n = arrays.n_bodies
    packed = kernels.kernel_model(arrays)  # the initial placement's: the run's reference
    windowed = n > DENSE_LIMIT
    linear = linear_setup(arrays, packed, sparse=windowed)
    damped = bool((arrays.damping > 0).any())
    name, step = pick_scheme(  # the step suits the outputs (on step ends or between)
        request.integrator,
        request.step,
        damped or arrays.resisted,  # dissipative: DOP853 with its events
        linear.omega_max,
        request.duration,
        request.rtol,
        request.outputs,
    )
    if linear.oscillating and linear.equilibrium.found:  # the lowest mode's coordinate
        mode_weights = arrays.inertia * linear.vectors[:, linear.oscillating[0]]
        q_ref = np.ascontiguousarray(linear.equilibrium.q, dtype=float)
    else:
        mode_weights, q_ref = np.zeros(n), np.zeros(n)
    tolerance = request.energy_tolerance
    return Plan(
        arrays=arrays,
        model=KernelModel(*packed),
        packed=packed,
        linear=linear,
        grid=_linspace(request.duration, request.outputs),
        scheme=name,
        step=step,
        chosen=step is not None and request.step is None,
        rtol=request.rtol,
        on_slip=request.on_slip,
        damped=damped,
        tolerance=tolerance if tolerance is not None else 100 * request.rtol + 1e-12,
        progress=progress,
        mode_weights=mode_weights,
        q_ref=q_ref,
        windowed=windowed,
    )

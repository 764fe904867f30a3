r"""The linear model of a system: its equilibrium, normal modes and stationary point, the
result type of the linear analysis and the exact linear motion.

About an equilibrium :math:`q^*` (:math:`\nabla U = 0`) the motion obeys
:math:`M\ddot u + K u = 0` with the constant diagonal :math:`M` and the exact Hessian :math:`K`
(geometric stiffness of pre-tensioned and tilted springs included), docs/physics.md (M12)-(M14).
Its solution for given initial conditions is a sum of normal modes (:func:`linear_motion`).
:class:`LinearAnalysis` holds what :func:`rollspring.analysis.modal.analyze` finds, and its JSON
form; the physics checks (:mod:`rollspring.analysis.checks`) and ``analyze`` build on this
module, never the other way round.
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from rollspring.analysis.banded import (
    ALL_MODES_LIMIT,
    DENSE_LIMIT,
    banded_modes,
    sparse_equilibrium,
)
from rollspring.analysis.conventions import CONVENTIONS
from rollspring.model import System
from rollspring.physics import (
    SystemArrays,
    generalized_forces,
    mass_matrix,
    spring_pair_matrix,
    springs_stay_level,
    stiffness_matrix,
)
from rollspring.physics.arrays import FloatArray

__all__ = [
    "ZERO_MODE_TOLERANCE",
    "Equilibrium",
    "LinearAnalysis",
    "Mode",
    "find_equilibrium",
    "linear_motion",
    "normal_modes",
    "resistance_decay",
    "stationary_weights",
]

#: An eigenvalue with |lambda| < ZERO_MODE_TOLERANCE * max|lambda| is a zero mode (omega = 0).
ZERO_MODE_TOLERANCE = 1e-10
#: :func:`find_equilibrium`'s tolerance: the largest residual, relative to the force scale
EQUILIBRIUM_TOLERANCE = 1e-13
#: Two frequencies closer than this (relative) are treated as one (degenerate modes).
_SAME_FREQUENCY = 1e-9


@dataclass(frozen=True)
class Equilibrium:
    r"""A configuration with :math:`Q(q^*) = -\nabla U = 0` and what acts there.

    ``found`` is False when no equilibrium exists near the initial placement (then ``q`` is the
    initial placement and ``reason`` says why).
    """

    q: FloatArray
    found: bool
    residual: float
    reason: str = ""
    #: the stiffness matrix K(q*) (None when no equilibrium was found)
    stiffness: FloatArray | None = None
    #: :func:`normal_modes` of (M, K(q*)): (eigenvalues, vectors, kinds), or None
    modes: tuple[FloatArray, FloatArray, np.ndarray] | None = None
    #: :func:`normal_modes` of (M, K(0)) at the initial placement, when the search computed
    #: them (None otherwise)
    placement_modes: tuple[FloatArray, FloatArray, np.ndarray] | None = None


def find_equilibrium(
    system: SystemArrays | System | dict[str, Any] | str,
    *,
    max_iterations: int = 200,
    tolerance: float = EQUILIBRIUM_TOLERANCE,
    forces: Callable[[FloatArray], FloatArray] | None = None,
    stiffness: Callable[[FloatArray], FloatArray] | None = None,
    sparse: bool | None = None,
) -> Equilibrium:
    r"""The equilibrium nearest the initial placement, with the zero modes held.

    1. Damped Newton on :math:`Q(q) = 0` restricted to the non-zero modes of the current
       iterate: :math:`\delta q = \sum_{\lambda_n \ne 0} v_n (v_n^T Q)/\lambda_n` with
       :math:`K v_n = \lambda_n M v_n`, :math:`v_n^T M v_m = \delta_{nm}`; each step at most
       0.5 rad, halved until the residual :math:`Q^T M^{-1} Q` decreases.
    2. Where the equilibrium has zero modes :math:`V_0` (a valley of equilibria), Newton on the
       bordered system :math:`Q(q) + M V_0\mu = 0,\; V_0^T M q = 0`: the point of the valley
       whose zero-mode coordinates equal those of the initial placement. The motion released
       from the initial placement conserves :math:`V_0^T M \dot q` (docs/physics.md (M14)), so it
       oscillates about this point.

    Springs attached at centres (or anchors) whose ends are level in the initial placement,
    and forces at centres (:func:`_level_centre_springs`), stay horizontal as the bodies roll:
    Q is affine in q and K does not depend on q, so the equilibrium is the first Newton step
    from the placement, :math:`q^* = \sum_{\lambda_n \ne 0} v_n (v_n^T Q_0)/\lambda_n`, with
    the zero modes held already (:math:`V_0^T M q^* = 0`). That step is taken directly, with one
    K and one set of modes, and checked (residual at most ``tolerance`` of the force scale,
    zero-mode coordinates at rounding); otherwise the general search above runs.

    Where Newton stalls, SciPy's trust-region least squares takes over, with at most
    5 ``max_iterations`` force evaluations a descent and 50 ``max_iterations`` in the whole
    search (1000 and 10 000 by default): a system with no exact root within reach (a small net
    force along a zero mode) stops there, its residual deciding as above.

    ``forces`` may replace :func:`~rollspring.physics.generalized_forces` of ``system`` by an
    equal but faster function of q (the simulator passes its compiled kernel), ``stiffness``
    likewise :func:`~rollspring.physics.stiffness_matrix`.

    Beyond :data:`~rollspring.analysis.banded.DENSE_LIMIT` bodies (or with ``sparse=True``)
    no dense matrix is formed: :func:`_large_equilibrium` (the placement when it is an
    equilibrium, else Newton with sparse factorisations); the returned ``stiffness`` and
    ``modes`` are then None. ``sparse=False`` forces the dense search.

    ``system`` is the :class:`~rollspring.physics.SystemArrays` of a system, or the system
    itself as :func:`rollspring.analyze` takes it (a System, its JSON form, a file path or a
    preset name); anything else is a one-line :class:`~rollspring.errors.ModelError`.
    """
    if not isinstance(system, SystemArrays):
        from rollspring.model import as_system
        from rollspring.physics import system_arrays

        system = system_arrays(as_system(system))
    n = system.n_bodies
    if forces is None:

        def forces(state: FloatArray) -> FloatArray:
            return generalized_forces(system, state)

    stiffness_of = stiffness
    if stiffness_of is None:

        def stiffness_of(state: FloatArray) -> FloatArray:
            return stiffness_matrix(system, state)

    inv_mass = 1.0 / system.inertia

    def residual_of(state: FloatArray) -> float:
        force = forces(state)
        return math.sqrt(float((force**2 * inv_mass).sum()))

    zeros = np.zeros(n)
    force_0 = forces(zeros)
    initial = math.sqrt(float((force_0**2 * inv_mass).sum()))
    dx, dy = _placement_vectors(system)
    lengths = np.sqrt(dx**2 + dy**2)
    scale = max(initial, _force_scale(system, lengths))
    target = tolerance * scale

    if (n > DENSE_LIMIT if sparse is None else sparse) and stiffness is None:
        large = _large_equilibrium(system, initial, target, scale)
        if large is not None:
            return large
    if _level_centre_springs(system, dx):
        level = _level_equilibrium(
            system.inertia,
            _level_stiffness(system, dx, lengths) if stiffness is None else stiffness(zeros),
            force_0,
            initial,
            target,
            residual_of,
        )
        if level is not None:
            return level

    mass = mass_matrix(system)
    root_mass = np.sqrt(system.inertia)
    #: K and the modes at the initial placement, once the search has computed them
    placement: list[tuple[FloatArray, tuple[FloatArray, FloatArray, np.ndarray]]] = []

    def modes_at(state: FloatArray) -> tuple[FloatArray, tuple[FloatArray, FloatArray, np.ndarray]]:
        if placement and not np.any(state):
            return placement[0]
        k = stiffness_of(state)
        result = (k, normal_modes(mass, k))
        if not placement and not np.any(state):
            placement.append(result)
        return result

    #: force evaluations left to SciPy's search, over every descent of this search: a system
    #: with no equilibrium within reach (a small net force along a zero mode) otherwise sent
    #: each descent to its cap and the zero-mode holding through 200 of them (an hour)
    budget = [_SEARCH_EVALUATIONS_PER_ITERATION * max_iterations]

    def exhausted() -> bool:
        return budget[0] <= 0

    def descend(start: FloatArray) -> tuple[FloatArray, float]:
        """Trust-region Newton on :math:`M^{-1/2} Q = 0` in the mass-weighted coordinates
        :math:`p = M^{1/2} q`, starting with steps of 0.1 rad: small regularised steps reach
        the nearest root, and near a valley of roots the step is the M-orthogonal projection
        onto it."""
        state, residual = start, residual_of(start)
        for _ in range(10):  # plain Newton while its steps are small and the residual falls
            if residual <= target:
                return state, residual
            _, (eigenvalues, vectors, kinds) = modes_at(state)
            nonzero = kinds != "zero"
            if not np.any(nonzero) or np.any(kinds == "unstable"):
                break  # Newton heads for saddles: leave it to the trust region
            along = vectors[:, nonzero].T @ forces(state)
            step = vectors[:, nonzero] @ (along / eigenvalues[nonzero])
            if float(np.max(np.abs(step))) > 0.1:
                break
            trial = state + step
            trial_residual = residual_of(trial)
            if not trial_residual < residual:
                break
            state, residual = trial, trial_residual
        if residual <= target or exhausted():
            return state, residual
        import scipy.optimize  # only when Newton stalls: SciPy's optimizers load on demand

        solution = scipy.optimize.least_squares(
            lambda p: forces(p / root_mass) / root_mass,
            state * root_mass,
            jac=lambda p: -stiffness_of(p / root_mass) / np.outer(root_mass, root_mass),
            method="trf",
            x_scale=0.1 * root_mass,  # trust region starts at 0.1 rad (0.1 m for sliders)
            xtol=1e-15,
            ftol=1e-15,
            gtol=1e-15,
            max_nfev=min(_DESCENT_EVALUATIONS_PER_ITERATION * max_iterations, budget[0]),
        )
        budget[0] -= int(solution.nfev)
        state = solution.x / root_mass
        return state, residual_of(state)

    q, residual = descend(zeros)
    if residual > 1e-9 * scale:
        return Equilibrium(
            np.zeros(n),
            False,
            initial,
            "no equilibrium near the initial placement: a net force acts along a direction "
            "with no restoring stiffness (the system accelerates away), or the nearest "
            "equilibrium is too far away to be found",
            placement_modes=placement[0][1] if placement else None,
        )
    stiffness_eq, modes = modes_at(q)
    n_zero = int(np.sum(modes[2] == "zero"))
    if n_zero:
        held = _hold_zero_modes(
            q, n_zero, mass, system, descend, max_iterations, stiffness_eq, exhausted
        )
        if not np.array_equal(held, q):
            q = held
            stiffness_eq, modes = modes_at(q)
            residual = residual_of(q)
    found = residual <= 1e-9 * scale
    return Equilibrium(
        q,
        found,
        residual,
        "" if found else "the equilibrium search did not converge",
        stiffness_eq if found else None,
        modes if found else None,
        placement[0][1] if placement else None,
    )


def _large_equilibrium(
    system: SystemArrays, initial: float, target: float, scale: float
) -> Equilibrium | None:
    r"""The equilibrium of a system of more than
    :data:`~rollspring.analysis.banded.DENSE_LIMIT` bodies without dense matrices: the
    placement itself when its residual is within ``target`` (a chain written with its springs
    at rest length), else Newton with sparse factorisations, bordered by the zero modes where
    K is singular (:func:`~rollspring.analysis.banded.sparse_equilibrium`). None when that
    does not converge and the dense search can still be afforded
    (:data:`~rollspring.analysis.banded.ALL_MODES_LIMIT` bodies); beyond, not found."""
    n = system.n_bodies
    if initial <= target:
        return Equilibrium(np.zeros(n), True, initial)
    q, residual, converged = sparse_equilibrium(system, target)
    if converged or residual <= 1e-9 * scale:
        return Equilibrium(q, True, residual)
    if n <= ALL_MODES_LIMIT:
        return None
    return Equilibrium(
        np.zeros(n),
        False,
        initial,
        f"no equilibrium found by sparse Newton from the initial placement ({n} bodies: the "
        "dense search with held zero modes is for at most "
        f"{ALL_MODES_LIMIT}); start the system at rest length, or tie it to a wall",
    )


def _level_centre_springs(
    system: SystemArrays, dx: FloatArray | None = None, dy: FloatArray | None = None
) -> bool:
    """True for the springs of :func:`~rollspring.physics.springs_stay_level` (level centre
    springs, forces at centres: Q(q) affine and K constant while no spring's ends pass each
    other; the class of :mod:`rollspring.analysis.batch_linear`) when, besides, no spring has
    zero length in the placement. ``dx``: the springs' horizontal extents in the placement
    (:func:`_placement_vectors`), when the caller has them."""
    if not springs_stay_level(system):
        return False
    if dx is None:
        dx, _ = _placement_vectors(system)
    return bool((dx != 0.0).all())


def _level_stiffness(
    system: SystemArrays, dx: FloatArray, lengths: FloatArray, *, sparse: bool = False
) -> Any:
    r""":func:`~rollspring.physics.stiffness_matrix` of a system of
    :func:`_level_centre_springs` (any q), :math:`K = \sum_s k_s b_s b_s^T` (M12) with the
    constant lever arms :math:`b_{si} = e_s \sigma_{si} s_i` (:math:`e_s = \pm 1` the spring's
    direction, :math:`\sigma_{si} = \pm 1` where end b / end a is on body i): the geometric
    stiffness :math:`T_sH_s` vanishes exactly on level centre springs. The same operations on
    the same numbers as ``stiffness_matrix`` (whose other terms are exact zeros there), so
    the same bits; SciPy CSR with ``sparse``."""
    direction = dx / lengths
    if not sparse and system.n_springs <= _FEW_SPRINGS:
        # a few springs: plain floats, the same products summed into each cell in the same
        # order (spring, then end pair) as the assembly below, so the same bits, without its
        # arrays (most of a small system's linear setup)
        n = system.n_bodies
        cells = [[0.0] * n for _ in range(n)]
        scale = system.scale.tolist()
        for d, k, ends in zip(
            direction.tolist(), system.stiffness.tolist(), system.end_body.tolist(), strict=True
        ):
            levers = [
                (i, d * (sign * scale[i]))
                for i, sign in zip(ends, (-1.0, 1.0), strict=True)
                if i >= 0
            ]
            for i, b_i in levers:
                for j, b_j in levers:
                    cells[i][j] += k * (b_i * b_j)
        return np.array(cells, dtype=float).reshape(n, n)
    lever = direction[:, None] * (_END_SIGN * system.scale[system.end_index])
    lever = lever * system.end_on_body
    outer = lever[:, :, None] * lever[:, None, :]
    return spring_pair_matrix(system, system.stiffness[:, None, None] * outer, sparse=sparse)


#: d = P_b - P_a: end a counts -1, end b +1
_END_SIGN = np.array([-1.0, 1.0])
#: up to this many springs, :func:`_level_stiffness` of a dense K sums plain floats
_FEW_SPRINGS = 32
#: the equilibrium search's force evaluations in SciPy's least squares, per ``max_iterations``:
#: one descent at most 5 (1000 by default; a solvable system of the property tests took at
#: most 331), the whole search at most 50 (10 000; the most such a system took was 5983)
_DESCENT_EVALUATIONS_PER_ITERATION = 5
_SEARCH_EVALUATIONS_PER_ITERATION = 50


def _level_equilibrium(
    inertia: FloatArray,
    stiffness: FloatArray,
    force_0: FloatArray,
    initial: float,
    target: float,
    residual_of: Callable[[FloatArray], float],
) -> Equilibrium | None:
    r"""The equilibrium of a system of :func:`_level_centre_springs`: one Newton step from the
    placement with the constant K (the step :func:`find_equilibrium`'s search takes first, so
    the same numbers), or None when the step does not land on an equilibrium to ``target``
    (the springs' ends would pass each other, a force along a zero mode, an unstable K) or the
    zero modes are not held to rounding: then the general search decides."""
    modes = normal_modes(inertia, stiffness)
    eigenvalues, vectors, kinds = modes
    listed = kinds.tolist()
    if "unstable" in listed:
        return None
    q = np.zeros(eigenvalues.size)
    residual = initial
    if initial > target:
        zero = kinds == "zero"
        nonzero = ~zero
        if "zero" in listed and "oscillating" not in listed:
            return None
        if q.size <= 2:  # plain floats summed in order, as the simulator's compiled twin
            # (rollspring.simulate.kernels.level_setup) sums them: the same bits (a BLAS product may
            # fuse or reorder its operations)
            rows, values = vectors.tolist(), eigenvalues.tolist()
            force_list = force_0.tolist()
            step = [0.0] * q.size
            for m in np.flatnonzero(nonzero).tolist():
                along_m = 0.0
                for i, force_i in enumerate(force_list):
                    along_m += rows[i][m] * force_i
                weight = along_m / values[m]
                for i in range(q.size):
                    step[i] += rows[i][m] * weight
            q = np.array(step)
        else:
            along = vectors[:, nonzero].T @ force_0
            q = vectors[:, nonzero] @ (along / eigenvalues[nonzero])
        residual = residual_of(q)
        if not residual <= target:
            return None
        if "zero" in listed:  # held: V0^T M q at rounding, as _hold_zero_modes checks it
            basis = vectors[:, zero]
            held = float(np.abs(basis.T @ (inertia * q)).max())
            size = max(1.0, float(np.abs(q).max()))
            if held > 1e-13 * size * float(np.abs(basis.T * inertia).max()):
                return None
    return Equilibrium(q, True, residual, "", stiffness, modes, modes)


def _valley_directions(
    system: SystemArrays,
    mass: FloatArray,
    q: FloatArray,
    n_zero: int,
    stiffness: FloatArray | None = None,
) -> FloatArray:
    """The ``n_zero`` softest M-normalised modes at ``q``: the directions along the valley."""
    if stiffness is None:
        stiffness = stiffness_matrix(system, q)
    eigenvalues, vectors = generalized_eigh(mass, stiffness)
    directions: FloatArray = vectors[:, np.argsort(np.abs(eigenvalues))[:n_zero]]
    return directions


def _hold_zero_modes(
    q: FloatArray,
    n_zero: int,
    mass: FloatArray,
    system: SystemArrays,
    descend: Callable[[FloatArray], tuple[FloatArray, float]],
    max_iterations: int,
    stiffness: FloatArray | None = None,
    exhausted: Callable[[], bool] = lambda: False,
) -> FloatArray:
    r"""Phase 2: the point of the valley of equilibria M-nearest to the initial placement.

    On the valley the tangent directions are the zero modes :math:`V_0(q)`; the M-nearest point
    has :math:`g(q) = V_0^T M q = 0` (docs/physics.md (M14): the released motion conserves
    :math:`V_0^T M \dot q`, so it oscillates about this point). Newton in the valley's own
    coordinates: move along :math:`V_0` by :math:`\alpha`, re-descend onto the valley, with the
    Jacobian :math:`\partial g/\partial\alpha` from finite differences (a straight valley, e.g.
    centre-attached springs on one floor, converges in one step). It stops, where it is, once
    the search's evaluations are ``exhausted()``.
    """
    basis = np.empty((q.size, n_zero))  # the valley directions of the current iterate

    def held(state: FloatArray) -> FloatArray:
        tangent = _valley_directions(system, mass, state, n_zero)
        result: FloatArray = basis.T @ mass @ tangent @ (tangent.T @ (mass @ state))
        return result

    size = max(1.0, float(np.max(np.abs(q))))
    known = stiffness  # K at the starting point, if the caller has it
    for _ in range(max_iterations):
        if exhausted():
            break
        basis = _valley_directions(system, mass, q, n_zero, known)
        known = None
        g = basis.T @ (mass @ q)
        if float(np.max(np.abs(g))) <= 1e-13 * size * float(np.max(np.abs(basis.T @ mass))):
            break
        h = 1e-6 * size
        jacobian = np.empty((n_zero, n_zero))
        for j in range(n_zero):
            moved, _ = descend(q + h * basis[:, j])
            jacobian[:, j] = (held(moved) - g) / h
        alpha = np.linalg.lstsq(jacobian, -g, rcond=None)[0]
        biggest = float(np.max(np.abs(basis @ alpha)))
        if biggest > 0.5:  # at most half a radian per step along the valley
            alpha *= 0.5 / biggest
        q, _ = descend(q + basis @ alpha)
        if biggest < 1e-15 * size:
            break
    return q


def _force_scale(system: SystemArrays, lengths: FloatArray | None = None) -> float:
    """A typical generalised force of the system, for relative tolerances (``lengths``: the
    springs' lengths in the placement, when the caller has them)."""
    if lengths is None:
        dx, dy = _placement_vectors(system)
        lengths = np.sqrt(dx**2 + dy**2)
    biggest = float(system.scale.max())
    spring_scale = float((system.stiffness * lengths * biggest).sum())
    applied = float(np.abs(system.force).sum()) * (biggest + float(system.force_r.max(initial=0)))
    return max(spring_scale, applied, 1e-300) / math.sqrt(float(system.inertia.min()))


def _placement_vectors(system: SystemArrays) -> tuple[FloatArray, FloatArray]:
    """Every spring's vector (end b minus end a) in the initial placement, (dx, dy):
    :func:`~rollspring.physics.spring_state` at q = 0 (the same arithmetic, so the same
    numbers; its length is ``sqrt(dx**2 + dy**2)``), without its derivatives. A few springs:
    a loop over plain floats."""
    sin = np.sin(system.end_alpha).tolist()
    cos = np.cos(system.end_alpha).tolist()
    r = system.end_r.tolist()
    anchor = system.end_anchor.tolist()
    x0, track, radius = system.x0.tolist(), system.track.tolist(), system.radius.tolist()
    dx, dy = [], []
    for s, ends in enumerate(system.end_body.tolist()):
        xy = [
            (x0[i] + r[s][j] * sin[s][j], track[i] + radius[i] + r[s][j] * cos[s][j])
            if i >= 0
            else anchor[s][j]
            for j, i in enumerate(ends)
        ]
        dx.append(xy[1][0] - xy[0][0])
        dy.append(xy[1][1] - xy[0][1])
    return np.array(dx, dtype=float), np.array(dy, dtype=float)


def resistance_decay(
    system: SystemArrays, normal: FloatArray, omega: float, vector: FloatArray
) -> float:
    r"""How much a mode's amplitude falls each period under rolling resistance, docs/physics.md
    (M23): with the mode's :math:`M`-orthonormal ``vector`` :math:`v` (:math:`v^T M v = 1`),
    frequency ``omega`` and the normal forces ``normal`` at the equilibrium, the resistance
    (M21) takes :math:`4 A_\eta\sum_i C_{rr,i} N_i s_i |v_i|` each period from the energy
    :math:`\tfrac12\omega^2 A_\eta^2` of the mode's coordinate, so

    .. math:: \Delta A_\eta = \frac{4}{\omega^2}\sum_i C_{rr,i} N_i s_i |v_i| ,

    returned as the fall of the largest centre displacement, :math:`\max_i s_i|v_i|\,\Delta
    A_\eta` (m per period): a linear fall, not an exponential one (Coulomb damping). For one body
    on a spring of stiffness :math:`k'` in its rolling coordinate it is :math:`4 C_{rr} N/k'`,
    twice :math:`2 C_{rr} N/k'` per half period, exactly; for a mode moving alone exact too (every
    body's velocity keeps its sign for half a period), a first-order estimate otherwise.
    0 without rolling resistance, or for a mode that does not oscillate."""
    if not system.resisted or not omega > 0:
        return 0.0
    lever = system.scale * np.abs(vector)
    drag = float(np.sum(system.rolling_resistance * np.asarray(normal) * lever))
    return 4.0 * drag / omega**2 * float(np.max(lever))


@dataclass(frozen=True)
class Mode:
    r"""One normal mode :math:`K v = \omega^2 M v`.

    Shapes are normalised so that the largest centre displacement is +1 m; every other field is
    the first-order change along that shape: ``shape_q`` (rad for rolling bodies, m for
    sliders), ``shape_x`` (m), ``spring_extension`` (m), ``friction`` and ``normal_force`` (N).
    ``kind`` is ``"oscillating"``, ``"zero"`` (omega = 0: a free, conserved motion) or
    ``"unstable"`` (negative eigenvalue; ``omega`` is then the growth rate).
    ``damping_ratio`` is :math:`\zeta = v^T C v/(2\omega)` (M-normalised ``v``, spring damping
    :math:`C = \sum_s c_s b_s b_s^T`): exact for modally damped systems, a projection otherwise.
    ``resistance_decay`` is how much the amplitude (the largest centre displacement, m) falls
    each period under rolling resistance, :func:`resistance_decay` (docs/physics.md (M23)).
    """

    eigenvalue: float
    omega: float
    kind: str
    shape_q: FloatArray
    shape_x: FloatArray
    spring_extension: FloatArray
    friction: FloatArray
    normal_force: FloatArray
    damping_ratio: float = 0.0
    resistance_decay: float = 0.0

    @property
    def frequency(self) -> float:
        """Frequency in Hz."""
        return self.omega / (2 * math.pi) if self.kind == "oscillating" else 0.0

    @property
    def period(self) -> float:
        """Period in s (inf for a zero or unstable mode)."""
        return (
            2 * math.pi / self.omega if self.kind == "oscillating" and self.omega > 0 else math.inf
        )


def generalized_eigh(mass: FloatArray, stiffness: FloatArray) -> tuple[FloatArray, FloatArray]:
    r"""Eigenvalues (ascending) and M-orthonormal eigenvectors (columns) of the symmetric
    problem :math:`K v = \lambda M v` (the lower triangle of K is read).

    With the diagonal M of this model (``mass`` as the (n, n) matrix or its diagonal (n,)) it is
    the standard problem of :math:`M^{-1/2} K M^{-1/2}` (NumPy's ``eigh``, LAPACK's ``syevd``),
    its vectors scaled back by :math:`M^{-1/2}`: what SciPy's generalised ``eigh`` (LAPACK's
    ``sygvd``) computes for a diagonal M, without SciPy's import (about 0.2 s) and call
    overhead. A full M goes to SciPy's generalised ``eigh`` (loaded on demand).
    Non-finite entries raise ValueError.
    """
    mass = np.asarray(mass, dtype=float)
    stiffness = np.asarray(stiffness, dtype=float)
    inertia = mass
    if mass.ndim == 2:
        inertia = np.diagonal(mass)
        if np.count_nonzero(mass) > np.count_nonzero(inertia):
            import scipy.linalg  # a full mass matrix (never this model's): SciPy, on demand

            full: tuple[FloatArray, FloatArray] = scipy.linalg.eigh(stiffness, mass)
            return full
    if not ((inertia > 0) & (inertia < math.inf)).all():
        raise ValueError("the mass matrix is not positive definite, or not finite")
    if inertia.size <= 2 and stiffness.shape == (inertia.size, inertia.size):
        small = _small_eigh(inertia.tolist(), stiffness.tolist())
        if small is not None:
            return small
    # sygvd's reduction with the Cholesky factor L = diag(b), b = sqrt(J), operation for
    # operation (its ``sygs2`` and ``trsm``), so the modes are SciPy's to the last bit:
    # C_ij = K_ij (1/b_j) / b_i below the diagonal (syevd reads the lower triangle),
    # C_ii = K_ii / b_i^2, and v = (1/b) w
    factor = np.sqrt(inertia)
    inverse = 1.0 / factor
    reduced = stiffness * inverse / factor[:, None]
    reduced.flat[:: inertia.size + 1] = np.diagonal(stiffness) / (factor * factor)
    if not np.isfinite(reduced).all():  # a non-finite K or M (a ValueError, as SciPy's)
        from rollspring.errors import NotFiniteError

        raise NotFiniteError(
            "the stiffness matrix is not finite in this configuration (a value beyond double "
            "precision, or a spring of non-zero rest length squeezed to zero length, whose "
            "force has no direction)"
        )
    eigenvalues, standard = np.linalg.eigh(reduced)
    vectors: FloatArray = standard * inverse[:, None]
    return eigenvalues, vectors


#: LAPACK's relative machine precision (``dlamch('E')``, half an ulp of 1)
_LAPACK_EPS = 2.0**-53


def _small_eigh(
    inertia: list[float], stiffness: list[list[float]]
) -> tuple[FloatArray, FloatArray] | None:
    r""":func:`generalized_eigh` of one or two coordinates in plain floats: the same
    operations as LAPACK's ``sygvd`` reduction and ``syevd`` (NumPy's ``eigh``), which for
    one coordinate returns :math:`C_{11}` and 1, and for two takes the tridiagonal
    :math:`(d_1, e, d_2) = (C_{11}, C_{21}, C_{22})` to ``steqr``: ``laev2``'s eigenvalues
    and rotation, or :math:`e = 0` where :math:`|e| \le \sqrt{|d_1|}\sqrt{|d_2|}\,\epsilon`,
    then sorted ascending (checked bit for bit against NumPy on random matrices:
    tests/test_analysis.py). None when it cannot stand in for LAPACK: non-finite numbers, or
    norms LAPACK would rescale (below 1e-140 or above 1e140)."""
    factor = [math.sqrt(m) for m in inertia]
    inverse = [1.0 / b for b in factor]
    if len(inertia) == 1:
        c11 = stiffness[0][0] / (factor[0] * factor[0])
        if not math.isfinite(c11):
            return None
        return np.array([c11]), np.array([[inverse[0]]])
    (k11, k12), (k21, k22) = stiffness
    if not all(map(math.isfinite, (k11, k12, k21, k22))):
        return None
    d1 = k11 / (factor[0] * factor[0])
    e = k21 * inverse[0] / factor[1]
    d2 = k22 / (factor[1] * factor[1])
    norm = max(abs(d1), abs(e), abs(d2))
    if not math.isfinite(norm) or (norm != 0.0 and not 1e-140 < norm < 1e140):
        return None
    if e == 0.0 or abs(e) <= (math.sqrt(abs(d1)) * math.sqrt(abs(d2))) * _LAPACK_EPS:
        w, (c, s) = [d1, d2], (1.0, 0.0)
    else:
        rt1, rt2, c, s = _laev2(d1, e, d2)
        w = [rt1, rt2]
    z = [[c, -s], [s, c]]  # steqr's rotation of the identity: columns (c, s), (-s, c)
    if w[1] < w[0]:  # steqr's closing selection sort
        w, z = [w[1], w[0]], [[z[0][1], z[0][0]], [z[1][1], z[1][0]]]
    vectors = [
        [z[0][0] * inverse[0], z[0][1] * inverse[0]],
        [z[1][0] * inverse[1], z[1][1] * inverse[1]],
    ]
    return np.array(w), np.array(vectors)


def _laev2(a: float, b: float, c: float) -> tuple[float, float, float, float]:
    """LAPACK's ``dlaev2``: eigenvalues ``rt1`` (the larger in magnitude) and ``rt2`` of
    [[a, b], [b, c]], and the unit eigenvector (cs1, sn1) of ``rt1``, operation for
    operation."""
    sm = a + c
    df = a - c
    adf = abs(df)
    tb = b + b
    ab = abs(tb)
    acmx, acmn = (a, c) if abs(a) > abs(c) else (c, a)
    # a square is a product, as compiled Fortran (and Numba) computes ``(AB/ADF)**2``: Python's
    # ``** 2`` calls the C library's pow, off by an ulp for about 1 in 1000 arguments
    if adf > ab:
        ratio = ab / adf
        rt = adf * math.sqrt(1.0 + ratio * ratio)
    elif adf < ab:
        ratio = adf / ab
        rt = ab * math.sqrt(1.0 + ratio * ratio)
    else:
        rt = ab * math.sqrt(2.0)
    if sm < 0.0:
        rt1 = 0.5 * (sm - rt)
        sgn1 = -1
        rt2 = (acmx / rt1) * acmn - (b / rt1) * b
    elif sm > 0.0:
        rt1 = 0.5 * (sm + rt)
        sgn1 = 1
        rt2 = (acmx / rt1) * acmn - (b / rt1) * b
    else:
        rt1 = 0.5 * rt
        rt2 = -0.5 * rt
        sgn1 = 1
    if df >= 0.0:
        cs = df + rt
        sgn2 = 1
    else:
        cs = df - rt
        sgn2 = -1
    if abs(cs) > ab:
        ct = -tb / cs
        sn1 = 1.0 / math.sqrt(1.0 + ct * ct)
        cs1 = ct * sn1
    elif ab == 0.0:
        cs1, sn1 = 1.0, 0.0
    else:
        tn = -cs / tb
        cs1 = 1.0 / math.sqrt(1.0 + tn * tn)
        sn1 = tn * cs1
    if sgn1 == sgn2:
        cs1, sn1 = -sn1, cs1
    return rt1, rt2, cs1, sn1


def normal_modes(
    mass: FloatArray, stiffness: FloatArray
) -> tuple[FloatArray, FloatArray, np.ndarray]:
    r"""Solve the symmetric generalised eigenproblem :math:`K v = \lambda M v`
    (:func:`generalized_eigh`).

    Returns eigenvalues (ascending), M-orthonormal eigenvectors (columns) and the kind of each
    mode: eigenvalues with :math:`|\lambda| < 10^{-10}\max|\lambda|` are zero modes and are
    returned as exactly 0.
    """
    eigenvalues, vectors = generalized_eigh(mass, stiffness)
    values = eigenvalues.tolist()  # a few numbers: plain floats are faster than NumPy's calls
    largest = max(map(abs, values), default=0.0)
    kinds = np.empty(len(values), dtype=object)
    for n, lam in enumerate(values):
        if largest == 0.0 or abs(lam) < ZERO_MODE_TOLERANCE * largest:
            kinds[n] = "zero"
            eigenvalues[n] = values[n] = 0.0
        elif lam < 0:
            kinds[n] = "unstable"
        else:
            kinds[n] = "oscillating"
    if all(a <= b for a, b in itertools.pairwise(values)):
        return eigenvalues, vectors, kinds  # still ascending (the usual case)
    order = np.argsort(eigenvalues, kind="stable")
    return eigenvalues[order], vectors[:, order], kinds[order]


def stationary_weights(
    system: SystemArrays, vectors: FloatArray, kinds: np.ndarray
) -> FloatArray | None:
    r"""Weights of the generalised stationary point (docs/physics.md (M14)),
    :math:`w_i = J_i v_{0i}/s_i` normalised to :math:`\sum w = 1`, from the single zero mode
    :math:`v_0` among ``vectors`` (columns, kinds from :func:`normal_modes`); None when there is
    no zero mode, more than one, or its weights sum to zero (no point is stationary)."""
    listed = np.asarray(kinds).tolist()
    if listed.count("zero") != 1:
        return None
    raw = system.inertia * vectors[:, listed.index("zero")] / system.scale
    total = float(raw.sum())
    if not abs(total) > 1e-9 * float(np.abs(raw).sum()):
        return None
    weights: FloatArray = raw / total
    weights[np.abs(weights) < 1e-15] = 0.0
    return weights


@dataclass(frozen=True)
class LinearAnalysis:
    """Everything the linear analysis of a system finds (see :func:`rollspring.analyze`)."""

    system: System
    arrays: SystemArrays
    equilibrium: Equilibrium
    mass: FloatArray
    stiffness: FloatArray
    modes: list[Mode]
    equilibrium_friction: FloatArray
    equilibrium_normal: FloatArray
    spring_tilt_deg: FloatArray
    spring_tension: FloatArray
    spring_length: FloatArray
    stationary_weights: FloatArray | None
    stationary_position: float | None
    stationary_velocity: float | None
    amplitude: FloatArray | None
    velocity_amplitude: FloatArray | None
    drift_velocity: FloatArray | None
    cm_amplitude: float | None
    stationary_amplitude: float | None
    friction_amplitude: FloatArray | None
    normal_force_range: FloatArray | None
    required_mu: FloatArray | None
    spring_split: dict[str, Any] | None
    warnings: list[str] = field(default_factory=list)

    @property
    def ids(self) -> tuple[str, ...]:
        """Body ids, in the order of the coordinates."""
        return self.arrays.ids

    @property
    def oscillating(self) -> list[Mode]:
        """The modes with omega > 0."""
        return [m for m in self.modes if m.kind == "oscillating"]

    def to_dict(self) -> dict[str, Any]:
        """The JSON form printed by ``rollspring analyze --json`` (see the README): every
        number finite or null, every per-body value keyed by id, the sign conventions
        (:data:`rollspring.analysis.conventions.CONVENTIONS`) stated."""
        arrays = self.arrays
        ids = arrays.ids
        q = self.equilibrium.q
        rotation = arrays.rolls * q
        sparse = hasattr(self.stiffness, "tocoo")  # a large system's SciPy sparse K
        modes = []
        for mode in self.modes:
            entry: dict[str, Any] = {
                "kind": mode.kind,
                "omega": _num(mode.omega) if mode.kind != "unstable" else 0.0,
                "growth_rate": _num(mode.omega) if mode.kind == "unstable" else None,
                "frequency_hz": _num(mode.frequency),
                "period": _num(mode.period),
                "damping_ratio": _num(mode.damping_ratio),
            }
            if arrays.resisted:  # (M23): the amplitude's fall per period (m)
                entry["resistance_decay_per_period"] = _num(mode.resistance_decay)
            if sparse:  # n numbers per mode and field: summarised, the shapes in Python
                entry["peak_friction"] = _num(float(np.max(np.abs(mode.friction), initial=0)))
                entry["peak_normal_force"] = _num(
                    float(np.max(np.abs(mode.normal_force), initial=0))
                )
            else:
                entry.update(
                    {
                        "shape": _by_id(ids, mode.shape_x),
                        "shape_phi": _by_id(ids, arrays.rolls * mode.shape_q),
                        "spring_extension": [_num(v) for v in mode.spring_extension],
                        "friction": _by_id(ids, mode.friction),
                        "normal_force": _by_id(ids, mode.normal_force),
                    }
                )
            modes.append(entry)
        stationary = None
        if self.stationary_weights is not None:
            weights = self.stationary_weights
            cm_weights = arrays.mass / arrays.mass.sum()
            stationary = {
                "weights": _by_id(ids, weights),
                "position": _num(self.stationary_position or 0.0),
                "velocity": _num(self.stationary_velocity or 0.0),
                "is_centre_of_mass": bool(np.allclose(weights, cm_weights, rtol=1e-9, atol=1e-12)),
            }
        response = None
        if self.amplitude is not None:
            assert self.friction_amplitude is not None
            assert self.normal_force_range is not None and self.required_mu is not None
            response = {
                "amplitude": _by_id(ids, self.amplitude),
                "velocity_amplitude": _by_id(ids, self.velocity_amplitude),
                "drift_velocity": _by_id(ids, self.drift_velocity),
                "cm_amplitude": _num(self.cm_amplitude or 0.0),
                "stationary_point_amplitude": (
                    None if self.stationary_amplitude is None else _num(self.stationary_amplitude)
                ),
                "friction_amplitude": _by_id(ids, self.friction_amplitude),
                "normal_force_range": {
                    i: [_num(lo), _num(hi)]
                    for i, (lo, hi) in zip(ids, self.normal_force_range, strict=True)
                },
                "required_mu": _by_id(ids, self.required_mu),
            }
        springs = []
        for s, name in enumerate(arrays.spring_names):
            spring = self.system.springs[s]
            springs.append(
                {
                    "name": name,
                    "ends": list(spring.ends),
                    "tilt_deg": _num(self.spring_tilt_deg[s]),
                    "tension": _num(self.spring_tension[s]),
                    "length": _num(self.spring_length[s]),
                    "rest_length": _num(arrays.rest_length[s]),
                }
            )
        split = None
        if self.spring_split is not None:
            split = {
                "k": _by_id(ids, self.spring_split["k"]),
                "share": _by_id(ids, self.spring_split["share"]),
                "clamped_omega": _by_id(ids, self.spring_split["clamped_omega"]),
                "omega": _num(self.spring_split["omega"]),
            }
        return {
            "system": self.system.name,
            "coordinates": list(ids),
            "coordinate_units": {
                i: ("rad" if r else "m") for i, r in zip(ids, arrays.rolls, strict=True)
            },
            "conventions": CONVENTIONS,
            "matrices": _sparse_matrices(self.mass, self.stiffness)
            if sparse
            else {
                "M": [[_num(v) for v in row] for row in self.mass],
                "K": [[_num(v) for v in row] for row in self.stiffness],
            },
            "equilibrium": {
                "found": self.equilibrium.found,
                "phi": _by_id(ids, rotation),
                "x": _by_id(ids, arrays.x0 + arrays.scale * q),
                "friction": _by_id(ids, self.equilibrium_friction),
                "normal_force": _by_id(ids, self.equilibrium_normal),
            },
            "modes": modes,
            "stationary_point": stationary,
            "response": response,
            "springs": springs,
            "spring_split": split,
            "warnings": list(self.warnings),
        }


def _sparse_matrices(mass: Any, stiffness: Any) -> dict[str, Any]:
    """M and K of a large system in ``analyze --json``: M's diagonal and K's non-zero entries
    (0-based row, column, value), O(n) numbers instead of n²."""
    coo = stiffness.tocoo()
    return {
        "M_diagonal": [_num(v) for v in mass.diagonal()],
        "K_entries": [
            [int(i), int(j), _num(v)]
            for i, j, v in zip(coo.row.tolist(), coo.col.tolist(), coo.data.tolist(), strict=True)
        ],
    }


def _num(value: float) -> float | None:
    value = float(value)
    if not math.isfinite(value):
        return None
    return 0.0 if value == 0 else value


def _by_id(ids: tuple[str, ...], values: Any) -> dict[str, float | None]:
    return {i: _num(v) for i, v in zip(ids, np.asarray(values, dtype=float), strict=True)}


def linear_motion(analysis: LinearAnalysis, t: FloatArray) -> FloatArray:
    r"""The motion of the linearised system from the initial state, by exact modal
    superposition: centre positions :math:`x_i(t) = x_{i0} + s_i q_i(t)` (m), shape
    (len(t), n_bodies).

    With :math:`u = q - q^*`, M-orthonormal modes :math:`v_n` (:math:`K v_n = \lambda_n M v_n`,
    docs/physics.md (M12)) and :math:`\eta_n = v_n^T M u`, each mode moves on its own:
    :math:`\eta_n(t) = \eta_{n0}\cos\omega_n t + \dot\eta_{n0}\sin(\omega_n t)/\omega_n`
    (oscillating), :math:`\eta_{n0} + \dot\eta_{n0} t` (zero mode, (M14)),
    :math:`\eta_{n0}\cosh\kappa_n t + \dot\eta_{n0}\sinh(\kappa_n t)/\kappa_n` (unstable,
    :math:`\kappa_n^2 = -\lambda_n`); the start is :math:`q(0) = 0` (the initial placement),
    :math:`\dot q(0) = v_0/s`. Without an equilibrium there is no linear motion: ValueError.
    """
    if not analysis.equilibrium.found:
        raise ValueError("no equilibrium near the initial placement: no linear motion")
    arrays = analysis.arrays
    times = np.asarray(t, dtype=float)
    if hasattr(analysis.stiffness, "tocoo"):  # a large system's sparse K: every mode, banded
        eigenvalues, found, kinds, _ = banded_modes(arrays, analysis.stiffness)
        assert found is not None
        vectors = found
        mass = arrays.inertia
    else:
        eigenvalues, vectors, kinds = normal_modes(analysis.mass, analysis.stiffness)
        mass = np.diag(analysis.mass) if np.ndim(analysis.mass) == 2 else analysis.mass
    q_eq = analysis.equilibrium.q
    eta0 = vectors.T @ (mass * -q_eq)
    etadot0 = vectors.T @ (mass * arrays.v0 / arrays.scale)
    eta = np.empty((times.size, eigenvalues.size))
    for n, (lam, kind) in enumerate(zip(eigenvalues, kinds, strict=True)):
        if kind == "oscillating":
            rate = math.sqrt(lam)
            eta[:, n] = eta0[n] * np.cos(rate * times) + etadot0[n] / rate * np.sin(rate * times)
        elif kind == "unstable":
            rate = math.sqrt(-lam)
            eta[:, n] = eta0[n] * np.cosh(rate * times) + etadot0[n] / rate * np.sinh(rate * times)
        else:
            eta[:, n] = eta0[n] + etadot0[n] * times
    q = q_eq + eta @ vectors.T
    return arrays.x0 + arrays.scale * q

r"""Linear analysis: equilibrium, normal modes, the stationary point, the exact linear response.

About an equilibrium :math:`q^*` (:math:`\nabla U = 0`) the motion obeys
:math:`M\ddot u + K u = 0` with the constant diagonal :math:`M` and the exact Hessian :math:`K`
(geometric stiffness of pre-tensioned and tilted springs included), docs/physics.md (M12)-(M14).
Its solution for given initial conditions is a sum of normal modes; every quantity that depends
linearly on the state (centre positions, the CM, friction, normal forces, spring lengths) is then
a constant plus a sum of sinusoids, whose amplitudes are reported here.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass, field, replace
from typing import Any

import numpy as np
import scipy.linalg

from rollspring.model import System
from rollspring.physics import (
    SystemArrays,
    contact_forces,
    contact_forces_jacobian,
    damping_matrix,
    generalized_forces,
    mass_matrix,
    spring_state,
    stiffness_matrix,
    system_arrays,
)
from rollspring.physics.arrays import FloatArray

__all__ = [
    "ZERO_MODE_TOLERANCE",
    "Equilibrium",
    "LinearAnalysis",
    "Mode",
    "analyze",
    "find_equilibrium",
    "linear_motion",
    "normal_modes",
    "stationary_weights",
]

#: An eigenvalue with |lambda| < ZERO_MODE_TOLERANCE * max|lambda| is a zero mode (omega = 0).
ZERO_MODE_TOLERANCE = 1e-10
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


def find_equilibrium(
    system: SystemArrays,
    *,
    max_iterations: int = 200,
    tolerance: float = 1e-13,
    forces: Callable[[FloatArray], FloatArray] | None = None,
    stiffness: Callable[[FloatArray], FloatArray] | None = None,
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

    ``forces`` may replace :func:`~rollspring.physics.generalized_forces` of ``system`` by an
    equal but faster function of q (the simulator passes its compiled kernel), ``stiffness``
    likewise :func:`~rollspring.physics.stiffness_matrix` (the simulator passes one that keeps
    K at the start).
    """
    n = system.n_bodies
    if forces is None:

        def forces(state: FloatArray) -> FloatArray:
            return generalized_forces(system, state)

    stiffness_of = stiffness
    if stiffness_of is None:

        def stiffness_of(state: FloatArray) -> FloatArray:
            return stiffness_matrix(system, state)

    mass = mass_matrix(system)
    inv_mass = 1.0 / system.inertia

    def residual_of(state: FloatArray) -> float:
        force = forces(state)
        return float(np.sqrt(np.sum(force**2 * inv_mass)))

    initial = residual_of(np.zeros(n))
    scale = max(initial, _force_scale(system))
    target = tolerance * scale

    root_mass = np.sqrt(system.inertia)

    def descend(start: FloatArray) -> tuple[FloatArray, float]:
        """Trust-region Newton on :math:`M^{-1/2} Q = 0` in the mass-weighted coordinates
        :math:`p = M^{1/2} q`, starting with steps of 0.1 rad: small regularised steps reach
        the nearest root, and near a valley of roots the step is the M-orthogonal projection
        onto it."""
        state, residual = start, residual_of(start)
        for _ in range(10):  # plain Newton while its steps are small and the residual falls
            if residual <= target:
                return state, residual
            eigenvalues, vectors, kinds = normal_modes(mass, stiffness_of(state))
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
        if residual <= target:
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
            max_nfev=100 * max_iterations,
        )
        state = solution.x / root_mass
        return state, residual_of(state)

    q, residual = descend(np.zeros(n))
    if residual > 1e-9 * scale:
        return Equilibrium(
            np.zeros(n),
            False,
            initial,
            "no equilibrium near the initial placement: a net force acts along a direction "
            "with no restoring stiffness (the system accelerates away), or the nearest "
            "equilibrium is too far away to be found",
        )
    stiffness_eq = stiffness_of(q)
    modes = normal_modes(mass, stiffness_eq)
    n_zero = int(np.sum(modes[2] == "zero"))
    if n_zero:
        held = _hold_zero_modes(q, n_zero, mass, system, descend, max_iterations, stiffness_eq)
        if not np.array_equal(held, q):
            q, stiffness_eq = held, stiffness_of(held)
            modes = normal_modes(mass, stiffness_eq)
            residual = residual_of(q)
    found = residual <= 1e-9 * scale
    return Equilibrium(
        q,
        found,
        residual,
        "" if found else "the equilibrium search did not converge",
        stiffness_eq if found else None,
        modes if found else None,
    )


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
    eigenvalues, vectors = scipy.linalg.eigh(stiffness, mass)
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
) -> FloatArray:
    r"""Phase 2: the point of the valley of equilibria M-nearest to the initial placement.

    On the valley the tangent directions are the zero modes :math:`V_0(q)`; the M-nearest point
    has :math:`g(q) = V_0^T M q = 0` (docs/physics.md (M14): the released motion conserves
    :math:`V_0^T M \dot q`, so it oscillates about this point). Newton in the valley's own
    coordinates: move along :math:`V_0` by :math:`\alpha`, re-descend onto the valley, with the
    Jacobian :math:`\partial g/\partial\alpha` from finite differences (a straight valley, e.g.
    centre-attached springs on one floor, converges in one step).
    """
    basis = np.empty((q.size, n_zero))  # the valley directions of the current iterate

    def held(state: FloatArray) -> FloatArray:
        tangent = _valley_directions(system, mass, state, n_zero)
        result: FloatArray = basis.T @ mass @ tangent @ (tangent.T @ (mass @ state))
        return result

    size = max(1.0, float(np.max(np.abs(q))))
    known = stiffness  # K at the starting point, if the caller has it
    for _ in range(max_iterations):
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


def _force_scale(system: SystemArrays) -> float:
    """A typical generalised force of the system, for relative tolerances."""
    springs = spring_state(system, np.zeros(system.n_bodies))
    spring_scale = np.sum(system.stiffness * springs.length * np.max(system.scale))
    applied = np.sum(np.abs(system.force)) * (
        np.max(system.scale) + np.max(system.force_r, initial=0)
    )
    return float(max(spring_scale, applied, 1e-300) / np.sqrt(np.min(system.inertia)))


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


def normal_modes(
    mass: FloatArray, stiffness: FloatArray
) -> tuple[FloatArray, FloatArray, np.ndarray]:
    r"""Solve the symmetric generalised eigenproblem :math:`K v = \lambda M v` (SciPy ``eigh``).

    Returns eigenvalues (ascending), M-orthonormal eigenvectors (columns) and the kind of each
    mode: eigenvalues with :math:`|\lambda| < 10^{-10}\max|\lambda|` are zero modes and are
    returned as exactly 0.
    """
    eigenvalues, vectors = scipy.linalg.eigh(stiffness, mass)
    largest = float(np.max(np.abs(eigenvalues))) if eigenvalues.size else 0.0
    kinds = np.empty(eigenvalues.size, dtype=object)
    for n, lam in enumerate(eigenvalues):
        if largest == 0.0 or abs(lam) < ZERO_MODE_TOLERANCE * largest:
            kinds[n] = "zero"
            eigenvalues[n] = 0.0
        elif lam < 0:
            kinds[n] = "unstable"
        else:
            kinds[n] = "oscillating"
    order = np.argsort(eigenvalues, kind="stable")
    return eigenvalues[order], vectors[:, order], kinds[order]


def stationary_weights(
    system: SystemArrays, vectors: FloatArray, kinds: np.ndarray
) -> FloatArray | None:
    r"""Weights of the generalised stationary point (docs/physics.md (M14)),
    :math:`w_i = J_i v_{0i}/s_i` normalised to :math:`\sum w = 1`, from the single zero mode
    :math:`v_0` among ``vectors`` (columns, kinds from :func:`normal_modes`); None when there is
    no zero mode, more than one, or its weights sum to zero (no point is stationary)."""
    zero = np.flatnonzero(np.asarray(kinds) == "zero")
    if zero.size != 1:
        return None
    raw = system.inertia * vectors[:, zero[0]] / system.scale
    total = float(np.sum(raw))
    if not abs(total) > 1e-9 * float(np.sum(np.abs(raw))):
        return None
    weights = raw / total
    weights[np.abs(weights) < 1e-15] = 0.0
    return weights


@dataclass(frozen=True)
class _Component:
    """A quantity g(t) = centre + sum_groups Re(amplitude_g exp(i omega_g t)) (+ drift t)."""

    centre: FloatArray
    amplitudes: np.ndarray  # (groups, ...) complex
    drift: FloatArray

    @property
    def amplitude(self) -> FloatArray:
        """Supremum over time of |g - centre| (exact for one frequency; for several, the
        supremum over all phases, approached arbitrarily closely by incommensurate motion)."""
        result: FloatArray = np.sum(np.abs(self.amplitudes), axis=0)
        return result


@dataclass(frozen=True)
class LinearAnalysis:
    """Everything the linear analysis of a system finds (see :func:`analyze`)."""

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
        """The JSON form printed by ``rollspring analyze --json`` (see the README)."""
        from rollspring.analysis.report import analysis_to_dict

        return analysis_to_dict(self)


def analyze(system: System) -> LinearAnalysis:
    r"""Linear analysis of a system about the equilibrium nearest its initial placement.

    Finds the equilibrium (:func:`find_equilibrium`), builds :math:`M` and :math:`K`
    (docs/physics.md (M12)), the normal modes, the zero modes and the stationary point they imply
    (M14), the exact linear response to the initial conditions (modal superposition): the
    amplitude of every body, of the CM and of :math:`\hat X`, the friction and normal-force
    amplitudes, the static friction coefficient the motion needs (:math:`\max |f|/N`), for two
    bodies the paper's split of the spring into :math:`k_1, k_2`, and each spring's tilt and
    tension.
    """
    arrays = system_arrays(system)
    warnings: list[str] = []
    equilibrium = find_equilibrium(arrays)
    if not equilibrium.found:
        warnings.append(
            equilibrium.reason + "; modes are those at the initial placement, and no "
            "response is computed"
        )
    q_eq = equilibrium.q
    mass = mass_matrix(arrays)
    stiffness = stiffness_matrix(arrays, q_eq)
    eigenvalues, vectors, kinds = normal_modes(mass, stiffness)
    d_friction, d_normal = contact_forces_jacobian(arrays, q_eq)
    friction_eq, normal_eq = contact_forces(arrays, q_eq)
    friction_eq = np.where(np.abs(friction_eq) < 1e-12 * _contact_scale(arrays), 0.0, friction_eq)
    springs = spring_state(arrays, q_eq)

    modes = []
    for lam, vec, kind in zip(eigenvalues, vectors.T, kinds, strict=True):
        modes.append(_mode(arrays, springs.lever, d_friction, d_normal, lam, vec, kind))

    # zero modes and the stationary point (M14)
    zero = [k for k, kind in enumerate(kinds) if kind == "zero"]
    weights = stationary_weights(arrays, vectors, kinds)
    position = velocity = None
    if weights is not None:
        position = float(weights @ arrays.x0)
        velocity = float(_clean(weights @ arrays.v0, float(np.max(np.abs(arrays.v0)))))
        if velocity != 0.0:
            warnings.append(
                f"the initial velocities move the stationary point X̂ uniformly at "
                f"{velocity:.6g} m/s"
            )
    elif len(zero) == 1:
        warnings.append("the conserved combination has zero total weight: no stationary point")
    elif len(zero) > 1:
        warnings.append(
            f"{len(zero)} zero modes (parts of the system move freely): no single stationary point"
        )

    unstable = [m for m in modes if m.kind == "unstable"]
    response: dict[str, Any] = {}
    if not equilibrium.found:
        pass
    elif unstable:
        warnings.append(
            f"the equilibrium is unstable ({len(unstable)} mode(s) with negative stiffness, "
            f"growth rate {unstable[0].omega:.6g} 1/s): no bounded linear response"
        )
    else:
        response = _response(
            arrays,
            q_eq,
            eigenvalues,
            vectors,
            kinds,
            d_friction,
            d_normal,
            friction_eq,
            normal_eq,
            springs.lever,
            weights,
        )

    tilt = _tilt_deg(springs.vector)
    split = _spring_split(arrays, springs.lever) if equilibrium.found else None
    damping = damping_matrix(arrays, q_eq)
    if np.any(arrays.damping > 0):
        ratios = []
        for k, mode in enumerate(modes):
            if mode.kind == "oscillating":
                ratio = float(vectors[:, k] @ damping @ vectors[:, k]) / (2 * mode.omega)
                modes[k] = replace(mode, damping_ratio=ratio)
                ratios.append(f"{ratio:.4g}")
        warnings.append(
            "springs have damping: the modes are the undamped ones, with modal damping ratios "
            f"({', '.join(ratios)}) from the modal projection of C; the response amplitudes are "
            "those of the undamped motion (the first swing)"
        )
    analysis = LinearAnalysis(
        system=system,
        arrays=arrays,
        equilibrium=equilibrium,
        mass=mass,
        stiffness=stiffness,
        modes=modes,
        equilibrium_friction=friction_eq,
        equilibrium_normal=normal_eq,
        spring_tilt_deg=tilt,
        spring_tension=np.where(
            np.abs(springs.tension) < 1e-12 * arrays.stiffness.sum(), 0.0, springs.tension
        ),
        spring_length=springs.length,
        stationary_weights=weights,
        stationary_position=position,
        stationary_velocity=velocity,
        amplitude=response.get("amplitude"),
        velocity_amplitude=response.get("velocity_amplitude"),
        drift_velocity=response.get("drift_velocity"),
        cm_amplitude=response.get("cm_amplitude"),
        stationary_amplitude=response.get("stationary_amplitude"),
        friction_amplitude=response.get("friction_amplitude"),
        normal_force_range=response.get("normal_force_range"),
        required_mu=response.get("required_mu"),
        spring_split=split,
        warnings=warnings,
    )
    from rollspring.analysis.checks import physics_warnings

    warnings.extend(physics_warnings(analysis))
    return analysis


def _contact_scale(arrays: SystemArrays) -> float:
    return float(np.sum(arrays.mass) * max(arrays.gravity, 1.0) + np.sum(arrays.stiffness) * 1.0)


def _mode(
    arrays: SystemArrays,
    lever: FloatArray,
    d_friction: FloatArray,
    d_normal: FloatArray,
    eigenvalue: float,
    vector: FloatArray,
    kind: str,
) -> Mode:
    shape_x = arrays.scale * vector
    biggest = int(np.argmax(np.abs(shape_x)))
    norm = shape_x[biggest]
    shape_q = vector / norm
    shape_x = shape_x / norm
    length_scale = float(np.max(np.abs(lever), initial=0.0)) * float(np.max(np.abs(shape_q)))
    # rounding noise of an exact zero, relative to the largest force change along the mode: a
    # contact force's, or the springs' (k times the extension; frictionless geometries have
    # contact forces that vanish to first order, and then only the springs set the scale)
    force_scale = float(np.max(np.abs(np.concatenate([d_friction, d_normal])), initial=0.0))
    force_scale *= float(np.max(np.abs(shape_q)))
    force_scale = max(force_scale, float(np.max(arrays.stiffness, initial=0.0)) * length_scale)
    return Mode(
        eigenvalue=float(eigenvalue),
        omega=float(math.sqrt(abs(eigenvalue))),
        kind=str(kind),
        shape_q=_clean(shape_q, float(np.max(np.abs(shape_q)))),
        shape_x=_clean(shape_x, 1.0),
        spring_extension=_clean(lever @ shape_q, length_scale),
        friction=_clean(d_friction @ shape_q, force_scale),
        normal_force=_clean(d_normal @ shape_q, force_scale),
    )


def _clean(values: FloatArray, scale: float, relative: float = 1e-12) -> FloatArray:
    """Set entries below ``relative * scale`` (rounding noise of an exact zero) to 0."""
    values = np.asarray(values, dtype=float)
    return np.where(np.abs(values) <= relative * scale, 0.0, values)


def _response(
    arrays: SystemArrays,
    q_eq: FloatArray,
    eigenvalues: FloatArray,
    vectors: FloatArray,
    kinds: np.ndarray,
    d_friction: FloatArray,
    d_normal: FloatArray,
    friction_eq: FloatArray,
    normal_eq: FloatArray,
    lever: FloatArray,
    weights: FloatArray | None,
) -> dict[str, Any]:
    r"""Modal superposition of the free response from q(0) = 0, qdot(0) = v0/s.

    With :math:`u = q - q^*`, :math:`\eta_n = v_n^T M u`: an oscillating mode gives
    :math:`\eta_n(t) = \mathrm{Re}[(\eta_{n0} - i\dot\eta_{n0}/\omega_n) e^{i\omega_n t}]`, a
    zero mode :math:`\eta_{n0} + \dot\eta_{n0} t`.
    """
    mass = arrays.inertia
    u0 = -q_eq
    udot0 = arrays.v0 / arrays.scale
    eta0 = vectors.T @ (mass * u0)
    etadot0 = vectors.T @ (mass * udot0)
    oscillating = [k for k, kind in enumerate(kinds) if kind == "oscillating"]
    zero = [k for k, kind in enumerate(kinds) if kind == "zero"]
    omegas = np.sqrt(eigenvalues[oscillating])
    complex_amp = eta0[oscillating] - 1j * etadot0[oscillating] / omegas
    groups = _frequency_groups(omegas)

    def component(per_mode: FloatArray, centre_eq: FloatArray | float) -> _Component:
        """per_mode: (..., n_modes) coefficient of each M-normalised mode in the quantity."""
        per_mode = np.asarray(per_mode)
        centre = centre_eq + per_mode[..., zero] @ eta0[zero]
        drift = per_mode[..., zero] @ etadot0[zero]
        osc = per_mode[..., oscillating] * complex_amp
        amps = (
            np.array([osc[..., g].sum(axis=-1) for g in groups])
            if groups
            else np.zeros((0, *per_mode.shape[:-1]), dtype=complex)
        )
        return _Component(np.asarray(centre, dtype=float), amps, np.asarray(drift, dtype=float))

    x_modes = arrays.scale[:, None] * vectors
    x_eq = arrays.x0 + arrays.scale * q_eq
    position = component(x_modes, x_eq)
    cm = component(
        arrays.mass @ x_modes / arrays.mass.sum(), float(arrays.mass @ x_eq / arrays.mass.sum())
    )
    friction = component(d_friction @ vectors, friction_eq)
    normal = component(d_normal @ vectors, normal_eq)
    length_scale = float(np.max(position.amplitude, initial=0.0))
    # rounding noise of an exact zero: relative to the largest force change the motion brings
    extension = np.abs(lever @ vectors[:, oscillating]) @ np.abs(complex_amp)  # per spring
    force_scale = float(np.max(arrays.stiffness * extension, initial=0.0))
    friction_amplitude = _clean(friction.amplitude, force_scale)
    friction = _Component(_clean(friction.centre, force_scale), friction.amplitudes, friction.drift)
    required = _required_mu(arrays, friction, normal)
    required[(friction_amplitude == 0.0) & (friction.centre == 0.0)] = 0.0
    result: dict[str, Any] = {
        "amplitude": position.amplitude,
        # d/dt multiplies each frequency group's complex amplitude by i omega
        "velocity_amplitude": np.sum(
            np.abs(position.amplitudes) * omegas[[g[0] for g in groups]][:, None], axis=0
        )
        if groups
        else np.zeros(arrays.n_bodies),
        "drift_velocity": _clean(position.drift, float(np.max(np.abs(arrays.v0), initial=0.0))),
        "cm_amplitude": float(_clean(cm.amplitude, length_scale)),
        "friction_amplitude": friction_amplitude,
        "normal_force_range": np.stack(
            [normal.centre - normal.amplitude, normal.centre + normal.amplitude], axis=-1
        ),
        "required_mu": required,
        "stationary_amplitude": None,
    }
    if weights is not None:
        xhat = component(weights @ x_modes, float(weights @ x_eq))
        result["stationary_amplitude"] = float(_clean(xhat.amplitude, length_scale))
    return result


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
    eigenvalues, vectors, kinds = normal_modes(analysis.mass, analysis.stiffness)
    q_eq = analysis.equilibrium.q
    mass = np.diag(analysis.mass) if np.ndim(analysis.mass) == 2 else analysis.mass
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


def _frequency_groups(omegas: FloatArray) -> list[list[int]]:
    groups: list[list[int]] = []
    for k, omega in enumerate(omegas):
        if groups and abs(omega - omegas[groups[-1][0]]) <= _SAME_FREQUENCY * omega:
            groups[-1].append(k)
        else:
            groups.append([k])
    return groups


def _required_mu(arrays: SystemArrays, friction: _Component, normal: _Component) -> FloatArray:
    r"""max over the motion of :math:`|f_i|/N_i` per body (inf if :math:`N_i` can reach 0).

    With one frequency the extreme is found over the phase :math:`\theta\in[0, 2\pi)` (dense
    sampling, then a bounded refinement); with several, over the torus of independent phases
    (the supremum approached by incommensurate motion).
    """
    n = arrays.n_bodies
    out = np.zeros(n)
    n_groups = friction.amplitudes.shape[0]
    rng = np.random.default_rng(12345)
    for i in range(n):
        if arrays.rolls[i] == 0:
            out[i] = 0.0
            continue
        f_c, n_c = float(friction.centre[i]), float(normal.centre[i])
        a_f = friction.amplitudes[:, i] if n_groups else np.zeros(0, complex)
        a_n = normal.amplitudes[:, i] if n_groups else np.zeros(0, complex)
        if n_c - np.sum(np.abs(a_n)) <= 0:
            out[i] = math.inf
            continue

        def ratio(theta: FloatArray) -> FloatArray:
            phase = np.exp(1j * np.atleast_2d(theta))
            # called only within this iteration: the loop's current values are the ones meant
            f = f_c + np.real(phase @ a_f)  # noqa: B023
            normal_force = n_c + np.real(phase @ a_n)  # noqa: B023
            result: FloatArray = np.abs(f) / normal_force
            return result

        if n_groups == 0:
            out[i] = abs(f_c) / n_c
            continue
        if n_groups == 1:
            grid = np.linspace(0.0, 2 * math.pi, 4097)[:, None]
        else:
            grid = rng.uniform(0.0, 2 * math.pi, size=(20000, n_groups))
        values = ratio(grid)
        best = int(np.argmax(values))
        import scipy.optimize  # loaded on demand (~0.1 s), not by every analysis

        res = scipy.optimize.minimize(
            lambda th: -float(ratio(th[None, :])[0]),
            grid[best],
            method="Nelder-Mead",
            options={"xatol": 1e-12, "fatol": 1e-15, "maxiter": 2000},
        )
        out[i] = max(float(values[best]), -float(res.fun))
    return out


def _tilt_deg(vector: FloatArray) -> FloatArray:
    """Angle of each spring line above the horizontal, from its first end to its second, in
    (-90, 90] degrees."""
    angle = np.degrees(np.arctan2(vector[..., 1], vector[..., 0]))
    angle = np.where(angle > 90.0, angle - 180.0, angle)
    angle = np.where(angle <= -90.0, angle + 180.0, angle)
    return np.where(np.abs(angle) < 1e-10, 0.0, angle)


def _spring_split(arrays: SystemArrays, lever: FloatArray) -> dict[str, Any] | None:
    r"""For two bodies joined by one spring: the paper's k1, k2 about the stationary point.

    :math:`\Omega_i^2 = k b_i^2/J_i` (body i alone, the other clamped, paper's Appendix B),
    :math:`\Omega^2 = \Omega_1^2 + \Omega_2^2`; body i's share of the deformation is
    :math:`\sigma_i = \Omega_i^2/\Omega^2` and :math:`k_i = k/\sigma_i`
    (paper eqs. (k1), (k2); :math:`1/k = 1/k_1 + 1/k_2`, eq. (part)). docs/physics.md section 7.1.
    """
    if arrays.n_bodies != 2 or arrays.n_springs != 1 or np.any(arrays.end_body < 0):
        return None
    k = float(arrays.stiffness[0])
    clamped = k * lever[0] ** 2 / arrays.inertia
    total = float(np.sum(clamped))
    if total <= 0 or np.any(clamped <= 0):
        return None
    share = clamped / total
    return {
        "clamped_omega": np.sqrt(clamped),
        "share": share,
        "k": k / share,
        "omega": math.sqrt(total),
    }

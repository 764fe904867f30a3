r"""The exact motion a fit compares with the data: the model's centre positions at given times.

**Level centre-joined springs** (:func:`rollspring.physics.mechanics.springs_stay_level`: every
spring joins body centres or anchors at one height, every external force acts at a centre, the
paper's Fig. 2 systems) are *exactly* linear while the bodies roll: the lever arms are constant,
so :math:`Q = Q_0 - K q - C\dot q` with constant :math:`K`, :math:`C` (docs/physics.md
section 8). In the centre positions :math:`x = x_{\rm placed} + s\,q` (:math:`s_i = R_i` rolling,
1 for a slider) the equations of motion are

.. math:: M_x\ddot x + C_x\dot x + K_x x = F,\qquad M_x = \mathrm{diag}(J_i/s_i^2),\;
          K_x = \frac{K_{ij}}{s_is_j},\; C_x = \frac{C_{ij}}{s_is_j},\;
          F = \frac{Q_{0}}{s} + K_x x_{\rm placed}

(:math:`J_i/R_i^2 = (1+\gamma_i)m_i`, the paper's :math:`I'/R^2`). With the state
:math:`z = (x, \dot x, 1)` this is :math:`\dot z = B z`, whose exact solution is
:math:`z(\tau) = e^{B\tau} z(0)` (:func:`motion_matrix`, :func:`transition_matrices`): spring
damping included, zero modes (a free pair's uniform drift, a defective eigenvalue) included, no
integration error — a matrix exponential per sampling step, then products. A fit of 600 frames
costs a few hundred microseconds per evaluation.

**Any other system** (attachments off the centres, tilted springs, a rolling resistance) is
integrated by :func:`rollspring.simulate` at ``rtol = 1e-9`` (with
``on_slip="continue"``: a slipping body continues with kinetic friction), its outputs at the
data's times. The same :func:`motion_matrix` then gives the linearisation about the placement,
used only for the fit's first guess.
"""

from __future__ import annotations

import numpy as np

from rollspring.model import System
from rollspring.physics import SystemArrays
from rollspring.physics.arrays import FloatArray
from rollspring.physics.mechanics import damping_matrix, generalized_forces, stiffness_matrix

__all__ = [
    "SIMULATION_RTOL",
    "expm",
    "motion_matrix",
    "simulated_states",
    "transition_matrices",
    "uniform_steps",
]

#: The accuracy of the simulated motion a fit compares with the data (non-level systems).
SIMULATION_RTOL = 1e-9


def motion_matrix(arrays: SystemArrays) -> FloatArray:
    r"""The (2n+1, 2n+1) matrix :math:`B` of :math:`\dot z = Bz`, :math:`z = (x,\dot x,1)`:

    .. math:: B = \begin{pmatrix}0 & I & 0\\ -M_x^{-1}K_x & -M_x^{-1}C_x & M_x^{-1}F\\
              0&0&0\end{pmatrix}

    with :math:`M_x, K_x, C_x, F` of the module's docstring, from the physics at the placement
    (:func:`~rollspring.physics.mechanics.stiffness_matrix`,
    :func:`~rollspring.physics.mechanics.damping_matrix`,
    :func:`~rollspring.physics.mechanics.generalized_forces`, docs/physics.md (M7), (M12)).
    Exact for level centre-joined springs; the linearisation about the placement otherwise.
    """
    n = arrays.n_bodies
    q = np.zeros(n)
    s = arrays.scale
    pair = np.outer(s, s)
    k_x = np.asarray(stiffness_matrix(arrays, q)) / pair
    c_x = np.asarray(damping_matrix(arrays, q)) / pair
    force = np.asarray(generalized_forces(arrays, q)) / s + k_x @ arrays.x0
    inverse_mass = (s * s / arrays.inertia)[:, None]
    b = np.zeros((2 * n + 1, 2 * n + 1))
    b[:n, n : 2 * n] = np.eye(n)
    b[n : 2 * n, :n] = -inverse_mass * k_x
    b[n : 2 * n, n : 2 * n] = -inverse_mass * c_x
    b[n : 2 * n, 2 * n] = inverse_mass[:, 0] * force
    return b


def uniform_steps(tau: FloatArray) -> tuple[float, np.ndarray] | None:
    """``(h, j)`` when the times are ``tau[0] + j h`` for whole numbers ``j`` (a video's frames,
    some perhaps missing), to 1e-9 of a step; None otherwise (or when the gaps are so long that
    the whole grid would be more than four times the times)."""
    if tau.size < 2:
        return None
    step = np.diff(tau)
    h = float(np.min(step))
    if not h > 0:
        return None
    j = np.rint((tau - tau[0]) / h).astype(np.int64)
    if j[-1] > 4 * tau.size + 16:
        return None
    if np.max(np.abs(tau[0] + j * h - tau)) > 1e-9 * h + 1e-12 * abs(tau[-1]):
        return None
    return h, j


def transition_matrices(b: FloatArray, tau: FloatArray) -> FloatArray:
    r""":math:`\Phi(\tau_j) = e^{B\tau_j}` for every time ``tau`` (N,), exact to rounding.

    On a uniform grid :math:`\tau_j = \tau_0 + j h` (:func:`uniform_steps`):
    :math:`\Phi_j = (e^{Bh})^{j} e^{B\tau_0}`, the powers by doubling (log2 N products of
    matrices), two matrix exponentials in all (:func:`scipy.linalg.expm`); otherwise one
    exponential per time. ``b`` (..., m, m) (a leading batch of systems is kept) -> (..., N, m, m).
    """
    b = np.asarray(b, dtype=np.float64)
    tau = np.asarray(tau, dtype=np.float64)
    grid = uniform_steps(tau)
    if grid is None:
        result: FloatArray = expm(tau[:, None, None] * b[..., None, :, :])
        return result
    h, j = grid
    step = expm(h * b)
    count = int(j[-1]) + 1
    m = b.shape[-1]
    powers = np.broadcast_to(np.eye(m), (*b.shape[:-2], 1, m, m))
    power = step
    while powers.shape[-3] < count:
        powers = np.concatenate([powers, powers @ power[..., None, :, :]], axis=-3)
        power = power @ power
    if tau[0] == 0.0:  # e^{0} = I
        return np.ascontiguousarray(powers[..., j, :, :])
    first = expm(tau[0] * b)
    result = powers[..., j, :, :] @ first[..., None, :, :]
    return result


def expm(a: FloatArray) -> FloatArray:
    r"""The matrix exponential :math:`e^{A}` of each of the small matrices ``a`` (..., m, m):
    scaling and squaring of the Taylor series,

    .. math:: e^{A} = \bigl(T_{18}(A/2^s)\bigr)^{2^s},\qquad
              \|A/2^s\|_\infty \le \tfrac12,

    whose truncation error is below :math:`2^{-19}/19! \approx 10^{-23}` of the norm, far under
    rounding. Written here because :func:`scipy.linalg.expm` takes milliseconds on the matrices
    of :func:`motion_matrix` (its exactly zero last row sends it down a slow path, measured
    7 ms for a 5x5 with SciPy 1.17) where this takes microseconds, and it runs over a batch at
    once."""
    a = np.asarray(a, dtype=np.float64)
    norm = float(np.max(np.sum(np.abs(a), axis=-1), initial=0.0))
    squarings = max(0, int(np.ceil(np.log2(norm / 0.5)))) if norm > 0.5 else 0
    scaled = a / 2.0**squarings
    eye = np.broadcast_to(np.eye(a.shape[-1]), a.shape)
    result = eye
    for order in range(18, 0, -1):  # Horner: I + A/1 (I + A/2 (I + ... (I + A/18)))
        result = eye + (scaled @ result) / order
    for _ in range(squarings):
        result = result @ result
    exponential: FloatArray = np.ascontiguousarray(result)
    return exponential


def simulated_states(
    system: System, tau: FloatArray, *, rtol: float = SIMULATION_RTOL
) -> tuple[FloatArray, FloatArray]:
    r"""Centre positions and velocities (N, n) of :func:`rollspring.simulate` at the times
    ``tau`` >= 0 (sorted) after the system's placement: on a uniform grid from 0 the outputs are
    those times; otherwise the outputs are four per step of the data and the states between them
    cubic Hermite interpolants of :math:`x` and :math:`\dot x` (error :math:`O(h^4)`, below
    ``rtol`` at that density)."""
    from rollspring.simulate import simulate

    tau = np.asarray(tau, dtype=np.float64)
    end = float(tau[-1])
    if end <= 0:
        arrays_x = np.array([b.x for b in system.bodies])
        arrays_v = np.array([b.v for b in system.bodies])
        return np.tile(arrays_x, (tau.size, 1)), np.tile(arrays_v, (tau.size, 1))
    grid = uniform_steps(tau)
    exact = grid is not None and abs(tau[0]) <= 1e-12 * max(end, 1.0)
    if grid is not None and exact:
        h, j = grid
        count = int(j[-1]) + 1
    else:
        h = float(np.min(np.diff(tau))) / 4 if tau.size > 1 else end / 16
        count = int(np.ceil(end / h)) + 1
    run = simulate(system, end, rtol=rtol, n_output=count, on_slip="continue", confirm=True)
    t, x, v = run.t, run.x, run.v
    if t[-1] < end * (1 - 1e-12):
        raise ArithmeticError(f"the simulation ended at {t[-1]:g} s: {run.message}")
    if grid is not None and exact:
        return x[j], v[j]
    return _hermite(t, x, v, tau)


def _hermite(
    t: FloatArray, x: FloatArray, v: FloatArray, tau: FloatArray
) -> tuple[FloatArray, FloatArray]:
    """Cubic Hermite interpolation of positions and velocities at ``tau`` (inside ``t``)."""
    from scipy.interpolate import CubicHermiteSpline

    spline = CubicHermiteSpline(t, x, v, axis=0)
    return spline(tau), spline(tau, 1)

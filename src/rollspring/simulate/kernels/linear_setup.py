"""The compiled linear setup of small level systems (``rollspring.simulate.setup``'s
``_small_level_equilibrium``): equilibrium, stiffness and normal modes in one call, the same
operations on the same numbers as :mod:`rollspring.analysis.linear`'s level branch.
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

from rollspring.analysis import linear as _linear
from rollspring.simulate.kernels import model as col
from rollspring.simulate.kernels.forces import generalized_forces

__all__ = ["GENERAL", "KIND_NAMES", "LEVEL", "MOST_BODIES", "level_setup"]

#: :func:`level_setup`'s verdicts: done, or the general search decides
LEVEL, GENERAL = 0, 1
#: the kinds of modes, by their codes in :func:`level_setup`'s result
KIND_NAMES = ("oscillating", "zero", "unstable")
_OSCILLATING, _ZERO, _UNSTABLE = range(3)
#: the most bodies :func:`level_setup` takes (LAPACK's two-coordinate path, bit for bit)
MOST_BODIES = 2
#: the most springs, and numbers of the forces' (F, 2) array, :func:`level_setup` sums for the
#: force scale: NumPy sums fewer than 8 numbers in order (as here), more pairwise
_IN_ORDER = 7

_laev2 = njit(cache=True)(_linear._laev2)  # LAPACK's dlaev2, compiled from the same source


@njit(cache=True, error_model="numpy")
def _residual(model, q):
    r""":math:`\sqrt{Q(q)^T M^{-1} Q(q)}` and :math:`Q(q)`."""
    force = generalized_forces(model, q)
    total = 0.0
    for i in range(q.shape[0]):
        total += force[i] * force[i] * model[0][i, col.INV_INERTIA]
    return math.sqrt(total), force


@njit(cache=True, error_model="numpy")
def _modes(inertia, k, zero_tolerance, eps):
    r""":math:`K v = \lambda M v` of one or two coordinates as ``linear._small_eigh``
    (eigenvalues ascending, M-orthonormal columns) and :func:`~rollspring.analysis.
    normal_modes`' kinds (``zero_tolerance``: :data:`~rollspring.analysis.ZERO_MODE_TOLERANCE`;
    ``eps``: LAPACK's machine precision); ok False where that would not stand in for LAPACK."""
    n = inertia.shape[0]
    values = np.zeros(n)
    vectors = np.zeros((n, n))
    kinds = np.zeros(n, dtype=np.int64)
    factor0 = math.sqrt(inertia[0])
    inverse0 = 1.0 / factor0
    if n == 1:
        values[0] = k[0, 0] / (factor0 * factor0)
        vectors[0, 0] = inverse0
        if not math.isfinite(values[0]):
            return False, values, vectors, kinds
    else:
        factor1 = math.sqrt(inertia[1])
        inverse1 = 1.0 / factor1
        for a in range(2):
            for b in range(2):
                if not math.isfinite(k[a, b]):
                    return False, values, vectors, kinds
        d1 = k[0, 0] / (factor0 * factor0)
        e = k[1, 0] * inverse0 / factor1
        d2 = k[1, 1] / (factor1 * factor1)
        norm = max(abs(d1), abs(e), abs(d2))
        if not math.isfinite(norm) or (norm != 0.0 and not 1e-140 < norm < 1e140):
            return False, values, vectors, kinds
        if e == 0.0 or abs(e) <= (math.sqrt(abs(d1)) * math.sqrt(abs(d2))) * eps:
            w0, w1, c, s = d1, d2, 1.0, 0.0
        else:
            w0, w1, c, s = _laev2(d1, e, d2)
        z00, z01, z10, z11 = c, -s, s, c  # steqr's rotation of the identity
        if w1 < w0:  # steqr's closing selection sort
            w0, w1, z00, z01, z10, z11 = w1, w0, z01, z00, z11, z10
        values[0], values[1] = w0, w1
        vectors[0, 0], vectors[0, 1] = z00 * inverse0, z01 * inverse0
        vectors[1, 0], vectors[1, 1] = z10 * inverse1, z11 * inverse1
    largest = 0.0
    for m in range(n):
        largest = max(largest, abs(values[m]))
    for m in range(n):
        if largest == 0.0 or abs(values[m]) < zero_tolerance * largest:
            kinds[m] = _ZERO
            values[m] = 0.0
        elif values[m] < 0:
            kinds[m] = _UNSTABLE
        else:
            kinds[m] = _OSCILLATING
    if n == 2 and values[1] < values[0]:  # normal_modes' stable argsort
        values[0], values[1] = values[1], values[0]
        kinds[0], kinds[1] = kinds[1], kinds[0]
        for a in range(2):
            vectors[a, 0], vectors[a, 1] = vectors[a, 1], vectors[a, 0]
    return True, values, vectors, kinds


@njit(cache=True, error_model="numpy")
def level_setup(model, tolerance, zero_tolerance, eps):
    r"""The equilibrium and normal modes of a system of level centre springs of at most
    :data:`MOST_BODIES` bodies, given as its kernel model (:func:`~rollspring.simulate.kernels.
    kernel_model`) with every spring's ends level and apart: ``(verdict, q*, residual, K,
    eigenvalues, vectors, kinds)``, the numbers of :func:`~rollspring.analysis.find_equilibrium`
    with ``tolerance`` (kinds coded by :data:`KIND_NAMES`), or :data:`GENERAL` first where its
    general search decides. ``zero_tolerance`` and ``eps`` are :func:`~rollspring.analysis.
    normal_modes`' zero-mode threshold and LAPACK's machine precision, given rather than read
    from :mod:`rollspring.analysis.linear` (Numba's cache would keep another module's constants
    after they change).

    One or two bodies whose springs stay level (:func:`~rollspring.physics.springs_stay_level`:
    K constant, Q affine in q) take a few dozen floating-point operations, and the Python
    around them (the level branch of ``find_equilibrium`` and ``normal_modes``) was a seventh
    of the paper's simulation (0.1 ms of 0.72). Here they are one call, the same operations on
    the same numbers, so the same bits:

    1. :math:`Q_0 = Q(0)` (M7) and the residual :math:`\sqrt{Q_0^T M^{-1} Q_0}`; the tolerance is
       ``tolerance`` of the larger of that and the force scale (``linear._force_scale``);
    2. :math:`K = \sum_s k_s b_s b_s^T` (M12) with the constant lever arms
       :math:`b_{si} = e_s\sigma_{si}s_i` (``linear._level_stiffness``);
    3. :math:`K v = \lambda M v` by LAPACK's reduction and ``steqr`` on two coordinates
       (``linear._small_eigh``; ``linear._laev2`` compiled from its source), the kinds as
       ``normal_modes`` gives them;
    4. the equilibrium, one Newton step from the placement along the non-zero modes,
       :math:`q^* = \sum_{\lambda_n\ne0} v_n (v_n^T Q_0)/\lambda_n`, checked (residual within
       the tolerance, zero-mode coordinates :math:`V_0^T M q^*` at rounding)
       (``linear._level_equilibrium``).

    Whatever that branch hands to the general search (an unstable K, a force along a zero
    mode, a residual above the tolerance, numbers LAPACK would rescale), more than
    :data:`MOST_BODIES` bodies, and more springs or forces than NumPy sums in order for the
    force scale, come back as :data:`GENERAL`; the caller then runs ``find_equilibrium``,
    which decides as before. Tests check the two against each other bit for bit."""
    bodies, springs, ends = model[0], model[1], model[2]
    n = bodies.shape[0]
    q = np.zeros(n)
    stiffness = np.zeros((n, n))
    few = springs.shape[0] <= _IN_ORDER and 2 * model[3].shape[0] <= _IN_ORDER
    if n > MOST_BODIES or n == 0 or not few:
        return GENERAL, q, 0.0, stiffness, np.zeros(n), np.zeros((n, n)), np.zeros(n, np.int64)
    inertia = bodies[:, col.INERTIA].copy()
    for i in range(n):
        if not (inertia[i] > 0.0 and inertia[i] < math.inf):
            return GENERAL, q, 0.0, stiffness, np.zeros(n), np.zeros((n, n)), np.zeros(n, np.int64)
    initial, force_0 = _residual(model, q)
    # linear._force_scale: the springs' and forces' typical generalised force
    biggest = bodies[0, col.SCALE]
    smallest_inertia = inertia[0]
    for i in range(1, n):
        biggest = max(biggest, bodies[i, col.SCALE])
        smallest_inertia = min(smallest_inertia, inertia[i])
    spring_scale = 0.0
    n_springs = springs.shape[0]
    dx = np.empty(n_springs)
    lengths = np.empty(n_springs)
    for s in range(n_springs):
        a, b = ends[s, 0], ends[s, 1]
        xa = bodies[a, col.X0] if a >= 0 else springs[s, col.AAX]
        ya = bodies[a, col.CY] if a >= 0 else springs[s, col.AAY]
        xb = bodies[b, col.X0] if b >= 0 else springs[s, col.ABX]
        yb = bodies[b, col.CY] if b >= 0 else springs[s, col.ABY]
        dx[s] = xb - xa
        if dx[s] == 0.0:  # ends one above the other: not linear._level_centre_springs
            return GENERAL, q, 0.0, stiffness, np.zeros(n), np.zeros((n, n)), np.zeros(n, np.int64)
        lengths[s] = math.sqrt(dx[s] ** 2 + (yb - ya) ** 2)
        spring_scale += springs[s, col.STIFF] * lengths[s] * biggest
    forces = model[3]
    applied = 0.0
    for f in range(forces.shape[0]):
        applied += abs(forces[f, col.FX])
        applied += abs(forces[f, col.FY])
    applied *= biggest  # forces at centres: force_r is 0
    scale = max(initial, max(spring_scale, applied, 1e-300) / math.sqrt(smallest_inertia))
    target = tolerance * scale
    # linear._level_stiffness: K = sum_s k_s b_s b_s^T, summed in its order
    for s in range(n_springs):
        direction = dx[s] / lengths[s]
        k = springs[s, col.STIFF]
        for j in range(2):
            i = ends[s, j]
            if i < 0:
                continue
            b_i = direction * ((-1.0 if j == 0 else 1.0) * bodies[i, col.SCALE])
            for other in range(2):
                m = ends[s, other]
                if m < 0:
                    continue
                b_m = direction * ((-1.0 if other == 0 else 1.0) * bodies[m, col.SCALE])
                stiffness[i, m] += k * (b_i * b_m)
    ok, values, vectors, kinds = _modes(inertia, stiffness, zero_tolerance, eps)
    has_zero = has_oscillating = False
    for m in range(n):
        if kinds[m] == _UNSTABLE:
            ok = False
        has_zero = has_zero or kinds[m] == _ZERO
        has_oscillating = has_oscillating or kinds[m] == _OSCILLATING
    if not ok:
        return GENERAL, q, 0.0, stiffness, values, vectors, kinds
    residual = initial
    if initial > target:
        if has_zero and not has_oscillating:
            return GENERAL, q, 0.0, stiffness, values, vectors, kinds
        # linear._level_equilibrium: the Newton step along the non-zero modes
        for m in range(n):
            if kinds[m] == _ZERO:
                continue
            along = 0.0
            for i in range(n):
                along += vectors[i, m] * force_0[i]
            weight = along / values[m]
            for i in range(n):
                q[i] += vectors[i, m] * weight
        residual, _ = _residual(model, q)
        if not residual <= target:
            return GENERAL, q, 0.0, stiffness, values, vectors, kinds
        if has_zero:  # held: V0^T M q at rounding
            held = size = weight_scale = 0.0
            for i in range(n):
                size = max(size, abs(q[i]))
            size = max(1.0, size)
            for m in range(n):
                if kinds[m] != _ZERO:
                    continue
                along = 0.0
                for i in range(n):
                    along += vectors[i, m] * (inertia[i] * q[i])
                    weight_scale = max(weight_scale, abs(vectors[i, m] * inertia[i]))
                held = max(held, abs(along))
            if held > 1e-13 * size * weight_scale:
                return GENERAL, q, 0.0, stiffness, values, vectors, kinds
    return LEVEL, q, residual, stiffness, values, vectors, kinds

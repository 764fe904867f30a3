r"""The linear model of a large system without dense matrices: every spring touches at most two
bodies, so with the bodies numbered along the springs (a chain) the stiffness matrix is banded.

* :func:`banded_stiffness` puts the mass-scaled stiffness
  :math:`A = M^{-1/2} K M^{-1/2}` (docs/physics.md (M12)) into LAPACK's lower band storage;
* :func:`banded_modes` solves :math:`K v = \lambda M v` from it: a tridiagonal :math:`A`
  (springs between neighbours only: every chain) by LAPACK's ``stevd`` for the eigenvalues
  (the lattice's frequencies to a few :math:`10^{-11}`, relative, at 2000 bodies) and ``stemr``
  (MRRR, O(n) per vector) for the vectors; wider bands by ``sbevd`` (SciPy's ``eig_banded``);
  ``select=(lo, hi)`` computes only the modes lo..hi (0-based, ascending) by bisection to the
  underflow threshold and inverse iteration (``stebz``/``stein``, O(n) per mode), without
  forming any n x n array;
* :func:`sparse_equilibrium` is the equilibrium search of :func:`~rollspring.analysis.linear.
  find_equilibrium` for systems beyond :data:`DENSE_LIMIT` bodies: Newton with a sparse LU
  factorisation of :math:`K` (O(n) for a band).

Zero modes (a chain without walls can roll as a whole when its springs join level centres)
are told by the same rule as :func:`~rollspring.analysis.linear.normal_modes`.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from rollspring.physics import SystemArrays, generalized_forces, stiffness_matrix
from rollspring.physics.arrays import FloatArray

__all__ = [
    "ALL_MODES_LIMIT",
    "DENSE_LIMIT",
    "banded_modes",
    "banded_stiffness",
    "mode_kinds",
    "sparse_equilibrium",
]

#: Up to this many bodies the analysis uses dense matrices (the reference path); beyond it the
#: banded and sparse path of this module.
DENSE_LIMIT = 64
#: Up to this many bodies :func:`rollspring.analyze` computes every mode (and the exact linear
#: response, which needs them all); beyond it the lowest modes (``modes=``).
ALL_MODES_LIMIT = 2000
#: LAPACK ``stebz``'s absolute tolerance: twice the underflow threshold, its most accurate
_BISECTION = 2.0 * float(np.finfo(float).tiny)
#: eigenvalues below this fraction of the largest are refined by bisection (every-mode path)
_REFINE = 1e-3
#: An eigenvalue with |lambda| < this * max|lambda| is a zero mode (as in ``normal_modes``).
_ZERO = 1e-10


def banded_stiffness(arrays: SystemArrays, stiffness: Any) -> tuple[FloatArray, int]:
    r"""The lower band of :math:`A = M^{-1/2} K M^{-1/2}` (``stiffness`` a SciPy sparse K):
    ``band[d, i] = A[i + d, i]`` for d = 0..bandwidth (LAPACK's lower storage), and the
    bandwidth (the largest :math:`|i - j|` with :math:`K_{ij} \ne 0`)."""
    coo = stiffness.tocoo()
    root = np.sqrt(arrays.inertia)
    lower = coo.row >= coo.col
    rows, cols = coo.row[lower], coo.col[lower]
    values = coo.data[lower] / root[rows] / root[cols]
    width = int((rows - cols).max(initial=0))
    band = np.zeros((width + 1, arrays.n_bodies))
    np.add.at(band, (rows - cols, cols), values)
    return band, width


def mode_kinds(eigenvalues: FloatArray, largest: float) -> np.ndarray:
    """ "zero", "unstable" or "oscillating" for each eigenvalue (zero modes set to exactly 0 in
    ``eigenvalues``), relative to the largest |eigenvalue| of the whole problem."""
    kinds = np.full(eigenvalues.size, "oscillating", dtype=object)
    zero = (np.abs(eigenvalues) < _ZERO * largest) | (largest == 0.0)
    kinds[eigenvalues < 0] = "unstable"
    kinds[zero] = "zero"
    eigenvalues[zero] = 0.0
    return kinds


def banded_modes(
    arrays: SystemArrays,
    stiffness: Any,
    *,
    select: tuple[int, int] | None = None,
    vectors: bool = True,
) -> tuple[FloatArray, FloatArray | None, np.ndarray, float]:
    r"""Normal modes :math:`K v = \lambda M v` of a sparse ``stiffness`` (the module's
    methods): eigenvalues ascending, M-orthonormal vectors (columns; None without
    ``vectors``), kinds, and the largest |eigenvalue| of the whole problem (the scale of the
    zero-mode rule). ``select=(lo, hi)``: only modes lo..hi (0-based, inclusive)."""
    import scipy.linalg

    band, width = banded_stiffness(arrays, stiffness)
    n = arrays.n_bodies
    inverse_root = 1.0 / np.sqrt(arrays.inertia)
    if width <= 1:
        diagonal = band[0]
        off = band[1, :-1] if width == 1 else np.zeros(n - 1)
        ends = (
            scipy.linalg.eigh_tridiagonal(
                diagonal, off, eigvals_only=True, select="i", select_range=(0, 0)
            ),
            scipy.linalg.eigh_tridiagonal(
                diagonal, off, eigvals_only=True, select="i", select_range=(n - 1, n - 1)
            ),
        )
        largest = float(max(abs(ends[0][0]), abs(ends[1][0])))
        if select is None:
            values = scipy.linalg.eigh_tridiagonal(diagonal, off, eigvals_only=True)
            # stevd is accurate to about eps |A|: the eigenvalues far below the largest again
            # by bisection to the underflow threshold, to their own relative accuracy
            small = np.flatnonzero(np.abs(values) < _REFINE * largest)
            if small.size:
                values[small[0] : small[-1] + 1] = scipy.linalg.eigh_tridiagonal(
                    diagonal,
                    off,
                    eigvals_only=True,
                    select="i",
                    select_range=(int(small[0]), int(small[-1])),
                    tol=_BISECTION,
                )
            standard = None
            if vectors:
                _, standard = scipy.linalg.eigh_tridiagonal(diagonal, off, lapack_driver="stemr")
        else:
            lo, hi = select
            # bisection to the underflow threshold: small eigenvalues to high relative
            # accuracy (a few 1e-11 of the lowest of 5000 bodies; eps |A| by default)
            if vectors:
                values, standard = scipy.linalg.eigh_tridiagonal(
                    diagonal, off, select="i", select_range=(lo, hi), tol=_BISECTION
                )
            else:
                values = scipy.linalg.eigh_tridiagonal(
                    diagonal,
                    off,
                    eigvals_only=True,
                    select="i",
                    select_range=(lo, hi),
                    tol=_BISECTION,
                )
                standard = None
    else:
        if select is None:
            if vectors:
                values, standard = scipy.linalg.eig_banded(band, lower=True)
            else:
                values = scipy.linalg.eig_banded(band, lower=True, eigvals_only=True)
                standard = None
            largest = float(np.abs(values).max(initial=0.0))
        else:
            lo, hi = select
            low = scipy.linalg.eig_banded(
                band, lower=True, eigvals_only=True, select="i", select_range=(0, 0)
            )
            high = scipy.linalg.eig_banded(
                band, lower=True, eigvals_only=True, select="i", select_range=(n - 1, n - 1)
            )
            largest = float(max(abs(low[0]), abs(high[0])))
            result = scipy.linalg.eig_banded(
                band, lower=True, eigvals_only=not vectors, select="i", select_range=(lo, hi)
            )
            values, standard = result if vectors else (result, None)
    values = np.asarray(values, dtype=float).copy()
    kinds = mode_kinds(values, largest)
    modes = None if standard is None else standard * inverse_root[:, None]
    return values, modes, kinds, largest


def sparse_equilibrium(
    arrays: SystemArrays, target: float, *, max_iterations: int = 50
) -> tuple[FloatArray, float, bool]:
    r"""Newton's method on :math:`Q(q) = 0` with sparse LU factorisations of :math:`K(q)`
    (SciPy's ``splu``; O(n) for a banded K): :math:`\delta q = K^{-1} Q`, each step at most
    0.5 rad (halved until the residual :math:`Q^T M^{-1} Q` falls), from the initial
    placement until the residual is at most ``target``. Returns (q, residual, converged).

    Where K is singular — zero modes :math:`V_0` (a chain without walls rolling as a whole,
    found by :func:`banded_modes` among the lowest modes) — the step solves the bordered system

    .. math:: \begin{pmatrix} K & M V_0 \\ V_0^{\mathsf T} M & 0 \end{pmatrix}
              \begin{pmatrix} \delta q \\ -\mu \end{pmatrix} =
              \begin{pmatrix} Q \\ -V_0^{\mathsf T} M q \end{pmatrix}

    (sparse too: the border is a few dense columns), which holds the zero-mode coordinates
    :math:`V_0^{\mathsf T} M q` at the placement's, 0: the point of the valley of equilibria
    the released motion oscillates about (docs/physics.md (M14); the dense search's
    ``_hold_zero_modes``). Not converged where the steps stall: the caller then tells why."""
    import scipy.sparse
    import scipy.sparse.linalg

    inv_mass = 1.0 / arrays.inertia

    def residual_of(state: FloatArray) -> tuple[FloatArray, float]:
        force = generalized_forces(arrays, state)
        return force, math.sqrt(float((force**2 * inv_mass).sum()))

    q = np.zeros(arrays.n_bodies)
    force, residual = residual_of(q)
    for _ in range(max_iterations):
        if residual <= target:
            return q, residual, True
        k_matrix = stiffness_matrix(arrays, q, sparse=True)
        step = _newton_step(arrays, k_matrix, force, q, scipy.sparse, scipy.sparse.linalg)
        if step is None:
            return q, residual, False
        biggest = float(np.abs(step).max(initial=0.0))
        if biggest > 0.5:
            step *= 0.5 / biggest
        for _ in range(30):
            trial = q + step
            trial_force, trial_residual = residual_of(trial)
            if trial_residual < residual:
                break
            step *= 0.5
        else:
            return q, residual, False
        q, force, residual = trial, trial_force, trial_residual
    return q, residual, residual <= target


def _newton_step(
    arrays: SystemArrays, k_matrix: Any, force: FloatArray, q: FloatArray, sparse: Any, linalg: Any
) -> FloatArray | None:
    """:math:`K^{-1}Q`, or the bordered step of :func:`sparse_equilibrium` when K is singular
    (None when neither can be taken)."""
    try:
        step: FloatArray = linalg.splu(k_matrix.tocsc()).solve(force)
        if np.isfinite(step).all():
            return step
    except RuntimeError:  # exactly singular
        pass
    lowest = min(arrays.n_bodies, 8)
    _, vectors, kinds, _ = banded_modes(arrays, k_matrix, select=(0, lowest - 1))
    zero = kinds == "zero"
    if vectors is None or not zero.any():
        return None
    border = arrays.inertia[:, None] * vectors[:, zero]  # M V0
    bordered = sparse.bmat(
        [[k_matrix, sparse.csr_array(border)], [sparse.csr_array(border.T), None]],
        format="csc",
    )
    right = np.concatenate([force, -(border.T @ q)])
    try:
        solution = linalg.splu(bordered).solve(right)
    except RuntimeError:
        return None
    step = solution[: arrays.n_bodies]
    return step if np.isfinite(step).all() else None

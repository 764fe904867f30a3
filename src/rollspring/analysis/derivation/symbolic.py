r"""The symbolic form of a system (SymPy): the :class:`SymbolicSystem` and what it offers (made
by :func:`~rollspring.analysis.derivation.build.symbolic_system`; its parts, energies and body
forces are built in :mod:`.parts`, :mod:`.energies` and :mod:`.body_forces`).

Public API (stable; :mod:`rollspring.analysis.derivation` re-exports it)::

    sym = symbolic_system(system, symbols=False)   # a validated rollspring System
    sym.bodies[i]          # SymbolicBody: id, shape, m, R, gamma, I, J, s, percussion_height, ...
    sym.springs[s]         # SymbolicSpring: k, rest_length L, reference vector d0, length, ...
    sym.q, sym.qd, sym.qdd # plain Symbols phi_i, dot phi_i, ddot phi_i (sliders: x_i, ...)
    sym.functions          # phi_i(t) (sympy.physics.mechanics dynamicsymbols), sym.t
    sym.potential          # exact V(q) (M5): springs and constant external forces
    sym.kinetic            # T = sum J_i qd_i^2 / 2 (M4)
    sym.lagrangian         # T - V
    sym.mass_matrix        # M = diag(J_i), sympy Matrix (M12)
    sym.generalized_forces # Q_i(q) = -dV/dq_i from the exact lever arms, sympy Matrix (M7)
    sym.potential_gradient # dV/dq_i by differentiating V (the Lagrange route; same values)
    sym.stiffness_matrix   # K = d2V/dq2 at the reference q = 0, closed form (M12), (M13), Matrix
    sym.hessian()          # the same K by differentiating V twice (a check; slower)
    sym.reference_forces   # Q(0): zero at an equilibrium (symbolically: the conditions)
    sym.lever_arms         # [{body: dl_s/dq_i}] exact lever arms of every spring
    sym.quadratic_potential# V(0) + Q(0)-term + 1/2 q^T K q: the quadratic form about q = 0
    sym.equations_of_motion(linear=False)   # [Eq(J_i qdd_i, Q_i)] (M7), or linearised
    sym.body_forces        # [(F_ix, F_iy)] resultant applied force on each body, in q
    sym.friction           # f_i = m_i s_i qdd_i - F_ix (M8), in q and qdd (0 for a slider)
    sym.friction_configuration  # f_i with (M7) substituted: Q_i/((1+gamma_i) R_i) - F_ix
    sym.normal             # N_i = m_i g - F_iy (M9), in q
    sym.linear_contact_forces   # (f, N) to first order about q = 0, from K and dF/dq
    sym.body_force_jacobian     # dF_i/dq_j at q = 0, closed form
    sym.zero_mode(), sym.zero_mode_count()  # the null vector of K (if exactly one), count
    sym.contact_torques    # Q_i computed as torques about the contact points (Newton's route)
    sym.in_time(expr)      # q -> phi(t), qd -> phi'(t), qdd -> phi''(t)
    sym.values             # {Symbol: float}: the system's numbers, to check against numerics
    sym.conditions         # [Eq]: what the parameters satisfy for this system (level ends)
    sym.apply_conditions(expr)  # expr with the conditions used
    sym.numeric(expr)      # float(expr.subs(values))
    sym.reference          # "equilibrium" or "initial placement"; sym.q_reference (rad, floats)

Coordinates are measured from the **reference configuration**: the equilibrium nearest the
initial placement (:func:`rollspring.analysis.find_equilibrium`), or the initial placement when
there is none. So the paper's constraint reads :math:`x_i = R_i\varphi_i` (origin at the
reference), and for springs at rest length there :math:`V = \tfrac12\sum_s k_s(l_s-\ell_s)^2`
with :math:`\ell_s` the spring's length at the reference.

What it offers comes in layers, each in its own module: the parts (bodies, attachments,
springs, forces; :mod:`.parts`), the energies, M, Q and K (:mod:`.energies`), the forces on the
bodies (:mod:`.body_forces`), and the building from a System (:mod:`.build`).
"""

from __future__ import annotations

from dataclasses import dataclass, field
from functools import cached_property
from typing import Any

import numpy as np
import sympy as sp
from sympy.physics.mechanics import dynamicsymbols

from rollspring.analysis.derivation.body_forces import BodyForcesMixin
from rollspring.analysis.derivation.parts import SymbolicBody, SymbolicForce, SymbolicSpring
from rollspring.analysis.linear import normal_modes
from rollspring.model import System

__all__ = ["SymbolicSystem", "is_tridiagonal", "matrix_to_float"]


@dataclass(eq=False)
class SymbolicSystem(BodyForcesMixin):
    """A system in SymPy form (see the module docstring). Build it with
    :func:`~.build.symbolic_system`. Its coordinates, energies, M, Q and K come from
    :class:`~.energies.EnergiesMixin`, the forces on its bodies from
    :class:`~.body_forces.BodyForcesMixin`."""

    system: System
    symbolic: bool
    bodies: tuple[SymbolicBody, ...]
    springs: tuple[SymbolicSpring, ...]
    forces: tuple[SymbolicForce, ...]
    g: sp.Expr
    values: dict[sp.Symbol, float]
    reference: str
    q_reference: np.ndarray
    t: sp.Symbol = field(default_factory=lambda: dynamicsymbols._t)
    notes: list[str] = field(default_factory=list)
    conditions: list[sp.Eq] = field(default_factory=list)
    _cache: dict[str, Any] = field(default_factory=dict, repr=False)

    def apply_conditions(self, expr: Any) -> Any:
        """``expr`` with :attr:`conditions` used: each solved for its last parameter (in name
        order) and substituted (``2R_1 = 3R_2/2`` -> ``R_2 = 4R_1/3``)."""
        for condition in self.conditions:
            unknown = sorted(condition.free_symbols, key=lambda x: x.name)[-1]
            (value,) = sp.solve(condition, unknown)
            expr = _xreplace(
                sp.sympify(expr) if not isinstance(expr, list | tuple) else expr, {unknown: value}
            )
        return expr

    # -- coordinates in time, parameters -------------------------------------------------------
    @property
    def functions(self) -> list[sp.Expr]:
        """The coordinates as functions of time (dynamicsymbols)."""
        return [b.function for b in self.bodies]

    @cached_property
    def _to_time(self) -> dict[sp.Symbol, sp.Expr]:
        mapping: dict[sp.Symbol, sp.Expr] = {}
        for b in self.bodies:
            mapping[b.q] = b.function
            mapping[b.qd] = b.function.diff(self.t)
            mapping[b.qdd] = b.function.diff(self.t, 2)
        return mapping

    def in_time(self, expr: Any) -> Any:
        """Replace q, qd, qdd by phi(t), phi'(t), phi''(t) (for display and mechanics)."""
        return _xreplace(expr, self._to_time)

    @property
    def parameters(self) -> list[sp.Symbol]:
        """Every free parameter symbol (empty when ``symbolic`` is False)."""
        return sorted(self.values, key=lambda s: s.name)

    def numeric(self, expr: sp.Expr) -> float:
        """The number of a parameter expression (no coordinates) for this system's values."""
        return float(sp.sympify(expr).xreplace(self.values).evalf(17))

    # -- zero modes ----------------------------------------------------------------------------
    def zero_mode(self) -> sp.Matrix | None:
        """A null vector of K if there is exactly one (numerically), else None (cached)."""
        if "zero_mode" not in self._cache:
            self._cache["zero_mode"] = _zero_mode(self)
        return self._cache["zero_mode"]

    def zero_mode_count(self) -> int:
        """Number of zero modes of (M, K), from the numbers (as rollspring.analyze counts them)."""
        if "n_zero" not in self._cache:
            mass = np.array(sp.matrix2numpy(self.mass_matrix.xreplace(self.values)), dtype=float)
            stiff = np.array(
                sp.matrix2numpy(self.stiffness_matrix.xreplace(self.values)), dtype=float
            )
            _, _, kinds = normal_modes(mass, stiff)
            self._cache["n_zero"] = int(np.sum(kinds == "zero"))
            self._cache["n_unstable"] = int(np.sum(kinds == "unstable"))
        result: int = self._cache["n_zero"]
        return result


def _xreplace(expr: Any, mapping: dict[Any, Any]) -> Any:
    if isinstance(expr, sp.Basic | sp.MatrixBase):
        return expr.xreplace(mapping)
    if isinstance(expr, tuple):
        return tuple(_xreplace(e, mapping) for e in expr)
    return [_xreplace(e, mapping) for e in expr]


def _zero_mode(sym: SymbolicSystem) -> sp.Matrix | None:
    if sym.zero_mode_count() != 1:
        return None
    K = sym.stiffness_matrix
    n = sym.n
    if is_tridiagonal(K) and all(K[i, i + 1] != 0 for i in range(n - 1)):
        # K v = 0 row by row: v_{i+1} = -(K_{i,i-1} v_{i-1} + K_{ii} v_i) / K_{i,i+1}
        v = [sp.Integer(1)]
        for i in range(n - 1):
            previous = K[i, i - 1] * v[i - 1] if i > 0 else 0
            v.append(sp.cancel(-(previous + K[i, i] * v[i]) / K[i, i + 1]))
        return sp.Matrix(v)
    if n > 8:
        return None
    basis = K.nullspace(simplify=True)
    if len(basis) != 1:
        return None
    v = basis[0]
    return v.applyfunc(sp.cancel)


def is_tridiagonal(K: sp.Matrix) -> bool:
    """No entry more than one place off the diagonal (a chain: each spring joins neighbours)."""
    n = K.shape[0]
    return all(K[i, j] == 0 for i in range(n) for j in range(n) if abs(i - j) > 1)


def matrix_to_float(matrix: sp.Matrix, values: dict[Any, Any]) -> np.ndarray:
    """A SymPy matrix of parameters as a float array, for the values given."""
    return np.array(sp.matrix2numpy(matrix.xreplace(values).evalf(17)), dtype=float)

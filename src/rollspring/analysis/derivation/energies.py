r"""The energies of a symbolic system and what follows from them by differentiation: T, V, the
Lagrangian, the mass matrix M, the generalised forces Q and the stiffness matrix K.

:class:`EnergiesMixin` gives :class:`~.symbolic.SymbolicSystem` its coordinates and these forms:
:math:`T = \sum_i \tfrac12 J_i\dot q_i^2` (M4), the exact potential :math:`V(q)` of the springs
and the constant external forces (M5), :math:`Q_i = -\partial V/\partial q_i` from the exact lever
arms without differentiating (M7), and :math:`K` at the reference in closed form spring by spring
(M12), (M13), with :meth:`~EnergiesMixin.hessian` as its check by differentiating V twice. The
forces on the bodies built on them are in :mod:`.body_forces`.
"""

from __future__ import annotations

from collections.abc import Iterable
from functools import cached_property
from typing import Any

import sympy as sp

from rollspring.analysis.derivation.parts import (
    SymbolicBody,
    SymbolicForce,
    SymbolicSpring,
    derivatives_at_reference,
)

__all__ = ["EnergiesMixin", "cheap_form"]


class EnergiesMixin:
    """The coordinates, T, V, M, Q and K of a :class:`~.symbolic.SymbolicSystem` (its parts are
    the dataclass fields declared there)."""

    bodies: tuple[SymbolicBody, ...]
    springs: tuple[SymbolicSpring, ...]
    forces: tuple[SymbolicForce, ...]

    # -- coordinates ---------------------------------------------------------------------------
    @property
    def n(self) -> int:
        """Number of bodies (coordinates)."""
        return len(self.bodies)

    @property
    def q(self) -> list[sp.Symbol]:
        """Configuration symbols (phi_i, or x_i for sliders)."""
        return [b.q for b in self.bodies]

    @property
    def qd(self) -> list[sp.Symbol]:
        """Velocity symbols."""
        return [b.qd for b in self.bodies]

    @property
    def qdd(self) -> list[sp.Symbol]:
        """Acceleration symbols."""
        return [b.qdd for b in self.bodies]

    # -- energies and forces ---------------------------------------------------------------------
    @cached_property
    def kinetic(self) -> sp.Expr:
        r""":math:`T = \sum_i \tfrac12 J_i\dot q_i^2` (König with rolling, M4)."""
        return sp.Add(*[b.J * b.qd**2 / 2 for b in self.bodies])

    @cached_property
    def spring_energies(self) -> list[sp.Expr]:
        """Each spring's exact energy."""
        return [s.energy for s in self.springs]

    @cached_property
    def force_potentials(self) -> list[sp.Expr]:
        r"""Each external force's potential :math:`-F\cdot(P(q) - P(0))`."""
        out = []
        for f in self.forces:
            dx, dy = f.attachment.displacement(self.bodies[f.body])
            out.append(-(f.Fx * dx + f.Fy * dy))
        return out

    @cached_property
    def potential(self) -> sp.Expr:
        r"""Exact potential :math:`V(q) = \sum_s \tfrac12 k_s(l_s - L_s)^2 - \sum_f F_f\cdot
        (P_f - P_f(0))` (M5); gravity is a constant while rolling and is left out."""
        return sp.Add(*self.spring_energies, *self.force_potentials)

    @cached_property
    def lagrangian(self) -> sp.Expr:
        """:math:`L = T - V` (M5)."""
        return self.kinetic - self.potential

    @cached_property
    def mass_matrix(self) -> sp.Matrix:
        """:math:`M = \\mathrm{diag}(J_i)`, constant for any geometry (M12)."""
        matrix = sp.zeros(self.n, self.n)
        for i, b in enumerate(self.bodies):
            matrix[i, i] = b.J
        return matrix

    @cached_property
    def potential_gradient(self) -> list[sp.Expr]:
        r""":math:`\partial V/\partial q_i` by differentiating the exact potential, spring by
        spring (each spring touches at most two coordinates): the Lagrange route."""
        grad: list[list[sp.Expr]] = [[] for _ in self.bodies]
        for spring, energy in zip(self.springs, self.spring_energies, strict=True):
            for i in set(spring.bodies):
                grad[i].append(sp.diff(energy, self.bodies[i].q))
        for f, energy in zip(self.forces, self.force_potentials, strict=True):
            grad[f.body].append(sp.diff(energy, self.bodies[f.body].q))
        return [sp.Add(*terms) for terms in grad]

    @cached_property
    def lever_arms(self) -> list[dict[int, sp.Expr]]:
        r"""Exact :math:`\partial l_s/\partial q_i = e_s\cdot\Delta_{si}` for each spring and
        body it touches, with :math:`\Delta_{si} = \pm dP/dq_i` (M2): no differentiation."""
        out = []
        for spring in self.springs:
            per_body: dict[int, tuple[sp.Expr, sp.Expr]] = {}
            for sign, at in zip((-1, 1), spring.attachments, strict=True):
                if at is None:
                    continue
                dx, dy = at.velocity_per_rate(self.bodies[at.body])
                old = per_body.get(at.body, (0, 0))
                per_body[at.body] = (old[0] + sign * dx, old[1] + sign * dy)
            ex, ey = spring.direction
            out.append({i: ex * dx + ey * dy for i, (dx, dy) in per_body.items()})
        return out

    @cached_property
    def generalized_forces(self) -> sp.Matrix:
        r""":math:`Q_i = -\partial V/\partial q_i = -\sum_s T_s\,\partial l_s/\partial q_i +
        \sum_f F_f\cdot dP_f/dq_i` (M7), from the lever arms (:attr:`lever_arms`), exact: the
        clockwise torque about the contact point (a slider: the horizontal force)."""
        terms: list[list[sp.Expr]] = [[] for _ in self.bodies]
        for spring, levers in zip(self.springs, self.lever_arms, strict=True):
            tension = spring.tension
            for i, lever in levers.items():
                terms[i].append(-tension * lever)
        for f in self.forces:
            dx, dy = f.attachment.velocity_per_rate(self.bodies[f.body])
            terms[f.body].append(f.Fx * dx + f.Fy * dy)
        return sp.Matrix([sp.Add(*t) for t in terms])

    @cached_property
    def _reference_point(self) -> dict[sp.Symbol, sp.Expr]:
        return {b.q: sp.Integer(0) for b in self.bodies}

    @cached_property
    def reference_forces(self) -> sp.Matrix:
        """:math:`Q(0)`: zero at an equilibrium (these are the equilibrium conditions)."""
        return sp.Matrix([_at_zero(Q, self._reference_point) for Q in self.generalized_forces])

    @cached_property
    def stiffness_matrix(self) -> sp.Matrix:
        r""":math:`K = \partial^2 V/\partial q^2` at the reference :math:`q = 0`, in closed form
        spring by spring (docs/physics.md (M12), (M13)): with :math:`\Delta_i = \pm dP/dq_i`,
        :math:`DD_i = \pm d^2P/dq_i^2` of the spring's ends on body i, :math:`e = d_0/\ell`,
        :math:`b_i = e\cdot\Delta_i`, :math:`T = k(\ell - L)`:

        .. math:: K = \sum_s k_s b b^T + T_s\Bigl[\frac{\Delta_i\cdot\Delta_j - b_i b_j}{\ell}
                  + \delta_{ij}\, e\cdot DD_i\Bigr] - \sum_f \mathrm{diag}(F_f\cdot
                  d^2P_f/dq^2)

        Each spring touches only the entries of its (at most two) bodies. :meth:`hessian`
        gives the same matrix by differentiating V twice (slower; used to check)."""
        n = self.n
        entries: dict[tuple[int, int], list[sp.Expr]] = {}
        for spring in self.springs:
            ex, ey = spring.e0
            tension = spring.reference_tension
            first: dict[int, tuple[sp.Expr, sp.Expr]] = {}
            second: dict[int, tuple[sp.Expr, sp.Expr]] = {}
            for sign, at in zip((-1, 1), spring.attachments, strict=True):
                if at is None:
                    continue
                (dx, dy), (ddx, ddy) = derivatives_at_reference(at, self.bodies[at.body])
                old = first.get(at.body, (0, 0)), second.get(at.body, (0, 0))
                first[at.body] = (old[0][0] + sign * dx, old[0][1] + sign * dy)
                second[at.body] = (old[1][0] + sign * ddx, old[1][1] + sign * ddy)
            lever = {i: sp.expand(ex * d[0] + ey * d[1]) for i, d in first.items()}
            touched = sorted(first)
            for a, i in enumerate(touched):
                for j in touched[a:]:
                    value = spring.k * lever[i] * lever[j]
                    if tension != 0:
                        dot = first[i][0] * first[j][0] + first[i][1] * first[j][1]
                        value += tension * (dot - lever[i] * lever[j]) / spring.ell
                        if i == j:
                            value += tension * (ex * second[i][0] + ey * second[i][1])
                    value = sp.expand(value)
                    if value != 0:
                        entries.setdefault((i, j), []).append(value)
        for f in self.forces:
            _, (ddx, ddy) = derivatives_at_reference(f.attachment, self.bodies[f.body])
            value = sp.expand(-(f.Fx * ddx + f.Fy * ddy))
            if value != 0:
                entries.setdefault((f.body, f.body), []).append(value)
        matrix = sp.zeros(n, n)
        for (i, j), terms in entries.items():
            value = cheap_form(sp.Add(*terms))
            matrix[i, j] = value
            matrix[j, i] = value
        return matrix

    def hessian(self) -> sp.Matrix:
        r""":math:`\partial^2 V/\partial q_i\partial q_j` at q = 0 by differentiating the exact
        potential spring by spring (the check of :attr:`stiffness_matrix`)."""
        n = self.n
        matrix = sp.zeros(n, n)
        zero = self._reference_point
        energies = list(zip(self.springs, self.spring_energies, strict=True))
        for spring, energy in energies:
            touched = sorted(set(spring.bodies))
            for a, i in enumerate(touched):
                for j in touched[a:]:
                    value = _at_zero(sp.diff(energy, self.bodies[i].q, self.bodies[j].q), zero)
                    matrix[i, j] += value
                    if i != j:
                        matrix[j, i] += value
        for f, energy in zip(self.forces, self.force_potentials, strict=True):
            q = self.bodies[f.body].q
            matrix[f.body, f.body] += _at_zero(sp.diff(energy, q, 2), zero)
        return matrix.applyfunc(cheap_form)

    @cached_property
    def quadratic_potential(self) -> sp.Expr:
        r"""The potential to second order about the reference:
        :math:`V(0) - Q(0)^T q + \tfrac12 q^T K q` (the linear term vanishes at an equilibrium)."""
        q = sp.Matrix(self.q)
        v0 = _at_zero(self.potential, self._reference_point)
        linear = -(self.reference_forces.T * q)[0, 0]
        quadratic = (q.T * self.stiffness_matrix * q)[0, 0] / 2
        return v0 + linear + sp.expand(quadratic)

    def equations_of_motion(self, *, linear: bool = False) -> list[sp.Eq]:
        r""":math:`J_i\ddot q_i = Q_i(q)` (M7), exact; ``linear=True``: :math:`J_i\ddot q_i =
        Q_i(0) - (Kq)_i` about the reference."""
        if linear:
            rhs = self.reference_forces - self.stiffness_matrix * sp.Matrix(self.q)
        else:
            rhs = self.generalized_forces
        return [sp.Eq(b.J * b.qdd, rhs[i], evaluate=False) for i, b in enumerate(self.bodies)]

    def linearized(self, exprs: Iterable[sp.Expr]) -> list[sp.Expr]:
        """First-order Taylor expansion of expressions of q about q = 0 (qdd kept as is)."""
        zero = self._reference_point
        out = []
        for e in exprs:
            e = sp.sympify(e)
            value = _at_zero(e, zero)
            terms = [value]
            for b in self.bodies:
                if e.has(b.q):
                    terms.append(_at_zero(sp.diff(e, b.q), zero) * b.q)
            out.append(sp.Add(*terms))
        return out


def _at_zero(expr: sp.Expr, zero: dict[Any, Any]) -> sp.Expr:
    """expr at q = 0 (subs, so that sin(0), sqrt(l^2) simplify)."""
    return cheap_form(sp.sympify(expr).subs(zero))


def cheap_form(expr: sp.Expr) -> sp.Expr:
    """A cheap normal form: expanded; rational functions over a common denominator and common
    factors taken out when the expression is small (no transcendental constants)."""
    expr = sp.expand(expr)
    if expr.has(sp.sin, sp.cos):  # transcendental constants: cancel is slow and gains little
        return expr
    if any(p.exp.is_negative for p in expr.atoms(sp.Pow)) and expr.count_ops() < 400:
        return sp.factor_terms(sp.cancel(expr))
    if isinstance(expr, sp.Add) and len(expr.args) <= 6:
        return sp.factor_terms(expr)
    return expr

r"""The symbolic form of a system (SymPy): coordinates, parameters, the exact potential, M and K.

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

Geometry, exactly (docs/physics.md (M1)): spring s has the vector :math:`d_s = P_b - P_a` with
:math:`d_s(0) = \ell_s(\cos\beta_s, \sin\beta_s)` at the reference (:math:`\beta_s` its tilt)
and each body end moves by

.. math:: P(\varphi) - P(0) = \bigl(s_i\varphi_i + r(\sin(\theta_0+\rho_i\varphi_i) -
          \sin\theta_0),\; r(\cos(\theta_0+\rho_i\varphi_i) - \cos\theta_0)\bigr)

(:math:`\theta_0` the attachment's angle from the upward vertical at the reference; rolling
:math:`s_i = R_i, \rho_i = 1`; slider :math:`s_i = 1, \rho_i = 0`). Absolute positions therefore
never appear: only the reference vectors :math:`d_s(0)` and the attachments do. With
``symbols=True`` a spring between two bodies has :math:`d_s(0) = (\ell_s, \Delta y_s)`, its
rise :math:`\Delta y_s` the difference of its ends' heights in the parameters (track heights
:math:`h_i`, heights such as :math:`2R_1`), so the exact potential holds for any sizes, a tilted
spring too; where the ends are level only for this system's numbers (the paper's Fig. 3,
:math:`2R_1 = \tfrac32 R_2`) that is a condition (:attr:`SymbolicSystem.conditions`) which the
expansions about the reference (K, the linear forces) use. A spring to an anchor keeps
:math:`\ell_s(\cos\beta_s, \sin\beta_s)`.

``symbols=False``: every number is an exact rational (the system's decimal values; the inertia
factors of the built-in shapes exactly: 1, 1/2, 2/5, 2/3). ``symbols=True``: masses
:math:`m_i`, radii :math:`R_i` (one :math:`R` when all radii are equal), stiffnesses :math:`k`
(or :math:`k_s`), spring lengths :math:`\ell_s`, tilts :math:`\beta_s` (0 when horizontal),
rest lengths :math:`L_s` (only for springs under tension at the reference), attachment heights
(:math:`2R_1`, :math:`\tfrac32R_2` when a simple multiple of the radius, else :math:`y_i`),
radii :math:`r_i` and angles, forces :math:`F`, gravity :math:`g`; the shapes give their inertia
factors (a ``custom`` shape gets :math:`\gamma_i`). ``values`` holds every symbol's number.
"""

from __future__ import annotations

import math
import os
from collections.abc import Iterable
from dataclasses import dataclass, field
from fractions import Fraction
from functools import cached_property
from typing import Any

import numpy as np
import sympy as sp
from sympy.physics.mechanics import dynamicsymbols

from rollspring.analysis.linear import find_equilibrium, normal_modes
from rollspring.model import Attachment as ModelAttachment
from rollspring.model import System
from rollspring.physics import end_kinematics, spring_state, system_arrays

__all__ = [
    "EXACT_INERTIA_FACTORS",
    "SymbolicBody",
    "SymbolicForce",
    "SymbolicSpring",
    "SymbolicSystem",
    "exact_number",
    "symbolic_system",
]

#: The inertia factors of the built-in shapes, exactly (I = gamma m R^2).
EXACT_INERTIA_FACTORS: dict[str, sp.Rational] = {
    "hoop": sp.Integer(1),
    "cylinder": sp.Rational(1, 2),
    "sphere": sp.Rational(2, 5),
    "shell": sp.Rational(2, 3),
    "slider": sp.Integer(0),
}

_ZERO_TILT = 1e-12  # |d_y| / l below this: the spring is horizontal at the reference
_ZERO_TENSION = 1e-9  # |l - L0| / l below this: the spring is at rest length at the reference
_ZERO_ANGLE = 1e-12  # |q*| below this (rad or m): the body did not move to reach equilibrium


def exact_number(value: float, *, tolerance: float = 1e-12) -> sp.Rational:
    """The simplest rational within ``tolerance`` (relative) of ``value``, else its decimal.

    ``0.1`` -> 1/10, ``1.4999999999999998`` -> 3/2, ``0.3333333333333333`` -> 1/3.
    """
    if value == 0.0:
        return sp.Integer(0)
    decimal = Fraction(repr(float(value)))
    for limit in (12, 1000, 10**6):
        candidate = decimal.limit_denominator(limit)
        if abs(float(candidate) - value) <= tolerance * abs(value):
            return sp.Rational(candidate.numerator, candidate.denominator)
    return sp.Rational(decimal.numerator, decimal.denominator)


def _nice_ratio(value: float) -> sp.Rational | None:
    """``value`` as p/q with q <= 12, if it is one (to 1e-12), else None."""
    if not math.isfinite(value):
        return None
    candidate = Fraction(repr(float(value))).limit_denominator(12)
    if abs(float(candidate) - value) <= 1e-12 * max(1.0, abs(value)):
        return sp.Rational(candidate.numerator, candidate.denominator)
    return None


@dataclass(frozen=True)
class SymbolicBody:
    r"""One body's parameters and coordinate (SymPy).

    ``q`` is the plain Symbol of its coordinate (:math:`\varphi_i`, or :math:`x_i` for a slider),
    ``function`` the same as a function of time. :math:`I = \gamma m R^2`,
    :math:`J = I + mR^2 = (1+\gamma)mR^2` (Steiner, docs/physics.md (M4); the paper's :math:`I'`);
    for a slider :math:`J = m`. ``s`` is :math:`dx/dq` (R or 1), ``rho`` 1 (rolling) or 0.
    """

    index: int
    id: str
    shape: str
    rolls: bool
    m: sp.Expr
    R: sp.Expr
    gamma: sp.Expr
    q: sp.Symbol
    qd: sp.Symbol
    qdd: sp.Symbol
    function: sp.Expr

    @property
    def label(self) -> str:
        """1-based label used in symbol names ("1", "2", ...)."""
        return str(self.index + 1)

    @property
    def s(self) -> sp.Expr:
        """:math:`dx_i/dq_i`: R for a rolling body, 1 for a slider."""
        return self.R if self.rolls else sp.Integer(1)

    @property
    def rho(self) -> int:
        """:math:`d\\theta/dq_i`: 1 for a rolling body, 0 for a slider."""
        return 1 if self.rolls else 0

    @property
    def I(self) -> sp.Expr:  # noqa: E743 - the physicist's name
        r"""Central moment of inertia :math:`I = \gamma m R^2` (0 for a slider)."""
        return self.gamma * self.m * self.R**2 if self.rolls else sp.Integer(0)

    @property
    def J(self) -> sp.Expr:
        r"""Inertia about the contact line :math:`J = I + mR^2` (M4); m for a slider."""
        return (1 + self.gamma) * self.m * self.R**2 if self.rolls else self.m

    @property
    def percussion_height(self) -> sp.Expr:
        r"""Height above the contact where a force needs no friction, :math:`(1+\gamma)R`
        (M10); the paper's :math:`y = R + I/(mR)`."""
        return (1 + self.gamma) * self.R


@dataclass(frozen=True)
class Attachment:
    r"""A point fixed in a body: distance ``r`` from the centre and angle ``theta0`` (from the
    upward vertical, clockwise) at the reference. ``height`` is its height above the contact
    at the reference when it lies on the centre vertical (else None)."""

    body: int
    r: sp.Expr
    theta0: sp.Expr
    height: sp.Expr | None

    def displacement(self, body: SymbolicBody) -> tuple[sp.Expr, sp.Expr]:
        """:math:`P(q) - P(0)`, exact (M1)."""
        q = body.q
        if self.r == 0:
            return body.s * q, sp.Integer(0)
        theta = self.theta0 + body.rho * q
        return (
            body.s * q + self.r * (sp.sin(theta) - sp.sin(self.theta0)),
            self.r * (sp.cos(theta) - sp.cos(self.theta0)),
        )

    def relative_to_contact(self, body: SymbolicBody) -> tuple[sp.Expr, sp.Expr]:
        """:math:`P - K_i` (position relative to the contact point) as a function of q."""
        if not body.rolls:
            return sp.Integer(0), body.R  # a slider's point: its centre
        theta = self.theta0 + body.q
        return self.r * sp.sin(theta), body.R + self.r * sp.cos(theta)

    def velocity_per_rate(self, body: SymbolicBody) -> tuple[sp.Expr, sp.Expr]:
        """:math:`dP/dq_i` (M2)."""
        if self.r == 0 or not body.rolls:
            return body.s, sp.Integer(0)
        theta = self.theta0 + body.q
        return body.R + self.r * sp.cos(theta), -self.r * sp.sin(theta)


@dataclass(frozen=True)
class SymbolicSpring:
    r"""One spring: ends a, b (body index or None for an anchor, with their attachments),
    stiffness ``k``, rest length ``L``, reference vector ``d0`` (from end a to end b), and its
    exact vector :math:`d(q)`, length :math:`l(q)` and tension :math:`T = k(l - L)`.

    ``d0`` is general in the parameters where the ends' heights are: between two bodies its
    vertical part is the difference of the end heights above the lower floor (track heights
    :math:`h_i` and heights above the contacts such as :math:`2R_1`), so the exact potential
    holds for a tilted spring too; where those heights are equal only for this system's numbers
    (the paper's Fig. 3: :math:`2R_1 = \tfrac32 R_2`), the system records the condition
    (:attr:`SymbolicSystem.conditions`). ``e0`` and ``ell`` are the direction and length at the
    reference for this system (the conditions holding): the expansions about the reference use
    them. ``relaxed``: the spring is at its rest length at the reference."""

    index: int
    name: str
    ends: tuple[str, str]
    attachments: tuple[Attachment | None, Attachment | None]
    k: sp.Expr
    L: sp.Expr
    ell: sp.Expr
    beta: sp.Expr
    d0: tuple[sp.Expr, sp.Expr]
    vector: tuple[sp.Expr, sp.Expr]
    length: sp.Expr
    stays_horizontal: bool
    e0: tuple[sp.Expr, sp.Expr] = (sp.Integer(1), sp.Integer(0))
    relaxed: bool = True

    @property
    def reference_tension(self) -> sp.Expr:
        r""":math:`T = k(\ell - L)` at the reference (0 for a relaxed spring)."""
        return sp.Integer(0) if self.relaxed else self.k * (self.ell - self.L)

    @property
    def bodies(self) -> tuple[int, ...]:
        """Indices of the bodies the spring touches (one or two)."""
        return tuple(a.body for a in self.attachments if a is not None)

    @property
    def tension(self) -> sp.Expr:
        """:math:`T = k(l - L)`, positive when stretched."""
        return self.k * (self.length - self.L)

    @property
    def energy(self) -> sp.Expr:
        r""":math:`\tfrac12 k (l - L)^2` (M5)."""
        return self.k * (self.length - self.L) ** 2 / 2

    @property
    def direction(self) -> tuple[sp.Expr, sp.Expr]:
        """Unit vector e = d/l from end a to end b."""
        if self.stays_horizontal:
            return self.e0
        return self.vector[0] / self.length, self.vector[1] / self.length


@dataclass(frozen=True)
class SymbolicForce:
    """A constant external force (Fx, Fy) at a point fixed in a body."""

    index: int
    body: int
    attachment: Attachment
    Fx: sp.Expr
    Fy: sp.Expr


@dataclass(eq=False)
class SymbolicSystem:
    """A system in SymPy form (see the module docstring). Build it with :func:`symbolic_system`."""

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
                (dx, dy), (ddx, ddy) = _derivatives_at_reference(at, self.bodies[at.body])
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
            _, (ddx, ddy) = _derivatives_at_reference(f.attachment, self.bodies[f.body])
            value = sp.expand(-(f.Fx * ddx + f.Fy * ddy))
            if value != 0:
                entries.setdefault((f.body, f.body), []).append(value)
        matrix = sp.zeros(n, n)
        for (i, j), terms in entries.items():
            value = _tidy(sp.Add(*terms))
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
        return matrix.applyfunc(_tidy)

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

    # -- forces on the bodies ------------------------------------------------------------------
    @cached_property
    def spring_end_forces(self) -> list[tuple[tuple[sp.Expr, sp.Expr], tuple[sp.Expr, sp.Expr]]]:
        """Force of each spring on its end a (:math:`+Te`) and end b (:math:`-Te`)."""
        out = []
        for s in self.springs:
            ex, ey = s.direction
            T = s.tension
            out.append(((T * ex, T * ey), (-T * ex, -T * ey)))
        return out

    @cached_property
    def body_forces(self) -> list[tuple[sp.Expr, sp.Expr]]:
        r"""Resultant applied force :math:`(F_{ix}, F_{iy})` on each body (springs and external
        forces; not gravity, friction or the normal force), exact in q."""
        fx: list[list[sp.Expr]] = [[] for _ in self.bodies]
        fy: list[list[sp.Expr]] = [[] for _ in self.bodies]
        for spring, forces in zip(self.springs, self.spring_end_forces, strict=True):
            for at, (Fx, Fy) in zip(spring.attachments, forces, strict=True):
                if at is not None:
                    fx[at.body].append(Fx)
                    fy[at.body].append(Fy)
        for f in self.forces:
            fx[f.body].append(f.Fx)
            fy[f.body].append(f.Fy)
        return [(sp.Add(*x), sp.Add(*y)) for x, y in zip(fx, fy, strict=True)]

    @cached_property
    def contact_torques(self) -> sp.Matrix:
        r"""Newton's route to :math:`Q_i`: the clockwise torque of the applied forces about the
        contact point, :math:`\sum [F_x (P_y - h_i) - F_y (P_x - x_i)]` (M7); a slider's
        :math:`Q_i` is its horizontal force."""
        terms: list[list[sp.Expr]] = [[] for _ in self.bodies]
        for spring, forces in zip(self.springs, self.spring_end_forces, strict=True):
            for at, (Fx, Fy) in zip(spring.attachments, forces, strict=True):
                if at is not None:
                    terms[at.body].append(self._torque(at, Fx, Fy))
        for f in self.forces:
            terms[f.body].append(self._torque(f.attachment, f.Fx, f.Fy))
        return sp.Matrix([sp.Add(*t) for t in terms])

    def _torque(self, at: Attachment, Fx: sp.Expr, Fy: sp.Expr) -> sp.Expr:
        body = self.bodies[at.body]
        if not body.rolls:
            return Fx
        rx, ry = at.relative_to_contact(body)
        return Fx * ry - Fy * rx

    @cached_property
    def friction(self) -> list[sp.Expr]:
        r"""Required static friction :math:`f_i = m_i R_i\ddot\varphi_i - F_{ix}` (M8), in q and
        qdd, positive along +x (0 for a slider, on a frictionless floor)."""
        return [
            b.m * b.s * b.qdd - F[0] if b.rolls else sp.Integer(0)
            for b, F in zip(self.bodies, self.body_forces, strict=True)
        ]

    @cached_property
    def friction_configuration(self) -> list[sp.Expr]:
        r""":math:`f_i = Q_i/((1+\gamma_i)R_i) - F_{ix}` (M8 with M7 substituted): a function
        of the configuration only."""
        return [
            b.m * b.s * Q / b.J - F[0] if b.rolls else sp.Integer(0)
            for b, Q, F in zip(self.bodies, self.generalized_forces, self.body_forces, strict=True)
        ]

    @cached_property
    def normal(self) -> list[sp.Expr]:
        r"""Normal force :math:`N_i = m_i g - F_{iy}` (M9), in q."""
        return [b.m * self.g - F[1] for b, F in zip(self.bodies, self.body_forces, strict=True)]

    @cached_property
    def reference_body_forces(self) -> list[tuple[sp.Expr, sp.Expr]]:
        """:math:`F_i` at the reference (tension T = k(ell - L) along e on every spring)."""
        fx: list[sp.Expr] = [sp.Integer(0)] * self.n
        fy: list[sp.Expr] = [sp.Integer(0)] * self.n
        for spring in self.springs:
            tension = spring.reference_tension
            ex, ey = spring.e0
            for sign, at in zip((1, -1), spring.attachments, strict=True):
                if at is not None:
                    fx[at.body] += sign * tension * ex
                    fy[at.body] += sign * tension * ey
        for f in self.forces:
            fx[f.body] += f.Fx
            fy[f.body] += f.Fy
        return [(sp.expand(x), sp.expand(y)) for x, y in zip(fx, fy, strict=True)]

    @cached_property
    def body_force_jacobian(self) -> list[list[tuple[sp.Expr, sp.Expr]]]:
        r""":math:`\partial F_i/\partial q_j` at the reference, in closed form: along a
        displacement the force on end a changes by :math:`k\,\delta l\,e + T(\delta d -
        e(e\cdot\delta d))/\ell` (docs/physics.md section 7); ``[i][j] = (dF_ix, dF_iy)``."""
        n = self.n
        out = [[(sp.Integer(0), sp.Integer(0)) for _ in range(n)] for _ in range(n)]
        for spring in self.springs:
            ex, ey = spring.e0
            tension = spring.reference_tension
            delta: dict[int, tuple[sp.Expr, sp.Expr]] = {}
            for sign, at in zip((-1, 1), spring.attachments, strict=True):
                if at is not None:
                    (dx, dy), _ = _derivatives_at_reference(at, self.bodies[at.body])
                    old = delta.get(at.body, (0, 0))
                    delta[at.body] = (old[0] + sign * dx, old[1] + sign * dy)
            for j, (dx, dy) in delta.items():
                lever = ex * dx + ey * dy
                pull_x = spring.k * lever * ex + tension * (dx - ex * lever) / spring.ell
                pull_y = spring.k * lever * ey + tension * (dy - ey * lever) / spring.ell
                for sign, at in zip((1, -1), spring.attachments, strict=True):
                    if at is not None:
                        old = out[at.body][j]
                        out[at.body][j] = (old[0] + sign * pull_x, old[1] + sign * pull_y)
        return [[(sp.expand(x), sp.expand(y)) for x, y in row] for row in out]

    @cached_property
    def linear_contact_forces(self) -> tuple[list[sp.Expr], list[sp.Expr]]:
        r"""Friction and normal forces to first order about the reference, from K and the force
        Jacobian (no differentiation of the exact forms):

        .. math:: f_i \approx f_i(0) - \sum_j\Bigl[\frac{m_i s_i}{J_i}K_{ij} +
                  \frac{\partial F_{ix}}{\partial q_j}\Bigr]q_j,\qquad
                  N_i \approx N_i(0) - \sum_j \frac{\partial F_{iy}}{\partial q_j} q_j
        """
        K = self.stiffness_matrix
        jac = self.body_force_jacobian
        friction, normal = [], []
        for i, b in enumerate(self.bodies):
            Fx0, Fy0 = self.reference_body_forces[i]
            normal.append(
                sp.Add(
                    b.m * self.g - Fy0, *[-jac[i][j][1] * self.bodies[j].q for j in range(self.n)]
                )
            )
            if not b.rolls:
                friction.append(sp.Integer(0))
                continue
            share = b.m * b.s / b.J
            terms = [_tidy(share * self.reference_forces[i] - Fx0)]
            for j in range(self.n):
                coefficient = _tidy(-share * K[i, j] - jac[i][j][0])
                if coefficient != 0:
                    terms.append(coefficient * self.bodies[j].q)
            friction.append(sp.Add(*terms))
        return friction, normal

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


def _derivatives_at_reference(
    at: Attachment, body: SymbolicBody
) -> tuple[tuple[sp.Expr, sp.Expr], tuple[sp.Expr, sp.Expr]]:
    """dP/dq and d2P/dq2 of a body point at q = 0, (M2), (M3)."""
    if at.r == 0 or not body.rolls:
        return (body.s, sp.Integer(0)), (sp.Integer(0), sp.Integer(0))
    sin, cos = sp.sin(at.theta0), sp.cos(at.theta0)
    return (body.R + at.r * cos, -at.r * sin), (-at.r * sin, -at.r * cos)


def _xreplace(expr: Any, mapping: dict[Any, Any]) -> Any:
    if isinstance(expr, sp.Basic | sp.MatrixBase):
        return expr.xreplace(mapping)
    if isinstance(expr, tuple):
        return tuple(_xreplace(e, mapping) for e in expr)
    return [_xreplace(e, mapping) for e in expr]


def _at_zero(expr: sp.Expr, zero: dict[Any, Any]) -> sp.Expr:
    """expr at q = 0 (subs, so that sin(0), sqrt(l^2) simplify)."""
    return _tidy(sp.sympify(expr).subs(zero))


def _tidy(expr: sp.Expr) -> sp.Expr:
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


def _zero_mode(sym: SymbolicSystem) -> sp.Matrix | None:
    if sym.zero_mode_count() != 1:
        return None
    K = sym.stiffness_matrix
    n = sym.n
    if _is_tridiagonal(K) and all(K[i, i + 1] != 0 for i in range(n - 1)):
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


def _end_height(
    at: Attachment | None, bodies: tuple[SymbolicBody, ...], track: Any
) -> sp.Expr | None:
    """The height of a spring end above the lowest floor at the reference, in the parameters
    (None for an anchor: its height is a number of the system, not a parameter)."""
    if at is None:
        return None
    body = bodies[at.body]
    if at.height is not None:
        above = at.height
    elif at.r == 0:
        above = body.R
    else:
        above = body.R + at.r * sp.cos(at.theta0)
    return track(at.body) + above


def _rise(
    ats: list[Attachment | None], bodies: tuple[SymbolicBody, ...], track: Any
) -> sp.Expr | None:
    """End b's height minus end a's, in the parameters (None if an end is an anchor)."""
    heights = [_end_height(a, bodies, track) for a in ats]
    if heights[0] is None or heights[1] is None:
        return None
    return sp.expand(heights[1] - heights[0])


def _is_tridiagonal(K: sp.Matrix) -> bool:
    n = K.shape[0]
    return all(K[i, j] == 0 for i in range(n) for j in range(n) if abs(i - j) > 1)


# -- building ------------------------------------------------------------------------------------


class _Namer:
    """Symbols named after the paper's notation, with their numbers recorded."""

    def __init__(self, symbolic: bool) -> None:
        self.symbolic = symbolic
        self.values: dict[sp.Symbol, float] = {}

    def __call__(self, name: str, value: float, **assumptions: bool) -> sp.Expr:
        if not self.symbolic:
            return exact_number(value)
        symbol = sp.Symbol(name, **assumptions)
        previous = self.values.get(symbol)
        if previous is not None and previous != value:
            raise ValueError(f"symbol {name} used for two values")  # a naming bug
        self.values[symbol] = float(value)
        return symbol


def symbolic_system(
    system: System | dict[str, Any] | str | os.PathLike[str], *, symbols: bool = False
) -> SymbolicSystem:
    """The SymPy form of a validated :class:`~rollspring.model.System`.

    ``symbols=False``: exact rational numbers; ``symbols=True``: parameters as symbols (see the
    module docstring). Coordinates are measured from the equilibrium nearest the initial
    placement (from :func:`rollspring.analysis.find_equilibrium`; the initial placement when
    there is none). ``system`` may also be its JSON form, a file path or a preset name
    (:func:`rollspring.model.as_system`).
    """
    from rollspring.model import as_system

    system = as_system(system)
    arrays = system_arrays(system)
    n = arrays.n_bodies
    equilibrium = find_equilibrium(arrays)
    q_ref = np.array(equilibrium.q, dtype=float) if equilibrium.found else np.zeros(n)
    q_ref = np.where(np.abs(q_ref) < _ZERO_ANGLE, 0.0, q_ref)
    reference = "equilibrium" if equilibrium.found else "initial placement"
    name = _Namer(symbols)

    rolling = [b for b in system.bodies if b.rolls]
    one_radius = len({b.radius for b in rolling}) == 1 and (len(rolling) > 1 or n == 1)
    single = n == 1

    def sub(base: str, label: str) -> str:
        return base if single else f"{base}_{label}"

    bodies = []
    for i, b in enumerate(system.bodies):
        label = str(i + 1)
        m = name(sub("m", label), b.mass, positive=True)
        if b.rolls:
            R = name("R" if one_radius else sub("R", label), b.radius, positive=True)
        else:
            R = exact_number(b.radius)  # a slider's drawing size: no role in its mechanics
        if b.shape == "custom":
            gamma = name(sub("gamma", label), float(b.gamma), positive=True)
        else:
            gamma = EXACT_INERTIA_FACTORS[b.shape]
        base = "phi" if b.rolls else "x"
        tail = "" if single else f"_{label}"
        q = sp.Symbol(base + tail, real=True)
        fn = dynamicsymbols(base + tail)
        qd = sp.Symbol(f"{base}dot{tail}", real=True)
        qdd = sp.Symbol(f"{base}ddot{tail}", real=True)
        bodies.append(SymbolicBody(i, b.id, b.shape, b.rolls, m, R, gamma, q, qd, qdd, fn))
    bodies_t = tuple(bodies)
    index = {b.id: i for i, b in enumerate(system.bodies)}

    # attachment naming: a body with one off-centre attachment gets short names (y_1, r_1)
    uses: dict[int, int] = {}
    for spring in system.springs:
        for end, at in zip(spring.ends, spring.attachments, strict=True):
            if end in index and not at.is_centre_form:
                uses[index[end]] = uses.get(index[end], 0) + 1
    for force in system.forces:
        if not force.at.is_centre_form:
            uses[index[force.body]] = uses.get(index[force.body], 0) + 1

    def attachment(body_index: int, at: ModelAttachment, where: str) -> Attachment:
        body = bodies_t[body_index]
        model = system.bodies[body_index]
        r_value, alpha = at.polar(model)
        moved = float(q_ref[body_index]) * (1.0 if model.rolls else 0.0)
        label = body.label if single is False else ""
        if r_value == 0.0:
            return Attachment(
                body_index, sp.Integer(0), sp.Integer(0), body.R if model.rolls else None
            )
        if at.height is not None and moved == 0.0:
            many = uses.get(body_index, 0) > 1
            ratio = _nice_ratio(at.height / model.radius)
            if ratio is not None and symbols:
                height = ratio * body.R
            else:
                nm = "y" + (f"_{label},{where}" if many else (f"_{label}" if label else ""))
                height = name(nm, at.height, positive=True)
            return Attachment(body_index, height - body.R, sp.Integer(0), height)
        many = uses.get(body_index, 0) > 1
        ratio = _nice_ratio(r_value / model.radius)
        if ratio is not None and symbols:
            r = ratio * body.R
        else:
            nm = "r" + (f"_{label},{where}" if many else (f"_{label}" if label else ""))
            r = name(nm, r_value, positive=True)
        theta_value = alpha + moved
        degrees = _nice_ratio(math.degrees(theta_value) / 15.0) if moved == 0.0 else None
        if degrees is not None:
            theta0 = sp.pi * degrees / 12
        elif symbols:
            nm = "theta" + (f"_{label},{where}" if many else (f"_{label}" if label else ""))
            theta0 = name(nm, theta_value, real=True)
        else:
            theta0 = exact_number(theta_value)
        return Attachment(body_index, r, theta0, None)

    # reference geometry of the springs (at the equilibrium)
    ref_state = spring_state(arrays, q_ref) if arrays.n_springs else None
    position, _, _ = end_kinematics(arrays, q_ref) if arrays.n_springs else (None, None, None)
    n_springs = len(system.springs)
    springs = []
    conditions: list[sp.Eq] = []
    lifted = [i for i, b in enumerate(system.bodies) if b.track_height != 0.0]

    def track(i: int) -> sp.Expr:
        """Body i's track height above the lowest floor (a symbol h_i where it is not 0)."""
        if i not in lifted:
            return sp.Integer(0)
        return name(sub("h", str(i + 1)), system.bodies[i].track_height, real=True)

    for s, spring in enumerate(system.springs):
        assert position is not None and ref_state is not None  # there are springs
        label = str(s + 1)
        only = n_springs == 1
        k = name("k" if only else f"k_{label}", spring.stiffness, positive=True)
        dx, dy = (position[s, 1] - position[s, 0]).tolist()
        length = float(ref_state.length[s])
        rest = float(arrays.rest_length[s])
        horizontal = abs(dy) <= _ZERO_TILT * length
        relaxed = abs(length - rest) <= _ZERO_TENSION * length
        ats: list[Attachment | None] = []
        for end, at in zip(spring.ends, spring.attachments, strict=True):
            ats.append(attachment(index[end], at, label) if end in index else None)
        rise = _rise(ats, bodies_t, track) if symbols else None
        ell_name = "ell" if only else f"ell_{label}"
        e0: tuple[sp.Expr, sp.Expr]
        if rise is not None and sp.expand(rise) != 0:
            # the vertical part in the parameters: exact for any sizes (a tilted spring too)
            ell = name(ell_name, abs(dx), positive=True)
            across = ell if dx > 0 else -ell
            d0 = (across, rise)
            if horizontal:  # level for this system's numbers only: a condition on them
                heights = [_end_height(a, bodies_t, track) for a in ats]
                assert heights[0] is not None and heights[1] is not None  # rise is known
                conditions.append(sp.Eq(heights[0], heights[1], evaluate=False))
                e0 = (sp.sign(across), sp.Integer(0))
            else:
                ell = sp.sqrt(ell**2 + rise**2)
                e0 = (across / ell, rise / ell)
            beta = sp.atan2(rise, across)
            general_length = sp.sqrt(across**2 + rise**2)
        else:
            ell = name(ell_name, length, positive=True)
            if horizontal:
                beta = sp.Integer(0) if dx > 0 else sp.pi
            elif symbols:
                beta = name("beta" if only else f"beta_{label}", math.atan2(dy, dx), real=True)
            else:
                beta = None
            if symbols or horizontal:
                d0 = (ell * sp.cos(beta), ell * sp.sin(beta))
            else:  # exact numbers: the reference vector itself
                d0x, d0y = exact_number(dx), exact_number(dy)
                ell = sp.sqrt(d0x**2 + d0y**2)
                beta = sp.atan2(d0y, d0x)
                d0 = (d0x, d0y)
            e0 = (sp.cos(beta), sp.sin(beta)) if horizontal else (d0[0] / ell, d0[1] / ell)
            general_length = ell
        L = (
            general_length
            if relaxed
            else name("L" if only else f"L_{label}", rest, nonnegative=True)
        )
        moves = [a.displacement(bodies_t[a.body]) if a is not None else (0, 0) for a in ats]
        vx = d0[0] + moves[1][0] - moves[0][0]
        vy = d0[1] + moves[1][1] - moves[0][1]
        level = horizontal and (rise is None or sp.expand(rise) == 0)
        stays = level and all(a is None or a.r == 0 for a in ats)
        if stays:
            vy = sp.Integer(0)
            exact_length = vx if dx > 0 else -vx
        else:
            exact_length = sp.sqrt(vx**2 + vy**2)
        springs.append(
            SymbolicSpring(
                s,
                arrays.spring_names[s],
                (spring.ends[0], spring.ends[1]),
                (ats[0], ats[1]),
                k,
                L,
                ell,
                beta,
                d0,
                (vx, vy),
                exact_length,
                stays,
                e0,
                relaxed,
            )
        )

    forces = []
    n_forces = len(system.forces)
    for f, force in enumerate(system.forces):
        label = "" if n_forces == 1 else f",{f + 1}"
        point = attachment(index[force.body], force.at, f"F{f + 1}")
        if force.fx != 0.0 and force.fy == 0.0 and n_forces == 1:
            Fx, Fy = name("F", force.fx, real=True), sp.Integer(0)
        else:
            Fx = name(f"F_x{label}", force.fx, real=True) if force.fx != 0.0 else sp.Integer(0)
            Fy = name(f"F_y{label}", force.fy, real=True) if force.fy != 0.0 else sp.Integer(0)
        forces.append(SymbolicForce(f, index[force.body], point, Fx, Fy))

    g = name("g", system.gravity, positive=True)
    notes = []
    if not equilibrium.found:
        notes.append(
            "no equilibrium near the initial placement: coordinates are measured from "
            "the initial placement and the expansions are about it"
        )
    if any(s.damping > 0 for s in system.springs):
        notes.append("spring damping is left out of the derivations (conservative forces only)")
    return SymbolicSystem(
        system=system,
        symbolic=symbols,
        bodies=bodies_t,
        springs=tuple(springs),
        forces=tuple(forces),
        g=g,
        values=dict(name.values),
        reference=reference,
        q_reference=q_ref,
        notes=notes,
        conditions=conditions,
    )


def matrix_to_float(matrix: sp.Matrix, values: dict[Any, Any]) -> np.ndarray:
    """A SymPy matrix of parameters as a float array, for the values given."""
    return np.array(sp.matrix2numpy(matrix.xreplace(values).evalf(17)), dtype=float)

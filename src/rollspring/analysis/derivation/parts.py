r"""The parts of a system in SymPy form: its bodies, the points fixed in them (with their exact
kinematics), its springs and external forces; and exact numbers for the system's decimals.

A :class:`~.symbolic.SymbolicSystem` (built by :func:`~.build.symbolic_system`) holds these
parts; every expression in them is in the coordinates :math:`q_i` measured from the reference
configuration, in exact rationals or in the parameters as symbols.

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
:math:`2R_1 = \tfrac32 R_2`) that is a condition
(:attr:`~.symbolic.SymbolicSystem.conditions`) which the expansions about the reference (K, the
linear forces) use. A spring to an anchor keeps
:math:`\ell_s(\cos\beta_s, \sin\beta_s)`.
"""

from __future__ import annotations

from dataclasses import dataclass
from fractions import Fraction

import sympy as sp

__all__ = [
    "EXACT_INERTIA_FACTORS",
    "Attachment",
    "SymbolicBody",
    "SymbolicForce",
    "SymbolicSpring",
    "derivatives_at_reference",
    "exact_number",
]


#: The inertia factors of the built-in shapes, exactly (I = gamma m R^2).
EXACT_INERTIA_FACTORS: dict[str, sp.Rational] = {
    "hoop": sp.Integer(1),
    "cylinder": sp.Rational(1, 2),
    "sphere": sp.Rational(2, 5),
    "shell": sp.Rational(2, 3),
    "slider": sp.Integer(0),
}


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


def derivatives_at_reference(
    at: Attachment, body: SymbolicBody
) -> tuple[tuple[sp.Expr, sp.Expr], tuple[sp.Expr, sp.Expr]]:
    """dP/dq and d2P/dq2 of a body point at q = 0, (M2), (M3)."""
    if at.r == 0 or not body.rolls:
        return (body.s, sp.Integer(0)), (sp.Integer(0), sp.Integer(0))
    sin, cos = sp.sin(at.theta0), sp.cos(at.theta0)
    return (body.R + at.r * cos, -at.r * sin), (-at.r * sin, -at.r * cos)

r"""The forces on the bodies of a symbolic system: the springs' pulls on their ends, each body's
resultant applied force, its torque about the contact point (Newton's route to Q), and the static
friction and normal force the floor must supply (docs/physics.md (M7)-(M9)), exact and to first
order about the reference.

:class:`BodyForcesMixin` adds these to :class:`~.symbolic.SymbolicSystem`, on top of the
energies, Q and K of :class:`~.energies.EnergiesMixin`; :mod:`.forces` derives the contact forces
step by step from them.
"""

from __future__ import annotations

from functools import cached_property

import sympy as sp

from rollspring.analysis.derivation.energies import EnergiesMixin, cheap_form
from rollspring.analysis.derivation.parts import Attachment, derivatives_at_reference
from rollspring.analysis.derivation.steps import named
from rollspring.model import System

__all__ = ["BodyForcesMixin"]


class BodyForcesMixin(EnergiesMixin):
    """The applied, friction and normal forces on the bodies of a
    :class:`~.symbolic.SymbolicSystem`."""

    g: sp.Expr
    system: System
    symbolic: bool

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
    def rolling_resistance(self) -> list[sp.Expr]:
        r"""The generalised force of rolling resistance on each body, docs/physics.md (M21):

        .. math:: \Gamma_i = -C_{rr,i}\, N_i\, R_i\,\operatorname{sgn}\dot\varphi_i

        (:math:`N_i` of :attr:`normal`, in q), the torque about the contact line of the normal
        force acting :math:`C_{rr} R` ahead of it: a dissipative force beside
        :math:`Q_i = -\partial V/\partial q_i`, with no potential. 0 for a body without it
        (and for a slider). :math:`C_{rr,i}` is the exact rational of the system's value, or
        with ``symbols=True`` the symbol ``C_rr<i>``."""
        out: list[sp.Expr] = []
        for b, body, normal in zip(self.bodies, self.system.bodies, self.normal, strict=True):
            if body.rolling_resistance <= 0 or not b.rolls:
                out.append(sp.Integer(0))
                continue
            c_rr: sp.Expr = (
                named(f"C_rr{b.label}", rf"C_{{\mathrm{{rr}},{b.label}}}", positive=True)
                if self.symbolic
                else sp.Rational(repr(body.rolling_resistance))
            )
            out.append(-c_rr * normal * b.R * sp.sign(b.qd))
        return out

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
                    (dx, dy), _ = derivatives_at_reference(at, self.bodies[at.body])
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
            terms = [cheap_form(share * self.reference_forces[i] - Fx0)]
            for j in range(self.n):
                coefficient = cheap_form(-share * K[i, j] - jac[i][j][0])
                if coefficient != 0:
                    terms.append(coefficient * self.bodies[j].q)
            friction.append(sp.Add(*terms))
        return friction, normal

r"""Rolling resistance in the derivations (docs/physics.md (M21)-(M23)): a generalised force,
not a potential.

The floor's normal force :math:`N_i` acting :math:`C_{rr,i} R_i` ahead of the contact line has
the torque :math:`\Gamma_i = -C_{rr,i} N_i R_i\operatorname{sgn}\dot\varphi_i` about it
(:attr:`~.symbolic.SymbolicSystem.rolling_resistance`). Newton's torque equations take it beside
the applied forces' torques, and the Euler-Lagrange equations as a generalised force
:math:`Q^{\mathrm{nc}}_i` (the virtual work of the shifted normal force is
:math:`\Gamma_i\,\delta\varphi_i`): :func:`resistance_step` writes that step. Energy conservation
and Hamilton's equations do not take it -- it dissipates energy and has no potential -- so with
it they, and the linearised equations of every method, describe the motion between the
instants a body stops or turns: :func:`resistance_note` says so.
"""

from __future__ import annotations

import sympy as sp

from rollspring.analysis.derivation.method import short
from rollspring.analysis.derivation.steps import GIVEN, Section, eq
from rollspring.analysis.derivation.symbolic import SymbolicSystem

__all__ = ["RESISTANCE_NOTE", "resistance_step"]

#: What the derivations say of rolling resistance (:attr:`SymbolicSystem.notes`).
RESISTANCE_NOTE = (
    "rolling resistance (M21) enters Newton's and Lagrange's exact equations as the generalised "
    "force -C_rr N R sgn(phi'); energy conservation and Hamilton's equations do not take it (it "
    "dissipates energy and has no potential), so they, and every method's linearised equations "
    "and frequencies, describe the motion between the instants a body stops or turns, where "
    "the resistance is a constant force that shifts the centre of the swing, not its frequency "
    "(the amplitude falls by (M23) a period; a body stops where |Q| <= C_rr N R, (M22))"
)


def resistance_step(
    section: Section, sym: SymbolicSystem, method: str, exact: list[sp.Eq], exact_tag: str
) -> None:
    """After the exact equations ``exact`` (step ``exact_tag``) of ``method`` (``"newton"`` or
    ``"lagrange"``), the same equations with the rolling resistance's generalised force added to
    each resisted body's (nothing when no body has rolling resistance)."""
    resistance = sym.rolling_resistance
    bodies = [i for i, term in enumerate(resistance) if term != 0]
    if not bodies:
        return
    equations = [eq(exact[i].lhs, exact[i].rhs + short(resistance[i])) for i in bodies]
    if method == "newton":
        why = (
            f"Rolling resistance: the floor's normal force N = m g - F_y acts C_rr R ahead of the "
            f"contact line z', so about z' it adds the torque -C_rr N R sgn(phi') to ({exact_tag})"
        )
    else:
        why = (
            "Rolling resistance as a generalised force: the normal force N = m g - F_y acting "
            "C_rr R ahead of the contact line does the virtual work -C_rr N R sgn(phi') "
            "delta phi, so the Euler-Lagrange equations read d/dt(dL/dphi_i') - dL/dphi_i = "
            f"Q^nc_i = -C_rr N R sgn(phi_i'), added to ({exact_tag})"
        )
    section.add(
        equations,
        why + ": exact while the body turns; at rest it holds the body while |Q| <= C_rr N R. "
        "Its sign follows the rotation, so it is not linear: the linearisation below is the "
        "motion between the instants a body stops or turns.",
        "(M21), (M22)",
        how=GIVEN,
    )

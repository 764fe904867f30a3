r"""Newton's derivation: the torques of the applied forces about the contact points (paper Sec. 2,
3 and 5.1; docs/physics.md (M7)).

Hooke's law gives each spring's force, :math:`F = k(l - L)`. For a rolling body the torque
equation about its contact point, :math:`J_i\ddot\varphi_i = ` the clockwise torque of the
applied forces, holds although the contact point accelerates: its acceleration points through
the centre, and friction and the normal force act at it. A slider obeys :math:`m\ddot x = F_x`.
Substituting the spring forces gives each body's exact equation of motion (while the bodies
roll); linearised, :mod:`.whole_system` takes them to the equation of the whole system and its
:math:`\Omega^2`.
"""

from __future__ import annotations

import sympy as sp

from rollspring.analysis.derivation.method import TITLES, MethodResult, method_section, short
from rollspring.analysis.derivation.resistance import resistance_step
from rollspring.analysis.derivation.setup import length_symbols, setup_tags
from rollspring.analysis.derivation.steps import GIVEN, How, eq
from rollspring.analysis.derivation.symbolic import SymbolicSystem
from rollspring.analysis.derivation.whole_system import linearise_in_angles

__all__ = ["newton"]


def newton(sym: SymbolicSystem, budget: float | None) -> MethodResult:
    """Torques of the applied forces about the contact points."""
    section = method_section(sym, "newton")
    tags = setup_tags(sym)
    lengths = length_symbols(sym)
    forces = [
        sp.Symbol("F" if len(sym.springs) == 1 else f"F_{s.index + 1}", real=True)
        for s in sym.springs
    ]
    if sym.springs:
        tension = section.add(
            [
                eq(F, s.k * sp.factor_terms(s.length - s.L))
                for F, s in zip(forces, sym.springs, strict=True)
            ],
            "Spring forces by Hooke's law, F = k(l - L) (positive when stretched: it pulls "
            f"both ends towards each other), with the lengths l of ({tags['lengths']}).",
            "paper F = k(R phi2 - R phi1)",
            how=How(
                "substitute",
                (tags["lengths"],),
                args=tuple(lengths),
                law=[
                    eq(F, s.k * (name - s.L))
                    for F, name, s in zip(forces, lengths, sym.springs, strict=True)
                ],
            ),
        )
    law = []
    for i, b in enumerate(sym.bodies):
        terms = []
        for F, levers in zip(forces, sym.lever_arms, strict=True):
            if i in levers:
                terms.append(-F * short(levers[i]))
        for f in sym.forces:
            if f.body == i:
                dx, dy = f.attachment.velocity_per_rate(b)
                terms.append(f.Fx * dx + f.Fy * dy)
        law.append(eq(b.J * b.qdd, sp.Add(*terms)))
    rolling = any(b.rolls for b in sym.bodies)
    why = (
        "For each rolling body, the torque equation about its contact line z' (the paper's "
        "instantaneous axis, through the body's lowest point): I' phi'' = the clockwise torque "
        f"of the applied forces, with I' of ({tags.get('inertia', '')}). It holds although the "
        "body's lowest point accelerates, because its acceleration (R phi'^2, straight up) "
        "points through the centre, the centre of mass; friction and the normal force act on "
        "z' and have no torque about it. The spring's torque is its force times its lever arm "
        "about z'."
        if rolling
        else "Newton's second law for each slider: m x'' = the horizontal applied force."
    )
    if rolling and any(not b.rolls for b in sym.bodies):
        why += " A slider: m x'' = the horizontal applied force."
    law_step = section.add(law, why, "paper (e), (f), (a), (b); (M7)", how=GIVEN)
    torques = sym.contact_torques
    nonlinear = [eq(b.J * b.qdd, short(torques[i])) for i, b in enumerate(sym.bodies)]
    exact_tag = law_step.tag
    if sym.springs:
        exact_tag = section.add(
            nonlinear,
            f"Substituting the spring forces ({tension.tag}) into ({law_step.tag}): each "
            "body's equation of motion, exact at any amplitude"
            + (" (while the bodies roll)." if rolling else "."),
            "paper (w2), (w22); (M7)",
            how=How("substitute", (law_step.tag, tension.tag), args=tuple(forces)),
        ).tag
    resistance_step(section, sym, "newton", nonlinear, exact_tag)
    result = MethodResult("newton", TITLES["newton"], True, "", section, nonlinear=nonlinear)
    linearise_in_angles(result, sym, exact_tag, budget)
    return result

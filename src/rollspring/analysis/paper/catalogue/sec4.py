"""The claims of Sec. 4: the spring at the percussion heights, no static friction (Fig. 3).

Eq. (fric) and the heights that cancel the friction, Fig. 3's geometry (R1 = R2/2, the centres
level), its equations of motion divided by the lever arms, the centre of mass at rest, and the
torques and angular momenta of the two bodies. Their words are in ``claims.toml``.
"""

from __future__ import annotations

import sympy as sp

from rollspring.analysis.paper.assumptions import LEVEL, SMALL_ANGLES
from rollspring.analysis.paper.catalogue.common import TRUE
from rollspring.analysis.paper.catalogue.entry import Entry, claim, restates
from rollspring.analysis.paper.notation import I_, Fx1, Fx2
from rollspring.analysis.paper.recipes.sec4 import (
    fig3_angular_momentum,
    fig3_combination,
    fig3_eom,
    fig3_equal_forces,
    fig3_friction,
    fig3_spring_force,
    fig3_torques_differ,
    fig3_x,
    fric,
    fric_coupled,
    friction_not_needed,
    geometry,
    heights,
)
from rollspring.analysis.paper.symbols import R1, R2, F, R, k, m, m1, m2, phi1, phi2, y

_F3 = k * (sp.Rational(3, 2) * R2 * phi2 - 2 * R1 * phi1)  # the spring force of Fig. 3

_J31, _J32 = 2 * m1 * R1**2, sp.Rational(3, 2) * m2 * R2**2  # I'_1, I'_2 of Fig. 3


def claims() -> list[Entry]:
    """The claims of Sec. 4, in the paper's order."""
    return [
        claim(
            key="sec4.friction-must-vanish",
            quantity=r"\dot X=0\ \text{requires}\ f_1=f_2=0",
            paper=TRUE,
            system="two-hoops, zero-sum",
            derive=friction_not_needed,
        ),
        claim(
            key="sec4.fric",
            quantity=r"\left(f(y),\ f''(y),\ \operatorname{sign}(-f'(y)/F)\right)",
            paper=(F * (1 - m * R * y / (I_ + m * R**2)), sp.Integer(0), sp.Integer(1)),
            system="pulled",
            derive=fric,
        ),
        claim(
            key="sec4.zero-friction-heights",
            quantity=r"\left(y_1,\ y_2\right)",
            paper=(2 * R, sp.Rational(3, 2) * R),
            system="pulled-hoop, pulled-cylinder",
            derive=heights,
        ),
        claim(
            key="sec4.fric-coupled",
            quantity=(
                r"\left(f_1,\ f_2\right)_{\text{Fig. 2}},\ "
                r"\left(f_1,\ f_2\right)_{\text{Fig. 3}}"
            ),
            paper=(
                -Fx1 * (1 - m1 * R * R / (m1 * R**2 + m1 * R**2)),
                -Fx2 * (1 - m2 * R * R / (m2 * R**2 / 2 + m2 * R**2)),
                -Fx1 * (1 - m1 * R1 * 2 * R1 / (m1 * R1**2 + m1 * R1**2)),
                -Fx2 * (1 - m2 * R2 * sp.Rational(3, 2) * R2 / (m2 * R2**2 / 2 + m2 * R2**2)),
            ),
            system="fig2, fig3",
            derive=fric_coupled,
            assumptions=(SMALL_ANGLES,),
        ),
        claim(
            key="sec4.fig3-no-friction",
            quantity=r"\left(f_1,\ f_2\right)",
            paper=(sp.Integer(0), sp.Integer(0)),
            system="fig3",
            derive=fig3_friction,
            assumptions=(SMALL_ANGLES,),
        ),
        claim(
            key="sec4.fig3-geometry",
            quantity="R_1",
            paper=R2 / 2,
            system="pulled-hoop, pulled-cylinder",
            derive=geometry,
            assumptions=(LEVEL,),
        ),
        restates("sec4.fig3-no-friction", key="sec4.fig3-caption"),
        claim(
            key="sec4.fig3-equations",
            quantity=r"\left(\ddot\varphi_1,\ \ddot\varphi_2\right)",
            paper=(_F3 * 2 * R1 / _J31, -_F3 * sp.Rational(3, 2) * R2 / _J32),
            system="fig3",
            derive=fig3_eom,
            assumptions=(SMALL_ANGLES,),
        ),
        claim(
            key="sec4.fig3-spring-force",
            quantity=r"F_{1x}",
            paper=_F3,
            system="fig3",
            derive=fig3_spring_force,
            assumptions=(SMALL_ANGLES,),
        ),
        claim(
            key="sec4.fig3-forces",
            quantity=(
                r"\left(\frac{I'_1}{2R_1}\ddot\varphi_1,\ "
                r"\frac{I'_2}{\frac32 R_2}\ddot\varphi_2\right)"
            ),
            paper=(_F3, -_F3),
            system="fig3",
            derive=fig3_combination(
                lambda sym: [
                    (sym.bodies[0].J / (2 * R1), 0),
                    (0, sym.bodies[1].J / (sp.Rational(3, 2) * R2)),
                ],
                "I'_i phiddot_i over the lever arms 2R_1, 3R_2/2, with the engine's equations of "
                "motion (exact, and linearised)",
            ),
            assumptions=(SMALL_ANGLES,),
        ),
        claim(
            key="sec4.fig3-sum",
            quantity=(
                r"\left(\frac{I'_1}{2R_1}\ddot\varphi_1+\frac{I'_2}{\frac32 R_2}\ddot\varphi_2,\ "
                r"m_1R_1\ddot\varphi_1+m_2R_2\ddot\varphi_2\right)"
            ),
            paper=(sp.Integer(0), sp.Integer(0)),
            system="fig3",
            derive=fig3_combination(
                lambda sym: [
                    (sym.bodies[0].J / (2 * R1), sym.bodies[1].J / (sp.Rational(3, 2) * R2)),
                    (_J31 / (2 * R1), _J32 / (sp.Rational(3, 2) * R2)),
                ],
                "the two sums with the engine's equations of motion (exact, and linearised)",
            ),
            assumptions=(SMALL_ANGLES,),
        ),
        claim(
            key="sec4.fig3-cm-acceleration",
            quantity=r"m_1R_1\ddot\varphi_1+m_2R_2\ddot\varphi_2",
            paper=sp.Integer(0),
            system="fig3",
            derive=fig3_combination(
                lambda sym: [(sym.bodies[0].m * R1, sym.bodies[1].m * R2)],
                "sum m_i R_i phiddot_i with the engine's equations of motion (exact, and "
                "linearised)",
            ),
            assumptions=(SMALL_ANGLES,),
        ),
        claim(
            key="sec4.fig3-cm-acceleration-x",
            quantity=r"\left(x_1,\ x_2,\ m_1\ddot x_1+m_2\ddot x_2\right)",
            paper=(R1 * phi1, R2 * phi2, sp.Integer(0)),
            system="fig3",
            derive=fig3_x,
            assumptions=(SMALL_ANGLES,),
        ),
        restates("abstract.fig3", key="sec4.fig3-cm-at-rest"),
        restates("abstract.fig3", key="sec4.fig3-cm-stationary-again"),
        claim(
            key="sec4.fig3-equal-spring-forces",
            quantity=r"\lvert F_{2x}/F_{1x}\rvert",
            paper=sp.Integer(1),
            system="fig3",
            derive=fig3_equal_forces,
        ),
        claim(
            key="sec4.fig3-torques-differ",
            quantity=r"2R_1\neq\tfrac32 R_2",
            paper=TRUE,
            system="fig3",
            derive=fig3_torques_differ,
        ),
        claim(
            key="sec4.fig3-angular-momentum",
            quantity=r"\dot L",
            paper=_F3 * (2 * R1 - sp.Rational(3, 2) * R2),
            system="fig3",
            derive=fig3_angular_momentum,
        ),
    ]

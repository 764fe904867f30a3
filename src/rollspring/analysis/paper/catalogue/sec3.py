"""The claims of Sec. 3: the hoop and the cylinder joined at their centres (Fig. 2).

Rolling constraints, Steiner's theorem, the rotations about the contact lines, the conserved
angular momentum and phase opposition, the stationary point X-hat with its weights, the static
frictions in the ratio 3/2, and the variants with two hoops and two cylinders. Their words are in
``claims.toml``.
"""

from __future__ import annotations

import sympy as sp

from rollspring.analysis.paper.assumptions import FRICTION_AMOUNTS, RELEASED, SPRING_MAGNITUDES
from rollspring.analysis.paper.catalogue.common import J1, J2, TRUE
from rollspring.analysis.paper.catalogue.entry import Entry, claim, restates
from rollspring.analysis.paper.recipes.sec3 import (
    contact_axis,
    fig2_constraints,
    fig2_dof,
    fig2_eom,
    fig2_horizontal,
    fig2_spring_force,
    fig2_sum,
    friction_in_mode,
    friction_ratio,
    momentum,
    phase_opposition,
    same_spring_forces,
    stationary,
    stationary_point,
    steiner,
    w_relation,
)
from rollspring.analysis.paper.symbols import R, k, m1, m2, phi1, phi2

_F2 = k * (R * phi2 - R * phi1)  # the spring force of Fig. 2 (Sec. 3)


def claims() -> list[Entry]:
    """The claims of Sec. 3, in the paper's order."""
    return [
        claim(
            key="sec3.fig2-horizontal",
            quantity=r"\left(F_{1y},\ F_{2y}\right)",
            paper=(sp.Integer(0), sp.Integer(0)),
            system="fig2",
            derive=fig2_horizontal,
        ),
        claim(
            key="sec3.fig2-dof",
            quantity="n",
            paper=sp.Integer(2),
            system="fig2",
            derive=fig2_dof,
        ),
        claim(
            key="sec3.fig2-constraints",
            quantity=r"\left(x_1,\ x_2\right)",
            paper=(R * phi1, R * phi2),
            system="fig2",
            derive=fig2_constraints,
        ),
        claim(
            key="sec3.contact-axis",
            quantity=r"\left(I'_1\ddot\varphi_1-RF_{1x},\ I'_2\ddot\varphi_2-RF_{2x}\right)",
            paper=(sp.Integer(0), sp.Integer(0)),
            system="fig2",
            derive=contact_axis,
        ),
        claim(
            key="sec3.fig2-rotation",
            quantity=r"\left(\ddot\varphi_1,\ \ddot\varphi_2\right)",
            paper=(_F2 * R / J1, -_F2 * R / J2),
            system="fig2",
            derive=fig2_eom,
        ),
        claim(
            key="sec3.fig2-spring-force",
            quantity=r"\left(F_{1x},\ \lvert F_{2x}\rvert\right)",
            paper=(_F2, sp.Abs(_F2)),
            system="fig2",
            derive=fig2_spring_force,
        ),
        claim(
            key="sec3.steiner",
            quantity=r"\left(I'_1,\ I'_1,\ I'_2,\ I'_2\right)",
            paper=(m1 * R**2 + m1 * R**2, J1, m2 * R**2 / 2 + m2 * R**2, J2),
            system="fig2",
            derive=steiner,
        ),
        restates("sec3.fig2-rotation", key="sec3.fig2-equations"),
        claim(
            key="sec3.fig2-sum",
            quantity=r"I'_1\ddot\varphi_1+I'_2\ddot\varphi_2",
            paper=sp.Integer(0),
            system="fig2",
            derive=fig2_sum,
        ),
        claim(
            key="sec3.angular-momentum",
            quantity=r"I'_1\dot\varphi_1+I'_2\dot\varphi_2",
            paper=sp.Integer(0),
            system="fig2",
            derive=momentum,
            assumptions=(RELEASED,),
        ),
        claim(
            key="sec3.phase-opposition",
            quantity=r"\operatorname{sign}\left(\varphi_2/\varphi_1\right)",
            paper=sp.Integer(-1),
            system="fig2",
            derive=phase_opposition,
        ),
        claim(
            key="sec3.w-relation",
            quantity=(
                r"\left(2m_1R\dot\varphi_1+\tfrac32 m_2R\dot\varphi_2,\ "
                r"2m_1\dot x_1+\tfrac32 m_2\dot x_2\right)"
            ),
            paper=(sp.Integer(0), sp.Integer(0)),
            system="fig2",
            derive=w_relation,
            assumptions=(RELEASED,),
        ),
        restates("abstract.cm-moves", key="sec3.cm-moves"),
        claim(
            key="sec3.stationary-point",
            quantity=r"\dot{\hat X}",
            paper=sp.Integer(0),
            system="fig2",
            derive=stationary_point,
            assumptions=(RELEASED,),
        ),
        claim(
            key="sec3.same-spring-forces",
            quantity=r"\left(F_{2x}/F_{1x},\ Q_2/Q_1\right)",
            paper=(sp.Integer(1), sp.Integer(1)),
            system="fig2",
            derive=same_spring_forces,
            assumptions=(SPRING_MAGNITUDES,),
        ),
        claim(
            key="sec3.friction-ratio",
            quantity=r"f_1/f_2",
            paper=sp.Rational(3, 2),
            system="fig2",
            derive=friction_ratio,
            assumptions=(FRICTION_AMOUNTS,),
        ),
        claim(
            key="sec3.two-hoops",
            quantity=r"\left(w_1,\ w_2\right)",
            paper=(m1 / (m1 + m2), m2 / (m1 + m2)),
            system="two-hoops",
            derive=stationary("two-hoops"),
        ),
        claim(
            key="sec3.two-cylinders",
            quantity=r"\left(w_1,\ w_2\right)",
            paper=(m1 / (m1 + m2), m2 / (m1 + m2)),
            system="two-cylinders",
            derive=stationary("two-cylinders"),
        ),
        restates("abstract.fig3", key="sec3.steady-cm"),
        claim(
            key="sec3.fig2-caption",
            quantity=r"f\neq 0",
            paper=TRUE,
            system="fig2",
            derive=friction_in_mode,
        ),
    ]

"""The claims of the abstract, Sec. 1 and Sec. 2 (two point masses, Fig. 1).

The abstract's four sentences (in a normal mode the centre of mass moves, because of the static
friction, which vanishes for equal moments of inertia; the spring at the right heights keeps it at
rest; four methods give one equation of motion), the centre-of-mass theorem of Sec. 1, and Sec. 2's
equations, potential and forces of two masses joined by a spring. Their words are in
``claims.toml``.
"""

from __future__ import annotations

import sympy as sp

from rollspring.analysis.paper.assumptions import (
    FORCE_AMOUNTS,
    RELEASED,
    RELEASED_FIG1,
    SMALL_ANGLES,
)
from rollspring.analysis.paper.catalogue.common import METHODS, TRUE
from rollspring.analysis.paper.catalogue.entry import Entry, claim, restates
from rollspring.analysis.paper.recipes.intro import (
    cm_theorem,
    cm_velocity,
    fig1_end_forces,
    fig1_eom,
    fig1_forces_from_u,
    fig1_momentum_sum,
    fig1_no_external,
    fig1_potential,
    fig1_vertical,
    friction_cause,
    methods_agree,
    same_inertia,
)
from rollspring.analysis.paper.recipes.sec3 import cm_moves
from rollspring.analysis.paper.symbols import k, x1, x2


def claims() -> list[Entry]:
    """The claims of Abstract, Sec. 1, Sec. 2, in the paper's order."""
    return [
        claim(
            key="abstract.cm-moves",
            quantity=r"\dot X\neq 0",
            paper=TRUE,
            system="fig2",
            derive=cm_moves("fig2"),
        ),
        claim(
            key="abstract.friction-cause",
            quantity=r"\left((m_1+m_2)\ddot X-(f_1+f_2),\ f_1+f_2\neq 0\right)",
            paper=(sp.Integer(0), TRUE),
            system="fig2",
            derive=friction_cause,
        ),
        claim(
            key="abstract.same-inertia",
            quantity=r"f_1+f_2",
            paper=sp.Integer(0),
            system="fig2, two-hoops, two-cylinders",
            derive=same_inertia,
        ),
        claim(
            key="abstract.fig3",
            quantity=r"\dot X",
            paper=sp.Integer(0),
            system="fig3",
            derive=cm_velocity(
                "fig3",
                "the zero mode of the engine's K gives sum m_i xdot_i = P_0 (M14)",
                small=True,
            ),
            assumptions=(RELEASED, SMALL_ANGLES),
        ),
        claim(
            key="abstract.methods",
            quantity=r"\left(\Omega^2,\ \Omega^2,\ \Omega^2,\ \Omega^2\right)",
            paper=METHODS,
            system="fig2",
            derive=methods_agree,
        ),
        claim(
            key="sec1.cm-theorem",
            quantity=r"\ddot X",
            paper=sp.Integer(0),
            system="fig1",
            derive=cm_theorem,
        ),
        claim(
            key="sec2.fig1-caption",
            quantity=r"\left(\sum f_i,\ \sum (N_i-m_ig)\right)",
            paper=(sp.Integer(0), sp.Integer(0)),
            system="fig1",
            derive=fig1_no_external,
        ),
        claim(
            key="sec2.fig1-cm-at-rest-text",
            quantity=r"\dot X",
            paper=sp.Integer(0),
            system="fig1",
            derive=cm_velocity(
                "fig1", "the zero mode of K gives sum m_i xdot_i = P_0 (M14); X-hat is the CM"
            ),
            assumptions=(RELEASED_FIG1,),
        ),
        claim(
            key="sec2.fig1-equal-forces",
            quantity=r"F_2/F_1",
            paper=sp.Integer(1),
            system="fig1",
            derive=fig1_end_forces,
            assumptions=(FORCE_AMOUNTS,),
        ),
        claim(
            key="sec2.fig1-equations",
            quantity=r"\left(m_1\ddot x_1,\ m_2\ddot x_2\right)",
            paper=(k * (x2 - x1), -k * (x2 - x1)),
            system="fig1",
            derive=fig1_eom,
        ),
        claim(
            key="sec2.fig1-potential",
            quantity="U",
            paper=k / 2 * (x2 - x1) ** 2,
            system="fig1",
            derive=fig1_potential,
        ),
        claim(
            key="sec2.fig1-forces-from-u",
            quantity=r"\left(F_1,\ F_2\right)",
            paper=(-sp.diff(k / 2 * (x2 - x1) ** 2, x1), -sp.diff(k / 2 * (x2 - x1) ** 2, x2)),
            system="fig1",
            derive=fig1_forces_from_u,
        ),
        claim(
            key="sec2.fig1-momentum-sum",
            quantity=r"\left(m_1\ddot x_1+m_2\ddot x_2,\ (m_1+m_2)\ddot X\right)",
            paper=(sp.Integer(0), sp.Integer(0)),
            system="fig1",
            derive=fig1_momentum_sum,
        ),
        restates("sec2.fig1-cm-at-rest-text", key="sec2.fig1-cm-at-rest"),
        claim(
            key="sec2.fig1-vertical",
            quantity=r"\left(N_1-m_1g,\ N_2-m_2g\right)",
            paper=(sp.Integer(0), sp.Integer(0)),
            system="fig1",
            derive=fig1_vertical,
        ),
    ]

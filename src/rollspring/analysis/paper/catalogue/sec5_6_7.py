"""The claims of Sec. 5.6 (Hamilton's equations) and Sec. 7 (the conclusion).

The Hamiltonian in canonical coordinates q_i = sqrt(J_i/m_i) phi_i, its equations and the factor
2/sqrt(3); then the conclusion, which restates the abstract's claims (``restates(...)``). Their
words are in ``claims.toml``.
"""

from __future__ import annotations

import sympy as sp

from rollspring.analysis.paper.assumptions import ORIGIN, RELEASED
from rollspring.analysis.paper.catalogue.common import hoop_cylinder_hamiltonian
from rollspring.analysis.paper.catalogue.entry import Entry, claim, restates
from rollspring.analysis.paper.notation import half, p1, p2, pd1, q1, q2
from rollspring.analysis.paper.recipes.sec5_3_5 import lagrangian
from rollspring.analysis.paper.recipes.sec5_6_7 import (
    canonical,
    factor_2_sqrt3,
    hamilton_equations,
    hamilton_final,
    hamilton_to_ep,
    hamiltonian,
    interchangeable,
    q_ratio,
    qdot,
)
from rollspring.analysis.paper.symbols import R, k, m1, m2, phi1, phi2, phid1, phid2, x1, x2


def claims() -> list[Entry]:
    """The claims of Sec. 5.6, Sec. 7, in the paper's order."""
    return [
        claim(
            key="sec5.6.lagrangian-hamilton",
            quantity=r"\mathcal{L}",
            paper=m1 * R**2 * phid1**2
            + sp.Rational(3, 4) * m2 * R**2 * phid2**2
            - k / 2 * (R * phi1 + R * phi2) ** 2,
            system="fig2",
            derive=lagrangian,
        ),
        claim(
            key="sec5.6.hamiltonian",
            quantity=r"\mathcal{H}",
            paper=hoop_cylinder_hamiltonian(
                q1, q2, p1, p2, 1 / sp.sqrt(2), sp.sqrt(2) / sp.sqrt(3)
            ),
            system="fig2",
            derive=hamiltonian(),
        ),
        claim(
            key="sec5.6.canonical-coordinates",
            quantity=r"\left(q_1,\ q_2\right)",
            paper=(sp.sqrt(2) * R * phi1, sp.sqrt(sp.Rational(3, 2)) * R * phi2),
            system="fig2",
            derive=canonical,
        ),
        claim(
            key="sec5.6.hamilton-equations",
            quantity=r"\left(-\dot p_1,\ -\dot p_2\right)",
            paper=(
                sp.expand(k * (q1 / sp.sqrt(2) + sp.sqrt(2) * q2 / sp.sqrt(3)) / sp.sqrt(2)),
                sp.expand(
                    k * (q1 / sp.sqrt(2) + sp.sqrt(2) * q2 / sp.sqrt(3)) * sp.sqrt(2) / sp.sqrt(3)
                ),
            ),
            system="fig2",
            derive=hamilton_equations,
        ),
        claim(
            key="sec5.6.factor-two-over-root-three",
            quantity=r"\text{ratio of the right-hand sides}",
            paper=2 / sp.sqrt(3),
            system="none",
            derive=factor_2_sqrt3,
        ),
        claim(
            key="sec5.6.canonical-ratio",
            quantity=r"\left(\dot p_2,\ q_2\right)",
            paper=(2 / sp.sqrt(3) * pd1, m1 / m2 * 2 / sp.sqrt(3) * q1),
            system="fig2",
            derive=q_ratio,
            assumptions=(RELEASED, ORIGIN),
        ),
        claim(
            key="sec5.6.hamilton-motion",
            quantity=r"-\dot p_1",
            paper=sp.expand(k * (q1 / 2 + 2 * m1 / (3 * m2) * q1)),
            system="fig2",
            derive=hamilton_final,
        ),
        claim(
            key="sec5.6.hamilton-is-ep",
            quantity=r"\left(\dot q_1,\ \Omega^2\right)",
            paper=(p1 / m1, k / m1 * (half + 2 * m1 / (3 * m2))),
            system="fig2",
            derive=hamilton_to_ep,
        ),
        claim(
            key="sec5.6.qdot",
            quantity=r"\left(\dot q_1,\ \dot q_2\right)",
            paper=(p1 / m1, p2 / m2),
            system="fig2",
            derive=qdot,
        ),
        claim(
            key="sec5.6.point-masses-canonical",
            quantity=r"\left(q_1,\ q_2\right)",
            paper=(x1, x2),
            system="fig1",
            derive=interchangeable,
        ),
        restates("abstract.cm-moves", key="sec7.cm-moves"),
        restates("abstract.friction-cause", key="sec7.friction-cause"),
        restates("abstract.same-inertia", key="sec7.same-inertia"),
        restates("abstract.fig3", key="sec7.fig3"),
        restates("abstract.methods", key="sec7.methods"),
        restates("sec5.5.frequencies-detect-errors", key="sec7.check"),
    ]

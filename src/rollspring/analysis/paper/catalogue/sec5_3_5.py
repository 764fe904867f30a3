"""The claims of Sec. 5.3 (Euler-Lagrange), 5.4 (natural frequencies) and 5.5.

The Lagrangian (l), the spring cut at X-hat into two parts (k1, k2 and their sum rule), eqs. (ga),
(de), (ep), (pe); the sum rule of the natural frequencies and its "consequently"; and what the
frequencies are for (Sec. 5.5). Their words are in ``claims.toml``.
"""

from __future__ import annotations

import sympy as sp

from rollspring.analysis.paper.assumptions import ORIGIN, RELEASED
from rollspring.analysis.paper.catalogue.common import J1, J2, TRUE, k1_paper
from rollspring.analysis.paper.catalogue.entry import Entry, claim, restates
from rollspring.analysis.paper.notation import ell_total
from rollspring.analysis.paper.recipes.sec5_1_2 import phi_relation
from rollspring.analysis.paper.recipes.sec5_3_5 import (
    app_a_phi_ratio,
    clamped_is_not_coupled,
    consequently,
    eom_flipped,
    ga,
    k_equal,
    k_equal_masses,
    k_inverse_sum,
    k_parts,
    k_series,
    lagrangian,
    mode_equation,
    normal_oscillation,
    parts_in_mode,
    quadratic_energy,
    shorter_stiffer,
    sum_rule_fig2,
    xhat_left,
    xhat_right,
)
from rollspring.analysis.paper.symbols import R, k, k1, k2, m1, m2, phi1, phi2, phid1, phid2, phidd1

_k2_paper = k * (3 * m2 + 4 * m1) / (4 * m1)


def claims() -> list[Entry]:
    """The claims of Sec. 5.3, Sec. 5.4, Sec. 5.5, in the paper's order."""
    return [
        claim(
            key="sec5.3.lagrangian",
            quantity=r"\mathcal{L}",
            paper=J1 * phid1**2 / 2 + J2 * phid2**2 / 2 - k / 2 * (R * phi1 + R * phi2) ** 2,
            system="fig2",
            derive=lagrangian,
        ),
        claim(
            key="sec5.3.spring-part-equations",
            quantity=r"\left(\ddot\phi_1,\ \ddot\phi_2\right)",
            paper=(-k1 * R**2 * phi1 / J1, -k2 * R**2 * phi2 / J2),
            system="fig2",
            derive=parts_in_mode,
        ),
        claim(
            key="sec5.3.spring-parts",
            quantity=r"\frac{1}{k_1}+\frac{1}{k_2}",
            paper=1 / k,
            system="fig2",
            derive=k_series,
        ),
        claim(
            key="sec5.3.lagrange-equations",
            quantity=r"\left(I'_1\ddot\phi_1,\ I'_2\ddot\phi_2\right)",
            paper=(-k * (R * phi1 + R * phi2) * R, -k * (R * phi1 + R * phi2) * R),
            system="fig2",
            derive=eom_flipped,
        ),
        claim(
            key="sec5.3.ga",
            quantity=r"\ddot\phi_2",
            paper=4 * m1 / (3 * m2) * phidd1,
            system="fig2",
            derive=ga,
        ),
        claim(
            key="sec5.3.de",
            quantity=r"\phi_2",
            paper=4 * m1 / (3 * m2) * phi1,
            system="fig2",
            derive=lambda b: phi_relation(b, flip=True),
            assumptions=(RELEASED, ORIGIN),
        ),
        claim(
            key="sec5.3.ep0",
            quantity=r"2m_1R^2\ddot\phi_1",
            paper=-k * (R * phi1 + R * 4 * m1 / (3 * m2) * phi1) * R,
            system="fig2",
            derive=mode_equation(0),
        ),
        restates("sec5.1.qq1", key="sec5.3.ep"),
        restates("sec5.1.qq1", key="sec5.3.ep-identical"),
        claim(
            key="sec5.3.pe",
            quantity=r"\tfrac32 m_2R^2\ddot\phi_2",
            paper=-k * (R * 3 * m2 / (4 * m1) * phi2 + R * phi2) * R,
            system="fig2",
            derive=mode_equation(1),
        ),
        claim(
            key="sec5.3.phi1-from-de",
            quantity=r"\phi_1/\phi_2",
            paper=3 * m2 / (4 * m1),
            system="fig2",
            derive=app_a_phi_ratio,
            assumptions=(RELEASED, ORIGIN),
        ),
        claim(
            key="sec5.3.k1-k2",
            quantity=r"\left(k_1,\ k_2\right)",
            paper=(k1_paper, _k2_paper),
            system="fig2",
            derive=k_parts,
        ),
        claim(
            key="sec5.3.part-satisfied",
            quantity=r"\frac{1}{k_1}+\frac{1}{k_2}",
            paper=1 / k1_paper + 1 / _k2_paper,
            system="fig2",
            derive=k_inverse_sum,
        ),
        claim(
            key="sec5.3.k-equal",
            quantity=r"m_1/m_2\ \text{from}\ k_1=k_2,\ A_1=A_2",
            paper=(sp.Rational(3, 4), sp.Rational(3, 4)),
            system="fig2",
            derive=k_equal,
        ),
        claim(
            key="sec5.3.k-equal-masses",
            quantity=r"\left(k_1,\ k_2\right)",
            paper=(7 * k / 3, 7 * k / 4),
            system="fig2",
            derive=k_equal_masses,
        ),
        claim(
            key="sec5.3.xhat-three-sevenths",
            quantity=r"\hat X",
            paper=sp.Rational(3, 7) * ell_total,
            system="fig2",
            derive=xhat_left,
        ),
        claim(
            key="sec5.3.right-part",
            quantity=r"l-\hat X",
            paper=sp.Rational(4, 7) * ell_total,
            system="fig2",
            derive=xhat_right,
        ),
        claim(
            key="sec5.3.shorter-stiffer",
            quantity=r"\left(k_1l_1/(kl),\ k_2l_2/(kl),\ k_1>k_2\right)",
            paper=(sp.Integer(1), sp.Integer(1), TRUE),
            system="fig2",
            derive=shorter_stiffer,
        ),
        claim(
            key="sec5.4.normal-oscillation",
            quantity=r"\text{one frequency, fixed phase}",
            paper=TRUE,
            system="fig2",
            derive=normal_oscillation,
        ),
        claim(
            key="sec5.4.sum-rule-consequently",
            quantity=r"\omega_n^2\ \text{of a system with normal oscillations}",
            paper=(
                (k1 + k2) / (2 * m1) + 2 * k2 / (3 * m2),
                (k1 + k2) / (2 * m1) + 2 * k2 / (3 * m2),
            ),
            system="fig4a",
            derive=consequently,
        ),
        claim(
            key="sec5.4.clamped-is-coupled",
            quantity=r"\Omega_i^2\in\{0,\ \Omega^2\}",
            paper=TRUE,
            system="fig2",
            derive=clamped_is_not_coupled,
        ),
        claim(
            key="sec5.4.quadratic-energy",
            quantity=r"\text{harmonic}",
            paper=TRUE,
            system="none",
            derive=quadratic_energy,
        ),
        claim(
            key="sec5.4.sum-rule",
            quantity=r"\Omega^2-\left(\Omega_1^2+\Omega_2^2\right)",
            paper=sp.Integer(0),
            system="fig2",
            derive=sum_rule_fig2,
        ),
        restates("sec5.4.sum-rule", key="sec5.5.frequencies-detect-errors"),
    ]

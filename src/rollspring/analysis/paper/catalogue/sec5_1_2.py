"""The claims of Sec. 5.1 (dynamic equations) and Sec. 5.2 (conservation of E and L).

Eqs. (QQ2), (QQ1), (QQQ1): the angle relation and Omega^2 from Newton's equations; then the
amplitudes, speeds, energies and Omega^2 again from the conservation of energy and angular
momentum, with isochronism and the centre of mass for equal masses. Their words are in
``claims.toml``.
"""

from __future__ import annotations

import sympy as sp

from rollspring.analysis.paper.assumptions import MAXIMAL, RELEASED
from rollspring.analysis.paper.catalogue.common import J1, J2, TRUE
from rollspring.analysis.paper.catalogue.entry import Entry, claim, restates
from rollspring.analysis.paper.notation import A, Omega, Phid1
from rollspring.analysis.paper.recipes.sec5_1_2 import (
    amplitude_sum,
    amplitudes,
    amplitudes_equal_masses,
    clamped_terms,
    cm_equal_masses,
    isochronism,
    isotonic,
    kinetic,
    mode_energy,
    nu,
    omega2,
    omega_chain,
    omega_from_sum,
    orbital_spin,
    phi_relation,
    qq2,
    relative_rates,
    speed_over_amplitude,
    speed_over_rate,
    speeds,
    substituted,
    undeformed_at_top_speed,
)
from rollspring.analysis.paper.symbols import R, k, m1, m2, phi1, phid1, phid2


def claims() -> list[Entry]:
    """The claims of Sec. 5, Sec. 5.2, in the paper's order."""
    return [
        claim(
            key="sec5.qq2",
            quantity=r"\ddot\varphi_1+\Omega^2\varphi_1",
            paper=sp.Integer(0),
            system="fig2",
            derive=qq2,
            assumptions=(RELEASED,),
        ),
        claim(
            key="sec5.1.phi-relation",
            quantity=r"\varphi_2",
            paper=-4 * m1 / (3 * m2) * phi1,
            system="fig2",
            derive=lambda b: phi_relation(b, flip=False),
            assumptions=(RELEASED,),
        ),
        claim(
            key="sec5.1.phi-substituted",
            quantity=r"2m_1R^2\ddot\varphi_1",
            paper=k * (-R * 4 * m1 / (3 * m2) * phi1 - R * phi1) * R,
            system="fig2",
            derive=substituted,
        ),
        claim(
            key="sec5.1.qq1",
            quantity=r"\Omega^2",
            paper=k / (2 * m1) * (1 + 4 * m1 / (3 * m2)),
            system="fig2",
            derive=omega2("fig2"),
        ),
        claim(
            key="sec5.1.omega2-fig2",
            quantity=r"\Omega^2",
            paper=k / (2 * m1) + 2 * k / (3 * m2),
            system="fig2",
            derive=omega2("fig2"),
        ),
        claim(
            key="sec5.1.omega2-terms",
            quantity=r"\left(K_{11}/J_1,\ K_{22}/J_2\right)",
            paper=(k / (2 * m1), 2 * k / (3 * m2)),
            system="fig2",
            derive=clamped_terms,
        ),
        claim(
            key="sec5.2.speeds-kinematics",
            quantity=r"\left(v_1/A_1,\ v_2/A_2\right)",
            paper=(Omega, Omega),
            system="fig2",
            derive=speed_over_amplitude,
        ),
        claim(
            key="sec5.2.amplitude-sum",
            quantity=r"A_1+A_2",
            paper=A,
            system="fig2",
            derive=amplitude_sum,
        ),
        claim(
            key="sec5.2.omega-from-sum",
            quantity=r"\left(v_1+v_2,\ (v_1+v_2)/A\right)",
            paper=(A * Omega, Omega),
            system="fig2",
            derive=omega_from_sum,
        ),
        claim(
            key="sec5.2.relative-coordinates",
            quantity=r"\left(\dot\varepsilon_1,\ \dot\varepsilon_2\right)",
            paper=(R * phid1, R * phid2),
            system="fig2",
            derive=relative_rates,
            assumptions=(RELEASED,),
        ),
        claim(
            key="sec5.2.energy",
            quantity=r"\tfrac12 I'_1\dot\Phi_1^2+\tfrac12 I'_2\dot\Phi_2^2",
            paper=k / 2 * A**2,
            system="fig2",
            derive=mode_energy,
        ),
        claim(
            key="sec5.2.nu",
            quantity=r"\dot\Phi_2",
            paper=4 * m1 / (3 * m2) * Phid1,
            system="fig2",
            derive=nu,
            assumptions=(MAXIMAL,),
        ),
        claim(
            key="sec5.2.undeformed-at-top-speed",
            quantity=r"\text{deformation at the largest speeds}",
            paper=sp.Integer(0),
            system="fig2",
            derive=undeformed_at_top_speed,
        ),
        claim(
            key="sec5.2.kinetic-rotational",
            quantity="T",
            paper=J1 * phid1**2 / 2 + J2 * phid2**2 / 2,
            system="fig2",
            derive=kinetic,
        ),
        claim(
            key="sec5.2.orbital-spin",
            quantity=r"\left(m_2R^2,\ I_2\right)",
            paper=(m2 * R**2, m2 * R**2 / 2),
            system="fig2",
            derive=orbital_spin,
        ),
        restates("sec5.2.nu", key="sec5.2.phidot-relation"),
        claim(
            key="sec5.2.speeds-from-rates",
            quantity=r"\left(v_1/\dot\Phi_1,\ v_2/\dot\Phi_2\right)",
            paper=(R, R),
            system="fig2",
            derive=speed_over_rate,
        ),
        claim(
            key="sec5.2.speeds",
            quantity=r"\left(v_1,\ v_2\right)",
            paper=(
                A * sp.sqrt(3 * k * m2 / (2 * m1 * (4 * m1 + 3 * m2))),
                A * sp.sqrt(8 * k * m1 / (3 * m2 * (4 * m1 + 3 * m2))),
            ),
            system="fig2",
            derive=speeds,
        ),
        claim(
            key="sec5.2.omega-from-speeds",
            quantity=r"\left(\Omega,\ \Omega,\ \Omega,\ \Omega\right)",
            paper=(
                (sp.sqrt(3 * m2 / (2 * m1)) + sp.sqrt(8 * m1 / (3 * m2)))
                * sp.sqrt(k)
                / sp.sqrt(4 * m1 + 3 * m2),
                (3 * m2 + 4 * m1)
                / sp.sqrt(2 * m1 * 3 * m2)
                * sp.sqrt(k)
                / sp.sqrt(4 * m1 + 3 * m2),
                sp.sqrt(k * (3 * m2 + 4 * m1) / (2 * m1 * 3 * m2)),
                sp.sqrt(k / (2 * m1) + 2 * k / (3 * m2)),
            ),
            system="fig2",
            derive=omega_chain,
        ),
        restates("sec5.1.omega2-fig2", key="sec5.2.omega-identical"),
        claim(
            key="sec5.2.isochronism",
            quantity=r"\left(\partial v_i/\partial A\neq 0,\ \partial\Omega/\partial A\right)",
            paper=(TRUE, sp.Integer(0)),
            system="fig2",
            derive=isochronism,
        ),
        claim(
            key="sec5.2.isochronism-unique",
            quantity=r"T\ \text{of a non-harmonic oscillator depends on its amplitude}",
            paper=TRUE,
            system="none",
            derive=isotonic,
        ),
        claim(
            key="sec5.2.amplitudes",
            quantity=r"\left(A_1,\ A_2\right)",
            paper=(A * 3 * m2 / (4 * m1 + 3 * m2), A * 4 * m1 / (4 * m1 + 3 * m2)),
            system="fig2",
            derive=amplitudes,
        ),
        claim(
            key="sec5.2.amplitudes-equal-masses",
            quantity=r"\left(A_1,\ A_2\right)",
            paper=(sp.Rational(3, 7) * A, sp.Rational(4, 7) * A),
            system="fig2",
            derive=amplitudes_equal_masses,
        ),
        claim(
            key="sec5.2.cm-not-stationary-equal-masses",
            quantity=r"\dot X\neq 0\ (m_1=m_2)",
            paper=TRUE,
            system="fig2",
            derive=cm_equal_masses,
        ),
    ]

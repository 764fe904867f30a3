"""The claims of App. A (static friction), App. B (frequencies) and App. C (the Hamiltonian).

App. A: each body's rotation and friction, the pulled body of Fig. 5 and where its friction
reverses; App. B: the two subsystems and their frequencies; App. C: the potential's coefficients
and the frequencies Omega_1 to Omega_4. Their words are in ``claims.toml``.
"""

from __future__ import annotations

import sympy as sp

from rollspring.analysis.paper.assumptions import ORIGIN_APP_A, RELEASED, SMALL_ANGLES
from rollspring.analysis.paper.catalogue.common import J1, J2, TRUE, k1_paper
from rollspring.analysis.paper.catalogue.entry import Entry, claim, restates
from rollspring.analysis.paper.notation import I_, f1, f2, fpull, p1, p2, q1, q2, q3, q4
from rollspring.analysis.paper.recipes.appendices import (
    app_a_friction,
    app_a_friction_torque,
    app_a_rotation,
    clamped,
    coefficients,
    fig5_cylinder,
    fig5_labels,
    fric_app_a,
    no_work,
    potential_fig3,
    potential_q,
    pull_at_floor,
    pull_eliminated,
    pull_equations,
    pull_phiddot,
    reversal,
    second_subsystem_mass,
    subsystem,
    subsystem_energy,
    sum_rule_fig3,
)
from rollspring.analysis.paper.symbols import (
    F,
    R,
    k,
    k1,
    k2,
    m,
    m1,
    m2,
    phi1,
    phi2,
    phid1,
    phid2,
    y,
)

_Omega1, _Omega2 = sp.sqrt(k / (2 * m1)), sp.sqrt(2 * k / (3 * m2))
_Omega3, _Omega4 = sp.sqrt(2 * k / m1), sp.sqrt(3 * k / (2 * m2))


def claims() -> list[Entry]:
    """The claims of App. A, App. B, App. C, in the paper's order."""
    return [
        restates("sec5.2.relative-coordinates", key="app-a.relative-coordinates"),
        claim(
            key="app-a.hoop-rotation",
            quantity=r"\left(\ddot\phi_1,\ \ddot\phi_1\right)",
            paper=(-k1 * R**2 * phi1 / J1, -k1 / (2 * m1) * phi1),
            system="fig2",
            derive=app_a_rotation(0),
        ),
        claim(
            key="app-a.hoop-friction-torque",
            quantity=r"\left(\ddot\phi_1,\ \ddot\phi_1\right)",
            paper=(-f1 * R / (m1 * R**2), -f1 / (m1 * R)),
            system="fig2",
            derive=app_a_friction_torque(0),
        ),
        claim(
            key="app-a.cylinder-rotation",
            quantity=r"\left(\ddot\phi_2,\ \ddot\phi_2\right)",
            paper=(-k2 * R**2 * phi2 / J2, -2 * k2 / (3 * m2) * phi2),
            system="fig2",
            derive=app_a_rotation(1),
        ),
        claim(
            key="app-a.cylinder-friction-torque",
            quantity=r"\left(\ddot\phi_2,\ \ddot\phi_2\right)",
            paper=(-f2 * R / (m2 * R**2 / 2), -2 * f2 / (m2 * R)),
            system="fig2",
            derive=app_a_friction_torque(1),
        ),
        claim(
            key="app-a.friction-hoop",
            quantity=r"\left(f_1,\ f_1\right)",
            paper=(k1 / 2 * R * phi1, k1_paper / 2 * R * phi1),
            system="fig2",
            derive=app_a_friction(0),
        ),
        claim(
            key="app-a.friction-cylinder-k2",
            quantity=r"f_2",
            paper=k2 / 2 * R * phi2,
            system="fig2",
            derive=app_a_friction(1, middle=True),
        ),
        claim(
            key="app-a.friction-cylinder",
            quantity=r"f_2",
            paper=k * (3 * m2 + 4 * m1) / (12 * m1) * R * phi2,
            system="fig2",
            derive=app_a_friction(1),
        ),
        restates(
            "sec5.3.phi1-from-de",
            key="app-a.phi-ratio",
            assumptions=(RELEASED, ORIGIN_APP_A),
        ),
        restates("sec3.friction-ratio", key="app-a.friction-ratio"),
        claim(
            key="app-a.pull-equations",
            quantity=r"\left(\ddot\varphi,\ f\right)",
            paper=(F * y / (I_ + m * R**2), F - m * R * F * y / (I_ + m * R**2)),
            system="pulled",
            derive=pull_equations,
        ),
        claim(
            key="app-a.pull-phiddot",
            quantity=r"\left(a/\ddot\varphi,\ \ddot\varphi,\ \ddot\varphi\right)",
            paper=(R, F / (m * R) - fpull / (m * R), F * y / (I_ + m * R**2)),
            system="pulled",
            derive=pull_phiddot,
        ),
        claim(
            key="app-a.pull-eliminated",
            quantity=r"\text{left}-\text{right}",
            paper=F / (m * R) - fpull / (m * R) - F * y / (I_ + m * R**2),
            system="pulled",
            derive=pull_eliminated,
        ),
        claim(
            key="app-a.fric",
            quantity="f(y)",
            paper=F - F * m * R / (I_ + m * R**2) * y,
            system="pulled",
            derive=fric_app_a,
        ),
        claim(
            key="app-a.fig5-labels",
            quantity=r"\left(f_1(y),\ f_2(y)\right)",
            paper=(F * (1 - 2 * y / (3 * R)), F * (1 - y / (2 * R))),
            system="pulled-hoop, pulled-cylinder",
            derive=fig5_labels,
        ),
        claim(
            key="app-a.friction-reversal",
            quantity=(
                r"\left(y\ \text{where}\ f_{\mathrm{cyl}}=0,\ "
                r"\operatorname{sign}f_{\mathrm{cyl}}(2R)/F,\ f_{\mathrm{hoop}}\geq 0\right)"
            ),
            paper=(sp.Rational(3, 2) * R, sp.Integer(-1), TRUE),
            system="pulled-hoop, pulled-cylinder",
            derive=reversal,
        ),
        claim(
            key="app-a.pull-at-floor",
            quantity=r"\left(f,\ a\right)",
            paper=(F, sp.Integer(0)),
            system="pulled",
            derive=pull_at_floor,
        ),
        claim(
            key="app-a.friction-no-work",
            quantity=r"v_{\mathrm{contact}}",
            paper=sp.Integer(0),
            system="pulled",
            derive=no_work,
        ),
        claim(
            key="app-a.fig5-cylinder",
            quantity=r"f(2R)",
            paper=-F / 3,
            system="pulled-cylinder",
            derive=fig5_cylinder,
        ),
        claim(
            key="app-b.energy-1",
            quantity=r"E_1",
            paper=J1 / 2 * phid1**2 + k / 2 * (R * phi1) ** 2,
            system="fig2",
            derive=subsystem_energy(0),
        ),
        claim(
            key="app-b.subsystem-1",
            quantity=r"\left(\alpha_1,\ \beta_1,\ \Omega_1,\ \Omega_1,\ \Omega_1\right)",
            paper=(
                J1,
                k * R**2,
                sp.sqrt(k * R**2 / J1),
                sp.sqrt(k * R**2 / (2 * m1 * R**2)),
                _Omega1,
            ),
            system="fig2",
            derive=subsystem(0),
        ),
        claim(
            key="app-b.mass-m",
            quantity=r"m_{\mathrm{cylinder}}",
            paper=m,
            system="fig2",
            derive=second_subsystem_mass,
        ),
        claim(
            key="app-b.energy-2",
            quantity=r"E_2",
            paper=J2 / 2 * phid2**2 + k / 2 * (R * phi2) ** 2,
            system="fig2",
            derive=subsystem_energy(1),
        ),
        claim(
            key="app-b.subsystem-2",
            quantity=r"\left(\alpha_2,\ \beta_2,\ \Omega_2,\ \Omega_2,\ \Omega_2\right)",
            paper=(
                J2,
                k * R**2,
                sp.sqrt(k * R**2 / J2),
                sp.sqrt(k * R**2 / (sp.Rational(3, 2) * m2 * R**2)),
                _Omega2,
            ),
            system="fig2",
            derive=subsystem(1),
        ),
        restates("sec5.4.sum-rule", key="app-b.sum-rule"),
        claim(
            key="app-b.omega2-fig3",
            quantity=r"\left(\Omega^2,\ \Omega^2-\Omega_3^2-\Omega_4^2\right)",
            paper=(2 * k / m1 + 3 * k / (2 * m2), sp.Integer(0)),
            system="fig3",
            derive=sum_rule_fig3,
        ),
        restates(
            "sec5.6.hamiltonian",
            key="app-c.hamiltonian",
            quantity=r"\mathcal{H}_f",
        ),
        claim(
            key="app-c.potential-coefficients",
            quantity=r"\left(\lvert c_1\rvert,\ \lvert c_2\rvert\right)",
            paper=(_Omega1 / sp.sqrt(k / m1), _Omega2 / sp.sqrt(k / m2)),
            system="fig2",
            derive=coefficients,
        ),
        claim(
            key="app-c.potential-fig2",
            quantity=r"U_f",
            paper=k / 2 * (_Omega1 / sp.sqrt(k / m1) * q1 + _Omega2 / sp.sqrt(k / m2) * q2) ** 2,
            system="fig2",
            derive=potential_q("fig2", (q1, q2), (p1, p2)),
        ),
        claim(
            key="app-c.omega1-omega2",
            quantity=r"\left(\Omega_1,\ \Omega_2\right)",
            paper=(_Omega1, _Omega2),
            system="fig2",
            derive=clamped("fig2", roots=True),
        ),
        claim(
            key="app-c.potential-fig3",
            quantity=r"U_{\bcancel{f}}",
            paper=k / 2 * (_Omega3 / sp.sqrt(k / m1) * q3 + _Omega4 / sp.sqrt(k / m2) * q4) ** 2,
            system="fig3",
            derive=potential_fig3,
            assumptions=(SMALL_ANGLES,),
        ),
        claim(
            key="app-c.omega3-omega4",
            quantity=r"\left(\Omega_3,\ \Omega_4\right)",
            paper=(_Omega3, _Omega4),
            system="fig3",
            derive=clamped("fig3", roots=True),
        ),
    ]

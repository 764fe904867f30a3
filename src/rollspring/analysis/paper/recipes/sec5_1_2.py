"""Recipes for Sec. 5.1 (dynamic equations) and Sec. 5.2 (conservation of E and L).

From the engine's closed-form Omega^2 and mode shape of Fig. 2: the angle relations, the
amplitudes and speeds in the mode, the largest kinetic energy, isochronism, and the isotonic
oscillator as the counter-example to "unique to harmonic oscillation".
"""

from __future__ import annotations

from collections.abc import Callable

import sympy as sp

from rollspring.analysis.paper.algebra import same, substitute, tidy
from rollspring.analysis.paper.bench import Bench
from rollspring.analysis.paper.notation import D0, P0, A, Omega, Phid1, beta0, omega0, t, xi, xid
from rollspring.analysis.paper.recipes.common import ORIENTATION, flip_first, from_rest, mode_ratio
from rollspring.analysis.paper.symbols import m1, m2, phi1, phi2
from rollspring.analysis.paper.types import Derived


def qq2(b: Bench) -> Derived:
    (w2,) = b.omega2("fig2")
    v0 = b.zero_mode("fig2")
    c = b.conserved("fig2")
    norm = sp.Add(*[ci * v0[i] for i, ci in enumerate(c)])
    drift = (P0 * t + D0) / norm  # the zero-mode coordinate: c . phi = P_0 t + D_0
    value = tidy(w2 * drift * v0[0])
    return from_rest(
        value,
        "phiddot_1 + Omega^2 phi_1 for the general motion: zero mode (P_0 t + D_0) v0 plus "
        "the oscillating mode",
        condition="the coordinate is measured from its equilibrium value (the paper's x₁, x₂ "
        "are the centres' positions, and the angles have no stated origin before Sec. 5.2)",
        value_if=substitute(value, {P0: 0, D0: 0}),
        why="otherwise q oscillates about its equilibrium value qₑ ≠ 0",
        correction=r"\ddot{q}+\Omega^2\left(q-q_e\right)=0,\ q_e\ \text{the equilibrium value of}"
        r"\ q",
    )


def _phi2_of_phi1(b: Bench) -> sp.Expr:
    """phi_2 from integrating the conserved c . phidot = P_0 twice: (P_0 t + D_0 - c_1 phi_1) /
    c_2."""
    c = b.conserved("fig2")
    return tidy((P0 * t + D0 - c[0] * phi1) / c[1])


def phi_relation(b: Bench) -> Derived:
    """Sec. 5.1: phi_2 in terms of phi_1 (the integration constant taken as zero, unstated)."""
    value = _phi2_of_phi1(b)
    return from_rest(
        value,
        "integrating the conserved c . phidot = P_0 (zero mode of K) twice",
        condition="the integration constant is zero: the angles measured from the equilibrium "
        "about X̂ (the paper takes X̂ as origin only from Sec. 5.2 on)",
        value_if=substitute(value, {P0: 0, D0: 0}),
        why="in general c · φ = P₀t + D₀ with c = v₀ᵀM = (I'₁, I'₂)",
        correction=r"2m_1\varphi_1+\frac{3}{2}m_2\varphi_2=\text{const}",
    )


def phi_relation_about_origin(b: Bench) -> Derived:
    """Sec. 5.3: phi_2 in terms of phi_1 with X-hat the origin (stated): both constants vanish."""
    value = _phi2_of_phi1(b)
    return Derived(
        value,
        "integrating the conserved c . phidot = P_0 (zero mode of K) twice",
        assumed=substitute(value, {P0: 0, D0: 0}),
        condition=ORIENTATION,
        paper_if=flip_first,
        why="in general c · φ = P₀t + D₀ with c = v₀ᵀM = (I'₁, I'₂)",
    )


def substituted(b: Bench) -> Derived:
    sym = b.sym("fig2")
    ratio = mode_ratio(b)
    rhs = sym.equations_of_motion()[0].rhs
    return Derived(
        tidy(rhs.subs(phi2, ratio * phi1)),
        "the engine's Q_1 of (w2) with the mode's phi_2 = (phi_2/phi_1) phi_1",
    )


def omega2(key: str) -> Callable[[Bench], Derived]:
    def derive(b: Bench) -> Derived:
        (w2,) = b.omega2(key)
        return Derived(w2, "the non-zero root of det(K - Omega^2 M) = 0 (engine's M, K)")

    return derive


def clamped_terms(b: Bench) -> Derived:
    sym = b.sym("fig2")
    return Derived(
        tuple(tidy(sym.stiffness_matrix[i, i] / body.J) for i, body in enumerate(sym.bodies)),
        "K_ii/J_i from the engine's M and K: the squared frequency of each body alone with the "
        "other held fixed, the paper's subsystems; these are partial (clamped) frequencies, not "
        "frequencies of the coupled system, whose only non-zero one is Omega",
    )


def speed_over_amplitude(b: Bench) -> Derived:
    (w2,) = b.omega2("fig2")
    return Derived(
        (sp.sqrt(w2), sp.sqrt(w2)),
        "in the mode every coordinate is a cos(Omega t): speed amplitude over displacement "
        "amplitude is Omega (engine's Omega^2)",
        paper_subs={Omega: sp.sqrt(w2)},
    )


def omega_from_sum(b: Bench) -> Derived:
    (w2,) = b.omega2("fig2")
    speeds = [sp.sqrt(w2) * amp for amp in b.amplitudes("fig2")]
    return Derived(
        (tidy(sp.Add(*speeds)), tidy(sp.Add(*speeds) / A)),
        "the sum of the derived largest speeds Omega A_i, and divided by A",
        paper_subs={Omega: sp.sqrt(w2)},
    )


def mode_energy(b: Bench) -> Derived:
    sym = b.sym("fig2")
    (w2,) = b.omega2("fig2")
    v = b.mode("fig2")
    deformation = sp.Abs(tidy(sum(bb * v[i] for i, bb in enumerate(b.lever("fig2")))))
    scale = A / deformation
    kinetic = tidy(w2 * scale**2 * (v.T * sym.mass_matrix * v)[0, 0] / 2)
    return Derived(
        kinetic,
        "largest kinetic energy sum J_i (Omega a v_i)^2 / 2 in the mode whose spring "
        "deformation is A",
    )


def nu(b: Bench) -> Derived:
    ratio = mode_ratio(b)
    return Derived(
        ratio * Phid1,
        "Phidot_2 in terms of Phidot_1 in the oscillating mode",
        assumed=sp.Abs(ratio) * Phid1,
        why="signed, the two angular velocities have opposite signs (as in (rel1), a sum)",
    )


def undeformed_at_top_speed(b: Bench) -> Derived:
    sym = b.sym("fig2")
    v = b.mode("fig2")
    (w2,) = b.omega2("fig2")
    phase = sp.Symbol("tau", real=True)  # Omega t; the mode: phi = v cos(tau)
    kinetic = w2 * (v.T * sym.mass_matrix * v)[0, 0] * sp.sin(phase) ** 2 / 2
    deformation = tidy(sum(bb * v[i] for i, bb in enumerate(b.lever("fig2")))) * sp.cos(phase)
    tops = [
        p_
        for p_ in sp.solve(sp.diff(kinetic, phase), phase)
        if sp.diff(kinetic, phase, 2).subs(phase, p_).is_negative
    ]
    at_tops = {tidy(deformation.subs(phase, p_)) for p_ in tops}
    return Derived(
        at_tops.pop() if len(at_tops) == 1 else tuple(at_tops),
        "the spring's deformation (b . v) cos(Omega t) at the phases where the kinetic energy of "
        "the engine's mode is largest (both speeds largest together)",
    )


def orbital_spin(b: Bench) -> Derived:
    body = b.sym("fig2").bodies[1]
    return Derived(
        (tidy(body.m * body.s**2), body.I),
        "the cylinder's J = m R^2 + I split into the centre's (orbital) and the spin part (M4)",
    )


def speed_over_rate(b: Bench) -> Derived:
    sym = b.sym("fig2")
    return Derived(
        tuple(body.s for body in sym.bodies),
        "centre speed over angular speed: s_i = R of the engine's rolling constraint (M2)",
    )


def speeds(b: Bench) -> Derived:
    (w2,) = b.omega2("fig2")
    return Derived(
        tuple(tidy(sp.sqrt(w2) * amp) for amp in b.amplitudes("fig2")),
        "v_i = Omega A_i: the mode's centre amplitudes times the derived Omega",
    )


def omega_chain(b: Bench) -> Derived:
    (w2,) = b.omega2("fig2")
    return Derived(
        (sp.sqrt(w2),) * 4,
        "square root of the non-zero root of det(K - Omega^2 M) = 0, for each form of the chain",
    )


def isochronism(b: Bench) -> Derived:
    (w2,) = b.omega2("fig2")
    speeds = [sp.sqrt(w2) * amp for amp in b.amplitudes("fig2")]
    depends = all(sp.diff(s_, A) != 0 for s_ in speeds)
    return Derived(
        (sp.true if depends else sp.false, sp.diff(sp.sqrt(w2), A)),
        "d/dA of the derived largest speeds Omega A_i and of Omega",
    )


def isotonic(b: Bench) -> Derived:
    """The isotonic oscillator V = omega^2 x^2/2 + beta/(2 x^2): u = x^2 obeys
    uddot = 4E - 4 omega^2 u, a harmonic motion at 2 omega for every energy E."""
    force = -sp.diff(omega0**2 * xi**2 / 2 + beta0 / (2 * xi**2), xi)
    xdd = force  # unit mass
    u_dd = 2 * xid**2 + 2 * xi * xdd  # d2(x^2)/dt2
    e_mech = xid**2 / 2 + omega0**2 * xi**2 / 2 + beta0 / (2 * xi**2)
    residual = sp.simplify(u_dd - (4 * e_mech - 4 * omega0**2 * xi**2))
    if residual != 0:
        raise RuntimeError("isotonic oscillator: x^2 is expected to oscillate harmonically")
    return Derived(
        sp.false,
        "the isotonic oscillator V = ω²x²/2 + β/(2x²) (SymPy): u = x² obeys ü = 4E − 4ω²u",
        why="isochronism is not unique to harmonic oscillation: the isotonic oscillator "
        "V = ω²x²/2 + β/(2x²) is not harmonic, yet x² oscillates harmonically at 2ω for every "
        "energy, so its period π/ω does not depend on the amplitude",
        correction=r"T=\frac{\pi}{\omega}\ \text{at every amplitude for}\ "
        r"V=\frac{1}{2}\omega^2x^2+\frac{\beta}{2x^2}",
    )


def amplitudes(b: Bench) -> Derived:
    return Derived(
        tuple(b.amplitudes("fig2")),
        "centre amplitudes R|v_i| of the mode scaled to a spring deformation A (deformation "
        "b . v, b the engine's lever arms)",
    )


def amplitude_sum(b: Bench) -> Derived:
    return Derived(tidy(sum(b.amplitudes("fig2"))), "sum of the derived centre amplitudes")


def amplitudes_equal_masses(b: Bench) -> Derived:
    return Derived(
        tuple(tidy(amp.subs(m2, m1)) for amp in b.amplitudes("fig2")),
        "the derived A_i with m_1 = m_2",
    )


def cm_equal_masses(b: Bench) -> Derived:
    sym = b.sym("fig2")
    v = b.mode("fig2")
    deformation = sp.Abs(tidy(sum(bb * v[i] for i, bb in enumerate(b.lever("fig2")))))
    cm = sp.Add(*[body.m * body.s * v[i] for i, body in enumerate(sym.bodies)]) / (m1 + m2)
    amplitude = tidy(sp.Abs(A * cm / deformation).subs(m2, m1))
    return Derived(
        sp.true if amplitude != 0 else sp.false,
        f"the centre of mass's amplitude in the mode with m_1 = m_2: {sp.sstr(amplitude)}",
    )


def kinetic(b: Bench) -> Derived:
    return Derived(b.sym("fig2").kinetic, "the engine's kinetic energy T (M5)")


def relative_rates(b: Bench) -> Derived:
    """The rates of epsilon_i = x_i - X-hat, with X-hat of eq. (c) (the engine's weights)."""
    sym = b.sym("fig2")
    w = b.weights("fig2")
    c = b.conserved("fig2")
    centre = [body.s * body.qd for body in sym.bodies]
    xhat_rate = sp.Add(*[w_ * v_ for w_, v_ in zip(w, centre, strict=True)])
    # the weights are those of the conserved c . phidot = P_0: X-hat moves at s P_0 / sum c
    scale = tidy(w[0] * sym.bodies[0].s / c[0])
    if not same(tidy(w[1] * sym.bodies[1].s / c[1]), scale):
        raise RuntimeError("fig2: X-hat's weights are expected to be the conserved combination's")
    value = tuple(tidy(v_ - scale * P0) for v_ in centre)
    if not same(
        xhat_rate.subs(sym.bodies[0].qd, (P0 - c[1] * sym.bodies[1].qd) / c[0]), scale * P0
    ):
        raise RuntimeError("fig2: X-hat is expected to move at s P_0 / sum c")
    return from_rest(
        value,
        "d/dt (x_i - X-hat) with the rolling constraint x_i = R phi_i (M2) and X-hat's velocity "
        "from the engine's conserved combination (M14)",
        why="X̂ moves uniformly at RP₀/(I'₁ + I'₂); it is the stationary origin only for a start "
        "from rest",
    )

"""Recipes for Sec. 5.3 (Euler-Lagrange), Sec. 5.4 (natural frequencies) and Sec. 5.5.

From the engine's Lagrangian, M and K: the spring's two parts cut at X-hat and their equations,
the clamped (partial) frequencies against the coupled one, the sum rule on Fig. 2 and on a system
where it fails (a wall spring), and a quadratic energy's oscillation.
"""

from __future__ import annotations

from collections.abc import Callable

import sympy as sp

from rollspring.analysis.paper.algebra import same, substitute, tidy
from rollspring.analysis.paper.bench import Bench
from rollspring.analysis.paper.notation import D0, P0, ell_total, t
from rollspring.analysis.paper.recipes.common import (
    ORIENTATION,
    clamped_sum,
    flip_first,
    flip_first_rate,
    mode_ratio,
    split,
)
from rollspring.analysis.paper.symbols import k1, k2, m1, m2, phi2, phidd1
from rollspring.analysis.paper.types import Derived


def lagrangian(b: Bench) -> Derived:
    value = sp.expand(b.sym("fig2").lagrangian)
    return Derived(
        value,
        "the engine's Lagrangian T - V (M5)",
        condition=ORIENTATION,
        paper_if=flip_first,
        correction=r"\mathcal{L}=\frac{1}{2}I'_1\dot{\phi_1}^2+\frac{1}{2}I'_2\dot{\phi_2}^2-"
        r"\frac{1}{2}k\left(\varepsilon_2-\varepsilon_1\right)^2,\ \varepsilon_i=R\phi_i",
    )


def parts_in_mode(b: Bench) -> Derived:
    """(Q1), (Q2): in the mode, body i moves as if tied to X-hat by its part of the spring."""
    (w2,) = b.omega2("fig2")
    sym = b.sym("fig2")
    return Derived(
        tuple(-w2 * body.q for body in sym.bodies),
        "phiddot_i = -Omega^2 phi_i in the engine's mode, against -k_i R^2 phi_i / J_i with k_i "
        "= k/w_j the stiffness of the spring's part between body i and X-hat",
        paper_subs=dict(zip((k1, k2), split(b), strict=True)),
    )


def k_series(b: Bench) -> Derived:
    first, second = split(b)
    return Derived(
        tidy(1 / first + 1 / second),
        "1/k_1 + 1/k_2 with the stiffnesses k_i = k/w_j of the spring's parts cut at X-hat",
    )


def eom_flipped(b: Bench) -> Derived:
    sym = b.sym("fig2")
    Q = tuple(eq.rhs for eq in sym.equations_of_motion())
    return Derived(
        Q,
        "J_i phiddot_i = Q_i from the engine's Lagrangian (M7)",
        condition=ORIENTATION,
        paper_if=flip_first_rate,
    )


def ga(b: Bench) -> Derived:
    acc = b.accelerations("fig2")
    ratio = tidy(acc[1] / acc[0])
    return Derived(
        ratio * phidd1,
        "phiddot_2 in terms of phiddot_1 from the engine's equations of motion",
        condition=ORIENTATION,
        paper_if=flip_first,
    )


def mode_equation(index: int) -> Callable[[Bench], Derived]:
    """J_i phiddot_i in the mode (phiddot = -Omega^2 phi), for (ep0) and (pe)."""

    def derive(b: Bench) -> Derived:
        (w2,) = b.omega2("fig2")
        body = b.sym("fig2").bodies[index]
        return Derived(
            tidy(-w2 * body.J * body.q),
            f"J_{index + 1} phiddot_{index + 1} = -Omega^2 J_{index + 1} phi_{index + 1} in the "
            "engine's mode (with the mode's ratio of the angles, in either orientation)",
        )

    return derive


def k_parts(b: Bench) -> Derived:
    return Derived(
        tuple(split(b)),
        "k_i = k/w_j: the spring cut at X-hat (the engine's weights w), each part's stiffness "
        "inversely proportional to its length",
    )


def k_inverse_sum(b: Bench) -> Derived:
    spring_k = b.sym("fig2").springs[0].k
    return Derived(1 / spring_k, "1/k of the whole spring")


def k_equal_masses(b: Bench) -> Derived:
    return Derived(
        tuple(tidy(v.subs(m2, m1)) for v in split(b)),
        "the spring parts' k_i = k/w_j with m_1 = m_2",
    )


def k_equal(b: Bench) -> Derived:
    first, second = split(b)
    (from_k,) = sp.solve(sp.Eq(first, second), m1)
    amp1, amp2 = b.amplitudes("fig2")
    (from_a,) = sp.solve(sp.Eq(amp1, amp2), m1)
    return Derived(
        (tidy(from_k / m2), tidy(from_a / m2)),
        "m_1/m_2 solving k_1 = k_2 and A_1 = A_2 with the spring parts' k_i and the derived A_i",
    )


def xhat_left(b: Bench) -> Derived:
    w = b.weights("fig2")
    # x_1 = 0, x_2 = l: X-hat = w_2 l, the length of the left part
    return Derived(tidy(w[1].subs(m2, m1) * ell_total), "X-hat = w_2 l with the engine's weights")


def xhat_right(b: Bench) -> Derived:
    w = b.weights("fig2")
    return Derived(
        tidy(ell_total - w[1].subs(m2, m1) * ell_total), "l - X-hat with the engine's weights"
    )


def shorter_stiffer(b: Bench) -> Derived:
    w = [tidy(w_.subs(m2, m1)) for w_ in b.weights("fig2")]
    lengths = [w[1] * ell_total, w[0] * ell_total]  # the left part, the right part
    parts = [tidy(v.subs(m2, m1)) for v in split(b)]
    spring_k = b.sym("fig2").springs[0].k
    return Derived(
        (
            tidy(parts[0] * lengths[0] / (spring_k * ell_total)),
            tidy(parts[1] * lengths[1] / (spring_k * ell_total)),
            sp.true if (parts[0] - parts[1]).is_positive else sp.false,
        ),
        "k_i l_i / (k l) for the spring's parts cut at X-hat (m_1 = m_2), and k_1 > k_2",
    )


def normal_oscillation(b: Bench) -> Derived:
    v = b.mode("fig2")
    ratio = mode_ratio(b)
    fixed = all(component != 0 for component in v) and ratio.is_real
    return Derived(
        sp.true if fixed else sp.false,
        f"the engine's mode: phi = v cos(Omega t) with v real, phi_2/phi_1 = {sp.sstr(ratio)}: "
        "one frequency and a fixed phase",
    )


def sum_rule_fig2(b: Bench) -> Derived:
    (w2,) = b.omega2("fig2")
    clamped = clamped_sum(b, "fig2")
    return Derived(
        tidy(w2 - clamped),
        "Omega^2 minus the sum of the clamped frequencies K_ii/J_ii (each body alone, the other "
        "held), all from the engine's M, K: equal because K has rank one (one spring, two bodies)",
    )


def frequency_check(b: Bench) -> Derived:
    """Sec. 5.5: the sum rule as a check of an equation of motion, and what it cannot see: the
    coupling's sign (K with the off-diagonal entries flipped, as Sec. 5.3's (al), (be) have it)
    leaves Omega^2 unchanged and turns the phase opposition into phase."""
    sym = b.sym("fig2")
    (w2,) = b.omega2("fig2")
    clamped = clamped_sum(b, "fig2")
    flipped = sym.stiffness_matrix.copy()
    flipped[0, 1], flipped[1, 0] = -flipped[0, 1], -flipped[1, 0]
    omega = sp.Symbol("Omega2", positive=True)
    roots = [r_ for r_ in sp.solve((flipped - omega * sym.mass_matrix).det(), omega) if r_ != 0]
    blind = len(roots) == 1 and tidy(roots[0] - w2) == 0
    return Derived(
        tidy(w2 - clamped),
        "Omega^2 minus the sum of the clamped frequencies K_ii/J_ii, from the engine's M, K; a "
        "necessary check only"
        + (
            ": the frequencies cannot see the coupling's sign — K with its off-diagonal entries "
            "flipped (Sec. 5.3's (al), (be), whose (de) puts the bodies in phase) has the same Ω², "
            "so the check passes equations the exact motion refutes (φ₂/φ₁ = −4m₁/(3m₂))"
            if blind
            else ""
        ),
    )


def consequently(b: Bench) -> Derived:
    """Sec. 5.4's "consequently": a system with normal oscillations (a wall spring on the hoop,
    joined to the cylinder) whose modes do not obey the sum rule."""
    sym = b.sym("fig4a")
    roots = b.omega2("fig4a")
    K = sym.stiffness_matrix
    clamped = sp.Add(*[K[i, i] / body.J for i, body in enumerate(sym.bodies)])
    trace_ok = same(sp.Add(*roots), clamped)
    return Derived(
        tuple(roots),
        "the roots of det(K - omega^2 M) = 0 for a hoop tied to a wall and joined to a cylinder "
        "(two normal oscillations), against the clamped sum K_11/J_1 + K_22/J_2",
        why="does not follow: a normal oscillation (one frequency, a fixed phase) does not make "
        "Ω² = Ω₁² + Ω₂²; a hoop tied to a wall and joined to the cylinder oscillates in two normal "
        "modes, neither with ω² = Ω₁² + Ω₂²"
        + ("; only their sum ω₁² + ω₂² equals Ω₁² + Ω₂²" if trace_ok else "")
        + ". For the paper's systems the equality holds because K has rank one (one spring, two "
        "bodies): Ω² = tr(M⁻¹K) = K₁₁/J₁ + K₂₂/J₂",
        correction=r"\Omega^2=\mathrm{tr}\left(M^{-1}K\right)=\Omega_1^2+\Omega_2^2\ \text{because}"
        r"\ K\ \text{has rank one (one spring, two bodies), not because the oscillation is normal}",
    )


def clamped_is_not_coupled(b: Bench) -> Derived:
    sym = b.sym("fig2")
    (w2,) = b.omega2("fig2")
    frequencies = [sp.Integer(0), w2]
    clamped = [tidy(sym.stiffness_matrix[i, i] / body.J) for i, body in enumerate(sym.bodies)]
    among = any(same(c_, f_) for c_ in clamped for f_ in frequencies)
    return Derived(
        sp.true if among else sp.false,
        "the coupled system's squared frequencies {0, Omega^2} (det(K - omega^2 M) = 0) against "
        "the clamped K_ii/J_i",
        why=f"the clamped frequencies Ω₁² = {sp.sstr(clamped[0])}, Ω₂² = {sp.sstr(clamped[1])} "
        "(one body held) are partial frequencies, not natural frequencies of the coupled system, "
        f"whose own are 0 and Ω² = {sp.sstr(w2)} = Ω₁² + Ω₂²",
        correction=r"\Omega_1,\ \Omega_2\ \text{are partial (clamped) frequencies; the coupled "
        r"system's are}\ 0\ \text{and}\ \Omega=\sqrt{\Omega_1^2+\Omega_2^2}",
    )


def quadratic_energy(b: Bench) -> Derived:
    """Sec. 5.4: E = alpha qdot^2/2 + beta q^2/2 conserved gives qddot = -(beta/alpha) q: a
    harmonic oscillation only when beta/alpha > 0 (for any real constants, not in general)."""

    def harmonic(**assumptions: bool) -> bool:
        alpha, beta = sp.symbols("alpha beta", **assumptions)
        q, qd, qdd = sp.symbols("q qdot qddot", real=True)
        energy_ = alpha * qd**2 / 2 + beta * q**2 / 2
        rate = sp.diff(energy_, qd) * qdd + sp.diff(energy_, q) * qd  # dE/dt
        (acc,) = sp.solve(sp.Eq(rate, 0), qdd)
        ratio = tidy(acc / q)
        return bool(ratio.free_symbols <= {alpha, beta} and ratio.is_negative)

    return Derived(
        sp.true if harmonic(real=True, nonzero=True) else sp.false,
        "dE/dt = 0 gives qddot = -(beta/alpha) q (SymPy): harmonic at Omega = sqrt(beta/alpha) "
        "when beta/alpha > 0; for beta/alpha < 0, q grows as exp(sqrt(-beta/alpha) t)",
        condition="β/α > 0 (the energy has a minimum at q = 0): a quadratic energy with β < 0, "
        "as an inverted pendulum's, has constant α and β and does not oscillate",
        value_if=sp.true if harmonic(positive=True) else sp.false,
        correction=r"\ddot q=-\frac{\beta}{\alpha}q\ \text{is a harmonic oscillation only for}"
        r"\ \beta/\alpha>0",
    )


def app_a_phi_ratio(b: Bench) -> Derived:
    c = b.conserved("fig2")
    general = tidy((P0 * t + D0 - c[1] * phi2) / c[0])  # phi_1 from c . phi = P_0 t + D_0
    value = tidy(general / phi2)
    return Derived(
        value,
        "phi_1/phi_2 from the conserved c . phi = P_0 t + D_0 (zero mode of K)",
        assumed=substitute(value, {P0: 0, D0: 0}),
        condition=ORIENTATION,
        paper_if=lambda e: -e,
    )

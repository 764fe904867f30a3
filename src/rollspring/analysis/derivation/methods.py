r"""The five derivations of the equations of motion, in the paper's order of ideas.

Each method builds a :class:`MethodResult`: a :class:`~.steps.Section` of steps (the
constraint relations, the moments of inertia about the contact lines by Steiner's theorem, the
method's own equations, the conserved quantities, the equation of motion of the whole system,
:math:`\Omega^2`) and its results in a common form, so that they can be compared
(:mod:`.crosscheck`): the linearised equations :math:`J_i\ddot\varphi_i = \dots` of every body
(in the angles), the exact ones where the method gives them, and the squared frequencies.

* ``newton``: torques of the spring forces about the contact lines (paper Sec. 2, 4.1; (M7));
* ``conservation``: energy and the conserved angular-momentum combination (Sec. 4.2); needs a
  single oscillating degree of freedom;
* ``lagrange``: Euler-Lagrange equations of :math:`L = T - V` (Sec. 4.3; (M5)), checked against
  ``sympy.physics.mechanics.LagrangesMethod``;
* ``natural-frequencies``: subsystem frequencies :math:`\Omega_i^2 = K_{ii}/J_i` and the sum
  rule (Sec. 4.4, App. B, C); needs two bodies with a zero mode (rank-1 K);
* ``hamilton``: canonical coordinates :math:`q_i = \sqrt{J_i/m_i}\,\varphi_i`,
  :math:`p_i = m_i\dot q_i` (Sec. 4.5; (M6)).
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field, replace
from typing import Any

import sympy as sp

from rollspring.analysis.derivation.frequencies import (
    OMEGA2,
    BudgetExceeded,
    Frequencies,
    normal_frequencies,
    time_budget,
)
from rollspring.analysis.derivation.steps import Section, Step, named
from rollspring.analysis.derivation.symbolic import SymbolicSystem

__all__ = ["METHODS", "MethodResult", "run_method"]

#: Method names, in the paper's order.
METHODS = ("newton", "conservation", "lagrange", "natural-frequencies", "hamilton")

TITLES = {
    "newton": "Dynamic equations (Newton, torques about the contact lines)",
    "conservation": "Conservation of energy and angular momentum",
    "lagrange": "Euler-Lagrange equations",
    "natural-frequencies": "Natural frequencies of the subsystems",
    "hamilton": "Hamilton's equations",
}


@dataclass
class MethodResult:
    r"""One method's derivation and its results.

    ``equations``: the linearised equations of motion :math:`J_i\ddot\varphi_i = \dots` of every
    body (in the angles; None where the method does not give them); ``nonlinear``: the exact
    ones (None where the method is linear only); ``system_equation``: the equation of motion of
    the whole system (:math:`\ddot\varphi_1 + \Omega^2\varphi_1 = 0`, or the matrix form);
    ``omega2``: the squared frequencies of the oscillating modes (closed forms; None entries
    where there is none); ``extras``: named intermediate results (tests, paper checks).
    """

    name: str
    title: str
    applies: bool
    reason: str
    section: Section
    equations: list[sp.Eq] | None = None
    nonlinear: list[sp.Eq] | None = None
    system_equation: Any = None
    omega2: list[sp.Expr | None] = field(default_factory=list)
    extras: dict[str, Any] = field(default_factory=dict)

    @property
    def steps(self) -> list[Step]:
        """The steps of the derivation."""
        return self.section.steps


# -- shared pieces ---------------------------------------------------------------------------------


def _x_symbol(sym: SymbolicSystem, i: int) -> sp.Symbol:
    body = sym.bodies[i]
    if not body.rolls:
        return body.q
    return sp.Symbol("x" + ("" if sym.n == 1 else f"_{body.label}"), real=True)


def _prime(sym: SymbolicSystem, i: int) -> sp.Symbol:
    return sp.Symbol("I'" + ("" if sym.n == 1 else f"_{sym.bodies[i].label}"))


def constraint_step(section: Section, sym: SymbolicSystem) -> None:
    """x_i = R_i phi_i for every rolling body (paper (g1), (g2))."""
    equations = [sp.Eq(_x_symbol(sym, i), b.s * b.q) for i, b in enumerate(sym.bodies) if b.rolls]
    if equations:
        origin = "the equilibrium" if sym.reference == "equilibrium" else "the initial placement"
        section.add(
            equations,
            f"Constraint relations of rolling without slipping: each centre "
            f"moves R per radian (x and the angle measured from {origin}).",
            "paper (g1), (g2); (M1)",
        )
    sliders = [b for b in sym.bodies if not b.rolls]
    if sliders:
        section.add(
            [sp.Eq(sp.Symbol(f"J_{b.label}"), b.m) for b in sliders],
            "Sliders on a frictionless floor: the coordinate is the displacement x and "
            "the mass matrix entry is m.",
            "(M4)",
        )


def steiner_step(section: Section, sym: SymbolicSystem) -> None:
    """I'_i = I_i + m_i R_i^2 = (1 + gamma_i) m_i R_i^2 (paper I'_1, I'_2)."""
    lines, eqs = [], []
    for i, b in enumerate(sym.bodies):
        if not b.rolls:
            continue
        mr2 = b.m * b.R**2
        eqs.append(sp.Eq(_prime(sym, i), b.J))
        lines.append(
            f"{sp.latex(_prime(sym, i))} &= {sp.latex(b.I)} + {sp.latex(mr2)} = {sp.latex(b.J)}"
        )
    if eqs:
        section.add(
            eqs,
            "Moments of inertia about the contact lines (the instantaneous axes "
            "z'), by Steiner's theorem with d = R.",
            "paper (I'1), (I'2); (M4)",
            latex=r"\begin{aligned}" + r" \\ ".join(lines) + r"\end{aligned}",
        )


def spring_steps(section: Section, sym: SymbolicSystem) -> None:
    """Each spring's exact length."""
    if not sym.springs:
        return
    eqs = []
    for s in sym.springs:
        name = sp.Symbol("l" + ("" if len(sym.springs) == 1 else f"_{s.index + 1}"))
        eqs.append(sp.Eq(name, s.length))
    section.add(
        eqs, "Spring lengths from the positions of their ends, exactly (no small angles).", "(M1)"
    )


def _is_linear(sym: SymbolicSystem) -> bool:
    """The exact equations are linear in the coordinates (e.g. centre springs, level)."""
    if "linear" not in sym._cache:
        exact = sym.generalized_forces
        linear = sym.reference_forces - sym.stiffness_matrix * sp.Matrix(sym.q)
        sym._cache["linear"] = all(sp.expand(exact[i] - linear[i]) == 0 for i in range(sym.n))
    result: bool = sym._cache["linear"]
    return result


def linear_equations(sym: SymbolicSystem) -> list[sp.Eq]:
    """J_i qdd_i = Q_i(0) - (K q)_i."""
    return sym.equations_of_motion(linear=True)


def _frequencies(sym: SymbolicSystem, budget: float | None) -> Frequencies:
    key = "frequencies"
    if key not in sym._cache:
        sym._cache[key] = normal_frequencies(sym, budget=budget)
    result: Frequencies = sym._cache[key]
    return result


def _whole_system(
    section: Section,
    sym: SymbolicSystem,
    *,
    coords: list[sp.Symbol],
    accels: list[sp.Symbol],
    velocities: list[sp.Symbol],
    masses: list[sp.Expr],
    K: sp.Matrix,
    v0: sp.Matrix | None,
    frequencies: Frequencies,
    in_angles: bool,
    labels: tuple[str, ...] = (),
) -> dict[str, Any]:
    r"""Conserved combination, elimination and :math:`\Omega^2` (paper (rel1), (QQ1), (QQQ1)).

    With a single zero mode :math:`v_0` (:math:`Kv_0 = 0`), adding the equations with weights
    :math:`v_{0i}` cancels the spring terms: :math:`\sum_i v_{0i}\mu_i\ddot y_i = 0`; two bodies
    then reduce to one equation.
    """
    n = len(coords)
    out: dict[str, Any] = {}
    refs = labels or (
        "paper (w2)+(w22)",
        "paper (rel1); (M14)",
        "paper (c); (M14)",
        "paper (QQ1)",
        "paper (QQQ1)",
        "paper (QQ1), first line",
    )
    if v0 is not None and frequencies.n_zero == 1:
        weighted = sp.Add(*[masses[i] * v0[i] * accels[i] for i in range(n)])
        section.add(
            sp.Eq(_content_free(weighted, accels), 0),
            "Adding the equations with the weights of the zero mode v0 (K v0 = 0), "
            "the spring terms cancel.",
            refs[0],
        )
        momentum = sp.Add(*[masses[i] * v0[i] * velocities[i] for i in range(n)])
        out["conserved"] = momentum
        section.add(
            sp.Eq(_content_free(momentum, velocities), 0),
            "Integrating over time: this combination of angular momenta about the "
            "contact lines (of linear momenta, for sliders) is conserved (zero for a "
            "start at rest relative to the stationary point).",
            refs[1],
        )
        if in_angles:
            weights = [sp.cancel(masses[i] * v0[i] / sym.bodies[i].s) for i in range(n)]
            common = _symbolic_gcd(weights)
            weights = [sp.cancel(w / common) for w in weights]
            out["weights"] = weights
            xs = [_x_symbol(sym, i) for i in range(n)]
            xhat = sp.Symbol("Xhat")
            per_mass = [sp.cancel(w / sym.bodies[i].m) for i, w in enumerate(weights)]
            is_cm = all(sp.simplify(r - per_mass[0]) == 0 for r in per_mass[1:])
            verdict = (
                "this point stays at rest; here it is the centre of mass (the weights are "
                "proportional to the masses)"
                if is_cm
                else "this point, not the centre of mass, stays at rest"
            )
            section.add(
                sp.Eq(
                    xhat,
                    sp.Add(*[w * x for w, x in zip(weights, xs, strict=True)]) / sp.Add(*weights),
                ),
                "With x_i = s_i q_i the combination is a weighted sum of centre "
                f"velocities: {verdict}.",
                refs[2],
            )
    if n == 2 and v0 is not None and frequencies.n_zero == 1 and v0[0] != 0 and v0[1] != 0:
        ratio = sp.cancel(-masses[0] * v0[0] / (masses[1] * v0[1]))
        out["ratio"] = ratio
        section.add(
            sp.Eq(coords[1], ratio * coords[0]),
            "Integrating again, with the origin at the stationary point.",
            "",
        )
        rhs = -(K[0, 0] * coords[0] + K[0, 1] * ratio * coords[0])
        section.add(
            sp.Eq(masses[0] * accels[0], sp.factor(rhs)),
            "Substituting into the first body's equation.",
            refs[5],
        )
        omega2 = sp.factor(sp.cancel((K[0, 0] + K[0, 1] * ratio) / masses[0]))
        out["system_equation"] = sp.Eq(accels[0] + omega2 * coords[0], 0)
        section.add(
            out["system_equation"],
            "The equation of motion of the whole system: a simple harmonic oscillation.",
            refs[3],
        )
        omega2 = _tidy(omega2)
        out["omega2"] = [omega2]
        section.add(sp.Eq(OMEGA2, omega2), "Comparing with q'' + Omega^2 q = 0.", refs[4])
        return out
    if n == 1:
        omega2 = _tidy(sp.cancel(K[0, 0] / masses[0]))
        out["system_equation"] = sp.Eq(accels[0] + omega2 * coords[0], 0)
        out["omega2"] = [omega2] if frequencies.n_zero == 0 else []
        section.add(
            out["system_equation"], "One body: its equation is that of the whole system.", ""
        )
        section.add(sp.Eq(OMEGA2, omega2), "Comparing with q'' + Omega^2 q = 0.", "")
        return out
    mass = sp.diag(*masses)
    qvec, avec = sp.Matrix(coords), sp.Matrix(accels)
    if n <= 8:
        out["system_equation"] = sp.Eq(mass * avec + K * qvec, sp.zeros(n, 1))
        section.add(
            sp.Eq(
                sp.MatMul(mass, avec, evaluate=False) + sp.MatMul(K, qvec, evaluate=False),
                sp.zeros(n, 1),
            ),
            "The equation of motion of the whole system in matrix form.",
            "(M12)",
            latex=rf"{sp.latex(mass)}{sp.latex(avec)} + {sp.latex(K)}{sp.latex(qvec)}"
            r" = 0",
        )
    else:
        out["system_equation"] = sp.Eq(mass * avec + K * qvec, sp.zeros(n, 1))
        section.add(
            sp.Eq(sp.Symbol("M") * sp.Symbol("qddot") + sp.Symbol("K") * sp.Symbol("q"), 0),
            f"The equation of motion of the whole system, M q'' + K q = 0 ({n} "
            "coupled equations; M and K above).",
            "(M12)",
            latex=r"M\ddot{q} + K q = 0",
        )
    if frequencies.characteristic is not None:
        section.add(
            sp.Eq(
                sp.factor(frequencies.characteristic) if n <= 4 else frequencies.characteristic, 0
            ),
            "Normal modes q = v cos(Omega t): det(K - Omega^2 M) = 0, the characteristic equation.",
            "(M12)",
        )
    else:
        section.add(
            sp.Eq(sp.Function("det")(sp.Symbol("K") - OMEGA2 * sp.Symbol("M")), 0),
            "Normal modes q = v cos(Omega t): det(K - Omega^2 M) = 0.",
            "(M12)",
        )
    closed = [w for w in frequencies.omega2 if w is not None]
    if frequencies.omega2:
        shown = [
            sp.Eq(
                sp.Symbol(f"Omega_{j + 1}^2"),
                w if w is not None else sp.Float(frequencies.numeric[j], 12),
            )
            for j, w in enumerate(frequencies.omega2)
        ]
        words = "Squared frequencies of the oscillating modes"
        words += (
            " (closed forms)."
            if len(closed) == len(frequencies.omega2)
            else " (closed forms where SymPy finds them, else the numbers)."
        )
        section.add(shown, words, "")
    if frequencies.n_zero:
        section.add(
            sp.Eq(sp.Symbol("Omega_0^2"), 0),
            f"{frequencies.n_zero} zero mode(s): a "
            "free, uniform motion (no restoring force along it).",
            "(M14)",
        )
    out["omega2"] = list(frequencies.omega2)
    return out


def _content_free(expr: sp.Expr, variables: list[sp.Symbol]) -> sp.Expr:
    """expr with its variable-free factor dropped (an expression equated to zero)."""
    expr = sp.factor_terms(sp.expand(expr))
    if isinstance(expr, sp.Mul):
        kept = [f for f in expr.args if f.has(*variables)]
        return sp.Mul(*kept) if kept else expr
    return expr


def _symbolic_gcd(values: list[sp.Expr]) -> sp.Expr:
    """The symbolic (non-numeric) common factor of expressions."""
    nonzero = [v for v in values if v != 0]
    if not nonzero:
        return sp.Integer(1)
    common = nonzero[0]
    for v in nonzero[1:]:
        common = sp.gcd(common, v)
    _, rest = sp.factor_terms(common).as_coeff_Mul()
    return rest if rest != 0 else sp.Integer(1)


def _tidy(expr: sp.Expr) -> sp.Expr:
    """A short form of a parameter expression (Omega^2 and the like)."""
    expr = sp.sympify(expr)
    candidates = [
        expr,
        sp.factor(expr),
        sp.apart(sp.cancel(expr), _first_symbol(expr)) if _first_symbol(expr) is not None else expr,
        sp.expand(expr),
    ]
    return min(candidates, key=lambda e: (sp.count_ops(e), len(str(e))))


def _first_symbol(expr: sp.Expr) -> sp.Symbol | None:
    masses = sorted((s for s in expr.free_symbols if s.name.startswith("m")), key=str)
    return masses[0] if masses else None


def _zero_mode_2(K: sp.Matrix) -> sp.Matrix | None:
    """The null vector of a rank-1 symmetric 2x2 matrix, normalised to v/(v_1 v_2)."""
    if K[1, 1] != 0:
        v = sp.Matrix([K[1, 1], -K[0, 1]])
    elif K[0, 0] != 0:
        v = sp.Matrix([-K[0, 1], K[0, 0]])
    else:
        return None
    if v[0] != 0 and v[1] != 0:
        v = sp.Matrix([sp.cancel(1 / v[1]), sp.cancel(1 / v[0])])
    return v


def _v0(sym: SymbolicSystem) -> sp.Matrix | None:
    if sym.zero_mode_count() != 1:
        return None
    if sym.n == 2:
        return _zero_mode_2(sym.stiffness_matrix)
    return sym.zero_mode()


def _applicable_linear(sym: SymbolicSystem) -> str:
    """Why a linearised derivation is not possible ('' when it is)."""
    if sym.reference != "equilibrium":
        return (
            "the system has no equilibrium near its initial placement, so there are no "
            "oscillations to linearise about"
        )
    n_zero = sym.zero_mode_count()
    if sym._cache.get("n_unstable"):
        return "the equilibrium is unstable (a negative stiffness): there is no oscillation"
    if n_zero == sym.n:
        return "nothing restores the equilibrium (every mode is a free motion): no oscillation"
    return ""


# -- the methods -----------------------------------------------------------------------------------


def newton(sym: SymbolicSystem, budget: float | None) -> MethodResult:
    """Torques of the applied forces about the contact lines (instantaneous axes)."""
    section = Section(TITLES["newton"])
    constraint_step(section, sym)
    steiner_step(section, sym)
    if sym.springs:
        tensions = []
        for s in sym.springs:
            name = sp.Symbol("F" if len(sym.springs) == 1 else f"F_{s.index + 1}")
            tensions.append(sp.Eq(name, s.k * sp.factor_terms(s.length - s.L)))
        section.add(
            tensions,
            "Spring forces: T = k(l - L), pulling both ends towards each "
            "other along the spring when stretched.",
            "paper F = k(R phi2 - R phi1)",
        )
    torques = sym.contact_torques
    nonlinear = [sp.Eq(b.J * b.qdd, _short(torques[i])) for i, b in enumerate(sym.bodies)]
    section.add(
        nonlinear,
        "Rotation about each contact line: the friction and normal forces "
        "act on the axis and drop out; only the applied forces' torques remain.",
        "paper (e), (f), (w2), (w22); (M7)",
    )
    result = MethodResult("newton", TITLES["newton"], True, "", section, nonlinear=nonlinear)
    reason = _applicable_linear(sym)
    if reason:
        result.reason = "linearisation: " + reason
        return result
    equations = linear_equations(sym)
    if _is_linear(sym):
        section.add(
            equations,
            "The equations are linear in the angles: exact at any amplitude while the bodies roll.",
            "docs/physics.md Sec. 8",
        )
    else:
        section.add(
            equations,
            "Linearised about the equilibrium (small angles): the "
            "stiffness matrix K = d2V/dq2 at q = 0.",
            "(M12), (M13)",
        )
    result.equations = equations
    freq = _frequencies(sym, budget)
    out = _whole_system(
        section,
        sym,
        coords=sym.q,
        accels=sym.qdd,
        velocities=sym.qd,
        masses=[b.J for b in sym.bodies],
        K=sym.stiffness_matrix,
        v0=_v0(sym),
        frequencies=freq,
        in_angles=True,
    )
    result.system_equation = out.get("system_equation")
    result.omega2 = out.get("omega2", [])
    result.extras.update(out)
    return result


def conservation(sym: SymbolicSystem, budget: float | None) -> MethodResult:
    """Energy and the conserved angular-momentum combination (one oscillating degree of
    freedom)."""
    section = Section(TITLES["conservation"])
    result = MethodResult("conservation", TITLES["conservation"], False, "", section)
    reason = _applicable_linear(sym)
    n_zero = sym.zero_mode_count() if not reason else 0
    if not reason:
        oscillating = sym.n - n_zero
        if n_zero == 0 and sym.n > 1:
            reason = (
                "no zero mode (a wall or a pre-tensioned spring holds the system): no "
                "conserved angular-momentum combination, and energy alone cannot fix "
                f"{sym.n} coordinates"
            )
        elif n_zero > 1:
            reason = (
                f"{n_zero} zero modes: parts of the system move freely, and energy with "
                "the conserved combinations does not single out one oscillation"
            )
        elif oscillating > 1:
            reason = (
                f"{oscillating} oscillating modes: energy and the one conserved "
                "angular-momentum combination give two equations for "
                f"{sym.n} coordinates"
            )
    if reason:
        result.reason = reason
        return result
    result.applies = True
    constraint_step(section, sym)
    steiner_step(section, sym)
    J = [b.J for b in sym.bodies]
    K = sym.stiffness_matrix
    kinetic = sym.kinetic
    quad = sp.expand(
        (sp.Matrix(sym.q).T * K * sp.Matrix(sym.q))[0, 0] / 2
        - (sym.reference_forces.T * sp.Matrix(sym.q))[0, 0]
    )
    energy = sp.Symbol("E")
    section.add(
        sp.Eq(energy, kinetic + sp.factor(quad)),
        "Mechanical energy: about the contact lines the kinetic energy is purely "
        "rotational; the potential to second order.",
        "paper (mu); (M6)",
    )
    if sym.n == 1:
        b = sym.bodies[0]
        derivative = sp.expand(sp.diff(kinetic + quad, b.qd) * b.qdd + sp.diff(quad, b.q) * b.qd)
        section.add(
            sp.Eq(sp.Symbol("Edot"), sp.factor(derivative)),
            "Energy is conserved: dE/dt = 0 for every motion.",
            "(M6)",
        )
        omega2 = _tidy(sp.cancel(K[0, 0] / J[0]))
        equation = sp.Eq(b.J * b.qdd, sym.reference_forces[0] - K[0, 0] * b.q)
        section.add(equation, "Dividing by the angular velocity.", "")
        result.equations = [equation]
        result.system_equation = sp.Eq(b.qdd + omega2 * b.q, 0)
        section.add(result.system_equation, "The equation of motion.", "")
        section.add(sp.Eq(OMEGA2, omega2), "The squared frequency.", "")
        result.omega2 = [omega2]
        return result
    v0 = _v0(sym)
    if v0 is None or v0[0] == 0 or v0[1] == 0:
        result.applies = False
        result.reason = "the zero mode moves one body only: no exchange between the two bodies"
        section.steps.clear()
        return result
    momentum = sp.Add(*[J[i] * v0[i] * sym.qd[i] for i in range(2)])
    section.add(
        sp.Eq(_content_free(momentum, sym.qd), 0),
        "The spring torques about the contact lines cancel in this combination "
        "(v0^T K = 0), so it is conserved; zero relative to the stationary point.",
        "paper (nu), (rel1); (M14)",
    )
    ratio = sp.cancel(-J[0] * v0[0] / (J[1] * v0[1]))
    section.add(sp.Eq(sym.qd[1], ratio * sym.qd[0]), "Solved for the second angular velocity.", "")
    # dE/dt = 0 and dP/dt = 0 give both accelerations (in phi, for any configuration)
    power = sp.Add(*[sym.qd[i] * (J[i] * sym.qdd[i] + sp.diff(quad, sym.q[i])) for i in range(2)])
    power = sp.expand(power.subs(sym.qd[1], ratio * sym.qd[0]) / sym.qd[0])
    balance = sp.Add(*[J[i] * v0[i] * sym.qdd[i] for i in range(2)])
    solution = sp.solve([power, balance], sym.qdd, dict=True)[0]
    equations = [
        sp.Eq(J[i] * sym.qdd[i], sp.factor(sp.expand(J[i] * solution[sym.qdd[i]])))
        for i in range(2)
    ]
    section.add(
        sp.Eq(sp.Symbol("Edot") / sym.qd[0], sp.collect(power, sym.qdd)),
        "dE/dt = 0 with the conserved combination substituted, divided by the first "
        "angular velocity.",
        "",
    )
    section.add(equations, "Together with dP/dt = 0 this gives each body's equation of motion.", "")
    result.equations = equations
    # the paper's route: maximal velocities, Omega = (v1 + v2)/A
    lever = _single_spring_lever(sym)
    if lever is not None:
        amplitude = sp.Symbol("A", positive=True)
        rates = [sp.Symbol("Phidot_" + sym.bodies[i].label, positive=True) for i in range(2)]
        k = sym.springs[0].k
        ratio_abs = sp.Abs(ratio)
        section.add(
            sp.Eq(k * amplitude**2 / 2, J[0] * rates[0] ** 2 / 2 + J[1] * rates[1] ** 2 / 2),
            "Energy at the largest deformation A equals the energy at the undeformed "
            "spring, where the angular velocities are largest.",
            "paper (mu)",
        )
        section.add(
            sp.Eq(rates[1], ratio_abs * rates[0]),
            "The conserved combination for the largest angular velocities (magnitudes).",
            "paper (nu)",
        )
        rate1 = amplitude * sp.sqrt(sp.cancel(k / (J[0] + J[1] * ratio_abs**2)))
        speeds = [
            sp.factor(sp.cancel(sym.bodies[0].s * rate1)),
            sp.factor(sp.cancel(sym.bodies[1].s * ratio_abs * rate1)),
        ]
        speeds = [_sqrt_form(v) for v in speeds]
        v_syms = [sp.Symbol(f"v_{sym.bodies[i].label}") for i in range(2)]
        section.add(
            [sp.Eq(v_syms[i], _root_display(speeds[i], amplitude)) for i in range(2)],
            "Largest centre speeds, v = R times the largest angular velocity (for a "
            "slider, its largest speed).",
            "paper (om), (pi)",
        )
        deformation_rate = sp.cancel(sp.Abs(lever[0] + lever[1] * ratio) * rate1)
        omega = _sqrt_form(sp.factor(deformation_rate / amplitude))
        section.add(
            sp.Eq(sp.Symbol("Omega"), omega),
            "The spring's deformation rate, sum_i b_i q_i' with the lever arms b_i, is A "
            "Omega at its largest (harmonic motion); for a horizontal spring between the "
            "centres the rate is v1 + v2, the paper's Omega = (v1 + v2)/A.",
            "paper Omega = (v1+v2)/A",
        )
        amplitudes = [sp.factor(sp.cancel(v / omega)) for v in speeds]
        section.add(
            [sp.Eq(sp.Symbol(f"A_{sym.bodies[i].label}"), amplitudes[i]) for i in range(2)],
            "Centre amplitudes about the stationary point, A_i = v_i / Omega.",
            "paper A1, A2 (Sec. 4.2)",
        )
        result.extras.update(speeds=speeds, omega=omega, amplitudes=amplitudes, amplitude=amplitude)
    omega2 = _tidy(
        sp.cancel(
            sp.Add(
                *[
                    K[i, j] * (ratio if i else 1) * (ratio if j else 1)
                    for i in range(2)
                    for j in range(2)
                ]
            )
            / (J[0] + J[1] * ratio**2)
        )
    )
    result.system_equation = sp.Eq(sym.qdd[0] + omega2 * sym.q[0], 0)
    section.add(
        result.system_equation,
        "Energy of the single oscillation E = (1/2)J q'^2 + "
        "(1/2)K q^2 in the first angle: its time derivative gives the equation of motion "
        "of the whole system.",
        "paper (QQ1)",
    )
    section.add(
        sp.Eq(OMEGA2, omega2),
        "The squared frequency; isochronous: the amplitude A drops out.",
        "paper (QQQ1)",
    )
    result.omega2 = [omega2]
    result.extras["ratio"] = ratio
    result.extras["conserved"] = momentum
    return result


def _single_spring_lever(sym: SymbolicSystem) -> list[sp.Expr] | None:
    """Lever arms b_i = dl/dphi_i at the reference for one unstressed spring (else None)."""
    if len(sym.springs) != 1 or sym.forces or sym.n != 2:
        return None
    spring = sym.springs[0]
    if spring.L != spring.ell:
        return None
    zero = {b.q: 0 for b in sym.bodies}
    return [sp.simplify(sp.diff(spring.length, b.q).subs(zero)) for b in sym.bodies]


def _root_display(expr: sp.Expr, factor: sp.Symbol) -> sp.Expr:
    """``factor * sqrt(rest)`` kept as one unevaluated root, as the paper prints (om), (pi)."""
    rest = sp.factor(sp.cancel(sp.expand(expr**2) / factor**2))
    return sp.Mul(factor, sp.Pow(rest, sp.S.Half, evaluate=False), evaluate=False)


def _sqrt_form(expr: sp.Expr) -> sp.Expr:
    """A positive expression as one square root, sqrt(expr^2) (SymPy takes positive factors
    out again): A sqrt(3 k m2/(2 m1 (4 m1 + 3 m2))) rather than a product of roots."""
    expr = sp.sympify(expr)
    if expr.is_positive is False:
        return expr
    squared = sp.factor(sp.cancel(sp.expand(expr**2)))
    return sp.sqrt(squared)


def lagrange(sym: SymbolicSystem, budget: float | None) -> MethodResult:
    """Euler-Lagrange equations of L = T - V; the structure route and LagrangesMethod."""
    section = Section(TITLES["lagrange"])
    constraint_step(section, sym)
    steiner_step(section, sym)
    kinetic_lines = []
    for b in sym.bodies:
        if b.rolls:
            kinetic_lines.append(
                rf"\tfrac12 {sp.latex(b.m)}\dot{{x}}_{{{b.label}}}^2 + \tfrac12 {sp.latex(b.I)}"
                rf"{sp.latex(b.qd)}^2 = \tfrac12 \left({sp.latex(b.J)}\right){sp.latex(b.qd)}^2"
            )
    tsym = sp.Symbol("T")
    section.add(
        sp.Eq(tsym, sym.kinetic),
        "Kinetic energy (König): translation plus rotation "
        "about the centre equals rotation about the contact line, x' = R phi'.",
        "(M4), (M5)",
        latex=(
            r"T = \sum_i \tfrac12 m_i\dot{x}_i^2 + \tfrac12 I_i\dot\varphi_i^2 = "
            + sp.latex(sym.kinetic)
        ),
    )
    spring_steps(section, sym)
    vsym = sp.Symbol("V")
    section.add(
        sp.Eq(vsym, _short(sym.potential)),
        "Potential energy of the springs (and "
        "constant forces), exactly; gravity is constant while rolling.",
        "(M5)",
    )
    lsym = named("L", r"\mathcal{L}")
    section.add(
        sp.Eq(lsym, tsym - vsym), "The Lagrangian.", "paper (l); (M5)", latex=r"\mathcal{L} = T - V"
    )
    momenta = [
        sp.Eq(sp.Symbol(f"p_{b.label}" if sym.n > 1 else "p"), b.J * b.qd) for b in sym.bodies
    ]
    section.add(
        momenta,
        "Generalised momenta: the mass matrix diag(J_i) is constant and diagonal for any geometry.",
        "(M6)",
        latex=_aligned_pairs(
            [
                (
                    rf"\frac{{\partial\mathcal{{L}}}}{{\partial "
                    rf"{sp.latex(b.qd)}}}",
                    sp.latex(b.J * b.qd),
                )
                for b in sym.bodies
            ]
        ),
    )
    gradient = sym.potential_gradient  # differentiate V, spring by spring
    nonlinear = [sp.Eq(b.J * b.qdd, _short(-gradient[i])) for i, b in enumerate(sym.bodies)]
    section.add(
        nonlinear,
        "Euler-Lagrange: d/dt(dL/dphi') = dL/dphi, i.e. J_i phi_i'' = "
        "-dV/dphi_i (the structure route: differentiate V only).",
        "paper (al), (be); (M7)",
    )
    result = MethodResult("lagrange", TITLES["lagrange"], True, "", section, nonlinear=nonlinear)
    check = mechanics_lagrange_check(sym, budget=budget)
    result.extras["mechanics"] = check
    if check["agrees"] is True:
        section.add(
            sp.Eq(sp.Symbol("residual"), 0),
            "sympy.physics.mechanics.LagrangesMethod on "
            "the same Lagrangian gives the same equations: the difference simplifies to "
            "zero.",
            "",
        )
    else:
        section.add(
            sp.Eq(
                sp.Symbol("residual"),
                check["residual"] if check["residual"] is not None else sp.Symbol("unknown"),
            ),
            "sympy.physics.mechanics.LagrangesMethod: " + check["message"],
            "",
        )
    reason = _applicable_linear(sym)
    if reason:
        result.reason = "linearisation: " + reason
        return result
    quad = sym.quadratic_potential
    section.add(
        sp.Eq(vsym, sp.factor(quad) if sym.n <= 4 else quad),
        "The potential to second order about the equilibrium: (1/2) q^T K q.",
        "paper (l) (QQ2 form); (M12)",
    )
    equations = linear_equations(sym)
    section.add(
        equations,
        "Linearised Euler-Lagrange equations."
        if not _is_linear(sym)
        else "The same equations, already linear (exact at any amplitude while rolling).",
        "paper (al), (be) (sign-corrected); (M12)",
    )
    result.equations = equations
    freq = _frequencies(sym, budget)
    out = _whole_system(
        section,
        sym,
        coords=sym.q,
        accels=sym.qdd,
        velocities=sym.qd,
        masses=[b.J for b in sym.bodies],
        K=sym.stiffness_matrix,
        v0=_v0(sym),
        frequencies=freq,
        in_angles=True,
        labels=(
            "paper (ga)",
            "paper (ga) integrated, (de); (M14)",
            "paper (c); (M14)",
            "paper (ep)",
            "paper (QQQ1)",
            "paper (ep0)",
        ),
    )
    result.system_equation = out.get("system_equation")
    result.omega2 = out.get("omega2", [])
    result.extras.update(out)
    split = _spring_split(sym, freq)
    if split is not None:
        section.add(
            [sp.Eq(sp.Symbol(f"k_{sym.bodies[i].label}'"), split[i]) for i in range(2)],
            "Split of the spring about the stationary point: k_i = k Omega^2/Omega_i^2 "
            "(then 1/k = 1/k_1 + 1/k_2).",
            "paper (k1), (k2), (part)",
        )
        result.extras["spring_split"] = split
    return result


def _aligned_pairs(pairs: list[tuple[str, str]]) -> str:
    return r"\begin{aligned}" + r" \\ ".join(f"{a} &= {b}" for a, b in pairs) + r"\end{aligned}"


def _spring_split(sym: SymbolicSystem, freq: Frequencies) -> list[sp.Expr] | None:
    """k_i = k / sigma_i, sigma_i = Omega_i^2 / Omega^2 (paper (k1), (k2))."""
    if sym.n != 2 or len(sym.springs) != 1 or freq.n_zero != 1 or sym.forces:
        return None
    if any(a is None for a in sym.springs[0].attachments):
        return None
    K = sym.stiffness_matrix
    clamped = [sp.cancel(K[i, i] / sym.bodies[i].J) for i in range(2)]
    if any(c == 0 for c in clamped):
        return None
    total = clamped[0] + clamped[1]
    k = sym.springs[0].k
    return [sp.factor(sp.cancel(k * total / c)) for c in clamped]


def mechanics_lagrange_check(sym: SymbolicSystem, *, budget: float | None = 30.0) -> dict[str, Any]:
    r"""The exact equations from ``sympy.physics.mechanics.LagrangesMethod`` against the
    structure route :math:`J_i\ddot\varphi_i + \partial V/\partial\varphi_i = 0`: the residual,
    expanded (and simplified if needed), must vanish."""
    from sympy.physics.mechanics import LagrangesMethod

    lag = sym.in_time(sym.lagrangian)
    try:
        with time_budget(budget):
            method = LagrangesMethod(lag, sym.functions)
            forms = list(method.form_lagranges_equations())
            ours = [
                sym.in_time(b.J * b.qdd + dV)
                for b, dV in zip(sym.bodies, sym.potential_gradient, strict=True)
            ]
            residual = [sp.expand(a - b) for a, b in zip(forms, ours, strict=True)]
            if any(r != 0 for r in residual):
                residual = [sp.simplify(r) for r in residual]
    except BudgetExceeded:
        return {
            "agrees": None,
            "residual": None,
            "equations": None,
            "message": f"did not finish within the {budget:g} s budget",
        }
    agrees = all(r == 0 for r in residual)
    return {
        "agrees": agrees,
        "residual": sp.Matrix(residual),
        "equations": forms,
        "message": "agrees" if agrees else "the residual does not simplify to zero",
    }


def natural_frequencies(sym: SymbolicSystem, budget: float | None) -> MethodResult:
    """Subsystem frequencies (one body clamped) and the sum rule, for rank-1 K."""
    section = Section(TITLES["natural-frequencies"])
    result = MethodResult("natural-frequencies", TITLES["natural-frequencies"], False, "", section)
    reason = _applicable_linear(sym)
    if not reason:
        n_zero = sym.zero_mode_count()
        if sym.n > 2:
            reason = (
                f"{sym.n} bodies: the subsystem frequencies do not add up to a normal "
                "frequency (the sum rule needs two bodies and a rank-1 K); only the trace "
                "identity sum(omega_n^2) = sum(K_ii/J_i) holds"
            )
        elif sym.n == 2 and n_zero != 1:
            reason = (
                "no zero mode (a wall or a pre-tensioned spring): K has rank 2 and "
                "Omega^2 is not Omega_1^2 + Omega_2^2; only the trace identity "
                "omega_1^2 + omega_2^2 = K_11/J_1 + K_22/J_2 holds"
            )
    if reason:
        result.reason = reason
        return result
    result.applies = True
    constraint_step(section, sym)
    steiner_step(section, sym)
    K = sym.stiffness_matrix
    J = [b.J for b in sym.bodies]
    alphas = [sp.Symbol(f"alpha_{b.label}") for b in sym.bodies]
    betas = [sp.Symbol(f"beta_{b.label}") for b in sym.bodies]
    clamped = [_tidy(sp.cancel(K[i, i] / J[i])) for i in range(sym.n)]
    omegas = [sp.Symbol(f"Omega_{b.label}") for b in sym.bodies]
    for i, b in enumerate(sym.bodies):
        energy = sp.Symbol(f"E_{b.label}")
        section.add(
            [
                sp.Eq(energy, J[i] * b.qd**2 / 2 + K[i, i] * b.q**2 / 2),
                sp.Eq(alphas[i], J[i]),
                sp.Eq(betas[i], K[i, i]),
                sp.Eq(omegas[i] ** 2, clamped[i]),
            ],
            f"Subsystem {b.label}: body {b.label} alone, the other clamped; the "
            "quadratic energy E = (1/2) alpha q'^2 + (1/2) beta q^2 gives Omega^2 = "
            "beta/alpha.",
            "paper (qee), App. B",
        )
    if sym.n == 1:
        omega2 = clamped[0]
        result.system_equation = sp.Eq(sym.qdd[0] + omega2 * sym.q[0], 0)
        section.add(result.system_equation, "One body: the subsystem is the system.", "")
        result.omega2 = [omega2]
        result.equations = linear_equations(sym)
        return result
    det = sp.cancel(K.det())
    section.add(
        sp.Eq(named("det K", r"\det K"), det),
        "K has rank 1 (a zero mode): the determinant vanishes.",
        "(M15)",
    )
    omega2 = _tidy(clamped[0] + clamped[1])
    section.add(
        sp.Eq(OMEGA2, sp.Add(omegas[0] ** 2, omegas[1] ** 2, evaluate=False)),
        "Sum rule: with det(K - Omega^2 M) = Omega^2 (Omega^2 - tr M^-1 K) J1 J2 the one "
        "non-zero root is the sum of the subsystem frequencies squared.",
        "paper Omega_f^2 = Omega_1^2 + Omega_2^2; (M15)",
    )
    section.add(
        sp.Eq(OMEGA2, omega2),
        "The squared frequency of the coupled system.",
        "paper (QQQ1), App. B",
    )
    # App. C: rank 1 fixes K from its diagonal up to the sign of K_12 (from the geometry)
    sign = 1 if sym.numeric(K[0, 1]) >= 0 else -1
    off = sp.factor(sp.powdenest(sp.sqrt(sp.factor(K[0, 0] * K[1, 1])), force=False)) * sign
    section.add(
        sp.Eq(sp.Symbol("K_12"), off),
        "Rank 1 fixes the coupling from the subsystems: "
        "K_12 = ±sqrt(K_11 K_22), the sign from the lever arms (opposite sides: -).",
        "paper App. C",
    )
    rebuilt = sp.Matrix([[K[0, 0], off], [off, K[1, 1]]])
    if len(sym.springs) == 1 and not sym.forces:
        m = [b.m for b in sym.bodies]
        k = sym.springs[0].k
        coefficients = [sp.Symbol(f"c_{b.label}") for b in sym.bodies]
        values = [sp.sqrt(sp.cancel(K[i, i] * m[i] / (J[i] * k))) for i in range(2)]
        values = [-values[0] if sign < 0 else values[0], values[1]]
        section.add(
            [sp.Eq(coefficients[i], values[i]) for i in range(2)],
            "Coefficients of the Hamiltonian potential (k/2)(c1 q1 + c2 q2)^2: |c_i| = "
            "Omega_i / sqrt(k/m_i); in a common orientation of the angles they have "
            "opposite signs here.",
            "paper (k0), App. C (sign-corrected)",
        )
        result.extras["c"] = values
    equations = [
        sp.Eq(J[i] * sym.qdd[i], -sp.expand((rebuilt * sp.Matrix(sym.q))[i])) for i in range(2)
    ]
    section.add(equations, "Each body's equation of motion, rebuilt from the subsystems.", "")
    result.equations = equations
    result.system_equation = sp.Eq(sym.qdd[0] + omega2 * sym.q[0], 0)
    section.add(
        result.system_equation,
        "The equation of motion of the whole system (about the stationary point).",
        "paper (QQ1)",
    )
    result.omega2 = [omega2]
    result.extras["clamped"] = clamped
    return result


def hamilton(sym: SymbolicSystem, budget: float | None) -> MethodResult:
    """Canonical coordinates q_i = sqrt(J_i/m_i) phi_i, p_i = m_i q_i'."""
    section = Section(TITLES["hamilton"])
    constraint_step(section, sym)
    steiner_step(section, sym)
    n = sym.n
    J = [b.J for b in sym.bodies]
    m = [b.m for b in sym.bodies]
    scale = [sp.sqrt(sp.cancel(J[i] / m[i])) for i in range(n)]  # q = scale * phi
    qs = [sp.Symbol(f"q_{b.label}" if n > 1 else "q", real=True) for b in sym.bodies]
    ps = [sp.Symbol(f"p_{b.label}" if n > 1 else "p", real=True) for b in sym.bodies]
    qdots = [sp.Symbol(f"qdot_{b.label}" if n > 1 else "qdot", real=True) for b in sym.bodies]
    pdots = [sp.Symbol(f"pdot_{b.label}" if n > 1 else "pdot", real=True) for b in sym.bodies]
    section.add(
        [sp.Eq(qs[i], scale[i] * sym.q[i]) for i in range(n)],
        "Canonical coordinates chosen so that the kinetic energy is sum p^2/(2m): "
        "q_i = sqrt(J_i/m_i) phi_i (a point transformation, hence canonical).",
        "paper q1 = sqrt(2) R phi1, q2 = sqrt(3/2) R phi2",
    )
    section.add([sp.Eq(ps[i], m[i] * qdots[i]) for i in range(n)], "Momenta.", "(M6)")
    back = {sym.q[i]: qs[i] / scale[i] for i in range(n)}
    potential_q = sym.potential.xreplace(back)
    kinetic_q = sp.Add(*[ps[i] ** 2 / (2 * m[i]) for i in range(n)])
    hsym = named("H", r"\mathcal{H}")
    section.add(
        sp.Eq(hsym, kinetic_q + _short(potential_q)),
        "The Hamiltonian, exactly: separable, kinetic part in p only.",
        "(M6)",
    )
    # exact Hamilton equations, then back to the angles
    dV = [
        sp.diff(potential_q, qs[i]) if potential_q.has(qs[i]) else sp.Integer(0) for i in range(n)
    ]
    section.add(
        [sp.Eq(qdots[i], ps[i] / m[i]) for i in range(n)]
        + [sp.Eq(-pdots[i], _short(dV[i])) for i in range(n)],
        "Hamilton's equations q' = dH/dp, -p' = dH/dq.",
        "paper (h)",
    )
    nonlinear = []
    for i, b in enumerate(sym.bodies):
        # p_i' = m_i q_i'' = m_i scale_i phi_i''; times scale_i: J_i phi_i'' = -scale_i dV/dq_i
        rhs = -(scale[i] * dV[i]).xreplace({qs[j]: scale[j] * sym.q[j] for j in range(n)})
        nonlinear.append(sp.Eq(b.J * b.qdd, _short(sp.powsimp(rhs))))
    section.add(
        nonlinear,
        "Back in the angles: m q'' = -dV/dq times sqrt(J/m) is J phi'' = -dV/dphi.",
        "(M7)",
    )
    result = MethodResult("hamilton", TITLES["hamilton"], True, "", section, nonlinear=nonlinear)
    reason = _applicable_linear(sym)
    if reason:
        result.reason = "linearisation: " + reason
        return result
    D = sp.diag(*scale)
    Dinv = sp.diag(*[1 / s for s in scale])
    Kq = (Dinv * sym.stiffness_matrix * Dinv).applyfunc(_compact_entry)
    qvec = sp.Matrix(qs)
    quadratic = sp.expand((qvec.T * Kq * qvec)[0, 0] / 2)
    lever = _single_spring_lever(sym)
    if lever is not None:
        k = sym.springs[0].k
        c = [sp.factor(sp.cancel(lever[i] / scale[i])) for i in range(2)]
        form = k / 2 * (c[0] * qs[0] + c[1] * qs[1]) ** 2
        section.add(
            sp.Eq(sp.Symbol("U"), form),
            "The potential to second order, as the "
            "paper writes it: U = (k/2)(c1 q1 + c2 q2)^2, c_i = b_i sqrt(m_i/J_i) (b_i "
            "the lever arms); in a common orientation c1 and c2 have opposite signs.",
            "paper (k), (k0) (sign-corrected)",
        )
        result.extras["c"] = c
        result.extras["potential_form"] = form
    else:
        section.add(
            sp.Eq(sp.Symbol("U"), quadratic),
            "The potential to second order about the "
            "equilibrium, (1/2) q^T K_q q with K_q = D^-1 K D^-1.",
            "(M12)",
        )
    linear_p = [
        sp.Eq(-pdots[i], sp.expand((Kq * qvec)[i] - sym.reference_forces[i] / scale[i]))
        for i in range(n)
    ]
    section.add(linear_p, "Linearised Hamilton's equations: -p_i' = dU/dq_i.", "paper (h)")
    equations = []
    for i, body in enumerate(sym.bodies):
        rhs = -(scale[i] * (Kq * qvec)[i]).xreplace({qs[j]: scale[j] * sym.q[j] for j in range(n)})
        rhs = sym.reference_forces[i] + sp.expand(sp.powsimp(sp.expand(rhs)))
        equations.append(sp.Eq(body.J * body.qdd, rhs))
    result.equations = equations
    mass_q = [m[i] for i in range(n)]
    qdd_q = [sp.Symbol(f"qddot_{bb.label}" if n > 1 else "qddot", real=True) for bb in sym.bodies]
    v0 = _v0(sym)
    v0q = (D * v0).applyfunc(sp.cancel) if v0 is not None else None
    if v0q is not None and n == 2:
        v0q = _zero_mode_2(Kq) or v0q
    dynamic = sp.Matrix(n, n, lambda i, j: sp.cancel(Kq[i, j] / m[i]))
    freq = (
        _frequencies(sym, budget)
        if n > 2
        else normal_frequencies(sym, budget=budget, matrix=dynamic)
    )
    out = _whole_system(
        section,
        sym,
        coords=qs,
        accels=qdd_q,
        velocities=qdots,
        masses=mass_q,
        K=Kq,
        v0=v0q,
        frequencies=freq,
        in_angles=False,
        labels=(
            "paper p2' = (2/sqrt3) p1' (sign-corrected)",
            "paper q2 = (m1/m2)(2/sqrt3) q1 (sign-corrected)",
            "",
            "paper p1' = m1 q1''",
            "paper (QQQ1)",
            "paper -p1' = k(q1/2 + 2 m1 q1/(3 m2))",
        ),
    )
    result.system_equation = out.get("system_equation")
    result.omega2 = out.get("omega2", [])
    result.extras.update(out)
    result.extras["Kq"] = Kq
    return result


def _compact_entry(expr: sp.Expr) -> sp.Expr:
    """A matrix entry: cancelled and factored unless it holds transcendental constants."""
    expr = sp.cancel(expr)
    if expr.has(sp.sin, sp.cos, sp.atan2) or sp.count_ops(expr) > 80:
        return expr
    return sp.factor(expr)


def _short(expr: sp.Expr) -> sp.Expr:
    """A compact form for display: factor small expressions, leave big ones alone."""
    expr = sp.sympify(expr)
    if expr.count_ops() <= 60:
        try:
            return min([expr, sp.factor(expr)], key=sp.count_ops)
        except Exception:  # noqa: BLE001 - display only
            return expr
    return expr


_RUNNERS: dict[str, Callable[[SymbolicSystem, float | None], MethodResult]] = {
    "newton": newton,
    "conservation": conservation,
    "lagrange": lagrange,
    "natural-frequencies": natural_frequencies,
    "hamilton": hamilton,
}


def run_method(sym: SymbolicSystem, name: str, *, budget: float | None = 10.0) -> MethodResult:
    """Run one method by name (see :data:`METHODS`). The paper's equation labels name its
    Fig. 2 formulas (centres joined by a horizontal spring); for any other system they are
    shown as "cf. paper ... (Fig. 2 there)": the step is the same idea, not the paper's
    expression."""
    result = _RUNNERS[name](sym, budget)
    if not _is_papers_fig2(sym):
        result.section.steps[:] = [
            replace(step, ref=_compare_ref(step.ref)) for step in result.section.steps
        ]
    return result


def _is_papers_fig2(sym: SymbolicSystem) -> bool:
    """Two rolling bodies joined at their centres by one horizontal spring (the paper's Fig. 2),
    nothing else."""
    return (
        sym.n == 2
        and len(sym.springs) == 1
        and sym.springs[0].bodies == (0, 1)
        and sym.springs[0].stays_horizontal
        and all(b.rolls for b in sym.bodies)
        and not sym.forces
    )


def _compare_ref(ref: str) -> str:
    """'paper (QQQ1); (M12)' -> 'cf. paper (QQQ1) (Fig. 2 there); (M12)'."""
    parts = [part.strip() for part in ref.split(";")]
    return "; ".join(
        f"cf. {part} (Fig. 2 there)" if part.startswith("paper") else part for part in parts if part
    )

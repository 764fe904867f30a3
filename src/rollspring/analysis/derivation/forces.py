r"""Friction and normal forces, symbolically (docs/physics.md (M8)-(M10); paper App. A).

* :func:`contact_force_section`: for a system, :math:`f_i = m_iR_i\ddot\varphi_i - F_{ix}`
  (M8), :math:`N_i = m_i g - F_{iy}` (M9), the same with the equations of motion substituted
  (functions of the configuration only), linearised; for two bodies and one spring the
  percussion ratios :math:`\lambda_i` and :math:`f_i = -(1-\lambda_i)F_{ix}` (M17).
* :func:`appendix_a_friction`: the paper's eq. (fric), :math:`f(y) = F(1 - mRy/(I+mR^2))`,
  derived from Newton's laws, and the height where no friction is needed,
  :math:`y^* = R + I/(mR)`, solved for any shape (:func:`zero_friction_heights`).
"""

from __future__ import annotations

from typing import Any

import sympy as sp

from rollspring.analysis.derivation.steps import Section
from rollspring.analysis.derivation.symbolic import EXACT_INERTIA_FACTORS, SymbolicSystem

__all__ = ["appendix_a_friction", "contact_force_section", "zero_friction_heights"]


def appendix_a_friction() -> tuple[Section, dict[str, sp.Expr]]:
    r"""Derive the paper's eq. (fric) and the zero-friction height (App. A).

    A round body (mass m, radius R, central moment of inertia I) pulled horizontally by F at
    height y above the floor, rolling without slipping; f is the static friction counted
    against F, as in the paper (rollspring's signed friction along +x is :math:`-f`):

    .. math:: F - f = ma,\quad Fy = (I + mR^2)\ddot\varphi,\quad a = R\ddot\varphi
              \;\Rightarrow\; f(y) = F\Bigl(1 - \frac{mRy}{I + mR^2}\Bigr),\quad
              f(y^*) = 0 \Leftrightarrow y^* = R + \frac{I}{mR}

    Returns the section and ``{"f": f(y), "y_star": y*, "phi_ddot": ...}``.
    """
    m, R, I, F = sp.symbols("m R I F", positive=True)
    y = sp.Symbol("y", nonnegative=True)
    f, a, acc = sp.symbols("f a phiddot", real=True)
    section = Section("Friction of a pulled body (paper App. A)")
    newton = sp.Eq(F - f, m * a)
    torque = sp.Eq(F * y, (I + m * R**2) * acc)
    rolling = sp.Eq(a, R * acc)
    section.add(
        [newton, torque],
        "Newton's law for the centre and rotation about the contact "
        "line; f is the static friction, counted against the pull F.",
        "paper (a1), (a2)",
    )
    section.add(rolling, "Rolling without slipping.", "paper a = R phi''")
    from_newton = sp.solve(newton.subs(a, R * acc), acc)[0]
    from_torque = sp.solve(torque, acc)[0]
    section.add(
        [sp.Eq(acc, from_newton), sp.Eq(acc, from_torque)],
        "The angular acceleration from each equation.",
        "paper App. A",
    )
    friction = sp.solve(sp.Eq(from_newton, from_torque), f)[0]
    friction = sp.collect(sp.expand(friction), F)
    section.add(
        sp.Eq(sp.Function("f")(y), F * (1 - m * R * y / (I + m * R**2))),
        "Eliminating the angular acceleration: the friction decreases linearly with the "
        "height of the pull.",
        "paper (fric)",
    )
    y_star = sp.solve(sp.Eq(friction, 0), y)[0]
    y_star = sp.expand(y_star)
    section.add(
        sp.Eq(sp.Symbol("y^*"), y_star),
        "No friction is needed for a pull at this height, whatever F (the percussion point).",
        "paper y1 = 2R, y2 = 3R/2; (M10)",
    )
    gamma = sp.Symbol("gamma", positive=True)
    section.add(
        sp.Eq(sp.Symbol("y^*"), sp.factor(y_star.subs(I, gamma * m * R**2))),
        "With I = gamma m R^2.",
        "(M10)",
    )
    heights = zero_friction_heights()
    section.add(
        [sp.Eq(sp.Symbol(f"y^*_{{{shape}}}"), h) for shape, h in heights.items()],
        "For each shape: hoop, solid cylinder, solid sphere, thin spherical shell.",
        "paper Sec. 3: 2R (hoop), 3R/2 (cylinder)",
    )
    return section, {
        "f": friction,
        "y_star": y_star,
        "phi_ddot": from_torque,
        "symbols": {"m": m, "R": R, "I": I, "F": F, "y": y},
    }


def zero_friction_heights() -> dict[str, sp.Expr]:
    r""":math:`y^* = R + I/(mR) = (1+\gamma)R` for every built-in shape (in units of a symbol R)."""
    R = sp.Symbol("R", positive=True)
    return {
        shape: (1 + gamma) * R
        for shape, gamma in EXACT_INERTIA_FACTORS.items()
        if shape != "slider"
    }


def contact_force_section(sym: SymbolicSystem) -> tuple[Section, dict[str, Any]]:
    """The friction and normal force on every body, symbolically (see the module)."""
    section = Section("Friction and normal forces")
    n = sym.n
    rolling = [i for i, b in enumerate(sym.bodies) if b.rolls]
    Fx = [sp.Symbol(f"F_{{{b.label}x}}") for b in sym.bodies]
    Fy = [sp.Symbol(f"F_{{{b.label}y}}") for b in sym.bodies]
    f_syms = [sp.Symbol(f"f_{b.label}") for b in sym.bodies]
    n_syms = [sp.Symbol(f"N_{b.label}") for b in sym.bodies]
    section.add(
        [
            sp.Eq(f_syms[i], sym.bodies[i].m * sym.bodies[i].s * sym.bodies[i].qdd - Fx[i])
            for i in rolling
        ]
        + [sp.Eq(n_syms[i], sym.bodies[i].m * sym.g - Fy[i]) for i in range(n)],
        "Newton's second law for each centre (it moves horizontally, x'' = R phi''): "
        "friction f along +x, normal force N; F_i is the applied force on body i.",
        "(M8), (M9)",
    )
    if rolling:
        section.add(
            [
                sp.Eq(
                    f_syms[i],
                    sp.Symbol(f"Q_{sym.bodies[i].label}")
                    / ((1 + sym.bodies[i].gamma) * sym.bodies[i].R)
                    - Fx[i],
                )
                for i in rolling
            ],
            "With the equation of motion J phi'' = Q: the friction depends on the "
            "configuration only, not on the velocities.",
            "(M8)",
        )
    results: dict[str, Any] = {}
    small = n <= 4
    if small:
        exact_f = sym.friction_configuration
        exact_n = sym.normal
        shown_f = [sp.Eq(f_syms[i], _compact(exact_f[i])) for i in rolling]
        shown_n = [sp.Eq(n_syms[i], _compact(exact_n[i])) for i in range(n)]
        if all(sp.count_ops(e.rhs) < 250 for e in shown_f + shown_n):
            section.add(shown_f + shown_n, "Exactly, in the angles (any amplitude).", "(M8), (M9)")
    linear_f, linear_n = sym.linear_contact_forces
    if small:
        linear_f = [_compact(e) for e in linear_f]
        linear_n = [_compact(e) for e in linear_n]
    results["friction_linear"] = linear_f
    results["normal_linear"] = linear_n
    section.add(
        [sp.Eq(f_syms[i], linear_f[i]) for i in rolling]
        + [sp.Eq(n_syms[i], linear_n[i]) for i in range(n)],
        "To first order in the angles about the reference.",
        "(M8), (M9)",
    )
    lam = _percussion_ratios(sym)
    if lam is not None:
        lsyms = [sp.Symbol(f"lambda_{b.label}") for b in sym.bodies]
        heights = [sp.Symbol(f"eta_{b.label}") for b in sym.bodies]
        section.add(
            [
                sp.Eq(lsyms[i], heights[i] / ((1 + sym.bodies[i].gamma) * sym.bodies[i].R))
                for i in range(2)
            ]
            + [sp.Eq(lsyms[i], lam[i]) for i in range(2)],
            "Where the spring line crosses each centre vertical (height eta above the "
            "contact), relative to the percussion height (1 + gamma) R.",
            "(M10), (M16)",
        )
        fx_sym = sp.Symbol("F_x")
        section.add(
            [sp.Eq(f_syms[0], -(1 - lam[0]) * fx_sym), sp.Eq(f_syms[1], (1 - lam[1]) * fx_sym)],
            "With F_x the spring's horizontal pull on body 1 (body 2 gets -F_x): f_i = "
            "-(1 - lambda_i) F_ix.",
            "(M17); paper App. A: F/2 and F/3",
        )
        if lam[1] != 1:
            ratio = sp.factor(-(1 - lam[0]) / (1 - lam[1]))
            section.add(
                sp.Eq(f_syms[0] / f_syms[1], ratio),
                "Ratio of the frictions, signed: the paper's f1/f2 = 3/2 is a ratio "
                "of magnitudes (they point opposite ways).",
                "paper f1/f2 = 3/2; (M17)",
            )
            results["friction_ratio"] = ratio
        results["lambda"] = lam
    shapes = {b.shape for b in sym.bodies if b.rolls}
    if shapes:
        section.add(
            [
                sp.Eq(sp.Symbol(f"y^*_{b.label}"), sp.factor((1 + b.gamma) * b.R))
                for b in sym.bodies
                if b.rolls
            ],
            "Height above each body's track where a pull needs no friction, y* = R + "
            "I/(mR) = (1 + gamma) R.",
            "paper (fric) = 0; (M10)",
        )
    return section, results


def _percussion_ratios(sym: SymbolicSystem) -> list[sp.Expr] | None:
    r""":math:`\lambda_i = \eta_i/((1+\gamma_i)R_i)` for two rolling bodies joined by one
    spring attached on the centre verticals (:math:`\eta_i` the attachment heights)."""
    if sym.n != 2 or len(sym.springs) != 1 or sym.forces:
        return None
    spring = sym.springs[0]
    points = [a for a in spring.attachments if a is not None and a.height is not None]
    if len(points) != len(spring.attachments):
        return None
    if not all(b.rolls for b in sym.bodies):
        return None
    out = []
    for at in points:
        body = sym.bodies[at.body]
        out.append(sp.factor(at.height / ((1 + body.gamma) * body.R)))
    if points[0].body != 0:
        out.reverse()
    return out


def _compact(expr: sp.Expr) -> sp.Expr:
    expr = sp.sympify(expr)
    if expr.count_ops() > 60 or expr.has(sp.sin, sp.cos, sp.sqrt(2).func):
        return expr
    try:
        return min([expr, sp.factor(expr)], key=sp.count_ops)
    except Exception:  # noqa: BLE001 - display only
        return expr

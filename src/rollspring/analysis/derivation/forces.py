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

from rollspring.analysis.derivation.method import sign_inside
from rollspring.analysis.derivation.parts import EXACT_INERTIA_FACTORS
from rollspring.analysis.derivation.setup import setup_tags
from rollspring.analysis.derivation.steps import DEFINE, GIVEN, How, Section, eq, inline, named
from rollspring.analysis.derivation.symbolic import SymbolicSystem

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
    section = Section("Friction of a pulled body (paper App. A)", prefix="A", cites="paper App. A")
    newton = eq(m * a, F - f)
    torque = eq(F * y, (I + m * R**2) * acc)
    laws = section.add(
        [newton, torque],
        "Newton's law for the centre (mass times acceleration equals the resultant force), and "
        "the torque equation about the contact line z' (the contact point's acceleration points "
        "through the centre, so I' phi'' = torque holds there, with I' = I + m R^2 by Steiner's "
        "theorem); f is the static friction, counted against the pull F.",
        "paper (a1), (a2)",
        how=GIVEN,
        latex=r"\begin{aligned}m a &= F - f \\ F y &= \left(I + m R^{2}\right) \ddot{\varphi}"
        r"\end{aligned}",
        plain="m⋅a = F - f\nF⋅y = (I + m⋅R²)⋅φ̈",
    )
    rolling = section.add(
        eq(a, R * acc), "Rolling without slipping.", "paper a = R phi''", how=GIVEN
    )
    from_newton = _solve_linear(newton.subs(a, R * acc), acc)
    from_torque = _solve_linear(torque, acc)
    first = section.add(
        eq(acc, from_newton),
        f"The angular acceleration from the first of ({laws.tag}), with a of ({rolling.tag}).",
        "paper App. A",
        how=How("solve", (f"{laws.tag}:1", rolling.tag), args=(acc, a)),
    )
    second = section.add(
        eq(acc, from_torque),
        f"The angular acceleration from the second of ({laws.tag}).",
        "paper App. A",
        how=How("solve", (f"{laws.tag}:2",), args=(acc,)),
    )
    friction = _solve_linear(eq(from_newton, from_torque), f)
    friction = sp.collect(sp.expand(friction), F)
    law = section.add(
        eq(f, F * (1 - m * R * y / (I + m * R**2))),
        f"Eliminating the angular acceleration between ({first.tag}) and ({second.tag}), solved "
        "for f: the friction decreases linearly with the height y of the pull.",
        "paper (fric)",
        how=How("solve", (first.tag, second.tag), args=(f, acc)),
        latex=sp.latex(eq(sp.Function("f")(y), F * (1 - m * R * y / (I + m * R**2)))),
    )
    y_star = sp.expand(_solve_linear(eq(friction, 0), y))
    star = sp.Symbol("y^*", positive=True)
    zero = section.add(
        eq(star, y_star),
        f"The height y* where ({law.tag}) gives f = 0: no friction is needed for a pull there, "
        "whatever F (the percussion point).",
        "paper y1 = 2R, y2 = 3R/2; (M10)",
        how=How("solve", (law.tag,), args=(y,), given=(eq(f, 0),)),
    )
    gamma = sp.Symbol("gamma", positive=True)
    factor = section.add(
        eq(star, sp.factor(y_star.subs(I, gamma * m * R**2))),
        f"With I = gamma m R^2 in ({zero.tag}).",
        "(M10)",
        how=How("substitute", (zero.tag,), args=(I,), given=(eq(I, gamma * m * R**2),)),
    )
    heights = zero_friction_heights()
    names = {shape: _shape_height(shape) for shape in heights}
    gammas = {shape: sp.Symbol(f"gamma_{shape}", positive=True) for shape in heights}
    section.add(
        [eq(names[shape], h) for shape, h in heights.items()],
        f"({factor.tag}) for each shape: gamma = 1 (hoop), 1/2 (solid cylinder), 2/5 (solid "
        "sphere), 2/3 (thin spherical shell).",
        "paper Sec. 4: 2R (hoop), 3R/2 (cylinder)",
        how=How(
            "substitute",
            (),
            args=tuple(gammas.values()),
            law=[eq(names[shape], (1 + gammas[shape]) * R) for shape in heights],
            given=tuple(eq(gammas[shape], EXACT_INERTIA_FACTORS[shape]) for shape in heights),
        ),
    )
    return section, {
        "f": friction,
        "y_star": y_star,
        "phi_ddot": from_torque,
        "symbols": {"m": m, "R": R, "I": I, "F": F, "y": y},
    }


def _solve_linear(equation: sp.Eq, x: sp.Symbol) -> sp.Expr:
    """The root of an equation linear in x (``sp.solve`` costs most of a second here)."""
    expr = sp.expand(equation.lhs - equation.rhs)
    slope = expr.coeff(x)
    return sp.cancel(-(expr - slope * x) / slope)


def _shape_height(shape: str) -> sp.Symbol:
    """The display name y*(shape)."""
    return named(f"y^*_{shape}", rf"y^*_{{\mathrm{{{shape}}}}}", f"y*({shape})", positive=True)


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
    section = Section("Friction and normal forces", prefix="C", cites="paper Sec. 3, 4 and App. A")
    tags = setup_tags(sym)
    n = sym.n
    rolling = [i for i, b in enumerate(sym.bodies) if b.rolls]
    Fx = [sp.Symbol(f"F_{b.label}x", real=True) for b in sym.bodies]
    Fy = [sp.Symbol(f"F_{b.label}y", real=True) for b in sym.bodies]
    Q = [sp.Symbol(f"Q_{b.label}", real=True) for b in sym.bodies]
    f_syms = [sp.Symbol(f"f_{b.label}", real=True) for b in sym.bodies]
    n_syms = [sp.Symbol(f"N_{b.label}", real=True) for b in sym.bodies]
    results: dict[str, Any] = {}
    rates = f" ({tags['rates']})" if "rates" in tags else ""
    newton = section.add(
        [
            eq(f_syms[i], sym.bodies[i].m * sym.bodies[i].s * sym.bodies[i].qdd - Fx[i])
            for i in rolling
        ]
        + [eq(n_syms[i], sym.bodies[i].m * sym.g - Fy[i]) for i in range(n)],
        "Newton's second law for each centre, horizontally (it accelerates by x'' = R phi'', "
        f"the derivative of{rates}) and vertically (it keeps its height): friction f along +x, "
        "normal force N; F_ix and F_iy are the horizontal and vertical parts of the applied "
        "force on body i (springs, constant forces).",
        "(M8), (M9)",
        how=GIVEN,
    )
    equations = [eq(b.qdd, Q[i] / b.J) for i, b in enumerate(sym.bodies)]
    with_motion = None
    if rolling:
        with_motion = section.add(
            [
                eq(
                    f_syms[i],
                    Q[i] / ((1 + sym.bodies[i].gamma) * sym.bodies[i].R) - Fx[i],
                )
                for i in rolling
            ],
            "With the equation of motion I' phi'' = Q (Q the torque of the applied forces about "
            "the contact point): the friction depends on the configuration only, not on the "
            "velocities.",
            "(M8)",
            how=How(
                "substitute",
                (f"{newton.tag}:{','.join(str(k + 1) for k in range(len(rolling)))}",),
                args=tuple(sym.bodies[i].qdd for i in rolling),
                given=tuple(equations[i] for i in rolling),
            ),
        )
    small = n <= 4
    exact_forces = {
        **{Q[i]: sym.generalized_forces[i] for i in range(n)},
        **{Fx[i]: sym.body_forces[i][0] for i in range(n)},
        **{Fy[i]: sym.body_forces[i][1] for i in range(n)},
    }
    given = tuple(eq(k, v) for k, v in exact_forces.items())
    exact_f = sym.friction_configuration
    exact_n = sym.normal
    shown_f = [eq(f_syms[i], _compact(exact_f[i])) for i in rolling]
    shown_n = [eq(n_syms[i], _compact(exact_n[i])) for i in range(n)]
    normal_picks = ",".join(str(len(rolling) + i + 1) for i in range(n))
    exact_f_tag = exact_n_tag = None
    if small and all(sp.count_ops(e.rhs) < 250 for e in shown_f + shown_n):
        if with_motion is not None:
            exact_f_tag = section.add(
                shown_f,
                f"Exactly, in the angles (any amplitude): ({with_motion.tag}) with Q_i and the "
                "applied forces from the geometry (the spring tensions and directions).",
                "(M8)",
                how=How("substitute", (with_motion.tag,), args=(*Q, *Fx), given=given),
            ).tag
        exact_n_tag = section.add(
            shown_n,
            f"The normal forces of ({newton.tag}), exactly, with the applied forces from the "
            "geometry.",
            "(M9)",
            how=How("substitute", (f"{newton.tag}:{normal_picks}",), args=tuple(Fy), given=given),
        ).tag
    linear_f, linear_n = sym.linear_contact_forces
    if small:
        linear_f = [_compact(e) for e in linear_f]
        linear_n = [_compact(e) for e in linear_n]
    results["friction_linear"] = linear_f
    results["normal_linear"] = linear_n
    shown = [eq(f_syms[i], linear_f[i]) for i in rolling] + [
        eq(n_syms[i], linear_n[i]) for i in range(n)
    ]
    already_linear = exact_n_tag is not None and all(
        sp.expand(exact - linear) == 0
        for exact, linear in zip(
            [exact_f[i] for i in rolling] + list(exact_n),
            [linear_f[i] for i in rolling] + list(linear_n),
            strict=True,
        )
    )
    if already_linear:
        pass  # the exact forces are linear in the angles: their first order is themselves
    elif exact_n_tag is not None:
        sources = (exact_f_tag, exact_n_tag) if exact_f_tag else (exact_n_tag,)
        section.add(
            shown,
            "To first order in the angles about the reference: linearising ("
            + "), (".join(sources)
            + ").",
            "(M8), (M9)",
            how=How("linearise", sources),
        )
    else:
        section.add(
            shown,
            "To first order in the angles about the reference, from K and the derivatives of "
            "the applied forces there (docs/physics.md Sec. 7).",
            "(M8), (M9)",
            how=GIVEN,
        )
    lam = _percussion_ratios(sym)
    if lam is not None:
        lsyms = [sp.Symbol(f"lambda_{b.label}", positive=True) for b in sym.bodies]
        heights = [sp.Symbol(f"eta_{b.label}", positive=True) for b in sym.bodies]
        ratios = section.add(
            [
                eq(lsyms[i], heights[i] / ((1 + sym.bodies[i].gamma) * sym.bodies[i].R))
                for i in range(2)
            ],
            "The percussion ratios: lambda_i is the height eta_i where the spring's line "
            "crosses body i's centre vertical, over the percussion height (1 + gamma) R.",
            "(M10), (M16)",
            how=DEFINE,
        )
        eta_values = [eq(heights[i], _height(sym, i)) for i in range(2)]
        values = section.add(
            [eq(lsyms[i], lam[i]) for i in range(2)],
            f"With this system's heights eta_1 = {inline(_height(sym, 0))}, eta_2 = "
            f"{inline(_height(sym, 1))} in ({ratios.tag}).",
            "(M16)",
            how=How("substitute", (ratios.tag,), args=tuple(heights), given=tuple(eta_values)),
        )
        fx_sym = sp.Symbol("F_x", real=True)
        share = section.add(
            [eq(f_syms[0], -(1 - lam[0]) * fx_sym), eq(f_syms[1], (1 - lam[1]) * fx_sym)],
            f"With F_x the spring's horizontal pull on body 1 (body 2 gets -F_x): f_i = -(1 - "
            f"lambda_i) F_ix (docs/physics.md (M17)), with ({values.tag}).",
            "(M17); paper App. A: F/2 and F/3",
            how=How(
                "substitute",
                (values.tag,),
                args=tuple(lsyms),
                law=[
                    eq(f_syms[0], -(1 - lsyms[0]) * fx_sym),
                    eq(f_syms[1], (1 - lsyms[1]) * fx_sym),
                ],
            ),
        )
        if lam[1] != 1:
            ratio = sp.factor(-(1 - lam[0]) / (1 - lam[1]))
            section.add(
                eq(f_syms[0] / f_syms[1], ratio),
                f"Dividing the two of ({share.tag}): the ratio of the frictions, signed; the "
                "paper's f1/f2 = 3/2 is a ratio of magnitudes (they point opposite ways).",
                "paper f1/f2 = 3/2; (M17)",
                how=How("evaluate", (share.tag,)),
            )
            results["friction_ratio"] = ratio
        results["lambda"] = lam
    shapes = {b.shape for b in sym.bodies if b.rolls}
    if shapes:
        stars = [sp.Symbol(f"y^*_{b.label}", positive=True) for b in sym.bodies]
        section.add(
            [
                eq(stars[i], sp.factor((1 + b.gamma) * b.R))
                for i, b in enumerate(sym.bodies)
                if b.rolls
            ],
            "The height above each body's track where a pull needs no friction, y* = R + "
            "I/(mR) = (1 + gamma) R (derived in the App. A section).",
            "paper (fric) = 0; (M10)",
            how=GIVEN,
        )
    return section, results


def _height(sym: SymbolicSystem, i: int) -> sp.Expr:
    """The height above body i's contact where the spring (on its centre vertical) is
    attached."""
    spring = sym.springs[0]
    for at in spring.attachments:
        if at is not None and at.body == i and at.height is not None:
            return at.height
    return sym.bodies[i].R


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
    """A short form for display, factored as :func:`~.method.short` factors (the sign inside
    the bracket, so that the bodies' forces read alike)."""
    expr = sp.sympify(expr)
    if expr.count_ops() > 60 or expr.has(sp.sin, sp.cos, sp.sqrt(2).func):
        return expr
    try:
        factored = sign_inside(sp.factor(expr))
    except Exception:  # noqa: BLE001 - display only
        return expr
    return factored if sp.count_ops(factored) <= sp.count_ops(expr) else expr

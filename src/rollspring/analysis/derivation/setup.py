r"""The system set up once for every method: data, constraints, inertias, T, V, M and K.

Every method refers to these steps by their numbers (``S5``: the constraint relations,
``S7``: the inertias about the contact lines, ...) instead of restating them;
:func:`setup_tags` says which number holds what.
"""

from __future__ import annotations

import sympy as sp

from rollspring.analysis.derivation.steps import (
    GIVEN,
    How,
    Section,
    eq,
    inline,
    latex_of,
    matrix_equation,
    named,
)
from rollspring.analysis.derivation.symbolic import SymbolicSystem

__all__ = [
    "kinetic_general",
    "length_symbols",
    "rate_symbols",
    "setup_section",
    "setup_tags",
    "x_symbol",
    "xdot_symbol",
]


def x_symbol(sym: SymbolicSystem, i: int) -> sp.Symbol:
    """The centre's displacement :math:`x_i` (a slider's coordinate itself)."""
    body = sym.bodies[i]
    if not body.rolls:
        return body.q
    return sp.Symbol("x" + ("" if sym.n == 1 else f"_{body.label}"), real=True)


def xdot_symbol(sym: SymbolicSystem, i: int) -> sp.Symbol:
    """The centre's velocity :math:`\\dot x_i`."""
    body = sym.bodies[i]
    if not body.rolls:
        return body.qd
    return sp.Symbol("xdot" + ("" if sym.n == 1 else f"_{body.label}"), real=True)


def length_symbols(sym: SymbolicSystem) -> list[sp.Symbol]:
    """The names :math:`l_s` of the spring lengths."""
    one = len(sym.springs) == 1
    return [sp.Symbol("l" if one else f"l_{s.index + 1}", positive=True) for s in sym.springs]


def rate_symbols(sym: SymbolicSystem) -> dict[sp.Symbol, sp.Symbol]:
    """Each coordinate's rate and each rate's rate (:math:`\\varphi\\to\\dot\\varphi\\to
    \\ddot\\varphi`, :math:`x\\to\\dot x`, :math:`E\\to\\dot E`)."""
    rates: dict[sp.Symbol, sp.Symbol] = {}
    for i, b in enumerate(sym.bodies):
        rates[b.q] = b.qd
        rates[b.qd] = b.qdd
        rates[x_symbol(sym, i)] = xdot_symbol(sym, i)
    rates[sp.Symbol("E")] = sp.Symbol("Edot")
    return rates


def kinetic_general(sym: SymbolicSystem) -> sp.Expr:
    r""":math:`T = \sum_i \tfrac12 m_i\dot x_i^2 + \tfrac12 I_i\dot\varphi_i^2` (König)."""
    terms = []
    for i, b in enumerate(sym.bodies):
        terms.append(b.m * xdot_symbol(sym, i) ** 2 / 2)
        if b.rolls:
            terms.append(b.I * b.qd**2 / 2)
    return sp.Add(*terms)


def setup_tags(sym: SymbolicSystem) -> dict[str, str]:
    """The numbers of the setup's steps by what they hold: ``constraints``, ``rates``,
    ``inertia``, ``kinetic``, ``mass``, ``lengths``, ``potential``, ``stiffness``,
    ``quadratic``, ``values`` (the parameters' numbers; those the system has)."""
    setup_section(sym)
    tags: dict[str, str] = sym._cache["setup_tags"]
    return tags


def setup_section(sym: SymbolicSystem) -> Section:
    """The symbolic system: data, constraints, inertias, T, M, the exact V, equilibrium, K and
    V to second order (built once per system; every method refers to it)."""
    if "setup" in sym._cache:
        cached: Section = sym._cache["setup"]
        return cached
    section = Section(
        "The system in symbols" if sym.symbolic else "The system",
        prefix="S",
        rates=rate_symbols(sym),
    )
    tags: dict[str, str] = {}
    rows = []
    for b in sym.bodies:
        kind = f"{b.shape} (gamma = {b.gamma})" if b.rolls else "slider"
        rows.append(f"{b.label} = {kind}" if b.id == b.shape else f"{b.label} = {b.id}: {kind}")
    section.add(
        sp.Matrix([[b.q, b.m, b.R if b.rolls else sp.Integer(0), b.gamma] for b in sym.bodies]),
        "The bodies (data): " + "; ".join(rows) + ". Columns: coordinate, mass, radius, "
        "inertia factor gamma (I = gamma m R^2 about the centre).",
        "docs/physics.md Sec. 1",
        how=GIVEN,
    )
    if sym.symbolic and sym.values:
        tags["values"] = section.add(
            [eq(s, sp.Float(v, 6)) for s, v in sorted(sym.values.items(), key=lambda p: p[0].name)],
            "The numbers of this system (data, SI units).",
            how=GIVEN,
        ).tag
    if sym.springs:
        section.add(
            [matrix_equation(f"d_{s.index + 1}", sp.Matrix(s.d0).T) for s in sym.springs],
            "Each spring's vector from its first end to its second at the reference (data): "
            + _spring_words(sym),
            "(M1)",
            how=GIVEN,
        )
    if sym.conditions:
        tags["conditions"] = section.add(
            list(sym.conditions),
            "For this system's numbers the ends are at equal heights, so the spring is "
            "horizontal at the reference: a condition the parameters satisfy. The exact "
            "potential below holds without it (a tilted spring too); the expansions about "
            "the reference (K and after) use it.",
            "(M1); docs/physics.md Sec. 7.1",
            how=GIVEN,
        ).tag
    rolling = [i for i, b in enumerate(sym.bodies) if b.rolls]
    origin = "the equilibrium" if sym.reference == "equilibrium" else "the initial placement"
    if rolling:
        tags["constraints"] = section.add(
            [eq(x_symbol(sym, i), sym.bodies[i].s * sym.bodies[i].q) for i in rolling],
            "Rolling without slipping (the constraint relations): the contact point is at "
            "rest, so each centre moves R per radian turned; x and the angle are measured "
            f"from {origin}.",
            "paper (g1), (g2); (M1)",
            how=GIVEN,
        ).tag
        tags["rates"] = section.add(
            [eq(xdot_symbol(sym, i), sym.bodies[i].s * sym.bodies[i].qd) for i in rolling],
            f"Differentiating ({tags['constraints']}) in time: the centres' velocities.",
            "",
            how=How("differentiate in time", (tags["constraints"],)),
        ).tag
    sliders = [b for b in sym.bodies if not b.rolls]
    if sliders:
        section.add(
            [eq(_j_symbol(sym, b.index), b.m) for b in sliders],
            "Sliders on a frictionless floor (data): the coordinate is the displacement x; "
            "they do not turn, so the I' of their equations is the mass.",
            "(M4)",
            how=GIVEN,
        )
    if rolling:
        lines, eqs = [], []
        for i in rolling:
            b = sym.bodies[i]
            J = _j_symbol(sym, i)
            eqs.append(eq(J, b.I + b.m * b.R**2))
            lines.append(
                rf"I'_{{{b.label}}} &= I_{{{b.label}}} + m_{{{b.label}}} d^2"
                rf" = {latex_of(b.I)} + {latex_of(b.m * b.R**2)} = {latex_of(b.J)}"
            )
        tags["inertia"] = section.add(
            eqs,
            "Moments of inertia about the contact lines (the paper's I'), by Steiner's "
            "parallel-axis theorem: the central I plus m d^2 with d = R, the distance from the "
            "centre to the contact line.",
            "paper (I'1), (I'2); (M4)",
            how=GIVEN,
            latex=r"\begin{aligned}" + r" \\ ".join(lines) + r"\end{aligned}",
        ).tag
    tsym = sp.Symbol("T")
    general = kinetic_general(sym)
    tags["kinetic_general"] = section.add(
        eq(tsym, general),
        "Kinetic energy by König's theorem: the centre's translation plus the rotation about "
        "the centre.",
        "(M4)",
        how=GIVEN,
    ).tag
    if rolling:
        tags["kinetic"] = section.add(
            eq(tsym, sym.kinetic),
            f"Substituting the velocities ({tags['rates']}): each body's kinetic energy is "
            f"(1/2) I' phi'^2, a rotation about its contact line with I' of ({tags['inertia']}).",
            "(M4)",
            how=How(
                "substitute",
                (tags["kinetic_general"], tags["rates"]),
                args=tuple(xdot_symbol(sym, i) for i in rolling),
            ),
        ).tag
    else:
        tags["kinetic"] = tags["kinetic_general"]
    tags["mass"] = section.add(
        matrix_equation("M", sym.mass_matrix),
        f"Mass matrix, read off T = (1/2) q'^T M q' ({tags['kinetic']}): diagonal and "
        "constant for any geometry.",
        "(M4), (M12)",
        how=How("read off", (tags["kinetic"],), args=(tuple(sym.qd),)),
    ).tag
    if sym.springs:
        tags["lengths"] = section.add(
            [eq(name, s.length) for name, s in zip(length_symbols(sym), sym.springs, strict=True)],
            "Spring lengths l = |d| from the positions of their ends (M1), exactly: no small "
            "angles.",
            "(M1)",
            how=GIVEN,
        ).tag
    vsym = sp.Symbol("V")
    law = _potential_law(sym)
    forces = " minus the work of the constant forces" if sym.forces else ""
    relaxed = [s for s in sym.springs if s.relaxed]
    rest = (
        ""
        if not relaxed
        else " The rest length L equals the length at the reference, L = ℓ, for every spring "
        "relaxed there" + (" (each spring here)." if len(relaxed) == len(sym.springs) else ".")
    )
    tags["potential"] = section.add(
        eq(vsym, sym.potential),
        f"Potential energy: V = sum (1/2) k (l - L)^2 of the springs{forces}, with the "
        f"lengths l of ({tags['lengths']}) and the rest lengths L; gravity is a constant while "
        "the bodies roll (their centres keep their heights) and is left out." + rest
        if sym.springs
        else f"Potential energy{forces}; gravity is a constant while the bodies roll.",
        "(M5)",
        how=How("substitute", (tags["lengths"],), args=tuple(length_symbols(sym)), law=law)
        if sym.springs
        else How("given"),
    ).tag
    reference_forces = sym.reference_forces
    if any(f != 0 for f in reference_forces):
        if sym.symbolic:
            tags["equilibrium"] = section.add(
                [eq(f, 0) for f in reference_forces if f != 0],
                "The reference is an equilibrium: the generalised forces vanish there, "
                "conditions the parameters satisfy (pre-tensioned springs or constant forces).",
                "(M7)",
                how=GIVEN,
            ).tag
        else:
            section.add(
                matrix_equation(
                    "Q_0", sp.Matrix([sp.Float(sym.numeric(f), 3) for f in reference_forces])
                ),
                "Generalised forces at the reference: zero to rounding (the equilibrium "
                "angles are found numerically; the exact numbers carry it).",
                "(M7)",
                how=GIVEN,
            )
    tags["stiffness"] = section.add(
        matrix_equation("K", sym.stiffness_matrix),
        f"Stiffness matrix: the second derivatives of V ({tags['potential']}) at the "
        "reference q = 0.",
        "(M12), (M13)",
        how=How("second derivative", (tags["potential"],), args=(tuple(sym.q),)),
    ).tag
    tags["quadratic"] = section.add(
        eq(vsym, sym.quadratic_potential),
        f"V to second order about the reference (Taylor): (1/2) q^T K q with K of "
        f"({tags['stiffness']})"
        + (" and the linear term of the equilibrium conditions." if "equilibrium" in tags else "."),
        "(M12)",
        how=How("expand to second order", (tags["potential"],), args=(tuple(sym.q),)),
    ).tag
    sym._cache["setup"] = section
    sym._cache["setup_tags"] = tags
    return section


def _j_symbol(sym: SymbolicSystem, i: int) -> sp.Symbol:
    """The paper's I'_i: body i's moment of inertia about its contact line (a slider's mass)."""
    label = "" if sym.n == 1 else sym.bodies[i].label
    text = "I\u2032" + "".join("₀₁₂₃₄₅₆₇₈₉"[int(c)] for c in label)
    return named(
        f"Iprime_{label}" if label else "Iprime",
        f"I'_{{{label}}}" if label else "I'",
        text,
        positive=True,
    )


def _potential_law(sym: SymbolicSystem) -> sp.Eq:
    """V = sum (1/2) k (l - L)^2 - sum F . (P - P0), the lengths as names."""
    terms = [
        s.k * (name - s.L) ** 2 / 2
        for name, s in zip(length_symbols(sym), sym.springs, strict=True)
    ]
    return eq(sp.Symbol("V"), sp.Add(*terms, *sym.force_potentials))


def _spring_words(sym: SymbolicSystem) -> str:
    words = []
    if not sym.symbolic:
        return "its horizontal and vertical parts, in metres."
    for s in sym.springs:
        across, rise = s.d0
        if rise == 0:
            words.append(f"spring {s.index + 1} is horizontal, {inline(abs(across))} long")
        elif s.beta is not None and s.beta.is_Symbol:
            words.append(
                f"spring {s.index + 1} is {inline(s.ell)} long, tilted by {inline(s.beta)} "
                "above the horizontal"
            )
        else:
            words.append(
                f"spring {s.index + 1} spans {inline(abs(across))} horizontally and rises by "
                "the difference of its ends' heights above the floor"
            )
    return "; ".join(words) + "."

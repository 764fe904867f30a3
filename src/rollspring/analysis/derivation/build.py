r"""``symbolic_system(system)``: the SymPy form of a validated System, its parameters named after
the paper's notation and its springs' geometry taken at the reference configuration.

The reference is the equilibrium nearest the initial placement
(:func:`rollspring.analysis.find_equilibrium`), or the initial placement when there is none.
Each number of the system becomes an exact rational or, with ``symbols=True``, a symbol whose
value is recorded (:attr:`~.symbolic.SymbolicSystem.values`); a spring whose ends are level
only for this system's numbers adds a condition (:attr:`~.symbolic.SymbolicSystem.conditions`).

``symbols=False``: every number is an exact rational (the system's decimal values; the inertia
factors of the built-in shapes exactly: 1, 1/2, 2/5, 2/3). ``symbols=True``: masses
:math:`m_i`, radii :math:`R_i` (one :math:`R` when all radii are equal), stiffnesses :math:`k`
(or :math:`k_s`), spring lengths :math:`\ell_s`, tilts :math:`\beta_s` (0 when horizontal),
rest lengths :math:`L_s` (only for springs under tension at the reference), attachment heights
(:math:`2R_1`, :math:`\tfrac32R_2` when a simple multiple of the radius, else :math:`y_i`),
radii :math:`r_i` and angles, forces :math:`F`, gravity :math:`g`; the shapes give their inertia
factors (a ``custom`` shape gets :math:`\gamma_i`). ``values`` holds every symbol's number.
"""

from __future__ import annotations

import math
import os
from fractions import Fraction
from typing import Any

import numpy as np
import sympy as sp
from sympy.physics.mechanics import dynamicsymbols

from rollspring.analysis.derivation.parts import (
    EXACT_INERTIA_FACTORS,
    Attachment,
    SymbolicBody,
    SymbolicForce,
    SymbolicSpring,
    exact_number,
)
from rollspring.analysis.derivation.symbolic import SymbolicSystem
from rollspring.analysis.linear import find_equilibrium
from rollspring.model import Attachment as ModelAttachment
from rollspring.model import System
from rollspring.physics import end_kinematics, spring_state, system_arrays

__all__ = ["symbolic_system"]


_ZERO_TILT = 1e-12  # |d_y| / l below this: the spring is horizontal at the reference
_ZERO_TENSION = 1e-9  # |l - L0| / l below this: the spring is at rest length at the reference
_ZERO_ANGLE = 1e-12  # |q*| below this (rad or m): the body did not move to reach equilibrium


def _nice_ratio(value: float) -> sp.Rational | None:
    """``value`` as p/q with q <= 12, if it is one (to 1e-12), else None."""
    if not math.isfinite(value):
        return None
    candidate = Fraction(repr(float(value))).limit_denominator(12)
    if abs(float(candidate) - value) <= 1e-12 * max(1.0, abs(value)):
        return sp.Rational(candidate.numerator, candidate.denominator)
    return None


class _Namer:
    """Symbols named after the paper's notation, with their numbers recorded."""

    def __init__(self, symbolic: bool) -> None:
        self.symbolic = symbolic
        self.values: dict[sp.Symbol, float] = {}

    def __call__(self, name: str, value: float, **assumptions: bool) -> sp.Expr:
        if not self.symbolic:
            return exact_number(value)
        symbol = sp.Symbol(name, **assumptions)
        previous = self.values.get(symbol)
        if previous is not None and previous != value:
            raise ValueError(f"symbol {name} used for two values")  # a naming bug
        self.values[symbol] = float(value)
        return symbol


def symbolic_system(
    system: System | dict[str, Any] | str | os.PathLike[str], *, symbols: bool = False
) -> SymbolicSystem:
    """The SymPy form of a validated :class:`~rollspring.model.System`.

    ``symbols=False``: exact rational numbers; ``symbols=True``: parameters as symbols (see the
    module docstring). Coordinates are measured from the equilibrium nearest the initial
    placement (from :func:`rollspring.analysis.find_equilibrium`; the initial placement when
    there is none). ``system`` may also be its JSON form, a file path or a preset name
    (:func:`rollspring.model.as_system`).
    """
    from rollspring.model import as_system

    system = as_system(system)
    arrays = system_arrays(system)
    n = arrays.n_bodies
    equilibrium = find_equilibrium(arrays)
    q_ref = np.array(equilibrium.q, dtype=float) if equilibrium.found else np.zeros(n)
    q_ref = np.where(np.abs(q_ref) < _ZERO_ANGLE, 0.0, q_ref)
    reference = "equilibrium" if equilibrium.found else "initial placement"
    name = _Namer(symbols)

    rolling = [b for b in system.bodies if b.rolls]
    one_radius = len({b.radius for b in rolling}) == 1 and (len(rolling) > 1 or n == 1)
    single = n == 1

    def sub(base: str, label: str) -> str:
        return base if single else f"{base}_{label}"

    bodies = []
    for i, b in enumerate(system.bodies):
        label = str(i + 1)
        m = name(sub("m", label), b.mass, positive=True)
        if b.rolls:
            R = name("R" if one_radius else sub("R", label), b.radius, positive=True)
        else:
            R = exact_number(b.radius)  # a slider's drawing size: no role in its mechanics
        if b.shape == "custom":
            gamma = name(sub("gamma", label), float(b.gamma), positive=True)
        else:
            gamma = EXACT_INERTIA_FACTORS[b.shape]
        base = "phi" if b.rolls else "x"
        tail = "" if single else f"_{label}"
        q = sp.Symbol(base + tail, real=True)
        fn = dynamicsymbols(base + tail)
        qd = sp.Symbol(f"{base}dot{tail}", real=True)
        qdd = sp.Symbol(f"{base}ddot{tail}", real=True)
        bodies.append(SymbolicBody(i, b.id, b.shape, b.rolls, m, R, gamma, q, qd, qdd, fn))
    bodies_t = tuple(bodies)
    index = {b.id: i for i, b in enumerate(system.bodies)}

    # attachment naming: a body with one off-centre attachment gets short names (y_1, r_1)
    uses: dict[int, int] = {}
    for spring in system.springs:
        for end, at in zip(spring.ends, spring.attachments, strict=True):
            if end in index and not at.is_centre_form:
                uses[index[end]] = uses.get(index[end], 0) + 1
    for force in system.forces:
        if not force.at.is_centre_form:
            uses[index[force.body]] = uses.get(index[force.body], 0) + 1

    def attachment(body_index: int, at: ModelAttachment, where: str) -> Attachment:
        body = bodies_t[body_index]
        model = system.bodies[body_index]
        r_value, alpha = at.polar(model)
        moved = float(q_ref[body_index]) * (1.0 if model.rolls else 0.0)
        label = body.label if single is False else ""
        if r_value == 0.0:
            return Attachment(
                body_index, sp.Integer(0), sp.Integer(0), body.R if model.rolls else None
            )
        if at.height is not None and moved == 0.0:
            many = uses.get(body_index, 0) > 1
            ratio = _nice_ratio(at.height / model.radius)
            if ratio is not None and symbols:
                height = ratio * body.R
            else:
                nm = "y" + (f"_{label},{where}" if many else (f"_{label}" if label else ""))
                height = name(nm, at.height, positive=True)
            return Attachment(body_index, height - body.R, sp.Integer(0), height)
        many = uses.get(body_index, 0) > 1
        ratio = _nice_ratio(r_value / model.radius)
        if ratio is not None and symbols:
            r = ratio * body.R
        else:
            nm = "r" + (f"_{label},{where}" if many else (f"_{label}" if label else ""))
            r = name(nm, r_value, positive=True)
        theta_value = alpha + moved
        degrees = _nice_ratio(math.degrees(theta_value) / 15.0) if moved == 0.0 else None
        if degrees is not None:
            theta0 = sp.pi * degrees / 12
        elif symbols:
            nm = "theta" + (f"_{label},{where}" if many else (f"_{label}" if label else ""))
            theta0 = name(nm, theta_value, real=True)
        else:
            theta0 = exact_number(theta_value)
        return Attachment(body_index, r, theta0, None)

    # reference geometry of the springs (at the equilibrium)
    ref_state = spring_state(arrays, q_ref) if arrays.n_springs else None
    position, _, _ = end_kinematics(arrays, q_ref) if arrays.n_springs else (None, None, None)
    n_springs = len(system.springs)
    springs = []
    conditions: list[sp.Eq] = []
    lifted = [i for i, b in enumerate(system.bodies) if b.track_height != 0.0]

    def track(i: int) -> sp.Expr:
        """Body i's track height above the lowest floor (a symbol h_i where it is not 0)."""
        if i not in lifted:
            return sp.Integer(0)
        return name(sub("h", str(i + 1)), system.bodies[i].track_height, real=True)

    for s, spring in enumerate(system.springs):
        assert position is not None and ref_state is not None  # there are springs
        label = str(s + 1)
        only = n_springs == 1
        k = name("k" if only else f"k_{label}", spring.stiffness, positive=True)
        dx, dy = (position[s, 1] - position[s, 0]).tolist()
        length = float(ref_state.length[s])
        rest = float(arrays.rest_length[s])
        horizontal = abs(dy) <= _ZERO_TILT * length
        relaxed = abs(length - rest) <= _ZERO_TENSION * length
        ats: list[Attachment | None] = []
        for end, at in zip(spring.ends, spring.attachments, strict=True):
            ats.append(attachment(index[end], at, label) if end in index else None)
        rise = _rise(ats, bodies_t, track) if symbols else None
        ell_name = "ell" if only else f"ell_{label}"
        e0: tuple[sp.Expr, sp.Expr]
        if rise is not None and sp.expand(rise) != 0:
            # the vertical part in the parameters: exact for any sizes (a tilted spring too)
            ell = name(ell_name, abs(dx), positive=True)
            across = ell if dx > 0 else -ell
            d0 = (across, rise)
            if horizontal:  # level for this system's numbers only: a condition on them
                heights = [_end_height(a, bodies_t, track) for a in ats]
                assert heights[0] is not None and heights[1] is not None  # rise is known
                conditions.append(sp.Eq(heights[0], heights[1], evaluate=False))
                e0 = (sp.sign(across), sp.Integer(0))
            else:
                ell = sp.sqrt(ell**2 + rise**2)
                e0 = (across / ell, rise / ell)
            beta = sp.atan2(rise, across)
            general_length = sp.sqrt(across**2 + rise**2)
        else:
            ell = name(ell_name, length, positive=True)
            if horizontal:
                beta = sp.Integer(0) if dx > 0 else sp.pi
            elif symbols:
                beta = name("beta" if only else f"beta_{label}", math.atan2(dy, dx), real=True)
            else:
                beta = None
            if symbols or horizontal:
                d0 = (ell * sp.cos(beta), ell * sp.sin(beta))
            else:  # exact numbers: the reference vector itself
                d0x, d0y = exact_number(dx), exact_number(dy)
                ell = sp.sqrt(d0x**2 + d0y**2)
                beta = sp.atan2(d0y, d0x)
                d0 = (d0x, d0y)
            e0 = (sp.cos(beta), sp.sin(beta)) if horizontal else (d0[0] / ell, d0[1] / ell)
            general_length = ell
        L = (
            general_length
            if relaxed
            else name("L" if only else f"L_{label}", rest, nonnegative=True)
        )
        moves = [a.displacement(bodies_t[a.body]) if a is not None else (0, 0) for a in ats]
        vx = d0[0] + moves[1][0] - moves[0][0]
        vy = d0[1] + moves[1][1] - moves[0][1]
        level = horizontal and (rise is None or sp.expand(rise) == 0)
        stays = level and all(a is None or a.r == 0 for a in ats)
        if stays:
            vy = sp.Integer(0)
            exact_length = vx if dx > 0 else -vx
        else:
            exact_length = sp.sqrt(vx**2 + vy**2)
        springs.append(
            SymbolicSpring(
                s,
                arrays.spring_names[s],
                (spring.ends[0], spring.ends[1]),
                (ats[0], ats[1]),
                k,
                L,
                ell,
                beta,
                d0,
                (vx, vy),
                exact_length,
                stays,
                e0,
                relaxed,
            )
        )

    forces = []
    n_forces = len(system.forces)
    for f, force in enumerate(system.forces):
        label = "" if n_forces == 1 else f",{f + 1}"
        point = attachment(index[force.body], force.at, f"F{f + 1}")
        if force.fx != 0.0 and force.fy == 0.0 and n_forces == 1:
            Fx, Fy = name("F", force.fx, real=True), sp.Integer(0)
        else:
            Fx = name(f"F_x{label}", force.fx, real=True) if force.fx != 0.0 else sp.Integer(0)
            Fy = name(f"F_y{label}", force.fy, real=True) if force.fy != 0.0 else sp.Integer(0)
        forces.append(SymbolicForce(f, index[force.body], point, Fx, Fy))

    g = name("g", system.gravity, positive=True)
    notes = []
    if not equilibrium.found:
        notes.append(
            "no equilibrium near the initial placement: coordinates are measured from "
            "the initial placement and the expansions are about it"
        )
    if any(s.damping > 0 for s in system.springs):
        notes.append("spring damping is left out of the derivations (conservative forces only)")
    if any(b.rolling_resistance > 0 for b in system.bodies):
        from rollspring.analysis.derivation.resistance import RESISTANCE_NOTE

        notes.append(RESISTANCE_NOTE)
    return SymbolicSystem(
        system=system,
        symbolic=symbols,
        bodies=bodies_t,
        springs=tuple(springs),
        forces=tuple(forces),
        g=g,
        values=dict(name.values),
        reference=reference,
        q_reference=q_ref,
        notes=notes,
        conditions=conditions,
    )


def _end_height(
    at: Attachment | None, bodies: tuple[SymbolicBody, ...], track: Any
) -> sp.Expr | None:
    """The height of a spring end above the lowest floor at the reference, in the parameters
    (None for an anchor: its height is a number of the system, not a parameter)."""
    if at is None:
        return None
    body = bodies[at.body]
    if at.height is not None:
        above = at.height
    elif at.r == 0:
        above = body.R
    else:
        above = body.R + at.r * sp.cos(at.theta0)
    return track(at.body) + above


def _rise(
    ats: list[Attachment | None], bodies: tuple[SymbolicBody, ...], track: Any
) -> sp.Expr | None:
    """End b's height minus end a's, in the parameters (None if an end is an anchor)."""
    heights = [_end_height(a, bodies, track) for a in ats]
    if heights[0] is None or heights[1] is None:
        return None
    return sp.expand(heights[1] - heights[0])

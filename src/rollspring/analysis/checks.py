"""Physics checks on a linear analysis: slipping, lift-off, and where the paper's claims fail.

Each check returns plain sentences for ``LinearAnalysis.warnings``; they are reported by
``rollspring analyze`` (on stderr with ``--json``, and in the JSON's ``"warnings"``).
"""

from __future__ import annotations

import math

import numpy as np

from rollspring.analysis.linear import LinearAnalysis
from rollspring.physics import end_kinematics, potential_energy

__all__ = [
    "is_exactly_linear",
    "percussion_attachments",
    "physics_warnings",
    "zero_mode_potential_change",
]


def physics_warnings(analysis: LinearAnalysis) -> list[str]:
    """All warnings about the physics of an analysed system (see the module docstring)."""
    out: list[str] = []
    out += _contact_warnings(analysis)
    out += _percussion_warnings(analysis)
    out += _geometry_warnings(analysis)
    out += _amplitude_warnings(analysis)
    out += _zero_mode_warnings(analysis)
    return out


def _contact_warnings(analysis: LinearAnalysis) -> list[str]:
    """Slipping and lift-off, at equilibrium and in the linear motion (docs/physics.md
    section 9)."""
    arrays = analysis.arrays
    out = []
    for i, body in enumerate(arrays.ids):
        mu = float(arrays.mu_static[i])
        f_eq, n_eq = analysis.equilibrium_friction[i], analysis.equilibrium_normal[i]
        rolls = arrays.rolls[i] > 0
        if n_eq < 0:
            out.append(
                f"'{body}' cannot rest on its track: the springs pull it up harder than "
                f"gravity holds it (N = {n_eq:.6g} N at equilibrium)"
            )
        elif rolls and f_eq != 0 and not math.isinf(mu) and abs(f_eq) > mu * n_eq:
            requirement = (
                "unbounded friction (N = 0)" if n_eq == 0 else f"mu_s >= {abs(f_eq) / n_eq:.6g}"
            )
            out.append(
                f"'{body}' cannot rest at the equilibrium without slipping: it needs "
                f"{requirement}, it has {mu:g}"
            )
        if analysis.required_mu is None or analysis.normal_force_range is None:
            continue
        low = float(analysis.normal_force_range[i][0])
        if low < 0 <= n_eq:
            out.append(
                f"'{body}' would lift off: in the linear motion its normal force reaches "
                f"{low:.6g} N"
            )
            continue
        if not rolls:
            continue
        needed = float(analysis.required_mu[i])
        if math.isinf(mu):
            continue  # rolling enforced (rack and pinion): it never slips
        if math.isinf(needed) and n_eq >= 0:
            out.append(
                f"'{body}' needs unbounded friction: its normal force reaches 0 while "
                f"friction is needed, so it slips unless rolling is enforced (mu_s = inf)"
            )
        elif needed > mu:
            out.append(f"'{body}' slips: the motion needs mu_s >= {needed:.6g}, it has {mu:g}")
    drift = analysis.drift_velocity
    if drift is not None and np.any(drift != 0) and analysis.stationary_weights is None:
        moving = ", ".join(
            f"'{b}' {v:.6g} m/s" for b, v in zip(arrays.ids, drift, strict=True) if v != 0
        )
        out.append(
            f"parts of the system drift freely (zero modes set moving by the initial "
            f"velocities): {moving}; amplitudes are about the drifting equilibrium"
        )
    return out


def percussion_attachments(analysis: LinearAnalysis) -> list[tuple[int, int, int]]:
    """Spring ends whose spring line passes through their body's percussion point, at
    equilibrium: (spring, end, body).

    The percussion point S lies on the vertical through the centre at height (1 + gamma) R above
    the contact; a force whose line passes through it needs no static friction, whatever its
    direction (lambda = 1, docs/physics.md (M10)); the paper's y1 = 2R (hoop) and y2 = 1.5R
    (cylinder).
    """
    arrays = analysis.arrays
    position, _, _ = end_kinematics(arrays, analysis.equilibrium.q)
    x_centre = arrays.x0 + arrays.scale * analysis.equilibrium.q
    found = []
    for s in range(arrays.n_springs):
        d = position[s, 1] - position[s, 0]
        if not np.hypot(*d) > 0:  # ends that meet (rest length 0): no line of force
            continue
        e = d / np.hypot(*d)
        for j in range(2):
            i = int(arrays.end_body[s, j])
            if i < 0 or arrays.rolls[i] == 0:
                continue
            percussion = np.array(
                [x_centre[i], arrays.track[i] + (1 + arrays.gamma[i]) * arrays.radius[i]]
            )
            offset = percussion - position[s, j]
            if abs(e[0] * offset[1] - e[1] * offset[0]) < 1e-9 * arrays.radius[i]:
                found.append((s, j, i))
    return found


def _percussion_warnings(analysis: LinearAnalysis) -> list[str]:
    arrays = analysis.arrays
    out = []
    ends = percussion_attachments(analysis)
    oscillating = analysis.oscillating
    spring_force_scale = max(
        (float(np.max(np.abs(arrays.stiffness * m.spring_extension))) for m in oscillating),
        default=0.0,
    )
    for s, _j, i in ends:
        body = arrays.ids[i]
        per_mode = [abs(float(m.friction[i])) for m in oscillating]
        if spring_force_scale > 0 and max(per_mode, default=0.0) > 1e-9 * spring_force_scale:
            out.append(
                f"spring '{arrays.spring_names[s]}' is attached at the percussion height of "
                f"'{body}' ({(1 + arrays.gamma[i]) * arrays.radius[i]:.6g} m above its track), "
                f"yet '{body}' still needs friction in the motion: other forces act on it"
            )
    # both ends of one spring at percussion points: the paper's Fig. 3 idea
    by_spring: dict[int, list[int]] = {}
    for s, _j, i in ends:
        by_spring.setdefault(s, []).append(i)
    for s, bodies in by_spring.items():
        if len(bodies) != 2:
            continue
        tilt = float(analysis.spring_tilt_deg[s])
        if abs(tilt) < 1e-9:
            continue
        i1, i2 = bodies
        name1, name2 = arrays.ids[i1], arrays.ids[i2]
        h1 = arrays.track[i1] + (1 + arrays.gamma[i1]) * arrays.radius[i1]
        h2 = arrays.track[i2] + (1 + arrays.gamma[i2]) * arrays.radius[i2]
        cos2 = math.cos(math.radians(tilt)) ** 2
        ratio = (1 + arrays.gamma[i2]) / (1 + arrays.gamma[i1])
        hint = (
            f"; a horizontal spring needs equal percussion heights "
            f"h + (1 + gamma) R: on one floor R_{name1}/R_{name2} = {ratio:.6g}"
        )
        shapes = {analysis.system.bodies[i1].shape, analysis.system.bodies[i2].shape}
        if shapes == {"hoop", "cylinder"}:
            hint += (
                " (the paper's Fig. 3 condition R1 = R2/2 holds only with the centres level,"
                " the hoop's track raised by R1)"
            )
        out.append(
            f"spring '{arrays.spring_names[s]}' joins the percussion points of '{name1}' and "
            f"'{name2}' but is tilted {tilt:.4g}° (heights {h1:.6g} m and {h2:.6g} m): friction "
            f"vanishes only to first order, Omega^2 is scaled by cos^2(tilt) = {cos2:.6g}, and "
            f"the normal forces oscillate{hint}"
        )
    return out


def _geometry_warnings(analysis: LinearAnalysis) -> list[str]:
    arrays = analysis.arrays
    out = []
    for s in range(arrays.n_springs):
        for j in range(2):
            i = int(arrays.end_body[s, j])
            if i >= 0 and arrays.end_r[s, j] > arrays.radius[i] * (1 + 1e-12):
                out.append(
                    f"spring '{arrays.spring_names[s]}' is attached to '{arrays.ids[i]}' "
                    f"{arrays.end_r[s, j]:.6g} m from its centre, outside its radius "
                    f"{arrays.radius[i]:.6g} m (a rigid arm is assumed)"
                )
    return out


def is_exactly_linear(analysis: LinearAnalysis) -> bool:
    """True when the equations of motion are linear at any amplitude (docs/physics.md section 8):
    every spring attached at centres (or anchors) and horizontal, external forces at centres,
    and no rolling resistance (its sign follows the motion, section 5.1)."""
    return _linear_geometry(analysis) and not analysis.arrays.resisted


def _linear_geometry(analysis: LinearAnalysis) -> bool:
    """The springs and forces give forces linear in the coordinates at any amplitude."""
    arrays = analysis.arrays
    centres = bool(np.all(arrays.end_r == 0)) and bool(np.all(arrays.force_r == 0))
    return centres and bool(np.all(analysis.spring_tilt_deg == 0))


def _amplitude_warnings(analysis: LinearAnalysis) -> list[str]:
    arrays = analysis.arrays
    if analysis.amplitude is None or _linear_geometry(analysis):
        return []
    out = []
    for i, body in enumerate(arrays.ids):
        if arrays.rolls[i] == 0:
            continue
        angle = float(analysis.amplitude[i] / arrays.radius[i])
        if angle > 0.2:
            out.append(
                f"'{body}' turns by up to {angle:.3g} rad: the linear results are only "
                f"approximate at this amplitude (the springs tilt as the bodies turn)"
            )
    return out


#: Samples of the exact potential along a zero mode, over a quarter turn each way.
_ZERO_MODE_SAMPLES = 41


def zero_mode_potential_change(analysis: LinearAnalysis) -> float | None:
    r"""How far the single zero mode :math:`v_0` (:math:`K v_0 = 0`, (M14)) is from a symmetry
    of the exact motion: the range (J) of the exact potential (M5)

    .. math:: \Delta U = \max_d U(q_{eq} + d\,v_0) - \min_d U(q_{eq} + d\,v_0),
              \qquad |d| \le \tfrac{\pi}{2} R_{\min}

    along it (``shape_q`` normalised to a largest centre displacement of 1 m, so :math:`d` is in
    metres: up to a quarter of the smallest rolling body's circumference). Zero to rounding
    when every spring is at the centres (the conserved (M11) is then exact); positive when the
    springs' ends turn with the bodies, so that moving along the linear zero mode stretches
    them at second order (docs/physics.md §8). None without exactly one zero mode or a found
    equilibrium."""
    zero = [mode for mode in analysis.modes if mode.kind == "zero"]
    arrays = analysis.arrays
    if len(zero) != 1 or not analysis.equilibrium.found or not np.any(arrays.rolls):
        return None
    reach = 0.5 * math.pi * float(np.min(arrays.radius[arrays.rolls > 0]))
    steps = np.linspace(-reach, reach, _ZERO_MODE_SAMPLES)
    states = analysis.equilibrium.q + steps[:, None] * zero[0].shape_q
    return float(np.ptp(potential_energy(arrays, states)))


def _zero_mode_warnings(analysis: LinearAnalysis) -> list[str]:
    """The stationary point is conserved only to first order when the zero mode is not a
    symmetry of the exact potential (:func:`zero_mode_potential_change`)."""
    arrays = analysis.arrays
    if _linear_geometry(analysis) or not arrays.n_springs:
        return []
    change = zero_mode_potential_change(analysis)
    reach = 0.5 * math.pi * float(np.min(arrays.radius[arrays.rolls > 0], initial=np.inf))
    scale = 0.5 * float(np.max(arrays.stiffness)) * reach**2
    if change is None or not change > 1e-9 * scale:
        return []
    zero = next(mode for mode in analysis.modes if mode.kind == "zero")
    shape = " : ".join(f"{value:.4g}" for value in zero.shape_x)
    names = ", ".join(arrays.ids)
    return [
        f"the zero mode (centres {names} moving {shape}) is free only to first order: the "
        f"spring ends turn with the bodies, so the exact potential changes by {change:.3g} J "
        f"within ±{reach:.3g} m along it; the stationary point X̂ stays put only at small "
        "amplitudes, and a finite oscillation can make the system creep along this mode "
        "(docs/physics.md §8; for the paper's Fig. 3 pair the creep grows about as "
        "exp(0.5 a Ω t), a the angular amplitude: see rollspring paper-check)"
    ]

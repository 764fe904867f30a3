"""The general state (any body may slip): its time derivative, and what is observed of rows of
states (contact forces, spring lengths and tensions, energies, friction ratios, their extremes).
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

from rollspring.simulate.kernels import model as col
from rollspring.simulate.kernels.forces import (
    _load_ends,
    _load_forces,
    _point,
    _spring_geometry,
    body_loads,
)
from rollspring.simulate.kernels.law import (
    elastic_tension,
    generalized_force,
    is_level,
    kinetic_friction,
    needed_friction,
    normal_force,
    resistance_limit,
    rolling_resistance,
    spring_energy,
    work,
)

__all__ = [
    "observe",
    "observe_rolling",
    "resistance_drives",
    "row_extremes",
    "slipping_derivatives",
]


@njit(cache=True, error_model="numpy")
def slipping_derivatives(model, state, slipping, sign, spin, damped, out):
    r"""Time derivative of the general state ``[x, phi, u, omega]`` (4n), docs/physics.md (M19),
    (M21).

    Rolling body: :math:`J\dot\omega = R F_x + \tau + \Gamma`, :math:`\dot u = R\dot\omega`;
    slider: :math:`m\dot u = F_x`; slipping body (``slipping[i]``, slip direction ``sign[i]`` =
    sign of the contact-point velocity :math:`v_s = u - R\omega`): :math:`f = -\mu_k N\,
    \mathrm{sign}`, :math:`m\dot u = F_x + f`, :math:`I\dot\omega = \tau - R f + \Gamma`.
    :math:`\Gamma = -C_{rr} N R\,\mathrm{spin}` is the rolling resistance (M21) of a body with
    :math:`C_{rr} > 0` turning with ``spin[i]`` = sign of :math:`\omega`; ``spin[i]`` 0 holds its
    rotation (and, rolling, its centre) at rest (M22).
    """
    n = slipping.shape[0]
    b, g = model[0], model[5]
    x = state[:n]
    phi = state[n : 2 * n]
    u = state[2 * n : 3 * n]
    w = state[3 * n :]
    ns = model[1].shape[0]
    fx = np.empty(n)
    fy = np.empty(n)
    tau = np.empty(n)
    length = np.empty(ns)
    tension = np.empty(ns)
    body_loads(model, x, phi, u, w, damped, fx, fy, tau, length, tension)
    for i in range(n):
        out[i] = u[i]
        out[n + i] = w[i]
        c_rr = b[i, col.C_RR]
        if b[i, col.ROLLS] == 0.0:
            out[2 * n + i] = fx[i] / b[i, col.MASS]
            out[3 * n + i] = 0.0
        elif slipping[i]:
            normal = normal_force(b[i, col.MASS] * g, fy[i])
            friction = kinetic_friction(b[i, col.MU_K], normal, sign[i])
            out[2 * n + i] = (fx[i] + friction) / b[i, col.MASS]
            drive = tau[i] - b[i, col.RADIUS] * friction
            if c_rr > 0.0:
                if spin[i] == 0.0:
                    drive = 0.0
                else:
                    drive += rolling_resistance(c_rr, normal, b[i, col.RADIUS], spin[i])
            out[3 * n + i] = drive / b[i, col.CENTRAL]
        else:
            gen = generalized_force(b[i, col.SCALE], fx[i], tau[i])
            if c_rr > 0.0:
                if spin[i] == 0.0:
                    gen = 0.0
                else:
                    normal = normal_force(b[i, col.MASS] * g, fy[i])
                    gen += rolling_resistance(c_rr, normal, b[i, col.SCALE], spin[i])
            alpha = gen / b[i, col.INERTIA]
            out[2 * n + i] = b[i, col.SCALE] * alpha
            out[3 * n + i] = alpha


@njit(cache=True, error_model="numpy")
def observe(
    model,
    states,
    slipping,
    sign,
    spin,
    damped,
    friction,
    normal,
    length,
    tension,
    potential,
    central,
    ratio,
    kinetic,
):
    r"""Per row of ``states`` (rows of ``[x, phi, u, omega]``): friction (the static friction
    a rolling body needs, (M8), or the kinetic friction of a slipping body, (M19)), normal force
    (M9), spring lengths and tensions, the potential energy
    :math:`U = \sum \tfrac12 k(l - L_0)^2 - \sum F\cdot(P - P_0)` (gravity left out; P_0 at the
    model's reference positions, so pass the model of the initial placement), the kinetic
    energy :math:`\sum \tfrac12 (m_i u_i^2 + I_i \omega_i^2)` (``central`` holds the central
    inertias :math:`I_i`) and the friction ratio :math:`|f|/(\mu_s N)` (0 for sliders and for
    :math:`\mu_s = \infty`, :math:`\infty` when :math:`N \le 0`).
    ``slipping``/``sign``/``spin`` are per row (``spin``: :func:`slipping_derivatives`'; a
    rolling body with rolling resistance needs the friction of (M8) with the resistance's
    torque (M21) beside Q, or, held at rest (``spin`` 0), :math:`f = -F_x`)."""
    n = states.shape[1] // 4
    b, springs, forces, force_body, g = model[0], model[1], model[3], model[4], model[5]
    fx = np.empty(n)
    fy = np.empty(n)
    tau = np.empty(n)
    zero_x = b[:, col.X0].copy()
    zero_phi = np.zeros(n)
    for row in range(states.shape[0]):
        state = states[row]
        x = state[:n]
        phi = state[n : 2 * n]
        body_loads(
            model,
            x,
            phi,
            state[2 * n : 3 * n],
            state[3 * n :],
            damped,
            fx,
            fy,
            tau,
            length[row],
            tension[row],
        )
        energy = 0.0
        for s in range(springs.shape[0]):
            energy += spring_energy(springs[s, col.STIFF], springs[s, col.REST], length[row, s])
        for j in range(forces.shape[0]):
            i = force_body[j]
            px, py, _, _ = _point(b, i, forces[j, col.FR], forces[j, col.FALPHA], x, phi)
            p0x, p0y, _, _ = _point(
                b, i, forces[j, col.FR], forces[j, col.FALPHA], zero_x, zero_phi
            )
            energy -= work(forces[j, col.FX], forces[j, col.FY], px - p0x, py - p0y)
        potential[row] = energy
        for i in range(n):
            normal[row, i] = normal_force(b[i, col.MASS] * g, fy[i])
            if b[i, col.ROLLS] == 0.0:
                friction[row, i] = 0.0
            elif slipping[row, i]:
                friction[row, i] = kinetic_friction(b[i, col.MU_K], normal[row, i], sign[row, i])
            else:
                gen = generalized_force(b[i, col.SCALE], fx[i], tau[i])
                c_rr = b[i, col.C_RR]
                if c_rr > 0.0:
                    if spin[row, i] == 0.0:
                        gen = 0.0
                    else:
                        gen += rolling_resistance(
                            c_rr, normal[row, i], b[i, col.SCALE], spin[row, i]
                        )
                friction[row, i] = needed_friction(
                    b[i, col.MASS], b[i, col.SCALE], b[i, col.INERTIA], gen, fx[i]
                )
        moving = 0.0
        for i in range(n):
            u = state[2 * n + i]
            w = state[3 * n + i]
            moving += 0.5 * (b[i, col.MASS] * u * u + central[i] * w * w)
            if b[i, col.ROLLS] == 0.0:
                ratio[row, i] = 0.0
            elif normal[row, i] <= 0.0:
                ratio[row, i] = np.inf
            elif math.isinf(b[i, col.MU_S]):
                ratio[row, i] = 0.0
            else:
                ratio[row, i] = abs(friction[row, i]) / (b[i, col.MU_S] * normal[row, i])
        kinetic[row] = moving


@njit(cache=True, error_model="numpy")
def observe_rolling(
    model,
    x0,
    q_rows,
    v_rows,
    central,
    energy_ref,
    states,
    friction,
    normal,
    length,
    tension,
    potential,
    kinetic,
    ratio,
    extremes,
):
    r""":func:`observe` of all-rolling, undamped rows given as (q, qdot) (rows of ``q_rows``,
    ``v_rows``) with reference positions ``x0``, in one pass: the general states
    :math:`[x_0 + s q, \rho q, s\dot q, \rho\dot q]` into ``states`` and everything
    :func:`observe` gives, the same operations on the same numbers but for a level spring's
    force, :math:`T\,\mathrm{sign}(dx)` (the stepping's) for :func:`observe`'s
    :math:`(T/|dx|)\,dx` (a bit or two apart). ``extremes`` (4, n)
    receives :func:`row_extremes` of the rows (nobody slips). Returns the largest
    :math:`|U + K - \text{energy\_ref}|` over the rows (NaN if any is)."""
    rows, n = q_rows.shape
    b, springs, ends, forces, force_body, g = (
        model[0],
        model[1],
        model[2],
        model[3],
        model[4],
        model[5],
    )
    x = np.empty(n)
    phi = np.empty(n)
    fx = np.empty(n)
    fy = np.empty(n)
    tau = np.empty(n)
    # each constant force's point of application at the model's reference positions
    zero_x = b[:, col.X0].copy()
    zero_phi = np.zeros(n)
    p0 = np.empty((forces.shape[0], 2))
    for j in range(forces.shape[0]):
        p0x, p0y, _, _ = _point(
            b, force_body[j], forces[j, col.FR], forces[j, col.FALPHA], zero_x, zero_phi
        )
        p0[j, 0] = p0x
        p0[j, 1] = p0y
    for i in range(n):
        extremes[0, i] = -np.inf
        extremes[1, i] = 0.0
        extremes[2, i] = np.inf
        extremes[3, i] = 0.0
    worst = 0.0
    invalid = False
    for row in range(rows):
        moving = 0.0
        for i in range(n):
            qi = q_rows[row, i]
            vi = v_rows[row, i]
            scale = b[i, col.SCALE]
            rolls = b[i, col.ROLLS]
            x[i] = x0[i] + scale * qi
            phi[i] = rolls * qi
            u = scale * vi
            w = rolls * vi
            states[row, i] = x[i]
            states[row, n + i] = phi[i]
            states[row, 2 * n + i] = u
            states[row, 3 * n + i] = w
            moving += 0.5 * (b[i, col.MASS] * u * u + central[i] * w * w)
            fx[i] = 0.0
            fy[i] = 0.0
            tau[i] = 0.0
        energy = 0.0
        for s in range(springs.shape[0]):  # body_loads without damping
            dx, dy, dist, oax, oay, obx, oby = _spring_geometry(b, springs, ends, s, x, phi)
            t = elastic_tension(springs[s, col.STIFF], springs[s, col.REST], dist)
            length[row, s] = dist
            tension[row, s] = t
            energy += spring_energy(springs[s, col.STIFF], springs[s, col.REST], dist)
            if is_level(dx, dy):
                # a level spring (dist is |dx|): T e_x = T sign(dx) (the stepping's force,
                # without the division of _load_ends, which gives it to the last bit or two)
                tx = t if dx > 0.0 else -t
                ia = ends[s, 0]
                ib = ends[s, 1]
                if ia >= 0:
                    fx[ia] += tx
                    tau[ia] += oax * tx
                if ib >= 0:
                    fx[ib] -= tx
                    tau[ib] -= obx * tx
            else:
                _load_ends(ends, s, t, dx, dy, dist, oax, oay, obx, oby, fx, fy, tau)
        _load_forces(b, forces, force_body, x, phi, fx, fy, tau)
        for j in range(forces.shape[0]):
            i = force_body[j]
            px, py, _, _ = _point(b, i, forces[j, col.FR], forces[j, col.FALPHA], x, phi)
            energy -= work(forces[j, col.FX], forces[j, col.FY], px - p0[j, 0], py - p0[j, 1])
        potential[row] = energy
        kinetic[row] = moving
        for i in range(n):
            nn = normal_force(b[i, col.MASS] * g, fy[i])
            normal[row, i] = nn
            if b[i, col.ROLLS] == 0.0:
                f = 0.0
                ratio[row, i] = 0.0
            else:
                gen = generalized_force(b[i, col.SCALE], fx[i], tau[i])
                f = needed_friction(b[i, col.MASS], b[i, col.SCALE], b[i, col.INERTIA], gen, fx[i])
                if nn <= 0.0:
                    ratio[row, i] = np.inf
                elif math.isinf(b[i, col.MU_S]):
                    ratio[row, i] = 0.0
                else:
                    ratio[row, i] = abs(f) / (b[i, col.MU_S] * nn)
            friction[row, i] = f
            # row_extremes: the first largest |f|/N (inf where N <= 0), the first smallest N
            value = abs(f) / nn if nn > 0.0 else np.inf
            if value != value:
                if extremes[0, i] == extremes[0, i]:
                    extremes[0, i] = value
                    extremes[1, i] = row
            elif value > extremes[0, i] or row == 0:
                extremes[0, i] = value
                extremes[1, i] = row
            if nn != nn:
                if extremes[2, i] == extremes[2, i]:
                    extremes[2, i] = nn
                    extremes[3, i] = row
            elif nn < extremes[2, i] or row == 0:
                extremes[2, i] = nn
                extremes[3, i] = row
        deviation = abs(energy + moving - energy_ref)
        if deviation != deviation:
            invalid = True
        elif deviation > worst:
            worst = deviation
    return np.nan if invalid else worst


@njit(cache=True, error_model="numpy")
def row_extremes(friction, normal, slipping):
    r"""Per body over the rows: the largest :math:`|f|/N` (:math:`\infty` where
    :math:`N \le 0`, :math:`-\infty` on slipping rows) and its row, the smallest N and its
    row -- the first such row, and the first NaN if any, as NumPy's argmax/argmin. Returns
    (ratio, ratio_row, normal, normal_row)."""
    rows, n = normal.shape
    best_ratio = np.empty(n)
    ratio_row = np.zeros(n, dtype=np.int64)
    best_normal = np.empty(n)
    normal_row = np.zeros(n, dtype=np.int64)
    for i in range(n):
        top = -np.inf
        at = 0
        for r in range(rows):
            nn = normal[r, i]
            if slipping[r, i]:
                value = -np.inf
            elif nn > 0.0:
                value = abs(friction[r, i]) / nn
            else:
                value = np.inf
            if value != value:
                top = value
                at = r
                break
            if r == 0 or value > top:
                top = value
                at = r
        best_ratio[i] = top
        ratio_row[i] = at
        low = normal[0, i]
        at = 0
        if low == low:
            for r in range(1, rows):
                nn = normal[r, i]
                if nn != nn:
                    low = nn
                    at = r
                    break
                if nn < low:
                    low = nn
                    at = r
        best_normal[i] = low
        normal_row[i] = at
    return best_ratio, ratio_row, best_normal, normal_row


@njit(cache=True, error_model="numpy")
def resistance_drives(model, state, slipping, sign, damped, drive, limit):
    r"""Per body of the general ``state``: the torque driving its rotation, the rolling
    resistance left out -- :math:`Q_i` (M7) of a rolling body, :math:`\tau_i - R_i f_i` (M19)
    of a slipping one, 0 for a slider -- into ``drive``, and the largest torque the
    resistance holds it at rest against, :math:`C_{rr} N R` (M22), into ``limit``. A body at
    rest stays so while :math:`|D| \le C_{rr} N R` and starts to turn the way :math:`D` drives
    it when :math:`|D|` exceeds it."""
    n = slipping.shape[0]
    b, g = model[0], model[5]
    ns = model[1].shape[0]
    fx = np.empty(n)
    fy = np.empty(n)
    tau = np.empty(n)
    length = np.empty(ns)
    tension = np.empty(ns)
    body_loads(
        model,
        state[:n],
        state[n : 2 * n],
        state[2 * n : 3 * n],
        state[3 * n :],
        damped,
        fx,
        fy,
        tau,
        length,
        tension,
    )
    for i in range(n):
        normal = normal_force(b[i, col.MASS] * g, fy[i])
        limit[i] = resistance_limit(b[i, col.C_RR], normal, b[i, col.RADIUS])
        if b[i, col.ROLLS] == 0.0:
            drive[i] = 0.0
        elif slipping[i]:
            friction = kinetic_friction(b[i, col.MU_K], normal, sign[i])
            drive[i] = tau[i] - b[i, col.RADIUS] * friction
        else:
            drive[i] = generalized_force(b[i, col.SCALE], fx[i], tau[i])

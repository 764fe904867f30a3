r"""Compiled (Numba) kernels: the exact rolling equations and explicit symplectic integrators.

While every body rolls the Hamiltonian is separable, :math:`H = \sum p_i^2/(2J_i) + U(q)` with a
constant diagonal mass matrix (docs/physics.md (M6)), so compositions of the kick-drift-kick
leapfrog

.. math:: v \mathrel{+}= \tfrac{h_k}{2} Q(q)/J,\quad q \mathrel{+}= h_k v,\quad
          v \mathrel{+}= \tfrac{h_k}{2} Q(q)/J, \qquad h_k = w_k h

are explicit and symplectic; the weights :math:`w_k` (Yoshida 1990; Kahan and Li 1997) give
orders 2, 4, 6 and 8. The force at the end of a stage is reused at the start of the next.

The general state (any body may slip) is per body the centre position :math:`x_i`, the rotation
:math:`\varphi_i` from the initial placement, the centre velocity :math:`u_i` and the angular
velocity :math:`\omega_i` (clockwise positive). An attachment at distance :math:`r` and angle
:math:`\alpha` (clockwise from up) is at (M1)

.. math::

   P = (x_i + r\sin\theta,\; h_i + R_i + r\cos\theta), \qquad \theta = \alpha + \rho_i\varphi_i

and the loads :func:`body_loads` are the resultant force :math:`(F_{ix}, F_{iy})` and the
clockwise torque :math:`\tau_i` about the centre of the springs (tension
:math:`T = k(l - L_0) + c\,\dot l`) and constant forces. For a rolling body the generalised force
is :math:`Q_i = R_i F_{ix} + \tau_i` (the torque about the contact point, (M7)), and (M8), (M9)
give the friction it needs and its normal force. The model is a tuple of flat arrays
(:func:`kernel_model`); tests check the kernels against :mod:`rollspring.physics` to rounding.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np
from numba import njit

from rollspring.analysis import linear as _linear
from rollspring.physics import SystemArrays
from rollspring.simulate.integrators import INTEGRATORS
from rollspring.simulate.status import Status

__all__ = [
    "GENERAL",
    "KIND_NAMES",
    "LEVEL",
    "MOST_BODIES",
    "SCHEMES",
    "STATUS_FINISHED",
    "STATUS_LIFTOFF",
    "STATUS_NONFINITE",
    "STATUS_SLIP",
    "advance",
    "advance_many",
    "body_links",
    "body_loads",
    "force_rates",
    "generalized_forces",
    "kernel_model",
    "level_setup",
    "observe",
    "observe_rolling",
    "refine_extremes",
    "refine_windowed",
    "rolling_forces",
    "row_extremes",
    "run_fixed_step",
    "signal_zero",
    "slipping_derivatives",
    "spring_balls",
]

STATUS_FINISHED = int(Status.FINISHED)
STATUS_NONFINITE = int(Status.NONFINITE)
STATUS_SLIP = int(Status.SLIP)
STATUS_LIFTOFF = int(Status.LIFTOFF)

#: name -> (order p, stage weights, C_p): the relative frequency error is C_p (omega h)^p
#: (:data:`rollspring.simulate.integrators.INTEGRATORS`, as the kernels take them).
SCHEMES: dict[str, tuple[int, np.ndarray, float]] = {
    name: (scheme.order, scheme.weights, scheme.error_constant)
    for name, scheme in INTEGRATORS.items()
}


# columns of the packed per-body, per-spring and per-force arrays of the kernel model
X0, SCALE, ROLLS, CY, INERTIA, MASS, MU_S, CENTRAL, MU_K, RADIUS, INV_INERTIA = range(11)
RA, ALPHA_A, RB, ALPHA_B, AAX, AAY, ABX, ABY, STIFF, REST, DAMP = range(11)
FR, FALPHA, FX, FY = range(4)


def kernel_model(arrays: SystemArrays, x0: np.ndarray | None = None) -> tuple[Any, ...]:
    """The model the kernels take: ``(bodies (n, 11), springs (S, 11), spring_ends (S, 2) int,
    forces (F, 4), force_body (F,) int, gravity)`` (columns named by the module constants).
    ``x0`` overrides the reference centre positions (after a body re-sticks:
    ``x_i - R_i phi_i``). Few packed arrays keep the compiled calls cheap."""
    a = arrays
    # one array of the columns as rows, transposed: the cheapest packing for a few bodies
    bodies = np.array(
        [
            a.x0 if x0 is None else x0,
            a.scale,
            a.rolls,
            a.track + a.radius,
            a.inertia,
            a.mass,
            a.mu_static,
            a.gamma * a.mass * a.radius**2,
            a.mu_kinetic,
            a.radius,
            1.0 / a.inertia,
        ],
        dtype=np.float64,
    ).T
    springs = np.array(
        [
            a.end_r[:, 0],
            a.end_alpha[:, 0],
            a.end_r[:, 1],
            a.end_alpha[:, 1],
            a.end_anchor[:, 0, 0],
            a.end_anchor[:, 0, 1],
            a.end_anchor[:, 1, 0],
            a.end_anchor[:, 1, 1],
            a.stiffness,
            a.rest_length,
            a.damping,
        ],
        dtype=np.float64,
    ).T.reshape(-1, 11)
    forces = np.array(
        [a.force_r, a.force_alpha, a.force[:, 0], a.force[:, 1]], dtype=np.float64
    ).T.reshape(-1, 4)
    return (
        np.ascontiguousarray(bodies),
        np.ascontiguousarray(springs),
        np.ascontiguousarray(a.end_body, dtype=np.int64),
        np.ascontiguousarray(forces),
        np.ascontiguousarray(a.force_body, dtype=np.int64),
        float(a.gravity),
    )


@njit(cache=True, inline="always", error_model="numpy")
def _point(bodies, i, r, alpha, x, phi):
    """Attachment position (M1) and its velocity per unit angular velocity at fixed centre."""
    if r == 0.0:
        return x[i], bodies[i, CY], 0.0, 0.0
    rolls = bodies[i, ROLLS]
    theta = alpha + rolls * phi[i]
    s = math.sin(theta)
    c = math.cos(theta)
    return x[i] + r * s, bodies[i, CY] + r * c, rolls * r * c, -rolls * r * s


@njit(cache=True, inline="always", error_model="numpy")
def _spring_geometry(bodies, springs, ends, s, x, phi):
    """Spring ``s``: the vector from its end a to its end b (dx, dy), its length, and each
    end's velocity per unit angular velocity of its body at a fixed centre (oax, oay, obx, oby;
    0 for an anchor), (M1)."""
    ia = ends[s, 0]
    ib = ends[s, 1]
    oax = 0.0
    oay = 0.0
    obx = 0.0
    oby = 0.0
    if ia >= 0:
        pax, pay, oax, oay = _point(bodies, ia, springs[s, RA], springs[s, ALPHA_A], x, phi)
    else:
        pax = springs[s, AAX]
        pay = springs[s, AAY]
    if ib >= 0:
        pbx, pby, obx, oby = _point(bodies, ib, springs[s, RB], springs[s, ALPHA_B], x, phi)
    else:
        pbx = springs[s, ABX]
        pby = springs[s, ABY]
    dx = pbx - pax
    dy = pby - pay
    # a level spring (both ends at one height): sqrt(dx^2) is |dx| exactly (IEEE
    # round-to-nearest, dx^2 neither overflowing nor underflowing), without the square
    # root's latency on the stepping's chain
    dist = abs(dx) if dy == 0.0 and 1e-150 < abs(dx) < 1e150 else math.sqrt(dx * dx + dy * dy)
    return dx, dy, dist, oax, oay, obx, oby


@njit(cache=True, inline="always", error_model="numpy")
def _load_ends(ends, s, t, dx, dy, dist, oax, oay, obx, oby, fx, fy, tau):
    """Add spring ``s``'s tension ``t`` to its bodies: :math:`+T e` on end a, :math:`-T e` on
    end b, and their clockwise torques about the centres."""
    ia = ends[s, 0]
    ib = ends[s, 1]
    per_length = t / dist
    tx = per_length * dx
    ty = per_length * dy
    if ia >= 0:
        fx[ia] += tx
        fy[ia] += ty
        tau[ia] += oax * tx + oay * ty
    if ib >= 0:
        fx[ib] -= tx
        fy[ib] -= ty
        tau[ib] -= obx * tx + oby * ty


@njit(cache=True, inline="always", error_model="numpy")
def body_loads(model, x, phi, u, w, damped, fx, fy, tau, length, tension):
    r"""Resultant force and clockwise torque about each centre of springs and constant forces;
    each spring's length and tension :math:`T = k(l - L_0) + c\,\dot l` (``damped``: include
    :math:`c\,\dot l`). Force on end a: :math:`+T e`, on end b: :math:`-T e`
    (docs/physics.md §2)."""
    bodies, springs, ends, forces, force_body = model[0], model[1], model[2], model[3], model[4]
    for i in range(x.shape[0]):
        fx[i] = 0.0
        fy[i] = 0.0
        tau[i] = 0.0
    for s in range(springs.shape[0]):
        dx, dy, dist, oax, oay, obx, oby = _spring_geometry(bodies, springs, ends, s, x, phi)
        t = springs[s, STIFF] * (dist - springs[s, REST])
        if damped and springs[s, DAMP] != 0.0:
            ia = ends[s, 0]
            ib = ends[s, 1]
            vax = 0.0
            vay = 0.0
            vbx = 0.0
            vby = 0.0
            if ia >= 0:
                vax = u[ia] + oax * w[ia]
                vay = oay * w[ia]
            if ib >= 0:
                vbx = u[ib] + obx * w[ib]
                vby = oby * w[ib]
            t += springs[s, DAMP] * (dx * (vbx - vax) + dy * (vby - vay)) / dist
        length[s] = dist
        tension[s] = t
        _load_ends(ends, s, t, dx, dy, dist, oax, oay, obx, oby, fx, fy, tau)
    for j in range(forces.shape[0]):
        i = force_body[j]
        _, _, ox, oy = _point(bodies, i, forces[j, FR], forces[j, FALPHA], x, phi)
        fx[i] += forces[j, FX]
        fy[i] += forces[j, FY]
        tau[i] += ox * forces[j, FX] + oy * forces[j, FY]


@njit(cache=True, inline="always", error_model="numpy")
def rolling_forces(model, q, scratch, gen, fx, fy):
    r"""Generalised forces :math:`Q_i = s_i F_{ix} + \tau_i` (M7) of the all-rolling state
    ``q`` (no damping), into ``gen``; resultant forces into ``fx``, ``fy``. ``scratch`` is a
    tuple of work arrays (x, zeros, tau, length, tension)."""
    # body_loads without damping, spring lengths and tensions, with fewer loads and stores on
    # the stepping's chain: the same operations but for level springs (both ends at one
    # height), whose force k (|dx| - L0) sign(dx) takes neither a square root nor a division
    bodies, springs, ends, forces, force_body = model[0], model[1], model[2], model[3], model[4]
    tau = scratch[2]
    for i in range(q.shape[0]):
        fx[i] = 0.0
        fy[i] = 0.0
        tau[i] = 0.0
    for s in range(springs.shape[0]):
        ia = ends[s, 0]
        ib = ends[s, 1]
        oax = 0.0
        oay = 0.0
        obx = 0.0
        oby = 0.0
        if ia >= 0:
            pax, pay, oax, oay = _rolling_point(bodies, ia, springs[s, RA], springs[s, ALPHA_A], q)
        else:
            pax = springs[s, AAX]
            pay = springs[s, AAY]
        if ib >= 0:
            pbx, pby, obx, oby = _rolling_point(bodies, ib, springs[s, RB], springs[s, ALPHA_B], q)
        else:
            pbx = springs[s, ABX]
            pby = springs[s, ABY]
        dx = pbx - pax
        dy = pby - pay
        if dy == 0.0 and 1e-150 < abs(dx) < 1e150:
            # a level spring (both ends at one height): T e_x = k (|dx| - L0) sign(dx), without
            # the square root and the division on the stepping's chain
            tx = springs[s, STIFF] * (dx - springs[s, REST] if dx > 0.0 else dx + springs[s, REST])
            ty = 0.0
        else:
            dist = math.sqrt(dx * dx + dy * dy)
            per_length = springs[s, STIFF] * (dist - springs[s, REST]) / dist
            tx = per_length * dx
            ty = per_length * dy
        # _load_ends's writes, written out here: a shared inlined helper for them made the
        # whole integration 2.5 times slower (bench_hoop_cylinder.py: 0.19 -> 0.47 ms)
        if ia >= 0:
            fx[ia] += tx
            fy[ia] += ty
            tau[ia] += oax * tx + oay * ty
        if ib >= 0:
            fx[ib] -= tx
            fy[ib] -= ty
            tau[ib] -= obx * tx + oby * ty
    for j in range(forces.shape[0]):
        i = force_body[j]
        _, _, ox, oy = _rolling_point(bodies, i, forces[j, FR], forces[j, FALPHA], q)
        fx[i] += forces[j, FX]
        fy[i] += forces[j, FY]
        tau[i] += ox * forces[j, FX] + oy * forces[j, FY]
    for i in range(q.shape[0]):
        gen[i] = bodies[i, SCALE] * fx[i] + tau[i]


@njit(cache=True, inline="always", error_model="numpy")
def _rolling_point(bodies, i, r, alpha, q):
    """:func:`_point` of an all-rolling state q: centre x = x0 + s q, rotation q."""
    x = bodies[i, X0] + bodies[i, SCALE] * q[i]
    if r == 0.0:
        return x, bodies[i, CY], 0.0, 0.0
    rolls = bodies[i, ROLLS]
    theta = alpha + rolls * q[i]
    s = math.sin(theta)
    c = math.cos(theta)
    return x + r * s, bodies[i, CY] + r * c, rolls * r * c, -rolls * r * s


@njit(cache=True, error_model="numpy")
def _workspace(model, n):
    """The work arrays of one force evaluation: (scratch, gen, fx, fy)."""
    return _scratch(n, model[1].shape[0]), np.empty(n), np.empty(n), np.empty(n)


@njit(cache=True, error_model="numpy")
def generalized_forces(model, q):
    r"""The generalised forces :math:`Q(q)` (M7) of an all-rolling state, as a new array (the
    compiled twin of :func:`rollspring.physics.generalized_forces` without damping)."""
    scratch, gen, fx, fy = _workspace(model, q.shape[0])
    rolling_forces(model, q, scratch, gen, fx, fy)
    return gen


@njit(cache=True, error_model="numpy")
def _scratch(n, n_springs):
    return (np.zeros(n), np.zeros(n), np.zeros(n), np.zeros(n_springs), np.zeros(n_springs))


@njit(cache=True, inline="always", error_model="numpy")
def _contact(model, i, gen_i, fx_i, fy_i):
    """(M8), (M9): friction needed to roll and the normal force."""
    b = model[0]
    friction = b[i, MASS] * b[i, SCALE] * gen_i / b[i, INERTIA] - fx_i if b[i, ROLLS] > 0.0 else 0.0
    return friction, b[i, MASS] * model[5] - fy_i


@njit(cache=True, inline="always", error_model="numpy")
def _stages(model, coeffs, h, q, v, scratch, gen, fx, fy):
    """One step: the stages of the composition, the closing half-kick of each stage merged
    with the opening half-kick of the next (they use the same force)."""
    bodies = model[0]
    n = q.shape[0]
    m = coeffs.shape[0]
    kick = 0.5 * h * coeffs[0]
    for i in range(n):
        v[i] += kick * gen[i] * bodies[i, INV_INERTIA]
    for k in range(m):
        hw = h * coeffs[k]
        for i in range(n):
            q[i] += hw * v[i]
        rolling_forces(model, q, scratch, gen, fx, fy)
        kick = 0.5 * h * (coeffs[k] + coeffs[k + 1]) if k + 1 < m else 0.5 * hw
        for i in range(n):  # kick / J off the chain force -> velocity -> position
            v[i] += gen[i] * (kick * bodies[i, INV_INERTIA])


@njit(cache=True, error_model="numpy")
def advance(model, coeffs, q, v, duration, n_steps):
    """Integrate ``n_steps`` equal steps over ``duration`` (may be 0) from (q, v); returns new
    arrays (q, v, friction, normal) at the end."""
    q = q.copy()
    v = v.copy()
    n = q.shape[0]
    scratch, gen, fx, fy = _workspace(model, n)
    friction = np.empty(n)
    normal = np.empty(n)
    rolling_forces(model, q, scratch, gen, fx, fy)
    h = duration / max(n_steps, 1)
    for _ in range(n_steps):
        _stages(model, coeffs, h, q, v, scratch, gen, fx, fy)
    for i in range(n):
        friction[i], normal[i] = _contact(model, i, gen[i], fx[i], fy[i])
    return q, v, friction, normal


@njit(cache=True, error_model="numpy")
def advance_many(model, coeffs, q_rows, v_rows, spans, pieces):
    """``advance`` from row j of (q_rows, v_rows) over spans[j] in pieces[j] equal steps, for
    every j at once; returns the arrays (q, v)."""
    q_out = np.empty_like(q_rows)
    v_out = np.empty_like(v_rows)
    for j in range(q_rows.shape[0]):
        q, v, _, _ = advance(model, coeffs, q_rows[j], v_rows[j], spans[j], pieces[j])
        q_out[j] = q
        v_out[j] = v
    return q_out, v_out


@njit(cache=True, inline="always", error_model="numpy")
def _rolling_lever(bodies, i, r, alpha, q, v):
    r"""Of a point at (r, alpha) on body i in the all-rolling state (q, v): its position p,
    its lever :math:`\ell = \partial p/\partial q_i` and the lever's rate
    :math:`\dot\ell = \dot q_i\,\partial\ell/\partial q_i` (M1):
    (px, py, lx, ly, dlx, dly)."""
    x = bodies[i, X0] + bodies[i, SCALE] * q[i]
    if r == 0.0:
        return x, bodies[i, CY], bodies[i, SCALE], 0.0, 0.0, 0.0
    rolls = bodies[i, ROLLS]
    theta = alpha + rolls * q[i]
    s = math.sin(theta)
    c = math.cos(theta)
    spin = rolls * rolls * v[i]
    return (
        x + r * s,
        bodies[i, CY] + r * c,
        bodies[i, SCALE] + rolls * r * c,
        -rolls * r * s,
        -spin * r * s,
        -spin * r * c,
    )


@njit(cache=True, error_model="numpy")
def force_rates(model, q, v, rate):
    r"""The rates :math:`\dot Q = (\partial Q/\partial q)\,\dot q = -K(q)\,\dot q` of the
    generalised forces (M7) of the all-rolling state (q, v) (no damping), into ``rate``: the
    jerk :math:`\dddot q = J^{-1}\dot Q` that the septic output interpolant takes.

    A spring's force on its end a is :math:`F = k(1 - L_0/L)\,d` (:math:`d = p_b - p_a`,
    :math:`L = |d|`) and :math:`Q_a = \ell_a\cdot F` (:math:`\ell = \partial p/\partial q`,
    :math:`-F` and :math:`Q_b = -\ell_b\cdot F` on end b), so
    :math:`\dot Q_a = \dot\ell_a\cdot F + \ell_a\cdot\dot F` with
    :math:`\dot F = k(1 - L_0/L)\,\dot d + k L_0 (d\cdot\dot d)/L^3\,d` and
    :math:`\dot d = \ell_b\dot q_b - \ell_a\dot q_a`; a constant force adds
    :math:`\dot\ell\cdot F`."""
    bodies, springs, ends, forces, force_body = model[0], model[1], model[2], model[3], model[4]
    for i in range(q.shape[0]):
        rate[i] = 0.0
    for s in range(springs.shape[0]):
        ia = ends[s, 0]
        ib = ends[s, 1]
        # the two ends written out: one inlined helper for both made the run's stepping kernel
        # (which calls this every step) 12% slower (349 steps of the paper's system: 154 ->
        # 172 us)
        lax = lay = dlax = dlay = lbx = lby = dlbx = dlby = 0.0
        vax = vay = vbx = vby = 0.0
        if ia >= 0:
            pax, pay, lax, lay, dlax, dlay = _rolling_lever(
                bodies, ia, springs[s, RA], springs[s, ALPHA_A], q, v
            )
            vax = lax * v[ia]
            vay = lay * v[ia]
        else:
            pax = springs[s, AAX]
            pay = springs[s, AAY]
        if ib >= 0:
            pbx, pby, lbx, lby, dlbx, dlby = _rolling_lever(
                bodies, ib, springs[s, RB], springs[s, ALPHA_B], q, v
            )
            vbx = lbx * v[ib]
            vby = lby * v[ib]
        else:
            pbx = springs[s, ABX]
            pby = springs[s, ABY]
        dx = pbx - pax
        dy = pby - pay
        ddx = vbx - vax
        ddy = vby - vay
        k = springs[s, STIFF]
        if dy == 0.0 and ddy == 0.0 and 1e-150 < abs(dx) < 1e150:
            # a level spring staying level: F_x = k (|dx| - L0) sign(dx), dF_x/dt = k ddx
            force_x = k * (dx - springs[s, REST] if dx > 0.0 else dx + springs[s, REST])
            force_y = 0.0
            rate_x = k * ddx
            rate_y = 0.0
        else:
            length = math.sqrt(dx * dx + dy * dy)
            stretch = k * (1.0 - springs[s, REST] / length)
            along = k * springs[s, REST] * (dx * ddx + dy * ddy) / (length * length * length)
            force_x = stretch * dx
            force_y = stretch * dy
            rate_x = stretch * ddx + along * dx
            rate_y = stretch * ddy + along * dy
        if ia >= 0:
            rate[ia] += dlax * force_x + dlay * force_y + lax * rate_x + lay * rate_y
        if ib >= 0:
            rate[ib] -= dlbx * force_x + dlby * force_y + lbx * rate_x + lby * rate_y
    for j in range(forces.shape[0]):
        i = force_body[j]
        _, _, _, _, dlx, dly = _rolling_lever(bodies, i, forces[j, FR], forces[j, FALPHA], q, v)
        rate[i] += dlx * forces[j, FX] + dly * forces[j, FY]


@njit(cache=True, inline="always", error_model="numpy")
def _hermite_coefficients(model, h, q0, v0, g0, r0, q1, v1, g1, r1, coef):
    r"""The septic Hermite interpolant of one step, per body as :math:`q(\theta) =
    \sum_{k=0}^{7} c_k\theta^k` (:math:`\theta = s/h \in [0, 1]`), from positions,
    velocities, accelerations :math:`a = Q/J` and jerks :math:`j = \dot Q/J` at both ends
    (``g``: Q, ``r``: :math:`\dot Q`), into ``coef[:, :8]`` and those of its derivative divided
    by h, the velocity, into ``coef[:, 8:]`` (n, 15). With :math:`V = h\dot q`,
    :math:`A = h^2 a`, :math:`\mathcal{J} = h^3 j` and :math:`D = q_1 - q_0`: :math:`c_0 = q_0`,
    :math:`c_1 = V_0`, :math:`c_2 = A_0/2`, :math:`c_3 = \mathcal{J}_0/6` and

    .. math::
        c_4 &= 35D - 20V_0 - 15V_1 - 5A_0 + \tfrac52 A_1 - \tfrac23\mathcal{J}_0
               - \tfrac16\mathcal{J}_1,\\
        c_5 &= -84D + 45V_0 + 39V_1 + 10A_0 - 7A_1 + \mathcal{J}_0 + \tfrac12\mathcal{J}_1,\\
        c_6 &= 70D - 36V_0 - 34V_1 - \tfrac{15}2 A_0 + \tfrac{13}2 A_1 - \tfrac23\mathcal{J}_0
               - \tfrac12\mathcal{J}_1,\\
        c_7 &= -20D + 10V_0 + 10V_1 + 2A_0 - 2A_1 + \tfrac16(\mathcal{J}_0 + \mathcal{J}_1).

    Its error is at most :math:`h^8\max|q^{(8)}|/10321920` in position (and, through its
    derivative, :math:`(\omega h)^7/2710000` of the velocity amplitude on a sine)."""
    bodies = model[0]
    hh = h * h
    hhh = hh * h
    inv_h = 1.0 / h
    sixth = 1.0 / 6.0
    for i in range(q0.shape[0]):
        inv = bodies[i, INV_INERTIA]
        d = q1[i] - q0[i]
        w0 = h * v0[i]
        w1 = h * v1[i]
        a0 = hh * (g0[i] * inv)
        a1 = hh * (g1[i] * inv)
        j0 = hhh * (r0[i] * inv)
        j1 = hhh * (r1[i] * inv)
        c4 = 35.0 * d - 20.0 * w0 - 15.0 * w1 - 5.0 * a0 + 2.5 * a1 - (4.0 * j0 + j1) * sixth
        c5 = -84.0 * d + 45.0 * w0 + 39.0 * w1 + 10.0 * a0 - 7.0 * a1 + j0 + 0.5 * j1
        c6 = 70.0 * d - 36.0 * w0 - 34.0 * w1 - 7.5 * a0 + 6.5 * a1 - (4.0 * j0 + 3.0 * j1) * sixth
        c7 = -20.0 * d + 10.0 * (w0 + w1) + 2.0 * (a0 - a1) + (j0 + j1) * sixth
        coef[i, 0] = q0[i]
        coef[i, 1] = w0
        coef[i, 2] = 0.5 * a0
        coef[i, 3] = j0 * sixth
        coef[i, 4] = c4
        coef[i, 5] = c5
        coef[i, 6] = c6
        coef[i, 7] = c7
        # the derivative's, divided by h: the velocity
        coef[i, 8] = v0[i]
        coef[i, 9] = a0 * inv_h
        coef[i, 10] = 0.5 * j0 * inv_h
        coef[i, 11] = 4.0 * c4 * inv_h
        coef[i, 12] = 5.0 * c5 * inv_h
        coef[i, 13] = 6.0 * c6 * inv_h
        coef[i, 14] = 7.0 * c7 * inv_h


@njit(cache=True, inline="always", error_model="numpy")
def _hermite(coef, theta, row, out_q, out_v):
    """The interpolant of :func:`_hermite_coefficients` at ``theta`` and its derivative (the
    velocity), by Estrin's scheme (short dependency chains), into row ``row`` of
    ``out_q``/``out_v``."""
    t = theta
    t2 = t * t
    t4 = t2 * t2
    for i in range(coef.shape[0]):
        out_q[row, i] = (
            (coef[i, 0] + coef[i, 1] * t)
            + t2 * (coef[i, 2] + coef[i, 3] * t)
            + t4 * ((coef[i, 4] + coef[i, 5] * t) + t2 * (coef[i, 6] + coef[i, 7] * t))
        )
        out_v[row, i] = (
            (coef[i, 8] + coef[i, 9] * t)
            + t2 * (coef[i, 10] + coef[i, 11] * t)
            + t4 * ((coef[i, 12] + coef[i, 13] * t) + t2 * coef[i, 14])
        )


@njit(cache=True, error_model="numpy")
def run_fixed_step(
    model,
    coeffs,
    q,
    v,
    t0,
    h,
    n_steps,
    check_contacts,
    out_times,
    out_q,
    out_v,
    extremes,
    extreme_states,
    ball_ptr,
    ball_idx,
    weights,
    q_ref,
    crossing,
    crossing_states,
    before,
):
    """Integrate ``n_steps`` steps of size ``h`` from (q, v) at time ``t0`` (updated in place),
    checking rolling validity after every step. The state at each of the sorted ``out_times``
    (within (t0, t0 + n_steps h]) is interpolated from the step holding it (``_hermite``,
    septic: with the jerks of :func:`force_rates` at the step's ends) into
    the rows of ``out_q``/``out_v``: the output spacing never limits the step.

    Kept across calls (the caller seeds them):

    * ``extremes`` (4, n): per body max |f|/N over the step ends and the start time of that
      step, min N and the start time of its step; ``extreme_states`` (2, 2, B) the state
      (q, v) at the start of those steps, from which the extreme can be refined: for body i
      (kind k) only the bodies of its ball ``ball_idx[ball_ptr[i]:ball_ptr[i + 1]]``
      (:func:`spring_balls`: all that can reach it within the refinement's force evaluations;
      every body for a small system), into ``extreme_states[k, :, ball_ptr[i]:ball_ptr[i + 1]]``
      -- O(1) per body for a chain, no (n, n) array.
    * ``crossing`` (4,): upward zero crossings of the signal s = weights . (q - q_ref): their
      count, the start times of the steps holding the first and the last, and the last value of
      s; ``crossing_states`` (2, 2, n) the states at the start of those two steps.

    ``before`` (2, n) receives the state at the start of the last step taken. Returns
    (status, step, body, rows): for an event the step in which it happened and the body; the
    number of output rows written (those before the event).
    """
    bodies = model[0]
    n = q.shape[0]
    scratch, gen, fx, fy = _workspace(model, n)
    gen_before = np.empty(n)
    # the force rates (jerks) at the step's ends, computed only for steps holding outputs
    rate = np.empty(n)
    rate_before = np.empty(n)
    rate_valid = False  # rate holds the current state's
    coef = np.empty((n, 15))  # the interpolant of the current step
    rolling_forces(model, q, scratch, gen, fx, fy)
    rows = 0
    n_out = out_times.shape[0]
    for step in range(1, n_steps + 1):
        for i in range(n):
            before[0, i] = q[i]
            before[1, i] = v[i]
            gen_before[i] = gen[i]
            rate_before[i] = rate[i]
        before_valid = rate_valid
        _stages(model, coeffs, h, q, v, scratch, gen, fx, fy)
        rate_valid = False
        event = -1
        event_body = -1
        for i in range(n):
            if not (math.isfinite(q[i]) and math.isfinite(v[i])):
                return STATUS_NONFINITE, step, i, rows
            if not check_contacts:
                continue
            friction, normal = _contact(model, i, gen[i], fx[i], fy[i])
            if normal < 0.0:
                event = STATUS_LIFTOFF
                event_body = i
                break
            if bodies[i, ROLLS] > 0.0 and abs(friction) > bodies[i, MU_S] * normal:
                event = STATUS_SLIP
                event_body = i
                break
        if event >= 0:  # the state after this step is past the event: not an extreme
            return event, step, event_body, rows
        t_start = t0 + (step - 1) * h
        # outputs inside this step; the last step also takes any left by rounding
        t_end = t_start + h if step < n_steps else np.inf
        # the interpolant, for a step holding an output before its end (outputs on step ends,
        # the only ones of some runs, need none); theta grows with the sorted outputs, so the
        # first output's tells
        if rows < n_out and out_times[rows] <= t_end and (out_times[rows] - t_start) / h < 1.0:
            if not before_valid:
                force_rates(model, before[0], before[1], rate_before)
            force_rates(model, q, v, rate)
            rate_valid = True
            _hermite_coefficients(
                model, h, before[0], before[1], gen_before, rate_before, q, v, gen, rate, coef
            )
        while rows < n_out and out_times[rows] <= t_end:
            theta = min(max((out_times[rows] - t_start) / h, 0.0), 1.0)
            if theta < 1.0:
                _hermite(coef, theta, rows, out_q, out_v)
            else:  # the step end itself
                for i in range(n):
                    out_q[rows, i] = q[i]
                    out_v[rows, i] = v[i]
            rows += 1
        for i in range(n):
            friction, normal = _contact(model, i, gen[i], fx[i], fy[i])
            if normal < extremes[2, i]:
                extremes[2, i] = normal
                extremes[3, i] = t_start
                for p in range(ball_ptr[i], ball_ptr[i + 1]):
                    extreme_states[1, 0, p] = before[0, ball_idx[p]]
                    extreme_states[1, 1, p] = before[1, ball_idx[p]]
            # |f|/N > best  <=>  |f| > best N (N > 0): no division in the common case
            if bodies[i, ROLLS] > 0.0 and normal > 0.0 and abs(friction) > extremes[0, i] * normal:
                extremes[0, i] = abs(friction) / normal
                extremes[1, i] = t_start
                for p in range(ball_ptr[i], ball_ptr[i + 1]):
                    extreme_states[0, 0, p] = before[0, ball_idx[p]]
                    extreme_states[0, 1, p] = before[1, ball_idx[p]]
        signal = 0.0
        for i in range(n):
            signal += weights[i] * (q[i] - q_ref[i])
        if crossing[3] < 0.0 <= signal:
            slot = 0 if crossing[0] == 0 else 1
            crossing[0] += 1
            crossing[1 + slot] = t_start
            if slot == 0:
                crossing[2] = t_start
            for j in range(n):
                crossing_states[slot, 0, j] = before[0, j]
                crossing_states[slot, 1, j] = before[1, j]
                if slot == 0:
                    crossing_states[1, 0, j] = before[0, j]
                    crossing_states[1, 1, j] = before[1, j]
        crossing[3] = signal
    return STATUS_FINISHED, n_steps, -1, rows


@njit(cache=True, inline="always", error_model="numpy")
def _advance_into(model, coeffs, h, q0, v0, span, q, v, scratch, gen, fx, fy):
    """``advance`` without allocations: (q, v) and the loads after ``span`` from (q0, v0), in
    ceil(span/h) equal steps."""
    for i in range(q0.shape[0]):
        q[i] = q0[i]
        v[i] = v0[i]
    rolling_forces(model, q, scratch, gen, fx, fy)
    if span > 0.0:
        pieces = max(1, math.ceil(span / h * (1.0 - 1e-12)))
        for _ in range(pieces):
            _stages(model, coeffs, span / pieces, q, v, scratch, gen, fx, fy)


@njit(cache=True, error_model="numpy")
def refine_extremes(model, coeffs, h, q0, v0, kinds, bodies, best):
    r"""The extremes the kernel found at step ends, refined on the integrator itself: for
    extreme j (``kinds[j]`` 0: max :math:`|f|/N`, 1: min :math:`N`, of body ``bodies[j]``) over
    the two steps from the state (q0[j], v0[j]), three grids of 9 points, each spanning the best
    point's neighbours on the last (spacing 2h/256 at the end; the three points a grid shares
    with the last are not evaluated again), then the vertex of the parabola through the best
    point and its neighbours: the value to about 1e-10 relative. The state at
    :math:`\tau \le h` is one step of :math:`\tau` from the start, beyond it one step of
    :math:`\tau - h` from the kernel's step end. ``best`` holds the values found so far as
    maximised quantities (:math:`|f|/N` or :math:`-N`); returns the refined ones in the same
    form."""
    m, n = q0.shape
    out = best.copy()
    work = _refine_work(model, n)
    for j in range(m):
        out[j] = _refine_one(model, coeffs, h, q0[j], v0[j], kinds[j], bodies[j], out[j], work)
    return out


@njit(cache=True, error_model="numpy")
def _refine_work(model, n):
    """The work arrays of :func:`_refine_one` for a model of n bodies."""
    scratch, gen, fx, fy = _workspace(model, n)
    states = np.empty((4, n))  # q, v, q_mid, v_mid
    return scratch, gen, fx, fy, states, np.empty(9), np.empty(9)


@njit(cache=True, error_model="numpy")
def _refine_one(model, coeffs, h, q0, v0, kind, b, best, work):
    """:func:`refine_extremes` of one extreme (kind 0: max |f|/N, 1: min N as -N) of body
    ``b`` over the two steps from (q0, v0); returns the refined value (at least ``best``)."""
    scratch, gen, fx, fy, states, values, times = work
    q, v, q_mid, v_mid = states[0], states[1], states[2], states[3]
    out = best
    _advance_into(model, coeffs, h, q0, v0, h, q_mid, v_mid, scratch, gen, fx, fy)
    lo, hi = 0.0, 2.0 * h
    k = -1
    for _level in range(3):
        if k >= 0:  # the last grid's best point and neighbours: this grid's 0, 4 and 8
            values[0], values[4], values[8] = values[k - 1], values[k], values[k + 1]
            times[0], times[4], times[8] = times[k - 1], times[k], times[k + 1]
        for p in range(9):
            if k >= 0 and p % 4 == 0:
                continue
            times[p] = lo + (hi - lo) * p / 8.0
            if times[p] <= h:
                _advance_into(model, coeffs, h, q0, v0, times[p], q, v, scratch, gen, fx, fy)
            else:
                _advance_into(
                    model, coeffs, h, q_mid, v_mid, times[p] - h, q, v, scratch, gen, fx, fy
                )
            friction, normal = _contact(model, b, gen[b], fx[b], fy[b])
            if kind == 0:
                values[p] = abs(friction) / normal if normal > 0.0 else np.inf
            else:
                values[p] = -normal
        k = min(max(int(np.argmax(values)), 1), 7)
        a, c = values[k - 1], values[k + 1]
        middle = values[k]
        out = max(out, np.max(values))
        curvature = a - 2.0 * middle + c
        if math.isfinite(a + middle + c) and curvature < 0.0 and abs(a - c) <= -2.0 * curvature:
            out = max(out, middle - (c - a) ** 2 / (8.0 * curvature))
        lo, hi = times[k - 1], times[k + 1]
    return out


@njit(cache=True, error_model="numpy")
def body_links(n, ends, force_body):
    """Each body's springs and constant forces, ascending, as two CSR pairs
    ``(spring_ptr, spring_ids, force_ptr, force_ids)`` (a spring with both ends on one body is
    listed once)."""
    n_springs = ends.shape[0]
    spring_ptr = np.zeros(n + 1, dtype=np.int64)
    for s in range(n_springs):
        ia, ib = ends[s, 0], ends[s, 1]
        if ia >= 0:
            spring_ptr[ia + 1] += 1
        if ib >= 0 and ib != ia:
            spring_ptr[ib + 1] += 1
    for i in range(n):
        spring_ptr[i + 1] += spring_ptr[i]
    spring_ids = np.empty(spring_ptr[n], dtype=np.int64)
    fill = spring_ptr[:n].copy()
    for s in range(n_springs):  # ascending s: each body's list comes out sorted
        ia, ib = ends[s, 0], ends[s, 1]
        if ia >= 0:
            spring_ids[fill[ia]] = s
            fill[ia] += 1
        if ib >= 0 and ib != ia:
            spring_ids[fill[ib]] = s
            fill[ib] += 1
    force_ptr = np.zeros(n + 1, dtype=np.int64)
    for j in range(force_body.shape[0]):
        force_ptr[force_body[j] + 1] += 1
    for i in range(n):
        force_ptr[i + 1] += force_ptr[i]
    force_ids = np.empty(force_ptr[n], dtype=np.int64)
    fill = force_ptr[:n].copy()
    for j in range(force_body.shape[0]):
        force_ids[fill[force_body[j]]] = j
        fill[force_body[j]] += 1
    return spring_ptr, spring_ids, force_ptr, force_ids


@njit(cache=True, error_model="numpy")
def spring_balls(n, ends, spring_ptr, spring_ids, radius):
    """Per body i the bodies within ``radius`` springs of it (itself included), ascending, as
    CSR ``(ball_ptr, ball_idx)``: breadth-first over the springs, O(ball size x links) per body
    -- 2 radius + 1 bodies for a chain, whatever its length."""
    stamp = np.full(n, -1, dtype=np.int64)
    queue = np.empty(n, dtype=np.int64)
    depth = np.empty(n, dtype=np.int64)
    ptr = np.zeros(n + 1, dtype=np.int64)
    chunks = []
    for i in range(n):
        stamp[i] = i
        queue[0] = i
        depth[0] = 0
        head, tail = 0, 1
        while head < tail:
            body = queue[head]
            d = depth[head]
            head += 1
            if d == radius:
                continue
            for p in range(spring_ptr[body], spring_ptr[body + 1]):
                s = spring_ids[p]
                for e in range(2):
                    other = ends[s, e]
                    if other >= 0 and stamp[other] != i:
                        stamp[other] = i
                        queue[tail] = other
                        depth[tail] = d + 1
                        tail += 1
        chunks.append(np.sort(queue[:tail]))
        ptr[i + 1] = ptr[i] + tail
    idx = np.empty(ptr[n], dtype=np.int64)
    for i in range(n):
        idx[ptr[i] : ptr[i + 1]] = chunks[i]
    return ptr, idx


@njit(cache=True, error_model="numpy")
def _window_model(model, ball, local, spring_ptr, spring_ids, force_ptr, force_ids, stamp, tag):
    """The model of the bodies ``ball`` (ascending; ``local`` maps them to 0, 1, ... and every
    other body to -1): their springs whose other end is in the ball or an anchor, and their
    forces, each in its order in ``model`` -- so each body's loads are summed in the same order
    as in the whole model, to the bit. Springs to bodies outside are left out: their effect
    reaches the ball's centre only after as many force evaluations as the ball's radius."""
    bodies, springs, ends, forces, force_body, g = model
    w = ball.shape[0]
    links = 0
    for a in range(w):
        links += spring_ptr[ball[a] + 1] - spring_ptr[ball[a]]
    picked = np.empty(links, dtype=np.int64)
    count = 0
    for a in range(w):
        i = ball[a]
        for p in range(spring_ptr[i], spring_ptr[i + 1]):
            s = spring_ids[p]
            if stamp[s] == tag:
                continue
            stamp[s] = tag
            ia, ib = ends[s, 0], ends[s, 1]
            if (ia < 0 or local[ia] >= 0) and (ib < 0 or local[ib] >= 0):
                picked[count] = s
                count += 1
    chosen = np.sort(picked[:count])
    sub_springs = np.empty((count, springs.shape[1]))
    sub_ends = np.empty((count, 2), dtype=np.int64)
    for c in range(count):
        s = chosen[c]
        sub_springs[c] = springs[s]
        for e in range(2):
            sub_ends[c, e] = local[ends[s, e]] if ends[s, e] >= 0 else ends[s, e]
    n_forces = 0
    for a in range(w):
        n_forces += force_ptr[ball[a] + 1] - force_ptr[ball[a]]
    listed = np.empty(n_forces, dtype=np.int64)
    c = 0
    for a in range(w):
        for p in range(force_ptr[ball[a]], force_ptr[ball[a] + 1]):
            listed[c] = force_ids[p]
            c += 1
    listed = np.sort(listed)
    sub_forces = np.empty((n_forces, forces.shape[1]))
    sub_force_body = np.empty(n_forces, dtype=np.int64)
    for c in range(n_forces):
        sub_forces[c] = forces[listed[c]]
        sub_force_body[c] = local[force_body[listed[c]]]
    sub_bodies = np.empty((w, bodies.shape[1]))
    for a in range(w):
        sub_bodies[a] = bodies[ball[a]]
    return sub_bodies, sub_springs, sub_ends, sub_forces, sub_force_body, g


@njit(cache=True, error_model="numpy")
def refine_windowed(model, coeffs, h, q0, v0, offsets, balls, kinds, bodies, best, links):
    r""":func:`refine_extremes` of a large system, each extreme on the model of its body's ball
    (:func:`spring_balls` of radius
    :func:`~rollspring.simulate.integrators.refinement_radius`, :func:`_window_model`): entry j's
    ball is ``balls[offsets[j]:offsets[j + 1]]`` (global body numbers, ascending) and its
    state ``q0``/``v0`` over the same slice. The refinement sees body ``bodies[j]`` after at
    most 2 stages + 1 force evaluations, so the ball's edge never reaches it: the same numbers
    as on the whole model, each in O(ball) instead of O(n)."""
    spring_ptr, spring_ids, force_ptr, force_ids = links
    n = model[0].shape[0]
    local = np.full(n, -1, dtype=np.int64)
    stamp = np.full(model[1].shape[0], -1, dtype=np.int64)
    out = best.copy()
    for j in range(kinds.shape[0]):
        ball = balls[offsets[j] : offsets[j + 1]]
        for a in range(ball.shape[0]):
            local[ball[a]] = a
        sub = _window_model(
            model, ball, local, spring_ptr, spring_ids, force_ptr, force_ids, stamp, j
        )
        work = _refine_work(sub, ball.shape[0])
        out[j] = _refine_one(
            sub,
            coeffs,
            h,
            q0[offsets[j] : offsets[j + 1]],
            v0[offsets[j] : offsets[j + 1]],
            kinds[j],
            local[bodies[j]],
            out[j],
            work,
        )
        for a in range(ball.shape[0]):
            local[ball[a]] = -1
    return out


@njit(cache=True, error_model="numpy")
def signal_zero(model, coeffs, h, q0, v0, weights, q_ref):
    r"""The instant :math:`\tau \in [0, h]` at which the signal
    :math:`s = w \cdot (q - q_{ref})`, negative at (q0, v0) and not negative one step later,
    crosses zero: Newton with the exact rate :math:`\dot s = w \cdot \dot q`, safeguarded by
    bisection, on the integrator's own step, to rounding."""
    n = q0.shape[0]
    scratch, gen, fx, fy = _workspace(model, n)
    q = np.empty(n)
    v = np.empty(n)
    lo, hi = 0.0, h
    s_lo = 0.0
    for i in range(n):
        s_lo += weights[i] * (q0[i] - q_ref[i])
    _advance_into(model, coeffs, h, q0, v0, hi, q, v, scratch, gen, fx, fy)
    s_hi = 0.0
    for i in range(n):
        s_hi += weights[i] * (q[i] - q_ref[i])
    t = lo - s_lo * (hi - lo) / (s_hi - s_lo) if s_hi != s_lo else hi
    for _ in range(60):
        _advance_into(model, coeffs, h, q0, v0, t, q, v, scratch, gen, fx, fy)
        value = 0.0
        rate = 0.0
        for i in range(n):
            value += weights[i] * (q[i] - q_ref[i])
            rate += weights[i] * v[i]
        if value < 0.0:
            lo = t
        else:
            hi = t
        step = value / rate if rate != 0.0 else np.inf
        if abs(step) <= 1e-12 * h:
            return t - step
        candidate = t - step
        if not (lo < candidate < hi):
            candidate = 0.5 * (lo + hi)
        if hi - lo <= 1e-16 * max(h, 1.0):
            return candidate
        t = candidate
    return t


@njit(cache=True, error_model="numpy")
def slipping_derivatives(model, state, slipping, sign, damped, out):
    r"""Time derivative of the general state ``[x, phi, u, omega]`` (4n), docs/physics.md (M19).

    Rolling body: :math:`J\dot\omega = R F_x + \tau`, :math:`\dot u = R\dot\omega`; slider:
    :math:`m\dot u = F_x`; slipping body (``slipping[i]``, slip direction ``sign[i]`` = sign of
    the contact-point velocity :math:`v_s = u - R\omega`): :math:`f = -\mu_k N\,\mathrm{sign}`,
    :math:`m\dot u = F_x + f`, :math:`I\dot\omega = \tau - R f`.
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
        if b[i, ROLLS] == 0.0:
            out[2 * n + i] = fx[i] / b[i, MASS]
            out[3 * n + i] = 0.0
        elif slipping[i]:
            friction = -b[i, MU_K] * (b[i, MASS] * g - fy[i]) * sign[i]
            out[2 * n + i] = (fx[i] + friction) / b[i, MASS]
            out[3 * n + i] = (tau[i] - b[i, RADIUS] * friction) / b[i, CENTRAL]
        else:
            alpha = (b[i, SCALE] * fx[i] + tau[i]) / b[i, INERTIA]
            out[2 * n + i] = b[i, SCALE] * alpha
            out[3 * n + i] = alpha


@njit(cache=True, error_model="numpy")
def observe(
    model,
    states,
    slipping,
    sign,
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
    ``slipping``/``sign`` are per row."""
    n = states.shape[1] // 4
    b, springs, forces, force_body, g = model[0], model[1], model[3], model[4], model[5]
    fx = np.empty(n)
    fy = np.empty(n)
    tau = np.empty(n)
    zero_x = b[:, X0].copy()
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
            energy += 0.5 * springs[s, STIFF] * (length[row, s] - springs[s, REST]) ** 2
        for j in range(forces.shape[0]):
            i = force_body[j]
            px, py, _, _ = _point(b, i, forces[j, FR], forces[j, FALPHA], x, phi)
            p0x, p0y, _, _ = _point(b, i, forces[j, FR], forces[j, FALPHA], zero_x, zero_phi)
            energy -= forces[j, FX] * (px - p0x) + forces[j, FY] * (py - p0y)
        potential[row] = energy
        for i in range(n):
            normal[row, i] = b[i, MASS] * g - fy[i]
            if b[i, ROLLS] == 0.0:
                friction[row, i] = 0.0
            elif slipping[row, i]:
                friction[row, i] = -b[i, MU_K] * normal[row, i] * sign[row, i]
            else:
                friction[row, i] = (
                    b[i, MASS] * b[i, SCALE] * (b[i, SCALE] * fx[i] + tau[i]) / b[i, INERTIA]
                    - fx[i]
                )
        moving = 0.0
        for i in range(n):
            u = state[2 * n + i]
            w = state[3 * n + i]
            moving += 0.5 * (b[i, MASS] * u * u + central[i] * w * w)
            if b[i, ROLLS] == 0.0:
                ratio[row, i] = 0.0
            elif normal[row, i] <= 0.0:
                ratio[row, i] = np.inf
            elif math.isinf(b[i, MU_S]):
                ratio[row, i] = 0.0
            else:
                ratio[row, i] = abs(friction[row, i]) / (b[i, MU_S] * normal[row, i])
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
    zero_x = b[:, X0].copy()
    zero_phi = np.zeros(n)
    p0 = np.empty((forces.shape[0], 2))
    for j in range(forces.shape[0]):
        p0x, p0y, _, _ = _point(
            b, force_body[j], forces[j, FR], forces[j, FALPHA], zero_x, zero_phi
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
            scale = b[i, SCALE]
            rolls = b[i, ROLLS]
            x[i] = x0[i] + scale * qi
            phi[i] = rolls * qi
            u = scale * vi
            w = rolls * vi
            states[row, i] = x[i]
            states[row, n + i] = phi[i]
            states[row, 2 * n + i] = u
            states[row, 3 * n + i] = w
            moving += 0.5 * (b[i, MASS] * u * u + central[i] * w * w)
            fx[i] = 0.0
            fy[i] = 0.0
            tau[i] = 0.0
        energy = 0.0
        for s in range(springs.shape[0]):  # body_loads without damping
            dx, dy, dist, oax, oay, obx, oby = _spring_geometry(b, springs, ends, s, x, phi)
            t = springs[s, STIFF] * (dist - springs[s, REST])
            length[row, s] = dist
            tension[row, s] = t
            energy += 0.5 * springs[s, STIFF] * (dist - springs[s, REST]) ** 2
            if dy == 0.0 and 1e-150 < abs(dx) < 1e150:
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
        for j in range(forces.shape[0]):
            i = force_body[j]
            px, py, ox, oy = _point(b, i, forces[j, FR], forces[j, FALPHA], x, phi)
            fx[i] += forces[j, FX]
            fy[i] += forces[j, FY]
            tau[i] += ox * forces[j, FX] + oy * forces[j, FY]
        for j in range(forces.shape[0]):
            i = force_body[j]
            px, py, _, _ = _point(b, i, forces[j, FR], forces[j, FALPHA], x, phi)
            energy -= forces[j, FX] * (px - p0[j, 0]) + forces[j, FY] * (py - p0[j, 1])
        potential[row] = energy
        kinetic[row] = moving
        for i in range(n):
            nn = b[i, MASS] * g - fy[i]
            normal[row, i] = nn
            if b[i, ROLLS] == 0.0:
                f = 0.0
                ratio[row, i] = 0.0
            else:
                f = (
                    b[i, MASS] * b[i, SCALE] * (b[i, SCALE] * fx[i] + tau[i]) / b[i, INERTIA]
                    - fx[i]
                )
                if nn <= 0.0:
                    ratio[row, i] = np.inf
                elif math.isinf(b[i, MU_S]):
                    ratio[row, i] = 0.0
                else:
                    ratio[row, i] = abs(f) / (b[i, MU_S] * nn)
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


# -- the linear setup of small level systems (rollspring.simulate.run._small_level_equilibrium) --

#: :func:`level_setup`'s verdicts: done, or the general search decides
LEVEL, GENERAL = 0, 1
#: the kinds of modes, by their codes in :func:`level_setup`'s result
KIND_NAMES = ("oscillating", "zero", "unstable")
_OSCILLATING, _ZERO, _UNSTABLE = range(3)
#: the most bodies :func:`level_setup` takes (LAPACK's two-coordinate path, bit for bit)
MOST_BODIES = 2
#: the most springs, and numbers of the forces' (F, 2) array, :func:`level_setup` sums for the
#: force scale: NumPy sums fewer than 8 numbers in order (as here), more pairwise
_IN_ORDER = 7

_laev2 = njit(cache=True)(_linear._laev2)  # LAPACK's dlaev2, compiled from the same source


@njit(cache=True, error_model="numpy")
def _residual(model, q):
    r""":math:`\sqrt{Q(q)^T M^{-1} Q(q)}` and :math:`Q(q)`."""
    force = generalized_forces(model, q)
    total = 0.0
    for i in range(q.shape[0]):
        total += force[i] * force[i] * model[0][i, INV_INERTIA]
    return math.sqrt(total), force


@njit(cache=True, error_model="numpy")
def _modes(inertia, k, zero_tolerance, eps):
    r""":math:`K v = \lambda M v` of one or two coordinates as ``linear._small_eigh``
    (eigenvalues ascending, M-orthonormal columns) and :func:`~rollspring.analysis.
    normal_modes`' kinds (``zero_tolerance``: :data:`~rollspring.analysis.ZERO_MODE_TOLERANCE`;
    ``eps``: LAPACK's machine precision); ok False where that would not stand in for LAPACK."""
    n = inertia.shape[0]
    values = np.zeros(n)
    vectors = np.zeros((n, n))
    kinds = np.zeros(n, dtype=np.int64)
    factor0 = math.sqrt(inertia[0])
    inverse0 = 1.0 / factor0
    if n == 1:
        values[0] = k[0, 0] / (factor0 * factor0)
        vectors[0, 0] = inverse0
        if not math.isfinite(values[0]):
            return False, values, vectors, kinds
    else:
        factor1 = math.sqrt(inertia[1])
        inverse1 = 1.0 / factor1
        for a in range(2):
            for b in range(2):
                if not math.isfinite(k[a, b]):
                    return False, values, vectors, kinds
        d1 = k[0, 0] / (factor0 * factor0)
        e = k[1, 0] * inverse0 / factor1
        d2 = k[1, 1] / (factor1 * factor1)
        norm = max(abs(d1), abs(e), abs(d2))
        if not math.isfinite(norm) or (norm != 0.0 and not 1e-140 < norm < 1e140):
            return False, values, vectors, kinds
        if e == 0.0 or abs(e) <= (math.sqrt(abs(d1)) * math.sqrt(abs(d2))) * eps:
            w0, w1, c, s = d1, d2, 1.0, 0.0
        else:
            w0, w1, c, s = _laev2(d1, e, d2)
        z00, z01, z10, z11 = c, -s, s, c  # steqr's rotation of the identity
        if w1 < w0:  # steqr's closing selection sort
            w0, w1, z00, z01, z10, z11 = w1, w0, z01, z00, z11, z10
        values[0], values[1] = w0, w1
        vectors[0, 0], vectors[0, 1] = z00 * inverse0, z01 * inverse0
        vectors[1, 0], vectors[1, 1] = z10 * inverse1, z11 * inverse1
    largest = 0.0
    for m in range(n):
        largest = max(largest, abs(values[m]))
    for m in range(n):
        if largest == 0.0 or abs(values[m]) < zero_tolerance * largest:
            kinds[m] = _ZERO
            values[m] = 0.0
        elif values[m] < 0:
            kinds[m] = _UNSTABLE
        else:
            kinds[m] = _OSCILLATING
    if n == 2 and values[1] < values[0]:  # normal_modes' stable argsort
        values[0], values[1] = values[1], values[0]
        kinds[0], kinds[1] = kinds[1], kinds[0]
        for a in range(2):
            vectors[a, 0], vectors[a, 1] = vectors[a, 1], vectors[a, 0]
    return True, values, vectors, kinds


@njit(cache=True, error_model="numpy")
def level_setup(model, tolerance, zero_tolerance, eps):
    r"""The equilibrium and normal modes of a system of level centre springs of at most
    :data:`MOST_BODIES` bodies, given as its kernel model (:func:`~rollspring.simulate.kernels.
    kernel_model`) with every spring's ends level and apart: ``(verdict, q*, residual, K,
    eigenvalues, vectors, kinds)``, the numbers of :func:`~rollspring.analysis.find_equilibrium`
    with ``tolerance`` (kinds coded by :data:`KIND_NAMES`), or :data:`GENERAL` first where its
    general search decides. ``zero_tolerance`` and ``eps`` are :func:`~rollspring.analysis.
    normal_modes`' zero-mode threshold and LAPACK's machine precision, given rather than read
    from :mod:`rollspring.analysis.linear` (Numba's cache would keep another module's constants
    after they change).

    One or two bodies whose springs stay level (:func:`~rollspring.physics.springs_stay_level`:
    K constant, Q affine in q) take a few dozen floating-point operations, and the Python
    around them (the level branch of ``find_equilibrium`` and ``normal_modes``) was a seventh
    of the paper's simulation (0.1 ms of 0.72). Here they are one call, the same operations on
    the same numbers, so the same bits:

    1. :math:`Q_0 = Q(0)` (M7) and the residual :math:`\sqrt{Q_0^T M^{-1} Q_0}`; the tolerance is
       ``tolerance`` of the larger of that and the force scale (``linear._force_scale``);
    2. :math:`K = \sum_s k_s b_s b_s^T` (M12) with the constant lever arms
       :math:`b_{si} = e_s\sigma_{si}s_i` (``linear._level_stiffness``);
    3. :math:`K v = \lambda M v` by LAPACK's reduction and ``steqr`` on two coordinates
       (``linear._small_eigh``; ``linear._laev2`` compiled from its source), the kinds as
       ``normal_modes`` gives them;
    4. the equilibrium, one Newton step from the placement along the non-zero modes,
       :math:`q^* = \sum_{\lambda_n\ne0} v_n (v_n^T Q_0)/\lambda_n`, checked (residual within
       the tolerance, zero-mode coordinates :math:`V_0^T M q^*` at rounding)
       (``linear._level_equilibrium``).

    Whatever that branch hands to the general search (an unstable K, a force along a zero
    mode, a residual above the tolerance, numbers LAPACK would rescale), more than
    :data:`MOST_BODIES` bodies, and more springs or forces than NumPy sums in order for the
    force scale, come back as :data:`GENERAL`; the caller then runs ``find_equilibrium``,
    which decides as before. Tests check the two against each other bit for bit."""
    bodies, springs, ends = model[0], model[1], model[2]
    n = bodies.shape[0]
    q = np.zeros(n)
    stiffness = np.zeros((n, n))
    few = springs.shape[0] <= _IN_ORDER and 2 * model[3].shape[0] <= _IN_ORDER
    if n > MOST_BODIES or n == 0 or not few:
        return GENERAL, q, 0.0, stiffness, np.zeros(n), np.zeros((n, n)), np.zeros(n, np.int64)
    inertia = bodies[:, INERTIA].copy()
    for i in range(n):
        if not (inertia[i] > 0.0 and inertia[i] < math.inf):
            return GENERAL, q, 0.0, stiffness, np.zeros(n), np.zeros((n, n)), np.zeros(n, np.int64)
    initial, force_0 = _residual(model, q)
    # linear._force_scale: the springs' and forces' typical generalised force
    biggest = bodies[0, SCALE]
    smallest_inertia = inertia[0]
    for i in range(1, n):
        biggest = max(biggest, bodies[i, SCALE])
        smallest_inertia = min(smallest_inertia, inertia[i])
    spring_scale = 0.0
    n_springs = springs.shape[0]
    dx = np.empty(n_springs)
    lengths = np.empty(n_springs)
    for s in range(n_springs):
        a, b = ends[s, 0], ends[s, 1]
        xa = bodies[a, X0] if a >= 0 else springs[s, AAX]
        ya = bodies[a, CY] if a >= 0 else springs[s, AAY]
        xb = bodies[b, X0] if b >= 0 else springs[s, ABX]
        yb = bodies[b, CY] if b >= 0 else springs[s, ABY]
        dx[s] = xb - xa
        if dx[s] == 0.0:  # ends one above the other: not linear._level_centre_springs
            return GENERAL, q, 0.0, stiffness, np.zeros(n), np.zeros((n, n)), np.zeros(n, np.int64)
        lengths[s] = math.sqrt(dx[s] ** 2 + (yb - ya) ** 2)
        spring_scale += springs[s, STIFF] * lengths[s] * biggest
    forces = model[3]
    applied = 0.0
    for f in range(forces.shape[0]):
        applied += abs(forces[f, FX])
        applied += abs(forces[f, FY])
    applied *= biggest  # forces at centres: force_r is 0
    scale = max(initial, max(spring_scale, applied, 1e-300) / math.sqrt(smallest_inertia))
    target = tolerance * scale
    # linear._level_stiffness: K = sum_s k_s b_s b_s^T, summed in its order
    for s in range(n_springs):
        direction = dx[s] / lengths[s]
        k = springs[s, STIFF]
        for j in range(2):
            i = ends[s, j]
            if i < 0:
                continue
            b_i = direction * ((-1.0 if j == 0 else 1.0) * bodies[i, SCALE])
            for other in range(2):
                m = ends[s, other]
                if m < 0:
                    continue
                b_m = direction * ((-1.0 if other == 0 else 1.0) * bodies[m, SCALE])
                stiffness[i, m] += k * (b_i * b_m)
    ok, values, vectors, kinds = _modes(inertia, stiffness, zero_tolerance, eps)
    has_zero = has_oscillating = False
    for m in range(n):
        if kinds[m] == _UNSTABLE:
            ok = False
        has_zero = has_zero or kinds[m] == _ZERO
        has_oscillating = has_oscillating or kinds[m] == _OSCILLATING
    if not ok:
        return GENERAL, q, 0.0, stiffness, values, vectors, kinds
    residual = initial
    if initial > target:
        if has_zero and not has_oscillating:
            return GENERAL, q, 0.0, stiffness, values, vectors, kinds
        # linear._level_equilibrium: the Newton step along the non-zero modes
        for m in range(n):
            if kinds[m] == _ZERO:
                continue
            along = 0.0
            for i in range(n):
                along += vectors[i, m] * force_0[i]
            weight = along / values[m]
            for i in range(n):
                q[i] += vectors[i, m] * weight
        residual, _ = _residual(model, q)
        if not residual <= target:
            return GENERAL, q, 0.0, stiffness, values, vectors, kinds
        if has_zero:  # held: V0^T M q at rounding
            held = size = weight_scale = 0.0
            for i in range(n):
                size = max(size, abs(q[i]))
            size = max(1.0, size)
            for m in range(n):
                if kinds[m] != _ZERO:
                    continue
                along = 0.0
                for i in range(n):
                    along += vectors[i, m] * (inertia[i] * q[i])
                    weight_scale = max(weight_scale, abs(vectors[i, m] * inertia[i]))
                held = max(held, abs(along))
            if held > 1e-13 * size * weight_scale:
                return GENERAL, q, 0.0, stiffness, values, vectors, kinds
    return LEVEL, q, residual, stiffness, values, vectors, kinds

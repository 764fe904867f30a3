r"""The loads of the compiled kernels, composed from the force law (:mod:`.law`): attachment
points, spring tensions, loads, contact.

An attachment at distance :math:`r` and angle :math:`\alpha` (clockwise from up) on body
:math:`i` is at (M1)

.. math::

   P = (x_i + r\sin\theta,\; h_i + R_i + r\cos\theta), \qquad \theta = \alpha + \rho_i\varphi_i

and :func:`body_loads` gives each centre's resultant force :math:`(F_{ix}, F_{iy})` and clockwise
torque :math:`\tau_i` of the springs (tension :math:`T = k(l - L_0) + c\,\dot l`, :math:`+T e`
on end a, :math:`-T e` on end b) and the constant forces. A rolling body's generalised force is
:math:`Q_i = s_i F_{ix} + \tau_i` (M7) (:func:`rolling_forces`, the stepping's), its rate
:func:`force_rates`; (M8), (M9) give the friction it needs and its normal force
(:func:`_contact`). docs/physics.md §2.
"""

from __future__ import annotations

import numpy as np
from numba import njit

from rollspring.simulate.kernels import model as col
from rollspring.simulate.kernels.law import (
    attachment,
    attachment_lever,
    damping_tension,
    distance,
    elastic_tension,
    generalized_force,
    is_level,
    level_pull,
    needed_friction,
    normal_force,
    pull,
    pull_rate,
    spring_length,
    torque,
)

__all__ = ["body_loads", "force_rates", "generalized_forces", "rolling_forces"]


@njit(cache=True, inline="always", error_model="numpy")
def _point(bodies, i, r, alpha, x, phi):
    """Attachment position (M1) and its velocity per unit angular velocity at fixed centre."""
    return attachment(x[i], bodies[i, col.CY], bodies[i, col.ROLLS], r, alpha, phi[i])


@njit(cache=True, inline="always", error_model="numpy")
def _spring_geometry(bodies, springs, ends, s, x, phi):
    """Spring ``s``: the vector from its end a to its end b (dx, dy), its length, and each
    end's velocity per unit angular velocity of its body at a fixed centre (oax, oay, obx, oby;
    0 for an anchor), (M1). The two ends written out: with one inlined helper for both (as
    :func:`_rolling_end`) the whole simulate() call of the paper's system with 2001 outputs,
    which observes every row through this, took 8% longer (0.58 -> 0.63 ms)."""
    ia = ends[s, 0]
    ib = ends[s, 1]
    oax = 0.0
    oay = 0.0
    obx = 0.0
    oby = 0.0
    if ia >= 0:
        pax, pay, oax, oay = _point(bodies, ia, springs[s, col.RA], springs[s, col.ALPHA_A], x, phi)
    else:
        pax = springs[s, col.AAX]
        pay = springs[s, col.AAY]
    if ib >= 0:
        pbx, pby, obx, oby = _point(bodies, ib, springs[s, col.RB], springs[s, col.ALPHA_B], x, phi)
    else:
        pbx = springs[s, col.ABX]
        pby = springs[s, col.ABY]
    dx = pbx - pax
    dy = pby - pay
    return dx, dy, spring_length(dx, dy), oax, oay, obx, oby


@njit(cache=True, inline="always", error_model="numpy")
def _end_velocity(u, w, i, ox, oy):
    """The velocity of a point of body ``i`` (centre velocity u, angular velocity w; an anchor
    for -1) whose velocity per unit angular velocity at a fixed centre is (ox, oy)."""
    if i < 0:
        return 0.0, 0.0
    return u[i] + ox * w[i], oy * w[i]


@njit(cache=True, inline="always", error_model="numpy")
def _load(fx, fy, tau, i, sign, tx, ty, ox, oy):
    """Add ``sign`` times the force (tx, ty) at a point of body ``i`` whose velocity per unit
    angular velocity is (ox, oy), and its clockwise torque about the centre (``sign`` 1.0 or
    -1.0: the same bits as adding or subtracting). The caller skips an anchor (``i`` -1): with
    that test inside this inlined helper the stepping ran 1.8 times slower
    (bench_offcentre.py: 0.44 -> 0.82 s)."""
    fx[i] += sign * tx
    fy[i] += sign * ty
    tau[i] += sign * torque(ox, oy, tx, ty)


@njit(cache=True, inline="always", error_model="numpy")
def _load_ends(ends, s, t, dx, dy, dist, oax, oay, obx, oby, fx, fy, tau):
    """Add spring ``s``'s tension ``t`` to its bodies: :math:`+T e` on end a, :math:`-T e` on
    end b, and their clockwise torques about the centres."""
    tx, ty = pull(t, dx, dy, dist)
    if ends[s, 0] >= 0:
        _load(fx, fy, tau, ends[s, 0], 1.0, tx, ty, oax, oay)
    if ends[s, 1] >= 0:
        _load(fx, fy, tau, ends[s, 1], -1.0, tx, ty, obx, oby)


@njit(cache=True, inline="always", error_model="numpy")
def _load_forces(bodies, forces, force_body, x, phi, fx, fy, tau):
    """Add each constant external force to its body: the force and its clockwise torque about
    the centre (docs/physics.md §2)."""
    for j in range(forces.shape[0]):
        i = force_body[j]
        _, _, ox, oy = _point(bodies, i, forces[j, col.FR], forces[j, col.FALPHA], x, phi)
        _load(fx, fy, tau, i, 1.0, forces[j, col.FX], forces[j, col.FY], ox, oy)


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
        t = elastic_tension(springs[s, col.STIFF], springs[s, col.REST], dist)
        if damped and springs[s, col.DAMP] != 0.0:
            vax, vay = _end_velocity(u, w, ends[s, 0], oax, oay)
            vbx, vby = _end_velocity(u, w, ends[s, 1], obx, oby)
            t += damping_tension(springs[s, col.DAMP], dx, dy, vbx - vax, vby - vay, dist)
        length[s] = dist
        tension[s] = t
        _load_ends(ends, s, t, dx, dy, dist, oax, oay, obx, oby, fx, fy, tau)
    _load_forces(bodies, forces, force_body, x, phi, fx, fy, tau)


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
        pax, pay, oax, oay = _rolling_end(bodies, springs, ia, s, 0, q)
        pbx, pby, obx, oby = _rolling_end(bodies, springs, ib, s, 1, q)
        dx = pbx - pax
        dy = pby - pay
        if is_level(dx, dy):
            # a level spring (both ends at one height): T e_x = k (|dx| - L0) sign(dx), without
            # the square root and the division on the stepping's chain
            tx = level_pull(springs[s, col.STIFF], springs[s, col.REST], dx)
            ty = 0.0
        else:
            dist = distance(dx, dy)
            tx, ty = pull(
                elastic_tension(springs[s, col.STIFF], springs[s, col.REST], dist), dx, dy, dist
            )
        if ia >= 0:
            _load(fx, fy, tau, ia, 1.0, tx, ty, oax, oay)
        if ib >= 0:
            _load(fx, fy, tau, ib, -1.0, tx, ty, obx, oby)
    for j in range(forces.shape[0]):
        i = force_body[j]
        _, _, ox, oy = _rolling_point(bodies, i, forces[j, col.FR], forces[j, col.FALPHA], q)
        _load(fx, fy, tau, i, 1.0, forces[j, col.FX], forces[j, col.FY], ox, oy)
    for i in range(q.shape[0]):
        gen[i] = generalized_force(bodies[i, col.SCALE], fx[i], tau[i])


@njit(cache=True, inline="always", error_model="numpy")
def _rolling_point(bodies, i, r, alpha, q):
    """:func:`_point` of an all-rolling state q: centre x = x0 + s q, rotation q."""
    x = bodies[i, col.X0] + bodies[i, col.SCALE] * q[i]
    return attachment(x, bodies[i, col.CY], bodies[i, col.ROLLS], r, alpha, q[i])


@njit(cache=True, inline="always", error_model="numpy")
def _rolling_end(bodies, springs, i, s, e, q):
    """End ``e`` (0: a, 1: b) of spring ``s`` in the all-rolling state q, on body ``i`` (-1: an
    anchor): its position and its velocity per unit angular velocity of the body at a fixed
    centre (0 for an anchor), (M1). An end's columns are end a's plus ``2 e`` (:mod:`.model`)."""
    if i < 0:
        return springs[s, col.AAX + 2 * e], springs[s, col.AAY + 2 * e], 0.0, 0.0
    return _rolling_point(bodies, i, springs[s, col.RA + 2 * e], springs[s, col.ALPHA_A + 2 * e], q)


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
    friction = (
        needed_friction(b[i, col.MASS], b[i, col.SCALE], b[i, col.INERTIA], gen_i, fx_i)
        if b[i, col.ROLLS] > 0.0
        else 0.0
    )
    return friction, normal_force(b[i, col.MASS] * model[5], fy_i)


@njit(cache=True, inline="always", error_model="numpy")
def _rolling_lever(bodies, i, r, alpha, q, v):
    r"""Of a point at (r, alpha) on body i in the all-rolling state (q, v): its position p,
    its lever :math:`\ell = \partial p/\partial q_i` and the lever's rate
    :math:`\dot\ell = \dot q_i\,\partial\ell/\partial q_i` (M1):
    (px, py, lx, ly, dlx, dly)."""
    x = bodies[i, col.X0] + bodies[i, col.SCALE] * q[i]
    return attachment_lever(
        x, bodies[i, col.CY], bodies[i, col.SCALE], bodies[i, col.ROLLS], r, alpha, q[i], v[i]
    )


@njit(cache=True, inline="always", error_model="numpy")
def _lever_end(bodies, springs, i, s, e, q, v):
    """:func:`_rolling_lever` of end ``e`` of spring ``s`` on body ``i`` (as
    :func:`_rolling_end`), and the end's velocity: (px, py, lx, ly, dlx, dly, vx, vy), the lever
    0 for an anchor."""
    if i < 0:
        px, py = springs[s, col.AAX + 2 * e], springs[s, col.AAY + 2 * e]
        return px, py, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0
    px, py, lx, ly, dlx, dly = _rolling_lever(
        bodies, i, springs[s, col.RA + 2 * e], springs[s, col.ALPHA_A + 2 * e], q, v
    )
    return px, py, lx, ly, dlx, dly, lx * v[i], ly * v[i]


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
        pax, pay, lax, lay, dlax, dlay, vax, vay = _lever_end(bodies, springs, ia, s, 0, q, v)
        pbx, pby, lbx, lby, dlbx, dlby, vbx, vby = _lever_end(bodies, springs, ib, s, 1, q, v)
        dx = pbx - pax
        dy = pby - pay
        ddx = vbx - vax
        ddy = vby - vay
        k = springs[s, col.STIFF]
        if ddy == 0.0 and is_level(dx, dy):
            # a level spring staying level: F_x = k (|dx| - L0) sign(dx), dF_x/dt = k ddx
            force_x = level_pull(k, springs[s, col.REST], dx)
            force_y = 0.0
            rate_x = k * ddx
            rate_y = 0.0
        else:
            force_x, force_y, rate_x, rate_y = pull_rate(k, springs[s, col.REST], dx, dy, ddx, ddy)
        if ia >= 0:
            rate[ia] += dlax * force_x + dlay * force_y + lax * rate_x + lay * rate_y
        if ib >= 0:
            rate[ib] -= dlbx * force_x + dlby * force_y + lbx * rate_x + lby * rate_y
    for j in range(forces.shape[0]):
        i = force_body[j]
        _, _, _, _, dlx, dly = _rolling_lever(
            bodies, i, forces[j, col.FR], forces[j, col.FALPHA], q, v
        )
        rate[i] += dlx * forces[j, col.FX] + dly * forces[j, col.FY]

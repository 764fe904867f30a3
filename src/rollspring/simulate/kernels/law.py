r"""The force law, written once: every force term as a scalar function Numba inlines.

Each term of docs/physics.md §2 is one small function of plain floats (no model arrays, no
columns), compiled with ``inline="always"`` so that it becomes part of the caller's own code:
the single-run kernels (:mod:`.forces`, :mod:`.observation`, :mod:`.linear_setup` through
:func:`~.forces.generalized_forces`) and the generated batch kernels
(:mod:`rollspring.simulate.batch.codegen`, which imports this module into every kernel it writes)
call them; the NumPy physics (:mod:`rollspring.physics.mechanics`) and the SymPy derivation are
checked against them, row by row, in ``tests/test_force_law.py`` (the linear part over many runs,
:mod:`rollspring.analysis.batch_linear`, is checked against ``analyze`` in
``tests/test_batch_linear.py``). An inlined call is the same operations on the same numbers as the
expression written out, so the callers' results are the same bits; the callers keep their loops,
loads and stores (a shared helper that writes the loads into arrays, with the test for an anchor
end inside it, made the stepping 1.8 to 2.5 times slower). docs/force-law.md lists the places a
new force term touches.

The terms, with the equations they implement:

* :func:`attachment` -- a point at (r, alpha) on a body and its velocity per unit angular
  velocity at a fixed centre (M1);
* :func:`attachment_lever` -- the same point in the all-rolling state, its lever
  :math:`\partial P/\partial q` and the lever's rate;
* :func:`distance`, :func:`spring_length` -- a spring's length (the latter exact for a level
  spring without a square root);
* :func:`elastic_tension` -- :math:`T = k(l - L_0)`; :func:`damping_tension` -- :math:`c\,\dot l`;
* :func:`pull` -- the force :math:`T e` on end a (:math:`-T e` on end b);
  :func:`level_pull` -- the same for a level spring, :math:`k(d_x - L_0\,\mathrm{sign}\,d_x)`;
  :func:`pull_rate` -- the elastic force on end a and its rate :math:`\dot F`;
* :func:`torque` -- the clockwise torque of a force at a point whose velocity per unit angular
  velocity is (ox, oy); :func:`arm_torque` -- the same from the arm :math:`P - C`;
* :func:`generalized_force` -- :math:`Q_i = s_i F_{ix} + \tau_i` (M7); :func:`reduced_force`
  -- the same per unit travel of the centre, :math:`Q_i/s_i`;
* :func:`needed_friction` -- the static friction rolling needs, (M8), from Q;
  :func:`rolling_friction` -- the same from the centre's acceleration, :math:`m\ddot x - F_x`;
* :func:`normal_force` -- :math:`N = m g - F_y` (M9);
* :func:`kinetic_friction` -- :math:`-\mu_k N\,\mathrm{sign}\,v_s` while slipping (M19);
* :func:`rolling_resistance` -- the torque :math:`-C_{rr} N R\,\mathrm{sign}\,\omega` of the
  normal force acting :math:`C_{rr} R` ahead of the contact (docs/physics.md (M21));
  :func:`resistance_limit` -- the largest torque it holds a body at rest against,
  :math:`C_{rr} N R`;
* :func:`spring_energy` -- :math:`\tfrac12 k (l - L_0)^2`; :func:`work` -- a constant force's
  work :math:`F\cdot\Delta P`.

A constant (external) force enters as its components and :func:`torque` at its point.
"""

from __future__ import annotations

import math

from numba import njit

__all__ = [
    "arm_torque",
    "attachment",
    "attachment_lever",
    "damping_tension",
    "distance",
    "elastic_tension",
    "generalized_force",
    "is_level",
    "kinetic_friction",
    "level_pull",
    "needed_friction",
    "normal_force",
    "pull",
    "pull_rate",
    "reduced_force",
    "resistance_limit",
    "rolling_friction",
    "rolling_resistance",
    "spring_energy",
    "spring_length",
    "torque",
    "work",
]


@njit(cache=True, inline="always", error_model="numpy")
def attachment(cx, cy, rolls, r, alpha, phi):
    r"""(M1): the point at distance ``r``, angle ``alpha`` (clockwise from up) on a body with
    centre (cx, cy) turned by ``phi`` (``rolls`` 0 for a slider), and its velocity per unit
    angular velocity at a fixed centre: ``(px, py, ox, oy)``,
    :math:`P = (c_x + r\sin\theta, c_y + r\cos\theta)`, :math:`\theta = \alpha + \rho\varphi`."""
    if r == 0.0:
        return cx, cy, 0.0, 0.0
    theta = alpha + rolls * phi
    s = math.sin(theta)
    c = math.cos(theta)
    return cx + r * s, cy + r * c, rolls * r * c, -rolls * r * s


@njit(cache=True, inline="always", error_model="numpy")
def attachment_lever(cx, cy, scale, rolls, r, alpha, q, v):
    r"""Of the point (r, alpha) on a rolling body (centre (cx, cy), coordinate q, rate v): its
    position p, its lever :math:`\ell = \partial p/\partial q` and the lever's rate
    :math:`\dot\ell = \dot q\,\partial\ell/\partial q` (M1): ``(px, py, lx, ly, dlx, dly)``."""
    if r == 0.0:
        return cx, cy, scale, 0.0, 0.0, 0.0
    theta = alpha + rolls * q
    s = math.sin(theta)
    c = math.cos(theta)
    spin = rolls * rolls * v
    return (
        cx + r * s,
        cy + r * c,
        scale + rolls * r * c,
        -rolls * r * s,
        -spin * r * s,
        -spin * r * c,
    )


@njit(cache=True, inline="always", error_model="numpy")
def distance(dx, dy):
    """The length of the vector (dx, dy)."""
    return math.sqrt(dx * dx + dy * dy)


@njit(cache=True, inline="always", error_model="numpy")
def is_level(dx, dy):
    """Both ends of a spring at one height, and dx^2 neither overflowing nor underflowing: its
    length is |dx| exactly (IEEE round-to-nearest)."""
    return dy == 0.0 and 1e-150 < abs(dx) < 1e150


@njit(cache=True, inline="always", error_model="numpy")
def spring_length(dx, dy):
    """A spring's length; a level spring's is |dx|, without the square root's latency on the
    stepping's chain (:func:`is_level`: the same number)."""
    return abs(dx) if is_level(dx, dy) else distance(dx, dy)


@njit(cache=True, inline="always", error_model="numpy")
def elastic_tension(k, rest, length):
    r"""The elastic tension :math:`T = k(l - L_0)` (positive when stretched)."""
    return k * (length - rest)


@njit(cache=True, inline="always", error_model="numpy")
def damping_tension(c, dx, dy, dvx, dvy, length):
    r"""The damping tension :math:`c\,\dot l = c\,(d\cdot\dot d)/l` (d = end b - end a)."""
    return c * (dx * dvx + dy * dvy) / length


@njit(cache=True, inline="always", error_model="numpy")
def pull(t, dx, dy, length):
    r"""The force of tension ``t`` on end a: :math:`T e = (T/l)\,d` (end b takes :math:`-T e`);
    where the ends meet (:math:`l = 0`) a spring without tension (rest length 0) pulls with
    :math:`k\,d = 0`, and one with tension with no defined direction (NaN)."""
    per_length = t / length if length > 0.0 or t != 0.0 else 0.0
    return per_length * dx, per_length * dy


@njit(cache=True, inline="always", error_model="numpy")
def level_pull(k, rest, dx):
    r""":func:`pull` of a level spring's elastic tension, :math:`T e_x = k(d_x - L_0\,
    \mathrm{sign}\,d_x)`: neither a square root nor a division (the same number as
    :math:`k(|d_x| - L_0)\,\mathrm{sign}\,d_x` for :math:`d_x \ne 0`)."""
    return k * (dx - math.copysign(rest, dx))


@njit(cache=True, inline="always", error_model="numpy")
def pull_rate(k, rest, dx, dy, ddx, ddy):
    r"""The elastic force on end a, :math:`F = k(1 - L_0/l)\,d`, and its rate
    :math:`\dot F = k(1 - L_0/l)\,\dot d + k L_0 (d\cdot\dot d)/l^3\,d` (d = end b - end a,
    :math:`l = |d|`, :math:`\dot d` = (ddx, ddy)): ``(fx, fy, rate_x, rate_y)``, the jerks of
    the stepping's outputs (:func:`~.forces.force_rates`)."""
    length = distance(dx, dy)
    if rest == 0.0:  # a zero-length spring: F = k d, smooth where its ends meet
        return k * dx, k * dy, k * ddx, k * ddy
    stretch = k * (1.0 - rest / length)
    along = k * rest * (dx * ddx + dy * ddy) / (length * length * length)
    return stretch * dx, stretch * dy, stretch * ddx + along * dx, stretch * ddy + along * dy


@njit(cache=True, inline="always", error_model="numpy")
def torque(ox, oy, fx, fy):
    r"""The clockwise torque about the centre of the force (fx, fy) at a point whose velocity per
    unit angular velocity is (ox, oy) (:func:`attachment`): :math:`o\cdot F`."""
    return ox * fx + oy * fy


@njit(cache=True, inline="always", error_model="numpy")
def arm_torque(ax, ay, fx, fy):
    r"""The clockwise torque of the force (fx, fy) at the arm (ax, ay) = P - C:
    :math:`a_y F_x - a_x F_y` (:func:`torque` with :math:`o = (a_y, -a_x)`)."""
    return ay * fx - ax * fy


@njit(cache=True, inline="always", error_model="numpy")
def generalized_force(scale, fx, tau):
    r"""(M7) A rolling body's generalised force :math:`Q_i = s_i F_{ix} + \tau_i` (the torque
    about the contact point; ``scale`` :math:`s_i` is the centre's travel per unit q)."""
    return scale * fx + tau


@njit(cache=True, inline="always", error_model="numpy")
def reduced_force(fx, tau, inv_scale):
    r"""(M7) per unit travel of the centre, :math:`Q_i/s_i = F_{ix} + \tau_i/s_i` (``inv_scale``
    :math:`1/s_i`; the batch kernels', which step the centre's displacement)."""
    return fx + tau * inv_scale


@njit(cache=True, inline="always", error_model="numpy")
def needed_friction(mass, scale, inertia, gen, fx):
    r"""(M8) The static friction a rolling body needs, :math:`f = m s Q/J - F_x` (+x)."""
    return mass * scale * gen / inertia - fx


@njit(cache=True, inline="always", error_model="numpy")
def rolling_friction(mass, acc, fx):
    r"""(M8) from the centre's acceleration: :math:`f = m\ddot x - F_x` (the batch kernels')."""
    return mass * acc - fx


@njit(cache=True, inline="always", error_model="numpy")
def normal_force(weight, fy):
    """(M9) The floor's normal force N = m g - F_y (``weight`` m g)."""
    return weight - fy


@njit(cache=True, inline="always", error_model="numpy")
def kinetic_friction(mu_k, normal, sign):
    r"""(M19) Kinetic friction while slipping, :math:`-\mu_k N\,\mathrm{sign}(v_s)`."""
    return -mu_k * normal * sign


@njit(cache=True, inline="always", error_model="numpy")
def rolling_resistance(c_rr, normal, radius, spin):
    r"""(M21) Rolling resistance: the floor's normal force acts :math:`C_{rr} R` ahead of the
    contact point, a clockwise torque :math:`-C_{rr} N R\,\mathrm{sign}\,\omega` about the
    contact (and about the centre) opposing the rotation (``spin`` the sign of
    :math:`\omega`, +1 or -1). For a rolling body it is a generalised force beside Q:
    :math:`(1+\gamma) m\ddot x = Q/R - C_{rr} N\,\mathrm{sign}\,\dot x`."""
    return -c_rr * normal * radius * spin


@njit(cache=True, inline="always", error_model="numpy")
def resistance_limit(c_rr, normal, radius):
    r"""(M22) The largest torque the shifted normal force holds a body at rest against,
    :math:`C_{rr} N R`: a body at rest stays so while the torque driving it is within it."""
    return c_rr * normal * radius


@njit(cache=True, inline="always", error_model="numpy")
def spring_energy(k, rest, length):
    r"""A spring's elastic energy :math:`\tfrac12 k (l - L_0)^2`."""
    return 0.5 * k * (length - rest) ** 2


@njit(cache=True, inline="always", error_model="numpy")
def work(fx, fy, dx, dy):
    r"""The work :math:`F\cdot\Delta P` of a constant force (fx, fy) over the displacement
    (dx, dy) of its point (the potential is its negative)."""
    return fx * dx + fy * dy

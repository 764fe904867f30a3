r"""Exact rolling mechanics: pure, vectorised functions of a system and a state.

The state is ``q`` (shape ``(..., n)``; rotation angles of rolling bodies, displacements of
sliders, see :mod:`rollspring.physics.arrays`) and, where velocities matter, ``qdot``. Nothing
here uses a small-angle approximation. Equation tags (M1)... refer to ``docs/physics.md``; "paper"
is G. Nyitray, *On the edge of complexity* (arXiv 2508.01379).

Sign conventions: ``x`` right, ``y`` up; rotations clockwise positive; the static friction ``f``
on a body is positive along +x; a spring's tension is positive when it is stretched.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING, Any, Literal, overload

import numpy as np
from numpy.typing import ArrayLike

from rollspring.physics.arrays import FloatArray, IntArray, SystemArrays

if TYPE_CHECKING:
    from scipy.sparse import csr_array

__all__ = [
    "SpringState",
    "accelerations",
    "body_forces",
    "body_forces_jacobian",
    "centre_of_mass",
    "centre_positions",
    "contact_forces",
    "contact_forces_jacobian",
    "damping_matrix",
    "dissipated_power",
    "end_kinematics",
    "force_point_kinematics",
    "force_work",
    "generalized_forces",
    "kinetic_energy",
    "mass_matrix",
    "potential_energy",
    "pseudo_momentum_conserved",
    "resisted_accelerations",
    "resisted_contact_forces",
    "rolling_resistance_torque",
    "spring_energies",
    "spring_pair_matrix",
    "spring_state",
    "springs_stay_level",
    "stiffness_entries",
    "stiffness_matrix",
    "total_energy",
]


def _as_state(system: SystemArrays, q: FloatArray | float) -> FloatArray:
    q = np.asarray(q, dtype=np.float64)
    if q.ndim == 0:
        q = np.full(system.n_bodies, float(q))
    if q.shape[-1] != system.n_bodies:
        raise ValueError(
            f"q has {q.shape[-1]} coordinates; the system has {system.n_bodies} bodies"
        )
    return q


def _point_kinematics(
    system: SystemArrays, body: ArrayLike, r: FloatArray, alpha: FloatArray, q: FloatArray
) -> tuple[FloatArray, FloatArray, FloatArray]:
    """Position, first and second derivative (w.r.t. the body's coordinate) of body points."""
    index = np.asarray(body, dtype=np.int64)
    qb = q[..., index]
    s, rho = system.scale[index], system.rolls[index]
    theta = alpha + rho * qb
    sin, cos = np.sin(theta), np.cos(theta)
    x = system.x0[index] + s * qb + r * sin
    y = system.track[index] + system.radius[index] + r * cos
    position = np.stack([x, y], axis=-1)
    first = np.stack([s + rho * r * cos, -rho * r * sin], axis=-1)
    second = np.stack([-(rho**2) * r * sin, -(rho**2) * r * cos], axis=-1)
    return position, first, second


def end_kinematics(
    system: SystemArrays, q: FloatArray
) -> tuple[FloatArray, FloatArray, FloatArray]:
    r"""Positions of the spring ends and their derivatives with respect to their body's coordinate.

    .. math::
        P = \bigl(x_{i0} + s_i q_i + r\sin\theta,\; h_i + R_i + r\cos\theta\bigr),\quad
        \theta = \alpha + \rho_i q_i                                                    \\
        \frac{dP}{dq_i} = (s_i + \rho_i r\cos\theta,\; -\rho_i r\sin\theta),\quad
        \frac{d^2P}{dq_i^2} = -\rho_i^2 (r\sin\theta,\; r\cos\theta)

    docs/physics.md (M1)-(M3). An anchor end is fixed: its derivatives are zero.
    Shapes: ``q`` (..., n) -> three arrays (..., S, 2 ends, 2 components).
    """
    q = _as_state(system, q)
    position, first, second = _point_kinematics(
        system, system.end_index, system.end_r, system.end_alpha, q
    )
    is_anchor = (system.end_body < 0)[..., None]
    position = np.where(is_anchor, system.end_anchor, position)
    first = np.where(is_anchor, 0.0, first)
    second = np.where(is_anchor, 0.0, second)
    return position, first, second


def force_point_kinematics(
    system: SystemArrays, q: FloatArray
) -> tuple[FloatArray, FloatArray, FloatArray]:
    """Points of application of the external forces, and derivatives, as :func:`end_kinematics`.

    Shapes: ``q`` (..., n) -> three arrays (..., F, 2).
    """
    q = _as_state(system, q)
    return _point_kinematics(system, system.force_body, system.force_r, system.force_alpha, q)


#: d = P_b - P_a: the sign of each end's contribution to the spring vector
_SIGN = np.array([-1.0, 1.0])


def _sum_to(index: IntArray, n: int, values: FloatArray) -> FloatArray:
    """Sum ``values`` (..., E) into ``n`` bins by ``index`` (E,): (..., n). O(E) work and
    memory, whatever the leading shape (one ``bincount`` over flattened bins)."""
    lead = values.shape[:-1]
    if values.shape[-1] == 0:
        return np.zeros((*lead, n))
    rows = values.reshape(-1, values.shape[-1])
    if rows.shape[0] == 1:
        total: Any = np.bincount(index, weights=rows[0], minlength=n)
    else:
        bins = (np.arange(rows.shape[0])[:, None] * n + index).reshape(-1)
        total = np.bincount(bins, weights=rows.reshape(-1), minlength=rows.shape[0] * n)
    result: FloatArray = total.reshape(*lead, n)
    return result


def _ends_to_bodies(system: SystemArrays, values: FloatArray) -> FloatArray:
    """Sum per-end values (..., S, 2) onto the bodies the ends are on, (..., n); anchor ends
    are dropped. The sparse form of a contraction with the (S, 2, n) incidence."""
    on_body = values * system.end_on_body
    return _sum_to(
        system.end_index.reshape(-1), system.n_bodies, on_body.reshape(*values.shape[:-2], -1)
    )


@dataclass(frozen=True)
class SpringState:
    r"""Every spring's geometry and force in one configuration (arrays of shape (..., S)).

    ``vector`` :math:`d = P_b - P_a`, ``length`` :math:`l = |d|`, ``direction``
    :math:`e = d/l`, ``tension`` :math:`T = k(l - L_0) + c\,\dot l` (positive when stretched),
    ``end_lever`` (..., S, 2) the lever arm :math:`b_{si} = \partial l/\partial q_i` with
    respect to the coordinate of the body each end is on (0 at an anchor); ``lever`` is the
    same as a dense (..., S, n) array (S x n numbers: for small systems).
    """

    vector: FloatArray
    length: FloatArray
    direction: FloatArray
    tension: FloatArray
    end_lever: FloatArray
    end_index: IntArray
    n_bodies: int

    @property
    def lever(self) -> FloatArray:
        r""":math:`b_{si} = \partial l_s/\partial q_i`, dense (..., S, n)."""
        lead = self.end_lever.shape[:-2]
        n_springs = self.end_lever.shape[-2]
        dense = np.zeros((*lead, n_springs, self.n_bodies))
        if dense.size == 0:
            return dense
        view = dense.reshape(-1, n_springs, self.n_bodies)
        per_end = self.end_lever.reshape(-1, n_springs, 2)
        rows = np.arange(n_springs)
        for j in (0, 1):
            where: Any = (slice(None), rows, self.end_index[:, j])
            np.add.at(view, where, per_end[:, :, j])
        return dense


def tension_per_length(system: SystemArrays, length: FloatArray) -> FloatArray:
    r"""The elastic tension per unit length of each spring, :math:`T/l = k(1 - L_0/l)`, the
    factor of the geometric stiffness :math:`T H` (M13) and of the pull's change across the
    spring: at :math:`l = 0` it is its limit :math:`k` for a rest length :math:`L_0 = 0` (a
    zero-length spring's force :math:`k\,d` is smooth through the meeting of its ends), and
    :math:`-\infty` otherwise (a force of magnitude :math:`kL_0` whose direction is undefined)."""
    length = np.asarray(length, dtype=float)
    tension = system.stiffness * (length - system.rest_length)
    meeting = np.where(system.rest_length == 0, system.stiffness, -np.inf)
    out: FloatArray = np.broadcast_to(meeting, np.broadcast(tension, length).shape).copy()
    np.divide(tension, length, out=out, where=length > 0)
    return out


def spring_state(
    system: SystemArrays, q: FloatArray, qdot: FloatArray | None = None
) -> SpringState:
    r"""Lengths, directions, tensions and lever arms of every spring.

    .. math:: T_s = k_s (l_s - L_{0s}) + c_s \dot l_s, \qquad
              b_{si} = \frac{\partial l_s}{\partial q_i} = e_s\cdot\Delta_{si},\qquad
              \Delta_{si} = \pm\frac{dP}{dq_i}

    docs/physics.md section 2 and (M7): :math:`b_{si}` is the signed lever arm of spring s about the
    contact point of body i (for a slider, the x-component of ``e``), non-zero only for the
    (at most two) bodies the spring's ends are on, so it is kept per end: O(S) work and memory.
    The damping term needs ``qdot``; without it the tension is the elastic one.
    """
    q = _as_state(system, q)
    position, first, _ = end_kinematics(system, q)
    vector = position[..., 1, :] - position[..., 0, :]
    length = np.sqrt(np.sum(vector**2, axis=-1))
    # e = d / l; 0 where the ends meet (l = 0), where only a spring of rest length 0 can be,
    # and its force k d and stiffness (tension_per_length) do not depend on e
    direction = np.divide(
        vector, length[..., None], out=np.zeros_like(vector), where=length[..., None] > 0
    )
    delta = _SIGN[:, None] * first  # (..., S, 2, 2): d(d)/dq of each end's body
    end_lever = np.einsum("...sc,...sjc->...sj", direction, delta)
    tension = system.stiffness * (length - system.rest_length)
    if qdot is not None:
        qdot = _as_state(system, qdot)
        length_rate = np.sum(end_lever * qdot[..., system.end_index], axis=-1)
        tension = tension + system.damping * length_rate
    return SpringState(
        vector, length, direction, tension, end_lever, system.end_index, system.n_bodies
    )


def generalized_forces(
    system: SystemArrays, q: FloatArray, qdot: FloatArray | None = None
) -> FloatArray:
    r"""Generalised forces :math:`Q_i = -\partial U/\partial q_i` (+ damping), shape (..., n).

    .. math:: Q_i = -\sum_s T_s b_{si} + \sum_{\text{forces on } i} F\cdot\frac{dP}{dq_i}

    For a rolling body :math:`Q_i` is the clockwise torque of the applied forces about its contact
    point :math:`K_i` (N m), docs/physics.md (M7); for a slider the horizontal force (N). The
    paper's eqs. (e), (f) and (a), (b) are special cases.
    """
    q = _as_state(system, q)
    springs = spring_state(system, q, qdot)
    torque = -_ends_to_bodies(system, springs.tension[..., None] * springs.end_lever)
    if system.force.shape[0]:
        _, first, _ = force_point_kinematics(system, q)
        work = np.einsum("fc,...fc->...f", system.force, first)
        torque = torque + _sum_to(system.force_body, system.n_bodies, work)
    result: FloatArray = torque
    return result


def mass_matrix(system: SystemArrays) -> FloatArray:
    r"""The constant diagonal mass matrix :math:`M = \mathrm{diag}(J_i)`, docs/physics.md (M4),
    (M12).

    :math:`J_i = (1+\gamma_i) m_i R_i^2` (kg m^2) for a rolling body (the paper's :math:`I'`,
    e.g. :math:`2m_1R^2` for the hoop and :math:`\tfrac32 m_2R^2` for the cylinder), ``m`` (kg)
    for a slider.
    """
    return np.diag(system.inertia)


def accelerations(
    system: SystemArrays, q: FloatArray, qdot: FloatArray | None = None
) -> FloatArray:
    r"""Exact equations of motion while every body rolls: :math:`\ddot q_i = Q_i / J_i`.

    docs/physics.md (M7), from the Lagrangian (M5): :math:`J_i\ddot\varphi_i = -\partial U/\partial
    \varphi_i`.
    """
    return generalized_forces(system, q, qdot) / system.inertia


def body_forces(system: SystemArrays, q: FloatArray, qdot: FloatArray | None = None) -> FloatArray:
    r"""Resultant applied force :math:`F_i = (F_{ix}, F_{iy})` on every body (springs and external
    forces; not gravity, friction or the normal force). Shape (..., n, 2), newtons.

    A spring pulls its end a with :math:`+T e` and its end b with :math:`-T e` (docs/physics.md
    section 2).
    """
    q = _as_state(system, q)
    springs = spring_state(system, q, qdot)
    pull = springs.tension[..., None] * springs.direction  # force on end a
    end_force = np.stack([pull, -pull], axis=-2)  # (..., S, 2 ends, 2 components)
    total = np.moveaxis(_ends_to_bodies(system, np.moveaxis(end_force, -1, -3)), -2, -1)
    if system.force.shape[0]:
        total = total + _sum_to(system.force_body, system.n_bodies, system.force.T).T
    result: FloatArray = total
    return result


def contact_forces(
    system: SystemArrays, q: FloatArray, qdot: FloatArray | None = None
) -> tuple[FloatArray, FloatArray]:
    r"""Static friction and normal force each body needs in configuration ``q``.

    .. math:: f_i = m_i R_i \ddot\varphi_i - F_{ix} = \frac{Q_i}{(1+\gamma_i)R_i} - F_{ix},
              \qquad N_i = m_i g - F_{iy}

    docs/physics.md (M8), (M9); reproduces the paper's eq. (fric), :math:`f = F(1 - mRy/(I+mR^2))`
    (the paper counts f opposite to F; here ``f`` is positive along +x). A slider is on a
    frictionless floor: its ``f`` is 0. Velocities enter only through spring damping.
    Shapes: ``q`` (..., n) -> two arrays (..., n), newtons.
    """
    q = _as_state(system, q)
    force = body_forces(system, q, qdot)
    qddot = accelerations(system, q, qdot)
    friction = system.mass * system.scale * qddot - force[..., 0]
    friction = np.where(system.rolls > 0, friction, 0.0)
    normal = system.mass * system.gravity - force[..., 1]
    return friction, normal


def stiffness_entries(system: SystemArrays, q: FloatArray) -> tuple[IntArray, IntArray, FloatArray]:
    r"""The non-zero terms of the stiffness matrix :math:`K = \partial^2 U/\partial q^2` at
    ``q``, as (rows, cols, values) triplets whose sums over repeated (row, col) are K's
    entries: four per spring between two bodies (one per anchored spring) plus one per
    spring end and per external force on the diagonal. O(S + F) work and memory.

    .. math::
        K = \sum_s \bigl[k_s b_s b_s^T + T_s H_s\bigr] - \sum_f \mathrm{diag}\bigl(F_f\cdot
        \tfrac{d^2P_f}{dq^2}\bigr),\qquad
        (H_s)_{ij} = \frac{\Delta_i\cdot\Delta_j - (e\cdot\Delta_i)(e\cdot\Delta_j)}{l}
                     + \delta_{ij}\, e\cdot DD_i

    docs/physics.md (M12), (M13), with :math:`\Delta_i = \pm dP/dq_i` and
    :math:`DD_i = \pm d^2P/dq_i^2` at the spring's end on body i (+ at end b, - at end a).
    """
    q = _as_state(system, q)
    if q.ndim != 1:
        raise ValueError("stiffness_entries takes one state q of shape (n,)")
    _position, first, second = end_kinematics(system, q)
    springs = spring_state(system, q)
    delta = _SIGN[:, None] * first  # (S, 2 ends, 2 components)
    e, length, b = springs.direction, springs.length, springs.end_lever
    tension = system.stiffness * (length - system.rest_length)
    dot = np.einsum("sjc,slc->sjl", delta, delta)
    outer = b[:, :, None] * b[:, None, :]
    pair = system.stiffness[:, None, None] * outer
    pair += tension_per_length(system, length)[:, None, None] * (dot - outer)
    path = tension[:, None] * np.einsum("sc,sjc->sj", e, _SIGN[:, None] * second)
    on_body = system.end_body >= 0
    both = on_body[:, :, None] & on_body[:, None, :]
    index = system.end_index
    rows = [np.broadcast_to(index[:, :, None], both.shape)[both], index[on_body]]
    cols = [np.broadcast_to(index[:, None, :], both.shape)[both], index[on_body]]
    values = [pair[both], path[on_body]]
    if system.force.shape[0]:
        _, _, force_second = force_point_kinematics(system, q)
        rows.append(system.force_body)
        cols.append(system.force_body)
        values.append(-np.einsum("fc,fc->f", system.force, force_second))
    return np.concatenate(rows), np.concatenate(cols), np.concatenate(values)


@overload
def stiffness_matrix(
    system: SystemArrays, q: FloatArray, *, sparse: Literal[False] = False
) -> FloatArray: ...
@overload
def stiffness_matrix(
    system: SystemArrays, q: FloatArray, *, sparse: Literal[True]
) -> csr_array: ...
def stiffness_matrix(system: SystemArrays, q: FloatArray, *, sparse: bool = False) -> Any:
    r"""Hessian of the potential, :math:`K = \partial^2 U/\partial q^2`, exact at ``q``
    (:func:`stiffness_entries` summed).

    .. math::
        K = \sum_s \bigl[k_s b_s b_s^T + T_s H_s\bigr] - \sum_f \mathrm{diag}\bigl(F_f\cdot
        \tfrac{d^2P_f}{dq^2}\bigr)

    docs/physics.md (M12), (M13): :math:`T_s H_s` is the geometric stiffness of a pre-tensioned
    spring. For the paper's Fig. 2 it is :math:`kR^2\begin{pmatrix}1&-1\\-1&1\end{pmatrix}`.
    Shape: ``q`` (n,) -> (n, n), in N m/rad (rolling) or N/m (sliders); with ``sparse=True`` a
    SciPy CSR array (O(S) memory: each spring touches two bodies).
    """
    rows, cols, values = stiffness_entries(system, q)
    return _assemble(system.n_bodies, rows, cols, values, sparse)


def _assemble(n: int, rows: IntArray, cols: IntArray, values: FloatArray, sparse: bool) -> Any:
    """Sum triplets into an (n, n) matrix: dense NumPy, or SciPy's CSR with ``sparse``."""
    if sparse:
        import scipy.sparse  # on demand: only the large-system path needs it

        return scipy.sparse.coo_array((values, (rows, cols)), shape=(n, n)).tocsr()
    # bincount sums each cell's values in their order, as np.add.at does (the same bits),
    # without add.at's overhead (a few times the whole assembly for a small system)
    flat = np.asarray(rows, dtype=np.intp) * n + np.asarray(cols, dtype=np.intp)
    summed = np.bincount(flat, weights=np.asarray(values, dtype=float), minlength=n * n)
    dense: FloatArray = summed.astype(np.float64, copy=False).reshape(n, n)  # int when empty
    return dense


def pseudo_momentum_conserved(system: SystemArrays) -> bool:
    r"""True when (M11) holds exactly: every spring joins two body centres (:math:`r = 0` at
    both ends, no anchor) and no constant force acts (docs/physics.md section 6). :math:`U`
    then depends on differences of centre positions only, :math:`\hat P = \sum_i (1+\gamma_i)
    m_i\dot x_i` is conserved, and :math:`\hat X`'s weights are :math:`(1+\gamma_i) m_i`;
    otherwise they are the zero mode's of (M14), if there is one."""
    return (
        system.force.shape[0] == 0
        and bool(np.all(system.end_body >= 0))
        and not bool(np.any(system.end_r))
    )


def springs_stay_level(system: SystemArrays) -> bool:
    r"""True when every spring joins body centres (or anchors) at one height in the initial
    placement and every external force acts at a centre (docs/physics.md section 8).

    Rolling keeps the centres' heights, so such springs stay horizontal whatever q (while
    their ends do not pass each other): the lever arms :math:`b_{si} = e_s\sigma_{si}s_i` are
    constant, the geometric stiffness :math:`T_sH_s` vanishes (K does not depend on q, Q is
    affine in q) and the normal forces :math:`N_i = m_i g - F_{iy}` are constant, exactly.
    """
    return system.level_centre_springs  # computed once per SystemArrays


def damping_matrix(system: SystemArrays, q: FloatArray, *, sparse: bool = False) -> Any:
    r"""Linear damping matrix of the spring dampers, :math:`C = \sum_s c_s b_s b_s^T`.

    The damping force :math:`c_s \dot l_s` along spring s, with :math:`\dot l_s = b_s\cdot\dot q`,
    gives the generalised force :math:`-C\dot q` (:func:`generalized_forces` with ``qdot``).
    Shape: ``q`` (n,) -> (n, n) (SciPy CSR with ``sparse=True``).
    """
    b = spring_state(system, q).end_lever
    outer = b[:, :, None] * b[:, None, :]
    return spring_pair_matrix(system, system.damping[:, None, None] * outer, sparse=sparse)


def spring_pair_matrix(system: SystemArrays, values: FloatArray, *, sparse: bool = False) -> Any:
    r"""The (n, n) matrix :math:`A = \sum_s \sum_{j,l} a_{sjl}\, u_{i(s,j)} u_{i(s,l)}^T` of
    per-spring end-pair terms ``values`` (S, 2, 2) (:math:`a_{sjl}` couples the bodies of ends
    j and l of spring s; terms at anchor ends are dropped): e.g. :math:`\sum_s k_s b_s b_s^T`
    from :math:`a_{sjl} = k_s b_{sj} b_{sl}`. Dense NumPy, or SciPy CSR with ``sparse``."""
    rows, cols, pairs = _pair_entries(system)
    return _assemble(system.n_bodies, rows, cols, np.asarray(values)[pairs], sparse)


def _pair_entries(system: SystemArrays) -> tuple[IntArray, IntArray, np.ndarray]:
    """Rows and columns of the (end j, end l) pairs of every spring with both on bodies, and
    the (S, 2, 2) mask that picks them."""
    on_body = system.end_body >= 0
    pairs = on_body[:, :, None] & on_body[:, None, :]
    index = system.end_index
    rows = np.broadcast_to(index[:, :, None], pairs.shape)[pairs]
    cols = np.broadcast_to(index[:, None, :], pairs.shape)[pairs]
    return rows, cols, pairs


def body_forces_jacobian(system: SystemArrays, q: FloatArray, *, sparse: bool = False) -> Any:
    r"""Derivative of the applied forces with respect to the coordinates, shape (n, 2, n)
    (with ``sparse=True`` two SciPy CSR arrays (n, n), of the x and the y components).

    For a displacement ``v``, the force on end a of a spring changes by
    :math:`\delta F_a = k\,\delta l\, e + T(\delta d - e(e\cdot\delta d))/l` with
    :math:`\delta d = \sum_i\Delta_i v_i`, :math:`\delta l = b\cdot v`
    (docs/physics.md section 7), and :math:`\delta F_b = -\delta F_a`. Constant external forces do
    not change.
    """
    q = _as_state(system, q)
    _, first, _ = end_kinematics(system, q)
    springs = spring_state(system, q)
    delta = _SIGN[:, None] * first  # (S, 2, 2): d(d)/dq of end l's body
    e, length, b = springs.direction, springs.length, springs.end_lever
    along = (system.stiffness[:, None] * b)[:, :, None] * e[:, None, :]
    across = (delta - b[:, :, None] * e[:, None, :]) * tension_per_length(system, length)[
        :, None, None
    ]
    d_pull = along + across  # (S, l, c): d(force on end a)/dq of end l's body
    # force on end j (+ at a, - at b) by coordinate of end l: (S, j, l, c)
    d_end = -_SIGN[None, :, None, None] * d_pull[:, None, :, :]
    rows, cols, pairs = _pair_entries(system)
    x_values, y_values = d_end[..., 0][pairs], d_end[..., 1][pairs]
    n = system.n_bodies
    if sparse:
        return (_assemble(n, rows, cols, x_values, True), _assemble(n, rows, cols, y_values, True))
    dense = np.zeros((n, 2, n))
    for component, values in enumerate((x_values, y_values)):
        where: Any = (rows, component, cols)
        np.add.at(dense, where, values)
    return dense


def contact_forces_jacobian(
    system: SystemArrays, q: FloatArray, *, sparse: bool = False
) -> tuple[Any, Any]:
    r"""Linear change of friction and normal forces with the coordinates, two (n, n) arrays
    (SciPy CSR arrays with ``sparse=True``).

    .. math:: \frac{\partial f_i}{\partial q_j} = -\frac{m_i s_i}{J_i} K_{ij}
              - \frac{\partial F_{ix}}{\partial q_j},\qquad
              \frac{\partial N_i}{\partial q_j} = -\frac{\partial F_{iy}}{\partial q_j}

    Differentiates (M8), (M9) with :math:`\ddot q = -M^{-1}K\,\delta q` (docs/physics.md section 7,
    "linear forces along a displacement").
    """
    factor = np.where(system.rolls > 0, system.mass * system.scale / system.inertia, 0.0)
    if sparse:
        import scipy.sparse

        k_sparse = stiffness_matrix(system, q, sparse=True)
        dx, dy = body_forces_jacobian(system, q, sparse=True)
        keep = scipy.sparse.diags_array((system.rolls > 0).astype(float))
        scale = scipy.sparse.diags_array(factor)
        return (-(scale @ k_sparse) - keep @ dx).tocsr(), (-dy).tocsr()
    k_matrix = stiffness_matrix(system, q)
    d_force = body_forces_jacobian(system, q)
    d_friction = -(system.mass * system.scale / system.inertia)[:, None] * k_matrix
    d_friction -= d_force[:, 0, :]
    d_friction[system.rolls == 0] = 0.0
    d_normal = -d_force[:, 1, :]
    return d_friction, d_normal


def spring_energies(system: SystemArrays, q: FloatArray) -> FloatArray:
    r"""Each spring's elastic energy :math:`\tfrac12 k_s (l_s - L_{0s})^2` (J), shape (..., S),
    from the end positions alone (M1), (M5)."""
    q = _as_state(system, q)
    position, _, _ = end_kinematics(system, q)
    vector = position[..., 1, :] - position[..., 0, :]
    length = np.sqrt(np.sum(vector**2, axis=-1))
    result: FloatArray = 0.5 * (system.stiffness * (length - system.rest_length) ** 2)
    return result


def force_work(system: SystemArrays, q: FloatArray) -> FloatArray:
    r"""The work each constant external force has done since the initial placement,
    :math:`F_f\cdot(P_f(q) - P_f(0))` (J), shape (..., F): minus its potential energy (M5)."""
    q = _as_state(system, q)
    position, _, _ = force_point_kinematics(system, q)
    rest, _, _ = force_point_kinematics(system, np.zeros(system.n_bodies))
    result: FloatArray = np.einsum("fc,...fc->...f", system.force, position - rest)
    return result


def potential_energy(system: SystemArrays, q: FloatArray) -> FloatArray:
    r"""Potential energy, zero in the initial placement's external-force level (J), (M5):

    .. math:: U = \sum_s \tfrac12 k_s (l_s - L_{0s})^2 - \sum_f F_f\cdot(P_f(q) - P_f(0))

    (:func:`spring_energies` and :func:`force_work` summed). Gravity is a constant while the
    bodies roll (centre heights do not change) and is left out.
    """
    q = _as_state(system, q)
    energy = np.sum(spring_energies(system, q), axis=-1)
    if system.force.shape[0]:
        energy = energy - np.sum(force_work(system, q), axis=-1)
    result: FloatArray = energy
    return result


def dissipated_power(
    system: SystemArrays,
    length: FloatArray,
    tension: FloatArray,
    friction: FloatArray,
    slip_velocity: FloatArray,
    normal: FloatArray | None = None,
    angular_velocity: FloatArray | None = None,
) -> FloatArray:
    r"""The power turned into heat, by spring damping, by kinetic friction and by rolling
    resistance (W; the last axis of the result: ``[damping, friction, rolling_resistance]``),
    from a state's spring lengths and tensions (``(..., S)``) and the bodies' friction forces,
    slip velocities :math:`v_{s,i} = \dot x_i - R_i\dot\varphi_i` (``(..., n)``; zero for a
    rolling body), normal forces and angular velocities (``(..., n)``; needed only when a body
    has rolling resistance):

    .. math::
        P_c = \sum_{s:\,c_s > 0} c_s \dot l_s^{\,2}
            = \sum_{s:\,c_s > 0} \frac{\bigl(T_s - k_s(l_s - L_{0s})\bigr)^2}{c_s},
        \qquad P_f = \sum_i \lvert f_i\, v_{s,i}\rvert,
        \qquad P_r = \sum_i C_{rr,i} N_i R_i \lvert\dot\varphi_i\rvert,

    the damping part :math:`c_s\dot l_s` of the tension (docs/physics.md section 2) read back
    from the tension, the kinetic friction (M19) opposing the slip, and the rolling
    resistance's torque (M21) opposing the rotation (for a rolling body
    :math:`C_{rr} N \lvert v\rvert`; a body it holds at rest does not turn). With
    :math:`W = \int (P_c + P_f + P_r)\,dt` the exact motion keeps :math:`E + W = E_0`."""
    length, tension = np.asarray(length, dtype=float), np.asarray(tension, dtype=float)
    power = np.zeros((*length.shape[:-1], 3))
    damped = system.damping > 0
    if np.any(damped):
        viscous = tension[..., damped] - system.stiffness[damped] * (
            length[..., damped] - system.rest_length[damped]
        )
        power[..., 0] = np.sum(viscous**2 / system.damping[damped], axis=-1)
    power[..., 1] = np.sum(np.abs(np.asarray(friction) * np.asarray(slip_velocity)), axis=-1)
    if system.resisted and normal is not None and angular_velocity is not None:
        torque = system.rolling_resistance * np.asarray(normal) * system.radius
        power[..., 2] = np.sum(torque * np.abs(np.asarray(angular_velocity)), axis=-1)
    return power


def rolling_resistance_torque(
    system: SystemArrays, normal: FloatArray, angular_velocity: FloatArray
) -> FloatArray:
    r"""The clockwise torque of rolling resistance on each body turning with
    ``angular_velocity`` (N m, shape (..., n)), docs/physics.md (M21): the normal force acts
    :math:`C_{rr} R` ahead of the contact point,

    .. math:: \Gamma_i = -C_{rr,i} N_i R_i\,\mathrm{sign}\,\dot\varphi_i ,

    about the contact point and the centre alike (the force is vertical). For a rolling body it
    is a generalised force beside :math:`Q_i`: :math:`(1+\gamma_i) m_i \ddot x_i = Q_i/R_i -
    C_{rr,i} N_i\,\mathrm{sign}\,\dot x_i`. At rest (:math:`\dot\varphi_i = 0`) it is 0 here;
    the torque then holds the body up to :math:`C_{rr} N R` (M22), as the simulation decides."""
    result: FloatArray = (
        -system.rolling_resistance
        * np.asarray(normal, dtype=float)
        * system.radius
        * np.sign(angular_velocity)
    )
    return result


def resisted_accelerations(system: SystemArrays, q: FloatArray, qdot: FloatArray) -> FloatArray:
    r"""Exact equations of motion while every body rolls, with rolling resistance,
    docs/physics.md (M7), (M21), (M22):

    .. math:: J_i\ddot q_i = Q_i + \Gamma_i, \qquad
              \Gamma_i = -C_{rr,i} N_i R_i\,\mathrm{sign}\,\dot\varphi_i ,

    i.e. :math:`(1+\gamma_i) m_i\ddot x_i = Q_i/R_i - C_{rr,i} N_i\,\mathrm{sign}\,\dot x_i`. A
    resisted body at rest is held (:math:`\ddot q_i = 0`) while :math:`|Q_i| \le C_{rr} N_i R_i`,
    else it starts the way :math:`Q_i` drives it, the resistance against it. Equal to
    :func:`accelerations` where :math:`C_{rr} = 0`. Shapes: (..., n)."""
    q, qdot = _as_state(system, q), _as_state(system, qdot)
    drive = generalized_forces(system, q, qdot)
    _, normal = contact_forces(system, q, qdot)
    resisted = (system.rolling_resistance > 0) & (system.rolls > 0)
    limit = system.rolling_resistance * normal * system.radius
    at_rest = resisted & (qdot == 0.0)
    held = at_rest & (np.abs(drive) <= limit)
    spin = np.where(at_rest, np.sign(drive), np.sign(qdot))
    torque = np.where(resisted, -limit * spin, 0.0)
    result: FloatArray = np.where(held, 0.0, (drive + torque) / system.inertia)
    return result


def resisted_contact_forces(
    system: SystemArrays, q: FloatArray, qdot: FloatArray
) -> tuple[FloatArray, FloatArray]:
    r"""Friction and normal force of every body rolling with rates ``qdot`` when bodies have
    rolling resistance, docs/physics.md (M8) with (M21), (M22):

    .. math:: f_i = \frac{Q_i + \Gamma_i}{(1+\gamma_i)R_i} - F_{ix}
              = \frac{Q_i}{(1+\gamma_i)R_i} - F_{ix}
                - \frac{C_{rr,i} N_i\,\mathrm{sign}\,\dot x_i}{1+\gamma_i},
              \qquad N_i = m_i g - F_{iy}

    (:func:`rolling_resistance_torque` :math:`\Gamma_i`; Newton's law for the centre,
    :math:`m\ddot x = F_x + f`, with :math:`J\ddot\varphi = Q + \Gamma`). The resistance
    takes :math:`C_{rr} N/(1+\gamma)` from the friction the rolling needs: the normal force's
    torque about the centre does part of the braking, the friction the rest. A resisted body at
    rest (:math:`\dot\varphi_i = 0`) is held while :math:`|Q_i| \le C_{rr} N_i R_i` (M22), and
    needs :math:`f_i = -F_{ix}`; beyond, it starts to roll the way :math:`Q_i` drives it, the
    resistance against it. Equal to :func:`contact_forces` where :math:`C_{rr} = 0`.
    Shapes: ``q``, ``qdot`` (..., n) -> two arrays (..., n), newtons."""
    friction, normal = contact_forces(system, q, qdot)
    q, qdot = _as_state(system, q), _as_state(system, qdot)
    omega = system.rolls * qdot
    resisted = (system.rolling_resistance > 0) & (system.rolls > 0)
    drive = generalized_forces(system, q, qdot)
    limit = system.rolling_resistance * normal * system.radius
    at_rest = resisted & (omega == 0.0)
    held = at_rest & (np.abs(drive) <= limit)
    spin = np.where(at_rest, np.sign(drive), np.sign(omega))
    torque = -system.rolling_resistance * normal * system.radius * spin
    moving = system.mass * system.scale * torque / system.inertia
    friction = np.where(resisted & ~held, friction + moving, friction)
    friction = np.where(held, -body_forces(system, q, qdot)[..., 0], friction)
    return friction, normal


def kinetic_energy(system: SystemArrays, qdot: FloatArray) -> FloatArray:
    r"""Kinetic energy :math:`T = \sum_i \tfrac12 J_i \dot q_i^2` (J), König's theorem with
    rolling, docs/physics.md (M4)-(M5); the paper's :math:`\tfrac12 I'_1\dot\varphi_1^2 + \dots`."""
    qdot = _as_state(system, qdot)
    result: FloatArray = 0.5 * np.sum(system.inertia * qdot**2, axis=-1)
    return result


def total_energy(system: SystemArrays, q: FloatArray, qdot: FloatArray) -> FloatArray:
    """Mechanical energy H = T + U (J), conserved while every body rolls, docs/physics.md (M6)."""
    return kinetic_energy(system, qdot) + potential_energy(system, q)


def centre_positions(system: SystemArrays, q: FloatArray) -> FloatArray:
    r"""Horizontal centre positions :math:`x_i = x_{i0} + s_i q_i` (m); the rolling constraint
    :math:`x = R\varphi` of the paper's eq. (g1, g2)."""
    q = _as_state(system, q)
    return system.x0 + system.scale * q


def centre_of_mass(system: SystemArrays, q: FloatArray) -> FloatArray:
    r"""Horizontal position of the centre of mass :math:`X = \sum m_i x_i/\sum m_i` (m)."""
    x = centre_positions(system, q)
    result: FloatArray = np.sum(system.mass * x, axis=-1) / np.sum(system.mass)
    return result

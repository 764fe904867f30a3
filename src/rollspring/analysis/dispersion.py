r"""Dispersion of a chain read as a periodic lattice: branches, gaps, group velocities, friction.

A chain (bodies in order of ``x``, repeating a unit cell of :math:`p` bodies every :math:`a`
metres, with the same springs in every cell: :func:`unit_cell`) is extended to the infinite
lattice with periodic (Bloch) boundaries. A wave :math:`u_{c,r} = e_r e^{i(qca - \omega t)}`
(cell :math:`c`, body :math:`r` of the cell, coordinates :math:`q_i` as in docs/physics.md
section 2) solves :math:`M\ddot u + Ku = 0` (M12) when

.. math:: K(q)\,e = \omega^2 M e, \qquad K(q) = \sum_c K_{0c}\, e^{iqca},
          \qquad M = \mathrm{diag}(J_r)

with :math:`K_{0c}` the block of the exact stiffness matrix between cell 0 and cell :math:`c`
(:func:`~rollspring.physics.stiffness_matrix` of cell 0 and its neighbours, so off-centre and
raised attachments, tilted and pre-tensioned springs are included); :math:`K(q)` is Hermitian,
:math:`K(-q) = \overline{K(q)}`. Its :math:`p` eigenvalues are the branches
:math:`\omega_b^2(q)` over the Brillouin zone :math:`|q| \le \pi/a`. With springs joining
centres, :math:`J_r = (1 + \gamma_r) m_r R_r^2` and :math:`K \propto R_r R_{r'}`, so in centre
displacements the masses are the rolling inertias :math:`(1+\gamma)m` and the diatomic lattice
(one spring :math:`k` between neighbours) has the closed form (:func:`diatomic_branches`)

.. math:: \omega_\pm^2 = k\Bigl(\frac1{M_1} + \frac1{M_2}\Bigr) \pm k\sqrt{\Bigl(\frac1{M_1}
          + \frac1{M_2}\Bigr)^2 - \frac{4\sin^2(qa/2)}{M_1M_2}}, \qquad M_r = (1+\gamma_r)m_r .

**Group velocity** :math:`v_g = d\omega/dq = e^H K'(q) e / (2\omega)` (Hellmann–Feynman, with
:math:`e^H M e = 1` and :math:`K'(q) = \sum_c ica\,K_{0c}e^{iqca}`); where a branch is at
:math:`\omega = 0` (the acoustic branch at :math:`q = 0`) it is the sound speed
:math:`\lim_{q\to 0^+}\omega/q`, from :math:`\omega/q` at :math:`qa = 0.01` and :math:`0.02`
extrapolated (Richardson: :math:`\omega/q = c + O(q^2)`).

**Friction and normal force per unit wave amplitude.** The linear change of friction and normal
force with the coordinates, :math:`\partial f_i/\partial q_j`, :math:`\partial N_i/\partial q_j`
(:func:`~rollspring.physics.contact_forces_jacobian`: (M8), (M9) differentiated, the formula
the modal analysis uses for each mode's ``friction``), taken on cell 0 with the same phases,
:math:`F(q) = \sum_c F_{0c} e^{iqca}`, gives body :math:`r`'s friction
:math:`\mathrm{Re}[(F(q)e)_r e^{-i\omega t}]` in the travelling wave: its amplitude
:math:`|(F(q)e)_r|` with :math:`e` scaled so the largest centre displacement amplitude
:math:`|s_r e_r|` is 1 m (N per metre of amplitude); likewise the normal force. The friction
coefficient the wave needs is then :math:`|f_r|/N_r` per metre of amplitude, to first order.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np

from rollspring.analysis.linear import ZERO_MODE_TOLERANCE, find_equilibrium
from rollspring.errors import AnalysisError
from rollspring.model import (
    LIMITS,
    System,
    as_system,
    rolled,
    system_from_dict,
    system_to_json,
)
from rollspring.physics import (
    contact_forces,
    contact_forces_jacobian,
    generalized_forces,
    stiffness_matrix,
    system_arrays,
)
from rollspring.physics.arrays import FloatArray

__all__ = [
    "DEFAULT_POINTS",
    "EQUILIBRIUM_BODIES",
    "MAX_POINTS",
    "Dispersion",
    "UnitCell",
    "diatomic_branches",
    "dispersion",
    "monatomic_branch",
    "unit_cell",
]

#: Points over the Brillouin zone by default, and at most.
DEFAULT_POINTS = 201
MAX_POINTS = 100_001
#: The most bodies of a chain whose placement is displaced that is read at its equilibrium.
EQUILIBRIUM_BODIES = 200
#: Relative tolerance of "the same" in a periodic chain (positions, masses, stiffnesses).
_SAME = 1e-9


@dataclass(frozen=True)
class UnitCell:
    """A chain's repeating unit: ``ids`` (the bodies of the first cell), the cell length ``a``
    (m), and ``lattice``: cell 0 with ``reach`` cells on each side (a system whose bodies
    ``index`` … ``index + p - 1`` are cell 0), springs as in the chain, no walls."""

    ids: tuple[str, ...]
    a: float
    reach: int
    lattice: System
    index: int
    #: (stiffness, joins centres on one level) of each spring of the cell, for the closed form
    springs: tuple[tuple[float, bool, int, int], ...]

    @property
    def p(self) -> int:
        """Bodies per cell."""
        return len(self.ids)


def unit_cell(system: System) -> UnitCell:
    """The smallest repeating unit of a chain (AnalysisError naming what breaks the period).

    The bodies, in the order of the file, must have increasing ``x``; body :math:`i + p` must
    equal body :math:`i` (shape, mass, radius, inertia factor, track height) ``a`` metres
    further on, and every spring between bodies must repeat: the spring from body :math:`i` to
    body :math:`i + d` has the same stiffness, rest length and attachments as the one from
    :math:`i + p` to :math:`i + p + d`, which must exist while both bodies do. Springs to
    anchors (walls) are left out: the lattice is infinite. At least two cells are needed.
    """
    if system.forces:
        raise AnalysisError("dispersion: a periodic chain has no constant forces (forces[0])")
    bodies = system.bodies
    n = len(bodies)
    x = [b.x for b in bodies]
    for i in range(n - 1):
        if not x[i + 1] > x[i]:
            raise AnalysisError(
                f"dispersion: bodies[{i + 1}] ('{bodies[i + 1].id}') is not to the right of "
                f"bodies[{i}]: a chain lists its bodies from left to right"
            )
    index = {b.id: i for i, b in enumerate(bodies)}
    rest = system.rest_lengths
    links: dict[tuple[int, int], tuple[Any, ...]] = {}
    for s, spring in enumerate(system.springs):
        ends = list(spring.ends)
        if ends[0] not in index or ends[1] not in index:
            continue
        ats = list(spring.attachments)
        i, j = index[ends[0]], index[ends[1]]
        if i > j:
            i, j, ats = j, i, ats[::-1]
        polar = tuple(at.polar(bodies[k]) for at, k in zip(ats, (i, j), strict=True))
        value = (spring.stiffness, rest[s], spring.damping, polar, s)
        if (i, j) in links:
            raise AnalysisError(
                f"dispersion: springs[{s}] joins '{bodies[i].id}' and '{bodies[j].id}' again: "
                "give one spring per pair"
            )
        links[(i, j)] = value
    if not links:
        raise AnalysisError("dispersion: no spring joins two bodies: this is not a chain")
    failure = ""
    for p in range(1, n // 2 + 1):
        failure = _period_failure(system, p, links)
        if not failure:
            return _cell(system, p, links)
    raise AnalysisError(
        f"dispersion: not a periodic chain of at least two cells ({failure or 'too few bodies'})"
    )


def _same(u: float, v: float, size: float) -> bool:
    return abs(u - v) <= _SAME * max(abs(u), abs(v), size)


def _period_failure(system: System, p: int, links: dict[tuple[int, int], tuple[Any, ...]]) -> str:
    """Why the chain does not repeat every ``p`` bodies ('' if it does)."""
    bodies = system.bodies
    n = len(bodies)
    a = bodies[p].x - bodies[0].x
    for i in range(n - p):
        first, second = bodies[i], bodies[i + p]
        if (first.shape, first.gamma) != (second.shape, second.gamma) or not all(
            _same(getattr(first, key), getattr(second, key), 1e-300) for key in ("mass", "radius")
        ):
            return f"'{second.id}' differs from '{first.id}'"
        if not _same(first.track_height, second.track_height, first.radius):
            return f"'{second.id}' is on another track than '{first.id}'"
        if not _same(second.x - first.x, a, a):
            return f"'{second.id}' is not {a:g} m after '{first.id}'"
    size = max(b.radius for b in bodies)
    checked: set[tuple[int, int]] = set()
    for (i, j), (k, rest, damping, polar, s) in links.items():
        d = j - i
        if (i % p, d) in checked:
            continue  # its kind was compared along the whole chain already
        checked.add((i % p, d))
        for shift in range(i % p, n - d, p):
            other = links.get((shift, shift + d))
            where = f"'{bodies[shift].id}' and '{bodies[shift + d].id}'"
            if other is None:
                return f"no spring joins {where} as springs[{s}] does a cell earlier or later"
            k2, rest2, damping2, polar2, _ = other
            same_ends = all(
                _same(r1, r2, size)
                and _same(math.cos(t1), math.cos(t2), 1.0)
                and _same(math.sin(t1), math.sin(t2), 1.0)
                for (r1, t1), (r2, t2) in zip(polar, polar2, strict=True)
            )
            if not (_same(k, k2, 0.0) and _same(rest, rest2, size) and damping == damping2):
                return f"the spring joining {where} differs from springs[{s}]"
            if not same_ends:
                return f"the spring joining {where} is attached elsewhere than springs[{s}]"
    return ""


def _cell(system: System, p: int, links: dict[tuple[int, int], tuple[Any, ...]]) -> UnitCell:
    """Cell 0 (the chain's first ``p`` bodies) with ``reach`` cells on each side."""
    bodies = system.bodies
    a = bodies[p].x - bodies[0].x
    reach = max(-(-(j - i) // p) for i, j in links)  # ceil(d / p)
    if (2 * reach + 1) * p > LIMITS["bodies"]:
        raise AnalysisError(
            f"dispersion: the chain repeats only every {p} bodies: its lattice of "
            f"{2 * reach + 1} cells would exceed {LIMITS['bodies']} bodies"
        )
    # one spring of each kind: the first occurrence of (i mod p, d)
    kinds: dict[tuple[int, int], tuple[int, int]] = {}
    for i, j in sorted(links):
        kinds.setdefault((i % p, j - i), (i, j))
    data = system_to_json(system)
    index = {b.id: i for i, b in enumerate(bodies)}
    rest = system.rest_lengths
    cells = range(-reach, reach + 1)
    new_bodies = []
    for c in cells:
        for r in range(p):
            entry = dict(data["bodies"][r])
            entry["id"] = f"c{c + reach}_{r}"
            entry["x"] = bodies[r].x + c * a
            entry["v"] = 0.0
            new_bodies.append(entry)
    new_springs = []
    closed: list[tuple[float, bool, int, int]] = []
    for (r, d), pair in sorted(kinds.items()):
        s = links[pair][4]
        original = system.springs[s]
        closed.append(
            (original.stiffness, all(at.is_centre_form for at in original.attachments), r, d)
        )
        flipped = index[original.ends[0]] > index[original.ends[1]]
        for c in cells:
            start = (c + reach) * p + r
            if start + d >= len(new_bodies):
                continue
            spring = dict(data["springs"][s])
            ends = [new_bodies[start]["id"], new_bodies[start + d]["id"]]
            spring["ends"] = ends[::-1] if flipped else ends
            spring["rest_length"] = rest[s]
            new_springs.append(spring)
    lattice = system_from_dict(
        {
            "name": f"{system.name} (periodic lattice)",
            "gravity": system.gravity,
            "bodies": new_bodies,
            "springs": new_springs,
        },
        source="lattice",
    )
    return UnitCell(
        ids=tuple(b.id for b in bodies[:p]),
        a=a,
        reach=reach,
        lattice=lattice,
        index=reach * p,
        springs=tuple(closed),
    )


@dataclass(frozen=True)
class Dispersion:
    """The branches of a periodic chain over its Brillouin zone (see the module docstring).

    Arrays are over ``q`` (points,), branches (p, ascending) and the cell's bodies (p):
    ``omega`` and ``group_velocity`` (points, p); ``friction``, ``normal_force``,
    ``displacement`` (points, p branches, p bodies), per metre of the largest centre
    displacement amplitude; ``closed_form`` (points, p) where the springs join centres
    (p = 1 or 2, one stiffness), else None.
    """

    system: System
    cell: UnitCell
    q: FloatArray
    omega: FloatArray
    group_velocity: FloatArray
    displacement: FloatArray
    friction: FloatArray
    normal_force: FloatArray
    friction_at_rest: FloatArray
    normal_at_rest: FloatArray
    closed_form: FloatArray | None
    rolling_mass: FloatArray
    warnings: tuple[str, ...] = ()

    @property
    def band_edges(self) -> FloatArray:
        """(p, 2): the lowest and highest ω of each branch over the zone, rad/s."""
        result: FloatArray = np.stack([self.omega.min(axis=0), self.omega.max(axis=0)], axis=-1)
        return result

    @property
    def gaps(self) -> list[tuple[int, float, float]]:
        """Every gap between branches b and b + 1 (1-based b): (b, ω low, ω high), rad/s."""
        edges = self.band_edges
        top = np.maximum.accumulate(edges[:, 1])
        return [
            (b + 1, float(top[b]), float(edges[b + 1, 0]))
            for b in range(edges.shape[0] - 1)
            if edges[b + 1, 0] > top[b]
        ]

    @property
    def required_mu(self) -> FloatArray:
        """(p branches, p bodies): the largest |f|/N over the zone per metre of amplitude
        (first order; inf where N is 0 at rest; 0 for sliders)."""
        with np.errstate(divide="ignore", invalid="ignore"):
            ratio = self.friction.max(axis=0) / self.normal_at_rest
        out: FloatArray = np.where(self.friction.max(axis=0) == 0.0, 0.0, ratio)
        return np.where(self.normal_at_rest > 0, out, math.inf)

    def to_dict(self) -> dict[str, Any]:
        """The JSON form ``rollspring dispersion --json`` prints: every number finite or null."""
        ids = list(self.cell.ids)
        branches = []
        for b in range(self.omega.shape[1]):
            peak = np.argmax(self.friction[:, b, :], axis=0)
            branches.append(
                {
                    "branch": b + 1,
                    "name": _branch_name(b, self.omega.shape[1], self.omega[:, b]),
                    "omega_min": _num(self.band_edges[b, 0]),
                    "omega_max": _num(self.band_edges[b, 1]),
                    "max_group_velocity": _num(np.abs(self.group_velocity[:, b]).max()),
                    "friction_max": {
                        i: {"amplitude": _num(self.friction[k, b, r]), "q": _num(self.q[k])}
                        for r, (i, k) in enumerate(zip(ids, peak, strict=True))
                    },
                    "normal_force_max": {
                        i: _num(self.normal_force[:, b, r].max()) for r, i in enumerate(ids)
                    },
                    "required_mu_per_metre": {
                        i: _num(self.required_mu[b, r]) for r, i in enumerate(ids)
                    },
                    "omega": [_num(v) for v in self.omega[:, b]],
                    "group_velocity": [_num(v) for v in self.group_velocity[:, b]],
                    "friction": {
                        i: [_num(v) for v in self.friction[:, b, r]] for r, i in enumerate(ids)
                    },
                    "normal_force": {
                        i: [_num(v) for v in self.normal_force[:, b, r]] for r, i in enumerate(ids)
                    },
                    "closed_form": None
                    if self.closed_form is None
                    else [_num(v) for v in self.closed_form[:, b]],
                }
            )
        return {
            "system": self.system.name,
            "cell": ids,
            "cell_length": _num(self.cell.a),
            "rolling_mass": {i: _num(v) for i, v in zip(ids, self.rolling_mass, strict=True)},
            "zone_edge": _num(math.pi / self.cell.a),
            "q": [_num(v) for v in self.q],
            "branches": branches,
            "gaps": [
                {"between": [b, b + 1], "omega_low": _num(lo), "omega_high": _num(hi)}
                for b, lo, hi in self.gaps
            ],
            "has_closed_form": self.closed_form is not None,
            "units": {
                "q": "rad/m",
                "omega": "rad/s",
                "group_velocity": "m/s",
                "friction": "N per m of amplitude",
                "normal_force": "N per m of amplitude",
                "required_mu_per_metre": "1/m",
            },
            "warnings": list(self.warnings),
        }


def _branch_name(b: int, p: int, omega: FloatArray) -> str:
    if b == 0 and float(omega.min()) == 0.0:
        return "acoustic"
    return "optical" if p == 2 and b == 1 else f"branch {b + 1}"


def _num(value: float) -> float | None:
    value = float(value)
    return None if not math.isfinite(value) else (0.0 if value == 0 else value)


def dispersion(
    system: System | dict[str, Any] | str, points: int = DEFAULT_POINTS, *, wavenumbers: Any = None
) -> Dispersion:
    """The branches of ``system`` read as a periodic chain (:func:`unit_cell`), at ``points``
    wavenumbers evenly over the Brillouin zone :math:`[-\\pi/a, \\pi/a]` (ends included), about
    the placement, which must be an equilibrium of the lattice (AnalysisError otherwise);
    ``wavenumbers`` (rad/m, finite) replaces the grid when given. ``system``: a System, its
    JSON form, a file path or a preset name.

    Parameters
    ----------
    system
        A chain: a :class:`~rollspring.model.System`, its JSON form, a file or a preset name.
    points
        How many wavenumbers over the Brillouin zone (3 to :data:`MAX_POINTS`).
    wavenumbers
        Wavenumbers (rad/m) to use instead of the even grid.

    Returns
    -------
    Dispersion
        The branches ω(q), gaps, group velocities, friction and normal force per amplitude.
    """
    system = as_system(system)
    if isinstance(points, bool) or not isinstance(points, int) or not 3 <= points <= MAX_POINTS:
        raise AnalysisError(
            f"points: must be a whole number from 3 to {MAX_POINTS} (got {points!r})"
        )
    cell, warnings = _periodic_cell(system)
    arrays = system_arrays(cell.lattice)
    p, a, first = cell.p, cell.a, cell.index
    rows = slice(first, first + p)
    zero = np.zeros(arrays.n_bodies)
    stiffness = stiffness_matrix(arrays, zero)[rows]
    d_friction, d_normal = contact_forces_jacobian(arrays, zero)
    friction_rest, normal_rest = contact_forces(arrays, zero)
    cells = np.repeat(np.arange(-cell.reach, cell.reach + 1), p)  # cell of each column
    if wavenumbers is None:
        q = np.linspace(-math.pi / a, math.pi / a, points)
        if points % 2:
            q[points // 2] = 0.0  # exactly: the acoustic branch's zero
    else:
        q = np.atleast_1d(np.asarray(wavenumbers, dtype=float))
        if q.ndim != 1 or not q.size or not np.isfinite(q).all():
            raise AnalysisError("wavenumbers: give finite numbers (rad/m)")
    phase = np.exp(1j * np.outer(q, cells * a))  # (points, columns)
    element = np.tile(np.arange(p), 2 * cell.reach + 1)
    gather = np.zeros((element.size, p))
    gather[np.arange(element.size), element] = 1.0

    def bloch(block: FloatArray, weight: np.ndarray) -> np.ndarray:
        """sum_c block_{0c} w_c, (points, p, p), from the (p, columns) rows of cell 0."""
        result: np.ndarray = np.einsum("rj,qj,js->qrs", block, weight, gather)
        return result

    k_q = bloch(stiffness, phase)
    k_q = 0.5 * (k_q + np.conj(np.swapaxes(k_q, -1, -2)))
    dk_q = bloch(stiffness, 1j * a * cells * phase)
    inertia = arrays.inertia[rows]
    root = np.sqrt(inertia)
    reduced = k_q / np.outer(root, root)
    eigenvalues, vectors = np.linalg.eigh(reduced)  # ascending, (points, p), (points, p, p)
    largest = float(np.abs(eigenvalues).max())
    eigenvalues = np.where(np.abs(eigenvalues) < ZERO_MODE_TOLERANCE * largest, 0.0, eigenvalues)
    if np.any(eigenvalues < 0):
        warnings.append(
            "the lattice is unstable (negative omega^2 on some wavenumbers): omega is "
            "reported as 0 there"
        )
    omega = np.sqrt(np.maximum(eigenvalues, 0.0))
    shapes = vectors / root[None, :, None]  # M-normalised e (columns), (points, p, p)
    slope = np.real(np.einsum("qrb,qrs,qsb->qb", np.conj(shapes), dk_q, shapes))
    with np.errstate(divide="ignore", invalid="ignore"):
        group = np.where(omega > 0, slope / (2.0 * np.where(omega > 0, omega, 1.0)), 0.0)
    if np.any(omega == 0.0):  # the sound speed there, lim omega/q as q -> 0+
        step = 0.01 / a
        near_k = bloch(stiffness, np.exp(1j * np.outer([step, 2 * step], cells * a)))
        near_k = 0.5 * (near_k + np.conj(np.swapaxes(near_k, -1, -2))) / np.outer(root, root)
        ratio = np.sqrt(np.maximum(np.linalg.eigvalsh(near_k), 0.0)) / np.array(
            [[step], [2 * step]]
        )
        # omega/q = c + O(q^2): Richardson's step removes the q^2 term (error O((qa)^4))
        sound = (4.0 * ratio[0] - ratio[1]) / 3.0
        group = np.where(omega == 0.0, np.where(q >= 0, 1.0, -1.0)[:, None] * sound[None, :], group)
    centre = arrays.scale[rows][None, :, None] * shapes  # centre displacements (points, p, p)
    size = np.abs(centre).max(axis=1, keepdims=True)
    size = np.where(size > 0, size, 1.0)
    centre, shapes = centre / size, shapes / size
    f_q = bloch(d_friction[rows], phase)
    n_q = bloch(d_normal[rows], phase)
    friction = np.abs(np.einsum("qrs,qsb->qbr", f_q, shapes))
    normal = np.abs(np.einsum("qrs,qsb->qbr", n_q, shapes))
    force_scale = float(np.max(np.abs(np.concatenate([d_friction[rows], d_normal[rows]]))))
    friction = np.where(friction <= 1e-12 * force_scale, 0.0, friction)
    normal = np.where(normal <= 1e-12 * force_scale, 0.0, normal)
    rolling_mass = inertia / arrays.scale[rows] ** 2
    closed = _closed_form(cell, q, rolling_mass, arrays)
    return Dispersion(
        system=system,
        cell=cell,
        q=q,
        omega=omega,
        group_velocity=group,
        displacement=np.abs(np.swapaxes(centre, 1, 2)),
        friction=friction,
        normal_force=normal,
        friction_at_rest=friction_rest[rows],
        normal_at_rest=normal_rest[rows],
        closed_form=closed,
        rolling_mass=rolling_mass,
        warnings=tuple(warnings),
    )


def _unbalanced(cell: UnitCell) -> str:
    """Why the lattice's placement is not an equilibrium ('' when it is: the generalised
    forces on cell 0, (M7), vanish to 1e-9 of the springs' force scale)."""
    arrays = system_arrays(cell.lattice)
    force = generalized_forces(arrays, np.zeros(arrays.n_bodies))[cell.index : cell.index + cell.p]
    scale = float(np.sum(arrays.stiffness) * np.max(arrays.radius) * cell.a)
    if float(np.max(np.abs(force))) <= 1e-9 * scale:
        return ""
    worst = int(np.argmax(np.abs(force)))
    return (
        f"dispersion: the placement is not an equilibrium of the periodic chain (a net "
        f"generalised force of {force[worst]:.3g} on '{cell.ids[worst]}'): the springs' rest "
        "lengths must balance in every cell"
    )


def _periodic_cell(system: System) -> tuple[UnitCell, list[str]]:
    """The unit cell of the chain as placed, when its placement is an equilibrium of the
    lattice; otherwise (an initial condition displaces it), for a chain of at most
    :data:`EQUILIBRIUM_BODIES` bodies, as it rests in the equilibrium nearest the placement
    (:func:`~rollspring.analysis.linear.find_equilibrium`)."""
    try:
        cell = unit_cell(system)
        problem = _unbalanced(cell)
    except AnalysisError as exc:
        cell, problem = None, str(exc)
    if cell is not None and not problem:
        return cell, []
    if len(system.bodies) > EQUILIBRIUM_BODIES:
        raise AnalysisError(
            f"{problem} (the placement is read as it is: give the chain at rest, e.g. "
            "rollspring chain without an initial condition)"
        )
    equilibrium = find_equilibrium(system_arrays(system))
    if not equilibrium.found:
        raise AnalysisError(problem)
    at_rest = rolled(system, equilibrium.q, velocities=np.zeros(len(system.bodies)))
    try:
        cell = unit_cell(at_rest)
    except AnalysisError:
        raise AnalysisError(problem) from None
    if _unbalanced(cell):
        raise AnalysisError(problem)
    return cell, [
        "read about the chain's equilibrium: the displacements and velocities of its "
        "initial condition are left out"
    ]


def _closed_form(cell: UnitCell, q: FloatArray, mass: FloatArray, arrays: Any) -> FloatArray | None:
    """The closed form of the monatomic or diatomic lattice when every spring of the cell
    joins neighbouring centres on one level with one stiffness (else None)."""
    p = cell.p
    springs = cell.springs
    if p > 2 or len(springs) != p or not all(centre and d == 1 for _, centre, _, d in springs):
        return None
    heights = arrays.track + arrays.radius
    if np.ptp(heights) > _SAME * float(np.max(arrays.radius)):
        return None
    k = springs[0][0]
    if any(not _same(s[0], k, 0.0) for s in springs):
        return None
    if p == 1:
        return monatomic_branch(q, cell.a, k, float(mass[0]))[:, None]
    return diatomic_branches(q, cell.a, k, float(mass[0]), float(mass[1]))


def monatomic_branch(q: FloatArray, a: float, k: float, mass: float) -> FloatArray:
    r""":math:`\omega = 2\sqrt{k/M}\,|\sin(qa/2)|`, :math:`M = (1+\gamma)m` (centre springs)."""
    result: FloatArray = 2.0 * np.sqrt(k / mass) * np.abs(np.sin(0.5 * np.asarray(q) * a))
    return result


def diatomic_branches(q: FloatArray, a: float, k: float, m1: float, m2: float) -> FloatArray:
    r"""The two branches (acoustic, optical) of the diatomic lattice, (len(q), 2), rad/s:

    .. math:: \omega_\pm^2 = kS \pm k\sqrt{S^2 - 4\sin^2(qa/2)/(M_1M_2)},\qquad
              S = \frac1{M_1} + \frac1{M_2}

    (``m1``, ``m2`` the rolling masses :math:`(1+\gamma)m`, ``a`` the cell length). The
    acoustic branch is evaluated as :math:`\omega_-^2 = 4k^2\sin^2(qa/2)/(M_1M_2\,\omega_+^2)`
    (the product of the roots), free of the cancellation near :math:`q = 0`."""
    total = 1.0 / m1 + 1.0 / m2
    sine2 = np.sin(0.5 * np.asarray(q, dtype=float) * a) ** 2
    root = np.sqrt(np.maximum(total**2 - 4.0 * sine2 / (m1 * m2), 0.0))
    upper = k * total + k * root
    lower = 4.0 * k * k * sine2 / (m1 * m2 * upper)
    result: FloatArray = np.sqrt(np.stack([lower, upper], axis=-1))
    return result

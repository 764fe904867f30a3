r"""Waves on a chain: where the energy is, how fast it travels, against the group velocity.

**Energy per body.** Along a motion (centre positions :math:`x_i(t)`, m, and velocities
:math:`v_i(t)`, m/s; coordinates :math:`q_i = (x_i - x_{i0})/s_i`, :math:`\dot q_i = v_i/s_i`,
docs/physics.md section 2) body :math:`i` carries

.. math:: e_i = \tfrac12 J_i \dot q_i^2 + \sum_{s \ni i} w_{si}\,\tfrac12 k_s (l_s - L_{0s})^2
          - \sum_{f \text{ on } i} F_f\cdot\bigl(P_f(q) - P_f(0)\bigr)

(J), with :math:`w_{si} = \tfrac12` for each body end of a spring joining two bodies and
:math:`w_{si} = 1` for the body of a spring tied to an anchor (a wall has no energy of its
own), so :math:`\sum_i e_i = T + U`, the total energy (M5), term by term.

**Energy centroid** and spread (m):

.. math:: X_E = \frac{\sum_i x_i e_i}{\sum_i e_i}, \qquad
          \sigma_E^2 = \frac{\sum_i (x_i - X_E)^2 e_i}{\sum_i e_i}.

In a linear lattice a packet's energy travels at the group velocity
:math:`v_g = d\omega/dq` of its wavenumber and branch (:mod:`rollspring.analysis.dispersion`).
The **measured speed** is the least-squares slope of :math:`X_E(t)` over the **clear window**:
the output times from the start for as long as :math:`[X_E - 3\sigma_E, X_E + 3\sigma_E]`
lies inside the chain (between its outermost bodies at rest), i.e. before the packet's edge
(99.7 % of a Gaussian's energy) reaches an end and is reflected.

**A struck end** (the energy starts within a few cells of an end) sends a front, not a packet:
its position :math:`d_F(t)` is the distance from the struck end beyond which a fraction
``front_fraction`` (1e-3) of the energy lies; no part of the disturbance travels faster than
the largest group velocity over the zone, :math:`\max_{q,b}|v_g|`, against which its
least-squares slope (while the front is inside the chain) is reported.

**Wavenumber and branch of a packet** (when not given): with the rolling masses
:math:`M_i = J_i/s_i^2`, the frequency :math:`\bar\omega^2 = \sum M_i v_i^2/\sum M_i u_i^2`
(:math:`u_i` the centre displacements from the rest positions at :math:`t = 0`), and
:math:`z_{c,r} = \sqrt{M_r}(u_{c,r} + i v_{c,r}/\bar\omega)` (cell :math:`c`, body :math:`r`
of the cell), a wave :math:`A e^{i(qca - \omega t)}` has :math:`z \propto e^{iqca}`: the
wavenumber is the peak of :math:`\sum_r |\sum_c z_{c,r} e^{-iqca}|^2` (a zero-padded FFT,
16 points per :math:`2\pi/(N_c a)`), the branch the one whose :math:`\omega_b(q)` is nearest
:math:`\bar\omega`.

Every function takes plain arrays (the simulation's outputs) and the system: this module does
not depend on :mod:`rollspring.simulate`.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from rollspring.analysis.dispersion import dispersion
from rollspring.analysis.linear import find_equilibrium
from rollspring.errors import AnalysisError
from rollspring.model import System, rolled
from rollspring.physics import SystemArrays, force_work, spring_energies, system_arrays
from rollspring.physics.arrays import FloatArray

__all__ = [
    "CLEARANCE",
    "FRONT_FRACTION",
    "Waves",
    "body_energies",
    "centroid_speed",
    "clear_window",
    "energy_centroid",
    "energy_front",
    "packet_wavenumber",
    "travelling_wave",
]

#: Half-width of the packet, in energy spreads σ_E, that must be inside the chain.
CLEARANCE = 3.0
#: The fraction of the energy ahead of a front.
FRONT_FRACTION = 1e-3
#: Rows of the motion whose springs are evaluated at once (bounds the memory: rows × springs).
_CHUNK = 256


def body_energies(system: SystemArrays, x: FloatArray, v: FloatArray) -> FloatArray:
    r"""The energy :math:`e_i` each body carries (module docstring), J, shape (..., n), from the
    centre positions ``x`` (m) and velocities ``v`` (m/s), shapes (..., n). Sums over the
    bodies to :func:`rollspring.physics.total_energy` (gravity, a constant, left out)."""
    x = np.asarray(x, dtype=np.float64)
    v = np.asarray(v, dtype=np.float64)
    if x.shape != v.shape or x.shape[-1:] != (system.n_bodies,):
        raise AnalysisError(
            f"body_energies: x and v must both be (..., {system.n_bodies}) arrays "
            f"(got {x.shape} and {v.shape})"
        )
    lead = x.shape[:-1]
    q = ((x - system.x0) / system.scale).reshape(-1, system.n_bodies)
    qdot = (v / system.scale).reshape(-1, system.n_bodies)
    energy = 0.5 * system.inertia * qdot**2
    both = np.all(system.end_body >= 0, axis=1)
    share = np.where(both[:, None], 0.5, 1.0) * system.end_on_body  # (S, 2)
    for start in range(0, q.shape[0], _CHUNK):
        rows = slice(start, start + _CHUNK)
        if system.n_springs:
            spring = spring_energies(system, q[rows])  # (rows, S)
            block = energy[rows]
            for j in range(2):
                np.add.at(block.T, system.end_index[:, j], (share[:, j] * spring).T)
        if system.force.shape[0]:
            np.add.at(energy[rows].T, system.force_body, -force_work(system, q[rows]).T)
    result: FloatArray = energy.reshape(*lead, system.n_bodies)
    return result


def energy_centroid(x: FloatArray, energies: FloatArray) -> tuple[FloatArray, FloatArray]:
    r"""The energy centroid :math:`X_E` and spread :math:`\sigma_E` (m), shapes (...), of
    bodies at ``x`` (m) carrying ``energies`` (J), shapes (..., n) (module docstring)."""
    x = np.asarray(x, dtype=np.float64)
    e = np.asarray(energies, dtype=np.float64)
    total = e.sum(axis=-1)
    safe = np.where(total != 0.0, total, 1.0)
    centroid = np.sum(x * e, axis=-1) / safe
    variance = np.sum((x - centroid[..., None]) ** 2 * e, axis=-1) / safe
    spread: FloatArray = np.sqrt(np.maximum(variance, 0.0))
    return centroid, spread


def clear_window(
    centroid: FloatArray,
    spread: FloatArray,
    left: float,
    right: float,
    *,
    clearance: float = CLEARANCE,
) -> int:
    r"""How many output rows from the start the packet stays clear of the ends: the rows
    while :math:`X_E - c\,\sigma_E \ge` ``left`` and :math:`X_E + c\,\sigma_E \le` ``right``
    (:math:`c` = ``clearance``), counted until the first that is not (0 if the first is not)."""
    clear = (centroid - clearance * spread >= left) & (centroid + clearance * spread <= right)
    outside = np.flatnonzero(~clear)
    return int(outside[0]) if outside.size else int(clear.size)


def centroid_speed(t: FloatArray, centroid: FloatArray, rows: int) -> tuple[float, float]:
    r"""The least-squares slope :math:`\hat v` (m/s) of :math:`X_E(t)` over the first ``rows``
    output times, and the rms distance (m) of the points from the fitted line; NaN for fewer
    than 3 rows."""
    if rows < 3:
        return math.nan, math.nan
    tt = np.asarray(t[:rows], dtype=np.float64)
    xx = np.asarray(centroid[:rows], dtype=np.float64)
    slope, intercept = np.polyfit(tt, xx, 1)
    residual = xx - (slope * tt + intercept)
    return float(slope), float(np.sqrt(np.mean(residual**2)))


def energy_front(
    x_rest: FloatArray,
    energies: FloatArray,
    *,
    start: float,
    fraction: float = FRONT_FRACTION,
) -> FloatArray:
    r"""The front of a disturbance started at ``start`` (m): the distance :math:`d_F` from it,
    over the bodies' rest positions ``x_rest`` (n,), beyond which ``fraction`` of the energy
    lies (the bodies' energies ``energies``, (..., n)); shape (...), m."""
    distance = np.abs(np.asarray(x_rest, dtype=np.float64) - start)
    order = np.argsort(distance, kind="stable")
    e = np.maximum(np.asarray(energies, dtype=np.float64)[..., order], 0.0)
    beyond = e[..., ::-1].cumsum(axis=-1)[..., ::-1]  # energy at this body and farther
    total = beyond[..., :1]
    # the farthest body with at least `fraction` of the energy at or beyond it
    inside = beyond >= fraction * total
    last = inside.shape[-1] - 1 - np.argmax(inside[..., ::-1], axis=-1)
    result: FloatArray = distance[order][last]
    return result


def packet_wavenumber(
    system: SystemArrays, cell_size: int, cell_length: float, u: FloatArray, v: FloatArray
) -> tuple[float, float]:
    r"""The wavenumber :math:`q` (rad/m, in the first zone) and the frequency
    :math:`\bar\omega` (rad/s) of the motion with centre displacements ``u`` (m, from rest)
    and velocities ``v`` (m/s) of a chain of cells of ``cell_size`` bodies, ``cell_length``
    metres long (module docstring)."""
    p = int(cell_size)
    cells = system.n_bodies // p
    rolling_mass = system.inertia / system.scale**2
    weight = np.sqrt(rolling_mass)
    u = np.asarray(u, dtype=np.float64)
    v = np.asarray(v, dtype=np.float64)
    stiff = float(np.sum(rolling_mass * u**2))
    omega = math.sqrt(float(np.sum(rolling_mass * v**2)) / stiff) if stiff > 0 else 0.0
    z = weight * (u + (1j * v / omega if omega > 0 else 0.0))
    z = z[: cells * p].reshape(cells, p)
    size = 16 * cells
    power = np.sum(np.abs(np.fft.fft(z, n=size, axis=0)) ** 2, axis=1)
    q = 2.0 * math.pi * np.fft.fftfreq(size, d=cell_length)
    return float(q[int(np.argmax(power))]), omega


@dataclass(frozen=True)
class Waves:
    """Energy along a chain's motion and the speed it travels at (module docstring); SI units.

    ``energies`` (T, n) J per body; ``centroid``, ``spread`` (T,) m; ``reference`` (n,) the
    rest positions (m, the equilibrium nearest the placement). ``kind``: ``"packet"`` (the
    energy starts clear of the ends), ``"front"`` (a struck end) or ``"spread"`` (neither: no
    speed is measured). For a packet: ``window`` (rows from the start while it is clear),
    ``speed`` (m/s, the centroid's slope there) and ``residual`` (m), ``wavenumber`` (rad/m),
    ``branch`` (1-based), ``group_velocity`` (m/s, dω/dq there); for a front: ``front`` (T,)
    m from the struck end, ``window`` the rows before it reaches the far end, ``speed`` its
    slope. ``max_group_velocity`` (m/s) over the zone and all branches. ``notes`` say what
    could not be computed and why. Values that do not apply are NaN (arrays: None)."""

    t: FloatArray
    energies: FloatArray
    centroid: FloatArray
    spread: FloatArray
    reference: FloatArray
    kind: str
    window: int
    speed: float
    residual: float
    wavenumber: float
    branch: int | None
    group_velocity: float
    max_group_velocity: float
    cell_length: float
    front: FloatArray | None = None
    start: float = math.nan
    notes: tuple[str, ...] = field(default_factory=tuple)

    @property
    def window_end(self) -> float:
        """The last time of the window (s); NaN without one."""
        return float(self.t[self.window - 1]) if self.window >= 1 else math.nan

    @property
    def relative_difference(self) -> float:
        """(measured − predicted)/predicted: the centroid against :math:`v_g` for a packet,
        the front against :math:`\\max|v_g|` for a struck end; NaN otherwise."""
        expected = self.group_velocity if self.kind == "packet" else self.max_group_velocity
        if self.kind == "spread" or not math.isfinite(expected) or expected == 0.0:
            return math.nan
        return (self.speed - expected) / expected

    def to_dict(self) -> dict[str, Any]:
        """The numbers (no per-body arrays) as JSON-ready values (NaN as None)."""

        def number(value: float) -> float | None:
            return float(value) if math.isfinite(value) else None

        return {
            "kind": self.kind,
            "window_rows": self.window,
            "window_end": number(self.window_end),
            "speed": number(self.speed),
            "residual": number(self.residual),
            "wavenumber": number(self.wavenumber),
            "branch": self.branch,
            "group_velocity": number(self.group_velocity),
            "max_group_velocity": number(self.max_group_velocity),
            "relative_difference": number(self.relative_difference),
            "cell_length": number(self.cell_length),
            "notes": list(self.notes),
            "units": {"speed": "m/s", "wavenumber": "rad/m", "window_end": "s"},
        }


def travelling_wave(
    system: System,
    t: FloatArray,
    x: FloatArray,
    v: FloatArray,
    *,
    wavenumber: float | None = None,
    branch: int | None = None,
    clearance: float = CLEARANCE,
) -> Waves:
    r"""The energy of ``system``'s motion (output times ``t`` (T,), s; centre positions ``x``
    and velocities ``v``, (T, n)) per body, its centroid and the speed it travels at, beside
    the group velocity of the packet's ``wavenumber`` (rad/m) and ``branch`` (1-based) on the
    chain read as a periodic lattice (found from the motion at ``t[0]`` when not given), or
    for a struck end the front's speed beside the largest group velocity (module docstring).
    Where the chain is not periodic (no dispersion) the speeds are measured and the group
    velocities are NaN, with a note."""
    t = np.asarray(t, dtype=np.float64)
    x = np.asarray(x, dtype=np.float64)
    v = np.asarray(v, dtype=np.float64)
    arrays = system_arrays(system)
    energies = body_energies(arrays, x, v)
    centroid, spread = energy_centroid(x, energies)
    notes: list[str] = []
    equilibrium = find_equilibrium(arrays)
    q_rest = equilibrium.q if equilibrium.found else np.zeros(arrays.n_bodies)
    if not equilibrium.found:
        notes.append("no equilibrium found: displacements are read from the placement")
    reference = arrays.x0 + arrays.scale * q_rest
    left, right = float(reference.min()), float(reference.max())
    length = right - left
    rows = clear_window(centroid, spread, left, right, clearance=clearance)
    kind = "packet" if rows >= 3 else "spread"
    front = None
    start = math.nan
    if kind == "spread" and length > 0:
        near = min(abs(centroid[0] - left), abs(centroid[0] - right))
        if near + spread[0] <= 0.1 * length:
            kind = "front"
            start = left if abs(centroid[0] - left) <= abs(centroid[0] - right) else right
            front = energy_front(reference, energies, start=start)
            reached = np.flatnonzero(front >= 0.9 * length)
            rows = int(reached[0]) if reached.size else int(t.size)
    if kind == "spread":
        rows = 0
        notes.append(
            "the energy starts neither clear of the ends nor at one end: no speed is measured"
        )
    speed, residual = centroid_speed(t, centroid if front is None else front, rows)
    if front is not None and rows >= 1 and start == right:
        speed = -speed if math.isfinite(speed) else speed
    rest = rolled(system, q_rest, velocities=np.zeros(arrays.n_bodies))
    group = top = q_found = cell_length = math.nan
    chosen: int | None = None
    try:
        lattice = dispersion(rest)
    except AnalysisError as exc:
        notes.append(f"no group velocity: {exc}")
    else:
        cell_length = lattice.cell.a
        top = float(np.abs(lattice.group_velocity).max())
        if kind == "packet":
            u0 = x[0] - reference
            q_found, omega_bar = packet_wavenumber(arrays, lattice.cell.p, cell_length, u0, v[0])
            if wavenumber is not None:
                q_found = float(wavenumber)
            at_q = dispersion(rest, wavenumbers=[q_found])
            if branch is None:
                chosen = int(np.argmin(np.abs(at_q.omega[0] - omega_bar))) + 1
            else:
                chosen = int(branch)
                if not 1 <= chosen <= lattice.cell.p:
                    raise AnalysisError(f"branch: must be from 1 to {lattice.cell.p}")
            group = float(at_q.group_velocity[0, chosen - 1])
    return Waves(
        t=t,
        energies=energies,
        centroid=centroid,
        spread=spread,
        reference=reference,
        kind=kind,
        window=rows,
        speed=speed,
        residual=residual,
        wavenumber=q_found,
        branch=chosen,
        group_velocity=group,
        max_group_velocity=top,
        cell_length=cell_length,
        front=front,
        start=start,
        notes=tuple(notes),
    )

r"""Modal analysis of a system (:func:`analyze`): the modes about its equilibrium with the
forces they change, the stationary point, the exact linear response to the initial conditions,
and the physics checks on the result.

The motion about the equilibrium is a sum of normal modes (:mod:`rollspring.analysis.linear`);
every quantity that depends linearly on the state (centre positions, the CM, friction, normal
forces, spring lengths) is then a constant plus a sum of sinusoids, whose amplitudes are
reported here. :func:`analyze` is :func:`analysis_request` (the arguments checked once), the cost
guard, then :func:`run_analysis`, which an interface that estimated the cost itself calls
directly.
"""

from __future__ import annotations

import math
import os
from dataclasses import dataclass, replace
from typing import Any

import numpy as np

from rollspring.analysis.banded import ALL_MODES_LIMIT, DENSE_LIMIT, banded_modes
from rollspring.analysis.checks import physics_warnings
from rollspring.analysis.linear import (
    _SAME_FREQUENCY,
    LinearAnalysis,
    Mode,
    find_equilibrium,
    normal_modes,
    resistance_decay,
    stationary_weights,
)
from rollspring.errors import AnalysisError
from rollspring.model import System
from rollspring.physics import (
    SpringState,
    SystemArrays,
    contact_forces,
    contact_forces_jacobian,
    damping_matrix,
    mass_matrix,
    spring_state,
    stiffness_matrix,
    system_arrays,
)
from rollspring.physics.arrays import FloatArray

__all__ = ["AnalysisRequest", "analysis_request", "analyze", "run_analysis"]


def analyze(
    system: System | dict[str, Any] | str | os.PathLike[str],
    *,
    confirm: bool = False,
    modes: int | tuple[int, int] | None = None,
    sparse: bool | None = None,
) -> LinearAnalysis:
    r"""Linear analysis of a system about the equilibrium nearest its initial placement.

    Finds the equilibrium (:func:`find_equilibrium`), builds :math:`M` and :math:`K`
    (docs/physics.md (M12)), the normal modes, the zero modes and the stationary point they imply
    (M14), the exact linear response to the initial conditions (modal superposition): the
    amplitude of every body, of the CM and of :math:`\hat X`, the friction and normal-force
    amplitudes, the static friction coefficient the motion needs (:math:`\max |f|/N`), for two
    bodies the paper's split of the spring into :math:`k_1, k_2`, and each spring's tilt and
    tension.

    ``system`` is a :class:`~rollspring.model.System`, its JSON form (a dict) or a file path or
    preset name (anything else is a one-line :class:`~rollspring.errors.ModelError`). An
    analysis estimated at more than 5 minutes (:func:`~rollspring.analysis.costs.analysis_cost`:
    about 950 bodies or more) is refused with its estimate
    (:class:`~rollspring.errors.CostTooHigh`) unless ``confirm=True`` (``--yes`` on the command
    line).

    Beyond :data:`~rollspring.analysis.banded.DENSE_LIMIT` bodies the matrices stay sparse
    (``mass`` and ``stiffness`` are SciPy CSR arrays) and the modes come from the banded
    solvers of :mod:`rollspring.analysis.banded`: every mode up to
    :data:`~rollspring.analysis.banded.ALL_MODES_LIMIT` bodies, beyond it the lowest 20 (the
    linear response, which needs them all, is then not computed). ``modes`` chooses: a count
    k (the lowest k modes) or a band ``(first, last)`` (1-based, ascending, inclusive), on
    any system; a partial set of modes leaves the response out. ``sparse`` forces the sparse
    path (True) or the dense one (False) whatever the size.

    Parameters
    ----------
    system
        A :class:`~rollspring.model.System`, its JSON form, a file path or a preset name.
    confirm
        Start even when the estimated time is above the bound.
    modes
        The lowest k modes, or a band ``(first, last)`` (1-based); None: every mode.
    sparse
        Force the sparse (True) or dense (False) path; None: by size.

    Returns
    -------
    LinearAnalysis
        The equilibrium, M and K, the modes, X̂'s weights, the friction needed.
    """
    from rollspring.analysis.costs import CONFIRM, analysis_cost, check_cost
    from rollspring.model import as_system

    system = as_system(system)
    if not isinstance(confirm, bool):
        raise AnalysisError(f"confirm: must be True or False, got {confirm!r}")
    request = analysis_request(system, modes=modes, sparse=sparse)  # fails before any work
    check_cost(analysis_cost(system, modes=modes), confirmed=confirm, flag=CONFIRM)
    return run_analysis(system, request)


@dataclass(frozen=True, slots=True)
class AnalysisRequest:
    """The checked arguments of one :func:`analyze` of a system (see there)."""

    #: the ``modes`` asked for (what the estimate counts), None for the default
    modes: int | tuple[int, int] | None
    #: the 0-based inclusive range of modes computed, None for all
    select: tuple[int, int] | None
    #: the sparse (banded) path: True, False, or None to choose by size
    sparse: bool | None


def analysis_request(
    system: System, *, modes: int | tuple[int, int] | None = None, sparse: bool | None = None
) -> AnalysisRequest:
    """The arguments of :func:`analyze` on ``system`` checked (``modes`` against its bodies:
    one-line :class:`~rollspring.errors.AnalysisError` naming the argument)."""
    if sparse is not None and not isinstance(sparse, bool | np.bool_):  # "yes" was taken as true
        raise AnalysisError(f"sparse: must be True, False or None (by size), got {sparse!r}")
    return AnalysisRequest(modes, _selection(modes, len(system.bodies)), sparse)


def run_analysis(system: System, request: AnalysisRequest) -> LinearAnalysis:
    """The analysis :func:`analyze` makes of a request checked already
    (:func:`analysis_request`), without estimating its cost (the caller's: :func:`analyze`, or
    an interface that estimated it once)."""
    modes, select, sparse = request.modes, request.select, request.sparse
    arrays = system_arrays(system)
    warnings: list[str] = []
    n = arrays.n_bodies
    large = n > DENSE_LIMIT if sparse is None else bool(sparse)
    equilibrium = find_equilibrium(arrays, sparse=large)
    if not equilibrium.found:
        warnings.append(
            equilibrium.reason + "; modes are those at the initial placement, and no "
            "response is computed"
        )
    q_eq = equilibrium.q
    mass: Any
    stiffness: Any
    if large:
        import scipy.sparse

        mass = scipy.sparse.diags_array(arrays.inertia).tocsr()
        stiffness = stiffness_matrix(arrays, q_eq, sparse=True)
        eigenvalues, found_vectors, kinds, _ = banded_modes(arrays, stiffness, select=select)
        assert found_vectors is not None
        vectors = found_vectors
        d_friction, d_normal = contact_forces_jacobian(arrays, q_eq, sparse=True)
    else:
        mass = mass_matrix(arrays)
        stiffness = stiffness_matrix(arrays, q_eq)
        eigenvalues, vectors, kinds = normal_modes(mass, stiffness)
        if select is not None:
            lo, hi = select
            eigenvalues, vectors, kinds = (
                eigenvalues[lo : hi + 1],
                vectors[:, lo : hi + 1],
                kinds[lo : hi + 1],
            )
        d_friction, d_normal = contact_forces_jacobian(arrays, q_eq)
    friction_eq, normal_eq = contact_forces(arrays, q_eq)
    friction_eq = np.where(np.abs(friction_eq) < 1e-12 * _contact_scale(arrays), 0.0, friction_eq)
    springs = spring_state(arrays, q_eq)
    levers = _Levers(springs, dense=not large)

    if large:
        mode_list = _modes_at_once(
            arrays, levers, d_friction, d_normal, eigenvalues, vectors, kinds
        )
    else:
        mode_list = [
            _mode(arrays, levers, d_friction, d_normal, lam, vec, kind)
            for lam, vec, kind in zip(eigenvalues, vectors.T, kinds, strict=True)
        ]
    partial = select is not None and (select[0] > 0 or select[1] < n - 1)
    if partial:
        assert select is not None
        warnings.append(
            f"modes {select[0] + 1} to {select[1] + 1} of {n} computed"
            + (
                f" (all {n} are computed for at most {ALL_MODES_LIMIT} bodies, or on request)"
                if modes is None
                else ""
            )
            + ": the linear response, which needs every mode, is not computed"
        )

    # zero modes and the stationary point (M14)
    zero = [k for k, kind in enumerate(kinds) if kind == "zero"]
    weights = stationary_weights(arrays, vectors, kinds)
    modes_list = mode_list
    position = velocity = None
    if weights is not None:
        position = float(weights @ arrays.x0)
        velocity = float(_clean(weights @ arrays.v0, float(np.max(np.abs(arrays.v0)))))
        if velocity != 0.0:
            warnings.append(
                f"the initial velocities move the stationary point X̂ uniformly at "
                f"{velocity:.6g} m/s"
            )
    elif len(zero) == 1:
        warnings.append("the conserved combination has zero total weight: no stationary point")
    elif len(zero) > 1:
        warnings.append(
            f"{len(zero)} zero modes (parts of the system move freely): no single stationary point"
        )

    unstable = [m for m in modes_list if m.kind == "unstable"]
    response: dict[str, Any] = {}
    if not equilibrium.found or partial:
        pass
    elif unstable:
        warnings.append(
            f"the equilibrium is unstable ({len(unstable)} mode(s) with negative stiffness, "
            f"growth rate {unstable[0].omega:.6g} 1/s): no bounded linear response"
        )
    else:
        response = _response(
            arrays,
            q_eq,
            eigenvalues,
            vectors,
            kinds,
            d_friction,
            d_normal,
            friction_eq,
            normal_eq,
            levers,
            weights,
            vectorised=large,
        )

    tilt = _tilt_deg(springs.vector)
    split = _spring_split(arrays, springs.lever) if equilibrium.found and n == 2 else None
    damping = damping_matrix(arrays, q_eq, sparse=large)
    if np.any(arrays.damping > 0):
        ratios = []
        for k, mode in enumerate(modes_list):
            if mode.kind == "oscillating":
                ratio = float(vectors[:, k] @ (damping @ vectors[:, k])) / (2 * mode.omega)
                modes_list[k] = replace(mode, damping_ratio=ratio)
                ratios.append(f"{ratio:.4g}")
        warnings.append(
            "springs have damping: the modes are the undamped ones, with modal damping ratios "
            f"({', '.join(ratios)}) from the modal projection of C; the response amplitudes are "
            "those of the undamped motion (the first swing)"
        )
    if arrays.resisted:
        drops = []
        for k, mode in enumerate(modes_list):
            if mode.kind == "oscillating":
                drop = resistance_decay(arrays, normal_eq, mode.omega, vectors[:, k])
                modes_list[k] = replace(mode, resistance_decay=drop)
                drops.append(f"{drop:.4g}")
        resisted = [i for i, c in zip(arrays.ids, arrays.rolling_resistance, strict=True) if c > 0]
        warnings.append(
            f"rolling resistance ({', '.join(resisted)}): the motion is not linear (the "
            "resistance's torque C_rr N R takes the sign of each body's rotation, and holds a "
            "body at rest while the torque driving it is within it); each mode's amplitude "
            f"falls by about ({', '.join(drops)}) m a period, linearly, not exponentially "
            "(docs/physics.md (M23)); the response amplitudes are those of the motion without "
            "it (the first swing)"
        )
    analysis = LinearAnalysis(
        system=system,
        arrays=arrays,
        equilibrium=equilibrium,
        mass=mass,
        stiffness=stiffness,
        modes=modes_list,
        equilibrium_friction=friction_eq,
        equilibrium_normal=normal_eq,
        spring_tilt_deg=tilt,
        spring_tension=np.where(
            np.abs(springs.tension) < 1e-12 * arrays.stiffness.sum(), 0.0, springs.tension
        ),
        spring_length=springs.length,
        stationary_weights=weights,
        stationary_position=position,
        stationary_velocity=velocity,
        amplitude=response.get("amplitude"),
        velocity_amplitude=response.get("velocity_amplitude"),
        drift_velocity=response.get("drift_velocity"),
        cm_amplitude=response.get("cm_amplitude"),
        stationary_amplitude=response.get("stationary_amplitude"),
        friction_amplitude=response.get("friction_amplitude"),
        normal_force_range=response.get("normal_force_range"),
        required_mu=response.get("required_mu"),
        spring_split=split,
        warnings=warnings,
    )
    warnings.extend(physics_warnings(analysis))
    return analysis


def _contact_scale(arrays: SystemArrays) -> float:
    return float(np.sum(arrays.mass) * max(arrays.gravity, 1.0) + np.sum(arrays.stiffness) * 1.0)


def _selection(modes: int | tuple[int, int] | None, n: int) -> tuple[int, int] | None:
    """The 0-based inclusive range of modes ``modes`` asks for (None: all), checked."""
    if modes is None:
        return None if n <= ALL_MODES_LIMIT else (0, min(n, _LOWEST) - 1)
    if isinstance(modes, bool) or not isinstance(modes, (int, np.integer, tuple)):
        raise AnalysisError(f"modes: a count or a (first, last) pair, got {modes!r}")
    if isinstance(modes, tuple):
        if len(modes) != 2 or not all(
            isinstance(v, (int, np.integer)) and not isinstance(v, bool) for v in modes
        ):
            raise AnalysisError(f"modes: a (first, last) pair of whole numbers, got {modes!r}")
        first, last = int(modes[0]), int(modes[1])
        if not 1 <= first <= last <= n:
            raise AnalysisError(f"modes: need 1 <= first <= last <= {n} (the bodies), got {modes}")
        return first - 1, last - 1
    count = int(modes)
    if not 1 <= count <= n:
        raise AnalysisError(f"modes: need 1 to {n} (the bodies), got {count}")
    return 0, count - 1


#: modes computed by default beyond ALL_MODES_LIMIT bodies
_LOWEST = 20


class _Levers:
    r"""The springs' lever arms :math:`b_{si}` as a linear map from coordinates to spring
    extensions, ``levers @ v`` (v of shape (n,) or (n, k)): a dense (S, n) product for small
    systems (the reference), per spring end for large ones (O(S))."""

    def __init__(self, springs: SpringState, *, dense: bool) -> None:
        self._springs = springs
        self._dense = springs.lever if dense else None
        self.max_abs = float(np.max(np.abs(springs.end_lever), initial=0.0))

    def __matmul__(self, vectors: FloatArray) -> FloatArray:
        if self._dense is not None:
            result: FloatArray = self._dense @ vectors
            return result
        end_lever, index = self._springs.end_lever, self._springs.end_index
        values = np.asarray(vectors)[index]  # (S, 2) or (S, 2, k)
        product: FloatArray = (
            np.einsum("sj,sjk->sk", end_lever, values)
            if values.ndim == 3
            else np.einsum("sj,sj->s", end_lever, values)
        )
        return product


def _max_abs(*matrices: Any) -> float:
    """Largest |entry| of dense or SciPy sparse matrices."""
    biggest = 0.0
    for matrix in matrices:
        data = matrix.data if hasattr(matrix, "tocsr") else matrix
        biggest = max(biggest, float(np.max(np.abs(data), initial=0.0)))
    return biggest


def _mode(
    arrays: SystemArrays,
    lever: _Levers,
    d_friction: Any,
    d_normal: Any,
    eigenvalue: float,
    vector: FloatArray,
    kind: str,
) -> Mode:
    shape_x = arrays.scale * vector
    biggest = int(np.argmax(np.abs(shape_x)))
    norm = shape_x[biggest]
    shape_q = vector / norm
    shape_x = shape_x / norm
    length_scale = lever.max_abs * float(np.max(np.abs(shape_q)))
    # rounding noise of an exact zero, relative to the largest force change along the mode: a
    # contact force's, or the springs' (k times the extension; frictionless geometries have
    # contact forces that vanish to first order, and then only the springs set the scale)
    force_scale = _max_abs(d_friction, d_normal) * float(np.max(np.abs(shape_q)))
    force_scale = max(force_scale, float(np.max(arrays.stiffness, initial=0.0)) * length_scale)
    return Mode(
        eigenvalue=float(eigenvalue),
        omega=float(math.sqrt(abs(eigenvalue))),
        kind=str(kind),
        shape_q=_clean(shape_q, float(np.max(np.abs(shape_q)))),
        shape_x=_clean(shape_x, 1.0),
        spring_extension=_clean(lever @ shape_q, length_scale),
        friction=_clean(d_friction @ shape_q, force_scale),
        normal_force=_clean(d_normal @ shape_q, force_scale),
    )


def _modes_at_once(
    arrays: SystemArrays,
    lever: _Levers,
    d_friction: Any,
    d_normal: Any,
    eigenvalues: FloatArray,
    vectors: FloatArray,
    kinds: np.ndarray,
) -> list[Mode]:
    """:func:`_mode` of every column of ``vectors`` with matrix products (large systems)."""
    if not eigenvalues.size:
        return []
    columns = np.arange(eigenvalues.size)
    shape_x = arrays.scale[:, None] * vectors
    biggest = np.argmax(np.abs(shape_x), axis=0)
    norm = shape_x[biggest, columns]
    shape_q = vectors / norm
    shape_x = shape_x / norm
    peak_q = np.max(np.abs(shape_q), axis=0)
    length_scale = lever.max_abs * peak_q
    force_scale = np.maximum(
        _max_abs(d_friction, d_normal) * peak_q,
        float(np.max(arrays.stiffness, initial=0.0)) * length_scale,
    )
    extension = lever @ shape_q
    friction = np.asarray(d_friction @ shape_q)
    normal = np.asarray(d_normal @ shape_q)
    shape_q = np.where(np.abs(shape_q) <= 1e-12 * peak_q, 0.0, shape_q)
    shape_x = np.where(np.abs(shape_x) <= 1e-12, 0.0, shape_x)
    extension = np.where(np.abs(extension) <= 1e-12 * length_scale, 0.0, extension)
    friction = np.where(np.abs(friction) <= 1e-12 * force_scale, 0.0, friction)
    normal = np.where(np.abs(normal) <= 1e-12 * force_scale, 0.0, normal)
    return [
        Mode(
            eigenvalue=float(eigenvalues[k]),
            omega=math.sqrt(abs(float(eigenvalues[k]))),
            kind=str(kinds[k]),
            shape_q=shape_q[:, k],
            shape_x=shape_x[:, k],
            spring_extension=extension[:, k],
            friction=friction[:, k],
            normal_force=normal[:, k],
        )
        for k in columns.tolist()
    ]


def _clean(values: FloatArray, scale: float, relative: float = 1e-12) -> FloatArray:
    """Set entries below ``relative * scale`` (rounding noise of an exact zero) to 0."""
    values = np.asarray(values, dtype=float)
    return np.where(np.abs(values) <= relative * scale, 0.0, values)


@dataclass(frozen=True)
class _Component:
    """A quantity g(t) = centre + sum_groups Re(amplitude_g exp(i omega_g t)) (+ drift t)."""

    centre: FloatArray
    amplitudes: np.ndarray  # (groups, ...) complex
    drift: FloatArray

    @property
    def amplitude(self) -> FloatArray:
        """Supremum over time of |g - centre| (exact for one frequency; for several, the
        supremum over all phases, approached arbitrarily closely by incommensurate motion)."""
        result: FloatArray = np.sum(np.abs(self.amplitudes), axis=0)
        return result


def _response(
    arrays: SystemArrays,
    q_eq: FloatArray,
    eigenvalues: FloatArray,
    vectors: FloatArray,
    kinds: np.ndarray,
    d_friction: Any,
    d_normal: Any,
    friction_eq: FloatArray,
    normal_eq: FloatArray,
    lever: _Levers,
    weights: FloatArray | None,
    *,
    vectorised: bool = False,
) -> dict[str, Any]:
    r"""Modal superposition of the free response from q(0) = 0, qdot(0) = v0/s.

    With :math:`u = q - q^*`, :math:`\eta_n = v_n^T M u`: an oscillating mode gives
    :math:`\eta_n(t) = \mathrm{Re}[(\eta_{n0} - i\dot\eta_{n0}/\omega_n) e^{i\omega_n t}]`, a
    zero mode :math:`\eta_{n0} + \dot\eta_{n0} t`.
    """
    mass = arrays.inertia
    u0 = -q_eq
    udot0 = arrays.v0 / arrays.scale
    eta0 = vectors.T @ (mass * u0)
    etadot0 = vectors.T @ (mass * udot0)
    oscillating = [k for k, kind in enumerate(kinds) if kind == "oscillating"]
    zero = [k for k, kind in enumerate(kinds) if kind == "zero"]
    omegas = np.sqrt(eigenvalues[oscillating])
    complex_amp = eta0[oscillating] - 1j * etadot0[oscillating] / omegas
    groups = _frequency_groups(omegas)

    def component(per_mode: Any, centre_eq: FloatArray | float) -> _Component:
        """per_mode: (..., n_modes) coefficient of each M-normalised mode in the quantity."""
        per_mode = np.asarray(per_mode)
        centre = centre_eq + per_mode[..., zero] @ eta0[zero]
        drift = per_mode[..., zero] @ etadot0[zero]
        osc = per_mode[..., oscillating] * complex_amp
        if not groups:
            amps = np.zeros((0, *per_mode.shape[:-1]), dtype=complex)
        elif vectorised and len(groups) == osc.shape[-1]:  # every frequency its own group
            amps = np.moveaxis(osc, -1, 0)
        elif vectorised:  # groups are runs of consecutive modes: one reduceat
            starts = np.array([g[0] for g in groups])
            amps = np.moveaxis(np.add.reduceat(osc, starts, axis=-1), -1, 0)
        else:
            amps = np.array([osc[..., g].sum(axis=-1) for g in groups])
        return _Component(np.asarray(centre, dtype=float), amps, np.asarray(drift, dtype=float))

    x_modes = arrays.scale[:, None] * vectors
    x_eq = arrays.x0 + arrays.scale * q_eq
    position = component(x_modes, x_eq)
    cm = component(
        arrays.mass @ x_modes / arrays.mass.sum(), float(arrays.mass @ x_eq / arrays.mass.sum())
    )
    friction = component(d_friction @ vectors, friction_eq)
    normal = component(d_normal @ vectors, normal_eq)
    length_scale = float(np.max(position.amplitude, initial=0.0))
    # rounding noise of an exact zero: relative to the largest force change the motion brings
    extension = np.abs(lever @ vectors[:, oscillating]) @ np.abs(complex_amp)  # per spring
    force_scale = float(np.max(arrays.stiffness * extension, initial=0.0))
    friction_amplitude = _clean(friction.amplitude, force_scale)
    friction = _Component(_clean(friction.centre, force_scale), friction.amplitudes, friction.drift)
    required = _required_mu(arrays, friction, normal)
    required[(friction_amplitude == 0.0) & (friction.centre == 0.0)] = 0.0
    result: dict[str, Any] = {
        "amplitude": position.amplitude,
        # d/dt multiplies each frequency group's complex amplitude by i omega
        "velocity_amplitude": np.sum(
            np.abs(position.amplitudes) * omegas[[g[0] for g in groups]][:, None], axis=0
        )
        if groups
        else np.zeros(arrays.n_bodies),
        "drift_velocity": _clean(position.drift, float(np.max(np.abs(arrays.v0), initial=0.0))),
        "cm_amplitude": float(_clean(cm.amplitude, length_scale)),
        "friction_amplitude": friction_amplitude,
        "normal_force_range": np.stack(
            [normal.centre - normal.amplitude, normal.centre + normal.amplitude], axis=-1
        ),
        "required_mu": required,
        "stationary_amplitude": None,
    }
    if weights is not None:
        xhat = component(weights @ x_modes, float(weights @ x_eq))
        result["stationary_amplitude"] = float(_clean(xhat.amplitude, length_scale))
    return result


def _frequency_groups(omegas: FloatArray) -> list[list[int]]:
    groups: list[list[int]] = []
    for k, omega in enumerate(omegas):
        if groups and abs(omega - omegas[groups[-1][0]]) <= _SAME_FREQUENCY * omega:
            groups[-1].append(k)
        else:
            groups.append([k])
    return groups


def _required_mu(arrays: SystemArrays, friction: _Component, normal: _Component) -> FloatArray:
    r"""max over the motion of :math:`|f_i|/N_i` per body (inf if :math:`N_i` can reach 0;
    0 for a slider), exactly: :func:`friction_ratio_sup` of every body at once."""
    a_f, a_n = friction.amplitudes, normal.amplitudes  # (groups, n) complex
    reach = normal.centre - np.sum(np.abs(a_n), axis=0)  # the smallest N the motion reaches
    rolls = arrays.rolls > 0
    lift = rolls & (reach <= 0)
    safe = rolls & ~lift
    out = np.zeros(arrays.n_bodies)
    out[lift] = math.inf
    if np.any(safe):
        out[safe] = friction_ratio_sup(
            friction.centre[safe], a_f[:, safe], normal.centre[safe], a_n[:, safe]
        )
    return out


def friction_ratio_sup(
    f_c: FloatArray, a_f: np.ndarray, n_c: FloatArray, a_n: np.ndarray
) -> FloatArray:
    r"""The supremum over the phases :math:`	heta_g` of

    .. math:: rac{|f|}{N},\qquad f = f_c + \mathrm{Re}\sum_g a_g e^{i	heta_g},\quad
              N = N_c + \mathrm{Re}\sum_g b_g e^{i	heta_g} > 0,

    for arrays of bodies (``f_c``, ``n_c`` (m,); ``a_f``, ``a_n`` (groups, m) complex);
    docs/physics.md (M20).
    Independent phases are what incommensurate frequency groups sweep (the supremum is
    approached arbitrarily closely); one group's one phase is the same problem. It is exact:
    :math:`\sup f/N \ge r` iff some phases make :math:`f - rN \ge 0`, and the phases maximise
    :math:`f - rN` term by term, so :math:`\sup f/N` is the largest root of the convex

    .. math:: h(r) = f_c - r N_c + \sum_g |a_g - r b_g|

    (it goes to :math:`-\infty` because :math:`N_c > \sum_g |b_g|`, so, convex, it decreases
    everywhere and has one root), and likewise :math:`\sup(-f)/N` with :math:`-f_c, -a_g`.
    Newton's method from the bound :math:`r_0 = (|f_c| + \sum|a_g|)/(N_c - \sum|b_g|)`
    (:math:`h(r_0) \le 0`): its first step lands left of the root (the tangent of a convex
    function lies below it), and from there it climbs to the root monotonically. A few
    vectorised steps; no search.
    """
    f_c = np.asarray(f_c, dtype=float)
    n_c = np.asarray(n_c, dtype=float)
    reach = n_c - np.sum(np.abs(a_n), axis=0)
    best = (np.abs(f_c) + np.sum(np.abs(a_f), axis=0)) / reach  # exact where N is constant
    varying = np.flatnonzero(np.any(a_n != 0, axis=0))
    if varying.size:
        f_v, n_v, a_v, b_v = f_c[varying], n_c[varying], a_f[:, varying], a_n[:, varying]
        start = best[varying]
        found = np.zeros(varying.size)
        for sign in (1.0, -1.0):
            r = start.copy()
            active = np.arange(varying.size)  # the bodies still moving
            for _ in range(100):
                d = sign * a_v[:, active] - r[active] * b_v[:, active]
                size = np.abs(d)
                h = sign * f_v[active] - r[active] * n_v[active] + np.sum(size, axis=0)
                with np.errstate(divide="ignore", invalid="ignore"):
                    turn = np.where(size > 0, -np.real(np.conj(d) * b_v[:, active]) / size, 0.0)
                slope = -n_v[active] + np.sum(turn, axis=0)
                step = np.where(slope < 0, h / slope, 0.0)
                r[active] -= step
                active = active[np.abs(step) > 4e-16 * np.abs(r[active])]
                if not active.size:
                    break
            found = np.maximum(found, r)
        best[varying] = found
    result: FloatArray = best
    return result


def _tilt_deg(vector: FloatArray) -> FloatArray:
    """Angle of each spring line above the horizontal, from its first end to its second, in
    (-90, 90] degrees."""
    angle = np.degrees(np.arctan2(vector[..., 1], vector[..., 0]))
    angle = np.where(angle > 90.0, angle - 180.0, angle)
    angle = np.where(angle <= -90.0, angle + 180.0, angle)
    return np.where(np.abs(angle) < 1e-10, 0.0, angle)


def _spring_split(arrays: SystemArrays, lever: FloatArray) -> dict[str, Any] | None:
    r"""For two bodies joined by one spring: the paper's k1, k2 about the stationary point.

    :math:`\Omega_i^2 = k b_i^2/J_i` (body i alone, the other clamped, paper's Appendix B),
    :math:`\Omega^2 = \Omega_1^2 + \Omega_2^2`; body i's share of the deformation is
    :math:`\sigma_i = \Omega_i^2/\Omega^2` and :math:`k_i = k/\sigma_i`
    (paper eqs. (k1), (k2); :math:`1/k = 1/k_1 + 1/k_2`, eq. (part)). docs/physics.md section 7.1.
    """
    if arrays.n_bodies != 2 or arrays.n_springs != 1 or np.any(arrays.end_body < 0):
        return None
    k = float(arrays.stiffness[0])
    clamped = k * lever[0] ** 2 / arrays.inertia
    total = float(np.sum(clamped))
    if total <= 0 or np.any(clamped <= 0):
        return None
    share = clamped / total
    return {
        "clamped_omega": np.sqrt(clamped),
        "share": share,
        "k": k / share,
        "omega": math.sqrt(total),
    }

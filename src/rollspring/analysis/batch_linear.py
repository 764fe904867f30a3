r"""The linear metrics of many runs of one system at once: :func:`batch_linear`.

A sweep stores, per run, three numbers of :func:`rollspring.analyze`: the modal frequencies,
the stationary weights (PHYSICS.md (M14)) and the linear response's ``required_mu`` (max
:math:`|f|/N`). :func:`batch_linear` computes them for arrays of runs (the batch paths of
:func:`rollspring.simulate_batch`: masses, radii, positions, velocities, stiffnesses, rest
lengths, gravity), and says for which runs it could (``handled``); the other runs are left to
:func:`~rollspring.analysis.analyze`, one by one. What depends on the masses, radii and
stiffnesses alone (the modes: a batched eigensolver) is computed once per distinct
configuration with array operations; the rest, a few dozen numbers a run, by a compiled loop
over the runs (:func:`_respond`, Numba), about a third of the CPU time of the same arithmetic as
array operations over the runs.

**Which runs.** The *flat centre class*: every spring end is a body's centre or an anchor,
every external force acts at a body's centre, and in the run's initial placement both ends of
every spring are at the same height. Rolling keeps centre heights, so every spring stays
horizontal; its length is :math:`|d|`, :math:`d = d_0 + \sum_i\sigma_{si}s_iq_i` (affine in
``q`` while the ends keep their order), the lever arms :math:`b_{si} = e_s\sigma_{si}s_i`
(:math:`e_s = \pm1`) are constant, the geometric stiffness :math:`T_sH_s` (M13) and the
change of the normal forces vanish exactly, and :math:`K = \sum_s k_s b_sb_s^T` (M12) does
not depend on ``q``. Then:

* the equilibrium with the zero modes held is one Newton step from the placement,
  :math:`q^* = \sum_{\lambda_n\ne0} v_n (v_n^TQ_0)/\lambda_n` (what
  :func:`~rollspring.analysis.find_equilibrium` converges to: :math:`V_0^TMq^* = 0`);
* the modes are a batched ``numpy.linalg.eigh`` of :math:`M^{-1/2}KM^{-1/2}` (computed once
  per distinct mass, radius and stiffness), zero modes as :func:`normal_modes` classifies them;
* :math:`N_i` is constant over the motion, so the maximum over the phases of
  :math:`|f_c + \mathrm{Re}\sum_g a_g e^{i\theta_g}|/N` that ``analyze`` searches for is
  :math:`(|f_c| + \sum_g|a_g|)/N` in closed form (frequency groups :math:`g` as ``analyze``
  forms them).

A run is *not* handled (left to ``analyze``) when the system is outside the class, a spring is
tilted in the run's placement or its ends would cross or meet at the equilibrium (length at
most :math:`10^{-9}` of the initial one), the affine Newton
step leaves a residual above :math:`10^{-11}` of the initial one (a net force along a zero
mode: no equilibrium), or an eigenvalue is negative or between :math:`10^{-13}` and
:math:`10^{-4}` of the largest (near the zero-mode threshold, or so ill-conditioned that two
correct computations differ by more than :math:`10^{-12}`). Handled runs agree with
``analyze`` to about :math:`10^{-13}` relative (tests/test_batch_linear.py).

The result of a run depends on that run's values only (never on the other runs of the call).
"""

from __future__ import annotations

import functools
from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import ArrayLike

from rollspring.analysis.linear import _SAME_FREQUENCY, ZERO_MODE_TOLERANCE
from rollspring.model import System
from rollspring.physics import system_arrays
from rollspring.physics.arrays import FloatArray

__all__ = ["BatchLinear", "batch_linear", "flat_centre_class"]

#: A handled run's eigenvalues are each below ``_ZERO * largest`` (a zero mode) or above
#: ``_CONDITION * largest``; anything between goes to ``analyze``.
_ZERO = 1e-13
_CONDITION = 1e-4
#: The affine equilibrium's residual, relative to the initial one, above which a run goes to
#: ``analyze`` (which finds no equilibrium when it is beyond 1e-9 of its force scale).
_RESIDUAL = 1e-11
#: A spring whose length at the equilibrium is at most this part of its initial length goes to
#: ``analyze``: its ends meet there (a rest length of 0), where the sign of d is rounding's.
_MEET = 1e-9
_BODY = ("mass", "radius", "x", "v", "mu_static", "mu_kinetic")


@dataclass(frozen=True)
class BatchLinear:
    """Linear metrics of each run (rows), as :func:`rollspring.analyze` gives them:
    ``omega`` (runs, modes) rad/s, sorted, zero modes exactly 0; ``stationary_weight``
    (runs, bodies), NaN without a single zero mode of non-zero total weight;
    ``required_mu`` (runs, bodies). Rows where ``handled`` is False are NaN: those runs need
    ``analyze``. ``reason`` says why no run at all is handled ('' otherwise)."""

    omega: FloatArray
    stationary_weight: FloatArray
    required_mu: FloatArray
    handled: np.ndarray
    reason: str = ""


def flat_centre_class(system: System) -> str:
    """'' when the system's topology is in the flat centre class (every spring end at a body's
    centre or an anchor, every force at a centre), else why not."""
    for k, spring in enumerate(system.springs):
        for end, at in zip(spring.ends, spring.attachments, strict=True):
            if end in system.body_map and not at.is_centre_form:
                return f"springs[{k}] is attached off a centre"
    for j, force in enumerate(system.forces):
        if not force.at.is_centre_form:
            return f"forces[{j}] acts off a centre"
    if not system.springs:
        return "no springs"
    return ""


def _per_run(
    system: System, parameters: Mapping[str, ArrayLike], n_runs: int | None
) -> tuple[int, dict[str, FloatArray]]:
    """Every per-run number of the class, (runs, n) or (runs, S) or (runs,)."""
    values = {key: np.atleast_1d(np.asarray(v, dtype=np.float64)) for key, v in parameters.items()}
    sizes = {v.size for v in values.values() if v.size != 1}
    if len(sizes) > 1:
        raise ValueError(f"parameters: arrays of different lengths {sorted(sizes)}")
    count = n_runs if n_runs is not None else (sizes.pop() if sizes else 1)
    index = {b.id: i for i, b in enumerate(system.bodies)}
    out = {
        "mass": np.array([b.mass for b in system.bodies]),
        "radius": np.array([b.radius for b in system.bodies]),
        "x": np.array([b.x for b in system.bodies]),
        "v": np.array([b.v for b in system.bodies]),
        "stiffness": np.array([s.stiffness for s in system.springs]),
        "rest_length": np.array(
            [np.nan if s.rest_length is None else s.rest_length for s in system.springs]
        ),
        "gravity": np.array(float(system.gravity)),
    }
    out = {k: np.broadcast_to(v, (count, *v.shape)).copy() for k, v in out.items()}
    for key, value in values.items():
        parts = key.split(".")
        value = np.broadcast_to(value, (count,)) if value.size == 1 else value
        if parts == ["gravity"]:
            out["gravity"][:] = value
        elif len(parts) == 3 and parts[0] == "bodies" and parts[1] in index and parts[2] in _BODY:
            if parts[2] in out:
                out[parts[2]][:, index[parts[1]]] = value
        elif (
            len(parts) == 3
            and parts[0] == "springs"
            and parts[1].isdigit()
            and int(parts[1]) < len(system.springs)
            and parts[2] in ("stiffness", "rest_length")
        ):
            out[parts[2]][:, int(parts[1])] = value
        else:
            raise ValueError(f"parameters[{key!r}]: not a batch path of this system")
    return count, out


def _unique_rows(columns: FloatArray) -> tuple[np.ndarray, np.ndarray]:
    """(a row index of each distinct row, the distinct row of each row), comparing only the
    columns that vary."""
    if columns.shape[0] == 0:
        return np.zeros(0, dtype=np.int64), np.zeros(0, dtype=np.int64)
    varying = np.flatnonzero(np.any(columns != columns[:1], axis=0))
    if varying.size == 0:
        return np.zeros(1, dtype=np.int64), np.zeros(columns.shape[0], dtype=np.int64)
    if varying.size == 1:
        _, first, inverse = np.unique(
            columns[:, varying[0]], return_index=True, return_inverse=True
        )
    else:
        _, first, inverse = np.unique(
            columns[:, varying], axis=0, return_index=True, return_inverse=True
        )
    return first, inverse.reshape(-1)


def _clean(values: FloatArray, scale: FloatArray, relative: float = 1e-12) -> FloatArray:
    """As analyze's: entries below ``relative * scale`` (per run) set to 0."""
    return np.where(np.abs(values) <= relative * scale, 0.0, values)


def batch_linear(
    system: System, parameters: Mapping[str, ArrayLike], *, n_runs: int | None = None
) -> BatchLinear:
    """The linear metrics of each run of ``system`` with ``parameters`` (batch paths -> arrays,
    broadcast to one run count; friction coefficients are accepted and do not enter), for the
    runs of the flat centre class (see the module); ``handled`` marks them."""
    count, p = _per_run(system, parameters, n_runs)
    n = len(system.bodies)
    nan = np.full((count, n), np.nan)
    reason = flat_centre_class(system)
    if reason:
        return BatchLinear(nan, nan.copy(), nan.copy(), np.zeros(count, dtype=bool), reason)
    arrays = system_arrays(system)
    rolls = arrays.rolls > 0
    sigma = arrays.incidence[:, 1, :] - arrays.incidence[:, 0, :]  # (S, n): +1 end b, -1 end a
    anchor = arrays.end_body < 0  # (S, 2)
    body = np.where(anchor, 0, arrays.end_body)
    external = np.zeros((2, n))
    for force, at_body in zip(arrays.force, arrays.force_body, strict=True):
        external[:, at_body] += force
    with np.errstate(all="ignore"):
        # --- per distinct (masses, radii, stiffnesses): everything that does not depend on
        # the placement, the velocities or gravity (the sign e_s of a spring enters K, the
        # friction change and |b.v| squared or in absolute value only)
        first, which = _unique_rows(
            np.concatenate([p["mass"], p["radius"], p["stiffness"]], axis=1)
        )
        m, radius, k = p["mass"][first], p["radius"][first], p["stiffness"][first]
        s = np.where(rolls, radius, 1.0)
        inertia = np.where(rolls, (1.0 + arrays.gamma) * m * radius**2, m)
        unsigned = sigma * s[:, None, :]  # |b_si| pattern, (U, S, n)
        stiffness = np.einsum("us,usi,usj->uij", k, unsigned, unsigned)  # sum k b b^T (M12)
        root = np.sqrt(inertia)
        scaled = stiffness / root[:, :, None] / root[:, None, :]
        scaled = 0.5 * (scaled + np.swapaxes(scaled, 1, 2))
        finite = np.all(np.isfinite(scaled), axis=(1, 2)) & np.all(np.isfinite(k), axis=1)
        scaled[~finite] = 0.0
        lam, vec = np.linalg.eigh(scaled)
        largest = np.max(np.abs(lam), axis=1, keepdims=True)
        zero = np.abs(lam) < ZERO_MODE_TOLERANCE * largest
        clear = (
            finite
            & (largest[:, 0] > 0)
            & np.all((np.abs(lam) < _ZERO * largest) | (lam >= _CONDITION * largest), axis=1)
        )
        lam = np.where(zero, 0.0, lam)
        order = np.argsort(lam, axis=1, kind="stable")
        lam = np.take_along_axis(lam, order, axis=1)
        zero = np.take_along_axis(zero, order, axis=1)
        vec = np.take_along_axis(vec, order[:, None, :], axis=2) / root[:, :, None]
        osc = ~zero
        omega_osc = np.sqrt(np.where(osc, lam, 1.0))
        # the equilibrium step q* = sum_{lambda != 0} v v^T Q0 / lambda, as a matrix
        newton = np.einsum(
            "uin,un,ujn->uij", vec, np.where(osc, 1.0 / np.where(osc, lam, 1.0), 0.0), vec
        )
        # friction change per unit of each mode (contact_forces_jacobian): -(m s/J) K - dF_x
        # with dF_x = -sum_s k e sigma b^T = -K / s for centre springs (e^2 = 1)
        d_force_x = -np.einsum("us,si,usj->uij", k, sigma, unsigned)
        d_friction = -(m * s / inertia)[:, :, None] * stiffness - d_force_x
        d_friction = np.where(rolls[None, :, None], d_friction, 0.0)
        per_mode = d_friction @ vec  # (U, bodies, modes)
        lever_mode = np.abs(unsigned @ vec)  # |b_s . v_n|, (U, S, modes)
        # frequency groups, as analyze's _frequency_groups over the oscillating modes
        group = np.full((first.size, n), -1)
        current = np.full(first.size, -1)
        start = np.zeros(first.size)
        for j in range(n):
            same = (current >= 0) & (
                np.abs(omega_osc[:, j] - start) <= _SAME_FREQUENCY * omega_osc[:, j]
            )
            new = osc[:, j] & ~same
            current = np.where(new, current + 1, current)
            start = np.where(new, omega_osc[:, j], start)
            group[:, j] = np.where(osc[:, j], current, -1)
        n_groups = int(current.max(initial=-1)) + 1
        omega = np.sqrt(np.abs(lam))
        # stationary weights from the single zero mode (M14), as stationary_weights
        single = np.sum(zero, axis=1) == 1
        raw = inertia * np.einsum("uin,un->ui", vec, np.where(zero, 1.0, 0.0)) / s
        total = np.sum(raw, axis=1, keepdims=True)
        weighted = single & (np.abs(total[:, 0]) > 1e-9 * np.sum(np.abs(raw), axis=1))
        weights = raw / np.where(total != 0, total, 1.0)
        weights = np.where(np.abs(weights) < 1e-15, 0.0, weights)
        weights = np.where(weighted[:, None], weights, np.nan)

        # --- per run: the placement, the equilibrium, the response to the initial state
        # (compiled: a few dozen numbers a run, where array operations over the runs cost
        # ten times the arithmetic in temporaries and gathers)
        omega_run, weights_run, required = np.full((3, count, n), np.nan)
        ok = np.zeros(count, dtype=np.bool_)
        _compiled()(
            which.astype(np.int64),
            clear,
            m,
            s,
            inertia,
            k,
            newton,
            vec,
            osc,
            zero,
            omega_osc,
            per_mode,
            lever_mode,
            group,
            n_groups,
            omega,
            weights,
            p["x"],
            p["v"],
            p["radius"],
            p["rest_length"],
            p["gravity"],
            anchor,
            np.ascontiguousarray(arrays.end_anchor, dtype=np.float64),
            body.astype(np.int64),
            np.asarray(arrays.track, dtype=np.float64),
            np.ascontiguousarray(sigma, dtype=np.float64),
            external,
            rolls,
            omega_run,
            weights_run,
            required,
            ok,
        )
    return BatchLinear(omega_run, weights_run, required, ok)


def _pulls(
    d: FloatArray,
    rest: FloatArray,
    k: FloatArray,
    sigma: FloatArray,
    external: FloatArray,
    s: FloatArray,
    u: int,
    force_x: FloatArray,
    force_q: FloatArray,
) -> None:
    r"""The horizontal applied force on each body and its generalised force for the level
    spring vectors ``d`` (into ``force_x``, ``force_q``): the pull :math:`T_se_s` on end a,
    :math:`T_s = k_s(|d_s| - L_s)`, so :math:`F_{x,i} = -\sum_s T_se_s\sigma_{si} + F_i`, and
    :math:`Q_i = s_iF_{x,i}` (M7) for centre attachments (:math:`b_{si} = e_s\sigma_{si}s_i`)."""
    for i in range(force_x.size):
        force_x[i] = 0.0
    for spring in range(d.size):
        pull = k[u, spring] * (abs(d[spring]) - rest[spring]) * np.sign(d[spring])
        for i in range(force_x.size):
            force_x[i] -= pull * sigma[spring, i]
    for i in range(force_x.size):
        force_x[i] += external[0, i]
        force_q[i] = s[u, i] * force_x[i]


def _respond(
    which: np.ndarray,
    clear: np.ndarray,
    m: FloatArray,
    s: FloatArray,
    inertia: FloatArray,
    k: FloatArray,
    newton: FloatArray,
    vec: FloatArray,
    osc: np.ndarray,
    zero: np.ndarray,
    omega_osc: FloatArray,
    per_mode: FloatArray,
    lever_mode: FloatArray,
    group: np.ndarray,
    n_groups: int,
    omega: FloatArray,
    weights: FloatArray,
    x: FloatArray,
    v: FloatArray,
    radius: FloatArray,
    rest_length: FloatArray,
    gravity: FloatArray,
    anchor: np.ndarray,
    end_anchor: FloatArray,
    end_body: np.ndarray,
    track: FloatArray,
    sigma: FloatArray,
    external: FloatArray,
    rolls: np.ndarray,
    omega_run: FloatArray,
    weights_run: FloatArray,
    required: FloatArray,
    ok: np.ndarray,
) -> None:
    r"""Each run's metrics (into ``omega_run``, ``weights_run``, ``required``, ``ok``; the
    rows of the runs not handled are left as they are) from the quantities of its distinct
    configuration ``which[r]`` (modes :math:`v_n` with :math:`v^TMv = 1`, the equilibrium step,
    the friction per unit of each mode, the springs' lever per mode, the frequency groups).

    The placement gives the spring vectors :math:`d_0` (level: both ends at one height, else
    the run is not handled); the equilibrium is :math:`q^* = \sum_{\lambda_n\ne0}
    v_nv_n^TQ(d_0)/\lambda_n`, kept when the ends keep their order and :math:`|Q(q^*)|_{M^{-1}}
    \le 10^{-11}|Q(d_0)|_{M^{-1}}`. At :math:`q^*` the friction is
    :math:`f^* = m s\,Q/J - F_x` (M8) and the normal force :math:`N = mg - F_y` (M9). The free
    response from :math:`q(0) = 0`, :math:`\dot q(0) = v_0/s` has modal amplitudes
    :math:`a_n = \eta_n - i\dot\eta_n/\omega_n`, :math:`\eta_n = v_n^TM(-q^*)`,
    :math:`\dot\eta_n = v_n^TM\dot q(0)`, so the friction is
    :math:`f_c + \mathrm{Re}\sum_g A_g e^{i\theta_g}` with :math:`f_c = f^* + \sum_{\lambda_n=0}
    (\partial f/\partial\eta_n)\eta_n` and :math:`A_g = \sum_{n\in g}(\partial f/\partial
    \eta_n)a_n`, whose largest magnitude over the phases is :math:`|f_c| + \sum_g|A_g|`; the
    required coefficient is that over :math:`N` (0 when both vanish below :math:`10^{-12}` of
    the largest spring force amplitude :math:`\max_s k_s\sum_n|b_s\cdot v_n||a_n|`; infinite
    when :math:`N \le 0`; 0 for a sliding body)."""
    n = m.shape[1]
    springs = k.shape[1]
    modes = vec.shape[2]
    d0 = np.empty(springs)
    d_eq = np.empty(springs)
    rest = np.empty(springs)
    q0_force = np.empty(n)
    q_force = np.empty(n)
    force_x = np.empty(n)
    q_eq = np.empty(n)
    friction_eq = np.empty(n)
    centre = np.empty(n)
    real = np.empty(modes)
    imag = np.empty(modes)
    ends_x = np.empty(2)
    ends_y = np.empty(2)
    for r in range(which.size):
        u = which[r]
        good = clear[u] and np.isfinite(gravity[r])
        for i in range(n):
            good = good and np.isfinite(v[r, i])
        for spring in range(springs):
            for end in range(2):
                at = end_body[spring, end]
                if anchor[spring, end]:
                    ends_x[end] = end_anchor[spring, end, 0]
                    ends_y[end] = end_anchor[spring, end, 1]
                else:
                    ends_x[end] = x[r, at]
                    ends_y[end] = track[at] + radius[r, at]
            d0[spring] = ends_x[1] - ends_x[0]
            length0 = abs(d0[spring])
            rest[spring] = length0 if np.isnan(rest_length[r, spring]) else rest_length[r, spring]
            good = (
                good
                and ends_y[0] == ends_y[1]
                and length0 > 0
                and np.isfinite(d0[spring])
                and np.isfinite(rest[spring])
            )
        if not good:
            continue
        _pulls(d0, rest, k, sigma, external, s, u, force_x, q0_force)
        initial = 0.0
        for i in range(n):
            q_eq[i] = 0.0
            for j in range(n):
                q_eq[i] += newton[u, i, j] * q0_force[j]
            initial += q0_force[i] ** 2 / inertia[u, i]
        for spring in range(springs):
            step = 0.0
            for i in range(n):
                step += s[u, i] * q_eq[i] * sigma[spring, i]
            d_eq[spring] = d0[spring] + step
            good = (
                good
                and np.sign(d_eq[spring]) == np.sign(d0[spring])
                and abs(d_eq[spring]) > _MEET * abs(d0[spring])
            )
        _pulls(d_eq, rest, k, sigma, external, s, u, force_x, q_force)
        residual = 0.0
        for i in range(n):
            residual += q_force[i] ** 2 / inertia[u, i]
        if not (good and residual <= _RESIDUAL**2 * initial):
            continue
        ok[r] = True
        for i in range(n):
            omega_run[r, i] = omega[u, i]
            weights_run[r, i] = weights[u, i]
        contact_scale = np.sum(m[u]) * max(gravity[r], 1.0) + np.sum(k[u])
        for i in range(n):
            friction = m[u, i] * s[u, i] * (q_force[i] / inertia[u, i]) - force_x[i]
            if not rolls[i] or abs(friction) < 1e-12 * contact_scale:
                friction = 0.0
            friction_eq[i] = friction
        for mode in range(modes):
            eta0 = 0.0
            rate = 0.0
            for i in range(n):
                eta0 += vec[u, i, mode] * (inertia[u, i] * -q_eq[i])
                rate += vec[u, i, mode] * (inertia[u, i] * (v[r, i] / s[u, i]))
            real[mode] = eta0 if osc[u, mode] else 0.0
            imag[mode] = rate / omega_osc[u, mode] if osc[u, mode] else 0.0
            if zero[u, mode]:
                for i in range(n):
                    friction_eq[i] += per_mode[u, i, mode] * eta0
        force_scale = 0.0
        for spring in range(springs):
            extension = 0.0
            for mode in range(modes):
                extension += lever_mode[u, spring, mode] * np.hypot(real[mode], imag[mode])
            force_scale = max(force_scale, k[u, spring] * extension)
        for i in range(n):
            centre[i] = friction_eq[i]
            amplitude = 0.0
            for g in range(n_groups):
                a = 0.0
                b = 0.0
                for mode in range(modes):
                    if group[u, mode] == g:
                        a += per_mode[u, i, mode] * real[mode]
                        b += per_mode[u, i, mode] * imag[mode]
                amplitude += np.hypot(a, b)
            if abs(centre[i]) <= 1e-12 * force_scale:
                centre[i] = 0.0
            normal = m[u, i] * gravity[r] - external[1, i]
            if not rolls[i] or (amplitude <= 1e-12 * force_scale and centre[i] == 0.0):
                required[r, i] = 0.0
            elif normal > 0:
                required[r, i] = (abs(centre[i]) + amplitude) / normal
            else:
                required[r, i] = np.inf


@functools.cache
def _compiled() -> Any:
    """:func:`_respond` compiled (Numba, no GIL; on disk once), with :func:`_pulls`, which it
    calls, compiled first: on first use, so that importing the package does not import Numba
    (``rollspring analyze`` starts without it)."""
    from numba import njit

    globals()["_pulls"] = njit(cache=True, error_model="numpy")(_pulls)
    return njit(cache=True, error_model="numpy", nogil=True)(_respond)

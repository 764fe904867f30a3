r"""The linear metrics of many runs of one system at once: :func:`batch_linear`.

A sweep stores, per run, three numbers of :func:`rollspring.analyze`: the modal frequencies,
the stationary weights (PHYSICS.md (M14)) and the linear response's ``required_mu`` (max
:math:`|f|/N`). :func:`batch_linear` computes them for arrays of runs (the batch paths of
:func:`rollspring.simulate_batch`: masses, radii, positions, velocities, stiffnesses, rest
lengths, gravity) with array operations over the runs, and says for which runs it could
(``handled``); the other runs are left to :func:`~rollspring.analysis.analyze`, one by one.

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
tilted in the run's placement or its ends would cross at the equilibrium, the affine Newton
step leaves a residual above :math:`10^{-11}` of the initial one (a net force along a zero
mode: no equilibrium), or an eigenvalue is negative or between :math:`10^{-13}` and
:math:`10^{-4}` of the largest (near the zero-mode threshold, or so ill-conditioned that two
correct computations differ by more than :math:`10^{-12}`). Handled runs agree with
``analyze`` to about :math:`10^{-13}` relative (tests/test_batch_linear.py).

The result of a run depends on that run's values only (never on the other runs of the call).
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass

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
        m, s, inertia, k = m[which], s[which], inertia[which], k[which]
        end_x = np.where(anchor, arrays.end_anchor[..., 0], p["x"][:, body])  # (R, S, 2)
        end_y = np.where(
            anchor, arrays.end_anchor[..., 1], (arrays.track + p["radius"])[:, body] + 0.0
        )
        d0 = end_x[..., 1] - end_x[..., 0]
        length0 = np.abs(d0)
        rest = np.where(np.isnan(p["rest_length"]), length0, p["rest_length"])
        e0 = np.sign(d0)
        ok = clear[which] & np.all(
            (end_y[..., 0] == end_y[..., 1]) & (length0 > 0) & np.isfinite(d0) & np.isfinite(rest),
            axis=1,
        )
        ok &= np.all(np.isfinite(p["v"]), axis=1) & np.isfinite(p["gravity"])

        def forces_at(d: FloatArray) -> tuple[FloatArray, FloatArray]:
            """(generalised forces Q, horizontal applied force F_x on each body) for spring
            vectors d: F_x = -sum T e sigma + F (the pull T e on end a), Q = s F_x (M7) for
            centre attachments (b = e sigma s)."""
            force_x = (k * (np.abs(d) - rest) * np.sign(d)) @ -sigma + external[0]
            return s * force_x, force_x

        q0_force, _ = forces_at(d0)
        q_eq = np.einsum("rij,rj->ri", newton[which], q0_force)
        d_eq = d0 + (s * q_eq) @ sigma.T
        ok &= np.all(np.sign(d_eq) == e0, axis=1)
        q_force, force_x = forces_at(d_eq)
        residual = np.sum(q_force**2 / inertia, axis=1)
        ok &= residual <= _RESIDUAL**2 * np.sum(q0_force**2 / inertia, axis=1)

        # the forces at the equilibrium (M8), (M9)
        contact_scale = (
            np.sum(m, axis=1) * np.maximum(p["gravity"], 1.0) + np.sum(k, axis=1) * 1.0
        )[:, None]
        friction_eq = np.where(rolls, m * s * (q_force / inertia) - force_x, 0.0)
        friction_eq = np.where(np.abs(friction_eq) < 1e-12 * contact_scale, 0.0, friction_eq)
        normal_eq = m * p["gravity"][:, None] - external[1]

        # the free response from q(0) = 0, qdot(0) = v0/s by modal superposition (_response)
        vec_r = vec[which]
        eta0 = np.einsum("rin,ri->rn", vec_r, inertia * -q_eq)
        rate = np.einsum("rin,ri->rn", vec_r, inertia * (p["v"] / s)) / omega_osc[which]
        osc_r, zero_r, per_mode_r = osc[which], zero[which], per_mode[which]
        real = np.where(osc_r, eta0, 0.0)  # amplitude_n = eta0_n - i etadot0_n / omega_n
        imag = np.where(osc_r, rate, 0.0)
        centre = friction_eq + np.einsum("rin,rn->ri", per_mode_r, np.where(zero_r, eta0, 0.0))
        friction_sum = np.zeros((count, n))
        group_r = group[which]
        for g in range(n_groups):
            member = group_r == g
            a = np.einsum("rin,rn->ri", per_mode_r, np.where(member, real, 0.0))
            b = np.einsum("rin,rn->ri", per_mode_r, np.where(member, imag, 0.0))
            friction_sum += np.hypot(a, b)
        extension = np.einsum("rsn,rn->rs", lever_mode[which], np.hypot(real, imag))
        force_scale = np.max(k * extension, axis=1, initial=0.0)[:, None]
        friction_amplitude = _clean(friction_sum, force_scale)
        centre = _clean(centre, force_scale)
        required = np.where(
            normal_eq > 0,
            (np.abs(centre) + friction_sum) / np.where(normal_eq > 0, normal_eq, 1.0),
            np.inf,
        )
        required = np.where((friction_amplitude == 0.0) & (centre == 0.0), 0.0, required)
        required = np.where(rolls, required, 0.0)
    keep = ok[:, None]
    return BatchLinear(
        np.where(keep, omega[which], np.nan),
        np.where(keep, weights[which], np.nan),
        np.where(keep, required, np.nan),
        ok,
    )

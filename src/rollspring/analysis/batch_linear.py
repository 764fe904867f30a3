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


def _per_run(system: System, parameters: Mapping[str, ArrayLike], n_runs: int | None
             ) -> tuple[int, dict[str, FloatArray]]:
    """Every per-run number of the class, (runs, n) or (runs, S) or (runs,)."""
    values = {key: np.atleast_1d(np.asarray(v, dtype=np.float64))
              for key, v in parameters.items()}
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
        "rest_length": np.array([np.nan if s.rest_length is None else s.rest_length
                                 for s in system.springs]),
        "gravity": np.array(float(system.gravity)),
    }
    out = {k: np.broadcast_to(v, (count, *v.shape)).copy() for k, v in out.items()}
    for key, value in values.items():
        parts = key.split(".")
        value = np.broadcast_to(value, (count,)) if value.size == 1 else value
        if parts == ["gravity"]:
            out["gravity"][:] = value
        elif len(parts) == 3 and parts[0] == "bodies" and parts[1] in index \
                and parts[2] in _BODY:
            if parts[2] in out:
                out[parts[2]][:, index[parts[1]]] = value
        elif len(parts) == 3 and parts[0] == "springs" and parts[1].isdigit() \
                and int(parts[1]) < len(system.springs) \
                and parts[2] in ("stiffness", "rest_length"):
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
        _, first, inverse = np.unique(columns[:, varying[0]], return_index=True,
                                      return_inverse=True)
    else:
        _, first, inverse = np.unique(columns[:, varying], axis=0, return_index=True,
                                      return_inverse=True)
    return first, inverse.reshape(-1)


def _clean(values: FloatArray, scale: FloatArray, relative: float = 1e-12) -> FloatArray:
    """As analyze's: entries below ``relative * scale`` (per run) set to 0."""
    return np.where(np.abs(values) <= relative * scale, 0.0, values)


def batch_linear(system: System, parameters: Mapping[str, ArrayLike], *,
                 n_runs: int | None = None) -> BatchLinear:
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
    with np.errstate(all="ignore"):
        m, radius, k = p["mass"], p["radius"], p["stiffness"]
        s = np.where(rolls, radius, 1.0)
        inertia = np.where(rolls, (1.0 + arrays.gamma) * m * radius**2, m)
        # the ends in the initial placement (M1) at their centres or anchors
        end_x = np.where(anchor, arrays.end_anchor[..., 0], p["x"][:, body])  # (R, S, 2)
        end_y = np.where(anchor, arrays.end_anchor[..., 1],
                         (arrays.track + radius)[:, body] + 0.0)
        d0 = end_x[..., 1] - end_x[..., 0]
        length0 = np.abs(d0)
        rest = np.where(np.isnan(p["rest_length"]), length0, p["rest_length"])
        e0 = np.sign(d0)
        lever = e0[:, :, None] * sigma * s[:, None, :]  # b_si (R, S, n), constant
        external = np.zeros((2, n))
        for force, at_body in zip(arrays.force, arrays.force_body, strict=True):
            external[:, at_body] += force
        ok = np.all(end_y[..., 0] == end_y[..., 1], axis=1) & np.all(np.isfinite(d0), axis=1)
        ok &= np.all(length0 > 0, axis=1)
        for name in ("mass", "radius", "x", "v", "stiffness"):
            ok &= np.all(np.isfinite(p[name]), axis=1)
        ok &= np.all(np.isfinite(rest), axis=1)
        ok &= np.isfinite(p["gravity"])

        # modes, once per distinct (masses, radii, stiffnesses): K = sum_s k b b^T (M12)
        key = np.concatenate([m, radius, k], axis=1)
        first, which = _unique_rows(key)
        ku, su, ju = k[first], s[first], inertia[first]
        stiffness_u = np.einsum("us,si,sj->uij", ku, sigma, sigma) * su[:, :, None] \
            * su[:, None, :]
        root = np.sqrt(ju)
        scaled = stiffness_u / root[:, :, None] / root[:, None, :]
        scaled = 0.5 * (scaled + np.swapaxes(scaled, 1, 2))
        finite_u = np.all(np.isfinite(scaled), axis=(1, 2))
        scaled[~finite_u] = 0.0
        lam_u, vec_u = np.linalg.eigh(scaled)
        largest = np.max(np.abs(lam_u), axis=1, keepdims=True)
        zero_u = np.abs(lam_u) < ZERO_MODE_TOLERANCE * largest
        clear_u = finite_u & (largest[:, 0] > 0) & np.all(
            (np.abs(lam_u) < _ZERO * largest) | (lam_u >= _CONDITION * largest), axis=1)
        lam_u = np.where(zero_u, 0.0, lam_u)
        order = np.argsort(lam_u, axis=1, kind="stable")
        lam_u = np.take_along_axis(lam_u, order, axis=1)
        zero_u = np.take_along_axis(zero_u, order, axis=1)
        vec_u = np.take_along_axis(vec_u, order[:, None, :], axis=2) / root[:, :, None]
        ok &= clear_u[which]
        lam, vec, zero, stiffness = lam_u[which], vec_u[which], zero_u[which], stiffness_u[which]
        osc = ~zero

        def forces_at(d: FloatArray) -> tuple[FloatArray, FloatArray, FloatArray]:
            """(generalised forces Q, spring x-force on each body, tensions) for spring
            vectors d: Q = -sum T b + F s (M7), the lever b constant in the class."""
            tension = k * (np.abs(d) - rest)
            q_force = -np.einsum("rs,rsi->ri", tension, lever) + external[0] * s
            pull = -np.einsum("rs,si->ri", tension * np.sign(d), sigma)  # T e on end a
            return q_force, pull, tension

        q0_force, _, _ = forces_at(d0)
        # the equilibrium, zero modes held: one Newton step from the placement
        along = np.einsum("rin,ri->rn", vec, q0_force)
        step = np.where(osc, along / np.where(osc, lam, 1.0), 0.0)
        q_eq = np.einsum("rin,rn->ri", vec, step)
        d_eq = d0 + np.einsum("si,ri->rs", sigma, s * q_eq)
        ok &= np.all(np.sign(d_eq) == e0, axis=1)
        q_force, pull, _ = forces_at(d_eq)
        residual = np.sqrt(np.sum(q_force**2 / inertia, axis=1))
        initial = np.sqrt(np.sum(q0_force**2 / inertia, axis=1))
        ok &= residual <= _RESIDUAL * initial

        # the forces at the equilibrium (M8), (M9) and their change (contact_forces_jacobian)
        contact_scale = (np.sum(m, axis=1) * np.maximum(p["gravity"], 1.0)
                         + np.sum(k, axis=1) * 1.0)[:, None]
        friction_eq = m * s * (q_force / inertia) - (pull + external[0])
        friction_eq = np.where(rolls, friction_eq, 0.0)
        friction_eq = np.where(np.abs(friction_eq) < 1e-12 * contact_scale, 0.0, friction_eq)
        normal_eq = m * p["gravity"][:, None] - external[1]
        d_force_x = -np.einsum("rs,si,rsj->rij", k * e0, sigma, lever)
        d_friction = -(m * s / inertia)[:, :, None] * stiffness - d_force_x
        d_friction = np.where(rolls[None, :, None], d_friction, 0.0)

        # the free response from q(0) = 0, qdot(0) = v0/s by modal superposition (_response)
        eta0 = np.einsum("rin,ri->rn", vec, inertia * -q_eq)
        etadot0 = np.einsum("rin,ri->rn", vec, inertia * (p["v"] / s))
        omega_osc = np.sqrt(np.where(osc, lam, 1.0))
        amplitude = np.where(osc, eta0 - 1j * etadot0 / omega_osc, 0.0)
        per_mode = np.einsum("rij,rjn->rin", d_friction, vec)  # friction per mode
        centre = friction_eq + np.einsum("rin,rn->ri", per_mode, np.where(zero, eta0, 0.0))
        terms = per_mode * amplitude[:, None, :]
        # frequency groups, as analyze's _frequency_groups over the oscillating modes
        group = np.full((count, n), -1)
        current = np.full(count, -1)
        start = np.zeros(count)
        for j in range(n):
            same = (current >= 0) & (np.abs(omega_osc[:, j] - start)
                                     <= _SAME_FREQUENCY * omega_osc[:, j])
            new = osc[:, j] & ~same
            current = np.where(new, current + 1, current)
            start = np.where(new, omega_osc[:, j], start)
            group[:, j] = np.where(osc[:, j], current, -1)
        friction_sum = np.zeros((count, n))
        for g in range(n):
            member = (group == g)[:, None, :]
            friction_sum += np.abs(np.sum(np.where(member, terms, 0.0), axis=-1))
        extension = np.einsum("rsn,rn->rs", np.abs(np.einsum("rsi,rin->rsn", lever, vec)),
                              np.abs(amplitude))
        force_scale = np.max(k * extension, axis=1, initial=0.0)[:, None]
        friction_amplitude = _clean(friction_sum, force_scale)
        centre = _clean(centre, force_scale)
        required = np.where(normal_eq > 0, (np.abs(centre) + friction_sum)
                            / np.where(normal_eq > 0, normal_eq, 1.0), np.inf)
        required = np.where((friction_amplitude == 0.0) & (centre == 0.0), 0.0, required)
        required = np.where(rolls, required, 0.0)

        omega = np.sqrt(np.abs(lam))
        # stationary weights from the single zero mode (M14), as stationary_weights
        single = np.sum(zero, axis=1) == 1
        zero_vec = np.einsum("rin,rn->ri", vec, np.where(zero, 1.0, 0.0))
        raw = inertia * zero_vec / s
        total = np.sum(raw, axis=1, keepdims=True)
        weighted = single & (np.abs(total[:, 0]) > 1e-9 * np.sum(np.abs(raw), axis=1))
        weights = raw / np.where(total != 0, total, 1.0)
        weights = np.where(np.abs(weights) < 1e-15, 0.0, weights)
        weights = np.where(weighted[:, None], weights, np.nan)
    handled = ok
    keep = handled[:, None]
    return BatchLinear(np.where(keep, omega, np.nan), np.where(keep, weights, np.nan),
                       np.where(keep, required, np.nan), handled)

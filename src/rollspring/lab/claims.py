r"""The paper's claims measured on a fitted recording of two bodies.

* **The centre of mass moves, X̂ stays put** (paper eq. (c); docs/physics.md (M11), (M14)):
  the peak-to-peak motion over the record of :math:`X_{\rm CM} = \sum m_ix_i/\sum m_i` and of
  :math:`\hat X = \sum w_i x_i` (the weights from
  :func:`rollspring.analysis.linear.stationary_weights`, :math:`w_i \propto (1+\gamma_i)m_i`
  for centre springs), on the fitted model's motion. A
  uniform drift of :math:`\hat X` (a pseudo-momentum :math:`\hat P \ne 0` at the start) counts:
  the value is what the record shows.
* **The frictions' ratio** (paper: 3 : 2 for the hoop and the cylinder; (M17)): the ratio of
  the friction amplitudes of the fitted system's linear response
  (:attr:`rollspring.analysis.LinearAnalysis.friction_amplitude`).
* **Each body rolled** (when angles were measured): the slip
  :math:`s = (x - x_0) - R(\varphi - \varphi_0)` is pure tracking noise when the body rolls; its
  RMS about its mean is compared with the noise of :math:`s`, estimated from its second
  differences (:math:`\sigma^2 = \langle(\Delta^2 s)^2\rangle/6` for white noise): ``rolled``
  when the RMS is at most three times the noise.

The uncertainties are propagated from the fit's covariance :math:`\Sigma` to first order,
:math:`\sigma_g^2 = \nabla g^T\Sigma\nabla g`, the gradient by forward differences of the model.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from rollspring.lab.fit import FitResult
from rollspring.physics import SystemArrays
from rollspring.physics.arrays import FloatArray

__all__ = ["measure_claims", "rolling_check"]


def _weights(arrays: SystemArrays) -> FloatArray | None:
    """X̂'s weights (M14) of the system at the placement, or None (no single zero mode)."""
    from rollspring.analysis.linear import normal_modes, stationary_weights
    from rollspring.physics.mechanics import mass_matrix, stiffness_matrix

    _, vectors, kinds = normal_modes(
        mass_matrix(arrays), np.asarray(stiffness_matrix(arrays, np.zeros(arrays.n_bodies)))
    )
    return stationary_weights(arrays, vectors, kinds)


def _peak_to_peak(result: FitResult, full: FloatArray, times: FloatArray) -> FloatArray:
    """(CM, X̂) peak-to-peak of the model at ``full`` over ``times`` (X̂ NaN without weights)."""
    problem = result.problem
    n = len(problem.ids)
    _, arrays, _ = problem.model(full[: problem.layout.n_paths])
    x = problem.states(full, times)[:, :n]
    cm = x @ arrays.mass / arrays.mass.sum()
    weights = _weights(arrays)
    stationary = x @ weights if weights is not None else np.full(times.size, np.nan)
    return np.array([np.ptp(cm), np.ptp(stationary)])


def _friction_ratio(result: FitResult, full: FloatArray) -> float:
    """Ratio of the two bodies' friction amplitudes in the fitted system's linear response."""
    from rollspring.analysis import analyze
    from rollspring.lab.fit import fitted_system_of

    analysis = analyze(fitted_system_of(result.problem, full), confirm=True)  # two bodies
    amplitude = analysis.friction_amplitude
    if amplitude is None or not amplitude[1] > 0:
        return math.nan
    return float(amplitude[0] / amplitude[1])


def _propagated(
    result: FitResult, values: FloatArray, function: Any, full: FloatArray
) -> FloatArray:
    """First-order standard errors of ``function(full)`` (an array) from the fit's covariance."""
    names = result.problem.layout.names
    fitted = [names.index(name) for name in result.fitted]
    gradient = []
    for index in fitted:
        step = result.problem.step(full, index)
        moved = full.copy()
        moved[index] += step
        gradient.append((np.asarray(function(moved)) - values) / step)
    if not gradient:
        return np.zeros_like(values)
    g = np.stack(gradient, axis=0)  # (p, k)
    covariance = result.covariance
    with np.errstate(invalid="ignore"):
        variance = np.einsum("pk,pq,qk->k", g, np.where(np.isfinite(covariance), covariance, 0), g)
    variance = np.where(np.isfinite(np.diag(covariance)).all(), variance, np.inf)
    return np.sqrt(np.maximum(variance, 0.0))


def measure_claims(result: FitResult) -> dict[str, Any]:
    """The paper's claims measured on the fitted two-body system (the module's docstring):
    ``cm_peak_to_peak``, ``stationary_peak_to_peak`` (m) and ``friction_ratio``, each
    ``{"value", "stderr"}``, and ``rolled`` per body when angles were measured. Empty for a
    system that does not have two bodies."""
    problem = result.problem
    if len(problem.ids) != 2:
        return {}
    full = result.best
    t = problem.t
    times = np.linspace(t[0], t[-1], 4 * t.size)
    values = _peak_to_peak(result, full, times)
    errors = _propagated(result, values, lambda f: _peak_to_peak(result, f, times), full)
    ratio = _friction_ratio(result, full)
    ratio_error = _propagated(
        result, np.array([ratio]), lambda f: np.array([_friction_ratio(result, f)]), full
    )[0]
    claims: dict[str, Any] = {
        "cm_peak_to_peak": _entry(values[0], errors[0]),
        "stationary_peak_to_peak": _entry(values[1], errors[1]),
        "friction_ratio": _entry(ratio, ratio_error),
        "bodies": list(problem.ids),
    }
    rolled = rolling_check(result)
    if rolled:
        claims["rolled"] = rolled
    return claims


def _entry(value: float, stderr: float) -> dict[str, float | None]:
    return {
        "value": float(value) if math.isfinite(value) else None,
        "stderr": float(stderr) if math.isfinite(stderr) else None,
    }


def rolling_check(result: FitResult) -> dict[str, dict[str, Any]]:
    r"""Per body with measured angles: the slip's RMS about its mean, the noise of the slip
    (from its second differences) and ``rolled`` (the RMS at most three times the noise)."""
    data = result.data
    out: dict[str, dict[str, Any]] = {}
    if not data.has_angles:
        return out
    radius = {body.id: body.radius for body in result.system.bodies}
    for column, body in enumerate(data.bodies):
        x, phi = data.x[:, column], data.phi[:, column]
        ok = np.isfinite(x) & np.isfinite(phi)
        if ok.sum() < 8:
            continue
        slip = (x[ok] - x[ok][0]) - radius[body] * (phi[ok] - phi[ok][0])
        spread = float(np.sqrt(np.mean((slip - slip.mean()) ** 2)))
        noise = float(np.sqrt(np.mean(np.diff(slip, 2) ** 2) / 6.0))
        out[body] = {
            "rolled": bool(spread <= 3.0 * noise + 1e-12),
            "slip_rms": spread,
            "noise": noise,
        }
    return out

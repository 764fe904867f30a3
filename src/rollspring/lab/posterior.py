r"""A posterior of a fit by MCMC (emcee's affine-invariant ensemble sampler).

The likelihood is Gaussian in the residuals with the fit's noise :math:`s` (the tracking noise
estimated from the residuals), the prior flat within the model's ranges. The errors are those
the fit's standard errors rest on: when the fit took them as an AR(1) process in the frames
(lag-1 autocorrelation :math:`\rho`, :func:`rollspring.lab.fit.correlated_covariance`), the
likelihood is that process's, each body's residuals in the order of its marked frames
(:math:`g_k` frames after the one before; an unmarked frame counts in the lag):

.. math:: \ln p(\theta\mid d) = -\frac{1}{2s^2}\sum_b\Big[r_{b1}^2 + \sum_{k\ge2}
          \frac{(r_{bk} - \rho^{g_k}r_{b,k-1})^2}{1-\rho^{2g_k}}\Big] + \text{const},

which is :math:`-\sum r^2/2s^2` for :math:`\rho = 0`. The errors locked to the bodies'
positions (a textured background, :func:`rollspring.lab.fit.locked_covariance`) repeat
wherever a body passes and do not average down: their share of the fit's covariance,
:math:`C_e`, is added to the chain as one independent draw from :math:`N(0, C_e)` per sample,
as it is added to the fit's covariance, a draw that leaves the prior's support drawn again
(:func:`_with_locked_errors`).

The walkers start in a small ball (a tenth of a standard error) around the least-squares
minimum and are evaluated as one batch (``vectorize=True``): on the linear route every walker's
motion :math:`e^{B\tau}z_0` comes from one batched matrix exponential and one batched product
(:func:`rollspring.lab.motion.transition_matrices` over a leading axis of systems). Credible
intervals are the 2.5 % and 97.5 % quantiles of the chain after its first half is discarded.
"""

from __future__ import annotations

import math
import time
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np

from rollspring.analysis.costs import Cost
from rollspring.errors import FitError
from rollspring.lab import parameters as paths_module
from rollspring.lab.fit import FitResult
from rollspring.lab.motion import transition_matrices
from rollspring.physics.arrays import FloatArray

__all__ = ["Posterior", "posterior_cost", "sample_posterior"]


@dataclass(frozen=True)
class Posterior:
    """The chain (steps, walkers, parameters) after burn-in, the parameters' names, their
    medians and 95 % credible intervals, and the mean acceptance fraction."""

    names: tuple[str, ...]
    samples: FloatArray
    median: FloatArray
    low: FloatArray
    high: FloatArray
    acceptance: float
    #: each parameter's integrated autocorrelation time (steps), and why an interval is not to
    #: be trusted (a chain shorter than :data:`CONVERGED_TAUS` of them, a parameter the fit
    #: found not identifiable)
    tau: FloatArray | None = None
    warnings: tuple[str, ...] = ()

    def to_dict(self) -> dict[str, Any]:
        """``{name: {"median", "low", "high", "tau"}}`` (the 95 % credible interval, the
        autocorrelation time in steps), the acceptance, the samples and the warnings."""
        tau = self.tau if self.tau is not None else np.full(len(self.names), np.nan)
        return {
            "credible_intervals": {
                name: {
                    "median": float(m),
                    "low": float(lo),
                    "high": float(hi),
                    "tau": float(t) if np.isfinite(t) else None,
                }
                for name, m, lo, hi, t in zip(
                    self.names, self.median, self.low, self.high, tau, strict=True
                )
            },
            "acceptance": float(self.acceptance),
            "samples": int(self.samples.shape[0] * self.samples.shape[1]),
            "warnings": list(self.warnings),
        }


@dataclass(frozen=True)
class _Errors:
    """The AR(1) likelihood's terms over the residual vector (the marked entries of the
    (frames, bodies) table in row-major order): entry ``current`` less ``coefficient`` times
    entry ``previous``, squared, times ``weight``."""

    current: np.ndarray
    previous: np.ndarray
    coefficient: FloatArray
    weight: FloatArray

    @classmethod
    def of(cls, marked: np.ndarray, rho: float) -> _Errors:
        """The terms for the table ``marked`` (frames, bodies) and autocorrelation ``rho``."""
        flat = np.cumsum(marked.ravel()).reshape(marked.shape) - 1  # each entry's place
        current, previous, gaps = [], [], []
        for b in range(marked.shape[1]):
            frames = np.flatnonzero(marked[:, b])
            if frames.size == 0:
                continue
            places = flat[frames, b]
            current.append(places)
            previous.append(np.concatenate([places[:1], places[:-1]]))
            gaps.append(np.concatenate([[0], np.diff(frames)]))
        gap = np.concatenate(gaps) if gaps else np.zeros(0, dtype=np.int64)
        # the first of each body: no term before it (coefficient 0, weight 1)
        coefficient = np.where(gap > 0, float(rho) ** gap, 0.0)
        return cls(
            np.concatenate(current) if current else np.zeros(0, dtype=np.int64),
            np.concatenate(previous) if previous else np.zeros(0, dtype=np.int64),
            coefficient,
            1.0 / (1.0 - coefficient**2),
        )

    def sum_of_squares(self, residual: FloatArray) -> FloatArray:
        r""":math:`\sum w (r_k - a r_{k-1})^2` over the last axis of ``residual``."""
        innovation = residual[..., self.current] - self.coefficient * residual[..., self.previous]
        return np.asarray(np.sum(self.weight * innovation**2, axis=-1))


def _full(result: FitResult, points: FloatArray) -> FloatArray:
    """Every parameter of the model for each row of ``points`` (rows, fitted parameters): the
    fit's best values with the fitted ones replaced."""
    names = result.problem.layout.names
    fitted = [names.index(name) for name in result.fitted]
    full = np.repeat(result.best[None, :], points.shape[0], axis=0)
    full[:, fitted] = points
    return full


def _inside_prior(result: FitResult, full: FloatArray) -> np.ndarray:
    """Whether each row of ``full`` (:func:`_full`) is within the flat prior's support: every
    PATH within the range a system file takes (the initial state and t0 are free)."""
    layout = result.problem.layout
    p = layout.n_paths
    low = np.array([paths_module.bounds_of(path, 0.0)[0] for path in layout.paths])
    high = np.array([paths_module.bounds_of(path, 0.0)[1] for path in layout.paths])
    return np.asarray(np.all((full[:, :p] >= low) & (full[:, :p] <= high), axis=1))


def _log_probability(result: FitResult, points: FloatArray, errors: _Errors) -> FloatArray:
    """The log-posterior of each row of ``points`` (walkers, fitted parameters)."""
    problem = result.problem
    layout = problem.layout
    full = _full(result, points)
    out = np.full(points.shape[0], -np.inf)
    p, n = layout.n_paths, len(problem.ids)
    inside = _inside_prior(result, full)
    scale = 1.0 / (2.0 * result.noise**2)
    if problem.level:
        rows = [int(k) for k in np.flatnonzero(inside)]
        affine = _affine_motion(result) if p else None
        if affine is not None:
            base, slopes = affine
            shift = full[rows, :p] - result.best[:p]
            matrices = list(base + np.einsum("wp,pij->wij", shift, slopes))
        else:
            matrices, kept = [], []
            for k in rows:
                try:
                    matrices.append(problem.model(full[k, :p])[2])
                except FitError:
                    continue
                kept.append(k)
            rows = kept
        if not rows:
            return out
        chosen = full[rows]
        offset = chosen[:, p + 2 * n + 1]
        start = chosen[:, p + 2 * n]
        if np.ptp(start) == 0:  # t0 held (or equal): one batch of exponentials
            tau = np.maximum(problem.t - start[0], 0.0)
            phi = transition_matrices(np.stack(matrices), tau)[:, :, problem.measured, :]
            z0 = np.concatenate([chosen[:, p : p + 2 * n], np.ones((len(rows), 1))], axis=1)
            x = np.einsum("wnbm,wm->wnb", phi, z0) + offset[:, None, None]
            residual = x[:, problem.mask] - problem.observed
            out[rows] = -scale * errors.sum_of_squares(residual)
            return out
    for walker in np.flatnonzero(inside).tolist():
        try:
            residual = problem.residual(full[walker])
        except (FitError, ArithmeticError):
            continue
        value = float(errors.sum_of_squares(residual))
        if math.isfinite(value):  # else the model cannot follow the walker: -inf, refused
            out[walker] = -scale * value
    return out


def _affine_motion(result: FitResult) -> tuple[FloatArray, FloatArray] | None:
    r"""``(B(θ̂), ∂B/∂θ)`` when the motion matrix is affine in the free PATHs — as it is in the
    springs' stiffnesses and dampings (:math:`K = \sum_s k_s b_sb_s^T`, :math:`C = \sum_s
    c_s b_sb_s^T` with constant lever arms, docs/physics.md (M12)) — checked by finite
    differences (second differences along each PATH and mixed ones vanish to 1e-10 of B);
    then every walker's :math:`B = B(\hat\theta) + \sum_p \partial_pB\,\Delta\theta_p`
    is exact, built for the whole batch at once. None otherwise (a mass enters as 1/m): each
    walker's system is built on its own."""
    problem = result.problem
    theta = result.best[: problem.layout.n_paths]
    key = tuple(theta.tolist())
    if key in problem.affine:
        return problem.affine[key]
    base = problem.model(theta)[2]
    scale = float(np.max(np.abs(base)))
    steps = 1e-2 * np.maximum(np.abs(theta), 1e-2)
    moved = []
    answer: tuple[FloatArray, FloatArray] | None = None
    try:
        for i, step in enumerate(steps):
            once, twice = theta.copy(), theta.copy()
            once[i] += step
            twice[i] += 2 * step
            b1, b2 = problem.model(once)[2], problem.model(twice)[2]
            if np.max(np.abs(b2 - 2 * b1 + base)) > 1e-10 * scale:
                raise ArithmeticError
            moved.append(b1)
        for i in range(len(steps)):
            for j in range(i + 1, len(steps)):
                both = theta.copy()
                both[[i, j]] += steps[[i, j]]
                mixed = problem.model(both)[2] - moved[i] - moved[j] + base
                if np.max(np.abs(mixed)) > 1e-10 * scale:
                    raise ArithmeticError
        slopes = np.stack([(b - base) / s for b, s in zip(moved, steps, strict=True)])
        answer = (base, slopes)
    except (ArithmeticError, FitError):
        answer = None
    problem.affine[key] = answer
    return answer


#: Draws of the locked errors tried for a sample before it is kept as it is (the prior's
#: support left by every one of them).
LOCKED_DRAWS = 100


def _with_locked_errors(result: FitResult, chain: FloatArray, seed: int) -> FloatArray:
    """``chain`` (steps, walkers, parameters) with the errors locked to the positions carried:
    each sample moved by an independent draw of :math:`N(0, C_e)` (``result.locked``, seeded),
    drawn again while the moved sample leaves the flat prior's support (a damping below zero),
    up to :data:`LOCKED_DRAWS` times, then left unmoved: the convolution, truncated to the
    support as the prior truncates the likelihood."""
    assert result.locked is not None  # the caller's condition
    covariance: FloatArray = result.locked
    rng = np.random.default_rng(seed + 1)
    flat = chain.reshape(-1, chain.shape[-1])
    moved = flat.copy()
    pending = np.arange(flat.shape[0])
    for _ in range(LOCKED_DRAWS):
        if pending.size == 0:
            break
        draws: FloatArray = rng.multivariate_normal(
            np.zeros(flat.shape[1]), covariance, size=pending.size, method="eigh"
        )
        trial = flat[pending] + draws
        inside = _inside_prior(result, _full(result, trial))
        moved[pending[inside]] = trial[inside]
        pending = pending[~inside]
    return moved.reshape(chain.shape)


def posterior_cost(result: FitResult, *, walkers: int | None = None, steps: int = 300) -> Cost:
    """The estimated cost of :func:`sample_posterior`: one evaluation of the log-posterior per
    walker and step, timed here at the fit's best values (one walker on the simulated motion,
    where each is a simulation of the record; every walker at once on the exact linear motion,
    evaluated as a batch). The fit's own evaluations are no measure: its trials include
    values far from the best (a slipping motion integrated by DOP853, 13 times slower)."""
    count = _walkers(result, walkers)
    errors = _Errors.of(result.problem.mask, result.rho)
    centre = np.array([result.parameters[name].value for name in result.fitted])
    timed = 1 if not result.level else count
    began = time.perf_counter()
    _log_probability(result, np.tile(centre, (timed, 1)), errors)
    per_walker = (time.perf_counter() - began) / timed
    return Cost(
        what="the posterior",
        bodies=len(result.problem.ids),
        seconds=count * steps * per_walker,
        smaller="fewer steps or walkers, a shorter record",
    )


def _walkers(result: FitResult, walkers: int | None) -> int:
    count = walkers or max(16, 4 * len(result.fitted))
    return count + count % 2


def sample_posterior(
    result: FitResult,
    *,
    walkers: int | None = None,
    steps: int = 300,
    seed: int = 0,
    progress: Callable[[float], None] | None = None,
) -> Posterior:
    """Sample the posterior around ``result`` (the module's docstring) with ``walkers`` walkers
    (default: four per parameter, at least 16) for ``steps`` steps, the first half discarded.
    Seeded: the same ``seed`` gives the same chain."""
    try:
        import emcee  # type: ignore[import-untyped]
    except ModuleNotFoundError:
        from rollspring.errors import MissingExtraError

        raise MissingExtraError("--posterior", ("lab",)) from None
    names = result.fitted
    dimension = len(names)
    if dimension == 0:
        raise FitError("--posterior: no parameter is fitted")
    count = _walkers(result, walkers)
    centre = np.array([result.parameters[name].value for name in names])
    # the spread the likelihood gives (the locked errors' share is added after sampling)
    variance = np.diag(result.covariance) - (
        np.diag(result.locked) if result.locked is not None else 0.0
    )
    spread = np.sqrt(np.maximum(variance, 0.0))
    spread = np.where(np.isfinite(spread) & (spread > 0), spread, 1e-6 * np.maximum(1, abs(centre)))
    rng = np.random.default_rng(seed)
    start = centre + 0.1 * spread * rng.standard_normal((count, dimension))
    for _ in range(60):  # walkers started outside the prior's support drawn again, nearer
        outside = ~_inside_prior(result, _full(result, start))
        if not outside.any():
            break
        spread = 0.5 * spread
        start[outside] = centre + 0.1 * spread * rng.standard_normal((outside.sum(), dimension))
    errors = _Errors.of(result.problem.mask, result.rho)
    sampler = emcee.EnsembleSampler(
        count,
        dimension,
        lambda points: _log_probability(result, np.atleast_2d(points), errors),
        vectorize=True,
    )
    sampler.random_state = np.random.RandomState(seed).get_state()
    for step, _ in enumerate(sampler.sample(start, iterations=steps), start=1):
        if progress is not None:
            progress(step / steps)
    chain = sampler.get_chain(discard=steps // 2)
    # tol=0: the estimate whatever the chain's length (emcee would log a warning otherwise);
    # the length is judged here, against CONVERGED_TAUS
    tau = np.asarray(emcee.autocorr.integrated_time(chain, tol=0), dtype=np.float64)
    warnings = _warnings(result, names, tau, chain.shape[0])
    if result.locked is not None and np.any(result.locked):
        chain = _with_locked_errors(result, chain, seed)
    flat = chain.reshape(-1, dimension)
    low, median, high = np.percentile(flat, [2.5, 50.0, 97.5], axis=0)
    acceptance = float(np.mean(sampler.acceptance_fraction))
    return Posterior(
        tuple(names),
        chain,
        median,
        low,
        high,
        acceptance if math.isfinite(acceptance) else 0.0,
        tau,
        warnings,
    )


#: A chain kept (after burn-in) of at least this many autocorrelation times, over all the
#: walkers a few hundred independent samples, gives a 95 % interval to trust (emcee's
#: documentation asks 50 for the time itself to be known well).
CONVERGED_TAUS = 10.0
#: The shortest chain kept whose autocorrelation time can be told at all (steps).
MIN_KEPT = 50


def _warnings(
    result: FitResult, names: Sequence[str], tau: FloatArray, kept: int
) -> tuple[str, ...]:
    """Why an interval is not to be trusted: a parameter the fit found not identifiable (its
    standard error infinite: the walkers spread from a guess, not from the likelihood), or a
    chain kept shorter than :data:`CONVERGED_TAUS` autocorrelation times (the interval may be
    far too narrow, and depend on the seed)."""
    out = [
        f"posterior: {name} is not identifiable (the fit's standard error is infinite): its "
        "interval says where the walkers were, not what the data allow"
        for name in names
        if not math.isfinite(result.stderr(name))
    ]
    if kept < MIN_KEPT:
        out.append(
            f"posterior: the chain kept is {kept} steps, too short to measure its "
            f"autocorrelation (at least {MIN_KEPT}): the intervals may be too narrow"
        )
        return tuple(out)
    short = [
        f"{name} (tau {t:.3g} steps)"
        for name, t in zip(names, tau, strict=True)
        if math.isfinite(result.stderr(name)) and not kept >= CONVERGED_TAUS * t
    ]
    if short:
        out.append(
            f"posterior: the chain kept is {kept} steps, fewer than {CONVERGED_TAUS:g} "
            f"autocorrelation times of {', '.join(short)}: their intervals may be too narrow"
        )
    return tuple(out)

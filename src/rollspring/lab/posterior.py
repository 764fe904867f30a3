r"""A posterior of a fit by MCMC (emcee's affine-invariant ensemble sampler).

The likelihood is Gaussian in the residuals with the fit's noise :math:`s` (the tracking noise
estimated from the residuals), the prior flat within the model's ranges:

.. math:: \ln p(\theta\mid d) = -\frac{1}{2s^2}\sum_{jb} r_{jb}(\theta)^2 + \text{const}.

The walkers start in a small ball (a tenth of a standard error) around the least-squares
minimum and are evaluated as one batch (``vectorize=True``): on the linear route every walker's
motion :math:`e^{B\tau}z_0` comes from one batched matrix exponential and one batched product
(:func:`rollspring.lab.motion.transition_matrices` over a leading axis of systems). Credible
intervals are the 2.5 % and 97.5 % quantiles of the chain after its first half is discarded.
"""

from __future__ import annotations

import math
from collections.abc import Callable
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

    def to_dict(self) -> dict[str, Any]:
        """``{name: {"median", "low", "high"}}`` (the 95 % credible interval), the acceptance."""
        return {
            "credible_intervals": {
                name: {"median": float(m), "low": float(lo), "high": float(hi)}
                for name, m, lo, hi in zip(
                    self.names, self.median, self.low, self.high, strict=True
                )
            },
            "acceptance": float(self.acceptance),
            "samples": int(self.samples.shape[0] * self.samples.shape[1]),
        }


def _log_probability(result: FitResult, points: FloatArray) -> FloatArray:
    """The log-posterior of each row of ``points`` (walkers, fitted parameters)."""
    problem = result.problem
    layout = problem.layout
    names = layout.names
    fitted = [names.index(name) for name in result.fitted]
    full = np.repeat(result.best[None, :], points.shape[0], axis=0)
    full[:, fitted] = points
    out = np.full(points.shape[0], -np.inf)
    p, n = layout.n_paths, len(problem.ids)
    low = np.array([paths_module.bounds_of(path, 0.0)[0] for path in layout.paths])
    high = np.array([paths_module.bounds_of(path, 0.0)[1] for path in layout.paths])
    inside = np.all((full[:, :p] >= low) & (full[:, :p] <= high), axis=1)
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
            out[rows] = -scale * np.sum(residual**2, axis=1)
            return out
    for walker in np.flatnonzero(inside).tolist():
        try:
            residual = problem.residual(full[walker])
        except (FitError, ArithmeticError):
            continue
        out[walker] = -scale * float(residual @ residual)
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


def posterior_cost(result: FitResult, *, walkers: int | None = None, steps: int = 300) -> Cost:
    """The estimated cost of :func:`sample_posterior`: on the simulated motion one evaluation
    of the residuals per walker and step, each as long as the fit's took on average; on the
    exact linear motion (evaluated as a batch) a small fraction of that."""
    count = _walkers(result, walkers)
    per_evaluation = result.seconds / max(result.evaluations, 1)
    factor = 0.05 if result.level else 1.0
    return Cost(
        what="the posterior",
        bodies=len(result.problem.ids),
        seconds=factor * count * steps * per_evaluation,
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
    spread = np.array([result.parameters[name].stderr for name in names])
    spread = np.where(np.isfinite(spread) & (spread > 0), spread, 1e-6 * np.maximum(1, abs(centre)))
    rng = np.random.default_rng(seed)
    start = centre + 0.1 * spread * rng.standard_normal((count, dimension))
    sampler = emcee.EnsembleSampler(
        count,
        dimension,
        lambda points: _log_probability(result, np.atleast_2d(points)),
        vectorize=True,
    )
    sampler.random_state = np.random.RandomState(seed).get_state()
    for step, _ in enumerate(sampler.sample(start, iterations=steps), start=1):
        if progress is not None:
            progress(step / steps)
    chain = sampler.get_chain(discard=steps // 2)
    flat = chain.reshape(-1, dimension)
    low, median, high = np.percentile(flat, [2.5, 50.0, 97.5], axis=0)
    acceptance = float(np.mean(sampler.acceptance_fraction))
    return Posterior(
        tuple(names), chain, median, low, high, acceptance if math.isfinite(acceptance) else 0.0
    )

r"""The model fitted to a measured table: least squares on the exact motion.

The residuals are the measured centre positions minus the model's,

.. math:: r_{jb} = x_b^{\rm model}(t_j - t_0;\,\theta, x_0, v_0) + \Delta x - x_{jb}^{\rm data},

over every marked frame j of every measured body b, minimised by SciPy's
:func:`~scipy.optimize.least_squares` (trust region reflective, bounds from the model's ranges)
over the free PATHs :math:`\theta`, each body's initial position and velocity :math:`x_0, v_0`
(at the data's first time) and, where it is identifiable, the offset :math:`\Delta x` between
the data's x origin and the system's.

**The motion** (:mod:`rollspring.lab.motion`): for level centre-joined springs (the paper's
Fig. 2 systems, exactly linear while rolling, spring damping included) the exact solution
:math:`e^{B\tau}z_0` — no integration error, a fraction of a millisecond per evaluation, the
derivatives with respect to the initial state exact (:math:`\partial x/\partial z_0` are
columns of :math:`e^{B\tau}`), those with respect to :math:`\theta` forward differences;
otherwise :func:`rollspring.simulate` at ``rtol = 1e-9`` with forward differences throughout.

**The global minimum from a rough start.** A stiffness 30 % off puts the model's frequency
30 % off; over tens of periods the least-squares surface then has a local minimum in every
period. Before the local solver the data's spectrum gives its strongest frequencies
(:func:`spectral_peaks`), and the free PATHs are moved, as little as they can be in log
terms, until a mode of the model has that frequency (:func:`_match_frequency`); the initial
state that best fits each such guess is then a linear least-squares problem (the motion is
linear in :math:`z_0` and :math:`\Delta x`: variable projection), and the best guess starts the
local solver. When ``t0`` is fitted it is scanned over a period around the data's start and
around the instant the recording shows the bodies start to move (:func:`_motion_onset`).
Damping-like PATHs that start at 0 stay there until the local solver, which finds them: the
decay moves the residuals smoothly, without local minima.

**The time offset and the initial state.** For an autonomous system a shift of the time origin
is a change of initial state: :math:`t_0` and :math:`(x_0, v_0)` cannot both be fitted. By
default the initial state at the data's first time is fitted and ``t0`` is that time, fixed;
with ``fix_initial=True`` the system's own initial state (e.g. released from rest) is taken to
hold until the data's time ``t0``, which is fitted.

**The x origin.** The data's x origin may differ from the system's. A free system (no anchors)
is invariant under translation, so with its initial positions free the offset is degenerate with
them: it is not fitted (the fitted positions are in the data's origin). With anchors (walls), or
with the initial state fixed, the offset is identifiable and fitted as ``x_offset``.

**Uncertainties.** With the Jacobian :math:`J` at the minimum and
:math:`s^2 = \sum r^2/(N - p)`, the covariance is :math:`s^2 (J^TJ)^{-1}` (from the singular
values and vectors of the column-normalised :math:`J`); the standard errors are its diagonal's
roots, the correlations its normalised form. That assumes independent errors. Tracking errors
are often not (a blurred outline is off the same way for several frames), and a model that
does not describe the data leaves residuals that follow each other: the residuals' lag-1
autocorrelation :math:`\rho = \sum_j r_j r_{j+1} / \sum_j r_j^2` (each body's consecutive
marked frames, pooled) is measured, and when it is above what independent errors give
(:math:`2/\sqrt N`) the errors are taken as an AR(1) process in the frames,
:math:`\Sigma_{ij} = s^2\rho^{|i-j|}` within a body, and the covariance is the least-squares
estimate's under them, :math:`(J^TJ)^{-1}J^T\Sigma J(J^TJ)^{-1}` (the sandwich; with
:math:`\rho = 0` it is :math:`s^2(J^TJ)^{-1}`). Above :data:`MODEL_MISMATCH_CORRELATION` a
warning says that the residuals are not noise: the model, as fitted, does not describe the data,
or the tracking's errors last several frames (the two look alike in the statistics measured
here: a short recording filmed at 60 fps, its outline blurred, reaches 0.64).
Errors the residuals cannot show are added when the data carry them: a track CSV's
``xlocked<m>_<id>`` columns (``rollspring track``'s measure of the error a textured background
locks to each body's position, which a fit absorbs into the initial state) add their linear
response :math:`\sum_{b,m}\sigma_{bm}^2 v_{bm}v_{bm}^T` to the covariance
(:func:`locked_covariance`), and so to every standard error and the claims'.
A near-singular :math:`J` (column-normalised condition number above
:data:`IDENTIFIABLE_CONDITION`) is reported as a warning naming the combination of parameters
the data do not constrain (the right singular vector).
"""

from __future__ import annotations

import dataclasses
import math
import time
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from rollspring.errors import FitError, RollspringError
from rollspring.lab import parameters as paths_module
from rollspring.lab.data import BodyData
from rollspring.lab.motion import motion_matrix, simulated_states, transition_matrices
from rollspring.model import System
from rollspring.physics import SystemArrays, system_arrays
from rollspring.physics.arrays import FloatArray
from rollspring.physics.mechanics import springs_stay_level

__all__ = [
    "EXPECTED_ITERATIONS",
    "IDENTIFIABLE_CONDITION",
    "FitResult",
    "FitStatus",
    "Parameter",
    "fit_model",
    "linear_route",
    "spectral_peaks",
]

#: A column-normalised Jacobian whose condition number exceeds this has a combination of
#: parameters the data do not constrain (a warning names it).
IDENTIFIABLE_CONDITION = 1e4

#: Residuals whose lag-1 autocorrelation exceeds this are not noise: a warning says that the
#: model, as fitted, may not describe the data (free more parameters or check the system), or
#: the tracking's errors last several frames.
MODEL_MISMATCH_CORRELATION = 0.5

#: The local solver's budget: evaluations of the residuals per fitted parameter.
MAX_EVALUATIONS_PER_PARAMETER = 100

#: The local solver's iterations as expected (each an evaluation of the residuals and one of
#: the Jacobian, p + 1 evaluations by forward differences): 5 to 12 on the fits of
#: bench/bench_lab_costs.py and the tests, rounded up. The cost estimate
#: (:func:`rollspring.lab.costs.fit_cost`) and the progress reported count on it.
EXPECTED_ITERATIONS = 12


class FitStatus:
    """The outcome of a fit: ``converged`` (the local solver's tolerances met) or
    ``not_converged`` (its budget ran out: the values are the best found)."""

    CONVERGED = "converged"
    NOT_CONVERGED = "not_converged"


@dataclass(frozen=True)
class Parameter:
    """One parameter of a fit: its ``value``, standard error ``stderr`` (0 for a fixed one),
    ``fixed`` when it was held, and its SI ``unit``."""

    name: str
    value: float
    stderr: float
    fixed: bool
    unit: str


@dataclass(frozen=True)
class _Layout:
    """Where each parameter sits in the full vector: the free PATHs, x0 (n), v0 (n), t0,
    x_offset; ``fitted`` the indices the solver moves."""

    paths: tuple[str, ...]
    ids: tuple[str, ...]
    fitted: tuple[int, ...]

    @property
    def names(self) -> tuple[str, ...]:
        return (
            *self.paths,
            *(f"bodies.{i}.x" for i in self.ids),
            *(f"bodies.{i}.v" for i in self.ids),
            "t0",
            "x_offset",
        )

    @property
    def n_paths(self) -> int:
        return len(self.paths)

    def split(self, full: FloatArray) -> tuple[FloatArray, FloatArray, FloatArray, float, float]:
        p, n = self.n_paths, len(self.ids)
        return (
            full[:p],
            full[p : p + n],
            full[p + n : p + 2 * n],
            float(full[p + 2 * n]),
            float(full[p + 2 * n + 1]),
        )


class _Problem:
    """The residuals of a fit and their Jacobian, over the full parameter vector."""

    def __init__(
        self, data: dict[str, Any], system: System, data_table: BodyData, layout: _Layout
    ) -> None:
        self.json = data
        self.layout = layout
        self.table = data_table
        self.ids = layout.ids
        self.t = data_table.t
        self.measured = np.asarray(data_table.index, dtype=np.int64)
        self.mask = np.isfinite(data_table.x)
        self.observed = data_table.x[self.mask]
        self.level = linear_route(system, layout.paths)
        self._systems: dict[tuple[float, ...], tuple[System, SystemArrays, FloatArray]] = {}
        #: the posterior's affine motion matrices, by the PATHs' values they were made at
        self.affine: dict[tuple[float, ...], tuple[FloatArray, FloatArray] | None] = {}
        #: told of each evaluation of the residuals (a simulation on the simulated route)
        self.on_evaluation: Callable[[], None] | None = None
        #: the last values the simulated route could not follow, and why
        self.failure = ""

    # -- the model at given parameters --------------------------------------------------------

    def model(self, theta: FloatArray) -> tuple[System, SystemArrays, FloatArray]:
        """The system, its arrays and its motion matrix at the PATHs' values ``theta``."""
        key = tuple(float(v) for v in theta)
        cached = self._systems.get(key)
        if cached is None:
            system = paths_module.with_values(
                self.json, dict(zip(self.layout.paths, key, strict=True))
            )
            arrays = system_arrays(system)
            cached = (system, arrays, motion_matrix(arrays))
            if len(self._systems) > 64:
                self._systems.clear()
            self._systems[key] = cached
        return cached

    def states(self, full: FloatArray, times: FloatArray | None = None) -> FloatArray:
        """The model's (x, v) (N, 2n) at the data's times (or ``times``), the x origin the
        data's (the offset added)."""
        theta, x0, v0, t0, offset = self.layout.split(full)
        times = self.t if times is None else times
        tau = np.maximum(times - t0, 0.0)  # before t0 the initial state holds
        n = len(self.ids)
        if self.level:
            _, _, b = self.model(theta)
            phi = transition_matrices(b, tau)
            z0 = np.concatenate([x0, v0, [1.0]])
            z = phi[:, : 2 * n, :] @ z0
        else:
            try:
                system = self._with_state(theta, x0, v0)
                x, v = simulated_states(system, tau)
            except (ArithmeticError, RollspringError) as exc:
                # a trial the model cannot follow (a body that leaves its track or slides
                # off at these values): no motion, so no residual the solver could take
                self.failure = f"{_values_text(self.layout, full)}: {exc}"
                return np.full((times.size, 2 * n), np.nan)
            z = np.concatenate([x, v], axis=1)
        z[:, :n] += offset
        return z

    def _with_state(self, theta: FloatArray, x0: FloatArray, v0: FloatArray) -> System:
        values = dict(zip(self.layout.paths, (float(v) for v in theta), strict=True))
        for i, ident in enumerate(self.ids):
            values[f"bodies.{ident}.x"] = float(x0[i])
            values[f"bodies.{ident}.v"] = float(v0[i])
        return paths_module.with_values(self.json, values)

    def residual(self, full: FloatArray) -> FloatArray:
        x = self.states(full)[:, self.measured]
        result: FloatArray = x[self.mask] - self.observed
        if self.on_evaluation is not None:
            self.on_evaluation()
        return result

    def jacobian(self, full: FloatArray) -> FloatArray:
        """d residual / d full[fitted]: exact for the initial state, t0 and the offset on the
        linear route, forward differences otherwise."""
        layout = self.layout
        n, p = len(self.ids), layout.n_paths
        columns = []
        base_states = None
        exact: dict[int, FloatArray] = {}
        if self.level:
            theta, x0, v0, t0, _ = layout.split(full)
            tau = np.maximum(self.t - t0, 0.0)
            _, _, b = self.model(theta)
            phi = transition_matrices(b, tau)
            z0 = np.concatenate([x0, v0, [1.0]])
            base_states = phi[:, : 2 * n, :] @ z0
            rows = phi[:, self.measured, :]  # (N, B, 2n+1)
            for k in range(2 * n):
                exact[p + k] = rows[:, :, k][self.mask]
            velocity = base_states[:, n + self.measured]
            exact[p + 2 * n] = np.where(self.t[:, None] > t0, -velocity, 0.0)[self.mask]
            exact[p + 2 * n + 1] = np.ones(self.observed.size)
        base = None
        for index in layout.fitted:
            if index in exact:
                columns.append(exact[index])
                continue
            if base is None:
                base = self.residual(full)
            step = self.step(full, index)
            moved = full.copy()
            moved[index] += step
            column = (self.residual(moved) - base) / step
            if not np.all(np.isfinite(column)):  # the model fails just above: below then
                moved[index] = full[index] - step
                column = (base - self.residual(moved)) / step
            if not np.all(np.isfinite(column)):
                raise FitError(
                    f"the model cannot be followed on either side of {layout.names[index]} = "
                    f"{full[index]:.6g} ({self.failure or 'not finite'})"
                )
            columns.append(column)
        return np.stack(columns, axis=1) if columns else np.zeros((self.observed.size, 0))

    def step(self, full: FloatArray, index: int) -> float:
        """The forward-difference step of ``full[index]`` (:func:`_step`); for t0, of the time
        after the data's first (the clock's reading, 1.7e9 s on an epoch, would make it
        1.7e5 s), and at least 64 of its float spacings (so that t0 + step differs from t0)."""
        p, n = self.layout.n_paths, len(self.ids)
        if index != p + 2 * n:
            return _step(full[index], self.level, index >= p)
        step = _step(full[index] - float(self.t[0]), self.level, True)
        return max(step, 64.0 * float(np.spacing(abs(full[index]))))


def _values_text(layout: _Layout, full: FloatArray) -> str:
    """The fitted PATHs' values of ``full``, for a message (``springs.0.stiffness = 130``)."""
    return ", ".join(f"{layout.names[i]} = {full[i]:.6g}" for i in range(layout.n_paths))


def _step(value: float, exact: bool, state: bool) -> float:
    """The forward-difference step of a parameter: relative sqrt(eps) on the exact linear
    motion, 1e-4 on the simulated one (well above its 1e-9 accuracy)."""
    relative = 1.5e-8 if exact else 1e-4
    floor = 1e-3 if state else 1e-2
    return relative * max(abs(value), floor)


#: Quantities the exact linear motion leaves out (the rolling resistance, a force
#: :math:`-C_{rr}N\,\mathrm{sign}(v)` that is not linear; the friction coefficients, which
#: decide slipping) or that may tilt the springs when they change (a radius, a track's height,
#: an attachment, an anchor's height): a fit that frees one of them, or a system with a rolling
#: resistance, is fitted on the simulated motion.
NONLINEAR_QUANTITIES = (
    "rolling_resistance",
    "mu_static",
    "mu_kinetic",
    "radius",
    "track_height",
    "height",
    "angle",
    "y",
)


def linear_route(system: System, paths: Sequence[str] = ()) -> bool:
    """Whether the fit's motion is the exact linear solution: level centre-joined springs
    (:func:`~rollspring.physics.mechanics.springs_stay_level`), no body with a rolling
    resistance, no free PATH among :data:`NONLINEAR_QUANTITIES`."""
    if any(path.split(".")[-1] in NONLINEAR_QUANTITIES for path in paths):
        return False
    resisted = any(float(getattr(b, "rolling_resistance", 0.0) or 0.0) > 0 for b in system.bodies)
    return springs_stay_level(system_arrays(system)) and not resisted


# ------------------------------------------------------------------------------- first guess


def spectral_peaks(t: FloatArray, x: FloatArray, count: int = 3) -> FloatArray:
    r"""The ``count`` strongest angular frequencies (rad/s, strongest first) in measured
    positions ``x`` (N, B) at times ``t``: each body's positions put on a uniform grid (linear
    interpolation over unmarked frames), their straight-line trend removed, a Hann window, the
    power spectrum :math:`|\mathrm{FFT}|^2` summed over the bodies and zero-padded eightfold,
    its local maxima refined by a parabola through the log-power of three bins. Frequencies
    below 1.5 cycles per record are left out (a drift, not an oscillation)."""
    h = float(np.median(np.diff(t)))
    grid = np.arange(t[0], t[-1] + 0.5 * h, h)
    if grid.size < 8:
        return np.zeros(0)
    power = None
    size = 8 * (1 << int(np.ceil(np.log2(grid.size))))
    window = np.hanning(grid.size)
    for column in x.T:
        ok = np.isfinite(column)
        if ok.sum() < 4:
            continue
        values = np.interp(grid, t[ok], column[ok])
        trend = np.polyval(np.polyfit(grid - grid[0], values, 1), grid - grid[0])
        spectrum = np.abs(np.fft.rfft((values - trend) * window, size)) ** 2
        power = spectrum if power is None else power + spectrum
    if power is None:
        return np.zeros(0)
    frequency = np.fft.rfftfreq(size, h) * 2 * np.pi
    low = 2 * np.pi * 1.5 / (grid[-1] - grid[0])
    inner = np.arange(1, power.size - 1)
    peaks = inner[(power[inner] > power[inner - 1]) & (power[inner] >= power[inner + 1])]
    peaks = peaks[frequency[peaks] > low]
    if peaks.size == 0:
        return np.zeros(0)
    peaks = peaks[np.argsort(power[peaks])[::-1][:count]]
    logs = np.log(np.maximum(power, np.finfo(float).tiny))
    a, b, c = logs[peaks - 1], logs[peaks], logs[peaks + 1]
    curvature = a - 2 * b + c
    shift = np.where(curvature < 0, 0.5 * (a - c) / np.where(curvature < 0, curvature, -1), 0.0)
    result: FloatArray = (peaks + np.clip(shift, -0.5, 0.5)) * (frequency[1] - frequency[0])
    return result


def _model_frequencies(arrays: SystemArrays) -> FloatArray:
    """The angular frequencies (rad/s) of the model's oscillating modes at the placement
    (:func:`rollspring.analysis.linear.normal_modes`)."""
    from rollspring.analysis.linear import normal_modes
    from rollspring.physics.mechanics import mass_matrix, stiffness_matrix

    values, _, kinds = normal_modes(
        mass_matrix(arrays), np.asarray(stiffness_matrix(arrays, np.zeros(arrays.n_bodies)))
    )
    result: FloatArray = np.sqrt(values[np.asarray(kinds) == "oscillating"])
    return result


def _match_frequency(
    problem: _Problem, theta: FloatArray, target: float, mode: int
) -> FloatArray | None:
    r"""The free PATHs moved so that the model's oscillating mode ``mode`` has the angular
    frequency ``target``, all together and as little as they can in log terms: Gauss-Newton
    steps of the minimum-norm solution of

    .. math:: \ln\omega_{\rm mode}(\theta) = \ln\omega_{\rm target},\qquad
              \Delta u = g\,\frac{\ln\omega_{\rm target} - \ln\omega}{g^Tg},\quad
              u = \ln\theta,\; g = \frac{\partial\ln\omega}{\partial u}

    over the positive PATHs (a PATH that starts at 0, a damping, stays there), within the
    model's ranges. None when no PATH moves the frequency or the model refuses the values."""
    movable = [i for i, v in enumerate(theta) if v > 0]
    if not movable:
        return None
    bounds = [paths_module.bounds_of(problem.layout.paths[i], theta[i]) for i in movable]
    low = np.array([math.log(b[0]) if b[0] > 0 else -np.inf for b in bounds])
    high = np.array([math.log(b[1]) if math.isfinite(b[1]) else np.inf for b in bounds])
    goal = math.log(target)

    def log_omega(u: FloatArray) -> float:
        moved = theta.copy()
        moved[movable] = np.exp(u)
        _, arrays, _ = problem.model(moved)
        omegas = _model_frequencies(arrays)
        return math.log(omegas[mode]) if mode < omegas.size else math.nan

    u = np.log(theta[movable])
    try:
        for _ in range(8):
            value = log_omega(u)
            if not math.isfinite(value):
                return None
            if abs(value - goal) < 1e-9:
                break
            gradient = np.empty(u.size)
            for k in range(u.size):
                moved = u.copy()
                moved[k] += 1e-6
                gradient[k] = (log_omega(moved) - value) / 1e-6
            norm = float(gradient @ gradient)
            if not norm > 0 or not math.isfinite(norm):
                return None
            u = np.clip(u + gradient * (goal - value) / norm, low, high)
        else:
            return None
    except FitError:
        return None
    result = theta.copy()
    result[movable] = np.exp(u)
    return result


def _profile(problem: _Problem, full: FloatArray) -> tuple[float, FloatArray]:
    r"""Variable projection on the linear route: the initial state and offset that best fit the
    data for the other parameters of ``full`` (the motion is linear in them:
    :math:`x_j = \Phi_j z_0 + \Delta x`), by linear least squares; ``(cost, full)``."""
    layout = problem.layout
    n, p = len(problem.ids), layout.n_paths
    theta, x0, v0, t0, offset = layout.split(full)
    linear = [i for i in layout.fitted if i >= p and i != p + 2 * n]
    try:
        _, _, b = problem.model(theta)
    except FitError:
        return math.inf, full
    tau = np.maximum(problem.t - t0, 0.0)
    phi = transition_matrices(b, tau)[:, problem.measured, :]  # (N, B, 2n+1)
    z0 = np.concatenate([x0, v0, [1.0]])
    design = []
    constant = (phi @ z0)[problem.mask] + offset
    for index in linear:
        if index == p + 2 * n + 1:
            column = np.ones(problem.observed.size)
            constant = constant - offset
        else:
            column = phi[:, :, index - p][problem.mask]
            constant = constant - column * z0[index - p]
        design.append(column)
    result = full.copy()
    if design:
        result[linear] = _linear_least_squares(
            np.stack(design, axis=1), problem.observed - constant
        )
    residual = problem.residual(result)
    return float(residual @ residual), result


def _linear_least_squares(matrix: FloatArray, target: FloatArray) -> FloatArray:
    r"""The least-squares solution of :math:`Az = y` for a tall :math:`A` with a few columns,
    by the normal equations of the column-normalised :math:`A` (a p × p solve; the minimum-norm
    solution along directions the columns do not separate)."""
    scale = np.sqrt(np.einsum("ij,ij->j", matrix, matrix))
    scale = np.where(scale > 0, scale, 1.0)
    normalised = matrix / scale
    solution: FloatArray = np.linalg.pinv(
        normalised.T @ normalised, rcond=1e-12, hermitian=True
    ) @ (normalised.T @ target)
    return solution / scale


#: Costs within this fraction of each other tie in the first guess (the nearer start wins).
_TIE = 1e-6


def _first_guess(problem: _Problem, full: FloatArray) -> FloatArray:
    """The start of the local solver: the best, by the profiled cost, of the user's values and
    each match of a model mode to one of the data's strongest frequencies (with the start time
    scanned over a period when it is fitted)."""
    layout = problem.layout
    n, p = len(problem.ids), layout.n_paths
    theta = full[:p]
    candidates = [theta]
    peaks = spectral_peaks(problem.t, problem.table.x)
    if p:
        _, arrays, _ = problem.model(theta)
        modes = _model_frequencies(arrays).size
        for target in peaks:
            for mode in range(modes):
                matched = _match_frequency(problem, theta, float(target), mode)
                if matched is not None:
                    candidates.append(matched)
    t0_index = p + 2 * n
    fitted_t0 = t0_index in layout.fitted
    best_cost, best = math.inf, full
    for candidate in candidates:
        trial = full.copy()
        trial[:p] = candidate
        starts = [full[t0_index]]
        if fitted_t0:
            _, arrays, _ = problem.model(candidate)
            omegas = _model_frequencies(arrays)
            period = 2 * math.pi / float(omegas.min()) if omegas.size else 1.0
            onset = _motion_onset(problem)
            reference = float(problem.t[0])
            starts = list(problem.t[0] + np.linspace(-period, period, 41))
            if onset > problem.t[0] + period:  # held still at first: scan around the release
                reference = onset
                starts += list(onset + np.linspace(-period, period, 41))
            # nearest first, and a later start only if clearly better: an undamped (or
            # linearised) model is periodic, so starts a period apart tie, and the one a period
            # early made a resisted fit settle on the wrong swing (C_rr 0.0014 for 0.002)
            starts.sort(key=lambda start: abs(start - reference))
        for start in starts:
            trial[t0_index] = start
            if problem.level:
                cost, guess = _profile(problem, trial)
            else:
                cost, guess = _linearised_profile(problem, trial)
            if cost < best_cost * (1.0 - _TIE):
                best_cost, best = cost, guess
    return best


def _start_as_given(problem: _Problem, full: FloatArray) -> FloatArray:
    """The start without the spectral search: the given PATHs' values, the initial state (and
    offset) that fit them best."""
    if problem.level:
        return _profile(problem, full)[1]
    return _linearised_profile(problem, full)[1]


def _motion_onset(problem: _Problem) -> float:
    r"""The first time any measured body has moved from where it started (the median of its
    first five positions) by more than six times the tracking noise (estimated from the second
    differences, :math:`\sigma^2 = \langle(\Delta^2x)^2\rangle/6`) in three frames running:
    where a release from rest shows."""
    onset = float(problem.t[-1])
    for column in range(problem.table.x.shape[1]):
        x = problem.table.x[:, column]
        ok = np.isfinite(x)
        if ok.sum() < 8:
            continue
        values, times = x[ok], problem.t[ok]
        noise = math.sqrt(float(np.mean(np.diff(values, 2) ** 2)) / 6.0)
        away = np.abs(values - np.median(values[:5])) > 6.0 * noise + 1e-12
        running = away[:-2] & away[1:-1] & away[2:]
        moved = np.flatnonzero(running)
        if moved.size:
            onset = min(onset, float(times[moved[0]]))
    return onset


def _linearised_profile(problem: _Problem, full: FloatArray) -> tuple[float, FloatArray]:
    """:func:`_profile` for a simulated system: the linearisation about the placement stands in
    for the motion in the first guess only."""
    level = problem.level
    problem.level = True
    try:
        cost, guess = _profile(problem, full)
    finally:
        problem.level = level
    return cost, guess


# ----------------------------------------------------------------------------------- the fit


@dataclass(frozen=True)
class FitResult:
    r"""A fitted model: the parameters (free PATHs, initial state, ``t0``, ``x_offset``) with
    standard errors, the residual RMS per measured body (m), the fitted system, the status, the
    warnings (parameters not identifiable), the covariance and correlations of the fitted
    parameters, the data and the model at the data's times.

    ``residual_rms`` per body is :math:`\sqrt{\sum_j r_{jb}^2 / N_b}`; ``noise`` the estimate
    :math:`s = \sqrt{\sum r^2/(N-p)}` of the tracking noise the standard errors rest on.
    """

    parameters: dict[str, Parameter]
    fitted: tuple[str, ...]
    covariance: FloatArray
    correlation: FloatArray
    residual_rms: dict[str, float]
    noise: float
    status: str
    message: str
    warnings: list[str]
    system: System
    data: BodyData
    model_x: FloatArray  # (N, B) the model at the data's times, the data's x origin
    level: bool
    n_points: int
    evaluations: int
    problem: _Problem = field(repr=False)
    best: FloatArray = field(repr=False)
    claims: dict[str, Any] = field(default_factory=dict)
    posterior: dict[str, Any] | None = None
    seconds: float = 0.0  # the fit's wall time (first guess, solver, standard errors)
    #: the residuals' lag-1 autocorrelation the standard errors take as AR(1) errors in the
    #: frames (:func:`correlated_covariance`); 0 when it is within noise (2/sqrt N)
    rho: float = 0.0
    #: the part of ``covariance`` from the errors locked to the bodies' positions
    #: (:func:`locked_covariance`); None without a measure of them
    locked: FloatArray | None = field(default=None, repr=False)

    @property
    def converged(self) -> bool:
        """Whether the local solver met its tolerances."""
        return self.status == FitStatus.CONVERGED

    def value(self, name: str) -> float:
        """A parameter's fitted value."""
        return self.parameters[name].value

    def stderr(self, name: str) -> float:
        """A parameter's standard error."""
        return self.parameters[name].stderr

    def to_dict(self) -> dict[str, Any]:
        """The JSON form (``rollspring fit --json``): ``parameters`` keyed by name, each
        ``{"value", "stderr"}`` (and ``"fixed": true`` for a held one), ``residual_rms`` per
        body (m), ``status``, ``claims`` for two-body systems, ``warnings``, the noise and the
        fitted parameters' correlations."""
        return {
            "status": self.status,
            "message": self.message,
            "parameters": {
                name: {
                    "value": _finite(p.value),
                    "stderr": _finite(p.stderr),
                    "unit": p.unit,
                    **({"fixed": True} if p.fixed else {}),
                }
                for name, p in self.parameters.items()
            },
            "residual_rms": {body: _finite(v) for body, v in self.residual_rms.items()},
            "noise": _finite(self.noise),
            "points": self.n_points,
            "motion": "exact linear solution" if self.level else "simulated (rtol 1e-9)",
            "correlation": {
                "parameters": list(self.fitted),
                "matrix": [[_finite(v) for v in row] for row in self.correlation.tolist()],
            },
            "claims": self.claims,
            "warnings": list(self.warnings),
            **({"posterior": self.posterior} if self.posterior is not None else {}),
        }

    def _repr_html_(self) -> str:
        from rollspring import presenters

        view = presenters.PRESENTERS.get("fit_html")
        if view is None:
            return f"<pre>{self.message}</pre>"
        text: str = view(self)
        return text


def _finite(value: float) -> float | None:
    return float(value) if math.isfinite(value) else None


#: SI units of the parameters by their last part (``springs.0.stiffness`` -> N/m).
UNITS = {
    "mass": "kg",
    "radius": "m",
    "stiffness": "N/m",
    "damping": "N s/m",
    "rest_length": "m",
    "gravity": "m/s^2",
    "mu_static": "1",
    "mu_kinetic": "1",
    "rolling_resistance": "1",
    "track_height": "m",
    "fx": "N",
    "fy": "N",
    "height": "m",
    "angle": "deg",
    "x": "m",
    "y": "m",
    "v": "m/s",
    "t0": "s",
    "x_offset": "m",
}


def _unit(name: str) -> str:
    return UNITS.get(name.split(".")[-1], "")


def fit_model(
    data: BodyData,
    system: System,
    free: Sequence[str],
    *,
    fix_initial: bool = False,
    first_guess: bool = True,
    max_evaluations: int | None = None,
    progress: Callable[[float], None] | None = None,
) -> FitResult:
    r"""Fit ``system`` to the measured ``data`` (:func:`rollspring.lab.data.match_bodies`),
    freeing the PATHs ``free`` (``springs.0.stiffness``, ``springs.0.damping``,
    ``bodies.hoop.mass``, ...) and each body's initial position and velocity (at the data's first
    time), or, with ``fix_initial``, the time ``t0`` at which the system's own initial state holds;
    ``x_offset`` where identifiable (the module's docstring). Minimises
    :math:`\sum_{jb} r_{jb}^2` (the module's docstring) from a first guess of the frequencies
    (:func:`spectral_peaks`; ``first_guess=False`` starts from the values given, for a start
    known to be close). A PATH that is no number of the system, or fewer measured points
    than fitted parameters, is a one-line :class:`~rollspring.errors.FitError`; a fit whose
    solver runs out of its budget returns with status ``not_converged`` and the best values.
    ``progress`` is told the fraction done (0..1) after the first guess and each evaluation.
    """
    from scipy.optimize import least_squares

    paths = paths_module.check_paths(system, list(free))
    json_form = paths_module.pinned_json(system)
    base = paths_module.with_values(json_form, {})
    arrays = system_arrays(base)
    n = arrays.n_bodies
    p = len(paths)
    anchored = arrays.has_anchors
    fitted = list(range(p))
    if fix_initial:
        fitted += [p + 2 * n, p + 2 * n + 1]  # t0, x_offset
    else:
        fitted += list(range(p, p + 2 * n))
        if anchored:
            fitted.append(p + 2 * n + 1)
    layout = _Layout(paths, arrays.ids, tuple(fitted))
    if data.n_points <= len(fitted):
        raise FitError(
            f"{data.source}: {data.n_points} measured positions, not more than the "
            f"{len(fitted)} fitted parameters ({', '.join(layout.names[i] for i in fitted)})"
        )
    problem = _Problem(json_form, base, data, layout)
    full = np.concatenate(
        [
            [paths_module.get_value(json_form, path) for path in paths],
            arrays.x0,
            arrays.v0,
            [data.t[0], 0.0],
        ]
    )
    if not fix_initial:
        full = _initial_from_data(problem, full)
    began = time.perf_counter()
    start = _first_guess(problem, full) if first_guess else _start_as_given(problem, full)
    if progress is not None:
        progress(0.2)
    low = np.full(full.size, -np.inf)
    high = np.full(full.size, np.inf)
    for i, path in enumerate(paths):
        low[i], high[i] = paths_module.bounds_of(path, full[i])
    index = np.asarray(fitted)
    # the solver sees t0 from the data's first time: its relative step tolerance is then one
    # of the time fitted, not of the clock's reading (an epoch time of 1.7e9 s stopped it
    # at steps of 0.17 s)
    shift = np.zeros(full.size)
    shift[p + 2 * n] = float(data.t[0])
    x_start = np.clip(start[index], low[index], high[index]) - shift[index]

    def expand(values: FloatArray) -> FloatArray:
        out = start.copy()
        out[index] = values + shift[index]
        return out

    evaluations = 0
    budget = max(1, max_evaluations or MAX_EVALUATIONS_PER_PARAMETER * (len(fitted) + 1))
    if progress is not None:
        # every evaluation of the residuals (the Jacobian's forward differences too: each a
        # simulation on the simulated route) moves it, from 0.2 towards 0.95, two thirds of
        # the way at the evaluations expected
        expected = EXPECTED_ITERATIONS * (len(fitted) + 2)
        done = 0

        def evaluated() -> None:
            nonlocal done
            done += 1
            progress(0.2 + 0.75 * (1.0 - math.exp(-done / expected)))

        problem.on_evaluation = evaluated

    def residual(values: FloatArray) -> FloatArray:
        nonlocal evaluations
        evaluations += 1
        return problem.residual(expand(values))

    def jacobian(values: FloatArray) -> FloatArray:
        return problem.jacobian(expand(values))

    tolerance = 1e-10 if problem.level else 1e-8
    if not np.all(np.isfinite(residual(x_start))):  # a trial later is a step refused
        why = problem.failure or "not finite"
        raise FitError(
            f"the model cannot be followed from the start values ({why}); give values the "
            "system runs with"
        )
    solution = least_squares(
        residual,
        x_start,
        jac=jacobian,
        bounds=(low[index] - shift[index], high[index] - shift[index]),
        x_scale="jac",
        method="trf",
        ftol=tolerance,
        xtol=tolerance,
        gtol=tolerance,
        max_nfev=budget,
    )
    best = expand(solution.x)
    status = FitStatus.CONVERGED if solution.status > 0 else FitStatus.NOT_CONVERGED
    message = (
        "the fit converged"
        if solution.status > 0
        else f"the fit did not converge within {budget} evaluations: the best values are shown"
    )
    result = _result(problem, best, status, message, evaluations, fix_initial)
    problem.on_evaluation = None
    seconds = time.perf_counter() - began
    return dataclasses.replace(result, seconds=seconds)


def _initial_from_data(problem: _Problem, full: FloatArray) -> FloatArray:
    """The measured bodies' first positions and velocities as the initial state (a start the
    first guess improves on; unmeasured bodies keep the system's)."""
    layout = problem.layout
    p, n = layout.n_paths, len(problem.ids)
    full = full.copy()
    t = problem.t
    for column, i in enumerate(problem.measured):
        x = problem.table.x[:, column]
        ok = np.isfinite(x)
        if ok.sum() >= 2:
            tt, xx = t[ok][:3], x[ok][:3]
            full[p + i] = float(np.interp(t[0], tt, xx))
            full[p + n + i] = float(np.polyfit(tt - tt[0], xx, 1)[0])
    return full


def _result(
    problem: _Problem,
    best: FloatArray,
    status: str,
    message: str,
    evaluations: int,
    fix_initial: bool,
) -> FitResult:
    """Standard errors, correlations, identifiability, residual RMS, the fitted system."""
    layout = problem.layout
    names = layout.names
    fitted = layout.fitted
    residual = problem.residual(best)
    jacobian = problem.jacobian(best)
    points, count = residual.size, len(fitted)
    dof = max(points - count, 1)
    noise = math.sqrt(float(residual @ residual) / dof)
    model_x = problem.states(best)[:, problem.measured]
    rho = residual_correlation(model_x - problem.table.x, problem.mask)
    covariance, warnings = _covariance(jacobian, noise, [names[i] for i in fitted])
    independent = covariance
    correlated = rho > 2.0 / math.sqrt(points) and bool(count)
    if correlated:
        covariance = correlated_covariance(jacobian, problem.mask, rho, independent, noise)
        with np.errstate(divide="ignore", invalid="ignore"):
            widened = float(np.nanmax(np.sqrt(np.diag(covariance) / np.diag(independent))))
        if rho > MODEL_MISMATCH_CORRELATION:
            # a smooth miss of the model and tracking errors that last several frames (a
            # textured or blurred outline, 3 s filmed at 60 fps: 0.64) look alike to each
            # statistic the fit measures of the residuals: the warning names both
            warnings.append(
                f"the residuals are not noise (lag-1 autocorrelation {rho:.2f}): either the "
                "model, as fitted, does not describe the data (free more parameters or check "
                "the system; the figure's residuals then follow the motion) or the tracking's "
                "errors last several frames (a textured or blurred outline); the standard "
                f"errors are widened up to {widened:.3g}× for it"
            )
    locked = None
    if problem.table.locked_error is not None and count:
        locked = locked_covariance(
            jacobian, problem.mask, problem.table.x, problem.table.locked_error, independent, noise
        )
        covariance = covariance + locked
    errors = np.sqrt(np.maximum(np.diag(covariance), 0.0))
    with np.errstate(divide="ignore", invalid="ignore"):
        correlation = covariance / np.outer(errors, errors)
    correlation = np.where(np.isfinite(correlation), correlation, 0.0)
    parameters: dict[str, Parameter] = {}
    for i, name in enumerate(names):
        if i in fitted:
            k = fitted.index(i)
            parameters[name] = Parameter(name, float(best[i]), float(errors[k]), False, _unit(name))
        else:
            parameters[name] = Parameter(name, float(best[i]), 0.0, True, _unit(name))
    rms = {}
    for column, body in enumerate(problem.table.bodies):
        ok = problem.mask[:, column]
        difference = model_x[ok, column] - problem.table.x[ok, column]
        rms[body] = float(np.sqrt(np.mean(difference**2)))
    fitted_system = fitted_system_of(problem, best)
    return FitResult(
        parameters=parameters,
        fitted=tuple(names[i] for i in fitted),
        covariance=covariance,
        correlation=correlation,
        residual_rms=rms,
        noise=noise,
        status=status,
        message=message,
        warnings=warnings,
        system=fitted_system,
        data=problem.table,
        model_x=model_x,
        level=problem.level,
        n_points=points,
        evaluations=evaluations,
        problem=problem,
        best=best,
        rho=rho if correlated else 0.0,
        locked=locked,
    )


def residual_correlation(residuals: FloatArray, marked: np.ndarray) -> float:
    r"""The residuals' lag-1 autocorrelation, pooled over the bodies:
    :math:`\rho = \sum_b\sum_j r_{j,b}\,r_{j+1,b} / \sum_b\sum_j r_{j,b}^2` over each body's
    consecutive marked frames (``residuals`` (N, B) model minus data, ``marked`` (N, B) where a
    frame has a mark); 0 for independent errors, near 1 for a model that misses the motion,
    clipped to [0, 0.99]."""
    pairs = marked[1:] & marked[:-1]
    current = np.where(marked, residuals, 0.0)
    lagged = float(np.sum(np.where(pairs, current[1:] * current[:-1], 0.0)))
    energy = float(np.sum(current**2))
    if energy <= 0.0:
        return 0.0
    return min(max(lagged / energy, 0.0), 0.99)


def correlated_covariance(
    jacobian: FloatArray, marked: np.ndarray, rho: float, independent: FloatArray, noise: float
) -> FloatArray:
    r"""The covariance of the least-squares estimate when each body's errors follow an AR(1)
    process in the frames, :math:`\Sigma_{ij} = s^2\rho^{|i-j|}`:
    :math:`C = (J^TJ)^{-1}J^T\Sigma J(J^TJ)^{-1} = A\,J^T\tilde\Sigma J\,A/s^2` with
    :math:`A = s^2(J^TJ)^{-1}` (``independent``, from :func:`_covariance`), :math:`s` the
    ``noise`` and :math:`\tilde\Sigma = \Sigma/s^2`. The rows of ``jacobian`` are the marked
    entries of the (frames, bodies) table ``marked`` in row-major order; :math:`\tilde\Sigma J`
    is a forward and a backward first-order filter along the frames (SciPy's ``lfilter``),
    :math:`y^f_i = J_i + \rho y^f_{i-1}`, :math:`y^b_i = J_i + \rho y^b_{i+1}`,
    :math:`\tilde\Sigma J = y^f + y^b - J` (an unmarked frame counts in the lag). Where a
    direction is not constrained (infinite variances) the long-run factor
    :math:`(1+\rho)/(1-\rho)` widens what is finite."""
    from scipy.signal import lfilter

    if not np.isfinite(independent).all() or noise <= 0.0:
        return independent * ((1.0 + rho) / (1.0 - rho))
    table = np.zeros((*marked.shape, jacobian.shape[1]))
    table[marked] = jacobian
    forward = lfilter([1.0], [1.0, -rho], table, axis=0)
    backward = lfilter([1.0], [1.0, -rho], table[::-1], axis=0)[::-1]
    filtered = (forward + backward - table)[marked]
    meat = jacobian.T @ filtered
    return np.asarray(independent @ meat @ independent, dtype=float) / noise**2


def locked_covariance(
    jacobian: FloatArray,
    marked: np.ndarray,
    x: FloatArray,
    locked: FloatArray,
    independent: FloatArray,
    noise: float,
) -> FloatArray:
    r"""The parameters' covariance from each body's error locked to its position (``track``'s
    ``xlocked_<id>``, :func:`rollspring.lab.tracking.locked_error`): body :math:`b`'s tracked
    positions carry an error :math:`e_b(x)`, a smooth function of the position that the fit
    cannot see (a swing scaled by :math:`1 + \epsilon` is another initial state), of RMS
    :math:`\sigma_b` (``locked``) over the positions measured. Written as
    :math:`e_b = \sum_{m=1}^{3} a_{bm}P_m(	ilde x)` (Legendre polynomials of the position
    scaled to [-1, 1] over the body's range) with independent coefficients of variance
    :math:`\sigma_b^2(2m+1)/3` (an RMS of :math:`\sigma_b` shared alike), each moves the
    estimate by :math:`\delta p = (J^TJ)^{-1}J^Tu_{bm}a_{bm}`, :math:`u_{bm}` the values of
    :math:`P_m` at the body's rows (zero on the others'), so that

    .. math:: C_e = \sum_{b,m} rac{(2m+1)\sigma_b^2}{3}\,v_{bm}v_{bm}^T, \qquad
              v_{bm} = A J^T u_{bm} / s^2

    with :math:`A = s^2(J^TJ)^{-1}` (``independent``) and :math:`s` the ``noise``; added to the
    fit's covariance, it reaches every standard error and the claims'. Rows of ``jacobian`` as
    in :func:`correlated_covariance`; zero where :math:`A` is not finite or :math:`s = 0`."""
    from numpy.polynomial import legendre

    count = jacobian.shape[1]
    total = np.zeros((count, count))
    if noise <= 0.0 or not np.isfinite(independent).all():
        return total
    for b, sigmas in enumerate(np.asarray(locked, dtype=float)):
        rows = marked[:, b]
        position = x[rows, b]
        width = float(np.ptp(position)) if rows.sum() >= 2 else 0.0
        if not (np.all(np.isfinite(sigmas)) and np.any(sigmas > 0.0)) or width <= 0.0:
            continue
        basis = legendre.legvander(2.0 * (position - position.min()) / width - 1.0, sigmas.size)
        for m, sigma in enumerate(sigmas, start=1):
            shape = np.zeros(marked.shape)
            shape[rows, b] = basis[:, m]
            v = independent @ (jacobian.T @ shape[marked]) / noise**2
            total += sigma**2 * np.outer(v, v)
    return total


def _covariance(
    jacobian: FloatArray, noise: float, names: Sequence[str]
) -> tuple[FloatArray, list[str]]:
    r""":math:`s^2 (J^TJ)^{-1}` from the eigen-decomposition of the column-normalised
    :math:`\tilde J^T\tilde J = V\Sigma^2V^T` (the singular values and right singular vectors
    of :math:`\tilde J`; the small p × p problem, not a factorisation of the tall Jacobian,
    whose LAPACK call is a hundred times slower on a machine whose cores are busy), and a warning
    for each direction of parameter space the data do not constrain (a singular value below
    :math:`1/` :data:`IDENTIFIABLE_CONDITION` of the largest): the combination named by its
    right singular vector, in units of each parameter's column scale."""
    count = jacobian.shape[1]
    if count == 0:
        return np.zeros((0, 0)), []
    scale = np.sqrt(np.einsum("ij,ij->j", jacobian, jacobian))
    scale = np.where(scale > 0, scale, 1.0)
    normalised_j = jacobian / scale
    values, vectors = np.linalg.eigh(normalised_j.T @ normalised_j)
    order = np.argsort(values)[::-1]
    singular = np.sqrt(np.maximum(values[order], 0.0))
    vt = vectors[:, order].T
    warnings = []
    largest = float(singular[0]) if singular.size else 0.0
    keep = singular > largest / IDENTIFIABLE_CONDITION
    for k in np.flatnonzero(~keep):
        vector = vt[k]
        terms = [
            f"{vector[i]:+.2f}·{names[i]}"
            for i in np.argsort(-np.abs(vector))
            if abs(vector[i]) >= 0.1
        ]
        warnings.append(
            "not identifiable: the data do not constrain the combination "
            + " ".join(terms)
            + " (each in units of its sensitivity); fix one of them or add data that separates them"
        )
    inverse = np.where(keep, 1.0 / np.where(keep, singular, 1.0) ** 2, np.inf)
    with np.errstate(invalid="ignore"):
        normalised = (vt.T * np.where(np.isfinite(inverse), inverse, 0.0)) @ vt
    covariance = noise**2 * normalised / np.outer(scale, scale)
    if not keep.all():  # the unconstrained directions: infinite variance along them
        for k in np.flatnonzero(~keep):
            involved = np.abs(vt[k]) >= 0.1
            covariance[involved, involved] = np.inf
    return covariance, warnings


def fitted_system_of(problem: _Problem, full: FloatArray) -> System:
    """The fitted system: the PATHs' values, each body's initial position (the system's x
    origin: the offset removed) and velocity at the data's first time (or the system's own with
    ``fix_initial``), every rest length written out."""
    theta, x0, v0, _, _ = problem.layout.split(full)
    return problem._with_state(theta, x0, v0)

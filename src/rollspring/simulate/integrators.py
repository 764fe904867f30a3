r"""The explicit symplectic integrators, shared by single runs, batches and sweeps.

While every body rolls the Hamiltonian is separable with a constant diagonal mass matrix
(docs/physics.md (M6)), so symmetric compositions of the kick-drift-kick leapfrog with stage weights
:math:`w_k` are explicit and symplectic (Yoshida 1990; Kahan and Li 1997). Each
:class:`Integrator` carries its order :math:`p` and the constant :math:`C_p` of its relative
frequency error :math:`C_p(\omega h)^p` (Verlet's 1/24 exact; the others measured on the
harmonic oscillator), from which the step for a tolerance follows (:meth:`Integrator.omega_step`,
the phase error over the run, what batches and sweeps use).

A single run (:func:`rollspring.simulate`) keeps the accuracy contract (README, "Accuracy"):
every output position and velocity within :math:`\mathrm{rtol}\,|\text{value}| +
\mathrm{rtol}/10\cdot\text{scale}` (scale: that quantity's largest |value| over the run). Its
step (:meth:`Integrator.contract_step`) is chosen for rtol/10: the phase error over the run
(:meth:`Integrator.phase_omega_step`) and, where outputs fall inside steps, the error of the
septic Hermite interpolant that gives them (:func:`output_omega_step`), each shrunk by a safety
factor measured on random nonlinear systems (``bench/bench_accuracy.py``; the motion's harmonics
above the fastest linear frequency make both errors larger than on a harmonic oscillator): per
scheme for the phase (:attr:`Integrator.safety`), :data:`OUTPUT_SAFETY` for the interpolant.
When it takes fewer steps, the step is instead rounded down to a whole fraction of the output
spacing, so that every output lands on a step end and only the phase bound applies.
:func:`choose_scheme` picks the scheme and step of a single run (and of its cost estimate,
:mod:`rollspring.simulate.costs`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from rollspring.errors import SimulationError

__all__ = [
    "CONTRACT_SHARE",
    "HERMITE_POSITION",
    "HERMITE_VELOCITY",
    "INTEGRATORS",
    "MAX_OMEGA_STEP",
    "OUTPUT_SAFETY",
    "Integrator",
    "choose_scheme",
    "output_omega_step",
    "refinement_radius",
]

#: Largest omega*h any scheme may use (well inside every scheme's stability interval, and at
#: least 12 steps per period of the fastest mode).
MAX_OMEGA_STEP = 0.5
#: The septic Hermite interpolant of a step (positions, velocities, accelerations and jerks at
#: both ends) errs by at most (omega h)^8 / 10321920 of the amplitude in position (8! 2^8) and
#: (omega h)^7 / 2710000 of the velocity amplitude in velocity (8! / max|d/dθ θ⁴(1-θ)⁴|, as
#: measured on sin t).
HERMITE_POSITION, HERMITE_VELOCITY = 10321920.0, 2.71e6
#: The contract's share of rtol the step is chosen for: its absolute term, rtol/10 of the scale.
CONTRACT_SHARE = 0.1
#: Factor on omega h of the interpolated outputs: the interpolant's error on the nonlinear test
#: set (bench/bench_accuracy.py), at most 0.4 of the contract with this factor (0.545 needed:
#: the motion's harmonics above omega make the error about 28 times the sine's at rtol 1e-10).
OUTPUT_SAFETY = 0.54


def output_omega_step(rtol: float) -> float:
    r""":math:`\omega h` at which the interpolated outputs between step ends keep the contract:
    :data:`OUTPUT_SAFETY` times the largest :math:`\omega h` with
    :math:`(\omega h)^8/10321920` and :math:`(\omega h)^7/2710000` at most rtol/10."""
    target = CONTRACT_SHARE * rtol
    result: float = OUTPUT_SAFETY * min(
        (HERMITE_POSITION * target) ** (1.0 / 8.0), (HERMITE_VELOCITY * target) ** (1.0 / 7.0)
    )
    return result


@dataclass(frozen=True)
class Integrator:
    """A symmetric composition of leapfrog stages: ``coefficients`` are the stage weights
    (summing to 1), ``order`` its order p, ``error_constant`` C_p of the relative frequency
    error C_p (omega h)^p, ``safety`` the factor on omega h that keeps a single run's contract
    (measured: see the module docstring)."""

    name: str
    order: int
    error_constant: float
    coefficients: tuple[float, ...]
    safety: float = 1.0

    @property
    def stages(self) -> int:
        """Force evaluations per step."""
        return len(self.coefficients)

    @property
    def weights(self) -> np.ndarray:
        """The stage weights as a new float array (what the kernels take)."""
        return np.array(self.coefficients, dtype=np.float64)

    def omega_step(self, rtol: float, radians: float) -> float:
        r""":math:`\omega h` for a phase error of at most ``rtol`` after ``radians`` of the
        fastest mode: :math:`C_p(\omega h)^p\,\text{radians} \le \text{rtol}`, capped at
        :data:`MAX_OMEGA_STEP`."""
        result: float = min(
            (rtol / (self.error_constant * radians)) ** (1.0 / self.order), MAX_OMEGA_STEP
        )
        return result

    def phase_omega_step(self, rtol: float, radians: float) -> float:
        r""":math:`\omega h` of a single run's phase: :attr:`safety` times the step of a phase
        error of rtol/10 after ``radians`` of the fastest mode, at most
        :data:`MAX_OMEGA_STEP`."""
        phase = (CONTRACT_SHARE * rtol / (self.error_constant * radians)) ** (1.0 / self.order)
        result: float = min(self.safety * phase, MAX_OMEGA_STEP)
        return result

    def contract_omega_step(self, rtol: float, radians: float) -> float:
        r""":math:`\omega h` of a single run whose outputs are interpolated inside the steps:
        :meth:`phase_omega_step`, at most :func:`output_omega_step`."""
        return min(self.phase_omega_step(rtol, radians), output_omega_step(rtol))

    def contract_step(
        self, omega: float, duration: float, rtol: float, n_output: int | None = None
    ) -> float:
        r"""The step h (s) of a single run (:func:`rollspring.simulate`) that keeps the accuracy
        contract over ``duration`` with fastest linear frequency ``omega``: outputs
        interpolated inside the steps (:meth:`contract_omega_step`) or, with ``n_output``
        evenly spaced outputs, the phase step alone rounded down so that every output lands on
        a step end (no interpolation): whichever takes fewer steps."""
        if omega <= 0:
            return duration
        radians = max(omega * duration, 2 * math.pi)
        interpolated = self.contract_omega_step(rtol, radians) / omega
        if n_output is None or n_output < 2:
            return interpolated
        spacing = duration / (n_output - 1)
        per_output = max(
            1, math.ceil(spacing * omega / self.phase_omega_step(rtol, radians) - 1e-9)
        )
        steps_interpolated = math.ceil(duration / interpolated * (1 - 1e-12))
        if (n_output - 1) * per_output <= steps_interpolated:
            return spacing / per_output
        return interpolated


def _symmetric(outer: tuple[float, ...]) -> tuple[float, ...]:
    """Weights w_1..w_m, w_0 = 1 - 2 sum w, w_m..w_1 of a symmetric composition."""
    return (*outer, 1.0 - 2.0 * sum(outer), *outer[::-1])


_Y4 = 1.0 / (2.0 - 2.0 ** (1.0 / 3.0))
_Y6 = (0.784513610477560, 0.235573213359357, -1.17767998417887)  # Yoshida 1990, solution A
_KL8 = (
    0.74167036435061295345,
    -0.40910082580003159400,
    0.19075471029623837995,
    -0.57386247111608226666,
    0.29906418130365592384,
    0.33462491824529818378,
    0.31529309239676659663,
)  # Kahan and Li 1997

#: name -> :class:`Integrator`, lowest order first. The safety factors: the largest factor on
#: omega h that brings the integration error (outputs on step ends) of every run of the test set
#: to 0.4 of the contract at rtol 1e-4 ... 1e-10 (bench/bench_accuracy.py, part A).
INTEGRATORS: dict[str, Integrator] = {
    integrator.name: integrator
    for integrator in (
        Integrator("verlet", 2, 1.0 / 24.0, (1.0,), safety=0.40),
        Integrator("yoshida4", 4, 0.0662, _symmetric((_Y4,)), safety=0.65),
        Integrator("yoshida6", 6, 0.00377, _symmetric(_Y6), safety=0.76),
        Integrator("kahanli8", 8, 4.8e-6, _symmetric(_KL8), safety=0.82),
    )
}

assert all(math.isclose(sum(i.coefficients), 1.0) for i in INTEGRATORS.values())


def refinement_radius(stages: int) -> int:
    """The radius (in springs) of the ball a refinement of a scheme of ``stages`` stages needs
    (:func:`~rollspring.simulate.kernels.refine_windowed`): every force evaluation carries a
    change one spring further, and a refinement takes at most two steps of the scheme's stages
    after the evaluation at its start; the ball reaches a spring further than that,
    ``2 stages + 2``."""
    return 2 * stages + 2


def choose_scheme(
    omega: float,
    duration: float,
    rtol: float,
    integrator: str = "auto",
    n_output: int | None = None,
) -> tuple[str, float]:
    r"""The scheme and step for a run, within the accuracy contract (README, "Accuracy"):
    :meth:`~rollspring.simulate.integrators.Integrator.contract_step` -- a phase error of
    rtol/10 after :math:`\omega T` radians and outputs interpolated inside the steps within
    rtol/10 (or, with ``n_output`` evenly spaced outputs, outputs on step ends when that takes
    fewer steps), each shrunk by its measured safety factor; :math:`\omega h` at most 0.5.
    ``auto`` takes the scheme with the fewest force evaluations, counting the force rates a step
    holding interpolated outputs takes as one more (the septic interpolant's jerks). Returns
    ``(name, h)``."""
    names = list(INTEGRATORS) if integrator == "auto" else [integrator]
    best: tuple[str, float, float] | None = None
    for name in names:
        scheme = INTEGRATORS[name]
        step = scheme.contract_step(omega, duration, rtol, n_output)
        if not step > 0:  # a duration so long that the contract's step underflows
            return name, step
        per_output = duration / (n_output - 1) / step if n_output and n_output > 1 else 0.5
        on_step_ends = abs(per_output - round(per_output)) <= 1e-9 * per_output
        cost = (scheme.stages + (0 if on_step_ends else 1)) * duration / step
        if best is None or cost < best[2]:
            best = (name, step, cost)
    assert best is not None  # names is never empty
    return best[0], best[1]


def pick_scheme(
    integrator: str,
    step: float | None,
    damped: bool,
    omega: float,
    duration: float,
    rtol: float,
    n_output: int | None = None,
) -> tuple[str, float | None]:
    """The integrator and step of a run: DOP853 (no fixed step) when a spring is damped or it is
    asked for; a fixed ``step`` with ``auto`` means Yoshida-4; else :func:`choose_scheme` for
    the fastest linear frequency ``omega`` (and the ``n_output`` output times). The run's set-up
    and its cost estimate both choose here."""
    if damped or integrator == "dop853":
        return "dop853", None
    if step is not None:
        return ("yoshida4" if integrator == "auto" else integrator), _resolved(duration, step)
    name, chosen = choose_scheme(omega, duration, rtol, integrator, n_output)
    return name, _resolved(duration, chosen)


#: The most fixed steps a run may take: beyond about 2^52 / 1024, the time t = n h rounds by more
#: than a thousandth of a step in double precision (its spacing at t is t 2^-52), and the steps
#: no longer follow each other as the scheme assumes.
MAX_STEPS = 2.0**52 / 1024


def _resolved(duration: float, step: float) -> float:
    """``step``, when ``duration`` takes at most :data:`MAX_STEPS` of it; else the one-line
    error (even with ``--yes``: no run of that length can be computed in double precision)."""
    steps = duration / step if step > 0 else math.inf
    if not steps <= MAX_STEPS:
        count = f"about {steps:.2g}" if math.isfinite(steps) else "more than 1e308"
        raise SimulationError(
            f"duration: {duration:.3g} s needs {count} steps of {step:.3g} s, beyond the "
            f"{MAX_STEPS:.2g} whose times double precision resolves; a shorter duration"
        )
    return step

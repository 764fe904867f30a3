r"""The explicit symplectic integrators, shared by single runs, batches and sweeps.

While every body rolls the Hamiltonian is separable with a constant diagonal mass matrix
(docs/physics.md (M6)), so symmetric compositions of the kick-drift-kick leapfrog with stage weights
:math:`w_k` are explicit and symplectic (Yoshida 1990; Kahan and Li 1997). Each
:class:`Integrator` carries its order :math:`p` and the constant :math:`C_p` of its relative
frequency error :math:`C_p(\omega h)^p` (Verlet's 1/24 exact; the others measured on the
harmonic oscillator), from which the step for a tolerance follows (:meth:`Integrator.omega_step`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

__all__ = ["INTEGRATORS", "MAX_OMEGA_STEP", "Integrator"]

#: Largest omega*h any scheme may use (well inside every scheme's stability interval, and at
#: least 12 steps per period of the fastest mode).
MAX_OMEGA_STEP = 0.5


@dataclass(frozen=True)
class Integrator:
    """A symmetric composition of leapfrog stages: ``coefficients`` are the stage weights
    (summing to 1), ``order`` its order p, ``error_constant`` C_p of the relative frequency
    error C_p (omega h)^p."""

    name: str
    order: int
    error_constant: float
    coefficients: tuple[float, ...]

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

#: name -> :class:`Integrator`, lowest order first.
INTEGRATORS: dict[str, Integrator] = {
    integrator.name: integrator
    for integrator in (
        Integrator("verlet", 2, 1.0 / 24.0, (1.0,)),
        Integrator("yoshida4", 4, 0.0662, _symmetric((_Y4,))),
        Integrator("yoshida6", 6, 0.00377, _symmetric(_Y6)),
        Integrator("kahanli8", 8, 4.8e-6, _symmetric(_KL8)),
    )
}

assert all(math.isclose(sum(i.coefficients), 1.0) for i in INTEGRATORS.values())

"""Simulation: the exact nonlinear motion (symplectic, compiled), slip and lift-off to the
instant, stick-slip with kinetic friction, and batches of runs.

The package itself is callable: ``rollspring.simulate(system, duration, ...)`` is
:func:`rollspring.simulate.run.simulate`, while ``rollspring.simulate.kernels`` and friends stay
importable as usual.
"""

import sys
import types
from typing import Any

from rollspring.simulate.batch import BatchResult, simulate_batch
from rollspring.simulate.integrators import Integrator
from rollspring.simulate.run import INTEGRATORS, Trajectory, choose_scheme, simulate
from rollspring.simulate.status import Status

# ``INTEGRATORS`` here is the tuple of names ``simulate`` accepts; the integrator objects are
# ``rollspring.simulate.integrators.INTEGRATORS``.
__all__ = [
    "INTEGRATORS",
    "BatchResult",
    "Integrator",
    "Status",
    "Trajectory",
    "choose_scheme",
    "simulate",
    "simulate_batch",
]


class _CallableModule(types.ModuleType):
    """This package, callable as :func:`simulate`."""

    def __call__(self, *args: Any, **kwargs: Any) -> Any:
        return simulate(*args, **kwargs)


sys.modules[__name__].__class__ = _CallableModule

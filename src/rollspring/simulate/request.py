"""A simulation's arguments, checked once: :class:`SimulationRequest`.

:func:`simulation_request` checks the arguments of :func:`rollspring.simulate` with the shared
validator (:mod:`rollspring.simulate.arguments`: one-line
:class:`~rollspring.errors.SimulationError` messages naming the argument, the command line's
words for the same mistake) and returns them as one frozen request. The cost estimate
(:func:`rollspring.simulate.costs.request_cost`), the set-up
(:func:`rollspring.simulate.setup.plan`) and the interfaces
(:func:`rollspring.service.runs.run_simulation`) take that request: nothing downstream checks the
arguments again.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

from rollspring.simulate import arguments
from rollspring.simulate.arguments import ON_SLIP
from rollspring.simulate.integrators import INTEGRATORS as SCHEMES

__all__ = ["DEFAULT_OUTPUTS", "INTEGRATORS", "SimulationRequest", "simulation_request"]

#: Accepted values of ``integrator`` (the symplectic schemes are
#: :data:`rollspring.simulate.integrators.INTEGRATORS`).
INTEGRATORS = ("auto", *SCHEMES, "dop853")
#: output times of a run that does not say (``n_output=None``)
DEFAULT_OUTPUTS = 2001


@dataclass(frozen=True, slots=True)
class SimulationRequest:
    """The checked arguments of one run of :func:`rollspring.simulate` (see there)."""

    #: seconds of motion, > 0 and finite
    duration: float
    #: the accuracy contract, within :data:`~rollspring.analysis.costs.RTOL_RANGE`
    rtol: float
    #: one of :data:`INTEGRATORS`
    integrator: str
    #: one of :data:`~rollspring.simulate.arguments.ON_SLIP`
    on_slip: str
    #: evenly spaced output times (>= 2), None for :data:`DEFAULT_OUTPUTS`
    n_output: int | None
    #: a fixed symplectic step (s, up to ``duration``), None for the contract's choice
    step: float | None
    #: the relative energy error a run may reach, None for ``100 rtol + 1e-12``
    energy_tolerance: Any

    @property
    def outputs(self) -> int:
        """The number of output times (``n_output``, or :data:`DEFAULT_OUTPUTS`)."""
        return DEFAULT_OUTPUTS if self.n_output is None else self.n_output


def simulation_request(
    duration: Any,
    *,
    rtol: Any = 1e-8,
    integrator: Any = "auto",
    on_slip: Any = "stop",
    n_output: Any = None,
    energy_tolerance: Any = None,
    step: Any = None,
) -> SimulationRequest:
    """The arguments of :func:`rollspring.simulate` checked, in this order (the first bad one is
    the error): ``duration``, ``rtol``, ``integrator``, ``on_slip``, ``n_output``,
    ``energy_tolerance``, ``step``."""
    duration = arguments.check_duration(duration)
    rtol = arguments.check_rtol_range(rtol)
    arguments.check_choice("integrator", integrator, INTEGRATORS, "integrator")
    arguments.check_choice("on_slip", on_slip, ON_SLIP, "on_slip")
    count = arguments.check_count("n_output", n_output, 2, optional=True)
    arguments.check_energy_tolerance(energy_tolerance)
    return SimulationRequest(
        duration=duration,
        rtol=rtol,
        integrator=integrator,
        on_slip=on_slip,
        n_output=count,
        step=arguments.check_step(step, duration),
        energy_tolerance=energy_tolerance,
    )

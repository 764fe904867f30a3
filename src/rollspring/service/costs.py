"""What a run will cost, known before it starts: steps × bodies, seconds, memory.

The command line refuses a run whose estimate is above a sane bound unless the user confirms it
(``--yes``), and says how long a confirmed long run should take; the estimate is made in well
under a second, before any long work. The Python API refuses the same runs with the same
message, unless called with ``confirm=True``: the estimates live with what they estimate, and
this module gathers them for the command line.

* A simulation (:func:`request_cost`, :mod:`rollspring.simulate.costs`): its step comes from
  the highest linear frequency at the initial placement and ``rtol``, exactly as
  :func:`rollspring.simulate.choose_scheme` chooses it (the compiled symplectic schemes); damped
  springs run DOP853, whose adaptive steps are estimated from the same frequency. Seconds
  follow from steps × (bodies + springs) at the measured cost of a body and step
  (docs/system-files.md), memory from the output arrays (and the CSV text when files are
  written).
* An analysis (:func:`analysis_cost`, :mod:`rollspring.analysis.costs`): its time grows with the
  cube of the number of bodies (dense matrices of the modes and the friction each body needs),
  measured on chains: 1 s for 100 bodies, 6 min for 1000.
* A derivation (:func:`derivation_cost`, SymPy) as n^1.5; a report (:func:`report_cost`) is an
  analysis, a simulation of at most 20 s and, unless left out, a derivation; a long chain's
  report is its simulation and about 15 s of drawing.

The constants are measurements on a laptop core (``bench/``), rounded up: an estimate is meant
to be right within a factor of a few, enough to tell seconds from days.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

from rollspring.analysis import costs as guard
from rollspring.analysis.costs import CONFIRM as CONFIRM
from rollspring.analysis.costs import MAX_MEMORY as MAX_MEMORY
from rollspring.analysis.costs import MAX_SECONDS as MAX_SECONDS
from rollspring.analysis.costs import RTOL_RANGE as RTOL_RANGE
from rollspring.analysis.costs import Cost as Cost
from rollspring.analysis.costs import analysis_cost as analysis_cost
from rollspring.analysis.costs import check_cost as check_cost
from rollspring.analysis.costs import derivation_cost as derivation_cost
from rollspring.model import System

if TYPE_CHECKING:
    from rollspring.simulate.request import SimulationRequest

#: the cost guard's names (:mod:`rollspring.analysis.costs`), and the estimates gathered here
__all__ = ["report_cost", "request_cost"]
__all__ += guard.__all__

#: the longest simulation a report makes by itself (its default duration), s
_REPORT_DURATION = 20.0
#: how to make a report smaller, in the command line's words and in Python's
_REPORT_SMALLER = {
    "--yes": "a shorter --duration, fewer bodies",
    CONFIRM: "a shorter duration, fewer bodies",
}


def request_cost(
    system: System, request: SimulationRequest, *, written: bool = False, what: str = "this run"
) -> Cost:
    """The estimated cost of a run whose arguments are checked already
    (:func:`rollspring.simulate.request.simulation_request`), its files too when ``written``,
    in the command line's words (:func:`rollspring.simulate.costs.request_cost`, loaded on first
    use: the compiled kernels are not for ``rollspring analyze``): nothing is checked again."""
    from rollspring.simulate.costs import request_cost as estimate

    return estimate(system, request, written=written, what=what)


def report_cost(
    system: System,
    *,
    duration: Any = None,
    derivation: bool = True,
    what: str = "the report",
    flag: str = "--yes",
) -> Cost:
    """The estimated cost of :func:`rollspring.build_report` on ``system``: the analysis, the
    simulation (``duration``, default at most 20 s) and, with ``derivation``, the derivation.
    ``flag`` is how the run is confirmed (``--yes``, or ``confirm=True`` in Python): the words
    of the message that says how to make it smaller."""
    from rollspring.model.chains import LONG_CHAIN
    from rollspring.simulate.request import simulation_request

    run = request_cost(
        system, simulation_request(_REPORT_DURATION if duration is None else duration), what=what
    )
    if len(system.bodies) > LONG_CHAIN:  # a long chain's summary: no analysis, no derivation
        seconds = 15.0 + run.seconds
        smaller = _REPORT_SMALLER.get(flag, _REPORT_SMALLER["--yes"])
        return Cost(what, run.bodies, seconds, run.memory, smaller=smaller)
    seconds = 5.0 + analysis_cost(system).seconds + run.seconds
    if derivation:
        seconds += derivation_cost(system).seconds
    smaller = _REPORT_SMALLER.get(flag, _REPORT_SMALLER["--yes"])
    return Cost(what, run.bodies, seconds, run.memory, smaller=smaller)

"""One validator for the arguments of :func:`~rollspring.simulate.simulate` and
:func:`~rollspring.simulate.simulate_batch`: every bad value is a
:class:`~rollspring.errors.SimulationError` whose message starts with the argument's name.

Numbers may be Python or NumPy numbers (``np.float64``, ``np.int64``); booleans are refused
everywhere (``True`` is not a duration, nor a count).
"""

from __future__ import annotations

import math
import numbers
import os
from collections.abc import Iterable
from typing import TYPE_CHECKING, Any, Literal, TypeAlias, overload

import numpy as np

from rollspring.errors import SimulationError

if TYPE_CHECKING:
    from rollspring.model import System

__all__ = [
    "MIN_DURATION",
    "ON_SLIP",
    "SystemLike",
    "check_choice",
    "check_count",
    "check_duration",
    "check_flag",
    "check_positive",
    "check_rtol",
    "check_rtol_range",
    "check_step",
]

#: Accepted values of ``on_slip``.
ON_SLIP = ("stop", "continue")

#: What the public functions take as a system: a System, its JSON form (a dict), or a file path
#: or preset name (:func:`rollspring.model.as_system` turns each into a System, or says why not).
SystemLike: TypeAlias = "System | dict[str, Any] | str | os.PathLike[str]"


def _bad(name: str, reason: str) -> SimulationError:
    return SimulationError(f"{name}: {reason}")


def _real(value: Any) -> float | None:
    """``value`` as a float if it is a real number (not a bool), else None."""
    if isinstance(value, bool | np.bool_) or not isinstance(value, numbers.Real):
        return None
    number: Any = value  # a Real: float() takes it, and an integer compares with 0
    try:
        return float(number)
    except OverflowError:  # an integer beyond double precision: an infinity, refused as one
        return math.inf if number > 0 else -math.inf


#: The shortest duration a run takes (s): far below any motion of these systems, and above
#: the subnormal numbers, whose steps come out non-finite.
MIN_DURATION = 1e-9


def check_duration(duration: Any) -> float:
    """A finite number of seconds, at least :data:`MIN_DURATION`."""
    value = _real(duration)
    if value is None or not math.isfinite(value) or value <= 0:
        raise _bad("duration", f"must be a positive number of seconds, got {duration!r}")
    if value < MIN_DURATION:
        raise _bad("duration", f"must be at least {MIN_DURATION:g} s, got {duration!r}")
    return value


def check_rtol(rtol: Any) -> float:
    """A number in (0, 1)."""
    value = _real(rtol)
    if value is None or not math.isfinite(value) or not 0 < value < 1:
        raise _bad("rtol", f"must be a number in (0, 1), got {rtol!r}")
    return value


def check_rtol_range(rtol: Any) -> float:
    """A number within :data:`~rollspring.analysis.costs.RTOL_RANGE` (what
    :func:`~rollspring.simulate.simulate` and the command line accept: finer is below what
    double precision delivers over a run, coarser is no accuracy)."""
    from rollspring.analysis.costs import RTOL_RANGE

    value = check_rtol(rtol)
    low, high = RTOL_RANGE
    if not low <= value <= high:
        raise _bad(
            "rtol",
            f"must be between {low:g} and {high:g} (finer is below what double precision "
            f"delivers), got {rtol!r}",
        )
    return value


def check_step(step: Any, duration: float) -> float | None:
    """None, or a positive number of seconds up to ``duration``."""
    if step is None:
        return None
    value = _real(step)
    if value is None or not math.isfinite(value) or not 0 < value <= duration:
        raise _bad("step", f"must be a positive number of seconds up to the duration, got {step!r}")
    return value


@overload
def check_count(name: str, value: Any, minimum: int, *, optional: Literal[False] = ...) -> int: ...
@overload
def check_count(name: str, value: Any, minimum: int, *, optional: bool) -> int | None: ...
def check_count(name: str, value: Any, minimum: int, *, optional: bool = False) -> int | None:
    """An integer (Python or NumPy, not a bool) of at least ``minimum``; None if ``optional``."""
    if value is None and optional:
        return None
    if (
        isinstance(value, bool | np.bool_)
        or not isinstance(value, numbers.Integral)
        or value < minimum
    ):
        raise _bad(name, f"must be an integer >= {minimum}, got {value!r}")
    return int(value)


def check_flag(name: str, value: Any) -> bool:
    """True or False (a Python or NumPy bool): ``confirm=1`` or ``confirm="yes"`` is refused
    rather than read as a yes."""
    if not isinstance(value, bool | np.bool_):
        raise _bad(name, f"must be True or False, got {value!r}")
    return bool(value)


def check_choice(name: str, value: Any, choices: Iterable[str], what: str) -> str:
    """One of ``choices`` (``what`` names the kind, for the message)."""
    choices = tuple(choices)
    if not isinstance(value, str) or value not in choices:
        if name == "on_slip":
            raise _bad(name, f"must be {' or '.join(repr(c) for c in choices)}, got {value!r}")
        raise _bad(name, f"unknown {what} {value!r}; choose one of {', '.join(choices)}")
    return value


#: The smallest relative energy error a run can be held to: double precision rounds every step
#: at about 1e-16, and a run of 1e4 to 1e8 steps accumulates that to about 1e-12 (the constant
#: floor of the default tolerance, 100 rtol + 1e-12). A smaller tolerance would only shrink the
#: step again and again, each retry longer, and never pass.
ENERGY_TOLERANCE_FLOOR = 1e-12


def check_energy_tolerance(value: Any) -> float | None:
    """None (the default, 100 rtol + 1e-12), or a relative energy error of at least
    :data:`ENERGY_TOLERANCE_FLOOR` (what double precision can give over a run)."""
    number = check_positive("energy_tolerance", value, optional=True)
    if number is not None and number < ENERGY_TOLERANCE_FLOOR:
        raise _bad(
            "energy_tolerance",
            f"{value!r} is below what double precision can hold a run to; the attainable "
            f"relative energy error is about {ENERGY_TOLERANCE_FLOOR:g}",
        )
    return number


def check_callback(name: str, value: Any) -> Any:
    """None or a function (``progress``): checked before the run, not when first called."""
    if value is not None and not callable(value):
        raise _bad(name, f"must be a function or None, got {type(value).__name__}")
    return value


def check_positive(name: str, value: Any, *, optional: bool = False) -> float | None:
    """A positive number (None if ``optional``)."""
    if value is None and optional:
        return None
    number = _real(value)
    if number is None or not number > 0 or math.isnan(number):
        raise _bad(name, f"must be a positive number, got {value!r}")
    return number

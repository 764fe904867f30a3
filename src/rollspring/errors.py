"""Exceptions raised by rollspring.

Every error carries a one-line message meant for a person: it names the field or the
argument and the reason. The command-line interface prints it and exits with code 2.

::

    RollspringError
    ├── ModelError          an invalid system: a file, a value, a preset name
    └── AnalysisError       the analysis cannot be carried out (e.g. no equilibrium)
"""

from __future__ import annotations

__all__ = ["AnalysisError", "ModelError", "RollspringError", "SimulationError"]


class RollspringError(Exception):
    """Base class of every error rollspring raises on purpose."""


class ModelError(RollspringError, ValueError):
    """The description of a system is invalid (a file, a value, a preset name)."""


class AnalysisError(RollspringError):
    """An analysis cannot be carried out for this system."""


class SimulationError(RollspringError, ValueError):
    """A simulation was requested with invalid arguments (duration, tolerance, integrator)."""

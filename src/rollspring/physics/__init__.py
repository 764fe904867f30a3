"""Exact rolling physics: pure, vectorised functions of a system (as arrays) and a state."""

from rollspring.physics import mechanics
from rollspring.physics.arrays import SystemArrays, system_arrays
from rollspring.physics.mechanics import *  # noqa: F403 - the names of mechanics.__all__

#: the arrays of a system, and every function of mechanics (its ``__all__``)
__all__ = ["SystemArrays", "system_arrays", *mechanics.__all__]

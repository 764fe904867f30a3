"""Analysis: linearisation, normal modes, the stationary point, the linear response."""

from rollspring.analysis.batch_linear import BatchLinear, batch_linear
from rollspring.analysis.linear import (
    ZERO_MODE_TOLERANCE,
    Equilibrium,
    LinearAnalysis,
    Mode,
    find_equilibrium,
    linear_motion,
    normal_modes,
    stationary_weights,
)
from rollspring.analysis.modal import analyze

__all__ = [
    "ZERO_MODE_TOLERANCE",
    "BatchLinear",
    "Equilibrium",
    "LinearAnalysis",
    "Mode",
    "analyze",
    "batch_linear",
    "find_equilibrium",
    "linear_motion",
    "normal_modes",
    "stationary_weights",
]

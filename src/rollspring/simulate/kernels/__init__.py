r"""Compiled (Numba) kernels: the exact rolling equations and explicit symplectic integrators.

The rolling state (every body rolls) is one angle per body and its rate, stepped by explicit
symplectic compositions of the leapfrog (:mod:`.stepping`). The general state (any body may
slip) is per body the centre position :math:`x_i`, the rotation :math:`\varphi_i` from the
initial placement, the centre velocity :math:`u_i` and the angular velocity :math:`\omega_i`
(clockwise positive) (:mod:`.observation`). Both take their forces from one law
(:mod:`.law`, docs/force-law.md) and the model as a tuple of flat arrays (:func:`kernel_model`);
tests check the kernels against :mod:`rollspring.physics` to rounding.

The package keeps each part beside the constants it uses (Numba caches a compiled kernel per
source file):

* :mod:`.model` -- :func:`kernel_model` and the columns of its packed arrays;
* :mod:`.law` -- the force law, written once: each term a scalar function Numba inlines;
* :mod:`.forces` -- the loads of a state from the law: springs and constant forces,
  :func:`body_loads`, the stepping's :func:`rolling_forces`, :func:`force_rates`, contact (M8),
  (M9);
* :mod:`.stepping` -- the symplectic compositions (:data:`SCHEMES`), :func:`advance`,
  :func:`run_fixed_step` and its interpolated outputs;
* :mod:`.refine` -- extremes and the period's zero refined on the integrator, the balls of
  bodies of long chains;
* :mod:`.observation` -- the general (slipping) state's derivative and what is observed of rows;
* :mod:`.linear_setup` -- :func:`level_setup`, the compiled setup of small level systems.

Numba's cache checks only the file of the function it compiled, while a kernel here inlines the
law, reads :mod:`.model`'s columns and calls the other modules' kernels: :mod:`._cache`, imported
first, drops the package's cached kernels whenever any of its sources changed (the batch kernels
carry the law's hash in their generated source).
"""

from __future__ import annotations

# first: the cached kernels are checked against every source of the package before any loads
from rollspring.simulate.kernels import _cache  # noqa: F401
from rollspring.simulate.kernels.forces import (
    body_loads,
    force_rates,
    generalized_forces,
    rolling_forces,
)
from rollspring.simulate.kernels.linear_setup import (
    GENERAL,
    KIND_NAMES,
    LEVEL,
    MOST_BODIES,
    level_setup,
)
from rollspring.simulate.kernels.model import kernel_model
from rollspring.simulate.kernels.observation import (
    observe,
    observe_rolling,
    resistance_drives,
    row_extremes,
    slipping_derivatives,
)
from rollspring.simulate.kernels.refine import (
    body_links,
    refine_extremes,
    refine_windowed,
    signal_zero,
    spring_balls,
)
from rollspring.simulate.kernels.stepping import (
    NEAR_REACH,
    SCHEMES,
    STATUS_NEAR,
    advance,
    advance_many,
    dip_vertex,
    run_fixed_step,
)

__all__ = [
    "GENERAL",
    "KIND_NAMES",
    "LEVEL",
    "MOST_BODIES",
    "NEAR_REACH",
    "SCHEMES",
    "STATUS_NEAR",
    "advance",
    "advance_many",
    "body_links",
    "body_loads",
    "dip_vertex",
    "force_rates",
    "generalized_forces",
    "kernel_model",
    "level_setup",
    "observe",
    "observe_rolling",
    "refine_extremes",
    "refine_windowed",
    "resistance_drives",
    "rolling_forces",
    "row_extremes",
    "run_fixed_step",
    "signal_zero",
    "slipping_derivatives",
    "spring_balls",
]

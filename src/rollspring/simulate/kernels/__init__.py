r"""Compiled (Numba) kernels: the exact rolling equations and explicit symplectic integrators.

While every body rolls the Hamiltonian is separable, :math:`H = \sum p_i^2/(2J_i) + U(q)` with a
constant diagonal mass matrix (docs/physics.md (M6)), so compositions of the kick-drift-kick
leapfrog

.. math:: v \mathrel{+}= \tfrac{h_k}{2} Q(q)/J,\quad q \mathrel{+}= h_k v,\quad
          v \mathrel{+}= \tfrac{h_k}{2} Q(q)/J, \qquad h_k = w_k h

are explicit and symplectic; the weights :math:`w_k` (Yoshida 1990; Kahan and Li 1997) give
orders 2, 4, 6 and 8. The force at the end of a stage is reused at the start of the next.

The general state (any body may slip) is per body the centre position :math:`x_i`, the rotation
:math:`\varphi_i` from the initial placement, the centre velocity :math:`u_i` and the angular
velocity :math:`\omega_i` (clockwise positive). An attachment at distance :math:`r` and angle
:math:`\alpha` (clockwise from up) is at (M1)

.. math::

   P = (x_i + r\sin\theta,\; h_i + R_i + r\cos\theta), \qquad \theta = \alpha + \rho_i\varphi_i

and the loads :func:`body_loads` are the resultant force :math:`(F_{ix}, F_{iy})` and the
clockwise torque :math:`\tau_i` about the centre of the springs (tension
:math:`T = k(l - L_0) + c\,\dot l`) and constant forces. For a rolling body the generalised force
is :math:`Q_i = R_i F_{ix} + \tau_i` (the torque about the contact point, (M7)), and (M8), (M9)
give the friction it needs and its normal force. The model is a tuple of flat arrays

The package keeps each part beside the constants it uses (Numba caches a compiled kernel per
source file):

* :mod:`.model` -- :func:`kernel_model` and the columns of its packed arrays;
* :mod:`.forces` -- the force law: attachment points (M1), spring tensions and their loads,
  :func:`body_loads`, the stepping's :func:`rolling_forces`, :func:`force_rates`, contact (M8),
  (M9);
* :mod:`.stepping` -- the symplectic compositions (:data:`SCHEMES`), :func:`advance`,
  :func:`run_fixed_step` and its interpolated outputs;
* :mod:`.refine` -- extremes and the period's zero refined on the integrator, the balls of
  bodies of long chains;
* :mod:`.observation` -- the general (slipping) state's derivative and what is observed of rows;
* :mod:`.linear_setup` -- :func:`level_setup`, the compiled setup of small level systems.
"""

from __future__ import annotations

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
    SCHEMES,
    STATUS_FINISHED,
    STATUS_LIFTOFF,
    STATUS_NONFINITE,
    STATUS_SLIP,
    advance,
    advance_many,
    run_fixed_step,
)

__all__ = [
    "GENERAL",
    "KIND_NAMES",
    "LEVEL",
    "MOST_BODIES",
    "SCHEMES",
    "STATUS_FINISHED",
    "STATUS_LIFTOFF",
    "STATUS_NONFINITE",
    "STATUS_SLIP",
    "advance",
    "advance_many",
    "body_links",
    "body_loads",
    "force_rates",
    "generalized_forces",
    "kernel_model",
    "level_setup",
    "observe",
    "observe_rolling",
    "refine_extremes",
    "refine_windowed",
    "rolling_forces",
    "row_extremes",
    "run_fixed_step",
    "signal_zero",
    "slipping_derivatives",
    "spring_balls",
]

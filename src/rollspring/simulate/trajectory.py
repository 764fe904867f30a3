"""``Trajectory``: the result of :func:`rollspring.simulate`, the motion at its output times.

Every output array (positions, velocities, contact forces, spring lengths and tensions,
energies), how the run ended (:class:`~rollspring.simulate.status.RunStatus`), the steps each
integrator took and the JSON summary. Its table and notebook views (``to_pandas``,
``to_xarray``, ``animate``) are drawn by :mod:`rollspring.outputs.jupyter`, a higher layer this
module does not import: they are looked up in :data:`rollspring.presenters.PRESENTERS`, which the
package root fills when it is imported. Light to import: NumPy and the model types only.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from rollspring import presenters
from rollspring.errors import SimulationError
from rollspring.model import System
from rollspring.physics.arrays import FloatArray
from rollspring.simulate.status import RunStatus

__all__ = ["Trajectory"]


@dataclass
class Trajectory:
    """The simulated motion at output times ``t`` (s), SI units throughout.

    Per body (columns in the order of ``ids``): ``x`` centre position (m), ``phi`` rotation from
    the initial placement (rad, clockwise positive), ``v`` centre velocity (m/s), ``omega``
    angular velocity (rad/s), ``friction`` (N, positive along +x: the static friction needed to
    roll, or the kinetic friction while slipping), ``normal`` (N), ``friction_ratio``
    :math:`|f|/(\\mu_s N)` (slip when it reaches 1), ``slipping`` (bool). Per spring:
    ``spring_length`` (m), ``spring_tension`` (N). Energies (J; gravity, a constant while
    rolling, left out): ``kinetic``, ``potential``, ``energy``. ``cm_x`` and ``stationary_x``
    (X̂, when the system has a single zero mode). ``status`` says how the run ended
    (:class:`~rollspring.simulate.status.RunStatus`, with ``message``); ``summary`` is the JSON
    summary.
    """

    system: System
    ids: tuple[str, ...]
    spring_names: tuple[str, ...]
    t: FloatArray
    x: FloatArray
    phi: FloatArray
    v: FloatArray
    omega: FloatArray
    friction: FloatArray
    normal: FloatArray
    friction_ratio: FloatArray
    slipping: np.ndarray
    spring_length: FloatArray
    spring_tension: FloatArray
    kinetic: FloatArray
    potential: FloatArray
    energy: FloatArray
    cm_x: FloatArray
    stationary_x: FloatArray | None
    #: how the run ended (a ``str``-valued enum: compares and prints as ``"finished"`` ...)
    status: RunStatus
    message: str
    integrator: str
    step: float | None
    n_steps: int
    events: list[dict[str, Any]] = field(default_factory=list)
    #: the steps each integrator took, in the order they were first used (a run that slipped
    #: goes on with DOP853: ``{"kahanli8": 1130, "dop853": 34}``); ``integrator`` names them
    #: joined by "+", ``n_steps`` is their sum
    steps_by_integrator: dict[str, int] = field(default_factory=dict)
    summary: dict[str, Any] = field(default_factory=dict)
    timings: dict[str, float] = field(default_factory=dict)

    def to_pandas(self) -> Any:
        """The trajectory as a ``pandas.DataFrame`` indexed by t (needs pandas; see
        :func:`rollspring.outputs.jupyter.trajectory_to_pandas`)."""
        return _presenter("to_pandas")(self)

    def to_xarray(self) -> Any:
        """The trajectory as an ``xarray.Dataset`` with dimensions time, body and spring (needs
        xarray; see :func:`rollspring.outputs.jupyter.trajectory_to_xarray`)."""
        return _presenter("to_xarray")(self)

    def animate(self, **options: Any) -> Any:
        """An inline animation for Jupyter (see
        :func:`rollspring.outputs.jupyter.animate_inline` for the options)."""
        return _presenter("animate")(self, **options)

    def columns(self) -> dict[str, tuple[str, FloatArray]]:
        """Every output as ``name -> (unit, values)``, named ``<body>.<quantity>``,
        ``<spring>.<quantity>`` or the quantity alone (the CSV columns)."""
        out: dict[str, tuple[str, FloatArray]] = {"t": ("s", self.t)}
        per_body = [
            ("x", "m", self.x),
            ("phi", "rad", self.phi),
            ("v", "m/s", self.v),
            ("omega", "rad/s", self.omega),
            ("friction", "N", self.friction),
            ("normal_force", "N", self.normal),
            ("friction_ratio", "1", self.friction_ratio),
            ("slipping", "1", self.slipping.astype(float)),
        ]
        for i, name in enumerate(self.ids):
            for quantity, unit, values in per_body:
                out[f"{name}.{quantity}"] = (unit, values[:, i])
        for s, name in enumerate(self.spring_names):
            out[f"{name}.length"] = ("m", self.spring_length[:, s])
            out[f"{name}.tension"] = ("N", self.spring_tension[:, s])
        out["kinetic_energy"] = ("J", self.kinetic)
        out["potential_energy"] = ("J", self.potential)
        out["energy"] = ("J", self.energy)
        out["cm_x"] = ("m", self.cm_x)
        if self.stationary_x is not None:
            out["stationary_x"] = ("m", self.stationary_x)
        return out


def _presenter(name: str) -> Callable[..., Any]:
    """The registered view ``name`` (:data:`rollspring.presenters.PRESENTERS`)."""
    try:
        return presenters.PRESENTERS[name]
    except KeyError:
        raise SimulationError(
            f"Trajectory.{name} is provided by rollspring.outputs: it was not registered "
            "(importing rollspring registers it)"
        ) from None

r"""The same system placed somewhere else along its rolling motion.

A system file gives every body's initial placement, and attachment points are fixed in the
bodies *in that placement*. Rolling body :math:`i` by an angle :math:`q_i` (clockwise) moves its
centre by :math:`s_i q_i` (:math:`s_i = R_i`; a slider's :math:`q_i` is its displacement in
metres) and turns every point fixed in it by :math:`q_i` about the centre (docs/physics.md (M1)):
a point at distance :math:`r` and angle :math:`\alpha` from straight up is then at
:math:`\alpha + q_i`. :func:`rolled` writes that configuration as a new system file, so a run
can start anywhere along the rolling motion (a normal mode displaced from the equilibrium, a body
dragged by hand) with the springs' rest lengths unchanged.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import TYPE_CHECKING

from rollspring.errors import ModelError

if TYPE_CHECKING:
    import numpy as np
    from numpy.typing import NDArray
from rollspring.model.files import system_from_dict
from rollspring.model.schema import Attachment, Body, System

__all__ = ["rolled"]


def rolled(
    system: System,
    q: Sequence[float] | NDArray[np.float64],
    *,
    velocities: Sequence[float] | NDArray[np.float64] | None = None,
) -> System:
    r"""``system`` with body :math:`i` rolled by :math:`q_i` (rad, clockwise; metres for a
    slider) from its initial placement: centre :math:`x_i + R_i q_i`, attachment points and the
    points of application of forces turned by :math:`q_i` about the centre (docs/physics.md (M1)),
    every spring's rest length kept (written explicitly). ``velocities`` (m/s, centre
    velocities) replace the initial velocities when given."""
    angles = [float(value) for value in q]
    if len(angles) != len(system.bodies):
        raise ModelError(f"rolled: {len(angles)} angles for {len(system.bodies)} bodies")
    if not all(math.isfinite(value) for value in angles):
        raise ModelError("rolled: the angles must be finite numbers")
    speeds = None if velocities is None else [float(value) for value in velocities]
    if speeds is not None and len(speeds) != len(angles):
        raise ModelError(f"rolled: {len(speeds)} velocities for {len(system.bodies)} bodies")
    turn = {body.id: angle for body, angle in zip(system.bodies, angles, strict=True)}
    bodies = []
    for i, body in enumerate(system.bodies):
        scale = 1.0 if body.shape == "slider" else body.radius
        update: dict[str, float] = {"x": body.x + scale * angles[i]}
        if speeds is not None:
            update["v"] = speeds[i]
        bodies.append(body.model_copy(update=update))
    by_id = system.body_map
    springs = []
    for spring, rest in zip(system.springs, system.rest_lengths, strict=True):
        ats = spring.attachments
        new_at = [
            _turned(at, by_id.get(end), turn.get(end, 0.0))
            for end, at in zip(spring.ends, ats, strict=True)
        ]
        springs.append(spring.model_copy(update={"rest_length": rest, "at": new_at}))
    forces = [
        force.model_copy(update={"at": _turned(force.at, by_id[force.body], turn[force.body])})
        for force in system.forces
    ]
    data = system.model_dump(mode="python", exclude_none=True)
    data["bodies"] = [b.model_dump(mode="python", exclude_none=True) for b in bodies]
    data["springs"] = [s.model_dump(mode="python", exclude_none=True) for s in springs]
    data["forces"] = [f.model_dump(mode="python", exclude_none=True) for f in forces]
    return system_from_dict(data, source="rolled")  # a one-line error if a value leaves its range


def _turned(at: Attachment, body: Body | None, angle: float) -> Attachment:
    """The attachment ``at`` of ``body`` after the body turned by ``angle`` (rad, clockwise):
    the centre and anchor ends stay as they are; any other point becomes ``{radius, angle}``."""
    if body is None or at.is_centre_form or angle == 0.0 or body.shape == "slider":
        return at
    radius, alpha = at.polar(body)
    if radius == 0.0:
        return Attachment()
    degrees = math.degrees(math.remainder(alpha + angle, 2.0 * math.pi))
    return Attachment(radius=radius, angle=degrees)

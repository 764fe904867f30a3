r"""The numeric form of a system: flat NumPy arrays in SI units, one entry per body/spring/force.

Every physics function takes a :class:`SystemArrays` and a state. The state is the vector of
generalised coordinates ``q`` (shape ``(..., n_bodies)``, any leading batch shape): for a rolling
body its rotation :math:`\varphi_i` (rad, clockwise positive, from the initial placement), for a
slider its displacement (m). Both are written with one formula by two per-body constants:

.. math:: x_i = x_{i0} + s_i q_i, \qquad \theta = \alpha + \rho_i q_i

with :math:`s_i = R_i, \rho_i = 1` for a rolling body (no slip, docs/physics.md section 2) and
:math:`s_i = 1, \rho_i = 0` for a slider (it translates without turning).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from rollspring.model import System

__all__ = ["SystemArrays", "system_arrays"]

FloatArray = NDArray[np.float64]
IntArray = NDArray[np.int64]


@dataclass(frozen=True, eq=False)
class SystemArrays:
    """A system as arrays (read-only). Build it with :func:`system_arrays`."""

    ids: tuple[str, ...]
    spring_names: tuple[str, ...]
    mass: FloatArray  # (n,) kg
    radius: FloatArray  # (n,) m
    gamma: FloatArray  # (n,) I = gamma m R^2 (0 for a slider)
    track: FloatArray  # (n,) height of the floor under each body, m
    x0: FloatArray  # (n,) initial centre positions, m
    v0: FloatArray  # (n,) initial centre velocities, m/s
    scale: FloatArray  # (n,) s_i: dx_i/dq_i (R for rolling, 1 for a slider)
    rolls: FloatArray  # (n,) rho_i: 1.0 rolling, 0.0 slider
    inertia: FloatArray  # (n,) J_i, the (constant) diagonal of the mass matrix, (M4)
    mu_static: FloatArray  # (n,)
    mu_kinetic: FloatArray  # (n,)
    gravity: float
    # springs
    stiffness: FloatArray  # (S,) N/m
    rest_length: FloatArray  # (S,) m
    damping: FloatArray  # (S,) N s/m
    end_body: IntArray  # (S, 2) body index of each end, -1 for an anchor
    end_r: FloatArray  # (S, 2) distance of the attachment from the centre
    end_alpha: FloatArray  # (S, 2) angle of the attachment, rad, clockwise from up (at q = 0)
    end_anchor: FloatArray  # (S, 2, 2) anchor position (zeros for a body end)
    incidence: FloatArray  # (S, 2, n) 1 where end j of spring s is on body i
    # constant external forces
    force_body: IntArray  # (F,)
    force_r: FloatArray  # (F,)
    force_alpha: FloatArray  # (F,)
    force: FloatArray  # (F, 2) N
    force_incidence: FloatArray  # (F, n)

    @property
    def n_bodies(self) -> int:
        """Number of bodies (= number of coordinates while all roll)."""
        return len(self.ids)

    @property
    def n_springs(self) -> int:
        """Number of springs."""
        return len(self.spring_names)

    @property
    def has_anchors(self) -> bool:
        """True when a spring is tied to a fixed anchor."""
        return bool(np.any(self.end_body < 0))


def system_arrays(system: System) -> SystemArrays:
    """Flatten a validated :class:`~rollspring.model.System` into :class:`SystemArrays`."""
    bodies = system.bodies
    index = {b.id: i for i, b in enumerate(bodies)}
    n = len(bodies)

    def arr(values: list[float]) -> FloatArray:
        out = np.array(values, dtype=np.float64)
        out.setflags(write=False)
        return out

    rolls = [1.0 if b.rolls else 0.0 for b in bodies]
    springs = system.springs
    n_s = len(springs)
    end_body = np.full((n_s, 2), -1, dtype=np.int64)
    end_r = np.zeros((n_s, 2))
    end_alpha = np.zeros((n_s, 2))
    end_anchor = np.zeros((n_s, 2, 2))
    incidence = np.zeros((n_s, 2, n))
    anchors = system.anchor_map
    names = []
    for s, spring in enumerate(springs):
        names.append(f"{spring.ends[0]}-{spring.ends[1]}")
        for j, (end, at) in enumerate(zip(spring.ends, spring.attachments, strict=True)):
            if end in index:
                i = index[end]
                end_body[s, j] = i
                end_r[s, j], end_alpha[s, j] = at.polar(bodies[i])
                incidence[s, j, i] = 1.0
            else:
                end_anchor[s, j] = (anchors[end].x, anchors[end].y)
    forces = system.forces
    n_f = len(forces)
    force_body = np.array([index[f.body] for f in forces], dtype=np.int64).reshape(n_f)
    force_polar = [f.at.polar(system.body_map[f.body]) for f in forces]
    force_incidence = np.zeros((n_f, n))
    force_incidence[np.arange(n_f), force_body] = 1.0
    for a in (end_body, end_r, end_alpha, end_anchor, incidence, force_body, force_incidence):
        a.setflags(write=False)
    # disambiguate repeated spring names (two springs between the same ends)
    counts: dict[str, int] = {}
    unique = []
    for name in names:
        counts[name] = counts.get(name, 0) + 1
        unique.append(name if names.count(name) == 1 else f"{name}#{counts[name]}")
    return SystemArrays(
        ids=tuple(b.id for b in bodies),
        spring_names=tuple(unique),
        mass=arr([b.mass for b in bodies]),
        radius=arr([b.radius for b in bodies]),
        gamma=arr([b.gamma for b in bodies]),
        track=arr([b.track_height for b in bodies]),
        x0=arr([b.x for b in bodies]),
        v0=arr([b.v for b in bodies]),
        scale=arr([b.radius if b.rolls else 1.0 for b in bodies]),
        rolls=arr(rolls),
        inertia=arr([b.contact_inertia for b in bodies]),
        mu_static=arr([b.mu_static for b in bodies]),
        mu_kinetic=arr([b.mu_kinetic_value for b in bodies]),
        gravity=float(system.gravity),
        stiffness=arr([s.stiffness for s in springs]),
        rest_length=arr(system.rest_lengths),
        damping=arr([s.damping for s in springs]),
        end_body=end_body,
        end_r=end_r,
        end_alpha=end_alpha,
        end_anchor=end_anchor,
        incidence=incidence,
        force_body=force_body,
        force_r=arr([p[0] for p in force_polar]),
        force_alpha=arr([p[1] for p in force_polar]),
        force=np.array([[f.fx, f.fy] for f in forces], dtype=np.float64).reshape(n_f, 2),
        force_incidence=force_incidence,
    )

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

import os
from collections import Counter
from dataclasses import dataclass
from functools import cached_property
from typing import Any

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
    #: (n,) C_rr: the normal force acts C_rr R ahead of the contact (0 for a slider)
    rolling_resistance: FloatArray
    gravity: float
    # springs
    stiffness: FloatArray  # (S,) N/m
    rest_length: FloatArray  # (S,) m
    damping: FloatArray  # (S,) N s/m
    end_body: IntArray  # (S, 2) body index of each end, -1 for an anchor
    end_r: FloatArray  # (S, 2) distance of the attachment from the centre
    end_alpha: FloatArray  # (S, 2) angle of the attachment, rad, clockwise from up (at q = 0)
    end_anchor: FloatArray  # (S, 2, 2) anchor position (zeros for a body end)
    # constant external forces
    force_body: IntArray  # (F,)
    force_r: FloatArray  # (F,)
    force_alpha: FloatArray  # (F,)
    force: FloatArray  # (F, 2) N

    @property
    def n_bodies(self) -> int:
        """Number of bodies (= number of coordinates while all roll)."""
        return len(self.ids)

    @property
    def n_springs(self) -> int:
        """Number of springs."""
        return len(self.spring_names)

    @cached_property
    def resisted(self) -> bool:
        """True when a body has rolling resistance (C_rr > 0): the motion is dissipative and
        piecewise smooth (docs/physics.md section 5)."""
        return bool(np.any(self.rolling_resistance > 0))

    @property
    def has_anchors(self) -> bool:
        """True when a spring is tied to a fixed anchor."""
        return bool(np.any(self.end_body < 0))

    @cached_property
    def end_index(self) -> IntArray:
        """(S, 2) body index of each spring end, an anchor end given body 0 (its
        :attr:`end_on_body` is 0): an index that is always valid, for gathers and scatters."""
        index: IntArray = np.where(self.end_body >= 0, self.end_body, 0)
        index.setflags(write=False)
        return index

    @cached_property
    def end_on_body(self) -> FloatArray:
        """(S, 2) 1.0 where a spring end is on a body, 0.0 at an anchor."""
        mask: FloatArray = (self.end_body >= 0).astype(np.float64)
        mask.setflags(write=False)
        return mask

    @cached_property
    def bandwidth(self) -> int:
        """Largest :math:`|i - j|` over the springs joining bodies i and j (0 without such
        springs): the stiffness matrix is banded with this half-bandwidth."""
        both = (self.end_body >= 0).all(axis=1)
        if not both.any():
            return 0
        ends = self.end_body[both]
        return int(np.abs(ends[:, 1] - ends[:, 0]).max())

    @cached_property
    def level_centre_springs(self) -> bool:
        """True when every spring joins body centres (or anchors) at one height and every
        external force acts at a centre: :func:`~rollspring.physics.springs_stay_level`."""
        if not self.n_springs or self.end_r.any() or self.force_r.any():
            return False
        centre = (self.track + self.radius).tolist()  # a few numbers: plain Python
        for (a, b), (ya, yb) in zip(
            self.end_body.tolist(), self.end_anchor[..., 1].tolist(), strict=True
        ):
            if (centre[a] if a >= 0 else ya) != (centre[b] if b >= 0 else yb):
                return False
        return True

    @cached_property
    def incidence(self) -> FloatArray:
        """(S, 2, n) dense incidence, 1 where end j of spring s is on body i: S x n numbers,
        for small systems only (the physics gathers and scatters by :attr:`end_index`)."""
        dense = np.zeros((self.n_springs, 2, self.n_bodies))
        s, j = np.nonzero(self.end_body >= 0)
        dense[s, j, self.end_body[s, j]] = 1.0
        dense.setflags(write=False)
        return dense


#: The fields of :class:`SystemArrays` that :func:`system_arrays` gathers as the rows of one
#: array per body and one per spring, in the rows' order.
_PER_BODY = (
    "mass",
    "radius",
    "gamma",
    "track",
    "x0",
    "v0",
    "scale",
    "rolls",
    "inertia",
    "mu_static",
    "mu_kinetic",
    "rolling_resistance",
)
_PER_SPRING = ("stiffness", "rest_length", "damping")


def system_arrays(system: System | dict[str, Any] | str | os.PathLike[str]) -> SystemArrays:
    """Flatten a validated :class:`~rollspring.model.System` into :class:`SystemArrays` (or
    the system that its JSON form, a file path or a preset name describes:
    :func:`rollspring.model.as_system`).

    The per-body and the per-spring numbers are gathered in plain Python and made into one
    array each (rows of read-only views): a few large NumPy calls instead of one per field.
    """
    if not isinstance(system, System):
        from rollspring.model import as_system

        system = as_system(system)
    bodies = system.bodies
    index = {b.id: i for i, b in enumerate(bodies)}
    per_body = np.array(
        [
            [
                b.mass,
                b.radius,
                b.gamma,
                b.track_height,
                b.x,
                b.v,
                b.radius if b.rolls else 1.0,
                1.0 if b.rolls else 0.0,
                b.contact_inertia,
                b.mu_static,
                b.mu_kinetic_value,
                b.rolling_resistance,
            ]
            for b in bodies
        ],
        dtype=np.float64,
    ).T.copy()  # (12, n): each row a contiguous view
    per_body.setflags(write=False)
    springs = system.springs
    n_s = len(springs)
    end_body = np.full((n_s, 2), -1, dtype=np.int64)
    end_r = np.zeros((n_s, 2))
    end_alpha = np.zeros((n_s, 2))
    end_anchor = np.zeros((n_s, 2, 2))
    anchors = system.anchor_map if system.anchors else {}
    names = []
    for s, spring in enumerate(springs):
        names.append(f"{spring.ends[0]}-{spring.ends[1]}")
        for j, (end, at) in enumerate(zip(spring.ends, spring.attachments, strict=True)):
            if end in index:
                i = index[end]
                end_body[s, j] = i
                if not at.is_centre_form:  # a centre is (0, 0)
                    end_r[s, j], end_alpha[s, j] = at.polar(bodies[i])
            else:
                end_anchor[s, j] = (anchors[end].x, anchors[end].y)
    per_spring = np.array(
        [
            [s.stiffness for s in springs],
            system.rest_lengths,
            [s.damping for s in springs],
        ],
        dtype=np.float64,
    ).reshape(3, n_s)
    per_spring.setflags(write=False)
    forces = system.forces
    n_f = len(forces)
    force_body = np.array([index[f.body] for f in forces], dtype=np.int64).reshape(n_f)
    force_polar = [f.at.polar(bodies[index[f.body]]) for f in forces]
    per_force = np.array(
        [[p[0] for p in force_polar], [p[1] for p in force_polar]], dtype=np.float64
    ).reshape(2, n_f)
    force = np.array([[f.fx, f.fy] for f in forces], dtype=np.float64).reshape(n_f, 2)
    for a in (
        end_body,
        end_r,
        end_alpha,
        end_anchor,
        force_body,
        per_force,
        force,
    ):
        a.setflags(write=False)
    # disambiguate repeated spring names (two springs between the same ends)
    unique = names
    if len(set(names)) < len(names):
        total = Counter(names)
        counts: Counter[str] = Counter()
        unique = []
        for name in names:
            counts[name] += 1
            unique.append(name if total[name] == 1 else f"{name}#{counts[name]}")
    bodies_rows = dict(zip(_PER_BODY, per_body, strict=True))
    spring_rows = dict(zip(_PER_SPRING, per_spring, strict=True))
    return SystemArrays(
        ids=tuple(index),
        spring_names=tuple(unique),
        gravity=float(system.gravity),
        end_body=end_body,
        end_r=end_r,
        end_alpha=end_alpha,
        end_anchor=end_anchor,
        force_body=force_body,
        force_r=per_force[0],
        force_alpha=per_force[1],
        force=force,
        **bodies_rows,
        **spring_rows,
    )

"""The kernel model: a system's arrays packed as the few flat arrays the compiled kernels take.

:func:`kernel_model` packs :class:`~rollspring.physics.SystemArrays` into one row per body, per
spring and per constant force; the column constants below name those rows' entries, and every
kernel module reads the model through them (``from rollspring.simulate.kernels import model as
col``, then ``springs[s, col.STIFF]``: Numba takes a module's integer attribute as a compile-time
constant, as it takes an imported name). Few packed arrays keep the compiled calls cheap.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from rollspring.physics import SystemArrays

__all__ = [
    "AAX",
    "AAY",
    "ABX",
    "ABY",
    "ALPHA_A",
    "ALPHA_B",
    "CENTRAL",
    "CY",
    "C_RR",
    "DAMP",
    "FALPHA",
    "FR",
    "FX",
    "FY",
    "INERTIA",
    "INV_INERTIA",
    "MASS",
    "MU_K",
    "MU_S",
    "RA",
    "RADIUS",
    "RB",
    "REST",
    "ROLLS",
    "SCALE",
    "STIFF",
    "X0",
    "kernel_model",
]

# columns of the packed per-body, per-spring and per-force arrays of the kernel model
X0, SCALE, ROLLS, CY, INERTIA, MASS, MU_S, CENTRAL, MU_K, RADIUS, INV_INERTIA, C_RR = range(12)
# a spring's end b has its columns two after end a's (RB = RA + 2, ..., ABY = AAY + 2): the
# kernels read end e (0: a, 1: b) at RA + 2 e, ALPHA_A + 2 e, AAX + 2 e, AAY + 2 e
RA, ALPHA_A, RB, ALPHA_B, AAX, AAY, ABX, ABY, STIFF, REST, DAMP = range(11)
FR, FALPHA, FX, FY = range(4)


def kernel_model(arrays: SystemArrays, x0: np.ndarray | None = None) -> tuple[Any, ...]:
    """The model the kernels take: ``(bodies (n, 12), springs (S, 11), spring_ends (S, 2) int,
    forces (F, 4), force_body (F,) int, gravity)`` (columns named by the module constants).
    ``x0`` overrides the reference centre positions (after a body re-sticks:
    ``x_i - R_i phi_i``). Few packed arrays keep the compiled calls cheap."""
    a = arrays
    # one array of the columns as rows, transposed: the cheapest packing for a few bodies
    bodies = np.array(
        [
            a.x0 if x0 is None else x0,
            a.scale,
            a.rolls,
            a.track + a.radius,
            a.inertia,
            a.mass,
            a.mu_static,
            a.gamma * a.mass * a.radius**2,
            a.mu_kinetic,
            a.radius,
            1.0 / a.inertia,
            a.rolling_resistance,
        ],
        dtype=np.float64,
    ).T
    springs = np.array(
        [
            a.end_r[:, 0],
            a.end_alpha[:, 0],
            a.end_r[:, 1],
            a.end_alpha[:, 1],
            a.end_anchor[:, 0, 0],
            a.end_anchor[:, 0, 1],
            a.end_anchor[:, 1, 0],
            a.end_anchor[:, 1, 1],
            a.stiffness,
            a.rest_length,
            a.damping,
        ],
        dtype=np.float64,
    ).T.reshape(-1, 11)
    forces = np.array(
        [a.force_r, a.force_alpha, a.force[:, 0], a.force[:, 1]], dtype=np.float64
    ).T.reshape(-1, 4)
    return (
        np.ascontiguousarray(bodies),
        np.ascontiguousarray(springs),
        np.ascontiguousarray(a.end_body, dtype=np.int64),
        np.ascontiguousarray(forces),
        np.ascontiguousarray(a.force_body, dtype=np.int64),
        float(a.gravity),
    )

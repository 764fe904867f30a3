"""Exact rolling physics: pure, vectorised functions of a system (as arrays) and a state."""

from rollspring.physics.arrays import SystemArrays, system_arrays
from rollspring.physics.mechanics import (
    SpringState,
    accelerations,
    body_forces,
    body_forces_jacobian,
    centre_of_mass,
    centre_positions,
    contact_forces,
    contact_forces_jacobian,
    end_kinematics,
    force_point_kinematics,
    generalized_forces,
    kinetic_energy,
    mass_matrix,
    potential_energy,
    spring_state,
    stiffness_matrix,
    total_energy,
)

__all__ = [
    "SpringState",
    "SystemArrays",
    "accelerations",
    "body_forces",
    "body_forces_jacobian",
    "centre_of_mass",
    "centre_positions",
    "contact_forces",
    "contact_forces_jacobian",
    "end_kinematics",
    "force_point_kinematics",
    "generalized_forces",
    "kinetic_energy",
    "mass_matrix",
    "potential_energy",
    "spring_state",
    "stiffness_matrix",
    "system_arrays",
    "total_energy",
]

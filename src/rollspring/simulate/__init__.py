"""Simulation: the exact nonlinear motion (symplectic, compiled), slip and lift-off to the
instant, stick-slip with kinetic friction, and batches of runs."""

from rollspring.simulate.run import INTEGRATORS, Trajectory, choose_scheme, simulate

__all__ = ["INTEGRATORS", "Trajectory", "choose_scheme", "simulate"]

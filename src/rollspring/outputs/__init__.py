"""Outputs: files, plots, animations and reports made from analyses and trajectories."""

from rollspring.outputs.atomic import atomic_write, atomic_write_bytes, atomic_write_text
from rollspring.outputs.mjcf import mjcf_warnings, system_to_mjcf, write_mjcf
from rollspring.outputs.trajectory import (
    json_ready,
    summary_json,
    trajectory_csv,
    write_trajectory,
)

__all__ = [
    "atomic_write",
    "atomic_write_bytes",
    "atomic_write_text",
    "json_ready",
    "mjcf_warnings",
    "summary_json",
    "system_to_mjcf",
    "trajectory_csv",
    "write_mjcf",
    "write_trajectory",
]

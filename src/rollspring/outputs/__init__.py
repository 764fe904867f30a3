"""Outputs: files, plots, animations and reports made from analyses and trajectories."""

from rollspring.outputs.files import atomic_write, atomic_write_bytes, atomic_write_text
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
    "summary_json",
    "trajectory_csv",
    "write_trajectory",
]

"""Outputs: files, plots, animations and reports made from analyses and trajectories."""

from rollspring.outputs.files import atomic_write, atomic_write_bytes, atomic_write_text
from rollspring.outputs.mjcf import mjcf_warnings, system_to_mjcf, write_mjcf
from rollspring.outputs.trajectory import (
    json_ready,
    summary_json,
    trajectory_csv,
    write_trajectory,
)


def _register_presenters() -> None:
    """``Trajectory.to_pandas``/``to_xarray``/``animate`` (the Jupyter views, imported on first
    use: Matplotlib and pandas stay out of ``import rollspring``)."""
    from rollspring.simulate.run import PRESENTERS

    def view(name: str):
        def call(*args, **kwargs):
            from rollspring.outputs import jupyter

            return getattr(jupyter, name)(*args, **kwargs)

        return call

    PRESENTERS.update(
        to_pandas=view("trajectory_to_pandas"),
        to_xarray=view("trajectory_to_xarray"),
        animate=view("animate_inline"),
    )


_register_presenters()

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

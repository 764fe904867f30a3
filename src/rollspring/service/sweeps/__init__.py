"""Sweeps: a grid of runs of one system, in-process or on a Dask cluster, into a Zarr store
(``rollspring sweep``; docs/sweeps.md is the contract).

``grid`` (PATHs, values, chunks: index arithmetic), ``compute`` (one chunk: a pure function of
the plan and the chunk index, the task a worker runs), ``store`` (template, regions, done
markers, fingerprint) and ``engine`` (:func:`sweep`: the plan, resuming, in-process or Dask).
"""

from rollspring.service.sweeps.engine import (
    DEFAULT_CHUNK,
    METRICS,
    SweepProgress,
    sweep,
    sweep_cost,
)
from rollspring.service.sweeps.grid import SweepError, parse_vary_spec
from rollspring.service.sweeps.store import StoreMismatchError

__all__ = [
    "DEFAULT_CHUNK",
    "METRICS",
    "StoreMismatchError",
    "SweepError",
    "SweepProgress",
    "parse_vary_spec",
    "sweep",
    "sweep_cost",
]

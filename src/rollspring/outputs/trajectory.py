"""Trajectory files: ``trajectory.csv``, ``trajectory.npz`` and ``summary.json``, written as a
set (:func:`rollspring.outputs.atomic.write_file_set`): a killed run never leaves a half-written
file, nor its files beside an earlier run's."""

from __future__ import annotations

import io
import json
import math
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np

from rollspring.outputs.atomic import write_file_set

if TYPE_CHECKING:  # in annotations only: writing a file loads no simulator (Numba, SciPy)
    from rollspring.simulate import Trajectory

__all__ = ["json_ready", "summary_json", "trajectory_csv", "write_trajectory"]


def json_ready(value: Any) -> Any:
    """NumPy scalars and arrays as plain JSON values; a non-finite number becomes ``null``
    (JSON has no infinity)."""
    if isinstance(value, dict):
        return {str(k): json_ready(v) for k, v in value.items()}
    if isinstance(value, list | tuple):
        return [json_ready(v) for v in value]
    if isinstance(value, np.ndarray):
        return json_ready(value.tolist())
    if isinstance(value, np.bool_ | bool):
        return bool(value)
    if isinstance(value, np.integer):
        return int(value)
    if isinstance(value, float | np.floating):
        value = float(value)
        return value if math.isfinite(value) else None
    return value


def summary_json(trajectory: Trajectory) -> dict[str, Any]:
    """The run's summary with the unit of every trajectory column (``"columns"``)."""
    summary = dict(trajectory.summary)
    summary["system"] = trajectory.system.name
    summary["columns"] = {name: unit for name, (unit, _) in trajectory.columns().items()}
    return json_ready(summary)


def trajectory_csv(trajectory: Trajectory) -> str:
    """One header line of column names (``<body>.<quantity>``), then one row per output time;
    the units are in ``summary.json`` under ``"columns"`` (SI throughout)."""
    columns = trajectory.columns()
    table = np.column_stack([values for _, values in columns.values()])
    buffer = io.StringIO()
    buffer.write(",".join(columns) + "\n")
    np.savetxt(buffer, table, delimiter=",", fmt="%.17g")
    return buffer.getvalue()


def write_trajectory(trajectory: Trajectory, directory: str | Path) -> list[Path]:
    """Write the three files into ``directory`` (created if needed) as one set: either all three
    of this run or, after a failure or an interruption, those that were there before; returns
    their paths. A failure to write is an :class:`~rollspring.errors.OutputError`."""

    def csv(path: Path) -> None:
        with open(path, "w", encoding="utf-8", newline="\n") as handle:
            handle.write(trajectory_csv(trajectory))

    def npz(path: Path) -> None:
        columns = {name: values for name, (_, values) in trajectory.columns().items()}
        with open(path, "wb") as handle:
            # NumPy's stubs type **kwds as the keyword options (allow_pickle): they are the arrays
            np.savez_compressed(handle, **columns)  # type: ignore[arg-type]

    def summary(path: Path) -> None:
        text = json.dumps(summary_json(trajectory), indent=2, ensure_ascii=False, allow_nan=False)
        with open(path, "w", encoding="utf-8", newline="\n") as handle:
            handle.write(text + "\n")

    return write_file_set(
        directory, {"trajectory.csv": csv, "trajectory.npz": npz, "summary.json": summary}
    )

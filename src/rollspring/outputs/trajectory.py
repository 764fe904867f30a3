"""Trajectory files: ``trajectory.csv``, ``trajectory.npz`` and ``summary.json``, each written
atomically (a killed run never leaves a half-written file)."""

from __future__ import annotations

import io
import json
import math
from pathlib import Path
from typing import Any

import numpy as np

from rollspring.outputs.files import atomic_write, atomic_write_text
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
    """Write the three files into ``directory`` (created if needed); returns their paths."""
    directory = Path(directory)
    directory.mkdir(parents=True, exist_ok=True)
    csv_path = directory / "trajectory.csv"
    npz_path = directory / "trajectory.npz"
    json_path = directory / "summary.json"
    atomic_write_text(csv_path, trajectory_csv(trajectory))
    with atomic_write(npz_path, "wb") as handle:
        columns = {name: values for name, (_, values) in trajectory.columns().items()}
        # NumPy's stubs type **kwds as the keyword options (allow_pickle): they are the arrays
        np.savez_compressed(handle, **columns)  # type: ignore[arg-type]
    atomic_write_text(
        json_path,
        json.dumps(summary_json(trajectory), indent=2, ensure_ascii=False, allow_nan=False) + "\n",
    )
    return [csv_path, npz_path, json_path]

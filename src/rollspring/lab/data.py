r"""Measured tables of a real experiment, read and matched to the bodies of a system.

Three formats, told apart by their first lines:

* **a ``track`` CSV or a plain CSV** (comma-separated): a header ``t,x_<id>,phi_<id>,...`` —
  the time ``t`` (s), each body's centre position ``x_<id>`` (m) and, optionally, its rotation
  angle ``phi_<id>`` (rad, clockwise positive) and the error locked to its position
  ``xlocked1_<id>``, ``xlocked2_<id>``, ``xlocked3_<id>`` (m, the same in every row), one row
  per frame. ``rollspring track`` writes it (in the system's order); any order of the columns
  is read.
* **a Tracker data file** (Open Source Physics' Tracker, "Export Data", tab-separated; commas
  and semicolons are read too): one track — its name on the first line, the column names
  (``t x y``, and whatever else was exported) on the second — or several tracks in one file: a
  first line ``#multi:``, a line of track names (each above its first column), then the column
  names. A track's ``x`` column is its centre position (m, as calibrated in Tracker); ``y`` and
  the other columns are not used.

Tracks are matched to bodies by name (``x_hoop`` and a track ``hoop`` are the body ``hoop``), or
by a mapping ``{track: body}`` (``--map track=body``). Empty cells (frames where a track was
not marked) are skipped: they are NaN in :attr:`Recording.x` and take no part in a fit.

Every refusal is a :class:`~rollspring.errors.DataError` with one line naming the file, the row
or column and the reason: no time column, a time that is not a number, times unsorted or
repeated, an unknown track or body, no position at all.
"""

from __future__ import annotations

import math
import os
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from typing import Protocol, cast

import numpy as np

from rollspring.errors import DataError
from rollspring.model import RANGES, System
from rollspring.model.files import not_regular
from rollspring.physics.arrays import FloatArray

__all__ = [
    "BodyData",
    "DataError",
    "Recording",
    "Tracks",
    "as_recording",
    "match_bodies",
    "parse_data",
    "read_data",
]

#: The largest data file read (bytes): a minute at 1000 frames/s of twenty bodies is 3 MB.
MAX_BYTES = 200_000_000
#: The largest time a table may hold (s; a clock's epoch reading, about 1.8e9 s, passes).
MAX_TIME = 1e10


@dataclass(frozen=True)
class Recording:
    """A measured table as read: per track the centre position and, if measured, the angle.

    ``t`` (N,) strictly increasing times (s); ``x`` and ``phi`` (N, T) per track (m, rad), NaN
    where a frame has no mark (``phi`` all NaN for a track without angles); ``tracks`` the T
    names (a body id for a CSV, a Tracker track's name); ``source`` the file it came from.
    """

    source: str
    t: FloatArray
    tracks: tuple[str, ...]
    x: FloatArray
    phi: FloatArray
    format: str  # "csv", "tracker" or "tracker-multi"
    locked_error: FloatArray | None = None  # (T, 3) m, track's xlocked<m>_<id>; 0 if none


@dataclass(frozen=True)
class BodyData:
    """A recording matched to a system: per measured body, its centre positions and angles.

    ``bodies`` the ids measured (in the system's order), ``index`` their indices among the
    system's bodies, ``t`` (N,), ``x`` and ``phi`` (N, B) with NaN where a frame has no mark;
    ``locked_error`` (B, 3) each body's error locked to its position, the standard deviations
    (m) of its coefficients on :math:`P_1, P_2, P_3` of the position (``track``'s
    ``xlocked<m>_<id>``; None when the file has none).
    """

    source: str
    t: FloatArray
    bodies: tuple[str, ...]
    index: tuple[int, ...]
    x: FloatArray
    phi: FloatArray
    locked_error: FloatArray | None = None

    @property
    def has_angles(self) -> bool:
        """Whether any body's angle was measured."""
        return bool(np.isfinite(self.phi).any())

    @property
    def n_points(self) -> int:
        """How many positions were measured (every body's marked frames)."""
        return int(np.isfinite(self.x).sum())


class Tracks(Protocol):
    """What :func:`rollspring.track` returns, as the fit sees it: the CSV it writes and the video
    it came from (:class:`rollspring.lab.tracking.TrackResult`)."""

    video: str

    def to_csv(self, path: str | os.PathLike[str] | None = None) -> str: ...


def as_recording(data: object) -> Recording:
    """What a fit is given, as a :class:`Recording`: a file path (:func:`read_data`), a
    :class:`Recording`, or the tracks of a video (:func:`rollspring.track`'s result, read from
    the CSV it writes, so that a file and the object give the same fit); anything else is a
    one-line :class:`DataError`."""
    if isinstance(data, Recording):
        return data
    if isinstance(data, str | os.PathLike):
        return read_data(data)
    if callable(getattr(data, "to_csv", None)) and isinstance(getattr(data, "video", None), str):
        tracks = cast(Tracks, data)
        return parse_data(tracks.to_csv(), f"the tracks of {tracks.video}")
    raise DataError(
        "data: expected a data file's path, a Recording or the result of rollspring.track, "
        f"got {type(data).__name__}"
    )


def read_data(path: str | os.PathLike[str]) -> Recording:
    """Read a measured table (a ``track`` CSV, a plain CSV or a Tracker data file; see the
    module's docstring): a :class:`Recording`, or a one-line :class:`DataError` naming the
    file and the reason."""
    shown = os.fspath(path)
    try:
        info = os.stat(path)
        kind = not_regular(info.st_mode)
        if kind is not None:  # a FIFO would block, a folder or a device is no table
            raise DataError(f"{shown}: is {kind}, not a data file (give a regular file)")
        if info.st_size > MAX_BYTES:
            raise DataError(
                f"{shown}: {info.st_size / 1e6:.0f} MB, larger than a data file is read"
            )
        descriptor = os.open(path, os.O_RDONLY | getattr(os, "O_NONBLOCK", 0))
        with os.fdopen(descriptor, "rb") as handle:
            if not_regular(os.fstat(handle.fileno()).st_mode) is not None:
                raise DataError(f"{shown}: not a regular file (it changed while being opened)")
            raw = handle.read(MAX_BYTES + 1)
    except OSError as exc:
        raise DataError(f"{shown}: cannot read ({exc.strerror or exc})") from None
    except DataError:
        raise
    except ValueError as exc:  # a path with a NUL byte
        raise DataError(f"{shown!r}: not a valid path ({exc})") from None
    try:
        text = raw.decode("utf-8-sig")
    except UnicodeDecodeError:
        try:
            text = raw.decode("latin-1")  # Tracker on older Windows systems
        except UnicodeDecodeError:  # pragma: no cover - latin-1 decodes every byte
            raise DataError(f"{shown}: not a text file") from None
    return parse_data(text, shown)


def parse_data(text: str, source: str = "<data>") -> Recording:
    """A measured table from its text (``source`` names it in messages): see :func:`read_data`."""
    # lines end in LF, CR LF or CR alone (a spreadsheet's "CSV (Macintosh)")
    lines = text.replace("\r\n", "\n").replace("\r", "\n").split("\n")
    while lines and not lines[-1].strip():
        lines.pop()
    if not lines or not any(line.strip() for line in lines):
        raise DataError(f"{source}: the file is empty")
    if "\x00" in text:
        raise DataError(f"{source}: not a text file (it holds NUL bytes)")
    first = lines[0].strip()
    if first.lower().startswith("#multi"):
        if len(lines) < 3:
            raise DataError(
                f"{source}: a Tracker '#multi:' file needs a line of track names and a line of "
                "column names"
            )
        separator = _separator(lines[2])
        names, header = _cells(lines[1], separator), _cells(lines[2], separator)
        return _tracker(source, names, header, lines[3:], separator, 4, "tracker-multi")
    header_line = lines[0]
    if len(lines) > 1 and not any(mark in lines[0] for mark in _SEPARATORS):
        header_line = lines[1]  # a Tracker file of one track: its name alone on the first line
    separator = _separator(header_line)
    head = _cells(lines[0], separator)
    second = _cells(lines[1], separator) if len(lines) > 1 else []
    named = [cell for cell in head if cell]
    if len(named) == 1 and second and second[0].strip().lower() == "t" and named[0] != "t":
        return _tracker(source, head, second, lines[2:], separator, 3, "tracker")
    return _table(source, head, lines[1:], separator)


_SEPARATORS = ("\t", ";", ",")


def _separator(header: str) -> str:
    """The column separator of a file, read from its header line (the numbers below may use
    decimal commas): tab (Tracker), else semicolon, else comma."""
    for separator in _SEPARATORS:
        if separator in header:
            return separator
    return ","


def _cells(line: str, separator: str) -> list[str]:
    return [cell.strip().strip('"').strip() for cell in line.split(separator)]


def _number(cell: str) -> float:
    """A cell's number (NaN for an empty cell); ValueError for text that is no number."""
    if not cell:
        return math.nan
    value = float(cell.replace(",", ".") if cell.count(",") == 1 and "." not in cell else cell)
    if not math.isfinite(value):
        raise ValueError(cell)
    return value


def _rows(
    source: str,
    lines: list[str],
    separator: str,
    columns: int,
    first_row: int,
    positions: Sequence[int] = (),
    times: Sequence[int] = (),
) -> FloatArray:
    """The numbers of the data lines (N, columns), NaN for empty cells (a short line's missing
    cells are empty: an unmarked frame); a line that is blank is skipped; a cell that is no
    number, a number in a ``positions`` column outside the model's positions
    (``RANGES["position"]``, m), one in a ``times`` column beyond :data:`MAX_TIME` or a line
    with more cells than the header (a column without a name) is a :class:`DataError` naming
    its row and column."""
    low, high, _ = RANGES["position"]
    rows = []
    for offset, line in enumerate(lines):
        if not line.strip():
            continue
        row = first_row + offset
        cells = _cells(line, separator)
        if any(cells[columns:]):
            raise DataError(
                f"{source}: row {row} has {len(cells)} cells, the header names {columns} "
                "columns (a column without a name, or a separator inside a number)"
            )
        cells = (cells + [""] * columns)[:columns]
        values = []
        for column, cell in enumerate(cells):
            try:
                values.append(_number(cell))
            except ValueError:
                raise DataError(
                    f"{source}: row {row}, column {column + 1}: {cell!r} is not a finite number"
                ) from None
            if math.isnan(values[-1]):  # an empty cell
                continue
            if column in positions and not low <= values[-1] <= high:
                raise DataError(
                    f"{source}: row {row}, column {column + 1}: {cell} m is outside the "
                    f"positions the model takes ({low:g} to {high:g} m)"
                )
            if column in times and not abs(values[-1]) <= MAX_TIME:
                raise DataError(
                    f"{source}: row {row}, column {column + 1}: the time {cell} s is beyond "
                    f"{MAX_TIME:g} s"
                )
        rows.append(values)
    if not rows:
        raise DataError(f"{source}: no data rows after the header")
    return np.array(rows, dtype=np.float64).reshape(len(rows), columns)


def _times(source: str, table: FloatArray, column: int, first_row: int) -> tuple[FloatArray, ...]:
    """The rows with a time (a row without one is an unmarked frame: skipped), checked strictly
    increasing: ``(t, kept rows)``."""
    keep = np.isfinite(table[:, column])
    if not keep.any():
        raise DataError(f"{source}: column 't' holds no time")
    t = table[keep, column]
    step = np.diff(t)
    if np.any(step <= 0):
        bad = int(np.flatnonzero(step <= 0)[0])
        row = first_row + int(np.flatnonzero(keep)[bad + 1])
        what = "repeats" if step[bad] == 0 else "is earlier than"
        raise DataError(
            f"{source}: row {row}: the time {t[bad + 1]:g} s {what} the row before "
            f"({t[bad]:g} s): times must be strictly increasing (sort the rows, drop repeats)"
        )
    return t, table[keep]


def _table(source: str, header: list[str], lines: list[str], separator: str) -> Recording:
    """A plain or ``track`` CSV: ``t``, ``x_<id>``, optional ``phi_<id>``."""
    lowered = [cell.lower() for cell in header]
    if "t" not in lowered:
        raise DataError(
            f"{source}: no time column: the header needs a column 't' (s) beside the "
            f"x_<body> columns (got {', '.join(header) or 'nothing'})"
        )
    seen: set[str] = set()
    for cell in header:
        if cell in seen and cell:
            raise DataError(f"{source}: column '{cell}' appears twice in the header")
        seen.add(cell)
    tracks: list[str] = []
    x_column: dict[str, int] = {}
    phi_column: dict[str, int] = {}
    locked_column: dict[tuple[str, int], int] = {}
    for column, cell in enumerate(header):
        if cell.lower() == "t" or not cell:
            continue
        kind, _, name = cell.partition("_")
        if kind == "x" and name:
            x_column[name] = column
            if name not in tracks:
                tracks.append(name)
        elif kind == "phi" and name:
            phi_column[name] = column
        elif kind in ("xlocked1", "xlocked2", "xlocked3") and name:
            locked_column[(name, int(kind[-1]))] = column
        else:
            raise DataError(
                f"{source}: column '{cell}': not a data column (expected t, x_<body id>, "
                "phi_<body id> or xlocked1/2/3_<body id>)"
            )
    for name in phi_column:
        if name not in x_column:
            raise DataError(f"{source}: column 'phi_{name}' has no position column 'x_{name}'")
    for name, degree in locked_column:
        if name not in x_column:
            raise DataError(
                f"{source}: column 'xlocked{degree}_{name}' has no position column 'x_{name}'"
            )
    if not tracks:
        raise DataError(f"{source}: no position column: the header needs x_<body id> columns")
    table = _rows(
        source,
        lines,
        separator,
        len(header),
        2,
        positions=list(x_column.values()),
        times=[lowered.index("t")],
    )
    t, table = _times(source, table, lowered.index("t"), 2)
    x = np.stack([table[:, x_column[name]] for name in tracks], axis=1)
    phi = np.stack(
        [
            table[:, phi_column[name]] if name in phi_column else np.full(len(t), np.nan)
            for name in tracks
        ],
        axis=1,
    )
    locked_error = None
    if locked_column:
        locked_error = np.zeros((len(tracks), 3))
        for (name, degree), column in locked_column.items():
            cells = table[:, column][np.isfinite(table[:, column])]
            if cells.size and (np.any(cells < 0) or np.ptp(cells) > 0):
                raise DataError(
                    f"{source}: column 'xlocked{degree}_{name}': must hold one error >= 0 (m), "
                    "the same in every row"
                )
            locked_error[tracks.index(name), degree - 1] = float(cells[0]) if cells.size else 0.0
    return Recording(source, t, tuple(tracks), x, phi, "csv", locked_error)


def _tracker(
    source: str,
    names: list[str],
    header: list[str],
    lines: list[str],
    separator: str,
    first_row: int,
    kind: str,
) -> Recording:
    """A Tracker data file: the track names (each above its first column), the column names,
    the rows."""
    lowered = [cell.lower() for cell in header]
    if not lowered or lowered[0] != "t":
        raise DataError(
            f"{source}: no time column: Tracker's column names must start with 't' (got "
            f"{', '.join(header) or 'nothing'})"
        )
    owner: list[str | None] = []
    current: str | None = None
    for column in range(len(header)):
        name = names[column] if column < len(names) else ""
        if name:
            current = name
        owner.append(current if column > 0 else None)
    if not any(owner):  # one track named on the first line, in the time column's cell
        single = next((n for n in names if n), "")
        owner = [None] + [single] * (len(header) - 1)
    tracks: list[str] = []
    x_column: dict[str, int] = {}
    for column, (owned, cell) in enumerate(zip(owner, lowered, strict=True)):
        if owned is None or cell != "x":
            continue
        name = owned
        if name in x_column:
            raise DataError(f"{source}: track '{name}' has two 'x' columns")
        x_column[name] = column
        tracks.append(name)
    if not tracks:
        raise DataError(f"{source}: no 'x' column of any track (columns: {', '.join(header)})")
    clocks = [column for column, cell in enumerate(lowered) if cell == "t"]
    table = _rows(
        source,
        lines,
        separator,
        len(header),
        first_row,
        positions=list(x_column.values()),
        times=clocks,
    )
    _same_clock(source, table, clocks, owner, first_row)
    t, table = _times(source, table, 0, first_row)
    x = np.stack([table[:, x_column[name]] for name in tracks], axis=1)
    return Recording(source, t, tuple(tracks), x, np.full_like(x, np.nan), kind)


def _same_clock(
    source: str, table: FloatArray, clocks: list[int], owner: list[str | None], first_row: int
) -> None:
    """A Tracker ``#multi:`` file whose tracks each have a ``t`` column: each must read the
    first column's time in every row where both are given (to a thousandth of a frame, the
    rounding of printed times), else the tracks are on different clocks: a
    :class:`DataError` naming the row and the track."""
    if len(clocks) < 2:
        return
    first = table[:, clocks[0]]
    steps = np.diff(first[np.isfinite(first)])
    tolerance = 1e-3 * float(np.median(steps)) if steps.size else 0.0
    for column in clocks[1:]:
        other = table[:, column]
        both = np.isfinite(first) & np.isfinite(other)
        off = both & ~(np.abs(other - first) <= tolerance + 1e-12 * np.abs(first))
        if off.any():
            row = int(np.flatnonzero(off)[0])
            track = owner[column] or f"column {column + 1}"
            raise DataError(
                f"{source}: row {first_row + row}: track '{track}' has t = {other[row]:g} s "
                f"where the first column has {first[row]:g} s (tracks on different clocks; "
                "export them with one time column, or align their times)"
            )


def match_bodies(
    recording: Recording, system: System, mapping: Mapping[str, str] | None = None
) -> BodyData:
    """Each track of ``recording`` matched to a body of ``system``: by ``mapping`` (track ->
    body id, ``--map track=body``), else by name. A track or a mapped body that is not in the
    system, a body measured twice, or no position at all is a one-line :class:`DataError`."""
    mapping = dict(mapping or {})
    ids = [body.id for body in system.bodies]
    for track, body in mapping.items():
        if track not in recording.tracks:
            raise DataError(
                f"--map {track}={body}: {recording.source} has no track '{track}' (tracks: "
                f"{', '.join(recording.tracks)})"
            )
        if body not in ids:
            raise DataError(f"--map {track}={body}: no body '{body}' (bodies: {', '.join(ids)})")
    by_body: dict[str, int] = {}
    for column, track in enumerate(recording.tracks):
        body = mapping.get(track, track)
        if body not in ids:
            what = "column 'x_" + track + "'" if recording.format == "csv" else f"track '{track}'"
            raise DataError(
                f"{recording.source}: {what}: no body '{body}' in the system (bodies: "
                f"{', '.join(ids)}); match it with --map {track}=BODY"
            )
        if body in by_body:
            raise DataError(
                f"{recording.source}: body '{body}' is measured twice (tracks "
                f"'{recording.tracks[by_body[body]]}' and '{track}')"
            )
        by_body[body] = column
    order = [i for i, body in enumerate(ids) if body in by_body]
    columns = [by_body[ids[i]] for i in order]
    x, phi = recording.x[:, columns], recording.phi[:, columns]
    for j, i in enumerate(order):
        if not np.isfinite(x[:, j]).any():
            raise DataError(
                f"{recording.source}: body '{ids[i]}' has no position (every cell empty)"
            )
        angles = np.isfinite(phi[:, j])
        if angles.any() and np.any(angles & ~np.isfinite(x[:, j])):
            row = int(np.flatnonzero(angles & ~np.isfinite(x[:, j]))[0])
            raise DataError(
                f"{recording.source}: body '{ids[i]}': an angle without a position at "
                f"t = {recording.t[row]:g} s"
            )
    locked_error = None if recording.locked_error is None else recording.locked_error[columns]
    return BodyData(
        recording.source,
        recording.t,
        tuple(ids[i] for i in order),
        tuple(order),
        x,
        phi,
        locked_error,
    )

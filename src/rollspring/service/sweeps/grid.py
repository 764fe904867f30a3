"""The grid of a sweep: its PATHs, their values, and the chunks it is cut into.

A PATH names one number of a system (docs/sweeps.md): the batch paths
``bodies.<id>.mass|radius|mu_static|mu_kinetic|x|v``, ``springs.<index>.stiffness|rest_length``
and ``gravity`` (given to :func:`rollspring.simulate_batch` as they are), ``modes.<n>.amplitude``
(start at rest at the equilibrium displaced along mode ``n``) and the attachment geometry
``springs.<index>.at.<end>.height|radius|angle``. The grid is the outer product of the values in
the order given; run ``r`` is the C-order (last PATH fastest) flat index.

Chunks are hyper-rectangles of the grid aligned with the Zarr chunks: whole trailing dimensions
while they fit in the requested number of runs, then a slice of the next one, then 1.
Everything here is index arithmetic: a chunk's parameter values are made from its own indices,
never from arrays over the whole grid.
"""

from __future__ import annotations

import math
import numbers
import re
from collections.abc import Iterable, Mapping, Sequence, Sized
from dataclasses import dataclass
from typing import Any

import numpy as np

from rollspring.errors import RollspringError, SweepError
from rollspring.model import System, system_from_dict, system_to_json
from rollspring.simulate.batch.parameters import NO_ROLLING_RESISTANCE
from rollspring.simulate.costs import MAX_RUNS

__all__ = [
    "BATCH_BODY_QUANTITIES",
    "UNITS",
    "Grid",
    "SweepError",
    "apply_values",
    "chunk_shape",
    "parse_vary_spec",
    "path_kind",
]


BATCH_BODY_QUANTITIES = ("mass", "radius", "mu_static", "mu_kinetic", "x", "v")
_SPRING_QUANTITIES = ("stiffness", "rest_length")
_AT_QUANTITIES = ("height", "radius", "angle")

#: Unit of each kind of PATH (SI; the last part of the PATH names the quantity).
UNITS = {
    "mass": "kg",
    "radius": "m",
    "mu_static": "1",
    "mu_kinetic": "1",
    "x": "m",
    "v": "m/s",
    "stiffness": "N/m",
    "rest_length": "m",
    "gravity": "m/s^2",
    "amplitude": "m",
    "height": "m",
    "angle": "deg",
}


def path_kind(system: System, path: str) -> tuple[str, tuple[Any, ...]]:
    """``(kind, target)`` of a PATH: kind ``batch`` (a :func:`simulate_batch` path), ``mode``
    (target ``(n,)``) or ``at`` (target ``(spring, end, quantity)``); a :class:`SweepError`
    naming the PATH otherwise."""
    if not isinstance(path, str) or not path:
        raise SweepError(f"--vary: empty PATH (give e.g. bodies.{system.bodies[0].id}.mass)")
    parts = path.split(".")
    ids = [b.id for b in system.bodies]
    n_springs = len(system.springs)

    def bad(reason: str) -> SweepError:
        return SweepError(f"--vary {path}: {reason}")

    def spring_index(text: str) -> int:
        if not text.isdigit() or int(text) >= n_springs:
            raise bad(
                f"no spring '{text}' (springs are numbered 0 to {n_springs - 1} in file order)"
                if n_springs
                else f"no spring '{text}' (the system has none)"
            )
        return int(text)

    if parts == ["gravity"]:
        return "batch", ()
    if parts[0] == "bodies" and len(parts) == 3:
        if parts[1] not in ids:
            raise bad(f"no body '{parts[1]}' (bodies: {', '.join(ids)})")
        if parts[2] == "rolling_resistance":
            raise bad(NO_ROLLING_RESISTANCE)
        if parts[2] not in BATCH_BODY_QUANTITIES:
            raise bad(
                f"unknown body quantity '{parts[2]}' (one of {', '.join(BATCH_BODY_QUANTITIES)})"
            )
        return "batch", ()
    if parts[0] == "springs" and len(parts) == 3:
        spring_index(parts[1])
        if parts[2] not in _SPRING_QUANTITIES:
            raise bad(
                f"unknown spring quantity '{parts[2]}' (one of "
                f"{', '.join(_SPRING_QUANTITIES)}, or at.<end>.height|radius|angle)"
            )
        return "batch", ()
    if parts[0] == "springs" and len(parts) == 5 and parts[2] == "at":
        k = spring_index(parts[1])
        if parts[3] not in ("0", "1"):
            raise bad(f"no end '{parts[3]}' (a spring's ends are 0 and 1)")
        end = int(parts[3])
        if parts[4] not in _AT_QUANTITIES:
            raise bad(
                f"unknown attachment quantity '{parts[4]}' (one of {', '.join(_AT_QUANTITIES)})"
            )
        if system.springs[k].ends[end] not in ids:
            raise bad(
                f"end {end} of spring {k} is the anchor "
                f"'{system.springs[k].ends[end]}', which has no attachment"
            )
        return "at", (k, end, parts[4])
    if parts[0] == "modes" and len(parts) == 3:
        if not parts[1].isdigit() or int(parts[1]) >= len(system.bodies):
            raise bad(
                f"no mode '{parts[1]}' (modes are numbered 0 to {len(system.bodies) - 1}, "
                "sorted by omega as analyze sorts them)"
            )
        if parts[2] != "amplitude":
            raise bad(f"unknown mode quantity '{parts[2]}' (only amplitude)")
        return "mode", (int(parts[1]),)
    raise bad(
        "unknown PATH (use bodies.<id>.<quantity>, springs.<index>.<quantity>, "
        "springs.<index>.at.<end>.<quantity>, modes.<n>.amplitude or gravity)"
    )


def unit_of(path: str) -> str:
    """SI unit of a PATH's values."""
    return UNITS[path.split(".")[-1]]


_NUMBER = r"[-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?|[-+]?inf"


def _number(text: str, spec: str) -> float:
    text = text.strip()
    if not re.fullmatch(_NUMBER, text, flags=re.IGNORECASE):
        raise SweepError(f"--vary {spec}: '{text}' is not a number")
    return float(text)


def parse_vary_spec(spec: str) -> tuple[str, list[float]]:
    """``PATH=START:STOP:NUM[:log]`` (NUM values from START to STOP, evenly or geometrically
    spaced, both ends included) or ``PATH=v1,v2,...`` -> ``(PATH, values)``."""
    if not isinstance(spec, str) or "=" not in spec:
        raise SweepError(f"--vary {spec}: expected PATH=START:STOP:NUM[:log] or PATH=v1,v2,...")
    path, _, rhs = spec.partition("=")
    path = path.strip()
    if not path:
        raise SweepError(f"--vary {spec}: the PATH before '=' is empty")
    if not rhs.strip():
        raise SweepError(f"--vary {spec}: no values after '='")
    if ":" in rhs:
        parts = rhs.split(":")
        if len(parts) not in (3, 4):
            raise SweepError(f"--vary {spec}: a range is START:STOP:NUM or START:STOP:NUM:log")
        if len(parts) == 4 and parts[3].strip() != "log":
            raise SweepError(
                f"--vary {spec}: the fourth part of a range can only be 'log', got '{parts[3]}'"
            )
        start, stop = _number(parts[0], spec), _number(parts[1], spec)
        if not parts[2].strip().isdigit() or int(parts[2]) < 1:
            raise SweepError(
                f"--vary {spec}: NUM must be a whole number >= 1, got '{parts[2].strip()}'"
            )
        num = int(parts[2])
        if num > MAX_RUNS:  # before an array of that many values is made
            raise SweepError(
                f"--vary {spec}: {num:.3g} values, more than a sweep holds ({MAX_RUNS:.0e} runs)"
            )
        if not (math.isfinite(start) and math.isfinite(stop)):
            raise SweepError(f"--vary {spec}: a range needs finite ends")
        if len(parts) == 4:
            if start <= 0 or stop <= 0:
                raise SweepError(f"--vary {spec}: a log range needs START and STOP > 0")
            values = np.geomspace(start, stop, num)
        else:
            values = np.linspace(start, stop, num)
        return path, [float(v) for v in values]
    return path, [_number(v, spec) for v in rhs.split(",")]


def chunk_shape(shape: tuple[int, ...], runs: int) -> tuple[int, ...]:
    """Chunk shape of at most ``runs`` runs (at least one): whole trailing dimensions while
    they fit, then a part of the next one, then 1."""
    out = [1] * len(shape)
    product = 1
    for d in reversed(range(len(shape))):
        if product * shape[d] <= runs:
            out[d] = shape[d]
            product *= shape[d]
        else:
            out[d] = max(1, runs // product)
            break
    return tuple(out)


@dataclass(frozen=True)
class Grid:
    """The PATHs (in order), their values and the chunking; pure index arithmetic."""

    paths: tuple[str, ...]
    values: tuple[tuple[float, ...], ...]
    chunks: tuple[int, ...]  # chunk shape

    @property
    def shape(self) -> tuple[int, ...]:
        return tuple(len(v) for v in self.values)

    @property
    def n_runs(self) -> int:
        return math.prod(self.shape)

    @property
    def chunk_grid(self) -> tuple[int, ...]:
        """Number of chunks along each dimension."""
        return tuple(-(-n // c) for n, c in zip(self.shape, self.chunks, strict=True))

    @property
    def n_chunks(self) -> int:
        return math.prod(self.chunk_grid)

    def region(self, index: int) -> tuple[slice, ...]:
        """The slices of the grid chunk ``index`` (C order over the chunk grid) covers."""
        position = np.unravel_index(index, self.chunk_grid)
        return tuple(
            slice(int(p) * c, min((int(p) + 1) * c, n))
            for p, c, n in zip(position, self.chunks, self.shape, strict=True)
        )

    def chunk_values(self, index: int) -> tuple[tuple[int, ...], dict[str, np.ndarray]]:
        """The region shape of chunk ``index`` and every PATH's value for each of its runs
        (flat, C order of the region)."""
        region = self.region(index)
        local = tuple(s.stop - s.start for s in region)
        grids = np.meshgrid(
            *(np.asarray(self.values[d][s], dtype=np.float64) for d, s in enumerate(region)),
            indexing="ij",
        )
        return local, {p: g.ravel() for p, g in zip(self.paths, grids, strict=True)}


def apply_values(
    base: dict[str, Any], system: System, values: Mapping[str, float], *, source: str = "sweep"
) -> System:
    """The system ``base`` (its :func:`system_to_json` form) with the batch and attachment
    PATHs in ``values`` set (mode amplitudes are not placements: see the compute module)."""
    index = {b.id: i for i, b in enumerate(system.bodies)}
    # copy only the containers the values change (validation does not mutate its input)
    data = dict(base)
    touched: dict[str, set[int]] = {"bodies": set(), "springs": set()}
    for path in values:
        parts = path.split(".")
        if parts[0] == "bodies":
            touched["bodies"].add(index[parts[1]])
        elif parts[0] == "springs":
            touched["springs"].add(int(parts[1]))
    for group, members in touched.items():
        if members:
            data[group] = list(base[group])
            for i in members:
                data[group][i] = dict(base[group][i])
    for path, value in values.items():
        parts = path.split(".")
        value = float(value)
        if parts[0] == "gravity":
            data["gravity"] = value
        elif parts[0] == "bodies":
            data["bodies"][index[parts[1]]][parts[2]] = value
        elif parts[0] == "springs" and len(parts) == 3:
            data["springs"][int(parts[1])][parts[2]] = value
        elif parts[0] == "springs":
            k, end, quantity = int(parts[1]), int(parts[3]), parts[4]
            spring = data["springs"][k]
            ats = spring.get("at") or [{}, {}]
            at = dict(ats[end])
            if quantity == "height":
                at = {"height": value}
            elif quantity == "radius":
                at.pop("height", None)
                at["radius"] = value
            else:
                if "radius" not in at:
                    raise SweepError(
                        f"--vary {path}: an angle needs a radius attachment "
                        "(give the end {radius = r} in the system, or vary "
                        f"springs.{k}.at.{end}.radius too)"
                    )
                at["angle"] = value
            ats = [dict(a) for a in ats]
            ats[end] = at
            spring["at"] = ats
    return system_from_dict(data, source=source)


#: Quantities whose value only its own body or spring validates (no check of the whole system
#: looks at them: not the placement, lengths or attachments), with that model.
_OWN_CHECK = {
    ("bodies", "mass"),
    ("bodies", "mu_static"),
    ("bodies", "mu_kinetic"),
    ("bodies", "v"),
    ("springs", "stiffness"),
}


def _part_of(base: dict[str, Any], system: System, path: str) -> dict[str, Any] | None:
    """The JSON form of the body or spring a PATH's value is checked by alone, or None."""
    parts = path.split(".")
    if len(parts) != 3 or (parts[0], parts[2]) not in _OWN_CHECK:
        return None
    if parts[0] == "bodies":
        index = [b.id for b in system.bodies].index(parts[1])
        return base["bodies"][index]
    return base["springs"][int(parts[1])]


def _part_valid(part: dict[str, Any], path: str, value: float) -> bool:
    """Whether the body or spring with ``value`` validates (a refusal is re-checked on the
    whole system, which words the message)."""
    from pydantic import ValidationError

    from rollspring.model import Body, Spring

    data = dict(part)
    data[path.split(".")[-1]] = value
    try:
        (Body if path.startswith("bodies.") else Spring).model_validate(data)
    except (ValidationError, ValueError):
        return False
    return True


def count_grid(vary: Mapping[str, Sequence[float]]) -> int:
    """The runs of the grid ``vary`` (the product of its lengths, in Python integers: nothing of
    the grid's size is made); :class:`SweepError` above :data:`MAX_RUNS`."""
    if not isinstance(vary, Mapping):
        return 1  # check_grid says what is wrong
    runs = 1
    for path, raw in vary.items():
        count = len(raw) if isinstance(raw, Sized) and not isinstance(raw, str | bytes) else 1
        runs *= count
        if runs > MAX_RUNS:
            raise SweepError(
                f"--vary {path}: the grid reaches {runs:.3g} runs, more than a sweep holds "
                f"({MAX_RUNS:.0e}); sweep it in parts"
            )
    return runs


def check_grid(
    system: System, vary: Mapping[str, Sequence[float]]
) -> tuple[tuple[str, ...], tuple[tuple[float, ...], ...]]:
    """Validate the PATHs and each value (each alone applied to ``system``): one-line
    :class:`SweepError` naming the PATH."""
    if not isinstance(vary, Mapping) or not vary:
        raise SweepError("--vary: give at least one PATH to vary")
    paths, values = [], []
    base = system_to_json(system)
    kinds = {}
    for path, raw in vary.items():
        kind, _target = path_kind(system, path)
        kinds[path] = kind
        array = _numbers(path, raw)
        if array.ndim == 0:
            array = array[None]
        if array.ndim != 1 or array.size == 0:
            raise SweepError(f"--vary {path}: give a non-empty list of numbers")
        if np.any(np.isnan(array)):
            raise SweepError(f"--vary {path}: NaN is not a value")
        if len(np.unique(array)) != array.size:
            raise SweepError(f"--vary {path}: a value is given twice")
        quantity = path.split(".")[-1]
        if not (quantity == "mu_static" and path.startswith("bodies.")) and not np.all(
            np.isfinite(array)
        ):
            raise SweepError(f"--vary {path}: the values must be finite")
        if kind == "mode":
            if np.any(array < 0):
                raise SweepError(f"--vary {path}: an amplitude must be >= 0")
        else:
            part = _part_of(base, system, path)
            if part is None or not _ends_valid(part, path, array):
                _check_each(base, system, path, part, array)
        paths.append(path)
        values.append(tuple(float(v) for v in array))
    _check_friction_pairs(dict(zip(paths, values, strict=True)))
    return tuple(paths), tuple(values)


def _check_friction_pairs(grid: dict[str, tuple[float, ...]]) -> None:
    """A body whose mu_static and mu_kinetic are both varied: each value is valid alone, but
    no run is when every mu_kinetic exceeds every mu_static (mu_kinetic <= mu_static):
    :class:`SweepError`, as for any grid without a valid run (it was a store of runs all
    invalid, exit 0)."""
    for path, statics in grid.items():
        parts = path.split(".")
        if len(parts) != 3 or parts[0] != "bodies" or parts[2] != "mu_static":
            continue
        kinetics = grid.get(f"bodies.{parts[1]}.mu_kinetic")
        if kinetics is not None and min(kinetics) > max(statics):
            raise SweepError(
                f"--vary: no run of the grid is a valid system: every bodies.{parts[1]}."
                f"mu_kinetic ({min(kinetics):g} and up) exceeds every mu_static (up to "
                f"{max(statics):g}); mu_kinetic must not exceed mu_static"
            )


def _numbers(path: str, raw: Any) -> np.ndarray:
    """The values of ``--vary PATH`` as floats: numbers only (a bool, a string or anything
    else is not one; NumPy's numbers are), none too large for a float."""
    if isinstance(raw, np.ndarray):
        if raw.dtype.kind not in "iuf":
            raise SweepError(
                f"--vary {path}: the values must be numbers, got an array of {raw.dtype}"
            )
        with np.errstate(over="ignore"):
            return np.asarray(raw, dtype=np.float64)
    listed = isinstance(raw, Iterable) and isinstance(raw, Sized) and not isinstance(raw, str)
    items: Iterable[Any] = raw if listed else [raw]
    values = []
    for item in items:
        if isinstance(item, bool | np.bool_) or not isinstance(item, numbers.Real):
            raise SweepError(
                f"--vary {path}: the values must be numbers, got {type(item).__name__} "
                f"{_shortened(item)}"
            )
        try:
            values.append(float(item))
        except OverflowError:
            raise SweepError(
                f"--vary {path}: {_shortened(item)} is too large for a float"
            ) from None
    array = np.array(values, dtype=np.float64)
    return array if listed else array[0]


def _shortened(item: Any) -> str:
    """``repr(item)``, its middle cut when long (a 5000-digit integer)."""
    if isinstance(item, int) and not isinstance(item, bool) and abs(item) >= 10**20:
        return "an integer of more than 20 digits"
    text = repr(item)
    return text if len(text) <= 40 else text[:18] + "…" + text[-18:]


def _ends_valid(part: dict[str, Any], path: str, values: np.ndarray) -> bool:
    """Whether the body or spring ``part`` validates with each of ``values``, from its smallest
    and largest finite values and its infinite ones: with the rest of its body or spring fixed,
    the finite values a quantity of :data:`_OWN_CHECK` may take are an interval (its range, and
    ``mu_kinetic <= mu_static``), so its ends decide (a few validations, not one a value)."""
    finite = values[np.isfinite(values)]
    probes = {float(v) for v in values[~np.isfinite(values)]}
    if finite.size:
        probes |= {float(finite.min()), float(finite.max())}
    return all(_part_valid(part, path, value) for value in probes)


def _check_each(
    base: dict[str, Any], system: System, path: str, part: dict[str, Any] | None, values: np.ndarray
) -> None:
    """Each of ``values`` applied alone to ``system`` (its body or spring first, when that
    decides): :class:`SweepError` wording the first refused."""
    for value in values:
        if part is not None and _part_valid(part, path, float(value)):
            continue
        try:
            apply_values(base, system, {path: float(value)}, source=f"--vary {path}")
        except SweepError:
            raise
        except RollspringError as exc:
            raise SweepError(f"{exc} (value {float(value)!r})") from None

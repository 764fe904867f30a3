"""Batch parameters: the paths a batch may vary (``bodies.<id>.mass`` ...), checked and broadcast
to one run count, and the per-run values of every quantity (:class:`Runs`)."""

from __future__ import annotations

from collections.abc import Mapping, Sized
from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import ArrayLike

from rollspring.errors import ModelError
from rollspring.model import RANGES, System
from rollspring.physics import system_arrays
from rollspring.physics.arrays import FloatArray

__all__ = [
    "NO_ROLLING_RESISTANCE",
    "PARAMETER_QUANTITIES",
    "Runs",
    "parse_parameters",
    "system_runs",
]

#: Quantities a parameter path may name: ``bodies.<id>.<q>``, ``springs.<index>.<q>``, ``gravity``.
PARAMETER_QUANTITIES = {
    "bodies": ("mass", "radius", "mu_static", "mu_kinetic", "x", "v"),
    "springs": ("stiffness", "rest_length"),
    "gravity": (),
}


#: Why a batch (and so a sweep) refuses a rolling resistance, varied or in the system.
NO_ROLLING_RESISTANCE = (
    "batch runs take no rolling resistance (symplectic integrators, no stick events); "
    "use rollspring.simulate"
)


def _bad(key: str, reason: str) -> ModelError:
    return ModelError(f"parameters[{key!r}]: {reason}")


@dataclass
class Runs:
    """The per-run values of every parameter (each ``(n_runs,)`` or ``(n_runs, n)``)."""

    n_runs: int
    mass: FloatArray
    radius: FloatArray
    mu_static: FloatArray
    mu_kinetic: FloatArray
    x: FloatArray
    v: FloatArray
    stiffness: FloatArray
    rest_length: FloatArray  # NaN where the spring's rest length is its initial length
    gravity: FloatArray
    parameters: dict[str, FloatArray]
    targets: dict[str, tuple[str, int]]  # key -> (quantity, body or spring index)


def parse_parameters(system: System, parameters: Mapping[str, ArrayLike]) -> Runs:
    """Check the parameter paths and values, broadcast them to one run count."""
    if not isinstance(parameters, Mapping):
        raise ModelError(
            f"parameters: must be a mapping of paths to arrays, got {type(parameters).__name__}"
        )
    index = {b.id: i for i, b in enumerate(system.bodies)}
    n_springs = len(system.springs)
    targets: dict[str, tuple[str, int]] = {}
    values: dict[str, FloatArray] = {}
    for key, raw in parameters.items():
        if not isinstance(key, str):
            raise ModelError(
                f"parameters: keys must be strings like 'bodies.<id>.mass', got {key!r}"
            )
        parts = key.split(".")
        if parts == ["gravity"]:
            targets[key] = ("gravity", 0)
        elif len(parts) == 3 and parts[0] == "bodies":
            _, ident, quantity = parts
            if ident not in index:
                raise _bad(key, f"no body '{ident}' (bodies: {', '.join(index)})")
            if quantity == "rolling_resistance":
                raise _bad(key, NO_ROLLING_RESISTANCE)
            if quantity not in PARAMETER_QUANTITIES["bodies"]:
                raise _bad(
                    key,
                    f"unknown body quantity '{quantity}' (one of "
                    f"{', '.join(PARAMETER_QUANTITIES['bodies'])})",
                )
            targets[key] = (quantity, index[ident])
        elif len(parts) == 3 and parts[0] == "springs":
            _, number, quantity = parts
            if not number.isdigit() or int(number) >= n_springs:
                raise _bad(
                    key,
                    f"no spring '{number}' (springs are numbered 0 to "
                    f"{n_springs - 1} in file order)"
                    if n_springs
                    else f"no spring '{number}' (the system has no springs)",
                )
            if quantity not in PARAMETER_QUANTITIES["springs"]:
                raise _bad(
                    key,
                    f"unknown spring quantity '{quantity}' (one of "
                    f"{', '.join(PARAMETER_QUANTITIES['springs'])})",
                )
            targets[key] = (quantity, int(number))
        else:
            raise _bad(
                key,
                "unknown parameter path (use 'bodies.<id>.<quantity>', "
                "'springs.<index>.<quantity>' or 'gravity')",
            )
        same = [
            other for other, target in targets.items() if other != key and target == targets[key]
        ]
        if same:
            raise _bad(key, f"names the same parameter as {same[0]!r}")
        if _has_bool(raw):  # NumPy would take True as 1.0
            raise _bad(key, "must be numbers, not true/false")
        try:
            array = np.asarray(raw, dtype=np.float64)
        except (TypeError, ValueError):
            raise _bad(key, "must be a number or a 1-D array of numbers") from None
        if array.ndim > 1:
            raise _bad(key, f"must be a number or a 1-D array, got shape {array.shape}")
        values[key] = array
    lengths = {key: a.shape[0] for key, a in values.items() if a.ndim == 1}
    sizes = set(lengths.values()) - {1}
    if len(sizes) > 1:
        first = next(key for key, size in lengths.items() if size != 1)
        for key, size in lengths.items():
            if size not in (1, lengths[first]):
                raise _bad(
                    key,
                    f"has {size} values but '{first}' has {lengths[first]}: "
                    "all arrays must have one length (or one value)",
                )
    n_runs = sizes.pop() if sizes else 1
    if n_runs == 0:
        raise _bad(next(iter(lengths)), "is empty: a batch needs at least one run")
    broadcast = {key: np.broadcast_to(a, (n_runs,)).copy() for key, a in values.items()}

    runs = system_runs(system, n_runs)
    runs.parameters = broadcast
    runs.targets = targets
    for key, value in broadcast.items():
        quantity, i = targets[key]
        _check_values(key, quantity, value)
        if quantity == "gravity":
            runs.gravity[:] = value
        else:
            getattr(runs, quantity)[:, i] = value
    # mu_kinetic may not exceed mu_static (its default is mu_static, or 0 when that is inf)
    fill_defaults(runs)
    over = runs.mu_kinetic > runs.mu_static
    if np.any(over):
        run, i = (int(v[0]) for v in np.nonzero(over))
        key = next(
            (k for k, (q, j) in targets.items() if q in ("mu_static", "mu_kinetic") and j == i),
            f"bodies.{system.bodies[i].id}.mu_kinetic",
        )
        raise _bad(
            key,
            f"mu_kinetic ({runs.mu_kinetic[run, i]:g}) exceeds mu_static "
            f"({runs.mu_static[run, i]:g}) in run {run}",
        )
    return runs


def count_runs(parameters: Mapping[str, ArrayLike]) -> int:
    """How many runs ``parameters`` broadcast to, from their lengths alone (no array of the
    runs' size is made); :class:`ModelError` above :data:`~rollspring.simulate.costs.MAX_RUNS`.
    The values themselves are checked by :func:`parse_parameters`."""
    from rollspring.simulate.costs import MAX_RUNS

    if not isinstance(parameters, Mapping):
        return 1  # parse_parameters says what is wrong
    lengths = {
        key: len(raw)
        for key, raw in parameters.items()
        if isinstance(raw, Sized) and not isinstance(raw, str | bytes) and _sized_axis(raw)
    }
    runs = max(lengths.values(), default=1)
    if runs > MAX_RUNS:
        key = max(lengths, key=lambda name: lengths[name])
        raise _bad(
            key,
            f"{runs:.3g} runs, more than one batch holds ({MAX_RUNS:.0e}); split the batch",
        )
    return runs


def _sized_axis(raw: Sized) -> bool:
    """Whether ``raw`` is a sequence of values (not a 0-d array), told without converting it."""
    return bool(getattr(raw, "ndim", 1))


def _has_bool(raw: Any) -> bool:
    """Whether ``raw`` (a value or a sequence of them) holds a bool: a bool array, a bool, or a
    list with one (NumPy would convert them to 0.0 and 1.0 without a word)."""
    if isinstance(raw, np.ndarray):
        return raw.dtype == np.bool_ or (
            raw.dtype == object and any(isinstance(v, bool | np.bool_) for v in raw.flat)
        )
    if isinstance(raw, list | tuple):
        return any(_has_bool(v) for v in raw)
    return isinstance(raw, bool | np.bool_)


def system_runs(system: System, n_runs: int) -> Runs:
    """``n_runs`` runs of the system's own values (no parameters)."""
    arrays = system_arrays(system)
    n_springs = len(system.springs)

    def per_body(base: ArrayLike) -> FloatArray:
        return np.repeat(np.asarray(base, dtype=np.float64)[None, :], n_runs, axis=0)

    return Runs(
        n_runs=n_runs,
        mass=per_body(arrays.mass),
        radius=per_body(arrays.radius),
        mu_static=per_body(arrays.mu_static),
        mu_kinetic=per_body(
            [b.mu_kinetic if b.mu_kinetic is not None else np.nan for b in system.bodies]
        ),
        x=per_body(arrays.x0),
        v=per_body(arrays.v0),
        stiffness=per_body(arrays.stiffness).reshape(n_runs, n_springs),
        rest_length=per_body(
            [s.rest_length if s.rest_length is not None else np.nan for s in system.springs]
        ).reshape(n_runs, n_springs),
        gravity=np.full(n_runs, float(arrays.gravity)),
        parameters={},
        targets={},
    )


def fill_defaults(runs: Runs) -> None:
    """``mu_kinetic`` where not given: ``mu_static``, or 0 when that is inf."""
    default_k = np.where(np.isfinite(runs.mu_static), runs.mu_static, 0.0)
    runs.mu_kinetic = np.where(np.isnan(runs.mu_kinetic), default_k, runs.mu_kinetic)


#: The batch quantities' ranges: those a system file has (``rollspring.model.RANGES``).
_RANGE_OF = {
    "mass": "mass",
    "radius": "radius",
    "mu_static": "friction",
    "mu_kinetic": "friction",
    "x": "position",
    "v": "velocity",
    "stiffness": "stiffness",
    "rest_length": "rest_length",
    "gravity": "gravity",
}


def _check_values(key: str, quantity: str, value: FloatArray) -> None:
    """Every run's value of ``key`` a number in the range a system file takes
    (``rollspring.model.RANGES``; ``mu_static`` may be inf), else a :class:`ModelError` naming
    the key, the range and the first run outside it."""

    def first(mask: np.ndarray) -> str:
        run = int(np.flatnonzero(mask)[0])
        return f"run {run} has {float(value[run])!r}"

    if quantity == "mu_static":
        bad = np.isnan(value) | (value < 0)
        if np.any(bad):
            raise _bad(key, f"must be >= 0 (inf allowed) ({first(bad)})")
        value = np.where(np.isinf(value), 0.0, value)
    elif not np.all(np.isfinite(value)):
        raise _bad(key, f"must be finite ({first(~np.isfinite(value))})")
    if quantity in ("mass", "radius", "stiffness") and np.any(value <= 0):
        raise _bad(key, f"must be > 0 ({first(value <= 0)})")
    if quantity in ("mu_kinetic", "rest_length", "gravity") and np.any(value < 0):
        raise _bad(key, f"must be >= 0 ({first(value < 0)})")
    name = _RANGE_OF.get(quantity)
    if name is not None:
        low, high, unit = RANGES[name]
        outside = (value < low) | (value > high)
        if np.any(outside):
            raise _bad(
                key,
                f"must be between {low:g} and {high:g}{' ' + unit if unit else ''}, the "
                f"verified range a system file takes ({first(outside)})",
            )

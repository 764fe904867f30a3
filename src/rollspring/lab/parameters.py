"""The numbers of a system a fit may free: the sweep's PATHs, and any other number of the system.

A PATH walks the system's JSON form (:func:`rollspring.model.system_to_json`): ``gravity``,
``bodies.<id>.<field>`` (``mass``, ``radius``, ``mu_static``, ``rolling_resistance``, ...),
``springs.<index>.<field>`` (``stiffness``, ``damping``, ``rest_length``),
``springs.<index>.at.<end>.<field>``, ``anchors.<id>.<field>``, ``forces.<index>.<field>``.
Whatever the model validates as a number is a PATH; the value set is checked by the model
itself (:func:`rollspring.model.system_from_dict`), so a value outside a range is refused in
the model's words. The initial state (``bodies.<id>.x``, ``.v``) is not a PATH: the fit frees
it on its own (``--fix-initial`` holds it).
"""

from __future__ import annotations

import copy
import math
from collections.abc import Mapping, Sequence
from typing import Any

import numpy as np

from rollspring.errors import FitError, RollspringError
from rollspring.model import RANGES, System, system_from_dict, system_to_json
from rollspring.physics import system_arrays
from rollspring.physics.mechanics import spring_state

__all__ = [
    "INITIAL_STATE",
    "bounds_of",
    "check_paths",
    "get_value",
    "pinned_json",
    "with_values",
]

#: The fields of a body that are its initial state (fitted as such, not as PATHs).
INITIAL_STATE = ("x", "v")

#: Which range of :data:`rollspring.model.RANGES` bounds each quantity (the PATH's last part).
_RANGE_OF = {
    "mass": "mass",
    "radius": "radius",
    "stiffness": "stiffness",
    "damping": "damping",
    "rest_length": "rest_length",
    "gravity": "gravity",
    "mu_static": "friction",
    "mu_kinetic": "friction",
    "rolling_resistance": "rolling_resistance",
    "track_height": "position",
    "fx": "force",
    "fy": "force",
    "height": "attachment",
    "angle": "angle",
}


def pinned_json(system: System) -> dict[str, Any]:
    """The system's JSON form with every spring's rest length written out (a spring without
    one rests at its initial length, which would move with the fitted initial positions)."""
    data = system_to_json(system)
    if any(spring.get("rest_length") is None for spring in data["springs"]):
        arrays = system_arrays(system)
        lengths = spring_state(arrays, np.zeros(arrays.n_bodies)).length
        for spring, length in zip(data["springs"], lengths.tolist(), strict=True):
            if spring.get("rest_length") is None:
                spring["rest_length"] = float(length)
    return data


_SINGULAR = {
    "bodies": "body",
    "anchors": "anchor",
    "springs": "spring",
    "forces": "force",
    "at": "end",
}


def _locate(data: dict[str, Any], path: str) -> tuple[Any, Any]:
    """The container and key a PATH names in the JSON form, or a :class:`FitError`."""
    parts = path.split(".")
    node: Any = data
    for depth, part in enumerate(parts[:-1]):
        if isinstance(node, dict):
            if part not in node:
                raise FitError(f"--free {path}: not a number of the system (no '{part}')")
            node = node[part]
        elif isinstance(node, list):
            if parts[depth - 1] in ("bodies", "anchors") and all(
                isinstance(item, dict) and "id" in item for item in node
            ):
                ids = [item["id"] for item in node]
                if part not in ids:
                    raise FitError(
                        f"--free {path}: no {_SINGULAR[parts[depth - 1]]} '{part}' "
                        f"({parts[depth - 1]}: {', '.join(ids) or 'none'})"
                    )
                node = node[ids.index(part)]
            else:
                if not part.isdigit() or int(part) >= len(node):
                    raise FitError(
                        f"--free {path}: no {_SINGULAR.get(parts[depth - 1], 'item')} '{part}' "
                        f"(numbered 0 to "
                        f"{len(node) - 1} in file order)"
                        if node
                        else f"--free {path}: the system has no {parts[depth - 1]}"
                    )
                node = node[int(part)]
        else:
            raise FitError(f"--free {path}: not a number of the system")
    return node, parts[-1]


def get_value(data: dict[str, Any], path: str) -> float:
    """The number a PATH names in the JSON form ``data``; a one-line :class:`FitError` when it
    names nothing, or something that is not a number."""
    container, key = _locate(data, path)
    if not isinstance(container, dict):
        raise FitError(f"--free {path}: not a number of the system (no '{key}')")
    value = container[key] if key in container else _default(path, key)
    if isinstance(value, bool) or not isinstance(value, int | float):
        raise FitError(f"--free {path}: not a number of the system ({key} is {value!r})")
    return float(value)


def _default(path: str, key: str) -> Any:
    """The model's default of a field its JSON form leaves out (a coefficient at 0, say), or a
    :class:`FitError` when the model has no such field."""
    from rollspring.model import Anchor, Body, ExternalForce, Spring
    from rollspring.model import System as SystemModel

    parts = path.split(".")
    model: Any = {
        "bodies": Body,
        "springs": Spring,
        "anchors": Anchor,
        "forces": ExternalForce,
    }.get(parts[0], SystemModel)
    if len(parts) not in (1, 3) or key not in model.model_fields:
        raise FitError(f"--free {path}: not a number of the system (no '{key}')")
    return model.model_fields[key].default


def check_paths(system: System, paths: Sequence[str]) -> tuple[str, ...]:
    """The ``--free`` PATHs checked: each names a number of the system, none twice, none the
    initial state; a one-line :class:`FitError` naming the PATH otherwise."""
    data = pinned_json(system)
    seen: list[str] = []
    for path in paths:
        if not isinstance(path, str) or not path.strip():
            raise FitError("--free: an empty PATH (give e.g. springs.0.stiffness)")
        path = path.strip()
        parts = path.split(".")
        if len(parts) == 3 and parts[0] == "bodies" and parts[2] in INITIAL_STATE:
            raise FitError(
                f"--free {path}: the initial state is fitted already (each body's x and v, "
                "unless --fix-initial holds them)"
            )
        get_value(data, path)
        if path in seen:
            raise FitError(f"--free {path}: given twice")
        seen.append(path)
    return tuple(seen)


def with_values(
    data: dict[str, Any], values: Mapping[str, float], *, source: str = "fit"
) -> System:
    """The system ``data`` (JSON form) with each PATH of ``values`` set, validated by the model
    (a value it refuses is a :class:`FitError` naming the PATH and the model's reason)."""
    changed = _copied(data, values)
    for path, value in values.items():
        container, key = _locate(changed, path)
        container[key] = float(value)
    try:
        return system_from_dict(changed, source=source)
    except RollspringError as exc:
        names = ", ".join(f"{p} = {v:.6g}" for p, v in values.items())
        raise FitError(f"{names}: the model refuses these values ({exc})") from None


def _copied(data: dict[str, Any], values: Mapping[str, float]) -> dict[str, Any]:
    """A copy of ``data`` deep enough that setting ``values`` leaves ``data`` unchanged: the
    top level, and deep copies of the groups (bodies, springs, ...) a PATH enters."""
    changed = dict(data)
    for group in {path.split(".")[0] for path in values}:
        if isinstance(changed.get(group), list | dict):
            changed[group] = copy.deepcopy(changed[group])
    return changed


def bounds_of(path: str, value: float) -> tuple[float, float]:
    """The range a PATH's value may take in a fit: the model's (:data:`RANGES`) for its
    quantity, non-negative for a coefficient the model has no range for; unbounded else."""
    quantity = path.split(".")[-1]
    name = _RANGE_OF.get(quantity)
    if name is not None and name in RANGES:
        low, high, _ = RANGES[name]
        return float(low), float(high)
    if quantity in _RANGE_OF:  # a coefficient whose range the model does not list (yet)
        return 0.0, math.inf
    return -math.inf, math.inf

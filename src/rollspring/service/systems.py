"""Systems as the interfaces receive them: a preset name, a file, the JSON form, TOML text.

The command line names presets and files; the web page sends a system's JSON form or the text
of a TOML file. Both end in one validated :class:`~rollspring.model.System`, with the same
one-line :class:`~rollspring.errors.ModelError` for every problem.
"""

from __future__ import annotations

from typing import Any

from rollspring.errors import ModelError
from rollspring.model import (
    System,
    load_system,
    preset_names,
    system_from_dict,
    system_from_text,
    system_to_json,
    system_to_toml,
)

__all__ = ["preset_catalogue", "resolve_system", "system_forms"]


def resolve_system(
    system: System | dict[str, Any] | str | None = None, *, toml: str | None = None
) -> System:
    """One validated system from exactly one of: a :class:`System`, its JSON form (a dict), a
    preset name or file path (str), or ``toml`` (the text of a TOML system file)."""
    if (system is None) == (toml is None):
        raise ModelError("give exactly one of 'system' and 'toml'")
    if toml is not None:
        return system_from_text(toml, format="toml", source="toml")
    if isinstance(system, System):
        return system
    if isinstance(system, dict):
        return system_from_dict(system, source="system")
    if isinstance(system, str):
        return load_system(system)
    raise ModelError(
        f"system: must be a system, its JSON form, a preset name or a file path "
        f"(got {type(system).__name__})"
    )


def system_forms(system: System) -> dict[str, Any]:
    """The system's JSON form and the text of its TOML file: ``{"system", "toml"}``."""
    return {"system": system_to_json(system), "toml": system_to_toml(system)}


def preset_catalogue() -> list[dict[str, Any]]:
    """Every preset as ``{"name", "title", "system"}`` (the system in its JSON form)."""
    out = []
    for name in preset_names():
        system = load_system(name)
        out.append({"name": name, "title": system.name, "system": system_to_json(system)})
    return out

"""What a system is: bodies, anchors, springs, forces; validation; files; presets.

The names load on first use: the presets' catalogue needs nothing, the rest pydantic (so the
command line's ``--help``, which lists the presets, starts without it).
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

from rollspring.model.catalog import DEFAULT_PRESET, preset_names, preset_path

if TYPE_CHECKING:
    from rollspring.model.chains import chain
    from rollspring.model.files import (
        MAX_FILE_BYTES,
        as_system,
        load_system,
        system_from_dict,
        system_from_text,
        system_json_schema,
        system_to_json,
        system_to_toml,
        validation_errors,
    )
    from rollspring.model.placement import rolled
    from rollspring.model.schema import (
        INERTIA_FACTORS,
        LIMITS,
        RANGES,
        Anchor,
        Attachment,
        Body,
        ExternalForce,
        Spring,
        System,
    )

#: name -> the module that defines it, imported on first use
_LAZY = {
    "chain": "rollspring.model.chains",
    **dict.fromkeys(
        (
            "MAX_FILE_BYTES",
            "as_system",
            "load_system",
            "system_from_dict",
            "system_from_text",
            "system_json_schema",
            "system_to_json",
            "system_to_toml",
            "validation_errors",
        ),
        "rollspring.model.files",
    ),
    "rolled": "rollspring.model.placement",
    **dict.fromkeys(
        (
            "INERTIA_FACTORS",
            "LIMITS",
            "RANGES",
            "Anchor",
            "Attachment",
            "Body",
            "ExternalForce",
            "Spring",
            "System",
        ),
        "rollspring.model.schema",
    ),
}


def __getattr__(name: str) -> Any:
    if name not in _LAZY:
        raise AttributeError(f"module 'rollspring.model' has no attribute {name!r}")
    import importlib

    value = getattr(importlib.import_module(_LAZY[name]), name)
    globals()[name] = value
    return value


def __dir__() -> list[str]:
    return sorted({*globals(), *_LAZY})


__all__ = [
    "DEFAULT_PRESET",
    "INERTIA_FACTORS",
    "LIMITS",
    "MAX_FILE_BYTES",
    "RANGES",
    "Anchor",
    "Attachment",
    "Body",
    "ExternalForce",
    "Spring",
    "System",
    "as_system",
    "chain",
    "load_system",
    "preset_names",
    "preset_path",
    "rolled",
    "system_from_dict",
    "system_from_text",
    "system_json_schema",
    "system_to_json",
    "system_to_toml",
    "validation_errors",
]

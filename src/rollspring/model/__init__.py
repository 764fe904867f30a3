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

#: name -> the module of this package that defines it, imported on first use
_LAZY = {
    "chain": "chains",
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
        "files",
    ),
    "rolled": "placement",
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
        "schema",
    ),
}


def __getattr__(name: str) -> Any:
    """A name of :data:`_LAZY`, from its module (imported now: plain imports, so the import
    graph and its checks see them), kept in this module's namespace for the next use."""
    where = _LAZY.get(name)
    if where == "chains":
        from rollspring.model import chains

        value = getattr(chains, name)
    elif where == "files":
        from rollspring.model import files

        value = getattr(files, name)
    elif where == "placement":
        from rollspring.model import placement

        value = getattr(placement, name)
    elif where == "schema":
        from rollspring.model import schema

        value = getattr(schema, name)
    else:
        raise AttributeError(f"module 'rollspring.model' has no attribute {name!r}")
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

"""What a system is: bodies, anchors, springs, forces; validation; files; presets."""

from rollspring.model.files import (
    DEFAULT_PRESET,
    load_system,
    preset_names,
    preset_path,
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
    Anchor,
    Attachment,
    Body,
    ExternalForce,
    Spring,
    System,
)

__all__ = [
    "DEFAULT_PRESET",
    "INERTIA_FACTORS",
    "Anchor",
    "Attachment",
    "Body",
    "ExternalForce",
    "Spring",
    "System",
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

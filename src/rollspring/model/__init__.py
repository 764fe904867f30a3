"""What a system is: bodies, anchors, springs, forces; validation; files; presets."""

from rollspring.model.files import (
    DEFAULT_PRESET,
    load_system,
    preset_names,
    preset_path,
    system_from_dict,
    system_json_schema,
)
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
    "system_from_dict",
    "system_json_schema",
]

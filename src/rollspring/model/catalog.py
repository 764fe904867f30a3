"""The built-in presets: their names and files (no validation here, so listing them is cheap:
the command line's ``--help`` names them without loading pydantic)."""

from __future__ import annotations

from importlib import resources
from pathlib import Path

from rollspring.errors import ModelError

__all__ = ["DEFAULT_PRESET", "preset_names", "preset_path"]

#: The built-in default system: the paper's hoop and cylinder joined at their centres (Fig. 2).
DEFAULT_PRESET = "hoop-cylinder"

_PRESET_DIR = "presets"


def preset_names() -> list[str]:
    """Names of the built-in presets (each is also a file in ``examples/``)."""
    folder = resources.files("rollspring.model") / _PRESET_DIR
    return sorted(
        p.name.removesuffix(".toml") for p in folder.iterdir() if p.name.endswith(".toml")
    )


def preset_path(name: str) -> Path:
    """Path of a preset's TOML file inside the installed package."""
    if name not in preset_names():
        raise ModelError(
            f"unknown preset '{name}' (presets: {', '.join(preset_names())}; or give a file path)"
        )
    return Path(str(resources.files("rollspring.model") / _PRESET_DIR / f"{name}.toml"))

"""Chains as the interfaces ask for them: generate one and write its file, read one as a
periodic lattice (its dispersion as JSON and as a figure).

``rollspring chain`` calls :func:`chain_file`, ``rollspring dispersion`` :func:`chain_dispersion`
and :func:`dispersion_figure`; the computing is :func:`rollspring.model.chains.chain` and
:func:`rollspring.analysis.dispersion.dispersion`, the drawing
:mod:`rollspring.outputs.dispersion_figure`.
"""

from __future__ import annotations

import json
import os
from pathlib import Path
from typing import Any

from rollspring.analysis.dispersion import DEFAULT_POINTS, Dispersion, dispersion
from rollspring.errors import OutputError
from rollspring.model import System, system_to_json, system_to_toml
from rollspring.model.chains import chain

__all__ = [
    "SYSTEM_FORMATS",
    "chain",
    "chain_dispersion",
    "chain_file",
    "dispersion_figure",
    "system_text",
]

#: System file extensions :func:`chain_file` writes: TOML or JSON.
SYSTEM_FORMATS = (".toml", ".json")


def system_text(system: System, format: str = "toml") -> str:  # noqa: A002 - toml or json
    """The text of ``system``'s file: TOML, or its JSON form (indented, one trailing line)."""
    if format == "json":
        return json.dumps(system_to_json(system), indent=2, ensure_ascii=False) + "\n"
    return system_to_toml(system)


def chain_file(system: System, path: str | os.PathLike[str]) -> Path:
    """Write ``system`` to ``path``: JSON for a ``.json`` file, TOML for ``.toml``
    (atomically; OutputError naming the file otherwise)."""
    from rollspring.outputs.atomic import atomic_write_text

    target = Path(path)
    suffix = target.suffix.lower()
    if suffix not in SYSTEM_FORMATS:
        raise OutputError(
            f"--out: {target.name}: a system file ends in {' or '.join(SYSTEM_FORMATS)}"
        )
    try:
        atomic_write_text(target, system_text(system, suffix[1:]))
    except OSError as exc:
        raise OutputError(f"--out: {target}: cannot write ({exc.strerror or exc})") from None
    return target


def chain_dispersion(
    system: System, points: int = DEFAULT_POINTS
) -> tuple[Dispersion, dict[str, Any], list[str]]:
    """The dispersion of ``system`` read as a periodic chain, its JSON form and warnings."""
    result = dispersion(system, points)
    return result, result.to_dict(), list(result.warnings)


def dispersion_figure(result: Dispersion, path: str | os.PathLike[str]) -> Path:
    """Draw ``result`` into ``path`` (.png or .svg); needs the ``plot`` extra."""
    from rollspring.outputs.dispersion_figure import write_dispersion_figure

    return write_dispersion_figure(result, path)

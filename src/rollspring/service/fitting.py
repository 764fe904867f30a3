"""What ``rollspring fit`` (and the report's lab section) do: read the data, fit, measure the
paper's claims, sample a posterior if asked, and write the fitted system and the figure as a
set.

The computation is :func:`rollspring.lab.api.fit`; the files are rendered first, in memory
(:func:`rollspring.outputs.lab.fitted_toml`, :func:`~rollspring.outputs.lab.fit_figure_png`),
then written each to a temporary file beside its place and renamed only when every one is
complete (:func:`rollspring.outputs.atomic.atomic_path`), so a failure leaves no new file.
"""

from __future__ import annotations

import contextlib
import os
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass
from pathlib import Path

from rollspring.errors import FitError
from rollspring.lab.fit import FitResult
from rollspring.model import System

__all__ = ["FitRequest", "lab_request", "parse_mapping", "run_fit", "write_fit_outputs"]


@dataclass(frozen=True)
class FitRequest:
    """The arguments of a fit, checked once: the data file, the free PATHs, the track ->
    body mapping, whether the initial state is held, whether to sample a posterior."""

    data: str
    free: tuple[str, ...]
    mapping: dict[str, str]
    fix_initial: bool = False
    posterior: bool = False
    confirm: bool = False


def parse_mapping(items: Sequence[str]) -> dict[str, str]:
    """``--map track=body`` options as ``{track: body}``; a one-line :class:`FitError` for an
    item without ``=`` or a track given twice."""
    mapping: dict[str, str] = {}
    for item in items:
        track, equals, body = item.partition("=")
        track, body = track.strip(), body.strip()
        if not equals or not track or not body:
            raise FitError(f"--map {item}: expected TRACK=BODY (a track's name, a body's id)")
        if track in mapping:
            raise FitError(f"--map {item}: track '{track}' is mapped twice")
        mapping[track] = body
    return mapping


def lab_request(
    system: System,
    data: str | os.PathLike[str],
    free: Sequence[str] | None = None,
    mapping: Mapping[str, str] | None = None,
) -> FitRequest:
    """The fit of a report's lab section: ``free`` PATHs, by default every spring's stiffness
    and damping. The data file is read, matched to the bodies and the PATHs checked now, so a
    bad one is refused before the report's work (one-line :class:`~rollspring.errors.DataError`
    or :class:`FitError`)."""
    from rollspring.lab.data import match_bodies, read_data
    from rollspring.lab.parameters import check_paths

    if free is None:
        free = [
            f"springs.{i}.{quantity}"
            for i in range(len(system.springs))
            for quantity in ("stiffness", "damping")
        ]
    match_bodies(read_data(data), system, mapping)
    check_paths(system, list(free))
    return FitRequest(data=os.fspath(data), free=tuple(free), mapping=dict(mapping or {}))


def run_fit(
    system: System, request: FitRequest, progress: Callable[[float], None] | None = None
) -> FitResult:
    """The fit of ``request`` on ``system`` (:func:`rollspring.lab.api.fit`), the claims
    measured; ``progress`` told the fraction done (0..1)."""
    from rollspring.lab.api import fit

    return fit(
        request.data,
        system,
        request.free,
        mapping=request.mapping,
        fix_initial=request.fix_initial,
        posterior=request.posterior,
        confirm=request.confirm,
        progress=progress,
    )


def write_fit_outputs(
    result: FitResult,
    *,
    system_path: str | os.PathLike[str] | None = None,
    figure_path: str | os.PathLike[str] | None = None,
) -> list[Path]:
    """The fitted system (TOML) and the figure (PNG, or SVG for a ``.svg`` name) written as a
    set: both rendered first, then each written beside its place and all renamed together."""
    from rollspring.errors import OutputError
    from rollspring.outputs.atomic import atomic_path

    contents: dict[Path, bytes] = {}
    if system_path is not None:
        from rollspring.outputs.lab import fitted_toml

        contents[Path(system_path)] = fitted_toml(result).encode("utf-8")
    if figure_path is not None:
        contents[Path(figure_path)] = _figure_bytes(result, Path(figure_path))
    try:
        with contextlib.ExitStack() as stack:
            for path, data in contents.items():
                temporary = stack.enter_context(atomic_path(path))
                temporary.write_bytes(data)
    except OSError as exc:
        raise OutputError(
            f"{exc.filename or 'output'}: cannot write ({exc.strerror or exc})"
        ) from None
    return list(contents)


def _figure_bytes(result: FitResult, path: Path) -> bytes:
    from rollspring.outputs.figures import figure_svg, plot_fit, theme
    from rollspring.outputs.lab import fit_figure_png

    if path.suffix.lower() == ".svg":
        with theme():
            return figure_svg(plot_fit(result)).encode("utf-8")
    return fit_figure_png(result)

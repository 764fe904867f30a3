"""What ``rollspring fit`` (and the report's lab section) do: read the data, fit, measure the
paper's claims, sample a posterior if asked, and write the fitted system and the figure as a
set.

The computation is :func:`rollspring.lab.api.fit`; the files are rendered first, in memory
(:func:`rollspring.outputs.lab.fitted_toml`, :func:`~rollspring.outputs.lab.fit_figure_png`),
then written each to a temporary file beside its place and renamed only when every one is
complete (:func:`rollspring.outputs.atomic.atomic_path`), so a failure leaves no new file.

Before the fit, its cost (:func:`fit_estimate`, :func:`rollspring.lab.costs.fit_cost`: tiny on
the exact linear motion, a simulation of the recording per evaluation on the simulated one) is
what the command line's ``--yes`` and a report's ``confirm`` check.
"""

from __future__ import annotations

import contextlib
import dataclasses
import os
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass
from pathlib import Path

from rollspring.errors import FitError
from rollspring.lab.costs import LabCost, fit_cost
from rollspring.lab.data import BodyData
from rollspring.lab.fit import FitResult
from rollspring.model import System

__all__ = [
    "FitRequest",
    "check_fit_places",
    "fit_estimate",
    "fit_table",
    "lab_request",
    "parse_mapping",
    "run_fit",
    "write_fit_outputs",
]


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
    *,
    confirm: bool = False,
    flag: str = "--yes",
) -> FitRequest:
    """The fit of a report's lab section: ``free`` PATHs, by default every spring's stiffness
    and damping. The data file is read, matched to the bodies, the PATHs checked and the fit's
    cost estimated now (:func:`fit_estimate`), so a bad one, or a fit above the bound that is
    not confirmed (``confirm``; ``flag`` says how) is refused before the report's work (one-line
    :class:`~rollspring.errors.DataError`, :class:`FitError` or
    :class:`~rollspring.errors.CostTooHigh`)."""
    from rollspring.analysis.costs import check_cost

    if free is None:
        free = [
            f"springs.{i}.{quantity}"
            for i in range(len(system.springs))
            for quantity in ("stiffness", "damping")
        ]
    request = FitRequest(data=os.fspath(data), free=tuple(free), mapping=dict(mapping or {}))
    check_cost(
        fit_estimate(system, request, fit_table(system, request)), confirmed=confirm, flag=flag
    )
    return dataclasses.replace(request, confirm=True)  # checked: the report's fit is not again


def fit_table(system: System, request: FitRequest) -> BodyData:
    """The request's data file read and matched to ``system``'s bodies (one-line
    :class:`~rollspring.errors.DataError`)."""
    from rollspring.lab.data import match_bodies, read_data

    return match_bodies(read_data(request.data), system, request.mapping)


def fit_estimate(system: System, request: FitRequest, table: BodyData) -> LabCost:
    """The estimated cost of the fit of ``request`` to ``table`` (:func:`fit_table`) on
    ``system``: :func:`rollspring.lab.costs.fit_cost`, in the command line's words; the PATHs
    are checked first (a one-line :class:`FitError` naming a bad one)."""
    from rollspring.lab.parameters import check_paths

    check_paths(system, list(request.free))
    return fit_cost(table, system, request.free, fix_initial=request.fix_initial)


def run_fit(
    system: System,
    request: FitRequest,
    progress: Callable[[float], None] | None = None,
    *,
    table: BodyData | None = None,
) -> FitResult:
    """The fit of ``request`` on ``system`` (:func:`rollspring.lab.api.fit`), the claims
    measured; ``progress`` told the fraction done (0..1); ``table`` the data read already
    (:func:`fit_table`), else the request's file is read. The cost is checked as
    :func:`rollspring.fit` checks it (``request.confirm``)."""
    from rollspring.lab.api import fit

    return fit(
        request.data if table is None else table,
        system,
        request.free,
        mapping=request.mapping,
        fix_initial=request.fix_initial,
        posterior=request.posterior,
        confirm=request.confirm,
        progress=progress,
    )


def check_fit_places(
    out: str | os.PathLike[str] | None,
    figure: str | os.PathLike[str] | None,
    data: str | os.PathLike[str] | None = None,
) -> None:
    """``--out`` and ``--figure`` checked before the fit: each a regular file or a new one in a
    writable folder, the fitted system a ``.toml``, the figure a ``.png`` or ``.svg`` (what is
    written), neither the other nor the ``data`` read; a one-line
    :class:`~rollspring.errors.OutputError` naming the option."""
    from rollspring.errors import OutputError
    from rollspring.outputs.atomic import same_file, writable_file

    places = {}
    for place, option, suffixes in (
        (out, "--out", (".toml",)),
        (figure, "--figure", (".png", ".svg")),
    ):
        if place is None:
            continue
        path = writable_file(place, option)  # an unwritable place fails now, not after the fit
        if path.suffix.lower() not in suffixes:
            raise OutputError(
                f"{option} {place}: must end in {' or '.join(suffixes)} (what is written there)"
            )
        if data is not None and same_file(path, data):
            raise OutputError(f"{option} {place}: the same file as the data read")
        places[option] = path
    if len(places) == 2 and same_file(places["--out"], places["--figure"]):
        raise OutputError(f"--figure {figure}: the same file as --out")


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

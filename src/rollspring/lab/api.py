"""``rollspring.fit`` and ``rollspring.track``: a measured table of a real experiment becomes a
fitted model; a video of it becomes tracks. Each is estimated before any work
(:mod:`rollspring.lab.costs`) and refused above the bound unless ``confirm=True``."""

from __future__ import annotations

import dataclasses
import os
from collections.abc import Callable, Mapping, Sequence
from typing import TYPE_CHECKING, Any

from rollspring.errors import FitError
from rollspring.lab.data import BodyData, Recording, Tracks, as_recording, match_bodies
from rollspring.lab.fit import FitResult, fit_model
from rollspring.model import System
from rollspring.simulate.arguments import check_callback, check_count, check_flag

if TYPE_CHECKING:
    from rollspring.lab.tracking import TrackResult

__all__ = ["fit", "track"]


def _check_arguments(
    free: Any,
    mapping: Any,
    fix_initial: Any,
    posterior: Any,
    claims: Any,
    seed: Any,
    confirm: Any,
) -> tuple[tuple[str, ...], dict[str, str] | None]:
    """:func:`fit`'s arguments checked before any work, each refused in one line naming it:
    ``free`` a PATH or a sequence of PATHs (text), ``mapping`` None or track name → body id
    (text to text), the flags True or False, ``seed`` an integer >= 0."""
    for name, value in (
        ("fix_initial", fix_initial),
        ("posterior", posterior),
        ("claims", claims),
        ("confirm", confirm),
    ):
        check_flag(name, value)
    check_count("seed", seed, 0)
    if isinstance(free, str):
        free = (free,)
    if not isinstance(free, Sequence) or not all(isinstance(path, str) for path in free):
        raise FitError(
            f"free: must be PATHs of the system, e.g. ['springs.0.stiffness'], got {free!r}"
        )
    if mapping is not None and (
        not isinstance(mapping, Mapping)
        or not all(isinstance(k, str) and isinstance(v, str) for k, v in mapping.items())
    ):
        raise FitError(
            f"mapping: must match track names to body ids, e.g. {{'mass A': 'hoop'}}, "
            f"got {mapping!r}"
        )
    return tuple(free), (dict(mapping) if mapping is not None else None)


def fit(
    data: str | os.PathLike[str] | Recording | BodyData | Tracks,
    system: System | dict[str, Any] | str | os.PathLike[str],
    free: Sequence[str] = (),
    *,
    mapping: Mapping[str, str] | None = None,
    fix_initial: bool = False,
    posterior: bool = False,
    claims: bool = True,
    seed: int = 0,
    confirm: bool = False,
    progress: Callable[[float], None] | None = None,
) -> FitResult:
    r"""Fit ``system`` to the measured table ``data`` (a file: a ``track`` CSV, a plain CSV
    ``t,x_<id>,phi_<id>`` or a Tracker data file; a :class:`~rollspring.lab.data.Recording`; or
    the tracks :func:`rollspring.track` returns)
    by least squares on the exact motion (:func:`rollspring.lab.fit.fit_model`).

    ``free`` are PATHs of the system (``springs.0.stiffness``, ``springs.0.damping``,
    ``bodies.hoop.mass``, ...); each body's initial position and velocity are fitted too (the
    system's own held, and the start time ``t0`` fitted, with ``fix_initial``); ``mapping``
    matches tracks to bodies (``{"mass A": "hoop"}``). For two bodies the paper's claims are
    measured (:func:`rollspring.lab.claims.measure_claims`: the CM's and X̂'s peak-to-peak
    motion, the frictions' ratio, whether each body rolled); ``posterior`` adds an MCMC
    posterior (:func:`rollspring.lab.posterior.sample_posterior`) as ``result.posterior``,
    refused with its estimate (:class:`~rollspring.errors.CostTooHigh`) above 5 minutes unless
    ``confirm``. The fit itself is estimated first (:func:`rollspring.lab.costs.fit_cost`: on
    the simulated motion a simulation of the recording per evaluation) and refused the same
    way. ``progress`` is told the fraction done (0..1). In Jupyter the result shows itself as a
    table and a figure.
    """
    from rollspring.analysis.costs import CONFIRM, check_cost
    from rollspring.lab.costs import fit_cost
    from rollspring.lab.parameters import check_paths
    from rollspring.model.files import as_system

    free, mapping = _check_arguments(free, mapping, fix_initial, posterior, claims, seed, confirm)
    check_callback("progress", progress)
    model = as_system(system)
    table = data if isinstance(data, BodyData) else match_bodies(as_recording(data), model, mapping)
    check_paths(model, list(free))  # a bad PATH is named before the estimate
    check_cost(
        fit_cost(table, model, free, fix_initial=fix_initial), confirmed=confirm, flag=CONFIRM
    )
    share = 0.3 if posterior else 0.9

    def part(low: float, high: float) -> Callable[[float], None] | None:
        if progress is None:
            return None
        report = progress
        return lambda fraction: report(low + (high - low) * fraction)

    result = fit_model(table, model, free, fix_initial=fix_initial, progress=part(0.0, share))
    measured: dict[str, Any] = {}
    if claims:
        from rollspring.lab.claims import measure_claims

        measured = measure_claims(result)
    sampled = None
    if posterior:
        from rollspring.lab.posterior import posterior_cost, sample_posterior

        check_cost(posterior_cost(result), confirmed=confirm)
        sampled = sample_posterior(result, seed=seed, progress=part(share, 1.0)).to_dict()
    if progress is not None:
        progress(1.0)
    warnings = [*result.warnings, *(sampled["warnings"] if sampled else [])]
    return dataclasses.replace(result, claims=measured, posterior=sampled, warnings=warnings)


def track(
    video: str | os.PathLike[str],
    system: System | dict[str, Any] | str | os.PathLike[str],
    *,
    scale: float | None = None,
    start: float | None = None,
    stop: float | None = None,
    origin: float | None = None,
    confirm: bool = False,
    progress: Callable[[float], None] | None = None,
) -> TrackResult:
    """Track every body of ``system`` (a :class:`~rollspring.model.System`, its JSON form, a
    file or a preset name) in ``video``: :func:`rollspring.lab.tracking.track_video`, whose
    result has the arrays ``t``, ``x``, ``phi``, ``.to_csv()``, ``.summary()`` and a notebook
    view. Estimated first from the video's header (:func:`rollspring.lab.costs.tracking_cost`:
    the frames from ``start`` to ``stop`` × their pixels) and refused above 5 minutes or 2 GiB
    (:class:`~rollspring.errors.CostTooHigh`, the estimate in its message) unless ``confirm``.

    Example::

        result = rollspring.track("hoop-cylinder.mp4", "hoop-cylinder")
        result.x[:, 0], result.phi[:, 0], result.summary()["roll_deg"]
    """
    from rollspring.analysis.costs import CONFIRM, check_cost
    from rollspring.lab.costs import tracking_cost, video_header
    from rollspring.lab.tracking import check_options, track_video
    from rollspring.model.files import as_system

    check_options(scale=scale, start=start, stop=stop, origin=origin)
    check_flag("confirm", confirm)
    check_callback("progress", progress)
    model = as_system(system)
    cost = tracking_cost(
        video_header(video), len(model.bodies), start=start, stop=stop, smaller=TRACK_SMALLER
    )
    check_cost(cost, confirmed=confirm, flag=CONFIRM)
    return track_video(
        video, model, scale=scale, start=start, stop=stop, origin=origin, progress=progress
    )


#: how to make a tracking smaller, in Python's words
TRACK_SMALLER = "a shorter stretch from start to stop, or a smaller video"

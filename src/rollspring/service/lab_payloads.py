"""The lab on the page (``POST /api/lab/data``, ``POST /api/fit``): a measured table sent as
text, read by :mod:`rollspring.lab.data` and matched to the system's bodies, and the fit of
:func:`rollspring.lab.api.fit` on it (as ``rollspring fit`` does) as JSON.

Nothing here reads a file: the table arrives as text with the name it had on the client's
machine, which every one-line message names (``tracks.csv: no time column``). The drawn data are
in the fitted system's frame: time from the instant the system's initial state holds (``t0``),
positions in the system's x origin (``x_offset`` removed), so that they lie over the simulated
motion of the fitted system from t = 0.

A fit is estimated before it starts (:func:`rollspring.lab.costs.fit_cost`) against the server's
time budget: one estimated above :data:`BUDGET_MARGIN` times the budget is refused at once
(:class:`~rollspring.errors.CostTooHigh`, HTTP 503) rather than abandoned when the budget runs
out. The estimates are rounded up (1.2 to 3.2 times the CPU time measured on the fits of
bench/bench_lab_costs.py and the tests), so one between the budget and that is started, and the
budget stops it if it must.
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from typing import Any

from rollspring.errors import CostTooHigh, DataError, FitError
from rollspring.model import System, system_to_json

__all__ = [
    "BUDGET_MARGIN",
    "DEFAULT_FREE_QUANTITIES",
    "data_payload",
    "default_free",
    "fit_payload",
]

#: The quantities of each spring fitted unless the request names its own PATHs.
DEFAULT_FREE_QUANTITIES = ("stiffness", "damping")

#: A fit estimated above this many times the time budget is refused before it starts (the
#: estimates are up to about three times the CPU time a fit takes).
BUDGET_MARGIN = 3.0


def default_free(system: System) -> list[str]:
    """Every spring's stiffness and damping: the PATHs a fit frees by default."""
    return [
        f"springs.{i}.{quantity}"
        for i in range(len(system.springs))
        for quantity in DEFAULT_FREE_QUANTITIES
    ]


def _column(values: Any) -> list[float | None]:
    return [float(v) if math.isfinite(v) else None for v in values.tolist()]


def _table(
    text: str,
    source: str,
    system: System,
    mapping: Mapping[str, str | None] | None,
    unmatched: str = "refuse",
) -> tuple[Any, list[str], dict[str, str | None]]:
    """The table matched to ``system``'s bodies, its tracks and the match used ({track: body id,
    or None for a track left out}). A track mapped to None is left out, and with ``unmatched``
    "omit" so is a track that names no body and is not in ``mapping``."""
    from dataclasses import replace

    from rollspring.lab.data import match_bodies, parse_data

    recording = parse_data(text, source)
    mapping = dict(mapping or {})
    ids = {body.id for body in system.bodies}
    for track in mapping:
        if track not in recording.tracks:
            raise DataError(
                f"--map {track}={mapping[track] or ''}: {recording.source} has no track "
                f"'{track}' (tracks: {', '.join(recording.tracks)})"
            )
    if unmatched == "omit":
        for track in recording.tracks:
            if track not in mapping and track not in ids:
                mapping[track] = None
    used = [i for i, track in enumerate(recording.tracks) if mapping.get(track, track) is not None]
    kept = replace(
        recording,
        tracks=tuple(recording.tracks[i] for i in used),
        x=recording.x[:, used],
        phi=recording.phi[:, used],
    )
    table = match_bodies(kept, system, {k: v for k, v in mapping.items() if v is not None})
    match = {track: mapping.get(track, track) for track in recording.tracks}
    return table, list(recording.tracks), match


def _drawn(
    table: Any, t0: float, x_offset: float, tracks: list[str], match: dict[str, str | None]
) -> dict[str, Any]:
    """The measured table as the page draws it: ``t`` from ``t0``, ``x`` less ``x_offset``."""
    return {
        "source": table.source,
        "tracks": tracks,
        "mapping": match,
        "t": _column(table.t - t0),
        "bodies": {
            body: {
                "x": _column(table.x[:, column] - x_offset),
                "phi": _column(table.phi[:, column]),
            }
            for column, body in enumerate(table.bodies)
        },
        "points": table.n_points,
    }


def data_payload(
    text: str,
    source: str,
    system: System,
    mapping: Mapping[str, str | None] | None = None,
    *,
    unmatched: str = "refuse",
) -> dict[str, Any]:
    """The table ``text`` (named ``source``) read and matched to ``system``'s bodies:
    ``{"source", "tracks", "mapping", "t", "bodies": {id: {"x", "phi"}}, "points", "free"}``
    (``tracks`` the file's track names, ``mapping`` the match used, {track: body id or None};
    ``t`` from the table's first time; ``free`` the PATHs a fit frees by default). A one-line
    :class:`~rollspring.errors.DataError` for a table that cannot be read or matched."""
    table, tracks, match = _table(text, source, system, mapping, unmatched)
    return {
        **_drawn(table, float(table.t[0]), 0.0, tracks, match),
        "free": default_free(system),
    }


def fit_payload(
    text: str,
    source: str,
    system: System,
    free: Sequence[str] | None = None,
    mapping: Mapping[str, str | None] | None = None,
    *,
    fix_initial: bool = False,
    posterior: bool = False,
    unmatched: str = "refuse",
    budget: float | None = None,
) -> dict[str, Any]:
    """The fit of ``system`` to the table ``text`` (named ``source``) freeing the PATHs ``free``
    (default :func:`default_free`) and each body's initial state (``rollspring fit``), with
    ``posterior`` its MCMC posterior too (``fit --posterior``: ``fit.posterior``), within the
    time ``budget`` (s; None: the command line's bound, 5 minutes; the fit is estimated
    before it starts, the posterior once the fit is done, from the fit's time an evaluation:
    either above :data:`BUDGET_MARGIN` times the budget is refused):

    ``{"fit": <rollspring fit --json's object>, "system": <the fitted system, JSON form>,
    "toml": <the fitted system file>, "data": <the table in the fitted system's frame>}``.

    One-line :class:`~rollspring.errors.DataError` or :class:`~rollspring.errors.FitError` for a
    table that cannot be read, a PATH that is no number of the system, too few points;
    :class:`~rollspring.errors.CostTooHigh` for a fit estimated above :data:`BUDGET_MARGIN`
    times the ``budget``, before it starts."""
    from rollspring.lab.api import fit
    from rollspring.lab.costs import fit_cost
    from rollspring.lab.parameters import check_paths
    from rollspring.outputs.lab import fitted_toml

    paths = default_free(system) if free is None else list(free)
    check_paths(system, paths)  # before the data, as the CLI: a bad PATH is named first
    table, tracks, match = _table(text, source, system, mapping, unmatched)
    if not paths and fix_initial:
        raise FitError("free: nothing to fit (no PATH, and the initial state held)")
    if budget is not None:
        cost = fit_cost(table, system, paths, fix_initial=fix_initial)
        if cost.seconds > BUDGET_MARGIN * budget:
            raise CostTooHigh(
                f"the fit would take {cost.describe()}, beyond the server's time budget of "
                f"{budget:g} s; fit a shorter recording or fewer PATHs, or run rollspring fit "
                "on the command line"
            )
    # within the budget, the budget is the bound (the command line's 5 minutes are not)
    result = fit(
        table,
        system,
        paths,
        fix_initial=fix_initial,
        posterior=posterior and budget is None,
        confirm=budget is not None,
    )
    if posterior and budget is not None:
        # the posterior's estimate rests on the fit's own time an evaluation: checked against
        # what the budget leaves once the fit is done, before any sampling
        import dataclasses

        from rollspring.lab.posterior import posterior_cost, sample_posterior

        sampling = posterior_cost(result)
        if result.seconds + sampling.seconds > BUDGET_MARGIN * budget:
            raise CostTooHigh(
                f"the posterior would take {sampling.describe()} after the fit's "
                f"{result.seconds:.3g} s, beyond the server's time budget of {budget:g} s; "
                "fit without it, or run rollspring fit --posterior on the command line"
            )
        sampled = sample_posterior(result).to_dict()
        result = dataclasses.replace(
            result, posterior=sampled, warnings=[*result.warnings, *sampled["warnings"]]
        )
    offset = result.parameters.get("x_offset")
    return {
        "fit": result.to_dict(),
        "system": system_to_json(result.system),
        "toml": fitted_toml(result),
        "data": _drawn(
            table,
            result.parameters["t0"].value,
            0.0 if offset is None else offset.value,
            tracks,
            match,
        ),
    }

r"""Maps of a parameter sweep: one metric of a sweep store over two of its grid dimensions.

A sweep store (``docs/sweeps.md``; ``rollspring sweep`` writes it, ``xarray.open_zarr`` reads
it) holds one variable per metric over the grid of varied PATHs (dimensions named by the PATH,
e.g. ``bodies.hoop.mass``), some also over ``body`` or ``mode``. A map shows one metric over two
of those dimensions; every other grid dimension is fixed at one of its values (``sel``), the
``body`` and ``mode`` dimensions at one body and mode (or, for the friction ratios and the
normal force, the extreme over the bodies).

Where the linear theory has a prediction, it is drawn over the simulated map (dashed):

* maps of ``status``, ``first_slip_time``, ``first_slip_body`` and ``max_friction_ratio``: the
  slip boundary of the linear theory, the contour :math:`\mu_\mathrm{needed} = \mu_s` where
  :math:`\mu_\mathrm{needed}` is ``required_mu_linear`` (analyze's ``required_mu``), against
  the simulated first-slip region. :math:`\mu_s` is the grid coordinate where
  ``bodies.<id>.mu_static`` is a dimension, else the body's value in the system (the store's
  ``system`` attribute). With several bodies the boundary is where the first one reaches it:
  :math:`\max_i \mu_{\mathrm{needed},i}/\mu_{s,i} = 1`;
* maps of ``period_measured``: contour lines of the linear period :math:`2\pi/\omega` of the
  lowest oscillating mode (or of ``mode``).

Nothing is computed here but ratios and extremes of stored values: the physics is in the store.

Public functions
----------------
* :func:`open_sweep` ``(path) -> xarray.Dataset``: a sweep store, checked to be one.
* :func:`prepare_map` ``(dataset, x, y, metric, *, sel=None, body=None, mode=None,
  linear=True) -> MapData``: the 2-D values, the overlay, the fixed values and notes (a
  ``sel`` value not on the grid is replaced by the nearest grid value, with a note); every
  bad argument raises :class:`MapError` with a one-line message.
* :func:`plot_map` ``(data, ax=None) -> Axes``: draw a :class:`MapData`.
* :func:`sweep_map` ``(dataset, x, y, metric, *, sel=None, body=None, mode=None, ax=None,
  linear=True) -> Axes``: both at once.
* :func:`write_map` ``(ax_or_figure, path, *, dpi=150) -> Path``: PNG, SVG or PDF, atomically.
"""

from __future__ import annotations

import math
import warnings
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np
import xarray as xr
from matplotlib import colormaps, patheffects
from matplotlib.axes import Axes
from matplotlib.colors import BoundaryNorm, ListedColormap, LogNorm, Normalize
from matplotlib.figure import Figure
from matplotlib.lines import Line2D
from matplotlib.patches import Patch
from matplotlib.ticker import FuncFormatter, NullFormatter

from rollspring.errors import MapError, ModelError
from rollspring.model import system_from_text
from rollspring.outputs.atomic import (
    atomic_path,
    atomic_write_bytes,
    atomic_write_text,
    writable_file,
)
from rollspring.outputs.figures import BODY_COLORS, figure_png, figure_svg, new_figure, theme

__all__ = [
    "CATEGORICAL",
    "SLIP_METRICS",
    "MapData",
    "MapError",
    "check_map_output",
    "open_sweep",
    "plot_map",
    "prepare_map",
    "sweep_map",
    "write_map",
]

#: Metrics drawn as categories (a legend, no colour bar).
CATEGORICAL = ("status", "first_slip_body")
#: Metrics over which the linear slip boundary (mu needed = mu_s) is drawn.
SLIP_METRICS = ("status", "first_slip_time", "first_slip_body", "max_friction_ratio")
#: Non-grid dimensions of a store.
_EXTRA_DIMS = ("body", "mode")
#: How a per-body metric is reduced over the bodies when no body is chosen.
_OVER_BODIES = {"max_friction_ratio": "max", "required_mu_linear": "max", "min_normal_force": "min"}
#: Colours of the status codes (by name); other names take _SPARE in turn.
_STATUS_COLORS = {
    "finished": "#a6d96a",
    "slip": "#fdae61",
    "liftoff": "#2c7bb6",
    "nonfinite": "#252525",
    "energy_error": "#d7191c",
    "invalid": "#bdbdbd",
}
_SPARE = ("#984ea3", "#ffff99", "#a65628", "#f781bf", "#66c2a5", "#8da0cb")
_NONE_COLOR = "#d9d9d9"
_LINEAR_LABEL = "linear theory: μ needed = μs"
_LINEAR_STYLE: dict[str, Any] = {"colors": "black", "linestyles": "dashed", "linewidths": 1.6}
_MAX_LISTED = 12
#: A white halo under the contour lines of the linear period and their labels (seen on dark
#: cells too).
_HALO = [patheffects.Stroke(linewidth=2.4, foreground="white"), patheffects.Normal()]


@dataclass
class MapData:
    """What a map draws, read from a sweep store by :func:`prepare_map`.

    ``values`` (ny, nx) over the coordinates ``x`` and ``y`` (grid values); ``categories``
    ``[(code, name, colour)]`` for a categorical metric (``values`` then holds codes); ``linear``
    (ny, nx) the linear theory's overlay field and ``linear_level``, its contour(s)
    (``linear_kind`` ``"slip"`` or ``"period"``); ``fixed`` the other dimensions' values as
    ``(name, value text)``; ``notes`` what was substituted (a ``sel`` value not on the grid)
    or could not be drawn.
    """

    x_name: str
    y_name: str
    metric: str
    x: np.ndarray
    y: np.ndarray
    values: np.ndarray
    x_units: str
    y_units: str
    units: str
    long_name: str
    x_log: bool
    y_log: bool
    metric_label: str
    title: str
    fixed: list[tuple[str, str]] = field(default_factory=list)
    categories: list[tuple[int, str, str]] | None = None
    linear: np.ndarray | None = None
    linear_kind: str | None = None
    linear_label: str | None = None
    notes: list[str] = field(default_factory=list)


# -- reading ---------------------------------------------------------------------------------


def open_sweep(path: str | Path) -> xr.Dataset:
    """Open the sweep store at ``path`` (lazily, Dask-backed); :class:`MapError` when there is
    nothing there or it is not a rollspring sweep store."""
    store = Path(path)
    if not store.exists():
        raise MapError(f"{path}: no such sweep store")
    if not store.is_dir():
        raise MapError(
            f"{path}: not a sweep store (a Zarr store is a directory; "
            "make one with rollspring sweep)"
        )
    try:
        with warnings.catch_warnings():
            # a store without consolidated metadata is read without (xarray warns about it)
            warnings.simplefilter("ignore")
            dataset = xr.open_zarr(store)
    except Exception as exc:  # noqa: BLE001 - any reading failure means "not a store"
        reason = " ".join(str(exc).split())[:160]
        raise MapError(f"{path}: not a sweep store ({type(exc).__name__}: {reason})") from None
    check_sweep(dataset, str(path))
    return dataset


def check_sweep(dataset: xr.Dataset, name: str = "dataset") -> None:
    """:class:`MapError` unless ``dataset`` looks like a sweep store (``docs/sweeps.md``): the
    ``system`` attribute and a ``status`` variable."""
    if not isinstance(dataset, xr.Dataset):
        raise MapError(f"{name}: not a sweep dataset (got {type(dataset).__name__})")
    missing = [
        what
        for what, ok in (
            ("the 'system' attribute", "system" in dataset.attrs),
            ("a 'status' variable", "status" in dataset.data_vars),
        )
        if not ok
    ]
    if missing:
        raise MapError(f"{name}: not a rollspring sweep store (no {' and no '.join(missing)})")


def grid_dims(dataset: xr.Dataset) -> list[str]:
    """The varied PATHs (every dimension but ``body`` and ``mode``), in the grid's order (that of
    ``status``'s dimensions)."""
    order = [*dataset["status"].dims, *dataset.dims] if "status" in dataset else [*dataset.dims]
    return list(dict.fromkeys(str(d) for d in order if d not in _EXTRA_DIMS))


def _listing(values: Sequence[Any] | np.ndarray) -> str:
    shown = [_number(v) if isinstance(v, (float, np.floating)) else str(v) for v in values]
    if len(shown) > _MAX_LISTED:
        shown = [*shown[: _MAX_LISTED // 2], "…", *shown[-_MAX_LISTED // 2 :]]
    return ", ".join(shown)


def _number(value: float | np.floating[Any]) -> str:
    return f"{float(value):.6g}"


def _units(variable: xr.DataArray) -> str:
    return str(variable.attrs.get("units", "")).strip()


def _with_units(name: str, units: str) -> str:
    return f"{name} ({units})" if units else name


def _is_log_spaced(values: np.ndarray) -> bool:
    """A grid made by ``START:STOP:NUM:log``: positive, at least 3 values, constant ratio (and
    not also constant difference)."""
    if values.size < 3 or not np.all(np.isfinite(values)) or np.any(values <= 0):
        return False
    logs = np.diff(np.log(values))
    steps = np.diff(values)
    return bool(np.allclose(logs, logs[0], rtol=1e-6, atol=0.0)) and not bool(
        np.allclose(steps, steps[0], rtol=1e-6, atol=0.0)
    )


def _edges(values: np.ndarray, log: bool) -> np.ndarray:
    """Cell edges around the grid values (midpoints; in log space for a log grid)."""
    v = np.log(values) if log else values.astype(float)
    inner = 0.5 * (v[1:] + v[:-1])
    edges = np.concatenate([[v[0] - (inner[0] - v[0])], inner, [v[-1] + (v[-1] - inner[-1])]])
    return np.exp(edges) if log else edges


def _choose_value(dataset: xr.Dataset, dim: str, raw: Any, notes: list[str]) -> Any:
    """The grid value of ``dim`` for a requested ``raw`` value: exact, else the nearest one
    inside the grid's range (with a note), else a :class:`MapError` listing the values."""
    values = dataset[dim].values
    try:
        wanted = float(raw)
    except (TypeError, ValueError):
        raise MapError(f"--sel {dim}={raw}: not a number (values: {_listing(values)})") from None
    exact = np.flatnonzero(values == wanted)
    if exact.size:
        return values[exact[0]]
    finite = values[np.isfinite(values)]
    if not math.isfinite(wanted) or finite.size == 0:
        raise MapError(f"--sel {dim}={raw}: not on the grid (values: {_listing(values)})")
    nearest = finite[int(np.argmin(np.abs(finite - wanted)))]
    if math.isclose(nearest, wanted, rel_tol=1e-9, abs_tol=1e-300):
        return nearest
    low, high = float(np.min(finite)), float(np.max(finite))
    span = (high - low) or abs(high) or 1.0
    if not (low - 1e-9 * span <= wanted <= high + 1e-9 * span):
        raise MapError(f"--sel {dim}={raw}: outside the grid (values: {_listing(values)})")
    notes.append(
        f"--sel {dim}={raw}: not on the grid; the nearest grid value {_number(nearest)} is shown"
    )
    return nearest


def _mu_static(dataset: xr.Dataset, system: Any | None, ids: list[str]) -> xr.DataArray | None:
    """mu_s of every body as a DataArray over ``body`` (and any grid dimension that varies it),
    or None when the system cannot be read."""
    columns = []
    for index, body_id in enumerate(ids):
        path = f"bodies.{body_id}.mu_static"
        if path in dataset.coords:
            columns.append(
                dataset[path].astype(float).reset_coords(drop=True)
                if dataset[path].ndim == 0
                else dataset[path].astype(float)
            )
        elif system is not None:
            columns.append(xr.DataArray(float(system.bodies[index].mu_static)))
        else:
            return None
    return xr.concat(xr.broadcast(*columns), dim="body").assign_coords(body=ids)


def _system(dataset: xr.Dataset) -> Any | None:
    try:
        return system_from_text(str(dataset.attrs.get("system", "")), source="the store's system")
    except ModelError:
        return None


def _reduce_bodies(
    variable: xr.DataArray, metric: str, body: str | None, ids: list[str]
) -> tuple[xr.DataArray, str | None]:
    if body is not None:
        return variable.sel(body=body), body
    if len(ids) == 1:
        return variable.isel(body=0), ids[0]
    how = _OVER_BODIES.get(metric)
    if how is None:
        raise MapError(
            f"--body: {metric} is given per body; choose one with --body ID "
            f"(bodies: {_listing(ids)})"
        )
    return getattr(variable, how)("body"), None


def prepare_map(
    dataset: xr.Dataset,
    x: str,
    y: str,
    metric: str,
    *,
    sel: Mapping[str, Any] | None = None,
    body: str | None = None,
    mode: int | None = None,
    linear: bool = True,
) -> MapData:
    """Read the map of ``metric`` over the grid dimensions ``x`` and ``y`` from a sweep
    ``dataset``; see the module's description. ``sel`` fixes the other varied PATHs (a grid
    dimension of a single value needs none); ``body`` picks a body of a per-body metric (default:
    the largest friction ratio, the smallest normal force over the bodies) and the body of the
    linear slip boundary (default: whichever reaches it first); ``mode`` the mode of ``omega``
    (and of the linear period over ``period_measured``). ``linear=False`` leaves the linear
    theory out."""
    check_sweep(dataset)
    dims = grid_dims(dataset)
    for option, name in (("--x", x), ("--y", y)):
        if name not in dims:
            raise MapError(
                f"{option} {name}: not a varied PATH of this sweep "
                f"(varied: {_listing(dims) or 'none'})"
            )
    if x == y:
        raise MapError(f"--y {y}: the same PATH as --x; a map needs two different PATHs")
    for option, name in (("--x", x), ("--y", y)):
        if dataset.sizes[name] < 2:
            raise MapError(
                f"{option} {name}: has a single value in this sweep; a map needs at least two"
            )
        if not np.all(np.isfinite(np.asarray(dataset[name].values, float))):
            raise MapError(
                f"{option} {name}: holds a value that is not finite "
                f"({_listing(dataset[name].values)}); a map axis needs finite "
                "values (map it with --sel instead)"
            )
    if metric not in dataset.data_vars:
        raise MapError(
            f"--metric {metric}: not in this store (metrics: "
            f"{_listing(sorted(str(v) for v in dataset.data_vars))})"
        )
    ids = [str(v) for v in dataset["body"].values] if "body" in dataset.coords else []
    notes: list[str] = []

    # the other grid dimensions, one value each
    chosen: dict[str, Any] = {}
    for key, raw in dict(sel or {}).items():
        if key == "body":
            if body is not None and str(raw) != body:
                raise MapError(f"--sel body={raw}: conflicts with --body {body}")
            body = str(raw)
            continue
        if key == "mode":
            mode = _mode_number(raw)
            continue
        if key in (x, y):
            raise MapError(f"--sel {key}: is the map's {'x' if key == x else 'y'} axis")
        if key not in dims:
            raise MapError(
                f"--sel {key}: not a varied PATH of this sweep (varied: {_listing(dims)})"
            )
        chosen[key] = _choose_value(dataset, key, raw, notes)
    for dim in dims:
        if dim in (x, y) or dim in chosen:
            continue
        if dataset.sizes[dim] == 1:
            chosen[dim] = dataset[dim].values[0]
        else:
            raise MapError(
                f"{dim}: also varied in this sweep; fix it with --sel {dim}=VALUE "
                f"(values: {_listing(dataset[dim].values)})"
            )
    if body is not None and body not in ids:
        raise MapError(f"--body {body}: no such body (bodies: {_listing(ids) or 'none'})")
    n_modes = dataset.sizes.get("mode", 0)
    if mode is not None and not 0 <= mode < n_modes:
        raise MapError(
            f"--mode {mode}: no such mode (modes: 0 … {n_modes - 1})"
            if n_modes
            else f"--mode {mode}: this store has no mode dimension"
        )

    plane = dataset.sel(chosen) if chosen else dataset
    variable = plane[metric]
    if "mode" in variable.dims:
        if mode is None:
            raise MapError(
                f"--mode: {metric} is given per mode; choose one with --mode N "
                f"(modes: 0 … {n_modes - 1}, sorted by ω)"
            )
        variable = variable.sel(mode=mode)
    shown_body = None
    if "body" in variable.dims:
        variable, shown_body = _reduce_bodies(variable, metric, body, ids)
    elif body is not None and not (linear and metric in SLIP_METRICS):
        raise MapError(f"--body {body}: {metric} is not given per body")
    if mode is not None and metric not in ("omega", "period_measured"):
        raise MapError(f"--mode {mode}: {metric} is not given per mode")
    extra = [d for d in variable.dims if d not in (x, y)]
    if extra:  # pragma: no cover - a store outside docs/sweeps.md
        raise MapError(
            f"--metric {metric}: has dimensions {', '.join(map(str, extra))} this map cannot fix"
        )
    values = np.asarray(variable.transpose(y, x).values)
    units = _units(plane[metric])
    long_name = str(plane[metric].attrs.get("long_name", ""))

    categories = None
    if metric == "status":
        categories = _status_categories(plane[metric])
    elif metric == "first_slip_body":
        categories = [(-1, "no slip", _NONE_COLOR)] + [
            (i, body_id, BODY_COLORS[i % len(BODY_COLORS)]) for i, body_id in enumerate(ids)
        ]
    if metric == "first_slip_body" and values.dtype.kind == "f":
        values = np.where(np.isfinite(values), values, -1).astype(int)

    xv, yv = np.asarray(dataset[x].values, float), np.asarray(dataset[y].values, float)
    label = metric
    if shown_body is not None and "body" in plane[metric].dims:
        label = f"{metric} [{shown_body}]"
    elif "body" in plane[metric].dims:
        label = f"{metric} [{_OVER_BODIES[metric]} over bodies]"
    if "mode" in plane[metric].dims:
        label = f"{metric} [mode {mode}]"
    data = MapData(
        x_name=x,
        y_name=y,
        metric=metric,
        x=xv,
        y=yv,
        values=values,
        x_units=_units(dataset[x]),
        y_units=_units(dataset[y]),
        units=units,
        long_name=long_name,
        x_log=_is_log_spaced(xv),
        y_log=_is_log_spaced(yv),
        metric_label=label,
        title="",
        categories=categories,
        notes=notes,
        fixed=[(dim, _with_value(value, _units(dataset[dim]))) for dim, value in chosen.items()],
    )

    if linear:
        _linear_overlay(data, plane, dataset, x, y, body, mode, ids)
    system = _system(dataset)
    name = system.name if system is not None and system.name else "sweep"
    fixed = ", ".join(f"{k} = {v}" for k, v in data.fixed)
    data.title = name + ("\n" + fixed if fixed else "")
    return data


def _mode_number(raw: Any) -> int:
    try:
        return int(str(raw))
    except ValueError:
        raise MapError(f"--sel mode={raw}: a mode is a whole number") from None


def _with_value(value: Any, units: str) -> str:
    text = _number(value)
    return f"{text} {units}" if units and units != "1" else text


def _status_categories(variable: xr.DataArray) -> list[tuple[int, str, str]]:
    codes = variable.attrs.get("flag_values")
    names = str(variable.attrs.get("flag_meanings", "")).split()
    if codes is None or len(names) != len(np.atleast_1d(codes)):
        raise MapError(
            "status: the store's status has no flag_values/flag_meanings "
            "(not a sweep store of docs/sweeps.md)"
        )
    spare = iter(_SPARE * 4)
    return [
        (int(code), name, _STATUS_COLORS.get(name) or next(spare))
        for code, name in zip(np.atleast_1d(codes), names, strict=True)
    ]


def _linear_overlay(
    data: MapData,
    plane: xr.Dataset,
    dataset: xr.Dataset,
    x: str,
    y: str,
    body: str | None,
    mode: int | None,
    ids: list[str],
) -> None:
    """Fill ``data.linear`` with the linear theory's field where it has a prediction."""
    if data.metric in SLIP_METRICS:
        if "required_mu_linear" not in plane:
            data.notes.append(
                "no linear slip boundary: the store has no required_mu_linear "
                "(swept with --metric without it)"
            )
            return
        mu = _mu_static(plane, _system(dataset), ids)
        if mu is None:
            data.notes.append("no linear slip boundary: the store's system cannot be read")
            return
        needed = plane["required_mu_linear"]
        with np.errstate(divide="ignore", invalid="ignore"):
            ratio = needed / mu  # inf mu_s: ratio 0, never slips
        ratio = ratio.sel(body=body) if body is not None else ratio.max("body")
        ratio = ratio.broadcast_like(
            plane[data.metric].isel({d: 0 for d in plane[data.metric].dims if d not in (x, y)})
        )
        data.linear = np.asarray(ratio.transpose(y, x).values, float)
        data.linear_kind = "slip"
        data.linear_label = _LINEAR_LABEL + (f" ({body})" if body is not None else "")
    elif data.metric == "period_measured":
        if "omega" not in plane:
            data.notes.append("no linear period: the store has no omega")
            return
        omega = plane["omega"]
        # without a mode: the lowest oscillating mode (zero modes are exactly 0)
        omega = omega.sel(mode=mode) if mode is not None else omega.where(omega > 0).min("mode")
        with np.errstate(divide="ignore", invalid="ignore"):
            period = 2 * math.pi / omega
        data.linear = np.asarray(period.transpose(y, x).values, float)
        data.linear_kind = "period"
        data.linear_label = "linear theory: 2π/ω" + (f" (mode {mode})" if mode is not None else "")


# -- drawing ---------------------------------------------------------------------------------


def plot_map(data: MapData, ax: Axes | None = None) -> Axes:
    """Draw ``data`` (from :func:`prepare_map`) on ``ax`` (default: a new 6.4 × 4.8 in figure):
    the metric as coloured cells over the grid (log axes for log-spaced grids), a colour bar
    ``metric (units)`` or, for categories, a legend; the linear theory dashed; labelled axes
    ``PATH (units)``; the system and the fixed values as title."""
    with theme():
        if ax is None:
            new = new_figure(6.4, 4.8)
            new.set_layout_engine("constrained")
            ax = new.add_subplot()
        fig = ax.figure
        xe, ye = _edges(data.x, data.x_log), _edges(data.y, data.y_log)
        handles: list[Any] = []
        if data.categories is not None:
            mesh, handles = _draw_categories(ax, data, xe, ye)
        else:
            mesh = _draw_values(ax, data, xe, ye, handles)
            bar = fig.colorbar(mesh, ax=ax, fraction=0.05, pad=0.02)
            bar.set_label(_with_units(data.metric_label, data.units))
            shown = np.asarray(data.values, float)
            shown = shown[np.isfinite(shown)]
            if shown.size and shown.min() == shown.max():  # one value: one tick, no range
                bar.set_ticks([float(shown[0])])
        if data.x_log:
            ax.set_xscale("log")
        if data.y_log:
            ax.set_yscale("log")
        for log, axis in ((data.x_log, ax.xaxis), (data.y_log, ax.yaxis)):
            if log:
                axis.set_major_formatter(FuncFormatter(_plain))
                axis.set_minor_formatter(NullFormatter())
        ax.set_xlim(xe[0], xe[-1])
        ax.set_ylim(ye[0], ye[-1])
        handles += _draw_linear(ax, data, mesh)
        ax.set_xlabel(_with_units(data.x_name, data.x_units))
        ax.set_ylabel(_with_units(data.y_name, data.y_units))
        ax.set_title(data.title)
        if data.categories is not None:
            ax.legend(
                handles=handles,
                loc="upper left",
                bbox_to_anchor=(1.02, 1.0),
                borderaxespad=0.0,
                title=data.metric_label,
            )
        elif handles:
            ax.legend(
                handles=handles,
                loc="upper center",
                bbox_to_anchor=(0.5, -0.13),
                ncols=len(handles),
                frameon=False,
                borderaxespad=0.0,
            )
    return ax


def _draw_categories(
    ax: Axes, data: MapData, xe: np.ndarray, ye: np.ndarray
) -> tuple[Any, list[Any]]:
    assert data.categories is not None  # drawn only for a categorical metric
    codes = [code for code, _, _ in data.categories]
    index = np.full(data.values.shape, -1, dtype=int)
    for i, code in enumerate(codes):
        index[data.values == code] = i
    cmap = ListedColormap([colour for _, _, colour in data.categories])
    norm = BoundaryNorm(np.arange(len(codes) + 1) - 0.5, len(codes))
    mesh = ax.pcolormesh(
        xe, ye, np.ma.masked_less(index, 0), cmap=cmap, norm=norm, shading="flat", rasterized=True
    )
    present = set(np.unique(index[index >= 0]).tolist())
    handles = [
        Patch(facecolor=colour, edgecolor="none", label=name)
        for i, (_, name, colour) in enumerate(data.categories)
        if i in present
    ]
    return mesh, handles


def _draw_values(
    ax: Axes, data: MapData, xe: np.ndarray, ye: np.ndarray, handles: list[Any]
) -> Any:
    values = np.asarray(data.values, float)
    finite = np.isfinite(values)
    masked = np.ma.masked_where(~finite, values)
    shown = values[finite]
    if shown.size and np.all(shown > 0) and shown.max() > 1e3 * shown.min():
        norm: Normalize = LogNorm(vmin=float(shown.min()), vmax=float(shown.max()))
    elif shown.size:
        low, high = float(shown.min()), float(shown.max())
        spread = 0.5 * (high - low) if high > low else 0.01 * abs(low) or 1.0
        middle = 0.5 * (low + high)  # a constant map shows the middle colour
        norm = Normalize(vmin=middle - spread, vmax=middle + spread)
    else:
        norm = Normalize(0.0, 1.0)
    cmap = colormaps["viridis"].with_extremes(bad=_NONE_COLOR)
    mesh = ax.pcolormesh(xe, ye, masked, cmap=cmap, norm=norm, shading="flat", rasterized=True)
    if not finite.all():
        what = {
            "first_slip_time": "no slip",
            "first_liftoff_time": "no lift-off",
            "period_measured": "fewer than two crossings",
        }.get(data.metric, "no value")
        handles.append(Patch(facecolor=_NONE_COLOR, edgecolor="none", label=what))
    return mesh


def _draw_linear(ax: Axes, data: MapData, mesh: Any) -> list[Any]:
    """The linear theory's contour(s) and their legend entry (nothing without a prediction)."""
    if data.linear is None:
        return []
    assert data.linear_label is not None  # set with the prediction
    field_ = np.ma.masked_invalid(data.linear)
    X, Y = np.meshgrid(data.x, data.y)
    if data.linear_kind == "slip":
        finite = field_.compressed()
        if finite.size and finite.min() < 1.0 < finite.max():
            ax.contour(X, Y, field_, levels=[1.0], **_LINEAR_STYLE)
            label = data.linear_label
        elif finite.size and finite.max() <= 1.0:
            label = data.linear_label.replace("μ needed = μs", "μ needed < μs everywhere")
        else:
            label = data.linear_label.replace("μ needed = μs", "μ needed > μs everywhere")
        return [Line2D([], [], color="black", linestyle="--", linewidth=1.6, label=label)]
    # period: contour lines at the colour bar's levels, labelled
    if field_.count() == 0:
        return []
    low, high = float(field_.min()), float(field_.max())
    label = data.linear_label
    if math.isclose(low, high, rel_tol=1e-9):
        label += f" = {low:.4g} s everywhere"
    else:
        levels = [
            v for v in _nice_levels(float(mesh.norm.vmin), float(mesh.norm.vmax)) if low < v < high
        ] or [0.5 * (low + high)]
        lines = ax.contour(
            X, Y, field_, levels=levels, colors="black", linestyles="dashed", linewidths=1.2
        )
        lines.set(path_effects=_HALO)
        for text in ax.clabel(lines, fmt=lambda v: f"{v:.3g} s", fontsize=7, colors="black"):
            text.set_path_effects(_HALO)
    return [Line2D([], [], color="black", linestyle="--", linewidth=1.2, label=label)]


def _plain(value: float, _position: Any = None) -> str:
    return f"{value:g}"


def _nice_levels(low: float, high: float, count: int = 6) -> list[float]:
    from matplotlib.ticker import MaxNLocator

    return [float(v) for v in MaxNLocator(count).tick_values(low, high)]


def sweep_map(
    dataset: xr.Dataset | str | Path,
    x: str,
    y: str,
    metric: str,
    *,
    sel: Mapping[str, Any] | None = None,
    body: str | None = None,
    mode: int | None = None,
    ax: Axes | None = None,
    linear: bool = True,
) -> Axes:
    """The map of ``metric`` over ``x`` and ``y`` of a sweep (a Dataset or a store's path):
    :func:`prepare_map` then :func:`plot_map`. Returns the Axes (``ax.figure`` the Figure)."""
    if not isinstance(dataset, xr.Dataset):
        dataset = open_sweep(dataset)
    return plot_map(
        prepare_map(dataset, x, y, metric, sel=sel, body=body, mode=mode, linear=linear), ax
    )


#: The finest resolution of a PNG map, dots per inch (a 6.4-inch map: 7680 pixels wide).
MAX_DPI = 1200.0


def check_map_output(path: str | Path, dpi: Any = 150.0, option: str = "-o") -> Path:
    """The checks of :func:`write_map`, for a caller to make before any work: ``dpi`` a number in
    (0, :data:`MAX_DPI`], the suffix .png, .svg or .pdf, and ``path`` a place a regular file can
    be written (:func:`~rollspring.outputs.atomic.writable_file`: no device, FIFO or folder)."""
    number = dpi if isinstance(dpi, int | float) and not isinstance(dpi, bool) else math.nan
    if not 0 < number <= MAX_DPI:
        raise MapError(f"--dpi: must be a number > 0 up to {MAX_DPI:g}, got {dpi!r}")
    path = Path(path)
    if path.suffix.lower() not in (".png", ".svg", ".pdf"):
        raise MapError(
            f"{option} {path}: unknown image format '{path.suffix}' (.png, .svg or .pdf)"
        )
    return writable_file(path, option)


def write_map(target: Axes | Figure, path: str | Path, *, dpi: float = 150.0) -> Path:
    """Write the map's figure to ``path`` (by its suffix: .png, .svg or .pdf), atomically, after
    :func:`check_map_output`."""
    fig = target.figure if isinstance(target, Axes) else target
    assert isinstance(fig, Figure)  # a map is drawn on a figure's own axes
    path = check_map_output(path, dpi)
    suffix = path.suffix.lower()
    if suffix == ".png":
        atomic_write_bytes(path, figure_png(fig, dpi=dpi))
    elif suffix == ".svg":
        atomic_write_text(path, figure_svg(fig))
    elif suffix == ".pdf":
        with atomic_path(path, suffix=".pdf") as temporary, theme():
            fig.savefig(
                temporary,
                format="pdf",
                metadata={"Creator": None, "Producer": None, "CreationDate": None},
            )
    return path

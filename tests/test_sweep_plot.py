r"""Maps of sweeps (``rollspring sweep-plot``, :mod:`rollspring.outputs.maps`): pixels against
baselines, the linear theory's overlay where it belongs, categorical legends, log axes, labels
with units, and every bad input a one-line error with exit code 2.

Until the sweep engine is used here, the maps are drawn from a small synthetic store made as
``docs/sweeps.md`` describes it: the paper's hoop and cylinder (preset ``hoop-cylinder``,
k = 100 N/m, μs = 1 for the cylinder) started at the spring's rest length with the hoop
launched at ``bodies.hoop.v``, over ``bodies.hoop.v`` × ``bodies.hoop.mu_static`` (log) ×
``springs.0.stiffness``. Its values are the linear motion's, which for this system is the exact
one while it rolls: Ω² = 7k/6, the hoop needs μ = k v/(2Ω g) and the cylinder k v/(3Ω g), a run
slips when the hoop needs more than its μs (at t = arcsin(μs/μ)/Ω). The baselines are updated
as those of ``tests/test_figures.py``::

    ROLLSPRING_UPDATE_BASELINES=1 .venv/bin/python -m pytest tests/test_sweep_plot.py
"""

from __future__ import annotations

import math
import warnings
from pathlib import Path

import numpy as np
import pytest
import typer
import xarray as xr
from matplotlib.contour import ContourSet
from typer.testing import CliRunner

from rollspring.cli.commands.sweep_plot import register
from rollspring.model import load_system, system_to_toml
from rollspring.outputs.maps import (
    MapError,
    open_sweep,
    plot_map,
    prepare_map,
    sweep_map,
    write_map,
)
from tests.test_figures import check_baseline

G = 9.81
K = 100.0
V, MU, KS = "bodies.hoop.v", "bodies.hoop.mu_static", "springs.0.stiffness"
runner = CliRunner()


def synthetic_sweep(system_toml: str | None = None) -> xr.Dataset:
    """A sweep store's Dataset (docs/sweeps.md) of the hoop-cylinder system, see the module."""
    system = load_system("hoop-cylinder")
    v = np.linspace(0.02, 0.4, 20)
    mu = np.geomspace(0.005, 0.5, 16)
    k = np.array([80.0, 100.0, 120.0])
    k3, mu3, v3 = np.meshgrid(k, mu, v, indexing="ij")
    omega = np.sqrt(7 * k3 / 6)
    need = np.stack([k3 * v3 / (2 * omega * G), k3 * v3 / (3 * omega * G)], axis=-1)
    mus = np.stack([mu3, np.ones_like(mu3)], axis=-1)
    ratio = (need / mus).max(-1)
    slip = ratio >= 1
    t_slip = np.full(slip.shape, np.nan)
    t_slip[slip] = np.arcsin(1 / ratio[slip]) / omega[slip]
    period = np.where(slip, np.nan, 2 * np.pi / omega)
    grid = (KS, MU, V)

    def var(data, dims, units, long_name, **attrs):
        return (dims, data, {"units": units, "long_name": long_name, **attrs})

    return xr.Dataset(
        {
            "omega": var(
                np.stack([np.zeros_like(omega), omega], -1),
                (*grid, "mode"),
                "rad/s",
                "linear angular frequencies",
            ),
            "stationary_weight": var(
                np.broadcast_to([4 / 7, 3 / 7], need.shape).copy(),
                (*grid, "body"),
                "1",
                "weights of the stationary point",
            ),
            "required_mu_linear": var(
                need, (*grid, "body"), "1", "max |f|/N of the linear response"
            ),
            "period_measured": var(period, grid, "s", "measured period"),
            "max_friction_ratio": var(
                np.where(slip[..., None], np.minimum(need, mus), need),
                (*grid, "body"),
                "1",
                "max |f|/N over the run",
            ),
            "min_normal_force": var(
                np.full(need.shape, G), (*grid, "body"), "N", "min N over the run"
            ),
            "first_slip_time": var(t_slip, grid, "s", "first slip"),
            "first_slip_body": var(
                np.where(slip, 0, -1).astype(np.int8),
                grid,
                "1",
                "index into body of the first slip",
            ),
            "energy_error": var(
                1e-12 * (1 + v3 / 0.4) ** 8, grid, "1", "max relative energy error"
            ),
            "status": var(
                np.where(slip, 2, 0).astype(np.int8),
                grid,
                "",
                "how the run ended",
                flag_values=np.array([0, 1, 2, 3, 4], dtype=np.int8),
                flag_meanings="finished nonfinite slip liftoff invalid",
            ),
        },
        coords={
            KS: (KS, k, {"units": "N/m"}),
            MU: (MU, mu, {"units": "1"}),
            V: (V, v, {"units": "m/s"}),
            "mode": ("mode", np.arange(2)),
            "body": ("body", np.array(["hoop", "cylinder"])),
        },
        attrs={
            "system": system_toml or system_to_toml(system),
            "rollspring_version": "test",
            "grid_fingerprint": "0" * 64,
            "duration": 2.0,
            "rtol": 1e-8,
            "on_slip": "stop",
            "integrator": "yoshida4",
            "step": 1e-3,
            "metrics": ["all"],
            "chunk": 960,
        },
    )


def hoop_boundary(v: np.ndarray, k: float = K) -> np.ndarray:
    """μs at which the hoop of the synthetic sweep just slips, as the linear theory says."""
    return k * v / (2 * math.sqrt(7 * k / 6) * G)


@pytest.fixture(scope="module")
def sweep() -> xr.Dataset:
    return synthetic_sweep()


@pytest.fixture(scope="module")
def store(sweep: xr.Dataset, tmp_path_factory: pytest.TempPathFactory) -> Path:
    path = tmp_path_factory.mktemp("sweep") / "sweep.zarr"
    with warnings.catch_warnings():  # Zarr v3 notes that fixed-width strings are an extension
        warnings.simplefilter("ignore")
        sweep.to_zarr(path, mode="w")
    return path


@pytest.fixture(scope="module")
def app() -> typer.Typer:
    application = typer.Typer()
    register(application)

    @application.command()
    def other() -> None:  # a second command, so that "sweep-plot" is a subcommand
        """Unused."""

    return application


def legend_texts(ax) -> list[str]:
    legend = ax.get_legend()
    return [] if legend is None else [t.get_text() for t in legend.get_texts()]


def contour_sets(ax) -> list[ContourSet]:
    return [c for c in ax.collections if isinstance(c, ContourSet)]


def slip_map(sweep: xr.Dataset, metric: str = "status", **kwargs):
    return sweep_map(sweep, V, MU, metric, sel={KS: K}, **kwargs)


# -- baselines --------------------------------------------------------------------------------


def test_status_map_matches_baseline(sweep, tmp_path) -> None:
    """Categories with their legend, a log μs axis, the linear slip boundary dashed."""
    check_baseline(slip_map(sweep).figure, "sweep-status", tmp_path)


def test_first_slip_time_map_matches_baseline(sweep, tmp_path) -> None:
    """A colour bar in s, 'no slip' cells in grey with a legend entry, the linear boundary."""
    check_baseline(slip_map(sweep, "first_slip_time").figure, "sweep-first-slip", tmp_path)


def test_period_map_matches_baseline(sweep, tmp_path) -> None:
    """Measured period over stiffness and speed with the linear 2π/ω contours."""
    ax = sweep_map(sweep, KS, V, "period_measured", sel={MU: 0.5})
    check_baseline(ax.figure, "sweep-period", tmp_path)


# -- what a map shows ---------------------------------------------------------------------------


@pytest.mark.parametrize(
    "metric", ["status", "first_slip_time", "first_slip_body", "max_friction_ratio"]
)
def test_slip_maps_carry_the_linear_boundary_where_theory_puts_it(sweep, metric) -> None:
    """One dashed contour at μ needed/μs = 1, labelled, along μs = k v/(2Ω g) (the hoop's)."""
    ax = slip_map(sweep, metric)
    (contour,) = contour_sets(ax)
    assert list(contour.levels) == [1.0]
    assert contour.get_linestyles()[0][1] is not None  # dashed
    assert "linear theory: μ needed = μs" in legend_texts(ax)
    vertices = np.concatenate([p.vertices for p in contour.get_paths()])
    assert len(vertices) > 10
    # linear interpolation of 1/μs between log-spaced grid rows: within a few per cent
    np.testing.assert_allclose(vertices[:, 1], hoop_boundary(vertices[:, 0]), rtol=0.04)


def test_mu_static_from_the_system_when_not_swept() -> None:
    """Without a mu_static dimension μs comes from the store's system (here 0.05 for the hoop):
    over stiffness and speed the boundary is v = 0.05 · 2Ω g / k (exact on the grid's
    stiffnesses, linearly interpolated between them)."""
    data = load_system("hoop-cylinder").model_dump()
    data["bodies"][0]["mu_static"] = 0.05
    from rollspring.model import system_from_dict

    toml = system_to_toml(system_from_dict(data))
    sweep = synthetic_sweep(toml).isel({MU: 0}, drop=True)
    ax = sweep_map(sweep, V, KS, "max_friction_ratio")
    (contour,) = contour_sets(ax)
    vertices = np.concatenate([p.vertices for p in contour.get_paths()])
    k = vertices[:, 1]
    np.testing.assert_allclose(vertices[:, 0], 0.05 * 2 * np.sqrt(7 * k / 6) * G / k, rtol=2e-3)
    on_grid = np.isin(k, [80.0, 100.0, 120.0])
    assert on_grid.sum() == 3
    np.testing.assert_allclose(
        vertices[on_grid, 0], 0.05 * 2 * np.sqrt(7 * k[on_grid] / 6) * G / k[on_grid], rtol=1e-9
    )


def test_body_selects_the_boundary_of_that_body(sweep) -> None:
    """The cylinder (μs = 1 from the system) never needs that much: no contour, and the
    legend says so."""
    ax = slip_map(sweep, "status", body="cylinder")
    assert contour_sets(ax) == []
    assert "linear theory: μ needed < μs everywhere (cylinder)" in legend_texts(ax)


def test_no_overlay_where_linear_theory_has_none_or_when_asked(sweep) -> None:
    assert contour_sets(slip_map(sweep, "energy_error")) == []
    assert contour_sets(slip_map(sweep, "status", linear=False)) == []
    assert not any("linear" in t for t in legend_texts(slip_map(sweep, "status", linear=False)))


def test_period_map_has_labelled_linear_period_contours(sweep) -> None:
    ax = sweep_map(sweep, KS, V, "period_measured", sel={MU: 0.5})
    (contour,) = contour_sets(ax)
    levels = np.asarray(contour.levels)
    assert len(levels) >= 2
    # each level sits at the stiffness where 2π/Ω equals it: k = 6/7 (2π/T)²
    for level, path in zip(levels, contour.get_paths(), strict=True):
        k = path.vertices[:, 0]
        np.testing.assert_allclose(k, 6 / 7 * (2 * np.pi / level) ** 2, rtol=0.01)
    assert any(t.get_text().endswith(" s") for t in ax.texts)
    assert "linear theory: 2π/ω" in legend_texts(ax)


def test_categorical_legends(sweep) -> None:
    assert legend_texts(slip_map(sweep, "status"))[:2] == ["finished", "slip"]
    assert legend_texts(slip_map(sweep, "first_slip_body"))[:2] == ["no slip", "hoop"]


def test_axes_labels_units_log_scale_colour_bar_and_title(sweep) -> None:
    ax = slip_map(sweep, "first_slip_time")
    assert ax.get_xlabel() == "bodies.hoop.v (m/s)"
    assert ax.get_ylabel() == "bodies.hoop.mu_static (1)"
    assert ax.get_xscale() == "linear" and ax.get_yscale() == "log"
    (bar,) = [a for a in ax.figure.axes if a is not ax]
    assert bar.get_ylabel() == "first_slip_time (s)"
    assert ax.get_title().splitlines() == [
        "Hoop and cylinder joined at their centres",
        "springs.0.stiffness = 100 N/m",
    ]
    assert "no slip" in legend_texts(ax)


def test_cells_hold_the_stored_values(sweep) -> None:
    data = prepare_map(sweep, V, MU, "max_friction_ratio", sel={KS: 120}, body="hoop")
    expected = sweep["max_friction_ratio"].sel({KS: 120.0, "body": "hoop"}).transpose(MU, V)
    np.testing.assert_array_equal(data.values, expected.values)
    over = prepare_map(sweep, V, MU, "max_friction_ratio", sel={KS: 120})
    assert over.metric_label == "max_friction_ratio [max over bodies]"
    np.testing.assert_array_equal(
        over.values,
        sweep["max_friction_ratio"].sel({KS: 120.0}).max("body").transpose(MU, V).values,
    )


def test_a_value_between_grid_values_takes_the_nearest_with_a_note(sweep) -> None:
    data = prepare_map(sweep, V, MU, "status", sel={KS: 97})
    assert data.notes == [f"--sel {KS}=97: not on the grid; the nearest grid value 100 is shown"]
    assert f"{KS} = 100 N/m" in data.title


def test_mode_of_omega(sweep) -> None:
    data = prepare_map(sweep, V, KS, "omega", sel={MU: 0.5}, mode=1)
    assert data.metric_label == "omega [mode 1]"
    np.testing.assert_allclose(data.values[:, 0], np.sqrt(7 * data.y / 6))


@pytest.mark.parametrize(
    ("x", "y", "metric", "kwargs", "message"),
    [
        (
            "bodies.hoop.mass",
            MU,
            "status",
            {},
            "--x bodies.hoop.mass: not a varied PATH of this "
            "sweep (varied: springs.0.stiffness, bodies.hoop.mu_static, bodies.hoop.v)",
        ),
        (V, V, "status", {}, "--y bodies.hoop.v: the same PATH as --x"),
        (V, MU, "speed", {"sel": {KS: 100}}, "--metric speed: not in this store (metrics: "),
        (
            V,
            MU,
            "status",
            {},
            "springs.0.stiffness: also varied in this sweep; fix it with "
            "--sel springs.0.stiffness=VALUE (values: 80, 100, 120)",
        ),
        (
            V,
            MU,
            "status",
            {"sel": {KS: 200}},
            "--sel springs.0.stiffness=200: outside the grid (values: 80, 100, 120)",
        ),
        (V, MU, "status", {"sel": {KS: "stiff"}}, "--sel springs.0.stiffness=stiff: not a number"),
        (V, MU, "status", {"sel": {KS: 100, V: 0.1}}, "--sel bodies.hoop.v: is the map's x axis"),
        (V, MU, "status", {"sel": {KS: 100, "gravity": 9.81}}, "--sel gravity: not a varied PATH"),
        (
            V,
            MU,
            "status",
            {"sel": {KS: 100}, "body": "sphere"},
            "--body sphere: no such body (bodies: hoop, cylinder)",
        ),
        (
            V,
            MU,
            "omega",
            {"sel": {KS: 100}},
            "--mode: omega is given per mode; choose one with --mode N (modes: 0 … 1, sorted by ω)",
        ),
        (V, MU, "omega", {"sel": {KS: 100}, "mode": 2}, "--mode 2: no such mode (modes: 0 … 1)"),
        (
            V,
            MU,
            "stationary_weight",
            {"sel": {KS: 100}},
            "--body: stationary_weight is given per "
            "body; choose one with --body ID (bodies: hoop, cylinder)",
        ),
        (
            V,
            MU,
            "energy_error",
            {"sel": {KS: 100}, "body": "hoop"},
            "--body hoop: energy_error is not given per body",
        ),
        (V, MU, "status", {"sel": {KS: 100}, "mode": 1}, "--mode 1: status is not given per mode"),
    ],
)
def test_bad_arguments_are_one_line_errors(sweep, x, y, metric, kwargs, message) -> None:
    with pytest.raises(MapError) as caught:
        prepare_map(sweep, x, y, metric, **kwargs)
    text = str(caught.value)
    assert text.startswith(message), text
    assert "\n" not in text


def test_a_single_valued_axis_is_refused(sweep) -> None:
    with pytest.raises(MapError, match="has a single value in this sweep"):
        prepare_map(sweep.isel({KS: [1]}), V, KS, "status", sel={MU: 0.5})


def test_a_dimension_of_one_value_needs_no_sel(sweep) -> None:
    data = prepare_map(sweep.isel({KS: [1]}), V, MU, "status")
    assert data.fixed == [(KS, "100 N/m")]


# -- the store and the command ------------------------------------------------------------------


def test_open_sweep_reads_the_store_lazily(store, sweep) -> None:
    dataset = open_sweep(store)
    assert dataset["status"].chunks is not None  # Dask-backed: a map loads only its plane
    ax = sweep_map(store, V, MU, "status", sel={KS: K})
    assert len(contour_sets(ax)) == 1


def test_cli_writes_the_map(app, store, tmp_path) -> None:
    target = tmp_path / "maps" / "map.png"
    result = runner.invoke(
        app,
        [
            "sweep-plot",
            str(store),
            "--x",
            V,
            "--y",
            MU,
            "--metric",
            "first_slip_time",
            "--sel",
            f"{KS}=99",
            "-o",
            str(target),
        ],
    )
    assert result.exit_code == 0, result.output
    assert target.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    assert result.stdout == ""
    assert result.stderr.splitlines() == [
        f"note: --sel {KS}=99: not on the grid; the nearest grid value 100 is shown",
        f"wrote {target}",
    ]


@pytest.mark.parametrize("suffix", [".svg", ".pdf"])
def test_cli_writes_svg_and_pdf(app, store, tmp_path, suffix) -> None:
    target = tmp_path / f"map{suffix}"
    result = runner.invoke(
        app,
        [
            "sweep-plot",
            str(store),
            "--x",
            V,
            "--y",
            KS,
            "--metric",
            "status",
            "--sel",
            f"{MU}=0.05",
            "-o",
            str(target),
        ],
    )
    assert result.exit_code == 0, result.output
    assert target.stat().st_size > 1000


def _bad_cli_cases(store: Path, tmp: Path) -> list[tuple[list[str], str]]:
    tmp.mkdir(exist_ok=True)
    plain = tmp / "plain"
    plain.mkdir(exist_ok=True)
    (plain / "notes.txt").write_text("not zarr")
    file = tmp / "file.zarr"
    file.write_text("")
    other = tmp / "other.zarr"
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        xr.Dataset({"a": ("x", np.arange(3.0))}).to_zarr(other, mode="w")
    base = ["--x", V, "--y", MU, "--metric", "status", "--sel", f"{KS}=100"]
    return [
        (
            ["sweep-plot", str(tmp / "missing.zarr"), *base],
            f"error: {tmp / 'missing.zarr'}: no such sweep store",
        ),
        (["sweep-plot", str(file), *base], f"error: {file}: not a sweep store"),
        (["sweep-plot", str(plain), *base], f"error: {plain}: not a sweep store"),
        (
            ["sweep-plot", str(other), *base],
            f"error: {other}: not a rollspring sweep store (no "
            "the 'system' attribute and no a 'status' variable)",
        ),
        (
            ["sweep-plot", str(store), "--x", "gravity", "--y", MU, "--metric", "status"],
            "error: --x gravity: not a varied PATH of this sweep",
        ),
        (
            ["sweep-plot", str(store), *base[:5], "speed"],
            "error: --metric speed: not in this store",
        ),
        (
            ["sweep-plot", str(store), *base, "--body", "wheel"],
            "error: --body wheel: no such body (bodies: hoop, cylinder)",
        ),
        (
            ["sweep-plot", str(store), *base[:6], "--sel", f"{KS}=1000"],
            f"error: --sel {KS}=1000: outside the grid (values: 80, 100, 120)",
        ),
        (
            ["sweep-plot", str(store), *base[:6], "--sel", KS],
            f"error: --sel {KS}: expected PATH=VALUE",
        ),
        (["sweep-plot", str(store), *base, "-o", str(tmp / "map.gif")], "error: -o "),
        (["sweep-plot", str(store), *base, "--dpi", "0"], "error: --dpi: must be a number > 0"),
    ]


def test_cli_bad_input_exit_2_with_one_line(app, store, tmp_path) -> None:
    for args, message in _bad_cli_cases(store, tmp_path / "cases"):
        result = runner.invoke(app, args)
        assert result.exit_code == 2, (args, result.output)
        lines = result.stderr.strip().splitlines()
        assert len(lines) == 1 and lines[0].startswith(message), (args, lines)
        assert result.stdout == ""


def test_write_map_refuses_an_unknown_format(sweep, tmp_path) -> None:
    with pytest.raises(MapError, match="unknown image format"):
        write_map(plot_map(prepare_map(sweep, V, MU, "status", sel={KS: K})), tmp_path / "map.jpg")


def test_the_rollspring_app_has_the_sweep_plot_command(store, tmp_path) -> None:
    from rollspring.cli import app as rollspring_app

    assert any(c.name == "sweep-plot" for c in rollspring_app.registered_commands)
    target = tmp_path / "map.png"
    result = runner.invoke(
        rollspring_app,
        [
            "sweep-plot",
            str(store),
            "--x",
            V,
            "--y",
            MU,
            "--metric",
            "status",
            "--sel",
            f"{KS}=100",
            "-o",
            str(target),
        ],
    )
    assert result.exit_code == 0, result.output
    assert target.exists()


def test_a_map_without_its_overlay_fails_its_baseline(sweep, tmp_path) -> None:
    """The comparison sees the dashed linear boundary: the same map without it fails."""
    from matplotlib.testing.compare import compare_images

    from rollspring.outputs.figures import figure_png
    from tests.test_figures import BASELINE_DPI, BASELINES, TOLERANCE

    actual = tmp_path / "bare.png"
    actual.write_bytes(
        figure_png(slip_map(sweep, "first_slip_time", linear=False).figure, dpi=BASELINE_DPI)
    )
    result = compare_images(str(BASELINES / "sweep-first-slip.png"), str(actual), tol=TOLERANCE)
    assert result is not None and "RMS" in result


def test_an_infinite_mu_static_can_be_selected_not_mapped(sweep) -> None:
    """``--vary bodies.hoop.mu_static=0.1,inf`` is a valid sweep: inf is a --sel value, not an
    axis."""
    mu = sweep[MU].values.copy()
    mu[-1] = np.inf
    infinite = sweep.assign_coords({MU: (MU, mu, {"units": "1"})})
    data = prepare_map(infinite, V, KS, "status", sel={MU: "inf"})
    assert data.fixed == [(MU, "inf")]
    assert data.linear is not None and np.nanmax(data.linear) < 1.0  # never slips
    with pytest.raises(MapError, match="holds a value that is not finite"):
        prepare_map(infinite, V, MU, "status", sel={KS: 100})
    with pytest.raises(MapError, match="not on the grid"):
        prepare_map(sweep, V, KS, "status", sel={MU: "inf"})


def test_a_map_of_a_real_sweep(tmp_path) -> None:
    """A store written by ``rollspring.sweep``: the map draws, and the simulated slip region
    lies where the linear theory puts it (this system's motion is linear while it rolls): runs
    needing under 0.9 μs roll to the end, runs needing over 1.1 μs slip."""
    from rollspring.service.sweeps import sweep

    store = tmp_path / "real.zarr"
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        sweep(
            "hoop-cylinder",
            {V: np.linspace(0.02, 0.3, 8), MU: np.geomspace(0.01, 0.5, 7)},
            1.0,
            out=store,
            refine_slip=False,
        )
    dataset = open_sweep(store)
    ax = sweep_map(dataset, V, MU, "status")
    assert len(contour_sets(ax)) == 1
    assert "linear theory: μ needed = μs" in legend_texts(ax)
    data = prepare_map(dataset, V, MU, "status")
    status = dataset["status"].attrs
    names = dict(zip(status["flag_values"], status["flag_meanings"].split(), strict=True))
    shown = np.vectorize(names.get)(data.values)
    assert set(shown[data.linear < 0.9]) == {"finished"}
    assert set(shown[data.linear > 1.1]) == {"slip"}
    assert (data.linear < 0.9).any() and (data.linear > 1.1).any()

"""rollspring sweep in this process: the store, resuming, refusals, bad arguments, and the
physics read back from the store (paper eq. QQQ1, the measured period, the first-slip map)."""

from __future__ import annotations

import math

import numpy as np
import pytest
import xarray as xr
from hypothesis import given, settings
from hypothesis import strategies as st
from typer.testing import CliRunner

import rollspring
from rollspring.model import system_from_dict, system_to_json
from rollspring.service.sweeps import StoreMismatchError, SweepError, parse_vary_spec, sweep

SYSTEM = "hoop-cylinder"


def cli_app():
    """The rollspring app (the sweep command is one of its commands)."""
    from rollspring.cli.app import app

    return app


def same(a: xr.Dataset, b: xr.Dataset) -> None:
    """Bit for bit: every variable, NaN where NaN."""
    assert sorted(a.data_vars) == sorted(b.data_vars)
    for name in a.data_vars:
        x, y = np.asarray(a[name].values), np.asarray(b[name].values)
        assert x.dtype == y.dtype and x.shape == y.shape, name
        assert np.array_equal(x, y, equal_nan=x.dtype.kind == "f"), name


@pytest.fixture(scope="module")
def system():
    return rollspring.load_system(SYSTEM)


# ---------------------------------------------------------------------------------------------
# the store


def test_store_layout_and_chunking_independence(system, tmp_path):
    vary = {
        "bodies.hoop.mass": [0.5, 1.0, 2.0],
        "springs.0.stiffness": [50.0, 100.0, 150.0, 200.0],
        "bodies.cylinder.mu_static": [0.01, 1.0],
    }
    one = sweep(system, vary, 3.0, chunk=5, out=tmp_path / "a.zarr")
    other = sweep(system, vary, 3.0, chunk=1000)  # in memory, one chunk
    same(one.load(), other)
    ds = xr.open_zarr(tmp_path / "a.zarr")
    assert list(ds["omega"].dims) == [*vary, "mode"]
    assert list(ds["max_friction_ratio"].dims) == [*vary, "body"]
    assert list(ds["body"].values) == ["hoop", "cylinder"]
    assert ds["bodies.hoop.mass"].attrs["units"] == "kg"
    assert ds["springs.0.stiffness"].attrs["units"] == "N/m"
    assert ds["bodies.cylinder.mu_static"].attrs["units"] == "1"
    for name in ds.data_vars:
        assert ds[name].attrs["units"] and ds[name].attrs["long_name"], name
    assert ds["status"].attrs["flag_meanings"].split()[:4] == [
        "finished",
        "nonfinite",
        "slip",
        "liftoff",
    ]
    attrs = ds.attrs
    assert rollspring.model.system_from_text(attrs["system"]) == system
    assert len(attrs["grid_fingerprint"]) == 64
    assert attrs["chunk"] == 4 and attrs["chunk_shape"] == [1, 2, 2] and attrs["n_chunks"] == 6
    assert attrs["step"] > 0 and attrs["integrator"] in ("verlet", "yoshida4", "yoshida6")
    # the low friction coefficient makes the cylinder slip at once (released compressed)
    slip = ds["status"].sel({"bodies.cylinder.mu_static": 0.01}).values
    assert np.all(slip == 2)
    assert np.all(ds["first_slip_body"].sel({"bodies.cylinder.mu_static": 0.01}).values == 1)
    assert np.all(ds["status"].sel({"bodies.cylinder.mu_static": 1.0}).values == 0)
    markers = sorted((tmp_path / "a.zarr" / ".rollspring-done").iterdir())
    assert [p.name for p in markers] == [str(i) for i in range(6)]


def test_resume_runs_only_unfinished_chunks(system, tmp_path):
    vary = {"springs.0.stiffness": np.linspace(50, 200, 6), "bodies.hoop.mass": [0.5, 1.0]}
    out = tmp_path / "r.zarr"
    first = sweep(system, vary, 2.0, chunk=2, out=out).load()
    for index in (1, 4):
        (out / ".rollspring-done" / str(index)).unlink()
    seen = []
    again = sweep(system, vary, 2.0, chunk=2, out=out, progress=seen.append).load()
    assert seen[0].chunks_skipped == 4 and seen[0].chunks_to_run == 2
    assert seen[-1].chunks_run == 2 and seen[-1].done_runs == 12
    same(first, again)


def test_resume_reruns_a_marked_chunk_whose_file_is_gone_and_drops_partial_files(system, tmp_path):
    """A resume checks the chunks its markers vouch for: one deleted from the store (here every
    variable's file of chunk 3, and one variable's of chunk 5) runs again instead of staying
    fill values; a ``.partial`` file a killed Zarr write left and a half-made marker go."""
    vary = {"springs.0.stiffness": np.linspace(50, 200, 6), "bodies.hoop.mass": [0.5, 1.0]}
    out = tmp_path / "r.zarr"
    first = sweep(system, vary, 2.0, chunk=2, out=out).load()
    chunk_files = sorted(p for p in out.glob("*/c.*") if p.is_file())
    assert chunk_files
    import zarr

    group = zarr.open_group(str(out), mode="r")
    gone = 0
    for name, array in group.arrays():
        if array.shape[:2] != (6, 2):
            continue
        for index, drop in ((3, True), (5, name == "status")):
            starts = [r.start for r in _grid_region(out, index)] + [0] * (array.ndim - 2)
            coords = tuple(a // c for a, c in zip(starts, array.chunks, strict=True))
            key = array.metadata.encode_chunk_key(coords)
            if drop and (out / name / key).is_file():  # a fill-valued chunk has no file
                (out / name / key).unlink()
                gone += 1
    assert gone > 10
    (out / "status" / "c.0.0.0123abcd.partial").write_bytes(b"half")
    (out / ".rollspring-done" / ".7.4242.tmp").touch()
    seen = []
    again = sweep(system, vary, 2.0, chunk=2, out=out, progress=seen.append).load()
    assert seen[0].chunks_skipped == 4 and seen[0].chunks_to_run == 2
    same(first, again)
    assert not list(out.rglob("*.partial")) and not list(out.rglob(".*.tmp"))


def _grid_region(out, index):
    """Chunk ``index``'s region in the store at ``out`` (chunks of 2 runs along the first axis,
    whole along the second: the store's own chunk shape)."""
    from rollspring.service.sweeps.store import read_attrs

    shape = read_attrs(out)["chunk_shape"]
    per_row = 2 // shape[1]
    return (
        slice((index // per_row) * shape[0], (index // per_row + 1) * shape[0]),
        slice((index % per_row) * shape[1], (index % per_row + 1) * shape[1]),
    )


def test_fingerprint_mismatch_is_refused(system, tmp_path):
    out = tmp_path / "f.zarr"
    sweep(system, {"springs.0.stiffness": [50.0, 100.0]}, 1.0, out=out)
    with pytest.raises(StoreMismatchError, match="holds another sweep"):
        sweep(system, {"springs.0.stiffness": [50.0, 101.0]}, 1.0, out=out)
    with pytest.raises(StoreMismatchError):
        sweep(system, {"springs.0.stiffness": [50.0, 100.0]}, 1.5, out=out)
    replaced = sweep(system, {"springs.0.stiffness": [50.0, 101.0]}, 1.0, out=out, overwrite=True)
    assert list(replaced["springs.0.stiffness"].values) == [50.0, 101.0]
    result = CliRunner().invoke(
        cli_app(),
        ["sweep", SYSTEM, "--vary", "springs.0.stiffness=1,2", "-T", "1", "--out", str(out)],
    )
    assert result.exit_code == 2
    assert result.output.count("\n") == 1 and "holds another sweep" in result.output


def test_grid_too_fast_to_resolve_is_refused(system, tmp_path):
    """A grid whose fastest run needs more than MAX_STEPS steps is refused before any run,
    with the frequency, the steps and the limit (it once ran the whole grid with one step
    of the whole duration); --step forces it."""
    from rollspring.simulate.batch.plan import MAX_STEPS, omega_limit, steps_needed

    vary = {"springs.0.stiffness": [100.0, 1e8]}
    omega = float(rollspring.analyze(_with_stiffness(system, 1e8)).modes[-1].omega)
    need = float(steps_needed(np.array([omega]), 1000.0, 1e-8, "auto")[0])
    assert need > MAX_STEPS
    with pytest.raises(SweepError) as refused:
        sweep(system, vary, 1000.0, confirm=True, out=tmp_path / "s.zarr")
    message = str(refused.value)
    assert f"{omega:.4g} rad/s" in message and f"{need:.3g} steps" in message
    assert f"{omega_limit(1000.0, 1e-8, 'auto'):.4g} rad/s are resolved" in message
    assert "\n" not in message and not (tmp_path / "s.zarr").exists()
    result = CliRunner().invoke(
        cli_app(),
        [
            "sweep",
            SYSTEM,
            "--vary",
            "springs.0.stiffness=100,1e8",
            "-T",
            "1000",
            "--yes",
            "--out",
            str(tmp_path / "c.zarr"),
        ],
    )
    assert result.exit_code == 2
    assert result.output.count("\n") == 1 and "pass --step to force it" in result.output
    assert not (tmp_path / "c.zarr").exists()
    forced = sweep(system, vary, 1e-3, step=1e-4)
    assert forced.attrs["step"] == pytest.approx(1e-4)


def _with_stiffness(system, stiffness):
    data = system_to_json(system)
    data["springs"][0]["stiffness"] = stiffness
    return system_from_dict(data)


def test_not_a_store_is_refused(system, tmp_path):
    (tmp_path / "x.zarr").write_text("hello")
    with pytest.raises(StoreMismatchError, match="not a rollspring sweep store"):
        sweep(system, {"springs.0.stiffness": [50.0]}, 1.0, out=tmp_path / "x.zarr")


def test_metric_selection_keeps_status(system):
    ds = sweep(system, {"springs.0.stiffness": [50.0, 100.0]}, 1.0, metrics=["period_measured"])
    assert sorted(ds.data_vars) == ["period_measured", "status"]
    assert ds.attrs["metrics"] == ["period_measured", "status"]


def test_on_slip_continue_equals_single_runs(system):
    vary = {"bodies.cylinder.mu_static": [0.01, 0.02], "bodies.cylinder.v": [0.0, 0.3]}
    ds = sweep(system, vary, 1.0, on_slip="continue", rtol=1e-8)
    assert "energy_dissipated" in ds and "time_slipping" in ds
    base = system_to_json(system)
    for mu in vary["bodies.cylinder.mu_static"]:
        for v in vary["bodies.cylinder.v"]:
            data = system_to_json(system)
            data["bodies"][1].update(mu_static=mu, v=v)
            run = rollspring.simulate(system_from_dict(data), 1.0, rtol=1e-8, on_slip="continue")
            point = ds.sel({"bodies.cylinder.mu_static": mu, "bodies.cylinder.v": v})
            assert float(point["energy_dissipated"]) == pytest.approx(
                run.energy[0] - run.energy[-1], rel=0, abs=0
            )
            assert float(point["first_slip_time"]) == run.summary["first_slip"]["time"]
            slipping = [(e["kind"], e["time"]) for e in run.events]
            assert slipping[0][0] == "slip"
            assert 0 < float(point["time_slipping"]) <= 1.0
            assert float(point["energy_dissipated"]) > 0
            assert int(point["status"]) == 0
    assert base == system_to_json(system)


def test_continue_only_metrics_need_continue(system):
    with pytest.raises(SweepError, match="only with --on-slip continue"):
        sweep(system, {"springs.0.stiffness": [50.0]}, 1.0, metrics=["energy_dissipated"])


def test_mode_amplitude_and_attachment_paths(system):
    ds = sweep(system, {"modes.1.amplitude": [0.0, 0.002, 0.004]}, 2.0)
    # released at rest along the mode about the equilibrium: X-hat stays put, the measured
    # period is the linear one, and the friction needed grows with the amplitude
    assert np.all(ds["status"].values == 0)
    omega = ds["omega"].sel(mode=1).values
    assert np.allclose(omega, 10.801234497346432, rtol=1e-12)
    period = ds["period_measured"].values[1:]
    assert np.allclose(period, 2 * np.pi / omega[1:], rtol=1e-6)
    need = ds["required_mu_linear"].sel(body="hoop").values
    assert need[0] == pytest.approx(0.0, abs=1e-15)
    assert need[2] == pytest.approx(2 * need[1], rel=1e-9)
    raised = sweep(system, {"springs.0.at.1.height": [0.1, 0.15]}, 1.0)
    assert np.all(raised["status"].values == 0)
    # the centre attachment (0.1 m = the radius) is the preset itself
    assert float(raised["omega"].sel(mode=1).values[0]) == pytest.approx(
        10.801234497346432, rel=1e-12
    )
    assert float(raised["omega"].sel(mode=1).values[1]) != pytest.approx(
        10.801234497346432, rel=1e-6
    )


# ---------------------------------------------------------------------------------------------
# bad arguments: one line, exit 2


BAD = [
    (["--vary", "springs.0.stiffness"], "expected PATH="),
    (["--vary", "=1,2"], "PATH before '=' is empty"),
    (["--vary", "springs.0.stiffness="], "no values"),
    (["--vary", "springs.0.stiffness=1:2"], "START:STOP:NUM"),
    (["--vary", "springs.0.stiffness=1:2:3:lin"], "can only be 'log'"),
    (["--vary", "springs.0.stiffness=1:2:0"], "NUM must be a whole number"),
    (["--vary", "springs.0.stiffness=1:2:x"], "NUM must be a whole number"),
    (["--vary", "springs.0.stiffness=a,b"], "is not a number"),
    (["--vary", "springs.0.stiffness=0:2:3:log"], "log range needs"),
    (["--vary", "springs.0.stiffness=1,1"], "given twice"),
    (["--vary", "springs.0.stiffness=-5,5"], "stiffness"),
    (["--vary", "bodies.hoop.mass=0,1"], "mass"),
    (["--vary", "bodies.wheel.mass=1,2"], "no body 'wheel'"),
    (["--vary", "bodies.hoop.colour=1,2"], "unknown body quantity"),
    (["--vary", "springs.3.stiffness=1,2"], "no spring '3'"),
    (["--vary", "springs.0.length=1,2"], "unknown spring quantity"),
    (["--vary", "springs.0.at.2.height=1,2"], "no end '2'"),
    (["--vary", "springs.0.at.0.angle=10,20"], "needs a radius attachment"),
    (["--vary", "modes.0.amplitude=0.001,0.002"], "zero mode"),
    (["--vary", "modes.7.amplitude=0.001"], "no mode '7'"),
    (["--vary", "gravity.x=1"], "unknown PATH"),
    (["--vary", "foo=1"], "unknown PATH"),
    (["--vary", "springs.0.stiffness=1,2", "--vary", "springs.0.stiffness=3"], "already varied"),
    (["--vary", "springs.0.stiffness=inf"], "finite"),
    (["--vary", "springs.0.stiffness=1,2", "--metric", "colour"], "unknown metric"),
    (["--vary", "springs.0.stiffness=1,2", "--metric", "time_slipping"], "only with"),
    (["--vary", "springs.0.stiffness=1,2", "--on-slip", "sometimes"], "--on-slip"),
    (["--vary", "springs.0.stiffness=1,2", "--chunk", "0"], "--chunk"),
    (["--vary", "springs.0.stiffness=1,2", "--scheduler", "nowhere"], "--scheduler"),
    (["--vary", "springs.0.stiffness=1,2", "--integrator", "euler"], "--integrator"),
]


@pytest.mark.parametrize(("args", "words"), BAD, ids=[" ".join(a) for a, _ in BAD])
def test_bad_arguments_are_one_line_errors(args, words, tmp_path):
    result = CliRunner().invoke(
        cli_app(), ["sweep", SYSTEM, *args, "-T", "1", "--out", str(tmp_path / "s.zarr")]
    )
    assert result.exit_code == 2, result.output
    assert result.output.startswith("error: ") and result.output.count("\n") == 1, result.output
    assert words in result.output
    assert not (tmp_path / "s.zarr").exists()


@pytest.mark.parametrize(
    ("args", "words"),
    [
        ([], "--vary"),
        (["--vary", "springs.0.stiffness=1"], "--duration"),
    ],
)
def test_missing_options(args, words, tmp_path):
    extra = [] if words == "--duration" else ["-T", "1"]
    result = CliRunner().invoke(
        cli_app(), ["sweep", SYSTEM, *args, *extra, "--out", str(tmp_path / "s.zarr")]
    )
    assert result.exit_code == 2 and words in result.output


# the values of a quantity only its body or spring checks: their ends decide (an interval)
_ENDS = [-1e7, -1e4, -1.0, -1e-300, 0.0, 1e-7, 1e-6, 0.3, 0.5, 0.7, 1.0, 1e4, 1e6, 1e9, 2e9]


@settings(max_examples=60, deadline=None)
@given(
    path=st.sampled_from(
        [
            "bodies.hoop.mass",
            "bodies.hoop.v",
            "bodies.hoop.mu_static",
            "bodies.hoop.mu_kinetic",
            "springs.0.stiffness",
        ]
    ),
    values=st.lists(
        st.one_of(st.sampled_from(_ENDS), st.floats(-2e9, 2e9), st.just(math.inf)),
        min_size=1,
        max_size=6,
        unique=True,
    ),
    mu_kinetic=st.sampled_from([None, 0.0, 0.5]),
)
def test_a_grid_axis_is_checked_by_its_ends_as_value_by_value(path, values, mu_kinetic):
    """check_grid validates an axis of a body's or a spring's own quantity by its smallest and
    largest finite values (and inf): the same verdict, and the same message, as value by value."""
    from rollspring.service.sweeps import grid

    data = system_to_json(rollspring.load_system(SYSTEM))
    data["bodies"][0]["mu_static"] = 0.6
    if mu_kinetic is not None:
        data["bodies"][0]["mu_kinetic"] = mu_kinetic
    system = system_from_dict(data)
    part = grid._part_of(system_to_json(system), system, path)
    array = np.asarray(values)
    each = all(grid._part_valid(part, path, float(v)) for v in array)
    assert grid._ends_valid(part, path, array) == each
    if not np.all(np.isfinite(array)) and not path.endswith("mu_static"):
        return  # refused as not finite before any value is checked
    try:
        grid.check_grid(system, {path: values})
    except SweepError as exc:
        assert not each
        with pytest.raises(SweepError) as one_by_one:
            grid._check_each(system_to_json(system), system, path, part, array)
        assert str(exc) == str(one_by_one.value)
    else:
        assert each


def test_parse_vary_spec():
    assert parse_vary_spec("springs.0.stiffness=1:3:3") == ("springs.0.stiffness", [1.0, 2.0, 3.0])
    path, values = parse_vary_spec("gravity=1:100:3:log")
    assert path == "gravity" and values == pytest.approx([1.0, 10.0, 100.0], rel=1e-15)
    assert parse_vary_spec("bodies.hoop.mu_static=0.1,inf")[1] == [0.1, math.inf]


# ---------------------------------------------------------------------------------------------
# physics on the store


M1 = [0.5, 0.8, 1.3, 2.0]
M2 = [0.4, 1.0, 1.7]
K = [30.0, 100.0, 250.0]


def qqq1(m1, m2, k):
    """Paper eq. (QQQ1): Omega^2 = k/(2 m1) + 2k/(3 m2)."""
    return np.sqrt(k / (2 * m1) + 2 * k / (3 * m2))


@pytest.fixture(scope="module")
def mass_grid(system, tmp_path_factory):
    vary = {"bodies.hoop.mass": M1, "bodies.cylinder.mass": M2, "springs.0.stiffness": K}
    omega_max = float(
        qqq1(
            np.array(M1)[:, None, None], np.array(M2)[None, :, None], np.array(K)[None, None, :]
        ).max()
    )
    # one step for the grid with the fastest mode turning 0.016 rad a step: the batch then
    # samples its metrics every step (it samples every max(1, int(0.03 / (omega h))) steps),
    # so the period's crossings are interpolated over 0.016 rad at most (see test below)
    out = tmp_path_factory.mktemp("sweep") / "masses.zarr"
    sweep(system, vary, 10.0, out=out, integrator="yoshida6", step=0.016 / omega_max, chunk=7)
    return xr.open_zarr(out)


def test_omega_is_paper_qqq1(mass_grid):
    m1 = mass_grid["bodies.hoop.mass"]
    m2 = mass_grid["bodies.cylinder.mass"]
    k = mass_grid["springs.0.stiffness"]
    expected = np.sqrt(k / (2 * m1) + 2 * k / (3 * m2)).transpose(*mass_grid["status"].dims)
    stored = mass_grid["omega"].sel(mode=1)
    assert np.max(np.abs(stored.values / expected.values - 1)) < 1e-12
    assert np.all(mass_grid["omega"].sel(mode=0).values == 0.0)
    # X-hat's weights (2 m1, 1.5 m2) normalised (paper eq. (c))
    w = mass_grid["stationary_weight"].sel(body="hoop")
    expected_w = (2 * m1 / (2 * m1 + 1.5 * m2)).broadcast_like(w).transpose(*w.dims)
    assert np.allclose(w.values, expected_w.values, rtol=1e-12)


def test_measured_period_is_the_linear_one(mass_grid):
    """The hoop-cylinder pair joined at the centres is exactly linear while it rolls, so the
    measured period is 2 pi / omega up to the integration (Yoshida-6 at omega h = 0.016: a
    frequency error of 6e-14) and the batch's period estimate: the mean spacing of upward
    zero crossings of the spring's length rate, each linearly interpolated between metric
    samples (an error growing as the cube of the phase between samples: 3e-9 at the default
    0.03 rad, 4e-10 at 0.016)."""
    assert mass_grid.attrs["metric_every"] == 1
    assert np.all(mass_grid["status"].values == 0)
    period = mass_grid["period_measured"].values
    linear = 2 * np.pi / mass_grid["omega"].sel(mode=1).values
    assert np.max(np.abs(period / linear - 1)) < 1e-9


def test_first_slip_map_agrees_with_single_runs(system, tmp_path):
    """First slip over (mu_s of the cylinder, its initial velocity): released from rest the
    pair needs the most friction at t = 0 (slip at once or never), so the amplitude varied is
    the initial velocity, which makes slips happen during the motion."""
    mu = np.linspace(0.04, 0.13, 12)
    v = np.linspace(0.05, 0.5, 10)
    ds = sweep(
        system,
        {"bodies.cylinder.mu_static": mu, "bodies.cylinder.v": v},
        2.0,
        rtol=1e-10,
        out=tmp_path / "slip.zarr",
        chunk=16,
    )
    t_slip = ds["first_slip_time"].values
    assert (t_slip > 0).sum() > 40 and np.isnan(t_slip).sum() > 5
    assert np.all((t_slip > 0) | np.isnan(t_slip))
    rng = np.random.default_rng(2026)
    points = [
        (int(i), int(j))
        for i, j in zip(rng.integers(0, len(mu), 20), rng.integers(0, len(v), 20), strict=True)
    ]
    for i, j in points:
        data = system_to_json(system)
        data["bodies"][1].update(mu_static=float(mu[i]), v=float(v[j]))
        run = rollspring.simulate(system_from_dict(data), 2.0, rtol=1e-10)
        first = run.summary["first_slip"]
        if first is None:
            assert np.isnan(t_slip[i, j]) and ds["first_slip_body"].values[i, j] == -1
        else:
            assert abs(t_slip[i, j] - first["time"]) <= 1e-9
            assert ds["body"].values[ds["first_slip_body"].values[i, j]] == first["body"]


def test_unrefined_slip_instant_is_interpolated_between_steps(system):
    """Without refinement the batch's instant comes from the contact margin interpolated
    linearly between steps: an error of order h^2 (5e-6 s at h = 1 ms for this system), far
    from 1e-9 s — which is why the sweep refines it by default."""
    vary = {"bodies.cylinder.mu_static": [0.05], "bodies.cylinder.v": [0.3]}
    raw = sweep(system, vary, 1.0, step=1e-3, integrator="yoshida6", refine_slip=False)
    fine = sweep(system, vary, 1.0, step=1e-3, integrator="yoshida6")
    gap = abs(float(raw["first_slip_time"][0, 0]) - float(fine["first_slip_time"][0, 0]))
    assert 1e-9 < gap < 1e-4


def test_the_template_is_the_one_xarray_writes(tmp_path):
    """The store's template is made with Zarr directly (a tenth of xarray's time, written while
    the first chunks step); every array's and the group's metadata, consolidated metadata
    included, is what ``xarray.Dataset.to_zarr(compute=False)`` writes for the same dataset
    (given the store's compressor, Blosc where Zarr's default is zstd)."""
    import json
    import warnings

    import dask.array as da
    from zarr.codecs import BloscCodec

    from rollspring.service.sweeps.grid import Grid, unit_of
    from rollspring.service.sweeps.store import _INTEGER, COMPRESSOR, VARIABLES, write_template
    from rollspring.simulate.status import FLAG_MEANINGS, FLAG_VALUES

    grid = Grid(
        ("springs.0.stiffness", "bodies.hoop.mu_static"),
        (tuple(np.linspace(50.0, 150.0, 7)), tuple(np.geomspace(0.1, 1.0, 5))),
        (3, 5),
    )
    ids, metrics, attrs = ["hoop", "cylinder"], tuple(VARIABLES), {"chunk_shape": [3, 5]}
    ours = tmp_path / "ours.zarr"
    write_template(ours, grid, ids, 2, metrics, attrs)

    coords = {
        p: (p, np.asarray(v), {"units": unit_of(p), "long_name": p})
        for p, v in zip(grid.paths, grid.values, strict=True)
    }
    coords["mode"] = ("mode", np.arange(2), {"units": "1", "long_name": "mode, sorted by omega"})
    coords["body"] = ("body", np.array(ids, dtype=str), {"units": "1", "long_name": "body id"})
    data, encoding = {}, {}
    for name in metrics:
        extra, units, long_name = VARIABLES[name]
        shape = (*grid.shape, *([2] if extra else []))
        dtype = _INTEGER.get(name, "float64")
        fill = -1 if name == "first_slip_body" else (5 if name == "status" else np.nan)
        var_attrs = {"units": units, "long_name": long_name}
        if name == "status":
            var_attrs |= {"flag_values": list(FLAG_VALUES), "flag_meanings": FLAG_MEANINGS}
        dims = (*grid.paths, *([extra] if extra else []))
        data[name] = (dims, da.full(shape, fill, dtype=dtype, chunks=shape), var_attrs)
        encoding[name] = {
            "chunks": (*grid.chunks, *([2] if extra else [])),
            "chunk_key_encoding": {"name": "default", "separator": "."},  # a file per chunk
        }
        if dtype != "float64":
            encoding[name]["fill_value"] = fill
    for name in [*coords, *metrics]:
        encoding.setdefault(name, {})["compressors"] = (BloscCodec(**COMPRESSOR),)
    theirs = tmp_path / "theirs.zarr"
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # Zarr v3's unspecified string type, consolidation
        xr.Dataset(data, coords=coords, attrs=attrs).to_zarr(
            str(theirs), mode="w", compute=False, zarr_format=3, encoding=encoding
        )
    for name in [".", *coords, *metrics]:
        assert json.loads((ours / name / "zarr.json").read_text()) == json.loads(
            (theirs / name / "zarr.json").read_text()
        ), name
    xr.testing.assert_identical(xr.open_zarr(ours).load(), xr.open_zarr(theirs).load())


def test_a_store_is_blosc_compressed_and_a_zstd_store_resumed_with_zstd(
    system, tmp_path, monkeypatch
):
    """A new store's arrays are Blosc (LZ4, level 5, shuffled bytes); a store made with Zarr's
    default zstd (as stores made before 30 Nov 2026) is resumed with its own codecs: its
    documents left as they were, the chunk run again encoded by zstd, the numbers the same."""
    import json

    import zarr
    from zarr.codecs import ZstdCodec
    from zarr.storage import MemoryStore

    from rollspring.service.sweeps import store
    from rollspring.service.sweeps.grid import Grid

    vary = {"springs.0.stiffness": np.linspace(50, 200, 4), "bodies.hoop.mass": [0.5, 1.0]}
    fresh = sweep(system, vary, 2.0, chunk=2, out=tmp_path / "new.zarr").load()
    for document in (tmp_path / "new.zarr").glob("*/zarr.json"):
        codecs = json.loads(document.read_text())["codecs"]
        assert codecs[-1]["name"] == "blosc", document
        assert {k: codecs[-1]["configuration"][k] for k in ("cname", "clevel")} == {
            "cname": "lz4",
            "clevel": 5,
        }

    def zarr_defaults(dtype, fill):
        array = zarr.create_array(
            MemoryStore(), shape=(1,), dtype=np.dtype(dtype), fill_value=fill, zarr_format=3
        )
        document = array.metadata.to_dict()
        return {name: document[name] for name in ("data_type", "fill_value", "codecs")}

    out = tmp_path / "old.zarr"
    with monkeypatch.context() as patched:
        patched.setattr(store, "_defaults", zarr_defaults)
        sweep(system, vary, 2.0, chunk=2, out=out)
    documents = [out / "zarr.json", *out.glob("*/zarr.json")]
    old = {document: document.read_text() for document in documents}
    assert '"blosc"' not in "".join(old.values()) and '"zstd"' in old[out / "zarr.json"]
    (out / "cm_amplitude" / "c.3.0").unlink()
    (out / ".rollspring-done" / "3").unlink()
    again = sweep(system, vary, 2.0, out=out).load()
    same(fresh, again)
    assert {document: document.read_text() for document in documents} == old
    grid = Grid(tuple(vary), tuple(tuple(map(float, v)) for v in vary.values()), (1, 2))
    encoder = store.RegionWriter(out, grid).encoders["cm_amplitude"]
    assert encoder is not None and isinstance(encoder.codecs[-1], ZstdCodec)


def test_a_rerun_without_chunk_resumes_a_store_of_any_chunk_size(system, tmp_path):
    """The default chunk changed (4096 -> 16384 runs): a rerun that gives no chunk takes the
    store's chunk shape, so a store made with another size is resumed, not refused."""
    vary = {"springs.0.stiffness": np.linspace(50, 200, 6), "bodies.hoop.mass": [0.5, 1.0]}
    out = tmp_path / "r.zarr"
    first = sweep(system, vary, 2.0, chunk=2, out=out).load()
    (out / ".rollspring-done" / "4").unlink()
    seen = []
    again = sweep(system, vary, 2.0, out=out, progress=seen.append).load()
    assert (seen[0].chunks_skipped, seen[0].chunks_to_run) == (5, 1)
    assert again.attrs["chunk_shape"] == [1, 2]
    same(first, again)

"""``rollspring fit``: measured tables read in every format, the paper's system fitted from a
rough start, its claims measured, the contract's JSON, bad input, written outputs (issue 27).

The data are made here from the closed-form motion of the hoop and the cylinder
(:mod:`tests.fit_data`), with seeded millimetre noise: nothing of rollspring makes them.
"""

from __future__ import annotations

import json
import math
from pathlib import Path

import numpy as np
import pytest
from typer.testing import CliRunner

import rollspring
from rollspring.cli import app
from rollspring.errors import DataError, FitError
from rollspring.lab import fit as fit_module
from rollspring.lab.data import match_bodies, parse_data, read_data
from rollspring.lab.fit import fit_model, spectral_peaks
from rollspring.lab.posterior import sample_posterior
from rollspring.model import load_system, system_from_dict
from tests.fit_data import (
    Truth,
    recording,
    write_csv,
    write_tracker,
    write_tracker_multi,
)

runner = CliRunner()

DAMPED = Truth(c=0.2, x2=0.47, v1=0.01)  # compressed by 3 cm, released with a push
UNDAMPED = Truth(m2=1.5, k=80.0, x2=0.485)
FREE = ["springs.0.stiffness", "springs.0.damping"]


def _system_file(folder: Path, truth: Truth, **changes: float) -> Path:
    import tomli_w

    path = folder / "rough.toml"
    path.write_text(tomli_w.dumps(truth.system(**changes)))
    return path


def _cli(*args: str) -> tuple[int, str, str]:
    result = runner.invoke(app, list(args))
    return result.exit_code, result.stdout, result.stderr


# ------------------------------------------------------------------------------ the formats


def test_every_format_reads_the_same_positions(tmp_path: Path) -> None:
    t, x, phi = recording(DAMPED, duration=1.0, fps=30)
    plain = read_data(write_csv(tmp_path / "plain.csv", t, x))
    track = read_data(write_csv(tmp_path / "track.csv", t, x, phi))
    single = read_data(write_tracker(tmp_path / "hoop.txt", t, x, 0, "hoop"))
    multi = read_data(write_tracker_multi(tmp_path / "multi.txt", t, x, ("mass A", "mass B")))
    assert plain.tracks == track.tracks == ("hoop", "cylinder")
    assert single.tracks == ("hoop",) and single.format == "tracker"
    assert multi.tracks == ("mass A", "mass B") and multi.format == "tracker-multi"
    for table in (plain, track, single, multi):
        np.testing.assert_array_equal(table.t, t)
        np.testing.assert_array_equal(table.x[:, 0], x[:, 0])
    np.testing.assert_array_equal(track.phi, phi)
    assert np.isnan(plain.phi).all() and np.isnan(multi.phi).all()
    np.testing.assert_array_equal(multi.x[:, 1], x[:, 1])


def test_unmarked_frames_are_skipped(tmp_path: Path) -> None:
    t, x, _ = recording(DAMPED, duration=2.0, fps=30)
    path = write_tracker_multi(tmp_path / "gaps.txt", t, x, ("mass A", "mass B"), unmarked=5)
    table = match_bodies(
        read_data(path), load_system("hoop-cylinder"), {"mass A": "hoop", "mass B": "cylinder"}
    )
    empty = np.arange(t.size) % 5 == 3
    assert np.isnan(table.x[empty, 1]).all() and np.isfinite(table.x[~empty, 1]).all()
    assert table.n_points == 2 * t.size - empty.sum()
    result = fit_model(table, system_from_dict(DAMPED.system(k=70.0, c=0.0)), FREE)
    assert result.value("springs.0.stiffness") == pytest.approx(DAMPED.k, rel=0.01)


@pytest.mark.parametrize(
    ("text", "message"),
    [
        ("x_hoop,x_cylinder\n0,1\n", "data.csv: no time column"),
        ("t,x_hoop\n0,0\n0.2,0\n0.1,0\n", "data.csv: row 4: the time 0.1 s is earlier than"),
        ("t,x_hoop\n0,0\n0.1,0\n0.1,0\n", "data.csv: row 4: the time 0.1 s repeats"),
        ("t,x_hoop\n0,0\n0.1,abc\n", "data.csv: row 3, column 2: 'abc' is not a finite number"),
        ("t,x_hoop,speed\n0,0,1\n", "data.csv: column 'speed': not a data column"),
        ("t,x_hoop,phi_wheel\n0,0,1\n", "column 'phi_wheel' has no position column"),
        ("t,x_hoop\n", "data.csv: no data rows"),
        ("", "data.csv: the file is empty"),
        ("mass A\nx\ty\n1\t2\n", "data.csv: no time column"),
    ],
)
def test_bad_tables_are_one_line_errors(text: str, message: str) -> None:
    with pytest.raises(DataError) as caught:
        parse_data(text, "data.csv")
    assert message in str(caught.value)
    assert "\n" not in str(caught.value)


def test_tracks_are_matched_by_name_or_map() -> None:
    system = load_system("hoop-cylinder")
    table = parse_data("t,x_wheel\n0,0\n0.1,0.01\n", "d.csv")
    with pytest.raises(DataError, match=r"column 'x_wheel': no body 'wheel' in the system"):
        match_bodies(table, system)
    assert match_bodies(table, system, {"wheel": "cylinder"}).bodies == ("cylinder",)
    with pytest.raises(DataError, match=r"--map wheel=disc: no body 'disc'"):
        match_bodies(table, system, {"wheel": "disc"})
    with pytest.raises(DataError, match=r"--map car=hoop: d.csv has no track 'car'"):
        match_bodies(table, system, {"car": "hoop"})


# ------------------------------------------------------------------------------ the fit


def test_the_spectrum_finds_the_frequency() -> None:
    t, x, _ = recording(DAMPED, duration=10.0, fps=60)
    omega = math.sqrt(DAMPED.k * (1 / (2 * DAMPED.m1) + 2 / (3 * DAMPED.m2)))
    assert spectral_peaks(t, x)[0] == pytest.approx(omega, rel=0.01)


@pytest.mark.parametrize("fps", [30.0, 60.0])
def test_a_rough_start_reaches_the_truth_with_damping(fps: float) -> None:
    """Stiffness 30 % off and no damping: k to 1 %, damping to 10 %, each within 3 standard
    errors (the issue's acceptance). One seed each: a 3-sigma check fails for 0.3 % of noise
    draws (the coverage test, test_fit_coverage.py, measures the errors' calibration)."""
    t, x, _ = recording(DAMPED, duration=10.0, fps=fps, seed=1)
    data = match_bodies(parse_data(_csv_text(t, x), "mem.csv"), load_system("hoop-cylinder"))
    result = fit_model(data, system_from_dict(DAMPED.system(k=70.0, c=0.0)), FREE)
    assert result.converged
    k, c = result.parameters["springs.0.stiffness"], result.parameters["springs.0.damping"]
    assert k.value == pytest.approx(DAMPED.k, rel=0.01)
    assert abs(k.value - DAMPED.k) <= 3 * k.stderr
    assert c.value == pytest.approx(DAMPED.c, rel=0.1)
    assert abs(c.value - DAMPED.c) <= 3 * c.stderr
    for body, index in (("hoop", 0), ("cylinder", 1)):
        assert result.residual_rms[body] == pytest.approx(1e-3, rel=0.15)
        x0 = result.parameters[f"bodies.{body}.x"]
        assert abs(x0.value - DAMPED.positions(np.zeros(1))[0, index]) <= 3 * x0.stderr
    assert result.level and not result.warnings


def test_a_rough_start_from_above_and_a_heavier_cylinder() -> None:
    """Undamped, stiffness 30 % too high, a cylinder 1.5 times the hoop: k to 1 %."""
    t, x, _ = recording(UNDAMPED, duration=8.0, fps=30, seed=3)
    data = match_bodies(parse_data(_csv_text(t, x), "mem.csv"), load_system("hoop-cylinder"))
    result = fit_model(
        data, system_from_dict(UNDAMPED.system(k=1.3 * UNDAMPED.k)), ["springs.0.stiffness"]
    )
    k = result.parameters["springs.0.stiffness"]
    assert (
        k.value == pytest.approx(UNDAMPED.k, rel=0.01) and abs(k.value - UNDAMPED.k) <= 3 * k.stderr
    )


def test_one_tracked_body_is_enough(tmp_path: Path) -> None:
    t, x, _ = recording(DAMPED, duration=10.0, fps=30, seed=5)
    path = write_tracker(tmp_path / "hoop.txt", t, x, 0, "hoop")
    result = rollspring.fit(path, DAMPED.system(k=70.0, c=0.0), FREE)
    assert list(result.residual_rms) == ["hoop"]
    k = result.parameters["springs.0.stiffness"]
    assert abs(k.value - DAMPED.k) <= 3 * k.stderr and k.value == pytest.approx(100, rel=0.01)


def test_the_claims_match_the_truth_within_their_uncertainty(tmp_path: Path) -> None:
    """The CM's and X̂'s peak-to-peak motion measured match the closed form's, within 3 of their
    stated standard errors; the frictions are 3 : 2 (paper); the bodies rolled."""
    truth = Truth(c=0.2, v1=0.0015, v2=-0.002)  # X̂ at rest: w1 v1 + w2 v2 = 0
    t, x, phi = recording(truth, duration=6.0, fps=60, seed=11)
    result = rollspring.fit(
        write_csv(tmp_path / "track.csv", t, x, phi), truth.system(k=70.0, c=0.0), FREE
    )
    fine = np.linspace(t[0], t[-1], 4 * t.size)
    exact = truth.positions(fine)
    cm = exact @ np.array([truth.m1, truth.m2]) / (truth.m1 + truth.m2)
    stationary = exact @ np.array(truth.weights)
    claims = result.claims
    for name, true in (
        ("cm_peak_to_peak", np.ptp(cm)),
        ("stationary_peak_to_peak", np.ptp(stationary)),
    ):
        measured = claims[name]
        assert measured["stderr"] > 0
        assert abs(measured["value"] - true) <= 3 * measured["stderr"], name
    assert claims["cm_peak_to_peak"]["value"] > 10 * claims["stationary_peak_to_peak"]["value"]
    assert claims["friction_ratio"]["value"] == pytest.approx(1.5, rel=1e-6)  # paper: 3 : 2
    assert all(check["rolled"] for check in claims["rolled"].values())


def test_a_slipping_recording_is_said_not_to_roll(tmp_path: Path) -> None:
    t, x, phi = recording(DAMPED, duration=4.0, fps=60, seed=2, slip=0.5, angle_noise=0.002)
    result = rollspring.fit(
        write_csv(tmp_path / "slip.csv", t, x, phi), DAMPED.system(), ["springs.0.stiffness"]
    )
    assert not any(check["rolled"] for check in result.claims["rolled"].values())


def test_the_cli_posterior(tmp_path: Path) -> None:
    t, x, _ = recording(DAMPED, duration=2.0, fps=30, seed=6)
    code, out, err = _cli(
        "fit",
        str(write_csv(tmp_path / "d.csv", t, x)),
        "--system",
        str(_system_file(tmp_path, DAMPED)),
        "--free",
        FREE[0],
        "--posterior",
        "--json",
    )
    assert code == 0, err
    document = json.loads(out)
    interval = document["posterior"]["credible_intervals"][FREE[0]]
    fitted = document["parameters"][FREE[0]]
    assert interval["low"] < fitted["value"] < interval["high"]
    assert interval["high"] - interval["low"] == pytest.approx(4 * fitted["stderr"], rel=0.4)


def test_masses_and_stiffness_together_are_not_identifiable() -> None:
    """Scaling every mass and the stiffness together leaves the undamped motion unchanged."""
    t, x, _ = recording(UNDAMPED, duration=4.0, fps=30, seed=4)
    data = match_bodies(parse_data(_csv_text(t, x), "mem.csv"), load_system("hoop-cylinder"))
    result = fit_model(
        data,
        system_from_dict(UNDAMPED.system()),
        ["springs.0.stiffness", "bodies.hoop.mass", "bodies.cylinder.mass"],
    )
    assert len(result.warnings) == 1
    warning = result.warnings[0]
    assert warning.startswith("not identifiable")
    for path in ("springs.0.stiffness", "bodies.hoop.mass", "bodies.cylinder.mass"):
        assert path in warning


@pytest.mark.parametrize(("release", "frames"), [(0.4, 240), (3.3, 600)])
def test_fix_initial_fits_the_release_time_and_the_origin(release: float, frames: int) -> None:
    """Held at the system's placement until ``release`` s into the record (a period into it,
    or most of a third of it), filmed with the x origin 0.25 m to the left: t0 and x_offset
    found, within 3 standard errors."""
    truth = Truth(c=0.1)
    t = np.arange(frames) / 60
    held = (t < release)[:, None]
    x = np.where(held, truth.positions(np.zeros(1)), truth.positions(np.maximum(t - release, 0)))
    x = x + 0.25 + np.random.default_rng(8).normal(0, 1e-3, x.shape)
    data = match_bodies(parse_data(_csv_text(t, x), "mem.csv"), load_system("hoop-cylinder"))
    result = fit_model(
        data, system_from_dict(truth.system(k=75.0)), ["springs.0.stiffness"], fix_initial=True
    )
    t0, offset = result.parameters["t0"], result.parameters["x_offset"]
    assert abs(t0.value - release) <= 3 * t0.stderr
    assert abs(offset.value - 0.25) <= 3 * offset.stderr
    assert result.parameters["bodies.hoop.x"].fixed
    assert result.value("springs.0.stiffness") == pytest.approx(truth.k, rel=0.01)


def test_a_wall_makes_the_origin_identifiable() -> None:
    """wall-hoop-cylinder: the anchor fixes where the equilibrium is, so the data's x origin is
    fitted (the data made from the model's own exact motion, shifted)."""
    from rollspring.lab.motion import motion_matrix, transition_matrices
    from rollspring.physics import system_arrays

    system = load_system("wall-hoop-cylinder")
    arrays = system_arrays(system)
    t = np.arange(300) / 50
    start = np.concatenate([arrays.x0 + np.array([0.01, -0.005]), arrays.v0, [1.0]])
    x = (transition_matrices(motion_matrix(arrays), t) @ start)[:, : arrays.n_bodies]
    x = x - 0.1 + np.random.default_rng(9).normal(0, 1e-3, x.shape)
    header = "t," + ",".join(f"x_{i}" for i in arrays.ids)
    text = "\n".join(
        [header] + [",".join(map(repr, map(float, (ti, *xi)))) for ti, xi in zip(t, x, strict=True)]
    )
    result = fit_model(match_bodies(parse_data(text, "wall.csv"), system), system, [])
    offset = result.parameters["x_offset"]
    assert not offset.fixed and abs(offset.value + 0.1) <= 3 * offset.stderr


def test_off_centre_springs_are_fitted_on_the_simulated_motion() -> None:
    """The frictionless preset (ends at the percussion points: not level-linear) is fitted on
    rollspring.simulate's motion; data from its own run with noise, stiffness 20 % off."""
    from rollspring.model import system_to_json

    system = load_system("frictionless")
    run = rollspring.simulate(system, 1.5, n_output=46, rtol=1e-10)
    x = run.x + np.random.default_rng(12).normal(0, 5e-4, run.x.shape)
    header = "t," + ",".join(f"x_{i}" for i in run.ids)
    text = "\n".join(
        [header]
        + [",".join(map(repr, map(float, (ti, *xi)))) for ti, xi in zip(run.t, x, strict=True)]
    )
    rough = system_to_json(system)
    true_k = rough["springs"][0]["stiffness"]
    rough["springs"][0]["stiffness"] = 0.8 * true_k
    result = fit_model(
        match_bodies(parse_data(text, "f.csv"), system),
        system_from_dict(rough),
        ["springs.0.stiffness"],
    )
    k = result.parameters["springs.0.stiffness"]
    assert not result.level
    assert abs(k.value - true_k) <= 3 * k.stderr and k.value == pytest.approx(true_k, rel=0.02)


def test_the_posterior_agrees_with_the_standard_errors() -> None:
    t, x, _ = recording(DAMPED, duration=3.0, fps=30, seed=21)
    data = match_bodies(parse_data(_csv_text(t, x), "mem.csv"), load_system("hoop-cylinder"))
    result = rollspring.fit(data, DAMPED.system(), FREE, claims=False)
    posterior = sample_posterior(result, steps=200, seed=3).to_dict()
    intervals = posterior["credible_intervals"]
    for name in FREE:
        interval, parameter = intervals[name], result.parameters[name]
        width = interval["high"] - interval["low"]
        assert width == pytest.approx(2 * 1.96 * parameter.stderr, rel=0.35)
        assert interval["low"] < parameter.value < interval["high"]
    assert 0.2 < posterior["acceptance"] < 0.9


def _interval_widths(posterior: dict, result, names) -> list[float]:
    """Each credible interval's width over the width the fit's standard error gives it."""
    intervals = posterior["credible_intervals"]
    return [
        (intervals[name]["high"] - intervals[name]["low"])
        / (2 * 1.96 * result.parameters[name].stderr)
        for name in names
    ]


def test_the_posterior_of_correlated_errors_is_as_wide_as_the_standard_errors() -> None:
    """Tracking errors that last several frames (AR(1), rho = 0.7, as a blurred or textured
    outline makes them): the fit widens its standard errors for them, and the posterior's
    likelihood is that AR(1) process's, so its 95 % intervals agree with them. With white
    errors of the same size the intervals would be about sqrt((1 - rho)/(1 + rho)) = 0.42 of
    that: too narrow."""
    import dataclasses

    t, x, _ = recording(DAMPED, duration=3.0, fps=30, noise=0.0)
    rng = np.random.default_rng(5)
    rho, sigma = 0.7, 1e-3
    noise = np.zeros_like(x)
    noise[0] = rng.normal(0.0, sigma, 2)
    for j in range(1, t.size):  # stationary AR(1) of standard deviation sigma
        noise[j] = rho * noise[j - 1] + rng.normal(0.0, sigma * math.sqrt(1 - rho**2), 2)
    data = match_bodies(parse_data(_csv_text(t, x + noise), "ar.csv"), load_system("hoop-cylinder"))
    result = rollspring.fit(data, DAMPED.system(), FREE, claims=False)
    assert result.rho == pytest.approx(rho, abs=0.15)
    posterior = sample_posterior(result, steps=200, seed=3).to_dict()
    for ratio in _interval_widths(posterior, result, FREE):
        assert ratio == pytest.approx(1.0, rel=0.35)
    white = sample_posterior(dataclasses.replace(result, rho=0.0), steps=200, seed=3).to_dict()
    for ratio in _interval_widths(white, result, FREE):
        assert ratio < 0.65


def test_the_posterior_carries_the_errors_locked_to_the_positions() -> None:
    """A recording with a measure of the error locked to each body's position (``track``'s
    ``xlocked`` columns, here 2, 1 and 1 mm of P1-P3 for both bodies): it does not
    average down, the fit adds its share to the covariance, and the posterior adds it to the
    chain, so that both give the same intervals; without it the posterior is narrower."""
    import dataclasses

    t, x, _ = recording(UNDAMPED, duration=3.0, fps=30, seed=11, noise=1e-4)
    text = _csv_text(t, x)
    data = match_bodies(parse_data(text, "locked.csv"), load_system("hoop-cylinder"))
    data = dataclasses.replace(
        data, locked_error=np.array([[2e-3, 1e-3, 1e-3], [2e-3, 1e-3, 1e-3]])
    )
    result = rollspring.fit(data, UNDAMPED.system(), ["springs.0.stiffness"], claims=False)
    assert result.locked is not None and result.locked[0, 0] > 0
    share = result.locked[0, 0] / result.covariance[0, 0]
    assert share > 0.5  # the locked errors dominate the stiffness's error here
    posterior = sample_posterior(result, steps=200, seed=4).to_dict()
    [ratio] = _interval_widths(posterior, result, ["springs.0.stiffness"])
    assert ratio == pytest.approx(1.0, rel=0.25)
    plain = sample_posterior(dataclasses.replace(result, locked=None), steps=200, seed=4)
    [narrow] = _interval_widths(plain.to_dict(), result, ["springs.0.stiffness"])
    assert narrow == pytest.approx(math.sqrt(1 - share), rel=0.25)


def test_the_locked_errors_never_carry_a_sample_outside_the_prior() -> None:
    """A damping near zero (an undamped recording), its error dominated by 5 mm of error
    locked to each position: the draws that would carry a sample below zero are drawn again
    (found by the review of 29 Nov: about half the samples were below zero), so every sample
    and the interval stay within the prior's support, and the interval is wider than without
    the locked errors."""
    import dataclasses

    t, x, _ = recording(UNDAMPED, duration=3.0, fps=30, seed=11, noise=1e-4)
    data = match_bodies(parse_data(_csv_text(t, x), "locked.csv"), load_system("hoop-cylinder"))
    data = dataclasses.replace(data, locked_error=np.full((2, 3), 5e-3))
    result = rollspring.fit(data, UNDAMPED.system(), ["springs.0.damping"], claims=False)
    assert result.parameters["springs.0.damping"].stderr > 5 * result.value("springs.0.damping")
    posterior = sample_posterior(result, steps=200, seed=4)
    damping = posterior.samples[..., result.fitted.index("springs.0.damping")]
    assert np.all(damping >= 0.0)
    plain = sample_posterior(dataclasses.replace(result, locked=None), steps=200, seed=4)
    k = result.fitted.index("springs.0.damping")
    assert posterior.high[k] - posterior.low[k] > 3 * (plain.high[k] - plain.low[k])


def test_paths_that_are_no_number_of_the_system() -> None:
    system = load_system("hoop-cylinder")
    t, x, _ = recording(DAMPED, duration=1.0, fps=30)
    data = match_bodies(parse_data(_csv_text(t, x), "m.csv"), system)
    for path, message in (
        ("springs.3.stiffness", "--free springs.3.stiffness: no spring '3'"),
        ("bodies.wheel.mass", "--free bodies.wheel.mass: no body 'wheel' (bodies: hoop, cylinder)"),
        ("bodies.hoop.shape", "--free bodies.hoop.shape: not a number of the system"),
        ("springs.0.colour", "--free springs.0.colour: not a number of the system (no 'colour')"),
        ("bodies.hoop.x", "--free bodies.hoop.x: the initial state is fitted already"),
    ):
        with pytest.raises(FitError) as caught:
            fit_model(data, system, [path])
        assert message in str(caught.value)


# ------------------------------------------------------------------------------ the command


def _csv_text(t: np.ndarray, x: np.ndarray) -> str:
    rows = [",".join(map(repr, map(float, (ti, *xi)))) for ti, xi in zip(t, x, strict=True)]
    return "\n".join(["t,x_hoop,x_cylinder", *rows]) + "\n"


def test_the_json_contract_and_the_written_outputs(tmp_path: Path) -> None:
    t, x, _ = recording(DAMPED, duration=5.0, fps=30, seed=7)
    data = write_tracker_multi(tmp_path / "tracks.txt", t, x, ("mass A", "mass B"))
    rough = _system_file(tmp_path, DAMPED, k=70.0, c=0.0)
    code, out, err = _cli(
        "fit",
        str(data),
        "--system",
        str(rough),
        "--free",
        FREE[0],
        "--free",
        FREE[1],
        "--map",
        "mass A=hoop",
        "--map",
        "mass B=cylinder",
        "--json",
        "-o",
        str(tmp_path / "fitted.toml"),
        "--figure",
        str(tmp_path / "fit.png"),
    )
    assert code == 0, err
    document = json.loads(out)
    assert document["status"] == "converged"
    names = {
        *FREE,
        "bodies.hoop.x",
        "bodies.cylinder.x",
        "bodies.hoop.v",
        "bodies.cylinder.v",
        "t0",
    }
    assert names <= set(document["parameters"])
    for entry in document["parameters"].values():
        assert {"value", "stderr"} <= set(entry)
    assert set(document["residual_rms"]) == {"hoop", "cylinder"}
    for name in ("cm_peak_to_peak", "stationary_peak_to_peak"):
        assert set(document["claims"][name]) == {"value", "stderr"}
    fitted = load_system(tmp_path / "fitted.toml")
    assert fitted.springs[0].stiffness == pytest.approx(document["parameters"][FREE[0]]["value"])
    assert fitted.bodies[1].x == pytest.approx(document["parameters"]["bodies.cylinder.x"]["value"])
    assert (tmp_path / "fit.png").read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    assert f"wrote {tmp_path / 'fitted.toml'}" in err


def test_the_text_output(tmp_path: Path) -> None:
    t, x, phi = recording(DAMPED, duration=3.0, fps=30, seed=9)
    code, out, _ = _cli(
        "fit",
        str(write_csv(tmp_path / "t.csv", t, x, phi)),
        "--system",
        str(_system_file(tmp_path, DAMPED)),
        "--free",
        FREE[0],
    )
    assert code == 0
    assert "springs.0.stiffness" in out and "cm_peak_to_peak" in out and "hoop rolled" in out


@pytest.mark.parametrize(
    ("text", "args", "message"),
    [
        ("x_hoop\n0\n", (), "error: {data}: no time column"),
        ("t,x_hoop\n0,0\n0.2,0\n0.1,0\n", (), "error: {data}: row 4: the time 0.1 s is earlier"),
        ("t,x_hoop\n0,0\n0,0\n", (), "error: {data}: row 3: the time 0 s repeats"),
        (
            "t,x_hoop\n0,0\n0.1,0\n0.2,0\n",
            (),
            "error: {data}: 3 measured positions, not more than the 5 fitted parameters",
        ),
        ("t,x_wheel\n0,0\n0.1,0\n", (), "error: {data}: column 'x_wheel': no body 'wheel'"),
        (
            "t,x_hoop\n0,0\n0.1,0\n",
            ("--map", "car=hoop"),
            "error: --map car=hoop: {data} has no track",
        ),
        ("t,x_hoop\n0,0\n0.1,0\n", ("--map", "car"), "error: --map car: expected TRACK=BODY"),
        (
            "t,x_hoop\n0,0\n0.1,0\n",
            ("--free", "springs.0.tension"),
            "error: --free springs.0.tension: not a number",
        ),
    ],
)
def test_bad_input_is_one_line_and_exit_2(
    tmp_path: Path, text: str, args: tuple[str, ...], message: str
) -> None:
    data = tmp_path / "data.csv"
    data.write_text(text)
    code, out, err = _cli(
        "fit",
        str(data),
        "--system",
        "hoop-cylinder",
        "--free",
        "springs.0.stiffness",
        *args,
        "-o",
        str(tmp_path / "fitted.toml"),
    )
    assert code == 2
    assert err.startswith(message.format(data=data)) and err.count("\n") == 1
    assert out == "" and not (tmp_path / "fitted.toml").exists()


def test_a_missing_data_file_is_one_line(tmp_path: Path) -> None:
    code, _, err = _cli("fit", str(tmp_path / "none.csv"), "--system", "hoop-cylinder")
    assert code == 2 and err.startswith(f"error: {tmp_path / 'none.csv'}: cannot read")


def test_an_unwritable_figure_is_refused_before_the_fit(tmp_path: Path) -> None:
    t, x, _ = recording(DAMPED, duration=2.0, fps=30)
    data = write_csv(tmp_path / "d.csv", t, x)
    (tmp_path / "folder.png").mkdir()
    code, _, err = _cli(
        "fit",
        str(data),
        "--system",
        "hoop-cylinder",
        "-o",
        str(tmp_path / "f.toml"),
        "--figure",
        str(tmp_path / "folder.png"),
    )
    assert code == 2 and "--figure" in err and not (tmp_path / "f.toml").exists()


def test_no_convergence_is_exit_1_with_the_best_values(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.setattr(fit_module, "MAX_EVALUATIONS_PER_PARAMETER", 0)  # one evaluation
    t, x, _ = recording(DAMPED, duration=5.0, fps=30, seed=1)
    code, out, err = _cli(
        "fit",
        str(write_csv(tmp_path / "d.csv", t, x)),
        "--system",
        str(_system_file(tmp_path, DAMPED, k=70.0, c=0.0)),
        "--free",
        FREE[0],
        "--free",
        FREE[1],
        "--json",
        "-o",
        str(tmp_path / "best.toml"),
    )
    assert code == 1
    document = json.loads(out)
    assert document["status"] == "not_converged"
    assert math.isfinite(document["parameters"][FREE[0]]["value"])
    assert "error: the fit did not converge within" in err
    assert (tmp_path / "best.toml").exists()


def test_the_notebook_view() -> None:
    t, x, _ = recording(DAMPED, duration=2.0, fps=30)
    data = match_bodies(parse_data(_csv_text(t, x), "m.csv"), load_system("hoop-cylinder"))
    view = rollspring.fit(data, DAMPED.system(), ["springs.0.stiffness"])._repr_html_()
    assert "<table>" in view and "springs.0.stiffness" in view and "data:image/png;base64," in view


def test_a_long_posterior_is_refused_with_its_estimate(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    """On the simulated motion every walker and step is a simulation: above the bound the
    posterior is refused with its estimate (here the bound lowered to 1 ms, the fit's own
    estimate made nothing: tests/test_lab_costs.py checks it), unless --yes."""
    from rollspring.analysis import costs
    from rollspring.lab import costs as lab_costs
    from rollspring.service import fitting

    def nothing(*args: object, **kwargs: object) -> lab_costs.LabCost:
        return lab_costs.LabCost("the fit", 2, 0.0)

    monkeypatch.setattr(lab_costs, "fit_cost", nothing)
    monkeypatch.setattr(fitting, "fit_cost", nothing)

    system = load_system("frictionless")
    run = rollspring.simulate(system, 0.5, n_output=16, rtol=1e-10)
    x = run.x + np.random.default_rng(13).normal(0, 5e-4, run.x.shape)
    header = "t," + ",".join(f"x_{i}" for i in run.ids)
    rows = [",".join(map(repr, map(float, (ti, *xi)))) for ti, xi in zip(run.t, x, strict=True)]
    data = tmp_path / "f.csv"
    data.write_text("\n".join([header, *rows]) + "\n")
    monkeypatch.setattr(costs, "MAX_SECONDS", 1e-3)
    code, out, err = _cli(
        "fit",
        str(data),
        "--system",
        "frictionless",
        "--free",
        "springs.0.stiffness",
        "--posterior",
        "-o",
        str(tmp_path / "fitted.toml"),
    )
    assert code == 2 and out == "" and err.count("\n") == 1
    assert err.startswith("error: the posterior would take about") and "--yes" in err
    assert not (tmp_path / "fitted.toml").exists()


def test_hostile_data_files(tmp_path: Path) -> None:
    """A folder, a FIFO, binary bytes, NUL bytes: one line each, never a hang or a traceback;
    CRLF lines, a BOM and semicolons with decimal commas are read."""
    import os

    fifo = tmp_path / "pipe.csv"
    os.mkfifo(fifo)
    binary = tmp_path / "binary.csv"
    binary.write_bytes(bytes(range(256)) * 4)
    for path, message in (
        (tmp_path, "is a folder, not a data file"),
        (fifo, "is a FIFO (named pipe), not a data file"),
        (binary, "not a text file"),
    ):
        code, out, err = _cli("fit", str(path), "--system", "hoop-cylinder")
        assert code == 2 and out == "" and err.count("\n") == 1 and message in err, err
    text = "\ufefft;x_hoop;x_cylinder\r\n0;0,001;0,49\r\n0,1;0,002;0,488\r\n"
    table = parse_data(text.encode("utf-8").decode("utf-8-sig"), "semi.csv")
    np.testing.assert_array_equal(table.t, [0.0, 0.1])
    np.testing.assert_array_equal(table.x, [[0.001, 0.49], [0.002, 0.488]])


def test_a_path_left_at_its_default_and_the_route_it_takes() -> None:
    """A number the system file leaves out (the model's default, as a coefficient at 0 is left
    out of the JSON form) is a PATH; a rolling resistance, a friction coefficient or a radius
    is fitted on the simulated motion (the exact linear motion leaves it out, or may stop being
    exact when it changes)."""
    from rollspring.lab.fit import linear_route
    from rollspring.lab.parameters import get_value, pinned_json

    system = load_system("hoop-cylinder")
    data = pinned_json(system)
    del data["springs"][0]["damping"]
    assert get_value(data, "springs.0.damping") == 0.0
    assert linear_route(system, ["springs.0.stiffness", "springs.0.damping", "bodies.hoop.mass"])
    for path in ("bodies.hoop.rolling_resistance", "bodies.hoop.mu_static", "bodies.hoop.radius"):
        assert not linear_route(system, [path])
    assert not linear_route(load_system("frictionless"))


@pytest.mark.parametrize("uniform", [True, False])
def test_the_exact_motion_is_the_closed_form(uniform: bool) -> None:
    """e^{Bt} z0 of the damped hoop-cylinder equals the closed form (tests/fit_data.py) to
    rounding, on a video's frames (powers of one step) and at scattered times (one exponential
    each), and the exponential equals SciPy's."""
    import scipy.linalg

    from rollspring.lab.motion import expm, motion_matrix, transition_matrices
    from rollspring.physics import system_arrays

    truth = Truth(c=0.3, x2=0.47, v1=0.02, v2=-0.01)
    arrays = system_arrays(system_from_dict(truth.system()))
    rng = np.random.default_rng(17)
    t = np.arange(900) / 90 if uniform else np.sort(rng.uniform(0, 10, 300))
    b = motion_matrix(arrays)
    z = transition_matrices(b, t) @ np.concatenate([arrays.x0, arrays.v0, [1.0]])
    np.testing.assert_allclose(z[:, :2], truth.positions(t), rtol=0, atol=1e-12)
    for tau in (1 / 60, 1.0, 10.0):
        np.testing.assert_allclose(expm(b * tau), scipy.linalg.expm(b * tau), rtol=0, atol=1e-12)


def test_rolling_resistance_is_fitted_from_a_rough_start() -> None:
    """The hoop rolls on a surface with C_rr = 0.004 (the cylinder on a smooth one), released
    from rest 4 cm compressed; the recording (5 s at 30 fps, 1 mm noise) comes from the
    independent integration of tests/test_rolling_resistance.py. From a stiffness 30 % off and
    no resistance the fit, on the simulated motion, recovers k to 1 % and C_rr to 10 %, each
    within 3 standard errors."""
    from tests.test_rolling_resistance import reference_level_chain

    t = np.arange(150) / 30
    x, _ = reference_level_chain(
        [1.0, 1.0], [1.0, 0.5], [0.004, 0.0], 100.0, 0.5, [0.0, 0.46], t[-1], t
    )
    x = x + np.random.default_rng(5).normal(0, 1e-3, x.shape)
    data = match_bodies(parse_data(_csv_text(t, x), "crr.csv"), load_system("hoop-cylinder"))
    rough = system_from_dict(Truth(x2=0.46).system(k=70.0))
    free = ["springs.0.stiffness", "bodies.hoop.rolling_resistance"]
    result = fit_model(data, rough, free, fix_initial=True)
    assert result.converged and not result.level
    k, c_rr = (result.parameters[name] for name in free)
    assert k.value == pytest.approx(100.0, rel=0.01) and abs(k.value - 100.0) <= 3 * k.stderr
    assert (
        c_rr.value == pytest.approx(0.004, rel=0.1) and abs(c_rr.value - 0.004) <= 3 * c_rr.stderr
    )


def test_a_held_start_is_found_on_the_first_swing_not_a_period_early(tmp_path: Path) -> None:
    """With ``fix_initial`` the data's start time t0 is scanned over a period each way on the
    linearised model, which is periodic: t0 = 0 and t0 = -T tie. The scan took -T first, and a
    resisted fit from C_rr = 0.001 settled there (C_rr 0.0014 for 0.002, t0 = -0.58 s, the
    residuals not noise). Ties now go to the nearer start: the release at the data's first
    frame, C_rr to 10 % and within 3 standard errors."""
    from rollspring.lab.synthetic import exact_motion

    def system(c_rr: float) -> dict[str, object]:
        data = Truth(x2=0.49).system()
        for entry in data["bodies"]:  # type: ignore[attr-defined]
            entry["rolling_resistance"] = c_rr
        return data

    truth = system_from_dict(system(0.002))
    t = np.arange(60) / 30.0  # 2 s at 30 fps
    x = exact_motion(truth, t).x + np.random.default_rng(3).normal(0.0, 4e-5, (t.size, 2))
    free = ["bodies.hoop.rolling_resistance", "bodies.cylinder.rolling_resistance"]
    result = rollspring.fit(
        write_csv(tmp_path / "resisted.csv", t, x), system(0.001), free=free, fix_initial=True
    )
    assert result.converged
    for path in free:
        fitted = result.parameters[path]
        assert abs(fitted.value - 0.002) <= min(2e-4, 3 * fitted.stderr), (path, fitted)
    period = 2 * math.pi / math.sqrt(100.0 * (1 / 2 + 2 / 3))
    assert abs(result.parameters["t0"].value) < 0.01 * period
    assert not result.warnings

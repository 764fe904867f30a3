"""The lab's cost guard (rollspring.lab.costs): ``track`` and ``fit`` estimated before any work,
refused above the bound with the estimate in one line unless ``--yes`` / ``confirm=True``,
nothing written when refused; the fit's progress on the simulated motion; the web's fit refused
with 503 when estimated beyond the server's time budget.

No long video exists here: the 2-hour 4K video is two frames whose AVI header claims 432 000,
and the short synthetic video is made expensive by raising the per-pixel constant."""

from __future__ import annotations

import itertools
import math
from pathlib import Path
from typing import Any

import numpy as np
import pytest
from typer.testing import CliRunner

import rollspring
from rollspring.analysis import costs as guard
from rollspring.cli import app
from rollspring.errors import CostTooHigh, TrackingError
from rollspring.lab import costs
from rollspring.lab.costs import VideoHeader, fit_cost, tracked_frames, tracking_cost
from rollspring.lab.data import match_bodies, parse_data
from rollspring.lab.synthetic import Camera, exact_motion, write_video
from rollspring.model import load_system, system_to_json
from rollspring.service import tracking as service_tracking
from rollspring.simulate.costs import simulation_cost
from tests.conftest import moving_hoop_cylinder
from tests.fit_data import Truth, recording, write_csv

runner = CliRunner()

#: two hours of 4K at 60 fps, as its header says
FOUR_K = VideoHeader(frames=432_000, fps=60.0, width=3840, height=2160)


def _cli(*args: str) -> tuple[int, str, str]:
    result = runner.invoke(app, list(args))
    return result.exit_code, result.stdout, result.stderr


@pytest.fixture(scope="module")
def video(tmp_path_factory: pytest.TempPathFactory) -> Path:
    """Half a second of the paper's hoop and cylinder, both rolling, 640×360 at 30 fps."""
    system = moving_hoop_cylinder()
    camera = Camera(fps=30, roll_deg=2.0, noise=4.0, blur=1.0, seed=1)
    motion = exact_motion(system, camera.frame_times(0.5))
    return write_video(tmp_path_factory.mktemp("video") / "short.mp4", system, motion, camera)


# ----------------------------------------------------------------------------- the estimates


def test_the_tracking_estimate_is_its_formula() -> None:
    """t = N_skip P c_decode + N (t_frame + P (c_track + c_overlay)); memory P b_pixel +
    N (b_frame + n b_body); the frames from --from to --to at the header's frame rate."""
    pixels = 3840.0 * 2160.0
    assert tracked_frames(FOUR_K) == (0, 432_000)
    assert tracked_frames(FOUR_K, 10.0, 20.0) == (600, 601)  # frames 600 … 1200
    assert tracked_frames(FOUR_K, 9000.0) == (432_000, 0)  # past the end
    assert tracked_frames(VideoHeader(100, 0.0, 64, 48), 1.0, 2.0) == (0, 100)  # no frame rate
    cost = tracking_cost(FOUR_K, 2, start=10.0, stop=20.0, overlay=True)
    per_pixel = costs._TRACK_PER_PIXEL + costs._OVERLAY_PER_PIXEL
    expected = 600 * pixels * costs._DECODE_PER_PIXEL + 601 * (
        costs._TRACK_PER_FRAME + pixels * per_pixel
    )
    assert cost.seconds == pytest.approx(expected, rel=1e-12)
    memory = pixels * costs._BYTES_PER_PIXEL + 601 * (
        costs._BYTES_PER_FRAME + 2 * costs._BYTES_PER_BODY_FRAME
    )
    assert cost.memory == pytest.approx(memory, rel=1e-12)
    whole = tracking_cost(FOUR_K, 2)
    assert whole.seconds > guard.MAX_SECONDS  # hours, not minutes
    assert "432000 frames of 3840×2160 px × 2 bodies" in whole.describe()


def test_a_video_without_a_frame_count_is_counted() -> None:
    """A header without a count: the frames are grabbed until the end (an exact count) or for
    at most COUNT_SECONDS (a lower bound: "at least", counted as above the bound)."""

    class Capture:
        def __init__(self, frames: float) -> None:
            self.left = frames

        def grab(self) -> bool:
            self.left -= 1
            return self.left >= 0

    assert costs._count_frames(Capture(37), 10.0) == (37, True)
    counted, complete = costs._count_frames(Capture(math.inf), 0.0)  # never ends: cut short
    assert counted == 16 and not complete
    header = VideoHeader(counted, 30.0, 640, 360, counted=True, complete=False)
    cost = tracking_cost(header, 2)
    assert cost.seconds >= 2 * guard.MAX_SECONDS and cost.lower_bound
    line = cost.describe()
    assert line.startswith("at least") and "more than 16 frames" in line
    assert "the header gives no frame count" in line
    with pytest.raises(CostTooHigh, match="confirm it with --yes"):
        guard.check_cost(cost, confirmed=False)


def test_a_raw_stream_is_counted(tmp_path: Path) -> None:
    """A raw MJPEG stream has no container: OpenCV reports a meaningless (negative) frame
    count, and the frames are counted instead, to the end."""
    import cv2

    path = tmp_path / "raw.mjpeg"
    writer = cv2.VideoWriter(str(path), cv2.VideoWriter.fourcc(*"MJPG"), 30, (64, 48))
    for i in range(20):
        writer.write(np.full((48, 64, 3), 10 * i, np.uint8))
    writer.release()
    capture = cv2.VideoCapture(str(path))
    assert not capture.get(cv2.CAP_PROP_FRAME_COUNT) > 0  # the header gives no count
    capture.release()
    header = costs.video_header(path)
    assert (header.frames, header.counted, header.complete) == (20, True, True)
    assert (header.width, header.height) == (64, 48)
    line = tracking_cost(header, 2).describe()
    assert line.startswith("about") and "20 frames of 64×48 px" in line
    assert "(counted: the header gives no frame count)" in line


def test_the_header_of_a_real_video(video: Path, tmp_path: Path) -> None:
    header = costs.video_header(video)
    assert (header.frames, header.width, header.height, header.counted) == (16, 640, 360, False)
    assert header.fps == pytest.approx(30.0)
    for path, message in (
        (tmp_path / "none.mp4", "no such file"),
        (tmp_path, "not a regular file"),
    ):
        with pytest.raises(TrackingError, match=message):
            costs.video_header(path)
    empty = tmp_path / "empty.mp4"
    empty.write_bytes(b"")
    with pytest.raises(TrackingError, match="empty file"):
        costs.video_header(empty)


def _table(duration: float, fps: float) -> Any:
    t, x, _ = recording(Truth(c=0.2), duration=duration, fps=fps, seed=4)
    rows = [f"{ti:.17g},{a:.17g},{b:.17g}" for ti, (a, b) in zip(t, x, strict=True)]
    text = "\n".join(["t,x_hoop,x_cylinder", *rows])
    return match_bodies(parse_data(text, "rec.csv"), load_system("hoop-cylinder"))


def test_the_fit_estimate_on_both_routes() -> None:
    """Linear route: t0 + t_scan + c N (2n+1)² E (p+2); simulated: t0 + t_scan + (E (p+2) + p)
    t_sim, t_sim the simulation's own estimate of the recording's span (DOP853 when a damping is
    free); t_scan = c_scan N with t0 fitted (fix_initial), else 0."""
    from rollspring.lab.fit import EXPECTED_ITERATIONS
    from rollspring.lab.motion import SIMULATION_RTOL

    table = _table(6.0, 60.0)
    system = load_system("hoop-cylinder")
    free = ["springs.0.stiffness", "springs.0.damping"]
    linear = fit_cost(table, system, free)
    p = 2 + 4  # the PATHs and each body's x0, v0
    expected = costs._FIT_SETUP + costs._LINEAR_PER_ENTRY * table.t.size * 25 * (
        EXPECTED_ITERATIONS * (p + 2)
    )
    assert linear.seconds == pytest.approx(expected, rel=1e-12)
    assert linear.seconds < 1.0  # tiny: 0.03 s measured
    held_linear = fit_cost(table, system, free, fix_initial=True)  # the PATHs, t0, the offset
    expected = (
        costs._FIT_SETUP
        + costs._T0_SCAN_PER_FRAME * table.t.size
        + costs._LINEAR_PER_ENTRY * table.t.size * 25 * (EXPECTED_ITERATIONS * (2 + 2 + 2))
    )
    assert held_linear.seconds == pytest.approx(expected, rel=1e-12)
    resisted = [*free, "bodies.hoop.rolling_resistance"]
    simulated = fit_cost(table, system, resisted)
    span = float(table.t[-1] - table.t[0])
    one = simulation_cost(
        system, span, rtol=SIMULATION_RTOL, integrator="dop853", outputs=4 * table.t.size
    )
    simulations = EXPECTED_ITERATIONS * (p + 3) + p + 1
    assert simulated.seconds == pytest.approx(costs._FIT_SETUP + simulations * one.seconds)
    assert f"about {simulations} simulations of {span:.3g} s" in simulated.describe()
    # with t0 fitted instead of the initial state: the PATHs, t0 and the offset
    held = fit_cost(table, system, resisted, fix_initial=True)
    assert f"× {3 + 2} fitted parameters" in held.describe()
    # a longer recording costs more, in proportion on the simulated route
    assert fit_cost(_table(24.0, 60.0), system, resisted).seconds > 3 * simulated.seconds


# ------------------------------------------------------------------------------- track refused


def _claiming(path: Path, frames: int) -> Path:
    """Two black 3840×2160 frames at 60 fps (an MJPEG AVI of 250 kB) whose header claims
    ``frames`` frames: the main header's total (avih) and the stream's length (strh)."""
    import struct

    import cv2

    writer = cv2.VideoWriter(str(path), cv2.VideoWriter.fourcc(*"MJPG"), 60, (3840, 2160))
    for _ in range(2):
        writer.write(np.zeros((2160, 3840, 3), np.uint8))
    writer.release()
    data = bytearray(path.read_bytes())
    struct.pack_into("<I", data, data.find(b"avih") + 8 + 16, frames)  # dwTotalFrames
    struct.pack_into("<I", data, data.find(b"strh") + 8 + 32, frames)  # dwLength
    path.write_bytes(bytes(data))
    return path


@pytest.fixture(scope="module")
def two_hours_4k(tmp_path_factory: pytest.TempPathFactory) -> Path:
    return _claiming(tmp_path_factory.mktemp("4k") / "two-hours-4k.avi", 432_000)


def test_a_two_hour_4k_video_is_refused_at_once(
    two_hours_4k: Path, tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    """The estimate from the header alone (a real file whose header says two hours of 4K at
    60 fps); nothing tracked, nothing written."""

    def never(*args: object, **kwargs: object) -> None:
        raise AssertionError("tracked")

    monkeypatch.setattr(service_tracking, "track_video", never)
    assert costs.video_header(two_hours_4k) == FOUR_K
    out, overlay = tmp_path / "tracks.csv", tmp_path / "overlay.mp4"
    code, stdout, err = _cli(
        "track",
        str(two_hours_4k),
        "--system",
        "hoop-cylinder",
        "-o",
        str(out),
        "--overlay",
        str(overlay),
    )
    assert code == 2 and stdout == "" and err.count("\n") == 1, err
    assert err.startswith("error: tracking would take about ")
    assert "432000 frames of 3840×2160 px × 2 bodies" in err
    assert "--from/--to" in err and err.rstrip().endswith("confirm it with --yes")
    assert list(tmp_path.iterdir()) == []
    with pytest.raises(CostTooHigh, match=r"432000 frames of 3840×2160 px.*confirm=True$"):
        rollspring.track(two_hours_4k, "hoop-cylinder")
    # a minute of it from the middle: the frames before --from decoded only, still too long
    code, _, err = _cli(
        "track", str(two_hours_4k), "-s", "hoop-cylinder", "-o", str(out), "--from", "3600"
    )
    assert code == 2 and "(and 216000 decoded before --from)" in err


def test_yes_lets_it_run(video: Path, tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    """The short video made expensive (its per-pixel cost raised a million times): refused
    without --yes, tracked with it (the tracks written)."""
    monkeypatch.setattr(costs, "_TRACK_PER_PIXEL", costs._TRACK_PER_PIXEL * 1e6)
    out = tmp_path / "tracks.csv"
    args = ["track", str(video), "--system", str(_system_file(tmp_path)), "-o", str(out)]
    code, _, err = _cli(*args)
    assert code == 2 and "16 frames of 640×360 px" in err and "--yes" in err
    assert not out.exists()
    code, _, err = _cli(*args, "--yes")
    assert code == 0, err
    assert "note: tracking will take about" in err  # a long run is announced
    assert out.read_text().startswith("t,x_hoop,phi_hoop,x_cylinder,phi_cylinder")
    assert out.read_text().count("\n") == 17  # the header and 16 frames


def _system_file(folder: Path) -> Path:
    import json

    path = folder.parent / "moving.json"
    path.write_text(json.dumps(system_to_json(moving_hoop_cylinder())), encoding="utf-8")
    return path


def test_confirm_in_python(video: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setattr(costs, "_TRACK_PER_PIXEL", costs._TRACK_PER_PIXEL * 1e6)
    system = moving_hoop_cylinder()
    with pytest.raises(CostTooHigh, match=r"16 frames of 640×360 px.*confirm=True"):
        rollspring.track(video, system)
    result = rollspring.track(video, system, confirm=True)
    assert result.t.size == 16
    with pytest.raises(rollspring.SimulationError, match="confirm: must be True or False"):
        rollspring.track(video, system, confirm="yes")


# --------------------------------------------------------------------------------- fit refused


@pytest.fixture(scope="module")
def off_centre(tmp_path_factory: pytest.TempPathFactory) -> Path:
    """Half a second of the frictionless preset (springs at the percussion points: fitted on
    the simulated motion), 0.5 mm of noise."""
    run = rollspring.simulate(load_system("frictionless"), 0.5, n_output=16, rtol=1e-10)
    x = run.x + np.random.default_rng(13).normal(0, 5e-4, run.x.shape)
    return write_csv(tmp_path_factory.mktemp("fit") / "f.csv", run.t, x)


def test_a_long_fit_is_refused_unless_yes(
    off_centre: Path, tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.setattr(guard, "MAX_SECONDS", 1e-3)
    out, figure = tmp_path / "fitted.toml", tmp_path / "fit.svg"
    args = ["fit", str(off_centre), "--system", "frictionless", "--free", "springs.0.stiffness"]
    args += ["-o", str(out), "--figure", str(figure)]
    code, stdout, err = _cli(*args)
    assert code == 2 and stdout == "" and err.count("\n") == 1, err
    assert err.startswith("error: the fit would take about ")
    assert "simulations of 0.5 s (32 points × 5 fitted parameters" in err
    assert "fewer --free PATHs" in err and "confirm it with --yes" in err
    assert list(tmp_path.iterdir()) == []
    code, _, err = _cli(*args, "--yes")
    assert code == 0, err
    assert out.exists() and figure.exists()


def test_a_long_fit_in_python_needs_confirm(
    off_centre: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.setattr(guard, "MAX_SECONDS", 1e-3)
    free = ["springs.0.stiffness"]
    with pytest.raises(CostTooHigh, match=r"^the fit would take about .*confirm=True$"):
        rollspring.fit(off_centre, "frictionless", free)
    result = rollspring.fit(off_centre, "frictionless", free, confirm=True, claims=False)
    assert not result.level and result.converged


def test_a_linear_fit_is_tiny(monkeypatch: pytest.MonkeyPatch) -> None:
    """The exact linear route is never refused at the bound (its estimate under a second)."""
    table = _table(2.0, 30.0)
    assert fit_cost(table, load_system("hoop-cylinder"), ["springs.0.stiffness"]).seconds < 1
    result = rollspring.fit(table, "hoop-cylinder", ["springs.0.stiffness"], claims=False)
    assert result.level


def test_the_progress_moves_with_each_simulation(off_centre: Path) -> None:
    """On the simulated motion the fraction moves with every evaluation (each a simulation),
    not only at the end: many distinct values between the first guess (0.2) and the end."""
    fractions: list[float] = []
    rollspring.fit(
        off_centre, "frictionless", ["springs.0.stiffness"], claims=False, progress=fractions.append
    )
    assert fractions[-1] == 1.0
    during = [f for f in fractions if 0.2 < f < 0.95]
    assert len(set(during)) >= 20, fractions
    assert all(b >= a for a, b in itertools.pairwise(fractions)), fractions


# ------------------------------------------------------------------------------------ the web


def _resisted_request() -> dict[str, Any]:
    """10 s at 60 fps of the paper's pair fitted with a rolling resistance (simulated route):
    estimated at tens of seconds."""
    from tests.test_web_lab_api import csv_text, rough_start
    from tests.test_web_lab_api import recording as web_recording

    t, x = web_recording()
    system = rough_start()
    system["bodies"][0]["rolling_resistance"] = 0.001
    return {"system": system, "data": csv_text(t, x)}


def test_the_web_fit_job_refuses_beyond_the_budget() -> None:
    """In the worker: estimated before it starts, refused as over budget (the app's 503)."""
    from rollspring.model import System
    from rollspring.service.lab_payloads import BUDGET_MARGIN
    from rollspring.web import jobs

    request = _resisted_request()
    system = System.model_validate(request["system"])
    job = {"system": system, "data": request["data"], "filename": "data.csv", "budget": 1.0}
    table = match_bodies(parse_data(request["data"], "data.csv"), system)
    estimate = fit_cost(table, system, ["springs.0.stiffness", "springs.0.damping"]).seconds
    assert estimate > BUDGET_MARGIN * 1.0
    status, (kind, message, loc) = jobs.execute("fit", job)
    assert (status, kind, loc) == ("error", "over_budget", [])
    assert message.startswith("the fit would take about ")
    assert "beyond the server's time budget of 1 s" in message


def test_the_web_answers_503_before_the_fit_starts() -> None:
    """``rollspring serve`` started from its command line on loopback, a budget of 3 s."""
    from tests.serving import Server

    server = Server("--workers", "1", "--budget", "3")
    try:
        answer = server.post("/api/fit", json=_resisted_request())
    finally:
        server.stop()
    assert answer.status_code == 503, answer.text
    detail = answer.json()["detail"]
    assert detail.startswith("the fit would take about ")
    assert "beyond the server's time budget of 3 s" in detail
    assert "simulations of 9.98 s" in detail


def test_the_web_posterior_is_refused_beyond_what_the_budget_leaves(monkeypatch) -> None:
    """``"posterior": true``: once the fit is done, the posterior's estimate (the fit's time an
    evaluation × walkers × steps) is checked against the budget before any sampling; above
    BUDGET_MARGIN times the budget the job is refused as over budget (the app's 503), naming the
    posterior. (Before, only the fit was estimated and the budget stopped the sampling.)"""
    from rollspring.analysis.costs import Cost
    from rollspring.lab import posterior as posterior_module
    from rollspring.model import System
    from rollspring.web import jobs
    from tests.test_web_lab_api import csv_text, recording, rough_start

    t, x = recording()
    system = System.model_validate(rough_start())
    seen: list[float] = []

    def estimate(result, **_: Any) -> Cost:
        seen.append(result.seconds)
        return Cost(what="the posterior", bodies=2, seconds=3600.0)

    def never(*_: Any, **__: Any) -> None:
        raise AssertionError("sampled although refused")

    monkeypatch.setattr(posterior_module, "posterior_cost", estimate)
    monkeypatch.setattr(posterior_module, "sample_posterior", never)
    job = {
        "system": system,
        "data": csv_text(t, x),
        "filename": "data.csv",
        "budget": 60.0,
        "posterior": True,
    }
    status, (kind, message, loc) = jobs.execute("fit", job)
    assert (status, kind, loc) == ("error", "over_budget", []), message
    assert len(seen) == 1 and seen[0] > 0  # estimated once, from the fit done
    assert message.startswith("the posterior would take about 60 min: 2 bodies after the fit's ")
    assert "beyond the server's time budget of 60 s" in message

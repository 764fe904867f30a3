"""Animations: the bodies turn by the trajectory's angle in the written frames, every format
is written whole (atomically) and offline, every preset animates without warnings, and the
``rollspring animate`` command.

The frame baseline is ``tests/baselines/frame-hoop-cylinder.png``; regenerate it with
``ROLLSPRING_UPDATE_BASELINES=1 .venv/bin/python -m pytest tests/test_animation.py`` (see
``tests/test_figures.py`` for the tolerance).
"""

from __future__ import annotations

import logging
import math
import os
import re
import subprocess
from pathlib import Path

import imageio_ffmpeg
import numpy as np
import pytest
from matplotlib.testing.compare import compare_images
from PIL import Image
from typer.testing import CliRunner

from rollspring.model import load_system, preset_names, system_from_dict
from rollspring.outputs import animation as animation_module
from rollspring.outputs.animation import (
    AnimationError,
    MotionAnimation,
    animation_html,
    frame_times,
    write_animation,
)
from rollspring.outputs.figures import COLORS
from rollspring.simulate import simulate

BASELINES = Path(__file__).parent / "baselines"
TOLERANCE = 2.0
UPDATE = os.environ.get("ROLLSPRING_UPDATE_BASELINES") == "1"
runner = CliRunner()


def run_cli(*args: str):
    from rollspring.cli import app  # here: the animation tests do not need the whole CLI

    return runner.invoke(app, list(args))


@pytest.fixture(scope="module")
def rolling():
    """Hoop and cylinder, the spring compressed by 0.1 m and both sent right at 0.3 m/s: the
    cylinder turns by several radians in 1.2 s. Outputs every 0.04 s, the frame spacing at 25
    fps, so frames fall on output times."""
    system = system_from_dict(
        {
            "bodies": [
                {"id": "hoop", "shape": "hoop", "mass": 1.0, "radius": 0.1, "x": 0.0, "v": 0.3},
                {
                    "id": "cylinder",
                    "shape": "cylinder",
                    "mass": 1.0,
                    "radius": 0.1,
                    "x": 0.4,
                    "v": 0.3,
                },
            ],
            "springs": [{"ends": ["hoop", "cylinder"], "stiffness": 100.0, "rest_length": 0.5}],
        }
    )
    trajectory = simulate(system, 1.2, n_output=31)
    assert trajectory.status == "finished"
    return trajectory


@pytest.fixture(scope="module")
def paper():
    return simulate(load_system("hoop-cylinder"), 1.0, n_output=201)


def _mark_angle(frame: np.ndarray, centre: tuple[float, float], radius: float) -> float:
    """Angle (rad, clockwise from up) of the radius mark around ``centre`` (column, row): the
    mean direction of the mark-coloured pixels between 0.35 and 1.05 radii."""
    rgb = frame[..., :3].astype(float)
    target = np.array([int(COLORS["mark"][k : k + 2], 16) for k in (1, 3, 5)], dtype=float)
    close = np.linalg.norm(rgb - target, axis=-1) < 60
    rows, columns = np.nonzero(close)
    dx, down = columns + 0.5 - centre[0], rows + 0.5 - centre[1]
    distance = np.hypot(dx, down)
    keep = (distance > 0.35 * radius) & (distance < 1.05 * radius)
    assert keep.sum() > 10, "the radius mark was not found"
    return math.atan2(float(np.mean(dx[keep])), -float(np.mean(down[keep])))


def test_gif_frames_show_the_cylinder_turning_by_its_angle(rolling, tmp_path) -> None:
    """Read two frames of the written GIF, find the cylinder's radius mark, and check that it
    turned by the trajectory's delta-phi: the mark's tip moved along the rim by R delta-phi
    (to 1.5 pixels), on top of the centre's own motion."""
    path = write_animation(rolling, tmp_path / "motion.gif", duration=0.6, fps=25, dpi=60)
    # the same layout, to map metres to pixels
    layout = MotionAnimation(rolling, duration=0.6, fps=25, dpi=60)
    assert np.allclose(layout.times, rolling.t[:16])
    with Image.open(path) as gif:
        assert gif.n_frames == 16
        angles, centres = {}, {}
        for k in (2, 14):
            gif.seek(k)
            frame = np.asarray(gif.convert("RGB"))
            x = rolling.x[k, 1]
            centre = layout.pixel(x, 0.1)
            rim = layout.pixel(x + 0.1, 0.1)
            radius = rim[0] - centre[0]
            angles[k] = _mark_angle(frame, centre, radius)
            centres[k] = centre
    turned = rolling.phi[14, 1] - rolling.phi[2, 1]
    assert abs(turned) > 1.0  # a real rotation, not noise
    seen = angles[14] - angles[2]
    seen += 2 * math.pi * round((turned - seen) / (2 * math.pi))  # the same turn, unwrapped
    assert radius * abs(seen - turned) < 1.5, (seen, turned, radius)
    # and the centre moved by delta-x = R delta-phi (rolling without slipping)
    moved = centres[14][0] - centres[2][0]
    assert moved == pytest.approx(radius * turned, abs=0.5)


def test_frame_matches_baseline(paper, tmp_path) -> None:
    animation = MotionAnimation(paper, fps=25, dpi=50)
    frame = animation.render(10)
    actual = tmp_path / "frame-hoop-cylinder.png"
    Image.fromarray(frame).save(actual)
    expected = BASELINES / "frame-hoop-cylinder.png"
    if UPDATE:
        expected.write_bytes(actual.read_bytes())
    assert expected.exists(), "no baseline; see the module docstring"
    result = compare_images(str(expected), str(actual), tol=TOLERANCE)
    assert result is None, f"{result} (see {tmp_path})"


def test_clock_shows_the_frame_time(paper) -> None:
    animation = MotionAnimation(paper, speed=0.5, fps=20, dpi=30)
    animation.update(7)
    assert animation.scene.clock.get_text() == f"t = {7 * 0.5 / 20:7.3f} s"


def test_clock_line_names_the_slipping_body() -> None:
    """Stick-slip (the hoop needs mu 0.047 here, it has 0.03): while the hoop slips the line
    above the clock says so, with the latest event."""
    data = load_system("hoop-cylinder").model_dump()
    data["bodies"][0]["v"] = 0.1
    data["bodies"][1]["x"] = 0.5
    for body in data["bodies"]:
        body["mu_static"] = 0.03
    trajectory = simulate(system_from_dict(data), 0.3, n_output=61, on_slip="continue")
    slip = trajectory.summary["first_slip"]
    assert slip["body"] == "hoop" and 0.04 < slip["time"] < 0.12
    animation = MotionAnimation(trajectory, fps=25, dpi=30)
    animation.update(0)
    assert animation.scene.note.get_text() == ""
    k = int(np.searchsorted(animation.times, slip["time"])) + 1  # the first frame after it
    assert trajectory.slipping[np.searchsorted(trajectory.t, animation.times[k]) - 1, 0]
    animation.update(k)
    assert animation.scene.note.get_text().startswith("slipping: hoop")


def test_mp4_has_every_frame(paper, tmp_path) -> None:
    path = write_animation(paper, tmp_path / "motion.mp4", duration=0.4, fps=25, dpi=40)
    assert imageio_ffmpeg.count_frames_and_secs(str(path)) == (11, pytest.approx(0.44))
    width, height = MotionAnimation(paper, fps=25, dpi=40).size
    width, height = width + (-width % 16), height + (-height % 16)  # padded to macro blocks
    decoded = subprocess.run(
        [
            imageio_ffmpeg.get_ffmpeg_exe(),
            "-v",
            "error",
            "-i",
            str(path),
            "-f",
            "rawvideo",
            "-pix_fmt",
            "rgb24",
            "-",
        ],
        capture_output=True,
        check=True,
    ).stdout
    frames = np.frombuffer(decoded, np.uint8).reshape(-1, height, width, 3)
    assert len(frames) == 11  # 0, 0.04, ..., 0.4 s
    assert not np.array_equal(frames[0], frames[-1])
    assert [p.name for p in tmp_path.iterdir()] == ["motion.mp4"]  # no temporary left


def test_html_is_self_contained_and_deterministic(paper, tmp_path) -> None:
    markup = animation_html(paper, duration=0.2, fps=10, dpi=30)
    assert markup.count("data:image/png;base64,") == 3  # 0, 0.1, 0.2 s
    assert "http" not in markup and "font-awesome" not in markup and "fa fa-" not in markup
    assert "<script" in markup and "\u25b6" in markup  # the player, with Unicode play buttons
    assert animation_html(paper, duration=0.2, fps=10, dpi=30) == markup
    page = write_animation(paper, tmp_path / "motion.html", duration=0.2, fps=10, dpi=30)
    text = page.read_text(encoding="utf-8")
    assert text.startswith("<!DOCTYPE html>") and markup in text


@pytest.mark.parametrize("suffix", [".gif", ".mp4"])
def test_a_failed_render_leaves_nothing_behind(paper, tmp_path, monkeypatch, suffix) -> None:
    target = tmp_path / f"motion{suffix}"
    target.write_bytes(b"previous")
    original = MotionAnimation.render

    def failing(self, i):
        if i == 3:
            raise RuntimeError("boom")
        return original(self, i)

    monkeypatch.setattr(MotionAnimation, "render", failing)
    with pytest.raises(RuntimeError, match="boom"):
        write_animation(paper, target, duration=0.4, fps=25, dpi=30)
    assert target.read_bytes() == b"previous"
    assert [p.name for p in tmp_path.iterdir()] == [target.name]


def test_progress_reaches_one(paper, tmp_path) -> None:
    seen: list[float] = []
    write_animation(paper, tmp_path / "m.gif", duration=0.3, fps=10, dpi=30, progress=seen.append)
    assert seen == pytest.approx([0.25, 0.5, 0.75, 1.0])


def test_frame_times(paper) -> None:
    times = frame_times(paper, speed=0.5, fps=10)
    assert times.size == 21 and times[-1] == pytest.approx(1.0)
    np.testing.assert_allclose(np.diff(times), 0.05)
    assert frame_times(paper, duration=0.3, fps=10).size == 4
    assert frame_times(paper, duration=50.0, fps=10)[-1] == pytest.approx(1.0)  # at most the run


@pytest.mark.parametrize(
    ("options", "message"),
    [
        ({"speed": 0.0}, "speed: must be a number > 0"),
        ({"fps": 2.5}, "fps: must be a whole number"),
        ({"fps": 500}, "fps: must be a whole number > 0 up to 120"),
        ({"duration": -1.0}, "duration: must be a number > 0"),
        ({"speed": 1e-4}, "at most 10000"),
    ],
)
def test_bad_options_are_refused(paper, options, message) -> None:
    with pytest.raises(AnimationError, match=re.escape(message)):
        frame_times(paper, **options)


def test_unknown_format_is_refused(paper, tmp_path) -> None:
    with pytest.raises(AnimationError, match=r"unknown animation format '\.avi'"):
        write_animation(paper, tmp_path / "motion.avi")


@pytest.mark.parametrize("name", preset_names())
def test_every_preset_animates_without_warnings(name, caplog) -> None:
    trajectory = simulate(load_system(name), 0.2, n_output=21)
    with caplog.at_level(logging.WARNING):
        animation = MotionAnimation(trajectory, fps=10, dpi=30)
        frames = list(animation.frames())
    assert len(frames) == 3
    assert all(frame.shape == frames[0].shape for frame in frames)
    assert [r.getMessage() for r in caplog.records if r.levelno >= logging.WARNING] == []


# -- the command -------------------------------------------------------------------------------


def test_animate_command_writes_a_gif(tmp_path) -> None:
    target = tmp_path / "out" / "motion.gif"
    result = run_cli(
        "animate", "hoop-cylinder", "-o", str(target), "-T", "0.1", "--dpi", "30", "--speed", "0.5"
    )
    assert result.exit_code == 0, result.output
    with Image.open(target) as gif:
        assert gif.n_frames == 6  # 0.1 s at half speed, 25 fps
    assert "wrote" in result.stderr and result.stdout == ""


@pytest.mark.parametrize(
    ("args", "option"),
    [
        (["-o", "motion.avi"], "--out"),
        (["-o", "motion"], "--out"),
        ([], "--out/-o is required"),
        (["-o", "m.gif", "--duration", "0"], "--duration"),
        (["-o", "m.gif", "--speed", "-1"], "--speed"),
        (["-o", "m.gif", "--fps", "0"], "--fps"),
        (["-o", "m.gif", "--dpi", "5"], "--dpi"),
        (["-o", "m.gif", "--on-slip", "later"], "--on-slip"),
        (["-o", "m.gif", "-T", "1000", "--speed", "0.01"], "--duration"),
    ],
)
def test_animate_command_errors_name_the_option(tmp_path, monkeypatch, args, option) -> None:
    monkeypatch.chdir(tmp_path)
    result = run_cli("animate", "hoop-cylinder", *args)
    assert result.exit_code == 2
    lines = result.stderr.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("error: ") and option in lines[0]
    assert not any(tmp_path.iterdir())


def test_module_lists_its_formats() -> None:
    assert set(animation_module.FORMATS.values()) == {"gif", "mp4", "html"}


def test_a_long_chain_is_animated_with_its_friction_pattern(tmp_path) -> None:
    """More than LONG_CHAIN bodies: a ChainAnimation. Each frame's points and strip show the
    friction ratio f/(μs N) of that time, the energy centroid line sits at X_E(t), and the
    pattern travels: the strongest friction moves by about v_g Δt."""
    from rollspring.analysis.waves import travelling_wave
    from rollspring.model.chains import chain
    from rollspring.outputs.animation import ChainAnimation
    from rollspring.outputs.figures import signed_friction_ratio

    system = chain("hoop", 80, spacing=0.5, packet=(2.0, 3.0), walls="both")
    run = simulate(system, 4.0, n_output=81)
    waves = travelling_wave(system, run.t, run.x, run.v)
    animation = ChainAnimation(run, waves=waves, fps=5, dpi=40)
    assert len(animation) == 21
    ratio = signed_friction_ratio(run)
    last = len(animation) - 1
    for i in (0, last):
        animation.update(i)
        row = int(np.searchsorted(run.t, animation.times[i]))
        assert np.allclose(animation._points.get_array(), ratio[row])
        assert animation._centroid is not None
        assert animation._centroid.get_xdata()[0] == pytest.approx(waves.centroid[row])
    moved = waves.centroid[-1] - waves.centroid[0]
    assert moved == pytest.approx(waves.group_velocity * 4.0, rel=0.1)
    frame = animation.render(last)
    assert frame.shape == (*animation.size[::-1], 4)
    target = write_animation(run, tmp_path / "chain.gif", waves=waves, fps=2, dpi=40)
    with Image.open(target) as gif:
        assert gif.n_frames == 9

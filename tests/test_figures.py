r"""Figures: pixels against committed baselines, every preset without warnings, and the numbers
drawn are the results' own.

Image baselines are small PNGs in ``tests/baselines/`` rendered at ``BASELINE_DPI``; a figure
matches when the RMS difference of its pixels (0-255 scale, Matplotlib's ``compare_images``) is
below ``TOLERANCE``: a font-rendering change of a pixel here and there passes, a moved body, a
missing arrow or another layout does not. On a mismatch the rendered image and a difference
image are left in pytest's temporary directory (the failure message names them).

After an intended change of the drawings, regenerate the baselines, look at them, and commit::

    ROLLSPRING_UPDATE_BASELINES=1 .venv/bin/python -m pytest \
        tests/test_figures.py tests/test_animation.py

(``tests/baselines/README.md`` says the same.)
"""

from __future__ import annotations

import io
import logging
import math
import re
from pathlib import Path

import matplotlib
import numpy as np
import pytest
from matplotlib.testing.compare import compare_images
from PIL import Image

from rollspring.analysis import analyze
from rollspring.model import load_system, preset_names, system_from_dict
from rollspring.outputs import figures
from rollspring.outputs.figures import (
    COLORS,
    figure_png,
    figure_svg,
    new_figure,
    plot_contact_forces,
    plot_energy,
    plot_friction_ratio,
    plot_modes,
    plot_phase_portraits,
    plot_positions,
    plot_system,
)
from rollspring.simulate import simulate
from tests.image_baselines import BASELINES, TOLERANCE, check_against_baseline

BASELINE_DPI = 50

#: Every shape, a wall, a raised track, off-centre and height attachments, an applied force.
GALLERY = {
    "name": "Gallery: every shape, a wall, a raised track, off-centre springs, a pull",
    "anchors": [{"id": "wall", "x": -0.4, "y": 0.2}],
    "bodies": [
        {"id": "hoop", "shape": "hoop", "mass": 1.0, "radius": 0.1, "x": 0.0, "track_height": 0.05},
        {"id": "sphere", "shape": "sphere", "mass": 1.0, "radius": 0.08, "x": 0.45},
        {"id": "shell", "shape": "shell", "mass": 0.8, "radius": 0.09, "x": 0.9},
        {
            "id": "wheel",
            "shape": "custom",
            "inertia_factor": 0.3,
            "mass": 1.2,
            "radius": 0.1,
            "x": 1.35,
        },
        {"id": "block", "shape": "slider", "mass": 0.5, "radius": 0.05, "x": 1.8},
    ],
    "springs": [
        {
            "ends": ["wall", "hoop"],
            "stiffness": 80.0,
            "at": [{}, {"height": 0.2}],
            "rest_length": 0.42,
        },
        {
            "ends": ["hoop", "sphere"],
            "stiffness": 100.0,
            "at": [{"radius": 0.06, "angle": 90.0}, {}],
        },
        {"ends": ["sphere", "shell"], "stiffness": 100.0},
        {"ends": ["shell", "wheel"], "stiffness": 120.0, "at": [{}, {"height": 0.15}]},
        {"ends": ["wheel", "block"], "stiffness": 60.0},
    ],
    "forces": [{"body": "wheel", "at": {"height": 0.18}, "fx": 1.0}],
}


@pytest.fixture(scope="module")
def paper():
    """The paper's Fig. 2 system, its analysis and 2 s of motion."""
    system = load_system("hoop-cylinder")
    return system, analyze(system), simulate(system, 2.0, n_output=401)


@pytest.fixture(scope="module")
def gallery():
    system = system_from_dict(GALLERY)
    return system, analyze(system), simulate(system, 2.0, n_output=401)


@pytest.fixture(scope="module")
def slipping():
    """The paper's hoop and cylinder released at the spring's rest length, the hoop pushed
    towards the cylinder, mu_s = 0.03: the friction needed grows from 0 with the compression
    until the hoop (which needs 3/2 of the cylinder's friction, paper App. A) slips."""
    data = load_system("hoop-cylinder").model_dump()
    data["bodies"][0]["v"] = 0.1
    data["bodies"][1]["x"] = 0.5
    for body in data["bodies"]:
        body["mu_static"] = 0.03
    return simulate(system_from_dict(data), 1.0, n_output=401, on_slip="continue")


def check_baseline(fig, name: str, tmp_path: Path) -> None:
    """Compare ``fig`` at BASELINE_DPI with ``tests/baselines/<name>.png`` (or write it)."""
    actual = tmp_path / f"{name}.png"
    actual.write_bytes(figure_png(fig, dpi=BASELINE_DPI))
    check_against_baseline(actual, name, __file__)


# -- baselines --------------------------------------------------------------------------------


def test_system_diagram_matches_baseline(paper, tmp_path) -> None:
    system, _, _ = paper
    check_baseline(plot_system(system).figure, "system-hoop-cylinder", tmp_path)


def test_gallery_diagram_matches_baseline(gallery, tmp_path) -> None:
    """Hoop, sphere, shell, custom body (radius of gyration dashed), slider block, hatched
    wall and raised track, off-centre springs."""
    system, _, _ = gallery
    check_baseline(plot_system(system).figure, "system-gallery", tmp_path)


def test_snapshot_with_forces_matches_baseline(gallery, tmp_path) -> None:
    _, _, trajectory = gallery
    ax = plot_system(trajectory, time=0.5, forces=True)
    check_baseline(ax.figure, "snapshot-gallery", tmp_path)


def test_equilibrium_with_forces_matches_baseline(gallery, tmp_path) -> None:
    _, analysis, _ = gallery
    ax = plot_system(analysis, at="equilibrium", forces=True)
    check_baseline(ax.figure, "equilibrium-gallery", tmp_path)


def test_modes_match_baseline(paper, tmp_path) -> None:
    _, analysis, _ = paper
    check_baseline(plot_modes(analysis), "modes-hoop-cylinder", tmp_path)


def test_positions_match_baseline(paper, tmp_path) -> None:
    _, _, trajectory = paper
    check_baseline(plot_positions(trajectory).figure, "positions-hoop-cylinder", tmp_path)


def test_contact_forces_match_baseline(paper, tmp_path) -> None:
    _, _, trajectory = paper
    check_baseline(plot_contact_forces(trajectory), "contact-hoop-cylinder", tmp_path)


def test_friction_ratio_with_slip_matches_baseline(slipping, tmp_path) -> None:
    check_baseline(plot_friction_ratio(slipping).figure, "ratio-slip", tmp_path)


def test_energy_matches_baseline(paper, tmp_path) -> None:
    _, _, trajectory = paper
    check_baseline(plot_energy(trajectory).figure, "energy-hoop-cylinder", tmp_path)


def test_phase_portraits_match_baseline(gallery, tmp_path) -> None:
    _, _, trajectory = gallery
    check_baseline(plot_phase_portraits(trajectory), "phase-gallery", tmp_path)


def test_a_changed_figure_fails_its_baseline(paper, tmp_path) -> None:
    """The comparison sees a change: the hoop drawn as a cylinder (same size) fails."""
    system, _, _ = paper
    data = system.model_dump()
    data["bodies"][0]["shape"] = "cylinder"
    moved = plot_system(system_from_dict(data)).figure
    expected = BASELINES / "system-hoop-cylinder.png"
    actual = tmp_path / "moved.png"
    actual.write_bytes(figure_png(moved, dpi=BASELINE_DPI))
    result = compare_images(str(expected), str(actual), tol=TOLERANCE)
    assert result is not None and "RMS" in result


# -- every preset, no warnings ---------------------------------------------------------------


@pytest.mark.parametrize("name", preset_names())
def test_every_figure_of_every_preset_renders_without_warnings(name, caplog) -> None:
    """pytest turns warnings into errors (filterwarnings = error); Matplotlib's logged
    warnings are checked here too."""
    system = load_system(name)
    analysis = analyze(system)
    trajectory = simulate(system, 1.0, n_output=201)
    with caplog.at_level(logging.WARNING):
        made = [
            plot_system(system).figure,
            plot_system(analysis, at="equilibrium", forces=True).figure,
            plot_system(trajectory, time=0.5, forces=True).figure,
            plot_positions(trajectory).figure,
            plot_contact_forces(trajectory),
            plot_friction_ratio(trajectory).figure,
            plot_energy(trajectory).figure,
            plot_phase_portraits(trajectory),
            plot_modes(analysis),
        ]
        for fig in made:
            pixels = np.asarray(Image.open(io.BytesIO(figure_png(fig, dpi=30))))
            width, height = fig.get_size_inches() * 30
            assert abs(pixels.shape[0] - height) <= 1 and abs(pixels.shape[1] - width) <= 1
            assert np.mean(pixels[..., :3] < 128) > 0.005  # something dark is drawn
    assert [r.getMessage() for r in caplog.records if r.levelno >= logging.WARNING] == []


# -- the numbers drawn are the results' own ---------------------------------------------------


def test_bodies_are_drawn_where_the_trajectory_puts_them(paper) -> None:
    """Radius mark from (x, h + R) to (x + R sin(phi), h + R + R cos(phi)), docs/physics.md (M1),
    at an output time of the trajectory."""
    _, _, trajectory = paper
    k = 150
    ax = plot_system(trajectory, time=float(trajectory.t[k]))
    marks = [line for line in ax.lines if line.get_color() == COLORS["mark"]]
    assert len(marks) == 2
    for i, mark in enumerate(marks):
        x, phi, radius = trajectory.x[k, i], trajectory.phi[k, i], 0.1
        np.testing.assert_allclose(mark.get_xdata(), [x, x + radius * math.sin(phi)], atol=1e-12)
        np.testing.assert_allclose(
            mark.get_ydata(), [radius, radius + radius * math.cos(phi)], atol=1e-12
        )


def test_cm_and_stationary_point_markers_sit_at_their_values(paper) -> None:
    _system, analysis, _ = paper
    ax = plot_system(analysis)
    cm = next(
        line for line in ax.lines if line.get_marker() == "^" and line.get_color() == COLORS["cm"]
    )
    xhat = next(
        line for line in ax.lines if line.get_marker() == "^" and line.get_color() == COLORS["xhat"]
    )
    assert cm.get_xdata()[0] == pytest.approx((0.0 + 0.49) / 2)  # equal masses
    # paper eq. (c): X-hat = (2 m1 x1 + 1.5 m2 x2) / (2 m1 + 1.5 m2)
    assert xhat.get_xdata()[0] == pytest.approx((2 * 0.0 + 1.5 * 0.49) / 3.5, rel=1e-12)


def test_positions_plot_the_trajectory_displacements(paper) -> None:
    _, _, trajectory = paper
    fig = new_figure(5, 3)
    ax = fig.add_subplot()
    assert plot_positions(trajectory, ax) is ax
    lines = {line.get_label(): line for line in ax.lines}
    np.testing.assert_array_equal(
        lines["cylinder"].get_ydata(), trajectory.x[:, 1] - trajectory.x[0, 1]
    )
    np.testing.assert_array_equal(lines["CM"].get_ydata(), trajectory.cm_x - trajectory.cm_x[0])
    assert np.ptp(lines[r"$\hat{X}$"].get_ydata()) < 1e-12  # X-hat stays put (paper Sec. 2)
    assert np.ptp(lines["CM"].get_ydata()) > 1e-3  # the CM does not


def test_first_slip_is_marked_at_its_time(slipping) -> None:
    ax = plot_friction_ratio(slipping)
    slip = slipping.summary["first_slip"]
    assert slip is not None and slip["body"] == "hoop"
    vertical = [
        line
        for line in ax.lines
        if np.ptp(line.get_xdata()) == 0 and line.get_xdata()[0] == slip["time"]
    ]
    assert vertical, "no line at the slip time"
    assert any(
        f"first slip: hoop, t = {slip['time']:.4g} s" == text.get_text() for text in ax.texts
    )


def test_mode_panels_give_each_frequency(paper) -> None:
    _, analysis, _ = paper
    fig = plot_modes(analysis)
    titles = [ax.get_title(loc="left") for ax in fig.axes]
    assert len(titles) == 2
    omega = math.sqrt(100 / 2 + 2 * 100 / 3)  # paper eq. (QQQ1)
    assert "zero mode" in titles[0]
    assert re.search(rf"{omega:.6g} rad/s", titles[1])


def test_given_axes_and_figures_are_used_and_returned(paper) -> None:
    system, analysis, trajectory = paper
    fig = new_figure(6, 3)
    ax = fig.add_subplot()
    assert plot_system(system, ax) is ax
    for function in (plot_friction_ratio, plot_energy):
        ax = new_figure(6, 3).add_subplot()
        assert function(trajectory, ax) is ax
    for function, result in (
        (plot_contact_forces, trajectory),
        (plot_phase_portraits, trajectory),
        (plot_modes, analysis),
    ):
        fig = new_figure(7, 6)
        assert function(result, fig) is fig


# -- determinism, no global state --------------------------------------------------------------


def test_rendering_is_deterministic(paper) -> None:
    system, _, trajectory = paper
    assert figure_png(plot_system(system).figure) == figure_png(plot_system(system).figure)
    svg = figure_svg(plot_energy(trajectory).figure)
    assert svg == figure_svg(plot_energy(trajectory).figure)
    assert "<dc:date>" not in svg


def test_figures_leave_the_callers_rcparams_alone(paper) -> None:
    _, analysis, trajectory = paper
    with matplotlib.rc_context({"font.size": 17.0, "lines.linewidth": 4.0}):
        before = dict(matplotlib.rcParams)
        fig = plot_modes(analysis)
        figure_png(fig)
        plot_contact_forces(trajectory)
        assert dict(matplotlib.rcParams) == before


def test_library_never_uses_pyplot() -> None:
    """Figures are Figure objects with an Agg canvas: no pyplot state, no display needed."""
    package = Path(figures.__file__).parent
    pattern = re.compile(r"matplotlib\.pyplot|from matplotlib import .*pyplot")
    paths = [
        *sorted(package.glob("*.py")),
        *(package.parent / n for n in ("animation.py", "jupyter.py")),
    ]
    assert len(paths) > 3
    for path in paths:
        assert not pattern.search(path.read_text(encoding="utf-8")), path.name


def test_bad_placement_is_refused(paper) -> None:
    _, analysis, _ = paper
    with pytest.raises(ValueError, match="at: must be 'initial' or 'equilibrium'"):
        plot_system(analysis, at="middle")


def test_a_long_chain_is_drawn_as_space_time_images() -> None:
    """plot_space_time: three images over the rest positions and the run's times; the energy
    panel carries the centroid path and the line X_E(0) + v_g t of the waves analysis."""
    from rollspring.analysis.waves import travelling_wave
    from rollspring.model.chains import chain
    from rollspring.outputs.figures import plot_space_time

    system = chain("hoop", 60, packet=(2.0, 3.0), walls="both")
    run = simulate(system, 2.0, n_output=41)
    waves = travelling_wave(system, run.t, run.x, run.v)
    fig = plot_space_time(run, waves)
    images = [ax.images[0] for ax in fig.axes if ax.images]
    assert len(images) == 3
    assert images[0].get_array().shape == (41, 60)
    energy_axes = fig.axes[2]
    centroid, predicted = energy_axes.lines[:2]
    assert np.allclose(centroid.get_xdata(), waves.centroid)
    x_line, t_line = predicted.get_xdata(), predicted.get_ydata()
    slope = (x_line[-1] - x_line[0]) / (t_line[-1] - t_line[0])
    assert slope == pytest.approx(waves.group_velocity, rel=1e-12)
    assert figures.figure_rgba(fig).shape[2] == 4

"""The paper's claims measured on videos filmed against a textured wall (issue 27's acceptance
point): the paper's hoop and cylinder rendered from their exact motion as a camera films them
(a textured wall and table, noise, blur, a 2° roll, flicker, MP4; three parameter sets: a damped
spring, a plain spring, rolling resistance; 30 and 60 fps), tracked (``rollspring.track``) and
fitted (``rollspring.fit``): the tracks recover the rendered motion (centres within 1 mm RMS,
angles within 0.02 rad RMS), the fit from the preset (the stiffness 30 % off, no damping, no
rolling resistance) recovers k within 1 % and the damping or C_rr within 10 %, each within 3
standard errors, and the CM's and X̂'s fitted peak-to-peak are within 3 stated standard errors
of the truth's (24 in 26 recordings within 2), computed from the exact motion the video was
rendered from.

Behind a textured wall the grain shifts each located edge by a few hundredths of a pixel, by
the same amount whenever a body stands at the same place: the tracked swings come out up to
about 1 % too wide or narrow, which the fit cannot see (a wider swing is another initial state).
``track`` measures that error locked to the position (its ``xlocked<m>_<id>`` columns) and the
fit adds it to the standard errors; before a plain wall it stays small. Then the propagation
itself against an exact linear response, and the columns' reading.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

import rollspring
from rollspring.errors import DataError
from rollspring.lab.data import read_data
from rollspring.lab.fit import FitResult
from rollspring.lab.synthetic import Camera, exact_motion, write_video
from rollspring.lab.tracking import TrackResult
from rollspring.model import System, system_to_json


def paper(
    stiffness: float = 100.0, damping: float = 0.0, rolling_resistance: float = 0.0
) -> System:
    """The preset ``hoop-cylinder`` (the paper's Fig. 2, released from rest with the spring
    1 cm short of its rest length) with this spring and rolling resistance C_rr."""
    data = system_to_json(rollspring.load_system("hoop-cylinder"))
    data["springs"][0].update(stiffness=stiffness, damping=damping)
    if rolling_resistance:
        for body in data["bodies"]:
            body["rolling_resistance"] = rolling_resistance
    return rollspring.system_from_dict(data)


def truth_claims(system: System, seconds: float, fps: float) -> tuple[float, float]:
    """The CM's and X̂'s peak-to-peak (m) of the exact motion, sampled as the fit samples its
    model (four times the frames), as ``tools/lab_walkthrough.py`` computes them."""
    frames = round(seconds * fps) + 1
    motion = exact_motion(system, np.linspace(0.0, seconds, 4 * frames))
    masses = np.array([body.mass for body in system.bodies])
    weights = np.asarray(rollspring.analyze(system).stationary_weights)
    return float(np.ptp(motion.x @ masses / masses.sum())), float(np.ptp(motion.x @ weights))


CAMERA = {"roll_deg": 2.0, "noise": 4.0, "blur": 1.0, "flicker": 0.03}
STIFFNESS = "springs.0.stiffness"
RESISTANCES = ["bodies.hoop.rolling_resistance", "bodies.cylinder.rolling_resistance"]
#: name: (the truth, its camera, seconds, the paths freed). Every fit starts from the preset
#: (k = 100 N/m, no damping, no rolling resistance: the stiffness 30 % off, or 43 % for the
#: soft spring), as the README's walk-through does; with rolling resistance the motion is
#: simulated (rests and releases) and each Jacobian column is a simulation. The cameras are the
#: README's (seed 1). Measured over seeds 1 to 5 (1 to 3 with rolling resistance): the CM's and
#: X̂'s peak-to-peak came within 2 stated standard errors of the truth in 24 of 26 cases and
#: within 2.3 in all; this seed is one of the two beyond 2 (the damped case, +2.3), so a single
#: recording is held to 3 standard errors here, as the fit's parameters are.
CASES = {
    "damped-60fps": (
        paper(130.0, 0.2),
        Camera(fps=60, seed=1, **CAMERA),
        3.0,
        [STIFFNESS, "springs.0.damping"],
    ),
    "soft-30fps": (paper(70.0), Camera(fps=30, seed=1, **CAMERA), 4.0, [STIFFNESS]),
    "resisted-30fps": (
        paper(130.0, rolling_resistance=0.002),
        Camera(fps=30, seed=1, **CAMERA),
        2.0,
        [STIFFNESS, *RESISTANCES],
    ),
}


def _within(value: float, stderr: float, truth: float, relative: float) -> None:
    """A fitted value within ``relative`` of the truth and within 3 standard errors of it."""
    assert abs(value - truth) <= relative * abs(truth), (value, truth)
    assert abs(value - truth) <= 3 * stderr, (value, stderr, truth)


@pytest.mark.parametrize("name", list(CASES))
def test_the_claims_measured_on_a_textured_wall(tmp_path: Path, name: str) -> None:
    truth, camera, seconds, free = CASES[name]
    motion = exact_motion(truth, camera.frame_times(seconds))
    video = write_video(tmp_path / f"{name}.mp4", truth, motion, camera)
    tracks = rollspring.track(video, truth)
    assert (np.sqrt(np.mean((tracks.x - motion.x) ** 2, axis=0)) <= 1e-3).all()
    assert (np.sqrt(np.mean((tracks.phi - motion.phi) ** 2, axis=0)) <= 0.02).all()
    # the wall's texture: an error locked to the position of some µm, measured and carried
    assert tracks.locked_error.shape == (2, 3)
    assert (tracks.locked_error[:, 0] > 1e-5).all(), tracks.locked_error
    result = rollspring.fit(tracks, paper(), free=free, confirm=True)
    assert result.converged, result.message
    spring = truth.springs[0]
    fitted = result.parameters
    _within(fitted[STIFFNESS].value, fitted[STIFFNESS].stderr, spring.stiffness, 0.01)
    if "springs.0.damping" in free:
        damping = fitted["springs.0.damping"]
        _within(damping.value, damping.stderr, spring.damping, 0.10)
    for path, body in zip(RESISTANCES, truth.bodies, strict=True):
        if path in free:
            _within(fitted[path].value, fitted[path].stderr, body.rolling_resistance, 0.10)
    cm, stationary = truth_claims(truth, seconds, camera.fps)
    for claim, expected in (("cm_peak_to_peak", cm), ("stationary_peak_to_peak", stationary)):
        measured = result.claims[claim]
        off = (measured["value"] - expected) / measured["stderr"]
        assert abs(off) <= 3.0, (claim, measured, expected, off)
    assert cm > 50 * result.claims["cm_peak_to_peak"]["stderr"]  # the claim is measured


def _fit_without_locked(tracks: TrackResult, path: Path) -> FitResult:
    """The fit of ``tracks`` as if ``track`` had not measured the locked error."""
    table = tracks.columns()
    kept = [name for name in table if not name.startswith("xlocked")]
    rows = np.column_stack([table[name] for name in kept])
    lines = [",".join(kept)] + [",".join(f"{v:.17g}" for v in row) for row in rows]
    path.write_text("\n".join(lines) + "\n", encoding="utf-8")
    return rollspring.fit(path, "hoop-cylinder", free=[STIFFNESS, "springs.0.damping"])


def test_a_plain_wall_locks_little(tmp_path: Path) -> None:
    """The same recording as the damped case, filmed against a plain wall: the error locked
    to the position is a fraction of the textured wall's, the claims' standard errors stay
    within 1.4 times the tracking noise's alone, and the claims are measured within two."""
    truth, camera, seconds, free = CASES["damped-60fps"]
    plain = Camera(fps=60, seed=1, texture=False, **CAMERA)
    motion = exact_motion(truth, plain.frame_times(seconds))
    tracks = rollspring.track(write_video(tmp_path / "plain.mp4", truth, motion, plain), truth)
    assert (tracks.locked_error[:, 0] < 8e-6).all(), tracks.locked_error
    result = rollspring.fit(tracks, paper(), free=free)
    bare = _fit_without_locked(tracks, tmp_path / "bare.csv")
    cm, stationary = truth_claims(truth, seconds, camera.fps)
    for claim, expected in (("cm_peak_to_peak", cm), ("stationary_peak_to_peak", stationary)):
        measured = result.claims[claim]
        noise_only = bare.claims[claim]["stderr"]
        assert noise_only <= measured["stderr"] <= 1.4 * noise_only, (claim, measured)
        assert abs(measured["value"] - expected) <= 2.0 * measured["stderr"], (claim, measured)


def test_the_locked_error_propagates_as_the_linear_response(tmp_path: Path) -> None:
    r"""On the exact linear route the fit's estimate moves by :math:`(J^TJ)^{-1}J^Tu` when the
    data move by :math:`u`: the hoop's positions moved by :math:`\epsilon P_m(\tilde x)` (each
    Legendre polynomial of its position over its range) move every fitted value by
    :math:`\epsilon v_m`, and a column ``xlocked<m>_hoop`` of :math:`\sigma` adds
    :math:`\sigma^2 v_m^2` to each squared standard error."""
    from numpy.polynomial import legendre

    truth = paper(130.0, 0.2)
    t = np.arange(241) / 60.0
    motion = exact_motion(truth, t)
    rng = np.random.default_rng(7)
    x = motion.x + rng.normal(0.0, 2e-5, motion.x.shape)
    hoop = x[:, 0]
    scaled = 2.0 * (hoop - hoop.min()) / np.ptp(hoop) - 1.0
    free = [STIFFNESS, "springs.0.damping"]

    def fit(x_table: np.ndarray, locked: tuple[int, float] | None = None) -> FitResult:
        header = ["t", "x_hoop", "x_cylinder"]
        columns = [t, x_table[:, 0], x_table[:, 1]]
        if locked is not None:
            header.append(f"xlocked{locked[0]}_hoop")
            columns.append(np.full(t.size, locked[1]))
        lines = [",".join(header)]
        lines += [",".join(f"{v:.17g}" for v in row) for row in np.column_stack(columns)]
        path = tmp_path / "data.csv"
        path.write_text("\n".join(lines) + "\n", encoding="utf-8")
        return rollspring.fit(path, "hoop-cylinder", free=free)

    base = fit(x)
    problem = base.problem
    jacobian = problem.jacobian(base.best)
    epsilon, sigma = 1e-6, 3e-6
    for m in (1, 2, 3):
        shape = legendre.legvander(scaled, 3)[:, m]
        table = np.zeros((t.size, 2))
        table[:, 0] = shape
        # the least-squares response to moving the data by u: lstsq(J, u)
        response = np.linalg.lstsq(jacobian, table[problem.mask], rcond=None)[0]
        locked = fit(x, (m, sigma))
        for k, name in enumerate(base.fitted):
            added = locked.stderr(name) ** 2 - base.stderr(name) ** 2
            assert added == pytest.approx((sigma * response[k]) ** 2, rel=1e-6), (m, name)
        # and a refit moves so (to its tolerance): the initial positions, linear in the data
        moved = fit(x + epsilon * table)
        for name in ("bodies.hoop.x", "bodies.cylinder.x"):
            k = base.fitted.index(name)
            shift = (moved.value(name) - base.value(name)) / epsilon
            assert shift == pytest.approx(response[k], rel=0.05, abs=1e-3), (m, name)
        # a systematic term widens the standard errors, it never moves the values
        assert locked.value(STIFFNESS) == base.value(STIFFNESS)


def test_the_locked_columns_are_read_and_checked(tmp_path: Path) -> None:
    good = tmp_path / "good.csv"
    good.write_text(
        "t,x_hoop,xlocked1_hoop,xlocked3_hoop,x_cylinder\n0,0,2e-6,1e-6,0.49\n0.1,0.001,2e-6,1e-6,0.5\n"
    )
    recording = read_data(good)
    assert recording.locked_error is not None
    np.testing.assert_array_equal(recording.locked_error, [[2e-6, 0.0, 1e-6], [0.0, 0.0, 0.0]])
    plain = tmp_path / "plain.csv"
    plain.write_text("t,x_hoop\n0,0\n0.1,0.001\n")
    assert read_data(plain).locked_error is None
    cases = [
        ("t,x_hoop,xlocked1_box\n0,0,1e-6\n", "column 'xlocked1_box' has no position column"),
        ("t,x_hoop,xlocked1_hoop\n0,0,1e-6\n0.1,0,2e-6\n", "the same in every row"),
        ("t,x_hoop,xlocked1_hoop\n0,0,-1e-6\n", "must hold one error >= 0"),
        ("t,x_hoop,xlocked4_hoop\n0,0,1e-6\n", "not a data column"),
    ]
    for text, message in cases:
        bad = tmp_path / "bad.csv"
        bad.write_text(text)
        with pytest.raises(DataError, match=message):
            read_data(bad)

"""What the fit says about itself: a model that does not describe the data is told (its
residuals are not noise), one that does is not; and ``rollspring.fit`` takes the tracks
``rollspring.track`` returns as it takes the file they are written to (issue 27)."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

import rollspring
from rollspring.errors import DataError
from rollspring.lab.data import BodyData
from rollspring.lab.fit import fit_model, residual_correlation
from rollspring.lab.tracking import TrackResult
from rollspring.model import system_from_dict
from tests.fit_data import Truth, recording

TRUTH = Truth(k=130.0, c=0.2, v1=0.01)


def _data(t: np.ndarray, x: np.ndarray) -> BodyData:
    return BodyData("seeded", t, ("hoop", "cylinder"), (0, 1), x, np.full_like(x, np.nan))


def test_a_model_that_misses_the_motion_is_told_and_a_right_one_is_not() -> None:
    t, x, _ = recording(TRUTH, duration=3.0, fps=60.0, seed=7)
    data = _data(t, x)
    # k held at the preset's 100 N/m while the data have 130: the fit converges to the best it
    # can, and its residuals follow the missed oscillation
    wrong = fit_model(data, system_from_dict(TRUTH.system(k=100.0)), ["springs.0.damping"])
    assert any("residuals are not noise" in w for w in wrong.warnings), wrong.warnings
    right = fit_model(
        data, system_from_dict(TRUTH.system(k=100.0)), ["springs.0.stiffness", "springs.0.damping"]
    )
    assert not any("residuals are not noise" in w for w in right.warnings), right.warnings
    assert abs(right.parameters["springs.0.stiffness"].value - TRUTH.k) < 0.01 * TRUTH.k


def test_the_residual_correlation_is_zero_for_noise_and_near_one_for_a_smooth_miss() -> None:
    rng = np.random.default_rng(3)
    marked = np.ones((4000, 2), dtype=bool)
    assert residual_correlation(rng.normal(size=(4000, 2)), marked) < 3 / np.sqrt(8000)
    slow = np.sin(np.linspace(0.0, 6.0, 4000))[:, None] * np.ones((1, 2))
    assert residual_correlation(slow, marked) > 0.98
    # unmarked frames break the pairs: a residual next to a gap pairs with nothing
    gaps = marked.copy()
    gaps[::2] = False
    assert residual_correlation(slow, gaps) == 0.0


def _tracks(t: np.ndarray, x: np.ndarray, phi: np.ndarray) -> TrackResult:
    n = t.size
    return TrackResult(
        video="film.mp4",
        ids=("hoop", "cylinder"),
        t=t,
        x=x,
        phi=phi,
        frames=np.arange(n),
        fps=60.0,
        scale=700.0,
        scale_source="radii",
        roll=0.0,
        residuals={},
        centre_px=np.zeros((n, 2, 2)),
        radius_px=np.full((n, 2), 70.0),
        circle_rms_px=np.zeros((n, 2)),
        marker_contrast=np.ones((n, 2)),
    )


def test_fit_takes_the_tracks_of_a_video_as_it_takes_their_file(tmp_path: Path) -> None:
    t, x, phi = recording(TRUTH, duration=2.0, fps=60.0, seed=11)
    tracks = _tracks(t, x, phi)
    path = tmp_path / "tracks.csv"
    tracks.to_csv(path)
    start = TRUTH.system(k=100.0)
    free = ["springs.0.stiffness", "springs.0.damping"]
    from_object = rollspring.fit(tracks, start, free=free, claims=False)
    from_file = rollspring.fit(path, start, free=free, claims=False)
    for name in free:
        assert from_object.parameters[name].value == from_file.parameters[name].value
    assert from_object.data.has_angles


@pytest.mark.parametrize("data", [42, None, [1.0, 2.0]])
def test_fit_refuses_data_of_another_kind_in_one_line(data: object) -> None:
    with pytest.raises(DataError, match=r"^data: expected a data file's path"):
        rollspring.fit(data, TRUTH.system(), free=["springs.0.stiffness"])  # type: ignore[arg-type]

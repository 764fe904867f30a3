"""simulate's summary extremes (the largest |f|/N while rolling, the smallest N) against the
same run looked at densely, on nine random systems where a reviewer or a scan found them wrong
(30 Nov):
stick-slip runs of many segments, sharp peaks, peaks inside long adaptive steps
(tests/data/extremes_cases.json says what each got wrong and by how much).

The reference is the same trajectory (the same rtol: the same steps, whatever the output times)
at 200 001 evenly spaced rows, each on the integrator's interpolant, over the rows where the
body rolls (|f|/N) or all rows (N). Rows sit below a peak by at most (omega dt)^2/8, 1e-7 relative
here, and a peak at an event's instant (a slip, where |f|/N reaches mu_s) can fall between
rows: that one is checked against mu_s itself."""

from __future__ import annotations

import json
import math
from pathlib import Path

import numpy as np
import pytest

import rollspring
from rollspring.model import system_from_dict

CASES = {
    case["name"]: case
    for case in json.loads((Path(__file__).parent / "data" / "extremes_cases.json").read_text())
}


def dense_extreme(case: dict, system: rollspring.System) -> float:
    run = rollspring.simulate(
        system, case["T"], rtol=case["rtol"], n_output=200_001, on_slip=case["on_slip"]
    )
    i = run.ids.index(case["body"])
    if case["kind"] == "normal":
        return float(np.min(run.normal[:, i]))
    with np.errstate(divide="ignore", invalid="ignore"):
        ratio = np.abs(run.friction[:, i]) / run.normal[:, i]
    return float(np.max(np.where(run.slipping[:, i], -np.inf, ratio)))


@pytest.mark.parametrize("name", list(CASES))
def test_the_summary_extremes_are_those_the_motion_reaches(name: str) -> None:
    case = CASES[name]
    system = system_from_dict(case["system"])
    run = rollspring.simulate(
        system, case["T"], rtol=case["rtol"], n_output=case["n_output"], on_slip=case["on_slip"]
    )
    reference = dense_extreme(case, system)
    if case["kind"] == "normal":
        value = run.summary["min_normal_force"][case["body"]]
        # never above what the motion reaches (the rows), nor below it by more than their gaps
        assert reference * (1 - 2e-7) <= value <= reference * (1 + 1e-9)
        return
    value = run.summary["max_friction_ratio"][case["body"]]
    mu = next(b["mu_static"] for b in case["system"]["bodies"] if b["id"] == case["body"])
    assert reference * (1 - 1e-9) <= value
    if math.isfinite(mu) and value > reference * (1 + 2e-7):
        # above every row: only at a slip's instant, where |f| reaches mu_s N exactly
        assert value == pytest.approx(mu, rel=1e-9)
        assert any(
            event["kind"] == "slip" and event["body"] == case["body"] for event in run.events
        )
    else:
        assert value <= reference * (1 + 2e-7)


def test_a_symmetric_stick_slip_motion_reports_no_period_instead_of_failing():
    """Two equal hoops moving apart symmetrically between walls, slipping and sticking: the
    lowest mode is not excited (its coordinate is rounding noise), so the rows' upward
    crossings of its mean are not the interpolant's. ``simulate`` raised SciPy's raw
    "f(a) and f(b) must have different signs"; the measured period is now None (found by a
    review, 30 Nov 2026)."""
    import rollspring
    from rollspring.model import system_from_dict

    hoop = {"shape": "hoop", "mass": 1.0, "radius": 0.1, "mu_static": 0.05, "mu_kinetic": 0.04}
    system = system_from_dict(
        {
            "gravity": 9.81,
            "bodies": [
                {"id": "a", "x": -0.3, "v": 0.4, **hoop},
                {"id": "b", "x": 0.3, "v": -0.4, **hoop},
            ],
            "springs": [
                {"ends": ["wl", "a"], "stiffness": 100, "rest_length": 0.5},
                {"ends": ["a", "b"], "stiffness": 100, "rest_length": 0.5},
                {"ends": ["b", "wr"], "stiffness": 100, "rest_length": 0.5},
            ],
            "anchors": [{"id": "wl", "x": -1.0, "y": 0.1}, {"id": "wr", "x": 1.0, "y": 0.1}],
        }
    )
    trajectory = rollspring.simulate(system, 3.0, on_slip="continue")
    assert trajectory.status == "finished"
    assert len(trajectory.events) > 0
    assert trajectory.summary["period_measured"] is None
    # the motion is symmetric: each body's extremes are the other's
    ratio = trajectory.summary["max_friction_ratio"]
    assert ratio["a"] == pytest.approx(ratio["b"], rel=1e-6)

"""simulate's summary extremes cover the run and nothing after it: a largest |f|/N reached at
the run's end was refined over a window of two steps that ran up to a step past the end (the
friction a motion needs, 28 % too high for a run of three steps: a run that never slipped
reported a largest |f|/N above its mu_s). Found by a helper's recomputation."""

from __future__ import annotations

import numpy as np
import pytest

import rollspring
from rollspring.model import system_from_dict, system_to_json


def pushed(mu: float = 1.0) -> rollspring.System:
    """The paper's pair released with the spring at its rest length and the hoop pushed: the
    friction a body needs grows from 0 for the first quarter period."""
    data = system_to_json(rollspring.load_system("hoop-cylinder"))
    data["bodies"][1]["x"] = 0.5
    data["bodies"][0]["v"] = 0.2
    data["bodies"][0]["mu_static"] = mu
    return system_from_dict(data)


def closed_form_ratios(t: float) -> tuple[float, float]:
    """|f|/N of the hoop and the cylinder at t, from the closed form (docs/physics.md 7.1,
    (M10)): the spring's stretch u = -(v0/Omega) sin(Omega t), Omega^2 = k (1/(2 m1) +
    2/(3 m2)); its tension k u pulls each body, whose friction is gamma/(1 + gamma) of it
    (1/2 for the hoop, 1/3 for the cylinder), against N = m g."""
    k, m, g, v0 = 100.0, 1.0, 9.81, 0.2
    omega = np.sqrt(k * (1 / (2 * m) + 2 / (3 * m)))
    tension = k * abs(v0 / omega * np.sin(omega * t))
    return tension / 2 / (m * g), tension / 3 / (m * g)


@pytest.mark.parametrize("duration", [0.05, 0.1, 0.13])
@pytest.mark.parametrize("rtol", [1e-6, 1e-8, 1e-10])
def test_a_largest_ratio_at_the_end_is_the_ratio_there(duration, rtol):
    run = rollspring.simulate(pushed(), duration, rtol=rtol, n_output=11)
    ratio = np.abs(run.friction) / run.normal
    assert np.all(np.diff(ratio, axis=0) > 0)  # still rising at the end
    exact = closed_form_ratios(duration)  # the largest over [0, T]: at T, a quarter period on
    for i, name in enumerate(run.ids):
        assert run.summary["max_friction_ratio"][name] == pytest.approx(ratio[-1, i], rel=1e-12)
        assert run.summary["max_friction_ratio"][name] == pytest.approx(exact[i], rel=100 * rtol)


def test_a_run_that_never_slips_needs_no_more_than_its_mu():
    needed = float(np.abs(rollspring.simulate(pushed(), 0.05).friction[-1, 0]) / 9.81)
    run = rollspring.simulate(pushed(mu=1.05 * needed), 0.05)
    assert run.status == "finished"
    assert run.summary["max_friction_ratio"]["hoop"] < 1.05 * needed

"""simulate's output times are the evenly spaced grid it promises (``n_output``), whatever the
events: stick-slip with ``on_slip="continue"`` keeps every grid time (a run whose motion
slipped and stuck again lost the grid times between the last step before each event and the
event), and a run stopped by an event keeps every grid time up to the event, then the event's
row. The rows at those times are the motion's (checked against the adaptive integrator)."""

from __future__ import annotations

import numpy as np
import pytest

import rollspring
from rollspring.model import system_from_dict, system_to_json

DURATION = 6.0
N_OUTPUT = 361


def hoop_cylinder(mu: float, v: float, *, at_rest_length: bool) -> rollspring.System:
    data = system_to_json(rollspring.load_system("hoop-cylinder"))
    data["bodies"][0]["mu_static"] = mu
    data["bodies"][0]["v"] = v
    if at_rest_length:  # the spring starts at its rest length: the friction needed grows from 0
        data["bodies"][1]["x"] = 0.5
    return system_from_dict(data)


@pytest.mark.parametrize("integrator", ["auto", "dop853"])
@pytest.mark.parametrize(
    ("mu", "v"), [(0.01, 0.0), (0.03, 0.0), (0.05, 0.0), (0.02, 0.2), (0.04, 0.5)]
)
def test_stick_slip_keeps_every_output_time(mu, v, integrator):
    system = hoop_cylinder(mu, v, at_rest_length=False)
    run = rollspring.simulate(
        system, DURATION, n_output=N_OUTPUT, on_slip="continue", integrator=integrator, rtol=1e-10
    )
    assert run.status == "finished"
    kinds = {event["kind"] for event in run.events}
    assert {"slip", "stick"} <= kinds, kinds  # the case is a stick-slip one
    assert np.array_equal(run.t, np.linspace(0.0, DURATION, N_OUTPUT))
    assert run.x.shape == (N_OUTPUT, 2) and np.all(np.isfinite(run.x))


@pytest.mark.parametrize(("mu", "v"), [(0.01, 0.0), (0.03, 0.0), (0.02, 0.2), (0.04, 0.5)])
def test_stick_slip_rows_are_the_motion(mu, v):
    """The rows the rolling path records from a step's start to an event inside it are the
    motion there: the symplectic path and the adaptive one agree at every output time."""
    system = hoop_cylinder(mu, v, at_rest_length=False)
    runs = [
        rollspring.simulate(
            system, DURATION, n_output=N_OUTPUT, on_slip="continue", integrator=name, rtol=1e-10
        )
        for name in ("auto", "dop853")
    ]
    assert len(runs[0].events) == len(runs[1].events)
    assert np.max(np.abs(runs[0].x - runs[1].x)) < 1e-9
    assert np.max(np.abs(runs[0].v - runs[1].v)) < 1e-8
    assert np.max(np.abs(runs[0].friction - runs[1].friction)) < 1e-6


@pytest.mark.parametrize("integrator", ["auto", "dop853"])
@pytest.mark.parametrize(("mu", "v"), [(0.01, 0.1), (0.02, 0.1), (0.05, 0.3), (0.02, 0.3)])
def test_a_stopped_run_keeps_the_output_times_before_its_event(mu, v, integrator):
    system = hoop_cylinder(mu, v, at_rest_length=True)
    run = rollspring.simulate(
        system, DURATION, n_output=N_OUTPUT, on_slip="stop", integrator=integrator, rtol=1e-10
    )
    assert run.status == "slip"
    event = run.summary["first_slip"]["time"]
    assert 0.0 < event < DURATION
    grid = np.linspace(0.0, DURATION, N_OUTPUT)
    before = grid[grid < event]
    assert np.array_equal(run.t[: before.size], before)
    assert run.t[-1] == pytest.approx(event, abs=1e-12)
    assert run.t.size in (before.size + 1, before.size + 2)  # a grid time at the event: once

"""Batch runs whose contact margins start at exactly zero (lengths and forces exact in binary),
against ``simulate`` with the same integrator and step: an event whose margin is zero at a
step's start is dated there by the batch's linear interpolation (it was dated at the step's end),
and a friction ratio 0/0 at the start does not stand for the whole run (it stayed 0 while
|f|/N > 0 at every t > 0)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from rollspring.simulate import simulate, simulate_batch
from tests.conftest import body, make_system, spring

M, R, G = 1.0, 0.125, 8.0


def on_a_wall_spring(v0: float, mu: float, rest_length: float | None):
    """A cylinder at x = 0 on a level spring (k = 32) from an anchor at x = -0.5: at its rest
    length (None: the initial length, f(0) = 0) or stretched (0.3125: a pull of 6 N, so
    |f(0)| = 2 N = mu_s N for mu_s = 0.25, N = 8 N)."""
    entry = spring("wall", "c", stiffness=32.0)
    if rest_length is not None:
        entry["rest_length"] = rest_length
    return make_system(
        [body("c", "cylinder", mass=M, radius=R, x=0.0, v=v0, mu_static=mu)],
        [entry],
        anchors=[{"id": "wall", "x": -0.5, "y": R}],
        gravity=G,
    )


@pytest.mark.parametrize(
    ("mu", "rest_length"),
    [(0.0, None), (0.25, 0.3125)],
    ids=["mu_s 0, no pull", "a pull at mu_s N"],
)
@pytest.mark.parametrize("step", [1e-3, None])
def test_a_slip_margin_at_zero_where_the_run_starts_slips_at_the_start(mu, rest_length, step):
    """|f| = mu_s N exactly at t = 0, the body moving so that |f| grows: it slips at 0, as
    ``simulate`` says (the margin is zero at the first step's start and past zero at its end)."""
    batch = simulate_batch(
        on_a_wall_spring(0.0, mu, rest_length), {"bodies.c.v": [1.0]}, 0.5, step=step
    )
    single = simulate(
        on_a_wall_spring(1.0, mu, rest_length), 0.5, integrator=batch.integrator, step=batch.step
    )
    assert single.status == "slip" and single.events[0]["time"] == 0.0
    assert batch.status_names[0] == "slip"
    assert batch.first_slip_time[0] == 0.0


def test_a_pull_at_mu_s_n_that_falls_still_rolls():
    """The same pull at mu_s N with the body moving so that it falls: no slip, in both."""
    batch = simulate_batch(on_a_wall_spring(0.0, 0.25, 0.3125), {"bodies.c.v": [-1.0]}, 0.2)
    single = simulate(
        on_a_wall_spring(-1.0, 0.25, 0.3125), 0.2, integrator=batch.integrator, step=batch.step
    )
    assert single.status == batch.status_names[0] == "finished"


def propped(v0: float):
    """A cylinder carried by a compressed spring from an anchor straight below its centre: the
    push k (L0 - l) = 32 (0.75 - 0.5) = 8 N is its weight, so N(0) = 0 and f(0) = 0."""
    return make_system(
        [body("c", "cylinder", mass=M, radius=R, x=0.0, v=v0, mu_static=math.inf)],
        [spring("a", "c", stiffness=32.0, rest_length=0.75)],
        anchors=[{"id": "a", "x": 0.0, "y": -0.375}],
        gravity=G,
    )


def test_a_friction_ratio_that_starts_as_zero_over_zero_is_the_largest_sampled_after():
    batch = simulate_batch(propped(0.0), {"bodies.c.v": [0.5, 1.0]}, 0.5)
    for run, v0 in enumerate((0.5, 1.0)):
        single = simulate(propped(v0), 0.5, integrator=batch.integrator, step=batch.step)
        assert single.normal[0, 0] == 0.0 and single.friction[0, 0] == 0.0
        # the run's last step is sampled: the batch's largest ratio is at least the ratio there
        at_end = abs(single.friction[-1, 0]) / single.normal[-1, 0]
        assert at_end > 0.01
        assert batch.max_friction_ratio[run, 0] >= at_end * (1 - 1e-9)
        assert np.isfinite(batch.max_friction_ratio[run, 0])

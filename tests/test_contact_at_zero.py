"""A contact margin exactly at zero where the motion starts (docs/physics.md (M9)): a cylinder
whose spring's vertical pull balances its weight to the last bit (N(0) = 0), rolling on under
the spring's hook, where its normal force rises, and lifting off where it falls to zero again.
The rolling (symplectic) path took a margin at zero at a step's start as crossing there when the
step ended past zero, and the whole motion was lost (lift-off reported at t = 0) whenever the
first step was longer than the time N stays positive."""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.integrate import quad

from rollspring.simulate import simulate
from tests.conftest import body, make_system, spring

M, R, K, L0, G = 1.0, 0.125, 32.0, 0.3125, 8.0
HOOK = (0.375, 0.625)  # the anchor: dx = 0.375, dy = 0.5, l = 0.625 from the centre at x = 0


def hooked(v0: float):
    """The cylinder (mu_s = inf: it cannot slip) at x = 0 moving at ``v0`` toward the hook;
    every length is exact in binary, so the spring's vertical pull k (l - L0) dy / l = 8 N is
    m g exactly and N(0) == 0.0."""
    return make_system(
        [body("c", "cylinder", mass=M, radius=R, x=0.0, v=v0, mu_static=math.inf)],
        [spring("hook", "c", stiffness=K, rest_length=L0)],
        anchors=[{"id": "hook", "x": HOOK[0], "y": HOOK[1]}],
        gravity=G,
    )


def length(x: float) -> float:
    return math.hypot(HOOK[0] - x, HOOK[1] - R)


def liftoff_time(v0: float) -> float:
    """N = m g - k (l - L0)(dy / l) (M9) is zero again at x = 0.75 (the mirror of x = 0 under
    the hook) and positive between; the time to get there from the energy (a rolling cylinder's
    kinetic energy (3/4) m v^2, (M5)): t = \\int_0^{0.75} dx / v(x)."""

    def speed(x: float) -> float:
        spring_energy = 0.5 * K * ((length(0.0) - L0) ** 2 - (length(x) - L0) ** 2)
        return math.sqrt(v0**2 + spring_energy / (0.75 * M))

    value, _ = quad(lambda x: 1.0 / speed(x), 0.0, 0.75, epsabs=1e-14, epsrel=1e-13)
    return value


@pytest.mark.parametrize("integrator", ["auto", "dop853"])
@pytest.mark.parametrize(("v0", "rtol"), [(10.0, 1e-6), (20.0, 1e-8), (60.0, 1e-8), (60.0, 1e-12)])
def test_a_normal_force_that_starts_at_zero_and_rises_lifts_off_where_it_falls_again(
    v0, rtol, integrator
):
    system = hooked(v0)
    tr = simulate(system, 0.5, rtol=rtol, integrator=integrator)
    assert tr.normal[0, 0] == 0.0  # at zero to the last bit where it starts
    assert tr.status == "liftoff"
    [event] = tr.events
    expected = liftoff_time(v0)
    # located on the step's interpolant: to a small part of the (long) step, not at t = 0
    assert event["time"] == pytest.approx(expected, rel=1e-4)
    assert tr.x[-1, 0] == pytest.approx(0.75, abs=1e-4)
    inside = (tr.t > 0.0) & (tr.t < event["time"])
    assert np.all(tr.normal[inside, 0] > 0.0)


def test_a_body_that_cannot_slip_with_no_normal_force_is_checked_without_inf_times_zero():
    """mu_s = inf and N = 0: the slip check skips the body (inf * 0 is NaN, and NumPy's
    warning an error in this suite); the cylinder released at rest is pulled under the hook,
    its normal force rising from zero, and rolls on."""
    tr = simulate(hooked(0.0), 0.5)
    assert tr.status == "finished" and tr.normal[0, 0] == 0.0
    assert np.all(tr.normal[1:, 0] > 0.0) and tr.x[-1, 0] > 0.0


@pytest.mark.parametrize(
    ("margin", "until", "first"),
    [
        (lambda t: math.sin(math.pi * t / 0.5), 0.7, 0.5),  # rises, falls through at 0.5
        (lambda t: -t, 0.3, 0.0),  # falls at once
        (lambda t: -math.sin(3 * math.pi * t), 0.9, 0.0),  # falls at once, then a bump
        (lambda t: math.sin(5 * math.pi * t) * (1 + 2 * t), 0.7, 0.2),  # two bumps, 2nd higher
    ],
)
def test_the_first_fall_of_a_margin_that_starts_at_zero(margin, until, first):
    """rolling._first_fall (first_crossing on one step): of a margin exactly 0 at the start and
    below 0 at the end, the first instant it falls through zero, not a later one after a higher
    bump."""
    from rollspring.simulate.rolling import _first_fall

    assert _first_fall(margin, until) == pytest.approx(first, abs=1e-9)


@pytest.mark.parametrize("integrator", ["auto", "dop853"])
@pytest.mark.parametrize("v0", [-1e-2, -1e-4, -1e-6])
def test_a_normal_force_at_zero_that_falls_first_lifts_off_at_once(v0, integrator):
    """The cylinder at N = 0 moving away from the hook, where N falls (it rises toward the
    hook): it lifts off at once, even when the spring's pull (6 N, 4 m/s^2 on the rolling
    cylinder) turns it back within 2|v0|/a (5 ms down to 0.5 us), inside the first step, so
    that the margin is back above zero at the step's end (the zero-start branch of
    rolling's dip search, which takes the first fall, not the root after a rise)."""
    tr = simulate(hooked(v0), 0.5, integrator=integrator)
    assert tr.normal[0, 0] == 0.0
    assert tr.status == "liftoff"
    [event] = tr.events
    assert event["kind"] == "liftoff" and event["body"] == "c"
    assert 0.0 <= event["time"] <= 1e-12

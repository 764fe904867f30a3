"""The nonlinear simulation against exact solutions: modal motion, convergence orders, energy,
slip and lift-off instants, stick-slip, damping, and the kernels against the NumPy physics."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from rollspring.analysis import analyze
from rollspring.errors import SimulationError
from rollspring.model import load_system
from rollspring.physics import (
    contact_forces,
    generalized_forces,
    potential_energy,
    stiffness_matrix,
    system_arrays,
)
from rollspring.simulate import kernels, simulate
from rollspring.simulate.integrators import INTEGRATORS
from tests.conftest import body, make_system, spring

G = 9.81


def centre_pair(m1: float, m2: float, k: float, compression: float = 0.01, **extra):
    """The paper's Fig. 2: hoop and cylinder joined at their centres (exactly linear)."""
    return make_system(
        [
            body("hoop", "hoop", mass=m1, x=0.0, **extra),
            body("cyl", "cylinder", mass=m2, x=0.5 - compression, **extra),
        ],
        [spring("hoop", "cyl", stiffness=k, rest_length=0.5)],
    )


def exact_pair(m1, m2, k, compression, t):
    """x1, x2 of the centre pair released from rest: X-hat = (2 m1 x1 + 1.5 m2 x2)/(2m1+1.5m2)
    stays put, the separation oscillates at Omega^2 = k/(2m1) + 2k/(3m2)."""
    omega = math.sqrt(k / (2 * m1) + 2 * k / (3 * m2))
    w1, w2 = 2 * m1 / (2 * m1 + 1.5 * m2), 1.5 * m2 / (2 * m1 + 1.5 * m2)
    x_hat = w2 * (0.5 - compression)
    separation = 0.5 - compression * np.cos(omega * t)
    return x_hat - w2 * separation, x_hat + w1 * separation, omega


@settings(max_examples=6, deadline=None)
@given(st.floats(0.2, 5.0), st.floats(0.2, 5.0), st.floats(10.0, 1000.0))
def test_centre_pair_matches_the_exact_modal_solution_over_100_periods(m1, m2, k):
    compression = 0.01
    _, _, omega = exact_pair(m1, m2, k, compression, 0.0)
    period = 2 * math.pi / omega
    trajectory = simulate(
        centre_pair(m1, m2, k, compression, mu_static=math.inf), 100 * period, rtol=1e-10
    )
    assert trajectory.status == "finished"
    x1, x2, _ = exact_pair(m1, m2, k, compression, trajectory.t)
    amplitude = max(np.ptp(x1), np.ptp(x2))  # the larger centre swing of the exact motion
    error = max(np.max(np.abs(trajectory.x[:, 0] - x1)), np.max(np.abs(trajectory.x[:, 1] - x2)))
    assert error <= 1e-9 * amplitude
    assert trajectory.summary["period_measured"] == pytest.approx(period, rel=1e-9)
    assert trajectory.summary["period_linear"] == pytest.approx(period, rel=1e-12)
    # X-hat is stationary (M11) and the friction ratio peaks at the paper's F/2 on the hoop
    assert np.ptp(trajectory.stationary_x) <= 1e-9 * amplitude
    force = k * compression
    assert trajectory.summary["max_friction_ratio"]["hoop"] == pytest.approx(
        force / 2 / (m1 * G), rel=1e-9
    )
    assert trajectory.summary["max_friction_ratio"]["cyl"] == pytest.approx(
        force / 3 / (m2 * G), rel=1e-9
    )


@pytest.mark.parametrize("rtol", [1e-6, 1e-9, 1e-12])
def test_outputs_between_steps_are_interpolated_within_rtol(rtol):
    """Many outputs per step: the septic Hermite outputs (positions and velocities) stay within
    rtol of the amplitude; the interpolation error ((omega h)^8/10321920 in position,
    (omega h)^7/2710000 in velocity) never exceeds the run's."""
    m1, m2, k, compression = 1.0, 1.3, 100.0, 0.01
    _, _, omega = exact_pair(m1, m2, k, compression, 0.0)
    duration = 2.25 * 2 * math.pi / omega
    trajectory = simulate(
        centre_pair(m1, m2, k, compression, mu_static=math.inf),
        duration,
        rtol=rtol,
        n_output=20_001,
    )
    assert trajectory.step > 3 * duration / 20_000  # every step holds several outputs
    _x1, x2, _ = exact_pair(m1, m2, k, compression, trajectory.t)
    amplitude = np.ptp(x2)
    assert np.max(np.abs(trajectory.x[:, 1] - x2)) <= rtol * amplitude
    speed = omega * compression * 1.5 * m2 / (2 * m1 + 1.5 * m2)  # the hoop's peak speed
    hoop_speed = -speed * np.sin(omega * trajectory.t)
    assert np.max(np.abs(trajectory.v[:, 0] - hoop_speed)) <= rtol * speed


def test_outputs_on_step_ends_where_that_takes_fewer_steps_are_within_rtol():
    """A tight rtol over one period: the interpolant would set the step, so the step divides
    the output spacing instead and every output is a step end (no interpolant), within rtol of
    the exact motion."""
    m1, m2, k, compression = 1.0, 1.3, 100.0, 0.01
    _, _, omega = exact_pair(m1, m2, k, compression, 0.0)
    duration, rtol = 2 * math.pi / omega, 1e-11
    kahanli8 = INTEGRATORS["kahanli8"]
    interpolated = math.ceil(duration / kahanli8.contract_step(omega, duration, rtol))
    # the most outputs whose spacing the phase step still spans: one step each, fewer steps
    n_output = interpolated  # interpolated - 1 intervals
    step = kahanli8.contract_step(omega, duration, rtol, n_output)
    assert step == pytest.approx(duration / (n_output - 1), rel=1e-12)
    trajectory = simulate(
        centre_pair(m1, m2, k, compression, mu_static=math.inf),
        duration,
        rtol=rtol,
        n_output=n_output,
    )
    assert trajectory.integrator == "kahanli8"
    assert trajectory.n_steps == n_output - 1 < interpolated
    _x1, x2, _ = exact_pair(m1, m2, k, compression, trajectory.t)
    amplitude = np.ptp(x2)
    assert np.max(np.abs(trajectory.x[:, 1] - x2)) <= rtol * amplitude
    speed = omega * compression * 1.5 * m2 / (2 * m1 + 1.5 * m2)  # the hoop's peak speed
    hoop_speed = -speed * np.sin(omega * trajectory.t)
    assert np.max(np.abs(trajectory.v[:, 0] - hoop_speed)) <= rtol * speed


@pytest.mark.parametrize(
    ("integrator", "order"), [("verlet", 2), ("yoshida4", 4), ("yoshida6", 6), ("kahanli8", 8)]
)
def test_fitted_order_of_each_integrator(integrator, order):
    m1, m2, k, compression = 1.0, 1.3, 100.0, 0.01
    _, _, omega = exact_pair(m1, m2, k, compression, 0.0)
    # a quarter period past a whole number of periods, where a phase error shows to first order
    duration = 4.25 * 2 * math.pi / omega
    system = centre_pair(m1, m2, k, compression)
    # steps large enough that rounding stays far below the error of the scheme
    base = {2: 0.1, 4: 0.2, 6: 0.4, 8: 0.6}[order] / omega
    errors, steps = [], []
    for factor in (1, 2, 4):
        h = base / factor
        trajectory = simulate(system, duration, integrator=integrator, step=h, n_output=2)
        x1, _, _ = exact_pair(m1, m2, k, compression, trajectory.t[-1])
        errors.append(abs(trajectory.x[-1, 0] - x1))
        steps.append(trajectory.step)
    fitted = np.polyfit(np.log(steps), np.log(errors), 1)[0]
    assert abs(fitted - order) <= 0.3


def off_centre_pair():
    """Hoop and sphere joined off-centre: the spring tilts and the motion is nonlinear."""
    return make_system(
        [
            body("hoop", "hoop", x=0.0, mu_static=math.inf),
            body("ball", "sphere", x=0.46, v=0.3, mu_static=math.inf),
        ],
        [
            spring(
                "hoop",
                "ball",
                at=[{"radius": 0.07, "angle": 40.0}, {"radius": 0.05, "angle": -120.0}],
            )
        ],
    )


def test_energy_stays_bounded_over_a_million_steps_of_a_nonlinear_run():
    system = off_centre_pair()
    analysis = analyze(system)
    omega = max(m.omega for m in analysis.modes)
    h = 0.15 / omega
    trajectory = simulate(
        system, 1_000_000 * h, integrator="yoshida4", step=h, n_output=4001, energy_tolerance=1e-3
    )
    assert trajectory.status == "finished"
    assert trajectory.n_steps == 1_000_000
    error = np.abs(trajectory.energy - trajectory.energy[0]) / trajectory.energy[0]
    early, late = error[:400].max(), error[-400:].max()
    assert error.max() < 1e-4
    assert late < 3 * early  # no secular growth: a symplectic scheme's error oscillates
    # really nonlinear: the bodies turn by many radians and the spring length varies by cm
    assert np.ptp(trajectory.phi[:, 0]) > 100
    assert np.ptp(trajectory.spring_length) > 0.02


def test_adaptive_dop853_and_symplectic_agree_on_the_nonlinear_run():
    system = off_centre_pair()
    symplectic = simulate(system, 3.0, rtol=1e-11, n_output=61)
    adaptive = simulate(system, 3.0, rtol=1e-11, n_output=61, integrator="dop853")
    assert adaptive.integrator == "dop853"
    np.testing.assert_allclose(adaptive.x, symplectic.x, atol=1e-8)
    np.testing.assert_allclose(adaptive.friction, symplectic.friction, atol=1e-6)


def moving_pair(mu_hoop: float):
    """Centre pair at rest length, pushed apart with X-hat at rest: the deformation is
    A sin(Omega t), so |f|/N peaks first at Omega t = pi/2."""
    w1, w2 = 2.0 / 3.5, 1.5 / 3.5  # X-hat weights of equal masses
    speed = 0.05
    return make_system(
        [
            body("hoop", "hoop", x=0.0, v=-w2 * speed, mu_static=mu_hoop),
            body("cyl", "cylinder", x=0.5, v=w1 * speed, mu_static=5.0),
        ],
        [spring("hoop", "cyl", rest_length=0.5)],
    )


@pytest.mark.parametrize("fraction", [0.999, 0.9])
def test_slip_starts_when_the_needed_friction_first_reaches_mu(fraction):
    needed = float(analyze(moving_pair(1.0)).required_mu[0])
    system = moving_pair(fraction * needed)
    omega = math.sqrt(100.0 / 2 + 2 * 100.0 / 3)
    trajectory = simulate(system, 10.0, rtol=1e-10)
    assert trajectory.status == "slip"
    slip = trajectory.summary["first_slip"]
    assert slip["body"] == "hoop"
    # f(t) = f_max sin(Omega t): the first instant with |f| = mu N
    assert slip["time"] == pytest.approx(math.asin(fraction) / omega, abs=1e-9)
    assert trajectory.t[-1] == slip["time"]
    assert trajectory.friction_ratio[-1, 0] == pytest.approx(1.0, abs=1e-9)


@pytest.mark.parametrize("rtol", [1e-8, 1e-10])
@pytest.mark.parametrize("graze", [1e-6, 1e-8, 1e-10])
def test_a_friction_that_grazes_mu_s_n_between_two_step_ends_slips_at_the_exact_instant(
    graze, rtol
):
    """mu_s a part ``graze`` below the peak of |f|/N: the excursion beyond mu_s N lasts
    2 sqrt(2 graze)/Omega (28 us at 1e-10), far inside one step, and both step ends around it
    are below the bound. The run slips at the first instant with |f| = mu_s N, sin(Omega t) =
    1 - graze, to the accuracy the step's interpolant gives a margin this flat there: a phase
    error delta moves the instant by delta / (Omega sqrt(2 graze)). Before 29 Nov 2026 such a
    run rolled to the end with its max |f|/N reported above mu_s."""
    needed = float(analyze(moving_pair(1.0)).required_mu[0])
    omega = math.sqrt(100.0 / 2 + 2 * 100.0 / 3)
    trajectory = simulate(moving_pair((1 - graze) * needed), 1.0, rtol=rtol)
    assert trajectory.status == "slip"
    slip = trajectory.summary["first_slip"]
    assert slip["body"] == "hoop"
    exact = math.asin(1 - graze) / omega
    slope = omega * math.sqrt(2 * graze)  # d|f|/(f_max dt) at the instant
    assert abs(slip["time"] - exact) <= 1e-2 * rtol / slope
    assert trajectory.friction_ratio[-1, 0] == pytest.approx(1.0, abs=1e-9)  # |f| / mu_s N


def test_a_friction_that_comes_within_1e_7_of_mu_s_n_rolls_on_with_the_same_motion_bit_for_bit():
    """mu_s a part 1e-7 above the peak of |f|/N: the steps where |f| comes nearest mu_s N are
    looked inside (the parabola's minimum is below its curvature term) and found clear; the
    run goes on from each such step's start, so the motion is the one with a large mu_s, bit
    for bit, and no slip is reported."""
    needed = float(analyze(moving_pair(1.0)).required_mu[0])
    close = simulate(moving_pair((1 + 1e-7) * needed), 2.0, rtol=1e-10)
    far = simulate(moving_pair(1.0), 2.0, rtol=1e-10)
    assert close.status == far.status == "finished"
    assert close.summary["first_slip"] is None
    np.testing.assert_array_equal(close.x, far.x)
    np.testing.assert_array_equal(close.v, far.v)
    assert close.summary["max_friction_ratio"]["hoop"] == pytest.approx(needed, rel=1e-9)


@pytest.mark.parametrize("rtol", [1e-8, 1e-10])
@pytest.mark.parametrize("graze", [1e-4, 1e-6, 1e-8])
def test_a_normal_force_that_grazes_zero_between_two_step_ends_lifts_off_at_the_exact_instant(
    graze, rtol
):
    """A cylinder on a spring to a hook 0.3 m above its centre, pushed along the track: the
    spring's upward pull k (l - L0) H / l is largest at the turning point x = A, and gravity is
    set a part ``graze`` below it, so N dips below zero for a moment around each turning
    point, between two step ends. The run lifts off where the pull first equals m g, at
    x*: t* = int_0^x* dx / v(x) with (1 + gamma) m v^2 / 2 = V(A) - V(x), exact for the
    rolling body (x = A - s^2 takes the turning point's 1/sqrt out of the integral). Before
    29 Nov 2026 the run lifted off 0.63 s late at 1e-4, and never below."""
    import scipy.integrate
    import scipy.optimize

    k, rest, above, m, radius, gamma, v0 = 100.0, 0.2, 0.3, 1.0, 0.1, 0.5, 0.6

    def pull(x: float) -> float:  # the spring's upward pull on the body
        length = math.hypot(x, above)
        return k * (length - rest) * above / length

    def potential(x: float) -> float:
        return 0.5 * k * (math.hypot(x, above) - rest) ** 2

    energy = 0.5 * (1 + gamma) * m * v0**2
    amplitude = scipy.optimize.brentq(lambda x: potential(x) - potential(0.0) - energy, 0.0, 5.0)
    gravity = pull(amplitude) * (1 - graze) / m
    x_star = scipy.optimize.brentq(lambda x: pull(x) - m * gravity, 0.0, amplitude)

    def dt_ds(s: float) -> float:  # dt/ds along x = A - s^2
        x = amplitude - s * s
        return 2 * s / math.sqrt(2 * (potential(amplitude) - potential(x)) / ((1 + gamma) * m))

    exact = scipy.integrate.quad(
        dt_ds, math.sqrt(amplitude - x_star), math.sqrt(amplitude), epsabs=0.0, epsrel=1e-12
    )[0]
    system = make_system(
        [body("c", "cylinder", mass=m, radius=radius, x=0.0, v=v0, mu_static=math.inf)],
        [spring("c", "hook", stiffness=k, rest_length=rest)],
        anchors=[{"id": "hook", "x": 0.0, "y": radius + above}],
        gravity=gravity,
    )
    trajectory = simulate(system, 1.0, rtol=rtol)
    assert trajectory.status == "liftoff"
    liftoff = trajectory.summary["first_liftoff"]
    assert abs(liftoff["time"] - exact) <= 1e-2 * rtol / math.sqrt(graze)


def phased_pair(tag: str, mu_hoop: float, peak: float, x0: float = 0.0):
    """:func:`moving_pair`'s bodies and spring, named with ``tag`` and placed at ``x0``, phased
    so that the hoop's |f|/N peaks at t = ``peak``."""
    w1, w2, speed = 2.0 / 3.5, 1.5 / 3.5, 0.05
    omega = math.sqrt(100.0 / 2 + 2 * 100.0 / 3)
    phase = math.pi / 2 - omega * peak
    d, rate = speed / omega * math.sin(phase), speed * math.cos(phase)
    bodies = [
        body(f"{tag}hoop", "hoop", x=x0 - w2 * d, v=-w2 * rate, mu_static=mu_hoop),
        body(f"{tag}cyl", "cylinder", x=x0 + 0.5 + w1 * d, v=w1 * rate, mu_static=5.0),
    ]
    return bodies, [spring(f"{tag}hoop", f"{tag}cyl", rest_length=0.5)]


def pairs_system(*pairs):
    return make_system(
        [b for bodies, _ in pairs for b in bodies], [s for _, springs in pairs for s in springs]
    )


def test_every_margin_near_its_bound_in_a_step_is_looked_at_and_the_earliest_dip_wins():
    """Two far-apart copies of the pair in one system, their hoops' peaks in the same step
    (found by the review of 29 Nov): A's hoop comes within 1e-7 of mu_s (clear), B's grazes
    it by 1e-8 0.3 of a step earlier, or later. B's slip is found whatever the bodies' order,
    at the instant B has alone; and of two grazes in one step, the earlier one wins."""
    omega = math.sqrt(100.0 / 2 + 2 * 100.0 / 3)
    needed = float(analyze(moving_pair(1.0)).required_mu[0])
    assert simulate(moving_pair(1.0), 1.0, rtol=1e-10).summary["step"] == pytest.approx(1 / 91)
    peak = 0.1 + 0.5 / 91  # inside the step from 9/91 to 10/91 s
    clear = phased_pair("A", (1 + 1e-7) * needed, peak)
    graze = phased_pair("B", (1 - 1e-8) * needed, peak, 10.0)
    alone = simulate(pairs_system(graze), 1.0, rtol=1e-10).summary["first_slip"]
    exact = peak - math.acos(1 - 1e-8) / omega  # sin(Omega t) = 1 - 1e-8 before the peak
    assert alone["time"] == pytest.approx(exact, abs=1e-7)
    for order in ((clear, graze), (graze, clear)):
        slip = simulate(pairs_system(*order), 1.0, rtol=1e-10).summary["first_slip"]
        assert slip == alone
    early = phased_pair("B", (1 - 1e-8) * needed, peak - 0.3 / 91, 10.0)
    late = phased_pair("A", (1 - 1e-8) * needed, peak)
    first = simulate(pairs_system(early), 1.0, rtol=1e-10).summary["first_slip"]
    assert first["body"] == "Bhoop"
    for order in ((late, early), (early, late)):
        assert simulate(pairs_system(*order), 1.0, rtol=1e-10).summary["first_slip"] == first


@pytest.mark.parametrize("fraction", [0.3, 0.5, 0.7, 1.5])
def test_a_graze_in_the_first_step_of_a_segment_is_found(fraction):
    """The kernel looks at a step from the two step ends before it; a segment's first step
    is looked at from its start, middle and end: the hoop's peak put 0.3, 0.5, 0.7 and 1.5 of
    a step after the release, mu_s 1e-8 below it, slips there (not a period later)."""
    omega = math.sqrt(100.0 / 2 + 2 * 100.0 / 3)
    needed = float(analyze(moving_pair(1.0)).required_mu[0])
    peak = fraction / 91  # the step of these runs at rtol 1e-10 is 1/91 s
    trajectory = simulate(pairs_system(phased_pair("", (1 - 1e-8) * needed, peak)), 1.0, rtol=1e-10)
    slip = trajectory.summary["first_slip"]
    assert slip["body"] == "hoop"
    assert slip["time"] == pytest.approx(peak - math.acos(1 - 1e-8) / omega, abs=1e-7)


def test_no_slip_just_above_the_needed_friction():
    needed = float(analyze(moving_pair(1.0)).required_mu[0])
    omega = math.sqrt(100.0 / 2 + 2 * 100.0 / 3)
    trajectory = simulate(moving_pair(1.001 * needed), 100 * 2 * math.pi / omega, rtol=1e-10)
    assert trajectory.status == "finished"
    assert trajectory.summary["first_slip"] is None
    assert trajectory.summary["max_friction_ratio"]["hoop"] == pytest.approx(needed, rel=1e-9)


def wall_cylinder(stretch: float, mu_s: float, mu_k: float):
    return make_system(
        [
            body(
                "c",
                "cylinder",
                mass=1.0,
                radius=0.1,
                x=0.5 + stretch,
                mu_static=mu_s,
                mu_kinetic=mu_k,
            )
        ],
        [spring("wall", "c", stiffness=100.0, rest_length=0.5)],
        anchors=[{"id": "wall", "x": 0.0, "y": 0.1}],
    )


def slipping_from_release(stretch, mu_k, t):
    """docs/physics.md section 9: a cylinder on a wall spring slipping from release:
    x = x_e + (x0 - x_e) cos(w0 t), phi = -mu_k g t^2/R, x_e = x_rest + mu_k m g/k (m = 1 kg,
    k = 100 N/m, R = 0.1 m), and the contact point's velocity x' - R phi'."""
    w0 = 10.0
    x_e, x0 = 0.5 + mu_k * G / 100.0, 0.5 + stretch
    x = x_e + (x0 - x_e) * np.cos(w0 * t)
    phi = -mu_k * G * t**2 / 0.1
    slip_velocity = -(x0 - x_e) * w0 * np.sin(w0 * t) + 2 * mu_k * G * t
    return x, phi, slip_velocity


def first_zero_of_slip_velocity(stretch, mu_k):
    from scipy.optimize import brentq

    return brentq(lambda t: slipping_from_release(stretch, mu_k, t)[2], 1e-6, math.pi / 10.0)


def test_stick_slip_follows_the_exact_slipping_solution_then_sticks():
    stretch, mu_s, mu_k = 0.1, 0.3, 0.25
    trajectory = simulate(
        wall_cylinder(stretch, mu_s, mu_k), 2.0, rtol=1e-12, on_slip="continue", n_output=2001
    )
    assert trajectory.status == "finished"
    assert trajectory.events[0] == {"kind": "slip", "time": 0.0, "body": "c"}
    t_stick = first_zero_of_slip_velocity(stretch, mu_k)
    # at each stop of the contact point the friction needed, -F/3, is within mu_s N: it
    # rolls again, until the spring pulls hard enough to make it slip again; the slips die out
    kinds = [e["kind"] for e in trajectory.events]
    assert kinds == ["slip", "stick"] * (len(kinds) // 2) and len(kinds) >= 2
    times = [e["time"] for e in trajectory.events] + [2.0]
    assert times[1] == pytest.approx(t_stick, abs=1e-9)
    during = trajectory.t < t_stick
    x, phi, _ = slipping_from_release(stretch, mu_k, trajectory.t[during])
    np.testing.assert_allclose(trajectory.x[during, 0], x, atol=1e-8)
    np.testing.assert_allclose(trajectory.phi[during, 0], phi, atol=1e-8)
    # the row at t = 0 too: the motion that starts there, under kinetic friction mu_k N
    # against the slip (not the static friction rolling would need: beyond mu_s N, which no
    # floor gives)
    assert trajectory.slipping[during, 0].all()
    assert abs(trajectory.friction[0, 0]) == pytest.approx(mu_k * trajectory.normal[0, 0])
    # energy is lost while slipping (at the rate mu_k N |v_s|) and only then
    assert np.all(np.diff(trajectory.energy) <= 1e-12 * trajectory.energy[0])
    assert trajectory.energy[-1] < 0.9 * trajectory.energy[0]
    for start, end in zip(times[1::2], times[2::2], strict=True):
        rolling = (trajectory.t > start) & (trajectory.t < end)
        assert not trajectory.slipping[rolling, 0].any()
        assert np.ptp(trajectory.energy[rolling]) <= 1e-9 * trajectory.energy[0]
        # rolling: x - R phi is constant
        assert np.ptp(trajectory.x[rolling, 0] - 0.1 * trajectory.phi[rolling, 0]) <= 1e-9


def test_slip_reverses_when_the_friction_needed_at_rest_is_too_large():
    """Stretched further, the contact point stops while the spring still pulls hard: the
    friction needed to roll, |F|/3, exceeds mu_s N, so the slip reverses instead."""
    stretch, mu_s, mu_k = 0.2, 0.3, 0.2
    trajectory = simulate(wall_cylinder(stretch, mu_s, mu_k), 1.0, rtol=1e-12, on_slip="continue")
    kinds = [e["kind"] for e in trajectory.events]
    assert kinds[:2] == ["slip", "reverse"]
    assert trajectory.events[1]["time"] == pytest.approx(
        first_zero_of_slip_velocity(stretch, mu_k), abs=1e-9
    )
    assert np.all(np.diff(trajectory.energy) <= 1e-12 * trajectory.energy[0])


def test_stop_on_slip_ends_the_run_at_release_when_friction_is_too_small():
    trajectory = simulate(wall_cylinder(0.2, 0.3, 0.2), 2.0)
    assert trajectory.status == "slip"
    assert trajectory.summary["first_slip"] == {"time": 0.0, "body": "c"}
    assert "starts to slip" in trajectory.message


def test_lift_off_is_found_to_the_instant():
    system = make_system(
        [body("s", "slider", mass=0.1, radius=0.05, x=0.0, v=5.0)],
        [
            spring("hook", "s", stiffness=5.0, rest_length=0.5),
            spring("wall", "s", stiffness=20.0, rest_length=0.4849),
        ],
        anchors=[{"id": "hook", "x": 0.3, "y": 0.6}, {"id": "wall", "x": -0.5, "y": 0.05}],
    )
    trajectory = simulate(system, 5.0, rtol=1e-10)
    assert trajectory.status == "liftoff"
    assert trajectory.summary["first_liftoff"]["body"] == "s"
    assert abs(trajectory.normal[-1, 0]) <= 1e-9 * 0.1 * G
    assert trajectory.normal[:-1, 0].min() > 0
    assert trajectory.summary["min_normal_force"]["s"] == pytest.approx(0.0, abs=1e-9)


def test_damped_wall_cylinder_matches_the_exact_damped_oscillator():
    """Wall spring at centre height: 1.5 m x'' = -k (x - x_r) - c x' exactly."""
    k, c, m = 100.0, 2.0, 1.0
    system = make_system(
        [body("c", "cylinder", mass=m, x=0.52, mu_static=math.inf)],
        [spring("wall", "c", stiffness=k, rest_length=0.5, damping=c)],
        anchors=[{"id": "wall", "x": 0.0, "y": 0.1}],
    )
    trajectory = simulate(system, 3.0, rtol=1e-11, n_output=301)
    assert trajectory.integrator == "dop853"
    mass = 1.5 * m
    gamma = c / (2 * mass)
    wd = math.sqrt(k / mass - gamma**2)
    t = trajectory.t
    exact = 0.5 + 0.02 * np.exp(-gamma * t) * (np.cos(wd * t) + gamma / wd * np.sin(wd * t))
    np.testing.assert_allclose(trajectory.x[:, 0], exact, atol=1e-9)
    assert np.all(np.diff(trajectory.energy) <= 1e-12)
    assert trajectory.summary["energy_error"] <= 1e-9


def off_centre_on_two_tracks(r1, a1, r2, a2, wall_at=None):
    """A hoop and a cylinder on tracks 3 cm apart, joined off-centre (r1, a1 on the hoop; r2,
    a2 on the cylinder), the cylinder tied to a raised wall (at its centre, or ``wall_at``),
    and a constant force off the hoop's centre."""
    return make_system(
        [body("a", "hoop", x=0.0), body("b", "cylinder", x=0.5, track_height=0.03)],
        [
            spring(
                "a",
                "b",
                rest_length=0.45,
                at=[{"radius": r1, "angle": a1}, {"radius": r2, "angle": a2}],
            ),
            spring("w", "b", stiffness=30.0, **({} if wall_at is None else {"at": [{}, wall_at]})),
        ],
        anchors=[{"id": "w", "x": 1.0, "y": 0.2}],
        forces=[{"body": "a", "at": {"radius": 0.05, "angle": 30.0}, "fx": 0.7, "fy": -0.3}],
    )


@settings(max_examples=25, deadline=None)
@given(
    st.floats(0.0, 0.1),
    st.floats(-180, 180),
    st.floats(0.0, 0.1),
    st.floats(-180, 180),
    st.floats(-3, 3),
    st.floats(-3, 3),
)
def test_kernels_agree_with_the_numpy_physics(r1, a1, r2, a2, q1, q2):
    system = off_centre_on_two_tracks(r1, a1, r2, a2)
    arrays = system_arrays(system)
    model = kernels.kernel_model(arrays)
    q = np.array([q1, q2])
    _, _, friction, normal = kernels.advance(
        model, kernels.SCHEMES["verlet"][1], q, np.zeros(2), 0.0, 0
    )
    f_ref, n_ref = contact_forces(arrays, q)
    np.testing.assert_allclose(friction, f_ref, atol=1e-12)
    np.testing.assert_allclose(normal, n_ref, atol=1e-12)
    state = np.concatenate([arrays.x0 + arrays.scale * q, q, [0.0, 0.0], [0.0, 0.0]])
    derivative = np.empty(8)
    kernels.slipping_derivatives(
        model, state, np.zeros(2, dtype=bool), np.zeros(2), np.zeros(2), False, derivative
    )
    np.testing.assert_allclose(
        derivative[6:] * arrays.inertia, generalized_forces(arrays, q), atol=1e-12
    )
    out = [np.empty((1, 2)), np.empty((1, 2)), np.empty((1, 2)), np.empty((1, 2)), np.empty(1)]
    ratio, kinetic = np.empty((1, 2)), np.empty(1)
    kernels.observe(
        model,
        state[None, :],
        np.zeros((1, 2), dtype=bool),
        np.zeros((1, 2)),
        np.zeros((1, 2)),
        False,
        *out,
        arrays.gamma * arrays.mass * arrays.radius**2,
        ratio,
        kinetic,
    )
    assert out[4][0] == pytest.approx(float(potential_energy(arrays, q)), abs=1e-12)
    assert kinetic[0] == 0.0  # at rest
    # the kernel's rule: |f|/(mu_s N) while the body presses on its track, inf once N <= 0
    # (a lifted body has no friction to spare); random attachments reach both cases
    pressing = n_ref > 0.0
    expected = np.full(2, np.inf)
    expected[pressing] = np.abs(f_ref[pressing]) / (arrays.mu_static[pressing] * n_ref[pressing])
    np.testing.assert_array_equal(np.isinf(ratio[0]), ~pressing)
    np.testing.assert_allclose(ratio[0][pressing], expected[pressing], rtol=1e-12)


@settings(max_examples=25, deadline=None)
@given(
    st.floats(0.0, 0.1),
    st.floats(-180, 180),
    st.floats(0.0, 0.1),
    st.floats(-180, 180),
    st.floats(-3, 3),
    st.floats(-3, 3),
    st.floats(-20, 20),
    st.floats(-20, 20),
)
def test_the_force_rates_are_minus_the_stiffness_times_the_velocities(
    r1, a1, r2, a2, q1, q2, v1, v2
):
    """The septic output interpolant's jerks: kernels.force_rates = dQ/dt = -K(q) qdot, with K
    the exact stiffness matrix (physics), and the central difference of Q along qdot."""
    system = off_centre_on_two_tracks(r1, a1, r2, a2, wall_at={"radius": r2, "angle": a1})
    arrays = system_arrays(system)
    model = kernels.kernel_model(arrays)
    q, v = np.array([q1, q2]), np.array([v1, v2])
    rate = np.empty(2)
    kernels.force_rates(model, q, v, rate)
    stiffness = stiffness_matrix(arrays, q)
    scale = np.abs(stiffness).max() * max(np.abs(v).max(), 1e-3)
    np.testing.assert_allclose(rate, -(stiffness @ v), rtol=0, atol=1e-12 * scale)
    eps = 1e-6 / max(np.abs(v).max(), 1e-3)
    difference = (
        generalized_forces(arrays, q + eps * v) - generalized_forces(arrays, q - eps * v)
    ) / (2 * eps)
    np.testing.assert_allclose(rate, difference, rtol=0, atol=1e-6 * scale)


@pytest.mark.parametrize(
    ("kwargs", "field"),
    [
        ({"duration": -1.0}, "duration"),
        ({"duration": math.nan}, "duration"),
        ({"rtol": 0.0}, "rtol"),
        ({"rtol": -1e-3}, "rtol"),
        ({"integrator": "rk45"}, "integrator"),
        ({"on_slip": "ignore"}, "on_slip"),
        ({"n_output": 1}, "n_output"),
        ({"step": 0.0}, "step"),
        ({"energy_tolerance": -1.0}, "energy_tolerance"),
    ],
)
def test_invalid_arguments_name_the_argument(kwargs, field):
    arguments = {"duration": 1.0, **kwargs}
    with pytest.raises(SimulationError, match=f"^{field}: "):
        simulate(centre_pair(1.0, 1.0, 100.0), **arguments)


def test_a_step_that_cannot_resolve_the_motion_is_reported_not_printed():
    trajectory = simulate(centre_pair(1.0, 1.0, 100.0), 20.0, integrator="verlet", step=0.3)
    assert trajectory.status in ("nonfinite", "energy_error")
    assert trajectory.message
    assert np.all(np.isfinite(trajectory.x))
    assert trajectory.t[-1] < 20.0


def test_a_slipping_hoop_matches_an_independent_solve_ivp_of_the_slipping_equations():
    """Hoop slipping, cylinder rolling, centre spring (docs/physics.md (M19)), written out by hand:
    m1 x1'' = F1 + f, I1 phi1'' = -R f, f = -mu_k m1 g sign(v_s); 1.5 m2 x2'' = -F1."""
    from scipy.integrate import solve_ivp

    m1, m2, k, radius, mu_k = 1.0, 1.0, 100.0, 0.1, 0.15
    system = make_system(
        [
            body("hoop", "hoop", x=0.0, mu_static=0.2, mu_kinetic=mu_k),
            body("cyl", "cylinder", x=0.45, mu_static=5.0),
        ],
        [spring("hoop", "cyl", stiffness=k, rest_length=0.5)],
    )
    trajectory = simulate(system, 1.0, rtol=1e-12, on_slip="continue", n_output=1001)
    assert trajectory.events[0] == {"kind": "slip", "time": 0.0, "body": "hoop"}
    end = trajectory.events[1]["time"]
    assert trajectory.events[1]["kind"] in ("stick", "reverse")

    def rhs(_t, y):
        x1, _phi1, x2, u1, w1, u2 = y
        force_on_hoop = k * (x2 - x1 - 0.5)
        friction = mu_k * m1 * G  # the slip velocity is negative: friction along +x
        return [
            u1,
            w1,
            u2,
            (force_on_hoop + friction) / m1,
            -radius * friction / (m1 * radius**2),
            -force_on_hoop / (1.5 * m2),
        ]

    reference = solve_ivp(
        rhs,
        (0.0, end),
        [0.0, 0.0, 0.45, 0.0, 0.0, 0.0],
        method="DOP853",
        rtol=1e-13,
        atol=1e-15,
        dense_output=True,
    )
    during = trajectory.t < end
    expected = reference.sol(trajectory.t[during])
    np.testing.assert_allclose(trajectory.x[during, 0], expected[0], atol=1e-8)
    np.testing.assert_allclose(trajectory.phi[during, 0], expected[1], atol=1e-8)
    np.testing.assert_allclose(trajectory.x[during, 1], expected[2], atol=1e-8)
    # the slip velocity reaches zero exactly at the event
    u1, w1 = reference.sol(end)[3:5]
    assert abs(u1 - radius * w1) <= 1e-9


def test_progress_is_reported_in_order_up_to_the_end():
    fractions = []
    # progress comes once per chunk of about 2e5 steps
    simulate(
        centre_pair(1.0, 1.0, 100.0, mu_static=math.inf),
        60.0,
        step=1e-4,
        n_output=601,
        progress=fractions.append,
    )
    assert fractions and fractions == sorted(fractions)
    assert fractions[-1] == 1.0 and len(fractions) >= 3


def test_trajectory_tables_and_views_come_from_the_outputs_layer():
    import rollspring  # registers the views

    trajectory = simulate(centre_pair(1.0, 1.3, 100.0), 0.5, n_output=51)
    frame = trajectory.to_pandas()
    assert list(frame.index) == list(trajectory.t)
    np.testing.assert_array_equal(frame["cyl.x"], trajectory.x[:, 1])
    assert frame.attrs["units"]["hoop.friction"] == "N"
    data = trajectory.to_xarray()
    np.testing.assert_array_equal(data["tension"].values, trajectory.spring_tension)
    player = trajectory.animate(fps=4, dpi=20).data  # Matplotlib's JS player, self-contained
    assert player.count("data:image/png;base64,") == 3 and "http" not in player
    assert callable(rollspring.presenters.PRESENTERS["animate"])


def test_a_view_without_the_outputs_layer_is_a_clear_error(monkeypatch):
    from rollspring import presenters

    monkeypatch.setattr(presenters, "PRESENTERS", {})
    trajectory = simulate(centre_pair(1.0, 1.3, 100.0), 0.1, n_output=3)
    with pytest.raises(SimulationError, match=r"to_pandas is provided by rollspring\.outputs"):
        trajectory.to_pandas()


def test_general_states_of_rows_are_the_formula() -> None:
    """[x0 + s q, rho q, s v, rho v] per row (computed transposed for speed), and per state."""
    from rollspring.simulate.run_state import general_state

    system = make_system(
        [body("h", "hoop", x=0.0), body("m", "slider", radius=0.05, x=0.5)],
        [spring("h", "m", rest_length=0.5)],
    )
    arrays = system_arrays(system)
    rng = np.random.default_rng(3)
    q, v, x0 = rng.normal(size=(7, 2)), rng.normal(size=(7, 2)), rng.normal(size=2)
    expected = np.concatenate(
        [x0 + arrays.scale * q, arrays.rolls * q, arrays.scale * v, arrays.rolls * v], axis=-1
    )
    states = general_state(arrays, q, v, x0)
    assert np.array_equal(states, expected) and states.flags.c_contiguous
    assert np.array_equal(general_state(arrays, q[3], v[3], x0), expected[3])


def test_level_springs_keep_the_normal_forces_constant_and_nothing_is_refined() -> None:
    """Centre springs on one level: N = m g at every instant, exactly (the summary's minimum is
    every row's); with a tilted spring N varies and its minimum is refined between rows."""
    level = simulate(load_system("hoop-cylinder"), 2.0)
    assert np.all(level.normal == level.normal[0])
    for i, name in enumerate(level.ids):
        assert level.summary["min_normal_force"][name] == level.normal[0, i]
    tilted = make_system(
        [body("h", "hoop", x=0.0, track_height=0.05), body("c", "cylinder", x=0.49)],
        [spring("h", "c", rest_length=0.5)],
    )
    run = simulate(tilted, 2.0)
    assert np.ptp(run.normal[:, 0]) > 0
    assert run.summary["min_normal_force"]["h"] <= float(np.min(run.normal[:, 0]))


@pytest.mark.parametrize(("gravity", "mu_static"), [(0.0, 0.5), (9.81, 0.0)])
def test_zero_friction_at_zero_normal_force_is_no_slip(gravity: float, mu_static: float) -> None:
    """No spring, so every body needs f = 0; with N = 0 (no gravity) or mu_s = 0 the no-slip
    condition |f| <= mu_s N holds with equality: the bodies roll on, no event (the rule was
    |f| >= mu_s N, which called 0 >= 0 a slip and then found no crossing: "nonfinite")."""
    from rollspring.model import system_from_dict
    from rollspring.simulate import simulate_batch

    system = system_from_dict(
        {
            "gravity": gravity,
            "bodies": [
                {
                    "id": "a",
                    "shape": "hoop",
                    "mass": 1.0,
                    "radius": 0.1,
                    "x": 0.0,
                    "mu_static": mu_static,
                    "v": 0.3,
                },
                {
                    "id": "b",
                    "shape": "cylinder",
                    "mass": 1.0,
                    "radius": 0.1,
                    "x": 1.0,
                    "mu_static": mu_static,
                },
            ],
        }
    )
    run = simulate(system, 1.0)
    assert run.status == "finished", run.message
    assert run.events == []
    # uniform rolling: x = x0 + v t exactly
    assert run.x[-1, 0] == pytest.approx(0.3, rel=1e-12)
    assert run.x[-1, 1] == 1.0
    batch = simulate_batch(system, {"gravity": [gravity, gravity]}, 1.0)
    assert list(batch.status_names) == ["finished", "finished"]


def test_the_summary_names_the_integrators_actually_used() -> None:
    """A run that slips from its first instant runs on DOP853 alone and says so (it used to
    report the symplectic scheme chosen beforehand and its step); one that switches back and
    forth counts the steps of each."""
    slipping = simulate(wall_cylinder(0.2, 0.3, 0.2), 0.1, on_slip="continue")
    assert slipping.events[0] == {"kind": "slip", "time": 0.0, "body": "c"}
    assert [e["kind"] for e in slipping.events] == ["slip"]  # slips all along
    assert slipping.integrator == "dop853"
    assert slipping.step is None and slipping.summary["step"] is None
    assert list(slipping.steps_by_integrator) == ["dop853"]
    assert slipping.n_steps == slipping.steps_by_integrator["dop853"] > 0
    assert slipping.summary["steps_by_integrator"] == slipping.steps_by_integrator
    assert slipping.summary["integrator"] == "dop853"

    stick_slip = simulate(wall_cylinder(0.1, 0.3, 0.25), 2.0, on_slip="continue")
    kinds = [e["kind"] for e in stick_slip.events]
    assert kinds[:2] == ["slip", "stick"]
    used = stick_slip.steps_by_integrator
    assert list(used) == ["dop853", stick_slip.integrator.split("+")[1]]
    assert stick_slip.integrator == "+".join(used)
    assert all(count > 0 for count in used.values())
    assert stick_slip.n_steps == sum(used.values()) == stick_slip.summary["steps"]
    assert stick_slip.step is not None  # the symplectic scheme's step

    rolling = simulate(load_system("hoop-cylinder"), 1.0)
    assert list(rolling.steps_by_integrator) == [rolling.integrator]
    assert rolling.steps_by_integrator[rolling.integrator] == rolling.n_steps


def test_integrator_words_name_each_integrator_and_its_steps() -> None:
    from rollspring.outputs.numbers import integrator_words

    assert integrator_words({"kahanli8": 1130}, 0.00885) == "kahanli8, 1130 steps of 0.00885 s"
    assert (
        integrator_words({"yoshida6": 400, "dop853": 34}, 0.005)
        == "yoshida6, 400 steps of 0.005 s; dop853, 34 adaptive steps"
    )
    assert integrator_words({}, 0.005, "yoshida6") == "yoshida6, 0 steps"


def _one_body(shape: str, at: dict, stiffness: float, v: float, anchor_y: float = 0.1):
    from rollspring.model import system_from_dict

    return system_from_dict(
        {
            "bodies": [{"id": "h", "shape": shape, "mass": 1.0, "radius": 0.1, "x": 0.1, "v": v}],
            "anchors": [{"id": "w", "x": -0.5, "y": anchor_y}],
            "springs": [
                {"ends": ["w", "h"], "stiffness": stiffness, "rest_length": 0.55, "at": [{}, at]}
            ],
        }
    )


@pytest.mark.parametrize(
    ("shape", "at"),
    [
        ("hoop", {"height": 0.15}),
        ("hoop", {"height": 0.05}),
        ("cylinder", {"radius": 0.07, "angle": 90.0}),
        ("sphere", {"height": 0.15}),
        ("shell", {"radius": 0.07, "angle": 90.0}),
    ],
)
def test_default_settings_keep_their_own_energy_tolerance(shape: str, at: dict) -> None:
    """Large swings (v = 2 m/s on a soft spring) are stiffer than the linear frequencies that
    choose the step: the run is started again with the step its energy error asks for, so the
    default settings pass their own tolerance (these ended in "energy_error", 5e-6 to 4e-4)."""
    run = simulate(_one_body(shape, at, 5.0, 2.0), 10.0)
    assert run.status in ("finished", "slip"), run.message
    assert run.summary["energy_error"] <= 100 * 1e-8 + 1e-12
    assert run.summary["retries"] >= 1
    # a given step is the caller's: never changed
    fixed = simulate(_one_body(shape, at, 5.0, 2.0), 10.0, step=0.01)
    assert fixed.step == pytest.approx(0.01) and fixed.summary["retries"] == 0


def test_a_spring_through_zero_length_is_named_as_the_reason() -> None:
    """The centre spring's anchor is level with the centre and the hoop rolls through it: the
    spring's force turns over at once, no step keeps the energy, and the message says why."""
    run = simulate(_one_body("hoop", {}, 5.0, 2.0), 10.0)
    assert run.status == "energy_error"
    assert "spring 0 passes through (nearly) zero length" in run.message
    assert run.summary["retries"] == 3
    assert math.isfinite(run.summary["energy_error"])


def test_a_rim_spring_hoop_passes_at_default_settings() -> None:
    """The issue's case: a hoop with a rim spring (k = 22, v = 2) failed its own energy
    tolerance at default settings (1.37e-6 against 1e-6)."""
    run = simulate(_one_body("hoop", {"radius": 0.1, "angle": 0.0}, 22.0, 2.0, 0.2), 10.0)
    assert run.status != "energy_error", run.message
    assert run.summary["energy_error"] <= 1e-6


def test_the_summary_energy_error_is_the_one_the_message_reports() -> None:
    """Relative to the energy at release, as the run's own check: a blow-up by a factor of
    hundreds is an error of hundreds (the summary divided by the largest |E| and showed ~1)."""
    run = simulate(load_system("hoop-cylinder"), 10.0, integrator="verlet", step=0.2)
    assert run.status == "energy_error"
    reported = float(run.message.split("the energy error ")[1].split()[0])
    assert reported > 10
    assert run.summary["energy_error"] == pytest.approx(reported, rel=5e-3)
    e0 = run.energy[0]
    assert run.summary["energy_error"] == pytest.approx(np.max(np.abs(run.energy - e0)) / e0)

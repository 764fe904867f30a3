"""simulate_batch against exact solutions and a SciPy reference: modal motion of the centre
pair, an off-centre/anchored/slider system run by run, slip and lift-off instants, energy,
convergence orders, independence of the runs, and the parameter errors."""

from __future__ import annotations

import json
import math

import numpy as np
import pytest
import scipy.integrate
import scipy.optimize

from rollspring.analysis import analyze
from rollspring.errors import ModelError, SimulationError
from rollspring.physics import contact_forces, generalized_forces, system_arrays
from rollspring.simulate.batch import (
    CHECK_COST,
    METRIC_PHASE,
    SAMPLE_COST,
    SCHEMES,
    STATUS_FINISHED,
    STATUS_LIFTOFF,
    STATUS_NONFINITE,
    STATUS_SLIP,
    run_cost,
    simulate_batch,
)
from tests.conftest import body, make_system, spring

G = 9.81
REST = 0.5


# --------------------------------------------------------------------------------------------
# the centre pair (the paper's Fig. 2): exactly linear while rolling


def centre_pair():
    """Hoop and cylinder (R = 0.1) joined at their centres by a spring of rest length 0.5; every
    run sets masses, stiffness, start and velocities through the same parameter keys."""
    return make_system(
        [body("hoop", "hoop", x=0.0), body("cyl", "cylinder", x=REST)],
        [spring("hoop", "cyl", stiffness=100.0, rest_length=REST)],
    )


def pair_parameters(m1, m2, k, *, compression=0.0, v_rel=0.0, mu=10.0):
    """Parameters of the centre pair: the spring compressed by ``compression`` and the bodies
    moving apart at ``v_rel`` with X-hat at rest (2 m1 v1 + 1.5 m2 v2 = 0)."""
    m1, m2, k = (np.asarray(a, dtype=float) for a in (m1, m2, k))
    w1, w2 = 2 * m1, 1.5 * m2
    return {
        "bodies.hoop.mass": m1,
        "bodies.cyl.mass": m2,
        "springs.0.stiffness": k,
        "bodies.cyl.x": REST - np.asarray(compression, dtype=float) + 0 * m1,
        "bodies.hoop.v": -w2 / (w1 + w2) * v_rel,
        "bodies.cyl.v": w1 / (w1 + w2) * v_rel,
        "bodies.hoop.mu_static": mu + 0 * m1,
        "bodies.cyl.mu_static": mu + 0 * m1,
    }


def pair_omega(m1, m2, k):
    """docs/physics.md 7.1: Omega^2 = k/(2 m1) + 2k/(3 m2)."""
    return np.sqrt(k / (2 * m1) + 2 * k / (3 * m2))


def pair_exact(m1, m2, k, compression, v_rel, t):
    """x1, x2 of the pair: X-hat stays put, the separation is
    REST - compression cos(Omega t) + (v_rel/Omega) sin(Omega t)."""
    m1, m2, k = (np.asarray(a, dtype=float)[..., None] for a in (m1, m2, k))
    omega = pair_omega(m1, m2, k)
    w1, w2 = 2 * m1 / (2 * m1 + 1.5 * m2), 1.5 * m2 / (2 * m1 + 1.5 * m2)
    x_hat = w2 * (REST - np.asarray(compression, dtype=float)[..., None])
    separation = (
        REST
        - np.asarray(compression, dtype=float)[..., None] * np.cos(omega * t)
        + np.asarray(v_rel, dtype=float)[..., None] / omega * np.sin(omega * t)
    )
    return x_hat - w2 * separation, x_hat + w1 * separation


def sampling_factor(result):
    """The smallest fraction of an extreme of a sinusoid at the fastest frequency that the
    metric samples (omega h metric_every rad apart, at most METRIC_PHASE unless every step) can
    see: cos(phase / 2)."""
    phase = result.omega_max * result.step * result.metric_every
    assert phase <= METRIC_PHASE or result.metric_every == 1
    return math.cos(phase / 2)


def test_centre_pair_batch_matches_the_exact_modal_solution():
    rng = np.random.default_rng(7)
    n = 24
    m1, m2 = rng.uniform(0.3, 3.0, n), rng.uniform(0.3, 3.0, n)
    k = rng.uniform(20.0, 500.0, n)
    compression = 0.01
    duration = 20.0
    result = simulate_batch(
        centre_pair(),
        pair_parameters(m1, m2, k, compression=compression),
        duration,
        rtol=1e-10,
        keep_trajectories=True,
        n_output=101,
    )
    assert result.n_runs == n and np.all(result.status == STATUS_FINISHED)
    assert np.all(np.isnan(result.first_slip_time)) and np.all(result.first_slip_body == -1)
    omega = pair_omega(m1, m2, k)
    # positions at the output times, to the phase accuracy rtol asks for
    x1, x2 = pair_exact(m1, m2, k, np.full(n, compression), np.zeros(n), result.t)
    error = np.maximum(np.abs(result.x[:, :, 0] - x1), np.abs(result.x[:, :, 1] - x2)).max()
    assert error <= 1e-8 * compression
    np.testing.assert_allclose(result.final_x, result.x[:, -1, :], rtol=0, atol=1e-15)
    # the measured period (minima of the spring length, interpolated) is 2 pi / Omega
    np.testing.assert_allclose(result.period_measured, 2 * np.pi / omega, rtol=1e-9)
    # X-hat is stationary (M11); the CM swings by m1 m2 A / ((m1+m2)(4m1+3m2)) (docs/physics.md 7.1)
    assert np.all(result.stationary_amplitude <= 1e-9 * compression)  # rounding only
    cm = m1 * m2 * compression / ((m1 + m2) * (4 * m1 + 3 * m2))
    assert np.all(result.cm_amplitude <= cm * (1 + 1e-9))
    assert np.all(result.cm_amplitude >= cm * (1 + sampling_factor(result)) / 2 * (1 - 1e-9))
    # friction f = -F/2 on the hoop, -F/3 on the cylinder (M10), largest at the release
    np.testing.assert_allclose(
        result.max_friction_ratio[:, 0], k * compression / (2 * m1 * G), rtol=1e-9
    )
    np.testing.assert_allclose(
        result.max_friction_ratio[:, 1], k * compression / (3 * m2 * G), rtol=1e-9
    )
    np.testing.assert_allclose(result.min_normal_force, np.stack([m1, m2], -1) * G, rtol=1e-15)
    # the energy error of an order-6 symplectic step at this tolerance
    assert np.all(result.energy_error <= 1e-8)


# --------------------------------------------------------------------------------------------
# a general system against SciPy, run by run


def general_system(k_ab=80.0, m_c=0.7, r_a=0.1):
    """Off-centre and height attachments, a wall anchor, a slider, a constant off-centre force,
    a sphere; rolling is enforced (mu_s = inf) so every run follows J q'' = Q(q) to the end."""
    roll = {"mu_static": math.inf}
    return make_system(
        [
            body("a", "hoop", mass=1.0, radius=r_a, x=0.0, **roll),
            body("b", "cylinder", mass=2.0, radius=0.15, x=0.6, **roll),
            body("c", "sphere", mass=m_c, radius=0.08, x=1.3, v=0.2, **roll),
            body("d", "slider", mass=0.5, radius=0.05, x=1.9),
        ],
        [
            spring(
                "a", "b", stiffness=k_ab, rest_length=0.55, at=[{"radius": 0.06, "angle": 60.0}, {}]
            ),
            spring("w", "a", stiffness=50.0, rest_length=0.45, at=[{}, {"height": 0.17}]),
            spring(
                "b", "c", stiffness=60.0, at=[{"height": 0.05}, {"radius": 0.05, "angle": 200.0}]
            ),
            spring("c", "d", stiffness=40.0, rest_length=0.62),
        ],
        anchors=[{"id": "w", "x": -0.5, "y": 0.2}],
        forces=[{"body": "c", "at": {"radius": 0.04, "angle": 30.0}, "fx": 0.3, "fy": -0.5}],
    )


GENERAL_RUNS = {
    "springs.0.stiffness": [80.0, 140.0, 60.0],
    "bodies.c.mass": [0.7, 0.4, 1.1],
    "bodies.a.radius": [0.1, 0.12, 0.09],
}  # radius moves a's height attachment


def reference(system, t_eval, duration):
    """J q'' = Q(q) (rollspring.physics, (M7)) by DOP853 at rtol 1e-12 from the placement."""
    arrays = system_arrays(system)
    n = arrays.n_bodies

    def rhs(_, z):
        return np.concatenate([z[n:], generalized_forces(arrays, z[:n]) / arrays.inertia])

    start = np.concatenate([np.zeros(n), arrays.v0 / arrays.scale])
    solution = scipy.integrate.solve_ivp(
        rhs,
        (0.0, duration),
        start,
        method="DOP853",
        rtol=1e-12,
        atol=1e-14,
        t_eval=t_eval,
        dense_output=True,
    )
    return arrays, solution


def test_each_batch_run_equals_a_scipy_integration_of_its_own_system():
    duration = 3.0
    result = simulate_batch(
        general_system(), GENERAL_RUNS, duration, rtol=1e-10, keep_trajectories=True, n_output=31
    )
    assert np.all(result.status == STATUS_FINISHED)
    for run in range(result.n_runs):
        system = general_system(
            k_ab=GENERAL_RUNS["springs.0.stiffness"][run],
            m_c=GENERAL_RUNS["bodies.c.mass"][run],
            r_a=GENERAL_RUNS["bodies.a.radius"][run],
        )
        arrays, solution = reference(system, result.t, duration)
        n = arrays.n_bodies
        x_ref = arrays.x0 + arrays.scale * solution.y[:n].T
        scale = np.ptp(x_ref, axis=0).max()
        assert np.abs(result.x[run] - x_ref).max() <= 1e-9 * scale
        np.testing.assert_allclose(
            result.final_v[run],
            arrays.scale * solution.y[n:, -1],
            rtol=0,
            atol=1e-9 * np.abs(solution.y[n:]).max(),
        )
        # extremes of |f|/N and N over a dense reference, up to the sampling of the metrics
        q = solution.sol(np.linspace(0.0, duration, 30001))[:n].T
        friction, normal = contact_forces(arrays, q)
        ratio = np.max(np.abs(friction) / normal, axis=0)
        assert np.all(result.max_friction_ratio[run] <= ratio * (1 + 1e-9) + 1e-15)
        assert np.all(result.max_friction_ratio[run] >= ratio * sampling_factor(result) ** 2)
        low = normal.min(axis=0)
        assert np.all(result.min_normal_force[run] >= low - 1e-9 * np.abs(low))
        assert np.all(
            result.min_normal_force[run]
            <= low + (normal.max(axis=0) - low) * (1 - sampling_factor(result))
        )


def test_energy_error_is_small_and_does_not_grow():
    """Yoshida-4 is symplectic: the energy error oscillates, bounded, instead of drifting; it
    falls as h^4."""
    step = 2e-3
    errors = [
        simulate_batch(
            general_system(), GENERAL_RUNS, duration, integrator="yoshida4", step=h
        ).energy_error
        for duration, h in ((2.0, step), (16.0, step), (2.0, step / 2))
    ]
    short, long, fine = errors
    assert np.all(short <= 1e-7)
    assert np.all(long <= 2.0 * short)  # eight times longer, no secular growth
    np.testing.assert_allclose(np.log2(short / fine), 4.0, atol=0.3)


def test_the_kernels_sine_and_cosine_are_within_two_ulps():
    """The generated kernels evaluate sin/cos by a polynomial LLVM can vectorise (batch._SINCOS)."""
    from numba import njit

    from rollspring.simulate import batch

    namespace = {"njit": njit, "math": math, "np": np}
    exec(batch._SINCOS, namespace)
    sincos = namespace["sincos"]

    @njit(error_model="numpy")
    def evaluate(x, s, c):
        for j in range(x.shape[0]):
            s[j], c[j] = sincos(x[j])

    x = np.concatenate(
        [np.linspace(-20.0, 20.0, 200001), np.random.default_rng(1).uniform(-1e4, 1e4, 200000)]
    )
    s, c = np.empty_like(x), np.empty_like(x)
    evaluate(x, s, c)
    for mine, exact in ((s, np.sin(x)), (c, np.cos(x))):
        assert np.all(np.abs(mine - exact) <= 2 * np.spacing(np.maximum(np.abs(exact), 0.5)))


# --------------------------------------------------------------------------------------------
# integrators


@pytest.mark.parametrize("integrator", ["verlet", "yoshida4"])
def test_convergence_order(integrator):
    m1, m2, k = np.array([1.0, 0.5]), np.array([1.0, 2.0]), np.array([100.0, 300.0])
    compression, duration = 0.01, 5.0
    order = SCHEMES[integrator][0]
    errors = []
    for h in (4e-3, 2e-3):
        result = simulate_batch(
            centre_pair(),
            pair_parameters(m1, m2, k, compression=compression),
            duration,
            integrator=integrator,
            step=h,
            keep_trajectories=True,
            n_output=51,
        )
        assert result.integrator == integrator and result.step == pytest.approx(h)
        x1, _ = pair_exact(m1, m2, k, np.full(2, compression), np.zeros(2), result.t)
        errors.append(np.abs(result.x[:, :, 0] - x1).max(axis=1))
    np.testing.assert_allclose(np.log2(errors[0] / errors[1]), order, atol=0.3)


def test_step_from_rtol_and_auto():
    """The step keeps the phase error C_p (omega h)^p omega T <= rtol, duration is a whole number
    of steps, and auto takes the cheapest scheme."""
    m1, m2, k = np.array([1.0, 0.4]), np.array([1.0, 0.6]), np.array([100.0, 400.0])
    params = pair_parameters(m1, m2, k, compression=0.01)
    omega = pair_omega(m1, m2, k).max()
    duration = 7.3
    for integrator in ("verlet", "yoshida4", "yoshida6"):
        order, _weights, constant = SCHEMES[integrator]
        result = simulate_batch(centre_pair(), params, duration, rtol=1e-7, integrator=integrator)
        assert result.step * result.n_steps == pytest.approx(duration, rel=1e-14)
        assert result.omega_max == pytest.approx(omega, rel=1e-12)
        phase = constant * (omega * result.step) ** order * omega * duration
        assert phase <= 1e-7 * (1 + 1e-9)
        # and not much finer than needed: one step fewer would break the bound
        longer = duration / (result.n_steps - 1)
        assert constant * (omega * longer) ** order * omega * duration > 1e-7
    runs = {
        name: simulate_batch(centre_pair(), params, duration, rtol=1e-7, integrator=name)
        for name in SCHEMES
    }
    costs = {name: run_cost(name, r.n_steps, r.metric_every) for name, r in runs.items()}
    for name, r in runs.items():  # metric samples METRIC_PHASE apart, or every step
        assert omega * r.step * r.metric_every <= METRIC_PHASE or r.metric_every == 1
        assert omega * r.step * (r.metric_every + 1) > METRIC_PHASE
        assert costs[name] == pytest.approx(
            r.n_steps * (len(SCHEMES[name][1]) + CHECK_COST)
            + math.ceil(r.n_steps / r.metric_every) * SAMPLE_COST
        )
    chosen = simulate_batch(centre_pair(), params, duration, rtol=1e-7).integrator
    assert costs[chosen] == min(costs.values())


# --------------------------------------------------------------------------------------------
# slip and lift-off


def test_slip_instant_and_no_slip_just_above_the_needed_mu():
    """Released at rest length, the pair's friction ratios are r_i |sin(Omega t)| with
    r = (k V/Omega)/(2 m1 g), (k V/Omega)/(3 m2 g): with mu_s below max r the body with the
    larger r slips at asin(mu_s/r)/Omega, before the first maximum at T/4; just above, never."""
    m1, m2, k, v_rel = 1.3, 0.8, 150.0, 0.12
    base = make_system(
        [
            body("hoop", "hoop", mass=m1, x=0.0, v=-1.5 * m2 / (2 * m1 + 1.5 * m2) * v_rel),
            body("cyl", "cylinder", mass=m2, x=REST, v=2 * m1 / (2 * m1 + 1.5 * m2) * v_rel),
        ],
        [spring("hoop", "cyl", stiffness=k, rest_length=REST)],
    )
    needed = analyze(base).required_mu
    omega = float(pair_omega(m1, m2, k))
    amplitude = k * v_rel / omega
    np.testing.assert_allclose(
        needed, [amplitude / (2 * m1 * G), amplitude / (3 * m2 * G)], rtol=1e-9
    )
    top = float(needed.max())
    first = int(np.argmax(needed))
    fractions = np.array([0.3, 0.8, 0.99, 1.001, 1.3])
    n = fractions.size
    params = pair_parameters(
        np.full(n, m1), np.full(n, m2), np.full(n, k), v_rel=v_rel, mu=top * fractions
    )
    duration = 3 * 2 * math.pi / omega
    for stop in (True, False):
        result = simulate_batch(centre_pair(), params, duration, rtol=1e-10, stop_on_slip=stop)
        slipped = fractions < 1
        assert np.all(result.status[slipped] == STATUS_SLIP)
        assert np.all(result.status[~slipped] == STATUS_FINISHED)
        assert np.all(result.first_slip_body[slipped] == first)
        assert np.all(np.isnan(result.first_slip_time[~slipped]))
        # instant: the margin r|sin| - mu is interpolated linearly between steps, an error of
        # at most h^2 max|margin''| / (8 |margin'|) at the crossing
        instant = np.arcsin(fractions[slipped]) / omega
        h = result.step
        bound = h**2 * top * omega**2 / (8 * top * omega * np.cos(omega * instant))
        assert np.all(np.abs(result.first_slip_time[slipped] - instant) <= bound + 1e-12)
        assert np.all(instant < 2 * math.pi / omega / 4)
        # just above the needed mu: the largest ratio seen is the needed one (sampled)
        assert np.all(result.max_friction_ratio[~slipped, first] <= top * (1 + 1e-9))
        assert np.all(result.max_friction_ratio[~slipped, first] >= top * sampling_factor(result))
        # a stopped run holds its state at the end of its slip step; a continued one rolls on
        ends = np.where(slipped & stop, np.ceil(result.first_slip_time / h) * h, duration)
        x1, x2 = pair_exact(
            np.full(n, m1),
            np.full(n, m2),
            np.full(n, k),
            np.zeros(n),
            np.full(n, v_rel),
            ends[:, None],
        )
        np.testing.assert_allclose(
            result.final_x, np.stack([x1[:, 0], x2[:, 0]], -1), rtol=0, atol=1e-10
        )


def test_liftoff_instant_matches_the_reference():
    """A hoop rolling away below a wall hook: the spring's upward pull k dy (1 - L0/l) grows
    with its length until N = m g - F_y reaches 0 (rolling enforced, mu_s = inf)."""
    system = make_system(
        [body("hoop", "hoop", x=0.0, v=-4.5, mu_static=math.inf)],
        [spring("hook", "hoop", stiffness=20.0, rest_length=0.3)],
        anchors=[{"id": "hook", "x": 0.5, "y": 0.7}],
    )
    duration = 1.0
    result = simulate_batch(system, {"springs.0.stiffness": [20.0, 20.0]}, duration, rtol=1e-10)
    assert np.all(result.status == STATUS_LIFTOFF)
    assert np.all(result.first_slip_body == 0)
    arrays, solution = reference(system, None, duration)

    def normal(t):
        return float(contact_forces(arrays, solution.sol(t)[:1])[1][0])

    grid = np.linspace(0.0, duration, 2001)
    crossing = int(np.argmax([normal(t) < 0 for t in grid]))
    assert crossing > 0
    instant = scipy.optimize.brentq(normal, grid[crossing - 1], grid[crossing], xtol=1e-14)
    # N is interpolated linearly between steps: error h^2 |N''| / (8 |N'|) at the crossing
    d = 1e-4
    slope = (normal(instant + d) - normal(instant - d)) / (2 * d)
    curvature = (normal(instant + d) - 2 * normal(instant) + normal(instant - d)) / d**2
    bound = result.step**2 * abs(curvature) / (8 * abs(slope))
    assert np.all(np.abs(result.first_slip_time - instant) <= 2 * bound + 1e-12)
    # the run stopped at the end of that step: the metrics include it, N just below 0 there
    end = math.ceil(instant / result.step) * result.step
    np.testing.assert_allclose(result.min_normal_force[:, 0], normal(end), rtol=0, atol=1e-8)
    assert normal(end) < 0.0


def test_a_diverging_run_is_reported_nonfinite():
    """Verlet at omega h = 3 (beyond its stability limit 2) overflows; the other run is fine."""
    m1, m2, k = np.ones(2), np.ones(2), np.array([1.0, 1e4])
    omega = float(pair_omega(1.0, 1.0, 1e4))
    result = simulate_batch(
        centre_pair(),
        pair_parameters(m1, m2, k, compression=0.01),
        4000 * 3 / omega,
        integrator="verlet",
        step=3 / omega,
        stop_on_slip=False,
    )
    assert list(result.status) == [STATUS_FINISHED, STATUS_NONFINITE]
    assert np.isfinite(result.final_x[0]).all()


# --------------------------------------------------------------------------------------------
# runs, outputs, parameters


def test_runs_are_independent_and_broadcast():
    """The motion of run i of a batch is bit for bit that of the batch of run i alone (same
    keys, same kernel, same step; only the sampling of the metrics follows the fastest run);
    scalars broadcast; a batch size that is not a multiple of the block works."""
    rng = np.random.default_rng(3)
    n = 300
    params = pair_parameters(
        rng.uniform(0.5, 2.0, n), 1.0, rng.uniform(50, 150, n), compression=0.01
    )
    whole = simulate_batch(centre_pair(), params, 2.0, integrator="yoshida4", step=1e-3)
    for run in (0, 255, 256, 299):
        alone = simulate_batch(
            centre_pair(),
            {
                key: value[run : run + 1] if np.ndim(value) else value
                for key, value in params.items()
            },
            2.0,
            integrator="yoshida4",
            step=1e-3,
        )
        assert np.array_equal(alone.final_x[0], whole.final_x[run])
        assert np.array_equal(alone.final_v[0], whole.final_v[run])
        assert alone.period_measured[0] == pytest.approx(whole.period_measured[run], rel=1e-6)
    assert whole.parameters["bodies.cyl.mass"].shape == (n,)


def test_result_outputs():
    params = pair_parameters([1.0, 2.0], [1.0, 1.0], [100.0, 100.0], compression=0.01)
    result = simulate_batch(centre_pair(), params, 1.0, keep_trajectories=True, n_output=11)
    assert result.t.shape == (11,) and result.x.shape == (2, 11, 2)
    assert result.n_steps % 10 == 0
    np.testing.assert_array_equal(result.x[:, 0, :], [[0.0, REST - 0.01]] * 2)
    table = result.summary_table()
    assert "hoop.max_friction_ratio" in table.splitlines()[0]
    data = json.loads(json.dumps(result.to_dict()))
    assert data["columns"]["status"] == ["finished", "finished"]
    assert data["columns"]["bodies.hoop.mass"] == [1.0, 2.0]
    assert list(result.status_names) == ["finished", "finished"]


def test_uniform_motion_of_x_hat_is_removed():
    """Both bodies rolling at v0 with the spring at rest: the CM moves uniformly (half range
    v0 T / 2) and X-hat - V-hat t stays put."""
    v0, duration = 0.3, 2.0
    params = pair_parameters([1.0, 2.0], [1.5, 0.5], [100.0, 200.0])
    params["bodies.hoop.v"] = params["bodies.cyl.v"] = np.full(2, v0)
    result = simulate_batch(centre_pair(), params, duration)
    np.testing.assert_allclose(result.cm_amplitude, v0 * duration / 2, rtol=1e-12)
    assert np.all(result.stationary_amplitude <= 1e-12 * v0 * duration)
    np.testing.assert_allclose(
        result.final_x, [[v0 * duration, REST + v0 * duration]] * 2, rtol=1e-12
    )


def test_default_rest_length_follows_the_start():
    """A spring without rest_length is at rest in every run's placement: nothing moves."""
    system = make_system([body("a", x=0.0), body("b", x=0.5)], [spring("a", "b")])
    result = simulate_batch(system, {"bodies.b.x": [0.4, 0.7]}, 1.0)
    np.testing.assert_array_equal(result.final_x, [[0.0, 0.4], [0.0, 0.7]])
    assert np.all(np.isnan(result.period_measured))
    assert np.all(result.cm_amplitude == 0.0)


@pytest.mark.parametrize(
    ("parameters", "words"),
    [
        ({"bodies.ghost.mass": 1.0}, ["bodies.ghost.mass", "no body 'ghost'"]),
        ({"bodies.hoop.colour": 1.0}, ["bodies.hoop.colour", "unknown body quantity"]),
        ({"springs.1.stiffness": 1.0}, ["springs.1.stiffness", "no spring '1'"]),
        ({"springs.0.damping": 1.0}, ["springs.0.damping", "unknown spring quantity"]),
        ({"mass": 1.0}, ["'mass'", "unknown parameter path"]),
        (
            {"bodies.hoop.mass": [1.0, 2.0], "springs.0.stiffness": [1.0, 2.0, 3.0]},
            ["springs.0.stiffness", "has 3 values"],
        ),
        ({"bodies.hoop.mass": [1.0, np.nan]}, ["bodies.hoop.mass", "finite"]),
        ({"bodies.hoop.mass": [1.0, -1.0]}, ["bodies.hoop.mass", "> 0"]),
        ({"bodies.cyl.radius": 0.0}, ["bodies.cyl.radius", "> 0"]),
        ({"springs.0.stiffness": [np.inf]}, ["springs.0.stiffness", "finite"]),
        ({"bodies.hoop.mu_static": -0.1}, ["bodies.hoop.mu_static", ">= 0"]),
        ({"bodies.hoop.mu_kinetic": 2.0}, ["mu_kinetic", "exceeds mu_static"]),
        ({"bodies.hoop.mass": [[1.0]]}, ["bodies.hoop.mass", "1-D"]),
        ({"bodies.hoop.mass": []}, ["bodies.hoop.mass", "empty"]),
        ({"bodies.cyl.x": 0.0}, ["springs[0]", "coincide"]),
    ],
)
def test_invalid_parameters_are_model_errors(parameters, words):
    with pytest.raises(ModelError) as error:
        simulate_batch(centre_pair(), parameters, 1.0)
    message = str(error.value)
    assert "\n" not in message
    for word in words:
        assert word in message


def test_parameters_that_break_the_model_are_refused():
    slider = make_system(
        [body("a", x=0.0), body("s", "slider", radius=0.05, x=0.5)],
        [spring("a", "s", at=[{}, {"height": 0.05}])],
    )
    with pytest.raises(ModelError, match=r"springs\[0\]\.at\[1\]: 's' is a slider"):
        simulate_batch(slider, {"bodies.s.radius": [0.05, 0.06]}, 1.0)
    with pytest.raises(ModelError, match=r"names the same parameter as 'springs\.0\.stiffness'"):
        simulate_batch(
            centre_pair(), {"springs.0.stiffness": 1.0, "springs.00.stiffness": 2.0}, 1.0
        )


def test_invalid_arguments_and_damped_springs():
    with pytest.raises(ModelError, match=r"springs\[0\]\.damping.*undamped.*rollspring.simulate"):
        simulate_batch(
            make_system([body("a", x=0.0), body("b", x=0.5)], [spring("a", "b", damping=0.1)]),
            {},
            1.0,
        )
    for kwargs in ({"integrator": "rk4"}, {"rtol": 0.0}, {"n_output": 1}, {"step": -1.0}):
        with pytest.raises(SimulationError):
            simulate_batch(centre_pair(), {}, 1.0, **kwargs)
    with pytest.raises(SimulationError, match="duration"):
        simulate_batch(centre_pair(), {}, math.nan)

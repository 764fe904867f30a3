"""The linear analysis beyond the paper: equilibria, zero modes, damping, warnings."""

from __future__ import annotations

import math

import numpy as np
import pytest
import scipy.linalg
from hypothesis import given, settings
from hypothesis import strategies as st

from rollspring.analysis import analyze, find_equilibrium, normal_modes
from rollspring.physics import (
    generalized_forces,
    mass_matrix,
    spring_state,
    stiffness_matrix,
    system_arrays,
)
from tests.conftest import NO_EXACT_EQUILIBRIUM, body, make_system, spring


@settings(max_examples=40, deadline=None)
@given(
    st.floats(0.0, 0.1),
    st.floats(-180, 180),
    st.floats(0.0, 0.1),
    st.floats(-180, 180),
    st.floats(-0.05, 0.05),
    st.sampled_from(["hoop", "cylinder", "sphere"]),
)
def test_equilibrium_holds_the_zero_mode_of_an_off_centre_pair(r1, a1, r2, a2, strain, shape):
    """Q(q*) = 0 and the zero-mode coordinate of the initial placement is kept:
    V0(q*)^T M (q* - 0) = 0, so the motion oscillates about q* (docs/physics.md (M14)).
    Springs up to 5 cm from their rest length on 0.1 m bodies (rolls of up to ~1 rad); far
    larger deformations can have the nearest equilibrium several radians away, where "nearest"
    stops being well defined."""
    ends = [{"radius": r1, "angle": a1}, {"radius": r2, "angle": a2}]
    placed = make_system(
        [body("a", "hoop", x=0.0), body("b", shape, x=0.5)], [spring("a", "b", at=ends)]
    )
    length = float(spring_state(system_arrays(placed), np.zeros(2)).length[0])
    system = make_system(
        [body("a", "hoop", x=0.0), body("b", shape, x=0.5)],
        [spring("a", "b", rest_length=length + strain, at=ends)],
    )
    arrays = system_arrays(system)
    equilibrium = find_equilibrium(arrays)
    assert equilibrium.found
    q = equilibrium.q
    mass = mass_matrix(arrays)
    assert np.max(np.abs(generalized_forces(arrays, q))) < 1e-9
    _, vectors, kinds = normal_modes(mass, stiffness_matrix(arrays, q))
    zero = vectors[:, kinds == "zero"]
    assert zero.shape[1] == 1  # a free pair at rest length: one valley of equilibria
    assert abs(float(zero[:, 0] @ mass @ q)) < 1e-9


def test_no_equilibrium_gives_no_response_and_says_why() -> None:
    system = make_system(
        [body("h", "hoop", x=0.0), body("c", "cylinder", x=0.5)],
        [spring("h", "c")],
        forces=[{"body": "h", "fx": 1.0}],
    )
    result = analyze(system)
    assert not result.equilibrium.found
    assert result.amplitude is None and result.required_mu is None
    assert result.spring_split is None
    assert any("no equilibrium" in w for w in result.warnings)
    assert result.to_dict()["response"] is None


def test_modal_damping_ratio_of_a_damped_wall_spring() -> None:
    """One body on a wall spring at centre height: K = k R^2, C = c R^2,
    zeta = c R/(2 sqrt(k J))."""
    k, c, m, radius = 80.0, 1.5, 0.9, 0.2
    system = make_system(
        [body("c", "cylinder", mass=m, radius=radius, x=0.0)],
        [spring("wall", "c", stiffness=k, damping=c)],
        anchors=[{"id": "wall", "x": -0.5, "y": radius}],
    )
    result = analyze(system)
    inertia = 1.5 * m * radius**2
    (mode,) = result.modes
    assert mode.damping_ratio == pytest.approx(c * radius / (2 * math.sqrt(k * inertia)), rel=1e-12)
    assert any("damping" in w for w in result.warnings)
    assert result.to_dict()["modes"][0]["damping_ratio"] == pytest.approx(mode.damping_ratio)


def test_zero_gravity_with_enforced_rolling_is_quiet() -> None:
    system = make_system(
        [
            body("h", "hoop", x=0.0, mu_static=math.inf),
            body("c", "cylinder", x=0.49, mu_static=math.inf),
        ],
        [spring("h", "c", rest_length=0.5)],
        gravity=0.0,
    )
    result = analyze(system)
    assert result.warnings == []
    assert np.all(np.isinf(result.required_mu))  # N = 0 while friction is needed


def test_zero_gravity_without_enforced_rolling_slips() -> None:
    system = make_system(
        [body("h", "hoop", x=0.0), body("c", "cylinder", x=0.49)],
        [spring("h", "c", rest_length=0.5)],
        gravity=0.0,
    )
    warnings = analyze(system).warnings
    assert any("unbounded friction" in w for w in warnings)
    assert not any("lift off" in w for w in warnings)


def test_a_slider_pulled_up_harder_than_its_weight_cannot_rest() -> None:
    system = make_system(
        [body("s", "slider", mass=0.1, radius=0.05, x=0.0, v=2.0)],
        [spring("hook", "s", stiffness=50.0, rest_length=0.2)],
        anchors=[{"id": "hook", "x": 0.0, "y": 0.6}],
    )
    result = analyze(system)
    tension = 50.0 * (0.55 - 0.2)
    assert result.equilibrium_normal[0] == pytest.approx(0.1 * 9.81 - tension, rel=1e-12)
    assert any("'s' cannot rest on its track" in w for w in result.warnings)


@pytest.mark.parametrize(("speed", "lifts"), [(2.0, False), (5.0, True)])
def test_a_slider_under_a_slanted_spring_lifts_off_when_pushed_hard(speed, lifts) -> None:
    """N = mg - T_y(x) changes to first order when the hook is off to one side; the linear
    response predicts N < 0 at the larger speed (N range = N* -/+ |dN/dx| A)."""
    system = make_system(
        [body("s", "slider", mass=0.1, radius=0.05, x=0.0, v=speed)],
        [
            spring("hook", "s", stiffness=5.0, rest_length=0.5),
            spring("wall", "s", stiffness=20.0, rest_length=0.4849),
        ],
        anchors=[{"id": "hook", "x": 0.3, "y": 0.6}, {"id": "wall", "x": -0.5, "y": 0.05}],
    )
    result = analyze(system)
    low, high = result.normal_force_range[0]
    assert low < result.equilibrium_normal[0] < high
    assert (low < 0) == lifts
    assert any("'s' would lift off" in w for w in result.warnings) == lifts


def test_a_body_far_too_light_for_its_spring_slips() -> None:
    system = make_system(
        [body("h", "hoop", x=0.0, mass=0.01, mu_static=0.3), body("c", "cylinder", x=0.4)],
        [spring("h", "c", rest_length=0.5)],
    )
    result = analyze(system)
    assert any("'h' slips: the motion needs mu_s >=" in w for w in result.warnings)


def test_drift_of_free_parts_is_reported() -> None:
    system = make_system(
        [
            body("h", "hoop", x=0.0),
            body("c", "cylinder", x=0.49),
            body("loner", "sphere", x=2.0, v=0.3),
        ],
        [spring("h", "c", rest_length=0.5)],
    )
    result = analyze(system)
    assert result.stationary_weights is None  # two zero modes
    assert result.drift_velocity[2] == pytest.approx(0.3, rel=1e-12)
    assert result.drift_velocity[0] == 0.0
    assert any("drift" in w and "'loner' 0.3 m/s" in w for w in result.warnings)


def test_modes_agree_with_a_direct_eigensolution_of_the_presets() -> None:
    for name in ("wall-hoop-cylinder", "three-bodies"):
        from rollspring.model import load_system

        result = analyze(load_system(name))
        direct = scipy.linalg.eigvalsh(result.stiffness, result.mass)
        np.testing.assert_allclose(
            [max(m.eigenvalue, 0) for m in result.modes],
            np.clip(direct, 0, None),
            atol=1e-9 * direct.max(),
        )


@settings(max_examples=60, deadline=None)
@given(
    st.lists(st.floats(0.05, 20.0), min_size=1, max_size=5),
    st.integers(0, 2**32 - 1),
)
def test_normal_modes_are_scipys_generalised_eigh_without_scipy(inertia, seed) -> None:
    """K v = lambda M v with a diagonal M by NumPy's eigh of M^-1/2 K M^-1/2 (SciPy's sygvd
    reduction operation for operation): SciPy's eigenvalues and M-orthonormal vectors."""
    from rollspring.analysis.linear import generalized_eigh

    rng = np.random.default_rng(seed)
    n = len(inertia)
    root = rng.normal(size=(n, n))
    stiffness = root @ root.T - rng.uniform(0, 2) * np.eye(n)  # some negative eigenvalues too
    mass = np.diag(inertia)
    expected = scipy.linalg.eigh(stiffness, mass)
    for given_mass in (mass, np.asarray(inertia)):
        eigenvalues, vectors = generalized_eigh(given_mass, stiffness)
        np.testing.assert_allclose(eigenvalues, expected[0], rtol=1e-12, atol=1e-12)
        np.testing.assert_allclose(vectors.T @ mass @ vectors, np.eye(n), atol=1e-12)
        np.testing.assert_allclose(stiffness @ vectors, mass @ vectors * eigenvalues, atol=1e-10)
    full = mass + 0.1 * np.ones((n, n))  # a full M: SciPy's generalised problem
    np.testing.assert_allclose(
        generalized_eigh(full, stiffness)[0], scipy.linalg.eigh(stiffness, full)[0]
    )
    with pytest.raises(ValueError, match="not finite in this configuration"):  # NotFiniteError
        generalized_eigh(mass, np.full((n, n), np.nan))


@settings(max_examples=200, deadline=None)
@given(
    st.floats(-5, 5),
    st.floats(0, 5),
    st.floats(-4, 4),
    st.floats(0.1, 10),
    st.floats(0.0, 0.999),
    st.floats(-4, 4),
)
def test_the_friction_ratio_of_one_frequency_is_found_exactly(
    f_c, size_f, angle_f, n_c, reach, angle_n
):
    """max over the phase of |f_c + Re(a_f e^it)| / (N_c + Re(a_n e^it)): the maximum of a
    fine grid zoomed in on, never exceeded by it (up to rounding)."""
    from rollspring.analysis.modal import friction_ratio_sup

    a_f = size_f * complex(math.cos(angle_f), math.sin(angle_f))
    a_n = reach * n_c * complex(math.cos(angle_n), math.sin(angle_n))  # N > 0 throughout

    def ratio(theta):
        return np.abs(f_c + np.real(a_f * np.exp(1j * theta))) / (
            n_c + np.real(a_n * np.exp(1j * theta))
        )

    one = friction_ratio_sup(np.array([f_c]), np.array([[a_f]]), np.array([n_c]), np.array([[a_n]]))
    exact = float(one[0])
    grid = np.linspace(0, 2 * np.pi, 20_001)
    for _ in range(4):  # zoom in on the best grid point: the maximum to rounding
        best = float(grid[np.argmax(ratio(grid))])
        spacing = grid[1] - grid[0]
        grid = np.linspace(best - spacing, best + spacing, 2001)
    searched = float(np.max(ratio(grid)))
    assert exact == pytest.approx(searched, rel=1e-11, abs=1e-15)


@pytest.mark.parametrize("seed", range(5))
def test_the_friction_ratio_of_several_frequencies_is_the_supremum_over_the_phases(seed) -> None:
    """Independent phases (incommensurate groups): never exceeded by random phases, and
    reached by coordinate ascent over the phases (each phase in turn set to its best on a
    fine circle, from the best random start)."""
    from rollspring.analysis.modal import friction_ratio_sup

    rng = np.random.default_rng(seed)
    groups = int(rng.integers(2, 6))
    a_f = rng.normal(size=groups) + 1j * rng.normal(size=groups)
    a_n = 0.8 * (rng.normal(size=groups) + 1j * rng.normal(size=groups))
    f_c, n_c = float(rng.normal()), float(np.sum(np.abs(a_n)) * rng.uniform(1.05, 2.0))
    several = friction_ratio_sup(np.array([f_c]), a_f[:, None], np.array([n_c]), a_n[:, None])
    exact = float(several[0])

    def ratio(phases):
        turn = np.exp(1j * phases)
        return np.abs(f_c + np.real(turn @ a_f)) / (n_c + np.real(turn @ a_n))

    samples = rng.uniform(0, 2 * np.pi, (200_000, groups))
    values = ratio(samples)
    assert values.max() <= exact * (1 + 1e-12)
    phases = samples[np.argmax(values)].copy()
    circle = np.linspace(0, 2 * np.pi, 4001)
    for _ in range(30):
        for g in range(groups):
            trial = np.repeat(phases[None, :], circle.size, axis=0)
            trial[:, g] = circle
            phases[g] = circle[np.argmax(ratio(trial))]
    assert float(ratio(phases[None, :])[0]) == pytest.approx(exact, rel=1e-5)


def test_level_centre_springs_take_the_one_step_equilibrium_with_one_set_of_modes() -> None:
    """Horizontal centre springs: the equilibrium is one Newton step with the zero mode held,
    K and the modes computed once (the placement's are the equilibrium's), no SciPy."""
    import rollspring.analysis.linear as linear
    from rollspring.model import load_system

    for name in ("hoop-cylinder", "three-bodies", "wall-hoop-cylinder", "two-masses"):
        arrays = system_arrays(load_system(name))
        equilibrium = find_equilibrium(arrays)
        assert equilibrium.found and equilibrium.placement_modes is equilibrium.modes
        assert linear._level_centre_springs(arrays)
        q = equilibrium.q
        mass = mass_matrix(arrays)
        assert np.max(np.abs(generalized_forces(arrays, q))) <= 1e-12
        assert np.array_equal(equilibrium.stiffness, stiffness_matrix(arrays, q))
        _, vectors, kinds = equilibrium.modes
        assert np.max(np.abs(vectors[:, kinds == "zero"].T @ mass @ q), initial=0) < 1e-15
    tilted = system_arrays(
        make_system(
            [body("h", track_height=0.05), body("c", "cylinder", x=0.49)],
            [spring("h", "c", rest_length=0.5)],
        )
    )
    assert not linear._level_centre_springs(tilted)
    assert find_equilibrium(tilted).placement_modes is not None  # the search's first K


def test_level_stiffness_of_plain_floats_has_the_assemblys_bits() -> None:
    """A few level centre springs: the stiffness summed in plain floats is the vectorised
    assembly's and ``stiffness_matrix``'s, bit for bit, on seeded random level chains (mixed
    shapes and radii, centres at one height, walls, springs skipping a body)."""
    import rollspring.analysis.linear as linear

    rng = np.random.default_rng(27)
    shapes = ["hoop", "cylinder", "sphere", "shell", "slider"]
    for _ in range(12):
        n = int(rng.integers(1, 9))
        radii = rng.uniform(0.02, 0.2, n)
        bodies = [
            body(
                f"b{i}",
                str(rng.choice(shapes)),
                mass=float(rng.uniform(0.1, 5)),
                radius=float(radii[i]),
                x=0.6 * i,
                track_height=float(0.3 - radii[i]),
            )
            for i in range(n)
        ]
        springs = [
            spring(f"b{i}", f"b{i + 1}", stiffness=float(rng.uniform(1, 1e3)))
            | {"rest_length": float(rng.uniform(0.3, 0.9))}
            for i in range(n - 1)
        ]
        springs += [
            spring(f"b{i}", f"b{i + 2}", stiffness=float(rng.uniform(1, 1e3)))
            for i in range(n - 2)
            if rng.random() < 0.5
        ]
        anchors = [{"id": "wall", "x": -0.7, "y": 0.3}]
        springs.append(spring("wall", "b0", stiffness=float(rng.uniform(1, 1e3))))
        arrays = system_arrays(make_system(bodies, springs, anchors=anchors))
        dx, dy = linear._placement_vectors(arrays)
        lengths = np.sqrt(dx**2 + dy**2)
        assert linear._level_centre_springs(arrays, dx)
        fast = linear._level_stiffness(arrays, dx, lengths)
        with pytest.MonkeyPatch.context() as patch:  # the vectorised dense assembly
            patch.setattr(linear, "_FEW_SPRINGS", -1)
            assembled = linear._level_stiffness(arrays, dx, lengths)
        for other in (assembled, stiffness_matrix(arrays, np.zeros(n))):
            assert np.array_equal(fast.view(np.int64), (other + 0.0).view(np.int64))


def test_paper_system_equilibrium_is_the_exact_stationary_split() -> None:
    """Fig. 2: q* puts the spring at rest with X-hat unmoved, to rounding."""
    from rollspring.model import load_system

    arrays = system_arrays(load_system("hoop-cylinder"))
    q = find_equilibrium(arrays).q
    # the spring at its rest length, X-hat = (2 m1 x1 + 1.5 m2 x2)/3.5 where it started
    x = arrays.x0 + arrays.scale * q
    assert x[1] - x[0] == pytest.approx(0.5, rel=1e-15)
    assert 2 * x[0] + 1.5 * x[1] == pytest.approx(1.5 * 0.49, rel=1e-15)


def test_one_and_two_coordinates_are_lapacks_eigh_in_plain_floats() -> None:
    """The paper's systems have two coordinates: their modes come from plain floats that
    follow LAPACK's syevd (laev2 and steqr's rotation and sort) operation for operation, so
    NumPy's eigenvalues and eigenvectors, signs included, to the last bit or one ulp."""
    from rollspring.analysis.linear import _small_eigh

    rng = np.random.default_rng(7)
    differ = 0
    for k in range(20_000):
        a, b, c = rng.normal(size=3) * 10.0 ** rng.integers(-6, 6, size=3)
        if k % 7 == 1:
            b = 0.0  # diagonal
        elif k % 7 == 2:
            c = a  # equal diagonal
        elif k % 7 == 3:
            b = a * 1e-17  # below steqr's split threshold
        elif k % 7 == 4:
            a, b, c = (float(x) for x in rng.integers(-3, 4, size=3))  # ties, zeros
        inertia = rng.uniform(0.01, 10.0, size=2)
        stiffness = np.array([[a, b], [b, c]])
        expected = scipy.linalg.eigh(stiffness, np.diag(inertia))
        eigenvalues, vectors = _small_eigh(inertia.tolist(), stiffness.tolist())
        scale = max(float(np.max(np.abs(expected[0]))), 1e-300)
        np.testing.assert_allclose(eigenvalues, expected[0], rtol=0, atol=4e-16 * scale)
        np.testing.assert_allclose(vectors, expected[1], rtol=0, atol=4e-16 * np.max(vectors))
        differ += not (
            np.array_equal(eigenvalues, expected[0]) and np.array_equal(vectors, expected[1])
        )
    assert differ < 20  # a handful differ by an ulp
    eigenvalue, vector = _small_eigh([2.0], [[3.0]])
    one = scipy.linalg.eigh([[3.0]], [[2.0]])  # 3 / sqrt(2)^2 = 1.4999999999999998
    assert eigenvalue.tolist() == one[0].tolist() and vector.tolist() == one[1].tolist()
    assert _small_eigh([1.0, 1.0], [[1e300, 0.0], [0.0, 1.0]]) is None  # LAPACK rescales


@pytest.mark.parametrize("system", NO_EXACT_EQUILIBRIUM, ids=["two-bodies", "three-bodies"])
def test_an_equilibrium_search_without_an_exact_root_is_bounded(system) -> None:
    """SciPy's least squares crawled after a root that is not there: to its cap of 20 000
    force evaluations (7 s) in every descent of the zero-mode holding, 200 of them (an hour of
    `rollspring analyze`; the second system hung a random-seed run of the suite). The search's
    evaluations are bounded now (10 000 by default); what it returns is checked as before: a
    residual within 1e-9 of the force scale is an equilibrium, else none is found."""
    arrays = system_arrays(system)
    count = [0]

    def forces(q):
        count[0] += 1
        return generalized_forces(arrays, q)

    equilibrium = find_equilibrium(arrays, forces=forces)
    # SciPy's evaluations, and a few of Newton's and the residual's per descent
    assert count[0] <= 12_000
    residual = float(
        np.sqrt((generalized_forces(arrays, equilibrium.q) ** 2 / arrays.inertia).sum())
    )
    assert residual == pytest.approx(equilibrium.residual, rel=1e-6, abs=1e-300)
    if equilibrium.found:
        assert equilibrium.stiffness is not None and equilibrium.modes is not None
    else:
        assert equilibrium.reason


def test_a_zero_mode_that_is_no_exact_symmetry_is_reported() -> None:
    """The "frictionless" pair (Fig. 3's idea): its linear zero mode moves the centres 3 : 4
    so both bodies turn by the same angle θ; the spring's ends then stay apart by
    (0.5 + 0.025(θ − sin θ), 0.025(1 − cos θ)) m, worked out here by hand from the rolling
    kinematics, so the exact potential changes along the mode and ``analyze`` says so."""
    from rollspring.analysis.checks import zero_mode_potential_change
    from rollspring.model import load_system

    analysis = analyze(load_system("frictionless"))
    zero = next(mode for mode in analysis.modes if mode.kind == "zero")
    np.testing.assert_allclose(zero.shape_x, [0.75, 1.0], rtol=1e-12)
    reach = 0.5 * math.pi * 0.075  # the largest centre displacement sampled (m)
    theta = np.linspace(-reach, reach, 41) / 0.1  # the cylinder's (and the hoop's) turn
    length = np.hypot(0.5 + 0.025 * (theta - np.sin(theta)), 0.025 * (1 - np.cos(theta)))
    by_hand = float(np.ptp(0.5 * 100.0 * (length - 0.5) ** 2))
    assert zero_mode_potential_change(analysis) == pytest.approx(by_hand, rel=1e-12)
    assert by_hand > 1e-3
    (warning,) = [w for w in analysis.warnings if w.startswith("the zero mode")]
    assert f"{by_hand:.3g} J" in warning and "creep" in warning


@pytest.mark.parametrize("preset", ["hoop-cylinder", "two-hoops", "three-bodies"])
def test_centre_springs_make_the_zero_mode_an_exact_symmetry(preset: str) -> None:
    """With every spring at the centres a common translation leaves every spring's length
    alone: the potential along the zero mode is constant to rounding, and nothing is said."""
    from rollspring.analysis.checks import zero_mode_potential_change
    from rollspring.model import load_system

    analysis = analyze(load_system(preset))
    change = zero_mode_potential_change(analysis)
    assert change is not None and change < 1e-20
    assert not [w for w in analysis.warnings if w.startswith("the zero mode")]


def test_equal_hoops_joined_at_their_tops_keep_the_symmetry() -> None:
    """Off-centre ends that turn alike (two equal hoops, the spring between their tops): a
    common translation turns both ends by the same angle, the spring keeps its length, the
    zero mode is exact, and no warning is given although the springs are off the centres."""
    from rollspring.analysis.checks import zero_mode_potential_change

    system = make_system(
        bodies=[body("a", "hoop", x=0.0, radius=0.1), body("b", "hoop", x=0.5, radius=0.1)],
        springs=[spring("a", "b", stiffness=80.0, rest_length=0.5, at=[{"height": 0.2}] * 2)],
    )
    analysis = analyze(system)
    change = zero_mode_potential_change(analysis)
    assert change is not None and change < 1e-20
    assert not [w for w in analysis.warnings if w.startswith("the zero mode")]

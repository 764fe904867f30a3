"""Every quantitative result of the paper, for random parameters (Hypothesis).

Paper: G. Nyitray, *On the edge of complexity: the simplest not simple coupled mechanical
system* (arXiv 2508.01379). Equation labels are the paper's LaTeX labels.
"""

from __future__ import annotations

import itertools
import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from rollspring.analysis import analyze
from rollspring.model import INERTIA_FACTORS, load_system
from rollspring.physics import contact_forces, system_arrays
from tests.conftest import body, make_system, spring

masses = st.floats(0.05, 20.0)
radii = st.floats(0.01, 1.0)
stiffnesses = st.floats(1.0, 5000.0)
compressions = st.floats(1e-4, 0.05)
paper = settings(max_examples=40, deadline=None)


def hoop_cylinder(m1: float, m2: float, radius: float, k: float, compression: float):
    """The paper's Fig. 2 system: centres joined by a spring compressed by `compression`."""
    rest = 10 * radius + 1.0
    return make_system(
        [
            body("hoop", "hoop", mass=m1, radius=radius, x=0.0),
            body("cylinder", "cylinder", mass=m2, radius=radius, x=rest - compression),
        ],
        [spring("hoop", "cylinder", stiffness=k, rest_length=rest)],
    )


@paper
@given(masses, masses, radii, stiffnesses, compressions)
def test_fig2_frequency_positions_and_stationary_point(m1, m2, radius, k, a) -> None:
    result = analyze(hoop_cylinder(m1, m2, radius, k, a))
    (mode,) = result.oscillating
    # eq. (QQQ1): Omega^2 = k/(2 m1) + 2k/(3 m2)
    assert mode.eigenvalue == pytest.approx(k / (2 * m1) + 2 * k / (3 * m2), rel=1e-12)
    # eq. (c): X-hat = (I'_1 x1 + I'_2 x2)/(I'_1 + I'_2), weights (2 m1, 1.5 m2) for equal R
    weights = np.array([2 * m1, 1.5 * m2]) / (2 * m1 + 1.5 * m2)
    np.testing.assert_allclose(result.stationary_weights, weights, rtol=1e-12)
    assert result.stationary_amplitude == pytest.approx(0.0, abs=1e-12 * a)
    # Sec. 4.2: A1 = A 3m2/(4m1 + 3m2), A2 = A 4m1/(4m1 + 3m2), A = spring deformation amplitude
    np.testing.assert_allclose(
        result.amplitude,
        [a * 3 * m2 / (4 * m1 + 3 * m2), a * 4 * m1 / (4 * m1 + 3 * m2)],
        rtol=1e-9,
    )
    # eqs. (om), (pi): maximal centre velocities v1 = A sqrt(3 k m2/(2 m1 (4 m1 + 3 m2))), ...
    v1 = a * math.sqrt(3 * k * m2 / (2 * m1 * (4 * m1 + 3 * m2)))
    v2 = a * math.sqrt(8 * k * m1 / (3 * m2 * (4 * m1 + 3 * m2)))
    np.testing.assert_allclose(result.velocity_amplitude, [v1, v2], rtol=1e-9)
    # the CM is not stationary: amplitude m1 m2 A / ((m1 + m2)(4 m1 + 3 m2)) (docs/physics.md 7.1)
    assert result.cm_amplitude == pytest.approx(
        m1 * m2 * a / ((m1 + m2) * (4 * m1 + 3 * m2)), rel=1e-9
    )
    # in the mode the bodies move in phase opposition (eq. (g))
    assert mode.shape_x[0] * mode.shape_x[1] < 0


@paper
@given(masses, masses, radii, stiffnesses, compressions)
def test_fig2_friction_amplitudes_are_f_over_2_and_f_over_3_opposite(m1, m2, radius, k, a):
    result = analyze(hoop_cylinder(m1, m2, radius, k, a))
    force = k * a  # amplitude of the spring force
    # Appendix A / docs/physics.md (M10): hoop -F/2, cylinder -F/3 for a centre pull
    np.testing.assert_allclose(result.friction_amplitude, [force / 2, force / 3], rtol=1e-9)
    (mode,) = result.oscillating
    # f1/f2 = -3/2: the paper's "f1/f2 = 3/2" is a ratio of magnitudes
    assert mode.friction[0] / mode.friction[1] == pytest.approx(-1.5, rel=1e-12)
    # required mu: max |f|/N = (F/2)/(m1 g), (F/3)/(m2 g)
    g = 9.81
    np.testing.assert_allclose(
        result.required_mu, [force / 2 / (m1 * g), force / 3 / (m2 * g)], rtol=1e-9
    )


@paper
@given(masses, masses, radii, stiffnesses, compressions)
def test_fig2_spring_split_k1_k2(m1, m2, radius, k, a) -> None:
    split = analyze(hoop_cylinder(m1, m2, radius, k, a)).spring_split
    assert split is not None
    # eqs. (k1), (k2), and (part): 1/k = 1/k1 + 1/k2
    k1, k2 = k * (3 * m2 + 4 * m1) / (3 * m2), k * (3 * m2 + 4 * m1) / (4 * m1)
    np.testing.assert_allclose(split["k"], [k1, k2], rtol=1e-12)
    assert 1 / split["k"][0] + 1 / split["k"][1] == pytest.approx(1 / k, rel=1e-12)
    # Appendix B: Omega_1 = sqrt(k/(2 m1)), Omega_2 = sqrt(2k/(3 m2)), Omega^2 = sum
    np.testing.assert_allclose(
        split["clamped_omega"], [math.sqrt(k / (2 * m1)), math.sqrt(2 * k / (3 * m2))], rtol=1e-12
    )


@paper
@given(
    st.sampled_from(["hoop", "cylinder", "sphere", "shell"]),
    masses,
    masses,
    radii,
    stiffnesses,
    compressions,
)
def test_equal_shapes_make_the_stationary_point_the_cm(shape, m1, m2, radius, k, a) -> None:
    rest = 10 * radius + 1.0
    system = make_system(
        [
            body("a", shape, mass=m1, radius=radius, x=0.0),
            body("b", shape, mass=m2, radius=radius, x=rest - a),
        ],
        [spring("a", "b", stiffness=k, rest_length=rest)],
    )
    result = analyze(system)
    np.testing.assert_allclose(
        result.stationary_weights, [m1 / (m1 + m2), m2 / (m1 + m2)], rtol=1e-12
    )
    assert result.cm_amplitude == pytest.approx(0.0, abs=1e-12 * a)
    gamma = INERTIA_FACTORS[shape]
    # Omega^2 = k/((1+gamma)) (1/m1 + 1/m2) (docs/physics.md (M15) with eta = R)
    assert result.oscillating[0].eigenvalue == pytest.approx(
        k / (1 + gamma) * (1 / m1 + 1 / m2), rel=1e-12
    )


@paper
@given(masses, masses, st.floats(0.01, 1.0), stiffnesses, st.floats(0.01, 1.0))
def test_fig3_percussion_points_remove_friction_and_fix_the_cm(m1, m2, r2, k, v) -> None:
    """Hoop at its top (2R1), cylinder at 1.5 R2, horizontal spring: R1 = 0.75 R2 (not R2/2)."""
    r1 = 0.75 * r2
    height = 1.5 * r2
    system = make_system(
        [
            body("hoop", "hoop", mass=m1, radius=r1, x=0.0, v=-v * 0.01),
            body("cylinder", "cylinder", mass=m2, radius=r2, x=1.0 + 2 * r2),
        ],
        [spring("hoop", "cylinder", stiffness=k, at=[{"height": height}, {"height": height}])],
    )
    result = analyze(system)
    (mode,) = result.oscillating
    # eq. for Omega with no friction (Appendix B): 2k/m1 + 3k/(2 m2)
    assert mode.eigenvalue == pytest.approx(2 * k / m1 + 3 * k / (2 * m2), rel=1e-12)
    assert result.spring_tilt_deg[0] == 0.0
    force_scale = k * float(np.max(np.abs(mode.spring_extension)))
    np.testing.assert_allclose(mode.friction, 0.0, atol=1e-12 * force_scale)
    # eq. (bb): the CM is stationary; X-hat is the CM
    np.testing.assert_allclose(
        result.stationary_weights, [m1 / (m1 + m2), m2 / (m1 + m2)], rtol=1e-9
    )
    assert result.cm_amplitude == pytest.approx(0.0, abs=1e-12)


@pytest.mark.parametrize("r2", [0.1, 0.37])
def test_fig3_r1_equal_r2_over_2_is_right_with_level_centres(r2: float) -> None:
    """Sec. 3: "the spring must be horizontal and the centres are at the same height,
    R1 = R2/2": true when the hoop's track is raised by R1 so that the centres are level."""
    r1 = r2 / 2
    system = make_system(
        [
            body("hoop", "hoop", radius=r1, x=0.0, track_height=r2 - r1, v=0.01),
            body("cylinder", "cylinder", radius=r2, x=0.5),
        ],
        [spring("hoop", "cylinder", at=[{"height": 2 * r1}, {"height": 1.5 * r2}])],
    )
    result = analyze(system)
    assert result.spring_tilt_deg[0] == 0.0
    assert result.oscillating[0].eigenvalue == pytest.approx(2 * 100 / 1 + 3 * 100 / 2, rel=1e-12)
    np.testing.assert_array_equal(result.friction_amplitude, [0.0, 0.0])
    assert not any("tilted" in w or "friction" in w for w in result.warnings)


def test_fig3_r1_equal_r2_over_2_on_one_floor_tilts_the_spring_and_says_so() -> None:
    r2 = 0.1
    system = make_system(
        [
            body("hoop", "hoop", radius=r2 / 2, x=0.0),
            body("cylinder", "cylinder", radius=r2, x=0.5),
        ],
        [spring("hoop", "cylinder", at=[{"height": r2}, {"height": 1.5 * r2}])],
    )
    result = analyze(system)
    tilt = math.degrees(math.atan2(0.5 * r2, 0.5))
    assert result.spring_tilt_deg[0] == pytest.approx(tilt, rel=1e-12)
    # friction still vanishes to first order (both ends at percussion points) ...
    np.testing.assert_allclose(result.oscillating[0].friction, 0.0, atol=1e-9)
    # ... but Omega^2 is scaled by cos^2(tilt) (docs/physics.md 7.1) and the analysis warns
    cos2 = math.cos(math.radians(tilt)) ** 2
    assert result.oscillating[0].eigenvalue == pytest.approx(cos2 * (2 * 100 / 1 + 150), rel=1e-12)
    assert any("R1 = R2/2" in w and "tilted" in w and "level" in w for w in result.warnings)


@paper
@given(
    st.sampled_from(["hoop", "cylinder", "sphere", "shell"]),
    masses,
    radii,
    st.floats(0.0, 1.0),
    st.floats(-50.0, 50.0).filter(lambda f: abs(f) > 1e-3),
)
def test_appendix_a_friction_of_a_pulled_body(shape, m, radius, y_over_2r, force) -> None:
    """eq. (fric): f(y) = F (1 - m R y / (I + m R^2)), counted opposite to F by the paper."""
    y = 2 * radius * y_over_2r
    system = make_system(
        [body("b", shape, mass=m, radius=radius)],
        forces=[{"body": "b", "at": {"height": y}, "fx": force}],
    )
    friction, normal = contact_forces(system_arrays(system), np.zeros(1))
    inertia = INERTIA_FACTORS[shape] * m * radius**2
    expected = force * (1 - m * radius * y / (inertia + m * radius**2))
    assert -friction[0] == pytest.approx(expected, rel=1e-12, abs=1e-12 * abs(force))
    assert normal[0] == pytest.approx(m * 9.81, rel=1e-12)


@pytest.mark.parametrize("shape", ["hoop", "cylinder", "sphere", "shell"])
@pytest.mark.parametrize("n_bodies", [1, 2, 3, 5, 8])
def test_chain_between_two_walls_has_textbook_frequencies(shape: str, n_bodies: int) -> None:
    """N equal bodies, N + 1 equal centre springs between two walls:
    omega_n^2 = (4 k R^2 / J) sin^2(n pi / (2 (N + 1)))."""
    k, m, radius, gap = 37.0, 0.7, 0.05, 0.4
    bodies = [body(f"b{i}", shape, mass=m, radius=radius, x=gap * (i + 1)) for i in range(n_bodies)]
    anchors = [
        {"id": "left", "x": 0.0, "y": radius},
        {"id": "right", "x": gap * (n_bodies + 1), "y": radius},
    ]
    names = ["left"] + [b["id"] for b in bodies] + ["right"]
    springs = [spring(a, b, stiffness=k) for a, b in itertools.pairwise(names)]
    result = analyze(make_system(bodies, springs, anchors=anchors))
    inertia = (1 + INERTIA_FACTORS[shape]) * m * radius**2
    n = np.arange(1, n_bodies + 1)
    expected = 4 * k * radius**2 / inertia * np.sin(n * np.pi / (2 * (n_bodies + 1))) ** 2
    np.testing.assert_allclose([mode.eigenvalue for mode in result.modes], expected, rtol=1e-10)
    assert result.stationary_weights is None  # walls remove the zero mode


def test_two_sliders_fig1_cm_stays_at_rest() -> None:
    """Sec. 2: point masses on a frictionless floor: Omega^2 = k (1/m1 + 1/m2), X-hat = CM."""
    m1, m2, k = 1.3, 0.4, 80.0
    system = make_system(
        [body("m1", "slider", mass=m1, x=0.0), body("m2", "slider", mass=m2, x=0.49)],
        [spring("m1", "m2", stiffness=k, rest_length=0.5)],
    )
    result = analyze(system)
    assert result.oscillating[0].eigenvalue == pytest.approx(k * (1 / m1 + 1 / m2), rel=1e-12)
    np.testing.assert_allclose(
        result.stationary_weights, [m1, m2] / np.float64(m1 + m2), rtol=1e-12
    )
    assert result.cm_amplitude == pytest.approx(0.0, abs=1e-15)
    np.testing.assert_array_equal(result.friction_amplitude, [0.0, 0.0])


def test_frictionless_preset_is_the_fig3_idea_done_right() -> None:
    result = analyze(load_system("frictionless"))
    assert result.oscillating[0].eigenvalue == pytest.approx(2 * 100 / 1 + 3 * 100 / 2, rel=1e-12)
    np.testing.assert_array_equal(result.friction_amplitude, [0.0, 0.0])
    assert result.cm_amplitude == 0.0
    assert result.spring_tilt_deg[0] == 0.0
    # one mode, shape normalised to a largest centre displacement of 1: the spring's
    # deformation amplitude is |spring_extension| x the largest body amplitude
    (mode,) = result.oscillating
    deformation = abs(mode.spring_extension[0]) * np.max(result.amplitude)
    assert deformation == pytest.approx(0.01, rel=1e-9)

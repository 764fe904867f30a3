"""The symbolic system against rollspring's numeric physics: M, K, Omega^2 for every preset; the
exact Q, friction and normal forces at random states of an everything-at-once system; the paper's
Fig. 2 formulas for random parameters, exactly."""

from __future__ import annotations

import math

import numpy as np
import pytest
import sympy as sp
from hypothesis import given, settings
from hypothesis import strategies as st

import rollspring
from rollspring.analysis import analyze
from rollspring.analysis.derivation import (
    OMEGA2,
    mechanics_lagrange_check,
    normal_frequencies,
    symbolic_system,
)
from rollspring.analysis.derivation.parts import exact_number
from rollspring.analysis.derivation.symbolic import matrix_to_float
from rollspring.model import load_system, preset_names
from rollspring.physics import (
    contact_forces,
    contact_forces_jacobian,
    generalized_forces,
    stiffness_matrix,
    system_arrays,
)
from tests.conftest import body, make_system, spring

PRESETS = preset_names()


@pytest.mark.parametrize("symbols", [False, True])
@pytest.mark.parametrize("name", PRESETS)
def test_mass_stiffness_and_frequencies_agree_with_analyze(name: str, symbols: bool) -> None:
    system = load_system(name)
    sym = symbolic_system(system, symbols=symbols)
    numeric = analyze(system)
    np.testing.assert_allclose(
        matrix_to_float(sym.mass_matrix, sym.values), numeric.mass, rtol=1e-13
    )
    scale = float(np.max(np.abs(numeric.stiffness)))
    np.testing.assert_allclose(
        matrix_to_float(sym.stiffness_matrix, sym.values),
        numeric.stiffness,
        rtol=1e-12,
        atol=1e-13 * scale,
    )
    frequencies = normal_frequencies(sym)
    expected = [m.eigenvalue for m in numeric.modes if m.kind != "zero"]
    assert frequencies.n_zero == sum(m.kind == "zero" for m in numeric.modes)
    if len(expected) <= 2:  # the paper's systems: closed forms (the quadratic formula at most)
        assert frequencies.complete
    else:  # the chains: degree 8 in Omega^2, no general formula; said so, numbers given
        assert not frequencies.complete
        assert any("no closed form" in note for note in frequencies.notes)
    values = [
        sym.numeric(w) if w is not None else number
        for w, number in zip(frequencies.omega2, frequencies.numeric, strict=True)
    ]
    np.testing.assert_allclose(values, expected, rtol=1e-11)
    shown = frequencies.characteristic
    if shown is None:  # symbols, no closed form: the polynomial at the parameters' values
        assert symbols and frequencies.at_values is not None
        shown = frequencies.at_values
    else:
        shown = sp.sympify(shown).xreplace(sym.values)
    roots = sorted(complex(r).real for r in sp.Poly(shown, OMEGA2).nroots(n=30))
    np.testing.assert_allclose(
        [r for r in roots if abs(r) > 1e-9 * roots[-1]], expected, rtol=1e-11
    )  # the displayed polynomial's own roots, not the eigenvalues it was matched with
    if symbols:  # the parameters really are symbols: nothing numeric is left in M
        assert all(entry.free_symbols for entry in sym.mass_matrix if entry != 0)


def test_closed_form_stiffness_equals_the_hessian_of_the_exact_potential() -> None:
    """K in closed form is the Hessian of the exact V at the reference, with the system's
    conditions (frictionless: the end heights 2R_1 and 3R_2/2 are equal)."""
    for name in ("frictionless", "wall-hoop-cylinder"):
        sym = symbolic_system(load_system(name), symbols=True)
        difference = sym.apply_conditions(sym.hessian() - sym.stiffness_matrix)
        assert sp.simplify(difference) == sp.zeros(sym.n, sym.n)


def everything_system():
    """Anchors (pre-tension), off-centre and height attachments, a raised track, a custom
    shape, a slider, a constant force, two springs between the same bodies."""
    return make_system(
        [
            body("hoop", "hoop", x=0.0),
            body("cyl", "cylinder", radius=0.08, x=0.5, track_height=0.05),
            body("wheel", "custom", radius=0.12, x=1.0, inertia_factor=0.75),
            body("block", "slider", mass=2.0, radius=0.05, x=1.5),
        ],
        [
            spring("wall", "hoop", at=[{}, {"radius": 0.05, "angle": 60.0}], rest_length=0.45),
            spring("hoop", "cyl", at=[{"height": 0.15}, {"radius": 0.06, "angle": -30.0}]),
            spring("hoop", "cyl", stiffness=50.0),
            spring("cyl", "wheel", at=[{}, {"height": 0.2}], rest_length=0.55),
            spring("wheel", "block", stiffness=80.0),
        ],
        anchors=[{"id": "wall", "x": -0.5, "y": 0.15}],
        forces=[{"body": "wheel", "at": {"radius": 0.05, "angle": 45.0}, "fx": 0.5, "fy": -0.2}],
    )


@pytest.mark.parametrize("symbols", [False, True])
def test_exact_forces_match_the_numeric_physics_at_random_states(symbols: bool) -> None:
    system = everything_system()
    sym = symbolic_system(system, symbols=symbols)
    assert sym.reference == "equilibrium"
    arrays = system_arrays(system)

    def lam(exprs):
        return sp.lambdify(sym.q, [sp.sympify(e).xreplace(sym.values) for e in exprs], "numpy")

    torque, newton = lam(sym.generalized_forces), lam(sym.contact_torques)
    friction, normal = lam(sym.friction_configuration), lam(sym.normal)
    rng = np.random.default_rng(7)
    for _ in range(4):
        u = rng.normal(0.0, 0.4, sym.n)
        q = sym.q_reference + u
        f_num, n_num = contact_forces(arrays, q)
        np.testing.assert_allclose(torque(*u), generalized_forces(arrays, q), atol=1e-10)
        np.testing.assert_allclose(newton(*u), generalized_forces(arrays, q), atol=1e-10)
        np.testing.assert_allclose(friction(*u), f_num, atol=1e-10)
        np.testing.assert_allclose(normal(*u), n_num, atol=1e-10)
    q_ref = sym.q_reference
    np.testing.assert_allclose(
        matrix_to_float(sym.stiffness_matrix, sym.values),
        stiffness_matrix(arrays, q_ref),
        atol=1e-10,
    )
    d_friction, d_normal = contact_forces_jacobian(arrays, q_ref)
    f_lin, n_lin = sym.linear_contact_forces
    jac_f = np.array([[float(sp.diff(e, q).xreplace(sym.values)) for q in sym.q] for e in f_lin])
    jac_n = np.array([[float(sp.diff(e, q).xreplace(sym.values)) for q in sym.q] for e in n_lin])
    np.testing.assert_allclose(jac_f, d_friction, atol=1e-9)
    np.testing.assert_allclose(jac_n, d_normal, atol=1e-9)


def test_lagranges_method_agrees_with_the_structure_route_off_centre() -> None:
    """sympy.physics.mechanics.LagrangesMethod on the exact (nonlinear) Lagrangian gives
    J_i phi_i'' + dV/dphi_i = 0 (Fig. 3 geometry: trigonometric attachment paths)."""
    sym = symbolic_system(load_system("frictionless"), symbols=True)
    check = mechanics_lagrange_check(sym)
    assert check["agrees"] is True
    assert check["residual"] == sp.zeros(2, 1)
    assert len(check["equations"]) == 2 and check["equations"][0].has(sp.sin)


def test_exact_numbers() -> None:
    assert exact_number(0.1) == sp.Rational(1, 10)
    assert exact_number(1.4999999999999998) == sp.Rational(3, 2)
    assert exact_number(1 / 3) == sp.Rational(1, 3)
    assert exact_number(0.0) == 0
    close = exact_number(math.pi)  # no simple fraction: the first within 1e-12 of pi
    assert abs(float(close) - math.pi) <= 1e-12 * math.pi and close.q <= 10**6
    assert exact_number(0.123456789012345) == sp.Rational(123456789012345, 10**15)


fig2 = settings(max_examples=12, deadline=None)


@fig2
@given(st.floats(0.05, 20.0), st.floats(0.05, 20.0), st.floats(0.01, 1.0), st.floats(1.0, 5000.0))
def test_fig2_exact_for_random_parameters(m1: float, m2: float, radius: float, k: float) -> None:
    rest = 10 * radius + 1.0
    system = make_system(
        [
            body("hoop", "hoop", mass=m1, radius=radius, x=0.0),
            body("cylinder", "cylinder", mass=m2, radius=radius, x=rest - 0.01),
        ],
        [spring("hoop", "cylinder", stiffness=k, rest_length=rest)],
    )
    sym = symbolic_system(system)
    M1, M2, K, R = (exact_number(v) for v in (m1, m2, k, radius))
    # paper (QQQ1), exactly in rational arithmetic
    (omega2,) = normal_frequencies(sym).omega2
    assert omega2 == K / (2 * M1) + 2 * K / (3 * M2)
    # Steiner (I'_1, I'_2) and K = k R^2 [[1, -1], [-1, 1]] (physics stiffness_matrix docstring)
    assert sym.mass_matrix == sp.diag(2 * M1 * R**2, sp.Rational(3, 2) * M2 * R**2)
    assert sym.stiffness_matrix == K * R**2 * sp.Matrix([[1, -1], [-1, 1]])
    # friction: -F/2 on the hoop, +F/3 on the cylinder, F = k(R phi2 - R phi1)
    p1, p2 = sym.q
    f1, f2 = sym.linear_contact_forces[0]
    assert sp.expand(f1 + K * (R * p2 - R * p1) / 2) == 0
    assert sp.expand(f2 - K * (R * p2 - R * p1) / 3) == 0


def test_geometric_stiffness_of_a_pretensioned_hoop_between_walls() -> None:
    """docs/physics.md section 7: a hoop point at alpha = 90 deg between two walls, both springs at
    tension T: K = (kL + kR) R^2 + T r^2 (1/lL + 1/lR) (the path-curvature terms cancel)."""
    system = make_system(
        [body("h", "hoop", x=0.0)],
        [
            spring("left", "h", at=[{}, {"radius": 0.05, "angle": 90.0}], rest_length=0.4),
            spring("h", "right", at=[{"radius": 0.05, "angle": 90.0}, {}], rest_length=0.4),
        ],
        anchors=[{"id": "left", "x": -0.45, "y": 0.1}, {"id": "right", "x": 0.55, "y": 0.1}],
    )
    sym = symbolic_system(system, symbols=True)
    s = {symbol.name: symbol for symbol in sym.values}
    k1, k2, l1, l2, R = s["k_1"], s["k_2"], s["ell_1"], s["ell_2"], s["R"]
    T = sp.Symbol("T", positive=True)
    at_tension = {s["L_1"]: l1 - T / k1, s["L_2"]: l2 - T / k2}
    (condition,) = sym.reference_forces  # equilibrium: the two tensions balance
    assert sp.simplify(condition.subs(at_tension)) == 0
    r = R / 2  # the attachment radius 0.05 m is R/2
    expected = (k1 + k2) * R**2 + T * r**2 * (1 / l1 + 1 / l2)
    assert sp.simplify(sym.stiffness_matrix[0, 0].subs(at_tension) - expected) == 0
    np.testing.assert_allclose(
        matrix_to_float(sym.stiffness_matrix, sym.values), analyze(system).stiffness, rtol=1e-12
    )


@pytest.mark.parametrize("raised", [False, True])
def test_the_frictionless_potential_is_general_tilted_springs_too(raised: bool) -> None:
    """The symbolic potential of the Fig. 3 geometry (ends at the hoop's top, 2R_1, and at
    1.5 R_2 on the cylinder) holds for any radii, masses, track height and spring: its
    vertical part is the difference of the end heights, not the 0 of this system's numbers.
    Substituted with random values that tilt the spring, it equals rollspring.physics'
    potential energy at random angles."""
    from rollspring.analysis.paper import paper_system
    from rollspring.physics import potential_energy

    template = paper_system("fig3") if raised else load_system("frictionless")
    sym = symbolic_system(template, symbols=True)
    assert sym.conditions  # level only for this system's numbers: a stated condition
    names = {s.name: s for s in sym.values}
    rng = np.random.default_rng(11 + raised)
    for _ in range(4):
        m1, m2 = rng.uniform(0.5, 3.0, 2)
        r1, r2 = rng.uniform(0.04, 0.15, 2)
        track = rng.uniform(0.0, 0.1) if raised else 0.0
        across, k = rng.uniform(0.3, 0.8), rng.uniform(20.0, 500.0)
        rise = 1.5 * r2 - (track + 2 * r1)
        assert abs(rise) > 1e-3  # the spring is tilted
        system = make_system(
            [
                body("hoop", "hoop", mass=m1, radius=r1, x=0.0, track_height=track),
                body("cyl", "cylinder", mass=m2, radius=r2, x=across),
            ],
            [
                spring(
                    "hoop",
                    "cyl",
                    stiffness=k,
                    rest_length=math.hypot(across, rise),
                    at=[{"height": 2 * r1}, {"height": 1.5 * r2}],
                )
            ],
        )
        values = {names["m_1"]: m1, names["m_2"]: m2, names["R_1"]: r1, names["R_2"]: r2}
        values |= {names["k"]: k, names["ell"]: across}
        if raised:
            values[names["h_1"]] = track
        potential = sp.lambdify(sym.q, sym.potential.xreplace(values), "numpy")
        arrays = system_arrays(system)
        for q in rng.normal(0.0, 0.5, (5, 2)):
            assert potential(*q) == pytest.approx(
                float(potential_energy(arrays, q)), rel=1e-9, abs=1e-12
            )


# -- chains: the lattices' closed forms, and ten bodies --------------------------------------------


def test_monatomic_chain_frequencies_are_the_standing_waves_of_the_lattice() -> None:
    """N equal bodies between walls: Omega_n^2 = (4k/M) sin^2(n pi/(2(N + 1))), M = (1 + gamma) m
    the rolling mass (the fixed-end monatomic chain, e.g. Kittel, Introduction to Solid State
    Physics, ch. 4; docs/physics.md section 7.2). The exact numbers factor the polynomial: its
    rational roots are found and equal the formula exactly."""
    system = load_system("chain-monatomic")
    n, k = len(system.bodies), system.springs[0].stiffness
    (body_mass,) = {b.mass for b in system.bodies}
    rolling = 2 * body_mass  # hoops: gamma = 1
    assert {b.shape for b in system.bodies} == {"hoop"}
    for symbols in (False, True):
        frequencies = normal_frequencies(symbolic_system(system, symbols=symbols))
        formula = [
            4 * sp.nsimplify(k / rolling) * sp.sin(j * sp.pi / (2 * (n + 1))) ** 2
            for j in range(1, n + 1)
        ]
        np.testing.assert_allclose(frequencies.numeric, [float(f) for f in formula], rtol=1e-12)
        exact = [(w, f) for w, f in zip(frequencies.omega2, formula, strict=True) if w is not None]
        if symbols:
            assert exact == []  # no closed form in 17 symbols: degree 8
        else:
            assert len(exact) == 2  # sin^2(pi/6), sin^2(pi/3): 50 and 150 s^-2
            assert all(sp.simplify(w - f) == 0 for w, f in exact)


def test_diatomic_chain_frequencies_lie_on_the_two_branches() -> None:
    """2N bodies of rolling masses M1, M2 alternating between walls: the two branches of the
    diatomic lattice, Omega^2 = k (s -/+ sqrt(s^2 - 4 sin^2(q a0)/(M1 M2))), s = 1/M1 + 1/M2, at
    q a0 = j pi/(2N + 1), j = 1..N (the fixed-end standing waves, a0 the spacing). The quadratic
    factor the exact numbers give (j = 3: sin^2 = 3/4) is the formula exactly."""
    system = load_system("chain-diatomic")
    n, k = len(system.bodies), sp.nsimplify(system.springs[0].stiffness)
    masses = [
        sp.nsimplify((1 + {"hoop": 1.0, "cylinder": 0.5}[b.shape]) * b.mass) for b in system.bodies
    ]
    m1, m2 = masses[0], masses[1]
    assert masses == [m1, m2] * (n // 2) and m1 != m2
    s = 1 / m1 + 1 / m2
    formula = []
    for j in range(1, n // 2 + 1):
        root = sp.sqrt(s**2 - 4 * sp.sin(j * sp.pi / (n + 1)) ** 2 / (m1 * m2))
        formula += [k * (s - root), k * (s + root)]
    formula.sort(key=float)
    frequencies = normal_frequencies(symbolic_system(system))
    np.testing.assert_allclose(frequencies.numeric, [float(f) for f in formula], rtol=1e-12)
    exact = [(w, f) for w, f in zip(frequencies.omega2, formula, strict=True) if w is not None]
    assert len(exact) == 2
    assert all(sp.simplify(w - f) == 0 for w, f in exact)
    gap = (2 * k / max(m1, m2), 2 * k / min(m1, m2))  # the lattice's band gap: no mode in it
    assert not any(float(gap[0]) < w < float(gap[1]) for w in frequencies.numeric)


@pytest.mark.slow
def test_a_ten_body_chain_is_derived_and_says_why_it_gives_numbers() -> None:
    """Degree 10 in Omega^2: with symbols the polynomial in 21 parameters is not expanded (it
    took more than five minutes), the derivation shows M, K and the equations, the polynomial at
    the parameters' values and its roots as numbers, and says why there is no closed form.
    (No time is asserted: the test would not finish in CI's budget if it were expanded.)"""
    from rollspring.analysis.derivation import derive

    system = rollspring.chain("hoop,cylinder", 10, walls="both", pluck=1)
    expected = sorted(m.eigenvalue for m in analyze(system).modes)
    for symbols in (True, False):
        derivation = derive(system, symbols=symbols)
        assert derivation.cross_check.agree
        sym = derivation.symbolic
        np.testing.assert_allclose(
            matrix_to_float(sym.stiffness_matrix, sym.values), analyze(system).stiffness
        )
        newton = derivation.methods["newton"].section
        words = [step.words for step in newton.steps]
        roots = next(step for step in newton.steps if step.words.startswith("The roots of"))
        assert "degree 10 in Omega^2" in roots.words
        assert "No closed form" in roots.words and "no general formula" in roots.words
        numbers = [
            float(e.rhs) for e in roots.equations if isinstance(e.rhs, sp.Float | sp.Integer)
        ]
        assert len(numbers) == 10
        np.testing.assert_allclose(numbers, expected, rtol=1e-10)
        assert any("as one matrix equation" in w for w in words)
        assert any("at the parameters' values" in w for w in words) == symbols
    text = derivation.render("text")
    assert "10 coupled equations" in text


def test_a_chain_with_springs_tilted_between_radii_is_derived_not_crashed() -> None:
    """Centres at different heights tilt the springs: K's entries are rational in the
    parameters, which the chain's polynomial recurrence cannot take (a PolynomialError, an
    internal error of derive and report, HTTP 500 on the web); such a chain takes the general
    path (here past its budget: the frequencies as numbers)."""
    from rollspring.model.chains import chain

    system = chain(("hoop", "cylinder"), 3, radius=(0.1, 0.2))
    sym = symbolic_system(system, symbols=True)
    frequencies = normal_frequencies(sym, budget=0.5)
    expected = [m.eigenvalue for m in analyze(system).modes if m.kind != "zero"]
    np.testing.assert_allclose(frequencies.numeric, expected, rtol=1e-10)
    assert frequencies.n_zero == 1

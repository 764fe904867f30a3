"""Dispersion of chains read as periodic lattices (``rollspring.analysis.dispersion``,
``rollspring dispersion``): the closed forms, group velocities, the friction per branch against
a finite chain's modal analysis, and the command."""

from __future__ import annotations

import json
import math

import numpy as np
import pytest
import scipy.optimize
from hypothesis import given
from hypothesis import strategies as st
from typer.testing import CliRunner

from rollspring import analyze
from rollspring.analysis.dispersion import (
    EQUILIBRIUM_BODIES,
    diatomic_branches,
    dispersion,
    monatomic_branch,
    unit_cell,
)
from rollspring.cli import app
from rollspring.errors import AnalysisError
from rollspring.model import INERTIA_FACTORS, load_system, system_from_dict, system_to_json
from rollspring.model.chains import chain

SHAPES = ("hoop", "cylinder", "sphere", "shell", "slider")


def _gamma(shape: str) -> float:
    return 0.0 if shape == "slider" else INERTIA_FACTORS[shape]


@given(
    shapes=st.tuples(st.sampled_from(SHAPES), st.sampled_from(SHAPES)),
    masses=st.tuples(st.floats(0.05, 20.0), st.floats(0.05, 20.0)),
    radius=st.floats(0.01, 0.3),
    k=st.floats(1.0, 1e5),
    n=st.integers(4, 12),
    walls=st.sampled_from(("none", "left", "both")),
)
def test_the_periodic_diatomic_chain_has_the_closed_form_branches(
    shapes, masses, radius: float, k: float, n: int, walls: str
) -> None:
    """Springs joining centres on one level (one radius: the centres at one height)."""
    spacing = 2.0 * radius + 0.1
    system = chain(shapes, n, mass=masses, radius=radius, stiffness=k, spacing=spacing, walls=walls)
    result = dispersion(system, 61)
    same = shapes[0] == shapes[1] and math.isclose(*masses, rel_tol=1e-9)  # the reading's tolerance
    assert result.cell.p == (1 if same else 2)
    if result.cell.p == 1:
        return  # the monatomic case: test_the_monatomic_chain_...
    m1, m2 = ((1.0 + _gamma(s)) * m for s, m in zip(shapes, masses, strict=True))
    a = 2.0 * spacing
    assert result.cell.a == pytest.approx(a, rel=1e-15)
    expected = diatomic_branches(result.q, a, k, m1, m2)
    top = float(expected.max())
    np.testing.assert_allclose(result.omega, expected, rtol=0.0, atol=1e-12 * top)
    np.testing.assert_allclose(result.omega**2, expected**2, rtol=0.0, atol=1e-12 * top**2)
    assert result.closed_form is not None
    # (its masses are J/R², (1 + gamma) m to rounding)
    np.testing.assert_allclose(result.closed_form, expected, rtol=0.0, atol=1e-13 * top)
    # the edges and the gap: sqrt(2k/M_heavy), sqrt(2k/M_light) at the zone edge
    heavy, light = max(m1, m2), min(m1, m2)
    edges = result.band_edges
    assert edges[0, 1] == pytest.approx(math.sqrt(2 * k / heavy), rel=1e-12)
    assert edges[1, 0] == pytest.approx(math.sqrt(2 * k / light), rel=1e-12)
    assert edges[1, 1] == pytest.approx(math.sqrt(2 * k * (1 / m1 + 1 / m2)), rel=1e-12)
    if heavy > light * (1 + 1e-9):
        ((branch, low, high),) = result.gaps
        assert branch == 1
        assert (low, high) == pytest.approx((edges[0, 1], edges[1, 0]), rel=1e-15)


def test_the_closed_form_is_the_textbook_formula() -> None:
    q = np.linspace(-math.pi, math.pi, 41)
    k, m1, m2, a = 50.0, 2.0, 1.5, 1.0
    total = 1 / m1 + 1 / m2
    root = np.sqrt(total**2 - 4 * np.sin(q * a / 2) ** 2 / (m1 * m2))
    textbook = np.sqrt(np.stack([k * total - k * root, k * total + k * root], axis=-1))
    np.testing.assert_allclose(diatomic_branches(q, a, k, m1, m2), textbook, rtol=1e-7, atol=1e-7)
    # equal masses: the acoustic branch is the monatomic chain's (spacing a/2), folded
    np.testing.assert_allclose(
        diatomic_branches(q, a, k, 1.3, 1.3)[:, 0], monatomic_branch(q, a / 2, k, 1.3), rtol=1e-12
    )


@pytest.mark.parametrize("shape", SHAPES)
def test_the_monatomic_chain_has_the_sine_branch_and_its_group_velocity(shape: str) -> None:
    k, mass, spacing = 300.0, 1.7, 0.4
    result = dispersion(chain(shape, 6, mass=mass, stiffness=k, spacing=spacing), 201)
    rolling = (1.0 + _gamma(shape)) * mass
    assert result.cell.p == 1
    expected = monatomic_branch(result.q, spacing, k, rolling)
    np.testing.assert_allclose(result.omega[:, 0], expected, rtol=0, atol=1e-12 * expected.max())
    np.testing.assert_allclose(result.closed_form[:, 0], expected, rtol=1e-15)
    # d omega/dq = a sqrt(k/M) cos(qa/2) sign(q); at q = 0 the sound speed a sqrt(k/M)
    speed = spacing * math.sqrt(k / rolling)
    slope = speed * np.cos(result.q * spacing / 2) * np.where(result.q >= 0, 1.0, -1.0)
    np.testing.assert_allclose(result.group_velocity[:, 0], slope, rtol=0, atol=1e-9 * speed)
    # the friction of a travelling wave: f = gamma m omega^2 x (M8 with centre springs)
    np.testing.assert_allclose(
        result.friction[:, 0, 0], _gamma(shape) * mass * expected**2, rtol=1e-9, atol=1e-9 * k
    )
    assert result.gaps == []


def test_diatomic_group_velocities_are_the_slopes_of_the_branches() -> None:
    k, a = 120.0, 1.0
    result = dispersion(chain("hoop,cylinder", 6, mass=[1.0, 0.7], stiffness=k), 401)
    m1, m2 = 2.0 * 1.0, 1.5 * 0.7
    h = 1e-6
    slope = (
        diatomic_branches(result.q + h, a, k, m1, m2)
        - diatomic_branches(result.q - h, a, k, m1, m2)
    ) / (2 * h)
    inside = (np.abs(result.q) > 1e-3) & (np.abs(result.q) < math.pi - 1e-3)
    np.testing.assert_allclose(result.group_velocity[inside], slope[inside], rtol=0, atol=1e-6)
    # q = 0: the acoustic branch's sound speed a sqrt(k/(2(M1 + M2))), the optical one's 0
    centre = int(np.flatnonzero(result.q == 0.0)[0])
    assert result.group_velocity[centre, 0] == pytest.approx(
        a * math.sqrt(k / (2 * (m1 + m2))), rel=1e-6
    )
    assert result.group_velocity[centre, 1] == pytest.approx(0.0, abs=1e-9)


def _fitted_amplitude(values: np.ndarray, phase: np.ndarray) -> float:
    """The amplitude of values = c1 cos(phase) + c2 sin(phase), fitted, and the fit's check."""
    basis = np.stack([np.cos(phase), np.sin(phase)], axis=-1)
    coefficients, *_ = np.linalg.lstsq(basis, values, rcond=None)
    np.testing.assert_allclose(
        basis @ coefficients, values, atol=1e-9 * max(1.0, np.abs(values).max())
    )
    return float(np.hypot(*coefficients))


@pytest.mark.parametrize(
    ("pattern", "heights"),
    [
        ("hoop,cylinder", [0.15, 0.02]),  # off-centre: the friction is not gamma m omega^2 x
        ("hoop,cylinder", None),
        ("sphere,shell,cylinder", [0.05, 0.18, 0.1]),
    ],
)
def test_the_friction_per_branch_matches_a_finite_chains_modal_analysis(pattern, heights) -> None:
    """A chain between two walls (clamped neighbours) has standing waves of the lattice:
    u_r(cell c) = Re(beta e_r exp(iqca)), and the friction of each of its modes (analyze's
    Mode.friction, the same dF/dq) is Re(beta (F(q) e)_r exp(iqca)): per unit amplitude the
    branch's friction at the mode's q."""
    p = len(pattern.split(","))
    cells = 12
    kwargs = {
        "pattern": pattern,
        "height": heights,
        "mass": [1.0, 1.3, 0.8][:p],
        "stiffness": 150.0,
    }
    finite = chain(n=p * cells, walls="both", **kwargs)
    periodic = chain(n=4 * p, **kwargs)
    grid = dispersion(periodic, 201)
    a = grid.cell.a
    positive = grid.q >= 0
    checked = 0
    for mode in analyze(finite).modes:
        assert mode.kind == "oscillating"
        branch = [b for b in range(p) if grid.band_edges[b, 0] < mode.omega < grid.band_edges[b, 1]]
        if len(branch) != 1:
            continue
        (b,) = branch

        def miss(q: float, b: int = b, target: float = mode.omega) -> float:
            return float(dispersion(periodic, wavenumbers=[q]).omega[0, b]) - target

        omegas = grid.omega[positive, b]
        qs = grid.q[positive]
        sign = np.sign(omegas - mode.omega)
        k = int(np.flatnonzero(sign[:-1] != sign[1:])[0])
        q = scipy.optimize.brentq(miss, qs[k], qs[k + 1], xtol=1e-15, rtol=1e-15)
        wave = dispersion(periodic, wavenumbers=[q])
        phase = q * a * np.arange(cells)
        shape = mode.shape_x.reshape(cells, p)
        friction = mode.friction.reshape(cells, p)
        normal = mode.normal_force.reshape(cells, p)
        size = max(_fitted_amplitude(shape[:, r], phase) for r in range(p))
        for r in range(p):
            np.testing.assert_allclose(
                _fitted_amplitude(friction[:, r], phase) / size,
                wave.friction[0, b, r],
                rtol=1e-7,
                atol=1e-9 * grid.friction.max(),
            )
            np.testing.assert_allclose(
                _fitted_amplitude(normal[:, r], phase) / size,
                wave.normal_force[0, b, r],
                rtol=1e-7,
                atol=1e-9 * max(grid.friction.max(), grid.normal_force.max()),
            )
            assert _fitted_amplitude(shape[:, r], phase) / size == pytest.approx(
                wave.displacement[0, b, r], rel=1e-7, abs=1e-9
            )
        checked += 1
    assert checked >= cells  # most modes lie inside a branch


def test_a_displaced_chain_is_read_at_its_equilibrium_and_a_pretension_changes_nothing() -> None:
    plucked = dispersion(chain("hoop,cylinder", 8, walls="both", pluck=3), 21)
    assert any("equilibrium" in w for w in plucked.warnings)
    np.testing.assert_allclose(
        plucked.omega, dispersion(chain("hoop,cylinder", 8), 21).omega, atol=1e-12
    )
    # every spring 10 % shorter at rest: level centre springs keep the closed form
    data = system_to_json(chain("hoop,cylinder", 8))
    for spring in data["springs"]:
        spring["rest_length"] = 0.45
    tense = dispersion(system_from_dict(data), 21)
    assert not tense.warnings
    np.testing.assert_allclose(tense.omega, tense.closed_form, atol=1e-12)
    # unequal rest lengths: a short chain is read where its springs relax, a = 0.45 + 0.55 m
    for s, spring in enumerate(data["springs"]):
        spring["rest_length"] = 0.45 if s % 2 else 0.55
    relaxed = dispersion(system_from_dict(data), 21)
    assert any("equilibrium" in w for w in relaxed.warnings)
    assert relaxed.cell.a == pytest.approx(1.0, rel=1e-12)
    np.testing.assert_allclose(relaxed.omega, relaxed.closed_form, atol=1e-10)


def test_a_system_may_be_given_as_its_json_form_a_path_or_a_preset_name(tmp_path) -> None:
    system = chain("hoop,cylinder", 6)
    expected = dispersion(system, 11).omega
    path = tmp_path / "chain.json"
    path.write_text(json.dumps(system_to_json(system)))
    for given_as in (system_to_json(system), path, str(path)):
        np.testing.assert_array_equal(dispersion(given_as, 11).omega, expected)
    np.testing.assert_array_equal(
        dispersion("two-hoops", 11).omega, dispersion(load_system("two-hoops"), 11).omega
    )


def test_what_is_not_a_periodic_chain_is_a_one_line_error() -> None:
    with pytest.raises(AnalysisError, match="not a periodic chain"):
        dispersion("hoop-cylinder")  # a preset name, a path, a dict or a System
    with pytest.raises(AnalysisError, match="no spring joins two bodies"):
        dispersion(load_system("two-masses").model_copy(update={"springs": []}))
    data = system_to_json(chain("hoop,cylinder", 8))
    data["springs"][1]["stiffness"] = 99.0  # (spring 3 would leave a period of 4 bodies)
    with pytest.raises(AnalysisError, match="differs from springs"):
        unit_cell(system_from_dict(data))
    # a long chain is read as placed: a displaced or unbalanced placement is refused
    with pytest.raises(AnalysisError, match=r"not a periodic chain .* give the chain at rest"):
        dispersion(chain("hoop,cylinder", EQUILIBRIUM_BODIES + 2, pluck=5))
    data = system_to_json(chain("hoop,cylinder", EQUILIBRIUM_BODIES + 2))
    for s, spring in enumerate(data["springs"]):
        spring["rest_length"] = 0.45 if s % 2 else 0.55
    with pytest.raises(AnalysisError, match=r"not an equilibrium of the periodic chain .* at rest"):
        dispersion(system_from_dict(data))
    data = system_to_json(chain("hoop", 4))
    data["bodies"] = data["bodies"][::-1]
    with pytest.raises(AnalysisError, match="from left to right"):
        unit_cell(system_from_dict(data))
    with pytest.raises(AnalysisError, match="points: must be a whole number from 3"):
        dispersion(chain("hoop", 4), 2)


runner = CliRunner()


def test_cli_prints_a_table_json_and_a_figure(tmp_path) -> None:
    path = tmp_path / "chain.toml"
    done = runner.invoke(app, ["chain", "--n", "10", "--walls", "both", "-o", str(path)])
    assert done.exit_code == 0, done.output
    done = runner.invoke(app, ["dispersion", str(path)])
    assert done.exit_code == 0, done.output
    assert "optical" in done.stdout and "Gap between branches 1 and 2: 10 … 11.547" in done.stdout
    done = runner.invoke(app, ["dispersion", str(path), "--json", "--points", "11"])
    assert done.exit_code == 0, done.output
    payload = json.loads(done.stdout)
    assert payload["cell"] == ["hoop1", "cylinder2"] and len(payload["q"]) == 11
    assert [b["name"] for b in payload["branches"]] == ["acoustic", "optical"]
    assert payload["gaps"][0]["omega_low"] == pytest.approx(10.0)
    assert payload["branches"][0]["closed_form"] == pytest.approx(
        payload["branches"][0]["omega"], abs=1e-12
    )
    figure = tmp_path / "branches.png"
    done = runner.invoke(app, ["dispersion", str(path), "--figure", str(figure), "--points", "51"])
    assert done.exit_code == 0, done.output
    assert figure.read_bytes().startswith(b"\x89PNG")


@pytest.mark.parametrize(
    ("args", "message"),
    [
        (["hoop-cylinder"], "error: dispersion: not a periodic chain"),
        (["two-hoops", "--points", "2"], "error: --points: must be a whole number from 3"),
        (
            ["two-hoops", "--figure", "x.pdf"],
            "error: --figure: x.pdf: give a file ending in .png or .svg",
        ),
        (["no-such-file.toml"], "error: no-such-file.toml: file not found"),
    ],
)
def test_cli_errors_are_one_line_with_exit_code_2(args: list[str], message: str) -> None:
    done = runner.invoke(app, ["dispersion", *args])
    assert done.exit_code == 2
    assert done.stderr.strip().startswith(message), done.stderr
    assert len(done.stderr.strip().splitlines()) == 1


@pytest.mark.parametrize(
    ("pattern", "branch"), [("cylinder", 1), ("hoop,cylinder", 1), ("hoop,cylinder", 2)]
)
def test_the_generators_packet_travels_at_about_the_group_velocity(
    pattern: str, branch: int
) -> None:
    """The linear motion (exact modal superposition) of a packet from ``chain(packet=...)``:
    its centroid moves the way and at about the speed dω/dq says (the optical branch's
    packet backwards). A check of the packet's velocities; the energy centroid's speed to 1 %
    is issue 14.4's."""
    from rollspring.analysis.linear import linear_motion

    n, q, width, spacing = 120, 1.2, 3.0, 0.5
    kwargs = {"pattern": pattern, "n": n, "spacing": spacing, "walls": "both"}
    packet = chain(**kwargs, packet=(q, width), branch=branch, amplitude=0.001)
    at_rest = np.array([b.x for b in chain(**kwargs).bodies])
    times = np.linspace(0.0, 1.4, 15)
    moved = linear_motion(analyze(packet), times) - at_rest
    weight = moved**2
    centroid = (weight * at_rest).sum(axis=1) / weight.sum(axis=1)
    speed = np.polyfit(times, centroid, 1)[0]
    expected = dispersion(chain(**kwargs), wavenumbers=[q]).group_velocity[0, branch - 1]
    assert speed == pytest.approx(expected, rel=0.03)

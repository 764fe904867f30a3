"""Waves on long chains (``rollspring.analysis.waves``): the energy per body sums to the total
energy, a packet's energy centroid travels at the group velocity dω/dq of its wavenumber and
branch (the closed forms of the monatomic and diatomic lattices), and a struck end's front
travels no faster than the largest group velocity."""

from __future__ import annotations

import json
import math

import numpy as np
import pytest

from rollspring.analysis.dispersion import diatomic_branches
from rollspring.analysis.waves import (
    Waves,
    body_energies,
    clear_window,
    energy_centroid,
    energy_front,
    travelling_wave,
)
from rollspring.errors import AnalysisError
from rollspring.model import INERTIA_FACTORS, System
from rollspring.model.chains import chain
from rollspring.physics import system_arrays, total_energy
from rollspring.simulate import simulate
from tests.conftest import body, make_system, spring

K = 100.0  # N/m, the chains' springs
SPACING = 0.5  # m


def _rolling_mass(shape: str, mass: float = 1.0) -> float:
    return (1.0 + INERTIA_FACTORS[shape]) * mass


def test_the_energy_per_body_sums_to_the_total_energy() -> None:
    """Off-centre and raised attachments, a wall, a slider and a constant force: the bodies'
    energies add up to T + U of rollspring.physics at random states."""
    system = make_system(
        [
            body("a", "hoop", x=0.0),
            body("b", "cylinder", mass=2.0, radius=0.15, x=0.6),
            body("c", "slider", mass=0.7, radius=0.05, x=1.1),
        ],
        [
            spring("a", "b", stiffness=80.0, at=[{"radius": 0.07, "angle": 30}, {"height": 0.2}]),
            spring("b", "c", stiffness=50.0),
            spring("wall", "a", stiffness=30.0),
        ],
        anchors=[{"id": "wall", "x": -0.5, "y": 0.1}],
        forces=[{"body": "b", "fx": 1.5, "fy": -0.4, "at": {"radius": 0.1, "angle": 90}}],
    )
    arrays = system_arrays(system)
    rng = np.random.default_rng(4)
    q = rng.normal(scale=0.3, size=(7, 3))
    qdot = rng.normal(size=(7, 3))
    x = arrays.x0 + arrays.scale * q
    v = arrays.scale * qdot
    energies = body_energies(arrays, x, v)
    assert energies.shape == (7, 3)
    expected = total_energy(arrays, q, qdot)
    assert energies.sum(axis=-1) == pytest.approx(expected, rel=1e-12, abs=1e-12)


def test_two_bodies_share_their_spring_half_and_half() -> None:
    """Two hoops joined at their centres: e_i = J_i qdot_i^2 / 2 + k (l - L0)^2 / 4 each."""
    system = make_system([body("a"), body("b", x=0.5)], [spring("a", "b", stiffness=K)])
    arrays = system_arrays(system)
    x = np.array([0.01, 0.47])
    v = np.array([0.3, -0.2])
    stretch = (x[1] - x[0]) - 0.5
    jay = 2.0 * 1.0 * 0.1**2  # a hoop: J = 2 m R^2
    expected = 0.5 * jay * (v / 0.1) ** 2 + 0.25 * K * stretch**2
    assert body_energies(arrays, x, v) == pytest.approx(expected, rel=1e-12)


def test_the_energy_partition_sums_to_the_simulated_energy_along_a_packet() -> None:
    system = chain("hoop,cylinder", 40, packet=(1.5, 2.0), walls="both")
    run = simulate(system, 1.0, n_output=51)
    energies = body_energies(system_arrays(system), run.x, run.v)
    assert energies.sum(axis=-1) == pytest.approx(run.energy, rel=1e-10)
    assert np.all(energies >= -1e-15)  # springs at rest in the placement: no negative part


def test_the_centroid_and_spread_of_two_equal_lumps() -> None:
    x = np.array([0.0, 1.0, 2.0, 3.0])
    centroid, spread = energy_centroid(x, np.array([[1.0, 0.0, 0.0, 1.0]]))
    assert centroid[0] == pytest.approx(1.5) and spread[0] == pytest.approx(1.5)
    assert clear_window(np.array([1.5, 1.6, 2.5]), np.array([0.1, 0.1, 0.2]), 0.0, 3.0) == 2
    front = energy_front(x, np.array([[1.0, 1.0, 1.0, 1e-4]]), start=0.0, fraction=1e-3)
    assert front[0] == pytest.approx(2.0)  # 1e-4 of 3 beyond body 4 is below 1e-3


def _measured(system: System, duration: float, rows: int, q: float | None = None) -> Waves:
    """The waves of a run; with ``q``, also checks that the group velocity at the wavenumber
    found from the motion is the one at ``q`` to the FFT's resolution."""
    run = simulate(system, duration, n_output=rows, rtol=1e-6)
    assert run.status == "finished"
    found = travelling_wave(system, run.t, run.x, run.v)
    if q is None:
        return found
    assert found.wavenumber == pytest.approx(q, abs=math.pi / (16 * len(system.bodies) * SPACING))
    given = travelling_wave(system, run.t, run.x, run.v, wavenumber=q)
    assert found.branch == given.branch
    assert found.group_velocity == pytest.approx(given.group_velocity, rel=2e-3)
    return given


@pytest.mark.parametrize("q", [1.0, 2.0])
def test_a_packet_on_a_monatomic_chain_travels_at_the_group_velocity(q: float) -> None:
    """200 hoops; ω = 2 sqrt(k/M) |sin(qa/2)| (M = 2m) gives v_g = a sqrt(k/M) cos(qa/2).
    A width of 16 cells: the part of the packet travelling back (the start uses ω(q) for
    every q of the packet) and its spread of group velocities are well below 1%."""
    system = chain("hoop", 200, spacing=SPACING, packet=(q, 8.0), walls="both")
    waves = _measured(system, 10.0, 201, q)
    expected = SPACING * math.sqrt(K / _rolling_mass("hoop")) * math.cos(q * SPACING / 2)
    assert waves.kind == "packet"
    assert waves.branch == 1
    assert waves.group_velocity == pytest.approx(expected, rel=1e-9)
    assert waves.window >= 100  # clear of the ends over at least half the run
    assert waves.speed == pytest.approx(expected, rel=0.01)


@pytest.mark.parametrize(("branch", "q"), [(1, 1.5), (2, 1.5), (2, 2.5)])
def test_a_packet_on_a_diatomic_chain_travels_at_the_group_velocity(branch: int, q: float) -> None:
    """Hoops and cylinders (masses 2 and 1.5 kg rolling), both branches: the centroid's speed
    against dω/dq of the closed form (a central difference), within 1%."""
    system = chain("hoop,cylinder", 240, spacing=SPACING, packet=(q, 10.0), branch=branch)
    waves = _measured(system, 10.0, 201, q)
    a = 2 * SPACING
    m1, m2 = _rolling_mass("hoop"), _rolling_mass("cylinder")
    h = 1e-5
    omega = diatomic_branches(np.array([q - h, q + h]), a, K, m1, m2)[:, branch - 1]
    expected = float(omega[1] - omega[0]) / (2 * h)
    assert waves.kind == "packet"
    assert waves.branch == branch  # found from the motion's frequency
    assert waves.group_velocity == pytest.approx(expected, rel=1e-7)
    assert waves.window >= 100
    assert waves.speed == pytest.approx(expected, rel=0.01)


def test_a_struck_end_sends_a_front_no_faster_than_the_largest_group_velocity() -> None:
    """Hoop 1 of 200 displaced next to a wall: the front (1e-3 of the energy ahead of it) is
    never more than two cells ahead of c t, c = a sqrt(k/M) the largest group velocity of the
    monatomic lattice (at q = 0), and it does travel: its slope is within 10% of c."""
    system = chain("hoop", 200, spacing=SPACING, pluck=1, walls="left")
    waves = _measured(system, 20.0, 201)
    c = SPACING * math.sqrt(K / _rolling_mass("hoop"))
    assert waves.kind == "front"
    assert waves.max_group_velocity == pytest.approx(c, rel=1e-9)
    assert waves.front is not None
    assert np.all(waves.front <= c * waves.t + 2 * SPACING)
    assert 0.9 * c <= waves.speed <= c


def test_a_chain_whose_energy_fills_it_has_no_speed() -> None:
    system = chain("hoop", 30, mode=3, walls="both")
    waves = _measured(system, 1.0, 21)
    assert waves.kind == "spread"
    assert math.isnan(waves.speed)
    assert waves.notes


def test_bad_arrays_are_refused() -> None:
    arrays = system_arrays(chain("hoop", 5))
    with pytest.raises(AnalysisError, match="body_energies: x and v"):
        body_energies(arrays, np.zeros((2, 5)), np.zeros((2, 4)))


def test_a_long_chain_gets_a_report_that_summarises_its_wave(monkeypatch) -> None:  # type: ignore[no-untyped-def]
    """More than LONG_CHAIN bodies: no per-body tables or modal analysis; space–time images,
    the chain animation and the measured speed beside dω/dq, the numbers those of
    travelling_wave on the report's own run."""
    from rollspring.model.chains import LONG_CHAIN
    from rollspring.outputs.report import _chain
    from rollspring.service.documents import build_report

    monkeypatch.setattr(_chain, "CHAIN_FRAMES", 4)
    n = 3 * LONG_CHAIN
    system = chain("hoop", n, spacing=SPACING, packet=(2.0, 3.0), walls="both")
    report = build_report(system, duration=2.0, derivation=False)
    assert report.analysis is None
    for section in ("overview", "chain", "waves", "space-time", "animation", "energy", "data"):
        assert section in report.sections
    html = report.html
    assert 'id="bodies"' not in html and 'id="modes"' not in html  # nothing per body
    assert 'id="figure-space-time"' in html
    assert html.count("<img") >= 2
    waves = travelling_wave(system, report.trajectory.t, report.trajectory.x, report.trajectory.v)
    start = html.index('id="wave-data">') + len('id="wave-data">')
    data = json.loads(html[start : html.index("</script>", start)])
    assert data["kind"] == "packet" == waves.kind
    assert data["speed"] == pytest.approx(waves.speed, rel=1e-12)
    assert data["group_velocity"] == pytest.approx(waves.group_velocity, rel=1e-12)
    c = SPACING * math.sqrt(K / _rolling_mass("hoop")) * math.cos(2.0 * SPACING / 2)
    assert data["group_velocity"] == pytest.approx(c, rel=5e-3)  # at the q found (FFT grid)
    assert "Chain" in html and f"{n} bodies" in html


def test_a_small_system_keeps_the_full_report() -> None:
    from rollspring.service.documents import build_report

    report = build_report(chain("hoop,cylinder", 3, pluck=1), duration=0.2, derivation=False)
    assert report.analysis is not None
    assert "modes" in report.sections and "space-time" not in report.sections

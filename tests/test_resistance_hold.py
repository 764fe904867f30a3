"""Rolling resistance's ``hold`` (docs/physics.md (M22), simulate/general.py): a body set turning
where a segment starts whose drive is beyond :math:`C_{rr} N R` by so little that it turns back
against its resistance at once is held at rest there, not released again at that instant, and
released only where its drive next exceeds the bound -- at the closed-form instant."""

from __future__ import annotations

import math

import numpy as np
import pytest

from rollspring.physics import system_arrays
from rollspring.simulate import kernels, simulate
from rollspring.simulate.crossings import ROOT_TOLERANCE
from rollspring.simulate.general import GeneralSegments
from tests.conftest import body, make_system, spring

G = 9.81
K = 100.0  # the spring's stiffness, N/m
C_RR = 0.01  # the cylinder's rolling resistance
LIMIT = C_RR * 1.0 * G  # C_rr N of the 1 kg cylinder: it is held while k |s| <= C_rr m g
W = math.sqrt(K / (2 * 0.5))  # the hoop's frequency on the spring, M_hoop = (1 + 1) 0.5 kg
V_HOOP = -1.0  # the hoop runs back toward the cylinder: the stretch falls at 1 m/s


def pulled_pair(x_hoop: float):
    """A cylinder (1 kg, R = 0.1 m, C_rr) at rest at x = 0 and a free hoop (0.5 kg, no
    resistance) at ``x_hoop`` on a centre spring (k, rest length 0.5 m), the hoop running back
    at 1 m/s: the spring's pull on the cylinder, k s with s = x_hoop - 0.5, falls at once."""
    return make_system(
        bodies=[
            body("cyl", "cylinder", mass=1.0, radius=0.1, x=0.0, rolling_resistance=C_RR),
            body("hoop", "hoop", mass=0.5, radius=0.1, x=x_hoop, v=V_HOOP),
        ],
        springs=[spring("cyl", "hoop", stiffness=K, rest_length=0.5)],
    )


def drive_beyond_bound(system) -> float:
    """The cylinder's :math:`|D| - C_{rr} N R` at release, as the run's kernel measures it."""
    arrays = system_arrays(system)
    state = np.concatenate([arrays.x0, np.zeros(2), arrays.v0, arrays.v0 / arrays.scale])
    drive, limit = np.empty(2), np.empty(2)
    model = kernels.kernel_model(arrays)
    kernels.resistance_drives(
        model, state, np.zeros(2, dtype=bool), np.zeros(2), False, drive, limit
    )
    return float(abs(drive[0]) - limit[0])


def record_holds(monkeypatch) -> list[dict]:
    """Every ``hold`` that :meth:`GeneralSegments._resistance_events` settles: its time and
    body, ``held_at`` and the spins after it, and the held body's ``|D| - C_rr N R`` in the
    state it was held in."""
    holds: list[dict] = []
    original = GeneralSegments._resistance_events

    def recording(self, t, state, slipping, sign, acceleration, trigger=None):
        original(self, t, state, slipping, sign, acceleration, trigger)
        if trigger is not None and trigger[0] == "hold":
            drive, limit = self._resistance_drive(state, slipping, sign)
            i = trigger[1]
            holds.append(
                {
                    "time": t,
                    "body": i,
                    "held_at": self.held_at.copy(),
                    "spin": self.spin.copy(),
                    "beyond": float(abs(drive[i]) - limit[i]),
                }
            )

    monkeypatch.setattr(GeneralSegments, "_resistance_events", recording)
    return holds


def check_held_then_released(tr, rtol: float) -> float:
    """The physics of a pulled pair held at once: the cylinder wholly at rest (M22) until the
    hoop's harmonic swing s(t) = s_i cos(W t) + (v / W) sin(W t) has turned the spring's pull
    into a push of C_rr m g, released there, the hoop on its closed form meanwhile, and the
    energy balance E + W_dissipated = E0 with nothing dissipated while held. Returns the
    release time."""
    s_i = tr.x[0, 1] - 0.5
    amplitude = math.hypot(s_i, V_HOOP / W)
    phase = math.atan2(-V_HOOP / W, s_i)  # s = A cos(W t + phase)
    t_release = (math.acos(-LIMIT / K / amplitude) - phase) / W  # first s = -C_rr m g / k
    assert tr.status == "finished"
    [rest, release, *_] = tr.events
    assert (rest["kind"], rest["body"]) == ("rest", "cyl")
    assert (release["kind"], release["body"]) == ("release", "cyl")
    assert release["time"] == pytest.approx(t_release, abs=1e-12)
    # nothing else at the instant it was held: above all no release of the held body
    assert [e for e in tr.events if e["time"] == rest["time"]] == [rest]
    held = tr.t < release["time"]
    assert held.sum() > 10
    assert np.all(tr.v[held, 0] == 0.0) and np.all(tr.omega[held, 0] == 0.0)
    assert np.max(np.abs(tr.x[held, 0])) <= 1e-15
    swing = s_i * np.cos(W * tr.t[held]) + V_HOOP / W * np.sin(W * tr.t[held])
    np.testing.assert_allclose(tr.x[held, 1], 0.5 + swing, atol=1e-12)
    # held, the cylinder dissipates nothing and the hoop keeps its energy
    np.testing.assert_allclose(tr.energy[held], tr.summary["energy"], rtol=1e-12)
    assert tr.summary["energy"] == pytest.approx(0.5 * 1.0 * V_HOOP**2 + 0.5 * K * s_i**2)
    assert tr.summary["energy_error"] < 10 * rtol
    # released, it rolls back with the push and its resistance dissipates
    rolling = (tr.t > release["time"] + 1e-3) & (tr.t < release["time"] + 0.02)
    assert rolling.sum() > 100 and np.all(tr.v[rolling, 0] < 0.0)
    assert tr.summary["dissipated_by"]["rolling_resistance"] > 0.0
    return t_release


@pytest.mark.parametrize("rtol", [1e-12, 1e-8])
def test_a_drive_beyond_the_bound_that_falls_back_at_once_is_held_until_the_closed_form_release(
    monkeypatch, rtol
):
    """The spring pulls the cylinder with (1 + 1e-12) C_rr m g while the hoop runs back at
    1 m/s: the cylinder is set turning (its drive is beyond the bound) but its drive falls
    below the bound within 2e-15 s, where its rotation, some 1e-28 rad/s, turns back: the
    segment's ``turn`` event at its start becomes a ``hold``, ``held_at`` is set, and the
    cylinder rests there -- the exact motion to the last bit. Checked: the branch is taken once,
    at the start, for the cylinder; then the physics of :func:`check_held_then_released`."""
    holds = record_holds(monkeypatch)
    system = pulled_pair(0.5 + LIMIT * (1 + 1e-12) / K)
    assert drive_beyond_bound(system) > 0.0  # set turning at release, not held
    tr = simulate(system, 0.05, rtol=rtol, n_output=501)
    [hold] = holds
    assert hold["body"] == 0 and hold["held_at"][0] == hold["time"]
    assert 0.0 <= hold["time"] <= 16 * ROOT_TOLERANCE  # turned back at once
    assert hold["spin"][0] == 0.0
    assert tr.events[0]["time"] == hold["time"]
    check_held_then_released(tr, rtol)


@pytest.mark.parametrize("rtol", [1e-12, 1e-10, 1e-8])
def test_a_pull_at_the_bound_to_the_last_bit_is_held_and_not_released_again_at_that_instant(
    monkeypatch, rtol
):
    """The spring's pull at C_rr m g itself (s = C_rr m g / k), the hoop running back: the
    first hoop position from there on whose pull the kernel measures beyond the bound (by
    rounding) sets the cylinder turning, and it turns back at the very start. Held there, its
    drive still measures beyond the bound in the state it rests in -- the case ``held_at`` is
    for: the ``hold`` keeps it at rest, the next segment does not release it again at that
    instant (a release there would turn it back at once again, a run of segments that end
    where they start), and the run goes on to the closed-form release. At rtol 1e-10 and
    above the integrator's first step passes over the whole time the drive stays inside the
    bound, from the hold to the release: read as it is, the held body's release function is
    past zero at both ends of that step, and the body was never released (held on while the
    spring pushed it with 80 times the bound, until the hoop slipped at 0.14 s). It is now
    measured from its value where the segment starts."""
    holds = record_holds(monkeypatch)
    x_hoop = 0.5 + LIMIT / K
    while drive_beyond_bound(pulled_pair(x_hoop)) <= 0.0:
        x_hoop = float(np.nextafter(x_hoop, np.inf))
    below = float(np.nextafter(x_hoop, -np.inf))
    assert drive_beyond_bound(pulled_pair(below)) <= 0.0 < drive_beyond_bound(pulled_pair(x_hoop))
    assert abs(x_hoop - 0.5 - LIMIT / K) < 1e-15  # at the bound to a few bits
    tr = simulate(pulled_pair(x_hoop), 0.05, rtol=rtol, n_output=501)
    [hold] = holds
    assert hold["body"] == 0 and hold["held_at"][0] == hold["time"] == 0.0
    assert hold["beyond"] > 0.0  # still past the bound, by rounding, where it is held
    assert hold["spin"][0] == 0.0
    check_held_then_released(tr, rtol)


def test_a_body_held_under_loads_far_above_its_bound_is_released_when_the_drive_passes_it(
    monkeypatch,
):
    """The rounding a hold leaves in the release function is that of the drive's terms, not of
    the bound: a cylinder with C_rr = 1e-4 (a bound of 9.8e-4 N) pushed back by a constant 1e4 N
    and pulled by a stiff spring (1e5 N/m) balancing it to the bound, the hoop running back at
    1 m/s. Held at the start (its drive past the bound by 1.07e-9 of it, rounding of 1e4 N), it
    is released where the spring's pull has fallen by twice the bound, at 2 C_rr m g / (k v)
    = 1.96e-8 s; an offset limited to 1e-9 of the bound left it held for good (it slipped at
    7.2e-5 s, pushed with a growing force while still at rest)."""
    holds = record_holds(monkeypatch)
    c_rr, k, push = 1e-4, 1e5, 1e4
    bound = c_rr * 1.0 * G

    def loaded(x_hoop: float):
        return make_system(
            bodies=[
                body("cyl", "cylinder", mass=1.0, radius=0.1, x=0.0, rolling_resistance=c_rr),
                body("hoop", "hoop", mass=0.5, radius=0.1, x=x_hoop, v=V_HOOP, mu_static=math.inf),
            ],
            springs=[spring("cyl", "hoop", stiffness=k, rest_length=0.5)],
            forces=[{"body": "cyl", "fx": -push}],
        )

    x_hoop = 0.5 + (push + bound) / k
    for _ in range(10_000):  # the first hoop position whose drive measures past the bound
        if drive_beyond_bound(loaded(x_hoop)) > 0.0:
            break
        x_hoop = float(np.nextafter(x_hoop, np.inf))
    assert drive_beyond_bound(loaded(x_hoop)) > 0.0
    for rtol in (1e-8, 1e-12):
        holds.clear()
        tr = simulate(loaded(x_hoop), 1e-4, rtol=rtol, n_output=201)
        [hold] = holds
        # past the bound (a torque, C_rr N R) by more than 1e-9 of it
        assert hold["time"] == 0.0 and hold["beyond"] > 1e-9 * bound * 0.1
        rest, release = tr.events[:2]
        assert (rest["kind"], rest["time"], release["kind"]) == ("rest", 0.0, "release")
        assert release["time"] == pytest.approx(2 * bound / (k * abs(V_HOOP)), rel=1e-3)

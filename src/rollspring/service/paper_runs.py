r"""The paper check's counterexamples, run: the exact nonlinear motion of the system a verdict
names, and the quantity that shows it.

A claim of the paper check (:mod:`rollspring.analysis.paper`) that is wrong, or holds only under a
condition the paper leaves unstated, names a :class:`~rollspring.analysis.paper.Counterexample`:
one of the paper's systems, how its motion starts, what is measured and the value the paper's
statement gives for it. :func:`run_counterexample` simulates it (:func:`rollspring.simulate`,
``rtol = 1e-10``) and measures; the run *disagrees* when
:math:`|\text{measured} - \text{paper}| > \text{tolerance}`.

The measures (:data:`MEASURES`), each a pure function of the run (ratios are dimensionless, a
distance in metres; :math:`\operatorname{ptp}` is the peak-to-peak range over the run,
:math:`\delta u = u - \bar u` the deviation from the run's mean, :math:`J_i = I_i + m_iR_i^2` the
inertia about the contact line, the paper's :math:`I'_i`):

* ``stationary_point_paper``: :math:`\operatorname{ptp}(\hat X_{\text{paper}}) /
  \operatorname{ptp}(x_1)` with the paper's eq. (c), :math:`\hat X = \sum J_i x_i / \sum J_i`;
* ``contact_momentum``: :math:`\operatorname{ptp}(\sum J_i\dot\varphi_i) /
  \operatorname{ptp}(J_1\dot\varphi_1)` (the paper's (rel1), :math:`I'_1\dot\varphi_1 +
  I'_2\dot\varphi_2 = 0`);
* ``cm_motion``: :math:`\operatorname{ptp}(X) / \operatorname{ptp}(x_1)`, X the centre of mass;
* ``cm_drift``: :math:`|\langle X\rangle_{\text{last period}} - \langle X\rangle_{\text{first
  period}}|` (m): how far the centre of mass creeps;
* ``mu_needed``: :math:`\max |f_i|/N_i`, the static friction coefficient the motion needs;
* ``friction_order``: :math:`\log_2` of :math:`\max|f|` at the amplitude over
  :math:`\max|f|` at half of it: the order in the amplitude of the static friction;
* ``friction_with_cm_still``: :math:`\max|f_1| / \max|F_{1x}|`, with :math:`F_{1x} = m_1\ddot
  x_1 - f_1` the spring's horizontal pull on body 1 (Newton);
* ``phi_ratio``: the slope of :math:`\delta\varphi_2` on :math:`\delta\varphi_1` (the mode's
  ratio :math:`\varphi_2/\varphi_1`, signed);
* ``canonical_ratio``: the same for :math:`q_i = \sqrt{J_i/m_i}\,\varphi_i` (Sec. 5.6);
* ``x1_offset``: :math:`\bar x_1 / (\operatorname{ptp}(x_1)/2)`: the centre of the
  oscillation of the centre's coordinate :math:`x_1`, in amplitudes;
* ``phi_relation_offset``: :math:`\overline{(J_1\varphi_1 + J_2\varphi_2)} /
  (J_2\operatorname{ptp}(\varphi_2)/2)` with :math:`\varphi_i = x_i/R_i` (the centres' coordinates):
  the integration constant of Sec. 5.1's :math:`\varphi_2 = -(4m_1/3m_2)\varphi_1`;
* ``omega2_over_clamped_sum``: :math:`\Omega^2 / \sum_i K_{ii}/J_i`, Ω from the measured period;
* ``omega2_over_clamped_first``: :math:`\Omega^2 / (K_{11}/J_1)`;
* ``angular_momentum_change``: :math:`\operatorname{ptp}(L_O) / \operatorname{ptp}(\sum
  J_i\dot\varphi_i)`, :math:`L_O = \sum (I_i\dot\varphi_i + m_i y_{ci}\dot x_i)` about a fixed
  point of the lower floor (clockwise), :math:`y_{ci}` the centre's height;
* ``cylinder_friction_k2``: :math:`|{\rm slope}(\delta f_2, \delta\varphi_2)| / (k_2R/2)` with
  App. A's :math:`k_2 = k(3m_2 + 4m_1)/(4m_1)` (the paper's eq. for :math:`f_2`).
"""

from __future__ import annotations

import copy
import math
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

import numpy as np

from rollspring.analysis.paper import SYSTEMS, ClaimCheck, Counterexample

__all__ = [
    "MEASURES",
    "CounterexampleRun",
    "drift_rate",
    "run_counterexample",
    "run_counterexamples",
]

#: The accuracy of the runs (the simulator's relative tolerance).
RTOL = 1e-10


@dataclass(frozen=True)
class CounterexampleRun:
    """A counterexample run: ``measured`` beside the ``paper``'s value; ``disagrees`` when they
    differ by more than the tolerance; ``details`` what else the run shows (words, numbers)."""

    counterexample: Counterexample
    measured: float
    details: str

    @property
    def disagrees(self) -> bool:
        return bool(abs(self.measured - self.counterexample.paper) > self.counterexample.tolerance)

    def to_dict(self) -> dict[str, Any]:
        """The JSON form: the counterexample's fields, ``measured``, ``disagrees``, ``details``."""
        return {
            **self.counterexample.to_dict(),
            "measured": self.measured,
            "disagrees": self.disagrees,
            "details": self.details,
        }


@dataclass(frozen=True)
class _Run:
    """A simulated run and what the measures need of its system."""

    data: dict[str, Any]
    run: Any
    period: float
    mass: np.ndarray
    radius: np.ndarray
    central: np.ndarray  # I_i about the centre
    contact: np.ndarray  # J_i = I_i + m_i R_i^2 about the contact line (the paper's I')
    centre_height: np.ndarray
    acceleration: np.ndarray  # the centres' xddot_i at the output times, from the physics (M7)


def _simulate(counterexample: Counterexample, amplitude: float | None = None) -> _Run:
    from rollspring.analysis import analyze
    from rollspring.model import system_from_dict
    from rollspring.physics import accelerations, system_arrays
    from rollspring.simulate.run import simulate

    data = copy.deepcopy(SYSTEMS[counterexample.system])
    system = system_from_dict(data)
    analysis = analyze(system)
    mode = analysis.oscillating[0]
    if counterexample.start == "mode":
        arrays = system_arrays(system)
        zero = np.zeros(len(system.bodies))
        if np.max(np.abs(accelerations(arrays, zero, zero))) > 1e-9:
            raise ValueError(f"{counterexample.system}: a mode start needs the equilibrium")
        shape_q = np.asarray(mode.shape_q, dtype=float)
        shape_x = np.asarray(mode.shape_x, dtype=float)
        a = counterexample.amplitude if amplitude is None else amplitude
        speeds = shape_x * (a / abs(shape_q[-1])) * mode.omega
        for body, speed in zip(data["bodies"], speeds, strict=True):
            body["v"] = float(speed)
        system = system_from_dict(data)
    periods = counterexample.periods
    run = simulate(
        system,
        periods * mode.period,
        rtol=RTOL,
        n_output=int(max(2001, 400 * periods)),
        confirm=True,
    )
    if str(run.status) != "finished":
        raise RuntimeError(f"{counterexample.system}: the run ended {run.status}: {run.message}")
    bodies = system.bodies
    radius = np.array([b.radius for b in bodies])
    # every output row rolls (the run finished without a slip): xddot_i = R_i phiddot_i exactly
    angular = accelerations(system_arrays(system), run.phi, run.omega)
    return _Run(
        data,
        run,
        mode.period,
        np.array([b.mass for b in bodies]),
        radius,
        np.array([b.central_inertia for b in bodies]),
        np.array([b.contact_inertia for b in bodies]),
        np.array([b.track_height + b.radius for b in bodies]),
        radius * angular,
    )


def _ptp(values: np.ndarray) -> float:
    return float(np.ptp(values))


def _slope(y: np.ndarray, x: np.ndarray) -> float:
    dx, dy = x - x.mean(), y - y.mean()
    return float(np.dot(dx, dy) / np.dot(dx, dx))


def _spring_pull(r: _Run) -> np.ndarray:
    """F_ix = m_i xddot_i - f_i (Newton along x), xddot from the physics' accelerations."""
    result: np.ndarray = r.mass * r.acceleration - r.run.friction
    return result


def _period_mean(values: np.ndarray, t: np.ndarray, period: float, last: bool) -> float:
    window = (t >= t[-1] - period) if last else (t <= t[0] + period)
    return float(values[window].mean())


def _stationary_point_paper(cx: Counterexample) -> tuple[float, str]:
    r = _simulate(cx)
    contact = r.contact
    paper = r.run.x @ contact / contact.sum()
    true = _ptp(r.run.stationary_x) / _ptp(r.run.x[:, 0])
    return (
        _ptp(paper) / _ptp(r.run.x[:, 0]),
        f"X-hat with the weights I'_i/R_i^2 stays put (range {true:.1e} of body 1's)",
    )


def _contact_momentum(cx: Counterexample) -> tuple[float, str]:
    r = _simulate(cx)
    contact = r.contact
    total = r.run.omega @ contact
    conserved = r.run.omega @ (contact / r.radius)
    kept = _ptp(conserved) / _ptp(contact[0] * r.run.omega[:, 0] / r.radius[0])
    return (
        _ptp(total) / _ptp(contact[0] * r.run.omega[:, 0]),
        f"sum I'_i phidot_i / R_i is what is conserved (range {kept:.1e} of body 1's)",
    )


def _cm_motion(cx: Counterexample) -> tuple[float, str]:
    r = _simulate(cx)
    return (
        _ptp(r.run.cm_x) / _ptp(r.run.x[:, 0]),
        f"the centre of mass swings {_ptp(r.run.cm_x) * 1e3:.3g} mm peak to peak",
    )


def _drift_rate(r: _Run, amplitude: float) -> float | None:
    r"""The growth rate (1/s) of the pair's slow motion: a line through the logarithm of
    :math:`|\langle\varphi_1\rangle|` per period while it is between 1e-3 and 0.1 of the
    amplitude; None when it stays below."""
    t = r.run.t
    periods = int(round(t[-1] / r.period))
    mean = np.array(
        [
            abs(r.run.phi[(t >= j * r.period) & (t < (j + 1) * r.period), 0].mean())
            for j in range(periods)
        ]
    )
    middle = (np.arange(periods) + 0.5) * r.period
    grows = (mean > 1e-3 * amplitude) & (mean < 0.1 * amplitude)
    if np.count_nonzero(grows) < 4:
        return None
    return float(np.polyfit(middle[grows], np.log(mean[grows]), 1)[0])


def drift_rate(counterexample: Counterexample) -> float | None:
    r"""The growth rate :math:`\lambda` (1/s) of the slow drift of ``counterexample``'s pair (a
    mode start): :math:`|\langle\varphi_1\rangle_{\text{period}}| \propto e^{\lambda t}`, or
    None when the drift stays below a thousandth of the amplitude."""
    return _drift_rate(_simulate(counterexample), counterexample.amplitude)


def _cm_drift(cx: Counterexample) -> tuple[float, str]:
    r = _simulate(cx)
    t, cm = r.run.t, r.run.cm_x
    drift = abs(_period_mean(cm, t, r.period, True) - _period_mean(cm, t, r.period, False))
    rate = _drift_rate(r, cx.amplitude)
    words = ""
    if rate is not None:
        omega = 2 * math.pi / r.period
        words = (
            f"; the drift grows as exp(lambda t), lambda = {rate:.3g} s^-1 = "
            f"{rate / (cx.amplitude * omega):.2f} a Omega (the mode's zero-frequency partner "
            "is unstable beyond first order)"
        )
    early = t <= t[0] + 10 * r.period
    ratio = np.abs(r.run.friction) / r.run.normal
    return (
        drift,
        f"at {cx.amplitude:g} rad the centre of mass moves {drift * 1e3:.3g} mm in "
        f"{t[-1]:.3g} s ({cx.periods:g} periods){words}; the motion needs mu_s >= "
        f"{np.max(ratio[early]):.2g} over its first 10 periods, {np.max(ratio):.2g} over all",
    )


def _mu_needed(cx: Counterexample) -> tuple[float, str]:
    r = _simulate(cx)
    ratio = np.abs(r.run.friction) / r.run.normal
    pull = float(np.max(np.abs(_spring_pull(r))))
    return (
        float(np.max(ratio)),
        f"max |f| = {np.max(np.abs(r.run.friction)):.2e} N at {cx.amplitude:g} rad, the "
        f"spring's pull {pull:.2e} N",
    )


def _friction_order(cx: Counterexample) -> tuple[float, str]:
    full = _simulate(cx)
    half = _simulate(cx, cx.amplitude / 2)
    big = float(np.max(np.abs(full.run.friction)))
    small = float(np.max(np.abs(half.run.friction)))
    pull = float(np.max(np.abs(_spring_pull(full))))
    mu = float(np.max(np.abs(full.run.friction) / full.run.normal))
    return (
        math.log2(big / small),
        f"max |f| = {big:.2e} N at {cx.amplitude:g} rad ({big / pull:.1e} of the spring's "
        f"pull), {small:.2e} N at half of it; mu_s >= {mu:.1e} is enough",
    )


def _friction_with_cm_still(cx: Counterexample) -> tuple[float, str]:
    r = _simulate(cx)
    pull = _spring_pull(r)
    cm = _ptp(r.run.cm_x) / _ptp(r.run.x[:, 0])
    return (
        float(np.max(np.abs(r.run.friction[:, 0])) / np.max(np.abs(pull[:, 0]))),
        f"the centre of mass moves {cm:.1e} of body 1's range: f_1 = -f_2",
    )


def _phi_ratio(cx: Counterexample) -> tuple[float, str]:
    r = _simulate(cx)
    return (
        _slope(r.run.phi[:, 1], r.run.phi[:, 0]),
        "phi_2/phi_1 in the motion: negative, the bodies turn in phase opposition",
    )


def _canonical_ratio(cx: Counterexample) -> tuple[float, str]:
    r = _simulate(cx)
    q = r.run.phi * np.sqrt(r.contact / r.mass)
    return _slope(q[:, 1], q[:, 0]), "q_2/q_1 in the motion, q_i = sqrt(I'_i/m_i) phi_i"


def _x1_offset(cx: Counterexample) -> tuple[float, str]:
    r = _simulate(cx)
    x1 = r.run.x[:, 0]
    return (
        float(x1.mean() / (_ptp(x1) / 2)),
        f"x_1 oscillates about {x1.mean() * 1e3:.3g} mm, its equilibrium, not about 0",
    )


def _phi_relation_offset(cx: Counterexample) -> tuple[float, str]:
    r = _simulate(cx)
    phi = r.run.x / r.radius  # the centres' coordinates over R
    contact = r.contact
    combination = phi @ contact
    return (
        float(combination.mean() / (contact[1] * _ptp(phi[:, 1]) / 2)),
        f"J_1 phi_1 + J_2 phi_2 = {combination.mean():.3g} kg m^2, a constant, not 0",
    )


def _omega2(r: _Run) -> float:
    measured = float(r.run.summary["period_measured"])
    return (2 * math.pi / measured) ** 2


def _clamped(r: _Run) -> np.ndarray:
    from rollspring.model import system_from_dict
    from rollspring.physics import stiffness_matrix, system_arrays

    system = system_from_dict(r.data)
    arrays = system_arrays(system)
    stiffness = stiffness_matrix(arrays, np.zeros(len(system.bodies)))
    result: np.ndarray = np.diag(stiffness) / r.contact
    return result


def _omega2_over_clamped_sum(cx: Counterexample) -> tuple[float, str]:
    r = _simulate(cx)
    clamped = _clamped(r)
    return (
        _omega2(r) / float(clamped.sum()),
        f"Omega^2 = {_omega2(r):.4g} s^-2 measured, Omega_1^2 + Omega_2^2 = "
        f"{clamped.sum():.4g} s^-2",
    )


def _omega2_over_clamped_first(cx: Counterexample) -> tuple[float, str]:
    r = _simulate(cx)
    clamped = _clamped(r)
    return (
        _omega2(r) / float(clamped[0]),
        f"Omega^2 = {_omega2(r):.4g} s^-2 measured, the clamped Omega_1^2 = {clamped[0]:.4g} "
        "s^-2: no frequency of the coupled motion",
    )


def _angular_momentum_change(cx: Counterexample) -> tuple[float, str]:
    r = _simulate(cx)
    about_floor = r.run.omega @ r.central + r.run.v @ (r.mass * r.centre_height)
    paper = r.run.omega @ r.contact
    return (
        _ptp(about_floor) / _ptp(paper),
        f"sum I'_i phidot_i changes by {_ptp(paper):.2e} kg m^2/s, the angular momentum about "
        f"a fixed point by {_ptp(about_floor):.2e}",
    )


def _cylinder_friction_k2(cx: Counterexample) -> tuple[float, str]:
    r = _simulate(cx)
    spring = r.data["springs"][0]["stiffness"]
    m1, m2 = r.mass
    k2 = spring * (3 * m2 + 4 * m1) / (4 * m1)
    slope = abs(_slope(r.run.friction[:, 1], r.run.phi[:, 1]))
    return (
        slope / (k2 * r.radius[1] / 2),
        f"f_2 = {slope / (k2 * r.radius[1]):.4f} k_2 R phi_2 in the motion",
    )


#: The measures by name: each runs the counterexample and gives (measured value, details).
MEASURES: dict[str, Callable[[Counterexample], tuple[float, str]]] = {
    "stationary_point_paper": _stationary_point_paper,
    "contact_momentum": _contact_momentum,
    "cm_motion": _cm_motion,
    "cm_drift": _cm_drift,
    "mu_needed": _mu_needed,
    "friction_order": _friction_order,
    "friction_with_cm_still": _friction_with_cm_still,
    "phi_ratio": _phi_ratio,
    "canonical_ratio": _canonical_ratio,
    "x1_offset": _x1_offset,
    "phi_relation_offset": _phi_relation_offset,
    "omega2_over_clamped_sum": _omega2_over_clamped_sum,
    "omega2_over_clamped_first": _omega2_over_clamped_first,
    "angular_momentum_change": _angular_momentum_change,
    "cylinder_friction_k2": _cylinder_friction_k2,
}


def run_counterexample(counterexample: Counterexample) -> CounterexampleRun:
    """Simulate ``counterexample``'s system and measure (see the module docstring)."""
    measure = MEASURES.get(counterexample.measure)
    if measure is None:
        raise ValueError(f"counterexample: no measure {counterexample.measure!r}")
    measured, details = measure(counterexample)
    return CounterexampleRun(counterexample, float(measured), details)


def run_counterexamples(
    checks: tuple[ClaimCheck, ...] | list[ClaimCheck],
) -> dict[str, CounterexampleRun]:
    """Each claim's counterexample run, by claim key (one run per distinct counterexample)."""
    done: dict[Counterexample, CounterexampleRun] = {}
    out: dict[str, CounterexampleRun] = {}
    for check in checks:
        cx = check.claim.counterexample
        if cx is None:
            continue
        if cx not in done:
            done[cx] = run_counterexample(cx)
        out[check.claim.key] = done[cx]
    return out

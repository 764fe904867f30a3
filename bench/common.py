"""Shared helpers of the benchmarks: timing, the exact modal solution of the hoop-cylinder
system, error measures, a MuJoCo model of it, and plain-text tables.

Every number a benchmark prints is measured in the same run; nothing here is a stored result.
"""

from __future__ import annotations

import math
import os
import platform
import time
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np

# -- timing -----------------------------------------------------------------------------------


def repeat(
    run: Callable[[], Any],
    repeats: int,
    *,
    warmup: int = 1,
    keep: Callable[[Any], Any] | None = None,
) -> list[tuple[float, Any]]:
    """Run ``run()`` ``warmup`` times untimed (Numba compiles, caches fill), then ``repeats``
    times; returns ``[(wall time, result), ...]`` of the timed runs, or with ``keep``
    ``[(wall time, keep(result)), ...]``, each result released before its timing ends.

    Keeping every large result alive makes each run page in fresh memory that a caller's loop
    would reuse: 30 kept trajectories of the paper's system cost each ``simulate()`` call about
    68 page faults (0 when each is released), tens of microseconds of a 0.6 ms call."""
    for _ in range(warmup):
        run()
    timed = []
    for _ in range(repeats):
        began = time.perf_counter()
        result = run() if keep is None else keep(run())  # released within the timing
        timed.append((time.perf_counter() - began, result))
    return timed


def best_of(run: Callable[[], Any], repeats: int, *, warmup: int = 1) -> tuple[float, Any]:
    """``(best wall time, its result)`` of :func:`repeat`: the best of several runs is the one
    least disturbed by other work on the machine."""
    return min(repeat(run, repeats, warmup=warmup), key=lambda pair: pair[0])


def one_core_opencv() -> Any:
    """Pin this process to its first allowed core (``os.sched_setaffinity`` where there is one)
    and turn OpenCV's own threads off: what one core tracks. Returns ``cv2``."""
    if hasattr(os, "sched_setaffinity"):
        os.sched_setaffinity(0, {sorted(os.sched_getaffinity(0))[0]})
    import cv2

    cv2.setNumThreads(1)
    return cv2


def machine_note() -> str:
    """One line on the machine and its load (other work on it makes timings noisy)."""
    load = os.getloadavg()[0] if hasattr(os, "getloadavg") else float("nan")
    return (
        f"machine: {platform.machine()}, {os.cpu_count()} CPUs, Python "
        f"{platform.python_version()}, load average {load:.2f} at start"
    )


# -- the paper's hoop-cylinder system (preset "hoop-cylinder") ---------------------------------


@dataclass(frozen=True)
class HoopCylinder:
    """The paper's Fig. 2: hoop (m1) and solid cylinder (m2), radius R, centres joined by a
    spring (k, rest length L0), released from rest compressed by ``compression``."""

    m1: float = 1.0
    m2: float = 1.0
    radius: float = 0.1
    k: float = 100.0
    rest_length: float = 0.5
    compression: float = 0.01
    mu: float = 1.0
    gravity: float = 9.81

    @property
    def x0(self) -> tuple[float, float]:
        """Initial centre positions (m)."""
        return 0.0, self.rest_length - self.compression

    @property
    def omega(self) -> float:
        """Omega^2 = k/(2 m1) + 2k/(3 m2) (docs/physics.md 7.1), rad/s."""
        return math.sqrt(self.k / (2 * self.m1) + 2 * self.k / (3 * self.m2))

    @property
    def weights(self) -> tuple[float, float]:
        """X-hat weights (2 m1, 1.5 m2), normalised: X-hat = w1 x1 + w2 x2 stays put (M11)."""
        a, b = 2 * self.m1, 1.5 * self.m2
        return a / (a + b), b / (a + b)

    @property
    def amplitudes(self) -> tuple[float, float]:
        """Amplitude of each centre's oscillation (m): w2 c and w1 c."""
        w1, w2 = self.weights
        return w2 * self.compression, w1 * self.compression

    @property
    def energy(self) -> float:
        """Energy of the motion (J): the spring's at release, gravity left out."""
        return 0.5 * self.k * self.compression**2

    def exact(self, t: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """Exact centre positions ``x`` and velocities ``v``, shape (len(t), 2): the spring
        deformation is ``-c cos(Omega t)`` and X-hat stays at its initial value."""
        t = np.asarray(t, dtype=float)
        w1, w2 = self.weights
        x_hat = w1 * self.x0[0] + w2 * self.x0[1]
        separation = self.rest_length - self.compression * np.cos(self.omega * t)
        rate = self.compression * self.omega * np.sin(self.omega * t)
        x = np.stack([x_hat - w2 * separation, x_hat + w1 * separation], axis=1)
        v = np.stack([-w2 * rate, w1 * rate], axis=1)
        return x, v


@dataclass(frozen=True)
class ModalErrors:
    """Errors of a hoop-cylinder run against the exact modal solution."""

    position: float  # max over the run and the bodies of |x_i - x_exact_i| / A_i
    frequency: float  # relative frequency error (omega_numerical / Omega - 1), fitted
    phase: float  # max |phase error| over the run (rad)
    energy: float  # mean energy over the last period / initial energy - 1


def modal_errors(
    case: HoopCylinder, t: np.ndarray, x: np.ndarray, v: np.ndarray, energy: np.ndarray
) -> ModalErrors:
    r"""Position, frequency and energy errors of a run sampled at times ``t`` (centres ``x``,
    velocities ``v``, shape (len(t), 2); ``energy`` the mechanical energy without gravity).

    The frequency error comes from the phase drift: the spring deformation
    :math:`d = x_2 - x_1 - L_0` and its rate give the phase :math:`\theta =
    \operatorname{atan2}(\dot d/\Omega, -d)` (:math:`\Omega t` for the exact motion, whatever
    the amplitude); the slope of the least-squares line through :math:`\theta - \Omega t`,
    divided by :math:`\Omega`, is the relative frequency error. It needs samples closer than half
    a period, and is insensitive to a decaying amplitude and to a drifting centre of mass.
    ``phase`` is the largest :math:`|\theta - \Omega t|` over the run: for a pure frequency
    error it is :math:`|\Delta\omega| T`, but it also holds offsets (a start-up transient) and
    phase that wanders without drifting.
    """
    t = np.asarray(t, dtype=float)
    exact_x, _ = case.exact(t)
    amplitude = np.asarray(case.amplitudes)
    position = float(np.max(np.abs(x - exact_x) / amplitude))
    omega = case.omega
    deformation = x[:, 1] - x[:, 0] - case.rest_length
    rate = v[:, 1] - v[:, 0]
    phase = np.unwrap(np.arctan2(rate / omega, -deformation))
    drift = phase - omega * t
    # centred abscissa: the slope of a line through 10^3 rad is then exact to rounding
    slope = np.polyfit(t - t.mean(), drift - drift[0], 1)[0]
    frequency = float(slope / omega)
    last = t >= t[-1] - 2 * math.pi / omega
    energy_change = float(np.mean(energy[last]) / case.energy - 1.0)
    return ModalErrors(position, frequency, float(np.max(np.abs(drift - drift[0]))), energy_change)


# -- MuJoCo ------------------------------------------------------------------------------------


def hoop_cylinder_mjcf(case: HoopCylinder) -> str:
    """MJCF of the hoop-cylinder system with MuJoCo's default options and contact.

    Planar: MuJoCo's x-z plane is ours (x right, z up). Each body has slide-x, slide-z and a
    hinge about y (the hinge angle is our clockwise phi); an explicit ``<inertial>`` gives the
    hoop I = m R^2 and the cylinder I = m R^2 / 2 (the contact geom, a cylinder lying along y,
    does not set the inertia). Both lie on a plane with friction ``mu`` (condim 3: sliding
    friction, no rolling resistance). A spatial tendon between the centres is the spring
    (stiffness k, springlength L0, no damping). Joint order in qpos: hoop x, z, phi, cylinder
    x, z, phi; qpos = 0 is the initial placement.
    """
    r, mu = case.radius, case.mu
    bodies = []
    for name, mass, gamma, x in (
        ("hoop", case.m1, 1.0, case.x0[0]),
        ("cylinder", case.m2, 0.5, case.x0[1]),
    ):
        inertia = gamma * mass * r * r
        bodies.append(f"""
    <body name="{name}" pos="{x!r} 0 {r!r}">
      <joint name="{name}:x" type="slide" axis="1 0 0"/>
      <joint name="{name}:z" type="slide" axis="0 0 1"/>
      <joint name="{name}:phi" type="hinge" axis="0 1 0"/>
      <inertial pos="0 0 0" mass="{mass!r}" diaginertia="{inertia!r} {inertia!r} {inertia!r}"/>
      <geom name="{name}" type="cylinder" size="{r!r} {0.25 * r!r}" zaxis="0 1 0"
            condim="3" friction="{mu!r} 0.005 0.0001"/>
      <site name="{name}:centre" pos="0 0 0"/>
    </body>""")
    return f"""<mujoco model="hoop-cylinder">
  <compiler angle="radian"/>
  <option gravity="0 0 {-case.gravity!r}"/>
  <worldbody>
    <geom name="floor" type="plane" size="0 0 1" condim="3" friction="{mu!r} 0.005 0.0001"/>
    {"".join(bodies)}
  </worldbody>
  <contact><exclude body1="hoop" body2="cylinder"/></contact>
  <tendon>
    <spatial name="spring" stiffness="{case.k!r}" springlength="{case.rest_length!r}"
             damping="0">
      <site site="hoop:centre"/>
      <site site="cylinder:centre"/>
    </spatial>
  </tendon>
</mujoco>
"""


# -- output ------------------------------------------------------------------------------------


def fmt(value: Any, spec: str = ".3g") -> str:
    """A table cell: numbers with ``spec``, None as '-', text as is."""
    if value is None:
        return "-"
    if isinstance(value, str):
        return value
    if isinstance(value, bool):
        return "yes" if value else "no"
    if isinstance(value, int):
        return f"{value:,}"
    return format(value, spec)


def print_table(title: str, headers: Sequence[str], rows: Sequence[Sequence[Any]]) -> None:
    """A plain-text table with right-aligned columns (the first column left-aligned)."""
    cells = [[str(h) for h in headers]] + [[fmt(c) for c in row] for row in rows]
    widths = [max(len(row[i]) for row in cells) for i in range(len(headers))]

    def line(row: Sequence[str]) -> str:
        return "  ".join(
            c.ljust(w) if i == 0 else c.rjust(w)
            for i, (c, w) in enumerate(zip(row, widths, strict=True))
        )

    print(f"\n{title}")
    print(line(cells[0]))
    print("  ".join("-" * w for w in widths))
    for row in cells[1:]:
        print(line(row))

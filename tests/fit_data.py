"""Measured tables made here, honestly: the paper's hoop and cylinder (Fig. 2, centre spring,
equal radii) from its closed-form motion, seeded noise, written as the lab's file formats.

The closed form (docs/physics.md section 7.1 and (M11)): with :math:`u = x_2 - x_1 - L_0`,

.. math:: \\ddot u + \\frac{c}{k}\\Omega^2\\dot u + \\Omega^2 u = 0,\\qquad
          \\Omega^2 = k\\Bigl(\\frac{1}{2m_1} + \\frac{2}{3m_2}\\Bigr),

and :math:`\\hat X = w_1x_1 + w_2x_2`, :math:`w \\propto (2m_1, \\tfrac32 m_2)`, moves uniformly;
:math:`x_1 = \\hat X - w_2(L_0 + u)`, :math:`x_2 = \\hat X + w_1(L_0 + u)`. Nothing of
rollspring computes these motions.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from pathlib import Path

import numpy as np

RADIUS = 0.1
REST_LENGTH = 0.5


@dataclass(frozen=True)
class Truth:
    """The true hoop-cylinder system: masses, stiffness, damping, initial state."""

    m1: float = 1.0
    m2: float = 1.0
    k: float = 100.0
    c: float = 0.0
    x1: float = 0.0
    x2: float = 0.49
    v1: float = 0.0
    v2: float = 0.0

    @property
    def weights(self) -> tuple[float, float]:
        a, b = 2 * self.m1, 1.5 * self.m2
        return a / (a + b), b / (a + b)

    def positions(self, t: np.ndarray) -> np.ndarray:
        """(N, 2) centre positions at times ``t`` (s) after the initial state."""
        w1, w2 = self.weights
        omega2 = self.k * (1 / (2 * self.m1) + 2 / (3 * self.m2))
        decay = self.c * omega2 / (2 * self.k)  # zeta * Omega
        damped = math.sqrt(omega2 - decay**2)
        u0 = self.x2 - self.x1 - REST_LENGTH
        du0 = self.v2 - self.v1
        u = np.exp(-decay * t) * (
            u0 * np.cos(damped * t) + (du0 + decay * u0) / damped * np.sin(damped * t)
        )
        hat0 = w1 * self.x1 + w2 * self.x2
        hat_v = w1 * self.v1 + w2 * self.v2
        hat = hat0 + hat_v * t
        return np.stack([hat - w2 * (REST_LENGTH + u), hat + w1 * (REST_LENGTH + u)], axis=1)

    def system(self, *, k: float | None = None, c: float | None = None) -> dict[str, object]:
        """The system file (JSON form) with this truth, or ``k``/``c`` changed (a rough start)."""
        return {
            "name": "hoop and cylinder",
            "bodies": [
                {
                    "id": "hoop",
                    "shape": "hoop",
                    "mass": self.m1,
                    "radius": RADIUS,
                    "x": self.x1,
                    "v": self.v1,
                },
                {
                    "id": "cylinder",
                    "shape": "cylinder",
                    "mass": self.m2,
                    "radius": RADIUS,
                    "x": self.x2,
                    "v": self.v2,
                },
            ],
            "springs": [
                {
                    "ends": ["hoop", "cylinder"],
                    "stiffness": self.k if k is None else k,
                    "rest_length": REST_LENGTH,
                    "damping": self.c if c is None else c,
                }
            ],
        }


def recording(
    truth: Truth,
    *,
    duration: float,
    fps: float,
    noise: float = 1e-3,
    seed: int = 0,
    angle_noise: float = 0.01,
    slip: float = 1.0,
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Times, noisy positions (N, 2) and noisy angles (N, 2) (``slip`` < 1 turns the bodies
    less than rolling would: a slipping recording)."""
    rng = np.random.default_rng(seed)
    t = np.arange(int(round(duration * fps))) / fps
    x = truth.positions(t)
    phi = slip * (x - x[0]) / RADIUS
    return (
        t,
        x + rng.normal(0.0, noise, x.shape),
        phi + rng.normal(0.0, angle_noise, phi.shape),
    )


def _number(value: float) -> str:
    return repr(float(value))


def write_csv(path: Path, t: np.ndarray, x: np.ndarray, phi: np.ndarray | None = None) -> Path:
    """A plain CSV (``t,x_hoop,x_cylinder``) or, with angles, the ``track`` CSV
    (``t,x_hoop,phi_hoop,x_cylinder,phi_cylinder``)."""
    names = ("hoop", "cylinder")
    if phi is None:
        header = "t," + ",".join(f"x_{n}" for n in names)
        rows = [",".join(map(_number, (ti, *xi))) for ti, xi in zip(t, x, strict=True)]
    else:
        header = "t," + ",".join(f"x_{n},phi_{n}" for n in names)
        rows = [
            ",".join(map(_number, (ti, xi[0], pi[0], xi[1], pi[1])))
            for ti, xi, pi in zip(t, x, phi, strict=True)
        ]
    path.write_text("\n".join([header, *rows]) + "\n")
    return path


def write_tracker(path: Path, t: np.ndarray, x: np.ndarray, column: int, name: str) -> Path:
    """A Tracker data file of one track: its name, then ``t x y``, tab-separated."""
    lines = [name, "t\tx\ty"]
    lines += [
        f"{_number(ti)}\t{_number(xi)}\t{RADIUS!r}" for ti, xi in zip(t, x[:, column], strict=True)
    ]
    path.write_text("\n".join(lines) + "\n")
    return path


def write_tracker_multi(
    path: Path, t: np.ndarray, x: np.ndarray, names: tuple[str, str], unmarked: int = 0
) -> Path:
    """A Tracker ``#multi:`` file: the track names above their first columns, then ``t x y x
    y``; every ``unmarked``-th frame of the second track left empty (not marked)."""
    lines = ["#multi:", f"\t{names[0]}\t\t{names[1]}\t", "t\tx\ty\tx\ty"]
    for j, (ti, xi) in enumerate(zip(t, x, strict=True)):
        second = ["", ""] if unmarked and j % unmarked == 3 else [_number(xi[1]), repr(RADIUS)]
        lines.append("\t".join([_number(ti), _number(xi[0]), repr(RADIUS), *second]))
    path.write_text("\n".join(lines) + "\n")
    return path

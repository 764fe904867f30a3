"""``rollspring.fit`` against the fits a user writes by hand, on the same recording.

The recording: the paper's hoop and cylinder (preset ``hoop-cylinder``, spring damping
0.2 N s/m), 10 s at 60 fps, both centres tracked with 1 mm of seeded noise, from the closed-form
motion (``Ω² = k/(2m1) + 2k/(3m2)`` for the spring's deformation, X̂ uniform). Fitted: the
stiffness, the damping and the initial state (x and v of both bodies), 6 parameters.

Routes, all from the same start (stiffness 3 % off, damping half the truth: a start every route
converges from) and to the same tolerances (``ftol = xtol = gtol = 1e-10``; the motion to
``rtol = 1e-9``):

1. **rollspring** ``rollspring.lab.fit.fit_model`` (the whole call: the spectral first guess, the
   exact solution e^{Bt} of the linear equations, the standard errors);
2. **SciPy by hand**: ``scipy.optimize.least_squares`` (2-point Jacobian) over
   ``solve_ivp(method="DOP853", rtol=1e-9, atol=1e-12)`` on the same equations of motion,
   ``(1+γ_i) m_i ẍ_i = ±(k u + c u̇)``, ``u = x2 − x1 − L0``;
3. **lmfit by hand**: ``lmfit.minimize`` (Levenberg–Marquardt) over the same ``solve_ivp``.

Then rollspring from the issue's rough start (stiffness 30 % off, no damping), and the SciPy
route from it, to show what the first guess is for. Printed: each route's time (best of several
for rollspring), its fitted k and c, and the ratios; the targets are rollspring ≥ 20× faster
and ≤ 2 s.
"""

from __future__ import annotations

import math
import os
import time

# One BLAS thread for every route: on a machine whose cores are busy, OpenBLAS's threads on the
# small factorisations of a fit (an SVD of a 1200 x 6 Jacobian) wait for each other, making each
# call about a hundred times slower (measured: 0.15 s against 1.4 ms).
os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")
os.environ.setdefault("OMP_NUM_THREADS", "1")

import numpy as np
from common import best_of, machine_note

from rollspring.lab.data import BodyData
from rollspring.lab.fit import fit_model
from rollspring.model import System, load_system, system_from_dict, system_to_json

M1, M2, K, C, L0 = 1.0, 1.0, 100.0, 0.2, 0.5
FPS, DURATION, NOISE = 60.0, 10.0, 1e-3
TOL = 1e-10


def closed_form(t: np.ndarray, k: float, c: float) -> np.ndarray:
    """Centre positions (N, 2) of the damped hoop-cylinder released from x = (0, 0.49)."""
    w1, w2 = 2 * M1 / (2 * M1 + 1.5 * M2), 1.5 * M2 / (2 * M1 + 1.5 * M2)
    omega2 = k * (1 / (2 * M1) + 2 / (3 * M2))
    decay = c * omega2 / (2 * k)
    damped = math.sqrt(omega2 - decay**2)
    u0 = 0.49 - L0
    u = np.exp(-decay * t) * (u0 * np.cos(damped * t) + decay * u0 / damped * np.sin(damped * t))
    hat = w2 * 0.49
    return np.stack([hat - w2 * (L0 + u), hat + w1 * (L0 + u)], axis=1)


def hand_model(params: np.ndarray, t: np.ndarray) -> np.ndarray:
    """What a user writes: the rolling equations integrated by solve_ivp (DOP853)."""
    from scipy.integrate import solve_ivp

    k, c, x1, x2, v1, v2 = params

    def rhs(_: float, y: np.ndarray) -> list[float]:
        u, du = y[1] - y[0] - L0, y[3] - y[2]
        force = k * u + c * du  # the spring pulls the hoop forward when stretched
        return [y[2], y[3], force / (2 * M1), -force / (1.5 * M2)]

    run = solve_ivp(
        rhs, (t[0], t[-1]), [x1, x2, v1, v2], method="DOP853", t_eval=t, rtol=1e-9, atol=1e-12
    )
    return run.y[:2].T


def hand_scipy(start: np.ndarray, t: np.ndarray, x: np.ndarray) -> np.ndarray:
    from scipy.optimize import least_squares

    solution = least_squares(
        lambda p: (hand_model(p, t) - x).ravel(), start, ftol=TOL, xtol=TOL, gtol=TOL, x_scale="jac"
    )
    return solution.x


def hand_lmfit(start: np.ndarray, t: np.ndarray, x: np.ndarray) -> np.ndarray:
    import lmfit

    parameters = lmfit.Parameters()
    for name, value in zip(("k", "c", "x1", "x2", "v1", "v2"), start, strict=True):
        parameters.add(name, value=value)

    def residual(p: lmfit.Parameters) -> np.ndarray:
        values = np.array([p[n].value for n in ("k", "c", "x1", "x2", "v1", "v2")])
        return (hand_model(values, t) - x).ravel()

    result = lmfit.minimize(residual, parameters, method="leastsq", ftol=TOL, xtol=TOL, gtol=TOL)
    return np.array([result.params[n].value for n in ("k", "c", "x1", "x2", "v1", "v2")])


def main() -> None:
    print(machine_note())
    t = np.arange(int(DURATION * FPS)) / FPS
    x = closed_form(t, K, C) + np.random.default_rng(2027).normal(0, NOISE, (t.size, 2))
    data = BodyData("bench", t, ("hoop", "cylinder"), (0, 1), x, np.full_like(x, np.nan))
    base = system_to_json(load_system("hoop-cylinder"))
    free = ["springs.0.stiffness", "springs.0.damping"]

    def system(k: float, c: float) -> System:
        changed = {**base, "springs": [{**base["springs"][0], "stiffness": k, "damping": c}]}
        return system_from_dict(changed)

    print(
        f"recording: {t.size} frames ({DURATION:g} s at {FPS:g} fps), 2 bodies, "
        f"{NOISE * 1e3:g} mm noise; truth k = {K:g} N/m, c = {C:g} N s/m\n"
    )
    close = system(0.97 * K, 0.5 * C)
    ours_time, ours = best_of(lambda: fit_model(data, close, free), 5)
    start = np.array([0.97 * K, 0.5 * C, 0.0, 0.49, 0.0, 0.0])
    began = time.perf_counter()
    scipy_fit = hand_scipy(start, t, x)
    scipy_time = time.perf_counter() - began
    began = time.perf_counter()
    lmfit_fit = hand_lmfit(start, t, x)
    lmfit_time = time.perf_counter() - began
    rows = [
        ("rollspring fit_model", ours_time, ours.value(free[0]), ours.value(free[1])),
        ("least_squares + solve_ivp DOP853", scipy_time, scipy_fit[0], scipy_fit[1]),
        ("lmfit + solve_ivp DOP853", lmfit_time, lmfit_fit[0], lmfit_fit[1]),
    ]
    print("from k 3 % off, c half the truth (every route converges):")
    print(
        f"{'route':36s} {'time (s)':>9s} {'k (N/m)':>12s} {'c (N s/m)':>11s} {'vs rollspring':>14s}"
    )
    for name, seconds, k, c in rows:
        print(f"{name:36s} {seconds:9.3f} {k:12.5f} {c:11.5f} {seconds / ours_time:13.1f}x")
    print(
        f"rollspring: k = {ours.value(free[0]):.4f} ± {ours.stderr(free[0]):.4f}, "
        f"c = {ours.value(free[1]):.4f} ± {ours.stderr(free[1]):.4f}\n"
    )

    rough = system(0.7 * K, 0.0)
    rough_time, rough_fit = best_of(lambda: fit_model(data, rough, free), 3)
    began = time.perf_counter()
    scipy_rough = hand_scipy(np.array([0.7 * K, 0.0, 0.0, 0.49, 0.0, 0.0]), t, x)
    scipy_rough_time = time.perf_counter() - began
    print("from the issue's rough start, k 30 % off and no damping:")
    print(
        f"{'rollspring fit_model':36s} {rough_time:9.3f} {rough_fit.value(free[0]):12.5f} "
        f"{rough_fit.value(free[1]):11.5f}"
    )
    print(
        f"{'least_squares + solve_ivp DOP853':36s} {scipy_rough_time:9.3f} "
        f"{scipy_rough[0]:12.5f} {scipy_rough[1]:11.5f} {scipy_rough_time / rough_time:13.1f}x"
    )
    fastest_hand = min(scipy_time, lmfit_time)
    print(
        f"\ntargets: >= 20x faster than the hand routes (measured {fastest_hand / ours_time:.0f}x "
        f"against the faster), rollspring <= 2 s (measured {ours_time:.3f} s; "
        f"{rough_time:.3f} s from the rough start)"
    )


if __name__ == "__main__":
    main()

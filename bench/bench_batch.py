"""Throughput of ``simulate_batch`` against a minimal hand-written kernel of the same equations.

Run: ``.venv/bin/python bench/bench_batch.py [--runs 65536] [--steps 4000] [--repeat 5]``.

The system is the ``hoop-cylinder`` preset (a hoop and a cylinder of radius R, their centres
joined by a horizontal spring), each run with its own stiffness. The reference is the least a
Numba kernel must do for it: blocks of 256 copies, the state in four arrays of 256 lanes, one
vectorisable loop over the lanes per stage of the composition (kick-drift-kick, merged kicks),
the exact force of a horizontal centre spring :math:`T e_x = k(d - L_0\\,\\mathrm{sign}\\,d)`
and the centre accelerations :math:`\\ddot x_i = \\pm T e_x R^2/J_i`, and nothing else: no
friction or lift-off checks, no metrics. ``simulate_batch`` does all of that for any topology
(its kernel is generated for this one). Both use all cores; times exclude compilation (each is
warmed up first) and the best of ``--repeat`` runs is reported, since other processes share the
machine. The ratio is measured within the same run. The reference is compiled afresh in each
run (no ``cache=True``): loaded from Numba's cache it ran 1.4x slower (Verlet 6.1-7.2 against
9.2-9.9 G/s, 30 Nov), while ``simulate_batch``'s generated kernels run at the same speed cached
or compiled afresh (measured with an empty ``ROLLSPRING_CACHE_DIR``).
"""

from __future__ import annotations

import argparse
import math
import time

import numpy as np
from numba import njit, prange

import rollspring
from rollspring.simulate.batch import SCHEMES, simulate_batch

B = 256
_ROW = B + 8  # a row's stride: 2112 bytes, a whole number of cache lines


@njit(error_model="numpy", fastmath={"contract"})
def _stage(y1, y2, u1, u2, k, dx, rest, a1, a2, drift, kick):
    for j in range(B):
        p1 = y1[j] + drift * u1[j]
        p2 = y2[j] + drift * u2[j]
        d = dx + p2 - p1
        tension = k[j] * (d - math.copysign(rest, d))
        u1[j] += kick * a1 * tension
        u2[j] -= kick * a2 * tension
        y1[j] = p1
        y2[j] = p2


@njit(parallel=True, error_model="numpy")
def minimal_kernel(stiffness, dx, rest, a1, a2, drift, kick, n_steps, out):
    """``n_steps`` steps of the composition (weights*h in ``drift``, merged kicks in
    ``kick``, the first half-kick ``0.5*drift[0]``) from rest; final positions into ``out``."""
    n_blocks = stiffness.shape[0] // B
    m = drift.shape[0]
    for blk in prange(n_blocks):
        lo = blk * B
        # the five rows in one buffer on a cache line, as the generated kernel's (Numba
        # aligns an array to 32 bytes only: on half of the heap's states the 64-byte vectors
        # straddled two lines and this kernel ran 1.4x slower)
        w = np.zeros(5 * _ROW + 8)
        a = (8 - (w.ctypes.data % 64) // 8) % 8
        y1 = w[a : a + B]
        y2 = w[a + _ROW : a + _ROW + B]
        u1 = w[a + 2 * _ROW : a + 2 * _ROW + B]
        u2 = w[a + 3 * _ROW : a + 3 * _ROW + B]
        k = w[a + 4 * _ROW : a + 4 * _ROW + B]
        k[:] = stiffness[lo : lo + B]
        _stage(y1, y2, u1, u2, k, dx, rest, a1, a2, 0.0, 0.5 * drift[0])  # opening half-kick
        for _ in range(n_steps):
            for s in range(m):
                _stage(y1, y2, u1, u2, k, dx, rest, a1, a2, drift[s], kick[s])
        out[0, lo : lo + B] = y1
        out[1, lo : lo + B] = y2


def _coefficients(name: str, h: float) -> tuple[np.ndarray, np.ndarray]:
    w = np.array(SCHEMES[name][1])
    drift = w * h
    kick = 0.5 * (w + np.roll(w, -1)) * h  # the last kick merged with the next opening one
    return drift, kick


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--runs", type=int, default=1 << 16)
    parser.add_argument("--steps", type=int, default=4000)
    parser.add_argument("--repeat", type=int, default=5)
    args = parser.parse_args()
    n_runs, n_steps = args.runs, args.steps
    h = 1e-4

    system = rollspring.load_system("hoop-cylinder")
    arrays = rollspring.system_arrays(system)
    stiffness = np.random.default_rng(0).uniform(50.0, 150.0, n_runs)
    parameters = {"springs.0.stiffness": stiffness}
    dx = float(arrays.x0[1] - arrays.x0[0])
    rest = float(arrays.rest_length[0])
    # centre acceleration per unit of spring force: R^2 / J (hoop 1/(2m), cylinder 2/(3m))
    a1 = float(arrays.radius[0] ** 2 / arrays.inertia[0])
    a2 = float(arrays.radius[1] ** 2 / arrays.inertia[1])
    n_pad = -(-n_runs // B) * B
    padded = np.resize(stiffness, n_pad)

    # (label, simulate_batch arguments): the given step, and what auto picks for rtol 1e-8
    cases = [
        ("verlet", {"duration": n_steps * h, "integrator": "verlet", "step": h}),
        ("yoshida4", {"duration": n_steps * h, "integrator": "yoshida4", "step": h}),
        ("auto 1e-8", {"duration": 10.0, "rtol": 1e-8}),
    ]
    print(f"hoop-cylinder, {n_runs} runs, each with its own stiffness; best of {args.repeat}")
    header = (
        f"{'case':>10}  {'scheme':>8}  {'omega h':>7}  {'steps':>6}  {'sampled':>7}  "
        f"{'simulate_batch':>14}  {'minimal kernel':>14}  {'ratio':>5}"
    )
    print(header)
    print("-" * len(header))
    for label, kwargs in cases:
        warm = dict(kwargs, duration=kwargs["duration"] / 100)
        simulate_batch(system, parameters, **warm)  # compile or load the kernel
        probe = simulate_batch(system, parameters, **kwargs)
        name, step, steps = probe.integrator, probe.step, probe.n_steps
        drift, kick = _coefficients(name, step)
        out = np.empty((2, n_pad))
        minimal_kernel(padded, dx, rest, a1, a2, drift, kick, 2, out)  # compile
        best_batch = best_minimal = math.inf
        for _ in range(args.repeat):
            t0 = time.perf_counter()
            minimal_kernel(padded, dx, rest, a1, a2, drift, kick, steps, out)
            best_minimal = min(best_minimal, time.perf_counter() - t0)
            result = simulate_batch(system, parameters, **kwargs)
            best_batch = min(best_batch, result.timings["integrate"])
        rate_batch = n_runs * steps / best_batch
        rate_minimal = n_runs * steps / best_minimal
        print(
            f"{label:>10}  {name:>8}  {probe.omega_max * step:>7.4f}  {steps:>6}  "
            f"{'1/' + str(probe.metric_every):>7}  {rate_batch / 1e9:>10.3f} G/s  "
            f"{rate_minimal / 1e9:>10.3f} G/s  {rate_batch / rate_minimal:>5.2f}"
        )
    print(
        "(system-steps per second: runs x steps / wall time of the integration; 'sampled':\n"
        " steps with a metric sample, see rollspring.simulate.batch.METRIC_PHASE)"
    )


if __name__ == "__main__":
    main()

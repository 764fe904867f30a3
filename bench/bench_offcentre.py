"""Steps per second of rollspring's compiled stepping on a nonlinear off-centre system, against a
minimal hand-written Numba kernel of the same equations and the same scheme.

The system: a hoop and a solid sphere (1 kg, R = 0.1 m) joined by a 100 N/m spring attached off
centre, at 0.07 m, 40 deg on the hoop and 0.05 m, -120 deg on the sphere (clockwise from up),
the sphere launched at 0.3 m/s, rolling enforced (mu_static = inf). The bodies turn by hundreds
of radians and the spring tilts: the motion is strongly nonlinear. Both codes take the same
fixed step with Yoshida's 4th-order kick-drift-kick composition of J phi'' = Q(phi); the hand
kernel knows this geometry and nothing else (scalar locals, no arrays, no checks), so it is
about as fast as Numba gets: rollspring's general kernel (any bodies, springs, anchors,
forces; slip/lift-off checks and contact extremes after every step) is measured against it.
Run: ``python bench/bench_offcentre.py`` (see bench/README.md).
"""

from __future__ import annotations

import math
import time

import numpy as np
from common import machine_note, print_table, repeat
from numba import njit

from rollspring import analyze, system_arrays, system_from_dict
from rollspring.simulate import simulate

N_STEPS = 2_000_000
N_OUTPUT = 2001
REPEATS = 5
TARGET_RATIO = 0.30


def off_centre_system():
    """Hoop and sphere joined off-centre (the system of the nonlinear tests)."""
    return system_from_dict(
        {
            "bodies": [
                {
                    "id": "hoop",
                    "shape": "hoop",
                    "mass": 1.0,
                    "radius": 0.1,
                    "x": 0.0,
                    "mu_static": math.inf,
                },
                {
                    "id": "ball",
                    "shape": "sphere",
                    "mass": 1.0,
                    "radius": 0.1,
                    "x": 0.46,
                    "v": 0.3,
                    "mu_static": math.inf,
                },
            ],
            "springs": [
                {
                    "ends": ["hoop", "ball"],
                    "stiffness": 100.0,
                    "at": [{"radius": 0.07, "angle": 40.0}, {"radius": 0.05, "angle": -120.0}],
                }
            ],
        }
    )


# -- the hand-written kernel -------------------------------------------------------------------

_W1 = 1.0 / (2.0 - 2.0 ** (1.0 / 3.0))
#: Yoshida's weights: w1, 1 - 2 w1, w1
YOSHIDA4 = (_W1, 1.0 - 2.0 * _W1, _W1)


@njit(cache=True, inline="always")
def _forces(q1, q2, p):
    """Q of both bodies: the spring between P_a on body 1 and P_b on body 2 (M1), force +T e
    on end a and -T e on end b, Q_i = s_i F_ix + clockwise torque about the centre (M7).

    The operations of rollspring's ``rolling_forces`` / ``_rolling_point`` for this system, in
    their order, so that the two codes round alike: the centre x0 + s q, the attachment point
    centre + (r sin, r cos), the lever arms (r cos, -r sin), T/l = k (l - L0) / l, each end's
    torque o_x T_x + o_y T_y, and Q = s F_x + tau with F_x = +-T_x. rollspring's branch for a
    level spring (dy exactly 0: no square root) is left out; this tilted spring's ends are
    practically never at exactly one height."""
    (x01, x02, s1, s2, cy1, cy2, ra, alpha_a, rb, alpha_b, k, rest, _, _) = p
    sa = math.sin(alpha_a + q1)
    ca = math.cos(alpha_a + q1)
    sb = math.sin(alpha_b + q2)
    cb = math.cos(alpha_b + q2)
    dx = ((x02 + s2 * q2) + rb * sb) - ((x01 + s1 * q1) + ra * sa)
    dy = (cy2 + rb * cb) - (cy1 + ra * ca)
    dist = math.sqrt(dx * dx + dy * dy)
    per_length = k * (dist - rest) / dist
    tx = per_length * dx
    ty = per_length * dy
    g1 = s1 * tx + ((ra * ca) * tx + (-ra * sa) * ty)
    g2 = s2 * -tx - ((rb * cb) * tx + (-rb * sb) * ty)
    return g1, g2


@njit(cache=True)
def yoshida4_steps(q1, q2, v1, v2, h, n_steps, p, w):
    """``n_steps`` Yoshida-4 steps of size ``h`` from (q, v); the closing half-kick of a stage
    and the opening one of the next share one force evaluation (3 per step). The kicks are
    rollspring's ``_stages``': the step's opening one (kick Q) / J, the others Q (kick / J)."""
    inv_j1 = p[12]
    inv_j2 = p[13]
    g1, g2 = _forces(q1, q2, p)
    for _ in range(n_steps):
        kick = 0.5 * h * w[0]
        v1 += kick * g1 * inv_j1
        v2 += kick * g2 * inv_j2
        for s in range(3):
            hw = h * w[s]
            q1 += hw * v1
            q2 += hw * v2
            g1, g2 = _forces(q1, q2, p)
            kick = 0.5 * h * (w[s] + w[s + 1]) if s < 2 else 0.5 * hw
            v1 += g1 * (kick * inv_j1)
            v2 += g2 * (kick * inv_j2)
    return q1, q2, v1, v2


def kernel_parameters(system):
    """The constants of ``_forces`` from the system's arrays."""
    a = system_arrays(system)
    assert a.n_bodies == 2 and a.n_springs == 1 and tuple(a.end_body[0]) == (0, 1)
    assert np.all(a.rolls == 1.0) and not a.force.shape[0] and not np.any(a.damping)
    cy = a.track + a.radius
    return (
        float(a.x0[0]),
        float(a.x0[1]),
        float(a.scale[0]),
        float(a.scale[1]),
        float(cy[0]),
        float(cy[1]),
        float(a.end_r[0, 0]),
        float(a.end_alpha[0, 0]),
        float(a.end_r[0, 1]),
        float(a.end_alpha[0, 1]),
        float(a.stiffness[0]),
        float(a.rest_length[0]),
        float(1.0 / a.inertia[0]),
        float(1.0 / a.inertia[1]),
    )


def hand_trajectory(p, q0, v0, h, n_rows, stride):
    """The hand kernel run from (q0, v0), rows every ``stride`` steps: (phi, phidot) (n_rows, 2)."""
    w = np.array(YOSHIDA4)
    q = np.empty((n_rows, 2))
    v = np.empty((n_rows, 2))
    q[0], v[0] = q0, v0
    for j in range(1, n_rows):
        q1, q2, v1, v2 = yoshida4_steps(
            q[j - 1, 0], q[j - 1, 1], v[j - 1, 0], v[j - 1, 1], h, stride, p, w
        )
        q[j], v[j] = (q1, q2), (v1, v2)
    return q, v


def main() -> None:
    print(
        "off-centre hoop + sphere, nonlinear: rollspring's compiled stepping vs a minimal "
        "hand-written Numba kernel (both Yoshida-4, the same fixed step)"
    )
    print(machine_note())
    system = off_centre_system()
    omega = max(m.omega for m in analyze(system).modes)
    step = 0.15 / omega
    duration = N_STEPS * step
    print(
        f"highest linear frequency {omega:.4f} rad/s; step 0.15/omega = {step:.4g} s; "
        f"{N_STEPS:,} steps = {duration:.1f} s of motion; best of {REPEATS} after warm-up"
    )

    def rollspring_run():
        return simulate(
            system,
            duration,
            integrator="yoshida4",
            step=step,
            n_output=N_OUTPUT,
            energy_tolerance=1e-3,
        )

    timed = repeat(rollspring_run, REPEATS, warmup=1)
    trajectory = timed[0][1]
    assert trajectory.status == "finished", trajectory.message
    steps = trajectory.n_steps
    h = trajectory.step  # rounded to divide the output spacing
    integrate = min(tr.timings["integrate"] for _, tr in timed)
    call = min(wall for wall, _ in timed)

    # the hand kernel: the same start, step and rows
    p = kernel_parameters(system)
    a = system_arrays(system)
    q0, v0 = np.zeros(2), a.v0 / a.scale
    stride = steps // (N_OUTPUT - 1)
    assert stride * (N_OUTPUT - 1) == steps
    w = np.array(YOSHIDA4)
    yoshida4_steps(0.0, 0.0, v0[0], v0[1], h, 10, p, w)  # compile (or load the cache)
    hand_walls = []
    for _ in range(REPEATS):
        began = time.perf_counter()
        yoshida4_steps(0.0, 0.0, v0[0], v0[1], h, steps, p, w)
        hand_walls.append(time.perf_counter() - began)
    hand = min(hand_walls)
    q, v = hand_trajectory(p, q0, v0, h, N_OUTPUT, stride)

    # agreement over the run, at rollspring's output rows
    phi_error = float(np.max(np.abs(q - trajectory.phi)))
    x_error = float(np.max(np.abs(a.radius * q + a.x0 - trajectory.x)))
    omega_error = float(np.max(np.abs(v - trajectory.omega)))
    spread = float(np.max(np.ptp(trajectory.phi, axis=0)))
    energy = trajectory.summary["energy_error"]

    rows = [
        [
            "rollspring: compiled stepping (timings['integrate'])",
            integrate,
            steps,
            steps / integrate,
            1e9 * integrate / steps,
            steps / integrate / (steps / hand),
        ],
        [
            "rollspring: whole simulate() call",
            call,
            steps,
            steps / call,
            1e9 * call / steps,
            steps / call / (steps / hand),
        ],
        [
            "hand-written Numba kernel (this file)",
            hand,
            steps,
            steps / hand,
            1e9 * hand / steps,
            1.0,
        ],
    ]
    print_table(
        "Steps per second (3 force evaluations per step)",
        ["code", "wall [s]", "steps", "steps/s", "ns/step", "speed vs hand"],
        rows,
    )
    same = " (bit for bit the same)" if phi_error == x_error == omega_error == 0.0 else ""
    print(
        f"\nagreement over the run at {N_OUTPUT} rows (bodies turned by up to {spread:.0f} rad)"
        f": max |phi diff| {phi_error:.2e} rad, max |x diff| {x_error:.2e} m, "
        f"max |omega diff| {omega_error:.2e} rad/s{same}; rollspring's energy error "
        f"{energy:.1e} (the step is long: omega h = 0.15)"
    )
    if x_error > 1e-10:
        print("WARNING: the two codes disagree by more than 1e-10 m")
    ratio = hand / integrate
    print(
        f"rollspring's stepping runs at {ratio:.0%} of the hand kernel's speed (target >= "
        f"{TARGET_RATIO:.0%}): {'met' if ratio >= TARGET_RATIO else 'NOT met'}"
    )


if __name__ == "__main__":
    main()

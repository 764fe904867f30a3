"""The paper's hoop-cylinder system, 10 s of motion: rollspring against MuJoCo, pymunk and SciPy.

Every engine integrates the same motion (preset ``hoop-cylinder``: hoop and solid cylinder,
1 kg, R = 0.1 m, centres joined by a 100 N/m spring of rest length 0.5 m, released from rest
compressed by 0.01 m). Its exact solution is known (``common.HoopCylinder.exact``), so each run
is scored by its largest position error, its frequency error (from the phase drift) and its
energy change. The key figure is the wall time each engine needs for a frequency error
<= 1e-9 over the 10 s, and its ratio to rollspring's. Run: ``python bench/bench_hoop_cylinder.py``
(about a minute; see bench/README.md); ``--engines rollspring,scipy`` runs only those (a few
seconds), ``--repeats N`` times rollspring's calls N times (default 30).
"""

from __future__ import annotations

import argparse
import importlib.util
import math
import time
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

import numpy as np
from common import (
    HoopCylinder,
    ModalErrors,
    hoop_cylinder_mjcf,
    machine_note,
    modal_errors,
    print_table,
    repeat,
)

from rollspring import load_system, system_arrays
from rollspring.physics import generalized_forces
from rollspring.simulate import simulate
from rollspring.simulate.kernels import SCHEMES

DURATION = 10.0
TARGET = 1e-9  # frequency error to reach
SPACING = 0.005  # output spacing of the other engines (rollspring's default: 2001 outputs)
CASE = HoopCylinder()


#: the criteria of "reaching" the target: the fitted frequency error, and the phase error that
#: rollspring's rtol bounds (max |phase error| over the run <= TARGET * Omega * DURATION)
CRITERIA = {
    "freq": (
        "fitted frequency error <= 1e-9",
        lambda e: abs(e.frequency) <= TARGET,
        lambda e: abs(e.frequency),
    ),
    "phase": (
        "max phase error <= 1e-9 * Omega T",
        lambda e: e.phase <= TARGET * CASE.omega * DURATION,
        lambda e: e.phase / (CASE.omega * DURATION),
    ),
}


@dataclass
class Run:
    """One timed run of an engine and its errors against the exact solution."""

    engine: str
    setting: str
    wall: float  # s
    steps: int
    evals: int  # force (right-hand side) evaluations
    errors: ModalErrors
    note: str = ""
    rtol: float | None = None  # the setting's tolerance, where it has one

    def meets(self, criterion: str) -> bool:
        return CRITERIA[criterion][1](self.errors)

    def row(self) -> list:
        e = self.errors
        met = "+".join(name for name in CRITERIA if self.meets(name)) or "no"
        return [
            self.engine,
            self.setting,
            self.wall,
            self.steps,
            self.steps / self.wall,
            self.evals,
            e.position,
            e.frequency,
            e.phase,
            e.energy,
            met,
        ]


@dataclass
class Choice:
    """The cheapest setting of an engine that meets a criterion, or the best it reached."""

    run: Run
    reached: bool
    extrapolated_wall: float | None = None  # to the target, when not reached


def climb(
    run, params, criteria=tuple(CRITERIA), retime: int = 3, retime_below: float = 5.0
) -> tuple[list[Run], dict[str, Choice]]:
    """Run ``run(p)`` for ``params`` from the cheapest until every criterion is met; the first
    setting meeting each is re-timed (best of ``retime``; runs over ``retime_below`` s are timed
    once). A criterion not met takes the run with the smallest error and an extrapolated wall
    time: the error's order in the number of steps fitted to the last three rungs."""
    ladder: list[tuple[object, Run]] = []
    first: dict[str, tuple[object, Run]] = {}
    for p in params:
        r = run(p)
        ladder.append((p, r))
        for name in criteria:
            if name not in first and r.meets(name):
                first[name] = (p, r)
        if len(first) == len(criteria):
            break
    retimed: dict[object, Run] = {}
    choices = {}
    for name in criteria:
        if name in first:
            p, r = first[name]
            if p not in retimed:
                extra = [run(p) for _ in range(retime - 1)] if r.wall < retime_below else []
                retimed[p] = min([r, *extra], key=lambda x: x.wall)
            choices[name] = Choice(retimed[p], True)
            continue
        error = CRITERIA[name][2]
        best = min((r for _, r in ladder), key=lambda r: error(r.errors))
        tail = [r for _, r in ladder][-3:]
        steps = np.log([r.steps for r in tail])
        order = -np.polyfit(steps, np.log([error(r.errors) for r in tail]), 1)[0]
        wall = best.wall * (error(best.errors) / TARGET) ** (1 / order) if order > 0 else math.inf
        choices[name] = Choice(best, False, wall)
    return [r for _, r in ladder], choices


# -- rollspring --------------------------------------------------------------------------------


def rollspring_runs(repeats: int = 30) -> list[Run]:
    """rtol from the documented relation (relative frequency error ~ rtol / (omega T)); the
    integration alone (``timings["integrate"]``) and the whole ``simulate()`` call, each the
    best of ``repeats``; with the default 2001 outputs and with 201 (a longer step fits)."""
    system = load_system("hoop-cylinder")
    a = system_arrays(system)
    assert (
        tuple(a.mass),
        tuple(a.radius),
        float(a.stiffness[0]),
        float(a.rest_length[0]),
        tuple(a.x0),
    ) == ((CASE.m1, CASE.m2), (CASE.radius,) * 2, CASE.k, CASE.rest_length, CASE.x0), (
        "the preset is not the benchmark's hoop-cylinder"
    )
    rtol = TARGET * CASE.omega * DURATION
    runs = []
    for n_output in (2001, 201):
        # 30 calls to warm up: a fresh process's first few dozen calls run up to 1.5 times
        # slower (measured: best of 30 after 2 warm-up calls 1.18 ms, after 60 calls 0.78 ms)
        call, integrate, fixed, trajectory = timed_calls(system, rtol, n_output, repeats, 30)
        FIXED[n_output] = (fixed[0], fixed[len(fixed) // 2])
        errors = modal_errors(CASE, trajectory.t, trajectory.x, trajectory.v, trajectory.energy)
        evals = trajectory.n_steps * len(SCHEMES[trajectory.integrator][1])
        period = trajectory.summary["period_measured"]
        note = (
            f"rtol={rtol:.3g}: {trajectory.integrator}, step {trajectory.step:.4g} s; "
            f"summary period_measured rel. error {period * CASE.omega / (2 * math.pi) - 1:.2e}"
            f", energy_error {trajectory.summary['energy_error']:.1e}"
        )
        setting = f"n_output={n_output}"
        runs.append(
            Run("rollspring integrate", setting, integrate, trajectory.n_steps, evals, errors, note)
        )
        runs.append(
            Run(
                "rollspring simulate()",
                setting,
                call,
                trajectory.n_steps,
                evals,
                errors,
                "whole call: setup, integration, outputs, summary",
            )
        )
    return runs


def timed_calls(
    system: Any, rtol: float, n_output: int, repeats: int, warmup: int
) -> tuple[float, float, list[float], Any]:
    """``simulate(system, DURATION, rtol=rtol, n_output=n_output)`` timed ``repeats`` times
    after ``warmup`` calls: the best whole call, the best integration, every call's fixed cost
    (whole call minus integration, ascending) and the trajectory (of one more call: the runs
    are deterministic, and the timed ones are released as they end)."""
    timed = repeat(
        lambda: simulate(system, DURATION, rtol=rtol, n_output=n_output),
        repeats,
        warmup=warmup,
        keep=integration_time,
    )
    call = min(wall for wall, _ in timed)
    integrate = min(seconds for _, seconds in timed)
    fixed = sorted(wall - seconds for wall, seconds in timed)
    return call, integrate, fixed, simulate(system, DURATION, rtol=rtol, n_output=n_output)


def integration_time(trajectory: Any) -> float:
    """What the timed loops keep of each call: its compiled stepping's seconds (the trajectory
    itself is released before the next call, as a caller's loop releases it)."""
    seconds: float = trajectory.timings["integrate"]
    return seconds


#: n_output -> (best, median) fixed cost of rollspring's call (whole call minus integration), s
FIXED: dict[int, tuple[float, float]] = {}


def rollspring_ladder(
    n_output: int, repeats: int
) -> tuple[list[tuple[Run, Run]], dict[str, tuple[Run, Run]]]:
    """rollspring at the same accuracy as the other engines' ladders: rtol = 1e-9 Omega T x
    :data:`LADDER_FACTORS` (1000 down to 1 in steps of 1, 2, 5: loosest first, as SciPy's
    ladder); the loosest meeting each criterion, as (integration, whole call), each the best of
    ``repeats`` calls."""
    system = load_system("hoop-cylinder")
    ladder: list[tuple[Run, Run]] = []
    chosen: dict[str, tuple[Run, Run]] = {}
    for factor in LADDER_FACTORS:
        rtol = TARGET * CASE.omega * DURATION * factor
        call, integrate, _, trajectory = timed_calls(system, rtol, n_output, repeats, 2)
        errors = modal_errors(CASE, trajectory.t, trajectory.x, trajectory.v, trajectory.energy)
        evals = trajectory.n_steps * len(SCHEMES[trajectory.integrator][1])
        setting = f"rtol={rtol:.3g}, n_output={n_output}"
        pair = (
            Run("rollspring integrate", setting, integrate, trajectory.n_steps, evals, errors),
            Run(
                "rollspring simulate()", setting, call, trajectory.n_steps, evals, errors, rtol=rtol
            ),
        )
        ladder.append(pair)
        for name in CRITERIA:
            if name not in chosen and pair[1].meets(name):
                chosen[name] = pair
        if len(chosen) == len(CRITERIA):
            break
    return ladder, chosen


# -- MuJoCo ------------------------------------------------------------------------------------

#: contact settings of the tuned runs
TUNED_SOLIMP = (0.9999, 0.9999, 0.001, 0.5, 2.0)
TUNED_NOTE = (
    "MuJoCo tuned: elliptic friction cone, geom solref = (2 dt, 1) (the stiffest "
    "contact MuJoCo allows at that step), solimp = (0.9999, 0.9999, 0.001, 0.5, 2); "
    "other options at their defaults (impratio, noslip_iterations did not help)"
)


def mujoco_run(timestep: float, integrator: str, tuned: bool) -> Run:
    """Step the MJCF model for DURATION, recording the state about every SPACING; the wall time
    is the stepping loop (the model compiled beforehand). ``tuned``: elliptic friction cone,
    contact solref time constant 2 timesteps (the stiffest MuJoCo allows), solimp 0.9999."""
    import mujoco

    model = mujoco.MjModel.from_xml_string(hoop_cylinder_mjcf(CASE))
    model.opt.timestep = timestep
    model.opt.integrator = {
        "Euler": mujoco.mjtIntegrator.mjINT_EULER,
        "RK4": mujoco.mjtIntegrator.mjINT_RK4,
    }[integrator]
    setting = f"{integrator}, dt={timestep:.4g}"
    if tuned:  # see TUNED_NOTE
        model.opt.cone = mujoco.mjtCone.mjCONE_ELLIPTIC
        model.geom_solref[:] = (2 * timestep, 1.0)
        model.geom_solimp[:] = TUNED_SOLIMP
    else:
        setting += ", default contact"
    data = mujoco.MjData(model)
    n_steps = round(DURATION / timestep)
    per = max(1, round(SPACING / timestep))
    chunks = [per] * (n_steps // per) + ([n_steps % per] if n_steps % per else [])
    times = np.empty(len(chunks) + 1)
    qpos = np.empty((len(chunks) + 1, model.nq))
    qvel = np.empty((len(chunks) + 1, model.nv))
    times[0], qpos[0], qvel[0] = data.time, data.qpos, data.qvel
    step = mujoco.mj_step
    began = time.perf_counter()
    for j, n in enumerate(chunks, start=1):
        step(model, data, nstep=n)
        times[j] = data.time
        qpos[j] = data.qpos
        qvel[j] = data.qvel
    wall = time.perf_counter() - began
    x0 = np.array(CASE.x0)
    x = qpos[:, [0, 3]] + x0
    z = qpos[:, [1, 4]]
    v = qvel[:, [0, 3]]
    inertia = np.array([CASE.m1, 0.5 * CASE.m2]) * CASE.radius**2
    mass = np.array([CASE.m1, CASE.m2])
    length = np.hypot(x[:, 1] - x[:, 0], z[:, 1] - z[:, 0])
    energy = (
        0.5 * (mass * (v**2 + qvel[:, [1, 4]] ** 2) + inertia * qvel[:, [2, 5]] ** 2).sum(1)
        + 0.5 * CASE.k * (length - CASE.rest_length) ** 2
    )  # gravity left out
    evals = n_steps * (4 if integrator == "RK4" else 1)
    return Run(
        "MuJoCo tuned" if tuned else "MuJoCo",
        setting,
        wall,
        n_steps,
        evals,
        modal_errors(CASE, times, x, v, energy),
    )


def mujoco_tuned_ladder() -> tuple[list[Run], dict[str, Choice]]:
    """RK4 with tuned contact at timesteps 5 ms / j (whole steps between outputs), from the
    longest."""
    return climb(
        lambda j: mujoco_run(SPACING / j, "RK4", tuned=True),
        (2, 3, 4, 5, 6, 7, 8, 10, 12, 16, 20, 25),
        retime=5,
    )


# -- pymunk ------------------------------------------------------------------------------------


def pymunk_run(dt: float) -> Run:
    """Circles with their moments of inertia (hoop m R^2, cylinder m R^2 / 2) on a static
    segment floor, friction mu on both, a DampedSpring with damping 0 between the centres;
    fixed steps ``dt`` in a Python loop (pymunk has no multi-step call)."""
    import pymunk

    space = pymunk.Space()
    space.gravity = (0.0, -CASE.gravity)
    space.collision_slop = 1e-6  # the default 0.1 is meant for pixels, not metres
    r = CASE.radius
    floor = pymunk.Segment(space.static_body, (-10.0, 0.0), (10.0, 0.0), 0.0)
    floor.friction = CASE.mu
    hoop = pymunk.Body(CASE.m1, pymunk.moment_for_circle(CASE.m1, r, r))
    cylinder = pymunk.Body(CASE.m2, pymunk.moment_for_circle(CASE.m2, 0.0, r))
    hoop.position, cylinder.position = (CASE.x0[0], r), (CASE.x0[1], r)
    shapes = [pymunk.Circle(hoop, r), pymunk.Circle(cylinder, r)]
    for shape in shapes:
        shape.friction = CASE.mu
    spring = pymunk.DampedSpring(hoop, cylinder, (0, 0), (0, 0), CASE.rest_length, CASE.k, 0.0)
    space.add(floor, hoop, cylinder, *shapes, spring)
    n_steps = round(DURATION / dt)
    per = max(1, round(SPACING / dt))
    n_rows = n_steps // per + 1
    state = np.empty((n_rows, 2, 6))  # per body: x, y, vx, vy, omega, (spare)

    def record(j: int) -> None:
        for i, b in enumerate((hoop, cylinder)):
            state[j, i, :5] = (
                b.position.x,
                b.position.y,
                b.velocity.x,
                b.velocity.y,
                b.angular_velocity,
            )

    record(0)
    step = space.step
    began = time.perf_counter()
    for j in range(1, n_rows):
        for _ in range(per):
            step(dt)
        record(j)
    wall = time.perf_counter() - began
    times = np.arange(n_rows) * per * dt
    x, v = state[:, :, 0], state[:, :, 2]
    mass = np.array([hoop.mass, cylinder.mass])
    inertia = np.array([hoop.moment, cylinder.moment])
    length = np.hypot(x[:, 1] - x[:, 0], state[:, 1, 1] - state[:, 0, 1])
    energy = (
        0.5 * (mass * (v**2 + state[:, :, 3] ** 2) + inertia * state[:, :, 4] ** 2).sum(1)
        + 0.5 * CASE.k * (length - CASE.rest_length) ** 2
    )
    return Run(
        "pymunk",
        f"dt={dt:g}",
        wall,
        (n_rows - 1) * per,
        (n_rows - 1) * per,
        modal_errors(CASE, times, x, v, energy),
    )


def pymunk_ladder() -> tuple[list[Run], dict[str, Choice]]:
    """Steps from 1e-4 s down to 2e-6 s (12 s of wall time for the last)."""
    return climb(pymunk_run, (1e-4, 5e-5, 2.5e-5, 1e-5, 5e-6, 2e-6), retime=2)


# -- SciPy -------------------------------------------------------------------------------------


def reduced_rhs():
    """J phi'' = Q(phi) of the hoop-cylinder, by hand (scalar Python, the fastest for SciPy's
    loop): P_i = (x_i0 + R phi_i, R), T = k (l - L0), Q_1 = T e_x R, Q_2 = -T e_x R. Checked
    against rollspring.physics.generalized_forces."""
    r, k, rest = CASE.radius, CASE.k, CASE.rest_length
    x10, x20 = CASE.x0
    j1, j2 = 2 * CASE.m1 * r * r, 1.5 * CASE.m2 * r * r

    def rhs(_t, y):
        phi1, phi2, w1, w2 = y
        dx = x20 + r * phi2 - x10 - r * phi1
        tension_x = k * (abs(dx) - rest) * math.copysign(1.0, dx)  # T e_x
        return [w1, w2, tension_x * r / j1, -tension_x * r / j2]

    arrays = system_arrays(load_system("hoop-cylinder"))
    rng = np.random.default_rng(1)
    for q in rng.normal(scale=0.2, size=(5, 2)):
        mine = np.array(rhs(0.0, [*q, 0.0, 0.0])[2:])
        theirs = generalized_forces(arrays, q) / arrays.inertia
        assert np.allclose(mine, theirs, rtol=1e-13, atol=1e-12), (mine, theirs)
    return rhs


def scipy_call(method: str, rtol: float, rhs) -> Callable[[], Any]:
    """The timed part of a SciPy run: ``solve_ivp`` over 10 s with outputs every 5 ms."""
    import scipy.integrate

    grid = np.linspace(0.0, DURATION, round(DURATION / SPACING) + 1)

    def solve() -> Any:
        return scipy.integrate.solve_ivp(
            rhs,
            (0.0, DURATION),
            [0.0, 0.0, 0.0, 0.0],
            method=method,
            t_eval=grid,
            rtol=rtol,
            atol=rtol * 1e-2,
        )

    return solve


def scipy_run(method: str, rtol: float, rhs) -> Run:
    import scipy.integrate

    grid = np.linspace(0.0, DURATION, round(DURATION / SPACING) + 1)
    solve = scipy_call(method, rtol, rhs)
    began = time.perf_counter()
    solution = solve()
    wall = time.perf_counter() - began
    # the number of steps, from an untimed run with the dense output (same steps)
    steps = (
        len(
            scipy.integrate.solve_ivp(
                rhs, (0.0, DURATION), [0.0] * 4, method=method, rtol=rtol, atol=rtol * 1e-2
            ).t
        )
        - 1
    )
    r = CASE.radius
    x = np.stack([CASE.x0[0] + r * solution.y[0], CASE.x0[1] + r * solution.y[1]], axis=1)
    v = r * solution.y[2:].T
    j = np.array([2 * CASE.m1, 1.5 * CASE.m2]) * r * r
    energy = (
        0.5 * (j * solution.y[2:].T ** 2).sum(1)
        + 0.5 * CASE.k * (x[:, 1] - x[:, 0] - CASE.rest_length) ** 2
    )
    return Run(
        f"SciPy {method}",
        f"rtol={rtol:g}",
        wall,
        steps,
        int(solution.nfev),
        modal_errors(CASE, grid, x, v, energy),
        rtol=rtol,
    )


def scipy_ladder(method: str, rhs) -> tuple[list[Run], dict[str, Choice]]:
    """rtol = 1e-6, 5e-7, 2e-7, 1e-7, ... 1e-13 (atol = rtol / 100): steps of 1, 2, 5, as
    rollspring's ladder."""
    rtols = [m * 10.0**-e for e in range(7, 14) for m in (10.0, 5.0, 2.0)] + [1e-13]
    return climb(lambda rtol: scipy_run(method, rtol, rhs), rtols, retime=5)


def interleaved_ratio(
    slow: Callable[[], Any],
    fast: Callable[[], Any],
    keep: Callable[[Any], Any],
    rounds: int = 15,
    inner: int = 5,
) -> tuple[float, float, list[Any]]:
    """Best wall times of ``slow`` and of ``fast``, the two alternating for ``rounds`` rounds of
    ``inner`` back-to-back calls each (the same warm, back-to-back timing for both, the same
    number of samples): a machine whose speed drifts (a shared VM's does, by tens of per cent
    over seconds) slows both alike, so their ratio holds. Also returns ``keep`` of each of
    ``fast``'s results; every result of either is released before the next call (kept, they
    made each call page in fresh memory: :func:`common.repeat`)."""
    slow_best = fast_best = math.inf
    kept = []
    for _ in range(rounds):
        for _ in range(inner):
            began = time.perf_counter()
            slow()
            slow_best = min(slow_best, time.perf_counter() - began)
        for _ in range(inner):
            began = time.perf_counter()
            value = keep(fast())  # the result released within the timing, as slow()'s is
            fast_best = min(fast_best, time.perf_counter() - began)
            kept.append(value)
    return slow_best, fast_best, kept


# -- the report --------------------------------------------------------------------------------

HEADERS = [
    "engine",
    "setting",
    "wall [s]",
    "steps",
    "steps/s",
    "force evals",
    "max|x-x_ex|/A",
    "freq. error",
    "max|phase err|",
    "energy change",
    "meets",
]


ENGINES = ("rollspring", "mujoco", "pymunk", "scipy")
#: the whole simulate() call against SciPy's DOP853 on the same equations (issue 12)
DOP853_TARGET = 30
#: rollspring's rtol ladder at the same accuracy: 1e-9 Omega T times these (1, 2, 5 steps)
LADDER_FACTORS = (1000.0, 500.0, 200.0, 100.0, 50.0, 20.0, 10.0, 5.0, 2.0, 1.0)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument(
        "--engines",
        default=",".join(ENGINES),
        help=f"comma-separated subset of {','.join(ENGINES)} (rollspring always runs)",
    )
    parser.add_argument("--repeats", type=int, default=30, help="timed rollspring calls (best of)")
    args = parser.parse_args()
    chosen = {e.strip() for e in args.engines.split(",") if e.strip()} | {"rollspring"}
    if chosen - set(ENGINES):
        parser.error(f"unknown engine(s): {', '.join(sorted(chosen - set(ENGINES)))}")
    for engine in ("mujoco", "pymunk"):
        if engine in chosen and importlib.util.find_spec(engine) is None:
            print(f"({engine} is not installed: skipped; pip install -e '.[bench]')")
            chosen.discard(engine)
    print("hoop-cylinder, 10 s (the paper's Fig. 2): every engine against the exact modal solution")
    print(machine_note())
    print(
        f"Omega = {CASE.omega:.6f} rad/s, {CASE.omega * DURATION / (2 * math.pi):.1f} periods;"
        f" target: relative frequency error <= {TARGET:g}, two readings:"
    )
    for name, (text, _, _) in CRITERIA.items():
        print(f"  {name}: {text}")

    began = time.perf_counter()
    rolls = rollspring_runs(args.repeats)
    engines: dict[str, tuple[list[Run], dict[str, Choice]]] = {}
    default = exported = None
    euler: list[Run] = []
    if "mujoco" in chosen:
        # MuJoCo: its defaults, the RK4 setting rollspring's MJCF export uses, then tuned
        default = min(
            (mujoco_run(0.002, "Euler", tuned=False) for _ in range(3)), key=lambda r: r.wall
        )
        exported = mujoco_run(1e-4, "RK4", tuned=False)
        # first-order Euler with the tuned contact, for comparison (RK4 is far cheaper at 1e-9)
        euler = [mujoco_run(dt, "Euler", tuned=True) for dt in (1e-3, 2.5e-4)]
        engines["MuJoCo tuned"] = mujoco_tuned_ladder()
    if "pymunk" in chosen:
        engines["pymunk"] = pymunk_ladder()
    if "scipy" in chosen:
        rhs = reduced_rhs()
        for method in ("DOP853", "RK45"):
            engines[f"SciPy {method}"] = scipy_ladder(method, rhs)

    print_table(
        "All runs. wall: 'rollspring integrate' = time in the compiled stepping kernel "
        f"(timings['integrate']), 'simulate()' = the whole call, both best of {args.repeats}; "
        "others = their stepping loop, timed once on the ladders (the chosen settings are "
        "re-timed: next table)",
        HEADERS,
        [r.row() for r in rolls]
        + [r.row() for r in (default, exported) if r is not None]
        + [r.row() for r in euler]
        + [r.row() for ladder, _ in engines.values() for r in ladder],
    )
    for r in rolls[::2]:
        print(f"  rollspring {r.setting}: {r.note}")
    for n_output, (best, median) in FIXED.items():
        print(
            f"  rollspring n_output={n_output}: fixed cost (whole call minus integration) "
            f"best {best * 1e3:.3f} ms, median {median * 1e3:.3f} ms"
        )
    if "mujoco" in chosen:
        print(f"  {TUNED_NOTE}")

    # -- the key figure ---------------------------------------------------------------------
    walls = {(r.engine.split()[1], r.setting): r.wall for r in rolls}
    bases = [
        walls["integrate", "n_output=2001"],
        walls["simulate()", "n_output=2001"],
        walls["integrate", "n_output=201"],
        walls["simulate()", "n_output=201"],
    ]
    rows = []
    for r in rolls:
        meets = "+".join(name for name in CRITERIA if r.meets(name))
        rows.append(
            [
                r.engine,
                "-",
                r.setting,
                r.wall,
                meets or "no",
                f"{r.errors.frequency:.1e}",
                f"{r.errors.phase:.1e}",
                *["1" if r.wall == b else "" for b in bases],
            ]
        )
    for name, (_, choices) in engines.items():
        shown: dict[int, list] = {}
        for criterion, choice in choices.items():
            run = choice.run
            if id(run) in shown and choice.reached:  # the same run meets both: one row
                shown[id(run)][1] += f"+{criterion}"
                continue
            if choice.reached:
                wall, ratios = f"{run.wall:.3g}", [f"{run.wall / b:.3g}" for b in bases]
            else:
                wall = f"{run.wall:.3g} (~{choice.extrapolated_wall:.2g})"
                ratios = [
                    f"{run.wall / b:.3g} (~{choice.extrapolated_wall / b:.2g})" for b in bases
                ]
            rows.append(
                [
                    name,
                    criterion,
                    run.setting,
                    wall,
                    choice.reached,
                    f"{run.errors.frequency:.1e}",
                    f"{run.errors.phase:.1e}",
                    *ratios,
                ]
            )
            shown[id(run)] = rows[-1]
    print_table(
        "Wall time [s] to reach the target over 10 s, per criterion: the cheapest setting found "
        "(re-timed), or if not reached ('no') the best one, with in brackets '~' the time "
        "extrapolated to the target; and the ratio to rollspring's integration / whole call, "
        "with 2001 and with 201 outputs",
        [
            "engine",
            "criterion",
            "setting",
            "wall [s]",
            "reached",
            "freq. error",
            "max|phase err|",
            "x integ.(2001)",
            "x call(2001)",
            "x integ.(201)",
            "x call(201)",
        ],
        rows,
    )

    # -- the targets ------------------------------------------------------------------
    print("\nThe issue's targets (criterion 'freq'; ratios with 2001 outputs, [201 outputs]):")
    for name in ("MuJoCo tuned", "pymunk"):
        if name not in engines:
            continue
        choice = engines[name][1]["freq"]
        wall = choice.run.wall
        qualifier = (
            ""
            if choice.reached
            else (f" (which only reaches {abs(choice.run.errors.frequency):.2e}; measured wall)")
        )
        for what, target, b_full, b_short in (
            ("integration", 1000, bases[0], bases[2]),
            ("whole simulate() call", 100, bases[1], bases[3]),
        ):
            print(
                f"  {what} >= {target}x faster than {name}{qualifier}: "
                f"{wall / b_full:.0f}x [{wall / b_short:.0f}x] -> "
                f"{'met' if wall / b_full >= target else 'NOT met'} "
                f"[{'met' if wall / b_short >= target else 'NOT met'}]"
            )
    if "SciPy DOP853" in engines:
        for criterion, choice in engines["SciPy DOP853"][1].items():
            if not choice.reached:
                continue
            wall = choice.run.wall
            # rollspring's run above is far more accurate than the target: the 30x is
            # judged at the same accuracy, below
            print(
                f"  whole simulate() call at rtol {TARGET * CASE.omega * DURATION:.3g} (frequency "
                f"error {abs(rolls[0].errors.frequency):.1e}, the target {TARGET:.0e}) against "
                f"SciPy DOP853 at the target ({criterion}: {choice.run.setting}, "
                f"{wall * 1e3:.1f} ms): "
                f"{wall / bases[1]:.1f}x [{wall / bases[3]:.1f}x]; the {DOP853_TARGET}x target "
                "is judged at the same accuracy, below"
            )
        # at the same accuracy: each engine at its loosest setting meeting the criterion
        print(
            "\nAt the same accuracy (each at the loosest setting meeting the criterion on a ladder "
            "of 1, 2, 5 steps; rollspring's rtol 1e-9 Omega T x 1000 ... 1; the pair re-timed "
            "interleaved: 15 rounds of 5 DOP853 calls and 5 rollspring calls, best of each):"
        )
        system = load_system("hoop-cylinder")
        for n_output in (2001, 201):
            ladder, chosen_rtol = rollspring_ladder(n_output, max(5, args.repeats // 3))
            for integrate_run, call_run in ladder:
                e = call_run.errors
                print(
                    f"  rollspring {call_run.setting}: integration {integrate_run.wall * 1e3:.3f}"
                    f" ms, whole call {call_run.wall * 1e3:.3f} ms, {call_run.steps} steps, "
                    f"freq. error {e.frequency:.1e}, max phase error {e.phase:.1e}"
                )
            for criterion, choice in engines["SciPy DOP853"][1].items():
                if not choice.reached or criterion not in chosen_rtol:
                    continue
                _, call_run = chosen_rtol[criterion]
                assert choice.run.rtol is not None and call_run.rtol is not None
                wall, call, integrations = interleaved_ratio(
                    scipy_call("DOP853", choice.run.rtol, rhs),
                    lambda r=call_run.rtol, k=n_output: simulate(
                        system, DURATION, rtol=r, n_output=k
                    ),
                    integration_time,
                )
                integrate = min(integrations)
                ratio = wall / call
                print(
                    f"  {criterion}: SciPy DOP853 {choice.run.setting} {wall * 1e3:.1f} ms / "
                    f"rollspring {call_run.setting} whole call {call * 1e3:.3f} ms = "
                    f"{ratio:.1f}x (integration {wall / integrate:.0f}x) -> "
                    f"{'met' if ratio >= DOP853_TARGET else 'NOT met'}"
                )
    if default is not None and exported is not None:
        print(
            f"\nMuJoCo defaults over 10 s: energy change {default.errors.energy:+.2e}, "
            f"frequency error {default.errors.frequency:+.2e}; RK4 at dt=1e-4 with default "
            f"contact: {exported.errors.energy:+.2e}, {exported.errors.frequency:+.2e}"
        )
    print(f"benchmark time {time.perf_counter() - began:.0f} s")


if __name__ == "__main__":
    main()

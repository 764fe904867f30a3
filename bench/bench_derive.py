"""Symbolic equations of motion plus M and K for chains of N rolling bodies: rollspring's
derivation engine against ``sympy.physics.mechanics`` (KanesMethod and LagrangesMethod), in the
same run.

The system: N bodies alternating hoop, solid cylinder, hoop, ... (radius R, masses m_i), centres
joined by springs k_1 ... k_{N-1} at rest length L, rolling without slipping on one floor. Every
engine produces, with the parameters as symbols:

* the exact equations of motion (rolling embedded: one coordinate phi_i per body);
* the mass matrix M and the stiffness matrix K at the equilibrium (phi = 0).

rollspring: ``symbolic_system(system, symbols=True)`` then ``equations_of_motion()``,
``mass_matrix``, ``stiffness_matrix`` (the numeric equilibrium search is included).
KanesMethod: frames B_i rotated by -phi_i, centres at (i L + R phi_i, R), rigid bodies with
I = gamma m R^2, spring forces k(l - L) e on the centres with l = |C_{i+1} - C_i| (the usual
``magnitude()``), kinematic equations u_i = phi_i'; ``kanes_equations``, ``mass_matrix``,
K = -d(forcing)/d(phi) at phi = u = 0. LagrangesMethod: the Lagrangian T - V of the same bodies
and springs; ``form_lagranges_equations``, ``mass_matrix``, K as above.

SymPy's cache is cleared before every timed run (each engine starts cold). rollspring: best of
3; SymPy mechanics: one run per N, and N doubles until a run takes longer than ``LIMIT`` seconds;
its time at the largest N is then extrapolated from a power law t = a N^p fitted (least squares
in log-log) to its measured points with N >= 16 -- said so in the output. Where both engines ran,
M and K are compared numerically (random parameter values).

    .venv/bin/python bench/bench_derive.py            # about 3-5 minutes
    .venv/bin/python bench/bench_derive.py --limit 60 # give SymPy more time per N
    .venv/bin/python bench/bench_derive.py --full     # SymPy at every N, measured (~10 min)
    .venv/bin/python bench/bench_derive.py --commands # `rollspring derive` per preset (~2 min)

``--commands`` times the whole command a user runs, ``rollspring derive PRESET`` (all five
methods, the cross-check, plain text to a file), for every preset with exact numbers and with
``--symbols``, and a free chain of six bodies written to a system file: a fresh process each
time (start-up and imports included), best of 3 wall-clock seconds and that run's CPU seconds,
against the target of 3 s for the largest preset.
"""

from __future__ import annotations

import argparse
import json
import math
import resource
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np
import sympy as sp
from sympy.core.cache import clear_cache

sys.path.insert(0, str(Path(__file__).resolve().parent))

from common import machine_note

from rollspring.analysis.derivation import symbolic_system
from rollspring.model import System, load_system, preset_names, system_from_dict

SIZES = (2, 4, 8, 16, 32, 64, 128)
LIMIT = 30.0  # seconds: SymPy mechanics stops doubling N after a run longer than this


def chain(n: int) -> System:
    """N alternating hoops and cylinders, centres joined by springs at rest length 0.5 m."""
    bodies = [
        {
            "id": f"b{i + 1}",
            "shape": "hoop" if i % 2 == 0 else "cylinder",
            "mass": 1.0 + 0.1 * i,
            "radius": 0.1,
            "x": 0.5 * i,
        }
        for i in range(n)
    ]
    springs = [{"ends": [f"b{i + 1}", f"b{i + 2}"], "stiffness": 100.0 + i} for i in range(n - 1)]
    return system_from_dict({"name": f"chain of {n}", "bodies": bodies, "springs": springs})


def rollspring_route(system: System):
    sym = symbolic_system(system, symbols=True)
    equations = sym.equations_of_motion()
    return sym, equations, sym.mass_matrix, sym.stiffness_matrix


def mechanics_model(n: int, *, with_speeds: bool):
    """Bodies, loads, potential and coordinates for sympy.physics.mechanics; velocities in the
    generalised speeds u (Kane) or in q' (Lagrange)."""
    from sympy.physics.mechanics import (
        Point,
        ReferenceFrame,
        RigidBody,
        dynamicsymbols,
        inertia,
    )

    q = dynamicsymbols(f"phi1:{n + 1}")
    u = dynamicsymbols(f"u1:{n + 1}")
    m = sp.symbols(f"m1:{n + 1}", positive=True)
    k = sp.symbols(f"k1:{n}", positive=True)
    R, L = sp.symbols("R L", positive=True)
    frame = ReferenceFrame("N")
    origin = Point("O")
    origin.set_vel(frame, 0)
    rates = u if with_speeds else [qi.diff() for qi in q]
    bodies, centres = [], []
    for i in range(n):
        body_frame = frame.orientnew(f"B{i}", "Axis", [-q[i], frame.z])  # clockwise positive
        body_frame.set_ang_vel(frame, -rates[i] * frame.z)
        centre = origin.locatenew(f"C{i}", (i * L + R * q[i]) * frame.x + R * frame.y)
        centre.set_vel(frame, R * rates[i] * frame.x)
        gamma = 1 if i % 2 == 0 else sp.Rational(1, 2)
        central = inertia(body_frame, 0, 0, gamma * m[i] * R**2)
        bodies.append(RigidBody(f"b{i}", centre, body_frame, m[i], (central, centre)))
        centres.append(centre)
    loads, potential = [], 0
    for s in range(n - 1):
        d = centres[s + 1].pos_from(centres[s])
        length = d.magnitude()
        tension = k[s] * (length - L)
        loads.append((centres[s], tension * d / length))
        loads.append((centres[s + 1], -tension * d / length))
        potential += k[s] * (length - L) ** 2 / 2
    return q, u, m, k, R, L, frame, bodies, loads, potential


def kane_route(n: int):
    from sympy.physics.mechanics import KanesMethod

    q, u, *_, frame, bodies, loads, _potential = mechanics_model(n, with_speeds=True)
    kd = [u[i] - q[i].diff() for i in range(n)]
    kane = KanesMethod(frame, q_ind=q, u_ind=u, kd_eqs=kd)
    fr, frstar = kane.kanes_equations(bodies, loads)
    mass = kane.mass_matrix
    at_rest = {**dict.fromkeys(q, 0), **dict.fromkeys(u, 0)}
    stiffness = -kane.forcing.jacobian(q).subs(at_rest)
    return fr + frstar, mass, stiffness


def lagrange_route(n: int):
    from sympy.physics.mechanics import LagrangesMethod, Lagrangian

    q, _u, *_, frame, bodies, _loads, potential = mechanics_model(n, with_speeds=False)
    lagrangian = Lagrangian(frame, *bodies) - potential
    method = LagrangesMethod(lagrangian, q)
    equations = method.form_lagranges_equations()
    mass = method.mass_matrix
    stiffness = (
        -method.forcing.jacobian(q).subs(dict.fromkeys(q, 0)).subs({qi.diff(): 0 for qi in q})
    )
    return equations, mass, stiffness


def timed(run):
    clear_cache()
    began = time.perf_counter()
    result = run()
    return time.perf_counter() - began, result


def compare(n: int, ours, theirs) -> float:
    """Largest relative difference of M and K for random parameter values."""
    sym, _, mass, stiffness = ours
    _, their_mass, their_stiffness = theirs
    rng = np.random.default_rng(n)
    mine: dict = {}
    values_m = rng.uniform(0.5, 2.0, n)
    values_k = rng.uniform(50.0, 150.0, n - 1)
    radius, length = 0.1, 0.5
    for b, value in zip(sym.bodies, values_m, strict=True):
        mine[b.m] = value
    for s, value in zip(sym.springs, values_k, strict=True):
        mine[s.k] = value
        mine[s.ell] = length
    mine[sym.bodies[0].R] = radius
    m = sp.symbols(f"m1:{n + 1}", positive=True)
    k = sp.symbols(f"k1:{n}", positive=True)
    R, L = sp.symbols("R L", positive=True)
    theirs_values = {
        **dict(zip(m, values_m, strict=True)),
        **dict(zip(k, values_k, strict=True)),
        R: radius,
        L: length,
    }

    def num(matrix, values):
        return np.array(sp.matrix2numpy(matrix.xreplace(values).evalf()), dtype=float)

    worst = 0.0
    for a, b in (
        (num(mass, mine), num(their_mass, theirs_values)),
        (num(stiffness, mine), num(sp.Matrix(their_stiffness), theirs_values)),
    ):
        worst = max(worst, float(np.max(np.abs(a - b)) / np.max(np.abs(b))))
    return worst


def power_law(points: list[tuple[int, float]]) -> tuple[float, float] | None:
    """(a, p) of t = a N^p fitted to the points with N >= 16 (at least two; the growth
    steepens with N, so the small sizes are left out)."""
    usable = [(n, t) for n, t in points if n >= 16 and t > 0]
    if len(usable) < 2:
        return None
    x = np.log([n for n, _ in usable])
    y = np.log([t for _, t in usable])
    p, log_a = np.polyfit(x, y, 1)
    return math.exp(log_a), p


COMMAND_TARGET = 3.0  # seconds: `rollspring derive` on the largest preset (issue 13)


def command_seconds(arguments: list[str]) -> tuple[float, float]:
    """(wall, CPU) seconds of one ``rollspring derive ...`` in a fresh process."""
    executable = Path(sys.executable).with_name("rollspring")
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    began = time.perf_counter()
    subprocess.run([str(executable), "derive", *arguments], check=True, capture_output=True)
    wall = time.perf_counter() - began
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    return wall, cpu


def commands(repeats: int = 3) -> None:
    """Time ``rollspring derive`` for every preset and a six-body chain (see the module)."""
    print(machine_note())
    print(
        "`rollspring derive SYSTEM -o FILE` (text), a fresh process each: best of "
        f"{repeats} wall seconds (its CPU seconds)\n"
    )
    with tempfile.TemporaryDirectory() as folder:
        six = Path(folder) / "chain-6.json"
        bodies = [
            {
                "id": f"b{i + 1}",
                "shape": ("hoop", "cylinder", "sphere")[i % 3],
                "mass": 1.0 + 0.1 * i,
                "radius": 0.1,
                "x": 0.5 * i,
            }
            for i in range(6)
        ]
        springs = [{"ends": [f"b{i + 1}", f"b{i + 2}"], "stiffness": 100.0 + i} for i in range(5)]
        six.write_text(json.dumps({"name": "chain of 6", "bodies": bodies, "springs": springs}))
        out = str(Path(folder) / "out.txt")
        cases = [(name, [name]) for name in preset_names()] + [("chain of 6", [str(six)])]
        largest = max(preset_names(), key=lambda name: len(load_system(name).bodies))
        print(f"{'system':24s} {'numbers':>16s} {'--symbols':>16s}")
        for label, system in cases:
            cells = []
            for extra in ([], ["--symbols"]):
                runs = [command_seconds([*system, *extra, "-o", out]) for _ in range(repeats)]
                wall, cpu = min(runs)
                verdict = ""
                if label == largest:
                    verdict = " ok" if wall <= COMMAND_TARGET else " SLOW"
                cells.append(f"{wall:6.2f} s ({cpu:4.2f}){verdict}")
            print(f"{label:24s} " + " ".join(f"{c:>16s}" for c in cells), flush=True)
        print(f"\ntarget: the largest preset ({largest}) within {COMMAND_TARGET:g} s")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument(
        "--limit",
        type=float,
        default=LIMIT,
        help="seconds after which SymPy mechanics stops doubling N",
    )
    parser.add_argument(
        "--full",
        action="store_true",
        help="run SymPy mechanics at every N (no extrapolation; ~10 minutes)",
    )
    parser.add_argument(
        "--commands",
        action="store_true",
        help="time `rollspring derive` for every preset instead (~2 minutes)",
    )
    args = parser.parse_args()
    if args.commands:
        commands()
        return
    print(machine_note())
    print(
        "Symbolic EoM + M + K for chains of alternating hoops and cylinders (parameters as "
        "symbols); SymPy cache cleared before each run.\n"
    )
    measured: dict[str, list[tuple[int, float]]] = {"KanesMethod": [], "LagrangesMethod": []}
    going = {"KanesMethod": True, "LagrangesMethod": True}
    ours_times: dict[int, float] = {}
    rows = []
    for n in SIZES:
        system = chain(n)
        runs = [timed(lambda system=system: rollspring_route(system)) for _ in range(3)]
        ours_time, ours = min(runs, key=lambda pair: pair[0])
        ours_times[n] = ours_time
        row = {"N": n, "rollspring": ours_time}
        for name, route in (("KanesMethod", kane_route), ("LagrangesMethod", lagrange_route)):
            if not going[name]:
                continue
            seconds, result = timed(lambda route=route, n=n: route(n))
            measured[name].append((n, seconds))
            row[name] = seconds
            if n <= 16:
                row[f"{name} check"] = compare(n, ours, result)
            if seconds > args.limit and not args.full:
                going[name] = False
        rows.append(row)
        print(_row_text(row), flush=True)
    largest = SIZES[-1]
    print()
    print(f"N = {largest}: rollspring {ours_times[largest]:.3f} s (best of 3, measured)")
    for name in measured:
        points = measured[name]
        at_largest = [t for n, t in points if n == largest]
        if at_largest:
            seconds, how = at_largest[0], "measured"
        else:
            fit = power_law(points)
            if fit is None:
                print(f"  {name}: too few points to extrapolate")
                continue
            a, p = fit
            seconds = a * largest**p
            how = (
                f"EXTRAPOLATED from t = {a:.3g} N^{p:.2f} fitted to its runs at N = "
                f"{', '.join(str(n) for n, _ in points if n >= 16)} (measured in this run)"
            )
        ratio = seconds / ours_times[largest]
        print(f"  {name}: {seconds:.1f} s ({how}); rollspring is {ratio:.0f}x faster")
        verdict = "met" if ratio >= 100 else "NOT met"
        print(f"    target >= 100x: {verdict}")
    print("\nRatios measured in this run (SymPy mechanics time / rollspring time):")
    for row in rows:
        parts = [f"{name} {row[name] / row['rollspring']:.0f}x" for name in measured if name in row]
        if parts:
            print(f"  N = {row['N']:>3}: " + ", ".join(parts))


def _row_text(row: dict) -> str:
    text = f"N = {row['N']:>3}  rollspring {row['rollspring']:8.3f} s"
    for name in ("KanesMethod", "LagrangesMethod"):
        if name in row:
            text += f"   {name} {row[name]:8.2f} s"
            check = row.get(f"{name} check")
            if check is not None:
                text += f" (M, K agree to {check:.1e})"
    return text


if __name__ == "__main__":
    main()

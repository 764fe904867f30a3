"""Long chains (issue 14.1): the cost of ``analyze`` and ``simulate`` against the number of
bodies, with the issue's targets.

Chains of hoops and cylinders (``rollspring.chain(pattern="hoop,cylinder", n=N, walls="both",
pluck=1)``: 1 kg, R = 0.1 m, 100 N/m springs joining the centres, a = 0.5 m, the first body
plucked 1 cm). Every figure is measured in this run:

* ``analyze`` of N = 100, 1000, 10000 bodies, each in a fresh process (its wall time, and its
  peak memory: the process' ``ru_maxrss``), beside a process that only imports rollspring and
  builds the chain (the baseline: the memory the analysis adds is the difference);
* ``rollspring simulate FILE -T 10`` of N = 1000 at the default rtol, the command line in a fresh
  process (median of 3, Numba's kernel cache warm), beside ``rollspring simulate hoop-cylinder
  -T 10`` timed alike (the start-up both pay);
* the cost of a simulation step for N = 100 … 3000 (``simulate(chain, 10.0)`` in this process,
  median of 3 after a warm-up: the whole call, setup, the 2001 output rows and the summary
  included, and the compiled stepping alone, ``timings["integrate"]``, each divided by the
  steps), with the exponent of a least-squares fit of log(cost per step) against log N;
* ``analyze`` with every mode for N = 250 … 2000 (median of 3) and its fitted exponent.

Targets: analyze N = 1000 ≤ 2 s, N = 10000 ≤ 30 s, peak memory < 1 GB; simulate N = 1000
-T 10 ≤ 10 s; exponents ≤ 1.2 per step, ≤ 2 for every mode. A missed target prints ✘ (exit
status 0: the benchmarks report, they do not fail). Run: ``python bench/bench_chains.py``
(about 2 minutes on 2 cores); ``--quick`` leaves out N = 10000 and N = 3000.
"""

from __future__ import annotations

import argparse
import json
import math
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
from common import fmt, machine_note, print_table

import rollspring
from rollspring.model.chains import chain

EXECUTABLE = str(Path(sys.executable).with_name("rollspring"))

#: a child process: build the chain of N bodies, optionally analyse it; print seconds and the
#: peak resident memory (ru_maxrss, kB on Linux) as JSON
CHILD = """
import json, resource, sys, time
import rollspring
from rollspring.model.chains import chain
n, work = int(sys.argv[1]), sys.argv[2]
system = chain(pattern="hoop,cylinder", n=n, walls="both", pluck=1)
began = time.perf_counter()
if work == "analyze":
    rollspring.analyze(system, confirm=True)
seconds = time.perf_counter() - began
print(json.dumps({"seconds": seconds,
                  "maxrss_mb": resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024}))
"""


def child(n: int, work: str) -> dict[str, float]:
    done = subprocess.run(
        [sys.executable, "-c", CHILD, str(n), work], capture_output=True, text=True, check=True
    )
    result: dict[str, float] = json.loads(done.stdout.strip().splitlines()[-1])
    return result


def mark(value: float, target: float) -> str:
    return "✔" if value <= target else "✘"


def fitted_exponent(sizes: list[int], costs: list[float]) -> float:
    """The slope of the least-squares line through (log N, log cost)."""
    slope, _ = np.polyfit(np.log(sizes), np.log(costs), 1)
    return float(slope)


def median_time(command: list[str], runs: int) -> float:
    times = []
    for _ in range(runs):
        began = time.perf_counter()
        subprocess.run(command, capture_output=True, check=True)
        times.append(time.perf_counter() - began)
    return statistics.median(times)


def system_of(n: int) -> rollspring.System:
    return chain(pattern="hoop,cylinder", n=n, walls="both", pluck=1)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="leave out N = 10000 and 3000")
    args = parser.parse_args()
    print(machine_note())
    rollspring.simulate(system_of(4), 0.1)  # Numba's kernels compiled (or loaded) once

    # -- analyze: time and peak memory, each in a fresh process ------------------------------
    baseline = child(100, "build")
    rows = [["import + chain of 100 (baseline)", "-", fmt(baseline["maxrss_mb"], ".0f"), "", ""]]
    targets = {100: None, 1000: 2.0, 10000: 30.0}
    for n, target in targets.items():
        if args.quick and n == 10000:
            continue
        measured = child(n, "analyze")
        rows.append(
            [
                f"analyze N = {n}",
                fmt(measured["seconds"]),
                fmt(measured["maxrss_mb"], ".0f"),
                fmt(measured["maxrss_mb"] - baseline["maxrss_mb"], ".0f"),
                ""
                if target is None
                else f"≤ {target:g} s {mark(measured['seconds'], target)}"
                + f", < 1 GB {mark(measured['maxrss_mb'], 1024)}",
            ]
        )
    print_table(
        "analyze of a chain (a fresh process each)",
        ["case", "time (s)", "peak RSS (MB)", "above baseline (MB)", "target"],
        rows,
    )

    # -- the command line: simulate -T 10 of 1000 bodies ------------------------------------
    with tempfile.TemporaryDirectory() as folder:
        path = str(Path(folder) / "chain.toml")
        subprocess.run(
            [EXECUTABLE, "chain", "--n", "1000", "--walls", "both", "--pluck", "1", "-o", path],
            capture_output=True,
            check=True,
        )
        paper = median_time([EXECUTABLE, "simulate", "hoop-cylinder", "-T", "10"], 3)
        long = median_time([EXECUTABLE, "simulate", path, "-T", "10"], 3)
    call = statistics.median(
        rollspring.simulate(system_of(1000), 10.0).timings["total"] for _ in range(3)
    )
    print_table(
        "rollspring simulate -T 10 (a fresh process each, median of 3)",
        ["case", "time (s)", "× the paper's system", "target"],
        [
            ["hoop-cylinder (baseline)", fmt(paper), "1", ""],
            ["chain of 1000 bodies", fmt(long), fmt(long / paper), f"≤ 10 s {mark(long, 10.0)}"],
            ["  of which simulate() in Python", fmt(call), fmt(call / paper), ""],
        ],
    )

    # -- the cost of a step against N ----------------------------------------------------------
    sizes = [100, 300, 1000] + ([] if args.quick else [3000])
    whole, stepping, rows = [], [], []
    for n in sizes:
        system = system_of(n)
        rollspring.simulate(system, 0.1)
        runs = [rollspring.simulate(system, 10.0, confirm=True) for _ in range(3)]
        steps = runs[0].n_steps
        total = statistics.median(r.timings["total"] for r in runs) / steps
        integrate = statistics.median(r.timings["integrate"] for r in runs) / steps
        whole.append(total)
        stepping.append(integrate)
        rows.append(
            [
                str(n),
                str(steps),
                fmt(total * 1e6),
                fmt(integrate * 1e6),
                fmt(integrate / (n + len(system.springs)) * 1e9),
            ]
        )
    exponent_whole = fitted_exponent(sizes, whole)
    exponent_step = fitted_exponent(sizes, stepping)
    rows.append(
        [
            "exponent",
            "",
            f"{exponent_whole:.2f} {mark(exponent_whole, 1.2)}",
            f"{exponent_step:.2f} {mark(exponent_step, 1.2)}",
            "",
        ]
    )
    print_table(
        "simulate(chain, 10 s): cost per step (median of 3; target exponent ≤ 1.2)",
        ["N", "steps", "whole call (µs/step)", "stepping (µs/step)", "ns per body+spring"],
        rows,
    )

    # -- analyze with every mode against N --------------------------------------------------------
    sizes = [250, 500, 1000, 2000]
    costs, rows = [], []
    for n in sizes:
        system = system_of(n)
        times = []
        for _ in range(3):
            began = time.perf_counter()
            result = rollspring.analyze(system, confirm=True)
            times.append(time.perf_counter() - began)
        assert len(result.modes) == n  # every mode
        costs.append(statistics.median(times))
        rows.append([str(n), fmt(costs[-1])])
    exponent = fitted_exponent(sizes, costs)
    rows.append(["exponent", f"{exponent:.2f} {mark(exponent, 2.0)}"])
    print_table(
        "analyze with every mode (median of 3; target exponent ≤ 2)", ["N", "time (s)"], rows
    )
    print(machine_note().replace("at start", "at the end"))
    if not math.isfinite(exponent):
        raise SystemExit(1)


if __name__ == "__main__":
    main()

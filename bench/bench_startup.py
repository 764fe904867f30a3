"""Start-up time of the command line and of ``import rollspring`` (issue 12, point 3).

Each case is a fresh process, run ``RUNS`` times after one untimed warm-up (which fills Numba's
on-disk kernel cache and the byte-code caches as a user's first run would: the processes run
without ``PYTHONDONTWRITEBYTECODE``, which would make every run compile rollspring's own modules
from source again, about 0.1 s of CPU, where an installed package has its byte code); the median
wall time is reported in seconds and as a multiple of a bare ``python -c pass`` timed in the same
run, with the target and ✔/✘ (on the median wall time), and the median CPU time (user + system)
of the process, which other work on the machine inflates far less than the wall time. The load
average is printed at the start and the end. The figures are also written to
``build/bench/startup.json``.

Cases and targets (seconds):

* ``python -c "import rollspring"``                    ≤ 0.3
* ``rollspring --help``                                ≤ 0.3
* ``rollspring analyze hoop-cylinder --json``          ≤ 0.6
* ``rollspring simulate hoop-cylinder -T 10``          ≤ 1.0 (kernel cache warm)
* ``rollspring chain --n 3 --pattern hoop --out c.toml`` ≤ 0.6 (writes a file: no Numba, SciPy)
* ``rollspring export hoop-cylinder --format mjcf -o x.xml`` ≤ 0.6 (the same)

The files the commands write go to a temporary folder, removed at the end.

Run: ``python bench/bench_startup.py`` (about 30 s). ``--runs N`` changes the number of runs.
Exit status 0 when it ran (a missed target is a ✘), as the other benchmarks.
"""

from __future__ import annotations

import argparse
import json
import os
import platform
import resource
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
PYTHON = sys.executable
EXECUTABLE = str(Path(sys.executable).with_name("rollspring"))

#: (label, command line, target in seconds or None); ``{out}`` in an argument stands for the
#: temporary folder the written files go to
CASES: list[tuple[str, list[str], float | None]] = [
    ("python -c pass", [PYTHON, "-c", "pass"], None),
    ("import rollspring", [PYTHON, "-c", "import rollspring"], 0.3),
    ("rollspring --help", [EXECUTABLE, "--help"], 0.3),
    (
        "rollspring analyze hoop-cylinder --json",
        [EXECUTABLE, "analyze", "hoop-cylinder", "--json"],
        0.6,
    ),
    (
        "rollspring simulate hoop-cylinder -T 10",
        [EXECUTABLE, "simulate", "hoop-cylinder", "-T", "10"],
        1.0,
    ),
    (
        "rollspring chain --n 3 --pattern hoop --out c.toml",
        [EXECUTABLE, "chain", "--n", "3", "--pattern", "hoop", "--out", "{out}/c.toml"],
        0.6,
    ),
    (
        "rollspring export hoop-cylinder --format mjcf -o x.xml",
        [EXECUTABLE, "export", "hoop-cylinder", "--format", "mjcf", "-o", "{out}/x.xml"],
        0.6,
    ),
]


#: The processes' environment: a fixed width for Rich, and byte-code caches written and read as
#: on a user's machine (``PYTHONDONTWRITEBYTECODE``, set in some sandboxes and CI images, would
#: compile rollspring's modules from source in every run).
ENVIRONMENT = {
    **{k: v for k, v in os.environ.items() if k != "PYTHONDONTWRITEBYTECODE"},
    "COLUMNS": "110",
}


def run_once(argv: list[str]) -> tuple[float, float]:
    """(wall time, CPU time user + system) of one process; raises if it fails. The CPU time
    is what the process itself spent, so it grows far less than the wall time when other work
    competes for the cores."""
    began = time.perf_counter()
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    done = subprocess.run(
        argv,
        stdout=subprocess.DEVNULL,
        stderr=subprocess.PIPE,
        check=False,
        env=ENVIRONMENT,
    )
    elapsed = time.perf_counter() - began
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    if done.returncode != 0:
        raise SystemExit(
            f"{' '.join(argv)} failed ({done.returncode}): "
            f"{done.stderr.decode(errors='replace').strip()}"
        )
    return elapsed, cpu


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--runs", type=int, default=10)
    parser.add_argument("--out", type=Path, default=ROOT / "build" / "bench" / "startup.json")
    args = parser.parse_args()

    load = os.getloadavg()[0] if hasattr(os, "getloadavg") else float("nan")
    print(
        f"machine: {platform.machine()}, {os.cpu_count()} CPUs, Python "
        f"{platform.python_version()}, load average {load:.2f} at start; "
        f"median of {args.runs} runs after one warm-up"
    )
    results = []
    folder = tempfile.TemporaryDirectory(prefix="rollspring-bench-startup-")
    for label, template, target in CASES:
        argv = [part.replace("{out}", folder.name) for part in template]
        run_once(argv)  # warm-up: byte-code and Numba caches
        measured = [run_once(argv) for _ in range(args.runs)]
        times = [wall for wall, _ in measured]
        cpu = [used for _, used in measured]
        results.append(
            {
                "case": label,
                "argv": [Path(template[0]).name, *template[1:]],
                "median_s": statistics.median(times),
                "best_s": min(times),
                "times_s": times,
                "cpu_median_s": statistics.median(cpu),
                "cpu_s": cpu,
                "target_s": target,
            }
        )
    folder.cleanup()
    load_end = os.getloadavg()[0] if hasattr(os, "getloadavg") else float("nan")
    bare = results[0]["median_s"]
    for row in results:
        row["multiple_of_bare_python"] = row["median_s"] / bare
        row["meets_target"] = (
            None if row["target_s"] is None else row["median_s"] <= row["target_s"]
        )

    headers = ("case", "median (s)", "best (s)", "CPU median (s)", "× python", "target (s)", "")
    cells = [headers] + [
        (
            r["case"],
            f"{r['median_s']:.3f}",
            f"{r['best_s']:.3f}",
            f"{r['cpu_median_s']:.3f}",
            f"{r['multiple_of_bare_python']:.1f}",
            "-" if r["target_s"] is None else f"≤ {r['target_s']:g}",
            "" if r["meets_target"] is None else ("✔" if r["meets_target"] else "✘"),
        )
        for r in results
    ]
    widths = [max(len(row[i]) for row in cells) for i in range(len(headers))]
    for n, row in enumerate(cells):
        print(
            "  ".join(
                c.ljust(w) if i == 0 else c.rjust(w)
                for i, (c, w) in enumerate(zip(row, widths, strict=True))
            )
        )
        if n == 0:
            print("  ".join("-" * w for w in widths))

    print(f"load average {load_end:.2f} at the end")
    args.out.parent.mkdir(parents=True, exist_ok=True)
    args.out.write_text(
        json.dumps(
            {
                "machine": {
                    "arch": platform.machine(),
                    "cpus": os.cpu_count(),
                    "python": platform.python_version(),
                    "load_average": load,
                    "load_average_end": load_end,
                },
                "runs": args.runs,
                "bare_python_s": bare,
                "cases": results,
            },
            indent=2,
        )
        + "\n"
    )
    print(f"wrote {args.out.relative_to(ROOT) if args.out.is_relative_to(ROOT) else args.out}")


if __name__ == "__main__":
    main()

"""Time ``rollspring report`` on the paper's hoop-cylinder system, end to end (target: < 10 s).

What is timed:

* **command, HTML**: ``rollspring report hoop-cylinder -o report.html`` as a fresh process, the
  way a user runs it: Python start-up, imports (NumPy, SciPy, Numba's cached kernels, Matplotlib,
  SymPy where the page uses it), the analysis, the simulation, every figure, the animation data,
  the derivations and paper checks the page holds, writing the file. This is the figure the
  issue's target applies to.
* **command, PDF**: the same with ``-o report.pdf`` (headless Chromium prints the page).
* **in-process**: ``build_report`` + ``write_report`` in this process, after a warm-up (imports
  and compilation paid once): what a notebook or a server calling the library pays per report.

The first process run is a warm-up, untimed (it fills Numba's and Matplotlib's on-disk caches as a
user's first run would). Each is run several times; the median and the best are printed with the
ratio of the median to the 10 s target. Run: ``python bench/bench_report.py``.
"""

from __future__ import annotations

import statistics
import subprocess
import sys
import tempfile
from pathlib import Path

from common import machine_note, print_table, repeat

TARGET = 10.0  # s, the target for the hoop-cylinder report
RUNS = 5
EXECUTABLE = Path(sys.executable).with_name("rollspring")


def command(out: Path) -> None:
    """One ``rollspring report`` process; raises if it fails."""
    done = subprocess.run(
        [str(EXECUTABLE), "report", "hoop-cylinder", "-o", str(out)],
        capture_output=True,
        text=True,
        check=False,
    )
    if done.returncode != 0 or not out.exists():
        raise SystemExit(f"rollspring report failed ({done.returncode}): {done.stderr.strip()}")


def main() -> None:
    print(machine_note())
    from rollspring import load_system
    from rollspring.outputs.report import find_chromium, write_report
    from rollspring.service.documents import build_report

    rows = []
    with tempfile.TemporaryDirectory(prefix="bench-report-") as folder:
        html = Path(folder) / "report.html"
        pdf = Path(folder) / "report.pdf"
        cases = [("command, HTML", lambda: command(html))]
        try:
            find_chromium()
            cases.append(("command, PDF", lambda: command(pdf)))
        except Exception as exc:  # noqa: BLE001 - the PDF row is optional
            print(f"(no PDF row: {exc})")
        system = load_system("hoop-cylinder")
        cases.append(("in-process build + write", lambda: write_report(build_report(system), html)))
        for label, run in cases:
            times = [t for t, _ in repeat(run, RUNS, warmup=1)]
            print(f"{label}: " + ", ".join(f"{t:.2f}" for t in times) + " s", flush=True)
            median = statistics.median(times)
            rows.append(
                [
                    label,
                    f"{median:.2f}",
                    f"{min(times):.2f}",
                    f"{max(times):.2f}",
                    f"{median / TARGET:.2f}",
                    "yes" if median < TARGET else "NO",
                ]
            )
        size = html.stat().st_size
        built = build_report(system)
    print_table(
        f"rollspring report hoop-cylinder: {RUNS} runs each after a warm-up",
        ["what", "median (s)", "best (s)", "worst (s)", "median / 10 s", "< 10 s"],
        rows,
    )
    stages = ", ".join(f"{stage} {seconds:.2f}" for stage, seconds in built.timings.items())
    print(f"HTML size {size / 1e6:.2f} MB; in-process stages (s): {stages}")


if __name__ == "__main__":
    main()

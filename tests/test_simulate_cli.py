"""``rollspring simulate``: files, JSON summary, errors, and atomic writing."""

from __future__ import annotations

import csv
import json
import math
import os
from pathlib import Path

import numpy as np
import pytest
from typer.testing import CliRunner

from rollspring.cli import app
from rollspring.model import load_system
from rollspring.outputs import atomic as output_files
from rollspring.outputs import write_trajectory
from rollspring.simulate import simulate

runner = CliRunner()
SUMMARY_KEYS = {
    "status",
    "energy",
    "energy_error",
    "period_measured",
    "period_linear",
    "max_friction_ratio",
    "min_normal_force",
    "first_slip",
    "first_liftoff",
    "final",
}


def run(*args: str):
    return runner.invoke(app, list(args))


def test_json_summary_is_the_only_thing_on_stdout(tmp_path) -> None:
    result = run("simulate", "hoop-cylinder", "--duration", "3", "--json", "--out", str(tmp_path))
    assert result.exit_code == 0, result.output
    summary = json.loads(result.stdout)
    assert SUMMARY_KEYS <= set(summary)
    assert summary["status"] == "finished"
    omega = math.sqrt(100 / 2 + 2 * 100 / 3)
    assert summary["period_linear"] == pytest.approx(2 * math.pi / omega, rel=1e-12)
    assert summary["period_measured"] == pytest.approx(2 * math.pi / omega, rel=1e-8)
    assert summary["final"]["time"] == 3.0
    assert set(summary["final"]["bodies"]["hoop"]) == {"x", "phi", "v", "omega"}
    assert "wrote" in result.stderr
    assert sorted(p.name for p in tmp_path.iterdir()) == [
        "summary.json",
        "trajectory.csv",
        "trajectory.npz",
    ]


def test_files_hold_the_same_numbers(tmp_path) -> None:
    trajectory = simulate(load_system("two-cylinders"), 1.0, n_output=101)
    write_trajectory(trajectory, tmp_path)
    with open(tmp_path / "trajectory.csv", newline="") as handle:
        rows = list(csv.reader(handle))
    header = rows[0]
    assert header[0] == "t"
    assert [h for h in header if h.endswith(".x")] == [f"{i}.x" for i in trajectory.ids]
    table = np.array(rows[1:], dtype=float)
    assert table.shape == (101, len(header))
    npz = np.load(tmp_path / "trajectory.npz")
    summary = json.loads((tmp_path / "summary.json").read_text())
    assert set(summary["columns"]) == set(header) == set(npz.files)
    first_x = next(h for h in header if h.endswith(".x"))
    np.testing.assert_array_equal(table[:, header.index(first_x)], npz[first_x])
    np.testing.assert_array_equal(npz[first_x], trajectory.x[:, 0])
    assert summary["columns"][first_x] == "m" and summary["columns"]["t"] == "s"


def test_without_out_no_files_are_written(tmp_path, monkeypatch) -> None:
    monkeypatch.chdir(tmp_path)
    result = run("simulate", "two-hoops", "-T", "1")
    assert result.exit_code == 0, result.output
    assert "finished" in result.stdout
    assert list(tmp_path.iterdir()) == []


@pytest.mark.parametrize(
    ("args", "field"),
    [
        (["--duration", "-1"], "duration"),
        (["--rtol", "0"], "rtol"),
        (["--integrator", "euler"], "integrator"),
        (["--on-slip", "skid"], "on_slip"),
        (["--outputs", "1"], "n_output"),
    ],
)
def test_invalid_arguments_are_one_line_errors_with_exit_2(args, field) -> None:
    result = run("simulate", "hoop-cylinder", *args)
    assert result.exit_code == 2
    assert result.stdout == ""
    lines = result.stderr.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith(f"error: {field}: ")


def test_a_slip_is_reported_on_stderr_and_in_the_summary(tmp_path) -> None:
    system = tmp_path / "slippy.toml"
    system.write_text(load_system_text().replace("mu_static = 1.0", "mu_static = 0.01", 1))
    result = run("simulate", str(system), "-T", "2", "--json")
    assert result.exit_code == 0, result.output
    summary = json.loads(result.stdout)
    assert summary["status"] == "slip"
    assert summary["first_slip"]["time"] == 0.0
    assert "starts to slip" in result.stderr


def load_system_text() -> str:
    from rollspring.model import preset_path

    return preset_path("hoop-cylinder").read_text()


@pytest.mark.parametrize("failing_call", range(1, 7))
def test_a_write_interrupted_in_its_swap_leaves_a_whole_set(
    tmp_path, monkeypatch, failing_call
) -> None:
    """The three files are one set: interrupted at any rename (the earlier set moving out, the
    new one moving in), the new set is already whole and marked in its staging folder, so the
    swap is finished before the interruption goes on: the folder holds the new run's three
    files and nothing else (no temporary file, no staging folder). A kill that no handler sees
    is tests/test_write_faults.py's."""
    trajectory = simulate(load_system("hoop-cylinder"), 0.5, n_output=11)
    write_trajectory(trajectory, tmp_path)
    before = {p.name: p.read_bytes() for p in tmp_path.iterdir()}

    real_replace = output_files.os.replace
    calls = []

    def failing_replace(source, target):
        calls.append(target)
        if len(calls) == failing_call:  # killed between two renames
            raise KeyboardInterrupt
        real_replace(source, target)

    monkeypatch.setattr(output_files.os, "replace", failing_replace)
    longer = simulate(load_system("hoop-cylinder"), 1.0, n_output=21)
    with pytest.raises(KeyboardInterrupt):
        write_trajectory(longer, tmp_path)
    after = {p.name: p.read_bytes() for p in tmp_path.iterdir()}
    monkeypatch.undo()
    fresh = tmp_path / "fresh"
    write_trajectory(longer, fresh)
    assert after == {p.name: p.read_bytes() for p in fresh.iterdir()} != before


def test_a_writer_that_fails_leaves_the_earlier_set_and_no_staging(tmp_path, monkeypatch) -> None:
    trajectory = simulate(load_system("hoop-cylinder"), 0.5, n_output=11)
    write_trajectory(trajectory, tmp_path)
    before = {p.name: p.read_bytes() for p in tmp_path.iterdir()}
    import rollspring.outputs.trajectory as writer

    def broken(*args, **kwargs):
        raise KeyboardInterrupt

    monkeypatch.setattr(writer.np, "savez_compressed", broken)
    with pytest.raises(KeyboardInterrupt):
        write_trajectory(simulate(load_system("hoop-cylinder"), 1.0, n_output=21), tmp_path)
    assert {p.name: p.read_bytes() for p in tmp_path.iterdir()} == before
    # a folder that did not exist is not created at all
    with pytest.raises(KeyboardInterrupt):
        write_trajectory(trajectory, tmp_path / "new")
    assert sorted(p.name for p in tmp_path.iterdir()) == sorted(before)


def test_leftovers_of_a_killed_run_are_removed_by_the_next(tmp_path) -> None:
    """SIGKILL leaves what no handler can remove: a staging folder, a parked set, a temporary
    file of an older rollspring; the next run into the folder removes them (never those of a
    process that still runs)."""
    import subprocess
    import sys

    dead = subprocess.run(
        [sys.executable, "-c", "import os; print(os.getpid())"],
        capture_output=True,
        text=True,
        check=True,
    )
    pid = int(dead.stdout)
    (tmp_path / f".rollspring-part-{pid}-abc").mkdir()
    (tmp_path / f".rollspring-part-{pid}-abc" / "trajectory.csv").write_text("half")
    (tmp_path / f".rollspring-old-{pid}-def").mkdir()
    (tmp_path / ".trajectory.csv.k2j3h4.part").write_text("half")  # no pid: an older version
    (tmp_path / "trajectory.csv").write_text("t\n0\n")  # an earlier run's lone file
    alive = tmp_path / f".rollspring-part-{os.getpid()}-ghi"
    alive.mkdir()
    write_trajectory(simulate(load_system("hoop-cylinder"), 0.5, n_output=11), tmp_path)
    assert sorted(p.name for p in tmp_path.iterdir()) == sorted(
        ["summary.json", "trajectory.csv", "trajectory.npz", alive.name]
    )


@pytest.mark.parametrize("where", ["under-a-file", "a-file", "proc"])
def test_an_unwritable_out_fails_at_once_before_the_run(tmp_path, monkeypatch, where) -> None:
    """--out into a place that cannot be written is a one-line error (exit 2) before any
    computation: the simulation is never started (it would fail here if it were). /proc refuses
    new folders to every user, root included (a read-only folder would not stop root)."""
    import rollspring.service.runs as runs

    blocker = tmp_path / "a-file"
    blocker.write_text("not a directory")
    if where == "under-a-file":
        out = blocker / "run"
    elif where == "a-file":
        out = blocker
    else:
        out = Path("/proc/rollspring-test-run")

    def never(*args, **kwargs):
        raise AssertionError("the simulation started before --out was checked")

    monkeypatch.setattr(runs, "run_simulation", never)
    result = run("simulate", "hoop-cylinder", "--duration", "600", "--out", str(out))
    assert result.exit_code == 2, result.output
    assert result.stderr.startswith(f"error: --out {out}: cannot write there (")
    assert len(result.stderr.strip().splitlines()) == 1
    assert sorted(p.name for p in tmp_path.iterdir()) == ["a-file"]  # nothing created
    assert not Path("/proc/rollspring-test-run").exists()


@pytest.mark.parametrize(
    "args", [["report", "hoop-cylinder"], ["animate", "hoop-cylinder", "-T", "1"]]
)
def test_report_and_animate_check_their_out_before_the_work(tmp_path, args) -> None:
    blocker = tmp_path / "a-file"
    blocker.write_text("not a directory")
    out = blocker / ("x.html" if args[0] == "report" else "x.gif")
    result = run(*args, "--out", str(out))
    assert result.exit_code == 2, result.output
    assert result.stderr == (
        f"error: --out {out}: cannot write there ({blocker} is not a directory)\n"
    )

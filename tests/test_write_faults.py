"""Crash-proof writes, proven by fault injection (issue 24, point 4).

A writer process is killed (``os._exit``, as SIGKILL: no handler, no ``finally``) just before
its k-th file operation, for every k until the write completes; then the next writer's recovery
(:func:`rollspring.outputs.atomic.remove_leftovers`, which every write runs first) is run, and
the folder must hold a complete set, the earlier one or the new one, never a mix, a partial set
or nothing, and no leftovers. The recovery itself is killed too, at each of its operations, and
recovered again.
"""

from __future__ import annotations

import subprocess
import sys
import textwrap
from pathlib import Path

import pytest

from rollspring.outputs import atomic
from rollspring.outputs.atomic import remove_leftovers

NAMES = ("trajectory.csv", "trajectory.npz", "summary.json")
OLD = {name: f"old {name}\n" for name in NAMES}
NEW = {name: f"new {name}\n" for name in NAMES}
_NAMES = ",".join(NAMES)

#: The writer, killed before its k-th file operation (every os call that touches the disk, and
#: every open): a subprocess, so that nothing of it runs after the kill.
_WRITER = textwrap.dedent(
    """
    import builtins, importlib.util, os, sys
    from pathlib import Path

    target, kill_at, job, source = Path(sys.argv[1]), int(sys.argv[2]), sys.argv[3], sys.argv[4]
    names = tuple(sys.argv[5].split(","))
    # the module alone (the outputs package would bring its renderers: 0.4 s a process)
    spec = importlib.util.spec_from_file_location("atomic_under_test", source)
    atomic = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(atomic)

    count = [0]

    def killed_before(function):
        def wrapped(*args, **kwargs):
            count[0] += 1
            if count[0] == kill_at:
                os._exit(9)
            return function(*args, **kwargs)
        return wrapped

    for name in ("replace", "rename", "unlink", "remove", "mkdir", "rmdir", "fsync", "chmod",
                 "open", "listdir", "scandir"):
        setattr(os, name, killed_before(getattr(os, name)))
    builtins.open = killed_before(builtins.open)
    if job == "write":
        atomic.write_file_set(
            target, {name: (lambda p, n=name: p.write_text("new " + n + "\\n")) for name in names}
        )
    else:
        atomic.remove_leftovers(target, names)
    print("done")
    """
)


def _run(target: Path, kill_at: int, job: str) -> bool:
    """Run the writer (``job`` "write") or a recovery ("recover") killed before operation
    ``kill_at``; whether it ran to the end."""
    done = subprocess.run(
        [sys.executable, "-c", _WRITER, str(target), str(kill_at), job, atomic.__file__, _NAMES],
        capture_output=True,
        text=True,
        timeout=120,
    )
    assert done.returncode in (0, 9), done.stderr
    return done.stdout == "done\n"


def _contents(folder: Path) -> dict[str, str] | None:
    """The folder's files and their text (None: the folder does not exist)."""
    if not folder.exists():
        return None
    return {path.name: path.read_text() for path in folder.iterdir()}


def _old_set(folder: Path) -> None:
    folder.mkdir()
    for name, text in OLD.items():
        (folder / name).write_text(text)


@pytest.mark.parametrize("existing", [True, False], ids=["replaces-a-set", "new-folder"])
def test_a_kill_at_any_file_operation_leaves_a_complete_old_or_new_set(
    tmp_path: Path, existing: bool
) -> None:
    earlier = OLD if existing else None
    kill_at, outcomes = 1, set()
    while True:
        case = tmp_path / f"kill-{kill_at}"
        case.mkdir()
        target = case / "run"
        if existing:
            _old_set(target)
        finished = _run(target, kill_at, "write")
        # the next writer's recovery: in the target folder, and beside it (a new folder is staged
        # beside its place)
        remove_leftovers(case, ("run",))
        if target.exists():
            remove_leftovers(target, NAMES)
        after = _contents(target)
        assert after in (earlier, NEW), (kill_at, after)
        assert sorted(p.name for p in case.iterdir()) == (["run"] if after else []), kill_at
        outcomes.add("new" if after == NEW else "old")
        if finished:
            assert after == NEW
            break
        kill_at += 1
    assert kill_at > 10  # every operation of the write was a kill point
    assert outcomes == {"old", "new"}  # early kills keep the earlier set, late ones the new


def test_a_kill_during_the_recovery_is_recovered_by_the_next(tmp_path: Path) -> None:
    """Kill the writer at each point of its swap, then kill the recovery at each of its own
    points: a further recovery still finds a complete set."""
    checked = 0
    kill_at = 1
    while True:
        base = tmp_path / f"write-{kill_at}"
        base.mkdir()
        target = base / "run"
        _old_set(target)
        if _run(target, kill_at, "write"):
            break
        recover_at = 1
        while True:
            case = tmp_path / f"write-{kill_at}-recover-{recover_at}"
            subprocess.run(["cp", "-a", str(target), str(case)], check=True)
            finished = _run(case, recover_at, "recover")
            remove_leftovers(case, NAMES)
            assert _contents(case) in (OLD, NEW), (kill_at, recover_at, _contents(case))
            checked += 1
            if finished:
                break
            recover_at += 1
        kill_at += 1
    assert checked > 20

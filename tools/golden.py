"""Golden outputs: record what the command line prints and writes, and compare two records.

The redesign of issue 23 moves code, never results: this script records, with the rollspring
package of the Python that runs it (or the command ``--rollspring``), ``analyze --json``,
``simulate --json`` and its written trajectory for every preset, ``paper-check --json``,
``derive`` LaTeX for three presets and the analysis of a 1000-body chain, then compares two
records byte for byte (``.npz`` archives array by array: a zip stores its members' dates; the
paper check's JSON without the claims' ``key`` fields, which the redesign added).

    .venv/bin/python tools/golden.py record build/golden/after
    .venv/bin/python tools/golden.py compare build/golden/before build/golden/after
    .venv/bin/python tools/golden.py against REV   # records REV (a git worktree) and the checkout

Exit code 0 when the two records are identical, 1 with the differing files listed otherwise.
"""

from __future__ import annotations

import argparse
import filecmp
import json
import os
import shutil
import subprocess
import sys
import tempfile
from pathlib import Path

import numpy as np

PRESETS = (
    "two-masses",
    "hoop-cylinder",
    "frictionless",
    "two-hoops",
    "two-cylinders",
    "wall-hoop-cylinder",
    "three-bodies",
    "chain-monatomic",
    "chain-diatomic",
)
DERIVED = ("two-masses", "hoop-cylinder", "frictionless")


def _run(cli: list[str], args: list[str], out: Path | None, cwd: Path, env: dict[str, str]) -> None:
    done = subprocess.run([*cli, *args], cwd=cwd, env=env, capture_output=True, check=False)
    if done.returncode != 0:
        sys.exit(
            f"golden: {' '.join(args)} failed ({done.returncode}): {done.stderr.decode()[-400:]}"
        )
    if out is not None:
        out.parent.mkdir(parents=True, exist_ok=True)
        out.write_bytes(done.stdout)


def record(where: Path, cli: list[str], env: dict[str, str] | None = None) -> None:
    """Write every golden output below ``where`` (emptied first)."""
    env = dict(os.environ if env is None else env, NO_COLOR="1", COLUMNS="100")
    shutil.rmtree(where, ignore_errors=True)
    where.mkdir(parents=True)
    for preset in PRESETS:
        _run(cli, ["analyze", preset, "--json"], where / "analyze" / f"{preset}.json", where, env)
        _run(
            cli,
            ["simulate", preset, "--json", "-o", f"simulate/{preset}"],
            where / "simulate" / f"{preset}.json",
            where,
            env,
        )
    _run(cli, ["paper-check", "--json"], where / "paper-check.json", where, env)
    for preset in DERIVED:
        _run(cli, ["derive", preset, "-f", "latex"], where / "derive" / f"{preset}.tex", where, env)
    _run(
        cli,
        ["chain", "--n", "1000", "--pattern", "hoop,cylinder", "-o", "chain.toml"],
        None,
        where,
        env,
    )
    _run(cli, ["analyze", "chain.toml", "--json"], where / "chain-1000.json", where, env)


def compare(before: Path, after: Path) -> list[str]:
    """The relative paths whose content differs (or that only one record has)."""
    names_before = {p.relative_to(before) for p in before.rglob("*") if p.is_file()}
    names_after = {p.relative_to(after) for p in after.rglob("*") if p.is_file()}
    differ = sorted(str(p) + " (only one side)" for p in names_before ^ names_after)
    for name in sorted(names_before & names_after):
        a, b = before / name, after / name
        if name.name == "paper-check.json":  # the redesign adds each claim's stable key
            same = _without_keys(json.loads(a.read_text())) == _without_keys(
                json.loads(b.read_text())
            )
        elif name.suffix == ".npz":
            with np.load(a) as x, np.load(b) as y:
                same = sorted(x.files) == sorted(y.files) and all(
                    x[k].dtype == y[k].dtype and x[k].tobytes() == y[k].tobytes() for k in x.files
                )
        else:
            same = filecmp.cmp(a, b, shallow=False)
        if not same:
            differ.append(str(name))
    return differ


#: The rollspring command of the Python that runs this script (the package on its path).
_CLI = [sys.executable, "-c", "import sys; from rollspring.cli import main; sys.exit(main())"]


def _without_keys(document: object) -> object:
    """The paper check's JSON without the claims' ``key`` fields."""
    if isinstance(document, dict):
        return {k: _without_keys(v) for k, v in document.items() if k != "key"}
    if isinstance(document, list):
        return [_without_keys(v) for v in document]
    return document


def _report(differ: list[str]) -> int:
    if differ:
        print("golden outputs differ:\n  " + "\n  ".join(differ))
        return 1
    print("golden outputs identical")
    return 0


def main() -> int:
    parser = argparse.ArgumentParser(
        description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter
    )
    sub = parser.add_subparsers(dest="verb", required=True)
    rec = sub.add_parser("record")
    rec.add_argument("where", type=Path)
    rec.add_argument("--rollspring", help="a rollspring command (default: this Python's package)")
    cmp_ = sub.add_parser("compare")
    cmp_.add_argument("before", type=Path)
    cmp_.add_argument("after", type=Path)
    against = sub.add_parser("against")
    against.add_argument("rev")
    against.add_argument("--keep", type=Path, default=Path("build/golden"))
    args = parser.parse_args()
    if args.verb == "record":
        record(args.where.resolve(), [args.rollspring] if args.rollspring else _CLI)
        return 0
    if args.verb == "compare":
        return _report(compare(args.before, args.after))
    # against REV: the revision's source on PYTHONPATH ahead of the editable install
    top = Path(__file__).resolve().parents[1]
    keep = args.keep.resolve()
    with tempfile.TemporaryDirectory() as tmp:
        tree = Path(tmp) / "base"
        subprocess.run(
            ["git", "-C", str(top), "worktree", "add", "--detach", str(tree), args.rev], check=True
        )
        try:
            env = dict(os.environ, PYTHONPATH=str(tree / "src"))
            record(keep / "before", _CLI, env)
        finally:
            subprocess.run(
                ["git", "-C", str(top), "worktree", "remove", "--force", str(tree)], check=True
            )
    record(keep / "after", _CLI, dict(os.environ, PYTHONPATH=str(top / "src")))
    return _report(compare(keep / "before", keep / "after"))


if __name__ == "__main__":
    sys.exit(main())

"""The web page's pure JavaScript modules (URL state, geometry, playback arithmetic, plot series,
field parsing), unit-tested with Node's own test runner: ``node --test tests/js/``."""

from __future__ import annotations

import shutil
import subprocess
from pathlib import Path

import pytest

REPO = Path(__file__).resolve().parents[1]


def test_node_unit_tests_pass() -> None:
    node = shutil.which("node")
    if node is None:
        pytest.fail("node is not installed (the page's JavaScript tests need Node ≥ 20)")
    done = subprocess.run(
        [node, "--test", "tests/js/"], cwd=REPO, capture_output=True, text=True, timeout=120
    )
    assert done.returncode == 0, done.stdout + done.stderr
    assert "# fail 0" in done.stdout
    assert "# pass 0\n" not in done.stdout, "no JavaScript test ran"

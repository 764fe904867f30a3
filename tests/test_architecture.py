"""Architecture: data flows one way, and the public API is what it says."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import rollspring

ROOT = Path(__file__).resolve().parents[1]


def test_import_linter_contracts_are_kept() -> None:
    """model -> physics -> analysis -> interfaces; the core imports no CLI, web or plotting
    library (contracts in pyproject.toml)."""
    lint = Path(sys.executable).with_name("lint-imports")
    result = subprocess.run([str(lint), "--config", str(ROOT / "pyproject.toml")], cwd=ROOT,
                            capture_output=True, text=True, check=False)
    assert result.returncode == 0, result.stdout + result.stderr
    assert "0 broken" in result.stdout


def test_public_api_names_exist() -> None:
    for name in rollspring.__all__:
        assert hasattr(rollspring, name), name

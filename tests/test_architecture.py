"""Architecture: data flows one way, and the public API is what it says."""

from __future__ import annotations

import ast
import subprocess
import sys
from pathlib import Path

import rollspring
from tests.code_reading import called_name

ROOT = Path(__file__).resolve().parents[1]


#: What computes results: the orchestration layer (rollspring.service) calls these, never outputs.
COMPUTATIONS = {
    "analyze",
    "simulate",
    "simulate_batch",
    "derive",
    "check_paper",
    "find_equilibrium",
    "normal_modes",
}


def test_import_linter_contracts_are_kept() -> None:
    """model -> physics -> analysis -> simulate -> lab -> outputs -> service -> interfaces; the core
    imports no CLI, web or plotting library (contracts in pyproject.toml)."""
    lint = Path(sys.executable).with_name("lint-imports")
    result = subprocess.run(
        [str(lint), "--config", str(ROOT / "pyproject.toml")],
        cwd=ROOT,
        capture_output=True,
        text=True,
        check=False,
    )
    assert result.returncode == 0, result.stdout + result.stderr
    assert "0 broken" in result.stdout


def test_public_api_names_exist() -> None:
    for name in rollspring.__all__:
        assert hasattr(rollspring, name), name


def test_outputs_render_results_and_interfaces_orchestrate() -> None:
    """No module of rollspring.outputs calls a computation (analyze, simulate, derive, ...), by
    name or as an attribute (``rollspring.analyze(...)``, ``paper_check.check_paper()``);
    importing their result types (LinearAnalysis, Trajectory, Derivation) is fine."""
    outputs = ROOT / "src" / "rollspring" / "outputs"
    modules = sorted(outputs.rglob("*.py"))
    assert len(modules) > 5
    calls = []
    for path in modules:
        for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"), str(path))):
            if not isinstance(node, ast.Call):
                continue
            name = called_name(node)
            if name in COMPUTATIONS:
                calls.append(f"{path.relative_to(ROOT)}:{node.lineno}: {name}()")
    assert not calls, "outputs must only render what rollspring.service computed:\n" + "\n".join(
        calls
    )

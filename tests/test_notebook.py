"""The examples notebook (``examples/paper.ipynb``) runs top to bottom in a fresh kernel of this
interpreter, its asserts (the paper's closed forms) hold, and its printed numbers are the paper's.

The kernel spec is written into a temporary Jupyter path and points at ``sys.executable``, so the
notebook runs on the venv that runs the tests, whatever kernels the machine has.
"""

from __future__ import annotations

import math
import sys
from pathlib import Path

import nbformat
import pytest
from ipykernel.kernelspec import install
from nbclient import NotebookClient

NOTEBOOK = Path(__file__).resolve().parents[1] / "examples" / "paper.ipynb"
KERNEL = "rollspring-tests"


@pytest.fixture(scope="module")
def executed(tmp_path_factory: pytest.TempPathFactory) -> nbformat.NotebookNode:
    folder = tmp_path_factory.mktemp("notebook")
    install(kernel_name=KERNEL, prefix=str(folder))
    spec = folder / "share" / "jupyter" / "kernels" / KERNEL / "kernel.json"
    assert sys.executable in spec.read_text()
    with pytest.MonkeyPatch.context() as patch:
        patch.setenv("JUPYTER_PATH", str(folder / "share" / "jupyter"))
        patch.setenv("JUPYTER_PLATFORM_DIRS", "1")
        patch.delenv("MPLBACKEND", raising=False)  # the kernel then draws inline
        notebook = nbformat.read(NOTEBOOK, as_version=4)
        client = NotebookClient(
            notebook, kernel_name=KERNEL, timeout=300, resources={"metadata": {"path": str(folder)}}
        )
        client.execute()
    return notebook


def test_the_notebook_is_committed_without_outputs() -> None:
    notebook = nbformat.read(NOTEBOOK, as_version=4)
    nbformat.validate(notebook)
    code = [cell for cell in notebook.cells if cell.cell_type == "code"]
    assert len(code) >= 7
    for cell in code:
        assert cell.outputs == [] and cell.execution_count is None
    assert "import rollspring" in code[0].source


def test_every_cell_runs_without_error(executed: nbformat.NotebookNode) -> None:
    code = [cell for cell in executed.cells if cell.cell_type == "code"]
    for number, cell in enumerate(code, 1):
        assert cell.execution_count == number
        assert not [o for o in cell.outputs if o.output_type == "error"], cell.source[:80]
    images = [o for cell in code for o in cell.outputs if "image/png" in o.get("data", {})]
    assert len(images) == 1  # the simulation against the linear solution


def test_the_printed_numbers_are_the_papers(executed: nbformat.NotebookNode) -> None:
    text = "\n".join(
        o.text
        for cell in executed.cells
        if cell.cell_type == "code"
        for o in cell.outputs
        if o.output_type == "stream"
    )
    k, m1, m2, amplitude = 100.0, 1.0, 1.0, 0.01  # the preset, as the paper's Fig. 2
    omega2 = k / (2 * m1) + 2 * k / (3 * m2)  # eq. (QQQ1)
    assert f"Omega^2 = {omega2:.6f} 1/s^2;  paper (QQQ1): {omega2:.6f} 1/s^2" in text
    assert f"Omega   = {math.sqrt(omega2):.6f} rad/s" in text
    assert "f1/f2 = -1.500000 (signed), |f1/f2| = 1.500000" in text
    total = 2 * m1 + 1.5 * m2  # paper eq. (c): I'_1, I'_2 over R^2
    assert f"(paper: {2 * m1 / total:.6f}, {1.5 * m2 / total:.6f})" in text
    assert f"(A/14 = {amplitude / 14:.6g} m)" in text
    assert f"Omega^2 = {2 * k / m1 + 3 * k / (2 * m2):.6f} (paper: " in text  # Fig. 3, App. B
    assert "slip - 'hoop' starts to slip at t = 0 s" in text
    assert "finished:" in text and "first slip: None" in text
    assert (
        "5 method(s) applied (newton, conservation, lagrange, natural-frequencies, "
        "hamilton); all methods agree." in text
    )

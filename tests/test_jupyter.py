"""Notebook display: rich HTML/LaTeX for systems, modes and trajectories, the inline animation,
pandas and xarray, and a real notebook run in a kernel (nbclient)."""

from __future__ import annotations

import base64
import math
import re
import types

import nbformat
import numpy as np
import pytest
from IPython.core.formatters import DisplayFormatter
from IPython.display import HTML
from nbclient import NotebookClient

from rollspring.analysis import analyze
from rollspring.model import load_system
from rollspring.outputs import jupyter
from rollspring.simulate import simulate


@pytest.fixture(scope="module")
def paper():
    system = load_system("hoop-cylinder")
    return system, analyze(system), simulate(system, 1.0, n_output=201)


@pytest.fixture()
def shell():
    """A stand-in for the IPython shell: real display formatters, no kernel."""
    shell = types.SimpleNamespace(display_formatter=DisplayFormatter())
    assert jupyter.register_formatters(shell) is True
    return shell


def _png_images(markup: str) -> list[bytes]:
    return [
        base64.b64decode(data)
        for data in re.findall(r'src="data:image/png;base64,([A-Za-z0-9+/=]+)"', markup)
    ]


def test_system_renders_as_a_diagram_and_tables(paper, shell) -> None:
    system, _, _ = paper
    bundle, _ = shell.display_formatter.format(system)
    markup = bundle["text/html"]
    images = _png_images(markup)
    assert len(images) == 1 and images[0][:4] == b"\x89PNG"
    assert markup.count("<table") == 2  # bodies, springs
    assert ">hoop<" in markup and ">cylinder<" in markup and ">0.49<" in markup
    assert "Hoop and cylinder joined at their centres" in markup


def test_modes_render_with_the_papers_frequency_and_math(paper, shell) -> None:
    _, analysis, _ = paper
    bundle, _ = shell.display_formatter.format(analysis)
    markup = bundle["text/html"]
    omega = math.sqrt(100 / (2 * 1.0) + 2 * 100 / (3 * 1.0))  # paper eq. (QQQ1)
    assert f">{omega:.8g}<" in markup
    assert "0.571429·x<sub>hoop</sub> + 0.428571·x<sub>cylinder</sub>" in markup  # eq. (c)
    assert "not the centre of mass" in markup
    assert len(_png_images(markup)) == 1
    latex = bundle["text/latex"]
    # M = diag(2 m1 R^2, 3/2 m2 R^2) (paper's I'1, I'2), K = k R^2 [[1, -1], [-1, 1]]
    assert r"M = \begin{pmatrix}0.02 & 0 \\ 0 & 0.015\end{pmatrix}" in latex
    assert r"K = \begin{pmatrix}1 & -1 \\ -1 & 1\end{pmatrix}" in latex
    assert latex.startswith("$$") and latex.endswith("$$")


def test_a_mode_renders_alone(paper, shell) -> None:
    _, analysis, _ = paper
    markup = shell.display_formatter.format(analysis.modes[1])[0]["text/html"]
    assert "oscillating mode" in markup and f"{2 * math.pi / analysis.modes[1].omega:.6g}" in markup


def test_trajectory_renders_its_summary_and_a_plot(paper, shell) -> None:
    _, _, trajectory = paper
    markup = shell.display_formatter.format(trajectory)[0]["text/html"]
    assert "finished" in markup and "first slip" in markup
    assert f"{trajectory.summary['period_measured']:.12g}" in markup
    assert len(_png_images(markup)) == 1


def test_without_ipython_nothing_is_registered() -> None:
    assert jupyter.register_formatters() is False  # no IPython shell runs under pytest


def test_inline_animation_is_an_html_object(paper) -> None:
    _, _, trajectory = paper
    shown = jupyter.animate_inline(trajectory, duration=0.2, fps=10, dpi=30)
    assert isinstance(shown, HTML)
    assert shown.data.count("data:image/png;base64,") == 3 and "<script" in shown.data


def test_to_pandas(paper) -> None:
    _, _, trajectory = paper
    frame = jupyter.trajectory_to_pandas(trajectory)
    np.testing.assert_array_equal(frame.index.to_numpy(), trajectory.t)
    assert frame.index.name == "t"
    np.testing.assert_array_equal(frame["cylinder.x"].to_numpy(), trajectory.x[:, 1])
    np.testing.assert_array_equal(
        frame["hoop-cylinder.tension"].to_numpy(), trajectory.spring_tension[:, 0]
    )
    assert frame["hoop.slipping"].dtype == bool
    assert frame.attrs["units"]["hoop.friction"] == "N" and frame.attrs["units"]["t"] == "s"
    assert len(frame.columns) == len(trajectory.columns()) - 1


def test_to_xarray(paper) -> None:
    _, _, trajectory = paper
    data = jupyter.trajectory_to_xarray(trajectory)
    assert dict(data.sizes) == {"time": trajectory.t.size, "body": 2, "spring": 1}
    np.testing.assert_array_equal(data["phi"].sel(body="cylinder").to_numpy(), trajectory.phi[:, 1])
    np.testing.assert_array_equal(data["stationary_x"].to_numpy(), trajectory.stationary_x)
    assert data["normal"].attrs["units"] == "N" and data["time"].attrs["units"] == "s"
    assert list(data["shape"].to_numpy()) == ["hoop", "cylinder"]


def test_a_notebook_shows_rich_output(tmp_path) -> None:
    """A real kernel: after register_formatters() the objects display as HTML."""
    notebook = nbformat.v4.new_notebook()
    notebook.cells = [
        nbformat.v4.new_code_cell(
            "import rollspring\n"
            "from rollspring.outputs.jupyter import register_formatters\n"
            "print(register_formatters())\n"
            "system = rollspring.load_system('two-hoops')"
        ),
        nbformat.v4.new_code_cell("system"),
        nbformat.v4.new_code_cell("rollspring.analyze(system)"),
    ]
    NotebookClient(
        notebook,
        timeout=120,
        kernel_name="python3",
        resources={"metadata": {"path": str(tmp_path)}},
    ).execute()
    first, shown, modes = (cell.outputs for cell in notebook.cells)
    assert first[0]["text"].strip() == "True"
    assert "<img" in shown[0]["data"]["text/html"] and ">hoop2<" in shown[0]["data"]["text/html"]
    assert "(the centre of mass)" in modes[0]["data"]["text/html"]  # two hoops: X-hat is the CM
    assert r"\begin{pmatrix}" in modes[0]["data"]["text/latex"]

"""The README tells the truth: its results table and examples are what the software computes."""

from __future__ import annotations

import importlib.util
import json
import math
import re
from pathlib import Path

import numpy as np
import pytest
from typer.testing import CliRunner

from rollspring import analyze, load_system
from rollspring.cli import app

README = (Path(__file__).resolve().parents[1] / "README.md").read_text()


def g(value: float) -> str:
    return f"{value:.6g}"


def test_results_table_numbers_come_from_the_software() -> None:
    result = analyze(load_system("hoop-cylinder"))
    mode = result.oscillating[0]
    assert result.spring_split is not None
    numbers = [
        mode.eigenvalue,
        mode.omega,
        *result.stationary_weights,
        *result.amplitude,
        *result.velocity_amplitude,
        result.cm_amplitude,
        *result.spring_split["k"],
        *result.spring_split["clamped_omega"],
        *result.friction_amplitude,
        *result.required_mu,
        mode.friction[0] / mode.friction[1],
    ]
    for value in numbers:
        assert g(float(value)) in README, g(float(value))
    fig3 = analyze(load_system("frictionless"))
    assert g(fig3.oscillating[0].eigenvalue) in README
    # the paper's R1 = R2/2 geometry of Fig. 3: ends at 0.1 m and 0.15 m, 0.5 m apart
    assert f"{math.degrees(math.atan2(0.05, 0.5)):.3g}°" in README


def test_cli_tour_lines_are_real_output() -> None:
    analysed = CliRunner().invoke(app, ["analyze"]).stdout
    simulated = CliRunner().invoke(app, ["simulate", "-T", "10", "--rtol", "1e-10"]).stdout
    analyze_part, simulate_part = README.split("## Simulation", 1)
    checked = 0
    for part, out in ((analyze_part, analysed), (simulate_part.split("```", 2)[1], simulated)):
        for line in part.splitlines():
            if line.startswith(
                (
                    "│ 2        │",
                    "│ hoop     │",
                    "│ cylinder │",
                    "CM amplitude",
                    "Stationary point X̂",
                    "Spring split",
                    "│ status",
                    "│ period",
                    "│ integrator",
                    "│ energy",
                )
            ):
                assert line in out, line
                checked += 1
    assert checked >= 12


def test_error_example_is_real(tmp_path: Path) -> None:
    bad = tmp_path / "bad.toml"
    good = (Path(__file__).resolve().parents[1] / "examples" / "hoop-cylinder.toml").read_text()
    bad.write_text(
        good.replace("mass = 1.0\nradius = 0.1\nx = 0.49", "mass = -1.0\nradius = 0.1\nx = 0.49")
    )
    result = CliRunner().invoke(app, ["analyze", str(bad)])
    assert result.exit_code == 2
    expected = "bodies[1].mass: must be between 1e-06 and 1e+06 kg, the verified range (got -1.0)"
    assert expected in result.stderr and expected in README


def test_python_example_values() -> None:
    result = analyze(load_system("hoop-cylinder"))
    np.testing.assert_allclose(result.stationary_weights, [4 / 7, 3 / 7], rtol=1e-12)


def _walkthrough():
    spec = importlib.util.spec_from_file_location(
        "lab_walkthrough", Path(__file__).resolve().parents[1] / "tools" / "lab_walkthrough.py"
    )
    assert spec is not None and spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


_NUMBER = re.compile(r"[-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?")


def _same_output(shown: str, printed: str) -> bool:
    """``printed`` is the line ``shown`` up to the last bits of its numbers: the same text
    around them and each number within 1e-5 relative (or 1e-9 absolute: an uncertainty at the
    level of rounding). OpenCV and the BLAS take other SIMD paths on other CPUs (AVX-512 or
    AVX2), which changes the last bits of a track, a fitted value's eighth digit, its
    uncertainty's sixth (0.0040479735 and 0.0040479789 N/m), and noise-level uncertainties
    more (a ratio fitted to 1.5 "± 7e-13" on one machine, "± 4e-10" on another)."""
    if _NUMBER.sub("#", shown) != _NUMBER.sub("#", printed):
        return False
    pairs = zip(_NUMBER.findall(shown), _NUMBER.findall(printed), strict=True)
    return all(math.isclose(float(a), float(b), rel_tol=1e-5, abs_tol=1e-9) for a, b in pairs)


def test_the_walkthrough_comparison_takes_last_bits_not_other_numbers() -> None:
    assert _same_output(
        '"circle_rms": 0.00015502396635246835,', '"circle_rms": 0.00015502396635246832,'
    )
    assert _same_output(
        "friction_ratio: 1.50000000000000 ± 0.00000000000072",
        "friction_ratio: 1.50000000000 ± 0.00000000036",
    )
    assert not _same_output('"value": 129.99335506624166,', '"value": 129.9894,')
    assert not _same_output('"circle_rms": 0.000155,', '"height_rms": 0.000155,')
    assert not _same_output("0,0,-0.0017,0.48", "0,0,-0.0017,0.48,1")


@pytest.mark.slow
def test_lab_walkthrough_is_real_output(tmp_path: Path) -> None:
    """The "Lab" section shows what its commands print (tools/lab_walkthrough.py runs them):
    every output line of its walk-through, the hand-marked fits and the comparisons with the
    truth, on the textured wall and on the plain one, its numbers to their last bits on another
    CPU (:func:`_same_output`). The tracking's speed (``frames_per_second``) is the one line
    that differs."""
    pytest.importorskip("cv2")
    section = README.split("## The lab:", 1)[1].split("\n## ", 1)[0]
    walkthrough = section.split("### The files", 1)[0]
    lab = _walkthrough()
    out = lab.walk(tmp_path)
    printed = {line.strip() for text in out.values() for line in text.splitlines()}
    printed |= set((tmp_path / "tracks.csv").read_text().splitlines())
    checked = 0
    for block in walkthrough.split("```text\n")[1:]:
        for line in block.split("```", 1)[0].splitlines():
            shown = line.strip()
            if shown.startswith(("$", "--", "…", '"frames_per_second"', "wrote ")) or not shown:
                continue
            assert shown in printed or any(_same_output(shown, p) for p in printed), line
            checked += 1
    assert checked >= 60
    section = " ".join(section.split())  # the prose, its lines joined
    assert "129.9894 ± 0.0085" in out["fit hoop.txt"] and "129.9894 ± 0.0085" in section
    assert "129.9947 ± 0.0060" in out["fit both.txt"] and "129.9947 ± 0.0060" in section
    plain = lab.plain_wall(tmp_path / "plain")
    walls = section.split("**The wall behind the bodies.**", 1)[1].split("**The report.**", 1)[0]
    for tracks, fit, where in (
        (tmp_path / "tracks.csv", out["fit"], section),
        (tmp_path / "plain" / "tracks.csv", plain["fit"], walls),
    ):
        for line in lab.tracking_errors(tracks):
            for number in re.findall(r"\d\.\d{3,4}", line):
                assert number in where, (line, number)
        for line in lab.against_truth(fit):
            off = re.search(r"([+-]\d+\.\d) standard errors", line)
            assert off is not None
            assert f"{off.group(1).replace('-', '−')} standard errors" in where, line
        fitted = json.loads(fit)
        assert not fitted["warnings"]
        k, c = (fitted["parameters"][f"springs.0.{name}"] for name in ("stiffness", "damping"))
        shown = [f"{k['value']:.4f} ± {k['stderr']:.4f} N/m"]
        shown.append(f"{c['value']:.5f} ± {c['stderr']:.5f} N s/m")
        for name in ("cm_peak_to_peak", "stationary_peak_to_peak"):
            claim = fitted["claims"][name]
            shown.append(f"{1e3 * claim['value']:.4f} ± {1e3 * claim['stderr']:.4f} mm")
        for number in shown:
            assert number in walls, number

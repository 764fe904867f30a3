"""The report's lab section (``rollspring report SYSTEM --data tracks.csv``, issue 27): the data
over the fitted model, the fitted values and the paper's claims measured."""

from __future__ import annotations

from pathlib import Path

from typer.testing import CliRunner

from rollspring.cli import app
from rollspring.model import system_from_dict
from rollspring.service.documents import build_report
from tests.fit_data import Truth, recording, write_csv

TRUTH = Truth(c=0.2, x2=0.47)


def test_the_report_shows_the_fitted_recording(tmp_path: Path) -> None:
    t, x, phi = recording(TRUTH, duration=3.0, fps=30, seed=4)
    data = write_csv(tmp_path / "tracks.csv", t, x, phi)
    report = build_report(
        system_from_dict(TRUTH.system(k=80.0, c=0.0)), duration=1.0, derivation=False, data=data
    )
    assert "lab" in report.sections
    page = report.html
    for piece in ('id="lab-figure"', 'id="lab-values"', 'id="lab-claims"', "springs.0.stiffness"):
        assert piece in page
    assert "the frictions&#x27; amplitude ratio" in page or "the frictions' amplitude ratio" in page
    assert "hoop rolled" in page


def test_a_bad_recording_is_refused_before_the_report(tmp_path: Path) -> None:
    data = tmp_path / "tracks.csv"
    data.write_text("t,x_wheel\n0,0\n0.1,0\n")
    result = CliRunner().invoke(
        app, ["report", "hoop-cylinder", "--data", str(data), "-o", str(tmp_path / "r.html")]
    )
    assert result.exit_code == 2
    assert result.stderr == (
        f"error: {data}: column 'x_wheel': no body 'wheel' in the system (bodies: hoop, "
        "cylinder); match it with --map wheel=BODY\n"
    )
    assert not (tmp_path / "r.html").exists()

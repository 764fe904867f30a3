"""The report page: its numbers are rollspring.analyze's (and the paper's), it is self-contained,
it is written atomically, and the CLI reports bad options in one line with exit code 2.

The page is parsed with the standard library's HTML parser; numbers are read back from the
``data-value`` attribute every numeric cell carries (the full float), so comparisons are exact.
The browser side (rendering, console, requests, the player, PDF) is ``test_report_browser.py``.
"""

from __future__ import annotations

import html
import json
import math
import os
import re
import shutil
import subprocess
from html.parser import HTMLParser
from pathlib import Path

import numpy as np
import pytest
from typer.testing import CliRunner

from rollspring import analyze, load_system, system_from_dict
from rollspring.analysis import paper as paper_check
from rollspring.analysis.paper import paper_figure
from rollspring.cli import app
from rollspring.model import preset_names
from rollspring.outputs import atomic as files
from rollspring.outputs.report import (
    CHROMIUM_ENV,
    MathConversionError,
    Report,
    ReportError,
    animation_data,
    find_chromium,
    latex_to_mathml,
    write_report,
)
from rollspring.outputs.report import _assets as report_assets
from rollspring.service.documents import build_report
from tests.conftest import body, make_system, spring

MATHML = "http://www.w3.org/1998/Math/MathML"
SVG = "http://www.w3.org/2000/svg"
runner = CliRunner()


class Page(HTMLParser):
    """Tables by id (rows of ``(text, data-value)`` cells), every src/href, scripts by id."""

    def __init__(self, text: str) -> None:
        super().__init__(convert_charrefs=True)
        self.tables: dict[str, list[list[tuple[str, float | None]]]] = {}
        self.links: list[str] = []
        self.scripts: dict[str, str] = {}
        self.ids: set[str] = set()
        self.math_elements = 0
        self.meta: list[dict[str, str | None]] = []
        self._table: str | None = None
        self._row: list[tuple[str, float | None]] | None = None
        self._cell: list[str] | None = None
        self._value: float | None = None
        self._script: str | None = None
        self._script_text: list[str] = []
        self.feed(text)
        self.close()

    def handle_starttag(self, tag: str, attrs: list[tuple[str, str | None]]) -> None:
        a = dict(attrs)
        if a.get("id"):
            self.ids.add(a["id"] or "")
        for key in ("src", "href"):
            if a.get(key) is not None:
                self.links.append(a[key] or "")
        if tag == "meta":
            self.meta.append(a)
        if tag == "math":
            self.math_elements += 1
            assert a.get("xmlns") == MATHML
        if tag == "table":
            self._table = a.get("id") or f"anonymous-{len(self.tables)}"
            self.tables[self._table] = []
        elif tag == "tr" and self._table is not None:
            self._row = []
        elif tag in ("td", "th") and self._row is not None:
            self._cell = []
            self._value = float(a["data-value"]) if a.get("data-value") else None
        elif tag == "script":
            self._script = a.get("id") or ""
            self._script_text = []

    def handle_endtag(self, tag: str) -> None:
        if tag in ("td", "th") and self._cell is not None and self._row is not None:
            self._row.append(("".join(self._cell).strip(), self._value))
            self._cell = None
        elif tag == "tr" and self._row is not None and self._table is not None:
            self.tables[self._table].append(self._row)
            self._row = None
        elif tag == "table":
            self._table = None
        elif tag == "script" and self._script is not None:
            self.scripts[self._script] = "".join(self._script_text)
            self._script = None

    def handle_data(self, data: str) -> None:
        if self._cell is not None:
            self._cell.append(data)
        if self._script is not None:
            self._script_text.append(data)

    def column(self, table_id: str, header: str) -> dict[str, float | None]:
        """``{first cell of the row: value of the column}`` for the body rows of a table."""
        rows = self.tables[table_id]
        index = [text for text, _ in rows[0]].index(header)
        return {row[0][0]: row[index][1] for row in rows[1:]}


@pytest.fixture(scope="module")
def report() -> Report:
    return build_report(load_system("hoop-cylinder"))


@pytest.fixture(scope="module")
def page(report: Report) -> Page:
    return Page(report.html)


def paper_parameters() -> dict[str, float]:
    """The paper's Fig. 2 parameters, read from the preset file (not from the analysis)."""
    system = load_system("hoop-cylinder")
    hoop, cylinder = system.bodies
    spring_ = system.springs[0]
    assert spring_.rest_length is not None
    return {
        "m1": hoop.mass,
        "m2": cylinder.mass,
        "R": hoop.radius,
        "k": spring_.stiffness,
        "A": spring_.rest_length - (cylinder.x - hoop.x),
        "g": system.gravity,
    }


# -- the numbers --------------------------------------------------------------------------------


def test_modal_table_holds_analyze_frequencies_and_the_papers_omega(
    report: Report, page: Page
) -> None:
    analysis = analyze(report.system)
    rows = page.tables["modes"][1:]
    assert [row[1][0] for row in rows] == [m.kind for m in analysis.modes]
    assert [row[2][1] for row in rows] == [m.omega for m in analysis.modes]
    assert [row[5][1] for row in rows] == [m.eigenvalue for m in analysis.modes]
    p = paper_parameters()
    omega2 = rows[1][5][1]
    assert omega2 == pytest.approx(
        p["k"] / (2 * p["m1"]) + 2 * p["k"] / (3 * p["m2"]), rel=1e-12
    )  # paper eq. (QQQ1)
    assert rows[1][4][1] == pytest.approx(2 * math.pi / math.sqrt(omega2), rel=1e-12)
    assert rows[0][2][1] == 0.0  # the zero mode: X-hat moves freely


def test_mode_shapes_and_friction_ratio(report: Report, page: Page) -> None:
    analysis = analyze(report.system)
    mode = analysis.modes[1]
    assert page.column("mode-shapes", "x, mode 2") == dict(
        zip(("hoop", "cylinder"), mode.shape_x.tolist(), strict=True)
    )
    assert page.column("mode-shapes", "f (N), mode 2") == dict(
        zip(("hoop", "cylinder"), mode.friction.tolist(), strict=True)
    )
    p = paper_parameters()
    shape = page.column("mode-shapes", "x, mode 2")
    # amplitudes about X-hat: A1/A2 = 3 m2 / (4 m1), opposite directions (paper Sec. 4.2)
    assert shape["hoop"] / shape["cylinder"] == pytest.approx(
        -3 * p["m2"] / (4 * p["m1"]), rel=1e-12
    )
    ratio = re.search(r'id="friction-ratio" data-value="([^"]+)"', report.html)
    assert ratio is not None
    assert float(ratio.group(1)) == pytest.approx(-1.5, rel=1e-12)  # App. A: |f1/f2| = 3/2


def test_stationary_point_weights_are_analyze_and_the_papers(report: Report, page: Page) -> None:
    analysis = analyze(report.system)
    assert analysis.stationary_weights is not None
    weights = page.column("stationary-weights", "weight of X̂")
    assert list(weights.values()) == analysis.stationary_weights.tolist()
    p = paper_parameters()
    total = 2 * p["m1"] + 1.5 * p["m2"]  # paper eq. (c): I'_i / R^2
    assert weights["hoop"] == pytest.approx(2 * p["m1"] / total, rel=1e-12)
    assert weights["cylinder"] == pytest.approx(1.5 * p["m2"] / total, rel=1e-12)
    cm = page.column("stationary-weights", "weight of the CM")
    assert cm["hoop"] == pytest.approx(p["m1"] / (p["m1"] + p["m2"]))
    values = {row[0][0]: row[1] for row in page.tables["stationary-point-values"][1:]}
    assert values["X̂ is the centre of mass"][0] == "no"
    assert values["CM amplitude, linear (m)"][1] == analysis.cm_amplitude
    # CM amplitude m1 m2 A / ((m1 + m2)(4 m1 + 3 m2)) = A/14 (docs/physics.md 7.1)
    assert values["CM amplitude, linear (m)"][1] == pytest.approx(
        p["m1"] * p["m2"] * p["A"] / ((p["m1"] + p["m2"]) * (4 * p["m1"] + 3 * p["m2"])), rel=1e-9
    )
    assert values["X̂ range in the simulation (m)"][1] == pytest.approx(0.0, abs=1e-12)


def test_friction_table_is_analyze_and_the_papers_appendix_a(report: Report, page: Page) -> None:
    analysis = analyze(report.system)
    assert analysis.friction_amplitude is not None and analysis.required_mu is not None
    amplitude = page.column("friction", "|f| amplitude, linear (N)")
    needed = page.column("friction", "μ needed = max |f|/N, linear")
    simulated = page.column("friction", "max |f|/N, simulated")
    assert list(amplitude.values()) == analysis.friction_amplitude.tolist()
    assert list(needed.values()) == analysis.required_mu.tolist()
    assert simulated == {
        b: report.trajectory.summary["max_friction_ratio"][b] for b in ("hoop", "cylinder")
    }
    p = paper_parameters()
    force = p["k"] * p["A"]  # F = kA; friction F/2 on the hoop, F/3 on the cylinder (App. A)
    assert amplitude["hoop"] == pytest.approx(force / 2, rel=1e-9)
    assert amplitude["cylinder"] == pytest.approx(force / 3, rel=1e-9)
    assert needed["hoop"] == pytest.approx(force / 2 / (p["m1"] * p["g"]), rel=1e-9)
    assert simulated["hoop"] == pytest.approx(needed["hoop"], rel=1e-6)
    verdicts = [row[-1][0] for row in page.tables["friction"][1:]]
    assert verdicts == ["rolls", "rolls"]  # mu_s = 1 against 0.05


def test_parameter_and_split_tables(report: Report, page: Page) -> None:
    system = report.system
    assert page.column("bodies", "m (kg)") == {b.id: b.mass for b in system.bodies}
    assert page.column("bodies", "J = (1+γ)mR² (kg m²)") == {
        b.id: b.contact_inertia for b in system.bodies
    }
    assert page.column("springs", "k (N/m)") == {"hoop-cylinder": system.springs[0].stiffness}
    p = paper_parameters()
    split = page.column("spring-split", "k_i (N/m)")
    # paper eqs. (k1), (k2)
    assert split["hoop"] == pytest.approx(p["k"] * (3 * p["m2"] + 4 * p["m1"]) / (3 * p["m2"]))
    assert split["cylinder"] == pytest.approx(p["k"] * (3 * p["m2"] + 4 * p["m1"]) / (4 * p["m1"]))


def test_embedded_analysis_and_animation_data(report: Report, page: Page) -> None:
    assert json.loads(page.scripts["analysis-data"]) == json.loads(
        json.dumps(analyze(report.system).to_dict())
    )
    data = json.loads(page.scripts["animation-data"])
    times = np.array(data["t"])
    assert times[0] == 0.0 and times[-1] == pytest.approx(report.trajectory.t[-1])
    assert np.allclose(np.diff(times), times[-1] / (times.size - 1), rtol=1e-5)
    assert data["x"][0] == [b.x for b in report.system.bodies]  # the initial placement
    assert data["xhat"] is not None
    assert np.ptp(data["xhat"]) < 1e-9  # X-hat stays put
    assert data["magnify"] >= 10  # 5 mm amplitudes in a 0.6 m scene are drawn magnified


def test_every_section_is_there_and_every_formula_is_mathml(report: Report, page: Page) -> None:
    for section in (
        "overview",
        "diagram",
        "parameters",
        "equilibrium",
        "modes",
        "stationary-point",
        "friction",
        "animation",
        "plots",
        "derivation",
        "paper-check",
        "warnings",
        "data",
    ):
        assert section in page.ids
    for figure in (
        "figure-system",
        "figure-equilibrium",
        "figure-modes",
        "figure-friction-ratio",
        "figure-contact-forces",
        "figure-positions",
        "figure-energy",
        "figure-phase",
    ):
        assert figure in page.ids
    assert report.math_failures == []
    assert 'class="tex-source"' not in report.html
    assert page.math_elements >= 100


def test_the_derivation_has_the_five_methods_and_they_agree(report: Report, page: Page) -> None:
    text = html.unescape(report.html)
    for title in (
        "Dynamic equations",
        "Conservation of energy and angular momentum",
        "Euler-Lagrange equations",
        "Natural frequencies of the subsystems",
        "Hamilton's equations",
    ):
        assert f"<h3>{title}" in text
    assert "Cross-check: " in text and "all methods that apply agree" in text
    verdicts = [row[2][0] for row in page.tables["cross-check"][1:]]
    assert len(verdicts) >= 5 and set(verdicts) == {"agrees"}
    methods = {row[0][0] for row in page.tables["cross-check"][1:]}
    assert methods >= {"newton", "conservation", "lagrange", "natural-frequencies", "hamilton"}


def test_the_papers_claims_about_fig_2_with_their_verdicts(report: Report, page: Page) -> None:
    rows = page.tables["paper-claims"][1:]
    shown = [(row[0][0], row[2][0]) for row in rows]
    claims = [
        c for c in paper_check.paper_claims() if "fig2" in {k.strip() for k in c.system.split(",")}
    ]
    assert [location for location, _ in shown] == [c.location for c in claims]
    assert len(shown) >= 20
    words = {
        "verified": "✔ verified",
        "holds-under-stated-assumption": "☑ holds under the paper's stated assumption",
        "holds-only-if": "⚠ holds only if",
        "wrong": "✘ wrong",
    }
    for claim, (_, verdict) in list(zip(claims, shown, strict=True))[:3]:  # paper_check's verdicts
        assert verdict == words[paper_check.check_claim(claim).verdict]
    # the frequency of eq. (QQQ1) is right (tests above recompute it from the closed form)
    assert ("Sec. 5.1, eq. (QQQ1)", "✔ verified") in shown
    # Sec. 3's "f1/f2 = 3/2" is a ratio of the amounts the paper names: the signed ratio is -3/2
    ratio = [c.key for c in claims].index("sec3.friction-ratio")
    assert shown[ratio][1] == words["holds-under-stated-assumption"]


def test_the_claims_quotes_formulas_and_corrections_are_mathml(report: Report) -> None:
    section = re.search(r'<section id="paper-check">.*?</section>', report.html, re.DOTALL)
    assert section
    body = section.group(0)
    rows = re.findall(r"<tbody>(.*?)</tbody>", body, re.DOTALL)[0].split("<tr>")[1:]
    _, checks = paper_figure_checks()
    assert len(rows) == len(checks) >= 20
    for row, check in zip(rows, checks, strict=True):
        cells = re.findall(r"<td[^>]*>(.*?)</td>", row, re.DOTALL)
        claim, correction = cells[1], cells[3]
        formula = re.search(r'<span class="cellmath">(.*?)</span>', claim, re.DOTALL)
        assert formula and formula.group(1).startswith(f'<math xmlns="{MATHML}"'), check.claim.key
        quote = re.search(r'<q class="quote">(.*?)</q>', claim, re.DOTALL)
        assert quote, check.claim.key
        # a formula in the paper's words: delimited, an environment, or a sub/superscript or =
        if re.search(r"\$|\\[(\[]|\\(?:begin|end)\{|[_^=]", check.claim.quote):
            assert f'<math xmlns="{MATHML}"' in quote.group(1), check.claim.key
        if check.correction:
            assert correction.count(f'<math xmlns="{MATHML}"') == 1, check.claim.key
    # what a reader sees of the section (outside MathML) has no LaTeX left in it
    visible = html.unescape(
        re.sub(r"<[^>]+>", "", re.sub(r"<math\b.*?</math>", "", body, flags=re.DOTALL))
    )
    for latex in ("$", "\\dot", "\\varphi", "\\frac", "\\emph", "\\ref", "\\left"):
        assert latex not in visible
    assert re.search(r"\\[A-Za-z]", visible) is None
    assert 'class="tex-source"' not in body and report.math_failures == []


def paper_figure_checks() -> tuple[str, tuple[paper_check.ClaimCheck, ...]]:
    from rollspring.service.documents import figure_claims

    figure = figure_claims(load_system("hoop-cylinder"))
    assert figure is not None
    return figure


# -- self-contained --------------------------------------------------------------------------


def test_the_page_fetches_nothing(report: Report, page: Page) -> None:
    assert page.links, "the page has images and links"
    for link in page.links:
        assert link.startswith(("data:", "#")), link[:60]
    addresses = set(re.findall(r"https?://[^\s\"'<>)]+", report.html))
    assert addresses <= {MATHML, SVG}  # namespace names, never fetched
    assert "@import" not in report.html and "url(" not in report.html
    policy = [m for m in page.meta if m.get("http-equiv") == "Content-Security-Policy"]
    assert policy and "default-src 'none'" in (policy[0].get("content") or "")


def test_style_and_player_are_the_front_end_files_inlined(report: Report) -> None:
    """The style sheet and the player live in ``outputs/report/assets`` (the player draws its
    springs with the shared outputs/js/geometry.js); the page carries them as one inline style
    and one classic script, without a module's import or export (a module script could not
    fetch its import)."""
    package = Path(report_assets.__file__).parent
    css = (package / "assets" / "report.css").read_text(encoding="utf-8")
    assert f"<style>{css}</style>" in report.html
    script = report_assets.player_script()
    assert f"<script>{script}</script>" in report.html
    assert not re.search(r"^\s*(import|export)\b", script, re.M)
    assert "function zigzag(" in script and "function startPlayer(" in script
    assert script.rstrip().endswith("startPlayer(document, window);\n})();")
    geometry = package.parent / "js" / "geometry.js"
    assert "export function zigzag(" in geometry.read_text(encoding="utf-8")
    node = shutil.which("node")
    if node is not None:  # its syntax as a classic script (test_report_browser runs it)
        checked = subprocess.run(
            [node, "--check"], input=script, capture_output=True, text=True, timeout=60
        )
        assert checked.returncode == 0, checked.stderr


def test_an_asset_that_cannot_be_inlined_is_refused() -> None:
    with pytest.raises(ValueError, match="cannot inline"):
        report_assets._inline('import x from "./other.js";\nexport default 1;\n', "x.js")
    with pytest.raises(ValueError, match="would end the inline script"):
        report_assets._inline('const s = "</script>";\n', "x.js")


def test_names_are_text_not_markup() -> None:
    name = 'Evil </script><img src="x"> & <!-- "quoted"'
    system = make_system(
        [body("hoop"), body("cyl", "cylinder", x=0.49)],
        [spring("hoop", "cyl", rest_length=0.5)],
        name=name,
        description="<b>bold?</b>",
    )
    built = build_report(system, duration=0.5, derivation=False)
    page = Page(built.html)
    assert "x" not in page.links  # the name's <img> is text, not an image
    assert json.loads(page.scripts["analysis-data"])["system"] == name
    assert "<h1>Evil &lt;/script&gt;&lt;img src=&quot;x&quot;&gt; &amp; &lt;!-- " in built.html
    assert "<b>bold?</b>" not in built.html


def test_write_report_is_atomic(
    report: Report, tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    target = tmp_path / "report.html"
    assert write_report(report, target) == target
    assert target.read_text(encoding="utf-8") == report.html
    target.write_text("previous")

    def broken(*_args: object) -> None:
        raise OSError(28, "No space left on device")

    monkeypatch.setattr(files.os, "replace", broken)
    with pytest.raises(ReportError, match="cannot write"):
        write_report(report, target)
    assert target.read_text() == "previous"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["report.html"]  # no partial file left


# -- other systems ------------------------------------------------------------------------------


def test_a_walled_system_has_no_stationary_point_and_all_math_converts() -> None:
    built = build_report(load_system("wall-hoop-cylinder"), duration=1.0, derivation=False)
    page = Page(built.html)
    assert built.math_failures == []
    assert "derivation" not in page.ids and "paper-check" not in page.ids
    assert "stationary-weights" not in page.tables
    assert "No stationary point" in built.html
    assert "anchors" in page.tables


def test_a_slipping_system_is_reported_as_slipping() -> None:
    system = make_system(
        [body("hoop", mu_static=0.03), body("ball", "sphere", x=0.49)],
        [spring("hoop", "ball", rest_length=0.5)],
    )
    built = build_report(system, duration=1.0, derivation=False)
    page = Page(built.html)
    verdicts = {row[0][0]: row[-1][0] for row in page.tables["friction"][1:]}
    assert verdicts == {"hoop": "slips", "ball": "rolls"}  # needs kA/(2mg) = 0.051 > 0.03
    assert paper_figure(system) is None  # a hoop and a sphere: none of the paper's figures
    assert built.trajectory.status == "slip"
    assert "first slip: 'hoop' at t = 0 s" in html.unescape(built.html)


def test_a_system_without_equilibrium_says_so() -> None:
    system = make_system([body("hoop")], [], forces=[{"body": "hoop", "fx": 1.0}])
    built = build_report(system, duration=0.5, derivation=False)
    page = Page(built.html)
    assert "<strong>no equilibrium</strong>" in built.html
    amplitude = page.column("friction", "|f| amplitude, linear (N)")
    assert amplitude == {"hoop": None}  # no linear response without an equilibrium
    assert built.trajectory.status == "finished"  # the motion itself is simulated


def test_which_of_the_papers_systems_a_system_is() -> None:
    figures = {name: paper_figure(load_system(name)) for name in preset_names()}
    keys = {name: None if f is None else f[1] for name, f in figures.items()}
    assert keys == {
        "chain-diatomic": None,
        "chain-monatomic": None,
        "frictionless": {"fig3"},
        "hoop-cylinder": {"fig2"},
        "three-bodies": None,
        "two-cylinders": {"two-cylinders"},
        "two-hoops": {"two-hoops"},
        "two-masses": {"fig1"},
        "wall-hoop-cylinder": {"fig4a"},
    }
    # the order of the bodies does not matter; a constant force or raised centres do
    data = load_system("hoop-cylinder").model_dump()
    swapped = {**data, "bodies": data["bodies"][::-1]}
    assert paper_figure(system_from_dict(swapped)) == figures["hoop-cylinder"]
    pulled = {**data, "forces": [{"body": "hoop", "fx": 1.0}]}
    assert paper_figure(system_from_dict(pulled)) is None
    raised = {**data, "bodies": [{**data["bodies"][0], "track_height": 0.05}, data["bodies"][1]]}
    assert paper_figure(system_from_dict(raised)) is None


def test_animation_data_of_a_run_stopped_at_its_start() -> None:
    system = make_system(
        [body("hoop", mu_static=0.03), body("cyl", "cylinder", x=0.49)],
        [spring("hoop", "cyl", rest_length=0.5)],
    )
    from rollspring import simulate

    run = simulate(system, 1.0)
    data = animation_data(analyze(system), run, 60)
    assert len(data["t"]) == 1 and data["x"] == [[0.0, 0.49]]


# -- MathML, Chromium lookup ------------------------------------------------------------------


def test_latex_to_mathml() -> None:
    mathml = latex_to_mathml(r"\Omega^2 = \frac{k}{2m_1} + \frac{2k}{3m_2}")
    assert mathml.startswith(f'<math xmlns="{MATHML}" display="block">')
    assert "<mfrac>" in mathml
    with pytest.raises(MathConversionError, match=r"does not know \\frobnicate"):
        latex_to_mathml(r"\frobnicate{x}")
    with pytest.raises(MathConversionError, match="cannot convert"):
        latex_to_mathml(r"\frac{1}{")


def test_find_chromium_names_what_to_install(
    monkeypatch: pytest.MonkeyPatch, tmp_path: Path
) -> None:
    monkeypatch.setenv(CHROMIUM_ENV, str(tmp_path / "no-such-chromium"))
    with pytest.raises(ReportError, match="apt-get install chromium"):
        find_chromium()
    monkeypatch.delenv(CHROMIUM_ENV)
    monkeypatch.setenv("PATH", str(tmp_path))
    with pytest.raises(ReportError, match="none on PATH"):
        find_chromium()


# -- the command line -----------------------------------------------------------------------


def test_cli_writes_the_report(tmp_path: Path) -> None:
    target = tmp_path / "out" / "hoop.html"
    result = runner.invoke(
        app, ["report", "two-hoops", "-o", str(target), "-T", "1", "--no-derivation"]
    )
    assert result.exit_code == 0, result.output
    page = Page(target.read_text(encoding="utf-8"))
    assert {"modes", "animation"} <= page.ids and "derivation" not in page.ids
    assert result.stderr.strip() == f"wrote {target}"
    assert result.stdout == ""


@pytest.mark.parametrize(
    ("args", "message"),
    [
        (["--format", "docx"], "--format: unknown format 'docx' (formats: html, pdf)"),
        (["-T", "-2"], "--duration: must be a positive number of seconds, got -2"),
        (["no-such-system"], "'no-such-system' is neither a file nor a preset"),
    ],
)
def test_cli_errors_are_one_line_with_exit_code_2(
    tmp_path: Path, args: list[str], message: str
) -> None:
    result = runner.invoke(app, ["report", *args, "-o", str(tmp_path / "r.html")])
    assert result.exit_code == 2
    assert result.stderr.count("\n") == 1
    assert message in result.stderr
    assert not (tmp_path / "r.html").exists()


def test_cli_pdf_without_chromium_is_one_line_naming_chromium(tmp_path: Path) -> None:
    env = {CHROMIUM_ENV: str(tmp_path / "missing" / "chromium")}
    result = runner.invoke(app, ["report", "-o", str(tmp_path / "r.pdf")], env=env)
    assert result.exit_code == 2
    line = result.stderr.strip()
    assert "\n" not in line and line.startswith("error: --format pdf needs Chromium")
    assert "install chromium" in line
    assert not (tmp_path / "r.pdf").exists()
    assert os.listdir(tmp_path) == []

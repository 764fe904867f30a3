"""The page explains the paper (issue 26, point 3), in a real browser against the real server:
the system's description is shown by the picker and follows it; the three "Why?" panels (X̂,
the moving CM, percussion points) open from their links and give the numbers of the system
shown — X̂'s weights are ``/api/analyze``'s, the percussion heights are (1 + γ)R; each rolling
body's percussion mark is drawn at (1 + γ)R above its contact point on its centre's vertical,
also while it rolls; "snap the spring here" sets the end's attachment to that height (read
back from the page's system and its TOML panel), and on the default preset snapping both ends
(with level springs, the paper's Fig. 3) brings the peak friction down more than 100×.

Nothing here waits on wall-clock time: every wait is for a condition in the page."""

from __future__ import annotations

import re

import pytest
import requests
from playwright.sync_api import Page, expect

from rollspring.model import system_from_dict
from tests.test_web_page import Opened, page_system, settle

#: The largest |f| of every body over the page's run, read from the force plot's data.
PEAK_FRICTION = """() => {
    const d = window.rollspringPage.plotData('forces');
    let peak = 0;
    d.labels.forEach((label, k) => {
        if (!/ f$/.test(label)) return;
        for (const v of d.data[k + 1]) if (v != null) peak = Math.max(peak, Math.abs(v));
    });
    return peak;
}"""


def presets(server: str) -> dict[str, dict]:
    return {p["name"]: p for p in requests.get(server + "/api/presets", timeout=30).json()}


def choose(page: Page, preset: str) -> None:
    page.select_option("#preset", preset)
    page.wait_for_function(
        "name => document.querySelector('#preset').value === name",
        arg=preset,
    )
    settle(page)


def no_horizontal_overflow(page: Page) -> None:
    width, inner = page.evaluate("() => [document.documentElement.scrollWidth, window.innerWidth]")
    assert width <= inner


# ------------------------------------------------------------------------------ description


def test_the_description_is_shown_and_follows_the_preset(laptop: Opened, server: str) -> None:
    page = laptop.page
    known = presets(server)
    shown = page.locator("#preset-description")
    default = known["hoop-cylinder"]["system"]["description"]
    assert default  # the default preset has one: the test would be empty otherwise
    expect(shown).to_be_visible()
    expect(shown).to_have_text(default)
    other = known["two-hoops"]["system"]["description"]
    assert other and other != default
    choose(page, "two-hoops")
    expect(shown).to_have_text(other)


# ----------------------------------------------------------------------------- explanations


def in_view(page: Page, selector: str) -> bool:
    return page.evaluate(
        """s => { const r = document.querySelector(s).getBoundingClientRect();
                  return r.bottom > 0 && r.top < window.innerHeight; }""",
        selector,
    )


@pytest.mark.parametrize("where", [".strip-note + .why-links", "#plots-title ~ .why-links"])
def test_each_explanation_opens_from_its_link(sized: Opened, where: str) -> None:
    page = sized.page
    links = page.locator(f"{where} a[data-why]")
    targets = links.evaluate_all("as => as.map(a => a.dataset.why)")
    assert set(targets) >= {"why-xhat", "why-cm"}
    if where.startswith(".strip"):
        assert "why-percussion" in targets
    for k, target in enumerate(targets):
        page.evaluate(
            "id => { document.getElementById(id).open = false; window.scrollTo(0, 0); }", target
        )
        links.nth(k).click()
        panel = page.locator(f"details#{target}")
        expect(panel).to_have_attribute("open", "")
        assert in_view(page, f"details#{target} > summary")
        assert page.evaluate("() => document.activeElement.closest('details')?.id") == target
        # the URL keeps the shared state: a link does not replace it
        assert not page.evaluate("() => location.hash").startswith("#why")
    no_horizontal_overflow(page)


def test_the_cm_panel_links_to_the_newton_plot(laptop: Opened) -> None:
    page = laptop.page
    page.locator(".strip-note + .why-links a[data-why=why-cm]").click()
    page.evaluate("() => window.scrollTo(0, 0)")
    page.locator("#why-cm a[data-why=newton]").click()
    assert in_view(page, '[data-plot="newton"]')
    expect(page.locator("#why-cm .numbers")).to_contain_text("Σm = 2.000 kg")


@pytest.mark.parametrize("preset", ["hoop-cylinder", "three-bodies", "two-cylinders"])
def test_the_explanations_give_the_numbers_of_the_system_shown(
    laptop: Opened, server: str, preset: str
) -> None:
    page = laptop.page
    if preset != "hoop-cylinder":
        choose(page, preset)
    system = page_system(page)
    analysis = requests.post(server + "/api/analyze", json={"system": system}, timeout=60).json()
    weights = analysis["stationary_point"]["weights"]
    assert weights  # these presets have an X̂
    shown = page.locator("#why-xhat .numbers li[data-why-body]").evaluate_all(
        "ls => Object.fromEntries(ls.map(l => [l.dataset.whyBody, Number(l.dataset.weight)]))"
    )
    assert shown == weights
    model = system_from_dict(system)
    heights = page.locator("#why-percussion .numbers li[data-why-body]").evaluate_all(
        "ls => Object.fromEntries(ls.map(l => [l.dataset.whyBody, Number(l.dataset.height)]))"
    )
    expected = {b.id: (1 + b.gamma) * b.radius for b in model.bodies if b.shape != "slider"}
    assert heights == pytest.approx(expected, rel=1e-15)
    assert set(heights) == {b.id for b in model.bodies}


def test_the_percussion_heights_of_hoop_and_cylinder_are_2r_and_1_5r(laptop: Opened) -> None:
    page = laptop.page
    heights = page.locator("#why-percussion .numbers li[data-why-body]").evaluate_all(
        "ls => Object.fromEntries(ls.map(l => [l.dataset.whyBody, Number(l.dataset.height)]))"
    )
    radii = {b["id"]: b["radius"] for b in page_system(page)["bodies"]}
    assert heights["hoop"] == pytest.approx(2 * radii["hoop"], rel=1e-15)
    assert heights["cylinder"] == pytest.approx(1.5 * radii["cylinder"], rel=1e-15)


# ------------------------------------------------------------------- percussion marks, snap


#: Each body's handle centre (its centre on the canvas, CSS px, placed by main.js), the canvas's
#: px per m and the marks drawn.
MARKS = """() => {
    const layer = document.querySelector('#handles').getBoundingClientRect();
    const centres = {};
    for (const h of document.querySelectorAll('#handles [data-body]')) {
        const r = h.getBoundingClientRect();
        centres[h.dataset.body] = {x: r.left - layer.left + r.width / 2,
                                   y: r.top - layer.top + r.height / 2};
    }
    const drawn = window.rollspringPage.drawn();
    return {centres, pxPerM: Number(document.querySelector('#scene').dataset.pxPerM),
            marks: drawn.percussion};
}"""


def check_marks(page: Page) -> dict:
    got = page.evaluate(MARKS)
    system = system_from_dict(page_system(page))
    assert set(got["marks"]) == {b.id for b in system.bodies if b.shape != "slider"}
    for b in system.bodies:
        centre = got["centres"][b.id]
        mark = got["marks"][b.id]
        # on the vertical through the centre, (1 + γ)R − R = γR above it (to 0.1 px: the
        # handles' boxes are laid out in 1/64 px units)
        assert mark["x"] == pytest.approx(centre["x"], abs=0.1)
        assert centre["y"] - mark["y"] == pytest.approx(b.gamma * b.radius * got["pxPerM"], abs=0.1)
    return got


def test_the_percussion_marks_are_drawn_on_each_body_and_move_with_it(sized: Opened) -> None:
    page = sized.page
    at_rest = check_marks(page)
    page.evaluate(
        "() => { const s = document.querySelector('#time'); s.value = '2.5';"
        " s.dispatchEvent(new Event('input')); }"
    )
    page.wait_for_function("() => window.rollspringPage.time() === 2.5")
    page.evaluate("() => new Promise(r => requestAnimationFrame(() => requestAnimationFrame(r)))")
    moved = check_marks(page)
    assert moved["marks"]["hoop"]["x"] != at_rest["marks"]["hoop"]["x"]
    page.locator("#show-percussion").uncheck()
    assert page.evaluate("() => window.rollspringPage.drawn().percussion") == {}


def toml_text(page: Page) -> str:
    panel = page.locator("details#toml-panel")
    if panel.get_attribute("open") is None:
        page.locator("details#toml-panel > summary").click()
    expect(page.locator("#toml")).to_have_value(re.compile(r"\[\[springs\]\]"))
    return page.locator("#toml").input_value()


def test_snap_sets_the_attachment_to_the_percussion_height(laptop: Opened) -> None:
    page = laptop.page
    page.locator(".strip-note + .why-links a[data-why=why-percussion]").click()
    assert page_system(page)["springs"][0].get("at") in (None, [{}, {}])
    page.locator('#why-percussion button.snap[data-spring="0"][data-end="0"]').click()
    settle(page)
    spring = page_system(page)["springs"][0]
    assert spring["ends"][0] == "hoop"
    assert spring["at"][0] == {"height": pytest.approx(2 * 0.1, rel=1e-15)}
    assert spring["at"][1] == {}
    assert "at = [\n    { height = 0.2 },\n    {},\n]" in toml_text(page)
    expect(page.locator("#why-percussion .snaps li").first).to_contain_text("✓")
    page.locator('#why-percussion button.snap[data-spring="0"][data-end="1"]').click()
    settle(page)
    spring = page_system(page)["springs"][0]
    assert spring["at"][1] == {"height": pytest.approx(1.5 * 0.1, rel=1e-15)}
    expect(page.locator("#preset")).to_have_value("")  # now an edited system


def test_snapping_both_ends_on_the_default_preset_stops_the_friction(laptop: Opened) -> None:
    page = laptop.page
    before = page.evaluate(PEAK_FRICTION)
    cm = page.evaluate("() => window.rollspringPage.plotData('newton')")
    assert before > 0.1  # the default preset needs friction: about 0.5 N
    page.locator(".strip-note + .why-links a[data-why=why-percussion]").click()
    page.locator("#why-percussion button.snap-level").click()
    settle(page)
    system = page_system(page)
    tracks = {b["id"]: b["track_height"] for b in system["bodies"]}
    at = system["springs"][0]["at"]
    # the spring's two ends at one height: level, as in the paper's Fig. 3
    assert tracks["hoop"] + at[0]["height"] == pytest.approx(tracks["cylinder"] + at[1]["height"])
    after = page.evaluate(PEAK_FRICTION)
    assert after * 100 <= before
    # and Σf, so the CM's acceleration, with it
    newton = page.evaluate("() => window.rollspringPage.plotData('newton')")
    peak = [
        max(abs(v) for series in d[1:] for v in series if v is not None)
        for d in (cm["data"], newton["data"])
    ]
    assert peak[1] * 100 <= peak[0]


def test_snapping_on_one_floor_tilts_the_spring_and_still_cuts_the_friction(laptop: Opened) -> None:
    page = laptop.page
    before = page.evaluate(PEAK_FRICTION)
    page.locator(".strip-note + .why-links a[data-why=why-percussion]").click()
    page.locator("#why-percussion button.snap-all").click()
    settle(page)
    system = page_system(page)
    assert {b["track_height"] for b in system["bodies"]} == {0.0}
    after = page.evaluate(PEAK_FRICTION)
    # first order gone, second order left: ~30× here (the level spring of the test above: >100×)
    assert after * 10 <= before

"""The guided lesson, "The paper in six steps" (issue 26, point 4), and the page's last gaps, in a
real browser against the real server, at 1280×800 and 390×844.

Each step loads its system and view and shows what its text says, measured from what the page
drew and plotted (``rollspringPage.drawn()``, ``plotData``) against the paper's formulas and the
engine: Fig. 1's centre of mass at rest; Fig. 2's CM swinging on the strip at ×200 while X̂ stays
put; X̂'s weights I′ᵢ/ΣI′ (the paper's eq. (c)); the frictions f₁/f₂ = −3/2 (Appendix A; PHYSICS
(M17)); Fig. 3's friction arrows ≈ 0 with the CM still at the same magnification; and at a large
amplitude the friction back and the pair creeping. Every step passes axe-core, fits the screen,
matches its screenshot baseline, and its shared link reopens it.

The leftovers of the page: plots zoom and pan from the keyboard and pan with Shift + drag; the
chain presets' drag handles are 44 px touch targets on a phone; the force values' text follows
the clock while playing.

The screenshot baselines (``tests/baselines/lesson-*.png``) are the viewport, halved, with the
clock paused at a fixed time and reduced motion asked for (no step starts playing); they are
compared as ``tests/test_figures.py`` compares its figures (RMS of the pixel difference). After
an intended change of the page, regenerate them, look at every one, and commit them::

    ROLLSPRING_UPDATE_BASELINES=1 .venv/bin/python -m pytest tests/test_web_guided.py

Nothing here waits on wall-clock time: every wait is for a condition in the page."""

from __future__ import annotations

import re
from pathlib import Path

import numpy as np
import pytest
import requests
from PIL import Image
from playwright.sync_api import Browser, Page, expect

import rollspring
from rollspring.model import load_system, system_from_dict
from rollspring.service.runs import ModeStart, mode_start
from tests.image_baselines import check_against_baseline
from tests.serving import LAPTOP, PHONE
from tests.test_web_lesson import no_horizontal_overflow, peak_to_peak, sig3, sweep
from tests.test_web_page import Opened, canvas_hash, clock, open_page, page_system, settle
from tests.test_web_phone import TAP, TARGETS, axe_violations, serious

#: Where the baselines' clock stands in the steps that play (paused there): an output time.
SHOT_T = 1.0

STEPS_JS = "async () => (await import('/static/js/lesson.js')).STEPS"
PLOTS = ["positions", "newton", "forces", "ratio", "energy"]
#: The view options of the page and their checkboxes.
BOXES = {
    "spring": "show-spring",
    "friction": "show-friction",
    "normal": "show-normal",
    "values": "show-values",
    "markers": "show-markers",
    "percussion": "show-percussion",
    "linear": "show-linear",
}


def lesson(page: Page) -> dict | None:
    return page.evaluate("() => window.rollspringPage.lesson()")


def playing(page: Page) -> bool:
    return page.evaluate("() => window.rollspringPage.playing()")


def seek(page: Page, t: float) -> None:
    """Move the clock to t with the time slider (as a reader does)."""
    page.locator("#time").evaluate(
        "(slider, t) => { slider.value = String(t); slider.dispatchEvent(new Event('input')); }",
        t,
    )


def shown_plots(page: Page) -> list[str]:
    return page.evaluate(
        "() => [...document.querySelectorAll('#plots .plot')].filter(f => !f.hidden)"
        ".map(f => f.dataset.plot)"
    )


def view(page: Page) -> dict[str, bool]:
    return {key: page.locator(f"#{box}").is_checked() for key, box in BOXES.items()}


def plotted(page: Page, key: str) -> dict:
    return page.evaluate("k => window.rollspringPage.plotData(k)", key)


def column(data: dict, label: str) -> np.ndarray:
    return np.array(data["data"][1 + data["labels"].index(label)], dtype=float)


def presets(server: str) -> dict[str, dict]:
    return {p["name"]: p["system"] for p in requests.get(server + "/api/presets").json()}


def check_screenshot(page: Page, name: str, tmp_path: Path) -> None:
    """The viewport, halved, against ``tests/baselines/<name>.png`` (or written there)."""
    page.evaluate("() => document.activeElement && document.activeElement.blur()")
    page.mouse.move(0, 0)  # no hover left where the last click was
    full = tmp_path / f"{name}-full.png"
    page.screenshot(path=str(full), animations="disabled", caret="hide")
    actual = tmp_path / f"{name}.png"
    with Image.open(full) as image:
        image.convert("RGB").resize(
            (image.width // 2, image.height // 2), Image.Resampling.BOX
        ).save(actual)
    check_against_baseline(actual, name, __file__)


# ---------------------------------------------------------------------- what each step shows


def strip_frames(page: Page) -> tuple[list[dict], float]:
    """The strip at every output time, and the animation's px per m."""
    strips = [f["drawn"]["strip"] for f in sweep(page)]
    return strips, float(page.locator("#scene").get_attribute("data-px-per-m"))


def check_fig1(page: Page, measured: dict) -> None:
    """Two sliders on a frictionless floor: the CM stays at rest (the paper's (m₁+m₂)Ẍ = 0)."""
    assert [b["shape"] for b in page_system(page)["bodies"]] == ["slider", "slider"]
    strips, _ = strip_frames(page)
    assert {s["magnification"] for s in strips} == {200}
    assert peak_to_peak([s["cm"] for s in strips]) <= 1e-9
    positions = plotted(page, "positions")
    assert np.ptp(column(positions, "m1")) > 5  # mm: the blocks swing ...
    assert np.ptp(column(positions, "CM")) < 1e-9  # ... the CM does not
    # the spring's pulls on the two blocks: equal and opposite (internal forces), drawn
    pulls = page.evaluate("() => window.rollspringPage.drawn().spring")
    assert len(pulls) == 2 and abs(pulls[0]) >= 20
    assert pulls[0] == pytest.approx(-pulls[1], rel=1e-12)


def check_fig2(page: Page, measured: dict) -> None:
    """Fig. 2: the CM swings on the strip (×200), X̂ stays put; friction arrows drawn."""
    strips, px_per_m = strip_frames(page)
    assert {s["magnification"] for s in strips} == {200}
    cm = peak_to_peak([s["cm"] for s in strips])
    run = rollspring.simulate(load_system("hoop-cylinder"), 10.0, n_output=601)
    assert cm == pytest.approx(float(np.ptp(run.cm_x)) * px_per_m * 200, rel=1e-6)
    assert cm >= 30
    assert peak_to_peak([s["xhat"] for s in strips]) <= 1
    measured["fig2 CM px"] = cm
    newton = plotted(page, "newton")
    friction, mass_acc = (np.array(c, dtype=float) for c in newton["data"][1:])
    assert np.max(np.abs(friction - mass_acc)) <= 1e-9 * np.max(np.abs(friction))


def check_xhat(page: Page, measured: dict) -> None:
    """X̂ = (I′₁x₁ + I′₂x₂)/(I′₁ + I′₂) (eq. (c)): weights 4/7, 3/7; flat while the CM swings."""
    system = load_system("hoop-cylinder")
    contact = [b.contact_inertia / b.radius**2 for b in system.bodies]
    weights = [c / sum(contact) for c in contact]
    assert weights == pytest.approx([4 / 7, 3 / 7], rel=1e-12)  # I′ = 2mR², 3/2·mR²
    note = page.locator("#analysis-note")
    expect(note).to_contain_text(f"X̂ = {weights[0]:.4f}·x_hoop + {weights[1]:.4f}·x_cylinder")
    positions = plotted(page, "positions")
    assert np.max(np.abs(column(positions, "X̂"))) < 1e-9
    assert np.ptp(column(positions, "CM")) > 1  # mm
    strips, _ = strip_frames(page)
    assert peak_to_peak([s["xhat"] for s in strips]) <= 1


def check_frictions(page: Page, measured: dict) -> None:
    """f₁/f₂ = −3/2 at every instant (PHYSICS (M17), f = −(1 − λ)F_x with λ = 1/(1 + γ) for a
    spring at the centres): in the plot, in the arrows and in their labels at the release."""
    forces = plotted(page, "forces")
    shown = {label for label, on in zip(forces["labels"], forces["shown"], strict=True) if on}
    assert shown == {"hoop f", "cylinder f"}
    hoop, cylinder = column(forces, "hoop f"), column(forces, "cylinder f")
    big = np.abs(cylinder) > 1e-3 * np.max(np.abs(cylinder))
    assert big.sum() > 500
    np.testing.assert_allclose(hoop[big] / cylinder[big], -1.5, rtol=1e-9)
    assert clock(page) == 0 and not playing(page)
    drawn = page.evaluate("() => window.rollspringPage.drawn()")
    assert drawn["friction"]["hoop"] / drawn["friction"]["cylinder"] == pytest.approx(-1.5)
    # at the release the spring pushes each body with k·0.01 m = 1 N: F_x = −1 N on the hoop
    system = load_system("hoop-cylinder")
    k = system.springs[0].stiffness
    push = k * (system.springs[0].rest_length - (system.bodies[1].x - system.bodies[0].x))
    lam = [b.mass * b.radius**2 / b.contact_inertia for b in system.bodies]  # 1/(1 + γ)
    f = [-(1 - lam[0]) * -push, -(1 - lam[1]) * push]
    for body, value in zip(("hoop", "cylinder"), f, strict=True):
        assert f"{body}: f = {'−' if value < 0 else '+'}{sig3(abs(value))} N" in drawn["labels"]


def check_fig3(page: Page, measured: dict) -> None:
    """Fig. 3: the spring's ends at the percussion points (1 + γ)R; friction arrows ≈ 0 at the
    default's scale; the CM all but still at the magnification of Fig. 2."""
    system = page_system(page)
    gamma = {"hoop": 1.0, "cylinder": 0.5}
    for body, at in zip(system["bodies"], system["springs"][0]["at"], strict=True):
        assert at["height"] == pytest.approx((1 + gamma[body["shape"]]) * body["radius"])
    frames = sweep(page)
    assert max(abs(v) for f in frames for v in f["drawn"]["friction"].values()) <= 2
    assert page.evaluate("() => window.rollspringPage.drawn().forceScale")["friction"] == 60
    strips = [f["drawn"]["strip"] for f in frames]
    assert {s["magnification"] for s in strips} == {200}
    cm = peak_to_peak([s["cm"] for s in strips])
    px_per_m = float(page.locator("#scene").get_attribute("data-px-per-m"))
    run = rollspring.simulate(system_from_dict(system), 10.0, n_output=601)
    assert cm == pytest.approx(float(np.ptp(run.cm_x)) * px_per_m * 200, rel=1e-6)
    assert cm <= 0.1 * measured["fig2 CM px"]
    assert set(page.evaluate("() => window.rollspringPage.drawn().percussion")) == set(gamma)
    measured["fig3 max |f|"] = float(np.max(np.abs(run.friction)))


def check_large(page: Page, measured: dict) -> None:
    """The Fig. 3 pair in its mode at 2 cm: the hoop turned by about 15°, friction back, the CM
    creeping away while the linear solution stays; it still rolls."""
    expect(page.locator("#initial")).to_contain_text("Starting at rest along mode 2")
    started = mode_start(load_system("frictionless"), ModeStart(mode=1, amplitude=0.02))
    hoop = started.bodies[0]
    assert np.degrees(hoop.x / hoop.radius) == pytest.approx(15, abs=0.5)
    run = rollspring.simulate(started, 10.0, n_output=601)
    assert run.summary["status"] == "finished"
    assert max(run.summary["max_friction_ratio"].values()) < 1  # it still rolls
    newton = plotted(page, "newton")
    friction = np.array(newton["data"][1], dtype=float)
    np.testing.assert_allclose(friction, run.friction.sum(axis=1), atol=1e-9)
    assert np.max(np.abs(run.friction)) > 100 * measured["fig3 max |f|"]
    positions = plotted(page, "positions")
    cm = column(positions, "CM")
    assert np.ptp(cm) == pytest.approx(np.ptp(run.cm_x) * 1000, rel=1e-6)
    assert np.ptp(cm) > 100  # mm: it walks away
    assert page.evaluate("() => window.rollspringPage.drawn().friction")  # arrows drawn
    frames = sweep(page)
    assert max(abs(v) for f in frames for v in f["drawn"]["friction"].values()) >= 20


CHECKS = {
    "fig1": check_fig1,
    "fig2": check_fig2,
    "xhat": check_xhat,
    "frictions": check_frictions,
    "fig3": check_fig3,
    "large": check_large,
}


# ------------------------------------------------------------------------------------- the walk


def test_the_lesson_walks_the_paper_in_six_steps(
    sized: Opened, server: str, tmp_path: Path
) -> None:
    page = sized.page
    size = "laptop" if page.viewport_size == LAPTOP else "phone"
    page.emulate_media(reduced_motion="reduce")  # no step starts playing: fixed frames
    steps = page.evaluate(STEPS_JS)
    assert [s["key"] for s in steps] == list(CHECKS)
    systems = presets(server)
    before = page_system(page)
    start = page.get_by_role("button", name="The paper in six steps")
    start.click()
    settle(page)
    panel = page.get_by_role("region", name="The paper in six steps")
    expect(panel).to_be_visible()
    assert page.evaluate("() => document.activeElement.id") == "lesson-step-title"
    measured: dict = {}
    for k, step in enumerate(steps):
        settle(page)
        assert lesson(page) == {"step": k, "key": step["key"], "count": 6}
        title = panel.get_by_role("heading", level=3)
        expect(title).to_have_text(f"{k + 1}. {step['title']} ({step['figure']})")
        assert re.search(r"Fig\. \d|eq|Appendix", step["figure"])
        in_view = title.bounding_box()
        assert (
            in_view
            and 0 <= in_view["y"]
            and in_view["y"] + in_view["height"] <= (page.viewport_size["height"])
        )
        # the indicator, the buttons
        current = panel.locator('[aria-current="step"]')
        expect(current).to_have_count(1)
        expect(current).to_have_text(str(k + 1))
        expect(page.locator("#lesson-progress")).to_have_text(f"Step {k + 1} of 6: {step['title']}")
        expect(panel.get_by_role("button", name="Back", exact=True)).to_be_enabled(enabled=k > 0)
        expect(panel.get_by_role("button", name="Next", exact=True)).to_be_enabled(enabled=k < 5)
        # what to look at: 2 to 4 plain sentences, in two paragraphs ("Fig." and "eq." end none)
        paragraphs = panel.locator("#lesson-text p").all_inner_texts()
        assert len(paragraphs) == 2
        said = " ".join(paragraphs)
        sentences = len(re.findall(r"[.!?](?:\s|$)", said)) - len(
            re.findall(r"\b(?:Fig|eqs?)\.\s", said)
        )
        assert 2 <= sentences <= 4, said
        # its system, its view, its plots, paused (reduced motion) at its time
        system = page_system(page)
        assert system == systems[step["preset"]]
        assert view(page) == {
            key: bool(step["show"].get(key, key in ("friction", "markers", "percussion")))
            for key in BOXES
        }
        assert shown_plots(page) == [p for p in PLOTS if p in step["plots"]]
        assert not playing(page) and clock(page) == step["t"]
        CHECKS[step["key"]](page, measured)
        no_horizontal_overflow(page)
        assert serious(axe_violations(page)) == []
        if size == "phone" and k == 0:  # the lesson's buttons and links: 44 px tap targets
            small = [t for t in page.evaluate(TARGETS) if t["width"] < TAP or t["height"] < TAP]
            assert small == []
        if step["play"]:
            seek(page, SHOT_T)
        else:
            seek(page, step["t"])
        check_screenshot(page, f"lesson-{k + 1}-{step['key']}-{size}", tmp_path)
        if step["key"] == "frictions":  # Reset all, in the lesson: the step set up again
            page.locator("#show-normal").check()
            page.get_by_role("button", name="Step", exact=True).click()
            page.get_by_role("button", name="Reset all").click()
            settle(page)
            assert lesson(page)["step"] == k and clock(page) == step["t"]
            assert not page.locator("#show-normal").is_checked()
        if k < 5:
            if k % 2:
                page.keyboard.press("n")  # the key does what Next does
            else:
                panel.get_by_role("button", name="Next", exact=True).click()
    # P goes back, N forward again
    page.keyboard.press("p")
    settle(page)
    assert lesson(page)["step"] == 4
    # leaving: the page as it was before the lesson, every plot and line back
    panel.get_by_role("button", name="Leave the lesson").click()
    settle(page)
    assert lesson(page) is None
    expect(panel).to_be_hidden()
    assert page_system(page) == before
    assert shown_plots(page) == PLOTS
    assert all(plotted(page, "forces")["shown"])
    assert page.evaluate("() => document.activeElement.id") == "lesson-start"
    assert "in-lesson" not in (page.locator("body").get_attribute("class") or "")
    no_horizontal_overflow(page)


# ----------------------------------------------------------------------------- shared links


def open_reduced(browser: Browser, server: str, url: str, viewport: dict) -> Opened:
    seen = open_page(browser, server, url, viewport=viewport)
    seen.page.emulate_media(reduced_motion="reduce")
    return seen


@pytest.mark.parametrize("viewport", [LAPTOP, PHONE], ids=["laptop-1280x800", "phone-390x844"])
def test_each_steps_shared_link_reopens_it(browser: Browser, server: str, viewport: dict) -> None:
    seen = open_reduced(browser, server, "/", viewport)
    page = seen.page
    try:
        steps = page.evaluate(STEPS_JS)
        page.get_by_role("button", name="The paper in six steps").click()
        settle(page)
        links = []
        for k, step in enumerate(steps):
            page.get_by_role("button", name=f"Step {k + 1}: {step['title']}").click()
            settle(page)
            seek(page, 0.5)
            page.locator("#share-url").evaluate("box => { box.value = ''; }")
            page.get_by_role("button", name="Share link").click()
            expect(page.locator("#share-url")).to_have_value(re.compile("#v1[.]"))
            url = page.locator("#share-url").input_value()
            expect(page.locator("#lesson-link")).to_have_attribute("href", re.compile("#v1[.]"))
            links.append(page.locator("#lesson-link").get_attribute("href"))
            shared = {
                "system": page_system(page),
                "t": clock(page),
                "frame": canvas_hash(page),
                "view": view(page),
                "plots": shown_plots(page),
            }
            fresh = open_page(browser, server, url, viewport=viewport)
            try:
                other = fresh.page
                settle(other)
                assert lesson(other) == {"step": k, "key": step["key"], "count": 6}
                expect(other.locator("#lesson-step-title")).to_contain_text(step["title"])
                assert not playing(other)
                reopened = {
                    "system": page_system(other),
                    "t": clock(other),
                    "frame": canvas_hash(other),
                    "view": view(other),
                    "plots": shown_plots(other),
                }
                assert reopened == shared
                fresh.check_clean()
            finally:
                fresh.page.close()
        seen.check_clean()
    finally:
        page.close()
    # "Link to this step": the step as the lesson sets it up, playing if it plays
    last = len(steps) - 1
    fresh = open_page(browser, server, links[last], viewport=viewport)
    try:
        other = fresh.page
        assert lesson(other)["step"] == last
        assert playing(other) == steps[last]["play"]
        assert shown_plots(other) == [p for p in PLOTS if p in steps[last]["plots"]]
        # pasted into the same tab (only the fragment changes): that step
        other.evaluate("href => { location.hash = new URL(href, location.href).hash; }", links[3])
        other.wait_for_function("() => window.rollspringPage.lesson()?.step === 3")
        settle(other)
        assert not playing(other) and clock(other) == steps[3]["t"]
        assert page_system(other)["name"].startswith("Hoop and cylinder joined at their centres")
        # another system chosen: the lesson's words no longer apply, its panel closes
        other.select_option("#preset", "two-hoops")
        settle(other)
        assert lesson(other) is None
        expect(other.locator("#lesson")).to_be_hidden()
        assert shown_plots(other) == PLOTS and all(plotted(other, "forces")["shown"])
        fresh.check_clean()
    finally:
        fresh.page.close()


#: Holds the page's reading of a deflated body (its own URL being encoded) once read, until the test
#: lets it go: a write of the page's state still in flight when a link is pasted, made certain,
#: and its end (microtasks alone) placed before the pasted link's queued hashchange.
HOLD_ENCODES = """(() => {
  const read = Response.prototype.arrayBuffer;
  let gate = null, open = null;
  window.rollspringTest = {
    held: 0,
    hold() { gate = new Promise(r => { open = r; }); },
    release() { const o = open; gate = null; open = null; if (o) o(); },
  };
  Response.prototype.arrayBuffer = async function () {
    const wait = gate;
    const bytes = await read.call(this);
    if (wait) { window.rollspringTest.held += 1; await wait; }
    return bytes;
  };
})()"""


def open_holding(browser: Browser, server: str) -> tuple[Page, list[str]]:
    """The page at a laptop's size with :data:`HOLD_ENCODES` installed, ready and settled,
    and the list its page errors go to."""
    page = browser.new_page(viewport=LAPTOP)
    errors: list[str] = []
    page.on("pageerror", lambda e: errors.append(str(e)))
    page.add_init_script(HOLD_ENCODES)
    try:
        page.goto(server + "/")
        page.evaluate("() => window.rollspringPage.ready()")
        settle(page)
    except BaseException:
        page.close()
        raise
    return page, errors


def test_a_link_pasted_while_the_page_writes_its_own_state_opens_the_link(
    browser: Browser, server: str
) -> None:
    """The flake this test replaces (CI of 30c8e1a): the page's own state, encoded before a link
    was pasted into the tab, was written over the link before its hashchange ran, so the page
    reopened its own old state. Here the page's write is held in flight, the link pasted, and the
    write let go before the hashchange is handled: the link must win."""
    page, errors = open_holding(browser, server)
    try:
        link = page.evaluate(
            "async () => '#' + await (await import('/static/js/urlstate.js'))"
            ".encodeState({lesson: 3})"
        )
        page.evaluate("() => window.rollspringTest.hold()")
        page.locator("#restart").click()  # the clock to 0: the page writes its state (held)
        page.wait_for_function("() => window.rollspringTest.held > 0")
        page.evaluate("link => { location.hash = link; window.rollspringTest.release(); }", link)
        page.wait_for_function("() => window.rollspringPage.lesson()?.step === 3")
        settle(page)
        assert lesson(page) == {"step": 3, "key": lesson(page)["key"], "count": 6}
        expect(page.locator("#lesson")).to_be_visible()
        assert errors == []
    finally:
        page.close()


URL_STATE = (
    "async () => (await (await import('/static/js/urlstate.js')).decodeState(location.hash))"
)
#: A condition for ``wait_for_function`` (which takes a promise for a truthy value): the clock
#: time the address bar's state holds is ``t``, decoded afresh at each poll.
URL_T_IS = """t => {
  import('/static/js/urlstate.js').then(m => m.decodeState(location.hash))
    .then(s => { window.rollspringUrlT = s ? s.t : null; });
  return window.rollspringUrlT === t;
}"""


def test_of_two_writes_of_the_pages_state_in_flight_the_newer_lands(
    browser: Browser, server: str
) -> None:
    """Two writes of the page's state to the URL in flight at once (an encode slower than the
    150 ms between two changes): the newer state is the one left in the address bar, whichever
    encode ends first (the older write used to land and the newer one to stand down)."""
    page, errors = open_holding(browser, server)
    try:
        page.evaluate("() => window.rollspringTest.hold()")
        seek(page, 0.3)
        page.wait_for_function("() => window.rollspringTest.held === 1")
        seek(page, 0.7)
        page.wait_for_function("() => window.rollspringTest.held === 2")
        page.evaluate("() => window.rollspringTest.release()")
        page.wait_for_function(URL_T_IS, arg=clock(page))
        assert clock(page) == pytest.approx(0.7, abs=0.05)
        assert page.evaluate(URL_STATE)["t"] == clock(page)
        assert errors == []
    finally:
        page.close()


def test_a_damaged_link_pasted_leaves_the_pages_own_state_in_the_address_bar(
    browser: Browser, server: str
) -> None:
    """A pasted fragment that holds no state opens nothing, and the page writes its own state
    back (the write pending before the paste was cancelled by it)."""
    opened = open_page(browser, server, "/")
    page = opened.page
    try:
        seek(page, 0.4)
        page.evaluate("() => { location.hash = '#v1.not-a-state'; }")
        page.wait_for_function(URL_T_IS, arg=clock(page))
        assert page.evaluate(URL_STATE)["t"] == clock(page) == pytest.approx(0.4, abs=0.05)
        opened.check_clean()
    finally:
        page.close()


# -------------------------------------------------------------------- the page's leftovers


def test_plots_zoom_and_pan_from_the_keyboard_and_pan_with_shift_drag(laptop: Opened) -> None:
    page = laptop.page
    windows = (
        "() => ['positions', 'newton', 'forces', 'ratio', 'energy'].map(k => "
        "window.rollspringPage.plotWindow(k))"
    )
    plot = page.get_by_role("figure", name=re.compile("^Positions"))
    plot.focus()
    page.keyboard.press("+")  # about the clock (t = 0): the first half of the run
    assert page.evaluate(windows) == [[0, 5]] * 5
    page.keyboard.press("+")
    assert page.evaluate(windows) == [[0, 2.5]] * 5
    page.keyboard.press("ArrowRight")  # a quarter of the window
    assert page.evaluate(windows) == [[0.625, 3.125]] * 5
    page.keyboard.press("ArrowLeft")
    page.keyboard.press("ArrowLeft")  # not before the start
    assert page.evaluate(windows) == [[0, 2.5]] * 5
    page.keyboard.press("-")
    assert page.evaluate(windows) == [[0, 5]] * 5
    page.keyboard.press("Home")
    assert page.evaluate(windows) == [[0, 10]] * 5
    assert clock(page) == 0
    # Shift + drag pans (a plain drag zooms: test_web_controls.py)
    page.keyboard.press("+")
    over = page.locator('[data-plot="energy"] .u-over')
    over.scroll_into_view_if_needed()
    box = over.bounding_box()
    y = box["y"] + box["height"] / 2
    page.keyboard.down("Shift")
    page.mouse.move(box["x"] + box["width"] * 0.6, y)
    page.mouse.down()
    page.mouse.move(box["x"] + box["width"] * 0.4, y, steps=4)
    page.mouse.move(box["x"] + box["width"] * 0.2, y, steps=4)
    page.mouse.up()
    page.keyboard.up("Shift")
    shown = page.evaluate(windows)
    assert shown[0] == pytest.approx([2, 7], abs=0.02)  # 40 % of the 5 s window later
    assert all(w == shown[0] for w in shown)
    assert clock(page) == 0  # a pan does not move the clock
    # listed in the keyboard-shortcut help
    page.keyboard.press("?")
    listed = page.get_by_role("dialog", name="Keyboard shortcuts").locator("dt").all_inner_texts()
    for keys in ("+ or −", "← or →", "Home", "N", "P"):
        assert keys in listed
    page.keyboard.press("Escape")


def test_chain_drag_handles_are_44_px_touch_targets_on_a_phone(phone: Opened) -> None:
    page = phone.page
    page.select_option("#preset", "chain-monatomic")
    settle(page)
    handles = page.evaluate(
        """() => [...document.querySelectorAll('#handles [role="slider"]')].map(h => {
            const box = h.getBoundingClientRect();
            const ring = parseFloat(getComputedStyle(h, '::after').width);
            const x = box.left + box.width / 2, y = box.top + box.height / 2;
            return {id: h.dataset.body, width: box.width, height: box.height, ring,
                    hit: document.elementFromPoint(x, y)?.dataset.body ?? null};
        })"""
    )
    assert len(handles) == 8
    for h in handles:
        assert h["width"] >= 44 and h["height"] >= 44, h
        assert h["ring"] < 44  # the body drawn smaller: its focus ring keeps its size
        assert h["hit"] == h["id"]  # a tap on a body's centre is that body's
    # dragging one by its target's edge moves it (a touch beside a small body still takes it)
    first = page.locator('#handles [data-body="hoop1"]')
    box = first.bounding_box()
    x, y = box["x"] + box["width"] / 2, box["y"] + box["height"] / 2
    ring = handles[0]["ring"]
    px_per_m = float(page.locator("#scene").get_attribute("data-px-per-m"))
    page.mouse.move(x, y - ring / 2 - 4)  # above the drawn body, inside the target
    page.mouse.down()
    page.mouse.move(x + 0.01 * px_per_m, y - ring / 2 - 4, steps=4)
    page.mouse.up()
    settle(page)
    assert page.locator("#disp-hoop1").get_attribute("data-m") != "0"


def test_the_force_values_follow_the_clock_while_playing_on_a_phone(phone: Opened) -> None:
    page = phone.page
    values = page.locator("#force-values")
    expect(values).to_contain_text("At t = 0.0000 s")
    page.get_by_role("button", name="Play", exact=True).click()
    page.wait_for_function(
        """() => {
        const m = /At t = ([\\d.]+) s/.exec(document.querySelector('#force-values').textContent);
        return m && Number(m[1]) > 0.3 && window.rollspringPage.playing();
    }"""
    )
    text = values.inner_text()
    page.get_by_role("button", name="Pause", exact=True).click()
    t = float(re.search(r"At t = ([\d.]+) s", text).group(1))
    run = rollspring.simulate(load_system("hoop-cylinder"), 10.0, n_output=601)
    # the page interpolates linearly between output times; the text has t to 4 decimals
    near = [float(np.interp(s, run.t, run.friction[:, 0])) for s in (t - 5e-5, t + 5e-5)]
    written = re.search(r"hoop: f = ([+−])([\d.e-]+) N", text)
    value = float(written.group(2)) * (-1 if written.group(1) == "−" else 1)
    assert min(near) - 5e-3 * abs(value) <= value <= max(near) + 5e-3 * abs(value)

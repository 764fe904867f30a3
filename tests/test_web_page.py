"""The interactive page (``rollspring serve``) in a real browser: Debian's Chromium driven by
Playwright, against the real server started as a subprocess on a free local port. The page loads
with no console error and no request outside its origin; the stiffness slider changes the modal
table's ω to what ``analyze`` gives; Play animates and Pause freezes; Step advances by one dt;
dragging a body sets its initial displacement; a slip is announced at the time ``simulate``
reports; a shared link restores the state; bad input is shown inline and the page keeps running;
every control is reachable and labelled from the keyboard; screenshots at laptop and phone sizes.

Nothing here waits on wall-clock time: every wait is for a condition in the page."""

from __future__ import annotations

import hashlib
import re
import shutil
from dataclasses import dataclass, field
from pathlib import Path

import pytest
from playwright.sync_api import Browser, Page, expect

import rollspring
from rollspring.model import system_from_dict
from tests.serving import LAPTOP, PHONE, VISIBLE_TEXT

REPO = Path(__file__).resolve().parents[1]


@dataclass
class Opened:
    page: Page
    base: str
    errors: list[str] = field(default_factory=list)
    requests: list[str] = field(default_factory=list)

    def check_clean(self) -> None:
        """No console error so far, and every request went to the app's own origin."""
        assert self.errors == []
        self.check_origin()

    def check_origin(self) -> None:
        assert self.requests
        outside = [
            u for u in self.requests if not u.startswith((self.base + "/", "data:", "blob:"))
        ]
        assert outside == []


def open_page(browser: Browser, base: str, url: str = "/", viewport: dict = LAPTOP) -> Opened:
    page = browser.new_page(viewport=viewport)
    seen = Opened(page, base)
    page.on(
        "console", lambda m: seen.errors.append(f"console: {m.text}") if m.type == "error" else None
    )
    page.on("pageerror", lambda e: seen.errors.append(f"page error: {e}"))
    page.on("request", lambda r: seen.requests.append(r.url))
    page.goto(base + url if url.startswith("/") else url)
    page.evaluate("() => window.rollspringPage.ready()")
    settle(page)
    return seen


def settle(page: Page) -> None:
    """Wait until every change is computed and drawn."""
    page.wait_for_function("() => window.rollspringPage && window.rollspringPage.settled()")


def canvas_hash(page: Page) -> str:
    data = page.evaluate("() => document.querySelector('#scene').toDataURL()")
    return hashlib.sha256(data.encode()).hexdigest()


def next_frames(page: Page, n: int = 5) -> None:
    """Let the browser paint n animation frames (no wall-clock wait)."""
    page.evaluate(
        """n => new Promise(done => {
        const go = k => k ? requestAnimationFrame(() => go(k - 1)) : done();
        go(n);
    })""",
        n,
    )


def clock(page: Page) -> float:
    return float(page.locator("#clock").get_attribute("data-t"))


def page_system(page: Page) -> dict:
    return page.evaluate("() => window.rollspringPage.system()")


def oscillating_omegas(system: dict) -> list[float]:
    result = rollspring.analyze(system_from_dict(system))
    return [m.omega for m in result.modes if m.kind == "oscillating"]


def wait_omega(page: Page, omega: float) -> None:
    """Wait until the modal table shows ω = omega to 6 significant digits."""
    page.wait_for_function(
        """omega => {
        const cell = document.querySelector('#modes tr[data-mode] td.omega:not(:empty)');
        const cells = [...document.querySelectorAll('#modes td.omega')].map(c => parseFloat(c.textContent));
        return cell && cells.some(w => Math.abs(w - omega) <= 5e-6 * omega);
    }""",
        arg=omega,
    )


def field(page: Page, path: str):
    return page.locator(f'#editor input[data-path="{path}"]')


# ------------------------------------------------------------------------------------ tests


def test_loads_with_no_console_error_and_no_request_outside_its_origin(opened: Opened) -> None:
    page = opened.page
    expect(page.locator("#modes tbody tr")).to_have_count(2)
    page.locator("details#derivation summary").click()  # the derivation loads on demand
    expect(page.locator("#derivation-body math").first).to_be_attached(timeout=60_000)
    page.mouse.wheel(0, 20_000)
    next_frames(page)
    opened.check_clean()
    assert any(u.endswith("/vendor/uplot/uPlot.esm.js") for u in opened.requests)
    assert any("/api/simulate" in u for u in opened.requests)


def test_stiffness_slider_changes_omega_to_what_analyze_gives(opened: Opened) -> None:
    page = opened.page
    page.select_option("#preset", "two-cylinders")
    settle(page)
    wait_omega(page, oscillating_omegas(page_system(page))[0])
    positions = page.locator('[data-plot="positions"]')
    revision = int(positions.get_attribute("data-revision"))
    before = page.evaluate(
        "() => document.querySelector('[data-plot=positions] canvas').toDataURL()"
    )
    slider = page.locator('input[type="range"][data-slider-for="springs.0.stiffness"]')
    slider.focus()
    for _ in range(40):
        page.keyboard.press("ArrowRight")
    settle(page)
    system = page_system(page)
    assert system["springs"][0]["stiffness"] != 100.0
    omega = oscillating_omegas(system)[0]
    wait_omega(page, omega)
    shown = float(page.locator("#modes td.omega").nth(1).inner_text())
    assert shown == pytest.approx(omega, rel=5e-6)
    assert int(positions.get_attribute("data-revision")) > revision
    after = page.evaluate(
        "() => document.querySelector('[data-plot=positions] canvas').toDataURL()"
    )
    assert after != before


def test_play_animates_and_pause_freezes(opened: Opened) -> None:
    page = opened.page
    first = canvas_hash(page)
    page.get_by_role("button", name="Play", exact=True).click()
    page.wait_for_function("() => window.rollspringPage.time() > 0.2")
    second = canvas_hash(page)
    page.wait_for_function(
        "t => window.rollspringPage.time() > t + 0.1",
        arg=page.evaluate("() => window.rollspringPage.time()"),
    )
    third = canvas_hash(page)
    assert len({first, second, third}) == 3
    assert len(page.evaluate("() => window.rollspringPage.frameTimes()")) > 2
    page.get_by_role("button", name="Pause", exact=True).click()
    frozen_t = clock(page)
    frozen = canvas_hash(page)
    next_frames(page, 10)
    assert clock(page) == frozen_t
    assert canvas_hash(page) == frozen


def test_step_advances_the_clock_by_exactly_one_dt(opened: Opened) -> None:
    page = opened.page
    dt = page.evaluate("() => window.rollspringPage.dt()")
    assert dt == pytest.approx(10 / 600, rel=1e-12)  # one output interval of the 601 outputs
    before = canvas_hash(page)
    for k in range(1, 4):
        page.get_by_role("button", name="Step", exact=True).click()
        assert clock(page) == pytest.approx(k * dt, abs=1e-12)
        expect(page.locator("#clock")).to_have_text(f"t = {k * dt:.4f} s")
    assert canvas_hash(page) != before


def test_dragging_the_cylinder_2_cm_sets_its_initial_displacement(opened: Opened) -> None:
    page = opened.page
    shown = page.locator("#disp-cylinder")
    expect(shown).to_have_text("0 m")
    px_per_m = float(page.locator("#scene").get_attribute("data-px-per-m"))
    box = page.locator('[data-body="cylinder"]').bounding_box()
    x, y = box["x"] + box["width"] / 2, box["y"] + box["height"] / 2
    page.mouse.move(x, y)
    page.mouse.down()
    page.mouse.move(x + 0.01 * px_per_m, y, steps=4)
    page.mouse.move(x + 0.02 * px_per_m, y, steps=4)
    page.mouse.up()
    expect(shown).to_have_text("+0.02000 m")
    assert float(shown.get_attribute("data-m")) == pytest.approx(0.02, abs=1e-12)
    settle(page)
    assert page_system(page)["bodies"][1]["x"] == pytest.approx(0.51, abs=1e-12)
    expect(field(page, "bodies.1.x")).to_have_value("0.51")
    update = page.evaluate("() => window.rollspringPage.lastUpdate()")
    assert update["drawn"] >= update["changed"]


def test_a_slip_is_announced_at_the_time_simulate_reports(opened: Opened) -> None:
    page = opened.page
    # the hoop launched at 0.3 m/s, the spring at its rest length: the friction the hoop needs
    # grows from 0 to 0.14 N per N, above its μs = 0.1
    for path, value in [
        ("bodies.1.x", "0.5"),
        ("bodies.0.v", "0.3"),
        ("bodies.0.mu_static", "0.1"),
    ]:
        field(page, path).fill(value)
        field(page, path).press("Enter")
    settle(page)
    run = rollspring.simulate(system_from_dict(page_system(page)), 10.0, n_output=601)
    slip = run.summary["first_slip"]
    assert slip is not None and slip["body"] == "hoop" and slip["time"] > 0.01
    alert = page.locator("#alert")
    assert alert.get_attribute("aria-live") == "assertive"
    expect(alert).to_be_empty()
    page.get_by_role("button", name="Play", exact=True).click()
    expect(alert).to_contain_text("hoop starts to slip", timeout=30_000)
    expect(alert).to_contain_text(f"t = {slip['time']:.4f} s")
    expect(page.get_by_role("button", name="Play", exact=True)).to_be_visible()  # it stopped there
    assert clock(page) == pytest.approx(slip["time"], abs=1e-3)


def test_a_shared_link_restores_omega_initial_state_and_frame(
    opened: Opened, browser: Browser, server: str
) -> None:
    page = opened.page
    stiffness = field(page, "springs.0.stiffness")
    stiffness.fill("150")
    stiffness.press("Enter")
    page.locator('[data-body="cylinder"]').focus()
    page.keyboard.press("PageUp")
    settle(page)
    page.get_by_role("button", name="Step", exact=True).click()
    page.get_by_role("button", name="Step", exact=True).click()
    page.get_by_label("spring forces").check()
    page.get_by_role("button", name="Share link").click()
    expect(page.locator("#share-url")).to_have_value(re.compile("#v1[.]"))
    url = page.locator("#share-url").input_value()
    assert url.startswith(server + "/#")
    settle(page)
    next_frames(page)
    shared = {
        "omega": page.locator("#modes td.omega").nth(1).inner_text(),
        "hoop": page.locator("#disp-hoop").inner_text(),
        "cylinder": page.locator("#disp-cylinder").inner_text(),
        "t": clock(page),
        "frame": canvas_hash(page),
    }
    assert shared["cylinder"] == "+0.01000 m"
    fresh = open_page(browser, server, url)
    try:
        other = fresh.page
        wait_omega(other, float(shared["omega"]))
        # every request answered and drawn before the frame is compared (the modal table can
        # be there while the motion is still on its way: the frame then differs)
        settle(other)
        next_frames(other)
        assert other.locator("#modes td.omega").nth(1).inner_text() == shared["omega"]
        assert other.locator("#disp-hoop").inner_text() == shared["hoop"]
        assert other.locator("#disp-cylinder").inner_text() == shared["cylinder"]
        assert clock(other) == shared["t"]
        assert other.get_by_label("spring forces").is_checked()
        assert canvas_hash(other) == shared["frame"]
        assert page_system(other) == page_system(page)
        fresh.check_clean()
    finally:
        fresh.page.close()


def test_bad_input_is_shown_inline_and_the_page_keeps_running(opened: Opened) -> None:
    page = opened.page
    page.locator("details#toml-panel summary").click()
    toml = page.locator("#toml")
    expect(toml).to_have_value(re.compile(re.escape("[[bodies]]")))
    toml.fill("bodies = [\n")
    page.get_by_role("button", name="Apply TOML").click()
    error = page.locator("#toml-error")
    expect(error).to_be_visible()
    assert error.inner_text().strip()
    expect(toml).to_have_attribute("aria-invalid", "true")
    mass = field(page, "bodies.0.mass")
    mass.fill("-1")
    mass.press("Enter")
    settle(page)
    slot = page.locator('#editor [data-error-for="bodies.0.mass"]')
    expect(slot).to_be_visible()
    expect(slot).to_contain_text("must be between 1e-06 and 1e+06 kg")
    expect(mass).to_have_attribute("aria-invalid", "true")
    before = canvas_hash(page)  # the last good motion still plays
    page.get_by_role("button", name="Play", exact=True).click()
    page.wait_for_function("() => window.rollspringPage.time() > 0.1")
    assert canvas_hash(page) != before
    page.get_by_role("button", name="Pause", exact=True).click()
    mass.fill("2")
    mass.press("Enter")
    settle(page)
    expect(slot).to_be_hidden()
    # the two refusals were the only console errors (Chromium logs every 4xx response)
    refused = [e for e in opened.errors if "status of 422" in e]
    assert len(refused) >= 2
    opened.errors[:] = [e for e in opened.errors if e not in refused]


ACCESSIBLE_NAME = """el => {
    const text = s => (s || '').replace(/\\s+/g, ' ').trim();
    if (el.getAttribute('aria-label')) return text(el.getAttribute('aria-label'));
    const by = el.getAttribute('aria-labelledby');
    if (by) return text(by.split(' ').map(id => document.getElementById(id)?.textContent).join(' '));
    if (el.labels && el.labels.length) return text([...el.labels].map(l => l.textContent).join(' '));
    return text(el.textContent || el.title);
}"""

DESCRIBE_FOCUS = """() => {
    const el = document.activeElement;
    if (!el || el === document.body) return null;
    if (!el.dataset.tabWalk) el.dataset.tabWalk = String(Math.random());
    return {key: el.dataset.tabWalk, tag: el.tagName, name: (%s)(el)};
}""".replace("%s", ACCESSIBLE_NAME)

INTERACTIVE = """() => [...document.querySelectorAll(
        'button, select, input, textarea, summary, [tabindex="0"], a[href]')]
    .filter(el => !el.disabled && el.checkVisibility({visibilityProperty: true}))
    .map(el => {
        if (!el.dataset.tabWalk) el.dataset.tabWalk = String(Math.random());
        return {key: el.dataset.tabWalk, tag: el.tagName, name: (%s)(el)};
    })""".replace("%s", ACCESSIBLE_NAME)


def test_every_control_is_reachable_with_tab_labelled_and_operable(opened: Opened) -> None:
    page = opened.page
    controls = page.evaluate(INTERACTIVE)
    assert len(controls) > 30
    unlabelled = [c for c in controls if not c["name"]]
    assert unlabelled == []
    reached: dict[str, dict] = {}
    page.locator("body").focus()
    for _ in range(len(controls) + 20):
        page.keyboard.press("Tab")
        focused = page.evaluate(DESCRIBE_FOCUS)
        if focused is None:
            continue
        if focused["key"] in reached:
            break
        reached[focused["key"]] = focused
    missing = [c for c in controls if c["key"] not in reached]
    assert missing == []
    assert all(c["name"] for c in reached.values())
    # operate a few with the keyboard alone
    handle = page.locator('[data-body="cylinder"]')
    handle.focus()
    page.keyboard.press("ArrowRight")
    expect(page.locator("#disp-cylinder")).to_have_text("+0.001000 m")
    page.keyboard.press("PageDown")
    expect(page.locator("#disp-cylinder")).to_have_text("−0.009000 m")
    assert handle.get_attribute("aria-valuenow") == "-0.009"
    page.keyboard.press("Home")
    expect(page.locator("#disp-cylinder")).to_have_text("0 m")
    settle(page)
    page.get_by_role("button", name="Play", exact=True).focus()
    page.keyboard.press("Enter")
    page.wait_for_function("() => window.rollspringPage.time() > 0.05")
    page.keyboard.press("Space")
    expect(page.get_by_role("button", name="Play", exact=True)).to_be_visible()
    page.locator("#time").focus()
    page.keyboard.press("End")
    assert clock(page) == pytest.approx(10.0)
    page.locator("#show-normal").focus()
    page.keyboard.press("Space")
    assert page.locator("#show-normal").is_checked()


@pytest.mark.parametrize("name, viewport", [("laptop-1280x800", LAPTOP), ("phone-390x844", PHONE)])
def test_screenshots(
    browser: Browser, server: str, tmp_path: Path, name: str, viewport: dict
) -> None:
    seen = open_page(browser, server, viewport=viewport)
    page = seen.page
    try:
        page.get_by_label("friction", exact=True).check()
        page.get_by_label("normal forces").check()
        for _ in range(20):
            page.get_by_role("button", name="Step", exact=True).click()
        width = page.evaluate("() => document.documentElement.scrollWidth")
        assert width <= viewport["width"], "no horizontal scrolling"
        path = tmp_path / f"web-page-{name}.png"
        page.screenshot(path=str(path), full_page=True)
        assert path.stat().st_size > 10_000
        shots = REPO / "build" / "screenshots"
        shots.mkdir(parents=True, exist_ok=True)
        shutil.copy(path, shots / path.name)
        seen.check_clean()
    finally:
        page.close()


@pytest.mark.parametrize("name, viewport", [("laptop-1280x800", LAPTOP), ("phone-390x844", PHONE)])
def test_the_papers_claims_are_mathml_and_their_table_never_widens_the_page(
    browser: Browser, server: str, name: str, viewport: dict
) -> None:
    from rollspring.service.documents import figure_claims

    seen = open_page(browser, server, viewport=viewport)
    page = seen.page
    try:
        figure = figure_claims(system_from_dict(page_system(page)))
        assert figure is not None, "the page opens on one of the paper's systems"
        checks = figure[1]
        page.locator("details#derivation summary").click()
        table = page.locator("#derivation-body table.claims")
        expect(table).to_be_visible(timeout=60_000)
        table.scroll_into_view_if_needed()
        next_frames(page)
        assert table.locator("tbody tr").count() == len(checks) >= 20
        quoted_math = 0
        for check in checks:
            row = table.locator(f'tbody tr[data-claim="{check.claim.key}"]')
            assert row.locator(".claim-math math").count() == 1, check.claim.key
            assert row.locator(".correction math").count() == (1 if check.correction else 0)
            in_quote = row.locator("q.quote math").count()
            if re.search(r"\$|\\[(\[]|\\(?:begin|end)\{|[_^=]", check.claim.quote):
                assert in_quote >= 1, check.claim.key
            quoted_math += in_quote
        assert quoted_math >= len(checks) // 2
        # rendered as MathML (laid out by Chromium, in its namespace), no LaTeX left as text
        maths = page.evaluate(
            "[...document.querySelectorAll('table.claims math')].map(m => "
            "[m.namespaceURI, m.getBoundingClientRect().width])"
        )
        assert all(ns == "http://www.w3.org/1998/Math/MathML" and w > 0 for ns, w in maths)
        text = table.evaluate(VISIBLE_TEXT)
        assert "$" not in text and re.search(r"\\[A-Za-z]", text) is None
        assert page.locator("table.claims .tex-source").count() == 0
        # the page never widens: the table wraps, or scrolls sideways inside its own box
        box = page.locator("#derivation-body .claims-scroll")
        widths = page.evaluate(
            "box => [document.documentElement.scrollWidth, window.innerWidth,"
            " box.scrollWidth, box.clientWidth]",
            box.element_handle(),
        )
        page_width, inner_width, table_width, box_width = widths
        assert page_width <= inner_width
        hint = page.locator("#derivation-body .scroll-hint")
        if viewport is PHONE:
            assert table_width > box_width  # it scrolls inside, and says so
            expect(hint).to_be_visible()
            assert box.get_attribute("data-overflowing") == "true"
            box.evaluate("b => { b.scrollLeft = b.scrollWidth; }")
            next_frames(page)
            assert page.evaluate("() => document.documentElement.scrollWidth") <= inner_width
        else:
            assert table_width <= box_width  # wide enough: it wraps, with no scroll bar
            expect(hint).to_be_hidden()
        seen.check_clean()
    finally:
        page.close()

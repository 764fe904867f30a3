"""The page on a phone and for every user (issue 26, point 6 and the accessibility acceptance),
in a real browser against the real server: at 390×844 the animation stays in view (sticky) while
the controls scroll, every tap target is at least 44 px, wide tables fit or scroll in a marked box;
the chain presets' body labels never overlap (at both sizes); axe-core finds no serious or
critical violation at 1280×800 or 390×844 with every panel open; no horizontal page overflow.

axe-core is the npm package pinned in the page's package.json (a dev dependency, installed by
``npm ci``), injected into the page by the test; the server does not serve it."""

from __future__ import annotations

import json
import re
from itertools import combinations
from pathlib import Path

import pytest
import requests
from playwright.sync_api import Browser, Page, expect

from tests.test_web_page import LAPTOP, PHONE, Opened, open_page, page_system, settle

STATIC = Path(__file__).resolve().parents[1] / "src" / "rollspring" / "web" / "static"
AXE = STATIC / "node_modules" / "axe-core" / "axe.min.js"
CHAINS = ["chain-diatomic", "chain-monatomic"]
#: The smallest tap target (CSS px), WCAG 2.5.5 and Apple's and Google's guides.
TAP = 44


def next_frames(page: Page, n: int = 2) -> None:
    """Let the browser lay out and paint n frames (resize observers run before each paint)."""
    page.evaluate(
        "n => new Promise(done => { const go = k => k ? requestAnimationFrame(() => go(k - 1)) "
        ": done(); go(n); })",
        n,
    )


def open_everything(page: Page) -> None:
    """Every panel open (the derivation, with the paper's claims; the system file; the three
    "Why?" explanations, with their snap buttons) and every view option ticked, as wide as the
    page gets."""
    for box in page.locator(".view-options input[type=checkbox]").all():
        box.check()
        settle(page)
    for panel in ("derivation", "toml-panel", "why-xhat", "why-cm", "why-percussion"):
        page.locator(f"details#{panel} > summary").click()
    expect(page.locator("#derivation-body table.claims")).to_have_count(1, timeout=120_000)
    expect(page.locator("#toml")).not_to_have_value("", timeout=30_000)
    settle(page)
    next_frames(page)


def no_horizontal_overflow(page: Page) -> None:
    width, inner = page.evaluate("() => [document.documentElement.scrollWidth, window.innerWidth]")
    assert width <= inner


def rect(page: Page, selector: str) -> dict:
    return page.evaluate(
        "s => document.querySelector(s).getBoundingClientRect().toJSON()", selector
    )


# ------------------------------------------------------------------ the animation stays in view


#: Scroll `el` into view as asked, or focus it (the browser scrolls it into view); its box and
#: the animation's (scene and strip), the page's scroll position and the viewport's height.
SCROLL_TO = """([selector, how]) => {
    const el = document.querySelector(selector);
    window.scrollTo(0, 0);
    if (how === 'focus') el.focus(); else el.scrollIntoView({block: how});
    const box = e => e.getBoundingClientRect().toJSON();
    return {el: box(el), scene: box(document.querySelector('#scene')),
            strip: box(document.querySelector('#strip')), scrolled: window.scrollY,
            height: window.innerHeight};
}"""

CONTROLS = [
    '#editor input[type="range"]',  # the first slider of the editor
    "#editor .add",  # the end of the editor
    "#show-absolute",  # the plots
    "#amplitude",  # the modes
    "#apply-toml",  # the end of the page (in the system-file panel)
]


def test_the_animation_stays_in_view_while_the_controls_scroll(phone: Opened) -> None:
    page = phone.page
    page.locator("details#toml-panel > summary").click()
    settle(page)
    for selector in CONTROLS:
        for how in ("start", "center", "end", "focus"):
            seen = page.evaluate(SCROLL_TO, [selector, how])
            # the page scrolled to the control, a screen or more below the animation ...
            assert seen["scrolled"] > 300, (selector, how)
            # ... and the animation, scene and strip, is still wholly on screen at the top
            for part in ("scene", "strip"):
                assert seen[part]["top"] >= 0 and seen[part]["bottom"] <= seen["height"]
            assert seen["scene"]["top"] <= 1
            # with the control below it, in view, never under it
            # (to half a pixel: scrolling rounds to device pixels)
            assert seen["el"]["top"] >= seen["strip"]["bottom"] - 0.5, (selector, how)
            assert seen["el"]["bottom"] <= seen["height"] + 0.5, (selector, how)
    # the animation takes well under half the screen
    assert seen["strip"]["bottom"] <= 0.4 * seen["height"]


def test_the_animation_scrolls_with_the_page_on_a_laptop(browser: Browser, server: str) -> None:
    seen = open_page(browser, server)
    page = seen.page
    top = rect(page, "#scene")["top"]
    page.evaluate("() => document.querySelector('#modes').scrollIntoView({block: 'start'})")
    assert page.evaluate("() => window.scrollY") > 100
    # the two-column layout keeps its order: the animation scrolls away like the rest
    assert rect(page, "#scene")["top"] < top - 100
    seen.check_clean()
    page.close()


# --------------------------------------------------------------------------------- tap targets

#: Every control's tap target (CSS px): its own box, a checkbox's or a file input's the label
#: that holds it (a tap on the label toggles it). Boxes focusable only to be scrolled sideways
#: (data-overflowing) are not tap targets.
TARGETS = """() => {
    const found = [];
    const selector = 'button, select, input, textarea, summary, a[href], [role="slider"], '
        + '[tabindex]:not([tabindex="-1"]):not([data-overflowing])';
    for (const el of document.querySelectorAll(selector)) {
        const style = getComputedStyle(el);
        let box = el.getBoundingClientRect();
        if (el.closest('[hidden], .visually-hidden') || style.visibility === 'hidden'
            || (box.width === 0 && box.height === 0)) continue;
        if (['checkbox', 'radio', 'file'].includes(el.type)) {
            const label = el.closest('label')
                || (el.id && document.querySelector(`label[for="${el.id}"]`));
            if (label) box = label.getBoundingClientRect();
        }
        const kind = el.type || el.getAttribute('role') || '';
        found.push({what: `${el.tagName.toLowerCase()}#${el.id}[${kind}]`
                          + ` ${el.dataset.path || el.textContent.trim().slice(0, 30)}`,
                    width: box.width, height: box.height});
    }
    return found;
}"""


def test_every_tap_target_is_at_least_44_px_on_a_phone(phone: Opened) -> None:
    page = phone.page
    open_everything(page)
    targets = page.evaluate(TARGETS)
    kinds = {re.sub(r"#.*\[", "[", t["what"]).split(" ")[0] for t in targets}
    # buttons, selects, text boxes, sliders, checkboxes, the file input, the panels' summaries,
    # the body handles: all measured
    for kind in (
        "button[button]",
        "select[select-one]",
        "input[text]",
        "input[range]",
        "input[checkbox]",
        "input[file]",
        "summary[]",
        "div[slider]",
        "textarea[textarea]",
    ):
        assert kind in kinds
    small = [t for t in targets if t["width"] < TAP or t["height"] < TAP]
    assert small == []
    # the controls of issue 26, point 5, among them
    ids = {t["what"].split("[")[0] for t in targets}
    for control in ("button#step-back", "button#reset-all", "button#keys-help", "input#duration"):
        assert control in ids
    no_horizontal_overflow(page)
    # the shortcut dialog, open: its Close button too
    page.locator("#keys-help").click()
    expect(page.get_by_role("dialog", name="Keyboard shortcuts")).to_be_visible()
    in_dialog = [t for t in page.evaluate(TARGETS) if t["what"].startswith("button#[button] Close")]
    assert len(in_dialog) == 1
    assert in_dialog[0]["width"] >= TAP and in_dialog[0]["height"] >= TAP


def test_targets_stay_compact_on_a_laptop(sized: Opened) -> None:
    """The 44 px rule is for narrow and touch screens: the laptop keeps its compact controls."""
    page = sized.page
    heights = {t["what"]: t["height"] for t in page.evaluate(TARGETS)}
    checkbox = next(h for w, h in heights.items() if w.startswith("input#show-spring"))
    if page.viewport_size == LAPTOP:
        assert checkbox < TAP
    else:
        assert checkbox >= TAP


# -------------------------------------------------------------------------------------- tables

#: Each table: its width, its scrolling box's (the nearest ancestor that scrolls sideways) and
#: that box's cue: marked overflowing, focusable, the hint before it shown.
TABLES = """() => [...document.querySelectorAll('table')].filter(t => t.offsetParent).map(t => {
    let box = t.parentElement;
    const scrolls = e => ['auto', 'scroll'].includes(getComputedStyle(e).overflowX);
    while (box && !scrolls(box)) box = box.parentElement;
    const hint = box && box.parentElement.querySelector('.scroll-hint');
    return {id: t.id || t.className, width: t.getBoundingClientRect().width,
            room: (box || t.parentElement).clientWidth,
            box: box ? {overflowing: box.dataset.overflowing, tabIndex: box.tabIndex,
                        name: box.getAttribute('aria-label'),
                        right: box.getBoundingClientRect().right} : null,
            hint: hint ? {hidden: hint.hidden, height: hint.getBoundingClientRect().height,
                          text: hint.textContent} : null};
})"""


def test_wide_tables_fit_or_scroll_in_a_box_with_a_visible_cue(sized: Opened) -> None:
    page = sized.page
    open_everything(page)
    tables = page.evaluate(TABLES)
    # the modes, the paper's claims and each plot's legend
    assert {"modes", "claims"} <= {t["id"] for t in tables}
    assert len(tables) >= 2 + page.locator(".plot").count()
    wide = [t for t in tables if t["width"] > t["room"] + 1]
    for t in tables:
        if t in wide:
            box = t["box"]
            assert box is not None, t
            # a visible cue: the box is marked (its shadows and edges) and the hint is shown
            assert box["overflowing"] == "true"
            assert box["tabIndex"] == 0 and box["name"]
            assert box["right"] <= page.viewport_size["width"]
            assert t["hint"] is not None and not t["hint"]["hidden"] and t["hint"]["height"] > 0
            assert "sideways" in t["hint"]["text"]
        elif t["box"] is not None and t["hint"] is not None:
            assert t["hint"]["hidden"]  # no cue when nothing is hidden
    if page.viewport_size == PHONE:
        # the modes table (7 columns) is wider than a phone: the cue is there, and every
        # "Play mode" button stays in view at the box's right edge
        assert "modes" in {t["id"] for t in wide}
        buttons = page.locator("#modes button")
        assert buttons.count() >= 1
        for button in buttons.all():
            box = button.bounding_box()
            assert box is not None
            assert box["x"] >= 0 and box["x"] + box["width"] <= PHONE["width"]
        # a tap on the visible button plays the mode
        buttons.first.click()
        settle(page)
        expect(page.locator("#initial")).to_contain_text("Starting at rest along mode 2")
    no_horizontal_overflow(page)


# ------------------------------------------------------------------------- chain body labels

#: What the scene drew at every 30th output time: the body labels' boxes and the canvas width.
LABELS = """() => {
    const page = window.rollspringPage;
    const slider = document.querySelector('#time');
    const dt = page.dt();
    const n = Math.round(Number(slider.max) / dt);
    const frames = [];
    for (let k = 0; k <= n; k += 30) {
        slider.value = String(k * dt);
        slider.dispatchEvent(new Event('input'));
        frames.push(page.drawn().bodyLabels);
    }
    return {frames, width: document.querySelector('#scene').getBoundingClientRect().width};
}"""


def overlap(a: dict, b: dict) -> bool:
    return (
        a["x"] < b["x"] + b["w"]
        and b["x"] < a["x"] + a["w"]
        and a["y"] < b["y"] + b["h"]
        and b["y"] < a["y"] + a["h"]
    )


@pytest.mark.parametrize("preset", CHAINS)
def test_chain_body_labels_never_overlap(sized: Opened, preset: str) -> None:
    page = sized.page
    page.select_option("#preset", preset)
    settle(page)
    ids = [b["id"] for b in page_system(page)["bodies"]]
    assert len(ids) == 8
    drawn = page.evaluate(LABELS)
    assert len(drawn["frames"]) == 21
    for labels in drawn["frames"]:
        # every body labelled once, with its id or its short form ("cylinder8" → "c8")
        assert sorted(label["id"] for label in labels) == sorted(ids)
        for label in labels:
            assert label["text"] == label["id"] or label["text"] == label["id"][0] + re.sub(
                r"^\D+", "", label["id"]
            )
            # on the canvas, over its body (or at the canvas's edge)
            assert label["y"] >= 0
            assert 0 <= label["x"] and label["x"] + label["w"] <= drawn["width"] + 1e-9
            assert label["x"] <= label["cx"] <= label["x"] + label["w"] or label["x"] in (
                0,
                pytest.approx(drawn["width"] - label["w"]),
            )
        # and no two overlap
        clashes = [(a["id"], b["id"]) for a, b in combinations(labels, 2) if overlap(a, b)]
        assert clashes == []
    # at the start, every label its full name: on one row on a laptop; a phone's chain is too
    # dense for one row, so some labels are raised
    first = drawn["frames"][0]
    assert all(label["text"] == label["id"] for label in first)
    rows = len({round(label["y"], 6) for label in first})
    assert rows == 1 if page.viewport_size == LAPTOP else rows >= 2
    no_horizontal_overflow(page)


def test_labels_of_a_sparse_system_stay_on_one_row(sized: Opened) -> None:
    page = sized.page
    labels = page.evaluate("() => window.rollspringPage.drawn().bodyLabels")
    assert {label["id"] for label in labels} == {"hoop", "cylinder"}
    assert all(label["text"] == label["id"] for label in labels)
    # each right over its body: the same row above bodies of the same size (both R = 0.1 m)
    assert len({round(label["y"], 6) for label in labels}) == 1


# ----------------------------------------------------------------------------------- axe-core


def axe_violations(page: Page) -> list[dict]:
    assert AXE.is_file(), f"{AXE} is missing: run `make` (npm ci in {STATIC})"
    page.add_script_tag(path=str(AXE))
    return page.evaluate(
        """async () => {
        const result = await axe.run(document, {resultTypes: ['violations']});
        return result.violations.map(v => ({id: v.id, impact: v.impact, help: v.help,
            nodes: v.nodes.map(n => n.target.join(' '))}));
    }"""
    )


def serious(violations: list[dict]) -> list[dict]:
    return [v for v in violations if v["impact"] in ("serious", "critical")]


def test_axe_core_finds_no_serious_or_critical_violation(sized: Opened) -> None:
    page = sized.page
    assert serious(axe_violations(page)) == []
    open_everything(page)
    assert serious(axe_violations(page)) == []
    no_horizontal_overflow(page)
    # with a bad run length shown at its box, and with the shortcut dialog open
    page.locator("#duration").fill("0")
    page.locator("#duration").press("Enter")
    expect(page.locator("#duration-error")).to_be_visible()
    page.locator("#keys-help").click()
    expect(page.get_by_role("dialog", name="Keyboard shortcuts")).to_be_visible()
    assert serious(axe_violations(page)) == []
    no_horizontal_overflow(page)


@pytest.mark.parametrize("preset", CHAINS)
def test_axe_core_on_the_chain_presets(phone: Opened, preset: str) -> None:
    page = phone.page
    page.select_option("#preset", preset)
    settle(page)
    next_frames(page)
    assert serious(axe_violations(page)) == []
    no_horizontal_overflow(page)


def test_axe_core_is_pinned_exactly_and_installed_from_the_lock_file() -> None:
    package = json.loads((STATIC / "package.json").read_text())
    lock = json.loads((STATIC / "package-lock.json").read_text())
    version = package["devDependencies"]["axe-core"]
    assert re.fullmatch(r"\d+\.\d+\.\d+", version)  # exact: no range
    assert lock["packages"]["node_modules/axe-core"]["version"] == version
    assert lock["packages"]["node_modules/axe-core"]["dev"] is True
    installed = json.loads((STATIC / "node_modules" / "axe-core" / "package.json").read_text())
    assert installed["version"] == version


def test_the_server_does_not_serve_node_modules(server: str) -> None:
    def status(path: str) -> int:
        return requests.get(server + path, timeout=30).status_code

    assert status("/static/node_modules/axe-core/axe.min.js") == 404
    assert status("/static/node_modules/uplot/dist/uPlot.esm.js") == 404
    # the page's own files and its uPlot still are
    assert status("/vendor/uplot/uPlot.esm.js") == 200
    assert status("/static/js/scrollbox.js") == 200

"""The page's controls people expect (issue 26, point 5), in a real browser against the real
server: Step back, Reset all, the run length (validated at its box, in the shared link), the
play/pause and step keys (not while typing), the keyboard-shortcut help dialog, and plot legends
that show each series' line as drawn (dash and width).

Nothing here waits on wall-clock time: every wait is for a condition in the page."""

from __future__ import annotations

import re

import pytest
import requests
from playwright.sync_api import Browser, Page, expect

from tests.test_web_page import Opened, clock, field, next_frames, open_page, page_system, settle

VIEW_OPTIONS = [
    "show-spring",
    "show-friction",
    "show-normal",
    "show-values",
    "show-markers",
    "show-linear",
    "show-dots",
    "continue-slip",
    "show-absolute",
]


def button(page: Page, name: str):
    return page.get_by_role("button", name=name, exact=True)


def playing(page: Page) -> bool:
    return button(page, "Pause").count() == 1


def view_state(page: Page) -> dict:
    return {
        "boxes": {name: page.locator(f"#{name}").is_checked() for name in VIEW_OPTIONS},
        "arrow-scale": page.locator("#arrow-scale").input_value(),
        "speed": page.locator("#speed").input_value(),
        "duration": page.locator("#duration").input_value(),
        "px per N": page.evaluate("() => window.rollspringPage.drawn().forceScale"),
    }


def run_end(page: Page) -> float:
    return page.evaluate("() => window.rollspringPage.plotData('positions').data[0].at(-1)")


def set_duration(page: Page, text: str) -> dict:
    """Type a run length and commit it; the /api/simulate request and answer it causes."""
    with page.expect_response(lambda r: r.url.endswith("/api/simulate")) as answer:
        page.locator("#duration").fill(text)
        page.locator("#duration").press("Enter")
    settle(page)
    return {"request": answer.value.request.post_data_json, "t": answer.value.json()["t"]}


# ------------------------------------------------------------------------------------ step back


def test_step_back_returns_to_the_previous_output_time_and_not_below_0(opened: Opened) -> None:
    page = opened.page
    times = page.evaluate("() => window.rollspringPage.plotData('positions').data[0]")
    expect(button(page, "Step back")).to_be_visible()
    button(page, "Step back").click()  # at t = 0: stays there
    assert clock(page) == 0
    for _ in range(3):
        button(page, "Step").click()
    assert clock(page) == pytest.approx(times[3], abs=1e-12)
    button(page, "Step back").click()
    assert clock(page) == pytest.approx(times[2], abs=1e-12)
    expect(page.locator("#clock")).to_have_text(f"t = {times[2]:.4f} s")
    button(page, "Step back").click()
    button(page, "Step back").click()
    assert clock(page) == 0
    button(page, "Step back").click()
    assert clock(page) == 0
    # paused anywhere (between two output times, or on one): back to the output time before
    button(page, "Play").click()
    page.wait_for_function("() => window.rollspringPage.time() > 0.3")
    button(page, "Pause").click()
    paused = clock(page)
    button(page, "Step back").click()
    before = max(t for t in times if t < paused - 1e-9)
    assert clock(page) == pytest.approx(before, abs=1e-12)


# ------------------------------------------------------------------------------------ reset all


def test_reset_all_restores_the_preset_view_scales_and_t_0(opened: Opened, server: str) -> None:
    page = opened.page
    preset = next(
        p for p in requests.get(server + "/api/presets").json() if p["name"] == "hoop-cylinder"
    )
    loaded = view_state(page)
    assert page_system(page) == preset["system"]
    # edit everything
    stiffness = field(page, "springs.0.stiffness")
    stiffness.fill("150")
    stiffness.press("Enter")
    settle(page)
    for name in ("show-spring", "show-values", "show-absolute"):
        page.locator(f"#{name}").check()
    page.locator("#show-markers").uncheck()
    page.select_option("#arrow-scale", "4")
    page.select_option("#speed", "2")
    set_duration(page, "4")
    button(page, "Step").click()
    button(page, "Step").click()
    edited = view_state(page)
    assert edited != loaded
    assert page_system(page) != preset["system"]
    assert clock(page) > 0
    expect(page.locator("#preset")).to_have_value("")  # "(edited) …"
    button(page, "Play").click()
    page.wait_for_function("() => window.rollspringPage.time() > 0.1")

    button(page, "Reset all").click()
    settle(page)
    assert page_system(page) == preset["system"]
    assert view_state(page) == loaded
    assert clock(page) == 0
    assert not playing(page)
    expect(page.locator("#preset")).to_have_value("hoop-cylinder")
    assert run_end(page) == pytest.approx(10, abs=1e-12)
    next_frames(page, 3)
    assert clock(page) == 0  # paused


# ----------------------------------------------------------------------------------- run length


def test_the_run_length_sets_the_computed_duration(opened: Opened) -> None:
    page = opened.page
    expect(page.get_by_label("Run length (s)")).to_have_value("10")
    assert run_end(page) == pytest.approx(10, abs=1e-12)
    sent = set_duration(page, "4")
    assert sent["request"]["duration"] == 4
    assert sent["t"][-1] == pytest.approx(4, abs=1e-12)
    assert run_end(page) == pytest.approx(4, abs=1e-12)
    assert page.locator("#time").get_attribute("max") == "4"
    expect(page.locator("#status")).to_contain_text("Computed 4.000 s")
    sent = set_duration(page, "25.5")
    assert sent["t"][-1] == pytest.approx(25.5, abs=1e-12)
    assert sent["request"]["outputs"] == 60 * 25.5 + 1  # one output every 1/60 s, as at 10 s


@pytest.mark.parametrize(
    ("text", "message"),
    [("abc", "must be a number of seconds"), ("0.5", "from 1 s to 60 s"), ("601", "not 601")],
)
def test_a_bad_run_length_is_shown_at_its_box_and_cleared_when_fixed(
    opened: Opened, text: str, message: str
) -> None:
    page = opened.page
    box = page.locator("#duration")
    error = page.locator("#duration-error")
    expect(error).to_be_hidden()
    requests_before = len([u for u in opened.requests if u.endswith("/api/simulate")])
    box.fill(text)
    box.press("Enter")
    expect(error).to_be_visible()
    expect(error).to_contain_text(message)
    expect(box).to_have_attribute("aria-invalid", "true")
    assert "duration-error" in (box.get_attribute("aria-describedby") or "")
    # nothing is sent: the motion shown stays the last one computed
    settle(page)
    assert len([u for u in opened.requests if u.endswith("/api/simulate")]) == requests_before
    assert run_end(page) == pytest.approx(10, abs=1e-12)
    # error placed next to the box, not at the top of the page
    box_y = box.bounding_box()["y"]
    error_y = error.bounding_box()["y"]
    assert 0 < error_y - box_y < 120
    sent = set_duration(page, "3")
    assert sent["t"][-1] == pytest.approx(3, abs=1e-12)
    expect(error).to_be_hidden()
    expect(box).not_to_have_attribute("aria-invalid", "true")


def test_the_run_length_survives_a_shared_link(
    opened: Opened, browser: Browser, server: str
) -> None:
    page = opened.page
    set_duration(page, "6")
    button(page, "Step").click()
    button(page, "Share link").click()
    expect(page.locator("#share-url")).to_have_value(re.compile("#v1[.]"))
    url = page.locator("#share-url").input_value()
    shared_t = clock(page)
    other = open_page(browser, server, url)
    try:
        expect(other.page.locator("#duration")).to_have_value("6")
        assert run_end(other.page) == pytest.approx(6, abs=1e-12)
        assert other.page.locator("#time").get_attribute("max") == "6"
        assert clock(other.page) == pytest.approx(shared_t, abs=1e-12)
        other.check_clean()
    finally:
        other.page.close()


# ----------------------------------------------------------------------------- keyboard, help


@pytest.mark.parametrize("key", ["Space", "k"])
def test_the_play_pause_key_toggles_playback(opened: Opened, key: str) -> None:
    page = opened.page
    page.locator("h1").click()  # the focus on the page, in no control
    page.keyboard.press(key)
    page.wait_for_function("() => window.rollspringPage.time() > 0.1")
    assert playing(page)
    page.keyboard.press(key)
    expect(button(page, "Play")).to_be_visible()
    frozen = clock(page)
    next_frames(page, 5)
    assert clock(page) == frozen
    assert frozen > 0


def test_keys_do_nothing_while_typing_in_a_field(opened: Opened) -> None:
    page = opened.page
    box = page.locator("#amplitude")
    box.fill("")
    box.press("k")
    box.press("Space")
    box.press(".")
    box.press("?")
    expect(box).to_have_value("k .?")
    assert not playing(page)
    assert clock(page) == 0
    expect(page.get_by_role("dialog")).to_have_count(0)
    box.fill("0.01")


def test_step_keys_move_the_clock_by_one_output_interval(opened: Opened) -> None:
    page = opened.page
    times = page.evaluate("() => window.rollspringPage.plotData('positions').data[0]")
    page.locator("h1").click()
    page.keyboard.press(".")
    page.keyboard.press(".")
    assert clock(page) == pytest.approx(times[2], abs=1e-12)
    page.keyboard.press(",")
    assert clock(page) == pytest.approx(times[1], abs=1e-12)
    page.keyboard.press("0")
    assert clock(page) == 0


def test_the_shortcut_help_opens_with_question_mark_and_escape_returns_focus(
    opened: Opened,
) -> None:
    page = opened.page
    button(page, "Step").focus()
    page.keyboard.press("?")
    dialog = page.get_by_role("dialog", name="Keyboard shortcuts")
    expect(dialog).to_be_visible()
    assert page.evaluate("() => document.activeElement.closest('dialog')?.id") == "shortcuts"
    listed = dialog.locator("dt").all_inner_texts()
    for keys in ("Space or K", ",", ".", "?"):
        assert keys in listed
    page.keyboard.press("Escape")
    expect(dialog).to_be_hidden()
    assert page.evaluate("() => document.activeElement.id") == "step"
    # the visible button opens it too; Close closes it and the focus goes back to the button
    button(page, "Keyboard shortcuts (?)").click()
    expect(dialog).to_be_visible()
    dialog.get_by_role("button", name="Close").click()
    expect(dialog).to_be_hidden()
    assert page.evaluate("() => document.activeElement.id") == "keys-help"
    assert clock(page) == 0 and not playing(page)  # "?" and Escape did nothing else


# --------------------------------------------------------------------------------------- legends

LEGEND = """key => [...document.querySelectorAll(`[data-plot="${key}"] .u-legend .u-series`)]
    .slice(1).map(row => {
        const marker = row.querySelector('.u-marker');
        const line = marker.querySelector('svg line');
        const box = marker.getBoundingClientRect();
        return {label: row.querySelector('.u-label').textContent,
                dash: line ? line.getAttribute('stroke-dasharray') : null,
                width: line ? Number(line.getAttribute('stroke-width')) : null,
                stroke: line ? line.getAttribute('stroke') : null,
                box: [box.width, box.height]};
    })"""


@pytest.mark.parametrize("key", ["positions", "newton", "forces", "ratio", "energy"])
def test_legends_show_each_series_line_as_drawn(opened: Opened, key: str) -> None:
    page = opened.page
    plotted = page.evaluate("k => window.rollspringPage.plotData(k)", key)
    legend = page.evaluate(LEGEND, key)
    assert [entry["label"] for entry in legend] == plotted["labels"]
    for entry, style in zip(legend, plotted["styles"], strict=True):
        assert entry["dash"] == (" ".join(str(d) for d in style["dash"]) or "none")
        assert entry["width"] == style["width"]
        assert entry["stroke"] == style["stroke"]
        assert entry["box"][0] > 10 and entry["box"][1] > 0
    if key == "positions":
        by_label = {entry["label"]: entry for entry in legend}
        assert by_label["X̂"]["dash"] == "10 5" and by_label["X̂"]["width"] == 3.5
        assert by_label["CM"]["dash"] == "none" and by_label["CM"]["width"] == 3.5


# ------------------------------------------------------------------------------------ zoom


def test_dragging_across_a_plot_zooms_every_plot_to_that_time_window(opened: Opened) -> None:
    page = opened.page
    keys = ["positions", "newton", "forces", "ratio", "energy"]
    whole = button(page, "Show the whole run")
    expect(whole).to_be_disabled()
    for key in keys:
        assert page.evaluate("k => window.rollspringPage.plotWindow(k)", key) == [0, 10]
    over = page.locator('[data-plot="positions"] .u-over')
    over.scroll_into_view_if_needed()
    box = over.bounding_box()
    y = box["y"] + box["height"] / 2
    page.mouse.move(box["x"] + box["width"] * 0.2, y)
    page.mouse.down()
    page.mouse.move(box["x"] + box["width"] * 0.35, y, steps=4)
    page.mouse.move(box["x"] + box["width"] * 0.5, y, steps=4)
    page.mouse.up()
    window = page.evaluate("() => window.rollspringPage.plotWindow('positions')")
    # about 2 s to 5 s of the 10 s run (the cursor lands on whole pixels)
    assert window[0] == pytest.approx(2, abs=0.05)
    assert window[1] == pytest.approx(5, abs=0.05)
    for key in keys:
        assert page.evaluate("k => window.rollspringPage.plotWindow(k)", key) == window
    assert clock(page) == 0  # a drag zooms; it does not move the clock
    expect(whole).to_be_enabled()
    # a click still moves the clock, within the window shown
    page.mouse.click(box["x"] + box["width"] / 2, y)
    assert window[0] < clock(page) < window[1]
    # an edit keeps the window
    stiffness = field(page, "springs.0.stiffness")
    stiffness.fill("150")
    stiffness.press("Enter")
    settle(page)
    assert page.evaluate("() => window.rollspringPage.plotWindow('energy')") == window
    whole.click()
    for key in keys:
        assert page.evaluate("k => window.rollspringPage.plotWindow(k)", key) == [0, 10]
    expect(whole).to_be_disabled()
    # Reset all shows the whole run too
    page.mouse.move(box["x"] + box["width"] * 0.2, y)
    page.mouse.down()
    page.mouse.move(box["x"] + box["width"] * 0.5, y, steps=4)
    page.mouse.up()
    assert page.evaluate("() => window.rollspringPage.plotWindow('ratio')") != [0, 10]
    button(page, "Reset all").click()
    settle(page)
    assert page.evaluate("() => window.rollspringPage.plotWindow('ratio')") == [0, 10]


# ------------------------------------------------------------------------- choosing the lines


def test_a_plots_lines_can_be_chosen_and_stay_chosen_through_edits(opened: Opened) -> None:
    page = opened.page
    figure = page.locator('[data-plot="positions"]')
    plotted = page.evaluate("() => window.rollspringPage.plotData('positions')")
    assert all(plotted["shown"])
    figure.get_by_text("Lines shown").click()
    boxes = figure.locator(".plot-lines input[type=checkbox]")
    expect(boxes).to_have_count(len(plotted["labels"]))
    figure.get_by_label("hoop", exact=True).uncheck()
    shown = page.evaluate("() => window.rollspringPage.plotData('positions').shown")
    assert shown == [label != "hoop" for label in plotted["labels"]]
    uplot = "() => [...document.querySelectorAll('[data-plot=positions] .u-legend .u-series')]" + (
        ".slice(1).map(r => !r.classList.contains('u-off'))"
    )
    assert page.evaluate(uplot) == shown  # the legend greys it out as uPlot hides it
    stiffness = field(page, "springs.0.stiffness")
    stiffness.fill("150")
    stiffness.press("Enter")
    settle(page)
    assert page.evaluate("() => window.rollspringPage.plotData('positions').shown") == shown
    figure.get_by_label("hoop", exact=True).check()
    assert all(page.evaluate("() => window.rollspringPage.plotData('positions').shown"))
    assert all(page.evaluate(uplot))
    # Reset all shows every line again
    figure.get_by_label("CM", exact=True).uncheck()
    assert not all(page.evaluate("() => window.rollspringPage.plotData('positions').shown"))
    button(page, "Reset all").click()
    settle(page)
    assert all(page.evaluate("() => window.rollspringPage.plotData('positions').shown"))
    expect(figure.get_by_label("CM", exact=True)).to_be_checked()

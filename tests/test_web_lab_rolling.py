"""Rolling resistance on the page, in Debian's Chromium against the real server: each rolling
body's C_rr slider changes the system the page sends; the energy plotted decays; the energy
dissipated the page shows is the engine's (:func:`rollspring.simulate` on the same system, as
the server runs it) to 1e-9; each body coming to rest under it is listed at the engine's time;
a shared link keeps C_rr.

Nothing here waits on wall-clock time: every wait is for a condition in the page."""

from __future__ import annotations

import itertools
import json

import pytest
from playwright.sync_api import Browser, expect

import rollspring
from rollspring.model import system_from_dict
from rollspring.model.schema import RANGES
from tests.test_web_page import Opened, open_page, page_system, settle

#: The slider's step (C_rr) and the presses to the value asked for.
STEP = 0.0005
PRESSES = 20


def test_the_c_rr_slider_sends_it_and_the_page_shows_the_engines_dissipation(
    opened: Opened, browser: Browser, server: str
) -> None:
    page = opened.page
    sent: list[dict] = []
    page.on(
        "request",
        lambda r: sent.append(r.post_data_json) if r.url.endswith("/api/simulate") else None,
    )
    # every rolling body has its field and slider, within the model's range
    for i in range(2):
        slider = page.locator(
            f'input[type="range"][data-slider-for="bodies.{i}.rolling_resistance"]'
        )
        expect(slider).to_have_count(1)
        low, high, _ = RANGES["rolling_resistance"]  # the model's range
        assert float(slider.get_attribute("min")) == low
        assert float(slider.get_attribute("max")) == high
    expect(page.locator("#energy-note")).to_be_hidden()  # nothing dissipated without it
    slider = page.locator('input[type="range"][data-slider-for="bodies.0.rolling_resistance"]')
    slider.focus()
    for _ in range(PRESSES):
        page.keyboard.press("ArrowRight")
    settle(page)
    wanted = pytest.approx(PRESSES * STEP, rel=1e-12)
    assert page_system(page)["bodies"][0]["rolling_resistance"] == wanted
    assert sent[-1]["system"]["bodies"][0]["rolling_resistance"] == wanted
    box = page.locator('#editor input[data-path="bodies.0.rolling_resistance"]')
    assert float(box.input_value()) == wanted  # the field follows its slider
    box.fill("0.012")
    box.press("Enter")
    settle(page)
    request = sent[-1]
    assert request["system"]["bodies"][0]["rolling_resistance"] == 0.012
    assert float(slider.input_value()) == 0.012
    # the engine on the same system, as the server runs it
    engine = rollspring.simulate(
        system_from_dict(request["system"]),
        request["duration"],
        rtol=request.get("rtol", 1e-8),
        n_output=request["outputs"],
        on_slip=request["on_slip"],
    )
    summary = engine.summary
    assert summary["dissipated_by"]["rolling_resistance"] > 0
    note = page.locator("#energy-note")
    expect(note).to_be_visible()
    shown = float(note.get_attribute("data-dissipated"))
    assert shown == pytest.approx(summary["energy_dissipated"], rel=1e-9)
    rolling = float(note.get_attribute("data-rolling-resistance"))
    assert rolling == pytest.approx(summary["dissipated_by"]["rolling_resistance"], rel=1e-9)
    expect(note).to_contain_text(
        f"rolling resistance {summary['dissipated_by']['rolling_resistance']:.4g}"
    )
    # each body's coming to rest, at the engine's time
    rests = [e for e in summary["events"] if e["kind"] in ("rest", "release")]
    assert rests
    listed = json.loads(note.get_attribute("data-events"))
    assert [(e["kind"], e["body"]) for e in listed] == [(e["kind"], e["body"]) for e in rests]
    for got, want in zip(listed, rests, strict=True):
        assert got["time"] == pytest.approx(want["time"], rel=1e-9)
        expect(note).to_contain_text(
            f"{want['body']} comes to rest"
            if want["kind"] == "rest"
            else f"{want['body']} starts to roll again"
        )
    # a body held at rest is drawn so, as a slipping one is: the longest rest of the run, the
    # clock moved into its middle with the time slider (which moves in output intervals)
    held = []
    for k, event in enumerate(rests):
        if event["kind"] == "rest":
            later = [e["time"] for e in rests[k + 1 :] if e["body"] == event["body"]]
            held.append((event["time"], later[0] if later else request["duration"], event["body"]))
    start, end, who = max(held, key=lambda h: h[1] - h[0])
    dt = page.evaluate("() => window.rollspringPage.dt()")
    assert end - start > 4 * dt
    page.locator("#time").fill(repr((start + end) / 2))
    assert start < page.evaluate("() => window.rollspringPage.time()") < end
    assert who in page.evaluate("() => window.rollspringPage.drawn().held")
    page.locator("#time").fill("0")
    assert page.evaluate("() => window.rollspringPage.drawn().held") == []
    # the energy plotted decays: the engine's total, which falls, never rising beyond the
    # integrator's error
    energy = page.evaluate("() => window.rollspringPage.plotData('energy')")
    total = energy["data"][energy["labels"].index("total") + 1]
    assert total == pytest.approx(list(engine.energy), rel=1e-9, abs=1e-15)
    assert total[-1] < 0.5 * total[0]
    error = summary["energy_error"] * total[0]  # the run's own accuracy (rtol 1e-8)
    assert 0 < error < 1e-6 * total[0]
    assert all(b <= a + error for a, b in itertools.pairwise(total))
    # a shared link keeps C_rr
    page.get_by_role("button", name="Share link").click()
    expect(page.locator("#share-url")).not_to_have_value("")
    url = page.locator("#share-url").input_value()
    fresh = open_page(browser, server, url)
    try:
        restored = page_system(fresh.page)
        assert restored["bodies"][0]["rolling_resistance"] == 0.012
        assert "rolling_resistance" not in restored["bodies"][1]
        settle(fresh.page)
        other = float(fresh.page.locator("#energy-note").get_attribute("data-dissipated"))
        assert other == pytest.approx(summary["energy_dissipated"], rel=1e-9)
        fresh.check_clean()
    finally:
        fresh.page.close()

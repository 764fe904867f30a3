"""The page teaches the paper (issue 26, points 1 and 2), in a real browser against the real
server: on the default system (the paper's Fig. 2, a hoop and a cylinder) the centre of mass
visibly swings on the magnified strip under the floor while X̂ stays put; Newton's second law for
the whole system, Σf = (Σm)·a_CM, holds in the plotted data; positions are plotted as
displacements from equilibrium; the force arrows keep one scale per kind of force while the page
is open (frictionless friction ≈ 0 px, the default's clearly visible), with a colour key, value
labels on hover, focus or always, and a "needed μ" gauge per body. At 1280×800 and 390×844, with
no horizontal overflow.

The drawn pixel positions are read from the page's test hook (``rollspringPage.drawn()``: what
the last frame drew), at the run's own output times; nothing waits on wall-clock time."""

from __future__ import annotations

import re

import numpy as np
import pytest
from playwright.sync_api import Page, expect

import rollspring
from rollspring.model import load_system, system_from_dict
from tests.test_web_page import Opened, page_system, settle

#: Every output time of the run (k·dt): move the clock there and keep what the frame drew.
SWEEP = """() => {
    const page = window.rollspringPage;
    const slider = document.querySelector('#time');
    const dt = page.dt();
    const n = Math.round(Number(slider.max) / dt);
    const frames = [];
    for (let k = 0; k <= n; k++) {
        slider.value = String(k * dt);
        slider.dispatchEvent(new Event('input'));
        frames.push({t: page.time(), drawn: page.drawn()});
    }
    return frames;
}"""


def sweep(page: Page) -> list[dict]:
    frames = page.evaluate(SWEEP)
    assert len(frames) == 601
    return frames


def peak_to_peak(values: list[float | None]) -> float:
    assert values and all(v is not None for v in values)
    return max(values) - min(values)


def no_horizontal_overflow(page: Page) -> None:
    width, inner = page.evaluate("() => [document.documentElement.scrollWidth, window.innerWidth]")
    assert width <= inner


def sig3(value: float) -> str:
    """``value`` to 3 significant digits, trailing zeros kept (the page's ``sig(x, 3)``)."""
    return f"{value:#.3g}".rstrip(".")


def simulated(page: Page) -> rollspring.Trajectory:
    """The page's system simulated here, as the page asks for it (10 s, 601 outputs)."""
    return rollspring.simulate(system_from_dict(page_system(page)), 10.0, n_output=601)


# ------------------------------------------------------------------------ 1. see the lesson


def test_the_cm_swings_on_the_magnified_strip_while_xhat_stays_put(sized: Opened) -> None:
    page = sized.page
    frames = sweep(page)
    strips = [f["drawn"]["strip"] for f in frames]
    cm = [s["cm"] for s in strips]
    xhat = [s["xhat"] for s in strips]
    mags = {s["magnification"] for s in strips}
    assert len(mags) == 1
    (mag,) = mags
    # the CM visibly swings (≥ 30 px peak to peak), X̂ stays put (≤ 1 px)
    assert peak_to_peak(cm) >= 30
    assert peak_to_peak(xhat) <= 1
    # ... and what is drawn is the motion, at the stated magnification of the animation's scale
    run = simulated(page)
    px_per_m = float(page.locator("#scene").get_attribute("data-px-per-m"))
    expected = float(np.ptp(run.cm_x)) * px_per_m * mag
    assert peak_to_peak(cm) == pytest.approx(expected, rel=1e-6)
    assert float(np.ptp(run.cm_x)) > 1e-3  # the paper's Fig. 2: the CM moves 1.4 mm
    strip = page.locator("#strip")
    assert strip.get_attribute("data-magnification") == str(mag)
    assert f"magnified ×{mag}" in strip.get_attribute("aria-label")
    assert mag >= 10
    no_horizontal_overflow(page)


#: The largest alpha of the strip canvas's pixels around (x, y) CSS px (3×3 device pixels).
ALPHA_AT = """([x, y]) => {
    const canvas = document.querySelector('#strip');
    const ratio = canvas.width / canvas.getBoundingClientRect().width;
    const px = canvas.getContext('2d').getImageData(
        Math.round(x * ratio) - 1, Math.round(y * ratio) - 1, 3, 3).data;
    let alpha = 0;
    for (let i = 3; i < px.length; i += 4) alpha = Math.max(alpha, px[i]);
    return alpha;
}"""


def test_the_strip_draws_a_fading_trail_of_each(laptop: Opened) -> None:
    page = laptop.page
    frames = sweep(page)
    dt = page.evaluate("() => window.rollspringPage.dt()")
    now = 120  # t = 2 s
    page.locator("#time").evaluate(
        "(slider, t) => { slider.value = String(t); slider.dispatchEvent(new Event('input')); }",
        now * dt,
    )
    strip = page.evaluate("() => window.rollspringPage.drawn().strip")
    assert strip["cm"] == frames[now]["drawn"]["strip"]["cm"]
    fall, trail = strip["fall"], strip["trail"]
    assert fall >= 10 and trail > 0

    def alpha_back(key: str, samples: int) -> int:
        x = frames[now - samples]["drawn"]["strip"][key]
        y = strip[f"{key}Y"] + samples * dt / trail * fall
        return page.evaluate(ALPHA_AT, [x, y])

    for key in ("cm", "xhat"):
        head = page.evaluate(ALPHA_AT, [strip[key], strip[f"{key}Y"]])
        recent, older = alpha_back(key, 9), alpha_back(key, 30)  # 0.15 s and 0.5 s ago
        assert head == 255
        assert 0 < older < recent < head  # it fades with age
    # the CM's trail is a wave (the CM moved), X̂'s a straight line down (it stayed put)
    assert abs(frames[now - 9]["drawn"]["strip"]["cm"] - strip["cm"]) > 10
    assert abs(frames[now - 9]["drawn"]["strip"]["xhat"] - strip["xhat"]) < 1e-6
    # nothing drawn beside the trail
    assert page.evaluate(ALPHA_AT, [strip["xhat"] + 40, strip["xhatY"] + fall / 2]) == 0


def test_newtons_second_law_for_the_whole_system_holds_in_the_plotted_data(
    laptop: Opened,
) -> None:
    page = laptop.page
    plotted = page.evaluate("() => window.rollspringPage.plotData('newton')")
    assert plotted["labels"] == ["Σf (frictions)", "(Σm)·a_CM"]
    t, friction, mass_acc = (np.array(column, dtype=float) for column in plotted["data"])
    assert np.isfinite(mass_acc).all()
    scale = np.max(np.abs(friction))
    assert scale > 0.1  # the frictions are not zero: they move the CM
    assert np.max(np.abs(friction - mass_acc)) <= 1e-9 * scale
    # Σf is the sum of the frictions the engine gives, computed independently here
    run = simulated(page)
    np.testing.assert_array_equal(t, run.t)
    np.testing.assert_allclose(friction, run.friction.sum(axis=1), rtol=0, atol=1e-12 * scale)
    # and (Σm)·a_CM is the total mass times the CM's acceleration: the central second
    # differences of cm_x, to their truncation error (hΩ)²/12 = 2.7e-3 at h = 1/60 s
    total = sum(b.mass for b in load_system("hoop-cylinder").bodies)
    h = run.t[1] - run.t[0]
    second = (run.cm_x[2:] - 2 * run.cm_x[1:-1] + run.cm_x[:-2]) / h**2
    np.testing.assert_allclose(total * second, mass_acc[1:-1], rtol=0, atol=5e-3 * scale)


def test_positions_are_displacements_from_equilibrium_with_the_cm_and_xhat_bold(
    laptop: Opened,
) -> None:
    page = laptop.page
    plotted = page.evaluate("() => window.rollspringPage.plotData('positions')")
    assert plotted["unit"] == "x − x_eq (mm)"
    assert plotted["labels"] == ["hoop", "cylinder", "CM", "X̂"]
    caption = page.locator('[data-plot="positions"] figcaption')
    expect(caption).to_contain_text("from equilibrium")
    data = [np.array(column, dtype=float) for column in plotted["data"]]
    run = simulated(page)
    eq = rollspring.analyze(load_system("hoop-cylinder")).to_dict()["equilibrium"]["x"]
    for i, body in enumerate(["hoop", "cylinder"]):
        np.testing.assert_allclose(data[1 + i], (run.x[:, i] - eq[body]) * 1000, atol=1e-9)
    cm, xhat = data[3], data[4]
    assert np.ptp(cm) == pytest.approx(np.ptp(run.cm_x) * 1000, rel=1e-9)
    assert np.ptp(cm) > 1.0  # mm
    assert np.max(np.abs(xhat)) < 1e-9  # X̂ is its equilibrium throughout
    # the kinetic energy split: translational + rotational = kinetic
    energy = page.evaluate("() => window.rollspringPage.plotData('energy')")
    labels = energy["labels"]
    assert labels[:3] == ["kinetic", "translational", "rotational"]
    kinetic, translational, rotational = (np.array(energy["data"][k]) for k in (1, 2, 3))
    np.testing.assert_allclose(translational + rotational, kinetic, rtol=1e-12, atol=1e-15)
    assert np.max(rotational) > 0.3 * np.max(kinetic)
    # absolute positions as an option
    page.get_by_label("absolute positions").check()
    absolute = page.evaluate("() => window.rollspringPage.plotData('positions')")
    assert absolute["unit"] == "x (m)"
    np.testing.assert_array_equal(absolute["data"][3], run.cm_x)
    expect(caption).not_to_contain_text("from equilibrium")


# ------------------------------------------------------------------- 2. forces you can read


def max_friction_px(page: Page) -> float:
    return max(abs(v) for f in sweep(page) for v in f["drawn"]["friction"].values())


def test_friction_arrows_keep_one_scale_frictionless_near_zero_default_visible(
    sized: Opened,
) -> None:
    page = sized.page
    scale = page.evaluate("() => window.rollspringPage.drawn().forceScale")
    default_px = max_friction_px(page)
    assert default_px >= 20
    # the arrow is the force at its kind's scale: the largest is the hoop's 0.5 N
    run = simulated(page)
    assert default_px == pytest.approx(np.max(np.abs(run.friction)) * scale["friction"], rel=1e-6)
    page.select_option("#preset", "frictionless")
    settle(page)
    frictionless_px = max_friction_px(page)
    assert frictionless_px <= 2
    assert page.evaluate("() => window.rollspringPage.drawn().forceScale") == scale
    # an edit is a new run: the scale stays
    stiffness = page.locator('#editor input[data-path="springs.0.stiffness"]')
    stiffness.fill("150")
    stiffness.press("Enter")
    settle(page)
    assert page.evaluate("() => window.rollspringPage.drawn().forceScale") == scale
    page.select_option("#preset", "hoop-cylinder")
    settle(page)
    assert max_friction_px(page) == pytest.approx(default_px, rel=1e-12)
    no_horizontal_overflow(page)


def test_the_arrow_scale_control_the_colour_key_and_value_labels(laptop: Opened) -> None:
    page = laptop.page
    key = page.get_by_role("group", name="Force arrows: colours and scales")
    expect(key).to_contain_text("friction f: 1 N = 60.0 px")
    expect(key).to_contain_text("normal force N: 1 N = 4.00 px")
    expect(key).to_contain_text("spring force: 1 N = 30.0 px")
    swatches = page.evaluate(
        "() => [...document.querySelectorAll('#force-key .swatch')]"
        ".map(s => getComputedStyle(s).backgroundColor)"
    )
    assert len(set(swatches)) == 3
    page.get_by_label("normal forces").check()
    page.get_by_role("button", name="Step", exact=True).click()
    drawn = page.evaluate("() => window.rollspringPage.drawn()")
    assert drawn["labels"] == []  # no value label until asked for
    # the scale control: every kind ×2, one scale for every run while the page is open
    page.select_option("#arrow-scale", "2")
    expect(key).to_contain_text("friction f: 1 N = 120 px")
    doubled = page.evaluate("() => window.rollspringPage.drawn()")
    assert doubled["forceScale"] == {"spring": 60, "friction": 120, "normal": 8}
    for kind in ("friction", "normal"):
        for body, px in drawn[kind].items():
            assert doubled[kind][body] == pytest.approx(2 * px, rel=1e-12)
    # value labels: on hover (the body brought into view first: ticking the boxes above may
    # have scrolled it off the top)
    page.locator('[data-body="hoop"]').scroll_into_view_if_needed()
    box = page.locator('[data-body="hoop"]').bounding_box()
    page.mouse.move(box["x"] + box["width"] / 2, box["y"] + box["height"] / 2)
    labels = page.evaluate("() => window.rollspringPage.drawn().labels")
    assert labels and all(label.startswith("hoop: ") for label in labels)
    assert any(re.fullmatch(r"hoop: f = [+−]\d\.\d\d+ N", label) for label in labels)
    assert "hoop: N = 9.81 N" in labels
    page.mouse.move(1, 1)
    assert page.evaluate("() => window.rollspringPage.drawn().labels") == []
    # ... on keyboard focus
    page.locator('[data-body="cylinder"]').focus()
    labels = page.evaluate("() => window.rollspringPage.drawn().labels")
    assert labels and all(label.startswith("cylinder: ") for label in labels)
    page.locator("#play").focus()
    # ... and always, for every body
    page.get_by_label("force values on the arrows").check()
    labels = page.evaluate("() => window.rollspringPage.drawn().labels")
    assert {label.split(":")[0] for label in labels} == {"hoop", "cylinder"}
    # the values as text, for every reader: the friction at the clock's time
    run = simulated(page)
    t = page.evaluate("() => window.rollspringPage.time()")
    i = int(np.argmin(np.abs(run.t - t)))
    assert run.t[i] == pytest.approx(t, abs=1e-12)
    f = run.friction[i, 0]
    text = page.locator("#force-values").inner_text()
    assert f"hoop: f = {'−' if f < 0 else '+'}{sig3(abs(f))} N" in text
    assert "N = 9.810 N" in text


def test_needed_mu_gauges_show_the_largest_friction_ratio_so_far_against_mu_s(
    laptop: Opened,
) -> None:
    page = laptop.page
    gauges = page.get_by_role("group", name=re.compile("Friction needed so far"))
    expect(gauges.locator(".gauge")).to_have_count(2)
    run = simulated(page)
    page.locator("#time").focus()
    page.keyboard.press("End")
    for i, body in enumerate(["hoop", "cylinder"]):
        needed = float(np.max(np.abs(run.friction[:, i]) / run.normal[:, i]))
        value = gauges.locator(f'.gauge[data-gauge="{body}"] .value')
        expect(value).to_have_text(f"needs μ ≥ {sig3(needed)} of μs = 1.00")
        assert needed > 0.03
    # a body that needs more than its μs slips: the gauge says so
    mu = page.locator('#editor input[data-path="bodies.0.mu_static"]')
    mu.fill("0.03")
    mu.press("Enter")
    settle(page)
    page.locator("#time").focus()
    page.keyboard.press("End")
    hoop = gauges.locator('.gauge[data-gauge="hoop"]')
    expect(hoop).to_have_attribute("data-over", "true")
    expect(hoop.locator(".value")).to_contain_text("of μs = 0.0300")

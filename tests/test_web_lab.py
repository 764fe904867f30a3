"""The lab on the page, in Debian's Chromium against the real server, at 1280×800 and 390×844:
a table made here from the exact motion of the hoop and cylinder (its spring damped, ~1 mm of
seeded noise) is loaded and drawn over the model's positions exactly as the file holds it; Fit
from a start whose stiffness is 30% off and without damping shows k within 1% of the truth and
within 3 standard errors — the values :func:`rollspring.fit` gives on the same file and start —
and puts the fitted system into the editor; the fitted system downloads as TOML; a bad file's
one-line error is shown next to the file control (picked or dropped); axe-core finds no serious
or critical violation with the lab panel open, and nothing overflows sideways.

Nothing here waits on wall-clock time: every wait is for a condition in the page."""

from __future__ import annotations

from pathlib import Path

import pytest
from playwright.sync_api import Page, expect

import rollspring
from rollspring.errors import DataError
from rollspring.lab.data import match_bodies, parse_data
from rollspring.model import load_system, system_from_dict
from rollspring.model.files import system_from_text
from tests.test_web_lab_api import DAMPING, STIFFNESS, csv_text, recording, rough_start
from tests.test_web_page import Opened, page_system, settle
from tests.test_web_phone import axe_violations, no_horizontal_overflow, serious

FREE = ["springs.0.stiffness", "springs.0.damping"]


def load_file(page: Page, name: str, text: str) -> None:
    page.locator("#lab-file").set_input_files(
        files=[{"name": name, "mimeType": "text/csv", "buffer": text.encode()}]
    )
    settle(page)


def drop_file(page: Page, name: str, text: str) -> None:
    """Drop a file on the lab's drop zone, as a file dragged from the desktop is."""
    page.evaluate(
        """([name, text]) => {
        const transfer = new DataTransfer();
        transfer.items.add(new File([text], name, {type: 'text/csv'}));
        const zone = document.querySelector('#lab-drop');
        zone.dispatchEvent(new DragEvent('dragover', {dataTransfer: transfer, bubbles: true,
                                                     cancelable: true}));
        zone.dispatchEvent(new DragEvent('drop', {dataTransfer: transfer, bubbles: true,
                                                 cancelable: true}));
    }""",
        [name, text],
    )
    settle(page)


def open_lab(page: Page) -> None:
    page.locator("details#lab > summary").click()
    expect(page.locator("#lab-file")).to_be_visible()


def set_start(page: Page) -> None:
    """The editor's system made the rough start: the preset's stiffness 30% off, no damping."""
    start = rough_start()
    for path, value in (
        ("springs.0.stiffness", start["springs"][0]["stiffness"]),
        ("springs.0.damping", start["springs"][0]["damping"]),
    ):
        box = page.locator(f'#editor input[data-path="{path}"]')
        box.fill(repr(value))
        box.press("Enter")
        settle(page)
    assert system_from_dict(page_system(page)) == system_from_dict(start)


def drawn_data(page: Page, body: str) -> tuple[list[float], list[float]]:
    """The times and values of the markers drawn for ``body``'s data in the positions plot."""
    plotted = page.evaluate("() => window.rollspringPage.plotData('positions')")
    column = plotted["labels"].index(f"{body} data") + 1
    assert plotted["styles"][column - 1]["markers"]
    pairs = [
        (t, v)
        for t, v in zip(plotted["data"][0], plotted["data"][column], strict=True)
        if v is not None
    ]
    return [t for t, _ in pairs], [v for _, v in pairs]


def test_data_drawn_and_fitted_as_rollspring_fit_does(sized: Opened, tmp_path: Path) -> None:
    page = sized.page
    t, x = recording()
    text = csv_text(t, x)
    set_start(page)
    open_lab(page)
    boxes = page.locator("#lab-free-list input[data-free]")
    ticked = [b.get_attribute("data-free") for b in boxes.all() if b.is_checked()]
    assert ticked == FREE  # the defaults: the spring's stiffness and damping
    load_file(page, "hoop-cylinder.csv", text)
    expect(page.locator("#lab-file-error")).to_be_hidden()
    expect(page.locator("#lab-file-info")).to_contain_text("hoop-cylinder.csv: 600 times")
    # drawn as the file holds it (absolute positions: the file's own numbers)
    page.locator("#show-absolute").check()
    settle(page)
    for column, body in enumerate(("hoop", "cylinder")):
        times, values = drawn_data(page, body)
        assert times == t.tolist()
        assert values == x[:, column].tolist()
    # Fit, from the rough start
    page.locator("#lab-fit").click()
    settle(page)
    row = page.locator('#lab-parameters tr[data-parameter="springs.0.stiffness"]')
    expect(row).to_have_count(1)
    k, k_error = float(row.get_attribute("data-value")), float(row.get_attribute("data-stderr"))
    assert abs(k - STIFFNESS) < 0.01 * STIFFNESS
    assert abs(k - STIFFNESS) < 3 * k_error
    shown, _, shown_error = row.locator("td.value").inner_text().partition(" ± ")
    assert abs(float(shown) - k) <= 0.05 * k_error  # written to the error's second digit
    assert float(shown_error) == pytest.approx(k_error, rel=0.05)
    # the same values as rollspring.fit on the same file and start
    path = tmp_path / "hoop-cylinder.csv"
    path.write_text(text)
    direct = rollspring.fit(str(path), system_from_dict(rough_start()), FREE)
    for name, parameter in direct.parameters.items():
        cells = page.locator(f'#lab-parameters tr[data-parameter="{name}"]')
        assert float(cells.get_attribute("data-value")) == pytest.approx(
            parameter.value, rel=1e-7, abs=1e-12
        )
    damping = page.locator('#lab-parameters tr[data-parameter="springs.0.damping"]')
    c, c_error = (
        float(damping.get_attribute("data-value")),
        float(damping.get_attribute("data-stderr")),
    )
    assert abs(c - DAMPING) < 3 * c_error
    for body, rms in direct.residual_rms.items():
        item = page.locator(f'#lab-rms li[data-body="{body}"]')
        assert float(item.get_attribute("data-value")) == pytest.approx(rms, rel=1e-7)
        expect(item).to_contain_text(f"residual RMS of {body}:")
    for claim in ("cm_peak_to_peak", "stationary_peak_to_peak"):
        item = page.locator(f'#lab-claims li[data-claim="{claim}"]')
        assert float(item.get_attribute("data-value")) == pytest.approx(
            direct.claims[claim]["value"], rel=1e-6, abs=1e-12
        )
        expect(item).to_contain_text(" ± ")
    # the fitted system in the editor; its motion over the data
    system = page_system(page)
    assert system["springs"][0]["stiffness"] == k
    assert system_from_dict(system) == direct.system
    times, values = drawn_data(page, "hoop")
    assert times == t.tolist()
    assert values == x[:, 0].tolist()
    # the fitted system downloads as TOML
    with page.expect_download() as waiting:
        page.locator("#lab-download").click()
    downloaded = Path(waiting.value.path()).read_text()
    assert system_from_text(downloaded, format="toml") == direct.system
    # the lab open with its results: accessible, and nothing overflows sideways
    assert serious(axe_violations(page)) == []
    no_horizontal_overflow(page)


def reader_message(name: str, text: str) -> str:
    with pytest.raises(DataError) as raised:
        match_bodies(parse_data(text, name), load_system("hoop-cylinder"))
    return " ".join(str(raised.value).split())


def test_a_bad_file_shows_its_one_line_error_next_to_the_file_control(sized: Opened) -> None:
    page = sized.page
    open_lab(page)
    picked = "t,x_hoop\n0,0.1\n0,0.2\n"  # a time repeated
    load_file(page, "repeated.csv", picked)
    error = page.locator("#lab-file-error")
    expect(error).to_have_text(reader_message("repeated.csv", picked))
    expect(page.locator("#lab-file")).to_have_attribute("aria-invalid", "true")
    assert page.locator("#lab-fit").is_disabled()
    # the error sits next to the file control
    control = page.locator("#lab-drop").bounding_box()
    shown = error.bounding_box()
    assert 0 <= shown["y"] - (control["y"] + control["height"]) < 40
    dropped = "position\n1\n2\n"  # no time column
    drop_file(page, "no-time.csv", dropped)
    expect(error).to_have_text(reader_message("no-time.csv", dropped))
    # a good file afterwards clears it
    t, x = recording()
    drop_file(page, "good.csv", csv_text(t[:120], x[:120]))
    expect(error).to_be_hidden()
    assert page.locator("#lab-fit").is_enabled()
    assert serious(axe_violations(page)) == []
    no_horizontal_overflow(page)
    # the two refusals were the only console errors (Chromium logs every 4xx response)
    refused = [e for e in sized.errors if "status of 422" in e]
    assert len(refused) == 2
    sized.errors[:] = [e for e in sized.errors if e not in refused]


def test_the_posterior_asked_on_the_page_shows_each_credible_interval(sized: Opened) -> None:
    """Tick "also sample the posterior" and Fit: a column of 95 % credible intervals beside the
    values, each holding its value and about as wide as 2 x 1.96 standard errors (emcee's
    sampling, as ``rollspring fit --posterior``); the table still fits the screen."""
    page = sized.page
    t, x = recording()
    set_start(page)
    open_lab(page)
    load_file(page, "hoop-cylinder.csv", csv_text(t, x))
    page.locator("#lab-posterior").check()
    page.locator("#lab-fit").click()
    settle(page)
    expect(page.locator("#lab-parameters thead")).to_contain_text("95 % credible interval (MCMC)")
    for name in FREE:
        row = page.locator(f'#lab-parameters tr[data-parameter="{name}"]')
        expect(row).to_have_count(1)
        value, stderr = (
            float(row.get_attribute("data-value")),
            float(row.get_attribute("data-stderr")),
        )
        low, high = float(row.get_attribute("data-low")), float(row.get_attribute("data-high"))
        assert low < value < high
        assert high - low == pytest.approx(2 * 1.96 * stderr, rel=0.35)
        expect(row.locator("td.interval")).to_contain_text(" … ")
    assert serious(axe_violations(page)) == []
    no_horizontal_overflow(page)

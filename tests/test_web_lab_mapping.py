"""The lab's track selects on the page, in Debian's Chromium against the real server, at
1280×800 and 390×844: a Tracker ``#multi:`` file made here from the exact motion of the hoop and
cylinder (~1 mm of seeded noise), its tracks named as Tracker names them ("mass A", "mass B"),
shows one select per track; matched to the hoop and the cylinder, the data drawn are the file's
and Fit gives what :func:`rollspring.fit` gives with the same ``mapping``; two tracks on one body
are refused next to the selects with the server's one line; a track "not used" is left out; a
track named as a body is pre-filled, and another system's bodies are offered once it is shown; the
selects are labelled, at least 44 px tall on the phone, axe-core clean, nothing overflows.

Nothing here waits on wall-clock time: every wait is for a condition in the page."""

from __future__ import annotations

from pathlib import Path

import pytest
from playwright.sync_api import Page, expect

import rollspring
from rollspring.errors import DataError
from rollspring.lab.data import match_bodies, parse_data
from rollspring.model import load_system, system_from_dict
from tests.fit_data import write_tracker_multi
from tests.test_web_lab import FREE, drawn_data, load_file, open_lab, set_start
from tests.test_web_lab_api import recording, rough_start
from tests.test_web_page import Opened, settle
from tests.test_web_phone import TAP, axe_violations, no_horizontal_overflow, serious

TRACKS = ("mass A", "mass B")
MAPPING = {"mass A": "hoop", "mass B": "cylinder"}


def choose(page: Page, track: str, label: str) -> None:
    """Pick ``label`` in the select of ``track`` from the keyboard (its label names it)."""
    select = page.get_by_label(f"track '{track}' is")
    select.focus()
    select.select_option(label=label)
    settle(page)


def test_tracker_tracks_matched_to_the_bodies_then_fitted(sized: Opened, tmp_path: Path) -> None:
    page = sized.page
    t, x = recording()
    path = write_tracker_multi(tmp_path / "tracker.txt", t, x, TRACKS)
    text = path.read_text()
    set_start(page)
    open_lab(page)
    load_file(page, "tracker.txt", text)
    # no track named as a body: one select per track, each "not used", nothing drawn yet
    expect(page.locator("#lab-file-error")).to_be_hidden()
    expect(page.locator("#lab-map")).to_be_visible()
    selects = page.locator("#lab-map select")
    expect(selects).to_have_count(2)
    for track in TRACKS:
        select = page.get_by_label(f"track '{track}' is")
        expect(select).to_have_value("")
        options = select.locator("option").all_inner_texts()
        assert options == ["hoop", "cylinder", "not used"]
    assert page.locator("#lab-fit").is_disabled()
    # one track matched: the hoop alone drawn; the other left out
    page.locator("#show-absolute").check()
    settle(page)
    choose(page, "mass A", "hoop")
    times, values = drawn_data(page, "hoop")
    assert times == t.tolist()
    assert values == x[:, 0].tolist()
    labels = page.evaluate("() => window.rollspringPage.plotData('positions')")["labels"]
    assert "cylinder data" not in labels
    # two tracks on one body: the server's one line next to the selects, Fit refused
    choose(page, "mass B", "hoop")
    with pytest.raises(DataError) as raised:
        match_bodies(
            parse_data(text, "tracker.txt"),
            load_system("hoop-cylinder"),
            {"mass A": "hoop", "mass B": "hoop"},
        )
    error = page.locator("#lab-map-error")
    expect(error).to_have_text(" ".join(str(raised.value).split()))
    expect(selects.first).to_have_attribute("aria-invalid", "true")
    assert page.locator("#lab-fit").is_disabled()
    assert serious(axe_violations(page)) == []
    # matched to the hoop and the cylinder: the file's data drawn
    choose(page, "mass B", "cylinder")
    expect(error).to_be_hidden()
    for column, body in enumerate(("hoop", "cylinder")):
        times, values = drawn_data(page, body)
        assert times == t.tolist()
        assert values == x[:, column].tolist()
    # the selects: labelled, at least 44 px tall on the phone, accessible, nothing overflows
    if page.viewport_size["width"] < 600:
        for select in selects.all():
            assert select.bounding_box()["height"] >= TAP
    assert serious(axe_violations(page)) == []
    no_horizontal_overflow(page)
    # Fit: what rollspring.fit gives on the same file, start and mapping
    page.locator("#lab-fit").click()
    settle(page)
    direct = rollspring.fit(str(path), system_from_dict(rough_start()), FREE, mapping=MAPPING)
    for name, parameter in direct.parameters.items():
        cells = page.locator(f'#lab-parameters tr[data-parameter="{name}"]')
        assert float(cells.get_attribute("data-value")) == pytest.approx(
            parameter.value, rel=1e-7, abs=1e-12
        )
    for body, rms in direct.residual_rms.items():
        item = page.locator(f'#lab-rms li[data-body="{body}"]')
        assert float(item.get_attribute("data-value")) == pytest.approx(rms, rel=1e-7)
    assert serious(axe_violations(page)) == []
    no_horizontal_overflow(page)
    # the refusal was the only console error (Chromium logs every 4xx response)
    refused = [e for e in sized.errors if "status of 422" in e]
    assert len(refused) == 1
    sized.errors[:] = [e for e in sized.errors if e not in refused]


def test_the_selects_are_pre_filled_by_name_and_shown_only_when_needed(sized: Opened) -> None:
    page = sized.page
    open_lab(page)
    t, x = recording()
    rows = [f"{float(a)!r},{float(b)!r}" for a, b in zip(t[:60], x[:60, 0], strict=True)]
    load_file(page, "hoop.csv", "\n".join(["t,x_hoop", *rows]) + "\n")
    expect(page.locator("#lab-file-info")).to_contain_text("positions of hoop")
    expect(page.locator("#lab-map")).to_be_hidden()  # every track named as a body
    assert page.locator("#lab-fit").is_enabled()
    load_file(page, "wheel.csv", "\n".join(["t,x_hoop,x_wheel", *(f"{r},0.5" for r in rows)]))
    expect(page.locator("#lab-map")).to_be_visible()
    expect(page.get_by_label("track 'hoop' is")).to_have_value("hoop")
    expect(page.get_by_label("track 'wheel' is")).to_have_value("")
    expect(page.locator("#lab-file-info")).to_contain_text("wheel.csv: 60 times")
    assert page.locator("#lab-fit").is_enabled()
    # another system: the selects offer its bodies, and the table is read again with them
    page.select_option("#preset", "two-cylinders")
    settle(page)
    hoop = page.get_by_label("track 'hoop' is")
    assert hoop.locator("option").all_inner_texts() == ["cylinder1", "cylinder2", "not used"]
    expect(hoop).to_have_value("")
    expect(page.locator("#lab-file-info")).to_contain_text("wheel.csv: no track matched to a body")
    assert page.locator("#lab-fit").is_disabled()

"""The report in a real browser: Debian's Chromium driven by Playwright (installed by
``make test``), as CI runs it. The page opens with no console error and no request but its own
file, its formulas are MathML rendered natively, its embedded images decode, the animation plays
when Play is clicked and stops on Pause, the speed and the frame slider work; ``--format pdf``
prints a PDF."""

from __future__ import annotations

import time
from collections.abc import Iterator
from dataclasses import dataclass, field
from pathlib import Path

import pytest
from playwright.sync_api import Browser, Page
from typer.testing import CliRunner

from rollspring.cli import app
from rollspring.model import load_system
from rollspring.outputs.report import write_report
from rollspring.service.documents import build_report
from tests.serving import VISIBLE_TEXT

MATHML = "http://www.w3.org/1998/Math/MathML"


@pytest.fixture(scope="module")
def report_file(tmp_path_factory: pytest.TempPathFactory) -> Path:
    path = tmp_path_factory.mktemp("report") / "hoop-cylinder.html"
    write_report(build_report(load_system("hoop-cylinder")), path)
    return path


@dataclass
class Opened:
    page: Page
    errors: list[str] = field(default_factory=list)
    requests: list[str] = field(default_factory=list)


@pytest.fixture(scope="module")
def opened(browser: Browser, report_file: Path) -> Iterator[Opened]:
    """The report open in one tab for the whole module (loading it is the slow part); the
    errors and requests seen accumulate, so every test also checks what came before it."""
    page = browser.new_page(viewport={"width": 1200, "height": 900})
    seen = Opened(page)
    page.on(
        "console",
        lambda message: (
            seen.errors.append(f"console: {message.text}") if message.type == "error" else None
        ),
    )
    page.on("pageerror", lambda error: seen.errors.append(f"page error: {error}"))
    page.on("request", lambda request: seen.requests.append(request.url))
    page.goto(report_file.as_uri(), wait_until="load")
    yield seen
    page.close()


def scene_png(page: Page) -> bytes:
    return page.locator("#scene").screenshot()


def clock(page: Page) -> float:
    text = page.locator("#clock").inner_text()  # "t = 1.234 s"
    return float(text.split("=")[1].split()[0])


def test_opens_with_no_console_error_and_no_request_but_its_own_file(
    opened: Opened, report_file: Path
) -> None:
    page = opened.page
    page.mouse.wheel(0, 20000)  # scroll through every section
    page.wait_for_timeout(300)
    assert opened.errors == []
    assert opened.requests, "the page itself is requested"
    for url in opened.requests:
        assert url == report_file.as_uri() or url.startswith("data:"), url[:80]
    assert (
        page.evaluate(
            "performance.getEntriesByType('resource')"
            ".filter(e => !e.name.startsWith('data:')).length"
        )
        == 0
    )
    images = page.evaluate("[...document.images].map(i => i.complete && i.naturalWidth > 0)")
    assert len(images) >= 8 and all(images)


def test_formulas_are_mathml_rendered_natively(opened: Opened) -> None:
    maths = opened.page.evaluate(
        "[...document.querySelectorAll('math')].map(m => [m.namespaceURI, "
        "getComputedStyle(m).display, m.getBoundingClientRect().height])"
    )
    assert len(maths) >= 100
    for namespace, display, height in maths:
        assert namespace == MATHML
        assert display in ("math", "block math", "inline math")  # MathML Core layout
        assert height > 0
    assert opened.page.locator(".tex-source").count() == 0
    # the derivation by the five methods, and the paper's claims, are math too
    assert opened.page.locator("#derivation .method").count() >= 7
    assert opened.page.locator("#derivation math").count() >= 50
    assert opened.page.locator("#paper-check math").count() >= 20
    aligned = opened.page.locator("#derivation mtable").count()
    assert aligned >= 5  # multi-line steps are MathML tables, not one run-on row
    assert opened.errors == []


@pytest.mark.parametrize(
    "viewport", [{"width": 1280, "height": 800}, {"width": 390, "height": 844}]
)
def test_the_claims_quotes_are_mathml_and_their_table_never_widens_the_page(
    browser: Browser, report_file: Path, viewport: dict
) -> None:
    page = browser.new_page(viewport=viewport)
    errors: list[str] = []
    page.on("pageerror", lambda error: errors.append(str(error)))
    try:
        page.goto(report_file.as_uri(), wait_until="load")
        table = page.locator("table#paper-claims")
        table.scroll_into_view_if_needed()
        quotes = page.locator("#paper-claims q.quote")
        assert quotes.count() >= 20
        assert page.locator("#paper-claims q.quote math").count() >= 10
        rendered = page.evaluate(
            "[...document.querySelectorAll('#paper-claims q.quote math')].map(m => "
            "[getComputedStyle(m).display, m.getBoundingClientRect().width])"
        )
        assert all(display in ("math", "inline math") and width > 0 for display, width in rendered)
        text = page.query_selector("#paper-check").evaluate(VISIBLE_TEXT)
        assert "$" not in text and "\\" not in text
        widths = page.evaluate(
            "[document.documentElement.scrollWidth, window.innerWidth,"
            " document.querySelector('#paper-claims').scrollWidth,"
            " document.querySelector('#paper-claims').clientWidth]"
        )
        page_width, inner_width, table_width, table_box = widths
        assert page_width <= inner_width
        if viewport["width"] < 500:  # the table scrolls sideways inside itself
            assert table_width > table_box
            page.locator("#paper-claims").evaluate("t => { t.scrollLeft = t.scrollWidth; }")
            assert page.evaluate("document.documentElement.scrollWidth") <= inner_width
        assert errors == []
    finally:
        page.close()


def test_play_moves_the_animation_and_pause_stops_it(opened: Opened) -> None:
    page = opened.page
    play = page.locator("#play")
    play.scroll_into_view_if_needed()
    before = scene_png(page)
    play.click()
    assert play.inner_text() == "Pause"
    page.wait_for_timeout(1000)
    after = scene_png(page)
    assert after != before
    assert clock(page) > 0.2
    play.click()  # Pause
    assert play.inner_text() == "Play"
    stopped = scene_png(page)
    time_stopped = clock(page)
    page.wait_for_timeout(500)
    assert scene_png(page) == stopped
    assert clock(page) == time_stopped
    assert opened.errors == []


def test_speed_control_and_frame_slider(opened: Opened) -> None:
    page = opened.page
    page.locator("#frame").fill("0")  # back to the start (and paused)
    assert clock(page) == 0.0
    page.select_option("#speed", "0.1")
    started = time.perf_counter()
    page.locator("#play").click()
    page.wait_for_timeout(800)
    page.locator("#play").click()
    wall = time.perf_counter() - started
    assert 0 < clock(page) <= 0.1 * wall + 0.02  # a tenth of real time
    frames = page.evaluate("JSON.parse(document.getElementById('animation-data').textContent).t")
    page.locator("#frame").fill("70")  # dragging the slider seeks (and pauses)
    assert clock(page) == pytest.approx(frames[70], abs=5e-4)
    assert page.locator("#play").inner_text() == "Play"
    shown = scene_png(page)
    page.select_option("#magnify", "1")  # true scale: the same instant drawn differently
    assert scene_png(page) != shown
    assert opened.errors == []


def test_pdf_is_printed_by_chromium(tmp_path: Path) -> None:
    target = tmp_path / "report.pdf"
    result = CliRunner().invoke(
        app, ["report", "hoop-cylinder", "-o", str(target), "-T", "1", "--no-derivation"]
    )
    assert result.exit_code == 0, result.output
    assert target.read_bytes().startswith(b"%PDF")
    assert target.stat().st_size > 20_000  # pages with figures, not an empty document

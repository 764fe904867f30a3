"""Real parts for tests: ``rollspring serve`` started from its command line, and Debian's
Chromium driven by Playwright (the ``browser`` fixture, shared through conftest.py)."""

from __future__ import annotations

import contextlib
import re
import signal
import subprocess
import sys
import time
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import requests

__all__ = ["CHROMIUM_ARGS", "Server", "launch_chromium"]

#: Headless Chromium as root, with nothing that reaches out of this machine.
CHROMIUM_ARGS = [
    "--no-sandbox",
    "--disable-gpu",
    "--disable-quic",
    "--no-first-run",
    "--disable-background-networking",
    "--disable-component-update",
    "--disable-sync",
]


@contextlib.contextmanager
def launch_chromium() -> Iterator[Any]:
    """Debian's Chromium (``rollspring.outputs.report.find_chromium``) under Playwright."""
    from playwright.sync_api import sync_playwright

    from rollspring.outputs.report import find_chromium

    with sync_playwright() as playwright:
        browser = playwright.chromium.launch(executable_path=find_chromium(), args=CHROMIUM_ARGS)
        try:
            yield browser
        finally:
            browser.close()


#: The page's two screens: a laptop and a phone held upright (CSS px).
LAPTOP = {"width": 1280, "height": 800}
PHONE = {"width": 390, "height": 844}
#: Both, with their test ids.
SIZES = [("laptop-1280x800", LAPTOP), ("phone-390x844", PHONE)]

#: What an element shows as text outside MathML (the page's ``evaluate`` on an element handle).
VISIBLE_TEXT = """el => {
    const walker = document.createTreeWalker(el, NodeFilter.SHOW_TEXT, {
        acceptNode: n => n.parentElement.closest('math') ? NodeFilter.FILTER_REJECT
                                                         : NodeFilter.FILTER_ACCEPT});
    let text = '';
    while (walker.nextNode()) text += walker.currentNode.data;
    return text;
}"""

SERVE = str(Path(sys.executable).with_name("rollspring"))


class Server:
    """``rollspring serve`` started from its command line on a free port (``options`` added)."""

    def __init__(self, *options: str) -> None:
        self.process = subprocess.Popen(
            [SERVE, "serve", "--port", "0", *options],
            stdout=subprocess.PIPE,
            stderr=subprocess.PIPE,
            text=True,
        )
        try:
            self.url = self._wait()
        except BaseException:
            self.stop()
            raise

    def _wait(self) -> str:
        assert self.process.stdout is not None
        line = self.process.stdout.readline()
        found = re.search(r"http://(\S+):(\d+)/", line)
        assert found, f"no URL in {line!r}"
        host = found.group(1)
        url = f"http://{'127.0.0.1' if host == '0.0.0.0' else host}:{found.group(2)}/"
        # It prints the URL once it answers (its worker processes warm): a request is answered
        # at once (tests/test_serve_cli.py checks that); asked again only should it fail.
        deadline = time.monotonic() + 180
        while True:
            assert self.process.poll() is None, f"rollspring serve exited: {self.stop()}"
            try:
                if requests.get(url + "api/start", timeout=30).status_code == 200:
                    return url
            except requests.RequestException:
                pass
            assert time.monotonic() < deadline, "the server did not answer within 180 s"
            time.sleep(0.2)

    def post(self, path: str, **options: Any) -> requests.Response:
        """``POST`` to ``path`` (``/api/...``) on this server over loopback (TestClient's call)."""
        return requests.post(self.url.rstrip("/") + path, timeout=600, **options)

    def stop(self) -> str:
        """Stop it as Ctrl-C does; what it printed on stderr."""
        self.process.send_signal(signal.SIGINT)
        try:
            _, errors = self.process.communicate(timeout=20)
        except subprocess.TimeoutExpired:
            self.process.kill()
            _, errors = self.process.communicate()
        return errors

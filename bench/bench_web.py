"""The interactive page's server and page under load: ``rollspring serve`` driven by ``wrk``, and
the page in headless Chromium.

Run: ``.venv/bin/python bench/bench_web.py [--runs 3] [--no-browser]`` (about 2.5 minutes;
needs Debian's ``wrk`` and, for (c), ``chromium``).

A real server is started as a user starts it, ``rollspring serve hoop-cylinder --host 127.0.0.1
--port 0`` (its defaults: one worker process per core, ``--limit-concurrency 64``, a 10 s
budget), as a subprocess; its URL is read from the line it prints, and it is stopped with
Ctrl-C (SIGINT) at the end. Every request body is the JSON of ``{"system": <the preset
hoop-cylinder as GET /api/presets gives it>, "duration": 10, "outputs": 600}`` with the spring
stiffness taken in turn from a sweep 80 → 120 → 80 N/m (a slider dragged back and forth): a
``wrk`` Lua script (written to a temporary file) pre-formats the 41 requests and sends them in
turn, counts the response statuses in ``response()`` and prints its figures as one JSON line
from ``done()`` (``latency:percentile(p)``, µs).

(a) **one client moving a slider**: ``wrk -t1 -c1 -d10s --latency`` on ``POST /api/simulate``
    (one connection, each request sent when the previous answer is in): p50/p95 round trip,
    target p95 ≤ 20 ms.
(b) **16 clients at once**: ``wrk -t1 -c16 -d20s``: requests/s, p95, and the responses that
    are not 2xx: the designed 503s (the app's ``{"detail": ...}`` when no worker is free or a
    computation runs past its budget, uvicorn's ``Service Unavailable`` past the concurrency
    limit) and everything else (other statuses, socket errors, wrk's timeouts); target: no 5xx
    but the designed 503s.
(c) **the page** in headless Chromium (Playwright's sync API, ``executable_path`` = Debian's
    chromium): open ``/``, await ``window.rollspringPage.ready()``, press Play, gather
    ``rollspringPage.frameTimes()`` (requestAnimationFrame timestamps) over 5 s → frame rate,
    mean and the 5th percentile of the instantaneous rate 1/Δt, target ≥ 55 fps; then 20
    changes of the spring-stiffness slider (one ArrowRight/ArrowLeft key press each, like a
    user's release of the slider) and, for each, ``lastUpdate().drawn - lastUpdate().changed``
    (the time from the change to the first frame drawn with the new motion), p50/p95, target
    p95 ≤ 50 ms. Skipped, with a message, when the page has no ``window.rollspringPage``.

(a) and (b) are each run ``--runs`` times after a 2 s warm-up; the table gives the median and
the range of the runs, and each run is printed. Load generator, server and browser share the
machine (2 cores on CI), so the figures include their competition for the CPU. The figures
are also written as JSON (``build/bench/web.json`` by default).

Exit status: 0 when the benchmark ran (targets missed are reported ✘, not failures); 1 when
something is broken: the server does not start or dies, ``wrk`` is missing or fails, a single
request is not answered correctly, or the page has ``rollspringPage`` but cannot be driven.
"""

from __future__ import annotations

import argparse
import contextlib
import itertools
import json
import math
import os
import re
import shutil
import signal
import statistics
import subprocess
import sys
import tempfile
import threading
import time
import urllib.error
import urllib.request
from pathlib import Path
from typing import Any

from common import machine_note, print_table

ROOT = Path(__file__).resolve().parent.parent
EXECUTABLE = Path(sys.executable).with_name("rollspring")
PRESET = "hoop-cylinder"
SWEEP = [80.0 + 2.0 * i for i in range(21)] + [118.0 - 2.0 * i for i in range(20)]  # N/m
TARGET_A_P95 = 20.0  # ms, one client's round trip
TARGET_FPS = 55.0
TARGET_UPDATE_P95 = 50.0  # ms, slider change -> new motion on screen
ARGS = [
    "--no-sandbox",
    "--disable-gpu",
    "--disable-quic",
    "--no-first-run",
    "--disable-background-networking",
    "--disable-component-update",
    "--disable-sync",
]


class Broken(Exception):
    """Something the benchmark needs does not work (exit status 1)."""


# -- the server ---------------------------------------------------------------------------------


class Server:
    """``rollspring serve`` in a subprocess (its own session), stopped with SIGINT."""

    def __init__(self, *extra: str) -> None:
        self.log = tempfile.NamedTemporaryFile(  # noqa: SIM115 - the server's stderr, for its life
            prefix="bench-web-server-", suffix=".log", delete=False
        )
        self.command = [
            str(EXECUTABLE),
            "serve",
            PRESET,
            "--host",
            "127.0.0.1",
            "--port",
            "0",
            *extra,
        ]
        self.process = subprocess.Popen(
            self.command, stdout=subprocess.PIPE, stderr=self.log, text=True, start_new_session=True
        )
        self.stop_note = ""
        self.returncode: int | None = None
        self.stdout: list[str] = []
        self.url = self._read_url(timeout=90)
        threading.Thread(target=self._drain, daemon=True).start()

    def _read_url(self, timeout: float) -> str:
        found: list[str] = []

        def read() -> None:
            assert self.process.stdout is not None
            for line in self.process.stdout:
                match = re.search(r" at (http://\S+/) \(Ctrl-C stops\)", line)
                if match:
                    found.append(match.group(1))
                    return

        reader = threading.Thread(target=read, daemon=True)
        reader.start()
        reader.join(timeout)
        if not found:
            exited = self.process.poll()
            self.stop()
            why = (
                f"exited with status {exited} before printing its URL"
                if exited is not None
                else f"printed no URL within {timeout:g} s"
            )
            raise Broken(f"the server {why}; its stderr: {self.stderr()[-2000:]}")
        return found[0]

    def _drain(self) -> None:
        assert self.process.stdout is not None
        for line in self.process.stdout:
            self.stdout.append(line)

    def stderr(self) -> str:
        return Path(self.log.name).read_text(errors="replace")

    def alive(self) -> bool:
        return self.process.poll() is None

    def wait_ready(self, timeout: float = 60) -> float:
        """Wait until ``GET /api/presets`` answers; seconds since the URL was printed."""
        began = time.perf_counter()
        while True:
            try:
                with urllib.request.urlopen(self.url + "api/presets", timeout=10) as answer:
                    if answer.status == 200:
                        return time.perf_counter() - began
            except OSError:
                pass
            if not self.alive() or time.perf_counter() - began > timeout:
                raise Broken(
                    f"the server at {self.url} did not answer within {timeout:g} s; "
                    f"its stderr: {self.stderr()[-2000:]}"
                )
            time.sleep(0.2)

    def _session_processes(self) -> list[int]:
        """Processes still in the server's session (workers, the forkserver)."""
        left = []
        for entry in Path("/proc").iterdir():
            if not entry.name.isdigit():
                continue
            try:
                fields = (entry / "stat").read_text().rsplit(")", 1)[1].split()
            except OSError:
                continue
            if int(fields[3]) == self.process.pid:  # field 6 of stat: the session id
                left.append(int(entry.name))
        return left

    def stop(self) -> None:
        """Ctrl-C, as a user stops it; then SIGTERM, SIGKILL if it does not exit."""
        if self.returncode is not None:
            return
        if self.process.poll() is None:
            self.process.send_signal(signal.SIGINT)
            try:
                self.process.wait(15)
                self.stop_note = "stopped by SIGINT"
            except subprocess.TimeoutExpired:
                self.process.terminate()
                try:
                    self.process.wait(5)
                    self.stop_note = "did not stop on SIGINT within 15 s; stopped by SIGTERM"
                except subprocess.TimeoutExpired:
                    self.process.kill()
                    self.process.wait()
                    self.stop_note = "did not stop on SIGINT or SIGTERM; killed"
        else:
            self.stop_note = f"had exited on its own (status {self.process.returncode})"
        self.returncode = self.process.returncode
        deadline = time.monotonic() + 5
        left = self._session_processes()
        while left and time.monotonic() < deadline:
            time.sleep(0.2)
            left = self._session_processes()
        if left:
            self.stop_note += f"; {len(left)} of its processes were left running (killed)"
            for pid in left:
                with contextlib.suppress(OSError):
                    os.kill(pid, signal.SIGKILL)


def get_json(url: str) -> Any:
    with urllib.request.urlopen(url, timeout=30) as answer:
        return json.load(answer)


def post_json(url: str, body: bytes) -> tuple[int, Any, float]:
    """``(status, decoded body, seconds)`` of one POST."""
    request = urllib.request.Request(
        url, data=body, method="POST", headers={"Content-Type": "application/json"}
    )
    began = time.perf_counter()
    try:
        with urllib.request.urlopen(request, timeout=60) as answer:
            data = answer.read()
            status = answer.status
    except urllib.error.HTTPError as exc:
        data = exc.read()
        status = exc.code
    seconds = time.perf_counter() - began
    try:
        return status, json.loads(data), seconds
    except ValueError:
        return status, data[:200], seconds


# -- wrk -----------------------------------------------------------------------------------------

LUA = r"""
-- rollspring bench_web.py: POST /api/simulate, the spring stiffness swept between requests
local bodies = {
%(bodies)s
}
local threads = {}

function setup(thread)
  table.insert(threads, thread)
end

function init(args)
  statuses = {}
  requests_made = {}
  local headers = {["Content-Type"] = "application/json"}
  for i, body in ipairs(bodies) do
    requests_made[i] = wrk.format("POST", "/api/simulate", headers, body)
  end
  counter = 0
end

function request()
  counter = counter + 1
  return requests_made[(counter - 1) %% #requests_made + 1]
end

function response(status, headers, body)
  local key = tostring(status)
  if status == 503 then
    if body:sub(1, 11) == '{"detail":"' then
      key = "503 app"
    elseif body == "Service Unavailable" then
      key = "503 limit"
    else
      key = "503 other"
    end
  end
  statuses[key] = (statuses[key] or 0) + 1
end

function done(summary, latency, requests)
  local total = {}
  for _, thread in ipairs(threads) do
    for key, count in pairs(thread:get("statuses")) do
      total[key] = (total[key] or 0) + count
    end
  end
  local parts = {}
  for key, count in pairs(total) do
    table.insert(parts, string.format('"%%s": %%d', key, count))
  end
  local cuts = {}
  for _, p in ipairs({50, 75, 90, 95, 99}) do
    table.insert(cuts, string.format('"%%d": %%d', p, latency:percentile(p)))
  end
  local e = summary.errors
  io.write(string.format(
    'WRK_JSON {"requests": %%d, "duration_us": %%d, "bytes": %%d, ' ..
    '"errors": {"connect": %%d, "read": %%d, "write": %%d, "status": %%d, "timeout": %%d}, ' ..
    '"latency_us": {"min": %%d, "mean": %%.1f, "max": %%d, "stdev": %%.1f, ' ..
    '"percentiles": {%%s}}, ' ..
    '"statuses": {%%s}}\n',
    summary.requests, summary.duration, summary.bytes,
    e.connect, e.read, e.write, e.status, e.timeout,
    latency.min, latency.mean, latency.max, latency.stdev, table.concat(cuts, ", "),
    table.concat(parts, ", ")))
end
"""


def lua_script(bodies: list[str]) -> str:
    def long_string(text: str) -> str:
        level = 0
        while f"]{'=' * level}]" in text:
            level += 1
        return f"[{'=' * level}[{text}]{'=' * level}]"

    return LUA % {"bodies": ",\n".join("  " + long_string(b) for b in bodies)}


def run_wrk(
    url: str, script: Path, *, threads: int, connections: int, seconds: int, timeout: int
) -> dict[str, Any]:
    """One wrk run; the figures its ``done()`` printed, with wrk's own text."""
    command = [
        "wrk",
        f"-t{threads}",
        f"-c{connections}",
        f"-d{seconds}s",
        "--latency",
        f"--timeout={timeout}s",
        "-s",
        str(script),
        url,
    ]
    done = subprocess.run(
        command, capture_output=True, text=True, check=False, timeout=seconds + timeout + 60
    )
    line = next((ln for ln in done.stdout.splitlines() if ln.startswith("WRK_JSON ")), None)
    if done.returncode != 0 or line is None:
        raise Broken(
            f"wrk failed ({done.returncode}): {done.stderr.strip()[:1000]} "
            f"{done.stdout.strip()[-1000:]}"
        )
    figures = json.loads(line[len("WRK_JSON ") :])
    figures["command"] = " ".join([*command[:-3], "<script.lua>", url])
    figures["wrk_output"] = [
        ln for ln in done.stdout.splitlines() if not ln.startswith("WRK_JSON ")
    ]
    return summarise(figures)


def summarise(figures: dict[str, Any]) -> dict[str, Any]:
    """Derived figures of one wrk run (ms, requests/s, the statuses sorted out)."""
    statuses = figures["statuses"]
    ok = sum(n for key, n in statuses.items() if key[:1] == "2")
    designed = statuses.get("503 app", 0) + statuses.get("503 limit", 0)
    other_5xx = sum(
        n for key, n in statuses.items() if key[:1] == "5" and key not in ("503 app", "503 limit")
    )
    other = sum(n for key, n in statuses.items() if key[:1] not in "25")
    errors = figures["errors"]
    socket_errors = errors["connect"] + errors["read"] + errors["write"] + errors["timeout"]
    latency = figures["latency_us"]
    figures.update(
        {
            "requests_per_s": figures["requests"] / (figures["duration_us"] / 1e6),
            "p50_ms": latency["percentiles"]["50"] / 1e3,
            "p95_ms": latency["percentiles"]["95"] / 1e3,
            "p99_ms": latency["percentiles"]["99"] / 1e3,
            "max_ms": latency["max"] / 1e3,
            "ok_2xx": ok,
            "designed_503": designed,
            "other_5xx": other_5xx,
            "other_non_2xx": other,
            "socket_errors": socket_errors,
        }
    )
    return figures


def print_run(label: str, figures: dict[str, Any]) -> None:
    print(
        f"  {label}: {figures['requests']} requests, {figures['requests_per_s']:.1f}/s, "
        f"p50 {figures['p50_ms']:.2f} ms, p95 {figures['p95_ms']:.2f} ms, "
        f"p99 {figures['p99_ms']:.2f} ms, max {figures['max_ms']:.1f} ms; "
        f"statuses {figures['statuses']}; socket errors {figures['errors']}",
        flush=True,
    )


# -- the page in Chromium -----------------------------------------------------------------------

FIND_SLIDERS = """() => [...document.querySelectorAll('input[type=range]')].map((el, i) => {
  const by = (el.getAttribute('aria-labelledby') || '').split(/\\s+/).filter(Boolean)
    .map(id => (document.getElementById(id) || {}).textContent || '');
  const labels = [...(el.labels || [])].map(l => l.textContent);
  return {index: i, id: el.id, name: el.name, value: el.value, min: el.min, max: el.max,
          step: el.step, visible: !!(el.offsetWidth || el.offsetHeight),
          text: [el.getAttribute('aria-label') || '', el.title || '', ...labels, ...by,
                 JSON.stringify(el.dataset)].join(' | ')};
})"""


# Where the time from a change to its first frame goes, from the browser's resource timing of the
# API requests the page sent after the change: "wait" from the change to the first request
# (the page's debounce), "requests" from then until the last answer is in (network, server,
# both computations), "client" from then to the frame (parsing, plots, drawing).
STAGES = """update => {
  const sent = performance.getEntriesByType('resource').filter(e =>
    /\\/api\\/(simulate|analyze)$/.test(new URL(e.name).pathname) &&
    e.startTime >= update.changed && e.responseEnd <= update.drawn);
  if (!sent.length) return {wait: null, requests: null, client: null, count: 0,
                           simulate: null, analyze: null};
  const first = Math.min(...sent.map(e => e.startTime));
  const last = Math.max(...sent.map(e => e.responseEnd));
  const took = path => Math.max(0, ...sent.filter(e => e.name.endsWith(path))
    .map(e => e.responseEnd - e.startTime));
  return {wait: first - update.changed, requests: last - first, client: update.drawn - last,
          count: sent.length, simulate: took('/api/simulate'), analyze: took('/api/analyze')};
}"""


def stiffness_slider(sliders: list[dict[str, Any]]) -> dict[str, Any] | None:
    """The spring stiffness's range input: labelled 'stiffness' (or the spring's k)."""
    for pattern in (r"stiff", r"spring.*\bk\b|\bk\b.*spring|\bk \(N/m\)|N/m"):
        found = [s for s in sliders if s["visible"] and re.search(pattern, s["text"], re.I)]
        if found:
            return found[0]
    return None


def percentile(values: list[float], p: float) -> float:
    """Linear-interpolated percentile (numpy's default)."""
    ordered = sorted(values)
    if len(ordered) == 1:
        return ordered[0]
    rank = (len(ordered) - 1) * p / 100
    low = math.floor(rank)
    high = min(low + 1, len(ordered) - 1)
    return ordered[low] + (ordered[high] - ordered[low]) * (rank - low)


def measure_page(url: str, *, seconds: float = 5.0, changes: int = 20) -> dict[str, Any]:
    """(c): frame rate while playing and slider-change-to-screen latency. ``{"skipped": why}``
    when the page or Chromium is missing; raises :class:`Broken` when the page has its hooks
    but cannot be driven."""
    try:
        from playwright.sync_api import Error as PlaywrightError
        from playwright.sync_api import sync_playwright
    except ImportError as exc:
        return {"skipped": f"Playwright is not installed ({exc})"}
    try:
        from rollspring.outputs.report import find_chromium

        chromium = find_chromium()
    except Exception:  # noqa: BLE001 - fall back to Debian's path
        chromium = "/usr/bin/chromium"
    if not Path(chromium).exists():
        return {"skipped": f"no Chromium ({chromium}); apt-get install chromium"}

    result: dict[str, Any] = {"chromium": chromium}
    problems: list[str] = []
    failed: list[str] = []
    with sync_playwright() as playwright:
        browser = playwright.chromium.launch(executable_path=chromium, args=ARGS)
        try:
            page = browser.new_page(viewport={"width": 1280, "height": 900})
            page.on(
                "console",
                lambda m: problems.append(f"console: {m.text}") if m.type == "error" else None,
            )
            page.on("pageerror", lambda e: problems.append(f"page error: {e}"))
            page.on(
                "response",
                lambda r: (
                    failed.append(f"{r.status} {r.request.method} {r.url}")
                    if r.status >= 400
                    else None
                ),
            )
            began = time.perf_counter()
            answer = page.goto(url, wait_until="load")
            status = answer.status if answer is not None else None
            try:
                page.wait_for_function("() => window.rollspringPage !== undefined", timeout=10_000)
            except PlaywrightError:
                why = (
                    f"GET / answered {status}"
                    if status != 200
                    else "the page has no window.rollspringPage"
                )
                return {
                    "skipped": f"{why} (the page or its benchmark hooks are not there "
                    f"yet); (c) not measured",
                    "problems": problems + failed,
                }
            try:
                page.evaluate("async () => { await window.rollspringPage.ready(); }")
                result["ready_ms"] = (time.perf_counter() - began) * 1e3
                result.update(_frame_rate(page, seconds))
                result.update(_slider_updates(page, changes))
            except PlaywrightError as exc:
                raise Broken(
                    f"the page could not be driven: {str(exc).splitlines()[0]}; "
                    f"page problems: {problems + failed}"
                ) from None
        finally:
            browser.close()
    result["problems"] = problems + failed
    return result


def _press_play(page: Any) -> str:
    """Click the Play button (by its accessible name); returns what was clicked."""
    button = page.get_by_role("button", name="Play", exact=True)  # not "Play mode 2"
    if button.count() == 0:
        button = page.locator("#play, [data-action=play]")
    if button.count() == 0:
        button = page.get_by_role("button", name=re.compile(r"^\W*play\W*$", re.I))
    if button.count() == 0:
        raise Broken("the page has no Play button (a button named 'Play')")
    # a handle, not the locator: once playing, the button is named "Pause" and the locator by
    # name would wait for it to read "Play" again (the end of the motion)
    handle = button.first.element_handle()
    clicked = handle.evaluate("el => el.outerHTML.slice(0, 120)")
    handle.click()
    return clicked


def _frame_rate(page: Any, seconds: float) -> dict[str, Any]:
    clicked = _press_play(page)
    page.wait_for_timeout(500)  # the first frames after Play (layout, first draw) left out
    start = page.evaluate("() => performance.now()")
    stamps: set[float] = set()
    end = start + seconds * 1e3
    now = start
    while now < end:  # frameTimes() holds the recent frames only: gathered every 0.25 s
        page.wait_for_timeout(250)
        got = page.evaluate(
            "() => [performance.now(), Array.from(window.rollspringPage.frameTimes())]"
        )
        now = got[0]
        stamps.update(float(t) for t in got[1])
    times = sorted(t for t in stamps if start <= t <= end)
    if len(times) < 3:
        raise Broken(
            f"frameTimes() gave {len(times)} frames over {seconds:g} s after Play ({clicked})"
        )
    gaps = [b - a for a, b in itertools.pairwise(times) if b > a]
    rates = [1e3 / gap for gap in gaps]
    return {
        "play_button": clicked,
        "frames": len(times),
        "frame_window_ms": times[-1] - times[0],
        "fps_mean": (len(times) - 1) / (times[-1] - times[0]) * 1e3,
        "fps_p5": percentile(rates, 5),
        "frame_interval_p50_ms": percentile(gaps, 50),
        "frame_interval_p95_ms": percentile(gaps, 95),
        "frame_interval_max_ms": max(gaps),
    }


def _slider_updates(page: Any, changes: int) -> dict[str, Any]:
    sliders = page.evaluate(FIND_SLIDERS)
    slider = stiffness_slider(sliders)
    if slider is None:
        raise Broken(
            "no visible range input labelled for the spring stiffness among "
            f"{[s['text'] for s in sliders]}"
        )
    element = page.locator("input[type=range]").nth(slider["index"])
    delays: list[float] = []
    stages: list[dict[str, float | None]] = []
    page.evaluate("() => performance.setResourceTimingBufferSize(10000)")
    method = "keyboard"
    playing = 0  # changes made while the animation played (the motion is 10 s long)
    for i in range(changes):
        key = "ArrowRight" if (i // 5) % 2 == 0 else "ArrowLeft"  # 5 up, 5 down, ...
        before = page.evaluate("() => window.rollspringPage.lastUpdate()") or {}
        playing += page.evaluate(
            "() => /pause/i.test(document.querySelector('#play')?.getAttribute('aria-label') || '')"
        )
        value = element.input_value()
        element.focus()
        if method == "keyboard":
            page.keyboard.press(key)
            if element.input_value() == value:  # the key did not move it: set it instead
                method = "value + change event"
        if method != "keyboard":
            element.evaluate(
                """(el, up) => {
                     const step = Number(el.step) || (Number(el.max) - Number(el.min)) / 100;
                     el.value = String(Number(el.value) + (up ? step : -step));
                     el.dispatchEvent(new Event('input', {bubbles: true}));
                     el.dispatchEvent(new Event('change', {bubbles: true}));
                   }""",
                key == "ArrowRight",
            )
        page.wait_for_function(
            """before => { const u = window.rollspringPage.lastUpdate();
                 return u && u.changed != null && u.drawn != null
                   && u.changed !== (before && before.changed) && u.drawn >= u.changed; }""",
            arg=before,
            timeout=10_000,
        )
        update = page.evaluate("() => window.rollspringPage.lastUpdate()")
        delays.append(float(update["drawn"]) - float(update["changed"]))
        stages.append(page.evaluate(STAGES, update))
        page.wait_for_timeout(300)  # a pause between releases
    breakdown = {}
    for key in ("wait", "requests", "client", "simulate", "analyze"):
        known = [s[key] for s in stages if s.get(key) is not None]
        breakdown[key] = (
            {"p50": percentile(known, 50), "p95": percentile(known, 95)} if known else None
        )
    return {
        "slider": {k: slider[k] for k in ("id", "text", "min", "max", "step")},
        "slider_method": method,
        "changes_while_playing": playing,
        "update_ms": delays,
        "update_stages_ms": stages,
        "update_breakdown_ms": breakdown,
        "update_p50_ms": percentile(delays, 50),
        "update_p95_ms": percentile(delays, 95),
        "update_max_ms": max(delays),
    }


# -- the report ---------------------------------------------------------------------------------


def spread(values: list[float], spec: str = ".1f", unit: str = "") -> str:
    """'median (min–max)' of the runs (just the value for one run)."""
    middle = format(statistics.median(values), spec) + unit
    if len(values) == 1:
        return middle
    return f"{middle} ({format(min(values), spec)}–{format(max(values), spec)})"


def mark(ok: bool | None) -> str:
    return "-" if ok is None else ("✔" if ok else "✘")


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--runs", type=int, default=3, help="wrk runs of (a) and of (b)")
    parser.add_argument("--single-seconds", type=int, default=10, help="length of each (a) run")
    parser.add_argument("--many-seconds", type=int, default=20, help="length of each (b) run")
    parser.add_argument("--clients", type=int, default=16, help="connections of (b)")
    parser.add_argument("--no-browser", action="store_true", help="leave (c) out")
    parser.add_argument(
        "--json",
        type=Path,
        default=ROOT / "build" / "bench" / "web.json",
        help="where to write the figures",
    )
    args = parser.parse_args()
    print(machine_note())
    if shutil.which("wrk") is None:
        print(
            "wrk is not installed (Debian: apt-get install wrk); nothing measured", file=sys.stderr
        )
        return 1
    version = subprocess.run(
        ["wrk", "--version"], capture_output=True, text=True, check=False
    ).stdout.splitlines()
    print(
        f"load generator: {version[0] if version else 'wrk'}; {os.cpu_count()} CPUs shared "
        "by the load generator, the server and its workers, and the browser"
    )
    record: dict[str, Any] = {
        "machine": machine_note(),
        "wrk": version[:1],
        "runs": args.runs,
        "targets": {
            "single_p95_ms": TARGET_A_P95,
            "fps": TARGET_FPS,
            "update_p95_ms": TARGET_UPDATE_P95,
            "many_5xx_other_than_503": 0,
        },
    }
    status = 0
    server = None
    try:
        server = Server()
        record["server"] = {
            "command": " ".join(server.command[1:]),
            "url": server.url,
            "ready_s": server.wait_ready(),
        }
        print(f"server: {' '.join(server.command[1:])} -> {server.url}", flush=True)
        status = measure(server, args, record)
    except Broken as exc:
        print(f"BROKEN: {exc}", file=sys.stderr)
        record["broken"] = str(exc)
        status = 1
    finally:
        if server is not None:
            server.stop()
            errors = [
                ln
                for ln in server.stderr().splitlines()
                if re.search(r"Traceback|ERROR|Exception|Error:", ln)
            ]
            record.setdefault("server", {}).update(
                {
                    "stop": server.stop_note,
                    "exit_status": server.returncode,
                    "stderr_error_lines": errors[:50],
                }
            )
            print(
                f"server {server.stop_note}, exit status {server.returncode}; "
                f"{len(errors)} error lines in its log"
                + (f" (first: {errors[0]!r}; log {server.log.name})" if errors else "")
            )
            if not errors:
                Path(server.log.name).unlink(missing_ok=True)
    args.json.parent.mkdir(parents=True, exist_ok=True)
    args.json.write_text(json.dumps(record, indent=2, default=str) + "\n")
    print(f"figures written to {args.json}")
    return status


def measure(server: Server, args: argparse.Namespace, record: dict[str, Any]) -> int:
    presets = get_json(server.url + "api/presets")
    system = next(p["system"] for p in presets if p["name"] == PRESET)
    bodies = []
    for stiffness in SWEEP:
        varied = json.loads(json.dumps(system))
        varied["springs"][0]["stiffness"] = stiffness
        bodies.append(json.dumps({"system": varied, "duration": 10, "outputs": 600}))
    # one request by hand: the answer is what the page needs (600 outputs, 10 s, finished)
    code, answer, seconds = post_json(server.url + "api/simulate", bodies[0].encode())
    if code != 200 or len(answer.get("t", [])) != 600 or answer["summary"]["status"] != "finished":
        raise Broken(f"POST /api/simulate answered {code}: {str(answer)[:300]}")
    size = len(json.dumps(answer))
    print(
        f"one request: 200, {len(answer['t'])} outputs, about {size / 1e3:.0f} kB of JSON, "
        f"{seconds * 1e3:.1f} ms (cold)"
    )
    record["response_kB"] = size / 1e3

    with tempfile.TemporaryDirectory(prefix="bench-web-") as folder:
        script = Path(folder) / "slider.lua"
        script.write_text(lua_script(bodies))
        run_wrk(server.url, script, threads=1, connections=2, seconds=2, timeout=15)  # warm-up
        single = []
        print(f"(a) one client, {args.single_seconds} s each:", flush=True)
        for i in range(args.runs):
            single.append(
                run_wrk(
                    server.url,
                    script,
                    threads=1,
                    connections=1,
                    seconds=args.single_seconds,
                    timeout=15,
                )
            )
            print_run(f"run {i + 1}", single[-1])
        many = []
        print(f"(b) {args.clients} clients, {args.many_seconds} s each:", flush=True)
        for i in range(args.runs):
            many.append(
                run_wrk(
                    server.url,
                    script,
                    threads=1,
                    connections=args.clients,
                    seconds=args.many_seconds,
                    timeout=30,
                )
            )
            print_run(f"run {i + 1}", many[-1])
    if not server.alive():
        raise Broken(f"the server died under load; its stderr: {server.stderr()[-2000:]}")
    record["single"] = single
    record["many"] = many

    if args.no_browser:
        page: dict[str, Any] = {"skipped": "--no-browser"}
    else:
        print("(c) the page in headless Chromium ...", flush=True)
        page = measure_page(server.url)
    record["page"] = page
    if "skipped" in page:
        print(f"(c) SKIPPED: {page['skipped']}")
    else:
        print(
            f"(c) {page['frames']} frames over {page['frame_window_ms'] / 1e3:.1f} s; "
            f"slider changes ({page['slider_method']}, slider {page['slider']['text']!r}, "
            f"{page['changes_while_playing']} while playing): "
            + ", ".join(f"{d:.1f}" for d in page["update_ms"])
            + " ms"
        )
        parts = [
            f"{key} p50 {v['p50']:.1f} / p95 {v['p95']:.1f} ms"
            for key, v in page["update_breakdown_ms"].items()
            if v
        ]
        print(
            "    where it goes (change → first API request sent, → last answer in, → frame "
            "drawn): " + "; ".join(parts)
        )
    if page.get("problems"):
        print(f"(c) page problems: {page['problems'][:10]}")

    p95a = [r["p95_ms"] for r in single]
    p50a = [r["p50_ms"] for r in single]
    p95b = [r["p95_ms"] for r in many]
    other_5xx = sum(r["other_5xx"] for r in many)
    other_fail = sum(r["other_non_2xx"] + r["socket_errors"] for r in many)
    rows = [
        ["(a) 1 client: round trip p50", spread(p50a, ".2f", " ms"), "-", "-"],
        [
            "(a) 1 client: round trip p95",
            spread(p95a, ".2f", " ms"),
            f"≤ {TARGET_A_P95:g} ms",
            mark(statistics.median(p95a) <= TARGET_A_P95),
        ],
        ["(a) 1 client: requests/s", spread([r["requests_per_s"] for r in single]), "-", "-"],
        [
            "(a) 1 client: not 2xx",
            str(sum(r["requests"] - r["ok_2xx"] for r in single)),
            "0",
            mark(all(r["requests"] == r["ok_2xx"] for r in single)),
        ],
        [
            f"(b) {args.clients} clients: requests/s",
            spread([r["requests_per_s"] for r in many]),
            "-",
            "-",
        ],
        [
            f"(b) {args.clients} clients: round trip p50",
            spread([r["p50_ms"] for r in many], ".1f", " ms"),
            "-",
            "-",
        ],
        [f"(b) {args.clients} clients: round trip p95", spread(p95b, ".1f", " ms"), "-", "-"],
        [
            f"(b) {args.clients} clients: designed 503s",
            str(sum(r["designed_503"] for r in many)),
            "-",
            "-",
        ],
        [f"(b) {args.clients} clients: other 5xx", str(other_5xx), "0", mark(other_5xx == 0)],
        [
            f"(b) {args.clients} clients: other failures (4xx, socket errors, timeouts)",
            str(other_fail - other_5xx),
            "0",
            mark(other_fail == other_5xx),
        ],
    ]
    if "skipped" in page:
        rows.append(["(c) page", "skipped", "-", "-"])
    else:
        rows += [
            [
                "(c) frame rate, mean",
                f"{page['fps_mean']:.1f} fps",
                f"≥ {TARGET_FPS:g} fps",
                mark(page["fps_mean"] >= TARGET_FPS),
            ],
            [
                "(c) frame rate, 5th percentile of 1/Δt",
                f"{page['fps_p5']:.1f} fps",
                f"≥ {TARGET_FPS:g} fps",
                mark(page["fps_p5"] >= TARGET_FPS),
            ],
            [
                "(c) slider change → new motion drawn, p50",
                f"{page['update_p50_ms']:.1f} ms",
                "-",
                "-",
            ],
            [
                "(c) slider change → new motion drawn, p95",
                f"{page['update_p95_ms']:.1f} ms",
                f"≤ {TARGET_UPDATE_P95:g} ms",
                mark(page["update_p95_ms"] <= TARGET_UPDATE_P95),
            ],
        ]
    runs = f"{args.runs} run{'s' if args.runs > 1 else ''}"
    print_table(
        f"rollspring serve {PRESET} (workers = cores, limit-concurrency 64): "
        f"POST /api/simulate 10 s, 600 outputs, stiffness swept; median (range) of "
        f"{runs}",
        ["measurement", "measured", "target", "met"],
        rows,
    )
    record["table"] = rows
    return 0


if __name__ == "__main__":
    sys.exit(main())

"""``rollspring serve`` from its command line: bad options are one-line errors with exit 2
before anything starts; another address than loopback is served with a warning; the URL is
printed only once the server answers (its workers warmed first, with a progress line)."""

from __future__ import annotations

import contextlib
import os
import re
import signal
import subprocess
import time
from pathlib import Path

import pytest
import requests
from typer.testing import CliRunner

from rollspring.cli import app
from rollspring.errors import ServeError
from rollspring.web import create_app
from rollspring.web.workers import max_workers
from tests.serving import SERVE, Server


@pytest.mark.parametrize(
    ("args", "words"),
    [
        (["--port", "70000"], "--port: must be 0 to 65535"),
        (["--port", "-1"], "--port: must be 0 to 65535"),
        (["--budget", "0"], "--budget: must be a positive number"),
        (["--budget", "inf"], "--budget: must be a positive number of seconds up to 86400"),
        (["--budget", "1e9"], "--budget: must be a positive number of seconds up to 86400"),
        (["--workers", "-2"], "--workers: must be 0 (one per core) to"),
        (["--workers", "100000"], "per core), got 100000"),
        (["--limit-concurrency", "0"], "--limit-concurrency: must be at least 1"),
        (["no-such-system"], "neither a file nor a preset"),
        (["--host", "no.such.host.invalid", "--port", "0"], "--host: cannot listen"),
    ],
)
def test_bad_options_are_one_line_errors(args: list[str], words: str) -> None:
    result = CliRunner().invoke(app, ["serve", *args])
    assert result.exit_code == 2, result.output
    assert words in result.stderr
    assert len(result.stderr.strip().splitlines()) == 1


def test_a_port_in_use_is_a_one_line_error() -> None:
    running = Server()
    try:
        port = running.url.rstrip("/").rsplit(":", 1)[1]
        result = CliRunner().invoke(app, ["serve", "--port", port])
        assert result.exit_code == 2
        assert "--port: cannot listen on 127.0.0.1:" in result.stderr
    finally:
        running.stop()


def test_another_address_than_loopback_is_served_with_a_warning() -> None:
    running = Server("--host", "0.0.0.0", "wall-hoop-cylinder")
    try:
        start = requests.get(running.url + "api/start", timeout=10).json()
        assert start["preset"] == "wall-hoop-cylinder"
    finally:
        errors = running.stop()
    assert "warning: serving on 0.0.0.0, reachable from other machines" in errors


@pytest.mark.parametrize(
    ("options", "words"),
    [
        ({"workers": 10**5}, "workers: must be 0 (one per core) to"),
        ({"workers": True}, "workers: must be a whole number"),
        ({"budget": float("inf")}, "budget: must be a positive number of seconds up to 86400"),
        ({"budget": "10"}, "budget: must be a number of seconds"),
    ],
)
def test_create_app_checks_its_pool_before_any_process_starts(options, words) -> None:
    with pytest.raises(ServeError, match=words.replace("(", r"\(").replace(")", r"\)")):
        create_app(**options)


def _group_alive(group: int) -> bool:
    try:
        os.killpg(group, 0)
    except ProcessLookupError:
        return False
    return True


@pytest.mark.parametrize("when", ["starting", "serving"])
def test_sigterm_stops_the_server_and_every_worker(when: str) -> None:
    """SIGTERM while the workers start (as many as allowed) or while it serves: the server and
    its workers are gone soon after (measured: under a second), nothing left in its group.
    Before, ``--workers 100000`` forked on and SIGTERM did not stop it."""
    process = subprocess.Popen(
        [SERVE, "serve", "--port", "0", "--workers", str(max_workers())],
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
        start_new_session=True,
    )
    try:
        assert process.stdout is not None and process.stderr is not None
        if when == "starting":  # the progress line: the workers are starting
            assert "warming up" in process.stderr.readline()
        else:  # the URL: it answers, its workers warm
            line = process.stdout.readline()
            url = re.search(r"http://127\.0\.0\.1:\d+/", line).group(0)  # type: ignore[union-attr]
            assert requests.get(url + "api/start", timeout=30).status_code == 200
        process.send_signal(signal.SIGTERM)
        process.communicate(timeout=30)
        deadline = time.monotonic() + 30
        while _group_alive(process.pid) and time.monotonic() < deadline:
            time.sleep(0.1)
        assert not _group_alive(process.pid), "worker processes outlived the server"
    finally:
        if _group_alive(process.pid):
            os.killpg(process.pid, signal.SIGKILL)
        process.communicate(timeout=30)


def _group(leader: int) -> list[int]:
    """The processes of the process group ``leader`` leads, but the leader."""
    found = []
    for stat in Path("/proc").glob("[0-9]*/stat"):
        with contextlib.suppress(OSError, IndexError, ValueError):
            fields = stat.read_text().rsplit(")", 1)[1].split()
            if int(fields[2]) == leader and int(stat.parent.name) != leader:
                found.append(int(stat.parent.name))
    return found


def test_the_url_is_printed_only_once_the_server_answers() -> None:
    """Issue 26: the URL came 9-37 s before the server answered (``--open`` showed a hanging
    browser). Now the workers warm first, with a progress line, and the URL follows. At the
    moment it appears the worker processes are all there, warm: frozen (SIGSTOP), the server
    still answers the page at once, for it waits on nothing more."""
    process = subprocess.Popen(
        [SERVE, "serve", "--port", "0", "--workers", "2"],
        stdout=subprocess.PIPE,
        stderr=subprocess.STDOUT,  # one stream: the order of the lines
        text=True,
        start_new_session=True,
    )
    frozen: list[int] = []
    try:
        assert process.stdout is not None
        lines = []
        for line in process.stdout:
            lines.append(line)
            if "http://" in line:
                break
        assert lines[0].startswith("rollspring: warming up 2 worker processes")
        assert "2/2 ready" in lines[-2], lines
        url = re.search(r"http://127\.0\.0\.1:\d+/", lines[-1]).group(0)  # type: ignore[union-attr]
        # the forkserver, its two workers (and multiprocessing's resource tracker)
        frozen = _group(process.pid)
        assert len(frozen) >= 3, frozen
        for pid in frozen:
            os.kill(pid, signal.SIGSTOP)
        page = requests.get(url, timeout=60)
        assert page.status_code == 200
        assert "<title>rollspring" in page.text
        for pid in frozen:
            os.kill(pid, signal.SIGCONT)
        frozen = []
        system = requests.get(url + "api/start", timeout=60).json()
        analysis = requests.post(url + "api/analyze", json={"system": system["system"]}, timeout=60)
        assert analysis.status_code == 200
        assert len(analysis.json()["modes"]) == 2
    finally:
        for pid in frozen:
            with contextlib.suppress(ProcessLookupError):
                os.kill(pid, signal.SIGCONT)
        process.send_signal(signal.SIGINT)
        try:
            process.communicate(timeout=30)
        except subprocess.TimeoutExpired:
            os.killpg(process.pid, signal.SIGKILL)
            process.communicate(timeout=30)

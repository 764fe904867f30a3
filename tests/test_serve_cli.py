"""``rollspring serve`` from its command line: bad options are one-line errors with exit 2
before anything starts; another address than loopback is served with a warning."""

from __future__ import annotations

import os
import re
import signal
import subprocess
import time

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
        assert process.stdout is not None
        line = process.stdout.readline()
        assert "http://127.0.0.1:" in line
        url = re.search(r"http://\S+/", line).group(0)  # type: ignore[union-attr]
        while when == "serving":  # until it answers: its workers are warm
            try:
                if requests.get(url + "api/start", timeout=30).status_code == 200:
                    break
            except requests.ConnectionError:
                time.sleep(0.2)
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

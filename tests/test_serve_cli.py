"""``rollspring serve`` from its command line: bad options are one-line errors with exit 2
before anything starts; another address than loopback is served with a warning."""

from __future__ import annotations

import pytest
import requests
from typer.testing import CliRunner

from rollspring.cli import app
from tests.serving import Server


@pytest.mark.parametrize(
    ("args", "words"),
    [
        (["--port", "70000"], "--port: must be 0 to 65535"),
        (["--port", "-1"], "--port: must be 0 to 65535"),
        (["--budget", "0"], "--budget: must be a positive number"),
        (["--workers", "-2"], "--workers: must be 0 or more"),
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

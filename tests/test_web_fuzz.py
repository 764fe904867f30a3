"""The web API against its own OpenAPI schema, on the real server: Schemathesis generates
requests from ``/openapi.json`` (valid and invalid ones) and checks that none gets a 5xx, that
every status code and content type is one the schema documents, and that every response body
fits its documented schema; and uvicorn's concurrency limit answers overload with 503 at once.
"""

from __future__ import annotations

import json
import os
import signal
import socket
import time
from collections.abc import Iterator
from pathlib import Path

import pytest
import requests
import schemathesis
from hypothesis import HealthCheck, given, settings
from schemathesis import GenerationMode, checks

from tests.serving import Server


@pytest.fixture(scope="module")
def server() -> Iterator[Server]:
    # under the client's timeout, and far above what any request takes on a quiet machine
    # (a cold Numba cache compiles inside it): a loaded one must not turn a slow answer into
    # a 503 "server error"
    running = Server("--budget", "120")
    yield running
    errors = running.stop()
    assert "Traceback" not in errors, errors


#: No 5xx, documented status codes and content types, bodies that fit their schema, and
#: schema-invalid requests rejected with a 4xx.
CHECKS = [
    checks.not_a_server_error,
    checks.status_code_conformance,
    checks.content_type_conformance,
    checks.response_schema_conformance,
    checks.negative_data_rejection,
]

#: Examples per operation and generation mode; the symbolic ones (derive, report: seconds
#: each) get fewer.
EXAMPLES = {"/api/derive": 6, "/api/report": 4}


@pytest.mark.parametrize("mode", list(GenerationMode), ids=lambda mode: mode.value)
def test_the_api_keeps_its_schema_and_never_fails(server: Server, mode: GenerationMode) -> None:
    """Every operation of ``/openapi.json``, with requests generated from its schema (valid
    ones, and with ``negative`` invalid ones)."""
    schema = schemathesis.openapi.from_url(server.url + "openapi.json")
    operations = [result.ok() for result in schema.get_all_operations()]
    assert {op.path for op in operations} >= {"/api/analyze", "/api/simulate", "/api/derive"}
    seen = 0
    for operation in operations:
        if mode is GenerationMode.NEGATIVE and operation.method.upper() == "GET":
            continue  # no parameters: nothing to make invalid

        @given(case=operation.as_strategy(generation_mode=mode))
        @settings(
            max_examples=EXAMPLES.get(operation.path, 40),
            deadline=None,
            derandomize=True,
            database=None,
            suppress_health_check=list(HealthCheck),
        )
        def call(case) -> None:
            nonlocal seen
            case.call_and_validate(base_url=server.url.rstrip("/"), checks=CHECKS, timeout=150)
            seen += 1

        call()
    assert seen > 100


def _descendants(pid: int) -> list[int]:
    """Every process below ``pid`` (Linux's /proc: the server's forkserver and workers)."""
    found: list[int] = []
    for task in Path(f"/proc/{pid}/task").iterdir():
        for child in (task / "children").read_text().split():
            found += [int(child), *_descendants(int(child))]
    return found


def _wait_until_read(server_port: int, client_port: int) -> None:
    """Until the server has read every byte the client at ``client_port`` sent it: the
    receive queue of the server's end of that connection (Linux's /proc/net/tcp{,6}) is
    empty. uvicorn parses what it reads in the same callback, so the request is counted."""
    deadline = time.monotonic() + 60
    while True:
        for table in ("/proc/net/tcp", "/proc/net/tcp6"):
            for line in Path(table).read_text().splitlines()[1:]:
                fields = line.split()
                local, remote, queues = fields[1], fields[2], fields[4]
                if (
                    int(local.rsplit(":", 1)[1], 16) == server_port
                    and int(remote.rsplit(":", 1)[1], 16) == client_port
                    and int(queues.split(":")[1], 16) == 0
                ):
                    return
        assert time.monotonic() < deadline, "the server did not read the request"
        time.sleep(0.01)


def test_overload_is_answered_503_at_once() -> None:
    """With room for two connections, a third gets 503 at once while the one in service is
    still served (a connection counts itself: a limit of 1 would refuse everything).

    Deterministic, whatever the machine's speed: the server's worker processes are stopped
    (SIGSTOP), so the request in service cannot finish until the test lets them go on
    (SIGCONT); uvicorn counts its connection while the third one comes, and the third
    connects only once the server has read the request in service."""
    busy = Server("--limit-concurrency", "2", "--workers", "1", "--budget", "60")
    try:
        three = requests.get(busy.url + "api/presets", timeout=10).json()
        chain = next(p["system"] for p in three if p["name"] == "three-bodies")
        body = json.dumps({"system": chain}).encode()
        host, port = busy.url.split("//")[1].rstrip("/").split(":")
        workers = _descendants(busy.process.pid)
        assert workers
        for pid in workers:
            os.kill(pid, signal.SIGSTOP)
        try:
            in_service = socket.create_connection((host, int(port)), timeout=60)
            in_service.sendall(
                f"POST /api/analyze HTTP/1.1\r\nHost: {host}\r\nConnection: close\r\n"
                f"Content-Type: application/json\r\nContent-Length: {len(body)}\r\n\r\n".encode()
                + body
            )
            # counted once the server has read it (else both connections could come in one
            # batch of the event loop, and the one in service be the one refused)
            _wait_until_read(int(port), in_service.getsockname()[1])
            refused = requests.get(busy.url + "api/presets", timeout=10)
            assert refused.status_code == 503
        finally:
            for pid in workers:
                os.kill(pid, signal.SIGCONT)
        answer = b""
        try:
            while chunk := in_service.recv(65536):
                answer += chunk
        finally:
            in_service.close()
        assert answer.startswith(b"HTTP/1.1 200"), answer[:200]
        assert b'"modes"' in answer
        # and once the connections have closed, it serves again
        deadline = time.monotonic() + 10
        while requests.get(busy.url + "api/presets", timeout=10).status_code != 200:
            assert time.monotonic() < deadline, "still refusing after the load was gone"
            time.sleep(0.1)
    finally:
        busy.stop()

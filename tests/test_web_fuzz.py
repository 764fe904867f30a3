"""The web API against its own OpenAPI schema, on the real server: Schemathesis generates
requests from ``/openapi.json`` (valid and invalid ones) and checks that none gets a 5xx, that
every status code and content type is one the schema documents, and that every response body
fits its documented schema; and uvicorn's concurrency limit answers overload with 503 at once.
"""

from __future__ import annotations

import socket
import time
from collections.abc import Iterator

import pytest
import requests
import schemathesis
from hypothesis import HealthCheck, given, settings
from schemathesis import GenerationMode, checks

from tests.serving import Server


@pytest.fixture(scope="module")
def server() -> Iterator[Server]:
    running = Server("--budget", "5")
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
            case.call_and_validate(base_url=server.url.rstrip("/"), checks=CHECKS, timeout=30)
            seen += 1

        call()
    assert seen > 100


def test_overload_is_answered_503_at_once() -> None:
    """With room for two connections, a third gets 503 at once while the open one is still
    served (a connection counts itself: a limit of 1 would refuse everything).

    Deterministic, whatever the machine's speed: the open connection is a raw socket holding
    a request whose headers are not finished, so it stays open until the test finishes it."""
    busy = Server("--limit-concurrency", "2", "--workers", "1", "--budget", "30")
    try:
        host, port = busy.url.split("//")[1].rstrip("/").split(":")
        held = socket.create_connection((host, int(port)), timeout=30)
        try:
            held.sendall(f"GET /api/presets HTTP/1.1\r\nHost: {host}\r\n".encode())
            refused = requests.get(busy.url + "api/presets", timeout=10)
            assert refused.status_code == 503
            # the held request, finished now, is served
            held.sendall(b"Connection: close\r\n\r\n")
            answer = b""
            while chunk := held.recv(65536):
                answer += chunk
        finally:
            held.close()
        assert answer.startswith(b"HTTP/1.1 200"), answer[:200]
        assert b"hoop-cylinder" in answer
        # and once the connections have closed, it serves again
        deadline = time.monotonic() + 10
        while requests.get(busy.url + "api/presets", timeout=10).status_code != 200:
            assert time.monotonic() < deadline, "still refusing after the load was gone"
            time.sleep(0.1)
    finally:
        busy.stop()

"""Slow clients cut off (issue 28), over the real server on loopback (server.local).

A request whose headers or body do not arrive within ``KINEMATICS_REQUEST_TIMEOUT`` is answered
408 problem+json and its connection closed (``server.deadlines``); the server goes on answering
everyone else. The test server's limit is 1 s so that the test takes a few seconds; the default
is 15 s.
"""

from __future__ import annotations

import json
import socket
from collections.abc import Iterator

import pytest

from server.deadlines import timeout_answer
from server.settings import Settings, from_environment
from tests.server.test_errors import FOUR_BAR
from tests.server.test_serving import request, server

# timed against servers of its own under load: run alone, after the others (tests/run.sh)
pytestmark = pytest.mark.serial

LIMIT = "1"


@pytest.fixture(scope="module")
def impatient() -> Iterator[str]:
    with server("slow-clients", KINEMATICS_WORKERS="1", KINEMATICS_REQUEST_TIMEOUT=LIMIT) as base:
        yield base


def connect(base: str) -> socket.socket:
    host, port = base.removeprefix("http://").split(":")
    sock = socket.create_connection((host, int(port)), timeout=30)
    return sock


def read_to_close(sock: socket.socket) -> bytes:
    """Everything the server sends until it closes the connection (30 s at most)."""
    chunks = []
    while chunk := sock.recv(65536):
        chunks.append(chunk)
    return b"".join(chunks)


def post_head(length: int) -> bytes:
    return (
        f"POST /api/v1/analyze HTTP/1.1\r\nhost: x\r\ncontent-type: application/json\r\n"
        f"content-length: {length}\r\n\r\n"
    ).encode()


def test_the_request_timeout_is_a_setting() -> None:
    assert Settings().request_timeout == 15.0
    assert from_environment({"KINEMATICS_REQUEST_TIMEOUT": "20"}).request_timeout == 20.0
    with pytest.raises(ValueError, match="KINEMATICS_REQUEST_TIMEOUT"):
        from_environment({"KINEMATICS_REQUEST_TIMEOUT": "0"})


def test_half_sent_headers_bodies_and_silence_are_answered_408_and_closed(impatient: str) -> None:
    """Twenty connections: silent, half a request line, half the headers, the headers and half
    the body (four of each, plus a kept-alive connection whose second request stops halfway);
    every one is answered 408 and closed, while a whole request on another connection is
    answered 200."""
    body = json.dumps({"scene": FOUR_BAR}).encode()
    partial = [
        b"",
        b"POST /api/v1/ana",
        post_head(len(body))[:40],
        post_head(len(body)) + body[:50],
    ]
    sockets = []
    for sent in partial * 4:
        sock = connect(impatient)
        sock.sendall(sent)
        sockets.append(sock)
    kept = connect(impatient)  # a whole request first, then half of a second one
    kept.sendall(post_head(len(body)) + body)
    first = b""
    while b"\r\n\r\n" not in first or not first.rstrip().endswith(b"}"):
        first += kept.recv(65536)
    assert first.startswith(b"HTTP/1.1 200")
    kept.sendall(post_head(len(body)) + body[:10])
    sockets.append(kept)
    assert request(impatient, "/api/v1/analyze", {"scene": FOUR_BAR})[0] == 200
    for sock in sockets:
        answer = read_to_close(sock)
        sock.close()
        assert answer.startswith(b"HTTP/1.1 408 "), answer[:200]
        head, _, problem = answer.partition(b"\r\n\r\n")
        assert b"content-type: application/problem+json" in head
        assert b"connection: close" in head
        detail = json.loads(problem)
        assert detail["code"] == "request_timeout" and detail["status"] == 408
        assert detail["detail"] == f"the request did not arrive within {LIMIT} s"
    assert timeout_answer(1.0).endswith(problem)
    assert request(impatient, "/health")[0] == 200  # the server answers on

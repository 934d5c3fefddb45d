"""Slow clients cut off: a request's headers and body must arrive within a stated time.

uvicorn waits for a request's bytes as long as its client likes: a connection that sends half
its headers, or half its body, or a byte every few seconds, holds a socket and a place in the
server for ever (the issue measured 100 such connections open past 41 s). ``DeadlineProtocol``
is uvicorn's h11 protocol with one timer more: from a connection's opening, and from the first
byte of each further request on a kept-alive connection, the whole request (headers and body)
must arrive within ``KINEMATICS_REQUEST_TIMEOUT`` seconds (``server.settings``, default 15).
Past it the server answers **408** problem+json with ``Connection: close`` (when it has not
begun an answer) and closes the connection; the endpoint, if it was waiting for the body, sees
the client leave. The time the server takes to answer is not counted (the time limits of
``server.workers`` bound it), nor the idle time between two requests, which uvicorn's keep-alive
timeout bounds (``--timeout-keep-alive``, 5 s by default).

Run uvicorn with ``--http server.deadlines:DeadlineProtocol`` (the Dockerfile and
``server.local`` do).
"""

from __future__ import annotations

import asyncio
import functools
from typing import Any

import h11
import orjson
from uvicorn.protocols.http.h11_impl import H11Protocol

from server.problems import PROBLEM, TITLES
from server.settings import from_environment

# The states of the client's side while its request is still arriving.
ARRIVING = (h11.IDLE, h11.SEND_BODY)


@functools.cache
def request_timeout() -> float:
    """Seconds within which a request must arrive (read once from the environment)."""
    return from_environment().request_timeout


def timeout_answer(seconds: float) -> bytes:
    """The 408 answer, as the bytes written to the connection before it is closed."""
    body = orjson.dumps(
        {
            "type": "/problems/request_timeout",
            "title": TITLES["request_timeout"],
            "status": 408,
            "detail": f"the request did not arrive within {seconds:g} s",
            "code": "request_timeout",
        }
    )
    head = (
        "HTTP/1.1 408 Request Timeout\r\n"
        f"content-type: {PROBLEM}\r\n"
        f"content-length: {len(body)}\r\n"
        "connection: close\r\n\r\n"
    )
    return head.encode() + body


class DeadlineProtocol(H11Protocol):
    """uvicorn's h11 protocol, with a deadline on the arrival of each request."""

    def __init__(self, *args: Any, **kwargs: Any) -> None:
        super().__init__(*args, **kwargs)
        self.deadline: asyncio.TimerHandle | None = None

    def connection_made(self, transport: asyncio.Transport) -> None:  # type: ignore[override]
        super().connection_made(transport)
        self._arm()

    def connection_lost(self, exc: Exception | None) -> None:
        self._disarm()
        super().connection_lost(exc)

    def data_received(self, data: bytes) -> None:
        if self.deadline is None and self.conn.their_state in ARRIVING:
            self._arm()  # the first bytes of a further request on a kept-alive connection
        super().data_received(data)
        if self.conn.their_state not in ARRIVING:
            self._disarm()  # the whole request is in

    def on_response_complete(self) -> None:
        self._disarm()  # between requests uvicorn's keep-alive timeout runs
        super().on_response_complete()

    def _arm(self) -> None:
        self._disarm()
        self.deadline = self.loop.call_later(request_timeout(), self._expire)

    def _disarm(self) -> None:
        if self.deadline is not None:
            self.deadline.cancel()
            self.deadline = None

    def _expire(self) -> None:
        self.deadline = None
        if self.transport.is_closing():
            return
        cycle = self.cycle
        if cycle is None or cycle.response_complete or not cycle.response_started:
            self.transport.write(timeout_answer(request_timeout()))
        self.transport.close()

"""``Server-Timing`` on every response, when ``KINEMATICS_SERVER_TIMING=1`` (load tests).

``app;dur=`` is the time from the moment the app received the request (uvicorn has parsed its
head) to the moment it started the response, in milliseconds; requests run in the worker pool add
``queue`` (waiting for a worker), ``worker`` (the round trip to it) and ``solve`` (the worker's
own time on it: the rest of ``worker`` is pickling, the pipe and a thread's hand-over) from
``server.workers``. A
client's latency minus ``app`` is what the server's front (reading sockets, parsing HTTP, an event
loop waiting for a core) and the client itself added: ``benchmarks/load.py`` reports both.
"""

from __future__ import annotations

import time

from starlette.types import ASGIApp, Receive, Scope, Send

from server.headers import Headers, edit_headers


class ServerTiming:
    """ASGI middleware: ``server-timing: app;dur=<ms>`` (joined to the pool's entries)."""

    def __init__(self, app: ASGIApp) -> None:
        self.app = app

    async def __call__(self, scope: Scope, receive: Receive, send: Send) -> None:
        arrived = time.perf_counter()

        def timed(headers: Headers) -> Headers:
            entry = f"app;dur={(time.perf_counter() - arrived) * 1e3:.2f}"
            kept = []
            for name, value in headers:
                if name.lower() == b"server-timing":
                    entry = f"{entry}, {value.decode()}"
                else:
                    kept.append((name, value))
            return [*kept, (b"server-timing", entry.encode())]

        await edit_headers(self.app, scope, receive, send, timed)

"""The load test's generator (benchmarks/load.py) against a scripted HTTP server in process:
it reads each answer whole on one keep-alive connection, takes the app's time from
Server-Timing, and counts a connection the server drops (then opens a new one)."""

from __future__ import annotations

import asyncio

from benchmarks.load import Connection, Tally
from tests import run_apart

ANSWER = (
    b"HTTP/1.1 200 OK\r\ncontent-length: 5\r\n"
    b"server-timing: app;dur=12.5, queue;dur=1.00\r\n\r\nhello"
)


async def scripted(answers: list[bytes]) -> tuple[Tally, list[int]]:
    """Four requests through one Connection to a server that answers from ``answers`` in turn
    (an empty answer: it drops the connection instead); the tally and the connections seen."""
    connections: list[int] = []
    script = iter(answers)

    async def serve(reader: asyncio.StreamReader, writer: asyncio.StreamWriter) -> None:
        connections.append(len(connections))
        while True:
            try:
                head = await reader.readuntil(b"\r\n\r\n")
            except asyncio.IncompleteReadError:
                break
            length = next(
                int(line.split(b":")[1])
                for line in head.split(b"\r\n")
                if line.lower().startswith(b"content-length")
            )
            await reader.readexactly(length)
            answer = next(script)
            if not answer:
                break
            writer.write(answer)
        writer.close()

    server = await asyncio.start_server(serve, "127.0.0.1", 0)
    port = server.sockets[0].getsockname()[1]
    connection, tally = Connection(f"http://127.0.0.1:{port}"), Tally()
    for _ in range(4):
        await connection.request(("POST", "/api/v1/analyze", {"scene": {}}), tally)
    connection.close()
    server.close()
    await server.wait_closed()
    return tally, connections


def test_answers_are_read_whole_on_one_connection_with_the_apps_time() -> None:
    tally, connections = run_apart(scripted([ANSWER] * 4))
    assert tally.statuses == {200: 4} and tally.dropped == 0
    assert tally.app == [0.0125] * 4  # seconds
    assert len(tally.latencies) == 4 and connections == [0]  # one keep-alive connection


def test_a_dropped_connection_is_counted_and_opened_again() -> None:
    busy = b"HTTP/1.1 503 Service Unavailable\r\ncontent-length: 0\r\n\r\n"
    tally, connections = run_apart(scripted([ANSWER, b"", busy, ANSWER]))
    assert tally.dropped == 1 and tally.statuses == {200: 2, 503: 1}
    assert tally.errors == 2 and tally.app == [0.0125, 0.0125]
    assert connections == [0, 1]

"""Load and burst test of the real server on loopback (issue 15): prints the issue's table.

Starts the app as the README does (one uvicorn process; the solver in its worker pool, sized to
the cores) through ``server.local.serve_locally``, then for each row keeps N clients sending the
same request for ``--duration`` seconds (each client sends its next request when the last one is
answered) and reports requests/s, p50, p99 and errors (answers other than 200, and connections
dropped or timed out): /analyze and /sweep (360 samples) at 20 and 100 clients, /solution, one
exercise with its worked solution, and one dynamics instant (forces and energy of the seed-004
four-bar) at 20 clients.

The burst sends 50 of the most expensive legal requests at once, each from its own loopback
address (one address may hold only its share of the slow lane), (sweeps of eight triads on one
crank, one Newton-Raphson group of 32 links, at the most samples the work budget allows: about
5 s of estimated work each) while cheap clients keep asking /health and /analyze; it reports
their p50 / p99 during the burst and how the burst was answered (200, stopped at the time limit
413, or 503 once a request waited ``KINEMATICS_QUEUE_WAIT``). The burst runs twice on each of
two servers, alternating: the workers at the server's own CPU priority (the default,
``KINEMATICS_WORKER_NICE=0``) and 10 nice levels below it (the Dockerfile's setting, so the event
loop gets a core first). The whole table runs again with ``KINEMATICS_WORKERS=0`` (no pool)
as a baseline.

The load generator runs on the same 2 cores as the server, so it must cost far less than the
server and must never starve a connection: two processes of asyncio clients, each client one
keep-alive HTTP/1.1 connection written and read as raw bytes. (The previous generator, httpx's
AsyncClient in one process, spent most of a core at 100 clients and read its connections
unevenly: its p99 was seconds while the server's own was a few hundred milliseconds; a section
of the table compares the two on the same server, alternating.) The servers run with
``KINEMATICS_SERVER_TIMING=1``, so each row also shows the server's own time per request (from
Server-Timing) and the CPU the front process (uvicorn, not the workers) used.

Loopback only, bounded in count and time: about 5 minutes with the defaults (7 rows x 10 s,
twice, four generator rows, four bursts of about 12 s, three server starts). Run from the
repository root::

    python -m benchmarks.load                  # the table, written into docs/BENCHMARKS.md
    python -m benchmarks.load --duration 60    # the issue's 60 s per row (about 20 minutes)
    python -m benchmarks.load --no-write       # print only
"""

from __future__ import annotations

import argparse
import asyncio
import json
import os
import resource
import sys
import time
from concurrent.futures import ProcessPoolExecutor
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

from benchmarks.sections import write_section  # noqa: E402
from server.local import serve_locally  # noqa: E402
from tests.dynamics_cases import seed004_scene  # noqa: E402
from tests.server.test_serving import NEWTON_RUNAWAY  # noqa: E402

DOC = ROOT / "docs" / "BENCHMARKS.md"
FOUR_BAR = json.loads((ROOT / "server" / "examples" / "S000-T1.json").read_text())
ANALYZE = ("POST", "/api/v1/analyze", {"scene": FOUR_BAR})
SWEEP = ("POST", "/api/v1/sweep", {"scene": FOUR_BAR, "samples": 360})
SOLUTION = ("POST", "/api/v1/solution", {"scene": FOUR_BAR})
EXERCISE = (
    "POST",
    "/api/v1/exercises",
    {"type": "four_bar_acceleration", "count": 1, "with_solutions": True},
)
DYNAMICS = (
    "POST",
    "/api/v1/analyze",
    {"scene": seed004_scene(), "quantities": ["forces", "energy"]},
)
HEALTH = ("GET", "/health", None)
EXPENSIVE = ("POST", "/api/v1/sweep", NEWTON_RUNAWAY)
Request = tuple[str, str, Any]
GENERATORS = 2  # load generator processes (one per core): none of them saturates


@dataclass
class Tally:
    latencies: list[float] = field(default_factory=list)  # s, as the client saw them
    app: list[float] = field(default_factory=list)  # s in the app (Server-Timing), when sent
    statuses: dict[int, int] = field(default_factory=dict)
    dropped: int = 0

    def add(self, status: int | None, seconds: float, app: float | None = None) -> None:
        if status is None:
            self.dropped += 1
            return
        self.latencies.append(seconds)
        if app is not None:
            self.app.append(app)
        self.statuses[status] = self.statuses.get(status, 0) + 1

    def quantile(self, q: float, of: list[float] | None = None) -> float:
        values = self.latencies if of is None else of
        if not values:
            return float("nan")
        ordered = sorted(values)
        return ordered[min(len(ordered) - 1, int(q * len(ordered)))]

    @property
    def errors(self) -> int:
        return sum(n for s, n in self.statuses.items() if s != 200) + self.dropped


class Connection:
    """One keep-alive HTTP/1.1 connection, requests written and answers read as raw bytes.

    The generator must cost the machine far less than the server, and must read every
    connection as soon as its answer arrives: httpx's pool spent most of a core at 100 clients
    and served its connections unevenly (see docs/SERVING.md, "The load generator"). A dropped
    connection is counted and opened again for the next request.
    """

    def __init__(self, base: str, address: str | None = None) -> None:
        host, _, port = base.removeprefix("http://").partition(":")
        self.host, self.port = host, int(port)
        self.address = address  # the client's own loopback address (127.0.0.x), if given
        self.streams: tuple[asyncio.StreamReader, asyncio.StreamWriter] | None = None

    async def request(self, request: Request, tally: Tally) -> None:
        method, path, body = request
        payload = b"" if body is None else json.dumps(body).encode()
        head = f"{method} {path} HTTP/1.1\r\nhost: {self.host}\r\n"
        if body is not None:
            head += f"content-type: application/json\r\ncontent-length: {len(payload)}\r\n"
        start = time.perf_counter()
        try:
            if self.streams is None:
                local = None if self.address is None else (self.address, 0)
                self.streams = await asyncio.open_connection(self.host, self.port, local_addr=local)
            reader, writer = self.streams
            writer.write(head.encode() + b"\r\n" + payload)
            lines = (await reader.readuntil(b"\r\n\r\n")).decode("latin-1").split("\r\n")
            headers = dict(line.lower().split(": ", 1) for line in lines[1:] if ": " in line)
            await reader.readexactly(int(headers["content-length"]))
        except (OSError, asyncio.IncompleteReadError, KeyError, ValueError):
            self.close()
            tally.add(None, time.perf_counter() - start)
            return
        tally.add(int(lines[0].split()[1]), time.perf_counter() - start, _app_seconds(headers))

    def close(self) -> None:
        if self.streams is not None:
            self.streams[1].close()
            self.streams = None


def _app_seconds(headers: dict[str, str]) -> float | None:
    """The ``app;dur=`` of a Server-Timing header (server.timing), in seconds."""
    for entry in headers.get("server-timing", "").split(","):
        name, _, duration = entry.strip().partition(";dur=")
        if name == "app":
            return float(duration) / 1e3
    return None


async def keep_sending(base: str, request: Request, tally: Tally, until: float) -> None:
    connection = Connection(base)
    while time.perf_counter() < until:
        await connection.request(request, tally)
    connection.close()


def _generate(base: str, request: Request, clients: int, start: float, duration: float) -> Tally:
    """In a generator process: ``clients`` closed-loop clients from wall-clock ``start``."""

    async def run() -> Tally:
        await asyncio.sleep(max(0.0, start - time.time()))
        tally, until = Tally(), time.perf_counter() + duration
        await asyncio.gather(*(keep_sending(base, request, tally, until) for _ in range(clients)))
        return tally

    return asyncio.run(run())


def load(
    base: str, request: Request, clients: int, duration: float, processes: int = GENERATORS
) -> tuple[Tally, float]:
    """``clients`` closed-loop clients spread over ``processes`` generator processes."""
    start = time.time() + 1.0  # every process connects at the same moment
    shares = [clients // processes + (k < clients % processes) for k in range(processes)]
    with ProcessPoolExecutor(processes) as pool:
        futures = [
            pool.submit(_generate, base, request, share, start, duration) for share in shares
        ]
        return merge([future.result() for future in futures]), duration


async def load_with_httpx(base: str, request: Request, clients: int, duration: float) -> Tally:
    """The previous generator, for comparison: httpx's AsyncClient in this one process."""
    import httpx

    method, path, body = request
    tally = Tally()
    limits = httpx.Limits(max_connections=clients + 10, max_keepalive_connections=clients + 10)
    async with httpx.AsyncClient(
        base_url=base, limits=limits, timeout=60.0, trust_env=False
    ) as client:
        until = time.perf_counter() + duration

        async def one() -> None:
            while time.perf_counter() < until:
                start = time.perf_counter()
                try:
                    response = await client.request(method, path, json=body)
                except httpx.HTTPError:
                    tally.add(None, time.perf_counter() - start)
                    continue
                seconds = time.perf_counter() - start
                tally.add(response.status_code, seconds, _app_seconds(dict(response.headers)))

        await asyncio.gather(*(one() for _ in range(clients)))
    return tally


async def burst(base: str, count: int) -> tuple[Tally, Tally, Tally, float]:
    """``count`` expensive requests at once; cheap ones (/health, /analyze) until they are done."""
    expensive, health, analyze = Tally(), Tally(), Tally()
    start = time.perf_counter()

    async def heavy(number: int) -> None:
        # Each from its own address: one client may hold only its share of the slow lane (429).
        connection = Connection(base, f"127.0.{1 + number // 250}.{1 + number % 250}")
        await connection.request(EXPENSIVE, expensive)
        connection.close()

    everything = asyncio.gather(*(heavy(n) for n in range(count)))
    stop = asyncio.get_running_loop().create_future()

    async def cheap(request: Request, tally: Tally) -> None:
        connection = Connection(base)
        while not stop.done():
            await connection.request(request, tally)
            await asyncio.sleep(0.05)
        connection.close()

    light = asyncio.gather(
        *(cheap(HEALTH, health) for _ in range(2)), *(cheap(ANALYZE, analyze) for _ in range(3))
    )
    await everything
    stop.set_result(None)
    await light
    return expensive, health, analyze, time.perf_counter() - start


def ms(seconds: float) -> str:
    return f"{seconds * 1000:.0f} ms" if seconds < 1 else f"{seconds:.2f} s"


def front_cpu_seconds(base: str) -> float:
    """CPU seconds used so far by the uvicorn process serving ``base`` (not its workers)."""
    port = base.rsplit(":", 1)[1].encode()
    for entry in Path("/proc").iterdir():
        try:
            argv = (entry / "cmdline").read_bytes().split(b"\0")
            if any(b"uvicorn" in arg for arg in argv) and port in argv:
                fields = (entry / "stat").read_text().rsplit(")", 1)[1].split()
                return (int(fields[11]) + int(fields[12])) / os.sysconf("SC_CLK_TCK")
        except (OSError, ValueError):  # gone, or not ours to read
            continue
    return float("nan")


def generator_cpu_seconds() -> float:
    """CPU seconds of this process and of its finished generator processes."""
    own, children = (
        resource.getrusage(who) for who in (resource.RUSAGE_SELF, resource.RUSAGE_CHILDREN)
    )
    return own.ru_utime + own.ru_stime + children.ru_utime + children.ru_stime


def row(name: str, tally: Tally, elapsed: float, front: float) -> str:
    rate = sum(tally.statuses.values()) / elapsed
    errors = f"{tally.errors}" + (f" ({tally.dropped} dropped)" if tally.dropped else "")
    p50, p99 = ms(tally.quantile(0.5)), ms(tally.quantile(0.99))
    app50, app99 = ms(tally.quantile(0.5, tally.app)), ms(tally.quantile(0.99, tally.app))
    return (
        f"| {name} | {rate:.0f} | {p50} | {p99} | {app50} | {app99} | "
        f"{front / elapsed:.0%} | {errors} |"
    )


HEAD = [
    "| requests/s | p50 | p99 | p50 in the app | p99 in the app | front process CPU | errors |",
    "|---|---|---|---|---|---|---|",
]
ROWS = [
    ("/analyze, 20 clients", ANALYZE, 20),
    ("/analyze, 100 clients", ANALYZE, 100),
    ("/sweep 360 samples, 20 clients", SWEEP, 20),
    ("/sweep 360 samples, 100 clients", SWEEP, 100),
    ("/solution, 20 clients", SOLUTION, 20),
    ("/exercises (one, with its solution), 20 clients", EXERCISE, 20),
    ("dynamics: /analyze with forces and energy, 20 clients", DYNAMICS, 20),
]


def table(base: str, duration: float) -> list[str]:
    lines = [f"| load ({duration:g} s each) " + HEAD[0], "|---" + HEAD[1]]
    for name, request, clients in ROWS:
        cpu = front_cpu_seconds(base)
        tally, elapsed = load(base, request, clients, duration)
        lines.append(row(name, tally, elapsed, front_cpu_seconds(base) - cpu))
        print(lines[-1], flush=True)
    return lines


def generators(base: str, duration: float, rounds: int = 2) -> list[str]:
    """/analyze at 100 clients from this generator and from the previous one, alternating."""
    lines = ["| generator, /analyze at 100 clients " + HEAD[0], "|---" + HEAD[1]]
    for round_ in range(1, rounds + 1):
        for name in (f"{GENERATORS} processes, raw HTTP/1.1", "httpx, one process (before)"):
            cpu, mine = front_cpu_seconds(base), generator_cpu_seconds()
            if name.startswith("httpx"):
                tally = asyncio.run(load_with_httpx(base, ANALYZE, 100, duration))
            else:
                tally, _ = load(base, ANALYZE, 100, duration)
            front = front_cpu_seconds(base) - cpu
            spent = (generator_cpu_seconds() - mine) / duration
            lines.append(row(f"{name}, round {round_}: CPU {spent:.0%}", tally, duration, front))
            print(lines[-1], flush=True)
    return lines


def merge(tallies: list[Tally]) -> Tally:
    merged = Tally()
    for tally in tallies:
        merged.latencies += tally.latencies
        merged.app += tally.app
        merged.dropped += tally.dropped
        for status, count in tally.statuses.items():
            merged.statuses[status] = merged.statuses.get(status, 0) + count
    return merged


async def bursts(servers: dict[str, str], rounds: int) -> list[str]:
    """``rounds`` bursts on each server, alternating (so both see the same machine load)."""
    runs: dict[str, list[tuple[Tally, Tally, Tally, float]]] = {name: [] for name in servers}
    for _ in range(rounds):
        for name, base in servers.items():
            runs[name].append(await burst(base, 50))
    lines = []
    for name, results in runs.items():
        expensive, health, analyze = (merge([r[i] for r in results]) for i in range(3))
        outcome = ", ".join(f"{n} x {s}" for s, n in sorted(expensive.statuses.items()))
        outcome += f", {expensive.dropped} dropped" if expensive.dropped else ""
        took = " and ".join(f"{r[3]:.1f} s" for r in results)
        lines += [
            f"| {name}: /health | {len(health.latencies)} | {ms(health.quantile(0.5))} | "
            f"{ms(health.quantile(0.99))} | {health.errors} | {took}: {outcome} |",
            f"| {name}: /analyze | {len(analyze.latencies)} | {ms(analyze.quantile(0.5))} | "
            f"{ms(analyze.quantile(0.99))} | {analyze.errors} | |",
        ]
    print("\n".join(lines), flush=True)
    return lines


GENERATOR_HEAD = [
    "",
    "The same server, /analyze at 100 clients, from this load generator and from the one used "
    "before (httpx's AsyncClient in one process), alternating; CPU is the generator's own (100% "
    "is one core):",
    "",
]
BURST_HEAD = [
    "",
    "Burst: 50 sweeps of eight triads (32 links by Newton-Raphson, 1,512 samples: the most the "
    "work budget allowed before its refit of 2026-11-29) sent at once, while 2 clients asked "
    "/health and 3 asked /analyze every "
    "50 ms. Two bursts each, alternating, on two servers: the workers at the server's CPU "
    "priority (the default, `KINEMATICS_WORKER_NICE=0`) and 10 levels below it (the "
    "Dockerfile's `KINEMATICS_WORKER_NICE=10`):",
    "",
    "| during the burst | requests | p50 | p99 | errors | the burst: answered in, statuses |",
    "|---|---|---|---|---|---|",
]


def write_doc(report: str) -> None:
    """Replace what stands between the load markers (a section appended if missing)."""
    write_section(DOC, "load", "Serving under load", report)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--duration", type=float, default=10.0, help="seconds per row (<= 120)")
    parser.add_argument("--no-write", action="store_true", help="leave docs/BENCHMARKS.md alone")
    args = parser.parse_args()
    duration = min(max(args.duration, 1.0), 120.0)
    before = os.getloadavg()[0]
    timed = {"KINEMATICS_SERVER_TIMING": "1"}
    with (
        serve_locally(settings=timed) as base,
        serve_locally(settings={**timed, "KINEMATICS_WORKER_NICE": "10"}) as low,
    ):
        lines = table(base, duration)
        compared = generators(base, duration)
        servers = {"workers at nice 0 (default)": base, "workers at nice 10 (Docker)": low}
        burst_lines = asyncio.run(bursts(servers, 2))
    body = "\n".join(lines + GENERATOR_HEAD + compared + BURST_HEAD + burst_lines)
    print("baseline: KINEMATICS_WORKERS=0", flush=True)
    with serve_locally(settings={**timed, "KINEMATICS_WORKERS": "0"}) as base:
        baseline = "\n".join(table(base, duration))
    after = os.getloadavg()[0]
    report = (
        f"Measured {time.strftime('%Y-%m-%d %H:%M UTC', time.gmtime())} by "
        f"`python -m benchmarks.load --duration {duration:g}` against one uvicorn process on "
        f"loopback with the default settings ({os.cpu_count()} cores, so 2 worker processes) and "
        f"`KINEMATICS_SERVER_TIMING=1`; the load generator ({GENERATORS} processes, raw "
        'keep-alive HTTP/1.1, one connection per client) ran on the same cores. "In the app" is '
        "the server's own time from Server-Timing (from the app receiving the request to its "
        'answer); "front process CPU" is the uvicorn process\'s CPU time over the row (100% is '
        f"one core; the workers not included). Load average (1 min) before {before:.2f}, after "
        f"{after:.2f} (other processes competed when above 0).\n\n{body}\n\n"
        "Baseline in the same run: the same server with `KINEMATICS_WORKERS=0`, the solver on "
        "the server's own threads as before issue 15 (no pool, no time limits; the burst is "
        f"not repeated: it stalled /health for minutes in the issue's measurement).\n\n{baseline}"
    )
    print(report)
    if not args.no_write:
        write_doc(report)


if __name__ == "__main__":
    main()

"""Load and burst test of the real server on loopback (issue 15): prints the issue's table.

Starts the app as the README does (one uvicorn process; the solver in its worker pool, sized to
the cores) through ``server.local.serve_locally``, then for each row keeps N clients sending the
same request for ``--duration`` seconds (each client sends its next request when the last one is
answered) and reports requests/s, p50, p99 and errors (answers other than 200, and connections
dropped or timed out): /analyze and /sweep (360 samples) at 20 and 100 clients, /solution, one
exercise with its worked solution, and one dynamics instant (forces and energy of the seed-004
four-bar) at 20 clients.

The burst sends 50 of the most expensive legal requests at once (sweeps of eight triads on one
crank, one Newton-Raphson group of 32 links, at the most samples the work budget allows: about
5 s of estimated work each) while cheap clients keep asking /health and /analyze; it reports
their p50 / p99 during the burst and how the burst was answered (200, stopped at the time limit
413, or 503 once a request waited ``KINEMATICS_QUEUE_WAIT``). The burst runs twice on each of
two servers, alternating: the workers at the server's own CPU priority (the default,
``KINEMATICS_WORKER_NICE=0``) and 10 nice levels below it (the Dockerfile's setting, so the event
loop gets a core first). The whole table runs again with ``KINEMATICS_WORKERS=0`` (no pool)
as a baseline.

Loopback only, bounded in count and time: about 4 minutes with the defaults (7 rows x 10 s,
twice, four bursts of about 12 s, three server starts). Run from the repository root::

    python -m benchmarks.load                  # the table, written into docs/BENCHMARKS.md
    python -m benchmarks.load --duration 60    # the issue's 60 s per row (about 16 minutes)
    python -m benchmarks.load --no-write       # print only

The load generator runs on the same 2 cores as the server, so it competes with it: the figures
are the server's under that handicap, as in the issue's own measurement.
"""

from __future__ import annotations

import argparse
import asyncio
import json
import os
import sys
import time
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import httpx

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


@dataclass
class Tally:
    latencies: list[float] = field(default_factory=list)
    statuses: dict[int, int] = field(default_factory=dict)
    dropped: int = 0

    def add(self, status: int | None, seconds: float) -> None:
        if status is None:
            self.dropped += 1
            return
        self.latencies.append(seconds)
        self.statuses[status] = self.statuses.get(status, 0) + 1

    def quantile(self, q: float) -> float:
        if not self.latencies:
            return float("nan")
        ordered = sorted(self.latencies)
        return ordered[min(len(ordered) - 1, int(q * len(ordered)))]

    @property
    def errors(self) -> int:
        return sum(n for s, n in self.statuses.items() if s != 200) + self.dropped


async def send(client: httpx.AsyncClient, request: Request, tally: Tally) -> None:
    method, path, body = request
    start = time.perf_counter()
    try:
        response = await client.request(method, path, json=body)
        await response.aread()
        tally.add(response.status_code, time.perf_counter() - start)
    except httpx.HTTPError:
        tally.add(None, time.perf_counter() - start)


async def keep_sending(
    client: httpx.AsyncClient, request: Request, tally: Tally, until: float
) -> None:
    while time.perf_counter() < until:
        await send(client, request, tally)


def _client(base: str, clients: int) -> httpx.AsyncClient:
    limits = httpx.Limits(max_connections=clients + 10, max_keepalive_connections=clients + 10)
    return httpx.AsyncClient(base_url=base, limits=limits, timeout=60.0, trust_env=False)


async def load(base: str, request: Request, clients: int, duration: float) -> tuple[Tally, float]:
    tally = Tally()
    async with _client(base, clients) as client:
        start = time.perf_counter()
        until = start + duration
        await asyncio.gather(*(keep_sending(client, request, tally, until) for _ in range(clients)))
        return tally, time.perf_counter() - start


async def burst(base: str, count: int) -> tuple[Tally, Tally, Tally, float]:
    """``count`` expensive requests at once; cheap ones (/health, /analyze) until they are done."""
    expensive, health, analyze = Tally(), Tally(), Tally()
    async with _client(base, count + 10) as client:
        start = time.perf_counter()
        heavy = asyncio.gather(*(send(client, EXPENSIVE, expensive) for _ in range(count)))
        stop = asyncio.get_running_loop().create_future()

        async def cheap(request: Request, tally: Tally) -> None:
            while not stop.done():
                await send(client, request, tally)
                await asyncio.sleep(0.05)

        light = asyncio.gather(
            *(cheap(HEALTH, health) for _ in range(2)), *(cheap(ANALYZE, analyze) for _ in range(3))
        )
        await heavy
        stop.set_result(None)
        await light
        return expensive, health, analyze, time.perf_counter() - start


def ms(seconds: float) -> str:
    return f"{seconds * 1000:.0f} ms" if seconds < 1 else f"{seconds:.2f} s"


def row(name: str, tally: Tally, elapsed: float) -> str:
    rate = sum(tally.statuses.values()) / elapsed
    errors = f"{tally.errors}" + (f" ({tally.dropped} dropped)" if tally.dropped else "")
    p50, p99 = ms(tally.quantile(0.5)), ms(tally.quantile(0.99))
    return f"| {name} | {rate:.0f} | {p50} | {p99} | {errors} |"


ROWS = [
    ("/analyze, 20 clients", ANALYZE, 20),
    ("/analyze, 100 clients", ANALYZE, 100),
    ("/sweep 360 samples, 20 clients", SWEEP, 20),
    ("/sweep 360 samples, 100 clients", SWEEP, 100),
    ("/solution, 20 clients", SOLUTION, 20),
    ("/exercises (one, with its solution), 20 clients", EXERCISE, 20),
    ("dynamics: /analyze with forces and energy, 20 clients", DYNAMICS, 20),
]


async def table(base: str, duration: float) -> list[str]:
    lines = [
        f"| load ({duration:g} s each) | requests/s | p50 | p99 | errors |",
        "|---|---|---|---|---|",
    ]
    for name, request, clients in ROWS:
        tally, elapsed = await load(base, request, clients, duration)
        lines.append(row(name, tally, elapsed))
        print(lines[-1], flush=True)
    return lines


def merge(tallies: list[Tally]) -> Tally:
    merged = Tally()
    for tally in tallies:
        merged.latencies += tally.latencies
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


BURST_HEAD = [
    "",
    "Burst: 50 sweeps of eight triads (32 links by Newton-Raphson, 1,512 samples: the most the "
    "work budget allows) sent at once, while 2 clients asked /health and 3 asked /analyze every "
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
    with serve_locally() as base, serve_locally(settings={"KINEMATICS_WORKER_NICE": "10"}) as low:
        lines = asyncio.run(table(base, duration))
        servers = {"workers at nice 0 (default)": base, "workers at nice 10 (Docker)": low}
        burst_lines = asyncio.run(bursts(servers, 2))
    body = "\n".join(lines + BURST_HEAD + burst_lines)
    print("baseline: KINEMATICS_WORKERS=0", flush=True)
    with serve_locally(settings={"KINEMATICS_WORKERS": "0"}) as base:
        baseline = "\n".join(asyncio.run(table(base, duration)))
    after = os.getloadavg()[0]
    report = (
        f"Measured {time.strftime('%Y-%m-%d %H:%M UTC', time.gmtime())} by "
        f"`python -m benchmarks.load --duration {duration:g}` against one uvicorn process on "
        f"loopback with the default settings ({os.cpu_count()} cores, so 2 worker processes); "
        f"the load generator ran on the same cores. Load average (1 min) before {before:.2f}, "
        f"after {after:.2f} (other processes competed when above 0).\n\n{body}\n\n"
        "Baseline in the same run: the same server with `KINEMATICS_WORKERS=0`, the solver on "
        "the server's own threads as before issue 15 (no pool, no time limits; the burst is "
        f"not repeated: it stalled /health for minutes in the issue's measurement).\n\n{baseline}"
    )
    print(report)
    if not args.no_write:
        write_doc(report)


if __name__ == "__main__":
    main()

"""What holds the server's event loop during a burst: every loop callback timed, wall and CPU.

Run from the repository root (about a minute)::

    python -m benchmarks.loop_callbacks            # workers at the default priority
    python -m benchmarks.loop_callbacks --nice 0   # workers at the server's own priority

Starts ``uvicorn server.app:app`` in a subprocess of this script whose asyncio handles are
wrapped to time each callback by the wall clock and by the loop thread's CPU time
(``time.thread_time``), sends the load test's burst (``benchmarks.load.burst``: 50 expensive
sweeps while /health and /analyze keep being asked) twice, and prints /health's latency and the
callbacks that took longest. A callback whose wall time far exceeds its CPU time was not working:
its thread was waiting for a core (or for the GIL); one whose CPU time is large was doing work on
the loop (serialisation, validation, bookkeeping) that belongs elsewhere. docs/SERVING.md ("What
held /health back") quotes a run.
"""

from __future__ import annotations

import argparse
import asyncio
import os
import subprocess
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
if str(ROOT) not in sys.path:
    sys.path.insert(0, str(ROOT))

SLOW = 0.010  # s of wall time: callbacks past it are recorded


def serve(port: int, record: Path) -> None:
    """In the subprocess: uvicorn with every asyncio callback timed into ``record``."""
    import asyncio.events

    import uvicorn

    run = asyncio.events.Handle._run
    out = record.open("w")

    def timed(handle: asyncio.events.Handle) -> None:
        wall, cpu = time.perf_counter(), time.thread_time()
        run(handle)
        wall, cpu = time.perf_counter() - wall, time.thread_time() - cpu
        if wall > SLOW:
            owner = getattr(handle._callback, "__self__", None)  # type: ignore[attr-defined]
            name = (
                owner.get_coro().__qualname__  # type: ignore[union-attr]
                if isinstance(owner, asyncio.Task)
                else getattr(handle._callback, "__qualname__", repr(handle._callback))  # type: ignore[attr-defined]
            )
            out.write(f"{wall * 1e3:.1f}\t{cpu * 1e3:.1f}\t{name}\n")
            out.flush()

    asyncio.events.Handle._run = timed  # type: ignore[method-assign]
    uvicorn.run("server.app:app", host="127.0.0.1", port=port, log_level="warning", loop="asyncio")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--nice", default="10", help="KINEMATICS_WORKER_NICE for the server")
    parser.add_argument("--serve", type=int, help=argparse.SUPPRESS)
    parser.add_argument("--record", type=Path, help=argparse.SUPPRESS)
    args = parser.parse_args()
    if args.serve:
        serve(args.serve, args.record)
        return

    import urllib.request

    from benchmarks.load import burst, ms
    from server.local import _free_port

    port, record = _free_port(), ROOT / "test-artifacts" / "loop-callbacks.tsv"
    record.parent.mkdir(exist_ok=True)
    env = {**os.environ, "KINEMATICS_WORKER_NICE": args.nice}
    command = [sys.executable, "-m", "benchmarks.loop_callbacks", "--serve", str(port)]
    server = subprocess.Popen([*command, "--record", str(record)], cwd=ROOT, env=env)
    base = f"http://127.0.0.1:{port}"
    opener = urllib.request.build_opener(urllib.request.ProxyHandler({}))
    try:
        for _ in range(300):
            try:
                opener.open(f"{base}/health", timeout=1)
                break
            except OSError:
                time.sleep(0.2)
        for round_ in (1, 2):
            _, health, _, elapsed = asyncio.run(burst(base, 50))
            print(
                f"burst {round_} ({elapsed:.1f} s): /health p50 {ms(health.quantile(0.5))}, "
                f"p99 {ms(health.quantile(0.99))} over {len(health.latencies)} requests"
            )
    finally:
        server.terminate()
        server.wait(timeout=30)
    rows = [line.split("\t") for line in record.read_text().splitlines()]
    rows.sort(key=lambda row: -float(row[0]))
    print(
        f"\n{len(rows)} loop callbacks took more than {SLOW * 1e3:g} ms of wall time; the longest:"
    )
    print("| wall | CPU of the loop thread | callback |\n|---|---|---|")
    for wall, cpu, name in rows[:15]:
        print(f"| {wall} ms | {cpu} ms | {name} |")
    busiest = sorted(rows, key=lambda row: -float(row[1]))[:3]
    print("most CPU: " + ", ".join(f"{cpu} ms ({name})" for _, cpu, name in busiest))


if __name__ == "__main__":
    main()

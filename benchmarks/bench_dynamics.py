"""Speed of the inverse dynamics: a sweep with ``forces`` and ``energy`` against the same sweep
without them (target: within 5x), in process and through the HTTP API.

Run from the repository root:

    python -m benchmarks.bench_dynamics            # seed 004 and a six-bar, 3600 samples
    python -m benchmarks.bench_dynamics --repeat 5 # fewer repetitions (noisier)

It prints a markdown table; nothing is written. The baseline (the kinematic sweep to
accelerations, which the dynamics needs anyway) is measured in the same run, interleaved with the
dynamic one, so a busy machine slows both: compare the ratio, not the times. Each run is timed in
CPU time of this process (``time.process_time``: what the work costs, whatever else the machine
runs) and in wall time (which on a loaded machine also counts the time other processes hold the
cores, more so for longer runs); the target is checked on the CPU ratio.
"""

from __future__ import annotations

import argparse
import os
import statistics
import sys
import time
from collections.abc import Callable
from pathlib import Path
from typing import Any

ROOT = Path(__file__).resolve().parent.parent
if str(ROOT) not in sys.path:
    sys.path.insert(0, str(ROOT))

from fastapi.testclient import TestClient  # noqa: E402

import solver  # noqa: E402
from server.app import app  # noqa: E402
from solver.model.scene import parse_linkage  # noqa: E402
from solver.teaching.presets import build_preset  # noqa: E402

KINEMATIC = ["position", "velocity", "acceleration"]
DYNAMIC = [*KINEMATIC, "forces", "energy"]
TARGET = 5.0


def six_bar() -> dict[str, Any]:
    """A Watt six-bar from the four-bar preset: a dyad from the coupler to the ground."""
    doc = build_preset("four_bar", {"mass_per_length": 5.0, "gravity": 9.81, "load": -20.0})
    doc["points"] |= {"X": [0.6, 0.5], "Q": [1.3, 1.0], "Y": [1.9, 0.2]}
    doc["links"]["coupler"]["points"].append("X")
    doc["links"]["ground"]["points"].append("Y")
    doc["links"] |= {"dyad_in": {"points": ["X", "Q"]}, "dyad_out": {"points": ["Q", "Y"]}}
    doc["joints"] += [
        {"type": "revolute", "point": "X", "links": ["coupler", "dyad_in"]},
        {"type": "revolute", "point": "Q", "links": ["dyad_in", "dyad_out"]},
        {"type": "revolute", "point": "Y", "links": ["dyad_out", "ground"]},
    ]
    doc["masses"] |= {
        "dyad_in": {"mass": 3.0, "bar": ["X", "Q"]},
        "dyad_out": {"mass": 3.0, "bar": ["Q", "Y"]},
    }
    return doc


def timed(run: Callable[[], Any]) -> tuple[float, float]:
    """(CPU seconds, wall seconds) of one call."""
    cpu, wall = time.process_time(), time.perf_counter()
    run()
    return time.process_time() - cpu, time.perf_counter() - wall


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--repeat", type=int, default=25)
    parser.add_argument("--samples", type=int, default=3600)
    args = parser.parse_args()
    n, repeat = args.samples, args.repeat
    client = TestClient(app)
    print(f"load average before: {os.getloadavg()[0]:.2f}; {n} samples, medians of {repeat}\n")
    print(
        "| linkage | path | kinematics CPU (ms) | with forces and energy CPU (ms) | CPU ratio "
        "| wall ratio | target |"
    )
    print("|---|---|---|---|---|---|---|")
    for name, doc in (
        ("seed 004 four-bar", build_preset("seed004", {})),
        ("Watt six-bar", six_bar()),
    ):
        scene = parse_linkage(doc)

        def solver_run(quantities: list[str], s: Any = scene) -> Any:
            return solver.sweep(s, n, quantities).as_dict()

        def http_run(quantities: list[str], d: dict[str, Any] = doc) -> Any:
            response = client.post(
                "/api/v1/sweep", json={"scene": d, "samples": n, "quantities": quantities}
            )
            assert response.status_code == 200, response.text
            return response.content

        for path, run in (("solver", solver_run), ("HTTP (in process)", http_run)):
            pairs = [
                (timed(lambda r=run: r(KINEMATIC)), timed(lambda r=run: r(DYNAMIC)))
                for _ in range(repeat)
            ]
            base = statistics.median(k[0] for k, _ in pairs)
            dyn = statistics.median(d[0] for _, d in pairs)
            ratio = statistics.median(d[0] / k[0] for k, d in pairs)
            wall = statistics.median(d[1] / k[1] for k, d in pairs)
            ok = "met" if ratio <= TARGET else "MISSED"
            print(
                f"| {name} | {path} | {base * 1e3:.1f} | {dyn * 1e3:.1f} | {ratio:.2f} | "
                f"{wall:.2f} | <= {TARGET:g}: {ok} |"
            )
    print(f"\nload average after: {os.getloadavg()[0]:.2f}")


if __name__ == "__main__":
    main()

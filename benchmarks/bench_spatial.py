"""Speed of the spatial sweep over time (solver.analysis.spatial_sweep), against a per-sample
baseline.

Run from the repository root:

    python -m benchmarks.bench_spatial            # 241, 3,600 and 36,000 samples
    python -m benchmarks.bench_spatial --quick    # 241 and 3,600 samples

The baseline, measured in the same run: the same moved chain analysed one instant at a time
(``analyze_spatial_chain`` on the chain at each sample, a Python loop), as a solver without
vectorisation would do it. Both give the same answers (checked to 1e-12 before timing). It prints
a markdown table: the median of five repeats (three for the baseline, which runs up to 3,600
samples), with the 1-minute load average (other processes on the machine make every number
slower and noisier).
"""

from __future__ import annotations

import argparse
import json
import os
import statistics
import sys
import time
from collections.abc import Callable
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
if str(ROOT) not in sys.path:
    sys.path.insert(0, str(ROOT))

import numpy as np  # noqa: E402

from solver.analysis.spatial_sweep import move_chain, sweep_spatial_time  # noqa: E402
from solver.kinematics.spatial import (  # noqa: E402
    SpatialChain,
    SpatialJoint,
    SpatialPoint,
    analyze_spatial_chain,
    parse_spatial_chain,
)

ARM = ROOT / "server" / "examples" / "S002-spatial-arm.json"
ALL = ["position", "velocity", "acceleration"]
BASELINE_UP_TO = 3600  # samples


def per_sample(chain: SpatialChain, time: np.ndarray) -> list[np.ndarray]:
    """The baseline: the moved chain analysed at each instant alone; B's acceleration."""
    moved, _ = move_chain(chain, time)
    out = []
    for i in range(time.size):
        joints = tuple(
            SpatialJoint(j.name, j.type, j.origin[i], j.axis[i], float(j.rate[i, 0]), j.rate_dot)
            for j in moved.joints
        )
        points = tuple(SpatialPoint(p.name, p.body, p.position[i]) for p in moved.points)
        out.append(analyze_spatial_chain(SpatialChain(joints, points)).points["B"].acceleration)
    return out


def median_seconds(run: Callable[[], object], repeats: int = 5) -> float:
    times = []
    for _ in range(repeats):
        start = time.perf_counter()
        run()
        times.append(time.perf_counter() - start)
    return statistics.median(times)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true")
    args = parser.parse_args()
    sizes = (241, 3600) if args.quick else (241, 3600, 36000)
    chain = parse_spatial_chain(json.loads(ARM.read_text()))
    load = os.getloadavg()[0]
    print(f"Spatial sweep of the S002 arm (3 joints, 3 points); load average {load:.2f}\n")
    print("| samples | vectorised sweep (ms) | per-sample loop (ms) | ratio |")
    print("|---:|---:|---:|---:|")
    for n in sizes:
        fast = median_seconds(lambda n=n: sweep_spatial_time(chain, 0.0, 2 * np.pi, n, ALL))
        if n > BASELINE_UP_TO:  # the loop would take minutes under load: not run
            print(f"| {n:,} | {fast * 1e3:.2f} | not run | |")
            continue
        time_axis = np.linspace(0.0, 2 * np.pi, n)
        swept = sweep_spatial_time(chain, 0.0, 2 * np.pi, n, ALL)
        baseline = per_sample(chain, time_axis)
        np.testing.assert_allclose(
            swept.analysis.points["B"].acceleration, np.array(baseline), rtol=0, atol=1e-12
        )
        slow = median_seconds(lambda t=time_axis: per_sample(chain, t), 3)
        print(f"| {n:,} | {fast * 1e3:.2f} | {slow * 1e3:.1f} | {slow / fast:.0f}x |")
    print(f"\nload average after: {os.getloadavg()[0]:.2f}")


if __name__ == "__main__":
    main()

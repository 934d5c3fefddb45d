"""Per-request time of the constraint Jacobian's users, two source trees interleaved.

    python -m benchmarks.bench_jacobian OLD_TREE NEW_TREE [--rounds 15]

Each round runs one process per tree (the old first, then the new, alternating which goes
first) that times, median of many calls: the four-bar sweep with every quantity at 360 and
3600 samples, and one /analyze computed in process (parse and analyze a four-bar and a
slider-crank, the condition number included). The report is the median over rounds per tree.
"""

from __future__ import annotations

import argparse
import json
import os
import statistics
import subprocess
import sys
import time

WORKER = r"""
import json
from benchmarks.bench_kinematics import latencies
from solver.analysis.instant import analyze
from solver.analysis.sweeps import sweep
from solver.model.scene import parse_linkage
from solver.teaching.presets import build_preset

four_bar = build_preset("four_bar", {"crank_angle_deg": 30.0})
slider = build_preset("slider_crank", {"crank_angle_deg": 30.0})
scene = parse_linkage(four_bar)
ALL = ["position", "velocity", "acceleration"]

def timed(fn, calls):
    return latencies(fn, calls).p50

print(json.dumps({
    "sweep 360": timed(lambda: sweep(scene, 360, ALL), 200),
    "sweep 3600": timed(lambda: sweep(scene, 3600, ALL), 60),
    "analyze four-bar": timed(lambda: analyze(parse_linkage(four_bar)), 300),
    "analyze slider-crank": timed(lambda: analyze(parse_linkage(slider)), 300),
}))
"""


def run(tree: str) -> dict[str, float]:
    env = {**os.environ, "PYTHONPATH": tree}
    out = subprocess.run(
        [sys.executable, "-c", WORKER], env=env, cwd=tree, check=True, capture_output=True
    )
    return dict(json.loads(out.stdout))


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("old")
    parser.add_argument("new")
    parser.add_argument("--rounds", type=int, default=15)
    args = parser.parse_args()
    times: dict[str, list[dict[str, float]]] = {args.old: [], args.new: []}
    for k in range(args.rounds):
        order = (args.old, args.new) if k % 2 == 0 else (args.new, args.old)
        for tree in order:
            times[tree].append(run(tree))
    print("| workload | old (ms) | new (ms) | new / old |")
    print("|---|---|---|---|")
    for name in times[args.old][0]:
        old = statistics.median(r[name] for r in times[args.old]) * 1e3
        new = statistics.median(r[name] for r in times[args.new]) * 1e3
        print(f"| {name} | {old:.3f} | {new:.3f} | {new / old:.3f} |")


if __name__ == "__main__":
    started = time.perf_counter()
    main()
    print(f"({time.perf_counter() - started:.0f} s)", file=sys.stderr)

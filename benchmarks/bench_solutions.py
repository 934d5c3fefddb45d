"""Worked solutions in-process: this tree against a baseline tree, in the same run.

    git archive <commit> | (mkdir -p /tmp/base && tar -x -C /tmp/base)
    python -m benchmarks.bench_solutions --baseline /tmp/base

Each preset at its defaults, ``solver.solve(doc, method, 4).as_dict()`` (``--method``, vector
by default: parse, analysis, steps, the /solution body), timed in a fresh interpreter per tree
and round, the two trees alternating so that both see the same load. Prints the median over
rounds of each round's p50, wall clock and CPU time of the process (the CPU time is what a quiet
machine would take, less sensitive to the other processes on a loaded one). Issue 12's target:
under 20 ms for the slowest preset on a quiet machine.
"""

from __future__ import annotations

import argparse
import json
import os
import statistics
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]

MEASURE = """
import json, statistics, sys, time
sys.path.insert(0, {tree!r})
import solver
from solver.presets import PRESETS, build_preset
out = {{}}
for name in PRESETS:
    doc = build_preset(name, {{}})
    for _ in range(3):
        solver.solve(doc, {method!r}, 4).as_dict()
    wall, cpu = [], []
    for _ in range({calls}):
        w, c = time.perf_counter(), time.process_time()
        solver.solve(doc, {method!r}, 4).as_dict()
        wall.append(time.perf_counter() - w)
        cpu.append(time.process_time() - c)
    out[name] = [statistics.median(wall), statistics.median(cpu)]
assert solver.__file__.startswith({tree!r}), solver.__file__
print(json.dumps(out))
"""


def measure(tree: Path, calls: int, method: str) -> dict[str, list[float]]:
    code = MEASURE.format(tree=str(tree), calls=calls, method=method)
    done = subprocess.run(
        [sys.executable, "-c", code], cwd=tree, capture_output=True, text=True, check=True
    )
    result: dict[str, list[float]] = json.loads(done.stdout.strip().splitlines()[-1])
    return result


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--baseline", type=Path, required=True, help="an exported older tree")
    parser.add_argument("--calls", type=int, default=15, help="solutions per preset and round")
    parser.add_argument("--rounds", type=int, default=3)
    parser.add_argument("--method", default="vector", help="vector, loop or newton_euler")
    args = parser.parse_args()
    trees = {"baseline": args.baseline.resolve(), "current": ROOT}
    load = os.getloadavg()[0]
    runs: dict[str, list[dict[str, list[float]]]] = {k: [] for k in trees}
    for _ in range(args.rounds):
        for key, tree in trees.items():
            runs[key].append(measure(tree, args.calls, args.method))
    print(
        f"method {args.method}; load average (1 min) before {load:.2f}, after "
        f"{os.getloadavg()[0]:.2f}; 2 cores"
    )
    print("| preset | baseline wall | current wall | ratio | baseline CPU | current CPU | ratio |")
    print("|---|---|---|---|---|---|---|")
    for name in runs["current"][0]:
        row = [name]
        for column in (0, 1):
            base, now = (
                statistics.median(run[name][column] for run in runs[key]) * 1e3
                for key in ("baseline", "current")
            )
            row += [f"{base:.1f} ms", f"{now:.1f} ms", f"{now / base:.2f}"]
        print("| " + " | ".join(row) + " |")


if __name__ == "__main__":
    main()

"""Worked solutions in-process: this tree against a baseline tree, in the same run.

    git archive <commit> | (mkdir -p /tmp/base && tar -x -C /tmp/base)
    python -m benchmarks.bench_solutions --baseline /tmp/base --label <commit>

Each preset at its defaults, ``solver.solve(doc, method, 4).as_dict()`` (``--methods``, vector
and loop by default: parse, analysis, steps, the /solution body), timed in a fresh interpreter
per tree and round, the two trees alternating so that both see the same load. Prints the median
over rounds of each round's p50, wall clock and CPU time of the process (the CPU time is what a
quiet machine would take, less sensitive to the other processes on a loaded one), and writes the
report into its section of docs/BENCHMARKS.md (not with ``--no-write``). Issue 12's target:
under 20 ms for the slowest preset on a quiet machine.
"""

from __future__ import annotations

import argparse
import json
import os
import statistics
import subprocess
import sys
from datetime import UTC, datetime
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
if str(ROOT) not in sys.path:  # run as `python benchmarks/bench_solutions.py`
    sys.path.insert(0, str(ROOT))

from benchmarks.sections import write_section  # noqa: E402

DOC = ROOT / "docs" / "BENCHMARKS.md"

MEASURE = """
import json, statistics, sys, time
sys.path.insert(0, {tree!r})
import solver
from solver.teaching.presets import PRESETS, build_preset
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


def table(runs: dict[str, list[dict[str, list[float]]]]) -> str:
    """Per preset: the median over rounds of wall and CPU p50, baseline and current, and ratios."""
    lines = [
        "| preset | baseline wall | current wall | ratio | baseline CPU | current CPU | ratio |",
        "|---|---|---|---|---|---|---|",
    ]
    for name in runs["current"][0]:
        row = [name]
        for column in (0, 1):
            base, now = (
                statistics.median(run[name][column] for run in runs[key]) * 1e3
                for key in ("baseline", "current")
            )
            row += [f"{base:.1f} ms", f"{now:.1f} ms", f"{now / base:.2f}"]
        lines.append("| " + " | ".join(row) + " |")
    return "\n".join(lines)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--baseline", type=Path, required=True, help="an exported older tree")
    parser.add_argument("--label", default="", help="what the baseline is (a commit, say)")
    parser.add_argument("--calls", type=int, default=15, help="solutions per preset and round")
    parser.add_argument("--rounds", type=int, default=3)
    parser.add_argument("--methods", default="vector,loop", help="comma-separated methods")
    parser.add_argument("--no-write", action="store_true", help="print only")
    args = parser.parse_args()
    trees = {"baseline": args.baseline.resolve(), "current": ROOT}
    parts = []
    for method in args.methods.split(","):
        load = os.getloadavg()[0]
        runs: dict[str, list[dict[str, list[float]]]] = {k: [] for k in trees}
        for _ in range(args.rounds):
            for key, tree in trees.items():
                runs[key].append(measure(tree, args.calls, method))
        parts.append(
            f"Method {method}, {args.rounds} rounds of {args.calls} calls per preset; load "
            f"average (1 min) before {load:.2f}, after {os.getloadavg()[0]:.2f} "
            f"({os.cpu_count()} cores).\n\n" + table(runs)
        )
    when = datetime.now(UTC).strftime("%Y-%m-%d %H:%M UTC")
    report = (
        f"Measured {when} by `python -m benchmarks.bench_solutions`: this tree against the "
        f"baseline {args.label or args.baseline}, alternating in the same run (medians over "
        "rounds of each round's p50; the CPU time is the process's).\n\n" + "\n\n".join(parts)
    )
    print(report)
    if not args.no_write:
        write_section(DOC, "solutions", "Worked solutions against a baseline", report)


if __name__ == "__main__":
    main()

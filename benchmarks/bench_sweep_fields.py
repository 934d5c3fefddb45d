"""The cost of a sweep's derived fields (four-bar loops, sliders' travel, quick-return strokes),
against the same sweeps in other source trees, timed in one run.

Run from the repository root:

    python -m benchmarks.bench_sweep_fields
    python -m benchmarks.bench_sweep_fields --tree before=/tmp/tree-a --tree merged=/tmp/tree-b

Each ``--tree NAME=DIR`` is a checkout of this repository (``git archive COMMIT | tar -x -C
DIR``): the same sweeps run there in a child process (this interpreter, ``DIR`` first on the
path), interleaved with this tree's so that a load on the machine hits every column alike. The
sweeps are ``solver.sweep`` on the presets quick_return (slotted lever), slider_crank and
four_bar with their default values, 360 and 3600 samples, positions alone and positions,
velocities and accelerations; each time is the best of ``--repeats`` runs (ms). It prints a
markdown table; a benchmark, not a test: it never fails.
"""

from __future__ import annotations

import argparse
import json
import subprocess
import sys
import time
from pathlib import Path
from typing import Any

ROOT = Path(__file__).resolve().parent.parent
PRESETS = ("quick_return", "slider_crank", "four_bar")
SIZES = (360, 3600)
QUANTITY_SETS = (("position",), ("position", "velocity", "acceleration"))


def best_ms(doc: dict[str, Any], samples: int, quantities: list[str], repeats: int) -> float:
    """The fastest of ``repeats`` sweeps of ``doc`` (ms), after one warm-up."""
    import solver  # the tree's own solver: a child imports it from its path

    solver.sweep(doc, samples, quantities)
    fastest = float("inf")
    for _ in range(repeats):
        began = time.perf_counter()
        solver.sweep(doc, samples, quantities)
        fastest = min(fastest, time.perf_counter() - began)
    return 1e3 * fastest


def child() -> None:
    """Time the cases read from stdin (a JSON list of [doc, samples, quantities, repeats])."""
    cases = json.load(sys.stdin)
    json.dump([best_ms(*case) for case in cases], sys.stdout)


def in_tree(directory: str, cases: list[Any]) -> list[float]:
    """The cases timed by this script in a child process with ``directory`` first on the path."""
    env = {"PYTHONPATH": directory, "PATH": "/usr/bin:/bin"}
    done = subprocess.run(
        [sys.executable, str(Path(__file__).resolve()), "--child"],
        input=json.dumps(cases),
        capture_output=True,
        text=True,
        check=True,
        env=env,
        cwd=directory,
    )
    times: list[float] = json.loads(done.stdout)
    return times


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--tree", action="append", default=[], help="NAME=DIR, another checkout")
    parser.add_argument("--repeats", type=int, default=5)
    parser.add_argument("--rounds", type=int, default=3, help="interleaved rounds; best kept")
    parser.add_argument("--child", action="store_true", help=argparse.SUPPRESS)
    args = parser.parse_args()
    if args.child:
        child()
        return
    trees = [tuple(t.split("=", 1)) for t in args.tree] + [("this tree", str(ROOT))]
    sys.path.insert(0, str(ROOT))
    from solver.teaching.presets import build_preset

    rows = [
        (name, samples, list(quantities))
        for name in PRESETS
        for samples in SIZES
        for quantities in QUANTITY_SETS
    ]
    cases = [[build_preset(name, {}), n, q, args.repeats] for name, n, q in rows]
    best = {tree: [float("inf")] * len(rows) for tree, _ in trees}
    for _ in range(args.rounds):
        for tree, directory in trees:
            best[tree] = [
                min(a, b) for a, b in zip(best[tree], in_tree(directory, cases), strict=True)
            ]
    print("| preset | samples | quantities | " + " | ".join(f"{t} (ms)" for t, _ in trees) + " |")
    print("|---|---:|---|" + "---:|" * len(trees))
    for k, (name, samples, quantities) in enumerate(rows):
        what = "p" if len(quantities) == 1 else "p, v, a"
        times = " | ".join(f"{best[tree][k]:.2f}" for tree, _ in trees)
        print(f"| {name} | {samples} | {what} | {times} |")


if __name__ == "__main__":
    main()

"""Worked solutions in-process: this tree against a baseline tree, in the same run.

    git archive <commit> | (mkdir -p /tmp/base && tar -x -C /tmp/base)
    python -m benchmarks.bench_solutions --baseline /tmp/base --label <commit>

Each preset at its defaults, ``solver.solve(doc, method, 4).as_dict(arrays=True)``
(``--methods``, vector and loop by default: parse, analysis, steps, the /solution body as the
route takes it; ``as_dict()`` in a tree older than ``arrays``, which kept the arrays), timed in a
fresh interpreter per tree and round, the two trees alternating so that both see the same load.
Prints the median over rounds of each round's p50, wall clock and CPU time of the process (the
CPU time is what a quiet machine would take, less sensitive to the other processes on a loaded
one), and writes the report into its section of docs/BENCHMARKS.md (not with ``--no-write``).
Issue 12's target: under 20 ms for the slowest preset on a quiet machine; issue 22's: no slower
than the tree before it (5c4fb6a).

With ``--instructions`` it counts instead the instructions each solution runs, under valgrind's
callgrind (``apt-get install valgrind``), in one process per tree: slow (one to three minutes a
tree), but the same on a loaded, throttled or shared machine, where the times above can move by
half between two runs of the same tree.
"""

from __future__ import annotations

import argparse
import json
import os
import re
import shutil
import statistics
import subprocess
import sys
import tempfile
from datetime import UTC, datetime
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
if str(ROOT) not in sys.path:  # run as `python benchmarks/bench_solutions.py`
    sys.path.insert(0, str(ROOT))

from benchmarks.sections import write_section  # noqa: E402

DOC = ROOT / "docs" / "BENCHMARKS.md"

SETUP = """
import functools, gc, json, statistics, sys, time
sys.path.insert(0, {tree!r})
import solver
from solver.teaching.presets import PRESETS, build_preset
assert solver.__file__.startswith({tree!r}), solver.__file__
def body(doc):
    # the body as the route takes it: arrays kept (a tree older than ``arrays`` keeps them)
    result = solver.solve(doc, {method!r}, 4)
    try:
        return result.as_dict(arrays=True)
    except TypeError:
        return result.as_dict()
def warmed(name, calls):
    # the preset's document, its solution made ``calls`` times first (caches, imports)
    doc = build_preset(name, {{}})
    for _ in range(calls):
        body(doc)
    return doc
"""

# Each preset's calls inside one ``functools.reduce``: callgrind counts the instructions run
# within it (``--toggle-collect``) and writes one file per call (``--dump-after``). With them,
# the size of each preset's body (its JSON, arrays as lists), what the instructions wrote.
COUNT = (
    SETUP
    + """
size = {{}}
for name in PRESETS:
    doc = warmed(name, 2)
    gc.collect()  # (each preset's count starts with the same heap: no earlier garbage)
    functools.reduce(lambda _, __: body(doc), range({calls}), None)
    size[name] = len(json.dumps(body(doc), default=lambda array: array.tolist()))
print(json.dumps(size))
"""
)

MEASURE = (
    SETUP
    + """
out = {{}}
for name in PRESETS:
    doc = warmed(name, 3)
    wall, cpu = [], []
    for _ in range({calls}):
        w, c = time.perf_counter(), time.process_time()
        body(doc)
        wall.append(time.perf_counter() - w)
        cpu.append(time.process_time() - c)
    out[name] = [statistics.median(wall), statistics.median(cpu)]
print(json.dumps(out))
"""
)


def measure(tree: Path, calls: int, method: str) -> dict[str, list[float]]:
    code = MEASURE.format(tree=str(tree), calls=calls, method=method)
    done = subprocess.run(
        [sys.executable, "-c", code], cwd=tree, capture_output=True, text=True, check=True
    )
    result: dict[str, list[float]] = json.loads(done.stdout.strip().splitlines()[-1])
    return result


def count(tree: Path, calls: int, method: str) -> dict[str, tuple[float, int]]:
    """Instructions per solution of each preset in ``tree`` (callgrind: what the code does,
    whatever the machine's speed or load), and the size of its body (bytes of JSON)."""
    code = COUNT.format(tree=str(tree), calls=calls, method=method)
    with tempfile.TemporaryDirectory() as out:
        done = subprocess.run(
            ["valgrind", "--tool=callgrind", "--collect-atstart=no",
             "--toggle-collect=functools_reduce", "--dump-after=functools_reduce",
             f"--callgrind-out-file={out}/calls", sys.executable, "-c", code],
            cwd=tree, capture_output=True, text=True, check=True,
            env={**os.environ, "PYTHONHASHSEED": "0"},  # (the same dict and set orders)
        )  # fmt: skip
        sizes: dict[str, int] = json.loads(done.stdout.strip().splitlines()[-1])
        counted = {}
        for k, name in enumerate(sizes, start=1):
            found = re.search(r"^totals: (\d+)$", Path(out, f"calls.{k}").read_text(), re.M)
            assert found is not None, f"no totals in callgrind's file {k}"
            counted[name] = (int(found.group(1)) / calls, sizes[name])
    return counted


def count_table(counts: dict[str, dict[str, tuple[float, int]]]) -> str:
    """Per preset: instructions per solution, baseline and current, their ratio, the bodies'
    sizes and the ratio of instructions per byte written (the same work for more content is
    1.00 there)."""
    lines = [
        "| preset | baseline instructions | current instructions | ratio | baseline body | "
        "current body | ratio | instructions per byte, ratio |",
        "|---|---|---|---|---|---|---|---|",
    ]
    for name, (now, now_size) in counts["current"].items():
        base, base_size = counts["baseline"][name]
        per_byte = (now / now_size) / (base / base_size)
        lines.append(
            f"| {name} | {base / 1e6:.1f} M | {now / 1e6:.1f} M | {now / base:.2f} | "
            f"{base_size / 1e3:.1f} kB | {now_size / 1e3:.1f} kB | {now_size / base_size:.2f} | "
            f"{per_byte:.2f} |"
        )
    return "\n".join(lines)


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
    parser.add_argument(
        "--instructions",
        action="store_true",
        help="count instructions under valgrind (callgrind) instead of timing: slow (about a "
        "minute a tree and method), but what a loaded or throttled machine cannot skew",
    )
    args = parser.parse_args()
    if args.instructions and shutil.which("valgrind") is None:
        parser.error("--instructions needs valgrind (apt-get install valgrind)")
    trees = {"baseline": args.baseline.resolve(), "current": ROOT}
    parts = []
    for method in args.methods.split(",") if args.instructions else ():
        counts = {key: count(tree, args.calls, method) for key, tree in trees.items()}
        parts.append(
            f"Method {method}, instructions per solution (callgrind, {args.calls} calls per "
            "preset after 2 to warm up).\n\n" + count_table(counts)
        )
    for method in () if args.instructions else args.methods.split(","):
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
    how = (
        "instructions counted by callgrind"
        if args.instructions
        else "alternating in the same run (medians over rounds of each round's p50; the CPU "
        "time is the process's)"
    )
    flag = " --instructions" if args.instructions else ""
    report = (
        f"Measured {when} by `python -m benchmarks.bench_solutions{flag}`: this tree against "
        f"the baseline {args.label or args.baseline}, {how}.\n\n" + "\n\n".join(parts)
    )
    print(report)
    if not args.no_write:
        section = "solution-instructions" if args.instructions else "solutions"
        title = "Worked solutions against a baseline" + (
            ", instructions" if args.instructions else ""
        )
        write_section(DOC, section, title, report)


if __name__ == "__main__":
    main()

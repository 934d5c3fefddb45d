"""Speed and memory of exercise generation: 1000 exercises with keys and worked solutions.

Run from the repository root:

    python -m benchmarks.bench_exercises              # 1000 exercises (about a minute)
    python -m benchmarks.bench_exercises --count 270  # fewer, noisier
    python -m benchmarks.bench_exercises --no-write   # print only

The exercises are spread evenly over every type and difficulty (ids ``type:difficulty:1:k``).
The baseline, measured in the same run on the same final scenes (interleaved exercise by
exercise, so that other load weighs on both alike), is the solver alone: parse and analyse each
scene (what its key needs) and build its worked solution. Generation costs more
than that by the rejected draws (a candidate near a dead centre, or with a negligible answer, is
drawn again) and the figure. Peak memory is tracemalloc's over generating and holding all the
exercises with their solutions (what an export of that many would hold), in a second, untimed
pass. The report is printed
and written into docs/BENCHMARKS.md between ``<!-- exercises:start -->`` and
``<!-- exercises:end -->`` (appended when absent; the rest of the file is kept).
"""

from __future__ import annotations

import argparse
import os
import statistics
import sys
import time
import tracemalloc
from collections.abc import Callable
from datetime import UTC, datetime
from pathlib import Path
from typing import Any

ROOT = Path(__file__).resolve().parent.parent
if str(ROOT) not in sys.path:  # run as `python benchmarks/bench_exercises.py`
    sys.path.insert(0, str(ROOT))

from solver.exercises import DIFFICULTIES, TYPES, Exercise, ExerciseId, build  # noqa: E402
from solver.exercises.answers import parse, solve_scene  # noqa: E402
from solver.exercises.checking import check_answers  # noqa: E402
from solver.exercises.export import answer_csv, html_sheets, moodle_xml  # noqa: E402
from solver.exercises.solutions import DIGITS, worked_solution  # noqa: E402
from solver.solutions import solve  # noqa: E402

DOC = ROOT / "docs" / "BENCHMARKS.md"
START, END = "<!-- exercises:start -->", "<!-- exercises:end -->"


def ids(count: int) -> list[ExerciseId]:
    combos = [(t, d) for t in TYPES for d in DIFFICULTIES]
    return [ExerciseId(*combos[k % len(combos)], 1, k // len(combos)) for k in range(count)]


def timed(fn: Callable[[], Any]) -> tuple[float, Any]:
    start = time.perf_counter()
    value = fn()
    return time.perf_counter() - start, value


def table(headers: list[str], rows: list[list[str]]) -> str:
    lines = ["| " + " | ".join(headers) + " |", "|" + "---|" * len(headers)]
    lines += ["| " + " | ".join(row) + " |" for row in rows]
    return "\n".join(lines)


def run(count: int) -> str:
    load_before = os.getloadavg()[0]
    wanted = ids(count)
    # generation (key + figure) and worked solution of each exercise, interleaved with the
    # baseline on its final scene, so that other load on the machine weighs on both alike
    per_type: dict[str, list[float]] = {t: [] for t in TYPES}
    exercises: list[Exercise] = []
    t_generate = t_solutions = t_analyze = t_solve = 0.0
    steps = 0
    for ident in wanted:
        dt, exercise = timed(lambda i=ident: build(i))
        per_type[ident.type].append(dt)
        t_generate += dt
        exercises.append(exercise)
        dt, solution = timed(lambda e=exercise: worked_solution(e))
        t_solutions += dt
        steps += len(solution)
        t_analyze += timed(lambda e=exercise: solve_scene(e.scene))[0]
        t_solve += timed(lambda e=exercise: solve(parse(e.scene), "vector", DIGITS))[0]
    # peak memory in a second pass (tracemalloc slows Python down: not in the timed pass)
    tracemalloc.start()
    held = [(e := build(i), worked_solution(e)) for i in wanted]
    _, peak = tracemalloc.get_traced_memory()
    tracemalloc.stop()
    del held
    # checking (a wrong answer: the typical mistakes are made) and exports of a full request
    sample = exercises[: min(len(exercises), 54)]
    check_times = [
        timed(lambda e=e: check_answers(e, {k: 1.5 * v for k, v in e.answers.items()}))[0]
        for e in sample
    ]
    batch = exercises[:100]
    t_moodle, _ = timed(lambda: moodle_xml(batch))
    t_html, _ = timed(lambda: html_sheets(batch, True))
    t_csv, _ = timed(lambda: answer_csv(batch))
    load_after = os.getloadavg()[0]

    ms = 1e3
    rows = [
        ["generate (key + figure)", f"{t_generate:.2f} s", f"{t_generate / count * ms:.2f} ms"],
        ["worked solutions", f"{t_solutions:.2f} s", f"{t_solutions / count * ms:.2f} ms"],
        ["**total**", f"**{t_generate + t_solutions:.2f} s**",
         f"**{(t_generate + t_solutions) / count * ms:.2f} ms**"],
        ["baseline: solver analysis of the final scenes", f"{t_analyze:.2f} s",
         f"{t_analyze / count * ms:.2f} ms"],
        ["baseline: solver worked solution of the final scenes", f"{t_solve:.2f} s",
         f"{t_solve / count * ms:.2f} ms"],
    ]  # fmt: skip
    by_type = [
        [
            name,
            f"{statistics.median(times) * ms:.2f} ms",
            f"{max(times) * ms:.1f} ms",
        ]
        for name, times in per_type.items()
        if times
    ]
    other = [
        [
            "check with diagnosis (every answer wrong), p50",
            f"{statistics.median(check_times) * ms:.1f} ms",
        ],
        [f"export of {len(batch)}: Moodle XML", f"{t_moodle * ms:.0f} ms"],
        [f"export of {len(batch)}: HTML key with worked solutions", f"{t_html * ms:.0f} ms"],
        [f"export of {len(batch)}: CSV", f"{t_csv * ms:.1f} ms"],
    ]  # fmt: skip
    when = datetime.now(UTC).strftime("%Y-%m-%d %H:%M UTC")
    ratio = (t_generate + t_solutions) / (t_analyze + t_solve)
    return "\n\n".join(
        [
            f"Measured {when} by `python -m benchmarks.bench_exercises --count {count}`: "
            f"{count} exercises over {len(TYPES)} types x {len(DIFFICULTIES)} difficulties, "
            f"{steps} solution steps. Load average (1 min) before {load_before:.2f}, after "
            f"{load_after:.2f} (2 cores: above 0 means other processes competed).",
            table(["stage", "time", "per exercise"], rows),
            f"Generation with solutions costs {ratio:.2f}x the solver alone on the same scenes "
            f"(generation alone {t_generate / t_analyze:.2f}x the analysis: rejected draws and "
            f"figures; solutions {t_solutions / t_solve:.2f}x the solver's steps). Peak memory "
            f"(tracemalloc) generating and holding all {count} exercises with their "
            f"solutions: {peak / 2**20:.1f} MiB.",
            table(["type", "generate p50", "slowest"], by_type),
            table(["operation", "time"], other),
        ]
    )


def write_doc(report: str) -> None:
    text = DOC.read_text() if DOC.exists() else "# Benchmarks\n"
    block = f"{START}\n{report}\n{END}"
    if START in text and END in text:
        head, rest = text.split(START, 1)
        text = head + block + rest.split(END, 1)[1]
    else:
        text = text.rstrip() + "\n\n## Exercises: generation, keys, solutions\n\n" + block + "\n"
    DOC.write_text(text)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--count", type=int, default=1000)
    parser.add_argument("--no-write", action="store_true")
    args = parser.parse_args()
    report = run(args.count)
    print(report)
    if not args.no_write:
        write_doc(report)


if __name__ == "__main__":
    main()

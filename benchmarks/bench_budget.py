"""The cost budget's Newton-Raphson model (solver/analysis/work_estimate.py) against measured times.

Run from the repository root (about 3 minutes on a loaded 2-core machine):

    python -m benchmarks.bench_budget

Before any work the budget estimates the seconds of one core that the links solved by
Newton-Raphson take, ``solver.estimate_work(...).newton.seconds``: links x (samples +
``SETUP_SAMPLES`` + ``SAMPLES_PER_RADIAN`` x the radians the drivers turn from the drawn pose),
and refuses a request whose estimate passes its endpoint's time limit / ``budget.SAFETY``. This
script times, on one core, what such requests really cost:

- sweeps (positions, velocities and accelerations) of Stephenson III six-bars
  (``tests.scenes.triads``: 1 to 8 triads on one crank, between limit positions:
  one Newton-Raphson group of 4 to 32 links) and of a fully turning triad
  (``benchmarks.bench_newton.FULL_TURN``) over 20 to 1,440 samples;
- instants (/analyze's solver call) of the fully turning triad 1 to 100 rad from the drawn pose,
  and time sweeps of it turning 10 and 100 rad (the continuation walks there).

With ``--whole`` it times instead the whole request's estimate (``WorkEstimate.seconds``, the
closed-form work and the drivers' turn; ``solver.exercise_work``): revolutions of S000-T1,
time sweeps and event searches of the parallelogram S003-T1 turning 65 to 268 rad, and five
exercises of each type with their worked solutions (fitted 2026-11-29 at a load average of 8 to
9, in wall time: the time limits are wall-clock).

For each it prints the charge, the estimate, the measured time and measured / estimated; the
largest ratio must stay at most 1 (then a request the budget accepts ends within its time limit
unless the machine is more than ``SAFETY`` times slower than when it was fitted). Each time is
the best of ``--repeats`` runs (the machine is shared: the least disturbed run is the cost).
Printed only; docs/SERVING.md quotes a run.
"""

from __future__ import annotations

import argparse
import contextlib
import copy
import json
import sys
import time
from collections.abc import Callable, Iterator
from functools import partial
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
if str(ROOT) not in sys.path:
    sys.path.insert(0, str(ROOT))


import solver  # noqa: E402
from benchmarks.bench_newton import FULL_TURN  # noqa: E402
from server import budget  # noqa: E402
from solver.analysis.work_estimate import SAMPLE_COST, SAMPLES_PER_RADIAN, SETUP_SAMPLES  # noqa: E402
from solver.exercises import TYPES, generate  # noqa: E402
from solver.exercises.solutions import worked_solution  # noqa: E402
from tests.scenes import triads  # noqa: E402

QUANTITIES = ["position", "velocity", "acceleration"]


def best(run: Callable[[], object], repeats: int) -> float:
    """Seconds of the least disturbed of ``repeats`` runs."""
    times = []
    for _ in range(repeats):
        start = time.perf_counter()
        run()
        times.append(time.perf_counter() - start)
    return min(times)


def far(turn: float) -> solver.ReadScene:
    """The fully turning triad driven by an angle law, ``turn`` rad from the drawn pose at t = 1."""
    doc = copy.deepcopy(FULL_TURN)
    doc["drivers"] = [{"link": "crank", "angle_law": f"{turn:g}*t"}]
    doc["time"] = 1.0
    return solver.read_scene(doc)


def cases() -> Iterator[tuple[str, solver.WorkEstimate, Callable[[], object]]]:
    """(request, the solver's estimate of its work, the solver call)."""
    for count in (1, 2, 4, 8):
        read = solver.read_scene(triads(count))
        for samples in (20, 90, 360, 1440):
            yield (
                f"sweep, {count} triad(s) between limit positions, {samples} samples",
                solver.estimate_work(read.scene, samples, QUANTITIES),
                partial(solver.sweep, read, samples, QUANTITIES),
            )  # fmt: skip
    full = solver.read_scene(FULL_TURN)
    for samples in (20, 360, 1440):
        yield (
            f"sweep, a fully turning triad, {samples} samples",
            solver.estimate_work(full.scene, samples, QUANTITIES),
            partial(solver.sweep, full, samples, QUANTITIES),
        )  # fmt: skip
    for radians in (1.0, 10.0, 100.0):
        read = far(radians)
        yield (
            f"instant, a fully turning triad {radians:g} rad from the drawn pose",
            solver.estimate_work(read.scene), partial(solver.analyze, read, QUANTITIES),
        )  # fmt: skip
    for radians in (10.0, 100.0):
        read = far(radians)
        yield (
            f"time sweep over [0, 1] s, a fully turning triad turning {radians:g} rad, 20 samples",
            solver.estimate_work(read.scene, 20, QUANTITIES, time_range=[0.0, 1.0]),
            partial(solver.sweep_time, read, [0.0, 1.0], 20, QUANTITIES),
        )  # fmt: skip


def whole_cases() -> Iterator[tuple[str, float, Callable[[], object]]]:
    """(request, the estimate of its whole work in seconds, the solver call)."""
    examples = ROOT / "server" / "examples"
    s000 = solver.read_scene(json.loads((examples / "S000-T1.json").read_text()))
    for samples in (360, 3600):
        yield (
            f"sweep of S000-T1, {samples} samples",
            solver.estimate_work(s000.scene, samples, QUANTITIES).seconds,
            partial(solver.sweep, s000, samples, QUANTITIES),
        )  # fmt: skip
    s003 = solver.read_scene(
        json.loads((examples / "S003-T1-translating-carrier.json").read_text())
    )
    for t in (5.0, 8.0):
        span = [0.0, t]
        yield (
            f"time sweep of S003-T1 over [0, {t:g}] s, 100 samples",
            solver.estimate_work(s003.scene, 100, QUANTITIES, time_range=span).seconds,
            partial(solver.sweep_time, s003, span, 100, QUANTITIES),
        )  # fmt: skip
        yield (
            f"event search of S003-T1, M reaches O1, t_max {t:g} s",
            solver.estimate_work(s003.scene, event=("M", t), reaches="O1").seconds,
            partial(_event, s003, t),
        )  # fmt: skip
    for kind in TYPES:
        yield (
            f"5 exercises {kind} with their worked solutions",
            solver.exercise_work(kind, 5, True).seconds,
            partial(_exercises, kind),
        )  # fmt: skip


def _event(read: solver.ReadScene, t_max: float) -> None:
    with contextlib.suppress(solver.NoEvent):  # searched to t_max: the work was done
        solver.find_event(read, "M", "O1", 1, t_max)


def _exercises(kind: str) -> None:
    for exercise in generate(kind, "challenging", 0, 5):
        exercise.as_json()
        worked_solution(exercise)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--repeats", type=int, default=3)
    parser.add_argument("--whole", action="store_true", help="the whole request's estimate")
    args = parser.parse_args()
    if args.whole:
        rows = ["| request | estimated | measured | measured / estimated |", "|---|---|---|---|"]
        for name, estimate, call in whole_cases():
            seconds = best(call, args.repeats)
            rows.append(
                f"| {name} | {estimate * 1e3:.0f} ms | {seconds * 1e3:.0f} ms | "
                f"{seconds / estimate:.2f} |"
            )
            print(rows[-1], flush=True)
        print("\n".join(["", *rows, ""]))
        return
    rows = [
        "| request | Newton links | link-samples | estimated | measured | measured / estimated |",
        "|---|---|---|---|---|---|",
    ]
    ratios = []
    for name, estimate, call in cases():
        work = estimate.newton
        assert work is not None
        seconds = best(call, args.repeats)
        ratios.append(seconds / work.seconds)
        rows.append(
            f"| {name} | {work.links} | {work.link_samples:,.0f} | {work.seconds * 1e3:.0f} ms | "
            f"{seconds * 1e3:.0f} ms | {ratios[-1]:.2f} |"
        )
        print(rows[-1], flush=True)
    print("\n".join(["", *rows, ""]))
    print(
        f"Largest measured / estimated: {max(ratios):.2f} (the model: {SAMPLE_COST * 1e6:g} "
        f"us per link-sample, {SETUP_SAMPLES} samples of path tracing, "
        f"{SAMPLES_PER_RADIAN} samples per radian from the drawn pose). A request is "
        f"refused past its endpoint's time limit / {budget.SAFETY:g}: an estimate within the "
        f"limit runs past the time limit only if it is off by more than {budget.SAFETY:g}x "
        f"({'OK' if max(ratios) <= budget.SAFETY else 'NOT SO HERE: re-fit'})."
    )


if __name__ == "__main__":
    main()

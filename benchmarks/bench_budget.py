"""The cost model of the budget (solver/analysis/work_estimate.py) fitted to measured CPU time.

Run from the repository root (about 5 minutes on a loaded 2-core machine):

    python -m benchmarks.bench_budget

Before any work the server estimates a request's seconds of one core (``solver.estimate_work``,
``solver.exercise_work`` and the fixed costs of ``server.budget``'s checks) and refuses a
request whose estimate passes its endpoint's time limit / ``budget.SAFETY``. The estimate is
linear in its constants: each request has *features* (link-samples solved by Newton-Raphson,
closed-form group-samples, radians of driver turn per dyad, response values, exercises, ...) and
its estimate is the sum of each feature times its constant:

| feature | constant |
|---|---|
| Newton links x samples | ``SAMPLE_COST`` |
| Newton links (path tracing, feasible-range search) | ``SAMPLE_COST x SETUP_SAMPLES`` |
| Newton links x radians from the drawn pose | ``SAMPLE_COST x SAMPLES_PER_RADIAN`` |
| closed-form groups x samples | ``CLOSED_FORM_COST`` |
| closed-form groups | ``CLOSED_FORM_COST x CLOSED_FORM_SETUP_SAMPLES`` |
| dyads and levers x radians walked | ``TURN_COST`` |
| values of a cam's, gear train's or spatial chain's response | ``VALUE_COST`` |
| a solution; balancing; synthesis | ``SOLUTION_COST``; ``BALANCE_COST``; ``SYNTHESIS_COST`` |
| exercises of a type, alone or with their worked solutions | ``EXERCISE_COSTS[type]`` |
| exercises exported (a printable sheet, on top of the exercises) | ``EXPORT_COST`` |
| every request (HTTP, validation, the check, serialising: fitted, not charged) | none |

It sends a spread of requests of every kind through the app in this process (no worker pool,
so the solver runs in this process and its CPU time is measured with ``time.process_time``:
parsing, the check, the solve and the serialisation): sweeps of closed-form linkages, of
Newton-Raphson groups of 4 to 32 links, of a spatial chain, a cam and a gear train over a range
of samples; instants far from the drawn pose; time sweeps and event searches that walk up to
268 rad; worked solutions by every method; balancing; synthesis; exercises of every type alone
and with their worked solutions, and exports. Each time is the least of ``--repeats`` runs (the
machine is shared: the least disturbed run is the cost).

The fit: non-negative least squares on the ratio, minimising sum_i (estimate_i / measured_i -
1)^2 over the constants (each request weighs the same whatever its size; a constant cannot be
negative). It prints each request's estimate with the constants in the code and with the fitted
ones, the measured time and measured / fitted, then the spread of that ratio (its quartiles and
extremes) and the fitted constants in the form the code states them. The fixed cost of a request
through the app (a few ms) is fitted so that it does not bend the other constants, but the
budget does not charge it: it is far below any limit. Printed only;
docs/BENCHMARKS.md quotes a run and the constants in the code are its fit (rounded).
"""

from __future__ import annotations

import argparse
import copy
import json
import math
import statistics
import sys
import time
from collections.abc import Callable, Iterator
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np
from scipy.optimize import nnls

ROOT = Path(__file__).resolve().parents[1]
if str(ROOT) not in sys.path:
    sys.path.insert(0, str(ROOT))

from fastapi.testclient import TestClient  # noqa: E402

import solver  # noqa: E402
from benchmarks.bench_newton import FULL_TURN  # noqa: E402
from server.app import create_app  # noqa: E402
from server.routes.presets import ALL_PRESETS  # noqa: E402
from server.settings import Settings  # noqa: E402
from solver.analysis import work_estimate as model  # noqa: E402
from solver.exercises import TYPES  # noqa: E402
from tests.scenes import triads  # noqa: E402

EXAMPLES = ROOT / "server" / "examples"
QUANTITIES = ["position", "velocity", "acceleration"]
DIFFICULTY = "challenging"  # the costliest


def example(name: str) -> dict[str, Any]:
    doc: dict[str, Any] = json.loads((EXAMPLES / f"{name}.json").read_text())
    return doc


@dataclass
class Case:
    """A request, its features (by the names of ``constants()``) and the app's answer status."""

    name: str
    path: str
    body: dict[str, Any]
    features: dict[str, float] = field(default_factory=dict)
    status: int = 200

    def __post_init__(self) -> None:
        self.features["request"] = 1  # every request's fixed cost


NEWTON = ("newton_sample", "newton_setup", "newton_radian")
GROUP = ("group_sample", "group_setup", "group_radian")


def constants() -> dict[str, float]:
    """Each feature's constant, as the code states it (seconds per unit of the feature)."""
    out = {
        "newton": model.SAMPLE_COST,
        "group": model.GROUP_SAMPLE_COST,
        "closed_sample": model.CLOSED_FORM_COST,
        "closed_setup": model.CLOSED_FORM_COST * model.CLOSED_FORM_SETUP_SAMPLES,
        "turn": model.TURN_COST,
        "value": model.VALUE_COST,
        "solution": model.SOLUTION_COST,
        "balance": model.BALANCE_COST,
        "synthesis": model.SYNTHESIS_COST,
        "export": model.EXPORT_COST,
        "request": 0.0,  # fitted, not charged (see the module)
    }
    for kind in TYPES:  # a type not listed costs the costliest (solver.exercise_work)
        out[f"exercise {kind}"] = solver.exercise_work(kind, 1, False).seconds
        out[f"exercise {kind} solved"] = solver.exercise_work(kind, 1, True).seconds
    return out


def features(estimate: solver.WorkEstimate) -> dict[str, float]:
    """The features of a scene's work (``estimate_work``): the Newton-Raphson groups' as their
    links and squared links times samples, fixed work and turn (``newton_features`` combines
    them)."""
    out: dict[str, float] = {}
    if estimate.newton is not None:
        n = estimate.newton
        for names, links in ((NEWTON, n.links), (GROUP, n.squared_links)):
            out |= dict(zip(names, (links * n.samples, links, links * n.turn), strict=True))
    if estimate.closed_form is not None:
        c = estimate.closed_form
        out |= {
            "closed_sample": c.groups * c.samples,
            "closed_setup": c.groups,
            "turn": c.branch_groups * c.turn,
        }
    if estimate.newton is None and estimate.closed_form is None:
        out["value"] = estimate.values
    return out


def far(turn: float) -> dict[str, Any]:
    """The fully turning triad driven by an angle law, ``turn`` rad from the drawn pose at t = 1."""
    doc = copy.deepcopy(FULL_TURN)
    doc["drivers"] = [{"link": "crank", "angle_law": f"{turn:g}*t"}]
    doc["time"] = 1.0
    return doc


def with_masses(doc: dict[str, Any]) -> dict[str, Any]:
    doc = copy.deepcopy(doc)
    doc["masses"] = {
        name: {"mass": 2.0, "bar": link["points"][:2]}
        for name, link in doc["links"].items()
        if not link.get("ground")
    }
    return doc


def sweep(name: str, doc: dict[str, Any], samples: int, **extra: Any) -> Case:
    scene = solver.parse_scene(doc)
    span = extra.get("time_range")
    estimate = solver.estimate_work(scene, samples, QUANTITIES, time_range=span)
    body = {"scene": doc, "samples": samples, "quantities": QUANTITIES, **extra}
    return Case(name, "/api/v1/sweep", body, features(estimate))


def cases() -> Iterator[Case]:
    s000, s003 = example("S000-T1"), example("S003-T1-translating-carrier")
    for samples in (90, 360, 1440, 5000):
        yield sweep(f"sweep of S000-T1 (closed form), {samples} samples", s000, samples)
    for count in (1, 2, 4, 8):
        for samples in (90, 360, 1300):
            name = f"sweep, {count} triad(s) ({4 * count} Newton links), {samples} samples"
            yield sweep(name, triads(count), samples)
    for samples in (20, 360):
        yield sweep(f"sweep of a fully turning triad, {samples} samples", FULL_TURN, samples)
    for turn in (10.0, 100.0):
        name = f"time sweep of a fully turning triad turning {turn:g} rad, 20 samples"
        yield sweep(name, far(turn), 20, time_range=[0.0, 1.0])
    for t in (2.0, 5.0, 8.0):
        name = f"time sweep of S003-T1 over [0, {t:g}] s ({0.5236 * t**3:.0f} rad), 100 samples"
        yield sweep(name, s003, 100, time_range=[0.0, t])
    spatial, gears = example("S002-spatial-arm"), example("G001-planetary")
    cam = json.loads((EXAMPLES / "cams" / "cam-roller-translating.json").read_text())
    for samples in (360, 3600, 20000):
        yield sweep(f"sweep of a cam, {samples} samples", cam, samples)
    for samples in (100, 2000, 10000):
        name = f"time sweep of the spatial arm, {samples} samples"
        yield sweep(name, spatial, samples, time_range=[0.0, 1.0])
        name = f"time sweep of the planetary gear train, {samples} samples"
        yield sweep(name, gears, samples, time_range=[0.0, 1.0])
    for turn in (1.0, 10.0, 40.0):
        estimate = solver.estimate_work(solver.parse_scene(far(turn)))
        name = f"instant of a fully turning triad {turn:g} rad from the drawn pose"
        yield Case(name, "/api/v1/analyze", {"scene": far(turn)}, features(estimate))
    for t in (5.0, 8.0):
        estimate = solver.estimate_work(solver.parse_scene(s003), event=("M", t), reaches="O1")
        event = {"moving_point": "M", "reaches": "O1", "t_max": t}
        name = f"event search of S003-T1, M reaches O1, t_max {t:g} s ({0.5236 * t**3:.0f} rad)"
        body = {"scene": s003, "event": event}  # searched to t_max: no_event (422)
        yield Case(name, "/api/v1/events", body, features(estimate), status=422)
    yield from solutions(s000)
    weights = [{"link": "crank", "mass": 1.0}, {"link": "rocker", "mass": 1.0}]
    balance = {"scene": with_masses(ALL_PRESETS["four_bar"].build({})), "counterweights": weights}
    yield Case("balancing of a four-bar", "/api/v1/balance", balance, {"balance": 1})
    from server.routes.synthesis import EXAMPLES as TASKS

    for task, given in TASKS.items():
        yield Case(f"synthesis, {task}", "/api/v1/synthesis", given["value"], {"synthesis": 1})
    yield from exercises()


def solutions(s000: dict[str, Any]) -> Iterator[Case]:
    """Worked solutions: the instant's features and one solution's."""
    instant = features(solver.estimate_work(solver.parse_scene(s000)))
    for method in ("vector", "loop"):
        body = {"scene": s000, "method": method}
        yield Case(f"solution of S000-T1, {method}", "/api/v1/solution", body,
                   instant | {"solution": 1})  # fmt: skip
    masses = with_masses(ALL_PRESETS["four_bar"].build({}))
    body = {"scene": masses, "method": "newton_euler"}
    instant = features(solver.estimate_work(solver.parse_scene(masses)))
    yield Case("solution of a four-bar with masses, newton_euler", "/api/v1/solution", body,
               instant | {"solution": 1})  # fmt: skip
    for name in ("G001-planetary",):
        yield Case(f"solution of {name}", "/api/v1/solution", {"scene": example(name)},
                   {"solution": 1})  # fmt: skip
    cam = json.loads((EXAMPLES / "cams" / "cam-roller-translating.json").read_text())
    yield Case("solution of a cam", "/api/v1/solution", {"scene": cam}, {"solution": 1})


def exercises() -> Iterator[Case]:
    for kind in TYPES:
        for count, solved in ((4, False), (12, False), (2, True), (5, True)):
            body = {"type": kind, "difficulty": DIFFICULTY, "count": count, "seed": 3,
                    "with_solutions": solved}  # fmt: skip
            what = "with their worked solutions" if solved else "alone"
            feature = f"exercise {kind}" + (" solved" if solved else "")
            yield Case(f"{count} exercises {kind} {what}", "/api/v1/exercises", body,
                       {feature: count})  # fmt: skip
        body = {"type": kind, "difficulty": DIFFICULTY, "count": 3, "seed": 5,
                "with_solutions": True, "format": "html"}  # fmt: skip
        yield Case(f"export of 3 exercises {kind}, html with solutions",
                   "/api/v1/exercises/export", body,
                   {f"exercise {kind} solved": 3, "export": 3})  # fmt: skip


def cpu_seconds(run: Callable[[], object], repeats: int) -> float:
    """CPU seconds of this process (every thread) of the least disturbed of ``repeats`` runs."""
    times = []
    for _ in range(repeats):
        start = time.process_time()
        run()
        times.append(time.process_time() - start)
    return min(times)


def fit(rows: list[tuple[dict[str, float], float]], names: list[str]) -> dict[str, float]:
    """Non-negative least squares on the ratio: min sum_i (sum_k c_k f_ik / m_i - 1)^2."""
    matrix = np.array([[amounts.get(n, 0.0) / measured for n in names] for amounts, measured
                       in rows])  # fmt: skip
    solution, _ = nnls(matrix, np.ones(len(rows)))
    return dict(zip(names, solution.tolist(), strict=True))


def two_stage_fit(rows: list[tuple[Case, float]]) -> tuple[float, float, dict[str, float]]:
    """The fixed work and samples per radian from a fit with a Newton-Raphson cost linear in
    the links (its three features free), then every constant with those two fixed and the
    group-size term added: (SETUP_SAMPLES, SAMPLES_PER_RADIAN, the constants)."""
    others = [n for n in constants() if n not in ("newton", "group")]
    linear = fit([(case.features, m) for case, m in rows], [*NEWTON, *others])
    setup = linear["newton_setup"] / linear["newton_sample"]
    radian = linear["newton_radian"] / linear["newton_sample"]
    amounts = [(newton_features(case, setup, radian), m) for case, m in rows]
    return setup, radian, fit(amounts, ["newton", "group", *others])


def newton_features(case: Case, setup: float, radian: float) -> dict[str, float]:
    """The case's features with the Newton-Raphson groups' as two: links x (samples + ``setup``
    + ``radian`` x turn) (constant ``newton``: SAMPLE_COST) and the same with squared links
    (``group``: GROUP_SAMPLE_COST)."""
    out = {k: v for k, v in case.features.items() if k not in NEWTON + GROUP}
    if NEWTON[0] in case.features:
        for name, names in (("newton", NEWTON), ("group", GROUP)):
            sample, fixed, turn = (case.features[n] for n in names)
            out[name] = sample + setup * fixed + radian * turn
    return out


def estimate(amounts: dict[str, float], values: dict[str, float]) -> float:
    return sum(values[name] * amount for name, amount in amounts.items())


def stated(setup: float, radian: float, fitted: dict[str, float]) -> list[str]:
    """The fitted constants as solver/analysis/work_estimate.py states them."""
    closed = fitted["closed_sample"]
    lines = [
        f"SAMPLE_COST = {fitted['newton'] * 1e6:.3g}e-6",
        f"GROUP_SAMPLE_COST = {fitted['group'] * 1e6:.3g}e-6",
        f"SETUP_SAMPLES = {setup:.0f}",
        f"SAMPLES_PER_RADIAN = {radian:.0f}",
        f"CLOSED_FORM_COST = {closed * 1e6:.3g}e-6",
        f"CLOSED_FORM_SETUP_SAMPLES = {fitted['closed_setup'] / closed:.0f}" if closed else "",
        f"TURN_COST = {fitted['turn'] * 1e3:.3g}e-3",
        f"VALUE_COST = {fitted['value'] * 1e6:.3g}e-6",
        f"SOLUTION_COST = {fitted['solution']:.3g}",
        f"BALANCE_COST = {fitted['balance']:.3g}",
        f"SYNTHESIS_COST = {fitted['synthesis']:.3g}",
        f"EXPORT_COST = {fitted['export']:.3g}",
        "EXERCISE_COSTS = {",
    ]
    lines.insert(0, f"(the fixed cost of a request, not charged: {fitted['request'] * 1e3:.3g} ms)")
    for kind in TYPES:
        alone, solved = fitted[f"exercise {kind}"], fitted[f"exercise {kind} solved"]
        lines.append(f'    "{kind}": ({alone:.2g}, {solved:.2g}),')
    return [*lines, "}"]


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--repeats", type=int, default=3)
    args = parser.parse_args()
    client = TestClient(create_app(Settings(workers=0)))
    code = constants()
    names = [*NEWTON, *GROUP, *code]
    rows: list[tuple[Case, float]] = []
    for case in cases():
        unknown = set(case.features) - set(names)
        assert not unknown, (case.name, unknown)

        def send(case: Case = case) -> None:
            response = client.post(case.path, json=case.body)
            assert response.status_code == case.status, (case.name, response.text[:300])

        rows.append((case, cpu_seconds(send, args.repeats)))
        print(f"{case.name}: {rows[-1][1] * 1e3:.1f} ms", file=sys.stderr, flush=True)
    setup, radian, fitted = two_stage_fit(rows)
    table = [
        "| request | estimated (code) | estimated (fit) | measured CPU | measured / fit |",
        "|---|---|---|---|---|",
    ]
    ratios = []
    for case, measured in rows:
        stated_now = newton_features(case, model.SETUP_SAMPLES, model.SAMPLES_PER_RADIAN)
        fitted_now = estimate(newton_features(case, setup, radian), fitted)
        ratios.append(measured / fitted_now)
        table.append(
            f"| {case.name} | {estimate(stated_now, code) * 1e3:,.1f} ms | "
            f"{fitted_now * 1e3:,.1f} ms | {measured * 1e3:,.1f} ms | {ratios[-1]:.2f} |"
        )
    quartiles = statistics.quantiles(ratios, n=4)
    spread = statistics.pstdev([math.log(r) for r in ratios])
    print("\n".join(table))
    print(
        f"\n{len(rows)} requests, measured / fitted estimate: min {min(ratios):.2f}, quartiles "
        f"{quartiles[0]:.2f} / {quartiles[1]:.2f} / {quartiles[2]:.2f}, max {max(ratios):.2f}; "
        f"standard deviation of its log {spread:.2f} (a factor of {math.exp(spread):.2f})."
    )
    print("\nThe fitted constants (non-negative least squares on the ratio):\n")
    print("\n".join(stated(setup, radian, fitted)))


if __name__ == "__main__":
    main()

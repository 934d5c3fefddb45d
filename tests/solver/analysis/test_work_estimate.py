"""The work estimate orders requests as their work orders them (not timed: the estimate counts).

The constants are fitted to measured CPU time (benchmarks/bench_budget.py); whatever their
values, more of any kind of work must cost more, in proportion where the work is.
"""

from __future__ import annotations

import copy
import json
from pathlib import Path
from typing import Any

import pytest

import solver
from solver.analysis.work_estimate import GROUP_SAMPLE_COST, SAMPLE_COST
from solver.exercises import TYPES
from tests.scenes import triads

EXAMPLES = Path(__file__).parents[3] / "server" / "examples"
S000_T1 = json.loads((EXAMPLES / "S000-T1.json").read_text())
S003_T1 = json.loads((EXAMPLES / "S003-T1-translating-carrier.json").read_text())
CAM = json.loads((EXAMPLES / "cams" / "cam-roller-translating.json").read_text())


def seconds(doc: dict[str, Any], samples: int | None = None, **given: Any) -> float:
    return solver.estimate_work(solver.parse_scene(doc), samples, **given).seconds


@pytest.mark.parametrize("doc", [S000_T1, triads(2), CAM], ids=["closed form", "Newton", "cam"])
def test_the_estimate_is_linear_in_samples(doc: dict[str, Any]) -> None:
    """Each sample adds the same work: e(4n) - e(2n) = 2 (e(2n) - e(n)) > 0; past the fixed
    work, doubling the samples nearly doubles the estimate."""
    n = 1000
    step = seconds(doc, 2 * n) - seconds(doc, n)
    assert step > 0
    assert seconds(doc, 4 * n) - seconds(doc, 2 * n) == pytest.approx(2 * step, rel=1e-12)
    assert 1.5 < seconds(doc, 40 * n) / seconds(doc, 20 * n) <= 2.0


def test_a_driver_law_turning_100_times_further_costs_more() -> None:
    """S003-T1's crank turns 0.5236 t^3 rad; the law x 100 turns it 100 times as far over the
    same time range, and the walk along the path is charged per radian."""
    faster = copy.deepcopy(S003_T1)
    faster["drivers"][0]["angle_law"] = f"100*({S003_T1['drivers'][0]['angle_law']})"
    span = [0.0, 2.0]
    slow, fast = seconds(S003_T1, 100, time_range=span), seconds(faster, 100, time_range=span)
    fixed = seconds(S003_T1, 100, time_range=[0.0, 0.0])  # no turn: the sampled work alone
    assert fast - fixed == pytest.approx(100 * (slow - fixed), rel=1e-6)
    assert fast > 10 * slow


def test_more_newton_links_cost_more_than_in_proportion() -> None:
    """A group of n links costs n x (SAMPLE_COST + n x GROUP_SAMPLE_COST) per sample: 32 links
    more than 8 times 4 (measured about 40 times, benchmarks/bench_budget.py)."""
    costs = [seconds(triads(count), 360) for count in (1, 2, 4, 8)]
    assert costs == sorted(costs) and len(set(costs)) == 4
    rate = [n * (SAMPLE_COST + n * GROUP_SAMPLE_COST) for n in (4, 32)]
    assert costs[3] / costs[0] == pytest.approx(rate[1] / rate[0])
    assert costs[3] / costs[0] > 8.0


def test_an_event_search_further_costs_more() -> None:
    near, far = (
        solver.estimate_work(solver.parse_scene(S003_T1), event=("M", t), reaches="O1").seconds
        for t in (2.0, 8.0)
    )
    assert far > near > 0


def test_exercises_cost_in_proportion_to_their_count_and_more_with_solutions() -> None:
    for kind in TYPES:
        one, ten = (solver.exercise_work(kind, n, False).seconds for n in (1, 10))
        assert ten == pytest.approx(10 * one) and one > 0
        assert solver.exercise_work(kind, 1, True).seconds >= one
        assert solver.exercise_work(kind, 1, True, export=True).seconds > one

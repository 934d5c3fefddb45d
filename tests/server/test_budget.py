"""Bounded cost (issue 15): every request's work and response size is checked after parsing and
before any work, and answered ``limit_exceeded`` (413) with the product and the limit.

The refusals must come from the budget (their detail states the product), not from a time
limit: each case here would run for tens of seconds or build gigabytes otherwise. Requests just
inside the limits still answer 200.
"""

from __future__ import annotations

import copy
import json
import math
import re
from pathlib import Path
from typing import Any

import pytest
import sympy
from fastapi.testclient import TestClient

import solver
from server import budget
from server.app import app
from server.routes.presets import ALL_PRESETS, build_any_preset
from server.settings import Settings
from solver.analysis.work_estimate import BALANCE_COST, SOLUTION_COST, SYNTHESIS_COST
from solver.errors import LimitExceeded
from solver.exercises import TYPES
from solver.model.laws import MAX_COMPOSITION, composition_depth, parse_time_law
from solver.model.scene import LinkageScene
from solver.position.assembly import MAX_DENSE_SAMPLES
from tests.scenes import triads
from tests.server.test_errors import FOUR_BAR, assert_problem

client = TestClient(app, raise_server_exceptions=False)
EXAMPLES = Path(__file__).parents[2] / "server" / "examples"
CARRIER = json.loads((EXAMPLES / "S003-T2-rotating-carrier.json").read_text())
ALL = ["position", "velocity", "acceleration", "poles", "components"]


def refused(path: str, body: dict[str, Any]) -> str:
    detail: str = assert_problem(client.post(path, json=body), 413, "limit_exceeded")["detail"]
    return detail


def four_bar_with_coupler_points(count: int) -> dict[str, Any]:
    scene = copy.deepcopy(FOUR_BAR)
    for i in range(count):
        name = f"K{i}"
        scene["points"][name] = [0.5 + 0.001 * i, 1.2]
        scene["links"]["coupler"]["points"].append(name)
    return scene


def test_the_issues_2_5_gb_sweep_is_refused_with_the_product() -> None:
    scene = four_bar_with_coupler_points(196)
    body = {"scene": scene, "samples": 100_000, "quantities": ALL}
    detail = refused("/api/v1/sweep", body)
    entries = 200 + 4 + 4  # points, links, joints
    assert f"100000 samples x {entries} points" in detail
    assert f"x 5 quantities = {100_000 * entries * 5:,}" in detail
    assert f"limit of {budget.MAX_SWEEP_VALUES:,}" in detail


@pytest.mark.slow
def test_a_sweep_just_inside_the_response_budget_answers() -> None:
    entries = 4 + 4 + 4
    samples = budget.MAX_SWEEP_VALUES // (entries * 5)
    body = {"scene": FOUR_BAR, "samples": samples, "quantities": ALL}
    response = client.post("/api/v1/sweep", json=body)
    assert response.status_code == 200, response.text[:300]
    assert response.json()["samples"] == samples
    body["samples"] = samples + 1
    assert "more than the limit" in refused("/api/v1/sweep", body)


def test_newton_work_of_a_sweep_is_bounded_at_half_its_time_limit() -> None:
    """One group of 32 links by Newton-Raphson costs 32 x (2.9 + 0.32 x 32) us = 420.48 us per
    sample, over (samples + 260 + 19 x turn) samples, within /sweep's 10 s / 2 = 5 s. The crank
    turns 2 t + 0.25 t^2 rad: 140 rad by t = 20 s, 480 by 40 s. By hand: 3,000 samples over [0,
    20] s: (3,000 + 260 + 2,660) x 420.48 us = 2.489 s, allowed; over [0, 40] s: 32 x (3,000 +
    260 + 9,120) = 396,160 link-samples x 13.14 us = 5.2055 s, refused."""
    scene = solver.read_scene(triads(8)).scene
    assert isinstance(scene, LinkageScene)
    assert budget.sweep(scene, 3000, None, [0.0, 20.0]) == pytest.approx(2.4892, rel=1e-4)
    body = {"scene": triads(8), "samples": 3000, "time_range": [0, 40]}
    detail = refused("/api/v1/sweep", body)
    assert "32 links solved by Newton-Raphson x (3000 samples over the time range + 260" in detail
    assert "+ 480 rad from the drawn pose x 19) = 396,160 link-samples" in detail
    assert "x (2.9 us + 0.32 us x 32 links per group) = 5.206 s of estimated work" in detail
    assert "more than the limit of 5 s (/api/v1/sweep's time limit of 10 s / safety factor 2)" in (
        detail
    )


def test_a_newton_group_past_the_measured_sizes_is_refused() -> None:
    detail = refused("/api/v1/sweep", {"scene": triads(9), "samples": 20})
    assert "a group of 36 links solved together by Newton-Raphson" in detail
    assert "more than the limit of 32 links" in detail


def test_newton_work_of_a_time_sweep_counts_the_turn_from_the_drawn_pose() -> None:
    """omega 2, alpha 0.5: the crank turns 2 + 0.25 = 2.25 rad by t = 1 s; 4 x (20,000 + 260 +
    2.25 x 19) = 81,211 link-samples x (2.9 + 0.32 x 4) us = 0.33946 s."""
    scene = solver.read_scene(triads(1)).scene
    assert isinstance(scene, LinkageScene)
    work = solver.estimate_work(scene, 20_000, None, time_range=[0, 1]).newton
    assert work is not None
    assert work.link_samples == pytest.approx(81_211)
    assert work.seconds == pytest.approx(81_211 * 4.18e-6)


def test_continuation_to_a_far_pose_is_bounded() -> None:
    """An angle law at t = 1e5 s puts the crank 1e8 rad from the drawn pose, which the
    continuation would walk; /analyze allows 2 s / 2 = 1 s: 4 x (1 + 260 + 19 x turn) x (2.9 +
    0.32 x 4) us <= 1 s for a turn up to (1 / 16.72e-6 - 261) / 19 = 3,134.0 rad."""
    scene = triads(1)
    scene["drivers"] = [{"link": "crank", "angle_law": "1000*t"}]
    scene["time"] = 1e5
    for path in ("/api/v1/analyze", "/api/v1/solution"):
        assert "1e+08 rad from the drawn pose" in refused(path, {"scene": scene})
    scene["time"] = 3.1340  # 3,134.0 rad: inside
    budget.instant(solver.read_scene(scene).scene)  # type: ignore[arg-type]
    scene["time"] = 3.1342  # 3,134.2 rad: outside
    assert "3134 rad from the drawn pose" in refused("/api/v1/analyze", {"scene": scene})


def test_a_triad_at_its_drawn_pose_still_answers() -> None:
    response = client.post("/api/v1/analyze", json={"scene": triads(1)})
    assert response.status_code == 200, response.text[:300]


def test_an_event_search_over_too_many_oscillations_is_refused() -> None:
    scene = copy.deepcopy(CARRIER)
    scene["moving_points"][0]["s_law"] = "0.1*sin(1000*t)"
    event = {"moving_point": "M", "reaches": "S", "t_max": 60.0}
    detail = refused("/api/v1/events", {"scene": scene, "event": event})
    # 1000 rad/s is 159.155 Hz: 60 s x 159.155 Hz = 9549 oscillations (to one sign change)
    found = re.search(r"= 60 s x ([0-9.]+) Hz = ([0-9,]+) oscillations", detail)
    assert found is not None, detail
    assert float(found[1]) == pytest.approx(1000 / (2 * math.pi), abs=0.01)
    assert abs(int(found[2].replace(",", "")) - 9549) <= 1
    assert f"limit of {budget.MAX_OSCILLATIONS:,}" in detail


def test_an_unresolvable_frequency_is_refused_as_at_least() -> None:
    scene = copy.deepcopy(CARRIER)
    scene["moving_points"][0]["s_law"] = "0.1*sin(1000000*t)"
    event = {"moving_point": "M", "reaches": "S", "t_max": 60.0}
    assert "at least" in refused("/api/v1/events", {"scene": scene, "event": event})


def test_a_slow_event_search_still_answers() -> None:
    event = {"moving_point": "M", "reaches": "S", "t_max": 60.0}
    response = client.post("/api/v1/events", json={"scene": CARRIER, "event": event})
    assert response.status_code in (200, 422), response.text  # found, or no_event
    assert response.json().get("code", "no_event") == "no_event" or "time" in response.json()


@pytest.mark.parametrize(
    ("law", "depth"),
    [
        ("6*pi*t^2", 1),
        ("2*t - 0.3*t^2", 1),
        ("0.1*sin(3*t)", 1),
        ("sin(t)^2", 2),
        ("t^t^t", 2),
        ("exp(-t)*sin(3*t)", 1),
        ("sqrt(1 + sin(t)^2)", 3),
        ("5", 0),
    ],
)
def test_composition_depth(law: str, depth: int) -> None:
    assert composition_depth(parse_time_law(law).expression) == depth
    assert composition_depth(sympy.sympify(0)) == 0


@pytest.mark.parametrize(
    "law",
    [
        "sin(" * 49 + "t" + ")" * 49,  # 3 to 4 s to differentiate
        "^".join(["t"] * 51),  # 53 s
        "exp( " * 40 + "t" + " )" * 40,  # spaces: a new text for the cache each time
    ],
)
def test_deeply_composed_laws_are_refused_before_differentiation(law: str) -> None:
    with pytest.raises(LimitExceeded, match=f"more than the limit of {MAX_COMPOSITION}"):
        parse_time_law(law)
    scene = copy.deepcopy(CARRIER)
    scene["moving_points"][0]["s_law"] = law
    assert "nests" in refused("/api/v1/analyze", {"scene": scene})


def test_the_composition_limit_itself_is_accepted() -> None:
    law = "sin(" * MAX_COMPOSITION + "t" + ")" * MAX_COMPOSITION
    assert composition_depth(parse_time_law(law).expression) == MAX_COMPOSITION


def test_a_time_sweeps_dense_grid_past_its_limit_is_refused_before_any_work() -> None:
    """Issue 28: the driver law 1e12 t^3 over [0, 1e6] s turns 1e30 rad; its dense grid's count
    (ceil(step / (pi/8)) per interval) overflowed an integer into a negative repeat count (500).
    The estimate sees it: refused with the drivers' turn and MAX_DENSE_SAMPLES."""
    scene = json.loads((EXAMPLES / "S003-T1-translating-carrier.json").read_text())
    scene["drivers"][0]["angle_law"] = "1e12*t^3"
    parsed = solver.read_scene(scene).scene
    assert isinstance(parsed, LinkageScene)
    with pytest.raises(LimitExceeded, match=r"the drivers turn 1e\+30 rad"):
        budget.sweep(parsed, 10, None, [0.0, 1e6])  # the budget only counts
    body = {"scene": scene, "samples": 10, "time_range": [0.0, 1e6]}
    detail = refused("/api/v1/sweep", body)
    assert "the drivers turn 1e+30 rad" in detail
    assert f"more than {MAX_DENSE_SAMPLES}" in detail


# --- the whole request's estimate (issue 28) ----------------------------------------------------

S000_T1 = json.loads((EXAMPLES / "S000-T1.json").read_text())
S003_T1 = json.loads((EXAMPLES / "S003-T1-translating-carrier.json").read_text())


def test_the_closed_form_work_of_a_revolution() -> None:
    """S000-T1: three closed-form groups (the dyad and two points placed on known links) x
    (360 + 360) samples x 4.6 us = 9.936 ms; no turn from the drawn pose."""
    estimate = solver.estimate_work(solver.parse_scene(S000_T1), 360)
    assert estimate.newton is None
    assert estimate.closed_form is not None
    assert (estimate.closed_form.groups, estimate.closed_form.branch_groups) == (3, 1)
    assert estimate.seconds == pytest.approx(3 * 720 * 4.6e-6)


def test_the_drivers_turn_is_charged_per_dyad() -> None:
    """S003-T1's crank turns 0.5236 t^3 rad: 8 x 0.5236 = 4.18879 rad by t = 2 s; 3 x (100 +
    360) x 4.6 us + 1 dyad x 4.18879 rad x 1.9 ms."""
    estimate = solver.estimate_work(solver.parse_scene(S003_T1), 100, None, time_range=[0.0, 2.0])
    turn = 0.5235987755982988 * 8
    assert estimate.seconds == pytest.approx(3 * 460 * 4.6e-6 + turn * 1.9e-3, rel=1e-3)
    assert "4.18879 rad the drivers turn from the drawn pose x 1.9 ms" in estimate.reckoning


def test_a_time_sweep_past_the_whole_budget_is_refused_with_its_turn() -> None:
    """The same over [0, 60] s: 113,097 rad x 1.9 ms = 214.9 s of /sweep's 5 s."""
    body = {"scene": S003_T1, "samples": 100, "time_range": [0, 60]}
    detail = refused("/api/v1/sweep", body)
    assert "113,097 rad the drivers turn" in detail and "= 214.9 s" in detail
    assert "more than the limit of 5 s (/api/v1/sweep's time limit of 10 s" in detail


def test_an_event_on_the_carrier_is_not_charged_the_walk() -> None:
    """M reaching S, a point of its own carrier, is searched along M's path: the turn is not
    walked (the contract test's event of S003-T1 is answered)."""
    scene = solver.parse_scene(S003_T1)
    on_carrier = solver.estimate_work(scene, event=("M", 60.0), reaches="S")
    off_carrier = solver.estimate_work(scene, event=("M", 60.0), reaches="O1")
    assert on_carrier.closed_form is not None and on_carrier.closed_form.turn == 0.0
    assert off_carrier.closed_form is not None
    assert off_carrier.closed_form.turn == pytest.approx(0.5235987755982988 * 60**3)


def test_exercises_cost_count_times_their_types_cost() -> None:
    assert solver.exercise_work("flywheel", 20, True).seconds == pytest.approx(20 * 0.06)
    assert solver.exercise_work("slider_crank", 100, False).seconds == pytest.approx(0.19)
    # a type not listed: the costliest with its solution (moving_point, 0.18 s), alone 4 ms
    assert solver.exercise_work("not-a-type", 1, False).seconds == pytest.approx(0.004)
    export = solver.exercise_work("flywheel", 10, True, export=True)
    assert export.seconds == pytest.approx(10 * (0.06 + 0.017))
    assert "10 exercises x 77 ms with its worked solution and its sheet (flywheel)" in (
        export.reckoning
    )
    for kind in TYPES:  # a hundred, the most allowed, fit (the costliest alone: 39 ms each)
        assert budget.exercises(kind, 100, False, "/api/v1/exercises") <= 5.0
    with pytest.raises(LimitExceeded, match="129 exercises x 39 ms each"):
        budget.exercises("synthesis_two_positions", 129, False, "/api/v1/exercises")
    detail = refused(
        "/api/v1/exercises",
        {"type": "flywheel", "difficulty": "challenging", "count": 84, "with_solutions": True},
    )
    assert "84 exercises x 60 ms with its worked solution (flywheel) = 5.04 s" in detail


def test_the_budget_follows_a_raised_time_limit_but_not_a_lowered_one() -> None:
    assert budget.limit("/api/v1/sweep") == 5.0
    for configured, allowed in ((40.0, 20.0), (1.0, 5.0)):
        token = budget.SETTINGS.set(Settings(time_limits={"/api/v1/sweep": configured}))
        try:
            assert budget.limit("/api/v1/sweep") == allowed
        finally:
            budget.SETTINGS.reset(token)


# --- every route's costliest legal request (issue 28) -------------------------------------------

FAR = triads(1)
FAR["drivers"] = [{"link": "crank", "angle_law": "1000*t"}]
FAR["time"] = 1e5  # the crank 1e8 rad from the drawn pose: the costliest instant a law may ask
FLYWHEELS = {"type": "flywheel", "difficulty": "challenging", "count": 100, "with_solutions": True}
REFUSED = {  # the costliest legal request of each route whose cost grows with its request
    ("POST", "/api/v1/analyze"): {"scene": FAR},
    ("POST", "/api/v1/solution"): {"scene": FAR},
    ("POST", "/api/v1/solution.html"): {"scene": FAR},
    ("POST", "/api/v1/sweep"): {"scene": triads(8), "samples": 100_000},
    ("POST", "/api/v1/events"): {
        "scene": S003_T1,
        "event": {"moving_point": "M", "reaches": "O1", "t_max": 1e6},
    },
    ("POST", "/api/v1/exercises"): FLYWHEELS,
    ("POST", "/api/v1/exercises/export"): {**FLYWHEELS, "format": "html"},
}
# The routes whose cost is bounded by what a request may ask: one exercise, a balancing, a
# preset's instant, the list of types.
BOUNDED = {
    ("GET", "/api/v1/exercises/{exercise_id}"),
    ("POST", "/api/v1/exercises/check"),
    ("POST", "/api/v1/balance"),
    ("GET", "/api/v1/solution.html"),
    ("GET", "/api/v1/exercises/types"),
    ("POST", "/api/v1/synthesis"),
}


def test_every_route_answered_in_a_worker_is_covered_here() -> None:
    """The operations answered in the worker pool are those that declare 429 (one client's
    share of slow work) in the OpenAPI document."""
    routes = {
        (method.upper(), path)
        for path, item in app.openapi()["paths"].items()
        for method, operation in item.items()
        if "429" in operation["responses"]
    }
    assert routes == set(REFUSED) | BOUNDED


@pytest.mark.parametrize(("method", "path"), sorted(REFUSED))
def test_the_costliest_legal_request_is_refused_before_any_work_with_its_numbers(
    method: str, path: str
) -> None:
    """Refused by the budget (413 with the product and the limit), not by a time limit."""
    detail = refused(path, REFUSED[(method, path)])
    stated = re.search(r" x .* = ([0-9,.e+]+)[ ,].*more than the limit of ([0-9,.]+)", detail)
    assert stated is not None, detail


def test_the_bounded_routes_costliest_requests_are_within_their_limits() -> None:
    """One exercise of the costliest type with its worked solution (GET by id; a check needs
    its key alone), a balancing, a synthesis and every preset's worked solution fit."""
    for kind in TYPES:
        assert solver.exercise_work(kind, 1, True).seconds <= budget.limit("/api/v1/exercises")
    assert budget.limit("/api/v1/balance") >= BALANCE_COST
    assert budget.limit("/api/v1/synthesis") >= SYNTHESIS_COST
    for name in ALL_PRESETS:
        scene = build_any_preset(name, {})
        cost = budget.read_instant(scene, False, "/api/v1/solution.html", SOLUTION_COST)
        assert cost <= budget.limit("/api/v1/solution.html")

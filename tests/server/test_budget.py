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

from server import budget
from server.app import app
from solver.errors import LimitExceeded
from solver.laws import MAX_COMPOSITION, composition_depth, parse_time_law
from tests.server.test_errors import FOUR_BAR, assert_problem
from tests.solver.test_newton import TRIAD

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


def triads(count: int) -> dict[str, Any]:
    """``count`` copies of the triad of tests/solver/test_newton.py hung from one crank pin A:
    one Newton-Raphson group of 4 x count links."""
    points: dict[str, list[float]] = {"O": [0, 0], "A": [0.3, 0.2]}
    links: dict[str, Any] = {"crank": {"points": ["O", "A"]}}
    ground = ["O"]
    joints = [{"type": "revolute", "point": "O", "links": ["ground", "crank"]}]
    for i in range(count):
        n = {p: f"{p}_{i}" for p in ("P1", "P2", "P3", "G2", "G3", "T", "L1", "L2", "L3")}
        for p in ("P1", "P2", "P3", "G2", "G3"):
            x, y = TRIAD["points"][p]
            points[n[p]] = [x, y + 3.0 * i]
        ground += [n["G2"], n["G3"]]
        links[n["T"]] = {"points": [n["P1"], n["P2"], n["P3"]]}
        links[n["L1"]] = {"points": ["A", n["P1"]]}
        links[n["L2"]] = {"points": [n["G2"], n["P2"]]}
        links[n["L3"]] = {"points": [n["G3"], n["P3"]]}
        for point, pair in (
            ("A", ("crank", "L1")),
            ("P1", ("L1", "T")),
            ("P2", ("T", "L2")),
            ("P3", ("T", "L3")),
            ("G2", ("L2", "ground")),
            ("G3", ("L3", "ground")),
        ):
            named = [n.get(link, link) for link in pair]
            joints.append({"type": "revolute", "point": n.get(point, point), "links": named})
    links["ground"] = {"points": ground, "ground": True}
    return {
        "kind": "linkage",
        "points": points,
        "links": links,
        "joints": joints,
        "drivers": [{"link": "crank", "omega": 2.0, "alpha": 0.5}],
    }


def test_the_issues_2_5_gb_sweep_is_refused_with_the_product() -> None:
    scene = four_bar_with_coupler_points(196)
    body = {"scene": scene, "samples": 100_000, "quantities": ALL}
    detail = refused("/api/v1/sweep", body)
    entries = 200 + 4 + 4  # points, links, joints
    assert f"100000 samples x {entries} points" in detail
    assert f"x 5 quantities = {100_000 * entries * 5:,}" in detail
    assert f"limit of {budget.MAX_SWEEP_VALUES:,}" in detail


def test_a_sweep_just_inside_the_response_budget_answers() -> None:
    entries = 4 + 4 + 4
    samples = budget.MAX_SWEEP_VALUES // (entries * 5)
    body = {"scene": FOUR_BAR, "samples": samples, "quantities": ALL}
    response = client.post("/api/v1/sweep", json=body)
    assert response.status_code == 200, response.text[:300]
    assert response.json()["samples"] == samples
    body["samples"] = samples + 1
    assert "more than the limit" in refused("/api/v1/sweep", body)


def test_newton_work_of_a_sweep_is_bounded() -> None:
    detail = refused("/api/v1/sweep", {"scene": triads(8), "samples": 20})
    work = 32 * (20 + budget.FEASIBLE_RANGE_SEARCH)
    assert f"32 links solved by Newton-Raphson x {20 + budget.FEASIBLE_RANGE_SEARCH}" in detail
    assert f"= {work:,} link-samples" in detail
    assert f"limit of {budget.MAX_NEWTON_WORK:,}" in detail


def test_newton_work_of_a_time_sweep_is_bounded() -> None:
    body = {"scene": triads(1), "samples": 20_000, "time_range": [0, 1]}
    assert "4 links solved by Newton-Raphson x 20000 samples" in refused("/api/v1/sweep", body)


def test_continuation_to_a_far_pose_is_bounded() -> None:
    """An angle law at t = 1e5 s puts the crank 1e8 rad from the drawn pose: Newton groups
    would walk there in 5-degree continuation steps."""
    scene = triads(1)
    scene["drivers"] = [{"link": "crank", "angle_law": "1000*t"}]
    scene["time"] = 1e5
    for path in ("/api/v1/analyze", "/api/v1/solution"):
        assert "continuation steps to the pose" in refused(path, {"scene": scene})


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

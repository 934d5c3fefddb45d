"""POST /api/v1/synthesis (issue 26) over HTTP: the body is ``solver.synthesize``'s, its scene
goes straight back into /analyze and /sweep, the refusals are problem+json with the reason, and
the route is published in OpenAPI with the three task shapes."""

from __future__ import annotations

import math
from typing import Any

import pytest
from fastapi.testclient import TestClient

import solver
from tests.server.test_contract import check as check_schema

MOTION = {
    "task": "motion",
    "positions": [
        {"point": [0, 0], "angle_deg": 0},
        {"point": [1, 0.5], "angle_deg": 30},
        {"point": [2, 0.3], "angle_deg": 60},
    ],
    "moving_pivots": [[-0.5, -0.2], [0.5, -0.3]],
}
FUNCTION = {
    "task": "function",
    "function": "x^2",
    "x_range": [1, 2],
    "input_range_deg": [30, 120],
    "output_range_deg": [60, 150],
    "precision_points": 3,
}
QUICK_RETURN = {"task": "quick_return", "time_ratio": 1.25, "rocker_length": 0.1, "swing_deg": 60}
TWO_POSITIONS = {
    "task": "motion",
    "positions": [{"point": [0, 0], "angle_deg": 0}, {"point": [1, 0.2], "angle_deg": 25}],
    "moving_pivots": [[-0.4, 0.1], [0.5, 0.2]],
    "bisector_offsets": [0.7, -0.3],
}


@pytest.mark.parametrize(
    "task",
    [MOTION, FUNCTION, QUICK_RETURN, TWO_POSITIONS],
    ids=["motion", "function", "quick_return", "bisector_offsets"],
)
def test_the_body_is_the_libraries_and_its_scene_is_analysed(
    client: TestClient, task: dict[str, Any]
) -> None:
    response = client.post("/api/v1/synthesis", json=task)
    assert response.status_code == 200, response.text
    body = response.json()
    assert body == solver.synthesize(task).as_dict()
    assert set(body["scene"]["links"]) == {"ground", "crank", "coupler", "rocker"}
    assert {"A", "B", "C", "D"} <= set(body["scene"]["points"])
    assert ("P" in body["scene"]["points"]) is (task["task"] == "motion")
    assert body["scene"]["drivers"][0]["link"] == "crank"
    for check in body["checks"]:
        assert {"driver_angle_deg", "error"} <= set(check)
    assert set(body["defects"]) >= {"branch", "order", "grashof"}
    assert isinstance(body["warnings"], list)
    # The scene is a scene-v1 linkage: /analyze at each check's crank angle, and /sweep.
    for check in body["checks"]:
        scene = {**body["scene"]}
        scene["drivers"] = [{**scene["drivers"][0], "angle_deg": check["driver_angle_deg"]}]
        analysed = client.post("/api/v1/analyze", json={"scene": scene, "quantities": ["position"]})
        assert analysed.status_code == 200
    swept = client.post("/api/v1/sweep", json={"scene": body["scene"], "samples": 90})
    assert swept.status_code == 200
    assert swept.json()["feasible"] is (not body["defects"]["grashof"])


def test_the_motion_checks_over_http(client: TestClient) -> None:
    body = client.post("/api/v1/synthesis", json=MOTION).json()
    for check, position in zip(body["checks"], MOTION["positions"], strict=True):
        assert check["reached"]
        assert math.dist(check["point"], position["point"]) < 1e-9


@pytest.mark.parametrize(
    ("task", "code", "words"),
    [
        ({**QUICK_RETURN, "time_ratio": 0.5}, "invalid_scene", "at least 1"),
        ({**FUNCTION, "function": "x^2 + y"}, "invalid_expression", "unknown name 'y'"),
        ({**MOTION, "moving_pivots": [[0, 1], [1, 1]], "positions": [
            {"point": [0, 0], "angle_deg": 0}, {"point": [1, 0], "angle_deg": 0},
            {"point": [2, 0], "angle_deg": 0}]}, "invalid_scene", "lie on one line"),
        ({**MOTION, "extra": 1}, "invalid_scene", "extra"),
        ({"task": "design"}, "invalid_scene", "task"),
        ({**TWO_POSITIONS, "bisector_offsets": [0.1, 0.2, 0.3]}, "invalid_scene",
         "bisector_offsets"),
        ({**MOTION, "bisector_offsets": [0.1, 0.2]}, "invalid_scene",
         "the free choice of two positions only"),
    ],
)  # fmt: skip
def test_refusals_are_problems_with_the_reason(
    client: TestClient, task: dict[str, Any], code: str, words: str
) -> None:
    response = client.post("/api/v1/synthesis", json=task)
    assert response.status_code == 422
    assert response.headers["content-type"].startswith("application/problem+json")
    problem = response.json()
    assert problem["code"] == code
    assert words in problem["detail"]


@pytest.mark.parametrize(
    "task",
    [MOTION, FUNCTION, QUICK_RETURN, {**QUICK_RETURN, "time_ratio": 0.5}],
    ids=["motion", "function", "quick_return", "refused"],
)
def test_responses_satisfy_the_published_schema(client: TestClient, task: dict[str, Any]) -> None:
    openapi = client.get("/api/v1/openapi.json").json()
    check_schema(openapi, "/synthesis", "post", client.post("/api/v1/synthesis", json=task))


def test_published_in_openapi(client: TestClient) -> None:
    spec = client.get("/api/v1/openapi.json").json()
    operation = spec["paths"]["/api/v1/synthesis"]["post"]
    assert "synthesis" in operation["tags"]
    assert {"200", "422", "413", "503"} <= set(operation["responses"])
    text = str(spec["components"]["schemas"])
    for name in ("MotionTask", "FunctionTask", "QuickReturnTask", "SynthesisResponse"):
        assert name in text
    motion = spec["components"]["schemas"]["MotionTask"]["properties"]
    assert "positive to the left of B1 -> B2" in str(motion["bisector_offsets"])

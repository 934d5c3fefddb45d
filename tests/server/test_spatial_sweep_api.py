"""POST /api/v1/sweep with ``time_range`` for a spatial chain: the body is the library's, the
response budget applies (413 with the product), and bad input is problem+json 422."""

from __future__ import annotations

import json
from pathlib import Path
from typing import Any

import numpy as np
from fastapi.testclient import TestClient

import solver
from server import budget
from server.app import app
from tests.server.test_errors import assert_problem

client = TestClient(app, raise_server_exceptions=False)
EXAMPLES = Path(__file__).parents[2] / "server" / "examples"
ARM: dict[str, Any] = json.loads((EXAMPLES / "S002-spatial-arm.json").read_text())
ALL = ["position", "velocity", "acceleration"]


def sweep(**extra: Any) -> Any:
    return client.post("/api/v1/sweep", json={"scene": ARM, **extra})


def test_time_sweep_of_the_arm_is_the_librarys() -> None:
    response = sweep(samples=7, time_range=[0, 2], quantities=ALL)
    assert response.status_code == 200, response.text
    body = response.json()
    expected = solver.sweep_time(ARM, (0, 2), 7, ALL).as_dict()
    np.testing.assert_array_equal(
        body["points"]["A"]["acceleration"], expected["points"]["A"]["acceleration"]
    )
    np.testing.assert_array_equal(body["bodies"]["3"]["omega"], expected["bodies"]["3"]["omega"])
    assert body["time"] == list(np.linspace(0, 2, 7)) and body["samples"] == 7
    assert [j["name"] for j in body["joints"]] == [j["name"] for j in ARM["joints"]]
    first = solver.analyze(ARM, ALL)  # t = 0 is the instant
    assert body["points"]["B"]["velocity"][0] == list(first["points"]["B"]["velocity"])


def test_the_response_budget_applies() -> None:
    entries = len(ARM["points"]) + 2 * len(ARM["joints"])
    samples = budget.MAX_SWEEP_VALUES // (entries * len(ALL)) + 1
    response = sweep(samples=samples, time_range=[0, 1], quantities=ALL)
    detail = assert_problem(response, 413, "limit_exceeded")["detail"]
    product = samples * entries * len(ALL)
    assert f"= {product:,}" in detail and f"{budget.MAX_SWEEP_VALUES:,}" in detail


def test_bad_input_is_problem_json() -> None:
    for extra, code in [
        ({"time_range": [1, 0]}, "invalid_scene"),
        ({"time_range": [0]}, "invalid_scene"),
        ({"time_range": [0, 1], "quantities": ["forces"]}, "invalid_scene"),
        ({"time_range": [0, 1], "quantities": ["speed"]}, None),  # the framework's validation
        ({"time_range": [0, "soon"]}, None),
        ({"samples": 10}, "invalid_scene"),  # no time range: a revolution needs a linkage
    ]:
        response = sweep(**extra)
        assert response.status_code == 422, (extra, response.text)
        assert response.headers["content-type"] == "application/problem+json"
        if code is not None:
            assert response.json()["code"] == code, extra
    bad = json.loads(json.dumps(ARM))
    bad["joints"][1]["axis"] = [0, 0, 0]
    response = client.post("/api/v1/sweep", json={"scene": bad, "time_range": [0, 1]})
    assert "zero vector" in assert_problem(response, 422, "invalid_scene")["detail"]

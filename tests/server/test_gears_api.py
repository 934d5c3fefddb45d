"""Gear trains over HTTP (issue 25, docs/GEARS.md): /analyze with and without input_torque,
/sweep with time_range, and every refusal as problem+json (invalid_scene, limit_exceeded),
never a 500 or a NaN."""

from __future__ import annotations

import copy
import json
from pathlib import Path
from typing import Any

import pytest
from fastapi.testclient import TestClient

import solver
from server import budget

EXAMPLE = json.loads(
    (
        Path(__file__).resolve().parents[2] / "server" / "examples" / "G001-planetary.json"
    ).read_text()
)
PROBLEM = "application/problem+json"


def problem(response: Any, status: int, code: str, *parts: str) -> str:
    assert response.status_code == status, response.text
    assert response.headers["content-type"] == PROBLEM
    body = response.json()
    assert body["code"] == code
    for part in parts:
        assert part in body["detail"], body["detail"]
    detail: str = body["detail"]
    return detail


def test_the_issues_example(client: TestClient) -> None:
    """Sun 20, planet 30, ring 80 fixed, sun at 100 rad/s: arm 100 x 20/100 = 20 rad/s, planet
    20 + (100 - 20)(-20/30) = -33 1/3 rad/s; with 12 N m on the sun the ring takes 12 x 80/20
    = 48 N m and the arm -(12 + 48) = -60 N m."""
    response = client.post("/api/v1/analyze", json={"scene": EXAMPLE})
    assert response.status_code == 200, response.text
    body = response.json()
    members = body["members"]
    assert members["arm"]["omega"] == pytest.approx(20.0, rel=1e-12)
    assert members["planet"]["omega"] == pytest.approx(-100.0 / 3.0, rel=1e-12)
    assert members["planet"]["omega_relative"] == pytest.approx(-160.0 / 3.0, rel=1e-12)
    assert members["arm"]["train_value"] == pytest.approx(0.2, rel=1e-12)
    assert [m["pitch_line_speed"] for m in body["meshes"]] == [pytest.approx(1.6)] * 2
    assert "torque" not in members["sun"]
    torqued = client.post(
        "/api/v1/analyze", json={"scene": EXAMPLE, "input_torque": {"sun": 12.0}}
    ).json()["members"]
    assert [torqued[n]["torque"] for n in ("sun", "planet", "ring", "arm")] == pytest.approx(
        [12.0, 0.0, 48.0, -60.0], rel=1e-12
    )
    assert body == solver.analyze(EXAMPLE).as_dict()


def test_the_sweep_over_time(client: TestClient) -> None:
    request = {"scene": EXAMPLE, "time_range": [0.0, 0.1], "samples": 5}
    body = client.post("/api/v1/sweep", json=request).json()
    assert body["time"] == pytest.approx([0.0, 0.025, 0.05, 0.075, 0.1])
    assert body["members"]["arm"]["angle"] == pytest.approx([0.0, 0.5, 1.0, 1.5, 2.0])
    assert len(body["members"]["planet"]["centre"]) == 5
    without = client.post("/api/v1/sweep", json={"scene": EXAMPLE})
    problem(without, 422, "invalid_scene", "time_range")


@pytest.mark.parametrize(
    ("change", "parts"),
    [
        ({"inputs": {"sun": 100.0}}, ("2 degrees of freedom", "1 is given")),
        ({"inputs": {"sun": 1, "ring": 0, "arm": 1}}, ("3 are given",)),
        ({"meshes": [["sun", "planet"], ["planet", "ring"], ["ring", "sun"]]}, ("cannot touch",)),
        ({"shafts": [["sun", "arm"], ["arm", "ring"]]}, ("arm is already in shafts[0]",)),
        ({"mounts": {"planet": "cage"}}, ("'cage' is not a carrier",)),
        ({"gears": "many"}, ("gears",)),
        ({"meshes": None}, ("meshes",)),
    ],
)
def test_invalid_scenes_are_problems(
    client: TestClient, change: dict[str, Any], parts: tuple[str, ...]
) -> None:
    doc = copy.deepcopy(EXAMPLE) | change
    for path, extra in (("/analyze", {}), ("/sweep", {"time_range": [0, 1]}), ("/solution", {})):
        problem(client.post(f"/api/v1{path}", json={"scene": doc, **extra}), 422, "invalid_scene")
    problem(client.post("/api/v1/analyze", json={"scene": doc}), 422, "invalid_scene", *parts)


def test_an_infinite_speed_is_refused_not_answered_as_nan(client: TestClient) -> None:
    text = json.dumps({"scene": EXAMPLE}).replace('"sun": 100.0', '"sun": 1e400')
    response = client.post(
        "/api/v1/analyze", content=text, headers={"Content-Type": "application/json"}
    )
    assert (
        response.status_code == 422
        and "NaN" not in response.text
        and "Infinity" not in (response.text)
    )


def test_pitch_circles_and_internal_pairs(client: TestClient) -> None:
    doc = copy.deepcopy(EXAMPLE)
    doc["gears"]["ring"]["teeth"] = 100
    problem(
        client.post("/api/v1/analyze", json={"scene": doc}),
        422,
        "invalid_scene",
        "0.002 (100 - 30) / 2 = 0.07 m",
    )
    doc["gears"]["planet"]["internal"] = True
    problem(client.post("/api/v1/analyze", json={"scene": doc}), 422, "invalid_scene", "both")


def test_torque_problems(client: TestClient) -> None:
    bad = client.post("/api/v1/analyze", json={"scene": EXAMPLE, "input_torque": {"arm": 1.0}})
    problem(bad, 422, "invalid_scene", "'arm' is not an input")
    linkage = json.loads(
        (Path(__file__).resolve().parents[2] / "server" / "examples" / "S000-T1.json").read_text()
    )
    wrong = client.post("/api/v1/analyze", json={"scene": linkage, "input_torque": {"A": 1.0}})
    problem(wrong, 422, "invalid_scene", "gear_train")


def test_the_budget_bounds_a_sweep(client: TestClient) -> None:
    """4 angles + the planet's centre (2) per sample: 100,000 samples are 600,000 values."""
    request = {"scene": EXAMPLE, "time_range": [0, 1], "samples": 100_000}
    problem(
        client.post("/api/v1/sweep", json=request),
        413,
        "limit_exceeded",
        "100000 samples x 6 member angles and planet centre coordinates x 1 quantities",
        f"{budget.MAX_SWEEP_VALUES:,}",
    )
    estimate = solver.estimate_work(solver.parse_scene(EXAMPLE), 100)
    assert estimate.values == 600

"""Gear-train presets over HTTP (issue 25): listed with ``?family=gear_trains`` (the default
listing stays the linkages'), built by POST /presets/{name}, answered by /analyze."""

from __future__ import annotations

import pytest
from fastapi.testclient import TestClient

from solver.teaching.gear_presets import GEAR_PRESETS
from solver.teaching.presets import PRESETS


def test_listing_by_family(client: TestClient) -> None:
    default = client.get("/api/v1/presets").json()["presets"]
    assert [p["name"] for p in default] == list(PRESETS)
    gears = client.get("/api/v1/presets", params={"family": "gear_trains"}).json()["presets"]
    assert [p["name"] for p in gears] == list(GEAR_PRESETS)
    teeth = next(q for q in gears[0]["parameters"] if q["name"] == "N2")
    assert (teeth["unit"], teeth["default"], teeth["minimum"]) == ("teeth", 20, 8)
    wrong = client.get("/api/v1/presets", params={"family": "spaceships"})
    assert wrong.status_code == 422
    assert wrong.headers["content-type"] == "application/problem+json"


def test_every_gear_preset_round_trips_through_analyze(client: TestClient) -> None:
    for name in GEAR_PRESETS:
        scene = client.post(f"/api/v1/presets/{name}", json={})
        assert scene.status_code == 200, scene.text
        answer = client.post("/api/v1/analyze", json={"scene": scene.json()})
        assert answer.status_code == 200, answer.text
        assert answer.json()["kind"] == "gear_train"


def test_the_differential_preset_with_values(client: TestClient) -> None:
    body = {"omega_left": 40.0, "omega_right": 0.0}
    scene = client.post("/api/v1/presets/differential", json=body).json()
    members = client.post("/api/v1/analyze", json={"scene": scene}).json()["members"]
    assert members["carrier"]["omega"] == pytest.approx(20.0, rel=1e-12)


def test_a_reverted_train_that_cannot_be_cut_on_one_module(client: TestClient) -> None:
    response = client.post("/api/v1/presets/compound_reverted", json={"N5": 40})
    assert response.status_code == 422
    assert response.json()["code"] == "invalid_scene"
    assert "N2 + N3 = N4 + N5" in response.json()["detail"]

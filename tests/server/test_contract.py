"""The API contract (issue 9): every 200 body is the solver result's ``as_dict()``, warnings and
``strict`` reach HTTP, and real responses satisfy the published OpenAPI schema."""

from __future__ import annotations

import json
from pathlib import Path
from typing import Any

import numpy as np
import pytest
from fastapi.testclient import TestClient

import solver

EXAMPLES = Path(__file__).resolve().parents[2] / "server" / "examples"
NAMES = sorted(path.stem for path in EXAMPLES.glob("*.json"))
SAMPLES = 24


def example(name: str) -> dict[str, Any]:
    data: dict[str, Any] = json.loads((EXAMPLES / f"{name}.json").read_text())
    return data


def plain(value: Any) -> Any:
    """A body as JSON would carry it: arrays as nested lists."""
    if isinstance(value, dict):
        return {k: plain(v) for k, v in value.items()}
    if isinstance(value, list):
        return [plain(v) for v in value]
    if isinstance(value, np.ndarray):
        return value.tolist()
    return value


def calls(name: str) -> list[tuple[str, dict[str, Any], solver.Result]]:
    """(endpoint, request, the library's result) for every endpoint that takes this scene."""
    doc = example(name)
    out: list[tuple[str, dict[str, Any], solver.Result]] = [
        ("/analyze", {"scene": doc}, solver.analyze(doc)),
        ("/analyze", {"scene": doc, "quantities": ["position"]}, solver.analyze(doc, ["position"])),
        ("/solution", {"scene": doc, "method": "loop"}, solver.solve(doc, "loop")),
    ]
    if doc["kind"] != "linkage":
        return out
    wanted = ["position", "velocity", "acceleration", "poles", "components"]
    if not doc.get("moving_points"):
        request = {"scene": doc, "samples": SAMPLES, "quantities": wanted}
        out.append(("/sweep", request, solver.sweep(doc, SAMPLES, wanted)))
    else:
        request = {"scene": doc, "samples": SAMPLES, "quantities": wanted, "time_range": [0, 1]}
        out.append(("/sweep", request, solver.sweep_time(doc, (0, 1), SAMPLES, wanted)))
        moving = doc["moving_points"][0]
        event = {"moving_point": moving["name"], "reaches": moving["path"]["start"]}
        try:
            result = solver.find_event(doc, moving["name"], moving["path"]["start"])
        except solver.NoEvent:
            return out
        out.append(("/events", {"scene": doc, "event": event}, result))
    return out


@pytest.mark.parametrize("name", NAMES)
def test_every_body_is_the_results_as_dict(client: TestClient, name: str) -> None:
    for endpoint, request, result in calls(name):
        response = client.post(f"/api/v1{endpoint}", json=request)
        assert response.status_code == 200, (endpoint, response.text)
        assert response.json() == plain(result.as_dict()), endpoint


def test_warnings_over_http_and_strict(client: TestClient) -> None:
    doc = example("S000-T2")
    doc["drivers"][0]["angle"] = 120
    warning = "drivers[0].angle is not a scene field; did you mean angle_deg?"
    for endpoint, extra in (("/analyze", {}), ("/sweep", {"samples": 8}), ("/solution", {})):
        body = client.post(f"/api/v1{endpoint}", json={"scene": doc, **extra}).json()
        assert body["warnings"] == [warning], endpoint
        strict = client.post(f"/api/v1{endpoint}", json={"scene": doc, "strict": True, **extra})
        assert strict.status_code == 422
        assert strict.headers["content-type"].startswith("application/problem+json")
        assert strict.json()["code"] == "invalid_scene" and warning in strict.json()["detail"]
    clean = client.post("/api/v1/analyze", json={"scene": example("S000-T2"), "strict": True})
    assert clean.status_code == 200 and clean.json()["warnings"] == []

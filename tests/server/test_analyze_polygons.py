"""POST /api/v1/analyze with the quantity ``polygons`` (an extension for the app's polygons: the
segments /solution carries, without writing the whole worked solution; docs/ARCHITECTURE.md).

The segments are checked against /solution's own and against the rigid-body formulas evaluated
here from the same answer's positions and rates (v_P - v_B = omega x r_BP, a_P - a_B =
alpha x r_BP - omega^2 r_BP), so a wrong segment, a wrong order or a body that is not /analyze's
fails.
"""

from __future__ import annotations

import json
from pathlib import Path
from typing import Any

import numpy as np
import pytest
from fastapi.testclient import TestClient

from solver.teaching.presets import PRESETS
from tests.server.test_contract import check

EXAMPLES = Path(__file__).resolve().parents[2] / "server" / "examples"
LINKAGES = sorted(
    p.stem for p in EXAMPLES.glob("*.json") if json.loads(p.read_text())["kind"] == "linkage"
)
KINEMATIC = ["position", "velocity", "acceleration", "poles", "components"]


def example(name: str) -> dict[str, Any]:
    data: dict[str, Any] = json.loads((EXAMPLES / f"{name}.json").read_text())
    return data


def preset(client: TestClient, name: str) -> dict[str, Any]:
    response = client.post(f"/api/v1/presets/{name}", json={})
    assert response.status_code == 200, response.text
    scene: dict[str, Any] = response.json()
    return scene


def post(client: TestClient, path: str, body: dict[str, Any]) -> dict[str, Any]:
    response = client.post(f"/api/v1{path}", json=body)
    assert response.status_code == 200, response.text
    answer: dict[str, Any] = response.json()
    return answer


def cross(w: float, r: np.ndarray) -> np.ndarray:
    """k w x r in the plane."""
    return np.array([-w * r[1], w * r[0]])


@pytest.mark.parametrize(
    "source", [f"example:{n}" for n in LINKAGES] + [f"preset:{n}" for n in PRESETS]
)
def test_polygons_are_the_solutions_and_the_rest_is_the_analyze_body(
    client: TestClient, source: str
) -> None:
    kind, name = source.split(":")
    scene = example(name) if kind == "example" else preset(client, name)
    answer = post(client, "/analyze", {"scene": scene, "quantities": [*KINEMATIC, "polygons"]})
    polygons = answer.pop("polygons")
    assert answer == post(client, "/analyze", {"scene": scene})
    for method in ("vector", "loop"):  # the vector method's order whichever method is asked
        assert polygons == post(client, "/solution", {"scene": scene, "method": method})["polygons"]
    points, links = answer["points"], answer["links"]
    assert polygons["segments"], "a linkage's polygons have segments"
    for seg in polygons["segments"]:
        base, point, link = points[seg["base"]], points[seg["point"]], links[seg["link"]]
        r = np.subtract(point["position"], base["position"])
        scale_v = max(np.hypot(*point["velocity"]), np.hypot(*base["velocity"]), 1e-300)
        scale_a = max(np.hypot(*point["acceleration"]), np.hypot(*base["acceleration"]), 1e-300)
        np.testing.assert_allclose(seg["velocity"], cross(link["omega"], r), atol=1e-12 * scale_v)
        np.testing.assert_allclose(seg["tangential"], cross(link["alpha"], r), atol=1e-12 * scale_a)
        np.testing.assert_allclose(seg["normal"], -(link["omega"] ** 2) * r, atol=1e-12 * scale_a)
        relative_v = np.subtract(point["velocity"], base["velocity"])
        relative_a = np.subtract(point["acceleration"], base["acceleration"])
        np.testing.assert_allclose(seg["velocity"], relative_v, atol=1e-9 * scale_v)
        total = np.add(seg["tangential"], seg["normal"])
        np.testing.assert_allclose(total, relative_a, atol=1e-9 * scale_a)


def test_only_the_quantities_asked_come_with_the_polygons(client: TestClient) -> None:
    scene = example("S000-T2")
    full = post(client, "/analyze", {"scene": scene, "quantities": [*KINEMATIC, "polygons"]})
    lean = post(client, "/analyze", {"scene": scene, "quantities": ["position", "polygons"]})
    assert lean["polygons"] == full["polygons"]
    assert (
        lean["points"]
        == post(client, "/analyze", {"scene": scene, "quantities": ["position"]})["points"]
    )
    assert all(set(p) == {"position"} for p in lean["points"].values())
    assert all(set(link) <= {"angle"} for link in lean["links"].values())
    assert "joints" not in lean and "instant_centres" not in lean
    assert "polygons" not in post(client, "/analyze", {"scene": scene})  # only when asked


def test_polygons_are_refused_where_there_are_none(client: TestClient) -> None:
    """A sweep, a spatial chain, a cam and a gear train: 422 invalid_scene, in words."""
    four_bar = example("S000-T1")
    refused = [
        ("/sweep", {"scene": four_bar, "samples": 8, "quantities": ["polygons"]}),
        ("/analyze", {"scene": example("S002-spatial-arm"), "quantities": ["polygons"]}),
        ("/analyze", {"scene": example("cams/cam-roller-translating"), "quantities": ["polygons"]}),
        ("/analyze", {"scene": example("G001-planetary"), "quantities": ["polygons"]}),
    ]
    for path, body in refused:
        response = client.post(f"/api/v1{path}", json=body)
        assert response.status_code == 422, (path, response.text)
        assert response.headers["content-type"].startswith("application/problem+json")
        problem = response.json()
        assert problem["code"] == "invalid_scene" and "polygons" in problem["detail"], problem


def test_the_extension_is_in_the_published_schema(client: TestClient) -> None:
    openapi = client.get("/api/v1/openapi.json").json()
    schemas = openapi["components"]["schemas"]
    analyze = json.dumps(schemas["AnalyzeRequest"]["properties"]["quantities"])
    sweep = json.dumps(schemas["SweepRequest"]["properties"]["quantities"])
    assert '"polygons"' in analyze and '"polygons"' not in sweep
    assert "PolygonValues" in json.dumps(schemas["AnalyzeResponse"]["properties"]["polygons"])
    body = {"scene": example("S000-T2"), "quantities": ["position", "polygons"]}
    check(openapi, "/analyze", "post", client.post("/api/v1/analyze", json=body))

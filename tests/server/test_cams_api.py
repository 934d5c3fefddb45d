"""Cams over HTTP (issue 24, docs/CAMS.md): POST /sweep and POST /analyze with a cam scene answer
the contract's fields, the body is the library's ``as_dict()``, real responses satisfy the
published schema, and every bad request is a problem+json, never a 500 or a NaN."""

from __future__ import annotations

import json
import math
from pathlib import Path
from typing import Any

import numpy as np
import pytest
from fastapi.testclient import TestClient

import solver
from tests.server.test_contract import check, plain

ROOT = Path(__file__).resolve().parents[2]
EXAMPLE = ROOT / "server" / "examples" / "cams" / "cam-roller-translating.json"


def cam() -> dict[str, Any]:
    doc: dict[str, Any] = json.loads(EXAMPLE.read_text())
    return doc


@pytest.fixture(scope="module")
def openapi(client: TestClient) -> dict[str, Any]:
    document: dict[str, Any] = client.get("/api/v1/openapi.json").json()
    return document


def test_sweep_answers_the_contract(client: TestClient, openapi: dict[str, Any]) -> None:
    """The contract's fields over a revolution from cam angle 0; the body is solver.sweep's; the
    example (cycloidal rise of 25 mm over 120 deg at 10 rad/s) peaks at v = 2 h omega / beta."""
    response = client.post("/api/v1/sweep", json={"scene": cam(), "samples": 72})
    assert response.status_code == 200, response.text
    body = response.json()
    assert body == plain(solver.sweep(cam(), 72).as_dict())
    check(openapi, "/sweep", "post", response)
    assert body["samples"] == 72 and body["cam_angle"][0] == 0.0
    assert body["cam_angle"][1] == pytest.approx(2 * math.pi / 72)
    for key in ("displacement", "velocity", "acceleration", "jerk"):
        assert len(body["follower"][key]) == 72
    for key in ("pressure_angle", "radius_of_curvature", "pitch_radius_of_curvature"):
        assert len(body[key]) == 72
    assert np.asarray(body["profile"]).shape == (72, 2)
    assert np.asarray(body["contact_point"]).shape == (72, 2)
    velocity = body["diagnostics"]["extremes"]["velocity"]
    assert velocity["max"] == pytest.approx(2 * 0.025 * 10 / math.radians(120), rel=1e-9)
    assert velocity["max_at_deg"] == pytest.approx(60.0)
    assert body["warnings"] == []


def test_analyze_at_an_angle(client: TestClient, openapi: dict[str, Any]) -> None:
    """/analyze with angle_deg: one cam angle, the same numbers as the library's."""
    response = client.post("/api/v1/analyze", json={"scene": cam(), "angle_deg": 60})
    assert response.status_code == 200, response.text
    check(openapi, "/analyze", "post", response)
    body = response.json()
    assert body == plain(solver.analyze(cam(), angle_deg=60).as_dict())
    assert body["segment"] == 0 and body["cam_angle_deg"] == pytest.approx(60.0)
    assert body["follower"]["displacement"] == pytest.approx(0.0125, rel=1e-12)
    assert body["follower"]["velocity"] == pytest.approx(0.5 / math.radians(120), rel=1e-12)
    default = client.post("/api/v1/analyze", json={"scene": cam()}).json()
    assert default["cam_angle"] == 0.0


def test_warnings_reach_http(client: TestClient) -> None:
    doc = cam()
    doc["segments"][0]["law"] = "harmonic"
    doc["cam"]["omeg"] = 1.0
    body = client.post("/api/v1/sweep", json={"scene": doc, "samples": 8}).json()
    assert body["warnings"][0] == "cam.omeg is not a scene field; did you mean omega?"
    assert any(
        w.startswith("discontinuous acceleration at cam angle 120 deg") for w in body["warnings"]
    )
    strict = client.post("/api/v1/sweep", json={"scene": doc, "strict": True})
    assert strict.status_code == 422 and strict.json()["code"] == "invalid_scene"


def _problem(client: TestClient, path: str, request: dict[str, Any], status: int = 422) -> str:
    response = client.post(f"/api/v1{path}", json=request)
    assert response.status_code == status, response.text
    assert response.headers["content-type"] == "application/problem+json"
    detail: str = response.json()["detail"]
    return detail


def test_errors_are_problems_with_the_numbers(client: TestClient, openapi: dict[str, Any]) -> None:
    short = cam()
    short["segments"][1]["duration_deg"] = 50
    detail = _problem(client, "/sweep", {"scene": short})
    assert detail.startswith("segments: the durations sum to 120 + 50 + 120 + 60 = 350 deg")
    far = cam()
    far["follower"]["offset"] = 0.05
    assert "prime circle radius" in _problem(client, "/analyze", {"scene": far})
    linkage = json.loads((ROOT / "server" / "examples" / "S000-T1.json").read_text())
    angle = _problem(client, "/analyze", {"scene": linkage, "angle_deg": 30})
    assert angle.startswith("angle_deg: the cam angle of a 'cam' scene")
    angle = _problem(client, "/solution", {"scene": linkage, "angle_deg": 30})
    assert angle.startswith("angle_deg: the cam angle of a 'cam' scene")
    timed = {"scene": cam(), "time_range": [0, 1]}
    assert _problem(client, "/sweep", timed).startswith("time_range: a cam is swept")
    dynamics = {"scene": cam(), "quantities": ["forces"]}
    assert "planar linkages only" in _problem(client, "/sweep", dynamics)
    huge = client.post("/api/v1/sweep", json={"scene": cam(), "samples": 10**6})
    assert huge.status_code == 413 and huge.json()["code"] == "limit_exceeded"
    assert "values per sample" in huge.json()["detail"]
    check(openapi, "/sweep", "post", huge)
    assert _problem(client, "/sweep", {"scene": cam(), "samples": 2}, 413).startswith("samples")


@pytest.mark.parametrize(
    "broken",
    [
        {"cam": {"base_radius": float("1e400"), "omega": 1}},
        {"cam": {"base_radius": 0.04, "omega": 1e300}},
        {"segments": []},
        {"segments": [{"type": "rise", "law": "cycloidal", "lift": 0.01, "duration_deg": 360}]},
        {"follower": {"motion": "oscillating", "contact": "roller", "roller_radius": 0.01,
                      "pivot": [0.0, 0.0], "arm_length": 0.05}},
        {"follower": {"motion": "oscillating", "contact": "knife", "pivot": [0.2, 0],
                      "arm_length": 0.01}},
        {"follower": "roller"},
    ],
)  # fmt: skip
def test_bad_cams_are_invalid_scenes(client: TestClient, broken: dict[str, Any]) -> None:
    doc = {**cam(), **broken}
    for path in ("/sweep", "/analyze"):
        response = client.post(f"/api/v1{path}", content=json.dumps({"scene": doc}))
        assert response.status_code == 422, response.text
        assert response.json()["code"] == "invalid_scene"


def test_the_example_is_listed_and_served(client: TestClient) -> None:
    """server/example_index.json lists the cam example with its kind (the app's menu leaves out
    kinds it cannot draw yet); /examples/cams/<file> serves it byte for byte."""
    examples = client.get("/examples/index.json").json()["examples"]
    listed = [entry for entry in examples if entry.get("kind") == "cam"]
    assert [entry["file"] for entry in listed] == ["cams/cam-roller-translating.json"]
    response = client.get("/examples/cams/cam-roller-translating.json")
    assert response.status_code == 200 and response.content == EXAMPLE.read_bytes()


# --- the Cams family -----------------------------------------------------------------------------

CAM_PRESETS = [
    "cam_roller_translating",
    "cam_offset_knife",
    "cam_flat_faced",
    "cam_oscillating_roller",
]


def test_cam_presets_are_listed_apart(client: TestClient, openapi: dict[str, Any]) -> None:
    """GET /presets?family=cams lists the four followers; GET /presets (the linkage menu) does
    not."""
    response = client.get("/api/v1/presets", params={"family": "cams"})
    check(openapi, "/presets", "get", response)
    listed = response.json()["presets"]
    assert [p["name"] for p in listed] == CAM_PRESETS
    laws = next(q for q in listed[0]["parameters"] if q["name"] == "rise_law")
    assert laws["labels"][int(laws["default"])] == "cycloidal"
    linkages = [p["name"] for p in client.get("/api/v1/presets").json()["presets"]]
    assert not set(linkages) & set(CAM_PRESETS)


@pytest.mark.parametrize("name", CAM_PRESETS)
def test_every_cam_preset_sweeps_without_warnings(client: TestClient, name: str) -> None:
    """Each preset at its defaults is a textbook-sound cam: no warning over a revolution."""
    scene = client.post(f"/api/v1/presets/{name}", json={})
    assert scene.status_code == 200, scene.text
    doc = scene.json()
    assert doc["kind"] == "cam"
    body = client.post("/api/v1/sweep", json={"scene": doc, "samples": 36}).json()
    assert body["warnings"] == [], body["warnings"]


def test_cam_preset_parameters(client: TestClient) -> None:
    """The laws by index, the oscillating lift in degrees turned to rad, bad values refused."""
    harmonic = float(solver.cams.LAW_NAMES.index("harmonic"))
    doc = client.post("/api/v1/presets/cam_oscillating_roller",
                      json={"rise_law": harmonic, "lift": 20.0}).json()  # fmt: skip
    assert doc["segments"][0]["law"] == "harmonic"
    assert doc["segments"][0]["lift"] == pytest.approx(math.radians(20.0))
    warned = client.post("/api/v1/sweep", json={"scene": doc, "samples": 36}).json()["warnings"]
    assert any(w.startswith("discontinuous acceleration") for w in warned)
    long = {"rise_deg": 200.0, "return_deg": 150.0}
    detail = _problem(client, "/presets/cam_flat_faced", long)
    assert detail.startswith("rise_deg + dwell_deg + return_deg = 200 + 60 + 150 = 410 deg")
    assert "cams: cam_roller_translating" in _problem(client, "/presets/cam_nope", {})


def test_worked_solution_at_a_cam_angle(client: TestClient, openapi: dict[str, Any]) -> None:
    """POST /solution with a cam and angle_deg: the library's body, its results the /analyze body
    at that angle, the steps of docs/CAMS.md; the printable page shows them with the figure."""
    request = {"scene": cam(), "angle_deg": 60}
    response = client.post("/api/v1/solution", json=request)
    assert response.status_code == 200, response.text
    body = response.json()
    assert body == plain(solver.solve(cam(), angle_deg=60).as_dict())
    assert body["results"] == plain(solver.analyze(cam(), angle_deg=60).as_dict())
    check(openapi, "/solution", "post", response)
    kinds = [s["kind"] for s in body["steps"]]
    assert kinds == ["cam.data", "cam.law", "cam.motion", "cam.pressure_angle",
                     "cam.curvature", "cam.fundamental_law", "cam.summary"]  # fmt: skip
    page = client.post("/api/v1/solution.html", json=request)
    assert page.status_code == 200 and page.headers["content-type"].startswith("text/html")
    assert "The pressure angle" in page.text and 'data-kind="cam"' in page.text
    assert "Segments (lift in m" in page.text and "cycloidal" in page.text

"""The API contract (issue 9): every 200 body is the solver result's ``as_dict()``, warnings and
``strict`` reach HTTP, and real responses satisfy the published OpenAPI schema."""

from __future__ import annotations

import json
from pathlib import Path
from typing import Any

import numpy as np
import pytest
from fastapi.testclient import TestClient
from jsonschema import Draft202012Validator

import solver
from server import problems
from server.app import API_PREFIX
from server.routes import dynamics, exercises, kinematics, presets, solution, synthesis
from server.workers import WorkerRoute
from solver.exercises import MAX_COUNT

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
    if doc["kind"] == "gear_train":  # speeds, torques and a time sweep (docs/GEARS.md)
        torque = {next(iter(doc["inputs"])): 12.0}
        swept = {"scene": doc, "samples": SAMPLES, "time_range": [0, 1]}
        return [
            ("/analyze", {"scene": doc}, solver.analyze(doc)),
            (
                "/analyze",
                {"scene": doc, "input_torque": torque},
                solver.analyze(doc, input_torque=torque),
            ),
            ("/sweep", swept, solver.sweep_time(doc, (0, 1), SAMPLES)),
        ]
    out: list[tuple[str, dict[str, Any], solver.Result]] = [
        ("/analyze", {"scene": doc}, solver.analyze(doc)),
        ("/analyze", {"scene": doc, "quantities": ["position"]}, solver.analyze(doc, ["position"])),
        ("/solution", {"scene": doc, "method": "loop"}, solver.solve(doc, "loop")),
    ]
    wanted = ["position", "velocity", "acceleration", "poles", "components"]
    if doc["kind"] == "spatial_chain":  # swept in time only
        request = {"scene": doc, "samples": SAMPLES, "quantities": wanted, "time_range": [0, 1]}
        out.append(("/sweep", request, solver.sweep_time(doc, (0, 1), SAMPLES, wanted)))
        return out
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


# --- the published schema ------------------------------------------------------------------------


@pytest.fixture(scope="module")
def openapi(client: TestClient) -> dict[str, Any]:
    document: dict[str, Any] = client.get("/api/v1/openapi.json").json()
    return document


def check(openapi: dict[str, Any], path: str, method: str, response: Any) -> None:
    """The response satisfies the schema the OpenAPI document publishes for its status and media
    type (JSON Schema 2020-12, references resolved within the document)."""
    media = response.headers["content-type"].split(";")[0]
    declared = openapi["paths"][f"/api/v1{path}"][method]["responses"]
    schema = declared[str(response.status_code)]["content"][media]["schema"]
    validator = Draft202012Validator({**openapi, **schema})
    body = response.json()
    errors = [f"{list(e.absolute_path)}: {e.message}" for e in validator.iter_errors(body)]
    assert not errors, (path, response.status_code, errors[:5])


@pytest.mark.parametrize("name", NAMES)
def test_real_responses_satisfy_the_published_schema(
    client: TestClient, openapi: dict[str, Any], name: str
) -> None:
    for endpoint, request, _ in calls(name):
        check(openapi, endpoint, "post", client.post(f"/api/v1{endpoint}", json=request))


def test_presets_and_problems_satisfy_the_published_schema(
    client: TestClient, openapi: dict[str, Any]
) -> None:
    check(openapi, "/presets", "get", client.get("/api/v1/presets"))
    check(openapi, "/presets/four_bar", "post", client.post("/api/v1/presets/four_bar", json={}))
    doc = example("S000-T1")
    doc["drivers"][0]["angle_deg"] = 180.0
    problems = [
        ("/analyze", {"scene": {"kind": "nope"}}),
        ("/analyze", {"scene": doc}),  # not_assemblable
        ("/analyze", {"scene": example("S000-T1"), "quantities": ["speed"]}),  # pydantic's
        ("/sweep", {"scene": example("S000-T1"), "samples": 10**7}),
        ("/solution", {"scene": example("S000-T1"), "digits": 0}),
    ]
    for endpoint, request in problems:
        response = client.post(f"/api/v1{endpoint}", json=request)
        assert response.status_code in (413, 422), response.text
        assert response.headers["content-type"] == "application/problem+json"
        check(openapi, endpoint, "post", response)


def test_the_schema_would_catch_a_wrong_body(client: TestClient, openapi: dict[str, Any]) -> None:
    """The check is not vacuous: a body without warnings, or with a vector as a string, fails."""
    response = client.post("/api/v1/analyze", json={"scene": example("S000-T2")})
    schema = openapi["paths"]["/api/v1/analyze"]["post"]["responses"]["200"]["content"]
    validator = Draft202012Validator({**openapi, **schema["application/json"]["schema"]})
    body = response.json()
    assert validator.is_valid(body)
    assert not validator.is_valid({k: v for k, v in body.items() if k != "warnings"})
    body["points"]["C"]["velocity"] = "fast"
    assert not validator.is_valid(body)


def test_every_error_is_declared_as_problem_json(openapi: dict[str, Any]) -> None:
    codes = openapi["components"]["schemas"]["ProblemCode"]["enum"]
    assert sorted(codes) == sorted(problems.TITLES)
    assert "HTTPValidationError" not in json.dumps(openapi)
    for path, operations in openapi["paths"].items():
        for method, operation in operations.items():
            for status, response in operation["responses"].items():
                media = set(response.get("content", {}))
                if status.startswith(("4", "5")):
                    assert media == {"application/problem+json"}, (path, method, status)
                elif path == "/api/v1/exercises/export":  # a file in the requested format
                    assert media == {
                        "application/xml",
                        "text/html; charset=utf-8",
                        "application/pdf",
                        "text/csv; charset=utf-8",
                        "application/json",
                        "application/zip",
                    }
                elif path.startswith("/api/v1/") and not path.endswith(".html"):
                    assert media == {"application/json"}, (path, method, status)
                    assert response["content"]["application/json"]["schema"] != {"type": "string"}


def test_exercise_responses_satisfy_the_published_schema(
    client: TestClient, openapi: dict[str, Any]
) -> None:
    """Every exercise type's generated body, one exercise by id, and a graded check."""
    check(openapi, "/exercises/types", "get", client.get("/api/v1/exercises/types"))
    types = [t["name"] for t in client.get("/api/v1/exercises/types").json()["types"]]
    for name in types:
        response = client.post("/api/v1/exercises", json={"type": name, "count": 1, "seed": 7})
        check(openapi, "/exercises", "post", response)
    exercise = response.json()["exercises"][0]
    one = client.get(f"/api/v1/exercises/{exercise['id']}")
    check(openapi, "/exercises/{exercise_id}", "get", one)
    answers = {a["key"]: 1.0 for a in exercise["asked"]}
    graded = client.post("/api/v1/exercises/check", json={"id": exercise["id"], "answers": answers})
    check(openapi, "/exercises/check", "post", graded)


def test_timeouts_limits_and_busy_answers_are_declared(openapi: dict[str, Any]) -> None:
    """Every operation declares the answers any request can get (408 past the request timeout,
    413, 422, 500); one that runs in the worker pool also 429 and 503, each with Retry-After;
    all as problem+json of the Problem schema."""
    pooled = {
        (API_PREFIX + route.path, method.lower())
        for module in (dynamics, exercises, kinematics, presets, solution, synthesis)
        for route in module.router.routes
        if isinstance(route, WorkerRoute)
        for method in route.methods
    }
    assert ("/api/v1/sweep", "post") in pooled and ("/api/v1/presets", "get") not in pooled
    problem = {"$ref": "#/components/schemas/Problem"}
    for path, operations in openapi["paths"].items():
        for method, operation in operations.items():
            declared = operation["responses"]
            expected = {"408", "413", "422", "500"}
            if (path, method) in pooled:
                expected |= {"429", "503"}
                for status in ("429", "503"):
                    header = declared[status]["headers"]["Retry-After"]
                    assert header["schema"] == {"type": "integer", "minimum": 0}
            assert expected <= set(declared), (path, method, expected - set(declared))
            for status in expected:
                content = declared[status]["content"]
                assert content == {"application/problem+json": {"schema": problem}}, (path, status)


def test_wrong_methods_other_media_types_and_exam_refusals_are_declared(
    openapi: dict[str, Any],
) -> None:
    """405 (with Allow) on every operation; 415 on every one that takes a body, and only there;
    404 on one exercise by id (an exam id not made here), 403 on a check (an exam exercise)."""
    problem = {"application/problem+json": {"schema": {"$ref": "#/components/schemas/Problem"}}}
    for path, operations in openapi["paths"].items():
        for method, operation in operations.items():
            declared = operation["responses"]
            assert declared["405"]["content"] == problem, (path, method)
            assert declared["405"]["headers"]["Allow"]["schema"] == {"type": "string"}
            assert ("415" in declared) == ("requestBody" in operation), (path, method)
    exercises = "/api/v1/exercises"
    assert openapi["paths"][exercises + "/{exercise_id}"]["get"]["responses"]["404"]["content"] == (
        problem
    )
    assert openapi["paths"][exercises + "/check"]["post"]["responses"]["403"]["content"] == problem


def test_integer_bounds_are_published_exactly(openapi: dict[str, Any]) -> None:
    """A bound is the integer the server enforces: the seed's maximum 2**63 - 1 (as a float it
    would read 2**63, a seed the server refuses); count 1..100, samples 2..100000."""
    schemas = openapi["components"]["schemas"]
    for model in ("ExercisesRequest", "ExportRequest"):
        fields = schemas[model]["properties"]
        assert (fields["seed"]["minimum"], fields["seed"]["maximum"]) == (0, 2**63 - 1)
        assert type(fields["seed"]["maximum"]) is int
        assert (fields["count"]["minimum"], fields["count"]["maximum"]) == (1, MAX_COUNT)
    samples = schemas["SweepRequest"]["properties"]["samples"]
    assert (samples["minimum"], samples["maximum"]) == (2, 100_000)
    assert all(type(samples[k]) is int for k in ("minimum", "maximum"))


def test_the_published_integer_bounds_are_the_servers(client: TestClient) -> None:
    """The bounds just published, at the edges: inside them answered, past them refused."""
    base = {"type": "four_bar_velocity", "count": 1}
    assert client.post("/api/v1/exercises", json={**base, "seed": 2**63 - 1}).status_code == 200
    assert client.post("/api/v1/exercises", json={**base, "seed": 2**63}).status_code == 422
    assert client.post("/api/v1/exercises", json={**base, "count": 0}).status_code == 413

"""Statics and friction through the API (issue 27): the request fields, the answers' shape
against the published schema, and bad input as problem+json 422s."""

from __future__ import annotations

import copy
from typing import Any

import pytest
from fastapi.testclient import TestClient

from tests.server.test_contract import check
from tests.solver.dynamics.test_statics import slider_crank


def post(client: TestClient, path: str, body: dict[str, Any]) -> Any:
    return client.post(f"/api/v1/{path}", json=body)


@pytest.fixture(scope="module")
def openapi(client: TestClient) -> dict[str, Any]:
    document: dict[str, Any] = client.get("/api/v1/openapi.json").json()
    return document


def test_statics_and_friction_are_published(openapi: dict[str, Any]) -> None:
    schemas = openapi["components"]["schemas"]
    for request in ("AnalyzeRequest", "SweepRequest"):
        statics = schemas[request]["properties"]["statics"]
        assert statics["type"] == "boolean" and statics["default"] is False
        assert "pin_radius" in statics["description"]
    assert {"efficiency", "self_locking"} <= set(schemas["CycleValues"]["properties"])
    assert "self_locking" in schemas["AnalyzeResponse"]["properties"]


def test_statics_over_http(client: TestClient, openapi: dict[str, Any]) -> None:
    request = {"scene": slider_crank(30.0), "quantities": ["forces"], "statics": True}
    response = post(client, "analyze", request)
    assert response.status_code == 200, response.text
    check(openapi, "/analyze", "post", response)
    body = response.json()
    assert body["drivers"][0]["torque"] == pytest.approx(-64.63850109422799, rel=1e-12)
    assert body["mechanical_advantage"]["P"] == pytest.approx(15.47065577127525, rel=1e-12)
    response = post(client, "sweep", {**request, "samples": 36})
    assert response.status_code == 200, response.text
    check(openapi, "/sweep", "post", response)
    assert len(response.json()["mechanical_advantage"]["P"]) == 36


def test_friction_over_http(client: TestClient, openapi: dict[str, Any]) -> None:
    """The self-locking slider-crank (r / l = 0.95, mu = 0.5): nulls where it locks, the cycle's
    self_locking in words, all as the published schema says."""
    scene = slider_crank(0.0, r=0.95, rod=1.0, B={"coefficient": 0.5})
    response = post(client, "sweep", {"scene": scene, "quantities": ["forces"], "samples": 72})
    assert response.status_code == 200, response.text
    check(openapi, "/sweep", "post", response)
    cycle = response.json()["cycle"]
    assert cycle["efficiency"] is None and "self-locking" in cycle["self_locking"]["reason"]
    scene["joints"][2]["friction"]["coefficient"] = 0.1
    scene["forces"][0]["magnitude"] = 'where(omega("rod") >= 0, -1000, 1000)'  # net work in
    response = post(client, "sweep", {"scene": scene, "quantities": ["forces"], "samples": 72})
    check(openapi, "/sweep", "post", response)
    driver = response.json()["drivers"][0]
    assert len(driver["torque_frictionless"]) == 72
    assert 0 < response.json()["cycle"]["efficiency"] <= 1
    response = post(client, "analyze", {"scene": scene, "quantities": ["forces"]})
    check(openapi, "/analyze", "post", response)
    assert response.json()["self_locking"] is None


@pytest.mark.parametrize(
    ("joint", "friction", "where"),
    [
        (2, {"coefficient": -0.2}, "joints[2].friction.coefficient"),
        (2, {"coefficient": 0.2, "pin_radius": 0.01}, "joints[2].friction.pin_radius"),
        (1, {"coefficient": 0.2}, "joints[1].friction.pin_radius"),
        (1, {"coefficient": 0.2, "pin_radius": -1}, "joints[1].friction.pin_radius"),
        (1, "rough", "joints[1].friction"),
    ],
)
def test_bad_friction_is_a_problem(
    client: TestClient, joint: int, friction: Any, where: str
) -> None:
    scene = copy.deepcopy(slider_crank(30.0))
    scene["joints"][joint]["friction"] = friction
    response = post(client, "analyze", {"scene": scene, "quantities": ["forces"]})
    assert response.status_code == 422, response.text
    assert response.headers["content-type"].startswith("application/problem+json")
    problem = response.json()
    assert problem["code"] == "invalid_scene"
    assert problem["detail"].startswith(where)


def test_statics_without_forces_or_not_a_boolean_is_a_problem(client: TestClient) -> None:
    response = post(
        client,
        "analyze",
        {"scene": slider_crank(30.0), "quantities": ["position"], "statics": True},
    )
    assert response.status_code == 422 and response.json()["code"] == "invalid_scene"
    assert "statics" in response.json()["detail"]
    response = post(client, "analyze", {"scene": slider_crank(30.0), "statics": "yes"})
    assert response.status_code == 422
    assert response.headers["content-type"].startswith("application/problem+json")

"""The worked solution by Newton-Euler (POST /api/v1/solution, method newton_euler): every step's
checks re-evaluate, every number with a source is the /analyze number (the results carry forces
and energy), seed 004's torque and joint forces are the reference's, and the free-body diagrams
are well-formed SVG with one arrow per force."""

from __future__ import annotations

import math
import xml.etree.ElementTree as ET
from typing import Any

import numpy as np
import pytest
from fastapi.testclient import TestClient
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from tests.dynamics_cases import EXPECTED, seed004_scene, with_masses_and_loads
from tests.linkage_strategies import linkages
from tests.solver.test_steps import unit_floors, verify


def at_path(body: Any, path: list[Any]) -> Any:
    for key in path:
        body = body[key]
    return body


def solve(client: TestClient, scene: dict[str, Any]) -> Any:
    response = client.post("/api/v1/solution", json={"scene": scene, "method": "newton_euler"})
    assert response.status_code == 200, response.text
    return response.json()


def check(body: Any) -> None:
    assert body["method"] == "newton_euler"
    floors = unit_floors(body["steps"])
    for step in body["steps"]:
        assert not verify(step, floors), (step["title"], verify(step, floors)[:3])
        for key, value in step["values"].items():
            if value["source"] is not None:
                reported = at_path(body["results"], value["source"])
                assert np.allclose(value["value"], reported, rtol=1e-15, atol=0), (
                    key,
                    step["title"],
                )


def test_seed004_by_newton_euler(client: TestClient) -> None:
    body = solve(client, seed004_scene(90))
    check(body)
    kinds = [s["kind"] for s in body["steps"]]
    for kind in (
        "dynamics.data",
        "dynamics.center_acceleration",
        "dynamics.free_body",
        "dynamics.equations",
        "dynamics.system",
        "dynamics.solution",
        "dynamics.power_balance",
    ):
        assert kind in kinds
    assert kinds.index("dynamics.solution") > kinds.index("dynamics.system")
    (solution,) = [s for s in body["steps"] if s["kind"] == "dynamics.solution"]
    assert solution["values"]["M_crank"]["value"] == pytest.approx(
        EXPECTED["theta=90deg/driving_torque_M_O"]["value"], rel=1e-9
    )
    B = EXPECTED["theta=90deg/force_B_coupler_on_member3"]["value"]
    assert [solution["values"]["Fx_B"]["value"], solution["values"]["Fy_B"]["value"]] == (
        pytest.approx(B, rel=1e-9)
    )
    (power,) = [s for s in body["steps"] if s["kind"] == "dynamics.power_balance"]
    assert power["values"]["M_power_balance"]["value"] == pytest.approx(
        EXPECTED["theta=90deg/driving_torque_from_power_balance"]["value"], rel=1e-9
    )
    assert body["results"]["drivers"][0]["torque"] == pytest.approx(952.5051075492952, rel=1e-9)


def test_the_seed_mistake_about_an_accelerating_pin(client: TestClient) -> None:
    """E004-7: about A the sum of moments is I_G alpha + r_AG x m a_G, not I_A alpha."""
    body = solve(client, seed004_scene(90))
    (mistake,) = [m for m in body["mistakes"] if m["kind"].startswith("dynamics.moment")]
    m, L = 60.0, 1.0
    alpha = EXPECTED["theta=90deg/alpha_coupler_z"]["value"]
    assert mistake["values"]["wrong"]["value"] == pytest.approx(m * L**2 / 3 * alpha, rel=1e-12)
    assert mistake["values"]["right"]["value"] != pytest.approx(
        mistake["values"]["wrong"]["value"], rel=0.1
    )


def test_free_body_diagrams(client: TestClient) -> None:
    body = solve(client, seed004_scene(180))
    free_body = [s for s in body["steps"] if s["kind"] == "dynamics.free_body"]
    diagrams = [s["diagram"] for s in free_body]
    svgs = [s["figure"] for s in free_body]
    assert [f["link"] for f in diagrams] == ["crank", "coupler", "rocker"]
    rocker = diagrams[2]
    names = [f["name"] for f in rocker["forces"]]
    assert names == ["F_B", "F_Gamma", "W_rocker", "W_mD", "F_D"]
    # the forces on member 3 and its moments balance its inertia: sum F = sum m a
    total = np.sum([f["vector"] for f in rocker["forces"]], axis=0)
    a_rocker = np.array(
        next(s for s in body["steps"] if s["title"] == "Acceleration of the centre of rocker")[
            "values"
        ]["a_G(rocker)"]["value"]
    )
    a_D = np.array(EXPECTED["theta=180deg/a_D"]["value"])
    assert total == pytest.approx(60 * a_rocker + 90 * a_D, abs=1e-6 * 3e4)
    for diagram, svg in zip(diagrams, svgs, strict=True):
        root = ET.fromstring(svg)
        arrows = [f for f in diagram["forces"] if math.hypot(*f["vector"]) > 1e-9 * 3e4]
        lines = root.findall("{http://www.w3.org/2000/svg}line")
        assert len(lines) == len(arrows)
    assert [m["name"] for m in diagrams[0]["moments"]] == ["M_crank"]


def test_a_spatial_chain_falls_back(client: TestClient) -> None:
    from tests.server.test_solution import example

    body = client.post(
        "/api/v1/solution",
        json={"scene": example("S002-spatial-arm"), "method": "newton_euler"},
    ).json()
    assert body["steps"][0]["kind"] == "fallback" and body["method"] == "vector"


@pytest.mark.parametrize("family", ["slider_crank", "block_in_lever", "six_bar"])
@settings(max_examples=4, deadline=None, database=None, suppress_health_check=list(HealthCheck))
@given(data=st.data())
def test_random_linkages_by_newton_euler(
    client: TestClient, family: str, data: st.DataObject
) -> None:
    check(solve(client, data.draw(linkages(family).flatmap(with_masses_and_loads))))


def test_printable_page_of_the_newton_euler_solution(client: TestClient) -> None:
    response = client.get("/api/v1/solution.html?preset=seed004&method=newton_euler")
    assert response.status_code == 200, response.text
    steps = response.text.split('<li class="step">')[1:]
    free_body = [s for s in steps if "<h3>Free-body diagram of" in s]
    assert len(free_body) == 3, "one free-body diagram per moving link"
    assert all('<figure class="figure"><svg' in s for s in free_body)
    assert "Newton-Euler" in response.text

"""The worked static force analysis (POST /api/v1/solution, method statics): every step's checks
re-evaluate, every number with a source is the /analyze number with ``statics``, the holding
torque of a slider-crank is the textbook's closed form, and the inertia terms are absent."""

from __future__ import annotations

import math
from typing import Any

import numpy as np
import pytest
from fastapi.testclient import TestClient

from tests.dynamics_cases import seed004_scene
from tests.server.test_dynamics_solution import at_path
from tests.solver.dynamics.test_statics import F, L, R, slider_crank
from tests.solver.solutions.test_solve import unit_floors, verify


def statics(client: TestClient, scene: dict[str, Any]) -> Any:
    response = client.post("/api/v1/solution", json={"scene": scene, "method": "statics"})
    assert response.status_code == 200, response.text
    body = response.json()
    assert body["method"] == "statics"
    floors = unit_floors(body["steps"])
    for step in body["steps"]:
        assert not verify(step, floors), (step["title"], verify(step, floors)[:3])
        for key, value in step["values"].items():
            if value["source"] is not None:
                reported = at_path(body["results"], value["source"])
                assert np.allclose(value["value"], reported, rtol=1e-15, atol=0), key
    return body


@pytest.mark.parametrize("theta_deg", [30.0, 120.0, 250.0])
def test_slider_crank_holding_torque(client: TestClient, theta_deg: float) -> None:
    """T = -F r sin(theta + beta) / cos beta (sin beta = r sin theta / l), 1e-9, both in the
    solution of the equilibrium equations and in the virtual-work check."""
    body = statics(client, slider_crank(theta_deg))
    th = math.radians(theta_deg)
    beta = math.asin(R * math.sin(th) / L)
    expected = -F * R * math.sin(th + beta) / math.cos(beta)
    (solution,) = [s for s in body["steps"] if s["kind"] == "dynamics.solution"]
    assert solution["values"]["M_crank"]["value"] == pytest.approx(expected, rel=1e-9)
    (check,) = [s for s in body["steps"] if s["kind"] == "dynamics.power_balance"]
    assert check["title"] == "Check: the holding torque by virtual work"
    assert check["values"]["M_power_balance"]["value"] == pytest.approx(expected, rel=1e-9)


def test_seed004_statics_has_no_inertia_terms(client: TestClient) -> None:
    """Seed 004 at 90 deg in statics: no accelerations of the centres, no I_G alpha or m a_G
    in the equations, which read sum = 0; the holding torque is the /analyze one with statics
    (the sources above) and differs from the dynamic one."""
    body = statics(client, seed004_scene(90))
    kinds = [s["kind"] for s in body["steps"]]
    assert "dynamics.center_acceleration" not in kinds
    equations = [s for s in body["steps"] if s["kind"] == "dynamics.equations"]
    assert [s["title"] for s in equations] == [
        f"Equilibrium equations of {link}" for link in ("crank", "coupler", "rocker")
    ]
    for step in equations:
        assert not any("a_G" in key or "I_G" in key for key in step["values"])
        assert r"\sum F_x = 0" in step["latex"]
    dynamic = client.post(
        "/api/v1/analyze", json={"scene": seed004_scene(90), "quantities": ["forces"]}
    ).json()
    static = body["results"]["drivers"][0]["torque"]
    assert static != pytest.approx(dynamic["drivers"][0]["torque"], rel=0.1)
    # the seed's rocker at rest: its weights' moments about Gamma held by the force at B
    (rocker,) = [s for s in equations if s["title"].endswith("rocker")]
    v = rocker["values"]
    held = v["r x m g(rocker)"]["value"] + v["r x m g(mD)"]["value"] + v["r x F(F_D)"]["value"]
    assert v["b_Mz(Gamma)"]["value"] == pytest.approx(-held, rel=1e-12)

"""The worked static force analysis (POST /api/v1/solution, method statics): every step's checks
re-evaluate, every number with a source is the /analyze number with ``statics``, the holding
torque of a slider-crank is the textbook's closed form, and the inertia terms are absent."""

from __future__ import annotations

import math
from typing import Any

import pytest
from fastapi.testclient import TestClient

from tests.dynamics_cases import seed004_scene
from tests.server.test_dynamics_solution import check, solve
from tests.solver.dynamics.test_friction import pin_bar, slider_only_torque
from tests.solver.dynamics.test_statics import F, L, R, slider_crank


def statics(client: TestClient, scene: dict[str, Any]) -> Any:
    response = client.post("/api/v1/solution", json={"scene": scene, "method": "statics"})
    assert response.status_code == 200, response.text
    body = response.json()
    check(body, "statics")
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


@pytest.mark.parametrize("method", ["statics", "newton_euler"])
@pytest.mark.parametrize("theta_deg", [30.0, 120.0, 250.0])
def test_slider_friction_in_the_worked_solution(
    client: TestClient, method: str, theta_deg: float
) -> None:
    """mu = 0.2 at the slider of the massless slider-crank (statics and dynamics agree): the
    driving torque is the hand solution of the two-force rod in the friction cone (1e-9), the
    friction step's f is mu |N| against the sliding with the friction angle atan mu, and the
    power check carries the friction's power."""
    mu = 0.2
    body = statics_or(client, slider_crank(theta_deg, B={"coefficient": mu}), method)
    expected = slider_only_torque(math.radians(theta_deg), mu)
    assert expected is not None
    (solution,) = [s for s in body["steps"] if s["kind"] == "dynamics.solution"]
    assert solution["values"]["M_crank"]["value"] == pytest.approx(expected, rel=1e-9)
    (friction,) = [s for s in body["steps"] if s["kind"] == "dynamics.friction"]
    v = {key: value["value"] for key, value in friction["values"].items()}
    assert v["phi(B)"] == pytest.approx(math.degrees(math.atan(mu)), rel=1e-15)
    assert math.hypot(*v["f(B)"]) == pytest.approx(mu * v["|N(B)|"], rel=1e-12)
    assert v["f(B)"][1] == 0.0  # along the guide (the x axis)
    v_B = body["results"]["points"]["B"]["velocity"][0]
    assert math.copysign(1, v["f(B)"][0]) == -math.copysign(1, v_B)  # against the sliding
    (check,) = [s for s in body["steps"] if s["kind"] == "dynamics.power_balance"]
    p_friction = check["values"]["P_friction"]["value"]
    assert p_friction == pytest.approx(v["f(B)"][0] * v_B, rel=1e-12) and p_friction < 0


def statics_or(client: TestClient, scene: dict[str, Any], method: str) -> Any:
    """The worked solution by ``method`` (statics or newton_euler), checked as ``statics`` does."""
    if method == "statics":
        return statics(client, scene)
    body = solve(client, scene)
    check(body)
    return body


@pytest.mark.parametrize("omega", [3.0, -3.0])
def test_pin_friction_circle_in_the_worked_solution(client: TestClient, omega: float) -> None:
    """The bar O-A (2 m) with F = 100 N across it at A and the pin O (r = 0.02 m, mu = 0.3):
    M = -2 F + mu r F sgn(omega) (the friction circle), the frictionless M_0 = -2 F beside it
    and no efficiency (the load drives the bar back: it is held, not driven)."""
    doc = pin_bar(omega)
    body = statics(client, doc)
    (solution,) = [s for s in body["steps"] if s["kind"] == "dynamics.solution"]
    M = -200.0 + 0.3 * 0.02 * 100 * math.copysign(1, omega)
    assert solution["values"]["M_bar"]["value"] == pytest.approx(M, rel=1e-12)
    assert solution["values"]["M_0"]["value"] == pytest.approx(-200.0, rel=1e-12)
    assert ("eta" in solution["values"]) == (omega < 0)  # driven where M omega > 0
    if omega < 0:
        eta = solution["values"]["eta"]["value"]
        assert eta == pytest.approx(200.0 / -M, rel=1e-12) and eta < 1
    (friction,) = [s for s in body["steps"] if s["kind"] == "dynamics.friction"]
    assert friction["values"]["mu r(O)"]["value"] == pytest.approx(0.006, rel=1e-12)
    assert "friction circle" in friction["text"]


def test_a_locked_pose_has_no_worked_solution(client: TestClient) -> None:
    """r / l = 0.95, mu = 0.5 at the slider, at 270 deg: the rod pushes inside the friction
    cone (the sweep's self-locking), so the equations with friction have no answer: a
    singular_configuration that says so, never a 500."""
    doc = slider_crank(270.0, r=0.95, rod=1.0, B={"coefficient": 0.5})
    response = client.post("/api/v1/solution", json={"scene": doc, "method": "statics"})
    assert response.status_code == 422, response.text
    problem = response.json()
    assert problem["code"] == "singular_configuration"
    assert "self-locking" in problem["detail"] and "slider B" in problem["detail"]

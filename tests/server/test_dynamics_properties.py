"""Properties of the forces and energy answers for random linkages with random masses and loads.

Families: four-bars, slider-cranks, quick-returns, the block in a slotted lever (a prismatic
joint) and six-bars (closed-form and Newton-Raphson), each with a random body on every moving
link, a point mass, gravity, a state-dependent force and a moment (tests/dynamics_cases.py).

- Newton-Euler and the power balance give the same driving torque: within 1e-9 of the torque
  scale (the largest joint force times the mechanism's size), the power balance computed from
  the energy rates and the loads' power without any joint force.
- Momentum: the frame force equals the weights plus the external force minus M a_G, and minus the
  sum of the forces that the ground exerts through its joints (1e-9 of the force scale).
- Over a full revolution at constant speed (four-bars, slider-cranks, quick-returns, six-bars),
  the mean motor power is minus the loads' work per period (T and V are periodic; smooth loads,
  so the sampled means agree to rounding where the samples resolve the motion: no step of the
  kinetic energy above 2% of its range, which leaves out the linkages that pass close to a change
  point, where T has a narrow spike).
"""

from __future__ import annotations

import math
from typing import Any

import pytest
from fastapi.testclient import TestClient
from hypothesis import HealthCheck, assume, given, settings
from hypothesis import strategies as st

from tests.dynamics_cases import force_vector, with_masses_and_loads
from tests.linkage_strategies import linkages

FAMILIES = ("four_bar", "slider_crank", "quick_return", "block_in_lever", "six_bar")
PROPERTY = settings(
    max_examples=12, deadline=None, database=None, suppress_health_check=list(HealthCheck)
)


def _size(doc: dict[str, Any]) -> float:
    xy = list(doc["points"].values())
    return max(math.dist(p, q) for p in xy for q in xy)


def _analyze(client: TestClient, doc: dict[str, Any]) -> Any:
    response = client.post(
        "/api/v1/analyze",
        json={"scene": doc, "quantities": ["position", "velocity", "forces", "energy"]},
    )
    assert response.status_code == 200, response.text
    return response.json()


def _force_scale(body: Any) -> float:
    return max(1.0, *(math.hypot(*j["force"]) for j in body["joints"]))


@pytest.mark.parametrize("family", FAMILIES)
@PROPERTY
@given(data=st.data())
def test_newton_euler_torque_equals_power_balance(
    client: TestClient, family: str, data: st.DataObject
) -> None:
    doc = data.draw(linkages(family).flatmap(with_masses_and_loads))
    body = _analyze(client, doc)
    (driver,) = body["drivers"]
    omega = body["links"][driver["link"]]["omega"]
    if omega == 0.0:
        assert driver["torque_from_power_balance"] is None
        return
    scale = _force_scale(body) * _size(doc)
    assert driver["torque_from_power_balance"] == pytest.approx(driver["torque"], abs=1e-9 * scale)
    assert driver["power"] == pytest.approx(driver["torque"] * omega, rel=1e-12, abs=1e-300)


@pytest.mark.parametrize("family", FAMILIES)
@PROPERTY
@given(data=st.data())
def test_frame_force_is_weights_plus_loads_minus_momentum_rate(
    client: TestClient, family: str, data: st.DataObject
) -> None:
    doc = data.draw(linkages(family).flatmap(with_masses_and_loads))
    body = _analyze(client, doc)
    com = body["center_of_mass"]
    mass = com["mass"]
    gravity = doc["gravity"]
    load = force_vector(doc, body["links"])
    momentum = [mass * gravity[i] + load[i] - mass * com["acceleration"][i] for i in range(2)]
    ground = next(name for name, link in doc["links"].items() if link.get("ground"))
    through_joints = [0.0, 0.0]
    for joint in body["joints"]:
        if ground in joint["links"]:  # the force on the ground: minus it if ground is first
            sign = -1.0 if joint["links"][0] == ground else 1.0
            through_joints = [through_joints[i] + sign * joint["force"][i] for i in range(2)]
    scale = 1e-9 * max(_force_scale(body), mass * math.hypot(*com["acceleration"]))
    assert body["frame_force"] == pytest.approx(momentum, abs=scale)
    assert body["frame_force"] == pytest.approx(through_joints, abs=scale)


@pytest.mark.slow
@pytest.mark.parametrize("family", ("four_bar", "slider_crank", "quick_return", "six_bar"))
@settings(max_examples=6, deadline=None, database=None, suppress_health_check=list(HealthCheck))
@given(data=st.data())
def test_mean_power_over_a_cycle_is_minus_the_work_of_the_loads(
    client: TestClient, family: str, data: st.DataObject
) -> None:
    doc = data.draw(linkages(family).flatmap(with_masses_and_loads))
    doc["drivers"][0] |= {"alpha": 0.0, "omega": data.draw(st.sampled_from([-7.0, 3.0, 20.0]))}
    loaded = doc["forces"][0]["link"]
    doc["torques"][0]["moment"] = f'25*cos(angle("{loaded}"))'
    response = client.post(
        "/api/v1/sweep",
        json={"scene": doc, "samples": 720, "quantities": ["forces", "energy"]},
    )
    # a six-bar may not close over a whole turn of its driver (Newton-Raphson stops at a limit)
    assume(response.json().get("code") != "not_assemblable")
    assert response.status_code == 200, response.text
    body = response.json()
    assume(body["feasible"])
    kinetic = body["energy"]["kinetic"]
    steps = [abs(b - a) for a, b in zip(kinetic, kinetic[1:] + kinetic[:1], strict=True)]
    assume(max(steps) <= 0.02 * (max(kinetic) - min(kinetic)))
    cycle = body["cycle"]
    work = sum(cycle["work"].values())
    torque = body["drivers"][0]["torque"]
    scale = max(abs(x) for x in torque) * abs(doc["drivers"][0]["omega"])
    assert cycle["mean_power"] == pytest.approx(-work / cycle["period"], abs=1e-8 * scale)
    assert cycle["period"] == pytest.approx(2 * math.pi / abs(doc["drivers"][0]["omega"]))

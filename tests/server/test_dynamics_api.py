"""The dynamics-v1 additions to /analyze and /sweep: shapes, defaults, and bad input as 422s."""

from __future__ import annotations

import copy
from typing import Any

import pytest
from fastapi.testclient import TestClient

from tests.dynamics_cases import seed004_scene, square_five_bar


def post(client: TestClient, path: str, body: dict[str, Any]) -> Any:
    return client.post(f"/api/v1/{path}", json=body)


def test_the_default_quantities_stay_kinematic(client: TestClient) -> None:
    """A scene with masses answers the kinematic default as before: no forces unless asked."""
    body = post(client, "analyze", {"scene": seed004_scene()}).json()
    assert "drivers" not in body and "energy" not in body
    assert body["joints"] == []  # components: the slider joints only (a four-bar has none)


def test_forces_with_components_keep_the_slider_parts() -> None:
    """Every joint in the scene's order; the slider keeps its kinematic parts and gets its
    force, which is normal to the slot (frictionless)."""
    from server.app import app
    from solver.teaching.presets import build_preset

    doc = build_preset("slider_crank", {})
    doc["masses"] = {name: {"mass": 2.0, "bar": link["points"][:2]}
                     for name, link in doc["links"].items() if not link.get("ground")}  # fmt: skip
    doc["gravity"] = [0, -9.81]
    with TestClient(app) as client:
        body = post(
            client, "analyze", {"scene": doc, "quantities": ["components", "forces"]}
        ).json()
    assert [j["point"] for j in body["joints"]] == [j["point"] for j in doc["joints"]]
    slider = body["joints"][-1]
    assert slider["type"] == "slider" and "coriolis_acceleration" in slider
    axis = next(j["axis"] for j in doc["joints"] if j["type"] == "slider")
    assert abs(slider["force"][0] * axis[0] + slider["force"][1] * axis[1]) < 1e-9
    assert abs(slider["force"][1]) > 1.0


def test_a_sweep_gives_arrays_and_a_cycle(client: TestClient) -> None:
    body = post(
        client,
        "sweep",
        {"scene": seed004_scene(), "samples": 36, "quantities": ["forces", "energy"]},
    ).json()
    assert len(body["joints"][0]["force"]) == 36
    assert len(body["drivers"][0]["torque"]) == 36
    assert len(body["energy"]["equivalent_inertia"]) == 36
    assert len(body["center_of_mass"]["position"]) == 36
    assert body["cycle"]["flywheel_inertia"] is None  # no speed_fluctuation asked


def test_no_cycle_without_constant_speed(client: TestClient) -> None:
    scene = seed004_scene()
    scene["drivers"][0]["alpha"] = 1.0
    body = post(client, "sweep", {"scene": scene, "samples": 36, "quantities": ["forces"]}).json()
    assert "cycle" not in body and len(body["drivers"][0]["torque"]) == 36


def test_a_time_sweep_with_forces(client: TestClient) -> None:
    scene = seed004_scene()
    body = post(
        client,
        "sweep",
        {"scene": scene, "samples": 5, "quantities": ["forces"], "time_range": [0, 0.1]},
    ).json()
    assert len(body["frame_force"]) == 5 and "cycle" not in body


def test_power_balance_torque_is_null_at_rest(client: TestClient) -> None:
    scene = seed004_scene()
    scene["drivers"][0]["omega"] = 0.0
    body = post(client, "analyze", {"scene": scene, "quantities": ["forces", "energy"]}).json()
    assert body["drivers"][0]["torque_from_power_balance"] is None
    assert body["energy"]["equivalent_inertia"] is None
    assert body["energy"]["kinetic"] == 0.0


def _broken(change: Any) -> dict[str, Any]:
    scene = copy.deepcopy(seed004_scene())
    change(scene)
    return scene


BAD = {
    "negative mass": (lambda s: s["masses"]["crank"].update(mass=-1), "masses.crank.mass"),
    "negative inertia": (
        lambda s: s["masses"].update(crank={"mass": 1, "center": [0, 0], "inertia": -2}),
        "masses.crank.inertia",
    ),
    "mass on the ground": (
        lambda s: s["masses"].update(ground={"mass": 1, "bar": ["O", "Gamma"]}),
        "masses.ground",
    ),
    "negative point mass": (lambda s: s["point_masses"][0].update(mass=-90), "point_masses[0]"),
    "force at a point not on its link": (
        lambda s: s["forces"][0].update(point="A"),
        "forces[0].point: 'A' is not a point of link 'rocker'",
    ),
    "bar end not on the link": (
        lambda s: s["masses"]["crank"].update(bar=["O", "B"]),
        "masses.crank.bar[1]",
    ),
    "unknown link": (lambda s: s.update(torques=[{"link": "x", "moment": "1"}]), "torques[0]"),
    "gravity not a vector": (lambda s: s.update(gravity=9.81), "gravity"),
    "direction not a number": (
        lambda s: s["forces"][0].update(direction_deg="up"),
        "forces[0].direction_deg",
    ),
    "both bar and centre": (
        lambda s: s["masses"]["crank"].update(center=[0, 0]),
        "masses.crank",
    ),
}


@pytest.mark.parametrize("case", sorted(BAD))
def test_bad_dynamics_fields_are_invalid_scene(client: TestClient, case: str) -> None:
    change, where = BAD[case]
    response = post(client, "analyze", {"scene": _broken(change), "quantities": ["forces"]})
    assert response.status_code == 422, response.text
    problem = response.json()
    assert problem["code"] == "invalid_scene"
    assert where in problem["detail"]


@pytest.mark.parametrize(
    ("magnitude", "position"),
    [('where(omega("rocker") == 0, 1, 0)', 22), ('angle("nowhere")', 7), ("1 +", 3)],
)
def test_bad_load_expressions_are_invalid_expression(
    client: TestClient, magnitude: str, position: int
) -> None:
    scene = _broken(lambda s: s["forces"][0].update(magnitude=magnitude))
    response = post(client, "analyze", {"scene": scene, "quantities": ["forces"]})
    assert response.status_code == 422, response.text
    problem = response.json()
    assert problem["code"] == "invalid_expression"
    assert problem["position"] == position
    assert problem["detail"].startswith("forces[0].magnitude")


def test_an_expression_undefined_in_the_motion_is_a_422(client: TestClient) -> None:
    scene = _broken(lambda s: s["forces"][0].update(magnitude='log(angle("rocker") - 10)'))
    response = post(client, "analyze", {"scene": scene, "quantities": ["forces"]})
    assert response.status_code == 422
    assert response.json()["code"] == "invalid_expression"
    assert response.json()["detail"].startswith("forces[0].magnitude: ")


def test_forces_of_a_spatial_chain_are_refused(client: TestClient) -> None:
    from tests.server.test_solution import example

    response = post(
        client, "analyze", {"scene": example("S002-spatial-arm"), "quantities": ["forces"]}
    )
    assert response.status_code == 422
    assert "planar linkages" in response.json()["detail"]


def test_two_drivers_each_get_their_virtual_power_torque(client: TestClient) -> None:
    """The five-bar worked by hand in tests/solver/dynamics/test_virtual_power.py, over HTTP: T_1 =
    -m (g - w^2) / 2 and T_2 = +m (g - w^2) / 2, from Newton-Euler and from virtual power."""
    w, m, g = 1.5, 4.0, 9.81
    body = post(
        client, "analyze", {"scene": square_five_bar(w, m, g), "quantities": ["forces"]}
    ).json()
    expected = [-m * (g - w**2) / 2, m * (g - w**2) / 2]
    for driver, torque in zip(body["drivers"], expected, strict=True):
        assert driver["torque"] == pytest.approx(torque, rel=1e-12)
        assert driver["torque_from_power_balance"] == pytest.approx(torque, rel=1e-12)

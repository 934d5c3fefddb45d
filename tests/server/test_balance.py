"""POST /api/v1/balance: the balanced four-bar's centre of mass stays still over a revolution,
for random four-bars with random bodies (centres off the links' lines too) and point masses; a
linkage that cannot be balanced this way is a 422."""

from __future__ import annotations

import math
from typing import Any

import numpy as np
import pytest
from fastapi.testclient import TestClient
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from solver.teaching.presets import build_preset
from tests.dynamics_cases import seed004_scene, with_masses_and_loads
from tests.linkage_strategies import linkages

WEIGHTS = [{"link": "crank", "mass": 5.0}, {"link": "rocker", "mass": 7.0}]


def balance(client: TestClient, scene: dict[str, Any], weights: Any = WEIGHTS) -> Any:
    return client.post("/api/v1/balance", json={"scene": scene, "counterweights": weights})


@pytest.mark.slow
@settings(max_examples=10, deadline=None, database=None, suppress_health_check=list(HealthCheck))
@given(data=st.data())
def test_the_balanced_centre_of_mass_stays_still(client: TestClient, data: st.DataObject) -> None:
    """Over a sweep of the balanced scene the centre of mass stays at the answer's point (1e-9 of
    the size), so the frame force is the weights and loads alone; the unbalanced one moves."""
    doc = data.draw(linkages("four_bar").flatmap(with_masses_and_loads))
    response = balance(client, doc)
    assert response.status_code == 200, response.text
    body = response.json()
    xy = np.array(list(doc["points"].values()))
    size = float(np.ptp(xy, axis=0).max())
    sweep = client.post(
        "/api/v1/sweep",
        json={"scene": body["scene"], "samples": 48, "quantities": ["position", "energy"]},
    ).json()
    centre = np.array(sweep["center_of_mass"]["position"])
    assert np.abs(centre - body["center_of_mass"]).max() <= 1e-9 * max(size, 1.0)
    assert sweep["center_of_mass"]["mass"] == pytest.approx(body["mass"])
    for weight in body["counterweights"]:
        ends = doc["links"][weight["link"]]["points"]
        u = np.subtract(doc["points"][ends[1]], doc["points"][ends[0]])
        u /= np.hypot(*u)
        r = np.subtract(weight["position"], doc["points"][weight["pivot"]])
        assert weight["distance"] == pytest.approx(float(r @ u), abs=1e-12 * size)
        assert math.hypot(weight["distance"], weight["offset"]) == pytest.approx(
            float(np.hypot(*r)), abs=1e-12 * size
        )


def test_the_counterweights_are_the_textbooks_points_k_and_l(client: TestClient) -> None:
    """Seed 004 balanced: the counterweights are new points K on the crank and L on the rocker,
    at the answer's positions, with point masses mK and mL of the masses asked for."""
    body = balance(client, seed004_scene()).json()
    scene = body["scene"]
    for weight, point in zip(body["counterweights"], ("K", "L"), strict=True):
        assert scene["points"][point] == pytest.approx(weight["position"], abs=1e-12)
        assert point in scene["links"][weight["link"]]["points"]
        masses = [m for m in scene["point_masses"] if m["point"] == point]
        assert masses == [
            {"name": f"m{point}", "link": weight["link"], "point": point, "mass": weight["mass"]}
        ]


def test_the_unbalanced_seed_moves_its_centre_of_mass(client: TestClient) -> None:
    sweep = client.post(
        "/api/v1/sweep",
        json={"scene": seed004_scene(), "samples": 24, "quantities": ["energy"]},
    ).json()
    assert np.ptp(np.array(sweep["center_of_mass"]["position"]), axis=0).max() > 0.1


def _slider_crank() -> dict[str, Any]:
    doc = build_preset("slider_crank", {})
    doc["masses"] = {
        "crank": {"mass": 1, "bar": ["A", "B"]},
        "coupler": {"mass": 1, "bar": ["B", "C"]},
    }
    return doc


@pytest.mark.parametrize(
    ("scene", "weights", "detail"),
    [
        (
            _slider_crank(),
            [{"link": "crank", "mass": 1}, {"link": "coupler", "mass": 1}],
            "four-bar",
        ),
        (
            {k: v for k, v in seed004_scene().items() if k != "masses"},
            [*WEIGHTS[:1], {"link": "rocker", "mass": 1}],
            "masses",
        ),
        (seed004_scene(), [{"link": "coupler", "mass": 1}, WEIGHTS[1]], "does not turn about"),
        (seed004_scene(), WEIGHTS[:1], "one on 'crank' and one on 'rocker'"),
        (seed004_scene(), [WEIGHTS[0], WEIGHTS[0]], "second counterweight"),
        (seed004_scene(), [{"link": "crank", "mass": -1}, WEIGHTS[1]], "mass"),
    ],
)
def test_what_cannot_be_balanced_is_a_422(
    client: TestClient, scene: Any, weights: Any, detail: str
) -> None:
    response = balance(client, scene, weights)
    assert response.status_code == 422, response.text
    assert response.json()["code"] == "invalid_scene"
    assert detail in response.json()["detail"]


def test_a_link_without_mass_data(client: TestClient) -> None:
    scene = seed004_scene()
    del scene["masses"]["coupler"]
    response = balance(client, scene)
    assert response.status_code == 422
    assert "masses.coupler" in response.json()["detail"]

"""The Newton tolerance as a user's choice: /analyze and /sweep accept ``tolerance`` (relative to
the scene size, 1e-15 .. 1e-6, default 1e-13), reject values outside with invalid_scene naming
the bounds, report it in diagnostics, and answer within it.

Source for the accuracy: the default-tolerance answer (residual at rounding), which a looser
tolerance may differ from by at most its residual times the condition number of the group.
"""

from __future__ import annotations

import numpy as np
import pytest
from fastapi.testclient import TestClient

from solver.model.scene import parse_linkage
from tests.solver.position.test_newton import TRIAD, with_angle

SIZE = parse_linkage(TRIAD).size


@pytest.mark.parametrize("route", ["/api/v1/analyze", "/api/v1/sweep"])
@pytest.mark.parametrize("tolerance", [0.0, -1e-10, 1e-16, 1e-5, 1.0])
def test_out_of_range_tolerance_is_invalid_scene(
    client: TestClient, route: str, tolerance: float
) -> None:
    response = client.post(route, json={"scene": TRIAD, "tolerance": tolerance})
    assert response.status_code == 422
    body = response.json()
    assert body["code"] == "invalid_scene"
    assert "tolerance" in body["detail"] and "1e-15" in body["detail"] and "1e-06" in body["detail"]


def test_default_tolerance_is_reported(client: TestClient) -> None:
    body = client.post("/api/v1/analyze", json={"scene": with_angle(TRIAD, 70.0)}).json()
    (group,) = body["diagnostics"]["newton"]
    assert group["relative_tolerance"] == 1e-13
    assert group["tolerance"] == pytest.approx(1e-13 * SIZE, rel=1e-12)
    assert group["residual_norm"] <= group["tolerance"]


@pytest.mark.parametrize("tolerance", [1e-15, 1e-10, 1e-6])
def test_sweep_answers_within_the_chosen_tolerance(client: TestClient, tolerance: float) -> None:
    """The reported residual is within the chosen tolerance, and the positions agree with the
    default answer to the tolerance times the group's condition number (bounded by 1e3 here:
    the tolerance is on the residual of the loop equations)."""
    request = {"scene": TRIAD, "samples": 90, "quantities": ["position", "velocity"]}
    default = client.post("/api/v1/sweep", json=request).json()
    chosen = client.post("/api/v1/sweep", json={**request, "tolerance": tolerance}).json()
    (group,) = chosen["diagnostics"]["newton"]
    assert group["relative_tolerance"] == tolerance
    assert group["residual_norm"] <= tolerance * SIZE
    assert chosen["limits"] == pytest.approx(default["limits"], abs=1e-12)
    for name in ("P1", "P2", "P3"):
        a = np.array(chosen["points"][name]["position"])
        b = np.array(default["points"][name]["position"])
        assert np.max(np.abs(a - b)) <= max(1e3 * tolerance * SIZE, 1e-13)


def test_analyze_answers_within_the_chosen_tolerance(client: TestClient) -> None:
    doc = with_angle(TRIAD, 70.0)
    default = client.post("/api/v1/analyze", json={"scene": doc}).json()
    loose = client.post("/api/v1/analyze", json={"scene": doc, "tolerance": 1e-6}).json()
    (group,) = loose["diagnostics"]["newton"]
    assert group["relative_tolerance"] == 1e-6 and group["residual_norm"] <= 1e-6 * SIZE
    a = np.array(loose["points"]["P2"]["position"])
    b = np.array(default["points"]["P2"]["position"])
    assert np.max(np.abs(a - b)) <= 1e3 * 1e-6 * SIZE

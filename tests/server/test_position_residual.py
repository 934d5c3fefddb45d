"""/analyze reports the residual of the polished position (issue 14) in
``diagnostics.position_residual`` (metres): 0 at the drawn pose (the drawn coordinates are the
answer), below 1e-30 of the size at a posed angle (the constraints evaluated in 40 digits), for
a closed-form linkage and a triad alike; /solution's results carry the same field."""

from __future__ import annotations

from fastapi.testclient import TestClient

from solver.model.scene import parse_linkage
from solver.teaching.presets import build_preset
from tests.solver.position.test_newton import TRIAD, with_angle


def test_drawn_pose_has_no_residual(client: TestClient) -> None:
    body = client.post("/api/v1/analyze", json={"scene": build_preset("four_bar", {})}).json()
    assert body["diagnostics"]["position_residual"] == 0.0


def test_posed_angle_reports_the_polished_residual(client: TestClient) -> None:
    for scene in (with_angle(build_preset("four_bar", {}), 123.4), with_angle(TRIAD, 70.0)):
        body = client.post("/api/v1/analyze", json={"scene": scene}).json()
        residual = body["diagnostics"]["position_residual"]
        assert 0.0 <= residual <= 1e-30 * parse_linkage(scene).size, residual
        solution = client.post("/api/v1/solution", json={"scene": scene}).json()
        assert solution["results"]["diagnostics"]["position_residual"] == residual

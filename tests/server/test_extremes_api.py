"""The extremes of tests/solver/analysis/test_extremes.py over HTTP: a dead centre is a 422
singular_configuration problem, a non-Grashof sweep states its feasible range."""

from __future__ import annotations

import pytest
from fastapi.testclient import TestClient

from tests.solver.analysis.test_extremes import (
    EXTENDED_DEAD_CENTRE,
    FOLDED_DEAD_CENTRE,
    S000_T1,
    T1_LIMIT,
    Doc,
)


@pytest.mark.parametrize(
    "doc", [FOLDED_DEAD_CENTRE, EXTENDED_DEAD_CENTRE], ids=["folded", "extended"]
)
def test_dead_centre_over_http_is_422_singular_configuration(client: TestClient, doc: Doc) -> None:
    """scene-v1 errors table: singular_configuration, 422, problem+json."""
    response = client.post("/api/v1/analyze", json={"scene": doc})
    assert response.status_code == 422
    assert response.headers["content-type"].startswith("application/problem+json")
    body = response.json()
    assert body["code"] == "singular_configuration"
    assert body["status"] == 422
    assert "dead centre" in body["detail"]


def test_non_grashof_sweep_over_http(client: TestClient) -> None:
    """The /sweep response states the feasible range (scene-v1): feasible false, two limits."""
    response = client.post("/api/v1/sweep", json={"scene": S000_T1["body"]["scene"], "samples": 50})
    assert response.status_code == 200
    body = response.json()
    assert body["feasible"] is False
    assert sorted(body["limits"]) == pytest.approx([-float(T1_LIMIT), float(T1_LIMIT)], abs=1e-8)
    assert len(body["driver_angle"]) == 50

"""The worked solution of a gear train over HTTP (issue 25): POST /solution answers the tabular
and formula methods with the /analyze body as ``results``; POST /solution.html prints it."""

from __future__ import annotations

import json
from pathlib import Path
from typing import Any

from fastapi.testclient import TestClient

from server.app import app
from tests.solver.solutions.test_solve import unit_floors, verify

EXAMPLE: dict[str, Any] = json.loads(
    (
        Path(__file__).resolve().parents[2] / "server" / "examples" / "G001-planetary.json"
    ).read_text()
)
client = TestClient(app)


def test_solution_of_the_planetary_example() -> None:
    response = client.post("/api/v1/solution", json={"scene": EXAMPLE, "digits": 5})
    assert response.status_code == 200, response.text
    body = response.json()
    analyze = client.post("/api/v1/analyze", json={"scene": EXAMPLE}).json()
    assert body["results"] == analyze
    assert body["method"] == "tabular" and body["digits"] == 5
    kinds = [s["kind"] for s in body["steps"]]
    assert kinds == [
        "gears.data",
        "gears.freedom",
        "gears.tabular",
        "gears.formula",
        "gears.train_value",
        "summary",
    ]
    floors = unit_floors(body["steps"])
    assert all(not verify(step, floors) for step in body["steps"])
    arm = body["steps"][3]["values"]["omega(arm)"]
    assert arm["value"] == 20.0 and arm["source"] == ["members", "arm", "omega"]


def test_printable_page_of_a_gear_train() -> None:
    page = client.post("/api/v1/solution.html", json={"scene": EXAMPLE})
    assert page.status_code == 200
    text = page.text
    for part in ("Tabular method, carrier arm", "Formula method", "<caption>Gears</caption>"):
        assert part in text
    assert "the tabular (Willis) method" in text and "<svg" in text

"""Every result's ``as_dict()`` is plain JSON data (issue 22): dicts, lists, strings, numbers,
booleans and None, which ``json.dumps`` writes with ``allow_nan=False``; it equals the JSON of the
HTTP body where the README says it is that body, and orjson writes it to the very bytes the
server sends. The result itself keeps its arrays as read-only numpy arrays.

Covered: every public entry point (analyze, sweep, sweep_time, find_event, solve) on every
bundled example and preset, the dynamics (forces and energy, a revolution's cycle, balancing) of
the seed004 preset, and every exercise type (the exercise, its check).
"""

from __future__ import annotations

import json
from pathlib import Path
from typing import Any

import numpy as np
import orjson
import pytest
from fastapi.testclient import TestClient

import solver
from solver.dynamics.balance import balance_four_bar
from solver.dynamics.body import balance_body
from solver.exercises import TYPES, generate
from solver.exercises.checking import check
from solver.teaching.presets import PRESETS

EXAMPLES = Path(__file__).resolve().parents[2] / "server" / "examples"
KINEMATIC = ["position", "velocity", "acceleration", "poles", "components"]
SAMPLES = 24


def scenes() -> dict[str, dict[str, Any]]:
    found = {p.stem: json.loads(p.read_text()) for p in sorted(EXAMPLES.rglob("*.json"))}
    for name, preset in PRESETS.items():
        found[f"preset-{name}"] = preset.build({})
    return found


SCENES = scenes()


def is_plain(value: Any) -> bool:
    """Only dict (str keys), list, str, int, float, bool and None, all the way down."""
    if isinstance(value, dict):
        return all(type(k) is str and is_plain(v) for k, v in value.items())
    if type(value) is list:
        return all(is_plain(v) for v in value)
    return type(value) in (str, int, float, bool, type(None))


def calls(doc: dict[str, Any]) -> list[tuple[str, dict[str, Any], solver.Result]]:
    """(endpoint, request, the library's result) of every entry point that takes this scene."""
    if doc["kind"] == "cam":  # one cam angle and a revolution
        at = {"scene": doc, "angle_deg": 60.0}
        return [
            ("/analyze", at, solver.analyze(doc, angle_deg=60.0)),
            ("/sweep", {"scene": doc, "samples": SAMPLES}, solver.sweep(doc, SAMPLES)),
        ]
    if doc["kind"] == "gear_train":  # speeds and torques, and its members over time
        first = next(iter(doc["inputs"]))
        torque = {"scene": doc, "input_torque": {first: 12.0}}
        swept = {"scene": doc, "samples": SAMPLES, "time_range": [0, 1]}
        return [
            ("/analyze", {"scene": doc}, solver.analyze(doc)),
            ("/analyze", torque, solver.analyze(doc, input_torque={first: 12.0})),
            ("/sweep", swept, solver.sweep_time(doc, (0, 1), SAMPLES)),
        ]
    dynamic = ["forces", "energy"] if "masses" in doc else []
    wanted = KINEMATIC + dynamic
    out: list[tuple[str, dict[str, Any], solver.Result]] = [
        ("/analyze", {"scene": doc, "quantities": wanted}, solver.analyze(doc, wanted)),
        ("/solution", {"scene": doc, "method": "loop"}, solver.solve(doc, "loop")),
    ]
    if dynamic:
        request = {"scene": doc, "method": "newton_euler"}
        out.append(("/solution", request, solver.solve(doc, "newton_euler")))
    if doc["kind"] == "linkage" and not doc.get("moving_points"):
        request = {"scene": doc, "samples": SAMPLES, "quantities": wanted}
        out.append(("/sweep", request, solver.sweep(doc, SAMPLES, wanted)))
    if doc["kind"] == "spatial_chain" or doc.get("moving_points"):
        request = {"scene": doc, "samples": SAMPLES, "time_range": [0, 1], "quantities": KINEMATIC}
        out.append(("/sweep", request, solver.sweep_time(doc, (0, 1), SAMPLES, KINEMATIC)))
    for moving in doc.get("moving_points") or []:
        # The point it starts from (found fast; a target it never reaches is searched for long).
        event = {"moving_point": moving["name"], "reaches": moving["path"]["start"]}
        try:
            result = solver.find_event(doc, event["moving_point"], event["reaches"])
        except solver.NoEvent:
            continue
        out.append(("/events", {"scene": doc, "event": event}, result))
    return out


@pytest.mark.parametrize("name", sorted(SCENES))
def test_as_dict_is_plain_json_and_the_http_body(client: TestClient, name: str) -> None:
    for endpoint, request, result in calls(SCENES[name]):
        body = result.as_dict()
        assert is_plain(body), endpoint
        json.dumps(body, allow_nan=False)
        response = client.post(f"/api/v1{endpoint}", json=request)
        assert response.status_code == 200, (endpoint, response.text)
        assert response.json() == body, endpoint
        assert orjson.dumps(body) == response.content, endpoint


def test_a_sweep_keeps_its_arrays_and_gives_lists() -> None:
    cycle = solver.sweep(SCENES["S000-T1"], SAMPLES, ["position", "velocity"])
    omega = cycle["links"]["rocker"]["omega"]
    assert isinstance(omega, np.ndarray) and not omega.flags.writeable
    assert cycle["points"]["C"]["position"].shape == (SAMPLES, 2)
    body = cycle.as_dict()
    assert body["links"]["rocker"]["omega"] == omega.tolist()
    assert body["points"]["C"]["position"] == cycle["points"]["C"]["position"].tolist()
    with_arrays = cycle.as_dict(arrays=True)
    np.testing.assert_array_equal(with_arrays["links"]["rocker"]["omega"], omega)
    assert orjson.dumps(with_arrays, option=orjson.OPT_SERIALIZE_NUMPY) == orjson.dumps(body)


def test_the_dynamics_of_a_revolution_are_plain_json(client: TestClient) -> None:
    doc = SCENES["preset-seed004"]
    result = solver.sweep(doc, 72, ["forces", "energy"], speed_fluctuation=0.04)
    body = result.as_dict()
    assert "cycle" in body and is_plain(body)
    json.dumps(body, allow_nan=False)
    request = {"scene": doc, "samples": 72, "quantities": ["forces", "energy"]}
    response = client.post("/api/v1/sweep", json={**request, "speed_fluctuation": 0.04})
    assert response.status_code == 200, response.text
    assert response.json() == body


def test_a_balance_is_plain_json(client: TestClient) -> None:
    doc = SCENES["preset-seed004"]
    links = solver.analyze(doc, ["position"])["four_bar_loops"][0]["links"]
    weights = [(links["crank"], 2.0), (links["rocker"], 3.0)]
    body = balance_body(balance_four_bar(solver.parse_scene(doc), doc, weights))
    assert is_plain(body)
    json.dumps(body, allow_nan=False)
    counterweights = [{"link": link, "mass": mass} for link, mass in weights]
    response = client.post("/api/v1/balance", json={"scene": doc, "counterweights": counterweights})
    assert response.status_code == 200, response.text
    assert response.json() == body


@pytest.mark.parametrize("kind", sorted(TYPES))
def test_an_exercise_and_its_check_are_plain_json(client: TestClient, kind: str) -> None:
    (exercise,) = generate(kind, "standard", 7, 1)
    body = exercise.as_json()
    assert is_plain(body)
    json.dumps(body, allow_nan=False)
    request = {"type": kind, "difficulty": "standard", "seed": 7, "count": 1}
    response = client.post("/api/v1/exercises", json=request)
    assert response.status_code == 200, response.text
    assert response.json() == {"exercises": [body]}
    answers = {key: -2.0 * value for key, value in exercise.answers.items()}
    graded = check(str(exercise.id), answers)
    assert is_plain(graded)
    json.dumps(graded, allow_nan=False)
    response = client.post(
        "/api/v1/exercises/check", json={"id": str(exercise.id), "answers": answers}
    )
    assert response.json() == graded

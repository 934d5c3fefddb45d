"""Exercises over the API (exercises-v1): every type and difficulty, answers against /analyze.

For each type and difficulty ``EXERCISE_COUNT`` exercises (default 50; the documented long run
sets ``KT_EXERCISE_COUNT=1000``): the scene answers /analyze, the answer at each path of that
response (or /events' time) equals the key to 1e-12, and the exercise is well-posed as the
response itself tells: no dead centre (condition number), a Grashof crank-rocker with a good
transmission angle where it is a four-bar, answers that are finite and clearly non-zero.
"""

from __future__ import annotations

import math
import os
from typing import Any

import pytest
from fastapi.testclient import TestClient

from solver.exercises import DIFFICULTIES, TYPES, ExerciseId, build
from solver.exercises.answers import DYNAMIC_ROOTS, STATICS, parse_sweep_root
from solver.exercises.cams import parse_cam_root
from solver.exercises.mistakes import typical_mistakes
from solver.exercises.model import within

EXERCISE_COUNT = int(os.environ.get("KT_EXERCISE_COUNT", "50"))
API = "/api/v1"


def at_path(body: Any, path: str) -> float:
    node = body
    for part in path.split("."):
        node = node[int(part)] if isinstance(node, list) else node[part]
    assert isinstance(node, float | int), (path, node)
    return float(node)


def remote_value(
    client: TestClient, scene: dict[str, Any], path: str, cache: dict[str, Any]
) -> float:
    if path.startswith("events."):
        _, moving, target, field = path.split(".")
        r = client.post(
            f"{API}/events",
            json={"scene": scene, "event": {"moving_point": moving, "reaches": target}},
        )
        assert r.status_code == 200, r.text
        return at_path(r.json(), field)
    root, _, rest = path.partition(".")
    angle = parse_cam_root(root)
    if angle is not None:  # a cam at a cam angle
        if root not in cache:
            r = client.post(f"{API}/analyze", json={"scene": scene, "angle_deg": angle})
            assert r.status_code == 200, r.text
            cache[root] = r.json()
        return at_path(cache[root], rest)
    sweep = parse_sweep_root(root)
    if sweep is not None:  # a cycle figure of /sweep (dynamics exercises)
        if root not in cache:
            samples, k = sweep
            request = {"scene": scene, "samples": samples, "quantities": ["forces"]}
            r = client.post(f"{API}/sweep", json=request | {"speed_fluctuation": k})
            assert r.status_code == 200, r.text
            cache[root] = r.json()
        return at_path(cache[root], rest)
    if root == STATICS:  # the static force analysis: /analyze with "statics": true
        if root not in cache:
            request = {"scene": scene, "quantities": ["forces"], "statics": True}
            r = client.post(f"{API}/analyze", json=request)
            assert r.status_code == 200, r.text
            cache[root] = r.json()
        return at_path(cache[root], rest)
    dynamic = root in DYNAMIC_ROOTS or path.split(".")[2:3] == ["force"]
    key = "analyze-forces" if dynamic else "analyze"
    if key not in cache:
        quantities = ["position", "velocity", "acceleration", "forces", "energy"]
        r = client.post(
            f"{API}/analyze",
            json={"scene": scene} | ({"quantities": quantities} if dynamic else {}),
        )
        assert r.status_code == 200, r.text
        cache[key] = r.json()
    return at_path(cache[key], path)


def assert_well_posed(exercise: dict[str, Any], analyzed: dict[str, Any] | None) -> None:
    for value in exercise["answers"].values():
        assert math.isfinite(value) and 1e-3 <= abs(value) <= 1e4, exercise["id"]
    assert {a["key"] for a in exercise["asked"]} == set(exercise["answers"])
    if analyzed is None:  # a spatial chain has no dead centres
        return
    assert analyzed["diagnostics"]["condition_number"] <= 60.0, exercise["id"]
    for loop in analyzed["four_bar_loops"]:
        assert loop["grashof"] == "Grashof crank-rocker"
        assert 35.0 <= loop["transmission_angle_deg"] <= 145.0, exercise["id"]


@pytest.mark.slow
@pytest.mark.parametrize("difficulty", DIFFICULTIES)
@pytest.mark.parametrize("kind", list(TYPES))
def test_answers_equal_analyze_at_their_paths(
    client: TestClient, kind: str, difficulty: str
) -> None:
    r = client.post(
        f"{API}/exercises",
        json={
            "type": kind,
            "count": min(EXERCISE_COUNT, 100),
            "seed": 11,
            "difficulty": difficulty,
        },
    )
    assert r.status_code == 200, r.text
    exercises = r.json()["exercises"]
    for start in range(100, EXERCISE_COUNT, 100):  # the long run: further batches by seed
        more = client.post(
            f"{API}/exercises",
            json={"type": kind, "count": min(100, EXERCISE_COUNT - start), "seed": 11 + start,
                  "difficulty": difficulty},
        )  # fmt: skip
        exercises += more.json()["exercises"]
    assert len(exercises) == EXERCISE_COUNT
    for e in exercises:
        assert e["id"] == f"{kind}:{difficulty}:{e['seed']}:{e['index']}"
        assert e["statement"]["figure_svg"].startswith("<svg")
        cache: dict[str, Any] = {}
        if "task" in e:  # a synthesis exercise: its paths point into /synthesis of its task
            r = client.post(f"{API}/synthesis", json=e["task"])
            assert r.status_code == 200, r.text
            for asked in e["asked"]:
                expected = at_path(r.json(), asked["path"])
                assert abs(e["answers"][asked["key"]] - expected) <= 1e-12 * max(1.0, abs(expected))
            assert_well_posed(e, None)
            continue
        for asked in e["asked"]:
            expected = remote_value(client, e["scene"], asked["path"], cache)
            assert abs(e["answers"][asked["key"]] - expected) <= 1e-12 * max(1.0, abs(expected))
            assert 0 < asked["tolerance"] < 0.1 and asked["unit"]
        if e["scene"]["kind"] == "linkage" and "analyze" not in cache:
            cache["analyze"] = client.post(f"{API}/analyze", json={"scene": e["scene"]}).json()
        assert_well_posed(e, cache.get("analyze") if e["scene"]["kind"] == "linkage" else None)


def test_types_list_every_type_with_difficulties_and_asks(client: TestClient) -> None:
    body = client.get(f"{API}/exercises/types").json()
    names = [t["name"] for t in body["types"]]
    assert names == list(TYPES)
    for t in body["types"]:
        assert t["difficulties"] == ["basic", "standard", "challenging"]
        assert t["asks"] and t["title"] and t["description"]


def test_an_id_gives_the_same_exercise_on_its_own_and_in_a_batch(client: TestClient) -> None:
    batch = client.post(
        f"{API}/exercises", json={"type": "slider_crank", "count": 3, "seed": 7}
    ).json()["exercises"]
    alone = client.get(f"{API}/exercises/slider_crank:standard:7:2").json()
    assert alone["id"] == "slider_crank:standard:7:2"
    assert {k: v for k, v in alone.items() if k != "solution"} == batch[2]
    assert [s["title"] for s in alone["solution"]["steps"]]


def test_with_solutions_adds_the_worked_solution_and_the_event_step(client: TestClient) -> None:
    body = client.post(
        f"{API}/exercises",
        json={"type": "moving_point", "seed": 3, "difficulty": "standard", "with_solutions": True},
    ).json()["exercises"][0]
    steps = body["solution"]["steps"]
    assert steps[-1]["kind"] == "event.time"
    assert steps[-1]["values"]["t"]["value"] == body["answers"]["t_M_T"]


@pytest.mark.parametrize(
    ("request_body", "code"),
    [
        ({"type": "nope"}, "invalid_scene"),
        ({"type": "four_bar_velocity", "difficulty": "hard"}, "invalid_scene"),
        ({"type": "four_bar_velocity", "count": 0}, "limit_exceeded"),
        ({"type": "four_bar_velocity", "count": 101}, "limit_exceeded"),
        ({"type": "four_bar_velocity", "seed": -1}, "invalid_scene"),
        ({"type": "four_bar_velocity", "seed": 1.5}, "invalid_scene"),
        ({"type": "four_bar_velocity", "colour": "red"}, "invalid_scene"),
    ],
)
def test_bad_requests_are_problems(
    client: TestClient, request_body: dict[str, Any], code: str
) -> None:
    r = client.post(f"{API}/exercises", json=request_body)
    status = 413 if code == "limit_exceeded" else 422  # limit_exceeded is always 413
    assert r.status_code == status and r.json()["code"] == code, r.text


@pytest.mark.parametrize(
    "bad_id", ["nope", "four_bar_velocity:standard:7", "x:standard:1:0", "four_bar_velocity:x:1:0"]
)
def test_unknown_ids_are_invalid_scene(client: TestClient, bad_id: str) -> None:
    r = client.get(f"{API}/exercises/{bad_id}")
    assert r.status_code == 422 and r.json()["code"] == "invalid_scene", r.text


@pytest.mark.parametrize(
    ("kind", "mistake"),
    [
        ("inverted_slider_crank", "coriolis_left_out"),
        ("quick_return", "coriolis_without_factor_2"),
        ("slider_crank", "coriolis_on_fixed_guide"),
        ("moving_point", "coriolis_left_out"),
        ("spatial_arm", "rotation_sign"),
        ("four_bar_velocity", "rotation_sign"),
        ("four_bar_velocity", "degrees_for_radians"),
        ("four_bar_acceleration", "alpha_in_normal_term"),
    ],
)
def test_named_mistakes_over_the_api(client: TestClient, kind: str, mistake: str) -> None:
    """The diagnosis as a client sees it: the sentence names the mistake."""
    e = build(ExerciseId(kind, "challenging", 8, 0))
    made = next(m for m in typical_mistakes(e) if m.kind == mistake)
    key, wrong = next(
        (k, v)
        for k, v in made.values.items()
        if not within(v, e.answers[k], 0.01) and not within(v, abs(e.answers[k]), 0.01)
    )  # a sign mistake on a negative answer is also its magnitude, named first: not that one
    r = client.post("/api/v1/exercises/check", json={"id": str(e.id), "answers": {key: wrong}})
    assert r.status_code == 200, r.text
    body = r.json()
    assert body["id"] == str(e.id) and body["score"] == 0.0
    row = next(x for x in body["results"] if x["key"] == key)
    assert row["verdict"] == "incorrect" and row["mistake"] == mistake
    assert row["given"] == wrong and row["expected"] == e.answers[key]
    assert row["diagnosis"].startswith("This is")
    missing = [x["verdict"] for x in body["results"] if x["key"] != key]
    assert set(missing) == {"missing"}


def test_check_rejects_unknown_ids_and_keys(client: TestClient) -> None:
    for body, word in (
        ({"id": "nope", "answers": {}}, "id"),
        ({"id": "four_bar_velocity:standard:7:0", "answers": {"x": 1.0}}, "unknown key"),
        ({"id": "four_bar_velocity:standard:7:0", "answers": {"omega_coupler": "a"}}, "answers"),
        ({"id": "four_bar_velocity:standard:7:0", "answers": {"omega_coupler": 1e308}}, "answers"),
    ):
        r = client.post(f"{API}/exercises/check", json=body)
        assert r.status_code == 422 and r.json()["code"] == "invalid_scene", r.text
        assert word in r.json()["detail"]


def test_a_huge_seed_is_a_seed_like_any_other(client: TestClient) -> None:
    seed = 2**63 - 1
    r = client.post(f"{API}/exercises", json={"type": "spatial_arm", "seed": seed})
    assert r.status_code == 200, r.text
    assert r.json()["exercises"][0]["id"] == f"spatial_arm:standard:{seed}:0"
    r = client.post(f"{API}/exercises", json={"type": "spatial_arm", "seed": seed + 1})
    assert r.status_code == 422 and r.json()["code"] == "invalid_scene"


@pytest.mark.parametrize(
    "kind", ["synthesis_function", "synthesis_fixed_pivots", "synthesis_two_positions"]
)
def test_synthesis_types_are_served_and_keyed_by_the_synthesis_body(
    client: TestClient, kind: str
) -> None:
    """Listed, generated, served by id and checked through the exercises contract; the key is
    the /synthesis body of the exercise's task at each path."""
    listed = {t["name"]: t for t in client.get(f"{API}/exercises/types").json()["types"]}
    assert listed[kind]["asks"]
    e = client.post(f"{API}/exercises", json={"type": kind, "seed": 12}).json()["exercises"][0]
    assert "scene" not in e and e["task"]["task"] in ("function", "motion")
    body = client.post(f"{API}/synthesis", json=e["task"]).json()
    for asked in e["asked"]:
        assert e["answers"][asked["key"]] == at_path(body, asked["path"])
    alone = client.get(f"{API}/exercises/{e['id']}").json()
    assert alone["task"] == e["task"] and alone["solution"]["steps"][0]["kind"].startswith(
        "synthesis."
    )
    first = e["asked"][0]["key"]
    wrong = client.post(
        f"{API}/exercises/check", json={"id": e["id"], "answers": {first: 2 * e["answers"][first]}}
    ).json()
    assert wrong["results"][0]["verdict"] == "incorrect" and wrong["score"] == 0.0

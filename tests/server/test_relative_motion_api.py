"""HTTP tests of composite motion (scene-v1 ``moving_points``), ``POST /api/v1/events``, time
sweeps, and hostile time laws (issue 3, "Prove it").

Sources: the seed-003 reference cases of tests/reference/seed-cases.json (compared with a
tolerance of 1e-6 relative to the largest magnitude of the same unit group in the case, at least
1) and the errata of ../shared/reference/ERRATA.md, section "Seed 003" (E003-*); the spec
../shared/spec/scene-v1.md for the shapes and error codes.

The fixtures ``client`` (TestClient) and ``live_server`` (base URL of a uvicorn on loopback) of
tests/conftest.py are used when they exist; otherwise a module-level TestClient serves.
"""

from __future__ import annotations

import copy
import json
import math
import multiprocessing
import time
from pathlib import Path
from typing import Any

import httpx
import numpy as np
import pytest
from fastapi.testclient import TestClient

from server.app import app

CASES = Path(__file__).resolve().parents[1] / "reference" / "seed-cases.json"
PROBLEM = "application/problem+json"
_LOCAL: TestClient | None = None


def _local_client() -> TestClient:
    global _LOCAL
    if _LOCAL is None:
        _LOCAL = TestClient(app)
    return _LOCAL


@pytest.fixture
def api(request: pytest.FixtureRequest) -> Any:
    """The shared ``client`` fixture if tests/conftest.py defines it, else our own TestClient."""
    try:
        return request.getfixturevalue("client")
    except pytest.FixtureLookupError:
        return _local_client()


@pytest.fixture
def hostile_api(request: pytest.FixtureRequest) -> Any:
    """The live server (real sockets, real worker threads) when the fixture exists."""
    try:
        base_url = request.getfixturevalue("live_server")
    except pytest.FixtureLookupError:
        yield _local_client()
        return
    with httpx.Client(base_url=str(base_url), timeout=30.0) as live:
        yield live


def _cases() -> dict[str, dict[str, Any]]:
    return {c["id"]: c for c in json.loads(CASES.read_text())["cases"]}


S003 = {k: v for k, v in _cases().items() if k.startswith("S003")}
T1, T2 = S003["S003-T1-translating-carrier"], S003["S003-T2-rotating-carrier"]


def _get(body: Any, path: str) -> Any:
    """A response field by the reference path syntax ("moving_points.M.velocity", "a[0].b")."""
    node = body
    for part in path.split("."):
        name, _, index = part.partition("[")
        node = node[name]
        if index:
            node = node[int(index.rstrip("]"))]
    return node


def _group_scales(case: dict[str, Any]) -> dict[str, float]:
    scale: dict[str, float] = {}
    for request in case["requests"]:
        for e in request["expected"]:
            magnitude = float(np.max(np.abs(np.asarray(e["value"], dtype=float))))
            scale[e["kind"]] = max(scale.get(e["kind"], 1.0), magnitude)
    return scale


def _post_ok(api: Any, path: str, body: dict[str, Any]) -> dict[str, Any]:
    response = api.post(path, json=body)
    assert response.status_code == 200, response.text
    return dict(response.json())


def _problem(response: Any, status: int, code: str) -> dict[str, Any]:
    assert response.status_code == status, response.text
    assert response.headers["content-type"].startswith(PROBLEM)
    body = dict(response.json())
    assert body["code"] == code, body
    assert body["status"] == status
    for key in ("type", "title", "detail"):
        assert isinstance(body[key], str) and body[key], key
    return body


# --- reference cases S003 through HTTP ---

REQUESTS = [
    pytest.param(case_id, i, id=f"{case_id}-{i}-{r['endpoint'].split('/')[-1]}")
    for case_id, case in S003.items()
    for i, r in enumerate(case["requests"])
]


@pytest.mark.parametrize(("case_id", "index"), REQUESTS)
def test_seed_003_requests_match_reference(api: Any, case_id: str, index: int) -> None:
    """Every analyze and events request of S003-T1 and S003-T2, unchanged; tolerance 1e-6
    relative to the largest magnitude of the same unit group in the case (at least 1)."""
    case = S003[case_id]
    request = case["requests"][index]
    scale = _group_scales(case)
    body = _post_ok(api, request["endpoint"].split()[1], request["body"])
    for e in request["expected"]:
        got = np.asarray(_get(body, e["path"]), dtype=float)
        np.testing.assert_allclose(
            got, e["value"], rtol=0, atol=1e-6 * scale[e["kind"]], err_msg=f"{case_id} {e['path']}"
        )


def _analyze_t1_at_1s(api: Any) -> dict[str, Any]:
    body = {"scene": T1["requests"][0]["body"]["scene"]}
    return _post_ok(api, "/api/v1/analyze", body)


def _analyze_t2_at_1s(api: Any) -> dict[str, Any]:
    return _post_ok(api, "/api/v1/analyze", {"scene": T2["requests"][0]["body"]["scene"]})


def test_errata_E003_1_relative_tangential_acceleration_direction(api: Any) -> None:
    """E003-1: M runs clockwise about D (from O over the top to A), so a_rel^tau = R theta''
    (sin theta, cos theta), along v_rel: at t = 1 s +(0.3265, 0.1885) m/s^2, not the seed's
    (-0.3265, -0.1885). Closed form with R = 0.18 m, theta = 6 pi t^2 / 18 (t = 1: theta = pi/3,
    theta'' = 2 pi / 3). Tolerance 1e-9 m/s^2 (closed form) and the erratum's 4 digits."""
    m = _analyze_t1_at_1s(api)["moving_points"]["M"]
    theta, theta_dd = math.pi / 3, 2 * math.pi / 3
    want = 0.18 * theta_dd * np.array([math.sin(theta), math.cos(theta)])
    np.testing.assert_allclose(m["relative_tangential"], want, rtol=0, atol=1e-9)
    np.testing.assert_allclose(m["relative_tangential"], [0.3265, 0.1885], rtol=0, atol=5e-5)
    assert float(np.dot(m["relative_tangential"], m["relative_velocity"])) > 0  # along v_rel
    assert m["s_ddot"] > 0


def test_errata_E003_2_3_transport_acceleration_of_task_1(api: Any) -> None:
    """E003-2/3: a_tr = eps x O1O (cos phi, sin phi) - w^2 O1O (cos phi, sin phi), with the
    length O1O = 0.2 m and the angle phi (not theta); phi = pi t^3 / 6: at t = 1 s phi = pi/6,
    w = pi/2, eps = pi. The carrier translates, so a_tr is the crank pin's acceleration.
    Tolerance 1e-9 m/s^2."""
    m = _analyze_t1_at_1s(api)["moving_points"]["M"]
    phi, w, eps = math.pi / 6, math.pi / 2, math.pi
    e = np.array([math.cos(phi), math.sin(phi)])
    tangential, normal = 0.2 * eps * np.array([-e[1], e[0]]), -(w**2) * 0.2 * e
    np.testing.assert_allclose(m["transport_acceleration"], tangential + normal, atol=1e-9)
    np.testing.assert_allclose(m["transport_tangential"], tangential, atol=1e-9)
    np.testing.assert_allclose(m["transport_normal"], normal, atol=1e-9)


def test_errata_E003_4_5_6_rotating_carrier_parts(api: Any) -> None:
    """E003-4: v_rel excludes the carrier rate: (1.63559, 0.21251) m/s, not (2.05209, 0.26662).
    E003-5: v_tr = phi' k x O1M = (0.47061, -0.36238) m/s, not (0.07653, -0.58902); v_abs =
    (2.10620, -0.14988) m/s. E003-6: a_rel = (0.23361, 9.17427), a_cor = (-0.59502, 4.57965),
    a_abs = (-0.05577, 14.56808) m/s^2. Tolerance: half a unit of the erratum's 5th decimal."""
    m = _analyze_t2_at_1s(api)["moving_points"]["M"]
    atol = 5e-6
    np.testing.assert_allclose(m["relative_velocity"], [1.63559, 0.21251], rtol=0, atol=atol)
    assert not np.allclose(m["relative_velocity"], [2.05209, 0.26662], atol=1e-3)
    np.testing.assert_allclose(m["transport_velocity"], [0.47061, -0.36238], rtol=0, atol=atol)
    assert not np.allclose(m["transport_velocity"], [0.07653, -0.58902], atol=1e-3)
    np.testing.assert_allclose(m["velocity"], [2.10620, -0.14988], rtol=0, atol=atol)
    np.testing.assert_allclose(m["relative_acceleration"], [0.23361, 9.17427], rtol=0, atol=atol)
    np.testing.assert_allclose(m["coriolis_acceleration"], [-0.59502, 4.57965], rtol=0, atol=atol)
    np.testing.assert_allclose(m["acceleration"], [-0.05577, 14.56808], rtol=0, atol=atol)
    # v_tr = phi' k x O1M with phi' = 2 - 0.6 t = 1.4 rad/s at t = 1 s (O1 = P at the origin).
    x, y = m["position"]
    np.testing.assert_allclose(m["transport_velocity"], [-1.4 * y, 1.4 * x], rtol=0, atol=1e-12)
    assert m["omega_carrier"] == pytest.approx(1.4, abs=1e-12)


def test_errata_E003_7_no_coriolis_on_the_translating_carrier(api: Any) -> None:
    """E003-7: phi' and phi'' are the crank's rates (pi/2 rad/s and pi rad/s^2 at t = 1 s); the
    carrier OA translates (omega = alpha = 0), hence a_cor = 0. Tolerance 1e-12."""
    for request in T1["requests"][:2]:
        body = _post_ok(api, "/api/v1/analyze", request["body"])
        m = body["moving_points"]["M"]
        t = request["body"]["scene"]["time"]
        np.testing.assert_allclose(m["coriolis_acceleration"], [0.0, 0.0], rtol=0, atol=1e-12)
        assert abs(m["omega_carrier"]) <= 1e-12 and abs(m["alpha_carrier"]) <= 1e-12
        assert abs(body["links"]["carrier"]["omega"]) <= 1e-12
        assert body["links"]["crank1"]["omega"] == pytest.approx(math.pi / 2 * t**2, abs=1e-9)
        assert body["links"]["crank1"]["alpha"] == pytest.approx(math.pi * t, abs=1e-9)


def test_moving_point_fields_follow_the_requested_quantities(api: Any) -> None:
    """Spec: the server computes and returns only what is asked; position-only gives M's
    position (same value as the full request, tolerance 1e-12) and no velocity."""
    scene = T2["requests"][0]["body"]["scene"]
    full = _post_ok(api, "/api/v1/analyze", {"scene": scene})["moving_points"]["M"]
    only = _post_ok(api, "/api/v1/analyze", {"scene": scene, "quantities": ["position"]})
    m = only["moving_points"]["M"]
    np.testing.assert_allclose(m["position"], full["position"], rtol=0, atol=1e-12)
    assert "velocity" not in m and "coriolis_acceleration" not in m


# --- events over HTTP: no_event ---


def _events_body(case: dict[str, Any], index: int, **event: Any) -> dict[str, Any]:
    body = copy.deepcopy(case["requests"][index]["body"])
    body["event"].update(event)
    return body


def test_events_target_off_the_path_is_no_event(api: Any) -> None:
    """A point of the carrier off M's circle: 422 problem+json with code no_event (spec)."""
    body = _events_body(T2, 2, reaches="Q")  # Q is the circle's centre
    _problem(api.post("/api/v1/events", json=body), 422, "no_event")


def test_events_occurrence_beyond_t_max_is_no_event(api: Any) -> None:
    """Task 1 reaches the target at sqrt(3) s (ERRATA, Seed 003): nothing by t_max = 1.7 s."""
    body = _events_body(T1, 2, t_max=1.7)
    _problem(api.post("/api/v1/events", json=body), 422, "no_event")
    found = _post_ok(api, "/api/v1/events", _events_body(T1, 2, t_max=1.8))
    assert found["time"] == pytest.approx(math.sqrt(3.0), rel=1e-6)


def test_events_position_is_the_moving_point_there(api: Any) -> None:
    """The response's position is M's position at the event time (analyze at that time,
    tolerance 1e-9 m) and coincides with the target's position there."""
    found = _post_ok(api, "/api/v1/events", T2["requests"][3]["body"])
    scene = copy.deepcopy(T2["requests"][3]["body"]["scene"]) | {"time": found["time"]}
    body = _post_ok(api, "/api/v1/analyze", {"scene": scene, "quantities": ["position"]})
    np.testing.assert_allclose(
        found["position"], body["moving_points"]["M"]["position"], rtol=0, atol=1e-9
    )
    np.testing.assert_allclose(
        found["position"], body["points"]["S"]["position"], rtol=0, atol=1e-9
    )


# --- time sweep over HTTP ---


@pytest.mark.parametrize("case", [T1, T2], ids=["T1", "T2"])
def test_time_sweep_arrays_equal_single_analyses(api: Any, case: dict[str, Any]) -> None:
    """POST /sweep with time_range: every array, sample by sample, equals POST /analyze at the
    same time (tolerance 1e-9 relative to the field's scale, at least 1)."""
    scene = case["requests"][0]["body"]["scene"]
    quantities = ["position", "velocity", "acceleration", "components"]
    sweep = _post_ok(
        api,
        "/api/v1/sweep",
        {"scene": scene, "samples": 5, "time_range": [0.5, 1.5], "quantities": quantities},
    )
    np.testing.assert_allclose(sweep["time"], np.linspace(0.5, 1.5, 5), rtol=0, atol=1e-15)
    for k, t in enumerate(sweep["time"]):
        single = _post_ok(api, "/api/v1/analyze", {"scene": scene | {"time": t}})
        for name, want in single["moving_points"]["M"].items():
            got = np.asarray(sweep["moving_points"]["M"][name][k], dtype=float)
            scale = max(1.0, float(np.max(np.abs(want))))
            np.testing.assert_allclose(got, want, rtol=0, atol=1e-9 * scale, err_msg=name)
        for name, point in single["points"].items():
            got = np.asarray(sweep["points"][name]["position"][k], dtype=float)
            np.testing.assert_allclose(got, point["position"], rtol=0, atol=1e-9, err_msg=name)


# --- hostile time laws ---

HUGE = "t+" * 49_999 + "t"  # 100 kB of an otherwise valid law
HOSTILE = [
    # (law, the positions that point at the offending character)
    pytest.param("__import__('os')", {0}, id="import"),
    pytest.param("t.real", {1}, id="attribute"),
    pytest.param("().__class__", {0, 1}, id="dunder"),
    pytest.param("lambda: 1", {0}, id="lambda"),
    pytest.param("[x for x in t]", {0}, id="comprehension"),
    pytest.param("9**9**9", {1, 3, 4}, id="power-tower"),
    pytest.param("9^9^9", {1, 2, 3}, id="caret-tower"),
    pytest.param(HUGE, set(range(len(HUGE) + 1)), id="100kB"),
    pytest.param("(t+1", {0, 4}, id="unclosed"),
    pytest.param("t+1)", {3}, id="unopened"),
    pytest.param("2*(t+(3*t)", {2, 10}, id="unclosed-nested"),
]


def _with_law(case: dict[str, Any], index: int, field: str, law: str) -> dict[str, Any]:
    body = copy.deepcopy(case["requests"][index]["body"])
    if field == "angle_law":
        body["scene"]["drivers"][0]["angle_law"] = law
    else:
        body["scene"]["moving_points"][0]["s_law"] = law
    return body


@pytest.mark.slow  # timed: its outcome depends on the machine's load
@pytest.mark.serial  # timed: run alone, after the others (tests/run.sh)
@pytest.mark.parametrize("endpoint", ["analyze", "events"])
@pytest.mark.parametrize("field", ["angle_law", "s_law"])
@pytest.mark.parametrize(("law", "positions"), HOSTILE)
def test_hostile_law_is_an_invalid_expression(
    hostile_api: Any, law: str, positions: set[int], field: str, endpoint: str
) -> None:
    """Each hostile law, as the driver's angle_law and as M's s_law, to /analyze (S003-T2 at
    t = 1 s) and /events (S003-T2, first return, t_max = 60 s): 422 problem+json, code
    invalid_expression, an integer ``position`` at the offending character, the answer in under
    1 s (measured around the request), and GET /health still answers 200 afterwards.
    The 100 kB law travels in a body well under the 1 MB limit: the server answers
    invalid_expression (422) with position 500, its law-length limit."""
    body = _with_law(T2, 0 if endpoint == "analyze" else 2, field, law)
    started = time.perf_counter()
    response = hostile_api.post(f"/api/v1/{endpoint}", json=body)
    elapsed = time.perf_counter() - started
    problem = _problem(response, 422, "invalid_expression")
    assert isinstance(problem["position"], int) and problem["position"] in positions, problem
    assert elapsed < 1.0, f"{elapsed:.3f} s"
    health = hostile_api.get("/health")
    assert health.status_code == 200 and health.json() == {"status": "ok"}


@pytest.mark.slow  # timed: its outcome depends on the machine's load
@pytest.mark.serial  # timed: run alone, after the others (tests/run.sh)
def test_law_over_the_body_limit_is_limit_exceeded(hostile_api: Any) -> None:
    """A 1.2 MB law makes the body exceed the server's 1 MB limit: 413, code limit_exceeded
    (spec: limit_exceeded, 413 or 422); the server stays healthy."""
    body = _with_law(T2, 0, "s_law", "t+" * 599_999 + "t")
    started = time.perf_counter()
    response = hostile_api.post("/api/v1/analyze", json=body)
    assert time.perf_counter() - started < 2.0
    _problem(response, 413, "limit_exceeded")
    assert hostile_api.get("/health").status_code == 200


def test_valid_requests_still_answer_after_hostile_ones(hostile_api: Any) -> None:
    """After the hostile requests above (same server), the reference request still answers
    with the reference values (tolerance 1e-6 relative to the group's scale)."""
    request = T2["requests"][0]
    body = hostile_api.post("/api/v1/analyze", json=request["body"])
    assert body.status_code == 200
    scale = _group_scales(T2)
    for e in request["expected"]:
        np.testing.assert_allclose(
            _get(body.json(), e["path"]), e["value"], rtol=0, atol=1e-6 * scale[e["kind"]]
        )


def _post_in_child(path: str, body: dict[str, Any], conn: Any) -> None:
    response = TestClient(app).post(path, json=body)
    conn.send((response.status_code, response.json()))


def test_hostile_angle_law_in_events_rejected_before_any_search() -> None:
    """/events with a hostile angle_law and a long (allowed) search horizon, t_max = 1000 s:
    the law is rejected at once (422 invalid_expression), not after the search for crossings
    (about 375 000 of them for S003 Task 2's s_law by 1000 s). Bound: 5 s. Run with a
    TestClient in a forked child that is terminated at the bound, so that a slow answer
    cannot hold up the suite or a shared server."""
    body = _with_law(T2, 2, "angle_law", "9**9**9")
    body["event"]["t_max"] = 1000.0
    ctx = multiprocessing.get_context("fork")
    parent, child = ctx.Pipe(duplex=False)
    process = ctx.Process(target=_post_in_child, args=("/api/v1/events", body, child))
    process.start()
    try:
        result = parent.recv() if parent.poll(5.0) else None
    finally:
        if process.is_alive():
            process.terminate()
        process.join(5.0)
    assert result is not None, "no answer within 5 s"
    status, problem = result
    assert status == 422 and problem["code"] == "invalid_expression", problem
    assert problem["position"] == 3

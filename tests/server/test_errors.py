"""Bad input over HTTP: every error is RFC 9457 problem+json with the scene-v1 ``code``, the right
status, a ``detail`` that says what is wrong, and never a 500.

Cases follow the errors table of scene-v1 and issue 2 ("Bad input"): unknown names, two grounds,
zero-length links, missing axes, a driver not on the ground, non-assemblable poses, non-finite
numbers, malformed and oversize requests. A hypothesis test then mutates valid scenes at random
(deleted keys, wrong types, huge and tiny numbers) and requires that no answer is a 500 and that
no 200 answer carries NaN or infinity.
"""

from __future__ import annotations

import copy
import json
import math
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import pytest
from fastapi.testclient import TestClient
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from solver.teaching.presets import build_preset

Doc = dict[str, Any]
REFERENCE = Path(__file__).resolve().parents[1] / "reference" / "seed-cases.json"
PROBLEM = "application/problem+json"
EXAMPLES = Path(__file__).resolve().parents[2] / "server" / "examples"
CODES = {
    "invalid_scene",
    "invalid_expression",
    "not_assemblable",
    "singular_configuration",
    "limit_exceeded",
    "not_found",
    "method_not_allowed",
}


def _scene(case_id: str) -> Doc:
    cases = json.loads(REFERENCE.read_text())["cases"]
    scene: Doc = next(c for c in cases if c["id"] == case_id)["requests"][0]["body"]["scene"]
    return scene


FOUR_BAR = _scene("S000-T1")  # crank, coupler, rocker; ground A-D
SLIDER = _scene("S000-T3")  # slider C on a fixed guide (joints[2])


def scene(base: Doc = FOUR_BAR) -> Doc:
    return copy.deepcopy(base)


def assert_problem(
    response: Any, status: int | tuple[int, ...], code: str | tuple[str, ...]
) -> dict[str, Any]:
    """RFC 9457 problem+json with the given status and code; returns the body."""
    statuses = status if isinstance(status, tuple) else (status,)
    codes = code if isinstance(code, tuple) else (code,)
    assert response.status_code in statuses, (response.status_code, response.text)
    assert response.headers["content-type"].startswith(PROBLEM), response.headers
    body: dict[str, Any] = response.json()
    assert body["code"] in codes, body
    assert body["status"] == response.status_code
    assert isinstance(body["title"], str) and body["title"]
    assert isinstance(body["type"], str) and body["type"]
    assert isinstance(body["detail"], str) and body["detail"]
    return body


def analyze(client: TestClient, doc: Doc, **extra: Any) -> Any:
    return client.post("/api/v1/analyze", json={"scene": doc, **extra})


# --- the scene contract: names, grounds, lengths, axes, drivers ----------------------------------


def _unknown_point_in_link(doc: Doc) -> None:
    doc["links"]["crank"]["points"] = ["A", "Zed"]


def _unknown_point_in_joint(doc: Doc) -> None:
    doc["joints"][1]["point"] = "Zed"


def _unknown_link_in_joint(doc: Doc) -> None:
    doc["joints"][1]["links"] = ["crank", "Zed"]


def _unknown_link_in_driver(doc: Doc) -> None:
    doc["drivers"][0]["link"] = "Zed"


def _two_grounds(doc: Doc) -> None:
    doc["links"]["rocker"]["ground"] = True


def _no_ground(doc: Doc) -> None:
    del doc["links"]["ground"]["ground"]


def _zero_length_link(doc: Doc) -> None:
    doc["points"]["B"] = list(doc["points"]["A"])


def _driver_not_on_the_ground(doc: Doc) -> None:
    doc["drivers"][0]["link"] = "coupler"


def _driving_the_ground(doc: Doc) -> None:
    doc["drivers"][0]["link"] = "ground"


def _no_driver(doc: Doc) -> None:
    doc["drivers"] = []


def _two_drivers(doc: Doc) -> None:
    doc["drivers"].append({"link": "rocker", "omega": 1.0})


def _unknown_joint_type(doc: Doc) -> None:
    doc["joints"][0]["type"] = "spherical"


def _joint_with_three_links(doc: Doc) -> None:
    doc["joints"][0]["links"] = ["ground", "crank", "coupler"]


def _point_in_no_link(doc: Doc) -> None:
    doc["points"]["Lonely"] = [5.0, 5.0]


CONTRACT_BREAKS = {
    "unknown point in a link": (_unknown_point_in_link, "Zed"),
    "unknown point in a joint": (_unknown_point_in_joint, "Zed"),
    "unknown link in a joint": (_unknown_link_in_joint, "Zed"),
    "unknown link in a driver": (_unknown_link_in_driver, "Zed"),
    "two grounds": (_two_grounds, "ground"),
    "no ground": (_no_ground, "ground"),
    "zero-length link": (_zero_length_link, "zero-length"),
    "driver not on the ground": (_driver_not_on_the_ground, "coupler"),
    "driving the ground": (_driving_the_ground, "ground"),
    "no driver": (_no_driver, "driver"),
    "two drivers on one degree of freedom": (_two_drivers, "degree"),
    "unknown joint type": (_unknown_joint_type, "spherical"),
    "joint with three links": (_joint_with_three_links, "two links"),
    "point in no link": (_point_in_no_link, "Lonely"),
}


@pytest.mark.parametrize("name", list(CONTRACT_BREAKS))
def test_scene_contract_breaks_are_invalid_scene(client: TestClient, name: str) -> None:
    """scene-v1: invalid_scene, 422, and ``detail`` says where (it names the culprit)."""
    mutate, mentioned = CONTRACT_BREAKS[name]
    doc = scene()
    mutate(doc)
    body = assert_problem(analyze(client, doc), 422, "invalid_scene")
    assert mentioned in body["detail"], body["detail"]


@pytest.mark.parametrize("joint_type", ["slider", "prismatic"])
def test_sliding_joint_without_axis(client: TestClient, joint_type: str) -> None:
    doc = scene(SLIDER)
    doc["joints"][2]["type"] = joint_type
    del doc["joints"][2]["axis"]
    body = assert_problem(analyze(client, doc), 422, "invalid_scene")
    assert "axis" in body["detail"]


@pytest.mark.parametrize("axis", [[0.0, 0.0], [1.0], "x", [1.0, "0"]])
def test_sliding_joint_with_a_bad_axis(client: TestClient, axis: Any) -> None:
    """A zero slot direction has no direction; a malformed one is not a vector."""
    doc = scene(SLIDER)
    doc["joints"][2]["axis"] = axis
    body = assert_problem(analyze(client, doc), 422, "invalid_scene")
    assert "axis" in body["detail"]


@pytest.mark.parametrize("kind", ["gearbox", None, 3])
def test_wrong_kind(client: TestClient, kind: Any) -> None:
    doc = scene()
    doc["kind"] = kind
    body = assert_problem(analyze(client, doc), 422, "invalid_scene")
    assert "kind" in body["detail"]


def test_sweep_of_a_spatial_chain_is_the_wrong_kind(client: TestClient) -> None:
    """/sweep turns a planar linkage's driver: a spatial chain is the wrong kind there."""
    chain = _scene("S002-spatial-arm")
    response = client.post("/api/v1/sweep", json={"scene": chain, "samples": 10})
    body = assert_problem(response, 422, "invalid_scene")
    assert "linkage" in body["detail"]


# --- poses ----------------------------------------------------------------------------------------


def test_non_assemblable_angle_shows_the_numbers(client: TestClient) -> None:
    """S000-T1 with the crank at 180 deg: B = (-1, 0), |BD| = 3.5 m > |BC| + |DC| = 2 + 1.11803 =
    3.11803 m (scene-v1: ``detail`` gives the numbers)."""
    doc = scene()
    doc["drivers"][0]["angle_deg"] = 180.0
    body = assert_problem(analyze(client, doc), 422, "not_assemblable")
    for number in ("3.5", "3.11803", "180"):
        assert number in body["detail"], body["detail"]


def test_non_assemblable_slider_pose_shows_the_numbers(client: TestClient) -> None:
    """S000-T3 with the crank at 270 deg: B = (0, -0.3), 0.54 m from the guide y = 0.24 m, more
    than the coupler's |BC| = 0.5 m."""
    doc = scene(SLIDER)
    doc["drivers"][0]["angle_deg"] = 270.0
    body = assert_problem(analyze(client, doc), 422, "not_assemblable")
    for number in ("0.54", "0.5"):
        assert number in body["detail"], body["detail"]


# --- numbers and bodies ---------------------------------------------------------------------------


@pytest.mark.parametrize("constant", ["NaN", "Infinity", "-Infinity"])
def test_non_finite_numbers_are_rejected(client: TestClient, constant: str) -> None:
    """Issue 2: finite numbers only. Python's json would read these; the API must not."""
    text = json.dumps({"scene": scene()}).replace("2.5", constant, 1)
    assert constant in text
    response = client.post(
        "/api/v1/analyze", content=text.encode(), headers={"content-type": "application/json"}
    )
    assert_problem(response, 422, "invalid_scene")


@pytest.mark.parametrize("where", ["points.A", "drivers.omega", "drivers.angle_deg", "time"])
def test_integer_too_large_for_a_float(client: TestClient, where: str) -> None:
    """JSON integers have no size limit: 10**400 is valid JSON but no float, so it is an invalid
    number (422), not an overflow inside the server (500)."""
    doc = scene()
    big = 10**400
    if where == "points.A":
        doc["points"]["A"] = [big, 0.0]
    elif where == "time":
        doc["time"] = big
    else:
        doc["drivers"][0][where.split(".")[1]] = big
    response = client.post(
        "/api/v1/analyze",
        content=json.dumps({"scene": doc}).encode(),
        headers={"content-type": "application/json"},
    )
    assert_problem(response, 422, "invalid_scene")


def test_non_finite_numbers_in_sweep_and_presets(client: TestClient) -> None:
    text = json.dumps({"scene": scene(), "samples": 10}).replace("-1.0", "NaN", 1)
    response = client.post(
        "/api/v1/sweep", content=text.encode(), headers={"content-type": "application/json"}
    )
    assert_problem(response, 422, "invalid_scene")
    response = client.post(
        "/api/v1/presets/four_bar",
        content=b'{"crank": Infinity}',
        headers={"content-type": "application/json"},
    )
    assert_problem(response, 422, "invalid_scene")


@pytest.mark.parametrize(
    "text",
    [
        b'{"scene": ',
        b"not json",
        b"",
        b"[1, 2]",
        b'"scene"',
        b'{"scene": {"kind": "linkage"}} trailing',
    ],
)
def test_malformed_json(client: TestClient, text: bytes) -> None:
    response = client.post(
        "/api/v1/analyze", content=text, headers={"content-type": "application/json"}
    )
    assert_problem(response, 422, "invalid_scene")


def test_missing_scene_and_unknown_top_level_field(client: TestClient) -> None:
    assert_problem(client.post("/api/v1/analyze", json={}), 422, "invalid_scene")
    body = assert_problem(
        client.post("/api/v1/analyze", json={"scene": scene(), "extra": 1}), 422, "invalid_scene"
    )
    assert "extra" in body["detail"]


def test_body_over_one_megabyte_is_413(client: TestClient) -> None:
    """Issue 2: bounded body bytes. 1.1 MB of valid JSON (a long title) with a content-length."""
    doc = scene()
    doc["title"] = "x" * 1_100_000
    body = assert_problem(analyze(client, doc), 413, "limit_exceeded")
    assert "1000000" in body["detail"] or "1 MB" in body["detail"]


def test_chunked_body_over_one_megabyte_is_413(client: TestClient) -> None:
    """Without a content-length the limit must hold while reading (a streamed body)."""

    def chunks() -> Iterator[bytes]:
        yield b'{"scene": {"title": "'
        for _ in range(120):
            yield b"x" * 10_000
        yield b'"}}'

    response = client.post(
        "/api/v1/analyze", content=chunks(), headers={"content-type": "application/json"}
    )
    assert "content-length" not in {k.lower() for k in response.request.headers}
    assert_problem(response, 413, "limit_exceeded")


def test_too_many_points(client: TestClient) -> None:
    """Issue 2: bounded points. 1000 extra points on the ground link (still under 1 MB)."""
    doc = scene()
    for k in range(1000):
        doc["points"][f"G{k}"] = [float(k), 10.0]
        doc["links"]["ground"]["points"].append(f"G{k}")
    assert len(json.dumps({"scene": doc})) < 1_000_000
    body = assert_problem(analyze(client, doc), (413, 422), "limit_exceeded")
    assert "points" in body["detail"]


def test_too_many_links(client: TestClient) -> None:
    doc = scene()
    for k in range(1000):
        doc["links"][f"bar{k}"] = {"points": ["A"]}
    body = assert_problem(analyze(client, doc), (413, 422), "limit_exceeded")
    assert "links" in body["detail"]


@pytest.mark.parametrize("samples", [0, 1, 100_001, 10**9, -5])
def test_samples_out_of_range(client: TestClient, samples: int) -> None:
    response = client.post("/api/v1/sweep", json={"scene": scene(), "samples": samples})
    body = assert_problem(response, (413, 422), "limit_exceeded")
    assert str(samples) in body["detail"]


@pytest.mark.parametrize("samples", ["many", 3.5, None, [10]])
def test_samples_of_the_wrong_type(client: TestClient, samples: Any) -> None:
    response = client.post("/api/v1/sweep", json={"scene": scene(), "samples": samples})
    body = assert_problem(response, 422, "invalid_scene")
    assert "samples" in body["detail"]


@pytest.mark.parametrize(
    ("endpoint", "quantities"),
    [
        ("/api/v1/analyze", ["position", "jerk"]),
        ("/api/v1/analyze", "position"),
        ("/api/v1/sweep", ["jerk"]),
    ],
)
def test_unknown_quantity(client: TestClient, endpoint: str, quantities: Any) -> None:
    response = client.post(endpoint, json={"scene": scene(), "quantities": quantities})
    body = assert_problem(response, 422, "invalid_scene")
    assert "quantities" in body["detail"]


# --- presets and routes ---------------------------------------------------------------------------


def test_unknown_preset(client: TestClient) -> None:
    """An unknown preset name: a clear error that lists the presets there are."""
    response = client.post("/api/v1/presets/hexapod", json={})
    body = assert_problem(response, (404, 422), ("not_found", "invalid_scene"))
    assert "hexapod" in body["detail"] and "four_bar" in body["detail"]


@pytest.mark.parametrize(
    ("values", "mentioned"),
    [
        ({"crank": -1.0}, "crank"),
        ({"crank": "long"}, "crank"),
        ({"wheels": 4}, "wheels"),
    ],
)
def test_bad_preset_parameters(client: TestClient, values: dict[str, Any], mentioned: str) -> None:
    response = client.post("/api/v1/presets/four_bar", json=values)
    body = assert_problem(response, 422, "invalid_scene")
    assert mentioned in body["detail"]


def test_preset_that_cannot_close(client: TestClient) -> None:
    """A four-bar whose coupler and rocker together are shorter than |BD|."""
    response = client.post(
        "/api/v1/presets/four_bar",
        json={"ground": 1.0, "crank": 0.2, "coupler": 0.3, "rocker": 0.3, "crank_angle_deg": 180.0},
    )
    body = assert_problem(response, 422, "not_assemblable")
    assert "1.2" in body["detail"]  # |BD| = 1.2 m


@pytest.mark.parametrize("method", ["GET", "POST"])
def test_unknown_api_route_is_404(client: TestClient, method: str) -> None:
    """No such endpoint under /api/v1: not found, whatever the method."""
    response = client.request(method, "/api/v1/simulate", json={})
    assert_problem(response, 404, "not_found")


def test_wrong_method_is_405_with_allow(client: TestClient) -> None:
    """A 405 names the methods the path answers (RFC 9110 15.5.6)."""
    response = client.get("/api/v1/analyze")
    assert_problem(response, 405, "method_not_allowed")
    assert response.headers["allow"] == "POST"
    assert client.delete("/api/v1/exercises/types").headers["allow"] == "GET"


def test_a_405_allows_every_method_of_the_documented_path(client: TestClient) -> None:
    """Found by schemathesis: a path with two routes (GET and POST /solution.html) named only
    the first's method, and /exercises/check the GET of /exercises/{exercise_id} (which would take
    'check' as an id) instead of its own POST. A concrete path is matched before a templated
    one, as OpenAPI matches them."""
    assert client.options("/api/v1/solution.html").headers["allow"] == "GET, POST"
    assert client.options("/api/v1/exercises/check").headers["allow"] == "POST"
    assert client.options("/api/v1/exercises/export").headers["allow"] == "POST"
    assert client.delete("/api/v1/exercises/any-id").headers["allow"] == "GET"


@pytest.mark.parametrize(
    "media", ["text/plain", "application/x-www-form-urlencoded", "multipart/form-data; b=x"]
)
def test_a_body_that_is_not_json_is_415(client: TestClient, media: str) -> None:
    """A valid scene sent under another media type is refused before it is read."""
    body = json.dumps({"scene": scene()}).encode()
    response = client.post("/api/v1/analyze", content=body, headers={"content-type": media})
    assert media.split(";")[0] in assert_problem(response, 415, "unsupported_media_type")["detail"]


@pytest.mark.parametrize("media", [None, "application/json; charset=utf-8", "Application/JSON"])
def test_a_json_body_is_read_under_any_json_media_type_or_none(
    client: TestClient, media: str | None
) -> None:
    body = json.dumps({"scene": scene()}).encode()
    headers = {} if media is None else {"content-type": media}
    response = client.post("/api/v1/analyze", content=body, headers=headers)
    assert response.status_code == 200, response.text


# --- fuzz: random mutations of valid scenes ---------------------------------------------------


def _valid_scenes() -> list[Doc]:
    docs = [scene(), scene(SLIDER), _scene("S000-T2"), _scene("S001-offset-slider-crank")]
    docs += [build_preset(name, {}) for name in ("quick_return", "inverted_slider_crank")]
    return docs


VALID = _valid_scenes()

_numbers = st.one_of(
    st.sampled_from(
        [0.0, -0.0, 1e308, -1e308, 5e-324, 1e6, -1e6, 1e6 + 1, 1e-300, 2**63, -(2**63), 10**400]
    ),
    st.floats(allow_nan=False, allow_infinity=False),
    st.integers(),
)
_junk = st.recursive(
    st.none() | st.booleans() | _numbers | st.text(max_size=20),
    lambda inner: (
        st.lists(inner, max_size=3) | st.dictionaries(st.text(max_size=5), inner, max_size=3)
    ),
    max_leaves=6,
)


def _paths(value: Any, prefix: tuple[Any, ...] = ()) -> list[tuple[Any, ...]]:
    """Every path to a value inside a JSON document (the root excluded)."""
    found = []
    items = (
        value.items()
        if isinstance(value, dict)
        else enumerate(value)
        if isinstance(value, list)
        else []
    )
    for key, item in items:
        found.append((*prefix, key))
        found += _paths(item, (*prefix, key))
    return found


def _is_number(value: Any) -> bool:
    return isinstance(value, int | float) and not isinstance(value, bool)


@st.composite
def mutated_requests(draw: st.DrawFn) -> tuple[str, Doc]:
    """A valid /analyze or /sweep request with one to three random mutations: a key or element
    deleted, a value replaced by junk or by a number, a key renamed, or (most often, so that many
    requests stay solvable and exercise the arithmetic) a number changed to another number."""
    doc = copy.deepcopy(draw(st.sampled_from(VALID)))
    endpoint = draw(st.sampled_from(["/api/v1/analyze", "/api/v1/analyze", "/api/v1/sweep"]))
    body: Doc = {"scene": doc}
    if endpoint.endswith("sweep"):
        body |= {
            "samples": draw(st.integers(2, 24)),
            "quantities": ["position", "velocity", "acceleration"],
        }
    for _ in range(draw(st.integers(1, 3))):
        action = draw(
            st.sampled_from(["delete", "replace", "number", "rename", "leaf", "leaf", "leaf"])
        )
        paths = _paths(body)
        if action == "leaf":
            paths = [p for p in paths if _is_number(_at(body, p))]
        if not paths:
            break
        path = draw(st.sampled_from(paths))
        parent = _at(body, path[:-1])
        key = path[-1]
        if action == "delete":
            del parent[key]
        elif action == "replace":
            parent[key] = draw(_junk)
        elif action == "number":
            parent[key] = draw(_numbers)
        elif action == "leaf":
            factor = draw(st.sampled_from([0.0, -1.0, 1e-9, 1e-3, 0.5, 2.0, 1e3, 1e9]))
            try:
                scaled = float(parent[key]) * factor
            except OverflowError:  # an integer beyond any float, from an earlier mutation
                scaled = factor
            parent[key] = draw(st.one_of(_numbers, st.just(scaled), st.floats(-10.0, 10.0)))
        elif isinstance(parent, dict):  # rename a key (a name that no longer matches)
            parent[draw(st.text(min_size=1, max_size=8))] = parent.pop(key)
        else:
            parent[key] = draw(st.text(max_size=8))
    return endpoint, body


def _at(body: Any, path: tuple[Any, ...]) -> Any:
    for key in path:
        body = body[key]
    return body


def _finite(value: Any) -> bool:
    if isinstance(value, float):
        return math.isfinite(value)
    if isinstance(value, dict):
        return all(_finite(v) for v in value.values())
    if isinstance(value, list):
        return all(_finite(v) for v in value)
    return True


def _reject_constant(name: str) -> Any:
    raise ValueError(f"{name} in a response body")


@pytest.mark.slow
@settings(
    max_examples=250,
    deadline=None,
    database=None,
    suppress_health_check=[HealthCheck.too_slow, HealthCheck.function_scoped_fixture],
)
@given(request=mutated_requests())
def test_mutated_scenes_never_give_500_or_nan(client: TestClient, request: tuple[str, Doc]) -> None:
    """Issue 2: no 500 for any input, and no NaN or infinity in any response (scene-v1)."""
    endpoint, body = request
    try:
        text = json.dumps(body, allow_nan=False)
    except (ValueError, OverflowError):
        return  # not JSON (e.g. an integer too large for a float is still JSON: kept)
    response = client.post(
        endpoint, content=text.encode(), headers={"content-type": "application/json"}
    )
    assert response.status_code != 500, response.text
    parsed = json.loads(response.text, parse_constant=_reject_constant)
    assert _finite(parsed)
    if response.status_code == 200:
        assert response.headers["content-type"].startswith("application/json")
    else:
        assert response.status_code in (413, 422), response.text
        assert response.headers["content-type"].startswith(PROBLEM)
        assert parsed["code"] in CODES, parsed


@pytest.mark.parametrize("samples", [-5, 0, 1, 100_001])
def test_a_time_sweeps_samples_are_bounded_as_a_revolutions(
    client: TestClient, samples: int
) -> None:
    """Issue 28: a negative count reached numpy's linspace in the cost estimate (500)."""
    carrier = json.loads((EXAMPLES / "S003-T1-translating-carrier.json").read_text())
    for extra in ({"time_range": [0.0, 1.0]}, {}):
        body = {"scene": carrier, "samples": samples, **extra}
        detail = assert_problem(client.post("/api/v1/sweep", json=body), 413, "limit_exceeded")
        assert detail["detail"] == f"samples: {samples} is outside 2..100000"


@pytest.mark.parametrize("literal", ["2" + "0" * 308, "1" + "0" * 309, "1e400"])
@pytest.mark.parametrize("path", ["analyze", "solution", "sweep", "events"])
def test_a_literal_past_the_float_range_is_an_invalid_expression(
    client: TestClient, literal: str, path: str
) -> None:
    """Issue 28: an integer of 309 digits has no float (OverflowError, 500 on every route)."""
    carrier = json.loads((EXAMPLES / "S003-T1-translating-carrier.json").read_text())
    carrier["drivers"][0]["angle_law"] = f"{literal}*t"
    body: Doc = {"scene": carrier}
    if path == "sweep":
        body["time_range"] = [0.0, 1.0]
    if path == "events":
        body["event"] = {"moving_point": "M", "reaches": "O1"}
    problem = assert_problem(client.post(f"/api/v1/{path}", json=body), 422, "invalid_expression")
    assert problem["detail"] == f"the number {literal} is larger than 1e12 at character 0"

"""The typed scene of the OpenAPI document (server.scene_schema): it describes every scene the
parsers accept and refuses none of them, it names exactly the fields the parsers know, every route
that takes or gives a scene uses it, and the parsers' own errors still answer a wrong scene."""

from __future__ import annotations

import copy
import json
from pathlib import Path
from typing import Any

import pytest
from fastapi.testclient import TestClient
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st
from jsonschema import Draft202012Validator

import solver
from server.app import app
from server.routes.presets import ALL_PRESETS
from solver.errors import KinematicsError
from solver.gears.scene import GEAR_TRAIN_FIELDS
from solver.model.scene import SCENE_FIELDS
from tests.linkage_strategies import six_bars
from tests.strategies import assemblable_presets

EXAMPLES = Path(__file__).resolve().parents[2] / "server" / "examples"
OPENAPI: dict[str, Any] = app.openapi()  # generated once, shared by the tests of this module
SCHEMAS: dict[str, Any] = OPENAPI["components"]["schemas"]
SCENE = Draft202012Validator({**OPENAPI, "$ref": "#/components/schemas/Scene"})
KIND_COMPONENTS = {
    "linkage": "LinkageScene",
    "spatial_chain": "SpatialChainScene",
    "cam": "CamScene",
    "gear_train": "GearTrainScene",
}
BUNDLED: dict[str, dict[str, Any]] = {
    **{
        f"example {p.relative_to(EXAMPLES)}": json.loads(p.read_text())
        for p in EXAMPLES.rglob("*.json")
    },
    **{f"preset {name}": preset.build({}) for name, preset in ALL_PRESETS.items()},
}


def refusals(doc: Any) -> list[str]:
    return [f"{list(e.absolute_path)}: {e.message}" for e in SCENE.iter_errors(doc)]


def accepted(doc: Any) -> bool:
    """The parsers' verdict (the source of truth)."""
    try:
        solver.read_scene(doc)
    except KinematicsError:
        return False
    return True


@pytest.mark.parametrize("name", sorted(BUNDLED))
def test_every_bundled_scene_satisfies_the_schema(name: str) -> None:
    """Every example of server/examples and every preset's scene (the golden corpus's scenes)."""
    assert accepted(BUNDLED[name])
    assert not refusals(BUNDLED[name]), name


def test_exercise_and_synthesis_scenes_satisfy_the_schema(client: TestClient) -> None:
    types = [t["name"] for t in client.get("/api/v1/exercises/types").json()["types"]]
    for name in types:
        answer = client.post("/api/v1/exercises", json={"type": name, "count": 2, "seed": 3})
        for exercise in answer.json()["exercises"]:
            if "scene" in exercise:  # a synthesis exercise is built on a task instead
                assert not refusals(exercise["scene"]), (name, refusals(exercise["scene"]))
    task = {"task": "quick_return", "time_ratio": 1.25, "rocker_length": 0.1, "swing_deg": 60}
    designed = client.post("/api/v1/synthesis", json=task)
    assert designed.status_code == 200 and not refusals(designed.json()["scene"])


@settings(max_examples=40, deadline=None, derandomize=True)
@given(assemblable_presets())
def test_drawn_preset_scenes_satisfy_the_schema(drawn: tuple[str, dict[str, float]]) -> None:
    name, values = drawn
    doc = ALL_PRESETS[name].build(values)
    assert not refusals(doc), refusals(doc)


@settings(max_examples=20, deadline=None, derandomize=True)
@given(six_bars())
def test_drawn_six_bars_satisfy_the_schema(six_bar: Any) -> None:
    assert not refusals(six_bar.doc), refusals(six_bar.doc)


# --- never stricter than the parsers -------------------------------------------------------------

ODD_VALUES = [None, True, 0, -1, 2, 2.5, 20.0, 1e7, 10**400, "", "x", "t", [], [1, 2], {}, {"a": 1}]


def _locations(value: Any, path: tuple[Any, ...] = ()) -> list[tuple[Any, ...]]:
    """Every path into a JSON document (the root excluded)."""
    out: list[tuple[Any, ...]] = [path] if path else []
    if isinstance(value, dict):
        for key, item in value.items():
            out += _locations(item, (*path, key))
    elif isinstance(value, list):
        for i, item in enumerate(value):
            out += _locations(item, (*path, i))
    return out


def _mutate(doc: Any, data: st.DataObject) -> None:
    """Replace, delete or add one value somewhere in ``doc``."""
    path = data.draw(st.sampled_from(_locations(doc)))
    parent = doc
    for step in path[:-1]:
        parent = parent[step]
    action = data.draw(st.sampled_from(["replace", "delete", "add"]))
    if action == "delete":
        del parent[path[-1]]
    elif action == "add" and isinstance(parent, dict):
        parent[data.draw(st.sampled_from(["extra", "angle", "drivres", "name"]))] = data.draw(
            st.sampled_from(ODD_VALUES)
        )
    else:
        parent[path[-1]] = copy.deepcopy(data.draw(st.sampled_from(ODD_VALUES)))


@settings(
    max_examples=50,
    deadline=None,
    derandomize=True,
    suppress_health_check=[HealthCheck.too_slow],
)
@given(st.data())
def test_the_schema_refuses_no_scene_the_parsers_accept(data: st.DataObject) -> None:
    """Bundled scenes changed in one to three places: what the parsers still accept, the schema
    accepts (what they refuse, the schema may or may not)."""
    doc = copy.deepcopy(BUNDLED[data.draw(st.sampled_from(sorted(BUNDLED)))])
    for _ in range(data.draw(st.integers(1, 3))):
        if _locations(doc):
            _mutate(doc, data)
    if accepted(doc):
        assert not refusals(doc), (json.dumps(doc)[:400], refusals(doc)[:3])


@pytest.mark.parametrize(
    ("name", "path", "value"),
    [
        ("example S000-T1.json", ("drivers", 0, "angle_law"), None),  # null: no law
        ("example S000-T1.json", ("joints", 0, "axis"), None),  # a revolute joint's axis: unused
        ("example S000-T1.json", ("points", "A", 0), 0),  # an integer coordinate
        ("example S000-T1.json", ("unknown",), {"a": 1}),  # a key the contract does not know
        ("example G001-planetary.json", ("gears", "sun", "teeth"), 20.0),  # a whole float
        ("example G001-planetary.json", ("title",), 5),  # a gear train's title not text
        ("example G001-planetary.json", ("module",), None),
    ],
)
def test_odd_documents_the_parsers_accept_are_valid(
    name: str, path: tuple[Any, ...], value: Any
) -> None:
    doc = copy.deepcopy(BUNDLED[name])
    parent = doc
    for step in path[:-1]:
        parent = parent[step]
    parent[path[-1]] = value
    assert accepted(doc)
    assert not refusals(doc), refusals(doc)


@pytest.mark.parametrize(
    ("path", "value"),
    [
        (("kind",), "linkages"),
        (("points",), "A B C D"),
        (("joints", 0, "type"), "hinge"),
        (("drivers", 0, "omega"), 1e7),  # |omega| <= 1e6 rad/s
        (("drivers", 0, "omega"), None),
        (("links", "crank", "points"), []),
        (("points", "A"), [0, 0, 0]),
        (("title",), None),
    ],
)
def test_the_schema_is_not_vacuous(path: tuple[Any, ...], value: Any) -> None:
    """Wrong documents that the parsers refuse are refused by the schema too."""
    doc = copy.deepcopy(BUNDLED["example S000-T1.json"])
    parent = doc
    for step in path[:-1]:
        parent = parent[step]
    parent[path[-1]] = value
    assert not accepted(doc)
    assert refusals(doc)


# --- the same fields as the parsers know ---------------------------------------------------------


def _resolve(schema: dict[str, Any]) -> list[dict[str, Any]]:
    """The object schemas ``schema`` stands for (through $ref, allOf, anyOf, oneOf)."""
    if "$ref" in schema:
        return _resolve(SCHEMAS[schema["$ref"].rsplit("/", 1)[1]])
    for key in ("allOf", "anyOf", "oneOf"):
        if key in schema:
            return [s for part in schema[key] for s in _resolve(part)]
    return [schema] if schema.get("type") == "object" or "properties" in schema else []


def _at(schemas: list[dict[str, Any]], pattern: str) -> list[dict[str, Any]]:
    for part in pattern.split(".") if pattern else []:
        name, listed = part.removesuffix("[]"), part.endswith("[]")
        deeper: list[dict[str, Any]] = []
        for schema in schemas:
            if name == "*":
                deeper += _resolve(schema["additionalProperties"])
                continue
            found = schema["properties"][name]
            if not listed:
                deeper += _resolve(found)
                continue
            for array in found.get("anyOf", [found]):
                deeper += _resolve(array["items"]) if "items" in array else []
        schemas = deeper
    return schemas


@pytest.mark.parametrize("kind", sorted(KIND_COMPONENTS))
def test_the_schema_names_the_fields_the_parsers_know(kind: str) -> None:
    """Each part of each kind has exactly the properties of the parsers' lists of known keys
    (solver.model.scene.SCENE_FIELDS, solver.gears.scene.GEAR_TRAIN_FIELDS): a field added to a
    parser and not to the schema, or the other way round, fails here."""
    known = GEAR_TRAIN_FIELDS if kind == "gear_train" else SCENE_FIELDS[kind]
    top = _resolve({"$ref": f"#/components/schemas/{KIND_COMPONENTS[kind]}"})
    for pattern, fields in known.items():
        parts = _at(top, pattern)
        assert parts, (kind, pattern)
        named = {name for part in parts for name in part.get("properties", {})}
        assert named == set(fields), (kind, pattern, named ^ set(fields))


# --- the routes ----------------------------------------------------------------------------------


def test_every_scene_of_the_contract_is_typed() -> None:
    """No request or response of the API carries a scene as a bare object: each refers to the
    union (or, where only a linkage will do, to its kind)."""
    found = []
    for name, schema in SCHEMAS.items():
        scene = schema.get("properties", {}).get("scene")
        if scene is not None:
            found.append(name)
            if "anyOf" in scene:  # an optional scene (an exercise built on a task has none)
                scene = next(s for s in scene["anyOf"] if s != {"type": "null"})
            assert scene["$ref"] in (
                "#/components/schemas/Scene",
                "#/components/schemas/LinkageScene",
            ), name
    assert {"AnalyzeRequest", "SweepRequest", "EventsRequest", "SolutionRequest"} <= set(found)
    assert {"BalanceRequest", "ExerciseModel", "BalanceResponse", "SynthesisResponse"} <= set(found)
    preset = OPENAPI["paths"]["/api/v1/presets/four_bar"]["post"]["responses"]["200"]
    assert preset["content"]["application/json"]["schema"]["$ref"] == "#/components/schemas/Scene"
    union = SCHEMAS["Scene"]
    assert union["discriminator"]["propertyName"] == "kind"
    assert sorted(union["discriminator"]["mapping"]) == sorted(KIND_COMPONENTS)


def test_a_wrong_scene_is_still_the_parsers_problem(client: TestClient) -> None:
    """The schema is published, not enforced: a wrong scene gets the parser's invalid_scene with
    its path and numbers (not the framework's validation messages), and unknown keys stay
    warnings."""
    doc = copy.deepcopy(BUNDLED["example S000-T1.json"])
    doc["drivers"][0]["omega"] = 1e7
    answer = client.post("/api/v1/analyze", json={"scene": doc})
    assert answer.status_code == 422
    assert answer.headers["content-type"] == "application/problem+json"
    assert answer.json()["code"] == "invalid_scene"
    assert answer.json()["detail"] == "drivers[0].omega: |1e+07| exceeds the limit 1e+06"
    doc = copy.deepcopy(BUNDLED["example S000-T1.json"])
    doc["drivres"] = []
    answer = client.post("/api/v1/analyze", json={"scene": doc, "quantities": ["position"]})
    assert answer.status_code == 200
    assert answer.json()["warnings"] == ["drivres is not a scene field; did you mean drivers?"]
    answer = client.post("/api/v1/sweep", json={"scene": [1, 2]})
    assert answer.status_code == 422 and answer.json()["code"] == "invalid_scene"

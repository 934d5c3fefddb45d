"""Clients generated from the OpenAPI document, as a program author would make them.

TypeScript: openapi-typescript (pinned with tsc in tests/clients/package-lock.json, installed by
tests/run.sh with ``npm ci``) writes the types, and the README's /analyze example
(tests/clients/readme_example.ts) compiles with ``tsc --strict``, no cast, while the same example
with a typo in a scene key (``drivres``) does not. Python: openapi-python-client (pinned in
requirements-test.lock) writes a client, which sends a test run of every route through the app
and parses every answer into its models, each model's ``to_dict()`` giving the answer back
unchanged.
"""

from __future__ import annotations

import copy
import importlib
import json
import pkgutil
import re
import shutil
import subprocess
import sys
import typing
from collections.abc import Iterator
from enum import Enum
from pathlib import Path
from types import ModuleType
from typing import Any

import pytest
from fastapi.testclient import TestClient

from server.app import app
from server.routes.presets import ALL_PRESETS
from tests.server.test_contract import NAMES, calls

pytestmark = pytest.mark.slow  # each generator takes a few seconds
CLIENTS = Path(__file__).resolve().parents[1] / "clients"
TSC = CLIENTS / "node_modules" / ".bin" / "tsc"
OPENAPI_TYPESCRIPT = CLIENTS / "node_modules" / ".bin" / "openapi-typescript"
TS_OPTIONS = ["--strict", "--noEmit", "--target", "es2022", "--module", "es2022"]
TS_OPTIONS += ["--moduleResolution", "bundler", "--lib", "es2022,dom"]


@pytest.fixture(scope="module")
def openapi_file(tmp_path_factory: pytest.TempPathFactory) -> Path:
    path = tmp_path_factory.mktemp("openapi") / "openapi.json"
    path.write_text(json.dumps(app.openapi()))
    return path


# --- TypeScript ----------------------------------------------------------------------------------


def tsc(folder: Path, *sources: str) -> subprocess.CompletedProcess[str]:
    return subprocess.run(
        ["node", str(TSC), *TS_OPTIONS, *sources],
        cwd=folder,
        capture_output=True,
        text=True,
        timeout=300,
    )


def test_the_readme_example_compiles_against_generated_typescript(
    openapi_file: Path, tmp_path: Path
) -> None:
    if shutil.which("node") is None or not TSC.exists():
        pytest.skip(
            "the TypeScript client test needs Node.js and `npm ci` in tests/clients (tests/run.sh "
            "does it; it skips this test with a warning when the npm registry is unreachable)"
        )
    generated = subprocess.run(
        [
            *("node", str(OPENAPI_TYPESCRIPT), str(openapi_file)),
            *("-o", str(tmp_path / "schema.d.ts")),
            "--no-default-non-nullable",  # a field with a default may be left out of a request
        ],
        capture_output=True,
        text=True,
        timeout=300,
    )
    assert generated.returncode == 0, generated.stderr
    example = (CLIENTS / "readme_example.ts").read_text()
    assert "drivers: [" in example
    (tmp_path / "readme_example.ts").write_text(example)
    (tmp_path / "typo.ts").write_text(example.replace("drivers: [", "drivres: ["))
    # Without narrowing by kind, a field of one answer is not a field of the union.
    narrowing = 'if (answer.kind !== "linkage") return `a ${answer.kind} has no coupler`;'
    assert narrowing in example
    (tmp_path / "unnarrowed.ts").write_text(example.replace(narrowing, ""))
    compiled = tsc(tmp_path, "readme_example.ts", "typo.ts", "unnarrowed.ts")  # one run for all
    errors = compiled.stdout.splitlines()
    assert errors, errors
    assert all(line.startswith(("typo.ts(", "unnarrowed.ts(", " ")) for line in errors), errors
    assert "'drivres' does not exist" in compiled.stdout, errors
    assert any(line.startswith("unnarrowed.ts(") for line in errors), errors


# --- Python --------------------------------------------------------------------------------------


@pytest.fixture(scope="module")
def python_client(openapi_file: Path) -> Iterator[dict[str, ModuleType]]:
    """The generated package ``kinematics_client``, imported; its operations' modules by name."""
    folder = openapi_file.parent
    config = folder / "config.yaml"
    config.write_text("post_hooks: []\npackage_name_override: kinematics_client\n")
    command = Path(sys.executable).parent / "openapi-python-client"
    generated = subprocess.run(
        [
            *(str(command), "generate", "--path", str(openapi_file), "--config", str(config)),
            *("--meta", "none", "--output-path", str(folder / "kinematics_client")),
        ],
        capture_output=True,
        text=True,
        timeout=300,
    )
    assert generated.returncode == 0, generated.stdout + generated.stderr
    assert "Warning" not in generated.stdout, generated.stdout
    sys.path.insert(0, str(folder))
    try:
        package = importlib.import_module("kinematics_client.api")
        operations = {
            info.name.rsplit(".", 1)[1]: importlib.import_module(info.name)
            for info in pkgutil.walk_packages(package.__path__, "kinematics_client.api.")
            if not info.ispkg
        }
        yield operations
    finally:
        sys.path.remove(str(folder))


def operation_ids() -> dict[tuple[str, str], str]:
    """The generated module of each operation: its operationId in snake case."""
    return {
        (method, path): re.sub("_+", "_", operation["operationId"])
        for path, item in app.openapi()["paths"].items()
        for method, operation in item.items()
    }


def four_bar_with_masses() -> dict[str, Any]:
    doc = copy.deepcopy(ALL_PRESETS["four_bar"].build({}))
    doc["masses"] = {
        name: {"mass": 2.0, "bar": link["points"][:2]}
        for name, link in doc["links"].items()
        if not link.get("ground")
    }
    return doc


def requests_of_every_route(client: TestClient) -> list[tuple[str, str, dict[str, Any], int]]:
    """(method, path, arguments, expected status): a test run of every operation."""
    out: list[tuple[str, str, dict[str, Any], int]] = []
    for name in NAMES:
        out += [("post", f"/api/v1{path}", {"body": body}, 200) for path, body, _ in calls(name)]
    apart = copy.deepcopy(calls("S000-T1")[0][1]["scene"])
    apart["drivers"][0]["angle_deg"] = 180.0  # not_assemblable
    out.append(("post", "/api/v1/analyze", {"body": {"scene": apart}}, 422))
    too_many = {"scene": calls("S000-T1")[0][1]["scene"], "samples": 10**7}
    out.append(("post", "/api/v1/sweep", {"body": too_many}, 413))
    for family in ("linkages", "cams", "gear_trains"):
        out.append(("get", "/api/v1/presets", {"family": family}, 200))
    out += [("post", f"/api/v1/presets/{name}", {"body": {}}, 200) for name in ALL_PRESETS]
    solution = {"scene": calls("S000-T1")[0][1]["scene"]}
    out.append(("post", "/api/v1/solution.html", {"body": solution}, 200))
    out.append(("get", "/api/v1/solution.html", {"preset": "four_bar"}, 200))
    out.append(("get", "/api/v1/exercises/types", {}, 200))
    types = [t["name"] for t in client.get("/api/v1/exercises/types").json()["types"]]
    for kind in types:
        out.append(("post", "/api/v1/exercises", {"body": {"type": kind, "seed": 7}}, 200))
    exercise = client.post("/api/v1/exercises", json={"type": types[0], "seed": 7}).json()
    first = exercise["exercises"][0]
    out.append(("get", "/api/v1/exercises/{exercise_id}", {"exercise_id": first["id"]}, 200))
    answers = {a["key"]: 1.0 for a in first["asked"]}
    check = {"id": first["id"], "answers": answers}
    out.append(("post", "/api/v1/exercises/check", {"body": check}, 200))
    for form in ("json", "csv"):
        export = {"type": types[0], "seed": 7, "format": form}
        out.append(("post", "/api/v1/exercises/export", {"body": export}, 200))
    weights = [{"link": "crank", "mass": 1.0}, {"link": "rocker", "mass": 1.0}]
    balance = {"scene": four_bar_with_masses(), "counterweights": weights}
    out.append(("post", "/api/v1/balance", {"body": balance}, 200))
    task = {"task": "quick_return", "time_ratio": 1.25, "rocker_length": 0.1, "swing_deg": 60}
    out.append(("post", "/api/v1/synthesis", {"body": task}, 200))
    out.append(("get", "/health", {}, 200))
    return out


def arguments(function: Any, given: dict[str, Any]) -> dict[str, Any]:
    """The generated function's keyword arguments: a body as its model (of a union, the first
    that takes it), a query value as its enum where it has one."""
    hints = typing.get_type_hints(function)
    out: dict[str, Any] = {}
    for name, value in given.items():
        kinds = [k for k in typing.get_args(hints[name]) or [hints[name]] if isinstance(k, type)]
        enum = next((k for k in kinds if issubclass(k, Enum)), None)
        out[name] = enum(value) if enum else value
        for model in (k for k in kinds if hasattr(k, "from_dict")):
            try:  # a union of bodies (the synthesis tasks): the one that takes the value
                out[name] = model.from_dict(value)
                break
            except (KeyError, TypeError, ValueError):
                continue
    return out


def test_a_generated_python_client_parses_every_answer(
    client: TestClient, python_client: dict[str, ModuleType]
) -> None:
    from kinematics_client.client import Client  # generated by the fixture
    from kinematics_client.models.exercise_list import ExerciseList
    from kinematics_client.models.problem import Problem

    generated = Client(base_url=str(client.base_url)).set_httpx_client(client)
    ids = operation_ids()
    covered = set()
    for method, path, given, status in requests_of_every_route(client):
        module = python_client[ids[(method, path)]]
        covered.add((method, path))
        response = module.sync_detailed(client=generated, **arguments(module.sync_detailed, given))
        assert response.status_code == status, (path, response.content[:300])
        media = response.headers["content-type"].split(";")[0]
        if media not in ("application/json", "application/problem+json"):
            continue  # an HTML page, a CSV file: text, not parsed
        parsed = response.parsed
        assert isinstance(parsed, Problem) == (status >= 400), (path, type(parsed))
        body = json.loads(response.content)
        if isinstance(parsed, str):  # a file in one of several formats: its text
            assert parsed == response.content.decode()
            parsed = ExerciseList.from_dict(body)  # the JSON export: the POST /exercises body
        as_dict = parsed if isinstance(parsed, list | dict) else parsed.to_dict()
        assert as_dict == body, path
    assert covered == set(ids), set(ids) - covered

"""Arbitrary JSON at every endpoint (issue 15): no 5xx, every error problem+json with a code.

Hypothesis feeds deep nesting, huge and tiny numbers, unusual Unicode (lone surrogates, control
and format characters, astral planes), duplicate keys and bodies that are not JSON at all, both
as the whole body and as the ``scene`` of a request, to every POST route of the OpenAPI
document (GET routes take query values, fuzzed by schemathesis in test_schemathesis.py).
Derandomised for CI with modest example counts; a longer run: FUZZ_EXAMPLES=5000.
"""

from __future__ import annotations

import json
import os
from typing import Any

import pytest
from fastapi.testclient import TestClient
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from server import problems
from server.app import app

client = TestClient(app, raise_server_exceptions=False)
EXAMPLES = int(os.environ.get("FUZZ_EXAMPLES", "60"))
CODES = set(problems.TITLES) - {"internal_error"}  # every code but the 500's
POSTS = sorted(
    path for path, item in app.openapi()["paths"].items() if "post" in item and "{" not in path
)

text = st.text(
    st.characters(codec=None, categories=None, exclude_characters=None), max_size=20
) | st.sampled_from(["\ud800", "\udfff", "a\x00b", "\u202e", "𝔄", "\ufeff", "linkage", "A"])
numbers = (
    st.integers(min_value=-(10**30), max_value=10**30)
    | st.floats(allow_nan=False, allow_infinity=False)
    | st.sampled_from([0, -0.0, 1e308, 5e-324, 10**300, 360])
)
leaves = st.none() | st.booleans() | numbers | text
documents = st.recursive(
    leaves,
    lambda inner: st.lists(inner, max_size=4) | st.dictionaries(text, inner, max_size=4),
    max_leaves=30,
)


def check(response: Any) -> None:
    """No 5xx; an error is problem+json with a known code (httpx or schemathesis responses)."""
    assert response.status_code < 500, (response.status_code, response.text[:300])
    if response.status_code >= 400:
        content_type = response.headers["content-type"]
        if isinstance(content_type, list):
            content_type = content_type[0]
        assert content_type.startswith("application/problem+json")
        body = response.json()
        assert body["code"] in CODES and body["status"] == response.status_code, body
        assert isinstance(body["detail"], str) and body["detail"]


def post_text(path: str, body: str | bytes) -> Any:
    return client.post(path, content=body, headers={"content-type": "application/json"})


fuzz = settings(
    max_examples=EXAMPLES,
    derandomize=True,
    deadline=None,
    suppress_health_check=[HealthCheck.too_slow, HealthCheck.data_too_large],
)


@pytest.mark.parametrize("path", POSTS)
@fuzz
@given(document=documents)
def test_any_json_body(path: str, document: Any) -> None:
    check(post_text(path, json.dumps(document)))


@pytest.mark.parametrize("path", POSTS)
@fuzz
@given(scene=documents, extra=st.dictionaries(st.sampled_from(["samples", "quantities",
       "time_range", "event", "method", "digits"]), documents, max_size=3))  # fmt: skip
def test_any_scene(path: str, scene: Any, extra: dict[str, Any]) -> None:
    check(post_text(path, json.dumps({"scene": scene, **extra})))


@pytest.mark.parametrize("path", POSTS)
@fuzz
@given(
    depth=st.integers(1, 5000),
    opener=st.sampled_from(["[", '{"a":']),
    key=text,
    raw=st.binary(max_size=40),
)
def test_nesting_duplicates_and_bytes(
    path: str, depth: int, opener: str, key: str, raw: bytes
) -> None:
    closer = "]" if opener == "[" else "}"
    check(post_text(path, '{"scene": ' + opener * depth + "1" + closer * depth + "}"))
    quoted = json.dumps(key)
    check(post_text(path, f'{{"scene": {{{quoted}: 1, {quoted}: 2}}}}'))
    check(post_text(path, raw))

"""Strict JSON at the edge (issue 15, "no 500 for any input").

Lone surrogates and control characters, names outside the allowed length and characters,
duplicate keys, booleans and numeric strings where numbers belong, nesting and number literals
beyond the limits, and names that are not strings: each is ``invalid_scene`` (422) with the path
of the offending value, never a 500. Markup in titles and names reaches the printable page
escaped.
"""

from __future__ import annotations

import copy
import json
from pathlib import Path
from typing import Any

import pytest
from fastapi.testclient import TestClient

from server.app import app
from tests.server.test_errors import FOUR_BAR, assert_problem

client = TestClient(app, raise_server_exceptions=False)
SPATIAL = json.loads(
    (Path(__file__).parents[2] / "server" / "examples" / "S002-spatial-arm.json").read_text()
)
ENDPOINTS = ("/api/v1/analyze", "/api/v1/solution", "/api/v1/solution.html", "/api/v1/sweep")


def post_text(path: str, text: str) -> Any:
    """POST a body written by hand (json.dumps escapes a lone surrogate as \\udfff)."""
    return client.post(path, content=text, headers={"content-type": "application/json"})


def post(path: str, body: dict[str, Any]) -> Any:
    return post_text(path, json.dumps(body))


def four_bar() -> dict[str, Any]:
    return copy.deepcopy(FOUR_BAR)


def detail(response: Any) -> str:
    text: str = assert_problem(response, 422, "invalid_scene")["detail"]
    return text


@pytest.mark.parametrize("path", ENDPOINTS)
def test_a_lone_surrogate_in_a_title_is_invalid_scene(path: str) -> None:
    scene = four_bar()
    scene["title"] = "four-bar \udfff"
    message = detail(post(path, {"scene": scene}))
    assert "scene.title" in message and "surrogate" in message and "U+DFFF" in message


@pytest.mark.parametrize("path", ENDPOINTS)
def test_a_lone_surrogate_in_a_name_is_invalid_scene(path: str) -> None:
    scene = four_bar()
    scene["points"]["\ud800"] = [5.0, 5.0]
    assert "surrogate" in detail(post(path, {"scene": scene}))


@pytest.mark.parametrize(
    ("name", "words"),
    [
        ("B" * 65, "1 to 64 characters"),
        ("", "1 to 64 characters"),
        ("B\x00", "U+0000"),
        ("B\u202e", "U+202E"),  # right-to-left override: a format character
        ("B\n", "U+000A"),
        (" B", "leading, trailing or double space"),
    ],
)
def test_names_are_limited_in_length_and_characters(name: str, words: str) -> None:
    scene = four_bar()
    scene["drivers"][0]["link"] = name
    message = detail(post("/api/v1/analyze", {"scene": scene}))
    assert "scene.drivers[0].link" in message and words in message, message


def test_names_in_lists_and_keys_are_checked() -> None:
    scene = four_bar()
    scene["links"]["crank"]["points"] = ["A", "B\x07"]
    assert "scene.links.crank.points[1]" in detail(post("/api/v1/analyze", {"scene": scene}))
    scene = four_bar()
    scene["links"]["c" * 70] = scene["links"].pop("crank")
    assert "(the key)" in detail(post("/api/v1/analyze", {"scene": scene}))


def test_textbook_names_are_accepted() -> None:
    scene = four_bar()
    scene["points"]["B′ (coupler) – β₁"] = [0.5, 0.5]
    scene["links"]["crank"]["points"].append("B′ (coupler) – β₁")
    assert post("/api/v1/analyze", {"scene": scene}).status_code == 200


def test_markup_in_titles_and_names_is_escaped_on_the_printable_page() -> None:
    scene = four_bar()
    scene["title"] = '<script>alert("t")</script><b>bold</b>'
    scene["points"]["<i>P</i>&amp;"] = [0.5, 0.5]
    scene["links"]["crank"]["points"].append("<i>P</i>&amp;")
    response = post("/api/v1/solution.html", {"scene": scene})
    assert response.status_code == 200, response.text
    page = response.text
    assert "<script>alert" not in page and "<b>bold" not in page and "<i>P" not in page
    assert "&lt;script&gt;alert(&quot;t&quot;)&lt;/script&gt;&lt;b&gt;bold" in page
    assert "&lt;i&gt;P&lt;/i&gt;&amp;amp;" in page


def test_a_duplicate_top_level_scene_is_refused() -> None:
    text = '{"scene": {"kind": "nothing"}, "scene": ' + json.dumps(FOUR_BAR) + "}"
    message = detail(post_text("/api/v1/analyze", text))
    assert "'scene' appears more than once" in message


def test_a_duplicate_nested_key_is_refused_with_its_path() -> None:
    text = json.dumps({"scene": FOUR_BAR}).replace('"A": [0', '"A": [9, 9], "A": [0', 1)
    message = detail(post_text("/api/v1/analyze", text))
    assert message.startswith("scene.points:") and "'A' appears more than once" in message


@pytest.mark.parametrize(
    ("path", "extra", "where"),
    [
        ("/api/v1/sweep", {"samples": "360"}, "samples"),
        ("/api/v1/sweep", {"samples": True}, "samples"),
        ("/api/v1/sweep", {"samples": 360.0}, "samples"),
        ("/api/v1/sweep", {"time_range": [0, True]}, "time_range.1"),
        ("/api/v1/sweep", {"time_range": ["0", 1]}, "time_range.0"),
        ("/api/v1/solution", {"digits": "4"}, "digits"),
        ("/api/v1/solution", {"digits": False}, "digits"),
    ],
)
def test_booleans_and_numeric_strings_are_not_numbers(
    path: str, extra: dict[str, Any], where: str
) -> None:
    message = detail(post(path, {"scene": four_bar(), **extra}))
    assert message.startswith(f"{where}:"), message


def test_a_boolean_coordinate_is_not_a_number() -> None:
    scene = four_bar()
    scene["points"]["C"] = [True, 1]
    assert "points.C[0]" in detail(post("/api/v1/analyze", {"scene": scene}))


def test_event_numbers_must_be_numbers() -> None:
    event = {"moving_point": "M", "reaches": "A", "occurrence": 1, "t_max": True}
    assert "event.t_max" in detail(post("/api/v1/events", {"scene": four_bar(), "event": event}))


def test_a_preset_parameter_must_be_a_number() -> None:
    response = client.post("/api/v1/presets/four_bar", json={"crank_deg": "30"})
    assert response.status_code == 422 and response.json()["code"] == "invalid_scene"


@pytest.mark.parametrize("body", [{"a": 1}, ["ground"], 3])
def test_a_spatial_point_whose_body_is_not_a_name(body: Any) -> None:
    scene = copy.deepcopy(SPATIAL)
    next(iter(scene["points"].values()))["body"] = body
    message = detail(post("/api/v1/analyze", {"scene": scene}))
    assert ".body: expected a name" in message


@pytest.mark.parametrize(
    ("text", "words"),
    [
        ('{"scene": ' + "[" * 100 + "]" * 100 + "}", "nested more than 32"),
        ('{"scene": ' + "[" * 100_000 + "]" * 100_000 + "}", "nested too deeply"),
        ('{"scene": {"kind": "linkage", "time": 1' + "0" * 500 + "}}", "501 digits, more than 400"),
        ('{"scene": {"kind": "linkage", "time": NaN}}', "NaN is not a number"),
        ('{"scene": {"kind": "linkage",}}', "not valid JSON"),
    ],
)
def test_malformed_documents_are_invalid_scene(text: str, words: str) -> None:
    assert words in detail(post_text("/api/v1/analyze", text))


def test_bytes_that_are_not_utf8_are_invalid_scene() -> None:
    body = b'{"scene": "\xff"}'
    response = client.post(
        "/api/v1/analyze", content=body, headers={"content-type": "application/json"}
    )
    assert "not UTF-8" in detail(response)

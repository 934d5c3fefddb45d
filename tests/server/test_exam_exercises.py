"""Exam sets over HTTP: an exam id yields no key through any route (GET serves the statement
only, check refuses it, exports for students carry neither a practice id nor an answer), forged
ids are 404, and a server without KINEMATICS_EXAM_SECRET refuses exam sets saying how to set it."""

from __future__ import annotations

import io
import re
import xml.etree.ElementTree as ET
import zipfile
from collections.abc import Iterator
from typing import Any

import pytest
from fastapi.testclient import TestClient

from server.app import app
from solver.exercises import TYPES, ExerciseId
from solver.exercises.exam import exam_id

API = "/api/v1/exercises"
VARIABLE = "KINEMATICS_EXAM_SECRET"
SECRET = "the tests' deployment secret, long enough"
SEED = 2**40 + 99
PRACTICE_ID = re.compile(r"[a-z_]+:[a-z]+:[0-9]+:[0-9]+")
CLOZE_PART = re.compile(r"\{1:NUMERICAL:=[^}]*\}")
KEY_NAMES = {"answers", "expected", "solution", "steps", "scene", "path"}


@pytest.fixture(scope="module")
def exam_client() -> Iterator[TestClient]:
    """A server with the secret in its environment (read in its process, sent to its workers
    with each request)."""
    with pytest.MonkeyPatch.context() as patch:
        patch.setenv(VARIABLE, SECRET)
        with TestClient(app, raise_server_exceptions=False) as test_client:
            yield test_client


def exam_set(client: TestClient, kind: str, count: int = 2) -> list[dict[str, Any]]:
    r = client.post(API, json={"type": kind, "seed": SEED, "count": count, "exam": True})
    assert r.status_code == 200, r.text
    exercises: list[dict[str, Any]] = r.json()["exercises"]
    return exercises


def walk(node: Any, path: str = "") -> Iterator[tuple[str, Any]]:
    """Every (path, value) of a JSON document, keys included as values of their own."""
    if isinstance(node, dict):
        for k, v in node.items():
            yield f"{path}.{k}", k
            yield from walk(v, f"{path}.{k}")
    elif isinstance(node, list):
        for i, v in enumerate(node):
            yield from walk(v, f"{path}.{i}")
    else:
        yield path, node


def forms(value: float) -> set[str]:
    """How a text could print an answer; none for a round one (-2.0 rad/s may be a datum too)."""
    if len(re.sub(r"[^0-9]", "", f"{value:.6g}").strip("0")) < 4:
        return set()
    return {repr(value), f"{value:.6g}", f"{value:.5g}"}


def carries(text: str, answers: dict[str, float]) -> list[str]:
    return [form for v in answers.values() for form in forms(v) if form in text]


@pytest.mark.parametrize("kind", list(TYPES))
def test_an_exam_id_yields_its_statement_and_no_key(exam_client: TestClient, kind: str) -> None:
    for exercise in exam_set(exam_client, kind):
        ident = exercise["id"]
        assert exercise["exam"] is True and ident.startswith("exam-")
        for shown in (kind, str(SEED), f"{kind}:"):
            assert shown not in ident
        r = exam_client.get(f"{API}/{ident}")
        assert r.status_code == 200, r.text
        body = r.json()
        assert body["id"] == ident and body["exam"] is True
        assert body["statement"] == exercise["statement"]
        for where, value in walk(body):
            assert value not in KEY_NAMES, where
            if isinstance(value, float) and value != round(value, 3):
                assert all(abs(value - a) > 1e-9 * abs(a) for a in exercise["answers"].values())
            if isinstance(value, str):
                assert not carries(value, exercise["answers"]), where
                assert PRACTICE_ID.search(value) is None, where
        check = exam_client.post(f"{API}/check", json={"id": ident, "answers": {}})
        assert check.status_code == 403
        assert check.headers["content-type"] == "application/problem+json"
        assert check.json()["code"] == "forbidden" and "exam" in check.json()["detail"]
        assert "expected" not in check.text


def test_forged_and_foreign_exam_ids_are_404(exam_client: TestClient) -> None:
    made = exam_set(exam_client, "four_bar_velocity", 1)[0]["id"]
    foreign = exam_id(ExerciseId("four_bar_velocity", "standard", SEED, 0), b"another secret!!")
    altered = made[:-2] + ("AA" if made[-2:] != "AA" else "BB")
    for unknown in (foreign, altered, "exam-AAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAA"):
        r = exam_client.get(f"{API}/{unknown}")
        assert r.status_code == 404 and r.json()["code"] == "not_found", r.text


def test_a_guessable_exam_seed_is_refused(exam_client: TestClient) -> None:
    r = exam_client.post(API, json={"type": "slider_crank", "seed": 20231234, "exam": True})
    assert r.status_code == 422 and "password" in r.json()["detail"]


def question_texts(xml: bytes) -> list[str]:
    quiz = ET.fromstring(xml)
    return [q.findtext("questiontext/text") or "" for q in quiz.findall("question")[1:]]


@pytest.mark.parametrize("kind", ["four_bar_velocity", "inverted_slider_crank", "flywheel"])
@pytest.mark.parametrize("style", ["auto", "numerical"])
def test_student_facing_exports_of_an_exam_set_carry_no_id_and_no_key(
    exam_client: TestClient, kind: str, style: str
) -> None:
    exercises = exam_set(exam_client, kind, 3)
    answers = {f"{i}{k}": v for i, e in enumerate(exercises) for k, v in e["answers"].items()}
    body = {"type": kind, "seed": SEED, "count": 3, "exam": True, "moodle_question": style}
    xml = exam_client.post(f"{API}/export", json={**body, "format": "moodle_xml"})
    sheet = exam_client.post(f"{API}/export", json={**body, "format": "html"})
    for r in (xml, sheet):
        assert r.status_code == 200, r.text
        name = r.headers["content-disposition"]
        assert str(SEED) not in name and "exam" in name and PRACTICE_ID.search(name) is None
    for text in question_texts(xml.content):
        shown = CLOZE_PART.sub("", text)  # Moodle turns a cloze part into an empty box
        assert PRACTICE_ID.search(shown) is None and str(SEED) not in shown
        assert not carries(shown, answers)
        assert re.search(r'alt="Figure: [^"]+"', shown)
    assert PRACTICE_ID.search(sheet.text) is None and str(SEED) not in sheet.text
    assert not carries(sheet.text, answers)
    quiz = ET.fromstring(xml.content)
    assert str(SEED) not in (quiz.findtext("question/category/text") or "")
    qti = exam_client.post(f"{API}/export", json={**body, "format": "qti"})
    assert qti.status_code == 200 and str(SEED) not in qti.headers["content-disposition"]
    package = zipfile.ZipFile(io.BytesIO(qti.content))
    for name in package.namelist():
        assert PRACTICE_ID.search(name) is None and str(SEED) not in name
        if name.startswith("items/") and name.endswith(".xml"):
            item = ET.fromstring(package.read(name))
            body_node = item.find("{http://www.imsglobal.org/xsd/imsqti_v2p1}itemBody")
            assert body_node is not None
            shown = ET.tostring(body_node, encoding="unicode")  # what the LMS shows
            assert PRACTICE_ID.search(shown) is None and str(SEED) not in shown
            assert not carries(shown, answers)


def test_the_instructor_key_of_an_exam_set_names_the_exam_ids(exam_client: TestClient) -> None:
    exercises = exam_set(exam_client, "slider_crank", 2)
    body = {"type": "slider_crank", "seed": SEED, "count": 2, "exam": True}
    key = exam_client.post(f"{API}/export", json={**body, "format": "csv"}).text
    sheet = exam_client.post(
        f"{API}/export", json={**body, "format": "html", "with_solutions": True}
    ).text
    for e in exercises:
        assert e["id"] in key and e["id"] in sheet
        assert repr(next(iter(e["answers"].values()))) in key


def test_without_the_secret_exam_sets_are_refused_saying_how_to_set_it(
    client: TestClient, monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.delenv(VARIABLE, raising=False)
    exam = exam_id(ExerciseId("four_bar_velocity", "standard", SEED, 0), SECRET.encode())
    body = {"type": "four_bar_velocity", "seed": SEED, "exam": True}
    for r in (
        client.post(API, json=body),
        client.post(f"{API}/export", json={**body, "format": "html"}),
        client.get(f"{API}/{exam}"),
    ):
        assert r.status_code == 503 and r.headers["content-type"] == "application/problem+json"
        assert r.json()["code"] == "not_configured" and VARIABLE in r.json()["detail"]
    checked = client.post(f"{API}/check", json={"id": exam, "answers": {}})
    assert checked.status_code == 403


def test_practice_ids_keep_their_key_and_their_alt_text_names_no_id(client: TestClient) -> None:
    ident = "four_bar_velocity:standard:2027:0"
    body = client.get(f"{API}/{ident}").json()
    assert (
        body["id"] == ident and body["answers"] and body["solution"]["steps"] and "exam" not in body
    )
    xml = client.post(
        f"{API}/export",
        json={"type": "four_bar_velocity", "seed": 2027, "format": "moodle_xml"},
    )
    assert xml.headers["content-disposition"].endswith('-standard-2027.xml"')
    (text,) = question_texts(xml.content)
    assert ident not in text and 'alt="Figure: ' in text

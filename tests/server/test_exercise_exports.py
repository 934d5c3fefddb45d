"""Exports: Moodle XML parsed and checked question by question, CSV and HTML carry every answer,
JSON is the /exercises response; statements and solutions typeset with the vendored KaTeX."""

from __future__ import annotations

import base64
import csv
import io
import json
import re
import shutil
import subprocess
import xml.etree.ElementTree as ET
from html.parser import HTMLParser
from pathlib import Path
from typing import Any

import pytest
from fastapi.testclient import TestClient

from solver.exercises import DIFFICULTIES, TYPES, ExerciseId, build

API = "/api/v1/exercises"
ROOT = Path(__file__).resolve().parents[2]
NODE = shutil.which("node")
CLOZE_PART = re.compile(r"\{1:NUMERICAL:=([-0-9.e+]+):([0-9.e+-]+)\}")


def export(client: TestClient, **body: Any) -> Any:
    r = client.post(f"{API}/export", json={"seed": 5, "count": 3, **body})
    assert r.status_code == 200, r.text
    return r


def key_of(client: TestClient, kind: str, difficulty: str = "standard") -> list[dict[str, Any]]:
    r = client.post(API, json={"type": kind, "seed": 5, "count": 3, "difficulty": difficulty})
    exercises: list[dict[str, Any]] = r.json()["exercises"]
    return exercises


def _svg_file(question: ET.Element) -> None:
    files = question.findall("questiontext/file")
    assert len(files) == 1 and files[0].get("name") == "figure.svg"
    assert files[0].get("encoding") == "base64"
    svg = ET.fromstring(base64.b64decode(files[0].text or ""))
    assert svg.tag == "{http://www.w3.org/2000/svg}svg"
    assert "@@PLUGINFILE@@/figure.svg" in (question.findtext("questiontext/text") or "")


@pytest.mark.parametrize("kind", list(TYPES))
def test_moodle_xml_cloze_questions_carry_the_key(client: TestClient, kind: str) -> None:
    r = export(client, type=kind, format="moodle_xml")
    assert r.headers["content-type"].startswith("application/xml")
    assert r.headers["content-disposition"] == (
        f'attachment; filename="exercises-{kind}-standard-5.xml"'
    )
    quiz = ET.fromstring(r.content)
    assert quiz.tag == "quiz"
    category, *questions = quiz.findall("question")
    assert category.get("type") == "category" and category.findtext("category/text")
    exercises = key_of(client, kind)
    assert len(questions) == len(exercises)
    for q, e in zip(questions, exercises, strict=True):
        assert q.get("type") == "cloze"
        assert q.findtext("name/text") == e["id"]
        _svg_file(q)
        text = q.findtext("questiontext/text") or ""
        parts = CLOZE_PART.findall(text)
        assert len(parts) == len(e["asked"])
        for (answer, tolerance), asked in zip(parts, e["asked"], strict=True):
            expected = e["answers"][asked["key"]]
            assert float(answer) == expected
            assert float(tolerance) == pytest.approx(abs(expected) * asked["tolerance"], rel=1e-15)
        assert int(q.findtext("defaultgrade") or 0) == len(e["asked"])


def test_moodle_xml_numerical_questions_one_per_quantity(client: TestClient) -> None:
    r = export(client, type="four_bar_acceleration", format="moodle_xml",
               moodle_question="numerical")  # fmt: skip
    questions = ET.fromstring(r.content).findall("question")[1:]
    exercises = key_of(client, "four_bar_acceleration")
    expected = [(e, a) for e in exercises for a in e["asked"]]
    assert len(questions) == len(expected)
    for q, (e, asked) in zip(questions, expected, strict=True):
        assert q.get("type") == "numerical"
        assert q.findtext("name/text") == f"{e['id']} {asked['key']}"
        _svg_file(q)
        answers = q.findall("answer")
        assert len(answers) == 1 and answers[0].get("fraction") == "100"
        value = float(answers[0].findtext("text") or "nan")
        assert value == e["answers"][asked["key"]]
        tolerance = float(answers[0].findtext("tolerance") or "nan")
        assert tolerance == pytest.approx(abs(value) * asked["tolerance"], rel=1e-15)
        assert q.findtext("units/unit/unit_name") == asked["unit"]


def test_moodle_auto_makes_a_single_quantity_numerical(client: TestClient) -> None:
    from solver.exercises.export import moodle_xml

    e = build(ExerciseId("slider_crank", "basic", 1, 0))
    one = type(e)(e.id, e.title, e.statement, e.scene, e.asked[:1], e.answers)
    quiz = ET.fromstring(moodle_xml([one]))
    assert [q.get("type") for q in quiz.findall("question")] == ["category", "numerical"]


def test_csv_key_has_a_row_per_exercise_and_quantity(client: TestClient) -> None:
    r = export(client, type="quick_return", difficulty="challenging", format="csv")
    assert r.headers["content-type"].startswith("text/csv")
    rows = list(csv.DictReader(io.StringIO(r.text)))
    exercises = key_of(client, "quick_return", "challenging")
    expected = [(e, a) for e in exercises for a in e["asked"]]
    assert len(rows) == len(expected)
    for row, (e, asked) in zip(rows, expected, strict=True):
        assert row["id"] == e["id"] and row["key"] == asked["key"] and row["path"] == asked["path"]
        assert float(row["answer"]) == e["answers"][asked["key"]]
        assert row["unit"] == asked["unit"]


def test_json_export_is_the_exercises_response(client: TestClient) -> None:
    r = export(client, type="moving_point", format="json")
    assert r.headers["content-type"].startswith("application/json")
    assert json.loads(r.content)["exercises"] == key_of(client, "moving_point")
    with_steps = export(client, type="moving_point", format="json", with_solutions=True).json()
    assert all(e["solution"]["steps"] for e in with_steps["exercises"])


class _Sheets(HTMLParser):
    def __init__(self) -> None:
        super().__init__()
        self.sections: list[str] = []
        self.answers: dict[str, list[str]] = {}
        self.svgs = 0
        self._answer: str | None = None

    def handle_starttag(self, tag: str, attrs: list[tuple[str, str | None]]) -> None:
        a = dict(attrs)
        if tag == "section":
            self.sections.append(a.get("data-id") or "")
        if tag == "svg":
            self.svgs += 1
        if tag == "td" and a.get("class") == "answer":
            self._answer = a.get("data-key")

    def handle_data(self, data: str) -> None:
        if self._answer is not None:
            self.answers.setdefault(self.sections[-1], []).append(f"{self._answer}={data}")
            self._answer = None


def test_html_sheets_one_page_per_exercise_with_and_without_the_key(client: TestClient) -> None:
    exercises = key_of(client, "inverted_slider_crank")
    student = _Sheets()
    student.feed(export(client, type="inverted_slider_crank", format="html").text)
    assert student.sections == [e["id"] for e in exercises]
    assert student.svgs == len(exercises) and not student.answers
    key_page = export(client, type="inverted_slider_crank", format="html", with_solutions=True)
    assert key_page.headers["content-disposition"].endswith('-key.html"')
    assert "page-break-after: always" in key_page.text
    key = _Sheets()
    key.feed(key_page.text)
    for e in exercises:
        assert key.answers[e["id"]] == [
            f"{a['key']}={e['answers'][a['key']]:.6g}" for a in e["asked"]
        ]
    assert key_page.text.count("class='step'") > 10 * len(exercises)


def test_export_rejects_an_unknown_format(client: TestClient) -> None:
    r = client.post(f"{API}/export", json={"type": "slider_crank", "format": "pdf"})
    assert r.status_code == 422 and r.json()["code"] == "invalid_scene"


@pytest.mark.slow
@pytest.mark.skipif(NODE is None, reason="node is not installed: KaTeX cannot run")
def test_statements_and_event_steps_typeset_with_katex() -> None:
    latex = []
    for kind in TYPES:
        for difficulty in DIFFICULTIES:
            e = build(ExerciseId(kind, difficulty, 2, 0))
            latex.append(e.statement.latex)
    from solver.exercises.solutions import worked_solution

    latex.append(worked_solution(build(ExerciseId("moving_point", "standard", 2, 0)))[-1]["latex"])
    done = subprocess.run(
        [str(NODE), str(ROOT / "tests" / "katex_check.mjs")],
        input="\n".join(json.dumps(s) for s in latex),
        capture_output=True,
        text=True,
        timeout=120,
    )
    failures = [json.loads(line) for line in done.stdout.splitlines() if '"ok":false' in line]
    assert done.returncode == 0 and not failures, failures


@pytest.mark.parametrize(
    "kind", ["synthesis_function", "synthesis_fixed_pivots", "synthesis_two_positions"]
)
def test_synthesis_exercises_in_every_export(client: TestClient, kind: str) -> None:
    """Exercises built on a synthesis task: the JSON carries the task, the CSV its paths into
    /synthesis and the key, the HTML sheets a figure each and the key with the worked solution."""
    exercises = client.post(API, json={"type": kind, "seed": 5, "count": 2}).json()["exercises"]
    assert all("task" in e and "scene" not in e for e in exercises)
    one = {"type": kind, "count": 2}
    assert json.loads(export(client, **one, format="json").content)["exercises"] == exercises
    rows = list(csv.DictReader(io.StringIO(export(client, **one, format="csv").text)))
    expected = [(e, a) for e in exercises for a in e["asked"]]
    assert [(r["id"], r["key"], r["path"]) for r in rows] == [
        (e["id"], a["key"], a["path"]) for e, a in expected
    ]
    assert [float(r["answer"]) for r in rows] == [e["answers"][a["key"]] for e, a in expected]
    student = _Sheets()
    student.feed(export(client, **one, format="html").text)
    assert student.sections == [e["id"] for e in exercises] and not student.answers
    assert student.svgs == len(exercises)
    key = _Sheets()
    key_page = export(client, **one, format="html", with_solutions=True).text
    key.feed(key_page)
    for e in exercises:
        assert key.answers[e["id"]] == [
            f"{a['key']}={e['answers'][a['key']]:.6g}" for a in e["asked"]
        ]
    assert key_page.count("class='step'") >= 4 * len(exercises)
    numerical = ET.fromstring(
        export(client, **one, format="moodle_xml", moodle_question="numerical").content
    )
    assert len(numerical.findall("question")) == 1 + len(expected)

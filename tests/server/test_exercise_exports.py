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
from html import escape
from html.parser import HTMLParser
from pathlib import Path
from typing import Any

import pytest
from fastapi.testclient import TestClient

from server.mathml import mathml
from solver.exercises import DIFFICULTIES, TYPES, ExerciseId, build
from solver.exercises.checking import mistakes_of
from solver.exercises.export import html_sheets, latex_items, moodle_xml, significant_digits
from solver.exercises.model import parse_id, within
from solver.teaching.mistakes import typical_mistake
from tests.moodle_rules import cloze_parts, math_problems, problems

API = "/api/v1/exercises"
ROOT = Path(__file__).resolve().parents[2]
NODE = shutil.which("node")
REFERENCES = ROOT / "tests" / "reference" / "moodle"


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


def _written(text: str, expected: float, tolerance: float) -> None:
    """An answer as the key writes it: within a tenth of the tolerance of the solver's value,
    in at most ``significant_digits`` digits (not sized by the value's repr)."""
    assert abs(float(text) - expected) <= 0.1 * tolerance * abs(expected)
    assert len(text.lstrip("-").replace(".", "").lstrip("0")) <= significant_digits(tolerance)


@pytest.mark.parametrize("kind", list(TYPES))
def test_moodle_xml_cloze_questions_carry_the_key_and_the_mistakes(
    client: TestClient, kind: str
) -> None:
    r = export(client, type=kind, format="moodle_xml")
    assert r.headers["content-type"].startswith("application/xml")
    assert r.headers["content-disposition"] == (
        f'attachment; filename="exercises-{kind}-standard-5.xml"'
    )
    assert problems(r.text) == []
    quiz = ET.fromstring(r.content)
    category, *questions = quiz.findall("question")
    assert category.get("type") == "category" and category.findtext("category/text")
    assert "random question" in (category.findtext("info/text") or "")
    exercises = key_of(client, kind)
    assert len(questions) == len(exercises)
    for q, e in zip(questions, exercises, strict=True):
        assert q.get("type") == "cloze"
        assert q.findtext("name/text") == e["id"]
        _svg_file(q)
        text = q.findtext("questiontext/text") or ""
        parts = cloze_parts(text)
        assert len(parts) == len(e["asked"])
        made = mistakes_of(build(parse_id(e["id"])))
        for (right, *wrong), asked in zip(parts, e["asked"], strict=True):
            expected = e["answers"][asked["key"]]
            assert right.fraction == 100
            _written(str(right.value), expected, asked["tolerance"])
            assert right.tolerance == pytest.approx(abs(expected) * asked["tolerance"], rel=5e-3)
            for w in wrong:  # each at a typical mistake's value, its feedback naming it
                assert w.fraction == 0
                assert not within(w.value, expected, asked["tolerance"])
                named = [
                    m
                    for m in made
                    if m.values.get(asked["key"]) is not None
                    and within(w.value, m.values[asked["key"]], 0.1 * asked["tolerance"])
                ]
                assert named, (asked["key"], w)
                assert typical_mistake(named[0].kind).title.rstrip(".") in w.feedback
        assert int(q.findtext("defaultgrade") or 0) == len(e["asked"])
        feedback = q.findtext("generalfeedback/text") or ""
        assert "The answers:" in feedback and "Worked solution" not in feedback


def test_moodle_xml_names_the_typical_mistakes_of_every_family(client: TestClient) -> None:
    """A distractor per mistake that gives a distinct wrong value: the sense of rotation, degrees
    for radians, the Coriolis term left out and halved."""
    r = export(client, type="moving_point", format="moodle_xml", count=4)
    feedback = " ".join(
        a.feedback
        for q in ET.fromstring(r.content).findall("question")[1:]
        for part in cloze_parts(q.findtext("questiontext/text") or "")
        for a in part
    )
    for kind in ("rotation_sign", "degrees_for_radians", "coriolis_left_out",
                 "coriolis_without_factor_2"):  # fmt: skip
        assert typical_mistake(kind).title.rstrip(".") in feedback


def test_moodle_xml_general_feedback_has_the_worked_solution_when_asked(
    client: TestClient,
) -> None:
    r = export(client, type="slider_crank", format="moodle_xml", count=1, with_solutions=True)
    assert problems(r.text) == []
    q = ET.fromstring(r.content).findall("question")[1]
    feedback = q.findtext("generalfeedback/text") or ""
    assert "Worked solution" in feedback and feedback.count("\\[") > 5


def test_moodle_xml_statement_data_one_formula_a_line() -> None:
    """The data as a list of short inline formulas (MathJax 3 ignores \\\\ in inline math)."""
    e = build(ExerciseId("four_bar_acceleration", "challenging", 3, 0))
    text = ET.fromstring(moodle_xml([e])).findall("question")[1].findtext("questiontext/text")
    assert text is not None
    items = re.findall(r"<li>\\\((.*?)\\\)</li>", text)
    assert items == latex_items(e.statement.latex) and len(items) >= 7
    assert any(item.startswith(r"\varphi_{AB} = ") for item in items)
    assert all("\\\\" not in item and len(item) <= 80 for item in items)
    assert math_problems(text, "statement") == []


@pytest.mark.parametrize("tolerance", [0.05, 0.002])
def test_the_tolerance_is_chosen_per_export(client: TestClient, tolerance: float) -> None:
    r = export(client, type="four_bar_velocity", format="moodle_xml", count=1,
               tolerance=tolerance)  # fmt: skip
    (e,) = key_of(client, "four_bar_velocity")[:1]
    parts = cloze_parts(ET.fromstring(r.content).findall("question")[1].findtext(
        "questiontext/text") or "")  # fmt: skip
    for (right, *_), asked in zip(parts, e["asked"], strict=True):
        expected = e["answers"][asked["key"]]
        _written(str(right.value), expected, tolerance)
        assert right.tolerance == pytest.approx(abs(expected) * tolerance, rel=5e-3)
    rows = list(csv.DictReader(io.StringIO(export(client, type="four_bar_velocity",
                format="csv", count=1, tolerance=tolerance).text)))  # fmt: skip
    assert {float(row["tolerance"]) for row in rows} == {tolerance}


@pytest.mark.parametrize("tolerance", [0, -0.01, 0.00001, 0.5])
def test_a_tolerance_out_of_range_is_refused(client: TestClient, tolerance: float) -> None:
    r = client.post(f"{API}/export", json={"type": "slider_crank", "format": "moodle_xml",
                                            "tolerance": tolerance})  # fmt: skip
    assert r.status_code == 422 and r.json()["code"] == "invalid_scene"


@pytest.mark.parametrize("reference", sorted(REFERENCES.glob("*.xml")), ids=lambda p: p.stem)
def test_the_reference_moodle_files_follow_moodles_import_rules(reference: Path) -> None:
    assert reference.stem in TYPES
    xml = reference.read_text()
    assert problems(xml) == []
    q = ET.fromstring(xml).findall("question")[1]
    assert "Worked solution" in (q.findtext("generalfeedback/text") or "")


def test_the_rules_catch_what_moodle_would_refuse() -> None:
    """The checker's own test: each broken rule is reported."""
    good = moodle_xml([build(ExerciseId("slider_crank", "basic", 1, 0))])
    assert problems(good) == []
    broken = {
        "inline break": good.replace("<li>\\(", "<li>\\(a \\\\ b ", 1),
        "no 100 %": good.replace(":NUMERICAL:=", ":NUMERICAL:%50%"),
        "no file": re.sub(r"<file [^>]*>[^<]*</file>", "", good),
        "category": good.replace("$course$/", "", 1),
        "unescaped": re.sub(r"#Right\.", "#Right } now", good, count=1),
    }
    for name, xml in broken.items():
        assert problems(xml), name


def test_moodle_auto_makes_a_single_quantity_numerical(client: TestClient) -> None:
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
    r = client.post(f"{API}/export", json={"type": "slider_crank", "format": "docx"})
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


def test_html_sheets_are_self_contained_with_mathml(client: TestClient) -> None:
    """No script, no external file: every formula typeset on the server as MathML."""
    for with_solutions in (False, True):
        page = export(client, type="moving_point", format="html", with_solutions=with_solutions)
        html = page.text
        assert "<script" not in html and "/vendor/" not in html
        assert not re.search(r"""(?:src|href)=["'](?!@)""", re.sub(r"<svg.*?</svg>", "", html,
                                                                  flags=re.S))  # fmt: skip
        assert html.count("<math") >= 3 and "<code class='tex'>" not in html
        assert "@media print" in html and "break-after: page" in html


def test_one_sheet_per_student_of_the_class_list(client: TestClient) -> None:
    names = ["Ada Lovelace", "James Watt", 'Emmy "E." Noether', "Ludwig Burmester"]
    csv_text = "name,number\n" + "".join(f'"{n.replace(chr(34), 2 * chr(34))}",{k}\n'
                                          for k, n in enumerate(names))  # fmt: skip
    sheets = _Sheets()
    page = export(client, type="slider_crank", format="html", students_csv=csv_text)
    sheets.feed(page.text)
    assert len(sheets.sections) == len(names) == len(set(sheets.sections))
    for name in names:
        assert f"Name: {escape(name)}</div>" in page.text
    moodle = export(client, type="slider_crank", format="moodle_xml", students_csv=csv_text)
    assert len(ET.fromstring(moodle.content).findall("question")) == 1 + len(names)
    for bad in ("name\n", "".join(f"student {k}\n" for k in range(101))):  # 0 and 101 names
        r = client.post(f"{API}/export", json={"type": "slider_crank", "format": "html",
                                                "students_csv": bad})  # fmt: skip
        assert r.status_code == 422, (bad[:20], r.text)


def test_every_statement_and_solution_line_converts_to_mathml() -> None:
    """No formula of any type falls back to its LaTeX source on the sheets; the fallback itself
    keeps an unreadable formula legible instead of failing the sheet."""
    for kind in TYPES:
        sheet = html_sheets([build(ExerciseId(kind, "standard", 2, 0))], True, mathml)
        assert "<code class='tex'>" not in sheet and sheet.count("<math") > 5, kind
    assert mathml(r"\frac{").startswith("<code class='tex'>")


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

"""The PDF export (server.pdf): the HTML sheets printed by headless Chromium, one page per
exercise for the students, the key with its worked solutions; a server without Chromium answers
503 pdf_unavailable saying what to install.

No PDF text extractor is in the test lock, so what the PDF says is checked on the HTML it
prints (the html export of the same request, the same function): its numbers are the
statement's, and a student sheet of an exam set carries no answer, no practice id and no seed.
"""

from __future__ import annotations

import re
from collections.abc import Iterator
from html import unescape
from typing import Any

import pytest
from fastapi.testclient import TestClient

from server.app import app
from solver.exercises.export import latex_items

API = "/api/v1/exercises"
SECRET = "the tests' deployment secret, long enough"
SEED = 2**40 + 7
PAGE = re.compile(rb"/Type\s*/Page(?![a-zA-Z])")  # a page object, not the /Pages tree
NUMBER = re.compile(r"[0-9]+(?:\.[0-9]+)?")  # unsigned: MathML writes a minus as its own <mo>


@pytest.fixture(scope="module")
def exam_client() -> Iterator[TestClient]:
    """A server with the exam secret in its environment."""
    with pytest.MonkeyPatch.context() as patch:
        patch.setenv("KINEMATICS_EXAM_SECRET", SECRET)
        with TestClient(app, raise_server_exceptions=False) as test_client:
            yield test_client


def _export(client: TestClient, **body: Any) -> Any:
    r = client.post(f"{API}/export", json={"seed": SEED, "exam": True, **body})
    assert r.status_code == 200, r.text
    return r


def _text(html: str) -> str:
    """The text a reader sees: tags (the MathML's too) and the figures' SVG left out."""
    html = re.sub(r"<svg.*?</svg>", " ", html, flags=re.S)
    return unescape(re.sub(r"<[^>]+>", " ", html))


def _stated_numbers(latex: str) -> list[str]:
    """The numbers the statement's data give, as written (``|AB| = 0.16\\,\\mathrm{m}``: 0.16)."""
    return [m.group() for item in latex_items(latex) for m in [NUMBER.search(item.split("=")[-1])]
            if m is not None]  # fmt: skip


@pytest.mark.parametrize(
    ("kind", "difficulty"),
    [("four_bar_velocity", "challenging"), ("synthesis_fixed_pivots", "challenging")],
)
def test_the_student_pdf_has_a_page_per_exercise_and_prints_no_key(
    exam_client: TestClient, kind: str, difficulty: str
) -> None:
    request = {"type": kind, "difficulty": difficulty, "count": 3}
    pdf = _export(exam_client, format="pdf", **request)
    assert pdf.headers["content-type"] == "application/pdf"
    name = pdf.headers["content-disposition"]
    assert name.endswith('.pdf"') and "-key" not in name and str(SEED) not in name
    assert pdf.content.startswith(b"%PDF-")
    assert len(PAGE.findall(pdf.content)) == 3
    key = exam_client.post(API, json={"seed": SEED, "exam": True, **request}).json()["exercises"]
    text = _text(_export(exam_client, format="html", **request).text)
    numbers = set(NUMBER.findall(text))
    for e in key:
        stated = _stated_numbers(e["statement"]["latex"])
        assert stated and set(stated) <= numbers, set(stated) - numbers
        for value in e["answers"].values():
            written = {f"{abs(value):.4g}", f"{abs(value):.5g}", f"{abs(value):.6g}"}
            if len(re.sub(r"[^0-9]", "", f"{value:.4g}").strip("0")) >= 3:  # not a round datum
                assert not written & numbers, (e["id"], value)
        assert e["id"].startswith("exam-")
    assert not re.search(r"[a-z_]+:[a-z]+:[0-9]+:[0-9]+", text) and str(SEED) not in text


def test_the_key_pdf_prints_the_answers_and_the_worked_solutions(exam_client: TestClient) -> None:
    request = {"type": "slider_crank", "difficulty": "basic", "count": 1}
    pdf = _export(exam_client, format="pdf", with_solutions=True, **request)
    assert pdf.headers["content-disposition"].endswith('-key.pdf"')
    assert pdf.content.startswith(b"%PDF-") and len(PAGE.findall(pdf.content)) >= 2
    html = _export(exam_client, format="html", with_solutions=True, **request).text
    key = exam_client.post(API, json={"seed": SEED, "exam": True, **request}).json()["exercises"]
    text = _text(html)
    assert "Worked solution" in text
    for e in key:
        for value in e["answers"].values():
            assert f"{value:.6g}" in text


def test_without_chromium_a_pdf_is_503_pdf_unavailable_saying_what_to_install(
    exam_client: TestClient,
) -> None:
    with pytest.MonkeyPatch.context() as patch:
        patch.setenv("KINEMATICS_CHROMIUM", "/nonexistent/chromium")
        r = exam_client.post(
            f"{API}/export", json={"type": "slider_crank", "seed": 3, "format": "pdf"}
        )
        other = exam_client.post(
            f"{API}/export", json={"type": "slider_crank", "seed": 3, "format": "html"}
        )
    assert r.status_code == 503, r.text
    assert r.headers["content-type"] == "application/problem+json"
    problem = r.json()
    assert problem["code"] == "pdf_unavailable" and problem["type"] == "/problems/pdf_unavailable"
    assert "apt-get install chromium" in problem["detail"]
    assert "KINEMATICS_CHROMIUM" in problem["detail"]
    assert other.status_code == 200  # every other format still served

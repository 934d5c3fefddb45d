"""Exercises in the browser: the printable sheet rendered in Chromium, the instructor page and
the student mode (static/exercises.html), against the real server."""

from __future__ import annotations

import json
import re
import urllib.request
from pathlib import Path
from typing import Any

import pytest

from tests.browser.conftest import AppPage, PageLog

pytestmark = pytest.mark.browser


def export(app: AppPage, **body: Any) -> str:
    request = urllib.request.Request(
        f"{app.url}/api/v1/exercises/export",
        data=json.dumps(body).encode(),
        headers={"Content-Type": "application/json"},
        method="POST",
    )
    with urllib.request.urlopen(request, timeout=60) as response:
        text: str = response.read().decode()
        return text


@pytest.mark.slow
@pytest.mark.parametrize("with_solutions", [False, True])
def test_the_printable_sheet_renders_from_disk_with_its_figures_and_formulas(
    app: AppPage, with_solutions: bool, tmp_path: Path
) -> None:
    students = "name\nAda Lovelace\nJames Watt\nEmmy Noether\n"
    html = export(
        app, type="quick_return", seed=12, format="html", with_solutions=with_solutions,
        students_csv=students,
    )  # fmt: skip
    saved = tmp_path / "sheet.html"
    saved.write_text(html)
    page = app.context.new_page()  # a page of its own: the app's page asks for 127.0.0.1 only
    requests: list[str] = []
    page.on("request", lambda r: requests.append(r.url))
    page.goto(saved.as_uri(), wait_until="load")  # opened from disk: nothing else to load
    assert requests == [saved.as_uri()]
    assert page.locator("section.sheet").count() == 3
    names = page.locator(".name").all_inner_texts()
    assert names == ["Name: Ada Lovelace", "Name: James Watt", "Name: Emmy Noether"]
    figures = page.locator("section.sheet figure svg")
    assert figures.count() == 3
    for k in range(3):
        box = figures.nth(k).bounding_box()
        assert box is not None and box["width"] > 300 and box["height"] > 200
        assert figures.nth(k).locator("line, polygon").count() >= 3
    formulas = page.locator(".tex math")
    assert formulas.count() >= 3 and page.locator(".tex code").count() == 0
    for k in range(formulas.count()):  # typeset: MathML laid out, not raw LaTeX
        box = formulas.nth(k).bounding_box()
        assert box is not None and box["height"] > 8 and box["width"] > 8
    assert "\\mathrm" not in page.locator("body").inner_text()
    pdf = page.pdf(format="A4")
    pages = len(re.findall(rb"/Type\s*/Page[^s]", pdf))
    if with_solutions:
        assert pages >= 3
        assert page.locator(".step").count() > 30
    else:
        assert pages == 3  # one page per student
    sheet = AppPage(page=page, log=PageLog(), url=saved.as_uri())
    sheet.screenshot(f"exercise-sheet-{'key' if with_solutions else 'student'}")


def open_page(app: AppPage, fragment: str = "") -> None:
    app.page.goto(f"{app.url}/exercises.html{fragment}")


def test_the_instructor_page_generates_previews_and_downloads(app: AppPage) -> None:
    page = app.page
    open_page(app)
    page.wait_for_selector("#preview .card")
    assert page.locator("#preview .card").count() == 5
    page.select_option("#ex-type", "quick_return")
    page.select_option("#ex-difficulty", "challenging")
    page.fill("#ex-count", "2")
    page.fill("#ex-seed", "9")
    page.click("#ex-generate")
    page.wait_for_selector('#preview .card[data-id="quick_return:challenging:9:1"]')
    cards = page.locator("#preview .card")
    assert cards.count() == 2
    status, body = app.post(
        "/exercises", {"type": "quick_return", "difficulty": "challenging", "seed": 9, "count": 2}
    )
    assert status == 200
    for k, exercise in enumerate(body["exercises"]):
        card = cards.nth(k)
        assert card.get_attribute("data-id") == exercise["id"]
        assert card.locator("figure svg").count() == 1
        card.locator("summary").click()
        for asked in exercise["asked"]:
            shown = card.locator(f'.key-value[data-key="{asked["key"]}"]').inner_text()
            assert float(shown) == pytest.approx(exercise["answers"][asked["key"]], rel=1e-5)
    page.wait_for_function("() => (document.querySelectorAll('#preview .tex .katex').length >= 2)")
    with page.expect_download() as download_info:
        page.click('.downloads button[data-format="csv"]')
    download = download_info.value
    assert download.suggested_filename == "exercises-quick_return-challenging-9.csv"
    text = Path(download.path()).read_text(encoding="utf-8")
    for exercise in body["exercises"]:
        for asked in exercise["asked"]:
            assert repr(exercise["answers"][asked["key"]]) in text
    # the export's own fields: the tolerance in %, a class list (one sheet per student), QTI
    page.fill("#ex-tolerance", "2")
    page.set_input_files(
        "#ex-students",
        files=[{"name": "class.csv", "mimeType": "text/csv",
                "buffer": b"name\nAda Lovelace\nJames Watt\nEmmy Noether\n"}],
    )  # fmt: skip
    with page.expect_download() as download_info:
        page.click('.downloads button[data-format="html"]:not([data-solutions])')
    sheets = Path(download_info.value.path()).read_text(encoding="utf-8")
    assert sheets.count('<section class="sheet"') == 3 and "Name: Emmy Noether" in sheets
    # the same sheets printed by the server: one page per student
    with page.expect_download() as download_info:
        page.click('.downloads button[data-format="pdf"]:not([data-solutions])')
    assert download_info.value.suggested_filename.endswith(".pdf")
    pdf = Path(download_info.value.path()).read_bytes()
    assert pdf.startswith(b"%PDF-") and len(re.findall(rb"/Type\s*/Page(?![a-zA-Z])", pdf)) == 3
    with page.expect_download() as download_info:
        page.click('.downloads button[data-format="qti"]')
    assert download_info.value.suggested_filename.endswith(".zip")
    with page.expect_download() as download_info:
        page.click('.downloads button[data-format="csv"]')
    rows = Path(download_info.value.path()).read_text(encoding="utf-8").splitlines()[1:]
    assert rows and all(",0.02," in row for row in rows)
    app.screenshot("exercises-instructor-1440")
    page.set_viewport_size({"width": 390, "height": 844})
    app.screenshot("exercises-instructor-390")
    assert not app.serious_accessibility_violations()
    with page.expect_download() as download_info:
        page.click('.downloads button[data-format="moodle_xml"]')
    assert download_info.value.suggested_filename.endswith(".xml")
    app.screenshot("exercises-instructor")


def test_the_student_mode_checks_diagnoses_and_reveals_one_step_at_a_time(app: AppPage) -> None:
    from solver.exercises import build, parse_id
    from solver.exercises.mistakes import typical_mistakes

    ident = "four_bar_acceleration:standard:3:0"
    exercise = build(parse_id(ident))
    made = next(m for m in typical_mistakes(exercise) if m.kind == "alpha_in_normal_term")
    page = app.page
    open_page(app, f"#id={ident}")
    page.wait_for_selector("#answer-rows tr")
    assert page.inner_text("#st-id") == ident
    assert page.locator("#st-figure svg").count() == 1
    keys = [a.key for a in exercise.asked]
    assert page.locator("#answer-rows tr").count() == len(keys)
    page.fill(f'input[name="{keys[0]}"]', f"{exercise.answers[keys[0]]:.5g}")
    page.fill(f'input[name="{keys[1]}"]', repr(made.values[keys[1]]))
    page.click("#check")
    page.wait_for_selector("#answer-rows .result.correct")
    rows = page.locator("#answer-rows tr")
    assert "correct" in (rows.nth(0).locator(".result").get_attribute("class") or "")
    wrong = rows.nth(1).locator(".result")
    assert "incorrect" in (wrong.get_attribute("class") or "")
    assert wrong.locator(".diagnosis").inner_text() == made.sentence
    assert "missing" in (rows.nth(2).locator(".result").get_attribute("class") or "")
    assert page.inner_text("#score") == f"1 of {len(keys)} correct"
    # the worked solution: nothing shown until asked, then one step per click
    assert page.locator("#st-steps li").count() == 0
    page.click("#next-step")
    assert page.locator("#st-steps li").count() == 1
    page.click("#next-step")
    assert page.locator("#st-steps li").count() == 2
    page.wait_for_function("() => (document.querySelectorAll('#st-steps .katex').length >= 1)")
    assert page.locator("#st-steps .step-error").count() == 0
    app.screenshot("exercises-student")
    # the share link carries the exercise id and opens the same exercise
    page.click("#st-share")
    link = page.input_value("#st-share-url")
    assert link.endswith(f"/exercises.html#id={ident.replace(':', '%3A')}")
    other = app.new_page()
    other.goto(link)
    other.wait_for_selector("#answer-rows tr")
    assert other.inner_text("#st-id") == ident


# Each block of formulas: the width it had before it was narrowed to fit its column
# (data-narrow) or null, and whether it still scrolls sideways.
FITS = """(selector) => [...document.querySelectorAll(selector)].map((b) => (
  { narrow: b.dataset.narrow ?? null, scrolls: b.scrollWidth > b.clientWidth + 1 }))"""


def test_on_a_phone_the_statement_gives_its_data_one_to_a_line(app: AppPage) -> None:
    """At 390 px the quick-return's data (four to a row, about 560 px wide) went past the
    column's edge; they are typeset again one datum to a line and fit, in the student mode and
    in the instructor's preview, and the worked solution's steps are narrowed as in the app."""
    page = app.page
    page.set_viewport_size({"width": 390, "height": 844})
    open_page(app, "#id=quick_return:challenging:9:0")
    page.wait_for_selector("#st-latex .step-math[data-narrow]")
    assert page.evaluate(FITS, "#st-latex .step-math") == [
        {"narrow": page.get_attribute("#st-latex .step-math", "data-narrow"), "scrolls": False}
    ]
    assert page.locator("#st-latex .step-error").count() == 0
    page.click("#next-step")
    page.wait_for_selector("#st-steps .step-math .katex")
    # Nothing scrolls sideways: the figure scales to the column, the answers' table fits it.
    assert page.evaluate("() => document.documentElement.scrollWidth <= window.innerWidth")
    app.screenshot("exercises-student-390")
    assert app.serious_accessibility_violations("#student") == []
    # The instructor's preview of the same type.
    open_page(app, "")
    page.wait_for_selector("#ex-type option", state="attached")
    page.select_option("#ex-type", "quick_return")
    page.select_option("#ex-difficulty", "challenging")
    page.click("#ex-generate")
    page.wait_for_selector("#preview article[data-id^='quick_return'] .tex .step-math[data-narrow]")
    blocks = page.evaluate(FITS, "#preview .tex .step-math")
    assert blocks and not any(b["scrolls"] for b in blocks), blocks
    # On a laptop the rows fit as they are; made narrow (a window, a phone turned), they give
    # their data one to a line then.
    page.set_viewport_size({"width": 1440, "height": 900})
    open_page(app, "#id=four_bar_acceleration:standard:3:0")
    page.wait_for_selector("#st-latex .step-math .katex")
    assert page.evaluate(FITS, "#st-latex .step-math") == [{"narrow": None, "scrolls": False}]
    page.set_viewport_size({"width": 390, "height": 844})
    page.wait_for_selector("#st-latex .step-math[data-narrow]")
    assert page.evaluate(FITS, "#st-latex .step-math")[0]["scrolls"] is False


def test_a_bad_share_link_says_why(app: AppPage) -> None:
    app.log.allow("422")
    open_page(app, "#id=not-an-id")
    app.page.wait_for_function(
        "() => (document.getElementById('status').textContent.includes('id'))"
    )
    assert "type:difficulty:seed:index" in app.page.inner_text("#status")


def test_the_exam_checkbox_draws_a_password_seed_and_asks_for_an_exam_set(app: AppPage) -> None:
    # the live server has no KINEMATICS_EXAM_SECRET: the page shows the server's refusal
    app.log.allow("503")
    page = app.page
    open_page(app)
    page.wait_for_selector("#preview .card")
    page.check("#ex-exam")
    seed = int(page.input_value("#ex-seed"))
    assert 2**32 <= seed < 2**63
    with page.expect_request(lambda r: r.url.endswith("/api/v1/exercises")) as sent:
        page.click("#ex-generate")
    body = json.loads(sent.value.post_data or "{}")  # Python's json: integers exact
    assert body["exam"] is True and body["seed"] == seed
    page.wait_for_function(
        "() => document.getElementById('status').textContent.includes('KINEMATICS_EXAM_SECRET')"
    )
    page.fill("#ex-seed", str(2**63 - 1))  # the documented maximum, every digit kept
    with page.expect_request(lambda r: r.url.endswith("/api/v1/exercises")) as sent:
        page.click("#ex-generate")
    assert f'"seed":{2**63 - 1}' in (sent.value.post_data or "")


def test_the_student_mode_of_an_exam_exercise_shows_the_statement_only(app: AppPage) -> None:
    from solver.exercises import generate

    exercise = generate("slider_crank", "standard", 2**40, 1, b"a secret of this test only")[0]
    body = exercise.statement_json()
    page = app.page
    page.route(
        f"**/api/v1/exercises/{body['id']}",
        lambda route: route.fulfill(status=200, content_type="application/json", json=body),
    )
    open_page(app, f"#id={body['id']}")
    page.wait_for_selector("#answer-rows tr")
    assert page.inner_text("#st-id") == body["id"]
    assert page.locator("#answer-rows tr").count() == len(exercise.asked)
    assert page.locator("#check").is_hidden() and page.locator("#st-solution").is_hidden()
    assert page.locator("#st-exam").is_visible()

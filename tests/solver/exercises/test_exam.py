"""Exam ids (solver.exercises.exam): opaque, unforgeable, tied to the secret; exam exercises
drawn apart from the practice ones; their student-facing exports carry no key."""

from __future__ import annotations

import re

import pytest

from solver.exercises import TYPES, ExerciseId, build, generate
from solver.exercises.exam import UnknownExamId, exam_id, is_exam_id, open_exam_id
from solver.exercises.export import figure_alt, html_sheets, set_name

SECRET = b"a deployment secret of the tests"
OTHER = b"another deployment's secret...."
SEED = 2**40 + 12345
PRACTICE_ID = re.compile(r"[a-z_]+:[a-z]+:[0-9]+:[0-9]+")


@pytest.mark.parametrize("kind", list(TYPES))
def test_an_exam_id_opens_to_its_parameters_and_shows_none_of_them(kind: str) -> None:
    for difficulty in ("basic", "challenging"):
        ident = ExerciseId(kind, difficulty, SEED, 7)
        token = exam_id(ident, SECRET)
        assert is_exam_id(token) and re.fullmatch(r"exam-[A-Za-z0-9_-]+", token)
        assert open_exam_id(token, SECRET) == ident
        for shown in (kind, difficulty, str(SEED), f"{SEED:x}", str(ident)):
            assert shown not in token


def test_two_secrets_give_different_ids_and_neither_opens_the_other() -> None:
    ident = ExerciseId("four_bar_velocity", "standard", SEED, 0)
    mine, theirs = exam_id(ident, SECRET), exam_id(ident, OTHER)
    assert mine != theirs
    with pytest.raises(UnknownExamId):
        open_exam_id(theirs, SECRET)
    with pytest.raises(UnknownExamId):
        open_exam_id(mine, OTHER)


def test_a_forged_or_altered_id_is_unknown() -> None:
    token = exam_id(ExerciseId("slider_crank", "standard", SEED, 3), SECRET)
    flipped = token[:-3] + ("A" if token[-3] != "A" else "B") + token[-2:]
    for forged in (flipped, token[:-4], "exam-", "exam-AAAA", "exam-!!!!", token + "AA"):
        with pytest.raises(UnknownExamId):
            open_exam_id(forged, SECRET)


def test_exam_exercises_are_drawn_apart_from_the_practice_ones_and_per_secret() -> None:
    exams = generate("four_bar_velocity", "standard", SEED, 3, SECRET)
    others = generate("four_bar_velocity", "standard", SEED, 3, OTHER)
    practice = generate("four_bar_velocity", "standard", SEED, 3)
    texts = [e.statement.text for e in exams]
    assert texts != [e.statement.text for e in practice]
    assert texts != [e.statement.text for e in others]
    assert [e.name for e in exams] == [exam_id(e.id, SECRET) for e in exams]
    assert [e.statement.text for e in generate("four_bar_velocity", "standard", SEED, 3, SECRET)]
    assert texts == [
        e.statement.text for e in generate("four_bar_velocity", "standard", SEED, 3, SECRET)
    ]


def _answer_forms(value: float) -> set[str]:
    """How a sheet could print an answer; none for a round one (-2.0 rad/s may be a datum too)."""
    if len(re.sub(r"[^0-9]", "", f"{value:.6g}").strip("0")) < 4:
        return set()
    return {repr(value), f"{value:.6g}", f"{value:.5g}"}


def test_the_statement_view_of_an_exam_exercise_carries_no_key() -> None:
    exercise = generate("inverted_slider_crank", "challenging", SEED, 1, SECRET)[0]
    body = exercise.statement_json()
    assert set(body) == {"id", "exam", "title", "statement", "asked"}
    assert body["exam"] is True and body["id"] == exercise.exam_id
    assert all(set(a) == {"key", "label", "unit", "symbol", "tolerance"} for a in body["asked"])
    text = repr(body)
    for value in exercise.answers.values():
        assert not any(form in text for form in _answer_forms(value))


@pytest.mark.parametrize("kind", list(TYPES))
def test_the_student_sheet_of_an_exam_set_carries_no_practice_id_and_no_answer(kind: str) -> None:
    exercises = generate(kind, "standard", SEED, 2, SECRET)
    sheet = html_sheets(exercises, with_solutions=False)
    assert PRACTICE_ID.search(sheet) is None and str(SEED) not in sheet
    for e in exercises:
        assert e.exam_id is not None and e.exam_id in sheet
        for value in e.answers.values():
            assert not any(form in sheet for form in _answer_forms(value)), (kind, value)
    assert str(SEED) not in set_name(exercises, "-") and str(SEED) not in set_name(exercises, "/")


def test_the_alt_text_describes_the_figure_and_names_no_id() -> None:
    practice = build(ExerciseId("four_bar_velocity", "standard", 2027, 0))
    assert (
        figure_alt(practice) == f"Figure: {practice.title}, drawn to scale with its points labelled"
    )
    assert str(practice.id) not in figure_alt(practice)

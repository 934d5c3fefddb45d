"""Grading: each answer against its key within the relative tolerance, and, for a wrong one, the
typical mistake that gives it.

A wrong answer is put down to a mistake when it lies within the tolerance of the wrong value that
mistake gives (``solver.exercises.mistakes``), that wrong value being itself clearly apart from
the right one; the first such mistake in the list is named.
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

from solver.errors import InvalidScene
from solver.exercises.cams import cam_mistakes
from solver.exercises.gear_mistakes import gear_train_mistakes
from solver.exercises.generation import build
from solver.exercises.mistakes import WrongAnswers, answer_mistakes, typical_mistakes
from solver.exercises.model import Asked, Exercise, parse_id, relative_error, within
from solver.exercises.synthesis_mistakes import synthesis_mistakes


def _diagnosis(
    asked: Asked, given: float, expected: float, mistakes: list[WrongAnswers]
) -> WrongAnswers | None:
    for mistake in mistakes:
        wrong = mistake.values.get(asked.key)
        if (
            wrong is not None
            and not within(wrong, expected, asked.tolerance)
            and within(given, wrong, asked.tolerance)
        ):
            return mistake
    return None


def mistakes_of(exercise: Exercise) -> list[WrongAnswers]:
    """The typical mistakes that can be made in the exercise with the wrong answers they give: a
    gear train's (``solver.exercises.gear_mistakes``), a cam's (``solver.exercises.cams``), a
    synthesis task's (``solver.exercises.synthesis_mistakes``), else a linkage's or a spatial
    chain's (``solver.exercises.mistakes.typical_mistakes``); first a force given as the reaction
    and a negative answer given as its magnitude (named before a reversed rotation, which may
    give the same value), last the x and y components swapped (``answer_mistakes``). Of each
    only the answers it gets wrong (beyond the asked tolerance), and none that gets every answer
    right in this exercise (a sign mistake on a zero, weights where there is no gravity)."""
    written = answer_mistakes(exercise)
    first = [m for m in written if m.kind != "components_swapped"]
    swapped = [m for m in written if m.kind == "components_swapped"]
    if exercise.task is not None:
        found = synthesis_mistakes(exercise)
    elif exercise.scene.get("kind") == "gear_train":
        found = gear_train_mistakes(exercise)
    elif exercise.scene.get("kind") == "cam":
        found = [WrongAnswers(*made) for made in cam_mistakes(exercise)]
    else:
        found = typical_mistakes(exercise)
    asked = {a.key: a for a in exercise.asked}
    made = []
    for mistake in first + found + swapped:
        wrong = {
            key: value
            for key, value in mistake.values.items()
            if key not in asked or not within(value, exercise.answers[key], asked[key].tolerance)
        }
        if any(key in asked for key in wrong):
            made.append(WrongAnswers(mistake.kind, mistake.sentence, wrong))
    return made


def check_answers(exercise: Exercise, answers: Mapping[str, float | None]) -> dict[str, Any]:
    """The /exercises/check body: a verdict per asked quantity, the score (the share correct)."""
    unknown = sorted(set(answers) - {a.key for a in exercise.asked})
    if unknown:
        raise InvalidScene(
            f"answers: unknown key(s) {', '.join(k[:40] for k in unknown[:5])} for "
            f"{exercise.id}; asked: {', '.join(a.key for a in exercise.asked)}"
        )
    mistakes: list[WrongAnswers] | None = None
    results = []
    for asked in exercise.asked:
        expected = exercise.answers[asked.key]
        given = answers.get(asked.key)
        result: dict[str, Any] = {"key": asked.key, "given": given, "expected": expected}
        if given is None:
            result |= {"verdict": "missing", "relative_error": None, "diagnosis": None}
        elif within(given, expected, asked.tolerance):
            error = relative_error(given, expected)
            result |= {"verdict": "correct", "relative_error": error, "diagnosis": None}
        else:
            if mistakes is None:
                mistakes = mistakes_of(exercise)
            found = _diagnosis(asked, given, expected, mistakes)
            result |= {
                "verdict": "incorrect",
                "relative_error": relative_error(given, expected),
                "diagnosis": None if found is None else found.sentence,
                "mistake": None if found is None else found.kind,
            }
        results.append(result)
    correct = sum(r["verdict"] == "correct" for r in results)
    return {"id": str(exercise.id), "score": correct / len(results), "results": results}


def check(exercise_id: str, answers: Mapping[str, float | None]) -> dict[str, Any]:
    """Grade answers to the exercise named by its id (``invalid_scene`` for an unknown id)."""
    return check_answers(build(parse_id(exercise_id)), answers)

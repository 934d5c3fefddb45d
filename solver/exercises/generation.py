"""Seeded generation: the exercise of an id, well-posed by construction.

The generator of ``type:difficulty:seed:index`` is ``random.Random`` seeded with that very string
(a SHA-512 of it: the same on every platform and Python version). The family draws candidates from
it until one passes every check below, so an id always gives the same exercise:

- the scene assembles (the preset's closed form, then the solver's own analysis);
- the pose is well away from a dead centre: the condition number of the velocity equations is at
  most ``MAX_CONDITION`` (a dead centre is infinite);
- the family's own test holds (the asked Grashof class, the transmission angle);
- the statement ends with the sign convention of its kind of scene
  (``solver.exercises.conventions``);
- every answer is finite, at least ``SMALL`` and at most ``LARGE`` times the size of a quantity in
  its unit (omega of the crank for rad/s, omega^2 L for m/s^2, ...): never negligibly small, where
  a relative tolerance means nothing, and never absurd;
- no two asked answers within twice the tolerance of each other (swapped, both would be marked
  right: a flywheel with k omega^2 = 1 has Delta E = I_F).

The last two are checked first on the answers a draft foresees (``Draft.foreseen``, a synthesis
task's design), before it is solved: the same drafts are refused, at less cost.
"""

from __future__ import annotations

import json
import random
from collections.abc import Mapping
from dataclasses import replace
from functools import partial

from solver.analysis.instant import LinkageAnalysis
from solver.errors import InvalidScene, KinematicsError, LimitExceeded
from solver.exercises.answers import Solved, solve_scene, value_at, value_in
from solver.exercises.conventions import sign_convention
from solver.exercises.exam import exam_id, generator_seed
from solver.exercises.figures import figure_svg
from solver.exercises.model import (
    DIFFICULTIES,
    Draft,
    Exercise,
    ExerciseId,
    Statement,
    check_seed_index,
    within,
)
from solver.exercises.registry import TYPES, ExerciseType

MAX_ATTEMPTS = 2000
MAX_CONDITION = 60.0
SMALL = 0.02
LARGE = 50.0
MAX_COUNT = 100  # exercises per request
MAX_INDEX_SPREAD = 4  # a set of n draws its n distinct exercises from the indices below 4 n
PENDING = ExerciseId("", "", 0, 0)


class GenerationFailed(RuntimeError):
    """No well-posed candidate in MAX_ATTEMPTS draws: a defect of the family's ranges."""


def exercise_type(name: str) -> ExerciseType:
    kind = TYPES.get(name)
    if kind is None:
        raise InvalidScene(f"unknown exercise type '{name[:64]}'; available: {', '.join(TYPES)}")
    return kind


def check_difficulty(difficulty: str) -> None:
    if difficulty not in DIFFICULTIES:
        raise InvalidScene(
            f"difficulty: unknown {difficulty[:32]!r}; available: {', '.join(DIFFICULTIES)}"
        )


def ill_posed(draft: Draft, solved: Solved, answers: dict[str, float]) -> str | None:
    """Why the candidate is not a good exercise, or None (see the module docstring)."""
    analysis = solved.analysis
    if isinstance(analysis, LinkageAnalysis):
        condition = analysis.diagnostics.condition_number
        if condition is None or condition > MAX_CONDITION:
            return f"near a dead centre (condition number {condition})"
    reason = draft.check(analysis)
    if reason is not None:
        return reason
    return ill_posed_answers(draft, answers)


def ill_posed_answers(draft: Draft, answers: Mapping[str, float]) -> str | None:
    """Why the asked answers in ``answers`` (all of them, or those a draft foresees) make the
    draft ill-posed, or None: one out of scale, or two that coincide (the module docstring)."""
    known = [asked for asked in draft.asked if asked.key in answers]
    for asked in known:
        size = draft.scales[asked.unit]
        value = abs(answers[asked.key])
        if not SMALL * size <= value <= LARGE * size:
            return f"{asked.key} = {answers[asked.key]:.3g} {asked.unit} is out of scale"
    for k, first in enumerate(known):
        for second in known[k + 1 :]:
            tolerance = 2 * max(first.tolerance, second.tolerance)
            if within(answers[first.key], answers[second.key], tolerance):
                return f"{first.key} and {second.key} coincide: swapped, both would be right"
    return None


def foreseen_answers(draft: Draft) -> dict[str, float]:
    """The asked answers of ``draft`` that its ``foreseen`` body holds (empty without one)."""
    body = draft.foreseen()
    if body is None:
        return {}
    found = {}
    for asked in draft.asked:
        try:
            found[asked.key] = value_in(body, asked.path)
        except InvalidScene:  # (not there, or no number: the solved body says)
            continue
    return found


def _candidate(kind: ExerciseType, difficulty: str, rng: random.Random) -> Exercise | None:
    """A drawn draft as an exercise (its id filled in by the caller), or None when the draft
    does not assemble or is not well-posed (a draft whose foreseen answers make it ill-posed
    is not solved at all: ``Draft.foreseen``)."""
    try:
        draft = kind.draw(rng, difficulty)
        if ill_posed_answers(draft, foreseen_answers(draft)) is not None:
            return None
        solved = solve_scene(draft.scene)
        answers = {a.key: value_at(solved, a.path) for a in draft.asked}
    except KinematicsError:
        return None
    if ill_posed(draft, solved, answers) is not None:
        return None
    text = f"{draft.text} {sign_convention(draft.scene)}".rstrip()
    statement = Statement(text, draft.latex, partial(figure_svg, draft.scene))
    return Exercise(PENDING, draft.title, statement, draft.scene, draft.asked, answers)


def build(ident: ExerciseId) -> Exercise:
    """The exercise named by ``ident`` (its id string seeds the generator)."""
    return _drawn(ident, str(ident))


def build_exam(ident: ExerciseId, secret: bytes) -> Exercise:
    """The exam exercise of ``ident`` under the deployment secret: drawn from a generator only
    the secret seeds, named by its exam id (``solver.exercises.exam``)."""
    exercise = _drawn(ident, generator_seed(ident, secret))
    return replace(exercise, exam_id=exam_id(ident, secret))


def _drawn(ident: ExerciseId, seed: str) -> Exercise:
    kind = exercise_type(ident.type)
    check_difficulty(ident.difficulty)
    check_seed_index(ident.seed, ident.index)
    rng = random.Random(seed)
    for _ in range(MAX_ATTEMPTS):
        exercise = _candidate(kind, ident.difficulty, rng)
        if exercise is not None:
            return replace(exercise, id=ident)
    raise GenerationFailed(f"no well-posed exercise for {ident} in {MAX_ATTEMPTS} draws")


def check_generation(kind: str, difficulty: str, count: int) -> None:
    """Refuse, before any work, what ``generate`` would: an unknown type or difficulty, or a
    count outside 1 to MAX_COUNT."""
    exercise_type(kind)
    check_difficulty(difficulty)
    if not 1 <= count <= MAX_COUNT:
        raise LimitExceeded(f"count: expected 1 to {MAX_COUNT} exercises, got {count}")


def generate(
    kind: str, difficulty: str, seed: int, count: int, exam_secret: bytes | None = None
) -> list[Exercise]:
    """``count`` distinct exercises ``kind:difficulty:seed:0``, ``1``, ... (with ``exam_secret``
    their exam versions, ``build_exam``): an index whose scene an earlier one of the set already
    has is passed over for the next, so no two students of a set share an exercise while each id
    still determines its exercise alone."""
    check_generation(kind, difficulty, count)
    made: list[Exercise] = []
    seen: set[str] = set()
    for index in range(MAX_INDEX_SPREAD * count):
        ident = ExerciseId(kind, difficulty, seed, index)
        exercise = build(ident) if exam_secret is None else build_exam(ident, exam_secret)
        scene = json.dumps(exercise.scene, sort_keys=True)
        if scene not in seen:
            seen.add(scene)
            made.append(exercise)
            if len(made) == count:
                return made
    raise GenerationFailed(
        f"{kind} {difficulty}: fewer than {count} distinct exercises in "
        f"{MAX_INDEX_SPREAD * count} indices"
    )

"""Every datum an answer depends on is stated: change any one drawn input of any type, and when the
answers change the statement (its text, its LaTeX or the labels and dimensions of its figure)
changes too. And every statement states its sign convention and axes.

The inputs are changed where they are drawn: a generator that gives the same draws as the
exercise's own except the k-th (``Perturbed``), so every input of every type (the registry's,
those added later too) is tried without knowing how the type builds its scene.
"""

from __future__ import annotations

import math
import random
import re
from typing import TYPE_CHECKING, TypeVar

import pytest

from solver.errors import KinematicsError
from solver.exercises.answers import solve_scene, value_at
from solver.exercises.conventions import sign_convention
from solver.exercises.figures import figure_svg
from solver.exercises.generation import build
from solver.exercises.model import DIFFICULTIES, Draft, ExerciseId
from solver.exercises.registry import TYPES

if TYPE_CHECKING:
    from _typeshed import SupportsLenAndGetItem

T = TypeVar("T")
SEEDS = (3, 8)
_SCALE_BAR = re.compile(r"^[0-9.e+-]+ m$")  # the scale bar's length: a drawing aid, not a datum


class Perturbed(random.Random):
    """``random.Random(seed)`` whose ``target``-th draw (randint, random or choice) is changed to
    another value of its range; ``draws`` counts the draws, ``changed`` says whether the target
    was reached."""

    def __init__(self, seed: str, target: int) -> None:
        super().__init__(seed)
        self.target, self.draws, self.changed = target, 0, False

    def _hit(self) -> bool:
        hit = self.draws == self.target
        self.draws += 1
        self.changed |= hit
        return hit

    def randint(self, a: int, b: int) -> int:
        value = super().randint(a, b)
        return a + (value - a + 1) % (b - a + 1) if self._hit() and b > a else value

    def random(self) -> float:
        value = super().random()
        return (value + 0.5) % 1.0 if self._hit() else value

    def choice(self, seq: SupportsLenAndGetItem[T]) -> T:
        index = self.randint(0, len(seq) - 1)
        return seq[index]


def _answers(draft: Draft) -> dict[str, float] | None:
    try:
        solved = solve_scene(draft.scene)
        return {a.key: value_at(solved, a.path) for a in draft.asked}
    except KinematicsError:
        return None


def _stated(draft: Draft) -> tuple[str, str, tuple[str, ...]]:
    """What a student reads: the text, the LaTeX and the figure's labels (no scale bar)."""
    labels = re.findall(r"<text[^>]*>([^<]*)</text>", figure_svg(draft.scene))
    return draft.text, draft.latex, tuple(t for t in labels if not _SCALE_BAR.match(t))


def _differ(a: dict[str, float], b: dict[str, float]) -> bool:
    return any(abs(a[k] - b[k]) > 1e-9 * max(abs(a[k]), abs(b[k]), 1e-12) for k in a)


@pytest.mark.parametrize("difficulty", DIFFICULTIES)
@pytest.mark.parametrize(
    "kind",
    # the synthesis types take 5 to 22 s each (a design solved for every changed input)
    [
        pytest.param(k, marks=pytest.mark.slow) if k.startswith("synthesis") else k
        for k in sorted(TYPES)
    ],
)
def test_every_input_an_answer_depends_on_is_stated(kind: str, difficulty: str) -> None:
    tried = 0
    for seed in SEEDS:
        name = f"{kind}:{difficulty}:{seed}"
        base = Perturbed(name, -1)
        draft = TYPES[kind].draw(base, difficulty)
        answers = _answers(draft)
        if answers is None:
            continue
        for target in range(base.draws):
            rng = Perturbed(name, target)
            other = TYPES[kind].draw(rng, difficulty)
            if not rng.changed or [a.key for a in other.asked] != [a.key for a in draft.asked]:
                continue
            if other.scene == draft.scene and other.asked == draft.asked:
                continue  # the same question (a draw of a draft the type rejects): same answers
            other_answers = _answers(other)
            if other_answers is None or not _differ(answers, other_answers):
                continue
            tried += 1
            assert _stated(other) != _stated(draft), (
                f"{name}: draw {target} changes the answers but not the statement"
            )
    assert tried > 0  # some input changed some answer


@pytest.mark.parametrize("kind", sorted(TYPES))
def test_every_statement_states_its_signs_and_axes(kind: str) -> None:
    for difficulty in DIFFICULTIES:
        e = build(ExerciseId(kind, difficulty, 5, 0))
        convention = sign_convention(e.scene)
        assert e.statement.text.endswith(convention)
        assert "Signs:" in convention and "with its sign" in convention
        if e.task is None and e.scene.get("kind", "linkage") == "linkage":
            assert "x to the right, y up" in convention
            labels = re.findall(r"<text[^>]*>([^<]*)</text>", e.statement.figure_svg)
            assert "x" in labels and "y" in labels  # the figure carries the axes


def test_the_rod_angle_is_stated_and_dimensioned() -> None:
    rods = [
        e
        for e in (build(ExerciseId("moving_point", "standard", seed, 0)) for seed in range(30))
        if e.scene["links"].get("rod") is not None
    ]
    assert rods
    for e in rods:
        s, t = e.scene["points"]["S"], e.scene["points"]["T"]
        angle = f"{math.degrees(math.atan2(t[1] - s[1], t[0] - s[0])):.4g}"
        assert f"points {angle} deg counter-clockwise from the x axis" in e.statement.text
        assert rf"\theta_0 = {angle}^\circ" in e.statement.latex
        assert f"θ0 = {angle}°" in e.statement.figure_svg

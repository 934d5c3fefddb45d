"""What an exercise is made of: its id, the asked quantities, the statement and the answer key.

An exercise is never stored: ``type:difficulty:seed:index`` determines it completely (the
generator is seeded with that very string), so the same id gives the same exercise on any server.
"""

from __future__ import annotations

import math
import re
from collections.abc import Callable, Mapping
from dataclasses import dataclass, field
from functools import cached_property
from typing import Any

from solver.errors import InvalidScene, LimitExceeded

DIFFICULTIES = ("basic", "standard", "challenging")
DEFAULT_DIFFICULTY = "standard"
DEFAULT_TOLERANCE = 0.01  # relative: 1 %
MAX_SEED = 2**63 - 1
MAX_INDEX = 1_000_000
_ID = re.compile(r"([a-z_]{1,40}):([a-z]{1,20}):([0-9]{1,19}):([0-9]{1,7})")


@dataclass(frozen=True)
class ExerciseId:
    """``type:difficulty:seed:index``; ``str()`` gives it back."""

    type: str
    difficulty: str
    seed: int
    index: int

    def __str__(self) -> str:
        return f"{self.type}:{self.difficulty}:{self.seed}:{self.index}"


def check_seed_index(seed: int, index: int) -> None:
    if not 0 <= seed <= MAX_SEED:
        raise InvalidScene(f"seed: expected an integer from 0 to {MAX_SEED}, got {seed}")
    if not 0 <= index < MAX_INDEX:
        raise LimitExceeded(f"index: expected an integer from 0 to {MAX_INDEX - 1}, got {index}")


def parse_id(text: str) -> ExerciseId:
    """The parts of an exercise id, or ``InvalidScene`` saying what is wrong with it."""
    match = _ID.fullmatch(text) if isinstance(text, str) else None
    if match is None:
        shown = repr(text)[:80]
        raise InvalidScene(
            f"id: {shown} is not an exercise id of the form type:difficulty:seed:index "
            "(e.g. four_bar_velocity:standard:7:0)"
        )
    kind, difficulty, seed, index = match.groups()
    check_seed_index(int(seed), int(index))
    return ExerciseId(kind, difficulty, int(seed), int(index))


@dataclass(frozen=True)
class Asked:
    """One asked quantity: its key in ``answers``, label, SI unit, path and relative tolerance.

    ``path`` is a dotted path into the /analyze response of the exercise's scene
    (``links.coupler.omega``, ``points.C.velocity.0``), or ``events.<M>.<target>.time`` for the
    first instant after t = 0 at which moving point M reaches ``target`` (as /events answers with
    its default ``occurrence`` 1 and ``t_max`` 60 s); for an exercise built on a synthesis task,
    a path into its /synthesis body (``freudenstein.K1``, ``scene.points.A.0``).
    """

    key: str
    label: str
    unit: str
    path: str
    symbol: str  # LaTeX of the quantity, e.g. \omega_{BC}
    tolerance: float = DEFAULT_TOLERANCE

    def as_json(self) -> dict[str, Any]:
        return {
            "key": self.key,
            "label": self.label,
            "unit": self.unit,
            "path": self.path,
            "tolerance": self.tolerance,
            "symbol": self.symbol,
        }


@dataclass(frozen=True)
class Statement:
    """What the student reads: the text, its data in LaTeX, and the figure (SVG), drawn by
    ``draw`` when it is first read (a check of the key or of the text never draws it)."""

    text: str
    latex: str
    draw: Callable[[], str] = field(repr=False, compare=False)

    @cached_property
    def figure_svg(self) -> str:
        return self.draw()


def is_task(doc: Mapping[str, Any]) -> bool:
    """Whether an exercise's document is a synthesis task (``{"task": "function", ...}``, POST
    /synthesis) rather than a scene (scene-v1, POST /analyze)."""
    return isinstance(doc.get("task"), str)


@dataclass(frozen=True)
class Exercise:
    """A generated exercise: its id, statement, the document it is built on, asked quantities
    and key.

    ``scene`` is that document: a scene-v1 scene, whose /analyze body the paths point into, or
    (``task``) a synthesis task, whose /synthesis body they point into; the JSON names it
    ``scene`` or ``task`` accordingly."""

    id: ExerciseId
    title: str
    statement: Statement
    scene: Mapping[str, Any]
    asked: tuple[Asked, ...]
    answers: Mapping[str, float]
    exam_id: str | None = None  # an exam exercise's opaque id (solver.exercises.exam)

    @property
    def task(self) -> Mapping[str, Any] | None:
        """The synthesis task the exercise is built on, or None for one built on a scene."""
        return self.scene if is_task(self.scene) else None

    @property
    def name(self) -> str:
        """The id a student may see: the exam id of an exam exercise, else ``str(id)``."""
        return str(self.id) if self.exam_id is None else self.exam_id

    def as_json(self) -> dict[str, Any]:
        """The instructor's view: everything, the key included (an exam exercise adds
        ``exam: true``; its id is the exam id)."""
        i = self.id
        exam = {} if self.exam_id is None else {"exam": True}
        return {
            "id": self.name,
            **exam,
            "type": i.type,
            "difficulty": i.difficulty,
            "seed": i.seed,
            "index": i.index,
            "title": self.title,
            "statement": {
                "text": self.statement.text,
                "latex": self.statement.latex,
                "figure_svg": self.statement.figure_svg,
            },
            ("scene" if self.task is None else "task"): self.scene,
            "asked": [a.as_json() for a in self.asked],
            "answers": dict(self.answers),
        }

    def statement_json(self) -> dict[str, Any]:
        """The student's view of an exam exercise: its id, title, statement and what is asked
        (labels, units, symbols, tolerance); no scene, no path, no key, no solution."""
        return {
            "id": self.name,
            "exam": self.exam_id is not None,
            "title": self.title,
            "statement": {
                "text": self.statement.text,
                "latex": self.statement.latex,
                "figure_svg": self.statement.figure_svg,
            },
            "asked": [
                {
                    "key": a.key,
                    "label": a.label,
                    "unit": a.unit,
                    "symbol": a.symbol,
                    "tolerance": a.tolerance,
                }
                for a in self.asked
            ],
        }


def relative_error(given: float, expected: float) -> float:
    """|given - expected| / |expected| (expected is never 0 in a well-posed exercise)."""
    return abs(given - expected) / abs(expected) if expected != 0.0 else abs(given)


def within(given: float, expected: float, tolerance: float) -> bool:
    return math.isfinite(given) and relative_error(given, expected) <= tolerance


@dataclass(frozen=True)
class Draft:
    """A candidate exercise drawn by a family before the well-posedness checks.

    ``scene`` is the document the exercise is built on: a scene, or a synthesis task
    (``is_task``), whose ``check`` then receives the /synthesis body.

    ``scales`` gives, per unit, the size an answer in that unit is measured against (the crank
    speed for rad/s, omega^2 L for m/s^2, ...): an answer below ``SMALL`` or above ``LARGE``
    times its scale makes the draft ill-posed. ``check`` is the family's own test on the analysis
    (Grashof class, transmission angle, ...): a reason to reject, or None.

    ``foreseen`` gives, where a family knows it at once, the part of the body the draft will be
    solved into that holds some of its answers (a synthesis task's design, before /synthesis
    verifies its linkage by analysis), else None: the answers found there are checked for scale
    and coincidence before the draft is solved, so that a draft they make ill-posed costs no
    analysis (the same drafts are kept: an id names the same exercise).
    """

    title: str
    text: str
    latex: str
    scene: dict[str, Any]
    asked: tuple[Asked, ...]
    scales: Mapping[str, float]
    check: Callable[[Any], str | None] = field(default=lambda analysis: None)
    foreseen: Callable[[], Mapping[str, Any] | None] = field(default=lambda: None)

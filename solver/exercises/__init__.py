"""Exercises for instructors: seeded, well-posed, with answer keys from the solver (exercises-v1).

``build(parse_id("four_bar_velocity:standard:7:0"))`` gives one exercise, ``generate(type,
difficulty, seed, count)`` several; ``check`` grades answers and names typical mistakes;
``solver.exercises.export`` writes Moodle XML, printable HTML, CSV and JSON.
"""

from solver.exercises.generation import MAX_COUNT, build, generate
from solver.exercises.model import DIFFICULTIES, Asked, Exercise, ExerciseId, parse_id
from solver.exercises.registry import TYPES, ExerciseType

__all__ = [
    "DIFFICULTIES",
    "MAX_COUNT",
    "TYPES",
    "Asked",
    "Exercise",
    "ExerciseId",
    "ExerciseType",
    "build",
    "generate",
    "parse_id",
]

"""The typical mistakes of the synthesis exercises (``solver.exercises.synthesis``), made with the
solver as the others' are: a misread task is synthesised by /synthesis (the Chebyshev spacing
replaced by the ends and the middle of the range; the coupler turned the other way, by its
degrees read as radians, or by its absolute angle instead of its turn from the first position),
and a misread equation is solved by the synthesis' own Freudenstein functions on the body's
numbers (the angles in degrees fed to the cosines, the sign of K2, the lengths from K1 and K2
swapped or given with the sign of K). Their ids are entries of the catalogue
``solver.teaching.mistakes``.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from typing import Any

import numpy as np

from solver.errors import KinematicsError
from solver.exercises.answers import solve_scene, value_at
from solver.exercises.mistakes import WrongAnswers
from solver.exercises.model import Exercise
from solver.synthesis import freudenstein_coefficients
from solver.synthesis.function import link_lengths

DEGREES = 180.0 / math.pi


def _values(exercise: Exercise, task: Mapping[str, Any]) -> dict[str, float] | None:
    """The asked values of a changed task (the solver's), None where it has none."""
    try:
        solved = solve_scene(task)
        return {a.key: value_at(solved, a.path) for a in exercise.asked}
    except KinematicsError:
        return None


def _from_coefficients(d: float, k1: float, k2: float, k3: float) -> dict[str, float]:
    """K1, K2, K3 and the lengths they give (|a|, b, |c|; none where no coupler closes)."""
    values = {"K1": k1, "K2": k2, "K3": k3}
    try:
        a, b, c = link_lengths(d, k1, k2, k3)
    except KinematicsError:
        return values
    return values | {"a": abs(a), "b": b, "c": abs(c)}


def _function_mistakes(exercise: Exercise, task: Mapping[str, Any]) -> list[WrongAnswers]:
    body = solve_scene(task).analysis
    assert isinstance(body, Mapping)
    out = []
    if task["precision_points"] == 3:  # Chebyshev spacing asked
        x0, xf = task["x_range"]
        values = _values(exercise, {**task, "precision_points": [x0, (x0 + xf) / 2, xf]})
        if values is not None:
            out.append(WrongAnswers(
                "synthesis.chebyshev_spacing",
                "This is what precision points at the ends and the middle of the range give: "
                "Chebyshev's are x_j = (x0 + xf)/2 - (xf - x0)/2 cos((2j - 1) pi / 6), j = 1, "
                "2, 3, inside the range.",
                values,
            ))  # fmt: skip
    points = body["precision_points"]
    inputs = np.array([p["input_angle_deg"] for p in points])
    outputs = np.array([p["output_angle_deg"] for p in points])
    d = body["freudenstein"]["d"]
    try:  # the degrees' numbers taken as radians by the cosines
        wrong = freudenstein_coefficients(inputs, outputs)
        out.append(WrongAnswers(
            "degrees_as_radians",
            "This is what the angles in degrees give in cosines that take radians: set the "
            "calculator to degrees, or convert (multiply by pi/180).",
            _from_coefficients(d, *wrong),
        ))  # fmt: skip
    except KinematicsError:
        pass
    k = body["freudenstein"]
    out.append(WrongAnswers(
        "synthesis.freudenstein_sign",
        "This is what the equation with +K2 cos(theta_2) gives: Freudenstein's equation is "
        "K1 cos(theta_4) - K2 cos(theta_2) + K3 = cos(theta_2 - theta_4).",
        _from_coefficients(d, k["K1"], -k["K2"], k["K3"]),
    ))  # fmt: skip
    out.append(WrongAnswers(
        "synthesis.signed_length",
        "This is d/K with its sign: a negative K1 (K2) is a crank (rocker) pointing the other "
        "way, and its length is |d/K|.",
        {"a": k["a"], "c": k["c"]},
    ))  # fmt: skip
    out.append(WrongAnswers(
        "synthesis.k1_k2_swapped",
        "These are the crank and the rocker swapped: in this equation K1 = d/a (the crank) and "
        "K2 = d/c (the rocker); other texts letter them the other way.",
        {"a": abs(k["c"]), "c": abs(k["a"])},
    ))  # fmt: skip
    return out


def _turned(task: Mapping[str, Any], angles: list[float]) -> dict[str, Any]:
    """The task with the positions' angles replaced."""
    positions = [
        {**p, "angle_deg": angle} for p, angle in zip(task["positions"], angles, strict=True)
    ]
    return {**task, "positions": positions}


def _motion_mistakes(exercise: Exercise, task: Mapping[str, Any]) -> list[WrongAnswers]:
    angles = [float(p["angle_deg"]) for p in task["positions"]]
    first = angles[0]
    made = [
        (
            "rotation_sign",
            "This is what the coupler turned the other way gives: angles are counter-clockwise "
            "positive, and B_j = P_j + e^(i (phi_j - phi_1)) (B_1 - P_1).",
            [-angle for angle in angles],
        ),
        (
            "degrees_as_radians",
            "This is what the turn in degrees read as radians gives: in e^(i (phi_j - phi_1)) "
            "the angle is in radians.",
            [first + (angle - first) * DEGREES for angle in angles],
        ),
    ]
    if first != 0.0:
        made.append((
            "synthesis.absolute_turn",
            "This is what turning the coupler by its angle phi_j gives: from the first position "
            "it turns by phi_j - phi_1.",
            [first] + [first + angle for angle in angles[1:]],
        ))  # fmt: skip
    out = []
    for kind, sentence, wrong in made:
        values = _values(exercise, _turned(task, wrong))
        if values is not None:
            out.append(WrongAnswers(kind, sentence, values))
    return out


def synthesis_mistakes(exercise: Exercise) -> list[WrongAnswers]:
    """The typical mistakes of a synthesis exercise with the wrong answers they give (only for
    the asked keys)."""
    task = exercise.task
    assert task is not None
    made = (
        _function_mistakes(exercise, task)
        if task["task"] == "function"
        else _motion_mistakes(exercise, task)
    )
    asked = {a.key for a in exercise.asked}
    return [
        WrongAnswers(m.kind, m.sentence, {k: v for k, v in m.values.items() if k in asked})
        for m in made
    ]

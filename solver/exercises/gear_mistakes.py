"""The typical mistakes of the gear-train exercises (``solver.exercises.gear_trains``), made with
the solver as the linkages' are (``solver.exercises.mistakes``): an input's rotation taken the
other way round (one input at a time), every annulus taken as an external gear (the sign of the
internal mesh), and a planet's speed relative to its carrier taken for its absolute speed (or the
other way round). Their ids are entries of the catalogue ``solver.teaching.mistakes``.
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

from solver.errors import KinematicsError
from solver.exercises.answers import Solved, solve_scene, value_at
from solver.exercises.mistakes import WrongAnswers
from solver.exercises.model import Exercise
from solver.gears import analyze_gear_train, parse_gear_train
from solver.teaching.mistakes import rings_as_external


def _values(exercise: Exercise, scene: Mapping[str, Any]) -> dict[str, float] | None:
    """The asked values on a changed scene (the solver's), None where it has none."""
    try:
        solved = solve_scene(scene)
        return {a.key: value_at(solved, a.path) for a in exercise.asked}
    except KinematicsError:
        return None


def gear_train_mistakes(exercise: Exercise) -> list[WrongAnswers]:
    """The typical mistakes of a gear-train exercise with the wrong answers they give."""
    scene = exercise.scene
    out = []
    for name, speed in scene["inputs"].items():
        if speed == 0.0:
            continue
        variant = {**scene, "inputs": {**scene["inputs"], name: -speed}}
        values = _values(exercise, variant)
        if values is not None:
            sentence = (
                f"This is what you get with the rotation of {name} taken the other way round: "
                "counter-clockwise is positive, and a differential adds its inputs with signs."
            )
            out.append(WrongAnswers("rotation_sign", sentence, values))
    if any(g.get("internal") for g in scene["gears"].values()):
        try:
            external = rings_as_external(parse_gear_train(scene))
            wrong = Solved(external, analyze_gear_train(external).as_dict())
            values = {a.key: value_at(wrong, a.path) for a in exercise.asked}
        except KinematicsError:
            values = None
        if values is not None:
            out.append(
                WrongAnswers(
                    "internal_mesh_as_external",
                    "This is what you get with the ring's mesh taken as external: an internal "
                    "gear turns the same way as its pinion, (omega_ring - omega_arm)/(omega_planet "
                    "- omega_arm) = +N_planet/N_ring, not -.",
                    values,
                )
            )
    swapped = {}
    solved = solve_scene(scene)
    for a in exercise.asked:
        member, _, field = a.path.removeprefix("members.").partition(".")
        if scene.get("mounts", {}).get(member) is None:
            continue
        other = "omega_relative" if field == "omega" else "omega"
        swapped[a.key] = value_at(solved, f"members.{member}.{other}")
    if swapped:
        out.append(
            WrongAnswers(
                "relative_for_absolute",
                "This is the planet's speed in the other frame: relative to its carrier it is "
                "omega_planet - omega_arm (what the arm-locked row of the table gives), "
                "absolute it is that plus omega_arm.",
                swapped,
            )
        )
    return out

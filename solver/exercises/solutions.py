"""The worked solution of an exercise: the solver's own steps (``solver.steps.solve``) for its
scene, then, for an asked event time, a step saying how the instant was found and what s is then.
"""

from __future__ import annotations

from typing import Any

from solver.exercises.answers import parse
from solver.exercises.model import Exercise
from solver.laws import parse_time_law
from solver.steps import Step, Value, solve
from solver.steps import latex as tex

DIGITS = 4


def _event_step(exercise: Exercise, key: str, path: str) -> Step:
    """M reaches the target when s(t) is the target's path coordinate: the time (the solver's
    ``find_event``) and s at that time (the scene's own law evaluated there)."""
    _, moving, target, _ = path.split(".")
    law = next(m["s_law"] for m in exercise.scene["moving_points"] if m["name"] == moving)
    t = exercise.answers[key]
    s = parse_time_law(law).evaluate(t)[0]
    title = f"When {moving} reaches {target}"
    text = (
        f"{moving} reaches {target} when its path coordinate s(t) = {law} equals the length of "
        f"the path from its start to {target}. The first such instant after t = 0 is "
        f"t = {t:.{DIGITS}g} s, where s = {s:.{DIGITS}g} m."
    )
    latex = (
        rf"s(t_{{{tex.name(target)}}}) = {s:.{DIGITS}g}\,\mathrm{{m}} \;\Rightarrow\; "
        rf"t_{{{tex.name(target)}}} = {t:.{DIGITS}g}\,\mathrm{{s}}"
    )
    values = {
        "t": Value(t, "s", f"{t:.{DIGITS}g} s", tuple(path.split("."))),
        "s": Value(s, "m", f"{s:.{DIGITS}g} m"),
    }
    return Step("event.time", title, latex, text, values)


def worked_solution(exercise: Exercise) -> list[dict[str, Any]]:
    """The steps as JSON, in the order a student should read them."""
    steps = list(solve(parse(exercise.scene), "vector", DIGITS).steps)
    steps += [
        _event_step(exercise, a.key, a.path) for a in exercise.asked if a.path.startswith("events.")
    ]
    return [step.as_json() for step in steps]

"""The worked solution of an exercise: the solver's own steps (``solver.solutions.solve``) for its
scene, then, for an asked event time, a step saying how the instant was found and what s is then;
for a synthesis task, the steps of its /synthesis body (``solver.solutions.synthesis``).
"""

from __future__ import annotations

from typing import Any

from solver.api import synthesize
from solver.exercises.answers import flywheel_request, parse, solve_scene, value_at
from solver.exercises.cams import cam_angle_of
from solver.exercises.model import Exercise
from solver.exercises.registry import TYPES
from solver.model.laws import parse_time_law
from solver.solutions import Step, Value, solve
from solver.solutions import latex as tex

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


def _cycle_step(exercise: Exercise) -> Step:
    """Over a revolution: the mean torque, the energy fluctuation and the flywheel (/sweep's
    cycle figures, the solver's)."""
    solved = solve_scene(exercise.scene)
    root, samples, k, omega = flywheel_request(exercise)
    figures = {
        name: value_at(solved, f"{root}.cycle.{name}")
        for name in ("mean_torque", "energy_fluctuation", "flywheel_inertia")
    }
    mean, swing, inertia = figures.values()
    text = (
        "Repeat the instant's analysis at every crank angle of a revolution (here "
        f"{samples} of them): the driving torque M(phi). Its mean is {mean:.{DIGITS}g} N m. The "
        "energy the crank gains above the mean, E(phi) = integral of (M - M_mean) d phi, swings "
        f"by Delta E = {swing:.{DIGITS}g} J between its largest and smallest value. A flywheel "
        f"with (I/2)(omega_max^2 - omega_min^2) = I k omega^2 = Delta E keeps the speed within k = "
        f"{k:g}: I = Delta E / (k omega^2) = {inertia:.{DIGITS}g} kg m^2."
    )
    latex = (
        rf"\bar M = {mean:.{DIGITS}g}\,\mathrm{{N\,m}},\quad \Delta E = \max_\varphi E - "
        rf"\min_\varphi E = {swing:.{DIGITS}g}\,\mathrm{{J}},\quad I_F = \frac{{\Delta E}}"
        rf"{{k\,\omega^2}} = \frac{{{swing:.{DIGITS}g}}}{{{k:g} \cdot {omega:.{DIGITS}g}^2}} = "
        rf"{inertia:.{DIGITS}g}\,\mathrm{{kg\,m^2}}"
    )
    values = {
        name: Value(value, unit, f"{value:.{DIGITS}g} {unit}", (root, "cycle", name))
        for (name, value), unit in zip(figures.items(), ("N m", "J", "kg m^2"), strict=True)
    }
    return Step("dynamics.flywheel", "The flywheel over a revolution", latex, text, values)


def worked_solution(exercise: Exercise) -> list[dict[str, Any]]:
    """The steps as JSON, in the order a student should read them: the Newton-Euler method for
    the dynamics types (and the cycle's flywheel), the static force analysis for the statics
    types, the synthesis' own steps for a synthesis task (its /synthesis body's ``steps``), the
    vector method otherwise; without the links' extreme angles over a turn, which no exercise
    asks."""
    if exercise.task is not None:
        return list(synthesize(exercise.task).as_dict()["steps"])
    family = TYPES[exercise.id.type].mistakes
    dynamic = family in ("dynamics_torque", "flywheel")
    method = "statics" if family in ("statics", "friction") else (
        "newton_euler" if dynamic else "vector")  # fmt: skip
    angle = cam_angle_of(exercise)  # a cam's solution is at the asked cam angle
    scene = parse(exercise.scene)
    # No exercise asks a link's extreme angles over a turn (its answers are one instant's, or a
    # cycle's torque figures): its solution leaves that step out.
    steps = list(
        solve(scene, method, DIGITS, angle_deg=float(angle or 0), angle_extremes=False).steps
    )
    if family == "flywheel":
        steps.append(_cycle_step(exercise))
    steps += [
        _event_step(exercise, a.key, a.path) for a in exercise.asked if a.path.startswith("events.")
    ]
    return [step.as_json() for step in steps]

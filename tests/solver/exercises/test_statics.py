"""The statics exercise types: a four-bar's holding torque and a slider-crank's driving torque
with friction. Their keys against independent values (virtual work from the velocities alone;
the hand solution of the two-force rod in the friction cone; the closed form without friction),
the checker's diagnoses and the worked solution (the static force analysis)."""

from __future__ import annotations

import math

import numpy as np
import pytest

import solver
from solver.exercises import DIFFICULTIES, build, parse_id
from solver.exercises.checking import check_answers
from solver.exercises.mistakes import typical_mistakes
from solver.exercises.solutions import worked_solution
from tests.solver.dynamics.test_friction import slider_only_torque
from tests.solver.dynamics.test_statics import F

SEEDS = (3, 11)


@pytest.mark.parametrize("difficulty", DIFFICULTIES)
@pytest.mark.parametrize("seed", SEEDS)
def test_the_holding_torque_is_virtual_work(difficulty: str, seed: int) -> None:
    """T omega + M_L omega_rocker + sum m g . v_G = 0 with the velocities of /analyze (no
    force computed): the key to 1e-9 of the largest term."""
    exercise = build(parse_id(f"holding_torque:{difficulty}:{seed}:0"))
    scene = exercise.scene
    body = solver.analyze(scene, ["velocity"]).as_dict()
    omega = scene["drivers"][0]["omega"]
    (load,) = scene["torques"]
    terms = [float(load["moment"]) * body["links"]["rocker"]["omega"]]
    g = np.array(scene.get("gravity", [0.0, 0.0]))
    for mass in scene.get("masses", {}).values():
        ends = [np.array(body["points"][p]["velocity"]) for p in mass["bar"]]
        terms.append(mass["mass"] * float(g @ (ends[0] + ends[1]) / 2))
    expected = -sum(terms) / omega
    size = max(abs(t) for t in terms) / abs(omega)
    assert exercise.answers["M_crank"] == pytest.approx(expected, abs=1e-9 * size)
    if difficulty != "basic":
        static = solver.analyze(scene, ["forces"], statics=True).as_dict()
        assert static["joints"][1]["point"] == "B"
        assert exercise.answers["F_B_y"] == static["joints"][1]["force"][1]


@pytest.mark.parametrize("difficulty", DIFFICULTIES)
@pytest.mark.parametrize("seed", SEEDS)
def test_the_friction_torque_is_the_hand_solution(difficulty: str, seed: int) -> None:
    """Basic (friction at the slider only, crank counter-clockwise, centred guide): the hand
    solution of the rod in the friction cone, scaled by P / F (1e-9); from standard on the
    frictionless key is -P r sin(theta + beta) / cos beta (offset e: sin beta = (r sin theta - e)
    / l), and the pin's friction makes the driver pay more where it drives."""
    exercise = build(parse_id(f"slider_crank_friction:{difficulty}:{seed}:0"))
    scene = exercise.scene
    r = math.dist(scene["points"]["A"], scene["points"]["B"])
    rod = math.dist(scene["points"]["B"], scene["points"]["C"])
    (force,) = scene["forces"]
    P = float(force["magnitude"])
    theta = math.atan2(scene["points"]["B"][1], scene["points"]["B"][0])
    joint = next(j for j in scene["joints"] if j["point"] == "C")
    mu = joint["friction"]["coefficient"]
    if difficulty == "basic":
        hand = slider_only_torque(theta, mu, r, rod)
        assert hand is not None
        assert exercise.answers["M_crank"] == pytest.approx(hand * P / F, rel=1e-9)
        return
    offset = scene["points"]["C"][1]
    beta = math.asin((r * math.sin(theta) - offset) / rod)
    frictionless = -P * r * math.sin(theta + beta) / math.cos(beta)
    assert exercise.answers["M_0"] == pytest.approx(frictionless, rel=1e-9, abs=1e-9 * P * r)
    omega = scene["drivers"][0]["omega"]
    if frictionless * omega > 0:  # the driver drives: friction costs it power
        assert exercise.answers["M_crank"] * omega > frictionless * omega


def _diagnosis(exercise_id: str, key: str, kind: str) -> None:
    exercise = build(parse_id(exercise_id))
    (wrong,) = [m.values[key] for m in typical_mistakes(exercise) if m.kind == kind]
    assert abs(wrong - exercise.answers[key]) > 0.01 * abs(exercise.answers[key])
    result = check_answers(exercise, {key: wrong})
    (graded,) = [r for r in result["results"] if r["key"] == key]
    assert graded["verdict"] == "incorrect"
    assert graded["mistake"] == kind and graded["diagnosis"]


def test_the_checker_knows_the_weights_left_out() -> None:
    _diagnosis("holding_torque:standard:3:0", "M_crank", "weights_left_out")


def test_the_checker_knows_the_friction_left_out() -> None:
    _diagnosis("slider_crank_friction:standard:3:0", "M_crank", "friction_left_out")


def test_the_worked_solution_is_the_static_force_analysis() -> None:
    exercise = build(parse_id("slider_crank_friction:standard:3:0"))
    steps = worked_solution(exercise)
    kinds = [step["kind"] for step in steps]
    assert "dynamics.friction" in kinds and "dynamics.center_acceleration" not in kinds
    (solution,) = [s for s in steps if s["kind"] == "dynamics.solution"]
    assert solution["values"]["M_crank"]["value"] == exercise.answers["M_crank"]
    assert solution["values"]["M_0"]["value"] == exercise.answers["M_0"]

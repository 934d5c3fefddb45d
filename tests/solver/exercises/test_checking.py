"""Checking answers: tolerance, scores, and each typical mistake diagnosed as itself.

The wrong answers of a mistake come from the solver (a misread input made in the scene) or from
the loop's acceleration equation with one term wrong. That equation solved right must give the
solver's own answers: this is what makes its wrong answers the ones a student gets.
"""

from __future__ import annotations

from collections import Counter

import numpy as np
import pytest

from solver.errors import InvalidScene
from solver.exercises import DIFFICULTIES, TYPES, ExerciseId, build
from solver.exercises.answers import solve_scene
from solver.exercises.checking import check, check_answers, mistakes_of
from solver.exercises.mistakes import (
    Numbers,
    lever_alpha,
    rrp_alpha,
    rrr_alphas,
    typical_mistakes,
)
from solver.exercises.model import within

SEEDS = range(6)


def test_right_answers_score_one_and_wrong_ones_zero() -> None:
    e = build(ExerciseId("four_bar_acceleration", "standard", 3, 0))
    right = check_answers(e, dict(e.answers))
    assert right["score"] == 1.0
    assert {r["verdict"] for r in right["results"]} == {"correct"}
    wrong = check_answers(e, {k: 1.5 * v for k, v in e.answers.items()})
    assert wrong["score"] == 0.0
    assert {r["verdict"] for r in wrong["results"]} == {"incorrect"}
    missing = check_answers(e, {})
    assert missing["score"] == 0.0 and {r["verdict"] for r in missing["results"]} == {"missing"}


def test_the_tolerance_is_relative() -> None:
    e = build(ExerciseId("slider_crank", "basic", 1, 0))
    key, value = next(iter(e.answers.items()))
    inside = check_answers(e, {key: value * 1.0099})["results"][0]
    outside = check_answers(e, {key: value * 1.0101})["results"][0]
    assert inside["verdict"] == "correct" and abs(inside["relative_error"] - 0.0099) < 1e-9
    assert outside["verdict"] == "incorrect"


def test_an_unknown_key_or_id_is_invalid_scene() -> None:
    with pytest.raises(InvalidScene, match="unknown key"):
        check("four_bar_velocity:standard:7:0", {"omega_crank": 1.0})
    with pytest.raises(InvalidScene, match="unknown exercise type"):
        check("warp_drive:standard:7:0", {})


@pytest.mark.parametrize("difficulty", DIFFICULTIES)
def test_the_loop_equations_solved_right_give_the_solver_s_answers(difficulty: str) -> None:
    for seed in SEEDS:
        n = Numbers(
            solve_scene(build(ExerciseId("four_bar_acceleration", difficulty, seed, 0)).scene)
        )
        a2, a3 = rrr_alphas(
            n.acc("B"), n.p("B"), n.p("C"), n.p("D"), n.omega("coupler"), n.omega("rocker")
        )
        assert np.allclose([a2, a3], [n.alpha("coupler"), n.alpha("rocker")], rtol=1e-10)
        n = Numbers(solve_scene(build(ExerciseId("slider_extension", difficulty, seed, 0)).scene))
        alpha = rrp_alpha(
            n.acc("B"), n.p("B"), n.p("C"), np.array([1.0, 0.0]), n.omega("coupler"), np.zeros(2)
        )
        assert np.isclose(alpha, n.alpha("coupler"), rtol=1e-10)
        for kind, pivot in (("inverted_slider_crank", "C"), ("quick_return", "O4")):
            n = Numbers(solve_scene(build(ExerciseId(kind, difficulty, seed, 0)).scene))
            joint = n.a.joints[0]
            u = joint.relative_velocity / np.hypot(*joint.relative_velocity)
            alpha = lever_alpha(
                n.acc("A"), n.p("A"), n.p(pivot), u, n.omega("lever"), joint.relative_velocity, 1.0
            )
            assert np.isclose(alpha, n.alpha("lever"), rtol=1e-10)


@pytest.mark.slow
def test_every_typical_mistake_is_diagnosed_as_itself() -> None:
    """For each exercise and each mistake, its wrong values are submitted (every key it changes
    at once, as a student making it would); for each of them where no earlier mistake in the
    list gives the same wrong value (then the diagnosis is ambiguous by nature), the diagnosis
    must name this mistake.

    One submission per mistake rather than one per wrong value (a third of the time: the
    mistakes are worked out once per submission): check_answers grades and diagnoses each row
    from its own value alone, so each row gets the verdict and diagnosis it gets submitted
    alone, which is what is asserted, and the keys a mistake leaves right must be graded
    correct beside the wrong ones."""
    diagnosed: Counter[str] = Counter()
    for kind in TYPES:
        for difficulty in DIFFICULTIES:
            for seed in SEEDS[:3]:
                e = build(ExerciseId(kind, difficulty, seed, 0))
                mistakes = mistakes_of(e)
                for i, mistake in enumerate(mistakes):
                    rows = {r["key"]: r for r in check_answers(e, mistake.values)["results"]}
                    for key, wrong in mistake.values.items():
                        asked = next(a for a in e.asked if a.key == key)
                        if within(wrong, e.answers[key], asked.tolerance):
                            assert rows[key]["verdict"] == "correct"
                            continue  # this mistake does not change this answer
                        earlier = [
                            m for m in mistakes[:i]
                            if key in m.values and within(wrong, m.values[key], asked.tolerance)
                            and not within(m.values[key], e.answers[key], asked.tolerance)
                        ]  # fmt: skip
                        row = rows[key]
                        assert row["verdict"] == "incorrect"
                        if not earlier:
                            assert row["mistake"] == mistake.kind, (e.id, key, row)
                            assert row["diagnosis"] == mistake.sentence
                            diagnosed[mistake.kind] += 1
    assert set(diagnosed) == {
        "cam_omega_left_out",
        "cam_beta_in_degrees",
        "coriolis_left_out",
        "coriolis_without_factor_2",
        "coriolis_on_fixed_guide",
        "rotation_sign",
        "degrees_for_radians",
        "alpha_in_normal_term",
        "weights_left_out",
        "inertia_left_out",
        "friction_left_out",
        "mean_torque_for_fluctuation",
        "flywheel_factor_two",
        "internal_mesh_as_external",
        "relative_for_absolute",
        "magnitude_for_component",
        "components_swapped",
        "action_reaction_sign",
        "degrees_as_radians",
        "synthesis.chebyshev_spacing",
        "synthesis.freudenstein_sign",
        "synthesis.signed_length",
        "synthesis.k1_k2_swapped",
        "synthesis.absolute_turn",
        "synthesis.offset_side",
        "synthesis.coupler_bisector",
        "cross.order",
    }, diagnosed


@pytest.mark.parametrize(
    ("kind", "pivot", "link", "points"),
    [
        ("four_bar_velocity", "B", "coupler", {"C", "P"}),
        ("four_bar_acceleration", "B", "coupler", {"C", "P"}),
        ("slider_crank", "B", "coupler", {"C"}),
        ("slider_extension", "B", "coupler", {"D"}),
        ("quick_return", "B", "rod", {"C"}),
    ],
)
def test_the_cross_product_in_the_wrong_order_reverses_the_relative_terms(
    kind: str, pivot: str, link: str, points: set[str]
) -> None:
    """r x omega for omega x r: v_X' = v_Q - omega x r = 2 v_Q - v_X, and the tangential term
    alone reversed: a_X' = a_Q - alpha x r - omega^2 r = 2 a_Q - 2 omega^2 r - a_X (from the
    solver's v_Q, v_X, a_Q, a_X, to 1e-9); diagnosed as itself where no earlier mistake gives
    the same value."""
    named = 0
    for seed in SEEDS:
        e = build(ExerciseId(kind, "challenging", seed, 0))
        n = Numbers(solve_scene(e.scene))
        (made,) = [m for m in typical_mistakes(e) if m.kind == "cross.order"]
        for key, value in made.values.items():
            field, point, axis = key[0], key[2:-2], "xy".index(key[-1])
            assert point in points
            r = n.p(point) - n.p(pivot)
            v = 2 * n.a.points[pivot].velocity - n.a.points[point].velocity
            a = 2 * n.acc(pivot) - 2 * n.omega(link) ** 2 * r - n.acc(point)
            expected = (v if field == "v" else a)[axis]
            assert abs(value - expected) <= 1e-9 * (1 + abs(expected))
            row = check_answers(e, {key: value})["results"]
            found = next(x for x in row if x["key"] == key)
            named += found["mistake"] == "cross.order"
    assert named > 0


def test_a_wrong_answer_that_is_no_typical_mistake_has_no_diagnosis() -> None:
    e = build(ExerciseId("inverted_slider_crank", "standard", 2, 0))
    row = check_answers(e, {"alpha_lever": e.answers["alpha_lever"] * 1.37})["results"][1]
    assert row["verdict"] == "incorrect" and row["diagnosis"] is None


def _made(e_kind: str, difficulty: str, seed: int) -> tuple[dict[str, float], dict[str, list]]:  # type: ignore[type-arg]
    e = build(ExerciseId(e_kind, difficulty, seed, 0))
    made: dict[str, list] = {}  # type: ignore[type-arg]
    for m in typical_mistakes(e):
        made.setdefault(m.kind, []).append(dict(m.values))
    return dict(e.answers), made


@pytest.mark.parametrize("seed", SEEDS)
def test_the_misread_inputs_give_what_their_laws_say(seed: int) -> None:
    """Velocities are linear in the crank's omega, accelerations at constant speed quadratic:
    the reversed rotation negates every velocity, the crank speed in deg/s multiplies it by
    180/pi, and an acceleration by (180/pi)^2; an answer in degrees is the answer times 180/pi."""
    to_deg = 180.0 / np.pi
    answers, made = _made("four_bar_velocity", "standard", seed)
    (reversed_,) = made["rotation_sign"]
    in_degrees, converted = made["degrees_for_radians"]
    for key, value in answers.items():
        assert np.isclose(reversed_[key], -value, rtol=1e-9)
        assert np.isclose(in_degrees[key], value * to_deg, rtol=1e-9)
    assert converted == {k: v * to_deg for k, v in answers.items() if k.startswith("omega")}
    answers, made = _made("four_bar_acceleration", "basic", seed)
    in_degrees = made["degrees_for_radians"][0]
    for key, value in answers.items():
        assert np.isclose(in_degrees[key], value * to_deg**2, rtol=1e-9)


@pytest.mark.parametrize("seed", SEEDS)
def test_a_coriolis_term_left_out_or_halved_is_missing_from_the_acceleration(seed: int) -> None:
    answers, made = _made("moving_point", "standard", seed)
    (left_out,) = made["coriolis_left_out"]
    (halved,) = made["coriolis_without_factor_2"]
    for axis in "xy":
        a, cor = answers[f"a_M_{axis}"], answers[f"a_cor_M_{axis}"]
        assert np.isclose(left_out[f"a_M_{axis}"], a - cor, rtol=1e-12, atol=1e-15)
        assert np.isclose(halved[f"a_M_{axis}"], a - cor / 2, rtol=1e-12, atol=1e-15)
        assert np.isclose(halved[f"a_cor_M_{axis}"], cor / 2, rtol=1e-12)

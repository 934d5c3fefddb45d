"""The gear-train exercise types (issue 25): keys against the textbook closed forms, whole
inputs, their worked solution, and the typical mistakes diagnosed.

Sources: Shigley/Uicker ch. 13 (ring fixed: omega_arm = omega_sun N_s / (N_s + N_r); the
planetary differential: omega_arm = (N_s omega_s + N_r omega_r) / (N_s + N_r), from the formula
method with e = -N_s / N_r); the spur-gear differential: omega_carrier = (omega_l + omega_r) / 2.
"""

from __future__ import annotations

import pytest

import solver
from solver.exercises import DIFFICULTIES, ExerciseId, build, generate
from solver.exercises.checking import check_answers, mistakes_of
from solver.exercises.solutions import worked_solution


@pytest.mark.parametrize("difficulty", DIFFICULTIES)
def test_planetary_output_is_shigleys_closed_form(difficulty: str) -> None:
    for e in generate("planetary_output", difficulty, 3, 10):
        teeth = {name: g["teeth"] for name, g in e.scene["gears"].items()}
        n_s, n_r = teeth["sun"], teeth["ring"]
        w_s, w_r = e.scene["inputs"]["sun"], e.scene["inputs"]["ring"]
        assert n_r == n_s + 2 * teeth["planet"]
        assert float(w_s).is_integer() and float(w_r).is_integer()
        assert (w_r == 0.0) == (difficulty != "challenging")
        arm = (n_s * w_s + n_r * w_r) / (n_s + n_r)
        assert e.answers["omega_arm"] == pytest.approx(arm, rel=1e-12)
        if difficulty != "basic":  # the planet: omega_arm + (-N_s / N_p)(omega_s - omega_arm)
            planet = arm - n_s / teeth["planet"] * (w_s - arm)
            assert e.answers["omega_planet"] == pytest.approx(planet, rel=1e-12)


@pytest.mark.parametrize("difficulty", DIFFICULTIES)
def test_differential_carrier_is_the_mean_or_the_weighted_mean(difficulty: str) -> None:
    for e in generate("differential_carrier", difficulty, 5, 10):
        inputs = e.scene["inputs"]
        if difficulty == "challenging":
            n_s, n_r = (e.scene["gears"][g]["teeth"] for g in ("sun", "ring"))
            expected = (n_s * inputs["sun"] + n_r * inputs["ring"]) / (n_s + n_r)
            assert e.answers["omega_arm"] == pytest.approx(expected, rel=1e-12)
        else:
            expected = (inputs["left"] + inputs["right"]) / 2
            assert e.answers["omega_carrier"] == pytest.approx(expected, rel=1e-12)


def test_the_worked_solution_is_the_tabular_method() -> None:
    e = build(ExerciseId("planetary_output", "standard", 1, 0))
    kinds = [s["kind"] for s in worked_solution(e)]
    assert kinds[:4] == ["gears.data", "gears.freedom", "gears.tabular", "gears.formula"]


def test_one_input_reversed_is_diagnosed_as_a_rotation_sign() -> None:
    """omega_l and omega_r with omega_r reversed: the carrier at (omega_l - omega_r) / 2."""
    e = build(ExerciseId("differential_carrier", "basic", 2, 0))
    w = e.scene["inputs"]
    wrong = (w["left"] - w["right"]) / 2
    row = check_answers(e, {"omega_carrier": wrong})["results"][0]
    assert row["verdict"] == "incorrect" and row["mistake"] == "rotation_sign"


def test_the_ring_taken_as_external_is_diagnosed() -> None:
    e = build(ExerciseId("planetary_output", "basic", 4, 0))
    (made,) = [m for m in mistakes_of(e) if m.kind == "internal_mesh_as_external"]
    n_s, n_r = (e.scene["gears"][g]["teeth"] for g in ("sun", "ring"))
    # the ring fixed, e = +N_s / N_r: omega_arm = -e omega_s / (1 - e)
    e_wrong = n_s / n_r
    expected = -e_wrong * e.scene["inputs"]["sun"] / (1 - e_wrong)
    assert made.values["omega_arm"] == pytest.approx(expected, rel=1e-12)
    row = check_answers(e, {"omega_arm": expected})["results"][0]
    assert row["mistake"] == "internal_mesh_as_external"


@pytest.mark.parametrize("seed", range(3))
def test_the_ring_as_external_is_graded_and_shown_alike(seed: int) -> None:
    """The checker's wrong omega_arm and the worked solution's are the same number (one
    definition: ``teaching.mistakes.rings_as_external``, analysed by the solver)."""
    e = build(ExerciseId("planetary_output", "basic", seed, 0))
    (made,) = [m for m in mistakes_of(e) if m.kind == "internal_mesh_as_external"]
    shown = solver.solve(e.scene).as_dict()["mistakes"]
    (same,) = [m for m in shown if m["kind"] == "internal_mesh_as_external"]
    assert same["values"]["wrong"]["value"] == made.values["omega_arm"]
    assert same["values"]["right"]["value"] == e.answers["omega_arm"]
    row = check_answers(e, {"omega_arm": same["values"]["wrong"]["value"]})["results"][0]
    assert row["mistake"] == "internal_mesh_as_external"

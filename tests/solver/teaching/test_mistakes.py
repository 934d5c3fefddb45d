"""One catalogue of typical mistakes: the worked solution and the exercise checker name a mistake by
the same id, and where both compute its wrong value they compute the same number.

Source: solver/teaching/mistakes.py (the catalogue), docs/EXERCISES.md (the checker's ids, public)
and docs/SOLUTIONS.md; the wrong values are properties of the formulas (a_Cor = 2 omega x v_rel).
"""

from __future__ import annotations

import json
from collections.abc import Mapping
from functools import cache
from pathlib import Path
from typing import Any

import numpy as np
import pytest

import solver
from solver.exercises import DIFFICULTIES, TYPES, Exercise, ExerciseId, build
from solver.exercises.cams import cam_angle_of
from solver.exercises.checking import check_answers, mistakes_of
from solver.exercises.mistakes import WrongAnswers, typical_mistakes
from solver.exercises.model import within
from solver.kinematics.relative_motion import coriolis_acceleration
from solver.kinematics.rigid import perp, rigid_body_acceleration
from solver.teaching.mistakes import (
    CATALOGUE,
    alpha_in_normal_term,
    coriolis_left_out,
    coriolis_with_omega_of,
    coriolis_without_factor_2,
    typical_mistake,
)

EXAMPLES = Path(__file__).resolve().parents[3] / "server" / "examples"
# The examples whose worked solutions list typical mistakes of the catalogue (linkages, chains).
SOLVED = [
    path
    for path in sorted(EXAMPLES.glob("*.json"))
    if json.loads(path.read_text())["kind"] in ("linkage", "spatial_chain")
]
DYNAMIC = ("four_bar_torque", "flywheel")
# The mistakes both outputs name: the worked solution shows them, the checker diagnoses them.
SHARED = {
    "coriolis_without_factor_2",
    "coriolis_on_fixed_guide",
    "internal_mesh_as_external",
    "relative_for_absolute",
    "cam_omega_left_out",
    "cam_beta_in_degrees",
    "cross.order",  # the solution at the driven link's pin, the checker at the asked points
}


def _shown(
    scene: Mapping[str, Any], method: str = "vector", angle_deg: float | None = None
) -> list[dict[str, Any]]:
    """The mistakes a worked solution lists (a cam's at ``angle_deg``, as an exercise's worked
    solution is at the cam angle it asks about)."""
    body = solver.solve(scene, method=method, angle_deg=angle_deg).as_dict()
    mistakes: list[dict[str, Any]] = body["mistakes"]
    return mistakes


def _angle(e: Exercise) -> float | None:
    angle = cam_angle_of(e)
    return None if angle is None else float(angle)


@cache
def _exercise(kind: str, difficulty: str, seed: int) -> Exercise:
    return build(ExerciseId(kind, difficulty, seed, 0))


def _diagnosed(e: Exercise) -> list[WrongAnswers]:
    return typical_mistakes(e)


def test_every_id_either_output_carries_is_in_the_catalogue_and_every_entry_is_used() -> None:
    """The seed scenes in every method and one exercise of every type and difficulty: the ids the
    worked solutions show and the checker diagnoses are all catalogue ids, and together they use
    every entry."""
    shown: set[str] = set()
    diagnosed: set[str] = set()
    for path in SOLVED:
        doc = json.loads(path.read_text())
        methods = ("vector",) if doc.get("kind") == "spatial_chain" else ("vector", "loop")
        for method in methods:
            shown |= {m["kind"] for m in _shown(doc, method)}
    for kind in TYPES:
        for difficulty in DIFFICULTIES:
            e = _exercise(kind, difficulty, 1)
            diagnosed |= {m.kind for m in mistakes_of(e)}
            method = "newton_euler" if kind in DYNAMIC else "vector"
            if e.task is None:  # a synthesis task's worked solution names no mistakes
                shown |= {m["kind"] for m in _shown(e.scene, method, _angle(e))}
    assert shown <= set(CATALOGUE), shown - set(CATALOGUE)
    assert diagnosed <= set(CATALOGUE), diagnosed - set(CATALOGUE)
    assert shown | diagnosed == set(CATALOGUE), set(CATALOGUE) - shown - diagnosed
    assert shown & diagnosed == SHARED


def test_a_solution_mistake_carries_its_catalogue_title() -> None:
    for path in SOLVED:
        for m in _shown(json.loads(path.read_text())):
            if m["kind"] != "dynamics.moment_about_accelerating_point":  # titled with its pin
                assert m["title"] == typical_mistake(m["kind"]).title


def test_a_diagnosis_outside_the_catalogue_is_refused() -> None:
    with pytest.raises(KeyError):
        WrongAnswers("coriolis.factor_2", "an id of no catalogue", {})


@pytest.mark.parametrize(
    ("kind", "key", "seed"),
    [("quick_return", "a_cor_A", seed) for seed in range(3)]
    + [("inverted_slider_crank", "a_cor_A", seed) for seed in range(3)]
    + [("moving_point", "a_cor_M", seed) for seed in range(3)],
)
def test_the_halved_coriolis_term_is_graded_and_shown_alike(kind: str, key: str, seed: int) -> None:
    """The Coriolis term without its 2: the checker diagnoses it as coriolis_without_factor_2 and
    the worked solution of the same scene shows that id, with the same wrong vector (a_Cor / 2),
    to the last bit."""
    e = _exercise(kind, "standard", seed)
    (made,) = [m for m in typical_mistakes(e) if m.kind == "coriolis_without_factor_2"]
    wrong = [made.values[f"{key}_{axis}"] for axis in "xy"]
    graded = check_answers(e, {f"{key}_{axis}": w for axis, w in zip("xy", wrong, strict=True)})
    named = {r["mistake"] for r in graded["results"] if r["key"].startswith(key)}
    assert named == {"coriolis_without_factor_2"}
    shown = [m for m in _shown(e.scene) if m["kind"] == "coriolis_without_factor_2"]
    assert shown, [m["kind"] for m in _shown(e.scene)]
    assert shown[0]["values"]["wrong"]["value"] == wrong


@pytest.mark.parametrize("seed", range(3))
def test_a_coriolis_term_on_the_fixed_guide_is_graded_and_shown_alike(seed: int) -> None:
    """The slider-crank's rod on its fixed guide: the checker names coriolis_on_fixed_guide for
    the wrong alpha it leads to, the worked solution shows the same id with the wrong term
    2 omega_rod x v_rel."""
    e = _exercise("slider_crank", "standard", seed)
    (made,) = [m for m in typical_mistakes(e) if m.kind == "coriolis_on_fixed_guide"]
    key = "alpha_coupler"
    graded = check_answers(e, {key: made.values[key]})
    (row,) = [r for r in graded["results"] if r["key"] == key]
    assert row["mistake"] == "coriolis_on_fixed_guide"
    (shown,) = [m for m in _shown(e.scene) if m["kind"] == "coriolis_on_fixed_guide"]
    analysis = solver.analyze(e.scene).as_dict()
    omega = analysis["links"]["coupler"]["omega"]
    v_rel = np.array(analysis["joints"][0]["relative_velocity"])
    expected = coriolis_acceleration(np.asarray(omega), v_rel)
    assert shown["values"]["wrong"]["value"] == pytest.approx(list(expected), rel=1e-12)


# --- the wrong values: each the formula with exactly one term wrong ----------------------------


def test_the_wrong_coriolis_terms() -> None:
    """a_Cor / 2 is omega x v_rel to the bit, 0 a_Cor has the shape of a_Cor, and the term with
    another link's omega is 2 omega_other x v_rel."""
    rng = np.random.default_rng(7)
    for _ in range(200):
        omega, v_rel = float(rng.normal()), rng.normal(size=2)
        a_cor = coriolis_acceleration(np.asarray(omega), v_rel)
        assert np.array_equal(coriolis_without_factor_2(a_cor), omega * perp(v_rel))
        assert np.array_equal(coriolis_left_out(a_cor), np.zeros(2))
        assert np.array_equal(coriolis_with_omega_of(omega, v_rel), a_cor)


def test_alpha_in_the_normal_term_differs_from_the_right_one_by_the_normal_term() -> None:
    """a_A + alpha x r - alpha r less the right a_A + alpha x r - omega^2 r: (omega^2 - alpha) r."""
    a_A, r = np.array([0.3, -1.2]), np.array([0.2, 0.1])
    omega, alpha = 3.0, 5.0
    right = rigid_body_acceleration(a_A, np.asarray(omega), np.asarray(alpha), r)
    np.testing.assert_allclose(
        alpha_in_normal_term(a_A, omega, alpha, r) - right, (omega**2 - alpha) * r, atol=1e-15
    )


# --- every family of the catalogue: a wrong value, and named where it is made -------------------


@cache
def _shown_by_id() -> dict[str, list[tuple[str, dict[str, Any], int]]]:
    """Catalogue id -> (where, the mistake as the /solution body lists it, the number of steps)
    over the worked solutions of the seed scenes (every method) and of one exercise of every
    type and difficulty."""
    found: dict[str, list[tuple[str, dict[str, Any], int]]] = {}
    scenes: list[tuple[str, Mapping[str, Any], str, float | None]] = []
    for path in SOLVED:
        doc = json.loads(path.read_text())
        methods = ("vector",) if doc.get("kind") == "spatial_chain" else ("vector", "loop")
        scenes += [(f"{path.stem}-{method}", doc, method, None) for method in methods]
    for kind in TYPES:
        for difficulty in DIFFICULTIES:
            e = _exercise(kind, difficulty, 1)
            method = "newton_euler" if kind in DYNAMIC else "vector"
            if e.task is None:  # a synthesis task's worked solution names no mistakes
                scenes.append((str(e.id), e.scene, method, _angle(e)))
    for where, scene, method, angle in scenes:
        body = solver.solve(scene, method=method, angle_deg=angle).as_dict()
        for m in body["mistakes"]:
            found.setdefault(m["kind"], []).append((where, m, len(body["steps"])))
    return found


@cache
def _diagnosed_by_id() -> dict[str, list[tuple[Exercise, WrongAnswers]]]:
    """Catalogue id -> (exercise, its wrong answers) over one exercise of every type and
    difficulty."""
    found: dict[str, list[tuple[Exercise, WrongAnswers]]] = {}
    for kind in TYPES:
        for difficulty in DIFFICULTIES:
            e = _exercise(kind, difficulty, 1)
            for made in mistakes_of(e):
                found.setdefault(made.kind, []).append((e, made))
    return found


def _made_earlier(e: Exercise, made: WrongAnswers, key: str, value: float) -> bool:
    """Whether a mistake listed before ``made`` gives ``value`` for ``key`` too (then the
    diagnosis names that one: ambiguous by nature, as a sign mistake on a negative answer that
    is also its magnitude)."""
    asked = next(a for a in e.asked if a.key == key)
    for other in mistakes_of(e):
        if other.kind == made.kind:
            return False
        if key in other.values and within(other.values[key], value, asked.tolerance):
            return True
    return False


@pytest.mark.parametrize("mistake_id", sorted(CATALOGUE))
def test_each_family_of_mistakes_gives_a_wrong_value_and_is_named_for_it(mistake_id: str) -> None:
    """For every entry of the catalogue, wherever a worked solution lists it: its wrong value
    shows differently from the right one at the solution's digits (a mistake that changes
    nothing in this problem is not listed; a mistake of form has words and no values), under
    the catalogue's title, below a step of the solution. Wherever the checker makes it with
    wrong answers: an answer with those values is graded incorrect and diagnosed as this
    mistake for at least one asked quantity (a mistake may leave a quantity right: a pole's
    coordinate it does not move)."""
    shown = _shown_by_id().get(mistake_id, [])
    diagnosed = [(e, m) for e, m in _diagnosed_by_id().get(mistake_id, []) if m.values]
    assert shown or diagnosed, f"{mistake_id}: made nowhere"
    for where, m, steps in shown:
        assert m["text"], (where, mistake_id)
        if m["values"]:  # else a mistake of form, explained in words (E3 x E1 is E2, not E1)
            wrong, right = m["values"]["wrong"], m["values"]["right"]
            assert wrong["display"] != right["display"], (where, mistake_id, wrong["display"])
        if mistake_id != "dynamics.moment_about_accelerating_point":  # titled with its pin
            assert m["title"] == typical_mistake(mistake_id).title
        assert 0 <= m["step"] < steps, (where, mistake_id)
    for e, made in diagnosed:
        named, ambiguous = set(), set()
        for key, value in made.values.items():
            row = next(r for r in check_answers(e, {key: value})["results"] if r["key"] == key)
            if row["verdict"] == "incorrect":
                named.add(row["mistake"])
                if _made_earlier(e, made, key, value):
                    ambiguous.add(row["mistake"])  # an earlier mistake gives this value too
        if named - ambiguous:  # else every value it gives is an earlier mistake's too
            assert mistake_id in named, (str(e.id), mistake_id, named, dict(made.values))


def test_a_cam_at_rest_lists_no_chain_rule_mistake() -> None:
    """At the start of the rise (v = 0: leaving omega out or beta in degrees gives 0 as well)
    the cam's worked solution lists neither chain-rule mistake; at the cam angle the exercise
    asks about, inside the lift, it lists both."""
    e = _exercise("cam_follower_motion", "standard", 2)
    assert not {m["kind"] for m in _shown(e.scene, "vector", 0.0)} & SHARED
    inside = {m["kind"] for m in _shown(e.scene, "vector", _angle(e))}
    assert {"cam_omega_left_out", "cam_beta_in_degrees"} <= inside

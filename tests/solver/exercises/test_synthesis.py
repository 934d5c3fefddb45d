"""The synthesis exercise types: keys against independent computations, the typical mistakes
against the misread systems (each diagnosed as itself: ``test_checking``, over every type), the
worked solution, an exercise built on a task.

Independent values: Freudenstein's 3x3 system K1 cos(theta_4) - K2 cos(theta_2) + K3 =
cos(theta_2 - theta_4) written and solved here with numpy at x_j = (x0 + xf)/2 - (xf - x0)/2
cos((2j - 1) pi / 6) (Norton, ch. 5; the lengths a = d/K1, c = d/K2, b^2 = a^2 + c^2 + d^2 -
2 a c K3); for motion, the four-bar with the answered fixed pivots analysed by
``solver.analyze`` at the crank angle of each position, whose coupler must be there (P and
the coupler's angle), and the pole P12 a fixed point of the rotation taking position 1 to 2.
"""

from __future__ import annotations

import cmath
import math
import random
from typing import Any

import numpy as np
import pytest

import solver
from solver.exercises import DIFFICULTIES, ExerciseId, build, generate
from solver.exercises.answers import solve_scene, value_at
from solver.exercises.checking import check_answers, mistakes_of
from solver.exercises.figures import figure_svg
from solver.exercises.generation import foreseen_answers
from solver.exercises.registry import TYPES
from solver.exercises.solutions import worked_solution
from solver.synthesis.function import parse_function

TOLERANCE = 1e-9  # relative, of the keys against the independent values


def _f(task: dict[str, Any], x: np.ndarray) -> np.ndarray:
    """f(x), read by the synthesis' parser (the time laws' language in x)."""
    value, _, _ = parse_function(task["function"]).evaluate(x)
    return np.asarray(value, dtype=float)


def freudenstein(task: dict[str, Any], xs: np.ndarray, degrees_as_radians: bool = False) -> dict:
    """K1, K2, K3 and |a|, b, |c| of the task at the precision points ``xs``, with numpy."""
    x0, xf = task["x_range"]
    y0, yf = _f(task, np.array([x0, xf]))
    (s2, f2), (s4, f4) = task["input_range_deg"], task["output_range_deg"]
    theta2 = s2 + (xs - x0) / (xf - x0) * (f2 - s2)
    theta4 = s4 + (_f(task, xs) - y0) / (yf - y0) * (f4 - s4)
    if not degrees_as_radians:
        theta2, theta4 = np.radians(theta2), np.radians(theta4)
    matrix = np.column_stack([np.cos(theta4), -np.cos(theta2), np.ones(3)])
    k1, k2, k3 = np.linalg.solve(matrix, np.cos(theta2 - theta4))
    d = task["ground_length"]
    a, c = d / k1, d / k2
    b = math.sqrt(a * a + c * c + d * d - 2 * a * c * k3)
    return {"K1": k1, "K2": k2, "K3": k3, "a": abs(a), "b": b, "c": abs(c)}


def chebyshev(x0: float, xf: float) -> np.ndarray:
    j = np.arange(1, 4)
    return (x0 + xf) / 2 - (xf - x0) / 2 * np.cos((2 * j - 1) * math.pi / 6)


@pytest.mark.parametrize("difficulty", DIFFICULTIES)
def test_function_keys_are_freudensteins_system_solved_with_numpy(difficulty: str) -> None:
    for e in generate("synthesis_function", difficulty, 3, 3):
        task = e.task
        assert task is not None and e.as_json()["task"] == task and "scene" not in e.as_json()
        given = task["precision_points"]
        xs = chebyshev(*task["x_range"]) if given == 3 else np.array(given)
        assert (given == 3) == (difficulty != "basic")
        expected = freudenstein(task, xs)
        assert set(e.answers) == ({"K1", "K2", "K3"} | ({"a", "b", "c"} if given == 3 else set()))
        for key, value in e.answers.items():
            assert value == pytest.approx(expected[key], rel=TOLERANCE), (e.id, key)


def _rotor(degrees: float) -> complex:
    return cmath.exp(1j * math.radians(degrees))


def _z(p: Any) -> complex:
    return complex(p[0], p[1])


def _guided(eid: str, A: complex, D: complex, task: dict[str, Any]) -> list[complex]:
    """The four-bar A B1 C1 D (P1 on the coupler) built here, analysed by the solver at the crank
    angle where B reaches each B_j = P_j + e^{i(phi_j - phi_1)} (B1 - P1): P must be at P_j and
    C at C_j (the coupler turned by phi_j - phi_1), to 1e-9 of the coupler. The places B_j."""
    positions = task["positions"]
    B1, C1 = (_z(p) for p in task["moving_pivots"])
    P1, phi1 = _z(positions[0]["point"]), positions[0]["angle_deg"]
    size = abs(C1 - B1)
    places_1 = zip("ABCDP", (A, B1, C1, D, P1), strict=True)
    doc = {
        "kind": "linkage",
        "points": {n: [z.real, z.imag] for n, z in places_1},
        "links": {"ground": {"points": ["A", "D"], "ground": True},
                  "crank": {"points": ["A", "B"]}, "coupler": {"points": ["B", "C", "P"]},
                  "rocker": {"points": ["D", "C"]}},
        "joints": [{"type": "revolute", "point": "A", "links": ["ground", "crank"]},
                   {"type": "revolute", "point": "B", "links": ["crank", "coupler"]},
                   {"type": "revolute", "point": "C", "links": ["coupler", "rocker"]},
                   {"type": "revolute", "point": "D", "links": ["rocker", "ground"]}],
    }  # fmt: skip
    places = []
    for p in positions:
        turn = _rotor(p["angle_deg"] - phi1)
        Bj, Cj = _z(p["point"]) + turn * (B1 - P1), _z(p["point"]) + turn * (C1 - P1)
        places.append(Bj)
        angle = math.degrees(cmath.phase(Bj - A))
        driver = {"link": "crank", "omega": 1.0, "alpha": 0.0, "angle_deg": angle}
        body = solver.analyze({**doc, "drivers": [driver]}).as_dict()
        at = {n: _z(body["points"][n]["position"]) for n in "BCP"}
        assert abs(at["P"] - _z(p["point"])) <= 1e-9 * size, eid
        assert abs(at["C"] - Cj) <= 1e-9 * size, eid
    return places


@pytest.mark.parametrize("difficulty", DIFFICULTIES)
def test_the_answered_fixed_pivots_guide_the_coupler_through_every_position(
    difficulty: str,
) -> None:
    """The four-bar A B1 C1 D (P1 on the coupler) built here from the answers, analysed by the
    solver at the crank angle where B reaches B_j = P_j + e^{i(phi_j - phi_1)} (B1 - P1): P is at
    P_j and the coupler turned by phi_j - phi_1, to 1e-9 of the coupler's length."""
    for e in generate("synthesis_fixed_pivots", difficulty, 4, 2):
        task, k = e.task, e.answers
        assert task is not None
        positions = task["positions"]
        assert len(positions) == 3 and (positions[0]["angle_deg"] == 0) == (difficulty == "basic")
        A, D = complex(k["A_x"], k["A_y"]), complex(k["D_x"], k["D_y"])
        B1, C1 = (_z(p) for p in task["moving_pivots"])
        P1, phi1 = _z(positions[0]["point"]), positions[0]["angle_deg"]
        size = abs(C1 - B1)
        places = _guided(e.id, A, D, task)
        # A is the centre of the circle through B1, B2, B3
        radii = [abs(b - A) for b in places]
        assert max(radii) - min(radii) <= 1e-9 * size
        if difficulty == "challenging":  # P12 is fixed by the rotation taking pose 1 to pose 2
            pole = complex(k["P12_x"], k["P12_y"])
            turn = _rotor(positions[1]["angle_deg"] - phi1)
            assert abs(pole + turn * (P1 - pole) - _z(positions[1]["point"])) <= 1e-9 * size


def test_the_function_mistakes_are_the_misread_systems_solved_with_numpy() -> None:
    e = build(ExerciseId("synthesis_function", "standard", 6, 0))
    task = e.task
    assert task is not None
    made = {m.kind: m.values for m in mistakes_of(e)}
    x0, xf = task["x_range"]
    ends = freudenstein(task, np.array([x0, (x0 + xf) / 2, xf]))
    for key, value in made["synthesis.chebyshev_spacing"].items():
        assert value == pytest.approx(ends[key], rel=TOLERANCE)
    radian_mode = freudenstein(task, chebyshev(x0, xf), degrees_as_radians=True)
    for key in ("K1", "K2", "K3"):
        assert made["degrees_as_radians"][key] == pytest.approx(radian_mode[key], rel=TOLERANCE)
    assert made["synthesis.freudenstein_sign"]["K2"] == -e.answers["K2"]
    assert made["synthesis.k1_k2_swapped"] == {"a": e.answers["c"], "c": e.answers["a"]}


def test_a_negative_k_given_as_a_length_is_the_sign_of_k() -> None:
    """A crank pointing the other way (K1 < 0): -|a| is diagnosed as the signed d / K1."""
    e = build(ExerciseId("synthesis_function", "challenging", 1, 0))
    assert e.answers["K1"] < 0
    assert check_answers(e, dict(e.answers))["score"] == 1.0
    result = check_answers(e, {"a": -e.answers["a"]})["results"][3]
    assert result["key"] == "a" and result["mistake"] == "synthesis.signed_length"


def test_the_worked_solution_is_the_synthesis_construction() -> None:
    e = build(ExerciseId("synthesis_function", "standard", 2, 0))
    steps = worked_solution(e)
    assert all(s["kind"].startswith("synthesis.") for s in steps)
    assert steps[0]["figure"].startswith("<svg")
    assert any("K_1" in s["latex"] for s in steps)
    motion = worked_solution(build(ExerciseId("synthesis_fixed_pivots", "standard", 2, 0)))
    assert all(s["kind"].startswith("synthesis.") for s in motion)


def test_the_statement_gives_what_the_task_gives() -> None:
    e = build(ExerciseId("synthesis_fixed_pivots", "challenging", 9, 0))
    task = e.task
    assert task is not None
    for p in task["positions"]:
        assert f"({p['point'][0]:g}, {p['point'][1]:g}) m at {p['angle_deg']:g} deg" in (
            e.statement.text
        )
    assert "pole P12" in e.statement.text
    f = build(ExerciseId("synthesis_function", "basic", 9, 0)).task
    assert f is not None and isinstance(f["precision_points"], list)


def _on_bisector(first: complex, second: complex, offset: float) -> complex:
    """M + d n with numpy: the chord's midpoint plus the offset times its unit normal to the
    left of first -> second."""
    chord = np.array([second.real - first.real, second.imag - first.imag])
    normal = np.array([-chord[1], chord[0]]) / np.linalg.norm(chord)
    x, y = np.array([first.real + second.real, first.imag + second.imag]) / 2 + offset * normal
    return complex(x, y)


@pytest.mark.parametrize("difficulty", DIFFICULTIES)
def test_two_position_keys_are_the_midpoint_plus_the_offset_along_the_normal(
    difficulty: str,
) -> None:
    """Two positions: B2 = P2 + e^{i(phi_2 - phi_1)} (B1 - P1) (C2 likewise), A = M + dA n of
    B1B2 and D of C1C2 (numpy), to 1e-9 of the coupler; A equidistant from B1 and B2; the
    four-bar built from the answers guides the coupler through both (``_guided``); P12 the
    fixed point of the rotation at challenging."""
    for e in generate("synthesis_two_positions", difficulty, 4, 3):
        task, k = e.task, e.answers
        assert task is not None
        positions = task["positions"]
        assert len(positions) == 2 and (positions[0]["angle_deg"] == 0) == (difficulty == "basic")
        dA, dD = task["bisector_offsets"]
        assert round(dA, 3) == dA and round(dD, 3) == dD  # millimetres
        B1, C1 = (_z(p) for p in task["moving_pivots"])
        P1, P2 = (_z(p["point"]) for p in positions)
        turn = _rotor(positions[1]["angle_deg"] - positions[0]["angle_deg"])
        B2, C2 = P2 + turn * (B1 - P1), P2 + turn * (C1 - P1)
        size = abs(C1 - B1)
        A, D = complex(k["A_x"], k["A_y"]), complex(k["D_x"], k["D_y"])
        assert abs(A - _on_bisector(B1, B2, dA)) <= 1e-9 * size, e.id
        assert abs(D - _on_bisector(C1, C2, dD)) <= 1e-9 * size, e.id
        assert abs(abs(A - B1) - abs(A - B2)) <= 1e-9 * size
        places = _guided(e.id, A, D, task)
        assert abs(places[1] - B2) <= 1e-12 * size
        assert (difficulty == "challenging") == ("P12_x" in k)
        if difficulty == "challenging":
            pole = complex(k["P12_x"], k["P12_y"])
            assert abs(pole + turn * (P1 - pole) - P2) <= 1e-9 * size


def test_the_two_position_mistakes_are_the_other_side_and_the_coupler_s_bisector() -> None:
    """The offsets' sign flipped: A = M - dA n; the coupler's bisector: A = M + dA n of B1C1 and
    D of C1B1 (numpy); each diagnosed by the check."""
    e = build(ExerciseId("synthesis_two_positions", "standard", 3, 0))
    task = e.task
    assert task is not None
    made = {m.kind: m.values for m in mistakes_of(e)}
    dA, dD = task["bisector_offsets"]
    B1, C1 = (_z(p) for p in task["moving_pivots"])
    P1, P2 = (_z(p["point"]) for p in task["positions"])
    turn = _rotor(task["positions"][1]["angle_deg"] - task["positions"][0]["angle_deg"])
    B2, C2 = P2 + turn * (B1 - P1), P2 + turn * (C1 - P1)
    expected = {
        "synthesis.offset_side": (_on_bisector(B1, B2, -dA), _on_bisector(C1, C2, -dD)),
        "synthesis.coupler_bisector": (_on_bisector(B1, C1, dA), _on_bisector(C1, B1, dD)),
    }
    for kind, (A, D) in expected.items():
        values = made[kind]
        got = (complex(values["A_x"], values["A_y"]), complex(values["D_x"], values["D_y"]))
        assert abs(got[0] - A) <= 1e-9 * abs(C1 - B1) and abs(got[1] - D) <= 1e-9 * abs(C1 - B1)
        row = check_answers(e, {"A_x": values["A_x"]})["results"][0]
        assert row["key"] == "A_x" and row["mistake"] == kind, (kind, row)


def test_the_two_position_statement_and_figure_give_the_offsets() -> None:
    e = build(ExerciseId("synthesis_two_positions", "challenging", 9, 0))
    task = e.task
    assert task is not None
    dA, dD = task["bisector_offsets"]
    assert f"dA = {dA:g} m" in e.statement.text and f"dD = {dD:g} m" in e.statement.text
    assert "pole P12" in e.statement.text and "d_A" in e.statement.latex
    figure = figure_svg(task)
    assert f"dA = {dA:g} m, dD = {dD:g} m" in figure and figure.count("B1") >= 1
    steps = worked_solution(e)
    assert all(s["kind"].startswith("synthesis.") for s in steps)
    assert any(f"dA = {dA:g} m" in s["text"] for s in steps)


@pytest.mark.parametrize("kind", ["synthesis_fixed_pivots", "synthesis_two_positions"])
def test_a_motion_drafts_foreseen_answers_are_its_solved_answers(kind: str) -> None:
    """The answers a motion draft foresees from its design (``Draft.foreseen``: the fixed
    pivots and the pole, before /synthesis verifies the linkage) are, to the last bit, those
    read from the body it is solved into; so a draft rejected on them before solving is one
    the solved answers reject too (the same exercises)."""
    compared = 0
    for difficulty in DIFFICULTIES:
        rng = random.Random(f"{kind}:{difficulty}")
        for _ in range(6):
            draft = TYPES[kind].draw(rng, difficulty)
            foreseen = foreseen_answers(draft)
            assert {"A_x", "A_y", "D_x", "D_y"} <= set(foreseen)
            solved = solve_scene(draft.scene)
            for asked in draft.asked:
                if asked.key in foreseen:
                    assert foreseen[asked.key] == value_at(solved, asked.path), asked.key
                    compared += 1
    assert compared >= 4 * 18

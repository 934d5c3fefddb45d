"""Exercise generation in the solver: ids, determinism by seed, nice inputs, figures."""

from __future__ import annotations

import itertools
import math
import re
import xml.etree.ElementTree as ET

import pytest

from solver.api import parse_scene, solve
from solver.errors import InvalidScene
from solver.exercises import DIFFICULTIES, TYPES, ExerciseId, build, generate, parse_id
from solver.exercises.families import POLE_REACH, num, polynomial
from solver.exercises.figures import nice_length
from solver.exercises.solutions import worked_solution
from solver.teaching.svg import text_box


def test_an_id_round_trips() -> None:
    ident = parse_id("four_bar_velocity:standard:7:0")
    assert ident == ExerciseId("four_bar_velocity", "standard", 7, 0)
    assert str(ident) == "four_bar_velocity:standard:7:0"


@pytest.mark.parametrize("bad", ["", "a:b:c:d", "four_bar_velocity:standard:-1:0", 7, "x" * 500])
def test_a_malformed_id_is_invalid_scene(bad: object) -> None:
    with pytest.raises(InvalidScene):
        parse_id(bad)  # type: ignore[arg-type]


@pytest.mark.parametrize("kind", list(TYPES))
def test_generation_is_deterministic_by_seed(kind: str) -> None:
    first = [e.as_json() for e in generate(kind, "standard", 2024, 3)]
    again = [e.as_json() for e in generate(kind, "standard", 2024, 3)]
    assert first == again
    other = [e.as_json() for e in generate(kind, "standard", 2025, 3)]
    documents = [e.get("scene") or e["task"] for e in first]
    assert [e.get("scene") or e["task"] for e in other] != documents
    # exercise k of a batch is the exercise of its own id
    assert build(parse_id(first[2]["id"])).as_json() == first[2]


def test_the_difficulty_changes_what_is_asked() -> None:
    asked = {
        d: [a.key for a in build(ExerciseId("quick_return", d, 5, 0)).asked] for d in DIFFICULTIES
    }
    assert set(asked["basic"]) < set(asked["standard"]) < set(asked["challenging"])


def _length(scene: dict, a: str, b: str) -> float:  # type: ignore[type-arg]
    return math.dist(scene["points"][a], scene["points"][b])


@pytest.mark.parametrize("difficulty", DIFFICULTIES)
def test_inputs_are_rounded_as_a_book_prints_them(difficulty: str) -> None:
    for e in generate("four_bar_acceleration", difficulty, 99, 20):
        scene = e.scene
        for a, b in (("A", "B"), ("B", "C"), ("D", "C"), ("A", "D")):
            length = _length(scene, a, b)  # type: ignore[arg-type]
            assert abs(length * 100 - round(length * 100)) < 1e-9, (e.id, a, b, length)
        driver = scene["drivers"][0]
        assert float(driver["omega"]).is_integer() and float(driver["alpha"]).is_integer()
        angle = math.degrees(math.atan2(*reversed(scene["points"]["B"])))
        assert abs(angle - round(angle / 5) * 5) < 1e-9
        if difficulty == "basic":
            assert driver["alpha"] == 0.0


@pytest.mark.parametrize("kind", list(TYPES))
def test_the_figure_is_svg_labelled_with_the_scene_points(kind: str) -> None:
    e = build(ExerciseId(kind, "challenging", 1, 0))
    root = ET.fromstring(e.statement.figure_svg)
    assert root.tag == "{http://www.w3.org/2000/svg}svg"
    labels = {t.text for t in root.iter("{http://www.w3.org/2000/svg}text")}
    if e.task is not None:  # what the task gives, never the answer: no fixed pivot of a motion
        if e.task["task"] == "motion":
            count = len(e.task["positions"])
            assert {"B1", "C1"} <= labels and "A" not in labels and "D" not in labels
            assert sum(bool(t and t.startswith("P")) for t in labels) == count
        else:  # the ground link and the two angle ranges, the links not drawn
            assert {"A", "D"} <= labels and "B" not in labels
            assert sum(bool(t and "→" in t) for t in labels) == 2
    elif e.scene["kind"] == "gear_train":  # each gear labelled with its name and teeth
        gears = e.scene["gears"]
        assert {f"{name} ({g['teeth']})" for name, g in gears.items()} <= labels
    elif e.scene["kind"] == "cam":  # the centre O and the pressure angle marked, not given
        assert {"O", "phi"} <= labels
    else:
        assert set(e.scene["points"]) <= labels
    assert any(text and " m" in text for text in labels)  # the scale bar
    if e.scene.get("kind") == "linkage":
        assert any(text and ("ω" in text or "φ" in text) for text in labels)


SVG = "{http://www.w3.org/2000/svg}"


@pytest.mark.parametrize("kind", list(TYPES))
def test_no_two_texts_of_a_figure_overlap_and_each_lies_within_it(kind: str) -> None:
    """Every text of an exercise's figure (a point's name, the driver's rates, the scale bar's
    length, a note), its box estimated as the canvas estimates it (``text_box``: wider than a
    sans-serif font sets most labels), meets no other and lies within the figure's view box.
    Before, over every type, difficulty and 12 seeds (720 figures), 213 pairs of texts overlapped
    (the rates on a point's name or on the scale bar's length, a differential's two side gears'
    names) and 57 texts ran off the figure (the two-position task's note, 100 px too long)."""
    for difficulty, seed in itertools.product(DIFFICULTIES, range(4)):
        e = build(ExerciseId(kind, difficulty, seed, 0))
        root = ET.fromstring(e.statement.figure_svg)
        left, top, width, height = (float(v) for v in root.get("viewBox", "").split())
        boxes = []
        for t in root.iter(f"{SVG}text"):
            at = (float(t.get("x", "")), float(t.get("y", "")))
            box = text_box(
                at, t.text or "", float(t.get("font-size", "")), t.get("text-anchor", "start")
            )
            assert left <= box.left and box.right <= left + width, (str(e.id), t.text)
            assert top <= box.top and box.bottom <= top + height, (str(e.id), t.text)
            boxes.append((t.text, box))
        for (a, box_a), (b, box_b) in itertools.combinations(boxes, 2):
            assert not box_a.overlaps(box_b), (str(e.id), a, b)


def test_statements_name_every_asked_symbol_in_latex() -> None:
    for kind in TYPES:
        e = build(ExerciseId(kind, "standard", 4, 0))
        for a in e.asked:
            assert a.symbol in e.statement.latex
        assert e.statement.text.endswith(".")


@pytest.mark.parametrize("target", [0.1 * (1 - 1e-16), 0.1, 1.0 - 1e-16, 3e-3, 0.7, 12.0, 1e3])
def test_the_scale_bar_is_a_round_length_within_its_room(target: float) -> None:
    length = nice_length(target)
    assert 0.2 * target < length <= target
    mantissa = length / 10.0 ** math.floor(math.log10(length) + 1e-9)
    assert round(mantissa, 9) in (1.0, 2.0, 5.0)


def test_a_set_is_of_distinct_exercises_each_determined_by_its_id() -> None:
    """The inverted slider-crank at basic has a few thousand scenes: among indices 0..39 of seed
    7 two scenes repeat; the set of 40 passes over them, and each id still gives its exercise."""
    raw = [build(ExerciseId("inverted_slider_crank", "basic", 7, i)).scene for i in range(40)]
    assert len({repr(s) for s in raw}) < 40
    made = generate("inverted_slider_crank", "basic", 7, 40)
    assert len({repr(e.scene) for e in made}) == 40
    assert [e.id.index for e in made][:3] == [0, 1, 2] and made[-1].id.index >= 40
    for e in made[-3:]:
        assert build(e.id) == e


def test_statements_read_as_a_lecturer_writes_them() -> None:
    assert num(-0.0) == "0" and num(-0.25) == "-0.25"
    assert polynomial([(-1.0, "t"), (-0.05, "t^2")]) == "-1 t - 0.05 t^2"
    assert polynomial([(3.0, "t"), (0.0, "t^2")]) == "3 t"
    assert polynomial([(0.0, "t"), (0.5, "t^2")]) == "0.5 t^2"
    for kind in TYPES:
        for difficulty in DIFFICULTIES:
            for seed in (0, 1):
                e = build(ExerciseId(kind, difficulty, seed, 0))
                text = e.statement.text + " " + e.statement.latex
                assert not re.search(r"(?<![\d.])-0(?![.\d])", text), (e.id, text)
                assert "+ -" not in text and "+-" not in text, (e.id, text)
                assert not re.search(r"-[\d.]+ m to the (left|right)", text), (e.id, text)
                values = sorted(e.answers.values())
                for a, b in itertools.pairwise(values):  # no two answers one could swap
                    assert abs(a - b) > 0.02 * max(abs(a), abs(b)), (e.id, e.answers)


def test_a_moving_point_law_with_a_negative_term_is_the_solvers_law() -> None:
    """The law as stated is the law analysed: phi(t) = -1 t - 0.05 t^2 in the scene too."""
    for seed in range(40):
        e = build(ExerciseId("moving_point", "challenging", seed, 0))
        law = e.scene["drivers"][0]["angle_law"]
        assert law.replace("*t", " t") in e.statement.text
        if "- " in law:
            return
    raise AssertionError("no law with a negative term in 40 seeds")


def test_the_coupler_poles_lie_on_the_sheet() -> None:
    for seed in range(25):
        e = build(ExerciseId("four_bar_poles", "standard", seed, 0))
        a, d = e.scene["points"]["A"], e.scene["points"]["D"]
        ground = math.dist(a, d)
        for kind in ("velocity_pole_coupler", "acceleration_pole_coupler"):
            pole = (e.answers[f"{kind}_x"], e.answers[f"{kind}_y"])
            assert math.dist(pole, a) <= POLE_REACH * ground


@pytest.mark.parametrize("kind", ["four_bar_velocity", "four_bar_acceleration"])
def test_the_angle_extremes_only_where_asked(kind: str) -> None:
    """A four-bar exercise asks one instant's velocities or accelerations, not the links'
    extreme angles over a turn: its worked solution leaves that step out, while the worked
    solution of its scene (/solution, any method) keeps it."""
    exercise = generate(kind, "standard", 5, 1)[0]
    kinds = [step["kind"] for step in worked_solution(exercise)]
    full = [step["kind"] for step in solve(parse_scene(exercise.scene)).as_dict()["steps"]]
    assert "angle_extremes" in full
    assert kinds == [kind for kind in full if kind != "angle_extremes"]

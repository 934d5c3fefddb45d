"""The cam exercise types (issue 24, ``solver.exercises.cams``): each key is the /analyze answer at
its path's cam angle, the statement carries the data, the worked solution is written at that
angle, and the chain rule's typical mistakes are diagnosed as themselves."""

from __future__ import annotations

import json
import math
from typing import Any

import pytest

import solver
from solver.exercises import DIFFICULTIES, ExerciseId, build
from solver.exercises.cams import cam_angle_of, cam_root, parse_cam_root
from solver.exercises.checking import check_answers, mistakes_of
from solver.exercises.export import answer_csv, exercises_json, html_sheets, moodle_xml
from solver.exercises.solutions import worked_solution

CAM_TYPES = ("cam_follower_motion", "cam_pressure_angle")
SEEDS = (1, 2, 3, 4, 5)


def _at(body: dict[str, Any], path: str) -> float:
    node: Any = body
    for part in path.split("."):
        node = node[int(part)] if isinstance(node, list) else node[part]
    return float(node)


@pytest.mark.parametrize("kind", CAM_TYPES)
@pytest.mark.parametrize("difficulty", DIFFICULTIES)
def test_keys_are_analyze_at_the_asked_cam_angle(kind: str, difficulty: str) -> None:
    for seed in SEEDS:
        e = build(ExerciseId(kind, difficulty, seed, 0))
        angle = cam_angle_of(e)
        assert angle is not None and angle % 5 == 0
        body = solver.analyze(dict(e.scene), angle_deg=angle).as_dict()
        for asked in e.asked:
            root, _, rest = asked.path.partition(".")
            assert parse_cam_root(root) == angle and root == cam_root(angle)
            assert e.answers[asked.key] == _at(body, rest), (e.id, asked.key)
        # a sound design: no pressure angle above its limit, no undercutting
        assert not [w for w in body["warnings"] if w.startswith(("pressure", "undercut"))]


@pytest.mark.parametrize("kind", CAM_TYPES)
def test_the_statement_carries_the_data(kind: str) -> None:
    for difficulty in DIFFICULTIES:
        e = build(ExerciseId(kind, difficulty, 7, 0))
        text, doc = e.statement.text, e.scene
        assert f"base radius {doc['cam']['base_radius']:g} m" in text
        assert f"{abs(doc['cam']['omega']):g} rad/s" in text
        assert f"rises {doc['segments'][0]['lift']:g} m" in text
        for segment in doc["segments"]:
            assert f"{segment['duration_deg']:g} deg" in text
        assert f"turned through {cam_angle_of(e)} deg" in text
        assert e.statement.figure_svg.startswith("<svg") and "phi =" not in e.statement.figure_svg
        if doc["follower"]["contact"] == "roller":
            assert f"radius {doc['follower']['roller_radius']:g} m" in text


def test_the_worked_solution_is_at_the_asked_angle_and_ends_with_the_key() -> None:
    for kind in CAM_TYPES:
        e = build(ExerciseId(kind, "standard", 3, 0))
        steps = worked_solution(e)
        summary = steps[-1]
        assert summary["kind"] == "cam.summary"
        assert f"theta = {cam_angle_of(e)} deg" in summary["text"]
        values = {v["source"][-1]: v["value"] for v in summary["values"].values()}
        for asked in e.asked:
            field = asked.path.split(".")[-1]
            if field in values:
                assert values[field] == e.answers[asked.key]


def test_the_chain_rule_mistakes_are_diagnosed() -> None:
    """v without omega is v / |omega|, a without omega^2 is a / omega^2; beta in degrees scales
    v by beta_rad / beta_deg = pi / 180; a pressure angle in degrees is diagnosed too."""
    e = build(ExerciseId("cam_follower_motion", "standard", 5, 0))
    omega = abs(e.scene["cam"]["omega"])
    made = {m.kind: m for m in mistakes_of(e)}
    left_out = made["cam_omega_left_out"].values
    assert left_out["v"] == pytest.approx(e.answers["v"] / omega)
    assert left_out["a"] == pytest.approx(e.answers["a"] / omega**2)
    assert made["cam_beta_in_degrees"].values["v"] == pytest.approx(e.answers["v"] * math.pi / 180)
    result = check_answers(e, {"v": left_out["v"], "a": e.answers["a"]})["results"]
    assert result[0]["mistake"] == "cam_omega_left_out" and result[1]["verdict"] == "correct"
    p = build(ExerciseId("cam_pressure_angle", "basic", 5, 0))
    degrees = math.degrees(p.answers["phi"])
    assert check_answers(p, {"phi": degrees})["results"][0]["mistake"] == "degrees_for_radians"


def test_every_export_carries_the_cam_key() -> None:
    """Moodle XML (cloze), the CSV key, the JSON and the HTML key sheets hold every answer."""
    exercises = [build(ExerciseId("cam_pressure_angle", "challenging", 9, i)) for i in range(2)]
    csv = answer_csv(exercises)
    data = json.loads(exercises_json(exercises, with_solutions=True))
    sheets = html_sheets(exercises, with_solutions=True)
    moodle = moodle_xml(exercises)
    for e, exported in zip(exercises, data["exercises"], strict=True):
        assert exported["answers"] == dict(e.answers)
        assert exported["solution"]["steps"][-1]["kind"] == "cam.summary"
        assert f'data-id="{e.id}"' in sheets or f"data-id='{e.id}'" in sheets
        for asked in e.asked:
            answer = e.answers[asked.key]
            assert repr(answer) in csv or f"{answer:.17g}" in csv
            assert f"{answer:.6g}" in sheets
            assert asked.path in csv
    assert moodle.count('<question type="cloze">') == len(exercises)

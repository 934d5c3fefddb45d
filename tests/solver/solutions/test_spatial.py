"""The worked solution of a spatial chain: the isometric figure of the chain and the
``reading`` step.

The figure parses as SVG; its projection is the isometric drawing written out here,
(X, Y) = (cos 30 (y - x), z - sin 30 (x + y)); every omega arrow measured on the paper (mm / 10
times the stated scale) is that projection of the /analyze body's omega to 0.1 %; the frame
E1, E2, E3 is drawn along the projected axes. The reading's words follow the signs of the
solver's numbers (omega . alpha, v . a) and its axis u is omega / |omega|. Its LaTeX renders in
KaTeX.
"""

from __future__ import annotations

import json
import math
import re
import xml.etree.ElementTree as ET
from pathlib import Path
from typing import Any

import numpy as np
import pytest
from hypothesis import given, settings

import solver
from solver.kinematics.spatial import parse_spatial_chain
from solver.solutions import solve
from solver.solutions.format import NOISE
from tests.solver.analysis.test_spatial_sweep import chains, seed_002, turntable_slider
from tests.solver.solutions.test_solve import NODE, _check_solution, run_katex

SVG = "{http://www.w3.org/2000/svg}"
RTOL = 1e-3
C30 = math.cos(math.radians(30))
PROJECTION = np.array([[-C30, C30, 0.0], [-0.5, -0.5, 1.0]])
EXAMPLES = Path(__file__).resolve().parents[3] / "server" / "examples"


def figure_of(solution: Any) -> ET.Element:
    figures = [s["figure"] for s in solution["steps"] if s.get("figure")]
    assert len(figures) == 1
    return ET.fromstring(figures[0])


def drawn(line: ET.Element, per_cm: float) -> np.ndarray:
    """A drawn line as a vector in the drawing's units: mm on paper, y up, / 10 * per_cm."""
    x1, y1, x2, y2 = (float(line.attrib[a]) for a in ("x1", "y1", "x2", "y2"))
    return np.array([x2 - x1, -(y2 - y1)]) / 10.0 * per_cm


def assert_figure_to_scale(doc: dict[str, Any]) -> int:
    """Check the figure; the number of omega arrows measured."""
    solution = solver.solve(doc)
    body = solver.analyze(doc)
    root = figure_of(solution)
    assert root.tag == f"{SVG}svg"
    scale = float(root.attrib["data-scale"])
    assert root.attrib["data-unit"] == "rad/s"
    caption = "".join(root.itertext())
    assert f"1 cm = {scale:g} rad/s" in caption, caption
    assert f"1 cm = {root.attrib['data-length-scale']} m" in caption
    rows = [[float(x) for x in row.split(",")] for row in root.attrib["data-projection"].split(";")]
    np.testing.assert_allclose(rows, PROJECTION, rtol=0, atol=1e-15)
    lines = {
        x.attrib["data-vector"]: x for x in root.iter(f"{SVG}line") if "data-vector" in x.attrib
    }
    measured = 0
    for name, motion in body["bodies"].items():
        want = PROJECTION @ np.array(motion["omega"])
        size = float(np.linalg.norm(want))
        if size * 10.0 / scale < 0.01:  # shorter than a pen draws: left out
            assert f"omega({name})" not in lines
            continue
        got = drawn(lines[f"omega({name})"], scale)
        assert np.linalg.norm(got - want) <= RTOL * size, (name, got, want)
        measured += 1
    frame = [drawn(lines[f"E{i}"], 1.0) for i in (1, 2, 3)]
    for i, e in enumerate(frame):  # along the projected axes, all three the same length in space
        column = PROJECTION[:, i]
        factor = float(np.linalg.norm(frame[2])) / float(np.linalg.norm(PROJECTION[:, 2]))
        np.testing.assert_allclose(e, factor * column, rtol=0, atol=RTOL * factor)
    return measured


def test_seed_002_figure_is_drawn_to_scale() -> None:
    assert assert_figure_to_scale(seed_002()) == 3


def test_prismatic_figure_is_drawn_to_scale() -> None:
    assert assert_figure_to_scale(turntable_slider(1.3, 0.4, -0.7)) == 2


def test_a_wrongly_scaled_omega_is_caught() -> None:
    """Mutation check: the measurement at twice the stated scale fails."""
    root = figure_of(solver.solve(seed_002()))
    line = next(x for x in root.iter(f"{SVG}line") if x.attrib.get("data-vector") == "omega(2)")
    want = PROJECTION @ np.array(solver.analyze(seed_002())["bodies"]["2"]["omega"])
    got = drawn(line, 2 * float(root.attrib["data-scale"]))
    assert np.linalg.norm(got - want) > RTOL * np.linalg.norm(want)


@pytest.mark.slow
@settings(max_examples=25, deadline=None)
@given(chains())
def test_random_chain_figures_are_drawn_to_scale(doc: dict[str, Any]) -> None:
    assert_figure_to_scale(doc)


# --- the reading ---------------------------------------------------------------------------------


def sentences(text: str) -> dict[str, str]:
    """The reading's sentence about each body ('body 2 turns ...') and point ('A moves ...')."""
    out = {}
    patterns = (
        r": (body (\S+) turns .*?) \(omega \. alpha",
        r": ((\S+) moves .*?) \(v \. a",
        r": (body (\S+) does not turn at this instant)\.",
        r": ((\S+) is at rest at this instant)\.",
    )
    for pattern in patterns:
        for match in re.finditer(pattern, text):
            out[match.group(2)] = match.group(1)
    return out


def trends(value: float, reference: float) -> set[str]:
    """What the reading may say of v . a (or omega . alpha). It writes steady where the product
    is rounding noise, |v . a| <= NOISE x max(|v||a|, the largest value of its unit in the
    solution), so at or below NOISE x |v||a| only steady; above 1e5 x NOISE x |v||a| (rates in
    these chains differ by less than 1e5) only the sign; in between either."""
    sign = "speeding up" if value > 0 else "slowing down"
    if abs(value) <= NOISE * reference:
        return {"steady"}
    return {sign} if abs(value) > 1e5 * NOISE * reference else {"steady", sign}


def says_one_of(sentence: str, words: set[str]) -> bool:
    return any(word in sentence for word in words)


def assert_reading_follows_the_signs(doc: dict[str, Any]) -> None:
    solution = solver.solve(doc)
    body = solution["results"]
    reading = next(s for s in solution["steps"] if s["kind"] == "reading")
    said = sentences(reading["text"])
    for name, motion in body["bodies"].items():
        w, a = np.array(motion["omega"]), np.array(motion["alpha"])
        size = float(np.linalg.norm(w))
        if size < 1e-9:
            assert "does not turn" in said[name]
            continue
        u = reading["values"][f"u({name})"]["value"]
        np.testing.assert_allclose(u, w / size, rtol=0, atol=1e-12)
        assert says_one_of(said[name], trends(float(w @ a), size * float(np.linalg.norm(a))))
        assert " rad/s " in said[name]
    for name, point in body["points"].items():
        v, a = np.array(point["velocity"]), np.array(point["acceleration"])
        speed = float(np.linalg.norm(v))
        if speed < 1e-9:
            assert "at rest" in said[name]
            continue
        speed_value = reading["values"][f"|v({name})|"]["value"]
        assert speed_value == pytest.approx(speed, rel=1e-12)
        assert says_one_of(said[name], trends(float(v @ a), speed * float(np.linalg.norm(a))))
        assert " m/s" in said[name]


def test_seed_002_reading() -> None:
    solution = solver.solve(seed_002())
    text = next(s for s in solution["steps"] if s["kind"] == "reading")["text"]
    assert "body 3 turns at 1.414 rad/s" in text and "slowing down" in text
    assert "body 1 turns at 1 rad/s about the axis u = (0, 0, 1) (nearest +E3)" in text
    assert_reading_follows_the_signs(seed_002())


def test_prismatic_reading() -> None:
    assert_reading_follows_the_signs(turntable_slider(1.3, 0.4, -0.7))


@pytest.mark.slow
@settings(max_examples=25, deadline=None)
@given(chains())
def test_random_chain_readings_follow_the_signs(doc: dict[str, Any]) -> None:
    assert_reading_follows_the_signs(doc)


def test_no_planar_method_is_faked() -> None:
    kinds = {s["kind"] for s in solver.solve(seed_002())["steps"]}
    assert "reading" in kinds
    assert not kinds & {"instant_centres", "graphical.velocity", "graphical.acceleration"}


@pytest.mark.slow
@pytest.mark.skipif(NODE is None, reason="node is not installed: KaTeX cannot run")
def test_spatial_solution_renders_in_katex() -> None:
    docs = [seed_002(), turntable_slider(1.3, 0.4, -0.7)]
    spatial = [json.loads(p.read_text()) for p in EXAMPLES.glob("*spatial*.json")]
    assert spatial
    docs += spatial
    latex = [s["latex"] for doc in docs for s in solver.solve(doc)["steps"] if s["latex"]]
    assert run_katex(latex) == []


def test_sliding_joint_origin_steps_hold() -> None:
    """A sliding joint whose origin is no named point gets its own steps: v_O = v_O' + omega x r
    + v_rel and the five terms of a_O with 2 omega x v_rel and a_rel; every check of every step
    holds and every sourced value is the analysis's. Mutation: a factor 2.5 for the 2 of the
    Coriolis term (solver.kinematics.spatial.sliding_terms) fails it."""
    doc = turntable_slider(1.3, 0.4, -0.7)
    doc["joints"][1]["origin"] = [1.0, 0.2, 0.0]
    solution = solve(parse_spatial_chain(doc))
    _check_solution(solution)
    kinds = {s.kind for s in solution.steps}
    assert {"spatial.origin.velocity", "spatial.origin.acceleration"} <= kinds


@pytest.mark.slow
@settings(max_examples=15, deadline=None)
@given(chains())
def test_random_chain_steps_hold(doc: dict[str, Any]) -> None:
    """Every check of every step of a random chain's solution holds (test_solve)."""
    _check_solution(solve(parse_spatial_chain(doc)))

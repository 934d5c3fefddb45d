"""Figures beside the steps: the mechanism to scale, the velocity and acceleration
polygons at their stated scales.

For every seed linkage and every preset, both methods: every figure is valid SVG (parsed by
xml.etree); every drawn vector (a ``<line data-vector=...>``) measured on the drawing, in cm
(one user unit = 1 mm) times the figure's stated scale, equals the vector computed here from the
/analyze body of the same scene (a point's velocity, v_Y - v_X, -omega^2 r_XY, alpha x r_XY, the
slot's transport / Coriolis / relative parts) to 0.1 % of its length; the scale printed in the
caption is the one used.
"""

from __future__ import annotations

import json
import re
import xml.etree.ElementTree as ET
from pathlib import Path
from typing import Any

import numpy as np
import pytest

from solver.analysis.results import analysis_body
from solver.model.scene import parse_linkage
from solver.solutions import Solution, solve
from solver.teaching.presets import PRESETS, build_preset

ROOT = Path(__file__).resolve().parents[3]
EXAMPLES = ROOT / "server" / "examples"
LINKAGES = sorted(
    p.stem for p in EXAMPLES.glob("*.json") if json.loads(p.read_text())["kind"] == "linkage"
)
SVG = "{http://www.w3.org/2000/svg}"
RTOL = 1e-3


def cases() -> list[tuple[str, dict[str, Any], str]]:
    out = []
    for method in ("vector", "loop"):
        out += [(n, json.loads((EXAMPLES / f"{n}.json").read_text()), method) for n in LINKAGES]
        out += [(n, build_preset(n, {}), method) for n in PRESETS]
    return out


CASES = cases()
IDS = [f"{n}-{m}" for n, _, m in CASES]


def perp(a: np.ndarray) -> np.ndarray:
    return np.array([-a[1], a[0]])


def expected_vector(name: str, body: dict[str, Any], doc: dict[str, Any]) -> np.ndarray:
    """The vector a figure's ``data-vector`` names, from the /analyze body."""

    def point(p: str, field: str) -> np.ndarray:
        if p in body["points"]:
            return np.array(body["points"][p][field], float)
        return np.array(body["moving_points"][p][field], float)

    def part(p: str, field: str) -> np.ndarray:
        for joint in body["joints"]:
            if joint["point"] == p:
                return np.array(joint[field], float)
        return np.array(body["moving_points"][p][field], float)

    if m := re.fullmatch(r"([va])\(([^()]+)\)-\1\(([^()]+)\)", name):
        field = "velocity" if m.group(1) == "v" else "acceleration"
        return point(m.group(2), field) - point(m.group(3), field)
    if m := re.fullmatch(r"(an|at)\((.+):(.+),(.+)\)", name):
        link, x, y = m.group(2), m.group(3), m.group(4)
        r = np.array(body["points"][y]["position"]) - np.array(body["points"][x]["position"])
        if m.group(1) == "an":
            return -(float(body["links"][link]["omega"]) ** 2) * r
        return float(body["links"][link]["alpha"]) * perp(r)
    if m := re.fullmatch(r"ic\((.+),(.+)\)-ic\((.+),(.+)\)", name):

        def centre(i: str, j: str) -> np.ndarray:
            found = next(c for c in body["instant_centres"] if set(c["links"]) == {i, j})
            return np.array(found["position"], float)

        return centre(m.group(1), m.group(2)) - centre(m.group(3), m.group(4))
    if m := re.fullmatch(r"r\((.+),(.+)\)", name):
        return point(m.group(2), "position") - point(m.group(1), "position")
    if m := re.fullmatch(r"([va])_(tr|rel|cor)\((.+)\)", name):
        what = {"tr": "transport", "rel": "relative", "cor": "coriolis"}[m.group(2)]
        field = f"{what}_{'velocity' if m.group(1) == 'v' else 'acceleration'}"
        return part(m.group(3), field)
    m = re.fullmatch(r"([va])\((.+)\)", name)
    assert m, name
    return point(m.group(2), "velocity" if m.group(1) == "v" else "acceleration")


def figures(solution: Solution) -> list[tuple[str, ET.Element]]:
    return [(s.kind, ET.fromstring(s.figure)) for s in solution.steps if s.figure]


@pytest.mark.parametrize(("name", "doc", "method"), CASES, ids=IDS)
def test_figures_are_svg_drawn_to_their_stated_scale(
    name: str, doc: dict[str, Any], method: str
) -> None:
    solution = solve(parse_linkage(doc), method)
    kinds = {s.kind for s in solution.steps}
    assert {"graphical.velocity", "graphical.acceleration"} <= kinds
    drawn = figures(solution)
    assert {k for k, _ in drawn} >= {
        "positions",
        "graphical.velocity",
        "graphical.acceleration",
        "instant_centres",
    }
    body = analysis_body(solution.analysis, [])
    measured = 0
    for kind, root in drawn:
        assert root.tag == f"{SVG}svg"
        scale = float(root.attrib["data-scale"])
        caption = "".join(root.itertext())
        assert f"1 cm = {scale:g} {root.attrib['data-unit']}" in caption, caption
        for line in root.iter(f"{SVG}line"):
            if "data-vector" not in line.attrib:
                continue
            x1, y1, x2, y2 = (float(line.attrib[a]) for a in ("x1", "y1", "x2", "y2"))
            drawn_vector = np.array([x2 - x1, -(y2 - y1)]) / 10.0 * scale  # mm -> cm -> units
            want = expected_vector(line.attrib["data-vector"], body, doc)
            size = float(np.linalg.norm(want))
            assert size > 0, (kind, line.attrib["data-vector"])
            assert np.linalg.norm(drawn_vector - want) <= RTOL * size, (
                name,
                kind,
                line.attrib["data-vector"],
                drawn_vector,
                want,
            )
            measured += 1
    assert measured >= 4


def test_a_wrongly_scaled_drawing_is_caught() -> None:
    """Mutation check: a polygon drawn at twice its stated scale fails the measurement."""
    solution = solve(parse_linkage(build_preset("four_bar", {})))
    step = next(s for s in solution.steps if s.kind == "graphical.velocity")
    root = ET.fromstring(step.figure)
    scale = 2 * float(root.attrib["data-scale"])
    body = analysis_body(solution.analysis, [])
    line = next(x for x in root.iter(f"{SVG}line") if "data-vector" in x.attrib)
    x1, y1, x2, y2 = (float(line.attrib[a]) for a in ("x1", "y1", "x2", "y2"))
    drawn_vector = np.array([x2 - x1, -(y2 - y1)]) / 10.0 * scale
    want = expected_vector(line.attrib["data-vector"], body, {})
    assert np.linalg.norm(drawn_vector - want) > RTOL * np.linalg.norm(want)


def test_polygon_labels_and_mehmke_on_a_coupler_point() -> None:
    """S001's coupler carries C: Mehmke's check says the image of C follows from B and the
    slider point; the acceleration polygon labels its normal and tangential parts."""
    solution = solve(
        parse_linkage(json.loads((EXAMPLES / "S001-offset-slider-crank.json").read_text()))
    )
    velocity = next(s for s in solution.steps if s.kind == "graphical.velocity")
    assert "Mehmke" in velocity.text and "1 cm = " in velocity.text
    acceleration = next(s for s in solution.steps if s.kind == "graphical.acceleration")
    names = [x.attrib.get("data-vector", "") for x in ET.fromstring(acceleration.figure).iter()]
    assert any(n.startswith("an(") for n in names) and any(n.startswith("at(") for n in names)


def test_user_names_are_escaped_in_figures() -> None:
    doc = build_preset("four_bar", {})
    doc = json.loads(json.dumps(doc).replace('"B"', '"B<&>"'))
    solution = solve(parse_linkage(doc))
    for _, root in figures(solution):
        assert root.tag == f"{SVG}svg"
    assert "B<&>" in "".join(ET.fromstring(solution.steps[1].figure).itertext())

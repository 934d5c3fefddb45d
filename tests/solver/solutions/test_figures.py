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

import itertools
import json
import math
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


# --- what the mechanism figure draws, and where its words go -----------------------------------

MECHANISMS = [(n, doc) for n, doc, m in CASES if m == "vector"]
MECHANISM_IDS = [n for n, _ in MECHANISMS]
EM_WIDTH, ASCENT, DESCENT = 0.6, 0.75, 0.2  # a text's box, in em: per character, above, below


def mechanism(solution: Solution) -> ET.Element:
    return next(root for kind, root in figures(solution) if kind == "positions")


def paper(root: ET.Element, p: list[float]) -> np.ndarray:
    """A model point (m) on the mechanism drawing (mm, y down) at its stated scale (m per cm)."""
    per_mm = float(root.attrib["data-scale"]) / 10.0
    return np.array([p[0] / per_mm, -p[1] / per_mm])


def corners(element: ET.Element) -> np.ndarray:
    return np.array([[float(v) for v in c.split(",")] for c in element.attrib["points"].split()])


def line_ends(element: ET.Element) -> tuple[np.ndarray, np.ndarray]:
    x1, y1, x2, y2 = (float(element.attrib[a]) for a in ("x1", "y1", "x2", "y2"))
    return np.array([x1, y1]), np.array([x2, y2])


def cross(a: np.ndarray, b: np.ndarray) -> float:
    return float(a[0] * b[1] - a[1] * b[0])


def parallel(a: np.ndarray, b: np.ndarray) -> bool:
    return abs(cross(a, b)) <= 1e-3 * np.linalg.norm(a) * np.linalg.norm(b)


@pytest.mark.parametrize(("name", "doc"), MECHANISMS, ids=MECHANISM_IDS)
def test_every_sliding_joint_is_drawn_as_a_block_between_the_rails_of_its_guide(
    name: str, doc: dict[str, Any]
) -> None:
    """For every slider and prismatic joint the mechanism figure has a four-cornered block
    centred on the joint's point (to 0.01 mm at the drawing's scale) and two rails of its guide
    parallel to the block's long side, one either side of it; the long side lies along the slot:
    along the scene's axis for a guide fixed in the ground, along the relative velocity where the
    point slides."""
    solution = solve(parse_linkage(doc))
    root = mechanism(solution)
    body = analysis_body(solution.analysis, [])
    sliding = [j for j in doc["joints"] if j["type"] != "revolute"]
    for joint, answer in zip(sliding, body["joints"], strict=True):
        point = joint["point"]
        (block,) = [e for e in root.iter(f"{SVG}polygon") if e.attrib.get("data-slider") == point]
        box = corners(block)
        assert box.shape == (4, 2)
        centre = paper(root, body["points"][point]["position"])
        assert np.linalg.norm(box.mean(axis=0) - centre) < 0.01, (name, point)
        long_side = box[1] - box[0]
        assert np.linalg.norm(long_side) > np.linalg.norm(box[2] - box[1])
        rails = [e for e in root.iter(f"{SVG}line") if e.attrib.get("data-guide") == point]
        assert len(rails) == 2, (name, point)
        sides = []
        for rail in rails:
            start, end = line_ends(rail)
            assert parallel(end - start, long_side), (name, point)
            offset = centre - start
            sides.append(np.sign(cross(long_side, offset)))
        assert sorted(sides) == [-1.0, 1.0]
        ground = next(k for k, v in doc["links"].items() if v.get("ground"))
        if joint["links"][0] == ground:
            assert parallel(np.array([joint["axis"][0], -joint["axis"][1]]), long_side)
        v_rel = np.array(answer["relative_velocity"], float)
        if np.linalg.norm(v_rel) > 1e-9:
            assert parallel(np.array([v_rel[0], -v_rel[1]]), long_side), (name, point)


def test_a_four_bar_has_no_slider_block() -> None:
    root = mechanism(solve(parse_linkage(build_preset("four_bar", {}))))
    assert not [e for e in root.iter() if "data-slider" in e.attrib or "data-guide" in e.attrib]


def arc_points(d: str) -> np.ndarray:
    """The end points of an SVG path made of M and A commands."""
    numbers = [float(x) for x in re.findall(r"-?\d+\.?\d*(?:e-?\d+)?", d)]
    out = [numbers[:2]]
    rest = numbers[2:]
    while rest:
        out.append(rest[5:7])
        rest = rest[7:]
    return np.array(out)


@pytest.mark.parametrize(
    ("name", "sweep_deg"),
    [("S003-T1-translating-carrier", 180.0), ("S003-T2-rotating-carrier", 360.0)],
)
def test_a_groove_is_drawn_in_its_disc_with_the_moving_point_on_it(
    name: str, sweep_deg: float
) -> None:
    """Seed 003: the carrier is a disc about the groove's centre, the groove an arc of radius R
    = |start - centre| from the start through the path's sweep (a semicircle in Task 1, the
    whole circle in Task 2), every end of its pieces at R from the centre, and M a labelled point
    at its /analyze position, on the groove."""
    doc = json.loads((EXAMPLES / f"{name}.json").read_text())
    solution = solve(parse_linkage(doc))
    root = mechanism(solution)
    body = analysis_body(solution.analysis, [])
    (mp,) = doc["moving_points"]
    centre = paper(root, body["points"][mp["path"]["center"]]["position"])
    start = paper(root, body["points"][mp["path"]["start"]]["position"])
    radius = float(np.linalg.norm(start - centre))
    (groove,) = [e for e in root.iter(f"{SVG}path") if e.attrib.get("data-groove") == "M"]
    ends = arc_points(groove.attrib["d"])
    assert np.linalg.norm(ends[0] - start) < 1e-3
    np.testing.assert_allclose(np.linalg.norm(ends - centre, axis=1), radius, rtol=1e-4)
    turned = math.degrees(
        sum(
            math.atan2(cross(a - centre, b - centre), float((a - centre) @ (b - centre)))
            for a, b in itertools.pairwise(ends)
        )
    )
    sense = 1.0 if mp["path"].get("direction", "ccw") == "ccw" else -1.0
    assert turned == pytest.approx(-sense * sweep_deg, abs=1e-6)  # y down: ccw turns negative
    (disc,) = [e for e in root.iter(f"{SVG}circle") if e.attrib.get("class") == "disc"]
    disc_centre = np.array([float(disc.attrib["cx"]), float(disc.attrib["cy"])])
    assert np.linalg.norm(disc_centre - centre) < 1e-3
    assert float(disc.attrib["r"]) > radius
    m = paper(root, body["moving_points"]["M"]["position"])
    assert abs(float(np.linalg.norm(m - centre)) - radius) < 1e-3
    dots = [
        np.array([float(c.attrib["cx"]), float(c.attrib["cy"])])
        for c in root.iter(f"{SVG}circle")
        if c.attrib.get("class") != "disc"
    ]
    assert min(float(np.linalg.norm(d - m)) for d in dots) < 0.01
    assert "M" in [t.text for t in root.iter(f"{SVG}text")]


def text_boxes(root: ET.Element) -> list[tuple[str, tuple[float, float, float, float]]]:
    """(text, (left, top, right, bottom)) of every <text>, estimated from its font size and its
    number of characters: EM_WIDTH em a character, ASCENT em above the baseline, DESCENT below."""
    out = []
    for t in root.iter(f"{SVG}text"):
        size = float(t.attrib["font-size"])
        width = EM_WIDTH * size * len(t.text or "")
        x, y = float(t.attrib["x"]), float(t.attrib["y"])
        left = (
            x
            - {"start": 0.0, "middle": width / 2, "end": width}[
                t.attrib.get("text-anchor", "start")
            ]
        )
        out.append((t.text or "", (left, y - ASCENT * size, left + width, y + DESCENT * size)))
    return out


@pytest.mark.parametrize(("name", "doc", "method"), CASES, ids=IDS)
def test_no_two_words_overlap_and_none_is_cut_off(
    name: str, doc: dict[str, Any], method: str
) -> None:
    """Every figure of every seed and preset: no two texts' boxes share an area (the polygon's
    'n BΓ' and 'n DΓ' of seed 004 included), and every text's box lies within the view box
    (the caption 'Acceleration polygon, 1 cm = 20 m/s^2; n normal, ...' included)."""
    for kind, root in figures(solve(parse_linkage(doc), method)):
        x0, y0, width, height = (float(v) for v in root.attrib["viewBox"].split())
        boxes = text_boxes(root)
        for i, (text, (left, top, right, bottom)) in enumerate(boxes):
            assert x0 <= left and right <= x0 + width, (name, kind, text)
            assert y0 <= top and bottom <= y0 + height, (name, kind, text)
            for other, (l2, t2, r2, b2) in boxes[i + 1 :]:
                apart = right <= l2 or r2 <= left or bottom <= t2 or b2 <= top
                assert apart, (name, kind, text, other)


def test_a_point_named_after_a_greek_letter_is_drawn_as_the_letter() -> None:
    """Seed 004's pivot Gamma: 'Γ' on the mechanism, 'n BΓ' and 'n DΓ' on the acceleration
    polygon, never the spelled-out name."""
    solution = solve(parse_linkage(build_preset("seed004", {})))
    texts = {kind: [t.text for t in root.iter(f"{SVG}text")] for kind, root in figures(solution)}
    assert "Γ" in texts["positions"]
    assert {"n BΓ", "n DΓ"} <= set(texts["graphical.acceleration"])
    assert not any("Gamma" in (t or "") for words in texts.values() for t in words)


def test_an_image_too_short_to_draw_has_no_length_to_read() -> None:
    """A slider-crank at rest with a subnormal alpha (2.2e-311 rad/s^2): its acceleration images
    are 1e-311 cm long, not drawn, so the polygon's step lists no length and no reading error
    for them (which would be 0.05 cm / 1e-311 cm = inf) and the solution is built."""
    values = {"crank": 1.0, "rod": 1.0, "offset": 0.0, "crank_angle_deg": 0.0}
    doc = build_preset("slider_crank", {**values, "omega": 0.0, "alpha": 2.225073858507e-311})
    solution = solve(parse_linkage(doc))
    step = next(s for s in solution.steps if s.kind == "graphical.acceleration")
    assert "relative error" not in step.values
    assert not [k for k in step.values if k.startswith("length ")]
    assert not [e for e in ET.fromstring(step.figure).iter() if "data-vector" in e.attrib]


BARS = {"link": 1.4, "guide": 0.5}  # mm: the stroke width of a link's bar and a guide's rail
IMPOSSIBLE = 0  # labels hemmed in by bars (see the test below)


def bar_crossings(root: ET.Element) -> list[tuple[str, str]]:
    """(text, class) of every <text> whose box (``text_boxes``) comes nearer than half a bar's
    width to a drawn bar or rail: the segment sampled every 0.02 mm, each sample's distance to
    the box measured."""
    bars = [
        (line.attrib["class"], *line_ends(line))
        for line in root.iter(f"{SVG}line")
        if line.attrib.get("class") in BARS
    ]
    out = []
    for text, (left, top, right, bottom) in text_boxes(root):
        for kind, a, b in bars:
            samples = np.linspace(0.0, 1.0, max(2, int(np.linalg.norm(b - a) / 0.02) + 2))
            at = a[None, :] + samples[:, None] * (b - a)[None, :]
            dx = np.maximum(np.maximum(left - at[:, 0], at[:, 0] - right), 0.0)
            dy = np.maximum(np.maximum(top - at[:, 1], at[:, 1] - bottom), 0.0)
            if np.min(np.hypot(dx, dy)) < BARS[kind] / 2 - 1e-6:
                out.append((text, kind))
    return out


def test_no_label_sits_on_a_bar_or_a_rail() -> None:
    """Every figure of every seed and preset, both methods: no label's box crosses a link's bar
    or a guide's rail where a free place exists within the search radius. The places left are
    counted: a label hemmed in by bars on every side within SEARCH_RINGS rings of its first
    place keeps the old rule (off the other labels only); at most IMPOSSIBLE of them (none in
    these figures: 72 of their 932 labels sat on a bar before the rule)."""
    found = []
    labels = 0
    for name, doc, method in CASES:
        for kind, root in figures(solve(parse_linkage(doc), method)):
            labels += sum(1 for _ in root.iter(f"{SVG}text"))
            found += [(name, method, kind, *c) for c in bar_crossings(root)]
    assert len(found) <= IMPOSSIBLE, (f"{len(found)} of {labels} labels on a bar", found)


def test_the_bar_check_can_fail() -> None:
    """A label set on a bar's middle is found; one set 2 mm beside it is not."""
    root = ET.fromstring(
        f'<svg xmlns="{SVG[1:-1]}"><line class="link" x1="0" y1="0" x2="10" y2="0"/>'
        '<text x="4" y="1" font-size="3">B</text><text x="4" y="-3" font-size="3">C</text></svg>'
    )
    assert bar_crossings(root) == [("B", "link")]

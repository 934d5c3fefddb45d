"""One SVG canvas: the map from the model (y up) to the drawing (y down), escaped elements, and
standalone documents that parse as XML, for the solution figures, the free-body diagrams and the
exercise figures alike. Source: the SVG 1.1 document structure; properties of an affine map.
"""

from __future__ import annotations

import math
import xml.etree.ElementTree as ET

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from solver.exercises import ExerciseId, build
from solver.exercises.figures import figure_svg
from solver.solutions.figures import Arrow, Dot, svg, wrap
from solver.solutions.free_body import Arrow as Force
from solver.solutions.free_body import Couple
from solver.solutions.free_body import svg as free_body_svg
from solver.teaching.svg import (
    CHAR_WIDTH,
    RING,
    SEARCH_RINGS,
    Box,
    Canvas,
    View,
    element,
    text_box,
)

SVG = "{http://www.w3.org/2000/svg}"
coordinate = st.floats(-1e3, 1e3, allow_nan=False)
points = st.lists(st.tuples(coordinate, coordinate), min_size=2, max_size=8)


def test_paper_view_divides_by_the_scale_and_turns_y_down() -> None:
    """(x, y) -> (x / per, -y / per) exactly, a zero keeping the sign the division gives."""
    view = View.paper(0.002)
    for x, y in [(0.3, 0.7), (-1.1, 0.0), (0.0, -2.5), (1e-9, 3.0)]:
        assert view.px((x, y)) == (x / 0.002, -y / 0.002)
    assert math.copysign(1.0, view.px((0.0, 0.0))[1]) == -1.0


@given(points)
def test_a_fitted_view_keeps_the_points_inside_the_margin_and_centred(xy: list) -> None:  # type: ignore[type-arg]
    """Every point lands within the margin of a 420 x 300 drawing, the box centred on the axis
    it does not fill."""
    view = View.fit(xy, 420.0, 300.0, 48.0)
    drawn = [view.px(p) for p in xy]
    xs, ys = [p[0] for p in drawn], [p[1] for p in drawn]
    tol = 1e-6
    assert min(xs) >= 48.0 - tol and max(xs) <= 372.0 + tol
    assert min(ys) >= 48.0 - tol and max(ys) <= 252.0 + tol
    assert (min(xs) + max(xs)) / 2 == pytest.approx(210.0, abs=1e-6)
    assert (min(ys) + max(ys)) / 2 == pytest.approx(150.0, abs=1e-6)


@given(points)
def test_a_centred_view_puts_the_box_centre_in_the_middle(xy: list) -> None:  # type: ignore[type-arg]
    view = View.centred(xy, 320.0, 70.0)
    drawn = [view.px(p) for p in xy]
    xs, ys = [p[0] for p in drawn], [p[1] for p in drawn]
    assert (min(xs) + max(xs)) / 2 == pytest.approx(160.0, abs=1e-6)
    assert (min(ys) + max(ys)) / 2 == pytest.approx(160.0, abs=1e-6)
    assert max(max(xs) - min(xs), max(ys) - min(ys)) <= 180.0 + 1e-6


def test_y_points_down_on_paper() -> None:
    view = View.fit([(0.0, 0.0), (1.0, 1.0)], 420.0, 300.0, 48.0)
    assert view.px((0.0, 1.0))[1] < view.px((0.0, 0.0))[1]


def test_labels_and_attributes_are_escaped() -> None:
    assert element("text", [("x", "1.0")], "a<b & c'") == '<text x="1.0">a&lt;b &amp; c\'</text>'
    assert element("line", [("data-vector", 'v"<')]) == '<line data-vector="v&quot;&lt;"/>'
    canvas = Canvas(View.paper(1.0))
    canvas.text((1.0, 2.0), "</svg>", [("fill", "#000")], digits=2)
    doc = canvas.document([("role", "img"), ("aria-label", 'say "hi" & go')], ["<title>t</title>"])
    root = ET.fromstring(doc)
    assert root.get("aria-label") == 'say "hi" & go'
    assert root.find(f"{SVG}text") is not None and root.find(f"{SVG}text").text == "</svg>"  # type: ignore[union-attr]


NASTY = "A&<\"'>"


def _parses(document: str) -> ET.Element:
    root = ET.fromstring(document)
    assert root.tag == f"{SVG}svg"
    return root


def test_a_solution_figure_is_standalone_xml_with_its_labels() -> None:
    arrow = Arrow(np.zeros(2), np.array([0.05, 0.02]), f"v({NASTY})", NASTY, "absolute")
    root = _parses(
        svg(NASTY, [arrow], [Dot(np.zeros(2), NASTY, True)], [], 0.002, NASTY, {"data-x": NASTY})
    )
    assert root.get("data-x") == NASTY
    assert root.find(f"{SVG}title").text == NASTY  # type: ignore[union-attr]
    (line,) = root.iter(f"{SVG}line")
    assert line.get("data-vector") == f"v({NASTY})"
    assert float(line.get("x2")) == pytest.approx(25.0)  # type: ignore[arg-type]
    assert {t.text for t in root.iter(f"{SVG}text")} == {NASTY}


def test_a_free_body_diagram_is_standalone_xml_with_its_labels() -> None:
    root = _parses(
        free_body_svg(
            NASTY,
            {NASTY: (0.0, 0.0), "B": (1.0, 0.0)},
            (0.5, 0.0),
            [Force(NASTY, "joint", (0.0, 0.0), (3.0, 4.0))],
            [Couple(NASTY, "load", -2.0)],
        )
    )
    assert root.get("aria-label") == f"free-body diagram of {NASTY}"
    texts = [t.text for t in root.iter(f"{SVG}text")]
    assert texts.count(NASTY) == 3 and "G" in texts


def test_an_exercise_figure_is_standalone_xml_with_its_title() -> None:
    e = build(ExerciseId("quick_return", "standard", 4, 0))
    scene = {**e.scene, "title": NASTY}
    root = _parses(figure_svg(scene))
    assert root.get("aria-label") == NASTY
    assert root.find(f"{SVG}title").text == NASTY  # type: ignore[union-attr]
    spatial = build(ExerciseId("spatial_arm", "basic", 4, 0))
    assert _parses(figure_svg(spatial.scene)).get("width") == "420"


@given(st.lists(st.tuples(coordinate, coordinate), min_size=1, max_size=12), st.integers(1, 9))
def test_labels_placed_on_one_canvas_never_overlap(places: list, length: int) -> None:  # type: ignore[type-arg]
    """Labels asked for at any places, the same place many times included: the boxes
    ``Canvas.label`` keeps (``text_box`` of the place it chose) share no area, and each is where
    its <text> is written."""
    canvas = Canvas(View.paper(1.0))
    for x, y in places + places[:1] * 3:
        canvas.label([((x, y), "start"), ((x, y), "end")], "W" * length, 3.0, [])
    boxes = canvas.labels
    for i, a in enumerate(boxes):
        assert not any(a.overlaps(b) for b in boxes[i + 1 :])
    texts = ET.fromstring(canvas.document([])).iter(f"{SVG}text")
    for box, t in zip(boxes, texts, strict=True):
        at = (float(t.attrib["x"]), float(t.attrib["y"]))
        expected = text_box(at, t.text or "", 3.0, t.attrib["text-anchor"])
        assert expected.left == pytest.approx(box.left, abs=0.01)
        assert expected.top == pytest.approx(box.top, abs=0.01)


def test_a_text_box_grows_with_its_characters_and_font() -> None:
    """width = CHAR_WIDTH size n; the anchor puts the box after, about or before the point."""
    start = text_box((10.0, 20.0), "abcd", 3.0, "start")
    assert start.right - start.left == pytest.approx(CHAR_WIDTH * 3.0 * 4)
    assert start.left == 10.0 and start.top < 20.0 < start.bottom
    middle = text_box((10.0, 20.0), "abcd", 3.0, "middle")
    assert (middle.left + middle.right) / 2 == pytest.approx(10.0)
    assert text_box((10.0, 20.0), "abcd", 3.0, "end").right == pytest.approx(10.0)
    assert not start.overlaps(text_box((start.right, 20.0), "x", 3.0))  # touching is apart


def test_a_long_caption_is_wrapped_after_its_commas_within_a_narrow_drawing() -> None:
    """A caption longer than its drawing is broken after its commas and semicolons (the scale
    kept whole) and every line lies inside the view box."""
    caption = "Acceleration polygon, 1 cm = 20 m/s^2; n normal, t tangential, tr transport"
    root = ET.fromstring(
        svg("t", [], [Dot(np.zeros(2), "A")], [], 1.0, caption, {"data-scale": "1"})
    )
    x0, _, width, _ = (float(v) for v in root.attrib["viewBox"].split())
    lines = [t.text or "" for t in root.iter(f"{SVG}text")][1:]
    assert len(lines) > 1 and " ".join(lines) == caption
    assert "1 cm = 20 m/s^2;" in lines
    for t in list(root.iter(f"{SVG}text"))[1:]:
        box = text_box((float(t.attrib["x"]), float(t.attrib["y"])), t.text or "", 3.4)
        assert x0 <= box.left and box.right <= x0 + width
    assert wrap("a, b", 1e9, 3.0) == ["a, b"]


def _near_bar(box: Box, y: float, half: float) -> bool:
    """The box comes within ``half`` of the horizontal bar y = ``y``, x in [-50, 50]."""
    return box.top - half < y < box.bottom + half and box.left < 50 and box.right > -50


def test_a_label_moves_off_a_bar_within_its_search_radius() -> None:
    """A label asked for on a bar (its first and only candidate across the bar) is set beside
    it, within SEARCH_RINGS rings of RING; with bars every 1 mm around it (no free place within
    the radius) it keeps its first place, off the other labels only."""
    canvas = Canvas(View.paper(1.0))
    canvas.keep_off((-50.0, 0.0), (50.0, 0.0), 1.4)
    box = canvas.label([((0.0, 1.0), "middle")], "B", 3.0, [])
    assert not _near_bar(box, 0.0, 0.7)
    assert math.hypot((box.left + box.right) / 2, box.bottom - 3.0 * 0.25 - 1.0) <= (
        SEARCH_RINGS * RING + 1e-9
    )
    hemmed = Canvas(View.paper(1.0))
    for k in range(-30, 31):
        hemmed.keep_off((-50.0, float(k)), (50.0, float(k)), 0.5)
    assert hemmed.label([((0.0, 1.0), "middle")], "B", 3.0, []) == text_box(
        (0.0, 1.0), "B", 3.0, "middle"
    )

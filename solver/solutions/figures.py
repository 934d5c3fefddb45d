"""Figures of a worked solution as standalone SVG: the mechanism to scale, the velocity and the
acceleration polygon at a stated scale.

Lengths are drawn in millimetres of paper (``width="...mm"``, one user unit = 1 mm), so a polygon
drawn at "1 cm = k m/s" has a segment of |v| / k cm = 10 |v| / k user units. Every drawn vector is
a ``<line>`` with ``data-vector`` naming what it is ("v(B)", "v(C)-v(B)", "an(B,C)", "at(B,C)",
"a_cor(C)"...) so that a program can measure it; the kinds are told apart by dash patterns as well
as colours, so that the figures print in black and white. Labels come from the user's scene and
are escaped.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from solver.teaching.svg import Canvas, View, element, marker

PAPER = 110.0  # mm: the larger side of a drawing
MARGIN = 12.0  # mm around it
SHORTEST = 0.01  # mm: a shorter vector is not drawn
NICE = (1.0, 2.0, 2.5, 5.0)
STYLE = {  # class: (colour, dash pattern)
    "absolute": ("#1f4e9c", ""),
    "relative": ("#b5471b", "5 2"),
    "normal": ("#2e7d32", "2 2"),
    "tangential": ("#6a1b9a", "6 2 1 2"),
    "coriolis": ("#8d6e00", "1 1.5"),
    "transport": ("#00838f", "4 1.5 1 1.5 1 1.5"),
    "position": ("#555555", "3 2"),
}


def nice_scale(largest: float, paper_cm: float) -> float:
    """A round scale k (units per cm: 1, 2, 2.5 or 5 times a power of ten) that draws
    ``largest`` in at most ``paper_cm`` centimetres; 1 where there is nothing to draw (0, or
    below 1e-290, which no round scale could hold without underflow: drawn as a point, as at
    rest)."""
    raw = largest / paper_cm
    if not raw >= 1e-290:
        return 1.0
    power = 10.0 ** math.floor(math.log10(raw))
    for step in (*NICE, 10.0):
        if step * power >= raw * (1 - 1e-12):
            return step * power
    return 10.0 * power  # pragma: no cover - the loop always returns


def scale_text(k: float, unit: str) -> str:
    return f"1 cm = {k:g} {unit}"


@dataclass(frozen=True)
class Arrow:
    """A drawn vector from ``start`` to ``end`` (in the figure's own units), with its name."""

    start: np.ndarray
    end: np.ndarray
    name: str
    label: str
    style: str


@dataclass(frozen=True)
class Dot:
    at: np.ndarray
    label: str
    fixed: bool = False


_MARKER = (
    ("viewBox", "0 0 6 6"),
    ("refX", "5.5"),
    ("refY", "3"),
    ("markerWidth", "5"),
    ("markerHeight", "5"),
    ("orient", "auto-start-reverse"),
)


def _defs() -> str:
    """An arrowhead in each style's colour, ``head-<style>``."""
    markers = "".join(
        marker([("id", f"head-{name}"), *_MARKER], [("d", "M0,0 L6,3 L0,6 z"), ("fill", colour)])
        for name, (colour, _) in STYLE.items()
    )
    return f"<defs>{markers}</defs>"


def svg(
    title: str,
    arrows: Sequence[Arrow],
    dots: Sequence[Dot],
    segments: Sequence[tuple[np.ndarray, np.ndarray, str]],
    per_mm: float,
    caption: str,
    extra: dict[str, str],
) -> str:
    """An SVG drawing: model coordinates (y up) times ``1 / per_mm`` give millimetres; ``extra``
    attributes of the drawing's root."""
    canvas = Canvas(View.paper(per_mm))
    points = [a.start for a in arrows] + [a.end for a in arrows] + [d.at for d in dots]
    points += [p for s in segments for p in s[:2]]
    x0, y0, width, height = _frame(points or [np.zeros(2)], canvas.view)
    for a, b, style in segments:
        _segment(canvas, canvas.px(a), canvas.px(b), style)
    for arrow in arrows:
        _arrow(canvas, arrow)
    for dot in dots:
        _dot(canvas, dot)
    return paper_document(canvas, (x0, y0, width, height), title, caption, extra, [_defs()])


def paper_document(
    canvas: Canvas,
    box: tuple[float, float, float, float],
    title: str,
    caption: str,
    extra: dict[str, str],
    head: Sequence[str] = (),
) -> str:
    """The drawing as a standalone SVG in millimetres of paper: the view box (x0, y0, width,
    height), its ``title``, the ``caption`` along its foot, ``extra`` root attributes."""
    x0, y0, width, height = box
    canvas.text((x0 + 2, y0 + height - 2.5), caption, [*_LABEL, ("fill", "#000000")], digits=2)
    return canvas.document(
        [
            ("role", "img"),
            ("width", f"{width:.1f}mm"),
            ("height", f"{height:.1f}mm"),
            ("viewBox", f"{x0:.3f} {y0:.3f} {width:.3f} {height:.3f}"),
            ("font-family", "sans-serif"),
            *extra.items(),
        ],
        [*head, element("title", [], title)],
    )


_LABEL = (("font-size", "3.4"),)


def _frame(points: Sequence[np.ndarray], view: View) -> tuple[float, float, float, float]:
    """The view box (x0, y0, width, height) in mm: the points with a margin, and room for the
    caption below."""
    paper = [view.px(p) for p in points]
    xs, ys = [p[0] for p in paper], [p[1] for p in paper]
    x0, y0 = min(xs) - MARGIN, min(ys) - MARGIN
    return x0, y0, max(xs) - min(xs) + 2 * MARGIN, max(ys) - min(ys) + 2 * MARGIN + 8.0


def _segment(
    canvas: Canvas, start: tuple[float, float], end: tuple[float, float], style: str
) -> None:
    """A line of the drawing: a link as a thick bar, anything else in its style's colour."""
    colour, dash = STYLE.get(style, ("#000000", ""))
    link = style == "link"
    stroke = [
        ("stroke", "#222222" if link else colour),
        ("stroke-width", "1.4" if link else "0.35"),
        ("stroke-linecap", "round"),
    ]
    if dash and not link:
        stroke.append(("stroke-dasharray", dash))
    canvas.line(start, end, stroke, lead=[("class", style)], digits=4)


def _arrow(canvas: Canvas, arrow: Arrow) -> None:
    """A vector as a line with an arrowhead and ``data-vector``, its label beside its middle
    (2.5 mm along the normal); nothing for a vector shorter than ``SHORTEST``."""
    (x1, y1), (x2, y2) = canvas.px(arrow.start), canvas.px(arrow.end)
    if math.hypot(x2 - x1, y2 - y1) < SHORTEST:
        return  # a vector at the rounding level, or shorter than a pen can draw
    colour, dash = STYLE[arrow.style]
    stroke = [
        ("stroke", colour),
        ("stroke-width", "0.45"),
        ("marker-end", f"url(#head-{arrow.style})"),
    ]
    if dash:
        stroke.append(("stroke-dasharray", dash))
    lead = [("class", arrow.style), ("data-vector", arrow.name)]
    canvas.line((x1, y1), (x2, y2), stroke, lead=lead, digits=6)
    if arrow.label:
        mx, my = (x1 + x2) / 2, (y1 + y2) / 2
        length = math.hypot(x2 - x1, y2 - y1) or 1.0
        nx, ny = -(y2 - y1) / length * 2.5, (x2 - x1) / length * 2.5
        style = [("font-size", "3"), ("fill", colour), ("text-anchor", "middle")]
        canvas.text((mx + nx, my + ny), arrow.label, style, digits=2)


def _dot(canvas: Canvas, dot: Dot) -> None:
    """A point as a small circle with its label (and a ground hatch under a fixed one)."""
    x, y = canvas.px(dot.at)
    ink = ("stroke", "#000000")
    canvas.circle((x, y), "0.9", [("fill", "#ffffff"), ink, ("stroke-width", "0.35")], digits=4)
    if dot.fixed:
        canvas.path(
            f"M{x - 2.5:.2f},{y + 3:.2f} L{x:.2f},{y + 0.9:.2f} L{x + 2.5:.2f},{y + 3:.2f} z",
            [("fill", "none"), ink, ("stroke-width", "0.3")],
        )
    canvas.text((x + 1.6, y - 1.6), dot.label, [*_LABEL, ("fill", "#000000")], digits=2)


def model_scale(points: Sequence[np.ndarray]) -> float:
    """Metres per millimetre of paper for a mechanism drawing (a round scale)."""
    extent = max(
        (float(np.max(np.abs(p - q))) for p in points for q in points),
        default=1.0,
    )
    return nice_scale(extent, PAPER / 10.0) / 10.0


def polygon_scale(vectors: Sequence[np.ndarray]) -> float:
    """Units per cm for a polygon whose largest vector takes at most 8 cm."""
    largest = max((float(np.hypot(*v)) for v in vectors), default=0.0)
    return nice_scale(largest, 8.0)

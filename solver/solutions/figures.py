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
import re
import unicodedata
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from solver.solutions.latex import greek
from solver.teaching.svg import Box, Canvas, Point, View, element, marker, text_box

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


@dataclass(frozen=True)
class Slider:
    """A sliding joint's block at ``at`` between the two rails of its guide (unit direction
    ``axis`` now), the rails hatched where the guide is the ground (``fixed``); ``name`` is the
    joint's point."""

    name: str
    at: np.ndarray
    axis: np.ndarray
    fixed: bool


@dataclass(frozen=True)
class Groove:
    """The path of a moving point ``name`` in its carrier: an arc about ``centre`` of ``radius``
    from the angle ``start`` (rad) through ``sweep`` (rad, counter-clockwise positive), or, with
    no centre, the line from ``start_point`` to ``end_point``; ``disc`` is the radius of the
    carrier drawn as a disc about the centre (0: no disc)."""

    name: str
    centre: np.ndarray | None
    radius: float
    start: float
    sweep: float
    start_point: np.ndarray
    end_point: np.ndarray
    disc: float = 0.0


BLOCK = (8.0, 5.0)  # mm: a slider block's length along its guide and its width
RAIL = 14.0  # mm: a guide's rails reach this far either side of its block's centre
HATCH = 2.5  # mm: between the strokes of a fixed guide's hatching


def figure_name(name: str) -> str:
    """A point's name as a figure writes it: a Greek letter spelled out ('Gamma', 'omega1') as
    the letter (Γ, ω1), as the steps' LaTeX sets it."""
    found = greek(name)
    if found is None:
        return name
    case = "CAPITAL" if found[0][0].isupper() else "SMALL"
    letter = {"lambda": "lamda"}.get(found[0].lower(), found[0].lower())  # Unicode's spelling
    return unicodedata.lookup(f"GREEK {case} LETTER {letter.upper()}") + found[1]


def svg(
    title: str,
    arrows: Sequence[Arrow],
    dots: Sequence[Dot],
    segments: Sequence[tuple[np.ndarray, np.ndarray, str]],
    per_mm: float,
    caption: str,
    extra: dict[str, str],
    sliders: Sequence[Slider] = (),
    grooves: Sequence[Groove] = (),
) -> str:
    """An SVG drawing: model coordinates (y up) times ``1 / per_mm`` give millimetres; ``extra``
    attributes of the drawing's root. Under the links: each groove's carrier disc and the groove,
    each guide's rails; over them each slider's block, then the vectors, the points and the
    labels (placed so that no two overlap: the points' first, then the vectors')."""
    canvas = Canvas(View.paper(per_mm))
    points = [a.start for a in arrows] + [a.end for a in arrows] + [d.at for d in dots]
    points += [p for s in segments for p in s[:2]]
    paper = [canvas.px(p) for p in points]
    for groove in grooves:
        paper += _groove(canvas, groove)
    for slider in sliders:
        paper += _rails(canvas, slider)
    for a, b, style in segments:
        _segment(canvas, canvas.px(a), canvas.px(b), style)
    for slider in sliders:
        _block(canvas, slider)
    labels = [_arrow(canvas, arrow) for arrow in arrows]
    for dot in dots:
        _dot(canvas, dot)
    for arrow, candidates in zip(arrows, labels, strict=True):
        if candidates:
            fill = [("fill", STYLE[arrow.style][0])]
            canvas.label(candidates, arrow.label, ARROW_FONT, fill, digits=2)
    box = _frame(paper or [(0.0, 0.0)], canvas.labels)
    return paper_document(canvas, box, title, caption, extra, [_defs()])


def paper_document(
    canvas: Canvas,
    box: tuple[float, float, float, float],
    title: str,
    caption: str,
    extra: dict[str, str],
    head: Sequence[str] = (),
) -> str:
    """The drawing as a standalone SVG in millimetres of paper: the view box (x0, y0, width,
    height), its ``title``, the ``caption`` along its foot, ``extra`` root attributes.

    The caption is wrapped after its commas and semicolons into lines that fit the width
    (estimated as the labels' boxes are, ``text_box``); the view box grows by a line for each
    line after the first, and widens for a part longer than the width, so nothing is
    clipped."""
    x0, y0, width, height = box
    lines = wrap(caption, width - 4.0, CAPTION_FONT)
    widest = max(text_box((0.0, 0.0), line, CAPTION_FONT).right for line in lines)
    width = max(width, widest + 4.0)
    height += LEADING * (len(lines) - 1)
    for i, line in enumerate(lines):
        at = (x0 + 2, y0 + height - 2.5 - LEADING * (len(lines) - 1 - i))
        canvas.text(at, line, [*_LABEL, ("fill", "#000000")], digits=2)
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


def wrap(text: str, width: float, size: float) -> list[str]:
    """``text`` broken after its commas and semicolons (a scale, "1 cm = 0.2 m/s", stays whole)
    into lines whose estimated width (``text_box``) is at most ``width`` in a font of ``size``; a
    part longer than that stands on a line of its own."""
    lines: list[str] = []
    for word in re.split(r"(?<=[,;]) ", text):
        longer = f"{lines[-1]} {word}" if lines else word
        if lines and text_box((0.0, 0.0), longer, size).right <= width:
            lines[-1] = longer
        else:
            lines.append(word)
    return lines


CAPTION_FONT = 3.4  # mm
BAR_WIDTH = 1.4  # mm: a link's bar
RAIL_WIDTH = 0.5  # mm: a guide's rail
ARROW_FONT = 3.0  # mm
LEADING = 4.4  # mm between the caption's lines
_LABEL = (("font-size", f"{CAPTION_FONT:g}"),)


def _frame(paper: Sequence[Point], labels: Sequence[Box]) -> tuple[float, float, float, float]:
    """The view box (x0, y0, width, height) in mm: the drawn points with a margin, every label's
    box within it, and room for the caption below."""
    xs, ys = [p[0] for p in paper], [p[1] for p in paper]
    x0 = min([min(xs) - MARGIN] + [b.left - 1.0 for b in labels])
    y0 = min([min(ys) - MARGIN] + [b.top - 1.0 for b in labels])
    x1 = max([max(xs) + MARGIN] + [b.right + 1.0 for b in labels])
    y1 = max([max(ys) + MARGIN] + [b.bottom + 1.0 for b in labels])
    return x0, y0, x1 - x0, y1 - y0 + 8.0


def _segment(
    canvas: Canvas, start: tuple[float, float], end: tuple[float, float], style: str
) -> None:
    """A line of the drawing: a link as a thick bar, anything else in its style's colour."""
    colour, dash = STYLE.get(style, ("#000000", ""))
    link = style == "link"
    stroke = [
        ("stroke", "#222222" if link else colour),
        ("stroke-width", f"{BAR_WIDTH:g}" if link else "0.35"),
        ("stroke-linecap", "round"),
    ]
    if dash and not link:
        stroke.append(("stroke-dasharray", dash))
    canvas.line(start, end, stroke, lead=[("class", style)], digits=4)
    if link:
        canvas.keep_off(start, end, BAR_WIDTH)


def _arrow(canvas: Canvas, arrow: Arrow) -> list[tuple[Point, str]]:
    """A vector as a line with an arrowhead and ``data-vector``; nothing for a vector shorter
    than ``SHORTEST``. The places for its label: beside its middle (2.5 mm along the normal),
    on the other side, then beside a third and two thirds of it (none without a label)."""
    (x1, y1), (x2, y2) = canvas.px(arrow.start), canvas.px(arrow.end)
    if math.hypot(x2 - x1, y2 - y1) < SHORTEST:
        return []  # a vector at the rounding level, or shorter than a pen can draw
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
    if not arrow.label:
        return []
    length = math.hypot(x2 - x1, y2 - y1) or 1.0
    nx, ny = -(y2 - y1) / length * 2.5, (x2 - x1) / length * 2.5
    places = []
    for t in (0.5, 1 / 3, 2 / 3):
        mx, my = x1 + t * (x2 - x1), y1 + t * (y2 - y1)
        places += [((mx + nx, my + ny), "middle"), ((mx - nx, my - ny + 2.0), "middle")]
    return places


def _dot(canvas: Canvas, dot: Dot) -> None:
    """A point as a small circle with its label (and a ground hatch under a fixed one): the
    label above and right of it, else above left, below right, below left."""
    x, y = canvas.px(dot.at)
    ink = ("stroke", "#000000")
    canvas.circle((x, y), "0.9", [("fill", "#ffffff"), ink, ("stroke-width", "0.35")], digits=4)
    if dot.fixed:
        canvas.path(
            f"M{x - 2.5:.2f},{y + 3:.2f} L{x:.2f},{y + 0.9:.2f} L{x + 2.5:.2f},{y + 3:.2f} z",
            [("fill", "none"), ink, ("stroke-width", "0.3")],
        )
    label = figure_name(dot.label)
    places = [
        ((x + 1.6, y - 1.6), "start"),
        ((x - 1.6, y - 1.6), "end"),
        ((x + 1.6, y + 4.4), "start"),
        ((x - 1.6, y + 4.4), "end"),
    ]
    canvas.label(places, label, CAPTION_FONT, [("fill", "#000000")], digits=2)


def _rails(canvas: Canvas, slider: Slider) -> list[Point]:
    """The guide of a slider: two rails along its axis either side of the block, reaching RAIL
    either way from its centre (``<line class="guide" data-guide=...>``), hatched on their outer
    sides for a fixed guide. The drawn corners, for the frame."""
    x, y = canvas.px(slider.at)
    u = np.array([slider.axis[0], -slider.axis[1]])  # y down
    n = np.array([-u[1], u[0]])
    corners: list[Point] = []
    ink = [("stroke", "#222222"), ("stroke-width", f"{RAIL_WIDTH:g}")]
    for side in (1.0, -1.0):
        offset = n * side * (BLOCK[1] / 2 + 0.3)
        a = np.array([x, y]) + offset - RAIL * u
        b = np.array([x, y]) + offset + RAIL * u
        lead = [("class", "guide"), ("data-guide", slider.name)]
        canvas.line((a[0], a[1]), (b[0], b[1]), ink, lead=lead, digits=4)
        canvas.keep_off((a[0], a[1]), (b[0], b[1]), RAIL_WIDTH)
        corners += [(a[0], a[1]), (b[0], b[1])]
        if slider.fixed:
            for k in range(int(2 * RAIL / HATCH) + 1):
                p = a + u * k * HATCH
                q = p + side * n * 1.8 - u * 1.2
                thin = [("stroke", "#222222"), ("stroke-width", "0.25")]
                canvas.line((p[0], p[1]), (q[0], q[1]), thin, lead=[("class", "hatch")], digits=3)
    return corners


def _block(canvas: Canvas, slider: Slider) -> None:
    """The slider's block: a BLOCK rectangle centred on its point, along its guide
    (``<polygon class="slider-block" data-slider=...>``)."""
    x, y = canvas.px(slider.at)
    u = np.array([slider.axis[0], -slider.axis[1]])
    n = np.array([-u[1], u[0]])
    half_u, half_n = u * BLOCK[0] / 2, n * BLOCK[1] / 2
    corners = [
        (x + su * half_u[0] + sn * half_n[0], y + su * half_u[1] + sn * half_n[1])
        for su, sn in ((-1, -1), (1, -1), (1, 1), (-1, 1))
    ]
    style = [("fill", "#ffffff"), ("stroke", "#222222"), ("stroke-width", "0.5")]
    canvas.keep_clear(corners)
    canvas.add(
        element(
            "polygon",
            [
                ("class", "slider-block"),
                ("data-slider", slider.name),
                ("points", " ".join(f"{px:.4f},{py:.4f}" for px, py in corners)),
                *style,
            ],
        )
    )


def _groove(canvas: Canvas, groove: Groove) -> list[Point]:
    """The carrier's disc (``<circle class="disc">``) and the groove in it
    (``<path class="groove" data-groove=...>``: an arc, or a line); the drawn extremes, for the
    frame."""
    ink = [("fill", "none"), ("stroke", "#222222"), ("stroke-width", "1.0")]
    lead = [("class", "groove"), ("data-groove", groove.name)]
    if groove.centre is None:
        (x1, y1), (x2, y2) = canvas.px(groove.start_point), canvas.px(groove.end_point)
        canvas.add(element("path", [*lead, ("d", f"M{x1:.4f},{y1:.4f} L{x2:.4f},{y2:.4f}"), *ink]))
        return [(x1, y1), (x2, y2)]
    cx, cy = canvas.px(groove.centre)
    scale = canvas.view.scale / canvas.view.per
    drawn: list[Point] = []
    if groove.disc > 0.0:
        r = groove.disc * scale
        fill = [("fill", "#eeeeee"), ("stroke", "#222222"), ("stroke-width", "0.5")]
        centre = [("cx", f"{cx:.4f}"), ("cy", f"{cy:.4f}"), ("r", f"{r:.4f}")]
        canvas.add(element("circle", [("class", "disc"), *centre, *fill]))
        drawn += [(cx - r, cy - r), (cx + r, cy + r)]
    r = groove.radius * scale
    steps = max(2, math.ceil(abs(groove.sweep) / (math.pi / 2)))  # arcs of at most 90 deg each
    ends = [groove.start + groove.sweep * k / steps for k in range(steps + 1)]
    at = [(cx + r * math.cos(a), cy - r * math.sin(a)) for a in ends]
    sweep_flag = 0 if groove.sweep > 0 else 1  # y down: counter-clockwise is SVG's sweep 0
    d = f"M{at[0][0]:.4f},{at[0][1]:.4f}" + "".join(
        f" A{r:.4f},{r:.4f} 0 0 {sweep_flag} {x:.4f},{y:.4f}" for x, y in at[1:]
    )
    canvas.add(element("path", [*lead, ("data-radius", f"{r:.4f}"), ("d", d), *ink]))
    return [*drawn, (cx - r, cy - r), (cx + r, cy + r)]


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

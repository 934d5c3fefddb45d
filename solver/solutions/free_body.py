"""Free-body diagrams: a link cut free, as data and as a small standalone SVG drawing (no script,
no external reference).

The drawing is the one a student draws before the equations: the known forces (weights, loads)
as arrows to a force scale, the unknown joint forces as their components with assumed senses
(dashed, of one length: their magnitudes are what the equations find), the moments as arcs (an
unknown driving torque counter-clockwise, as assumed), and no label over another or over the
drawing's edge. The data keeps, beside the unknowns, every force as solved (``forces``).
"""

from __future__ import annotations

import math
import re
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from typing import Any

from solver.solutions.figures import figure_name
from solver.teaching.svg import Canvas, View, element, escape_text, marker

SIZE = 320  # px, the drawing is square
MARGIN = 70  # px around the link, room for the arrows
ARROW = 55.0  # px, the longest known force
UNKNOWN = 38.0  # px, every unknown component
FONT = 11  # px, the labels
HEIGHT = SIZE + 34  # px, the force scale and the legend in a strip under the square

Box = tuple[float, float, float, float]  # x0, y0, x1, y1 in the drawing


@dataclass(frozen=True)
class Arrow:
    """A force on the link: its name, where it acts and its vector (N); ``kind`` says what it is
    ('joint' as solved, 'weight', 'load', 'friction' at a slot as the converged answer gives
    it)."""

    name: str
    kind: str
    at: tuple[float, float]
    vector: tuple[float, float]


@dataclass(frozen=True)
class Assumed:
    """An unknown force component as drawn: its name, where it acts, the unit vector of its
    assumed sense and the solved value along it (negative: the force acts the other way)."""

    name: str
    at: tuple[float, float]
    sense: tuple[float, float]
    value: float


@dataclass(frozen=True)
class Couple:
    """A moment on the link (N m, counter-clockwise positive): a driver's, a prismatic joint's or
    a load; ``unknown`` for one the equations find (drawn counter-clockwise, as assumed)."""

    name: str
    kind: str
    value: float
    unknown: bool = False


def figure(
    link: str,
    points: Mapping[str, tuple[float, float]],
    center: tuple[float, float] | None,
    arrows: Sequence[Arrow],
    couples: Sequence[Couple],
    unknowns: Sequence[Assumed] = (),
) -> dict[str, Any]:
    """The free-body diagram as JSON-ready data with its SVG: the solved forces (``forces``), the
    unknown components with their assumed senses and solved values (``unknowns``), the moments
    and the force scale (N per px of a known force's arrow; null without known forces)."""
    known = [a for a in arrows if a.kind != "joint"]
    return {
        "type": "free_body_diagram",
        "link": link,
        "points": {k: list(v) for k, v in points.items()},
        "center_of_mass": None if center is None else list(center),
        "forces": [
            {"name": a.name, "kind": a.kind, "at": list(a.at), "vector": list(a.vector)}
            for a in arrows
        ],
        "unknowns": [
            {"name": u.name, "at": list(u.at), "sense": list(u.sense), "value": u.value}
            for u in unknowns
        ],
        "moments": [
            {"name": c.name, "kind": c.kind, "value": c.value, "unknown": c.unknown}
            for c in couples
        ],
        "force_scale": _newtons_per_px(known),
        "svg": svg(link, points, center, known, couples, unknowns),
    }


def _newtons_per_px(known: Sequence[Arrow]) -> float | None:
    """N per px of the known forces' arrows: the largest is ARROW px long."""
    largest = max((math.hypot(*a.vector) for a in known), default=0.0)
    return largest / ARROW if largest > 0 else None


def label_width(name: str) -> float:
    """The drawn width of a label (px): its base at FONT, its subscript smaller."""
    base, _, subscript = name.partition("_")
    return 0.62 * FONT * len(base) + 0.5 * FONT * len(subscript)


def _overlap(a: Box, b: Box) -> float:
    w = min(a[2], b[2]) - max(a[0], b[0])
    h = min(a[3], b[3]) - max(a[1], b[1])
    return w * h if w > 0 and h > 0 else 0.0


class Labels:
    """Labels placed one by one where they overlap no earlier label or mark and stay inside the
    drawing: the first free place among a few around the anchor, else the least covered one."""

    def __init__(self, canvas: Canvas) -> None:
        self.canvas = canvas
        self.taken: list[Box] = []

    def mark(self, box: Box) -> None:
        """Keep ``box`` free of labels (a point, an arrowhead)."""
        self.taken.append(box)

    def place(self, anchor: tuple[float, float], name: str, color: str) -> Box:
        """Write ``name`` ('F_B,x': F with the subscript B,x) near ``anchor``; returns its box."""
        w, h = label_width(name), FONT + 2.0
        x, y = anchor
        offsets = [
            (5, -5),
            (5, 5 + h),
            (-5 - w, -5),
            (-5 - w, 5 + h),
            (-w / 2, -8),
            (-w / 2, 9 + h),
        ]
        best: tuple[float, Box] | None = None
        for dx, dy in offsets:
            left = min(max(x + dx, 2.0), SIZE - 2.0 - w)
            base = min(max(y + dy, h), SIZE - 2.0)
            box = (left, base - h + 2, left + w, base + 2)
            covered = sum(_overlap(box, t) for t in self.taken)
            if best is None or covered < best[0]:
                best = (covered, box)
            if covered == 0:
                break
        assert best is not None
        box = best[1]
        self.taken.append(box)
        self.canvas.add(_label(box[0], box[3] - 2, name, color))
        return box


def _label(x: float, y: float, name: str, color: str) -> str:
    """<text> of a name with its subscript (after '_') lowered and smaller."""
    base, _, subscript = name.partition("_")
    inner = escape_text(base)
    if subscript:
        inner += element("tspan", [("dy", "3"), ("font-size", str(FONT - 3))], subscript)
    return f'<text x="{x:.1f}" y="{y:.1f}" font-size="{FONT}" fill="{color}">{inner}</text>'


def svg(
    link: str,
    points: Mapping[str, tuple[float, float]],
    center: tuple[float, float] | None,
    known: Sequence[Arrow],
    couples: Sequence[Couple],
    unknowns: Sequence[Assumed] = (),
) -> str:
    """The drawing: the link as a bar through its points; each known force an arrow at its point
    whose length is its magnitude to the force scale (at least 0.4 ARROW, so a small one stays
    visible; the scale is drawn below); each unknown component a dashed arrow of UNKNOWN px in
    its assumed sense; each moment a named arc (counter-clockwise arrowhead for a positive or an
    unknown value). y is up as in the scene; the points' box is centred, its larger side
    SIZE - 2 MARGIN."""
    canvas = Canvas(
        View.centred(list(points.values()) + ([center] if center else []), SIZE, MARGIN)
    )
    labels = Labels(canvas)
    largest = max((math.hypot(*a.vector) for a in known), default=0.0)
    _link(canvas, labels, points, center)
    tips = [_known(canvas, a, largest) for a in known]
    tips += [_unknown(canvas, u) for u in unknowns]
    for tip, _ in (t for t in tips if t is not None):
        labels.mark((tip[0] - 4, tip[1] - 4, tip[0] + 4, tip[1] + 4))
    for drawn in tips:
        if drawn is not None:
            (x, y), (name, color) = drawn
            labels.place((x, y), name, color)
    for k, c in enumerate(couples):
        _couple(canvas, labels, k, c)
    if largest > 0:
        _scale(canvas, largest)
    if unknowns:
        canvas.add(
            _label(SIZE - 4 - label_width("unknown: dashed, assumed sense"), HEIGHT - 8,
                   "unknown: dashed, assumed sense", "#c0392b")
        )  # fmt: skip
    head = marker(_MARKER, [("d", "M0,0 L9,4 L0,8 z"), ("fill", "context-stroke")])
    return canvas.document(
        [
            ("viewBox", f"0 0 {SIZE} {HEIGHT}"),
            ("width", SIZE),
            ("height", HEIGHT),
            ("role", "img"),
            ("aria-label", f"free-body diagram of {link}"),
        ],
        [f"<defs>{head}</defs>"],
    )


_MARKER = (
    ("id", "head"),
    ("markerWidth", "9"),
    ("markerHeight", "8"),
    ("refX", "8"),
    ("refY", "4"),
    ("orient", "auto"),
    ("markerUnits", "userSpaceOnUse"),
)


def _link(
    canvas: Canvas,
    labels: Labels,
    points: Mapping[str, tuple[float, float]],
    center: tuple[float, float] | None,
) -> None:
    """The link as a bar through its named points, and its centre of mass G; the points'
    labels placed first."""
    canvas.points("polyline", map(canvas.px, points.values()), _BAR)
    places = [canvas.px(p) for p in points.values()]
    for x, y in places:
        canvas.circle((x, y), "4", [("fill", "#222")])
        labels.mark((x - 5, y - 5, x + 5, y + 5))
    if center is not None:
        x, y = canvas.px(center)
        canvas.circle((x, y), "5", [("fill", "none"), ("stroke", "#222")])
        labels.mark((x - 6, y - 6, x + 6, y + 6))
    for name, (x, y) in zip(points, places, strict=True):
        labels.place((x, y), _greek(name), "#222")
    if center is not None:
        labels.place(canvas.px(center), "G", "#222")


_WORD = re.compile(r"[A-Za-z]+[0-9]{0,2}")


def _greek(name: str) -> str:
    """A name as the figures write it: each Greek letter spelled out in it as the letter
    ('F_Gamma,x' as F_Γ,x), as ``figures.figure_name`` writes a point's name."""
    return _WORD.sub(lambda m: figure_name(m.group()), name)


_BAR = (
    ("fill", "none"),
    ("stroke", "#555"),
    ("stroke-width", "8"),
    ("stroke-linecap", "round"),
    ("stroke-linejoin", "round"),
    ("opacity", "0.6"),
)

_COLORS = {"weight": "#2c3e50", "load": "#27ae60", "friction": "#d35400"}


def _known(
    canvas: Canvas, a: Arrow, largest: float
) -> tuple[tuple[float, float], tuple[str, str]] | None:
    """A known force as an arrow from its point, ARROW * max(|F| / |F|max, 0.4) long; its tip
    and label; nothing for a force below 1e-9 of the largest."""
    magnitude = math.hypot(*a.vector)
    if largest == 0.0 or magnitude < 1e-9 * largest:
        return None
    length = ARROW * max(magnitude / largest, 0.4)
    x0, y0 = canvas.px(a.at)
    x1 = x0 + a.vector[0] / magnitude * length
    y1 = y0 - a.vector[1] / magnitude * length
    color = _COLORS.get(a.kind, "#27ae60")
    canvas.line(
        (x0, y0), (x1, y1), [("stroke", color), ("stroke-width", "2"), ("marker-end", "url(#head)")]
    )
    return (x1, y1), (_greek(a.name), color)


def _unknown(canvas: Canvas, u: Assumed) -> tuple[tuple[float, float], tuple[str, str]]:
    """An unknown component as a dashed arrow of UNKNOWN px from its point in its assumed sense;
    its tip and label."""
    x0, y0 = canvas.px(u.at)
    x1, y1 = x0 + u.sense[0] * UNKNOWN, y0 - u.sense[1] * UNKNOWN
    canvas.line(
        (x0, y0),
        (x1, y1),
        [
            ("stroke", "#c0392b"),
            ("stroke-width", "2"),
            ("stroke-dasharray", "5 3"),
            ("marker-end", "url(#head)"),
        ],
    )
    return (x1, y1), (_greek(u.name), "#c0392b")


def _couple(canvas: Canvas, labels: Labels, k: int, c: Couple) -> None:
    """The k-th moment as a named arc down the drawing's left edge; nothing for a known zero."""
    if c.value == 0.0 and not c.unknown:
        return
    x, y = 22.0, 24.0 + 24.0 * k
    sweep = 0 if c.unknown or c.value > 0 else 1  # counter-clockwise on the screen if positive
    canvas.path(
        f"M{x + 8:.1f},{y:.1f} A8,8 0 1 {sweep} {x:.1f},{y - 8:.1f}",
        [
            ("fill", "none"),
            ("stroke", "#8e44ad"),
            ("stroke-width", "2"),
            ("marker-end", "url(#head)"),
        ]
        + ([("stroke-dasharray", "4 2")] if c.unknown else []),
    )
    labels.mark((x - 10, y - 18, x + 10, y + 10))
    labels.place((x + 8, y + 4), _greek(c.name), "#8e44ad")


def _nice(x: float) -> float:
    """The largest of 1, 2, 5 x 10^n not above x."""
    power = 10.0 ** math.floor(math.log10(x))
    return max(m * power for m in (1.0, 2.0, 5.0) if m * power <= x * (1 + 1e-12))


def _scale(canvas: Canvas, largest: float) -> None:
    """The force scale under the drawing: a bar of a round force, its length to the scale."""
    force = _nice(largest / 2)
    length = ARROW * force / largest
    y = SIZE + 10.0
    canvas.line((8, y), (8 + length, y), [("stroke", "#2c3e50"), ("stroke-width", "2")])
    canvas.line((8, y - 4), (8, y + 4), [("stroke", "#2c3e50")])
    canvas.line((8 + length, y - 4), (8 + length, y + 4), [("stroke", "#2c3e50")])
    canvas.add(_label(16 + length, y + 4, f"{force:g} N", "#2c3e50"))

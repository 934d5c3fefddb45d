"""Free-body diagrams: a link, the forces on it (arrows with their names) and its moments, as data
and as a small standalone SVG drawing (no script, no external reference)."""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from typing import Any

from solver.teaching.svg import Canvas, View, marker

SIZE = 320  # px, the drawing is square
MARGIN = 70  # px around the link, room for the arrows
ARROW = 55.0  # px, the longest arrow


@dataclass(frozen=True)
class Arrow:
    """A force on the link: its name, where it acts and its vector (N); ``kind`` says what it is
    ('joint', 'weight', 'load')."""

    name: str
    kind: str
    at: tuple[float, float]
    vector: tuple[float, float]


@dataclass(frozen=True)
class Couple:
    """A moment on the link (N m, counter-clockwise positive): a driver's, a prismatic joint's or
    a load."""

    name: str
    kind: str
    value: float


def figure(
    link: str,
    points: Mapping[str, tuple[float, float]],
    center: tuple[float, float] | None,
    arrows: Sequence[Arrow],
    couples: Sequence[Couple],
) -> dict[str, Any]:
    """The free-body diagram as JSON-ready data with its SVG."""
    return {
        "type": "free_body_diagram",
        "link": link,
        "points": {k: list(v) for k, v in points.items()},
        "center_of_mass": None if center is None else list(center),
        "forces": [
            {"name": a.name, "kind": a.kind, "at": list(a.at), "vector": list(a.vector)}
            for a in arrows
        ],
        "moments": [{"name": c.name, "kind": c.kind, "value": c.value} for c in couples],
        "svg": svg(link, points, center, arrows, couples),
    }


def svg(
    link: str,
    points: Mapping[str, tuple[float, float]],
    center: tuple[float, float] | None,
    arrows: Sequence[Arrow],
    couples: Sequence[Couple],
) -> str:
    """The drawing: the link as a bar through its points, each force an arrow at its point whose
    length is proportional to its magnitude, each moment a named arc (counter-clockwise arrowhead
    for a positive value). y is up as in the scene; the points' box is centred, its larger side
    SIZE - 2 MARGIN."""
    canvas = Canvas(
        View.centred(list(points.values()) + ([center] if center else []), SIZE, MARGIN)
    )
    largest = max((math.hypot(*a.vector) for a in arrows), default=0.0)
    _link(canvas, points, center)
    for a in arrows:
        _force(canvas, a, largest)
    for k, c in enumerate(couples):
        _couple(canvas, k, c)
    head = marker(_MARKER, [("d", "M0,0 L9,4 L0,8 z"), ("fill", "context-stroke")])
    return canvas.document(
        [
            ("viewBox", f"0 0 {SIZE} {SIZE}"),
            ("width", SIZE),
            ("height", SIZE),
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
    canvas: Canvas, points: Mapping[str, tuple[float, float]], center: tuple[float, float] | None
) -> None:
    """The link as a bar through its named points, and its centre of mass G."""
    canvas.points("polyline", map(canvas.px, points.values()), _BAR)
    for name, p in points.items():
        x, y = canvas.px(p)
        canvas.circle((x, y), "4", [("fill", "#222")])
        canvas.text((x + 6, y + 14), name, _LABEL)
    if center is not None:
        x, y = canvas.px(center)
        canvas.circle((x, y), "5", [("fill", "none"), ("stroke", "#222")])
        canvas.text((x + 6, y - 6), "G", _LABEL)


_LABEL = (("font-size", "11"),)
_BAR = (
    ("fill", "none"),
    ("stroke", "#555"),
    ("stroke-width", "8"),
    ("stroke-linecap", "round"),
    ("stroke-linejoin", "round"),
    ("opacity", "0.6"),
)


def _force(canvas: Canvas, a: Arrow, largest: float) -> None:
    """A force as an arrow from its point, ARROW * max(|F| / |F|max, 0.4) long, with its name;
    nothing for a force below 1e-9 of the largest."""
    magnitude = math.hypot(*a.vector)
    if largest == 0.0 or magnitude < 1e-9 * largest:
        return
    length = ARROW * max(magnitude / largest, 0.4)
    x0, y0 = canvas.px(a.at)
    x1 = x0 + a.vector[0] / magnitude * length
    y1 = y0 - a.vector[1] / magnitude * length
    color = {"joint": "#c0392b", "weight": "#2c3e50", "load": "#27ae60"}.get(a.kind, "#c0392b")
    canvas.line(
        (x0, y0), (x1, y1), [("stroke", color), ("stroke-width", "2"), ("marker-end", "url(#head)")]
    )
    canvas.text((x1 + 3, y1 - 3), a.name, [*_LABEL, ("fill", color)])


def _couple(canvas: Canvas, k: int, c: Couple) -> None:
    """The k-th moment as a named arc in the top right corner; nothing for a zero moment."""
    if c.value == 0.0:
        return
    x, y = SIZE - 60, 24 + 22 * k
    sweep = 0 if c.value > 0 else 1  # counter-clockwise on the screen for a positive moment
    canvas.path(
        f"M{x + 8:.1f},{y:.1f} A8,8 0 1 {sweep} {x:.1f},{y - 8:.1f}",
        [
            ("fill", "none"),
            ("stroke", "#8e44ad"),
            ("stroke-width", "2"),
            ("marker-end", "url(#head)"),
        ],
    )
    canvas.text((x + 14, y + 4), c.name, [*_LABEL, ("fill", "#8e44ad")])

"""Free-body diagrams: a link, the forces on it (arrows with their names) and its moments, as data
and as a small standalone SVG drawing (no script, no external reference)."""

from __future__ import annotations

import html
import math
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass
from typing import Any

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
    for a positive value). y is up as in the scene."""
    px = _pixels(list(points.values()) + ([center] if center else []))
    largest = max((math.hypot(*a.vector) for a in arrows), default=0.0)
    parts = [
        f'<svg xmlns="http://www.w3.org/2000/svg" viewBox="0 0 {SIZE} {SIZE}" width="{SIZE}" '
        f'height="{SIZE}" role="img" aria-label="free-body diagram of {html.escape(link)}">',
        '<defs><marker id="head" markerWidth="9" markerHeight="8" refX="8" refY="4" '
        'orient="auto" markerUnits="userSpaceOnUse"><path d="M0,0 L9,4 L0,8 z" '
        'fill="context-stroke"/></marker></defs>',
        *_link(points, center, px),
    ]
    for a in arrows:
        parts += _force(a, px, largest)
    for k, c in enumerate(couples):
        parts += _couple(k, c)
    parts.append("</svg>")
    return "".join(parts)


Pixels = Callable[[tuple[float, float]], tuple[float, float]]


def _pixels(xy: list[tuple[float, float]]) -> Pixels:
    """The map from the scene (y up) to the drawing (y down): the points' bounding box centred,
    its larger side scaled to SIZE - 2 MARGIN."""
    xs, ys = [p[0] for p in xy], [p[1] for p in xy]
    span = max(max(xs) - min(xs), max(ys) - min(ys), 1e-300)
    scale = (SIZE - 2 * MARGIN) / span
    cx, cy = (max(xs) + min(xs)) / 2, (max(ys) + min(ys)) / 2

    def px(p: tuple[float, float]) -> tuple[float, float]:
        return SIZE / 2 + (p[0] - cx) * scale, SIZE / 2 - (p[1] - cy) * scale

    return px


def _link(
    points: Mapping[str, tuple[float, float]], center: tuple[float, float] | None, px: Pixels
) -> list[str]:
    """The link as a bar through its named points, and its centre of mass G."""
    e = html.escape
    chain = " ".join(f"{x:.1f},{y:.1f}" for x, y in map(px, points.values()))
    parts = [
        f'<polyline points="{chain}" fill="none" stroke="#555" stroke-width="8" '
        'stroke-linecap="round" stroke-linejoin="round" opacity="0.6"/>'
    ]
    for name, p in points.items():
        x, y = px(p)
        parts.append(f'<circle cx="{x:.1f}" cy="{y:.1f}" r="4" fill="#222"/>')
        parts.append(f'<text x="{x + 6:.1f}" y="{y + 14:.1f}" font-size="11">{e(name)}</text>')
    if center is not None:
        x, y = px(center)
        parts.append(f'<circle cx="{x:.1f}" cy="{y:.1f}" r="5" fill="none" stroke="#222"/>')
        parts.append(f'<text x="{x + 6:.1f}" y="{y - 6:.1f}" font-size="11">G</text>')
    return parts


def _force(a: Arrow, px: Pixels, largest: float) -> list[str]:
    """A force as an arrow from its point, ARROW * max(|F| / |F|max, 0.4) long, with its name;
    nothing for a force below 1e-9 of the largest."""
    magnitude = math.hypot(*a.vector)
    if largest == 0.0 or magnitude < 1e-9 * largest:
        return []
    length = ARROW * max(magnitude / largest, 0.4)
    x0, y0 = px(a.at)
    x1 = x0 + a.vector[0] / magnitude * length
    y1 = y0 - a.vector[1] / magnitude * length
    color = {"joint": "#c0392b", "weight": "#2c3e50", "load": "#27ae60"}.get(a.kind, "#c0392b")
    return [
        f'<line x1="{x0:.1f}" y1="{y0:.1f}" x2="{x1:.1f}" y2="{y1:.1f}" stroke="{color}" '
        'stroke-width="2" marker-end="url(#head)"/>',
        f'<text x="{x1 + 3:.1f}" y="{y1 - 3:.1f}" font-size="11" fill="{color}">'
        f"{html.escape(a.name)}</text>",
    ]


def _couple(k: int, c: Couple) -> list[str]:
    """The k-th moment as a named arc in the top right corner; nothing for a zero moment."""
    if c.value == 0.0:
        return []
    x, y = SIZE - 60, 24 + 22 * k
    sweep = 0 if c.value > 0 else 1  # counter-clockwise on the screen for a positive moment
    return [
        f'<path d="M{x + 8:.1f},{y:.1f} A8,8 0 1 {sweep} {x:.1f},{y - 8:.1f}" fill="none" '
        'stroke="#8e44ad" stroke-width="2" marker-end="url(#head)"/>',
        f'<text x="{x + 14:.1f}" y="{y + 4:.1f}" font-size="11" fill="#8e44ad">'
        f"{html.escape(c.name)}</text>",
    ]

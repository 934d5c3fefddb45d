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
from xml.sax.saxutils import escape, quoteattr

import numpy as np

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
    ``largest`` in at most ``paper_cm`` centimetres."""
    if largest <= 0.0:
        return 1.0
    raw = largest / paper_cm
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


def _defs() -> str:
    markers = "".join(
        f'<marker id="head-{name}" viewBox="0 0 6 6" refX="5.5" refY="3" markerWidth="5" '
        f'markerHeight="5" orient="auto-start-reverse"><path d="M0,0 L6,3 L0,6 z" '
        f'fill="{colour}"/></marker>'
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
    attributes: dict[str, str],
) -> str:
    """An SVG drawing: model coordinates (y up) times ``1 / per_mm`` give millimetres."""
    points = [a.start for a in arrows] + [a.end for a in arrows] + [d.at for d in dots]
    points += [p for s in segments for p in s[:2]]
    x0, y0, width, height = _frame(points or [np.zeros(2)], per_mm)
    body = [_defs(), f"<title>{escape(title)}</title>"]
    body += [_segment(_paper(a, per_mm), _paper(b, per_mm), style) for a, b, style in segments]
    for arrow in arrows:
        body += _arrow(arrow, per_mm)
    for dot in dots:
        body += _dot(dot, per_mm)
    body.append(
        f'<text x="{x0 + 2:.2f}" y="{y0 + height - 2.5:.2f}" font-size="3.4" fill="#000000">'
        f"{escape(caption)}</text>"
    )
    extra = "".join(f" {k}={quoteattr(v)}" for k, v in attributes.items())
    return (
        f'<svg xmlns="http://www.w3.org/2000/svg" role="img" width="{width:.1f}mm" '
        f'height="{height:.1f}mm" viewBox="{x0:.3f} {y0:.3f} {width:.3f} {height:.3f}"'
        f' font-family="sans-serif"{extra}>' + "".join(body) + "</svg>"
    )


def _paper(p: np.ndarray, per_mm: float) -> tuple[float, float]:
    """(x, -y) / per_mm: a model point in millimetres of paper, y down as SVG draws."""
    return float(p[0]) / per_mm, -float(p[1]) / per_mm


def _frame(points: Sequence[np.ndarray], per_mm: float) -> tuple[float, float, float, float]:
    """The view box (x0, y0, width, height) in mm: the points with a margin, and room for the
    caption below."""
    xs = [float(p[0]) / per_mm for p in points]
    ys = [-float(p[1]) / per_mm for p in points]
    x0, y0 = min(xs) - MARGIN, min(ys) - MARGIN
    return x0, y0, max(xs) - min(xs) + 2 * MARGIN, max(ys) - min(ys) + 2 * MARGIN + 8.0


def _segment(start: tuple[float, float], end: tuple[float, float], style: str) -> str:
    """A line of the drawing: a link as a thick bar, anything else in its style's colour."""
    (x1, y1), (x2, y2) = start, end
    colour, dash = STYLE.get(style, ("#000000", ""))
    width_mm = "1.4" if style == "link" else "0.35"
    stroke = "#222222" if style == "link" else colour
    return (
        f'<line class="{style}" x1="{x1:.4f}" y1="{y1:.4f}" x2="{x2:.4f}" y2="{y2:.4f}" '
        f'stroke="{stroke}" stroke-width="{width_mm}" stroke-linecap="round"'
        + (f' stroke-dasharray="{dash}"' if dash and style != "link" else "")
        + "/>"
    )


def _arrow(arrow: Arrow, per_mm: float) -> list[str]:
    """A vector as a line with an arrowhead and ``data-vector``, its label beside its middle
    (2.5 mm along the normal); nothing for a vector shorter than ``SHORTEST``."""
    (x1, y1), (x2, y2) = _paper(arrow.start, per_mm), _paper(arrow.end, per_mm)
    if math.hypot(x2 - x1, y2 - y1) < SHORTEST:
        return []  # a vector at the rounding level, or shorter than a pen can draw
    colour, dash = STYLE[arrow.style]
    out = [
        f'<line class="{arrow.style}" data-vector={quoteattr(arrow.name)} '
        f'x1="{x1:.6f}" y1="{y1:.6f}" x2="{x2:.6f}" y2="{y2:.6f}" stroke="{colour}" '
        f'stroke-width="0.45" marker-end="url(#head-{arrow.style})"'
        + (f' stroke-dasharray="{dash}"' if dash else "")
        + "/>"
    ]
    if arrow.label:
        mx, my = (x1 + x2) / 2, (y1 + y2) / 2
        length = math.hypot(x2 - x1, y2 - y1) or 1.0
        nx, ny = -(y2 - y1) / length * 2.5, (x2 - x1) / length * 2.5
        out.append(
            f'<text x="{mx + nx:.2f}" y="{my + ny:.2f}" font-size="3" fill="{colour}" '
            f'text-anchor="middle">{escape(arrow.label)}</text>'
        )
    return out


def _dot(dot: Dot, per_mm: float) -> list[str]:
    """A point as a small circle with its label (and a ground hatch under a fixed one)."""
    x, y = _paper(dot.at, per_mm)
    out = [
        f'<circle cx="{x:.4f}" cy="{y:.4f}" r="0.9" fill="#ffffff" stroke="#000000" '
        'stroke-width="0.35"/>'
    ]
    if dot.fixed:
        out.append(
            f'<path d="M{x - 2.5:.2f},{y + 3:.2f} L{x:.2f},{y + 0.9:.2f} L{x + 2.5:.2f},'
            f'{y + 3:.2f} z" fill="none" stroke="#000000" stroke-width="0.3"/>'
        )
    out.append(
        f'<text x="{x + 1.6:.2f}" y="{y - 1.6:.2f}" font-size="3.4" fill="#000000">'
        f"{escape(dot.label)}</text>"
    )
    return out


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

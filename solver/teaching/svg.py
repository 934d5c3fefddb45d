"""One SVG canvas for every drawing the app makes: the figures of a worked solution (the mechanism
to scale, the velocity and acceleration polygons, ``solver.solutions.figures``), the free-body
diagrams (``solver.solutions.free_body``) and the figure of an exercise
(``solver.exercises.figures``).

A ``View`` maps the model's coordinates (y up) to the drawing's (y down) at one scale for x and
y; a ``Canvas`` collects the elements of a drawing in the drawing's coordinates, each written
with its attributes in order and its numbers to the digits asked, and closes them into a
standalone SVG document (no script, no external reference). Labels come from the user's scene:
every text and attribute value is escaped here, once.

Labels are placed so that no two overlap: a label's box is estimated from its font size and its
number of characters (``text_box``: ``CHAR_WIDTH`` em per character, ``ASCENT`` em above the
baseline and ``DESCENT`` below, wider than a sans-serif font sets most labels), and
``Canvas.label`` takes the first of its candidate places whose box meets no label placed before,
else the nearest free place on rings around the first candidate.
"""

from __future__ import annotations

import html
import math
from collections.abc import Iterable, Sequence
from dataclasses import dataclass

import numpy as np

Point = tuple[float, float]
CHAR_WIDTH = 0.62  # em: the width estimated for one character of a label (sans-serif)
ASCENT = 0.8  # em: a label's box above its baseline
DESCENT = 0.25  # em: and below it
RING = 1.5  # mm: the step between the rings of places tried when no candidate is free
SEARCH_RINGS = 4  # rings within which a label looks for a place off every bar
Coordinates = Sequence[float] | np.ndarray  # a model point: (x, y), a (2,) array
Attribute = tuple[str, str | float]


@dataclass(frozen=True)
class View:
    """The map from the model (y up) to the drawing (y down):
    (x, y) -> (dx + (x - x0) scale / per, dy - (y - y1) scale / per).

    The scale is a ratio ``scale / per`` so that a drawing at a stated scale ("1 mm of paper =
    per m", ``paper``) divides by it exactly as the scale reads."""

    x0: float
    y1: float
    scale: float
    dx: float = 0.0
    dy: float = 0.0
    per: float = 1.0

    def px(self, p: Coordinates) -> Point:
        """The drawing's coordinates of the model point ``p``."""
        x = self.dx + (float(p[0]) - self.x0) * self.scale / self.per
        y = self.dy - (float(p[1]) - self.y1) * self.scale / self.per
        return x, y

    @classmethod
    def paper(cls, per: float) -> View:
        """(x, y) -> (x / per, -y / per): a drawing at "1 unit = per model units" about the
        model's origin. The offsets are -0.0 so that a zero keeps its sign (-0 / per for y = 0),
        as the division alone gives it."""
        return cls(0.0, 0.0, 1.0, -0.0, -0.0, per)

    @classmethod
    def fit(cls, points: Sequence[Point], width: float, height: float, margin: float) -> View:
        """The points' bounding box at the largest scale that fits ``width`` x ``height`` within
        ``margin``, centred."""
        xs, ys = [p[0] for p in points], [p[1] for p in points]
        x0, y1 = min(xs), max(ys)
        span_x, span_y = max(xs) - x0, y1 - min(ys)
        scale = min(
            (width - 2 * margin) / max(span_x, 1e-9), (height - 2 * margin) / max(span_y, 1e-9)
        )
        return cls(x0, y1, scale, (width - scale * span_x) / 2, (height - scale * span_y) / 2)

    @classmethod
    def centred(cls, points: Sequence[Point], size: float, margin: float) -> View:
        """The points' bounding box centred in a ``size`` square, its larger side scaled to
        ``size - 2 margin``."""
        xs, ys = [p[0] for p in points], [p[1] for p in points]
        span = max(max(xs) - min(xs), max(ys) - min(ys), 1e-300)
        centre = ((max(xs) + min(xs)) / 2, (max(ys) + min(ys)) / 2)
        return cls(centre[0], centre[1], (size - 2 * margin) / span, size / 2, size / 2)


@dataclass(frozen=True)
class Bar:
    """A drawn segment from a to b, ``width`` wide, that labels keep off."""

    a: Point
    b: Point
    width: float


@dataclass(frozen=True)
class Box:
    """An axis-aligned box in the drawing's coordinates (y down): left <= right, top <= bottom."""

    left: float
    top: float
    right: float
    bottom: float

    def overlaps(self, other: Box) -> bool:
        """True when the two boxes share an area (touching edges do not overlap)."""
        return (
            self.left < other.right
            and other.left < self.right
            and self.top < other.bottom
            and other.top < self.bottom
        )


def crosses(box: Box, a: Point, b: Point, pad: float) -> bool:
    """True when the segment ab passes through ``box`` grown by ``pad`` on every side (a bar's
    half width): the segment clipped to the box's slab in x, then in y, keeps a piece."""
    low, high = 0.0, 1.0
    for start, delta, lo, hi in (
        (a[0], b[0] - a[0], box.left - pad, box.right + pad),
        (a[1], b[1] - a[1], box.top - pad, box.bottom + pad),
    ):
        if delta == 0.0:
            if not lo < start < hi:
                return False
            continue
        t1, t2 = sorted(((lo - start) / delta, (hi - start) / delta))
        low, high = max(low, t1), min(high, t2)
        if low >= high:
            return False
    return True


def text_box(at: Point, label: str, size: float, anchor: str = "start") -> Box:
    """The box of a label set at ``at`` (its baseline) in a font of ``size``:
    width = CHAR_WIDTH size n for n characters, from ASCENT size above the baseline to
    DESCENT size below, starting at x, centred on it or ending there by ``anchor``."""
    width = CHAR_WIDTH * size * len(label)
    left = at[0] - {"start": 0.0, "middle": width / 2, "end": width}[anchor]
    return Box(left, at[1] - ASCENT * size, left + width, at[1] + DESCENT * size)


def escape_text(text: str) -> str:
    """A label as element text: &, < and > escaped."""
    return html.escape(text, quote=False)


def attributes(pairs: Iterable[Attribute]) -> str:
    """' name="value"' for each pair in order, the value escaped for a double-quoted attribute."""
    return "".join(f' {name}="{html.escape(str(value))}"' for name, value in pairs)


def element(tag: str, pairs: Iterable[Attribute], text: str | None = None) -> str:
    """<tag .../> or, with ``text`` (escaped), <tag ...>text</tag>."""
    if text is None:
        return f"<{tag}{attributes(pairs)}/>"
    return f"<{tag}{attributes(pairs)}>{escape_text(text)}</{tag}>"


def marker(pairs: Iterable[Attribute], path: Iterable[Attribute]) -> str:
    """<marker ...> holding one <path>: an arrowhead for ``marker-end``."""
    return f"<marker{attributes(pairs)}>{element('path', path)}</marker>"


def number(x: float, digits: int) -> str:
    """x with ``digits`` decimals, as every coordinate of a drawing is written."""
    return f"{x:.{digits}f}"


class Canvas:
    """An SVG drawing being built: a view, its elements in order, then the document.

    Every element's coordinates are the drawing's (``px`` maps a model point there), written with
    ``digits`` decimals unless an element asks for others."""

    def __init__(self, view: View, digits: int = 1) -> None:
        self.view = view
        self.digits = digits
        self.parts: list[str] = []
        self.labels: list[Box] = []  # the boxes of the labels placed so far
        self.clear: list[Box] = []  # drawn shapes that labels keep clear of (``keep_clear``)
        self.bars: list[Bar] = []  # drawn segments that labels keep off (``keep_off``)

    def px(self, p: Coordinates) -> Point:
        return self.view.px(p)

    def add(self, *elements: str) -> None:
        """Elements written elsewhere (a group, a marker, a path with its own ``d``)."""
        self.parts.extend(elements)

    def _n(self, x: float, digits: int | None) -> str:
        return number(x, self.digits if digits is None else digits)

    def line(
        self,
        a: Point,
        b: Point,
        style: Sequence[Attribute],
        lead: Sequence[Attribute] = (),
        digits: int | None = None,
    ) -> None:
        """<line> from a to b (drawing coordinates), its ``lead`` attributes first."""
        ends = [("x1", a[0]), ("y1", a[1]), ("x2", b[0]), ("y2", b[1])]
        coords = [(k, self._n(v, digits)) for k, v in ends]
        self.add(element("line", [*lead, *coords, *style]))

    def circle(
        self, centre: Point, r: float | str, style: Sequence[Attribute], digits: int | None = None
    ) -> None:
        """<circle> about ``centre`` (drawing coordinates) of radius ``r`` (a number is written
        with the coordinates' digits)."""
        radius = r if isinstance(r, str) else self._n(r, digits)
        cx, cy = self._n(centre[0], digits), self._n(centre[1], digits)
        self.add(element("circle", [("cx", cx), ("cy", cy), ("r", radius), *style]))

    def text(
        self, at: Point, label: str, style: Sequence[Attribute], digits: int | None = None
    ) -> None:
        """<text> at ``at`` (drawing coordinates), the label escaped."""
        x, y = self._n(at[0], digits), self._n(at[1], digits)
        self.add(element("text", [("x", x), ("y", y), *style], label))

    def label(
        self,
        candidates: Sequence[tuple[Point, str]],
        label: str,
        size: float,
        style: Sequence[Attribute],
        digits: int | None = None,
    ) -> Box:
        """<text> of ``label`` in a font of ``size`` at the first candidate (a place and its
        text-anchor) whose box overlaps no label placed before and no shape kept clear of and
        crosses no bar kept off; if every one does, at the nearest such place on rings of radius
        RING, 2 RING, ... up to SEARCH_RINGS around the first; if none is free of the bars
        there, the first place free of the labels and shapes alone (the candidates, then rings
        without end). Its box is kept (``labels``) and returned."""
        places = self.digits if digits is None else digits
        boxes = [*self.labels, *self.clear]
        place = _free_place(candidates, label, size, boxes, places, self.bars)
        (x, y), anchor = place
        box = text_box((x, y), label, size, anchor)
        self.labels.append(box)
        lead = [("font-size", f"{size:g}"), ("text-anchor", anchor)]
        self.text((x, y), label, [*lead, *style], digits)
        return box

    def keep_off(self, a: Point, b: Point, width: float) -> None:
        """Labels placed from now on do not cross the segment ab drawn ``width`` wide (a link's
        bar, a guide's rail)."""
        self.bars.append(Bar(a, b, width))

    def keep_clear(self, corners: Iterable[Point]) -> None:
        """Labels placed from now on keep clear of the box around these corners (a drawn
        shape a label would hide)."""
        xs, ys = zip(*corners, strict=True)
        self.clear.append(Box(min(xs), min(ys), max(xs), max(ys)))

    def points(self, tag: str, corners: Iterable[Point], style: Sequence[Attribute]) -> None:
        """<polyline> or <polygon> through the corners (drawing coordinates)."""
        chain = " ".join(f"{self._n(x, None)},{self._n(y, None)}" for x, y in corners)
        self.add(element(tag, [("points", chain), *style]))

    def path(self, d: str, style: Sequence[Attribute]) -> None:
        """<path> of the drawing's path data ``d``."""
        self.add(element("path", [("d", d), *style]))

    def document(self, pairs: Sequence[Attribute], head: Sequence[str] = ()) -> str:
        """The standalone SVG: its root attributes, the ``head`` (defs, title, background), the
        elements."""
        root = f'<svg xmlns="http://www.w3.org/2000/svg"{attributes(pairs)}>'
        return root + "".join(head) + "".join(self.parts) + "</svg>"


def _free_place(
    candidates: Sequence[tuple[Point, str]],
    label: str,
    size: float,
    placed: Sequence[Box],
    digits: int,
    bars: Sequence[Bar] = (),
) -> tuple[Point, str]:
    """The first candidate whose box meets none of ``placed`` and crosses none of ``bars``;
    else, on rings of radius k RING (k = 1 .. SEARCH_RINGS) around the first candidate, 16
    places each, the first such one; else the same without the bars, the rings without end. A
    place is rounded to the ``digits`` it is written with before its box is tried."""

    def rounded(at: Point) -> Point:
        return round(at[0], digits), round(at[1], digits)

    def free(at: Point, anchor: str, off: Sequence[Bar]) -> bool:
        box = text_box(at, label, size, anchor)
        return not any(box.overlaps(other) for other in placed) and not any(
            crosses(box, bar.a, bar.b, bar.width / 2) for bar in off
        )

    def ring(k: int) -> list[Point]:
        (x, y), r = candidates[0][0], k * RING
        turns = (2 * math.pi * i / 16 for i in range(16))
        return [rounded((x + r * math.cos(t), y + r * math.sin(t))) for t in turns]

    anchor = candidates[0][1]
    for off in (bars, ()):
        for at, side in candidates:
            if free(rounded(at), side, off):
                return rounded(at), side
        k = 1
        while not off or k <= SEARCH_RINGS:  # finitely many boxes: a ring beyond is free
            for at in ring(k):
                if free(at, anchor, off):
                    return at, anchor
            k += 1
    raise AssertionError("unreachable: a ring beyond every box is free")

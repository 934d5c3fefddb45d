"""One SVG canvas for every drawing the app makes: the figures of a worked solution (the mechanism
to scale, the velocity and acceleration polygons, ``solver.solutions.figures``), the free-body
diagrams (``solver.solutions.free_body``) and the figure of an exercise
(``solver.exercises.figures``).

A ``View`` maps the model's coordinates (y up) to the drawing's (y down) at one scale for x and
y; a ``Canvas`` collects the elements of a drawing in the drawing's coordinates, each written
with its attributes in order and its numbers to the digits asked, and closes them into a
standalone SVG document (no script, no external reference). Labels come from the user's scene:
every text and attribute value is escaped here, once.
"""

from __future__ import annotations

import html
from collections.abc import Iterable, Sequence
from dataclasses import dataclass

import numpy as np

Point = tuple[float, float]
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

"""The figure of an exercise: an SVG drawing of its scene to scale, labelled, rotations drawn.

Planar scenes are drawn in the x-y plane (y up) at one scale with a scale bar: links as bars
(a link with three or more points as a plate), fixed pivots hatched, sliders as blocks on their
guide (a fixed guide hatched, a slot drawn on its link), the driver's rotation as an arrow about
its pivot with omega (and alpha) beside it, a moving point's path dashed, a straight path through
its pivot with its angle from x dimensioned, and the x and y axes at the origin. Spatial chains are
drawn in an oblique projection with each joint's axis and rate.
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from itertools import pairwise
from typing import Any

from solver.cams import parse_cam
from solver.exercises.model import is_task
from solver.gears import parse_gear_train
from solver.model.scene import Joint, ground_pivot, parse_linkage
from solver.solutions.cam import cam_context, cam_figure
from solver.solutions.gear_train import train_figure
from solver.teaching.svg import Attribute, Canvas, View, element, text_box

WIDTH, HEIGHT, MARGIN = 420.0, 300.0, 48.0
INK = "#1f2937"
LINK = "#2563eb"
GUIDE = "#6b7280"
ROTATION = "#dc2626"
FONT: Attribute = ("font-family", "sans-serif")
Point = tuple[float, float]


def _canvas(points: Sequence[Point]) -> Canvas:
    """World coordinates (m) to SVG pixels: one scale for x and y, y pointing up, the points
    fitted within the margin and centred."""
    return Canvas(View.fit(points, WIDTH, HEIGHT, MARGIN))


def _line(canvas: Canvas, a: Point, b: Point, color: str, width: float, dash: str = "") -> None:
    """A line between two world points."""
    style: list[Attribute] = [
        ("stroke", color),
        ("stroke-width", width),
        ("stroke-linecap", "round"),
    ]
    if dash:
        style.append(("stroke-dasharray", dash))
    canvas.line(canvas.px(a), canvas.px(b), style)


PAD = 4.0  # px: a label's box stays this far inside the figure's edges
BESIDE = ((7.0, -7.0, "start"), (-7.0, -7.0, "end"), (7.0, 16.0, "start"), (-7.0, 16.0, "end"))


def _inside(at: Point, label: str, size: float, anchor: str) -> tuple[Point, str]:
    """A label's place moved, just enough for its box to lie within the figure."""
    box = text_box(at, label, size, anchor)
    dx = max(PAD - box.left, 0.0) + min(WIDTH - PAD - box.right, 0.0)
    dy = max(PAD - box.top, 0.0) + min(HEIGHT - PAD - box.bottom, 0.0)
    return (at[0] + dx, at[1] + dy), anchor


def _text(
    canvas: Canvas, p: Point, label: str, dx: float = 7, dy: float = -7, color: str = INK
) -> None:
    """A label (13 px) beside a world point: (dx, dy) pixels off it, else the first free one of
    the places around it (``BESIDE``), away from the labels, bars and marks placed before
    (``Canvas.label``) and within the figure."""
    x, y = canvas.px(p)
    offsets = [(dx, dy, "start"), *(o for o in BESIDE if o[:2] != (dx, dy))]
    places = [_inside((x + ox, y + oy), label, 13, side) for ox, oy, side in offsets]
    canvas.label(places, label, 13, [("fill", color), FONT])


def _mark(canvas: Canvas, x: float, y: float, half_width: float, up: float, down: float) -> None:
    """Labels keep clear of a mark drawn about (x, y) pixels: a pivot's hatching, a block, a
    point's circle, a rotation's arrow."""
    canvas.keep_clear([(x - half_width, y - up), (x + half_width, y + down)])


def _document(canvas: Canvas, title: str) -> str:
    """The figure on a white background, titled."""
    size = [("width", f"{WIDTH:.0f}"), ("height", f"{HEIGHT:.0f}")]
    return canvas.document(
        [
            ("viewBox", f"0 0 {WIDTH:.0f} {HEIGHT:.0f}"),
            *size,
            ("role", "img"),
            ("aria-label", title),
        ],
        [element("title", [], title), element("rect", [*size, ("fill", "white")])],
    )


def nice_length(target: float) -> float:
    """1, 2 or 5 times a power of ten, at most ``target``."""
    power = 10.0 ** math.floor(math.log10(target))
    if power > target:  # log10 rounded up to a whole number just above the target
        power /= 10.0
    return max(m * power for m in (1.0, 2.0, 5.0) if m * power <= target)


def _scale_bar(canvas: Canvas) -> None:
    """A bar of a round length (``nice_length``) at the bottom left, labelled; labels placed
    afterwards keep clear of it."""
    length = nice_length(0.25 * (WIDTH - 2 * MARGIN) / canvas.view.scale)
    x, y = 12.0, HEIGHT - 14.0
    w = length * canvas.view.scale
    canvas.path(
        f"M{x:.1f} {y - 4:.1f}V{y:.1f}H{x + w:.1f}V{y - 4:.1f}",
        [("fill", "none"), ("stroke", INK), ("stroke-width", "1.2")],
    )
    canvas.keep_clear([(x, y - 4), (x + w, y)])
    canvas.label([((x + w + 6, y), "start")], f"{length:g} m", 11, [("fill", INK), FONT])


def _ground_pivot(canvas: Canvas, p: Point) -> None:
    x, y = canvas.px(p)
    _mark(canvas, x, y, 12, 0, 20)
    ink = [("stroke", INK), ("stroke-width", "1.2")]
    canvas.path(f"M{x:.1f} {y:.1f}l-9 15h18z", [("fill", "#e5e7eb"), *ink])
    canvas.path(f"M{x - 12:.1f} {y + 15:.1f}h24", ink)
    for k in range(6):
        canvas.path(f"M{x - 12 + 5 * k:.1f} {y + 15:.1f}l-4 5", [("stroke", INK)])


def _rotation(canvas: Canvas, p: Point, omega: float) -> None:
    """An arc arrow of radius 22 px under ``p``, counter-clockwise when omega > 0 (labels keep
    clear of it)."""
    x, y = canvas.px(p)
    r, start, end = 22.0, math.radians(200), math.radians(-20)
    if omega < 0:
        start, end = end, start
    sx, sy = x + r * math.cos(start), y - r * math.sin(start)
    ex, ey = x + r * math.cos(end), y - r * math.sin(end)
    sweep = 1 if omega < 0 else 0  # SVG's y points down: a ccw turn on paper is sweep 0
    heading = end + (math.pi / 2 if omega > 0 else -math.pi / 2)
    hx, hy = math.cos(heading), -math.sin(heading)
    nx, ny = -hy, hx
    tip = (ex + 7 * hx, ey + 7 * hy)
    canvas.path(
        f"M{sx:.1f} {sy:.1f}A{r} {r} 0 0 {sweep} {ex:.1f} {ey:.1f}",
        [("fill", "none"), ("stroke", ROTATION), ("stroke-width", "1.6")],
    )
    canvas.path(
        f"M{tip[0]:.1f} {tip[1]:.1f}L{ex + 4 * nx:.1f} {ey + 4 * ny:.1f}"
        f"L{ex - 4 * nx:.1f} {ey - 4 * ny:.1f}z",
        [("fill", ROTATION)],
    )
    _mark(canvas, x, y, r, 8, r)


def _rotation_label(canvas: Canvas, p: Point, label: str) -> None:
    """A driver's rates under its pivot's hatching, else beside or above the pivot where that
    place is taken, else in a corner of the figure (in the rotation's colour)."""
    x, y = canvas.px(p)
    offsets = [(-30.0, 38.0, "start"), (0.0, 38.0, "middle"), (30.0, 38.0, "end")]
    offsets += [(28.0, 4.0, "start"), (-28.0, 4.0, "end"), (0.0, -28.0, "middle")]
    offsets += [(28.0, 22.0, "start"), (-28.0, 22.0, "end"), (28.0, -16.0, "start")]
    offsets += [(-28.0, -16.0, "end"), (0.0, -44.0, "middle")]
    places = [_inside((x + dx, y + dy), label, 12, side) for dx, dy, side in offsets]
    corners = [((WIDTH - PAD, HEIGHT - 8.0), "end"), ((WIDTH - PAD, 16.0), "end")]
    canvas.label([*places, *corners], label, 12, [("fill", ROTATION), FONT])


def _block(canvas: Canvas, p: Point, axis: Point) -> None:
    x, y = canvas.px(p)
    _mark(canvas, x, y, 12, 12, 12)  # the block's box whatever its guide's angle
    angle = -math.degrees(math.atan2(axis[1], axis[0]))
    canvas.add(
        element(
            "rect",
            [
                ("x", f"{x - 12:.1f}"), ("y", f"{y - 7:.1f}"), ("width", "24"), ("height", "14"),
                ("fill", "#fde68a"), ("stroke", INK), ("stroke-width", "1.2"),
                ("transform", f"rotate({angle:.2f} {x:.1f} {y:.1f})"),
            ],
        )
    )  # fmt: skip


def _driver_label(driver: Mapping[str, Any]) -> tuple[float, str]:
    if "angle_law" in driver:
        return 1.0, "φ(t)"
    omega, alpha = float(driver.get("omega", 0.0)), float(driver.get("alpha", 0.0))
    label = f"ω = {abs(omega):g} rad/s"
    if alpha:
        label += f", α = {abs(alpha):g} rad/s²"
    return omega or 1.0, label


def _pivot(joints: Sequence[Joint], ground: str, link: str) -> str:
    """The point of the revolute joint between ``link`` and the ground (a figure's turning links
    have one)."""
    pivot = ground_pivot(link, joints, ground)
    assert pivot is not None, link
    return pivot


def _disc_radius(pivot: Point, centre: Point, start: Point) -> float:
    """A disc about ``pivot`` wide enough for the groove about ``centre`` through ``start``."""
    return 1.1 * (math.dist(pivot, centre) + math.dist(centre, start))


@dataclass(frozen=True)
class _Linkage:
    """A planar scene read for drawing: its points (m), ground link and parsed joints."""

    scene: Mapping[str, Any]
    pts: dict[str, Point]
    ground: str
    joints: Sequence[Joint]

    @property
    def moving_points(self) -> list[Mapping[str, Any]]:
        return list(self.scene.get("moving_points", []))

    def pivot(self, link: str) -> Point:
        return self.pts[_pivot(self.joints, self.ground, link)]


def _linkage(scene: Mapping[str, Any]) -> str:
    """The scale bar and the axes first, then guides and paths, the links, pivots, blocks,
    points and rotations; the labels last, each where it meets no other label, bar or mark."""
    links = scene["links"]
    drawing = _Linkage(
        scene,
        {k: (float(v[0]), float(v[1])) for k, v in scene["points"].items()},
        next(k for k, v in links.items() if v.get("ground")),
        parse_linkage(scene).joints,
    )
    arcs = _arc_paths(drawing)
    canvas = _canvas(_extent(drawing, arcs))
    _scale_bar(canvas)
    _axes(canvas)
    _draw_paths(canvas, drawing, arcs)
    for name, link in links.items():
        _draw_link(canvas, drawing, name, [drawing.pts[p] for p in link["points"]])
    _draw_marks(canvas, drawing)
    _slot_angles(canvas, drawing)
    return _document(canvas, str(scene.get("title", "linkage")))


def _axes(canvas: Canvas) -> None:
    """The frame the answers are given in: x and y arrows, 34 px, from the origin (0, 0)."""
    x, y = canvas.px((0.0, 0.0))
    style: list[Attribute] = [("stroke", GUIDE), ("stroke-width", "1.2"), ("fill", "none")]
    canvas.path(f"M{x:.1f} {y:.1f}h34m-6 -4l6 4l-6 4", style)
    canvas.path(f"M{x:.1f} {y:.1f}v-34m-4 6l4 -6l4 6", style)
    canvas.keep_off((x, y), (x + 34, y), 8)
    canvas.keep_off((x, y), (x, y - 34), 8)
    canvas.label([((x + 37, y + 4), "start")], "x", 11, [("fill", GUIDE), FONT])
    canvas.label([((x - 4, y - 38), "start")], "y", 11, [("fill", GUIDE), FONT])


def _slot_angles(canvas: Canvas, drawing: _Linkage) -> None:
    """The angle dimension of each straight path through its carrier's pivot: an arc from the
    x direction to the path, labelled with the angle at the drawn instant (t = 0)."""
    for mp in drawing.moving_points:
        path = mp["path"]
        if path["type"] != "line":
            continue
        o = drawing.pivot(mp["link"])
        s, t = drawing.pts[path["start"]], drawing.pts[path["through"]]
        cross = (s[0] - o[0]) * (t[1] - o[1]) - (s[1] - o[1]) * (t[0] - o[0])
        if abs(cross) > 1e-9 * max(math.dist(o, t), 1e-12) ** 2:
            continue  # a slot off the pivot: its angle is not a dimension from O
        theta = math.atan2(t[1] - o[1], t[0] - o[0])
        x, y = canvas.px(o)
        r = 40.0
        ex, ey = x + r * math.cos(theta), y - r * math.sin(theta)
        sweep = 0 if theta >= 0 else 1
        large = 1 if abs(theta) > math.pi else 0
        style: list[Attribute] = [("stroke", GUIDE), ("stroke-width", "1"), ("fill", "none")]
        canvas.path(f"M{x:.1f} {y:.1f}h{r + 14:.0f}", [*style, ("stroke-dasharray", "3 3")])
        canvas.path(f"M{x + r:.1f} {y:.1f}A{r} {r} 0 {large} {sweep} {ex:.1f} {ey:.1f}", style)
        half = theta / 2
        label = f"θ0 = {math.degrees(theta):.4g}°"
        at = (x + (r + 8) * math.cos(half), y - (r + 8) * math.sin(half) + 4)
        canvas.label([_inside(at, label, 12, "start")], label, 12, [("fill", INK), FONT])


def _arc_paths(drawing: _Linkage) -> list[tuple[Point, float]]:
    """The centre and radius r = |C S| of each moving point's arc path."""
    arcs = []
    for mp in drawing.moving_points:
        path = mp["path"]
        if path["type"] == "arc":
            c, s = drawing.pts[path["center"]], drawing.pts[path["start"]]
            arcs.append((c, math.dist(c, s)))
    return arcs


def _extent(drawing: _Linkage, arcs: Sequence[tuple[Point, float]]) -> list[Point]:
    """The points to fit on the canvas: the scene's points, each arc path's and each disc's box."""
    extent = list(drawing.pts.values())
    for c, r in arcs:
        extent += [(c[0] - r, c[1] - r), (c[0] + r, c[1] + r)]
    for mp in drawing.moving_points:
        if mp["path"]["type"] == "arc":
            o = drawing.pivot(mp["link"])
            pts, path = drawing.pts, mp["path"]
            reach = _disc_radius(o, pts[path["center"]], pts[path["start"]])
            extent += [(o[0] - reach, o[1] - reach), (o[0] + reach, o[1] + reach)]
    return extent


def _draw_paths(canvas: Canvas, drawing: _Linkage, arcs: Sequence[tuple[Point, float]]) -> None:
    """Each slider's guide (solid when fixed, dashed on a moving link) through its point along
    its axis, each arc path dashed, each straight path as a wide slot."""
    pts, ground = drawing.pts, drawing.ground
    for j in drawing.scene["joints"]:
        if j["type"] == "revolute":
            continue
        p, u = pts[j["point"]], (float(j["axis"][0]), float(j["axis"][1]))
        n = math.hypot(*u)
        u = (u[0] / n, u[1] / n)
        reach = 0.35 * (WIDTH - 2 * MARGIN) / canvas.view.scale
        a, b = (
            (p[0] - reach * u[0], p[1] - reach * u[1]),
            (p[0] + reach * u[0], p[1] + reach * u[1]),
        )
        fixed = j["links"][0] == ground
        _line(canvas, a, b, GUIDE, 1.4 if fixed else 1.0, "" if fixed else "5 3")
        canvas.keep_off(canvas.px(a), canvas.px(b), 3)
    for c, r in arcs:
        style = [("fill", "none"), ("stroke", GUIDE), ("stroke-width", "1.4")]
        canvas.circle(canvas.px(c), r * canvas.view.scale, [*style, ("stroke-dasharray", "5 3")])
    for mp in drawing.moving_points:
        if mp["path"]["type"] == "line":
            a, b = pts[mp["path"]["start"]], pts[mp["path"]["through"]]
            _line(canvas, a, b, GUIDE, 6, "")
            canvas.keep_off(canvas.px(a), canvas.px(b), 8)


def _draw_link(canvas: Canvas, drawing: _Linkage, name: str, members: list[Point]) -> None:
    """A moving link: a disc where it carries a groove, a plate with three or more points, else a
    bar."""
    if name == drawing.ground or len(members) < 2:
        return
    paths = [mp["path"] for mp in drawing.moving_points if mp["link"] == name]
    if any(path["type"] == "arc" for path in paths):  # a turning disc carrying a groove
        pivot, path = drawing.pivot(name), paths[0]
        radius = _disc_radius(pivot, drawing.pts[path["center"]], drawing.pts[path["start"]])
        canvas.circle(
            canvas.px(pivot),
            radius * canvas.view.scale,
            [
                ("fill", "#dbeafe"),
                ("fill-opacity", "0.5"),
                ("stroke", LINK),
                ("stroke-width", "2.5"),
            ],
        )
    elif len(members) >= 3:
        plate = [("fill", "#dbeafe"), ("fill-opacity", "0.6"), ("stroke", LINK)]
        plate += [("stroke-width", "2.5"), ("stroke-linejoin", "round")]
        canvas.points("polygon", map(canvas.px, members), plate)
        for a, b in pairwise([*members, members[0]]):
            canvas.keep_off(canvas.px(a), canvas.px(b), 4)
    else:
        _line(canvas, members[0], members[1], LINK, 3.5)
        canvas.keep_off(canvas.px(members[0]), canvas.px(members[1]), 5)


def _draw_marks(canvas: Canvas, drawing: _Linkage) -> None:
    """The fixed pivots hatched, the sliders' blocks, each driver's rotation about its pivot,
    then the labels: every point's name, each moving point's start, each rotation's rates."""
    pts, scene = drawing.pts, drawing.scene
    for j in scene["joints"]:
        if j["type"] == "revolute" and drawing.ground in j["links"]:
            _ground_pivot(canvas, pts[j["point"]])
    for j in scene["joints"]:
        if j["type"] != "revolute":
            _block(canvas, pts[j["point"]], (float(j["axis"][0]), float(j["axis"][1])))
    for p in pts.values():
        canvas.circle(
            canvas.px(p), "3.5", [("fill", "white"), ("stroke", INK), ("stroke-width", "1.4")]
        )
        _mark(canvas, *canvas.px(p), 4, 4, 4)
    rotations = [(drawing.pivot(d["link"]), *_driver_label(d)) for d in scene["drivers"]]
    for pivot, omega, _ in rotations:
        _rotation(canvas, pivot, omega)
    for name, p in pts.items():
        _text(canvas, p, name)
    for mp in drawing.moving_points:
        start = pts[mp["path"]["start"]]
        _text(canvas, start, f"{mp['name']} (t = 0)", dx=7, dy=16, color=ROTATION)
    for pivot, _, label in rotations:
        _rotation_label(canvas, pivot, label)


def _oblique(p: Sequence[float]) -> Point:
    """Cabinet-style oblique view: y to the right, z up, x receding down-left at 30 deg."""
    return (p[1] - 0.5 * p[0] * math.cos(math.pi / 6), p[2] - 0.5 * p[0] * math.sin(math.pi / 6))


def _spatial(scene: Mapping[str, Any]) -> str:
    joints = scene["joints"]
    points = {k: v["position"] for k, v in scene["points"].items()}
    chain = [j["origin"] for j in joints] + [points[k] for k in points]
    flat = [_oblique(p) for p in chain] + [_oblique([0, 0, -0.15])]
    canvas = _canvas(flat)
    _scale_bar(canvas)
    o = (0.0, 0.0)
    axes = [
        (_oblique(axis), label)
        for axis, label in (((0.3, 0, 0), "x"), ((0, 0.3, 0), "y"), ((0, 0, 0.3), "z"))
    ]
    for end, _ in axes:
        _line(canvas, o, end, GUIDE, 1.0, "3 3")
    _ground_pivot(canvas, _oblique([0, 0, 0]))
    route = [_oblique(j["origin"]) for j in joints] + [_oblique(p) for p in points.values()]
    for a, b in pairwise(route):
        _line(canvas, a, b, LINK, 3.5)
        canvas.keep_off(canvas.px(a), canvas.px(b), 5)
    rates = []  # each joint's axis drawn from its origin, its rate at the tip
    for k, j in enumerate(joints, start=1):
        start = _oblique(j["origin"])
        tip = _oblique([j["origin"][i] + 0.2 * j["axis"][i] for i in range(3)])
        _line(canvas, start, tip, ROTATION, 1.8)
        canvas.keep_off(canvas.px(start), canvas.px(tip), 3)
        rates.append((tip, f"ω{k} = {j['rate']:g}"))
    for position in points.values():
        canvas.circle(canvas.px(_oblique(position)), "3.5", [("fill", "white"), ("stroke", INK)])
        _mark(canvas, *canvas.px(_oblique(position)), 4, 4, 4)
    for end, label in axes:
        _text(canvas, end, label, color=GUIDE)
    for tip, label in rates:
        _text(canvas, tip, label, color=ROTATION)
    for name, position in points.items():
        _text(canvas, _oblique(position), name, dy=16)
    _text(canvas, _oblique(joints[1]["origin"]), "O2", dx=-24)
    _text(canvas, (0.0, 0.0), "O", dx=-16)
    return _document(canvas, str(scene.get("title", "spatial chain")))


def _arrow(canvas: Canvas, p: Point, angle: float, length: float, color: str) -> None:
    """An arrow of ``length`` (m) from the world point ``p`` at ``angle`` (rad)."""
    tip = (p[0] + length * math.cos(angle), p[1] + length * math.sin(angle))
    _line(canvas, p, tip, color, 2.0)
    x, y = canvas.px(tip)
    hx, hy = math.cos(angle), -math.sin(angle)  # the drawing's y points down
    canvas.path(
        f"M{x + 6 * hx:.1f} {y + 6 * hy:.1f}L{x - 4 * hy:.1f} {y + 4 * hx:.1f}"
        f"L{x + 4 * hy:.1f} {y - 4 * hx:.1f}z",
        [("fill", color)],
    )


def _motion_task(task: Mapping[str, Any]) -> str:
    """The coupler's positions: each point P_j with an arrow along the coupler's angle there
    (the angles are in the statement), and the coupler B1 C1 P1 of the first position drawn as
    a plate (the fixed pivots are asked, so they are not drawn)."""
    positions = task["positions"]
    places = [(float(p["point"][0]), float(p["point"][1])) for p in positions]
    b1, c1 = ((float(q[0]), float(q[1])) for q in task["moving_pivots"])
    size = math.dist(b1, c1)
    heads = [
        (x + 0.3 * size * math.cos(math.radians(p["angle_deg"])),
         y + 0.3 * size * math.sin(math.radians(p["angle_deg"])))
        for (x, y), p in zip(places, positions, strict=True)
    ]  # fmt: skip
    canvas = _canvas([*places, *heads, b1, c1])
    _scale_bar(canvas)
    if "bisector_offsets" in task:  # two positions: the free choice the task states, top left
        d_a, d_d = task["bisector_offsets"]
        lines = ["on the bisectors of B1B2, C1C2:", f"dA = {d_a:g} m, dD = {d_d:g} m"]
        for k, line in enumerate(lines):
            canvas.label([((PAD, 16.0 + 15 * k), "start")], line, 12, [("fill", INK), FONT])
    plate = [canvas.px(q) for q in (b1, c1, places[0])]
    canvas.points("polygon", plate, [("fill", "#dbeafe"), ("stroke", LINK), ("stroke-width", 2)])
    for k, (place, p) in enumerate(zip(places, positions, strict=True), start=1):
        _arrow(canvas, place, math.radians(p["angle_deg"]), 0.3 * size, ROTATION)
        canvas.circle(canvas.px(place), "3.5", [("fill", "white"), ("stroke", INK)])
        _text(canvas, place, f"P{k}", dx=-24, dy=4 + 12 * (k - 2))  # stacked: poses are near
    for name, q in (("B1", b1), ("C1", c1)):
        canvas.circle(canvas.px(q), "3.5", [("fill", "white"), ("stroke", INK)])
        _text(canvas, q, name, dy=16)
    return _document(canvas, "coupler positions to pass through")


def _range_arc(
    canvas: Canvas, centre: Point, angles_deg: Sequence[float], radius: float, label: str
) -> None:
    """Two rays from ``centre`` at the ends of an angle range and the arc between them, from
    the first end to the second, labelled with the range."""
    first, second = (math.radians(a) for a in angles_deg)
    for angle in (first, second):
        tip = (centre[0] + radius * math.cos(angle), centre[1] + radius * math.sin(angle))
        _line(canvas, centre, tip, LINK, 1.4)
    r = 0.6 * radius
    x0, y0 = canvas.px((centre[0] + r * math.cos(first), centre[1] + r * math.sin(first)))
    x1, y1 = canvas.px((centre[0] + r * math.cos(second), centre[1] + r * math.sin(second)))
    pixels = r * canvas.view.scale
    large = 1 if abs(second - first) > math.pi else 0
    sweep = 0 if second > first else 1  # SVG's y points down: a ccw arc on paper is sweep 0
    canvas.path(
        f"M{x0:.1f} {y0:.1f}A{pixels:.1f} {pixels:.1f} 0 {large} {sweep} {x1:.1f} {y1:.1f}",
        [("fill", "none"), ("stroke", ROTATION), ("stroke-width", "1.6")],
    )
    middle = 0.5 * (first + second)
    _text(
        canvas,
        (centre[0] + radius * math.cos(middle), centre[1] + radius * math.sin(middle)),
        label,
        dx=-20,
        color=ROTATION,
    )


def _function_task(task: Mapping[str, Any]) -> str:
    """The ground link A D to scale, and at A (D) the crank's (rocker's) angle range from the
    ground line (the links themselves are asked, so they are not drawn)."""
    d = float(task["ground_length"])
    a, dpoint = (0.0, 0.0), (d, 0.0)
    radius = 0.45 * d
    extent = [a, dpoint]
    for centre in (a, dpoint):
        extent += [
            (centre[0] + radius * math.cos(math.radians(t)),
             centre[1] + radius * math.sin(math.radians(t)))
            for t in range(0, 360, 30)
        ]  # fmt: skip
    canvas = _canvas(extent)
    _scale_bar(canvas)
    _line(canvas, a, dpoint, GUIDE, 1.4, "6 4")
    for centre, key, symbol in ((a, "input_range_deg", "θ2"), (dpoint, "output_range_deg", "θ4")):
        ends = task[key]
        _range_arc(canvas, centre, ends, radius, f"{symbol}: {ends[0]:g}° → {ends[1]:g}°")
    for name, q in (("A", a), ("D", dpoint)):
        _ground_pivot(canvas, q)
        canvas.circle(canvas.px(q), "3.5", [("fill", "white"), ("stroke", INK)])
        _text(canvas, q, name, dx=-16, dy=-6)
    return _document(canvas, "ground link and angle ranges of the function generator")


def figure_svg(scene: Mapping[str, Any]) -> str:
    """The exercise's figure (a standalone SVG document); for a synthesis task, what the task
    gives (the positions, or the ground link and the angle ranges), never the answer."""
    if is_task(scene):
        return _motion_task(scene) if scene["task"] == "motion" else _function_task(scene)
    if scene.get("kind") == "gear_train":
        return train_figure(parse_gear_train(scene))
    if scene.get("kind") == "cam":  # at cam angle 0, the pressure angle marked, not given
        return cam_figure(cam_context(parse_cam(scene), 0.0), labelled=False)
    return _spatial(scene) if scene.get("kind") == "spatial_chain" else _linkage(scene)

"""The worked solution of a synthesis (POST /synthesis): the construction in words and equations,
with the synthesis' own numbers, and the checks read from the analysis.

Motion (three positions): the poles P12, P13, P23; the centre point A of B's places B1, B2, B3,
the point equally far from the three (|AB1| = |AB2| = |AB3|, where the perpendicular bisectors
meet), and D likewise of C1, C2, C3 (with the fixed pivots given, the circle points are found
the same way from A and D seen from the coupler); two positions, the stated choice on each
bisector (with the task's offsets d, the pivot M + d n: the chord's midpoint M, its unit normal
n to the left, and |AB1| = |AB2|). Function: the precision points, Freudenstein's equation

    K1 cos(theta_4) - K2 cos(theta_2) + K3 = cos(theta_2 - theta_4)

written at each of them with the numbers (a linear system in K1, K2, K3), and the lengths
a = d / K1, c = d / K2, b^2 = a^2 + c^2 + d^2 - 2 a c K3. Quick return: alpha = 180 (Q - 1) /
(Q + 1), the limit positions and a, b from |AC| at them. Every step ends with the checks that
the solver's analysis of the returned scene gives. Each step is built with ``StepBuilder``:
its shown arithmetic is checked (``Check`` relations) to recompute from its shown digits. A
figure of the construction (the places of the moving pivots, the circles through them about the
fixed pivots, the linkage in its first position) is drawn on the one SVG canvas
(``solver.teaching.svg``).
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from typing import Any

from solver.model.scene import parse_linkage
from solver.solutions.builder import StepBuilder
from solver.solutions.equation import Equation, Frac, Num, Pt, Signed, Sym
from solver.solutions.format import Formatter
from solver.solutions.model import Step
from solver.teaching.svg import Attribute, Canvas, View

FIGURE_SIZE = 320.0  # px: the construction's figure, square
FIGURE_MARGIN = 24.0

JSON = Mapping[str, Any]


def _builder(kind: str, title: str) -> StepBuilder:
    return StepBuilder(Formatter(), f"synthesis.{kind}", title)


def _point(body: JSON, name: str) -> tuple[float, float]:
    x, y = body["scene"]["points"][name]
    return float(x), float(y)


def _checks_step(body: JSON, what: str) -> Step:
    """The checks by analysis and the defects, in words with the numbers; an error that is
    rounding noise at the linkage's scale (its size) reads 0."""
    b = _builder("checks", "Checks by analysis of the synthesised linkage")
    size = parse_linkage(body["scene"]).size
    for k, check in enumerate(body["checks"]):
        angle = b.value(f"crank angle {k + 1}", math.radians(check["driver_angle_deg"]), "rad")
        error = b.value(f"error {k + 1}", check["error"], "", reference=size)
        reached = "reaches it" if check["reached"] else "does not reach it on this assembly"
        b.say(
            f"{what} {k + 1}: with the crank at ",
            Num(angle, unit=True),
            f" the analysed linkage {reached} (off by ",
            Num(error),
            "). ",
        )
    defects = body["defects"]
    found = [name for name in ("branch", "order", "grashof") if defects[name]]
    b.say(
        f"Grashof class: {defects['grashof_class']}. "
        + ("Defects: " + ", ".join(found) + "." if found else "No branch, order or Grashof defect.")
    )
    for warning in body["warnings"]:
        b.say(" " + warning[0].upper() + warning[1:] + ".")
    return b.build()


def _lengths_step(body: JSON) -> Step:
    """The four link lengths from the pivots at the first position (|AB|, |BC|, |DC|, |AD|)."""
    b = _builder("lengths", "The link lengths")
    for link, (first, second) in (
        ("crank", ("A", "B")),
        ("coupler", ("B", "C")),
        ("rocker", ("D", "C")),
        ("ground", ("A", "D")),
    ):
        p, q = _point(body, first), _point(body, second)
        vector = b.value(f"{first}{second}", (q[0] - p[0], q[1] - p[1]), "m")
        length = b.value(link, body["dimensions"][link], "m", ("dimensions", link))
        b.check("norm", length, vector)
        b.line(Equation.of(Sym(f"|{first}{second}|", f"|{first}{second}|"), Num(length, True)))
        b.say(f"The {link} {first}{second} is ", Num(length, unit=True), ". ")
    return b.build()


def _centre_step(body: JSON, fixed: str, moving: str, places: Sequence[Sequence[float]]) -> Step:
    """The point equally far from the places (the centre of the circle through them)."""
    name = "centre point" if fixed in ("A", "D") else "circle point"
    b = _builder("centre", f"The {name} {fixed} of {moving}1, {moving}2, {moving}3")
    centre = b.value(fixed, _point(body, fixed), "m", ("scene", "points", fixed))
    radius = math.dist(_point(body, fixed), places[0])
    r = b.value(f"|{fixed}{moving}|", radius, "m")
    for j, place in enumerate(places, start=1):
        at = b.value(f"{moving}{j}", tuple(place), "m")
        cx, cy = b.vector(centre)
        arm = b.value(f"{fixed}{moving}{j}", (place[0] - cx, place[1] - cy), "m")
        b.check("sum", arm, at, -centre)
        b.check("norm", r, arm)
        b.line(
            Equation.of(Sym(f"|{fixed}{moving}_{j}|", f"|{fixed}{moving}{j}|"), Num(r, unit=True))
        )
        b.say(f"{moving}{j} = ", Pt(at, "m"), "; ")
    b.say(
        f"{fixed} = ",
        Pt(centre, "m"),
        f" is where the perpendicular bisectors of {moving}1{moving}2 and {moving}2{moving}3 "
        f"meet: equally far from the three places, ",
        Num(r, unit=True),
        f", so {moving} turns about {fixed} through all three positions.",
    )
    return b.build()


def _poles_step(body: JSON) -> Step:
    b = _builder("poles", "The poles of the coupler's displacements")
    for name, pole in body["construction"]["poles"].items():
        if pole is None:
            b.say(f"{name}: the coupler translates between these positions (no pole). ")
            continue
        ref = b.value(name, tuple(pole), "m", ("construction", "poles", name))
        b.say(
            f"{name} = ",
            Pt(ref, "m"),
            f": the point about which the coupler turns from position {name[1]} to {name[2]}. ",
        )
    b.say(
        "Every centre point sees each chord B_jB_k under half the coupler's turn, and the "
        "perpendicular bisector of every chord passes through the pole P_jk."
    )
    return b.build()


def _offset_step(body: JSON, fixed: str, moving: str, offset: float) -> Step:
    """A = M + d n on the perpendicular bisector of B1B2: M = (B1 + B2)/2, n = k x (B2 - B1) /
    |B2 - B1| (the chord turned 90 deg to its left), and |AB1| = |AB2|."""
    places = body["construction"]["places"][moving]
    b = _builder("offset", f"The fixed pivot {fixed} on the bisector of {moving}1{moving}2")
    first = b.value(f"{moving}1", tuple(places[0]), "m", ("construction", "places", moving, 0))
    second = b.value(f"{moving}2", tuple(places[1]), "m", ("construction", "places", moving, 1))
    (x1, y1), (x2, y2) = places[0], places[1]
    chord = b.value(f"{moving}1{moving}2", (x2 - x1, y2 - y1), "m")
    b.check("sum", chord, second, -first)
    middle = b.value("M", (0.5 * (x1 + x2), 0.5 * (y1 + y2)), "m")
    b.check("sum", middle, first, second, factor=0.5)
    length = b.value(f"|{moving}1{moving}2|", math.hypot(x2 - x1, y2 - y1), "m")
    b.check("norm", length, chord)
    one = b.value("k", 1.0, "")
    turned = b.value("k x chord", (y1 - y2, x2 - x1), "m")
    b.check("cross", turned, one, chord)
    norm = math.hypot(x2 - x1, y2 - y1)
    normal = b.value("n", ((y1 - y2) / norm, (x2 - x1) / norm), "")
    b.check("quotient", normal, turned, length)
    index = 0 if fixed == "A" else 1
    d = b.value(f"d{fixed}", offset, "m", ("construction", "bisector_offsets", index))
    nx, ny = b.vector(normal)
    step = b.value(f"d{fixed} n", (offset * nx, offset * ny), "m")
    b.check("product", step, d, normal)
    centre = b.value(fixed, _point(body, fixed), "m", ("scene", "points", fixed))
    b.check("sum", centre, middle, step)
    b.line(Equation.of(Sym("M", "M"), Pt(middle, "m")))
    b.line(Equation.of(Sym(r"\vec n", "n"), Pt(normal)))
    b.line(Equation.of(Sym(fixed, fixed), Pt(centre, "m")))
    cx, cy = b.vector(centre)
    radius = b.value(f"|{fixed}{moving}|", math.dist((cx, cy), places[0]), "m")
    for j, place in ((1, first), (2, second)):
        arm = b.value(f"{fixed}{moving}{j}", (places[j - 1][0] - cx, places[j - 1][1] - cy), "m")
        b.check("sum", arm, place, -centre)
        b.check("norm", radius, arm)
    b.say(
        f"{moving}1 = ", Pt(first, "m"), f" and {moving}2 = ", Pt(second, "m"),
        ": the chord's midpoint M = ", Pt(middle, "m"), ", its length ", Num(length, unit=True),
        f", its unit normal to the left of {moving}1 -> {moving}2 n = ", Pt(normal),
        f". {fixed} = M + d{fixed} n with d{fixed} = ", Num(d, unit=True), ": ",
        Pt(centre, "m"), f", equally far from {moving}1 and {moving}2 (",
        Num(radius, unit=True), f"), so {moving} turns about {fixed} through both positions.",
    )  # fmt: skip
    return b.build()


def _motion_steps(body: JSON) -> list[Step]:
    places = body["construction"]["places"]
    steps = [_poles_step(body)]
    if len(body["checks"]) == 3:
        steps.append(_centre_step(body, "A", "B", places["B"]))
        steps.append(_centre_step(body, "D", "C", places["C"]))
    else:
        b = _builder("choice", "Two positions: a free choice on each bisector")
        b.say(
            body["construction"]["choices"][0][0].upper()
            + body["construction"]["choices"][0][1:]
            + "."
        )
        steps.append(b.build())
        offsets = body["construction"].get("bisector_offsets")
        if offsets is not None:
            steps.append(_offset_step(body, "A", "B", offsets[0]))
            steps.append(_offset_step(body, "D", "C", offsets[1]))
    steps.append(_lengths_step(body))
    steps.append(_checks_step(body, "Position"))
    return steps


def _function_steps(body: JSON) -> list[Step]:
    k = body["freudenstein"]
    b = _builder("precision", "Precision points")
    spacing = "Chebyshev spacing" if body["spacing"] == "chebyshev" else "the given points"
    b.say(f"The three precision points ({spacing}): ")
    for j, p in enumerate(body["precision_points"], start=1):
        x = b.value(f"x{j}", p["x"], "")
        y = b.value(f"y{j}", p["y"], "")
        t2 = b.value(f"theta_2,{j}", math.radians(p["input_angle_deg"]), "rad")
        t4 = b.value(f"theta_4,{j}", math.radians(p["output_angle_deg"]), "rad")
        b.say(
            f"x{j} = ", Num(x), f", y{j} = ", Num(y), ", theta_2 = ", Num(t2, unit=True),
            ", theta_4 = ", Num(t4, unit=True), "; ",
        )  # fmt: skip
    steps = [b.build()]
    b = _builder("freudenstein", "Freudenstein's equation at the precision points")
    K1 = b.value("K1", k["K1"], "", ("freudenstein", "K1"))
    K2 = b.value("K2", k["K2"], "", ("freudenstein", "K2"))
    K3 = b.value("K3", k["K3"], "", ("freudenstein", "K3"))
    one = b.value("1", 1.0, "")
    b.say(
        "K1 cos(theta_4) - K2 cos(theta_2) + K3 = cos(theta_2 - theta_4), with K1 = d/a, "
        "K2 = d/c, K3 = (a^2 - b^2 + c^2 + d^2)/(2ac), written at each point: "
    )
    for j, p in enumerate(body["precision_points"], start=1):
        th2, th4 = math.radians(p["input_angle_deg"]), math.radians(p["output_angle_deg"])
        c4 = b.value(f"cos theta_4,{j}", math.cos(th4), "")
        c2 = b.value(f"K2 coefficient -cos theta_2,{j}", -math.cos(th2), "")
        right = b.value(f"cos(theta_2 - theta_4),{j}", math.cos(th2 - th4), "")
        b.check("linear", right, c4, K1, c2, K2, one, K3)
        b.line(
            Equation.of(
                (Num(c4), Sym(r"\,K_1 ", " K1 "), Signed(c2), Sym(r"\,K_2 + K_3", " K2 + K3")),
                Num(right),
            )
        )
    b.say(
        "Solved: K1 = ", Num(K1), ", K2 = ", Num(K2), ", K3 = ", Num(K3), "."
    )  # fmt: skip
    steps.append(b.build())
    b = _builder("lengths", "The link lengths from K1, K2, K3")
    K1, K2, K3 = (b.value(n, k[n], "", ("freudenstein", n)) for n in ("K1", "K2", "K3"))
    d = b.value("d", k["d"], "m", ("freudenstein", "d"))
    a = b.value("a", k["a"], "m", ("freudenstein", "a"))
    c = b.value("c", k["c"], "m", ("freudenstein", "c"))
    coupler = b.value("b", k["b"], "m", ("freudenstein", "b"))
    b.check("quotient", a, d, K1)
    b.check("quotient", c, d, K2)
    a2, b2, c2, d2 = (
        b.value(f"{n}^2", b.scalar(r) ** 2, "m^2")
        for n, r in (("a", a), ("b", coupler), ("c", c), ("d", d))
    )
    ac = b.value("2acK3", 2 * k["a"] * k["c"] * k["K3"], "m^2")
    b.check("product", ac, a, c, K3, factor=2.0)
    b.check("sum", b2, a2, c2, d2, -ac)
    b.line(Equation.of(Sym("a", "a"), Frac(d, K1), Num(a, unit=True)))
    b.line(Equation.of(Sym("c", "c"), Frac(d, K2), Num(c, unit=True)))
    b.line(
        Equation.of(
            Sym("b^2", "b^2"),
            Sym("a^2 + c^2 + d^2 - 2acK_3", "a^2 + c^2 + d^2 - 2acK3"),
            Num(b2, unit=True),
        )
    )
    b.say(
        "a = d/K1 = ",
        Num(a, unit=True),
        ", c = d/K2 = ",
        Num(c, unit=True),
        ", b = ",
        Num(coupler, unit=True),
        ".",
    )
    if k["a"] < 0 or k["c"] < 0:
        b.say(" A negative length is the link pointing the other way (its angle + 180 deg).")
    steps.append(b.build())
    b = _builder("structural", "Structural error")
    se = body["structural_error"]
    if se["max"] is not None:
        worst = b.value("max error", se["max"], "")
        at = b.value("at x", se["at_x"], "")
        b.say(
            "Over the range the generated y differs from f(x) by at most ",
            Num(worst),
            " (at x = ",
            Num(at),
            "); it is zero at the precision points.",
        )
    steps.append(b.build())
    steps.append(_checks_step(body, "Precision point"))
    return steps


def _quick_return_steps(body: JSON) -> list[Step]:
    b = _builder("alpha", "The crank's turn between the limit positions")
    ratio = b.value("Q", body["time_ratio"], "")
    alpha = b.value("alpha", math.radians(body["construction"]["alpha_deg"]), "rad")
    b.say(
        "The crank turns through 180 + alpha for the slow stroke and 180 - alpha for the fast "
        "one: Q = (180 + alpha)/(180 - alpha), so alpha = 180 (Q - 1)/(Q + 1) = ",
        Num(alpha, unit=True), " for Q = ", Num(ratio), ".",
    )  # fmt: skip
    steps = [b.build()]
    b = _builder("limits", "The limit positions and the crank pivot")
    limits = body["construction"]["limit_positions"]
    stretched = b.value("C stretched", tuple(limits["stretched"]), "m")
    folded = b.value("C folded", tuple(limits["folded"]), "m")
    A = b.value("A", _point(body, "A"), "m")
    L1 = b.value("|AC stretched|", math.dist(limits["stretched"], _point(body, "A")), "m")
    L2 = b.value("|AC folded|", math.dist(limits["folded"], _point(body, "A")), "m")
    arm1 = b.value(
        "AC stretched",
        (limits["stretched"][0] - b.vector(A)[0], limits["stretched"][1] - b.vector(A)[1]),
        "m",
    )
    arm2 = b.value(
        "AC folded",
        (limits["folded"][0] - b.vector(A)[0], limits["folded"][1] - b.vector(A)[1]),
        "m",
    )
    b.check("sum", arm1, stretched, -A)
    b.check("sum", arm2, folded, -A)
    b.check("norm", L1, arm1)
    b.check("norm", L2, arm2)
    crank = b.value("a", body["dimensions"]["crank"], "m", ("dimensions", "crank"))
    coupler = b.value("b", body["dimensions"]["coupler"], "m", ("dimensions", "coupler"))
    b.check("sum", crank, L1, -L2, factor=0.5)
    b.check("sum", coupler, L1, L2, factor=0.5)
    b.say(
        "At the limit positions crank and coupler are in line: C = ", Pt(stretched, "m"),
        " stretched out (|AC| = b + a = ", Num(L1, unit=True), ") and C = ", Pt(folded, "m"),
        " folded (|AC| = b - a = ", Num(L2, unit=True), "). The crank pivot A sees the chord "
        "between them under alpha. So a = ", Num(crank, unit=True), " and b = ",
        Num(coupler, unit=True), ". ", body["construction"]["choice"][0].upper(),
        body["construction"]["choice"][1:] + ".",
    )  # fmt: skip
    steps.append(b.build())
    steps.append(_lengths_step(body))
    steps.append(_checks_step(body, "Limit position"))
    return steps


def construction_figure(body: JSON) -> str:
    """The construction as an SVG: the linkage at its first position, the fixed pivots, the
    places of the moving pivots (motion) or the limit positions (quick return) with the
    circles through them about the fixed pivots."""
    names = [n for n in ("A", "B", "C", "D", "P") if n in body["scene"]["points"]]
    points = {n: _point(body, n) for n in names}
    extra: list[tuple[str, tuple[float, float]]] = []
    construction = body.get("construction", {})
    for moving, places in construction.get("places", {}).items():
        if moving in ("B", "C"):
            extra += [
                (f"{moving}{j + 1}", (float(p[0]), float(p[1]))) for j, p in enumerate(places)
            ]
    for name, place in construction.get("limit_positions", {}).items():
        extra.append((f"C {name}", (float(place[0]), float(place[1]))))
    everything = list(points.values()) + [p for _, p in extra]
    view = View.centred(everything, FIGURE_SIZE, FIGURE_MARGIN)
    canvas = Canvas(view)
    thin: list[Attribute] = [("stroke", "#888"), ("fill", "none"), ("stroke-width", 1)]
    for centre, moving in (("A", "B"), ("D", "C")):
        radius = math.dist(points[centre], points[moving]) * view.scale / view.per
        canvas.circle(canvas.px(points[centre]), radius, [*thin, ("stroke-dasharray", "4 3")])
    bar: list[Attribute] = [("stroke", "#222"), ("stroke-width", 2)]
    for first, second in (("A", "B"), ("B", "C"), ("D", "C")):
        canvas.line(canvas.px(points[first]), canvas.px(points[second]), bar)
    if "P" in points:
        canvas.points("polygon", [canvas.px(points[n]) for n in ("B", "C", "P")],
                      [("fill", "#cde"), ("stroke", "#222")])  # fmt: skip
    for label, place in extra:
        canvas.circle(canvas.px(place), 2.5, [("fill", "#c33")])
        x, y = canvas.px(place)
        canvas.text((x + 4, y - 4), label, [("font-size", 11), ("fill", "#c33")])
    for name, place in points.items():
        canvas.circle(canvas.px(place), 3.5, [("fill", "#fff"), ("stroke", "#222")])
        x, y = canvas.px(place)
        canvas.text((x + 5, y + 13), name, [("font-size", 12)])
    return canvas.document(
        [("width", FIGURE_SIZE), ("height", FIGURE_SIZE),
         ("viewBox", f"0 0 {FIGURE_SIZE:g} {FIGURE_SIZE:g}")]
    )  # fmt: skip


def synthesis_steps(body: JSON) -> list[Step]:
    """The worked solution of a /synthesis body, step by step, the first with the figure."""
    task = body["task"]
    if task == "motion":
        steps = _motion_steps(body)
    elif task == "function":
        steps = _function_steps(body)
    else:
        steps = _quick_return_steps(body)
    first = steps[0]
    return [
        Step(first.kind, first.title, first.latex, first.text, first.values, first.checks,
             construction_figure(body)),
        *steps[1:],
    ]  # fmt: skip

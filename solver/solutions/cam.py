"""The worked solution of a cam at one cam angle (kind ``cam.*``), in Norton's notation (Design of
Machinery, ch. 8).

At the cam angle theta the follower is in segment i, which starts at theta_0 and lasts beta;
x = (theta - theta_0) / beta. The steps:

- the data, with a figure of the cam turned to theta, the follower, the common normal at the
  contact and the pressure angle;
- the segment's law y(x), y'(x), y''(x), y'''(x) written out with the numbers (a modified
  trapezoid or sine piece by piece, from the piece's start);
- s = s_0 +- h y, ds/dtheta = +-h y' / beta, d2s/dtheta2 = +-h y'' / beta^2,
  d3s/dtheta3 = +-h y''' / beta^3, and by the chain rule v = (ds/dtheta) |omega|,
  a = (d2s/dtheta2) omega^2, j = (d3s/dtheta3) |omega|^3;
- the pressure angle: translating, phi = arctan((ds/dtheta - epsilon) / (sqrt(R_p^2 - epsilon^2)
  + s)) (Norton eq. 8.31); oscillating, phi = arctan((l (ds/dtheta - 1) + d cos beta) /
  (d sin beta)); a flat face, phi = 0;
- the radius of curvature: translating knife or roller, of the pitch curve
  rho_p = (A^2 + B^2)^(3/2) / (A^2 + B (B + s') - A s''), A = sqrt(R_p^2 - epsilon^2) + s,
  B = s' - epsilon (Norton eq. 8.33 with the offset), the cam surface's rho = rho_p - r_f;
  oscillating, rho_p = -|u|^3 / (u x w), u = P' - J P, w = P'' - 2 J P' - P; a flat face, the
  envelope's rho = h + d2h/dalpha2 (translating: R_b + s + s'', Norton eq. 8.37);
- the fundamental law of cam design: s, v and a at both ends of the segment against the
  neighbouring segments';
- the summary.

Every number the solver answers enters with its path in the /analyze body of the same cam angle
(``source``), every step's arithmetic as checks, so that the shown numbers recompute.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from fractions import Fraction
from typing import Any, NamedTuple

import numpy as np

from solver.cams.analysis import JUMP_TOLERANCE, PRESSURE_ANGLE_LIMIT_DEG, analyze_cam
from solver.cams.geometry import Lift, follower_lift, pitch_curve_tangent, pitch_point
from solver.cams.laws import LAWS, MODIFIED_SINE, MODIFIED_TRAPEZOID, AccelerationPieces
from solver.cams.model import CamScene, Segment
from solver.solutions.builder import StepBuilder
from solver.solutions.equation import (
    CDOT,
    Alt,
    Boxed,
    Equation,
    Num,
    Paren,
    Piece,
    Pt,
    Ref,
    Sym,
    latex_only,
)
from solver.solutions.figures import nice_scale
from solver.solutions.format import Formatter
from solver.solutions.model import Mistake, Solution, Step, Value
from solver.teaching.mistakes import cam_beta_in_degrees, cam_rate_without_omega, typical_mistake
from solver.teaching.svg import Canvas, View, element

JSON = dict[str, Any]
DEG = math.pi / 180.0
# the polynomial laws by their coefficients of y(x) (power: coefficient); the derivatives follow
POLYNOMIALS = {
    "polynomial_345": {3: 10.0, 4: -15.0, 5: 6.0},
    "polynomial_4567": {4: 35.0, 5: -84.0, 6: 70.0, 7: -20.0},
}
PIECEWISE = {"modified_trapezoid": MODIFIED_TRAPEZOID, "modified_sine": MODIFIED_SINE}
LAW_TITLES = {
    "uniform": "uniform motion (constant velocity)",
    "harmonic": "simple harmonic motion",
    "cycloidal": "cycloidal motion",
    "polynomial_345": "the 3-4-5 polynomial",
    "polynomial_4567": "the 4-5-6-7 polynomial",
    "modified_trapezoid": "the modified trapezoid",
    "modified_sine": "the modified sine",
}
DERIVATIVES = (("y", "y", "y"), ("y'", "y'", "dy"), ("y''", "y''", "d2y"), ("y'''", "y'''", "d3y"))


class CamContext(NamedTuple):
    """What every step reads: the scene, the cam angle (rad), the /analyze body there, the lift
    and its segment, and the formatter."""

    scene: CamScene
    theta: float
    body: JSON
    lift: Lift
    segment: Segment
    number: int
    fmt: Formatter

    def builder(self, kind: str, title: str) -> StepBuilder:
        return StepBuilder(self.fmt, kind, title)

    @property
    def unit(self) -> str:
        """The lift's unit: m, or rad for an oscillating follower."""
        return "rad" if self.scene.follower.motion == "oscillating" else "m"

    @property
    def sign(self) -> float:
        """+1 on a rise, -1 on a return (0 on a dwell)."""
        return {"rise": 1.0, "return": -1.0}.get(self.segment.type, 0.0)


class LawValues(NamedTuple):
    """y, y', y'', y''' at x (references into the step being written)."""

    y: Ref
    dy: Ref
    d2y: Ref
    d3y: Ref


def cam_solution(scene: CamScene, angle_deg: float, digits: int) -> Solution:
    """The worked solution of ``scene`` at cam angle ``angle_deg`` (modulo 360), numbers shown
    with ``digits`` significant digits."""
    ctx = cam_context(scene, angle_deg, digits)
    steps = [data_step(ctx)]
    law: tuple[float, ...] | None = None
    if ctx.segment.law is not None:
        law_step, law = law_values(ctx)
        steps.append(law_step)
    motion = motion_step(ctx, law)
    steps += [motion, pressure_angle_step(ctx), curvature_step(ctx), fundamental_law_step(ctx)]
    steps.append(summary_step(ctx))
    mistakes = cam_mistakes(ctx, steps.index(motion))
    return Solution(tuple(steps), tuple(mistakes), ctx.body, "cam", "cam", digits)


def cam_context(scene: CamScene, angle_deg: float, digits: int = 4) -> CamContext:
    """The cam at ``angle_deg`` as the steps read it: /analyze's body there, the lift, the
    segment, a formatter of ``digits`` significant digits."""
    body = analyze_cam(scene, angle_deg)
    theta = body["cam_angle"]
    lift = follower_lift(scene, np.array([theta]))
    index = int(lift.segment[0])
    fmt = Formatter(digits, unit_scales(scene, body))
    return CamContext(scene, theta, body, lift, scene.segments[index], index, fmt)


def _per_radian(unit: str, order: int) -> str:
    """The unit of d^k s/dtheta^k: 'm/rad', 'm/rad^2' ('' for a lift in rad)."""
    if not unit:
        return ""
    return f"{unit}/rad" + (f"^{order}" if order > 1 else "")


def unit_scales(scene: CamScene, body: JSON) -> dict[str, float]:
    """The size of each unit's quantities over the revolution (the extremes of /analyze's
    diagnostics): a number smaller than rounding noise next to it shows as 0."""
    extremes = body["diagnostics"]["extremes"]

    def largest(name: str) -> float:
        return max(abs(extremes[name]["min"]), abs(extremes[name]["max"]))

    w = abs(scene.omega)
    unit = "rad" if scene.follower.motion == "oscillating" else "m"
    per = "" if unit == "rad" else unit
    scales = {
        "": 1.0,
        "rad": 2.0 * math.pi,
        "m": scene.prime_radius + largest("displacement"),
        "m^2": (scene.prime_radius + largest("displacement")) ** 2,
        "m^3": (scene.prime_radius + largest("displacement")) ** 3,
        f"{unit}/s": largest("velocity"),
        f"{unit}/s^2": largest("acceleration"),
        f"{unit}/s^3": largest("jerk"),
    }
    if per:
        for order, name in enumerate(("velocity", "acceleration", "jerk"), 1):
            scales[_per_radian(per, order)] = largest(name) / w**order
    return scales


# --- the data and the figure ------------------------------------------------------------------


def _follower_words(scene: CamScene) -> str:
    f = scene.follower
    contact = {"knife": "knife-edge", "roller": "roller", "flat": "flat-faced"}[f.contact]
    if f.motion == "translating":
        where = f" with offset {f.offset:g} m" if f.offset else " without offset"
        return f"a translating {contact} follower{where}"
    return f"an oscillating {contact} follower about the pivot ({f.pivot[0]:g}, {f.pivot[1]:g}) m"


def data_step(ctx: CamContext) -> Step:
    """The cam, its follower, the segment the angle lies in, and the figure."""
    scene, seg = ctx.scene, ctx.segment
    b = ctx.builder("cam.data", "Data: the cam, the follower and the segment")
    rb = b.value("R_b", scene.base_radius, "m", ("diagnostics", "base_radius"))
    omega = b.value("omega", scene.omega, "rad/s")
    theta = b.value("theta", ctx.theta / DEG, "deg", ("cam_angle_deg",))
    base = Equation.of("R_b", Num(rb, unit=True))
    speed = Equation.of(Sym(r"\omega", "omega"), Num(omega, unit=True))
    angle = Equation.of(Sym(r"\theta", "theta"), Num(theta, unit=True))
    b.line("&", *_joined((base, speed)))
    b.line(angle)
    roller: tuple[Piece, ...] = ()
    if scene.follower.contact == "roller":
        rf = b.value("r_f", scene.follower.roller_radius, "m")
        rp = b.value("R_p", scene.prime_radius, "m", ("diagnostics", "prime_radius"))
        b.check("sum", rp, rb, rf)
        prime = Equation.of(
            "R_p",
            "R_b + r_f",
            latex_only(Num(rb), " + ", Num(rf)),
            # the text gives R_p as the scene has it, not to the step's digits
            Alt((Num(rp, unit=True),), (f"{scene.prime_radius:g} m",)),
        )
        b.line(prime)
        roller = (" The prime circle is ", prime, ".")
    sense = "counter-clockwise" if scene.omega > 0 else "clockwise"
    segments = "; ".join(
        f"{s.type} {s.law + ' ' if s.law else ''}"
        + (f"of {s.lift:g} {ctx.unit} " if s.law else "")
        + f"over {s.duration_deg:g} deg"
        for s in scene.segments
    )
    b.say(
        "A disc cam of base radius ",
        base,
        f" turns {sense} at ",
        speed,
        f" with {_follower_words(scene)}. The segments from cam angle 0: {segments}.",
        *roller,
        " At ",
        angle,
        f" the follower is in {seg.describe(ctx.number)}, from "
        f"{math.degrees(seg.start):g} deg to {math.degrees(seg.start) + seg.duration_deg:g} deg.",
    )
    step = b.build()
    return Step(
        step.kind, step.title, step.latex, step.text, step.values, step.checks, cam_figure(ctx)
    )


FIGURE = 100.0  # mm: the side of the figure
COLOURS = {"cam": "#1f4e9c", "follower": "#b5471b", "normal": "#2e7d32", "motion": "#6a1b9a"}


def _turned(points: np.ndarray, angle: float) -> np.ndarray:
    """Points turned counter-clockwise by ``angle`` (rad) about the origin."""
    c, s = math.cos(angle), math.sin(angle)
    return np.stack([c * points[:, 0] - s * points[:, 1], s * points[:, 0] + c * points[:, 1]], 1)


def cam_figure(ctx: CamContext, labelled: bool = True) -> str:
    """The cam turned to theta (its profile, base circle dashed), the follower, and at the pitch
    point the common normal and the follower's direction of motion, the pressure angle between
    them (its value written unless not ``labelled``: an exercise's figure)."""
    scene, f = ctx.scene, ctx.scene.follower
    mirror = np.array([math.copysign(1.0, scene.omega), 1.0])
    profile = _turned(np.asarray(ctx.body["profile"]), math.copysign(ctx.theta, scene.omega))
    contact = np.asarray(ctx.body["contact_point"])
    if f.contact == "flat":
        pitch, direction = contact, np.array([0.0, 1.0])
        normal = direction
        if f.motion == "oscillating":
            pivot = np.asarray(f.pivot)
            arm = (contact - pivot) / np.linalg.norm(contact - pivot)
            normal = np.array([-arm[1], arm[0]]) * mirror
            direction = normal
    else:
        p, dp, _, t = pitch_point(scene, ctx.lift)
        u = pitch_curve_tangent(p, dp)[0]
        pitch, direction = p[0] * mirror, t[0] * mirror
        normal = np.array([-u[1], u[0]]) / math.hypot(*u) * mirror
    reach = scene.prime_radius + max(abs(s.level) for s in scene.segments) + f.roller_radius
    extra = [pitch + direction * 0.6 * reach, np.zeros(2)]
    if f.motion == "oscillating":
        extra.append(np.asarray(f.pivot))
    frame = [tuple(x) for x in (*profile, *extra)]
    view = View.centred(frame, FIGURE, 8.0)
    canvas = Canvas(view, 2)
    cam_colour = COLOURS["cam"]
    canvas.points(
        "polygon",
        [canvas.px(x) for x in profile],
        [("fill", "#dde6f4"), ("stroke", cam_colour), ("stroke-width", "0.5")],
    )
    canvas.circle(
        canvas.px((0.0, 0.0)),
        scene.base_radius * view.scale,
        [
            ("fill", "none"),
            ("stroke", cam_colour),
            ("stroke-width", "0.25"),
            ("stroke-dasharray", "1.5 1"),
        ],
    )
    canvas.circle(canvas.px((0.0, 0.0)), 0.8, [("fill", "#000000")])
    follower = [("stroke", COLOURS["follower"]), ("stroke-width", "0.8"), ("fill", "none")]
    if f.motion == "translating":
        canvas.line(canvas.px(pitch), canvas.px(pitch + direction * 0.6 * reach), follower)
    else:
        canvas.line(canvas.px(np.asarray(f.pivot)), canvas.px(pitch), follower)
        canvas.circle(canvas.px(np.asarray(f.pivot)), 1.0, [("fill", COLOURS["follower"])])
    if f.contact == "roller":
        canvas.circle(canvas.px(pitch), f.roller_radius * view.scale, follower)
    if f.contact == "flat":
        tangent = np.array([direction[1], -direction[0]]) * 0.45 * reach
        canvas.line(canvas.px(contact - tangent), canvas.px(contact + tangent), follower)
    length = 0.35 * reach
    for name, vector in (("normal", normal), ("motion", direction)):
        colour = COLOURS[name]
        style = [("stroke", colour), ("stroke-width", "0.4"), ("data-vector", name)]
        if name == "normal":
            style.append(("stroke-dasharray", "2 1"))
        start = pitch if name == "motion" else pitch - vector * 0.5 * length
        canvas.line(canvas.px(start), canvas.px(pitch + vector * length), style)
    canvas.circle(canvas.px(contact), 0.9, [("fill", "#000000")])
    label = [("font-size", "3.4"), ("font-family", "sans-serif")]
    phi = math.degrees(float(ctx.body["pressure_angle"]))
    at = canvas.px(pitch + normal * 1.05 * length)  # beside the normal, clear of the follower
    canvas.text((at[0] + 1.5, at[1]), f"phi = {phi:.3g} deg" if labelled else "phi", label)
    canvas.text(canvas.px((0.0, 0.0)), "O", [*label, ("dx", "1.5"), ("dy", "3.5")])
    bar = nice_scale(0.2 * FIGURE / view.scale, 1.0)  # a round length, a fifth of the drawing
    width = bar * view.scale
    canvas.path(f"M4 {FIGURE - 7:g}v2h{width:.2f}v-2", [("fill", "none"), ("stroke", "#000000")])
    canvas.text((width + 6.0, FIGURE - 5.0), f"{bar:g} m", label)
    title = element("title", [], f"The cam at theta = {math.degrees(ctx.theta):g} deg")
    size = f"{FIGURE:g}"
    return canvas.document(
        [
            ("width", f"{size}mm"),
            ("height", f"{size}mm"),
            ("viewBox", f"0 0 {size} {size}"),
            ("role", "img"),
            ("data-kind", "cam"),
        ],
        [title],
    )


# --- the law ------------------------------------------------------------------------------------


def _write(b: StepBuilder, symbol: Sym, *sides: Piece | tuple[Piece, ...]) -> None:
    """symbol = sides..., as a LaTeX line and a sentence."""
    equation = Equation.of(symbol, *sides)
    b.line(equation)
    b.say(equation, ".")


# a derivative c f(angle) of a law: its symbol, its formula (LaTeX, text), the factor written
# before the number of f (LaTeX, text), f's value and the derivative's value
ScaledTrig = tuple[str, tuple[str, str], tuple[str, str], Ref, Ref]
PI_HALF = (r"\frac{\pi}{2} \cdot ", "(pi/2) x ")
PI2_HALF = (r"\frac{\pi^2}{2} \cdot ", "(pi^2/2) x ")
PI3_HALF = (r"-\frac{\pi^3}{2} \cdot ", "-(pi^3/2) x ")
TWO_PI = (r"2\pi \cdot ", "2 pi x ")
FOUR_PI2 = (r"4\pi^2 \cdot ", "4 pi^2 x ")


def _scaled_trig(b: StepBuilder, rows: Sequence[ScaledTrig]) -> None:
    """y^(n) = c f(angle) = c (f) = value, a line each: y' = (pi/2) sin(pi x) = (pi/2) x
    (0.7071) = 1.111."""
    for symbol, formula, factor, trig, result in rows:
        _write(b, Sym(symbol, symbol), Sym(*formula), (Sym(*factor), Paren(trig)), Num(result))


def _trig(b: StepBuilder, name: str, angle: Ref) -> tuple[Ref, Ref]:
    """cos and sin of ``angle`` (rad), checked through (cos, sin) = e^(i angle)."""
    value = b.scalar(angle)
    one = b.value("1", 1.0, "")
    unit = b.value(f"e^(i {name})", (math.cos(value), math.sin(value)), "")
    b.check("phasor", unit, one, angle)
    cos = b.value(f"cos {name}", math.cos(value), "", reference=1.0)
    sin = b.value(f"sin {name}", math.sin(value), "", reference=1.0)
    b.check("sum", cos, unit[0])
    b.check("sum", sin, unit[1])
    return cos, sin


def _pi_multiple(k: float) -> tuple[str, str]:
    """k = (p/q) pi written in LaTeX and in text: '4\\pi', '\\frac{4\\pi}{3}'."""
    ratio = Fraction(k / math.pi).limit_denominator(12)
    top = "" if ratio.numerator == 1 else str(ratio.numerator)
    if ratio.denominator == 1:
        return rf"{top}\pi", f"{top} pi".strip()
    return rf"\frac{{{top}\pi}}{{{ratio.denominator}}}", f"({top} pi/{ratio.denominator})"


def law_values(ctx: CamContext) -> tuple[Step, tuple[float, ...]]:
    """x = (theta - theta_0) / beta and the law's y, y', y'', y''' at x, written out."""
    seg = ctx.segment
    assert seg.law is not None
    b = ctx.builder("cam.law", f"The law: {LAW_TITLES[seg.law]} at x")
    theta = b.value("theta", ctx.theta / DEG, "deg", ("cam_angle_deg",))
    start = b.value("theta_0", math.degrees(seg.start), "deg")
    beta = b.value("beta", seg.duration_deg, "deg")
    turned = b.value("theta - theta_0", b.scalar(theta) - b.scalar(start), "deg")
    # x and the law's values as the solver has them (in radians: its rounding, not ours)
    x_solver = min(1.0, max(0.0, (ctx.theta - seg.start) / seg.duration))
    x = b.value("x", x_solver, "")
    b.check("sum", turned, theta, -start)
    b.check("quotient", x, turned, beta)
    fraction = Equation.of(
        "x",
        Sym(r"\frac{\theta - \theta_0}{\beta}", "(theta - theta_0)/beta"),
        latex_only(r"\frac{", Num(theta), " - ", Num(start), "}{", Num(beta), "}"),
        Num(x),
    )
    b.line(fraction)
    b.say(
        "The cam has turned theta - theta_0 = ",
        Num(turned, unit=True),
        " into the segment of duration beta = ",
        Num(beta, unit=True),
        ": ",
        fraction,
        ".",
    )
    if seg.law == "uniform":
        values = _uniform(b, x)
    elif seg.law == "harmonic":
        values = _harmonic(b, x)
    elif seg.law == "cycloidal":
        values = _cycloidal(b, x)
    elif seg.law in POLYNOMIALS:
        values = _polynomial(b, x, POLYNOMIALS[seg.law])
    else:
        values = _pieces(b, x, PIECEWISE[seg.law])
    exact = LAWS[seg.law](np.array([x_solver]))
    for ref, number in zip(values, exact, strict=True):
        b.put(ref.key, float(number[0]), "")
    return b.build(), tuple(b.scalar(v) for v in values)


def _uniform(b: StepBuilder, x: Ref) -> LawValues:
    """y = x, y' = 1, y'' = y''' = 0 (the acceleration is infinite at the ends)."""
    one = b.value("y'", 1.0, "")
    zero2, zero3 = b.value("y''", 0.0, ""), b.value("y'''", 0.0, "")
    y = b.value("y", b.scalar(x), "")
    b.check("sum", y, x)
    _write(b, Sym("y", "y"), "x", Num(y))
    constant = (Equation.of("y'", "1"), Sym(r",\quad ", " and "), Equation.of("y''", "y'''", "0"))
    b.line("&", *constant)
    b.say(
        *constant,
        " inside the segment; at its ends the velocity jumps, an infinite acceleration.",
    )
    return LawValues(y, one, zero2, zero3)


def _harmonic(b: StepBuilder, x: Ref) -> LawValues:
    """y = (1 - cos pi x)/2, y' = (pi/2) sin pi x, y'' = (pi^2/2) cos pi x,
    y''' = -(pi^3/2) sin pi x."""
    angle = b.value("pi x", math.pi * b.scalar(x), "rad")
    b.check("product", angle, x, factor=math.pi)
    cos, sin = _trig(b, "pi x", angle)
    one = b.value("1", 1.0, "")
    rest = b.value("1 - cos pi x", 1.0 - b.scalar(cos), "")
    b.check("sum", rest, one, -cos)
    y = b.value("y", b.scalar(rest) / 2.0, "")
    b.check("product", y, rest, factor=0.5)
    dy = b.value("y'", math.pi / 2.0 * b.scalar(sin), "")
    d2y = b.value("y''", math.pi**2 / 2.0 * b.scalar(cos), "")
    d3y = b.value("y'''", -(math.pi**3) / 2.0 * b.scalar(sin), "")
    b.check("product", dy, sin, factor=math.pi / 2.0)
    b.check("product", d2y, cos, factor=math.pi**2 / 2.0)
    b.check("product", d3y, sin, factor=-(math.pi**3) / 2.0)
    _write(b, Sym(r"\pi x", "pi x"), Num(angle, unit=True))
    _write(
        b,
        Sym("y", "y"),
        Sym(r"\frac{1 - \cos \pi x}{2}", "(1 - cos(pi x))/2"),
        (Sym(r"\frac{1 - ", "(1 - "), Paren(cos), Sym("}{2}", ")/2")),
        Num(y),
    )
    _scaled_trig(
        b,
        (
            ("y'", (r"\frac{\pi}{2}\sin \pi x", "(pi/2) sin(pi x)"), PI_HALF, sin, dy),
            ("y''", (r"\frac{\pi^2}{2}\cos \pi x", "(pi^2/2) cos(pi x)"), PI2_HALF, cos, d2y),
            ("y'''", (r"-\frac{\pi^3}{2}\sin \pi x", "-(pi^3/2) sin(pi x)"), PI3_HALF, sin, d3y),
        ),
    )
    return LawValues(y, dy, d2y, d3y)


def _cycloidal(b: StepBuilder, x: Ref) -> LawValues:
    """y = x - sin(2 pi x)/(2 pi), y' = 1 - cos 2 pi x, y'' = 2 pi sin 2 pi x,
    y''' = 4 pi^2 cos 2 pi x."""
    angle = b.value("2 pi x", 2.0 * math.pi * b.scalar(x), "rad")
    b.check("product", angle, x, factor=2.0 * math.pi)
    cos, sin = _trig(b, "2 pi x", angle)
    one = b.value("1", 1.0, "")
    part = b.value("sin(2 pi x)/(2 pi)", b.scalar(sin) / (2.0 * math.pi), "", reference=1.0)
    b.check("product", part, sin, factor=1.0 / (2.0 * math.pi))
    y = b.value("y", b.scalar(x) - b.scalar(part), "")
    b.check("sum", y, x, -part)
    dy = b.value("y'", 1.0 - b.scalar(cos), "")
    b.check("sum", dy, one, -cos)
    d2y = b.value("y''", 2.0 * math.pi * b.scalar(sin), "")
    d3y = b.value("y'''", 4.0 * math.pi**2 * b.scalar(cos), "")
    b.check("product", d2y, sin, factor=2.0 * math.pi)
    b.check("product", d3y, cos, factor=4.0 * math.pi**2)
    _write(b, Sym(r"2\pi x", "2 pi x"), Num(angle, unit=True))
    _write(
        b,
        Sym("y", "y"),
        Sym(r"x - \frac{\sin 2\pi x}{2\pi}", "x - sin(2 pi x)/(2 pi)"),
        (Num(x), Sym(r" - \frac{", " - "), Paren(sin), Sym(r"}{2\pi}", "/(2 pi)")),
        Num(y),
    )
    _scaled_trig(
        b,
        (
            ("y'", (r"1 - \cos 2\pi x", "1 - cos(2 pi x)"), ("1 - ", "1 - "), cos, dy),
            ("y''", (r"2\pi \sin 2\pi x", "2 pi sin(2 pi x)"), TWO_PI, sin, d2y),
            ("y'''", (r"4\pi^2 \cos 2\pi x", "4 pi^2 cos(2 pi x)"), FOUR_PI2, cos, d3y),
        ),
    )
    return LawValues(y, dy, d2y, d3y)


def _monomial(coefficient: float, power: int, first: bool) -> tuple[str, str]:
    """'10x^3', '- 15x^4' (LaTeX and text)."""
    sign = "-" if coefficient < 0 else ("" if first else "+")
    body = f"{abs(coefficient):g}" + ("" if power == 0 else "x" if power == 1 else f"x^{power}")
    lead = f"{sign} " if sign and not first else sign
    return lead + body, lead + body


def _polynomial(b: StepBuilder, x: Ref, coefficients: dict[int, float]) -> LawValues:
    """y = sum c_k x^k and its derivatives term by term, each term c_k x^k from the powers of
    x."""
    top = max(coefficients)
    powers: dict[int, Ref] = {0: b.value("x^0", 1.0, ""), 1: x}
    for k in range(2, top + 1):
        powers[k] = b.value(f"x^{k}", b.scalar(x) ** k, "")
        b.check("product", powers[k], powers[k - 1], x)
    shown = [
        Equation.of(Sym(f"x^{{{k}}}", f"x^{k}"), Num(powers[k]))
        for k in range(2, top + 1)
        if k >= min(coefficients) - 3
    ]
    b.line("&", *_joined(shown))
    b.say(*_joined(shown), ".")
    results = []
    current = coefficients
    for order, (symbol_tex, symbol_text, key) in enumerate(DERIVATIVES):
        terms: list[tuple[float, int, Ref]] = []
        for k, c in sorted(current.items()):
            term = b.value(f"{key}: {c:g} x^{k}", c * b.scalar(powers[k]), "")
            b.check("product", term, powers[k], factor=c)
            terms.append((c, k, term))
        result = b.value(symbol_text, sum(b.scalar(t) for _, _, t in terms), "")
        b.check("sum", result, *(t for _, _, t in terms))
        formula_tex = " ".join(_monomial(c, k, i == 0)[0] for i, (c, k, _) in enumerate(terms))
        numbers: list[Piece] = []
        for i, (c, k, _) in enumerate(terms):
            sign = ("-" if c < 0 else "") if i == 0 else (" - " if c < 0 else " + ")
            numbers.append(f"{sign}{abs(c):g}")
            if k:
                numbers += [CDOT, Paren(powers[k])]
        sums: list[Piece] = []
        for i, (_, _, t) in enumerate(terms):
            if i:
                sums.append(" + ")
            sums.append(Paren(t) if i else Num(t))
        del order
        _write(
            b,
            Sym(symbol_tex, symbol_text),
            Sym(formula_tex, formula_tex),
            tuple(numbers),
            tuple(sums),
            Num(result),
        )
        results.append(result)
        current = {k - 1: k * c for k, c in current.items() if k > 0}
    return LawValues(*results)


def _joined(equations: Sequence[Equation]) -> list[Piece | Equation]:
    out: list[Piece | Equation] = []
    for i, equation in enumerate(equations):
        if i:
            out.append(Sym(r",\quad ", ", "))
        out.append(equation)
    return out


def _pieces(b: StepBuilder, x: Ref, law: AccelerationPieces) -> LawValues:
    """The piece x lies in: y'' = A (p + q sin k u + r cos k u) with u = x - x_i, integrated from
    the piece's start (y_i, y'_i); A from y(1) = 1 (``AccelerationPieces``)."""
    amplitude, starts_y, starts_dy = law.starting_values()
    xv = b.scalar(x)
    i = int(np.clip(np.searchsorted(law.starts, xv, side="right") - 1, 0, len(law.starts) - 1))
    p, q, r, k = law.p[i], law.q[i], law.r[i], law.k[i]
    a = b.value("A", amplitude, "")
    xi = b.value("x_i", law.starts[i], "")
    yi = b.value("y_i", starts_y[i], "")
    dyi = b.value("y'_i", starts_dy[i], "")
    u = b.value("u", xv - law.starts[i], "")
    b.check("sum", u, x, -xi)
    end = (*law.starts[1:], 1.0)[i]
    piece = (
        Sym("&", "The amplitude from y(1) = 1 is "),
        Equation.of("A", Num(a)),
        Sym(
            rf",\quad x \in [{law.starts[i]:g}, {end:g}):\; ",
            f"; x lies in the piece from x_i = {law.starts[i]:g} to {end:g}, ",
        ),
        Equation.of("u", "x - x_i", Num(u)),
        Sym(r",\; ", ", where "),
        Equation.of("y_i", Num(yi)),
        Sym(r",\; ", " and "),
        Equation.of("y'_i", Num(dyi)),
    )
    b.line(*piece)
    b.say(*piece, ".")
    drift = b.value("y'_i u", b.scalar(dyi) * b.scalar(u), "")
    b.check("product", drift, dyi, u)
    if p:  # constant acceleration pA
        pa = b.value("p A", p * amplitude, "")
        b.check("product", pa, a, factor=p)
        d2y = b.value("y''", b.scalar(pa), "")
        b.check("sum", d2y, pa)
        d3y = b.value("y'''", 0.0, "")
        gain = b.value("p A u", b.scalar(pa) * b.scalar(u), "")
        b.check("product", gain, pa, u)
        dy = b.value("y'", b.scalar(dyi) + b.scalar(gain), "")
        b.check("sum", dy, dyi, gain)
        half = b.value("p A u^2/2", b.scalar(pa) * b.scalar(u) ** 2 / 2.0, "")
        b.check("product", half, pa, u, u, factor=0.5)
        y = b.value("y", b.scalar(yi) + b.scalar(drift) + b.scalar(half), "")
        b.check("sum", y, yi, drift, half)
        sign = "" if p > 0 else "-"
        _write(b, Sym("y''", "y''"), Sym(f"{sign}A", f"{sign}A"), Num(d2y))
        _write(b, Sym("y'''", "y'''"), "0")
        _write(
            b,
            Sym("y'", "y'"),
            Sym(f"y'_i {'+' if p > 0 else '-'} A u", f"y'_i {'+' if p > 0 else '-'} A u"),
            (Num(dyi), " + ", Paren(gain)),
            Num(dy),
        )
        _write(
            b,
            Sym("y", "y"),
            Sym(
                rf"y_i + y'_i u {'+' if p > 0 else '-'} \frac{{A u^2}}{{2}}",
                f"y_i + y'_i u {'+' if p > 0 else '-'} A u^2/2",
            ),
            (Num(yi), " + ", Paren(drift), " + ", Paren(half)),
            Num(y),
        )
        return LawValues(y, dy, d2y, d3y)
    k_tex, k_text = _pi_multiple(k)
    ku = b.value("k u", k * b.scalar(u), "rad")
    b.check("product", ku, u, factor=k)
    cos, sin = _trig(b, "k u", ku)
    one = b.value("1", 1.0, "")
    _write(b, Sym("k u", "k u"), Sym(rf"{k_tex}\, u", f"{k_text} u"), Num(ku, unit=True))
    if q:  # y'' = A sin k u
        d2y = b.value("y''", amplitude * b.scalar(sin), "")
        b.check("product", d2y, a, sin)
        d3y = b.value("y'''", amplitude * k * b.scalar(cos), "")
        b.check("product", d3y, a, cos, factor=k)
        rest = b.value("1 - cos k u", 1.0 - b.scalar(cos), "")
        b.check("sum", rest, one, -cos)
        gain = b.value("A (1 - cos k u)/k", amplitude * b.scalar(rest) / k, "")
        b.check("product", gain, a, rest, factor=1.0 / k)
        dy = b.value("y'", b.scalar(dyi) + b.scalar(gain), "")
        b.check("sum", dy, dyi, gain)
        inner = b.value("u/k - sin(k u)/k^2", b.scalar(u) / k - b.scalar(sin) / k**2, "")
        over_k = b.value("u/k", b.scalar(u) / k, "")
        b.check("product", over_k, u, factor=1.0 / k)
        sin_k2 = b.value("sin(k u)/k^2", b.scalar(sin) / k**2, "")
        b.check("product", sin_k2, sin, factor=1.0 / k**2)
        b.check("sum", inner, over_k, -sin_k2)
        lift = b.value("A (u/k - sin(k u)/k^2)", amplitude * b.scalar(inner), "")
        b.check("product", lift, a, inner)
        y = b.value("y", b.scalar(yi) + b.scalar(drift) + b.scalar(lift), "")
        b.check("sum", y, yi, drift, lift)
        forms = (
            (Sym("A sin ku", "A sin(k u)"), d2y),
            (Sym(r"A k \cos ku", "A k cos(k u)"), d3y),
            (Sym(r"y'_i + \frac{A (1 - \cos ku)}{k}", "y'_i + A (1 - cos(k u))/k"), dy),
            (
                Sym(
                    r"y_i + y'_i u + A\left(\frac{u}{k} - \frac{\sin ku}{k^2}\right)",
                    "y_i + y'_i u + A (u/k - sin(k u)/k^2)",
                ),
                y,
            ),
        )
        parts = {
            dy: (Num(dyi), " + ", Paren(gain)),
            y: (Num(yi), " + ", Paren(drift), " + ", Paren(lift)),
        }
    else:  # y'' = r A cos k u
        d2y = b.value("y''", r * amplitude * b.scalar(cos), "")
        b.check("product", d2y, a, cos, factor=r)
        d3y = b.value("y'''", -r * amplitude * k * b.scalar(sin), "")
        b.check("product", d3y, a, sin, factor=-r * k)
        gain = b.value("r A sin(k u)/k", r * amplitude * b.scalar(sin) / k, "")
        b.check("product", gain, a, sin, factor=r / k)
        dy = b.value("y'", b.scalar(dyi) + b.scalar(gain), "")
        b.check("sum", dy, dyi, gain)
        rest = b.value("1 - cos k u", 1.0 - b.scalar(cos), "")
        b.check("sum", rest, one, -cos)
        lift = b.value("r A (1 - cos k u)/k^2", r * amplitude * b.scalar(rest) / k**2, "")
        b.check("product", lift, a, rest, factor=r / k**2)
        y = b.value("y", b.scalar(yi) + b.scalar(drift) + b.scalar(lift), "")
        b.check("sum", y, yi, drift, lift)
        s = "" if r > 0 else "-"
        forms = (
            (Sym(f"{s}A \\cos ku", f"{s}A cos(k u)"), d2y),
            (
                Sym(f"{'-' if r > 0 else ''}A k \\sin ku", f"{'-' if r > 0 else ''}A k sin(k u)"),
                d3y,
            ),
            (
                Sym(
                    rf"y'_i {'+' if r > 0 else '-'} \frac{{A \sin ku}}{{k}}",
                    f"y'_i {'+' if r > 0 else '-'} A sin(k u)/k",
                ),
                dy,
            ),
            (
                Sym(
                    rf"y_i + y'_i u {'+' if r > 0 else '-'} \frac{{A (1 - \cos ku)}}{{k^2}}",
                    f"y_i + y'_i u {'+' if r > 0 else '-'} A (1 - cos(k u))/k^2",
                ),
                y,
            ),
        )
        parts = {
            dy: (Num(dyi), " + ", Paren(gain)),
            y: (Num(yi), " + ", Paren(drift), " + ", Paren(lift)),
        }
    names = {d2y: ("y''", "y''"), d3y: ("y'''", "y'''"), dy: ("y'", "y'"), y: ("y", "y")}
    for formula, value in forms:
        sides: list[Piece | tuple[Piece, ...]] = [formula]
        if value in parts:
            sides.append(parts[value])
        _write(b, Sym(*names[value]), *sides, Num(value))
    return LawValues(y, dy, d2y, d3y)


# --- s, v, a, j -----------------------------------------------------------------------------------


def motion_step(ctx: CamContext, numbers: tuple[float, ...] | None) -> Step:
    """s = s_0 +- h y and its derivatives in theta, then per time by the chain rule."""
    seg, unit = ctx.segment, ctx.unit
    b = ctx.builder("cam.motion", "The follower's displacement, velocity, acceleration and jerk")
    per = "" if unit == "rad" else unit
    follower = ctx.body["follower"]
    src = ("follower",)
    w = b.value("|omega|", abs(ctx.scene.omega), "rad/s")
    if numbers is None:
        s = b.value("s", follower["displacement"], unit, (*src, "displacement"))
        still = Equation.of("s", "s_0", Num(s, unit=True))
        b.line(still)
        b.line(
            r"&\frac{ds}{d\theta} = \frac{d^2s}{d\theta^2} = \frac{d^3s}{d\theta^3} = 0 "
            r"\;\Rightarrow\; v = a = j = 0"
        )
        b.say(
            "In a dwell the follower stands still at ",
            still,
            ": s', s'' and s''' are 0, and so are v, a and j.",
        )
        return b.build()
    law = LawValues(*(b.value(n, v, "") for (_, n, _), v in zip(DERIVATIVES, numbers, strict=True)))
    lift = b.value("h", seg.lift, unit)
    s0 = b.value("s_0", seg.level, unit)
    beta_deg = b.value("beta (deg)", seg.duration_deg, "deg")
    beta = b.value("beta", seg.duration, "rad")
    b.check("product", beta, beta_deg, factor=DEG)
    pm = "+" if ctx.sign > 0 else "-"
    word = "rise" if ctx.sign > 0 else "return"
    hy = b.value("h y", seg.lift * b.scalar(law.y), unit)
    b.check("product", hy, lift, law.y)
    s = b.value("s", follower["displacement"], unit, (*src, "displacement"))
    b.check("sum", s, s0, hy if ctx.sign > 0 else -hy)
    duration = Equation.of(
        Sym(r"\beta", "beta"), latex_only(Num(beta_deg, unit=True)), Num(beta, unit=True)
    )
    displacement = Equation.of(
        "s",
        Sym(f"s_0 {pm} h\\,y", f"s_0 {pm} h y"),
        latex_only(Num(s0), f" {pm} ", Num(lift), r" \cdot ", Paren(law.y)),
        Num(s, unit=True),
    )
    b.line(duration)
    b.line(displacement)
    b.say(
        f"On a {word} of h = ",
        Num(lift, unit=True),
        " from s_0 = ",
        Num(s0, unit=True),
        ": ",
        displacement,
        "; ",
        duration,
        ".",
    )
    derivatives = []
    for order, (y, name) in enumerate(((law.dy, "ds"), (law.d2y, "d2s"), (law.d3y, "d3s")), 1):
        hy_k = b.value(f"h y^({order})", seg.lift * b.scalar(y), unit)
        b.check("product", hy_k, lift, y)
        power = b.value(
            f"beta^{order}", seg.duration**order, f"rad^{order}" if order > 1 else "rad"
        )
        if order > 1:
            b.check("product", power, *([beta] * order))
        else:
            b.check("sum", power, beta)
        value = float((ctx.lift.ds, ctx.lift.d2s, ctx.lift.d3s)[order - 1][0])
        d = b.value(name, value, _per_radian(per, order))
        b.check("quotient", d, hy_k, power, factor=ctx.sign)
        primes = "'" * order
        power_tex = f"^{order}" if order > 1 else ""
        dtheta = rf"\frac{{d{power_tex}s}}{{d\theta{power_tex}}}"
        beta_tex = r"\beta" + (f"^{order}" if order > 1 else "")
        sign_tex = "" if ctx.sign > 0 else "-"
        equation = Equation.of(
            Sym(dtheta, f"s{primes}"),
            Sym(
                rf"{sign_tex}\frac{{h\,y{primes}}}{{{beta_tex}}}",
                f"{sign_tex}h y{primes}/beta{'^' + str(order) if order > 1 else ''}",
            ),
            (
                Sym(rf"{sign_tex}\frac{{", f"{sign_tex}("),
                Num(lift),
                CDOT,
                Paren(y),
                Sym("}{", ")/"),
                Num(power) if order == 1 else Paren(beta),
                Sym(f"^{order}" if order > 1 else "", f"^{order}" if order > 1 else ""),
                Sym("}", ""),
            ),
            Num(d, unit=True),
        )
        b.line(equation)
        b.say(equation, ".")
        derivatives.append(d)
    names = (
        ("velocity", "v", "|omega|", r"|\omega|"),
        ("acceleration", "a", "omega^2", r"\omega^2"),
        ("jerk", "j", "|omega|^3", r"|\omega|^3"),
    )
    rate = w
    for order, (d, (field, letter, w_text, w_tex)) in enumerate(
        zip(derivatives, names, strict=True), 1
    ):
        if order > 1:
            rate = b.value(f"|omega|^{order}", abs(ctx.scene.omega) ** order, f"1/s^{order}")
            b.check("product", rate, *([w] * order))
        time_unit = f"{unit}/s" + (f"^{order}" if order > 1 else "")
        answer = b.value(letter, follower[field], time_unit, (*src, field))
        b.check("product", answer, d, rate)
        primes = "'" * order
        equation = Equation.of(
            Sym(letter, letter),
            Sym(f"s{primes}\\,{w_tex}", f"s{primes} {w_text}"),
            (Num(d), CDOT, Num(rate)),
            Boxed((Num(answer, unit=True),)),
        )
        b.line(equation)
        b.say(equation, ".")
    b.say(
        "By the chain rule, each derivative in time is the derivative in the cam angle times "
        "the cam's speed to the same power (omega constant)."
    )
    return b.build()


# --- the pressure angle -------------------------------------------------------------------------


def _derivatives(b: StepBuilder, ctx: CamContext) -> tuple[Ref, Ref, Ref]:
    """s, s' and s'' at theta (from the motion step's numbers)."""
    unit = ctx.unit
    per = "" if unit == "rad" else unit
    s = b.value("s", float(ctx.lift.s[0]), unit, ("follower", "displacement"))
    ds = b.value("ds", float(ctx.lift.ds[0]), f"{per}/rad" if per else "")
    d2s = b.value("d2s", float(ctx.lift.d2s[0]), f"{per}/rad^2" if per else "")
    return s, ds, d2s


def _offset(b: StepBuilder, ctx: CamContext) -> tuple[Ref, Ref, Ref]:
    """epsilon = e sign(omega), R_p and sqrt(R_p^2 - epsilon^2) with their checks."""
    scene = ctx.scene
    e = b.value("e", scene.follower.offset, "m")
    eps = b.value("epsilon", math.copysign(1.0, scene.omega) * scene.follower.offset, "m")
    b.check("product", eps, e, factor=math.copysign(1.0, scene.omega))
    rp = b.value("R_p", scene.prime_radius, "m", ("diagnostics", "prime_radius"))
    rp2 = b.value("R_p^2", scene.prime_radius**2, "m^2")
    eps2 = b.value("epsilon^2", b.scalar(eps) ** 2, "m^2")
    d2 = b.value("R_p^2 - epsilon^2", b.scalar(rp2) - b.scalar(eps2), "m^2")
    d = b.value("sqrt(R_p^2 - epsilon^2)", math.sqrt(b.scalar(d2)), "m")
    b.check("product", rp2, rp, rp)
    b.check("product", eps2, eps, eps)
    b.check("sum", d2, rp2, -eps2)
    b.check("product", d2, d, d)
    offset = Equation.of(
        Sym(r"\varepsilon", "epsilon"),
        Sym(r"e\,\operatorname{sign}\omega", "e sign(omega)"),
        Num(eps, unit=True),
    )
    axis = Equation.of(
        Sym(r"\sqrt{R_p^2 - \varepsilon^2}", "sqrt(R_p^2 - epsilon^2)"),
        latex_only(r"\sqrt{", Num(rp2), " - ", Paren(eps2), "}"),
        Num(d, unit=True),
    )
    b.line("&", offset, r",\quad ", axis)
    b.say(
        "The offset seen from a counter-clockwise cam is ",
        offset,
        "; the follower's axis meets the prime circle at ",
        axis,
        " from the cam's centre line.",
    )
    return eps, rp, d


def _angle_of(b: StepBuilder, ctx: CamContext, denominator: Ref, numerator: Ref) -> Ref:
    """phi = arctan(numerator / denominator) (the solver's number), with its checks (the
    denominator is positive: atan2 is arctan)."""
    pair = b.value("(den, num)", (b.scalar(denominator), b.scalar(numerator)), "")
    b.check("sum", denominator, pair[0])
    b.check("sum", numerator, pair[1])
    phi = b.value("phi", float(ctx.body["pressure_angle"]), "rad", ("pressure_angle",))
    b.check("angle", phi, pair)
    return phi


def pressure_angle_step(ctx: CamContext) -> Step:
    """phi from Norton's eq. 8.31 (translating), the oscillating arm's form, or 0 for a flat
    face; compared with the usual limit."""
    scene, f = ctx.scene, ctx.scene.follower
    b = ctx.builder("cam.pressure_angle", "The pressure angle")
    limit = PRESSURE_ANGLE_LIMIT_DEG[f.motion]
    if f.contact == "flat":
        phi = b.value("phi", float(ctx.body["pressure_angle"]), "rad", ("pressure_angle",))
        b.line(r"&\phi = ", Num(phi, unit=True))
        b.say(
            "A flat face is square to the follower's direction of motion (or passes through "
            "the pivot): the common normal at the contact is that direction, so the pressure "
            "angle phi is 0 at every cam angle."
        )
        return b.build()
    s, ds, _ = _derivatives(b, ctx)
    if f.motion == "translating":
        eps, _, d = _offset(b, ctx)
        num = b.value("s' - epsilon", b.scalar(ds) - b.scalar(eps), "m")
        den = b.value("sqrt(R_p^2 - epsilon^2) + s", b.scalar(d) + b.scalar(s), "m")
        b.check("sum", num, ds, -eps)
        b.check("sum", den, d, s)
        phi = _angle_of(b, ctx, den, num)
        formula = Sym(
            r"\arctan\frac{ds/d\theta - \varepsilon}{\sqrt{R_p^2 - \varepsilon^2} + s}",
            "arctan((ds/dtheta - epsilon)/(sqrt(R_p^2 - epsilon^2) + s))",
        )
        numbers: tuple[Piece, ...] = (
            Sym(r"\arctan\frac{", "arctan(("),
            Num(ds),
            " - ",
            Paren(eps),
            Sym("}{", ")/("),
            Num(d),
            " + ",
            Paren(s),
            Sym("}", "))"),
        )
        source = "Norton eq. 8.31"
    else:
        pivot = b.value("pivot", f.pivot, "m")
        dist = b.value("d", math.hypot(*f.pivot), "m")
        b.check("norm", dist, pivot)
        arm = b.value("l", f.arm_length, "m")
        rest = b.value("beta_0", scene.rest_angle, "rad")
        beta = b.value("beta", scene.rest_angle + b.scalar(s), "rad")
        b.check("sum", beta, rest, s)
        cos, sin = _trig(b, "beta", beta)
        one = b.value("1", 1.0, "")
        less = b.value("s' - 1", b.scalar(ds) - 1.0, "")
        b.check("sum", less, ds, -one)
        swing = b.value("l (s' - 1)", b.scalar(arm) * b.scalar(less), "m")
        b.check("product", swing, arm, less)
        near = b.value("d cos beta", b.scalar(dist) * b.scalar(cos), "m")
        b.check("product", near, dist, cos)
        num = b.value("l (s' - 1) + d cos beta", b.scalar(swing) + b.scalar(near), "m")
        b.check("sum", num, swing, near)
        den = b.value("d sin beta", b.scalar(dist) * b.scalar(sin), "m")
        b.check("product", den, dist, sin)
        phi = _angle_of(b, ctx, den, num)
        turned = Equation.of(
            Sym(r"\beta", "beta"),
            Sym(r"\beta_0 + s", "beta_0 + s"),
            latex_only(Num(rest), " + ", Paren(s)),
            Num(beta, unit=True),
        )
        pivot_distance = Equation.of("d", Num(dist, unit=True))
        arm_length = Equation.of("l", Num(arm, unit=True))
        b.line("&", *_joined((turned, pivot_distance, arm_length)))
        b.say(
            "The arm's angle from the line to the cam centre is ",
            turned,
            "; the pivot is ",
            pivot_distance,
            " from the cam centre, the arm ",
            arm_length,
            " long.",
        )
        formula = Sym(
            r"\arctan\frac{l\,(ds/d\theta - 1) + d\cos\beta}{d\sin\beta}",
            "arctan((l (ds/dtheta - 1) + d cos beta)/(d sin beta))",
        )
        numbers = (
            Sym(r"\arctan\frac{", "arctan(("),
            Num(arm),
            CDOT,
            Paren(less),
            " + ",
            Num(dist),
            CDOT,
            Paren(cos),
            Sym("}{", ")/("),
            Num(dist),
            CDOT,
            Paren(sin),
            Sym("}", "))"),
        )
        source = "the oscillating arm's form of tan phi = (u . T)/(u . n)"
    quotient = (Sym(r"\arctan\frac{", "arctan("), Num(num), Sym("}{", "/"), Num(den), Sym("}", ")"))
    degrees = b.value("phi (deg)", math.degrees(b.scalar(phi)), "deg")
    b.check("product", degrees, phi, factor=1.0 / DEG)
    equation = Equation.of(
        Sym(r"\phi", "phi"),
        formula,
        numbers,
        quotient,
        Num(phi, unit=True),
        Boxed((Num(degrees, unit=True),)),
        breaks=(2,),
    )
    b.line(equation)
    b.say(f"The pressure angle ({source}): ", equation, ".")
    verdict = (
        f"within the usual limit of {limit:g} deg for a {f.motion} follower"
        if abs(b.scalar(degrees)) <= limit
        else f"above the usual limit of {limit:g} deg for a {f.motion} follower: the side "
        "load on the follower's guide grows and it may jam; a larger base radius (or an offset "
        "on the rise's side) lowers it"
    )
    b.say(f"|phi| is {verdict}.")
    return b.build()


# --- the radius of curvature --------------------------------------------------------------------


def curvature_step(ctx: CamContext) -> Step:
    """rho of the pitch curve and of the cam surface (see the module)."""
    f = ctx.scene.follower
    b = ctx.builder("cam.curvature", "The radius of curvature")
    s, ds, d2s = _derivatives(b, ctx)
    surface_source = ("radius_of_curvature",)
    if f.contact == "flat":
        rho = _flat_radius(b, ctx, s, ds, d2s)
        verdict = (
            "positive: the cam is convex under the face"
            if b.scalar(rho) > 0
            else "negative: a cusp, the face cannot follow the lift (undercutting)"
        )
        b.say(f"rho is {verdict}.")
        return b.build()
    if f.motion == "translating":
        pitch = _translating_pitch_radius(b, ctx, s, ds, d2s)
    else:
        pitch = _pitch_radius_vectors(b, ctx)
    r = b.value("r_f", f.roller_radius, "m")
    rho = b.value("rho", float(ctx.body["radius_of_curvature"]), "m", surface_source)
    b.check("sum", rho, pitch, -r)
    equation = Equation.of(
        Sym(r"\rho", "rho"),
        Sym(r"\rho_p - r_f", "rho_p - r_f"),
        (Num(pitch), " - ", Num(r)),
        Boxed((Num(rho, unit=True),)),
    )
    b.line(equation)
    b.say("The cam surface lies r_f inside the pitch curve: ", equation, ".")
    if f.contact == "roller":
        ok = not (0 < b.scalar(pitch) < f.roller_radius)
        verdict = (
            "the pitch curve is concave here, which a roller always follows"
            if b.scalar(pitch) < 0
            else "larger than the roller radius: no undercutting here"
            if ok
            else "smaller than the roller radius: the cam surface would cross itself (undercutting)"
        )
        b.say(f"rho_p is {verdict}.")
    return b.build()


def _translating_pitch_radius(b: StepBuilder, ctx: CamContext, s: Ref, ds: Ref, d2s: Ref) -> Ref:
    """rho_p = (A^2 + B^2)^(3/2) / (A^2 + B (B + s') - A s''), A = sqrt(R_p^2 - eps^2) + s,
    B = s' - eps (Norton eq. 8.33 with the offset)."""
    eps, _, d = _offset(b, ctx)
    a = b.value("A", b.scalar(d) + b.scalar(s), "m")
    b.check("sum", a, d, s)
    bb = b.value("B", b.scalar(ds) - b.scalar(eps), "m")
    b.check("sum", bb, ds, -eps)
    a2 = b.value("A^2", b.scalar(a) ** 2, "m^2")
    b2 = b.value("B^2", b.scalar(bb) ** 2, "m^2")
    b.check("product", a2, a, a)
    b.check("product", b2, bb, bb)
    u = b.value("(A, B)", (b.scalar(a), b.scalar(bb)), "m")
    b.check("sum", a, u[0])
    b.check("sum", bb, u[1])
    length = b.value("|(A, B)|", math.hypot(b.scalar(a), b.scalar(bb)), "m")
    b.check("norm", length, u)
    cube = b.value("(A^2 + B^2)^(3/2)", b.scalar(length) ** 3, "m^3")
    b.check("product", cube, length, length, length)
    c = b.value("B + s'", b.scalar(bb) + b.scalar(ds), "m")
    b.check("sum", c, bb, ds)
    bc = b.value("B (B + s')", b.scalar(bb) * b.scalar(c), "m^2")
    b.check("product", bc, bb, c)
    as2 = b.value("A s''", b.scalar(a) * b.scalar(d2s), "m^2")
    b.check("product", as2, a, d2s)
    den = b.value("A^2 + B (B + s') - A s''", b.scalar(a2) + b.scalar(bc) - b.scalar(as2), "m^2")
    b.check("sum", den, a2, bc, -as2)
    pitch = b.value("rho_p", _solvers(ctx, b.scalar(cube) / b.scalar(den)), "m", _pitch_source(ctx))
    b.check("quotient", pitch, cube, den)
    sum_a = Equation.of(
        "A",
        Sym(r"\sqrt{R_p^2 - \varepsilon^2} + s", "sqrt(R_p^2 - epsilon^2) + s"),
        Num(a, unit=True),
    )
    sum_b = Equation.of(
        "B", Sym(r"\frac{ds}{d\theta} - \varepsilon", "s' - epsilon"), Num(bb, unit=True)
    )
    radius = Equation.of(
        Sym(r"\rho_p", "rho_p"),
        Sym(
            r"\frac{(A^2 + B^2)^{3/2}}{A^2 + B\,(B + s') - A\,s''}",
            "(A^2 + B^2)^(3/2)/(A^2 + B (B + s') - A s'')",
        ),
        latex_only(
            r"\frac{",
            Num(length),
            "^3}{",
            Num(a2),
            " + ",
            Paren(bb),
            r" \cdot ",
            Paren(c),
            " - ",
            Paren(a),
            r" \cdot ",
            Paren(d2s),
            "}",
        ),
        latex_only(r"\frac{", Num(cube), "}{", Num(den), "}"),
        Num(pitch, unit=True),
    )
    b.line("&", sum_a, r",\quad ", sum_b)
    b.line(radius)
    b.say(
        "The pitch curve's radius of curvature (Norton eq. 8.33, with the offset: ",
        sum_a,
        ", ",
        sum_b,
        "): ",
        radius,
        ".",
    )
    return pitch


def _solvers(ctx: CamContext, derived: float) -> float:
    """rho_p as the solver answers it (a roller's), else as derived here (a knife's pitch curve
    is its cam surface)."""
    return float(ctx.body["pitch_radius_of_curvature"]) if _pitch_source(ctx) else derived


def _pitch_source(ctx: CamContext) -> tuple[str, ...] | None:
    """The path of rho_p in the /analyze body (a roller's only)."""
    return ("pitch_radius_of_curvature",) if ctx.scene.follower.contact == "roller" else None


def _pitch_radius_vectors(b: StepBuilder, ctx: CamContext) -> Ref:
    """rho_p = -|u|^3 / (u x w), u = P' - J P, w = P'' - 2 J P' - P (the pitch point P(theta)
    of a counter-clockwise cam)."""
    p_, dp_, d2p_, _ = pitch_point(ctx.scene, ctx.lift)
    p = b.value("P", p_[0], "m")
    dp = b.value("P'", dp_[0], "m")
    d2p = b.value("P''", d2p_[0], "m")
    one = b.value("1", 1.0, "")
    jp = b.value("J P", (-p_[0][1], p_[0][0]), "m")
    b.check("cross", jp, one, p)
    u = b.value("u", (dp_[0][0] + p_[0][1], dp_[0][1] - p_[0][0]), "m")
    b.check("sum", u, dp, -jp)
    jdp2 = b.value("2 J P'", (-2.0 * dp_[0][1], 2.0 * dp_[0][0]), "m")
    b.check("cross", jdp2, one, dp, factor=2.0)
    w_ = np.asarray(d2p_[0]) - np.asarray(b.vector(jdp2)) - p_[0]
    w = b.value("w", w_, "m")
    b.check("sum", w, d2p, -jdp2, -p)
    (u_x, u_y), (w_x, w_y) = b.vector(u), w_
    cross = b.value("u x w", float(u_x * w_y - u_y * w_x), "m^2")
    b.check("cross", cross, u, w)
    length = b.value("|u|", math.hypot(*b.vector(u)), "m")
    b.check("norm", length, u)
    cube = b.value("|u|^3", b.scalar(length) ** 3, "m^3")
    b.check("product", cube, length, length, length)
    pitch = b.value(
        "rho_p", _solvers(ctx, -b.scalar(cube) / b.scalar(cross)), "m", _pitch_source(ctx)
    )
    b.check("quotient", pitch, cube, cross, factor=-1.0)
    b.line(
        "&P = ",
        *_point(p),
        r",\quad P' = ",
        *_point(dp),
        r",\quad P'' = ",
        *_point(d2p),
    )
    tangent = Equation.of("u", Sym("P' - JP", "P' - J P"), latex_only(*_point(u)))
    turn = Equation.of("w", Sym("P'' - 2JP' - P", "P'' - 2 J P' - P"), latex_only(*_point(w)))
    radius = Equation.of(
        Sym(r"\rho_p", "rho_p"),
        Sym(r"-\frac{|u|^3}{u \times w}", "-|u|^3/(u x w)"),
        latex_only(r"-\frac{", Num(length), "^3}{", Paren(cross), "}"),
        Num(pitch, unit=True),
    )
    b.line("&", tangent, r",\quad ", turn)
    b.line(radius)
    b.say(
        "The pitch point P(theta) (in the ground, the cam turning counter-clockwise) traces the "
        "pitch curve as the cam sees it; its tangent is ",
        tangent,
        " (J the quarter turn), ",
        turn,
        ", and ",
        radius,
        ".",
    )
    return pitch


def _point(ref: Ref) -> tuple[Piece, ...]:
    return (Pt(ref, "m"),)


def _flat_radius(b: StepBuilder, ctx: CamContext, s: Ref, ds: Ref, d2s: Ref) -> Ref:
    """Translating: rho = R_b + s + s'' (Norton eq. 8.37); through a pivot: rho = h +
    d2h/dalpha2 of the face line n . x = h, h = d sin beta."""
    scene = ctx.scene
    rb = b.value("R_b", scene.base_radius, "m", ("diagnostics", "base_radius"))
    rho = b.value("rho", float(ctx.body["radius_of_curvature"]), "m", ("radius_of_curvature",))
    if scene.follower.motion == "translating":
        b.check("sum", rho, rb, s, d2s)
        equation = Equation.of(
            Sym(r"\rho", "rho"),
            Sym(r"R_b + s + \frac{d^2s}{d\theta^2}", "R_b + s + s''"),
            (Num(rb), " + ", Paren(s), " + ", Paren(d2s)),
            Boxed((Num(rho, unit=True),)),
        )
        b.line(equation)
        b.say("Under a flat face (Norton eq. 8.37): ", equation, ".")
        return rho
    dist = b.value("d", math.hypot(*scene.follower.pivot), "m")
    beta = b.value("beta", scene.rest_angle + b.scalar(s), "rad")
    rest = b.value("beta_0", scene.rest_angle, "rad")
    b.check("sum", beta, rest, s)
    cos, sin = _trig(b, "beta", beta)
    h = b.value("h", b.scalar(dist) * b.scalar(sin), "m")
    b.check("product", h, dist, sin)
    dh = b.value("h'", b.scalar(dist) * b.scalar(cos) * b.scalar(ds), "m")
    b.check("product", dh, dist, cos, ds)
    t1 = b.value("cos beta s''", b.scalar(cos) * b.scalar(d2s), "")
    t2 = b.value("sin beta s'^2", b.scalar(sin) * b.scalar(ds) ** 2, "")
    b.check("product", t1, cos, d2s)
    b.check("product", t2, sin, ds, ds)
    inner = b.value("cos beta s'' - sin beta s'^2", b.scalar(t1) - b.scalar(t2), "")
    b.check("sum", inner, t1, -t2)
    d2h = b.value("h''", b.scalar(dist) * b.scalar(inner), "m")
    b.check("product", d2h, dist, inner)
    one = b.value("1", 1.0, "")
    da = b.value("alpha'", b.scalar(ds) - 1.0, "")
    b.check("sum", da, ds, -one)
    top = b.value(
        "h'' alpha' - h' alpha''", b.scalar(d2h) * b.scalar(da) - b.scalar(dh) * b.scalar(d2s), "m"
    )
    hd = b.value("h'' alpha'", b.scalar(d2h) * b.scalar(da), "m")
    dd = b.value("h' alpha''", b.scalar(dh) * b.scalar(d2s), "m")
    b.check("product", hd, d2h, da)
    b.check("product", dd, dh, d2s)
    b.check("sum", top, hd, -dd)
    da3 = b.value("alpha'^3", b.scalar(da) ** 3, "")
    b.check("product", da3, da, da, da)
    haa = b.value("d2h/dalpha2", b.scalar(top) / b.scalar(da3), "m")
    b.check("quotient", haa, top, da3)
    b.check("sum", rho, h, haa)
    height = Equation.of("h", Sym(r"d \sin\beta", "d sin beta"), Num(h, unit=True))
    turning = Equation.of(Sym(r"\alpha'", "alpha'"), "s' - 1", Num(da))
    b.line("&", height, r",\quad ", turning)
    equation = Equation.of(
        Sym(r"\rho", "rho"),
        Sym(
            r"h + \frac{h''\alpha' - h'\alpha''}{\alpha'^3}",
            "h + (h'' alpha' - h' alpha'')/alpha'^3",
        ),
        (Num(h), " + ", Sym(r"\frac{", "("), Num(top), Sym("}{", ")/"), Paren(da3), Sym("}", "")),
        Boxed((Num(rho, unit=True),)),
    )
    b.line(equation)
    b.say(
        "The face through the pivot is the line n . x = h with ",
        height,
        "; its normal turns at ",
        turning,
        " in the cam's frame; the cam surface is the envelope of those lines: ",
        equation,
        ".",
    )
    return rho


# --- the fundamental law ----------------------------------------------------------------------


def _ends(scene: CamScene, index: int) -> tuple[tuple[float, float, float], ...]:
    """(s, s', s'') at the start and at the end of segment ``index``, from its law's end
    values."""
    seg = scene.segments[index]
    if seg.law is None:
        return ((seg.level, 0.0, 0.0), (seg.level, 0.0, 0.0))
    y = LAWS[seg.law](np.array([0.0, 1.0]))
    h = seg.lift if seg.type == "rise" else -seg.lift
    beta = seg.duration
    return tuple(
        (seg.level + h * float(y.y[k]), h * float(y.dy[k]) / beta, h * float(y.d2y[k]) / beta**2)
        for k in (0, 1)
    )


def fundamental_law_step(ctx: CamContext) -> Step:
    """s, v and a on both sides of the segment's two boundaries: the fundamental law of cam
    design asks all three to be continuous (the jerk finite)."""
    scene, i = ctx.scene, ctx.number
    n = len(scene.segments)
    b = ctx.builder("cam.fundamental_law", "The fundamental law of cam design at the boundaries")
    w = abs(scene.omega)
    extremes = ctx.body["diagnostics"]["extremes"]
    scales = {
        "v": max(abs(extremes["velocity"]["min"]), abs(extremes["velocity"]["max"])),
        "a": max(abs(extremes["acceleration"]["min"]), abs(extremes["acceleration"]["max"])),
    }
    unit = ctx.unit
    faults = []
    for where, before, after in (
        (scene.segments[i].start, (i - 1) % n, i),
        (scene.segments[i].start + scene.segments[i].duration, i, (i + 1) % n),
    ):
        angle = math.degrees(where) % 360.0
        left, right = _ends(scene, before)[1], _ends(scene, after)[0]
        pieces: list[Piece] = [
            Sym(
                rf"&\theta = {angle:g}^\circ:\;",
                f"At theta = {angle:g} deg ({scene.segments[before].describe(before)} "
                f"into {scene.segments[after].describe(after)}): ",
            )
        ]
        for k, (letter, factor, u) in enumerate(
            (("s", 1.0, unit), ("v", w, f"{unit}/s"), ("a", w * w, f"{unit}/s^2"))
        ):
            tag = f"{letter}({angle:g})"
            one = b.value(f"{tag}-", left[k] * factor, u, reference=scales.get(letter, 0.0))
            two = b.value(f"{tag}+", right[k] * factor, u, reference=scales.get(letter, 0.0))
            jump = b.value(
                f"{tag} jump", two_minus(b, two, one), u, reference=scales.get(letter, 0.0)
            )
            b.check("sum", jump, two, -one)
            broken = letter != "s" and abs(b.scalar(jump)) > JUMP_TOLERANCE * scales[letter]
            if broken:
                faults.append(f"{letter} at {angle:g} deg")
            pieces += [
                Sym(r",\;" if k else "", "; " if k else ""),
                Sym(f"{letter}: ", f"{letter} "),
                Num(one),
                Sym(r" \to ", " to "),
                Alt((Num(two),), (Num(two, unit=True),)),
                Sym(r"\;(\text{jump})", " (a jump)") if broken else "",
            ]
        b.line(*pieces)
        b.say(*pieces, ".")
    if faults:
        b.say(
            "The fundamental law of cam design is broken (" + ", ".join(faults) + "): a jump in "
            "v is an infinite acceleration, a jump in a an infinite jerk. Choose laws whose "
            "velocity and acceleration match at the boundaries (cycloidal, 3-4-5, modified "
            "sine into a dwell)."
        )
    else:
        b.say(
            "s, v and a are continuous at both boundaries: the jerk stays finite there, as "
            "the fundamental law of cam design asks."
        )
    return b.build()


def two_minus(b: StepBuilder, two: Ref, one: Ref) -> float:
    """The jump after minus before."""
    return b.scalar(two) - b.scalar(one)


# --- summary and mistakes ---------------------------------------------------------------------


def summary_step(ctx: CamContext) -> Step:
    """The answers at theta, as /analyze gives them."""
    body, unit = ctx.body, ctx.unit
    b = ctx.builder("cam.summary", "Summary")
    f = body["follower"]
    s = b.value("s", f["displacement"], unit, ("follower", "displacement"))
    v = b.value("v", f["velocity"], f"{unit}/s", ("follower", "velocity"))
    a = b.value("a", f["acceleration"], f"{unit}/s^2", ("follower", "acceleration"))
    j = b.value("j", f["jerk"], f"{unit}/s^3", ("follower", "jerk"))
    phi = b.value("phi", body["pressure_angle"], "rad", ("pressure_angle",))
    rho = b.value("rho", body["radius_of_curvature"], "m", ("radius_of_curvature",))
    motion = _joined([Equation.of(k.key, Num(k, unit=True)) for k in (s, v, a, j)])
    angle = Equation.of(Sym(r"\phi", "phi"), Num(phi, unit=True))
    radius = Equation.of(Sym(r"\rho", "rho"), Num(rho, unit=True))
    b.line("&", *motion)
    b.line("&", angle, r",\quad ", radius)
    b.say(
        f"At theta = {math.degrees(ctx.theta):g} deg: ",
        *motion,
        "; pressure angle ",
        angle,
        ", radius of curvature ",
        radius,
        ".",
    )
    return b.build()


def cam_mistakes(ctx: CamContext, motion: int) -> list[Mistake]:
    """Typical mistakes with the chain rule (``solver.teaching.mistakes``): v = ds/dtheta (the
    cam's speed left out), and beta in degrees in ds/dtheta = h y'/beta; only where the wrong
    number shows differently from v (at a dwell, or at rest, both are 0: nothing to get
    wrong)."""
    if ctx.segment.law is None:
        return []
    fmt, unit = ctx.fmt, ctx.unit
    v = float(ctx.body["follower"]["velocity"])
    omega, duration = ctx.scene.omega, ctx.segment.duration_deg

    def value(x: float, u: str) -> Value:
        return Value(x, u, fmt.display(x, u))

    def mistake(kind: str, text: str, wrong: float, wrong_unit: str) -> Mistake:
        entry = typical_mistake(kind)
        values = {"wrong": value(wrong, wrong_unit), "right": value(v, f"{unit}/s")}
        return Mistake(kind, entry.title, text, values, step=motion)

    ds = cam_rate_without_omega(v, omega, 1)
    wrong = cam_beta_in_degrees(v, duration, 1)
    made = [
        mistake(
            "cam_omega_left_out",
            "ds/dtheta is the velocity per radian of cam turn; the follower's velocity in time "
            f"is v = (ds/dtheta) omega. Leaving omega out gives {fmt.text(ds)} instead of "
            f"{fmt.text(v)} {unit}/s.",
            ds,
            _per_radian(unit if unit == "m" else "", 1),
        ),
        mistake(
            "cam_beta_in_degrees",
            "In ds/dtheta = h y'/beta the duration beta is in radians (theta is). With beta in "
            f"degrees, v comes out as {fmt.text(wrong)} instead of {fmt.text(v)} {unit}/s.",
            wrong,
            f"{unit}/s",
        ),
    ]
    return [m for m in made if m.values["wrong"].display.rsplit(" ", 1)[0] != fmt.text(v)]

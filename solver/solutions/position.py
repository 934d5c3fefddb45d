"""The position analysis, derived (kinds ``position.crank``, ``position.triangle``,
``position.slider``): how each point of the analysed pose follows from the ones before it.

- a driven crank: B = A + a e^(i theta);
- a dyad of two links (triangle C1 X C2, sides r1, r2 and d = |C1 C2|): by the law of cosines
  cos gamma = (r1^2 + d^2 - r2^2) / (2 r1 d), then X = C1 + r1 e^(i (theta_d +- gamma)), theta_d
  the direction of C1 C2; the sign is the assembly, the side of C1 C2 on which X is drawn;
- a link and a fixed straight guide (centre C, radius r; guide through Q along u): the offset
  h = u x (C - Q), the foot F = Q + ((C - Q) . u) u, and X = F +- w u with w = sqrt(r^2 - h^2);
  the sign is the assembly, the side of the foot on which X is drawn.

Closed forms come first, then the numbers; the result is the solver's own position.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import partial

import numpy as np

from solver.position import constraints, newton
from solver.position.topology import (
    CircleSpec,
    DriverStep,
    DyadStep,
    LeverStep,
    LineSpec,
    NewtonStep,
    PlanStep,
)
from solver.solutions import latex as tex
from solver.solutions.builder import StepBuilder
from solver.solutions.format import latex_unit
from solver.solutions.linkage import LinkageContext
from solver.solutions.model import Step

DEGREE = r"{}^{\circ}"


def _point(b: StepBuilder, ctx: LinkageContext, name: str) -> str:
    return b.put(f"pos({name})", ctx.pos(name), "m", ("points", name, "position"))


def crank_step(ctx: LinkageContext, step: DriverStep) -> Step | None:
    others = [p for p in ctx.scene.links[step.link].points if p != step.pivot]
    if not others:
        return None
    x = others[0]
    b = ctx.builder("position.crank", f"Position of {x} (driven link {step.link})")
    a = _point(b, ctx, step.pivot)
    target = _point(b, ctx, x)
    r = ctx.pos(x) - ctx.pos(step.pivot)
    length = b.put(f"|{step.pivot}{x}|", float(np.hypot(*r)), "m")
    theta = b.put(f"theta({step.link})", math.atan2(r[1], r[0]), "rad")
    arm = b.put(f"r({step.pivot},{x})", r, "m")
    b.check("phasor", arm, length, theta)
    b.check("sum", target, a, arm)
    deg = tex.paren(ctx.fmt.latex(math.degrees(b.scalar(theta))) + DEGREE)
    b.line(
        rf"&{tex.name(x)} = {tex.name(step.pivot)} + a\,e^{{i\theta}} = {b.point(a)} + "
        rf"{b.num(length)}\,e^{{i\,{deg}}} = "
        rf"{tex.boxed_result(b.point(target) + latex_unit('m'))}"
    )
    b.say(
        f"The driven link {step.link} of length a = {b.txt(length)} is at theta = "
        f"{ctx.fmt.text(math.degrees(b.scalar(theta)))} deg: {x} = {step.pivot} + a "
        f"(cos theta, sin theta) = {b.txt(target)}."
    )
    return b.build()


@dataclass(frozen=True)
class TriangleValues:
    """The keys of X = C1 + r1 e^(i (theta_d +- gamma)) in the triangle C1 X C2: C1, X, r1,
    r2, d = |C1 C2|, the squares r1^2, r2^2, d^2, 2 r1 d, cos gamma, gamma, theta_d and theta;
    ``sign`` +1 where X lies on the left of C1 C2 (the drawn assembly), -1 on its right."""

    p1: str
    target: str
    r1: str
    r2: str
    d: str
    squares: tuple[str, str, str]
    den: str
    cos: str
    gamma: str
    theta_d: str
    angle: str
    sign: float


def triangle_step(
    ctx: LinkageContext, step: DyadStep, first: CircleSpec, second: CircleSpec
) -> Step:
    """cos gamma = (r1^2 + d^2 - r2^2) / (2 r1 d), X = C1 + r1 e^(i (theta_d +- gamma))."""
    x, c1, c2 = step.point, first.center, second.center
    b = ctx.builder("position.triangle", f"Position of {x}: the triangle {c1}{x}{c2}")
    triangle_lines(b, x, (first, second), triangle_values(b, ctx, x, first, second))
    return b.build()


def triangle_values(
    b: StepBuilder, ctx: LinkageContext, x: str, first: CircleSpec, second: CircleSpec
) -> TriangleValues:
    """The triangle's numbers, with a check for each piece of arithmetic."""
    c1, c2 = first.center, second.center
    p1, p2, target = _point(b, ctx, c1), _point(b, ctx, c2), _point(b, ctx, x)
    r1 = b.put(f"|{c1}{x}|", first.radius, "m")
    r2 = b.put(f"|{c2}{x}|", second.radius, "m")
    dv = ctx.pos(c2) - ctx.pos(c1)
    dk = b.put(f"r({c1},{c2})", dv, "m")
    d = b.put(f"|{c1}{c2}|", float(np.hypot(*dv)), "m")
    b.check("sum", dk, p2, f"-{p1}")
    b.check("norm", d, dk)
    squares, den, cos = cosine_law(b, r1, r2, d)
    rx = ctx.pos(x) - ctx.pos(c1)
    gamma, theta_d, angle, sign = triangle_angle(b, dv, rx, cos, dk)
    arm = b.put(f"r({c1},{x})", rx, "m")
    b.check("phasor", arm, r1, angle)
    b.check("sum", target, p1, arm)
    return TriangleValues(p1, target, r1, r2, d, squares, den, cos, gamma, theta_d, angle, sign)


def cosine_law(b: StepBuilder, r1: str, r2: str, d: str) -> tuple[tuple[str, str, str], str, str]:
    """cos gamma = (r1^2 + d^2 - r2^2) / (2 r1 d): the keys of (r1^2, r2^2, d^2), of 2 r1 d
    and of cos gamma."""
    sq = {k: b.put(f"{k}^2", b.scalar(k) ** 2, "m^2") for k in (r1, r2, d)}
    for k, v in sq.items():
        b.check("product", v, k, k)
    num = b.put("r1^2 + d^2 - r2^2", b.scalar(sq[r1]) + b.scalar(sq[d]) - b.scalar(sq[r2]), "m^2")
    den = b.put("2 r1 d", 2 * b.scalar(r1) * b.scalar(d), "m^2")
    cos = b.put("cos gamma", b.scalar(num) / b.scalar(den), "")
    b.check("sum", num, sq[r1], sq[d], f"-{sq[r2]}")
    b.check("product", den, r1, d, factor=2.0)
    b.check("quotient", cos, num, den)
    return (sq[r1], sq[r2], sq[d]), den, cos


def triangle_angle(
    b: StepBuilder, dv: np.ndarray, rx: np.ndarray, cos: str, dk: str
) -> tuple[str, str, str, float]:
    """gamma, the angle at C1 between C1 C2 (``dv``) and C1 X (``rx``), theta_d = arg C1 C2
    and theta = theta_d +- gamma, the sign that of X's side of C1 C2 (as drawn). gamma comes
    from the drawn geometry (acos loses digits where the triangle is nearly flat) and is
    checked against cos gamma. Returns the keys of gamma, theta_d, theta and the sign."""
    side = float(dv[0] * rx[1] - dv[1] * rx[0])
    gamma_value = math.atan2(abs(side), float(np.dot(dv, rx)))
    gamma = b.put("gamma", gamma_value, "rad")
    one = b.put("1", 1.0, "")
    unit = b.put("e^(i gamma)", (math.cos(gamma_value), math.sin(gamma_value)), "")
    b.check("phasor", unit, one, gamma)
    b.check("sum", cos, f"{unit}[0]")
    theta_d = b.put("theta_d", math.atan2(dv[1], dv[0]), "rad")
    b.check("angle", theta_d, dk)
    sign = 1.0 if side >= 0 else -1.0
    angle = b.put("theta", b.scalar(theta_d) + sign * gamma_value, "rad")
    b.check("sum", angle, theta_d, gamma if sign > 0 else f"-{gamma}")
    return gamma, theta_d, angle, sign


def triangle_lines(
    b: StepBuilder, x: str, circles: tuple[CircleSpec, CircleSpec], v: TriangleValues
) -> None:
    """Write the law of cosines, its numbers and the assembly taken."""
    (first, second), pm = circles, "+" if v.sign > 0 else "-"
    c1, c2 = first.center, second.center
    r1_sq, r2_sq, d_sq = v.squares
    b.line(
        rf"&\cos\gamma = \frac{{r_1^2 + d^2 - r_2^2}}{{2\,r_1\,d}}, \quad "
        rf"{tex.name(x)} = {tex.name(c1)} + r_1\,e^{{i(\theta_d {pm} \gamma)}}"
    )
    b.line(
        rf"&d = |{tex.name(c1)}{tex.name(c2)}| = {b.numu(v.d)}, \quad \cos\gamma = "
        rf"\frac{{{b.num(r1_sq)} + {b.num(d_sq)} - {b.num(r2_sq)}}}{{{b.num(v.den)}}} = "
        rf"{b.num(v.cos)}, \quad \gamma = {b.numu(v.gamma)}, \quad \theta_d = "
        rf"{b.numu(v.theta_d)}"
    )
    b.line(
        rf"&{tex.name(x)} = {b.point(v.p1)} + {b.num(v.r1)}\,e^{{i\,{tex.paren(b.num(v.angle))}}}"
        rf" = {tex.boxed_result(b.point(v.target) + latex_unit('m'))}"
    )
    b.say(
        f"{x} is at {b.txt(v.r1)} from {c1} (link {first.link}) and {b.txt(v.r2)} from {c2} "
        f"(link {second.link}); {c1}{c2} = {b.txt(v.d)}. The law of cosines gives cos gamma = "
        f"(r1^2 + d^2 - r2^2)/(2 r1 d) = {b.txtn(v.cos)}, gamma = {b.txt(v.gamma)}, the angle "
        f"at {c1} between {c1}{c2} (at theta_d = {b.txt(v.theta_d)}) and {c1}{x}. Two "
        "assemblies close the triangle, theta_d + gamma and theta_d - gamma; the one taken is "
        f"{x} on the {'left' if v.sign > 0 else 'right'} of {c1}{c2}, as drawn (the solver "
        f"keeps the drawn branch): {x} = {b.txt(v.target)}."
    )


@dataclass(frozen=True)
class CarriedLine:
    """The keys of a moving guide's slot now, Q = A + |Q0 - A0| e^(i (phi0 + theta_rot)) and
    u = e^(i (beta0 + theta_rot)): A, theta_rot, Q0 - A0, |Q0 - A0|, phi0 + theta_rot, Q, u0,
    beta0, beta and u."""

    anchor: str
    turn: str
    d0: str
    size: str
    phi: str
    q: str
    u0: str
    beta0: str
    beta: str
    u: str


def carried_line(b: StepBuilder, ctx: LinkageContext, line: LineSpec) -> tuple[str, str]:
    """The slot of a moving guide G now: Q = A + e^(i theta_G) (Q0 - A0) and u = e^(i (beta0 +
    theta_G)), the drawn line (through Q0 along u0) turned with G about its first point A by
    theta_G, the rotation of G since its drawing. Returns the keys of Q and u."""
    anchor = ctx.scene.links[line.guide].points[0]
    v = carried_line_values(b, ctx, line, anchor)
    carried_line_lines(b, line.guide, anchor, v)
    return v.q, v.u


def carried_line_values(
    b: StepBuilder, ctx: LinkageContext, line: LineSpec, anchor: str
) -> CarriedLine:
    """Q and u of the slot now, with a check for each piece of arithmetic."""
    pa = _point(b, ctx, anchor)
    turn = b.put(
        f"theta_rot({line.guide})", float(ctx.analysis.motion.links[line.guide].theta[0]), "rad"
    )
    d0_np = np.asarray(line.through0, dtype=float) - ctx.scene.drawn(anchor)
    d0 = b.put("Q0 - A0", d0_np, "m")
    size = b.put("|Q0 - A0|", float(np.hypot(*d0_np)), "m")
    phi0 = b.put("phi0", math.atan2(d0_np[1], d0_np[0]), "rad")
    phi = b.put("phi0 + theta_rot", b.scalar(phi0) + b.scalar(turn), "rad")
    d = b.put(
        "Q - A", b.scalar(size) * np.array([math.cos(b.scalar(phi)), math.sin(b.scalar(phi))]), "m"
    )
    q = b.put("Q", np.asarray(b.vector(pa)) + np.asarray(b.vector(d)), "m")
    u0_np = np.asarray(line.direction0, dtype=float)
    u0 = b.put("u0", u0_np / float(np.hypot(*u0_np)), "")
    beta0 = b.put("beta0", math.atan2(u0_np[1], u0_np[0]), "rad")
    beta = b.put("beta", b.scalar(beta0) + b.scalar(turn), "rad")
    one = b.put("1", 1.0, "")
    u = b.put("u", (math.cos(b.scalar(beta)), math.sin(b.scalar(beta))), "")
    b.check("norm", size, d0)
    b.check("angle", phi0, d0)
    b.check("sum", phi, phi0, turn)
    b.check("phasor", d, size, phi)
    b.check("sum", q, pa, d)
    b.check("angle", beta0, u0)
    b.check("sum", beta, beta0, turn)
    b.check("phasor", u, one, beta)
    return CarriedLine(pa, turn, d0, size, phi, q, u0, beta0, beta, u)


def carried_line_lines(b: StepBuilder, g: str, anchor: str, v: CarriedLine) -> None:
    """Write Q = A + e^(i theta_G) (Q0 - A0) and u = e^(i (beta0 + theta_G)) with the numbers."""
    a, gn = tex.name(anchor), tex.name(g)
    b.line(
        rf"&Q = {a} + e^{{i\theta_{{{gn}}}}}(Q_0 - {a}_0) = {b.point(v.anchor)} + "
        rf"{b.num(v.size)}\,e^{{i\,{tex.paren(b.num(v.phi))}}} = {b.point(v.q)}"
        rf"{latex_unit('m')}, \quad \vec{{u}} = e^{{i(\beta_0 + \theta_{{{gn}}})}} = "
        rf"e^{{i\,{tex.paren(b.num(v.beta))}}} = {b.point(v.u)}"
    )
    b.say(
        f"The slot is fixed in the moving link {g}: drawn through Q0 at {b.txtn(v.d0)} m from "
        f"{anchor} along u0 = {b.txtn(v.u0)} (angle beta0 = {b.txt(v.beta0)}), and {g} has "
        f"turned by theta_{g} = {b.txt(v.turn)} about {anchor} since its drawing. So the slot "
        f"now passes through Q = {anchor} + e^(i theta_{g}) (Q0 - {anchor}0) = {b.txt(v.q)} "
        f"along u = e^(i (beta0 + theta_{g})) = {b.txtn(v.u)}."
    )


@dataclass(frozen=True)
class SliderValues:
    """The keys of X = Q + ((C - Q) . u +- w) u: Q, u, r, h = u x (C - Q), (C - Q) . u,
    w = sqrt(r^2 - h^2), r^2, h^2, s and X; ``sign`` +1 where X is ahead of C's foot along u
    (the drawn assembly), -1 behind it."""

    q: str
    u: str
    r: str
    h: str
    along: str
    w: str
    r2: str
    h2: str
    s: str
    target: str
    sign: float


def slider_step(ctx: LinkageContext, step: DyadStep, circle: CircleSpec, line: LineSpec) -> Step:
    """h = u x (C - Q), w = sqrt(r^2 - h^2), X = Q + ((C - Q) . u +- w) u."""
    x = step.point
    fixed = line.guide == ctx.scene.ground
    guide = "fixed guide" if fixed else f"slot of {line.guide}"
    b = ctx.builder(
        "position.slider" if fixed else "position.slot",
        f"Position of {x}: link {circle.link} and the {guide}",
    )
    v = slider_values(b, ctx, x, circle, line)
    slider_lines(b, x, circle, guide, v)
    return b.build()


def slot_now(b: StepBuilder, ctx: LinkageContext, line: LineSpec) -> tuple[str, str]:
    """The keys of Q and u of a slot now: as drawn in the ground, else ``carried_line``."""
    if line.guide != ctx.scene.ground:
        return carried_line(b, ctx, line)
    u_np = np.asarray(line.direction0, dtype=float)
    return b.put("Q", line.through0, "m"), b.put("u", u_np / float(np.hypot(*u_np)), "")


def slider_values(
    b: StepBuilder, ctx: LinkageContext, x: str, circle: CircleSpec, line: LineSpec
) -> SliderValues:
    """The circle-line intersection's numbers, with a check for each piece of arithmetic;
    w comes from the pose (the distance of X from C's foot)."""
    c = circle.center
    pc, target = _point(b, ctx, c), _point(b, ctx, x)
    q, u = slot_now(b, ctx, line)
    q_np, u_np = np.asarray(b.vector(q)), np.asarray(b.vector(u))
    r = b.put(f"|{c}{x}|", circle.radius, "m")
    cq = b.put(f"{c} - Q", ctx.pos(c) - q_np, "m")
    b.check("sum", cq, pc, f"-{q}")
    h = b.put("h", float(u_np[0] * b.vector(cq)[1] - u_np[1] * b.vector(cq)[0]), "m")
    along = b.put("(C - Q).u", float(np.dot(b.vector(cq), u_np)), "m")
    b.check("cross", h, u, cq)
    b.check("dot", along, cq, u)
    s_value = float(np.dot(ctx.pos(x) - q_np, u_np))
    w = b.put("w", abs(s_value - b.scalar(along)), "m")
    r2, h2, w2 = (b.put(f"{k}^2", b.scalar(k) ** 2, "m^2") for k in (r, h, w))
    for key, base in ((r2, r), (h2, h), (w2, w)):
        b.check("product", key, base, base)
    b.check("sum", r2, w2, h2)
    sign = 1.0 if s_value >= b.scalar(along) else -1.0
    s = b.put("s", s_value, "m")
    b.check("sum", s, along, w if sign > 0 else f"-{w}")
    offset = b.put("s u", s_value * u_np, "m")
    b.check("product", offset, s, u)
    b.check("sum", target, q, offset)
    return SliderValues(q, u, r, h, along, w, r2, h2, s, target, sign)


def slider_lines(b: StepBuilder, x: str, circle: CircleSpec, guide: str, v: SliderValues) -> None:
    """Write the closed form, its numbers and the assembly taken."""
    c, pm = circle.center, "+" if v.sign > 0 else "-"
    b.line(
        rf"&h = \vec{{u}} \times ({tex.name(c)} - Q), \quad w = \sqrt{{r^2 - h^2}}, \quad "
        rf"{tex.name(x)} = Q + ((\,{tex.name(c)} - Q) \cdot \vec{{u}} {pm} w)\,\vec{{u}}"
    )
    b.line(
        rf"&h = {b.numu(v.h)}, \quad w = \sqrt{{{b.num(v.r2)} - {b.num(v.h2)}}} = "
        rf"{b.numu(v.w)}, \quad s = {b.num(v.along)} {pm} {b.num(v.w)} = {b.numu(v.s)}"
    )
    b.line(
        rf"&{tex.name(x)} = {b.point(v.q)} + {tex.paren(b.num(v.s))}\,{b.point(v.u)} = "
        rf"{tex.boxed_result(b.point(v.target) + latex_unit('m'))}"
    )
    b.say(
        f"{x} is at r = {b.txt(v.r)} from {c} (link {circle.link}) and on the {guide} through "
        f"Q = {b.txt(v.q)} along u = {b.txtn(v.u)}. {c} is at h = {b.txt(v.h)} from the guide; "
        f"the circle meets it at w = sqrt(r^2 - h^2) = {b.txt(v.w)} on either side of the foot "
        f"of {c}. The assembly taken is {x} {'ahead of' if v.sign > 0 else 'behind'} the foot "
        f"along u, as drawn: s = {b.txt(v.s)}, {x} = {b.txt(v.target)}."
    )


# --- a pin in the turning slot of a lever about a known pivot ---------------------------------


@dataclass(frozen=True)
class LeverNotation:
    """How a lever's closed form is written: the keys of s, c and beta and their LaTeX symbols;
    w is the vector from the lever's pivot to the pin."""

    s: str
    c: str
    beta: str
    s_tex: str
    c_tex: str
    beta_tex: str


TURN_LATEX = {"": "", "2pi": r" + 2\pi", "-2pi": r" - 2\pi"}  # the whole turn of wrap_turn
TURN_TEXT = {"": "", "2pi": " + 2 pi", "-2pi": " - 2 pi"}


def wrap_turn(b: StepBuilder, value: float, target: float) -> tuple[str, float]:
    """The whole turns k (as an operand '2pi' or '-2pi', '' for none) with value + k 2 pi =
    target, and the corrected value: an angle found as a sum is written in (-pi, pi]."""
    k = round((target - value) / (2 * math.pi))
    if k == 0:
        return "", value
    b.put("2pi", 2 * math.pi, "rad")
    return ("2pi" if k > 0 else "-2pi"), value + math.copysign(2 * math.pi, k)


@dataclass(frozen=True)
class LeverClosedForm:
    """The keys of a lever's closed form (``lever_values``) and the whole turn of beta."""

    c: str
    w2: str
    c2: str
    s: str
    epsilon: str
    theta_w: str
    beta: str
    turn: str


def lever_closed_form(b: StepBuilder, w: str, u_np: np.ndarray, n: LeverNotation) -> None:
    """(s + i c) e^(i beta) = w, w the vector from the lever's pivot to the pin (registered as
    ``w``): squared and added, s^2 + c^2 = |w|^2, so s = +-sqrt(|w|^2 - c^2); then beta =
    arg w - arg(s + i c). The offset c of the slot is a constant of the lever (from the pose);
    the sign of s is the drawn assembly (the pin ahead of the pivot along the slot, or behind)."""
    lever_lines(b, w, n, lever_values(b, w, u_np, n))


def lever_values(b: StepBuilder, w: str, u_np: np.ndarray, n: LeverNotation) -> LeverClosedForm:
    """Put the closed form's numbers, with a check for each piece of arithmetic."""
    w_np = np.asarray(b.vector(w))
    size = float(np.hypot(*w_np))  # c and arg(s + i c) at rounding level next to it are 0
    c = b.put(n.c, float(u_np[0] * w_np[1] - u_np[1] * w_np[0]), "m", reference=size)
    s_value = float(np.dot(w_np, u_np))
    w2 = b.put("|w|^2", float(np.dot(w_np, w_np)), "m^2")
    c2 = b.put(f"{n.c}^2", b.scalar(c) ** 2, "m^2", reference=size**2)
    s2 = b.put(f"{n.s}^2", s_value**2, "m^2", reference=b.scalar(w2))
    s = b.put(n.s, s_value, "m")
    sc = b.put(f"({n.s}, {n.c})", (s_value, b.scalar(c)), "m")
    eps = b.put("epsilon", math.atan2(b.scalar(c), s_value), "rad", reference=math.pi)
    theta_w = b.put("theta_w", math.atan2(w_np[1], w_np[0]), "rad")
    b.check("dot", w2, w, w)
    b.check("product", c2, c, c)
    b.check("sum", s2, w2, f"-{c2}")
    b.check("product", s2, s, s)
    b.check("sum", s, f"{sc}[0]")
    b.check("sum", c, f"{sc}[1]")
    b.check("angle", eps, sc)
    b.check("angle", theta_w, w)
    turn, beta_value = wrap_turn(b, b.scalar(theta_w) - b.scalar(eps), math.atan2(u_np[1], u_np[0]))
    beta = b.put(n.beta, beta_value, "rad")
    b.check("sum", beta, theta_w, f"-{eps}", *([turn] if turn else []))
    return LeverClosedForm(c, w2, c2, s, eps, theta_w, beta, turn)


def lever_lines(b: StepBuilder, w: str, n: LeverNotation, f: LeverClosedForm) -> None:
    """Write the closed form: Re and Im, the elimination, the numbers, the assembly taken."""
    ahead = b.scalar(f.s) >= 0
    pm = "+" if ahead else "-"
    b.line(
        rf"&\text{{Re: }} {n.s_tex}\cos{n.beta_tex} - {n.c_tex}\sin{n.beta_tex} = w_x, "
        rf"\quad \text{{Im: }} {n.s_tex}\sin{n.beta_tex} + {n.c_tex}\cos{n.beta_tex} = w_y"
    )
    b.line(
        rf"&{n.s_tex}^2 + {n.c_tex}^2 = |w|^2 \;\Rightarrow\; {n.s_tex} = \pm"
        rf"\sqrt{{|w|^2 - {n.c_tex}^2}}, \quad {n.beta_tex} = \arg w - "
        rf"\arg({n.s_tex} + i\,{n.c_tex})"
    )
    b.line(
        rf"&w = {b.point(w)}{latex_unit('m')}, \quad |w|^2 = {b.numu(f.w2)}, "
        rf"\quad {n.c_tex} = {b.numu(f.c)}"
    )
    b.line(
        rf"&{n.s_tex} = {pm}\sqrt{{{b.num(f.w2)} - {b.num(f.c2)}}} = "
        rf"{tex.boxed_result(b.numu(f.s))}"
    )
    b.line(
        rf"&\arg w = {b.numu(f.theta_w)}, \quad \arg({n.s_tex} + i\,{n.c_tex}) = "
        rf"{b.numu(f.epsilon)}, \quad {n.beta_tex} = {b.num(f.theta_w)} - "
        rf"{tex.paren(b.num(f.epsilon))}{TURN_LATEX[f.turn]} = {tex.boxed_result(b.numu(f.beta))}"
    )
    where = "ahead of" if ahead else "behind"
    b.say(
        "Written as (s + i c) e^(i beta) = w, the real and imaginary parts are s cos "
        "beta - c sin beta = w_x and s sin beta + c cos beta = w_y. Squaring and adding "
        f"eliminates beta: s^2 + c^2 = |w|^2, with the slot's offset c = {b.txt(f.c)} from the "
        f"pivot (a constant of the lever) and |w|^2 = {b.txt(f.w2)}, so s = +-sqrt(|w|^2 - c^2)"
        f". Two assemblies: the pin {where} the pivot along the slot (sign {pm}) is the one "
        f"drawn (the solver keeps the drawn branch): s = {b.txt(f.s)}. Then beta = arg w - "
        f"arg(s + i c) = {b.txt(f.theta_w)} - {b.txt(f.epsilon)}{TURN_TEXT[f.turn]} = "
        f"{b.txt(f.beta)}, the angle of the slot."
    )


def lever_step(ctx: LinkageContext, step: LeverStep) -> Step:
    """The lever's angle and the pin's distance along its slot, from the triangle pivot-pin."""
    q, p = step.pivot, step.pin
    b = ctx.builder("position.lever", f"Position of lever {step.link}: its slot through {p}")
    pq, pp = _point(b, ctx, q), _point(b, ctx, p)
    w = b.put(f"r({q},{p})", ctx.pos(p) - ctx.pos(q), "m")
    b.check("sum", w, pp, f"-{pq}")
    notation = LeverNotation("s", "c", "beta", "s", "c", r"\beta")
    b.line(
        rf"&w = {tex.name(p)} - {tex.name(q)} = (s + i\,c)\,e^{{i\beta}}, \quad s \text{{ along "
        rf"the slot, }} c \text{{ its offset from }} {tex.name(q)}"
    )
    b.say(
        f"Lever {step.link} turns about {q}; its slot passes through the pin {p}. From {q}, {p} "
        f"is s along the slot and c across it: w = {p} - {q} = {b.txt(w)}."
    )
    lever_closed_form(b, w, ctx.slot(step.link, p).direction, notation)
    return b.build()


# --- a Newton group: the loop-closure equations solved numerically ---------------------------

MAX_SHOWN_ITERATIONS = 12


def _power(x: float) -> str:
    """A residual in LaTeX with a power of ten (2 digits): rounding-level numbers are the point."""
    if x == 0.0:
        return "0"
    mantissa, exponent = f"{x:.1e}".split("e")
    return rf"{mantissa} \cdot 10^{{{int(exponent)}}}"


def _joint_equation(ctx: LinkageContext, joint_index: int) -> tuple[str, str]:
    """One joint's loop-closure equation (LaTeX, text): the joint's point as carried by either
    link (a pin), on the guide's line (a slot), no relative turn (a prismatic joint)."""
    joint = ctx.scene.joints[joint_index]
    i, j = (tex.name(k) for k in joint.links)
    p = tex.name(joint.point)
    if joint.type == "revolute":
        return (
            rf"\vec{{r}}_{{{i}}} + e^{{i\theta_{{{i}}}}}\vec{{d}}_{{{p}}}^{{\,{i}}} = "
            rf"\vec{{r}}_{{{j}}} + e^{{i\theta_{{{j}}}}}\vec{{d}}_{{{p}}}^{{\,{j}}}",
            f"{joint.point} carried by {joint.links[0]} = {joint.point} carried by "
            f"{joint.links[1]} (2 equations)",
        )
    g, f = tex.name(joint.guide), tex.name(joint.follower)
    line = (
        rf"\vec{{n}}_{{{g}}} \cdot ({p}^{{\,{f}}} - {p}^{{\,{g}}}) = 0",
        f"{joint.point} of {joint.follower} on the slot line of {joint.guide} (normal n)",
    )
    if joint.type == "prismatic":
        return (
            line[0] + rf", \quad \theta_{{{f}}} = \theta_{{{g}}}",
            line[1] + f", and {joint.follower} does not turn relative to {joint.guide}",
        )
    return line


def newton_iterations(ctx: LinkageContext, step: NewtonStep) -> tuple[list[float], bool]:
    """|Phi(q_k)| of Newton-Raphson q_(k+1) = q_k - J(q_k)^-1 Phi(q_k) on the group's joint
    equations from the drawn pose q_0, the group's known neighbours where the solver put them
    (the solver's own ``newton_raphson``, one iteration more each time, until the solver's
    tolerance), and whether the pose reached is the solver's."""
    scene = ctx.scene
    system = constraints.ConstraintSystem(scene, step.links)
    known = constraints.states({k: ctx.analysis.motion.links[k] for k in system.known}, scene)
    tolerance = group_report(ctx, step).tolerance
    q0 = system.drawn()[None]
    residuals: list[float] = []
    q = q0
    for k in range(MAX_SHOWN_ITERATIONS + 1):
        q, residual, done, _ = newton.newton_raphson(
            system, known, q0, tolerance, polish=False, max_iterations=k
        )
        residuals.append(float(residual[0]))
        if done < k or residual[0] <= tolerance:
            break
    solver_q = np.concatenate(
        [
            np.append(ctx.pos(scene.links[k].points[0]), ctx.analysis.motion.links[k].theta[0])
            for k in step.links
        ]
    )
    weights = np.tile([1.0, 1.0, scene.size], len(step.links))
    gap = float(np.max(np.abs((q[0] - solver_q) * weights)))
    return residuals, gap <= 1e-9 * scene.size


def group_report(ctx: LinkageContext, step: NewtonStep) -> newton.NewtonReport:
    """The solver's diagnostics of the group: its iterations, residual and tolerance."""
    return next(r for r in ctx.analysis.diagnostics.newton if set(r.links) == set(step.links))


def newton_position_step(ctx: LinkageContext, step: NewtonStep) -> Step:
    """Phi(q) = 0, the joints' equations in q = (x, y, theta) of each link of the group (its first
    point and its rotation from the drawing), solved numerically (``newton_iterations``)."""
    b = ctx.builder("position.newton", f"Position of links {', '.join(step.links)}: Newton-Raphson")
    residuals, same = newton_iterations(ctx, step)
    report = group_report(ctx, step)
    for k, r in enumerate(residuals):
        b.put(f"|Phi(q_{k})|", r, "m")
    b.put("iterations (solver)", float(report.iterations), "")
    b.put("residual (solver)", report.residual_norm, "m")
    b.put("tolerance", report.tolerance, "m")
    newton_lines(b, ctx, step, residuals, same)
    return b.build()


def newton_lines(
    b: StepBuilder, ctx: LinkageContext, step: NewtonStep, residuals: list[float], same: bool
) -> None:
    """Write the joints' equations, the iteration, the residuals and the solver's diagnostics."""
    report = group_report(ctx, step)
    joints = [n for n, joint in enumerate(ctx.scene.joints) if set(joint.links) & set(step.links)]
    equations = [_joint_equation(ctx, n) for n in joints]
    unknowns = ", ".join(
        rf"x_{{{tex.name(k)}}}, y_{{{tex.name(k)}}}, \theta_{{{tex.name(k)}}}" for k in step.links
    )
    for latex, _ in equations:
        b.line("&" + latex)
    b.line(
        rf"&\vec{{q}} = ({unknowns}), \quad \vec{{q}}_{{k+1}} = \vec{{q}}_k - "
        rf"J(\vec{{q}}_k)^{{-1}}\,\Phi(\vec{{q}}_k), \quad \vec{{q}}_0 = \text{{drawn pose}}"
    )
    header = " & ".join(str(k) for k in range(len(residuals)))
    row = " & ".join(_power(r) for r in residuals)
    b.line(
        r"&\begin{array}{c|" + "c" * len(residuals) + r"} k & " + header + r" \\ \hline "
        r"|\Phi(\vec{q}_k)|\ (\mathrm{m}) & " + row + r" \end{array}"
    )
    plural = "" if report.iterations == 1 else "s"
    b.line(
        rf"&\text{{solver: }} {report.iterations} \text{{ iteration{plural}, residual }} "
        rf"{_power(report.residual_norm)}\,\mathrm{{m}} \le "
        rf"{_power(report.tolerance)}\,\mathrm{{m}}"
    )
    b.say(newton_text(step, [text for _, text in equations], report, residuals, same))


def newton_text(
    step: NewtonStep,
    equations: list[str],
    report: newton.NewtonReport,
    residuals: list[float],
    same: bool,
) -> str:
    """The Newton step in words: the equations, the iteration, the residuals, the solver's."""
    plural = "" if report.iterations == 1 else "s"
    reached = (
        ", and the pose reached is the solver's."
        if same
        else ", and lands on another assembly than the solver's, which follows the "
        "linkage continuously from its drawing (the branch rule): the solver's pose is used."
    )
    return (
        f"Links {', '.join(step.links)} form no group with a closed-form solution: their joints "
        "give as many equations Phi(q) = 0 as unknowns, each link's first point (x, y) and its "
        "rotation theta from the drawing: "
        + "; ".join(equations)
        + ". The equations are not linear in the angles, so they are solved numerically, by "
        "Newton-Raphson: q(k+1) = q(k) - J(q(k))^-1 Phi(q(k)), J the Jacobian of Phi. Started "
        "from the drawn pose, the residual |Phi| falls as "
        + ", ".join(f"{r:.1e} m" for r in residuals)
        + reached
        + f" The solver (solver diagnostics) took {report.iterations} iteration{plural} from "
        f"its continuation's start, to a residual of {report.residual_norm:.1e} m, below the "
        f"tolerance {report.tolerance:.1e} m: the numbers are exact to rounding."
    )


def group_step(ctx: LinkageContext, step: PlanStep) -> Step | None:
    """The position step of one group of the solver's plan (None: nothing to derive)."""
    if isinstance(step, DriverStep):
        return crank_step(ctx, step)
    if isinstance(step, DyadStep):
        circles = [s for s in step.loci if isinstance(s, CircleSpec)]
        lines = [s for s in step.loci if isinstance(s, LineSpec)]
        if len(circles) == 2:
            return triangle_step(ctx, step, circles[0], circles[1])
        if circles and lines:
            return slider_step(ctx, step, circles[0], lines[0])
    if isinstance(step, LeverStep):
        return lever_step(ctx, step)
    if isinstance(step, NewtonStep):
        return newton_position_step(ctx, step)
    return None


def position_steps(ctx: LinkageContext) -> list[Step]:
    """The position analysis of the analysed pose, group by group of the solver's plan."""
    built = (ctx.replayed(partial(group_step, ctx, step)) for step in ctx.analysis.plan.steps)
    return [step for step in built if step is not None]

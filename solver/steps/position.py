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

import numpy as np

from solver.steps import latex as tex
from solver.steps.builder import StepBuilder
from solver.steps.format import latex_unit
from solver.steps.linkage import LinkageContext
from solver.steps.model import Step
from solver.topology import CircleSpec, DriverStep, DyadStep, LineSpec

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


def triangle_step(
    ctx: LinkageContext, step: DyadStep, first: CircleSpec, second: CircleSpec
) -> Step:
    x = step.point
    c1, c2 = first.center, second.center
    b = ctx.builder("position.triangle", f"Position of {x}: the triangle {c1}{x}{c2}")
    p1, p2, target = _point(b, ctx, c1), _point(b, ctx, c2), _point(b, ctx, x)
    r1 = b.put(f"|{c1}{x}|", first.radius, "m")
    r2 = b.put(f"|{c2}{x}|", second.radius, "m")
    dv = ctx.pos(c2) - ctx.pos(c1)
    dk = b.put(f"r({c1},{c2})", dv, "m")
    d = b.put(f"|{c1}{c2}|", float(np.hypot(*dv)), "m")
    b.check("sum", dk, p2, f"-{p1}")
    b.check("norm", d, dk)
    sq = {k: b.put(f"{k}^2", b.scalar(k) ** 2, "m^2") for k in (r1, r2, d)}
    for k, v in sq.items():
        b.check("product", v, k, k)
    num = b.put("r1^2 + d^2 - r2^2", b.scalar(sq[r1]) + b.scalar(sq[d]) - b.scalar(sq[r2]), "m^2")
    den = b.put("2 r1 d", 2 * b.scalar(r1) * b.scalar(d), "m^2")
    cos = b.put("cos gamma", b.scalar(num) / b.scalar(den), "")
    b.check("sum", num, sq[r1], sq[d], f"-{sq[r2]}")
    b.check("product", den, r1, d, factor=2.0)
    b.check("quotient", cos, num, den)
    rx = ctx.pos(x) - ctx.pos(c1)
    side = float(dv[0] * rx[1] - dv[1] * rx[0])
    # the angle from the drawn geometry (acos loses digits where the triangle is nearly flat)
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
    arm = b.put(f"r({c1},{x})", rx, "m")
    b.check("phasor", arm, r1, angle)
    b.check("sum", target, p1, arm)
    where = "left" if sign > 0 else "right"
    pm = "+" if sign > 0 else "-"
    b.line(
        rf"&\cos\gamma = \frac{{r_1^2 + d^2 - r_2^2}}{{2\,r_1\,d}}, \quad "
        rf"{tex.name(x)} = {tex.name(c1)} + r_1\,e^{{i(\theta_d {pm} \gamma)}}"
    )
    b.line(
        rf"&d = |{tex.name(c1)}{tex.name(c2)}| = {b.numu(d)}, \quad \cos\gamma = "
        rf"\frac{{{b.num(sq[r1])} + {b.num(sq[d])} - {b.num(sq[r2])}}}{{{b.num(den)}}} = "
        rf"{b.num(cos)}, \quad \gamma = {b.numu(gamma)}, \quad \theta_d = {b.numu(theta_d)}"
    )
    b.line(
        rf"&{tex.name(x)} = {b.point(p1)} + {b.num(r1)}\,e^{{i\,{tex.paren(b.num(angle))}}} = "
        rf"{tex.boxed_result(b.point(target) + latex_unit('m'))}"
    )
    b.say(
        f"{x} is at {b.txt(r1)} from {c1} (link {first.link}) and {b.txt(r2)} from {c2} (link "
        f"{second.link}); {c1}{c2} = {b.txt(d)}. The law of cosines gives cos gamma = "
        f"(r1^2 + d^2 - r2^2)/(2 r1 d) = {b.txtn(cos)}, gamma = {b.txt(gamma)}, the angle at "
        f"{c1} between {c1}{c2} (at theta_d = {b.txt(theta_d)}) and {c1}{x}. Two assemblies "
        f"close the triangle, theta_d + gamma and theta_d - gamma; the one taken is {x} on the "
        f"{where} of {c1}{c2}, as drawn (the solver keeps the drawn branch): {x} = {b.txt(target)}."
    )
    return b.build()


def slider_step(ctx: LinkageContext, step: DyadStep, circle: CircleSpec, line: LineSpec) -> Step:
    x, c = step.point, circle.center
    b = ctx.builder("position.slider", f"Position of {x}: link {circle.link} and the fixed guide")
    pc, target = _point(b, ctx, c), _point(b, ctx, x)
    u_np = np.asarray(line.direction0, dtype=float)
    u_np = u_np / float(np.hypot(*u_np))
    q = b.put("Q", line.through0, "m")
    u = b.put("u", u_np, "")
    r = b.put(f"|{c}{x}|", circle.radius, "m")
    cq = b.put(f"{c} - Q", ctx.pos(c) - np.asarray(line.through0), "m")
    b.check("sum", cq, pc, f"-{q}")
    h = b.put("h", float(u_np[0] * b.vector(cq)[1] - u_np[1] * b.vector(cq)[0]), "m")
    along = b.put("(C - Q).u", float(np.dot(b.vector(cq), u_np)), "m")
    b.check("cross", h, u, cq)
    b.check("dot", along, cq, u)
    s_value = float(np.dot(ctx.pos(x) - np.asarray(line.through0), u_np))
    w = b.put("w", abs(s_value - b.scalar(along)), "m")  # sqrt(r^2 - h^2), from the pose
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
    pm = "+" if sign > 0 else "-"
    b.line(
        rf"&h = \vec{{u}} \times ({tex.name(c)} - Q), \quad w = \sqrt{{r^2 - h^2}}, \quad "
        rf"{tex.name(x)} = Q + ((\,{tex.name(c)} - Q) \cdot \vec{{u}} {pm} w)\,\vec{{u}}"
    )
    b.line(
        rf"&h = {b.numu(h)}, \quad w = \sqrt{{{b.num(r2)} - {b.num(h2)}}} = {b.numu(w)}, "
        rf"\quad s = {b.num(along)} {pm} {b.num(w)} = {b.numu(s)}"
    )
    b.line(
        rf"&{tex.name(x)} = {b.point(q)} + {tex.paren(b.num(s))}\,{b.point(u)} = "
        rf"{tex.boxed_result(b.point(target) + latex_unit('m'))}"
    )
    where = "ahead of" if sign > 0 else "behind"
    b.say(
        f"{x} is at r = {b.txt(r)} from {c} (link {circle.link}) and on the fixed guide through "
        f"Q = {b.txt(q)} along u = {b.txtn(u)}. {c} is at h = {b.txt(h)} from the guide; the "
        f"circle meets it at w = sqrt(r^2 - h^2) = {b.txt(w)} on either side of the foot of "
        f"{c}. The assembly taken is {x} {where} the foot along u, as drawn: s = {b.txt(s)}, "
        f"{x} = {b.txt(target)}."
    )
    return b.build()


def position_steps(ctx: LinkageContext) -> list[Step]:
    """The position analysis of the analysed pose, group by group of the solver's plan."""
    out: list[Step] = []
    for step in ctx.analysis.plan.steps:
        if isinstance(step, DriverStep):
            crank = crank_step(ctx, step)
            if crank is not None:
                out.append(crank)
        elif isinstance(step, DyadStep):
            circles = [s for s in step.loci if isinstance(s, CircleSpec)]
            lines = [s for s in step.loci if isinstance(s, LineSpec)]
            if len(circles) == 2:
                out.append(triangle_step(ctx, step, circles[0], circles[1]))
            elif circles and lines and lines[0].guide == ctx.scene.ground:
                out.append(slider_step(ctx, step, circles[0], lines[0]))
    return out

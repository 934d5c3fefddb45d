"""RRP in the worked solutions: a joint point on a circle and a straight guide (the
slider-crank's coupler and slider; the guide fixed, or a slot of a moving link), the
slider-crank loop it closes, its dyad in the vector method.

With the guide through Q along u and the circle about C of radius r: the offset h = u x (C - Q),
the foot F = Q + ((C - Q) . u) u, and X = F +- w u with w = sqrt(r^2 - h^2); the sign is the
assembly, the side of the foot on which X is drawn.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from solver.position.topology import CircleSpec, DyadStep, LineSpec
from solver.solutions import latex as tex
from solver.solutions.builder import StepBuilder
from solver.solutions.equation import Boxed, Num, Paren, Pt, Ref
from solver.solutions.groups.base import DyadSolution, SolutionGroup
from solver.solutions.groups.pose import point_value, slot_now
from solver.solutions.linkage import LinkageContext
from solver.solutions.model import Step

if TYPE_CHECKING:
    from solver.solutions.loop import Loop, LoopMethod


@dataclass(frozen=True)
class SliderValues:
    """The values of X = Q + ((C - Q) . u +- w) u: Q, u, r, h = u x (C - Q), (C - Q) . u,
    w = sqrt(r^2 - h^2), r^2, h^2, s and X; ``sign`` +1 where X is ahead of C's foot along u
    (the drawn assembly), -1 behind it."""

    q: Ref
    u: Ref
    r: Ref
    h: Ref
    along: Ref
    w: Ref
    r2: Ref
    h2: Ref
    s: Ref
    target: Ref
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


def slider_values(
    b: StepBuilder, ctx: LinkageContext, x: str, circle: CircleSpec, line: LineSpec
) -> SliderValues:
    """The circle-line intersection's numbers, with a check for each piece of arithmetic;
    w comes from the pose (the distance of X from C's foot)."""
    c = circle.center
    pc, target = point_value(b, ctx, c), point_value(b, ctx, x)
    q, u = slot_now(b, ctx, line)
    q_np, u_np = np.asarray(b.vector(q)), np.asarray(b.vector(u))
    r = b.value(f"|{c}{x}|", circle.radius, "m")
    cq = b.value(f"{c} - Q", ctx.pos(c) - q_np, "m")
    b.check("sum", cq, pc, -q)
    h = b.value("h", float(u_np[0] * b.vector(cq)[1] - u_np[1] * b.vector(cq)[0]), "m")
    along = b.value("(C - Q).u", float(np.dot(b.vector(cq), u_np)), "m")
    b.check("cross", h, u, cq)
    b.check("dot", along, cq, u)
    s_value = float(np.dot(ctx.pos(x) - q_np, u_np))
    w = b.value("w", abs(s_value - b.scalar(along)), "m")
    r2, h2, w2 = (b.value(f"{k.key}^2", b.scalar(k) ** 2, "m^2") for k in (r, h, w))
    for key, base in ((r2, r), (h2, h), (w2, w)):
        b.check("product", key, base, base)
    b.check("sum", r2, w2, h2)
    sign = 1.0 if s_value >= b.scalar(along) else -1.0
    s = b.value("s", s_value, "m")
    b.check("sum", s, along, w if sign > 0 else -w)
    offset = b.value("s u", s_value * u_np, "m")
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
        "&h = ",
        Num(v.h, unit=True),
        r", \quad w = \sqrt{",
        Num(v.r2),
        " - ",
        Num(v.h2),
        "} = ",
        Num(v.w, unit=True),
        r", \quad s = ",
        Num(v.along),
        f" {pm} ",
        Num(v.w),
        " = ",
        Num(v.s, unit=True),
    )
    b.line(
        f"&{tex.name(x)} = ",
        Pt(v.q),
        " + ",
        Paren(v.s),
        r"\,",
        Pt(v.u),
        " = ",
        Boxed((Pt(v.target, "m"),)),
    )
    b.say(
        f"{x} is at r = ",
        Num(v.r, unit=True),
        f" from {c} (link {circle.link}) and on the {guide} through Q = ",
        Pt(v.q),
        " along u = ",
        Num(v.u),
        f". {c} is at h = ",
        Num(v.h, unit=True),
        " from the guide; the circle meets it at w = sqrt(r^2 - h^2) = ",
        Num(v.w, unit=True),
        f" on either side of the foot of {c}. The assembly taken is {x} "
        f"{'ahead of' if v.sign > 0 else 'behind'} the foot along u, as drawn: s = ",
        Num(v.s, unit=True),
        f", {x} = ",
        Pt(v.target),
        ".",
    )


class RRP(DyadSolution):
    """The RRP dyad: the circle and the guide; the slider-crank loop."""

    def position_step(self, ctx: LinkageContext, step: DyadStep) -> Step:
        return slider_step(ctx, step, self.circles(step)[0], self.slots(step)[0])

    def loop(self, method: LoopMethod, step: DyadStep) -> Loop:
        return method.slider_crank_loop(step.point, self.circles(step)[0], self.slots(step)[0])


GROUP: SolutionGroup = RRP("RRP", loop_mistakes=("loop.real_slider",))

"""RRR in the worked solutions: the triangle C1 X C2 of a joint point on two circles (the
four-bar's coupler and rocker), the four-bar loop it closes, its dyad in the vector method.

By the law of cosines cos gamma = (r1^2 + d^2 - r2^2) / (2 r1 d), then X = C1 + r1 e^(i (theta_d
+- gamma)), theta_d the direction of C1 C2; the sign is the assembly, the side of C1 C2 on which
X is drawn.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from solver.position.groups.rrr import chord
from solver.position.topology import CircleSpec, DyadStep
from solver.solutions import latex as tex
from solver.solutions.builder import StepBuilder
from solver.solutions.equation import Boxed, Num, Paren, Pt, Ref
from solver.solutions.groups.base import DyadSolution, SolutionGroup
from solver.solutions.groups.pose import point_value
from solver.solutions.linkage import LinkageContext
from solver.solutions.model import Step

if TYPE_CHECKING:
    from solver.solutions.loop import Loop, LoopMethod


@dataclass(frozen=True)
class TriangleValues:
    """The values of X = C1 + r1 e^(i (theta_d +- gamma)) in the triangle C1 X C2: C1, X, r1,
    r2, d = |C1 C2|, the squares r1^2, r2^2, d^2, 2 r1 d, cos gamma, gamma, theta_d and theta;
    ``sign`` +1 where X lies on the left of C1 C2 (the drawn assembly), -1 on its right."""

    p1: Ref
    target: Ref
    r1: Ref
    r2: Ref
    d: Ref
    squares: tuple[Ref, Ref, Ref]
    den: Ref
    cos: Ref
    gamma: Ref
    theta_d: Ref
    angle: Ref
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
    p1, p2, target = point_value(b, ctx, c1), point_value(b, ctx, c2), point_value(b, ctx, x)
    r1 = b.value(f"|{c1}{x}|", first.radius, "m")
    r2 = b.value(f"|{c2}{x}|", second.radius, "m")
    dv = ctx.pos(c2) - ctx.pos(c1)
    cut = chord(dv[None], first.radius, second.radius)  # the position layer's RRR
    dk = b.value(f"r({c1},{c2})", dv, "m")
    d = b.value(f"|{c1}{c2}|", float(cut.d[0]), "m")
    b.check("sum", dk, p2, -p1)
    b.check("norm", d, dk)
    squares, den, cos = cosine_law(b, r1, r2, d, float(cut.a[0]) / first.radius)
    rx = ctx.pos(x) - ctx.pos(c1)
    gamma, theta_d, angle, sign = triangle_angle(b, dv, rx, cos, dk)
    arm = b.value(f"r({c1},{x})", rx, "m")
    b.check("phasor", arm, r1, angle)
    b.check("sum", target, p1, arm)
    return TriangleValues(p1, target, r1, r2, d, squares, den, cos, gamma, theta_d, angle, sign)


def cosine_law(
    b: StepBuilder, r1: Ref, r2: Ref, d: Ref, cos_gamma: float
) -> tuple[tuple[Ref, Ref, Ref], Ref, Ref]:
    """cos gamma = (r1^2 + d^2 - r2^2) / (2 r1 d) = a / r1, a the distance from C1 to the
    common chord (``rrr.chord``): the values (r1^2, r2^2, d^2), 2 r1 d and cos gamma."""
    sq = {k: b.value(f"{k.key}^2", b.scalar(k) ** 2, "m^2") for k in (r1, r2, d)}
    for k, v in sq.items():
        b.check("product", v, k, k)
    num = b.value("r1^2 + d^2 - r2^2", b.scalar(sq[r1]) + b.scalar(sq[d]) - b.scalar(sq[r2]), "m^2")
    den = b.value("2 r1 d", 2 * b.scalar(r1) * b.scalar(d), "m^2")
    cos = b.value("cos gamma", cos_gamma, "")
    b.check("sum", num, sq[r1], sq[d], -sq[r2])
    b.check("product", den, r1, d, factor=2.0)
    b.check("quotient", cos, num, den)
    return (sq[r1], sq[r2], sq[d]), den, cos


def triangle_angle(
    b: StepBuilder, dv: np.ndarray, rx: np.ndarray, cos: Ref, dk: Ref
) -> tuple[Ref, Ref, Ref, float]:
    """gamma, the angle at C1 between C1 C2 (``dv``) and C1 X (``rx``), theta_d = arg C1 C2
    and theta = theta_d +- gamma, the sign that of X's side of C1 C2 (as drawn). gamma comes
    from the drawn geometry (acos loses digits where the triangle is nearly flat) and is
    checked against cos gamma. Returns gamma, theta_d, theta and the sign."""
    side = float(dv[0] * rx[1] - dv[1] * rx[0])
    gamma_value = math.atan2(abs(side), float(np.dot(dv, rx)))
    gamma = b.value("gamma", gamma_value, "rad")
    one = b.value("1", 1.0, "")
    unit = b.value("e^(i gamma)", (math.cos(gamma_value), math.sin(gamma_value)), "")
    b.check("phasor", unit, one, gamma)
    b.check("sum", cos, unit[0])
    theta_d = b.value("theta_d", math.atan2(dv[1], dv[0]), "rad")
    b.check("angle", theta_d, dk)
    sign = 1.0 if side >= 0 else -1.0
    angle = b.value("theta", b.scalar(theta_d) + sign * gamma_value, "rad")
    b.check("sum", angle, theta_d, gamma if sign > 0 else -gamma)
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
        rf"&d = |{tex.name(c1)}{tex.name(c2)}| = ",
        Num(v.d, unit=True),
        r", \quad \cos\gamma = \frac{",
        Num(r1_sq),
        " + ",
        Num(d_sq),
        " - ",
        Num(r2_sq),
        "}{",
        Num(v.den),
        "} = ",
        Num(v.cos),
        r", \quad \gamma = ",
        Num(v.gamma, unit=True),
        r", \quad \theta_d = ",
        Num(v.theta_d, unit=True),
    )
    b.line(
        f"&{tex.name(x)} = ",
        Pt(v.p1),
        " + ",
        Num(v.r1),
        r"\,e^{i\,",
        Paren(v.angle),
        "} = ",
        Boxed((Pt(v.target, "m"),)),
    )
    b.say(
        f"{x} is at ",
        Num(v.r1, unit=True),
        f" from {c1} (link {first.link}) and ",
        Num(v.r2, unit=True),
        f" from {c2} (link {second.link}); {c1}{c2} = ",
        Num(v.d, unit=True),
        ". The law of cosines gives cos gamma = (r1^2 + d^2 - r2^2)/(2 r1 d) = ",
        Num(v.cos),
        ", gamma = ",
        Num(v.gamma, unit=True),
        f", the angle at {c1} between {c1}{c2} (at theta_d = ",
        Num(v.theta_d, unit=True),
        f") and {c1}{x}. Two assemblies close the triangle, theta_d + gamma and theta_d - gamma; "
        f"the one taken is {x} on the {'left' if v.sign > 0 else 'right'} of {c1}{c2}, as drawn "
        f"(the solver keeps the drawn branch): {x} = ",
        Pt(v.target),
        ".",
    )


class RRR(DyadSolution):
    """The RRR dyad: the triangle; the four-bar loop."""

    def position_step(self, ctx: LinkageContext, step: DyadStep) -> Step:
        first, second = self.circles(step)
        return triangle_step(ctx, step, first, second)

    def loop(self, method: LoopMethod, step: DyadStep) -> Loop:
        first, second = self.circles(step)
        return method.four_bar_loop(step.point, first, second)


GROUP: SolutionGroup = RRR("RRR")

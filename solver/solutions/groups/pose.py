"""What the groups' position steps share: a point's position as a value, and a slot now.

A slot fixed in the ground is as drawn (through Q0 along u0); a slot in a moving guide G is the
drawn line turned with G about its first point A: Q = A + e^(i theta_G) (Q0 - A0),
u = e^(i (beta0 + theta_G)).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from solver.position.topology import LineSpec
from solver.solutions import latex as tex
from solver.solutions.builder import StepBuilder
from solver.solutions.equation import Num, Paren, Pt, Ref
from solver.solutions.linkage import LinkageContext


def point_value(b: StepBuilder, ctx: LinkageContext, name: str) -> Ref:
    """The position of the point ``name`` as a value of the step."""
    return b.value(f"pos({name})", ctx.pos(name), "m", ("points", name, "position"))


@dataclass(frozen=True)
class CarriedLine:
    """The values of a moving guide's slot now, Q = A + |Q0 - A0| e^(i (phi0 + theta_rot)) and
    u = e^(i (beta0 + theta_rot)): A, theta_rot, Q0 - A0, |Q0 - A0|, phi0 + theta_rot, Q, u0,
    beta0, beta and u."""

    anchor: Ref
    turn: Ref
    d0: Ref
    size: Ref
    phi: Ref
    q: Ref
    u0: Ref
    beta0: Ref
    beta: Ref
    u: Ref


def carried_line(b: StepBuilder, ctx: LinkageContext, line: LineSpec) -> tuple[Ref, Ref]:
    """The slot of a moving guide G now: Q = A + e^(i theta_G) (Q0 - A0) and u = e^(i (beta0 +
    theta_G)), the drawn line (through Q0 along u0) turned with G about its first point A by
    theta_G, the rotation of G since its drawing. Returns Q and u."""
    anchor = ctx.scene.links[line.guide].points[0]
    v = carried_line_values(b, ctx, line, anchor)
    carried_line_lines(b, line.guide, anchor, v)
    return v.q, v.u


def carried_line_values(
    b: StepBuilder, ctx: LinkageContext, line: LineSpec, anchor: str
) -> CarriedLine:
    """Q and u of the slot now, with a check for each piece of arithmetic."""
    pa = point_value(b, ctx, anchor)
    turn = b.value(
        f"theta_rot({line.guide})", float(ctx.analysis.motion.links[line.guide].theta[0]), "rad"
    )
    d0_np = np.asarray(line.through0, dtype=float) - ctx.scene.drawn(anchor)
    d0 = b.value("Q0 - A0", d0_np, "m")
    size = b.value("|Q0 - A0|", float(np.hypot(*d0_np)), "m")
    phi0 = b.value("phi0", math.atan2(d0_np[1], d0_np[0]), "rad")
    phi = b.value("phi0 + theta_rot", b.scalar(phi0) + b.scalar(turn), "rad")
    d = b.value(
        "Q - A", b.scalar(size) * np.array([math.cos(b.scalar(phi)), math.sin(b.scalar(phi))]), "m"
    )
    q = b.value("Q", np.asarray(b.vector(pa)) + np.asarray(b.vector(d)), "m")
    u0_np = np.asarray(line.direction0, dtype=float)
    u0 = b.value("u0", u0_np / float(np.hypot(*u0_np)), "")
    beta0 = b.value("beta0", math.atan2(u0_np[1], u0_np[0]), "rad")
    beta = b.value("beta", b.scalar(beta0) + b.scalar(turn), "rad")
    one = b.value("1", 1.0, "")
    u = b.value("u", (math.cos(b.scalar(beta)), math.sin(b.scalar(beta))), "")
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
        rf"&Q = {a} + e^{{i\theta_{{{gn}}}}}(Q_0 - {a}_0) = ",
        Pt(v.anchor),
        " + ",
        Num(v.size),
        r"\,e^{i\,",
        Paren(v.phi),
        "} = ",
        Pt(v.q, "m"),
        rf", \quad \vec{{u}} = e^{{i(\beta_0 + \theta_{{{gn}}})}} = e^{{i\,",
        Paren(v.beta),
        "} = ",
        Pt(v.u),
    )
    b.say(
        f"The slot is fixed in the moving link {g}: drawn through Q0 at ",
        Num(v.d0),
        f" m from {anchor} along u0 = ",
        Num(v.u0),
        " (angle beta0 = ",
        Num(v.beta0, unit=True),
        f"), and {g} has turned by theta_{g} = ",
        Num(v.turn, unit=True),
        f" about {anchor} since its drawing. So the slot now passes through Q = {anchor} + "
        f"e^(i theta_{g}) (Q0 - {anchor}0) = ",
        Pt(v.q),
        f" along u = e^(i (beta0 + theta_{g})) = ",
        Num(v.u),
        ".",
    )


def slot_now(b: StepBuilder, ctx: LinkageContext, line: LineSpec) -> tuple[Ref, Ref]:
    """Q and u of a slot now: as drawn in the ground, else ``carried_line``."""
    if line.guide != ctx.scene.ground:
        return carried_line(b, ctx, line)
    u_np = np.asarray(line.direction0, dtype=float)
    return b.value("Q", line.through0, "m"), b.value("u", u_np / float(np.hypot(*u_np)), "")

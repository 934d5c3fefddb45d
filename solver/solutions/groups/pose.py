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
from solver.solutions.format import latex_unit
from solver.solutions.linkage import LinkageContext


def point_value(b: StepBuilder, ctx: LinkageContext, name: str) -> str:
    """The position of the point ``name`` as a value of the step (its key)."""
    return b.put(f"pos({name})", ctx.pos(name), "m", ("points", name, "position"))


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
    pa = point_value(b, ctx, anchor)
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


def slot_now(b: StepBuilder, ctx: LinkageContext, line: LineSpec) -> tuple[str, str]:
    """The keys of Q and u of a slot now: as drawn in the ground, else ``carried_line``."""
    if line.guide != ctx.scene.ground:
        return carried_line(b, ctx, line)
    u_np = np.asarray(line.direction0, dtype=float)
    return b.put("Q", line.through0, "m"), b.put("u", u_np / float(np.hypot(*u_np)), "")

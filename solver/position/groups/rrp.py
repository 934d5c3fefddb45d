"""RRP: a joint point on a circle about a known centre and on a slot of a known link (the
slider-crank's coupler and slider)."""

from __future__ import annotations

import numpy as np

from solver.kinematics.rigid import Array, cross, dot, perp, scale
from solver.position.groups.base import DyadGroup
from solver.position.groups.loci import Circle, Intersection, Line, digits, root


def circle_line(c: Circle, line: Line, name: str) -> Intersection:
    """RRP: X = Q + t w with |X - C| = r: t = -b +/- sqrt(b^2 - c), b = w.(Q - C).

    The line is s = w x (Q - C) from C: margin m = r - |s| = min(r - s, r + s), the pieces'
    rates -+ ds/du with ds/du = omega (k x w) x (Q - C) + w x (v_Q - v_C).
    """
    q_c = line.through.p - c.center.p
    b = dot(line.direction, q_c)
    h2 = b**2 - (dot(q_c, q_c) - c.radius**2)
    s = cross(line.direction, q_c)
    margin = c.radius - np.abs(s)
    rates: tuple[Array | None, Array | None] = (None, None)
    if line.through.v is not None and c.center.v is not None and line.omega is not None:
        s_rate = line.omega * cross(perp(line.direction), q_c) + cross(
            line.direction, line.through.v - c.center.v
        )
        rates = (-s_rate, s_rate)

    def message() -> str:
        distance = abs(float(s[int(np.argmin(margin))]))
        n = digits(distance, c.radius)
        return (
            f"the distance from {c.center_name} to the slot of {name} in '{line.guide}' is "
            f"{distance:.{n}g} m > |{c.center_name}{name}| = {c.radius:.{n}g} m"
        )

    base = line.through.p - scale(b, line.direction)
    pieces = ((c.radius - s, rates[0]), (c.radius + s, rates[1]))
    return Intersection(base, line.direction, root(h2, c.radius**2), margin, pieces, message)


GROUP = DyadGroup("RRP", circle_line, two_branch=True)

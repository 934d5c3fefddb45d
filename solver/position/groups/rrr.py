"""RRR: a joint point on two circles about known centres (the four-bar's coupler-rocker dyad)."""

from __future__ import annotations

import numpy as np

from solver.kinematics.rigid import Array, dot, perp, scale
from solver.position.groups.base import DyadGroup
from solver.position.groups.loci import Circle, Intersection, digits, root


def circle_circle(c1: Circle, c2: Circle, name: str) -> Intersection:
    """RRR: d = |C1C2|, a = (r1^2 - r2^2 + d^2) / 2d along C1C2, h^2 = r1^2 - a^2 across.

    Margin m = min(r1 + r2 - d, d - |r1 - r2|), the pieces' rates -+ dd/du = -+ u.(v2 - v1),
    u = (C2 - C1) / d.
    """
    d_vec = c2.center.p - c1.center.p
    d = np.sqrt(dot(d_vec, d_vec))
    safe_d = np.where(d > 0.0, d, 1.0)
    u = d_vec / safe_d[:, None]
    u[d == 0.0] = (1.0, 0.0)  # coincident centres: any direction (every point of the circle fits)
    a = (c1.radius**2 - c2.radius**2 + d**2) / (2.0 * safe_d)
    h2 = c1.radius**2 - a**2
    total, diff = c1.radius + c2.radius, abs(c1.radius - c2.radius)
    extended, folded = total - d, d - diff
    margin = np.minimum(extended, folded)
    rates: tuple[Array | None, Array | None] = (None, None)
    if c1.center.v is not None and c2.center.v is not None:
        d_rate = dot(u, c2.center.v - c1.center.v)
        rates = (-d_rate, d_rate)

    def message() -> str:
        dk = float(d[int(np.argmin(margin))])
        n = digits(dk, total if dk > total else diff)
        pair = f"|{c1.center_name}{c2.center_name}| = {dk:.{n}g} m"
        if dk > total:
            return (
                f"{pair} > |{c1.center_name}{name}| + |{c2.center_name}{name}| = "
                f"{c1.radius:.{n}g} + {c2.radius:.{n}g} = {total:.{n}g} m"
            )
        return f"{pair} < ||{c1.center_name}{name}| - |{c2.center_name}{name}|| = {diff:.{n}g} m"

    pieces = ((extended, rates[0]), (folded, rates[1]))
    return Intersection(
        c1.center.p + scale(a, u), perp(u), root(h2, c1.radius**2), margin, pieces, message
    )


GROUP = DyadGroup("RRR", circle_circle)

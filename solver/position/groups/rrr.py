"""RRR: a joint point on two circles about known centres (the four-bar's coupler-rocker dyad)."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from solver.kinematics.rigid import Array, dot, perp, scale
from solver.position.groups.base import DyadGroup
from solver.position.groups.loci import Circle, Intersection, digits, root


@dataclass(frozen=True)
class Chord:
    """The common chord of two circles, column by column over samples (``chord``)."""

    d: Array
    ux: Array
    uy: Array
    a: Array
    h2: Array


def chord(dx: Array, dy: Array, r1: float, r2: float) -> Chord:
    """RRR: d = |C1C2|, u = (C2 - C1) / d, a = (r1^2 - r2^2 + d^2) / 2d along C1C2 from C1,
    h^2 = r1^2 - a^2 across it, from (dx, dy) = C2 - C1; coincident centres (d = 0) take
    u = (1, 0): any direction (every point of the circle fits). The RRR formula, once: the
    assembler's ``circle_circle`` and the compiled plan's columns both use it."""
    d = np.sqrt(dx * dx + dy * dy)
    safe_d = d if d.min() > 0.0 else np.where(d > 0.0, d, 1.0)
    ux, uy = dx / safe_d, dy / safe_d
    if safe_d is not d:
        ux[d == 0.0], uy[d == 0.0] = 1.0, 0.0
    a = (r1**2 - r2**2 + d**2) / (2.0 * safe_d)
    return Chord(d, ux, uy, a, r1**2 - a**2)


def circle_circle(c1: Circle, c2: Circle, name: str) -> Intersection:
    """RRR: the point at a along C1C2 and h across it (``chord``).

    Margin m = min(r1 + r2 - d, d - |r1 - r2|), the pieces' rates -+ dd/du = -+ u.(v2 - v1),
    u = (C2 - C1) / d.
    """
    d_vec = c2.center.p - c1.center.p
    cut = chord(d_vec[:, 0], d_vec[:, 1], c1.radius, c2.radius)
    d, a, h2 = cut.d, cut.a, cut.h2
    u = np.stack((cut.ux, cut.uy), axis=-1)
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


GROUP = DyadGroup("RRR", circle_circle, two_branch=True)

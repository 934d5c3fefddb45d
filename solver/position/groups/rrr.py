"""RRR: a joint point on two circles about known centres (the four-bar's coupler-rocker dyad)."""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from typing import TYPE_CHECKING, cast

import numpy as np

from solver.kinematics.rigid import (
    Array,
    PointMotion,
    Relative,
    dot,
    omega_cross,
    perp,
    scale,
    solve_2x2,
)
from solver.position.groups.base import Closure, DyadGroup, Known, Placed
from solver.position.groups.loci import Circle, Intersection, Piece, digits, root

if TYPE_CHECKING:
    from solver.position.topology import CircleSpec, DyadStep


@dataclass(frozen=True, init=False)
class Chord:
    """The common chord of two circles, column by column over samples (``chord``): ``u`` is
    (N, 2), the others (N,). (Frozen, its fields written at once as ``rigid.PointMotion``'s.)"""

    d: Array
    u: Array
    a: Array
    h2: Array

    def __init__(self, d: Array, u: Array, a: Array, h2: Array) -> None:
        fields = self.__dict__
        fields["d"], fields["u"], fields["a"], fields["h2"] = d, u, a, h2


def chord(d_vec: Array, r1: float, r2: float) -> Chord:
    """RRR: d = |C1C2|, u = (C2 - C1) / d, a = (r1^2 - r2^2 + d^2) / 2d along C1C2 from C1,
    h^2 = r1^2 - a^2 across it, from ``d_vec`` = C2 - C1 (N, 2); coincident centres (d = 0) take
    u = (1, 0): any direction (every point of the circle fits). The RRR formula, once: the
    intersection of two circles (``circle_circle``) and the group's closure (``GROUP``) use it."""
    squares = d_vec * d_vec
    d = np.sqrt(squares[..., 0] + squares[..., 1])
    safe_d = _positive(d)
    u = d_vec / safe_d[..., None]  # (both coordinates at once: ``rigid.points``)
    if safe_d is not d:
        u[d == 0.0] = (1.0, 0.0)
    a = (r1**2 - r2**2 + d**2) / (2.0 * safe_d)
    return Chord(d, u, a, r1**2 - a**2)


def margin_pieces(d: Array, r1: float, r2: float) -> tuple[Array, Array]:
    """The smooth pieces of the margin m = min(r1 + r2 - d, d - |r1 - r2|): the dyad stretched
    (r1 + r2 - d) and folded (d - |r1 - r2|)."""
    return (r1 + r2) - d, d - abs(r1 - r2)


def piece_rates(u: Array, v1: Array | None, v2: Array | None) -> tuple[Array | None, Array | None]:
    """The rates of the margin's pieces (stretched, folded: ``margin_pieces``) as C1 and C2
    move: -+ dd/du = -+ u.(v2 - v1), u = (C2 - C1) / d; None without velocities."""
    if v1 is None or v2 is None:
        return None, None
    d_rate = dot(u, v2 - v1)
    return -d_rate, d_rate


def failure(
    d: Array, margin: Array, centres: tuple[str, str], radii: tuple[float, float], name: str
) -> Callable[[], str]:
    """Why two circles about ``centres`` with ``radii`` fail to meet (built only when they do):
    their centres too far apart or too close, at the sample of the smallest margin."""
    (c1, c2), (r1, r2) = centres, radii
    total, diff = r1 + r2, abs(r1 - r2)

    def message() -> str:
        dk = float(d[int(np.argmin(margin))])
        n = digits(dk, total if dk > total else diff)
        pair = f"|{c1}{c2}| = {dk:.{n}g} m"
        if dk > total:
            return (
                f"{pair} > |{c1}{name}| + |{c2}{name}| = {r1:.{n}g} + {r2:.{n}g} = {total:.{n}g} m"
            )
        return f"{pair} < ||{c1}{name}| - |{c2}{name}|| = {diff:.{n}g} m"

    return message


def circle_circle(c1: Circle, c2: Circle, name: str) -> Intersection:
    """RRR: the point at a along C1C2 and h across it (``chord``).

    Margin m = min(r1 + r2 - d, d - |r1 - r2|), the pieces' rates -+ dd/du = -+ u.(v2 - v1),
    u = (C2 - C1) / d.
    """
    cut = chord(c2.center.p - c1.center.p, c1.radius, c2.radius)
    u = cut.u
    extended, folded = margin_pieces(cut.d, c1.radius, c2.radius)
    margin = np.minimum(extended, folded)
    rates = piece_rates(u, c1.center.v, c2.center.v)
    message = failure(cut.d, margin, (c1.center_name, c2.center_name), (c1.radius, c2.radius), name)
    pieces = ((extended, rates[0]), (folded, rates[1]))
    return Intersection(
        c1.center.p + scale(cut.a, u), perp(u), root(cut.h2, c1.radius**2), margin, pieces, message
    )


@dataclass(frozen=True)
class CircleCircle(DyadGroup):
    """RRR on the (N, 2) arrays of its centres' motions: the same numbers as ``circle_circle``
    (a centre at rest subtracted as its zeros, v - 0 = v exactly) with the x and y of a
    difference in one array operation; its rates from the differentiated constraints
    (``point_rates``)."""

    def close(self, step: DyadStep, known: Known) -> Closure:
        first, second = cast("tuple[CircleSpec, CircleSpec]", step.loci)  # (RRR)
        c1, c2 = known.points[first.center], known.points[second.center]
        r1, r2 = first.radius, second.radius
        cut = chord(c2.p - c1.p, r1, r2)
        extended, folded = margin_pieces(cut.d, r1, r2)
        margin = np.minimum(extended, folded)

        def pieces() -> tuple[Piece, ...]:
            """The pieces with their rates (``piece_rates``)."""
            stretching, folding = piece_rates(cut.u, c1.v, c2.v)
            return ((extended, stretching), (folded, folding))

        message = failure(cut.d, margin, (first.center, second.center), (r1, r2), step.point)
        resting = known.resting(second.center)

        def place(sign: Array | float, order: int) -> Placed:
            """X = C1 + a u + sign h (k x u), the drawn position at the drawn pose."""
            h = root(cut.h2, r1**2)
            # (one branch, +1, everywhere: h itself, as h 1.0 is, to the bit)
            across = h if isinstance(sign, float) and sign == 1.0 else sign * h
            X = c1.p + scale(cut.a, cut.u) + omega_cross(across, cut.u)
            X[known.at_drawn] = known.drawn(step.point)
            motion, sine, seen = point_rates(X, c1, c2, order, resting)
            relative = {(first.center, step.point): seen[0], (second.center, step.point): seen[1]}
            return Placed(sine, points={step.point: motion}, relative=relative)

        return Closure(step.point, margin, pieces, message, True, place)


def _positive(x: Array) -> Array:
    """np.where(x > 0, x, 1.0) for x >= 0 (a length, or a product of lengths): ``x`` itself where
    none is 0 (the common case; counted, cheaper than a reduction: a NaN, of a point not placed,
    stays NaN, and so does all that is computed from it)."""
    return x if np.count_nonzero(x) == x.size else np.where(x > 0.0, x, 1.0)


def point_rates(
    X: Array, c1: PointMotion, c2: PointMotion, order: int, c2_resting: bool = False
) -> tuple[PointMotion, Array, tuple[Relative, Relative]]:
    """``loci.point_motion`` for two circles about C1, C2: G v_X = b and G a_X = b' by Cramer's
    rule, G = [X - C1; X - C2], b_i = (X - C_i).v_Ci, b'_i = (X - C_i).a_Ci - |v_X - v_Ci|^2,
    and the sine of the angle between the rows, |det G| / (|g1| |g2|); ``c2_resting``: C2 at
    rest (v_X - v_C2 is v_X). With them, X seen from C1 and from C2 (``rigid.relative``: the
    rows g_i, |g_i|^2 and, with accelerations, v_X - v_Ci)."""
    g1, g2 = X - c1.p, X - c2.p
    g1x, g1y, g2x, g2y = g1[..., 0], g1[..., 1], g2[..., 0], g2[..., 1]
    det = g1x * g2y - g1y * g2x
    squares = dot(g1, g1), dot(g2, g2)
    sine = np.abs(det) / _positive(np.sqrt(squares[0] * squares[1]))
    if order < 1:
        return PointMotion(X), sine, (Relative(g1, squares[0]), Relative(g2, squares[1]))
    assert c1.v is not None and c2.v is not None
    if np.count_nonzero(det) < det.size:  # (counted: cheaper than det.all())
        det = np.where(det != 0.0, det, np.inf)
    rows = (g1x, g1y), (g2x, g2y)
    v = np.empty_like(X)
    solve_2x2(*rows, (dot(g1, c1.v), dot(g2, c2.v)), det, (v[..., 0], v[..., 1]))
    if order < 2:
        return PointMotion(X, v), sine, (Relative(g1, squares[0]), Relative(g2, squares[1]))
    assert c1.a is not None and c2.a is not None
    w1 = v - c1.v
    w2 = v if c2_resting else v - c2.v
    rhs = (
        dot(g1, c1.a) - dot(w1, w1),
        dot(g2, c2.a) - dot(w2, w2),
    )
    a = np.empty_like(X)
    solve_2x2(*rows, rhs, det, (a[..., 0], a[..., 1]))
    seen = Relative(g1, squares[0], w1), Relative(g2, squares[1], w2)
    return PointMotion(X, v, a), sine, seen


GROUP = CircleCircle("RRR", circle_circle, two_branch=True)

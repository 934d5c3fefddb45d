"""Closed-form solutions of the two-joint groups (dyads) a linkage decomposes into.

A joint point X whose two constraints involve only known links lies on two *loci*: a circle (X and
a known point C are on one link, so |CX| is fixed) or a line (X slides in a slot of a known
link). RRR is circle-circle, RRP (pin or block in a slot) circle-line, a pin in two slots
line-line. Where a link pivots on a known point and its slot must pass through a known pin
(inverted slider-crank, slotted lever), the unknown is the link's angle: ``slotted_lever``.

Each solution has two branches (the orientation of the dyad's triangle), chosen by ``sign``. The
velocities and accelerations come from differentiating the same two constraints: a 2-by-2 linear
system ``G v_X = b`` solved by Cramer's rule, vectorised over samples.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

from solver.kinematics.rigid import Array, PointMotion, cross, dot, perp, scale

EPS = float(np.finfo(float).eps)
# h^2 below this fraction of r^2 is rounding noise (h^2 = r^2 - a^2 is good to a few eps r^2):
# the point is on the tangency, h = 0 (a square root of the noise would be ~1e-8 r off).
TANGENCY_TOLERANCE = 16.0 * EPS
# The two branches of a group coincide within rounding where its length margin m (see
# ``Intersection``) is below this fraction of the linkage's size: a tangency, or two coincident
# centres. Rounding makes m uncertain by a few eps times the size (~1e-15 L); 1e-13 L is 100
# times that, and 10 times less than the closest approach of a linkage 1e-12 (relative to its
# longest link) off a change point.
COINCIDENCE_TOLERANCE = 1e-13

# A smooth piece of a group's length margin and its rate along the driver's path (None without
# velocities): the margin is the smallest of its pieces.
Piece = tuple[Array, Array | None]


@dataclass(frozen=True)
class Circle:
    """X is on a link that carries the known point ``center``: |X - C| = radius."""

    center: PointMotion
    radius: float
    center_name: str
    link: str


@dataclass(frozen=True)
class Line:
    """X slides on the line through Q with unit direction w, fixed in a known guide link."""

    through: PointMotion
    direction: Array
    omega: Array | None
    alpha: Array | None
    guide: str


Locus = Circle | Line


@dataclass(frozen=True)
class Intersection:
    """X = base + sign h offset for the two branches.

    ``margin`` m (metres) is how far the group is from having its two branches meet: the smallest
    of r1 + r2 - d and d - |r1 - r2| (two circles whose centres are d apart), of r - s and r + s
    (a circle and a line at signed distance s from its centre); negative where the loci do not
    meet, +inf where the group has one solution. ``pieces`` are those smooth functions with their
    rates (none for one solution): where two are equal m has a corner, a local maximum, so the
    branch search screens each piece on its own.
    """

    base: Array
    offset: Array
    h: Array
    margin: Array
    pieces: tuple[Piece, ...]
    describe: Callable[[], str]  # why the loci fail to meet (built only when they do)

    @property
    def message(self) -> str:
        return self.describe()

    def point(self, sign: Array) -> Array:
        return self.base + scale(sign * self.h, self.offset)


def _root(h2: Array, r2: float | Array) -> Array:
    """sqrt(h^2), a tangency within rounding (h^2 <= TANGENCY_TOLERANCE r^2) snapped to zero."""
    floor = TANGENCY_TOLERANCE * r2
    if isinstance(floor, float) and h2.min() > floor:  # no tangency anywhere (the common case)
        return np.sqrt(h2)
    return np.sqrt(np.where(h2 > floor, h2, 0.0))


def intersect(first: Locus, second: Locus, name: str) -> Intersection:
    """Both candidate positions of the point ``name`` on the two loci."""
    if isinstance(first, Line) and isinstance(second, Circle):
        first, second = second, first
    if isinstance(first, Circle) and isinstance(second, Circle):
        return _circle_circle(first, second, name)
    if isinstance(first, Circle) and isinstance(second, Line):
        return _circle_line(first, second, name)
    assert isinstance(first, Line) and isinstance(second, Line)
    return _line_line(first, second, name)


def _circle_circle(c1: Circle, c2: Circle, name: str) -> Intersection:
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
        n = _digits(dk, total if dk > total else diff)
        pair = f"|{c1.center_name}{c2.center_name}| = {dk:.{n}g} m"
        if dk > total:
            return (
                f"{pair} > |{c1.center_name}{name}| + |{c2.center_name}{name}| = "
                f"{c1.radius:.{n}g} + {c2.radius:.{n}g} = {total:.{n}g} m"
            )
        return f"{pair} < ||{c1.center_name}{name}| - |{c2.center_name}{name}|| = {diff:.{n}g} m"

    pieces = ((extended, rates[0]), (folded, rates[1]))
    return Intersection(
        c1.center.p + scale(a, u), perp(u), _root(h2, c1.radius**2), margin, pieces, message
    )


def _digits(a: float, b: float) -> int:
    """Significant digits (6 to 15) that show two different numbers as different."""
    return next((n for n in range(6, 16) if f"{a:.{n}g}" != f"{b:.{n}g}"), 15)


def _circle_line(c: Circle, line: Line, name: str) -> Intersection:
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
        n = _digits(distance, c.radius)
        return (
            f"the distance from {c.center_name} to the slot of {name} in '{line.guide}' is "
            f"{distance:.{n}g} m > |{c.center_name}{name}| = {c.radius:.{n}g} m"
        )

    base = line.through.p - scale(b, line.direction)
    pieces = ((c.radius - s, rates[0]), (c.radius + s, rates[1]))
    return Intersection(base, line.direction, _root(h2, c.radius**2), margin, pieces, message)


def _line_line(l1: Line, l2: Line, name: str) -> Intersection:
    """A pin in two slots: X = Q1 + t w1 with w2 x (X - Q2) = 0 (one solution: margin +inf)."""
    denominator = cross(l2.direction, l1.direction)
    parallel = np.abs(denominator) <= 1e-12
    t = cross(l2.direction, l2.through.p - l1.through.p) / np.where(parallel, 1.0, denominator)
    margin = np.where(parallel, -np.inf, np.inf)
    base = l1.through.p + scale(t, l1.direction)

    def message() -> str:
        return f"the two slots that carry {name} (in '{l1.guide}' and '{l2.guide}') are parallel"

    return Intersection(base, l1.direction, np.zeros_like(t), margin, (), message)


def _constraint_row(locus: Locus, X: Array) -> Array:
    """Gradient of the constraint: (X - C) for a circle, the slot normal n = k x w for a line."""
    return X - locus.center.p if isinstance(locus, Circle) else perp(locus.direction)


def _velocity_rhs(locus: Locus, row: Array, X: Array) -> Array:
    """Circle: (X-C).v_X = (X-C).v_C.   Line: n.v_X = n.v_Q + omega w.(X - Q).
    (``row`` is the constraint's gradient, X - C or n.)"""
    if isinstance(locus, Circle):
        assert locus.center.v is not None
        return dot(row, locus.center.v)
    assert locus.through.v is not None and locus.omega is not None
    return dot(row, locus.through.v) + locus.omega * dot(locus.direction, X - locus.through.p)


def _acceleration_rhs(locus: Locus, row: Array, X: Array, v_X: Array) -> Array:
    """Circle: (X-C).a_X = (X-C).a_C - |v_X - v_C|^2.
    Line: n.a_X = n.a_Q + 2 omega w.(v_X - v_Q) + alpha w.(X - Q)."""
    if isinstance(locus, Circle):
        assert locus.center.v is not None and locus.center.a is not None
        v_rel = v_X - locus.center.v
        return dot(row, locus.center.a) - dot(v_rel, v_rel)
    Q = locus.through
    assert Q.v is not None and Q.a is not None
    assert locus.omega is not None and locus.alpha is not None
    w = locus.direction
    return dot(row, Q.a) + 2.0 * locus.omega * dot(w, v_X - Q.v) + locus.alpha * dot(w, X - Q.p)


def solve_2x2(row1: Array, row2: Array, rhs1: Array, rhs2: Array, det: Array) -> Array:
    """Cramer's rule for [row1; row2] x = [rhs1; rhs2]: x = (|b r2|, |r1 b|) / |r1 r2|, with
    ``det`` = |r1 r2| (inf where it is 0)."""
    out = np.empty((det.size, 2))
    np.divide(rhs1 * row2[:, 1] - rhs2 * row1[:, 1], det, out=out[:, 0])
    np.divide(row1[:, 0] * rhs2 - row2[:, 0] * rhs1, det, out=out[:, 1])
    return out


def point_motion(first: Locus, second: Locus, X: Array, order: int) -> tuple[PointMotion, Array]:
    """Velocity and acceleration of X from the differentiated constraints G v_X = b (2x2,
    Cramer), and sin(g1, g2) = |det G| / (|g1| |g2|), the sine of the angle between the
    gradients (0: a dead centre)."""
    g1, g2 = _constraint_row(first, X), _constraint_row(second, X)
    det = cross(g1, g2)
    norms = np.sqrt(dot(g1, g1) * dot(g2, g2))
    sine = np.abs(det) / np.where(norms > 0.0, norms, 1.0)
    if order < 1:
        return PointMotion(X), sine
    det = np.where(det != 0.0, det, np.inf)
    v = solve_2x2(g1, g2, _velocity_rhs(first, g1, X), _velocity_rhs(second, g2, X), det)
    if order < 2:
        return PointMotion(X, v), sine
    rhs1, rhs2 = _acceleration_rhs(first, g1, X, v), _acceleration_rhs(second, g2, X, v)
    return PointMotion(X, v, solve_2x2(g1, g2, rhs1, rhs2, det)), sine


@dataclass(frozen=True)
class LeverSolution:
    """Angle and rates of a slotted lever, and the sine of the angle between slot and r."""

    beta: Array
    omega: Array | None
    alpha: Array | None
    gradient_sine: Array


def lever_margin(pivot: PointMotion, pin: PointMotion, offset: float) -> Piece:
    """The slot meets the pin where |AP| >= |e|: margin m = |r| - |e| (r = P - A; negative: no
    slot through P; one smooth piece) and, with velocities, its rate dm/du = r.(v_P - v_A) / |r|."""
    r = pin.p - pivot.p
    length = np.sqrt(dot(r, r))
    rate = None
    if pin.v is not None and pivot.v is not None:
        rate = dot(r, pin.v - pivot.v) / np.where(length > 0.0, length, 1.0)
    return length - abs(offset), rate


def slotted_lever(
    pivot: PointMotion,
    pin: PointMotion,
    offset: float,
    sign: Array,
    order: int,
    known: tuple[Array, float] | None = None,
) -> LeverSolution:
    """The direction beta of a slot through ``pin``, in a lever turning about ``pivot``.

    The slot line keeps the signed offset e = u x (P - A) from the pivot, u = (cos beta,
    sin beta). With r = P - A: beta = atan2(r) - atan2(e, sign sqrt(|r|^2 - e^2)).
    Differentiating u x r = e once and twice:
    omega = (u x v_rel) / (u.r),  alpha = (u x a_rel - 2 omega u.v_rel - omega^2 e) / (u.r).
    ``known`` = (mask, beta): samples where the direction is known (the drawn pose).
    """
    r = pin.p - pivot.p
    r2 = dot(r, r)
    along = sign * _root(r2 - offset**2, r2)
    beta = np.arctan2(r[:, 1], r[:, 0]) - np.arctan2(offset, along)
    if known is not None:
        beta[known[0]] = known[1]
    u = np.stack((np.cos(beta), np.sin(beta)), axis=-1)
    u_r = dot(u, r)
    safe = np.where(u_r != 0.0, u_r, np.inf)
    omega = alpha = None
    if order >= 1:
        assert pin.v is not None and pivot.v is not None
        v_rel = pin.v - pivot.v
        omega = cross(u, v_rel) / safe
        if order >= 2:
            assert pin.a is not None and pivot.a is not None
            a_rel = pin.a - pivot.a
            alpha = (cross(u, a_rel) - 2.0 * omega * dot(u, v_rel) - omega**2 * offset) / safe
    gradient_sine = np.abs(u_r) / np.sqrt(np.where(r2 > 0.0, r2, 1.0))
    return LeverSolution(beta, omega, alpha, gradient_sine)

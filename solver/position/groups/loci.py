"""The loci of a joint point and what every closed-form group shares (was ``dyads``).

A joint point X whose two constraints involve only known links lies on two *loci*: a circle (X and
a known point C are on one link, so |CX| is fixed) or a line (X slides in a slot of a known
link). RRR is circle-circle, RRP (pin or block in a slot) circle-line, a pin in two slots
line-line. Where a link pivots on a known point and its slot must pass through a known pin
(inverted slider-crank, slotted lever), the unknown is the link's angle: ``slotted_lever``.

Each solution has two branches (the orientation of the dyad's triangle), chosen by ``sign``. The
velocities and accelerations come from differentiating the same two constraints, each locus's
row (``Circle``, ``Line``: a line's is the whole system's slider row, ``constraints``): a 2-by-2
linear system ``G v_X = b`` solved by Cramer's rule, vectorised over samples.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

from solver.kinematics.rigid import (
    Array,
    PointMotion,
    cross,
    dot,
    perp,
    points,
    scale,
    solve_2x2,
)
from solver.position.constraints import slider_acceleration_rhs, slider_velocity_rhs

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
    """X is on a link that carries the known point ``center``: |X - C| = radius.

    Its row (|X - C|^2 - r^2) / 2 = 0 has the gradient g = X - C; differentiated,
    g.v_X = g.v_C and g.a_X = g.a_C - |v_X - v_C|^2."""

    center: PointMotion
    radius: float
    center_name: str
    link: str

    def gradient(self, X: Array) -> Array:
        """g = X - C."""
        return X - self.center.p

    def velocity_rhs(self, g: Array, X: Array) -> Array:
        """g.v_C."""
        assert self.center.v is not None
        return dot(g, self.center.v)

    def acceleration_rhs(self, g: Array, X: Array, v_X: Array) -> Array:
        """g.a_C - |v_X - v_C|^2."""
        assert self.center.v is not None and self.center.a is not None
        v_rel = v_X - self.center.v
        return dot(g, self.center.a) - dot(v_rel, v_rel)


@dataclass(frozen=True)
class Line:
    """X slides on the line through Q with unit direction w, fixed in a known guide link.

    Its row is a slider's, n.(X - Q) = 0 with n = k x w, the follower's point X the unknown:
    the gradient is n and the right-hand sides are the whole system's
    (``constraints.slider_velocity_rhs``, ``constraints.slider_acceleration_rhs``):
    n.v_X = n.v_Q + omega w.(X - Q) and n.a_X = n.a_Q + 2 omega w.(v_X - v_Q) + alpha w.(X - Q).
    """

    through: PointMotion
    direction: Array
    omega: Array | None
    alpha: Array | None
    guide: str

    def gradient(self, X: Array) -> Array:
        """g = n = k x w, the slot's normal."""
        return perp(self.direction)

    def velocity_rhs(self, g: Array, X: Array) -> Array:
        """n.v_Q + omega w.(X - Q)."""
        Q = self.through
        assert Q.v is not None and self.omega is not None
        return slider_velocity_rhs(g, dot(self.direction, X - Q.p), Q.v, self.omega)

    def acceleration_rhs(self, g: Array, X: Array, v_X: Array) -> Array:
        """n.a_Q + 2 omega w.(v_X - v_Q) + alpha w.(X - Q)."""
        Q, w = self.through, self.direction
        assert Q.v is not None and Q.a is not None
        assert self.omega is not None and self.alpha is not None
        wd = dot(w, X - Q.p)
        return slider_acceleration_rhs(g, w, wd, Q.a, self.omega, self.alpha, v_X - Q.v)


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

    def point(self, sign: Array | float) -> Array:
        return self.base + scale(sign * self.h, self.offset)


def root(h2: Array, r2: float | Array) -> Array:
    """sqrt(h^2), a tangency within rounding (h^2 <= TANGENCY_TOLERANCE r^2) snapped to zero."""
    floor = TANGENCY_TOLERANCE * r2
    if isinstance(floor, float) and h2.min() > floor:  # no tangency anywhere (the common case)
        return np.sqrt(h2)
    return np.sqrt(np.where(h2 > floor, h2, 0.0))


def digits(a: float, b: float) -> int:
    """Significant digits (6 to 15) that show two different numbers as different."""
    return next((n for n in range(6, 16) if f"{a:.{n}g}" != f"{b:.{n}g}"), 15)


def _solve(row1: Array, row2: Array, rhs1: Array, rhs2: Array, det: Array) -> Array:
    """[row1; row2] x = [rhs1; rhs2] per sample (``rigid.solve_2x2``), as (N, 2)."""
    out = points((det.size, 2))
    rows = (row1[..., 0], row1[..., 1]), (row2[..., 0], row2[..., 1])
    solve_2x2(*rows, (rhs1, rhs2), det, (out[..., 0], out[..., 1]))
    return out


def point_motion(first: Locus, second: Locus, X: Array, order: int) -> tuple[PointMotion, Array]:
    """Velocity and acceleration of X from the differentiated constraints G v_X = b (2x2,
    Cramer; G's rows the loci's gradients, b their ``velocity_rhs`` and ``acceleration_rhs``),
    and sin(g1, g2) = |det G| / (|g1| |g2|), the sine of the angle between the
    gradients (0: a dead centre)."""
    g1, g2 = first.gradient(X), second.gradient(X)
    det = cross(g1, g2)
    norms = np.sqrt(dot(g1, g1) * dot(g2, g2))
    sine = np.abs(det) / np.where(norms > 0.0, norms, 1.0)
    if order < 1:
        return PointMotion(X), sine
    det = np.where(det != 0.0, det, np.inf)
    v = _solve(g1, g2, first.velocity_rhs(g1, X), second.velocity_rhs(g2, X), det)
    if order < 2:
        return PointMotion(X, v), sine
    rhs1, rhs2 = first.acceleration_rhs(g1, X, v), second.acceleration_rhs(g2, X, v)
    return PointMotion(X, v, _solve(g1, g2, rhs1, rhs2, det)), sine

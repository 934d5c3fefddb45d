"""Planar vectors and the motion of points and rigid links, vectorised over samples.

Every array has a leading sample axis: points are ``(N, 2)``, link angles and rates ``(N,)``. A
quantity that was not asked for is ``None``: the solver computes only the requested orders
(0 position, 1 velocity, 2 acceleration). Points over samples are stored column by column
(``points``: Fortran order, each coordinate contiguous), so that a factor per sample multiplies
both coordinates in one broadcast operation (``scale``, ``omega_cross``) as fast as one column at
any number of samples; every operation is the same, element by element, in either order.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

Array = np.ndarray
FLOAT = np.dtype(float)


def cross(a: Array, b: Array) -> Array:
    """z-component of a x b for planar vectors (the 2-by-2 determinant |a b|)."""
    return a[..., 0] * b[..., 1] - a[..., 1] * b[..., 0]


def dot(a: Array, b: Array) -> Array:
    """a . b = ax bx + ay by for planar vectors (of one shape: the products in one array
    operation, then their sum)."""
    if a.shape == b.shape:
        products = a * b
        return products[..., 0] + products[..., 1]
    return a[..., 0] * b[..., 0] + a[..., 1] * b[..., 1]


def points(shape: tuple[int, ...]) -> Array:
    """An empty (..., 2) float array of ``shape`` (its last axis the 2 coordinates), column by
    column (Fortran order: each coordinate contiguous over the samples)."""
    return np.empty(shape, order="F")


def perp(a: Array) -> Array:
    """k x a: the vector a turned 90 degrees counter-clockwise."""
    out = np.empty_like(a, dtype=np.result_type(a, float))  # (object, 40 digits, stays object)
    out[..., 0] = -a[..., 1]
    out[..., 1] = a[..., 0]
    return out


# One sample's number, or a column of numbers over samples (N,).
Column = Array | float


def determinant_2x2(row1: tuple[Column, Column], row2: tuple[Column, Column]) -> Column:
    """D = |r1 r2| = a11 a22 - a12 a21, the determinant of [row1; row2]."""
    return row1[0] * row2[1] - row1[1] * row2[0]


def cramer_numerators(
    row1: tuple[Column, Column], row2: tuple[Column, Column], rhs: tuple[Column, Column]
) -> tuple[Column, Column]:
    """D1 = |b r2| = b1 a22 - b2 a12 and D2 = |r1 b| = a11 b2 - a21 b1, Cramer's numerators of
    [row1; row2] x = rhs (x = (D1, D2) / D, ``solve_2x2``)."""
    (a11, a12), (a21, a22) = row1, row2
    return rhs[0] * a22 - rhs[1] * a12, a11 * rhs[1] - a21 * rhs[0]


def solve_2x2(
    row1: tuple[Column, Column],
    row2: tuple[Column, Column],
    rhs: tuple[Column, Column],
    det: Column | None = None,
    out: tuple[Array, Array] | None = None,
) -> tuple[Column, Column]:
    """Cramer's rule for [row1; row2] x = rhs: x = (|b r2|, |r1 b|) / D, D = |r1 r2| =
    r1x r2y - r1y r2x (``det`` given where the caller has it, inf where it is 0), column by
    column over samples (written into ``out`` where given). The one 2-by-2 solve of the solver."""
    if det is None:
        det = determinant_2x2(row1, row2)
    first, second = cramer_numerators(row1, row2, rhs)
    if out is None:
        return first / det, second / det
    np.divide(first, det, out=out[0])
    np.divide(second, det, out=out[1])
    return out


def rotate(vector: Array, angle: Array) -> Array:
    """R(angle) vector for each sample: ``vector`` is (2,) or (N, 2), ``angle`` (N,)."""
    return rotate_by(vector, np.cos(angle), np.sin(angle))


def rotate_by(vector: Array, cos: Array, sin: Array) -> Array:
    """R vector = (cos x - sin y, sin x + cos y), the angle's cosine and sine given (broadcast:
    (M, K) angles and (K, 2) vectors give (M, K, 2))."""
    x, y = vector[..., 0], vector[..., 1]
    if cos.dtype == FLOAT and x.dtype == FLOAT and x.shape in ((), cos.shape):
        out = points((*cos.shape, 2))
    else:  # object (40 digits, solver.position.polish) stays object
        kind = np.result_type(cos, x, float)
        out = np.empty((*np.broadcast_shapes(cos.shape, x.shape), 2), dtype=kind, order="F")
    # (each product written into its column, the second subtracted or added in place: the same
    # operations as cos x - sin y, without a temporary copied in)
    np.multiply(cos, x, out=out[..., 0])
    np.subtract(out[..., 0], sin * y, out=out[..., 0])
    np.multiply(sin, x, out=out[..., 1])
    np.add(out[..., 1], cos * y, out=out[..., 1])
    return out


def scale(factor: Column, vector: Array) -> Array:
    """factor[i] * vector[i] for each sample: the factor broadcast over both coordinates (one
    operation, in the vector's order: on ``points`` as fast as a column)."""
    if isinstance(factor, np.ndarray):
        factor = factor[..., None]
    return vector * factor


@dataclass(frozen=True, init=False)
class PointMotion:
    """Position, velocity and acceleration of a point; orders not computed are ``None``.

    (Frozen, its fields written into the instance's dict by its own ``__init__``: a frozen
    dataclass's generated one sets each through ``object.__setattr__``, some 1,800 machine
    instructions a field, and a 360-sample sweep makes these motions by the dozen.)"""

    p: Array
    v: Array | None = None
    a: Array | None = None

    def __init__(self, p: Array, v: Array | None = None, a: Array | None = None) -> None:
        fields = self.__dict__
        fields["p"], fields["v"], fields["a"] = p, v, a

    def at(self, part: slice | Array) -> PointMotion:
        """The same motion at the samples ``part`` only (a slice or sample indices)."""
        v, a = self.v, self.a
        return PointMotion(
            self.p[part], None if v is None else v[part], None if a is None else a[part]
        )


@dataclass(frozen=True, init=False)
class LinkMotion:
    """Motion of a rigid link: an anchor point's motion and the rotation from the drawn pose.

    ``theta`` is the rotation of the link from its drawn pose (not its absolute angle), so a
    point drawn at ``X0`` is at ``anchor.p + R(theta) (X0 - anchor0)``. (Frozen, its fields
    written at once as ``PointMotion``'s.)
    """

    anchor0: Array
    anchor: PointMotion
    theta: Array
    omega: Array | None = None
    alpha: Array | None = None

    def __init__(
        self,
        anchor0: Array,
        anchor: PointMotion,
        theta: Array,
        omega: Array | None = None,
        alpha: Array | None = None,
    ) -> None:
        fields = self.__dict__
        fields["anchor0"], fields["anchor"], fields["theta"] = anchor0, anchor, theta
        fields["omega"], fields["alpha"] = omega, alpha

    def point(self, drawn: Array) -> PointMotion:
        """Motion of the link's point drawn at ``drawn``: rigid-body velocity and acceleration."""
        r = rotate(np.asarray(drawn, dtype=float) - self.anchor0, self.theta)
        p = self.anchor.p + r
        v = a = None
        if self.omega is not None and self.anchor.v is not None:
            v = rigid_body_velocity(self.anchor.v, self.omega, r)
        if self.alpha is not None and self.anchor.a is not None and self.omega is not None:
            a = rigid_body_acceleration(self.anchor.a, self.omega, self.alpha, r)
        return PointMotion(p, v, a)


def omega_cross(omega: Column, r: Array) -> Array:
    """omega x r = omega (k x r): a rate about k (an angular velocity or acceleration) crossed
    with a planar vector, sample by sample. The rotation's term of a rigid body's velocity
    (omega x r_AB) and its tangential acceleration (alpha x r_AB): ``scale(omega, perp(r))``
    written as (r_y omega, r_x omega) with its first column negated, (-r_y) omega as -(r_y omega)
    (the same number in IEEE arithmetic; a vector not in floats as written, negated in its own
    arithmetic as ``perp`` does)."""
    if r.dtype != FLOAT:
        return scale(omega, perp(r))
    out = scale(omega, r[..., ::-1])
    np.negative(out[..., 0], out=out[..., 0])
    return out


def normal_acceleration(omega: Column, r_AB: Array) -> Array:
    """a_n = omega x (omega x r_AB) = -omega^2 r_AB: the normal (centripetal) term of a point B
    of a link turning at omega, towards A."""
    return scale(-(omega**2), r_AB)


def rigid_body_velocity(v_A: Array, omega: Array, r_AB: Array) -> Array:
    """v_B = v_A + omega x r_AB."""
    return v_A + omega_cross(omega, r_AB)


def rigid_body_acceleration(a_A: Array, omega: Array, alpha: Array, r_AB: Array) -> Array:
    """a_B = a_A + alpha x r_AB - omega^2 r_AB (tangential plus normal term)."""
    return a_A + omega_cross(alpha, r_AB) + normal_acceleration(omega, r_AB)


@dataclass(frozen=True, init=False)
class Relative:
    """A point Q seen from a point P over the samples: r = Q - P (N, 2), |r|^2 = r.r and, where
    computed, v_rel = v_Q - v_P (N, 2). (Frozen, its fields written at once as
    ``PointMotion``'s.)"""

    r: Array
    r2: Array
    v: Array | None = None

    def __init__(self, r: Array, r2: Array, v: Array | None = None) -> None:
        fields = self.__dict__
        fields["r"], fields["r2"], fields["v"] = r, r2, v


def relative(P: PointMotion, Q: PointMotion, resting: bool = False) -> Relative:
    """r = Q - P, |r|^2 and v_rel = v_Q - v_P (v_Q itself where P is ``resting``: at rest, its
    rates zeros; None without velocities)."""
    r = Q.p - P.p
    v = None
    if P.v is not None and Q.v is not None:
        v = Q.v if resting else Q.v - P.v
    return Relative(r, dot(r, r), v)


def direction(P0: Array, Q0: Array) -> float:
    """angle(P0Q0) = atan2 of Q0 - P0: the direction of a link's drawn points."""
    r0 = Q0 - P0
    return float(np.arctan2(r0[1], r0[0]))


def link_from_two_points(
    P0: Array,
    P: PointMotion,
    Q: PointMotion,
    drawn: float,
    resting: bool = False,
    seen: Relative | None = None,
) -> LinkMotion:
    """The motion of a link from two of its points P, Q (P drawn at P0, the drawn direction
    ``drawn`` = angle(P0Q0); ``resting``: P at rest, its rates zeros; ``seen``: Q seen from P
    where known, ``relative``).

    theta = angle(PQ) - angle(P0Q0); omega = (r x v_rel) / |r|^2; alpha = (r x a_rel) / |r|^2,
    from v_rel = omega x r and a_rel = alpha x r - omega^2 r with r = Q - P (a_rel - 0 = a_rel:
    a point at rest is not subtracted).
    """
    if seen is None or (seen.v is None and P.v is not None and Q.v is not None):
        seen = relative(P, Q, resting)
    rx, ry = seen.r[..., 0], seen.r[..., 1]
    theta = np.arctan2(ry, rx) - drawn
    omega = alpha = None
    if seen.v is not None:
        omega = (rx * seen.v[..., 1] - ry * seen.v[..., 0]) / seen.r2
    if P.a is not None and Q.a is not None:
        a_rel = Q.a if resting else Q.a - P.a
        alpha = (rx * a_rel[..., 1] - ry * a_rel[..., 0]) / seen.r2
    return LinkMotion(P0, P, theta, omega, alpha)


def repeat(point: Array, samples: int) -> Array:
    """The (2,) ``point`` at each of ``samples`` samples, (N, 2), a new array (``points``: the
    row broadcast down each contiguous column)."""
    out = points((samples, 2))
    out[...] = point
    return out


def fixed_link(anchor0: Array, samples: int) -> LinkMotion:
    """The ground: at rest in its drawn pose."""
    zeros2 = np.zeros((samples, 2), order="F")
    zeros = np.zeros(samples)
    anchor = PointMotion(repeat(anchor0, samples), zeros2, zeros2)
    return LinkMotion(anchor0, anchor, zeros, zeros, zeros)

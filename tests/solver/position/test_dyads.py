"""The closed-form groups (solver.position.groups): the length margin's rate is its derivative
(central differences), and a pin in two nearly parallel slots still meets while parallel slots do
not.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np
import pytest

from solver.position import groups
from solver.position.groups import loci, rpr


def _moving(point: np.ndarray, t: np.ndarray, spin: float) -> Any:
    """A point turning about the origin at ``spin`` rad per unit t, from ``point`` at t = 0."""
    from solver.kinematics.rigid import PointMotion

    c, s = np.cos(spin * t), np.sin(spin * t)
    p = np.stack((c * point[0] - s * point[1], s * point[0] + c * point[1]), axis=-1)
    return PointMotion(p, spin * np.stack((-p[:, 1], p[:, 0]), axis=-1))


@pytest.mark.parametrize("kind", ["circle-circle", "circle-line", "lever"])
def test_margin_pieces_rates_are_their_derivatives(kind: str) -> None:
    """Each smooth piece of a group's margin (r1 + r2 - d and d - |r1 - r2|; r - s and r + s;
    |AP| - |e|), its rate dm/du against central differences (step 1e-6, to 1e-8), with every
    locus moving: centres on circles, the slot turning with its guide; the margin is the
    smallest piece."""

    t0 = np.linspace(0.1, 6.0, 7)
    step = 1e-6

    def margin_and_pieces(t: np.ndarray) -> tuple[np.ndarray, tuple[loci.Piece, ...]]:
        first = _moving(np.array([0.4, 0.1]), t, 1.0)
        second = _moving(np.array([1.0, -0.2]), t, -0.7)
        if kind == "lever":
            piece = rpr.lever_margin(first, second, 0.3)
            return piece[0], (piece,)
        circle = loci.Circle(first, 0.9, "B", "coupler")
        if kind == "circle-circle":
            other: loci.Locus = loci.Circle(second, 0.5, "D", "rocker")
        else:
            direction = np.stack((np.cos(-0.7 * t), np.sin(-0.7 * t)), axis=-1)
            omega = np.full(t.size, -0.7)
            other = loci.Line(second, direction, omega, np.zeros(t.size), "guide")
        cut = groups.intersect(circle, other, "C")
        return cut.margin, cut.pieces

    margin, pieces = margin_and_pieces(t0)
    ahead, behind = margin_and_pieces(t0 + step)[1], margin_and_pieces(t0 - step)[1]
    assert len(pieces) == (1 if kind == "lever" else 2)
    np.testing.assert_array_equal(margin, np.min([values for values, _ in pieces], axis=0))
    for (_, rate), (forward, _), (backward, _) in zip(pieces, ahead, behind, strict=True):
        assert rate is not None
        np.testing.assert_allclose(rate, (forward - backward) / (2.0 * step), atol=1e-8)


def test_pin_in_two_nearly_parallel_slots_still_meets() -> None:
    """Two slots 1e-6 rad apart meet, far away: slot 1 the x axis, slot 2 through (0, 1) at
    angle 1e-6, so X = (-1 / tan(1e-6), 0) (one solution: margin +inf); parallel slots do not."""
    from solver.kinematics.rigid import PointMotion

    def slot(through: list[float], angle: float) -> loci.Line:
        direction = np.array([[math.cos(angle), math.sin(angle)]])
        return loci.Line(PointMotion(np.array([through])), direction, None, None, "guide")

    cut = groups.intersect(slot([0.0, 0.0], 0.0), slot([0.0, 1.0], 1e-6), "X")
    assert cut.margin[0] == math.inf
    np.testing.assert_allclose(cut.point(np.ones(1))[0], [-1.0 / math.tan(1e-6), 0.0], rtol=1e-9)
    parallel = groups.intersect(slot([0.0, 0.0], 0.0), slot([0.0, 1.0], 0.0), "X")
    assert parallel.margin[0] == -math.inf and "parallel" in parallel.message


# --- rates of every group type against finite differences -------------------------------------


def _trajectory(p0: list[float], amp: list[float], w: float, phase: float, t: np.ndarray) -> Any:
    """p(t) = p0 + amp (cos(w t + phase), sin(w t + phase)) with its exact v and a: a point with
    a general motion (translating and circling), so no term of the rates vanishes."""
    from solver.kinematics.rigid import PointMotion

    c, s = np.cos(w * t + phase), np.sin(w * t + phase)
    p = np.stack((p0[0] + amp[0] * c, p0[1] + amp[1] * s), axis=-1)
    v = np.stack((-w * amp[0] * s, w * amp[1] * c), axis=-1)
    a = np.stack((-w * w * amp[0] * c, -w * w * amp[1] * s), axis=-1)
    return PointMotion(p, v, a)


def _slot(t: np.ndarray, through: Any, phi0: float, omega0: float, alpha: float) -> Any:
    """A slot through a moving point, turning by phi = phi0 + omega0 t + alpha t^2 / 2."""

    phi = phi0 + omega0 * t + 0.5 * alpha * t * t
    direction = np.stack((np.cos(phi), np.sin(phi)), axis=-1)
    return loci.Line(through, direction, omega0 + alpha * t, np.full(t.size, alpha), "guide")


def _loci(kind: str, t: np.ndarray) -> tuple[Any, Any]:

    B = _trajectory([0.3, 0.2], [0.25, 0.15], 1.3, 0.4, t)
    D = _trajectory([1.1, -0.1], [0.1, 0.2], -0.9, 1.0, t)
    circle = loci.Circle(B, 0.8, "B", "coupler")
    if kind == "circle-circle":
        return circle, loci.Circle(D, 0.6, "D", "rocker")
    if kind == "circle-line":
        return circle, _slot(t, D, 1.9, 0.7, -0.4)
    return _slot(t, B, 0.3, -0.5, 0.6), _slot(t, D, 1.9, 0.7, -0.4)  # a pin in two slots


def _on_locus(locus: Any, X: np.ndarray) -> np.ndarray:
    """The constraint's residual: |X - C| - r on a circle, n.(X - Q) on a slot (n = k x w)."""
    from solver.kinematics.rigid import cross, dot

    if isinstance(locus, loci.Circle):
        d = X - locus.center.p
        return np.sqrt(dot(d, d)) - locus.radius
    return cross(locus.direction, X - locus.through.p)


@pytest.mark.parametrize("sign", [1.0, -1.0])
@pytest.mark.parametrize("kind", ["circle-circle", "circle-line", "line-line"])
def test_group_point_lies_on_both_loci_and_its_rates_are_derivatives(
    kind: str, sign: float
) -> None:
    """Every group type with both loci moving (centres on ellipses, slots through moving points
    turning with angular acceleration): X lies on both loci (to 1e-12 m), and the velocity and
    acceleration of ``point_motion`` are the central differences (step 1e-5) of X and of that
    velocity, to 1e-7 (the truncation error is ~1e-10 times the third derivative)."""

    t0, step = np.linspace(0.2, 5.8, 9), 1e-5

    def solve(t: np.ndarray) -> Any:
        first, second = _loci(kind, t)
        cut = groups.intersect(first, second, "C")
        assert np.all(cut.margin > 0.0)
        X = cut.point(np.full(t.size, sign))
        return first, second, loci.point_motion(first, second, X, 2)[0]

    first, second, motion = solve(t0)
    for locus in (first, second):
        assert np.abs(_on_locus(locus, motion.p)).max() <= 1e-12
    (_, _, ahead), (_, _, behind) = solve(t0 + step), solve(t0 - step)
    np.testing.assert_allclose(motion.v, (ahead.p - behind.p) / (2.0 * step), atol=1e-7)
    np.testing.assert_allclose(motion.a, (ahead.v - behind.v) / (2.0 * step), atol=1e-7)


def test_coincident_centres_with_equal_radii_give_a_point_of_both_circles() -> None:
    """B = D and |BC| = |DC| (a kite at the pose where B falls on D): every point of the circle
    fits; the one given must lie on it (|X - B| = r) for both branches, and the margin is 0."""
    from solver.kinematics.rigid import PointMotion

    B = PointMotion(np.array([[0.7, -0.3]]))
    cut = groups.intersect(loci.Circle(B, 0.5, "B", "c"), loci.Circle(B, 0.5, "D", "r"), "C")
    assert cut.margin[0] == 0.0
    for sign in (1.0, -1.0):
        X = cut.point(np.array([sign]))[0]
        assert math.hypot(*(X - B.p[0])) == pytest.approx(0.5, abs=1e-15)


def _numbers(text: str) -> list[float]:
    import re

    return [float(x) for x in re.findall(r"-?\d+(?:\.\d+)?(?:e-?\d+)?", text)]


@pytest.mark.parametrize(
    ("distances", "worst", "extended"),
    [
        ([0.9, 1.2345678, 1.0], "1.23457", True),  # the worst sample, at 6 digits
        ([0.79, 0.8000001, 0.5], "0.8000001", True),  # 7 digits to tell it from 0.8
        ([0.5, 0.1999999, 0.3], "0.1999999", False),  # folded: 7 digits to tell it from 0.2
        ([0.05, 0.3], "0.05", False),
    ],
)
def test_message_shows_the_worst_sample_with_enough_digits(
    distances: list[float], worst: str, extended: bool
) -> None:
    """Circles r1 = 0.5 and r2 = 0.3 whose centres are d apart at each sample: the loci fail to
    meet where d > 0.8 (extended) or d < 0.2 (folded). The message gives the d of the worst
    sample (least margin), with 6 significant digits or as many as show it different from the
    bound, and the numbers it prints satisfy the inequality it states."""
    from solver.kinematics.rigid import PointMotion

    d = np.array(distances)
    C1 = PointMotion(np.zeros((d.size, 2)))
    C2 = PointMotion(np.stack((d, np.zeros(d.size)), axis=-1))
    cut = groups.intersect(loci.Circle(C1, 0.5, "B", "c"), loci.Circle(C2, 0.3, "D", "r"), "C")
    message = cut.message
    assert message.startswith(f"|BD| = {worst} m")
    numbers = _numbers(message)
    if extended:
        assert " > |BC| + |DC| = 0.5 + 0.3 = 0.8 m" in message
        assert numbers[0] > numbers[-1]
    else:
        assert " < ||BC| - |DC|| = 0.2 m" in message
        assert numbers[0] < numbers[-1]


@pytest.mark.parametrize("pivot_moves", [False, True])
def test_slotted_lever_rates_are_derivatives_of_its_angle(pivot_moves: bool) -> None:
    """A slot at offset e = 0.15 from its pivot A, through a pin P (both moving): the slot keeps
    its offset (u x (P - A) = e, to 1e-12), omega and alpha are central differences (step 1e-5)
    of beta and omega to 1e-7, and the sine between slot and r = P - A is the closed form
    sqrt(|r|^2 - e^2) / |r| (|r| from 0.45 to 1.4, on both sides of 1)."""
    from solver.kinematics.rigid import PointMotion, cross

    t0, step, e = np.linspace(0.2, 5.8, 9), 1e-5, 0.15

    def solve(t: np.ndarray) -> tuple[Any, Any, Any]:
        pin = _trajectory([0.9, 0.1], [0.5, 0.35], 1.1, 0.3, t)
        pivot = _trajectory([0.0, 0.0], [0.1, 0.05], -0.8, 0.0, t)
        if not pivot_moves:
            zero = np.zeros((t.size, 2))
            pivot = PointMotion(zero.copy(), zero, zero)
        return pin, pivot, rpr.slotted_lever(pivot, pin, e, np.ones(t.size), 2)

    pin, pivot, lever = solve(t0)
    u = np.stack((np.cos(lever.beta), np.sin(lever.beta)), axis=-1)
    r = pin.p - pivot.p
    np.testing.assert_allclose(cross(u, r), e, atol=1e-12)
    length = np.hypot(*r.T)
    assert length.min() < 1.0 < length.max()
    np.testing.assert_allclose(lever.gradient_sine, np.sqrt(length**2 - e * e) / length, rtol=1e-12)
    (_, _, ahead), (_, _, behind) = solve(t0 + step), solve(t0 - step)
    turn = np.remainder(ahead.beta - behind.beta + np.pi, 2.0 * np.pi) - np.pi
    np.testing.assert_allclose(lever.omega, turn / (2.0 * step), atol=1e-7)
    np.testing.assert_allclose(lever.alpha, (ahead.omega - behind.omega) / (2.0 * step), atol=1e-7)


def test_slotted_lever_at_unit_distance_and_on_its_pivot() -> None:
    """A slot through its pivot (e = 0): with the pin 1 m along the slot (u.r = 1 exactly) moving
    across it at 2 m/s, omega = v / |r| = 2 rad/s; with the pin on the pivot the slot's angle is
    undetermined, a dead centre: gradient sine 0 and a finite margin rate, never NaN."""
    from solver.kinematics.rigid import PointMotion

    zero = np.zeros((1, 2))
    pivot = PointMotion(zero, zero, zero)
    pin = PointMotion(np.array([[1.0, 0.0]]), np.array([[0.0, 2.0]]), zero)
    assert rpr.slotted_lever(pivot, pin, 0.0, np.ones(1), 1).omega == pytest.approx([2.0])
    on_pivot = PointMotion(zero, np.array([[0.3, -0.4]]), zero)
    lever = rpr.slotted_lever(pivot, on_pivot, 0.0, np.ones(1), 0)
    assert lever.gradient_sine[0] == 0.0
    margin, rate = rpr.lever_margin(pivot, on_pivot, 0.0)
    assert margin[0] == 0.0 and rate is not None and np.isfinite(rate[0])


def _circle_and_line_at(distance: float, angle: float) -> tuple[Any, Any, np.ndarray, np.ndarray]:
    """A circle of radius 1000 m about C and a slot at ``distance`` from C with direction angle
    ``angle``: the loci, the foot F of the perpendicular from C, and the slot's direction w."""
    from solver.kinematics.rigid import PointMotion

    w = np.array([math.cos(angle), math.sin(angle)])
    C = np.array([0.3, -0.7])
    F = C + distance * np.array([-w[1], w[0]])
    circle = loci.Circle(PointMotion(C[None, :]), 1000.0, "C", "c")
    line = loci.Line(PointMotion((F + 2.7 * w)[None, :]), w[None, :], None, None, "guide")
    return circle, line, F, w


def _two_circles_at(distance: float, angle: float) -> tuple[Any, Any, np.ndarray, np.ndarray]:
    """Circles of radii 1000 m and 600 m whose centres are ``distance`` apart in direction
    ``angle``: the loci, the foot F on the line of centres (a = (r1^2 - r2^2 + d^2) / 2d from
    C1) and the unit normal to it (the common chord's direction)."""
    from solver.kinematics.rigid import PointMotion

    u = np.array([math.cos(angle), math.sin(angle)])
    C1 = np.array([0.3, -0.7])
    C2 = C1 + distance * u
    a = (1000.0**2 - 600.0**2 + distance**2) / (2.0 * distance)
    ends = ((C1, 1e3), (C2, 600.0))
    circles = (loci.Circle(PointMotion(C[None, :]), r, "C", "c") for C, r in ends)
    return *circles, C1 + a * u, np.array([-u[1], u[0]])


@pytest.mark.parametrize("kind", ["circle-line", "circle-circle"])
def test_tangency_is_snapped_only_within_rounding_at_any_scale(kind: str) -> None:
    """Radius 1000 m: at an exact tangency (slot at distance r, or centres r1 + r2 apart) h^2 is
    rounding noise of a few eps r^2 (1e-10 m^2 here): the point is the tangent point, to 1e-8 m,
    not sqrt(noise) ~ 1e-5 m off. A half-chord of about 1e-3 m (h^2 ~ 1e-6 m^2, 1e-12 r^2:
    far above the noise) is kept: X = F +- h n, h from the closed form (Pythagoras, or Heron's
    area for two circles), to 1e-6 m. Twenty directions each."""

    for k in range(1, 21):
        angle = 0.3 * k
        if kind == "circle-line":
            first, second, F, w = _circle_and_line_at(1000.0, angle)
        else:
            first, second, F, w = _two_circles_at(1600.0, angle)
        cut = groups.intersect(first, second, "X")
        for sign in (1.0, -1.0):
            assert math.hypot(*(cut.point(np.array([sign]))[0] - F)) <= 1e-8, (k, sign)
        h = 1e-3
        if kind == "circle-line":
            first, second, F, w = _circle_and_line_at(math.sqrt((1e3 - h) * (1e3 + h)), angle)
        else:
            d = 1600.0 - 1.5e-9  # h^2 ~ 2 (r1 r2 / (r1 + r2)) (r1 + r2 - d) = 1.1e-6 m^2
            s = 0.5 * (1e3 + 600.0 + d)
            h = 2.0 * math.sqrt(s * (s - 1e3) * (s - 600.0) * 0.5 * (1600.0 - d)) / d
            first, second, F, w = _two_circles_at(d, angle)
        cut = groups.intersect(first, second, "X")
        X = cut.point(np.ones(1))[0]
        assert min(math.hypot(*(X - F - h * w)), math.hypot(*(X - F + h * w))) <= 1e-6, k


def test_slot_message_shows_the_worst_sample() -> None:
    """A circle of radius 0.3 about the origin and the slot y = s at s = 0.35, 0.5, 0.4: the
    loci fail to meet at every sample, worst (least margin 0.3 - |s|) at s = 0.5; the message
    gives that distance."""
    from solver.kinematics.rigid import PointMotion

    s = np.array([0.35, 0.5, 0.4])
    centre = PointMotion(np.zeros((3, 2)))
    through = PointMotion(np.stack((np.full(3, 0.2), s), axis=-1))
    direction = np.tile([1.0, 0.0], (3, 1))
    slot = loci.Line(through, direction, None, None, "guide")
    cut = groups.intersect(loci.Circle(centre, 0.3, "A", "crank"), slot, "B")
    assert cut.message == (
        "the distance from A to the slot of B in 'guide' is 0.5 m > |AB| = 0.3 m"
    )


# --- intersections in either order, parallel slots, a determinant of exactly one ----------------


def test_a_line_and_a_circle_meet_in_either_order() -> None:
    """intersect(line, circle) = intersect(circle, line): the x axis and the unit circle about
    (0.5, 0.6) meet at x = 0.5 -+ 0.8 (Pythagoras: 0.6^2 + 0.8^2 = 1)."""
    from solver.kinematics.rigid import PointMotion

    line = loci.Line(PointMotion(np.array([[0.0, 0.0]])), np.array([[1.0, 0.0]]), None, None, "g")
    circle = loci.Circle(PointMotion(np.array([[0.5, 0.6]])), 1.0, "A", "crank")
    for first, second in ((line, circle), (circle, line)):
        cut = groups.intersect(first, second, "B")
        ends = sorted(cut.point(np.array([s]))[0][0] for s in (1.0, -1.0))
        np.testing.assert_allclose(ends, [0.5 - 0.8, 0.5 + 0.8], rtol=0, atol=1e-15)


def test_parallel_slots_are_named_in_the_message() -> None:
    """Two parallel slots: the message names the pin and both guides."""
    from solver.kinematics.rigid import PointMotion

    def slot(y: float, guide: str) -> loci.Line:
        p = PointMotion(np.array([[0.0, y]]))
        return loci.Line(p, np.array([[1.0, 0.0]]), None, None, guide)

    cut = groups.intersect(slot(0.0, "frame"), slot(1.0, "slider"), "P")
    assert cut.message == "the two slots that carry P (in 'frame' and 'slider') are parallel"


def test_rates_where_the_determinant_is_exactly_one() -> None:
    """X = (0, 1) on circles about C1 = (0, 0) and C2 = (1, 0): rows X - C1 = (0, 1) and
    X - C2 = (-1, 1), det = 1 exactly (a determinant of 1 is not a dead centre). By hand from
    (X - C_i).(v_X - v_i) = 0 with v1 = (0.3, 0.7), v2 = (0.4, 0.1): v_y = 0.7 and
    -v_x + v_y = -0.4 + 0.1, so v_X = (1.0, 0.7)."""
    from solver.kinematics.rigid import PointMotion

    def centre(p: list[float], v: list[float]) -> PointMotion:
        return PointMotion(np.array([p]), np.array([v]))

    first = loci.Circle(centre([0.0, 0.0], [0.3, 0.7]), 1.0, "C1", "a")
    second = loci.Circle(centre([1.0, 0.0], [0.4, 0.1]), math.sqrt(2.0), "C2", "b")
    motion, sine = loci.point_motion(first, second, np.array([[0.0, 1.0]]), 1)
    assert motion.v is not None
    np.testing.assert_allclose(motion.v[0], [1.0, 0.7], rtol=0, atol=1e-15)
    assert sine[0] == pytest.approx(1.0 / math.sqrt(2.0), rel=1e-15)

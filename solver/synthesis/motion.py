"""Motion generation: a four-bar whose coupler passes through two or three given poses.

Points are complex numbers z = x + iy. A coupler-fixed point with coordinates q in the coupler's
frame (origin at P, x axis along the pose's angle phi) is at z_j = P_j + e^{i phi_j} q in pose j.
With the moving pivot B given (its place B_1 at the first pose), B_j follows and the fixed pivot A
is the centre point: the centre of the circle through B_1, B_2, B_3 (the point where the
perpendicular bisectors of B_1B_2 and B_2B_3 meet). With the fixed pivot A given (the inverse
problem), A is seen from the coupler at a_j = e^{-i phi_j} (A - P_j) and the circle point B is
the centre of the circle through a_1, a_2, a_3, carried back to the first pose. Two poses leave
one free choice on each bisector: the task's ``bisector_offsets`` state it (``offset_point``),
else ``BISECTOR_DISTANCE`` does. The poles P_jk (the centres
of the rotations taking pose j to pose k) are where the bisectors of every dyad meet: three
coincident poles leave no four-bar.
"""

from __future__ import annotations

import cmath
import math
from dataclasses import dataclass

from solver.errors import InvalidScene
from solver.synthesis.task import MotionTask, Pose

# Two poses: each pivot on its bisector at this many chord lengths from the chord's midpoint,
# so that its link turns by 2 atan(1 / 2) = 53.13 deg between the poses.
BISECTOR_DISTANCE = 1.0
COINCIDENT = 1e-9  # of the task's size: two points closer are one point
COLLINEAR = 1e-9  # sine of the angle at which three points count as collinear


def rotor(angle: float) -> complex:
    """e^{i angle}: the rotation by ``angle`` (rad) as a complex factor."""
    return cmath.exp(1j * angle)


def cross(u: complex, v: complex) -> float:
    """u x v = Im(conj(u) v), the z-component of the planar cross product."""
    return (u.conjugate() * v).imag


def in_pose(pose: Pose, q: complex) -> complex:
    """z_j = P_j + e^{i phi_j} q: the coupler point with coupler coordinates q, in pose j."""
    return pose.point + rotor(pose.angle) * q


def in_coupler(pose: Pose, z: complex) -> complex:
    """q = e^{-i phi_j} (z - P_j): the fixed point z seen from the coupler in pose j."""
    return (z - pose.point) * rotor(-pose.angle)


def pole(first: Pose, second: Pose) -> complex | None:
    """P_jk = (P_k - e^{i d} P_j) / (1 - e^{i d}), d = phi_k - phi_j: the fixed point of the
    rotation taking pose j to pose k; None for a translation (d = 0 mod 2 pi)."""
    turn = rotor(second.angle - first.angle)
    if abs(1.0 - turn) < 1e-12:
        return None
    return (second.point - turn * first.point) / (1.0 - turn)


def circumcentre(a: complex, b: complex, c: complex) -> complex | None:
    """The centre a + o of the circle through a, b, c, with u = b - a, v = c - a:
    o = -i (|u|^2 v - |v|^2 u) / (2 u x v); None where the three are collinear."""
    u, v = b - a, c - a
    area = cross(u, v)
    if abs(area) <= COLLINEAR * abs(u) * abs(v):
        return None
    return a - 1j * (abs(u) ** 2 * v - abs(v) ** 2 * u) / (2.0 * area)


def bisector_point(
    first: complex, second: complex, line: tuple[complex, complex], side: float
) -> complex:
    """The point M +- BISECTOR_DISTANCE i (z_2 - z_1) of the perpendicular bisector of z_1 z_2
    (M the midpoint) that lies on ``side`` (+1 left, -1 right) of the line through ``line``
    (the first candidate when both lie on one side)."""
    middle = 0.5 * (first + second)
    normal = BISECTOR_DISTANCE * 1j * (second - first)
    start, end = line
    for sign in (1.0, -1.0):
        candidate = middle + sign * normal
        if cross(end - start, candidate - start) * side > 0.0:
            return candidate
    return middle + normal


def offset_point(first: complex, second: complex, offset: float) -> complex:
    """M + d i (z_2 - z_1) / |z_2 - z_1|: the point of the perpendicular bisector of z_1 z_2 (M
    the midpoint) at the signed distance d from M, positive to the left of z_1 -> z_2."""
    chord = second - first
    return 0.5 * (first + second) + offset * 1j * chord / abs(chord)


def bisector_offset(first: complex, second: complex, z: complex) -> float:
    """d = (z_2 - z_1) x (z - M) / |z_2 - z_1|: the signed distance along the perpendicular
    bisector of z_1 z_2 from its midpoint M to the foot of z (``offset_point``'s d)."""
    chord = second - first
    return cross(chord, z - 0.5 * (first + second)) / abs(chord)


@dataclass(frozen=True)
class MotionDesign:
    """A four-bar for a motion task: its pivots A, B, C, D and coupler point P at the first pose,
    the places of B, C, P in every pose, the poles P_jk (None for a translation) and the free
    choices taken, in words."""

    A: complex
    B: complex
    C: complex
    D: complex
    P: complex
    targets: tuple[dict[str, complex], ...]
    poles: dict[str, complex | None]
    choices: tuple[str, ...]


def _xy(z: complex) -> str:
    return f"({z.real:.6g}, {z.imag:.6g})"


def _size(task: MotionTask) -> float:
    given = [p.point for p in task.positions] + list(task.moving_pivots or task.fixed_pivots or ())
    return max(max(abs(a - b) for a in given for b in given), 1e-300)


def poles_of(positions: tuple[Pose, ...]) -> dict[str, complex | None]:
    """The poles P12 (and P13, P23 for three poses), by name."""
    names = [(0, 1)] if len(positions) == 2 else [(0, 1), (0, 2), (1, 2)]
    return {f"P{j + 1}{k + 1}": pole(positions[j], positions[k]) for j, k in names}


def _check_poses(task: MotionTask, size: float) -> dict[str, complex | None]:
    """The poles, refusing equal poses and three poses that are rotations about one point."""
    positions = task.positions
    for j in range(len(positions)):
        for k in range(j + 1, len(positions)):
            same_angle = abs(math.remainder(positions[k].angle - positions[j].angle, math.tau))
            if abs(positions[k].point - positions[j].point) <= COINCIDENT * size and (
                same_angle <= 1e-12
            ):
                raise InvalidScene(
                    f"positions[{k}]: the same pose as positions[{j}]; the coupler does not move"
                )
    poles = poles_of(positions)
    found = [p for p in poles.values() if p is not None]
    if len(found) == 3 and max(abs(p - found[0]) for p in found) <= COINCIDENT * size:
        raise InvalidScene(
            f"positions: the poles P12, P13, P23 coincide at {_xy(found[0])}: the three "
            "positions are rotations about one fixed point, so the centre points of both "
            "dyads are that pole (a link turning about it gives the motion; no four-bar does)"
        )
    return poles


def _centre(points: list[complex], name: str, moving: str, size: float) -> complex:
    """The centre point of a moving pivot's places ``points``: the circumcentre (three), the
    chosen point of the bisector (two; see ``bisector_point``, the side given later)."""
    centre = circumcentre(points[0], points[1], points[2])
    if centre is None:
        raise InvalidScene(
            f"{moving}1, {moving}2, {moving}3 lie on one line ({', '.join(map(_xy, points))}): "
            f"the centre point {name} is at infinity (a slider on a fixed guide would guide "
            f"{moving}); choose another moving pivot"
        )
    return centre


def _check_links(design: dict[str, complex], size: float) -> None:
    if abs(design["A"] - design["D"]) <= COINCIDENT * size:
        raise InvalidScene(
            f"the fixed pivots A and D coincide at {_xy(design['A'])}: the ground has zero "
            "length; choose other pivots"
        )
    for first, second, link in (("A", "B", "crank"), ("B", "C", "coupler"), ("D", "C", "rocker")):
        if abs(design[first] - design[second]) <= COINCIDENT * size:
            raise InvalidScene(
                f"the {link} has zero length: {first} = {second} = {_xy(design[first])}; "
                "choose other pivots"
            )


def _direct(task: MotionTask, size: float) -> tuple[dict[str, complex], list[str]]:
    """Moving pivots given: the centre points A (of B) and D (of C)."""
    assert task.moving_pivots is not None
    first = task.positions[0]
    B1, C1 = task.moving_pivots
    places = {
        name: [in_pose(p, in_coupler(first, z)) for p in task.positions]
        for name, z in (("B", B1), ("C", C1))
    }
    choices = []
    if len(task.positions) == 3:
        A = _centre(places["B"], "A", "B", size)
        D = _centre(places["C"], "D", "C", size)
    else:
        for name in ("B", "C"):
            if abs(places[name][1] - places[name][0]) <= COINCIDENT * size:
                raise InvalidScene(
                    f"moving_pivots: {name} is at the pole P12 {_xy(places[name][0])}: it does "
                    "not move between the two positions, so it has no perpendicular bisector; "
                    "choose another moving pivot"
                )
        if task.bisector_offsets is not None:
            dA, dD = task.bisector_offsets
            A = offset_point(places["B"][0], places["B"][1], dA)
            D = offset_point(places["C"][0], places["C"][1], dD)
            choices.append(
                f"two positions: A is taken on the perpendicular bisector of B1B2 at dA = {dA:g} "
                f"m from the chord's midpoint and D on that of C1C2 at dD = {dD:g} m (the "
                "bisector_offsets given; positive to the left of B1 -> B2 and C1 -> C2)"
            )
            return {"A": A, "B": B1, "C": C1, "D": D}, choices
        side = -1.0 if cross(C1 - B1, first.point - B1) > 0.0 else 1.0
        A = bisector_point(places["B"][0], places["B"][1], (B1, C1), side)
        D = bisector_point(places["C"][0], places["C"][1], (B1, C1), side)
        choices.append(
            "two positions: A is taken on the perpendicular bisector of B1B2 and D on that of "
            f"C1C2, each {BISECTOR_DISTANCE:g} chord length from the chord's midpoint (each link "
            f"turns by {math.degrees(2.0 * math.atan(0.5 / BISECTOR_DISTANCE)):.2f} deg between "
            "the positions), on the side of the coupler line B1C1 away from P1"
        )
    return {"A": A, "B": B1, "C": C1, "D": D}, choices


def _inverse(task: MotionTask, size: float) -> tuple[dict[str, complex], list[str]]:
    """Fixed pivots given: the circle points B (of A) and C (of D) at the first pose."""
    assert task.fixed_pivots is not None
    first = task.positions[0]
    A, D = task.fixed_pivots
    seen = {name: [in_coupler(p, z) for p in task.positions] for name, z in (("A", A), ("D", D))}
    choices = []
    if len(task.positions) == 3:
        qB = _centre(seen["A"], "B", "A'", size)
        qC = _centre(seen["D"], "C", "D'", size)
        B, C = in_pose(first, qB), in_pose(first, qC)
    else:
        for name in ("A", "D"):
            if abs(seen[name][1] - seen[name][0]) <= COINCIDENT * size:
                raise InvalidScene(
                    f"fixed_pivots: {name} is the pole P12 {_xy(task.positions[0].point)}: seen "
                    "from the coupler it does not move, so every coupler point is a circle "
                    "point for it; choose another fixed pivot"
                )
        side = 1.0 if cross(D - A, first.point - A) >= 0.0 else -1.0
        line = (in_coupler(first, A), in_coupler(first, D))
        B = in_pose(first, bisector_point(seen["A"][0], seen["A"][1], line, side))
        C = in_pose(first, bisector_point(seen["D"][0], seen["D"][1], line, side))
        choices.append(
            "two positions: the circle point B is taken on the perpendicular bisector of A'1A'2 "
            "(A seen from the coupler in the two positions) and C on that of D'1D'2, each "
            f"{BISECTOR_DISTANCE:g} chord length from the chord's midpoint, on the side of the "
            "ground line AD where P1 is"
        )
    return {"A": A, "B": B, "C": C, "D": D}, choices


def synthesise_motion(task: MotionTask) -> MotionDesign:
    """The four-bar of a motion task (``InvalidScene`` saying why where there is none)."""
    size = _size(task)
    poles = _check_poses(task, size)
    pivots, choices = _direct(task, size) if task.moving_pivots else _inverse(task, size)
    _check_links(pivots, size)
    first = task.positions[0]
    targets = tuple(
        {
            name: in_pose(pose, in_coupler(first, pivots[name])) if name != "P" else pose.point
            for name in ("B", "C", "P")
        }
        for pose in task.positions
    )
    return MotionDesign(
        pivots["A"], pivots["B"], pivots["C"], pivots["D"], first.point, targets, poles,
        tuple(choices),
    )  # fmt: skip

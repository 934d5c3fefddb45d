"""The quick-return crank-rocker: a rocker of length c swinging through phi with time ratio Q.

The textbook's construction: at the rocker's two limit positions C1 and C2 (|DC1| = |DC2| = c,
angle C1 D C2 = phi) the crank and the coupler are in line, stretched out at one (|AC| = b + a)
and folded at the other (|AC| = b - a). Between them the crank turns by 180 + alpha one way (the
slow stroke) and 180 - alpha the other way (the fast stroke), so that

    Q = (180 + alpha) / (180 - alpha),   alpha = 180 (Q - 1) / (Q + 1)  (deg),

and the angle C1 A C2 is alpha: the crank pivot A lies on the arc through C1 and C2 that sees
the chord C1C2 under alpha (for Q = 1, on the line C1C2 outside the chord). Any such A gives
a = (|AC_stretched| - |AC_folded|) / 2 and b = (|AC_stretched| + |AC_folded|) / 2; the free
choice of A along the arc is made here for the transmission angle mu: A is placed where the
crank is longest relative to the ground (a / d) among the pivots whose smallest transmission
angle over a revolution is at least 40 deg (where none reaches 40 deg, where it is largest),
among the Grashof crank-rockers (the crank the shortest link) that pass C1 and C2 on one
assembly; mu is extreme where the crank lies along the ground, cos(mu) = (b^2 + c^2 - (d -+
a)^2) / (2 b c).
"""

from __future__ import annotations

import cmath
import math
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np
from scipy.optimize import brentq, minimize_scalar

from solver.errors import InvalidScene
from solver.kinematics.four_bar import extreme_transmission_angles, grashof_class
from solver.kinematics.rigid import Array
from solver.synthesis.motion import cross, rotor
from solver.synthesis.task import QuickReturnTask

CANDIDATES = 4000  # crank pivots tried along each arc before the refinement
MIN_TRANSMISSION = math.radians(40.0)  # the transmission angle the crank pivot is placed for


def crank_angle_difference(time_ratio: float) -> float:
    """alpha = pi (Q - 1) / (Q + 1) (rad): the crank's turn between its two limit positions
    differs from a half turn by alpha."""
    return math.pi * (time_ratio - 1.0) / (time_ratio + 1.0)


@dataclass(frozen=True)
class QuickReturnDesign:
    """The crank-rocker of a quick-return task, in a frame with A at the origin and D on the
    positive x axis: the pivots, the rocker's two limit positions (``stretched``: crank and
    coupler in line, ``folded``: overlapping), the lengths (a, b, c, d), alpha (rad) and the
    smallest transmission angle (rad) over a revolution."""

    D: complex
    stretched: complex
    folded: complex
    lengths: tuple[float, float, float, float]
    alpha: float
    min_transmission: float


def _quality(A: complex, C1: complex, C2: complex, c: float, alpha: float) -> float:
    """The smallest min(mu, pi - mu) over a revolution of the crank-rocker with crank pivot A
    (rad, D at the origin), or -1 where it is not a Grashof crank-rocker or passes C1 and C2
    on two different assemblies (on two sides of the ground line)."""
    L1, L2 = abs(C1 - A), abs(C2 - A)
    a, b, d = 0.5 * abs(L1 - L2), 0.5 * (L1 + L2), abs(A)
    if a <= 1e-9 * c or grashof_class(d, a, b, c) != "Grashof crank-rocker":
        return -1.0
    if cross(-A, C1 - A) * cross(-A, C2 - A) <= 0.0:  # C1, C2 on two assemblies
        return -1.0
    if abs(abs(cmath.phase((C1 - A) / (C2 - A))) - alpha) > 1e-9:  # the other arc
        return -1.0
    mu = extreme_transmission_angles(a, b, c, d)
    return min(min(m, math.pi - m) for m in mu)


def _crank_over_ground(A: complex, C1: complex, C2: complex) -> float:
    """a / d for the crank pivot A (D at the origin): a = | |AC1| - |AC2| | / 2."""
    return 0.5 * abs(abs(C1 - A) - abs(C2 - A)) / abs(A)


def _pivots(alpha: float, C1: complex, C2: complex, side: float, t: Array) -> Array:
    """Candidate crank pivots at parameter t in [0, 1): around the whole circle through C1 and
    C2 whose centre is on ``side`` of the chord (the points that see the chord under alpha are
    those on the centre's side for alpha < 90 deg; ``_quality`` keeps only them), or, for alpha
    = 0, along the line C1C2 beyond C2 (t < 1/2) or beyond C1 (t > 1/2)."""
    middle, chord = 0.5 * (C1 + C2), C2 - C1
    along = chord / abs(chord)
    if alpha == 0.0:
        out = np.tan(np.pi * np.abs(t - 0.5)) * abs(chord)
        return np.where(t < 0.5, C2 + out * along, C1 - out * along)
    centre = middle + side * 1j * along * 0.5 * abs(chord) / math.tan(alpha)
    circle: Array = centre + 0.5 * abs(chord) / math.sin(alpha) * np.exp(2j * np.pi * t)
    return circle


def _refine(
    quality: Callable[[float], float], target: float, inside: float, outside: float
) -> float:
    """Where the smallest transmission angle crosses ``target`` between the parameter
    ``inside`` (above it) and ``outside`` (below it, still a crank-rocker), by Brent's method."""
    return float(brentq(lambda u: quality(u) - target, inside, outside, xtol=1e-15))


def synthesise_quick_return(task: QuickReturnTask) -> QuickReturnDesign:
    """The crank-rocker of the task (``InvalidScene`` where no crank-rocker has its time ratio
    and swing). The crank pivot is the point of the construction's arcs (either side of the
    chord C1C2) where the crank is longest relative to the ground, a / d, among those whose
    smallest transmission angle is at least ``MIN_TRANSMISSION``; where none reaches it, the
    point with the largest smallest transmission angle."""
    c, phi = task.rocker_length, task.swing
    alpha = crank_angle_difference(task.time_ratio)
    C1, C2 = c * rotor(0.5 * math.pi + 0.5 * phi), c * rotor(0.5 * math.pi - 0.5 * phi)
    grid = (np.arange(CANDIDATES) + 0.5) / CANDIDATES
    rows = []
    for side in (1.0, -1.0) if alpha > 0.0 else (1.0,):
        for t, A in zip(grid, _pivots(alpha, C1, C2, side, grid), strict=True):
            A = complex(A)
            rows.append(
                (side, float(t), _quality(A, C1, C2, c, alpha), _crank_over_ground(A, C1, C2))
            )
    valid = [row for row in rows if row[2] > 0.0]
    if not valid:
        raise InvalidScene(
            f"time_ratio: no crank-rocker has the time ratio {task.time_ratio:g} with a rocker "
            f"swing of {math.degrees(phi):g} deg: the crank pivot must see the chord C1C2 "
            f"under alpha = 180 (Q - 1) / (Q + 1) = {math.degrees(alpha):.4g} deg, and no such "
            "point gives a Grashof crank-rocker passing both limit positions on one assembly"
        )
    best = max(range(len(rows)), key=lambda i: rows[i][2])
    side, t = rows[best][0], rows[best][1]

    def quality(u: float) -> float:
        return _quality(complex(_pivots(alpha, C1, C2, side, np.array([u]))[0]), C1, C2, c, alpha)

    if rows[best][2] < MIN_TRANSMISSION:  # the best transmission angle there is
        step = 1.0 / CANDIDATES
        refined = minimize_scalar(
            lambda u: -quality(u), bounds=(t - step, t + step), method="bounded",
            options={"xatol": 1e-13},
        )  # fmt: skip
        if -float(refined.fun) > rows[best][2]:
            t = float(refined.x)
    else:  # the longest crank (relative to the ground) keeping MIN_TRANSMISSION
        k = max(
            (i for i, row in enumerate(rows) if row[2] >= MIN_TRANSMISSION),
            key=lambda i: rows[i][3],
        )
        side, t = rows[k][0], rows[k][1]
        for j in (k - 1, (k + 1) % len(rows)):  # a neighbour past 40 deg with a longer crank
            past = rows[j][0] == side and 0.0 < rows[j][2] < MIN_TRANSMISSION
            if past and rows[j][3] > rows[k][3] and abs(rows[j][1] - t) < 0.5:
                t = _refine(quality, MIN_TRANSMISSION, t, rows[j][1])
    A = complex(_pivots(alpha, C1, C2, side, np.array([t]))[0])
    L1, L2 = abs(C1 - A), abs(C2 - A)
    stretched, folded = (C1, C2) if L1 > L2 else (C2, C1)
    a, b = 0.5 * abs(L1 - L2), 0.5 * (L1 + L2)
    # The frame of the scene: A at the origin, D on the positive x axis.
    turn = -A.conjugate() / abs(A)
    return QuickReturnDesign(
        -A * turn, (stretched - A) * turn, (folded - A) * turn, (a, b, c, abs(A)), alpha, quality(t)
    )

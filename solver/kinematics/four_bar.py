"""Four-bar loops: Grashof's classification and the transmission angle.

Grashof: with s the shortest and l the longest of the four lengths, s + l <= p + q lets the
shortest link turn fully; the transmission angle is the angle between coupler and rocker.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from solver.kinematics.rigid import Array, cross


@dataclass(frozen=True)
class FourBarLoop:
    """A ground-crank-coupler-rocker loop: its Grashof class and transmission angle (rad), a
    float at one instant or an array over a sweep's samples. ``points`` are B, C, D of the
    angle BCD: the crank pin, the coupler-rocker joint, the rocker's ground pivot."""

    links: tuple[str, str, str, str]
    lengths: tuple[float, float, float, float]
    grashof: str
    transmission_angle: float | Array
    points: tuple[str, str, str]


def grashof_class(ground: float, crank: float, coupler: float, rocker: float) -> str:
    """Grashof's criterion s + l <= p + q, and which link is the shortest."""
    lengths = [ground, crank, coupler, rocker]
    s, l_ = min(lengths), max(lengths)
    spread = s + l_ - (sum(lengths) - s - l_)
    if abs(spread) <= 1e-12 * l_:
        return "change-point"
    if spread > 0:
        return "non-Grashof triple-rocker"
    shortest = int(np.argmin(lengths))
    return (
        "Grashof double-crank",
        "Grashof crank-rocker",
        "Grashof double-rocker",
        "Grashof rocker-crank",
    )[shortest]


def extreme_transmission_angles(a: float, b: float, c: float, d: float) -> tuple[float, float]:
    """The transmission angles of a four-bar (crank a, coupler b, rocker c, ground d) with the
    crank along the ground, pointing away from the rocker and towards it (where a crank that
    turns fully meets its extremes): cos(mu) = (b^2 + c^2 - (d +- a)^2) / (2 b c), clipped to
    [-1, 1]."""
    far = (b * b + c * c - (d + a) ** 2) / (2.0 * b * c)
    near = (b * b + c * c - (d - a) ** 2) / (2.0 * b * c)
    return math.acos(max(-1.0, min(1.0, far))), math.acos(max(-1.0, min(1.0, near)))


def transmission_angle(B: Array, C: Array, D: Array) -> Array:
    """The angle BCD between coupler CB and rocker CD at their joint C (0..pi), at every sample:
    points (2,) give a 0-d array, points (N, 2) an array (N,)."""
    u, w = B - C, D - C
    return np.arctan2(np.abs(cross(u, w)), np.vecdot(u, w))

"""Dead-centre (limit) positions of the slider mechanisms: stroke, time ratio, transmission angle.

Offset slider-crank (crank r, connecting rod l, offset e of the guide from the crank pivot): the
crank turns fully iff r + |e| < l; the slider's limit positions are where crank and rod lie in
one line, x = sqrt((l + r)^2 - e^2) (extended) and x = sqrt((l - r)^2 - e^2) (folded), so the
stroke is their difference; between them the crank turns 180 + a and 180 - a degrees with
a = asin(e / (l - r)) - asin(e / (l + r)), and the time ratio of the strokes at constant crank
speed is (180 + |a|) / (180 - |a|). The transmission angle mu is the angle between the rod and
the normal to the guide, mu = 90 deg - |phi| with sin phi = (e - r sin theta) / l.

Crank and slotted lever (crank r about O, slot through the lever's pivot C, |OC| = d): with
r < d the lever rocks and its limit positions are where the slot is tangent to the crank circle
(crank perpendicular to the slot), at cos(theta - theta_C) = r / d; the crank turns
360 - 2 acos(r / d) degrees over the slow stroke and 2 acos(r / d) over the quick return, i.e.
a = 2 asin(r / d) in (180 + a) / (180 - a); the lever swings through 2 asin(r / d).
"""

from __future__ import annotations

import math
from typing import NamedTuple


class SliderCrankLimits(NamedTuple):
    """The dead centres of an offset slider-crank, in the guide's frame (origin at the crank
    pivot's foot, x along the guide towards the slider): slider positions ``x_far`` (crank and
    rod extended) and ``x_near`` (folded), crank angles ``theta_far``, ``theta_near`` (rad, from
    the guide direction), the crank's turn over each stroke, the time ratio and the transmission
    angle's extremes (rad)."""

    x_far: float
    x_near: float
    stroke: float
    theta_far: float
    theta_near: float
    advance: float  # a (rad): the slow stroke takes pi + |a|, the quick one pi - |a|
    slow_stroke: float
    fast_stroke: float
    time_ratio: float
    mu_min: float
    mu_max: float


def crank_turns_fully(crank: float, rod: float, offset: float) -> bool:
    """r + |e| < l: the crank of a slider-crank passes both dead centres and turns fully."""
    return crank + abs(offset) < rod


def quick_return_ratio(advance: float) -> float:
    """(180 + a) / (180 - a) with a in radians: (pi + |a|) / (pi - |a|), the slow stroke's time
    over the quick one's at constant crank speed."""
    return (math.pi + abs(advance)) / (math.pi - abs(advance))


def slider_crank_dead_centres(crank: float, rod: float, offset: float) -> SliderCrankLimits:
    """x = sqrt((l +- r)^2 - e^2), theta = atan2(e, x) (+ pi folded), a = asin(e / (l - r)) -
    asin(e / (l + r)), mu_min = acos((r + |e|) / l), mu_max = acos(max(0, |e| - r) / l); the
    crank must turn fully (``crank_turns_fully``), else ValueError."""
    r, rod_l, e = crank, rod, offset
    if not crank_turns_fully(r, rod_l, e):
        raise ValueError(
            f"r + |e| = {r + abs(e):g} >= l = {rod_l:g}: the crank does not turn fully"
        )
    x_far = math.sqrt((rod_l + r) ** 2 - e * e)
    x_near = math.sqrt((rod_l - r) ** 2 - e * e)
    advance = math.asin(e / (rod_l - r)) - math.asin(e / (rod_l + r))
    return SliderCrankLimits(
        x_far,
        x_near,
        x_far - x_near,
        math.atan2(e, x_far),
        math.atan2(e, x_near) + math.pi,
        advance,
        math.pi + abs(advance),
        math.pi - abs(advance),
        quick_return_ratio(advance),
        math.acos((r + abs(e)) / rod_l),
        math.acos(max(0.0, abs(e) - r) / rod_l),
    )


class SlottedLeverLimits(NamedTuple):
    """The limit positions of a crank and slotted lever (slot through the lever's pivot): the
    crank angles ``theta_1``, ``theta_2`` (rad, from the direction pivot O to lever pivot C,
    +-acos(r/d)), the lever's swing, the crank's turn over each stroke and the time ratio."""

    theta_1: float
    theta_2: float
    swing: float
    slow_stroke: float
    fast_stroke: float
    time_ratio: float


def slotted_lever_dead_centres(crank: float, centres: float) -> SlottedLeverLimits:
    """cos theta = r / d (crank perpendicular to the slot), swing 2 asin(r / d), strokes
    360 - 2 acos(r / d) and 2 acos(r / d) degrees, a = 2 asin(r / d); r < d, else ValueError
    (the lever turns round: a Whitworth drive, no limit positions)."""
    if not crank < centres:
        raise ValueError(f"r = {crank:g} >= d = {centres:g}: the lever turns round")
    half = math.acos(crank / centres)
    advance = 2.0 * math.asin(crank / centres)
    return SlottedLeverLimits(
        half,
        -half,
        advance,
        2.0 * math.pi - 2.0 * half,
        2.0 * half,
        quick_return_ratio(advance),
    )

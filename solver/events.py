"""The instant at which a moving point reaches a named point: ``find_event``.

When the target is a point of M's own carrier, coincidence means M's path coordinate s(t) equals
the target's (plus whole turns of an arc). s(t) is split at the zeros of s'(t) into monotonic
pieces, so every level between a piece's end values is crossed exactly once there and is found by
Brent's method: no crossing is missed between samples, however fast M moves. For any other
target the distance |M(t) - P(t)| is sampled with the linkage, its local minima refined, and a
minimum below ``COINCIDENCE_TOLERANCE`` of the scene size counts as a meeting.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from itertools import pairwise

import numpy as np
from scipy.optimize import brentq, minimize_scalar

from solver.analysis import driver_inputs_over_time
from solver.assembly import assemble, require_feasible
from solver.errors import InvalidScene, LimitExceeded, NoEvent
from solver.laws import parse_time_law
from solver.relative_motion import path_geometry
from solver.rigid import Array
from solver.scene import MAX_TIME, LinkageScene, MovingPoint
from solver.topology import build_plan

GRID = 4096  # samples of s(t) or of the distance over [0, t_max]
MAX_OCCURRENCE = 10_000
ON_PATH_TOLERANCE = 1e-9  # relative to the path's size: the target lies on M's path
COINCIDENCE_TOLERANCE = 1e-7  # relative to the scene size: M meets a target off its carrier


@dataclass(frozen=True)
class Event:
    time: float
    position: Array


def _path_levels(scene: LinkageScene, mp: MovingPoint, target: str) -> tuple[float, float]:
    """(s of the target on M's path, the period of the path: 2 pi R for an arc, 0 for a line)."""
    route = mp.path
    start, point = scene.drawn(route.start), scene.drawn(target)
    if route.type == "line":
        assert route.through is not None
        u = scene.drawn(route.through) - start
        u = u / math.hypot(*u)
        off = abs(u[0] * (point - start)[1] - u[1] * (point - start)[0])
        if off > ON_PATH_TOLERANCE * max(math.hypot(*(point - start)), scene.size):
            raise NoEvent(
                f"{target} is {off:.6g} m off the line along which {mp.name} moves, "
                f"so {mp.name} never reaches it"
            )
        return float(u @ (point - start)), 0.0
    assert route.center is not None
    center = scene.drawn(route.center)
    radius = math.hypot(*(start - center))
    distance = math.hypot(*(point - center))
    if abs(distance - radius) > ON_PATH_TOLERANCE * radius:
        raise NoEvent(
            f"{target} is not on the arc of {mp.name}: |{route.center}{target}| = "
            f"{distance:.6g} m, radius {radius:.6g} m"
        )
    turn = 1.0 if route.direction == "ccw" else -1.0
    angle = turn * (math.atan2(*(point - center)[::-1]) - math.atan2(*(start - center)[::-1]))
    return radius * (angle % (2.0 * math.pi)), 2.0 * math.pi * radius


def _crossings_of_levels(mp: MovingPoint, level: float, period: float, t_max: float) -> list[float]:
    """All t in [0, t_max] with s(t) = level + k period (any integer k; k = 0 for a line)."""
    law = parse_time_law(mp.s_law)

    def s(t: float) -> float:
        return float(law.evaluate(t)[0])

    def s_dot(t: float) -> float:
        return float(law.evaluate(t)[1])

    grid = np.linspace(0.0, t_max, GRID + 1)
    rates = law.evaluate(grid)[1]
    breaks = [0.0]
    for i in np.flatnonzero(np.sign(rates[:-1]) * np.sign(rates[1:]) < 0):
        breaks.append(brentq(s_dot, grid[i], grid[i + 1], xtol=1e-15 * max(t_max, 1.0)))
    breaks.append(t_max)
    times = []
    for a, b in pairwise(breaks):
        sa, sb = s(a), s(b)
        low, high = min(sa, sb), max(sa, sb)
        if period > 0.0:
            turns = range(
                math.ceil((low - level) / period), math.floor((high - level) / period) + 1
            )
        else:
            turns = range(int(low <= level <= high))
        for k in turns:
            target = level + k * period
            if sa == target:
                times.append(a)
            elif sb == target:
                times.append(b)
            else:
                times.append(
                    brentq(
                        lambda t, c=target: s(t) - c, a, b, xtol=1e-15 * max(t_max, 1.0), rtol=1e-15
                    )
                )
    return times


def _meetings_off_carrier(
    scene: LinkageScene, mp: MovingPoint, target: str, t_max: float
) -> list[float]:
    """Local minima of |M(t) - P(t)| that reach zero (to the coincidence tolerance)."""
    plan = build_plan(scene)
    law = parse_time_law(mp.s_law)

    def gap(times: Array) -> Array:
        motion = assemble(
            scene, plan, driver_inputs_over_time(scene, times), 0, continuation=times.size > 2
        )
        require_feasible(motion, "while searching for the event")
        drawn = path_geometry(scene, mp, law.evaluate(times)[0]).point
        m = motion.links[mp.link].point(drawn).p
        return np.hypot(*(m - motion.points[target].p).T)

    grid = np.linspace(0.0, t_max, GRID + 1)
    d = gap(grid)
    times = []
    tolerance = COINCIDENCE_TOLERANCE * scene.size
    for k in np.flatnonzero((d[1:-1] <= d[:-2]) & (d[1:-1] <= d[2:])) + 1:
        found = minimize_scalar(
            lambda t: float(gap(np.array([t]))[0]),
            bounds=(grid[k - 1], grid[k + 1]),
            method="bounded",
            options={"xatol": 1e-13 * max(t_max, 1.0)},
        )
        if found.fun <= tolerance:
            times.append(float(found.x))
    if d[-1] <= tolerance:
        times.append(t_max)
    return times


def find_event(
    scene: LinkageScene, moving_point: str, reaches: str, occurrence: int, t_max: float
) -> Event:
    """The ``occurrence``-th instant after t = 0 at which ``moving_point`` coincides with
    ``reaches`` (t = 0 itself does not count)."""
    mp = next((m for m in scene.moving_points if m.name == moving_point), None)
    if mp is None:
        raise InvalidScene(f"event.moving_point: unknown moving point '{moving_point}'")
    if reaches not in scene.points:
        raise InvalidScene(f"event.reaches: unknown point '{reaches}'")
    if not 1 <= occurrence <= MAX_OCCURRENCE:
        raise LimitExceeded(f"event.occurrence: {occurrence} is outside 1..{MAX_OCCURRENCE}")
    if not 0.0 < t_max <= MAX_TIME:
        raise LimitExceeded(f"event.t_max: {t_max} s is outside (0, {MAX_TIME:g}] s")
    if reaches in scene.links[mp.link].points:
        level, period = _path_levels(scene, mp, reaches)
        times = _crossings_of_levels(mp, level, period, t_max)
    else:
        times = _meetings_off_carrier(scene, mp, reaches, t_max)
    after_start = sorted({t for t in times if t > 1e-12 * t_max})
    distinct = [
        t for i, t in enumerate(after_start) if i == 0 or t - after_start[i - 1] > 1e-10 * t_max
    ]
    if len(distinct) < occurrence:
        raise NoEvent(
            f"{moving_point} reaches {reaches} {len(distinct)} time(s) in "
            f"0 < t <= {t_max:g} s, not {occurrence}"
        )
    time = distinct[occurrence - 1]
    plan = build_plan(scene)
    motion = assemble(scene, plan, driver_inputs_over_time(scene, np.array([time])), 0)
    require_feasible(motion, f"at t = {time:.6g} s")
    drawn = path_geometry(scene, mp, parse_time_law(mp.s_law).evaluate(np.array([time]))[0])
    return Event(time, motion.links[mp.link].point(drawn.point).p[0])

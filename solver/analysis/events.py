"""The instant at which a moving point reaches a named point: ``find_event``.

When the target is a point of M's own carrier, coincidence means M's path coordinate s(t) equals
the target's (plus whole turns of an arc). Time is marched in windows from t = 0, stopping at the
requested occurrence; in each window s(t) is split at the zeros of s'(t) into monotonic pieces,
so every level between a piece's end values is crossed exactly once there and is found by
Brent's method (turning points and crossings one at a time, only as far as the occurrence). A
window is narrowed until, on every interval between two of its samples, the range of s' or that
of s'' keeps one sign (ranges of the exact derivatives by interval arithmetic,
``TimeLaw.rate_ranges``): s is then monotonic there, or s' is and s turns at most once, at a
sign change of s' between the samples. So no turning point hides between samples, however the
samples alias a fast oscillation; only a window 1e-12 t_max wide (the resolution of the times)
is searched as it is. For any other target the distance |M(t) - P(t)| is sampled with the
linkage (assembled with continuation from t = 0), and at each local minimum (the first and last
samples' on their one side), in time order up to the occurrence, the root of
d(d^2)/dt = 2 (M - P).(v_M - v_P) is taken, the instants between samples assembled on the
branches the samples followed; a minimum below ``COINCIDENCE_TOLERANCE`` of the scene size
counts as a meeting. Either way, times less than 1e-10 t_max apart are one meeting (the
resolution of the answer). The event's position is that of the linkage followed from t = 0.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Iterable, Iterator
from dataclasses import dataclass
from itertools import chain, pairwise

import numpy as np
from scipy.optimize import brentq

from solver.errors import InvalidScene, LimitExceeded, NoEvent
from solver.kinematics.relative_motion import moving_point_motion, path_geometry
from solver.kinematics.rigid import Array, cross, dot
from solver.model.laws import parse_time_law
from solver.model.scene import MAX_TIME, LinkageScene, MovingPoint
from solver.position.assembly import assemble, branches_at, require_feasible
from solver.position.drivers import driver_inputs_over_time
from solver.position.topology import build_plan

WINDOW = 64  # samples per window of the path-coordinate search
MAX_SEARCH_SAMPLES = 1_000_000  # evaluations of the law (samples and Brent's) before giving up
DISTANCE_GRID = 4096  # samples of |M - P| over [0, t_max]
MAX_OCCURRENCE = 10_000
ON_PATH_TOLERANCE = 1e-9  # relative to the path's size: the target lies on M's path
TOUCH_TOLERANCE = 1e-12  # relative: a turning point this close to the target's s touches it
COINCIDENCE_TOLERANCE = 1e-7  # relative to the scene size: M meets a target off its carrier


@dataclass(frozen=True)
class Event:
    time: float
    position: Array


def _path_levels(scene: LinkageScene, mp: MovingPoint, target: str) -> tuple[float, float]:
    """(s of the target on M's path, the period of the path: 2 pi R for a whole circle, 0 for a
    line or a groove with an end, ``sweep_deg`` < 360, beyond whose end no target lies)."""
    route = mp.path
    start, point = scene.drawn(route.start), scene.drawn(target)
    if route.type == "line":
        assert route.through is not None
        u = scene.drawn(route.through) - start
        u = u / math.hypot(*u)
        off = abs(cross(u, point - start))
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
    angle %= 2.0 * math.pi
    if route.sweep_deg >= 360.0:
        return radius * angle, 2.0 * math.pi * radius
    sweep = math.radians(route.sweep_deg)
    if angle > sweep * (1.0 + ON_PATH_TOLERANCE):
        raise NoEvent(
            f"{target} is past the end of the groove of {mp.name} ({route.sweep_deg:g} deg from "
            f"{route.start}), so {mp.name} never reaches it there"
        )
    return radius * angle, 0.0  # a groove with an end: no whole turns


def _zeros(f: Callable[[float], float], grid: Array, values: Array) -> Iterator[float]:
    """Zeros of f on the grid in increasing order, each found when asked for: exact zeros at
    samples, and Brent's root in each sign change."""
    exact = values == 0.0
    changes = np.append(values[:-1] * values[1:] < 0.0, False)
    for i in np.flatnonzero(exact | changes).tolist():
        if exact[i]:
            yield float(grid[i])
        else:
            yield brentq(f, grid[i], grid[i + 1], xtol=1e-15 * max(abs(grid[i]), 1.0))


def _levels_crossed(
    s: Callable[[float], float], a: float, b: float, level: float, period: float
) -> Iterator[float]:
    """On a piece [a, b] where s is monotonic: the times at which s = level + k period, in
    increasing order (a falling s meets the higher copies first), each found when asked for."""
    sa, sb = s(a), s(b)
    low, high = min(sa, sb), max(sa, sb)
    touch = TOUCH_TOLERANCE * max(abs(level), abs(low), abs(high), period, 1e-300)
    if period > 0.0:
        turns = range(
            math.ceil((low - touch - level) / period),
            math.floor((high + touch - level) / period) + 1,
        )
    else:
        turns = range(int(low - touch <= level <= high + touch))
    for k in reversed(turns) if sb < sa else turns:
        target = level + k * period
        if abs(sa - target) <= touch:
            yield a
        elif abs(sb - target) <= touch:
            yield b
        else:
            yield brentq(
                lambda t, c=target: s(t) - c, a, b, xtol=1e-15 * max(abs(b), 1.0), rtol=1e-15
            )


def _add_meetings(meetings: list[float], times: Iterable[float], t_max: float, wanted: int) -> None:
    """Append to ``meetings`` the new meetings among ``times`` (increasing, none before the last
    meeting) until there are ``wanted``, reading ``times`` no further: a time counts after
    t = 0 (more than 1e-12 t_max) and more than 1e-10 t_max after the last meeting, the
    resolution of the answer (a crossing found again at the start of the next piece, or two
    crossings that close, are one meeting)."""
    for t in times:
        if t > 1e-12 * t_max and (not meetings or t - meetings[-1] > 1e-10 * t_max):
            meetings.append(t)
            if len(meetings) == wanted:
                return


def _crossings_of_levels(
    mp: MovingPoint, level: float, period: float, t_max: float, wanted: int
) -> list[float]:
    """The first ``wanted`` meetings (``_add_meetings``) in (0, t_max] with
    s(t) = level + k period (k = 0 for a line)."""
    law = parse_time_law(mp.s_law)
    evaluated = 0  # of the law: the windows' samples and Brent's method's

    def s(t: float) -> float:
        nonlocal evaluated
        evaluated += 1
        return law.at(t, 0)

    def s_dot(t: float) -> float:
        nonlocal evaluated
        evaluated += 1
        return law.at(t, 1)

    widest = t_max / WINDOW
    width, t = widest, 0.0
    meetings: list[float] = []
    while t < t_max and len(meetings) < wanted:
        grid = np.linspace(t, min(t + width, t_max), WINDOW + 1)
        rates = law.evaluate(grid)[1]
        evaluated += grid.size
        if evaluated > MAX_SEARCH_SAMPLES:
            raise LimitExceeded(
                f"{mp.name} moves too fast to search up to t_max = {t_max:g} s "
                f"(more than {MAX_SEARCH_SAMPLES} samples): lower t_max"
            )
        # Between two samples s is monotonic where s' keeps one sign; where s'' does, s' is
        # monotonic and s turns at most once, where s' changes sign between the samples.
        (v_low, v_high), (a_low, a_high) = law.rate_ranges(grid[:-1], grid[1:])
        resolved = (v_low >= 0.0) | (v_high <= 0.0) | (a_low >= 0.0) | (a_high <= 0.0)
        if not resolved.all() and width > 1e-12 * t_max:
            width /= 4.0
            continue
        breaks = chain([float(grid[0])], _zeros(s_dot, grid, rates), [float(grid[-1])])
        crossings = (
            c for a, b in pairwise(breaks) if b > a for c in _levels_crossed(s, a, b, level, period)
        )
        _add_meetings(meetings, crossings, t_max, wanted)
        t = grid[-1]
        width = min(2.0 * width, widest)
    return meetings


def _meetings_off_carrier(
    scene: LinkageScene, mp: MovingPoint, target: str, t_max: float
) -> Iterator[float]:
    """Local minima of |M(t) - P(t)| that reach zero (to the coincidence tolerance), in time
    order, each refined when asked for: sampled on the distance grid, assembled with
    continuation from t = 0, each minimum (a first or last sample's included, on its one side)
    refined by Brent's method on the rate of approach, the instants between samples assembled
    on the branches followed there (``branches_at``)."""
    plan = build_plan(scene)
    grid = np.linspace(0.0, t_max, DISTANCE_GRID + 1)
    swept = assemble(scene, plan, driver_inputs_over_time(scene, grid), 0, continuation=True)
    require_feasible(swept, "while searching for the event")
    law = parse_time_law(mp.s_law)
    on_grid = path_geometry(scene, mp, law.evaluate(grid)[0]).point
    d = np.hypot(*(swept.links[mp.link].point(on_grid).p - swept.points[target].p).T)

    def at(t: float) -> tuple[Array, Array, Array, Array]:
        """M, v_M, P, v_P at t, on the branches the grid's continuation followed (assembled to
        order 2: ``moving_point_motion`` takes the carrier's accelerations)."""
        times = np.array([t])
        signs = branches_at(swept.flips, t / t_max * DISTANCE_GRID)
        motion = assemble(scene, plan, driver_inputs_over_time(scene, times), 2, signs=signs)
        require_feasible(motion, "while searching for the event")
        M = moving_point_motion(scene, mp, motion.links[mp.link], times)
        P = motion.points[target]
        assert P.v is not None
        return M.position, M.velocity, P.p, P.v

    def approach(t: float) -> float:
        """d(|M - P|^2)/dt / 2 = (M - P).(v_M - v_P): negative while M closes in."""
        m, v_m, p, v_p = at(t)
        return float(dot(m - p, v_m - v_p)[0])

    tolerance = COINCIDENCE_TOLERANCE * scene.size
    before = np.concatenate([[np.inf], d[:-1]])
    after = np.concatenate([d[1:], [np.inf]])
    for k in np.flatnonzero((d <= before) & (d <= after)).tolist():
        a, b = float(grid[max(k - 1, 0)]), float(grid[min(k + 1, DISTANCE_GRID)])
        fa, fb = approach(a), approach(b)
        t = float(grid[k]) if fa * fb > 0.0 else brentq(approach, a, b, xtol=1e-15 * t_max)
        m_t, _, p_t, _ = at(t)
        if float(np.hypot(*(m_t - p_t)[0])) <= tolerance:
            yield t


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
        meetings = _crossings_of_levels(mp, level, period, t_max, occurrence)
    else:
        meetings = []
        _add_meetings(meetings, _meetings_off_carrier(scene, mp, reaches, t_max), t_max, occurrence)
    if len(meetings) < occurrence:
        raise NoEvent(
            f"{moving_point} reaches {reaches} {len(meetings)} time(s) in "
            f"0 < t <= {t_max:g} s, not {occurrence}"
        )
    time = meetings[occurrence - 1]
    # The linkage at that time on the branches followed from t = 0 (as finely as the grid).
    followed = np.linspace(0.0, time, 2 + math.ceil(DISTANCE_GRID * time / t_max))
    motion = assemble(
        scene, build_plan(scene), driver_inputs_over_time(scene, followed), 0, continuation=True
    )
    require_feasible(motion, f"at t = {time:.6g} s")
    drawn = path_geometry(scene, mp, parse_time_law(mp.s_law).evaluate(followed[-1:])[0])
    return Event(time, motion.links[mp.link].point(drawn.point).p[-1])

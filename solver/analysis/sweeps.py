"""A sweep of the first driver through one revolution, or through its feasible range.

The whole sweep is one vectorised run of the plan with branch continuation (one sample more than
asked, back at the start, so that the closing interval is searched for close approaches too).
Where the linkage cannot turn fully (a sample that does not close, or a window between two
samples found by the closest-approach search), the feasible interval around the starting angle
is found on a probe grid, its ends (the limit positions) are refined by bisection, and the
samples are spread strictly inside it (at a limit position itself the velocity equations are
singular). Close approaches of a group's two branches (within 1e-3 of the size) are reported.
Samples that land exactly on a change point (a parallelogram's crossing: the velocity equations
singular, the motion smooth) take their rates from their two neighbours and are listed in
``singular_samples``.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Iterable
from dataclasses import dataclass, field
from functools import cached_property, partial

import numpy as np
from numpy.polynomial import chebyshev

from solver.analysis.link_kinematics import four_bar_loops, link_poles
from solver.analysis.sliding_joints import (
    SliderTravel,
    SlidingJoint,
    slider_travel,
    sliding_joints,
)
from solver.errors import InvalidScene, LimitExceeded
from solver.kinematics.four_bar import FourBarLoop
from solver.kinematics.poles import Poles
from solver.kinematics.relative_motion import MovingPointMotion, moving_point_motion
from solver.kinematics.rigid import Array
from solver.model.quantities import normalise_quantities, required_order
from solver.model.scene import LinkageScene
from solver.position.assembly import (
    WARNING_MARGIN,
    DriverInput,
    Motion,
    assemble,
    branches_at,
    require_feasible,
)
from solver.position.continuation import Continuation
from solver.position.drivers import drawn_angle, driver_input, driver_inputs_over_time
from solver.position.newton import newton_tolerance
from solver.position.topology import Plan, build_plan

MAX_SAMPLES = 100_000
PROBE_SAMPLES = 720  # feasibility probe: 0.5 degree
# From 90 samples (4 degrees) on, the sweep is its own feasibility probe: a window where the
# linkage cannot close between two samples is found by the closest-approach search of assembly.
SELF_PROBING_SAMPLES = 90
BISECTION_STEPS = 48  # limit positions to 2 pi / 720 / 2^48 rad
# The halvings of the bisection decided by one assembly: the midpoints of all the ways the next
# BISECTION_LEVELS can go (2^levels - 1 turns) probed at once (``_limit``).
BISECTION_LEVELS = 6
MIN_GRADIENT_SINE = 1e-12  # sine of the angle between a group's constraint gradients
# A ram's extreme positions: STROKE_NODES Chebyshev-Lobatto nodes in each bracket, both extremes
# in one run, until the root's estimated error is below STROKE_TOLERANCE rad (at most
# STROKE_RUNS runs; one from about 40 samples a revolution on).
STROKE_NODES = 8
STROKE_TOLERANCE = 1e-13
STROKE_RUNS = 6
NEWTON_STEPS = 20  # on the interpolant: quadratic from the secant, a few in practice


def check_samples(samples: int) -> None:
    """2 <= samples <= MAX_SAMPLES (a sweep's documented bounds), else ``LimitExceeded`` stating
    them."""
    if not 2 <= samples <= MAX_SAMPLES:
        raise LimitExceeded(f"samples: {samples} is outside 2..{MAX_SAMPLES}")


class _Warned:
    """A sweep's warnings in words (one per close approach of two branches), and its four-bar
    loops and sliders, computed on first access: a caller pays only for what it reads."""

    scene: LinkageScene
    motion: Motion
    quantities: frozenset[str]
    close_approaches: tuple[CloseApproach, ...]
    order: int  # the order the motion was computed to (``required_order``)

    @property
    def warnings(self) -> list[str]:
        return [a.warning for a in self.close_approaches]

    @cached_property
    def four_bar_loops(self) -> list[FourBarLoop]:
        """The four-bar loops' transmission angles at every sample (``four_bar_loops``), where
        positions were asked for; computed on first access."""
        if "position" not in self.quantities:
            return []
        return four_bar_loops(self.scene, build_plan(self.scene), self.motion, every_sample=True)

    @cached_property
    def sliders(self) -> list[SliderTravel]:
        """The sliders' travel along their guides (``slider_travel``: positions, velocities or
        accelerations, as asked); computed on first access."""
        if not self.quantities & {"position", "velocity", "acceleration"}:
            return []
        return slider_travel(self.scene, self.motion, self.order)


@dataclass(frozen=True, init=False)
class Sweep(_Warned):
    """The linkage over the driver's cycle; ``driver_angle`` is the driver link's absolute angle.
    (Frozen, its fields written at once as ``rigid.PointMotion``'s.)"""

    scene: LinkageScene
    driver: str
    driver_angle: Array
    motion: Motion
    feasible: bool
    limits: tuple[float, ...]
    singular_samples: Array
    quantities: frozenset[str]
    joints: list[SlidingJoint]
    poles: dict[str, tuple[Poles, Poles]]
    close_approaches: tuple[CloseApproach, ...] = ()
    order: int = 0
    # A ram's strokes refined from the sweep's own run (``_strokes`` on it; None: not a full
    # revolution).
    stroke_of: Callable[[SliderTravel], Strokes | None] | None = field(
        default=None, repr=False, compare=False
    )
    # A link's extreme angles refined from the sweep's own run (``_angle_extremes`` on it; None:
    # not a full revolution).
    extremes_of: Callable[[str], AngleExtremes | None] | None = field(
        default=None, repr=False, compare=False
    )

    def __init__(
        self,
        scene: LinkageScene,
        driver: str,
        driver_angle: Array,
        motion: Motion,
        feasible: bool,
        limits: tuple[float, ...],
        singular_samples: Array,
        quantities: frozenset[str],
        joints: list[SlidingJoint],
        poles: dict[str, tuple[Poles, Poles]],
        close_approaches: tuple[CloseApproach, ...] = (),
        order: int = 0,
        stroke_of: Callable[[SliderTravel], Strokes | None] | None = None,
        extremes_of: Callable[[str], AngleExtremes | None] | None = None,
    ) -> None:
        fields = self.__dict__
        fields["scene"], fields["driver"], fields["driver_angle"] = scene, driver, driver_angle
        fields["motion"], fields["feasible"], fields["limits"] = motion, feasible, limits
        fields["singular_samples"], fields["quantities"] = singular_samples, quantities
        fields["joints"], fields["poles"] = joints, poles
        fields["close_approaches"], fields["order"] = close_approaches, order
        fields["stroke_of"], fields["extremes_of"] = stroke_of, extremes_of

    def angle_extremes(self, link: str) -> AngleExtremes | None:
        """``link``'s least and greatest angle over a full revolution of the driver and the
        driver's angles there (``AngleExtremes``, refined to rounding by further runs); None
        where the driver does not turn fully or the link turns fully (never turns back)."""
        if self.extremes_of is None or link not in self.motion.links:
            return None
        return self.extremes_of(link)

    @cached_property
    def strokes(self) -> dict[str, Strokes | None]:
        """Each ram's (slider on a fixed guide) extreme positions over a full revolution
        (``Strokes``, refined to rounding by further runs), where positions were asked for;
        computed on first access."""
        strokes: dict[str, Strokes | None] = {}
        if self.stroke_of is None or "position" not in self.quantities:
            return strokes
        for travel in self.sliders:
            if travel.links[0] == self.scene.ground:
                strokes[travel.point] = self.stroke_of(travel)
        return strokes


@dataclass(frozen=True)
class Strokes:
    """A slider on a fixed guide (a ram) over a full revolution of the driver: its two extreme
    positions (where ds/dt = 0), at the driver's absolute angles ``driver_angles`` (rad, in the
    order the driver reaches them) with ``displacements`` s there (m); the driver's turn over
    the slower stroke and over the faster one (rad, summing to 2 pi), and their ratio, the
    quick-return time ratio at constant driver speed. None where the ram does not reverse
    exactly twice a revolution."""

    driver_angles: tuple[float, float]
    displacements: tuple[float, float]
    slow_stroke: float
    fast_stroke: float

    @property
    def time_ratio(self) -> float:
        return self.slow_stroke / self.fast_stroke


@dataclass(frozen=True)
class CloseApproach:
    """Where a group's two branches come within ``margin`` (m, its length margin) of meeting,
    without meeting: at the first driver's absolute angle ``driver_angle`` (rad)."""

    point: str
    driver: str
    margin: float
    driver_angle: float

    @property
    def warning(self) -> str:
        degrees = math.degrees(math.remainder(self.driver_angle, 2.0 * math.pi))
        # In (-180, 180] as printed: an angle within rounding of 180 deg reads 180.0 either side.
        shown = f"{degrees:.1f}".replace("-180.0", "180.0")
        return (
            f"the linkage passes within {self.margin:.2g} m of a change point at {shown} "
            f"deg ('{self.driver}' angle; the two assemblies of {self.point} nearly meet there); "
            "a real mechanism with clearance could switch assembly here"
        )


def close_approaches(motion: Motion, driver: str, angles: Array) -> tuple[CloseApproach, ...]:
    """The near misses of ``motion`` closer than the warning margin, at the driver angles
    interpolated between the samples' ``angles`` (closest first)."""
    if not motion.approaches:
        return ()
    found = [
        CloseApproach(
            a.point, driver, a.margin, float(np.interp(a.at, np.arange(angles.size), angles))
        )
        for a in motion.near_misses
        if a.margin < WARNING_MARGIN * motion.size
    ]
    return tuple(sorted(found, key=lambda a: a.margin))


def once_a_turn(approaches: tuple[CloseApproach, ...]) -> tuple[CloseApproach, ...]:
    """A revolution's close approaches with each pose once: one at the closing sample is the
    one at the first (the same point within 1e-9 rad of the same angle, modulo a turn)."""
    kept: list[CloseApproach] = []
    for a in approaches:
        if not any(
            b.point == a.point
            and abs(math.remainder(b.driver_angle - a.driver_angle, 2.0 * math.pi)) <= 1e-9
            for b in kept
        ):
            kept.append(a)
    return tuple(kept)


def _joints_and_poles(
    scene: LinkageScene, motion: Motion, wanted: frozenset[str], order: int
) -> tuple[list[SlidingJoint], dict[str, tuple[Poles, Poles]]]:
    """The slider parts (``components``) and the links' poles (``poles``), where requested."""
    joints = sliding_joints(scene, motion, order) if "components" in wanted else []
    poles = {}
    if "poles" in wanted:
        poles = {link: link_poles(scene, motion, link) for link in scene.moving_links}
    return joints, poles


class _Driven:
    """Assembles the linkage with the first driver turned by given angles, the others held."""

    def __init__(self, scene: LinkageScene, plan: Plan, tolerance: float | None = None) -> None:
        self.scene, self.plan = scene, plan
        self.given = [driver_input(scene, d, scene.time) for d in scene.drivers]
        self.newton_groups = Continuation(scene, newton_tolerance(tolerance))

    def inputs(self, turns: Array, unit: bool = False) -> list[DriverInput]:
        """The drivers at ``turns`` of the first, at their given rates; ``unit``: the first at
        omega = 1, alpha = 0 and the others at rest (velocities are then d/d theta and
        accelerations d2/d theta2 of the first driver's angle)."""
        n = turns.size
        first = (0.0, 1.0, 0.0) if unit else self.given[0]
        own = np.empty((2, n))  # (one array for both of its rates, filled row by row)
        own[0], own[1] = first[1], first[2]
        inputs = [DriverInput(turns, own[0], own[1])]
        for turn, omega, alpha in self.given[1:]:
            rates = (0.0, 0.0) if unit else (omega, alpha)
            inputs.append(DriverInput(np.full(n, turn), *(np.full(n, r) for r in rates)))
        return inputs

    def run(self, turns: Array, order: int, start: float | None = 0.0) -> Motion:
        """The linkage at ``turns``, on the drawn branch at the turn nearest ``start`` (None:
        at the first turn)."""
        anchor = 0
        if start is not None and turns[0] != start:  # (a revolution starts at ``start``)
            anchor = int(np.argmin(np.abs(turns - start)))
        return assemble(
            self.scene,
            self.plan,
            self.inputs(turns),
            order,
            continuation=True,
            anchor=anchor,
            newton_groups=self.newton_groups,
        )

    def rates(self, turns: Array, signs: dict[int, float]) -> Motion:
        """The linkage at ``turns`` on the branches ``signs`` of its two-branch steps (as
        followed by a sweep: ``branches_at``), with the first driver at unit rate and the others
        at rest: velocities d/d theta and accelerations d2/d theta2 of the first driver's angle."""
        inputs = self.inputs(turns, unit=True)
        return assemble(
            self.scene, self.plan, inputs, 2, signs=signs, newton_groups=self.newton_groups
        )

    def closes(self, turns: Array, strictly: bool = False) -> Array:
        """Whether the linkage closes at each of ``turns`` (each sample alone: no branch is
        followed from one to the next); ``strictly``: without the tangency tolerance (a limit
        found so lies inside the tolerance band and can be posed again)."""
        inputs = self.inputs(turns)
        motion = assemble(self.scene, self.plan, inputs, 0, newton_groups=self.newton_groups)
        if strictly:
            closed: Array = (motion.margin >= 0.0) & motion.converged
            return closed
        return motion.feasible


def _limit(driven: _Driven, inside: float, outside: float) -> float:
    """Bisection for the limit position between a closing and a non-closing driver turn:
    BISECTION_STEPS halvings, middle = (inside + outside) / 2 replacing the end on its side.
    The midpoints of every way the next BISECTION_LEVELS halvings can go are probed in one
    assembly (``_midpoints``), and the halvings then follow the probes' answers: each sample
    closes or not alone, so the limit is the very turn one halving at a time finds."""
    steps = BISECTION_STEPS
    while steps:
        levels = min(BISECTION_LEVELS, steps)
        turns = _midpoints(inside, outside, levels)
        closed = driven.closes(turns, strictly=True)
        node = 0
        for _ in range(levels):
            if closed[node]:
                inside, node = float(turns[node]), 2 * node + 2
            else:
                outside, node = float(turns[node]), 2 * node + 1
        steps -= levels
    return inside


def _midpoints(inside: float, outside: float, levels: int) -> Array:
    """The midpoints of ``levels`` halvings of (inside, outside) whichever way each goes, as a
    binary tree in an array: node j is the midpoint of its interval, its children 2j + 1 (j does
    not close: the interval (inside, j)) and 2j + 2 (j closes: (j, outside))."""
    midpoints: list[float] = []
    intervals = [(inside, outside)]
    for _ in range(levels):
        halves = []
        for low, high in intervals:
            middle = 0.5 * (low + high)
            midpoints.append(middle)
            halves += [(low, middle), (middle, high)]
        intervals = halves
    return np.array(midpoints)


def _turns_fully(motion: Motion) -> bool:
    """Every sample closes, and no window between two samples fails to."""
    feasible = motion.feasible
    return np.count_nonzero(feasible) == feasible.size and not motion.windows


def _first_failure(motion: Motion, turns: Array) -> tuple[float, float]:
    """(the last closing turn, the first non-closing one) along ``turns``: the first sample that
    does not close, or the deepest point of the first window between samples that does not."""
    bad = int(np.argmin(motion.feasible)) if not np.all(motion.feasible) else turns.size
    for window in motion.windows:
        k = math.floor(window.at)
        if k + 1 <= bad:
            x = window.at - k
            return float(turns[k]), float(turns[k] + x * (turns[k + 1] - turns[k]))
    return float(turns[bad - 1]), float(turns[bad])


def _feasible_range(driven: _Driven, start: float, direction: float) -> tuple[float, float] | None:
    """None if the driver turns fully, else the (low, high) turns bounding the start's interval."""
    step = 2.0 * math.pi / PROBE_SAMPLES
    turns = start + direction * step * np.arange(PROBE_SAMPLES + 1)
    motion = driven.run(turns, 0, None)
    if _turns_fully(motion):
        return None
    behind_turns = start - direction * step * np.arange(PROBE_SAMPLES + 1)
    behind = driven.run(behind_turns, 0, None)
    end = _limit(driven, *_first_failure(motion, turns))
    begin = _limit(driven, *_first_failure(behind, behind_turns))
    return (min(begin, end), max(begin, end))


def _newton_range(driven: _Driven, start: float, direction: float) -> tuple[float, float] | None:
    """The feasible range of a linkage with a Newton group: None if the driver turns fully, else
    the turns of the two limit positions its branch meets either way from the drawn pose (found
    by continuation to rounding, whatever the number of samples)."""
    branch = driven.newton_groups.branch(tuple(given[0] for given in driven.given[1:]))
    far = start + direction * 2.0 * math.pi
    return branch.limits(min(start, far), max(start, far))


def _smooth_singular_samples(motion: Motion, singular: Array, cyclic: bool) -> None:
    """Rates at isolated singular samples from the mean of their two neighbours (in place; the
    zeros of the ground and its points, read-only and shared, ``assembly.at_rest``, stay)."""
    n = motion.feasible.size
    rates: list[Array | None] = []
    for point in motion.points.values():
        rates += [point.v, point.a]
    for link in motion.links.values():
        rates += [link.omega, link.alpha, link.anchor.v, link.anchor.a]
    for k in singular:
        before, after = (k - 1) % n, (k + 1) % n
        if not cyclic:
            before, after = max(k - 1, 0), min(k + 1, n - 1)
        for values in rates:
            if values is not None and values.flags.writeable:
                values[k] = 0.5 * (values[before] + values[after])


def _revolution(scene: LinkageScene, samples: int, start: float, direction: float) -> Array:
    """theta_k = start + direction 2 pi k / samples, k = 0 .. samples (back at the start), once
    per scene and (samples, start, direction): the latest kept (``LinkageScene.latest``),
    read-only (shared by the sweeps that ask for it, as ``assembly.at_rest``'s arrays are)."""

    def make() -> Array:
        turns = start + direction * 2.0 * math.pi * np.arange(samples + 1.0) / samples
        turns.flags.writeable = False
        return turns

    return scene.latest("revolution", (samples, start, direction), make)


def _cycle(
    driven: _Driven,
    samples: int,
    order: int,
    start: float,
    direction: float,
    revolution: tuple[Array, Motion] | None,
) -> tuple[Array, Motion, tuple[float, float] | None]:
    """The driver's turns from ``start`` and the motion over them: a full revolution with one
    sample more than asked, back at the start (so the last interval is searched too), or, where
    the linkage cannot turn fully, the midpoints of ``samples`` equal parts of its feasible range
    (that range, the limits, is returned too; None for a full revolution). ``revolution``: the
    turns and the motion over the full revolution where the sweep ran it as its own feasibility
    probe and the linkage turns fully (``_turns_fully``)."""
    if revolution is not None:
        return *revolution, None
    turns = _revolution(driven.scene, samples, start, direction)
    if not driven.plan.closed_form:
        span = _newton_range(driven, start, direction)
    else:
        span = _feasible_range(driven, start, direction)
    if span is None:
        return turns, driven.run(turns, order, start), None
    low, high = span
    turns = low + (high - low) * (np.arange(samples) + 0.5) / samples
    if direction < 0:
        turns = turns[::-1]
    return turns, driven.run(turns, order, start), span


def sweep(
    scene: LinkageScene,
    samples: int,
    quantities: Iterable[str] | None = None,
    tolerance: float | None = None,
) -> Sweep:
    """Turn the first driver through a revolution (or its feasible range) from its start angle;
    ``tolerance`` is a Newton group's (relative to the size; default NEWTON_TOLERANCE)."""
    if not scene.drivers:
        raise InvalidScene("drivers: a sweep needs a driver")
    check_samples(samples)
    wanted = normalise_quantities(["position"] if quantities is None else quantities)
    plan = build_plan(scene)
    driven = _Driven(scene, plan, tolerance)
    start, omega, _ = driven.given[0]
    direction = -1.0 if omega < 0 else 1.0
    order = required_order(wanted)
    drawn = (
        drawn_angle(scene, scene.drivers[0].link)
        if len(scene.links[scene.drivers[0].link].points) >= 2
        else 0.0
    )
    span: tuple[float, float] | None = None
    revolution = None
    if driven.plan.closed_form and samples >= SELF_PROBING_SAMPLES:
        # The sweep is its own feasibility probe; a revolution that turns fully closes at its
        # first sample, the start.
        turns = _revolution(scene, samples, start, direction)
        revolution = turns, driven.run(turns, order, start)
    # The drawn pose closes by construction; a start at angle_deg must be checked.
    unchecked = revolution is None or not _turns_fully(revolution[1])
    if unchecked and start != 0.0 and not driven.closes(np.array([start]))[0]:
        require_feasible(driven.run(np.array([start]), 0), "at the sweep's starting angle")
    turns, motion, span = _cycle(
        driven, samples, order, start, direction, None if unchecked else revolution
    )
    angles = drawn + turns
    approaches = close_approaches(motion, scene.drivers[0].link, angles)
    if span is None:  # the closing sample off
        approaches = once_a_turn(approaches)
        motion, turns, angles = motion.cut(slice(0, samples)), turns[:samples], angles[:samples]
    if unchecked:  # (a revolution that turns fully closes at every sample and between them)
        require_feasible(motion, "during the sweep")
    limits: tuple[float, ...] = span or ()
    singular = np.array([], dtype=int)
    if order and motion.gradient_sine.min() < MIN_GRADIENT_SINE:  # (one pass where none is)
        singular = np.flatnonzero(motion.gradient_sine < MIN_GRADIENT_SINE)
    if singular.size:
        _smooth_singular_samples(motion, singular, cyclic=span is None)
    stroke_of = extremes_of = None
    if span is None:
        stroke_of = partial(_strokes, driven, turns=turns, drawn=drawn, motion=motion)
        extremes_of = partial(_angle_extremes, driven, turns=turns, drawn=drawn, motion=motion)
    return Sweep(
        scene,
        scene.drivers[0].link,
        angles,
        motion,
        span is None,
        tuple(drawn + limit for limit in limits),
        singular,
        wanted,
        *_joints_and_poles(scene, motion, wanted, order),
        approaches,
        order,
        stroke_of,
        extremes_of,
    )


def _hermite_interpolation() -> Array:
    """The matrix taking the values f(x_i) and the slopes f'(x_i) at the ``STROKE_NODES``
    Chebyshev-Lobatto nodes x_i = -cos(pi i / (n - 1)) of [-1, 1] to the Chebyshev coefficients
    of their Hermite interpolant (degree 2 n - 1)."""
    degree = 2 * STROKE_NODES - 1
    basis = np.eye(degree + 1)
    values = chebyshev.chebvander(_NODES, degree)
    slopes = np.stack([chebyshev.chebval(_NODES, chebyshev.chebder(b)) for b in basis], axis=1)
    inverse: Array = np.linalg.inv(np.vstack([values, slopes]))
    return inverse


_NODES = -np.cos(np.pi * np.arange(STROKE_NODES) / (STROKE_NODES - 1))
_HERMITE = _hermite_interpolation()


def _stationary_points(
    s: Array, rate: Array, curvature: Array, half_widths: Array
) -> tuple[Array, Array, Array] | None:
    """Where s(theta) is stationary in each bracket j, from s, ds/dtheta and d2s/dtheta2 (rows
    j) at the ``_NODES`` of the bracket of half-width ``half_widths[j]`` (x = (theta -
    centre) / half-width): the root x* of the Hermite interpolant p of ds/dtheta between the
    two nodes where it changes sign (Newton's method on p from the secant there), s at x* (the
    Hermite interpolant of s), and the root's estimated error in theta, |a_(m-1)| + |a_m| (the
    last two Chebyshev coefficients of p) over |p'(x*)|, times the half-width. None unless
    ds/dtheta changes sign exactly once along each bracket's nodes and Newton's method stays
    between those two nodes."""
    sign = np.signbit(rate)
    changes = sign[:, 1:] != sign[:, :-1]
    if np.any(np.count_nonzero(changes, axis=1) != 1):
        return None
    k = np.argmax(changes, axis=1)
    rows = np.arange(k.size)
    low, high = _NODES[k], _NODES[k + 1]
    width = half_widths[:, None]
    slope = _HERMITE @ np.concatenate([rate, width * curvature], axis=1).T  # a column each
    bend = chebyshev.chebder(slope)
    before, after = rate[rows, k], rate[rows, k + 1]
    x = low - before * (high - low) / (after - before)
    for _ in range(NEWTON_STEPS):
        step = chebyshev.chebval(x, slope, tensor=False) / chebyshev.chebval(x, bend, tensor=False)
        x = x - step
        if np.any((x < low) | (x > high)):
            return None
        if np.all(np.abs(step) <= 4e-16):
            break
    tail = np.abs(slope[-1]) + np.abs(slope[-2])
    error = tail / np.abs(chebyshev.chebval(x, bend, tensor=False)) * half_widths
    values = _HERMITE @ np.concatenate([s, width * rate], axis=1).T
    return x, chebyshev.chebval(x, values, tensor=False), error


Columns = Callable[[Motion], tuple[Array, Array, Array]]
"""A quantity s of a run and its derivatives ds/dtheta, d2s/dtheta2 (the run at unit driver
rate: ``_Driven.rates``)."""


def _extremes(
    driven: _Driven, columns: Columns, brackets: list[tuple[float, float]], signs: dict[int, float]
) -> list[tuple[float, float]] | None:
    """The driver turns where the quantity ``columns`` gives is stationary, one in each bracket
    (low, high) of turns, with its value there: ``_stationary_points`` on ds/dtheta from one
    run (``_Driven.rates``, on the branches ``signs``) over every bracket's nodes, repeated on
    brackets shrunk around the roots until each root's estimated error is below
    ``STROKE_TOLERANCE`` (None if it is not after ``STROKE_RUNS`` runs, or where ds/dtheta does
    not change sign once in a bracket)."""
    centres = np.array([0.5 * (low + high) for low, high in brackets])
    widths = np.array([0.5 * (high - low) for low, high in brackets])
    for _ in range(STROKE_RUNS):
        motion = driven.rates((centres[:, None] + widths[:, None] * _NODES).ravel(), signs)
        s, rate, curvature = (c.reshape(centres.size, -1) for c in columns(motion))
        found = _stationary_points(s, rate, curvature, widths)
        if found is None:
            return None
        x, values, errors = found
        roots = centres + widths * x
        if np.all(errors <= STROKE_TOLERANCE):
            return [(float(r), float(v)) for r, v in zip(roots, values, strict=True)]
        # The next bracket: well around the root, never wider than half this one.
        centres, widths = roots, np.minimum(0.5 * widths, np.maximum(16.0 * errors, 1e-15))
    return None


def _travel_columns(scene: LinkageScene, point: str) -> Columns:
    """The displacement of ``point``'s slider on its guide and its derivatives."""

    def columns(motion: Motion) -> tuple[Array, Array, Array]:
        travel = next(t for t in slider_travel(scene, motion, 2) if t.point == point)
        assert travel.sliding_velocity is not None and travel.sliding_acceleration is not None
        return travel.displacement, travel.sliding_velocity, travel.sliding_acceleration

    return columns


def _turning_points(
    driven: _Driven, values: Array, columns: Columns, turns: Array, motion: Motion, scale: float
) -> list[tuple[float, float]] | None:
    """Where a quantity sampled as ``values`` at ``turns`` (one turn, without the closing
    sample; ``motion`` the sweep's) turns back over the revolution: each sampled extreme
    bracketed by its two neighbours and refined to rounding where ds/dtheta = 0 (``_extremes``
    on ``columns``, on the branches the sweep followed there), as (turn, value) in the order the
    driver reaches them (steps below 1e-12 ``scale`` count as standing still). [] where it never
    turns back; None where a refinement fails."""
    step = np.diff(np.append(values, values[0]))  # s[k + 1] - s[k], cyclic
    moving = np.flatnonzero(np.abs(step) > 1e-12 * scale)
    signs = np.sign(step[moving])
    turning = np.flatnonzero(signs != np.roll(signs, 1))  # s turns back between moving steps
    delta = turns[1] - turns[0]
    period = delta * turns.size  # +-2 pi, as the driver turns
    runs: dict[tuple[tuple[int, float], ...], list[tuple[float, float]]] = {}
    for j in turning:
        before, after = int(moving[j - 1]), int(moving[j])  # steps k -> k + 1 (cyclic)
        ends = (turns[before], turns[after] + delta + (period if after < before else 0.0))
        branches = branches_at(motion.flips, float((before + 1) % turns.size))
        runs.setdefault(tuple(sorted(branches.items())), []).append((min(ends), max(ends)))
    extremes: list[tuple[float, float]] = []
    for branches_key, brackets in runs.items():  # (one run per set of branches)
        found = _extremes(driven, columns, brackets, dict(branches_key))
        if found is None:
            return None
        extremes += found
    turned = [(turns[0] + (((root - turns[0]) / period) % 1.0) * period, s) for root, s in extremes]
    return sorted(turned, key=lambda f: (f[0] - turns[0]) / period)  # as the driver reaches them


def _strokes(
    driven: _Driven, travel: SliderTravel, turns: Array, drawn: float, motion: Motion
) -> Strokes | None:
    """The ram's extreme positions over a revolution sampled at ``turns``: its two turning
    points (``_turning_points``; as the limit positions are refined, whatever the number of
    samples), None unless it turns back exactly twice."""
    columns = _travel_columns(driven.scene, travel.point)
    found = _turning_points(driven, travel.displacement, columns, turns, motion, motion.size)
    if found is None or len(found) != 2:
        return None
    first = abs(found[1][0] - found[0][0])
    second = 2.0 * math.pi - first
    return Strokes(
        (float(drawn + found[0][0]), float(drawn + found[1][0])),
        (found[0][1], found[1][1]),
        float(max(first, second)),
        float(min(first, second)),
    )


@dataclass(frozen=True)
class AngleExtremes:
    """A link's least and greatest absolute angle over a full revolution of the driver (rad,
    the angle followed continuously from the drawn pose) at the driver's absolute angles
    ``driver_angles`` (rad, in [drawn, drawn + 2 pi) as the driver turns from its drawn angle),
    where its angular velocity is zero (refined to rounding: ``_turning_points``)."""

    least: float
    greatest: float
    driver_angles: tuple[float, float]  # at the least, at the greatest


def _angle_extremes(
    driven: _Driven, link: str, turns: Array, drawn: float, motion: Motion
) -> AngleExtremes | None:
    """``link``'s extreme angles over the revolution sampled at ``turns`` (``motion`` the
    sweep's): its turning points' least and greatest; None where it turns fully (never turns
    back) or a refinement fails."""
    own = drawn_angle(driven.scene, link)

    def columns(run: Motion) -> tuple[Array, Array, Array]:
        m = run.links[link]
        assert m.omega is not None and m.alpha is not None
        return own + m.theta, m.omega, m.alpha

    sampled = own + motion.links[link].theta
    found = _turning_points(driven, sampled, columns, turns, motion, 1.0)
    if not found:
        return None
    # Each refined angle on the sweep's continuous branch (that of the nearest sample).
    near = []
    for t, v in found:
        k = round((t - turns[0]) / (turns[1] - turns[0])) % turns.size
        near.append((t, v + 2.0 * math.pi * round((sampled[k] - v) / (2.0 * math.pi))))
    low, high = min(near, key=lambda f: f[1]), max(near, key=lambda f: f[1])
    return AngleExtremes(low[1], high[1], (float(drawn + low[0]), float(drawn + high[0])))


@dataclass(frozen=True)
class TimeSweep(_Warned):
    """The linkage and its moving points over ``time`` (for animating time laws)."""

    scene: LinkageScene
    time: Array
    driver_angle: Array
    motion: Motion
    moving_points: dict[str, MovingPointMotion]
    quantities: frozenset[str]
    joints: list[SlidingJoint]
    poles: dict[str, tuple[Poles, Poles]]
    close_approaches: tuple[CloseApproach, ...] = ()
    order: int = 0


def sweep_time(
    scene: LinkageScene,
    t0: float,
    t1: float,
    samples: int,
    quantities: Iterable[str] | None = None,
    tolerance: float | None = None,
) -> TimeSweep:
    """The scene at ``samples`` instants from t0 to t1 (drivers and moving points by their laws);
    ``tolerance`` as for ``sweep``."""
    check_samples(samples)
    if not (math.isfinite(t0) and math.isfinite(t1) and t1 > t0):
        raise InvalidScene(f"time_range: expected [t0, t1] with t1 > t0, got [{t0}, {t1}]")
    wanted = normalise_quantities(["position"] if quantities is None else quantities)
    times = np.linspace(t0, t1, samples)
    plan = build_plan(scene)
    inputs = driver_inputs_over_time(scene, times)
    order = required_order(wanted, bool(scene.moving_points))
    groups = Continuation(scene, newton_tolerance(tolerance))
    motion = assemble(scene, plan, inputs, order, continuation=True, newton_groups=groups)
    require_feasible(motion, f"during t = {t0:g} .. {t1:g} s")
    if scene.moving_points and order < 2:
        motion_for_points = assemble(
            scene, plan, inputs, 2, continuation=True, newton_groups=groups
        )
    else:
        motion_for_points = motion
    moving = {
        mp.name: moving_point_motion(scene, mp, motion_for_points.links[mp.link], times)
        for mp in scene.moving_points
    }
    first = scene.drivers[0].link if scene.drivers else None
    angle = np.zeros(samples)
    if first is not None and len(scene.links[first].points) >= 2:
        angle = drawn_angle(scene, first) + inputs[0].theta
    return TimeSweep(
        scene,
        times,
        angle,
        motion,
        moving,
        wanted,
        *_joints_and_poles(scene, motion, wanted, order),
        close_approaches(motion, first or "", angle),
        order,
    )

"""Assemble a linkage at given driver inputs: positions, velocities, accelerations on request.

Runs a ``Plan`` (see ``topology``) vectorised over samples. The branch of each two-branch group is
the drawn one (the same orientation of the dyad's triangle, as the spec asks for a single pose).
With ``continuation=True`` (a sweep) it switches only where the group's two branches meet between
two samples within rounding: the closest approach of the branches over the continuous driver
path is found by Brent's method wherever the samples' margins and their rates say it could come
near (``candidate_intervals``), so a parallelogram stays a parallelogram through its change
points and a linkage 1e-12 off a change point keeps its assembly, at any sample count. Where
two samples are further apart than MAX_DRIVER_STEP in some driver, the continuation follows a
grid with driver values inserted between them (``DenseGrid``) and answers at the given samples.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, replace
from functools import cached_property
from typing import cast

import numpy as np
import numpy.typing as npt
from scipy.optimize import brentq, minimize_scalar

from solver.errors import LimitExceeded, NotAssemblable
from solver.kinematics.rigid import (
    Array,
    LinkMotion,
    PointMotion,
    Relative,
    direction,
    link_from_two_points,
    repeat,
    rotate,
)
from solver.model.scene import LinkageScene
from solver.position import groups, newton
from solver.position.continuation import Continuation, solve_group
from solver.position.groups import loci
from solver.position.newton import NewtonReport
from solver.position.topology import (
    CircleSpec,
    DriverStep,
    DyadStep,
    GuidedStep,
    LeverStep,
    LocusSpec,
    NewtonStep,
    Plan,
    PlanStep,
    Reach,
    TwoPointStep,
)

EPS = float(np.finfo(float).eps)

# Where the branches come closer than this fraction of the linkage's size without meeting, a
# sweep reports the closest approach (a real mechanism with clearance could switch there).
WARNING_MARGIN = 1e-3

# The largest step of any driver between two samples that the continuation follows as it is;
# longer steps are split into equal parts no longer than this (``dense_grid``). A group's margin
# is a smooth function of each driver angle, periodic in 2 pi: a piece with one minimum a turn
# (the four-bar's d - |r1 - r2|) is convex within about pi/2 of it, and a step under pi/2 keeps
# the interval around it inside that convex neighbourhood, as the screen needs, and two of a
# parallelogram's change points (pi apart) out of one interval, as the search needs (it finds
# one minimum an interval). pi/8 leaves a factor 4 for pieces with more than one minimum a turn:
# the two-dip six-bar's dips, 37 deg apart, are missed at steps of 45 deg, found from 40 deg down.
MAX_DRIVER_STEP = math.pi / 8
# The most samples a densified grid may have: 1e6 samples, 400 000 rad of a driver (a
# parallelogram's 125 000 change points, one every pi of the crank, each searched in some 10 ms).
MAX_DENSE_SAMPLES = 1_000_000
# A piece's rate at a sample counts as zero (the piece stationary there) below this fraction of
# its larger rate at the two ends of the interval: a rate of rounding (sin 2 pi = -2.4e-16) is
# far below it, and a minimum this close to a sample is there to 1e-18 of the interval squared.
STATIONARY = 1e-9


@dataclass(frozen=True, init=False)
class DriverInput:
    """Rotation of a driven link from its drawn pose, and its rates, per sample (N,). (Frozen,
    its fields written at once as ``rigid.PointMotion``'s.)"""

    theta: Array
    omega: Array
    alpha: Array

    def __init__(self, theta: Array, omega: Array, alpha: Array) -> None:
        fields = self.__dict__
        fields["theta"], fields["omega"], fields["alpha"] = theta, omega, alpha


@dataclass(frozen=True)
class Approach:
    """The closest approach of a group's two branches between samples: at fractional sample
    ``at`` of the samples asked for (k + x: x of the way from sample k to k + 1, the drivers
    linear in x), the length margin ``margin`` (metres; within the coincidence tolerance the
    branches meet, below it the group cannot close)."""

    point: str
    at: float
    margin: float


@dataclass(frozen=True, init=False)
class Motion:
    """The solved state of a linkage over N samples.

    ``gradient_sine`` is the smallest sine of the angle between the two constraint gradients of
    any group (0 at a dead centre); ``margin`` the smallest length margin m / size of any
    two-branch group (negative where a group does not close); ``converged`` false where a Newton
    group's Newton-Raphson did not converge; ``group_margins`` each two-branch group's m (metres),
    by the point (or slot) it locates.
    With continuation, ``approaches`` lists every close approach found between samples: branch
    switches (the branches meet), near misses, and windows where the linkage cannot close.
    (Frozen, its fields written at once as ``rigid.PointMotion``'s.)
    """

    links: dict[str, LinkMotion]
    points: dict[str, PointMotion]
    margin: Array
    converged: Array
    gradient_sine: Array
    failures: list[str]
    newton: list[NewtonReport]
    approaches: list[Approach]
    size: float
    group_margins: dict[str, Array]
    # With continuation, per two-branch step (its index in the plan): its branch sign at the first
    # sample and the fractional samples where it switches (``branches_at``).
    flips: dict[int, tuple[float, list[float]]]

    def __init__(
        self,
        links: dict[str, LinkMotion],
        points: dict[str, PointMotion],
        margin: Array,
        converged: Array,
        gradient_sine: Array,
        failures: list[str],
        newton: list[NewtonReport],
        approaches: list[Approach],
        size: float,
        group_margins: dict[str, Array],
        flips: dict[int, tuple[float, list[float]]],
    ) -> None:
        fields = self.__dict__
        fields["links"], fields["points"], fields["margin"] = links, points, margin
        fields["converged"], fields["gradient_sine"], fields["failures"] = (
            converged,
            gradient_sine,
            failures,
        )
        fields["newton"], fields["approaches"], fields["size"] = newton, approaches, size
        fields["group_margins"], fields["flips"] = group_margins, flips

    @property
    def feasible(self) -> Array:
        """Samples where every group closed (to the coincidence tolerance) and every Newton group
        converged."""
        return (self.margin >= -loci.COINCIDENCE_TOLERANCE) & self.converged

    def cut(self, part: slice | Array) -> Motion:
        """The same motion at the samples ``part`` only (a slice or sample indices; approaches,
        Newton reports and branch switches kept as found)."""
        points, cut = {}, {}  # (a link's anchor is a point's motion, by its id: cut once)
        for k, m in self.points.items():
            points[k] = cut[id(m)] = m.at(part)
        links = {}
        for k, link in self.links.items():
            anchor = cut.get(id(link.anchor))
            if anchor is None:  # (a pivot that is no point of the scene's)
                anchor = cut[id(link.anchor)] = link.anchor.at(part)
            omega, alpha = link.omega, link.alpha
            links[k] = LinkMotion(
                link.anchor0,
                anchor,
                link.theta[part],
                None if omega is None else omega[part],
                None if alpha is None else alpha[part],
            )
        return Motion(
            links,
            points,
            self.margin[part],
            self.converged[part],
            self.gradient_sine[part],
            self.failures,
            self.newton,
            self.approaches,
            self.size,
            {k: m[part] for k, m in self.group_margins.items()},
            self.flips,
        )

    @property
    def windows(self) -> list[Approach]:
        """Closest approaches between samples where the linkage cannot close."""
        return [a for a in self.approaches if a.margin < -loci.COINCIDENCE_TOLERANCE * self.size]

    @property
    def near_misses(self) -> list[Approach]:
        """Closest approaches between samples where the branches come close without meeting."""
        return [a for a in self.approaches if a.margin > loci.COINCIDENCE_TOLERANCE * self.size]


# A driver that moves along the path: (driver, its angles theta_k, the largest magnitude of its
# steps delta_k = theta_k+1 - theta_k).
PathStep = tuple[int, Array, float]


def path_steps(inputs: Sequence[DriverInput]) -> list[PathStep]:
    """The drivers that move along the path (thetas linear between samples), with their steps."""
    path = []
    for driver, given in enumerate(inputs):
        theta = given.theta
        # (The steps are not kept: at many samples a live array costs its page faults.)
        largest = float(np.abs(theta[1:] - theta[:-1]).max()) if theta.size > 1 else 0.0
        if largest > 0.0:
            path.append((driver, theta, largest))
    return path


def coarse(path: Sequence[PathStep]) -> bool:
    """Whether some driver steps more than MAX_DRIVER_STEP between two samples (then the
    continuation follows a denser grid: ``dense_grid``)."""
    return any(largest > MAX_DRIVER_STEP for _, _, largest in path)


def rates_alone(inputs: Sequence[DriverInput], order: int, path: Sequence[PathStep]) -> bool:
    """Whether a run's velocities (``order`` >= 1) are at the rate of the one driver that moves
    along the path alone (non-zero at every sample, every other driver at rest): then a margin's
    rate over that driver's rate is dm/dtheta."""
    if order < 1 or len(path) != 1:
        return False
    moving = path[0][0]
    return all(
        bool((given.omega != 0.0).all()) if driver == moving else not given.omega.any()
        for driver, given in enumerate(inputs)
    )


def unit_rate(inputs: Sequence[DriverInput], driver: int) -> list[DriverInput]:
    """The same driver angles with ``driver`` turning at unit rate and every other at rest."""
    n = inputs[0].theta.size
    return [
        DriverInput(given.theta, np.full(n, float(j == driver)), np.zeros(n))
        for j, given in enumerate(inputs)
    ]


def lipschitz_clear(
    least: float, reaches: Sequence[Reach], path: Sequence[PathStep], size: float
) -> bool:
    """Whether the margin of a group measured between points of the given reaches, ``least``
    min(m) at the samples, stays above WARNING_MARGIN size between every two samples, whatever
    its shape: m is 1-Lipschitz in those points, so |dm/du| <= G = sum |P - pivot| max |delta|
    and m >= (m_k + m_k+1 - G) / 2 between samples k and k + 1; min(m) - G / 2 >= WARNING_MARGIN
    size clears every interval."""
    bound = 0.0
    for moving, _, step in path:
        bound += step * sum(radius for driver, radius in reaches if driver == moving)
    return bool(least - 0.5 * bound >= WARNING_MARGIN * size)


def path_rates(sensitivities: Sequence[Array], path: Sequence[PathStep]) -> tuple[Array, Array]:
    """(p, q): dm/du at the start and at the end of each interval along its own direction,
    p_k = sum_i g_i,k delta_i,k and q_k = sum_i g_i,k+1 delta_i,k (g_i = dm/dtheta_i)."""
    falls = rises = np.zeros(path[0][1].size - 1)
    for g, (_, theta, _) in zip(sensitivities, path, strict=True):
        delta = theta[1:] - theta[:-1]
        falls, rises = falls + g[:-1] * delta, rises + g[1:] * delta
    return falls, rises


def screen(
    margin: Array,
    pieces: Sequence[Array],
    sensitivities: Sequence[Sequence[Array]],
    path: Sequence[PathStep],
    size: float,
    closed: Array | None = None,
) -> list[tuple[int, int]]:
    """The intervals the branch search examines, in the order of the path: (k, j), piece j of a
    group's margin (``loci.Piece``: the margin is the smallest of its smooth pieces) between
    samples k and k + 1 that both close (``closed``: where every group so far closes; None:
    all), from each piece's rates along the path (``path_rates``; ``sensitivities[i][j]`` is
    dm_j/dtheta for the i-th moving driver) and from the margin's values:

    - every interval that ``candidate_intervals`` finds for a piece (sound for a piece no steeper
      between its samples than at one of them, a piece convex there among them);
    - beside every sample that ``candidate_minima`` finds, the intervals where a piece turns from
      falling to rising, or, where none does, both, for the piece that is the margin there.
    """
    minima = candidate_minima(margin, size)
    # candidate_intervals' bound is at least min(m) - max(|p|, |q|) / 2, and |p|, |q| <=
    # sum_i max |g_i| max |delta_i|: where that clears the threshold, it finds nothing (the
    # common case, a linkage far from its change points).
    largest = [step for _, _, step in path]
    steepest = max(
        sum(np.abs(g).max() * step for g, step in zip(of_piece, largest, strict=True))
        for of_piece in zip(*sensitivities, strict=True)
    )
    if not minima.size and margin.min() - 0.5 * steepest >= WARNING_MARGIN * size:
        return []
    found: set[tuple[int, int]] = set()
    turns = []
    for j, values in enumerate(pieces):
        falls, rises = path_rates([of_driver[j] for of_driver in sensitivities], path)
        found |= {(int(k), j) for k in candidate_intervals(values, falls, rises, size)}
        turns.append((falls < 0.0) & (rises >= 0.0))
    for k in minima:
        beside = [int(i) for i in (k - 1, k) if 0 <= i < margin.size - 1]
        turning = {(i, j) for j, turn in enumerate(turns) for i in beside if turn[i]}
        active = int(np.argmin([values[k] for values in pieces]))
        found |= turning or {(i, active) for i in beside}
    # (Where a sample does not close, the group's rates there are those of a pose that is not.)
    return sorted((k, j) for k, j in found if closed is None or (closed[k] and closed[k + 1]))


def candidate_minima(margin: Array, size: float) -> Array:
    """Samples k at a local minimum of the margin (two samples or more) whose neighbourhood may
    dip below the warning threshold by its values alone: m_k - max(m_k-1 - m_k, m_k+1 - m_k) <
    WARNING_MARGIN size (a bound that holds for a margin convex between samples k - 1 and k + 1,
    and generous where it is not: a V as deep as its steeper side). The first and the last
    sample count with their one neighbour."""
    # Every such bound is at least min(m) - max |m_k+1 - m_k|: where that clears the threshold,
    # no sample is a candidate (the common case, a linkage far from its change points).
    if margin.min() - np.abs(np.diff(margin)).max() >= WARNING_MARGIN * size:
        return np.array([], dtype=int)
    before = np.concatenate([[np.inf], margin[:-1]])
    after = np.concatenate([margin[1:], [np.inf]])
    rise = np.maximum(
        np.where(np.isinf(before), -np.inf, before - margin),
        np.where(np.isinf(after), -np.inf, after - margin),
    )
    found = (margin < before) & (margin <= after) & (margin - rise < WARNING_MARGIN * size)
    return np.flatnonzero(found)


def candidate_intervals(margin: Array, falls: Array, rises: Array, size: float) -> Array:
    """Intervals k (samples k to k + 1) where a piece of a margin may dip below WARNING_MARGIN
    size, by its values and its rates p, q at both ends (``path_rates``). Where its rate between
    them is nowhere steeper than at an end (a piece convex there, or steepest at a sample),
    |dm/du| <= G = max(|p|, |q|), so m >= (m_k + m_k+1 - G) / 2 there. Candidates: the intervals
    where that bound falls below the threshold and the piece turns from falling to rising
    (p < 0 <= q), or does not but both samples clear the threshold (a dip hidden between them);
    not those beside a sample already below it without a turn (the minimum there is searched
    where the piece turns)."""
    floor = WARNING_MARGIN * size
    # G also takes |m_k+1 - m_k| (no more than G within the class): outside it, so that the
    # bound is never above the lower sample.
    steepest = np.maximum(np.maximum(np.abs(falls), np.abs(rises)), np.abs(np.diff(margin)))
    before, after = margin[:-1], margin[1:]
    lowest = np.minimum(before, after)
    turns = (falls < 0.0) & (rises >= 0.0)
    return np.flatnonzero((0.5 * (before + after - steepest) < floor) & (turns | (lowest >= floor)))


def branches_at(flips: Mapping[int, tuple[float, list[float]]], u: float) -> dict[int, float]:
    """The branch sign of each two-branch step at fractional sample u of a motion assembled with
    continuation (``Motion.flips``): its sign at the first sample, times -1 for every switch
    before u."""
    return {
        step: first * (-1.0) ** sum(1 for at in switches if at < u)
        for step, (first, switches) in flips.items()
    }


def between(values: Array, k: Array | int, x: Array | float) -> Array:
    """values at fractional samples u = k + x, 0 <= x <= 1, linear between samples k and k + 1
    (exactly values[k] at x = 0)."""
    return np.asarray(values[k] + x * (values[k + 1] - values[k]))


def interpolated_inputs(inputs: Sequence[DriverInput], k: int, x: float) -> list[DriverInput]:
    """The drivers at fractional sample u = k + x, 0 <= x <= 1 (thetas linear between samples k
    and k + 1), with rates d theta / du: the path the continuation follows between two samples."""
    out = []
    for given in inputs:
        theta = given.theta
        step = float(theta[k + 1] - theta[k])
        out.append(DriverInput(np.array([between(theta, k, x)]), np.array([step]), np.zeros(1)))
    return out


@dataclass(frozen=True)
class DenseGrid:
    """The samples a continuation follows where the given ones step too far (``dense_grid``):
    ``inputs`` the drivers on it, ``index`` the dense sample of each given sample."""

    inputs: list[DriverInput]
    index: Array

    def given(self, u: float) -> float:
        """The fractional given sample of fractional dense sample u (the drivers are linear in
        both between two given samples, so the map is linear there)."""
        k = min(int(np.searchsorted(self.index, u, side="right")) - 1, self.index.size - 2)
        return k + float((u - self.index[k]) / (self.index[k + 1] - self.index[k]))

    def restrict(self, motion: Motion) -> Motion:
        """A motion followed on the dense grid at the given samples: its close approaches and
        branch switches at given fractional samples; a dense sample between two given ones that
        does not close, a window between them (the deepest of each interval, as the search
        reports one); a Newton group that did not converge between them, not converged at the
        first of the two."""
        index = self.index
        converged = np.logical_and.reduceat(motion.converged, index)
        return replace(
            motion.cut(index),
            converged=converged,
            newton=[
                replace(report, converged=np.logical_and.reduceat(report.converged, index))
                for report in motion.newton
            ],
            approaches=[Approach(a.point, self.given(a.at), a.margin) for a in motion.approaches]
            + self.windows(motion),
            flips={
                step: (first, [self.given(u) for u in switches])
                for step, (first, switches) in motion.flips.items()
            },
        )

    def windows(self, motion: Motion) -> list[Approach]:
        """The deepest dense sample of each given interval that a group fails to close at (not
        a given sample), as a window: the group with the smallest margin there."""
        fails = motion.margin < -loci.COINCIDENCE_TOLERANCE
        fails[self.index] = False
        found = []
        for k in np.unique(np.searchsorted(self.index, np.flatnonzero(fails)) - 1).tolist():
            inside = np.arange(self.index[k] + 1, self.index[k + 1])
            deepest = int(inside[np.argmin(motion.margin[inside])])
            point = min(motion.group_margins, key=lambda p: motion.group_margins[p][deepest])
            margin = float(motion.group_margins[point][deepest])
            found.append(Approach(point, self.given(deepest), margin))
        return found


def dense_parts(inputs: Sequence[DriverInput]) -> npt.NDArray[np.int_] | None:
    """None where no driver steps more than MAX_DRIVER_STEP between two samples; else the fewest
    equal parts of every interval that bring each driver's step within it, ceil(widest step /
    MAX_DRIVER_STEP) (at least 1). Raises ``LimitExceeded``, stating the drivers' turn, where
    1 + their sum passes MAX_DENSE_SAMPLES (counted in floats: a driver turning 1e30 rad
    would overflow an integer count)."""
    path = path_steps(inputs)
    if not coarse(path):
        return None
    widest = np.max([np.abs(np.diff(theta)) for _, theta, _ in path], axis=0)
    parts = np.maximum(np.ceil(widest / MAX_DRIVER_STEP), 1.0)  # 1: every driver at rest
    total = float(parts.sum()) + 1.0
    if not total <= MAX_DENSE_SAMPLES:
        raise LimitExceeded(
            f"samples: following the linkage in driver steps of at most {MAX_DRIVER_STEP:.4g} "
            f"rad (pi/8) between the {widest.size + 1} samples (the drivers turn "
            f"{float(widest.sum()):.6g} rad, steps of up to {float(widest.max()):.6g} rad) "
            f"takes {total:.0f} samples, more than {MAX_DENSE_SAMPLES}: shorten the range or "
            "slow the drivers"
        )
    return parts.astype(int)


def dense_grid(inputs: Sequence[DriverInput]) -> DenseGrid | None:
    """None where no driver steps more than MAX_DRIVER_STEP between two samples; else every
    interval split into its ``dense_parts``, the drivers' angles and rates linear between the
    given samples (``between``). Raises ``LimitExceeded`` beyond MAX_DENSE_SAMPLES."""
    parts = dense_parts(inputs)
    if parts is None:
        return None
    total = int(parts.sum()) + 1
    index = np.concatenate([[0], np.cumsum(parts)])
    k = np.repeat(np.arange(parts.size), parts)
    x = (np.arange(total - 1) - index[k]) / parts[k]
    dense = [
        DriverInput(
            *(np.append(between(a, k, x), a[-1]) for a in (given.theta, given.omega, given.alpha))
        )
        for given in inputs
    ]
    return DenseGrid(dense, index)


class _Assembler:
    """Runs one plan over one set of inputs (state lives only for the duration of ``run``).

    ``signs`` forces the branch of given steps, one sign or one per sample (used to evaluate a
    group between two samples, or its rate at unit driver rate, with the branches chosen there);
    with continuation, each group is on its drawn branch at sample ``anchor``.
    """

    def __init__(
        self,
        scene: LinkageScene,
        inputs: Sequence[DriverInput],
        order: int,
        continuation: bool,
        signs: Mapping[int, float | Array] | None = None,
        anchor: int = 0,
        newton_groups: Continuation | None = None,
    ) -> None:
        self.scene = scene
        self.newton_groups = newton_groups
        self.inputs = inputs
        self.order = order
        # Where a screen at order 0 needs rates: velocities at unit rate of the moving driver,
        # computed up to the last group that needs them (``run``).
        self.rates, self.rated_until = order, 0
        self.continuation = continuation
        self.signs = signs or {}
        self.samples = len(inputs[0].theta) if inputs else 1
        # Samples at the drawn pose (every driver unturned): the drawn coordinates are the answer
        # there (they close by construction; a re-solved point near a tangency would not be).
        self.at_drawn = inputs[0].theta == 0.0 if inputs else np.ones(1, dtype=bool)
        for given in inputs[1:]:
            self.at_drawn &= given.theta == 0.0
        self.links: dict[str, LinkMotion] = {}
        self.points: dict[str, PointMotion] = {}
        self.relative: dict[tuple[str, str], Relative] = {}  # (``Placed.relative``)
        self.resting_ids: set[int] = set()  # (ids of) the fixed points' and driver pivots' motions
        # The smallest relative margin and gradient sine of the groups so far, per sample (1.0
        # before the first group: ``per_sample``).
        self.margin: Array | float = 1.0
        self.converged = np.empty(self.samples, dtype=bool)
        self.converged.fill(True)  # (cheaper than np.ones)
        self.gradient_sine: Array | float = 1.0
        self.failures: list[str] = []
        self.reports: list[newton.NewtonReport] = []
        self.steps: tuple[PlanStep, ...] = ()
        self.anchor = anchor
        self.flips: dict[int, tuple[float, list[float]]] = {}  # sign at sample 0, switches
        self.sign_of: dict[int, Array | float] = {}  # each two-branch step's sign per sample
        self.approaches: list[Approach] = []
        self.last: Callable[[], tuple[loci.Piece, ...]] = tuple  # the last group's pieces
        self.group_margins: dict[str, Array] = {}

    def know(self, link: str, motion: LinkMotion) -> None:
        """Record a link's motion and carry its points not yet known (``LinkMotion.point``)."""
        self.links[link] = motion
        for p in self.scene.links[link].points:
            if p not in self.points:
                self.points[p] = motion.point(self.scene.drawn(p))

    def two_point(self, step: TwoPointStep) -> None:
        """A link known from two of its known points (``rigid.link_from_two_points``)."""
        P, Q = self.points[step.first], self.points[step.second]
        P0 = self.scene.drawn(step.first)
        directions = self.scene.memo.setdefault("directions", {})  # (of the drawn pose: once)
        drawn = directions.get((step.first, step.second))
        if drawn is None:
            drawn = directions[step.first, step.second] = direction(
                P0, self.scene.drawn(step.second)
            )
        seen = self.relative.get((step.first, step.second))
        motion = link_from_two_points(P0, P, Q, drawn, self.resting(step.first), seen)
        self.know(step.link, motion)

    def resting(self, point: str) -> bool:
        """Whether a known point is at rest by construction (fixed, or a driver's pivot)."""
        return id(self.points[point]) in self.resting_ids

    def closed(self) -> Array:
        """Samples where every group so far closed (and every Newton group converged)."""
        return (self.margin >= -loci.COINCIDENCE_TOLERANCE) & self.converged

    def close(self, margin: Array, least: float, message: Callable[[], str]) -> None:
        """Record a group's relative margin (``least`` its smallest, NaN where one is), and its
        message where it newly fails to close (no sample fails where ``least`` does not)."""
        if not least >= -loci.COINCIDENCE_TOLERANCE:
            fails = margin < -loci.COINCIDENCE_TOLERANCE
            if fails.any() and (fails & self.closed()).any():
                self.failures.append(message())
        self.margin = np.minimum(self.margin, margin)

    def locus(self, spec: LocusSpec) -> loci.Locus:
        if isinstance(spec, CircleSpec):
            return loci.Circle(self.points[spec.center], spec.radius, spec.center, spec.link)
        guide = self.links[spec.guide]
        through = guide.point(np.array(spec.through0))
        direction = rotate(np.array(spec.direction0), guide.theta)
        return loci.Line(through, direction, guide.omega, guide.alpha, spec.guide)

    def computed(self, index: int) -> int:
        """The order step ``index`` computes: velocities too, before the last group whose
        screen needs them."""
        return max(self.order, 1) if index < self.rated_until else self.order

    def drive(self, index: int, step: DriverStep) -> None:
        given = self.inputs[step.driver]
        pivot0 = self.scene.drawn(step.pivot)
        if step.pivot in self.scene.links[self.scene.ground].points:
            anchor = self.points[step.pivot]  # (at rest, as a driver's pivot is)
        else:
            zeros = np.zeros((self.samples, 2), order="F")
            anchor = PointMotion(repeat(pivot0, self.samples), zeros, zeros)
            self.resting_ids.add(id(anchor))
        self.know(
            step.link,
            LinkMotion(
                pivot0,
                anchor,
                given.theta,
                given.omega if self.computed(index) >= 1 else None,
                given.alpha if self.computed(index) >= 2 else None,
            ),
        )

    @cached_property
    def path(self) -> list[PathStep]:
        return path_steps(self.inputs)

    def branch(
        self,
        index: int,
        step: DyadStep | LeverStep,
        point: str,
        drawn: float,
        margin: Array,
        least: float,
        pieces: Callable[[], tuple[loci.Piece, ...]],
    ) -> Array | float:
        """The branch sign per sample: the drawn one, switched after every closest approach
        between samples where the two branches meet within rounding (a change point); one sign
        for every sample where it does not switch. ``least``: the margin's smallest value."""
        sign: Array | float = self.signs.get(index, drawn)
        if not self.continuation:
            return sign
        size = self.scene.size
        switches: list[float] = []
        for k, piece in self.candidates(index, step, margin, least, pieces):
            approach = self.closest_approach(index, point, k, piece)
            if approach is None:
                continue
            self.approaches.append(approach)
            if abs(approach.margin) <= loci.COINCIDENCE_TOLERANCE * size:
                if not switches:  # (one sign per sample from here on, a copy)
                    sign = np.full(self.samples, sign)
                switches.append(approach.at)
                assert isinstance(sign, np.ndarray)
                sign[math.floor(approach.at) + 1 :] *= -1.0
        at_anchor = sign if isinstance(sign, float) else sign[self.anchor]
        if at_anchor != drawn:  # the drawn branch holds at the anchor sample
            sign = -sign
        self.flips[index] = (float(sign if isinstance(sign, float) else sign[0]), switches)
        self.sign_of[index] = sign
        return sign

    def candidates(
        self,
        index: int,
        step: DyadStep | LeverStep,
        margin: Array,
        least: float,
        pieces: Callable[[], tuple[loci.Piece, ...]],
    ) -> list[tuple[int, int]]:
        """The intervals and pieces where group ``index``'s margin (``least`` its smallest value)
        may dip below the warning threshold (``screen``); none where it is measured between
        points that turn with drivers and its Lipschitz bound clears the threshold
        (``lipschitz_clear``)."""
        size = self.scene.size
        if not self.path or (
            step.reach is not None and lipschitz_clear(least, step.reach, self.path, size)
        ):
            return []
        found = pieces()  # (their rates computed only here)
        if not found:
            return []
        sensitivities = [self.sensitivities(index, driver, found) for driver, _, _ in self.path]
        values = [values for values, _ in found]
        return screen(margin, values, sensitivities, self.path, size, self.closed())

    def sensitivities(self, index: int, driver: int, pieces: tuple[loci.Piece, ...]) -> list[Array]:
        """dm_j/dtheta of each piece of group ``index`` for one driver, per sample: the pieces'
        rates over the driver's rate where this run's velocities are that driver's alone
        (``rates_alone``), else from a run of the plan up to the group at unit rate of that
        driver, on the branches chosen so far."""
        source = self
        if not rates_alone(self.inputs, self.rates, self.path):
            source = _Assembler(
                self.scene, unit_rate(self.inputs, driver), 1, False, self.sign_of,
                newton_groups=self.newton_groups,
            )  # fmt: skip
            source.run_steps(self.steps[: index + 1])
            pieces = source.last()
        omega = source.inputs[driver].omega
        out = []
        for _, rate in pieces:
            assert rate is not None  # (velocities computed)
            out.append(rate / omega)
        return out

    def closest_approach(self, index: int, point: str, k: int, piece: int) -> Approach | None:
        """The minimum of a piece of group ``index``'s margin between samples k and k + 1
        (``screen``): Brent's method on the root of its rate where the rates at both ends
        bracket one, else bounded Brent minimisation of the piece. None where that finds it no
        lower inside than at both ends (a minimum beyond a first or last sample is not there:
        a revolution's interval before its first sample is searched from its closing sample,
        the same pose), or where another piece is lower there (the margin, the smaller of them,
        has no minimum there)."""

        def evaluate(x: float, order: int = 0) -> tuple[float, float, float]:
            """(the piece, its rate (0.0 at ``order`` 0: positions only), the margin: the
            smallest piece) at u = k + x."""
            inputs = interpolated_inputs(self.inputs, k, x)
            probe = _Assembler(self.scene, inputs, order, False, branches_at(self.flips, k + x))
            probe.run_steps(self.steps[: index + 1])
            last = probe.last()
            values, rate = last[piece]
            margin = min(float(other[0]) for other, _ in last)
            return float(values[0]), 0.0 if rate is None else float(rate[0]), margin

        start, rate_low, _ = evaluate(0.0, 1)
        end, rate_high, _ = evaluate(1.0, 1)
        if rate_low < 0.0 <= rate_high:
            x = brentq(lambda x: evaluate(x, 1)[1], 0.0, 1.0, xtol=1e-15, rtol=4.0 * EPS)
        else:
            found = minimize_scalar(
                lambda x: evaluate(x)[0], bounds=(0.0, 1.0), method="bounded",
                options={"xatol": 1e-12},
            )  # fmt: skip
            if found.fun < min(start, end):
                x = float(found.x)
            else:
                at_end = self.stationary_end(k, (start, end), (rate_low, rate_high))
                if at_end is None:
                    return None
                x = at_end
        value, _, margin = evaluate(x)
        return None if value > margin else Approach(point, k + x, margin)

    def stationary_end(
        self, k: int, values: tuple[float, float], rates: tuple[float, float]
    ) -> float | None:
        """x = 0 or 1 where a piece is least between samples k and k + 1 at the run's first or
        last sample and stationary there (its rate zero within ``STATIONARY`` of the larger of
        its two rates): its minimum is on that sample, inside the run (a four-bar drawn, or a
        time sweep started, at its closest approach: the rates at the two copies of that pose in
        a revolution are 0 and -2e-16, so neither interval beside it turns). None otherwise: a
        minimum beyond the first or last sample is not in the run; and a meeting there needs no
        switch (the drawn branch holds at the drawn pose)."""
        (start, end), scale = values, STATIONARY * max(map(abs, rates))
        meets = loci.COINCIDENCE_TOLERANCE * self.scene.size
        if k == 0 and start <= end and abs(rates[0]) <= scale and start > meets:
            return 0.0
        if k + 2 == self.samples and end < start and abs(rates[1]) <= scale and end > meets:
            return 1.0
        return None

    def group(self, index: int, step: DyadStep | LeverStep) -> None:
        """A closed-form group, asked through its type (``groups.group_of``): its margin, then
        its solution on the branch chosen for it."""
        closure = groups.group_of(step).close(step, self)
        size = self.scene.size
        least = float(closure.margin.min())  # (one reduction: the failures and the screen's)
        self.close(closure.margin / size, least / size, closure.describe)
        self.last = closure.pieces
        if closure.two_branch:
            self.group_margins[closure.label] = closure.margin
        sign = self.branch(
            index, step, closure.label, step.sign, closure.margin, least, closure.pieces
        )
        placed = closure.place(sign, self.computed(index))
        self.gradient_sine = np.minimum(self.gradient_sine, placed.gradient_sine)
        self.points.update(placed.points)
        self.relative.update(placed.relative)
        for link, motion in placed.links.items():
            self.know(link, motion)

    def drawn(self, point: str) -> Array:
        return self.scene.drawn(point)

    def run_steps(self, steps: tuple[PlanStep, ...]) -> None:
        self.steps = steps
        fixed, ground = at_rest(self.scene, self.samples)
        self.points.update(fixed)
        for motion in fixed.values():
            self.resting_ids.add(id(motion))
        self.links[self.scene.ground] = ground
        for index, step in enumerate(steps):
            if isinstance(step, DriverStep):
                self.drive(index, step)
            elif isinstance(step, DyadStep | LeverStep):
                self.group(index, step)
            elif isinstance(step, TwoPointStep):
                self.two_point(step)
            elif isinstance(step, GuidedStep):
                guide = self.links[step.guide]
                self.know(
                    step.link,
                    LinkMotion(
                        self.scene.drawn(step.point),
                        self.points[step.point],
                        guide.theta,
                        guide.omega,
                        guide.alpha,
                    ),
                )
            else:
                self.newton_group(index, step)

    def run(self, plan: Plan) -> Motion:
        self.steps = plan.steps
        rated = self.rated(plan)
        if self.continuation and self.order == 0 and len(self.path) == 1 and rated:
            # The screens of groups measured from moving points need the pieces' rates: this run
            # computes velocities at unit rate of the moving driver (``sensitivities``), up to the
            # last such group.
            self.inputs, self.rates = unit_rate(self.inputs, self.path[0][0]), 1
            self.rated_until = rated[-1]
        self.run_steps(plan.steps)
        links, points = self.links, self.points
        if self.rates > self.order:
            links, points = self.positions_only()
        return Motion(
            links,
            points,
            self.per_sample(self.margin),
            self.converged,
            self.per_sample(self.gradient_sine),
            self.failures,
            self.reports,
            self.approaches,
            self.scene.size,
            self.group_margins,
            self.flips,
        )

    def per_sample(self, value: Array | float) -> Array:
        """``value`` at every sample (1.0: no group has lowered it)."""
        return value if isinstance(value, np.ndarray) else np.full(self.samples, value)

    @staticmethod
    def rated(plan: Plan) -> list[int]:
        """The two-branch groups of the plan measured from points that do not turn with drivers
        alone (their ``reach`` is None): their screens need a velocity analysis."""
        steps = cast("tuple[DyadStep | LeverStep, ...]", plan.steps)  # (at ``two_branch``)
        return [i for i in plan.two_branch if steps[i].reach is None]

    def positions_only(self) -> tuple[dict[str, LinkMotion], dict[str, PointMotion]]:
        """The links and points as a run at order 0 gives them, from one that computed
        velocities for the screen: every rate dropped but those at rest by construction (the
        ground's, its points', a driver's pivot's, and a link's guided by the ground)."""
        ground = self.links[self.scene.ground]

        def still(motion: PointMotion) -> PointMotion:
            return motion if id(motion) in self.resting_ids else PointMotion(motion.p)

        links = {
            name: link
            if link is ground
            else LinkMotion(
                link.anchor0,
                still(link.anchor),
                link.theta,
                *((link.omega, link.alpha) if link.omega is ground.omega else (None, None)),
            )
            for name, link in self.links.items()
        }
        return links, {name: still(motion) for name, motion in self.points.items()}

    def newton_group(self, index: int, step: NewtonStep) -> None:
        solved, report = solve_group(
            self.scene,
            step.links,
            self.links,
            [given.theta for given in self.inputs],
            self.computed(index),
            self.newton_groups or Continuation(self.scene),
        )
        self.reports.append(report)
        if np.any(~report.converged & self.closed()):
            self.failures.append(report.message)
        self.converged = self.converged & report.converged
        for link, motion in solved.items():
            self.know(link, motion)


def at_rest(scene: LinkageScene, samples: int) -> tuple[dict[str, PointMotion], LinkMotion]:
    """The ground's points and the ground over ``samples`` samples: at rest in the drawn pose,
    no rotation to apply, their rates zeros. Made once per scene and sample count (the last
    count asked, ``LinkageScene.latest``) with their arrays read-only: every run at that count
    shares them, as every caller shares ``LinkageScene.drawn``'s."""
    return scene.latest("at_rest", samples, lambda: _at_rest(scene, samples))


def _at_rest(scene: LinkageScene, samples: int) -> tuple[dict[str, PointMotion], LinkMotion]:
    ground = scene.links[scene.ground]
    still, zeros = np.zeros((samples, 2), order="F"), np.zeros(samples)  # (``rigid.points``)
    fixed = {p: PointMotion(repeat(scene.drawn(p), samples), still, still) for p in ground.points}
    for array in (still, zeros, *(motion.p for motion in fixed.values())):
        array.flags.writeable = False
    anchor = ground.points[0]
    return fixed, LinkMotion(scene.drawn(anchor), fixed[anchor], zeros, zeros, zeros)


def follows_path(plan: Plan) -> bool:
    """Whether the continuation follows the path (then on a ``dense_grid`` where the drivers
    step too far): only a group with two branches, or a Newton group, depends on it."""
    return bool(plan.two_branch) or not plan.closed_form


def assemble(
    scene: LinkageScene,
    plan: Plan,
    inputs: Sequence[DriverInput],
    order: int,
    continuation: bool = False,
    anchor: int = 0,
    newton_groups: Continuation | None = None,
    signs: Mapping[int, float] | None = None,
) -> Motion:
    """Positions (order 0), velocities (1) and accelerations (2) of every link and point; with
    continuation the drawn branch holds at sample ``anchor``; ``newton_groups`` carries a Newton
    group's tolerance and the branches already followed; ``signs`` forces the branch of the
    two-branch steps it names (``branches_at``: an instant on a motion followed before). With
    continuation, where a driver steps more than MAX_DRIVER_STEP between two samples and the
    plan has a two-branch or a Newton group, the linkage is followed on a grid that does not
    (``dense_grid``) and returned at the samples."""
    path = path_steps(inputs) if continuation and follows_path(plan) else None
    grid = dense_grid(inputs) if path is not None and coarse(path) else None
    if grid is None:
        assembler = _Assembler(
            scene, inputs, order, continuation, signs, anchor=anchor, newton_groups=newton_groups
        )
        if path is not None:
            assembler.path = path  # (found once)
        return assembler.run(plan)
    dense = _Assembler(
        scene, grid.inputs, order, continuation, signs, int(grid.index[anchor]), newton_groups
    )
    return grid.restrict(dense.run(plan))


def require_feasible(motion: Motion, where: str) -> None:
    """Raise ``NotAssemblable`` with the numbers of the first group that did not close (at a
    sample, or in a window between two samples)."""
    if not motion.feasible.all():
        raise NotAssemblable(f"the linkage cannot be closed {where}: " + "; ".join(motion.failures))
    if motion.windows:
        window = motion.windows[0]
        raise NotAssemblable(
            f"the linkage cannot be closed {where}: the loci of {window.point} fail to meet by "
            f"{-window.margin:.3g} m between samples {math.floor(window.at)} and "
            f"{math.floor(window.at) + 1}"
        )

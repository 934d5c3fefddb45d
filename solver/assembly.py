"""Assemble a linkage at given driver inputs: positions, velocities, accelerations on request.

Runs a ``Plan`` (see ``topology``) vectorised over samples. The branch of each two-branch group is
the drawn one (the same orientation of the dyad's triangle, as the spec asks for a single pose).
With ``continuation=True`` (a sweep) it switches only where the group's two branches meet between
two samples within rounding: the closest approach of the branches over the continuous driver
path is found by Brent's method wherever the samples say it could come near, so a parallelogram
stays a parallelogram through its change points and a linkage 1e-12 off a change point keeps its
assembly, at any sample count.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, field

import numpy as np
from scipy.optimize import brentq, minimize_scalar

from solver import dyads, newton
from solver.continuation import Continuation, solve_group
from solver.errors import NotAssemblable
from solver.rigid import (
    Array,
    LinkMotion,
    PointMotion,
    fixed_link,
    link_from_two_points,
    repeat,
    rotate,
)
from solver.scene import LinkageScene
from solver.topology import (
    CircleSpec,
    DriverStep,
    DyadStep,
    GuidedStep,
    LeverStep,
    LocusSpec,
    NewtonStep,
    Plan,
    Step,
    TwoPointStep,
)

EPS = float(np.finfo(float).eps)

# Where the branches come closer than this fraction of the linkage's size without meeting, a
# sweep reports the closest approach (a real mechanism with clearance could switch there).
WARNING_MARGIN = 1e-3


@dataclass(frozen=True)
class DriverInput:
    """Rotation of a driven link from its drawn pose, and its rates, per sample (N,)."""

    theta: Array
    omega: Array
    alpha: Array


@dataclass(frozen=True)
class Approach:
    """The closest approach of a group's two branches between samples: at fractional sample
    ``at`` (k + x: x of the way from sample k to k + 1), the length margin ``margin`` (metres;
    within the coincidence tolerance the branches meet, below it the group cannot close)."""

    point: str
    at: float
    margin: float


@dataclass(frozen=True)
class Motion:
    """The solved state of a linkage over N samples.

    ``gradient_sine`` is the smallest sine of the angle between the two constraint gradients of
    any group (0 at a dead centre); ``margin`` the smallest length margin m / size of any
    two-branch group (negative where a group does not close); ``converged`` false where a Newton
    group's Newton-Raphson did not converge; ``group_margins`` each two-branch group's m (metres),
    by the point (or slot) it locates.
    With continuation, ``approaches`` lists every close approach found between samples: branch
    switches (the branches meet), near misses, and windows where the linkage cannot close.
    """

    links: dict[str, LinkMotion]
    points: dict[str, PointMotion]
    margin: Array
    converged: Array
    gradient_sine: Array
    failures: list[str] = field(default_factory=list)
    newton: list[newton.NewtonReport] = field(default_factory=list)
    approaches: list[Approach] = field(default_factory=list)
    size: float = 1.0
    group_margins: dict[str, Array] = field(default_factory=dict)
    # With continuation, per two-branch step (its index in the plan): its branch sign at the first
    # sample and the fractional samples where it switches (``branches_at``).
    flips: dict[int, tuple[float, list[float]]] = field(default_factory=dict)

    @property
    def feasible(self) -> Array:
        """Samples where every group closed (to the coincidence tolerance) and every Newton group
        converged."""
        return (self.margin >= -dyads.COINCIDENCE_TOLERANCE) & self.converged

    def cut(self, part: slice) -> Motion:
        """The same motion at the samples ``part`` only (approaches kept as found)."""

        def take(a: Array | None) -> Array | None:
            return None if a is None else a[part]

        def point(m: PointMotion) -> PointMotion:
            return PointMotion(m.p[part], take(m.v), take(m.a))

        links = {
            k: LinkMotion(m.anchor0, point(m.anchor), m.theta[part], take(m.omega), take(m.alpha))
            for k, m in self.links.items()
        }
        return Motion(
            links,
            {k: point(m) for k, m in self.points.items()},
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
        return [a for a in self.approaches if a.margin < -dyads.COINCIDENCE_TOLERANCE * self.size]

    @property
    def near_misses(self) -> list[Approach]:
        """Closest approaches between samples where the branches come close without meeting."""
        return [a for a in self.approaches if a.margin > dyads.COINCIDENCE_TOLERANCE * self.size]


def candidate_minima(margin: Array, size: float) -> Array:
    """Samples k at a local minimum of the margin whose neighbourhood may dip below the warning
    threshold: m_k - max(m_k-1 - m_k, m_k+1 - m_k) < WARNING_MARGIN size (a bound that holds for a
    smooth minimum within half a step of k and for a V-shaped one, |d| at coincident centres).
    The first and the last sample count with their one neighbour: a minimum between the first two
    samples, nearer the first, has no sample before it (a revolution's closing sample is the
    first's pose, but the interval before it is searched from the last sample)."""
    if margin.size < 2:
        return np.array([], dtype=int)
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
    found &= margin >= -dyads.COINCIDENCE_TOLERANCE * size  # an infeasible sample is reported so
    return np.flatnonzero(found)


def branches_at(flips: Mapping[int, tuple[float, list[float]]], u: float) -> dict[int, float]:
    """The branch sign of each two-branch step at fractional sample u of a motion assembled with
    continuation (``Motion.flips``): its sign at the first sample, times -1 for every switch
    before u."""
    return {
        step: first * (-1.0) ** sum(1 for at in switches if at < u)
        for step, (first, switches) in flips.items()
    }


def interpolated_inputs(inputs: Sequence[DriverInput], k: int, x: float) -> list[DriverInput]:
    """The drivers at fractional sample u = k + x, -1 <= x <= 1 (x <= 0 at the last sample;
    thetas linear between samples), with rates d theta / du: the path the continuation follows
    between two samples."""
    out = []
    for given in inputs:
        theta = given.theta
        backward = x < 0.0 or k + 1 == theta.size
        step = float(theta[k] - theta[k - 1] if backward else theta[k + 1] - theta[k])
        out.append(DriverInput(np.array([theta[k] + x * step]), np.array([step]), np.zeros(1)))
    return out


class _Assembler:
    """Runs one plan over one set of inputs (state lives only for the duration of ``run``).

    ``signs`` forces the branch of given steps (used to evaluate a group between two samples with
    the branches its inputs were given there); with continuation, each group is on its drawn
    branch at sample ``anchor``.
    """

    def __init__(
        self,
        scene: LinkageScene,
        inputs: Sequence[DriverInput],
        order: int,
        continuation: bool,
        signs: Mapping[int, float] | None = None,
        anchor: int = 0,
        newton_groups: Continuation | None = None,
    ) -> None:
        self.scene = scene
        self.newton_groups = newton_groups
        self.inputs = inputs
        self.order = order
        self.continuation = continuation
        self.signs = signs or {}
        self.samples = len(inputs[0].theta) if inputs else 1
        # Samples at the drawn pose (every driver unturned): the drawn coordinates are the answer
        # there (they close by construction; a re-solved point near a tangency would not be).
        self.at_drawn = np.ones(self.samples, dtype=bool)
        for given in inputs:
            self.at_drawn &= given.theta == 0.0
        self.links: dict[str, LinkMotion] = {}
        self.points: dict[str, PointMotion] = {}
        self.margin = np.ones(self.samples)
        self.converged = np.ones(self.samples, dtype=bool)
        self.gradient_sine = np.ones(self.samples)
        self.failures: list[str] = []
        self.reports: list[newton.NewtonReport] = []
        self.steps: tuple[Step, ...] = ()
        self.anchor = anchor
        self.flips: dict[int, tuple[float, list[float]]] = {}  # sign at sample 0, switches
        self.approaches: list[Approach] = []
        self.last: tuple[Array, Array | None] = (np.ones(1), None)  # last group's m, dm/du
        self.group_margins: dict[str, Array] = {}

    def know(self, link: str, motion: LinkMotion) -> None:
        self.links[link] = motion
        for p in self.scene.links[link].points:
            if p not in self.points:
                self.points[p] = motion.point(self.scene.drawn(p))

    def closed(self) -> Array:
        """Samples where every group so far closed (and every Newton group converged)."""
        return (self.margin >= -dyads.COINCIDENCE_TOLERANCE) & self.converged

    def close(self, margin: Array, message: Callable[[], str]) -> None:
        """Record a group's relative margin, and its message where it newly fails to close."""
        fails = margin < -dyads.COINCIDENCE_TOLERANCE
        if fails.any() and np.any(fails & self.closed()):
            self.failures.append(message())
        self.margin = np.minimum(self.margin, margin)

    def locus(self, spec: LocusSpec) -> dyads.Locus:
        if isinstance(spec, CircleSpec):
            return dyads.Circle(self.points[spec.center], spec.radius, spec.center, spec.link)
        guide = self.links[spec.guide]
        through = guide.point(np.array(spec.through0))
        direction = rotate(np.array(spec.direction0), guide.theta)
        return dyads.Line(through, direction, guide.omega, guide.alpha, spec.guide)

    def drive(self, step: DriverStep) -> None:
        given = self.inputs[step.driver]
        pivot0 = self.scene.drawn(step.pivot)
        zeros = np.zeros((self.samples, 2))
        anchor = PointMotion(repeat(pivot0, self.samples), zeros, zeros)
        self.know(
            step.link,
            LinkMotion(
                pivot0,
                anchor,
                given.theta,
                given.omega if self.order >= 1 else None,
                given.alpha if self.order >= 2 else None,
            ),
        )

    def branch(self, index: int, point: str, drawn: float, margin: Array) -> Array:
        """The branch sign per sample: the drawn one, switched after every closest approach
        between samples where the two branches meet within rounding (a change point)."""
        sign = np.full(self.samples, self.signs.get(index, drawn))
        if not self.continuation:
            return sign
        size = self.scene.size
        switches: list[float] = []
        for k in candidate_minima(margin, size):
            approach = self.closest_approach(index, point, int(k))
            if approach is None:
                continue
            self.approaches.append(approach)
            if abs(approach.margin) <= dyads.COINCIDENCE_TOLERANCE * size:
                switches.append(approach.at)
                sign[math.floor(approach.at) + 1 :] *= -1.0
        if sign[self.anchor] != drawn:  # the drawn branch holds at the anchor sample
            sign *= -1.0
        self.flips[index] = (float(sign[0]), switches)
        return sign

    def closest_approach(self, index: int, point: str, k: int) -> Approach | None:
        """The minimum of group ``index``'s margin between samples k - 1 and k + 1 (k alone on
        the side of a first or last sample): Brent's method on the root of dm/du (or on m itself
        where dm/du does not change sign there). None where the margin falls on beyond a first
        or last sample: no minimum lies inside (a revolution's interval before its first sample
        is searched from its closing sample, the same pose)."""

        def evaluate(x: float) -> tuple[float, float]:
            inputs = interpolated_inputs(self.inputs, k, x)
            probe = _Assembler(self.scene, inputs, 1, False, branches_at(self.flips, k + x))
            probe.run_steps(self.steps[: index + 1])
            m, rate = probe.last
            return float(m[0]), 0.0 if rate is None else float(rate[0])

        low = -1.0 if k > 0 else 0.0
        high = 1.0 if k + 1 < self.samples else 0.0
        rate_low, rate_high = evaluate(low)[1], evaluate(high)[1]
        if (k == 0 and rate_low > 0.0) or (k + 1 == self.samples and rate_high < 0.0):
            return None
        if rate_low < 0.0 < rate_high:
            x = brentq(lambda x: evaluate(x)[1], low, high, xtol=1e-15, rtol=4.0 * EPS)
        else:
            found = minimize_scalar(
                lambda x: evaluate(x)[0], bounds=(low, high), method="bounded",
                options={"xatol": 1e-12},
            )  # fmt: skip
            x = float(found.x)
        return Approach(point, k + x, evaluate(x)[0])

    def dyad(self, index: int, step: DyadStep) -> None:
        first, second = (self.locus(spec) for spec in step.loci)
        cut = dyads.intersect(first, second, step.point)
        self.close(cut.margin / self.scene.size, cut.describe)
        self.last = (cut.margin, cut.margin_rate)
        # Two branches wherever a circle is involved (a pin in two slots has one).
        if isinstance(first, dyads.Circle) or isinstance(second, dyads.Circle):
            self.group_margins[step.point] = cut.margin
        X = cut.point(self.branch(index, step.point, step.sign, cut.margin))
        X[self.at_drawn] = self.scene.drawn(step.point)
        self.points[step.point], sine = dyads.point_motion(first, second, X, self.order)
        self.gradient_sine = np.minimum(self.gradient_sine, sine)

    def lever(self, index: int, step: LeverStep) -> None:
        pivot, pin = self.points[step.pivot], self.points[step.pin]
        margin, rate = dyads.lever_margin(pivot, pin, step.offset)
        self.close(
            margin / self.scene.size,
            lambda: (
                f"|{step.pivot}{step.pin}| is shorter than the offset "
                f"{abs(step.offset):.6g} m of the slot of '{step.link}' from its pivot {step.pivot}"
            ),
        )
        self.last = (margin, rate)
        label = f"the slot of '{step.link}'"
        self.group_margins[label] = margin
        sign = self.branch(index, label, step.sign, margin)
        drawn = math.atan2(step.direction0[1], step.direction0[0])
        solution = dyads.slotted_lever(
            pivot, pin, step.offset, sign, self.order, (self.at_drawn, drawn)
        )
        self.gradient_sine = np.minimum(self.gradient_sine, solution.gradient_sine)
        theta = solution.beta - drawn
        self.know(
            step.link,
            LinkMotion(self.scene.drawn(step.pivot), pivot, theta, solution.omega, solution.alpha),
        )

    def run_steps(self, steps: tuple[Step, ...]) -> None:
        self.steps = steps
        ground = self.scene.links[self.scene.ground]
        self.links[ground.name] = fixed_link(self.scene.drawn(ground.points[0]), self.samples)
        at_rest = np.zeros((self.samples, 2))
        for p in ground.points:  # fixed points: no rotation to apply, no rates to compute
            self.points[p] = PointMotion(
                repeat(self.scene.drawn(p), self.samples), at_rest, at_rest
            )
        for index, step in enumerate(steps):
            if isinstance(step, DriverStep):
                self.drive(step)
            elif isinstance(step, DyadStep):
                self.dyad(index, step)
            elif isinstance(step, LeverStep):
                self.lever(index, step)
            elif isinstance(step, TwoPointStep):
                self.know(
                    step.link,
                    link_from_two_points(
                        self.scene.drawn(step.first),
                        self.scene.drawn(step.second),
                        self.points[step.first],
                        self.points[step.second],
                    ),
                )
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
                self.newton_group(step)

    def run(self, plan: Plan) -> Motion:
        self.run_steps(plan.steps)
        return Motion(
            self.links,
            self.points,
            self.margin,
            self.converged,
            self.gradient_sine,
            self.failures,
            self.reports,
            self.approaches,
            self.scene.size,
            self.group_margins,
            self.flips,
        )

    def newton_group(self, step: NewtonStep) -> None:
        solved, report = solve_group(
            self.scene,
            step.links,
            self.links,
            [given.theta for given in self.inputs],
            self.order,
            self.newton_groups or Continuation(self.scene),
        )
        self.reports.append(report)
        if np.any(~report.converged & self.closed()):
            self.failures.append(report.message)
        self.converged = self.converged & report.converged
        for link, motion in solved.items():
            self.know(link, motion)


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
    two-branch steps it names (``branches_at``: an instant on a motion followed before)."""
    return _Assembler(
        scene, inputs, order, continuation, signs, anchor=anchor, newton_groups=newton_groups
    ).run(plan)


def require_feasible(motion: Motion, where: str) -> None:
    """Raise ``NotAssemblable`` with the numbers of the first group that did not close (at a
    sample, or in a window between two samples)."""
    if not np.all(motion.feasible):
        raise NotAssemblable(f"the linkage cannot be closed {where}: " + "; ".join(motion.failures))
    if motion.windows:
        window = motion.windows[0]
        raise NotAssemblable(
            f"the linkage cannot be closed {where}: the loci of {window.point} fail to meet by "
            f"{-window.margin:.3g} m between samples {math.floor(window.at)} and "
            f"{math.floor(window.at) + 1}"
        )

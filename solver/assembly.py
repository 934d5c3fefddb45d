"""Assemble a linkage at given driver inputs: positions, velocities, accelerations on request.

Runs a ``Plan`` (see ``topology``) vectorised over samples. The branch of each two-branch group is
either the drawn one (``continuation=False``: the same orientation of the dyad's triangle, as the
spec asks for a single pose) or followed from sample to sample with a predictor
(``continuation=True``: a sweep keeps a parallelogram a parallelogram through its change points).
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass, field

import numpy as np

from solver import dyads, newton
from solver.continuation import Continuation, solve_group
from solver.errors import NotAssemblable
from solver.rigid import (
    Array,
    LinkMotion,
    PointMotion,
    dot,
    fixed_link,
    link_from_two_points,
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
    TwoPointStep,
)

# A branch switch must bring the next sample at least this much closer to the predicted position.
SWITCH_MARGIN = 0.5
MAX_BRANCH_SWITCHES = 64


@dataclass(frozen=True)
class DriverInput:
    """Rotation of a driven link from its drawn pose, and its rates, per sample (N,)."""

    theta: Array
    omega: Array
    alpha: Array


@dataclass(frozen=True)
class Motion:
    """The solved state of a linkage over N samples.

    ``conditioning`` is the smallest sine of the angle between the two constraint gradients of any
    group (0 at a dead centre); ``margin`` the smallest h^2 / r^2 of any two-branch group
    (negative where a group does not close; -1 where Newton-Raphson did not converge).
    """

    links: dict[str, LinkMotion]
    points: dict[str, PointMotion]
    margin: Array
    conditioning: Array
    failures: list[str] = field(default_factory=list)
    newton: list[newton.NewtonReport] = field(default_factory=list)

    @property
    def feasible(self) -> Array:
        """Samples where every group closed (to the tangency tolerance)."""
        return self.margin >= -dyads.TANGENCY_TOLERANCE


def continuous_sign(candidate: Callable[[Array], Array], drawn: float, samples: int) -> Array:
    """Per-sample branch signs that keep the motion smooth, starting on the drawn branch.

    With a constant sign the path P follows one side of the dyad. Where the other side's point is
    clearly closer to the linear prediction 2 P[k-1] - P[k-2] (which happens only where the two
    branches meet, at a change point), the sign flips from that sample on.
    """
    sign = np.full(samples, drawn)
    if samples < 3:
        return sign
    plus, minus = candidate(np.ones(samples)), candidate(-np.ones(samples))
    # A switch needs the branches closer than a few steps: 2 h < 3 (|dP_k| + |dP_k-1|).
    separation = np.sqrt(dot(plus - minus, plus - minus))
    step = np.sqrt(
        np.maximum(
            dot(np.diff(plus, axis=0), np.diff(plus, axis=0)),
            dot(np.diff(minus, axis=0), np.diff(minus, axis=0)),
        )
    )
    if separation.min() > 6.0 * step.max():
        return sign
    for _ in range(MAX_BRANCH_SWITCHES):
        keep = np.where((sign > 0)[:, None], plus, minus)
        other = np.where((sign > 0)[:, None], minus, plus)
        predicted = 2.0 * keep[1:-1] - keep[:-2]
        err_keep = np.hypot(*(keep[2:] - predicted).T)
        err_other = np.hypot(*(other[2:] - predicted).T)
        switch = np.flatnonzero(err_other < SWITCH_MARGIN * err_keep)
        if switch.size == 0:
            break
        sign[switch[0] + 2 :] *= -1.0
    return sign


class _Assembler:
    """Runs one plan over one set of inputs (state lives only for the duration of ``run``)."""

    def __init__(
        self,
        scene: LinkageScene,
        inputs: Sequence[DriverInput],
        order: int,
        continuation: bool,
        newton_groups: Continuation | None = None,
    ) -> None:
        self.scene = scene
        self.newton_groups = newton_groups
        self.inputs = inputs
        self.order = order
        self.continuation = continuation
        self.samples = len(inputs[0].theta) if inputs else 1
        self.links: dict[str, LinkMotion] = {}
        self.points: dict[str, PointMotion] = {}
        self.margin = np.ones(self.samples)
        self.conditioning = np.ones(self.samples)
        self.failures: list[str] = []
        self.reports: list[newton.NewtonReport] = []

    def know(self, link: str, motion: LinkMotion) -> None:
        self.links[link] = motion
        for p in self.scene.links[link].points:
            if p not in self.points:
                self.points[p] = motion.point(self.scene.drawn(p))

    def close(self, gap2: Array, message: str) -> None:
        """Record a group's margin h^2 / r^2, and its message where it newly fails to close."""
        failing = gap2 < -dyads.TANGENCY_TOLERANCE
        if np.any(failing & (self.margin >= -dyads.TANGENCY_TOLERANCE)):
            self.failures.append(message)
        self.margin = np.minimum(self.margin, gap2)

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
        anchor = PointMotion(np.broadcast_to(pivot0, (self.samples, 2)).copy(), zeros, zeros)
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

    def dyad(self, step: DyadStep) -> None:
        first, second = (self.locus(spec) for spec in step.loci)
        cut = dyads.intersect(first, second, step.point)
        self.close(cut.gap2, cut.message)
        sign = (
            continuous_sign(cut.point, step.sign, self.samples)
            if self.continuation
            else np.full(self.samples, step.sign)
        )
        X = cut.point(sign)
        self.conditioning = np.minimum(
            self.conditioning, dyads.relative_determinant(first, second, X)
        )
        self.points[step.point] = dyads.point_motion(first, second, X, self.order)

    def lever(self, step: LeverStep) -> None:
        pivot, pin = self.points[step.pivot], self.points[step.pin]

        def direction(sign: Array) -> Array:
            beta = dyads.slotted_lever(pivot, pin, step.offset, sign, 0).beta
            return np.stack((np.cos(beta), np.sin(beta)), axis=-1)

        sign = (
            continuous_sign(direction, step.sign, self.samples)
            if self.continuation
            else np.full(self.samples, step.sign)
        )
        solution = dyads.slotted_lever(pivot, pin, step.offset, sign, self.order)
        self.close(
            solution.gap2,
            f"|{step.pivot}{step.pin}| is shorter than the offset {abs(step.offset):.6g} m "
            f"of the slot of '{step.link}' from its pivot {step.pivot}",
        )
        self.conditioning = np.minimum(self.conditioning, solution.conditioning)
        theta = solution.beta - np.arctan2(step.direction0[1], step.direction0[0])
        self.know(
            step.link,
            LinkMotion(self.scene.drawn(step.pivot), pivot, theta, solution.omega, solution.alpha),
        )

    def run(self, plan: Plan) -> Motion:
        ground = self.scene.links[self.scene.ground]
        self.links[ground.name] = fixed_link(self.scene.drawn(ground.points[0]), self.samples)
        at_rest = np.zeros((self.samples, 2))
        for p in ground.points:  # fixed points: no rotation to apply, no rates to compute
            drawn = np.broadcast_to(self.scene.drawn(p), (self.samples, 2))
            self.points[p] = PointMotion(drawn, at_rest, at_rest)
        for step in plan.steps:
            if isinstance(step, DriverStep):
                self.drive(step)
            elif isinstance(step, DyadStep):
                self.dyad(step)
            elif isinstance(step, LeverStep):
                self.lever(step)
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
        return Motion(
            self.links, self.points, self.margin, self.conditioning, self.failures, self.reports
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
        self.close(np.where(report.converged, 0.0, -1.0), report.message)
        for link, motion in solved.items():
            self.know(link, motion)


def assemble(
    scene: LinkageScene,
    plan: Plan,
    inputs: Sequence[DriverInput],
    order: int,
    continuation: bool = False,
    newton_groups: Continuation | None = None,
) -> Motion:
    """Positions (order 0), velocities (1) and accelerations (2) of every link and point;
    ``newton_groups`` carries a Newton group's tolerance and the branches already followed."""
    return _Assembler(scene, inputs, order, continuation, newton_groups).run(plan)


def require_feasible(motion: Motion, where: str) -> None:
    """Raise ``NotAssemblable`` with the numbers of the first group that did not close."""
    if not np.all(motion.feasible):
        raise NotAssemblable(f"the linkage cannot be closed {where}: " + "; ".join(motion.failures))

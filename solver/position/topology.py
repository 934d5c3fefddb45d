"""Decomposition of a linkage into its driver(s) and closed-form groups, in solving order.

Starting from the ground and the driven links, a link becomes known when two of its points are
known (or one point and its angle, through a prismatic joint), and a point becomes known when it
lies on two loci built from known links (a dyad). A lever whose slot must pass through a known
pin is solved for its angle. Whatever cannot be reached this way is one Newton-Raphson group.
The branch of every two-branch group is read off the drawn pose, and so is the reach of the points
its length margin is measured between, where drivers alone turn them (``Reach``).
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import cached_property
from itertools import combinations
from typing import Any, cast

import numpy as np

from solver.kinematics.rigid import PointMotion, cross, dot
from solver.model.scene import Joint, LinkageScene
from solver.position import groups
from solver.position.groups import loci
from solver.position.groups.base import Turning, Where


@dataclass(frozen=True)
class CircleSpec:
    """The point is on ``link``, which carries the known point ``center``."""

    link: str
    center: str
    radius: float

    @property
    def carrier(self) -> str | None:
        """The link that carries the located point (``link``)."""
        return self.link

    def gradient(self, X: Any, where: Where, turning: Turning) -> Any:
        """g = X - C, the gradient of |X - C|^2 / 2 = r^2 / 2, in the arithmetic of ``where``."""
        return X - where(self.link, self.center)


@dataclass(frozen=True)
class LineSpec:
    """The point slides on the line through its drawn position ``through0``, fixed in ``guide``."""

    guide: str
    through0: tuple[float, float]
    direction0: tuple[float, float]

    @property
    def carrier(self) -> str | None:
        """None: the guide does not carry the located point."""
        return None

    def gradient(self, X: Any, where: Where, turning: Turning) -> Any:
        """g = n = k x w, the slot's normal, w = R(theta_guide) w0 with (cos, sin) of the
        guide's turn from ``turning``, in its arithmetic."""
        cos, sin = turning(self.guide)
        (x0, y0) = self.direction0
        w = (cos * x0 - sin * y0, sin * x0 + cos * y0)
        return (-w[1], w[0])


LocusSpec = CircleSpec | LineSpec

# A point fixed, or turned by a driver about its ground pivot: (driver, |P - pivot|), a fixed
# point's radius 0. Along a sweep's path such a point moves at |P - pivot| |d theta / du|.
Reach = tuple[int, float]


@dataclass(frozen=True)
class DriverStep:
    """A driven link turning about its ground pivot."""

    link: str
    pivot: str
    driver: int


@dataclass(frozen=True)
class DyadStep:
    """A joint point located on two loci (RRR, RRP, pin in two slots); ``sign`` = drawn branch;
    ``reach``: that of its circles' centres (a slot in the ground adds none), None where one of
    them moves otherwise (located by a dyad or a Newton group; a slot in a moving link)."""

    point: str
    loci: tuple[LocusSpec, LocusSpec]
    sign: float
    reach: tuple[Reach, ...] | None = None

    @cached_property
    def kind(self) -> str:
        """Its Assur group (``solver.position.groups``): RRR on two circles, RRP on a circle and
        a slot, PRP on two slots."""
        return ("PRP", "RRP", "RRR")[sum(isinstance(spec, CircleSpec) for spec in self.loci)]


@dataclass(frozen=True)
class TwoPointStep:
    """A link known from two of its known points."""

    link: str
    first: str
    second: str


@dataclass(frozen=True)
class GuidedStep:
    """A link with one known point that cannot turn relative to a known link (prismatic)."""

    link: str
    point: str
    guide: str


@dataclass(frozen=True)
class LeverStep:
    """A link turning about a known ``pivot`` whose slot passes through the known ``pin``;
    ``reach``: that of the pivot and the pin, None where one of them moves otherwise."""

    link: str
    pivot: str
    pin: str
    offset: float
    sign: float
    direction0: tuple[float, float]
    reach: tuple[Reach, ...] | None = None

    @property
    def kind(self) -> str:
        """Its Assur group (``solver.position.groups``): RPR, the slotted lever."""
        return "RPR"


@dataclass(frozen=True)
class NewtonStep:
    """Links that form no closed-form group: solved together by Newton-Raphson."""

    links: tuple[str, ...]


PlanStep = DriverStep | DyadStep | TwoPointStep | GuidedStep | LeverStep | NewtonStep


@dataclass(frozen=True)
class Plan:
    """The solving order of a linkage."""

    steps: tuple[PlanStep, ...]

    @cached_property
    def closed_form(self) -> bool:
        return not any(isinstance(step, NewtonStep) for step in self.steps)

    @cached_property
    def two_branch(self) -> tuple[int, ...]:
        """The indices of its two-branch steps: a lever, or a dyad with a circle among its loci
        (a pin in two slots has one solution)."""
        return tuple(
            i
            for i, step in enumerate(self.steps)
            if isinstance(step, LeverStep)
            or (isinstance(step, DyadStep) and any(isinstance(s, CircleSpec) for s in step.loci))
        )


def _locus(spec: LocusSpec, scene: LinkageScene) -> loci.Locus:
    """The locus at the drawn pose (one sample), to read the drawn branch."""
    if isinstance(spec, CircleSpec):
        center = PointMotion(scene.drawn(spec.center)[None])
        return loci.Circle(center, spec.radius, spec.center, spec.link)
    through = PointMotion(np.array(spec.through0)[None])
    return loci.Line(through, np.array(spec.direction0)[None], None, None, spec.guide)


def drawn_branch(scene: LinkageScene, point: str, loci: tuple[LocusSpec, LocusSpec]) -> float:
    """+1 or -1: the side of the intersection's base on which the drawn point lies."""
    cut = groups.intersect(_locus(loci[0], scene), _locus(loci[1], scene), point)
    side = float(dot(scene.drawn(point) - cut.base[0], cut.offset[0]))
    return 1.0 if side >= 0.0 else -1.0


class _Decomposition:
    """Knowledge propagation over the scene's links and points (used once, by ``build_plan``)."""

    def __init__(self, scene: LinkageScene) -> None:
        self.scene = scene
        self.known_links: set[str] = set()
        self.known_points: set[str] = set()
        self.steps: list[PlanStep] = []
        self.reach: dict[str, Reach] = {}  # the points fixed or turned by a driver alone

    def know_link(self, link: str, step: PlanStep) -> None:
        self.steps.append(step)
        self.known_links.add(link)
        self.known_points.update(self.scene.links[link].points)

    def sliding_joints(self) -> list[Joint]:
        return [j for j in self.scene.joints if j.type != "revolute"]

    def try_link(self, link: str) -> bool:
        scene = self.scene
        known = [p for p in scene.links[link].points if p in self.known_points]
        if len(known) >= 2:
            first, second = max(
                combinations(known, 2),
                key=lambda ab: float(np.hypot(*(scene.drawn(ab[0]) - scene.drawn(ab[1])))),
            )
            self.know_link(link, TwoPointStep(link, first, second))
            return True
        if len(known) != 1:
            return False
        for joint in self.sliding_joints():
            if joint.type == "prismatic" and link in joint.links:
                other = joint.links[0] if joint.links[1] == link else joint.links[1]
                if other in self.known_links:
                    self.know_link(link, GuidedStep(link, known[0], other))
                    return True
            if joint.guide == link and joint.point in self.known_points and joint.point != known[0]:
                assert joint.axis is not None
                u0 = np.array(joint.axis)
                r0 = scene.drawn(joint.point) - scene.drawn(known[0])
                sign = 1.0 if float(dot(u0, r0)) >= 0.0 else -1.0
                reach = self.reach_of([known[0], joint.point])
                offset = float(cross(u0, r0))
                step = LeverStep(link, known[0], joint.point, offset, sign, joint.axis, reach)
                self.know_link(link, step)
                return True
        return False

    def loci(self, point: str) -> list[LocusSpec]:
        scene = self.scene
        found: list[LocusSpec] = []
        for link in scene.links_of(point):
            if link in self.known_links:
                continue
            centers = [p for p in scene.links[link].points if p in self.known_points]
            if centers:
                radius = float(np.hypot(*(scene.drawn(point) - scene.drawn(centers[0]))))
                found.append(CircleSpec(link, centers[0], radius))
        for joint in self.sliding_joints():
            if joint.guide not in self.known_links:
                continue
            assert joint.axis is not None
            carried = joint.point == point or (
                joint.type == "prismatic"
                and point in scene.links[joint.follower].points
                and joint.follower not in self.known_links
            )
            if carried:
                found.append(LineSpec(joint.guide, scene.points[point], joint.axis))
        return found

    def try_point(self, point: str) -> bool:
        loci = self.loci(point)
        if len(loci) < 2:
            return False
        # Prefer circles (RRR) over slots, which keeps the best-conditioned classical dyads.
        loci.sort(key=lambda spec: isinstance(spec, LineSpec))
        pair = (loci[0], loci[1])
        ground = self.scene.ground
        if any(isinstance(spec, LineSpec) and spec.guide != ground for spec in pair):
            reach = None
        else:
            reach = self.reach_of([spec.center for spec in pair if isinstance(spec, CircleSpec)])
        step = DyadStep(point, pair, drawn_branch(self.scene, point, pair), reach)
        self.steps.append(step)
        self.known_points.add(point)
        return True

    def reach_of(self, points: list[str]) -> tuple[Reach, ...] | None:
        """The reach of each of ``points``, or None where one of them moves otherwise."""
        if any(p not in self.reach for p in points):
            return None
        return tuple(self.reach[p] for p in points)

    def run(self) -> Plan:
        scene = self.scene
        self.known_links.add(scene.ground)
        self.known_points.update(scene.links[scene.ground].points)
        self.reach = {p: (0, 0.0) for p in scene.links[scene.ground].points}
        for index, driver in enumerate(scene.drivers):
            pivot = scene.drawn(driver.pivot)
            for p in scene.links[driver.link].points:
                self.reach.setdefault(p, (index, float(np.hypot(*(scene.drawn(p) - pivot)))))
            self.know_link(driver.link, DriverStep(driver.link, driver.pivot, index))
        progress = True
        while progress:
            progress = False
            for link in scene.links:
                if link not in self.known_links and self.try_link(link):
                    progress = True
            if progress:
                continue
            for point in scene.points:
                if point not in self.known_points and self.try_point(point):
                    progress = True
                    break
        rest = tuple(link for link in scene.links if link not in self.known_links)
        if rest:
            self.steps.append(NewtonStep(rest))
        return Plan(tuple(self.steps))


def build_plan(scene: LinkageScene) -> Plan:
    """The solving order: drivers, closed-form groups, then a Newton group if needed. Built once
    per scene object and kept on it (``LinkageScene.memo``: a sweep, its probe and /analyze of
    one parsed scene share it; a fifth of a 360-sample sweep's time went into building it again)."""
    plan = scene.memo.get("plan")
    if plan is None:
        plan = scene.memo["plan"] = _Decomposition(scene).run()
    return cast(Plan, plan)

"""A closed-form plan compiled once per scene into column-form steps (issue 8: sweeps at speed).

A plan made only of drivers, two-circle dyads (RRR) and links known from two points (a four-bar
and its six-bar relatives) runs here on x and y columns of (N,) arrays instead of (N, 2)
vectors, with every point's position, velocity and acceleration written straight into
preallocated (N, 2) arrays. A fixed point's coordinates stay plain floats (its rates are 0).

The formulas are those of ``rigid`` and ``groups`` (``rrr``, ``loci``), evaluated in the same order
of floating-point operations (x - y computed as x + (-y), a product by a negated factor as the
negated product, v - 0 as v: all exact in IEEE arithmetic), so the answers are the general
assembler's bit for bit (tests/solver/position/test_compiled_plan.py). The branch search itself is
left out: its screen runs here as in ``assembly._Assembler.candidates``, on the same numbers, and
wherever it has something to examine (``assembly.screen``), a group does not close or a driver steps
too far between two samples (``assembly.MAX_DRIVER_STEP``), ``run`` returns None and the general
assembler runs instead, so the branch guarantees, the close-approach warnings and the failure
messages are unchanged. A dyad's margin rates are computed only where the screen needs them: where
its centres turn with drivers and its Lipschitz bound does not clear (from their velocities, or at
unit driver rate, 0 + k x (P - pivot)), and for a dyad on a moving centre (a six-bar's second dyad),
whose run therefore computes velocities, at unit rate of the moving driver where they are not at its
rate alone (``assembly.rates_alone``)."""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from functools import cached_property
from typing import cast

import numpy as np

from solver.kinematics.rigid import Array, Column, LinkMotion, PointMotion, repeat, solve_2x2
from solver.model.scene import LinkageScene
from solver.position.assembly import (
    DriverInput,
    Motion,
    PathStep,
    coarse,
    lipschitz_clear,
    path_steps,
    rates_alone,
    screen,
    unit_rate,
)
from solver.position.groups import loci, rrr
from solver.position.topology import CircleSpec, DriverStep, DyadStep, Plan, Reach, TwoPointStep


@dataclass
class _Point:
    """A point's columns (x, y; vx, vy; ax, ay) and the (N, 2) arrays they live in; a fixed
    point's columns are floats and its rates 0.0."""

    x: Column
    y: Column
    vx: Column = 0.0
    vy: Column = 0.0
    ax: Column = 0.0
    ay: Column = 0.0


@dataclass(frozen=True)
class _Rigid:
    """Points carried by a link, drawn at anchor0 + r0 (r0 = drawn - anchor0)."""

    anchor0: Array
    names: tuple[str, ...]
    r0: tuple[tuple[float, float], ...]


@dataclass(frozen=True)
class _Drive:
    link: str
    pivot: str
    driver: int
    carried: _Rigid


@dataclass(frozen=True)
class _Dyad:
    point: str
    first: CircleSpec
    second: CircleSpec
    sign: float
    drawn: tuple[float, float]
    reach: tuple[Reach, ...] | None  # its centres' (``topology.DyadStep``)


@dataclass(frozen=True)
class _TwoPoint:
    link: str
    first: str
    second: str
    angle0: float  # arctan2 of the drawn first -> second
    carried: _Rigid


_Step = _Drive | _Dyad | _TwoPoint


def _positive(x: Array) -> Array:
    """np.where(x > 0, x, 1.0): ``x`` itself where every x is positive (the common case)."""
    return x if x.min() > 0.0 else np.where(x > 0.0, x, 1.0)


def _sub(a: Column, b: Column) -> Column:
    """a - b; a - (+0.0) is a exactly (a fixed point's rate or coordinate), so not computed."""
    if isinstance(b, float) and b == 0.0 and math.copysign(1.0, b) > 0.0:
        return a
    return a - b


class CompiledPlan:
    """The steps of a closed-form plan in column form, with the scene's constants read once."""

    def __init__(self, scene: LinkageScene, steps: tuple[_Step, ...]) -> None:
        self.size = scene.size  # (no reference to the scene: the cache forgets it with it)
        self.steps = steps
        ground = scene.links[scene.ground]
        self.ground = ground.name
        self.fixed = {
            p: (float(scene.drawn(p)[0]), float(scene.drawn(p)[1])) for p in ground.points
        }
        self.ground_points = ground.points
        self.ground_anchor0 = scene.drawn(ground.points[0])
        # A dyad on a moving centre: its screen needs the rates of a velocity analysis.
        self.rated = any(isinstance(step, _Dyad) and step.reach is None for step in steps)

    def run(
        self, inputs: Sequence[DriverInput], order: int, keep: int | None = None
    ) -> Motion | None:
        """The motion at ``inputs`` on the drawn branches (up to accelerations for ``order``
        2), or None where the general assembler must decide (a group fails to close somewhere,
        or its margin dips where the branch search looks, or a driver steps more than
        ``assembly.MAX_DRIVER_STEP`` between two samples: the general assembler follows a denser
        grid there). ``keep``: only the first ``keep`` samples are returned (all are checked), as
        ``Motion.cut`` would give them."""
        n = inputs[0].theta.size
        kept = slice(0, n if keep is None else keep)
        path = path_steps(inputs)
        if coarse(path):
            return None
        if not (self.rated and path) or rates_alone(inputs, order, path):
            return _Run(self, inputs, order, kept, path).motion()
        if len(path) > 1:  # (the general assembler takes a run per moving driver)
            return None
        # The screen at unit rate of the moving driver (``assembly._Assembler.sensitivities``); at
        # order 0 that run is the answer, its velocities dropped.
        screened = _Run(self, unit_rate(inputs, path[0][0]), 0, kept, path, velocities=1).motion()
        if screened is None or order == 0:
            return screened
        return _Run(self, inputs, order, kept, path, screening=False).motion()


class _Run:
    """One run of a compiled plan over one set of inputs."""

    def __init__(
        self,
        plan: CompiledPlan,
        inputs: Sequence[DriverInput],
        order: int,
        kept: slice,
        path: list[PathStep],
        velocities: int = 0,
        screening: bool = True,
    ) -> None:
        """``order``: the orders returned; ``velocities``: computed at least to this order;
        ``screening``: the branch search's screen runs (not where it ran at unit driver rate)."""
        self.plan, self.inputs, self.order, self.kept = plan, inputs, order, kept
        self.computed = max(order, velocities)
        self.path, self.screening = path, screening
        self.turned: dict[str, tuple[int, Array, Array]] = {}  # driver, R(theta) r0 of its points
        self.n = inputs[0].theta.size
        n = kept.stop
        at_drawn = inputs[0].theta == 0.0
        for given in inputs[1:]:
            at_drawn &= given.theta == 0.0
        self.drawn_samples = np.flatnonzero(at_drawn)
        self.cols: dict[str, _Point] = {}
        self.points: dict[str, PointMotion] = {}
        at_rest = np.zeros((n, 2))
        for p, (x, y) in plan.fixed.items():
            self.cols[p] = _Point(x, y)
            self.points[p] = PointMotion(repeat(np.array((x, y)), n), at_rest, at_rest)
        # The ground (``rigid.fixed_link``) and the drivers' pivots share the fixed points' arrays.
        zeros = np.zeros(n)
        anchor = self.points[plan.ground_points[0]]
        self.links: dict[str, LinkMotion] = {
            plan.ground: LinkMotion(plan.ground_anchor0, anchor, zeros, zeros, zeros)
        }
        self.margin = np.ones(self.n)
        self.gradient_sine = np.ones(self.n)
        self.group_margins: dict[str, Array] = {}

    @cached_property
    def alone(self) -> bool:
        """Whether the velocities computed are at the moving driver's rate alone."""
        return rates_alone(self.inputs, self.computed, self.path)

    def motion(self) -> Motion | None:
        for step in self.plan.steps:
            if isinstance(step, _Drive):
                self.drive(step)
            elif isinstance(step, _Dyad):
                if not self.dyad(step):
                    return None
            else:
                self.two_point(step)
        kept = self.kept
        return Motion(
            self.links,
            self.points,
            self.margin[kept],
            np.ones(kept.stop, dtype=bool),
            self.gradient_sine[kept],
            size=self.plan.size,
            group_margins={k: m[kept] for k, m in self.group_margins.items()},
        )

    def new_point(self) -> tuple[_Point, Array, Array, Array]:
        """Fresh (N, 2) arrays p, v and a (v and a written only for the orders computed) and
        the point's columns, views of them."""
        p, v, a = (np.empty((self.n, 2)) for _ in range(3))
        return _Point(p[:, 0], p[:, 1], v[:, 0], v[:, 1], a[:, 0], a[:, 1]), p, v, a

    def known(self, name: str, point: _Point, p: Array, v: Array, a: Array) -> None:
        self.cols[name] = point
        order, kept = self.order, self.kept
        self.points[name] = PointMotion(
            p[kept], v[kept] if order >= 1 else None, a[kept] if order >= 2 else None
        )

    def carry(
        self,
        rigid: _Rigid,
        anchor: _Point,
        theta: Array,
        omega: Array | None,
        alpha: Array | None,
        driver: int | None = None,
    ) -> None:
        """Points fixed in a link: p = p_A + R(theta) r0, v = v_A + omega k x r,
        a = a_A + alpha k x r - omega^2 r (``rigid.LinkMotion.point``); ``driver``: the link is
        that driver's, turning about its fixed pivot (r kept for the rates at unit rate)."""
        if not rigid.names:
            return
        cos, sin = np.cos(theta), np.sin(theta)
        w2 = None if omega is None or alpha is None else omega**2
        for name, (x0, y0) in zip(rigid.names, rigid.r0, strict=True):
            point, p, v, a = self.new_point()
            rx = cos * x0 - sin * y0
            ry = sin * x0 + cos * y0
            np.add(anchor.x, rx, out=p[:, 0])
            np.add(anchor.y, ry, out=p[:, 1])
            if driver is not None:
                self.turned[name] = (driver, rx, ry)
            if omega is not None:
                np.subtract(anchor.vx, ry * omega, out=v[:, 0])
                np.add(anchor.vy, rx * omega, out=v[:, 1])
            if w2 is not None:
                np.subtract(anchor.ax - ry * alpha, w2 * rx, out=a[:, 0])
                np.subtract(anchor.ay + rx * alpha, w2 * ry, out=a[:, 1])
            self.known(name, point, p, v, a)

    def drive(self, step: _Drive) -> None:
        given = self.inputs[step.driver]
        omega = given.omega if self.computed >= 1 else None
        alpha = given.alpha if self.computed >= 2 else None
        kept, order = self.kept, self.order
        self.links[step.link] = LinkMotion(
            step.carried.anchor0,
            self.points[step.pivot],
            given.theta[kept],
            given.omega[kept] if order >= 1 else None,
            given.alpha[kept] if order >= 2 else None,
        )
        self.carry(step.carried, self.cols[step.pivot], given.theta, omega, alpha, step.driver)

    def dyad(self, step: _Dyad) -> bool:
        """RRR (``rrr.circle_circle`` and ``loci.point_motion``); False where the general
        assembler must run instead."""
        c1, c2 = self.cols[step.first.center], self.cols[step.second.center]
        r1, r2 = step.first.radius, step.second.radius
        cut = rrr.chord(cast(Array, _sub(c2.x, c1.x)), cast(Array, _sub(c2.y, c1.y)), r1, r2)
        d, ux, uy, a, h2 = cut.d, cut.ux, cut.uy, cut.a, cut.h2
        margin = np.minimum((r1 + r2) - d, d - abs(r1 - r2))

        def pieces() -> tuple[Array, Array]:
            """r1 + r2 - d and d - |r1 - r2| (made again where the screen needs them: at many
            samples two more live arrays would cost their allocations' page faults)."""
            return (r1 + r2) - d, d - abs(r1 - r2)

        def sensitivities(driver: int) -> list[Array]:
            """dm/dtheta of the pieces r1 + r2 - d and d - |r1 - r2|
            (``assembly._Assembler.sensitivities``): their rates -+ u.(v2 - v1)
            (``rrr.circle_circle``) over the driver's rate where the velocities are its
            alone, else with the centres at its unit rate."""
            if self.alone:
                v1, v2 = (c1.vx, c1.vy), (c2.vx, c2.vy)
            else:
                v1 = self.unit_velocity(step.first.center, driver)
                v2 = self.unit_velocity(step.second.center, driver)
            d_rate = ux * _sub(v2[0], v1[0]) + uy * _sub(v2[1], v1[1])
            if self.alone:  # ((-x) / y is -(x / y) in IEEE arithmetic)
                d_rate = d_rate / self.inputs[driver].omega
            return [-d_rate, d_rate]

        if not self.close(step, margin, pieces, sensitivities):
            return False
        h = loci.root(h2, r1**2)
        if step.sign < 0.0:
            h = -h
        point, p, v, acc = self.new_point()
        np.subtract(c1.x + ux * a, uy * h, out=p[:, 0])
        np.add(c1.y + uy * a, ux * h, out=p[:, 1])
        if self.drawn_samples.size:
            p[self.drawn_samples] = step.drawn
        self.rates(point, c1, c2, v, acc)
        self.known(step.point, point, p, v, acc)
        return True

    def close(
        self,
        step: _Dyad,
        margin: Array,
        pieces: Callable[[], tuple[Array, Array]],
        sensitivities: Callable[[int], list[Array]],
    ) -> bool:
        """Record a group's margin m (``assembly._Assembler.close``); False where it fails to
        close somewhere or the branch search would look at it (``_Assembler.candidates``, from
        the same numbers: the pieces' dm/dtheta for a moving driver from ``sensitivities``)."""
        size = self.plan.size
        relative = margin / size
        if relative.min() < -loci.COINCIDENCE_TOLERANCE:
            return False
        path = self.path
        if self.screening and path:
            reach = step.reach
            if reach is None or not lipschitz_clear(margin, reach, path, size):
                rates = [sensitivities(driver) for driver, _, _ in path]
                if screen(margin, pieces(), rates, path, size):
                    return False
        self.margin = np.minimum(self.margin, relative)
        self.group_margins[step.point] = margin
        return True

    def unit_velocity(self, name: str, driver: int) -> tuple[Column, Column]:
        """A point's velocity at unit rate of ``driver`` (every other at rest), where it is fixed
        or turned by a driver: 0 + k x (P - pivot), as ``rigid.LinkMotion.point`` gives it."""
        turned = self.turned.get(name)
        if turned is None or turned[0] != driver:
            return 0.0, 0.0
        _, rx, ry = turned
        return 0.0 - ry, 0.0 + rx

    def rates(self, X: _Point, c1: _Point, c2: _Point, v: Array, a: Array) -> None:
        """G v_X = b and G a_X = b' by Cramer's rule, G = [X - C1; X - C2], and the sine of the
        angle between the rows, |det G| / (|g1| |g2|) (``loci.point_motion``)."""
        g1x, g1y = _sub(X.x, c1.x), _sub(X.y, c1.y)
        g2x, g2y = _sub(X.x, c2.x), _sub(X.y, c2.y)
        det = g1x * g2y - g1y * g2x
        norms = np.sqrt((g1x * g1x + g1y * g1y) * (g2x * g2x + g2y * g2y))
        sine = np.abs(det) / _positive(norms)
        self.gradient_sine = np.minimum(self.gradient_sine, sine)
        if self.computed < 1:
            return
        if not np.all(det):
            det = np.where(det != 0.0, det, np.inf)
        rows = (g1x, g1y), (g2x, g2y)
        rhs = (g1x * c1.vx + g1y * c1.vy, g2x * c2.vx + g2y * c2.vy)
        solve_2x2(*rows, rhs, det, (v[:, 0], v[:, 1]))
        if self.computed < 2:
            return
        w1x, w1y = _sub(X.vx, c1.vx), _sub(X.vy, c1.vy)
        w2x, w2y = _sub(X.vx, c2.vx), _sub(X.vy, c2.vy)
        rhs = (
            (g1x * c1.ax + g1y * c1.ay) - (w1x * w1x + w1y * w1y),
            (g2x * c2.ax + g2y * c2.ay) - (w2x * w2x + w2y * w2y),
        )
        solve_2x2(*rows, rhs, det, (a[:, 0], a[:, 1]))

    def two_point(self, step: _TwoPoint) -> None:
        """theta = angle(PQ) - angle(P0Q0), omega = (r x v_rel) / |r|^2, alpha = (r x a_rel) /
        |r|^2 with r = Q - P (``rigid.link_from_two_points``)."""
        P, Q = self.cols[step.first], self.cols[step.second]
        rx, ry = _sub(Q.x, P.x), _sub(Q.y, P.y)
        theta = np.arctan2(ry, rx) - step.angle0
        r2 = rx * rx + ry * ry
        omega = alpha = None
        if self.computed >= 1:
            omega = cast(Array, (rx * _sub(Q.vy, P.vy) - ry * _sub(Q.vx, P.vx)) / r2)
        if self.computed >= 2:
            alpha = cast(Array, (rx * _sub(Q.ay, P.ay) - ry * _sub(Q.ax, P.ax)) / r2)
        kept, order = self.kept, self.order
        self.links[step.link] = LinkMotion(
            step.carried.anchor0,
            self.points[step.first],
            theta[kept],
            None if omega is None or order < 1 else omega[kept],
            None if alpha is None or order < 2 else alpha[kept],
        )
        self.carry(step.carried, P, theta, omega, alpha)


def _carried(scene: LinkageScene, link: str, anchor: str, known: set[str]) -> _Rigid:
    """The points of ``link`` not yet known, relative to its anchor's drawn position."""
    names = tuple(p for p in scene.links[link].points if p not in known)
    known.update(names)
    anchor0 = scene.drawn(anchor)
    r0 = tuple((float(r[0]), float(r[1])) for r in (scene.drawn(p) - anchor0 for p in names))
    return _Rigid(anchor0, names, r0)


def _compile(scene: LinkageScene, plan: Plan) -> CompiledPlan | None:
    """The plan's steps in column form; None if it has a step of another kind (a slot, a
    lever, a prismatic guide, a Newton group) or a dyad between two fixed points."""
    fixed = set(scene.links[scene.ground].points)
    known = set(fixed)
    steps: list[_Step] = []
    for step in plan.steps:
        if isinstance(step, DriverStep):
            if step.pivot not in fixed:
                return None
            carried = _carried(scene, step.link, step.pivot, known)
            steps.append(_Drive(step.link, step.pivot, step.driver, carried))
        elif isinstance(step, DyadStep):
            first, second = step.loci
            if not (isinstance(first, CircleSpec) and isinstance(second, CircleSpec)):
                return None
            if first.center in fixed and second.center in fixed:
                return None
            drawn = scene.drawn(step.point)
            steps.append(
                _Dyad(step.point, first, second, step.sign, (drawn[0], drawn[1]), step.reach)
            )
            known.add(step.point)
        elif isinstance(step, TwoPointStep):
            r0 = scene.drawn(step.second) - scene.drawn(step.first)
            angle0 = float(np.arctan2(r0[1], r0[0]))
            carried = _carried(scene, step.link, step.first, known)
            steps.append(_TwoPoint(step.link, step.first, step.second, angle0, carried))
        else:
            return None
    return CompiledPlan(scene, tuple(steps))


def compiled_plan(scene: LinkageScene, plan: Plan) -> CompiledPlan | None:
    """The scene's plan in column form (None if it cannot be), compiled once per scene object
    and kept on it (``LinkageScene.memo``)."""
    memo = scene.memo
    if "compiled_plan" not in memo:
        memo["compiled_plan"] = _compile(scene, plan)
    return cast(CompiledPlan | None, memo["compiled_plan"])

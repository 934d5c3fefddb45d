"""One instant of a planar linkage in full: ``analyze(scene, quantities)``.

Positions, velocities and accelerations of every point and link, poles, the transport / relative /
Coriolis split at every slider and prismatic joint, instant centres, four-bar loops and the
condition number of the velocity equations. Only the requested quantities are computed (a
position-only request never differentiates anything).
"""

from __future__ import annotations

import math
from collections.abc import Iterable
from dataclasses import dataclass, field
from itertools import combinations

import numpy as np

from solver import newton
from solver.assembly import WARNING_MARGIN, DriverInput, Motion, assemble, require_feasible
from solver.continuation import Continuation
from solver.dyads import COINCIDENCE_TOLERANCE
from solver.errors import InvalidScene, SingularConfiguration
from solver.laws import parse_time_law
from solver.poles import (
    FourBarLoop,
    InstantCentre,
    Poles,
    acceleration_poles,
    grashof_class,
    instant_centre,
    transmission_angle,
    velocity_poles,
)
from solver.polish import exact_turn, polish
from solver.relative_motion import MovingPointMotion, coriolis_acceleration, moving_point_motion
from solver.rigid import (
    Array,
    perp,
    rigid_body_acceleration,
    rigid_body_velocity,
)
from solver.scene import Driver, LinkageScene
from solver.topology import CircleSpec, DriverStep, DyadStep, Plan, build_plan

QUANTITIES = ("position", "velocity", "acceleration", "poles", "components")
DYNAMIC_QUANTITIES = ("forces", "energy")  # dynamics-v1: computed by solver.dynamics
# cond(J) above this: the velocity equations are singular to within rounding (a dead centre).
SINGULAR_CONDITION = 1e12


@dataclass(frozen=True)
class PointResult:
    position: Array | None = None
    velocity: Array | None = None
    acceleration: Array | None = None


@dataclass(frozen=True)
class LinkResult:
    """A moving link: absolute angle (first to second point; None with one point), rates, poles."""

    angle: float | None = None
    omega: float | None = None
    alpha: float | None = None
    velocity_pole: Array | None = None
    acceleration_pole: Array | None = None


@dataclass(frozen=True)
class SlidingJoint:
    """Velocity and acceleration of the follower's point P of a slider or prismatic joint.

    v = v_transport + v_relative;  a = a_transport + a_relative + a_coriolis, with the transport
    terms those of the guide's point coinciding with P, and a_coriolis = 2 omega_guide x v_rel.
    """

    point: str
    type: str
    links: tuple[str, str]
    omega_guide: Array
    transport_velocity: Array
    relative_velocity: Array
    velocity: Array
    transport_acceleration: Array | None
    relative_acceleration: Array | None
    coriolis_acceleration: Array | None
    acceleration: Array | None

    def at(self, k: int) -> SlidingJoint:
        """The same parts at sample ``k`` alone (arrays over samples become single values)."""

        def pick(value: Array | None) -> Array | None:
            return None if value is None else value[k]

        return SlidingJoint(
            self.point, self.type, self.links, self.omega_guide[k],
            self.transport_velocity[k], self.relative_velocity[k], self.velocity[k],
            pick(self.transport_acceleration), pick(self.relative_acceleration),
            pick(self.coriolis_acceleration), pick(self.acceleration),
        )  # fmt: skip


@dataclass(frozen=True)
class Diagnostics:
    """How the answer was obtained and how much to trust it."""

    condition_number: float | None
    closed_form: bool
    newton: tuple[newton.NewtonReport, ...]
    driver_angles: dict[str, float]
    closest_approach: tuple[str, float] | None = None  # the group nearest its change point, m
    position_residual: float = 0.0  # |Phi| of the polished position, m (0 at the drawn pose)


@dataclass(frozen=True)
class LinkageAnalysis:
    quantities: frozenset[str]
    points: dict[str, PointResult]
    links: dict[str, LinkResult]
    joints: list[SlidingJoint]
    instant_centres: list[InstantCentre]
    four_bar_loops: list[FourBarLoop]
    diagnostics: Diagnostics
    plan: Plan
    motion: Motion = field(repr=False)
    moving_points: dict[str, MovingPointMotion] = field(default_factory=dict)
    warnings: tuple[str, ...] = ()


def near_change_point(motion: Motion) -> tuple[tuple[str, float] | None, tuple[str, ...]]:
    """The two-branch group with the smallest length margin at the (single) pose, and a warning
    where its two branches are closer than the warning margin without meeting."""
    margins = {name: float(m[0]) for name, m in motion.group_margins.items()}
    if not margins:
        return None, ()
    name = min(margins, key=lambda k: margins[k])
    margin = margins[name]
    if not COINCIDENCE_TOLERANCE * motion.size < margin < WARNING_MARGIN * motion.size:
        return (name, margin), ()
    return (name, margin), (
        f"the two assemblies of {name} are within {margin:.2g} m of a change point at this pose; "
        "a real mechanism with clearance could switch assembly here",
    )


def normalise_quantities(quantities: Iterable[str] | None) -> frozenset[str]:
    """The requested quantities; the default is every kinematic one (the dynamic ones, which
    dynamics-v1 adds, only when asked for)."""
    if quantities is None:
        return frozenset(QUANTITIES)
    chosen = frozenset(quantities)
    allowed = (*QUANTITIES, *DYNAMIC_QUANTITIES)
    unknown = sorted(chosen - set(allowed))
    if unknown:
        raise InvalidScene(f"quantities: unknown {unknown}; allowed: {', '.join(allowed)}")
    return chosen


def required_order(quantities: frozenset[str], moving_points: bool = False) -> int:
    """0 for positions, 1 to velocities, 2 to accelerations (poles, components, forces and
    energy need both; so do moving points, whose velocity and acceleration parts come together)."""
    if quantities & {"acceleration", "poles", "components", *DYNAMIC_QUANTITIES} or (
        moving_points and quantities - {"position"}
    ):
        return 2
    return 1 if "velocity" in quantities else 0


def drawn_angle(scene: LinkageScene, link: str) -> float:
    points = scene.links[link].points
    d = scene.drawn(points[1]) - scene.drawn(points[0])
    return math.atan2(d[1], d[0])


def _start_turn(scene: LinkageScene, driver: Driver, wrap: bool = True) -> float:
    """The driver's rotation from the drawn pose to its ``angle_deg`` (0 without one), reduced
    to (-pi, pi] unless ``wrap`` is false (then as written: angle_deg - the drawn angle)."""
    if driver.angle_deg is None:
        return 0.0
    if len(scene.links[driver.link].points) < 2:
        raise InvalidScene(
            f"drivers: angle_deg needs two points on link '{driver.link}' to define its angle"
        )
    turn = math.radians(driver.angle_deg) - drawn_angle(scene, driver.link)
    return math.atan2(math.sin(turn), math.cos(turn)) if wrap else turn


def driver_motion(
    scene: LinkageScene, driver: Driver, times: Array, wrap: bool = True
) -> DriverInput:
    """A driver's rotation from the drawn pose, omega and alpha at each of ``times``.

    With an ``angle_law`` the law gives all three. A driver with constant ``alpha`` turns from
    its starting angle (drawn, or ``angle_deg``) as phi = omega t + alpha t^2 / 2, so at the
    default time 0 it is exactly where the scene puts it, with the given omega and alpha.
    """
    if driver.angle_law is not None:
        return DriverInput(*parse_time_law(driver.angle_law).evaluate(times))
    return DriverInput(
        _start_turn(scene, driver, wrap) + driver.omega * times + 0.5 * driver.alpha * times**2,
        driver.omega + driver.alpha * times,
        np.full(times.size, driver.alpha),
    )


def driver_input(
    scene: LinkageScene, driver: Driver, time: float, wrap: bool = True
) -> tuple[float, float, float]:
    """(rotation from the drawn pose, omega, alpha) of a driver at one instant."""
    at = driver_motion(scene, driver, np.array([time]), wrap)
    return float(at.theta[0]), float(at.omega[0]), float(at.alpha[0])


def driver_inputs_over_time(scene: LinkageScene, times: Array) -> list[DriverInput]:
    """Every driver's rotation from the drawn pose and its rates at each of ``times``."""
    return [driver_motion(scene, driver, times) for driver in scene.drivers]


def solve_instant(
    scene: LinkageScene,
    plan: Plan,
    order: int,
    time: float | None = None,
    newton_groups: Continuation | None = None,
) -> tuple[Motion, dict[str, float], float]:
    """Assemble the linkage at the drivers' requested angles (index 0 of the returned motion),
    its position polished in extended precision away from the drawn pose (``solver.polish``;
    the residual, m, is returned last).

    A Newton group takes the pose its branch reaches from the drawn pose (``solver.continuation``)
    as the driver turns to ``angle_deg`` as written (not reduced to one turn), which is how a
    sweep's ``driver_angle`` reads.
    """
    t = scene.time if time is None else time
    given = [driver_input(scene, d, t) for d in scene.drivers]
    turns = [driver_input(scene, d, t, wrap=plan.closed_form)[0] for d in scene.drivers]
    inputs = [
        DriverInput(np.array([turn]), np.array([w]), np.array([e]))
        for turn, (_, w, e) in zip(turns, given, strict=True)
    ]
    motion = assemble(scene, plan, inputs, order, newton_groups=newton_groups)
    residual = 0.0
    if any(turn != 0.0 for turn in turns) and np.all(motion.feasible):  # not the drawn pose
        exact = [
            exact_turn(scene, d, t, turn) for d, turn in zip(scene.drivers, turns, strict=True)
        ]
        motion, residual = polish(scene, plan, inputs, exact, order, motion)
    angles = {
        d.link: math.degrees(drawn_angle(scene, d.link) + g[0])
        for d, g in zip(scene.drivers, given, strict=True)
        if len(scene.links[d.link].points) >= 2
    }
    where = "at " + ", ".join(f"{k} angle {v:.6g} deg" for k, v in angles.items())
    if not angles:
        where = "at the drawn pose"
    require_feasible(motion, where)
    return motion, angles, residual


def sliding_joints(scene: LinkageScene, motion: Motion, order: int) -> list[SlidingJoint]:
    """Every slider and prismatic joint split into its parts, at every sample of ``motion``."""
    joints = []
    for joint in scene.joints:
        if joint.type == "revolute":
            continue
        guide = motion.links[joint.guide]
        P = motion.points[joint.point]
        assert P.v is not None and guide.omega is not None and guide.anchor.v is not None
        r = P.p - guide.anchor.p
        v_tr = rigid_body_velocity(guide.anchor.v, guide.omega, r)
        v_rel = P.v - v_tr
        a_tr = a_rel = a_cor = None
        if order >= 2:
            assert P.a is not None and guide.alpha is not None and guide.anchor.a is not None
            a_tr = rigid_body_acceleration(guide.anchor.a, guide.omega, guide.alpha, r)
            a_cor = coriolis_acceleration(guide.omega, v_rel)
            a_rel = P.a - a_tr - a_cor
        joints.append(
            SlidingJoint(
                joint.point,
                joint.type,
                joint.links,
                guide.omega,
                v_tr,
                v_rel,
                P.v,
                a_tr,
                a_rel,
                a_cor,
                P.a if order >= 2 else None,
            )
        )
    return joints


def link_poles(scene: LinkageScene, motion: Motion, link: str) -> tuple[Poles, Poles]:
    """The velocity and acceleration poles of a moving link at every sample of ``motion``."""
    m = motion.links[link]
    X = m.anchor
    assert X.v is not None and X.a is not None and m.omega is not None and m.alpha is not None
    return (
        velocity_poles(X.p, X.v, m.omega, scene.size),
        acceleration_poles(X.p, X.a, m.omega, m.alpha, scene.size),
    )


def _link_results(
    scene: LinkageScene, motion: Motion, quantities: frozenset[str]
) -> dict[str, LinkResult]:
    results = {}
    for name in scene.moving_links:
        link = motion.links[name]
        points = scene.links[name].points
        angle = None
        if len(points) >= 2 and "position" in quantities:
            d = motion.points[points[1]].p[0] - motion.points[points[0]].p[0]
            angle = math.atan2(d[1], d[0])
        omega = None if link.omega is None else float(link.omega[0])
        alpha = None if link.alpha is None else float(link.alpha[0])
        v_pole = a_pole = None
        if "poles" in quantities:
            v_poles, a_poles = link_poles(scene, motion, name)
            v_pole, a_pole = v_poles.at(0), a_poles.at(0)
        results[name] = LinkResult(
            angle,
            omega if "velocity" in quantities or "poles" in quantities else None,
            alpha if "acceleration" in quantities or "poles" in quantities else None,
            v_pole,
            a_pole,
        )
    return results


def _instant_centres(scene: LinkageScene, plan: Plan, motion: Motion) -> list[InstantCentre]:
    """Instant centres of every pair of links (ground included), from the velocity fields.

    They depend on the geometry alone (for one degree of freedom): with every driver at rest the
    same pose is differentiated at unit driver rates instead.
    """
    driver_rates = [motion.links[d.link].omega for d in scene.drivers]
    if all(rate is not None and rate[0] == 0.0 for rate in driver_rates):
        unit = [
            DriverInput(motion.links[d.link].theta[:1], np.ones(1), np.zeros(1))
            for d in scene.drivers
        ]
        motion = assemble(scene, plan, unit, 1)
    fields = {}
    for name in scene.links:
        link = motion.links[name]
        assert link.anchor.v is not None and link.omega is not None
        omega = float(link.omega[0])
        fields[name] = (link.anchor.v[0] - omega * perp(link.anchor.p[0]), omega)
    return [
        instant_centre(i, *fields[i], j, *fields[j], scene.size)
        for i, j in combinations(scene.links, 2)
    ]


def four_bar_loops(scene: LinkageScene, plan: Plan, motion: Motion) -> list[FourBarLoop]:
    """RRR dyads closing a loop ground - driven crank - coupler - rocker - ground."""
    cranks = {s.link: s.pivot for s in plan.steps if isinstance(s, DriverStep)}
    ground_points = set(scene.links[scene.ground].points)
    loops = []
    for step in plan.steps:
        if not (isinstance(step, DyadStep) and all(isinstance(c, CircleSpec) for c in step.loci)):
            continue
        first, second = step.loci
        assert isinstance(first, CircleSpec) and isinstance(second, CircleSpec)
        if first.center in ground_points:
            first, second = second, first
        crank = next(
            (
                c
                for c, pivot in cranks.items()
                if first.center in scene.links[c].points and first.center != pivot
            ),
            None,
        )
        if crank is None or second.center not in ground_points:
            continue
        A, B = scene.drawn(cranks[crank]), scene.drawn(first.center)
        D = scene.drawn(second.center)
        lengths = (
            float(np.hypot(*(D - A))),
            float(np.hypot(*(B - A))),
            first.radius,
            second.radius,
        )
        p = motion.points
        mu = transmission_angle(p[first.center].p[0], p[step.point].p[0], p[second.center].p[0])
        loops.append(
            FourBarLoop(
                (scene.ground, crank, first.link, second.link), lengths, grashof_class(*lengths), mu
            )
        )
    return loops


def analyze(
    scene: LinkageScene, quantities: Iterable[str] | None = None, tolerance: float | None = None
) -> LinkageAnalysis:
    """The linkage at its drivers' angles: drawn, ``angle_deg``, or ``angle_law`` at ``time``;
    ``tolerance`` is a Newton group's (relative to the size; default newton.NEWTON_TOLERANCE)."""
    wanted = normalise_quantities(quantities)
    order = required_order(wanted, bool(scene.moving_points))
    plan = build_plan(scene)
    groups = Continuation(scene, newton.newton_tolerance(tolerance))
    motion, angles, residual = solve_instant(scene, plan, order, newton_groups=groups)
    condition = None
    if order >= 1:
        condition = newton.velocity_condition_number(scene, motion.links, 0)
        if condition > SINGULAR_CONDITION or float(motion.conditioning[0]) == 0.0:
            where = ", ".join(f"{k} at {v:.6g} deg" for k, v in angles.items())
            raise SingularConfiguration(
                f"dead centre{' with ' + where if where else ''}: the velocity equations are "
                f"singular (condition number {condition:.3g}), so the driver cannot move the "
                "linkage here",
                condition,
            )
    points = {
        name: PointResult(
            m.p[0] if "position" in wanted else None,
            m.v[0] if "velocity" in wanted and m.v is not None else None,
            m.a[0] if "acceleration" in wanted and m.a is not None else None,
        )
        for name, m in motion.points.items()
        if name in scene.points
    }
    joints = (
        [j.at(0) for j in sliding_joints(scene, motion, order)] if "components" in wanted else []
    )
    centres = _instant_centres(scene, plan, motion) if "poles" in wanted else []
    closest, warnings = near_change_point(motion)
    diagnostics = Diagnostics(
        condition, plan.closed_form, tuple(motion.newton), angles, closest, residual
    )
    moving = {}
    if scene.moving_points:
        carriers = motion.links
        if order < 2:  # a position-only request: M's position comes with its parts
            carriers = solve_instant(scene, plan, 2, newton_groups=groups)[0].links
        moving = {
            mp.name: moving_point_motion(scene, mp, carriers[mp.link], np.array([scene.time])).at(0)
            for mp in scene.moving_points
        }
    return LinkageAnalysis(
        wanted,
        points,
        _link_results(scene, motion, wanted),
        joints,
        centres,
        four_bar_loops(scene, plan, motion),
        diagnostics,
        plan,
        motion,
        moving,
        warnings,
    )

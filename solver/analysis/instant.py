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

import numpy as np

from solver.analysis.link_kinematics import four_bar_loops, instant_centres, poles_at
from solver.analysis.sliding_joints import SlidingJoint, sliding_joints
from solver.errors import SingularConfiguration
from solver.kinematics.four_bar import FourBarLoop
from solver.kinematics.instant_centres import InstantCentre
from solver.kinematics.relative_motion import MovingPointMotion, moving_point_motion
from solver.kinematics.rigid import Array
from solver.model.quantities import normalise_quantities, required_order
from solver.model.scene import LinkageScene
from solver.position import constraints, newton
from solver.position.assembly import WARNING_MARGIN, DriverInput, Motion, assemble, require_feasible
from solver.position.continuation import Continuation
from solver.position.drivers import drawn_angle, driver_input
from solver.position.groups.loci import COINCIDENCE_TOLERANCE
from solver.position.polish import exact_turn, polish
from solver.position.topology import Plan, build_plan

# cond(J) above this: the velocity equations are singular to within rounding (a dead centre).
MAX_CONDITION_NUMBER = 1e12


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


def solve_instant(
    scene: LinkageScene,
    plan: Plan,
    order: int,
    time: float | None = None,
    newton_groups: Continuation | None = None,
) -> tuple[Motion, dict[str, float], float]:
    """Assemble the linkage at the drivers' requested angles (index 0 of the returned motion),
    its position polished in 40 digits away from the drawn pose (``solver.position.polish``; the
    residual, m, is returned last).

    A Newton group takes the pose its branch reaches from the drawn pose
    (``solver.position.continuation``) as the driver turns to ``angle_deg`` as written (not
    reduced to one turn), which is how a sweep's ``driver_angle`` reads.
    """
    t = scene.time if time is None else time
    given = [driver_input(scene, d, t) for d in scene.drivers]
    turns = [g[0] for g in given]  # reduced to one turn, unless a Newton group follows them
    if not plan.closed_form:
        turns = [driver_input(scene, d, t, wrap=False)[0] for d in scene.drivers]
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


def _link_results(
    scene: LinkageScene, motion: Motion, quantities: frozenset[str]
) -> dict[str, LinkResult]:
    results = {}
    poles = poles_at(scene, motion, 0) if "poles" in quantities else None
    rates = "velocity" in quantities or "poles" in quantities
    accelerations = "acceleration" in quantities or "poles" in quantities
    for m, name in enumerate(scene.moving_links):
        link = motion.links[name]
        points = scene.links[name].points
        angle = None
        if len(points) >= 2 and "position" in quantities:
            d = motion.points[points[1]].p[0] - motion.points[points[0]].p[0]
            angle = math.atan2(d[1], d[0])
        results[name] = LinkResult(
            angle,
            float(link.omega[0]) if rates and link.omega is not None else None,
            float(link.alpha[0]) if accelerations and link.alpha is not None else None,
            None if poles is None else poles[0].at(m),
            None if poles is None else poles[1].at(m),
        )
    return results


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
        condition = constraints.velocity_condition_number(scene, motion.links, 0)
        if condition > MAX_CONDITION_NUMBER or float(motion.gradient_sine[0]) == 0.0:
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
    centres = instant_centres(scene, plan, motion) if "poles" in wanted else []
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

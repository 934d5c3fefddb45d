"""The textbook kinematics applied to a solved linkage: each link's poles, every pair's instant
centre (Kennedy) and the four-bar loops with their Grashof class and transmission angle.

The formulas are those of ``solver.kinematics``; this module finds where they apply in a scene's
plan and evaluates them on its ``Motion``.
"""

from __future__ import annotations

from itertools import combinations

import numpy as np

from solver.kinematics.four_bar import FourBarLoop, grashof_class, transmission_angle
from solver.kinematics.instant_centres import InstantCentre, centres_of_pairs
from solver.kinematics.poles import Poles, acceleration_poles, velocity_poles
from solver.kinematics.rigid import rigid_body_velocity
from solver.model.scene import LinkageScene
from solver.position.assembly import DriverInput, Motion, assemble
from solver.position.topology import CircleSpec, DriverStep, DyadStep, Plan


def link_poles(scene: LinkageScene, motion: Motion, link: str) -> tuple[Poles, Poles]:
    """The velocity and acceleration poles of a moving link at every sample of ``motion``."""
    m = motion.links[link]
    X = m.anchor
    assert X.v is not None and X.a is not None and m.omega is not None and m.alpha is not None
    return (
        velocity_poles(X.p, X.v, m.omega, scene.size),
        acceleration_poles(X.p, X.a, m.omega, m.alpha, scene.size),
    )


def poles_at(scene: LinkageScene, motion: Motion, k: int) -> tuple[Poles, Poles]:
    """``link_poles`` of every moving link at sample ``k`` in one call: row m of the velocity and
    the acceleration poles is link ``scene.moving_links[m]`` (the links stacked as samples)."""
    links = [motion.links[name] for name in scene.moving_links]
    anchors = [m.anchor for m in links]
    p, v, a = (np.array([getattr(x, order)[k] for x in anchors]) for order in ("p", "v", "a"))
    omega, alpha = (np.array([getattr(m, rate)[k] for m in links]) for rate in ("omega", "alpha"))
    return (
        velocity_poles(p, v, omega, scene.size),
        acceleration_poles(p, a, omega, alpha, scene.size),
    )


TINY_RATE = 1e-150  # rad/s: below it a rate times a length squared may underflow


def instant_centres(scene: LinkageScene, plan: Plan, motion: Motion) -> list[InstantCentre]:
    """Instant centres of every pair of links (ground included), from the velocity fields.

    They depend on the geometry and the ratios of the driver rates alone: with every driver at
    rest the same pose is differentiated at unit driver rates instead, and with rates so small
    that the velocities would lose their digits to underflow (below ``TINY_RATE``), at the rates
    divided by the largest.
    """
    rates = [motion.links[d.link].omega for d in scene.drivers]
    if all(rate is not None for rate in rates):
        largest = max((abs(float(rate[0])) for rate in rates if rate is not None), default=0.0)
        if largest < TINY_RATE:
            unit = [
                DriverInput(
                    motion.links[d.link].theta[:1],
                    np.ones(1) if largest == 0.0 else rate[:1] / largest,
                    np.zeros(1),
                )
                for d, rate in zip(scene.drivers, rates, strict=True)
                if rate is not None
            ]
            motion = assemble(scene, plan, unit, 1)
    links = [motion.links[name] for name in scene.links]
    p, v = (np.array([getattr(m.anchor, order)[0] for m in links]) for order in ("p", "v"))
    omega = np.array([m.omega[0] for m in links if m.omega is not None])
    assert omega.shape == (len(links),)
    V = rigid_body_velocity(v, omega, -p)  # each link's velocity field at the origin
    i, j = np.array(list(combinations(range(len(links)), 2))).T
    pairs = list(combinations(scene.links, 2))
    return centres_of_pairs(pairs, V[i], omega[i], V[j], omega[j], scene.size)


def four_bar_loops(
    scene: LinkageScene, plan: Plan, motion: Motion, every_sample: bool = False
) -> list[FourBarLoop]:
    """RRR dyads closing a loop ground - driven crank - coupler - rocker - ground; the
    transmission angle at the first sample of ``motion`` (a float), or at every sample (an
    array) if ``every_sample``."""
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
        points = (first.center, step.point, second.center)
        B, C, D = (motion.points[name].p for name in points)
        mu = (
            transmission_angle(B, C, D)
            if every_sample
            else float(transmission_angle(B[0], C[0], D[0]))
        )
        links = (scene.ground, crank, first.link, second.link)
        loops.append(FourBarLoop(links, lengths, grashof_class(*lengths), mu, points))
    return loops

"""Four-bar loops: Grashof's classification and the transmission angle.

Grashof: with s the shortest and l the longest of the four lengths, s + l <= p + q lets the
shortest link turn fully; the transmission angle is the angle between coupler and rocker.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from solver.assembly import Motion
from solver.rigid import Array, cross
from solver.scene import LinkageScene
from solver.topology import CircleSpec, DriverStep, DyadStep, Plan


@dataclass(frozen=True)
class FourBarLoop:
    """A ground-crank-coupler-rocker loop: its Grashof class and transmission angle (rad), a
    float at one instant or an array over a sweep's samples. ``points`` are B, C, D of the
    angle BCD: the crank pin, the coupler-rocker joint, the rocker's ground pivot."""

    links: tuple[str, str, str, str]
    lengths: tuple[float, float, float, float]
    grashof: str
    transmission_angle: float | Array
    points: tuple[str, str, str]


def grashof_class(ground: float, crank: float, coupler: float, rocker: float) -> str:
    """Grashof's criterion s + l <= p + q, and which link is the shortest."""
    lengths = [ground, crank, coupler, rocker]
    s, l_ = min(lengths), max(lengths)
    spread = s + l_ - (sum(lengths) - s - l_)
    if abs(spread) <= 1e-12 * l_:
        return "change-point"
    if spread > 0:
        return "non-Grashof triple-rocker"
    shortest = int(np.argmin(lengths))
    return (
        "Grashof double-crank",
        "Grashof crank-rocker",
        "Grashof double-rocker",
        "Grashof rocker-crank",
    )[shortest]


def transmission_angle(B: Array, C: Array, D: Array) -> Array:
    """The angle BCD between coupler CB and rocker CD at their joint C (0..pi), at every sample:
    points (2,) give a 0-d array, points (N, 2) an array (N,)."""
    u, w = B - C, D - C
    return np.arctan2(np.abs(cross(u, w)), np.vecdot(u, w))


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

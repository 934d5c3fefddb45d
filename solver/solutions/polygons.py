"""The velocity and acceleration polygons as data: every image segment in the worked solution's
order, from the base point the solution uses.

A segment joins the images of two points B (the base) and P of one link. Its parts are those of
the rigid-body formulas the solution writes

    v_P = v_B + omega x r_BP,        a_P = a_B + alpha x r_BP - omega^2 r_BP,

that is the relative velocity omega x r_BP, the tangential part alpha x r_BP and the normal part
-omega^2 r_BP (towards B). The Coriolis, transport and relative parts of the sliders and moving
points are in the /analyze body (``joints``, ``moving_points``); ``sliding`` lists where, in the
order the solution takes them up. The browser draws these vectors; it computes none.
"""

from __future__ import annotations

from collections.abc import Iterable
from typing import Any

import numpy as np

from solver.analysis.instant import LinkageAnalysis
from solver.kinematics.rigid import normal_acceleration, omega_cross
from solver.model.scene import LinkageScene
from solver.solutions import Step

JSON = dict[str, Any]


def _base_and_link(step: Step) -> tuple[str | None, str | None]:
    """The step's base point (its first point acceleration) and its link (first omega)."""
    base = link = None
    for value in step.values.values():
        source = value.source or ()
        if len(source) == 3 and source[0] == "points" and source[2] == "acceleration":
            base = base or str(source[1])
        if len(source) == 3 and source[0] == "links" and source[2] == "omega":
            link = link or str(source[1])
    return base, link


def segment_order(scene: LinkageScene, steps: Iterable[Step]) -> list[tuple[str, str, str]]:
    """(link, base, point) for every segment the solution's acceleration steps write with a normal
    part ``normal(B,P)``, first appearance of each (link, point) only, in the steps' order."""
    order: list[tuple[str, str, str]] = []
    seen: set[tuple[str, str]] = set()
    for step in steps:
        if not step.kind.startswith("acceleration."):
            continue
        base, link = _base_and_link(step)
        if base is None or link is None or base not in scene.links[link].points:
            continue
        prefix = f"normal({base},"
        for key in step.values:
            point = key[len(prefix) : -1]
            written = key.startswith(prefix) and key.endswith(")")
            if written and point in scene.links[link].points and (link, point) not in seen:
                seen.add((link, point))
                order.append((link, base, point))
    return order


def _sliding_order(steps: Iterable[Step]) -> list[list[str | int]]:
    """Paths of the joints and moving points whose Coriolis term the solution takes up."""
    found: list[list[str | int]] = []
    for step in steps:
        for value in step.values.values():
            source = value.source or ()
            if len(source) == 3 and source[2] == "coriolis_acceleration":
                owner = list(source[:2])
                if owner not in found:
                    found.append(owner)
    return found


def polygons(scene: LinkageScene, analysis: LinkageAnalysis, steps: Iterable[Step]) -> JSON:
    """The segments of the polygons (v = omega x r, tangential = alpha x r, normal = -omega^2 r)
    and the sliding parts' places, in the order of the vector method's ``steps``."""
    steps = tuple(steps)
    segments = []
    for link, base, point in segment_order(scene, steps):
        motion = analysis.links[link]
        B, P = analysis.points[base].position, analysis.points[point].position
        assert B is not None and P is not None
        assert motion.omega is not None and motion.alpha is not None
        r = np.asarray(P) - np.asarray(B)
        segments.append(
            {
                "link": link,
                "base": base,
                "point": point,
                "velocity": omega_cross(motion.omega, r).tolist(),
                "tangential": omega_cross(motion.alpha, r).tolist(),
                "normal": normal_acceleration(motion.omega, r).tolist(),
            }
        )
    return {"segments": segments, "sliding": _sliding_order(steps)}

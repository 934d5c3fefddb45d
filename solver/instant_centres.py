"""Instant centres of every pair of links (Kennedy), from their velocity fields.

Link i's velocity field is v(P) = V_i + omega_i k x P; the instant centre of i and j is the point
where the two fields agree, P = k x (V_i - V_j) / (omega_i - omega_j), or a direction at infinity
where the two links translate relative to each other.
"""

from __future__ import annotations

from dataclasses import dataclass
from itertools import combinations

import numpy as np

from solver.assembly import DriverInput, Motion, assemble
from solver.poles import POLE_TOLERANCE
from solver.rigid import Array, perp
from solver.scene import LinkageScene
from solver.topology import Plan


@dataclass(frozen=True)
class InstantCentre:
    """The instant centre of links i and j: a point, or a direction at infinity (relative
    translation); both ``None`` when the two links are at rest relative to each other."""

    links: tuple[str, str]
    position: Array | None
    direction: Array | None


def instant_centre(
    link_i: str, V_i: Array, omega_i: float, link_j: str, V_j: Array, omega_j: float, size: float
) -> InstantCentre:
    """The point P with v_i(P) = v_j(P): P = k x (V_i - V_j) / (omega_i - omega_j).

    ``V`` is the velocity of the link's point at the world origin (v_A - omega k x A), so each
    link's velocity field is v(P) = V + omega k x P.
    """
    dv = V_i - V_j
    dw = omega_i - omega_j
    speed = float(np.hypot(*dv))
    reference = float(np.hypot(*V_i) + np.hypot(*V_j)) + (abs(omega_i) + abs(omega_j)) * size
    if speed + abs(dw) * size <= POLE_TOLERANCE * reference:  # at rest relative to each other
        return InstantCentre((link_i, link_j), None, None)
    if abs(dw) * size <= POLE_TOLERANCE * (speed + abs(dw) * size):  # relative translation
        return InstantCentre((link_i, link_j), None, perp(dv) / speed)
    return InstantCentre((link_i, link_j), perp(dv) / dw, None)


def instant_centres(scene: LinkageScene, plan: Plan, motion: Motion) -> list[InstantCentre]:
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

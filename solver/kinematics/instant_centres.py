"""Instant centres of every pair of links (Kennedy), from their velocity fields.

Link i's velocity field is v(P) = V_i + omega_i k x P; the instant centre of i and j is the point
where the two fields agree, P = k x (V_i - V_j) / (omega_i - omega_j), or a direction at infinity
where the two links translate relative to each other.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from solver.kinematics.poles import POLE_TOLERANCE
from solver.kinematics.rigid import Array, perp


@dataclass(frozen=True)
class InstantCentre:
    """The instant centre of links i and j: a point, or a direction at infinity (relative
    translation); both ``None`` when the two links are at rest relative to each other."""

    links: tuple[str, str]
    position: Array | None
    direction: Array | None


def centres_of_pairs(
    pairs: Sequence[tuple[str, str]],
    V_i: Array,
    omega_i: Array,
    V_j: Array,
    omega_j: Array,
    size: float,
) -> list[InstantCentre]:
    """The point P with v_i(P) = v_j(P) for each pair (i, j) (row k of the (K, 2) ``V`` and (K,)
    ``omega`` arrays): P = k x (V_i - V_j) / (omega_i - omega_j).

    ``V`` is the velocity of the link's point at the world origin (v_A - omega k x A), so each
    link's velocity field is v(P) = V + omega k x P.
    """
    dv = V_i - V_j
    dw = omega_i - omega_j
    speed = np.hypot(dv[:, 0], dv[:, 1])
    reference = np.hypot(V_i[:, 0], V_i[:, 1]) + np.hypot(V_j[:, 0], V_j[:, 1])
    reference += (np.abs(omega_i) + np.abs(omega_j)) * size
    turning = np.abs(dw) * size
    at_rest = speed + turning <= POLE_TOLERANCE * reference  # relative to each other
    translating = turning <= POLE_TOLERANCE * (speed + turning)
    normal = perp(dv)
    centres = []
    for k, links in enumerate(pairs):
        if at_rest[k]:
            centres.append(InstantCentre(links, None, None))
        elif translating[k]:
            centres.append(InstantCentre(links, None, normal[k] / speed[k]))
        else:
            centres.append(InstantCentre(links, normal[k] / dw[k], None))
    return centres

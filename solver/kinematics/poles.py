"""Velocity poles and acceleration poles of a moving link.

A pole that does not exist (a translating link, a link at rest) is ``None``: the threshold
``POLE_TOLERANCE`` compares omega L (or sqrt(omega^4 + alpha^2) L) with the point's velocity
(acceleration), so rounding noise in the rate of a translating link does not produce a pole a
million kilometres away.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from solver.kinematics.rigid import Array, dot, perp

POLE_TOLERANCE = 1e-10


@dataclass(frozen=True)
class Poles:
    """Poles over samples: ``position`` (N, 2) is meaningful where ``exists`` (N,) is true."""

    position: Array
    exists: Array

    def at(self, k: int) -> Array | None:
        return self.position[k] if self.exists[k] else None


def velocity_poles(X: Array, v_X: Array, omega: Array, size: float) -> Poles:
    """From v_X = omega x r_PX: P = X + (k x v_X) / omega, where the link turns."""
    speed = np.sqrt(dot(v_X, v_X))
    turning = (omega != 0.0) & (
        np.abs(omega) * size > POLE_TOLERANCE * (speed + np.abs(omega) * size)
    )
    r_XP = perp(v_X)
    r_XP /= np.where(turning, omega, 1.0)[..., None]
    return Poles(X + r_XP, turning)


def acceleration_poles(X: Array, a_X: Array, omega: Array, alpha: Array, size: float) -> Poles:
    """From a_X = alpha x r_GX - omega^2 r_GX: r_GX = M^-1 a_X with M = [[-w^2, -a], [a, -w^2]].

    M^-1 = [[-w^2, a], [-a, -w^2]] / (w^4 + a^2), so G = X - M^-1 a_X.
    """
    det = omega**4 + alpha**2
    rate = np.sqrt(det)
    magnitude = np.sqrt(dot(a_X, a_X))
    exists = (det != 0.0) & (rate * size > POLE_TOLERANCE * (magnitude + rate * size))
    safe = np.where(exists, det, 1.0)
    w2 = omega**2
    r_GX = np.empty_like(a_X)
    r_GX[..., 0] = (-w2 * a_X[..., 0] + alpha * a_X[..., 1]) / safe
    r_GX[..., 1] = (-alpha * a_X[..., 0] - w2 * a_X[..., 1]) / safe
    return Poles(X - r_GX, exists)

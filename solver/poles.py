"""Velocity poles, acceleration poles, instant centres (Kennedy), and four-bar classification.

A pole that does not exist (a translating link, a link at rest) is ``None``: the threshold
``POLE_TOLERANCE`` compares omega L (or sqrt(omega^4 + alpha^2) L) with the point's velocity
(acceleration), so rounding noise in the rate of a translating link does not produce a pole a
million kilometres away.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from solver.rigid import Array, dot, perp

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


@dataclass(frozen=True)
class FourBarLoop:
    """A ground-crank-coupler-rocker loop: its Grashof class and transmission angle (rad)."""

    links: tuple[str, str, str, str]
    lengths: tuple[float, float, float, float]
    grashof: str
    transmission_angle: float


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


def transmission_angle(B: Array, C: Array, D: Array) -> float:
    """The angle BCD between coupler CB and rocker CD at their joint C (0..pi)."""
    u, w = B - C, D - C
    return float(np.arctan2(abs(u[0] * w[1] - u[1] * w[0]), u @ w))

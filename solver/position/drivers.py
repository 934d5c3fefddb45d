"""Driver motion: a driver's rotation from the drawn pose, omega and alpha at given times.

phi(t) = phi_0 + omega t + alpha t^2 / 2 for a constant alpha (phi_0 the turn from the drawn
pose to ``angle_deg``), or the driver's ``angle_law``.
"""

from __future__ import annotations

import math
from typing import TypeVar, cast

import numpy as np

from solver.errors import InvalidScene
from solver.kinematics.rigid import Array
from solver.model.laws import parse_time_law
from solver.model.scene import Driver, LinkageScene
from solver.position.assembly import DriverInput

T = TypeVar("T", float, Array)


def drawn_angle(scene: LinkageScene, link: str) -> float:
    """The drawn angle of ``link``, atan2 of the vector from its first point to its second, once
    per scene (kept in its ``memo``)."""
    angles = scene.memo.setdefault("drawn_angles", {})
    angle = angles.get(link)
    if angle is None:
        points = scene.links[link].points
        d = scene.drawn(points[1]) - scene.drawn(points[0])
        angle = angles[link] = math.atan2(d[1], d[0])
    return cast(float, angle)


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
    turn, omega = _uniformly_accelerated(_start_turn(scene, driver, wrap), driver, times)
    return DriverInput(turn, omega, np.full(times.size, driver.alpha))


def _uniformly_accelerated(start: float, driver: Driver, t: T) -> tuple[T, T]:
    """phi = phi_0 + omega t + alpha t^2 / 2 and its rate omega + alpha t, at a time ``t`` (a
    float) or at times (an array): the same operations either way, so the same numbers."""
    return (
        start + driver.omega * t + 0.5 * driver.alpha * (t * t),
        driver.omega + driver.alpha * t,
    )


def driver_input(
    scene: LinkageScene, driver: Driver, time: float, wrap: bool = True
) -> tuple[float, float, float]:
    """(rotation from the drawn pose, omega, alpha) of a driver at one instant."""
    if driver.angle_law is None:  # in floats (numpy's one-sample arrays cost a microsecond a step)
        turn, omega = _uniformly_accelerated(_start_turn(scene, driver, wrap), driver, float(time))
        return turn, omega, float(driver.alpha)
    at = driver_motion(scene, driver, np.array([time]), wrap)
    return float(at.theta[0]), float(at.omega[0]), float(at.alpha[0])


def driver_inputs_over_time(scene: LinkageScene, times: Array) -> list[DriverInput]:
    """Every driver's rotation from the drawn pose and its rates at each of ``times``."""
    return [driver_motion(scene, driver, times) for driver in scene.drivers]

"""A cycle's figures from a full-revolution sweep at constant driver speed.

With N samples equally spaced in the driver angle (so equally spaced in time, dt = T / N):

    period T = 2 pi / |omega|        mean torque = (1/N) sum M        mean power = (1/N) sum M omega
    work of a load W = T (1/N) sum P_load
    E(theta) = integral of (M - mean M) d theta (trapezoids; it returns to 0 after a turn)
    energy fluctuation = max E - min E        flywheel inertia = fluctuation / (k omega^2)

The rectangle rule is the trapezoid rule of a periodic function: exact to rounding for smooth
loads, of second order where a load law has a kink.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from solver.dynamics.analysis import LinkageDynamics
from solver.dynamics.loads import AppliedForce, AppliedMoment


@dataclass(frozen=True)
class Cycle:
    period: float
    mean_torque: float
    mean_power: float
    work: dict[str, float]
    energy_fluctuation: float
    flywheel_inertia: float | None


def cycle_figures(
    dynamics: LinkageDynamics, omega: float, speed_fluctuation: float | None = None
) -> Cycle:
    """The figures of one revolution of the (single) driver turning at constant ``omega``."""
    driver = dynamics.drivers[0]
    n = driver.torque.size
    period = 2.0 * math.pi / abs(omega)
    mean_torque = float(np.mean(driver.torque))
    excess = driver.torque - mean_torque
    step = 2.0 * math.pi / n
    energy = np.concatenate([[0.0], np.cumsum(0.5 * (excess + np.roll(excess, -1)) * step)])
    fluctuation = float(np.max(energy) - np.min(energy))
    loads: list[AppliedForce | AppliedMoment] = [*dynamics.forces.forces, *dynamics.forces.moments]
    return Cycle(
        period,
        mean_torque,
        float(np.mean(driver.power)),
        {load.name: float(np.mean(load.power)) * period for load in loads},
        fluctuation,
        None if speed_fluctuation is None else fluctuation / (speed_fluctuation * omega**2),
    )

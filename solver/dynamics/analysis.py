"""The dynamics of a solved motion: Newton-Euler forces, driver torques checked by the power
balance, energy and centre of mass (the quantities ``forces`` and ``energy`` of dynamics-v1)."""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from solver.assembly import Motion
from solver.dynamics.energy import Energy, energy, power_balance_torque
from solver.dynamics.loads import dynamics_of
from solver.dynamics.newton_euler import ForceAnalysis, inverse_dynamics
from solver.rigid import Array
from solver.scene import LinkageScene


@dataclass(frozen=True)
class DriverLoad:
    """A driver's torque on its link, its power M omega, and the torque again from the power
    balance (NaN where omega = 0, or where several drivers share the power)."""

    link: str
    torque: Array
    power: Array
    torque_from_power_balance: Array


@dataclass(frozen=True)
class LinkageDynamics:
    forces: ForceAnalysis
    drivers: list[DriverLoad]
    energy: Energy
    equivalent_inertia: Array  # 2 T / omega_1^2, NaN where omega_1 = 0 (or without driver)
    times: Array


def linkage_dynamics(
    scene: LinkageScene,
    motion: Motion,
    times: Array,
    singular: Array | None = None,
    cyclic: bool = True,
) -> LinkageDynamics:
    """Everything dynamics-v1 reports, at every sample of ``motion`` (accelerations required)."""
    result = inverse_dynamics(scene, motion, times, singular, cyclic)
    gravity = np.array(dynamics_of(scene).gravity)
    drivers = []
    for driver in scene.drivers:
        omega = motion.links[driver.link].omega
        assert omega is not None
        torque = result.torques[driver.link]
        balance = np.full(times.size, np.nan)
        if len(scene.drivers) == 1:
            balance = power_balance_torque(
                result.elements, result.forces, result.moments, gravity, omega
            )
        drivers.append(DriverLoad(driver.link, torque, torque * omega, balance))
    energies = energy(result.elements, gravity, times.size)
    inertia = np.full(times.size, np.nan)
    if scene.drivers:
        omega = motion.links[scene.drivers[0].link].omega
        assert omega is not None
        inertia = energies.equivalent_inertia(omega)
    return LinkageDynamics(result, drivers, energies, inertia, times)


def sweep_times(scene: LinkageScene, driver_angle: Array, omega: float) -> Array:
    """The time t of each sample of a revolution sweep, for the load expressions: the scene's
    time plus the time the first driver takes from the first sample at its omega (held over the
    sweep; the scene's time throughout if it does not turn)."""
    if omega == 0.0 or not math.isfinite(omega):
        return np.full(driver_angle.size, scene.time)
    return scene.time + (driver_angle - driver_angle[0]) / omega

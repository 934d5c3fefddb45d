"""The dynamics of a solved motion: Newton-Euler forces, driver torques checked by the power
balance, energy and centre of mass (the quantities ``forces`` and ``energy`` of dynamics-v1)."""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from solver.dynamics.energy import Energy, energy, power_balance_torque
from solver.dynamics.loads import dynamics_of
from solver.dynamics.newton_euler import ForceAnalysis, inverse_dynamics, neighbour_mean
from solver.dynamics.virtual_power import partial_motion, virtual_power_torque
from solver.kinematics.rigid import Array
from solver.model.scene import LinkageScene
from solver.position.assembly import Motion


@dataclass(frozen=True)
class DriverLoad:
    """A driver's torque on its link, its power M omega, and the torque again without the joint
    forces: from the power balance (one driver) or the virtual power of the driver's partial
    motion (several); NaN where omega = 0 or that partial motion is undefined."""

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
    anchor: int = 0,
) -> LinkageDynamics:
    """Everything dynamics-v1 reports, at every sample of ``motion`` (accelerations required;
    ``singular`` samples take their neighbours' mean, ``anchor`` is the sample where a sweep's
    motion is on its drawn branch)."""
    singular = np.array([], dtype=int) if singular is None else np.asarray(singular)
    result = inverse_dynamics(scene, motion, times, singular, cyclic)
    gravity = np.array(dynamics_of(scene).gravity)
    drivers = []
    for index, driver in enumerate(scene.drivers):
        omega = motion.links[driver.link].omega
        assert omega is not None
        torque = result.torques[driver.link]
        check = np.where(
            omega != 0.0, _independent_torque(scene, motion, result, gravity, index, anchor), np.nan
        )
        neighbour_mean(check, singular, cyclic)
        drivers.append(DriverLoad(driver.link, torque, torque * omega, check))
    energies = energy(result.elements, gravity, times.size)
    inertia = np.full(times.size, np.nan)
    if scene.drivers:
        omega = motion.links[scene.drivers[0].link].omega
        assert omega is not None
        inertia = energies.equivalent_inertia(omega)
    return LinkageDynamics(result, drivers, energies, inertia, times)


def _independent_torque(
    scene: LinkageScene,
    motion: Motion,
    result: ForceAnalysis,
    gravity: Array,
    driver: int,
    anchor: int,
) -> Array:
    """Driver ``driver``'s torque without the joint forces: the power balance of a single
    driver, the virtual power of its partial motion when there are several."""
    loads = (result.elements, result.forces, result.moments)
    if len(scene.drivers) == 1:
        omega = motion.links[scene.drivers[0].link].omega
        assert omega is not None
        return power_balance_torque(*loads, gravity, omega)
    partial = partial_motion(scene, motion, driver, anchor)
    return virtual_power_torque(partial, motion, scene.size, *loads, gravity)


def sweep_times(scene: LinkageScene, driver_angle: Array, omega: float) -> Array:
    """The time t of each sample of a revolution sweep, for the load expressions: the scene's
    time plus the time the first driver takes from the first sample at its omega (held over the
    sweep; the scene's time throughout if it does not turn)."""
    if omega == 0.0 or not math.isfinite(omega):
        return np.full(driver_angle.size, scene.time)
    return scene.time + (driver_angle - driver_angle[0]) / omega

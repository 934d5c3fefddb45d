"""Energy, centre of mass and the power balance of the moving masses.

    T = sum (m v_G^2 + I omega^2) / 2          V = - sum m g . r_G
    dT/dt = sum (m a_G . v_G + I omega alpha)   dV/dt = - sum m g . v_G

The power balance gives the driving torque without any joint force (frictionless joints do no
work): M omega_driver = dT/dt + dV/dt - sum F . v_P - sum M omega_link.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from solver.dynamics.loads import AppliedForce, AppliedMoment, MassElement
from solver.kinematics.rigid import Array, dot


@dataclass(frozen=True)
class Energy:
    """Kinetic and potential energy and the centre of mass of all moving masses, per sample.

    The centre of mass is None without mass.
    """

    kinetic: Array
    potential: Array
    mass: float
    center: Array | None
    center_velocity: Array | None
    center_acceleration: Array | None

    def equivalent_inertia(self, omega: Array) -> Array:
        """2 T / omega^2 (the inertia reduced to a link turning at omega); NaN where omega = 0."""
        with np.errstate(divide="ignore", invalid="ignore"):
            return np.where(
                omega != 0.0, 2.0 * self.kinetic / np.where(omega != 0, omega, 1) ** 2, np.nan
            )


def energy(elements: list[MassElement], gravity: Array, samples: int) -> Energy:
    kinetic, potential = np.zeros(samples), np.zeros(samples)
    mass = 0.0
    first = [np.zeros((samples, 2)) for _ in range(3)]  # sum m r, sum m v, sum m a
    for e in elements:
        kinetic += 0.5 * (e.mass * dot(e.v, e.v) + e.inertia * e.omega**2)
        potential -= e.mass * (e.p @ gravity)
        mass += e.mass
        for total, vector in zip(first, (e.p, e.v, e.a), strict=True):
            total += e.mass * vector
    if mass == 0.0:
        return Energy(kinetic, potential, 0.0, None, None, None)
    return Energy(kinetic, potential, mass, *(total / mass for total in first))


def energy_rate(elements: list[MassElement], gravity: Array, samples: int) -> Array:
    """d(T + V)/dt at every sample."""
    rate = np.zeros(samples)
    for e in elements:
        rate += e.mass * dot(e.a - gravity, e.v) + e.inertia * e.omega * e.alpha
    return rate


def load_power(forces: list[AppliedForce], moments: list[AppliedMoment], samples: int) -> Array:
    """The power of the external forces and moments at every sample."""
    power = np.zeros(samples)
    for force in forces:
        power += force.power
    for moment in moments:
        power += moment.power
    return power


def power_balance_torque(
    elements: list[MassElement],
    forces: list[AppliedForce],
    moments: list[AppliedMoment],
    gravity: Array,
    omega: Array,
) -> Array:
    """The single driver's torque (dT/dt + dV/dt - P_loads) / omega; NaN where omega = 0."""
    n = omega.size
    net = energy_rate(elements, gravity, n) - load_power(forces, moments, n)
    with np.errstate(divide="ignore", invalid="ignore"):
        return np.where(omega != 0.0, net / np.where(omega != 0.0, omega, 1.0), np.nan)

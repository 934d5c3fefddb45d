"""The dynamics of a solved motion: Newton-Euler forces, driver torques checked by the power
balance, energy and centre of mass (the quantities ``forces`` and ``energy`` of dynamics-v1)."""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from solver.dynamics.energy import Energy, energy, power_balance_torque
from solver.dynamics.friction import FrictionSolution, has_friction, solve_with_friction
from solver.dynamics.loads import dynamics_of, mass_elements
from solver.dynamics.newton_euler import (
    ForceAnalysis,
    force_analysis,
    inverse_dynamics,
    neighbour_mean,
)
from solver.dynamics.virtual_power import partial_motion, virtual_power_torque
from solver.kinematics.rigid import Array
from solver.model.scene import LinkageScene
from solver.position.assembly import Motion

# A mean input power below this fraction of the mean absolute input power is zero (rounding).
NET_POWER = 1e-9


@dataclass(frozen=True)
class DriverLoad:
    """A driver's torque on its link, its power M omega, and the torque again without the joint
    forces: from the power balance (one driver) or the virtual power of the driver's partial
    motion (several); NaN where omega = 0 or that partial motion is undefined."""

    link: str
    torque: Array
    power: Array
    torque_from_power_balance: Array
    torque_frictionless: Array | None = None  # with friction at some joint
    omega: Array | None = None  # the driver's


@dataclass(frozen=True)
class Locking:
    """Where the mechanism locks (the first sample) and why, in words."""

    sample: int
    driver_angle: float  # rad, the first driver's angle as in the response
    reason: str


@dataclass(frozen=True)
class LinkageDynamics:
    forces: ForceAnalysis
    drivers: list[DriverLoad]
    energy: Energy
    equivalent_inertia: Array  # 2 T / omega_1^2, NaN where omega_1 = 0 (or without driver)
    times: Array
    friction: FrictionSolution | None = None  # with friction at some joint
    statics: bool = False


def linkage_dynamics(
    scene: LinkageScene,
    motion: Motion,
    times: Array,
    singular: Array | None = None,
    cyclic: bool = True,
    anchor: int = 0,
    statics: bool = False,
) -> LinkageDynamics:
    """Everything dynamics-v1 reports, at every sample of ``motion`` (accelerations required;
    ``singular`` samples take their neighbours' mean, ``anchor`` is the sample where a sweep's
    motion is on its drawn branch). ``statics``: the masses count only through their weight.
    With friction at some joint the forces and torques are those with friction
    (``solve_with_friction``), each driver keeping its frictionless torque too."""
    singular = np.array([], dtype=int) if singular is None else np.asarray(singular)
    frictionless = inverse_dynamics(scene, motion, times, singular, cyclic, statics)
    gravity = np.array(dynamics_of(scene).gravity)
    result, friction = frictionless, None
    if has_friction(scene):
        friction = solve_with_friction(
            scene, motion, frictionless.system, frictionless.solution, singular, cyclic
        )
        result = force_analysis(
            scene,
            motion,
            frictionless.system,
            friction.solution,
            frictionless.elements,
            frictionless.forces,
            frictionless.moments,
            friction.forces,
            friction.moments,
        )
    drivers = []
    for index, driver in enumerate(scene.drivers):
        omega = motion.links[driver.link].omega
        assert omega is not None
        torque = result.torques[driver.link]
        check = np.where(
            omega != 0.0,
            _independent_torque(scene, motion, frictionless, gravity, index, anchor),
            np.nan,
        )
        if friction is not None:  # the friction's power -P_f is supplied by the one driver
            if len(scene.drivers) == 1:
                with np.errstate(divide="ignore", invalid="ignore"):
                    check = check - friction.power / omega
            else:  # its share among several drivers is not defined by the power balance
                check = np.full_like(check, np.nan)
        neighbour_mean(check, singular, cyclic)
        without = None if friction is None else frictionless.torques[driver.link]
        drivers.append(DriverLoad(driver.link, torque, torque * omega, check, without, omega))
    energies = energy(
        mass_elements(scene, motion) if statics else result.elements, gravity, times.size
    )
    inertia = np.full(times.size, np.nan)
    if scene.drivers:
        omega = motion.links[scene.drivers[0].link].omega
        assert omega is not None
        inertia = energies.equivalent_inertia(omega)
    return LinkageDynamics(result, drivers, energies, inertia, times, friction, statics)


def self_locking(scene: LinkageScene, dynamics: LinkageDynamics, angle: Array) -> Locking | None:
    """The first sample where the mechanism locks by friction, with the driver ``angle`` (rad,
    per sample) and the joints whose friction locks it, in words; None where it never does."""
    friction = dynamics.friction
    if friction is None or not friction.locked.any():
        return None
    k = int(np.flatnonzero(friction.locked)[0])
    names = [_joint_words(scene, i) for i in friction.causes.get(k, ())]
    by = " and ".join(names) if names else "the joints together"
    degrees = math.degrees(float(angle[k]))
    return Locking(
        k,
        float(angle[k]),
        f"self-locking at driver angle {degrees:.6g} deg: the friction at {by} grows faster "
        "than the force that drives it (the force lies inside the friction cone or circle), so "
        "the equations with friction change sign there and no finite driving torque moves the "
        "mechanism in its prescribed sense",
    )


def mechanical_advantage(dynamics: LinkageDynamics, omega: Array) -> dict[str, Array]:
    """Each named load's ratio to the torque of the driver turning at ``omega`` that holds it
    alone, from virtual work (T omega + Q v_Q = 0): MA = -Q / T = omega / v_Q, with v_Q the
    load's velocity (omega_L of a moment; v_P . F / |F| of a force, then in 1/m); NaN where v_Q
    = 0 (a toggle: the load is held by no torque) or a force is zero (no direction)."""
    out = {}
    with np.errstate(divide="ignore", invalid="ignore"):
        for force in dynamics.forces.forces:
            size = np.hypot(force.force[:, 0], force.force[:, 1])
            speed = force.power / size
            out[force.name] = np.where((size > 0) & (speed != 0), omega / speed, np.nan)
        for moment in dynamics.forces.moments:
            out[moment.name] = np.where(moment.omega != 0, omega / moment.omega, np.nan)
    return out


def efficiency(dynamics: LinkageDynamics, omega: float) -> float | None:
    """eta = mean(M_0 omega) / mean(M omega) over a revolution at constant ``omega``: the
    frictionless mean input power over that with friction, of a driven machine (None where the
    frictionless mean input power is not positive, to ``NET_POWER`` of the mean absolute input
    power, or the mechanism locks)."""
    driver = dynamics.drivers[0]
    if driver.torque_frictionless is None:
        return None
    ideal = float(np.mean(driver.torque_frictionless)) * omega
    real = float(np.mean(driver.torque)) * omega
    # A machine whose loads do no net work (a constant moment on a rocker, the weights) has a
    # frictionless mean input power of rounding: not a driven machine either.
    gross = float(np.mean(np.abs(driver.torque_frictionless))) * abs(omega)
    if not (math.isfinite(real) and ideal > NET_POWER * gross and real > 0.0):
        return None
    return ideal / real


def _joint_words(scene: LinkageScene, index: int) -> str:
    joint = scene.joints[index]
    friction = joint.friction
    assert friction is not None
    if joint.type == "revolute":
        return (
            f"the pin {joint.point} (friction circle mu r = {friction.coefficient:.6g} x "
            f"{friction.pin_radius:.6g} m)"
        )
    angle = math.degrees(math.atan(friction.coefficient))
    return (
        f"the {joint.type} {joint.point} (mu = {friction.coefficient:.6g}, friction angle "
        f"{angle:.6g} deg)"
    )


def non_convergence(dynamics: LinkageDynamics, angle: Array) -> str | None:
    """A sentence where the friction iteration did not converge (outside self-locking)."""
    friction = dynamics.friction
    if friction is None:
        return None
    missing = ~friction.converged & ~friction.locked
    if not missing.any():
        return None
    k = np.flatnonzero(missing)
    return (
        f"friction: the iteration from the frictionless answer did not converge in "
        f"{friction.iterations} steps at {k.size} pose(s), first at driver angle "
        f"{math.degrees(float(angle[k[0]])):.6g} deg; the torque with friction is null there"
    )


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

"""Dynamics-v1 quantities in the result bodies: ``forces`` and ``energy`` of /analyze, /sweep and
a Newton-Euler worked solution, a revolution's ``cycle``, and the /balance body.

``joints`` becomes every joint of the scene in its order, each with its force (the slider and
prismatic joints keep their kinematic parts when ``components`` is asked too), ``drivers`` their
torque, power and power-balance torque, and the frame's force and moment; ``energy`` and
``center_of_mass``. In a sweep each is an array over the samples; a value that does not exist
(the power-balance torque where omega = 0) is null.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import Any

import numpy as np

from solver.analysis.instant import LinkageAnalysis
from solver.analysis.sweeps import Sweep, TimeSweep
from solver.dynamics.analysis import (
    LinkageDynamics,
    efficiency,
    linkage_dynamics,
    mechanical_advantage,
    non_convergence,
    self_locking,
    sweep_times,
)
from solver.dynamics.balance import Balance
from solver.dynamics.cycle import cycle_figures
from solver.dynamics.loads import link_state
from solver.kinematics.rigid import Array
from solver.model.quantities import DYNAMIC_QUANTITIES
from solver.model.scene import LinkageScene
from solver.position.drivers import driver_input

JSON = dict[str, Any]
Convert = Callable[[Array], Any]


def _instant(value: Array) -> Any:
    """Sample 0 of an array over samples: a number or a vector; null for NaN."""
    first = value[0]
    if np.isnan(first).any():  # a torque, force or moment that does not exist (self-locking)
        return None
    if np.ndim(first) == 0:
        return float(first)
    return [float(x) for x in first]


def _samples(value: Array) -> Any:
    """The whole array (orjson serialises it); a list with nulls where it has NaN (a vector
    with NaN is null)."""
    if np.isnan(value).any():
        if value.ndim == 2:
            return [None if np.isnan(x).any() else [float(c) for c in x] for x in value]
        return [None if np.isnan(x) else float(x) for x in value]
    return np.ascontiguousarray(value, dtype=float)


def _add(body: JSON, dynamics: LinkageDynamics, wanted: frozenset[str], convert: Convert) -> None:
    if "forces" in wanted:
        kinematic = iter(body.get("joints", []))
        joints = []
        for joint in dynamics.forces.joints:
            out: JSON = {"point": joint.joint.point, "type": joint.joint.type}
            out["links"] = list(joint.joint.links)
            if joint.joint.type != "revolute" and "components" in wanted:
                out.update(next(kinematic))
            out["force"] = convert(joint.force)
            if joint.moment is not None:
                out["moment"] = convert(joint.moment)
            joints.append(out)
        body["joints"] = joints
        drivers = []
        for d in dynamics.drivers:
            out = {
                "link": d.link,
                "torque": convert(d.torque),
                "power": convert(d.power),
                "torque_from_power_balance": convert(d.torque_from_power_balance),
            }
            if d.torque_frictionless is not None:
                out["torque_frictionless"] = convert(d.torque_frictionless)
            drivers.append(out)
        body["drivers"] = drivers
        if dynamics.statics and len(dynamics.drivers) == 1:
            omega = dynamics.drivers[0].omega
            assert omega is not None
            body["mechanical_advantage"] = {
                name: convert(value)
                for name, value in mechanical_advantage(dynamics, omega).items()
            }
        body["frame_force"] = convert(dynamics.forces.frame_force)
        body["frame_moment"] = convert(dynamics.forces.frame_moment)
    if "energy" in wanted:
        e = dynamics.energy
        body["energy"] = {
            "kinetic": convert(e.kinetic),
            "potential": convert(e.potential),
            "equivalent_inertia": convert(dynamics.equivalent_inertia),
        }
        body["center_of_mass"] = {
            "mass": e.mass,
            "position": None if e.center is None else convert(e.center),
            "velocity": None if e.center_velocity is None else convert(e.center_velocity),
            "acceleration": (
                None if e.center_acceleration is None else convert(e.center_acceleration)
            ),
        }


def _friction(body: JSON, dynamics: LinkageDynamics, angle: Array) -> None:
    """With friction: why the iteration did not converge (a warning), and a locking's words."""
    sentence = non_convergence(dynamics, angle)
    if sentence is not None:
        body["warnings"] = [*body.get("warnings", []), sentence]


def _driver_angle(scene: LinkageScene, result: LinkageAnalysis) -> Array:
    """The first driver's absolute angle (rad) at the instant (0 without drivers)."""
    if not scene.drivers:
        return np.zeros(1)
    return link_state(scene, result.motion, [scene.drivers[0].link])[scene.drivers[0].link][0]


def add_instant_dynamics(
    body: JSON, scene: LinkageScene, result: LinkageAnalysis, statics: bool = False
) -> JSON:
    """The /analyze body with the requested dynamic quantities added (unchanged without);
    ``statics``: the masses count only through their weight. With friction ``self_locking``
    is null or says why the mechanism locks at this pose."""
    wanted = result.quantities
    if wanted & set(DYNAMIC_QUANTITIES):
        dynamics = linkage_dynamics(scene, result.motion, np.array([scene.time]), statics=statics)
        _add(body, dynamics, wanted, _instant)
        if dynamics.friction is not None and "forces" in wanted:
            angle = _driver_angle(scene, result)
            _friction(body, dynamics, angle)
            locking = self_locking(scene, dynamics, angle)
            body["self_locking"] = None if locking is None else locking.reason
    return body


def add_dynamics_results(
    body: JSON, scene: LinkageScene, result: LinkageAnalysis, statics: bool = False
) -> JSON:
    """The /analyze body of a worked solution with ``forces`` and ``energy`` added (the paths
    of its Newton-Euler steps' numbers point into them; ``statics``: of the static analysis)."""
    dynamics = linkage_dynamics(scene, result.motion, np.array([scene.time]), statics=statics)
    _add(body, dynamics, result.quantities | set(DYNAMIC_QUANTITIES), _instant)
    return body


def add_sweep_dynamics(
    body: JSON,
    result: Sweep | TimeSweep,
    speed_fluctuation: float | None = None,
    statics: bool = False,
) -> JSON:
    """The /sweep body with the requested dynamic quantities added, and a revolution's ``cycle``
    (with ``forces``, one driver turning fully at constant omega; with friction its
    ``efficiency`` and ``self_locking``). ``statics``: the masses count only through their
    weight."""
    wanted = result.quantities
    if not wanted & set(DYNAMIC_QUANTITIES):
        return body
    scene, motion = result.scene, result.motion
    if isinstance(result, TimeSweep):
        dynamics = linkage_dynamics(scene, motion, result.time, cyclic=False, statics=statics)
        _add(body, dynamics, wanted, _samples)
        if dynamics.friction is not None and "forces" in wanted and scene.drivers:
            link = scene.drivers[0].link
            _friction(body, dynamics, link_state(scene, motion, [link])[link][0])
        return body
    omega = motion.links[result.driver].omega
    alpha = motion.links[result.driver].alpha
    assert omega is not None and alpha is not None
    times = sweep_times(scene, result.driver_angle, float(omega[0]))
    start = driver_input(scene, scene.drivers[0], scene.time)[0]  # as the sweep began
    anchor = int(np.argmin(np.abs(motion.links[result.driver].theta - start)))
    dynamics = linkage_dynamics(
        scene, motion, times, result.singular_samples, result.feasible, anchor, statics
    )
    _add(body, dynamics, wanted, _samples)
    if dynamics.friction is not None and "forces" in wanted:
        _friction(body, dynamics, result.driver_angle)
    if (
        "forces" in wanted
        and result.feasible
        and len(scene.drivers) == 1
        and omega[0] != 0.0
        and np.all(alpha == 0.0)
    ):
        cycle = cycle_figures(dynamics, float(omega[0]), speed_fluctuation)
        body["cycle"] = {
            "period": cycle.period,
            "mean_torque": cycle.mean_torque,
            "mean_power": cycle.mean_power,
            "work": cycle.work,
            "energy_fluctuation": cycle.energy_fluctuation,
            "flywheel_inertia": cycle.flywheel_inertia,
            "speed_fluctuation": speed_fluctuation,
        }
        if dynamics.friction is not None:  # a locked pose has no torque: no means either
            for key in ("mean_torque", "mean_power", "energy_fluctuation", "flywheel_inertia"):
                value = body["cycle"][key]
                body["cycle"][key] = None if value is None or math.isnan(value) else value
            locking = self_locking(scene, dynamics, result.driver_angle)
            body["cycle"]["efficiency"] = efficiency(dynamics, float(omega[0]))
            body["cycle"]["self_locking"] = (
                None
                if locking is None
                else {
                    "driver_angle_deg": math.degrees(locking.driver_angle),
                    "reason": locking.reason,
                }
            )
    return body


def balance_body(result: Balance) -> JSON:
    """The POST /balance body: where the counterweights go, the still centre of mass, and the
    balanced scene."""
    return {
        "counterweights": [
            {
                "link": w.link,
                "mass": w.mass,
                "pivot": w.pivot,
                "distance": w.distance,
                "offset": w.offset,
                "position": list(w.position),
            }
            for w in result.counterweights
        ],
        "center_of_mass": list(result.center_of_mass),
        "mass": result.mass,
        "scene": result.scene,
    }

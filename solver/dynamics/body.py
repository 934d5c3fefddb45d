"""Dynamics-v1 quantities in the result bodies: ``forces`` and ``energy`` of /analyze, /sweep and
a Newton-Euler worked solution, a revolution's ``cycle``, and the /balance body.

``joints`` becomes every joint of the scene in its order, each with its force (the slider and
prismatic joints keep their kinematic parts when ``components`` is asked too), ``drivers`` their
torque, power and power-balance torque, and the frame's force and moment; ``energy`` and
``center_of_mass``. In a sweep each is an array over the samples; a value that does not exist
(the power-balance torque where omega = 0) is null.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

import numpy as np

from solver.analysis.instant import LinkageAnalysis
from solver.analysis.sweeps import Sweep, TimeSweep
from solver.dynamics.analysis import LinkageDynamics, linkage_dynamics, sweep_times
from solver.dynamics.balance import Balance
from solver.dynamics.cycle import cycle_figures
from solver.kinematics.rigid import Array
from solver.model.quantities import DYNAMIC_QUANTITIES
from solver.model.scene import LinkageScene
from solver.position.drivers import driver_input

JSON = dict[str, Any]
Convert = Callable[[Array], Any]


def _instant(value: Array) -> Any:
    """Sample 0 of an array over samples: a number or a vector; null for NaN."""
    first = value[0]
    if np.ndim(first) == 0:
        return None if np.isnan(first) else float(first)
    return [float(x) for x in first]


def _samples(value: Array) -> Any:
    """The whole array (orjson serialises it); a list with nulls where it has NaN."""
    if np.isnan(value).any():
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
        body["drivers"] = [
            {
                "link": d.link,
                "torque": convert(d.torque),
                "power": convert(d.power),
                "torque_from_power_balance": convert(d.torque_from_power_balance),
            }
            for d in dynamics.drivers
        ]
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


def add_instant_dynamics(body: JSON, scene: LinkageScene, result: LinkageAnalysis) -> JSON:
    """The /analyze body with the requested dynamic quantities added (unchanged without)."""
    wanted = result.quantities
    if wanted & set(DYNAMIC_QUANTITIES):
        dynamics = linkage_dynamics(scene, result.motion, np.array([scene.time]))
        _add(body, dynamics, wanted, _instant)
    return body


def add_dynamics_results(body: JSON, scene: LinkageScene, result: LinkageAnalysis) -> JSON:
    """The /analyze body of a worked solution with ``forces`` and ``energy`` added (the paths
    of its Newton-Euler steps' numbers point into them)."""
    dynamics = linkage_dynamics(scene, result.motion, np.array([scene.time]))
    _add(body, dynamics, result.quantities | set(DYNAMIC_QUANTITIES), _instant)
    return body


def add_sweep_dynamics(
    body: JSON, result: Sweep | TimeSweep, speed_fluctuation: float | None = None
) -> JSON:
    """The /sweep body with the requested dynamic quantities added, and a revolution's ``cycle``
    (with ``forces``, one driver turning fully at constant omega)."""
    wanted = result.quantities
    if not wanted & set(DYNAMIC_QUANTITIES):
        return body
    scene, motion = result.scene, result.motion
    if isinstance(result, TimeSweep):
        dynamics = linkage_dynamics(scene, motion, result.time, cyclic=False)
        _add(body, dynamics, wanted, _samples)
        return body
    omega = motion.links[result.driver].omega
    alpha = motion.links[result.driver].alpha
    assert omega is not None and alpha is not None
    times = sweep_times(scene, result.driver_angle, float(omega[0]))
    start = driver_input(scene, scene.drivers[0], scene.time)[0]  # as the sweep began
    anchor = int(np.argmin(np.abs(motion.links[result.driver].theta - start)))
    dynamics = linkage_dynamics(
        scene, motion, times, result.singular_samples, result.feasible, anchor
    )
    _add(body, dynamics, wanted, _samples)
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

"""Solver results to the JSON shapes of the scene-v1 spec (plus documented extra outputs).

Only the requested quantities appear. Vectors are [x, y] (or [x, y, z]); a pole that does not
exist is null; sweep arrays follow ``driver_angle`` sample by sample.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import Any

import numpy as np

from solver.analysis import LinkageAnalysis, SlidingJoint
from solver.assembly import Motion
from solver.poles import Poles
from solver.relative_motion import MovingPointMotion
from solver.scene import LinkageScene
from solver.spatial import SpatialAnalysis
from solver.sweep import Sweep, TimeSweep

JSON = dict[str, Any]


def vector(value: np.ndarray | None) -> list[float] | None:
    return None if value is None else [float(x) for x in value]


def array(value: np.ndarray | None) -> np.ndarray | None:
    """A C-contiguous float array (what orjson serialises natively), or None."""
    return None if value is None else np.ascontiguousarray(value, dtype=float)


def _point(position: Any, velocity: Any, acceleration: Any, wanted: frozenset[str]) -> JSON:
    out: JSON = {}
    for key, value in (
        ("position", position),
        ("velocity", velocity),
        ("acceleration", acceleration),
    ):
        if key in wanted:
            out[key] = value
    return out


MOVING_POINT_FIELDS = {
    "position": ("position",),
    "velocity": ("velocity", "transport_velocity", "relative_velocity"),
    "acceleration": (
        "acceleration",
        "transport_acceleration",
        "relative_acceleration",
        "coriolis_acceleration",
    ),
    "components": (
        "transport_tangential",
        "transport_normal",
        "relative_tangential",
        "relative_normal",
        "omega_carrier",
        "alpha_carrier",
        "s",
        "s_dot",
        "s_ddot",
    ),
}


def moving_point_fields(
    motion: MovingPointMotion, wanted: frozenset[str], convert: Callable[[Any], Any]
) -> JSON:
    """The requested fields of a moving point (scalars as numbers, vectors converted)."""
    out: JSON = {}
    for quantity, names in MOVING_POINT_FIELDS.items():
        if quantity in wanted:
            for name in names:
                value = getattr(motion, name)
                out[name] = float(value) if np.ndim(value) == 0 else convert(value)
    return out


SLIDING_JOINT_PARTS = (
    "transport_velocity",
    "relative_velocity",
    "velocity",
    "transport_acceleration",
    "relative_acceleration",
    "coriolis_acceleration",
    "acceleration",
)


def sliding_joint_fields(joint: SlidingJoint, convert: Callable[[Any], Any]) -> JSON:
    """A slider or prismatic joint's parts (vectors converted; the guide's omega as is)."""
    out: JSON = {"point": joint.point, "type": joint.type, "links": list(joint.links)}
    omega = joint.omega_guide
    out["omega_guide"] = float(omega) if np.ndim(omega) == 0 else convert(omega)
    for name in SLIDING_JOINT_PARTS:
        out[name] = convert(getattr(joint, name))
    return out


def analysis_response(result: LinkageAnalysis) -> JSON:
    """The /analyze body of a linkage."""
    wanted = result.quantities
    body: JSON = {
        "points": {
            name: _point(vector(p.position), vector(p.velocity), vector(p.acceleration), wanted)
            for name, p in result.points.items()
        },
        "links": {},
    }
    for name, link in result.links.items():
        out: JSON = {}
        if "position" in wanted:
            out["angle"] = link.angle
        if "velocity" in wanted or "poles" in wanted:
            out["omega"] = link.omega
        if "acceleration" in wanted or "poles" in wanted:
            out["alpha"] = link.alpha
        if "poles" in wanted:
            out["velocity_pole"] = vector(link.velocity_pole)
            out["acceleration_pole"] = vector(link.acceleration_pole)
        body["links"][name] = out
    if "components" in wanted:
        body["joints"] = [sliding_joint_fields(j, vector) for j in result.joints]
    if result.moving_points:
        body["moving_points"] = {
            name: moving_point_fields(m, wanted, vector) for name, m in result.moving_points.items()
        }
    if "poles" in wanted:
        body["instant_centres"] = [
            {
                "links": list(c.links),
                "position": vector(c.position),
                "direction_at_infinity": vector(c.direction),
            }
            for c in result.instant_centres
        ]
    body["four_bar_loops"] = [
        {
            "links": dict(zip(("ground", "crank", "coupler", "rocker"), loop.links, strict=True)),
            "lengths": dict(
                zip(("ground", "crank", "coupler", "rocker"), loop.lengths, strict=True)
            ),
            "grashof": loop.grashof,
            "transmission_angle": loop.transmission_angle,
            "transmission_angle_deg": math.degrees(loop.transmission_angle),
        }
        for loop in result.four_bar_loops
    ]
    d = result.diagnostics
    body["diagnostics"] = {
        "condition_number": d.condition_number,
        "position_method": "closed-form dyads" if d.closed_form else "dyads and Newton-Raphson",
        "newton": [
            {
                "links": list(r.links),
                "converged": bool(np.all(r.converged)),
                "iterations": r.iterations,
                "residual_norm": r.residual_norm,
                "tolerance": r.tolerance,
                "relative_tolerance": r.relative_tolerance,
            }
            for r in d.newton
        ],
        "driver_angles_deg": d.driver_angles,
    }
    return body


def spatial_response(result: SpatialAnalysis, wanted: frozenset[str]) -> JSON:
    """The /analyze body of a spatial chain (with the five acceleration terms as an extra)."""
    body: JSON = {"bodies": {}, "points": {}}
    for name, b in result.bodies.items():
        out: JSON = {}
        if "velocity" in wanted:
            out["omega"] = vector(b.omega)
        if "acceleration" in wanted:
            out["alpha"] = vector(b.alpha)
        body["bodies"][name] = out
    for name, p in result.points.items():
        out = _point(vector(p.position), vector(p.velocity), vector(p.acceleration), wanted)
        if "components" in wanted:
            out["acceleration_terms"] = {
                "origin": vector(p.a_origin),
                "tangential": vector(p.tangential),
                "centripetal": vector(p.centripetal),
                "coriolis": vector(p.coriolis),
                "relative": vector(p.relative),
            }
        body["points"][name] = out
    return body


def _pole_list(poles: Poles) -> list[list[float] | None]:
    """[x, y] at each sample, null where the pole does not exist."""
    return [p if e else None for p, e in zip(poles.position.tolist(), poles.exists, strict=True)]


def _motion_arrays(
    scene: LinkageScene,
    motion: Motion,
    wanted: frozenset[str],
    joints: list[SlidingJoint],
    poles: dict[str, tuple[Poles, Poles]],
) -> JSON:
    """Points, links (with their poles) and slider parts of a vectorised motion, as the sweep
    arrays of the spec."""
    points = {
        name: _point(array(p.p), array(p.v), array(p.a), wanted)
        for name, p in motion.points.items()
        if name in scene.points
    }
    links: JSON = {}
    for name in scene.moving_links:
        link, on_link = motion.links[name], scene.links[name].points
        out: JSON = {}
        if "position" in wanted:
            out["angle"] = None
            if len(on_link) >= 2:
                d = motion.points[on_link[1]].p - motion.points[on_link[0]].p
                out["angle"] = array(np.arctan2(d[:, 1], d[:, 0]))
        if "velocity" in wanted:
            out["omega"] = array(link.omega)
        if "acceleration" in wanted:
            out["alpha"] = array(link.alpha)
        if name in poles:
            out["velocity_pole"], out["acceleration_pole"] = map(_pole_list, poles[name])
        links[name] = out
    body: JSON = {"points": points, "links": links}
    if "components" in wanted:
        body["joints"] = [sliding_joint_fields(j, array) for j in joints]
    return body


def sweep_response(result: Sweep) -> JSON:
    """The /sweep body: arrays sample by sample (numpy arrays, serialised by orjson)."""
    return {
        "driver": result.driver,
        "driver_angle": array(result.driver_angle),
        "samples": int(result.driver_angle.size),
        **_motion_arrays(
            result.scene, result.motion, result.quantities, result.joints, result.poles
        ),
        "feasible": result.feasible,
        "limits": list(result.limits),
        "singular_samples": [int(k) for k in result.singular_samples],
        **_newton_diagnostics(result.motion),
    }


def _newton_diagnostics(motion: Motion) -> JSON:
    """A sweep's Newton groups (if any): how Newton-Raphson went over all its samples."""
    if not motion.newton:
        return {}
    groups = [
        {
            "links": list(r.links),
            "iterations": r.iterations,
            "residual_norm": r.residual_norm,
            "tolerance": r.tolerance,
            "relative_tolerance": r.relative_tolerance,
        }
        for r in motion.newton
    ]
    return {"diagnostics": {"newton": groups}}


def time_sweep_response(result: TimeSweep) -> JSON:
    """The /sweep body for a time range: arrays follow ``time``."""
    wanted = result.quantities
    return {
        "time": array(result.time),
        "driver_angle": array(result.driver_angle),
        "samples": int(result.time.size),
        **_motion_arrays(result.scene, result.motion, wanted, result.joints, result.poles),
        "moving_points": {
            name: moving_point_fields(m, wanted, array) for name, m in result.moving_points.items()
        },
        "feasible": True,
        "limits": [],
    }

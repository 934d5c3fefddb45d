"""Results as data: the solver's answers in the shapes of the scene-v1 contract, frozen.

Every result is a read-only mapping whose ``as_dict()`` is exactly the body the HTTP endpoint sends,
as plain JSON data (``json.dumps`` writes it): the result itself holds a sweep's arrays as read-only
numpy arrays, ``as_dict()`` gives them as nested lists of floats (``as_dict(arrays=True)`` keeps
them as arrays: the same body, which orjson writes byte for byte the same, faster). ``holds`` is the
one place that decides which quantities a result carries. Results copy what they keep: no result
shares memory with the solver's internal state or with the caller's input, and none can be changed
(mappings are ``MappingProxyType``, lists are tuples, arrays have ``writeable = False``).

Vectors are [x, y] (or [x, y, z]); a pole that does not exist is None; sweep arrays follow
``driver_angle`` (or ``time``) sample by sample.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Iterator, Mapping
from dataclasses import dataclass
from types import MappingProxyType
from typing import Any

import numpy as np

from solver.analysis.instant import Diagnostics, LinkageAnalysis, LinkResult
from solver.analysis.sliding_joints import SliderTravel, SlidingJoint
from solver.analysis.spatial_sweep import SpatialSweep
from solver.analysis.sweeps import CloseApproach, Strokes, Sweep, TimeSweep
from solver.kinematics.four_bar import FourBarLoop
from solver.kinematics.instant_centres import InstantCentre
from solver.kinematics.poles import Poles
from solver.kinematics.relative_motion import MovingPointMotion
from solver.kinematics.rigid import Array
from solver.kinematics.spatial import SpatialAnalysis
from solver.model.scene import LinkageScene
from solver.position.assembly import Motion

JSON = dict[str, Any]


@dataclass(frozen=True)
class Contents:
    """Which quantities a result holds, field by field (see ``holds``)."""

    position: bool
    velocity: bool
    acceleration: bool
    omega: bool
    alpha: bool
    poles: bool
    components: bool

    def point(self, position: Any, velocity: Any, acceleration: Any) -> JSON:
        """A point's requested vectors."""
        out: JSON = {}
        if self.position:
            out["position"] = position
        if self.velocity:
            out["velocity"] = velocity
        if self.acceleration:
            out["acceleration"] = acceleration
        return out


def holds(quantities: frozenset[str]) -> Contents:
    """The fields a result of the requested ``quantities`` carries: points' vectors as asked; a
    link's omega with velocities or poles, its alpha with accelerations or poles (a pole is read
    with the rates that place it); slider and moving-point parts with ``components``."""
    return Contents(
        position="position" in quantities,
        velocity="velocity" in quantities,
        acceleration="acceleration" in quantities,
        omega=bool(quantities & {"velocity", "poles"}),
        alpha=bool(quantities & {"acceleration", "poles"}),
        poles="poles" in quantities,
        components="components" in quantities,
    )


# --- freezing ------------------------------------------------------------------------------------


ATOMS = frozenset({str, float, int, bool, type(None)})  # the JSON leaves, frozen as they are
# (the exact types of a body's containers: tested before an ``isinstance`` against the
# ``Mapping`` ABC, which costs several times more, and a body has thousands of them)
SEQUENCES = frozenset({list, tuple})
MAPPINGS = frozenset({dict, MappingProxyType})


def freeze(value: Any) -> Any:
    """A deep, read-only copy: mappings as ``MappingProxyType``, lists as tuples, arrays copied
    with ``writeable = False``."""
    kind = type(value)
    if kind in ATOMS:
        return value
    # (a leaf is tested here, not in a call of its own: most of a body's values are leaves)
    if kind in SEQUENCES or (kind not in MAPPINGS and isinstance(value, list | tuple)):
        return tuple([item if type(item) in ATOMS else freeze(item) for item in value])
    if kind in MAPPINGS or isinstance(value, Mapping):
        return MappingProxyType(
            {key: item if type(item) in ATOMS else freeze(item) for key, item in value.items()}
        )
    if isinstance(value, np.ndarray):
        copy = np.array(value, copy=True, order="C")
        copy.flags.writeable = False
        return copy
    return value


def thaw(value: Any) -> Any:
    """The JSON-shaped body of a frozen value: dicts and lists (read-only arrays kept)."""
    kind = type(value)
    if kind in ATOMS:
        return value
    if kind is tuple or (kind not in MAPPINGS and isinstance(value, tuple)):
        return [item if type(item) in ATOMS else thaw(item) for item in value]
    if kind in MAPPINGS or isinstance(value, Mapping):
        return {key: item if type(item) in ATOMS else thaw(item) for key, item in value.items()}
    return value


def plain(value: Any) -> Any:
    """The plain JSON data of a frozen value: dicts, lists, str, int, float, bool and None (an
    array as nested lists of Python numbers, a numpy scalar as a Python one, a tuple as a list);
    ``TypeError`` for anything else."""
    kind = type(value)
    if kind in ATOMS:
        return value
    if kind in SEQUENCES or (kind not in MAPPINGS and isinstance(value, list | tuple)):
        return [item if type(item) in ATOMS else plain(item) for item in value]
    if kind in MAPPINGS or isinstance(value, Mapping):
        return {key: item if type(item) in ATOMS else plain(item) for key, item in value.items()}
    if isinstance(value, np.ndarray | np.generic) and value.dtype.kind in "biuf":
        return value.tolist()
    raise TypeError(f"{kind.__name__} is no JSON value")


class Result(Mapping[str, Any]):
    """A frozen response body: read it as a mapping, or take ``as_dict()`` (the HTTP body)."""

    __slots__ = ("_body",)
    _body: Mapping[str, Any]

    def __init__(self, body: Mapping[str, Any]) -> None:
        object.__setattr__(self, "_body", freeze(body))

    def __setattr__(self, name: str, value: Any) -> None:
        raise AttributeError(f"{type(self).__name__} is read-only")

    def __getitem__(self, key: str) -> Any:
        return self._body[key]

    def __iter__(self) -> Iterator[str]:
        return iter(self._body)

    def __len__(self) -> int:
        return len(self._body)

    def __repr__(self) -> str:
        return f"{type(self).__name__}({', '.join(self._body)})"

    @property
    def warnings(self) -> tuple[str, ...]:
        """Sentences about the request that did not stop the answer (unknown keys, ...)."""
        warnings: tuple[str, ...] = self._body.get("warnings", ())
        return warnings

    def as_dict(self, *, arrays: bool = False) -> JSON:
        """The body the HTTP endpoint sends, as new plain dicts and lists (``json.dumps`` writes
        it; arrays as nested lists of floats). ``arrays=True``: the same body with the arrays kept
        as the result's read-only numpy arrays (the server's path: orjson writes them natively,
        the same bytes)."""
        body: JSON = thaw(self._body) if arrays else plain(self._body)
        return body


class AnalysisResult(Result):
    """One instant (POST /analyze): points, links (or bodies), joints, poles, diagnostics."""

    __slots__ = ()


class SweepResult(Result):
    """A driver's revolution or feasible range (POST /sweep): arrays over ``driver_angle``."""

    __slots__ = ()


class TimeSweepResult(Result):
    """The scene over a time range (POST /sweep with ``time_range``): arrays over ``time``; a
    linkage's points, links and moving points, or a spatial chain's bodies, points and joints."""

    __slots__ = ()


class EventResult(Result):
    """The instant a moving point reaches a named point (POST /events)."""

    __slots__ = ()


class SolutionResult(Result):
    """The worked solution (POST /solution): steps, mistakes and the /analyze body as results."""

    __slots__ = ()


# --- bodies --------------------------------------------------------------------------------------


def vector(value: Array | None) -> list[float] | None:
    return None if value is None else [float(x) for x in value]


def array(value: Array | None) -> Array | None:
    """A C-contiguous float array (what orjson serialises natively), or None."""
    return None if value is None else np.ascontiguousarray(value, dtype=float)


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
    motion: MovingPointMotion, wanted: Contents, convert: Callable[[Any], Any]
) -> JSON:
    """The requested fields of a moving point (scalars as numbers, vectors converted)."""
    out: JSON = {}
    for quantity, names in MOVING_POINT_FIELDS.items():
        if getattr(wanted, quantity):
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


FOUR_BAR = ("ground", "crank", "coupler", "rocker")


def analysis_body(result: LinkageAnalysis, warnings: list[str]) -> JSON:
    """The /analyze body of a linkage."""
    wanted = holds(result.quantities)
    body: JSON = {
        "points": {
            name: wanted.point(vector(p.position), vector(p.velocity), vector(p.acceleration))
            for name, p in result.points.items()
        },
        "links": {name: _link_fields(link, wanted) for name, link in result.links.items()},
    }
    if wanted.components:
        body["joints"] = [sliding_joint_fields(j, vector) for j in result.joints]
    if result.moving_points:
        body["moving_points"] = {
            name: moving_point_fields(m, wanted, vector) for name, m in result.moving_points.items()
        }
    if wanted.poles:
        body["instant_centres"] = [_instant_centre_fields(c) for c in result.instant_centres]
    body["four_bar_loops"] = [_four_bar_fields(loop) for loop in result.four_bar_loops]
    body["diagnostics"] = _diagnostics_fields(result.diagnostics)
    body["warnings"] = [*warnings, *result.warnings]  # the request's, then the pose's
    return body


def _link_fields(link: LinkResult, wanted: Contents) -> JSON:
    """A link's requested angle, rates and poles."""
    out: JSON = {}
    if wanted.position:
        out["angle"] = link.angle
    if wanted.omega:
        out["omega"] = link.omega
    if wanted.alpha:
        out["alpha"] = link.alpha
    if wanted.poles:
        out["velocity_pole"] = vector(link.velocity_pole)
        out["acceleration_pole"] = vector(link.acceleration_pole)
    return out


def _instant_centre_fields(c: InstantCentre) -> JSON:
    """An instant centre: its two links and its position (or its direction at infinity)."""
    return {
        "links": list(c.links),
        "position": vector(c.position),
        "direction_at_infinity": vector(c.direction),
    }


def _four_bar_fields(loop: FourBarLoop) -> JSON:
    """A four-bar loop: links and lengths by role, Grashof class, transmission angle."""
    return {
        "links": dict(zip(FOUR_BAR, loop.links, strict=True)),
        "lengths": dict(zip(FOUR_BAR, loop.lengths, strict=True)),
        "grashof": loop.grashof,
        "transmission_angle": loop.transmission_angle,
        "transmission_angle_deg": math.degrees(loop.transmission_angle),
    }


def _diagnostics_fields(d: Diagnostics) -> JSON:
    """How the pose was found (closed form or Newton, each Newton group's report) and how far it
    is from a change point."""
    return {
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
        "closest_approach": None
        if d.closest_approach is None
        else {"point": d.closest_approach[0], "margin": d.closest_approach[1]},
        "position_residual": d.position_residual,
    }


def spatial_body(result: SpatialAnalysis, quantities: frozenset[str], warnings: list[str]) -> JSON:
    """The /analyze body of a spatial chain (with the five acceleration terms as an extra)."""
    body = _spatial_fields(result, holds(quantities), vector)
    body["warnings"] = list(warnings)
    return body


def _spatial_fields(
    result: SpatialAnalysis, wanted: Contents, convert: Callable[[Any], Any]
) -> JSON:
    """Bodies' omega and alpha, points' vectors and acceleration terms (each converted)."""
    body: JSON = {"bodies": {}, "points": {}}
    for name, b in result.bodies.items():
        out: JSON = {}
        if wanted.velocity:
            out["omega"] = convert(b.omega)
        if wanted.acceleration:
            out["alpha"] = convert(b.alpha)
        body["bodies"][name] = out
    for name, p in result.points.items():
        out = wanted.point(convert(p.position), convert(p.velocity), convert(p.acceleration))
        if wanted.components:
            out["acceleration_terms"] = {
                "origin": convert(p.a_origin),
                "tangential": convert(p.tangential),
                "centripetal": convert(p.centripetal),
                "coriolis": convert(p.coriolis),
                "relative": convert(p.relative),
            }
        body["points"][name] = out
    return body


def spatial_time_sweep_body(result: SpatialSweep, warnings: list[str]) -> JSON:
    """The /sweep body of a spatial chain over a time range: arrays follow ``time``; bodies and
    points as in /analyze, sample by sample, and each joint's pose (origin, axis, displacement
    q(t)) with positions and its rate with velocities."""
    wanted = holds(result.quantities)
    joints = []
    for joint in result.moved.joints:
        out: JSON = {"name": joint.name, "type": joint.type}
        if wanted.position:
            out["origin"] = array(joint.origin)
            out["axis"] = array(joint.axis)
            out["displacement"] = array(result.displacement[joint.name])
        if wanted.velocity:
            out["rate"] = array(np.ravel(joint.rate))
        joints.append(out)
    return {
        "time": array(result.time),
        "samples": int(result.time.size),
        **_spatial_fields(result.analysis, wanted, array),
        "joints": joints,
        "feasible": True,
        "limits": [],
        "warnings": list(warnings),
    }


def link_angles(scene: LinkageScene, motion: Motion) -> dict[str, Array | None]:
    """Every moving link's absolute angle at every sample: atan2 of the vector from its first to
    its second point (scene-v1); None for a link with one point."""
    angles: dict[str, Array | None] = {}
    for name in scene.moving_links:
        on_link = scene.links[name].points
        angles[name] = None
        if len(on_link) >= 2:
            d = motion.points[on_link[1]].p - motion.points[on_link[0]].p
            angles[name] = np.arctan2(d[:, 1], d[:, 0])
    return angles


def _pole_list(poles: Poles) -> list[list[float] | None]:
    """[x, y] at each sample, null where the pole does not exist."""
    return [p if e else None for p, e in zip(poles.position.tolist(), poles.exists, strict=True)]


def _motion_arrays(
    scene: LinkageScene,
    motion: Motion,
    quantities: frozenset[str],
    joints: list[SlidingJoint],
    poles: dict[str, tuple[Poles, Poles]],
) -> JSON:
    """Points, links (with their poles) and slider parts of a vectorised motion, as the sweep
    arrays of the spec."""
    wanted = holds(quantities)
    points = {
        name: wanted.point(array(p.p), array(p.v), array(p.a))
        for name, p in motion.points.items()
        if name in scene.points
    }
    angles = link_angles(scene, motion) if wanted.position else {}
    links: JSON = {}
    for name in scene.moving_links:
        link = motion.links[name]
        out: JSON = {}
        if wanted.position:
            out["angle"] = array(angles[name])
        if wanted.omega:
            out["omega"] = array(link.omega)
        if wanted.alpha:
            out["alpha"] = array(link.alpha)
        if name in poles:
            out["velocity_pole"], out["acceleration_pole"] = map(_pole_list, poles[name])
        links[name] = out
    body: JSON = {"points": points, "links": links}
    if wanted.components:
        body["joints"] = [sliding_joint_fields(j, array) for j in joints]
    return body


def sweep_body(result: Sweep, warnings: list[str]) -> JSON:
    """The /sweep body: arrays sample by sample."""
    body: JSON = {
        "driver": result.driver,
        "driver_angle": array(result.driver_angle),
        "samples": int(result.driver_angle.size),
        **_motion_arrays(
            result.scene, result.motion, result.quantities, result.joints, result.poles
        ),
        "feasible": result.feasible,
        "limits": list(result.limits),
        "singular_samples": [int(k) for k in result.singular_samples],
        **_approach_fields(result.close_approaches, warnings),
    }
    if result.motion.newton:  # how Newton-Raphson went over all the samples of each group
        body["diagnostics"]["newton"] = [
            {
                "links": list(r.links),
                "iterations": r.iterations,
                "residual_norm": r.residual_norm,
                "tolerance": r.tolerance,
                "relative_tolerance": r.relative_tolerance,
            }
            for r in result.motion.newton
        ]
    body.update(_loop_and_slider_arrays(result, result.strokes))
    return body


def _loop_and_slider_arrays(
    result: Sweep | TimeSweep, strokes: dict[str, Strokes | None] | None = None
) -> JSON:
    """The sweep's four-bar loops with their transmission angle at every sample (with
    positions), and its sliders' travel along their guides (axis and displacement with
    positions, ds/dt with velocities, d2s/dt2 with accelerations); over a revolution
    (``strokes`` given), each slider on a fixed guide with its quick-return strokes."""
    wanted = holds(result.quantities)
    out: JSON = {}
    if wanted.position:
        out["four_bar_loops"] = [
            {
                "links": dict(zip(FOUR_BAR, loop.links, strict=True)),
                "lengths": dict(zip(FOUR_BAR, loop.lengths, strict=True)),
                "grashof": loop.grashof,
                "angle_points": list(loop.points),
                "transmission_angle": array(np.asarray(loop.transmission_angle)),
                "transmission_angle_deg": array(np.degrees(loop.transmission_angle)),
            }
            for loop in result.four_bar_loops
        ]
    if result.sliders:
        ground = result.scene.ground
        out["sliders"] = [
            _slider_fields(travel, wanted, strokes, travel.links[0] == ground)
            for travel in result.sliders
        ]
    return out


def _slider_fields(
    travel: SliderTravel, wanted: Contents, strokes: dict[str, Strokes | None] | None, fixed: bool
) -> JSON:
    out: JSON = {"point": travel.point, "type": travel.type, "links": list(travel.links)}
    if wanted.position:
        out["axis"] = array(travel.axis)
        out["displacement"] = array(travel.displacement)
    if wanted.velocity:
        out["sliding_velocity"] = array(travel.sliding_velocity)
    if wanted.acceleration:
        out["sliding_acceleration"] = array(travel.sliding_acceleration)
    if strokes is not None and fixed and wanted.position:
        found = strokes.get(travel.point)
        out["quick_return"] = None if found is None else _strokes_fields(found)
    return out


def _strokes_fields(strokes: Strokes) -> JSON:
    """A ram's extreme positions over the revolution and its quick-return time ratio."""
    return {
        "time_ratio": strokes.time_ratio,
        "extreme_positions": [
            {"driver_angle": angle, "driver_angle_deg": math.degrees(angle), "displacement": s}
            for angle, s in zip(strokes.driver_angles, strokes.displacements, strict=True)
        ],
        "slow_stroke": strokes.slow_stroke,
        "slow_stroke_deg": math.degrees(strokes.slow_stroke),
        "fast_stroke": strokes.fast_stroke,
        "fast_stroke_deg": math.degrees(strokes.fast_stroke),
    }


def _approach_fields(found: tuple[CloseApproach, ...], warnings: list[str]) -> JSON:
    """A sweep's close approaches to a change point: in ``diagnostics`` and, in words, in
    ``warnings`` after the request's own."""
    approaches = [
        {
            "point": a.point,
            "margin": a.margin,
            "driver_angle": a.driver_angle,
            "driver_angle_deg": math.degrees(a.driver_angle),
        }
        for a in found
    ]
    return {
        "diagnostics": {
            "close_approaches": approaches,
            "closest_approach": approaches[0] if approaches else None,
        },
        "warnings": [*warnings, *(a.warning for a in found)],
    }


def time_sweep_body(result: TimeSweep, warnings: list[str]) -> JSON:
    """The /sweep body for a time range: arrays follow ``time``."""
    wanted = result.quantities
    return {
        "time": array(result.time),
        "driver_angle": array(result.driver_angle),
        "samples": int(result.time.size),
        **_motion_arrays(result.scene, result.motion, wanted, result.joints, result.poles),
        "moving_points": {
            name: moving_point_fields(m, holds(wanted), array)
            for name, m in result.moving_points.items()
        },
        "feasible": True,
        "limits": [],
        **_approach_fields(result.close_approaches, warnings),
        **_loop_and_slider_arrays(result),
    }

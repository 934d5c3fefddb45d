"""Velocity and acceleration of a serial chain of joints in space, at one instant (or at many).

Joint k connects body k-1 (the ground for k = 1) to body k, named by the joint. Its ``origin`` and
unit ``axis`` are world coordinates at the instant; the axis is fixed in body k-1 and turns with it.
The analysis walks the chain link by link, as in the textbook: compose the angular velocities and
accelerations, carry the velocity and acceleration of each joint origin along, then apply the
five-term formula a = a_O + alpha x r + omega x (omega x r) + 2 omega x v_rel + a_rel at each point.

Every formula is written on the last axis, so the same walk serves a chain at N instants at once
(``solver.analysis.spatial_sweep``): vectors then have shape (N, 3) and rates (N, 1).
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any, Literal

import numpy as np

from solver.errors import InvalidScene, LimitExceeded

MAX_JOINTS = 64
MAX_POINTS = 256
MAX_MAGNITUDE = 1e6  # m, rad/s, m/s and their rates: a larger number is a typo
GROUND = "ground"
JointType = Literal["revolute", "prismatic"]


Rate = float | np.ndarray  # a number at an instant, an (N, 1) column over N instants


@dataclass(frozen=True)
class SpatialJoint:
    name: str
    type: JointType
    origin: np.ndarray  # (3,), or (N, 3) over N instants
    axis: np.ndarray  # unit vector
    rate: Rate
    rate_dot: Rate


@dataclass(frozen=True)
class SpatialPoint:
    name: str
    body: str
    position: np.ndarray


@dataclass(frozen=True)
class SpatialChain:
    joints: tuple[SpatialJoint, ...]
    points: tuple[SpatialPoint, ...]
    title: str = ""


@dataclass(frozen=True)
class CompositionTerms:
    """Joint k's terms in body k's rates (``composition_terms``):

    omega_k = omega_{k-1} + rate e_k,  alpha_k = alpha_{k-1} + rate_dot e_k + rate de_k/dt

    for a revolute joint; zero for a prismatic one, which adds no rotation.
    """

    rate_axis: np.ndarray
    rate_dot_axis: np.ndarray
    rate_axis_rate: np.ndarray


@dataclass(frozen=True)
class BodyMotion:
    """Motion of body k; ``velocity_origin``/``acceleration_origin`` are those of the joint origin
    O_k taken as a point of body k. ``axis_rate`` is d(e_k)/dt = omega_{k-1} x e_k and
    ``composition`` joint k's terms in omega_k and alpha_k."""

    omega: np.ndarray
    alpha: np.ndarray
    origin: np.ndarray
    velocity_origin: np.ndarray
    acceleration_origin: np.ndarray
    axis_rate: np.ndarray
    composition: CompositionTerms


@dataclass(frozen=True)
class RigidTerms:
    """The terms of a point P of a rigid body turning at omega, alpha, r = P - O (``rigid_terms``):

    v_P = v_O + omega x r,  a_P = a_O + alpha x r + omega x (omega x r).
    """

    r: np.ndarray
    omega_x_r: np.ndarray
    alpha_x_r: np.ndarray
    centripetal: np.ndarray


@dataclass(frozen=True)
class PointMotion:
    """Motion of a point P of body k, with the five terms of its acceleration (r = P - O_k).

    ``a_origin`` is the acceleration of O_k carried by the joint's guide: O_k as a point of body k
    itself for a revolute joint, the coincident point of body k-1 for a prismatic one, whose
    sliding then gives ``coriolis`` = 2 omega_{k-1} x v_rel and ``relative`` = rate_dot e_k.
    ``rigid`` holds r, omega x r, ``tangential`` = alpha x r and ``centripetal`` =
    omega x (omega x r) (all zero for a point of the ground).
    """

    position: np.ndarray
    velocity: np.ndarray
    acceleration: np.ndarray
    a_origin: np.ndarray
    tangential: np.ndarray
    centripetal: np.ndarray
    coriolis: np.ndarray
    relative: np.ndarray
    rigid: RigidTerms


@dataclass(frozen=True)
class SpatialAnalysis:
    bodies: dict[str, BodyMotion]
    points: dict[str, PointMotion]


# --- parsing -------------------------------------------------------------------------------------


def _number(value: Any, where: str) -> float:
    if isinstance(value, bool) or not isinstance(value, int | float):
        raise InvalidScene(f"{where} must be a number, got {value!r}")
    try:
        number = float(value)
    except OverflowError:  # an integer literal beyond the float range
        number = math.inf
    if not math.isfinite(number):
        raise InvalidScene(f"{where} is not a finite number ({str(value)[:20]})")
    if abs(number) > MAX_MAGNITUDE:
        raise InvalidScene(f"{where}: |{number:g}| exceeds the limit {MAX_MAGNITUDE:g}")
    return number


def _vector(value: Any, where: str) -> np.ndarray:
    if not isinstance(value, list | tuple) or len(value) != 3:
        raise InvalidScene(f"{where} must be a vector of 3 numbers [x, y, z], got {value!r}")
    return np.array([_number(c, f"{where}[{i}]") for i, c in enumerate(value)], dtype=float)


def _parse_joint(raw: Any, i: int) -> SpatialJoint:
    where = f"joints[{i}]"
    if not isinstance(raw, Mapping):
        raise InvalidScene(f"{where} must be an object")
    name = raw.get("name")
    if not isinstance(name, str) or not name:
        raise InvalidScene(f"{where}.name must be a non-empty string, got {name!r}")
    if name == GROUND:
        raise InvalidScene(f'{where}.name "{GROUND}" is reserved for the fixed frame')
    jtype = raw.get("type")
    if jtype not in ("revolute", "prismatic"):
        raise InvalidScene(f"{where}.type {jtype!r} is unknown: use 'revolute' or 'prismatic'")
    for key in ("origin", "axis", "rate"):
        if key not in raw:
            raise InvalidScene(f"{where}.{key} is missing")
    axis = _vector(raw["axis"], f"{where}.axis")
    norm = float(np.linalg.norm(axis))
    if norm < 1e-12:
        raise InvalidScene(f"{where}.axis is the zero vector")
    return SpatialJoint(
        name=name,
        type=jtype,
        origin=_vector(raw["origin"], f"{where}.origin"),
        axis=axis / norm,
        rate=_number(raw["rate"], f"{where}.rate"),
        rate_dot=_number(raw.get("rate_dot", 0.0), f"{where}.rate_dot"),
    )


def parse_spatial_chain(doc: Mapping[str, Any]) -> SpatialChain:
    """Validate a ``spatial_chain`` scene document and build the chain (axes normalised)."""
    if not isinstance(doc, Mapping):
        raise InvalidScene("the scene must be a JSON object")
    if doc.get("kind") != "spatial_chain":
        raise InvalidScene(f"kind must be 'spatial_chain', got {doc.get('kind')!r}")
    title = doc.get("title", "")
    if not isinstance(title, str):
        raise InvalidScene("title must be a string")
    raw_joints = doc.get("joints")
    if not isinstance(raw_joints, list) or not raw_joints:
        raise InvalidScene("joints must be a non-empty list of joints")
    if len(raw_joints) > MAX_JOINTS:
        raise LimitExceeded(f"joints has {len(raw_joints)} entries, more than {MAX_JOINTS}")
    joints: list[SpatialJoint] = []
    for i, raw in enumerate(raw_joints):
        joint = _parse_joint(raw, i)
        if any(j.name == joint.name for j in joints):
            raise InvalidScene(f"joints[{i}].name {joint.name!r} is a duplicate joint name")
        joints.append(joint)
    raw_points = doc.get("points", {})
    if not isinstance(raw_points, Mapping):
        raise InvalidScene('points must be an object {"name": {"body": ..., "position": [...]}}')
    if len(raw_points) > MAX_POINTS:
        raise LimitExceeded(f"points has {len(raw_points)} entries, more than {MAX_POINTS}")
    bodies = {GROUND} | {j.name for j in joints}
    points: list[SpatialPoint] = []
    for name, raw in raw_points.items():
        if not isinstance(raw, Mapping):
            raise InvalidScene(f"point {name!r} must be an object with body and position")
        body = raw.get("body")
        if body not in bodies:
            raise InvalidScene(f"point {name!r} is attached to unknown body {body!r}")
        position = _vector(raw.get("position"), f"points.{name}.position")
        points.append(SpatialPoint(name=str(name), body=str(body), position=position))
    return SpatialChain(joints=tuple(joints), points=tuple(points), title=title)


# --- the textbook steps --------------------------------------------------------------------------


def axis_rate(omega_parent: np.ndarray, axis: np.ndarray) -> np.ndarray:
    """de_k/dt = omega_{k-1} x e_k: the axis is fixed in body k-1 and turns with it."""
    return np.cross(omega_parent, axis)


def composition_terms(joint: SpatialJoint, axis_rate: np.ndarray) -> CompositionTerms:
    """rate e_k, rate_dot e_k and rate de_k/dt (de_k/dt = ``axis_rate``): the terms of
    omega_k = omega_{k-1} + rate e_k and alpha_k = alpha_{k-1} + rate_dot e_k + rate de_k/dt
    (a revolute joint; zero for a prismatic one)."""
    if joint.type == "revolute":
        return CompositionTerms(
            joint.rate * joint.axis, joint.rate_dot * joint.axis, joint.rate * axis_rate
        )
    zero = np.zeros_like(axis_rate)
    return CompositionTerms(zero, zero, zero)


def angular_velocity_composition(
    omega_parent: np.ndarray, joint: SpatialJoint, terms: CompositionTerms
) -> np.ndarray:
    """omega_k = omega_{k-1} + rate_k e_k (revolute); omega_k = omega_{k-1} (prismatic)."""
    if joint.type == "revolute":
        return omega_parent + terms.rate_axis
    return omega_parent.copy()


def angular_acceleration_composition(
    alpha_parent: np.ndarray, joint: SpatialJoint, terms: CompositionTerms
) -> np.ndarray:
    """alpha_k = alpha_{k-1} + rate_dot_k e_k + rate_k de_k/dt, de_k/dt = omega_{k-1} x e_k
    (revolute); alpha_k = alpha_{k-1} (prismatic)."""
    if joint.type == "revolute":
        return alpha_parent + terms.rate_dot_axis + terms.rate_axis_rate
    return alpha_parent.copy()


def rigid_terms(omega: np.ndarray, alpha: np.ndarray, r: np.ndarray) -> RigidTerms:
    """omega x r, alpha x r and omega x (omega x r): the terms of v_P = v_O + omega x r and
    a_P = a_O + alpha x r + omega x (omega x r) for a point P of a rigid body, r = P - O."""
    omega_x_r = np.cross(omega, r)
    return RigidTerms(r, omega_x_r, np.cross(alpha, r), np.cross(omega, omega_x_r))


def rigid_body_velocity(v_origin: np.ndarray, terms: RigidTerms) -> np.ndarray:
    """v_P = v_O + omega x r_{OP}."""
    return v_origin + terms.omega_x_r


def rigid_body_acceleration(a_origin: np.ndarray, terms: RigidTerms) -> np.ndarray:
    """a_P = a_O + alpha x r_{OP} + omega x (omega x r_{OP})."""
    return a_origin + terms.alpha_x_r + terms.centripetal


def sliding_terms(omega_parent: np.ndarray, joint: SpatialJoint) -> tuple[np.ndarray, ...]:
    """v_rel = rate e, a_rel = rate_dot e, a_cor = 2 omega_{k-1} x v_rel (prismatic; else zero)."""
    if joint.type == "prismatic":
        v_rel = joint.rate * joint.axis
        return v_rel, joint.rate_dot * joint.axis, 2.0 * np.cross(omega_parent, v_rel)
    zero = np.zeros_like(joint.axis)
    return zero, zero, zero


@dataclass(frozen=True)
class OriginTerms(RigidTerms):
    """The terms carrying joint k's origin O_k with body k-1, r = O_k - O_{k-1}:

    v_{O_k} = v_{O_{k-1}} + omega x r + v_rel,
    a_{O_k} = a_{O_{k-1}} + alpha x r + omega x (omega x r) + 2 omega x v_rel + a_rel,

    with body k-1's omega and alpha, and the sliding terms of joint k (zero for a revolute one).
    """

    v_rel: np.ndarray
    coriolis: np.ndarray
    a_rel: np.ndarray


def origin_terms(parent: BodyMotion, joint: SpatialJoint) -> OriginTerms:
    """r = O_k - O_{k-1}, omega x r, alpha x r, omega x (omega x r) with body k-1's rates
    (``rigid_terms``), and v_rel = rate e_k, 2 omega x v_rel, a_rel = rate_dot e_k of joint k's
    sliding (``sliding_terms``)."""
    carried = rigid_terms(parent.omega, parent.alpha, joint.origin - parent.origin)
    v_rel, a_rel, coriolis = sliding_terms(parent.omega, joint)
    return OriginTerms(
        carried.r, carried.omega_x_r, carried.alpha_x_r, carried.centripetal, v_rel, coriolis, a_rel
    )


def ground_motion(like: np.ndarray) -> BodyMotion:
    """The ground as body 0: at rest at the origin (zeros shaped like ``like``: (3,) or (N, 3))."""
    zero = np.zeros_like(like)
    return BodyMotion(zero, zero, zero, zero, zero, zero, CompositionTerms(zero, zero, zero))


def analyze_spatial_chain(chain: SpatialChain) -> SpatialAnalysis:
    """Walk the chain from the ground: omega, alpha and the joint-origin motion of every body,
    then the velocity and the five-term acceleration of every point,
    a_P = a_O + alpha x r + omega x (omega x r) + 2 omega x v_rel + a_rel."""
    parent = ground_motion(chain.joints[0].origin)
    bodies: dict[str, BodyMotion] = {}
    guides: dict[str, tuple[np.ndarray, OriginTerms]] = {}  # O_k as a point of body k-1
    for joint in chain.joints:
        terms = origin_terms(parent, joint)
        a_guide = rigid_body_acceleration(parent.acceleration_origin, terms)
        guides[joint.name] = (a_guide, terms)
        turning = axis_rate(parent.omega, joint.axis)
        composition = composition_terms(joint, turning)
        parent = BodyMotion(
            omega=angular_velocity_composition(parent.omega, joint, composition),
            alpha=angular_acceleration_composition(parent.alpha, joint, composition),
            origin=joint.origin,
            velocity_origin=rigid_body_velocity(parent.velocity_origin, terms) + terms.v_rel,
            acceleration_origin=a_guide + terms.a_rel + terms.coriolis,
            axis_rate=turning,
            composition=composition,
        )
        bodies[joint.name] = parent
    points: dict[str, PointMotion] = {}
    for point in chain.points:
        if point.body == GROUND:
            rest = np.zeros_like(point.position)
            still = RigidTerms(rest, rest, rest, rest)
            points[point.name] = PointMotion(
                point.position, rest, rest, rest, rest, rest, rest, rest, still
            )
            continue
        body, (a_guide, guide) = bodies[point.body], guides[point.body]
        rigid = rigid_terms(body.omega, body.alpha, point.position - body.origin)
        points[point.name] = PointMotion(
            point.position,
            rigid_body_velocity(body.velocity_origin, rigid),
            rigid_body_acceleration(body.acceleration_origin, rigid),
            a_guide,
            rigid.alpha_x_r,
            rigid.centripetal,
            guide.coriolis,
            guide.a_rel,
            rigid,
        )
    return SpatialAnalysis(bodies=bodies, points=points)

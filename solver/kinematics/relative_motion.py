"""A point M moving along a path fixed in a moving link (the carrier): composite motion.

The path is drawn with the scene: an ``arc`` about a centre point of the carrier, starting at a
start point and running cw or ccw, or a ``line`` from a start point through another. ``s(t)`` is
M's arc length from the start. Then (transport = the carrier's point coinciding with M)

    v = v_transport + v_relative,            v_relative = s' t
    a = a_transport + a_relative + a_coriolis,
    a_relative = s'' t + (s'^2 / R) n,        a_coriolis = 2 omega_carrier x v_relative

with t the path's unit tangent and n its unit normal towards the centre (world frame). The
tangential and normal parts of the transport acceleration are its components along and across
the coincident point's own velocity (for a carrier turning about a fixed pivot: alpha x r and
-omega^2 r).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, fields

import numpy as np

from solver.kinematics.rigid import (
    Array,
    LinkMotion,
    dot,
    omega_cross,
    perp,
    rigid_body_acceleration,
    rigid_body_velocity,
    rotate,
    scale,
)
from solver.model.laws import parse_time_law
from solver.model.scene import LinkageScene, MovingPoint


@dataclass(frozen=True)
class PathGeometry:
    """Where s puts M on the path, in the drawn frame of the carrier (arrays over samples)."""

    point: Array
    tangent: Array
    normal: Array
    curvature: float


def path_radius(scene: LinkageScene, mp: MovingPoint) -> float:
    """R = |P_0 - C|: the radius of an arc path, its start P_0 and centre C as drawn."""
    assert mp.path.center is not None
    return math.hypot(*(scene.drawn(mp.path.start) - scene.drawn(mp.path.center)))


def path_geometry(scene: LinkageScene, mp: MovingPoint, s: Array) -> PathGeometry:
    """M0(s), its unit tangent (direction of increasing s) and inward normal, drawn frame."""
    route = mp.path
    start = scene.drawn(route.start)
    if route.type == "line":
        assert route.through is not None
        u = scene.drawn(route.through) - start
        u = u / math.hypot(*u)
        n = np.broadcast_to(perp(u), (s.size, 2))
        return PathGeometry(start + np.outer(s, u), np.broadcast_to(u, (s.size, 2)), n, 0.0)
    assert route.center is not None
    center = scene.drawn(route.center)
    radius = path_radius(scene, mp)
    turn = 1.0 if route.direction == "ccw" else -1.0
    phi = math.atan2(start[1] - center[1], start[0] - center[0]) + turn * s / radius
    radial = np.stack((np.cos(phi), np.sin(phi)), axis=-1)
    return PathGeometry(center + radius * radial, turn * perp(radial), -radial, 1.0 / radius)


@dataclass(frozen=True)
class MovingPointMotion:
    """M's motion and its parts; arrays over samples (see ``at`` for one instant). ``tangent``
    and ``normal`` are the path's unit tangent tau (direction of increasing s) and inward normal
    n at M in the world frame, ``curvature`` its 1/R (0 on a line)."""

    position: Array
    velocity: Array
    acceleration: Array
    transport_velocity: Array
    relative_velocity: Array
    transport_acceleration: Array
    relative_acceleration: Array
    coriolis_acceleration: Array
    transport_tangential: Array
    transport_normal: Array
    relative_tangential: Array
    relative_normal: Array
    omega_carrier: Array
    alpha_carrier: Array
    s: Array
    s_dot: Array
    s_ddot: Array
    tangent: Array
    normal: Array
    curvature: Array

    def at(self, k: int) -> MovingPointMotion:
        """The same quantities at sample ``k`` alone."""
        return MovingPointMotion(**{f.name: getattr(self, f.name)[k] for f in fields(self)})


def intrinsic_parts(acceleration: Array, velocity: Array) -> tuple[Array, Array]:
    """a = a_t + a_n: the components along and across the velocity (a_t = a if v = 0)."""
    speed2 = dot(velocity, velocity)
    moving = speed2 > 0.0
    along = np.where(moving, dot(acceleration, velocity) / np.where(moving, speed2, 1.0), 0.0)
    tangential = np.where(moving[:, None], scale(along, velocity), acceleration)
    return tangential, acceleration - tangential


def coriolis_acceleration(omega_carrier: Array, v_rel: Array) -> Array:
    """a_coriolis = 2 omega x v_rel (zero when the carrier does not turn or M rests on it)."""
    return omega_cross(2.0 * omega_carrier, v_rel)


def sliding_velocity_parts(
    v_A: Array, omega_guide: Array, r_AP: Array, v_P: Array
) -> tuple[Array, Array]:
    """v_P = v_transport + v_relative at a point P sliding on a guide, A a point of the guide:
    v_transport = v_A + omega_guide x r_AP (the guide's point coinciding with P) and
    v_relative = v_P - v_transport."""
    v_transport = rigid_body_velocity(v_A, omega_guide, r_AP)
    return v_transport, v_P - v_transport


def sliding_acceleration_parts(
    a_A: Array, omega_guide: Array, alpha_guide: Array, r_AP: Array, v_rel: Array, a_P: Array
) -> tuple[Array, Array, Array]:
    """a_P = a_transport + a_relative + a_coriolis at a point P sliding on a guide:
    a_transport = a_A + alpha_guide x r_AP - omega_guide^2 r_AP,
    a_coriolis = 2 omega_guide x v_rel and a_relative = a_P - a_transport - a_coriolis;
    returned as (a_transport, a_relative, a_coriolis)."""
    a_transport = rigid_body_acceleration(a_A, omega_guide, alpha_guide, r_AP)
    a_coriolis = coriolis_acceleration(omega_guide, v_rel)
    return a_transport, a_P - a_transport - a_coriolis, a_coriolis


def moving_point_motion(
    scene: LinkageScene, mp: MovingPoint, carrier: LinkMotion, time: Array
) -> MovingPointMotion:
    """Composite motion of M at the given times, on a carrier already solved at those times."""
    s, s_dot, s_ddot = parse_time_law(mp.s_law).evaluate(np.asarray(time, dtype=float))
    path = path_geometry(scene, mp, s)
    coincident = carrier.point(path.point)
    assert coincident.v is not None and coincident.a is not None
    assert carrier.omega is not None and carrier.alpha is not None
    tangent = rotate(path.tangent, carrier.theta)
    normal = rotate(path.normal, carrier.theta)
    v_rel = scale(s_dot, tangent)
    a_rel_t = scale(s_ddot, tangent)
    a_rel_n = scale(s_dot**2 * path.curvature, normal)
    a_rel = a_rel_t + a_rel_n
    a_cor = coriolis_acceleration(carrier.omega, v_rel)
    a_tr_t, a_tr_n = intrinsic_parts(coincident.a, coincident.v)
    return MovingPointMotion(
        coincident.p,
        coincident.v + v_rel,
        coincident.a + a_rel + a_cor,
        coincident.v,
        v_rel,
        coincident.a,
        a_rel,
        a_cor,
        a_tr_t,
        a_tr_n,
        a_rel_t,
        a_rel_n,
        carrier.omega,
        carrier.alpha,
        s,
        s_dot,
        s_ddot,
        tangent,
        normal,
        np.broadcast_to(path.curvature, s.shape),
    )

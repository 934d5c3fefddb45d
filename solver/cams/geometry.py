"""The follower's motion over the cam angle and the cam's shape: the textbook formulas, vectorised.

The cam angle theta is the angle the cam has turned through since its angle 0, in its own
direction of rotation; the follower's lift s(theta) and its derivatives with respect to theta
come from the segments' laws. Everything is computed for a cam turning counter-clockwise; a
clockwise cam (omega < 0) is that mechanism mirrored in the y axis (x -> -x), so its offset and
its pivot's x enter mirrored and its profile and contact points leave mirrored.

Shapes come from the follower's positions as seen from the cam (the envelope):

- knife and roller: the pitch point P(theta) (knife tip, roller centre) traces the pitch curve
  R(-theta) P in the cam's frame; its tangent there, turned back to the ground, is
  u = P' - J P (J the quarter turn), the cam surface lies r inwards along the normal J u / |u|,
  and its radius of curvature is that of the pitch curve, rho = -|u|^3 / (u x w) with
  w = P'' - 2 J P' - P (positive where the cam is convex), less r;
- flat face: the face is the line n . x = h in the ground (n its unit normal away from the cam),
  n at angle alpha - theta in the cam's frame; the cam surface is the envelope of those lines,
  the contact point h n + (dh/dalpha) J n, and rho = h + d2h/dalpha2.
"""

from __future__ import annotations

import math
from typing import NamedTuple

import numpy as np

from solver.cams.laws import LAWS
from solver.cams.model import CamScene

Array = np.ndarray


class Lift(NamedTuple):
    """The follower's lift s and ds/dtheta, d2s/dtheta2, d3s/dtheta3 (m or rad), and the index
    of the segment each cam angle lies in."""

    s: Array
    ds: Array
    d2s: Array
    d3s: Array
    segment: Array


class CamGeometry(NamedTuple):
    """The mechanism at cam angles ``theta``: the ``lift``, the ``pressure_angle`` (rad), the
    cam surface's radius of curvature ``radius`` (m, positive convex), the roller's pitch curve's
    ``pitch_radius`` (None but for a roller), the ``contact`` point in the ground at each angle
    and the cam surface's ``profile`` points in the cam's frame at angle 0 (both N x 2, m)."""

    theta: Array
    lift: Lift
    pressure_angle: Array
    radius: Array
    pitch_radius: Array | None
    contact: Array
    profile: Array


def follower_lift(scene: CamScene, theta: Array) -> Lift:
    """s(theta) segment by segment: x = (theta - theta_0) / beta, a rise s = s_0 + h y(x),
    a return s = s_0 - h y(x), a dwell s = s_0, with ds/dtheta = +-h y' / beta,
    d2s/dtheta2 = +-h y'' / beta^2, d3s/dtheta3 = +-h y''' / beta^3."""
    theta = np.mod(np.asarray(theta, dtype=float), 2.0 * math.pi)
    starts = np.array([seg.start for seg in scene.segments])
    index = np.clip(np.searchsorted(starts, theta, side="right") - 1, 0, len(starts) - 1)
    s, ds, d2s, d3s = (np.zeros_like(theta) for _ in range(4))
    for i, seg in enumerate(scene.segments):
        at = index == i
        s[at] = seg.level
        if seg.law is None or not at.any():
            continue
        x = np.clip((theta[at] - seg.start) / seg.duration, 0.0, 1.0)
        y = LAWS[seg.law](x)
        h = seg.lift if seg.type == "rise" else -seg.lift
        beta = seg.duration
        s[at] += h * y.y
        ds[at] = h * y.dy / beta
        d2s[at] = h * y.d2y / beta**2
        d3s[at] = h * y.d3y / beta**3
    return Lift(s, ds, d2s, d3s, index)


def quarter_turn(v: Array) -> Array:
    """J v = (-v_y, v_x): v turned 90 degrees counter-clockwise (rows of N x 2)."""
    return np.stack([-v[:, 1], v[:, 0]], axis=1)


def cam_frame(points: Array, theta: Array) -> Array:
    """R(-theta) p: ground points seen from a cam turned counter-clockwise by theta."""
    c, s = np.cos(theta), np.sin(theta)
    return np.stack([c * points[:, 0] + s * points[:, 1], -s * points[:, 0] + c * points[:, 1]], 1)


def _dot(a: Array, b: Array) -> Array:
    return np.einsum("ij,ij->i", a, b)


def _cross(a: Array, b: Array) -> Array:
    return a[:, 0] * b[:, 1] - a[:, 1] * b[:, 0]


def pitch_curve_tangent(p: Array, dp: Array) -> Array:
    """u = P' - J P: d/dtheta of the pitch point R(-theta) P seen from the cam, turned back to
    the ground (the pitch curve's tangent at the contact)."""
    return dp - quarter_turn(p)


def pressure_angle(u: Array, direction: Array) -> Array:
    """tan phi = (u . T) / (u . (-J T)): the angle between the common normal (normal to the
    pitch curve's tangent u) and the follower's direction of motion T at the pitch point.
    Translating (T = (0, 1), P = (e, d + s), d = sqrt(R_p^2 - e^2)):
    phi = arctan((ds/dtheta - e) / (d + s)) (Norton eq. 8.31); oscillating (T = J e_arm):
    phi = arctan((l (dpsi/dtheta - 1) + D cos beta) / (D sin beta))."""
    return np.arctan(_dot(u, direction) / _dot(u, -quarter_turn(direction)))


def pitch_radius_of_curvature(p: Array, dp: Array, d2p: Array) -> Array:
    """rho = -|u|^3 / (u x w), u = P' - J P, w = P'' - 2 J P' - P: the radius of curvature of
    the pitch curve R(-theta) P(theta) (positive where convex). For a translating follower
    without offset, rho = ((R_p + s)^2 + s'^2)^(3/2) / ((R_p + s)^2 + 2 s'^2 - (R_p + s) s'')
    (Norton eq. 8.33)."""
    u = pitch_curve_tangent(p, dp)
    w = d2p - 2.0 * quarter_turn(dp) - p
    speed = np.hypot(u[:, 0], u[:, 1])
    with np.errstate(divide="ignore"):
        rho: Array = -(speed**3) / _cross(u, w)
    return rho


def pitch_point(scene: CamScene, lift: Lift) -> tuple[Array, Array, Array, Array]:
    """The pitch point P, P', P'' (d/dtheta) in the ground and the follower's direction of
    motion T there, for a cam turning counter-clockwise."""
    f, n = scene.follower, lift.s.size
    if f.motion == "translating":
        e = _mirrored_offset(scene)
        d = math.sqrt(scene.prime_radius**2 - e**2)
        p = np.stack([np.full(n, e), d + lift.s], 1)
        zeros = np.zeros(n)
        return (
            p,
            np.stack([zeros, lift.ds], 1),
            np.stack([zeros, lift.d2s], 1),
            np.tile([0, 1.0], (n, 1)),
        )
    pivot = _mirrored_pivot(scene)
    psi = _arm_angle(scene, lift)
    arm = np.stack([np.cos(psi), np.sin(psi)], 1)
    normal = quarter_turn(arm)
    arm_length = f.arm_length
    p = pivot + arm_length * arm
    dp = arm_length * lift.ds[:, None] * normal
    d2p = arm_length * (lift.d2s[:, None] * normal - (lift.ds**2)[:, None] * arm)
    return p, dp, d2p, normal


def _mirrored_offset(scene: CamScene) -> float:
    """The offset of the counter-clockwise mechanism: e sign(omega)."""
    return math.copysign(1.0, scene.omega) * scene.follower.offset


def _mirrored_pivot(scene: CamScene) -> Array:
    x, y = scene.follower.pivot
    return np.array([math.copysign(1.0, scene.omega) * x, y])


def _arm_angle(scene: CamScene, lift: Lift) -> Array:
    """psi = gamma + beta_0 + s: the arm's (the face's) direction from the pivot, gamma the
    direction from the pivot to the cam centre, turned counter-clockwise by the rest angle and
    the lift (away from the cam centre)."""
    pivot = _mirrored_pivot(scene)
    gamma = math.atan2(-pivot[1], -pivot[0])
    psi: Array = gamma + scene.rest_angle + lift.s
    return psi


def _flat_face(scene: CamScene, lift: Lift) -> tuple[Array, Array]:
    """The contact point (ground) and the cam surface's rho under the face n . x = h: h(theta)
    and the normal's angle in the cam's frame alpha(theta) = angle(n) - theta, by the envelope.
    Translating: n = (0, 1), h = R_b + s; through the pivot: n = J e(psi), h = d sin beta."""
    n_samples = lift.s.size
    if scene.follower.motion == "translating":
        n = np.tile([0, 1.0], (n_samples, 1))
        h, dh, d2h = scene.base_radius + lift.s, lift.ds, lift.d2s
        dalpha, d2alpha = -np.ones(n_samples), np.zeros(n_samples)
    else:
        distance = math.hypot(*scene.follower.pivot)
        beta = scene.rest_angle + lift.s
        psi = _arm_angle(scene, lift)
        n = quarter_turn(np.stack([np.cos(psi), np.sin(psi)], 1))
        h = distance * np.sin(beta)
        dh = distance * np.cos(beta) * lift.ds
        d2h = distance * (np.cos(beta) * lift.d2s - np.sin(beta) * lift.ds**2)
        dalpha, d2alpha = lift.ds - 1.0, lift.d2s
    return envelope_of_lines(n, h, dh, d2h, dalpha, d2alpha)


def envelope_of_lines(
    n: Array, h: Array, dh: Array, d2h: Array, dalpha: Array, d2alpha: Array
) -> tuple[Array, Array]:
    """The envelope of the lines n(alpha) . x = h: the contact point x = h n + h_alpha J n and
    the radius of curvature rho = h + h_alpha_alpha, with h_alpha = h' / alpha' and
    h_alpha_alpha = (h'' alpha' - h' alpha'') / alpha'^3 (' = d/dtheta). A translating flat
    face (alpha' = -1): x = (s', R_b + s), rho = R_b + s + s'' (Norton eq. 8.37)."""
    h_alpha = dh / dalpha
    h_alpha_alpha = (d2h * dalpha - dh * d2alpha) / dalpha**3
    contact = h[:, None] * n + h_alpha[:, None] * quarter_turn(n)
    return contact, h + h_alpha_alpha


def cam_geometry(scene: CamScene, theta: Array) -> CamGeometry:
    """The lift, pressure angle, radii of curvature, contact points and profile at the cam
    angles ``theta`` (rad turned in the cam's direction of rotation)."""
    theta = np.asarray(theta, dtype=float)
    lift = follower_lift(scene, theta)
    pitch_radius: Array | None = None
    if scene.follower.contact == "flat":
        contact, radius = _flat_face(scene, lift)
        angle = np.zeros_like(theta)  # the face's normal is the contact point's path's direction
    else:
        p, dp, d2p, direction = pitch_point(scene, lift)
        u = pitch_curve_tangent(p, dp)
        angle = pressure_angle(u, direction)
        rho = pitch_radius_of_curvature(p, dp, d2p)
        r = scene.follower.roller_radius
        contact = p - r * quarter_turn(u) / np.hypot(u[:, 0], u[:, 1])[:, None]
        radius = rho - r
        if scene.follower.contact == "roller":
            pitch_radius = rho
    profile = cam_frame(contact, theta)
    if scene.omega < 0:  # mirrored back: the clockwise cam
        contact = contact * [-1.0, 1.0]
        profile = profile * [-1.0, 1.0]
    return CamGeometry(theta, lift, angle, radius, pitch_radius, contact, profile)

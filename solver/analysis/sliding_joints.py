"""The transport / relative / Coriolis split at every slider and prismatic joint.

v_P = v_transport + v_relative;  a_P = a_transport + a_relative + a_coriolis, where the transport
terms are those of the guide's point coinciding with P and a_coriolis = 2 omega_guide x v_rel.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from solver.kinematics.relative_motion import (
    sliding_acceleration_parts,
    sliding_velocity_parts,
)
from solver.kinematics.rigid import (
    Array,
    dot,
    perp,
    rotate,
)
from solver.model.scene import LinkageScene
from solver.position.assembly import Motion


@dataclass(frozen=True)
class SlidingJoint:
    """Velocity and acceleration of the follower's point P of a slider or prismatic joint.

    v = v_transport + v_relative;  a = a_transport + a_relative + a_coriolis, with the transport
    terms those of the guide's point coinciding with P, and a_coriolis = 2 omega_guide x v_rel.
    """

    point: str
    type: str
    links: tuple[str, str]
    omega_guide: Array
    transport_velocity: Array
    relative_velocity: Array
    velocity: Array
    transport_acceleration: Array | None
    relative_acceleration: Array | None
    coriolis_acceleration: Array | None
    acceleration: Array | None

    def at(self, k: int) -> SlidingJoint:
        """The same parts at sample ``k`` alone (arrays over samples become single values)."""

        def pick(value: Array | None) -> Array | None:
            return None if value is None else value[k]

        return SlidingJoint(
            self.point, self.type, self.links, self.omega_guide[k],
            self.transport_velocity[k], self.relative_velocity[k], self.velocity[k],
            pick(self.transport_acceleration), pick(self.relative_acceleration),
            pick(self.coriolis_acceleration), pick(self.acceleration),
        )  # fmt: skip


def sliding_joints(scene: LinkageScene, motion: Motion, order: int) -> list[SlidingJoint]:
    """Every slider and prismatic joint split into its parts, at every sample of ``motion``."""
    joints = []
    for joint in scene.joints:
        if joint.type == "revolute":
            continue
        guide = motion.links[joint.guide]
        P = motion.points[joint.point]
        assert P.v is not None and guide.omega is not None and guide.anchor.v is not None
        r = P.p - guide.anchor.p
        v_tr, v_rel = sliding_velocity_parts(guide.anchor.v, guide.omega, r, P.v)
        a_tr = a_rel = a_cor = None
        if order >= 2:
            assert P.a is not None and guide.alpha is not None and guide.anchor.a is not None
            a_tr, a_rel, a_cor = sliding_acceleration_parts(
                guide.anchor.a, guide.omega, guide.alpha, r, v_rel, P.a
            )
        joints.append(
            SlidingJoint(
                joint.point,
                joint.type,
                joint.links,
                guide.omega,
                v_tr,
                v_rel,
                P.v,
                a_tr,
                a_rel,
                a_cor,
                P.a if order >= 2 else None,
            )
        )
    return joints


@dataclass(frozen=True)
class SliderTravel:
    """A slider or prismatic joint's point P along its guide, at every sample: the guide's unit
    direction ``axis`` (N, 2) (the drawn axis turned with the guide), the displacement
    s = (r_P - r_Q) . e from the guide's point Q that coincided with P in the drawn pose (for a
    fixed guide s = (r - r_0) . e), and its rates ``sliding_velocity`` ds/dt and
    ``sliding_acceleration`` d2s/dt2 (the relative velocity and acceleration along the guide;
    on a fixed guide v . e and a . e). Orders not computed are None."""

    point: str
    type: str
    links: tuple[str, str]
    axis: Array
    displacement: Array
    sliding_velocity: Array | None
    sliding_acceleration: Array | None


def slider_travel(scene: LinkageScene, motion: Motion, order: int) -> list[SliderTravel]:
    """Every slider and prismatic joint's travel along its guide, at every sample of ``motion``
    (rates up to ``order``: ds/dt from 1, d2s/dt2 from 2).

    With e = R(theta_guide) e_0 and Q the guide's point drawn at P, s = (r_P - r_Q) . e; since
    r_P - r_Q lies along e, ds/dt = (v_P - v_Q) . e and d2s/dt2 = (a_P - a_Q) . e +
    omega_guide (v_P - v_Q) . (k x e)."""
    travels = []
    for joint in scene.joints:
        if joint.type == "revolute":
            continue
        assert joint.axis is not None
        guide = motion.links[joint.guide]
        P = motion.points[joint.point]
        Q = guide.point(scene.drawn(joint.point))
        e = rotate(np.asarray(joint.axis, dtype=float), guide.theta)
        s = dot(P.p - Q.p, e)
        s_dot = s_ddot = None
        if order >= 1 and P.v is not None and Q.v is not None:
            dv = P.v - Q.v
            s_dot = dot(dv, e)
            if order >= 2 and P.a is not None and Q.a is not None and guide.omega is not None:
                s_ddot = dot(P.a - Q.a, e) + guide.omega * dot(dv, perp(e))
        travels.append(SliderTravel(joint.point, joint.type, joint.links, e, s, s_dot, s_ddot))
    return travels

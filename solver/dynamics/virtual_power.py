"""Driver torques by the principle of virtual power (D'Alembert), one driver at a time.

Turn driver i at unit rate with the other drivers held: every point's velocity is then its
kinematic influence coefficient dv_P/dq_i and every link's omega is domega/dq_i (the partial
motion of driver i). Frictionless joints do no virtual power in a motion their constraints allow,
and driver j's link turns at delta_ij in it, so

    T_i = sum_masses [(m a_G - m g) . dv_G/dq_i + I_G alpha domega/dq_i]
          - sum_forces F . dv_P/dq_i - sum_moments M domega/dq_i

gives each driver's torque without any joint force. With one driver dv/dq = v / omega and this is
the power balance M omega = d(T + V)/dt - P_loads (``energy.power_balance_torque``).
"""

from __future__ import annotations

import numpy as np

from solver.analysis.sweeps import MIN_GRADIENT_SINE
from solver.dynamics.loads import AppliedForce, AppliedMoment, MassElement
from solver.kinematics.rigid import Array, dot, rigid_body_velocity
from solver.model.scene import LinkageScene
from solver.position.assembly import DriverInput, Motion, assemble
from solver.position.topology import build_plan

# The partial motion must be the analysed one: a point more than this (relative to the size) from
# where the motion has it is on another assembly, and the torque is left undefined there.
SAME_POSE = 1e-6


def partial_motion(scene: LinkageScene, motion: Motion, driver: int, anchor: int = 0) -> Motion:
    """The velocity analysis of ``motion``'s poses with driver ``driver`` at 1 rad/s and the
    others held (on the motion's branches: continuation from sample ``anchor``, where the drawn
    assembly holds, as in the sweep that made ``motion``)."""
    n = motion.margin.size
    inputs = [
        DriverInput(motion.links[d.link].theta, np.full(n, float(j == driver)), np.zeros(n))
        for j, d in enumerate(scene.drivers)
    ]
    return assemble(scene, build_plan(scene), inputs, 1, continuation=True, anchor=anchor)


def virtual_power_torque(
    partial: Motion,
    motion: Motion,
    size: float,
    elements: list[MassElement],
    forces: list[AppliedForce],
    moments: list[AppliedMoment],
    gravity: Array,
) -> Array:
    """T_i of the module docstring from driver i's ``partial`` motion; NaN where that motion is
    undefined (its velocity equations singular: a dead centre or a change point, where the sweep
    takes the neighbours' mean; or its poses not the motion's)."""

    def influence(link: str, at: Array) -> Array:
        """dv/dq_i of the point of ``link`` that is at ``at`` (N, 2)."""
        moving = partial.links[link]
        assert moving.anchor.v is not None and moving.omega is not None
        return rigid_body_velocity(moving.anchor.v, moving.omega, at - moving.anchor.p)

    def turn(link: str) -> Array:
        omega = partial.links[link].omega
        assert omega is not None
        return omega

    torque = np.zeros(motion.margin.size)
    for e in elements:
        torque += dot(e.mass * (e.a - gravity), influence(e.link, e.p))
        torque += e.inertia * e.alpha * turn(e.link)
    for f in forces:
        torque -= dot(f.force, influence(f.link, f.position))
    for m in moments:
        torque -= m.moment * turn(m.link)
    apart = np.zeros(motion.margin.size)
    for name, point in motion.points.items():
        apart = np.maximum(apart, np.hypot(*(partial.points[name].p - point.p).T))
    undefined = (apart > SAME_POSE * size) | (partial.gradient_sine < MIN_GRADIENT_SINE)
    return np.where(undefined | ~np.isfinite(torque), np.nan, torque)

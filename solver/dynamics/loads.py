"""The moving masses and the external loads of a linkage at every sample of a solved motion.

Each link's mass is a body (mass at a centre carried by the link, inertia about it) plus any
point masses on it; each is one ``MassElement`` with its position, velocity and acceleration
from the rigid-body formulas. Force and moment expressions are evaluated on the links' state
(angle as in the response, omega, alpha) and the sample times.
"""

from __future__ import annotations

import math
from collections.abc import Iterable
from dataclasses import dataclass, replace

import numpy as np

from solver.errors import InvalidExpression
from solver.kinematics.rigid import Array, rotate, scale
from solver.model.dynamics import Dynamics
from solver.model.laws import State, StateExpression
from solver.model.scene import LinkageScene
from solver.position.assembly import Motion

EMPTY = Dynamics()


@dataclass(frozen=True)
class MassElement:
    """A mass on ``link``: a body (``inertia`` about its centre) or a point mass (inertia 0)."""

    name: str
    link: str
    mass: float
    inertia: float
    p: Array  # (N, 2)
    v: Array
    a: Array
    omega: Array  # (N,) the link's
    alpha: Array


@dataclass(frozen=True)
class AppliedForce:
    """An external force on ``link`` at ``point``: its vector and its point's velocity."""

    name: str
    link: str
    point: str
    position: Array
    velocity: Array
    force: Array

    @property
    def power(self) -> Array:
        """P = F . v_P."""
        return self.force[:, 0] * self.velocity[:, 0] + self.force[:, 1] * self.velocity[:, 1]


@dataclass(frozen=True)
class AppliedMoment:
    """An external moment on ``link`` and the link's omega."""

    name: str
    link: str
    moment: Array
    omega: Array

    @property
    def power(self) -> Array:
        """P = M omega."""
        return self.moment * self.omega


def dynamics_of(scene: LinkageScene) -> Dynamics:
    return EMPTY if scene.dynamics is None else scene.dynamics


def link_state(
    scene: LinkageScene, motion: Motion, links: Iterable[str] | None = None
) -> dict[str, tuple[Array, Array, Array]]:
    """(angle in (-pi, pi], omega, alpha) per sample of every link with two points (of
    ``links`` only, when given)."""
    state = {}
    for name in scene.links if links is None else links:
        link = scene.links[name]
        if len(link.points) < 2:
            continue
        m = motion.links[name]
        d = motion.points[link.points[1]].p - motion.points[link.points[0]].p
        assert m.omega is not None and m.alpha is not None
        state[name] = (np.arctan2(d[:, 1], d[:, 0]), m.omega, m.alpha)
    return state


def mass_elements(scene: LinkageScene, motion: Motion) -> list[MassElement]:
    """Every body and point mass with its motion (requires accelerations in ``motion``)."""
    dynamics = dynamics_of(scene)

    def element(name: str, on: str, mass: float, inertia: float, at: Array) -> MassElement:
        link = motion.links[on]
        P = link.point(at)
        assert P.v is not None and P.a is not None
        assert link.omega is not None and link.alpha is not None
        return MassElement(name, on, mass, inertia, P.p, P.v, P.a, link.omega, link.alpha)

    return [
        element(body.link, body.link, body.mass, body.inertia, np.array(body.center))
        for body in dynamics.bodies
    ] + [
        element(pm.name, pm.link, pm.mass, 0.0, scene.drawn(pm.point))
        for pm in dynamics.point_masses
    ]


def static_elements(elements: list[MassElement]) -> list[MassElement]:
    """The masses of a static analysis: a_G = 0 and alpha = 0, so each counts only through its
    weight m g (the inertia terms m a_G and I_G alpha left out)."""
    return [replace(e, a=np.zeros_like(e.a), alpha=np.zeros_like(e.alpha)) for e in elements]


def applied_loads(
    scene: LinkageScene, motion: Motion, times: Array
) -> tuple[list[AppliedForce], list[AppliedMoment]]:
    """The external forces and moments at every sample (their expressions evaluated)."""
    dynamics = dynamics_of(scene)
    read = {f.link for f in dynamics.forces if f.relative_to == "link"}
    for expression in [f.magnitude for f in dynamics.forces] + [m.moment for m in dynamics.torques]:
        read |= expression.links
    state = link_state(scene, motion, sorted(read))  # the angles the loads read, no others
    forces = []
    for index, f in enumerate(dynamics.forces):
        link = motion.links[f.link]
        P = link.point(scene.drawn(f.point))
        assert P.v is not None
        direction = np.full(times.shape, math.radians(f.direction_deg))
        if f.relative_to == "link":
            direction = direction + state[f.link][0]
        magnitude = _evaluate(f.magnitude, times, state, f"forces[{index}].magnitude")
        vector = scale(magnitude, rotate(np.array([1.0, 0.0]), direction))
        forces.append(AppliedForce(f.name, f.link, f.point, P.p, P.v, vector))
    moments = []
    for index, m in enumerate(dynamics.torques):
        omega = motion.links[m.link].omega
        assert omega is not None
        value = _evaluate(m.moment, times, state, f"torques[{index}].moment")
        moments.append(AppliedMoment(m.name, m.link, value, omega))
    return forces, moments


def _evaluate(expression: StateExpression, times: Array, state: State, path: str) -> Array:
    """The expression's values, or its error with the field it belongs to."""
    try:
        return expression.evaluate(times, state)
    except InvalidExpression as error:
        raise InvalidExpression(
            f"{path}: {error.message}", error.position, error.expression
        ) from None

"""RPR: a slotted lever turning about a known pivot, its slot through a known pin (the inverted
slider-crank, the quick-return's slotted lever); the unknown is the lever's angle."""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from solver.kinematics.rigid import Array, LinkMotion, PointMotion, cross, dot
from solver.position.groups.base import Closure, Known, Placed, Turning, Where
from solver.position.groups.loci import Piece, root

if TYPE_CHECKING:
    from solver.position.topology import LeverStep


@dataclass(frozen=True)
class LeverSolution:
    """Angle and rates of a slotted lever, and the sine of the angle between slot and r."""

    beta: Array
    omega: Array | None
    alpha: Array | None
    gradient_sine: Array


def lever_margin(pivot: PointMotion, pin: PointMotion, offset: float) -> Piece:
    """The slot meets the pin where |AP| >= |e|: margin m = |r| - |e| (r = P - A; negative: no
    slot through P; one smooth piece) and, with velocities, its rate dm/du = r.(v_P - v_A) / |r|."""
    r = pin.p - pivot.p
    length = np.sqrt(dot(r, r))
    rate = None
    if pin.v is not None and pivot.v is not None:
        rate = dot(r, pin.v - pivot.v) / np.where(length > 0.0, length, 1.0)
    return length - abs(offset), rate


def slotted_lever(
    pivot: PointMotion,
    pin: PointMotion,
    offset: float,
    sign: Array | float,
    order: int,
    known: tuple[Array, float] | None = None,
) -> LeverSolution:
    """The direction beta of a slot through ``pin``, in a lever turning about ``pivot``.

    The slot line keeps the signed offset e = u x (P - A) from the pivot, u = (cos beta,
    sin beta). With r = P - A: beta = atan2(r) - atan2(e, sign sqrt(|r|^2 - e^2)).
    Differentiating u x r = e once and twice:
    omega = (u x v_rel) / (u.r),  alpha = (u x a_rel - 2 omega u.v_rel - omega^2 e) / (u.r).
    ``known`` = (mask, beta): samples where the direction is known (the drawn pose).
    """
    r = pin.p - pivot.p
    r2 = dot(r, r)
    along = sign * root(r2 - offset**2, r2)
    beta = np.arctan2(r[:, 1], r[:, 0]) - np.arctan2(offset, along)
    if known is not None:
        beta[known[0]] = known[1]
    u = np.stack((np.cos(beta), np.sin(beta)), axis=-1)
    u_r = dot(u, r)
    safe = np.where(u_r != 0.0, u_r, np.inf)
    omega = alpha = None
    if order >= 1:
        assert pin.v is not None and pivot.v is not None
        v_rel = pin.v - pivot.v
        omega = cross(u, v_rel) / safe
        if order >= 2:
            assert pin.a is not None and pivot.a is not None
            a_rel = pin.a - pivot.a
            alpha = (cross(u, a_rel) - 2.0 * omega * dot(u, v_rel) - omega**2 * offset) / safe
    gradient_sine = np.abs(u_r) / np.sqrt(np.where(r2 > 0.0, r2, 1.0))
    return LeverSolution(beta, omega, alpha, gradient_sine)


class LeverGroup:
    """The slotted lever as a closed-form group (``groups.Group``)."""

    kind = "RPR"

    def close(self, step: LeverStep, known: Known) -> Closure:
        pivot, pin = known.points[step.pivot], known.points[step.pin]
        piece = lever_margin(pivot, pin, step.offset)

        def describe() -> str:
            return (
                f"|{step.pivot}{step.pin}| is shorter than the offset "
                f"{abs(step.offset):.6g} m of the slot of '{step.link}' from its pivot {step.pivot}"
            )

        def place(sign: Array | float, order: int) -> Placed:
            drawn = math.atan2(step.direction0[1], step.direction0[0])
            solution = slotted_lever(pivot, pin, step.offset, sign, order, (known.at_drawn, drawn))
            theta = solution.beta - drawn
            link = LinkMotion(known.drawn(step.pivot), pivot, theta, solution.omega, solution.alpha)
            return Placed(solution.gradient_sine, links={step.link: link})

        label = f"the slot of '{step.link}'"
        return Closure(label, piece[0], lambda: (piece,), describe, True, place)

    def gradients(self, step: LeverStep, where: Where, turning: Turning) -> None:
        """None: ``polish`` does not check a lever's branch (its restarts keep the dyads')."""
        return None


GROUP = LeverGroup()

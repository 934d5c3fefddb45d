"""A spatial chain over time: the chain of the scene moved by its joints, analysed at every instant.

Joint k's variable moves from the scene's pose (t = 0) as q_k(t) = rate t + rate_dot t^2 / 2, so
its rate at t is rate + rate_dot t. The pose at t is the product of exponentials of the joints'
screws, taken in the scene's frame at t = 0: body k maps a point x of the scene to

    G_k(t) x = G_1(q_1) G_2(q_2) ... G_k(q_k) x,
    G_j(q) x = Rot(e_j, q) (x - O_j) + O_j   (revolute: Rodrigues' rotation about e_j through O_j),
    G_j(q) x = x + q e_j                     (prismatic: a translation along e_j).

Joint k's axis and origin at t are carried by body k-1 (e_k(t) = R_{k-1} e_k, O_k(t) =
G_{k-1} O_k), every point by its own body. The moved chain, with arrays over the samples, is then
analysed by the instant's own walk (``solver.kinematics.spatial.analyze_spatial_chain``),
vectorised.
"""

from __future__ import annotations

import math
from collections.abc import Iterable
from dataclasses import dataclass

import numpy as np

from solver.analysis.sweeps import check_samples
from solver.errors import InvalidScene
from solver.kinematics.spatial import (
    GROUND,
    SpatialAnalysis,
    SpatialChain,
    SpatialJoint,
    SpatialPoint,
    analyze_spatial_chain,
)
from solver.model.quantities import normalise_quantities
from solver.model.scene import MAX_TIME


@dataclass(frozen=True)
class SpatialSweep:
    """The chain at ``time`` (N,): the moved chain (joints' origins and axes (N, 3), rates
    (N, 1)), each joint's displacement q_k(t) (N,) and the analysis at every sample."""

    time: np.ndarray
    moved: SpatialChain
    displacement: dict[str, np.ndarray]
    analysis: SpatialAnalysis
    quantities: frozenset[str]


def displacement(joint: SpatialJoint, time: np.ndarray) -> np.ndarray:
    """q_k(t) = rate t + rate_dot t^2 / 2 (rad for a revolute joint, m for a prismatic one)."""
    return joint.rate * time + 0.5 * joint.rate_dot * time * time


def rodrigues(axis: np.ndarray, angle: np.ndarray) -> np.ndarray:
    """Rot(e, q) = I + sin q [e]x + (1 - cos q) [e]x^2, one (3, 3) matrix per angle: (N, 3, 3)."""
    k = np.array([[0.0, -axis[2], axis[1]], [axis[2], 0.0, -axis[0]], [-axis[1], axis[0], 0.0]])
    s, c = np.sin(angle)[:, None, None], np.cos(angle)[:, None, None]
    rotation: np.ndarray = np.eye(3) + s * k + (1.0 - c) * (k @ k)
    return rotation


def _apply(rotation: np.ndarray, x: np.ndarray) -> np.ndarray:
    """R x for a stack of matrices (N, 3, 3) and one vector (3,) or a stack (N, 3)."""
    moved: np.ndarray = np.einsum("nij,j->ni" if x.ndim == 1 else "nij,nj->ni", rotation, x)
    return moved


def move_chain(chain: SpatialChain, time: np.ndarray) -> tuple[SpatialChain, dict[str, np.ndarray]]:
    """The chain at every instant of ``time`` (arrays over the samples) by the product of
    exponentials, and each joint's displacement q_k(t)."""
    n = time.size
    rotation = np.broadcast_to(np.eye(3), (n, 3, 3))  # R_{k-1}, body k-1 in the scene's frame
    shift = np.zeros((n, 3))  # d_{k-1}: G_{k-1} x = R_{k-1} x + d_{k-1}
    frames = {GROUND: (rotation, shift)}
    joints: list[SpatialJoint] = []
    displacements: dict[str, np.ndarray] = {}
    for joint in chain.joints:
        q = displacement(joint, time)
        displacements[joint.name] = q
        joints.append(
            SpatialJoint(
                name=joint.name,
                type=joint.type,
                origin=_apply(rotation, joint.origin) + shift,
                axis=_apply(rotation, joint.axis),
                rate=(joint.rate + joint.rate_dot * time)[:, None],
                rate_dot=joint.rate_dot,
            )
        )
        if joint.type == "revolute":  # G_{k-1} G_k: R_{k-1} Rot, R_{k-1} (O - Rot O) + d_{k-1}
            turn = rodrigues(joint.axis, q)
            shift = _apply(rotation, joint.origin - _apply(turn, joint.origin)) + shift
            rotation = rotation @ turn
        else:  # G_{k-1} G_k: R_{k-1}, R_{k-1} q e + d_{k-1}
            shift = _apply(rotation, joint.axis) * q[:, None] + shift
        frames[joint.name] = (rotation, shift)
    points = tuple(
        SpatialPoint(p.name, p.body, _apply(frames[p.body][0], p.position) + frames[p.body][1])
        for p in chain.points
    )
    return SpatialChain(tuple(joints), points, chain.title), displacements


def sweep_spatial_time(
    chain: SpatialChain,
    t0: float,
    t1: float,
    samples: int,
    quantities: Iterable[str] | None = None,
) -> SpatialSweep:
    """The chain at ``samples`` instants from t0 to t1 (POST /sweep with ``time_range``)."""
    check_samples(samples)
    if not (math.isfinite(t0) and math.isfinite(t1) and t1 > t0):
        raise InvalidScene(f"time_range: expected [t0, t1] with t1 > t0, got [{t0}, {t1}]")
    if max(abs(t0), abs(t1)) > MAX_TIME:
        raise InvalidScene(f"time_range: |t| must not exceed {MAX_TIME:g} s, got [{t0}, {t1}]")
    wanted = normalise_quantities(["position"] if quantities is None else quantities)
    time = np.linspace(t0, t1, samples)
    moved, displacements = move_chain(chain, time)
    return SpatialSweep(time, moved, displacements, analyze_spatial_chain(moved), wanted)

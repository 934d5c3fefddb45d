"""Dry friction at the joints: the Newton-Euler system with friction, solved by iteration.

At a revolute joint with pin radius r and coefficient mu the reaction F (first link on second)
is tangent to the friction circle of radius mu r on the side that opposes the relative rotation:
the second link gets the friction moment

    M_f = -mu r |F| sgn(omega_rel),        omega_rel = omega_second - omega_first

and the first -M_f. At a slot (slider or prismatic joint) the second link gets the Coulomb force

    f = -mu |N| sgn(v_rel . u) u,          v_rel = v_P(second) - v_P(first)

at P, along the slot's direction u (turned with its guide), and the first -f; the total force is
the normal force N k x u plus f, tilted from the normal by the friction angle atan mu. (A
prismatic joint's moment makes edge forces whose friction needs the block's length, which the
scene does not give: only its N is taken.) Where the relative motion is zero the friction is
left out (its sense is not defined).

|F| and |N| depend on the unknowns u, so the equations are nonlinear. Iteration k starts from
the frictionless answer u_0 and linearises |F| = e_k . F (e_k = F_k / |F_k|) and |N| = sgn(N_k) N,
so the friction is a known multiple of the unknowns: (A + B(u_k)) u_{k+1} = b. At a fixed point
the linearisation is exact. The friction power sum M_f omega_rel + f . v_rel = -sum mu r |F|
|omega_rel| - sum mu |N| |v_rel . u| is never positive.

Self-locking: as mu grows from 0 the driving torque is u = (A + B)^-1 b; it goes through infinity
where det(A + B) passes through zero. Where det(A + B) / det A <= 0 at the answer (or the senses
flip from one iteration to the next, which is the same thing seen by the iteration), no finite
driving torque moves the mechanism in the prescribed sense: it locks.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from solver.dynamics.newton_euler import DENSE_LIMIT, System, neighbour_mean
from solver.kinematics.rigid import Array, cross, dot, rigid_body_velocity, rotate
from solver.model.scene import LinkageScene
from solver.position.assembly import Motion

# The iteration stops where no unknown changes by more than this fraction of the largest one.
FRICTION_TOLERANCE = 1e-13
MAX_FRICTION_ITERATIONS = 60


@dataclass(frozen=True)
class FrictionSolution:
    """The unknowns with friction (N, m; NaN where the mechanism locks or the iteration did not
    converge), each friction joint's force (slot, (N, 2)) or moment (pin, (N,)) on its second
    link, the friction power (N,), and where and why the answer is missing."""

    solution: Array
    forces: dict[int, Array]
    moments: dict[int, Array]
    power: Array
    locked: Array
    converged: Array
    iterations: int
    causes: dict[int, tuple[int, ...]]  # locked sample -> the joints whose friction locks it


def has_friction(scene: LinkageScene) -> bool:
    """True where some joint carries friction (with a zero coefficient too)."""
    return any(joint.friction is not None for joint in scene.joints)


def _active(scene: LinkageScene) -> list[int]:
    """The joints whose friction is not zero."""
    out = []
    for index, joint in enumerate(scene.joints):
        f = joint.friction
        if f is not None and (f.circle_radius if joint.type == "revolute" else f.coefficient) > 0:
            out.append(index)
    return out


@dataclass(frozen=True)
class _Joint:
    """A friction joint's data over the samples: its columns in u, the rows of its links, the
    relative motion's sense, and (slots) the slot direction and the arms."""

    index: int
    columns: tuple[int, ...]
    rows: tuple[int | None, int | None]  # first, second link (None: the ground)
    coefficient: float  # mu r (pin) or mu (slot)
    sense: Array  # sgn(omega_rel) or sgn(v_rel . u)
    relative: Array  # omega_rel or v_rel . u
    direction: Array | None  # u (N, 2) at a slot
    arms: tuple[Array | None, Array | None]  # P - R of the first and second link (slot)


def _joints(scene: LinkageScene, motion: Motion, system: System) -> list[_Joint]:
    row = {name: 3 * i for i, name in enumerate(scene.moving_links)}
    columns: dict[int, list[int]] = {}
    for column, (kind, index, axis) in enumerate(system.origins):
        if kind == "joint" and axis != 2:
            columns.setdefault(index, []).append(column)
    out = []
    for index in _active(scene):
        joint = scene.joints[index]
        friction = joint.friction
        assert friction is not None
        first, second = (motion.links[name] for name in joint.links)
        assert first.omega is not None and second.omega is not None
        rows = tuple(row.get(name) for name in joint.links)
        direction: Array | None = None
        arms: tuple[Array | None, ...] = (None, None)
        if joint.type == "revolute":  # omega_rel
            coefficient, relative = friction.circle_radius, second.omega - first.omega
        else:  # v_rel . u, with P's arms from each link's reference point
            assert joint.axis is not None
            P = second.point(scene.drawn(joint.point))
            assert P.v is not None and first.anchor.v is not None
            direction = rotate(np.array(joint.axis), first.theta)
            v_first = rigid_body_velocity(first.anchor.v, first.omega, P.p - first.anchor.p)
            coefficient, relative = friction.coefficient, dot(P.v - v_first, direction)
            arms = tuple(
                None if name == scene.ground else P.p - system.reference[name]
                for name in joint.links
            )
        out.append(
            _Joint(
                index,
                tuple(columns[index]),
                (rows[0], rows[1]),
                coefficient,
                np.sign(relative),
                relative,
                direction,
                (arms[0], arms[1]),
            )
        )
    return out


def _terms(joint: _Joint, u: Array) -> tuple[list[tuple[int, int, Array]], Array]:
    """B's entries of one joint linearised at u, and the friction (moment (N,) or force
    (N, 2) on the second link) they give at u."""
    entries: list[tuple[int, int, Array]] = []
    first, second = joint.rows
    if joint.direction is None:  # a pin: M_f = -mu r sgn(omega_rel) e . F on the second link
        F = u[:, list(joint.columns)]
        size = np.hypot(F[:, 0], F[:, 1])
        e = F / np.where(size > 0, size, 1.0)[:, None]
        c = -joint.coefficient * joint.sense[:, None] * e
        for row, sign in ((second, 1.0), (first, -1.0)):
            if row is not None:
                for k, column in enumerate(joint.columns):
                    entries.append((row + 2, column, sign * c[:, k]))
        return entries, c[:, 0] * F[:, 0] + c[:, 1] * F[:, 1]
    # a slot: f = -mu sgn(N) sgn(v_rel . u) N u at P on the second link
    column = joint.columns[0]
    N = u[:, column]
    d = -joint.coefficient * (np.sign(N) * joint.sense)[:, None] * joint.direction
    for row, sign, arm in ((second, 1.0, joint.arms[1]), (first, -1.0, joint.arms[0])):
        if row is not None:
            assert arm is not None
            entries.append((row, column, sign * d[:, 0]))
            entries.append((row + 1, column, sign * d[:, 1]))
            entries.append((row + 2, column, sign * cross(arm, d)))
    return entries, d * N[:, None]


def _blocks(entries: list[tuple[int, int, Array]], n: int, m: int, chunk: slice) -> Array:
    A = np.zeros((chunk.stop - chunk.start, m, m))
    for row, column, values in entries:
        A[:, row, column] += np.broadcast_to(values, (n,))[chunk]
    return A


def _solve(entries: list[tuple[int, int, Array]], rhs: Array, skip: Array) -> tuple[Array, Array]:
    """u of every sample and sgn det A (0 where singular); ``skip`` samples get an identity."""
    n, m = rhs.shape
    u, sign = np.zeros((n, m)), np.zeros(n)
    step = max(1, DENSE_LIMIT // (m * m))
    for start in range(0, n, step):
        chunk = slice(start, min(n, start + step))
        A = _blocks(entries, n, m, chunk)
        A[skip[chunk]] = np.eye(m)
        s, _ = np.linalg.slogdet(A)
        good = s != 0.0
        A[~good] = np.eye(m)
        b = np.where(good[:, None], rhs[chunk], 0.0)
        u[chunk] = np.linalg.solve(A, b[..., None])[..., 0]
        sign[chunk] = s
    return u, sign


def solve_with_friction(
    scene: LinkageScene,
    motion: Motion,
    system: System,
    frictionless: Array,
    singular: Array,
    cyclic: bool = True,
) -> FrictionSolution:
    """The Newton-Euler system with the joints' friction (see the module docstring), iterated
    from the ``frictionless`` unknowns u_0; ``singular`` samples take their neighbours' mean."""
    n = frictionless.shape[0]
    joints = _joints(scene, motion, system)
    base = list(system.entries)
    skip = np.zeros(n, dtype=bool)
    skip[singular] = True
    if not joints:  # zero coefficients: today's answer, bit for bit
        nothing = np.zeros(n, dtype=bool)
        return FrictionSolution(frictionless, {}, {}, np.zeros(n), nothing, ~nothing, 0, {})
    _, sign0 = _solve(base, system.rhs, skip)
    u = frictionless
    scale = np.max(np.abs(frictionless), axis=1)
    converged = np.zeros(n, dtype=bool)
    flipped = np.zeros(n, dtype=bool)
    iterations = 0
    sign = sign0
    while iterations < MAX_FRICTION_ITERATIONS and not converged.all():
        iterations += 1
        extra = [entry for joint in joints for entry in _terms(joint, u)[0]]
        u_next, sign = _solve(base + extra, system.rhs, skip)
        change = np.max(np.abs(u_next - u), axis=1)
        converged = change <= FRICTION_TOLERANCE * np.maximum(scale, np.max(np.abs(u_next), axis=1))
        flipped |= sign * sign0 <= 0
        u = u_next
    locked = ((sign * sign0 <= 0) | (flipped & ~converged)) & ~skip
    converged |= skip
    forces, moments = {}, {}
    power = np.zeros(n)
    for joint in joints:
        value = _terms(joint, u)[1]
        if joint.direction is None:
            moments[joint.index] = value
            power += value * joint.relative
        else:
            forces[joint.index] = value
            power += dot(value, joint.direction) * joint.relative
    missing = locked | ~converged
    u = u.copy()
    u[missing] = np.nan
    neighbour_mean(u, singular, cyclic)
    for values in (*forces.values(), *moments.values(), power):
        values[missing] = np.nan
        neighbour_mean(values, singular, cyclic)
    causes = {
        int(k): tuple(
            joint.index for joint in joints if _locks(joint, base, system.rhs, frictionless, k)
        )
        for k in np.flatnonzero(locked)[:1]
    }
    return FrictionSolution(u, forces, moments, power, locked, converged, iterations, causes)


def _locks(
    joint: _Joint, base: list[tuple[int, int, Array]], rhs: Array, u0: Array, k: int
) -> bool:
    """True where this joint's friction alone, linearised at the frictionless answer u_0, makes
    det(A + B) change sign at sample k: it alone would lock the mechanism there."""
    pick = slice(k, k + 1)
    n = rhs.shape[0]
    one = [(row, column, np.broadcast_to(v, (n,))[pick]) for row, column, v in base]
    alone = _Joint(
        joint.index,
        joint.columns,
        joint.rows,
        joint.coefficient,
        joint.sense[pick],
        joint.relative[pick],
        None if joint.direction is None else joint.direction[pick],
        (
            None if joint.arms[0] is None else joint.arms[0][pick],
            None if joint.arms[1] is None else joint.arms[1][pick],
        ),
    )
    no = np.zeros(1, dtype=bool)
    _, before = _solve(one, rhs[pick], no)
    _, after = _solve(one + _terms(alone, u0[pick])[0], rhs[pick], no)
    return bool(before[0] * after[0] <= 0)

"""Loop-closure equations in link coordinates, and Newton-Raphson for groups with no closed form.

Every moving link has coordinates q = (x, y, theta): the world position of its anchor (its first
point) and its rotation from the drawn pose, so a point drawn at X0 is at
X = c + R(theta) (X0 - A0). The joints give the constraints

- revolute at P between links i, j:  X_i(P) - X_j(P) = 0
- slider at P (guide g, follower f):  n_g . (X_f(P) - Q_g) = 0, Q_g the guide's point drawn at P
- prismatic: the slider equation and theta_f - theta_g = 0

with the analytic Jacobian J = dPhi/dq. Velocities solve J qdot = b_v and accelerations
J qddot = b_a (the known links' motion and the quadratic velocity terms on the right). The same
system with every moving link unknown and the drivers' rows added is the linkage's velocity
system, whose (dimensionless) condition number is reported.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass

import numpy as np

from solver.rigid import Array, LinkMotion, PointMotion
from solver.scene import Joint, LinkageScene

NEWTON_TOLERANCE = 1e-13  # residual, relative to the scene size
NEWTON_MAX_ITERATIONS = 50


@dataclass(frozen=True)
class NewtonReport:
    """How Newton-Raphson went: the worst sample's iterations and residual; which converged."""

    links: tuple[str, ...]
    converged: Array
    iterations: int
    residual_norm: float
    tolerance: float
    message: str


@dataclass(frozen=True)
class _Pose:
    """One link at one sample: anchor position, rotation from drawn, and rates (if known)."""

    c: Array
    theta: float
    v: Array
    omega: float
    a: Array
    alpha: float


def _kperp(r: Array) -> Array:
    return np.array([-r[1], r[0]])


class ConstraintSystem:
    """The constraint equations of the joints touching ``unknown`` links (and drivers, if asked)."""

    def __init__(self, scene: LinkageScene, unknown: Sequence[str], drivers: bool = False) -> None:
        self.scene = scene
        self.unknown = tuple(unknown)
        self.column = {link: 3 * k for k, link in enumerate(self.unknown)}
        self.joints: tuple[Joint, ...] = tuple(
            j for j in scene.joints if j.links[0] in self.column or j.links[1] in self.column
        )
        self.drivers = tuple(d.link for d in scene.drivers) if drivers else ()
        self.anchor0 = {name: scene.drawn(link.points[0]) for name, link in scene.links.items()}
        self.rows = sum(
            {"revolute": 2, "slider": 1, "prismatic": 2}[j.type] for j in self.joints
        ) + len(self.drivers)

    def _r(self, pose: _Pose, link: str, point: str) -> Array:
        """R(theta) (X0 - A0): the anchor-to-point vector of ``link``'s point."""
        c, s = np.cos(pose.theta), np.sin(pose.theta)
        d = self.scene.drawn(point) - self.anchor0[link]
        return np.array([c * d[0] - s * d[1], s * d[0] + c * d[1]])

    def _slot(self, joint: Joint, pose: _Pose) -> tuple[Array, Array]:
        assert joint.axis is not None
        c, s = np.cos(pose.theta), np.sin(pose.theta)
        w = np.array([c * joint.axis[0] - s * joint.axis[1], s * joint.axis[0] + c * joint.axis[1]])
        return w, _kperp(w)

    def equations(self, poses: Mapping[str, _Pose], order: int) -> tuple[Array, Array, Array]:
        """(Phi, J, b): residual, Jacobian and the right-hand side of order 1 or 2 (0: zeros)."""
        phi = np.zeros(self.rows)
        J = np.zeros((self.rows, 3 * len(self.unknown)))
        b = np.zeros(self.rows)
        row = 0

        def add(link: str, k: int, grad_c: Array, grad_theta: float) -> None:
            if link in self.column:
                col = self.column[link]
                J[k, col : col + 2] += grad_c
                J[k, col + 2] += grad_theta

        def point_term(link: str, point: str, n: Array, k: int, sign: float) -> None:
            """sign n.X_link(point): Jacobian, and its known or quadratic part of b."""
            pose = poses[link]
            r = self._r(pose, link, point)
            add(link, k, sign * n, sign * float(n @ _kperp(r)))
            phi[k] += sign * float(n @ (pose.c + r))
            known = link not in self.column
            if order == 1 and known:
                b[k] -= sign * float(n @ (pose.v + pose.omega * _kperp(r)))
            elif order == 2:
                quadratic = -(pose.omega**2) * r
                full = pose.a + pose.alpha * _kperp(r) + quadratic
                b[k] -= sign * float(n @ (full if known else quadratic))

        def angle_term(link: str, k: int, sign: float) -> None:
            pose = poses[link]
            add(link, k, np.zeros(2), sign)
            phi[k] += sign * pose.theta
            if link not in self.column and order:
                b[k] -= sign * (pose.omega if order == 1 else pose.alpha)

        for joint in self.joints:
            i, j = joint.links
            if joint.type == "revolute":
                for axis in (np.array([1.0, 0.0]), np.array([0.0, 1.0])):
                    point_term(i, joint.point, axis, row, 1.0)
                    point_term(j, joint.point, axis, row, -1.0)
                    row += 1
                continue
            guide = poses[i]
            w, n = self._slot(joint, guide)
            point_term(j, joint.point, n, row, 1.0)
            point_term(i, joint.point, n, row, -1.0)
            # n turns with the guide: dn/dtheta_g = -w, so add -(w.d) to the guide's column
            # and its rates' terms (-omega_g w.d, -alpha_g w.d - 2 omega_g w.(v_f - v_Q)).
            f = poses[j]
            d = f.c + self._r(f, j, joint.point) - guide.c - self._r(guide, i, joint.point)
            add(i, row, np.zeros(2), -float(w @ d))
            if i not in self.column and order == 1:
                b[row] += guide.omega * float(w @ d)
            if order == 2:
                v_f = f.v + f.omega * _kperp(self._r(f, j, joint.point))
                v_q = guide.v + guide.omega * _kperp(self._r(guide, i, joint.point))
                b[row] += 2.0 * guide.omega * float(w @ (v_f - v_q))
                if i not in self.column:
                    b[row] += guide.alpha * float(w @ d)
            row += 1
            if joint.type == "prismatic":
                angle_term(j, row, 1.0)
                angle_term(i, row, -1.0)
                row += 1
        for link in self.drivers:
            angle_term(link, row, 1.0)
            row += 1
        return phi, J, b


class KnownPoses:
    """The known links' poses and rates sample by sample, each link's anchor moved once to its
    first point (the anchor the constraint equations use)."""

    def __init__(self, links: Mapping[str, LinkMotion], scene: LinkageScene) -> None:
        self.links = links
        self.first = {
            name: motion.point(scene.drawn(scene.links[name].points[0]))
            for name, motion in links.items()
        }

    def at(self, k: int) -> dict[str, _Pose]:
        zero = np.zeros(2)
        poses = {}
        for name, motion in self.links.items():
            first = self.first[name]
            poses[name] = _Pose(
                first.p[k],
                float(motion.theta[k]),
                zero if first.v is None else first.v[k],
                0.0 if motion.omega is None else float(motion.omega[k]),
                zero if first.a is None else first.a[k],
                0.0 if motion.alpha is None else float(motion.alpha[k]),
            )
        return poses


def _unknown_poses(system: ConstraintSystem, q: Array, qd: Array, qdd: Array) -> dict[str, _Pose]:
    return {
        link: _Pose(
            q[3 * k : 3 * k + 2],
            float(q[3 * k + 2]),
            qd[3 * k : 3 * k + 2],
            float(qd[3 * k + 2]),
            qdd[3 * k : 3 * k + 2],
            float(qdd[3 * k + 2]),
        )
        for k, link in enumerate(system.unknown)
    }


def _continuation_legs(
    known: Mapping[str, LinkMotion], samples: int
) -> list[list[tuple[int, tuple[int, ...]]]]:
    """Samples in solving order, each with the already solved neighbours to predict from.

    Continuation starts at the sample where the known links are nearest their drawn pose (the
    drawn branch) and runs outwards in two legs, to the last sample and to the first.
    """
    away = np.zeros(samples)
    for motion in known.values():
        away += np.abs(np.angle(np.exp(1j * motion.theta)))
    start = int(np.argmin(away))
    legs = []
    for leg in (list(range(start, samples)), list(range(start, -1, -1))):
        legs.append([(k, tuple(leg[max(i - 2, 0) : i][::-1])) for i, k in enumerate(leg)])
    legs[1] = legs[1][1:]  # the starting sample is solved once, in the first leg
    return legs


def _newton(
    system: ConstraintSystem, fixed: Mapping[str, _Pose], q: Array, tolerance: float
) -> tuple[Array, float, int]:
    """Newton-Raphson q <- q - J^+ Phi(q) from ``q``: (solution, residual norm, iterations)."""
    zero = np.zeros(q.size)
    residual, iterations = np.inf, 0
    while iterations < NEWTON_MAX_ITERATIONS:
        phi, J, _ = system.equations({**fixed, **_unknown_poses(system, q, zero, zero)}, 0)
        residual = float(np.linalg.norm(phi))
        step = np.linalg.lstsq(J, phi, rcond=None)[0]
        if residual <= tolerance:
            # One more step polishes a converged iterate to rounding (quadratic convergence).
            phi_next = system.equations(
                {**fixed, **_unknown_poses(system, q - step, zero, zero)}, 0
            )[0]
            if float(np.linalg.norm(phi_next)) < residual:
                q, residual = q - step, float(np.linalg.norm(phi_next))
            break
        q = q - step
        iterations += 1
    return q, residual, iterations


def solve_group(
    scene: LinkageScene,
    group: Sequence[str],
    known: Mapping[str, LinkMotion],
    samples: int,
    order: int,
) -> tuple[dict[str, LinkMotion], NewtonReport]:
    """Newton-Raphson for the links of ``group`` at every sample, then their rates.

    Each sample starts from its neighbours' solutions extrapolated linearly (the first from the
    drawn pose), which keeps the assembly branch along a sweep.
    """
    system = ConstraintSystem(scene, group)
    n = 3 * len(group)
    tolerance = NEWTON_TOLERANCE * scene.size
    q_all = np.zeros((samples, n))
    qd_all = np.zeros((samples, n))
    qdd_all = np.zeros((samples, n))
    converged = np.zeros(samples, dtype=bool)
    worst_iterations, worst_residual = 0, 0.0
    drawn = np.concatenate([np.append(system.anchor0[link], 0.0) for link in group])
    known_poses = KnownPoses(known, scene)
    for leg in _continuation_legs(known, samples):
        for k, previous in leg:
            q = drawn
            if len(previous) == 2:
                q = 2.0 * q_all[previous[0]] - q_all[previous[1]]
            elif previous:
                q = q_all[previous[0]]
            fixed = known_poses.at(k)
            q, residual, iterations = _newton(system, fixed, q, tolerance)
            worst_iterations = max(worst_iterations, iterations)
            worst_residual = max(worst_residual, residual)
            q_all[k] = q
            converged[k] = residual <= tolerance
            if not converged[k]:
                break  # past a limit position the rest of this leg cannot close either
            zero = np.zeros(n)
            if order >= 1:
                _, J, b = system.equations({**fixed, **_unknown_poses(system, q, zero, zero)}, 1)
                qd_all[k] = np.linalg.lstsq(J, b, rcond=None)[0]
            if order >= 2:
                poses = {**fixed, **_unknown_poses(system, q, qd_all[k], zero)}
                _, J, b = system.equations(poses, 2)
                qdd_all[k] = np.linalg.lstsq(J, b, rcond=None)[0]
    motions = {}
    for index, link in enumerate(group):
        s = slice(3 * index, 3 * index + 2)
        anchor = PointMotion(
            q_all[:, s], qd_all[:, s] if order >= 1 else None, qdd_all[:, s] if order >= 2 else None
        )
        motions[link] = LinkMotion(
            system.anchor0[link],
            anchor,
            q_all[:, 3 * index + 2],
            qd_all[:, 3 * index + 2] if order >= 1 else None,
            qdd_all[:, 3 * index + 2] if order >= 2 else None,
        )
    message = f"Newton-Raphson closed the loop of {', '.join(group)}"
    if not np.all(converged):
        message = (
            f"Newton-Raphson did not close the loop of {', '.join(group)}: residual "
            f"{worst_residual:.3g} m > tolerance {tolerance:.3g} m after {worst_iterations} "
            "iterations"
        )
    report = NewtonReport(
        tuple(group), converged, worst_iterations, worst_residual, tolerance, message
    )
    return motions, report


def velocity_condition_number(
    scene: LinkageScene, links: Mapping[str, LinkMotion], k: int
) -> float:
    """cond(J) of the whole velocity system (drivers included), angle columns scaled by the size.

    Scaling the rotation columns and the angle rows by the scene size makes J dimensionless, so
    the number does not change when every length is multiplied by k.
    """
    moving = scene.moving_links
    system = ConstraintSystem(scene, moving, drivers=True)
    _, J, _ = system.equations(KnownPoses(links, scene).at(k), 0)
    size = scene.size
    J = J.copy()
    J[:, 2::3] /= size
    angle_rows = [r for r in range(J.shape[0]) if not np.any(J[r, 0::3]) and not np.any(J[r, 1::3])]
    J[angle_rows] *= size
    if J.shape[0] != J.shape[1]:
        return float("inf")
    singular_values = np.linalg.svd(J, compute_uv=False)
    if singular_values[-1] == 0.0:
        return float("inf")
    return float(singular_values[0] / singular_values[-1])

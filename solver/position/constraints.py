"""Loop-closure equations in link coordinates, their Jacobian, the velocity and acceleration
solves, and the condition number of the velocity equations.

Every moving link has coordinates q = (x, y, theta): the world position of its anchor (its first
point) and its rotation from the drawn pose, so a point drawn at X0 is at
X = c + R(theta) (X0 - A0). The joints give the constraints

- revolute at P between links i, j:  X_i(P) - X_j(P) = 0
- slider at P (guide g, follower f):  n_g . (X_f(P) - Q_g) = 0, Q_g the guide's point drawn at P
- prismatic: the slider equation and theta_f - theta_g = 0
- a driver whose angle is given: theta_d - turn_d = 0

with the analytic Jacobian J = dPhi/dq. Velocities solve J qdot = b_v and accelerations
J qddot = b_a (the known links' motion and the quadratic velocity terms on the right). The same
system with every moving link unknown and the drivers' rows added is the linkage's velocity
system, whose (dimensionless) condition number is reported.

Each row's entries and rates are written once, as functions of the row's geometry
(``unit_entries``, ``held_angle_entries``, ``revolute_rotation_entries``, ``slider_axes``,
``slider_rotation_entries``, ``slider_velocity_rhs``, ``slider_acceleration_rhs``): the
joint-by-joint evaluation (``ConstraintSystem``), the velocity system at one pose
(``velocity_jacobian``) and a point on a line (``loci.Line``, a slider row whose follower is the
point) place them. The rows linear in (q, cos theta, sin theta) are also held as constant
matrices (``LinearForm``: its K_q the system's constant entries, J's rotation entries
``rotation_entries``, the curvature terms ``turning_terms``), and ``Rotations`` is Q^T of them.

Everything is evaluated for M samples at once: Phi is (M, rows), J (M, rows, 3 x unknown links),
so the equations of every sample of a sweep are solved together with ``numpy.linalg.solve`` on
the stacked Jacobians (Newton-Raphson on them is ``solver.position.newton``).
"""

from __future__ import annotations

import copy
import weakref
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass
from functools import cached_property
from typing import TypeVar

import mpmath as mp
import numpy as np

from solver.kinematics.rigid import Array, LinkMotion, PointMotion, dot, perp, rotate_by
from solver.model.scene import Joint, LinkageScene

JOINT_ROWS = {"revolute": 2, "slider": 1, "prismatic": 2}  # rows of each joint type
Link = TypeVar("Link", int, str)  # a link by its index (``ConstraintSystem``) or its name
DENSE_UNKNOWNS = 24  # LinearForm on many samples up to this many unknowns (ConstraintSystem._dense)


@dataclass(frozen=True)
class _Pose:
    """One link at one sample: anchor position, rotation from drawn, and rates (if known)."""

    c: Array
    theta: float
    v: Array
    omega: float
    a: Array
    alpha: float


@dataclass(frozen=True)
class States:
    """Known links over M samples: anchor (first point) position, rotation from drawn, rates."""

    c: Array  # (M, 2)
    theta: Array  # (M,)
    v: Array  # (M, 2)
    omega: Array  # (M,)
    a: Array  # (M, 2)
    alpha: Array  # (M,)


def _cos_sin(theta: Array) -> tuple[Array, Array]:
    """cos and sin elementwise, in the arithmetic of ``theta`` (mpmath for an object array)."""
    if theta.dtype != object:
        return np.cos(theta), np.sin(theta)
    pairs = np.empty((*theta.shape, 2), dtype=object)
    pairs.reshape(-1, 2)[:] = [mp.cos_sin(x) for x in theta.flat]
    return pairs[..., 0], pairs[..., 1]


@dataclass(frozen=True)
class _Links:
    """Every link's (M, L) state arrays at once, the cosine and sine of its rotation, and the
    order of the rates wanted (``ConstraintSystem.evaluate``)."""

    c: Array
    cos: Array
    sin: Array
    v: Array
    omega: Array
    a: Array
    alpha: Array
    order: int

    def velocity(self, link: Array, r: Array) -> Array:
        """v + omega k x r: the velocity of the links' points at arms r from their anchors."""
        return self.v[:, link] + self.omega[:, link, None] * perp(r)

    def side(self, link: Array, d: Array) -> tuple[Array, Array, Array | None]:
        """Point, anchor-to-point vector r and (order 1, 2) the point's rate terms."""
        r = rotate_by(d, self.cos[:, link], self.sin[:, link])
        rate = None
        if self.order == 1:
            rate = self.velocity(link, r)
        elif self.order == 2:
            rate = (
                self.a[:, link]
                + self.alpha[:, link, None] * perp(r)
                - (self.omega[:, link] ** 2)[..., None] * r
            )
        return self.c[:, link] + r, r, rate


class ConstraintSystem:
    """The constraint equations of the joints touching ``unknown`` links, and one row per link
    in ``angles`` holding its rotation (a driver's given turn); ``drivers=True`` adds every
    driver's row (the linkage's velocity system). ``exact`` converts the drawn coordinates and
    axes; given (``solver.position.polish``: to 40-digit mpmath numbers, an object array), Phi, J
    and b are evaluated in that arithmetic."""

    def __init__(
        self,
        scene: LinkageScene,
        unknown: Sequence[str],
        drivers: bool = False,
        angles: Sequence[str] = (),
        exact: Callable[[Array], Array] | None = None,
    ) -> None:
        number = exact or (lambda x: np.asarray(x, dtype=float))
        self._scene = weakref.ref(scene)  # not kept alive by its cached systems
        self.unknown = tuple(unknown)
        self.column = {link: 3 * k for k, link in enumerate(self.unknown)}
        self.names = tuple(scene.links)
        index = {name: k for k, name in enumerate(self.names)}
        self.anchor0 = {name: scene.drawn(link.points[0]) for name, link in scene.links.items()}
        self.angles = tuple(d.link for d in scene.drivers) if drivers else tuple(angles)
        joints = [j for j in scene.joints if j.links[0] in self.column or j.links[1] in self.column]
        self.known = tuple(
            sorted({link for j in joints for link in j.links if link not in self.column})
        )
        rows = self._joint_rows(joints, index, number, exact is not None)
        self.angle_rows = np.arange(rows, rows + len(self.angles))
        self.angle_links = np.array([index[link] for link in self.angles], dtype=int)
        self.rows = rows + len(self.angles)
        self.n = 3 * len(self.unknown)
        # Column of each scene link's x (or -1 where known), and the constant unit entries of J.
        self.col = np.array([self.column.get(name, -1) for name in self.names], dtype=int)
        self.unknown_index = np.array([index[link] for link in self.unknown], dtype=int)
        self._jacobian_layout()
        self.known_index = np.array([index[link] for link in self.known], dtype=int)
        # Rows that are lengths (scaled by the size in the condition number) and angles.
        self.length_rows = np.ones(self.rows, dtype=bool)
        self.length_rows[self.prismatic[:, 3]] = False
        self.length_rows[self.angle_rows] = False
        # The fast evaluation where the equations are linear in (q, cos theta, sin theta).
        self.linear = None if exact or self.sld.size else LinearForm(self)

    @property
    def scene(self) -> LinkageScene:
        """The scene, held weakly: a system in ``constraint_system``'s cache must not keep its
        scene alive (the cache forgets the scene's systems when the scene is freed)."""
        scene = self._scene()
        assert scene is not None, "a constraint system outlived its scene"
        return scene

    @cached_property
    def scaled(self) -> tuple[Array, Array, LinearForm | None]:
        """(column, row, form): the equations in coordinates x = q / column with lengths in scene
        sizes (column = (size, size, 1) per link, row = size on the length rows, 1 on the
        angles'), Phi / row, and their ``LinearForm`` (None where not linear): the path
        following's (``continuation.Branch``)."""
        size = self.scene.size
        column = np.tile([size, size, 1.0], len(self.unknown))
        row = np.where(self.length_rows, size, 1.0)
        return column, row, None if self.linear is None else self.linear.scaled(column, row)

    def _joint_rows(
        self,
        joints: Sequence[Joint],
        index: Mapping[str, int],
        number: Callable[[Array], Array],
        exact: bool,
    ) -> int:
        """The joints' rows: revolute (two each), slider (one) and prismatic (slider and equal
        angles), with each side's drawn anchor-to-joint vector; returns the number of rows."""
        scene = self.scene
        rows = 0
        revolute: list[tuple[int, int, int]] = []
        sliding: list[tuple[int, int, int]] = []  # (slot row, guide, follower)
        prismatic: list[tuple[int, int, int, int]] = []  # and the row of the equal angles
        offsets: list[tuple[Array, Array]] = []
        slot_offsets: list[tuple[Array, Array, Array]] = []
        for joint in joints:
            i, j = (index[link] for link in joint.links)
            point = number(scene.drawn(joint.point))
            d_i = point - number(self.anchor0[joint.links[0]])
            d_j = point - number(self.anchor0[joint.links[1]])
            if joint.type == "revolute":
                revolute.append((rows, i, j))
                offsets.append((d_i, d_j))
                rows += 2
                continue
            assert joint.axis is not None
            sliding.append((rows, i, j))
            slot_offsets.append((d_i, d_j, number(np.array(joint.axis, dtype=float))))
            if joint.type == "prismatic":
                prismatic.append((rows, i, j, rows + 1))
                rows += 1
            rows += 1
        dtype = object if exact else float
        self.rev = np.array(revolute, dtype=int).reshape(-1, 3)
        self.rev_d = np.array(offsets, dtype=dtype).reshape(-1, 2, 2)
        self.sld = np.array(sliding, dtype=int).reshape(-1, 3)
        self.sld_d = np.array(slot_offsets, dtype=dtype).reshape(-1, 3, 2)
        self.prismatic = np.array(prismatic, dtype=int).reshape(-1, 4)
        return rows

    def _jacobian_layout(self) -> None:
        """J's constant entries with a column for every link's (x, y, theta) (``constant``:
        dX/dc = I on both sides of each revolute joint's two rows, +-1 on a prismatic joint's
        and a held angle's rotation column) and the unknowns' columns of it (``unit``); where
        J's pose-dependent entries go (flat indices into a (rows, n) matrix, ``flat``): the
        rotation columns of both sides of each revolute joint's two rows, then each slider's
        follower (x, y, theta) and guide (x, y, theta) columns; the masks pick the unknown
        sides."""
        rev, sld = self.rev.tolist(), self.sld.tolist()
        entries = [e for row, i, j in rev for e in unit_entries("revolute", row, i, j)]
        for row, i, j, _ in self.prismatic.tolist():
            entries += unit_entries("prismatic", row, i, j)
        for row, link in zip(self.angle_rows.tolist(), self.angle_links.tolist(), strict=True):
            entries += held_angle_entries(row, link)
        self.constant = np.zeros((self.rows, 3 * len(self.names)))
        if entries:  # no two in one place: a row's two sides are different links
            rows, links, offsets, values = zip(*entries, strict=True)
            columns = [3 * link + offset for link, offset in zip(links, offsets, strict=True)]
            self.constant[list(rows), columns] = values
        self.unit = self.constant[:, _columns_of(self.unknown_index)]
        n, col = self.n, self.col.tolist()
        flat: list[int] = []
        for side in (1, 2):  # the revolute rows' left links, then their right
            for offset in (0, 1):
                flat += [(r[0] + offset) * n + col[r[side]] + 2 for r in rev if col[r[side]] >= 0]
        for side in (2, 1):  # the sliders' followers, then their guides
            for offset in (0, 1, 2):
                flat += [r[0] * n + col[r[side]] + offset for r in sld if col[r[side]] >= 0]
        self.flat = np.array(flat, dtype=int)
        known = self.col < 0
        self.rev_mask = (~known[self.rev[:, 1]], ~known[self.rev[:, 2]])
        self.sld_mask = (~known[self.sld[:, 2]], ~known[self.sld[:, 1]])

    def _stack(
        self, known: Mapping[str, States], q: Array, qd: Array | None, order: int
    ) -> tuple[Array, ...]:
        """Every link's (M, L) state arrays; the unknowns' rates are qd (order 2) or zero.

        A link in no equation of the group (the frame of a five-bar's dyad) stays at zero: its
        cos and sin are taken with the others' and never read (in 40 digits, not a None)."""
        M = q.shape[0]
        L = len(self.names)
        kind = q.dtype
        c, theta = np.zeros((M, L, 2), dtype=kind), np.zeros((M, L), dtype=kind)
        v = a = np.zeros((1, L, 2), dtype=kind)
        omega = alpha = np.zeros((1, L), dtype=kind)
        if order:
            v, a = np.zeros((M, L, 2), dtype=kind), np.zeros((M, L, 2), dtype=kind)
            omega, alpha = np.zeros((M, L), dtype=kind), np.zeros((M, L), dtype=kind)
        for k, name in zip(self.known_index, self.known, strict=True):
            s = known[name]
            c[:, k], theta[:, k] = s.c, s.theta
            if order:
                v[:, k], omega[:, k], a[:, k], alpha[:, k] = s.v, s.omega, s.a, s.alpha
        u = self.unknown_index
        qs = q.reshape(M, -1, 3)
        c[:, u], theta[:, u] = qs[..., :2], qs[..., 2]
        if order == 2 and qd is not None:
            qds = qd.reshape(M, -1, 3)
            v[:, u], omega[:, u] = qds[..., :2], qds[..., 2]
        return c, theta, v, omega, a, alpha

    def evaluate(
        self,
        known: Mapping[str, States],
        q: Array,
        qd: Array | None = None,
        order: int = 0,
        turns: Array | None = None,
    ) -> tuple[Array, Array, Array]:
        """(Phi, J, b) for M samples: (M, rows), (M, rows, n), (M, rows); ``q`` is (M, n).

        ``order`` 1 or 2 gives the right-hand side of the velocity or acceleration equations
        (order 2 needs the unknowns' rates ``qd``); ``turns`` (M, len(angles)) the held angles.
        Without sliding or prismatic joints, in double: by the matrix products of ``LinearForm``.
        """
        if self._dense(q.shape[0]) and q.dtype != object:
            assert self.linear is not None
            return self.linear.evaluate(known, q, qd, order, turns)
        M = q.shape[0]
        c, theta, v, omega, a, alpha = self._stack(known, q, qd, order)
        links = _Links(c, *_cos_sin(theta), v, omega, a, alpha, order)
        phi = np.zeros((M, self.rows), dtype=q.dtype)
        J = np.empty((M, self.rows, self.n), dtype=q.dtype)
        J[:] = self.unit
        b = np.zeros((M, self.rows), dtype=q.dtype)
        entries = self._revolute_rows(links, phi, b) + self._slider_rows(links, phi, b)
        if self.flat.size:
            J.reshape(M, -1)[:, self.flat] = np.concatenate(entries, axis=1)
        if self.prismatic.size:
            _, g, f, rows = self.prismatic.T
            phi[:, rows] = theta[:, f] - theta[:, g]
            if order:
                rate = omega if order == 1 else alpha
                b[:, rows] = rate[:, g] - rate[:, f]
        if self.angle_rows.size:
            held = theta[:, self.angle_links]
            phi[:, self.angle_rows] = held if turns is None else held - turns
            if order:
                rate = omega if order == 1 else alpha
                b[:, self.angle_rows] = -rate[:, self.angle_links]
        return phi, J, b

    def residual(
        self,
        known: Mapping[str, States],
        samples: int,
        turns: Array | None = None,
        scale: tuple[Array, Array] | None = None,
    ) -> Callable[[Array], tuple[Array, Array]]:
        """q -> (Phi(q), J(q)) for (M, n) q, or (n,) q where ``samples`` is 1, with the known
        links and held ``turns`` fixed (the iterations of Newton-Raphson): the known links'
        part computed once where linear. ``scale`` (per column, per row): the equations in
        scaled coordinates x = q / column, Phi / row and J column / row."""
        if self.linear is not None and self._dense(samples):
            form = self.linear if scale is None else self.linear.scaled(*scale)
            fixed = form.known_terms(known, samples, 0, turns)[0]
            fixed = fixed[0] if samples == 1 else fixed
            return lambda q: form.pose(q, fixed)
        if scale is None:
            return lambda q: self.evaluate(known, q, turns=turns)[:2]
        column, row = scale
        jacobian_scale = column[None, :] / row[:, None]

        def general(x: Array) -> tuple[Array, Array]:
            phi, J, _ = self.evaluate(known, np.atleast_2d(x * column), turns=turns)
            shape = x.shape[:-1]
            return (phi / row).reshape(*shape, -1), (J * jacobian_scale).reshape(
                *shape, *J.shape[1:]
            )

        return general

    def _dense(self, samples: int) -> bool:
        """Whether ``LinearForm``'s dense products are the cheaper evaluation: always at one
        pose, on many samples only for small groups (their matrices are mostly zeros: 96
        unknowns on 1512 samples took 60 ms against 30 ms joint by joint)."""
        return self.linear is not None and (samples == 1 or self.n <= DENSE_UNKNOWNS)

    def rotations(self, samples: int) -> Rotations | None:
        """The square equations in the rotations alone (``Rotations``) where they are the
        cheaper evaluation on ``samples`` samples (``_dense``), else None."""
        if self.linear is None or not self._dense(samples):
            return None
        rotations = self.linear.rotations
        return rotations if rotations is not None and rotations.square else None

    def solve(self, J: Array, b: Array) -> Array:
        """x with J x = b for (M, n, n) J from ``evaluate``: ``LinearForm.solve`` where linear,
        else ``solve_linear``."""
        if self.linear is not None and J.dtype != object:
            return self.linear.solve(J, b)
        return solve_linear(J, b)

    def _revolute_rows(self, links: _Links, phi: Array, b: Array) -> list[Array]:
        """X_i - X_j into Phi and the rate terms into b (in place); J's rotation entries."""
        if not self.rev.size:
            return []
        rows, i, j = self.rev.T
        X_i, r_i, rate_i = links.side(i, self.rev_d[:, 0])
        X_j, r_j, rate_j = links.side(j, self.rev_d[:, 1])
        phi[:, rows], phi[:, rows + 1] = (X_i - X_j).transpose(2, 0, 1)
        if rate_i is not None and rate_j is not None:
            b[:, rows], b[:, rows + 1] = (rate_j - rate_i).transpose(2, 0, 1)
        mi, mj = self.rev_mask
        t_i, t_j = revolute_rotation_entries(r_i, r_j)
        return [t_i[:, mi, 0], t_i[:, mi, 1], t_j[:, mj, 0], t_j[:, mj, 1]]

    def _slider_rows(self, links: _Links, phi: Array, b: Array) -> list[Array]:
        """n_g . (X_f - X_g) into Phi and its rate terms into b (in place); J's entries."""
        if not self.sld.size:
            return []
        rows, g, f = self.sld.T
        w, n = slider_axes(self.sld_d[:, 2], links.cos[:, g], links.sin[:, g])
        X_f, r_f, rate_f = links.side(f, self.sld_d[:, 1])
        X_g, r_g, rate_g = links.side(g, self.sld_d[:, 0])
        d = X_f - X_g
        wd = dot(w, d)
        phi[:, rows] = dot(n, d)
        theta_f, theta_g = slider_rotation_entries(n, r_f, r_g, wd)
        omega, order = links.omega, links.order
        if order == 1 and rate_f is not None and rate_g is not None:
            b[:, rows] = slider_velocity_rhs(n, wd, rate_g - rate_f, omega[:, g])
        elif order == 2 and rate_f is not None and rate_g is not None:
            v_rel = links.velocity(f, r_f) - links.velocity(g, r_g)
            b[:, rows] = slider_acceleration_rhs(
                n, w, wd, rate_g - rate_f, omega[:, g], links.alpha[:, g], v_rel
            )
        mf, mg = self.sld_mask
        return [
            n[:, mf, 0],
            n[:, mf, 1],
            theta_f[:, mf],
            -n[:, mg, 0],
            -n[:, mg, 1],
            theta_g[:, mg],
        ]

    def equations(self, poses: Mapping[str, _Pose], order: int) -> tuple[Array, Array, Array]:
        """(Phi, J, b) at one sample, from single-sample poses (every link, known or not)."""

        def states(p: _Pose) -> States:
            return States(
                p.c[None], np.array([p.theta]), p.v[None], np.array([p.omega]),
                p.a[None], np.array([p.alpha]),
            )  # fmt: skip

        known = {name: states(poses[name]) for name in self.known}
        q = np.concatenate([np.append(poses[k].c, poses[k].theta) for k in self.unknown])
        qd = np.concatenate([np.append(poses[k].v, poses[k].omega) for k in self.unknown])
        phi, J, b = self.evaluate(known, q[None], qd[None], order)
        return phi[0], J[0], b[0]

    def drawn(self) -> Array:
        """q at the drawn pose: every unknown link's anchor where drawn, rotation 0."""
        return np.concatenate([np.append(self.anchor0[link], 0.0) for link in self.unknown])

    def motions(self, q: Array, qd: Array | None, qdd: Array | None) -> dict[str, LinkMotion]:
        """The unknown links' motions from (N, n) coordinates and rates."""
        out = {}
        for index, link in enumerate(self.unknown):
            s = slice(3 * index, 3 * index + 2)
            anchor = PointMotion(
                q[:, s], None if qd is None else qd[:, s], None if qdd is None else qdd[:, s]
            )
            out[link] = LinkMotion(
                self.anchor0[link],
                anchor,
                q[:, 3 * index + 2],
                None if qd is None else qd[:, 3 * index + 2],
                None if qdd is None else qdd[:, 3 * index + 2],
            )
        return out


def unit_entries(kind: str, row: int, i: Link, j: Link) -> list[tuple[int, Link, int, float]]:
    """The constant entries of J (row, link, column in its (x, y, theta), value) of a joint
    between links i and j (a sliding joint's guide i and follower j) whose rows start at
    ``row``: a revolute joint's X_i - X_j = c_i + r_i - c_j - r_j has dPhi/dc = I and -I; a
    prismatic joint's angle row theta_j - theta_i (after its slider row) +1 and -1; a slider's
    row n.(X_j - X_i) none (n turns with the guide: ``slider_rotation_entries``)."""
    if kind == "revolute":
        return [(row, i, 0, 1.0), (row + 1, i, 1, 1.0), (row, j, 0, -1.0), (row + 1, j, 1, -1.0)]
    if kind == "prismatic":
        return [(row + 1, j, 2, 1.0), (row + 1, i, 2, -1.0)]
    return []


def held_angle_entries(row: int, link: Link) -> list[tuple[int, Link, int, float]]:
    """The entry of a held angle's row theta - turn (a driver's): dPhi/dtheta = 1."""
    return [(row, link, 2, 1.0)]


def revolute_rotation_entries(r_i: Array, r_j: Array) -> tuple[Array, Array]:
    """dPhi/dtheta_i = k x r_i and dPhi/dtheta_j = -k x r_j of a revolute joint's two rows
    Phi = X_i - X_j, X = c + r with r = R(theta) (P0 - A0) the arm from the link's anchor
    (dr/dtheta = k x r): the (x row, y row) entries of each side."""
    return perp(r_i), -perp(r_j)


def slider_axes(axis: Array, cos: Array, sin: Array) -> tuple[Array, Array]:
    """(w, n) of a slider: its axis w = R(theta_g) w0 turned with the guide and the normal
    n = k x w of its row n.(X_f - X_g) = 0."""
    w = rotate_by(axis, cos, sin)
    return w, perp(w)


def slider_rotation_entries(n: Array, r_f: Array, r_g: Array, wd: Array) -> tuple[Array, Array]:
    """dPhi/dtheta_f = n.(k x r_f) and dPhi/dtheta_g = -n.(k x r_g) - w.d of a slider's row
    Phi = n.(X_f - X_g), d = X_f - X_g (``wd`` = w.d), r the arms from the follower's and the
    guide's anchors: the normal n = k x w turns with the guide, dn/dtheta_g = -w."""
    return dot(n, perp(r_f)), -dot(n, perp(r_g)) - wd


def slider_velocity_rhs(n: Array, wd: Array, known: Array, omega: Array) -> Array:
    """n.(v_g - v_f)_known + omega_g w.d: the right-hand side of a slider's row
    Phi = n.(X_f - X_g) = 0 differentiated once, n.(v_f - v_g) - omega_g w.d = 0 (the normal
    turns with the guide, dn/dt = -omega_g w), the unknown velocities' terms on the left;
    ``known`` the rest of v_g - v_f, ``wd`` = w.d, d = X_f - X_g. The one definition of the
    row's rates: the whole system's (``ConstraintSystem``) and a point's on a line
    (``loci.point_motion``, where v_f = v_X is the unknown and known = v_Q)."""
    return dot(n, known) + omega * wd


def slider_acceleration_rhs(
    n: Array, w: Array, wd: Array, known: Array, omega: Array, alpha: Array, v_rel: Array
) -> Array:
    """n.(a_g - a_f)_known + 2 omega_g w.(v_f - v_Q) + alpha_g w.d: the slider's row
    differentiated twice, n.(a_f - a_g) - 2 omega_g w.(v_f - v_g) - alpha_g w.d = 0 (on the
    row n.d = 0, so the omega_g^2 n.d term vanishes); ``v_rel`` = v_f - v_Q, the rest as
    ``slider_velocity_rhs``."""
    return dot(n, known) + 2.0 * omega * dot(w, v_rel) + alpha * wd


def constraint_system(
    scene: LinkageScene, unknown: Sequence[str], angles: Sequence[str] = ()
) -> ConstraintSystem:
    """``ConstraintSystem(scene, unknown, angles=angles)`` built once per scene object and kept
    on it (``LinkageScene.memo``, as ``topology.build_plan``): every sweep of one parsed scene,
    its branches and their poses share it (building the triad's two systems was an eighth of a
    360-sample sweep). Nothing changes a system once built (its ``cached_property`` values are
    functions of it alone), so every reuse gives the same results."""
    systems: dict[tuple[tuple[str, ...], tuple[str, ...]], ConstraintSystem]
    systems = scene.memo.setdefault("constraint_systems", {})
    which = (tuple(unknown), tuple(angles))
    system = systems.get(which)
    if system is None:
        system = systems[which] = ConstraintSystem(scene, unknown, angles=angles)
    return system


class LinearForm:
    """Phi(q) = K_q q + K_c cos(theta) + K_s sin(theta) + Phi_known(t): the rows of revolute
    joints (X = c + R(theta) d) and of held angles are linear in each link's (x, y, theta) and
    the cosine and sine of its rotation, with constant K.

    So J = K_q + (K_s cos - K_c sin) in the rotation columns, b_v = -Phi_known' and
    b_a = -Phi_known'' + (K_c cos + K_s sin) omega^2 (the unknowns' centripetal terms): a few
    matrix products per evaluation, for one pose or M samples at once. The same equations as
    ``ConstraintSystem.evaluate`` (a test compares them), which also handles sliding and
    prismatic joints (not linear in these terms) and 40-digit arithmetic.
    """

    def __init__(self, system: ConstraintSystem) -> None:
        links = len(system.names)
        Kq = system.constant
        Kc, Ks = np.zeros((system.rows, links)), np.zeros((system.rows, links))
        for (row, i, j), (d_i, d_j) in zip(system.rev, system.rev_d, strict=True):
            for link, d, sign in ((i, d_i, 1.0), (j, d_j, -1.0)):
                Kc[row : row + 2, link] += sign * d
                Ks[row : row + 2, link] += sign * perp(d)
        self.angle_rows = system.angle_rows
        self.known = system.known
        parts = []
        for index in (system.unknown_index, system.known_index):
            parts.append((Kq[:, _columns_of(index)], Kc[:, index], Ks[:, index]))
        (self.q, self.c, self.s), (self.known_q, self.known_c, self.known_s) = parts
        self._derive()

    def _derive(self) -> None:
        """What the evaluations read from K: the rotation entries of J that vary (a revolute
        row touches two links: their flat indices into (rows, n), the link and the entries of
        K_c, K_s there: K_q has none in those rows, a revolute joint's); the elimination of the
        translations waits for ``solve``."""
        rows, links = np.nonzero((self.c != 0.0) | (self.s != 0.0))
        self.flat = rows * self.q.shape[1] + 3 * links + 2
        self.links = links
        self.entries = self.c[rows, links], self.s[rows, links]
        self.__dict__.pop("rotations", None)  # a scaled copy eliminates with its own K_q

    @cached_property
    def rotations(self) -> Rotations | None:
        """The equations in the rotations alone (``Rotations``), built at their first use (an
        SVD: a third of building the form, which the condition number of one instant never
        solves with); None unless every link's translation is fixed by its rows."""
        eliminated = _translations_eliminated(self.q)
        return None if eliminated is None else Rotations(self, *eliminated)

    def scaled(self, column: Array, row: Array) -> LinearForm:
        """The same equations in scaled coordinates (``ConstraintSystem.residual``): Phi / row
        at x = q / column (rotations unscaled: column is 1 there)."""
        assert np.all(column[2::3] == 1.0)
        out = copy.copy(self)
        out.q = self.q * column[None, :] / row[:, None]
        out.c, out.s = self.c / row[:, None], self.s / row[:, None]
        out.known_q = self.known_q / row[:, None]
        out.known_c, out.known_s = self.known_c / row[:, None], self.known_s / row[:, None]
        out._derive()
        return out

    def pose(self, q: Array, known: Array) -> tuple[Array, Array]:
        """(Phi, J) at q ((n,) or (M, n)), given the known links' part of Phi (``known_terms``)."""
        cos, sin = np.cos(q[..., 2::3]), np.sin(q[..., 2::3])
        phi = self.residual(q, known, cos, sin)
        J = np.empty((*q.shape[:-1], *self.q.shape))
        J[...] = self.q
        rotation = rotation_entries(*self.entries, cos[..., self.links], sin[..., self.links])
        J.reshape(*q.shape[:-1], -1)[..., self.flat] = rotation
        return phi, J

    def residual(
        self, q: Array, known: Array, cos: Array | None = None, sin: Array | None = None
    ) -> Array:
        """Phi = K_q q + K_c cos(theta) + K_s sin(theta) + Phi_known at q ((n,) or (M, n)), given
        the known links' part (``known_terms``) and, if already computed, cos and sin theta."""
        theta = q[..., 2::3]
        cos = np.cos(theta) if cos is None else cos
        sin = np.sin(theta) if sin is None else sin
        return np.asarray(q @ self.q.T + cos @ self.c.T + sin @ self.s.T + known)

    def bending(self, q: Array, tangent: Array) -> Array:
        """(K_c cos + K_s sin) theta'^2 along a path q(s) with q' = ``tangent`` ((n,) or
        (M, n)): the right-hand side of J q'' = -d^2 Phi/ds^2 + J q'' (differentiating J q' = 0
        once more; ``turning_terms``)."""
        return turning_terms(q[..., 2::3], tangent[..., 2::3], self.c, self.s)

    def solve(self, J: Array, b: Array) -> Array:
        """x with J x = b for (M, n, n) J from ``pose``, the translations eliminated: with
        J = [A | J_theta] (A the constant translation columns) and Q^T A = 0,
        Q^T J_theta x_theta = Q^T b (one rotation per link: an (M, U, U) system) and then
        x_c = A^+ (b - J_theta x_theta). Without that structure, or singular: ``solve_linear``."""
        rotations = self.rotations
        if rotations is None or not rotations.square:
            return solve_linear(J, b)
        J_theta = J[..., 2::3]
        Q = rotations.Q
        try:
            x_theta = np.linalg.solve(Q.T @ J_theta, (b @ Q)[..., None])[..., 0]
        except np.linalg.LinAlgError:
            return solve_linear(J, b)
        rest = b - np.einsum("mij,mj->mi", J_theta, x_theta)
        return rotations.assemble(x_theta, rest @ rotations.pseudo_inverse.T)

    def known_terms(
        self, known: Mapping[str, States], samples: int, order: int, turns: Array | None
    ) -> tuple[Array, Array]:
        """The known links' part of Phi (minus the held angles' ``turns``) and of b at ``order``
        (-Phi_known' or -Phi_known''), each (M, rows)."""
        phi = np.zeros((samples, self.q.shape[0]))
        b = np.zeros_like(phi)
        if self.known:
            s = [known[name] for name in self.known]
            theta = _columns([x.theta for x in s], samples)
            cos, sin = np.cos(theta), np.sin(theta)
            q = _columns([c for x in s for c in (x.c[..., 0], x.c[..., 1], x.theta)], samples)
            phi += q @ self.known_q.T + cos @ self.known_c.T + sin @ self.known_s.T
            if order:
                omega = _columns([x.omega for x in s], samples)
                dot_q = [(x.v, x.omega) if order == 1 else (x.a, x.alpha) for x in s]
                rates = _columns([c for v, w in dot_q for c in (v[..., 0], v[..., 1], w)], samples)
                w = rates[:, 2::3]  # omega (order 1) or alpha (order 2)
                squared = omega**2 if order == 2 else np.zeros_like(omega)
                b -= rates @ self.known_q.T
                b -= (w * cos - squared * sin) @ self.known_s.T
                b += (w * sin + squared * cos) @ self.known_c.T
        if turns is not None and self.angle_rows.size:
            phi[:, self.angle_rows] -= turns
        return phi, b

    def evaluate(
        self,
        known: Mapping[str, States],
        q: Array,
        qd: Array | None,
        order: int,
        turns: Array | None,
    ) -> tuple[Array, Array, Array]:
        """(Phi, J, b) for M samples, as ``ConstraintSystem.evaluate``."""
        phi_known, b = self.known_terms(known, q.shape[0], order, turns)
        phi, J = self.pose(q, phi_known)
        return phi, J, b + self.centripetal(q, qd) if order == 2 else b

    def centripetal(self, q: Array, qd: Array | None) -> Array:
        """The unknowns' part of b_a: (K_c cos + K_s sin) omega^2, (M, rows) (``bending`` in
        time)."""
        if qd is None:
            return np.zeros((q.shape[0], self.q.shape[0]))
        return self.bending(q, qd)


def rotation_entries(c: Array, s: Array, cos: Array, sin: Array) -> Array:
    """S cos theta - C sin theta: dPhi/dtheta of rows C cos theta + S sin theta + ... (a revolute
    joint's, X = c + R(theta) d = c + d cos theta + (k x d) sin theta: ``LinearForm``, and Q^T
    of them in ``Rotations``), entry by entry (broadcast)."""
    return np.asarray(s * cos - c * sin)


def turning_terms(theta: Array, rate: Array, c: Array, s: Array) -> Array:
    """(C cos theta + S sin theta) theta'^2, per row: with rows C cos theta + S sin theta + ...
    (``LinearForm``, and Q^T of them in ``Rotations``) whose Jacobian in theta is
    J_theta = S diag(cos) - C diag(sin) (``rotation_entries``), -(d/dt J_theta) theta' is this
    (theta and its rate ``rate`` (U,) or (M, U)): the acceleration's and a path's curvature's
    right-hand side."""
    turning = rate**2
    return np.asarray((np.cos(theta) * turning) @ c.T + (np.sin(theta) * turning) @ s.T)


def _translations_eliminated(Kq: Array) -> tuple[Array, Array] | None:
    """(Q, A^+) for ``Rotations``: A the translation columns of J (constant: K_q's x and y
    columns), Q an orthonormal basis of the rows' space orthogonal to A's columns; None unless
    A has full column rank (every link's translation fixed by its rows)."""
    rows = Kq.shape[0]
    A = Kq.reshape(rows, -1, 3)[..., :2].reshape(rows, -1)
    if A.shape[1] == 0 or A.shape[1] > rows:
        return None
    U, singular, Vt = np.linalg.svd(A)
    if singular[-1] <= 1e-9 * singular[0]:
        return None
    columns = A.shape[1]
    return U[:, columns:], (Vt.T / singular) @ U[:, :columns].T  # A^+ = V S^-1 U_1^T


class Rotations:
    """The loop equations in the unknown links' rotations theta alone. With
    Phi = A c + r(theta) + k (A the constant translation columns, r(theta) = K_theta theta +
    K_c cos theta + K_s sin theta, k the known links' part) and Q^T A = 0 (Q orthonormal):

        G(theta) = Q^T (r(theta) + k) = 0,   c = -A^+ (r(theta) + k),

    dG/dtheta = Q^T K_theta + Q^T K_s diag(cos) - Q^T K_c diag(sin) = Q^T J_theta. Where G = 0
    these c close every row exactly; elsewhere |Phi(c, theta)| = |G(theta)| (the least-squares
    translations). Newton-Raphson in theta takes the same steps as on the whole system (its
    rotation part does not depend on c), on (U, U) instead of (3U, 3U) systems.
    """

    def __init__(self, form: LinearForm, Q: Array, pseudo_inverse: Array) -> None:
        self.Q, self.pseudo_inverse = Q, pseudo_inverse
        self.k_theta, self.k_c, self.k_s = form.q[:, 2::3], form.c, form.s
        self.t, self.c, self.s = Q.T @ self.k_theta, Q.T @ form.c, Q.T @ form.s
        self.complex = self.c - 1j * self.s
        self.held = bool(np.any(self.t))  # rows holding an unknown's angle (a driver's)
        self.square = self.t.shape[0] == self.t.shape[1]

    def fixed(self, known: Array) -> Array:
        """Q^T k: the known links' part of G, from theirs of Phi (``LinearForm.known_terms``)."""
        return np.asarray(known @ self.Q)

    def pose(self, theta: Array, fixed: Array) -> tuple[Array, Array]:
        """(G, dG/dtheta) at theta ((U,) or (M, U)), given ``fixed`` = Q^T k: with
        P = (C - i S) exp(i theta) (per column), G = sum of Re P + fixed and dG/dtheta = -Im P
        (the fewest numpy calls: this is the path following's evaluation, one pose at a time)."""
        P = self.complex * np.exp(1j * theta)[..., None, :]
        G = P.real.sum(axis=-1) + fixed
        J = -P.imag
        if self.held:
            G += theta @ self.t.T
            J += self.t
        return G, J

    def jacobian(self, theta: Array, cos: Array | None = None, sin: Array | None = None) -> Array:
        """dG/dtheta at (M, U) theta (its cosines and sines, if already computed)."""
        cos = np.cos(theta) if cos is None else cos
        sin = np.sin(theta) if sin is None else sin
        J = rotation_entries(self.c, self.s, cos[..., None, :], sin[..., None, :])
        return J + self.t if self.held else J

    def bending(self, theta: Array, tangent: Array) -> Array:
        """(C cos + S sin) theta'^2 along a path theta(s) with theta' = ``tangent`` ((U,) or
        (M, U)): the right-hand side of dG/dtheta theta'' = ... (differentiating
        dG/dtheta theta' = 0; ``turning_terms``)."""
        return turning_terms(theta, tangent, self.c, self.s)

    def translations(self, theta: Array, known: Array) -> Array:
        """c = -A^+ (r(theta) + k) at (M, U) theta, k (M, rows) or (rows,): (M, 2U)."""
        r = np.cos(theta) @ self.k_c.T + np.sin(theta) @ self.k_s.T + known
        if self.held:
            r += theta @ self.k_theta.T
        return np.asarray(-(r @ self.pseudo_inverse.T))

    def rates(
        self,
        theta: Array,
        jacobian: Array,
        b: Array,
        solve: Callable[[Array, Array], Array] | None = None,
    ) -> Array:
        """x with J x = b (J the whole system's at (M, U) theta, b (M, rows)): dG/dtheta
        x_theta = Q^T b with ``jacobian`` = dG/dtheta (LU, or ``solve``), then
        x_c = A^+ (b - J_theta x_theta), J_theta x_theta = K_theta x_theta +
        K_s (cos x_theta) - K_c (sin x_theta)."""
        if solve is None:
            x_theta = np.linalg.solve(jacobian, (b @ self.Q)[..., None])[..., 0]
        else:
            x_theta = solve(jacobian, b @ self.Q)
        turned = (np.cos(theta) * x_theta) @ self.k_s.T - (np.sin(theta) * x_theta) @ self.k_c.T
        if self.held:
            turned += x_theta @ self.k_theta.T
        return self.assemble(x_theta, (b - turned) @ self.pseudo_inverse.T)

    @staticmethod
    def assemble(theta: Array, c: Array) -> Array:
        """(M, 3U) coordinates (x, y, theta per link) from (M, U) rotations and (M, 2U) c."""
        M, links = theta.shape
        x = np.empty((M, links, 3))
        x[..., 2], x[..., :2] = theta, c.reshape(M, links, 2)
        return x.reshape(M, -1)


def _columns_of(links: Array) -> Array:
    """The (x, y, theta) columns of the links at ``links`` (indices): 3 k, 3 k + 1, 3 k + 2."""
    return (3 * links[:, None] + np.arange(3)).ravel()


def _columns(arrays: Sequence[Array], samples: int) -> Array:
    """(M, K) from K per-sample arrays (each (M,) or broadcast to it)."""
    out = np.empty((samples, len(arrays)))
    for k, a in enumerate(arrays):
        out[:, k] = a
    return out


def solve_linear(J: Array, b: Array) -> Array:
    """x with J x = b for stacked systems (M, n, n) x (M, n): LU where square and regular, least
    squares (pseudo-inverse) for a singular or non-square sample."""
    if J.shape[-1] == J.shape[-2]:
        try:
            return np.linalg.solve(J, b[..., None])[..., 0]
        except np.linalg.LinAlgError:
            pass
    return np.einsum("mij,mj->mi", np.linalg.pinv(J), b)


def rates(
    system: ConstraintSystem, known: Mapping[str, States], q: Array, order: int
) -> tuple[Array | None, Array | None]:
    """qdot from J qdot = b_v and qddot from J qddot = b_a at every sample (stacked solves; J
    evaluated once where the equations are linear in (q, cos, sin): b_a needs no J there)."""
    rotations = system.rotations(q.shape[0])
    if rotations is not None and system.linear is not None and order:
        try:
            return _rotation_rates(system.linear, rotations, known, q, order)
        except np.linalg.LinAlgError:  # a singular sample: least squares below
            pass
    qd = qdd = None
    if order >= 1:
        _, J, b = system.evaluate(known, q, order=1)
        qd = system.solve(J, b)
    if order >= 2:
        if system.linear is not None and system._dense(q.shape[0]):
            b = system.linear.known_terms(known, q.shape[0], 2, None)[1]
            b += system.linear.centripetal(q, qd)
        else:
            _, J, b = system.evaluate(known, q, qd, order=2)
        qdd = system.solve(J, b)
    return qd, qdd


def _rotation_rates(
    form: LinearForm, rotations: Rotations, known: Mapping[str, States], q: Array, order: int
) -> tuple[Array | None, Array | None]:
    """``rates`` by ``Rotations.rates``: dG/dtheta evaluated once for both solves, b_v =
    -Phi_known' and b_a = -Phi_known'' + (K_c cos + K_s sin) omega^2."""
    theta = q[:, 2::3]
    J = rotations.jacobian(theta)
    qd = rotations.rates(theta, J, form.known_terms(known, q.shape[0], 1, None)[1])
    if order < 2:
        return qd, None
    b = form.known_terms(known, q.shape[0], 2, None)[1] + form.centripetal(q, qd)
    return qd, rotations.rates(theta, J, b)


def states(links: Mapping[str, LinkMotion], scene: LinkageScene) -> dict[str, States]:
    """Known links as ``States`` over their samples, each anchor moved to the link's first point
    (the anchor of the constraint equations); rates not computed are zero."""
    out = {}
    for name, motion in links.items():
        first = motion.point(scene.drawn(scene.links[name].points[0]))
        zeros2 = np.zeros_like(first.p)
        zeros = np.zeros(first.p.shape[0])
        out[name] = States(
            first.p,
            np.broadcast_to(motion.theta, zeros.shape),
            zeros2 if first.v is None else first.v,
            zeros if motion.omega is None else np.broadcast_to(motion.omega, zeros.shape),
            zeros2 if first.a is None else first.a,
            zeros if motion.alpha is None else np.broadcast_to(motion.alpha, zeros.shape),
        )
    return out


class KnownPoses:
    """The known links' poses and rates sample by sample (single-sample ``_Pose`` values)."""

    def __init__(self, links: Mapping[str, LinkMotion], scene: LinkageScene) -> None:
        self.states = states(links, scene)

    def at(self, k: int) -> dict[str, _Pose]:
        return {
            name: _Pose(
                s.c[k], float(s.theta[k]), s.v[k], float(s.omega[k]), s.a[k], float(s.alpha[k])
            )
            for name, s in self.states.items()
        }


def velocity_jacobian(
    scene: LinkageScene, links: Mapping[str, LinkMotion], k: int
) -> tuple[Array, Array]:
    """J = dPhi/dq of the whole velocity system at sample ``k``, and which of its rows are
    lengths (not angles): ``ConstraintSystem(scene, scene.moving_links, drivers=True)``'s rows
    (each joint in order, then theta_d of each driver; every moving link's (x, y, theta)
    columns in ``scene.moving_links`` order) from the same row functions (``unit_entries``,
    ``revolute_rotation_entries``, ``slider_axes``, ``slider_rotation_entries``,
    ``held_angle_entries``), placed at one pose without the system's layout (building that
    costs more than the whole of this)."""
    column = {name: 3 * m for m, name in enumerate(scene.moving_links)}
    index = {name: m for m, name in enumerate(scene.links)}
    theta = np.array([links[name].theta[k] for name in scene.links], dtype=float)
    cos, sin = np.cos(theta), np.sin(theta)
    ends = [(link, joint.point) for joint in scene.joints for link in joint.links]
    drawn = np.array([scene.drawn(point) for _, point in ends])
    anchors = np.array([scene.drawn(scene.links[link].points[0]) for link, _ in ends])
    which = [index[link] for link, _ in ends]
    arms = rotate_by(drawn - anchors, cos[which], sin[which])  # r_i, r_j of each joint in turn
    rows = sum(JOINT_ROWS[joint.type] for joint in scene.joints) + len(scene.drivers)
    J, lengths = np.zeros((rows, 3 * len(column))), np.ones(rows, dtype=bool)

    def put(entries: Sequence[tuple[int, str, int, Array | float]]) -> None:
        for row, link, offset, value in entries:
            if link in column:
                J[row, column[link] + offset] = value

    turned = (t.tolist() for t in revolute_rotation_entries(arms[::2], arms[1::2]))
    row = 0
    for joint, r_i, r_j, t_i, t_j in zip(scene.joints, arms[::2], arms[1::2], *turned, strict=True):
        i, j = joint.links
        put(unit_entries(joint.type, row, i, j))
        if joint.type == "revolute":
            put(((row, i, 2, t_i[0]), (row + 1, i, 2, t_i[1])))
            put(((row, j, 2, t_j[0]), (row + 1, j, 2, t_j[1])))
        else:
            assert joint.axis is not None
            w, n = slider_axes(np.array(joint.axis), cos[index[i]], sin[index[i]])
            c_i, c_j = (_anchor(scene, links[x], x)[k] for x in (i, j))
            wd = dot(w, (c_j + r_j) - (c_i + r_i))
            f, g = slider_rotation_entries(n, r_j, r_i, wd)
            put([(row, j, 0, n[0]), (row, j, 1, n[1]), (row, j, 2, f)])
            put([(row, i, 0, -n[0]), (row, i, 1, -n[1]), (row, i, 2, g)])
            lengths[row + 1 : row + JOINT_ROWS[joint.type]] = False
        row += JOINT_ROWS[joint.type]
    for driver in scene.drivers:
        put(held_angle_entries(row, driver.link))
        lengths[row] = False
        row += 1
    return J, lengths


def _anchor(scene: LinkageScene, motion: LinkMotion, link: str) -> Array:
    """The positions of the link's first point (the anchor of the constraint equations)."""
    positions = LinkMotion(motion.anchor0, PointMotion(motion.anchor.p), motion.theta)
    return positions.point(scene.drawn(scene.links[link].points[0])).p


def velocity_condition_number(
    scene: LinkageScene, links: Mapping[str, LinkMotion], k: int
) -> float:
    """cond(J) = sigma_max / sigma_min of the whole velocity system (drivers included,
    ``velocity_jacobian``), angle columns scaled by the size.

    Scaling the rotation columns and the angle rows by the scene size makes J dimensionless, so
    the number does not change when every length is multiplied by k.
    """
    J, length_rows = velocity_jacobian(scene, links, k)
    size = scene.size
    J[:, 2::3] /= size
    J[~length_rows] *= size
    if J.shape[0] != J.shape[1]:
        return float("inf")
    singular_values = np.linalg.svd(J, compute_uv=False)
    if singular_values[-1] == 0.0:
        return float("inf")
    return float(singular_values[0] / singular_values[-1])

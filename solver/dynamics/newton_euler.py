"""Inverse dynamics by Newton-Euler: one sparse linear system per instant, over all samples.

For every moving link k, with R_k its anchor point (any point will do, moving or not):

    sum F = sum_i m_i a_i                                     (two force equations)
    sum (r - R_k) x F + sum M = sum_i [I_i alpha + (r_i - R_k) x m_i a_i]    (moment about R_k)

where i runs over the link's masses (the body and its point masses). The unknowns are the joint
reactions (revolute: Fx, Fy; slider: the force normal to the slot, frictionless; prismatic: that
force and a moment) and every driver's torque: 3 per moving link, as many as the equations
(Gruebler). Each joint's force is the one its first link exerts on its second; the second link
gets +F, the first -F. The matrix is sparse (a force enters only the equations of the two links it
joins) and has the same pattern at every sample: it is kept as (row, column, values per sample)
entries, and the samples' blocks are solved together, as one dense batch by LAPACK for small
linkages or as one block-diagonal sparse matrix by SuperLU for large ones.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass

import numpy as np
import scipy.sparse
import scipy.sparse.linalg

from solver.dynamics.loads import (
    AppliedForce,
    AppliedMoment,
    MassElement,
    applied_loads,
    dynamics_of,
    mass_elements,
    static_elements,
)
from solver.errors import SingularConfiguration
from solver.kinematics.rigid import Array, cross, perp, rotate
from solver.model.scene import Joint, LinkageScene
from solver.position.assembly import Motion

# Up to this many matrix entries over all samples (16 MB) the blocks are solved as one dense
# batch (LAPACK), beyond as one sparse block-diagonal matrix (SuperLU).
DENSE_LIMIT = 2_000_000


def neighbour_mean(values: Array, singular: Array, cyclic: bool) -> None:
    """values[k] = (values[k - 1] + values[k + 1]) / 2 at the ``singular`` samples, in place
    (``cyclic``: over a whole revolution, else the ends repeat themselves)."""
    n = values.shape[0]
    for k in singular:
        before, after = ((k - 1) % n, (k + 1) % n) if cyclic else (max(k - 1, 0), min(k + 1, n - 1))
        values[k] = 0.5 * (values[before] + values[after])


@dataclass(frozen=True)
class System:
    """The Newton-Euler system A u = b of every sample: ``entries`` (row, column, values (N,))
    of A, ``rhs`` b (N, m), and the names of the unknowns and of the equations. ``origins`` says
    what each unknown is: ("joint", index in the scene's joints, 0 | 1 for x | y of a revolute
    joint's force, 0 for a slot's normal force, 2 for a prismatic joint's moment) or ("driver",
    index, 0)."""

    unknowns: tuple[str, ...]
    origins: tuple[tuple[str, int, int], ...]
    equations: tuple[str, ...]
    entries: tuple[tuple[int, int, Array], ...]
    rhs: Array
    reference: dict[str, Array]  # link -> the point R_k its moments are taken about (N, 2)

    def matrix(self, k: int) -> Array:
        """A at sample ``k`` (dense)."""
        m = len(self.unknowns)
        A = np.zeros((m, m))
        for row, column, values in self.entries:
            A[row, column] += values[k]
        return A

    def solve(self, singular: Array, cyclic: bool = True) -> Array:
        """u (N, m); ``singular`` samples (change points inside a sweep, where the equations are
        singular and the motion smooth) take the mean of their neighbours (``cyclic``: over a
        whole revolution)."""
        n, m = self.rhs.shape
        rhs = self.rhs.copy()
        rhs[singular] = 0.0  # an identity block there, replaced below
        try:
            if n * m * m <= DENSE_LIMIT:
                u = self._solve_dense(rhs, singular)
            else:
                u = self._solve_sparse(rhs, singular)
        except (RuntimeError, np.linalg.LinAlgError):
            raise SingularConfiguration(
                "the Newton-Euler equations are singular: at a dead centre the driver cannot "
                "move the linkage, so its torque and the joint forces are not determined",
                float("inf"),
            ) from None
        neighbour_mean(u, singular, cyclic)
        return u

    def _solve_dense(self, rhs: Array, singular: Array) -> Array:
        """Every sample's block at once by LAPACK's LU (small systems)."""
        n, m = rhs.shape
        entries = np.zeros((m, m, n))  # samples last: each entry one contiguous write
        for row, column, values in self.entries:
            entries[row, column] += values
        A = entries.transpose(2, 0, 1)  # a view: LAPACK's gufunc copies each block anyway
        A[singular] = np.eye(m)
        return np.linalg.solve(A, rhs[..., None])[..., 0]

    def _solve_sparse(self, rhs: Array, singular: Array) -> Array:
        """The blocks as one block-diagonal sparse matrix, one SuperLU factorisation (natural
        ordering: the fill stays inside each block)."""
        n, m = rhs.shape
        rows = np.array([e[0] for e in self.entries])
        columns = np.array([e[1] for e in self.entries])
        values = np.stack([e[2] for e in self.entries], axis=1)  # (N, entries)
        values[singular] = 0.0
        offsets = (np.arange(n) * m)[:, None]
        diagonal = (singular[:, None] * m + np.arange(m)).ravel()
        A = scipy.sparse.csc_matrix(
            (
                np.concatenate([values.ravel(), np.ones(diagonal.size)]),
                (
                    np.concatenate([(offsets + rows).ravel(), diagonal]),
                    np.concatenate([(offsets + columns).ravel(), diagonal]),
                ),
            ),
            shape=(n * m, n * m),
        )
        lu = scipy.sparse.linalg.splu(A, permc_spec="NATURAL")
        return lu.solve(rhs.ravel()).reshape(n, m)


@dataclass(frozen=True)
class JointForce:
    """The force the joint's first link exerts on its second (N, 2); prismatic: and a moment."""

    joint: Joint
    force: Array
    moment: Array | None


@dataclass(frozen=True)
class ForceAnalysis:
    """Joint forces, driver torques (on their links), and what the mechanism does to its frame."""

    joints: list[JointForce]
    torques: dict[str, Array]
    frame_force: Array
    frame_moment: Array
    elements: list[MassElement]
    forces: list[AppliedForce]
    moments: list[AppliedMoment]
    system: System
    solution: Array  # u (N, m): the unknowns in the order of ``system.unknowns``


def slot_normal(joint: Joint, motion: Motion) -> Array:
    """The unit normal k x u of a slider's slot direction u, turned with its guide (N, 2)."""
    assert joint.axis is not None
    return perp(rotate(np.array(joint.axis), motion.links[joint.guide].theta))


class _Columns:
    """The columns of A being assembled: one per unknown, with its name and origin, and the
    (row, column, values) entries it adds to the equations of the links it acts on."""

    def __init__(self, scene: LinkageScene, motion: Motion) -> None:
        self.ground = scene.ground
        self.row = {name: 3 * i for i, name in enumerate(scene.moving_links)}
        self.reference = {name: motion.links[name].anchor.p for name in scene.moving_links}
        n = motion.margin.size
        self.constant = {sign: np.broadcast_to(sign, n) for sign in (1.0, -1.0)}  # no copies
        self.arms: dict[tuple[str, str], Array] = {}  # (link, point): point - R_link
        self.unknowns: list[str] = []
        self.origins: list[tuple[str, int, int]] = []
        self.entries: list[tuple[int, int, Array]] = []

    def new(self, name: str, origin: tuple[str, int, int]) -> int:
        """A new unknown (column); returns its index."""
        self.unknowns.append(name)
        self.origins.append(origin)
        return len(self.unknowns) - 1

    def force(self, column: int, link: str, sign: float, point: Array, d: Array) -> None:
        """sign F along d at ``point``: (d_x, d_y, ((point - R_link) x d)_z) in link's rows."""
        if link == self.ground:
            return
        r = self.row[link]
        self.entries.append((r, column, sign * d[:, 0]))
        self.entries.append((r + 1, column, sign * d[:, 1]))
        self.entries.append((r + 2, column, sign * cross(point - self.reference[link], d)))

    def component(
        self, column: int, link: str, sign: float, name: str, point: Array, axis: int
    ) -> None:
        """A force along x (axis 0) or y (1) at point ``name``: ``force`` with d = e_x or e_y,
        (r x e_x)_z = -r_y, (r x e_y)_z = r_x."""
        if link == self.ground:
            return
        r = self.row[link]
        if (link, name) not in self.arms:
            self.arms[link, name] = point - self.reference[link]
        arm = self.arms[link, name]
        self.entries.append((r + axis, column, self.constant[sign]))
        self.entries.append((r + 2, column, (sign if axis else -sign) * arm[:, 1 - axis]))

    def moment(self, column: int, link: str, sign: float) -> None:
        """sign M in link's moment equation."""
        if link != self.ground:
            self.entries.append((self.row[link] + 2, column, self.constant[sign]))


def _joint_columns(columns: _Columns, scene: LinkageScene, motion: Motion) -> None:
    """Each joint's force (+F on its second link, -F on its first): Fx, Fy of a revolute joint,
    the normal force N of a slot and the moment M of a prismatic joint; each driver's torque."""
    for index, joint in enumerate(scene.joints):
        P = motion.points[joint.point].p
        first, second = joint.links
        if joint.type == "revolute":
            for axis in (0, 1):
                column = columns.new(f"F{'xy'[axis]}_{joint.point}", ("joint", index, axis))
                columns.component(column, second, 1.0, joint.point, P, axis)
                columns.component(column, first, -1.0, joint.point, P, axis)
            continue
        normal = slot_normal(joint, motion)
        column = columns.new(f"N_{joint.point}", ("joint", index, 0))
        columns.force(column, second, 1.0, P, normal)
        columns.force(column, first, -1.0, P, normal)
        if joint.type == "prismatic":
            column = columns.new(f"M_{joint.point}", ("joint", index, 2))
            columns.moment(column, second, 1.0)
            columns.moment(column, first, -1.0)
    for index, driver in enumerate(scene.drivers):
        columns.moment(columns.new(f"M_{driver.link}", ("driver", index, 0)), driver.link, 1.0)


def _right_hand_side(
    scene: LinkageScene,
    columns: _Columns,
    elements: list[MassElement],
    forces: list[AppliedForce],
    moments: list[AppliedMoment],
    n: int,
) -> Array:
    """b per link: (m a - m g, I alpha + (r - R) x (m a - m g)) of its masses, minus its applied
    forces (F, (r - R) x F) and moments."""
    row, reference = columns.row, columns.reference
    gravity = np.array(dynamics_of(scene).gravity)
    rhs = np.zeros((n, 3 * len(scene.moving_links)))
    for e in elements:
        r = row[e.link]
        inertial = e.mass * (e.a - gravity)  # m a - m g
        rhs[:, r : r + 2] += inertial
        rhs[:, r + 2] += e.inertia * e.alpha + cross(e.p - reference[e.link], inertial)
    for f in forces:
        r = row[f.link]
        rhs[:, r : r + 2] -= f.force
        rhs[:, r + 2] -= cross(f.position - reference[f.link], f.force)
    for m in moments:
        rhs[:, row[m.link] + 2] -= m.moment
    return rhs


def newton_euler_system(
    scene: LinkageScene,
    motion: Motion,
    elements: list[MassElement],
    forces: list[AppliedForce],
    moments: list[AppliedMoment],
) -> System:
    """Build A u = b (see the module docstring) at every sample."""
    columns = _Columns(scene, motion)
    _joint_columns(columns, scene, motion)
    rhs = _right_hand_side(scene, columns, elements, forces, moments, motion.margin.size)
    links = scene.moving_links
    equations = tuple(f"{kind}({name})" for name in links for kind in ("Fx", "Fy", "Mz"))
    return System(
        tuple(columns.unknowns),
        tuple(columns.origins),
        equations,
        tuple(columns.entries),
        rhs,
        columns.reference,
    )


def inverse_dynamics(
    scene: LinkageScene,
    motion: Motion,
    times: Array,
    singular: Array | None = None,
    cyclic: bool = True,
    statics: bool = False,
) -> ForceAnalysis:
    """Joint forces, driver torques and the frame's load at every sample of ``motion``
    (accelerations required); ``times`` are the samples' t for the load expressions.
    ``statics``: the masses count only through their weight (``static_elements``)."""
    elements = mass_elements(scene, motion)
    if statics:
        elements = static_elements(elements)
    forces, moments = applied_loads(scene, motion, times)
    system = newton_euler_system(scene, motion, elements, forces, moments)
    u = system.solve(np.array([], dtype=int) if singular is None else np.asarray(singular), cyclic)
    return force_analysis(scene, motion, system, u, elements, forces, moments)


def force_analysis(
    scene: LinkageScene,
    motion: Motion,
    system: System,
    u: Array,
    elements: list[MassElement],
    forces: list[AppliedForce],
    moments: list[AppliedMoment],
    friction_forces: Mapping[int, Array] | None = None,
    friction_moments: Mapping[int, Array] | None = None,
) -> ForceAnalysis:
    """The joint forces, torques and frame load from the solved unknowns ``u``; a joint's
    friction (by its index: a slot's force, a pin's moment, on its second link) is added to its
    force and to the frame's load."""
    n = u.shape[0]
    friction_forces = friction_forces or {}
    friction_moments = friction_moments or {}
    joints, torques = [], {}
    frame_force, frame_moment = np.zeros((n, 2)), np.zeros(n)
    column = 0
    for index, joint in enumerate(scene.joints):
        P = motion.points[joint.point].p
        moment = None
        if joint.type == "revolute":
            force = u[:, column : column + 2].copy()
            column += 2
        else:
            force = u[:, column, None] * slot_normal(joint, motion)
            column += 1
            if joint.type == "prismatic":
                moment = u[:, column].copy()
                column += 1
        if index in friction_forces:
            force = force + friction_forces[index]
        joints.append(JointForce(joint, force, moment))
        if scene.ground in joint.links:  # the force on the ground: -F if it is the first link
            sign = -1.0 if joint.links[0] == scene.ground else 1.0
            frame_force += sign * force
            frame_moment += sign * cross(P, force)
            if moment is not None:
                frame_moment += sign * moment
            if index in friction_moments:
                frame_moment += sign * friction_moments[index]
    for driver in scene.drivers:
        torques[driver.link] = u[:, column].copy()
        frame_moment -= torques[driver.link]
        column += 1
    return ForceAnalysis(
        joints, torques, frame_force, frame_moment, elements, forces, moments, system, u
    )

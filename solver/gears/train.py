"""A gear train's speeds and torques: every mesh's Willis relation, every shaft and every input
in one linear system, solved exactly.

Seen from the body that holds both its axes (its carrier, the "arm", or the frame), a mesh is an
ordinary pair of gears: ``willis_relation``. With the shafts (members keyed together turn as
one) the relations are a homogeneous system A omega = 0 over all members (gears and carriers);
its rank r leaves f = n - r degrees of freedom, which the inputs must fix: exactly f of them, and
independent ones. The speeds are then omega = T u, with T = N (E N)^-1 for a basis N of A's null
space and E the rows that pick the inputs out, computed in exact rational arithmetic
(``solver.gears.exact``): T holds the train values, the exact ratios of tooth numbers.

Torques (ideal gears, no inertia): for every motion the train allows (every omega in A's null
space) the torques the world applies do no work in sum, sum_i T_i omega_i = 0 (the virtual
power). For a coaxial train the rotation of everything as one body is such a motion, which
gives the torque balance sum_i T_i = 0; the train's own motion gives the power balance. Applied
body by body with the mesh forces as unknowns (``member_torques``).
"""

from __future__ import annotations

import functools
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from fractions import Fraction

from solver.errors import InvalidScene
from solver.gears import exact
from solver.gears.scene import GearTrainScene, Mesh


def willis_relation(teeth_a: int, teeth_b: int, internal: bool) -> Fraction:
    """(omega_b - omega_arm) / (omega_a - omega_arm) = -N_a / N_b for an external mesh and
    +N_a / N_b for an internal one: in the frame of the arm (the carrier) that holds both axes
    the two gears turn as an ordinary pair, the pitch circles rolling on each other (Willis)."""
    ratio = Fraction(teeth_a, teeth_b)
    return ratio if internal else -ratio


def mesh_relation(scene: GearTrainScene, mesh: Mesh) -> list[Fraction]:
    """The mesh's Willis relation as a row of A over ``scene.members``:
    (omega_b - omega_arm) - e (omega_a - omega_arm) = 0, e = ``willis_relation``."""
    members = scene.members
    a, b = (scene.gear(name) for name in mesh.gears)
    e = willis_relation(a.teeth, b.teeth, mesh.internal)
    row = [Fraction(0)] * len(members)
    row[members.index(b.name)] = Fraction(1)
    row[members.index(a.name)] = -e
    if mesh.carrier is not None:
        row[members.index(mesh.carrier)] = e - 1
    return row


def shaft_relations(scene: GearTrainScene) -> list[list[Fraction]]:
    """omega_first - omega_other = 0 for every other member of every shaft."""
    members = scene.members
    rows = []
    for shaft in scene.shafts:
        for name in shaft[1:]:
            row = [Fraction(0)] * len(members)
            row[members.index(shaft[0])] = Fraction(1)
            row[members.index(name)] = Fraction(-1)
            rows.append(row)
    return rows


def relations(scene: GearTrainScene) -> list[list[Fraction]]:
    """A: every mesh's Willis relation, then every shaft's."""
    return [mesh_relation(scene, m) for m in scene.meshes] + shaft_relations(scene)


def degrees_of_freedom(scene: GearTrainScene) -> int:
    """f = n - rank A: members less independent relations."""
    members = len(scene.members)
    return members - exact.rank(relations(scene), members)


@dataclass(frozen=True)
class Transfer:
    """omega = T u: ``values[i][k]`` the exact d omega_i / d u_k for member i and input k."""

    members: tuple[str, ...]
    inputs: tuple[str, ...]
    values: tuple[tuple[Fraction, ...], ...]
    degrees_of_freedom: int

    def speeds(self, given: Sequence[float]) -> dict[str, Fraction]:
        """Each member's omega for the inputs' values, exactly (from the floats given)."""
        u = [Fraction(v) for v in given]
        return {
            name: sum((t * x for t, x in zip(row, u, strict=True)), Fraction(0))
            for name, row in zip(self.members, self.values, strict=True)
        }


@functools.lru_cache(maxsize=64)  # parsing checks it, analysing uses it: one scene, once
def speed_transfer(scene: GearTrainScene) -> Transfer:
    """T = N (E N)^-1 (see the module); ``InvalidScene`` where the inputs are too few or too many
    for the degrees of freedom, or do not determine every member."""
    members = scene.members
    n = len(members)
    a = relations(scene)
    basis = exact.null_space(a, n)  # f vectors
    f = len(basis)
    names = [name for name, _ in scene.inputs]
    if len(names) != f:
        said = ", ".join(names) or "none"
        raise InvalidScene(
            f"inputs: the train has {f} degree{'s' if f != 1 else ''} of freedom ({n} members, "
            f"{n - f} independent relations of {len(scene.meshes)} meshes and the shafts), so it "
            f"needs {f} input{'s' if f != 1 else ''}, but {len(names)} "
            f"{'are' if len(names) != 1 else 'is'} given ({said})"
            + ("; give 0 for a fixed member" if len(names) < f else "")
        )
    picks = [[Fraction(int(name == m)) for m in members] for name in names]
    if f and exact.rank(a + picks, n) < n:
        free = exact.null_space(a + picks, n)
        loose = [m for j, m in enumerate(members) if any(v[j] != 0 for v in free)]
        raise InvalidScene(
            f"inputs: {', '.join(names)} do not determine the train: their speeds are tied by "
            f"the meshes or shafts, and {', '.join(loose)} can still turn with them given; "
            "choose inputs that fix every member"
        )
    # (E N)^-1 column by column: the train's response to a unit speed of each input.
    en = [[vector[members.index(name)] for vector in basis] for name in names]
    columns = []
    for k in range(f):
        unit = [Fraction(int(i == k)) for i in range(f)]
        weights = exact.solve(en, unit)
        columns.append(
            [
                sum((w * v[j] for w, v in zip(weights, basis, strict=True)), Fraction(0))
                for j in range(n)
            ]
        )
    values = tuple(tuple(columns[k][j] for k in range(f)) for j in range(n))
    return Transfer(members, tuple(names), values, f)


def groups(scene: GearTrainScene) -> list[tuple[str, ...]]:
    """The bodies that turn as one: each shaft, and every other member on its own."""
    keyed = {name for shaft in scene.shafts for name in shaft}
    return list(scene.shafts) + [(m,) for m in scene.members if m not in keyed]


def outputs(scene: GearTrainScene) -> list[tuple[str, ...]]:
    """The bodies that deliver the train's power to the world (besides the inputs): a body on
    the frame's axes, no input among its members, that meets the rest of the train at one
    place only (one frame gear, or the planets of one carrier, or its own planets). A body that
    meets it at two places (an idler, a carrier keyed to the next stage's sun) passes the power
    on; a planet cannot be reached from outside."""
    inputs = {name for name, _ in scene.inputs}
    body_of = {m: g for g in groups(scene) for m in g}
    out = []
    for group in groups(scene):
        if inputs & set(group) or scene.mount(group[0]) is not None:
            continue
        meets: set[object] = set()
        for mesh in scene.meshes:
            for mine, other in (mesh.gears, mesh.gears[::-1]):
                if mine in group:
                    carrier = scene.mount(other)
                    meets.add(("planets", carrier) if carrier else body_of[other])
        for name in group:
            if any(g.carrier == name for g in scene.gears):
                meets.add(("planets", name))
        if len(meets) == 1:
            out.append(group)
    return out


def member_torques(scene: GearTrainScene, input_torque: Mapping[str, float]) -> dict[str, Fraction]:
    """Each member's torque from the world (its hub torque: what its shaft, bearing, motor,
    load or the frame applies to it), for the input torques given (N m) and ideal gears.

    Unknowns: a generalised force lambda_k per mesh (the Willis row a_k times lambda_k is the
    torques the mesh applies to its gears and carrier) and the world's torque W on each output
    body. Each body is in balance: sum over its members of (A_mesh^T lambda)_i + W = 0, with W
    given on the inputs of ``input_torque``, unknown on ``outputs`` and on the other inputs (a
    fixed member's reaction), zero elsewhere. A member's hub torque is -(A_mesh^T lambda)_i."""
    inputs = [name for name, _ in scene.inputs]
    for name in input_torque:
        if name not in inputs:
            raise InvalidScene(
                f"input_torque: {name!r} is not an input (the inputs: {', '.join(inputs)}); "
                "a torque is given on an input"
            )
    members = scene.members
    rows = [mesh_relation(scene, m) for m in scene.meshes]
    bodies = groups(scene)
    loaded = [g for g in bodies if set(g) & set(inputs) and not set(g) & set(input_torque)]
    loaded += outputs(scene)
    p, u = len(rows), len(loaded)
    system: list[list[Fraction]] = []
    rhs: list[Fraction] = []
    for body in bodies:
        line = [sum((rows[k][members.index(m)] for m in body), Fraction(0)) for k in range(p)]
        line += [Fraction(int(body == other)) for other in loaded]
        given = sum((Fraction(v) for n, v in input_torque.items() if n in body), Fraction(0))
        system.append(line)
        rhs.append(-given)
    width = p + u
    reduced, pivots = exact.row_echelon(
        [[*r, b] for r, b in zip(system, rhs, strict=True)], width + 1
    )
    if width in pivots:
        raise InvalidScene(
            "input_torque: the torques given cannot be in balance: with ideal gears the "
            "balances of torque and power tie them to each other for these tooth numbers, or "
            "nothing in the train takes them up (no output, no fixed member); give the torque "
            "on one input"
        )
    free = [j for j in range(width) if j not in pivots]
    if any(j >= p for j in free) or any(
        pivot >= p and any(row[j] != 0 for j in free)
        for row, pivot in zip(reduced, pivots, strict=True)
    ):
        names = ", ".join("+".join(g) for g in loaded)
        raise InvalidScene(
            f"input_torque: the balances of torque and power do not fix the torques on "
            f"{names}: the train delivers its power to more bodies than the balances can "
            "share it among; give fewer outputs (fix or drive one)"
        )
    solution = [Fraction(0)] * width
    for row, pivot in zip(reduced, pivots, strict=True):
        solution[pivot] = row[width]

    def hub(j: int, x: Sequence[Fraction]) -> Fraction:
        return -sum((rows[k][j] * x[k] for k in range(p)), Fraction(0))

    for z in exact.null_space(system, width):  # mesh forces the balances leave open
        split = [name for j, name in enumerate(members) if hub(j, z) != 0]
        if split:
            raise InvalidScene(
                f"input_torque: the torques of {', '.join(split)} are not fixed: the load "
                "splits between meshes that repeat one another in a way ideal rigid gears "
                "leave open"
            )
    return {name: hub(j, solution) for j, name in enumerate(members)}

"""What a gear train is: the scene of kind ``gear_train`` (docs/GEARS.md), parsed and checked.

A gear turns about the frame unless ``mounts`` puts its axis on a carrier; ``shafts`` key
members together (a compound gear, a carrier driving the next stage's sun); ``meshes`` pair
gears; ``inputs`` give the absolute angular velocities (rad/s, counter-clockwise positive seen
from the front) of as many members as the train has degrees of freedom; ``module`` (m) sets the
pitch radii r = m N / 2. The parser rejects, with the numbers, a document that breaks the
contract: unknown names, a member in two shafts, a mesh of two internal gears, an annulus with no
more teeth than its pinion, pitch circles that cannot touch on the module and mounts
(``solver.gears.geometry``), and inputs that do not match the degrees of freedom
(``solver.gears.train``), the last two by ``solver.gears.parse_gear_train``.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Mapping
from dataclasses import dataclass
from typing import Any

from solver.errors import InvalidScene

MAX_MEMBERS = 64  # gears and carriers together (a 64-member train solves in well under 1 s)
MAX_TEETH = 10_000
MAX_MODULE = 1.0  # m
MAX_SPEED = 1e9  # rad/s

# The keys a gear_train document may have, for the warnings about unknown keys
# (solver.model.scene.unknown_fields).
GEAR_TRAIN_FIELDS: dict[str, frozenset[str]] = {
    "": frozenset(
        ("kind", "title", "gears", "carriers", "mounts", "shafts", "meshes", "inputs", "module")
    ),
    "gears.*": frozenset(("teeth", "internal")),
}


@dataclass(frozen=True)
class Gear:
    """A gear of ``teeth`` teeth; ``internal`` for an annulus; ``carrier`` its axis's carrier
    (None: the axis is fixed in the frame)."""

    name: str
    teeth: int
    internal: bool
    carrier: str | None


@dataclass(frozen=True)
class Mesh:
    """Two meshing gears, seen from ``carrier`` (None: the frame), the body that holds both
    axes; ``internal`` when one of them is an annulus."""

    gears: tuple[str, str]
    carrier: str | None
    internal: bool


@dataclass(frozen=True)
class GearTrainScene:
    """A parsed gear train (immutable). ``members``: the gears, then the carriers."""

    gears: tuple[Gear, ...]
    carriers: tuple[str, ...]
    shafts: tuple[tuple[str, ...], ...]
    meshes: tuple[Mesh, ...]
    inputs: tuple[tuple[str, float], ...]
    module: float | None = None
    title: str | None = None

    @property
    def members(self) -> tuple[str, ...]:
        return tuple(g.name for g in self.gears) + self.carriers

    @property
    def response_entries(self) -> tuple[int, str]:
        """Values per sample of a sweep, and what they are: each member's angle, each planet's
        centre (x, y) when the module places it (``solver.estimate_work`` counts them)."""
        planets = sum(1 for g in self.gears if g.carrier is not None)
        count = len(self.members) + (2 * planets if self.module is not None else 0)
        return count, "member angles and planet centre coordinates"

    def gear(self, name: str) -> Gear:
        return next(g for g in self.gears if g.name == name)

    def mount(self, member: str) -> str | None:
        """The carrier that holds ``member``'s axis (None: the frame; a carrier turns about the
        frame)."""
        return next((g.carrier for g in self.gears if g.name == member), None)


def real(value: Any) -> float | None:
    """``value`` as a finite float, or None where it is not a finite number (a bool, a string,
    NaN, infinity, an integer too large for a float)."""
    if isinstance(value, bool) or not isinstance(value, int | float):
        return None
    try:
        number = float(value)
    except OverflowError:
        return None
    return number if math.isfinite(number) else None


def _names(value: Any, where: str) -> list[str]:
    if not isinstance(value, list) or not all(isinstance(v, str) for v in value):
        raise InvalidScene(f"{where}: expected a list of names, got {value!r}")
    return value


def _known(name: str, known: tuple[str, ...], where: str, what: str) -> str:
    if name not in known:
        listed = ", ".join(known) or "none"
        raise InvalidScene(f"{where}: {name!r} is not a {what} (the train's {what}s: {listed})")
    return name


def _speed(value: Any, where: str) -> float:
    number = real(value)
    if number is None:
        raise InvalidScene(f"{where}: expected a finite number (rad/s), got {value!r:.40}")
    if abs(number) > MAX_SPEED:
        raise InvalidScene(f"{where}: |{number:g}| rad/s is more than {MAX_SPEED:g} rad/s")
    return number


def _gear(name: Any, body: Any, mounts: Mapping[str, str]) -> Gear:
    where = f"gears.{name}"
    if not isinstance(name, str) or not name:
        raise InvalidScene(f"gears: a gear's name must be a non-empty string, got {name!r}")
    if not isinstance(body, Mapping):
        raise InvalidScene(f"{where}: expected an object with teeth, got {body!r}")
    teeth = body.get("teeth")
    number = real(teeth)
    if number is None or number != int(number) or not 1 <= number <= MAX_TEETH:
        raise InvalidScene(
            f"{where}.teeth: expected a whole number 1..{MAX_TEETH}, got {teeth!r:.40}"
        )
    internal = body.get("internal", False)
    if not isinstance(internal, bool):
        raise InvalidScene(f"{where}.internal: expected true or false, got {internal!r}")
    return Gear(name, int(number), internal, mounts.get(name))


def _shafts(
    value: Any, members: tuple[str, ...], scene_mount: Callable[[str], str | None]
) -> tuple[tuple[str, ...], ...]:
    if not isinstance(value, list):
        raise InvalidScene(f"shafts: expected a list of lists of member names, got {value!r}")
    seen: dict[str, int] = {}
    out: list[tuple[str, ...]] = []
    for i, group in enumerate(value):
        names = _names(group, f"shafts[{i}]")
        for name in names:
            _known(name, members, f"shafts[{i}]", "member")
            if name in seen:
                where = f"listed in shafts[{i}]" if seen[name] == i else f"in shafts[{seen[name]}]"
                raise InvalidScene(
                    f"shafts[{i}]: {name} is already {where}; a member is keyed to "
                    "one shaft (list every member of a shaft in one group)"
                )
            seen[name] = i
        axes = {scene_mount(name) for name in names}
        if len(axes) > 1:
            told = ", ".join(
                f"{n} on carrier {scene_mount(n)}" if scene_mount(n) else f"{n} about the frame"
                for n in names
            )
            raise InvalidScene(
                f"shafts[{i}]: the members of a shaft turn about one axis, but {told}"
            )
        out.append(tuple(names))
    return tuple(out)


def _mesh(i: int, pair: Any, gears: Mapping[str, Gear], carriers: tuple[str, ...]) -> Mesh:
    where = f"meshes[{i}]"
    if not isinstance(pair, list) or len(pair) != 2 or not all(isinstance(p, str) for p in pair):
        raise InvalidScene(f"{where}: expected two gear names, got {pair!r}")
    for name in pair:
        if name in carriers:
            raise InvalidScene(f"{where}: {name} is a carrier; a mesh pairs two gears")
        _known(name, tuple(gears), where, "gear")
    a, b = gears[pair[0]], gears[pair[1]]
    if a.name == b.name:
        raise InvalidScene(f"{where}: {a.name} cannot mesh with itself")
    if a.internal and b.internal:
        raise InvalidScene(
            f"{where}: {a.name} and {b.name} are both internal gears; an annulus meshes with an "
            "external gear"
        )
    if a.internal or b.internal:
        ring, pinion = (a, b) if a.internal else (b, a)
        if ring.teeth <= pinion.teeth:
            raise InvalidScene(
                f"{where}: the annulus {ring.name} ({ring.teeth} teeth) cannot hold {pinion.name} "
                f"({pinion.teeth} teeth) inside it; an annulus needs more teeth than its pinion"
            )
    if a.carrier is not None and b.carrier is not None and a.carrier != b.carrier:
        raise InvalidScene(
            f"{where}: {a.name} turns on carrier {a.carrier} and {b.name} on carrier "
            f"{b.carrier}; two meshing gears must have their axes on one body (put both on one "
            "carrier)"
        )
    return Mesh((a.name, b.name), a.carrier or b.carrier, a.internal or b.internal)


def build_gear_train(doc: Mapping[str, Any]) -> GearTrainScene:
    """The scene of a ``gear_train`` document, its names and values checked (``InvalidScene``
    says what is wrong); ``solver.gears.parse_gear_train`` also checks its pitch circles and its
    inputs."""
    if doc.get("kind") != "gear_train":
        raise InvalidScene(f"kind: expected 'gear_train', got {doc.get('kind')!r}")
    raw_gears = doc.get("gears")
    if not isinstance(raw_gears, Mapping) or not raw_gears:
        raise InvalidScene(f"gears: expected an object of gears by name, got {raw_gears!r}")
    carriers = tuple(_names(doc.get("carriers", []), "carriers"))
    if len(set(carriers)) != len(carriers):
        raise InvalidScene(f"carriers: a name is listed twice in {list(carriers)}")
    for name in carriers:
        if name in raw_gears:
            raise InvalidScene(f"carriers: {name} is already a gear's name")
    if len(raw_gears) + len(carriers) > MAX_MEMBERS:
        raise InvalidScene(
            f"gears and carriers: {len(raw_gears)} + {len(carriers)} members, more than "
            f"{MAX_MEMBERS}"
        )
    raw_mounts = doc.get("mounts", {})
    if not isinstance(raw_mounts, Mapping):
        raise InvalidScene(f"mounts: expected an object gear -> carrier, got {raw_mounts!r}")
    mounts: dict[str, str] = {}
    for gear, carrier in raw_mounts.items():
        if gear in carriers:
            raise InvalidScene(f"mounts: {gear} is a carrier; a carrier turns about the frame")
        _known(gear, tuple(raw_gears), "mounts", "gear")
        if not isinstance(carrier, str):
            raise InvalidScene(f"mounts.{gear}: expected a carrier's name, got {carrier!r}")
        mounts[gear] = _known(carrier, carriers, f"mounts.{gear}", "carrier")
    gears = {name: _gear(name, body, mounts) for name, body in raw_gears.items()}
    members = (*gears, *carriers)

    def mount(name: str) -> str | None:
        return gears[name].carrier if name in gears else None

    shafts = _shafts(doc.get("shafts", []), members, mount)
    raw_meshes = doc.get("meshes")
    if not isinstance(raw_meshes, list):
        raise InvalidScene(f"meshes: expected a list of gear pairs, got {raw_meshes!r}")
    meshes = tuple(_mesh(i, pair, gears, carriers) for i, pair in enumerate(raw_meshes))
    for i, mesh in enumerate(meshes):
        for j in range(i):
            if set(meshes[j].gears) == set(mesh.gears):
                raise InvalidScene(
                    f"meshes[{i}]: {' and '.join(mesh.gears)} already mesh in meshes[{j}]"
                )
    raw_inputs = doc.get("inputs")
    if not isinstance(raw_inputs, Mapping):
        raise InvalidScene(
            f"inputs: expected an object member -> angular velocity (rad/s), got {raw_inputs!r}"
        )
    inputs = tuple(
        (_known(name, members, "inputs", "member"), _speed(value, f"inputs.{name}"))
        for name, value in raw_inputs.items()
    )
    module = doc.get("module")
    metres = real(module)
    if module is not None and (metres is None or not 0.0 < metres <= MAX_MODULE):
        raise InvalidScene(
            f"module: expected a number of metres in (0, {MAX_MODULE:g}], got {module!r:.40}"
        )
    title = doc.get("title")
    return GearTrainScene(
        tuple(gears.values()),
        carriers,
        shafts,
        meshes,
        inputs,
        metres,
        title if isinstance(title, str) else None,
    )

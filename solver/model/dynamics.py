"""The mass properties and loads of a linkage (dynamics-v1 scene fields), and their validation.

``parse_dynamics`` reads ``masses``, ``point_masses``, ``gravity``, ``forces`` and ``torques``
from a scene document, checks every name against the scene's links and points, and returns a
``Dynamics`` (None when the document has none of these fields). Centres of mass are kept in world
coordinates at the drawn pose; the links carry them from there.
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any, Literal

from solver.errors import InvalidExpression, InvalidScene, LimitExceeded
from solver.model.laws import StateExpression, parse_state_expression

if TYPE_CHECKING:  # the scene module imports this one
    from solver.model.scene import Link

FIELDS = ("masses", "point_masses", "gravity", "forces", "torques")
MAX_MASS = 1e9  # kg
MAX_INERTIA = 1e12  # kg m^2
MAX_GRAVITY = 1e4  # m/s^2
MAX_DIRECTION_DEG = 1e6
MAX_LOADS = 100


@dataclass(frozen=True)
class Body:
    """The mass of a link: ``mass`` at ``center`` (world, drawn pose), ``inertia`` about it."""

    link: str
    mass: float
    center: tuple[float, float]
    inertia: float


@dataclass(frozen=True)
class PointMass:
    """A concentrated mass at a named point, carried by ``link``."""

    name: str
    link: str
    point: str
    mass: float


@dataclass(frozen=True)
class Force:
    """An external force at ``point`` of ``link``: magnitude(state) along ``direction_deg``,
    measured from +x (``world``) or from the link's angle (``link``: it turns with the link)."""

    name: str
    link: str
    point: str
    magnitude: StateExpression
    direction_deg: float
    relative_to: Literal["world", "link"]


@dataclass(frozen=True)
class Torque:
    """An external moment on ``link`` (counter-clockwise positive) as an expression."""

    name: str
    link: str
    moment: StateExpression


@dataclass(frozen=True)
class Dynamics:
    bodies: tuple[Body, ...] = ()
    point_masses: tuple[PointMass, ...] = ()
    gravity: tuple[float, float] = (0.0, 0.0)
    forces: tuple[Force, ...] = ()
    torques: tuple[Torque, ...] = ()

    @property
    def total_mass(self) -> float:
        return sum(b.mass for b in self.bodies) + sum(p.mass for p in self.point_masses)

    def masses_of(self, link: str) -> tuple[Sequence[Body], Sequence[PointMass]]:
        return (
            [b for b in self.bodies if b.link == link],
            [p for p in self.point_masses if p.link == link],
        )


def _fail(path: str, message: str) -> InvalidScene:
    return InvalidScene(f"{path}: {message}")


def _number(value: Any, path: str, limit: float, minimum: float = -math.inf) -> float:
    if isinstance(value, bool) or not isinstance(value, int | float):
        raise _fail(path, f"expected a number, got {value!r}")
    number = float(value)
    if not math.isfinite(number) or abs(number) > limit:
        raise _fail(path, f"must be a finite number of magnitude at most {limit:g}")
    if number < minimum:
        raise _fail(path, f"must not be negative, got {number:g}")
    return number


def _vector(value: Any, path: str, limit: float) -> tuple[float, float]:
    if not isinstance(value, Sequence) or isinstance(value, str) or len(value) != 2:
        raise _fail(path, f"expected a vector [x, y], got {value!r}")
    return (_number(value[0], f"{path}[0]", limit), _number(value[1], f"{path}[1]", limit))


def _object(value: Any, path: str) -> Mapping[str, Any]:
    if not isinstance(value, Mapping):
        raise _fail(path, "expected an object")
    return value


def _entries(value: Any, path: str) -> Sequence[Any]:
    if not isinstance(value, Sequence) or isinstance(value, str):
        raise _fail(path, "expected a list")
    if len(value) > MAX_LOADS:
        raise LimitExceeded(f"{path}: {len(value)} entries exceed the limit of {MAX_LOADS}")
    return value


class _Parser:
    def __init__(
        self, points: Mapping[str, tuple[float, float]], links: Mapping[str, Link]
    ) -> None:
        self.points, self.links = points, links

    def moving_link(self, value: Any, path: str) -> str:
        if not isinstance(value, str) or value not in self.links:
            raise _fail(path, f"unknown link {value!r}")
        if self.links[value].ground:
            raise _fail(path, f"'{value}' is the ground: only moving links carry masses and loads")
        return value

    def point_of(self, link: str, value: Any, path: str) -> str:
        if not isinstance(value, str) or value not in self.links[link].points:
            raise _fail(path, f"{value!r} is not a point of link '{link}'")
        return value

    def name(self, value: Any, path: str, used: set[str]) -> str:
        if not isinstance(value, str) or not value or len(value) > 64:
            raise _fail(path, f"expected a non-empty name, got {value!r}")
        if value in used:
            raise _fail(path, f"the name '{value}' is used twice")
        used.add(value)
        return value

    def expression(self, value: Any, path: str) -> StateExpression:
        if isinstance(value, int | float) and not isinstance(value, bool):
            value = repr(float(_number(value, path, 1e12)))
        if not isinstance(value, str):
            raise _fail(path, "expected an expression (a string) or a number")
        try:
            parsed = parse_state_expression(value)
        except InvalidExpression as error:
            raise InvalidExpression(f"{path}: {error.message}", error.position, value) from None
        for link in sorted(parsed.links):
            if link not in self.links:
                raise InvalidExpression(f"{path}: unknown link '{link}'", value.find(link), value)
            if len(self.links[link].points) < 2:
                raise InvalidExpression(
                    f"{path}: link '{link}' has one point, so no angle", value.find(link), value
                )
        return parsed

    def bodies(self, raw: Any) -> tuple[Body, ...]:
        bodies = []
        for link, body in _object(raw, "masses").items():
            path = f"masses.{link}"
            self.moving_link(link, path)
            body = _object(body, path)
            mass = _number(body.get("mass"), f"{path}.mass", MAX_MASS, 0.0)
            if "bar" in body:
                if "center" in body or "inertia" in body:
                    raise _fail(path, "give either bar or center and inertia, not both")
                ends = body["bar"]
                if not isinstance(ends, Sequence) or isinstance(ends, str) or len(ends) != 2:
                    raise _fail(f"{path}.bar", "expected two points [P, Q]")
                P, Q = (self.point_of(link, e, f"{path}.bar[{i}]") for i, e in enumerate(ends))
                (px, py), (qx, qy) = self.points[P], self.points[Q]
                center = (0.5 * (px + qx), 0.5 * (py + qy))
                inertia = mass * ((qx - px) ** 2 + (qy - py) ** 2) / 12.0
            elif "center" in body:
                center = _vector(body["center"], f"{path}.center", 1e6)
                inertia = _number(body.get("inertia", 0.0), f"{path}.inertia", MAX_INERTIA, 0.0)
            else:
                raise _fail(path, "give bar: [P, Q] or center: [x, y] with inertia")
            bodies.append(Body(link, mass, center, inertia))
        return tuple(bodies)

    def point_masses(self, raw: Any) -> tuple[PointMass, ...]:
        used: set[str] = set()
        masses = []
        for i, entry in enumerate(_entries(raw, "point_masses")):
            path = f"point_masses[{i}]"
            entry = _object(entry, path)
            name = self.name(entry.get("name", f"m_{entry.get('point')}"), f"{path}.name", used)
            link = self.moving_link(entry.get("link"), f"{path}.link")
            point = self.point_of(link, entry.get("point"), f"{path}.point")
            masses.append(
                PointMass(name, link, point, _number(entry.get("mass"), f"{path}.mass", 1e9, 0.0))
            )
        return tuple(masses)

    def forces(self, raw: Any, used: set[str]) -> tuple[Force, ...]:
        forces = []
        for i, entry in enumerate(_entries(raw, "forces")):
            path = f"forces[{i}]"
            entry = _object(entry, path)
            name = self.name(entry.get("name", f"F{i + 1}"), f"{path}.name", used)
            link = self.moving_link(entry.get("link"), f"{path}.link")
            point = self.point_of(link, entry.get("point"), f"{path}.point")
            relative_to = entry.get("relative_to", "world")
            if relative_to not in ("world", "link"):
                raise _fail(f"{path}.relative_to", "expected 'world' or 'link'")
            if relative_to == "link" and len(self.links[link].points) < 2:
                raise _fail(f"{path}.relative_to", f"link '{link}' has one point, so no angle")
            forces.append(
                Force(
                    name,
                    link,
                    point,
                    self.expression(entry.get("magnitude"), f"{path}.magnitude"),
                    _number(
                        entry.get("direction_deg", 0.0), f"{path}.direction_deg", MAX_DIRECTION_DEG
                    ),
                    relative_to,
                )
            )
        return tuple(forces)

    def torques(self, raw: Any, used: set[str]) -> tuple[Torque, ...]:
        torques = []
        for i, entry in enumerate(_entries(raw, "torques")):
            path = f"torques[{i}]"
            entry = _object(entry, path)
            name = self.name(entry.get("name", f"M{i + 1}"), f"{path}.name", used)
            link = self.moving_link(entry.get("link"), f"{path}.link")
            torques.append(
                Torque(name, link, self.expression(entry.get("moment"), f"{path}.moment"))
            )
        return tuple(torques)


def parse_dynamics(
    doc: Mapping[str, Any],
    points: Mapping[str, tuple[float, float]],
    links: Mapping[str, Link],
) -> Dynamics | None:
    """The dynamics fields of a scene document, validated (None if it has none of them)."""
    if not any(key in doc for key in FIELDS):
        return None
    parser = _Parser(points, links)
    used: set[str] = set()
    return Dynamics(
        parser.bodies(doc.get("masses", {})),
        parser.point_masses(doc.get("point_masses", [])),
        _vector(doc.get("gravity", [0.0, 0.0]), "gravity", MAX_GRAVITY),
        parser.forces(doc.get("forces", []), used),
        parser.torques(doc.get("torques", []), used),
    )

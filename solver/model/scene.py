"""The immutable scene model of a planar linkage, and its validation from a scene-v1 document.

A ``LinkageScene`` is the definition (what the mechanism is, drawn in one pose); the solver never
mutates it. ``parse_linkage`` turns a JSON document into one, or raises ``InvalidScene`` /
``LimitExceeded`` with a message that says where the document is wrong.
"""

from __future__ import annotations

import difflib
import math
from collections.abc import Callable, Hashable, Iterable, Mapping, Sequence
from dataclasses import dataclass
from functools import cached_property
from typing import Any, Literal, TypeVar

import numpy as np

from solver.errors import InvalidScene, LimitExceeded
from solver.model.dynamics import Dynamics, parse_dynamics
from solver.model.laws import parse_time_law

JointType = Literal["revolute", "slider", "prismatic"]

T = TypeVar("T")

MAX_POINTS = 200
MAX_LINKS = 100
MAX_JOINTS = 200
MAX_MOVING_POINTS = 20
MAX_NAME_LENGTH = 64
MAX_COORDINATE = 1e6  # m: a mechanism larger than 1000 km is a typo
MAX_RATE = 1e6  # rad/s and rad/s^2 magnitudes
MAX_TIME = 1e6  # s
# Two points of one link closer than this fraction of the scene's size make a zero-length link.
MIN_RELATIVE_LENGTH = 1e-9


@dataclass(frozen=True)
class Link:
    """A rigid link: the names of the points attached to it."""

    name: str
    points: tuple[str, ...]
    ground: bool = False


@dataclass(frozen=True)
class Friction:
    """Dry (Coulomb) friction at a joint: |f| = mu |N| along a slot, and at a revolute joint the
    friction circle of radius mu r (``pin_radius`` r, None at a slot): a friction moment
    mu r |F| against the relative rotation (docs/DYNAMICS.md, "Friction")."""

    coefficient: float
    pin_radius: float | None = None

    @property
    def circle_radius(self) -> float:
        """mu r: the friction circle's radius (0 at a slot, where the pin has none)."""
        return self.coefficient * (self.pin_radius or 0.0)


@dataclass(frozen=True)
class Joint:
    """A joint at ``point`` between ``links``; slider and prismatic: ``links = (guide, follower)``.

    ``axis`` is the unit direction of the slot (world coordinates at the drawn pose), fixed in the
    guide; ``None`` for a revolute joint. ``friction``: None for a frictionless joint.
    """

    type: JointType
    point: str
    links: tuple[str, str]
    axis: tuple[float, float] | None = None
    friction: Friction | None = None

    @property
    def guide(self) -> str:
        return self.links[0]

    @property
    def follower(self) -> str:
        return self.links[1]


@dataclass(frozen=True)
class Driver:
    """A driven link turning about its revolute joint with the ground.

    Either constant ``omega``/``alpha`` (with an optional absolute ``angle_deg``), or an
    ``angle_law``: the rotation from the drawn pose in radians as an expression in ``t``.
    """

    link: str
    pivot: str
    omega: float = 0.0
    alpha: float = 0.0
    angle_deg: float | None = None
    angle_law: str | None = None


@dataclass(frozen=True)
class Path:
    """A path fixed in a link: an ``arc`` about ``center`` from ``start`` or a ``line``.

    An arc spans ``sweep_deg`` degrees from ``start`` in its ``direction`` (360: a whole circle,
    whose arc length wraps round; less: a groove with an end, 180 a semicircle)."""

    type: Literal["arc", "line"]
    start: str
    center: str | None = None
    direction: Literal["cw", "ccw"] = "ccw"
    through: str | None = None
    sweep_deg: float = 360.0


@dataclass(frozen=True)
class MovingPoint:
    """A point moving along ``path`` fixed in ``link``, with arc length ``s_law`` (m) in time."""

    name: str
    link: str
    path: Path
    s_law: str


@dataclass(frozen=True)
class LinkageScene:
    """A planar linkage drawn in one pose (scene-v1 kind ``linkage``)."""

    title: str
    points: Mapping[str, tuple[float, float]]
    links: Mapping[str, Link]
    joints: tuple[Joint, ...]
    drivers: tuple[Driver, ...]
    ground: str
    moving_points: tuple[MovingPoint, ...] = ()
    time: float = 0.0
    dynamics: Dynamics | None = None  # masses and loads (dynamics-v1), None without them

    def drawn(self, point: str) -> np.ndarray:
        """The drawn position of ``point`` as an array (read-only: shared between callers)."""
        return self._drawn[point]

    @cached_property
    def _drawn(self) -> dict[str, np.ndarray]:
        arrays = {name: np.array(xy, dtype=float) for name, xy in self.points.items()}
        for array in arrays.values():
            array.flags.writeable = False
        return arrays

    @cached_property
    def memo(self) -> dict[str, Any]:
        """What the layers above derive from this scene once (its plan, its constraint systems),
        by name: kept on the scene object and forgotten with it (a scene is immutable, so is all
        that is derived from it)."""
        return {}

    def latest(self, name: str, key: Hashable, make: Callable[[], T]) -> T:
        """``make()`` for ``key``, kept in ``memo`` under ``name`` for the latest key only (what
        depends on a sweep's sample count, say: the next count asked replaces it)."""
        kept = self.memo.get(name)
        if kept is not None and kept[0] == key:
            return kept[1]
        value = make()
        self.memo[name] = (key, value)
        return value

    @cached_property
    def size(self) -> float:
        """A characteristic length: the diagonal of the drawn points' bounding box."""
        xy = np.array(list(self.points.values()), dtype=float)
        return max(float(np.hypot(*(xy.max(axis=0) - xy.min(axis=0)))), 1e-300)

    def links_of(self, point: str) -> tuple[str, ...]:
        """The links the point is rigidly attached to."""
        return tuple(name for name, link in self.links.items() if point in link.points)

    @property
    def moving_links(self) -> tuple[str, ...]:
        return tuple(name for name in self.links if name != self.ground)

    @property
    def degrees_of_freedom(self) -> int:
        """Gruebler's count: 3 per moving link, minus 2 per revolute and prismatic, 1 per slider."""
        removed = {"revolute": 2, "prismatic": 2, "slider": 1}
        return 3 * len(self.moving_links) - sum(removed[j.type] for j in self.joints)


def _where(path: str, message: str) -> InvalidScene:
    return InvalidScene(f"{path}: {message}")


def _name(value: Any, path: str) -> str:
    if not isinstance(value, str) or not value:
        raise _where(path, f"expected a non-empty name, got {value!r}")
    if len(value) > MAX_NAME_LENGTH:
        raise _where(path, f"names are at most {MAX_NAME_LENGTH} characters")
    return value


def _number(value: Any, path: str, limit: float) -> float:
    if isinstance(value, bool) or not isinstance(value, int | float):
        raise _where(path, f"expected a number, got {value!r}")
    try:
        number = float(value)
    except OverflowError:  # an integer literal beyond the float range
        number = math.inf
    if not math.isfinite(number):
        raise _where(path, "must be a finite number")
    if abs(number) > limit:
        raise _where(path, f"|{number:g}| exceeds the limit {limit:g}")
    return number


def _vector(value: Any, path: str, limit: float = MAX_COORDINATE) -> tuple[float, float]:
    if not isinstance(value, Sequence) or isinstance(value, str) or len(value) != 2:
        raise _where(path, f"expected a vector [x, y], got {value!r}")
    return (_number(value[0], f"{path}[0]", limit), _number(value[1], f"{path}[1]", limit))


def _mapping(value: Any, path: str) -> Mapping[str, Any]:
    if not isinstance(value, Mapping):
        raise _where(path, "expected an object")
    return value


def _list(value: Any, path: str, limit: int) -> Sequence[Any]:
    if not isinstance(value, Sequence) or isinstance(value, str):
        raise _where(path, "expected a list")
    if len(value) > limit:
        raise LimitExceeded(f"{path}: {len(value)} entries exceed the limit of {limit}")
    return value


def _parse_points(doc: Mapping[str, Any]) -> dict[str, tuple[float, float]]:
    raw = _mapping(doc.get("points"), "points")
    if not raw:
        raise _where("points", "a linkage needs at least one point")
    if len(raw) > MAX_POINTS:
        raise LimitExceeded(f"points: {len(raw)} points exceed the limit of {MAX_POINTS}")
    return {_name(k, "points"): _vector(v, f"points.{k}") for k, v in raw.items()}


def _parse_links(doc: Mapping[str, Any], points: Mapping[str, Any]) -> dict[str, Link]:
    raw = _mapping(doc.get("links"), "links")
    if len(raw) > MAX_LINKS:
        raise LimitExceeded(f"links: {len(raw)} links exceed the limit of {MAX_LINKS}")
    links: dict[str, Link] = {}
    for name, body in raw.items():
        path = f"links.{_name(name, 'links')}"
        body = _mapping(body, path)
        names = tuple(
            _name(p, f"{path}.points[{i}]")
            for i, p in enumerate(_list(body.get("points"), f"{path}.points", MAX_POINTS))
        )
        if not names:
            raise _where(f"{path}.points", "a link needs at least one point")
        for i, p in enumerate(names):
            if p not in points:
                raise _where(f"{path}.points[{i}]", f"unknown point '{p}'")
        if len(set(names)) != len(names):
            raise _where(f"{path}.points", "a point is listed twice")
        ground = body.get("ground", False)
        if not isinstance(ground, bool):
            raise _where(f"{path}.ground", "expected true or false")
        links[name] = Link(name, names, ground)
    grounds = [name for name, link in links.items() if link.ground]
    if len(grounds) != 1:
        raise _where(
            "links",
            f'exactly one link must have "ground": true, found {len(grounds)}'
            + (f" ({', '.join(grounds)})" if grounds else ""),
        )
    return links


def _check_link_lengths(
    links: Mapping[str, Link], points: Mapping[str, tuple[float, float]]
) -> None:
    xy = np.array(list(points.values()))
    size = max(float(np.hypot(*(xy.max(axis=0) - xy.min(axis=0)))), 1e-300)
    for link in links.values():
        if link.ground:
            continue
        for i, a in enumerate(link.points):
            for b in link.points[i + 1 :]:
                d = math.dist(points[a], points[b])
                if d <= MIN_RELATIVE_LENGTH * size:
                    raise _where(
                        f"links.{link.name}",
                        f"zero-length link: points {a} and {b} coincide (|{a}{b}| = {d:.3g} m)",
                    )


def _parse_joints(doc: Mapping[str, Any], links: Mapping[str, Link]) -> tuple[Joint, ...]:
    joints = []
    for i, body in enumerate(_list(doc.get("joints"), "joints", MAX_JOINTS)):
        path = f"joints[{i}]"
        body = _mapping(body, path)
        kind = body.get("type")
        if kind not in ("revolute", "slider", "prismatic"):
            raise _where(
                f"{path}.type",
                f"unknown joint type {kind!r}; expected revolute, slider or prismatic",
            )
        point = _name(body.get("point"), f"{path}.point")
        pair = _list(body.get("links"), f"{path}.links", MAX_LINKS)
        if len(pair) != 2:
            raise _where(f"{path}.links", "a joint connects exactly two links")
        a, b = (_name(x, f"{path}.links[{k}]") for k, x in enumerate(pair))
        for k, name in enumerate((a, b)):
            if name not in links:
                raise _where(f"{path}.links[{k}]", f"unknown link '{name}'")
        if a == b:
            raise _where(f"{path}.links", "a joint connects two different links")
        axis = None
        if kind == "revolute":
            if point not in links[a].points or point not in links[b].points:
                raise _where(
                    f"{path}.point",
                    f"revolute joint point '{point}' must be listed in "
                    f"the points of both links '{a}' and '{b}'",
                )
        else:
            if "axis" not in body:
                raise _where(f"{path}.axis", f"a {kind} joint needs the slot direction 'axis'")
            ax = _vector(body["axis"], f"{path}.axis")
            norm = math.hypot(*ax)
            if norm == 0.0:
                raise _where(f"{path}.axis", "the slot direction is the zero vector")
            axis = (ax[0] / norm, ax[1] / norm)
            if point not in links[b].points:
                raise _where(
                    f"{path}.point",
                    f"the {kind} point '{point}' is attached to the "
                    f"follower '{b}' and must be listed in its points",
                )
            if point in links[a].points:
                raise _where(
                    f"{path}.point",
                    f"the {kind} point '{point}' slides in the guide "
                    f"'{a}' and must not be listed in the guide's points",
                )
        friction = None
        if "friction" in body:
            friction = _parse_friction(body["friction"], kind, f"{path}.friction")
        joints.append(Joint(kind, point, (a, b), axis, friction))
    return tuple(joints)


# A coefficient of dry friction above this is a typo (rubber on dry concrete is about 1).
MAX_FRICTION_COEFFICIENT = 10.0


def _parse_friction(value: Any, kind: str, path: str) -> Friction:
    """``{"coefficient": mu}`` at a slider or prismatic joint, ``{"coefficient": mu,
    "pin_radius": r}`` at a revolute joint; mu in [0, 10], r > 0 (m)."""
    body = _mapping(value, path)
    for key in body:
        if key not in ("coefficient", "pin_radius"):
            raise _where(f"{path}.{key}", "friction takes 'coefficient' and 'pin_radius' only")
    if "coefficient" not in body:
        raise _where(f"{path}.coefficient", "friction needs its Coulomb coefficient")
    mu = _number(body["coefficient"], f"{path}.coefficient", MAX_FRICTION_COEFFICIENT)
    if mu < 0.0:
        raise _where(f"{path}.coefficient", f"a friction coefficient is not negative (got {mu})")
    if kind != "revolute":
        if "pin_radius" in body:
            raise _where(
                f"{path}.pin_radius", f"a {kind} joint has no pin: its friction is mu |N| alone"
            )
        return Friction(mu)
    if "pin_radius" not in body:
        raise _where(
            f"{path}.pin_radius",
            "a revolute joint's friction needs the pin radius (friction circle mu r)",
        )
    r = _number(body["pin_radius"], f"{path}.pin_radius", MAX_COORDINATE)
    if r <= 0.0:
        raise _where(f"{path}.pin_radius", f"the pin radius is positive (got {r} m)")
    return Friction(mu, r)


def ground_pivot(link: str, joints: Iterable[Joint], ground: str) -> str | None:
    """The point of the revolute joint between ``link`` and the ground, or None if it has none
    (the fixed pivot a driver turns about, a link's velocity pole)."""
    for joint in joints:
        if joint.type == "revolute" and set(joint.links) == {link, ground}:
            return joint.point
    return None


def _parse_drivers(
    doc: Mapping[str, Any], links: Mapping[str, Link], joints: Sequence[Joint], ground: str
) -> tuple[Driver, ...]:
    drivers = []
    seen = set()
    for i, body in enumerate(_list(doc.get("drivers", []), "drivers", MAX_LINKS)):
        path = f"drivers[{i}]"
        body = _mapping(body, path)
        link = _name(body.get("link"), f"{path}.link")
        if link not in links:
            raise _where(f"{path}.link", f"unknown link '{link}'")
        if link == ground:
            raise _where(f"{path}.link", "the ground cannot be driven")
        if link in seen:
            raise _where(f"{path}.link", f"link '{link}' is driven twice")
        seen.add(link)
        pivot = ground_pivot(link, joints, ground)
        if pivot is None:
            raise _where(
                f"{path}.link",
                f"the driven link '{link}' has no revolute joint with the ground '{ground}'",
            )
        law = body.get("angle_law")
        if law is not None:
            if not isinstance(law, str):
                raise _where(f"{path}.angle_law", "expected an expression in t")
            if "omega" in body or "alpha" in body or "angle_deg" in body:
                raise _where(path, "give either angle_law or omega/alpha/angle_deg, not both")
            parse_time_law(law)
            drivers.append(Driver(link, pivot, angle_law=law))
            continue
        angle = body.get("angle_deg")
        drivers.append(
            Driver(
                link,
                pivot,
                omega=_number(body.get("omega", 0.0), f"{path}.omega", MAX_RATE),
                alpha=_number(body.get("alpha", 0.0), f"{path}.alpha", MAX_RATE),
                angle_deg=None if angle is None else _number(angle, f"{path}.angle_deg", 1e6),
            )
        )
    return tuple(drivers)


def _parse_moving_points(
    doc: Mapping[str, Any], scene_points: Mapping[str, Any], links: Mapping[str, Link]
) -> tuple[MovingPoint, ...]:
    moving: list[MovingPoint] = []
    for i, body in enumerate(
        _list(doc.get("moving_points", []), "moving_points", MAX_MOVING_POINTS)
    ):
        path = f"moving_points[{i}]"
        body = _mapping(body, path)
        name = _name(body.get("name"), f"{path}.name")
        if name in scene_points or any(m.name == name for m in moving):
            raise _where(f"{path}.name", f"the name '{name}' is already used")
        link = _name(body.get("link"), f"{path}.link")
        if link not in links:
            raise _where(f"{path}.link", f"unknown link '{link}'")
        raw = _mapping(body.get("path"), f"{path}.path")
        kind = raw.get("type")

        def point_of_link(
            key: str, p: str = path, r: Mapping[str, Any] = raw, carrier: str = link
        ) -> str:
            value = _name(r.get(key), f"{p}.path.{key}")
            if value not in links[carrier].points:
                raise _where(f"{p}.path.{key}", f"'{value}' is not a point of link '{carrier}'")
            return value

        if kind == "arc":
            direction = raw.get("direction", "ccw")
            if direction not in ("cw", "ccw"):
                raise _where(f"{path}.path.direction", "expected 'cw' or 'ccw'")
            center, start = point_of_link("center"), point_of_link("start")
            if scene_points[center] == scene_points[start]:
                raise _where(f"{path}.path", "the arc's start coincides with its centre")
            sweep = _number(raw.get("sweep_deg", 360.0), f"{path}.path.sweep_deg", 360.0)
            if sweep <= 0.0:
                raise _where(f"{path}.path.sweep_deg", "expected 0 < sweep_deg <= 360")
            route = Path("arc", start, center=center, direction=direction, sweep_deg=sweep)
        elif kind == "line":
            start, through = point_of_link("start"), point_of_link("through")
            if scene_points[start] == scene_points[through]:
                raise _where(f"{path}.path", "the line's start and through points coincide")
            route = Path("line", start, through=through)
        else:
            raise _where(f"{path}.path.type", f"unknown path type {kind!r}; expected arc or line")
        law = body.get("s_law")
        if not isinstance(law, str):
            raise _where(f"{path}.s_law", "expected an expression in t")
        parse_time_law(law)
        moving.append(MovingPoint(name, link, route, law))
    return tuple(moving)


def parse_linkage(doc: Mapping[str, Any]) -> LinkageScene:
    """Validate a scene-v1 ``linkage`` document and build the immutable scene."""
    doc = _mapping(doc, "scene")
    if doc.get("kind") != "linkage":
        raise _where("kind", f"expected 'linkage', got {doc.get('kind')!r}")
    title = doc.get("title", "")
    if not isinstance(title, str):
        raise _where("title", "expected a string")
    points = _parse_points(doc)
    links = _parse_links(doc, points)
    ground = next(name for name, link in links.items() if link.ground)
    attached = {p for link in links.values() for p in link.points}
    for name in points:
        if name not in attached:
            raise _where(f"points.{name}", "the point is not attached to any link")
    _check_link_lengths(links, points)
    joints = _parse_joints(doc, links)
    drivers = _parse_drivers(doc, links, joints, ground)
    time = _number(doc.get("time", 0.0), "time", MAX_TIME)
    scene = LinkageScene(
        title[:200],
        points,
        links,
        joints,
        drivers,
        ground,
        _parse_moving_points(doc, points, links),
        time,
        parse_dynamics(doc, points, links),
    )
    if scene.degrees_of_freedom != len(drivers):
        raise _where(
            "drivers",
            f"the linkage has {scene.degrees_of_freedom} degree(s) of freedom "
            f"(3 x {len(scene.moving_links)} links - 2 per revolute and prismatic joint "
            f"- 1 per slider) but {len(drivers)} driver(s)",
        )
    return scene


# --- keys the contract knows ---------------------------------------------------------------------

# The fields of scene-v1 (and of its additive extensions, dynamics-v1), by where they appear:
# "[]" stands for every entry of a list, "*" for every value of a name-keyed object. Points are
# name-keyed vectors and have no fields of their own.
SCENE_FIELDS: dict[str, dict[str, frozenset[str]]] = {
    "linkage": {
        "": frozenset(
            (
                "kind", "title", "points", "links", "joints", "drivers", "moving_points", "time",
                "masses", "point_masses", "gravity", "forces", "torques",
            )
        ),
        "links.*": frozenset(("points", "ground")),
        "joints[]": frozenset(("type", "point", "links", "axis", "friction")),
        "drivers[]": frozenset(("link", "omega", "alpha", "angle_deg", "angle_law")),
        "moving_points[]": frozenset(("name", "link", "path", "s_law")),
        "moving_points[].path": frozenset(
            ("type", "center", "start", "direction", "through", "sweep_deg")
        ),
        "masses.*": frozenset(("mass", "bar", "center", "inertia")),
        "point_masses[]": frozenset(("name", "link", "point", "mass")),
        "forces[]": frozenset(
            ("name", "link", "point", "magnitude", "direction_deg", "relative_to")
        ),
        "torques[]": frozenset(("name", "link", "moment")),
    },
    "spatial_chain": {
        "": frozenset(("kind", "title", "joints", "points")),
        "joints[]": frozenset(("name", "type", "origin", "axis", "rate", "rate_dot")),
        "points.*": frozenset(("body", "position")),
    },
    "cam": {
        "": frozenset(("kind", "title", "cam", "follower", "segments")),
        "cam": frozenset(("base_radius", "omega")),
        "follower": frozenset(
            ("motion", "contact", "roller_radius", "offset", "pivot", "arm_length")
        ),
        "segments[]": frozenset(("type", "law", "lift", "duration_deg")),
    },
}  # fmt: skip


# Fields whose value is text; between equally near names, one that takes the kind of value given
# wins ("angle": 120 is nearer angle_deg than angle_law).
TEXT_FIELDS = frozenset(
    ("kind", "title", "type", "point", "link", "name", "center", "start", "through", "direction",
     "angle_law", "s_law", "magnitude", "moment", "relative_to", "body", "motion", "contact",
     "law")
)  # fmt: skip


def _nearest(key: str, value: Any, known: frozenset[str]) -> str | None:
    """The known name nearest to ``key`` (difflib's ratio of at least 0.6), or None."""

    def ratio(name: str) -> float:
        return difflib.SequenceMatcher(None, key, name).ratio()

    close = difflib.get_close_matches(key, sorted(known), n=3, cutoff=0.6)
    nearest = [name for name in close if ratio(name) == ratio(close[0])]
    fitting = [name for name in nearest if (name in TEXT_FIELDS) == isinstance(value, str)]
    return next(iter(fitting or nearest), None)


def _unknown_here(known: frozenset[str], body: Mapping[str, Any], where: str) -> list[str]:
    """One sentence per key of ``body`` that ``known`` lacks, with the nearest known name."""
    found = []
    for key, value in body.items():
        if key in known:
            continue
        path = f"{where}.{key}" if where else str(key)
        close = _nearest(str(key), value, known)
        hint = f"did you mean {close}?" if close else f"the fields are {', '.join(sorted(known))}"
        found.append(f"{path} is not a scene field; {hint}")
    return found


def unknown_keys(
    doc: Mapping[str, Any], fields: Mapping[str, frozenset[str]] | None = None
) -> list[str]:
    """Every key of a scene document that the contract does not know, as sentences naming the key,
    its path and the nearest valid name: ``drivers[0].angle is not a scene field; did you mean
    angle_deg?``. The spec allows extra fields, so these are warnings (an error only on request);
    parts of the document that are not shaped as the contract says are left to the parser.
    ``fields``: the known keys by path pattern (default: the kind's in ``SCENE_FIELDS``; a
    chapter's own kind brings its own, e.g. ``solver.gears.scene.GEAR_TRAIN_FIELDS``)."""
    if fields is None:
        fields = SCENE_FIELDS.get(str(doc.get("kind")), {}) if isinstance(doc, Mapping) else {}
    found: list[str] = []
    for pattern, known in fields.items():
        for where, body in _bodies(doc, pattern):
            found += _unknown_here(known, body, where)
    return found


def _bodies(doc: Mapping[str, Any], pattern: str) -> list[tuple[str, Mapping[str, Any]]]:
    """The objects of ``doc`` at ``pattern`` (e.g. ``moving_points[].path``), with their paths."""
    level: list[tuple[str, Any]] = [("", doc)]
    for part in pattern.split(".") if pattern else []:
        name, star = part.removesuffix("[]"), part.endswith("[]")
        deeper: list[tuple[str, Any]] = []
        for where, body in level:
            if name == "*":
                if isinstance(body, Mapping):
                    deeper += [(f"{where}.{k}", v) for k, v in body.items()]
                continue
            value = body.get(name) if isinstance(body, Mapping) else None
            path = f"{where}.{name}" if where else name
            if star:
                if isinstance(value, list):
                    deeper += [(f"{path}[{i}]", item) for i, item in enumerate(value)]
            elif value is not None:
                deeper.append((path, value))
        level = deeper
    return [(where, body) for where, body in level if isinstance(body, Mapping)]

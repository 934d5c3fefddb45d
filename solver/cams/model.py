"""What a cam mechanism is: the scene of ``"kind": "cam"`` (docs/CAMS.md), parsed and checked.

A disc cam of base radius R_b turns at omega (rad/s, counter-clockwise positive); a follower
(translating with an offset, or oscillating about a pivot) touches it with a knife edge, a
roller or a flat face; its lift over one revolution is a list of rise, dwell and return
segments that start at cam angle 0 and last 360 degrees in all. Every refusal is an
``InvalidScene`` that states the numbers.
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from typing import Any, Literal, cast, get_args

from solver.cams.laws import LAW_NAMES, LawName
from solver.errors import InvalidScene, LimitExceeded

MAX_SEGMENTS = 64
MAX_LENGTH = 1e3  # m: a cam larger than a kilometre is a typo
MAX_OMEGA = 1e6  # rad/s
FULL_TURN_DEG = 360.0
TURN_TOLERANCE_DEG = 1e-9  # the durations' sum may differ from 360 deg by rounding only
LEVEL_TOLERANCE = 1e-12  # relative to the largest lift: rises and returns must cancel

Motion = Literal["translating", "oscillating"]
Contact = Literal["knife", "roller", "flat"]
SegmentType = Literal["rise", "dwell", "return"]
MOTIONS: tuple[Motion, ...] = get_args(Motion)
CONTACTS: tuple[Contact, ...] = get_args(Contact)
SEGMENT_TYPES: tuple[SegmentType, ...] = get_args(SegmentType)


@dataclass(frozen=True)
class Follower:
    """The follower: ``motion`` and ``contact``; a roller's radius (0 otherwise); a translating
    follower's ``offset`` e (its axis is the line x = e, the follower moving along +y); an
    oscillating follower's ``pivot`` [x, y] and ``arm_length`` (0 for a flat face, whose face
    passes through the pivot)."""

    motion: Motion
    contact: Contact
    roller_radius: float = 0.0
    offset: float = 0.0
    pivot: tuple[float, float] = (0.0, 0.0)
    arm_length: float = 0.0


@dataclass(frozen=True)
class Segment:
    """One part of the revolution: a ``rise`` or ``return`` by ``lift`` (m, or rad for an
    oscillating follower) along ``law``, or a ``dwell``; it starts at ``start`` (rad) at the
    follower's ``level`` (the lift reached so far) and lasts ``duration`` (rad)."""

    type: SegmentType
    law: LawName | None
    lift: float
    duration_deg: float
    start: float
    duration: float
    level: float

    def describe(self, index: int) -> str:
        """``segments[0] (rise, cycloidal)``: the segment as a warning names it."""
        what = self.type if self.law is None else f"{self.type}, {self.law}"
        return f"segments[{index}] ({what})"


@dataclass(frozen=True)
class CamScene:
    """A cam, its follower and the follower's lift over one revolution (see the module)."""

    base_radius: float
    omega: float
    follower: Follower
    segments: tuple[Segment, ...]
    title: str = ""

    @property
    def prime_radius(self) -> float:
        """R_p = R_b + r: the prime circle, the pitch curve's smallest radius (R_b for a knife)."""
        return self.base_radius + self.follower.roller_radius

    @property
    def rest_angle(self) -> float:
        """beta_0, an oscillating follower's angle at the pivot between the line to the cam
        centre and the arm (the face) at zero lift: the arm's end on the prime circle,
        cos beta_0 = (d^2 + l^2 - R_p^2) / (2 d l), or the face tangent to the base circle,
        sin beta_0 = R_b / d (d the pivot's distance from the cam centre). 0 when translating."""
        f = self.follower
        d = math.hypot(*f.pivot)
        if f.motion == "translating":
            return 0.0
        if f.contact == "flat":
            return math.asin(self.base_radius / d)
        arm, rp = f.arm_length, self.prime_radius
        return math.acos((d * d + arm * arm - rp * rp) / (2.0 * d * arm))

    @property
    def response_entries(self) -> tuple[int, str]:
        """A sweep's values per sample (for the server's budget): the cam angle, s, v, a, j, the
        pressure angle, the radii of curvature, and the profile and contact point [x, y]."""
        radii = 2 if self.follower.contact == "roller" else 1
        return 1 + 4 + 1 + radii + 2 + 2, "values per sample"


def _where(path: str, message: str) -> InvalidScene:
    return InvalidScene(f"{path}: {message}")


def _mapping(value: Any, path: str) -> Mapping[str, Any]:
    if not isinstance(value, Mapping):
        raise _where(path, f"expected an object, got {value!r}")
    return value


def _number(value: Any, path: str, limit: float) -> float:
    if isinstance(value, bool) or not isinstance(value, int | float):
        raise _where(path, f"expected a number, got {value!r}")
    number = float(value) if abs(value) < 1e308 else math.inf
    if not math.isfinite(number):
        raise _where(path, "must be a finite number")
    if abs(number) > limit:
        raise _where(path, f"|{number:g}| exceeds the limit {limit:g}")
    return number


def _positive(body: Mapping[str, Any], key: str, path: str, limit: float) -> float:
    if key not in body:
        raise _where(f"{path}.{key}" if path else key, "is required")
    number = _number(body[key], f"{path}.{key}" if path else key, limit)
    if number <= 0.0:
        raise _where(f"{path}.{key}" if path else key, f"must be positive, got {number:g}")
    return number


def _choice(body: Mapping[str, Any], key: str, path: str, choices: tuple[str, ...]) -> str:
    value = body.get(key)
    if value not in choices:
        raise _where(f"{path}.{key}", f"expected one of {', '.join(choices)}, got {value!r}")
    return cast(str, value)


def _refuse(body: Mapping[str, Any], keys: Sequence[str], path: str, why: str) -> None:
    for key in keys:
        if key in body:
            raise _where(f"{path}.{key}", why)


def _parse_follower(doc: Mapping[str, Any], base_radius: float) -> Follower:
    body = _mapping(doc.get("follower"), "follower")
    motion = cast(Motion, _choice(body, "motion", "follower", MOTIONS))
    contact = cast(Contact, _choice(body, "contact", "follower", CONTACTS))
    roller = 0.0
    if contact == "roller":
        roller = _positive(body, "roller_radius", "follower", MAX_LENGTH)
    else:
        _refuse(body, ["roller_radius"], "follower", f"a {contact} follower has no roller")
    prime = base_radius + roller
    if motion == "translating":
        _refuse(body, ["pivot", "arm_length"], "follower", "a translating follower has no arm")
        offset = _number(body.get("offset", 0.0), "follower.offset", MAX_LENGTH)
        if contact != "flat" and abs(offset) >= prime:
            circle = "R_b + r" if contact == "roller" else "R_b"
            raise _where(
                "follower.offset",
                f"|e| = {abs(offset):g} m is not less than the prime circle radius {circle} = "
                f"{prime:g} m: the follower's axis misses the cam",
            )
        return Follower(motion, contact, roller, offset)
    _refuse(body, ["offset"], "follower", "an oscillating follower has a pivot, not an offset")
    raw = body.get("pivot")
    if not isinstance(raw, Sequence) or isinstance(raw, str) or len(raw) != 2:
        raise _where("follower.pivot", f"expected a point [x, y], got {raw!r}")
    pivot = (
        _number(raw[0], "follower.pivot[0]", MAX_LENGTH),
        _number(raw[1], "follower.pivot[1]", MAX_LENGTH),
    )
    distance = math.hypot(*pivot)
    if contact == "flat":
        _refuse(body, ["arm_length"], "follower", "a flat face passes through the pivot")
        if distance <= base_radius:
            raise _where(
                "follower.pivot",
                f"the pivot is {distance:g} m from the cam centre, not outside the base circle "
                f"R_b = {base_radius:g} m",
            )
        return Follower(motion, contact, roller, pivot=pivot)
    arm = _positive(body, "arm_length", "follower", MAX_LENGTH)
    if not abs(distance - arm) < prime < distance + arm:
        raise _where(
            "follower",
            f"an arm of {arm:g} m about a pivot {distance:g} m from the cam centre reaches "
            f"radii {abs(distance - arm):g} to {distance + arm:g} m, and not the prime circle "
            f"radius {prime:g} m",
        )
    return Follower(motion, contact, roller, pivot=pivot, arm_length=arm)


def _parse_segments(doc: Mapping[str, Any], unit: str) -> tuple[Segment, ...]:
    raw = doc.get("segments")
    if not isinstance(raw, Sequence) or isinstance(raw, str) or not raw:
        raise _where("segments", "expected a non-empty list of rise, dwell and return segments")
    if len(raw) > MAX_SEGMENTS:
        raise LimitExceeded(f"segments: {len(raw)} entries exceed the limit of {MAX_SEGMENTS}")
    segments: list[Segment] = []
    start_deg, level = 0.0, 0.0
    for i, item in enumerate(raw):
        path = f"segments[{i}]"
        body = _mapping(item, path)
        kind = cast(SegmentType, _choice(body, "type", path, SEGMENT_TYPES))
        duration_deg = _positive(body, "duration_deg", path, FULL_TURN_DEG)
        law: LawName | None = None
        lift = 0.0
        if kind == "dwell":
            _refuse(body, ["law", "lift"], path, "a dwell has no law and no lift")
        else:
            law = cast(LawName, _choice(body, "law", path, LAW_NAMES))
            lift = _positive(body, "lift", path, MAX_LENGTH)
        segments.append(
            Segment(kind, law, lift, duration_deg, math.radians(start_deg),
                    math.radians(duration_deg), level)
        )  # fmt: skip
        start_deg += duration_deg
        level += lift if kind == "rise" else -lift if kind == "return" else 0.0
        if level < -LEVEL_TOLERANCE * max(s.lift for s in segments):
            raise _where(
                path,
                f"the return of {lift:g} {unit} takes the follower to {level:g} {unit}, below "
                "its lowest position (the base circle)",
            )
    if abs(start_deg - FULL_TURN_DEG) > TURN_TOLERANCE_DEG:
        listed = " + ".join(f"{s.duration_deg:g}" for s in segments)
        raise _where(
            "segments",
            f"the durations sum to {listed} = {start_deg:g} deg, not 360 deg: the segments "
            "must fill one revolution",
        )
    rises = sum(s.lift for s in segments if s.type == "rise")
    returns = sum(s.lift for s in segments if s.type == "return")
    if abs(rises - returns) > LEVEL_TOLERANCE * max(rises, returns, 1e-300):
        raise _where(
            "segments",
            f"the rises lift the follower {rises:g} {unit} and the returns lower it "
            f"{returns:g} {unit}: over a revolution they must cancel",
        )
    return tuple(segments)


def parse_cam(doc: Mapping[str, Any]) -> CamScene:
    """Validate a scene document of ``"kind": "cam"`` and build the immutable ``CamScene``."""
    doc = _mapping(doc, "scene")
    if doc.get("kind") != "cam":
        raise _where("kind", f"expected 'cam', got {doc.get('kind')!r}")
    cam = _mapping(doc.get("cam"), "cam")
    base_radius = _positive(cam, "base_radius", "cam", MAX_LENGTH)
    if "omega" not in cam:
        raise _where("cam.omega", "is required")
    omega = _number(cam["omega"], "cam.omega", MAX_OMEGA)
    if omega == 0.0:
        raise _where("cam.omega", "must not be 0: its sign sets the direction the cam turns")
    follower = _parse_follower(doc, base_radius)
    unit = "rad" if follower.motion == "oscillating" else "m"
    segments = _parse_segments(doc, unit)
    title = doc.get("title", "")
    if not isinstance(title, str):
        raise _where("title", f"expected text, got {title!r}")
    scene = CamScene(base_radius, omega, follower, segments, title)
    top = max(s.level + (s.lift if s.type == "rise" else 0.0) for s in segments)
    if follower.motion == "oscillating" and scene.rest_angle + top >= math.pi:
        raise _where(
            "segments",
            f"the arm starts {math.degrees(scene.rest_angle):g} deg from the line to the cam "
            f"centre and a lift of {top:g} rad would swing it to "
            f"{math.degrees(scene.rest_angle + top):g} deg, past that line",
        )
    return scene

"""The scene-v1 family as JSON Schema in the OpenAPI document: a union discriminated on ``kind``.

Published, never used to validate: a request's ``scene`` is read by the solver's parsers
(``solver.model.scene``, ``solver.model.dynamics``, ``solver.kinematics.spatial``,
``solver.cams.model``, ``solver.gears.scene``), which stay the one source of truth and say where a
document is wrong as an ``invalid_scene`` problem. These models describe the same documents for
generated clients and schema-driven tools, with the bounds the parsers enforce (their own
constants), and refuse no document the parsers accept: a field a parser takes as ``null`` is
nullable here, a number is any JSON number (an integer too), and no object forbids keys it does
not name (a key the contract does not know is a warning, ``"strict": true`` an error; the
schema leaves ``additionalProperties`` unset, so a generated client's types still catch a typo).
What a schema cannot say (a name that must be a point of that link, the segments filling a
revolution) the parsers check. ``tests/server/test_scene_schema.py`` validates every bundled
example, preset and exercise scene against it, and checks its fields against the parsers' lists
of known keys (``SCENE_FIELDS``, ``GEAR_TRAIN_FIELDS``).
"""

from __future__ import annotations

from typing import Annotated, Any, Literal

from pydantic import MISSING, BaseModel, Field, TypeAdapter, WithJsonSchema

from solver.cams.laws import LawName
from solver.cams.model import FULL_TURN_DEG, MAX_OMEGA, MAX_SEGMENTS, Contact, Motion, SegmentType
from solver.cams.model import MAX_LENGTH as MAX_CAM_LENGTH
from solver.gears.scene import MAX_MEMBERS, MAX_MODULE, MAX_SPEED, MAX_TEETH
from solver.kinematics import spatial
from solver.model import dynamics, laws
from solver.model.scene import (
    MAX_COORDINATE,
    MAX_FRICTION_COEFFICIENT,
    MAX_JOINTS,
    MAX_LINKS,
    MAX_MOVING_POINTS,
    MAX_NAME_LENGTH,
    MAX_POINTS,
    MAX_RATE,
    MAX_TIME,
)

REF = "#/components/schemas/{model}"
MAX_ANGLE_DEG = 1e6  # a driver's drawn angle_deg, as solver.model.scene checks it
MAX_EXPRESSION_NUMBER = 1e12  # a load given as a number, as solver.model.dynamics checks it


Name = Annotated[str, Field(min_length=1, max_length=MAX_NAME_LENGTH)]
Coordinate = Annotated[float, Field(ge=-MAX_COORDINATE, le=MAX_COORDINATE, description="m")]
Vector = Annotated[list[Coordinate], Field(min_length=2, max_length=2, description="[x, y] (m)")]
Expression = Annotated[
    str,
    Field(
        max_length=laws.MAX_LENGTH,
        description="An expression in t (s): numbers, + - * / ^, parentheses, t, pi, e and "
        + ", ".join(laws.FUNCTIONS),
    ),
]


class Document(BaseModel):
    """A scene part: described, never validated here (the parsers do that). A field typed
    ``X | MISSING`` is optional but not nullable (the parser refuses null there); ``X | None``
    is nullable (the parser takes null as absent)."""


# --- linkage -------------------------------------------------------------------------------------


class LinkageLink(Document):
    """A rigid link: the names of the points attached to it."""

    points: list[Name] = Field(min_length=1, max_length=MAX_POINTS)
    ground: bool = Field(False, description="exactly one link of the scene is the ground")


class JointFriction(Document):
    """Dry friction (dynamics-v1): coefficient mu at a slider or prismatic joint; mu and the pin
    radius (the friction circle mu r) at a revolute joint."""

    coefficient: float = Field(ge=0, le=MAX_FRICTION_COEFFICIENT)
    pin_radius: float | MISSING = Field(
        MISSING, gt=0, le=MAX_COORDINATE, description="m; a revolute joint only, and required there"
    )


class LinkageJoint(Document):
    """A joint at ``point`` between two links; slider and prismatic: ``links = [guide,
    follower]`` with the slot's direction ``axis``."""

    type: Literal["revolute", "slider", "prismatic"]
    point: Name
    links: list[Name] = Field(min_length=2, max_length=2)
    axis: list[Coordinate] | None = Field(
        None,
        min_length=2,
        max_length=2,
        description="slider and prismatic (required there): the slot's direction [x, y] at the "
        "drawn pose, not zero",
    )
    friction: JointFriction | MISSING = Field(MISSING)


class LinkageDriver(Document):
    """A driven link turning about its revolute joint with the ground: constant omega and alpha
    (from the drawn pose, or from angle_deg), or an angle law."""

    link: Name
    omega: float = Field(0.0, ge=-MAX_RATE, le=MAX_RATE, description="rad/s")
    alpha: float = Field(0.0, ge=-MAX_RATE, le=MAX_RATE, description="rad/s^2")
    angle_deg: float | None = Field(
        None,
        ge=-MAX_ANGLE_DEG,
        le=MAX_ANGLE_DEG,
        description="the link's absolute angle (deg); default: as drawn",
    )
    angle_law: Expression | None = Field(
        None, description="rad turned from the drawn pose, in t; not with omega, alpha, angle_deg"
    )


class ArcPath(Document):
    """An arc about ``center`` from ``start`` (points of the carrying link)."""

    type: Literal["arc"]
    center: Name
    start: Name
    direction: Literal["cw", "ccw"] = "ccw"
    sweep_deg: float = Field(360.0, gt=0, le=360, description="360: a whole circle")


class LinePath(Document):
    """A straight line from ``start`` through ``through`` (points of the carrying link)."""

    type: Literal["line"]
    start: Name
    through: Name


class MovingPoint(Document):
    """A point moving along a path fixed in ``link``, at arc length s_law(t) (m)."""

    name: Name
    link: Name
    path: Annotated[ArcPath | LinePath, Field(discriminator="type")]
    s_law: Expression


class BodyMass(Document):
    """A link's mass (dynamics-v1): a uniform bar between two of its points, or a centre of mass
    and an inertia about it."""

    mass: float = Field(ge=0, le=dynamics.MAX_MASS, description="kg")
    bar: list[Name] | MISSING = Field(MISSING, min_length=2, max_length=2, description="[P, Q]")
    center: list[Annotated[float, Field(ge=-1e6, le=1e6)]] | MISSING = Field(
        MISSING, min_length=2, max_length=2, description="m, with inertia"
    )
    inertia: float = Field(0.0, ge=0, le=dynamics.MAX_INERTIA, description="kg m^2 about center")


class PointMass(Document):
    name: Name | MISSING = Field(MISSING, description="default m_<point>")
    link: Name
    point: Name
    mass: float = Field(ge=0, le=dynamics.MAX_MASS, description="kg")


StateExpression = Annotated[
    str | Annotated[float, Field(ge=-MAX_EXPRESSION_NUMBER, le=MAX_EXPRESSION_NUMBER)],
    Field(description="a number, or an expression in the state (t, link angles and rates)"),
]


class Force(Document):
    name: Name | MISSING = Field(MISSING, description="default F1, F2, ...")
    link: Name
    point: Name
    magnitude: StateExpression = Field(description="N")
    direction_deg: float = Field(0.0, ge=-dynamics.MAX_DIRECTION_DEG, le=dynamics.MAX_DIRECTION_DEG)
    relative_to: Literal["world", "link"] = "world"


class Torque(Document):
    name: Name | MISSING = Field(MISSING, description="default M1, M2, ...")
    link: Name
    moment: StateExpression = Field(description="N m, counter-clockwise positive")


class LinkageScene(Document):
    """A planar linkage drawn in one pose (scene-v1), with optional time laws (moving points,
    driver angle laws) and dynamics (dynamics-v1: masses, loads, gravity)."""

    kind: Literal["linkage"]
    title: str = ""
    points: dict[Name, Vector] = Field(
        min_length=1, max_length=MAX_POINTS, description="name -> [x, y] (m) at the drawn pose"
    )
    links: dict[Name, LinkageLink] = Field(max_length=MAX_LINKS)
    joints: list[LinkageJoint] = Field(max_length=MAX_JOINTS)
    drivers: list[LinkageDriver] = Field(
        [], max_length=MAX_LINKS, description="as many as the degrees of freedom"
    )
    moving_points: list[MovingPoint] = Field([], max_length=MAX_MOVING_POINTS)
    time: float = Field(0.0, ge=-MAX_TIME, le=MAX_TIME, description="s, the instant analysed")
    masses: dict[Name, BodyMass] | MISSING = Field(MISSING, description="by link name")
    point_masses: list[PointMass] | MISSING = Field(MISSING, max_length=dynamics.MAX_LOADS)
    gravity: list[Annotated[float, Field(ge=-dynamics.MAX_GRAVITY, le=dynamics.MAX_GRAVITY)]] = (
        Field([0.0, 0.0], min_length=2, max_length=2, description="m/s^2")
    )
    forces: list[Force] | MISSING = Field(MISSING, max_length=dynamics.MAX_LOADS)
    torques: list[Torque] | MISSING = Field(MISSING, max_length=dynamics.MAX_LOADS)


# --- spatial chain -------------------------------------------------------------------------------

Spatial = Annotated[
    float,
    Field(
        ge=-spatial.MAX_MAGNITUDE,
        le=spatial.MAX_MAGNITUDE,
        description="m, rad/s, m/s or their rates",
    ),
]
Vector3 = Annotated[list[Spatial], Field(min_length=3, max_length=3, description="[x, y, z]")]


class SpatialJoint(Document):
    """A joint of a serial chain, at the pose t = 0; each joint names the body after it."""

    name: str = Field(min_length=1, description="the body it carries; 'ground' is reserved")
    type: Literal["revolute", "prismatic"]
    origin: Vector3
    axis: Vector3 = Field(description="not zero; normalised by the server")
    rate: Spatial = Field(description="rad/s or m/s")
    rate_dot: Spatial = Field(0.0, description="rad/s^2 or m/s^2")


class SpatialPoint(Document):
    body: str = Field(description="'ground' or a joint's name")
    position: Vector3


class SpatialChainScene(Document):
    """A spatial serial chain of revolute and prismatic joints (scene-v1)."""

    kind: Literal["spatial_chain"]
    title: str = ""
    joints: list[SpatialJoint] = Field(min_length=1, max_length=spatial.MAX_JOINTS)
    points: dict[str, SpatialPoint] = Field({}, max_length=spatial.MAX_POINTS)


# --- cam -----------------------------------------------------------------------------------------

CamLength = Annotated[float, Field(gt=0, le=MAX_CAM_LENGTH, description="m")]


class Cam(Document):
    base_radius: CamLength
    omega: float = Field(
        ge=-MAX_OMEGA, le=MAX_OMEGA, description="rad/s, not 0: its sign sets the direction"
    )


class CamFollower(Document):
    """Translating (offset) or oscillating (pivot, arm_length); knife, roller or flat face."""

    motion: Motion
    contact: Contact
    roller_radius: CamLength | MISSING = Field(MISSING, description="m; a roller (required there)")
    offset: float = Field(0.0, ge=-MAX_CAM_LENGTH, le=MAX_CAM_LENGTH, description="m, translating")
    pivot: list[Annotated[float, Field(ge=-MAX_CAM_LENGTH, le=MAX_CAM_LENGTH)]] | MISSING = Field(
        MISSING, min_length=2, max_length=2, description="m, oscillating (required there)"
    )
    arm_length: CamLength | MISSING = Field(
        MISSING, description="m; an oscillating knife or roller"
    )


class CamSegment(Document):
    """A rise, dwell or return over duration_deg of cam angle; the segments fill 360 deg."""

    type: SegmentType
    law: LawName | MISSING = Field(MISSING, description="a rise or return (required there)")
    lift: CamLength | MISSING = Field(MISSING, description="m (rad: oscillating); a rise or return")
    duration_deg: float = Field(gt=0, le=FULL_TURN_DEG)


class CamScene(Document):
    """A disc cam and its follower (docs/CAMS.md)."""

    kind: Literal["cam"]
    title: str = ""
    cam: Cam
    follower: CamFollower
    segments: list[CamSegment] = Field(min_length=1, max_length=MAX_SEGMENTS)


# --- gear train ----------------------------------------------------------------------------------


class Gear(Document):
    teeth: int = Field(ge=1, le=MAX_TEETH)
    internal: bool = Field(False, description="an annulus (internal teeth)")


class GearTrainScene(Document):
    """A gear train: gears, carriers, their shafts and meshes, the inputs' speeds
    (docs/GEARS.md)."""

    kind: Literal["gear_train"]
    title: Any = Field(None, description="text (anything else is ignored)")
    gears: dict[Name, Gear] = Field(min_length=1, max_length=MAX_MEMBERS)
    carriers: list[str] = Field([], max_length=MAX_MEMBERS)
    mounts: dict[str, str] = Field({}, description="gear -> the carrier holding its axis")
    shafts: list[list[str]] = Field([], description="members turning together")
    meshes: list[Annotated[list[str], Field(min_length=2, max_length=2)]]
    inputs: dict[str, Annotated[float, Field(ge=-MAX_SPEED, le=MAX_SPEED)]] = Field(
        description="member -> angular velocity (rad/s)"
    )
    module: float | None = Field(None, gt=0, le=MAX_MODULE, description="m; places the gears")


Scene = Annotated[
    LinkageScene | SpatialChainScene | CamScene | GearTrainScene, Field(discriminator="kind")
]
KINDS: dict[str, type[Document]] = {
    "linkage": LinkageScene,
    "spatial_chain": SpatialChainScene,
    "cam": CamScene,
    "gear_train": GearTrainScene,
}


def components() -> dict[str, Any]:
    """The scene's schemas for ``components.schemas``: ``Scene`` (the union) and its parts."""
    schema = TypeAdapter(Scene).json_schema(ref_template=REF)
    parts: dict[str, Any] = schema.pop("$defs")
    schema["description"] = (
        "A scene-v1 document, by kind: 'linkage' (with dynamics-v1), 'spatial_chain', 'cam' "
        "(docs/CAMS.md), 'gear_train' (docs/GEARS.md). Keys the contract does not know are "
        "warnings ('strict': true makes them invalid_scene)."
    )
    return {"Scene": schema, **parts}


def scene_field(model: str = "Scene") -> Any:
    """A request's or response's ``scene``: a JSON object at run time (the parsers read it), the
    typed ``model`` in the OpenAPI document (an ``allOf`` of its one reference for pydantic, which
    resolves a bare reference; ``plain_references`` makes it the reference)."""
    return Annotated[dict[str, Any], WithJsonSchema({"allOf": [{"$ref": REF.format(model=model)}]})]


SceneObject = scene_field()
LinkageSceneObject = scene_field("LinkageScene")
FIELD_REFERENCES = [[{"$ref": REF.format(model=model)}] for model in ("Scene", "LinkageScene")]


def plain_references(value: Any) -> Any:
    """``value`` (an OpenAPI document, changed in place) with every ``{"allOf": [{"$ref": R}],
    ...}`` of a scene made ``{"$ref": R, ...}``: a generated TypeScript client reads an ``allOf``
    of a discriminated union as a subtype of it, the bare reference as the union itself."""
    if isinstance(value, dict):
        if value.get("allOf") in FIELD_REFERENCES:
            value["$ref"] = value.pop("allOf")[0]["$ref"]
        for item in value.values():
            plain_references(item)
    elif isinstance(value, list):
        for item in value:
            plain_references(item)
    return value

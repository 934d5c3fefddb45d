"""Request models at the edge (one per endpoint and direction).

The scene itself is validated by the solver's own parsers (``solver.model.scene``,
``solver.kinematics.spatial``), which know the contract in full and say where a document is wrong;
here it is an object with the spec's examples attached for the OpenAPI page.
"""

from __future__ import annotations

import json
from enum import StrEnum
from pathlib import Path
from typing import Annotated, Any, Literal

from pydantic import BaseModel, ConfigDict, Field
from pydantic.fields import FieldInfo

import solver
from server import scene_schema
from server.scene_schema import LinkageSceneObject, SceneObject
from solver.analysis.sweeps import MAX_SAMPLES

EXAMPLES = Path(__file__).parent / "examples"


def _example(name: str) -> dict[str, Any]:
    data: dict[str, Any] = json.loads((EXAMPLES / f"{name}.json").read_text())
    return data


Quantity = solver.Quantity  # declared once, in solver.model.quantities
InstantQuantity = solver.InstantQuantity  # /analyze's: the quantities and "polygons"


class Strict(BaseModel):
    model_config = ConfigDict(extra="forbid", allow_inf_nan=False, strict=True)


STRICT: bool = Field(
    False,
    description="true: a scene key the contract does not know is an invalid_scene error "
    "instead of a warning in the response's 'warnings'.",
)


NewtonTolerance = Annotated[
    float | None,
    Field(
        description="Newton-Raphson tolerance for linkages the closed-form dyads cannot solve "
        "(triads, some six-bars): the loop-closure residual relative to the scene size, between "
        "1e-15 and 1e-6 (default 1e-13). Looser is faster and less accurate; see "
        "docs/BENCHMARKS.md. Reported in diagnostics."
    ),
]


Statics = Annotated[
    bool,
    Field(
        description="dynamics-v1 (issue 27): with the quantity 'forces', the static force "
        "analysis: the masses count only through their weight (no inertia force), the fields "
        "as with dynamics; with one driver also each load's mechanical_advantage. A scene's "
        "joints may carry friction: {'coefficient': mu} at a slider or prismatic joint, "
        "{'coefficient': mu, 'pin_radius': r} at a revolute joint (0 <= mu <= 10, r > 0 m); "
        "then drivers[i].torque is with friction and drivers[i].torque_frictionless without. "
        "docs/DYNAMICS.md",
    ),
]


class AnalyzeRequest(Strict):
    scene: SceneObject = Field(
        description="A scene-v1 document: kind 'linkage', 'spatial_chain', 'cam' (docs/CAMS.md) "
        "or 'gear_train' (docs/GEARS.md).",
        examples=[
            _example("S000-T1"),
            _example("S002-spatial-arm"),
            _example("cams/cam-roller-translating"),
            _example("G001-planetary"),
        ],
    )
    quantities: list[InstantQuantity] | None = Field(
        None,
        description="What to compute (default: all). The server computes only these. A "
        "gear_train answers its speeds whatever is asked. 'polygons' (an extension, a linkage "
        "only): the velocity and acceleration polygons' segments, as /solution's 'polygons'.",
    )
    strict: bool = STRICT
    tolerance: NewtonTolerance = None
    angle_deg: float | None = Field(
        None,
        description="A cam scene only: the cam angle (deg, turned in the cam's direction of "
        "rotation from its angle 0; default 0). docs/CAMS.md",
    )
    input_torque: dict[str, float] | None = Field(
        None,
        description="A gear_train: the torque (N m) the world applies to an input, e.g. "
        '{"sun": 12.0}; the response then carries every member\'s torque and power (ideal '
        "gears, from the balances of torque and power).",
    )
    statics: Statics = False


class SweepRequest(Strict):
    scene: SceneObject = Field(
        description="A scene-v1 document: a 'linkage' or a 'cam', or a 'spatial_chain' or "
        "'gear_train' with time_range.",
        examples=[_example("S000-T1"), _example("cams/cam-roller-translating")],
    )
    samples: int = Field(
        360,
        description="Samples over the revolution (or feasible range, or time range); outside "
        f"2..{MAX_SAMPLES} (a cam: from 3) the answer is 413 limit_exceeded.",
        json_schema_extra={"minimum": 2, "maximum": MAX_SAMPLES},
    )
    quantities: list[Quantity] | None = Field(
        None,
        description="Default: position only. 'poles': each link's velocity and acceleration "
        "pole per sample (null where none); 'components': the slider joints' (and moving "
        "points') transport, relative and Coriolis parts per sample.",
    )
    time_range: list[float] | None = Field(
        None,
        description="[t0, t1] (s): sweep in time through the scene's time laws instead "
        "of a driver revolution; a spatial_chain's joints move from its pose at t = 0 by "
        "q(t) = rate t + rate_dot t^2 / 2.",
    )
    strict: bool = STRICT
    speed_fluctuation: float | None = Field(
        None,
        gt=0,
        le=1,
        description="dynamics-v1: the coefficient of speed fluctuation k for which the cycle "
        "gives the flywheel inertia energy_fluctuation / (k omega^2).",
    )
    tolerance: NewtonTolerance = None
    statics: Statics = False


class EventSpec(Strict):
    moving_point: str = Field(description="The name of a moving point of the scene.")
    reaches: str = Field(description="The name of the point it should coincide with.")
    occurrence: int = Field(1, description="Which meeting after t = 0 (1 = the first).")
    t_max: float = Field(60.0, description="Search 0 < t <= t_max (s).")


class EventsRequest(Strict):
    scene: SceneObject = Field(
        description="A scene-v1 'linkage' with moving_points.",
        examples=[_example("S003-T2-rotating-carrier")],
    )
    event: EventSpec
    strict: bool = STRICT


# --- responses -----------------------------------------------------------------------------------
# Declared for the OpenAPI document, never used to validate on the hot path: the routes return
# the solver result's body through orjson (server.responses). Every model admits more fields
# than it names (the spec's extensions add quantities), and a contract test checks real
# responses against the published schema.


class Open(BaseModel):
    model_config = ConfigDict(extra="allow")


Vector = list[float]
Vectors = list[Vector]
WARNINGS: list[str] = Field(
    description="What the server noticed but answered anyway: a scene key the contract does "
    "not know (with its path and the nearest valid name), a pose near a change point. Empty "
    'when all is well; "strict": true turns unknown keys into invalid_scene.',
)


class PointValues(Open):
    position: Vector | None = None
    velocity: Vector | None = None
    acceleration: Vector | None = None


class LinkValues(Open):
    angle: float | None = Field(
        None, description="rad, first point towards second; null: one point"
    )
    omega: float | None = None
    alpha: float | None = None
    velocity_pole: Vector | None = Field(None, description="null where the link translates")
    acceleration_pole: Vector | None = None


class JointValues(Open):
    point: str
    type: Literal["revolute", "slider", "prismatic"]
    links: list[str] = Field(description="slider and prismatic: [guide, follower]")
    omega_guide: float | None = None
    transport_velocity: Vector | None = None
    relative_velocity: Vector | None = None
    velocity: Vector | None = None
    transport_acceleration: Vector | None = None
    relative_acceleration: Vector | None = None
    coriolis_acceleration: Vector | None = None
    acceleration: Vector | None = None


class MovingPointValues(Open):
    position: Vector | None = None
    velocity: Vector | None = None
    acceleration: Vector | None = None
    transport_velocity: Vector | None = None
    relative_velocity: Vector | None = None
    transport_acceleration: Vector | None = None
    relative_acceleration: Vector | None = None
    coriolis_acceleration: Vector | None = None


class InstantCentreValues(Open):
    links: list[str]
    position: Vector | None
    direction_at_infinity: Vector | None


class FourBarLoopValues(Open):
    links: dict[str, str]
    lengths: dict[str, float]
    grashof: str
    transmission_angle: float
    transmission_angle_deg: float


class NewtonValues(Open):
    links: list[str]
    converged: bool
    iterations: int
    residual_norm: float
    tolerance: float


class DiagnosticsValues(Open):
    condition_number: float | None
    position_method: str
    newton: list[NewtonValues]
    driver_angles_deg: dict[str, float]
    position_residual: float = 0.0  # m: |Phi| of the polished pose (0 at the drawn pose)


class BodyValues(Open):
    omega: Vector | None = None
    alpha: Vector | None = None


class SpatialPointValues(PointValues):
    acceleration_terms: dict[str, Vector] | None = None


ANSWER_KIND = (
    "what the answer is (the discriminator of /analyze's and /sweep's answers): the scene's "
    "kind, and 'linkage_time' for a linkage swept over a time_range (arrays over time rather "
    "than over driver_angle)"
)


class SegmentValues(Open):
    """One image segment B -> P of a link: v_P - v_B = velocity, a_P - a_B = tangential + normal."""

    link: str
    base: str
    point: str
    velocity: Vector = Field(description="omega x r_BP")
    tangential: Vector = Field(description="alpha x r_BP")
    normal: Vector = Field(description="-omega^2 r_BP, towards the base point")


class PolygonValues(Open):
    segments: list[SegmentValues] = Field(description="In the vector method's order")
    sliding: list[list[str | int]] = Field(
        description="Paths in results of the joints and moving points with a Coriolis part "
        '(["joints", 0], ["moving_points", "M"]), in the order the solution takes them up'
    )


class AnalyzeResponse(Open):
    """One instant. A linkage has points, links, four_bar_loops and diagnostics (joints,
    moving_points, instant_centres where asked or present); a spatial chain bodies and points."""

    kind: Literal["linkage", "spatial_chain"] = Field(description=ANSWER_KIND)
    points: dict[str, SpatialPointValues]
    links: dict[str, LinkValues] | None = None
    joints: list[JointValues] | None = None
    moving_points: dict[str, MovingPointValues] | None = None
    instant_centres: list[InstantCentreValues] | None = None
    four_bar_loops: list[FourBarLoopValues] | None = None
    diagnostics: DiagnosticsValues | None = None
    bodies: dict[str, BodyValues] | None = None
    warnings: list[str] = WARNINGS
    mechanical_advantage: dict[str, float | None] | None = Field(
        None,
        description="statics, one driver: each named load over the driver torque that holds it "
        "alone, omega_driver / v_load (a moment: 1; a force: 1/m); null at a toggle",
    )
    self_locking: str | None = Field(
        None, description="with friction: null, or why no driving torque moves the mechanism"
    )
    polygons: PolygonValues | None = Field(
        None,
        description="with the quantity 'polygons' (an extension): a linkage's velocity and "
        "acceleration polygons, segment by segment, as /solution's 'polygons'",
    )


class SweepPointValues(Open):
    position: Vectors | None = None
    velocity: Vectors | None = None
    acceleration: Vectors | None = None


class SweepLinkValues(Open):
    angle: list[float] | None = None
    omega: list[float] | None = None
    alpha: list[float] | None = None
    velocity_pole: list[Vector | None] | None = None
    acceleration_pole: list[Vector | None] | None = None


class SweepJointValues(Open):
    point: str
    type: Literal["revolute", "slider", "prismatic"]
    links: list[str]
    omega_guide: list[float] | None = None
    transport_velocity: Vectors | None = None
    relative_velocity: Vectors | None = None
    velocity: Vectors | None = None
    transport_acceleration: Vectors | None = None
    relative_acceleration: Vectors | None = None
    coriolis_acceleration: Vectors | None = None
    acceleration: Vectors | None = None


class SweepFourBarLoopValues(Open):
    """A four-bar loop over the sweep (with positions): as in /analyze, with the transmission
    angle at every sample."""

    links: dict[str, str] = Field(description="ground, crank, coupler, rocker: the link names")
    lengths: dict[str, float] = Field(description="m, by role")
    grashof: str
    angle_points: list[str] = Field(
        description="B, C, D of the transmission angle BCD: the crank pin, the coupler-rocker "
        "joint, the rocker's ground pivot"
    )
    transmission_angle: list[float] = Field(description="rad, 0..pi, per sample")
    transmission_angle_deg: list[float] = Field(description="deg, per sample")


class ExtremePosition(Open):
    driver_angle: float = Field(description="rad, the driver link's absolute angle")
    driver_angle_deg: float
    displacement: float = Field(description="m, s at the extreme position")


class QuickReturnValues(Open):
    """A ram's two extreme positions over a revolution (ds/dt = 0, found to rounding) and the
    driver's turn over each stroke; the time ratio at constant driver speed."""

    time_ratio: float = Field(description="slow_stroke / fast_stroke, (180 + a) / (180 - a)")
    extreme_positions: list[ExtremePosition] = Field(
        description="in the order the driver reaches them"
    )
    slow_stroke: float = Field(description="rad of driver turn over the slower stroke")
    slow_stroke_deg: float
    fast_stroke: float = Field(description="rad of driver turn over the faster (return) stroke")
    fast_stroke_deg: float


class SweepSliderValues(Open):
    """A slider or prismatic joint's point along its guide, per sample."""

    point: str
    type: Literal["slider", "prismatic"]
    links: list[str] = Field(description="guide, follower")
    axis: Vectors | None = Field(
        None, description="the guide's unit direction (the drawn axis turned with the guide)"
    )
    displacement: list[float] | None = Field(
        None,
        description="m, s = (r_P - r_Q) . axis from the guide's point Q drawn at P (a fixed "
        "guide: from the drawn position)",
    )
    sliding_velocity: list[float] | None = Field(
        None, description="m/s, ds/dt (a fixed guide: v . axis)"
    )
    sliding_acceleration: list[float] | None = Field(
        None, description="m/s^2, d2s/dt2 (a fixed guide: a . axis)"
    )
    quick_return: QuickReturnValues | None = Field(
        None,
        description="a revolution's slider on a fixed guide (with positions): null unless it "
        "reverses exactly twice a full revolution",
    )


class SweepMovingPointValues(Open):
    position: Vectors | None = None
    velocity: Vectors | None = None
    acceleration: Vectors | None = None


class SelfLockingValues(Open):
    driver_angle_deg: float = Field(description="the first pose of the revolution that locks")
    reason: str = Field(description="the joints whose friction locks it, and why, in words")


class CycleValues(Open):
    """A revolution's figures (dynamics-v1); with friction at some joint also its efficiency
    and self-locking (issue 27)."""

    period: float
    mean_torque: float | None
    mean_power: float | None
    work: dict[str, float]
    energy_fluctuation: float | None
    flywheel_inertia: float | None
    speed_fluctuation: float | None
    efficiency: float | None = Field(
        None,
        description="with friction: the frictionless mean input power over that with friction "
        "(a driven machine; null where the first is not positive or the mechanism locks)",
    )
    self_locking: SelfLockingValues | None = Field(
        None, description="with friction: null, or the first pose that locks and why"
    )


class SweepResponse(Open):
    """A revolution of the first driver, or its feasible range (arrays over driver_angle)."""

    kind: Literal["linkage"] = Field(description=ANSWER_KIND)
    driver: str
    driver_angle: list[float] = Field(description="rad, the driver link's absolute angle")
    samples: int
    points: dict[str, SweepPointValues]
    links: dict[str, SweepLinkValues]
    joints: list[SweepJointValues] | None = None
    feasible: bool = Field(description="false: the driver rocks between the two limits")
    limits: list[float] = Field(description="rad: the limit positions, empty if feasible")
    singular_samples: list[int]
    warnings: list[str] = WARNINGS
    four_bar_loops: list[SweepFourBarLoopValues] | None = Field(
        None, description="with positions: each four-bar loop's transmission angle per sample"
    )
    sliders: list[SweepSliderValues] | None = Field(
        None, description="each slider's travel along its guide; a ram's quick-return ratio"
    )
    mechanical_advantage: dict[str, list[float | None]] | None = Field(
        None, description="statics, one driver: each named load's mechanical advantage per sample"
    )
    cycle: CycleValues | None = Field(
        None, description="with forces, one driver turning fully at constant omega"
    )


class TimeSweepResponse(Open):
    """A linkage over a time range through its laws (arrays over time)."""

    kind: Literal["linkage_time"] = Field(description=ANSWER_KIND)
    time: list[float]
    driver_angle: list[float]
    samples: int
    points: dict[str, SweepPointValues]
    links: dict[str, SweepLinkValues]
    joints: list[SweepJointValues] | None = None
    moving_points: dict[str, SweepMovingPointValues]
    feasible: bool
    limits: list[float]
    warnings: list[str] = WARNINGS
    four_bar_loops: list[SweepFourBarLoopValues] | None = None
    sliders: list[SweepSliderValues] | None = None


class SpatialSweepBodyValues(Open):
    omega: Vectors | None = Field(None, description="rad/s, per sample")
    alpha: Vectors | None = Field(None, description="rad/s^2, per sample")


class SpatialSweepPointValues(SweepPointValues):
    acceleration_terms: dict[str, Vectors] | None = None


class SpatialSweepJointValues(Open):
    name: str
    type: Literal["revolute", "prismatic"]
    origin: Vectors | None = Field(None, description="m, the joint origin at each sample")
    axis: Vectors | None = Field(None, description="the unit axis at each sample")
    displacement: list[float] | None = Field(
        None, description="q(t) = rate t + rate_dot t^2 / 2 from the scene's pose (rad or m)"
    )
    rate: list[float] | None = Field(None, description="rate + rate_dot t (rad/s or m/s)")


class SpatialTimeSweepResponse(Open):
    """A spatial chain over a time range: each joint moves from the scene's pose at t = 0 by
    q(t) = rate t + rate_dot t^2 / 2 (arrays over time)."""

    kind: Literal["spatial_chain"] = Field(description=ANSWER_KIND)
    time: list[float]
    samples: int
    bodies: dict[str, SpatialSweepBodyValues]
    points: dict[str, SpatialSweepPointValues]
    joints: list[SpatialSweepJointValues]
    feasible: bool
    limits: list[float]
    warnings: list[str] = WARNINGS


class GearMemberValues(Open):
    """A gear or carrier of a gear train (docs/GEARS.md)."""

    type: Literal["gear", "carrier"]
    omega: float = Field(description="rad/s, absolute, counter-clockwise positive from the front")
    train_value: float | None = Field(
        description="omega / omega of the first input; null where the first input stands still"
    )
    centre: Vector | None = Field(
        description="m, the axis at t = 0 (a planet's with its carrier at angle 0); null "
        "without a module"
    )
    teeth: int | None = None
    internal: bool | None = None
    carrier: str | None = Field(None, description="a gear: the carrier of its axis (null: frame)")
    omega_relative: float | None = Field(
        None, description="a gear: rad/s relative to its carrier (to the frame: its omega)"
    )
    pitch_radius: float | None = Field(None, description="a gear: m, r = m N / 2")
    torque: float | None = Field(
        None,
        description="with input_torque: N m, the torque applied to the member at its hub (by "
        "the world, or by its shaft's other members)",
    )
    power: float | None = Field(None, description="with input_torque: W, torque x omega")


class GearMeshValues(Open):
    gears: list[str] = Field(description="[a, b]")
    carrier: str | None = Field(description="the body holding both axes (null: the frame)")
    internal: bool
    willis_ratio: float = Field(
        description="(omega_b - omega_arm) / (omega_a - omega_arm): -N_a/N_b external, "
        "+N_a/N_b internal"
    )
    pitch_line_speed: float | None = Field(
        description="m/s, r_a |omega_a - omega_arm|; null without a module"
    )


class GearTrainAnalyzeResponse(Open):
    """A gear train at its inputs' speeds (docs/GEARS.md)."""

    kind: Literal["gear_train"] = Field(description=ANSWER_KIND)
    degrees_of_freedom: int
    first_input: str | None
    members: dict[str, GearMemberValues]
    meshes: list[GearMeshValues]
    warnings: list[str] = WARNINGS


class GearSweepMemberValues(Open):
    angle: list[float] = Field(description="rad from t = 0, omega t, per sample")
    centre: Vectors | None = Field(
        None, description="a gear on a carrier, with a module: m, its axis per sample"
    )


class GearTrainSweepResponse(Open):
    """A gear train over a time range (arrays over time)."""

    kind: Literal["gear_train"] = Field(description=ANSWER_KIND)
    time: list[float]
    samples: int
    members: dict[str, GearSweepMemberValues]
    warnings: list[str] = WARNINGS


class EventResponse(Open):
    time: float = Field(description="s")
    position: Vector
    moving_point: str
    reaches: str
    occurrence: int
    warnings: list[str] = WARNINGS


class CamFollowerValues(Open):
    """The follower's motion per time at the cam's omega: m, m/s, m/s^2, m/s^3 (rad, rad/s,
    ... for an oscillating follower); one number at an angle, a list over a sweep."""

    displacement: float | list[float]
    velocity: float | list[float]
    acceleration: float | list[float]
    jerk: float | list[float]


class CamExtreme(Open):
    min: float
    min_at_deg: float = Field(description="cam angle of the minimum")
    max: float
    max_at_deg: float = Field(description="cam angle of the maximum")


class CamDiagnostics(Open):
    extremes: dict[str, CamExtreme] = Field(
        description="displacement, velocity, acceleration, jerk, pressure_angle, "
        "radius_of_curvature (and pitch_radius_of_curvature) over the revolution, on a grid "
        "of grid_samples cam angles"
    )
    base_radius: float
    prime_radius: float = Field(description="m, base radius + roller radius")
    lift_unit: Literal["m", "rad"]
    grid_samples: int


CAM_RADIUS = "m, the cam surface's radius of curvature (positive convex; null at an inflection)"
CAM_PITCH_RADIUS = "m, a roller only: the pitch curve's radius of curvature"
CAM_PRESSURE_ANGLE = "rad, between the common normal and the follower's direction of motion"


class CamSweepResponse(Open):
    """A cam over one revolution (arrays over cam_angle; docs/CAMS.md)."""

    kind: Literal["cam"] = Field(description=ANSWER_KIND)
    samples: int
    cam_angle: list[float] = Field(description="rad turned in the cam's direction, from 0")
    follower: CamFollowerValues
    pressure_angle: list[float] = Field(description=CAM_PRESSURE_ANGLE)
    radius_of_curvature: list[float | None] = Field(description=CAM_RADIUS)
    pitch_radius_of_curvature: list[float | None] | None = Field(None, description=CAM_PITCH_RADIUS)
    profile: Vectors = Field(description="the cam surface [x, y] (m) in the cam's frame at angle 0")
    contact_point: Vectors = Field(description="m, the contact point in the ground per sample")
    diagnostics: CamDiagnostics
    warnings: list[str] = WARNINGS


class CamAnalyzeResponse(Open):
    """A cam at one cam angle (docs/CAMS.md)."""

    kind: Literal["cam"] = Field(description=ANSWER_KIND)
    cam_angle: float = Field(description="rad, angle_deg modulo 360 deg")
    cam_angle_deg: float
    segment: int = Field(description="the index of the segment the angle lies in")
    follower: CamFollowerValues
    pressure_angle: float = Field(description=CAM_PRESSURE_ANGLE)
    radius_of_curvature: float | None = Field(description=CAM_RADIUS)
    pitch_radius_of_curvature: float | None = Field(None, description=CAM_PITCH_RADIUS)
    contact_point: Vector
    profile: Vectors = Field(description="the cam surface at 360 points, cam's frame at angle 0")
    diagnostics: CamDiagnostics
    warnings: list[str] = WARNINGS


AnalyzeAnswer = Annotated[
    AnalyzeResponse | CamAnalyzeResponse | GearTrainAnalyzeResponse, Field(discriminator="kind")
]
SweepAnswer = Annotated[
    SweepResponse
    | TimeSweepResponse
    | SpatialTimeSweepResponse
    | CamSweepResponse
    | GearTrainSweepResponse,
    Field(discriminator="kind"),
]


class ValueModel(Open):
    value: float | list[float]
    unit: str
    display: str
    source: list[str | int] | None


class CheckModel(Open):
    relation: str
    result: str
    operands: list[str]
    factor: float


class StepModel(Open):
    kind: str
    title: str
    latex: str
    text: str
    values: dict[str, ValueModel]
    checks: list[CheckModel]


class MistakeModel(Open):
    kind: str
    title: str
    text: str
    values: dict[str, ValueModel]


class SolutionResponse(Open):
    method: str
    requested_method: str
    digits: int
    steps: list[StepModel]
    mistakes: list[MistakeModel]
    results: AnalyzeAnswer = Field(
        description="The /analyze body of the same scene (a cam's at the same angle_deg)"
    )
    polygons: PolygonValues | None = Field(
        None, description="A linkage's velocity and acceleration polygons, segment by segment"
    )
    warnings: list[str] = WARNINGS


class PresetParameter(Open):
    name: str
    default: float
    unit: str
    description: str
    minimum: float | None
    maximum: float | None
    choices: list[float] | None
    labels: list[str] | None


class PresetInfo(Open):
    name: str
    title: str
    description: str
    parameters: list[PresetParameter]
    scene: SceneObject = Field(
        description="The preset's scene-v1 document at its defaults: what POST "
        "/presets/{name} with {} answers."
    )


class PresetList(Open):
    presets: list[PresetInfo]


class ExerciseTypeInfo(Open):
    name: str
    title: str
    description: str
    difficulties: list[str]
    asks: list[str]


class ExerciseTypeList(Open):
    """GET /exercises/types."""

    types: list[ExerciseTypeInfo]


class AskedQuantity(Open):
    key: str
    label: str
    unit: str
    path: str
    tolerance: float
    symbol: str


class ExerciseStatement(Open):
    text: str
    latex: str
    figure_svg: str


class ExerciseModel(Open):
    """One generated exercise (exercises-v1): its id, statement, scene (or synthesis task),
    asked quantities, key."""

    id: str
    type: str
    difficulty: str
    seed: int
    index: int
    title: str
    statement: ExerciseStatement
    scene: SceneObject | None = Field(
        None, description="The scene the exercise is built on (its paths point into /analyze)."
    )
    task: dict[str, Any] | None = Field(
        None,
        description="Extension: instead of a scene, the synthesis task a synthesis exercise is "
        "built on (its paths point into the /synthesis body of that task).",
    )
    asked: list[AskedQuantity]
    answers: dict[str, float]
    exam: Literal[True] | None = Field(
        None, description="Extension: present (true) on an exam exercise, whose id is opaque."
    )


class ExamAsked(Open):
    key: str
    label: str
    unit: str
    symbol: str
    tolerance: float


class ExamStatementModel(Open):
    """GET /exercises/{id} of an exam exercise: the statement only (no scene, key or solution)."""

    id: str
    exam: Literal[True]
    title: str
    statement: ExerciseStatement
    asked: list[ExamAsked]


class ExerciseList(Open):
    """POST /exercises."""

    exercises: list[ExerciseModel]


class AnswerVerdict(Open):
    key: str
    given: float | None
    expected: float
    verdict: Literal["correct", "incorrect", "missing"]
    relative_error: float | None
    diagnosis: str | None


class CheckResponse(Open):
    """POST /exercises/check."""

    id: str
    score: float
    results: list[AnswerVerdict]


class CounterweightValues(Open):
    link: str
    mass: float
    pivot: str
    distance: float
    offset: float
    position: list[float]


class BalanceResponse(Open):
    """POST /balance (dynamics-v1)."""

    counterweights: list[CounterweightValues]
    center_of_mass: list[float]
    mass: float
    scene: LinkageSceneObject = Field(description="The scene with its counterweights' masses")


class Health(Open):
    """GET /health."""

    status: Literal["ok"]


class ProblemCode(StrEnum):
    """The stable machine-readable codes of every error (scene-v1 "Errors", and the server's)."""

    invalid_scene = "invalid_scene"
    invalid_expression = "invalid_expression"
    not_assemblable = "not_assemblable"
    singular_configuration = "singular_configuration"
    limit_exceeded = "limit_exceeded"
    no_event = "no_event"
    not_found = "not_found"
    forbidden = "forbidden"
    not_configured = "not_configured"
    pdf_unavailable = "pdf_unavailable"
    method_not_allowed = "method_not_allowed"
    unsupported_media_type = "unsupported_media_type"
    internal_error = "internal_error"
    busy = "busy"
    too_many_requests = "too_many_requests"
    request_timeout = "request_timeout"


class Problem(Open):
    """RFC 9457 problem details, with the stable ``code``."""

    type: str
    title: str
    status: int
    detail: str = Field(description="What is wrong, with the numbers that show it")
    code: ProblemCode
    position: int | None = Field(None, description="invalid_expression: the character (0-based)")
    expression: str | None = None
    condition_number: float | None = None


PROBLEM_MEDIA_TYPE = "application/problem+json"
RETRY_AFTER = {
    "Retry-After": {
        "description": "Seconds to wait before trying again",
        "schema": {"type": "integer", "minimum": 0},
    }
}
# What any route can answer: the request too slow to arrive (server.deadlines), too large, not
# answerable, or a defect.
FRONT_PROBLEMS: dict[int | str, dict[str, Any]] = {
    408: {
        "model": Problem,
        "description": "The request's headers and body did not arrive within the server's "
        "request timeout (request_timeout; KINEMATICS_REQUEST_TIMEOUT, default 15 s): the "
        "connection is closed (Connection: close)",
    },
    413: {"model": Problem, "description": "The request is too large (limit_exceeded)"},
    422: {
        "model": Problem,
        "description": "The request cannot be answered: invalid_scene, invalid_expression, "
        "not_assemblable, singular_configuration, limit_exceeded, no_event",
    },
    405: {
        "model": Problem,
        "description": "Another method on this path (method_not_allowed): the Allow header "
        "lists the methods it answers",
        "headers": {
            "Allow": {"description": "The path's methods, e.g. POST", "schema": {"type": "string"}}
        },
    },
    500: {"model": Problem, "description": "An unexpected error (internal_error): a defect"},
}
# What a route that takes a body answers when the body is sent as anything but JSON.
UNSUPPORTED_MEDIA_TYPE = {
    "description": "The body was sent under a Content-Type other than application/json "
    "(unsupported_media_type); a body without a Content-Type is read as JSON",
    "content": {PROBLEM_MEDIA_TYPE: {"schema": {"$ref": "#/components/schemas/Problem"}}},
}
# What a route that runs in the worker pool (server.workers) can answer besides.
PROBLEMS: dict[int | str, dict[str, Any]] = {
    **FRONT_PROBLEMS,
    429: {
        "model": Problem,
        "description": "This client already has its share of slow requests running or waiting "
        "(too_many_requests): see Retry-After",
        "headers": RETRY_AFTER,
    },
    503: {
        "model": Problem,
        "description": "Every worker is busy (busy): see Retry-After. On the exercise routes "
        "also an exam request where no exam secret is set (not_configured), and a PDF export where "
        "the server has no Chromium to print it with (pdf_unavailable)",
        "headers": RETRY_AFTER,
    },
}


def publish(document: dict[str, Any]) -> dict[str, Any]:
    """The OpenAPI document as published: the typed scene's schemas (server.scene_schema) among
    its components, and every error as application/problem+json."""
    found = document.setdefault("components", {}).setdefault("schemas", {})
    for name, schema in scene_schema.components().items():
        if found.setdefault(name, schema) != schema:
            raise ValueError(f"two schemas named {name} in the OpenAPI document")
    exact_integer_bounds(document)
    for path in document.get("paths", {}).values():
        for operation in path.values():
            if "requestBody" in operation:
                operation["responses"].setdefault("415", UNSUPPORTED_MEDIA_TYPE)
    return problems_as_problem_json(scene_schema.plain_references(document))


# An integer field's bound (annotated_types Ge, Le, Gt, Lt) and its JSON Schema keyword.
INTEGER_BOUNDS = {
    "ge": "minimum",
    "le": "maximum",
    "gt": "exclusiveMinimum",
    "lt": "exclusiveMaximum",
}


def _request_models(model: type[BaseModel]) -> list[type[BaseModel]]:
    """``model`` and every model derived from it."""
    return [model, *(m for sub in model.__subclasses__() for m in _request_models(sub))]


def integer_bounds(field: FieldInfo) -> dict[str, int]:
    """The JSON Schema bounds of an integer field, exact: its constraints and the bounds it
    publishes without enforcing them (``json_schema_extra``)."""
    bounds = {
        keyword: getattr(constraint, attribute)
        for constraint in field.metadata
        for attribute, keyword in INTEGER_BOUNDS.items()
        if isinstance(getattr(constraint, attribute, None), int)
    }
    extra = field.json_schema_extra if isinstance(field.json_schema_extra, dict) else {}
    bounds.update(
        (k, v) for k, v in extra.items() if k in INTEGER_BOUNDS.values() and isinstance(v, int)
    )
    return bounds


def exact_integer_bounds(document: dict[str, Any]) -> None:
    """Give the integer fields of the request models their bounds as integers, as the models
    state them: FastAPI writes every bound as a float, so a seed's maximum 2**63 - 1 would be
    published as 9.223372036854776e18, which is 2**63 (a seed the server refuses)."""
    found = document.get("components", {}).get("schemas", {})
    for model in _request_models(Strict):
        published = found.get(model.__name__, {}).get("properties", {})
        for name, field in model.model_fields.items():
            if field.annotation is int and (field.alias or name) in published:
                published[field.alias or name].update(integer_bounds(field))


def problems_as_problem_json(document: dict[str, Any]) -> dict[str, Any]:
    """Declare every 4xx and 5xx response of an OpenAPI document as application/problem+json
    (FastAPI writes a declared model under the route's own media type: JSON, or HTML)."""
    for path in document.get("paths", {}).values():
        for operation in path.values():
            for status, response in operation.get("responses", {}).items():
                content = response.get("content", {})
                if status[:1] in "45" and content:
                    response["content"] = {PROBLEM_MEDIA_TYPE: next(iter(content.values()))}
    return document

"""The solver's public entry points: a scene in (a scene-v1 dict or a parsed scene), a frozen
result out whose ``as_dict()`` is the body of the matching HTTP endpoint.

    import solver
    result = solver.analyze(doc, ["position", "velocity"])
    result["links"]["coupler"]["omega"]

A dict is checked against the contract: a key it does not know (``"angle"`` for ``angle_deg``)
is reported in the result's ``warnings`` (``drivers[0].angle is not a scene field; did you mean
angle_deg?``), or raises ``InvalidScene`` with ``strict=True`` (``strict`` applies where a
document is read: a parsed scene carries no key warnings, a ``ReadScene`` those found on
reading). Errors are the exceptions of ``solver.errors`` (``InvalidScene``, ``NotAssemblable``,
``SingularConfiguration``...).
"""

from __future__ import annotations

import warnings as python_warnings
from collections.abc import Iterable, Mapping, Sequence
from dataclasses import dataclass, replace
from typing import Any

from solver import solutions as worked
from solver.analysis import events, instant, results
from solver.analysis.results import (
    AnalysisResult,
    EventResult,
    SolutionResult,
    SweepResult,
    TimeSweepResult,
)
from solver.analysis.spatial_sweep import sweep_spatial_time
from solver.analysis.sweeps import sweep as sweep_linkage
from solver.analysis.sweeps import sweep_time as sweep_linkage_time
from solver.cams import CamScene, analyze_cam, parse_cam, sweep_cam
from solver.dynamics.body import add_dynamics_results, add_instant_dynamics, add_sweep_dynamics
from solver.errors import InvalidScene
from solver.gears import (
    GEAR_TRAIN_FIELDS,
    GearTrainScene,
    analyze_gear_train,
    parse_gear_train,
    sweep_gear_train,
)
from solver.kinematics.spatial import SpatialChain, analyze_spatial_chain, parse_spatial_chain
from solver.model.quantities import (
    DYNAMIC_QUANTITIES,
    POLYGONS,
    QUANTITIES,
    normalise_quantities,
)
from solver.model.scene import LinkageScene, parse_linkage, unknown_keys
from solver.solutions.polygons import polygons
from solver.solutions.solve import vector_method_steps
from solver.solutions.synthesis import synthesis_steps
from solver.synthesis import SynthesisResult
from solver.synthesis import synthesize as synthesize_task

Scene = LinkageScene | SpatialChain | CamScene | GearTrainScene
# The digits of the vector method's steps that /analyze's polygons follow: the segments are the
# analysis' numbers and the steps are read for their order only, which no digit count changes.
POLYGON_DIGITS = 4


class SceneWarning(UserWarning):
    """A scene document has a key the contract does not know (``parse_scene`` warns with it)."""


@dataclass(frozen=True)
class ReadScene:
    """A parsed scene with the warnings about its document, for a caller that looks at the scene
    (a cost check, say) before asking for a result that must still carry those warnings."""

    scene: Scene
    warnings: tuple[str, ...]


SceneInput = Mapping[str, Any] | LinkageScene | SpatialChain | CamScene | GearTrainScene | ReadScene


def _parse(doc: Mapping[str, Any], strict: bool) -> tuple[Scene, list[str]]:
    """The scene of a document of either kind, and the warnings about its unknown keys."""
    kind = doc.get("kind") if isinstance(doc, Mapping) else None
    scene: Scene
    if kind == "linkage":
        scene = parse_linkage(doc)
    elif kind == "spatial_chain":
        scene = parse_spatial_chain(doc)
    elif kind == "cam":
        scene = parse_cam(doc)
    elif kind == "gear_train":
        scene = parse_gear_train(doc)
    else:
        raise InvalidScene(
            f"kind: expected 'linkage', 'spatial_chain', 'cam' or 'gear_train', got {kind!r}"
        )
    found = unknown_keys(doc, GEAR_TRAIN_FIELDS if kind == "gear_train" else None)
    if strict and found:
        raise InvalidScene("strict: " + "; ".join(found))
    return scene, found


def _scene(scene: SceneInput, strict: bool) -> tuple[Scene, list[str]]:
    if isinstance(scene, ReadScene):
        return scene.scene, list(scene.warnings)
    if isinstance(scene, LinkageScene | SpatialChain | CamScene | GearTrainScene):
        return scene, []
    return _parse(scene, strict)


def _linkage(scene: SceneInput, strict: bool, what: str) -> tuple[LinkageScene, list[str]]:
    parsed, found = _scene(scene, strict)
    if not isinstance(parsed, LinkageScene):
        raise InvalidScene(f"kind: {what} takes a 'linkage' scene")
    return parsed, found


def parse_scene(doc: Mapping[str, Any], *, strict: bool = False) -> Scene:
    """Validate a scene-v1 document of kind ``linkage``, ``spatial_chain``, ``cam``
    (docs/CAMS.md) or ``gear_train`` (docs/GEARS.md) and build the
    immutable scene. Unknown keys are reported with ``SceneWarning`` (``InvalidScene`` when
    ``strict``)."""
    scene, found = _parse(doc, strict)
    for sentence in found:
        python_warnings.warn(sentence, SceneWarning, stacklevel=2)
    return scene


def read_scene(doc: Mapping[str, Any], *, strict: bool = False) -> ReadScene:
    """Parse a document as ``parse_scene`` does, keeping the warnings with the scene (each entry
    point accepts the returned ``ReadScene`` and reports them)."""
    scene, found = _parse(doc, strict)
    return ReadScene(scene, tuple(found))


def analyze(
    scene: SceneInput,
    quantities: Iterable[str] | None = None,
    *,
    strict: bool = False,
    tolerance: float | None = None,
    angle_deg: float | None = None,
    input_torque: Mapping[str, float] | None = None,
    statics: bool = False,
) -> AnalysisResult:
    """One instant (POST /analyze): the linkage at its drivers' angles (drawn, ``angle_deg``, or
    ``angle_law`` at ``time``), the spatial chain, or the cam at cam angle ``angle_deg``
    (default 0; docs/CAMS.md). ``quantities``: any of position, velocity, acceleration, poles,
    components (default: all); only those are computed (a cam answers all its fields); a
    linkage's ``polygons`` adds the polygons' segments as /solution's ``polygons`` gives them.
    ``tolerance``: a Newton group's residual relative to the scene size (1e-15 to 1e-6, default
    1e-13). A gear train answers its speeds whatever the quantities, and with ``input_torque``
    (N m on inputs) every member's torque (docs/GEARS.md). ``statics`` (with ``forces``): the
    static force analysis, the masses counting only through their weight (docs/DYNAMICS.md)."""
    parsed, found = _scene(scene, strict)
    quantities = None if quantities is None else tuple(quantities)
    if POLYGONS in (quantities or ()) and not isinstance(parsed, LinkageScene):
        raise InvalidScene("quantities: polygons are drawn for a planar linkage (kind 'linkage')")
    if isinstance(parsed, GearTrainScene):
        if statics:
            raise InvalidScene("statics: a gear_train's torques are static already (input_torque)")
        return analyze_gear_train(parsed, input_torque, found)
    if input_torque is not None:
        raise InvalidScene("input_torque: a torque on an input is given for a gear_train")
    wanted = normalise_quantities(quantities, instant=True)
    _statics(statics, wanted)
    if isinstance(parsed, CamScene):
        _no_dynamics(wanted)
        body = analyze_cam(parsed, 0.0 if angle_deg is None else angle_deg, found)
        return AnalysisResult(_kind("cam", body))
    if angle_deg is not None:
        raise InvalidScene(
            "angle_deg: the cam angle of a 'cam' scene; a linkage's driver takes "
            "drivers[].angle_deg"
        )
    if isinstance(parsed, LinkageScene):
        if POLYGONS not in wanted:
            result = instant.analyze(parsed, wanted, tolerance)
            body = results.analysis_body(result, found)
        else:  # the polygons follow the vector method's steps, written from the whole analysis
            result = instant.analyze(parsed, wanted - {POLYGONS} | set(QUANTITIES), tolerance)
            steps = vector_method_steps(parsed, result, POLYGON_DIGITS)
            result = replace(result, quantities=wanted - {POLYGONS})  # the body: those asked
            body = results.analysis_body(result, found)
            body[POLYGONS] = polygons(parsed, result, steps)
        body = add_instant_dynamics(body, parsed, result, statics)
        return AnalysisResult(_kind("linkage", body))
    _no_dynamics(wanted)
    body = results.spatial_body(analyze_spatial_chain(parsed), wanted, found)
    return AnalysisResult(_kind("spatial_chain", body))


def sweep(
    scene: SceneInput,
    samples: int = 360,
    quantities: Iterable[str] | None = None,
    *,
    strict: bool = False,
    speed_fluctuation: float | None = None,
    tolerance: float | None = None,
    statics: bool = False,
) -> SweepResult:
    """The linkage over one revolution of its first driver from its start angle, or over its
    feasible range with the limit positions (POST /sweep). Default quantity: position. With
    ``forces``, a revolution at constant speed also gets its ``cycle`` (and the flywheel inertia
    for the coefficient of ``speed_fluctuation``). ``statics`` (with ``forces``): the static
    force analysis over the revolution. A cam: one revolution of its cam angle with every field
    of docs/CAMS.md."""
    _statics(statics, normalise_quantities(quantities))
    read, found = _scene(scene, strict)
    if isinstance(read, CamScene):
        _no_dynamics(normalise_quantities(quantities))
        if speed_fluctuation is not None:
            raise InvalidScene("speed_fluctuation: a cam's sweep has no dynamics")
        return SweepResult(_kind("cam", sweep_cam(read, samples, found)))
    if isinstance(read, GearTrainScene):
        raise InvalidScene("time_range: a gear_train is swept over a time range [t0, t1]")
    parsed, found = _linkage(
        ReadScene(read, tuple(found)),
        strict,
        "a sweep over a revolution (a spatial_chain is swept with a time range)",
    )
    result = sweep_linkage(parsed, samples, quantities, tolerance)
    body = add_sweep_dynamics(results.sweep_body(result, found), result, speed_fluctuation, statics)
    return SweepResult(_kind("linkage", body))


def _kind(kind: str, body: Mapping[str, Any]) -> dict[str, Any]:
    """``body`` with its ``kind`` first: what the answer is, the discriminator of /analyze's and
    /sweep's answers (the scene's kind; a linkage over a time range ``linkage_time``, its arrays
    over time rather than over the driver's angle)."""
    return {"kind": kind, **body}


def _statics(statics: bool, wanted: frozenset[str]) -> None:
    """A static force analysis answers the quantity ``forces``."""
    if statics and "forces" not in wanted:
        raise InvalidScene("statics: a static force analysis asks for the quantity 'forces'")


def _no_dynamics(wanted: frozenset[str]) -> None:
    """Forces and energy (dynamics-v1) are a planar linkage's only: a spatial chain or a cam
    answers its kinematic fields alone."""
    if wanted & set(DYNAMIC_QUANTITIES):
        raise InvalidScene("quantities: forces and energy are defined for planar linkages only")


def sweep_time(
    scene: SceneInput,
    time_range: Sequence[float],
    samples: int = 360,
    quantities: Iterable[str] | None = None,
    *,
    strict: bool = False,
    tolerance: float | None = None,
    statics: bool = False,
) -> TimeSweepResult:
    """The scene at ``samples`` instants over ``time_range`` = (t0, t1) (POST /sweep with
    ``time_range``): a linkage and its moving points through its time laws, or a spatial chain
    whose joints move from the scene's pose at t = 0 as q(t) = rate t + rate_dot t^2 / 2.
    Default quantity: position."""
    _statics(statics, normalise_quantities(quantities))
    parsed, found = _scene(scene, strict)
    if isinstance(parsed, CamScene):
        raise InvalidScene("time_range: a cam is swept over a revolution of its cam angle")
    if isinstance(parsed, GearTrainScene):
        if statics:
            raise InvalidScene("statics: a gear_train's torques are static already (input_torque)")
        return sweep_gear_train(parsed, time_range, samples, found)
    if len(time_range) != 2:
        raise InvalidScene("time_range: expected [t0, t1]")
    t0, t1 = time_range
    if isinstance(parsed, SpatialChain):
        _no_dynamics(normalise_quantities(quantities))
        chain = sweep_spatial_time(parsed, t0, t1, samples, quantities)
        body = results.spatial_time_sweep_body(chain, found)
        return TimeSweepResult(_kind("spatial_chain", body))
    result = sweep_linkage_time(parsed, t0, t1, samples, quantities, tolerance)
    body = add_sweep_dynamics(results.time_sweep_body(result, found), result, statics=statics)
    return TimeSweepResult(_kind("linkage_time", body))


def find_event(
    scene: SceneInput,
    moving_point: str,
    reaches: str,
    occurrence: int = 1,
    t_max: float = 60.0,
    *,
    strict: bool = False,
) -> EventResult:
    """The ``occurrence``-th instant after t = 0 at which ``moving_point`` coincides with the
    point ``reaches``, searched in 0 < t <= ``t_max`` (POST /events)."""
    parsed, found = _linkage(scene, strict, "an event search")
    event = events.find_event(parsed, moving_point, reaches, occurrence, t_max)
    return EventResult(
        {
            "time": event.time,
            "position": results.vector(event.position),
            "moving_point": moving_point,
            "reaches": reaches,
            "occurrence": occurrence,
            "warnings": found,
        }
    )


def solve(
    scene: SceneInput,
    method: str = "vector",
    digits: int = 4,
    *,
    strict: bool = False,
    angle_deg: float | None = None,
) -> SolutionResult:
    """The worked solution (POST /solution) by ``method`` ('vector', 'loop', 'newton_euler' or
    'statics', the static force analysis),
    numbers shown with ``digits`` significant digits; ``results`` is the /analyze body of the
    same instant and, for a linkage, ``polygons`` the polygons' segments in the vector method's
    order. A cam's at cam angle ``angle_deg`` (default 0; docs/CAMS.md)."""
    parsed, found = _scene(scene, strict)
    if isinstance(parsed, CamScene):
        angle = 0.0 if angle_deg is None else angle_deg
        cam = worked.solve(parsed, method, digits, angle_deg=angle)
        body = _kind("cam", {**cam.analysis, "warnings": [*found, *cam.analysis["warnings"]]})
        return SolutionResult(worked.solution_body(cam, body, None, body["warnings"]))
    if angle_deg is not None:
        raise InvalidScene("angle_deg: the cam angle of a 'cam' scene's worked solution")
    solution = worked.solve(parsed, method, digits)
    if isinstance(parsed, GearTrainScene):  # its steps' numbers point into its /analyze body
        body = analyze_gear_train(parsed, None, found).as_dict()
        return SolutionResult(worked.solution_body(solution, body, None, found))
    if not isinstance(parsed, LinkageScene):
        spatial = results.spatial_body(solution.analysis, frozenset(QUANTITIES), found)
        body = _kind("spatial_chain", spatial)
        return SolutionResult(worked.solution_body(solution, body, None, found))
    # The polygons follow the vector method's steps, whichever method the solution uses.
    vector_steps = (
        solution.steps
        if solution.method in ("vector", "newton_euler", "statics")
        else vector_method_steps(parsed, solution.analysis, digits)
    )
    shapes = polygons(parsed, solution.analysis, vector_steps)
    body = _kind("linkage", results.analysis_body(solution.analysis, found))
    if solution.method in ("newton_euler", "statics"):  # its numbers point into forces, energy
        add_dynamics_results(body, parsed, solution.analysis, solution.method == "statics")
    return SolutionResult(worked.solution_body(solution, body, shapes, found))


def synthesize(task: Mapping[str, Any]) -> SynthesisResult:
    """The four-bar for a synthesis task (POST /synthesis; docs/SYNTHESIS.md): two or three
    coupler positions, a function, or a quick-return time ratio. The body has the scene-v1
    linkage, its dimensions, the checks and defects from the solver's analysis of it, the
    warnings, and ``steps``: the worked solution (the construction with its numbers and a
    figure). ``InvalidScene`` (``InvalidExpression`` for the function) says why a task has none.
    """
    body = synthesize_task(task).as_dict()
    body["steps"] = [step.as_json() for step in synthesis_steps(body)]
    return SynthesisResult(body)

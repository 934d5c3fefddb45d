"""The answer key from the solver itself: the value at a path of the /analyze (or /events) answer.

A path names a number of the /analyze response of the scene (``points.C.velocity.0``,
``links.coupler.omega``, ``joints.0.coriolis_acceleration.1``, ``moving_points.M.acceleration.0``,
``bodies.3.omega.2``; a gear train's ``members.arm.omega``, walked on its /analyze body; a
synthesis task's ``freudenstein.K1`` or ``scene.points.A.0``, walked on its /synthesis body); the
solver's result objects carry the same names, so the path is walked on them directly.
``events.<M>.<target>.time`` is ``find_event``'s answer with /events' defaults.
Dynamics paths (``drivers.0.torque``, ``joints.1.force.0``, ``sweep[samples=720,k=4/100].cycle.
flywheel_inertia``, ``statics.drivers.0.torque`` of the static force analysis) are walked on the
/analyze (or /sweep) body itself.
Nothing here computes a kinematic quantity: every number is the solver's.
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from solver.analysis.events import find_event
from solver.analysis.instant import LinkageAnalysis, analyze
from solver.api import analyze as analyze_body
from solver.api import sweep as sweep_body
from solver.cams import CamScene, analyze_cam, parse_cam
from solver.errors import InvalidScene
from solver.exercises.cams import parse_cam_root
from solver.exercises.model import Exercise, is_task
from solver.gears import GearTrainScene, parse_gear_train
from solver.kinematics.spatial import (
    SpatialAnalysis,
    SpatialChain,
    analyze_spatial_chain,
    parse_spatial_chain,
)
from solver.model.scene import LinkageScene, parse_linkage
from solver.synthesis import parse_task, synthesize
from solver.synthesis.task import FunctionTask, MotionTask, QuickReturnTask, Task

EVENT_OCCURRENCE = 1  # /events' defaults
EVENT_T_MAX = 60.0
# The roots of paths into the dynamics answers (dynamics-v1), besides joints.<k>.force.<axis> and
# sweep[samples=N,k=P/100].cycle.<figure> (solver.exercises.dynamics).
DYNAMIC_ROOTS = frozenset({"drivers", "frame_force", "frame_moment", "energy", "center_of_mass"})
# The root of paths into the /analyze body of the static force analysis ("statics": true):
# statics.drivers.0.torque, statics.joints.2.force.1.
STATICS = "statics"
# The attributes a path may name (the /analyze field names that the result objects share).
_FIELDS = frozenset(
    {
        "position", "velocity", "acceleration", "angle", "omega", "alpha", "velocity_pole",
        "acceleration_pole", "transport_velocity", "relative_velocity", "transport_acceleration",
        "relative_acceleration", "coriolis_acceleration", "omega_carrier", "alpha_carrier", "s",
        "s_dot", "s_ddot",
    }
)  # fmt: skip


@dataclass(frozen=True)
class Solved:
    """A scene parsed and analysed once (all quantities), to read any number of paths from."""

    scene: LinkageScene | SpatialChain | GearTrainScene | CamScene | Task
    # a gear train's analysis is its /analyze body, a cam's its /analyze at cam angle 0, a
    # synthesis task's its /synthesis body
    analysis: LinkageAnalysis | SpatialAnalysis | Mapping[str, Any]
    document: Mapping[str, Any] = field(default_factory=dict)  # for the dynamics' bodies
    bodies: dict[str, Mapping[str, Any]] = field(default_factory=dict, compare=False)

    def dynamics(self, root: str) -> Mapping[str, Any]:
        """The /analyze body with ``forces`` and ``energy``, that with ``statics`` (root
        ``statics``), or a /sweep body (``sweep[...]`` roots), computed once per root."""
        key = root if root.startswith("sweep[") or root == STATICS else ""
        if key not in self.bodies:
            self.bodies[key] = dynamic_body(self.document, key)
        return self.bodies[key]


def parse(doc: Mapping[str, Any]) -> LinkageScene | SpatialChain | GearTrainScene | CamScene:
    if doc.get("kind") == "spatial_chain":
        return parse_spatial_chain(doc)
    if doc.get("kind") == "gear_train":
        return parse_gear_train(doc)
    if doc.get("kind") == "cam":
        return parse_cam(doc)
    return parse_linkage(doc)


def solve_scene(doc: Mapping[str, Any]) -> Solved:
    """The scene analysed as /analyze analyses it, with every quantity; a synthesis task
    designed as /synthesis designs it (its body, but for the worked solution's ``steps``, which
    ``solver.api.synthesize`` adds and no path names)."""
    if is_task(doc):
        return Solved(parse_task(doc), synthesize(doc).as_dict(), doc)
    scene = parse(doc)
    if isinstance(scene, LinkageScene):
        return Solved(scene, analyze(scene), doc)
    if isinstance(scene, GearTrainScene):  # its /analyze body (docs/GEARS.md)
        return Solved(scene, analyze_body(doc).as_dict(), doc)
    if isinstance(scene, CamScene):
        return Solved(scene, analyze_cam(scene), doc)
    return Solved(scene, analyze_spatial_chain(scene), doc)


def parse_sweep_root(part: str) -> tuple[int, float] | None:
    """(samples, speed_fluctuation) of a ``sweep[samples=N,k=P/100]`` path root, else None."""
    if not (part.startswith("sweep[samples=") and part.endswith("/100]")):
        return None
    samples, _, k = part[len("sweep[samples=") : -len("/100]")].partition(",k=")
    if not (samples.isdigit() and k.isdigit()):
        return None
    return int(samples), int(k) / 100


def flywheel_request(exercise: Exercise) -> tuple[str, int, float, float]:
    """(path root, samples, k, the driver's omega) of a flywheel exercise: the /sweep request its
    ``flywheel_inertia`` answer names (``sweep[samples=N,k=P/100]``)."""
    path = next(a.path for a in exercise.asked if a.key == "flywheel_inertia")
    root = path.split(".")[0]
    found = parse_sweep_root(root)
    if found is None:
        raise InvalidScene(f"path root {root!r}: expected sweep[samples=N,k=P/100]")
    samples, k = found
    return root, samples, k, float(exercise.scene["drivers"][0]["omega"])


def dynamic_body(doc: Mapping[str, Any], root: str) -> Mapping[str, Any]:
    """The /analyze body with every kinematic quantity and ``forces`` and ``energy`` (root ""),
    that of the static force analysis with ``forces`` (root ``statics``), or the /sweep body
    with ``forces`` of a ``sweep[samples=N,k=P/100]`` root: the result itself, read as its body
    (its arrays kept: a path reads one number of them, so none is made a list)."""
    if not root:
        quantities = ["position", "velocity", "acceleration", "forces", "energy"]
        return analyze_body(doc, quantities)
    if root == STATICS:
        return analyze_body(doc, ["position", "velocity", "forces"], statics=True)
    sweep = parse_sweep_root(root)
    if sweep is None:
        raise InvalidScene(f"path root {root!r}: expected sweep[samples=N,k=P/100]")
    samples, k = sweep
    return sweep_body(doc, samples, ["forces"], speed_fluctuation=k)


def _step(node: Any, part: str, path: str) -> Any:
    if isinstance(node, Mapping):
        if part not in node:
            raise InvalidScene(f"path {path!r}: no {part!r}")
        return node[part]
    if isinstance(node, Sequence | np.ndarray):
        if not part.isdigit() or int(part) >= len(node):
            raise InvalidScene(f"path {path!r}: no index {part!r}")
        return node[int(part)]
    if part not in _FIELDS or not hasattr(node, part):
        raise InvalidScene(f"path {path!r}: no field {part!r}")
    return getattr(node, part)


def value_in(body: Any, path: str) -> float:
    """The number at ``path`` in a body of plain dicts and lists (a /synthesis or a gear
    train's /analyze body: ``scene.points.A.0``); ``InvalidScene`` if there is none."""
    return _number(body, path.split("."), path)


def value_at(solved: Solved, path: str) -> float:
    """The number at ``path`` (see the module docstring); ``InvalidScene`` if there is none."""
    parts = path.split(".")
    # a gear train's members.<name>.omega; a synthesis task's freudenstein.K1, scene.points.A.0
    if isinstance(solved.scene, GearTrainScene | MotionTask | FunctionTask | QuickReturnTask):
        return value_in(solved.analysis, path)
    if parts[0] == "events":
        if len(parts) != 4 or parts[3] != "time" or not isinstance(solved.scene, LinkageScene):
            raise InvalidScene(f"path {path!r}: expected events.<moving point>.<target>.time")
        return find_event(solved.scene, parts[1], parts[2], EVENT_OCCURRENCE, EVENT_T_MAX).time
    rooted = parts[0].startswith("sweep[") or parts[0] == STATICS
    if parts[0] in DYNAMIC_ROOTS or rooted or parts[2:3] == ["force"]:
        if not isinstance(solved.scene, LinkageScene):
            raise InvalidScene(f"path {path!r}: dynamics are defined for planar linkages only")
        body: Any = solved.dynamics(parts[0])
        return _number(body, parts[1:] if rooted else parts, path)
    if isinstance(solved.scene, CamScene):  # analyze[angle_deg=N]: /analyze at that cam angle
        angle = parse_cam_root(parts[0])
        if angle is None:
            raise InvalidScene(f"path {path!r}: a cam's paths start with analyze[angle_deg=N]")
        if parts[0] not in solved.bodies:
            solved.bodies[parts[0]] = analyze_cam(solved.scene, angle)
        return _number(solved.bodies[parts[0]], parts[1:], path)
    a = solved.analysis
    assert not isinstance(a, Mapping)
    roots: dict[str, Any] = {"points": a.points}
    if isinstance(a, LinkageAnalysis):
        roots |= {"links": a.links, "joints": a.joints, "moving_points": a.moving_points}
    else:
        roots["bodies"] = a.bodies
    if parts[0] not in roots:
        raise InvalidScene(f"path {path!r}: unknown root {parts[0]!r}")
    return _number(roots[parts[0]], parts[1:], path)


def _number(node: Any, parts: Sequence[str], path: str) -> float:
    """The number reached from ``node`` along ``parts``."""
    for part in parts:
        node = _step(node, part, path)
    if node is None or np.ndim(node) != 0:
        raise InvalidScene(f"path {path!r} does not name a number")
    value = float(node)
    if not math.isfinite(value):
        raise InvalidScene(f"path {path!r}: the value is not finite")
    return value

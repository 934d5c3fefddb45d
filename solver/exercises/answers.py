"""The answer key from the solver itself: the value at a path of the /analyze (or /events) answer.

A path names a number of the /analyze response of the scene (``points.C.velocity.0``,
``links.coupler.omega``, ``joints.0.coriolis_acceleration.1``, ``moving_points.M.acceleration.0``,
``bodies.3.omega.2``); the solver's result objects carry the same names, so the path is walked on
them directly. ``events.<M>.<target>.time`` is ``find_event``'s answer with /events' defaults.
Nothing here computes a kinematic quantity: every number is the solver's.
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np

from solver.errors import InvalidScene
from solver.events import find_event
from solver.instant import LinkageAnalysis, analyze
from solver.scene import LinkageScene, parse_linkage
from solver.spatial import SpatialAnalysis, SpatialChain, analyze_spatial_chain, parse_spatial_chain

EVENT_OCCURRENCE = 1  # /events' defaults
EVENT_T_MAX = 60.0
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

    scene: LinkageScene | SpatialChain
    analysis: LinkageAnalysis | SpatialAnalysis


def parse(doc: Mapping[str, Any]) -> LinkageScene | SpatialChain:
    if doc.get("kind") == "spatial_chain":
        return parse_spatial_chain(doc)
    return parse_linkage(doc)


def solve_scene(doc: Mapping[str, Any]) -> Solved:
    """The scene analysed as /analyze analyses it, with every quantity."""
    scene = parse(doc)
    if isinstance(scene, LinkageScene):
        return Solved(scene, analyze(scene))
    return Solved(scene, analyze_spatial_chain(scene))


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


def value_at(solved: Solved, path: str) -> float:
    """The number at ``path`` (see the module docstring); ``InvalidScene`` if there is none."""
    parts = path.split(".")
    if parts[0] == "events":
        if len(parts) != 4 or parts[3] != "time" or not isinstance(solved.scene, LinkageScene):
            raise InvalidScene(f"path {path!r}: expected events.<moving point>.<target>.time")
        return find_event(solved.scene, parts[1], parts[2], EVENT_OCCURRENCE, EVENT_T_MAX).time
    a = solved.analysis
    roots: dict[str, Any] = {"points": a.points}
    if isinstance(a, LinkageAnalysis):
        roots |= {"links": a.links, "joints": a.joints, "moving_points": a.moving_points}
    else:
        roots["bodies"] = a.bodies
    if parts[0] not in roots:
        raise InvalidScene(f"path {path!r}: unknown root {parts[0]!r}")
    node = roots[parts[0]]
    for part in parts[1:]:
        node = _step(node, part, path)
    if node is None or np.ndim(node) != 0:
        raise InvalidScene(f"path {path!r} does not name a number")
    value = float(node)
    if not math.isfinite(value):
        raise InvalidScene(f"path {path!r}: the value is not finite")
    return value

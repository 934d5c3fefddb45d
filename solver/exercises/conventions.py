"""The sign convention of an exercise's answers, one sentence per kind of scene, appended to every
statement (``solver.exercises.generation``): a signed answer means nothing without it, and a
student who answers a magnitude must be told beforehand that a sign is asked.

The sentences say what the solver's answers are: planar linkages in the scene's x-y frame (x to
the right, y up, angles and every rotation, moment and torque counter-clockwise positive), spatial
chains in their right-handed x, y, z frame as drawn, gear trains about their common axis, cams
along the follower's stroke, synthesis tasks in the frame of their given coordinates
(docs/EXERCISES.md, "Sign convention").
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

from solver.exercises.model import is_task

PLANAR = (
    "Signs: x to the right, y up, {origin}; angles, angular velocities and accelerations, "
    "moments and torques counter-clockwise positive; give every component with its sign."
)
SPATIAL = (
    "Signs: the right-handed axes x, y, z as drawn (z up), origin at O; give every component "
    "with its sign."
)
GEAR_TRAIN = (
    "Signs: every angular velocity about the common axis, counter-clockwise positive seen from "
    "the same side; give every answer with its sign."
)
TASK = (
    "Signs: x to the right, y up, in the frame the given coordinates are written in; angles "
    "counter-clockwise positive; give every answer with its sign."
)
CAM = (
    "Signs: the follower's displacement, velocity, acceleration and jerk positive away from the "
    "cam centre; the pressure angle positive on the rise of a follower without offset, negative "
    "on its return; give every answer with its sign."
)


def sign_convention(scene: Mapping[str, Any]) -> str:
    """The sentence stating the signs and axes of the answers of an exercise on ``scene``."""
    if is_task(scene):  # a synthesis task: its given points and angles fix the frame
        return TASK
    kind = scene.get("kind", "linkage")
    if kind != "linkage":
        return {"spatial_chain": SPATIAL, "gear_train": GEAR_TRAIN, "cam": CAM}.get(kind, "")
    return PLANAR.format(origin=_origin(scene.get("points", {})))


def _origin(points: Mapping[str, Any]) -> str:
    """Where the frame's origin is: the point the scene puts at (0, 0), else the drawn axes."""
    at_origin = [name for name, p in points.items() if p[0] == 0.0 and p[1] == 0.0]
    return f"origin at {at_origin[0]}" if at_origin else "origin where the drawn axes cross"

"""The three synthesis tasks of POST /synthesis, read from their JSON documents (docs/SYNTHESIS.md).

``parse_task`` checks a task document and builds one of ``MotionTask``, ``FunctionTask`` and
``QuickReturnTask`` (frozen; angles in radians, points as complex numbers x + iy). Every
refusal is an ``InvalidScene`` naming the field and saying why, as the scene parser's are; a key
the task does not know is refused with the nearest valid name.
"""

from __future__ import annotations

import difflib
import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from typing import Any

from solver.errors import InvalidScene

MAX_COORDINATE = 1e6  # m: a point or length past this is refused (no linkage is that large)
MIN_LENGTH = 1e-6  # m: a given length below this is refused (no linkage is that small)
MIN_SWING_DEG = 1e-3  # a swing closer than this to 0 or 180 deg has no constructible chord
MAX_PRECISION_POINTS = 3  # Freudenstein's equation has three coefficients K1, K2, K3


@dataclass(frozen=True)
class Pose:
    """A precision position of the coupler: its point P (x + iy, m) and its angle (rad)."""

    point: complex
    angle: float


@dataclass(frozen=True)
class MotionTask:
    """Motion generation: the coupler through two or three poses, with the coupler's two moving
    pivots (B, C at the first pose) or the two fixed pivots (A, D) given; for two poses with the
    moving pivots, optionally ``bisector_offsets`` (dA, dD; m): each fixed pivot's signed
    distance along its perpendicular bisector from the chord's midpoint (positive to the left of
    B1 -> B2, C1 -> C2), None for the stated default choice."""

    positions: tuple[Pose, ...]
    moving_pivots: tuple[complex, complex] | None
    fixed_pivots: tuple[complex, complex] | None
    bisector_offsets: tuple[float, float] | None = None


@dataclass(frozen=True)
class FunctionTask:
    """Function generation y = f(x) over ``x_range``: the crank's angle maps x linearly onto
    ``input_range``, the rocker's angle maps y onto ``output_range`` (absolute angles from the
    ground line A -> D, rad); ``precision_x`` the precision points given, or None for Chebyshev
    spacing; ``ground_length`` |AD| (m)."""

    function: str
    x_range: tuple[float, float]
    input_range: tuple[float, float]
    output_range: tuple[float, float]
    precision_x: tuple[float, ...] | None
    ground_length: float


@dataclass(frozen=True)
class QuickReturnTask:
    """A crank-rocker whose rocker swings through ``swing`` (rad) with the time ratio
    ``time_ratio`` (slow stroke over fast stroke at constant crank speed)."""

    time_ratio: float
    rocker_length: float
    swing: float


Task = MotionTask | FunctionTask | QuickReturnTask

FIELDS: dict[str, frozenset[str]] = {
    "motion": frozenset({"task", "positions", "moving_pivots", "fixed_pivots", "bisector_offsets"}),
    "function": frozenset(
        {
            "task",
            "function",
            "x_range",
            "input_range_deg",
            "output_range_deg",
            "precision_points",
            "ground_length",
        }
    ),
    "quick_return": frozenset({"task", "time_ratio", "rocker_length", "swing_deg"}),
}
REQUIRED: dict[str, tuple[str, ...]] = {
    "motion": ("positions",),
    "function": ("function", "x_range", "input_range_deg", "output_range_deg"),
    "quick_return": ("time_ratio", "rocker_length", "swing_deg"),
}


def _number(value: Any, where: str) -> float:
    """A finite JSON number of moderate size (not a boolean)."""
    if isinstance(value, bool) or not isinstance(value, int | float):
        raise InvalidScene(f"{where}: expected a number, got {value!r}")
    number = float(value)
    if not math.isfinite(number) or abs(number) > MAX_COORDINATE:
        raise InvalidScene(f"{where}: {value!r} is not a finite number within 1e6")
    return number


def _pair(value: Any, where: str) -> tuple[float, float]:
    if not isinstance(value, Sequence) or isinstance(value, str) or len(value) != 2:
        raise InvalidScene(f"{where}: expected two numbers [a, b], got {value!r}")
    return _number(value[0], f"{where}[0]"), _number(value[1], f"{where}[1]")


def _point(value: Any, where: str) -> complex:
    x, y = _pair(value, where)
    return complex(x, y)


def _positive(value: Any, where: str) -> float:
    number = _number(value, where)
    if number <= 0.0:
        raise InvalidScene(f"{where}: must be positive, got {number:g}")
    return number


def _length(value: Any, where: str) -> float:
    number = _positive(value, where)
    if number < MIN_LENGTH:
        raise InvalidScene(f"{where}: {number:g} m is below {MIN_LENGTH:g} m")
    return number


def _span(value: Any, where: str, unit: str) -> tuple[float, float]:
    low, high = _pair(value, where)
    if low == high:
        raise InvalidScene(f"{where}: the two ends are equal ({low:g}{unit}): the range is empty")
    return low, high


def _check_keys(doc: Mapping[str, Any], task: str) -> None:
    known = FIELDS[task]
    for key in doc:
        if key not in known:
            near = difflib.get_close_matches(str(key), sorted(known), n=1, cutoff=0.6)
            hint = (
                f"; did you mean {near[0]}?"
                if near
                else f"; a {task} task takes " + ", ".join(sorted(known))
            )
            raise InvalidScene(f"{key}: not a field of a {task} task{hint}")
    for key in REQUIRED[task]:
        if key not in doc:
            raise InvalidScene(f"{key}: a {task} task needs it")


def _motion(doc: Mapping[str, Any]) -> MotionTask:
    positions = doc["positions"]
    if not isinstance(positions, Sequence) or isinstance(positions, str):
        raise InvalidScene("positions: expected a list of 2 or 3 positions")
    if not 2 <= len(positions) <= 3:
        raise InvalidScene(
            f"positions: {len(positions)} given; a four-bar is synthesised for 2 or 3 positions"
        )
    poses = []
    for k, entry in enumerate(positions):
        where = f"positions[{k}]"
        if not isinstance(entry, Mapping) or set(entry) != {"point", "angle_deg"}:
            raise InvalidScene(f'{where}: expected {{"point": [x, y], "angle_deg": a}}')
        angle = math.radians(_number(entry["angle_deg"], f"{where}.angle_deg"))
        poses.append(Pose(_point(entry["point"], f"{where}.point"), angle))
    given = [key for key in ("moving_pivots", "fixed_pivots") if key in doc]
    if len(given) != 1:
        raise InvalidScene(
            "moving_pivots: give either moving_pivots (B, C at the first position) or "
            "fixed_pivots (A, D), not " + ("both" if given else "neither")
        )
    key = given[0]
    pivots = doc[key]
    if not isinstance(pivots, Sequence) or isinstance(pivots, str) or len(pivots) != 2:
        raise InvalidScene(f"{key}: expected two points [[x, y], [x, y]]")
    pair = (_point(pivots[0], f"{key}[0]"), _point(pivots[1], f"{key}[1]"))
    if pair[0] == pair[1]:
        raise InvalidScene(f"{key}: the two pivots coincide at {_xy(pair[0])}")
    offsets = _offsets(doc, len(poses), key) if "bisector_offsets" in doc else None
    if key == "moving_pivots":
        return MotionTask(tuple(poses), pair, None, offsets)
    return MotionTask(tuple(poses), None, pair)


def _offsets(doc: Mapping[str, Any], count: int, pivots: str) -> tuple[float, float]:
    """``bisector_offsets`` [dA, dD] (m): only for two positions with the moving pivots given
    (three positions fix A and D; with the fixed pivots given there is nothing to place)."""
    if count != 2:
        raise InvalidScene(
            f"bisector_offsets: {count} positions fix the centre points A and D (where the "
            "bisectors meet); the offsets are the free choice of two positions only"
        )
    if pivots != "moving_pivots":
        raise InvalidScene(
            "bisector_offsets: they place the fixed pivots A and D on the bisectors of B1B2 and "
            "C1C2, so they go with moving_pivots, not with fixed_pivots (which gives A and D)"
        )
    return _pair(doc["bisector_offsets"], "bisector_offsets")


def _function(doc: Mapping[str, Any]) -> FunctionTask:
    text = doc["function"]
    if not isinstance(text, str):
        raise InvalidScene(f"function: expected an expression in x as a string, got {text!r}")
    x_range = _span(doc["x_range"], "x_range", "")
    inputs = _span(doc["input_range_deg"], "input_range_deg", " deg")
    outputs = _span(doc["output_range_deg"], "output_range_deg", " deg")
    for where, (low, high) in (("input_range_deg", inputs), ("output_range_deg", outputs)):
        if abs(high - low) >= 360.0:
            raise InvalidScene(
                f"{where}: a range of {abs(high - low):g} deg is a full turn or more"
            )
    given = doc.get("precision_points", MAX_PRECISION_POINTS)
    points: tuple[float, ...] | None = None
    if isinstance(given, Sequence) and not isinstance(given, str):
        points = tuple(_number(x, f"precision_points[{k}]") for k, x in enumerate(given))
        if len(points) != MAX_PRECISION_POINTS:
            raise InvalidScene(
                f"precision_points: {len(points)} given; Freudenstein's equation has three "
                "coefficients K1, K2, K3, so exactly 3 precision points"
            )
        low, high = sorted(x_range)
        for k, x in enumerate(points):
            if not low <= x <= high:
                raise InvalidScene(f"precision_points[{k}]: x = {x:g} is outside x_range")
        if len(set(points)) != len(points):
            raise InvalidScene("precision_points: two precision points are equal")
    elif isinstance(given, bool) or given != MAX_PRECISION_POINTS:
        raise InvalidScene(
            f"precision_points: {given!r}; Freudenstein's equation has three coefficients K1, "
            "K2, K3: give 3 (Chebyshev spacing) or a list of three x values"
        )
    ground = _length(doc.get("ground_length", 1.0), "ground_length")
    return FunctionTask(
        text,
        x_range,
        (math.radians(inputs[0]), math.radians(inputs[1])),
        (math.radians(outputs[0]), math.radians(outputs[1])),
        points,
        ground,
    )


def _quick_return(doc: Mapping[str, Any]) -> QuickReturnTask:
    ratio = _positive(doc["time_ratio"], "time_ratio")
    if ratio < 1.0:
        raise InvalidScene(
            f"time_ratio: {ratio:g} < 1; the time ratio is the slow stroke's time over the fast "
            f"one's, at least 1 (the same linkage turning the other way gives {1.0 / ratio:.6g})"
        )
    length = _length(doc["rocker_length"], "rocker_length")
    swing = _number(doc["swing_deg"], "swing_deg")
    if not MIN_SWING_DEG <= swing <= 180.0 - MIN_SWING_DEG:
        raise InvalidScene(
            f"swing_deg: {swing:g} deg; a rocker swings through 0 < swing < 180 deg (at least "
            f"{MIN_SWING_DEG:g} deg from either end)"
        )
    return QuickReturnTask(ratio, length, math.radians(swing))


def _xy(z: complex) -> str:
    return f"({z.real:.6g}, {z.imag:.6g})"


def parse_task(doc: Any) -> Task:
    """Check a synthesis task document and build its task (``InvalidScene`` saying where and
    why)."""
    if not isinstance(doc, Mapping):
        raise InvalidScene("task: expected an object with a 'task' field")
    kind = doc.get("task")
    if kind not in FIELDS:
        raise InvalidScene(f"task: expected 'motion', 'function' or 'quick_return', got {kind!r}")
    _check_keys(doc, kind)
    if kind == "motion":
        return _motion(doc)
    if kind == "function":
        return _function(doc)
    return _quick_return(doc)

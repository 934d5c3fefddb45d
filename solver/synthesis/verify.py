"""A synthesised four-bar as a scene-v1 linkage, and what the project's own analysis says of it.

The scene has the links ``ground`` (A, D), ``crank`` (A, B; the input, driven), ``coupler`` (B,
C and, for a motion task, P) and ``rocker`` (D, C). Nothing here trusts the synthesis' algebra:
each precision position is checked by analysing the scene with the crank turned to its angle
(``solver.analysis.instant.analyze``: the assembly of the drawn pose, polished in 40 digits),
and the crank's range, the assembly it keeps and the transmission angle come from a sweep
(``solver.analysis.sweeps.sweep``), as POST /analyze and POST /sweep would answer.
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np

from solver.analysis import instant
from solver.analysis.instant import LinkageAnalysis
from solver.analysis.sweeps import sweep
from solver.kinematics.rigid import Array
from solver.model.scene import LinkageScene, parse_linkage

SWEEP_SAMPLES = 720  # the verifying sweep: half a degree
REACHED = 1e-9  # of the scene's size: a position is reached when the analysed pose is this close
MIN_TRANSMISSION_DEG = 40.0  # a transmission angle below this is warned about
FAR_PIVOT = 10.0  # a fixed pivot farther than this many coupler lengths from P1 is warned about

JOINTS = (("A", ("ground", "crank")), ("B", ("crank", "coupler")), ("C", ("coupler", "rocker")))


def four_bar_document(
    points: Mapping[str, complex], omega: float, title: str, coupler_point: bool
) -> dict[str, Any]:
    """The scene-v1 linkage of a synthesised four-bar, posed at ``points`` (A, B, C, D and, with
    ``coupler_point``, P), the crank driven at ``omega`` rad/s."""
    names = ("A", "B", "C", "D", "P") if coupler_point else ("A", "B", "C", "D")
    return {
        "kind": "linkage",
        "title": title,
        "points": {name: [points[name].real, points[name].imag] for name in names},
        "links": {
            "ground": {"points": ["A", "D"], "ground": True},
            "crank": {"points": ["A", "B"]},
            "coupler": {"points": ["B", "C", "P"] if coupler_point else ["B", "C"]},
            "rocker": {"points": ["D", "C"]},
        },
        "joints": [
            {"type": "revolute", "point": point, "links": list(pair)}
            for point, pair in (*JOINTS, ("D", ("rocker", "ground")))
        ],
        "drivers": [{"link": "crank", "omega": omega, "alpha": 0.0}],
    }


def analysed_at(
    document: Mapping[str, Any], crank_angle: float, quantities: Sequence[str] = ("position",)
) -> LinkageAnalysis:
    """The scene analysed with the crank at the absolute angle ``crank_angle`` (rad): POST
    /analyze with ``drivers[0].angle_deg``."""
    driver = {**document["drivers"][0], "angle_deg": math.degrees(crank_angle)}
    return instant.analyze(parse_linkage({**document, "drivers": [driver]}), quantities)


def position_of(analysis: LinkageAnalysis, name: str) -> complex:
    """A point's analysed position as x + iy."""
    position = analysis.points[name].position
    assert position is not None
    return complex(float(position[0]), float(position[1]))


@dataclass(frozen=True)
class Travel:
    """The crank's travel as /sweep finds it: whether it turns fully, its limit angles (absolute,
    rad) where it cannot, and the transmission angle BCD (rad) at each sampled crank angle."""

    feasible: bool
    limits: tuple[float, ...]
    driver_angle: Array
    transmission_angle: Array
    grashof: str


def travel(document: Mapping[str, Any]) -> Travel:
    """Sweep the scene (``SWEEP_SAMPLES``, positions) and keep what the checks need."""
    scene: LinkageScene = parse_linkage(document)
    found = sweep(scene, SWEEP_SAMPLES, ["position"])
    loop = found.four_bar_loops[0]
    return Travel(
        found.feasible,
        found.limits,
        np.asarray(found.driver_angle),
        np.asarray(loop.transmission_angle),
        loop.grashof,
    )


def ccw_turn(start: float, end: float) -> float:
    """The counter-clockwise turn from ``start`` to ``end``, in [0, 2 pi)."""
    return (end - start) % math.tau


@dataclass(frozen=True)
class Passage:
    """How the crank passes the precision angles: the sense it turns in (+1 counter-clockwise),
    each angle unwrapped onto its travel from the first (None where the crank cannot reach it
    from the first without passing a limit position), and whether it meets them out of order."""

    sense: float
    unwrapped: tuple[float | None, ...]
    order_defect: bool


def passage(angles: Sequence[float], found: Travel) -> Passage:
    """The sense of rotation that meets ``angles`` (absolute crank angles, rad) in the given
    order: for a crank that turns fully, the sense in which the second comes before the third
    (with two, the shorter way to the second); for a crank that rocks between limit positions,
    the sense from the first to the second, and the order is a defect where the angles are not
    monotonic along the feasible interval."""
    first = angles[0]
    if found.feasible:
        if len(angles) == 3:
            sense = 1.0 if ccw_turn(first, angles[1]) < ccw_turn(first, angles[2]) else -1.0
        else:
            sense = 1.0 if ccw_turn(first, angles[-1]) <= math.pi else -1.0
        unwrapped = tuple(first + sense * ccw_turn(first * sense, a * sense) for a in angles)
        return Passage(sense, unwrapped, False)
    low, high = sorted(found.limits)
    placed: list[float | None] = []
    for angle in angles:
        turns = math.ceil((low - angle) / math.tau)
        candidate = angle + turns * math.tau
        placed.append(candidate if candidate <= high else None)
    reached = [a for a in placed if a is not None]
    steps = np.diff(reached)
    sense = 1.0 if steps.size == 0 or steps[0] >= 0.0 else -1.0
    order_defect = bool(np.any(steps * sense < 0.0))
    return Passage(sense, tuple(placed), order_defect)


def transmission_on_the_way(found: Travel, passed: Passage) -> tuple[float, float]:
    """The smallest transmission angle min(mu, 180 - mu) (deg) at the sampled crank angles
    between the first precision angle and the farthest one the crank reaches, and the crank
    angle (deg) where it is."""
    reached = [a for a in passed.unwrapped if a is not None]
    angles = found.driver_angle
    first = reached[0]
    if found.feasible:
        turned = (passed.sense * (angles - first)) % math.tau
        span = max(passed.sense * (a - first) for a in reached)
        on_way = turned <= span + 1e-12
    else:
        on_way = (angles >= min(reached) - 1e-12) & (angles <= max(reached) + 1e-12)
    if not np.any(on_way):
        on_way = np.ones_like(angles, dtype=bool)
    mu = np.minimum(found.transmission_angle, math.pi - found.transmission_angle)
    k = int(np.argmin(np.where(on_way, mu, np.inf)))
    return math.degrees(float(mu[k])), math.degrees(float(angles[k]))


def transmission_warning(found: Travel, passed: Passage, what: str) -> list[str]:
    """A sentence when the transmission angle falls below ``MIN_TRANSMISSION_DEG`` on the way."""
    mu, at = transmission_on_the_way(found, passed)
    if mu >= MIN_TRANSMISSION_DEG:
        return []
    return [
        f"the transmission angle falls to {mu:.1f} deg (below {MIN_TRANSMISSION_DEG:g} deg) at "
        f"crank angle {math.remainder(at, 360.0):.1f} deg, {what}: the rocker is then pushed "
        "nearly along its own length and a real linkage would bind"
    ]


def far_pivot_warnings(
    points: Mapping[str, complex], reference: complex, scale: float
) -> list[str]:
    """A sentence for each fixed pivot farther than ``FAR_PIVOT`` coupler lengths ``scale``
    from ``reference``."""
    out = []
    for name in ("A", "D"):
        distance = abs(points[name] - reference)
        if distance > FAR_PIVOT * scale:
            out.append(
                f"the fixed pivot {name} is {distance:.4g} m from the first position's point, "
                f"{distance / scale:.1f} coupler lengths away: a large linkage for the motion"
            )
    return out


def defects_fields(
    found: Travel, passed: Passage, errors: Sequence[float], size: float
) -> dict[str, Any]:
    """The three defects: ``branch`` (a precision position is met only on the other assembly:
    the analysed pose at its crank angle is off), ``order`` (not met in the given order as the
    crank turns one way), ``grashof`` (the crank cannot turn fully: /sweep's ``feasible`` is
    false), with the linkage's Grashof class."""
    return {
        "branch": any(e > REACHED * size for e in errors),
        "order": passed.order_defect,
        "grashof": not found.feasible,
        "grashof_class": found.grashof,
    }

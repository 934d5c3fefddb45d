"""POST /synthesis: a synthesis task in, the four-bar that does it out, checked by analysis.

``synthesize`` reads the task (``solver.synthesis.task``), designs the linkage (``motion``,
``function``, ``quick_return``), writes it as a scene-v1 linkage (``verify``), and then asks the
project's own analysis where that scene passes each precision position (the ``checks``), whether
its crank turns fully, on which assembly and in which order it meets them (the ``defects``),
and how its transmission angle fares (the ``warnings``). docs/SYNTHESIS.md is the contract.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from solver.analysis.results import Result
from solver.model.scene import parse_linkage
from solver.position.assembly import DriverInput, assemble
from solver.position.topology import build_plan
from solver.synthesis.function import Scales, design_function
from solver.synthesis.motion import MotionDesign, rotor, synthesise_motion
from solver.synthesis.quick_return import synthesise_quick_return
from solver.synthesis.task import FunctionTask, MotionTask, QuickReturnTask, parse_task
from solver.synthesis.verify import (
    MIN_TRANSMISSION_DEG,
    REACHED,
    analysed_at,
    ccw_turn,
    defects_fields,
    far_pivot_warnings,
    four_bar_document,
    passage,
    position_of,
    transmission_on_the_way,
    transmission_warning,
    travel,
)

STRUCTURAL_SAMPLES = 201  # x values over the range at which the structural error is measured

JSON = dict[str, Any]


class SynthesisResult(Result):
    """The body of POST /synthesis (docs/SYNTHESIS.md)."""


def _xy(z: complex) -> list[float]:
    return [z.real, z.imag]


def _angle(z: complex) -> float:
    return math.atan2(z.imag, z.real)


def _lengths(points: dict[str, complex]) -> JSON:
    return {
        "ground": abs(points["D"] - points["A"]),
        "crank": abs(points["B"] - points["A"]),
        "coupler": abs(points["C"] - points["B"]),
        "rocker": abs(points["C"] - points["D"]),
    }


def _defect_sentences(defects: JSON, checks: list[JSON], what: str) -> list[str]:
    out = []
    if defects["grashof"]:
        out.append(
            f"grashof defect: the crank cannot turn fully ({defects['grashof_class']}); it rocks "
            "between limit positions, so a motor turning round cannot drive it"
        )
    for k, check in enumerate(checks):
        if not check["reached"]:
            out.append(
                f"{what} {k + 1} is not reached by the linkage turning from the first: the "
                f"analysed pose at crank angle {check['driver_angle_deg']:.2f} deg is "
                f"{check['error']:.4g} off (it is met only on the other assembly, or beyond a "
                "limit position)"
            )
    if defects["order"]:
        out.append(
            f"order defect: the crank meets the {what}s out of the given order whichever way it "
            "turns between its limit positions"
        )
    return out


def _points(design: MotionDesign) -> dict[str, complex]:
    return {"A": design.A, "B": design.B, "C": design.C, "D": design.D, "P": design.P}


def _construction(task: MotionTask, design: MotionDesign) -> JSON:
    """The poles, the places of B, C and P, the choices made, the bisector offsets given."""
    return {
        "poles": {k: None if p is None else _xy(p) for k, p in design.poles.items()},
        "places": {name: [_xy(t[name]) for t in design.targets] for name in ("B", "C", "P")},
        "choices": list(design.choices),
    } | ({} if task.bisector_offsets is None else {"bisector_offsets": [*task.bisector_offsets]})


def designed_motion(task: MotionTask, design: MotionDesign) -> JSON:
    """The part of a motion task's /synthesis body that its ``design``
    (``synthesise_motion(task)``) alone fixes, before the linkage is verified by analysis: the
    points of the linkage (``scene.points``: A, B, C, D and P) and the construction (the poles,
    the places of B, C and P, the choices made, the bisector offsets given). ``synthesize``
    writes the same numbers; an exercise reads its answers here before it pays for the
    verification (``solver.exercises.generation``)."""
    return {
        "scene": {"points": {name: _xy(z) for name, z in _points(design).items()}},
        "construction": _construction(task, design),
    }


def _motion(task: MotionTask) -> JSON:
    design: MotionDesign = synthesise_motion(task)
    points = _points(design)
    angles = [_angle(t["B"] - design.A) for t in design.targets]
    probe = four_bar_document(points, 1.0, "synthesised four-bar (motion)", True)
    found = travel(probe)
    passed = passage(angles, found)
    document = four_bar_document(points, passed.sense, "synthesised four-bar (motion)", True)
    size = parse_linkage(document).size
    checks: list[JSON] = []
    for k, (target, angle) in enumerate(zip(design.targets, angles, strict=True)):
        analysis = analysed_at(document, angle)
        at = {name: position_of(analysis, name) for name in ("B", "C", "P")}
        error = max(abs(at[name] - target[name]) for name in at)
        coupler = _angle(at["C"] - at["B"]) - _angle(points["C"] - points["B"])
        checks.append(
            {
                "position": k + 1,
                "driver_angle_deg": math.degrees(angle),
                "error": error,
                "reached": error <= REACHED * size and passed.unwrapped[k] is not None,
                "point": _xy(at["P"]),
                "coupler_turn_deg": math.degrees(math.remainder(coupler, math.tau)),
            }
        )
    defects = defects_fields(found, passed, [c["error"] for c in checks], size)
    mu, mu_at = transmission_on_the_way(found, passed)
    warnings = _defect_sentences(defects, checks, "position")
    warnings += transmission_warning(found, passed, "between the first and the last position")
    warnings += far_pivot_warnings(points, design.P, abs(design.C - design.B))
    BP = design.P - design.B
    return {
        "task": "motion",
        "scene": document,
        "dimensions": {
            **_lengths(points),
            "coupler_point": {
                "BP": abs(BP),
                "angle_deg": math.degrees(
                    math.remainder(_angle(BP) - _angle(design.C - design.B), math.tau)
                ),
            },
            "grashof": found.grashof,
        },
        "construction": _construction(task, design),
        "checks": checks,
        "defects": defects,
        "transmission_angle": {"min_deg": mu, "at_driver_angle_deg": mu_at},
        "warnings": warnings,
    }


def _function(task: FunctionTask) -> JSON:
    design = design_function(task)
    scales, xs, ys, theta2, theta4 = design.scales, design.x, design.y, design.crank, design.rocker
    (k1, k2, k3), a, b, c = design.k, design.a, design.b, design.c
    spacing = "given" if task.precision_x else "chebyshev"
    d = task.ground_length
    # A negative length is the link pointing the other way: its link angle is theta + pi.
    crank_offset = math.pi if a < 0.0 else 0.0
    rocker_offset = math.pi if c < 0.0 else 0.0
    A, D = 0j, complex(d, 0.0)
    B = A + abs(a) * rotor(float(theta2[0]) + crank_offset)
    C = D + abs(c) * rotor(float(theta4[0]) + rocker_offset)
    points = {"A": A, "B": B, "C": C, "D": D}
    crank_angles = [float(t) + crank_offset for t in theta2]
    probe = four_bar_document(points, 1.0, "synthesised four-bar (function)", False)
    found = travel(probe)
    sense = 1.0 if task.input_range[1] >= task.input_range[0] else -1.0
    document = four_bar_document(points, sense, "synthesised four-bar (function)", False)
    scene = parse_linkage(document)
    per_radian = (scales.yf - scales.y0) / (task.output_range[1] - task.output_range[0])
    checks: list[JSON] = []
    for x, y, angle, wanted in zip(xs, ys, crank_angles, theta4, strict=True):
        analysis = analysed_at(document, angle)
        rocker = _angle(position_of(analysis, "C") - position_of(analysis, "D")) - rocker_offset
        off = math.remainder(rocker - float(wanted), math.tau)
        checks.append(
            {
                "x": float(x),
                "y": float(y),
                "driver_angle_deg": math.degrees(angle),
                "output_angle_deg": math.degrees(float(wanted) + off),
                "output_angle_error_deg": math.degrees(abs(off)),
                "error": abs(off * per_radian),
                "reached": abs(off) * abs(c) <= REACHED * scene.size,
            }
        )
    structural = _structural_error(task, scales, scene, crank_offset, rocker_offset, per_radian)
    passed = passage([crank_angles[0]], found)
    defects = defects_fields(found, passed, [0.0], 1.0)
    defects["branch"] = not all(check["reached"] for check in checks)
    defects["order"] = False
    warnings = []
    if defects["grashof"]:
        warnings.append(
            f"the crank cannot turn fully ({found.grashof}); it rocks between limit positions, "
            "which suits a function generator as long as the input range lies between them"
        )
    for check in checks:
        if not check["reached"]:
            warnings.append(
                f"branch defect: at x = {check['x']:.6g} the linkage is on the other assembly "
                f"(the output is {check['output_angle_error_deg']:.4g} deg off)"
            )
    if not structural["reached"]:
        warnings.append(
            "the linkage cannot be closed over the whole input range on the first precision "
            "point's assembly: the structural error is given where it closes"
        )
    mu = np.minimum(found.transmission_angle, math.pi - found.transmission_angle)
    warnings += _range_transmission(found, task, crank_offset, mu)
    return {
        "task": "function",
        "scene": document,
        "dimensions": {
            "ground": d,
            "crank": abs(a),
            "coupler": b,
            "rocker": abs(c),
            "grashof": found.grashof,
        },
        "freudenstein": {"K1": k1, "K2": k2, "K3": k3, "a": a, "b": b, "c": c, "d": d},
        "precision_points": [
            {
                "x": float(x),
                "y": float(y),
                "input_angle_deg": math.degrees(float(t2)),
                "output_angle_deg": math.degrees(float(t4)),
            }
            for x, y, t2, t4 in zip(xs, ys, theta2, theta4, strict=True)
        ],
        "spacing": spacing,
        "checks": checks,
        "defects": defects,
        "structural_error": structural,
        "warnings": warnings,
    }


def _range_transmission(found: Any, task: FunctionTask, offset: float, mu: Any) -> list[str]:
    """A sentence when the transmission angle falls below the limit inside the input range."""
    start, end = (t + offset for t in task.input_range)
    turned = (found.driver_angle - start) * (1.0 if end >= start else -1.0) % math.tau
    inside = turned <= abs(end - start) + 1e-12
    if not np.any(inside):
        return []
    k = int(np.argmin(np.where(inside, mu, np.inf)))
    worst = math.degrees(float(mu[k]))
    if worst >= MIN_TRANSMISSION_DEG:
        return []
    return [
        f"the transmission angle falls to {worst:.1f} deg (below {MIN_TRANSMISSION_DEG:g} deg) "
        f"at crank angle {math.remainder(math.degrees(float(found.driver_angle[k])), 360.0):.1f} "
        "deg, inside the input range: a real linkage would bind there"
    ]


def _structural_error(
    task: FunctionTask,
    scales: Scales,
    scene: Any,
    crank_offset: float,
    rocker_offset: float,
    per_radian: float,
) -> JSON:
    """The generated y against f(x) at ``STRUCTURAL_SAMPLES`` x over the range: the linkage
    assembled at each crank angle on the drawn assembly (as /analyze at that angle)."""
    x = np.linspace(*task.x_range, STRUCTURAL_SAMPLES)
    desired = scales.y(x)
    crank = scales.crank(x) + crank_offset
    drawn = _angle(complex(*scene.points["B"]) - complex(*scene.points["A"]))
    n = x.size
    zeros = np.zeros(n)
    motion = assemble(scene, build_plan(scene), [DriverInput(crank - drawn, zeros, zeros)], 0)
    C, D = motion.points["C"].p, motion.points["D"].p
    rocker = np.arctan2(C[:, 1] - D[:, 1], C[:, 0] - D[:, 0]) - rocker_offset
    off = np.remainder(rocker - scales.rocker(desired) + math.pi, math.tau) - math.pi
    error = off * per_radian
    feasible = np.asarray(motion.feasible, dtype=bool)
    generated = desired + error
    k = int(np.argmax(np.where(feasible, np.abs(error), -1.0)))
    return {
        "max": float(abs(error[k])) if feasible.any() else None,
        "at_x": float(x[k]) if feasible.any() else None,
        "max_output_angle_deg": math.degrees(float(abs(off[k]))) if feasible.any() else None,
        "reached": bool(feasible.all()),
        "x": [float(v) for v in x],
        "y_desired": [float(v) for v in desired],
        "y_generated": [
            float(v) if ok else None for v, ok in zip(generated, feasible, strict=True)
        ],
        "error": [float(v) if ok else None for v, ok in zip(error, feasible, strict=True)],
    }


def _quick_return(task: QuickReturnTask) -> JSON:
    design = synthesise_quick_return(task)
    a, b, c, d = design.lengths
    A, D = 0j, design.D
    stretched_angle = _angle(design.stretched)  # the crank points at C, stretched out
    folded_angle = _angle(-design.folded)  # the crank points away from C, folded back
    # Pose at the limit from which the counter-clockwise crank makes the slow stroke.
    if ccw_turn(stretched_angle, folded_angle) > math.pi:
        order = (
            ("stretched", stretched_angle, design.stretched),
            ("folded", folded_angle, design.folded),
        )
    else:
        order = (
            ("folded", folded_angle, design.folded),
            ("stretched", stretched_angle, design.stretched),
        )
    first_angle, first_C = order[0][1], order[0][2]
    points = {"A": A, "B": a * rotor(first_angle), "C": first_C, "D": D}
    document = four_bar_document(points, 1.0, "synthesised quick-return crank-rocker", False)
    size = parse_linkage(document).size
    found = travel(document)
    checks: list[JSON] = []
    rocker_angles = []
    for name, angle, limit in order:
        analysis = analysed_at(document, angle, ("position", "velocity"))
        at = position_of(analysis, "C")
        rocker = analysis.links["rocker"]
        rocker_angles.append(_angle(at - D))
        error = abs(at - limit)
        checks.append(
            {
                "limit": name,
                "driver_angle_deg": math.degrees(angle),
                "error": error,
                "reached": error <= REACHED * size,
                "rocker_angle_deg": math.degrees(_angle(at - D)),
                "rocker_omega": rocker.omega,
            }
        )
    slow = ccw_turn(order[0][1], order[1][1])
    mu = np.minimum(found.transmission_angle, math.pi - found.transmission_angle)
    k = int(np.argmin(mu))
    passed = passage([order[0][1], order[1][1]], found)
    defects = defects_fields(found, passed, [ch["error"] for ch in checks], size)
    warnings = _defect_sentences(defects, checks, "limit position")
    if math.degrees(float(mu[k])) < MIN_TRANSMISSION_DEG:
        warnings.append(
            f"the transmission angle falls to {math.degrees(float(mu[k])):.1f} deg (below "
            f"{MIN_TRANSMISSION_DEG:g} deg) at crank angle "
            f"{math.remainder(math.degrees(float(found.driver_angle[k])), 360.0):.1f} deg: the "
            "best crank pivot on the construction's arc cannot do better for this time ratio "
            "and swing"
        )
    return {
        "task": "quick_return",
        "scene": document,
        "dimensions": {
            "ground": d,
            "crank": a,
            "coupler": b,
            "rocker": c,
            "grashof": found.grashof,
        },
        "construction": {
            "alpha_deg": math.degrees(design.alpha),
            "limit_positions": {"stretched": _xy(design.stretched), "folded": _xy(design.folded)},
            "choice": (
                "the crank pivot A is taken on the arc through C1 and C2 that sees the chord "
                "under alpha where the smallest transmission angle over a revolution is largest "
                f"({math.degrees(design.min_transmission):.2f} deg)"
            ),
        },
        "checks": checks,
        "time_ratio": slow / (math.tau - slow),
        "swing_deg": math.degrees(
            abs(math.remainder(rocker_angles[1] - rocker_angles[0], math.tau))
        ),
        "defects": defects,
        "transmission_angle": {
            "min_deg": math.degrees(float(mu[k])),
            "at_driver_angle_deg": math.degrees(float(found.driver_angle[k])),
        },
        "warnings": warnings,
    }


def synthesize(task: Any) -> SynthesisResult:
    """The four-bar for a synthesis task (a motion, function or quick_return document; POST
    /synthesis), with its checks, defects and warnings from the solver's own analysis.
    ``InvalidScene`` (or ``InvalidExpression`` for the function) says why a task has no
    answer."""
    parsed = parse_task(task)
    if isinstance(parsed, MotionTask):
        return SynthesisResult(_motion(parsed))
    if isinstance(parsed, FunctionTask):
        return SynthesisResult(_function(parsed))
    return SynthesisResult(_quick_return(parsed))

"""The synthesis families (docs/SYNTHESIS.md): exercises built on a synthesis task, not a scene.

An exercise of these types carries a task document of POST /synthesis (``"task": "function"``
or ``"motion"``) where the others carry a scene, and its paths point into the /synthesis body
of that task: ``freudenstein.K1``, ``dimensions.crank``, ``scene.points.A.0`` (the fixed pivot
A of the returned linkage), ``construction.poles.P12.1``. The draft's ``check`` receives that
body: a drawn task is kept only when the returned linkage has no defect (it reaches every
precision position or point on one assembly, in order), no warning (transmission angle, far
pivot), and links in proportion; a task the solver refuses (Freudenstein's equations singular,
b^2 <= 0, collinear places) is drawn again, like any ill-posed draft (``generation.build``: a
bounded number of draws, the generator seeded by the id). As /synthesis verifies its linkage by
a sweep (a tenth of a second), a draw first screens its candidates by the design alone (the
construction or Freudenstein's equation, no analysis; at most ``SCREEN_DRAWS`` of them): the
lengths a Grashof crank-rocker in proportion, the fixed pivots near the positions. A motion
draft also foresees its answers from its design (``Draft.foreseen``: the fixed pivots and the
pole, the numbers /synthesis writes), so that one whose answers coincide (a ground drawn level:
A_y = D_y) is refused before its linkage is verified.
"""

from __future__ import annotations

import math
import random
from collections.abc import Mapping, Sequence
from typing import Any

from solver.errors import KinematicsError
from solver.exercises.families import asked_latex, four_bar_values, givens_latex, num, pick
from solver.exercises.model import Asked, Draft
from solver.kinematics.four_bar import extreme_transmission_angles, grashof_class
from solver.synthesis import parse_task
from solver.synthesis.answer import designed_motion
from solver.synthesis.function import design_function
from solver.synthesis.motion import (
    bisector_offset,
    cross,
    in_coupler,
    in_pose,
    rotor,
    synthesise_motion,
)
from solver.synthesis.task import FunctionTask, MotionTask, Pose
from solver.synthesis.verify import MIN_TRANSMISSION_DEG
from solver.teaching.presets import build_preset

SCREEN_DRAWS = 200  # cheap draws (the design alone, no analysis) before a candidate is returned
CRANK_ROCKER = "Grashof crank-rocker"
MAX_PROPORTION = 6.0  # the longest link (ground included) over the shortest
MAX_PIVOT_DISTANCE = 5.0  # a fixed pivot's distance from P1, in coupler lengths (BC)
MIN_LINK_TURN_DEG = 15.0  # two positions: the crank's and the rocker's turn between them

# (the function in the task's language, its LaTeX, the x range)
_FUNCTIONS: tuple[tuple[str, str, tuple[float, float]], ...] = (
    ("x^2", "x^2", (1.0, 2.0)),
    ("x^2", "x^2", (0.0, 1.0)),
    ("x^3", "x^3", (1.0, 2.0)),
    ("x^1.5", "x^{1.5}", (1.0, 3.0)),
    ("sqrt(x)", r"\sqrt{x}", (1.0, 4.0)),
    ("1/x", r"1/x", (1.0, 2.0)),
)
_HARDER_FUNCTIONS: tuple[tuple[str, str, tuple[float, float]], ...] = (
    ("log(x)", r"\ln x", (1.0, 2.0)),
    ("exp(x)", r"e^x", (0.0, 1.0)),
    ("sin(x)", r"\sin x", (0.0, 1.5)),
    ("1/x^2", r"1/x^2", (1.0, 2.0)),
)
_FUNCTION_WORDS = {"log(x)": "ln(x) (the natural logarithm)", "exp(x)": "e^x"}


def _dimensionless(key: str, label: str, symbol: str) -> Asked:
    return Asked(key, label, "1", f"freudenstein.{key}", symbol)


def _length(key: str, link: str, label: str) -> Asked:
    return Asked(key, f"length of the {label}", "m", f"dimensions.{link}", key)


FREUDENSTEIN_ASKED = (
    _dimensionless("K1", "Freudenstein's coefficient K1 = d/a", "K_1"),
    _dimensionless("K2", "Freudenstein's coefficient K2 = d/c", "K_2"),
    _dimensionless("K3", "Freudenstein's coefficient K3", "K_3"),
)
LENGTHS_ASKED = (
    _length("a", "crank", "crank AB (a)"),
    _length("b", "coupler", "coupler BC (b)"),
    _length("c", "rocker", "rocker DC (c)"),
)


def _screened(draw: Any, passes: Any, rng: random.Random, difficulty: str) -> Draft:
    """The first of up to ``SCREEN_DRAWS`` drafts of ``draw`` whose task ``passes`` the cheap
    test of its design (a task the design refuses fails it), else the last one drawn."""
    for _ in range(SCREEN_DRAWS):
        draft: Draft = draw(rng, difficulty)
        try:
            if passes(parse_task(draft.scene)):
                return draft
        except KinematicsError:
            continue
    return draft


def _crank_rocker(ground: float, crank: float, coupler: float, rocker: float) -> bool:
    """A Grashof crank-rocker (the crank turns fully), its links in proportion, its
    transmission angle at least MIN_TRANSMISSION_DEG over the revolution."""
    lengths = (ground, crank, coupler, rocker)
    if grashof_class(*lengths) != CRANK_ROCKER or _in_proportion(lengths) is not None:
        return False
    return all(_transmits(mu) for mu in extreme_transmission_angles(crank, coupler, rocker, ground))


def _transmits(mu: float) -> bool:
    """min(mu, 180 - mu) at least MIN_TRANSMISSION_DEG."""
    return math.degrees(min(float(mu), math.pi - float(mu))) >= MIN_TRANSMISSION_DEG


def _in_proportion(lengths: Sequence[float]) -> str | None:
    if max(lengths) > MAX_PROPORTION * min(lengths):
        shown = ", ".join(f"{v:.3g}" for v in lengths)
        return f"links out of proportion ({shown} m)"
    return None


def _function_check(body: Any) -> str | None:
    """A function generator that closes over the whole input range on one assembly, reaches
    every precision point, and whose only warning may be a crank that rocks (harmless here)."""
    defects = body["defects"]
    if defects["branch"] or not body["structural_error"]["reached"]:
        return "the linkage does not follow the function over the range on one assembly"
    if len(body["warnings"]) != int(defects["grashof"]):
        return "; ".join(body["warnings"])
    d = body["dimensions"]
    return _in_proportion([d["ground"], d["crank"], d["coupler"], d["rocker"]])


def _ranges(rng: random.Random, difficulty: str) -> tuple[list[float], list[float]]:
    """The crank's and the rocker's angle ranges (deg, multiples of 15): the crank turning 150
    to 240 deg while the rocker swings 30 to 60 deg, the rocker's range starting 45 to 135 deg
    from the crank's, or that plus 180 (where most draws give a Grashof crank-rocker that
    transmits well); decreasing ranges at challenging."""
    start = pick(rng, 0.0, 120.0, 15.0)
    inputs = [start, start + pick(rng, 150.0, 240.0, 15.0)]
    start = (start + pick(rng, 45.0, 135.0, 15.0) + (180.0 if rng.random() < 0.5 else 0.0)) % 360
    outputs = [start, start + pick(rng, 30.0, 60.0, 15.0)]
    if difficulty == "challenging":
        if rng.random() < 0.5:
            inputs.reverse()
        if rng.random() < 0.5:
            outputs.reverse()
    return inputs, outputs


def _one_assembly(places: Sequence[tuple[complex, complex]], D: complex) -> bool:
    """The coupler BC and the rocker DC meet at C with the same sense at every (B, C)."""
    return len({cross(B - C, D - C) > 0 for B, C in places}) == 1


def _function_passes(task: Any) -> bool:
    assert isinstance(task, FunctionTask)
    design = design_function(task)
    D = complex(task.ground_length, 0.0)
    # a signed length along the link angle is the link pointing the other way
    places = [
        (design.a * rotor(float(t2)), D + design.c * rotor(float(t4)))
        for t2, t4 in zip(design.crank, design.rocker, strict=True)
    ]
    lengths = (task.ground_length, abs(design.a), design.b, abs(design.c))
    return _one_assembly(places, D) and _crank_rocker(*lengths)


def function_generator(rng: random.Random, difficulty: str) -> Draft:
    """Freudenstein's K1, K2, K3 (from standard on also the link lengths a, b, c) of a function
    generator at three precision points: given at basic, Chebyshev spacing from standard on; the
    design a Grashof crank-rocker (``_screened``)."""
    return _screened(_function_draft, _function_passes, rng, difficulty)


def _function_draft(rng: random.Random, difficulty: str) -> Draft:
    functions = _FUNCTIONS + (_HARDER_FUNCTIONS if difficulty == "challenging" else ())
    function, function_tex, x_range = rng.choice(functions)
    inputs, outputs = _ranges(rng, difficulty)
    ground = pick(rng, 0.1, 0.3, 0.05)
    x0, xf = x_range
    task: dict[str, Any] = {
        "task": "function",
        "function": function,
        "x_range": list(x_range),
        "input_range_deg": inputs,
        "output_range_deg": outputs,
        "ground_length": ground,
    }
    if difficulty == "basic":  # given precision points, a tenth of the range in from the ends
        span = xf - x0
        task["precision_points"] = [round(x0 + span * f, 10) for f in (0.1, 0.5, 0.9)]
        where = "at the precision points x = " + ", ".join(num(x) for x in task["precision_points"])
    else:
        task["precision_points"] = 3
        where = "at three precision points with Chebyshev spacing"
    asked = FREUDENSTEIN_ASKED + (LENGTHS_ASKED if difficulty != "basic" else ())
    goal = "K1, K2 and K3" if difficulty == "basic" else (
        "K1, K2 and K3, then the lengths a, b and c (positive: a negative K is a link pointing "
        "the other way)")  # fmt: skip
    words = _FUNCTION_WORDS.get(function, function)
    text = (
        f"A four-bar ABCD (crank AB = a, coupler BC = b, rocker DC = c, ground AD = d = "
        f"{num(ground)} m) is to generate y = {words} for {num(x0)} <= x <= {num(xf)}. The "
        f"crank's angle theta_2 maps x linearly onto {num(inputs[0])} to {num(inputs[1])} deg, "
        f"the rocker's angle theta_4 maps y onto {num(outputs[0])} to {num(outputs[1])} deg "
        f"(f({num(x0)}) to the first end), both measured counter-clockwise from the ground line "
        f"A to D. Write Freudenstein's equation K1 cos(theta_4) - K2 cos(theta_2) + K3 = "
        f"cos(theta_2 - theta_4), K1 = d/a, K2 = d/c, K3 = (a^2 - b^2 + c^2 + d^2)/(2ac), "
        f"{where}, and find {goal}."
    )
    givens = [
        ("d", ground, "m"),
        (r"x_0", x0, ""),
        (r"x_f", xf, ""),
        (r"\theta_{2s}", inputs[0], "deg"),
        (r"\theta_{2f}", inputs[1], "deg"),
        (r"\theta_{4s}", outputs[0], "deg"),
        (r"\theta_{4f}", outputs[1], "deg"),
    ]
    latex = (
        f"y = {function_tex},\\; " + givens_latex(givens) + r"\\"
        r"K_1 \cos\theta_4 - K_2 \cos\theta_2 + K_3 = \cos(\theta_2 - \theta_4)\\"
        + asked_latex(asked)
    )
    return Draft(
        "Function generator: Freudenstein's equation",
        text,
        latex,
        task,
        asked,
        {"1": 1.0, "m": ground},
        _function_check,
    )


# --- motion generation ---------------------------------------------------------------------------


def _xy_asked(key: str, label: str, path: str, symbol: str) -> tuple[Asked, Asked]:
    return (
        Asked(f"{key}_x", f"x of {label}", "m", f"{path}.0", f"x_{{{symbol}}}"),
        Asked(f"{key}_y", f"y of {label}", "m", f"{path}.1", f"y_{{{symbol}}}"),
    )


PIVOTS_ASKED = (
    *_xy_asked("A", "the fixed pivot A (of B)", "scene.points.A", "A"),
    *_xy_asked("D", "the fixed pivot D (of C)", "scene.points.D", "D"),
)
POLE_ASKED = _xy_asked("P12", "the pole P12", "construction.poles.P12", "P_{12}")


def _designed(task: Mapping[str, Any]) -> dict[str, Any]:
    """The part of a motion task's /synthesis body its design fixes (the fixed pivots, the
    pole): ``Draft.foreseen``."""
    parsed = parse_task(task)
    assert isinstance(parsed, MotionTask)
    return designed_motion(parsed, synthesise_motion(parsed))


def _motion_check(body: Any) -> str | None:
    """A motion generator without defects (every position reached, on one assembly, in order,
    the crank turning fully) or warnings, its fixed pivots near the positions."""
    if any(body["defects"][k] for k in ("branch", "order", "grashof")) or body["warnings"]:
        return "; ".join(body["warnings"]) or "a defect"
    points = body["scene"]["points"]
    coupler = math.dist(points["B"], points["C"])
    first = body["construction"]["places"]["P"][0]
    for pivot in ("A", "D"):
        if math.dist(points[pivot], first) > MAX_PIVOT_DISTANCE * coupler:
            return f"the fixed pivot {pivot} is far from the positions"
    d = body["dimensions"]
    return _in_proportion([d["ground"], d["crank"], d["coupler"], d["rocker"]])


def _point(rng: random.Random, x: tuple[float, float], y: tuple[float, float]) -> list[float]:
    """A point with coordinates in whole centimetres within the given ranges (m)."""
    return [pick(rng, x[0], x[1], 0.01), pick(rng, y[0], y[1], 0.01)]


def _plus(p: Sequence[float], q: Sequence[float]) -> list[float]:
    return [round(p[0] + q[0], 10), round(p[1] + q[1], 10)]


def _positions_text(positions: Sequence[Mapping[str, Any]]) -> str:
    return "; ".join(
        f"P{k + 1} = ({num(p['point'][0])}, {num(p['point'][1])}) m at {num(p['angle_deg'])} deg"
        for k, p in enumerate(positions)
    )


def _motion_passes(task: Any) -> bool:
    assert isinstance(task, MotionTask)
    design = synthesise_motion(task)
    size = abs(design.C - design.B)
    if max(abs(design.A - design.P), abs(design.D - design.P)) > MAX_PIVOT_DISTANCE * size:
        return False
    lengths = [abs(design.D - design.A), abs(design.B - design.A), size, abs(design.C - design.D)]
    if not _one_assembly([(t["B"], t["C"]) for t in design.targets], design.D):
        return False
    return _crank_rocker(*lengths)


def fixed_pivots(rng: random.Random, difficulty: str) -> Draft:
    """The fixed pivots A and D (the centre points) of a four-bar whose coupler passes through
    three positions with its moving pivots B1, C1 given (basic: the first at angle 0); at
    challenging also the pole P12; the design a Grashof crank-rocker with its pivots near the
    positions (``_screened``)."""
    return _screened(_motion_draft, _motion_passes, rng, difficulty)


def _poses(
    rng: random.Random, count: int
) -> tuple[list[dict[str, Any]], list[list[float]], tuple[complex, complex]]:
    """``count`` poses of the coupler of a drawn Grashof crank-rocker (``four_bar_values``, moved
    off the origin) at crank angles 40 to 70 deg apart: its point P (m) and the direction of BC
    (deg), rounded to millimetres and whole degrees; B, C at the first pose, rounded; and its
    fixed pivots A, D (moved, not rounded)."""
    values = four_bar_values(rng, "standard", False, False)
    # P off the line BC
    values |= {"coupler_point_u": pick(rng, 0.1, 0.3, 0.05),
               "coupler_point_v": pick(rng, 0.1, 0.25, 0.05)}  # fmt: skip
    shift = _point(rng, (0.1, 0.5), (0.1, 0.5))
    crank = pick(rng, 0.0, 345.0, 15.0)
    positions: list[dict[str, Any]] = []
    for k in range(count):
        points = build_preset("four_bar", {**values, "crank_angle_deg": crank % 360.0})["points"]
        b, c, p = (points[name] for name in ("B", "C", "P"))
        angle = math.degrees(math.atan2(c[1] - b[1], c[0] - b[0]))
        point = [round(p[0] + shift[0], 3), round(p[1] + shift[1], 3)]
        positions.append({"point": point, "angle_deg": float(round(angle))})
        if k == 0:
            pivots = [[round(q[0] + shift[0], 3), round(q[1] + shift[1], 3)] for q in (b, c)]
            fixed = tuple(complex(q[0] + shift[0], q[1] + shift[1])
                          for q in (points["A"], points["D"]))  # fmt: skip
        crank += pick(rng, 40.0, 70.0, 5.0)
    return positions, pivots, (fixed[0], fixed[1])


POLE_SENTENCE = " Find also the pole P12 of the coupler's displacement from position 1 to 2."


def _pose_givens(
    positions: Sequence[Mapping[str, Any]], b1: Sequence[float], c1: Sequence[float]
) -> list[tuple[str, float, str]]:
    """The givens of a motion task: each position's P and angle, then B1 and C1."""
    givens: list[tuple[str, float, str]] = []
    for k, p in enumerate(positions, start=1):
        givens += [(f"x_{{P{k}}}", p["point"][0], "m"), (f"y_{{P{k}}}", p["point"][1], "m"),
                   (f"\\varphi_{k}", p["angle_deg"], "deg")]  # fmt: skip
    pivots = [("x_{B1}", b1[0], "m"), ("y_{B1}", b1[1], "m"), ("x_{C1}", c1[0], "m"),
              ("y_{C1}", c1[1], "m")]  # fmt: skip
    return [*givens, *pivots]


def _from_zero(positions: Sequence[Mapping[str, Any]]) -> list[dict[str, Any]]:
    """The positions turned so that the first is at angle 0: the turns are the angles."""
    return [{**p, "angle_deg": p["angle_deg"] - positions[0]["angle_deg"]} for p in positions]


def _motion_draft(rng: random.Random, difficulty: str) -> Draft:
    positions, (b1, c1), _ = _poses(rng, 3)
    if difficulty == "basic":
        positions = _from_zero(positions)
    task = {"task": "motion", "positions": positions, "moving_pivots": [b1, c1]}
    asked = PIVOTS_ASKED + (POLE_ASKED if difficulty == "challenging" else ())
    pole = POLE_SENTENCE if difficulty == "challenging" else ""
    text = (
        "A coupler carries a point P and the pivots B and C. It is to pass through three "
        f"positions, each given by P and the coupler's angle (counter-clockwise from the x "
        f"axis): {_positions_text(positions)}. In the first position B1 = ({num(b1[0])}, "
        f"{num(b1[1])}) m and C1 = ({num(c1[0])}, {num(c1[1])}) m. Find the fixed pivots A "
        f"(the centre of B's circle) and D (that of C's) of the four-bar ABCD that guides "
        f"it.{pole}"
    )
    latex = givens_latex(_pose_givens(positions, b1, c1)) + r"\\" + asked_latex(asked)
    coupler = math.dist(b1, c1)
    return Draft(
        "Motion generation: fixed pivots for three positions",
        text,
        latex,
        task,
        asked,
        {"m": coupler},
        _motion_check,
        lambda: _designed(task),
    )


def two_positions(rng: random.Random, difficulty: str) -> Draft:
    """The fixed pivots A and D of a four-bar whose coupler passes through two positions, its
    moving pivots B1, C1 given and each fixed pivot's offset along its perpendicular bisector
    from the chord's midpoint (``bisector_offsets``: the free choice of two positions, here
    the drawn crank-rocker's own, rounded to millimetres); basic: the first position at angle
    0; at challenging also the pole P12; the design screened as for three positions."""
    return _screened(_two_positions_draft, _two_positions_pass, rng, difficulty)


def _two_positions_pass(task: Any) -> bool:
    """``_motion_passes``, and each link turning at least ``MIN_LINK_TURN_DEG`` between the two
    positions, 2 atan(|chord| / (2 |d|)): a pivot far out on the bisector of a short chord moves
    a lot with the last digit of the chord's direction (ill-conditioned for a hand solution)."""
    assert isinstance(task, MotionTask) and task.bisector_offsets is not None
    design = synthesise_motion(task)
    for name, offset in zip("BC", task.bisector_offsets, strict=True):
        chord = abs(design.targets[1][name] - design.targets[0][name])
        if 2.0 * math.degrees(math.atan2(chord, 2.0 * abs(offset))) < MIN_LINK_TURN_DEG:
            return False
    return _motion_passes(task)


def _two_positions_draft(rng: random.Random, difficulty: str) -> Draft:
    positions, (b1, c1), (A, D) = _poses(rng, 2)
    if difficulty == "basic":
        positions = _from_zero(positions)
    poses = [Pose(complex(*p["point"]), math.radians(p["angle_deg"])) for p in positions]
    offsets = []
    for first, fixed in ((complex(*b1), A), (complex(*c1), D)):
        second = in_pose(poses[1], in_coupler(poses[0], first))
        offsets.append(round(bisector_offset(first, second, fixed), 3))
    task = {"task": "motion", "positions": positions, "moving_pivots": [b1, c1],
            "bisector_offsets": offsets}  # fmt: skip
    asked = PIVOTS_ASKED + (POLE_ASKED if difficulty == "challenging" else ())
    pole = POLE_SENTENCE if difficulty == "challenging" else ""
    text = (
        "A coupler carries a point P and the pivots B and C. It is to pass through two "
        f"positions, each given by P and the coupler's angle (counter-clockwise from the x "
        f"axis): {_positions_text(positions)}. In the first position B1 = ({num(b1[0])}, "
        f"{num(b1[1])}) m and C1 = ({num(c1[0])}, {num(c1[1])}) m. Two positions leave each "
        f"fixed pivot free on a perpendicular bisector: A (the centre of B's circle) is to lie "
        f"on the perpendicular bisector of B1B2 at dA = {num(offsets[0])} m from the chord's "
        f"midpoint, D (that of C's) on the bisector of C1C2 at dD = {num(offsets[1])} m, "
        "each positive to the left of the chord's direction B1 -> B2 (C1 -> C2). Find A and D "
        f"of the four-bar ABCD that guides the coupler.{pole}"
    )
    givens = [*_pose_givens(positions, b1, c1), ("d_A", offsets[0], "m"),
              ("d_D", offsets[1], "m")]  # fmt: skip
    latex = givens_latex(givens) + r"\\" + asked_latex(asked)
    return Draft(
        "Motion generation: fixed pivots for two positions",
        text,
        latex,
        task,
        asked,
        {"m": math.dist(b1, c1)},
        _motion_check,
        lambda: _designed(task),
    )

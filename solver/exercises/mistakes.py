"""Typical mistakes, made on purpose: the wrong answers a student gets, to recognise them.

Each mistake is made with the solver. A misread input (a rotation taken the other way, a crank
speed in degrees per second) is made in the scene itself, which the solver then analyses; an
answer given in degrees instead of radians is the solver's answer converted. A mistake inside
the acceleration equations (the Coriolis term left out, halved, or put on a fixed guide; a normal
term written with alpha) is made by writing the textbook's acceleration equation of the loop with
that one term wrong, every other number in it being the solver's, and solving it for the
unknowns (the equations solved right reproduce the solver's answers: tested). Every mistake is
named by its id in the catalogue (``solver.teaching.mistakes``), as the worked solutions name it.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Mapping
from dataclasses import dataclass
from typing import Any

import numpy as np

from solver.analysis.instant import LinkageAnalysis
from solver.errors import KinematicsError
from solver.exercises.answers import Solved, flywheel_request, solve_scene, value_at
from solver.exercises.model import Exercise
from solver.exercises.registry import TYPES
from solver.kinematics.relative_motion import coriolis_acceleration
from solver.kinematics.rigid import Array, perp, rigid_body_acceleration, solve_2x2
from solver.teaching.mistakes import (
    alpha_in_normal_term,
    coriolis_left_out,
    coriolis_with_omega_of,
    coriolis_without_factor_2,
    cross_order,
    cross_order_acceleration,
    typical_mistake,
)

DEGREES = 180.0 / math.pi


@dataclass(frozen=True)
class WrongAnswers:
    """One typical mistake: its id in the catalogue (``solver.teaching.mistakes``), the sentence
    that explains it, the wrong answers it gives."""

    kind: str
    sentence: str
    values: Mapping[str, float]

    def __post_init__(self) -> None:
        typical_mistake(self.kind)  # every diagnosis is an entry of the catalogue


# --- the acceleration equations of the loops, with one term open to a mistake -------------------


def _solve2(first: Array, second: Array, rhs: Array) -> tuple[float, float]:
    """x, y with x first + y second = rhs (``rigid.solve_2x2``)."""
    x, y = solve_2x2((first[0], second[0]), (first[1], second[1]), (rhs[0], rhs[1]))
    return float(x), float(y)


def rrr_alphas(
    a_B: Array, B: Array, C: Array, D: Array, omega_BC: float, omega_DC: float
) -> tuple[float, float]:
    """alpha_BC, alpha_DC from a_B + alpha_BC k x r_BC - omega_BC^2 r_BC
    = alpha_DC k x r_DC - omega_DC^2 r_DC (D fixed)."""
    r_BC, r_DC = C - B, C - D
    rhs = -a_B + omega_BC**2 * r_BC - omega_DC**2 * r_DC
    return _solve2(perp(r_BC), -perp(r_DC), rhs)


def rrp_alpha(a_B: Array, B: Array, C: Array, u: Array, omega_BC: float, extra: Array) -> float:
    """alpha_BC from a_B + alpha_BC k x r_BC - omega_BC^2 r_BC = s'' u + extra: C slides along
    u on a fixed guide; ``extra`` is a Coriolis term written there by mistake (0 when right)."""
    r_BC = C - B
    alpha, _ = _solve2(perp(r_BC), -u, -a_B + omega_BC**2 * r_BC + extra)
    return alpha


def lever_alpha(
    a_pin: Array, pin: Array, pivot: Array, u: Array, omega: float, v_rel: Array, factor: float
) -> float:
    """alpha of a lever turning about a fixed pivot whose slot (direction u) carries the pin:
    a_pin = alpha k x r - omega^2 r + s'' u + factor 2 omega k x v_rel, r = pin - pivot
    (``factor`` 1 is right; 0 leaves the Coriolis term out, 1/2 forgets its 2)."""
    r = pin - pivot
    rhs = a_pin + omega**2 * r - factor * coriolis_acceleration(np.asarray(omega), v_rel)
    alpha, _ = _solve2(perp(r), u, rhs)
    return alpha


def _rigid(a_A: Array, omega: float, alpha: float, r_AB: Array) -> Array:
    """The solver's a_B = a_A + alpha x r_AB - omega^2 r_AB at one instant."""
    return rigid_body_acceleration(a_A, np.asarray(omega), np.asarray(alpha), r_AB)


# --- helpers over the solver's results -----------------------------------------------------------


class Numbers:
    """The solver's numbers of one exercise, by name."""

    def __init__(self, solved: Solved) -> None:
        assert isinstance(solved.analysis, LinkageAnalysis)
        self.scene = solved.scene
        self.a = solved.analysis
        self.driver = self.a.links[solved.scene.drivers[0].link]  # type: ignore[union-attr]

    def p(self, name: str) -> Array:
        value = self.a.points[name].position
        assert value is not None
        return value

    def vel(self, name: str) -> Array:
        value = self.a.points[name].velocity
        assert value is not None
        return value

    def acc(self, name: str) -> Array:
        value = self.a.points[name].acceleration
        assert value is not None
        return value

    def omega(self, link: str) -> float:
        value = self.a.links[link].omega
        assert value is not None
        return value

    def alpha(self, link: str) -> float:
        value = self.a.links[link].alpha
        assert value is not None
        return value

    def crank_pin_written_with_alpha(self, pivot: str, pin: str) -> Array:
        """a_pin with the normal term written alpha r instead of omega^2 r."""
        r = self.p(pin) - self.p(pivot)
        return alpha_in_normal_term(self.acc(pivot), self.omega_driver, self.alpha_driver, r)

    @property
    def omega_driver(self) -> float:
        assert self.driver.omega is not None
        return self.driver.omega

    @property
    def alpha_driver(self) -> float:
        assert self.driver.alpha is not None
        return self.driver.alpha


def _components(key: str, vector: Array) -> dict[str, float]:
    return {f"{key}_x": float(vector[0]), f"{key}_y": float(vector[1])}


_ALPHA_NORMAL = (
    "This is what you get with the normal term of the crank pin written with alpha: the normal "
    "(centripetal) acceleration is omega^2 r, pointing to the centre; alpha gives the tangential "
    "term alpha x r."
)


# --- per family ----------------------------------------------------------------------------------


def _four_bar(n: Numbers) -> list[WrongAnswers]:
    if n.alpha_driver == 0.0 or n.alpha_driver == n.omega_driver**2:
        return []
    a_B = n.crank_pin_written_with_alpha("A", "B")
    B, C, D = n.p("B"), n.p("C"), n.p("D")
    w2, w3 = n.omega("coupler"), n.omega("rocker")
    a2, a3 = rrr_alphas(a_B, B, C, D, w2, w3)
    values = {"alpha_coupler": a2, "alpha_rocker": a3}
    values |= _components("a_C", _rigid(a_B, w2, a2, C - B))
    if "P" in n.a.points:
        values |= _components("a_P", _rigid(a_B, w2, a2, n.p("P") - B))
    return [WrongAnswers("alpha_in_normal_term", _ALPHA_NORMAL, values)]


def _coupler_after(n: Numbers, a_B: Array, extra: Array) -> dict[str, float]:
    """The coupler BC(D) and its slider C on the fixed guide from a (possibly wrong) a_B."""
    B, C = n.p("B"), n.p("C")
    w = n.omega("coupler")
    u = np.array([1.0, 0.0])
    alpha = rrp_alpha(a_B, B, C, u, w, extra)
    values = {"alpha_coupler": alpha}
    values["a_C_x"] = float(_rigid(a_B, w, alpha, C - B)[0])
    if "D" in n.a.points:
        values |= _components("a_D", _rigid(a_B, w, alpha, n.p("D") - B))
    return values


def _slider(n: Numbers) -> list[WrongAnswers]:
    joint = n.a.joints[0]
    v_rel = joint.relative_velocity
    extra = coriolis_with_omega_of(n.omega("coupler"), v_rel)
    out = [
        WrongAnswers(
            "coriolis_on_fixed_guide",
            "This is what you get with a Coriolis term 2 omega x v_rel at the slider C: its guide "
            "is fixed (the ground does not turn), so there is no Coriolis term there, however the "
            "rod turns.",
            _coupler_after(n, n.acc("B"), extra),
        )
    ]
    if n.alpha_driver not in (0.0, n.omega_driver**2):
        a_B = n.crank_pin_written_with_alpha("A", "B")
        out.append(
            WrongAnswers("alpha_in_normal_term", _ALPHA_NORMAL, _coupler_after(n, a_B, 0 * extra))
        )
    return out


def _lever_mistakes(
    n: Numbers, crank_pivot: str, pivot: str, after: Callable[[float], Any]
) -> list[WrongAnswers]:
    """Coriolis left out or halved at the pin A in the lever's slot, and the crank pin's normal
    term written with alpha; ``after(alpha_lever)`` gives the further wrong answers."""
    joint = n.a.joints[0]
    assert joint.coriolis_acceleration is not None
    A, C = n.p("A"), n.p(pivot)
    speed = float(np.hypot(*joint.relative_velocity))
    if speed == 0.0:
        return []
    u = joint.relative_velocity / speed
    w = n.omega("lever")

    def wrong(a_pin: Array, factor: float) -> dict[str, float]:
        alpha = lever_alpha(a_pin, A, C, u, w, joint.relative_velocity, factor)
        return {"alpha_lever": alpha, **after(alpha)}

    a_cor = joint.coriolis_acceleration
    out = [
        WrongAnswers(
            "coriolis_left_out",
            "This is what you get with the Coriolis acceleration left out: the slot turns with "
            "the lever, so the sliding block has a Coriolis term 2 omega_lever x v_rel.",
            {**wrong(n.acc("A"), 0.0), **_components("a_cor_A", coriolis_left_out(a_cor))},
        ),
        WrongAnswers(
            "coriolis_without_factor_2",
            "This is what you get with omega x v_rel for the Coriolis term: it is "
            "2 omega_lever x v_rel (half from the relative velocity turning with the slot, half "
            "from the slot carrying the block to faster places).",
            {
                **wrong(n.acc("A"), 0.5),
                **_components("a_cor_A", coriolis_without_factor_2(a_cor)),
            },
        ),
    ]
    if n.alpha_driver not in (0.0, n.omega_driver**2):
        a_pin = n.crank_pin_written_with_alpha(crank_pivot, "A")
        out.append(WrongAnswers("alpha_in_normal_term", _ALPHA_NORMAL, wrong(a_pin, 1.0)))
    return out


def _lever(n: Numbers) -> list[WrongAnswers]:
    return _lever_mistakes(n, "O", "C", lambda alpha: {})


def _quick_return(n: Numbers) -> list[WrongAnswers]:
    O4, B, C = n.p("O4"), n.p("B"), n.p("C")
    w_lever, w_rod = n.omega("lever"), n.omega("rod")

    def ram(alpha_lever: float) -> dict[str, float]:
        a_B = _rigid(np.zeros(2), w_lever, alpha_lever, B - O4)
        alpha_rod = rrp_alpha(a_B, B, C, np.array([1.0, 0.0]), w_rod, np.zeros(2))
        return {"a_C_x": float(_rigid(a_B, w_rod, alpha_rod, C - B)[0])}

    return _lever_mistakes(n, "O2", "O4", ram)


def _moving_point(solved: Solved) -> list[WrongAnswers]:
    assert isinstance(solved.analysis, LinkageAnalysis)
    m = solved.analysis.moving_points["M"]
    a, cor = np.asarray(m.acceleration), np.asarray(m.coriolis_acceleration)
    return [
        WrongAnswers(
            "coriolis_left_out",
            "This is what you get with the Coriolis acceleration left out: M moves relative to a "
            "turning body, so a = a_transport + a_relative + 2 omega x v_rel.",
            {**_components("a_M", a - cor), **_components("a_cor_M", coriolis_left_out(cor))},
        ),
        WrongAnswers(
            "coriolis_without_factor_2",
            "This is what you get with omega x v_rel for the Coriolis term: it is 2 omega x v_rel.",
            {
                **_components("a_M", a - coriolis_without_factor_2(cor)),
                **_components("a_cor_M", coriolis_without_factor_2(cor)),
            },
        ),
    ]


def _cross_order(exercise: Exercise, solved: Solved) -> list[WrongAnswers]:
    """The cross products of the rigid-body formula in the wrong order for each asked point X of
    a turning link: v_X = v_Q + r_QX x omega (``cross_order``) and a_X = a_Q + r_QX x alpha +
    (r_QX x omega) x omega (``cross_order_acceleration``), Q the link's first point (its pivot
    or the joint it is driven through: B of the coupler BC), every other value the solver's."""
    n = Numbers(solved)
    links = exercise.scene["links"]
    values: dict[str, float] = {}
    for a in exercise.asked:
        root, point, field, axis = [*a.path.split("."), "", "", ""][:4]
        if root != "points" or field not in ("velocity", "acceleration"):
            continue
        link = next(
            (k for k, v in links.items() if not v.get("ground") and point in v["points"][1:]),
            None,
        )
        if link is None:
            continue
        pivot = links[link]["points"][0]
        r = n.p(point) - n.p(pivot)
        if field == "velocity":
            wrong = cross_order(n.vel(pivot), n.omega(link), r)
        else:
            wrong = cross_order_acceleration(n.acc(pivot), n.omega(link), n.alpha(link), r)
        values[a.key] = float(wrong[int(axis)])
    if not values:
        return []
    return [
        WrongAnswers(
            "cross.order",
            "This is what you get with the cross product in the wrong order: the relative "
            "velocity of a point of a turning link is omega x r (r from the known point to the "
            "asked one), its tangential acceleration alpha x r; r x omega and r x alpha reverse "
            "them.",
            values,
        )
    ]


# --- misread inputs, made in the scene -----------------------------------------------------------


def _with_drivers(
    scene: Mapping[str, Any], change: Callable[[float], float], law: str
) -> list[tuple[str, dict[str, Any]]]:
    """Variants of a scene with its given rotations changed, each with the rotation's name: the
    planar drivers all at once, the spatial joints one at a time."""
    if scene.get("kind") == "spatial_chain":
        variants = []
        for k in range(len(scene["joints"])):
            joints = [dict(j) for j in scene["joints"]]
            joints[k]["rate"] = change(joints[k]["rate"])
            joints[k]["rate_dot"] = change(joints[k]["rate_dot"])
            variants.append((f"the rate of joint {joints[k]['name']}", {**scene, "joints": joints}))
        return variants
    drivers = []
    for d in scene["drivers"]:
        if "angle_law" in d:
            drivers.append({**d, "angle_law": law.format(d["angle_law"])})
        else:
            drivers.append({**d, "omega": change(d["omega"]), "alpha": change(d["alpha"])})
    names = " and ".join(f"the rotation of the {d['link']}" for d in scene["drivers"])
    return [(names, {**scene, "drivers": drivers})]


def _scene_mistakes(exercise: Exercise) -> list[WrongAnswers]:
    paths = {a.key: a.path for a in exercise.asked if not a.path.startswith("events.")}
    out = []
    for kind, change, law, sentence in (
        (
            "rotation_sign",
            lambda x: -x,
            "-({})",
            "This is what you get with {} taken the other way round: counter-clockwise is "
            "positive (about the axis by the right-hand rule), clockwise negative.",
        ),
        (
            "degrees_for_radians",
            lambda x: x * DEGREES,
            "({})*180/pi",
            "This is what you get with {} in degrees: omega and alpha enter v = omega x r and "
            "a = alpha x r - omega^2 r in rad/s and rad/s^2.",
        ),
    ):
        for name, variant in _with_drivers(exercise.scene, change, law):
            try:
                solved = solve_scene(variant)
                values = {key: value_at(solved, path) for key, path in paths.items()}
            except KinematicsError:
                continue
            out.append(WrongAnswers(kind, sentence.format(name), values))
    in_degrees = {
        a.key: exercise.answers[a.key] * DEGREES for a in exercise.asked if a.unit.startswith("rad")
    }
    if in_degrees:
        out.append(
            WrongAnswers(
                "degrees_for_radians",
                "This is the right value in degrees: the answer is asked in radians "
                "(rad/s, rad/s^2); multiply degrees by pi/180.",
                in_degrees,
            )
        )
    return out


# --- dynamics: the load terms a student leaves out, made in the scene; the flywheel's formula ----


def _variant_values(exercise: Exercise, variant: Mapping[str, Any]) -> dict[str, float]:
    """The asked values of the exercise's paths on a changed scene (the solver's)."""
    solved = solve_scene(variant)
    return {a.key: value_at(solved, a.path) for a in exercise.asked}


def _dynamics_torque(exercise: Exercise, solved: Solved) -> list[WrongAnswers]:
    scene = exercise.scene
    at_rest = [{**d, "omega": 0.0, "alpha": 0.0} for d in scene["drivers"]]
    return [
        WrongAnswers(
            "weights_left_out",
            "This is what you get without the weights: the power balance (or the equations of "
            "each link) must include m g of every link, whose power -m g . v_G is not zero.",
            _variant_values(exercise, {**scene, "gravity": [0.0, 0.0]}),
        ),
        WrongAnswers(
            "inertia_left_out",
            "This is the static answer: the inertia forces -m a_G and moments -I_G alpha of the "
            "moving links were left out (the crank turns, so the links accelerate).",
            _variant_values(exercise, {**scene, "drivers": at_rest}),
        ),
    ]


def _statics(exercise: Exercise, solved: Solved) -> list[WrongAnswers]:
    scene = exercise.scene
    if not any(scene.get("gravity", [0.0, 0.0])):
        return []
    return [
        WrongAnswers(
            "weights_left_out",
            "This is what you get without the weights: each link's m g acts at its centre and "
            "has a moment about every pivot.",
            _variant_values(exercise, {**scene, "gravity": [0.0, 0.0]}),
        )
    ]


def _friction(exercise: Exercise, solved: Solved) -> list[WrongAnswers]:
    scene = exercise.scene
    joints = [{k: v for k, v in j.items() if k != "friction"} for j in scene["joints"]]
    without = solve_scene({**scene, "joints": joints})
    values = {  # the frictionless scene has no torque_frictionless: that key is not affected
        a.key: value_at(without, a.path)
        for a in exercise.asked
        if not a.path.endswith("torque_frictionless")
    }
    return [
        WrongAnswers(
            "friction_left_out",
            "This is the torque without friction: the Coulomb force mu |N| at the slider (and "
            "the friction moment mu r |F| at the pin) resists the motion, and the driver must "
            "overcome it as well.",
            values,
        )
    ]


def _flywheel(exercise: Exercise, solved: Solved) -> list[WrongAnswers]:
    root, _, k, omega = flywheel_request(exercise)
    mean = value_at(solved, f"{root}.cycle.mean_torque")
    fluctuation = value_at(solved, f"{root}.cycle.energy_fluctuation")
    work = abs(mean) * 2.0 * math.pi
    return [
        WrongAnswers(
            "mean_torque_for_fluctuation",
            "This is the work of the mean torque over a revolution, not the energy fluctuation: "
            "the flywheel must absorb the largest swing of the integral of (M - M_mean) d phi.",
            {"energy_fluctuation": work, "flywheel_inertia": work / (k * omega**2)},
        ),
        WrongAnswers(
            "flywheel_factor_two",
            "This is twice the inertia: Delta E = I omega^2 k follows from (I/2)(omega_max^2 - "
            "omega_min^2) with omega_max - omega_min = k omega; the 1/2 does not remain.",
            {"flywheel_inertia": 2.0 * fluctuation / (k * omega**2)},
        ),
    ]


_FAMILIES: Mapping[str, Callable[[Exercise, Solved], list[WrongAnswers]]] = {
    "four_bar": lambda e, s: _four_bar(Numbers(s)),
    "slider": lambda e, s: _slider(Numbers(s)),
    "lever": lambda e, s: _lever(Numbers(s)),
    "quick_return": lambda e, s: _quick_return(Numbers(s)),
    "moving_point": lambda e, s: _moving_point(s),
    # The arm's joints are all revolute: no sliding, so no Coriolis term to get wrong.
    "spatial": lambda e, s: [],
    "dynamics_torque": _dynamics_torque,
    "flywheel": _flywheel,
    "statics": _statics,
    "friction": _friction,
}


# the planar linkages whose asked points' rates follow from the rigid-body formula
_POINT_FAMILIES = ("four_bar", "slider", "lever", "quick_return")


def typical_mistakes(exercise: Exercise) -> list[WrongAnswers]:
    """Every typical mistake that applies to the exercise, with the wrong answers it gives
    (only for the asked keys it changes)."""
    family = TYPES[exercise.id.type].mistakes
    solved = solve_scene(exercise.scene)
    made = _FAMILIES[family](exercise, solved) + _scene_mistakes(exercise)
    if family in _POINT_FAMILIES:  # last: where it gives a misread input's value, that is named
        made += _cross_order(exercise, solved)
    asked = {a.key for a in exercise.asked}
    return [
        WrongAnswers(m.kind, m.sentence, {k: v for k, v in m.values.items() if k in asked})
        for m in made
    ]


def answer_mistakes(exercise: Exercise) -> list[WrongAnswers]:
    """Mistakes in writing the answer down, for any type: a force given as the reaction on the
    other body (``action_reaction_sign``, force answers), a negative answer given as its
    magnitude (``magnitude_for_component``), the x and y components of an asked vector swapped
    (``components_swapped``)."""
    answers = exercise.answers
    reaction = {a.key: -answers[a.key] for a in exercise.asked if a.unit == "N"}
    magnitude = {k: -v for k, v in answers.items() if v < 0.0}
    swapped: dict[str, float] = {}
    for key in answers:
        twin = key[:-2] + "_y"
        if key.endswith("_x") and twin in answers:
            swapped |= {key: answers[twin], twin: answers[key]}
    made = []
    if reaction:
        made.append(WrongAnswers(
            "action_reaction_sign",
            "This is the force on the other body: the pin force asked is the one the named body "
            "exerts, and the reaction has the opposite sign.",
            reaction,
        ))  # fmt: skip
    if magnitude:
        made.append(WrongAnswers(
            "magnitude_for_component",
            "This is the magnitude of a negative answer: each component, angular velocity and "
            "acceleration is asked with its sign (the statement's sign convention), or the "
            "rotation was taken the other way round.",
            magnitude,
        ))  # fmt: skip
    if swapped:
        made.append(WrongAnswers(
            "components_swapped",
            "This is the other component's value: the x and y components swapped.",
            swapped,
        ))  # fmt: skip
    return made

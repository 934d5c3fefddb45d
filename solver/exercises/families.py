"""The kinematic exercise families, one textbook mechanism each, drawn with nice rounded inputs
(the types that use them are registered in ``solver.exercises.registry``).

A family draws a candidate (``Draft``) from a seeded ``random.Random``: the scene (a preset's,
or built as a preset would build it), what it asks, the statement, and the scales an answer is
measured against. Whether the draft is well-posed is decided by ``generate`` with the solver's
own analysis; the family only adds its own test (the Grashof class, the transmission angle).
The difficulty sets what is asked and which inputs are plain: ``basic`` turns the crank at a
constant speed and asks the first rates; ``standard`` adds points and accelerations;
``challenging`` adds an angular acceleration of the crank, offsets and further points.
"""

from __future__ import annotations

import math
import random
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from typing import Any

from solver.exercises.model import Asked, Draft
from solver.teaching.presets import build_preset

TRANSMISSION_MIN_DEG = 35.0  # the transmission angle stays within [35, 145] deg


def pick(rng: random.Random, low: float, high: float, step: float) -> float:
    """A multiple of ``step`` in [low, high], as a book would print it (no rounding noise)."""
    count = round((high - low) / step)
    return round(low + step * rng.randint(0, count), 10)


def rate(rng: random.Random, low: int, high: int, signed: bool = True) -> float:
    """A whole number in [low, high] (rad/s, rad/s^2), of either sign when ``signed``."""
    value = float(rng.randint(low, high))
    return -value if signed and rng.random() < 0.5 else value


def num(x: float) -> str:
    """A given number as printed in the statement (a zero without its sign: never "-0")."""
    return f"{x + 0.0:g}"


def polynomial(terms: Sequence[tuple[float, str]]) -> str:
    """c1 x1 + c2 x2 + ... as a lecturer writes it: "3 t - 0.05 t^2", never "+ -", zero terms
    left out (a lone 0 if all are); each term is (coefficient, its variable part)."""
    out = ""
    for coefficient, part in terms:
        if coefficient == 0.0:
            continue
        sign = "-" if coefficient < 0 else "+"
        body = f"{num(abs(coefficient))} {part}".strip()
        out = (f"-{body}" if sign == "-" else body) if not out else f"{out} {sign} {body}"
    return out or "0"


def sense(omega: float) -> str:
    return "counter-clockwise" if omega > 0 else "clockwise"


# --- asked quantities ----------------------------------------------------------------------------

_AXES = ("x", "y", "z")


def omega_of(link: str, name: str, sub: str) -> Asked:
    return Asked(
        f"omega_{link}",
        f"angular velocity of the {name} {sub.replace('_', '')}",
        "rad/s",
        f"links.{link}.omega",
        rf"\omega_{{{sub}}}",
    )


def alpha_of(link: str, name: str, sub: str) -> Asked:
    return Asked(
        f"alpha_{link}",
        f"angular acceleration of the {name} {sub.replace('_', '')}",
        "rad/s^2",
        f"links.{link}.alpha",
        rf"\alpha_{{{sub}}}",
    )


def vector_of(
    root: str, owner: str, field: str, key: str, label: str, unit: str, symbol: str, axes: str
) -> tuple[Asked, ...]:
    """The components (``axes`` among "xyz") of a vector at ``root.owner.field``; ``symbol`` is
    the LaTeX symbol and subscript, e.g. ``v_{C``, closed here with the axis: ``v_{C,x}``."""
    return tuple(
        Asked(
            f"{key}_{axis}",
            f"{label}, {axis} component",
            unit,
            f"{root}.{owner}.{field}.{_AXES.index(axis)}",
            f"{symbol},{axis}}}",
        )
        for axis in axes
    )


def velocity_of(point: str, axes: str = "xy") -> tuple[Asked, ...]:
    return vector_of(
        "points", point, "velocity", f"v_{point}", f"velocity of {point}", "m/s",
        rf"v_{{{point}", axes,
    )  # fmt: skip


def acceleration_of(point: str, axes: str = "xy") -> tuple[Asked, ...]:
    return vector_of(
        "points", point, "acceleration", f"a_{point}", f"acceleration of {point}", "m/s^2",
        rf"a_{{{point}", axes,
    )  # fmt: skip


def scales(omega: float, alpha: float, size: float) -> dict[str, float]:
    """The size of an answer in each unit for a crank turning at omega, alpha in a drawing of
    ``size`` metres."""
    rates = max(omega * omega, abs(alpha))
    return {
        "rad/s": abs(omega),
        "rad/s^2": rates,
        "m/s": abs(omega) * size,
        "m/s^2": rates * size,
        "m": size,
    }


def givens_latex(rows: Sequence[tuple[str, float, str]]) -> str:
    r"""``symbol = value\,unit`` rows, comma-separated, four to a line."""
    units = {"m": r"\,\mathrm{m}", "rad/s": r"\,\mathrm{rad/s}", "rad/s^2": r"\,\mathrm{rad/s^2}"}
    units |= {"deg": r"^\circ", "s": r"\,\mathrm{s}", "m/s^2": r"\,\mathrm{m/s^2}", "": ""}
    units["N"] = r"\,\mathrm{N}"
    items = [f"{s} = {num(v)}{units[u]}" for s, v, u in rows]
    lines = [",\\; ".join(items[k : k + 4]) for k in range(0, len(items), 4)]
    return ",\\\\".join(lines)


def asked_latex(asked: Sequence[Asked]) -> str:
    return r"\text{Find } " + ",\\; ".join(a.symbol for a in asked)


def crank_sentence(pin: str, pivot: str, omega: float, alpha: float) -> str:
    turn = f"turns {sense(omega)} at a constant {abs(omega):g} rad/s"
    if alpha != 0.0:
        speeding = "speeding up" if alpha * omega > 0 else "slowing down"
        turn = f"turns {sense(omega)} at {abs(omega):g} rad/s, {speeding} at {abs(alpha):g} rad/s^2"
    return f"The crank {pivot}{pin} {turn}."


def rates_for(rng: random.Random, difficulty: str, accelerating: bool) -> tuple[float, float]:
    """(omega, alpha) of the crank: alpha = 0 unless the difficulty wants an accelerating crank."""
    omega = rate(rng, 2, 12, signed=difficulty != "basic")
    alpha = rate(rng, 2, 30) if accelerating else 0.0
    return omega, alpha


# --- four-bar ------------------------------------------------------------------------------------


def four_bar_scene(
    rng: random.Random, difficulty: str, accelerating: bool, coupler_point: bool
) -> tuple[dict[str, Any], dict[str, float]]:
    """The scene of ``four_bar_values`` and its values."""
    v = four_bar_values(rng, difficulty, accelerating, coupler_point)
    return build_preset("four_bar", v), v


def four_bar_values(
    rng: random.Random, difficulty: str, accelerating: bool, coupler_point: bool
) -> dict[str, float]:
    """The four-bar preset's values of a Grashof crank-rocker drawn with rounded lengths
    (s + l at least 5 % of l below p + q), its crank's rates and (``coupler_point``) a coupler
    point."""
    while True:
        v = {
            "ground": pick(rng, 0.3, 0.8, 0.05),
            "crank": pick(rng, 0.08, 0.25, 0.01),
            "coupler": pick(rng, 0.3, 0.9, 0.05),
            "rocker": pick(rng, 0.2, 0.8, 0.05),
        }
        lengths = sorted(v.values())
        # crank-rocker with a margin from the change point: s + l <= p + q - 5 % of l
        if v["crank"] == lengths[0] and lengths[0] + lengths[3] <= (
            lengths[1] + lengths[2] - 0.05 * lengths[3]
        ):
            break
    step = 15.0 if difficulty == "basic" else 5.0
    v["crank_angle_deg"] = pick(rng, 0.0, 360.0 - step, step)
    v["omega"], v["alpha"] = rates_for(rng, difficulty, accelerating)
    v["assembly"] = 0.0
    if coupler_point:
        v["coupler_point_u"] = pick(rng, 0.1, 0.5, 0.05)
        v["coupler_point_v"] = pick(rng, -0.2, 0.2, 0.05)
    else:
        v["coupler_point_u"] = v["coupler_point_v"] = 0.0
    return v


def four_bar_check(analysis: Any) -> str | None:
    """Why a four-bar draft is refused (not a Grashof crank-rocker, or a transmission angle
    outside 35..145 degrees), or None."""
    loops = analysis.four_bar_loops
    if not loops or loops[0].grashof != "Grashof crank-rocker":
        return "not a Grashof crank-rocker"
    mu = math.degrees(loops[0].transmission_angle)
    if not TRANSMISSION_MIN_DEG <= mu <= 180.0 - TRANSMISSION_MIN_DEG:
        return f"transmission angle {mu:.1f} deg"
    return None


def four_bar_text(v: Mapping[str, float], goal: str, point: bool) -> tuple[str, str]:
    """The statement of a four-bar exercise (text and LaTeX givens) ending with ``goal``."""
    text = (
        f"In the four-bar linkage ABCD the fixed pivots A and D are {num(v['ground'])} m apart "
        f"(D to the right of A). The crank AB = {num(v['crank'])} m, the coupler BC = "
        f"{num(v['coupler'])} m and the rocker DC = {num(v['rocker'])} m (C above the line BD, "
        f"a Grashof crank-rocker). The crank is drawn at {num(v['crank_angle_deg'])} deg from AD. "
        + crank_sentence("B", "A", v["omega"], v["alpha"])
    )
    if point:
        side = "left" if v["coupler_point_v"] >= 0 else "right"
        text += (
            f" The coupler point P lies {num(v['coupler_point_u'])} m along BC from B and "
            f"{num(abs(v['coupler_point_v']))} m to the {side} of the line from B to C."
        )
    rows = [
        (r"|AD|", v["ground"], "m"),
        (r"|AB|", v["crank"], "m"),
        (r"|BC|", v["coupler"], "m"),
        (r"|DC|", v["rocker"], "m"),
        (r"\varphi_{AB}", v["crank_angle_deg"], "deg"),
        (r"\omega_{AB}", v["omega"], "rad/s"),
    ]
    if v["alpha"] != 0.0 or "acceleration" in goal:
        rows.append((r"\alpha_{AB}", v["alpha"], "rad/s^2"))
    return f"{text} {goal}", givens_latex(rows)


def _four_bar_rates(rng: random.Random, difficulty: str, kind: str) -> Draft:
    """The coupler's and the rocker's angular rates (and, above basic, C's and P's vector) of
    ``kind`` 'velocity' or 'acceleration'."""
    point = difficulty == "challenging"
    accelerations = kind == "acceleration"
    with_alpha = accelerations and difficulty != "basic"
    scene, v = four_bar_scene(rng, difficulty, with_alpha, point)
    angular, of_point = (alpha_of, acceleration_of) if accelerations else (omega_of, velocity_of)
    asked: tuple[Asked, ...] = (
        angular("coupler", "coupler", "BC"),
        angular("rocker", "rocker", "DC"),
    )
    if difficulty != "basic":
        asked += of_point("C")
    if point:
        asked += of_point("P")
    rates = "angular accelerations" if accelerations else "angular velocities"
    vectors = "accelerations" if accelerations else "velocities"
    text, latex = four_bar_text(
        v, f"Find the {rates} of the coupler and the rocker"
        + (f" and the {vectors} asked." if difficulty != "basic" else "."), point,
    )  # fmt: skip
    return Draft(
        f"Four-bar: {vectors}", text, latex + r"\\" + asked_latex(asked), scene, asked,
        scales(v["omega"], v["alpha"], v["ground"]), four_bar_check,
    )  # fmt: skip


def four_bar_velocity(rng: random.Random, difficulty: str) -> Draft:
    return _four_bar_rates(rng, difficulty, "velocity")


def four_bar_acceleration(rng: random.Random, difficulty: str) -> Draft:
    return _four_bar_rates(rng, difficulty, "acceleration")


def _pole(link: str, kind: str, sub: str) -> tuple[Asked, ...]:
    name = "velocity pole" if kind == "velocity" else "acceleration pole"
    symbol = "P" if kind == "velocity" else "Q"
    return vector_of(
        "links", link, f"{kind}_pole", f"{kind}_pole_{link}", f"{name} of {sub}", "m",
        rf"{symbol}_{{{sub}", "xy",
    )  # fmt: skip


POLE_REACH = 3.0  # an asked pole lies within 3 |AD| of A: on the figure's sheet


def poles_check(analysis: Any) -> str | None:
    """``four_bar_check``, and the coupler's poles within ``POLE_REACH`` |AD| of A (a pole
    tens of |AD| away is off any sheet, and ill-conditioned to construct)."""
    reason = four_bar_check(analysis)
    if reason is not None:
        return reason
    a, d = analysis.points["A"].position, analysis.points["D"].position
    ground = float(math.dist(a, d))
    coupler = analysis.links["coupler"]
    for pole in (coupler.velocity_pole, coupler.acceleration_pole):
        if pole is not None and math.dist(pole, a) > POLE_REACH * ground:
            return f"a pole {math.dist(pole, a) / ground:.1f} |AD| from A"
    return None


def four_bar_poles(rng: random.Random, difficulty: str) -> Draft:
    scene, v = four_bar_scene(rng, difficulty, difficulty == "challenging", False)
    asked: tuple[Asked, ...] = _pole("coupler", "velocity", "BC")
    if difficulty != "basic":
        asked += _pole("coupler", "acceleration", "BC")
    goal = "Locate the velocity pole (instant centre) of the coupler BC" + (
        " and its acceleration pole (the point of BC with zero acceleration)"
        if difficulty != "basic"
        else ""
    )
    text, latex = four_bar_text(v, goal + ", with A as the origin and x along AD.", False)
    return Draft(
        "Four-bar: poles of the coupler", text, latex + r"\\" + asked_latex(asked), scene, asked,
        scales(v["omega"], v["alpha"], v["ground"]), poles_check,
    )  # fmt: skip


# --- slider-crank --------------------------------------------------------------------------------


def slider_crank(rng: random.Random, difficulty: str) -> Draft:
    crank = pick(rng, 0.05, 0.2, 0.01)
    v = {
        "crank": crank,
        "rod": round(crank * pick(rng, 3.0, 5.0, 0.5), 10),
        "offset": 0.0 if difficulty == "basic" else pick(rng, 0.01, 0.4, 0.01) * crank / 0.2,
        "crank_angle_deg": pick(rng, 0.0, 345.0, 15.0 if difficulty == "basic" else 5.0),
        "assembly": 0.0,
        "coupler_point_u": 0.0,
        "coupler_point_v": 0.0,
    }
    v["offset"] = round(v["offset"], 3) * (1 if rng.random() < 0.5 else -1)
    v["omega"], v["alpha"] = rates_for(rng, difficulty, difficulty == "challenging")
    scene = build_preset("slider_crank", v)
    asked: tuple[Asked, ...] = (
        velocity_of("C", "x")[0],
        omega_of("coupler", "connecting rod", "BC"),
    )
    if difficulty != "basic":
        asked += (acceleration_of("C", "x")[0], alpha_of("coupler", "connecting rod", "BC"))
    guide = "through A" if v["offset"] == 0 else f"at y = {num(v['offset'])} m (offset)"
    text = (
        f"In the slider-crank ABC the crank AB = {num(crank)} m turns about the fixed pivot A, "
        f"the connecting rod BC = {num(v['rod'])} m drives the slider C along the horizontal guide "
        f"{guide}, C to the right of B. The crank is drawn at {num(v['crank_angle_deg'])} deg. "
        + crank_sentence("B", "A", v["omega"], v["alpha"])
        + " Find the slider's velocity and the rod's angular velocity"
        + (" and accelerations." if difficulty != "basic" else ".")
    )
    latex = givens_latex(
        [
            ("|AB|", crank, "m"),
            ("|BC|", v["rod"], "m"),
            ("e", v["offset"], "m"),
            (r"\varphi_{AB}", v["crank_angle_deg"], "deg"),
            (r"\omega_{AB}", v["omega"], "rad/s"),
            (r"\alpha_{AB}", v["alpha"], "rad/s^2"),
        ]
    )
    return Draft(
        "Offset slider-crank", text, latex + r"\\" + asked_latex(asked), scene, asked,
        scales(v["omega"], v["alpha"], crank + v["rod"]),
    )  # fmt: skip


# --- inverted slider-crank and quick-return ------------------------------------------------


def _coriolis_of(joint: int, point: str) -> tuple[Asked, ...]:
    return vector_of(
        "joints", str(joint), "coriolis_acceleration", f"a_cor_{point}",
        f"Coriolis acceleration of {point} in the slot", "m/s^2", rf"a^{{Cor}}_{{{point}", "xy",
    )  # fmt: skip


def _inverted_slider_crank_text(v: Mapping[str, float], difficulty: str) -> str:
    """The statement of the inverted slider-crank in words."""
    return (
        f"In the inverted slider-crank the crank OA = {num(v['crank'])} m turns about the fixed "
        f"pivot O; its pin A carries a block sliding in the slot of the lever CD, pivoted at C, "
        f"{num(v['ground'])} m to the right of O"
        + (
            f"; the slot runs {num(abs(v['slot_offset']))} m from C, to the "
            f"{'left' if v['slot_offset'] > 0 else 'right'} of C->D"
            if v["slot_offset"]
            else "; the slot runs through C"
        )
        + f". The crank is drawn at {num(v['crank_angle_deg'])} deg. "
        + crank_sentence("A", "O", v["omega"], v["alpha"])
        + " Find the lever's angular velocity"
        + (
            " and the block's sliding velocity."
            if difficulty == "basic"
            else ", its angular acceleration and the Coriolis acceleration of A."
        )
    )


def inverted_slider_crank(rng: random.Random, difficulty: str) -> Draft:
    ground = pick(rng, 0.2, 0.5, 0.05)
    crank = round(ground * pick(rng, 0.3, 0.7, 0.1), 10)
    v = {
        "crank": crank,
        "ground": ground,
        "lever": round(math.ceil((ground + crank) * 1.2 / 0.05) * 0.05, 10),
        "slot_offset": 0.0 if difficulty != "challenging" else pick(rng, -0.03, 0.03, 0.01),
        "crank_angle_deg": pick(rng, 0.0, 345.0, 15.0 if difficulty == "basic" else 5.0),
    }
    v["omega"], v["alpha"] = rates_for(rng, difficulty, difficulty == "challenging")
    scene = build_preset("inverted_slider_crank", v)
    asked: tuple[Asked, ...] = (omega_of("lever", "slotted lever", "CD"),)
    if difficulty == "basic":
        asked += vector_of(
            "joints", "0", "relative_velocity", "v_rel_A", "sliding velocity of A in the slot",
            "m/s", r"v^{rel}_{A", "xy",
        )  # fmt: skip
    else:
        asked += (alpha_of("lever", "slotted lever", "CD"), *_coriolis_of(0, "A"))
    latex = givens_latex(
        [
            ("|OA|", crank, "m"),
            ("|OC|", ground, "m"),
            ("e", v["slot_offset"], "m"),
            (r"\varphi_{OA}", v["crank_angle_deg"], "deg"),
            (r"\omega_{OA}", v["omega"], "rad/s"),
            (r"\alpha_{OA}", v["alpha"], "rad/s^2"),
        ]
    )
    return Draft(
        "Inverted slider-crank (Coriolis)", _inverted_slider_crank_text(v, difficulty),
        latex + r"\\" + asked_latex(asked), scene, asked,
        scales(v["omega"], v["alpha"], ground + crank),
    )  # fmt: skip


def _quick_return_text(v: Mapping[str, float], difficulty: str) -> str:
    """The statement of the crank-and-slotted-lever quick-return mechanism in words."""
    return (
        f"In the crank-and-slotted-lever quick-return mechanism the crank O2A = "
        f"{num(v['crank'])} m turns about O2; its pin A slides in the slot of the lever O4B = "
        f"{num(v['lever'])} m, pivoted at O4 {num(v['ground'])} m below O2. The link BC = "
        f"{num(v['rod'])} m drives the ram C along the horizontal guide y = "
        f"{num(v['ram_height'])} m. The crank is drawn at {num(v['crank_angle_deg'])} deg. "
        + crank_sentence("A", "O2", v["omega"], v["alpha"])
        + " Find the lever's angular velocity and the ram's velocity"
        + (
            ", the lever's angular acceleration and the Coriolis acceleration of A"
            if difficulty != "basic"
            else ""
        )
        + (" and the ram's acceleration." if difficulty == "challenging" else ".")
    )


def quick_return(rng: random.Random, difficulty: str) -> Draft:
    ground = pick(rng, 0.2, 0.4, 0.05)
    crank = round(ground * pick(rng, 0.3, 0.6, 0.1), 10)
    lever = round(math.ceil((ground + crank) * 1.5 / 0.05) * 0.05, 10)
    v = {
        "crank": crank,
        "ground": ground,
        "lever": lever,
        "rod": pick(rng, 0.15, 0.3, 0.05),
        "ram_height": round(lever - ground + pick(rng, -0.05, 0.0, 0.01), 10),
        "slot_offset": 0.0,
        "crank_angle_deg": pick(rng, 0.0, 345.0, 15.0 if difficulty == "basic" else 5.0),
    }
    v["omega"], v["alpha"] = rates_for(rng, difficulty, difficulty == "challenging")
    scene = build_preset("quick_return", v)
    asked: tuple[Asked, ...] = (
        omega_of("lever", "slotted lever", "O_4B"),
        velocity_of("C", "x")[0],
    )
    if difficulty != "basic":
        asked += (alpha_of("lever", "slotted lever", "O_4B"), *_coriolis_of(0, "A"))
    if difficulty == "challenging":
        asked += (acceleration_of("C", "x")[0],)
    latex = givens_latex(
        [
            ("|O_2A|", crank, "m"),
            ("|O_2O_4|", ground, "m"),
            ("|O_4B|", lever, "m"),
            ("|BC|", v["rod"], "m"),
            ("y_C", v["ram_height"], "m"),
            (r"\varphi_{O_2A}", v["crank_angle_deg"], "deg"),
            (r"\omega_{O_2A}", v["omega"], "rad/s"),
            (r"\alpha_{O_2A}", v["alpha"], "rad/s^2"),
        ]
    )
    return Draft(
        "Quick-return mechanism (Coriolis)", _quick_return_text(v, difficulty),
        latex + r"\\" + asked_latex(asked), scene, asked, scales(v["omega"], v["alpha"], lever),
    )  # fmt: skip


# --- slider on a fixed guide with an extension ---------------------------------------------------


def slider_extension(rng: random.Random, difficulty: str) -> Draft:
    crank = pick(rng, 0.1, 0.3, 0.02)
    v = {
        "crank": crank,
        "coupler": round(crank * pick(rng, 1.6, 3.0, 0.2), 10),
        "extension": pick(rng, 0.1, 0.4, 0.05),
        "guide_height": round(crank * pick(rng, 0.0, 0.8, 0.2), 10),
        "crank_angle_deg": pick(rng, 0.0, 345.0, 15.0 if difficulty == "basic" else 5.0),
    }
    v["omega"], v["alpha"] = rates_for(rng, difficulty, difficulty == "challenging")
    scene = build_preset("slider_guide_extension", v)
    asked: tuple[Asked, ...] = (omega_of("coupler", "coupler", "BCD"), *velocity_of("D"))
    if difficulty != "basic":
        asked += (alpha_of("coupler", "coupler", "BCD"),)
    if difficulty == "challenging":
        asked += acceleration_of("D")
    text = (
        f"The crank AB = {num(crank)} m turns about the fixed pivot A. The coupler BCD is pinned "
        f"to it at B; its point C (BC = {num(v['coupler'])} m) slides along the fixed horizontal "
        f"guide y = {num(v['guide_height'])} m, to the right of B, and D lies on the extension of "
        f"BC beyond C, CD = {num(v['extension'])} m. The crank is drawn at "
        f"{num(v['crank_angle_deg'])} deg. "
        + crank_sentence("B", "A", v["omega"], v["alpha"])
        + " Find the coupler's angular velocity and the velocity of D"
        + (", and the coupler's angular acceleration" if difficulty != "basic" else "")
        + (" and the acceleration of D." if difficulty == "challenging" else ".")
    )
    latex = givens_latex(
        [
            ("|AB|", crank, "m"),
            ("|BC|", v["coupler"], "m"),
            ("|CD|", v["extension"], "m"),
            ("y_C", v["guide_height"], "m"),
            (r"\varphi_{AB}", v["crank_angle_deg"], "deg"),
            (r"\omega_{AB}", v["omega"], "rad/s"),
            (r"\alpha_{AB}", v["alpha"], "rad/s^2"),
        ]
    )
    return Draft(
        "Slider on a fixed guide with an extension", text, latex + r"\\" + asked_latex(asked),
        scene, asked, scales(v["omega"], v["alpha"], crank + v["coupler"] + v["extension"]),
    )  # fmt: skip


# --- a point moving on a moving body -------------------------------------------------------------


def _moving(key: str, field: str, label: str, unit: str, symbol: str) -> tuple[Asked, ...]:
    return vector_of("moving_points", "M", field, key, label, unit, symbol, "xy")


@dataclass(frozen=True)
class Carrier:
    """The body M moves on and M's path in it: the points, the path, the words and the givens."""

    name: str
    points: dict[str, list[float]]
    on: list[str]
    path: dict[str, str]
    where: str
    size: float  # m: the farthest the path reaches from O
    rows: list[tuple[str, float, str]]


def _groove_disc(rng: random.Random) -> Carrier:
    """A disc with a circular groove of radius R centred at Q, |OQ| = q: M runs from S (below Q)
    by the angle SQT to T, S = Q + R (cos -90, sin -90), T = Q + R (cos phi, sin phi)."""
    q = pick(rng, 0.1, 0.3, 0.05)
    radius = pick(rng, 0.05, 0.15, 0.01)
    turn_deg = pick(rng, 90.0, 270.0, 45.0)
    direction = "ccw" if rng.random() < 0.5 else "cw"
    side = 1.0 if direction == "ccw" else -1.0
    start_angle = math.radians(-90.0)
    points = {"O": [0.0, 0.0], "Q": [q, 0.0]}
    points["S"] = [q + radius * math.cos(start_angle), radius * math.sin(start_angle)]
    phi = start_angle + side * math.radians(turn_deg)
    points["T"] = [q + radius * math.cos(phi), radius * math.sin(phi)]
    where = (
        f"a circular groove of radius {num(radius)} m centred at Q, {num(q)} m from O; M "
        f"starts at S (straight below Q) and runs {'counter-' if side > 0 else ''}clockwise "
        f"round the groove; T is {num(turn_deg)} deg further round"
    )
    path = {"type": "arc", "center": "Q", "start": "S", "direction": direction}
    rows = [("|OQ|", q, "m"), ("R", radius, "m"), (r"\angle SQT", turn_deg, "deg")]
    return Carrier("disc", points, ["O", "Q", "S", "T"], path, where, q + radius, rows)


def _slotted_rod(rng: random.Random) -> Carrier:
    """A rod with a straight slot at the angle theta_0 from x at t = 0 (stated, and dimensioned in
    the figure): S = |OS| u, T = (|OS| + |ST|) u, u = (cos theta_0, sin theta_0)."""
    start = pick(rng, 0.05, 0.15, 0.05)
    length = pick(rng, 0.2, 0.5, 0.05)
    angle_deg = pick(rng, 0.0, 60.0, 15.0)
    angle = math.radians(angle_deg)
    unit = (math.cos(angle), math.sin(angle))
    points = {
        "O": [0.0, 0.0],
        "S": [start * unit[0], start * unit[1]],
        "T": [(start + length) * unit[0], (start + length) * unit[1]],
    }
    where = (
        f"a straight slot along the rod, from S ({num(start)} m from O) outwards to its end T "
        f"({num(length)} m further); at t = 0 the rod points {num(angle_deg)} deg "
        "counter-clockwise from the x axis; M starts at S"
    )
    path = {"type": "line", "start": "S", "through": "T"}
    rows = [("|OS|", start, "m"), ("|ST|", length, "m"), (r"\theta_0", angle_deg, "deg")]
    return Carrier("rod", points, ["O", "S", "T"], path, where, start + length, rows)


def _moving_point_scene(carrier: Carrier, law: str, s_law: str, t1: float) -> dict[str, Any]:
    """The carrier turning about O by phi(t) = law, M on its path by s(t) = s_law, at t1."""
    return {
        "kind": "linkage",
        "title": "point moving on a turning " + carrier.name,
        "points": carrier.points,
        "links": {
            "ground": {"points": ["O"], "ground": True},
            carrier.name: {"points": carrier.on},
        },
        "joints": [{"type": "revolute", "point": "O", "links": ["ground", carrier.name]}],
        "drivers": [{"link": carrier.name, "angle_law": law}],
        "moving_points": [
            {"name": "M", "link": carrier.name, "path": carrier.path, "s_law": s_law}
        ],
        "time": t1,
    }


def moving_point(rng: random.Random, difficulty: str) -> Draft:
    """A disc (or a rod) turning about O by a time law, and M moving along a groove (or a slot)
    fixed in it by s(t) = c t^2: at t1, M's velocity, its Coriolis and absolute acceleration; and
    the instant at which M reaches the target point T of its path."""
    groove = rng.random() < 0.5
    omega = rate(rng, 1, 4, signed=difficulty != "basic")
    epsilon = rate(rng, 1, 3) / 10 if difficulty == "challenging" else 0.0
    c = pick(rng, 0.02, 0.1, 0.01)
    t1 = pick(rng, 0.5, 2.0, 0.5)
    law = polynomial([(omega, "t"), (epsilon / 2, "t^2")])
    carrier = _groove_disc(rng) if groove else _slotted_rod(rng)
    asked: tuple[Asked, ...] = _moving("v_M", "velocity", "velocity of M", "m/s", "v_{M")
    asked += _moving(
        "a_cor_M", "coriolis_acceleration", "Coriolis acceleration of M", "m/s^2",
        r"a^{Cor}_{M",
    )  # fmt: skip
    if difficulty != "basic":
        asked += _moving("a_M", "acceleration", "acceleration of M", "m/s^2", "a_{M")
        asked += (Asked("t_M_T", "time at which M reaches T", "s", "events.M.T.time", "t_{T}"),)
    text = (
        f"A {carrier.name} turns about the fixed pivot O by the angle phi(t) = {law} rad (phi "
        f"counter-clockwise positive: the {carrier.name} turns "
        f"{sense(omega)}). It carries {carrier.where}, by the law s(t) = {num(c)} t^2 (s in m, "
        f"t in s). Drawn at t = 0. At t = {num(t1)} s find the velocity of M and its Coriolis "
        "acceleration"
        + (
            ", its absolute acceleration, and the time at which M reaches T."
            if difficulty != "basic"
            else "."
        )
    )
    latex = (
        rf"\varphi(t) = {law}"
        + rf",\; s(t) = {num(c)}\,t^2,\; t_1 = {num(t1)}\,\mathrm{{s}},\; "
        + givens_latex(carrier.rows)
    )
    rates = max(omega * omega, abs(epsilon), 1.0)
    return Draft(
        "Point moving on a turning " + carrier.name, text, latex + r"\\" + asked_latex(asked),
        _moving_point_scene(carrier, law.replace(" t", "*t"), f"{num(c)}*t^2", t1), asked,
        {"m/s": max(abs(omega), 1.0) * carrier.size, "m/s^2": rates * carrier.size, "s": 1.0},
    )  # fmt: skip


# --- spatial arm ---------------------------------------------------------------------------------


@dataclass(frozen=True)
class Arm:
    """The arm of seed 002 drawn: lengths |OO2| = l1 (tilted from z), |O2A| = l2 along
    e3 = (0, cos d, -sin d), |AB| = l3 along x; the relative rates and their rates of change."""

    l1: float
    tilt: float  # rad: OO2 from z in the y-z plane
    l2: float
    down: float  # rad: body 2 below the y axis
    l3: float
    rates: list[float]
    rate_dots: list[float]


def _draw_arm(rng: random.Random, difficulty: str) -> Arm:
    """The arm's lengths, angles and rates, drawn in the order of the book's givens."""
    l1 = pick(rng, 0.8, 1.5, 0.1)
    tilt = math.radians(pick(rng, 15.0, 45.0, 15.0))
    l2 = pick(rng, 0.4, 0.8, 0.1)
    down = math.radians(pick(rng, 15.0, 60.0, 15.0))
    l3 = pick(rng, 0.1, 0.3, 0.05)
    rates = [rate(rng, 1, 3, signed=difficulty != "basic") for _ in range(3)]
    rate_dots = [rate(rng, 1, 5) if difficulty == "challenging" else 0.0 for _ in range(3)]
    return Arm(l1, tilt, l2, down, l3, rates, rate_dots)


def _arm_scene(arm: Arm) -> dict[str, Any]:
    """O2 = l1 (0, sin tilt, cos tilt), A = O2 + l2 e3, B = A + l3 E1; axes z, x and e3."""
    o2 = [0.0, arm.l1 * math.sin(arm.tilt), arm.l1 * math.cos(arm.tilt)]
    e3 = [0.0, math.cos(arm.down), -math.sin(arm.down)]
    a = [o2[k] + arm.l2 * e3[k] for k in range(3)]
    b = [a[0] + arm.l3, a[1], a[2]]
    axes = [[0.0, 0.0, 1.0], [1.0, 0.0, 0.0], e3]
    origins = [[0.0, 0.0, 0.0], o2, a]
    joints = [
        {
            "name": str(k + 1),
            "type": "revolute",
            "origin": origins[k],
            "axis": axes[k],
            "rate": arm.rates[k],
            "rate_dot": arm.rate_dots[k],
        }
        for k in range(3)
    ]
    return {
        "kind": "spatial_chain",
        "title": "spatial arm",
        "joints": joints,
        "points": {"A": {"body": "2", "position": a}, "B": {"body": "3", "position": b}},
    }


def _arm_text(arm: Arm, difficulty: str) -> str:
    """The statement of the spatial arm in words."""
    rates, rate_dots = arm.rates, arm.rate_dots
    return (
        f"A spatial arm: body 1 turns about the vertical z axis through O at {rates[0]:g} rad/s; "
        f"at its top O2, {num(arm.l1)} m from O in the y-z plane at {math.degrees(arm.tilt):g} "
        f"deg from z, body 2 is hinged about the x axis at {rates[1]:g} rad/s relative to body "
        f"1; at A, {num(arm.l2)} m from O2 along body 2 (pointing {math.degrees(arm.down):g} deg "
        f"below the y axis), body 3 turns about that same direction at {rates[2]:g} rad/s "
        f"relative to body 2, and carries the point B, {num(arm.l3)} m from A along x."
        + (
            f" The relative rates change at {rate_dots[0]:g}, {rate_dots[1]:g} and "
            f"{rate_dots[2]:g} rad/s^2."
            if difficulty == "challenging"
            else " The relative rates are constant."
        )
        + " Find the angular velocity of body 3"
        + (" and the velocity and acceleration of B." if difficulty != "basic" else ".")
    )


def spatial_arm(rng: random.Random, difficulty: str) -> Draft:
    """The arm of seed 002: a column turning about z, an arm hinged about x at its top, and a
    forearm turning about its own axis, carrying the tool point B off that axis."""
    arm = _draw_arm(rng, difficulty)
    asked: tuple[Asked, ...] = vector_of(
        "bodies", "3", "omega", "omega_3", "angular velocity of body 3", "rad/s",
        r"\omega_{3", "xyz",
    )  # fmt: skip
    if difficulty != "basic":
        asked += velocity_of("B", "xyz")
    asked += acceleration_of("B", "xyz") if difficulty != "basic" else ()
    latex = givens_latex(
        [
            ("|OO_2|", arm.l1, "m"),
            ("|O_2A|", arm.l2, "m"),
            ("|AB|", arm.l3, "m"),
            (r"\omega_{1}", arm.rates[0], "rad/s"),
            (r"\omega_{21}", arm.rates[1], "rad/s"),
            (r"\omega_{32}", arm.rates[2], "rad/s"),
        ]
    )
    largest = max(abs(r) for r in arm.rates) + max(abs(r) for r in arm.rate_dots) ** 0.5
    return Draft(
        "Spatial arm", _arm_text(arm, difficulty), latex + r"\\" + asked_latex(asked),
        _arm_scene(arm), asked, scales(largest, 0.0, arm.l1 + arm.l2 + arm.l3),
    )  # fmt: skip

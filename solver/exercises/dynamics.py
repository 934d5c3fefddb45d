"""The dynamics exercise types (dynamics-v1): a four-bar's driving torque at an instant, the
flywheel for a coefficient of speed fluctuation over a cycle, and in statics a four-bar's holding
torque and a slider-crank's driving torque with friction.

Both draw a Grashof crank-rocker (``families.four_bar_values``) with uniform bars of a given mass
per length and, from standard on, gravity; the torque's rocker carries a constant load moment
from standard on, the flywheel's a resisting moment during its counter-clockwise swing (a
working stroke, so that the mean torque is not zero). Their paths
point into the dynamics answers: ``drivers.0.torque`` and ``joints.1.force.0`` of ``/analyze``
with the quantities ``forces`` and ``energy``, and ``sweep[samples=720,k=P/100].cycle.<figure>``,
the ``cycle`` of ``/sweep`` over a revolution with 720 samples and ``speed_fluctuation`` P/100;
``statics.drivers.0.torque`` (and ``torque_frictionless``, ``joints.<k>.force.<axis>``) of
``/analyze`` with ``statics``.
"""

from __future__ import annotations

import random
from collections.abc import Mapping
from typing import Any

from solver.exercises.families import (
    asked_latex,
    four_bar_check,
    four_bar_text,
    four_bar_values,
    givens_latex,
    num,
    pick,
    scales,
)
from solver.exercises.model import Asked, Draft
from solver.teaching.presets import build_preset

CYCLE_SAMPLES = 720  # half a degree: the cycle figures to well within the 1 % tolerance
GRAVITY = 9.81


def cycle_path(percent: int, figure: str) -> str:
    """The path of a cycle figure of /sweep with ``speed_fluctuation`` percent / 100."""
    return f"sweep[samples={CYCLE_SAMPLES},k={percent}/100].cycle.{figure}"


def _bars(rng: random.Random, v: dict[str, float], weights: bool) -> str:
    """Uniform bars of a drawn mass per length and (``weights``) gravity along -y, set in the
    preset values ``v``; their sentence."""
    v["mass_per_length"] = pick(rng, 2.0, 20.0, 1.0)
    v["gravity"] = GRAVITY if weights else 0.0
    v["load"] = 0.0
    text = (
        f" Every link is a uniform slender bar of {num(v['mass_per_length'])} kg per metre "
        "(its centre of mass at its middle, I = m L^2 / 12 about it); joints are frictionless"
    )
    if weights:
        return text + f"; gravity {num(GRAVITY)} m/s^2 acts along -y."
    return text + "; the mechanism lies in a horizontal plane (no weights)."


def _stroke_load(rng: random.Random, scene: dict[str, Any], v: dict[str, float]) -> str:
    """A resisting moment on the rocker during its counter-clockwise swing only (a working
    stroke: it does net work over a revolution, so the mean torque is not zero); its sentence."""
    moment = pick(rng, 10.0, 80.0, 5.0)
    scene["torques"] = [
        {"name": "load", "link": "rocker", "moment": f'where(omega("rocker") > 0, {-moment!r}, 0)'}
    ]
    v["load"] = moment
    return (
        f" While the rocker swings counter-clockwise it works against a resisting moment of "
        f"{num(moment)} N m (clockwise); on its return it is free."
    )


def _dynamic_scales(v: Mapping[str, float]) -> dict[str, float]:
    """The size of a force, a torque, an energy and an inertia in this four-bar: the largest of
    the inertia forces m omega^2 L (m of the whole mechanism), the weights and the load."""
    length = v["ground"]
    mass = v["mass_per_length"] * (v["crank"] + v["coupler"] + v["rocker"])
    rates = max(v["omega"] ** 2, abs(v["alpha"]))
    force = max(mass * rates * length, mass * v["gravity"], abs(v["load"]) / length)
    return scales(v["omega"], v["alpha"], length) | {
        "N": force,
        "N m": force * length,
        "J": force * length,
        "kg m^2": mass * length**2,
        "W": force * length * abs(v["omega"]),
    }


TORQUE = Asked("M_crank", "driving torque on the crank AB", "N m", "drivers.0.torque", r"M_{AB}")
FORCE_B = tuple(
    Asked(
        f"F_B_{axis}", f"force of the crank on the coupler at B, {axis} component", "N",
        f"joints.1.force.{index}", rf"F_{{B,{axis}}}",
    )
    for index, axis in enumerate("xy")
)  # fmt: skip


def four_bar_torque(rng: random.Random, difficulty: str) -> Draft:
    """The torque that drives the crank at the drawn instant (inverse dynamics); from standard on
    with weights and a load, and the pin force at B; challenging: an accelerating crank."""
    v = four_bar_values(rng, difficulty, difficulty == "challenging", False)
    masses = _bars(rng, v, difficulty != "basic")
    if difficulty == "basic":
        masses += " It carries no load."
    else:
        v["load"] = pick(rng, -40.0, 40.0, 5.0) or 10.0
        masses += (
            f" The rocker carries a constant external moment of {num(v['load'])} N m "
            "(counter-clockwise positive)."
        )
    scene = build_preset("four_bar", v)
    asked: tuple[Asked, ...] = (TORQUE,)
    if difficulty != "basic":
        asked += FORCE_B
    text, latex = four_bar_text(
        v,
        masses.strip()
        + " Find the torque the motor must apply to the crank at this instant"
        + (
            " and the force the crank exerts on the coupler at B." if difficulty != "basic" else "."
        ),
        False,
    )
    return Draft(
        "Four-bar: driving torque", text, latex + r"\\" + asked_latex(asked), scene, asked,
        _dynamic_scales(v), four_bar_check,
    )  # fmt: skip


def flywheel(rng: random.Random, difficulty: str) -> Draft:
    """The flywheel that keeps the crank's speed within a coefficient of fluctuation k over a
    revolution at constant mean speed: the energy fluctuation and I = fluctuation / (k omega^2);
    challenging: also the mean driving torque."""
    v = four_bar_values(rng, difficulty, False, False)
    masses = _bars(rng, v, difficulty != "basic")
    percent = rng.choice([2, 3, 4, 5, 8, 10])
    scene = build_preset("four_bar", v)
    masses += _stroke_load(rng, scene, v)
    asked: tuple[Asked, ...] = (
        Asked(
            "energy_fluctuation", "largest energy fluctuation of the crank over a revolution",
            "J", cycle_path(percent, "energy_fluctuation"), r"\Delta E",
        ),
        Asked(
            "flywheel_inertia", "moment of inertia of the flywheel on the crank", "kg m^2",
            cycle_path(percent, "flywheel_inertia"), r"I_F",
        ),
    )  # fmt: skip
    if difficulty == "challenging":
        asked += (
            Asked(
                "mean_torque", "mean driving torque over a revolution", "N m",
                cycle_path(percent, "mean_torque"), r"\bar{M}",
            ),
        )  # fmt: skip
    goal = (
        masses.strip()
        + " The crank turns at a constant mean speed; a flywheel on it is to keep the coefficient "
        f"of speed fluctuation (omega_max - omega_min) / omega at k = {percent / 100:g}. Find the "
        "largest fluctuation of the energy over a revolution and the flywheel's moment of inertia"
        + (" and the mean driving torque." if difficulty == "challenging" else ".")
    )
    text, latex = four_bar_text(v, goal, False)
    latex += rf",\; k = {percent / 100:g}"
    return Draft(
        "Four-bar: flywheel", text, latex + r"\\" + asked_latex(asked), scene, asked,
        _dynamic_scales(v), four_bar_check,
    )  # fmt: skip


# --- statics and friction (docs/DYNAMICS.md "Statics", "Friction") ------------------------------

HOLDING_TORQUE = Asked(
    "M_crank", "torque on the crank AB that holds the linkage", "N m", "statics.drivers.0.torque",
    r"M_{AB}",
)  # fmt: skip
STATIC_FORCE_B = tuple(
    Asked(
        f"F_B_{axis}", f"force of the crank on the coupler at B, {axis} component", "N",
        f"statics.joints.1.force.{index}", rf"F_{{B,{axis}}}",
    )
    for index, axis in enumerate("xy")
)  # fmt: skip
QUASI_STATIC = (
    " The crank turns so slowly that the inertia forces are negligible: a static force analysis."
)


def holding_torque(rng: random.Random, difficulty: str) -> Draft:
    """The torque that holds a four-bar against a load moment on its rocker (statics: the masses
    count only through their weight, ``statics.drivers.0.torque``); from standard on with the
    bars' weights and the pin force at B (``statics.joints.1.force.<axis>``)."""
    v = four_bar_values(rng, difficulty, False, False)
    masses = _bars(rng, v, difficulty != "basic")
    v["load"] = pick(rng, -60.0, 60.0, 5.0) or 20.0
    masses += (
        f" The rocker carries a constant external moment of {num(v['load'])} N m "
        "(counter-clockwise positive)."
    )
    scene = build_preset("four_bar", v)
    asked: tuple[Asked, ...] = (HOLDING_TORQUE,)
    if difficulty != "basic":
        asked += STATIC_FORCE_B
    goal = (
        masses.strip()
        + QUASI_STATIC
        + " Find the torque on the crank that holds the linkage in this position"
        + (" and the force the crank exerts on the coupler at B." if difficulty != "basic" else ".")
    )
    text, latex = four_bar_text(v, goal, False)
    return Draft(
        "Four-bar: holding torque (statics)", text, latex + r"\\" + asked_latex(asked), scene,
        asked, _dynamic_scales({**v, "omega": 0.0, "alpha": 0.0}), four_bar_check,
    )  # fmt: skip


def slider_crank_friction(rng: random.Random, difficulty: str) -> Draft:
    """A slider-crank pushing a piston force P with Coulomb friction mu at the slider (statics,
    no masses): the driving torque with friction (``statics.drivers.0.torque``), from standard
    on with a friction circle at the pin B and the torque without friction
    (``statics.drivers.0.torque_frictionless``); challenging: an offset guide and the guide's
    reaction on the slider (``statics.joints.2.force.<axis>``)."""
    crank = pick(rng, 0.05, 0.2, 0.01)
    v = {
        "crank": crank,
        "rod": round(crank * pick(rng, 3.0, 5.0, 0.5), 10),
        "offset": 0.0,
        "crank_angle_deg": pick(rng, 15.0, 345.0, 15.0),
        "assembly": 0.0,
        "coupler_point_u": 0.0,
        "coupler_point_v": 0.0,
        "omega": float(rng.choice([-1, 1]) if difficulty != "basic" else 1),
        "alpha": 0.0,
        "mass_per_length": 0.0,
        "gravity": 0.0,
        "load": pick(rng, 200.0, 2000.0, 100.0),
    }
    if difficulty == "challenging":
        v["offset"] = round(pick(rng, 0.01, 0.4, 0.01) * crank / 0.2, 3)
    mu = pick(rng, 0.05, 0.3, 0.05)
    scene = build_preset("slider_crank", v)
    slider = next(k for k, j in enumerate(scene["joints"]) if j["point"] == "C")
    scene["joints"][slider]["friction"] = {"coefficient": mu}
    friction = f"Coulomb friction mu = {num(mu)} between the slider and its guide"
    rows = [
        ("|AB|", crank, "m"),
        ("|BC|", v["rod"], "m"),
        ("e", v["offset"], "m"),
        (r"\varphi_{AB}", v["crank_angle_deg"], "deg"),
        ("P", v["load"], "N"),
        (r"\mu_C", mu, ""),
    ]
    if difficulty != "basic":
        pin, radius = pick(rng, 0.1, 0.3, 0.05), pick(rng, 0.005, 0.02, 0.005)
        pin_b = next(k for k, j in enumerate(scene["joints"]) if j["point"] == "B")
        scene["joints"][pin_b]["friction"] = {"coefficient": pin, "pin_radius": radius}
        friction += f", and at the pin B (radius {num(radius)} m) mu = {num(pin)}"
        rows += [(r"\mu_B", pin, ""), ("r_B", radius, "m")]
    asked: tuple[Asked, ...] = (
        Asked("M_crank", "driving torque on the crank AB with friction", "N m",
              "statics.drivers.0.torque", r"M_{AB}"),
    )  # fmt: skip
    if difficulty != "basic":
        asked += (
            Asked("M_0", "driving torque on the crank AB without friction", "N m",
                  "statics.drivers.0.torque_frictionless", r"M_0"),
        )  # fmt: skip
    if difficulty == "challenging":
        asked += tuple(
            Asked(f"N_C_{axis}", f"force of the guide on the slider C, {axis} component", "N",
                  f"statics.joints.{slider}.force.{index}", rf"F_{{C,{axis}}}")
            for index, axis in enumerate("xy")
        )  # fmt: skip
    sense = "counter-clockwise" if v["omega"] > 0 else "clockwise"
    guide = "through A" if v["offset"] == 0 else f"at y = {num(v['offset'])} m (offset)"
    text = (
        f"In the slider-crank ABC the crank AB = {num(crank)} m turns {sense} about the fixed "
        f"pivot A, the connecting rod BC = {num(v['rod'])} m drives the slider C along the "
        f"horizontal guide {guide}, C to the right of B. The crank is drawn at "
        f"{num(v['crank_angle_deg'])} deg. A force P = {num(v['load'])} N acts on the slider "
        f"along -x; {friction}. The links' masses are negligible." + QUASI_STATIC + " Find the "
        "torque on the crank that keeps it turning at this position"
        + (", the same torque without friction" if difficulty != "basic" else "")
        + (" and the guide's force on the slider." if difficulty == "challenging" else ".")
    )
    size = v["load"]
    return Draft(
        "Slider-crank with friction (statics)", text,
        givens_latex(rows) + r"\\" + asked_latex(asked), scene, asked,
        scales(v["omega"], 0.0, crank + v["rod"]) | {"N": size, "N m": size * crank},
    )  # fmt: skip

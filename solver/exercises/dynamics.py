"""The dynamics exercise types (dynamics-v1): a four-bar's driving torque at an instant, and the
flywheel for a coefficient of speed fluctuation over a cycle.

Both draw a Grashof crank-rocker (``families.four_bar_scene``) with uniform bars of a given mass
per length and, from standard on, gravity; the torque's rocker carries a constant load moment
from standard on, the flywheel's a resisting moment during its counter-clockwise swing (a
working stroke, so that the mean torque is not zero). Their paths
point into the dynamics answers: ``drivers.0.torque`` and ``joints.1.force.0`` of ``/analyze``
with the quantities ``forces`` and ``energy``, and ``sweep[samples=720,k=P/100].cycle.<figure>``,
the ``cycle`` of ``/sweep`` over a revolution with 720 samples and ``speed_fluctuation`` P/100.
"""

from __future__ import annotations

import random
from collections.abc import Mapping
from typing import Any

from solver.exercises.families import (
    asked_latex,
    four_bar_check,
    four_bar_scene,
    four_bar_text,
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
    _, v = four_bar_scene(rng, difficulty, difficulty == "challenging", False)
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
    _, v = four_bar_scene(rng, difficulty, False, False)
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

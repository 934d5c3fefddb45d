"""The gear-train exercise types (docs/GEARS.md, docs/EXERCISES.md): the output speed of a
planetary train, and the carrier's speed of a differential (their typical mistakes:
``solver.exercises.gear_mistakes``).

Both draw a textbook train (``solver.teaching.gear_presets``) with whole tooth numbers and whole
input speeds in rad/s; their keys are paths into the /analyze body of the gear train
(``members.arm.omega``, ``members.planet1.omega_relative``), read by ``solver.exercises.answers``.
The typical mistakes are made with the solver, as for the linkages: an input's rotation taken the
other way round (one input at a time), every annulus taken as an external gear (the sign of the
internal mesh), and a planet's speed relative to its carrier taken for its absolute speed (or the
other way round).
"""

from __future__ import annotations

import random
from collections.abc import Mapping

from solver.exercises.families import asked_latex, num, pick, rate
from solver.exercises.model import Asked, Draft
from solver.teaching.gear_presets import build_gear_preset

MODULE = 0.002  # m: the drawing's scale only (the speeds depend on the tooth ratios alone)


def _omega(member: str, label: str, symbol: str) -> Asked:
    return Asked(f"omega_{member}", label, "rad/s", f"members.{member}.omega", symbol)


def _relative(planet: str, carrier: str, symbol: str) -> Asked:
    return Asked(
        f"omega_{planet}_rel",
        f"angular velocity of {planet} relative to the {carrier}",
        "rad/s",
        f"members.{planet}.omega_relative",
        symbol,
    )


def _speeds_scale(inputs: Mapping[str, float]) -> dict[str, float]:
    """The size of an answer in rad/s: the fastest input."""
    return {"rad/s": max(abs(v) for v in inputs.values())}


def planetary_output(rng: random.Random, difficulty: str) -> Draft:
    """A sun driven, one planet on the arm, the annulus (N_sun + 2 N_planet teeth) fixed: the
    arm's speed (the output) and, from standard on, the planet's; challenging: the annulus turns
    too, at a given speed."""
    sun, planet = int(pick(rng, 12, 40, 1)), int(pick(rng, 12, 40, 1))
    omega_sun = rate(rng, 10, 300, signed=difficulty != "basic")
    doc = build_gear_preset(
        "planetary_ring_fixed",
        {"N_sun": sun, "N_planet": planet, "omega_sun": omega_sun, "module": MODULE},
    )
    ring = doc["gears"]["ring"]["teeth"]
    omega_ring = rate(rng, 5, 100) if difficulty == "challenging" else 0.0
    doc["inputs"] = {"sun": omega_sun, "ring": omega_ring}
    asked: tuple[Asked, ...] = (_omega("arm", "angular velocity of the arm", r"\omega_{arm}"),)
    if difficulty != "basic":
        asked += (_omega("planet", "angular velocity of the planet", r"\omega_{planet}"),)
    ring_text = "is held fixed" if omega_ring == 0.0 else f"turns at {num(omega_ring)} rad/s"
    text = (
        f"A simple planetary train: the sun ({sun} teeth) is driven at {num(omega_sun)} rad/s "
        f"(counter-clockwise positive); it meshes with a planet ({planet} teeth) carried by "
        f"the arm, which meshes with the internal ring gear ({ring} teeth), coaxial with the "
        f"sun; the ring {ring_text}. Find the angular velocity of the arm (the output)"
        + (" and of the planet (absolute)." if difficulty != "basic" else ".")
    )
    latex = (
        rf"N_{{sun}} = {sun},\; N_{{planet}} = {planet},\; N_{{ring}} = {ring},\\ "
        rf"\omega_{{sun}} = {num(omega_sun)}\,\mathrm{{rad/s}},\; "
        rf"\omega_{{ring}} = {num(omega_ring)}\,\mathrm{{rad/s}}\\" + asked_latex(asked)
    )
    scale = _speeds_scale(doc["inputs"])
    return Draft("Planetary train: output speed", text, latex, doc, asked, scale)


def differential_carrier(rng: random.Random, difficulty: str) -> Draft:
    """A spur-gear differential, both side gears driven: the carrier's speed and, from standard
    on, the first planet's speed relative to the carrier; challenging: a planetary differential
    (sun and annulus both driven, unequal teeth), its carrier and its planet's relative speed."""
    if difficulty == "challenging":
        sun, planet = int(pick(rng, 12, 40, 1)), int(pick(rng, 12, 40, 1))
        inputs = {"sun": rate(rng, 10, 300), "ring": rate(rng, 10, 300)}
        doc = build_gear_preset(
            "planetary_ring_fixed", {"N_sun": sun, "N_planet": planet, "module": MODULE}
        )
        doc["inputs"] = inputs
        doc["title"] = "planetary differential"
        ring = doc["gears"]["ring"]["teeth"]
        asked: tuple[Asked, ...] = (
            _omega("arm", "angular velocity of the carrier (arm)", r"\omega_{arm}"),
            _relative("planet", "arm", r"\omega_{planet/arm}"),
        )
        text = (
            f"A planetary differential: the sun ({sun} teeth) turns at {num(inputs['sun'])} "
            f"rad/s and the internal ring ({ring} teeth) at {num(inputs['ring'])} "
            f"rad/s (counter-clockwise positive), both driven; a planet ({planet} teeth) on the "
            "carrier (arm) meshes with both. Find the angular velocity of the carrier and the "
            "planet's angular velocity relative to the carrier."
        )
        latex = (
            rf"N_{{sun}} = {sun},\; N_{{planet}} = {planet},\; N_{{ring}} = {ring},"
            rf"\\ \omega_{{sun}} = {num(inputs['sun'])}\,\mathrm{{rad/s}},\; "
            rf"\omega_{{ring}} = {num(inputs['ring'])}\,\mathrm{{rad/s}}\\" + asked_latex(asked)
        )
        scale = _speeds_scale(inputs)
        return Draft("Differential: carrier speed", text, latex, doc, asked, scale)
    side, planet = int(pick(rng, 14, 40, 1)), int(pick(rng, 10, 24, 1))
    left = rate(rng, 5, 200, signed=difficulty != "basic")
    right = rate(rng, 5, 200, signed=difficulty != "basic")
    doc = build_gear_preset(
        "differential",
        {
            "N_side": side,
            "N_planet": planet,
            "omega_left": left,
            "omega_right": right,
            "module": MODULE,
        },
    )
    asked = (_omega("carrier", "angular velocity of the carrier", r"\omega_{carrier}"),)
    if difficulty == "standard":
        asked += (_relative("planet1", "carrier", r"\omega_{planet1/carrier}"),)
    text = (
        f"A spur-gear differential: the left and right side gears ({side} teeth each) turn about "
        f"one axis at {num(left)} rad/s and {num(right)} rad/s (counter-clockwise positive). "
        f"Two meshing planets ({planet} teeth each) on the carrier, which turns about the same "
        "axis, mesh one with the left and one with the right side gear. Find the angular "
        "velocity of the carrier"
        + (
            " and that of planet1 (meshing with the left gear) relative to the carrier."
            if difficulty == "standard"
            else "."
        )
    )
    latex = (
        rf"N_{{side}} = {side},\; N_{{planet}} = {planet},\\ "
        rf"\omega_{{left}} = {num(left)}\,\mathrm{{rad/s}},\; "
        rf"\omega_{{right}} = {num(right)}\,\mathrm{{rad/s}}\\" + asked_latex(asked)
    )
    scale = _speeds_scale({"left": left, "right": right})
    return Draft("Differential: carrier speed", text, latex, doc, asked, scale)

"""The cam families (docs/CAMS.md): a disc cam with a rise, a dwell, a return and a dwell, the
follower asked about at one cam angle.

An exercise's answers are read from /analyze of its scene at that cam angle: the paths start
with the root ``analyze[angle_deg=N]`` (N whole degrees; the request a client repeats), e.g.
``analyze[angle_deg=65].follower.velocity`` or
``analyze[angle_deg=65].diagnostics.extremes.pressure_angle.max``. The typical mistakes are the
chain rule's (``solver.teaching.mistakes``): the cam's speed left out, the duration in degrees,
and a pressure angle given in degrees.
"""

from __future__ import annotations

import math
import random
from collections.abc import Mapping
from typing import Any

from solver.cams.laws import LAW_NAMES
from solver.exercises.families import asked_latex, givens_latex, num, pick, sense
from solver.exercises.model import Asked, Draft, Exercise
from solver.teaching.cam_presets import CAM_PRESETS
from solver.teaching.mistakes import cam_beta_in_degrees, cam_rate_without_omega

ROOT = "analyze[angle_deg="
LAWS_BY_DIFFICULTY = {
    "basic": ("harmonic", "cycloidal"),
    "standard": ("harmonic", "cycloidal", "polynomial_345", "polynomial_4567"),
    "challenging": ("cycloidal", "polynomial_345", "polynomial_4567", "modified_trapezoid",
                    "modified_sine"),
}  # fmt: skip
LAW_WORDS = {
    "harmonic": "simple harmonic",
    "cycloidal": "cycloidal",
    "polynomial_345": "3-4-5 polynomial",
    "polynomial_4567": "4-5-6-7 polynomial",
    "modified_trapezoid": "modified trapezoid",
    "modified_sine": "modified sine",
}
DESIGN_FAULTS = ("pressure angle", "undercutting")  # warnings a drawn cam must not have


def cam_root(angle_deg: int) -> str:
    """The path root of /analyze at ``angle_deg``: ``analyze[angle_deg=65]``."""
    return f"{ROOT}{angle_deg}]"


def parse_cam_root(part: str) -> int | None:
    """The cam angle (deg) of an ``analyze[angle_deg=N]`` path root, else None."""
    if not (part.startswith(ROOT) and part.endswith("]")):
        return None
    digits = part[len(ROOT) : -1]
    return int(digits) if digits.isdigit() else None


def cam_angle_of(exercise: Exercise) -> int | None:
    """The cam angle the exercise asks about (None for an exercise of another kind)."""
    for asked in exercise.asked:
        found = parse_cam_root(asked.path.split(".")[0])
        if found is not None:
            return found
    return None


def _design_check(body: Any) -> str | None:
    """A drawn cam must be a sound design: no pressure angle above the limit, no undercutting
    (a jump of the acceleration is the law's, and asked about in the worked solution)."""
    for warning in body["warnings"]:
        if warning.startswith(DESIGN_FAULTS):
            return warning
    return None


def _draw_cam(rng: random.Random, difficulty: str, preset: str) -> dict[str, Any]:
    """Rounded parameters of a cam with a translating follower (``preset``): whole rad/s, lifts
    and radii in millimetres (the lift 20 to 45 % of the base radius, so that the pressure
    angle seldom passes its limit), durations in steps of 10 deg."""
    laws = LAWS_BY_DIFFICULTY[difficulty]
    values = {
        "base_radius": pick(rng, 0.03, 0.06, 0.005),
        "omega": float(rng.randint(5, 15))
        * (1 if difficulty == "basic" or rng.random() < 0.5 else -1),
        "lift": 0.0,  # a share of the base radius, below (no pressure angle above 30 deg)
        "rise_law": float(LAW_NAMES.index(rng.choice(laws))),
        "rise_deg": pick(rng, 100.0, 150.0, 10.0),
        "dwell_deg": pick(rng, 20.0, 60.0, 10.0),
        "return_law": float(LAW_NAMES.index(rng.choice(laws))),
        "return_deg": pick(rng, 100.0, 150.0, 10.0),
        "offset": 0.0 if difficulty == "basic" else pick(rng, -0.01, 0.01, 0.002),
    }
    values["lift"] = round(values["base_radius"] * pick(rng, 0.2, 0.45, 0.05), 3)
    if preset == "cam_roller_translating":
        values["roller_radius"] = pick(rng, 0.006, 0.015, 0.001)
    return CAM_PRESETS[preset].build(values)


def _angle_in_a_lift(rng: random.Random, doc: Mapping[str, Any]) -> int:
    """A cam angle (a multiple of 5 deg) inside the rise or the return, clear of their ends."""
    rise, dwell, ret = (s["duration_deg"] for s in doc["segments"][:3])
    if rng.random() < 0.5:
        start, length = 0.0, rise
    else:
        start, length = rise + dwell, ret
    low, high = start + 0.1 * length, start + 0.9 * length
    return int(pick(rng, 5.0 * math.ceil(low / 5.0), 5.0 * math.floor(high / 5.0), 5.0))


def _cam_text(doc: Mapping[str, Any], angle: int) -> str:
    """The cam, its follower and its segments in words."""
    cam, f = doc["cam"], doc["follower"]
    rise, dwell, ret, *rest = doc["segments"]
    contact = "a roller of radius " + num(f["roller_radius"]) + " m" if f["contact"] == "roller" \
        else "a knife edge"  # fmt: skip
    axis = (
        f"an axis offset by {num(f['offset'])} m (the line x = {num(f['offset'])} m, the cam "
        "centre at the origin)"
        if f.get("offset")
        else "an axis through the cam centre"
    )
    last = f", then dwells for {num(rest[0]['duration_deg'])} deg" if rest else ""
    return (
        f"A disc cam of base radius {num(cam['base_radius'])} m turns {sense(cam['omega'])} at a "
        f"constant {abs(cam['omega']):g} rad/s. Its translating follower touches it with "
        f"{contact} on {axis}. From cam angle 0 the follower rises {num(rise['lift'])} m by "
        f"the {LAW_WORDS[rise['law']]} law over {num(rise['duration_deg'])} deg, dwells for "
        f"{num(dwell['duration_deg'])} deg, returns by the {LAW_WORDS[ret['law']]} law over "
        f"{num(ret['duration_deg'])} deg{last}. The cam has turned through {angle} deg."
    )


def _givens(doc: Mapping[str, Any], angle: int) -> list[tuple[str, float, str]]:
    cam, f = doc["cam"], doc["follower"]
    rows = [(r"R_b", cam["base_radius"], "m"), (r"\omega", cam["omega"], "rad/s"),
            ("h", doc["segments"][0]["lift"], "m"), (r"\theta", float(angle), "deg")]  # fmt: skip
    if f["contact"] == "roller":
        rows.insert(1, ("r_f", f["roller_radius"], "m"))
    if f.get("offset"):
        rows.insert(1, (r"\varepsilon", f["offset"], "m"))
    return rows


def _lift_scales(doc: Mapping[str, Any]) -> dict[str, float]:
    """The size of an answer in each unit: h omega^k / beta^k (the shortest lift), the base
    radius for a length, one radian for an angle."""
    omega = abs(doc["cam"]["omega"])
    h = doc["segments"][0]["lift"]
    beta = math.radians(min(s["duration_deg"] for s in doc["segments"] if "law" in s))
    return {
        "m/s": h * omega / beta,
        "m/s^2": h * omega**2 / beta**2,
        "m/s^3": h * omega**3 / beta**3,
        "rad": 1.0,
        "m": doc["cam"]["base_radius"],
    }


def follower_motion(rng: random.Random, difficulty: str) -> Draft:
    """The follower's velocity and acceleration (challenging: and jerk) at a cam angle inside the
    rise or the return."""
    doc = _draw_cam(rng, difficulty, "cam_roller_translating")
    angle = _angle_in_a_lift(rng, doc)
    root = cam_root(angle)
    asked = [
        Asked("v", "velocity of the follower", "m/s", f"{root}.follower.velocity", "v"),
        Asked("a", "acceleration of the follower", "m/s^2", f"{root}.follower.acceleration", "a"),
    ]
    if difficulty == "challenging":
        asked.append(Asked("j", "jerk of the follower", "m/s^3", f"{root}.follower.jerk", "j"))
    what = "velocity, acceleration and jerk" if difficulty == "challenging" else (
        "velocity and acceleration")  # fmt: skip
    text = (
        _cam_text(doc, angle) + f" Find the follower's {what} there (positive away from the cam "
        "centre)."
    )
    latex = givens_latex(_givens(doc, angle)) + r"\\" + asked_latex(asked)
    return Draft("Cam: the follower's motion", text, latex, doc, tuple(asked), _lift_scales(doc),
                 _design_check)  # fmt: skip


def pressure_angle(rng: random.Random, difficulty: str) -> Draft:
    """The pressure angle at a cam angle (standard: and the cam surface's radius of curvature;
    challenging: and the largest pressure angle over the revolution)."""
    preset = "cam_offset_knife" if rng.random() < 0.5 else "cam_roller_translating"
    doc = _draw_cam(rng, difficulty, preset)
    angle = _angle_in_a_lift(rng, doc)
    root = cam_root(angle)
    asked = [Asked("phi", "pressure angle", "rad", f"{root}.pressure_angle", r"\phi")]
    if difficulty != "basic":
        asked.append(Asked("rho", "radius of curvature of the cam surface", "m",
                           f"{root}.radius_of_curvature", r"\rho"))  # fmt: skip
    if difficulty == "challenging":
        extremes = f"{root}.diagnostics.extremes.pressure_angle"
        asked += [
            Asked("phi_min", "smallest pressure angle over the revolution", "rad",
                  f"{extremes}.min", r"\phi_{\min}"),
            Asked("phi_max", "largest pressure angle over the revolution", "rad",
                  f"{extremes}.max", r"\phi_{\max}"),
        ]  # fmt: skip
    names = {
        "basic": "the pressure angle",
        "standard": "the pressure angle and the radius of curvature of the cam surface",
        "challenging": "the pressure angle and the radius of curvature of the cam surface",
    }
    text = _cam_text(doc, angle) + f" Find, at that cam angle, {names[difficulty]} (in rad, m)."
    if difficulty == "challenging":
        text += (
            " Find also the smallest and the largest pressure angle over a revolution (signed: "
            "positive on the rise of a follower without offset, negative on its return)."
        )
    latex = givens_latex(_givens(doc, angle)) + r"\\" + asked_latex(asked)
    return Draft("Cam: pressure angle and curvature", text, latex, doc, tuple(asked),
                 _lift_scales(doc), _design_check)  # fmt: skip


def cam_mistakes(exercise: Exercise) -> list[tuple[str, str, dict[str, float]]]:
    """The typical mistakes of a cam exercise as (catalogue id, sentence, wrong answers): the
    rates without the cam's speed, the segment's duration in degrees, a pressure angle in
    degrees."""
    angle = cam_angle_of(exercise)
    assert angle is not None
    doc = exercise.scene
    omega = doc["cam"]["omega"]
    theta, duration = float(angle), 0.0
    for segment in doc["segments"]:
        if theta < segment["duration_deg"]:
            duration = segment["duration_deg"]
            break
        theta -= segment["duration_deg"]
    orders = {"v": 1, "a": 2, "j": 3}
    rates = {k: v for k, v in exercise.answers.items() if k in orders}
    out = []
    if rates:
        out.append((
            "cam_omega_left_out",
            "This is the derivative in the cam angle, per radian: the rate in time is it times "
            "the cam's speed, v = (ds/dtheta) omega, a = (d2s/dtheta2) omega^2.",
            {k: cam_rate_without_omega(v, omega, orders[k]) for k, v in rates.items()},
        ))  # fmt: skip
        out.append((
            "cam_beta_in_degrees",
            "This is what the segment's duration in degrees gives: in ds/dtheta = h y'/beta, "
            "beta is in radians, as theta is.",
            {k: cam_beta_in_degrees(v, duration, orders[k]) for k, v in rates.items()},
        ))  # fmt: skip
    angles = {k: math.degrees(v) for k, v in exercise.answers.items() if k.startswith("phi")}
    if angles:
        out.append((
            "degrees_for_radians",
            "This is the right value in degrees: the answer is asked in radians; multiply "
            "degrees by pi/180.",
            angles,
        ))  # fmt: skip
    return out

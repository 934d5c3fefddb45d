"""What the endpoints answer for a gear train: one instant (POST /analyze: every member's
angular velocity, each gear's velocity relative to its carrier, every mesh's pitch-line speed,
the train values, with ``input_torque`` every member's torque) and the train over a time range
(POST /sweep with ``time_range``: every member's angle, each planet's centre).

The inputs are constant angular velocities, so every member turns at a constant rate and its
angle from t = 0 is theta = omega t; a planet's centre turns with its carrier about the
carrier's axis. Results are frozen (``solver.analysis.results``); their ``as_dict()`` is the HTTP
body (docs/GEARS.md).
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from fractions import Fraction
from typing import Any

import numpy as np

from solver.analysis.results import AnalysisResult, TimeSweepResult
from solver.analysis.sweeps import MAX_SAMPLES
from solver.errors import InvalidScene, LimitExceeded
from solver.gears.geometry import Layout, check_pitch_circles
from solver.gears.scene import GearTrainScene, build_gear_train, real
from solver.gears.train import member_torques, speed_transfer, willis_relation

MAX_TORQUE = 1e12  # N m
MAX_RESULT = 1e300  # a speed, torque or power past this is refused (its square would overflow)


def parse_gear_train(doc: Mapping[str, Any]) -> GearTrainScene:
    """Validate a ``gear_train`` document (``InvalidScene`` with the numbers): its names and
    values (``scene.build_gear_train``), its pitch circles (``geometry.check_pitch_circles``)
    and its inputs against the degrees of freedom (``train.speed_transfer``)."""
    scene = build_gear_train(doc)
    check_pitch_circles(scene)
    speed_transfer(scene)
    return scene


def number(value: Fraction, what: str) -> float:
    """An exact result as a float, or ``InvalidScene`` where it does not fit one (a train of many
    large ratios, a first input too slow for its train values): never an infinity."""
    try:
        out = float(value)
    except OverflowError:
        out = math.inf
    if not math.isfinite(out) or abs(out) > MAX_RESULT:
        raise InvalidScene(
            f"{what}: about 10^{_magnitude(value)}, more than {MAX_RESULT:g}; the tooth ratios "
            "multiply the inputs past what a float holds"
        )
    return out


def _magnitude(value: Fraction) -> int:
    """log10 |value|, roughly (from the digits of numerator and denominator)."""
    return len(str(abs(value.numerator))) - len(str(value.denominator))


def _torques(value: Mapping[str, Any]) -> dict[str, float]:
    if not isinstance(value, Mapping) or not value:
        raise InvalidScene(f"input_torque: expected an object input -> torque (N m), got {value!r}")
    out = {}
    for name, torque in value.items():
        number = real(torque)
        if number is None or abs(number) > MAX_TORQUE:
            raise InvalidScene(
                f"input_torque.{name}: expected a finite number of N m (|T| <= {MAX_TORQUE:g}), "
                f"got {torque!r:.40}"
            )
        out[str(name)] = number
    return out


def analyze_gear_train(
    scene: GearTrainScene,
    input_torque: Mapping[str, Any] | None = None,
    warnings: Sequence[str] = (),
) -> AnalysisResult:
    """The body of POST /analyze for a gear train (docs/GEARS.md)."""
    transfer = speed_transfer(scene)
    omega = transfer.speeds([value for _, value in scene.inputs])
    first = scene.inputs[0][0] if scene.inputs else None
    layout: Layout | None = check_pitch_circles(scene)
    torque = member_torques(scene, _torques(input_torque)) if input_torque is not None else None
    members: dict[str, Any] = {}
    for name in scene.members:
        entry: dict[str, Any] = {"omega": number(omega[name], f"members.{name}.omega")}
        gear = next((g for g in scene.gears if g.name == name), None)
        if gear is not None:
            arm = omega[gear.carrier] if gear.carrier else Fraction(0)
            entry |= {
                "type": "gear",
                "teeth": gear.teeth,
                "internal": gear.internal,
                "carrier": gear.carrier,
                "omega_relative": number(omega[name] - arm, f"members.{name}.omega_relative"),
                "pitch_radius": layout.pitch_radius[name] if layout else None,
            }
        else:
            entry["type"] = "carrier"
        base = omega[first] if first is not None else Fraction(0)
        entry["train_value"] = (
            number(omega[name] / base, f"members.{name}.train_value") if base != 0 else None
        )
        entry["centre"] = list(layout.centre[name]) if layout else None
        if torque is not None:
            entry["torque"] = number(torque[name], f"members.{name}.torque")
            entry["power"] = number(torque[name] * omega[name], f"members.{name}.power")
        members[name] = entry
    meshes = []
    for mesh in scene.meshes:
        a, b = (scene.gear(n) for n in mesh.gears)
        arm = omega[mesh.carrier] if mesh.carrier else Fraction(0)
        # v = r_a |omega_a - omega_arm| = r_b |omega_b - omega_arm|, r = m N / 2 (exactly equal)
        module = scene.module
        speed = (
            abs(number((omega[a.name] - arm) * a.teeth * Fraction(module) / 2, "pitch-line speed"))
            if module is not None
            else None
        )
        meshes.append(
            {
                "gears": list(mesh.gears),
                "carrier": mesh.carrier,
                "internal": mesh.internal,
                "willis_ratio": float(willis_relation(a.teeth, b.teeth, mesh.internal)),
                "pitch_line_speed": speed,
            }
        )
    body = {
        "kind": "gear_train",
        "degrees_of_freedom": transfer.degrees_of_freedom,
        "first_input": first,
        "members": members,
        "meshes": meshes,
        "warnings": list(warnings),
    }
    return AnalysisResult(body)


def sweep_gear_train(
    scene: GearTrainScene,
    time_range: Sequence[float],
    samples: int,
    warnings: Sequence[str] = (),
) -> TimeSweepResult:
    """The body of POST /sweep with ``time_range`` for a gear train: theta = omega t for every
    member; a planet's centre c(t) = c_arm + R(theta_arm) (c_0 - c_arm) (with a module)."""
    if not 2 <= samples <= MAX_SAMPLES:
        raise LimitExceeded(f"samples: {samples} is outside 2..{MAX_SAMPLES}")
    if len(time_range) != 2:
        raise InvalidScene("time_range: expected [t0, t1]")
    t0, t1 = (real(t) for t in time_range)
    if t0 is None or t1 is None or not t1 > t0:
        raise InvalidScene(f"time_range: expected [t0, t1] with t1 > t0, got {list(time_range)}")
    time = np.linspace(t0, t1, samples)
    omega = speed_transfer(scene).speeds([value for _, value in scene.inputs])
    layout = check_pitch_circles(scene)
    rates = {name: number(omega[name], f"members.{name}.omega") for name in scene.members}
    angle = {name: rates[name] * time + 0.0 for name in scene.members}  # + 0.0: no -0.0
    members: dict[str, Any] = {}
    for name in scene.members:
        entry: dict[str, Any] = {"angle": angle[name]}
        carrier = scene.mount(name)
        if layout is not None and carrier is not None:
            cx, cy = layout.centre[carrier]
            dx, dy = layout.centre[name][0] - cx, layout.centre[name][1] - cy
            turn = angle[carrier]
            entry["centre"] = np.column_stack(
                (
                    cx + dx * np.cos(turn) - dy * np.sin(turn),
                    cy + dx * np.sin(turn) + dy * np.cos(turn),
                )
            )
        members[name] = entry
    body = {
        "kind": "gear_train",
        "time": time,
        "samples": samples,
        "members": members,
        "warnings": list(warnings),
    }
    return TimeSweepResult(body)

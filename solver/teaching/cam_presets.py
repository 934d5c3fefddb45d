"""The Cams family: textbook cam mechanisms as cam scenes (docs/CAMS.md) from named parameters.

Four followers on a disc cam with a rise, a dwell, a return and a dwell: a translating roller
follower, an offset knife edge, a flat-faced follower and an oscillating roller follower. Lengths
in m, angles in degrees (an oscillating follower's lift too, turned to rad in the scene), the
laws chosen by index among ``LAW_NAMES``. Every default makes a cam without warnings.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass
from types import MappingProxyType
from typing import Any

from solver.cams.laws import LAW_NAMES
from solver.errors import InvalidScene
from solver.teaching.presets import Preset, PresetParameter

MAX_CAM_LENGTH = 10.0  # m
MAX_CAM_OMEGA = 1e4  # rad/s


@dataclass(frozen=True)
class CamPreset(Preset):
    """A cam mechanism type: its parameters (the common ones and its follower's); its
    ``geometry`` gives the follower's part of the scene; ``lift_unit`` "deg" for an oscillating
    follower's lift (written to the scene in rad)."""

    lift_unit: str = "m"

    def build(self, values: Mapping[str, float]) -> dict[str, Any]:
        """The cam scene: rise, dwell, return over ``return_deg`` and a dwell to 360 deg."""
        v = self.resolve(values)
        rest = 360.0 - v["rise_deg"] - v["dwell_deg"] - v["return_deg"]
        if rest < 0.0:
            raise InvalidScene(
                f"rise_deg + dwell_deg + return_deg = {v['rise_deg']:g} + {v['dwell_deg']:g} + "
                f"{v['return_deg']:g} = {360.0 - rest:g} deg, more than 360 deg"
            )
        lift = math.radians(v["lift"]) if self.lift_unit == "deg" else v["lift"]
        segments: list[dict[str, Any]] = [
            {"type": "rise", "law": LAW_NAMES[int(v["rise_law"])], "lift": lift,
             "duration_deg": v["rise_deg"]},
            {"type": "dwell", "duration_deg": v["dwell_deg"]},
            {"type": "return", "law": LAW_NAMES[int(v["return_law"])], "lift": lift,
             "duration_deg": v["return_deg"]},
            {"type": "dwell", "duration_deg": rest},
        ]  # fmt: skip
        return {
            "kind": "cam",
            "title": self.title,
            "cam": {"base_radius": v["base_radius"], "omega": v["omega"]},
            "follower": self.geometry(v),
            "segments": [s for s in segments if s["duration_deg"] > 0.0],
        }


def _length(name: str, default: float, description: str, minimum: float = 1e-4) -> PresetParameter:
    return PresetParameter(name, default, "m", description, minimum, MAX_CAM_LENGTH)


def _law(name: str, default: str, what: str) -> PresetParameter:
    return PresetParameter(
        name,
        float(LAW_NAMES.index(default)),
        "",
        f"The {what}'s motion law.",
        choices=tuple(float(i) for i in range(len(LAW_NAMES))),
        labels=LAW_NAMES,
    )


def _duration(name: str, default: float, what: str, minimum: float = 1.0) -> PresetParameter:
    return PresetParameter(name, default, "deg", f"Cam angle of the {what}.", minimum, 358.0)


def _common(base: float, lift: PresetParameter, rise: str, ret: str) -> tuple[PresetParameter, ...]:
    return (
        _length("base_radius", base, "Base circle radius: the cam surface's smallest radius."),
        PresetParameter(
            "omega",
            10.0,
            "rad/s",
            "Angular velocity of the cam, counter-clockwise positive.",
            -MAX_CAM_OMEGA,
            MAX_CAM_OMEGA,
        ),
        lift,
        _law("rise_law", rise, "rise"),
        _duration("rise_deg", 120.0, "rise"),
        _duration("dwell_deg", 60.0, "dwell after the rise", 0.0),
        _law("return_law", ret, "return"),
        _duration("return_deg", 120.0, "return"),
    )


def _lift(default: float) -> PresetParameter:
    return _length("lift", default, "The follower's lift (total rise).")


def _roller(default: float) -> PresetParameter:
    return _length("roller_radius", default, "Radius of the roller.")


def _offset(default: float) -> PresetParameter:
    return PresetParameter(
        "offset", default, "m",
        "The follower's axis is the line x = offset (positive: less pressure angle on the rise "
        "of a counter-clockwise cam).", -MAX_CAM_LENGTH, MAX_CAM_LENGTH,
    )  # fmt: skip


CAM_PRESETS: Mapping[str, CamPreset] = MappingProxyType(
    {
        p.name: p
        for p in (
            CamPreset(
                "cam_roller_translating",
                "Disc cam, translating roller follower",
                "A roller follower on an offset axis: cycloidal rise, dwell, 3-4-5 return.",
                (*_common(0.04, _lift(0.025), "cycloidal", "polynomial_345"),
                 _roller(0.01), _offset(0.005)),
                lambda v: {"motion": "translating", "contact": "roller",
                           "roller_radius": v["roller_radius"], "offset": v["offset"]},
            ),
            CamPreset(
                "cam_offset_knife",
                "Disc cam, offset knife-edge follower",
                "A knife edge on an axis offset from the cam centre: the pitch curve is the cam.",
                (*_common(0.05, _lift(0.02), "cycloidal", "cycloidal"), _offset(0.01)),
                lambda v: {"motion": "translating", "contact": "knife", "offset": v["offset"]},
            ),
            CamPreset(
                "cam_flat_faced",
                "Disc cam, flat-faced translating follower",
                "A flat face square to the follower axis: rho = R_b + s + s'' must stay positive.",
                _common(0.05, _lift(0.02), "modified_sine", "modified_sine"),
                lambda v: {"motion": "translating", "contact": "flat"},
            ),
            CamPreset(
                "cam_oscillating_roller",
                "Disc cam, oscillating roller follower",
                "A roller at the end of an arm swinging about a fixed pivot; the lift is an angle.",
                (*_common(0.04, PresetParameter("lift", 15.0, "deg", "The arm's swing.", 0.1, 80.0),
                          "polynomial_345", "polynomial_345"),
                 _roller(0.01),
                 PresetParameter("pivot_x", 0.09, "m", "The pivot's x.", -MAX_CAM_LENGTH,
                                 MAX_CAM_LENGTH),
                 PresetParameter("pivot_y", 0.0, "m", "The pivot's y.", -MAX_CAM_LENGTH,
                                 MAX_CAM_LENGTH),
                 _length("arm_length", 0.08, "The arm, from the pivot to the roller centre.")),
                lambda v: {"motion": "oscillating", "contact": "roller",
                           "roller_radius": v["roller_radius"],
                           "pivot": [v["pivot_x"], v["pivot_y"]], "arm_length": v["arm_length"]},
                lift_unit="deg",
            ),
        )
    }
)  # fmt: skip

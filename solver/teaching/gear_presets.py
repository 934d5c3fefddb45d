"""Textbook gear trains as generators of scene-v1 ``gear_train`` documents (docs/GEARS.md): a
compound reverted train, a simple planetary train with the ring fixed, a spur-gear differential
with two inputs, two planetary stages in series.

Each preset turns a few named parameters (tooth numbers, the module in m, input speeds in rad/s)
into a document the gear solver accepts; a choice of teeth that cannot be cut on one module (a
reverted train whose two stages differ in centre distance) is refused with the numbers. They
are listed apart from the linkages (``GET /api/v1/presets?family=gear_trains``) so that the
linkage menu and its answers stay as they are.
"""

from __future__ import annotations

import inspect
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass
from types import MappingProxyType
from typing import Any

from solver.errors import InvalidScene
from solver.gears import parse_gear_train
from solver.teaching.presets import Preset, PresetParameter

MIN_TEETH = 8
MAX_TEETH = 400
MAX_SPEED = 1e4  # rad/s


Generator = Callable[[Mapping[str, float]], dict[str, Any]]


@dataclass(frozen=True)
class GearPreset(Preset):
    """A textbook gear train: its parameters and (``geometry``) the generator of the train's
    part of the scene."""

    def build(self, values: Mapping[str, float]) -> dict[str, Any]:
        """The scene-v1 ``gear_train`` document; missing values take their defaults. Raises
        ``InvalidScene`` for an unknown parameter, a value out of range or teeth the train
        cannot have."""
        v = self.resolve(values)
        for p in self.parameters:
            if p.unit == "teeth" and v[p.name] != int(v[p.name]):
                raise InvalidScene(f"{p.name} = {v[p.name]:g} is not a whole number of teeth")
        doc = {"kind": "gear_train", "title": self.title, **self.geometry(v)}
        parse_gear_train(doc)  # the document is the contract's: checked as a client's would be
        return doc


def _teeth(name: str, default: int, description: str) -> PresetParameter:
    return PresetParameter(name, default, "teeth", description, MIN_TEETH, MAX_TEETH)


def _speed(name: str, default: float, description: str) -> PresetParameter:
    return PresetParameter(name, default, "rad/s", description, -MAX_SPEED, MAX_SPEED)


MODULE = PresetParameter("module", 0.002, "m", "The module m: pitch radii r = m N / 2.", 1e-4, 0.05)


def _n(v: Mapping[str, float], name: str) -> int:
    return int(v[name])


def _compound_reverted(v: Mapping[str, float]) -> dict[str, Any]:
    """Gear 2 on the input shaft drives gear 3; gear 4, keyed to gear 3 on the countershaft,
    drives gear 5 on the output shaft, coaxial with the input (reverted): on one module the two
    stages need one centre distance, N2 + N3 = N4 + N5. Train value e = (N2 / N3)(N4 / N5)."""
    n2, n3, n4, n5 = (_n(v, k) for k in ("N2", "N3", "N4", "N5"))
    if n2 + n3 != n4 + n5:
        raise InvalidScene(
            f"a reverted train on one module needs N2 + N3 = N4 + N5 (one centre distance): "
            f"{n2} + {n3} = {n2 + n3} but {n4} + {n5} = {n4 + n5}"
        )
    return {
        "gears": {"gear2": {"teeth": n2}, "gear3": {"teeth": n3}, "gear4": {"teeth": n4},
                  "gear5": {"teeth": n5}},
        "carriers": [],
        "mounts": {},
        "shafts": [["gear3", "gear4"]],
        "meshes": [["gear2", "gear3"], ["gear4", "gear5"]],
        "inputs": {"gear2": v["omega_in"]},
        "module": v["module"],
    }  # fmt: skip


def _planetary_stage(sun: int, planet: int, stage: str = "") -> dict[str, Any]:
    """One simple planetary stage (its members' names end in ``stage``): a sun, a planet on the
    arm, the annulus around them with N_ring = N_sun + 2 N_planet teeth (one module)."""
    s, p, r, arm = (f"{name}{stage}" for name in ("sun", "planet", "ring", "arm"))
    return {
        "gears": {s: {"teeth": sun}, p: {"teeth": planet},
                  r: {"teeth": sun + 2 * planet, "internal": True}},
        "carriers": [arm],
        "mounts": {p: arm},
        "meshes": [[s, p], [p, r]],
    }  # fmt: skip


def _planetary_train(
    stages: Sequence[Mapping[str, Any]],
    shafts: list[list[str]],
    inputs: dict[str, float],
    module: float,
) -> dict[str, Any]:
    """The planetary ``stages`` in one train, members keyed together by ``shafts``."""
    return {
        "gears": {k: g for stage in stages for k, g in stage["gears"].items()},
        "carriers": [c for stage in stages for c in stage["carriers"]],
        "mounts": {k: c for stage in stages for k, c in stage["mounts"].items()},
        "shafts": shafts,
        "meshes": [m for stage in stages for m in stage["meshes"]],
        "inputs": inputs,
        "module": module,
    }


def _planetary_ring_fixed(v: Mapping[str, float]) -> dict[str, Any]:
    """A sun driven, one planet on the arm, the annulus fixed (N_ring = N_sun + 2 N_planet on one
    module): the arm turns at omega_arm / omega_sun = N_sun / (N_sun + N_ring)."""
    stage = _planetary_stage(_n(v, "N_sun"), _n(v, "N_planet"))
    return _planetary_train([stage], [], {"sun": v["omega_sun"], "ring": 0.0}, v["module"])


def _differential(v: Mapping[str, float]) -> dict[str, Any]:
    """A spur-gear differential: side gears left and right (equal teeth) on the carrier's axis,
    two meshing planets on the carrier, one on each side gear; both side gears driven (two
    inputs): the carrier turns at the mean, (omega_left + omega_right) / 2."""
    side, planet = _n(v, "N_side"), _n(v, "N_planet")
    return {
        "gears": {"left": {"teeth": side}, "planet1": {"teeth": planet},
                  "planet2": {"teeth": planet}, "right": {"teeth": side}},
        "carriers": ["carrier"],
        "mounts": {"planet1": "carrier", "planet2": "carrier"},
        "shafts": [],
        "meshes": [["left", "planet1"], ["planet1", "planet2"], ["planet2", "right"]],
        "inputs": {"left": v["omega_left"], "right": v["omega_right"]},
        "module": v["module"],
    }  # fmt: skip


def _two_stage_planetary(v: Mapping[str, float]) -> dict[str, Any]:
    """Two simple planetary stages in series, both rings fixed, the first arm keyed to the
    second sun: e = N_sun1 / (N_sun1 + N_ring1) x N_sun2 / (N_sun2 + N_ring2), with
    N_ring = N_sun + 2 N_planet in each stage."""
    stages = [_planetary_stage(_n(v, f"N_sun{k}"), _n(v, f"N_planet{k}"), str(k)) for k in (1, 2)]
    inputs = {"sun1": v["omega_sun"], "ring1": 0.0, "ring2": 0.0}
    return _planetary_train(stages, [["arm1", "sun2"]], inputs, v["module"])


def _preset(
    name: str, title: str, generator: Generator, *parameters: PresetParameter
) -> GearPreset:
    return GearPreset(name, title, inspect.cleandoc(generator.__doc__ or ""), parameters, generator)


GEAR_PRESETS: Mapping[str, GearPreset] = MappingProxyType(
    {
        p.name: p
        for p in (
            _preset(
                "compound_reverted",
                "compound reverted gear train",
                _compound_reverted,
                _teeth("N2", 20, "Teeth of gear 2, on the input shaft."),
                _teeth("N3", 40, "Teeth of gear 3, on the countershaft."),
                _teeth("N4", 16, "Teeth of gear 4, keyed to gear 3."),
                _teeth("N5", 44, "Teeth of gear 5, on the output shaft."),
                _speed("omega_in", 150.0, "Angular velocity of the input shaft (gear 2)."),
                MODULE,
            ),
            _preset(
                "planetary_ring_fixed",
                "simple planetary train, ring fixed",
                _planetary_ring_fixed,
                _teeth("N_sun", 20, "Teeth of the sun."),
                _teeth("N_planet", 30, "Teeth of the planet (the ring has N_sun + 2 N_planet)."),
                _speed("omega_sun", 100.0, "Angular velocity of the sun (the input)."),
                MODULE,
            ),
            _preset(
                "differential",
                "spur-gear differential, two inputs",
                _differential,
                _teeth("N_side", 20, "Teeth of each side gear."),
                _teeth("N_planet", 10, "Teeth of each of the two planets."),
                _speed("omega_left", 30.0, "Angular velocity of the left side gear."),
                _speed("omega_right", 10.0, "Angular velocity of the right side gear."),
                MODULE,
            ),
            _preset(
                "two_stage_planetary",
                "two-stage planetary train",
                _two_stage_planetary,
                _teeth("N_sun1", 20, "Teeth of the first stage's sun (the input)."),
                _teeth("N_planet1", 30, "Teeth of the first stage's planet."),
                _teeth("N_sun2", 18, "Teeth of the second stage's sun, keyed to the first arm."),
                _teeth("N_planet2", 27, "Teeth of the second stage's planet."),
                _speed("omega_sun", 300.0, "Angular velocity of the first sun (the input)."),
                MODULE,
            ),
        )
    }
)


def build_gear_preset(name: str, values: Mapping[str, float]) -> dict[str, Any]:
    """The scene-v1 ``gear_train`` document of gear preset ``name`` with the given values."""
    preset = GEAR_PRESETS.get(name)
    if preset is None:
        raise InvalidScene(f"unknown gear preset '{name}'; available: {', '.join(GEAR_PRESETS)}")
    return preset.build(values)

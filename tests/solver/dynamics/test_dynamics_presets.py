"""Presets with masses: the optional uniform bars, gravity and load of every textbook preset, and
seed 004 as a preset (the same scene as the reference's, so the same answers)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from solver.analysis.instant import analyze
from solver.dynamics.analysis import linkage_dynamics
from solver.model.scene import parse_linkage
from solver.teaching.presets import PRESETS, build_preset
from tests.dynamics_cases import EXPECTED, seed004_scene

TEXTBOOK = [name for name in PRESETS if name != "seed004"]


@pytest.mark.parametrize("name", TEXTBOOK)
def test_default_presets_have_no_mass_fields(name: str) -> None:
    doc = build_preset(name, {})
    assert not {"masses", "point_masses", "gravity", "forces", "torques"} & set(doc)


@pytest.mark.parametrize("name", TEXTBOOK)
def test_mass_per_length_gravity_and_load(name: str) -> None:
    """Every moving link a uniform bar of mass rho |PQ|; the driver's torque from Newton-Euler
    equals the power balance's; the load acts on the output."""
    doc = build_preset(name, {"mass_per_length": 4.0, "gravity": 9.81, "load": -25.0})
    moving = [k for k, link in doc["links"].items() if not link.get("ground")]
    assert sorted(doc["masses"]) == sorted(moving)
    for body in doc["masses"].values():
        P, Q = (doc["points"][p] for p in body["bar"])
        assert body["mass"] == pytest.approx(4.0 * math.dist(P, Q), rel=1e-15)
    assert doc["gravity"] == [0.0, -9.81]
    assert len(doc.get("forces", [])) + len(doc.get("torques", [])) == 1
    scene = parse_linkage(doc)
    result = linkage_dynamics(scene, analyze(scene, ["acceleration"]).motion, np.zeros(1))
    (driver,) = result.drivers
    scale = max(float(np.hypot(*j.force[0])) for j in result.forces.joints) * scene.size
    assert driver.torque_from_power_balance[0] == pytest.approx(driver.torque[0], abs=1e-9 * scale)
    assert result.energy.mass == pytest.approx(sum(b["mass"] for b in doc["masses"].values()))


def test_seed004_preset_is_the_reference_scene() -> None:
    preset, reference = build_preset("seed004", {}), seed004_scene()
    for point, xy in reference["points"].items():
        assert preset["points"][point] == pytest.approx(xy, abs=1e-15)
    for key in ("links", "joints", "masses", "point_masses", "gravity"):
        assert preset[key] == reference[key]
    assert preset["drivers"][0]["omega"] == pytest.approx(8 * math.pi, rel=1e-15)


@pytest.mark.parametrize("angle", [90, 180])
def test_seed004_preset_answers_the_reference(angle: int) -> None:
    scene = parse_linkage(build_preset("seed004", {"crank_angle_deg": angle}))
    result = linkage_dynamics(scene, analyze(scene, ["acceleration"]).motion, np.zeros(1))
    torque = EXPECTED[f"theta={angle}deg/driving_torque_M_O"]["value"]
    assert result.drivers[0].torque[0] == pytest.approx(torque, rel=1e-9)
    force = EXPECTED[f"theta={angle}deg/force_B_coupler_on_member3"]["value"]
    assert result.forces.joints[2].force[0] == pytest.approx(force, rel=1e-9)


def test_seed004_force_on_must_exceed_the_least_phi3() -> None:
    from solver.errors import InvalidScene

    with pytest.raises(InvalidScene, match="force_on_deg"):
        build_preset("seed004", {"force_on_deg": -40})

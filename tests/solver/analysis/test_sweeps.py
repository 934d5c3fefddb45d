"""Poles and slider parts over a sweep equal those of single instants at the same driver angle
(source: /analyze, itself checked against seed-cases.json); a translating carrier has no pole."""

import json
import math
from pathlib import Path

import numpy as np
import pytest

from solver.analysis.instant import analyze
from solver.analysis.sweeps import sweep, sweep_time
from solver.errors import NotAssemblable
from solver.model.scene import parse_linkage
from solver.teaching.presets import build_preset

EXAMPLES = Path(__file__).resolve().parents[3] / "server" / "examples"
ALL = ["position", "velocity", "acceleration", "poles", "components"]


def at_angle(doc: dict, radians: float) -> dict:
    driver = {**doc["drivers"][0], "angle_deg": math.degrees(radians)}
    return {**doc, "drivers": [driver]}


def check_against_instants(doc: dict, samples: int) -> None:
    """Tolerance: 1e-9 of the scene's velocity and acceleration scales (the two answers take
    different paths: branch continuation versus the drawn branch at angle_deg)."""
    result = sweep(parse_linkage(doc), samples, ALL)
    size = parse_linkage(doc).size
    for k in range(0, samples, max(1, samples // 5)):
        single = analyze(parse_linkage(at_angle(doc, float(result.driver_angle[k]))))
        for name, (v_poles, a_poles) in result.poles.items():
            for poles, expected in (
                (v_poles, single.links[name].velocity_pole),
                (a_poles, single.links[name].acceleration_pole),
            ):
                got = poles.at(k)
                assert (got is None) == (expected is None), (name, k)
                if got is not None and expected is not None:
                    assert np.linalg.norm(got - expected) <= 1e-9 * max(size, np.linalg.norm(got))
        for swept, one in zip(result.joints, single.joints, strict=True):
            v_scale = np.abs(swept.velocity).max() + 1.0
            a_scale = np.abs(swept.acceleration).max() + 1.0
            for part in ("transport_velocity", "relative_velocity"):
                np.testing.assert_allclose(
                    getattr(swept, part)[k], getattr(one, part), atol=1e-9 * v_scale
                )
            for part in (
                "transport_acceleration",
                "relative_acceleration",
                "coriolis_acceleration",
            ):
                np.testing.assert_allclose(
                    getattr(swept, part)[k], getattr(one, part), atol=1e-9 * a_scale
                )


def test_slotted_lever_sweep_matches_single_instants() -> None:
    check_against_instants(json.loads((EXAMPLES / "S000-T2.json").read_text()), 40)


def test_offset_slider_crank_sweep_matches_single_instants() -> None:
    check_against_instants(build_preset("slider_crank", {"alpha": 5.0}), 36)


def test_translating_carrier_has_no_velocity_pole_over_time() -> None:
    doc = json.loads((EXAMPLES / "S003-T1-translating-carrier.json").read_text())
    result = sweep_time(parse_linkage(doc), 0.0, 1.5, 7, ["position", "poles"])
    v_poles, _ = result.poles["carrier"]
    assert not np.any(v_poles.exists)
    crank_poles, _ = result.poles["crank1"]
    assert np.all(crank_poles.exists[1:])  # the crank turns about O1 once it moves
    np.testing.assert_allclose(crank_poles.position[1:], 0.0, atol=1e-12)


def test_a_start_that_cannot_close_is_reported_however_many_samples() -> None:
    """A triple rocker (ground 1, crank 0.8, coupler 0.51, rocker 0.61: 1.51 > 1.41, not
    Grashof) started at 180 deg, where B to D is 1.8 > 0.51 + 0.61: the sweep refuses at its
    starting angle, whether it probes first (36 samples) or turns compiled (360)."""
    doc = build_preset("four_bar", {})
    doc["points"] = {"A": [0.0, 0.0], "B": [0.4, 0.4 * math.sqrt(3.0)], "C": [0.9, 0.6]}
    doc["points"] |= {"D": [1.0, 0.0], "P": [0.6, 0.7]}
    for samples in (36, 360):
        with pytest.raises(NotAssemblable, match="at the sweep's starting angle"):
            sweep(parse_linkage(at_angle(doc, math.pi)), samples, ALL)
    assert sweep(parse_linkage(doc), 360, ALL).limits  # feasible at the drawn pose, not fully

"""What a sweep computes for the browser to draw: each four-bar loop's transmission angle per
sample, each slider's travel along its guide, and a ram's quick-return strokes; and
``solver.estimate_work``, the cost a server compares with its limits.

The quick-return time ratio is checked against the closed form (180 + a) / (180 - a), a the
deviation from 180 deg of the crank angle between the ram's two extreme positions, derived here
from the geometry alone."""

from __future__ import annotations

import math

import numpy as np
import pytest

import solver
from solver.teaching.presets import build_preset
from tests.scenes import triads


def _quick_return_closed_form(crank: float, ground: float) -> float:
    """Slot through O4: the lever's extremes are where the crank is perpendicular to it,
    cos(beta / 2) = crank / ground; the return takes beta of crank turn, the cut 360 - beta."""
    beta = 2.0 * math.acos(crank / ground)
    a = math.pi - beta  # the cut's deviation from half a turn
    return (math.pi + a) / (math.pi - a)


def _offset_slider_crank_closed_form(crank: float, rod: float, offset: float) -> float:
    """The extremes with crank and rod in line: stretched, C at r + l from A, and folded, at
    l - r; their crank angles differ by 180 deg + a, a = asin(e / (l - r)) - asin(e / (l + r))."""
    a = math.asin(offset / (rod - crank)) - math.asin(offset / (rod + crank))
    return (math.pi + a) / (math.pi - a)


@pytest.mark.parametrize("samples", [8, 36, 360, 1001])
def test_quick_return_ratio_of_the_slotted_lever_is_the_closed_form(samples: int) -> None:
    for crank, ground in ((0.1, 0.3), (0.12, 0.3), (0.2, 0.35)):
        doc = build_preset("quick_return", {"crank": crank, "ground": ground})
        body = solver.sweep(doc, samples, ["position"]).as_dict(arrays=True)
        ram = next(s for s in body["sliders"] if s["point"] == "C")
        found = ram["quick_return"]
        expected = _quick_return_closed_form(crank, ground)
        assert found["time_ratio"] == pytest.approx(expected, rel=1e-12)
        assert found["slow_stroke"] + found["fast_stroke"] == pytest.approx(2 * math.pi)
        # The extremes bound every sampled displacement.
        extremes = sorted(e["displacement"] for e in found["extreme_positions"])
        assert extremes[0] <= min(ram["displacement"]) + 1e-15
        assert extremes[1] >= max(ram["displacement"]) - 1e-15


@pytest.mark.parametrize("samples", [12, 360])
def test_quick_return_ratio_of_the_offset_slider_crank_is_the_closed_form(samples: int) -> None:
    for crank, rod, offset in ((0.1, 0.35, 0.05), (0.1, 0.3, 0.12), (0.05, 0.2, -0.08)):
        doc = build_preset("slider_crank", {"crank": crank, "rod": rod, "offset": offset})
        body = solver.sweep(doc, samples, ["position", "velocity"]).as_dict(arrays=True)
        (ram,) = body["sliders"]
        expected = _offset_slider_crank_closed_form(crank, rod, abs(offset))
        assert ram["quick_return"]["time_ratio"] == pytest.approx(expected, rel=1e-12)
        # At the extreme positions the crank and the rod are in line: |AC| = l -+ r.
        reach = sorted(
            math.hypot(doc["points"]["C"][0] + e["displacement"], offset)
            for e in ram["quick_return"]["extreme_positions"]
        )
        assert reach == pytest.approx([rod - crank, rod + crank], rel=1e-9)


def test_a_centred_slider_crank_has_no_quick_return_and_a_rocking_one_none() -> None:
    centred = solver.sweep(build_preset("slider_crank", {"offset": 0.0}), 90).as_dict(arrays=True)
    assert centred["sliders"][0]["quick_return"]["time_ratio"] == pytest.approx(1.0, abs=1e-12)
    rocking = solver.sweep(build_preset("slider_crank", {"rod": 0.1, "crank": 0.08}), 90)
    body = rocking.as_dict(arrays=True)
    if not body["feasible"]:
        assert body["sliders"][0]["quick_return"] is None


def test_slider_travel_is_the_displacement_along_the_guide_and_its_rates() -> None:
    doc = build_preset("quick_return", {})
    body = solver.sweep(doc, 360, ["position", "velocity", "acceleration"]).as_dict(arrays=True)
    ram = next(s for s in body["sliders"] if s["point"] == "C")
    p = np.asarray(body["points"]["C"]["position"])
    assert ram["displacement"] == pytest.approx(p[:, 0] - doc["points"]["C"][0], abs=1e-15)
    assert ram["sliding_velocity"] == pytest.approx(body["points"]["C"]["velocity"][:, 0])
    assert ram["sliding_acceleration"] == pytest.approx(body["points"]["C"]["acceleration"][:, 0])
    # In the lever's slot: the axis turns with the lever, s' is the relative velocity along it.
    pin = next(s for s in body["sliders"] if s["point"] == "A")
    lever = np.asarray(body["links"]["lever"]["angle"])
    turned = np.unwrap(np.arctan2(pin["axis"][:, 1], pin["axis"][:, 0]))
    assert np.ptp(turned - np.unwrap(lever)) < 1e-12
    parts = solver.sweep(doc, 360, ["components"]).as_dict(arrays=True)
    joint = next(j for j in parts["joints"] if j["point"] == "A")
    along = np.sum(joint["relative_velocity"] * pin["axis"], axis=1)
    assert pin["sliding_velocity"] == pytest.approx(along, abs=1e-12)
    # Finite differences of s over time (the crank turns at omega).
    omega = doc["drivers"][0]["omega"]
    dt = 2 * math.pi / 360 / abs(omega)
    central = (np.roll(pin["displacement"], -1) - np.roll(pin["displacement"], 1)) / (2 * dt)
    assert central == pytest.approx(pin["sliding_velocity"], rel=1e-3, abs=1e-3)


def test_sweep_fields_follow_the_requested_quantities() -> None:
    doc = build_preset("slider_crank", {})
    velocity_only = solver.sweep(doc, 20, ["velocity"]).as_dict(arrays=True)
    assert "four_bar_loops" not in velocity_only
    assert set(velocity_only["sliders"][0]) == {"point", "type", "links", "sliding_velocity"}
    poles_only = solver.sweep(doc, 20, ["poles"]).as_dict(arrays=True)
    assert "sliders" not in poles_only and "four_bar_loops" not in poles_only


def test_transmission_angle_per_sample_is_the_analysed_one() -> None:
    doc = build_preset("four_bar", {})
    body = solver.sweep(doc, 36).as_dict(arrays=True)
    (loop,) = body["four_bar_loops"]
    assert loop["angle_points"] == ["B", "C", "D"]
    for k in (0, 7, 20):
        at = dict(
            doc,
            drivers=[dict(doc["drivers"][0], angle_deg=body["driver_angle"][k] * 180 / math.pi)],
        )
        instant = solver.analyze(at, ["position"])["four_bar_loops"][0]
        assert loop["transmission_angle"][k] == pytest.approx(
            instant["transmission_angle"], abs=1e-12
        )
    # Closed form at the crank along the ground line: |BD| = ground -+ crank.
    a, b, c, d = (loop["lengths"][k] for k in ("crank", "coupler", "rocker", "ground"))
    mu = [math.acos((b * b + c * c - e * e) / (2 * b * c)) for e in (d - a, d + a)]
    assert min(loop["transmission_angle"]) >= mu[0] - 1e-12
    assert max(loop["transmission_angle"]) <= mu[1] + 1e-12


def test_estimate_work_counts_the_response_and_the_newton_work() -> None:
    doc = build_preset("four_bar", {})
    scene = solver.parse_scene(doc)
    estimate = solver.estimate_work(scene, 1000, ["position", "velocity"])
    entries = len(doc["points"]) + len(doc["links"]) + len(doc["joints"])
    assert estimate.values == 1000 * entries * 2
    assert estimate.newton is None  # closed-form dyads only
    triad = solver.parse_scene(triads(2))
    work = solver.estimate_work(triad, 360).newton
    assert work is not None and work.groups == (8,) and work.turn == 0.0
    assert work.link_samples == 8 * (360 + work.setup_samples)
    # one group of 8 links: 8 x (SAMPLE_COST + 8 x GROUP_SAMPLE_COST) per sample
    per_sample = 8 * work.sample_cost + 8 * 8 * work.group_sample_cost
    assert work.seconds == pytest.approx((360 + work.setup_samples) * per_sample, rel=1e-12)
    instant = solver.estimate_work(triad)
    assert instant.samples == 1 and instant.newton is not None

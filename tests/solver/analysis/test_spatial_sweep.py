"""Tests of solver.analysis.spatial_sweep (a spatial chain over time): every sample is the instant
analysis of the scene moved to t, built here independently (each joint in turn turns everything
after it by Rodrigues' formula, in world coordinates); finite differences of the sweep's own
positions and omegas; t = 0 is the instant analysis exactly; closed forms for seed 002 and a slider
on a turntable; bad input."""

from __future__ import annotations

import json
import math
from pathlib import Path
from typing import Any

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import solver
from solver.errors import InvalidScene, LimitExceeded

CASES = Path(__file__).resolve().parents[2] / "reference" / "seed-cases.json"
ALL = ["position", "velocity", "acceleration", "components"]


def seed_002() -> dict[str, Any]:
    cases = json.loads(CASES.read_text())["cases"]
    case = next(c for c in cases if c["id"] == "S002-spatial-arm")
    scene: dict[str, Any] = case["requests"][0]["body"]["scene"]
    return scene


def turntable_slider(w: float, u: float, u_dot: float) -> dict[str, Any]:
    """A table turning about z at w, a block sliding along x (fixed in the table) at u, u_dot."""
    return {
        "kind": "spatial_chain",
        "joints": [
            {"name": "table", "type": "revolute", "origin": [0, 0, 0], "axis": [0, 0, 1],
             "rate": w},
            {"name": "block", "type": "prismatic", "origin": [0, 0, 0], "axis": [1, 0, 0],
             "rate": u, "rate_dot": u_dot},
        ],
        "points": {"P": {"body": "block", "position": [0, 0, 0]},
                   "Q": {"body": "table", "position": [0.5, 0, 0.2]},
                   "G": {"body": "ground", "position": [1, 2, 3]}},
        "title": "slider on a turntable",
    }  # fmt: skip


# --- the scene moved to t, built independently ---------------------------------------------------


def rodrigues(v: np.ndarray, e: np.ndarray, q: float) -> np.ndarray:
    """v turned by q about the unit axis e: v cos q + (e x v) sin q + e (e . v)(1 - cos q)."""
    out: np.ndarray = (
        v * math.cos(q) + np.cross(e, v) * math.sin(q) + e * np.dot(e, v) * (1 - math.cos(q))
    )
    return out


def move(x: np.ndarray, kind: str, e: np.ndarray, o: np.ndarray, q: float) -> np.ndarray:
    """x turned by q about the line (o, e), or slid by q along e."""
    return o + rodrigues(x - o, e, q) if kind == "revolute" else x + q * e


def moved_scene(doc: dict[str, Any], t: float) -> dict[str, Any]:
    """The scene document at time t: joint k, in order, turns (slides) by q_k(t) = rate t +
    rate_dot t^2 / 2 about (along) its current axis through its current origin everything after
    it: later joints' origins and axes, points of bodies k and after; its rate becomes rate +
    rate_dot t."""
    joints = [dict(j) for j in doc["joints"]]
    for j in joints:
        j["origin"] = np.array(j["origin"], dtype=float)
        axis = np.array(j["axis"], dtype=float)
        j["axis"] = axis / np.linalg.norm(axis)
    order = {"ground": 0} | {j["name"]: k for k, j in enumerate(joints, start=1)}
    points = {n: np.array(p["position"], dtype=float) for n, p in doc["points"].items()}
    for k, j in enumerate(joints, start=1):
        rate, rate_dot = j["rate"], j.get("rate_dot", 0.0)
        q = rate * t + 0.5 * rate_dot * t * t
        e, o = j["axis"], j["origin"]

        for later in joints[k:]:
            later["origin"] = move(later["origin"], j["type"], e, o, q)
            if j["type"] == "revolute":
                later["axis"] = rodrigues(later["axis"], e, q)
        for name, p in doc["points"].items():
            if order[p["body"]] >= k:
                points[name] = move(points[name], j["type"], e, o, q)
        j["rate"] = rate + rate_dot * t
    return {
        "kind": "spatial_chain",
        "joints": [j | {"origin": list(j["origin"]), "axis": list(j["axis"])} for j in joints],
        "points": {
            n: {"body": p["body"], "position": list(points[n])} for n, p in doc["points"].items()
        },
    }


coord = st.floats(-2, 2, allow_nan=False)
# A joint rate as a problem states one: at rest, or between 1e-3 and 3 either way (a rate of
# 1e-161 rad/s is a body that turns, which the readings rightly say, yet no textbook's).
rate = st.one_of(st.just(0.0), st.floats(1e-3, 3), st.floats(-3, -1e-3))


@st.composite
def chains(draw: st.DrawFn) -> dict[str, Any]:
    n = draw(st.integers(1, 4))
    joints = []
    for k in range(n):
        axis = [draw(coord) for _ in range(3)]
        if np.linalg.norm(axis) < 0.2:
            axis = [0.0, 0.0, 1.0]
        joints.append(
            {
                "name": f"b{k}",
                "type": draw(st.sampled_from(["revolute", "prismatic"])),
                "origin": [draw(coord) for _ in range(3)],
                "axis": axis,
                "rate": draw(rate),
                "rate_dot": draw(rate),
            }
        )
    bodies = ["ground", *(j["name"] for j in joints)]
    points = {
        f"P{i}": {
            "body": draw(st.sampled_from(bodies)),
            "position": [draw(coord) for _ in range(3)],
        }
        for i in range(draw(st.integers(1, 3)))
    }
    return {"kind": "spatial_chain", "joints": joints, "points": points}


def largest(vectors: Any) -> float:
    """The largest component among the vectors, at least 1 (the scale of a tolerance)."""
    return max(1.0, *(float(np.max(np.abs(v))) for v in vectors))


# Tolerance: 1e-11 relative to the largest magnitude of the same quantity (at least 1). The two
# constructions (a product of exponentials, the joints one by one) differ by rounding only,
# ~ 1e-15 per operation over at most four joints and |t| <= 1.5.
def assert_sample_is_instant(doc: dict[str, Any], times: list[float]) -> None:
    over = solver.sweep_time(doc, (times[0], times[-1]), len(times), ALL)
    np.testing.assert_allclose(over["time"], times, rtol=0, atol=1e-15)
    for i, t in enumerate(over["time"]):
        moved = moved_scene(doc, float(t))
        instant = solver.analyze(moved, ALL)
        points = instant["points"]
        for field in ("position", "velocity", "acceleration"):
            size = largest(p[field] for p in points.values())
            for name, p in points.items():
                got = over["points"][name][field][i]
                np.testing.assert_allclose(got, p[field], rtol=0, atol=1e-11 * size)
        size = largest(p["acceleration"] for p in points.values())
        for name, p in points.items():
            for term, value in p["acceleration_terms"].items():
                got = over["points"][name]["acceleration_terms"][term][i]
                np.testing.assert_allclose(got, value, rtol=0, atol=1e-11 * size)
        for name, body in instant["bodies"].items():
            for field in ("omega", "alpha"):
                got = over["bodies"][name][field][i]
                atol = 1e-11 * largest([body[field]])
                np.testing.assert_allclose(got, body[field], rtol=0, atol=atol)
        size = largest(j["origin"] for j in moved["joints"])
        for joint, drawn in zip(over["joints"], moved["joints"], strict=True):
            np.testing.assert_allclose(
                joint["origin"][i], drawn["origin"], rtol=0, atol=1e-11 * size
            )
            np.testing.assert_allclose(joint["axis"][i], drawn["axis"], rtol=0, atol=1e-12)
            assert joint["rate"][i] == pytest.approx(drawn["rate"], rel=1e-14, abs=1e-14)


def test_seed_002_samples_are_the_moved_scene() -> None:
    assert_sample_is_instant(seed_002(), [-0.5, 0.0, 0.5, 1.0, 1.5])


def test_prismatic_samples_are_the_moved_scene() -> None:
    assert_sample_is_instant(turntable_slider(1.3, 0.4, -0.7), [0.0, 0.5, 1.0])


@pytest.mark.slow
@settings(max_examples=40, deadline=None)
@given(chains(), st.floats(-1.5, 0.0), st.floats(0.1, 1.5))
def test_random_chain_samples_are_the_moved_scene(
    doc: dict[str, Any], t0: float, t1: float
) -> None:
    assert_sample_is_instant(doc, list(np.linspace(t0, t1, 3)))


# --- closed forms --------------------------------------------------------------------------------


def test_slider_on_turntable_closed_form() -> None:
    """r(t) = s(t) (cos wt, sin wt, 0), s = u t + u_dot t^2 / 2: v = s' e_r + s w e_theta,
    a = (s'' - s w^2) e_r + 2 s' w e_theta (the Coriolis term), to 1e-12."""
    w, u, u_dot = 1.3, 0.4, -0.7
    over = solver.sweep_time(turntable_slider(w, u, u_dot), (0.0, 2.0), 9, ALL)
    t = np.asarray(over["time"])
    s, s1 = u * t + 0.5 * u_dot * t * t, u + u_dot * t
    e_r = np.stack([np.cos(w * t), np.sin(w * t), 0 * t], axis=1)
    e_th = np.stack([-np.sin(w * t), np.cos(w * t), 0 * t], axis=1)
    p = over["points"]["P"]
    np.testing.assert_allclose(p["position"], s[:, None] * e_r, atol=1e-12)
    np.testing.assert_allclose(
        p["velocity"], s1[:, None] * e_r + (s * w)[:, None] * e_th, atol=1e-12
    )
    a = (u_dot - s * w * w)[:, None] * e_r + (2 * s1 * w)[:, None] * e_th
    np.testing.assert_allclose(p["acceleration"], a, atol=1e-12)
    np.testing.assert_allclose(
        p["acceleration_terms"]["coriolis"], (2 * s1 * w)[:, None] * e_th, atol=1e-12
    )
    np.testing.assert_allclose(over["bodies"]["block"]["omega"], np.tile([0, 0, w], (9, 1)))
    ground = over["points"]["G"]
    np.testing.assert_array_equal(ground["position"], np.tile([1.0, 2.0, 3.0], (9, 1)))
    np.testing.assert_array_equal(ground["velocity"], np.zeros((9, 3)))
    block = next(j for j in over["joints"] if j["name"] == "block")
    np.testing.assert_allclose(block["displacement"], s, atol=1e-15)
    np.testing.assert_allclose(block["rate"], s1, atol=1e-15)


def test_seed_002_second_body_closed_form() -> None:
    """Seed 002: body 1 turns about z at 1 rad/s, joint 2's axis x is carried by it:
    omega_2(t) = -(cos t, sin t, 0) + (0, 0, 1), alpha_2 = (sin t, -cos t, 0), to 1e-12."""
    over = solver.sweep_time(seed_002(), (0.0, 3.0), 13, ["velocity", "acceleration"])
    t = np.asarray(over["time"])
    omega = np.stack([-np.cos(t), -np.sin(t), np.ones_like(t)], axis=1)
    alpha = np.stack([np.sin(t), -np.cos(t), np.zeros_like(t)], axis=1)
    np.testing.assert_allclose(over["bodies"]["2"]["omega"], omega, atol=1e-12)
    np.testing.assert_allclose(over["bodies"]["2"]["alpha"], alpha, atol=1e-12)


# --- finite differences of the sweep itself ------------------------------------------------------

# h = 1e-4; tolerance 1e-6 relative to the largest magnitude (at least 1): central differences err
# by ~ h^2 |omega|^2 / 6 (truncation) plus eps |x| / h^2 ~ 1e-7 (rounding of second differences).
H = 1e-4


@settings(max_examples=40, deadline=None)
@given(chains(), st.floats(-1.0, 1.0))
def test_finite_differences_of_the_sweep(doc: dict[str, Any], t: float) -> None:
    over = solver.sweep_time(doc, (t - H, t + H), 3, ALL)
    points = over["points"].values()
    v_scale = largest(p["velocity"][1] for p in points)
    a_scale = largest(p["acceleration"][1] for p in points)
    for p in points:
        x, v = np.asarray(p["position"]), np.asarray(p["velocity"])
        np.testing.assert_allclose(v[1], (x[2] - x[0]) / (2 * H), atol=1e-6 * v_scale)
        second = (x[2] - 2 * x[1] + x[0]) / H**2
        np.testing.assert_allclose(p["acceleration"][1], second, atol=1e-6 * a_scale)
        first = (v[2] - v[0]) / (2 * H)
        np.testing.assert_allclose(p["acceleration"][1], first, atol=1e-6 * a_scale)
    for b in over["bodies"].values():
        w = np.asarray(b["omega"])
        atol = 1e-6 * largest([b["alpha"][1]])
        np.testing.assert_allclose(b["alpha"][1], (w[2] - w[0]) / (2 * H), atol=atol)


# --- t = 0 is the instant ------------------------------------------------------------------------


@pytest.mark.parametrize("doc", [seed_002(), turntable_slider(1.3, 0.4, -0.7)])
def test_time_zero_is_the_instant_exactly(doc: dict[str, Any]) -> None:
    assert_time_zero_is_the_instant(doc)


@settings(max_examples=30, deadline=None)
@given(chains())
def test_random_chain_at_time_zero_is_the_instant_exactly(doc: dict[str, Any]) -> None:
    assert_time_zero_is_the_instant(doc)


def assert_time_zero_is_the_instant(doc: dict[str, Any]) -> None:
    over = solver.sweep_time(doc, (0.0, 1.0), 4, ALL)
    instant = solver.analyze(doc, ALL)
    for name, p in instant["points"].items():
        for field in ("position", "velocity", "acceleration"):
            assert list(over["points"][name][field][0]) == list(p[field]), (name, field)
        for term, value in p["acceleration_terms"].items():
            assert list(over["points"][name]["acceleration_terms"][term][0]) == list(value)
    for name, b in instant["bodies"].items():
        assert list(over["bodies"][name]["omega"][0]) == list(b["omega"])
        assert list(over["bodies"][name]["alpha"][0]) == list(b["alpha"])


def test_quantities_choose_the_fields() -> None:
    over = solver.sweep_time(seed_002(), (0.0, 1.0), 5)  # default: position
    assert set(over["points"]["A"]) == {"position"} and over["bodies"]["2"] == {}
    assert set(over["joints"][0]) == {"name", "type", "origin", "axis", "displacement"}
    over = solver.sweep_time(seed_002(), (0.0, 1.0), 5, ["velocity"])
    assert set(over["points"]["A"]) == {"velocity"} and set(over["bodies"]["2"]) == {"omega"}
    assert over["samples"] == 5 and over["feasible"] is True and over["warnings"] == ()


# --- bad input -----------------------------------------------------------------------------------


@pytest.mark.parametrize(
    ("time_range", "samples", "quantities", "error", "match"),
    [
        ((1.0, 0.0), 10, None, InvalidScene, "t1 > t0"),
        ((0.0, math.nan), 10, None, InvalidScene, "time_range"),
        ((0.0, 2e6), 10, None, InvalidScene, "must not exceed"),
        ((0.0,), 10, None, InvalidScene, "expected"),
        ((0.0, 1.0), 1, None, LimitExceeded, "samples"),
        ((0.0, 1.0), 10, ["forces"], InvalidScene, "planar linkages only"),
        ((0.0, 1.0), 10, ["speed"], InvalidScene, "unknown"),
    ],
)
def test_bad_input(
    time_range: tuple[float, ...], samples: int, quantities: Any, error: type, match: str
) -> None:
    with pytest.raises(error, match=match):
        solver.sweep_time(seed_002(), time_range, samples, quantities)


def test_a_revolution_sweep_still_refuses_a_spatial_chain() -> None:
    with pytest.raises(InvalidScene, match="time range"):
        solver.sweep(seed_002(), 10)

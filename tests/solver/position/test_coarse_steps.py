"""Sweeps whose driver steps far between two samples (``assembly.MAX_DRIVER_STEP``): the linkage
is followed on a grid split into steps within the bound and answered at the samples asked for,
so it keeps its assembly (a parallelogram stays one through its change points), warns of every
close approach at its driver angle, and costs nothing where the steps are short (the compiled
plan still runs a revolution of 360 samples)."""

from __future__ import annotations

import copy
import math
from typing import Any

import numpy as np
import pytest

import solver
from benchmarks.bench_newton import FULL_TURN
from solver.errors import LimitExceeded, NotAssemblable
from solver.model.scene import parse_linkage
from solver.position.assembly import MAX_DENSE_SAMPLES, MAX_DRIVER_STEP, dense_grid
from solver.position.drivers import driver_inputs_over_time
from solver.teaching.presets import build_preset
from tests.solver.analysis.test_events import _assert_exact_time, _four_bar, _parallelogram, _time

DRAWN = math.radians(60.0)  # the crank's drawn angle in ``_parallelogram(60.0, ...)``


def _without_moving_points(doc: dict[str, Any]) -> dict[str, Any]:
    """The scene without its moving point (a time sweep then assembles the linkage once)."""
    doc.pop("moving_points")
    return doc


def _circles(c1: np.ndarray, r1: float, c2: np.ndarray, r2: float) -> np.ndarray:
    """The intersection of the circles (c1, r1) and (c2, r2) to the left of c1 -> c2, per row."""
    d = np.hypot(*(c2 - c1).T)[:, None]
    u = (c2 - c1) / d
    a = (r1**2 - r2**2 + d**2) / (2.0 * d)
    h = np.sqrt(r1**2 - a**2)
    return np.asarray(c1 + a * u + h * np.stack([-u[:, 1], u[:, 0]], axis=1))


def _crank(t: np.ndarray) -> np.ndarray:
    """B = 0.4 (cos, sin)(60 deg + t): the crank pin at 1 rad/s."""
    return 0.4 * np.stack([np.cos(DRAWN + t), np.sin(DRAWN + t)], axis=1)


@pytest.mark.slow
@pytest.mark.parametrize(
    ("t1", "samples"), [(10.0, 2), (100.0, 4), (100.0, 11), (100.0, 37), (100.0, 42), (1e3, 50)]
)
def test_parallelogram_swept_in_long_steps_stays_a_parallelogram(t1: float, samples: int) -> None:
    """The parallelogram (crank = rocker = 0.4, coupler = ground = 1) at 1 rad/s over t1 s:
    C = B + (1, 0) at every sample, B = 0.4 (cos, sin)(60 deg + t), with crank steps of 2.4 to
    33 rad between samples (followed at those steps, the sweep took the crossed assembly, 0.7 m
    off, at each of these sample counts)."""
    result = solver.sweep_time(
        _without_moving_points(_parallelogram(60.0, [0.5, -2.0])), [0.0, t1], samples
    )
    B = _crank(np.linspace(0.0, t1, samples))
    np.testing.assert_allclose(result["points"]["B"]["position"], B, rtol=0, atol=1e-9)
    np.testing.assert_allclose(
        result["points"]["C"]["position"], B + np.array([1.0, 0.0]), atol=1e-9
    )


@pytest.mark.parametrize(("samples", "law"), [(35, "t"), (41, "t"), (35, "0.01*t**2")])
def test_four_bar_near_its_change_points_keeps_its_branch_and_warns_at_each(
    samples: int, law: str
) -> None:
    """The parallelogram with its rocker 1e-4 m longer (a crank-rocker, no change point: its two
    assemblies come within 1e-4 m at every crank angle k pi) turned by 100 rad over 100 s, at
    1 rad/s (crank steps of 2.9 and 2.5 rad) or by 0.01 t^2 rad (steps from 0.02 to 5.7 rad,
    so the intervals are split into different numbers of parts): C is on the drawn branch (the
    circles' intersection to the left of B -> D, closed form) at every sample, and each of the
    32 close approaches is warned of at its crank angle k pi with its margin 1e-4 m (the sweep
    followed at those steps missed 5 and 2 of them at 1 rad/s)."""
    rocker = 0.4 + 1e-4
    D = np.array([[1.0, 0.0]])
    B0 = _crank(np.zeros(1))
    C0 = _circles(B0, 1.0, D, rocker)
    doc = _without_moving_points(_four_bar(B0[0].tolist(), C0[0].tolist(), [0.5, -2.0], "0.5"))
    doc["drivers"][0]["angle_law"] = law
    result = solver.sweep_time(doc, [0.0, 100.0], samples)
    t = np.linspace(0.0, 100.0, samples)
    B = _crank(t if law == "t" else 0.01 * t**2)
    want = _circles(B, 1.0, np.repeat(D, samples, axis=0), rocker)
    np.testing.assert_allclose(result["points"]["C"]["position"], want, rtol=0, atol=1e-9)
    found = sorted(result["diagnostics"]["close_approaches"], key=lambda a: a["driver_angle"])
    turns = np.arange(1, 33) * math.pi  # 60 deg + 100 rad = 32.2 pi
    np.testing.assert_allclose([a["driver_angle"] for a in found], turns, rtol=0, atol=1e-9)
    np.testing.assert_allclose([a["margin"] for a in found], 1e-4, rtol=0, atol=1e-12)


def _triad_with_a_parallelogram() -> dict[str, Any]:
    """The full-turning triad of the Newton benchmark driven at 1 rad/s, with a parallelogram on
    its crank (Q on the crank 0.4 m from O, coupler QS = ground OR = 1, rocker RS = 0.4): a
    Newton group and a dyad that passes a change point every pi."""
    doc = copy.deepcopy(FULL_TURN)
    doc["drivers"] = [{"link": "crank", "angle_law": "t"}]
    A = doc["points"]["A"]
    Q = 0.4 * np.array([A[0], A[1]]) / math.hypot(A[0], A[1])
    doc["points"] |= {"Q": Q.tolist(), "S": [Q[0] + 1.0, Q[1]], "R": [1.0, 0.0]}
    doc["links"]["crank"]["points"].append("Q")
    doc["links"]["ground"]["points"].append("R")
    doc["links"] |= {"coupler": {"points": ["Q", "S"]}, "rocker": {"points": ["R", "S"]}}
    doc["joints"] += [
        {"type": "revolute", "point": "Q", "links": ["crank", "coupler"]},
        {"type": "revolute", "point": "S", "links": ["coupler", "rocker"]},
        {"type": "revolute", "point": "R", "links": ["rocker", "ground"]},
    ]
    return doc


def test_triad_swept_in_long_steps_agrees_with_the_fine_sweep() -> None:
    """``_triad_with_a_parallelogram`` over 30 s at 13 samples (2.5 rad a step) and at 481 (the
    fine sweep's every 40th sample at the same instants): every point agrees to 1e-9 m (followed
    at 2.5 rad a step, S took the crossed assembly, 0.71 m off)."""
    doc = _triad_with_a_parallelogram()
    coarse = solver.sweep_time(doc, [0.0, 30.0], 13)
    fine = solver.sweep_time(doc, [0.0, 30.0], 481)
    for point, motion in coarse["points"].items():
        np.testing.assert_allclose(
            motion["position"], np.asarray(fine["points"][point]["position"])[::40], atol=1e-9
        )


def test_sweep_too_long_to_follow_is_refused_with_its_numbers() -> None:
    """The parallelogram over 1e6 s at 1 rad/s in 2 samples: following it in steps of pi/8 takes
    ceil(1e6 / (pi/8)) + 1 samples, more than MAX_DENSE_SAMPLES: refused (limit_exceeded)."""
    needed = math.ceil(1e6 / MAX_DRIVER_STEP) + 1
    assert needed > MAX_DENSE_SAMPLES
    with pytest.raises(
        LimitExceeded, match=rf"takes {needed} samples, more than {MAX_DENSE_SAMPLES}"
    ):
        solver.sweep_time(_parallelogram(60.0, [0.5, -2.0]), [0.0, 1e6], 2)


def test_short_steps_are_followed_as_given_and_long_ones_on_a_denser_grid() -> None:
    """The four-bar preset (a crank-rocker far from its change points): a revolution in 360
    samples is followed as given; 101 samples over 100 s at 1 rad/s (1 rad a step, which its
    screen alone would pass) on a denser grid, at steps of at most pi/8."""
    doc = build_preset("four_bar", {})
    doc["drivers"] = [{"link": "crank", "angle_law": "t"}]
    scene = parse_linkage(doc)
    revolution = np.linspace(0.0, 2.0 * math.pi, 361)
    assert dense_grid(driver_inputs_over_time(scene, revolution)) is None
    grid = dense_grid(driver_inputs_over_time(scene, np.linspace(0.0, 100.0, 101)))
    assert grid is not None
    assert np.abs(np.diff(grid.inputs[0].theta)).max() <= MAX_DRIVER_STEP


def test_a_window_between_two_samples_a_turn_apart_is_refused_with_its_depth() -> None:
    """Crank AB = 0.6, coupler BC = 0.5, rocker DC = 0.3, ground AD = 1 m, drawn with the crank
    at 0 deg and turned at 1 rad/s: the loop closes only while |BD| <= 0.8 m (within 53.1 deg of
    the ground line). A time sweep over one turn in two samples (0 and 2 pi: both close) is
    refused for the window between them, at its deepest dense sample, the crank at pi (pi/8 a
    step): |BD| = 1.6 m, the loci of C 1.6 - 0.8 = 0.8 m apart."""
    doc = _four_bar([0.6, 0.0], [1.0, 0.3], [0.5, -2.0], "0.25")
    doc.pop("moving_points")
    with pytest.raises(NotAssemblable) as refused:
        solver.sweep_time(doc, [0.0, 2.0 * math.pi], 2)
    assert str(refused.value.message) == (
        "the linkage cannot be closed during t = 0 .. 6.28319 s: the loci of C fail to meet by "
        "0.8 m between samples 0 and 1"
    )


@pytest.mark.slow
def test_a_meeting_off_the_carrier_searched_on_long_steps_is_on_the_parallelogram() -> None:
    """The parallelogram drawn at 60 deg, at 1 rad/s: M (s = 0.5 on the coupler) runs round
    (0.5, 0) + 0.4 (cos, sin)(60 deg + t) and meets G, that circle's point at 200 deg, when the
    crank has turned 140 deg (closed form, 1e-6). Searched to t_max = 1700 s, the distance grid
    (4096 samples) steps 0.415 rad, more than pi/8: the grid is followed densely, and the
    instants between its samples are assembled on the branches it followed (its switches mapped
    back to the grid's samples)."""
    G = [0.5 + 0.4 * math.cos(math.radians(200.0)), 0.4 * math.sin(math.radians(200.0))]
    assert MAX_DRIVER_STEP < 1700.0 / 4096
    _assert_exact_time(
        _time(_parallelogram(60.0, G), "G", 1, 1700.0), math.radians(140.0), "", 1e-6
    )

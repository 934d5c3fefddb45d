"""Grashof classes and the transmission angle against textbook values: swapping two
class labels, or a constant transmission angle, turns a test red.

Grashof's criterion (e.g. Norton, Design of Machinery, sec. 2.12; Uicker, Pennock and Shigley,
Theory of Machines and Mechanisms, sec. 1.10): with s the shortest link, l the longest and p, q
the others, s + l < p + q is a Grashof linkage, and then the link next to the shortest decides:
the shortest as ground gives a double-crank (drag-link), as crank a crank-rocker, as rocker a
rocker-crank (the rocker turns fully), as coupler a double-rocker; s + l > p + q is a non-Grashof
triple-rocker; s + l = p + q a change-point linkage. The transmission angle mu is the angle BCD
between coupler and rocker, from the law of cosines (Norton eq. 4.32):
cos mu = (b^2 + c^2 - |BD|^2) / (2 b c), |BD|^2 = a^2 + g^2 - 2 a g cos(theta2).
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np
import pytest

from solver.analysis.instant import analyze
from solver.kinematics.four_bar import FourBarLoop, extreme_transmission_angles, transmission_angle
from solver.model.scene import parse_linkage
from solver.teaching.presets import build_preset
from tests.dynamics_cases import five_bar_points, five_bar_topology

# (ground, crank, coupler, rocker, drawn crank angle in degrees) -> textbook class
CASES = {
    "Grashof crank-rocker": (1.0, 0.15, 1.0, 0.55, 30.0),
    "Grashof double-crank": (0.15, 1.0, 1.0, 0.55, 30.0),
    "Grashof double-rocker": (1.0, 0.55, 0.15, 1.0, 70.0),
    "Grashof rocker-crank": (1.0, 0.55, 1.0, 0.15, 70.0),
    "non-Grashof triple-rocker": (2.5, 1.0, 2.0, math.sqrt(1.25), 60.0),
    "change-point": (1.0, 0.4, 1.0, 0.4, 60.0),
}


def _loop(
    g: float, a: float, b: float, c: float, angle: float, at: float | None = None
) -> FourBarLoop:
    doc = build_preset(
        "four_bar",
        {"ground": g, "crank": a, "coupler": b, "rocker": c, "crank_angle_deg": angle},
    )
    if at is not None:
        doc["drivers"][0]["angle_deg"] = at
    (loop,) = analyze(parse_linkage(doc), ["position"]).four_bar_loops
    return loop


@pytest.mark.parametrize("expected", list(CASES))
def test_grashof_class_is_the_textbook_one(expected: str) -> None:
    """Each of the six classes from lengths that are textbook examples of it."""
    assert _loop(*CASES[expected]).grashof == expected


@pytest.mark.parametrize("name", list(CASES))
def test_transmission_angle_follows_the_law_of_cosines(name: str) -> None:
    """mu at five crank angles of each linkage's range against the law of cosines, to 1e-12 rad;
    it changes with the crank angle (a constant would fail)."""
    g, a, b, c, drawn = CASES[name]
    seen = []
    for turn in (-8.0, -4.0, 0.0, 4.0, 8.0):
        theta = drawn + turn
        bd2 = a * a + g * g - 2.0 * a * g * math.cos(math.radians(theta))
        expected = math.acos((b * b + c * c - bd2) / (2.0 * b * c))
        mu = _loop(g, a, b, c, drawn, theta).transmission_angle
        assert mu == pytest.approx(expected, abs=1e-12), (name, theta)
        seen.append(mu)
    assert max(seen) - min(seen) > 1e-3, name


def test_seed_004_transmission_angle_extremes() -> None:
    """Seed 004's crank-rocker: mu is smallest with the crank along the ground towards D
    (|BD| = g - a) and largest away from it (|BD| = g + a): Norton eq. 4.33,
    cos mu_min = (b^2 + c^2 - (g - a)^2) / 2bc, here 58.2 and 91.0 deg to 0.1 deg."""
    g, a, b, c, drawn = CASES["Grashof crank-rocker"]
    low = _loop(g, a, b, c, drawn, 0.0).transmission_angle
    high = _loop(g, a, b, c, drawn, 180.0).transmission_angle
    assert math.degrees(low) == pytest.approx(
        math.degrees(math.acos((b * b + c * c - (g - a) ** 2) / (2 * b * c))), abs=1e-9
    )
    assert math.degrees(high) == pytest.approx(
        math.degrees(math.acos((b * b + c * c - (g + a) ** 2) / (2 * b * c))), abs=1e-9
    )
    assert round(math.degrees(low), 1) == 58.2 and round(math.degrees(high), 1) == 91.0


@pytest.mark.parametrize("eps", [1e-9, -1e-9])
def test_a_linkage_1e_9_off_the_equality_is_not_a_change_point(eps: float) -> None:
    """s + l = p + q - 1e-9 (rocker 1e-9 longer) is a crank-rocker, 1e-9 shorter a triple rocker:
    only the equality within rounding (1e-12 of the longest link) is a change point."""
    loop = _loop(1.0, 0.4, 0.9, 0.5 + eps, 30.0)
    assert loop.grashof == ("Grashof crank-rocker" if eps > 0 else "non-Grashof triple-rocker")


def _shifted_six_bar() -> dict[str, Any]:
    """A crank A-B driving a slider (rod B-S, block S on a horizontal guide) and a Watt six-bar
    (four-bar A-B-C-D, then rocker D-C-E driving the dyad E-G-F), drawn away from the origin
    (every point shifted by (3, -2)). The plan solves the slider's dyad first, then the loop
    A-B-C-D, then E-G-F, whose input is a rocker, not a driven crank."""
    points = {"A": (0.0, 0.0), "B": (0.12, 0.35), "S": (-0.9, -0.3), "C": (0.9, 0.8),
              "D": (1.0, 0.0), "E": (1.5, 0.6), "F": (2.4, 0.0), "G": (2.2, 0.9)}  # fmt: skip
    bars = [
        "ground crank A",
        "crank rod B",
        "rod block S",
        "crank coupler B",
        "coupler rocker C",
        "rocker ground D",
        "rocker coupler2 E",
        "coupler2 rocker2 G",
        "rocker2 ground F",
    ]
    return {
        "kind": "linkage",
        "points": {name: [x + 3.0, y - 2.0] for name, (x, y) in points.items()},
        "links": {
            "ground": {"points": ["A", "D", "F"], "ground": True},
            "crank": {"points": ["A", "B"]},
            "rod": {"points": ["B", "S"]},
            "block": {"points": ["S"]},
            "coupler": {"points": ["B", "C"]},
            "rocker": {"points": ["D", "C", "E"]},
            "coupler2": {"points": ["E", "G"]},
            "rocker2": {"points": ["F", "G"]},
        },
        "joints": [
            {"type": "revolute", "point": p, "links": [a, b]} for a, b, p in map(str.split, bars)
        ]
        + [{"type": "prismatic", "point": "S", "links": ["ground", "block"], "axis": [1.0, 0.0]}],
        "drivers": [{"link": "crank", "omega": 2.0, "alpha": 0.0}],
    }


def test_the_driven_four_bar_inside_a_six_bar_away_from_the_origin() -> None:
    """Only the loop ground-crank-coupler-rocker is a four-bar loop (found after the slider's
    dyad; the rocker-driven loop E-G-F is not one), its lengths are the drawn |AD|, |AB|, |BC|,
    |DC| wherever the linkage is drawn (1e-12), Grashof: s + l = 0.37 + 1 < p + q with the crank
    shortest, a crank-rocker, and mu at the drawn pose is the law of cosines' (1e-12 rad)."""
    doc = _shifted_six_bar()
    P = {name: complex(*xy) for name, xy in doc["points"].items()}
    (loop,) = analyze(parse_linkage(doc), ["position"]).four_bar_loops
    assert loop.links == ("ground", "crank", "coupler", "rocker")
    g, a, b, c = (abs(P[q] - P[p]) for p, q in ("AD", "AB", "BC", "DC"))
    assert loop.lengths == pytest.approx((g, a, b, c), abs=1e-12)
    assert loop.grashof == "Grashof crank-rocker"
    bd2 = abs(P["D"] - P["B"]) ** 2
    assert loop.transmission_angle == pytest.approx(
        math.acos((b * b + c * c - bd2) / (2.0 * b * c)), abs=1e-12
    )


def test_a_four_bar_on_a_five_bar_crank_is_found_after_the_five_bar() -> None:
    """A five-bar (cranks O1-A, O2-B, both driven, dyad A-C-B) with a four-bar O1-A-E-F on its
    first crank: the plan closes the five-bar's dyad first (no ground pivot: not a four-bar
    loop), then E. The four-bar is still found, with the drawn lengths |O1F|, |O1A|, |AE|, |FE|
    (1e-12), a crank-rocker (s + l = 0.49 + 1.02 < p + q = 1.87, the crank shortest) and the
    law of cosines' transmission angle (1e-12 rad)."""
    doc: dict[str, Any] = {
        "kind": "linkage",
        "points": {**five_bar_points(), "F": [-1.0, 0.2], "E": [-0.6, 1.0]},
        **five_bar_topology(),
        "drivers": [
            {"link": "crank1", "omega": 2.0, "alpha": 0.0},
            {"link": "crank2", "omega": 1.0, "alpha": 0.0},
        ],
    }
    doc["links"] |= {
        "ground": {"points": ["O1", "O2", "F"], "ground": True},
        "coupler": {"points": ["A", "E"]},
        "rocker": {"points": ["F", "E"]},
    }
    doc["joints"] += [
        {"type": "revolute", "point": "A", "links": ["crank1", "coupler"]},
        {"type": "revolute", "point": "E", "links": ["coupler", "rocker"]},
        {"type": "revolute", "point": "F", "links": ["rocker", "ground"]},
    ]
    P = {name: complex(*xy) for name, xy in doc["points"].items()}
    (loop,) = analyze(parse_linkage(doc), ["position"]).four_bar_loops
    assert loop.links == ("ground", "crank1", "coupler", "rocker")
    g, a, b, c = (abs(P[q] - P[p]) for p, q in (("O1", "F"), ("O1", "A"), ("A", "E"), ("F", "E")))
    assert loop.lengths == pytest.approx((g, a, b, c), abs=1e-12)
    assert loop.grashof == "Grashof crank-rocker"
    fa2 = abs(P["A"] - P["F"]) ** 2
    assert loop.transmission_angle == pytest.approx(
        math.acos((b * b + c * c - fa2) / (2.0 * b * c)), abs=1e-12
    )


@pytest.mark.parametrize(("a", "b", "c", "d"), [(0.1, 0.35, 0.3, 0.4), (0.02, 0.05, 0.04, 0.045)])
def test_the_extreme_transmission_angles_are_those_of_the_crank_along_the_ground(
    a: float, b: float, c: float, d: float
) -> None:
    """With the crank along the ground (A at the origin, D at (d, 0), B at (-a, 0) and (a, 0)),
    the angle BCD measured on the assembled linkage equals the law-of-cosines extremes, 1e-12."""
    D = np.array([d, 0.0])
    for B, expected in zip(
        (np.array([-a, 0.0]), np.array([a, 0.0])),
        extreme_transmission_angles(a, b, c, d),
        strict=True,
    ):
        BD = float(np.linalg.norm(D - B))
        along = (b * b - c * c + BD * BD) / (2.0 * BD)  # C from B along BD, and off it
        C = B + (D - B) / BD * along + np.array([0.0, math.sqrt(b * b - along * along)])
        assert float(transmission_angle(B, C, D)) == pytest.approx(expected, abs=1e-12)

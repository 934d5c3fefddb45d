"""Instant centres (solver.kinematics.instant_centres) on random linkages: Kennedy's theorem, the
centre of a revolute pair at its joint, of a slider's pair on the normal to the slot (the random
families, tolerances and helpers are those of test_properties.py).
"""

from __future__ import annotations

import math
from itertools import combinations

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from solver.teaching.presets import build_preset
from tests.dynamics_cases import five_bar_points, five_bar_topology
from tests.linkage_strategies import FAMILIES
from tests.solver.analysis.test_properties import (
    PROPERTY,
    Doc,
    cross,
    draw_linkage,
    norm,
    solve,
)
from tests.solver.analysis.test_sliding_joints import _guide_frame


@pytest.mark.slow
@pytest.mark.parametrize("family", FAMILIES)
@PROPERTY
@given(data=st.data())
def test_instant_centres_obey_kennedy(family: str, data: st.DataObject) -> None:
    """Kennedy's theorem: the three instant centres of any three links lie on one line (where two
    are points; with one at infinity the other two lie on a line in its direction). Also, the
    centre of two links joined by a revolute is the joint, and that of a slider's guide and
    follower lies on the normal to the slot through the pin (at infinity, normal to the slot, for
    a prismatic joint). Tolerance: 1e-8 on the sine of the angle between the two chords (rounding
    of centres far away grows with their distance), 1e-9 L on the joint positions."""
    _, scene, result = draw_linkage(data, family)
    centres = {frozenset(c.links): c for c in result.instant_centres}
    names = list(scene.links)
    assert len(centres) == len(names) * (len(names) - 1) // 2
    size = scene.size
    for i, j, k in combinations(names, 3):
        trio = [centres[frozenset(pair)] for pair in ((i, j), (j, k), (i, k))]
        points = [c.position for c in trio if c.position is not None]
        directions = [c.direction for c in trio if c.direction is not None]
        if len(points) == 3:
            a, b = points[1] - points[0], points[2] - points[0]
            if min(norm(a), norm(b)) > 1e-6 * size:
                assert abs(cross(a, b)) <= 1e-8 * norm(a) * norm(b), (i, j, k, points)
        elif len(points) == 2 and len(directions) == 1:
            chord = points[1] - points[0]
            if norm(chord) > 1e-6 * size:
                assert abs(cross(chord, directions[0])) <= 1e-8 * norm(chord), (i, j, k)
    omegas = {name: (0.0 if name == scene.ground else result.links[name].omega) for name in names}
    for joint in scene.joints:
        centre = centres[frozenset(joint.links)]
        X = result.points[joint.point].position
        if joint.type == "revolute":
            wi, wj = (omegas[n] for n in joint.links)
            if abs(wi - wj) <= 1e-9 * (abs(wi) + abs(wj)):
                continue  # no relative rotation: the centre is at infinity or undefined (rest)
            assert centre.position is not None, joint
            spread = (abs(wi) + abs(wj)) / abs(wi - wj)  # cancellation in k x dv / d(omega)
            assert norm(centre.position - X) <= 1e-9 * size * max(1.0, spread), joint
            continue
        assert joint.axis is not None
        _, turn, _, _ = _guide_frame(scene, result, joint.guide)
        u = np.array(
            [
                math.cos(turn) * joint.axis[0] - math.sin(turn) * joint.axis[1],
                math.sin(turn) * joint.axis[0] + math.cos(turn) * joint.axis[1],
            ]
        )
        if centre.position is not None:
            off = centre.position - X
            assert abs(float(off @ u)) <= 1e-8 * max(size, norm(off)), joint
        elif centre.direction is not None:
            assert abs(float(centre.direction @ u)) <= 1e-8, joint


# Found by the Kennedy test: a block in a slotted lever at the instant it does not slide (the
# crank pin on the line of the two pivots): block and lever move as one body, v_rel = 0 exactly.
BLOCK_AT_RELATIVE_REST: Doc = {
    "kind": "linkage",
    "points": {"O": [0.0, 0.0], "A": [0.9, 0.0], "C": [0.3, 0.0], "D": [2.3, 0.0]},
    "links": {
        "ground": {"points": ["O", "C"], "ground": True},
        "crank": {"points": ["O", "A"]},
        "lever": {"points": ["C", "D"]},
        "block": {"points": ["A"]},
    },
    "joints": [
        {"type": "revolute", "point": "O", "links": ["ground", "crank"]},
        {"type": "revolute", "point": "C", "links": ["ground", "lever"]},
        {"type": "revolute", "point": "A", "links": ["crank", "block"]},
        {"type": "prismatic", "point": "A", "links": ["lever", "block"], "axis": [1.0, 0.0]},
    ],
    "drivers": [{"link": "crank", "omega": 10.0, "alpha": 0.0}],
}


def test_prismatic_pair_at_relative_rest_has_no_centre_along_the_slot() -> None:
    """The centre of a prismatic pair is at infinity normal to the slot, or does not exist when
    the pair does not move relative to itself (scene-v1: null where none exists). Here v_rel = 0
    exactly, so a direction along the slot (1, 0) can only come from rounding noise."""
    result = solve(BLOCK_AT_RELATIVE_REST)
    (joint,) = result.joints
    assert np.all(joint.relative_velocity == 0.0)
    (centre,) = [c for c in result.instant_centres if set(c.links) == {"lever", "block"}]
    assert centre.position is None
    assert centre.direction is None or abs(float(centre.direction[0])) <= 1e-8


def _line_intersection(P: np.ndarray, Q: np.ndarray, R: np.ndarray, S: np.ndarray) -> np.ndarray:
    """The point where line PQ meets line RS (Cramer's rule on P + s (Q - P) = R + t (S - R))."""
    d1, d2, r = Q - P, S - R, R - P
    s = (r[0] * d2[1] - r[1] * d2[0]) / (d1[0] * d2[1] - d1[1] * d2[0])
    return P + s * d1


@pytest.mark.parametrize("omega", [0.0, 3.7, -25.0])
def test_four_bar_instant_centres_by_kennedy_at_rest_and_moving(omega: float) -> None:
    """A four-bar's six instant centres from its geometry alone (Kennedy's theorem, e.g. Norton,
    Design of Machinery, sec. 6.4): the four joints, I(ground, coupler) where the crank line AB
    meets the rocker line DC, and I(crank, rocker) where the coupler line BC meets the ground
    line AD. They are the same with the crank at rest (omega = 0: the centres of the pose, not
    "none") as turning either way; to 1e-12 of the size."""
    doc = build_preset(
        "four_bar",
        {"ground": 1.0, "crank": 0.4, "coupler": 0.9, "rocker": 0.7, "crank_angle_deg": 60.0},
    )
    doc["drivers"][0]["omega"] = omega
    result = solve(doc)
    A, B, C, D = (np.asarray(result.points[p].position) for p in "ABCD")
    expected = {
        frozenset({"ground", "crank"}): A,
        frozenset({"crank", "coupler"}): B,
        frozenset({"coupler", "rocker"}): C,
        frozenset({"rocker", "ground"}): D,
        frozenset({"ground", "coupler"}): _line_intersection(A, B, D, C),
        frozenset({"crank", "rocker"}): _line_intersection(B, C, A, D),
    }
    centres = {frozenset(c.links): c for c in result.instant_centres}
    assert set(centres) == set(expected)
    for pair, point in expected.items():
        centre = centres[pair]
        assert centre.position is not None and centre.direction is None, pair
        np.testing.assert_allclose(centre.position, point, rtol=0, atol=1e-12, err_msg=str(pair))


def test_five_bar_with_one_crank_at_rest_is_a_four_bar() -> None:
    """A five-bar (cranks O1-A, O2-B, dyad A-C-B) with crank2 at rest and crank1 turning: crank2
    moves with the ground, so the two have no instant centre (both fields vanish exactly: none,
    not a direction 0/0), and the rest is the four-bar O1-A-C-B: I(ground, left) =
    I(crank2, left) where the crank line O1A meets the rocker line BC, I(ground, right) =
    I(crank2, right) = B, and I(crank1, right) where line AC meets line O1B; to 1e-12."""
    doc: Doc = {
        "kind": "linkage",
        "points": five_bar_points(),
        **five_bar_topology(),
        "drivers": [
            {"link": "crank1", "omega": 2.0, "alpha": 0.0},
            {"link": "crank2", "omega": 0.0, "alpha": 0.0},
        ],
    }
    result = solve(doc)
    O1, A, B, C = (np.asarray(result.points[p].position) for p in ("O1", "A", "B", "C"))
    centres = {frozenset(c.links): c for c in result.instant_centres}
    rest = centres[frozenset({"ground", "crank2"})]
    assert rest.position is None and rest.direction is None
    expected = {
        ("ground", "left"): _line_intersection(O1, A, B, C),
        ("crank2", "left"): _line_intersection(O1, A, B, C),
        ("ground", "right"): B,
        ("crank2", "right"): B,
        ("crank1", "right"): _line_intersection(A, C, O1, B),
        ("ground", "crank1"): O1,
    }
    for pair, point in expected.items():
        centre = centres[frozenset(pair)]
        assert centre.position is not None, pair
        np.testing.assert_allclose(centre.position, point, rtol=0, atol=1e-12, err_msg=str(pair))

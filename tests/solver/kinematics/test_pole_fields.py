"""Poles and instant centres checked against the fields they come from
(solver/kinematics/poles.py, instant_centres.py): each number against its definition.

A rigid link's velocity field is v(P) = v_X + omega k x (P - X) and its acceleration field
a(P) = a_X + alpha k x (P - X) - omega^2 (P - X). The velocity pole is the point where the first
vanishes, the acceleration pole where the second does, and the instant centre of two links where
their velocity fields agree: each is checked by evaluating the fields there (relative residual
1e-12 of the field's scale), independently of the formula that found it. The threshold between a
slowly turning link and a translating one (POLE_TOLERANCE = 1e-10, relative) is checked at
sizes from 1e-6 m to 1e3 m.
"""

from __future__ import annotations

import numpy as np
import pytest

from solver.kinematics.four_bar import grashof_class
from solver.kinematics.instant_centres import InstantCentre, centres_of_pairs
from solver.kinematics.poles import POLE_TOLERANCE, acceleration_poles, velocity_poles
from solver.kinematics.rigid import perp

RNG = np.random.default_rng(8)
# omega = 1 exactly and negative rates are among the cases (a pole must not depend on the sign).
OMEGAS = np.concatenate(([1.0, -1.0, 0.5], RNG.uniform(-20.0, 20.0, 29)))
ALPHAS = np.concatenate(([0.0, 0.0, -3.0], RNG.uniform(-200.0, 200.0, 29)))


def test_velocity_pole_is_where_the_velocity_field_vanishes() -> None:
    X = RNG.uniform(-2.0, 2.0, (OMEGAS.size, 2))
    v_X = RNG.uniform(-5.0, 5.0, (OMEGAS.size, 2))
    poles = velocity_poles(X, v_X, OMEGAS, 1.0)
    assert poles.exists.all()
    at_pole = v_X + OMEGAS[:, None] * perp(poles.position - X)
    scale = np.hypot(*v_X.T)[:, None]
    np.testing.assert_allclose(at_pole / scale, 0.0, atol=1e-12)


def test_acceleration_pole_is_where_the_acceleration_field_vanishes() -> None:
    X = RNG.uniform(-2.0, 2.0, (OMEGAS.size, 2))
    a_X = RNG.uniform(-50.0, 50.0, (OMEGAS.size, 2))
    poles = acceleration_poles(X, a_X, OMEGAS, ALPHAS, 1.0)
    assert poles.exists.all()
    r = poles.position - X
    at_pole = a_X + ALPHAS[:, None] * perp(r) - OMEGAS[:, None] ** 2 * r
    scale = np.hypot(*a_X.T)[:, None]
    np.testing.assert_allclose(at_pole / scale, 0.0, atol=1e-12)


@pytest.mark.parametrize("size", [1e-6, 1.0, 1e3])
def test_the_pole_threshold_is_relative_to_the_size(size: float) -> None:
    """omega size against 1e-10 (|v| + omega size): a link at 1e-8 of the speed turns (its pole is
    1e8 sizes away), one at 1e-12 translates; a link turning about X itself (v_X = 0) has its
    pole at X, however small the linkage."""
    X = np.zeros((1, 2))
    speed = 3.0 * size  # a velocity of the linkage's order: omega ~ 3 rad/s
    v = np.array([[speed, 0.0]])
    assert velocity_poles(X, v, np.array([1e-8 * speed / size]), size).exists[0]
    assert not velocity_poles(X, v, np.array([1e-12 * speed / size]), size).exists[0]
    at_rest = velocity_poles(X, np.zeros((1, 2)), np.array([2.0]), size)
    assert at_rest.exists[0]
    np.testing.assert_allclose(at_rest.position[0], [0.0, 0.0], atol=1e-15)
    # Acceleration: rate = sqrt(omega^4 + alpha^2) against |a| / size alike.
    a = np.array([[30.0 * size, 0.0]])
    for alpha, exists in ((1e-8 * 30.0, True), (1e-12 * 30.0, False)):
        poles = acceleration_poles(X, a, np.zeros(1), np.array([alpha]), size)
        assert poles.exists[0] == exists
    about_X = acceleration_poles(X, np.zeros((1, 2)), np.array([2.0]), np.zeros(1), size)
    assert about_X.exists[0]
    np.testing.assert_allclose(about_X.position[0], [0.0, 0.0], atol=1e-15)


def field(V: np.ndarray, omega: float, P: np.ndarray) -> np.ndarray:
    """v(P) = V + omega k x P, V being the velocity of the link's point at the origin."""
    return V + omega * perp(P)


def instant_centre(
    V_i: np.ndarray, omega_i: float, V_j: np.ndarray, omega_j: float, size: float
) -> InstantCentre:
    """The instant centre of one pair of links."""
    omegas = np.array([omega_i]), np.array([omega_j])
    return centres_of_pairs([("i", "j")], V_i[None], omegas[0], V_j[None], omegas[1], size)[0]


def test_instant_centre_is_where_two_velocity_fields_agree() -> None:
    """20 random pairs of fields at once (each pair's centre from its own row)."""
    V_i, V_j = RNG.uniform(-5.0, 5.0, (2, 20, 2))
    w_i, w_j = RNG.uniform(-10.0, 10.0, (2, 20))
    pairs = [(f"i{k}", f"j{k}") for k in range(20)]
    centres = centres_of_pairs(pairs, V_i, w_i, V_j, w_j, 1.0)
    for k, centre in enumerate(centres):
        assert centre.links == pairs[k]
        assert centre.position is not None and centre.direction is None
        gap = field(V_i[k], w_i[k], centre.position) - field(V_j[k], w_j[k], centre.position)
        assert np.hypot(*gap) <= 1e-12 * (np.hypot(*V_i[k]) + np.hypot(*V_j[k]))


@pytest.mark.parametrize("size", [1e-3, 1.0, 1e3])
def test_instant_centre_at_infinity_and_at_rest(size: float) -> None:
    """Equal rates: relative translation, the centre at infinity perpendicular to the relative
    velocity (a unit vector); equal fields: no centre. Rates differing by 1e-8 of the
    velocities' scale still give a (far) point; by 1e-12, a translation."""
    V_i, V_j = np.array([1.0, 2.0]) * size, np.array([-0.5, 0.25]) * size
    translation = instant_centre(V_i, 2.0, V_j, 2.0, size)
    assert translation.position is None and translation.direction is not None
    dv = V_i - V_j
    np.testing.assert_allclose(translation.direction, perp(dv) / np.hypot(*dv), atol=1e-15)
    rest = instant_centre(V_i, 2.0, V_i.copy(), 2.0, size)
    assert rest.position is None and rest.direction is None
    speed = float(np.hypot(*dv)) / size
    far = instant_centre(V_i, 2.0 + 1e-8 * speed, V_j, 2.0, size)
    assert far.position is not None
    gap = field(V_i, 2.0 + 1e-8 * speed, far.position) - field(V_j, 2.0, far.position)
    assert np.hypot(*gap) <= 1e-6 * size  # the point lies 1e8 sizes away: rounding grows with it
    near = instant_centre(V_i, 2.0 + 1e-12 * speed, V_j, 2.0, size)
    assert near.position is None and near.direction is not None


@pytest.mark.parametrize("scale", [1e-3, 1.0, 1e3])
def test_grashof_change_point_tolerance_scales_with_the_longest_link(scale: float) -> None:
    """s + l = p + q within 1e-13 of the longest link (rounding) is a change point at any scale;
    off by 1e-9 of it, it is not: longer, a triple-rocker; shorter, a crank-rocker."""
    lengths = [0.3 * scale, 0.1 * scale, 0.7 * scale, 0.5 * scale]
    for rounding in (1.0, 1 + 1e-13, 1 - 1e-13):
        assert grashof_class(*lengths[:2], lengths[2] * rounding, lengths[3]) == "change-point"
    assert grashof_class(*lengths[:2], lengths[2] * (1 + 1e-9), lengths[3]) == (
        "non-Grashof triple-rocker"
    )
    assert grashof_class(*lengths[:2], lengths[2] * (1 - 1e-9), lengths[3]) == (
        "Grashof crank-rocker"
    )


@pytest.mark.parametrize("size", [1e-6, 1.0, 1e3])
def test_instant_centre_thresholds_are_relative_to_speeds_and_size(size: float) -> None:
    """At rest relative to each other means |dv| + |dw| size within 1e-10 of the links' own
    motion (|V_i| + |V_j| + (|omega_i| + |omega_j|) size): two links turning at 2 rad/s whose
    origin velocities are small (1e-3 size per second) and differ by 1e-12 of the motion are at
    rest relative to each other; by 1e-8, or with rates 1e-8 apart, they are not. Two links
    turning about the origin at different rates meet there, however small the linkage."""
    V = np.array([1e-3, 0.0]) * size
    motion = 4.0 * size  # (|omega_i| + |omega_j|) size dominates the reference
    rest = instant_centre(V, 2.0, V + np.array([1e-12 * motion, 0.0]), 2.0, size)
    assert rest.links == ("i", "j") and rest.position is None and rest.direction is None
    moving = instant_centre(V, 2.0, V + np.array([1e-8 * motion, 0.0]), 2.0, size)
    assert moving.links == ("i", "j") and moving.direction is not None
    turning = instant_centre(V, 2.0 + 1e-8 * motion / size, V, 2.0, size)
    assert turning.links == ("i", "j") and turning.position is not None
    # Two translating links (omega = 0): the reference is |V_i| + |V_j| alone.
    sliding = np.array([3.0, -1.0]) * size
    same = instant_centre(sliding, 0.0, sliding * (1 + 1e-12), 0.0, size)
    assert same.position is None and same.direction is None
    about_origin = instant_centre(np.zeros(2), 3.0, np.zeros(2), -1.0, size)
    assert about_origin.position is not None
    np.testing.assert_allclose(about_origin.position, [0.0, 0.0], atol=1e-15)


@pytest.mark.parametrize("size", [1e-3, 1.0, 1e3])
def test_the_thresholds_hold_at_the_boundary(size: float) -> None:
    """The boundary itself, omega size = POLE_TOLERANCE x the speed exactly: the test is
    omega size <= POLE_TOLERANCE (speed + omega size) for a translation, so the boundary
    translates (no pole; no instant centre, a direction) and 1e-6 beyond it turns. Likewise the
    acceleration pole with sqrt(omega^4 + alpha^2) size against |a|."""
    X = np.zeros((1, 2))
    speed = 3.0 * size
    v = np.array([[speed, 0.0]])
    for factor, turns in ((1.0, False), (1.0 + 1e-6, True)):
        omega = factor * POLE_TOLERANCE * speed / size
        assert velocity_poles(X, v, np.array([omega]), size).exists[0] == turns
        centre = instant_centre(v[0], omega, np.zeros(2), 0.0, size)
        assert (centre.position is not None) == turns
        assert (centre.direction is not None) == (not turns)
        a = v * 10.0
        alpha = factor * POLE_TOLERANCE * 10.0 * speed / size
        poles = acceleration_poles(X, a, np.zeros(1), np.array([alpha]), size)
        assert poles.exists[0] == turns

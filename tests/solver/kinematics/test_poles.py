"""Velocity and acceleration poles (solver.kinematics.poles).

The threshold that tells a slowly turning link from a translating one (poles.POLE_TOLERANCE):
a pole a million sizes away is still a pole; rounding noise (1e-13 of the speed) is not. On
random linkages (the families and helpers of test_properties.py) the poles reproduce every
point's velocity and acceleration."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from solver.kinematics.poles import acceleration_poles, velocity_poles
from tests.linkage_strategies import FAMILIES
from tests.solver.analysis.test_properties import (
    IDENTITY_TOL,
    PROPERTY,
    draw_linkage,
    group_scales,
    norm,
    perp,
)


def test_slowly_turning_link_has_a_far_velocity_pole() -> None:
    """v_X = omega x r_PX, so P = X + (k x v_X) / omega: omega = 1e-6 rad/s, v = 1 m/s along x
    puts P 1e6 m above X (omega L / v = 1e-6 on a 1 m linkage); omega = 1e-13 is noise."""
    X, v = np.array([[2.0, 3.0]]), np.array([[1.0, 0.0]])
    poles = velocity_poles(X, v, np.array([1e-6]), 1.0)
    position = poles.at(0)
    assert position is not None
    np.testing.assert_allclose(position, [2.0, 3.0 + 1e6], rtol=1e-12)
    assert velocity_poles(X, v, np.array([1e-13]), 1.0).at(0) is None


def test_slowly_turning_link_has_a_far_acceleration_pole() -> None:
    """a_X = alpha x r_GX - omega^2 r_GX: with omega = 0 and alpha = 1e-6 rad/s^2, a = 1 m/s^2
    along x, G = X + (k x a) / alpha, 1e6 m above X; alpha = 1e-13 is noise."""
    X, a = np.array([[0.0, 0.0]]), np.array([[1.0, 0.0]])
    poles = acceleration_poles(X, a, np.zeros(1), np.array([1e-6]), 1.0)
    position = poles.at(0)
    assert position is not None
    np.testing.assert_allclose(position, [0.0, 1e6], rtol=1e-12)
    assert acceleration_poles(X, a, np.zeros(1), np.array([1e-13]), 1.0).at(0) is None


@pytest.mark.slow
@pytest.mark.parametrize("family", FAMILIES)
@PROPERTY
@given(data=st.data())
def test_poles_reproduce_the_velocity_and_acceleration_fields(
    family: str, data: st.DataObject
) -> None:
    """The velocity pole P of a link gives v_X = omega k x (X - P) for every point X of the link;
    the acceleration pole G gives a_X = alpha k x (X - G) - omega^2 (X - G). A missing pole means
    a translating (or resting) link: then omega (omega^4 + alpha^2) is negligible against the
    field. Tolerance 1e-9 of max(group magnitude, the rate times |X - pole|): a far pole carries
    the rounding of its own magnitude."""
    _, scene, result = draw_linkage(data, family)
    v_scale, a_scale, _, _ = group_scales(result)
    for name in scene.moving_links:
        link = result.links[name]
        w, al = link.omega, link.alpha
        for x in scene.links[name].points:
            X = result.points[x]
            if link.velocity_pole is None:
                assert abs(w) * scene.size <= 1e-9 * v_scale, name
            else:
                r = X.position - link.velocity_pole
                expected = w * perp(r)
                assert norm(X.velocity - expected) <= IDENTITY_TOL * max(
                    v_scale, abs(w) * norm(r)
                ), name
            if link.acceleration_pole is None:
                assert math.hypot(w**2, al) * scene.size <= 1e-9 * a_scale, name
            else:
                r = X.position - link.acceleration_pole
                expected = al * perp(r) - w**2 * r
                reach = math.hypot(w**2, al) * norm(r)
                assert norm(X.acceleration - expected) <= IDENTITY_TOL * max(a_scale, reach), name

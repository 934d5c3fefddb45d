"""The threshold that tells a slowly turning link from a translating one (poles.POLE_TOLERANCE):
a pole a million sizes away is still a pole; rounding noise (1e-13 of the speed) is not."""

from __future__ import annotations

import numpy as np

from solver.poles import acceleration_poles, velocity_poles


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

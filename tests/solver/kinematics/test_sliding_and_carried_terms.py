"""The textbook parts the analysis and the worked solutions share: a sliding point's
v = v_tr + v_rel and a = a_tr + a_rel + a_Cor (kinematics.relative_motion), and the terms that
carry a spatial joint's origin with the body before it (kinematics.spatial.origin_terms).
Source: the relative-motion theorem (a_Cor = 2 omega x v_rel); properties checked on numbers.
"""

from __future__ import annotations

import numpy as np
from hypothesis import given
from hypothesis import strategies as st

from solver.kinematics.relative_motion import (
    sliding_acceleration_parts,
    sliding_velocity_parts,
)
from solver.kinematics.rigid import perp
from solver.kinematics.spatial import (
    BodyMotion,
    SpatialJoint,
    ground_motion,
    origin_terms,
)

number = st.floats(-100.0, 100.0, allow_nan=False)
vector2 = st.tuples(number, number).map(np.array)


@given(vector2, number, number, vector2, vector2, vector2, vector2)
def test_the_sliding_parts_add_up_to_the_point_s_motion(
    v_A: np.ndarray,
    omega: float,
    alpha: float,
    r: np.ndarray,
    v_P: np.ndarray,
    a_A: np.ndarray,
    a_P: np.ndarray,
) -> None:
    """v_tr = v_A + omega x r, v_tr + v_rel = v_P; a_tr = a_A + alpha x r - omega^2 r,
    a_Cor = 2 omega x v_rel, a_tr + a_rel + a_Cor = a_P."""
    w, al = np.asarray(omega), np.asarray(alpha)
    v_tr, v_rel = sliding_velocity_parts(v_A, w, r, v_P)
    np.testing.assert_allclose(v_tr, v_A + omega * perp(r), rtol=1e-12, atol=1e-9)
    np.testing.assert_allclose(v_tr + v_rel, v_P, rtol=1e-12, atol=1e-9)
    a_tr, a_rel, a_cor = sliding_acceleration_parts(a_A, w, al, r, v_rel, a_P)
    np.testing.assert_allclose(a_tr, a_A + alpha * perp(r) - omega**2 * r, rtol=1e-12, atol=1e-6)
    np.testing.assert_allclose(a_cor, 2.0 * omega * perp(v_rel), rtol=1e-12, atol=1e-9)
    np.testing.assert_allclose(a_tr + a_rel + a_cor, a_P, rtol=1e-12, atol=1e-6)


def test_a_joint_origin_is_carried_by_the_body_before_it() -> None:
    """r = O_k - O_{k-1}; omega x r, alpha x r, omega x (omega x r) with the parent's rates;
    a prismatic joint adds v_rel = rate e, a_rel = rate_dot e, 2 omega x v_rel; a revolute one
    nothing."""
    omega, alpha = np.array([0.0, 0.0, 2.0]), np.array([0.0, 0.5, -1.0])
    parent = BodyMotion(
        omega, alpha, np.array([0.1, 0.0, 0.0]), np.zeros(3), np.zeros(3), np.zeros(3)
    )
    e = np.array([1.0, 0.0, 0.0])
    slider = SpatialJoint("s", "prismatic", np.array([1.1, 0.2, 0.0]), e, 0.4, -0.7)
    terms = origin_terms(parent, slider)
    np.testing.assert_array_equal(terms.r, [1.0, 0.2, 0.0])
    np.testing.assert_allclose(terms.omega_x_r, [-0.4, 2.0, 0.0])
    np.testing.assert_allclose(terms.alpha_x_r, np.cross(alpha, terms.r))
    np.testing.assert_allclose(terms.centripetal, [-4.0, -0.8, 0.0])  # -omega^2 r in the plane
    np.testing.assert_allclose(terms.v_rel, 0.4 * e)
    np.testing.assert_allclose(terms.a_rel, -0.7 * e)
    np.testing.assert_allclose(terms.coriolis, [0.0, 1.6, 0.0])  # 2 (2 k) x (0.4 i)
    hinge = SpatialJoint("h", "revolute", slider.origin, e, 0.4, -0.7)
    carried = origin_terms(parent, hinge)
    for zero in (carried.v_rel, carried.a_rel, carried.coriolis):
        np.testing.assert_array_equal(zero, np.zeros(3))
    rest = origin_terms(ground_motion(np.zeros(3)), slider)
    np.testing.assert_array_equal(rest.omega_x_r, np.zeros(3))
    np.testing.assert_array_equal(rest.coriolis, np.zeros(3))

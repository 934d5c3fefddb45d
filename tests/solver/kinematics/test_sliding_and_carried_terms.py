"""The textbook parts the analysis and the worked solutions share: a rigid link's terms
omega x r, alpha x r and -omega^2 r (kinematics.rigid), a sliding point's v = v_tr + v_rel and
a = a_tr + a_rel + a_Cor (kinematics.relative_motion), the terms of a point of a spatial body
and of the composition of a chain's rates, and those that carry a spatial joint's origin with the
body before it (kinematics.spatial).
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
from solver.kinematics.rigid import normal_acceleration, omega_cross, perp
from solver.kinematics.spatial import (
    BodyMotion,
    CompositionTerms,
    SpatialJoint,
    composition_terms,
    ground_motion,
    origin_terms,
    rigid_terms,
)

number = st.floats(-100.0, 100.0, allow_nan=False)
vector2 = st.tuples(number, number).map(np.array)


@given(number, vector2)
def test_a_link_s_rotation_terms_are_the_cross_products_with_k(omega: float, r: np.ndarray) -> None:
    """omega x r = (0, 0, omega) x (r_x, r_y, 0), and -omega^2 r = omega x (omega x r)."""
    k_omega = np.array([0.0, 0.0, omega])
    r3 = np.array([r[0], r[1], 0.0])
    np.testing.assert_allclose(omega_cross(omega, r), np.cross(k_omega, r3)[:2], atol=1e-12)
    np.testing.assert_allclose(
        normal_acceleration(omega, r),
        np.cross(k_omega, np.cross(k_omega, r3))[:2],
        rtol=1e-12,
        atol=1e-9,
    )
    over_samples = omega_cross(np.array([omega, 2.0 * omega]), np.array([r, r]))
    np.testing.assert_array_equal(over_samples[0], omega_cross(omega, r))


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
    zero = np.zeros(3)
    parent = BodyMotion(
        omega,
        alpha,
        np.array([0.1, 0.0, 0.0]),
        zero,
        zero,
        zero,
        CompositionTerms(zero, zero, zero),
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


def test_a_point_of_a_spatial_body_has_the_rigid_body_terms() -> None:
    """omega x r, alpha x r and omega x (omega x r) of r = P - O: for omega = 2 k, r = i,
    omega x r = 2 j, omega x (omega x r) = -4 i = -omega^2 r."""
    omega, alpha = np.array([0.0, 0.0, 2.0]), np.array([0.0, 0.5, -1.0])
    r = np.array([1.0, 0.0, 0.0])
    terms = rigid_terms(omega, alpha, r)
    np.testing.assert_array_equal(terms.r, r)
    np.testing.assert_allclose(terms.omega_x_r, [0.0, 2.0, 0.0])
    np.testing.assert_allclose(terms.alpha_x_r, [0.0, -1.0, -0.5])
    np.testing.assert_allclose(terms.centripetal, [-4.0, 0.0, 0.0])


def test_a_revolute_joint_composes_the_rates_and_a_prismatic_one_adds_none() -> None:
    """omega_k = omega_{k-1} + rate e_k, alpha_k = alpha_{k-1} + rate_dot e_k + rate de_k/dt:
    the terms rate e, rate_dot e and rate de/dt of a revolute joint; zeros for a prismatic one."""
    e, e_dot = np.array([1.0, 0.0, 0.0]), np.array([0.0, 2.0, 0.0])
    hinge = SpatialJoint("h", "revolute", np.zeros(3), e, 0.4, -0.7)
    terms = composition_terms(hinge, e_dot)
    np.testing.assert_allclose(terms.rate_axis, [0.4, 0.0, 0.0])
    np.testing.assert_allclose(terms.rate_dot_axis, [-0.7, 0.0, 0.0])
    np.testing.assert_allclose(terms.rate_axis_rate, [0.0, 0.8, 0.0])
    slider = SpatialJoint("s", "prismatic", np.zeros(3), e, 0.4, -0.7)
    none = composition_terms(slider, e_dot)
    for zero in (none.rate_axis, none.rate_dot_axis, none.rate_axis_rate):
        np.testing.assert_array_equal(zero, np.zeros(3))

"""Property test of the slider split (solver.analysis.sliding_joints) on random linkages with
sliders: v = v_tr + v_rel, a = a_tr + a_rel + a_cor with a_cor = 2 omega_guide x v_rel (the random
families, tolerances and helpers are those of test_properties.py).
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from solver.analysis.instant import LinkageAnalysis
from solver.model.scene import LinkageScene
from tests.solver.analysis.test_properties import (
    IDENTITY_TOL,
    PROPERTY,
    SLIDER_FAMILIES,
    cross,
    draw_linkage,
    group_scales,
    norm,
    perp,
)


def _guide_frame(
    scene: LinkageScene, result: LinkageAnalysis, guide: str
) -> tuple[np.ndarray, float, float, float]:
    """(a point G of the guide now, its rotation from the drawn pose, omega, alpha); ground: 0."""
    if guide == scene.ground:
        return scene.drawn(scene.links[guide].points[0]), 0.0, 0.0, 0.0
    g0, g1 = scene.links[guide].points[:2]
    now = result.points[g1].position - result.points[g0].position
    drawn = scene.drawn(g1) - scene.drawn(g0)
    turn = math.atan2(now[1], now[0]) - math.atan2(drawn[1], drawn[0])
    link = result.links[guide]
    return result.points[g0].position, turn, link.omega, link.alpha


@pytest.mark.slow
@pytest.mark.parametrize("family", SLIDER_FAMILIES)
@PROPERTY
@given(data=st.data())
def test_slider_components(family: str, data: st.DataObject) -> None:
    """At every slider and prismatic joint (scene-v1 'joints'; textbook composite motion):

    - the transport velocity/acceleration are those of the guide's point coinciding with P,
      computed here from the guide's own point G: v_G + omega_g k x GP, a_G + alpha_g k x GP -
      omega_g^2 GP;
    - v_tr + v_rel = v_P and a_tr + a_rel + a_cor = a_P (the absolute values of /analyze);
    - v_rel and a_rel are along the slot (the slot is a straight line fixed in the guide);
    - a_cor = 2 omega_guide k x v_rel, with omega_guide the guide link's own omega;
    - on a ground guide the transport terms and the Coriolis term are exactly zero (the carrier
      does not move; ERRATA E000-T3-3 is the textbook mistake this guards against);
    - a block in a prismatic joint turns with its guide.

    Tolerance 1e-9 of the group's largest magnitude (identities within one answer)."""
    _, scene, result = draw_linkage(data, family)
    v_scale, a_scale, w_scale, al_scale = group_scales(result)
    assert result.joints, "the family has a sliding joint"
    axes = {(j.point, j.links): j.axis for j in scene.joints if j.type != "revolute"}
    for joint in result.joints:
        guide, follower = joint.links
        G, turn, omega_g, alpha_g = _guide_frame(scene, result, guide)
        P = result.points[joint.point]
        axis = np.array(axes[(joint.point, joint.links)])
        u = np.array(
            [
                math.cos(turn) * axis[0] - math.sin(turn) * axis[1],
                math.sin(turn) * axis[0] + math.cos(turn) * axis[1],
            ]
        )
        if guide == scene.ground:
            assert np.all(joint.coriolis_acceleration == 0.0)
            assert np.all(joint.transport_velocity == 0.0)
            assert np.all(joint.transport_acceleration == 0.0)
            assert joint.omega_guide == 0.0
            v_G = a_G = np.zeros(2)
        else:
            v_G, a_G = (
                result.points[scene.links[guide].points[0]].velocity,
                result.points[scene.links[guide].points[0]].acceleration,
            )
        GP = P.position - G
        v_tr = v_G + omega_g * perp(GP)
        a_tr = a_G + alpha_g * perp(GP) - omega_g**2 * GP
        assert abs(joint.omega_guide - omega_g) <= IDENTITY_TOL * w_scale
        assert norm(joint.transport_velocity - v_tr) <= IDENTITY_TOL * v_scale
        assert norm(joint.transport_acceleration - a_tr) <= IDENTITY_TOL * a_scale
        assert norm(joint.transport_velocity + joint.relative_velocity - P.velocity) <= (
            IDENTITY_TOL * v_scale
        )
        assert (
            norm(
                joint.transport_acceleration
                + joint.relative_acceleration
                + joint.coriolis_acceleration
                - P.acceleration
            )
            <= IDENTITY_TOL * a_scale
        )
        assert abs(cross(joint.relative_velocity, u)) <= IDENTITY_TOL * v_scale
        assert abs(cross(joint.relative_acceleration, u)) <= IDENTITY_TOL * a_scale
        a_cor = 2.0 * omega_g * perp(joint.relative_velocity)
        assert norm(joint.coriolis_acceleration - a_cor) <= IDENTITY_TOL * a_scale
        if joint.type == "prismatic":
            block = result.links[follower]
            assert abs(block.omega - omega_g) <= IDENTITY_TOL * w_scale
            assert abs(block.alpha - alpha_g) <= IDENTITY_TOL * al_scale

"""Friction at the joints (issue 27, docs/DYNAMICS.md "Friction"): closed forms (a slider whose
reaction tilts by atan mu, a pin's friction circle), self-locking where the rod's force lies
inside the friction cone, and properties (zero coefficients give today's answers bit for bit,
the friction power is never positive and is what the driver pays on top, the efficiency is at
most 1).

No published worked answer of a slider-crank with friction was found in the reference corpus
(the textbook problems found state the data, not the answer); the slider-crank's answer here is
derived by hand below from the two-force rod and the friction cone.
"""

from __future__ import annotations

import copy
import math
import re
from typing import Any

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

import solver
from solver.analysis.instant import analyze
from solver.dynamics.analysis import linkage_dynamics
from solver.errors import InvalidScene
from solver.model.scene import parse_linkage
from solver.teaching.presets import build_preset
from tests.dynamics_cases import with_masses_and_loads
from tests.linkage_strategies import linkages
from tests.solver.dynamics.test_statics import F, L, R, slider_crank


def slider_only_torque(theta: float, mu: float, r: float = R, rod: float = L) -> float | None:
    """The driving torque of ``slider_crank`` with Coulomb friction mu at the slider alone, by
    hand: the massless rod is a two-force member, so the ground's and the load's force on it at B,
    G = (P - mu sgn(N) s N, N) (P = -F, s = sgn v_B), lies along the rod, e = (-cos beta,
    sin beta): N = -P tan beta / (1 - mu sgn(N) s tan beta), the sense sgn(N) that agrees with
    its own answer; the crank then needs T = -(A x G)_z. None where no sense agrees: the rod's
    force lies inside the friction cone (self-locking)."""
    A = np.array([r * math.cos(theta), r * math.sin(theta)])
    beta = math.asin(A[1] / rod)
    x_B = A[0] + rod * math.cos(beta)
    # v_B / omega = d x_B / d theta = -r sin theta - r cos theta tan beta (omega > 0)
    s = math.copysign(1.0, -r * math.sin(theta) - r * math.cos(theta) * math.tan(beta))
    P = -F
    for sense in (1.0, -1.0):
        N = -P * math.tan(beta) / (1 - mu * sense * s * math.tan(beta))
        if N * sense >= 0 and 1 - mu * sense * s * math.tan(beta) > 0:
            G = np.array([P - mu * sense * s * N, N])
            assert x_B > 0
            return float(-(A[0] * G[1] - A[1] * G[0]))
    return None


def test_slider_friction_tilts_the_reaction_by_the_friction_angle() -> None:
    """The driving torque with mu = 0.2 at the slider equals the hand solution at every sample
    (1e-12 of F r), and the slider's reaction makes atan 0.2 with the guide's normal."""
    mu = 0.2
    body = solver.sweep(slider_crank(0.0, B={"coefficient": mu}), 72, ["forces"]).as_dict()
    torque = body["drivers"][0]["torque"]
    for theta, value in zip(body["driver_angle"], torque, strict=True):
        expected = slider_only_torque(theta, mu)
        assert expected is not None
        assert value == pytest.approx(expected, abs=1e-12 * F * R)
    forces = np.array(next(j for j in body["joints"] if j["point"] == "B")["force"])
    moving = np.abs(np.sin(np.array(body["driver_angle"]))) > 1e-9  # not at the dead centres
    tilt = np.abs(forces[moving, 0] / forces[moving, 1])
    assert np.max(np.abs(tilt - mu)) <= 1e-12
    assert body["cycle"]["self_locking"] is None
    assert body["cycle"]["efficiency"] is None  # a constant load does no net work in a turn


def pin_bar(omega: float) -> dict[str, Any]:
    """A bar O-A (2 m) on the pin O (radius 0.02 m, mu = 0.3) driven at ``omega``, with a force
    of 100 N across it at A (+y)."""
    return {
        "kind": "linkage",
        "points": {"O": [0, 0], "A": [2, 0]},
        "links": {"ground": {"points": ["O"], "ground": True}, "bar": {"points": ["O", "A"]}},
        "joints": [
            {
                "type": "revolute",
                "point": "O",
                "links": ["ground", "bar"],
                "friction": {"coefficient": 0.3, "pin_radius": 0.02},
            }
        ],
        "drivers": [{"link": "bar", "omega": omega}],
        "forces": [
            {"name": "F", "link": "bar", "point": "A", "magnitude": 100, "direction_deg": 90}
        ],
    }


@pytest.mark.parametrize("omega", [3.0, -3.0])
def test_pin_friction_is_the_friction_circle(omega: float) -> None:
    """A bar O-A (2 m) held against a force F = 100 N at A across it, pin O of radius 0.02 m
    with mu = 0.3: the reaction (F at O) is tangent to the friction circle mu r = 6 mm, on the
    side that opposes the rotation, so T = -2 F + mu r F sgn(omega)."""
    doc = pin_bar(omega)
    body = solver.analyze(doc, ["forces"]).as_dict()
    driver = body["drivers"][0]
    assert driver["torque_frictionless"] == pytest.approx(-200.0, abs=1e-12)
    assert driver["torque"] == pytest.approx(-200.0 + 0.3 * 0.02 * 100 * math.copysign(1, omega))
    assert body["self_locking"] is None


def test_self_locking_where_the_rod_pushes_inside_the_friction_cone() -> None:
    """r / l = 0.95 and mu = 0.5 (friction angle 26.57 deg): where the rod resists the crank and
    leans more than 90 - 26.57 deg from the guide (mu tan beta >= 1), no force moves the slider;
    the locked samples are exactly those where the hand solution has no sense, and the cycle
    reports the first with the slider's friction angle in words."""
    mu, r, rod = 0.5, 0.95, 1.0
    body = solver.sweep(
        slider_crank(0.0, r=r, rod=rod, B={"coefficient": mu}), 360, ["forces"]
    ).as_dict()
    torque = body["drivers"][0]["torque"]
    hand = [slider_only_torque(t, mu, r, rod) for t in body["driver_angle"]]
    assert [t is None for t in torque] == [h is None for h in hand]
    locked = [math.degrees(t) for t, h in zip(body["driver_angle"], hand, strict=True) if h is None]
    assert 250 < locked[0] < 252 and 288 < locked[-1] < 290  # asin(0.8944 / 0.95) = 70.3 deg
    for value, expected in zip(torque, hand, strict=True):
        if expected is not None:
            assert value == pytest.approx(expected, rel=1e-12, abs=1e-11 * F * r)
    locking = body["cycle"]["self_locking"]
    assert locking["driver_angle_deg"] == pytest.approx(locked[0])
    assert "slider B" in locking["reason"] and "26.5651 deg" in locking["reason"]
    assert body["cycle"]["efficiency"] is None and body["cycle"]["mean_torque"] is None
    at_pose = solver.analyze(slider_crank(270.0, r=r, rod=rod, B={"coefficient": mu}), ["forces"])
    assert at_pose.as_dict()["drivers"][0]["torque"] is None
    assert "self-locking at driver angle -90 deg" in at_pose.as_dict()["self_locking"]


def with_friction(doc: dict[str, Any], mu: float, pin_radius: float) -> dict[str, Any]:
    for joint in doc["joints"]:
        joint["friction"] = (
            {"coefficient": mu, "pin_radius": pin_radius}
            if joint["type"] == "revolute"
            else {"coefficient": mu}
        )
    return doc


def test_zero_coefficients_give_todays_answers_bit_for_bit() -> None:
    masses = {"crank": {"mass": 2.0, "bar": ["O", "A"]}, "rod": {"mass": 5.0, "bar": ["A", "B"]}}
    plain = slider_crank(30.0) | {"masses": masses, "gravity": [0, -9.81]}
    plain["forces"][0]["magnitude"] = 'where(omega("rod") >= 0, -1000, 1000)'  # net work in
    zero = with_friction(copy.deepcopy(plain), 0.0, 0.01)
    before = solver.sweep(plain, 90, ["forces", "energy"]).as_dict()
    after = solver.sweep(zero, 90, ["forces", "energy"]).as_dict()
    for key in ("joints", "frame_force", "frame_moment", "energy"):
        assert repr(after[key]) == repr(before[key])
    driver = after["drivers"][0]
    assert repr(driver["torque"]) == repr(before["drivers"][0]["torque"])
    assert repr(driver["torque_frictionless"]) == repr(before["drivers"][0]["torque"])
    assert after["cycle"]["efficiency"] == 1.0 and after["cycle"]["self_locking"] is None


@pytest.mark.parametrize("family", ["four_bar", "slider_crank", "block_in_lever", "six_bar"])
@settings(max_examples=6, deadline=None, database=None, suppress_health_check=list(HealthCheck))
@given(data=st.data(), mu=st.floats(0.01, 0.3))
def test_friction_power_is_never_positive_and_the_driver_pays_it(
    family: str, data: st.DataObject, mu: float
) -> None:
    """P_f = -sum mu r |F| |omega_rel| - sum mu |N| |v_rel| <= 0, and with one driver the power
    balance holds with it: (M - M_0) omega = -P_f (1e-9 of the largest force x size x omega)."""
    doc = with_friction(data.draw(linkages(family).flatmap(with_masses_and_loads)), mu, 0.01)
    scene = parse_linkage(doc)
    motion = analyze(scene, ["acceleration"]).motion
    d = linkage_dynamics(scene, motion, np.array([0.0]))
    assert d.friction is not None
    if d.friction.locked[0]:
        return
    assert d.friction.power[0] <= 0.0
    driver = d.drivers[0]
    assert driver.omega is not None and driver.torque_frictionless is not None
    omega = float(driver.omega[0])
    xy = np.array(list(doc["points"].values()))
    size = 1 + float(np.abs(xy).max())
    scale = max(1.0, *(float(np.hypot(*j.force[0])) for j in d.forces.joints)) * size
    paid = float(driver.torque[0] - driver.torque_frictionless[0]) * omega
    assert paid == pytest.approx(-float(d.friction.power[0]), abs=1e-9 * scale * (1 + abs(omega)))


@pytest.mark.parametrize("mu", [0.05, 0.2, 0.4])
def test_efficiency_is_at_most_one(mu: float) -> None:
    """A slider-crank whose load on the slider switches with the rod's sense of rotation (so
    the driver puts net work in), with friction at every joint: 0 < efficiency < 1, lower for
    more friction."""
    doc = with_friction(slider_crank(0.0), mu, 0.01)
    doc["forces"][0]["magnitude"] = 'where(omega("rod") >= 0, -1000, 1000)'
    eta = solver.sweep(doc, 360, ["forces"]).as_dict()["cycle"]["efficiency"]
    assert 0 < eta < 1
    less = with_friction(slider_crank(0.0), mu / 2, 0.01)
    less["forces"] = doc["forces"]
    assert solver.sweep(less, 360, ["forces"]).as_dict()["cycle"]["efficiency"] > eta


@pytest.mark.parametrize(
    ("joint", "friction", "message"),
    [
        (2, {"coefficient": -0.1}, "joints[2].friction.coefficient: a friction coefficient is not"),
        (2, {"coefficient": 0.1, "pin_radius": 0.01}, "joints[2].friction.pin_radius: a slider"),
        (0, {"coefficient": 0.1}, "joints[0].friction.pin_radius: a revolute joint's friction"),
        (0, {"coefficient": 0.1, "pin_radius": 0}, "joints[0].friction.pin_radius: the pin radius"),
        (0, {"pin_radius": 0.01}, "joints[0].friction.coefficient: friction needs"),
        (0, {"coefficient": 0.1, "pin_radius": 0.01, "mu": 1}, "joints[0].friction.mu: friction"),
        (0, {"coefficient": 11, "pin_radius": 0.01}, "joints[0].friction.coefficient"),
    ],
)
def test_bad_friction_is_an_invalid_scene(
    joint: int, friction: dict[str, Any], message: str
) -> None:
    doc = slider_crank(30.0)
    doc["joints"][joint]["friction"] = friction
    with pytest.raises(InvalidScene, match=re.escape(message)):
        solver.analyze(doc, ["forces"])


def test_no_efficiency_where_the_loads_do_no_net_work() -> None:
    """A four-bar with weights and a constant moment on its rocker: over a turn the loads do no
    net work (the frictionless mean input power is rounding), so there is no efficiency."""
    doc = build_preset("four_bar", {"mass_per_length": 10, "gravity": 9.81, "load": 50})
    cycle = solver.sweep(with_friction(doc, 0.1, 0.01), 360, ["forces"]).as_dict()["cycle"]
    assert cycle["efficiency"] is None and cycle["mean_power"] > 0

"""Driver torques by virtual power (the partial motion of each driver): equal to the Newton-Euler
torques with two drivers, to the power balance with one, and to a five-bar worked by hand."""

from __future__ import annotations

import math
from typing import Any

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

import solver
from solver.analysis.instant import analyze
from solver.dynamics.analysis import linkage_dynamics
from solver.dynamics.energy import power_balance_torque
from solver.dynamics.virtual_power import partial_motion, virtual_power_torque
from solver.errors import KinematicsError
from solver.model.scene import parse_linkage
from tests.dynamics_cases import five_bars, square_five_bar, with_masses_and_loads
from tests.linkage_strategies import linkages

PROPERTY = settings(
    max_examples=10, deadline=None, database=None, suppress_health_check=list(HealthCheck)
)


def _scale(d: Any, doc: dict[str, Any]) -> float:
    """Force times length: the size of a torque in this linkage (for absolute tolerances)."""
    xy = np.array(list(doc["points"].values()))
    size = float(np.ptp(xy, axis=0).max()) or 1.0
    forces = [float(np.abs(j.force).max()) for j in d.forces.joints]
    return max(1.0, *forces) * size


def _analysed(doc: dict[str, Any]) -> tuple[Any, Any]:
    scene = parse_linkage(doc)
    try:
        motion = analyze(scene, ["acceleration"]).motion
    except KinematicsError:
        return scene, None
    return scene, motion


@PROPERTY
@given(doc=five_bars().flatmap(with_masses_and_loads))
def test_two_cranks_newton_euler_equals_virtual_power(doc: dict[str, Any]) -> None:
    """A five-bar driven by both cranks, random masses, gravity and loads: each driver's torque
    from the Newton-Euler system equals its virtual-power torque (1e-9 of force x size)."""
    scene, motion = _analysed(doc)
    if motion is None:
        return
    d = linkage_dynamics(scene, motion, np.array([scene.time]))
    assert [driver.link for driver in d.drivers] == ["crank1", "crank2"]
    for driver in d.drivers:
        assert driver.torque_from_power_balance[0] == pytest.approx(
            driver.torque[0], abs=1e-9 * _scale(d, doc)
        )


@pytest.mark.parametrize("family", ["four_bar", "slider_crank", "block_in_lever", "six_bar"])
@PROPERTY
@given(data=st.data())
def test_one_driver_virtual_power_is_the_power_balance(family: str, data: st.DataObject) -> None:
    """With one driver the partial motion is the motion divided by omega: the virtual-power
    torque equals the power balance (d(T + V)/dt - P_loads) / omega and the Newton-Euler torque."""
    doc = data.draw(linkages(family).flatmap(with_masses_and_loads))
    scene = parse_linkage(doc)
    motion = analyze(scene, ["acceleration"]).motion
    d = linkage_dynamics(scene, motion, np.array([0.0]))
    omega = motion.links[scene.drivers[0].link].omega
    if omega[0] == 0.0:
        return
    loads = (d.forces.elements, d.forces.forces, d.forces.moments)
    gravity = np.array(doc["gravity"])
    virtual = virtual_power_torque(
        partial_motion(scene, motion, 0), motion, scene.size, *loads, gravity
    )
    balance = power_balance_torque(*loads, gravity, omega)
    tolerance = 1e-9 * _scale(d, doc)
    assert virtual[0] == pytest.approx(balance[0], abs=tolerance)
    assert virtual[0] == pytest.approx(d.drivers[0].torque[0], abs=tolerance)


def test_a_five_bar_by_hand() -> None:
    """Driver 1 at unit rate, B held: v_A = (-1, 0), v_C on the circle about B (along (1, 1)) and
    (v_C - v_A) . (C - A) = 0 give dv_C/dq_1 = (-1/2, -1/2); likewise dv_C/dq_2 = (-1/2, 1/2). At
    omega_1 = omega_2 = w the dyad translates with a_C = a_A = (0, -w^2), so with the mass m at C
    T_1 = m (a_C - g) . dv_C/dq_1 = -m (g - w^2) / 2 and T_2 = +m (g - w^2) / 2 (at rest: the
    weight shared by the two 45-degree links, each pushing its crank's pin with m g / 2 a side)."""
    w, m, g = 1.5, 4.0, 9.81
    doc = square_five_bar(w, m, g)
    scene = parse_linkage(doc)
    motion = analyze(scene, ["acceleration"]).motion
    first, second = (partial_motion(scene, motion, i) for i in (0, 1))
    assert first.points["C"].v[0] == pytest.approx([-0.5, -0.5], abs=1e-15)
    assert second.points["C"].v[0] == pytest.approx([-0.5, 0.5], abs=1e-15)
    assert motion.points["C"].a[0] == pytest.approx([0.0, -(w**2)], abs=1e-14)
    body = solver.analyze(scene, ["forces"]).as_dict()
    expected = [-m * (g - w**2) / 2, m * (g - w**2) / 2]
    for driver, torque in zip(body["drivers"], expected, strict=True):
        assert driver["torque"] == pytest.approx(torque, rel=1e-13)
        assert driver["torque_from_power_balance"] == pytest.approx(torque, rel=1e-13)


def test_a_driver_at_rest_has_no_power_balance_torque() -> None:
    """dynamics-v1: null where the driver's omega is 0 (the other driver's is still given)."""
    doc = square_five_bar(1.5, 4.0, 9.81)
    doc["drivers"][1]["omega"] = 0.0
    body = solver.analyze(parse_linkage(doc), ["forces"]).as_dict()
    first, second = body["drivers"]
    assert first["torque_from_power_balance"] == pytest.approx(first["torque"], rel=1e-12)
    assert second["torque_from_power_balance"] is None
    assert math.isfinite(second["torque"])


def test_a_two_driver_sweep_checks_every_sample() -> None:
    """A sweep of the first crank with the second held at its omega: the virtual-power torque of
    both drivers equals the Newton-Euler one at every sample."""
    doc = square_five_bar(3.0, 4.0, 9.81)
    doc["masses"] = {
        name: {"mass": 2.0, "bar": doc["links"][name]["points"][:2]}
        for name in ("crank1", "crank2", "left", "right")
    }
    body = solver.sweep(parse_linkage(doc), 90, ["acceleration", "forces"]).as_dict()
    for driver in body["drivers"]:
        torque = np.array(driver["torque"])
        check = np.array(driver["torque_from_power_balance"], dtype=float)
        assert check == pytest.approx(torque, abs=1e-9 * max(1.0, np.abs(torque).max()))

"""Static force analysis (issue 27, docs/DYNAMICS.md "Statics"): closed forms of the holding
torque (a slider-crank's T = F r sin(theta + beta) / cos beta, a four-bar's by virtual work
omega_out / omega_in), the mechanical advantage, and properties (statics is dynamics without
inertia; the virtual-work balance of the weights and loads to 1e-12)."""

from __future__ import annotations

import json
import math
from pathlib import Path
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

R, L, F = 0.1, 0.3, 1000.0


def slider_crank(theta_deg: float, r: float = R, rod: float = L, **joint_friction: Any) -> Any:
    """Crank O-A (r), rod A-B (``rod``), B sliding on the x axis (a slider joint of the rod, no
    block), a force -F along x at B; driven at 10 rad/s; no masses. ``joint_friction``: the
    ``friction`` of joints O, A, B by point name."""
    th = math.radians(theta_deg)
    A = [r * math.cos(th), r * math.sin(th)]
    joints: list[dict[str, Any]] = [
        {"type": "revolute", "point": "O", "links": ["ground", "crank"]},
        {"type": "revolute", "point": "A", "links": ["crank", "rod"]},
        {"type": "slider", "point": "B", "links": ["ground", "rod"], "axis": [1, 0]},
    ]
    for joint in joints:
        if joint["point"] in joint_friction:
            joint["friction"] = joint_friction[joint["point"]]
    return {
        "kind": "linkage",
        "points": {"O": [0, 0], "A": A, "B": [A[0] + math.sqrt(rod * rod - A[1] ** 2), 0]},
        "links": {
            "ground": {"points": ["O"], "ground": True},
            "crank": {"points": ["O", "A"]},
            "rod": {"points": ["A", "B"]},
        },
        "joints": joints,
        "drivers": [{"link": "crank", "omega": 10.0}],
        "forces": [{"name": "P", "link": "rod", "point": "B", "magnitude": -F}],
    }


def test_slider_crank_holding_torque_is_f_r_sin_theta_plus_beta_over_cos_beta() -> None:
    """T = -F r sin(theta + beta) / cos beta (sin beta = r sin theta / l; the load -F x at B
    and counter-clockwise torques positive): the closed form of every textbook, over a turn."""
    body = solver.sweep(slider_crank(0.0), 72, ["forces"], statics=True).as_dict()
    theta = np.array(body["driver_angle"])
    beta = np.arcsin(R * np.sin(theta) / L)
    expected = -F * R * np.sin(theta + beta) / np.cos(beta)
    torque = np.array(body["drivers"][0]["torque"])
    assert np.max(np.abs(torque - expected)) <= 1e-12 * F * R
    # the rod is a two-force member: the slider's reaction is normal to the guide, F tan beta
    normal = np.array(next(j for j in body["joints"] if j["point"] == "B")["force"])
    assert np.max(np.abs(normal[:, 0])) == 0.0
    assert np.max(np.abs(normal[:, 1] - (-F) * -np.tan(beta))) <= 1e-12 * F


def four_bar(**extra: Any) -> dict[str, Any]:
    """A crank-rocker (ground 1, crank 0.3, coupler 1, rocker 0.8) with a moment on the rocker."""
    doc = build_preset("four_bar", {"ground": 1.0, "crank": 0.3, "coupler": 1.0, "rocker": 0.8})
    doc["torques"] = [{"name": "M_out", "link": "rocker", "moment": "-50"}]
    doc.update(extra)
    return doc


def test_four_bar_holding_torque_by_virtual_work() -> None:
    """T_in omega_in + M_out omega_out = 0 with omega_out / omega_in = a sin(theta3 - theta2) /
    (c sin(theta3 - theta4)) (the four-bar's closed form, Norton's eq. 6.18), and the mechanical
    advantage M_out / T_in = -omega_in / omega_out."""
    doc = four_bar()
    body = solver.sweep(doc, 90, ["position", "forces"], statics=True).as_dict()
    angle = {name: np.array(link["angle"]) for name, link in body["links"].items()}
    a, c = 0.3, 0.8
    ratio = (
        a
        * np.sin(angle["coupler"] - angle["crank"])
        / (c * np.sin(angle["coupler"] - angle["rocker"]))
    )
    torque = np.array(body["drivers"][0]["torque"])
    assert np.max(np.abs(torque - 50.0 * ratio)) <= 1e-11 * 50
    advantage = np.array(body["mechanical_advantage"]["M_out"], dtype=float)
    assert np.max(np.abs(advantage - 1 / ratio)) <= 1e-9 * np.max(np.abs(1 / ratio))
    assert np.allclose(-50.0 / torque, -advantage, rtol=1e-11)


def _static_and_dynamic(doc: dict[str, Any]) -> tuple[Any, Any]:
    scene = parse_linkage(doc)
    motion = analyze(scene, ["acceleration"]).motion
    times = np.array([scene.time])
    return (
        linkage_dynamics(scene, motion, times, statics=True),
        linkage_dynamics(scene, motion, times),
    )


@pytest.mark.parametrize("family", ["four_bar", "slider_crank", "block_in_lever", "six_bar"])
@settings(max_examples=6, deadline=None, database=None, suppress_health_check=list(HealthCheck))
@given(data=st.data())
def test_statics_balances_the_virtual_work_of_the_weights_and_loads(
    family: str, data: st.DataObject
) -> None:
    """T omega = -sum m g . v_G - sum F . v_P - sum M omega_L (the virtual-work, or power,
    balance without the kinetic energy), 1e-12 of the largest term; without masses statics is
    dynamics bit for bit."""
    doc = data.draw(linkages(family).flatmap(with_masses_and_loads))
    if doc["drivers"][0].get("omega", 0.0) == 0.0:
        doc["drivers"][0]["omega"] = 1.5
    static, dynamic = _static_and_dynamic(doc)
    g = np.array(doc["gravity"])
    terms = [-e.mass * float(g @ e.v[0]) for e in static.forces.elements]
    terms += [-float(f.power[0]) for f in static.forces.forces]
    terms += [-float(m.power[0]) for m in static.forces.moments]
    driver = static.drivers[0]
    assert driver.omega is not None
    omega = float(driver.omega[0])
    scale = max(abs(t) for t in [*terms, float(driver.torque[0] * omega), 1.0])
    assert float(driver.torque[0]) * omega == pytest.approx(sum(terms), abs=1e-12 * scale)
    assert float(driver.torque_from_power_balance[0]) * omega == pytest.approx(
        sum(terms), abs=1e-12 * scale
    )
    for key in ("masses", "point_masses"):
        doc.pop(key, None)
    static, dynamic = _static_and_dynamic(doc)
    assert np.array_equal(static.forces.solution, dynamic.forces.solution)


def test_statics_is_dynamics_with_the_linkage_at_rest() -> None:
    """With masses and gravity, the static forces at omega = 2 rad/s are the dynamic ones of the
    same pose at rest (omega = alpha = 0: no inertia force), to rounding."""
    masses = {
        "crank": {"mass": 2.0, "bar": ["A", "B"]},
        "coupler": {"mass": 5.0, "bar": ["B", "C"]},
        "rocker": {"mass": 4.0, "center": [1.0, 0.4], "inertia": 0.3},
    }
    moving = four_bar(masses=masses, gravity=[0, -9.81])
    moving["drivers"][0].update(omega=2.0, alpha=3.0)
    still = four_bar(masses=masses, gravity=[0, -9.81])
    still["drivers"][0].update(omega=0.0, alpha=0.0)
    static = solver.analyze(moving, ["forces"], statics=True).as_dict()
    at_rest = solver.analyze(still, ["forces"]).as_dict()
    dynamic = solver.analyze(moving, ["forces"]).as_dict()
    for s, r, d in zip(static["joints"], at_rest["joints"], dynamic["joints"], strict=True):
        assert s["force"] == pytest.approx(r["force"], abs=1e-12 * 200)
        assert s["force"] != pytest.approx(d["force"], abs=1e-3)  # the inertia matters here
    assert static["drivers"][0]["torque"] == pytest.approx(
        at_rest["drivers"][0]["torque"], abs=1e-12 * 200
    )


def test_statics_asks_for_forces() -> None:
    with pytest.raises(InvalidScene, match="statics: a static force analysis asks"):
        solver.analyze(four_bar(), ["position"], statics=True)


def test_a_gear_train_has_no_statics_flag() -> None:
    """A gear train's torques come from input_torque, static already: the flag is refused."""
    path = Path(__file__).resolve().parents[3] / "server" / "examples" / "G001-planetary.json"
    with pytest.raises(InvalidScene, match="statics: a gear_train's torques are static"):
        solver.analyze(json.loads(path.read_text()), ["forces"], statics=True)

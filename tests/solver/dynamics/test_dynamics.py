"""Inverse dynamics in the solver: closed forms, the moment balance about the origin, the state
expressions of loads, and the scene fields' validation."""

from __future__ import annotations

import math
from typing import Any

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from solver.analysis.instant import analyze
from solver.dynamics.analysis import linkage_dynamics
from solver.errors import InvalidExpression
from solver.kinematics.rigid import cross
from solver.model.laws import parse_state_expression, parse_time_law
from solver.model.scene import parse_linkage
from tests.dynamics_cases import with_masses_and_loads
from tests.linkage_strategies import linkages


def crank(angle_deg: float, omega: float, alpha: float, **extra: Any) -> dict[str, Any]:
    """A bar O-A (length 2 m) turning about O, drawn along +x."""
    return {
        "kind": "linkage",
        "points": {"O": [0, 0], "A": [2, 0]},
        "links": {"ground": {"points": ["O"], "ground": True}, "bar": {"points": ["O", "A"]}},
        "joints": [{"type": "revolute", "point": "O", "links": ["ground", "bar"]}],
        "drivers": [{"link": "bar", "omega": omega, "alpha": alpha, "angle_deg": angle_deg}],
        **extra,
    }


def dynamics_of(doc: dict[str, Any]) -> Any:
    scene = parse_linkage(doc)
    result = analyze(scene, ["acceleration"])
    return linkage_dynamics(scene, result.motion, np.array([scene.time]))


@pytest.mark.parametrize(("angle", "omega", "alpha"), [(30, 2.0, 3.0), (-120, -5.0, 0.0)])
def test_a_uniform_bar_turning_under_gravity(angle: float, omega: float, alpha: float) -> None:
    """M = I_O alpha + m g (L/2) cos(theta) with I_O = m L^2 / 3; the pivot force m a_G - m g
    with a_G = alpha k x r_G - omega^2 r_G; T = I_O omega^2 / 2; V = m g y_G."""
    m, L, g = 3.0, 2.0, 9.81
    doc = crank(angle, omega, alpha, masses={"bar": {"mass": m, "bar": ["O", "A"]}})
    doc["gravity"] = [0, -g]
    d = dynamics_of(doc)
    th = math.radians(angle)
    I_O = m * L**2 / 3
    assert d.drivers[0].torque[0] == pytest.approx(
        I_O * alpha + m * g * L / 2 * math.cos(th), rel=1e-12
    )
    r = np.array([math.cos(th), math.sin(th)]) * L / 2
    a_G = alpha * np.array([-r[1], r[0]]) - omega**2 * r
    assert d.forces.joints[0].force[0] == pytest.approx(m * a_G - m * np.array([0, -g]), abs=1e-12)
    assert d.energy.kinetic[0] == pytest.approx(I_O * omega**2 / 2, rel=1e-12)
    assert d.energy.potential[0] == pytest.approx(m * g * r[1], abs=1e-12)
    assert d.equivalent_inertia[0] == pytest.approx(I_O, rel=1e-12)


def test_a_force_turning_with_the_link_and_a_moment() -> None:
    """At rest, a force F at A perpendicular to the bar (90 deg from it) needs M = -F L, and an
    external moment M_ext needs -M_ext; the power-balance torque is null at omega = 0."""
    doc = crank(
        40,
        0.0,
        0.0,
        forces=[{"name": "F", "link": "bar", "point": "A", "magnitude": "5",
                 "direction_deg": 90, "relative_to": "link"}],
        torques=[{"name": "M", "link": "bar", "moment": "-3"}],
    )  # fmt: skip
    d = dynamics_of(doc)
    assert d.drivers[0].torque[0] == pytest.approx(-5 * 2 + 3, rel=1e-12)
    assert np.isnan(d.drivers[0].torque_from_power_balance[0])
    assert np.isnan(d.equivalent_inertia[0])
    th = math.radians(130)
    assert d.forces.joints[0].force[0] == pytest.approx(-5 * np.array([math.cos(th), math.sin(th)]))


@pytest.mark.parametrize("family", ["four_bar", "slider_crank", "block_in_lever", "six_bar"])
@settings(max_examples=8, deadline=None, database=None, suppress_health_check=list(HealthCheck))
@given(data=st.data())
def test_frame_moment_is_the_moment_of_weights_and_loads_minus_the_rate_of_angular_momentum(
    family: str, data: st.DataObject
) -> None:
    """About the origin: M_frame = sum r x m g + sum r_F x F + sum M - sum (I alpha + r x m a)
    (the whole mechanism's balance; the solver's equations take moments about each link's own
    moving point instead)."""
    doc = data.draw(linkages(family).flatmap(with_masses_and_loads))
    scene = parse_linkage(doc)
    d = linkage_dynamics(scene, analyze(scene, ["acceleration"]).motion, np.array([0.0]))
    g = np.array(doc["gravity"])
    expected = 0.0
    for e in d.forces.elements:
        expected += float(cross(e.p, e.mass * (g - e.a))[0]) - e.inertia * float(e.alpha[0])
    for f in d.forces.forces:
        expected += float(cross(f.position, f.force)[0])
    for m in d.forces.moments:
        expected += float(m.moment[0])
    xy = np.array(list(doc["points"].values()))
    scale = max(1.0, *(float(np.hypot(*j.force[0])) for j in d.forces.joints)) * (
        1 + float(np.abs(xy).max())
    )
    assert float(d.forces.frame_moment[0]) == pytest.approx(expected, abs=1e-9 * scale)


# --- state expressions ------------------------------------------------------------------------

STATE = {"L": (np.array([0.5, -2.0, 3.0]), np.array([1.0, -1.0, 0.0]), np.array([2.0, 0, -2]))}
TIMES = np.array([0.0, 1.0, 2.0])


@pytest.mark.parametrize(
    ("text", "expected"),
    [
        ('angle("L") + omega("L") * alpha("L")', [2.5, -2.0, 3.0]),
        ("where(t >= 1, 10, -10)", [-10, 10, 10]),
        ('where(omega("L") < 0 or t > 1.5, 1, 0)', [0, 1, 1]),
        ("0 < t <= 1", [0, 1, 0]),
        ("not t > 0 and 1", [1, 0, 0]),
        ("2^3 + sqrt(4) - 3*cos(pi)", [13, 13, 13]),
        ("where(t > 0, sqrt(t - 1 + 1), 0)", [0, 1, math.sqrt(2)]),
    ],
)
def test_state_expressions(text: str, expected: list[float]) -> None:
    assert parse_state_expression(text).evaluate(TIMES, STATE) == pytest.approx(expected)


@pytest.mark.parametrize(
    ("text", "position"),
    [
        ("t == 1", 2),
        ("t != 1", 2),
        ("angle(L)", 6),
        ("where(t, 1)", 0),
        ('angle("L", 2)', 0),
        ("foo(t)", 0),
        ('__import__("os")', 0),
        ("t if t else 1", 2),
        ("(lambda: 1)()", 1),
        ("t not 1", 2),
        ("t[0]", 1),
    ],
)
def test_bad_state_expressions_point_at_the_character(text: str, position: int) -> None:
    with pytest.raises(InvalidExpression) as error:
        parse_state_expression(text)
    assert error.value.position == position


def test_the_time_law_language_is_unchanged() -> None:
    for text in ("t < 1", 'angle("L")', "where(t, 1, 2)", "t and 1"):
        with pytest.raises(InvalidExpression):
            parse_time_law(text)


def test_an_undefined_value_is_an_invalid_expression_naming_the_state() -> None:
    with pytest.raises(InvalidExpression, match=r'angle\("L"\) = -2'):
        parse_state_expression('sqrt(angle("L"))').evaluate(TIMES, STATE)


def test_dense_and_sparse_solutions_agree_and_singular_samples_take_the_neighbours_mean(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    """Both ways of solving the samples' blocks give the same forces (1e-12 relative); a sample
    marked singular (a change point inside a sweep) gets the mean of its neighbours."""
    from solver.analysis.sweeps import sweep
    from solver.dynamics import newton_euler
    from tests.dynamics_cases import seed004_scene

    scene = parse_linkage(seed004_scene())
    motion = sweep(scene, 36, ["acceleration"]).motion
    times = np.linspace(0, 0.25, 36, endpoint=False)
    system = newton_euler.inverse_dynamics(scene, motion, times).system
    singular = np.array([0, 7])
    dense = system.solve(singular)
    monkeypatch.setattr(newton_euler, "DENSE_LIMIT", 0)
    sparse = system.solve(singular)
    assert sparse == pytest.approx(dense, rel=1e-12, abs=1e-9)
    plain = system.solve(np.array([], dtype=int))
    assert dense[7] == pytest.approx(0.5 * (plain[6] + plain[8]), rel=1e-12)
    assert dense[0] == pytest.approx(0.5 * (plain[35] + plain[1]), rel=1e-12)
    assert np.delete(dense, [0, 7], axis=0) == pytest.approx(np.delete(plain, [0, 7], axis=0))

"""Gear trains (issue 25, docs/GEARS.md) against textbook trains with published answers and by
properties. The relations are solved in exact rational arithmetic, so the speeds agree with the
textbook ratios to rounding: REL = 1e-12."""

from __future__ import annotations

from fractions import Fraction
from typing import Any

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import solver
from solver.gears import degrees_of_freedom, parse_gear_train, willis_relation

REL = 1e-12
# Speeds a user gives: 0 (fixed) or at least a micro-radian per second (a first input of 1e-300
# rad/s makes train values past a float: refused, see the last test).
speed = st.floats(-1e3, 1e3).filter(lambda x: x == 0 or abs(x) > 1e-6)


def planetary(sun: int, planet: int, ring: int, inputs: dict[str, float], **extra: Any) -> dict:
    """A simple planetary train: sun, one planet on the arm, an annulus."""
    return {
        "kind": "gear_train",
        "gears": {
            "sun": {"teeth": sun},
            "planet": {"teeth": planet},
            "ring": {"teeth": ring, "internal": True},
        },
        "carriers": ["arm"],
        "mounts": {"planet": "arm"},
        "shafts": [],
        "meshes": [["sun", "planet"], ["planet", "ring"]],
        "inputs": inputs,
        **extra,
    }


def reverted(a: int, b: int, c: int, d: int, omega: float) -> dict:
    """A compound reverted train: a drives b, c on b's shaft drives d (a and d coaxial)."""
    return {
        "kind": "gear_train",
        "gears": {n: {"teeth": t} for n, t in zip("abcd", (a, b, c, d), strict=True)},
        "shafts": [["b", "c"]],
        "meshes": [["a", "b"], ["c", "d"]],
        "inputs": {"a": omega},
    }


def differential(left: float, right: float) -> dict:
    """A spur-gear differential: side gears L and R (20 teeth) on the carrier's axis, two meshing
    planets (10 teeth) on the carrier, P1 on L and P2 on R."""
    return {
        "kind": "gear_train",
        "gears": {"L": {"teeth": 20}, "P1": {"teeth": 10}, "P2": {"teeth": 10}, "R": {"teeth": 20}},
        "carriers": ["C"],
        "mounts": {"P1": "C", "P2": "C"},
        "meshes": [["L", "P1"], ["P1", "P2"], ["P2", "R"]],
        "inputs": {"L": left, "R": right},
        "module": 0.003,
    }


def two_stage(s1: int, p1: int, r1: int, s2: int, p2: int, r2: int, omega: float) -> dict:
    """Two planetary stages, both rings fixed, the first carrier keyed to the second sun."""
    gears = {
        "s1": {"teeth": s1}, "p1": {"teeth": p1}, "r1": {"teeth": r1, "internal": True},
        "s2": {"teeth": s2}, "p2": {"teeth": p2}, "r2": {"teeth": r2, "internal": True},
    }  # fmt: skip
    return {
        "kind": "gear_train",
        "gears": gears,
        "carriers": ["c1", "c2"],
        "mounts": {"p1": "c1", "p2": "c2"},
        "shafts": [["c1", "s2"]],
        "meshes": [["s1", "p1"], ["p1", "r1"], ["s2", "p2"], ["p2", "r2"]],
        "inputs": {"s1": omega, "r1": 0.0, "r2": 0.0},
    }


def omegas(doc: dict, **kwargs: Any) -> dict[str, float]:
    return {k: v["omega"] for k, v in solver.analyze(doc, **kwargs)["members"].items()}


# --- textbook trains -----------------------------------------------------------------------------


def test_shigley_planetary_sun_driven_ring_fixed() -> None:
    """Shigley's Mechanical Engineering Design, ch. 13, the planetary example: sun 20, planet 30,
    ring 80 fixed, the sun at -100 rev/min (clockwise): the arm turns at -20 rev/min and the
    planet at +33 1/3 rev/min (e = -N2/N5 = -1/4 from the sun to the ring, arm fixed)."""
    w = omegas(planetary(20, 30, 80, {"sun": -100.0, "ring": 0.0}))
    assert w["arm"] == pytest.approx(-20.0, rel=REL)
    assert w["planet"] == pytest.approx(100.0 / 3.0, rel=REL)
    assert w["ring"] == 0.0


@pytest.mark.parametrize(("sun", "planet"), [(20, 30), (24, 18), (13, 41), (100, 7)])
def test_planetary_with_the_ring_fixed(sun: int, planet: int) -> None:
    """omega_arm / omega_sun = N_s / (N_s + N_r) with the ring fixed (Norton, ch. 9; the
    tabular method: arm locked, the sun turned once: the ring turns -N_s/N_r)."""
    ring = sun + 2 * planet
    body = solver.analyze(planetary(sun, planet, ring, {"sun": 7.5, "ring": 0.0}, module=0.001))
    assert body["members"]["arm"]["train_value"] == pytest.approx(sun / (sun + ring), rel=REL)
    assert body["members"]["arm"]["omega"] == pytest.approx(7.5 * sun / (sun + ring), rel=REL)
    assert body["first_input"] == "sun" and body["degrees_of_freedom"] == 2


def test_compound_reverted_train_is_the_product_of_tooth_ratios() -> None:
    """e = (N_a / N_b) (N_c / N_d), positive through two external meshes (Shigley Eq. 13-30:
    the product of the driving tooth numbers over the product of the driven)."""
    body = solver.analyze(reverted(20, 40, 16, 44, 150.0))
    expected = Fraction(20, 40) * Fraction(16, 44)
    assert body["members"]["d"]["train_value"] == pytest.approx(float(expected), rel=REL)
    assert body["members"]["d"]["omega"] == pytest.approx(150.0 * float(expected), rel=REL)
    assert body["members"]["c"]["omega"] == body["members"]["b"]["omega"]
    assert body["members"]["b"]["omega"] == pytest.approx(-75.0, rel=REL)
    assert body["degrees_of_freedom"] == 1


@given(speed, speed)
@settings(max_examples=40, deadline=None)
def test_differential_carrier_is_the_mean_of_the_side_gears(left: float, right: float) -> None:
    """A differential with equal side gears: omega_C = (omega_L + omega_R) / 2."""
    w = omegas(differential(left, right))
    assert w["C"] == pytest.approx((left + right) / 2.0, rel=REL, abs=1e-12)


def test_fergusons_paradox() -> None:
    """Ferguson's paradox: a planet on the arm meshes with a fixed gear of 20 teeth and three
    gears on the same axis of 20, 21 and 19 teeth; with the arm turned, the 20-tooth gear stands
    still, the 21 turns with the arm (1 - 20/21 = 1/21 of its speed) and the 19 against it
    (1 - 20/19 = -1/19)."""
    gears = {"S": 20, "P": 15, "Q20": 20, "Q21": 21, "Q19": 19}
    doc = {
        "kind": "gear_train",
        "gears": {n: {"teeth": t} for n, t in gears.items()},
        "carriers": ["arm"],
        "mounts": {"P": "arm"},
        "meshes": [["S", "P"], ["P", "Q20"], ["P", "Q21"], ["P", "Q19"]],
        "inputs": {"arm": 2.0, "S": 0.0},
    }
    w = omegas(doc)
    assert w["Q20"] == pytest.approx(0.0, abs=1e-15)
    assert w["Q21"] == pytest.approx(2.0 / 21.0, rel=REL)
    assert w["Q19"] == pytest.approx(-2.0 / 19.0, rel=REL)


def test_two_stage_planetary_is_the_product_of_the_stages() -> None:
    """Two stages with fixed rings in series: e = N_s1/(N_s1+N_r1) x N_s2/(N_s2+N_r2)."""
    body = solver.analyze(two_stage(20, 30, 80, 18, 27, 72, 300.0))
    expected = Fraction(20, 100) * Fraction(18, 90)
    assert body["members"]["c2"]["train_value"] == pytest.approx(float(expected), rel=REL)
    assert body["members"]["c1"]["omega"] == body["members"]["s2"]["omega"]
    assert body["degrees_of_freedom"] == 3


@pytest.mark.parametrize(
    ("doc", "dof"),
    [
        (reverted(20, 40, 16, 44, 1.0), 1),
        (planetary(20, 30, 80, {"sun": 1.0, "ring": 0.0}), 2),
        (differential(1.0, 2.0), 2),
        (two_stage(20, 30, 80, 18, 27, 72, 1.0), 3),
    ],
)
def test_degrees_of_freedom_of_the_textbook_trains(doc: dict, dof: int) -> None:
    """Simple and compound trains 1, a planetary train and a differential 2 (Gruebler for gear
    trains: 3 (n - 1) - 2 j_1 - j_2); two stages with the carrier keyed to the next sun 3, less
    the fixed rings."""
    assert degrees_of_freedom(parse_gear_train(doc)) == dof


def test_willis_relation() -> None:
    """(omega_b - omega_arm)/(omega_a - omega_arm) = -N_a/N_b external, +N_a/N_b internal."""
    assert willis_relation(20, 30, internal=False) == Fraction(-2, 3)
    assert willis_relation(30, 80, internal=True) == Fraction(3, 8)


# --- properties ----------------------------------------------------------------------------------

teeth = st.integers(8, 120)


@given(teeth, teeth, st.floats(-1e3, 1e3, allow_nan=False).filter(lambda x: abs(x) > 1e-6))
@settings(max_examples=40, deadline=None)
def test_a_fixed_carrier_gives_the_ordinary_train(sun: int, planet: int, omega: float) -> None:
    """With the arm held, sun -> ring is an ordinary train through an idler: e = -N_s/N_r, and
    the planet turns at -N_s/N_p."""
    ring = sun + 2 * planet
    w = omegas(planetary(sun, planet, ring, {"sun": omega, "arm": 0.0}))
    assert w["ring"] == pytest.approx(-omega * sun / ring, rel=REL)
    assert w["planet"] == pytest.approx(-omega * sun / planet, rel=REL)


@given(teeth, teeth, st.floats(-1e3, 1e3, allow_nan=False))
@settings(max_examples=40, deadline=None)
def test_a_rigid_train_when_every_input_turns_alike(sun: int, planet: int, omega: float) -> None:
    """Sun and ring at one speed: the whole train turns as one body, every speed relative to the
    arm 0 (the planet's on its carrier, the pitch-line speeds)."""
    ring = sun + 2 * planet
    doc = planetary(sun, planet, ring, {"sun": omega, "ring": omega}, module=0.001)
    body = solver.analyze(doc)
    for member in body["members"].values():
        assert member["omega"] == pytest.approx(omega, rel=REL, abs=1e-12)
    assert body["members"]["planet"]["omega_relative"] == pytest.approx(0.0, abs=1e-12)
    assert [m["pitch_line_speed"] for m in body["meshes"]] == [0.0, 0.0]


@given(teeth, teeth, speed, speed, st.floats(-100, 100))
@settings(max_examples=60, deadline=None)
def test_power_and_torque_balance(
    sun: int, planet: int, w_sun: float, w_ring: float, torque: float
) -> None:
    """Ideal gears: sum T omega = 0 (power), and for this coaxial train sum T = 0 (torque);
    the ring and arm torques are T_s N_r/N_s and -T_s (1 + N_r/N_s) whatever the speeds."""
    ring = sun + 2 * planet
    doc = planetary(sun, planet, ring, {"sun": w_sun, "ring": w_ring})
    members = solver.analyze(doc, input_torque={"sun": torque})["members"]
    scale = abs(torque) * (abs(w_sun) + abs(w_ring) + 1) * (1 + ring / sun)
    assert sum(m["torque"] * m["omega"] for m in members.values()) == pytest.approx(
        0.0, abs=1e-12 * scale
    )
    assert sum(m["torque"] for m in members.values()) == pytest.approx(
        0.0, abs=1e-12 * (1 + abs(torque)) * (1 + ring / sun)
    )
    assert members["ring"]["torque"] == pytest.approx(torque * ring / sun, rel=REL, abs=1e-300)
    assert members["arm"]["torque"] == pytest.approx(
        -torque * (1 + ring / sun), rel=REL, abs=1e-300
    )
    assert members["planet"]["torque"] == 0.0


def test_torques_of_a_compound_train() -> None:
    """Power in = power out through the compound train: T_d = -T_a omega_a / omega_d; the idler
    shaft takes no torque from the world, its two gears pass it on (T_b = -T_c)."""
    members = solver.analyze(reverted(20, 40, 16, 44, 150.0), input_torque={"a": 10.0})["members"]
    assert members["d"]["torque"] == pytest.approx(-10.0 * 40 * 44 / (20 * 16), rel=REL)
    assert members["b"]["torque"] + members["c"]["torque"] == pytest.approx(0.0, abs=1e-12)
    assert members["b"]["torque"] == pytest.approx(10.0 * 40 / 20, rel=REL)
    assert members["a"]["power"] + members["d"]["power"] == pytest.approx(0.0, abs=1e-9)


def test_torques_of_two_stages_and_a_differential() -> None:
    """The first carrier passes its torque to the second sun; the differential splits the
    carrier's torque equally between its side gears."""
    members = solver.analyze(two_stage(20, 30, 80, 18, 27, 72, 300.0), input_torque={"s1": 2.0})[
        "members"
    ]
    assert members["c1"]["torque"] == pytest.approx(-10.0, rel=REL)
    assert members["s2"]["torque"] == pytest.approx(10.0, rel=REL)
    assert members["c2"]["torque"] == pytest.approx(-50.0, rel=REL)
    diff = solver.analyze(differential(30.0, 10.0), input_torque={"L": 4.0})["members"]
    assert diff["R"]["torque"] == pytest.approx(4.0, rel=REL)
    assert diff["C"]["torque"] == pytest.approx(-8.0, rel=REL)


def test_pitch_line_speed_and_relative_speeds() -> None:
    """v = r |omega - omega_arm| is the same on both gears of a mesh: sun 20 teeth on module
    2 mm (r = 20 mm) at 100 rad/s with the arm at 20 rad/s: v = 0.02 x 80 = 1.6 m/s."""
    body = solver.analyze(planetary(20, 30, 80, {"sun": 100.0, "ring": 0.0}, module=0.002))
    assert [m["pitch_line_speed"] for m in body["meshes"]] == [pytest.approx(1.6, rel=REL)] * 2
    assert body["meshes"][0]["pitch_line_speed"] == body["meshes"][1]["pitch_line_speed"]
    planet = body["members"]["planet"]
    assert planet["omega_relative"] == pytest.approx(-80.0 * 20 / 30, rel=REL)
    assert planet["pitch_radius"] == pytest.approx(0.03, rel=REL)
    assert planet["centre"] == pytest.approx([0.05, 0.0], abs=1e-15)
    without = solver.analyze(planetary(20, 30, 80, {"sun": 100.0, "ring": 0.0}))
    assert without["meshes"][0]["pitch_line_speed"] is None
    assert without["members"]["planet"]["centre"] is None


def test_the_train_value_needs_a_turning_first_input() -> None:
    body = solver.analyze(planetary(20, 30, 80, {"ring": 0.0, "sun": 10.0}))
    assert body["first_input"] == "ring"
    assert all(m["train_value"] is None for m in body["members"].values())


def test_results_past_a_float_are_refused_not_infinite() -> None:
    """A first input of 1e-300 rad/s and a ring at 1000 rad/s: the planet's train value would
    be about 1e303, refused rather than answered as a float near overflow."""
    doc = planetary(20, 30, 80, {"sun": 1e-300, "ring": 1000.0})
    with pytest.raises(solver.InvalidScene, match=r"members\.planet\.train_value: about 10\^303"):
        solver.analyze(doc)


def test_sweep_angles_and_planet_centres() -> None:
    """theta = omega t; the planet's centre turns with the arm about the sun's axis."""
    doc = planetary(20, 30, 80, {"sun": 1.0, "ring": 0.0}, module=0.002)
    body = solver.sweep_time(doc, (0.0, 5.0), 11)
    assert list(body["time"]) == pytest.approx([0.5 * k for k in range(11)])
    assert body["members"]["arm"]["angle"][-1] == pytest.approx(1.0, rel=REL)
    assert body["members"]["sun"]["angle"][-1] == pytest.approx(5.0, rel=REL)
    centre = body["members"]["planet"]["centre"]
    assert centre[-1] == pytest.approx([0.05 * 0.5403023058681398, 0.05 * 0.8414709848078965])
    assert "centre" not in body["members"]["sun"]

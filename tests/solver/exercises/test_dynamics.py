"""The dynamics exercise types: the driving torque of a four-bar at an instant and the flywheel
over a cycle. Their keys against independent values (the power balance; the energies and the
load's work over the cycle), the checker's diagnoses, and the Newton-Euler worked solution."""

from __future__ import annotations

import math

import numpy as np
import pytest

import solver
from solver.exercises import DIFFICULTIES, build, parse_id
from solver.exercises.answers import parse_sweep_root
from solver.exercises.checking import check_answers
from solver.exercises.solutions import worked_solution

SEEDS = (3, 11)


@pytest.mark.parametrize("difficulty", DIFFICULTIES)
@pytest.mark.parametrize("seed", SEEDS)
def test_the_torque_key_is_the_power_balance(difficulty: str, seed: int) -> None:
    """The key (Newton-Euler) equals the torque from the power balance, computed without any
    joint force (1e-9 of the largest joint force times the ground link)."""
    exercise = build(parse_id(f"four_bar_torque:{difficulty}:{seed}:0"))
    body = solver.analyze(exercise.scene, ["acceleration", "forces"]).as_dict()
    (driver,) = body["drivers"]
    scale = max(math.hypot(*j["force"]) for j in body["joints"]) * exercise.scene["points"]["D"][0]
    assert exercise.answers["M_crank"] == pytest.approx(
        driver["torque_from_power_balance"], abs=1e-9 * scale
    )
    assert driver["torque"] == exercise.answers["M_crank"]
    if difficulty != "basic":
        assert body["joints"][1]["point"] == "B"
        assert exercise.answers["F_B_x"] == body["joints"][1]["force"][0]


@pytest.mark.parametrize("difficulty", DIFFICULTIES)
@pytest.mark.parametrize("seed", SEEDS)
def test_the_flywheel_key_from_the_energies_and_the_load(difficulty: str, seed: int) -> None:
    """At constant omega, integral of (M - M_mean) d phi = (T + V) - (T + V)_0 - W_load - M_mean
    phi (phi the crank's turn, negative for a clockwise crank): the energy fluctuation from the
    sweep's kinetic and potential energies and the work of the stroke's resisting moment
    (-|M_load| times the rocker's turn while it swings counter-clockwise), without the torque;
    I_F = fluctuation / (k omega^2). 1e-3: the kink of the load law at the rocker's ends,
    sampled at 720 points."""
    exercise = build(parse_id(f"flywheel:{difficulty}:{seed}:0"))
    path = next(a.path for a in exercise.asked if a.key == "flywheel_inertia")
    found = parse_sweep_root(path.split(".")[0])
    assert found is not None
    samples, k = found
    quantities = ["position", "acceleration", "forces", "energy"]
    body = solver.sweep(exercise.scene, samples, quantities, speed_fluctuation=k).as_dict()
    omega = exercise.scene["drivers"][0]["omega"]
    phi = np.unwrap(np.array(body["driver_angle"]))  # the crank's turn, either way
    phi = np.append(phi - phi[0], math.copysign(2 * math.pi, omega))
    energy = np.array(body["energy"]["kinetic"]) + np.array(body["energy"]["potential"])
    energy = np.append(energy - energy[0], 0.0)
    rocker = np.unwrap(np.array(body["links"]["rocker"]["angle"]))
    rocker = np.append(rocker, rocker[0])
    moment = float(exercise.scene["torques"][0]["moment"].split(", ")[1])  # where(c, -M, 0)
    turning = np.diff(rocker)
    work = np.concatenate([[0.0], np.cumsum(np.where(turning > 0, moment * turning, 0.0))])
    mean = body["cycle"]["mean_torque"]
    assert mean * phi[-1] == pytest.approx(-work[-1], rel=1e-3), "mean power = -load work"
    swing = energy - work - mean * phi
    fluctuation = float(swing.max() - swing.min())
    assert exercise.answers["energy_fluctuation"] == pytest.approx(fluctuation, rel=1e-3)
    assert exercise.answers["flywheel_inertia"] == pytest.approx(
        exercise.answers["energy_fluctuation"] / (k * omega**2), rel=1e-12
    )
    if difficulty == "challenging":
        assert exercise.answers["mean_torque"] == mean


def _diagnosis(exercise_id: str, key: str, kind: str) -> None:
    """The wrong value of mistake ``kind`` is recognised, named, and differs from the key."""
    exercise = build(parse_id(exercise_id))
    from solver.exercises.mistakes import typical_mistakes

    (wrong,) = [m.values[key] for m in typical_mistakes(exercise) if m.kind == kind]
    assert abs(wrong - exercise.answers[key]) > 0.05 * abs(exercise.answers[key])
    result = check_answers(exercise, {key: wrong})
    (graded,) = [r for r in result["results"] if r["key"] == key]
    assert graded["verdict"] == "incorrect"
    assert graded["mistake"] == kind and graded["diagnosis"]


def test_the_checker_knows_the_power_balance_without_the_weights() -> None:
    _diagnosis("four_bar_torque:standard:3:0", "M_crank", "weights_left_out")


def test_the_checker_knows_the_static_torque() -> None:
    _diagnosis("four_bar_torque:challenging:3:0", "M_crank", "inertia_left_out")


def test_the_checker_knows_the_mean_torque_for_the_energy_fluctuation() -> None:
    for key in ("energy_fluctuation", "flywheel_inertia"):
        _diagnosis("flywheel:standard:7:0", key, "mean_torque_for_fluctuation")


def test_the_checker_knows_the_flywheel_twice_too_heavy() -> None:
    _diagnosis("flywheel:basic:7:0", "flywheel_inertia", "flywheel_factor_two")


def test_the_worked_solutions_are_newton_euler_and_the_cycle() -> None:
    torque = worked_solution(build(parse_id("four_bar_torque:standard:3:0")))
    kinds = [step["kind"] for step in torque]
    assert any(k.startswith("dynamics.") for k in kinds), kinds
    assert "dynamics.power_balance" in kinds
    exercise = build(parse_id("flywheel:challenging:7:0"))
    steps = worked_solution(exercise)
    last = steps[-1]
    assert last["kind"] == "dynamics.flywheel"
    values = last["values"]
    assert values["flywheel_inertia"]["value"] == exercise.answers["flywheel_inertia"]
    assert values["energy_fluctuation"]["value"] == exercise.answers["energy_fluctuation"]
    assert values["mean_torque"]["value"] == exercise.answers["mean_torque"]

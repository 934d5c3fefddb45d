"""A gear-train scene that breaks the contract is an InvalidScene whose message says what is
wrong with the numbers (issue 25): the inputs against the degrees of freedom, pitch circles that
cannot touch, two internal gears in mesh, a member in two shafts, unknown names, torques that
cannot be in balance or are not fixed by it."""

from __future__ import annotations

import copy
from typing import Any

import pytest

import solver
from tests.solver.gears.test_gears import differential, planetary, reverted

EXAMPLE = planetary(20, 30, 80, {"sun": 100.0, "ring": 0.0}, module=0.002)


def changed(**fields: Any) -> dict[str, Any]:
    doc = copy.deepcopy(EXAMPLE)
    doc.update(fields)
    return doc


def refused(doc: dict[str, Any], *parts: str, **kwargs: Any) -> str:
    with pytest.raises(solver.InvalidScene) as caught:
        solver.analyze(doc, **kwargs)
    for part in parts:
        assert part in caught.value.message, caught.value.message
    return caught.value.message


def test_too_few_and_too_many_inputs_say_how_many() -> None:
    refused(changed(inputs={"sun": 100.0}), "2 degrees of freedom", "needs 2 inputs", "1 is given")
    refused(
        changed(inputs={"sun": 1.0, "ring": 0.0, "arm": 2.0}),
        "2 degrees of freedom",
        "3 are given (sun, ring, arm)",
    )
    refused(reverted(20, 40, 16, 44, 1.0) | {"inputs": {}}, "1 degree of freedom", "needs 1")


def test_inputs_that_do_not_determine_the_train() -> None:
    """Two pairs side by side (2 degrees of freedom): inputs on both gears of one pair leave the
    other pair free."""
    doc = {
        "kind": "gear_train",
        "gears": {n: {"teeth": 20} for n in "abcd"},
        "meshes": [["a", "b"], ["c", "d"]],
        "inputs": {"a": 1.0, "b": -1.0},
    }
    refused(doc, "a, b do not determine the train", "c, d can still turn")


def test_pitch_circles_that_cannot_touch() -> None:
    """A ring of 100 teeth about the sun's axis: the planet would have to be (20 + 30)/2 and
    (100 - 30)/2 modules from it at once."""
    doc = changed()
    doc["gears"]["ring"]["teeth"] = 100
    refused(doc, "meshes[1]", "cannot touch", "0.002 (100 - 30) / 2 = 0.07 m", "0.05 m apart")
    doc["module"] = None
    assert solver.analyze(doc)["members"]["arm"]["omega"] == pytest.approx(100 * 20 / 120)


def test_two_planets_too_far_apart() -> None:
    doc = differential(1.0, 2.0)
    doc["gears"]["L"]["teeth"] = 60  # P1 45 modules/2 out, P2 15: 10 apart at most... no triangle
    refused(doc, "meshes[1]", "no point is", "cannot touch")


def test_a_mesh_on_one_axis() -> None:
    doc = changed(meshes=[["sun", "planet"], ["planet", "ring"], ["sun", "ring"]])
    refused(doc, "meshes[2]", "sun and ring turn about one axis (with arm)", "cannot touch")


def test_two_internal_gears_and_a_small_annulus() -> None:
    doc = changed()
    doc["gears"]["planet"]["internal"] = True
    refused(doc, "meshes[1]", "planet and ring are both internal gears")
    doc = changed()
    doc["gears"]["ring"]["teeth"] = 30
    refused(doc, "meshes[1]", "annulus ring (30 teeth)", "planet (30 teeth)")


def test_a_member_in_two_shafts_and_shafts_across_axes() -> None:
    doc = reverted(20, 40, 16, 44, 1.0)
    doc["shafts"] = [["b", "c"], ["c", "d"]]
    refused(doc, "shafts[1]", "c is already in shafts[0]")
    refused(changed(shafts=[["sun", "planet"]]), "shafts[0]", "planet on carrier arm")


@pytest.mark.parametrize(
    ("fields", "parts"),
    [
        ({"meshes": [["sun", "planet"], ["planet", "moon"]]}, ("meshes[1]", "'moon' is not")),
        ({"mounts": {"planet": "cage"}}, ("mounts.planet", "'cage' is not a carrier")),
        ({"mounts": {"comet": "arm"}}, ("mounts", "'comet' is not a gear")),
        ({"inputs": {"sun": 1.0, "moon": 0.0}}, ("inputs", "'moon' is not a member")),
        ({"shafts": [["sun", "x"]]}, ("shafts[0]", "'x' is not a member")),
        ({"meshes": [["sun", "arm"]]}, ("meshes[0]", "arm is a carrier")),
        ({"meshes": [["sun", "planet"], ["planet", "sun"]]}, ("meshes[1]", "already mesh")),
        ({"inputs": {"sun": float("nan"), "ring": 0}}, ("inputs.sun", "finite")),
        ({"module": -1}, ("module", "-1")),
        ({"carriers": ["arm", "arm"]}, ("carriers", "twice")),
    ],
)
def test_unknown_names_and_bad_values(fields: dict[str, Any], parts: tuple[str, ...]) -> None:
    refused(changed(**fields), *parts)


def test_teeth_are_whole_numbers() -> None:
    doc = changed()
    doc["gears"]["sun"]["teeth"] = 20.5
    refused(doc, "gears.sun.teeth", "20.5")
    doc["gears"]["sun"]["teeth"] = 20.0  # a whole number written as a float is read as one
    assert solver.analyze(doc)["members"]["sun"]["teeth"] == 20


def test_torques_not_on_an_input_unbalanced_or_not_fixed() -> None:
    refused(EXAMPLE, "'arm' is not an input", input_torque={"arm": 1.0})
    refused(EXAMPLE, "input_torque.sun", input_torque={"sun": float("inf")})
    refused(differential(3.0, 1.0), "cannot be in balance", input_torque={"L": 4.0, "R": 5.0})
    both = solver.analyze(differential(3.0, 1.0), input_torque={"L": 4.0, "R": 4.0})
    assert both["members"]["C"]["torque"] == pytest.approx(-8.0, rel=1e-12)
    ferguson = {
        "kind": "gear_train",
        "gears": {n: {"teeth": t} for n, t in {"S": 20, "P": 15, "Q": 21, "U": 19}.items()},
        "carriers": ["arm"],
        "mounts": {"P": "arm"},
        "meshes": [["S", "P"], ["P", "Q"], ["P", "U"]],
        "inputs": {"arm": 2.0, "S": 0.0},
    }
    refused(ferguson, "do not fix the torques", input_torque={"arm": 1.0})


def test_the_other_endpoints_say_what_a_gear_train_takes() -> None:
    with pytest.raises(solver.InvalidScene, match="time range"):
        solver.sweep(EXAMPLE)
    assert solver.solve(EXAMPLE)["method"] == "tabular"  # the worked solution is written now
    with pytest.raises(solver.InvalidScene, match="t1 > t0"):
        solver.sweep_time(EXAMPLE, (1.0, 1.0), 10)
    with pytest.raises(solver.LimitExceeded, match="samples"):
        solver.sweep_time(EXAMPLE, (0.0, 1.0), 1)
    linkage = {"kind": "linkage"}
    with pytest.raises(solver.InvalidScene):
        solver.analyze(linkage, input_torque={"a": 1.0})


def test_unknown_keys_are_warnings_or_strict_errors() -> None:
    doc = changed(modul=0.002)
    assert solver.analyze(doc).warnings == ("modul is not a scene field; did you mean module?",)
    doc = changed()
    doc["gears"]["sun"]["teth"] = 3
    with pytest.raises(solver.InvalidScene, match=r"strict: gears\.sun\.teth"):
        solver.analyze(doc, strict=True)

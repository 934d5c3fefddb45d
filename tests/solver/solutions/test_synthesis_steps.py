"""The worked solution of a synthesis (issue 26): every step's shown arithmetic recomputes from its
shown digits (the independent checker of test_solve), the numbers are the synthesis body's, and
the first step carries the construction's figure as a standalone SVG."""

from __future__ import annotations

import math
import xml.etree.ElementTree as ET
from typing import Any

import pytest

import solver
from tests.solver.solutions.test_solve import unit_floors, verify

TASKS: dict[str, dict[str, Any]] = {
    "three positions": {
        "task": "motion",
        "positions": [
            {"point": [0, 0], "angle_deg": 0},
            {"point": [1, 0.5], "angle_deg": 30},
            {"point": [2, 0.3], "angle_deg": 60},
        ],
        "moving_pivots": [[-0.5, -0.2], [0.5, -0.3]],
    },
    "two positions, fixed pivots": {
        "task": "motion",
        "positions": [{"point": [0, 0], "angle_deg": 0}, {"point": [1, 0.5], "angle_deg": 30}],
        "fixed_pivots": [[-0.5, -1.2], [1.5, -1.3]],
    },
    "two positions, bisector offsets": {
        "task": "motion",
        "positions": [{"point": [0, 0], "angle_deg": 0}, {"point": [1, 0.2], "angle_deg": 25}],
        "moving_pivots": [[-0.4, 0.1], [0.5, 0.2]],
        "bisector_offsets": [0.7, -0.3],
    },
    "function": {
        "task": "function",
        "function": "log(x)",
        "x_range": [1, 3],
        "input_range_deg": [40, 130],
        "output_range_deg": [70, 140],
    },
    "quick return": {
        "task": "quick_return",
        "time_ratio": 1.4,
        "rocker_length": 0.2,
        "swing_deg": 50,
    },
}


@pytest.mark.parametrize("name", TASKS)
def test_the_shown_arithmetic_recomputes(name: str) -> None:
    body = solver.synthesize(TASKS[name]).as_dict()
    steps = body["steps"]
    assert len(steps) >= 4
    floors = unit_floors(steps)
    for step in steps:
        assert step["kind"].startswith("synthesis.")
        assert step["title"] and step["text"]
        assert verify(step, floors) == [], step["title"]
    assert steps[-1]["title"] == "Checks by analysis of the synthesised linkage"
    figure = ET.fromstring(steps[0]["figure"])
    assert figure.tag == "{http://www.w3.org/2000/svg}svg"
    assert all("figure" not in step for step in steps[1:])


def test_the_steps_show_the_bodys_numbers() -> None:
    body = solver.synthesize(TASKS["function"]).as_dict()
    step = next(s for s in body["steps"] if s["title"].startswith("Freudenstein"))
    for k in ("K1", "K2", "K3"):
        assert step["values"][k]["value"] == body["freudenstein"][k]
    assert step["latex"].count("K_3 =") == 3  # one equation per precision point
    motion = solver.synthesize(TASKS["three positions"]).as_dict()
    centre = next(s for s in motion["steps"] if s["title"].startswith("The centre point A"))
    assert centre["values"]["A"]["value"] == motion["scene"]["points"]["A"]


@pytest.mark.parametrize("name", TASKS)
def test_a_check_off_by_rounding_noise_reads_zero(name: str) -> None:
    """'off by 1.665 x 10^-16' was float noise: an error within 1e-11 of the linkage's size (the
    diagonal of its points' bounding box) reads 0, a larger one its digits."""
    body = solver.synthesize(TASKS[name]).as_dict()
    (step,) = [s for s in body["steps"] if s["kind"] == "synthesis.checks"]
    xy = [tuple(p) for p in body["scene"]["points"].values()]
    size = math.dist(*(tuple(f(c) for c in zip(*xy, strict=True)) for f in (min, max)))
    for k, check in enumerate(body["checks"], start=1):
        display = step["values"][f"error {k}"]["display"]
        assert (display == "0") == (check["error"] <= 1e-11 * size), (display, check["error"])
    assert "10^-" not in step["text"]

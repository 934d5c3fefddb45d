"""The polygons as data (solver.solutions.polygons): image segments in the worked solution's order.

Every segment must close its triangle with the solver's own absolute vectors (v_P - v_B and
a_P - a_B, to 1e-12 of the largest vector of the instant), its normal part must point from P
towards B and its tangential part across the link; where the worked solution writes the same
parts, they are its numbers; and the segments come in the order the solution's steps take them.
"""

from __future__ import annotations

import json
from pathlib import Path
from typing import Any

import numpy as np
import pytest

import solver
from solver.teaching.presets import PRESETS, build_preset

EXAMPLES = Path(__file__).resolve().parents[3] / "server" / "examples"
SCENES = {f"preset {name}": build_preset(name, {}) for name in PRESETS} | {
    path.stem: json.loads(path.read_text())
    for path in sorted(EXAMPLES.glob("*.json"))
    if json.loads(path.read_text())["kind"] == "linkage"
}


def vec(value: Any) -> np.ndarray:
    return np.asarray(value, dtype=float)


@pytest.mark.parametrize("name", sorted(SCENES))
def test_segments_close_with_the_solvers_vectors(name: str) -> None:
    solution = solver.solve(SCENES[name], "loop")  # polygons follow the vector method anyway
    points = solution["results"]["points"]
    size = max(
        float(np.linalg.norm(vec(p[k])))
        for p in points.values()
        for k in ("velocity", "acceleration")
    )
    tolerance = 1e-12 * max(size, 1.0)
    segments = solution["polygons"]["segments"]
    assert segments, name
    for s in segments:
        B, P = points[s["base"]], points[s["point"]]
        r = vec(P["position"]) - vec(B["position"])
        v_rel, normal, tangential = vec(s["velocity"]), vec(s["normal"]), vec(s["tangential"])
        np.testing.assert_allclose(v_rel, vec(P["velocity"]) - vec(B["velocity"]), atol=tolerance)
        np.testing.assert_allclose(
            normal + tangential, vec(P["acceleration"]) - vec(B["acceleration"]), atol=tolerance
        )
        assert float(normal @ r) <= tolerance * float(np.linalg.norm(r))  # towards B
        assert abs(float(tangential @ r)) <= tolerance * float(np.linalg.norm(r))  # across


@pytest.mark.parametrize("name", sorted(SCENES))
def test_segments_are_the_worked_solutions(name: str) -> None:
    """Same base points, same numbers, same order as the vector method's acceleration steps."""
    solution = solver.solve(SCENES[name], "vector")
    steps = [s for s in solution["steps"] if s["kind"].startswith("acceleration.")]
    first_step = []
    for s in solution["polygons"]["segments"]:
        key = f"normal({s['base']},{s['point']})"
        where = [i for i, step in enumerate(steps) if key in step["values"]]
        assert where, key
        first_step.append(where[0])
        for step in steps:
            values = step["values"]
            if key in values:
                assert s["normal"] == pytest.approx(values[key]["value"], rel=1e-12, abs=1e-12)
            tangential = f"alpha x r({s['base']},{s['point']})"
            if tangential in values:
                assert s["tangential"] == pytest.approx(
                    values[tangential]["value"], rel=1e-12, abs=1e-12
                )
    assert first_step == sorted(first_step)


def test_the_coriolis_parts_are_named_in_the_solutions_order() -> None:
    solution = solver.solve(build_preset("quick_return", {}))
    assert solution["polygons"]["sliding"] == (("joints", 0), ("joints", 1))
    for owner, index in solution["polygons"]["sliding"]:
        assert "coriolis_acceleration" in solution["results"][owner][index]


def test_a_spatial_chain_has_no_polygons() -> None:
    doc = json.loads((EXAMPLES / "S002-spatial-arm.json").read_text())
    assert "polygons" not in solver.solve(doc)

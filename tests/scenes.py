"""Scenes shared by the solver's and the server's tests (and the budget's benchmark)."""

from __future__ import annotations

from typing import Any

from tests.solver.position.test_newton import TRIAD


def triads(count: int) -> dict[str, Any]:
    """``count`` copies of the triad of tests/solver/position/test_newton.py hung from one crank
    pin A: one Newton-Raphson group of 4 x count links."""
    points: dict[str, list[float]] = {"O": [0, 0], "A": [0.3, 0.2]}
    links: dict[str, Any] = {"crank": {"points": ["O", "A"]}}
    ground = ["O"]
    joints = [{"type": "revolute", "point": "O", "links": ["ground", "crank"]}]
    for i in range(count):
        n = {p: f"{p}_{i}" for p in ("P1", "P2", "P3", "G2", "G3", "T", "L1", "L2", "L3")}
        for p in ("P1", "P2", "P3", "G2", "G3"):
            x, y = TRIAD["points"][p]
            points[n[p]] = [x, y + 3.0 * i]
        ground += [n["G2"], n["G3"]]
        links[n["T"]] = {"points": [n["P1"], n["P2"], n["P3"]]}
        links[n["L1"]] = {"points": ["A", n["P1"]]}
        links[n["L2"]] = {"points": [n["G2"], n["P2"]]}
        links[n["L3"]] = {"points": [n["G3"], n["P3"]]}
        for point, pair in (
            ("A", ("crank", "L1")),
            ("P1", ("L1", "T")),
            ("P2", ("T", "L2")),
            ("P3", ("T", "L3")),
            ("G2", ("L2", "ground")),
            ("G3", ("L3", "ground")),
        ):
            named = [n.get(link, link) for link in pair]
            joints.append({"type": "revolute", "point": n.get(point, point), "links": named})
    links["ground"] = {"points": ground, "ground": True}
    return {
        "kind": "linkage",
        "points": points,
        "links": links,
        "joints": joints,
        "drivers": [{"link": "crank", "omega": 2.0, "alpha": 0.5}],
    }

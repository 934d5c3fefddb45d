"""Scenes with masses and loads for the dynamics tests: seed 004 as its reference file describes
it, and a Hypothesis strategy that puts random masses, gravity and loads on random linkages.

Seed 004 (tests/reference/seed004-dynamics.json): crank O-A, coupler A-B, member 3 Gamma-B-D
(a uniform bar Gamma->D with a point mass at D), driven at 240 rpm. The seed measures phi3 from +y
clockwise, so phi3 = pi/2 - angle("rocker"); its force F_D acts at D perpendicular to Gamma-D
(90 degrees from the rocker's direction), with magnitude F_max (phi3 - phi3_c) / (phi3_min -
phi3_c) while phi3 decreases between phi3_c = -10 deg and phi3_min, else 0.
"""

from __future__ import annotations

import copy
import json
import math
from pathlib import Path
from typing import Any

from hypothesis import strategies as st

REFERENCE = Path(__file__).resolve().parent / "reference" / "seed004-dynamics.json"
SEED004 = json.loads(REFERENCE.read_text())
EXPECTED: dict[str, Any] = SEED004["expected"]


def seed004_scene(angle_deg: float | None = None) -> dict[str, Any]:
    """The seed 004 scene, drawn at theta = 0, analysed at ``angle_deg`` of the crank."""
    data = SEED004["input"]
    phi3_min = math.radians(EXPECTED["phi3_min_deg"]["value"])
    phi3_c = math.radians(data["force_D"]["phi3_c_deg"])
    phi3 = 'pi/2 - angle("rocker")'
    law = (
        f'where(omega("rocker") >= 0 and {phi3} < {phi3_c!r} and {phi3} > {phi3_min!r}, '
        f"{data['force_D']['F_max']!r}*({phi3} - {phi3_c!r})/({phi3_min!r} - {phi3_c!r}), 0)"
    )
    driver: dict[str, Any] = {
        "link": "crank",
        "omega": data["crank_speed_rpm"] * 2 * math.pi / 60,
        "alpha": 0.0,
    }
    if angle_deg is not None:
        driver["angle_deg"] = angle_deg
    return {
        "kind": "linkage",
        "title": "seed 004",
        "points": {
            "O": [0.0, 0.0],
            "A": [data["l1"], 0.0],
            "B": EXPECTED["theta=0deg/r_B"]["value"],
            "Gamma": [data["l"], 0.0],
            "D": EXPECTED["theta=0deg/r_D"]["value"],
        },
        "links": {
            "ground": {"points": ["O", "Gamma"], "ground": True},
            "crank": {"points": ["O", "A"]},
            "coupler": {"points": ["A", "B"]},
            "rocker": {"points": ["Gamma", "B", "D"]},
        },
        "joints": [
            {"type": "revolute", "point": "O", "links": ["ground", "crank"]},
            {"type": "revolute", "point": "A", "links": ["crank", "coupler"]},
            {"type": "revolute", "point": "B", "links": ["coupler", "rocker"]},
            {"type": "revolute", "point": "Gamma", "links": ["ground", "rocker"]},
        ],
        "drivers": [driver],
        "masses": {
            "crank": {"mass": data["m1"], "bar": ["O", "A"]},
            "coupler": {"mass": data["m2"], "bar": ["A", "B"]},
            "rocker": {"mass": data["m3"], "bar": ["Gamma", "D"]},
        },
        "point_masses": [{"name": "mD", "link": "rocker", "point": "D", "mass": data["mD"]}],
        "gravity": [0.0, -data["g"]],
        "forces": [
            {
                "name": "F_D",
                "link": "rocker",
                "point": "D",
                "magnitude": law,
                "direction_deg": 90,
                "relative_to": "link",
            }
        ],
    }


@st.composite
def with_masses_and_loads(draw: st.DrawFn, doc: dict[str, Any]) -> dict[str, Any]:
    """``doc`` with a random body on every moving link (a bar or a centre with an inertia), a
    point mass, gravity, a force (world or link direction) whose magnitude depends on the state,
    and a moment. The load laws are written so that ``load_values`` can recompute them."""
    doc = copy.deepcopy(doc)
    points = doc["points"]
    xy = [p for p in points.values()]
    size = max(math.dist(p, q) for p in xy for q in xy) or 1.0
    moving = [name for name, link in doc["links"].items() if not link.get("ground")]
    angled = [name for name in moving if len(doc["links"][name]["points"]) >= 2]
    masses: dict[str, Any] = {}
    for name in moving:
        on = doc["links"][name]["points"]
        mass = draw(st.floats(0.1, 50.0))
        if len(on) >= 2 and draw(st.booleans()):
            masses[name] = {"mass": mass, "bar": [on[0], on[1]]}
        else:
            cx, cy = points[on[0]]
            masses[name] = {
                "mass": mass,
                "center": [cx + size * draw(st.floats(-1, 1)), cy + size * draw(st.floats(-1, 1))],
                "inertia": mass * size**2 * draw(st.floats(0.0, 0.3)),
            }
    doc["masses"] = masses
    carrier = draw(st.sampled_from(moving))
    doc["point_masses"] = [
        {
            "name": "m_p",
            "link": carrier,
            "point": draw(st.sampled_from(doc["links"][carrier]["points"])),
            "mass": draw(st.floats(0.0, 20.0)),
        }
    ]
    doc["gravity"] = [draw(st.floats(-10, 10)), draw(st.floats(-10, 10))]
    loaded = draw(st.sampled_from(angled))
    c = [draw(st.floats(-100, 100)) for _ in range(3)]
    relative = draw(st.sampled_from(["world", "link"]))
    doc["forces"] = [
        {
            "name": "F",
            "link": loaded,
            "point": draw(st.sampled_from(doc["links"][loaded]["points"])),
            "magnitude": f'{c[0]!r} + {c[1]!r}*cos(angle("{loaded}")) + {c[2]!r}*omega("{loaded}")',
            "direction_deg": draw(st.floats(-180, 180)),
            "relative_to": relative,
        }
    ]
    turned = draw(st.sampled_from(moving))
    k = draw(st.floats(-50, 50))
    doc["torques"] = [{"name": "M", "link": turned, "moment": f"{k!r}*sin(3*t) + 10"}]
    return doc


def force_vector(doc: dict[str, Any], links: dict[str, Any]) -> tuple[float, float]:
    """The random force of ``with_masses_and_loads`` from an /analyze body's links (recomputed
    here from the law's coefficients, independently of the solver's expression evaluator)."""
    force = doc["forces"][0]
    terms = force["magnitude"].split(" + ")
    c0 = float(terms[0])
    c1 = float(terms[1].split("*")[0])
    c2 = float(terms[2].split("*")[0])
    link = links[force["link"]]
    magnitude = c0 + c1 * math.cos(link["angle"]) + c2 * link["omega"]
    direction = math.radians(force["direction_deg"])
    if force["relative_to"] == "link":
        direction += link["angle"]
    return magnitude * math.cos(direction), magnitude * math.sin(direction)


def five_bar_topology() -> dict[str, Any]:
    """The five-bar's links and joints, a fresh copy: cranks O1-A and O2-B, the dyad A-C-B
    (``left``, ``right``)."""
    return {
        "links": {
            "ground": {"points": ["O1", "O2"], "ground": True},
            "crank1": {"points": ["O1", "A"]},
            "crank2": {"points": ["O2", "B"]},
            "left": {"points": ["A", "C"]},
            "right": {"points": ["B", "C"]},
        },
        "joints": [
            {"type": "revolute", "point": "O1", "links": ["ground", "crank1"]},
            {"type": "revolute", "point": "O2", "links": ["ground", "crank2"]},
            {"type": "revolute", "point": "A", "links": ["crank1", "left"]},
            {"type": "revolute", "point": "B", "links": ["crank2", "right"]},
            {"type": "revolute", "point": "C", "links": ["left", "right"]},
        ],
    }


def five_bar_points() -> dict[str, list[float]]:
    """A five-bar drawn off any symmetry (cranks O1-A and O2-B, dyad A-C-B), a fresh copy."""
    return {
        "O1": [0.0, 0.0],
        "O2": [1.2, 0.0],
        "A": [0.2, 0.45],
        "B": [1.5, 0.4],
        "C": [0.9, 1.1],
    }


@st.composite
def five_bars(draw: st.DrawFn) -> dict[str, Any]:
    """A five-bar with two driven cranks, O1-A and O2-B, and the dyad A-C-B (links ``left`` =
    [A, C], ``right`` = [B, C]), drawn posed, the triangle ACB kept away from flat, both cranks at
    random omega and alpha: two degrees of freedom."""
    d = draw(st.floats(0.5, 2.0))
    r1, r2 = draw(st.floats(0.2, 1.0)), draw(st.floats(0.2, 1.0))
    t1, t2 = draw(st.floats(-math.pi, math.pi)), draw(st.floats(-math.pi, math.pi))
    A = complex(r1 * math.cos(t1), r1 * math.sin(t1))
    B = complex(d + r2 * math.cos(t2), r2 * math.sin(t2))
    span = abs(B - A)
    if span < 0.1:
        A, B = A - 0.1, B + 0.1
    C = (A + B) / 2 + (B - A) * 1j * draw(st.sampled_from([-1, 1])) * draw(st.floats(0.3, 1.0))

    def rate(largest: float) -> float:
        value = draw(st.floats(0.5, largest)) * draw(st.sampled_from([-1, 1]))
        return float(value)

    def xy(z: complex) -> list[float]:
        return [z.real, z.imag]

    return {
        "kind": "linkage",
        "points": {"O1": [0.0, 0.0], "O2": [d, 0.0], "A": xy(A), "B": xy(B), "C": xy(C)},
        **five_bar_topology(),
        "drivers": [
            {"link": "crank1", "omega": rate(20.0), "alpha": rate(50.0)},
            {"link": "crank2", "omega": rate(20.0), "alpha": rate(50.0)},
        ],
    }


def square_five_bar(omega: float, mass: float, g: float) -> dict[str, Any]:
    """Cranks O1-A and O2-B upright (length 1, 2 m apart), the dyad's pin C at (1, 2) carrying a
    point mass: both cranks at the same omega, so the dyad's links translate."""
    return {
        "kind": "linkage",
        "points": {"O1": [0, 0], "O2": [2, 0], "A": [0, 1], "B": [2, 1], "C": [1, 2]},
        **five_bar_topology(),
        "drivers": [{"link": "crank1", "omega": omega}, {"link": "crank2", "omega": omega}],
        "point_masses": [{"name": "mC", "link": "left", "point": "C", "mass": mass}],
        "gravity": [0, -g],
    }

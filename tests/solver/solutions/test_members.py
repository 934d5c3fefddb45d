"""Two- and three-force members in the worked force analysis (``solver.solutions.members``,
docs/DYNAMICS.md "Two- and three-force members"): a four-bar whose massless coupler is loaded
only at its pins carries S along AB, the magnitude found by hand from the rocker's moments about
its pivot and the crank's torque from the crank's moments about O; the rocker loaded at D is a
three-force member whose meeting point is where the solver's joint forces' lines cross; a
coupler with a weight or a load is not a two-force member; with friction at the pins the line
is tangent to the friction circles."""

from __future__ import annotations

import math
from functools import cache
from typing import Any

import numpy as np
import pytest

import solver
from solver.api import parse_scene, solve
from tests.solver.dynamics.test_statics import F, L, R, slider_crank
from tests.solver.solutions.test_solve import unit_floors, verify

CRANK, COUPLER, ROCKER, GROUND, EXTENSION = 0.3, 1.0, 0.8, 1.0, 1.2
P_D, DIRECTION = 100.0, 30.0  # the load at D (N) and its direction (deg)


def _cross(u: Any, v: Any) -> float:
    return float(u[0] * v[1] - u[1] * v[0])


@cache
def four_bar(theta_deg: float = 60.0) -> dict[str, Any]:
    """Crank O-A, coupler A-B, rocker C-B-D (D on CB produced, |CD| = 1.2 |CB|), driven at 2
    rad/s, the force P_D at D at 30 deg; no masses."""
    th = math.radians(theta_deg)
    A = np.array([CRANK * math.cos(th), CRANK * math.sin(th)])
    C = np.array([GROUND, 0.0])
    d = float(np.hypot(*(C - A)))
    along = (COUPLER**2 - ROCKER**2 + d * d) / (2 * d)
    e = (C - A) / d
    B = A + along * e + math.sqrt(COUPLER**2 - along**2) * np.array([-e[1], e[0]])
    D = C + EXTENSION * (B - C)
    revolute = [("O", "ground", "crank"), ("A", "crank", "coupler"), ("B", "coupler", "rocker"),
                ("C", "ground", "rocker")]  # fmt: skip
    return {
        "kind": "linkage",
        "points": {
            "O": [0.0, 0.0],
            "A": A.tolist(),
            "B": B.tolist(),
            "C": C.tolist(),
            "D": D.tolist(),
        },
        "links": {
            "ground": {"points": ["O", "C"], "ground": True},
            "crank": {"points": ["O", "A"]},
            "coupler": {"points": ["A", "B"]},
            "rocker": {"points": ["C", "B", "D"]},
        },
        "joints": [{"type": "revolute", "point": p, "links": [a, b]} for p, a, b in revolute],
        "drivers": [{"link": "crank", "omega": 2.0}],
        "forces": [
            {
                "name": "F_D",
                "link": "rocker",
                "point": "D",
                "direction_deg": DIRECTION,
                "magnitude": P_D,
            }
        ],
    }


def worked(doc: dict[str, Any], method: str = "statics") -> dict[str, Any]:
    """The worked solution, every step's checks re-evaluated."""
    body: dict[str, Any] = solve(parse_scene(doc), method).as_dict()
    floors = unit_floors(body["steps"])
    for step in body["steps"]:
        assert not verify(step, floors), (step["title"], verify(step, floors)[:3])
    return body


def steps_of(body: dict[str, Any], kind: str) -> dict[str, dict[str, Any]]:
    """The steps of ``kind`` by their link (the title's first word)."""
    return {s["title"].split(":")[0]: s for s in body["steps"] if s["kind"] == kind}


def value(step: dict[str, Any], key: str) -> Any:
    return np.array(step["values"][key]["value"])


@pytest.mark.parametrize("method", ["statics", "newton_euler"])
@pytest.mark.parametrize("theta_deg", [60.0, 200.0])
def test_a_massless_coupler_is_a_two_force_member(method: str, theta_deg: float) -> None:
    """S along AB by hand: the rocker's moments about C, M_D + (B - C) x (-S e_AB) = 0, give S;
    the crank's about O, T + (A - O) x (S e_AB) = 0, give T (1e-9 relative). Massless links have
    no inertia: statics and dynamics agree."""
    doc = four_bar(theta_deg)
    p = {k: np.array(v) for k, v in doc["points"].items()}
    e = (p["B"] - p["A"]) / np.hypot(*(p["B"] - p["A"]))
    load = P_D * np.array([math.cos(math.radians(DIRECTION)), math.sin(math.radians(DIRECTION))])
    S = _cross(p["D"] - p["C"], load) / _cross(p["B"] - p["C"], e)
    T = -S * _cross(p["A"], e)
    body = worked(doc, method)
    two = steps_of(body, "dynamics.two_force")
    assert list(two) == ["coupler"]
    step = two["coupler"]
    assert value(step, "S(coupler)") == pytest.approx(S, rel=1e-9)
    assert value(step, "e(A,B)") == pytest.approx(e, rel=1e-12)
    assert "a two-force member" in step["text"] and "F(B) = -F(A) = S e(A,B)" in step["text"]
    (solution,) = [s for s in body["steps"] if s["kind"] == "dynamics.solution"]
    assert solution["values"]["M_crank"]["value"] == pytest.approx(T, rel=1e-9)
    # the free body draws one unknown S along AB (tension: +e at B, -e at A)
    (free,) = [s for s in body["steps"] if s["title"] == "Free-body diagram of coupler"]
    unknowns = free["diagram"]["unknowns"]
    assert [u["name"] for u in unknowns] == ["S_AB", "S_AB"]
    for u in unknowns:
        assert u["value"] == pytest.approx(S, rel=1e-9)
        assert np.array(u["sense"]) == pytest.approx(e if u["at"] == list(p["B"]) else -e)


def _meeting_point(at: list[np.ndarray], forces: list[np.ndarray]) -> np.ndarray:
    """Where the lines at[0] + t forces[0] and at[1] + s forces[1] cross."""
    t = _cross(at[1] - at[0], forces[1]) / _cross(forces[0], forces[1])
    return at[0] + t * forces[0]


def test_the_loaded_rocker_is_a_three_force_member() -> None:
    """Its meeting point K is where the lines of the solver's forces at B and C cross (from
    /analyze with statics, 1e-9 of the size), the load's line runs through it too, and the
    force triangle's magnitudes are the solver's forces along their directions."""
    doc = four_bar()
    step = steps_of(worked(doc), "dynamics.three_force")["rocker"]
    answer = solver.analyze(parse_scene(doc), ["forces"], statics=True).as_dict()
    joints = {j["point"]: np.array(j["force"]) for j in answer["joints"]}
    p = {k: np.array(v) for k, v in doc["points"].items()}
    on_rocker = [-joints["B"], joints["C"]]  # B: coupler on rocker; C: ground on rocker
    K = _meeting_point([p["B"], p["C"]], on_rocker)
    assert value(step, "K(rocker)") == pytest.approx(K, abs=1e-9)
    load = P_D * np.array([math.cos(math.radians(DIRECTION)), math.sin(math.radians(DIRECTION))])
    assert abs(_cross(p["D"] - K, load)) <= 1e-9 * P_D
    u_C = (K - p["C"]) / np.hypot(*(K - p["C"]))
    assert value(step, "s(F_C)") == pytest.approx(float(on_rocker[1] @ u_C), rel=1e-9)
    assert "the force triangle then gives the magnitudes" in step["text"]


def test_no_two_force_member_with_a_weight_or_a_load() -> None:
    """The coupler with a weight (statics, gravity) is a three-force member (its pins and its
    weight, their lines meeting at one point), not a two-force member; with a load and a moment
    on it, neither (it carries a couple)."""
    heavy = four_bar() | {"masses": {"coupler": {"mass": 5.0, "bar": ["A", "B"]}},
                          "gravity": [0, -9.81]}  # fmt: skip
    body = worked(heavy)
    assert "coupler" not in steps_of(body, "dynamics.two_force")
    three = steps_of(body, "dynamics.three_force")["coupler"]
    answer = solver.analyze(parse_scene(heavy), ["forces"], statics=True).as_dict()
    joints = {j["point"]: np.array(j["force"]) for j in answer["joints"]}
    p = {k: np.array(v) for k, v in heavy["points"].items()}
    K = _meeting_point([p["A"], p["B"]], [joints["A"], -joints["B"]])
    assert value(three, "K(coupler)") == pytest.approx(K, abs=1e-9)
    G = (p["A"] + p["B"]) / 2
    assert abs(K[0] - G[0]) <= 1e-9  # the weight's vertical line through G
    loaded = four_bar() | {
        "forces": [*four_bar()["forces"], {"name": "Q", "link": "coupler", "point": "A",
                                           "direction_deg": 90, "magnitude": 10}],
        "torques": [{"name": "M_c", "link": "coupler", "moment": "5"}],
    }  # fmt: skip
    body = worked(loaded)
    assert "coupler" not in steps_of(body, "dynamics.two_force")
    assert "coupler" not in steps_of(body, "dynamics.three_force")


def test_with_pin_friction_the_line_is_tangent_to_the_friction_circles() -> None:
    """mu = 0.2, r = 0.01 m at A and B: the coupler's forces are still equal and opposite, and
    their line lies mu r = 2 mm off each pin centre (the friction circle)."""
    doc = four_bar()
    friction = {"coefficient": 0.2, "pin_radius": 0.01}
    doc = doc | {"joints": [j | {"friction": friction} if j["point"] in "AB" else j
                            for j in doc["joints"]]}  # fmt: skip
    step = steps_of(worked(doc), "dynamics.two_force")["coupler"]
    assert value(step, "F(A) + F(B)") == pytest.approx(np.zeros(2), abs=1e-9)
    for pin in "AB":
        assert abs(float(value(step, f"d({pin})"))) == pytest.approx(0.2 * 0.01, rel=1e-9)
    assert "tangent to each friction circle" in step["text"]


@pytest.mark.parametrize("theta_deg", [30.0, 120.0, 250.0])
def test_the_slider_cranks_rod_meets_at_the_slider(theta_deg: float) -> None:
    """The rod of ``slider_crank`` (pin A, the slot's N at B, the load -F x at B) is a
    three-force member meeting at B: the force at A runs along AB, s(F_A) = F / cos beta along
    u = (B - A) / |AB| and |s(N_B)| = F tan beta, the closed forms (1e-9 relative)."""
    doc = slider_crank(theta_deg)
    step = steps_of(worked(doc), "dynamics.three_force")["rod"]
    beta = math.asin(R * math.sin(math.radians(theta_deg)) / L)
    assert value(step, "K(rod)") == pytest.approx(np.array(doc["points"]["B"]), abs=1e-12)
    assert float(value(step, "s(F_A)")) == pytest.approx(F / math.cos(beta), rel=1e-9)
    assert abs(float(value(step, "s(N_B)"))) == pytest.approx(F * abs(math.tan(beta)), rel=1e-9)

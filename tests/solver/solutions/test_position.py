"""The position analysis derived for every group of the solver's plan.

Every preset and seed example, both methods: each group has its `position.*` step (a crank, a
triangle, a slider on a fixed guide, a pin in a moving slot, a slotted lever, a Newton group),
and in the loop method each loop has its closed form (`position.loop`). The closed forms are
recomputed here from the numbers they show, independently of `solver.solutions`, and must give the
solver's angles to 1e-12: the four-bar's theta14 = delta +- acos(C / sqrt(A^2 + B^2)) with
A = 2 a4 d_x, B = 2 a4 d_y, C = a3^2 - a4^2 - |d|^2 (d = D - B); the slotted lever's
s = +-sqrt(|w|^2 - c^2) and beta = arg w - atan2(c, s) (w = P - Q). A scene with a pin in the
slot of a turning link and a six-bar with a Newton group (drawn here) cover the other two kinds;
every step's checks re-evaluate and its LaTeX typesets (test_solve's machinery).
"""

from __future__ import annotations

import functools
import itertools
import json
import math
from pathlib import Path
from typing import Any

import numpy as np
import pytest

from solver.analysis.instant import analyze
from solver.model.scene import parse_linkage
from solver.position.topology import DriverStep, DyadStep, LeverStep, LineSpec, NewtonStep
from solver.solutions import Solution, Step, solve
from solver.teaching.presets import PRESETS, build_preset
from tests.linkage_strategies import stephenson_six_bar
from tests.solver.solutions.test_solve import NODE, _check_solution, run_katex

EXAMPLES = Path(__file__).resolve().parents[3] / "server" / "examples"
LINKAGE_SEEDS = sorted(
    p.stem for p in EXAMPLES.glob("*.json") if json.loads(p.read_text())["kind"] == "linkage"
)
ANGLE_TOL = 1e-12

# A rocker DX whose pin X slides in the slot of the driven link "guide" (a dyad on a moving
# guide), analysed 10 deg from its drawing so that the slot has turned.
PIN_IN_TURNING_SLOT: dict[str, Any] = {
    "kind": "linkage",
    "title": "rocker pin in a turning slot",
    "points": {"O": [0.0, 0.0], "E": [0.0, 0.2], "D": [0.4, 0.0], "X": [0.25, 0.2]},
    "links": {
        "ground": {"points": ["O", "D"], "ground": True},
        "guide": {"points": ["O", "E"]},
        "rocker": {"points": ["D", "X"]},
    },
    "joints": [
        {"type": "revolute", "point": "O", "links": ["ground", "guide"]},
        {"type": "revolute", "point": "D", "links": ["ground", "rocker"]},
        {"type": "slider", "point": "X", "links": ["guide", "rocker"], "axis": [0.8660254, 0.5]},
    ],
    "drivers": [{"link": "guide", "omega": 2.0, "alpha": 1.0, "angle_deg": 80.0}],
}

# A Stephenson six-bar driven by dyad_in (from tests.linkage_strategies): the four-bar loop
# A-B-C-D and the dyad X-Q-Y on the coupler close only together, a Newton group; analysed 5 deg
# from its drawing so that Newton-Raphson has work to do.
STEPHENSON: dict[str, Any] = stephenson_six_bar(
    {
        "A": [0.0, 0.0],
        "B": [0.5, 0.0],
        "C": [0.75, 0.4330127018922193],
        "D": [1.0, 0.0],
        "X": [0.0, 1.0],
        "Y": [0.875, 0.649519052838329],
        "Q": [0.13397459621556138, 0.0669872981077807],
    },
    {"link": "dyad_in", "omega": 1.0, "alpha": 0.0, "angle_deg": -86.82855334700785},
    "Stephenson six-bar (ground-coupler, driver dyad_in)",
)


def offset_lever() -> dict[str, Any]:
    """The inverted slider-crank preset with its slot turned by 10 deg about the pin: the slot
    no longer passes through the lever's pivot (offset c != 0)."""
    doc = build_preset("inverted_slider_crank", {})
    slot = next(j for j in doc["joints"] if j["type"] == "slider")
    x, y = slot["axis"]
    turn = math.radians(10.0)
    slot["axis"] = [
        x * math.cos(turn) - y * math.sin(turn),
        x * math.sin(turn) + y * math.cos(turn),
    ]
    doc["title"] = "inverted slider-crank, offset slot"
    return doc


def documents() -> dict[str, dict[str, Any]]:
    docs = {name: build_preset(name, {}) for name in PRESETS}
    docs |= {name: json.loads((EXAMPLES / f"{name}.json").read_text()) for name in LINKAGE_SEEDS}
    docs["offset_lever"] = offset_lever()
    return docs


DOCS = documents()
CASES = [(n, m) for n in DOCS for m in ("vector", "loop")]


@functools.cache
def solved(name: str, method: str) -> Solution:
    """The worked solution of ``DOCS[name]`` by ``method``, solved when a test first asks for it
    (not when the module is collected, by every worker)."""
    return solve(parse_linkage(DOCS[name]), method)


def steps(solution: Solution, kind: str) -> list[Step]:
    return [s for s in solution.steps if s.kind == kind]


def wrapped(x: float) -> float:
    return math.remainder(x, 2 * math.pi)


@pytest.mark.parametrize(("name", "method"), CASES, ids=[f"{n}-{m}" for n, m in CASES])
def test_every_group_has_its_position_derived(name: str, method: str) -> None:
    solution = solved(name, method)
    kinds = [s.kind for s in solution.steps]
    for group in solution.analysis.plan.steps:
        if isinstance(group, DriverStep):
            assert "position.crank" in kinds, name
        elif isinstance(group, DyadStep):
            lines = [s for s in group.loci if isinstance(s, LineSpec)]
            moving = lines and lines[0].guide != parse_linkage(DOCS[name]).ground
            wanted = {"position.slot"} if moving else {"position.triangle", "position.slider"}
            assert set(kinds) & wanted, name
        elif isinstance(group, LeverStep):
            assert "position.lever" in kinds, name
        elif isinstance(group, NewtonStep):
            assert "position.newton" in kinds, name
    if solution.method == "loop":
        assert kinds.count("position.loop") == kinds.count("loop.position") > 0, name


ANALYSES = {n: analyze(parse_linkage(d)) for n, d in DOCS.items()}  # (a solution's .analysis)
FOUR_BAR_LOOPS = [n for n in DOCS if ANALYSES[n].four_bar_loops]
LEVERS = [n for n in DOCS if any(isinstance(g, LeverStep) for g in ANALYSES[n].plan.steps)]


def four_bar_dyad(name: str, solution: Solution) -> tuple[str, str, str]:
    """(B, C, D): the coupler's centre, the joint and the rocker's fixed pivot of the first RRR
    dyad of ``DOCS[name]``, from the solver's plan."""
    fixed = set(DOCS[name]["links"]["ground"]["points"])
    dyad = next(g for g in solution.analysis.plan.steps if isinstance(g, DyadStep))
    centres = [spec.center for spec in dyad.loci if not isinstance(spec, LineSpec)]
    rocker = next(c for c in centres if c in fixed)
    coupler = next(c for c in centres if c not in fixed)
    return coupler, dyad.point, rocker


@pytest.mark.parametrize("name", FOUR_BAR_LOOPS)
def test_four_bar_closed_form_gives_the_solver_angles(name: str) -> None:
    """theta14 = delta +- acos(C / R) from A, B, C recomputed from the shown a3, a4 and d."""
    assert {"four_bar", "S000-T1", "seed004"} <= set(FOUR_BAR_LOOPS)
    solution = solved(name, "loop")
    step = next(s for s in steps(solution, "position.loop") if "gamma" in s.values)
    v = {k: x.value for k, x in step.values.items()}
    a3, a4 = v["a3"], v["a4"]
    d = np.asarray(v["d"])
    b, c, dd = four_bar_dyad(name, solution)
    points = solution.analysis.points
    np.testing.assert_allclose(d, points[dd].position - points[b].position, rtol=0, atol=1e-15)
    big_a, big_b = 2 * a4 * d[0], 2 * a4 * d[1]
    big_c = a3**2 - a4**2 - float(d @ d)
    assert (v["A"], v["B"], v["C"]) == pytest.approx((big_a, big_b, big_c), rel=1e-12, abs=1e-15)
    assert math.cos(v["gamma"]) == pytest.approx(v["cos gamma"], abs=1e-12)
    assert v["cos gamma"] == pytest.approx(big_c / math.hypot(big_a, big_b), abs=1e-12)
    delta = math.atan2(big_b, big_a)
    gamma = math.acos(big_c / math.hypot(big_a, big_b))
    r_dc = points[c].position - points[dd].position
    r_bc = points[c].position - points[b].position
    theta14 = math.atan2(r_dc[1], r_dc[0])
    sign = 1.0 if "(sign +)" in step.text else -1.0
    closed = delta + sign * gamma
    assert abs(wrapped(closed - theta14)) < ANGLE_TOL, (name, closed, theta14)
    assert abs(wrapped(delta - sign * gamma - theta14)) > 1e-6, "the other assembly differs"
    z = d + a4 * np.array([math.cos(closed), math.sin(closed)])
    assert abs(wrapped(math.atan2(z[1], z[0]) - math.atan2(r_bc[1], r_bc[0]))) < ANGLE_TOL
    assert np.hypot(*z) == pytest.approx(a3, rel=1e-12)
    assert f"{c} on the {'left' if sign > 0 else 'right'} of {b}{dd}" in step.text


@pytest.mark.parametrize("method", ["vector", "loop"])
@pytest.mark.parametrize("name", LEVERS)
def test_slotted_lever_closed_form_gives_the_solver_angle(name: str, method: str) -> None:
    """s = +-sqrt(|w|^2 - c^2), beta = arg w - atan2(c, s): the slot's direction and the pin's
    distance from the pivot along it, as the solver has them (the lever's slot turned with it)."""
    assert {"inverted_slider_crank", "quick_return", "S000-T2", "offset_lever"} <= set(LEVERS)
    solution = solved(name, method)
    kind = "position.lever" if method == "vector" else "position.loop"
    step = next(s for s in steps(solution, kind) if "epsilon" in s.values)
    v = {k: x.value for k, x in step.values.items()}
    keys = {
        k[0]: k for k in v if k[:1] in "scb" and k.rstrip("0123456789") in ("s", "s1", "c", "beta")
    }
    lever = next(g for g in solution.analysis.plan.steps if isinstance(g, LeverStep))
    points = solution.analysis.points
    w = points[lever.pin].position - points[lever.pivot].position
    np.testing.assert_allclose(
        v["w" if "w" in v else f"r({lever.pivot},{lever.pin})"], w, atol=1e-15
    )
    c = v[keys["c"]]
    sign = 1.0 if "(sign +)" in step.text else -1.0
    s = sign * math.sqrt(float(w @ w) - c**2)
    beta = math.atan2(w[1], w[0]) - math.atan2(c, s)
    turn = solution.analysis.motion.links[lever.link].theta[0]
    u0 = np.asarray(lever.direction0) / np.hypot(*lever.direction0)
    slot = math.atan2(u0[1], u0[0]) + turn
    assert abs(wrapped(beta - slot)) < ANGLE_TOL, (name, beta, slot)
    assert v[keys["b"]] == pytest.approx(wrapped(slot), abs=ANGLE_TOL)
    assert s == pytest.approx(v[keys["s"]], abs=1e-12)
    assert abs(c - lever.offset) < 1e-12
    assert (abs(c) > 0.01) == (name == "offset_lever")


@pytest.mark.slow
def test_pin_in_a_turning_slot() -> None:
    """X = Q + s u on the slot as it is now (turned with the guide), |X - D| = |DX|."""
    solution = solve(parse_linkage(PIN_IN_TURNING_SLOT), "vector")
    _check_solution(solution)
    step = next(iter(steps(solution, "position.slot")))
    v = {k: np.asarray(x.value) for k, x in step.values.items()}
    x = solution.analysis.points["X"].position
    np.testing.assert_allclose(v["Q"] + v["s"] * v["u"], x, atol=1e-12)
    turn = math.radians(80.0 - 90.0)  # the guide O-E is drawn at 90 deg
    assert float(v["theta_rot(guide)"]) == pytest.approx(turn, abs=1e-12)
    assert float(v["beta"]) == pytest.approx(math.radians(30.0) + turn, abs=1e-7)
    assert np.hypot(*(x - solution.analysis.points["D"].position)) == pytest.approx(0.25, rel=1e-12)
    assert "slot of guide" in step.title and "behind the foot" in step.text
    loop = solve(parse_linkage(PIN_IN_TURNING_SLOT), "loop")
    assert loop.method == "vector" and steps(loop, "position.slot")
    if NODE is not None:
        assert run_katex([step.latex]) == []


@pytest.mark.slow
def test_newton_group_shows_the_iterations_and_the_solver_residual() -> None:
    solution = solve(parse_linkage(STEPHENSON), "vector")
    _check_solution(solution)
    step = next(iter(steps(solution, "position.newton")))
    report = solution.analysis.diagnostics.newton[0]
    residuals = [x.value for k, x in step.values.items() if k.startswith("|Phi(q_")]
    assert residuals[0] > 1e-3 and residuals[-1] <= report.tolerance
    # quadratic convergence: each residual at most a constant times the square of the last
    assert all(b < 10 * a * a / 1e-2 for a, b in itertools.pairwise(residuals))
    assert step.values["iterations (solver)"].value == report.iterations
    assert step.values["residual (solver)"].value == report.residual_norm
    assert "solved numerically, by Newton-Raphson" in step.text
    assert "the pose reached is the solver's" in step.text
    assert r"\Phi" in step.latex and r"\hline" in step.latex
    if NODE is not None:
        assert run_katex([step.latex]) == []


@pytest.mark.slow
def test_every_new_position_step_renders_in_katex() -> None:
    if NODE is None:
        pytest.skip("node is not installed")
    kinds = ("position.lever", "position.loop")
    latex = [s.latex for n, m in CASES for s in solved(n, m).steps if s.kind in kinds]
    assert latex and run_katex(latex) == []


@pytest.mark.parametrize("method", ["vector", "loop"])
def test_offset_lever_steps_re_evaluate(method: str) -> None:
    """The one scene here not among the presets and seeds that test_steps re-evaluates."""
    solution = solved("offset_lever", method)
    assert solution.method == method
    _check_solution(solution)

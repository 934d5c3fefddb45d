"""Worked solutions (solver.solutions.solve): the steps carry the solver's numbers, the seeds'
corrected values, never the seeds' mistakes, arithmetic that re-evaluates to what they state, and
LaTeX that KaTeX renders; and they read as a lecturer expects (second half): no printed number is
rounding noise, the moving point and the event time of seed 003 (t = sqrt(3) s and 1.474810 s)
are in its Results, one symbol per angle, the spatial chain computes each point once, an
all-revolute dyad is not called a "relative connection", every typical mistake sits under the
step it belongs to, and the shown arithmetic recomputes to the shown digits.

Sources: tests/reference/seed-cases.json (corrected reference values, compared with a tolerance of
1e-6 relative to the largest magnitude of the same unit group in the case, at least 1) and
../shared/reference/ERRATA.md (E000-*, E001-*, E002-*, E003-*: what the seeds got wrong); random
scenes of every preset from ``tests.strategies.assemblable_presets`` (property: every ``check``
of every step holds, every ``source`` is the /analyze number).

``verify`` below re-evaluates a step's checks from its listed values, independently of
solver.solutions: relations as documented in docs/SOLUTIONS.md, each compared with a relative
tolerance of 1e-9 of the size of the terms it is made of (stricter than the display precision).
"""

from __future__ import annotations

import functools
import json
import math
import re
import shutil
import subprocess
from collections.abc import Iterable, Iterator, Sequence
from pathlib import Path
from typing import Any

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from solver.analysis.instant import LinkageAnalysis
from solver.analysis.results import analysis_body, spatial_body
from solver.errors import InvalidScene
from solver.kinematics.spatial import parse_spatial_chain
from solver.model.quantities import QUANTITIES
from solver.model.scene import parse_linkage
from solver.solutions import Solution, Step, solve
from solver.solutions.format import Formatter
from solver.solutions.relative import arc_events
from solver.teaching.presets import PRESETS, build_preset
from tests.linkage_strategies import linkages
from tests.strategies import assemblable_presets

ROOT = Path(__file__).resolve().parents[3]
REFERENCE = ROOT / "tests" / "reference"
EXAMPLES = ROOT / "server" / "examples"
KATEX_CHECK = ROOT / "tests" / "katex_check.mjs"
CASES = json.loads((REFERENCE / "seed-cases.json").read_text())["cases"]
RTOL = 1e-9
NODE = shutil.which("node")
needs_node = pytest.mark.skipif(NODE is None, reason="node is not installed: KaTeX cannot run")

JSONValue = Any


# --- an independent checker of the steps' arithmetic -------------------------------------------


def _size(x: JSONValue) -> float:
    return float(np.linalg.norm(np.atleast_1d(np.asarray(x, dtype=float))))


def _perp(a: np.ndarray) -> np.ndarray:
    return np.array([-a[1], a[0]])


def _cross(a: JSONValue, b: JSONValue) -> JSONValue:
    a, b = np.atleast_1d(np.asarray(a, float)), np.atleast_1d(np.asarray(b, float))
    if a.size == 1 and b.size == 2:  # (0, 0, a) x (b_x, b_y, 0)
        return float(a[0]) * _perp(b)
    if a.size == 2 and b.size == 2:  # z-component of a planar cross product
        return float(a[0] * b[1] - a[1] * b[0])
    assert a.size == b.size == 3, (a, b)
    return np.cross(a, b)


def unit_floors(steps: Iterable[dict[str, Any]]) -> dict[str, float]:
    """The largest magnitude of each unit over a whole solution (the scale of rounding noise)."""
    floors: dict[str, float] = {}
    for step in steps:
        for v in step["values"].values():
            floors[v["unit"]] = max(floors.get(v["unit"], 0.0), _size(v["value"]))
    return floors


def verify(step: dict[str, Any], floors: dict[str, float] | None = None) -> list[str]:
    """The checks of one step (as JSON) that do not hold; [] when the step is consistent.

    ``floors``: the scale of each unit in the whole solution (``unit_floors``); rounding noise
    of the solver is relative to it (a pole 1e-16 m away from a pivot at the origin)."""
    values = {
        k: np.asarray(v["value"], float) if isinstance(v["value"], list) else v["value"]
        for k, v in step["values"].items()
    }
    units = {k: v["unit"] for k, v in step["values"].items()}
    floor = dict(floors or {})  # the largest magnitude of each unit in the step (or solution)
    for key, value in values.items():
        floor[units[key]] = max(floor.get(units[key], 0.0), _size(value))
    natural: dict[str, float] = {}  # size of the terms a checked result was made of
    failures = []

    def get(name: str) -> tuple[JSONValue, float]:
        sign = -1.0 if name.startswith("-") else 1.0
        name = name.lstrip("-")
        index = None
        if name.endswith("]") and name.rsplit("[", 1)[0] in values:
            name, rest = name.rsplit("[", 1)
            index = int(rest[:-1])
        value = values[name]
        scale = natural.get(name, _size(value))  # a component: the size of its vector
        if index is not None:
            value = float(value[index])
        return sign * value, scale

    for check in step["checks"]:
        relation, factor = check["relation"], check["factor"]
        got = [get(o) for o in check["operands"]]
        vals, scales = [g[0] for g in got], [g[1] for g in got]
        if relation == "sum":
            lhs: JSONValue = sum(vals[1:], vals[0])
            scale = sum(scales)
        elif relation == "cross":
            lhs, scale = _cross(vals[0], vals[1]), scales[0] * scales[1]
        elif relation == "product":
            lhs, scale = math.prod(vals), math.prod(scales)
        elif relation == "quotient":
            lhs, scale = vals[0] / vals[1], scales[0] / abs(vals[1])
        elif relation == "det2":
            lhs = vals[0] * vals[3] - vals[1] * vals[2]
            scale = scales[0] * scales[3] + scales[1] * scales[2]
        elif relation == "linear":
            lhs = sum(vals[k] * vals[k + 1] for k in range(0, len(vals), 2))
            scale = sum(scales[k] * scales[k + 1] for k in range(0, len(vals), 2))
        elif relation == "dot":
            lhs, scale = float(np.dot(vals[0], vals[1])), scales[0] * scales[1]
        elif relation in ("phasor", "iphasor"):
            unit = np.array([math.cos(vals[-1]), math.sin(vals[-1])])
            lhs = math.prod(vals[:-1]) * (unit if relation == "phasor" else _perp(unit))
            scale = math.prod(scales[:-1])
        elif relation == "angle":
            lhs, scale = math.atan2(vals[0][1], vals[0][0]), math.pi
        elif relation == "norm":
            lhs, scale = _size(vals[0]), scales[0]
        else:
            failures.append(f"unknown relation {relation}")
            continue
        lhs = factor * np.asarray(lhs)
        scale *= abs(factor)
        result, _ = get(check["result"])
        diff = lhs - np.asarray(result)
        if relation == "angle":
            diff = (diff + math.pi) % (2 * math.pi) - math.pi
        tolerance = RTOL * (scale + _size(result) + floor[units[check["result"]]]) + 1e-300
        if not _size(diff) <= tolerance:
            failures.append(
                f"{step['kind']} '{step['title']}': {check['result']} = {relation}"
                f"{tuple(check['operands'])} x {factor}: states {result}, "
                f"re-evaluates to {lhs}"
            )
        natural.setdefault(check["result"], scale + _size(result))
    return failures


# --- helpers ------------------------------------------------------------------------------------


def scene_of(doc: dict[str, Any]) -> Any:
    return parse_linkage(doc) if doc["kind"] == "linkage" else parse_spatial_chain(doc)


def example(name: str) -> dict[str, Any]:
    doc: dict[str, Any] = json.loads((EXAMPLES / f"{name}.json").read_text())
    return doc


def steps_of(solution: Solution, kind: str) -> list[Step]:
    return [s for s in solution.steps if s.kind == kind]


def one(steps: Sequence[Step], title_part: str = "") -> Step:
    found = [s for s in steps if title_part in s.title]
    assert len(found) == 1, [s.title for s in steps]
    return found[0]


def value(step: Step, key: str) -> Any:
    v = step.values[key].value
    return np.array(v) if isinstance(v, tuple) else v


def results_body(solution: Solution) -> dict[str, Any]:
    if isinstance(solution.analysis, LinkageAnalysis):
        return analysis_body(solution.analysis, [])
    return spatial_body(solution.analysis, frozenset(QUANTITIES), [])


def at_path(body: Any, path: Sequence[Any]) -> Any:
    for key in path:
        body = body[key]
    return body


def parse_path(text: str) -> list[str | int]:
    """'joints[0].coriolis_acceleration' -> ['joints', 0, 'coriolis_acceleration']."""
    out: list[str | int] = []
    for part in text.split("."):
        name, *indices = re.split(r"\[(\d+)\]", part)
        if name:
            out.append(name)
        out += [int(i) for i in indices if i]
    return out


def all_latex(solution: Solution) -> list[str]:
    return [s.latex for s in solution.steps if s.latex]


def run_katex(latex: Iterable[str]) -> list[dict[str, Any]]:
    """Typeset each string with the vendored KaTeX under node (one process); the failures."""
    assert NODE is not None
    lines = "\n".join(json.dumps(s) for s in latex) + "\n"
    done = subprocess.run(
        [NODE, str(KATEX_CHECK)],
        input=lines,
        capture_output=True,
        text=True,
        timeout=120,
        check=False,
    )
    results = [json.loads(line) for line in done.stdout.splitlines() if line.strip()]
    assert len(results) == lines.count("\n"), done.stderr
    failures = [r for r in results if not r["ok"]]
    assert (done.returncode == 0) == (not failures), done.stderr
    return failures


class Katex:
    """A long-lived tests/katex_check.mjs: one JSON line in, one result line out."""

    def __init__(self) -> None:
        assert NODE is not None
        self.process = subprocess.Popen(
            [NODE, str(KATEX_CHECK)],
            stdin=subprocess.PIPE,
            stdout=subprocess.PIPE,
            text=True,
            bufsize=1,
        )

    def failures(self, latex: Iterable[str]) -> list[dict[str, Any]]:
        assert self.process.stdin is not None and self.process.stdout is not None
        out = []
        for s in latex:
            self.process.stdin.write(json.dumps(s) + "\n")
            self.process.stdin.flush()
            result = json.loads(self.process.stdout.readline())
            if not result["ok"]:
                out.append(result)
        return out

    def close(self) -> None:
        assert self.process.stdin is not None
        self.process.stdin.close()
        self.process.wait(timeout=30)


@pytest.fixture(scope="module")
def katex() -> Iterator[Katex]:
    if NODE is None:
        pytest.skip("node is not installed: KaTeX cannot run")
    checker = Katex()
    yield checker
    checker.close()


def analyze_cases() -> list[tuple[str, int, dict[str, Any], list[dict[str, Any]]]]:
    out = []
    for case in CASES:
        for k, request in enumerate(case["requests"]):
            if request["endpoint"] == "POST /api/v1/analyze":
                out.append((case["id"], k, request["body"]["scene"], request["expected"]))
    return out


ANALYZE_CASES = analyze_cases()
# A gear train's worked solution has its own tests (test_gear_train.py): every other example.
SEED_SCENES = sorted(
    p.stem for p in EXAMPLES.glob("*.json") if json.loads(p.read_text())["kind"] != "gear_train"
)


# --- the seeds: corrected values, determinants, never the seeds' mistakes -------------------------


def _unit_scales(expected: list[dict[str, Any]]) -> dict[str, float]:
    scales: dict[str, float] = {}
    for e in expected:
        scales[e["kind"]] = max(scales.get(e["kind"], 1.0), _size(e["value"]))
    return scales


@pytest.mark.parametrize("method", ["vector", "loop"])
@pytest.mark.parametrize(
    ("case", "index", "scene", "expected"),
    ANALYZE_CASES,
    ids=[f"{c}-{k}" for c, k, _, _ in ANALYZE_CASES],
)
def test_every_reference_value_appears_in_the_steps_with_its_source(
    case: str, index: int, scene: dict[str, Any], expected: list[dict[str, Any]], method: str
) -> None:
    """seed-cases.json: each corrected value is shown in some step, labelled with its path in the
    /analyze response, and equal to the reference (1e-6 of the unit group's largest value). The
    loop method shows the links' rates (and moving points); poles and slot parts are the vector
    method's."""
    solution = solve(scene_of(scene), method)
    if solution.method == "loop":
        expected = [
            e
            for e in expected
            if e["kind"] in ("omega", "alpha") or e["path"].startswith("moving_points")
        ]
    shown: dict[tuple[Any, ...], list[Any]] = {}
    for step in solution.steps:
        for v in step.values.values():
            if v.source is not None:
                shown.setdefault(tuple(v.source), []).append(v.value)
    scales = _unit_scales(expected)
    for e in expected:
        path = tuple(parse_path(e["path"]))
        assert path in shown, f"{case}: no step shows {e['path']}"
        for got in shown[path]:
            np.testing.assert_allclose(
                got,
                e["value"],
                rtol=0,
                atol=1e-6 * scales[e["kind"]],
                err_msg=f"{case} {e['path']}",
            )


def test_s000_t1_coupler_and_rocker_rates_have_their_own_labels() -> None:
    """E000-T1-4: eps_2 (coupler) = +0.09375, eps_3 (rocker) = -0.375 rad/s^2, two unknowns."""
    solution = solve(parse_linkage(example("S000-T1")))
    step = one(steps_of(solution, "acceleration.dyad.solve"))
    assert value(step, "alpha(coupler)") == pytest.approx(0.09375, abs=1e-12)
    assert value(step, "alpha(rocker)") == pytest.approx(-0.375, abs=1e-12)
    assert step.values["alpha(coupler)"].source == ("links", "coupler", "alpha")
    assert step.values["alpha(rocker)"].source == ("links", "rocker", "alpha")
    boxed = r"\alpha_{\text{coupler}} = \frac{0.1875}{2} = \underline{\underline{0.09375"
    assert boxed in step.latex
    assert r"\alpha_{\text{rocker}} = \underline{\underline{-0.375" in step.latex
    velocity = one(steps_of(solution, "velocity.dyad.solve"))
    assert value(velocity, "omega(coupler)") == pytest.approx(0.25, abs=1e-12)
    assert value(velocity, "omega(rocker)") == pytest.approx(-1.0, abs=1e-12)
    # E000-T1-2: the unknown omega of the coupler stands in the determinant, not the crank's -1
    side = one(steps_of(solution, "velocity.dyad.side"), "through link coupler")
    assert (
        r"\begin{vmatrix} \mathbf{i} & \mathbf{j} & \mathbf{k} \\ 0 & 0 & "
        r"\omega_{\text{coupler}} \\ 2 & 0 & 0 \end{vmatrix}"
    ) in side.latex
    # E000-T1-6: the rocker's acceleration pole is D; the coupler's is computed
    poles = steps_of(solution, "poles.acceleration")
    assert value(one(poles, "rocker"), "G(rocker)") == pytest.approx([2.5, 0.0], abs=1e-12)
    coupler = one(poles, "coupler")
    np.testing.assert_allclose(value(coupler, "G(coupler)"), [12.3077, 3.4615], atol=1e-4)
    np.testing.assert_allclose(value(coupler, "r(G,C)"), [-10.3077, -2.4615], atol=1e-4)
    assert r"D = \begin{vmatrix}" in coupler.latex  # Cramer's rule, determinants written out
    pole = one(steps_of(solution, "poles.velocity"), "coupler")
    np.testing.assert_allclose(value(pole, "P(coupler)"), [0.0, 5.0], atol=1e-12)
    np.testing.assert_allclose(value(pole, "r(P,C)"), [2.0, -4.0], atol=1e-12)  # E000-T1-5


def test_s000_t2_coriolis_is_two_omega_guide_cross_v_rel() -> None:
    """E000-T2-3: a_Cor = 2 omega_guide x v_rel with v_rel = (0, 0.69282), = (2.77128, 0)."""
    solution = solve(parse_linkage(example("S000-T2")))
    step = one(steps_of(solution, "acceleration.coriolis"))
    np.testing.assert_allclose(value(step, "v_rel(B)"), [0.0, 0.69282032], atol=1e-8)
    np.testing.assert_allclose(value(step, "a_cor(B)"), [2.77128129, 0.0], atol=1e-8)
    assert value(step, "omega(guide)") == pytest.approx(-2.0, abs=1e-12)
    assert {
        "relation": "cross",
        "result": "a_cor(B)",
        "operands": ["omega(guide)", "v_rel(B)"],
        "factor": 2.0,
    } in [c.as_json() for c in step.checks]
    assert (
        r"2 \cdot \begin{vmatrix} \mathbf{i} & \mathbf{j} & \mathbf{k} \\ 0 & 0 & -2 \\ 0 & "
        r"0.6928 & 0 \end{vmatrix}"
    ) in step.latex
    assert r"\underline{\underline{\begin{pmatrix} 2.771 \\ 0 \\ 0 \end{pmatrix}" in step.latex
    assert "v_rel" in step.text and "not its absolute velocity" in step.text
    solved = one(steps_of(solution, "acceleration.lever.solve"))
    assert value(solved, "alpha(guide)") == pytest.approx(9.92820323, abs=1e-7)
    assert value(solved, "s_ddot(B/guide)") == pytest.approx(-1.03923048, abs=1e-7)
    # E000-T2-2: the fixed joints are C and A; D moves
    fixed = one(steps_of(solution, "velocity.fixed"))
    assert set(fixed.values) == {"v(C)", "v(A)"}
    d = one(steps_of(solution, "acceleration.rigid"), "of D")
    np.testing.assert_allclose(value(d, "a(D)"), [-3.97128129, -1.6], atol=1e-8)


def test_s000_t2_rounded_reproduces_the_seed_numbers() -> None:
    """S000-T2-rounded: with x = 0.35 m the seed's own numbers (eps = 10, a_Cor = (2.8, 0))."""
    solution = solve(parse_linkage(example("S000-T2-rounded")))
    cor = one(steps_of(solution, "acceleration.coriolis"))
    np.testing.assert_allclose(value(cor, "a_cor(B)"), [2.8, 0.0], atol=1e-12)
    solved = one(steps_of(solution, "acceleration.lever.solve"))
    assert value(solved, "alpha(guide)") == pytest.approx(10.0, abs=1e-9)


def test_s000_t3_coriolis_is_zero_on_the_fixed_guide() -> None:
    """E000-T3-3..7: no Coriolis term (the guide is fixed), eps_2 = +7.68, a_C = (1.8432, 0)."""
    solution = solve(parse_linkage(example("S000-T3")))
    step = one(steps_of(solution, "acceleration.coriolis"))
    assert value(step, "a_cor(C)") == pytest.approx([0.0, 0.0], abs=1e-15)
    assert "slot is fixed in the ground" in step.text and "does not rotate" in step.text
    assert "omega(coupler) = -1.44 rad/s) does not enter the Coriolis term" in step.text
    assert r"\underline{\underline{\vec{0}" in step.latex
    everything = " ".join(s.latex + " " + s.text for s in solution.steps)
    for wrong in ("-2.76", "2.16", "1.85", "41.4", "1.021", "-1.896"):
        assert wrong not in everything, wrong
    solved = one(steps_of(solution, "acceleration.dyad.solve"))
    assert value(solved, "alpha(coupler)") == pytest.approx(7.68, abs=1e-12)
    assert value(solved, "s_ddot(C/ground)") == pytest.approx(1.8432, abs=1e-12)
    d = one(steps_of(solution, "acceleration.rigid"), "of D")
    np.testing.assert_allclose(value(d, "a(D)"), [1.01376, 3.072], atol=1e-12)
    pole = one(steps_of(solution, "poles.acceleration"), "coupler")
    np.testing.assert_allclose(value(pole, "G(coupler)"), [0.38040, 0.46369], atol=1e-5)


def test_s000_t4_exact_geometry() -> None:
    """E000-T4-2..6: omega_2 = 0.347195, eps_2 = 1.582003, r_P2B = (-0.77165, -1.21593)."""
    solution = solve(parse_linkage(example("S000-T4")))
    assert value(one(steps_of(solution, "velocity.dyad.solve")), "omega(coupler)") == (
        pytest.approx(0.347195, abs=1e-6)
    )
    assert value(one(steps_of(solution, "acceleration.dyad.solve")), "alpha(coupler)") == (
        pytest.approx(1.582003, abs=1e-6)
    )
    pole = one(steps_of(solution, "poles.velocity"), "coupler")
    np.testing.assert_allclose(value(pole, "r(P,B)"), [-0.77165, -1.21593], atol=1e-5)
    g = one(steps_of(solution, "poles.acceleration"), "coupler")
    np.testing.assert_allclose(value(g, "G(coupler)"), [0.92181, 0.21263], atol=1e-5)


def test_s001_loop_closure_with_cramer_determinants() -> None:
    """Seed 001 in complex form: omega13, s14' by Cramer's rule; E001-1: s14'' is real."""
    solution = solve(parse_linkage(example("S001-offset-slider-crank")), "loop")
    assert solution.method == "loop"
    loop = one(steps_of(solution, "loop.position"))
    assert r"a_{2}\,e^{i\theta_{12}} + a_{3}\,e^{i\theta_{13}} = (s_{14} + i\,c_{4})" in loop.latex
    velocity = one(steps_of(solution, "loop.velocity"))
    acceleration = one(steps_of(solution, "loop.acceleration"))
    for step in (velocity, acceleration):
        for determinant in (
            r"&D = \begin{vmatrix}",
            r"&D_1 = \begin{vmatrix}",
            r"&D_2 = \begin{vmatrix}",
        ):
            assert determinant in step.latex
        assert {c.relation for c in step.checks} >= {"det2", "quotient", "linear", "iphasor"}
    assert value(velocity, "omega13") == pytest.approx(-1.4364480255814462, abs=1e-9)
    assert value(velocity, "s_dot14") == pytest.approx(-0.9186030506423194, abs=1e-9)
    assert value(acceleration, "alpha13") == pytest.approx(27.53593004048058, abs=1e-8)
    assert value(acceleration, "s_ddot14") == pytest.approx(-2.9782882140571525, abs=1e-9)
    assert isinstance(value(acceleration, "s_ddot14"), float)  # a real unknown, no i
    points = steps_of(solution, "loop.acceleration.point")
    c = one(points, "of C")
    np.testing.assert_allclose(
        value(c, "a(C)"), [-6.280099909976226, -4.426899503843152], atol=1e-9
    )


@pytest.mark.parametrize(
    "name", ["S000-T1", "S000-T2", "S000-T3", "S000-T4", "S003-T1-translating-carrier"]
)
def test_loop_method_applies_to_the_seed_linkages(name: str) -> None:
    solution = solve(parse_linkage(example(name)), "loop")
    assert solution.method == "loop" and not solution.fell_back
    assert steps_of(solution, "loop.velocity") and steps_of(solution, "loop.acceleration")


def test_s002_spatial_arm_composition_axis_rates_and_five_terms() -> None:
    """Seed 002 (E002-1, E002-2): a_O2 = (0, -0.6, 0) along E2; a_B = (0.4, -1.98564, 0.5)."""
    solution = solve(parse_spatial_chain(example("S002-spatial-arm")))
    omega3 = one(steps_of(solution, "spatial.omega"), "body 3")
    np.testing.assert_allclose(value(omega3, "omega(3)"), [-1, 0.8660254, 0.5], atol=1e-7)
    axis = one(steps_of(solution, "spatial.axis_rate"), "joint 3")
    np.testing.assert_allclose(value(axis, "e_dot(3)"), [-0.8660254, -0.5, -0.8660254], atol=1e-7)
    assert r"\begin{vmatrix} \mathbf{E}_1 & \mathbf{E}_2 & \mathbf{E}_3" in axis.latex
    alpha3 = one(steps_of(solution, "spatial.alpha"), "body 3")
    np.testing.assert_allclose(value(alpha3, "alpha(3)"), [-0.8660254, -1.5, -0.8660254], atol=1e-7)
    o2 = one(steps_of(solution, "spatial.point.acceleration"), "of O2")
    np.testing.assert_allclose(value(o2, "a(O2)"), [0.0, -0.6, 0.0], atol=1e-12)
    b = one(steps_of(solution, "spatial.point.acceleration"), "of B")
    np.testing.assert_allclose(value(b, "omega x (omega x r)"), [-0.2, -0.1732051, -0.1], atol=1e-7)
    np.testing.assert_allclose(value(b, "a(B)"), [0.4, -1.985641, 0.5], atol=1e-6)
    for term in ("a_O", "alpha x r", "omega x (omega x r)", "2 omega x v_rel", "a_rel"):
        assert term in b.values
    assert solve(parse_spatial_chain(example("S002-spatial-arm")), "loop").fell_back


def test_s003_relative_velocity_has_no_carrier_rate() -> None:
    """E003-4..6 at t = 1 s: v_rel = (1.63559, 0.21251), v_tr = (0.47061, -0.36238),
    a_Cor = (-0.59502, 4.57965), a = (-0.05577, 14.56808)."""
    solution = solve(parse_linkage(example("S003-T2-rotating-carrier")))
    rel = one(steps_of(solution, "relative.relative_velocity"))
    np.testing.assert_allclose(value(rel, "v_rel(M)"), [1.63559, 0.21251], atol=1e-5)
    tr = one(steps_of(solution, "relative.transport_velocity"))
    np.testing.assert_allclose(value(tr, "v_tr(M)"), [0.47061, -0.36238], atol=1e-5)
    cor = one(steps_of(solution, "relative.coriolis"))
    np.testing.assert_allclose(value(cor, "a_cor(M)"), [-0.59502, 4.57965], atol=1e-5)
    total = one(steps_of(solution, "relative.acceleration"))
    np.testing.assert_allclose(value(total, "a(M)"), [-0.05577, 14.56808], atol=1e-5)
    mistakes = {m.kind: m for m in solution.mistakes}
    np.testing.assert_allclose(
        mistakes["relative.carrier_rate"].values["wrong"].value, [2.05209, 0.26662], atol=1e-5
    )  # the seed's form, shown as wrong


def test_s003_translating_carrier_has_no_coriolis_and_tangential_along_the_motion() -> None:
    """E003-1, E003-7: a_rel^tau = (+0.3265, +0.1885) at t = 1 s; the carrier translates."""
    solution = solve(parse_linkage(example("S003-T1-translating-carrier")))
    rel = one(steps_of(solution, "relative.relative_acceleration"))
    np.testing.assert_allclose(value(rel, "a_rel tangential"), [0.3265, 0.1885], atol=1e-4)
    cor = one(steps_of(solution, "relative.coriolis"))
    assert value(cor, "a_cor(M)") == pytest.approx([0.0, 0.0], abs=1e-15)
    assert "translates" in cor.text
    assert "coriolis.translating_carrier" in {m.kind for m in solution.mistakes}


# --- typical mistakes ---------------------------------------------------------------------------


def test_mistakes_show_the_seed_errors_as_wrong_numbers() -> None:
    t3 = {m.kind: m for m in solve(parse_linkage(example("S000-T3"))).mistakes}
    fixed = t3["coriolis_on_fixed_guide"]
    np.testing.assert_allclose(fixed.values["wrong"].value, [0.0, -2.7648], atol=1e-12)
    assert fixed.values["right"].value == pytest.approx((0.0, 0.0), abs=1e-15)
    assert "alpha(coupler) = 2.15 rad/s^2 instead of 7.68 rad/s^2" in fixed.text  # E000-T3-4
    t2 = {m.kind: m for m in solve(parse_linkage(example("S000-T2"))).mistakes}
    np.testing.assert_allclose(
        t2["coriolis_without_factor_2"].values["wrong"].value, [1.3856406, 0], atol=1e-7
    )
    assert "coriolis.absolute_velocity" in t2 and "labels.omega_alpha" in t2
    t1 = {m.kind: m for m in solve(parse_linkage(example("S000-T1"))).mistakes}
    assert {"unknowns.which_link", "normal.sign", "cross.order"} <= set(t1)
    np.testing.assert_allclose(t1["normal.sign"].values["wrong"].value, [1.0, 1.0], atol=1e-12)
    np.testing.assert_allclose(t1["cross.order"].values["wrong"].value, [-1.0, 0.0], atol=1e-12)
    assert (
        "coriolis_on_fixed_guide" not in t1 and "coriolis_without_factor_2" not in t1
    )  # not relevant
    loop = {
        m.kind for m in solve(parse_linkage(example("S001-offset-slider-crank")), "loop").mistakes
    }
    assert {"loop.derivative_i", "loop.real_slider"} <= loop
    spatial = {m.kind for m in solve(parse_spatial_chain(example("S002-spatial-arm"))).mistakes}
    assert {"spatial.axis_rate", "spatial.centripetal_order"} <= spatial


# --- every step re-evaluates; every source is the solver's number ---------------------------------


def _check_solution(solution: Solution) -> None:
    body = results_body(solution)
    floors = unit_floors(step.as_json() for step in solution.steps)
    for step in solution.steps:
        data = step.as_json()
        failures = verify(data, floors)
        assert not failures, failures[:3]
        for key, v in step.values.items():
            if v.source is not None:
                reported = at_path(body, v.source)
                assert np.array_equal(np.asarray(v.value, float), np.asarray(reported, float)), (
                    step.title,
                    key,
                    v.value,
                    reported,
                )
        _boxed_results_are_listed_values(step, solution.digits)
    assert solution.steps[-1].kind == "summary"


_NUMBER = re.compile(r"(?<![\w^{.])-?\d+(?:\.\d+)?(?: \\cdot 10\^\{-?\d+\})?")
_BOXED = "\\underline{\\underline{"


def _boxed(latex: str) -> list[str]:
    """The contents of every doubly underlined result (balanced braces)."""
    out = []
    start = latex.find(_BOXED)
    while start >= 0:
        depth, i = 2, start + len(_BOXED)
        while depth:
            depth += {"{": 1, "}": -1}.get(latex[i], 0) if latex[i - 1] != "\\" else 0
            i += 1
        out.append(latex[start + len(_BOXED) : i - 2])
        start = latex.find(_BOXED, i)
    return out


def _boxed_results_are_listed_values(step: Step, digits: int) -> None:
    """Every number in a doubly underlined result is one of the step's values as displayed (with
    ``digits`` or, where the step's arithmetic needs them to recompute, more)."""
    shown = {"0"}
    for d in range(digits, 16):
        fmt = Formatter(d)
        for v in step.values.values():
            for x in v.value if isinstance(v.value, tuple) else (v.value,):
                shown.update((fmt.latex(x), fmt.latex(-x)))
    boxes = _boxed(step.latex)
    for boxed in boxes:
        for number in _NUMBER.findall(boxed):
            assert number in shown, (step.title, number, boxed)


@pytest.mark.parametrize("method", ["vector", "loop"])
@pytest.mark.parametrize("name", SEED_SCENES)
def test_seed_steps_re_evaluate_and_carry_the_solver_numbers(name: str, method: str) -> None:
    _check_solution(solve(scene_of(example(name)), method))


@pytest.mark.parametrize("offset", [1e-17, -1e-9, 0.05])
def test_the_slider_classification_typesets_angles_written_with_a_power_of_ten(
    offset: float,
) -> None:
    """A nearly centred slider-crank (an offset of 1e-17 m, as a drawing leaves it) has a
    time-ratio angle of order 1e-16 deg, written 6.9 \\cdot 10^{-16} deg: every step still
    typesets with the vendored KaTeX (a degree sign after a power of ten needs its own group)."""
    scene = parse_linkage(build_preset("slider_crank", {"offset": offset}))
    for method in ("vector", "loop"):
        assert not run_katex(all_latex(solve(scene, method)))


@pytest.mark.parametrize(
    ("omega", "alpha"), [(0.0, 5e-324), (5e-324, 0.0), (1e-200, 0.0), (0.0, 1e-200)]
)
def test_a_crank_at_a_subnormal_rate_is_worked_as_any_other(omega: float, alpha: float) -> None:
    """Rates whose products underflow (5e-324 rad/s, the smallest float): the polygons are drawn
    (as points where nothing is left to draw), the instant centres are the geometry's (the
    same as at a rate of 1 rad/s), and every step re-evaluates."""
    values = {"crank": 0.5, "ground": 1.0, "slot_offset": 0.0, "lever": 3.0}
    scene = parse_linkage(
        build_preset("inverted_slider_crank", {**values, "omega": omega, "alpha": alpha})
    )
    solution = solve(scene, "vector")
    _check_solution(solution)
    unit = solve(parse_linkage(build_preset("inverted_slider_crank", {**values, "omega": 1.0})))

    def kennedy(steps: Sequence[Step]) -> dict[str, Any]:  # the centres P_ij between links
        step = next(s for s in steps if s.kind == "instant_centres")
        return {k: v.value for k, v in step.values.items() if re.fullmatch(r"P\d\d", k)}

    assert kennedy(solution.steps) == kennedy(unit.steps) != {}


@pytest.mark.slow
@settings(max_examples=60, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(assemblable_presets(), st.sampled_from(["vector", "loop"]))
def test_random_presets_every_step_re_evaluates(
    case: tuple[str, dict[str, float]], method: str
) -> None:
    """Property on random scenes of every preset: each step's checks hold with the values it
    lists, and every value labelled with a source is exactly the /analyze number."""
    _check_solution(solve(parse_linkage(build_preset(*case)), method))


@pytest.mark.slow
@pytest.mark.parametrize("family", ["six_bar", "block_in_lever"])
def test_six_bars_and_blocks_every_step_re_evaluates(family: str) -> None:
    """Random Watt/Stephenson six-bars (some need a Newton group) and a block in a prismatic
    joint (``tests.linkage_strategies``): the same property as for the presets."""

    @settings(max_examples=15, deadline=None, suppress_health_check=list(HealthCheck))
    @given(linkages(family), st.sampled_from(["vector", "loop"]))
    def run(doc: dict[str, Any], method: str) -> None:
        _check_solution(solve(parse_linkage(doc), method))

    run()


def test_the_checker_can_fail() -> None:
    """A wrong number in a step is caught (a test that cannot fail is a defect)."""
    solution = solve(parse_linkage(example("S000-T2")))
    step = one(steps_of(solution, "acceleration.coriolis")).as_json()
    assert not verify(step)
    step["values"]["a_cor(B)"]["value"] = [2.77128129 / 2, 0.0]  # the missing factor 2
    assert verify(step)
    step = one(steps_of(solution, "acceleration.lever.solve")).as_json()
    step["values"]["alpha(guide)"]["value"] = 10.0  # the seed's rounded geometry
    assert verify(step)


# --- numbers and options ------------------------------------------------------------------------


@pytest.mark.parametrize(("x", "digits", "text"), [
    (0.09375, 4, "0.09375"), (0.09375, 2, "0.094"), (-0.375, 4, "-0.375"),
    (12.307692307, 4, "12.31"), (12345.6, 4, "12350"), (0.0127, 4, "0.0127"),
    (2.5e-7, 3, "2.5 x 10^-7"), (1e-17, 4, "1 x 10^-17"), (0.0, 4, "0"), (-0.0, 4, "0"),
    (math.pi, 15, "3.14159265358979"), (1.0, 1, "1"), (9.96, 2, "10"),
])  # fmt: skip
def test_formatter_significant_digits(x: float, digits: int, text: str) -> None:
    assert Formatter(digits).text(x) == text


def test_formatter_hides_rounding_noise_next_to_the_unit_scale() -> None:
    fmt = Formatter(4, {"m/s": 1.0})
    assert fmt.text(6e-17, "m/s") == "0"
    assert fmt.text_vector((1.0, -6.123e-17), "m/s") == "(1, 0) m/s"
    assert fmt.latex(2.5e-7) == r"2.5 \cdot 10^{-7}"


def test_digits_change_the_display_not_the_data() -> None:
    scene = parse_linkage(example("S000-T1"))
    two, eight = solve(scene, digits=2), solve(scene, digits=8)
    a2 = one(steps_of(two, "acceleration.dyad.solve"))
    a8 = one(steps_of(eight, "acceleration.dyad.solve"))
    assert a2.values["alpha(coupler)"].display == "0.094 rad/s^2"
    assert a8.values["alpha(coupler)"].display == "0.09375 rad/s^2"
    assert a2.values["alpha(coupler)"].value == a8.values["alpha(coupler)"].value


@pytest.mark.parametrize(
    ("method", "digits"),
    [("graphical", 4), ("vector", 0), ("vector", 16), ("loop", True), ("vector", 4.0)],
)
def test_bad_options_are_invalid_scene(method: str, digits: Any) -> None:
    with pytest.raises(InvalidScene):
        solve(parse_linkage(example("S000-T1")), method, digits)


def test_loop_method_falls_back_for_a_newton_group_and_says_why() -> None:
    from tests.solver.position.test_newton import TRIAD

    solution = solve(parse_linkage(TRIAD), "loop")
    assert solution.method == "vector" and solution.requested_method == "loop"
    assert solution.steps[0].kind == "fallback"
    assert "Newton group" in solution.steps[0].text
    assert steps_of(solution, "velocity.newton")
    _check_solution(solution)


def test_solver_steps_import_no_web_framework() -> None:
    for path in (ROOT / "solver" / "solutions").glob("*.py"):
        source = path.read_text()
        for banned in ("fastapi", "pydantic", "starlette", "server"):
            assert not re.search(rf"^\s*(from|import) {banned}\b", source, re.M), (path, banned)


@pytest.mark.slow
def test_user_names_are_escaped_in_latex() -> None:
    doc = build_preset("four_bar", {})
    rename = {"A": "A_1", "B": "B{x}", "C": "C\\", "D": "D&%$#", "P": "É ~^"}
    doc = json.loads(json.dumps(doc))
    doc["points"] = {rename[k]: v for k, v in doc["points"].items()}
    for link in doc["links"].values():
        link["points"] = [rename[p] for p in link["points"]]
    for joint in doc["joints"]:
        joint["point"] = rename[joint["point"]]
    doc["links"]["coupler #1}"] = doc["links"].pop("coupler")
    for joint in doc["joints"]:
        joint["links"] = ["coupler #1}" if k == "coupler" else k for k in joint["links"]]
    solution = solve(parse_linkage(doc))
    _check_solution(solution)
    joined = "\n".join(all_latex(solution))
    assert r"\text{B\{x\}}" in joined and r"\text{coupler \#1\}}" in joined
    if NODE is not None:
        assert run_katex(all_latex(solution)) == []


# --- KaTeX -------------------------------------------------------------------------------------


@needs_node
def test_katex_check_reports_a_broken_string() -> None:
    failures = run_katex([r"\frac{1}{", r"\vec{v}_{B}"])
    assert len(failures) == 1 and "\\frac{1}{" in failures[0]["latex"]


@pytest.mark.slow
@needs_node
def test_every_seed_step_renders_in_katex() -> None:
    latex = []
    for name in SEED_SCENES:
        for method in ("vector", "loop"):
            latex += all_latex(solve(scene_of(example(name)), method))
    assert len(latex) > 300
    assert run_katex(latex) == []


@pytest.mark.slow
@needs_node
@settings(max_examples=30, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(case=assemblable_presets())
def test_random_preset_steps_render_in_katex(
    katex: Katex, case: tuple[str, dict[str, float]]
) -> None:
    latex = []
    for method in ("vector", "loop"):
        latex += all_latex(solve(parse_linkage(build_preset(*case)), method))
    assert katex.failures(latex) == []


@pytest.mark.parametrize("name", list(PRESETS))
def test_textbook_presets_solve_with_both_methods(name: str) -> None:
    scene = parse_linkage(build_preset(name, {}))
    for method in ("vector", "loop"):
        solution = solve(scene, method)
        assert solution.method == method
        _check_solution(solution)


# ---- reading a solution: no noise, one symbol per angle, mistakes in place, shown arithmetic ---

SEEDS = sorted(
    p.stem for p in EXAMPLES.glob("*.json") if json.loads(p.read_text())["kind"] != "gear_train"
)
NUMBER = re.compile(r"-?\d+(?:\.\d+)?(?:(?: \\cdot | x )10\^\{?(-?\d+)\}?)?")
NOISE_RATIO = 1e-9  # a printed number this much smaller than the largest one is rounding noise


def solution_of(doc: dict[str, Any], method: str = "vector") -> Solution:
    scene = parse_linkage(doc) if doc["kind"] == "linkage" else parse_spatial_chain(doc)
    return solve(scene, method)


# The worked solutions read by the tests below, "<seed or preset>-<method>", each solved when a
# test first asks for it (``solution``), not when the module is collected (by every worker).
NAMES = [f"{n}-{method}" for method in ("vector", "loop") for n in (*SEEDS, *PRESETS)]


@functools.cache
def solution_named(name: str) -> Solution:
    """The worked solution ``name`` of ``NAMES``, solved once for this module's tests."""
    scene, method = name.rsplit("-", 1)
    return solution_of(example(scene) if scene in SEEDS else build_preset(scene, {}), method)


@pytest.fixture
def solution(name: str) -> Solution:
    """The worked solution named by the test's ``name`` parameter."""
    return solution_named(name)


def printed_numbers(text: str) -> list[float]:
    """Every number in a LaTeX or plain-text string, powers of ten included."""
    out = []
    for match in NUMBER.finditer(text):
        body = match.group(0)
        mantissa = re.split(r" \\cdot | x ", body)[0]
        exponent = int(match.group(1)) if match.group(1) else 0
        out.append(float(mantissa) * 10.0**exponent)
    return out


@pytest.mark.parametrize("name", NAMES)
def test_no_printed_number_is_rounding_noise(name: str, solution: Solution) -> None:
    """S003-T1 printed '- 5.55·10^-31·(-0.18, 0, 0)': omega^2 of a carrier that does not turn.
    A value at the rounding level is zero and is written 0."""
    texts = [s.latex for s in solution.steps] + [s.text for s in solution.steps]
    texts += [v.display for s in solution.steps for v in s.values.values()]
    texts += [m.text for m in solution.mistakes]
    numbers = [abs(x) for t in texts for x in printed_numbers(t) if x != 0.0]
    largest = max(numbers)
    tiny = [x for x in numbers if x < NOISE_RATIO * largest]
    assert not tiny, (name, tiny[:5], largest)


def test_the_noise_detector_can_fail() -> None:
    assert printed_numbers(r"- 5.55 \cdot 10^{-31} \cdot 2") == [5.55e-31, 2.0]
    assert printed_numbers("-5.55 x 10^-31 times r") == [-5.55e-31]


@pytest.mark.parametrize("method", ["vector", "loop"])
@pytest.mark.parametrize("name", ["S003-T1-translating-carrier", "S003-T2-rotating-carrier"])
def test_s003_results_show_the_moving_point_and_the_event_time(name: str, method: str) -> None:
    solution = solution_of(example(name), method)
    summary = solution.steps[-1]
    assert summary.kind == "summary"
    for field in ("position", "velocity", "acceleration"):
        assert any(v.source == ("moving_points", "M", field) for v in summary.values.values())
    assert r"\vec{v}_{M}" in summary.latex and "Moving point M" in summary.text
    event = next(s for s in solution.steps if s.kind == "relative.event")
    times = [
        r["expected"][0]["value"]
        for c in CASES
        if c["id"] == name
        for r in c["requests"]
        if r["endpoint"] == "POST /api/v1/events"
    ]
    # T1: M from O over the top to A (half a turn); T2: M back at its start (a full turn)
    wanted = times[0]
    shown = [v.value for k, v in event.values.items() if k.startswith("t_")]
    assert any(t == pytest.approx(wanted, abs=1e-9) for t in shown), (shown, wanted)
    assert f"{wanted:.4g}" in event.latex


def test_s003_t1_event_is_root_three() -> None:
    event = next(
        s
        for s in solution_of(example("S003-T1-translating-carrier")).steps
        if s.kind == "relative.event"
    )
    assert event.values["t_1"].value == pytest.approx(math.sqrt(3), abs=1e-12)


def test_s003_t1_states_only_the_events_within_its_semicircular_groove() -> None:
    """Seed 003 Task 1: M runs in a semicircular groove (sweep_deg 180) and leaves it at its end,
    s = pi R (t = sqrt 3 s, ERRATA); the full turn s = 2 pi R (t = sqrt 6 = 2.449 s) lies past
    the groove's end and is no event."""
    event = next(
        s
        for s in solution_of(example("S003-T1-translating-carrier")).steps
        if s.kind == "relative.event"
    )
    times = [v.value for k, v in event.values.items() if k.startswith("t_")]
    assert times == [pytest.approx(math.sqrt(3), abs=1e-12)]
    assert "back at" not in event.text and "2.449" not in event.latex
    assert "end of its semicircular groove" in event.text and "leaves it" in event.text


@pytest.mark.parametrize(
    ("sweep", "levels"),
    [(360.0, [1.0, 2.0]), (270.0, [1.0, 1.5]), (180.0, [1.0]), (90.0, [0.5])],
)
def test_arc_events_lie_within_the_arc(sweep: float, levels: list[float]) -> None:
    """s / (pi R) of the events: never past the arc's end (sweep_deg / 180)."""
    assert [k for k, _ in arc_events(sweep, "S")] == levels


@pytest.mark.parametrize("sweep", [0, -90, 361, "180"])
def test_an_arc_sweep_outside_0_to_360_degrees_is_refused(sweep: Any) -> None:
    doc = example("S003-T1-translating-carrier")
    doc["moving_points"][0]["path"]["sweep_deg"] = sweep
    with pytest.raises(InvalidScene, match="sweep_deg"):
        parse_linkage(doc)


def test_spatial_chain_computes_each_point_once_and_speaks_of_space() -> None:
    solution = solution_of(example("S002-spatial-arm"))
    velocities = [s for s in solution.steps if s.kind.endswith("velocity")]
    results = [
        tuple(round(x, 12) for x in v.value)  # type: ignore[union-attr]
        for s in velocities
        for k, v in s.values.items()
        if k.startswith("v(")
        and k.endswith(")")
        and v.display != "(0, 0, 0) m/s"
        and k in {f"v({p})" for p in ("O2", "A", "B")} | {f"v(O{j})" for j in "123"}
        and s.title.split(" ")[2].rstrip(":") in k
    ]
    assert len(results) == len(set(results)), [s.title for s in velocities]
    titles = [s.title for s in solution.steps]
    assert "Velocity of A (the origin O3 of joint 3)" in titles
    assert not any("joint origin O3" in t or "joint origin O2" in t for t in titles)
    assert "page" not in solution.convention and "E1, E2, E3" in solution.convention
    assert "z out of the page" in solution_of(example("S000-T1")).convention


def test_all_revolute_dyad_is_not_a_relative_connection() -> None:
    solution = solution_of(example("S000-T1"))
    solve_steps = [s for s in solution.steps if s.kind.endswith("dyad.solve")]
    assert solve_steps and all("relative connection" not in s.title for s in solve_steps)
    t3 = solution_of(example("S000-T3"))  # a slider: geometric = relative connection
    assert any("relative connection" in s.title for s in t3.steps if s.kind.endswith(".solve"))


@pytest.mark.parametrize("name", ["slider_crank", "inverted_slider_crank", "quick_return"])
def test_loop_with_a_slider_does_not_call_every_length_constant(name: str) -> None:
    solution = solution_of(build_preset(name, {}), "loop")
    loop = [s for s in solution.steps if s.kind in ("loop.velocity", "loop.acceleration")]
    assert loop
    for step in loop:
        assert "lengths of links are constant" not in step.text
        assert "slider's s varies" in step.text


@pytest.mark.parametrize("name", ["inverted_slider_crank", "quick_return"])
def test_one_symbol_per_angle_of_a_turning_slot(name: str) -> None:
    """Not phi3 in the text and beta3 in the LaTeX: a turning slot's angle is beta everywhere."""
    solution = solution_of(build_preset(name, {}), "loop")
    for step in solution.steps:
        if not step.kind.startswith("loop"):
            continue
        for n in re.findall(r"\\beta_\{(\d+)\}", step.latex):
            assert f"phi{n}" not in step.text and f"phi{n}" not in step.values, step.title
        for n in re.findall(r"\\varphi_\{(\d+)\}", step.latex):
            assert f"beta{n}" not in step.text, step.title


# --- typical mistakes under their step ------------------------------------------------------------


@pytest.mark.parametrize("name", NAMES)
def test_every_mistake_names_an_existing_step(name: str, solution: Solution) -> None:
    for mistake in solution.mistakes:
        assert mistake.step is not None, (name, mistake.kind)
        assert 0 <= mistake.step < len(solution.steps), (name, mistake.kind)
        assert mistake.as_json()["step"] == mistake.step
        if solution.method == "loop":  # in loop mode, only loop-method mistakes
            assert solution.steps[mistake.step].kind.startswith(("loop.", "relative.")), (
                name,
                mistake.kind,
                solution.steps[mistake.step].kind,
            )


def test_vector_mistakes_are_all_placed() -> None:
    """No mistake of the vector method is lost by placing it (each finds its step)."""
    from solver.analysis.instant import analyze
    from solver.solutions.format import Formatter
    from solver.solutions.linkage import LinkageContext, unit_scales
    from solver.solutions.mistakes import linkage_mistakes

    for name in SEEDS:
        doc = example(name)
        if doc["kind"] != "linkage":
            continue
        scene = parse_linkage(doc)
        analysis = analyze(scene)
        ctx = LinkageContext(scene, analysis, Formatter(4, unit_scales(analysis, scene.size)))
        listed = {m.kind for m in linkage_mistakes(ctx)}
        assert {m.kind for m in solve(scene).mistakes} == listed, name


@pytest.mark.parametrize(
    ("name", "kind", "step_kind", "title_part"),
    [
        ("S000-T1", "normal.sign", "acceleration.rigid", "of B ("),
        ("S000-T1", "cross.order", "velocity.rigid", "of B ("),
        ("S000-T1", "unknowns.which_link", "velocity.dyad.side", "coupler"),
        ("S000-T2", "coriolis_without_factor_2", "acceleration.coriolis", "B"),
        ("S000-T3", "coriolis_on_fixed_guide", "acceleration.coriolis", "C"),
        ("S003-T2-rotating-carrier", "relative.carrier_rate", "relative.relative_velocity", "M"),
        ("S003-T1-translating-carrier", "coriolis.translating_carrier", "relative.coriolis", ""),
        ("S002-spatial-arm", "spatial.axis_rate", "spatial.alpha", "body 2"),
    ],
)
def test_mistakes_sit_under_the_step_they_belong_to(
    name: str, kind: str, step_kind: str, title_part: str
) -> None:
    solution = solution_of(example(name))
    mistake = next(m for m in solution.mistakes if m.kind == kind)
    assert mistake.step is not None
    step = solution.steps[mistake.step]
    assert step.kind == step_kind and title_part in step.title, (step.kind, step.title)


def test_loop_mode_lists_only_loop_mistakes() -> None:
    vector = {m.kind for m in solution_of(example("S000-T1")).mistakes}
    loop = {m.kind for m in solution_of(example("S000-T1"), "loop").mistakes}
    assert "normal.sign" in vector and "normal.sign" not in loop
    assert "loop.derivative_i" in loop


def _mistake(name: str, kind: str) -> Any:
    return next(m for m in solution_of(example(name)).mistakes if m.kind == kind)


def test_errata_mistakes_with_their_wrong_numbers() -> None:
    """ERRATA.md: E003-1 (tangential relative acceleration reversed: (-0.3265, -0.1885) for
    (+0.3265, +0.1885)), E000-T2-4 (alpha squared in the normal term), E000-T1-5 (the pole from
    another point's velocity: P = (2, 5) instead of (0, 5)), E000-T2-6 (x = 0.346 rounded to
    0.35), and a trigonometry slip in the position (crank2 of S003-T1 at 30 deg, not 60)."""
    sense = _mistake("S003-T1-translating-carrier", "relative.tangential_sense")
    wrong, right = (np.array(sense.values[k].value) for k in ("wrong", "right"))
    np.testing.assert_allclose(wrong - right, [-2 * 0.32648, -2 * 0.18850], atol=1e-4)
    squared = _mistake("S000-T2", "normal.alpha_squared")
    np.testing.assert_allclose(squared.values["right"].value, [0.78564, -1.83923], atol=1e-5)
    r_cb = np.array([-math.sqrt(0.12), 0.2])  # B - C, crank 0.4 m
    np.testing.assert_allclose(
        np.array(squared.values["wrong"].value) - squared.values["right"].value,
        -(3.0**2 - 2.0**2) * r_cb,
        atol=1e-9,
    )
    pole = _mistake("S000-T1", "poles.wrong_velocity")
    np.testing.assert_allclose(pole.values["wrong"].value, [2.0, 5.0], atol=1e-12)
    np.testing.assert_allclose(pole.values["right"].value, [0.0, 5.0], atol=1e-12)
    rounding = _mistake("S000-T2", "inputs.rounding")
    assert rounding.values["wrong"].value == pytest.approx(0.35, abs=1e-12)
    assert rounding.values["right"].value == pytest.approx(math.sqrt(0.12), abs=1e-12)
    trig = _mistake("S003-T1-translating-carrier", "position.trigonometry")
    assert trig.values["right"].value == pytest.approx(30.0, abs=1e-9)
    assert trig.values["wrong"].value == pytest.approx(60.0, abs=1e-9)


# --- the shown arithmetic recomputes from the shown numbers -----------------------------------

_DISPLAY_NUMBER = re.compile(r"-?\d+(?:\.\d+)?(?: x 10\^-?\d+)?")


def shown_number(display: str) -> tuple[np.ndarray, np.ndarray]:
    """The numbers of a display string ('(-0.1571, 0.2721) m/s', '1.5 x 10^-7 m', '30 deg')
    and one unit in the last digit of each."""
    body = display.split(")")[0] if display.startswith("(") else display.split(" ")[0]
    if " x 10^" in display and not display.startswith("("):
        body = " ".join(display.split(" ")[:3])
    numbers, ulps = [], []
    for text in _DISPLAY_NUMBER.findall(body):
        mantissa, _, exponent = text.partition(" x 10^")
        power = int(exponent) if exponent else 0
        decimals = len(mantissa.split(".")[1]) if "." in mantissa else 0
        numbers.append(float(mantissa) * 10.0**power)
        if float(mantissa) == 0.0:
            ulps.append(0.0)
        elif decimals:
            ulps.append(10.0 ** (power - decimals))
        else:  # an integer: its last significant digit
            digits = mantissa.lstrip("-")
            ulps.append(10.0 ** (power + len(digits) - len(digits.rstrip("0"))))
    return np.array(numbers), np.array(ulps)


def _relation(relation: str, ops: list[np.ndarray], factor: float) -> tuple[np.ndarray, float]:
    size = [float(np.linalg.norm(o)) for o in ops]

    def perp(a: np.ndarray) -> np.ndarray:
        return np.array([-a[1], a[0]])

    if relation == "sum":
        value, scale = np.sum(np.broadcast_arrays(*ops), axis=0), sum(size)
    elif relation == "cross":
        a, b = ops
        if a.size == 1:
            value = a[0] * perp(b)
        elif a.size == 2:
            value = np.array([a[0] * b[1] - a[1] * b[0]])
        else:
            value = np.cross(a, b)
        scale = size[0] * size[1]
    elif relation == "product":
        value, scale = np.prod(np.broadcast_arrays(*ops), axis=0), math.prod(size)
    elif relation == "quotient":
        value, scale = ops[0] / ops[1], size[0] / size[1]
    elif relation == "det2":
        value, scale = ops[0] * ops[3] - ops[1] * ops[2], size[0] * size[3] + size[1] * size[2]
    elif relation == "linear":
        value = sum(ops[k] * ops[k + 1] for k in range(0, len(ops), 2))
        scale = sum(size[k] * size[k + 1] for k in range(0, len(ops), 2))
    elif relation == "dot":
        value, scale = np.array([np.dot(ops[0], ops[1])]), size[0] * size[1]
    elif relation in ("phasor", "iphasor"):
        e = np.array([math.cos(ops[-1][0]), math.sin(ops[-1][0])])
        value = np.prod(np.broadcast_arrays(*ops[:-1]), axis=0) * (
            e if relation == "phasor" else perp(e)
        )
        scale = math.prod(size[:-1])
    elif relation == "angle":
        value, scale = np.array([math.atan2(ops[0][1], ops[0][0])]), math.pi
    else:
        assert relation == "norm"
        value, scale = np.array([np.linalg.norm(ops[0])]), size[0]
    return factor * np.asarray(value, float), abs(factor) * scale


def unrecomputable(step: Any) -> list[str]:
    """The checks of a step whose result, recomputed from the operands as displayed, differs
    from the result as displayed by more than 0.6 unit in its last digit."""
    shown = {k: shown_number(v.display) for k, v in step.values.items()}
    failures = []

    def get(name: str) -> tuple[np.ndarray, np.ndarray]:
        sign = -1.0 if name.startswith("-") else 1.0
        key = name.lstrip("-")
        match = re.fullmatch(r"(.*)\[(\d)\]", key)
        if match and match.group(1) in shown:
            numbers, ulps = shown[match.group(1)]
            i = int(match.group(2))
            return sign * numbers[i : i + 1], ulps[i : i + 1]
        numbers, ulps = shown[key]
        return sign * numbers, ulps

    for check in step.checks:
        if check.relation == "linear":  # an equation in the unknowns, not shown arithmetic
            continue
        ops = [get(o.name)[0] for o in check.operands]
        value, scale = _relation(check.relation, ops, check.factor)
        result, ulps = get(check.result.name)
        diff = value - result
        if check.relation == "angle":
            diff = (diff + math.pi) % (2 * math.pi) - math.pi
        floor = float(np.max(ulps)) if np.any(ulps) else 0.0
        if floor == 0.0:  # the result is shown as 0: the last digit of the terms' size
            floor = 10.0 ** (math.floor(math.log10(scale)) - 3) if scale > 0 else 0.0
        tolerance = 0.6 * np.maximum(ulps, floor) * (1 + 1e-9) + 1e-12 * scale
        if np.any(np.abs(diff) > tolerance):
            failures.append(
                f"{step.kind} '{step.title}': {check.result} = {check.relation}"
                f"{check.operands}: shown {result}, recomputed {value}"
            )
    return failures


def test_shown_number_parses_displays() -> None:
    numbers, ulps = shown_number("(-0.1571, 0.2721) m/s")
    np.testing.assert_allclose(numbers, [-0.1571, 0.2721])
    np.testing.assert_allclose(ulps, [1e-4, 1e-4])
    numbers, ulps = shown_number("1.5 x 10^-7 m")
    np.testing.assert_allclose(numbers, [1.5e-7])
    np.testing.assert_allclose(ulps, [1e-8])
    numbers, ulps = shown_number("12350 m")
    np.testing.assert_allclose(ulps, [10.0])


@pytest.mark.parametrize("name", NAMES)
def test_shown_arithmetic_recomputes_to_the_shown_digits(name: str, solution: Solution) -> None:
    """-0.03125/0.0127 must not read -2.462: each check, evaluated with its operands as they are
    displayed, gives its result as displayed (to 0.6 unit in the last digit)."""
    failures = [f for step in solution.steps for f in unrecomputable(step)]
    assert not failures, (name, failures[:3])


def significant_digits(number: float, ulp: float) -> int:
    """The significant digits of a shown number, from the unit in its last digit."""
    return math.floor(math.log10(abs(number))) - round(math.log10(ulp)) + 1


def mixed_precision(step: Any) -> list[str]:
    """The checks whose operands are shown at different precisions: with D the most significant
    digits any operand shows, an operand shown with fewer is wrong unless its number rounded to
    D digits is what it shows (trailing zeros are dropped: 0.15 at four digits)."""
    shown = {k: shown_number(v.display) for k, v in step.values.items()}
    exact = {k: np.atleast_1d(np.asarray(v.value, float)) for k, v in step.values.items()}
    failures = []
    for check in step.checks:
        if check.relation == "linear":
            continue
        keys = {o.ref.key for o in check.operands}
        numbers = [
            (key, float(x), float(u), float(e))
            for key in keys
            for x, u, e in zip(*shown[key], exact[key], strict=False)
            if x != 0.0 and u > 0.0
        ]
        if not numbers:
            continue
        most = max(significant_digits(x, u) for _, x, u, _ in numbers)
        for key, x, _, e in numbers:
            if float(f"{e:.{most - 1}e}") != pytest.approx(x, rel=1e-12):
                failures.append(f"{step.kind} '{step.title}': {key} = {x} beside {most} digits")
    return failures


@pytest.mark.parametrize("name", NAMES)
def test_the_operands_of_a_check_are_shown_at_one_precision(name: str, solution: Solution) -> None:
    """0.347195^2 beside 1.582 in one product: the factors of one piece of shown arithmetic
    (a product, a sum, a quotient) have one count of significant digits."""
    failures = [f for step in solution.steps for f in mixed_precision(step)]
    assert not failures, (name, failures[:3])


SQUARED_FACTOR = re.compile(r"(\d|\))\^\{?2\}?\s*(\\cdot|\\,|\\begin|\()")


@pytest.mark.parametrize("name", NAMES)
def test_omega_squared_is_a_value_of_its_own(name: str, solution: Solution) -> None:
    """'- 0.347195^2 . (0.77165, -0.21108)': no line multiplies a squared number by another;
    omega^2 is written once (omega_3^2 = 0.3472^2 = 0.1205) and that value multiplies r."""
    squared = [
        (step.kind, line)
        for step in solution.steps
        for line in step.latex.split(r"\\")
        if SQUARED_FACTOR.search(line)
    ]
    assert not squared, (name, squared[:2])
    assert SQUARED_FACTOR.search(r"- 0.347195^2 \cdot \begin{pmatrix}")


def test_the_precision_check_can_fail() -> None:
    """The issue's line: omega = 0.347195 (six digits) times r = 1.582 (four)."""
    from solver.solutions.equation import Ref
    from solver.solutions.model import Check, Step, Value

    step = Step(
        "x",
        "x",
        "",
        "",
        {
            "w": Value(0.34719529, "rad/s", "0.347195 rad/s"),
            "r": Value(1.58213, "m", "1.582 m"),
            "n": Value(0.34719529**2 * 1.58213, "m/s^2", "0.1907 m/s^2"),
        },
        (Check("product", Ref("n").operand, tuple(Ref(k).operand for k in "wwr")),),
    )
    assert mixed_precision(step)
    assert significant_digits(0.15, 0.01) == 2


def test_the_recompute_check_can_fail() -> None:
    """The issue's example: 0.0127 shown with four digits makes -0.03125/0.0127 = -2.461."""
    from solver.solutions.equation import Ref
    from solver.solutions.model import Check, Step, Value

    step = Step(
        "x",
        "x",
        "",
        "",
        {
            "n": Value(-0.03125, "", "-0.03125"),
            "d": Value(0.012695, "", "0.0127"),
            "q": Value(-0.03125 / 0.012695, "", "-2.462"),
        },
        (Check("quotient", Ref("q").operand, (Ref("n").operand, Ref("d").operand)),),
    )
    assert unrecomputable(step)


# --- reading the answer -------------------------------------------------------------------------


def reading(solution: Solution) -> Any:
    return next(s for s in solution.steps if s.kind == "reading")


def test_reading_the_answer_in_words() -> None:
    """S000-T3: coupler omega = -1.44 (clockwise), alpha = +7.68 (counter-clockwise): slowing
    down; C slides to the right (v_C = 0.96 m/s) and speeds up (a_C = 1.8432 m/s^2). S000-T1: the
    crank (omega = alpha = -1) speeds up."""
    t3 = reading(solution_of(example("S000-T3")))
    assert "omega clockwise, alpha counter-clockwise: link coupler is slowing down" in t3.text
    assert "C slides to the right, speeding up" in t3.text
    t1 = reading(solution_of(example("S000-T1")))
    assert "omega clockwise, alpha clockwise: link crank is speeding up" in t1.text
    m = reading(solution_of(example("S003-T2-rotating-carrier")))
    assert "M moves to the right and down" in m.text and "slowing down" in m.text


@pytest.mark.parametrize("name", NAMES)
def test_units_on_every_line_and_no_signed_speed(name: str, solution: Solution) -> None:
    for step in solution.steps:
        if step.kind == "reading":
            for line in step.latex.split(r" \\ "):
                assert r"\mathrm{" in line, (name, line)
        for match in re.finditer(r"speed (?:of |is |= )?(-?[\d.]+)", step.text):
            assert float(match.group(1)) >= 0, (name, step.title, match.group(0))
        assert "sliding speed" not in step.text and "the speed of" not in step.text, name


# --- new step kinds -----------------------------------------------------------------------------


@pytest.mark.parametrize("name", NAMES)
def test_step_kinds_present(name: str, solution: Solution) -> None:
    kinds = {s.kind for s in solution.steps}
    if "spatial" in name:
        assert {"spatial.omega", "spatial.point.acceleration", "summary"} <= kinds
        return
    assert {
        "positions",
        "graphical.velocity",
        "graphical.acceleration",
        "instant_centres",
        "reading",
        "summary",
    } <= kinds, name
    # four-bars (Grashof) and slider mechanisms (dead centres, issue 29) are classified
    sliding = bool(solution.analysis.joints)
    assert ("classification" in kinds) == bool(solution.analysis.four_bar_loops or sliding), name
    assert "position.crank" in kinds, name
    dyads = [s for s in solution.analysis.plan.steps if type(s).__name__ == "DyadStep"]
    if dyads:
        assert kinds & {"position.triangle", "position.slider"}, name
    centres = next(s for s in solution.steps if s.kind == "instant_centres")
    assert "Not found" not in centres.text, (name, centres.text)


def test_classification_of_the_four_bar_preset_against_a_brute_force_cycle() -> None:
    """ground 1, crank 0.15, coupler 1, rocker 0.55 m: 0.15 + 1 < 1 + 0.55, a crank-rocker; mu
    over a full turn, sampled every 0.01 deg from the geometry, has the extremes shown."""
    solution = solution_of(build_preset("four_bar", {}))
    step = next(s for s in solution.steps if s.kind == "classification")
    assert "Grashof crank-rocker" in step.latex and "s + l < p + q" in step.text
    g, a, b, c = 1.0, 0.15, 1.0, 0.55
    theta = np.radians(np.arange(0.0, 360.0, 0.01))
    diagonal = np.hypot(a * np.cos(theta) - g, a * np.sin(theta))
    mu = np.degrees(np.arccos((b * b + c * c - diagonal**2) / (2 * b * c)))
    shown_min = math.degrees(step.values["mu_min"].value)
    shown_max = math.degrees(step.values["mu_max"].value)
    assert shown_min == pytest.approx(float(mu.min()), abs=1e-6)
    assert shown_max == pytest.approx(float(mu.max()), abs=1e-6)
    assert step.values["mu"].source == ("four_bar_loops", 0, "transmission_angle")
    t1 = next(s for s in solution_of(example("S000-T1")).steps if s.kind == "classification")
    assert "non-Grashof triple-rocker" in t1.latex and "does not turn fully" in t1.text


@pytest.mark.parametrize(
    ("name", "pair", "where"),
    [
        ("S000-T1", "P13", [0.0, 5.0]),  # E000-T1-5: P_2 = (0, 5)
        ("S000-T3", "P13", [0.32, -0.42667]),  # the coupler's pole, on the slot's normal at C
        ("S000-T4", "P13", [0.90561, 1.42701]),  # E000-T4-5: P_2
    ],
)
def test_kennedy_gives_the_textbook_poles(name: str, pair: str, where: list[float]) -> None:
    step = next(s for s in solution_of(example(name)).steps if s.kind == "instant_centres")
    np.testing.assert_allclose(step.values[pair].value, where, atol=1e-5)
    assert "velocity pole of link coupler found analytically" in step.text


def test_position_of_seed_000_type_1_by_the_law_of_cosines() -> None:
    """B = (0, 1), D = (2.5, 0), BC = 2, DC = sqrt(1.25): BD = sqrt(7.25), cos gamma =
    (4 + 7.25 - 1.25) / (2 * 2 * sqrt(7.25)), and C = (2, 1) above BD, as drawn."""
    step = next(s for s in solution_of(example("S000-T1")).steps if s.kind == "position.triangle")
    assert step.values["cos gamma"].value == pytest.approx(10 / (4 * math.sqrt(7.25)), rel=1e-12)
    np.testing.assert_allclose(step.values["pos(C)"].value, [2.0, 1.0], atol=1e-12)
    assert "C on the left of BD, as drawn" in step.text


def test_loop_method_has_the_poles_and_says_the_equivalence_once() -> None:
    solution = solution_of(example("S000-T1"), "loop")
    assert solution.method == "loop"
    poles = [s for s in solution.steps if s.kind == "poles.velocity"]
    coupler = next(s for s in poles if "coupler" in s.title)
    np.testing.assert_allclose(coupler.values["P(coupler)"].value, [0.0, 5.0], atol=1e-12)
    said = [s for s in solution.steps if "both methods solve the same two equations" in s.text]
    assert len(said) == 1 and said[0].kind == "loop.velocity"


@pytest.mark.parametrize("name", ["S001-offset-slider-crank", "S000-T4"])
def test_slider_crank_loop_position_in_closed_form(name: str) -> None:
    """Seed 001's form: the imaginary part gives theta13, the real part s14 (the guide's frame)."""
    solution = solution_of(example(name), "loop")
    step = next(s for s in solution.steps if s.kind == "position.loop")
    loop = next(s for s in solution.steps if s.kind == "loop.position")
    for key in ("s14", "theta13"):
        assert step.values[key].value == loop.values[key].value
    assert r"\text{Im: }" in step.latex and r"\text{Re: }" in step.latex
    assert "the assembly as drawn" in step.text

"""The worked solution of a cam (issue 24, ``solver.solutions.cam``): every number against the
solver's /analyze body and against closed forms (Norton, Design of Machinery, ch. 8), the shown
arithmetic recomputes, and the fundamental law is judged as the warnings judge it."""

from __future__ import annotations

import math
from typing import Any

import numpy as np
import pytest

import solver
from solver.cams import LAW_NAMES, LAWS
from solver.errors import InvalidScene
from solver.teaching.cam_presets import CAM_PRESETS
from tests.solver.cams.test_cams import BETA_DEG, FOLLOWERS, OMEGA, H, scene
from tests.solver.solutions.test_solve import run_katex, unit_floors, unrecomputable, verify

ANGLES = (0.0, 17.0, 60.0, 100.0, 120.0, 150.0, 233.3, 299.0, 330.0)


def _solution(doc: dict[str, Any], angle: float, digits: int = 4) -> dict[str, Any]:
    body: dict[str, Any] = solver.solve(doc, digits=digits, angle_deg=angle).as_dict()
    return body


def _step(body: dict[str, Any], kind: str) -> dict[str, Any]:
    return next(s for s in body["steps"] if s["kind"] == kind)


def _at(body: dict[str, Any], source: list[str | int]) -> Any:
    node: Any = body
    for part in source:
        node = node[part]
    return node


def _cases() -> list[tuple[str, dict[str, Any]]]:
    cases = []
    for name, (follower, lift) in FOLLOWERS.items():
        for law in LAW_NAMES:
            cases.append((f"{name}-{law}", scene(law, law, follower, lift=lift)))
    cases.append(("clockwise-knife", scene(follower=FOLLOWERS["knife"][0], omega=-7.0)))
    cases.append(("clockwise-oscillating", scene(follower=FOLLOWERS["oscillating_roller"][0],
                                                 omega=-7.0, lift=0.3)))  # fmt: skip
    return cases


CASES = _cases()


@pytest.mark.parametrize(("name", "doc"), CASES, ids=[c[0] for c in CASES])
def test_every_number_with_a_source_is_the_solvers_and_the_arithmetic_recomputes(
    name: str, doc: dict[str, Any]
) -> None:
    """At nine cam angles (segment boundaries among them): each value that names a path of the
    /analyze body is that body's number, every check holds, and shown with its digits each
    check's arithmetic gives the shown result."""
    for angle in ANGLES:
        body = _solution(doc, angle)
        analyzed = solver.analyze(doc, angle_deg=angle).as_dict()
        assert body["results"] == analyzed
        assert body["method"] == body["requested_method"] == "cam"
        floors = unit_floors(body["steps"])
        for step in body["steps"]:
            assert not verify(step, floors), (name, angle, verify(step, floors)[:2])
            for key, value in step["values"].items():
                if value["source"] is not None:
                    assert value["value"] == _at(analyzed, value["source"]), (name, key)
        typed = solver.solutions.solve(solver.parse_scene(doc), angle_deg=angle)
        failures = [f for step in typed.steps for f in unrecomputable(step)]
        assert not failures, (name, angle, failures[:2])


@pytest.mark.parametrize("law", LAW_NAMES)
@pytest.mark.parametrize("angle", [0.0, 10.0, 30.0, 45.0, 60.0, 77.0, 105.0, 119.0])
def test_the_law_written_out_gives_the_laws_values(law: str, angle: float) -> None:
    """y, y', y'', y''' of the law step equal the law's closed form at x = theta / beta (every
    piece of the modified trapezoid and sine is met)."""
    step = _step(_solution(scene(law, law), angle), "cam.law")
    values = {k: v["value"] for k, v in step["values"].items()}
    x = angle / BETA_DEG
    assert values["x"] == pytest.approx(x, rel=1e-14, abs=1e-15)
    expected = LAWS[law](np.array([x]))
    for key, exact in zip(("y", "y'", "y''", "y'''"), expected, strict=True):
        assert values[key] == pytest.approx(float(exact[0]), rel=1e-12, abs=1e-12), key


def test_cycloidal_rise_at_mid_segment_against_the_closed_forms() -> None:
    """x = 1/2 of a cycloidal rise: s = h/2, v = 2 h omega / beta (the peak), a = 0,
    j = -4 pi^2 h omega^3 / beta^3 (Norton eq. 8.6)."""
    body = _solution(scene(), 60.0)
    motion = {k: v["value"] for k, v in _step(body, "cam.motion")["values"].items()}
    beta = math.radians(BETA_DEG)
    assert motion["s"] == pytest.approx(H / 2, rel=1e-14)
    assert motion["v"] == pytest.approx(2 * H * OMEGA / beta, rel=1e-14)
    assert motion["a"] == pytest.approx(0.0, abs=1e-12)
    assert motion["j"] == pytest.approx(-4 * math.pi**2 * H * OMEGA**3 / beta**3, rel=1e-12)
    assert "0.2387" in _step(body, "cam.motion")["text"]


def test_pressure_angle_and_radius_against_nortons_formulas() -> None:
    """The offset roller at 60 deg: phi = arctan((s' - e)/(sqrt(R_p^2 - e^2) + s)) (eq. 8.31);
    without offset rho_p = ((R_p + s)^2 + s'^2)^(3/2) / ((R_p + s)^2 + 2 s'^2 - (R_p + s) s'')
    (eq. 8.33), rho = rho_p - r."""
    beta = math.radians(BETA_DEG)
    for offset, angle in ((0.005, 60.0), (0.0, 40.0), (0.0, 200.0)):
        follower = {"motion": "translating", "contact": "roller", "roller_radius": 0.01,
                    "offset": offset}  # fmt: skip
        body = _solution(scene(follower=follower), angle)
        phi = _step(body, "cam.pressure_angle")["values"]["phi"]["value"]
        rho = _step(body, "cam.curvature")["values"]
        x = angle / BETA_DEG if angle < 120 else (angle - 180.0) / BETA_DEG
        law = LAWS["cycloidal" if angle < 120 else "polynomial_345"](np.array([x]))
        sign = 1.0 if angle < 120 else -1.0
        s = H * float(law.y[0]) if angle < 120 else H - H * float(law.y[0])
        ds, d2s = sign * H * float(law.dy[0]) / beta, sign * H * float(law.d2y[0]) / beta**2
        rp = 0.05
        assert phi == pytest.approx(math.atan((ds - offset) / (math.sqrt(rp**2 - offset**2) + s)))
        if offset == 0.0:
            r = rp + s
            norton = (r**2 + ds**2) ** 1.5 / (r**2 + 2 * ds**2 - r * d2s)
            assert rho["rho_p"]["value"] == pytest.approx(norton, rel=1e-12)
            assert rho["rho"]["value"] == pytest.approx(norton - 0.01, rel=1e-12)


def test_flat_face_radius_is_nortons_8_37() -> None:
    """rho = R_b + s + s'' under a translating flat face, and phi = 0."""
    doc = scene(follower={"motion": "translating", "contact": "flat"})
    body = _solution(doc, 50.0)
    x = 50.0 / BETA_DEG
    law = LAWS["cycloidal"](np.array([x]))
    beta = math.radians(BETA_DEG)
    expected = 0.04 + H * float(law.y[0]) + H * float(law.d2y[0]) / beta**2
    assert _step(body, "cam.curvature")["values"]["rho"]["value"] == pytest.approx(expected)
    assert _step(body, "cam.pressure_angle")["values"]["phi"]["value"] == 0.0


def test_the_fundamental_law_step_names_the_jumps_the_warnings_name() -> None:
    """A harmonic rise into a dwell: the acceleration jumps at 120 deg (and at 0 deg), as the
    warnings say; a cycloidal rise is continuous at both ends."""
    harmonic = _solution(scene("harmonic", "harmonic"), 30.0)
    text = _step(harmonic, "cam.fundamental_law")["text"]
    assert "a at 0 deg" in text and "a at 120 deg" in text and "(a jump)" in text
    assert any("discontinuous acceleration at cam angle 120 deg" in w
               for w in harmonic["warnings"])  # fmt: skip
    smooth = _step(_solution(scene(), 30.0), "cam.fundamental_law")["text"]
    assert "continuous at both boundaries" in smooth and "jump" not in smooth
    uniform = _step(_solution(scene("uniform", "uniform"), 30.0), "cam.fundamental_law")["text"]
    assert "v at 0 deg" in uniform and "v at 120 deg" in uniform


def test_a_dwell_is_written_as_rest() -> None:
    body = _solution(scene(), 150.0)
    kinds = [s["kind"] for s in body["steps"]]
    assert "cam.law" not in kinds
    assert "s = s_0 = 0.025 m" in _step(body, "cam.motion")["text"]
    assert body["mistakes"] == []


def test_the_figure_shows_the_cam_the_follower_and_the_pressure_angle() -> None:
    for name, preset in CAM_PRESETS.items():
        body = _solution(preset.build({}), 45.0)
        figure = body["steps"][0]["figure"]
        assert figure.startswith("<svg") and 'data-kind="cam"' in figure, name
        assert 'data-vector="normal"' in figure and 'data-vector="motion"' in figure
        assert "phi = " in figure and "<script" not in figure


def test_mistakes_give_the_chain_rule_left_out_and_beta_in_degrees() -> None:
    body = _solution(scene(), 60.0)
    mistakes = {m["kind"]: m for m in body["mistakes"]}
    v = 2 * H * OMEGA / math.radians(BETA_DEG)
    assert mistakes["cam_omega_left_out"]["values"]["wrong"]["value"] == pytest.approx(v / OMEGA)
    wrong = mistakes["cam_beta_in_degrees"]["values"]["wrong"]["value"]
    assert wrong == pytest.approx(v * math.radians(BETA_DEG) / BETA_DEG)
    motion = [s["kind"] for s in body["steps"]].index("cam.motion")
    assert {m["step"] for m in body["mistakes"]} == {motion}


def test_angle_deg_belongs_to_a_cam() -> None:
    linkage = {
        "kind": "linkage",
        "points": {"A": [0, 0], "B": [0, 1], "C": [2, 1], "D": [2.5, 0]},
        "links": {"ground": {"points": ["A", "D"], "ground": True},
                  "crank": {"points": ["A", "B"]}, "coupler": {"points": ["B", "C"]},
                  "rocker": {"points": ["D", "C"]}},
        "joints": [{"type": "revolute", "point": p, "links": pair} for p, pair in
                   (("A", ["ground", "crank"]), ("B", ["crank", "coupler"]),
                    ("C", ["coupler", "rocker"]), ("D", ["rocker", "ground"]))],
        "drivers": [{"link": "crank", "omega": -1.0, "alpha": -1.0}],
    }  # fmt: skip
    with pytest.raises(InvalidScene, match="angle_deg"):
        solver.solve(linkage, angle_deg=30.0)
    with pytest.raises(InvalidScene, match="angle_deg"):
        solver.solve(scene(), angle_deg=math.inf)


def test_every_step_typesets_with_katex() -> None:
    """The LaTeX of every step, for every law and follower preset at angles in each segment,
    compiles with the vendored KaTeX (tests/katex_check.mjs, throwOnError)."""
    latex = []
    for preset in CAM_PRESETS.values():
        for law in range(len(LAW_NAMES)):
            doc = preset.build({"rise_law": law, "return_law": law})
            for angle in (0.0, 30.0, 150.0, 200.0):
                latex += [s["latex"] for s in _solution(doc, angle)["steps"]]
    assert not run_katex(latex)

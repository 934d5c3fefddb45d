"""The worked solution by Newton-Euler (POST /api/v1/solution, method newton_euler): every step's
checks re-evaluate, every number with a source is the /analyze number (the results carry forces
and energy), seed 004's torque and joint forces are the reference's, and the free-body diagrams
are well-formed SVG with one arrow per force."""

from __future__ import annotations

import cmath
import math
import xml.etree.ElementTree as ET
from typing import Any

import numpy as np
import pytest
from fastapi.testclient import TestClient
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from solver.solutions.free_body import FONT, label_width
from tests.dynamics_cases import (
    EXPECTED,
    five_bar_points,
    five_bar_topology,
    seed004_scene,
    with_masses_and_loads,
)
from tests.linkage_strategies import linkages
from tests.solver.solutions.test_solve import unit_floors, verify


def at_path(body: Any, path: list[Any]) -> Any:
    for key in path:
        body = body[key]
    return body


def solve(client: TestClient, scene: dict[str, Any]) -> Any:
    response = client.post("/api/v1/solution", json={"scene": scene, "method": "newton_euler"})
    assert response.status_code == 200, response.text
    return response.json()


def check(body: Any, method: str = "newton_euler") -> None:
    """Every step's checks re-evaluate and every number with a source is the response's."""
    assert body["method"] == method
    floors = unit_floors(body["steps"])
    for step in body["steps"]:
        assert not verify(step, floors), (step["title"], verify(step, floors)[:3])
        for key, value in step["values"].items():
            if value["source"] is not None:
                reported = at_path(body["results"], value["source"])
                assert np.allclose(value["value"], reported, rtol=1e-15, atol=0), (
                    key,
                    step["title"],
                )


def test_seed004_by_newton_euler(client: TestClient) -> None:
    body = solve(client, seed004_scene(90))
    check(body)
    kinds = [s["kind"] for s in body["steps"]]
    for kind in (
        "dynamics.data",
        "dynamics.center_acceleration",
        "dynamics.free_body",
        "dynamics.equations",
        "dynamics.system",
        "dynamics.solution",
        "dynamics.power_balance",
    ):
        assert kind in kinds
    assert kinds.index("dynamics.solution") > kinds.index("dynamics.system")
    (solution,) = [s for s in body["steps"] if s["kind"] == "dynamics.solution"]
    assert solution["values"]["M_crank"]["value"] == pytest.approx(
        EXPECTED["theta=90deg/driving_torque_M_O"]["value"], rel=1e-9
    )
    B = EXPECTED["theta=90deg/force_B_coupler_on_member3"]["value"]
    assert [solution["values"]["Fx_B"]["value"], solution["values"]["Fy_B"]["value"]] == (
        pytest.approx(B, rel=1e-9)
    )
    (power,) = [s for s in body["steps"] if s["kind"] == "dynamics.power_balance"]
    assert power["values"]["M_power_balance"]["value"] == pytest.approx(
        EXPECTED["theta=90deg/driving_torque_from_power_balance"]["value"], rel=1e-9
    )
    assert body["results"]["drivers"][0]["torque"] == pytest.approx(952.5051075492952, rel=1e-9)


def test_the_seed_mistake_about_an_accelerating_pin(client: TestClient) -> None:
    """E004-7: about A the sum of moments is I_G alpha + r_AG x m a_G, not I_A alpha."""
    body = solve(client, seed004_scene(90))
    (mistake,) = [m for m in body["mistakes"] if m["kind"].startswith("dynamics.moment")]
    m, L = 60.0, 1.0
    alpha = EXPECTED["theta=90deg/alpha_coupler_z"]["value"]
    assert mistake["values"]["wrong"]["value"] == pytest.approx(m * L**2 / 3 * alpha, rel=1e-12)
    assert mistake["values"]["right"]["value"] != pytest.approx(
        mistake["values"]["wrong"]["value"], rel=0.1
    )


SVG = "{http://www.w3.org/2000/svg}"


def _label_boxes(root: ET.Element) -> list[tuple[float, float, float, float]]:
    """Each <text>'s box as free_body places it: its width from label_width (the subscript in
    its <tspan>), FONT + 2 high above its baseline."""
    boxes = []
    for text in root.iter(f"{SVG}text"):
        spans = list(text)
        name = (text.text or "") + ("_" + (spans[0].text or "") if spans else "")
        x, y = float(text.attrib["x"]), float(text.attrib["y"])
        boxes.append((x, y - FONT, x + label_width(name), y + 2))
    return boxes


def test_free_body_diagrams(client: TestClient) -> None:
    """Each diagram: the forces as solved (their sum is sum m a), the unknown joint-force
    components with their assumed senses (+x, +y on a joint's second link, -x, -y on its first)
    valued as solved, drawn dashed, the known forces drawn to the force scale, and no label over
    another or outside the drawing."""
    body = solve(client, seed004_scene(180))
    free_body = [s for s in body["steps"] if s["kind"] == "dynamics.free_body"]
    diagrams = [s["diagram"] for s in free_body]
    svgs = [s["figure"] for s in free_body]
    assert [f["link"] for f in diagrams] == ["crank", "coupler", "rocker"]
    rocker = diagrams[2]
    names = [f["name"] for f in rocker["forces"]]
    assert names == ["F_B", "F_Gamma", "W_rocker", "W_mD", "F_D"]
    # the forces on member 3 and its moments balance its inertia: sum F = sum m a
    total = np.sum([f["vector"] for f in rocker["forces"]], axis=0)
    a_rocker = np.array(
        next(s for s in body["steps"] if s["title"] == "Acceleration of the centre of rocker")[
            "values"
        ]["a_G(rocker)"]["value"]
    )
    a_D = np.array(EXPECTED["theta=180deg/a_D"]["value"])
    inertia = 60 * a_rocker + 90 * a_D
    assert total == pytest.approx(inertia, abs=1e-6 * 3e4)
    # the same sum from the unknowns as drawn: value times assumed sense, plus the known forces
    assert [u["name"] for u in rocker["unknowns"]] == ["F_B,x", "F_B,y", "F_Gamma,x", "F_Gamma,y"]
    assert [u["sense"] for u in rocker["unknowns"]] == [[1, 0], [0, 1]] * 2
    drawn = sum(np.array(u["sense"]) * u["value"] for u in rocker["unknowns"])
    known = np.sum([f["vector"] for f in rocker["forces"] if f["kind"] != "joint"], axis=0)
    assert drawn + known == pytest.approx(inertia, abs=1e-6 * 3e4)
    joints = body["results"]["joints"]
    assert [u["value"] for u in rocker["unknowns"]] == pytest.approx(
        [*joints[2]["force"], *joints[3]["force"]], rel=1e-12
    )
    crank = diagrams[0]  # the crank is the first link of the pin A: the reaction, -x and -y
    assert [u["sense"] for u in crank["unknowns"]] == [[1, 0], [0, 1], [-1, 0], [0, -1]]
    assert [(m["name"], m["unknown"]) for m in crank["moments"]] == [("M_crank", True)]
    for diagram, svg in zip(diagrams, svgs, strict=True):
        root = ET.fromstring(svg)
        lines = root.findall(f"{SVG}line")
        dashed = [line for line in lines if "stroke-dasharray" in line.attrib]
        arrows = [line for line in lines if "marker-end" in line.attrib]
        known = [
            f
            for f in diagram["forces"]
            if f["kind"] != "joint" and math.hypot(*f["vector"]) > 1e-9 * 3e4
        ]
        assert len(dashed) == len(diagram["unknowns"])
        assert len(arrows) == len(diagram["unknowns"]) + len(known)
        width, height = (float(v) for v in root.attrib["viewBox"].split()[2:])
        boxes = _label_boxes(root)
        assert "Γ" in "".join(root.itertext()) or diagram["link"] != "rocker"
        for k, (x0, y0, x1, y1) in enumerate(boxes):
            assert x0 >= 0 and x1 <= width and y0 >= 0 and y1 <= height, diagram["link"]
            for other in boxes[k + 1 :]:
                apart = x1 <= other[0] or other[2] <= x0 or y1 <= other[1] or other[3] <= y0
                assert apart, (diagram["link"], (x0, y0, x1, y1), other)


def test_a_spatial_chain_falls_back(client: TestClient) -> None:
    from tests.server.test_solution import example

    body = client.post(
        "/api/v1/solution",
        json={"scene": example("S002-spatial-arm"), "method": "newton_euler"},
    ).json()
    assert body["steps"][0]["kind"] == "fallback" and body["method"] == "vector"


@pytest.mark.slow
@pytest.mark.parametrize("family", ["slider_crank", "block_in_lever", "six_bar"])
@settings(max_examples=4, deadline=None, database=None, suppress_health_check=list(HealthCheck))
@given(data=st.data())
def test_random_linkages_by_newton_euler(
    client: TestClient, family: str, data: st.DataObject
) -> None:
    check(solve(client, data.draw(linkages(family).flatmap(with_masses_and_loads))))


def test_printable_page_of_the_newton_euler_solution(client: TestClient) -> None:
    response = client.get("/api/v1/solution.html?preset=seed004&method=newton_euler")
    assert response.status_code == 200, response.text
    steps = response.text.split('<li class="step">')[1:]
    free_body = [s for s in steps if "<h3>Free-body diagram of" in s]
    assert len(free_body) == 3, "one free-body diagram per moving link"
    assert all('<figure class="figure"><svg' in s for s in free_body)
    assert "Newton-Euler" in response.text


def _two_crank_five_bar(time: float = 0.0) -> dict[str, Any]:
    """The five-bar of five_bar_points driven by both cranks (omega, alpha each), with masses,
    gravity, a force at C on ``left`` and a moment on ``right``, drawn ``time`` s after the drawn
    pose: each crank turned by omega t + alpha t^2 / 2 about its pivot and turning at
    omega + alpha t, C where the circles about A and B meet on the same side of AB, and the
    centre of mass of ``left`` moved with A and C."""
    drawn = five_bar_points()
    points = dict(drawn)
    rates = {"crank1": (3.0, -2.0, "O1", "A"), "crank2": (-5.0, 4.0, "O2", "B")}
    drivers = []
    for link, (w, al, pivot, tip) in rates.items():
        turn = cmath.exp(1j * (w * time + al * time**2 / 2))
        o, p = complex(*drawn[pivot]), complex(*drawn[tip])
        z = o + (p - o) * turn
        points[tip] = [z.real, z.imag]
        drivers.append({"link": link, "omega": w + al * time, "alpha": al})
    a0, b0, c0 = (complex(*drawn[k]) for k in "ABC")
    a, b = complex(*points["A"]), complex(*points["B"])
    r1, r2, d = abs(c0 - a0), abs(c0 - b0), abs(b - a)
    along = (r1**2 - r2**2 + d**2) / (2 * d)
    side = 1 if ((b0 - a0).conjugate() * (c0 - a0)).imag > 0 else -1
    c = a + (b - a) / d * complex(along, side * math.sqrt(r1**2 - along**2))
    points["C"] = [c.real, c.imag]
    # The centre of mass of ``left`` is fixed in it: carried from the drawn A, C to these.
    g = a + (complex(0.6, 0.8) - a0) * (c - a) / (c0 - a0)
    return {
        "kind": "linkage",
        "points": points,
        **five_bar_topology(),
        "drivers": drivers,
        "masses": {
            "crank1": {"mass": 2.0, "bar": ["O1", "A"]},
            "crank2": {"mass": 3.0, "bar": ["O2", "B"]},
            "left": {"mass": 4.0, "center": [g.real, g.imag], "inertia": 0.2},
            "right": {"mass": 5.0, "bar": ["B", "C"]},
        },
        "gravity": [0.0, -9.81],
        "forces": [
            {"name": "F", "link": "left", "point": "C", "magnitude": 40, "direction_deg": -60}
        ],
        "torques": [{"name": "M_r", "link": "right", "moment": 7.5}],
    }


def _analyze(client: TestClient, scene: dict[str, Any], quantities: list[str]) -> Any:
    response = client.post("/api/v1/analyze", json={"scene": scene, "quantities": quantities})
    assert response.status_code == 200, response.text
    return response.json()


def test_power_balance_of_two_drivers(client: TestClient) -> None:
    """A five-bar driven by both cranks: the check is the drivers' total power, each term
    M_i omega_i the analysis's torque times its crank's omega (1e-12), equal to d(T + V)/dt
    minus the loads' power, where d(T + V)/dt is the central difference of /analyze's energies
    at t = +-1e-4 s (1e-6 of the largest term) and the loads' power is F . v_C + M omega_right
    from /analyze's velocities (1e-12)."""
    body = solve(client, _two_crank_five_bar())
    check(body)
    (step,) = [s for s in body["steps"] if s["kind"] == "dynamics.power_balance"]
    values = {key: v["value"] for key, v in step["values"].items()}
    a = _analyze(client, _two_crank_five_bar(), ["velocity", "forces"])
    terms = []
    for driver in a["drivers"]:
        link = driver["link"]
        expected = driver["torque"] * a["links"][link]["omega"]
        assert values[f"P({link})"] == pytest.approx(expected, rel=1e-12)
        terms.append(expected)
    assert values["P_drivers"] == pytest.approx(sum(terms), rel=1e-12)
    assert min(abs(t) for t in terms) > 1.0  # both drivers do work here

    h = 1e-4
    energy = []
    for t in (-h, h):
        e = _analyze(client, _two_crank_five_bar(t), ["energy"])["energy"]
        energy.append(e["kinetic"] + e["potential"])
    rate = (energy[1] - energy[0]) / (2 * h)
    c = a["points"]["C"]["velocity"]
    force = [40 * math.cos(math.radians(-60)), 40 * math.sin(math.radians(-60))]
    loads = force[0] * c[0] + force[1] * c[1] + 7.5 * a["links"]["right"]["omega"]
    assert values["P_loads"] == pytest.approx(loads, rel=1e-12)
    size = max(abs(values["dT/dt"]), abs(values["dV/dt"]), abs(loads))
    assert values["dT/dt"] + values["dV/dt"] == pytest.approx(rate, abs=1e-6 * size)
    assert values["dT/dt + dV/dt - P_loads"] == pytest.approx(rate - loads, abs=1e-6 * size)
    assert values["P_drivers"] == pytest.approx(rate - loads, abs=1e-6 * size)
    assert "M_{\\text{crank1}}\\,\\omega_{\\text{crank1}}" in step["latex"]
    assert "M_crank2 omega(crank2)" in step["text"]


def test_the_equations_of_member_3_term_by_term(client: TestClient) -> None:
    """Seed 004 at theta = 90 deg, member 3 about Gamma: each term the step writes is the one
    computed here from the reference's positions, accelerations and load (1e-9), and the collected
    right-hand sides are the reference's joint forces put into the equations (1e-9)."""
    body = solve(client, seed004_scene(90))
    (step,) = [s for s in body["steps"] if s["title"] == "Equations of motion of rocker"]
    values = {key: v["value"] for key, v in step["values"].items()}

    def ref(name: str) -> np.ndarray:
        return np.array(EXPECTED[f"theta=90deg/{name}"]["value"], dtype=float)

    def cross(a: np.ndarray, b: np.ndarray) -> float:
        return float(a[0] * b[1] - a[1] * b[0])

    gamma = np.array([1.0, 0.0])
    r_D, a_D, g = ref("r_D") - gamma, ref("a_D"), np.array([0.0, -9.81])
    alpha = float(ref("alpha_rocker_z"))
    assert values["I_G alpha(rocker)"] == pytest.approx(60 * 0.7**2 / 12 * alpha, rel=1e-9)
    assert values["r x m a_G(mD)"] == pytest.approx(cross(r_D, 90 * a_D), rel=1e-9)
    assert values["r x m g(mD)"] == pytest.approx(cross(r_D, 90 * g), rel=1e-9)
    assert values["r x m g(rocker)"] == pytest.approx(cross(r_D / 2, 60 * g), rel=1e-9)
    assert values["r x F(F_D)"] == pytest.approx(cross(r_D, ref("F_D_vector")), abs=1e-9)
    B, G = ref("force_B_coupler_on_member3"), ref("force_Gamma_ground_on_member3")
    assert values["b_Fx"] == pytest.approx(B[0] + G[0], rel=1e-9)
    assert values["b_Fy"] == pytest.approx(B[1] + G[1], rel=1e-9)
    moment = cross(ref("r_B") - gamma, B)
    assert values["b_Mz(Gamma)"] == pytest.approx(moment, rel=1e-9)
    latex = step["latex"]
    assert latex.count(r"\begin{vmatrix}") == 6  # F_B, two weights, F_D, two m a_G
    assert r"I_{G,\text{rocker}}\,\alpha = " in latex
    assert "r(Gamma,B) cross F(B) = " in step["text"]
    assert "passes through Gamma" in step["text"]


def test_the_whole_mechanism_is_the_seeds_seventh_question(client: TestClient) -> None:
    """Seed 004's 7th question at theta = 90 deg: the ground's reactions at O and Gamma add up to
    the reference's sum (1e-9), and with the weights and the load to the reference's total m a_G
    (1e-9)."""
    body = solve(client, seed004_scene(90))
    check(body)
    (step,) = [s for s in body["steps"] if s["kind"] == "dynamics.whole_mechanism"]
    values = {key: np.array(v["value"]) for key, v in step["values"].items()}
    reactions = values["R(O)"] + values["R(Gamma)"]
    expected = EXPECTED["theta=90deg/sum_ground_reactions_O_plus_Gamma"]["value"]
    assert reactions == pytest.approx(expected, rel=1e-9)
    total = EXPECTED["theta=90deg/m_total_times_a_G"]["value"]
    assert values["sum m a_G"] == pytest.approx(total, rel=1e-9)
    assert values["sum external"] == pytest.approx(total, rel=1e-9)

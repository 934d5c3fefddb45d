"""The seed004 preset's worked solutions answer the seed's questions as it asks them, against
tests/reference/seed004-dynamics.json (copied from the course's reference values; the seed's
phi3 is measured from +y clockwise, phi3 = 90 deg - the rocker's angle):

- question 1 (phi2 and phi3 over a revolution, their extremes and where they occur): the step
  ``angle_extremes`` (any four-bar whose crank turns fully), against the reference's phi3 range
  and crank angles (1e-9 deg), against a dense sweep of the same scene refined independently (a
  quartic through the five samples around each sampled extreme: 1e-9 rad), and by the property
  of each extreme (the coupler stands still where the crank is parallel to the rocker, the
  rocker where the crank and the coupler are collinear: 1e-9);
- question 3 (the tangential and radial parts of D's acceleration): the vector and the loop
  method's step for D, at four crank angles (rel 1e-12);
- question 7 (sum m a_G beside the ground's reactions): the Newton-Euler step
  ``dynamics.whole_mechanism``, at four crank angles (rel 1e-9).
"""

from __future__ import annotations

import math
from functools import cache
from typing import Any

import numpy as np
import pytest

from solver.api import parse_scene, solve, sweep
from solver.teaching.presets import PRESETS
from tests.dynamics_cases import EXPECTED
from tests.solver.solutions.test_solve import unit_floors, verify

ANGLES = (0, 90, 180, 270)
DENSE = 36_000  # a sample each 0.01 deg


@cache
def worked(method: str, angle: float = 0.0) -> dict[str, Any]:
    """The preset's worked solution by ``method`` with the crank drawn at ``angle`` deg."""
    scene = PRESETS["seed004"].build({"crank_angle_deg": angle})
    body: dict[str, Any] = solve(scene, method).as_dict()
    floors = unit_floors(body["steps"])
    for step in body["steps"]:
        assert not verify(step, floors), (step["title"], verify(step, floors)[:3])
    return body


def step_of(body: dict[str, Any], kind: str, title: str = "") -> dict[str, Any]:
    (step,) = [s for s in body["steps"] if s["kind"] == kind and title in s["title"]]
    return step


def values(step: dict[str, Any]) -> dict[str, Any]:
    return {key: np.array(v["value"]) for key, v in step["values"].items()}


def ref(name: str) -> Any:
    return EXPECTED[name]["value"]


@pytest.mark.parametrize("method", ["vector", "loop", "newton_euler"])
def test_question_1_the_extremes_of_phi3(method: str) -> None:
    """phi3 runs from -31.8214 deg (crank at 213.354 deg) to +1.0418 deg (crank at 28.567 deg),
    the reference's values to 1e-9 deg, whichever the method."""
    step = step_of(worked(method), "angle_extremes")
    assert (
        step["title"]
        == "Extremes of the angles of the coupler and the rocker over a turn of the crank"
    )
    v = values(step)
    assert 90.0 - v["phi_max (rocker)"] == pytest.approx(ref("phi3_min_deg"), abs=1e-9)
    assert 90.0 - v["phi_min (rocker)"] == pytest.approx(ref("phi3_max_deg"), abs=1e-9)
    assert v["theta at phi_max (rocker)"] == pytest.approx(ref("theta_at_phi3_min_deg"), abs=1e-9)
    assert v["theta at phi_min (rocker)"] == pytest.approx(ref("theta_at_phi3_max_deg"), abs=1e-9)
    for name, shown in step["values"].items():
        assert shown["display"].split()[0] in step["text"], name


def _dense_extremes(link: str) -> tuple[tuple[float, float], tuple[float, float]]:
    """(theta, phi) in deg at the least and the greatest phi of ``link`` over a dense sweep:
    the quartic through the five samples around each sampled extreme, at its stationary point."""
    scene = PRESETS["seed004"].build({})
    body = sweep(scene, DENSE, ["position"]).as_dict()
    theta = np.degrees(np.unwrap(np.array(body["driver_angle"])))
    points = body["points"]
    first, second = {
        "coupler": ("A", "B"),
        "rocker": ("Gamma", "B"),
    }[link]
    d = np.array(points[second]["position"]) - np.array(points[first]["position"])
    phi = np.degrees(np.unwrap(np.arctan2(d[:, 1], d[:, 0])))
    found = []
    for k in (int(np.argmin(phi)), int(np.argmax(phi))):
        around = [(k + j) % theta.size for j in range(-2, 3)]
        t = theta[k] + np.array([(theta[i] - theta[k] + 180.0) % 360.0 - 180.0 for i in around])
        quartic = np.polynomial.Polynomial.fit(t, phi[around], 4)
        roots = quartic.deriv().roots()
        real = [r.real for r in roots if abs(r.imag) < 1e-9 and t[0] <= r.real <= t[-1]]
        (root,) = real
        found.append((root % 360.0, float(quartic(root))))
    return found[0], found[1]


@pytest.mark.parametrize("link", ["coupler", "rocker"])
def test_question_1_extremes_against_a_dense_sweep(link: str) -> None:
    """Each extreme and its crank angle agree with a dense sweep refined by a quartic (1e-9
    rad; the quartic's own error is some 1e-12 rad)."""
    v = values(step_of(worked("vector"), "angle_extremes"))
    (t_low, low), (t_high, high) = _dense_extremes(link)
    tolerance = math.degrees(1e-9)
    assert v[f"phi_min ({link})"] == pytest.approx(low, abs=tolerance)
    assert v[f"phi_max ({link})"] == pytest.approx(high, abs=tolerance)
    assert v[f"theta at phi_min ({link})"] == pytest.approx(t_low, abs=tolerance)
    assert v[f"theta at phi_max ({link})"] == pytest.approx(t_high, abs=tolerance)


def test_question_1_extremes_where_the_link_stands_still() -> None:
    """At the coupler's extremes the crank OA is parallel to the rocker Gamma-B (v_A and v_B
    parallel, the coupler translates for an instant); at the rocker's the crank and the coupler
    are collinear. Checked on the preset drawn at each crank angle found (1e-9 in the sine)."""
    v = values(step_of(worked("vector"), "angle_extremes"))
    for link, (first, second) in {"coupler": (("O", "A"), ("Gamma", "B")),
                                  "rocker": (("O", "A"), ("A", "B"))}.items():  # fmt: skip
        for end in ("min", "max"):
            theta = float(v[f"theta at phi_{end} ({link})"])
            scene = parse_scene(PRESETS["seed004"].build({"crank_angle_deg": theta}))
            p = {name: np.array(xy) for name, xy in scene.points.items()}
            u, w = p[first[1]] - p[first[0]], p[second[1]] - p[second[0]]
            sine = (u[0] * w[1] - u[1] * w[0]) / (np.linalg.norm(u) * np.linalg.norm(w))
            assert abs(sine) < 1e-9, (link, end, sine)
            d = p["B"] - p["A" if link == "coupler" else "Gamma"]
            assert math.degrees(math.atan2(d[1], d[0])) == pytest.approx(
                v[f"phi_{end} ({link})"], abs=1e-9
            )


@pytest.mark.parametrize(
    ("method", "kind"), [("vector", "acceleration.rigid"), ("loop", "loop.acceleration.point")]
)
@pytest.mark.parametrize("angle", ANGLES)
def test_question_3_the_tangential_and_radial_parts_of_a_D(
    method: str, kind: str, angle: int
) -> None:
    """|a_t(D)| = (l3 + lD) |phi3''| and |a_n(D)| = (l3 + lD) phi3'^2, the reference's
    a_D_tangential_along_e_theta and a_D_radial_along_e_r in size (rel 1e-12), in the vector
    method's step for D and in the loop method's (the same function writes both)."""
    step = step_of(worked(method, angle), kind, "Acceleration of D")
    v = values(step)
    key = f"theta={angle}deg/"
    assert v["|a_t(D)|"] == pytest.approx(abs(ref(key + "a_D_tangential_along_e_theta")), rel=1e-12)
    assert v["|a_n(D)|"] == pytest.approx(abs(ref(key + "a_D_radial_along_e_r")), rel=1e-12)
    assert v["|a(D)|"] == pytest.approx(ref(key + "a_D_magnitude"), rel=1e-12)
    assert r"\vec{a}^{\,t}_{D} + \vec{a}^{\,n}_{D}" in step["latex"]
    assert "tangential part" in step["text"] and "radial (normal) part" in step["text"]


@pytest.mark.parametrize("angle", ANGLES)
def test_question_7_sum_m_a_G_beside_the_ground_reactions(angle: int) -> None:
    """The ground's reactions at O and Gamma add up to the reference's sum, and sum m a_G to the
    reference's m a_G of the whole mechanism (rel 1e-9)."""
    step = step_of(worked("newton_euler", angle), "dynamics.whole_mechanism")
    v = values(step)
    key = f"theta={angle}deg/"
    assert v["sum R_ground"] == pytest.approx(
        ref(key + "sum_ground_reactions_O_plus_Gamma"), rel=1e-9
    )
    assert v["sum m a_G"] == pytest.approx(ref(key + "m_total_times_a_G"), rel=1e-9)
    assert "beside the sum of m a_G" in step["title"]

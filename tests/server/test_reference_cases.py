"""The planar linkage cases of seed-cases.json, sent over HTTP to a live uvicorn server.

Every request of cases S000-* and S001 (POST /api/v1/analyze with a linkage scene that has no
moving points) is posted as it stands, and every expected value is compared as the file's "about"
says: within 1e-6 of the largest magnitude of the same unit group ("kind": r, v, a, omega, alpha)
in the case, that magnitude taken as at least 1. The reference values correct the seed solutions'
mistakes (ERRATA.md); a few of those corrections are asserted again by name below, so that a
regression to the seed's wrong value is reported as the erratum it reintroduces.
"""

from __future__ import annotations

import json
import math
from pathlib import Path
from typing import Any

import httpx
import pytest

REFERENCE = Path(__file__).resolve().parents[1] / "reference" / "seed-cases.json"
RELATIVE_TOLERANCE = 1e-6  # seed-cases.json "about"


def _planar_requests() -> list[tuple[str, dict[str, Any]]]:
    cases = json.loads(REFERENCE.read_text())["cases"]
    selected = []
    for case in cases:
        for index, request in enumerate(case["requests"]):
            scene = request["body"]["scene"]
            if (
                request["endpoint"] == "POST /api/v1/analyze"
                and scene["kind"] == "linkage"
                and not scene.get("moving_points")
            ):
                selected.append((f"{case['id']}#{index}", request))
    return selected


PLANAR = _planar_requests()


def test_the_planar_cases_are_the_ones_issue_2_names() -> None:
    """S000-T1..T4 (with the rounded T2) and S001: the selection must not silently shrink."""
    ids = sorted(name.split("#")[0] for name, _ in PLANAR)
    assert ids == [
        "S000-T1",
        "S000-T2",
        "S000-T2-rounded",
        "S000-T3",
        "S000-T4",
        "S001-offset-slider-crank",
    ]


def resolve(body: Any, path: str) -> Any:
    """The response field named by a reference path such as ``joints[0].coriolis_acceleration``."""
    value = body
    for part in path.split("."):
        name, _, rest = part.partition("[")
        value = value[name]
        for index in rest.rstrip("]").split("]["):
            if index:
                value = value[int(index)]
    return value


def _flat(value: Any) -> list[float]:
    return [float(x) for x in value] if isinstance(value, list) else [float(value)]


def group_tolerances(expected: list[dict[str, Any]]) -> dict[str, float]:
    largest: dict[str, float] = {}
    for item in expected:
        size = max(abs(x) for x in _flat(item["value"]))
        largest[item["kind"]] = max(largest.get(item["kind"], 1.0), size)
    return {kind: RELATIVE_TOLERANCE * size for kind, size in largest.items()}


@pytest.fixture(scope="module")
def http(live_server: str) -> Any:
    with httpx.Client(base_url=live_server, timeout=30.0) as session:
        yield session


_answers: dict[str, Any] = {}


def answer(http: httpx.Client, name: str) -> Any:
    """The live server's answer to a reference request (posted once per module)."""
    if name not in _answers:
        request = dict(PLANAR)[name]
        method, url = request["endpoint"].split(" ", 1)
        response = http.request(method, url, json=request["body"])
        assert response.status_code == 200, response.text
        assert response.headers["content-type"].startswith("application/json")
        _answers[name] = response.json()
    return _answers[name]


@pytest.mark.parametrize("name", [name for name, _ in PLANAR])
def test_reference_case_over_http(http: httpx.Client, name: str) -> None:
    """Every expected value of the case within 1e-6 of its unit group's largest magnitude."""
    request = dict(PLANAR)[name]
    body = answer(http, name)
    tolerance = group_tolerances(request["expected"])
    wrong = []
    for item in request["expected"]:
        got = resolve(body, item["path"])
        assert got is not None, f"{item['path']} is null"
        got_values, want = _flat(got), _flat(item["value"])
        assert len(got_values) == len(want), item["path"]
        if any(abs(g - w) > tolerance[item["kind"]] for g, w in zip(got_values, want, strict=True)):
            wrong.append(
                f"{item['path']}: got {got_values}, reference {want} "
                f"(tolerance {tolerance[item['kind']]:.1e})"
            )
    assert not wrong, "\n".join(wrong)


def _value(http: httpx.Client, case: str, path: str) -> list[float]:
    return _flat(resolve(answer(http, f"{case}#0"), path))


def test_erratum_E000_T1_4_coupler_and_rocker_alpha(http: httpx.Client) -> None:
    """E000-T1-4: the seed's eps_2 = -0.375 is the ROCKER's alpha; the coupler's is +0.09375."""
    (coupler,) = _value(http, "S000-T1", "links.coupler.alpha")
    (rocker,) = _value(http, "S000-T1", "links.rocker.alpha")
    assert coupler == pytest.approx(0.09375, abs=1e-9)
    assert rocker == pytest.approx(-0.375, abs=1e-9)


def test_erratum_E000_T1_6_coupler_acceleration_pole(http: httpx.Client) -> None:
    """E000-T1-6: G_2 = (12.3077, 3.4615) m (4 decimals in ERRATA); G_3 = D, not G_2 = D."""
    assert _value(http, "S000-T1", "links.coupler.acceleration_pole") == pytest.approx(
        [12.3077, 3.4615], abs=5e-5
    )
    assert _value(http, "S000-T1", "links.rocker.acceleration_pole") == pytest.approx(
        [2.5, 0.0], abs=1e-9
    )


def test_erratum_E000_T2_6_exact_geometry_coriolis(http: httpx.Client) -> None:
    """E000-T2-6/-3: with x = sqrt(0.12) m, a_Cor = (2.77128, 0) and beta_B = 0.69282 m/s (the
    seed's 2.8 and 0.7 belong to the rounded x = 0.35 m, case S000-T2-rounded)."""
    assert _value(http, "S000-T2", "joints[0].coriolis_acceleration") == pytest.approx(
        [2.77128, 0.0], abs=5e-6
    )
    assert _value(http, "S000-T2", "joints[0].relative_velocity") == pytest.approx(
        [0.0, 0.69282], abs=5e-6
    )
    assert _value(http, "S000-T2-rounded", "joints[0].coriolis_acceleration") == pytest.approx(
        [2.8, 0.0], abs=1e-9
    )


def test_erratum_E000_T3_3_no_coriolis_on_a_fixed_guide(http: httpx.Client) -> None:
    """E000-T3-3: the guide of C is the ground, so the Coriolis term is exactly zero (the seed's
    (0, -2.76) used the coupler's omega_2, which has nothing to do with the guide)."""
    coriolis = _value(http, "S000-T3", "joints[0].coriolis_acceleration")
    assert coriolis == [0.0, 0.0]  # exactly: the guide does not turn
    # scene-v1: when the guide is the ground, the transport motion is zero too
    assert _value(http, "S000-T3", "joints[0].transport_velocity") == [0.0, 0.0]
    assert _value(http, "S000-T3", "joints[0].transport_acceleration") == [0.0, 0.0]


def test_erratum_E000_T3_4_and_5_coupler_alpha_and_slider_acceleration(http: httpx.Client) -> None:
    """E000-T3-4: eps_2 = +7.68 rad/s^2 (not 2.16); E000-T3-5: a_C = (1.8432, 0) (a slider on a
    horizontal fixed guide has no a_y); E000-T3-6: a_D = (1.01376, 3.072) m/s^2."""
    (alpha,) = _value(http, "S000-T3", "links.coupler.alpha")
    assert alpha == pytest.approx(7.68, abs=1e-9)
    assert _value(http, "S000-T3", "points.C.acceleration") == pytest.approx(
        [1.8432, 0.0], abs=1e-9
    )
    assert _value(http, "S000-T3", "points.D.acceleration") == pytest.approx(
        [1.01376, 3.072], abs=1e-9
    )


def test_erratum_E000_T4_4_and_5_exact_slider_crank(http: httpx.Client) -> None:
    """E000-T4-4: eps_2 = 1.582003 rad/s^2 (the seed's 1.43 came from 0.1089 * -0.21 = -0.13);
    E000-T4-2: omega_2 = 0.347195 rad/s; E000-T4-5: P_2 = (0.90561, 1.42701) m. Values to the
    digits ERRATA.md prints."""
    (alpha,) = _value(http, "S000-T4", "links.coupler.alpha")
    assert alpha == pytest.approx(1.582003, abs=5e-7)
    assert alpha != pytest.approx(1.43, abs=0.1)
    (omega,) = _value(http, "S000-T4", "links.coupler.omega")
    assert omega == pytest.approx(0.347195, abs=5e-7)
    assert _value(http, "S000-T4", "links.coupler.velocity_pole") == pytest.approx(
        [0.90561, 1.42701], abs=5e-6
    )


def test_erratum_E001_1_slider_acceleration_is_real(http: httpx.Client) -> None:
    """E001-1: the spurious i in Eq. (10) would give s14'' an imaginary part; the slider of S001
    runs on the fixed x axis, so its acceleration has no y component (to rounding)."""
    a_x, a_y = _value(http, "S001-offset-slider-crank", "points.B.acceleration")
    assert abs(a_y) <= 1e-12 * math.hypot(a_x, 1.0)
    assert a_x == pytest.approx(-2.9782882140571525, abs=1e-6)

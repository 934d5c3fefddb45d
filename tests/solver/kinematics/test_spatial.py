"""Tests of solver.kinematics.spatial: the seed-002 reference case, a planar special case, a
prismatic hand example, an independent finite-difference check on random chains, and parse
errors."""

from __future__ import annotations

import copy
import json
import math
from pathlib import Path
from typing import Any

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from solver.errors import InvalidScene, LimitExceeded
from solver.kinematics.spatial import (
    SpatialChain,
    SpatialJoint,
    SpatialPoint,
    analyze_spatial_chain,
    parse_spatial_chain,
)

CASES = Path(__file__).resolve().parents[2] / "reference" / "seed-cases.json"


def _case(case_id: str) -> dict[str, Any]:
    cases = json.loads(CASES.read_text())["cases"]
    return next(c for c in cases if c["id"] == case_id)


# --- reference case S002 -------------------------------------------------------------------------


def test_seed_002_spatial_arm_matches_reference() -> None:
    request = _case("S002-spatial-arm")["requests"][0]
    result = analyze_spatial_chain(parse_spatial_chain(request["body"]["scene"]))
    expected = request["expected"]
    # Tolerance: 1e-6 relative to the largest magnitude of the same unit group, at least 1.
    scale: dict[str, float] = {}
    for e in expected:
        scale[e["kind"]] = max(scale.get(e["kind"], 1.0), float(np.max(np.abs(e["value"]))))
    for e in expected:
        group, name, field = e["path"].split(".")
        motion = (result.bodies if group == "bodies" else result.points)[name]
        got = getattr(motion, field)
        np.testing.assert_allclose(
            got, e["value"], rtol=0, atol=1e-6 * scale[e["kind"]], err_msg=e["path"]
        )
    # ERRATA E002-2 and the velocity check: the corrected values, not the seed's.
    b = result.points["B"]
    np.testing.assert_allclose(b.acceleration, [0.4, -1.985641, 0.5], atol=1e-6)
    np.testing.assert_allclose(b.velocity, [-1.119615, -0.2, -0.692820], atol=1e-6)
    # E002-1: a^{O2} lies along e2', not e1'.
    np.testing.assert_allclose(result.points["O2"].acceleration, [0, -0.6, 0], atol=1e-9)
    np.testing.assert_allclose(result.points["A"].acceleration, [0.6, -1.639230, 0.3], atol=1e-6)


def test_revolute_body_axis_rate_and_origin() -> None:
    request = _case("S002-spatial-arm")["requests"][0]
    result = analyze_spatial_chain(parse_spatial_chain(request["body"]["scene"]))
    # e3 = e2'' turns with body 2: de3/dt = omega_2 x e3.
    e3 = np.array([0.0, math.sqrt(3) / 2, -0.5])
    np.testing.assert_allclose(result.bodies["3"].axis_rate, np.cross([-1, 0, 1], e3), atol=1e-9)
    np.testing.assert_allclose(result.bodies["2"].axis_rate, [0, 1, 0], atol=1e-12)
    np.testing.assert_allclose(result.bodies["1"].axis_rate, [0, 0, 0], atol=1e-12)
    # The origin of joint 3 is the point A of body 2.
    np.testing.assert_allclose(
        result.bodies["3"].velocity_origin, result.points["A"].velocity, atol=1e-12
    )


def test_ground_point_is_at_rest() -> None:
    doc = {
        "kind": "spatial_chain",
        "joints": [
            {"name": "1", "type": "revolute", "origin": [0, 0, 0], "axis": [0, 0, 2], "rate": 3}
        ],
        "points": {"G": {"body": "ground", "position": [1, 2, 3]}},
    }
    chain = parse_spatial_chain(doc)
    np.testing.assert_allclose(chain.joints[0].axis, [0, 0, 1])
    g = analyze_spatial_chain(chain).points["G"]
    np.testing.assert_allclose(g.position, [1, 2, 3])
    assert not g.velocity.any() and not g.acceleration.any()


def test_prismatic_on_turntable_has_coriolis() -> None:
    """Slider on an arm turning at w about z: the textbook's four terms, written by hand."""
    w, wd, u, ud = 2.0, 0.5, 0.3, -0.7
    chain = SpatialChain(
        joints=(
            SpatialJoint("arm", "revolute", np.zeros(3), np.array([0.0, 0, 1]), w, wd),
            SpatialJoint("block", "prismatic", np.array([1.0, 0, 0]), np.array([1.0, 0, 0]), u, ud),
        ),
        points=(SpatialPoint("P", "block", np.array([1.0, 0, 0])),),
    )
    result = analyze_spatial_chain(chain)
    p = result.points["P"]
    np.testing.assert_allclose(p.velocity, [u, w, 0])
    np.testing.assert_allclose(p.a_origin, [-(w**2), wd, 0])  # coincident point of the arm
    np.testing.assert_allclose(p.coriolis, [0, 2 * w * u, 0])
    np.testing.assert_allclose(p.relative, [ud, 0, 0])
    np.testing.assert_allclose(p.acceleration, [ud - w**2, wd + 2 * w * u, 0])
    np.testing.assert_allclose(result.bodies["block"].omega, [0, 0, w])
    np.testing.assert_allclose(result.bodies["block"].alpha, [0, 0, wd])


# --- planar special case -------------------------------------------------------------------------

coord = st.floats(-1.0, 1.0, allow_nan=False)
rate = st.floats(-2.0, 2.0, allow_nan=False)


@st.composite
def planar_chains(draw: st.DrawFn) -> SpatialChain:
    n = draw(st.integers(1, 5))
    joints = tuple(
        SpatialJoint(
            str(k),
            "revolute",
            np.array([draw(coord), draw(coord), 0.0]),
            np.array([0.0, 0.0, draw(st.sampled_from([1.0, -1.0]))]),
            draw(rate),
            draw(rate),
        )
        for k in range(n)
    )
    points = tuple(
        SpatialPoint(
            f"P{i}", str(draw(st.integers(0, n - 1))), np.array([draw(coord), draw(coord), 0])
        )
        for i in range(draw(st.integers(1, 4)))
    )
    return SpatialChain(joints, points)


def _planar_reference(chain: SpatialChain) -> dict[str, tuple[np.ndarray, np.ndarray]]:
    """Link by link in the plane: v = v_O + w k x r, a = a_O + al k x r - w^2 r."""

    def kx(r: np.ndarray) -> np.ndarray:
        return np.array([-r[1], r[0]])

    w = al = 0.0
    o, v, a = np.zeros(2), np.zeros(2), np.zeros(2)
    state: dict[str, tuple[float, float, np.ndarray, np.ndarray, np.ndarray]] = {}
    for j in chain.joints:
        r = j.origin[:2] - o
        v, a = v + w * kx(r), a + al * kx(r) - w**2 * r
        w, al, o = w + j.axis[2] * j.rate, al + j.axis[2] * j.rate_dot, j.origin[:2]
        state[j.name] = (w, al, o, v, a)
    out = {}
    for p in chain.points:
        w, al, o, v, a = state[p.body]
        r = p.position[:2] - o
        out[p.name] = (v + w * kx(r), a + al * kx(r) - w**2 * r)
    return out


@pytest.mark.slow
@given(planar_chains())
def test_planar_chain_gives_planar_answer(chain: SpatialChain) -> None:
    result = analyze_spatial_chain(chain)
    for name, (v, a) in _planar_reference(chain).items():
        p = result.points[name]
        np.testing.assert_allclose(p.velocity, [*v, 0], atol=1e-12)
        np.testing.assert_allclose(p.acceleration, [*a, 0], atol=1e-11)
    for body in result.bodies.values():
        assert body.omega[:2].tolist() == [0, 0] and body.alpha[:2].tolist() == [0, 0]


# --- random spatial chains against an independent time integrator -------------------------------


@st.composite
def unit_vectors(draw: st.DrawFn) -> np.ndarray:
    v = np.array([draw(coord) for _ in range(3)])
    n = float(np.linalg.norm(v))
    return v / n if n > 0.2 else np.array([0.0, 0.0, 1.0])


@st.composite
def spatial_chains(draw: st.DrawFn) -> SpatialChain:
    n = draw(st.integers(1, 5))
    joints = tuple(
        SpatialJoint(
            f"b{k}",
            draw(st.sampled_from(["revolute", "prismatic"])),
            np.array([draw(coord) for _ in range(3)]),
            draw(unit_vectors()),
            draw(rate),
            draw(rate),
        )
        for k in range(n)
    )
    points = tuple(
        SpatialPoint(
            f"P{i}",
            draw(st.sampled_from(["ground", *(j.name for j in joints)])),
            np.array([draw(coord) for _ in range(3)]),
        )
        for i in range(draw(st.integers(1, 4)))
    )
    return SpatialChain(joints, points)


def _rodrigues(e: np.ndarray, q: float) -> np.ndarray:
    K = np.array([[0, -e[2], e[1]], [e[2], 0, -e[0]], [-e[1], e[0], 0]])
    Q: np.ndarray = np.eye(3) + math.sin(q) * K + (1 - math.cos(q)) * (K @ K)
    return Q


def _pose(chain: SpatialChain, t: float) -> tuple[list[np.ndarray], dict[str, np.ndarray]]:
    """World rotation R_k(t) of every body and world position of every point at time t.

    Joint k turns (or slides) by q_k(t) = rate t + rate_dot t^2 / 2; the joints act in order, each
    moving everything after it about (along) its current axis through its current origin. Body k
    maps a drawn point x to R_k x + p_k; index 0 is the ground.
    """
    n = len(chain.joints)
    R = [np.eye(3) for _ in range(n + 1)]
    p = [np.zeros(3) for _ in range(n + 1)]
    for k, j in enumerate(chain.joints, start=1):
        e, o = R[k - 1] @ j.axis, R[k - 1] @ j.origin + p[k - 1]  # axis fixed in body k-1
        q = j.rate * t + 0.5 * j.rate_dot * t * t
        for b in range(k, n + 1):
            if j.type == "revolute":
                Q = _rodrigues(e, q)
                R[b], p[b] = Q @ R[b], Q @ (p[b] - o) + o
            else:
                p[b] = p[b] + q * e
    index = {"ground": 0} | {j.name: k for k, j in enumerate(chain.joints, start=1)}
    points = {pt.name: R[index[pt.body]] @ pt.position + p[index[pt.body]] for pt in chain.points}
    return R, points


# Tolerance 1e-6, relative to the largest magnitude of the same quantity (at least 1), h = 1e-4:
# central differences err by ~ h^2 |omega|^2 / 6 relative (truncation; |omega| <= 10 here gives
# <= 2e-7) plus ~ eps |x| / h^2 ~ 1e-7 (rounding of the second difference of positions, |x| < 5).
# The worst seen over 2000 random chains was 8e-8, so 1e-6 leaves a margin of ten.
H = 1e-4
RTOL = 1e-6


def _omegas(chain: SpatialChain, t: float) -> list[np.ndarray]:
    (Rm, _), (R0, _), (Rp, _) = (_pose(chain, t + s) for s in (-H, 0.0, H))
    out = []
    for k in range(1, len(chain.joints) + 1):
        W = (Rp[k] - Rm[k]) / (2 * H) @ R0[k].T
        S = 0.5 * (W - W.T)
        out.append(np.array([S[2, 1], S[0, 2], S[1, 0]]))
    return out


def _close(got: np.ndarray, want: np.ndarray, scale: float) -> None:
    np.testing.assert_allclose(got, want, rtol=0, atol=RTOL * max(1.0, scale))


@pytest.mark.slow
@settings(max_examples=200, deadline=None)
@given(spatial_chains())
def test_random_chain_against_finite_differences(chain: SpatialChain) -> None:
    result = analyze_spatial_chain(chain)
    for p in result.points.values():
        terms = p.a_origin + p.tangential + p.centripetal + p.coriolis + p.relative
        np.testing.assert_allclose(terms, p.acceleration, rtol=0, atol=1e-12)

    omega0, omega_m, omega_p = (_omegas(chain, s) for s in (0.0, -H, H))
    for k, j in enumerate(chain.joints):
        body = result.bodies[j.name]
        _close(body.omega, omega0[k], float(np.max(np.abs(omega0))))
        alpha = (omega_p[k] - omega_m[k]) / (2 * H)
        _close(body.alpha, alpha, float(np.max(np.abs(body.alpha))))

    (_, xm), (_, x0), (_, xp) = (_pose(chain, s) for s in (-H, 0.0, H))
    v_scale = max(float(np.max(np.abs(p.velocity))) for p in result.points.values())
    a_scale = max(float(np.max(np.abs(p.acceleration))) for p in result.points.values())
    for name, p in result.points.items():
        np.testing.assert_allclose(x0[name], p.position, atol=1e-14)
        _close(p.velocity, (xp[name] - xm[name]) / (2 * H), v_scale)
        _close(p.acceleration, (xp[name] - 2 * x0[name] + xm[name]) / H**2, a_scale)


# --- parse errors --------------------------------------------------------------------------------


def _doc() -> dict[str, Any]:
    return {
        "kind": "spatial_chain",
        "joints": [
            {"name": "1", "type": "revolute", "origin": [0, 0, 0], "axis": [0, 0, 1], "rate": 1.0},
            {"name": "2", "type": "prismatic", "origin": [1, 0, 0], "axis": [1, 0, 0], "rate": 0.5},
        ],
        "points": {"B": {"body": "2", "position": [1, 0, 0]}},
    }


def _with(path: str, value: Any) -> dict[str, Any]:
    doc = copy.deepcopy(_doc())
    target: Any = doc
    keys: list[Any] = [
        int(k) if k.isdigit() and i == 1 else k for i, k in enumerate(path.split("/"))
    ]
    for key in keys[:-1]:
        target = target[key]
    target[keys[-1]] = value
    return doc


@pytest.mark.parametrize(
    ("doc", "message"),
    [
        (_with("joints/1/axis", [0, 0, 0]), "joints[1].axis is the zero vector"),
        (_with("points/B/body", "x"), "point 'B' is attached to unknown body 'x'"),
        (_with("joints/1/name", "1"), "joints[1].name '1' is a duplicate"),
        (_with("joints/0/name", "ground"), 'joints[0].name "ground" is reserved'),
        (_with("joints/0/rate", math.nan), "joints[0].rate is not a finite number"),
        (_with("joints/1/origin", [0, 0, math.inf]), "joints[1].origin[2] is not a finite"),
        (_with("joints/0/axis", [0, 1]), "joints[0].axis must be a vector of 3 numbers"),
        (_with("points/B/position", [1, 0]), "points.B.position must be a vector of 3"),
        (_with("joints/1/type", "helical"), "joints[1].type 'helical' is unknown"),
        (_with("joints/0/rate_dot", "fast"), "joints[0].rate_dot must be a number"),
        (_with("joints/0/rate", True), "joints[0].rate must be a number"),
        (_with("joints", []), "joints must be a non-empty list"),
        (_with("kind", "linkage"), "kind must be 'spatial_chain'"),
        (_with("points", [1, 2]), "points must be an object"),
    ],
)
def test_invalid_documents_name_the_field(doc: dict[str, Any], message: str) -> None:
    with pytest.raises(InvalidScene) as info:
        parse_spatial_chain(doc)
    assert message in info.value.message


def test_missing_field_is_named() -> None:
    doc = _doc()
    del doc["joints"][1]["axis"]
    with pytest.raises(InvalidScene, match=r"joints\[1\]\.axis is missing"):
        parse_spatial_chain(doc)


def test_size_limits() -> None:
    joint = {"type": "revolute", "origin": [0, 0, 0], "axis": [0, 0, 1], "rate": 1.0}
    many_joints = {
        "kind": "spatial_chain",
        "joints": [{**joint, "name": str(i)} for i in range(65)],
    }
    with pytest.raises(LimitExceeded, match="joints has 65 entries"):
        parse_spatial_chain(many_joints)
    many_points = _with(
        "points", {f"P{i}": {"body": "1", "position": [0, 0, 0]} for i in range(257)}
    )
    with pytest.raises(LimitExceeded, match="points has 257 entries"):
        parse_spatial_chain(many_points)
    ok = {"kind": "spatial_chain", "joints": [{**joint, "name": str(i)} for i in range(64)]}
    assert len(parse_spatial_chain(ok).joints) == 64

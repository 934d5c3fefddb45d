"""Tests of solver.kinematics.relative_motion through solver.analysis.instant: a point M moving
along a path fixed in a
moving link (composite motion, scene-v1 ``moving_points``).

Sources of the expected values:

- the seed-003 reference cases of tests/reference/seed-cases.json (compared at the solver level;
  the HTTP comparison is in tests/server/test_relative_motion_api.py), with the errata of
  ../shared/reference/ERRATA.md, section "Seed 003";
- independent checks that need no reference: central finite differences in time of the solver's
  own positions (and velocities), the rigid-body formulas for the transport point, the geometry
  of the path (tangent, curvature), and the textbook identities v = v_tr + v_rel,
  a = a_tr + a_rel + a_cor, a_cor = 2 omega x v_rel.

Random scenes (hypothesis, modest example counts): a disc pivoted at the ground, driven by a random
polynomial or sinusoidal ``angle_law``, carrying M on an arc or a line with a random ``s_law``;
M on the coupler of a random four-bar (``tests.strategies.assemblable_presets``) whose crank
follows an ``angle_law``; M on the translating coupler of a parallelogram.
"""

from __future__ import annotations

import copy
import dataclasses
import json
import math
from pathlib import Path
from typing import Any

import numpy as np
import pytest
from hypothesis import HealthCheck, assume, given, reject, settings
from hypothesis import strategies as st

from solver.analysis.instant import analyze
from solver.analysis.sweeps import sweep_time
from solver.errors import InvalidScene, NotAssemblable, SingularConfiguration
from solver.kinematics.relative_motion import MovingPointMotion
from solver.model.scene import LinkageScene, parse_linkage
from solver.teaching.presets import build_preset
from tests.strategies import assemblable_presets

CASES = Path(__file__).resolve().parents[2] / "reference" / "seed-cases.json"
SETTINGS = settings(max_examples=25, deadline=None, suppress_health_check=[HealthCheck.too_slow])
# Central-difference step in time (s). With the bounded laws drawn below the truncation error
# h^2/6 |x'''| and the rounding error eps |x| / h both stay below 1e-8 of the quantity's scale.
H = 1e-4
# Tolerance of a finite-difference comparison, relative to the scale of the compared group
# (the largest magnitude among the values compared, at least 1).
FD_RTOL = 1e-6
# Tolerance of an identity that holds exactly in exact arithmetic (sums of parts, tangency):
# relative to the scale of the group, at least 1.
EXACT_RTOL = 1e-12

VECTOR_FIELDS = (
    "position",
    "velocity",
    "acceleration",
    "transport_velocity",
    "relative_velocity",
    "transport_acceleration",
    "relative_acceleration",
    "coriolis_acceleration",
    "transport_tangential",
    "transport_normal",
    "relative_tangential",
    "relative_normal",
)
SCALAR_FIELDS = ("omega_carrier", "alpha_carrier", "s", "s_dot", "s_ddot")


# --- helpers ---


def _case(case_id: str) -> dict[str, Any]:
    cases = json.loads(CASES.read_text())["cases"]
    return next(c for c in cases if c["id"] == case_id)


def _scale(*values: Any) -> float:
    """The largest magnitude among the values (vectors or numbers), at least 1."""
    return max([1.0] + [float(np.max(np.abs(np.asarray(v, dtype=float)))) for v in values])


def _close(got: Any, want: Any, rtol: float, scale: float, what: str) -> None:
    np.testing.assert_allclose(
        np.asarray(got, dtype=float),
        np.asarray(want, dtype=float),
        rtol=0,
        atol=rtol * scale,
        err_msg=what,
    )


def _at(scene: LinkageScene, t: float) -> MovingPointMotion:
    return analyze(dataclasses.replace(scene, time=t)).moving_points["M"]


def _num(x: float) -> str:
    """A float as a time-law literal (repr round-trips exactly; parentheses keep the sign)."""
    return f"({x!r})"


def _perp(v: Any) -> np.ndarray:
    """k x v."""
    return np.array([-v[1], v[0]], dtype=float)


def _cross(a: Any, b: Any) -> float:
    return float(a[0] * b[1] - a[1] * b[0])


# --- strategies ---

_coef = st.floats(-1.5, 1.5, allow_nan=False)


@st.composite
def angle_laws(draw: st.DrawFn, amplitude: float = 1.0) -> str:
    """A polynomial or sinusoidal rotation law (radians), bounded rates for t in [0, 2]."""
    if draw(st.booleans()):
        c1, c2, c3 = (amplitude * draw(_coef) for _ in range(3))
        return f"{_num(c1)}*t + {_num(c2)}*t^2 + {_num(c3 / 3)}*t^3"
    a = amplitude * draw(_coef)
    w, phase = draw(st.floats(0.3, 4.0)), draw(st.floats(-math.pi, math.pi))
    return f"{_num(a)}*sin({_num(w)}*t + {_num(phase)})"


@st.composite
def s_laws(draw: st.DrawFn) -> str:
    """A polynomial or sinusoidal arc-length law (m), or a constant one (M at rest on the path)."""
    kind = draw(st.sampled_from(["poly", "sin", "const"]))
    if kind == "poly":
        c0, c1, c2 = (draw(_coef) for _ in range(3))
        return f"{_num(c0)} + {_num(c1)}*t + {_num(c2 / 2)}*t^2"
    if kind == "sin":
        a, w = draw(_coef), draw(st.floats(0.3, 4.0))
        return f"{_num(a)}*cos({_num(w)}*t) + {_num(draw(_coef))}"
    return _num(draw(_coef))


def _polar(r: float, a: float) -> list[float]:
    return [r * math.cos(a), r * math.sin(a)]


@st.composite
def paths(draw: st.DrawFn) -> tuple[dict[str, Any], dict[str, list[float]]]:
    """A path (arc or line) in the frame of the carrier, as (path spec, drawn points), relative
    to an origin at the carrier's reference point and a unit length."""
    a0 = draw(st.floats(-math.pi, math.pi))
    center = _polar(draw(st.floats(0.2, 1.0)), draw(st.floats(-math.pi, math.pi)))
    if draw(st.booleans()):
        radius = draw(st.floats(0.1, 1.0))
        start = [center[0] + radius * math.cos(a0), center[1] + radius * math.sin(a0)]
        direction = draw(st.sampled_from(["cw", "ccw"]))
        spec = {"type": "arc", "center": "Q1", "start": "Q2", "direction": direction}
        return spec, {"Q1": center, "Q2": start}
    length = draw(st.floats(0.2, 1.0))
    through = [center[0] + length * math.cos(a0), center[1] + length * math.sin(a0)]
    return {"type": "line", "start": "Q1", "through": "Q2"}, {"Q1": center, "Q2": through}


def disc_scene(
    angle_law: str, s_law: str, path: dict[str, Any], pts: dict[str, list[float]]
) -> dict[str, Any]:
    """A disc pivoted at O (ground) turning by ``angle_law``, M on ``path`` of the disc."""
    return {
        "kind": "linkage",
        "title": "disc",
        "points": {"O": [0.0, 0.0], "K": [1.0, 0.0], **pts},
        "links": {
            "ground": {"points": ["O"], "ground": True},
            "disc": {"points": ["O", "K", *pts]},
        },
        "joints": [{"type": "revolute", "point": "O", "links": ["ground", "disc"]}],
        "drivers": [{"link": "disc", "angle_law": angle_law}],
        "moving_points": [{"name": "M", "link": "disc", "path": path, "s_law": s_law}],
    }


def on_coupler(
    doc: dict[str, Any],
    angle_law: str,
    s_law: str,
    path: dict[str, Any],
    pts: dict[str, list[float]],
) -> dict[str, Any]:
    """A four-bar document (links crank, coupler, rocker) with the crank on ``angle_law`` and M
    on ``path`` of the coupler; ``pts`` are in units of |BC| in the frame B -> C."""
    doc = copy.deepcopy(doc)
    b, c = np.array(doc["points"]["B"]), np.array(doc["points"]["C"])
    u = (c - b) / np.linalg.norm(c - b)
    length = float(np.linalg.norm(c - b))
    for name, (x, y) in pts.items():
        doc["points"][name] = list(map(float, b + length * (x * u + y * _perp(u))))
        doc["links"]["coupler"]["points"].append(name)
    doc["drivers"] = [{"link": "crank", "angle_law": angle_law}]
    doc["moving_points"] = [{"name": "M", "link": "coupler", "path": path, "s_law": s_law}]
    return doc


def parallelogram(theta_deg: float, crank: float, ground: float) -> dict[str, Any]:
    """Parallelogram A-B-C-D (AB = DC = crank, BC = AD = ground): the coupler BC translates."""
    b = _polar(crank, math.radians(theta_deg))
    return {
        "kind": "linkage",
        "title": "parallelogram",
        "points": {"A": [0.0, 0.0], "D": [ground, 0.0], "B": b, "C": [b[0] + ground, b[1]]},
        "links": {
            "ground": {"points": ["A", "D"], "ground": True},
            "crank": {"points": ["A", "B"]},
            "coupler": {"points": ["B", "C"]},
            "rocker": {"points": ["D", "C"]},
        },
        "joints": [
            {"type": "revolute", "point": "A", "links": ["ground", "crank"]},
            {"type": "revolute", "point": "B", "links": ["crank", "coupler"]},
            {"type": "revolute", "point": "C", "links": ["coupler", "rocker"]},
            {"type": "revolute", "point": "D", "links": ["rocker", "ground"]},
        ],
        "drivers": [],
    }


@st.composite
def disc_scenes(draw: st.DrawFn) -> tuple[LinkageScene, float]:
    path, pts = draw(paths())
    size = draw(st.floats(0.2, 3.0))
    pts = {k: [size * x for x in v] for k, v in pts.items()}
    doc = disc_scene(draw(angle_laws()), draw(s_laws()), path, pts)
    return parse_linkage(doc), draw(st.floats(0.0, 2.0))


@st.composite
def four_bar_scenes(draw: st.DrawFn) -> tuple[LinkageScene, float]:
    _, values = draw(assemblable_presets(["four_bar"]))
    path, pts = draw(paths())
    # Small crank motions: the linkage stays near its (well-conditioned) drawn pose.
    doc = on_coupler(
        build_preset("four_bar", values), draw(angle_laws(0.1)), draw(s_laws()), path, pts
    )
    scene, t = parse_linkage(doc), draw(st.floats(0.0, 0.5))
    for tt in (t - H, t, t + H):
        try:
            result = analyze(dataclasses.replace(scene, time=tt))
        except (NotAssemblable, SingularConfiguration):
            assume(False)
        assume(result.diagnostics.condition_number is not None)
        assume(result.diagnostics.condition_number < 1e4)
    return scene, t


@st.composite
def parallelogram_scenes(draw: st.DrawFn) -> tuple[LinkageScene, float]:
    theta = draw(st.floats(25.0, 155.0)) * draw(st.sampled_from([1.0, -1.0]))
    doc = parallelogram(theta, draw(st.floats(0.1, 2.0)), draw(st.floats(0.2, 2.0)))
    path, pts = draw(paths())
    try:
        scene = parse_linkage(on_coupler(doc, draw(angle_laws(0.1)), draw(s_laws()), path, pts))
    except InvalidScene:  # a path point drawn onto a joint: a zero-length link, not a scene
        reject()
    return scene, draw(st.floats(0.0, 1.0))


any_scene = st.one_of(disc_scenes(), four_bar_scenes(), parallelogram_scenes())


# --- reference cases S003 (solver level) ---


@pytest.mark.parametrize("case_id", ["S003-T1-translating-carrier", "S003-T2-rotating-carrier"])
def test_seed_003_analyze_requests_match_reference(case_id: str) -> None:
    """Source: seed-cases.json; tolerance 1e-6 relative to the largest magnitude of the same unit
    group in the case, at least 1."""
    case = _case(case_id)
    scale: dict[str, float] = {}
    for request in case["requests"]:
        for e in request["expected"]:
            scale[e["kind"]] = max(scale.get(e["kind"], 1.0), _scale(e["value"]))
    for request in case["requests"]:
        if request["endpoint"] != "POST /api/v1/analyze":
            continue
        m = analyze(parse_linkage(request["body"]["scene"])).moving_points["M"]
        for e in request["expected"]:
            group, name, field = e["path"].split(".")
            assert (group, name) == ("moving_points", "M")
            _close(getattr(m, field), e["value"], 1e-6, scale[e["kind"]], e["path"])


# --- properties on random scenes ---


@pytest.mark.slow
@SETTINGS
@given(any_scene)
def test_velocity_and_acceleration_are_time_derivatives_of_position(
    drawn: tuple[LinkageScene, float],
) -> None:
    """v = dr/dt and a = dv/dt (= d2r/dt2) by central differences with step H in time.
    Tolerance FD_RTOL = 1e-6 relative to the scale of the compared quantities (at least 1)."""
    scene, t = drawn
    before, now, after = _at(scene, t - H), _at(scene, t), _at(scene, t + H)
    v_fd = (after.position - before.position) / (2 * H)
    scale = _scale(v_fd, now.velocity)
    _close(now.velocity, v_fd, FD_RTOL, scale, "v = dr/dt")
    a_fd = (after.velocity - before.velocity) / (2 * H)
    scale = _scale(a_fd, now.acceleration)
    _close(now.acceleration, a_fd, FD_RTOL, scale, "a = dv/dt")
    # Second difference of positions with a larger step (truncation h^2/12 |r''''|): looser.
    h2 = 1e-3
    far_before, far_after = _at(scene, t - h2), _at(scene, t + h2)
    a_fd2 = (far_after.position - 2 * now.position + far_before.position) / h2**2
    _close(now.acceleration, a_fd2, 1e-4, _scale(a_fd2, now.acceleration), "a = d2r/dt2")
    # The carrier's rates are the derivatives of its rotation; s_dot, s_ddot those of s.
    _close(now.s_dot, (after.s - before.s) / (2 * H), FD_RTOL, _scale(now.s_dot), "s_dot")
    _close(
        now.s_ddot, (after.s_dot - before.s_dot) / (2 * H), FD_RTOL, _scale(now.s_ddot), "s_ddot"
    )
    _close(
        now.alpha_carrier,
        (after.omega_carrier - before.omega_carrier) / (2 * H),
        FD_RTOL,
        _scale(now.alpha_carrier),
        "alpha_carrier",
    )
    # omega_carrier = the rate of the carrier's own angle (its first two points).
    carrier = scene.moving_points[0].link
    angles = [
        analyze(dataclasses.replace(scene, time=tt)).links[carrier].angle for tt in (t - H, t + H)
    ]
    assert angles[0] is not None and angles[1] is not None
    turn = math.remainder(angles[1] - angles[0], 2 * math.pi)
    _close(now.omega_carrier, turn / (2 * H), FD_RTOL, _scale(now.omega_carrier), "omega")


@pytest.mark.slow
@SETTINGS
@given(any_scene)
def test_parts_add_up_and_match_the_textbook_formulas(drawn: tuple[LinkageScene, float]) -> None:
    """v = v_tr + v_rel; a = a_tr + a_rel + a_cor; tangential + normal = the part;
    a_cor = 2 omega_carrier x v_rel; the transport terms are those of the carrier's coincident
    point by the rigid-body formulas from another point of the carrier (v_K + omega x KM,
    a_K + alpha x KM - omega^2 KM). Tolerance EXACT_RTOL = 1e-12 relative to the group's scale
    for the sums, 1e-9 for the rigid-body formulas (a different route through the solver)."""
    scene, t = drawn
    result = analyze(dataclasses.replace(scene, time=t))
    m = result.moving_points["M"]
    sv = _scale(m.velocity, m.transport_velocity, m.relative_velocity)
    _close(m.velocity, m.transport_velocity + m.relative_velocity, EXACT_RTOL, sv, "v sum")
    parts = (m.transport_acceleration, m.relative_acceleration, m.coriolis_acceleration)
    sa = _scale(m.acceleration, *parts)
    _close(m.acceleration, sum(parts), EXACT_RTOL, sa, "a sum")
    _close(
        m.transport_tangential + m.transport_normal,
        m.transport_acceleration,
        EXACT_RTOL,
        sa,
        "transport tangential + normal",
    )
    _close(
        m.relative_tangential + m.relative_normal,
        m.relative_acceleration,
        EXACT_RTOL,
        sa,
        "relative tangential + normal",
    )
    _close(
        m.coriolis_acceleration,
        2 * m.omega_carrier * _perp(m.relative_velocity),
        EXACT_RTOL,
        sa,
        "a_cor = 2 omega x v_rel",
    )
    # The tangential and normal parts of the transport acceleration are along and across the
    # coincident point's velocity.
    if np.linalg.norm(m.transport_velocity) > 1e-6 * sv:
        u = m.transport_velocity / np.linalg.norm(m.transport_velocity)
        assert abs(_cross(m.transport_tangential, u)) <= 1e-9 * sa
        assert abs(float(np.dot(m.transport_normal, u))) <= 1e-9 * sa
    # Transport from a second point of the carrier (K on the disc, B on a coupler).
    carrier = scene.moving_points[0].link
    ref = "O" if carrier == "disc" else "B"
    k = result.points[ref]
    link = result.links[carrier]
    assert link.omega is not None and link.alpha is not None
    assert k.position is not None and k.velocity is not None and k.acceleration is not None
    r = m.position - k.position
    _close(link.omega, m.omega_carrier, 1e-12, _scale(link.omega), "omega_carrier")
    _close(link.alpha, m.alpha_carrier, 1e-12, _scale(link.alpha), "alpha_carrier")
    _close(m.transport_velocity, k.velocity + link.omega * _perp(r), 1e-9, sv, "v_tr")
    a_tr = k.acceleration + link.alpha * _perp(r) - link.omega**2 * r
    _close(m.transport_acceleration, a_tr, 1e-9, sa, "a_tr")


@pytest.mark.slow
@SETTINGS
@given(any_scene)
def test_relative_motion_follows_the_path_geometry(drawn: tuple[LinkageScene, float]) -> None:
    """v_rel is tangent to the path (|v_rel| = |s_dot|); a_rel_t = s_ddot along the tangent;
    |a_rel_n| = s_dot^2 / R towards the centre on an arc and 0 on a line; M lies on the path;
    the path's unit tangent, normal and curvature at M are those of the circle or the line.
    Tolerance 1e-9 relative to the group's scale (the geometry is recomputed here from the
    solver's positions of the path's points)."""
    scene, t = drawn
    result = analyze(dataclasses.replace(scene, time=t))
    m = result.moving_points["M"]
    mp = scene.moving_points[0]
    sv = _scale(m.velocity, m.relative_velocity, m.s_dot)
    sa = _scale(m.acceleration, m.relative_acceleration, m.s_dot**2, m.s_ddot)
    sr = _scale(m.position, *(p.position for p in result.points.values()))
    _close(np.linalg.norm(m.relative_velocity), abs(m.s_dot), 1e-12, sv, "|v_rel| = |s_dot|")
    _close(np.linalg.norm(m.relative_tangential), abs(m.s_ddot), 1e-12, sa, "|a_rel_t|")
    _close(
        float(np.dot(m.relative_tangential, m.relative_velocity)),
        m.s_ddot * m.s_dot,
        1e-9,
        sa * sv,
        "a_rel_t along v_rel, sign of s_ddot s_dot",
    )
    if mp.path.type == "arc":
        assert mp.path.center is not None
        c = result.points[mp.path.center].position
        assert c is not None
        radius = math.dist(scene.points[mp.path.center], scene.points[mp.path.start])
        r = m.position - c
        _close(np.linalg.norm(r), radius, 1e-9, sr, "M on the circle")
        _close(float(np.dot(m.relative_velocity, r)), 0.0, 1e-9, sv * sr, "v_rel tangent (arc)")
        _close(
            np.linalg.norm(m.relative_normal),
            m.s_dot**2 / radius,
            1e-9,
            _scale(sa, m.s_dot**2 / radius),
            "|a_rel_n| = s_dot^2 / R",
        )
        _close(
            m.relative_normal,
            -(m.s_dot**2 / radius) * r / radius,
            1e-9,
            _scale(sa, m.s_dot**2 / radius),
            "a_rel_n points to the centre",
        )
        # The direction of travel: ccw paths turn counter-clockwise about the centre (relative
        # to the carrier) for s_dot > 0.
        turn = 1.0 if mp.path.direction == "ccw" else -1.0
        _close(m.relative_velocity, turn * m.s_dot * _perp(r / radius), 1e-9, sv, "cw / ccw")
        _close(m.tangent, turn * _perp(r / radius), 1e-9, 1.0, "tau, the arc's unit tangent")
        _close(m.normal, -r / radius, 1e-9, 1.0, "n, the unit normal towards the centre")
        _close(m.curvature, 1.0 / radius, 1e-12, 1.0 / radius, "1/R")
    else:
        assert mp.path.through is not None
        a, b = result.points[mp.path.start].position, result.points[mp.path.through].position
        assert a is not None and b is not None
        u = (b - a) / np.linalg.norm(b - a)
        _close(_cross(m.position - a, u), 0.0, 1e-9, sr, "M on the line")
        _close(float(np.dot(m.position - a, u)), m.s, 1e-9, sr, "s measured from start")
        _close(m.relative_velocity, m.s_dot * u, 1e-9, sv, "v_rel along the line")
        _close(m.relative_normal, [0.0, 0.0], 1e-12, sa, "no normal part on a line")
        _close(m.tangent, u, 1e-9, 1.0, "tau along the line")
        _close(m.normal, _perp(u), 1e-9, 1.0, "n, tau turned counter-clockwise on a line")
        assert m.curvature == 0.0


@pytest.mark.slow
@SETTINGS
@given(parallelogram_scenes())
def test_no_coriolis_on_a_translating_carrier(drawn: tuple[LinkageScene, float]) -> None:
    """The coupler of a parallelogram translates: omega_carrier = 0 and a_cor = 0 (ERRATA E003-7
    states the reason for seed 003 Task 1); the transport parts equal the motion of B.
    Tolerance 1e-9 relative to the group's scale."""
    scene, t = drawn
    result = analyze(dataclasses.replace(scene, time=t))
    m = result.moving_points["M"]
    sa = _scale(m.acceleration, m.transport_acceleration, m.relative_acceleration)
    _close(m.omega_carrier, 0.0, 1e-9, 1.0, "omega of the translating carrier")
    _close(m.alpha_carrier, 0.0, 1e-9, _scale(result.links["crank"].alpha), "alpha carrier")
    _close(m.coriolis_acceleration, [0.0, 0.0], 1e-9, sa, "Coriolis on a translating carrier")
    b = result.points["B"]
    _close(m.transport_velocity, b.velocity, 1e-9, _scale(b.velocity), "v_tr = v_B")
    _close(m.transport_acceleration, b.acceleration, 1e-9, sa, "a_tr = a_B")


@pytest.mark.slow
@SETTINGS
@given(any_scene, st.floats(-1.0, 1.0))
def test_point_at_rest_on_its_path_moves_with_the_carrier(
    drawn: tuple[LinkageScene, float], s0: float
) -> None:
    """A constant s_law: v_rel = a_rel = a_cor = 0 and the motion is the transport motion.
    Tolerance: exactly zero parts; 1e-12 relative for the equalities."""
    scene, t = drawn
    mp = dataclasses.replace(scene.moving_points[0], s_law=_num(s0))
    m = _at(dataclasses.replace(scene, moving_points=(mp,)), t)
    assert m.s_dot == 0.0 and m.s_ddot == 0.0
    np.testing.assert_array_equal(m.relative_velocity, [0.0, 0.0])
    np.testing.assert_array_equal(m.relative_acceleration, [0.0, 0.0])
    np.testing.assert_array_equal(m.coriolis_acceleration, [0.0, 0.0])
    _close(m.velocity, m.transport_velocity, 1e-12, _scale(m.velocity), "v = v_tr")
    _close(m.acceleration, m.transport_acceleration, 1e-12, _scale(m.acceleration), "a = a_tr")


@pytest.mark.slow
@settings(max_examples=10, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(any_scene, st.floats(0.05, 1.0), st.integers(2, 9))
def test_time_sweep_equals_single_analyses(
    drawn: tuple[LinkageScene, float], span: float, samples: int
) -> None:
    """sweep_time's arrays, sample by sample, equal analyze() at the same instants.
    Tolerance 1e-9 relative to each field's scale (the sweep runs the plan vectorised with
    continuation; the single analyses run it at one instant)."""
    scene, t0 = drawn
    t1 = t0 + span * (0.5 if scene.moving_points[0].link == "coupler" else 1.0)
    quantities = ["position", "velocity", "acceleration", "components"]
    try:
        result = sweep_time(scene, t0, t1, samples, quantities)
    except NotAssemblable:  # a random four-bar may not reach that far
        assume(False)
    np.testing.assert_allclose(result.time, np.linspace(t0, t1, samples), rtol=0, atol=1e-15)
    swept = result.moving_points["M"]
    for k in sorted({0, samples // 2, samples - 1}):
        try:
            single = analyze(dataclasses.replace(scene, time=float(result.time[k])))
        except SingularConfiguration:  # a dead centre inside the range: no single analysis
            assume(False)
        m = single.moving_points["M"]
        for name in (*VECTOR_FIELDS, *SCALAR_FIELDS):
            want, got = getattr(m, name), getattr(swept, name)[k]
            _close(got, want, 1e-9, _scale(want), f"{name} at sample {k}")
        for name, p in single.points.items():
            _close(result.motion.points[name].p[k], p.position, 1e-9, _scale(p.position), name)


# --- hand-checked instants ---


def test_disc_with_point_on_radial_line_matches_closed_form() -> None:
    """A disc turning at phi = 2t - 0.3t^2 about O with M on the radial line from O along the
    disc's x-axis, s = 0.1 + 0.5 t^2 (textbook slotted disc). Closed form with r = s, phi:
    r_M = s e_r, v = s' e_r + s phi' e_phi, a = (s'' - s phi'^2) e_r + (s phi'' + 2 s' phi') e_phi.
    Source: polar kinematics; tolerance 1e-12 relative to the group's scale."""
    doc = disc_scene(
        "2*t - 0.3*t^2", "0.1 + 0.5*t^2", {"type": "line", "start": "O", "through": "K"}, {}
    )
    t = 0.8
    m = _at(parse_linkage(doc), t)
    phi, dphi, ddphi = 2 * t - 0.3 * t**2, 2 - 0.6 * t, -0.6
    s, ds, dds = 0.1 + 0.5 * t**2, t, 1.0
    er, ephi = np.array([math.cos(phi), math.sin(phi)]), np.array([-math.sin(phi), math.cos(phi)])
    _close(m.position, s * er, 1e-12, 1, "r")
    _close(m.velocity, ds * er + s * dphi * ephi, 1e-12, 2, "v")
    _close(m.relative_velocity, ds * er, 1e-12, 2, "v_rel")
    _close(m.transport_velocity, s * dphi * ephi, 1e-12, 2, "v_tr")
    _close(m.coriolis_acceleration, 2 * ds * dphi * ephi, 1e-12, 5, "a_cor")
    _close(
        m.acceleration, (dds - s * dphi**2) * er + (s * ddphi + 2 * ds * dphi) * ephi, 1e-12, 5, "a"
    )
    _close(m.transport_normal, -s * dphi**2 * er, 1e-12, 5, "a_tr normal")
    _close(m.transport_tangential, s * ddphi * ephi, 1e-12, 5, "a_tr tangential")

"""Property tests of the planar solver on random linkages: every preset, a block in a slotted
lever (prismatic joint) and random Watt and Stephenson six-bars (``tests.linkage_strategies``).

Each property is a theorem of plane kinematics that any correct answer satisfies, so no reference
values are needed: velocities are derivatives of positions and accelerations of velocities
(central finite differences), lengths scale out, rigid links have similar velocity images
(Mehmke), and the loop closes along a whole sweep. The same families and helpers serve the
property tests of the slider split (test_sliding_joints.py), of the instant centres
(test_instant_centres.py, Kennedy) and of the poles (test_poles.py).

Tolerances are stated next to each test. ``L`` is the scene's size (diagonal of the drawn points'
bounding box), and a tolerance "relative to the group" is relative to the largest magnitude of
that quantity (velocity, acceleration, angular rate) in the same answer, as in seed-cases.json.
Draws are limited to well-posed instants (reported condition number below ``WELL_POSED``): near a
dead centre the derivatives grow without bound and finite differences say nothing (the extremes
are tested on purpose in test_extremes.py).
"""

from __future__ import annotations

import copy
import math
from itertools import combinations
from typing import Any

import numpy as np
import pytest
from hypothesis import HealthCheck, assume, given, settings
from hypothesis import strategies as st

from solver.analysis.instant import LinkageAnalysis, analyze
from solver.analysis.sweeps import sweep
from solver.model.scene import LinkageScene, parse_linkage
from tests.linkage_strategies import FAMILIES, linkages

Doc = dict[str, Any]
EPS = np.finfo(float).eps
WELL_POSED = 200.0  # reported condition number of the drawn pose's velocity equations
SLIDER_FAMILIES = [f for f in FAMILIES if f not in ("four_bar", "six_bar")]
# Within one answer, identities of the rigid-body field are computed with a handful of roundings:
# 1e-9 of the group's largest magnitude leaves a factor 1e6 above eps for cond <= WELL_POSED.
IDENTITY_TOL = 1e-9

PROPERTY = settings(
    max_examples=40,
    deadline=None,
    database=None,
    suppress_health_check=[HealthCheck.too_slow, HealthCheck.filter_too_much],
)


def solve(doc: Doc, quantities: list[str] | None = None) -> LinkageAnalysis:
    return analyze(parse_linkage(doc), quantities)


def driver_angle_deg(doc: Doc) -> float:
    """The drawn absolute angle of the first driver's link (first to second point), degrees."""
    link = doc["links"][doc["drivers"][0]["link"]]["points"]
    (x0, y0), (x1, y1) = (doc["points"][p] for p in link[:2])
    return math.degrees(math.atan2(y1 - y0, x1 - x0))


def posed(doc: Doc, angle_deg: float) -> Doc:
    out = copy.deepcopy(doc)
    out["drivers"][0]["angle_deg"] = angle_deg
    return out


def perp(v: np.ndarray) -> np.ndarray:
    """k x v."""
    return np.array([-v[1], v[0]])


def cross(a: np.ndarray, b: np.ndarray) -> float:
    return float(a[0] * b[1] - a[1] * b[0])


def norm(v: np.ndarray) -> float:
    return float(np.hypot(v[0], v[1]))


def wrap(angle: float) -> float:
    return math.atan2(math.sin(angle), math.cos(angle))


def group_scales(result: LinkageAnalysis) -> tuple[float, float, float, float]:
    """Largest |v|, |a| over the points and largest |omega|, |alpha| over the links (tiny if 0)."""
    v = max(norm(p.velocity) for p in result.points.values())
    a = max(norm(p.acceleration) for p in result.points.values())
    w = max(abs(link.omega) for link in result.links.values())
    al = max(abs(link.alpha) for link in result.links.values())
    return v or 1e-300, a or 1e-300, w or 1e-300, al or 1e-300


def draw_linkage(data: st.DataObject, family: str) -> tuple[Doc, LinkageScene, LinkageAnalysis]:
    doc = data.draw(linkages(family, WELL_POSED), label="doc")
    scene = parse_linkage(doc)
    return doc, scene, analyze(scene)


# --- derivatives -----------------------------------------------------------------------------

# Step of the central differences: 1e-4 deg = 1.745e-6 rad. The error of a central difference is
# truncation h^2/6 |x'''| plus rounding (position error)/h. Positions carry a few eps L times at
# most the condition number (<= 200 here), so rounding <= 200 * 4 eps L / 1.745e-6 ~ 1e-7 L, and
# away from limit positions (cond <= 200) truncation is of the same order or smaller. Measured over
# 840 draws (120 per family): velocity errors <= 1.4e-9 |omega| L, acceleration errors <= 3.4e-8
# (omega^2 + |alpha|) L (one earlier draw at cond 211: 2.5e-7). Tolerances: 1e-6 |omega| L and
# 1e-5 (omega^2 + |alpha|) L (the velocities being differenced carry their own ~ cond eps error,
# hence the looser second one).
# A 1e-4 relative error in alpha, say, is caught.
FD_STEP_DEG = 1e-4
FD_VELOCITY_TOL = 1e-6
FD_ACCELERATION_TOL = 1e-5


@pytest.mark.slow
@pytest.mark.parametrize("family", FAMILIES)
@PROPERTY
@given(data=st.data())
def test_velocity_is_the_derivative_of_position(family: str, data: st.DataObject) -> None:
    """v_X = omega dX/dtheta and omega_link = omega d(angle)/dtheta (central differences)."""
    doc, scene, base = draw_linkage(data, family)
    omega = doc["drivers"][0]["omega"]
    start = driver_angle_deg(doc)
    plus, minus = (solve(posed(doc, start + s * FD_STEP_DEG)) for s in (1.0, -1.0))
    h2 = 2.0 * math.radians(FD_STEP_DEG)
    scale = abs(omega) * scene.size
    for name, point in base.points.items():
        fd = omega * (plus.points[name].position - minus.points[name].position) / h2
        assert norm(fd - point.velocity) <= FD_VELOCITY_TOL * scale, (name, fd, point.velocity)
    _, _, w_scale, _ = group_scales(base)
    for name, link in base.links.items():
        if link.angle is None:
            continue
        fd = omega * wrap(plus.links[name].angle - minus.links[name].angle) / h2
        assert abs(fd - link.omega) <= FD_VELOCITY_TOL * max(w_scale, abs(omega)), name


@pytest.mark.slow
@pytest.mark.parametrize("family", FAMILIES)
@PROPERTY
@given(data=st.data())
def test_acceleration_is_the_derivative_of_velocity(family: str, data: st.DataObject) -> None:
    """With the driver's omega and alpha held, d/dt = omega d/dtheta at a pose, so
    a_X = omega dv_X/dtheta + alpha dX/dtheta and alpha_link = omega d(omega_link)/dtheta
    + alpha d(angle)/dtheta (the second terms account for the driver's own alpha)."""
    doc, scene, base = draw_linkage(data, family)
    omega, alpha = doc["drivers"][0]["omega"], doc["drivers"][0]["alpha"]
    start = driver_angle_deg(doc)
    plus, minus = (solve(posed(doc, start + s * FD_STEP_DEG)) for s in (1.0, -1.0))
    h2 = 2.0 * math.radians(FD_STEP_DEG)
    scale = (omega**2 + abs(alpha)) * scene.size
    for name, point in base.points.items():
        p, m = plus.points[name], minus.points[name]
        fd = omega * (p.velocity - m.velocity) / h2 + alpha * (p.position - m.position) / h2
        assert norm(fd - point.acceleration) <= FD_ACCELERATION_TOL * scale, (
            name,
            fd,
            point.acceleration,
        )
    _, _, w_scale, al_scale = group_scales(base)
    rate_scale = max(w_scale * abs(omega), al_scale, omega**2 + abs(alpha))
    for name, link in base.links.items():
        p, m = plus.links[name], minus.links[name]
        fd = omega * (p.omega - m.omega) / h2
        if link.angle is not None:
            fd += alpha * wrap(p.angle - m.angle) / h2
        elif omega:  # a one-point link (a block): d(angle)/dtheta = omega_link / omega
            fd += alpha * link.omega / omega
        else:  # omega = 0: d(angle)/dtheta of a one-point link is not observable here
            continue
        assert abs(fd - link.alpha) <= FD_ACCELERATION_TOL * rate_scale, name


@pytest.mark.slow
@pytest.mark.parametrize("family", ["four_bar", "quick_return", "six_bar"])
@settings(max_examples=6, deadline=None, database=None, suppress_health_check=list(HealthCheck))
@given(data=st.data())
def test_sweep_rates_are_derivatives_of_sweep_positions(family: str, data: st.DataObject) -> None:
    """Along a sweep (the driver's omega and alpha held at every sample): v = omega dX/dtheta and
    a = omega dv/dtheta + alpha dX/dtheta, by Richardson-extrapolated central differences
    (error O(h^4): with 4000 samples h <= 1.6e-3 rad, h^4 ~ 6e-12). Only samples at least 10 % of
    a limited range from its ends are compared (near a limit position the derivatives blow up).
    Tolerance 1e-6 of the sweep's largest |v| (|a|). Also: a sample equals /analyze at its angle.
    """
    doc = data.draw(linkages(family, WELL_POSED, newton=False), label="doc")
    scene = parse_linkage(doc)
    omega, alpha = doc["drivers"][0]["omega"], doc["drivers"][0]["alpha"]
    n = 4000
    result = sweep(scene, n, ["position", "velocity", "acceleration"])
    theta = result.driver_angle
    if result.feasible:
        step = 2.0 * math.pi / n * np.sign(theta[1] - theta[0])
        keep = np.arange(n)
    else:
        step = theta[1] - theta[0]
        keep = np.arange(n // 10, n - n // 10)

    def derivative(x: np.ndarray) -> np.ndarray:
        def shifted(k: int) -> np.ndarray:
            return np.roll(x, -k, axis=0)[keep]

        d1 = (shifted(1) - shifted(-1)) / (2 * step)
        d2 = (shifted(2) - shifted(-2)) / (4 * step)
        return (4.0 * d1 - d2) / 3.0

    points = result.motion.points
    v_scale = max(float(np.max(np.hypot(*points[p].v.T))) for p in scene.points) or 1e-300
    a_scale = max(float(np.max(np.hypot(*points[p].a.T))) for p in scene.points) or 1e-300
    for name in scene.points:
        m = points[name]
        dx, dv = derivative(m.p), derivative(m.v)
        err_v = np.max(np.hypot(*(omega * dx - m.v[keep]).T))
        err_a = np.max(np.hypot(*(omega * dv + alpha * dx - m.a[keep]).T))
        assert err_v <= 1e-6 * v_scale, (name, err_v, v_scale)
        assert err_a <= 1e-6 * a_scale, (name, err_a, a_scale)
    # a sample 10 deg from the start (or 10 % into a limited range) equals /analyze at its angle,
    # which reaches it from the drawn pose on the drawn branch
    start = math.radians(driver_angle_deg(doc))
    target = start + math.copysign(math.radians(10.0), step)
    if not result.feasible:
        target = start + 0.1 * (theta[keep[len(keep) // 2]] - start)
    k = nearest_sample(theta, target)
    single = solve(posed(doc, math.degrees(theta[k])))
    for name in scene.points:
        assert norm(single.points[name].position - points[name].p[k]) <= 1e-9 * scene.size
        assert norm(single.points[name].velocity - points[name].v[k]) <= 1e-9 * v_scale
        assert norm(single.points[name].acceleration - points[name].a[k]) <= 1e-8 * a_scale


# --- scaling -----------------------------------------------------------------------------------


@pytest.mark.slow
@pytest.mark.parametrize("family", FAMILIES)
@PROPERTY
@given(data=st.data(), exponent=st.floats(-3.0, 3.0))
def test_scaling_every_length(family: str, data: st.DataObject, exponent: float) -> None:
    """Multiplying every length by k (1e-3..1e3) multiplies positions, velocities, accelerations
    and poles by k and leaves angles, omega, alpha and the (dimensionless) condition number
    unchanged. Tolerance 1e-9 of each group's largest magnitude (k is not a power of two, so the
    two answers differ by rounding, amplified by at most the condition number <= 200)."""
    doc, _, base = draw_linkage(data, family)
    k = 10.0**exponent
    big = copy.deepcopy(doc)
    big["points"] = {name: [k * x, k * y] for name, (x, y) in doc["points"].items()}
    scaled = solve(big)
    v_scale, a_scale, w_scale, al_scale = group_scales(base)
    size = parse_linkage(doc).size
    for name, p in base.points.items():
        q = scaled.points[name]
        assert norm(q.position - k * p.position) <= IDENTITY_TOL * k * size, name
        assert norm(q.velocity - k * p.velocity) <= IDENTITY_TOL * k * v_scale, name
        assert norm(q.acceleration - k * p.acceleration) <= IDENTITY_TOL * k * a_scale, name
    for name, link in base.links.items():
        other = scaled.links[name]
        if link.angle is not None:
            assert abs(wrap(other.angle - link.angle)) <= IDENTITY_TOL, name
        assert abs(other.omega - link.omega) <= IDENTITY_TOL * w_scale, name
        assert abs(other.alpha - link.alpha) <= IDENTITY_TOL * al_scale, name
        for pole, scaled_pole in (
            (link.velocity_pole, other.velocity_pole),
            (link.acceleration_pole, other.acceleration_pole),
        ):
            assert (pole is None) == (scaled_pole is None), name
            if pole is not None:
                reach = max(size, norm(pole))  # a far pole is only as good as its magnitude
                assert norm(scaled_pole - k * pole) <= 1e-8 * k * reach, name
    assert scaled.diagnostics.condition_number == pytest.approx(
        base.diagnostics.condition_number, rel=1e-6
    )


# --- rigid links -------------------------------------------------------------------------------


def _pairs(scene: LinkageScene, link: str) -> list[tuple[str, str]]:
    return list(combinations(scene.links[link].points, 2))


@pytest.mark.slow
@pytest.mark.parametrize(
    "family", ["four_bar", "slider_crank", "slider_guide_extension", "six_bar"]
)
@PROPERTY
@given(data=st.data())
def test_velocity_image_is_similar_to_the_link(family: str, data: st.DataObject) -> None:
    """Mehmke: for a link with three or more points, (v_Y - v_X) / (Y - X) (as complex numbers)
    is the same number i omega for every pair, so the velocity image is the link rotated by 90 deg
    and scaled by omega; likewise (a_Y - a_X) / (Y - X) = alpha i - omega^2 for the acceleration
    image. Tolerance 1e-9 of the group's largest magnitude (an identity within one answer).
    These families all have a link with three points (coupler point, extension, ternary link)."""
    _, scene, result = draw_linkage(data, family)
    v_scale, a_scale, _, _ = group_scales(result)
    ternary = [name for name in scene.moving_links if len(scene.links[name].points) >= 3]
    assume(ternary)  # a coupler point drawn onto B or C is left out of the preset
    for name in ternary:
        link = result.links[name]
        ratios_v, ratios_a = [], []
        for x, y in _pairs(scene, name):
            X, Y = result.points[x], result.points[y]
            r = complex(*(Y.position - X.position))
            ratios_v.append(complex(*(Y.velocity - X.velocity)) / r)
            ratios_a.append(complex(*(Y.acceleration - X.acceleration)) / r)
            length = abs(r)
            # similar images: every ratio is i omega (resp. i alpha - omega^2)
            assert abs(ratios_v[-1] - 1j * link.omega) * length <= IDENTITY_TOL * v_scale
            assert abs(ratios_a[-1] - (1j * link.alpha - link.omega**2)) * length <= (
                IDENTITY_TOL * a_scale
            )


@pytest.mark.slow
@pytest.mark.parametrize("family", FAMILIES)
@PROPERTY
@given(data=st.data())
def test_relative_velocity_of_two_points_is_perpendicular(family: str, data: st.DataObject) -> None:
    """For any two points X, Y of a rigid link, v_Y - v_X is perpendicular to Y - X and its size
    is |omega| |XY| (the link cannot stretch). Tolerance 1e-9 of the largest |v|."""
    _, scene, result = draw_linkage(data, family)
    v_scale, _, _, _ = group_scales(result)
    for name in scene.moving_links:
        omega = result.links[name].omega
        for x, y in _pairs(scene, name):
            r = result.points[y].position - result.points[x].position
            v_rel = result.points[y].velocity - result.points[x].velocity
            assert abs(float(v_rel @ r)) / norm(r) <= IDENTITY_TOL * v_scale, (name, x, y)
            assert abs(norm(v_rel) - abs(omega) * norm(r)) <= IDENTITY_TOL * v_scale, (name, x, y)


# --- loop closure over a sweep -------------------------------------------------------------------

LOOP_CLOSURE_TOL = 1e-12  # of the linkage size, at every sample


def loop_closure_residual(scene: LinkageScene, positions: dict[str, np.ndarray]) -> np.ndarray:
    """Per sample, the largest violation of a constraint, in metres: a change of distance between
    two points of one link, a ground point moved, a sliding point off its slot line."""
    n = next(iter(positions.values())).shape[0]
    worst = np.zeros(n)
    for link in scene.links.values():
        if link.ground:
            for p in link.points:
                worst = np.maximum(worst, np.hypot(*(positions[p] - scene.drawn(p)).T))
            continue
        for x, y in combinations(link.points, 2):
            drawn = norm(scene.drawn(y) - scene.drawn(x))
            now = np.hypot(*(positions[y] - positions[x]).T)
            worst = np.maximum(worst, np.abs(now - drawn))
    for joint in scene.joints:
        if joint.type == "revolute":
            continue
        assert joint.axis is not None
        guide = scene.links[joint.guide].points
        P0, axis = scene.drawn(joint.point), np.array(joint.axis)
        if joint.guide == scene.ground:
            through, direction = np.broadcast_to(P0, (n, 2)), np.broadcast_to(axis, (n, 2))
        else:
            g0, g1 = guide[:2]
            d0 = scene.drawn(g1) - scene.drawn(g0)
            d = positions[g1] - positions[g0]
            turn = np.arctan2(d[:, 1], d[:, 0]) - math.atan2(d0[1], d0[0])
            c, s = np.cos(turn), np.sin(turn)

            def rotated(v: np.ndarray, c: np.ndarray = c, s: np.ndarray = s) -> np.ndarray:
                return np.stack((c * v[0] - s * v[1], s * v[0] + c * v[1]), axis=-1)

            through = positions[g0] + rotated(P0 - scene.drawn(g0))
            direction = rotated(axis)
        off = positions[joint.point] - through
        worst = np.maximum(worst, np.abs(off[:, 0] * direction[:, 1] - off[:, 1] * direction[:, 0]))
    return worst


@pytest.mark.slow
@pytest.mark.parametrize("family", FAMILIES)
@PROPERTY
@given(data=st.data())
def test_loop_closes_over_a_sweep(family: str, data: st.DataObject) -> None:
    """Every link keeps its lengths, the ground stays put and every sliding point stays on its
    slot line, at every sample of a 360-sample sweep: residual below 1e-12 of the linkage size.
    Six-bars include those that need a Newton-Raphson group."""
    doc = data.draw(linkages(family, WELL_POSED), label="doc")
    check_loop_closure(doc)


def check_loop_closure(doc: Doc) -> None:
    scene = parse_linkage(doc)
    result = sweep(scene, 360, ["position"])
    positions = {name: m.p for name, m in result.motion.points.items() if name in scene.points}
    residual = loop_closure_residual(scene, positions)
    assert float(np.max(residual)) <= LOOP_CLOSURE_TOL * scene.size, (
        int(np.argmax(residual)),
        float(np.max(residual)),
    )
    # the sweep follows the drawn branch: near the drawn angle it agrees with /analyze there
    k = nearest_sample(result.driver_angle, math.radians(driver_angle_deg(doc)))
    single = solve(posed(doc, math.degrees(result.driver_angle[k])), ["position"])
    for name in scene.points:
        assert norm(single.points[name].position - positions[name][k]) <= 1e-9 * scene.size, name


def nearest_sample(angles: np.ndarray, target: float) -> int:
    return int(np.argmin(np.abs(np.angle(np.exp(1j * (angles - target))))))

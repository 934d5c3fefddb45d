"""Newton groups over a sweep: one pose per driver angle, the feasible range and its limits.

Sources: the closed-form limit of a non-Grashof four-bar (S000-T1) for the limit finder; an
independent reference path (natural-parameter continuation: small driver steps from the drawn
pose, each predicted linearly from the two before and closed by least-squares Newton-Raphson,
steps refined towards the limits) for the poses; central finite differences over the sweep's
own samples for the rates; and the property that a sweep answers the same range and poses at
any number of samples, and /analyze at a swept angle the swept pose.

Random triads (Stephenson III: a ternary link on three binary links from the crank and two
ground pivots) are drawn from a seeded generator; about half of them cannot turn fully.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings

from solver.analysis.instant import analyze
from solver.analysis.sweeps import Sweep, sweep
from solver.errors import NotAssemblable
from solver.model.scene import LinkageScene, parse_linkage
from solver.position.constraints import ConstraintSystem, States
from solver.position.continuation import Branch
from tests.linkage_strategies import condition_number, six_bars
from tests.solver.analysis.test_extremes import S000_T1, T1_LIMIT
from tests.solver.position.test_newton import TRIAD, with_angle

Doc = dict[str, Any]
TRIADS = 10  # random triads in CI (a longer run: RANDOM_TRIADS=200, see docs/BENCHMARKS.md)


def random_triad(rng: np.random.Generator) -> Doc:
    """A triad drawn at random points (lengths taken from the drawing, so it closes there)."""
    pivot, G2, G3 = np.zeros(2), rng.uniform(1.0, 2.5, 2), rng.uniform([1.0, -1.5], [2.5, 0.0])
    A = rng.uniform(0.2, 0.5) * np.array([math.cos(a := rng.uniform(0, 2 * math.pi)), math.sin(a)])
    centre = rng.uniform([0.6, -0.2], [1.6, 1.2])
    P1, P2, P3 = (centre + rng.uniform(-0.45, 0.45, 2) for _ in range(3))
    doc: Doc = {**TRIAD, "points": {}}
    drawn = (pivot, A, P1, P2, P3, G2, G3)
    for name, p in zip(("O", "A", "P1", "P2", "P3", "G2", "G3"), drawn, strict=True):
        doc["points"][name] = [float(p[0]), float(p[1])]
    return doc


def triads(count: int, seed: int = 14) -> list[Doc]:
    """``count`` random triads whose drawn pose is well conditioned (cond < 1e4) and whose
    triangle P1 P2 P3 is not thin."""
    rng = np.random.default_rng(seed)
    found = []
    while len(found) < count:
        doc = random_triad(rng)
        P1, P2, P3 = (np.array(doc["points"][k]) for k in ("P1", "P2", "P3"))
        u, w = P2 - P1, P3 - P1
        if abs(u[0] * w[1] - u[1] * w[0]) < 0.05 or condition_number(doc) > 1e4:
            continue
        found.append(doc)
    return found


def reference_poses(scene: LinkageScene, turns: np.ndarray, limits: tuple[float, ...]) -> dict:
    """Every moving link's coordinates at ``turns`` by small-step natural continuation from the
    drawn pose (an algorithm independent of the solver's arclength continuation)."""
    system = ConstraintSystem(scene, scene.moving_links, drivers=True)
    ground = scene.ground
    zero2, zero = np.zeros((1, 2)), np.zeros(1)
    known = {ground: States(system.anchor0[ground][None], zero, zero2, zero, zero2, zero)}
    out = {}
    for sense in (1.0, -1.0):
        mine = sorted((t for t in turns if (t >= 0) == (sense > 0)), key=abs)
        t, q, previous = 0.0, system.drawn(), system.drawn()
        dt_previous = 0.0
        for target in mine:
            while abs(target - t) > 0.0:
                room = min((abs(lim - t) for lim in limits if (lim - t) * sense > 0), default=1.0)
                dt = min(1e-2, max(room / 8.0, 1e-9), abs(target - t))
                guess = q + (q - previous) * (dt / dt_previous if dt_previous else 0.0)
                for _ in range(30):
                    phi, J, _ = system.evaluate(
                        known, guess[None], turns=np.array([[t + sense * dt]])
                    )
                    guess = guess - np.linalg.lstsq(J[0], phi[0], rcond=None)[0]
                    if np.linalg.norm(phi) < 1e-14:
                        break
                assert np.linalg.norm(phi) < 1e-12, "the reference path lost the loop"
                previous, q, t, dt_previous = q, guess, t + sense * dt, dt
            out[target] = q
    return out


def swept_positions(result: Sweep, scene: LinkageScene) -> np.ndarray:
    return np.stack([result.motion.points[p].p for p in scene.points], axis=1)


def check_against_analyze(doc: Doc, result: Sweep, every: int) -> None:
    """/analyze at swept angles returns the swept pose to 1e-12 m."""
    scene = parse_linkage(doc)
    for k in range(0, result.driver_angle.size, every):
        angle = math.degrees(float(result.driver_angle[k]))
        drivers = [{**doc["drivers"][0], "angle_deg": angle}, *doc["drivers"][1:]]
        at = analyze(parse_linkage({**doc, "drivers": drivers}), ["position"])
        for name in scene.points:
            assert np.max(np.abs(at.points[name].position - result.motion.points[name].p[k])) <= (
                1e-12
            ), (name, angle)


def test_limit_finder_on_a_non_grashof_four_bar_equals_the_closed_form() -> None:
    """The continuation's limit positions of S000-T1 equal the closed-form +-theta_lim to 1e-12."""
    scene = parse_linkage(S000_T1["body"]["scene"])
    limits = Branch(scene).limits(-math.pi, math.pi)
    assert limits is not None
    A, B = (np.array(scene.points[p]) for p in ("A", "B"))
    drawn = math.atan2(*(B - A)[::-1])
    assert drawn + limits[0] == pytest.approx(-float(T1_LIMIT), abs=1e-12)
    assert drawn + limits[1] == pytest.approx(float(T1_LIMIT), abs=1e-12)


@pytest.mark.slow
@pytest.mark.parametrize("doc", triads(TRIADS), ids=[f"triad{k}" for k in range(TRIADS)])
def test_random_triad_sweeps_agree_at_every_sample_count(doc: Doc) -> None:
    """36, 360 and 3600 samples: every sweep answers (no not_assemblable), with the same range
    and limits (to 1e-9 rad); the poses equal the reference path to 1e-9 m, and /analyze at
    swept angles gives the swept pose to 1e-12 m."""
    scene = parse_linkage(doc)
    results = {n: sweep(scene, n, ["position"]) for n in (36, 360, 3600)}
    first = results[36]
    for result in results.values():
        assert result.feasible == first.feasible
        np.testing.assert_allclose(result.limits, first.limits, rtol=0, atol=1e-9)
    coarse = results[36]
    turns = coarse.driver_angle - _drawn_crank(doc)  # the driver's turns from the drawn pose
    limits = tuple(lim - _drawn_crank(doc) for lim in coarse.limits)
    reference = reference_poses(scene, turns, limits)
    system = ConstraintSystem(scene, scene.moving_links)
    for k, turn in enumerate(turns):
        for index, link in enumerate(system.unknown):
            q = reference[turn][3 * index : 3 * index + 3]
            motion = coarse.motion.links[link]
            anchor = motion.point(scene.drawn(scene.links[link].points[0])).p[k]
            np.testing.assert_allclose(anchor, q[:2], rtol=0, atol=1e-9)
    check_against_analyze(doc, results[360], every=37)


def _drawn_crank(doc: Doc) -> float:
    pivot, A = (np.array(doc["points"][p], dtype=float) for p in ("O", "A"))
    return math.atan2(A[1] - pivot[1], A[0] - pivot[0])


@pytest.mark.slow
def test_triad_sweep_at_36000_samples_has_the_same_limits() -> None:
    doc = next(d for d in triads(TRIADS) if not sweep(parse_linkage(d), 36).feasible)
    scene = parse_linkage(doc)
    coarse, fine = sweep(scene, 36, ["position"]), sweep(scene, 36000, ["position"])
    np.testing.assert_allclose(fine.limits, coarse.limits, rtol=0, atol=1e-9)
    check_against_analyze(doc, fine, every=4999)


@pytest.mark.slow
def test_triad_keeps_its_branch_next_to_its_limit_positions() -> None:
    """Next to each limit the pose moves as the square root of the distance (a fold): samples
    1e-7 rad inside answer, with the group's Jacobian nearly singular, and 1e-7 rad outside do
    not; the sweep's end samples at 36000 samples equal the reference path."""
    scene = parse_linkage(TRIAD)
    result = sweep(scene, 36000, ["position"])
    assert not result.feasible
    low, high = result.limits
    for limit, inward in ((low, 1.0), (high, -1.0)):
        inside = analyze(parse_linkage(with_angle(TRIAD, math.degrees(limit + inward * 1e-7))))
        assert inside.diagnostics.condition_number is not None
        assert inside.diagnostics.condition_number > 1e2
        with pytest.raises(NotAssemblable):
            analyze(parse_linkage(with_angle(TRIAD, math.degrees(limit - inward * 1e-7))))
    drawn = _drawn_crank(TRIAD)
    ends = np.array([result.driver_angle[0], result.driver_angle[-1]]) - drawn
    reference = reference_poses(scene, ends, (low - drawn, high - drawn))
    system = ConstraintSystem(scene, scene.moving_links)
    for k, turn in zip((0, -1), ends, strict=True):
        for index, link in enumerate(system.unknown):
            anchor = result.motion.links[link].point(scene.drawn(scene.links[link].points[0])).p[k]
            q = reference[turn][3 * index : 3 * index + 2]
            np.testing.assert_allclose(anchor, q, rtol=0, atol=1e-7)


def test_sweep_rates_equal_finite_differences_of_the_sweep() -> None:
    """Velocities and accelerations of a 3600-sample triad sweep against central differences of
    its own positions and velocities (step 2 pi / 3600 of the range; truncation ~ 1e-6 of the
    largest value), away from the limits where the rates grow without bound."""
    omega = 2.0
    doc = {**TRIAD, "drivers": [{"link": "crank", "omega": omega, "alpha": 0.0}]}
    scene = parse_linkage(doc)
    result = sweep(scene, 3600, ["position", "velocity", "acceleration"])
    dt = float(result.driver_angle[1] - result.driver_angle[0]) / omega
    inner = slice(200, -200)
    for name in ("P1", "P2", "P3"):
        point = result.motion.points[name]
        fd_v = (point.p[2:] - point.p[:-2]) / (2 * dt)
        fd_a = (point.v[2:] - point.v[:-2]) / (2 * dt)
        v, a = point.v[1:-1][inner], point.a[1:-1][inner]
        assert np.max(np.abs(fd_v[inner] - v)) <= 1e-5 * np.max(np.abs(v))
        assert np.max(np.abs(fd_a[inner] - a)) <= 1e-4 * np.max(np.abs(a))


@pytest.mark.slow
@settings(max_examples=6, deadline=None, suppress_health_check=list(HealthCheck))
@given(six_bars(newton=True))
def test_newton_six_bars_agree_at_every_sample_count(six_bar: Any) -> None:
    """Stephenson six-bars closed by Newton-Raphson: 36, 360 and 3600 samples answer with the
    same range and limits; /analyze at swept angles gives the swept pose to 1e-12 m."""
    doc = six_bar.doc
    scene = parse_linkage(doc)
    results = {n: sweep(scene, n, ["position"]) for n in (36, 360, 3600)}
    for result in results.values():
        assert result.feasible == results[36].feasible
        np.testing.assert_allclose(result.limits, results[36].limits, rtol=0, atol=1e-9)
    check_against_analyze(doc, results[360], every=61)


def two_driver_triad() -> Doc:
    """The triad with its pivot G2 carried by a second driven crank H-G2 (two degrees of freedom),
    the second driver turned 5 deg from its drawn angle (-90 deg; it turns -76 .. +8.9 deg)."""
    doc: Doc = {**TRIAD, "points": {**TRIAD["points"], "H": [2.2, 2.4]}}
    doc["links"] = {**TRIAD["links"], "ground": {"points": ["O", "H", "G3"], "ground": True},
                    "crank2": {"points": ["H", "G2"]}}  # fmt: skip
    doc["joints"] = [j for j in TRIAD["joints"] if j["point"] != "G2"] + [
        {"type": "revolute", "point": "G2", "links": ["L2", "crank2"]},
        {"type": "revolute", "point": "H", "links": ["ground", "crank2"]},
    ]
    doc["drivers"] = [
        {"link": "crank", "omega": 1.0, "alpha": 0.0},
        {"link": "crank2", "omega": 0.5, "alpha": 0.0, "angle_deg": -85.0},
    ]
    return doc


def three_crank_triad(third_deg: float) -> Doc:
    """``two_driver_triad`` with its pivot G3 carried by a third driven crank J-G3 (J at
    (1.8, -0.9)), turning at 0.3 rad/s and posed at ``third_deg``."""
    doc = two_driver_triad()
    doc["points"]["J"] = [1.8, -0.9]
    doc["links"] |= {
        "ground": {"points": ["O", "H", "J"], "ground": True},
        "crank3": {"points": ["J", "G3"]},
    }
    doc["joints"] = [j for j in doc["joints"] if j["point"] != "G3"] + [
        {"type": "revolute", "point": "G3", "links": ["L3", "crank3"]},
        {"type": "revolute", "point": "J", "links": ["ground", "crank3"]},
    ]
    doc["drivers"].append({"link": "crank3", "omega": 0.3, "alpha": 0.0, "angle_deg": third_deg})
    return doc


def test_second_driver_is_turned_first_then_the_first_swept() -> None:
    """Two drivers: the second is turned to its angle (first held), then the first swept. The
    sweep's limits agree at 36 and 360 samples, its poses close every loop, and /analyze at
    swept angles gives the swept pose."""
    doc = two_driver_triad()
    scene = parse_linkage(doc)
    coarse, fine = sweep(scene, 36, ["position"]), sweep(scene, 360, ["position"])
    assert coarse.feasible == fine.feasible
    np.testing.assert_allclose(fine.limits, coarse.limits, rtol=0, atol=1e-9)
    G2 = fine.motion.points["G2"].p
    H = np.array(doc["points"]["H"])
    angle = np.degrees(np.arctan2(G2[:, 1] - H[1], G2[:, 0] - H[0]))
    np.testing.assert_allclose(angle, -85.0, atol=1e-9)
    check_against_analyze(doc, fine, every=41)


@pytest.mark.parametrize("doc", triads(TRIADS), ids=[f"triad{k}" for k in range(TRIADS)])
def test_triad_limits_solve_the_fold_equations(doc: Doc) -> None:
    """Each limit position is a fold: the loop equations F(x) = 0 hold and the Jacobian with the
    driver held, J_q, has a null vector v (J_q v = 0, c . v = 1). That extended system, solved
    independently (scipy's fsolve, finite-difference Jacobian) from the limit node, gives the
    same driver turn to 1e-12 rad."""
    from scipy.optimize import fsolve

    scene = parse_linkage(doc)
    branch = Branch(scene)
    if branch.limits(0.0, 2.0 * math.pi) is None:
        pytest.skip("turns fully")
    for leg in branch.legs.values():
        x0 = leg.x[-1]
        keep = [i for i in range(x0.size) if i != branch.free]
        v0 = np.linalg.svd(branch.equations(x0)[1][:, keep])[2][-1]

        def extended(
            z: np.ndarray, v0: np.ndarray = v0, n: int = x0.size, keep: list[int] = keep
        ) -> np.ndarray:
            F, J = branch.equations(z[:n])
            return np.concatenate([F, J[:, keep] @ z[n:], [v0 @ z[n:] - 1.0]])

        z = fsolve(extended, np.concatenate([x0, v0]), xtol=1e-14)
        assert np.linalg.norm(extended(z)) < 1e-12
        assert leg.limit == pytest.approx(z[branch.free], abs=1e-12)


@pytest.mark.parametrize("sense", [1, -1])
def test_path_curvature_equals_the_turning_of_its_tangents(sense: int) -> None:
    """The predictor's curvature kappa = dtau/ds at a node of the path (from the second
    derivative of the loop equations) equals (tau(ds) - tau(0)) / ds of the tangents at a node
    ds = 1e-5 further, to 1e-3 of |kappa| (the difference quotient's error is O(ds)); the node
    is a few steps from the drawn pose, where no link's rotation is 0."""
    branch = Branch(parse_linkage(TRIAD))
    leg = branch.extend(sense, sense * 0.3)
    x, tau = leg.x[3], leg.tau[3]
    assert np.all(np.abs(np.sin(x[2::3])) > 1e-3)
    kappa = branch.curvature(x, tau, branch.equations(x)[1])
    assert kappa is not None and np.linalg.norm(kappa) > 0.1
    ds = 1e-5
    node, J, converged, _ = branch.correct(x + ds * tau, tau, 1e-15)
    assert converged
    turning = (branch.tangent(J, tau) - tau) / np.linalg.norm(node - x)
    np.testing.assert_allclose(turning, kappa, atol=1e-3 * np.linalg.norm(kappa))

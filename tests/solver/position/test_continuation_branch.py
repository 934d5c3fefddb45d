"""Newton groups followed over a cycle (solver.position.continuation): the branch kept, the
limit positions found, the path's numerics exact where they should be.

A Newton group's sweep does not depend on how finely its path is refined. A sample's starting
value is interpolated on the followed path; when its first Newton step is longer than
``continuation.BRANCH_GAP`` of the size, the path segment holding it is split (``Branch.refine``)
and the sample solved again. With the default gap (1e-2) the interpolation is so good that no case
we know of splits a segment, so these tests lower the gap to 1e-8, which splits segments around
most samples several times over. The answer must not change: the same feasibility and limits, the
same pose at every sample (to 1e-12 m, rounding of the final Newton-Raphson polish), on the
rocking triad (two limit positions) at 36 and 360 samples (where samples fall inside a leg's last
segment) and the fully turning one at 36.

Also the branch rule with two and three drivers (the others turned first, one after the other),
each sample against an independent natural-continuation reference path, and the messages where
a driver cannot be turned or a pose is beyond a limit (the absolute crank angle, off the origin).

The second half checks the followed path against independent values:

- a 50-digit reference (mpmath): the triad's length equations (and a slot's line equation)
  solved by mpmath.findroot at the sample's crank angle, started from the solver's answer, as
  benchmarks/bench_newton.py does; its limit positions as folds of those equations (the
  Jacobian in the unknown points singular, the crank angle an unknown too), likewise;
- the branch: a natural-continuation reference path (small crank steps from the drawn pose,
  test_newton_continuation.py), independent of the solver's pseudo-arclength continuation;
- central finite differences of positions for the rates;
- a closed form: a triad drawn with two parallelograms on its crank translates its ternary link
  with the crank pin;
- polynomials, for the path's interpolant and predictor (``continuation.Leg``,
  ``continuation.predict``: exact to the degree they claim) and the bordered solve
  (``continuation.bordered_solve``: least squares where singular).

The slider triad (the rocking triad of test_newton.py with its link L3 replaced by a slot in the
ground for P3) is the Newton group whose equations are not linear in the links' rotations alone:
it is followed in every link's (x, y, theta), its path's curvature estimated from the tangents
(the predictor and ``Leg.middle`` without a curvature).
"""

from __future__ import annotations

import copy
import math
import re
from typing import Any

import mpmath as mp
import numpy as np
import pytest

from benchmarks.bench_newton import FULL_TURN
from solver.analysis.instant import analyze
from solver.analysis.sweeps import Sweep, sweep, sweep_time
from solver.errors import NotAssemblable
from solver.model.scene import LinkageScene, parse_linkage
from solver.position import continuation
from solver.position.assembly import DriverInput, assemble
from solver.position.constraints import ConstraintSystem, States
from solver.position.topology import build_plan
from tests.solver.position.test_newton import TRIAD, with_angle
from tests.solver.position.test_newton_continuation import (
    TRIADS,
    check_against_analyze,
    reference_poses,
    three_crank_triad,
    triads,
    two_driver_triad,
)


def _sweep(doc: dict[str, Any], samples: int) -> Sweep:
    return sweep(parse_linkage(doc), samples, ["position", "velocity"])


@pytest.mark.parametrize(
    ("name", "samples"), [("rocking triad", 36), ("rocking triad", 360), ("full-turn triad", 36)]
)
def test_a_finely_refined_path_gives_the_same_sweep(
    name: str, samples: int, monkeypatch: pytest.MonkeyPatch
) -> None:
    doc = TRIAD if name == "rocking triad" else FULL_TURN
    coarse = _sweep(doc, samples)
    monkeypatch.setattr(continuation, "BRANCH_GAP", 1e-8)
    fine = _sweep(doc, samples)
    assert fine.feasible == coarse.feasible == (name == "full-turn triad")
    np.testing.assert_allclose(fine.limits, coarse.limits, rtol=0, atol=1e-12)
    np.testing.assert_array_equal(fine.driver_angle, coarse.driver_angle)
    assert fine.singular_samples.size == coarse.singular_samples.size == 0
    for point, motion in coarse.motion.points.items():
        refined = fine.motion.points[point]
        np.testing.assert_allclose(refined.p, motion.p, rtol=0, atol=1e-12)
        assert motion.v is not None and refined.v is not None
        np.testing.assert_allclose(refined.v, motion.v, rtol=0, atol=1e-9 * np.abs(motion.v).max())


def _path_to(scene: LinkageScene, others: list[float], firsts: np.ndarray) -> list[np.ndarray]:
    """Every moving link's coordinates with the other drivers at turns ``others`` and the first at
    each of ``firsts``, reached from the drawn pose by the branch rule (the other drivers turned
    one after the other, those not yet turned and the first held at 0; then the first), by
    small-step natural continuation: each step
    (at most 1e-2 rad) predicted linearly from the one before and closed by least-squares
    Newton-Raphson to 1e-14. Independent of the solver's arclength continuation."""
    system = ConstraintSystem(scene, scene.moving_links, drivers=True)
    zero2, zero = np.zeros((1, 2)), np.zeros(1)
    ground = States(system.anchor0[scene.ground][None], zero, zero2, zero, zero2, zero)
    known = {scene.ground: ground}

    def walk(q: np.ndarray, turns: np.ndarray, index: int, target: float) -> np.ndarray:
        previous, step = q, 0.0
        while turns[index] != target:
            dt = float(np.clip(target - turns[index], -1e-2, 1e-2))
            guess = q + (q - previous) * (dt / step if step else 0.0)
            turns[index] += dt
            for _ in range(30):
                phi, J, _ = system.evaluate(known, guess[None], turns=turns[None])
                guess = guess - np.linalg.lstsq(J[0], phi[0], rcond=None)[0]
                if np.linalg.norm(phi) < 1e-14:
                    break
            assert np.linalg.norm(phi) < 1e-12, "the reference path lost the loop"
            previous, q, step = q, guess, dt
        return q

    staged, turns = system.drawn(), np.zeros(1 + len(others))
    for index, turn in enumerate(others, start=1):
        staged = walk(staged, turns, index, turn)
    out: dict[float, np.ndarray] = {}
    for sense in (1.0, -1.0):
        q, turns = staged, np.array([0.0, *others])
        for target in sorted((float(t) for t in firsts if (t >= 0) == (sense > 0)), key=abs):
            q = out[target] = walk(q, turns, 0, target)
    return [out[float(t)] for t in firsts]


def _drawn_angle(doc: dict[str, Any], pivot: str, tip: str) -> float:
    (x0, y0), (x1, y1) = doc["points"][pivot], doc["points"][tip]
    return math.atan2(y1 - y0, x1 - x0)


def test_second_driver_turned_far_then_the_first_swept_follows_the_branch_rule() -> None:
    """The two-driver triad (a Newton group between two driven cranks) with its second crank
    turned 60 deg from the drawn pose: every sample of a 12-sample sweep of the first crank,
    limit positions included, equals the reference path (second crank turned first, then the
    first) to 1e-9 m."""
    doc = two_driver_triad()
    doc["drivers"][1]["angle_deg"] = -150.0
    scene = parse_linkage(doc)
    result = sweep(scene, 12, ["position"])
    assert not result.feasible
    second = math.radians(-150.0) - _drawn_angle(doc, "H", "G2")
    first = result.driver_angle - _drawn_angle(doc, "O", "A")
    reference = _path_to(scene, [second], first)
    assert_follows(result, scene, reference)


def assert_follows(result: Sweep, scene: LinkageScene, reference: list[np.ndarray]) -> None:
    """Every sample's link anchors equal the reference path's coordinates to 1e-9 m."""
    system = ConstraintSystem(scene, scene.moving_links)
    for k, q in enumerate(reference):
        for index, link in enumerate(system.unknown):
            anchor = result.motion.links[link].point(scene.drawn(scene.links[link].points[0]))
            np.testing.assert_allclose(anchor.p[k], q[3 * index : 3 * index + 2], atol=1e-9)


@pytest.mark.slow
def test_three_drivers_are_turned_in_order_then_the_first_swept() -> None:
    """The triad with both of its ground pivots on driven cranks (H-G2 turned 60 deg, J-G3 20
    deg): the second crank is turned first (the third held at its drawn pose), then the third,
    then the first swept; every sample of 12 equals that reference path to 1e-9 m."""
    doc = three_crank_triad(110.0)
    doc["drivers"][1]["angle_deg"] = -150.0
    scene = parse_linkage(doc)
    result = sweep(scene, 12, ["position"])
    assert not result.feasible
    others = [
        math.radians(-150.0) - _drawn_angle(doc, "H", "G2"),
        math.radians(110.0) - _drawn_angle(doc, "J", "G3"),
    ]
    first = result.driver_angle - _drawn_angle(doc, "O", "A")
    reference = _path_to(scene, others, first)
    assert_follows(result, scene, reference)


def test_second_driver_out_of_reach_names_it() -> None:
    """The second crank asked 70 deg the other way (beyond its limit position at +8.9 deg from
    the drawn pose): not assemblable, and the message names the driver that cannot be turned."""
    doc = two_driver_triad()
    doc["drivers"][1]["angle_deg"] = -20.0
    with pytest.raises(
        NotAssemblable,
        match=r"turning driver 2 \(crank2\) from its drawn pose either way meets a limit position "
        "first",
    ):
        sweep(parse_linkage(doc), 12, ["position"])


def test_a_pose_beyond_a_limit_off_the_origin_reports_the_absolute_crank_angle() -> None:
    """The rocking triad drawn 3 m right and 2 m down (its crank's drawn angle unchanged,
    atan2(0.2, 0.3)), posed 0.5 rad beyond its upper limit: the message gives the crank's
    absolute angle (to 1e-3 deg, as printed) and says why in full."""
    triad: dict[str, Any] = TRIAD
    shifted = {**triad, "points": {p: [x + 3.0, y - 2.0] for p, (x, y) in triad["points"].items()}}
    limit = sweep(parse_linkage(shifted), 36).limits[1]
    beyond = math.degrees(limit + 0.5)
    doc = {**shifted, "drivers": [{**triad["drivers"][0], "angle_deg": beyond}]}
    with pytest.raises(NotAssemblable) as caught:
        analyze(parse_linkage(doc))
    message = str(caught.value)
    assert "turning crank from its drawn pose either way meets a limit position first" in message
    (angle,) = set(re.findall(r"crank angle (\S+) deg", message))
    assert float(angle) == pytest.approx(beyond, abs=1e-3)


def test_samples_start_from_the_quintic_through_each_nodes_tangent_and_curvature() -> None:
    """The interpolant of each path segment (continuation.quintic_hermite, in u = (s - s_k) / h)
    takes each end node's position, tangent times h and curvature times h^2 (1e-12), so the samples
    start close enough for two Newton-Raphson iterations (the cubic through positions and
    tangents needed three) on both triads at 360 and 3600 samples."""
    branch = continuation.Branch(parse_linkage(FULL_TURN))
    branch.limits(0.0, 2.0 * math.pi)
    s, X, T, K = branch.legs[1].arrays()
    k = np.arange(s.size - 1)
    h = np.diff(s)[:, None]
    quintic = continuation.quintic_hermite((s, X, T, K), k)
    powers = np.arange(6.0)
    for u, end in ((0.0, k), (1.0, k + 1)):
        at = u ** np.maximum(powers - 2, 0)[:, None, None]
        value = continuation.horner(quintic, np.full((k.size, 1), u))
        slope = np.sum(
            quintic[1:] * (powers[1:, None, None] * u ** (powers[1:, None, None] - 1)), 0
        )
        bend = np.sum(quintic[2:] * (powers[2:] * (powers[2:] - 1))[:, None, None] * at[2:], 0)
        np.testing.assert_allclose(value, X[end], rtol=0.0, atol=1e-12)
        np.testing.assert_allclose(slope, T[end] * h, rtol=0.0, atol=1e-12)
        np.testing.assert_allclose(bend, K[end] * h * h, rtol=0.0, atol=1e-12)
    for doc in (FULL_TURN, TRIAD):
        for samples in (360, 3600):
            result = sweep(parse_linkage(doc), samples, ["position"])
            assert [report.iterations for report in result.motion.newton] == [2]


def test_a_segments_arclength_is_its_arcs_so_the_starts_are_close() -> None:
    """The quintic's parameter is arclength, so a segment's length is taken as that of a
    circular arc on its chord, c (1 + c^2 |kappa|^2 / 24), not the chord: the full-turning
    triad's 360 starting values then lie within 3e-4 m of the polished poses (median 1.5e-6
    m; with the chord alone 5e-4 and 2.6e-6: a regression bound, the measured values being
    2.2e-4 and 7e-7 on the path with every segment halved, ``Branch.halved``)."""
    scene = parse_linkage(FULL_TURN)
    result = sweep(scene, 360, ["position"])
    branch = continuation.Branch(scene)
    branch.limits(0.0, 2.0 * math.pi)
    starts = branch.guesses(result.driver_angle - result.driver_angle[0])[0]
    links = result.motion.links
    solved = np.concatenate(
        [np.stack([*links[g].anchor.p.T, links[g].theta], 1) for g in scene.moving_links], axis=1
    )
    error = np.max(np.abs(starts - solved), axis=1)
    assert np.max(error) <= 3e-4 and np.median(error) <= 1.5e-6


def test_halved_segments_add_path_nodes_with_their_tangents_and_curvatures() -> None:
    """``Branch.halved`` adds a node at the middle of every segment of the full-turning triad's
    leg (its middles lay up to 6e-4 from the path, over HALVING_RESIDUAL) and none to the
    rocking triad's (within 1e-5). Each added node is a node like those followed one at a time:
    on the path (|F| <= 1e-9, scaled), its tangent a unit null vector of dF/dx (1e-12), its
    curvature solving dF/dx kappa = bending with tau . kappa = 0 (1e-10), between its two
    neighbours in the driver's turn; the starting values from the halved leg are closer to the
    polished poses than from the leg as followed (largest error at least 10 times smaller;
    measured 2.2e-4 against 7.4e-3, the medians 7e-7 against 4e-5: 2^6 would be h^6)."""
    branch = continuation.Branch(parse_linkage(FULL_TURN))
    branch.limits(0.0, 2.0 * math.pi)
    leg = branch.legs[1]
    assert leg.gap > continuation.HALVING_RESIDUAL
    followed = leg.arrays()
    s, X, T, K = branch.halved(leg)
    assert X.shape[0] == 2 * followed[1].shape[0] - 1
    np.testing.assert_array_equal(X[::2], followed[1])
    assert np.all(np.diff(s) > 0.0) and np.all(np.diff(X[:, branch.free]) > 0.0)
    assert branch.bending is not None
    for x, tau, kappa in zip(X[1::2], T[1::2], K[1::2], strict=True):
        F, J = branch.equations(x)
        assert np.linalg.norm(F) <= 1e-9
        assert np.linalg.norm(J @ tau) <= 1e-12 and abs(np.linalg.norm(tau) - 1.0) <= 1e-12
        bent = J @ kappa - branch.bending(x, tau)
        assert np.linalg.norm(bent) <= 1e-10 * np.linalg.norm(kappa)
        assert abs(tau @ kappa) <= 1e-10 * np.linalg.norm(kappa)
    rocking = continuation.Branch(parse_linkage(TRIAD))
    rocking.limits(0.0, 2.0 * math.pi)
    for each in rocking.legs.values():
        assert each.gap <= continuation.HALVING_RESIDUAL
        assert rocking.halved(each)[1].shape == each.arrays()[1].shape

    scene = parse_linkage(FULL_TURN)
    result = sweep(scene, 360, ["position"])
    links = result.motion.links
    solved = np.concatenate(
        [np.stack([*links[g].anchor.p.T, links[g].theta], 1) for g in scene.moving_links], axis=1
    )
    turns = result.driver_angle - result.driver_angle[0]
    halved = np.max(np.abs(branch.guesses(turns)[0] - solved))
    leg.halved = followed  # the starts from the leg as followed
    assert 10.0 * halved <= np.max(np.abs(branch.guesses(turns)[0] - solved))


# ---- Newton groups followed against 50-digit references, folds and closed forms ------------------

Doc = dict[str, Any]
AXIS = (1.0, 0.3)  # the slot's direction
UNKNOWN = ("P1", "P2", "P3")


def slider_triad() -> Doc:
    """The rocking triad with P3 of the ternary link T in a slot of the ground (direction AXIS
    through P3 as drawn) instead of on the rocker L3."""
    doc: Doc = copy.deepcopy(TRIAD)
    del doc["links"]["L3"], doc["points"]["G3"]
    doc["links"]["ground"]["points"] = ["O", "G2"]
    doc["joints"] = [j for j in doc["joints"] if j["point"] not in ("P3", "G3")]
    doc["joints"].append(
        {"type": "slider", "point": "P3", "links": ["ground", "T"], "axis": list(AXIS)}
    )
    return doc


def _links(doc: Doc) -> list[tuple[str, str]]:
    """The pairs of points a triad's links hold at their drawn distance (L3's without a slot)."""
    pairs = [("A", "P1"), ("P1", "P2"), ("P1", "P3"), ("P2", "P3"), ("G2", "P2")]
    return [*pairs, ("G3", "P3")] if "G3" in doc["points"] else pairs


def _equations(doc: Doc) -> Any:
    """F(z, turn) = 0 of a triad with unknown points z = (P1, P2, P3) in 50 digits: squared
    lengths of L1, L2 (and L3) and of T's three sides less their drawn values, and for a slot
    P3's offset across it; the crank point A turned by ``turn`` about O."""
    drawn = {k: mp.matrix([mp.mpf(v[0]), mp.mpf(v[1])]) for k, v in doc["points"].items()}
    pairs = _links(doc)
    squared = [mp.fsum((drawn[a][i] - drawn[b][i]) ** 2 for i in (0, 1)) for a, b in pairs]

    def F(z: Any, turn: Any) -> list[Any]:
        c, s = mp.cos(turn), mp.sin(turn)
        pivot, A0 = drawn["O"], drawn["A"]
        at = dict(drawn)
        at["A"] = mp.matrix([
            pivot[0] + c * (A0[0] - pivot[0]) - s * (A0[1] - pivot[1]),
            pivot[1] + s * (A0[0] - pivot[0]) + c * (A0[1] - pivot[1]),
        ])  # fmt: skip
        for k, name in enumerate(UNKNOWN):
            at[name] = mp.matrix([z[2 * k], z[2 * k + 1]])
        rows = [
            mp.fsum((at[a][i] - at[b][i]) ** 2 for i in (0, 1)) - squared[k]
            for k, (a, b) in enumerate(pairs)
        ]
        if "G3" not in drawn:
            d = at["P3"] - drawn["P3"]
            rows.append(AXIS[0] * d[1] - AXIS[1] * d[0])
        return rows

    return F


def reference_points(doc: Doc, turn: float, start: np.ndarray) -> np.ndarray:
    """P1, P2, P3 ((3, 2)) at the crank's ``turn`` from its drawn pose, solved in 50 digits
    from ``start``."""
    F = _equations(doc)
    with mp.workdps(50):
        root = mp.findroot(lambda *z: F(z, mp.mpf(turn)), [mp.mpf(float(v)) for v in start.flat])
        assert mp.norm(mp.matrix(F(root, mp.mpf(turn)))) < mp.mpf(10) ** -40
        return np.array([float(root[i]) for i in range(6)]).reshape(3, 2)


def reference_limit(doc: Doc, turn: float, start: np.ndarray) -> float:
    """The crank's turn at a limit position (a fold: F = 0 and det dF/dz = 0, seven equations
    in z and the turn) in 50 digits, from ``turn`` and points ``start``."""
    F = _equations(doc)

    def fold(*unknowns: Any) -> list[Any]:
        z, turn = unknowns[:6], unknowns[6]
        J = mp.matrix(6, 6)
        h = mp.mpf(10) ** -30
        for j in range(6):  # dF/dz by a complex step: exact to the working precision
            shifted = list(z)
            shifted[j] += mp.mpc(0, h)
            for i, value in enumerate(F(shifted, turn)):
                J[i, j] = mp.im(value) / h
        return [*F(z, turn), mp.det(J)]

    with mp.workdps(50):
        guess = [mp.mpf(float(v)) for v in start.flat] + [mp.mpf(turn)]
        root = mp.findroot(fold, guess)
        assert mp.norm(mp.matrix(fold(*root))) < mp.mpf(10) ** -35
        return float(root[6])


def drawn_crank(doc: Doc) -> float:
    (x0, y0), (x1, y1) = doc["points"]["O"], doc["points"]["A"]
    return math.atan2(y1 - y0, x1 - x0)


def swept_points(result: Any, k: int) -> np.ndarray:
    return np.array([result.motion.points[p].p[k] for p in UNKNOWN])


@pytest.mark.slow
@pytest.mark.parametrize("samples", [12, 360])
def test_slider_triad_sweep_equals_the_50_digit_reference(samples: int) -> None:
    """Every sample (every 30th of 360) equals the 50-digit roots to 1e-12 m and the natural
    continuation path from the drawn pose to 1e-9 m (the branch kept); /analyze at swept angles
    gives the swept pose."""
    doc = slider_triad()
    scene = parse_linkage(doc)
    result = sweep(scene, samples, ["position"])
    assert not result.feasible
    turns = result.driver_angle - drawn_crank(doc)
    every = max(samples // 12, 1)
    for k in range(0, samples, every):
        swept = swept_points(result, k)
        reference = reference_points(doc, float(turns[k]), swept)
        np.testing.assert_allclose(swept, reference, rtol=0.0, atol=1e-12)
    limits = tuple(limit - drawn_crank(doc) for limit in result.limits)
    path = reference_poses(scene, turns[::every], limits)
    system = ConstraintSystem(scene, scene.moving_links)
    for k, turn in zip(range(0, samples, every), turns[::every], strict=True):
        for index, link in enumerate(system.unknown):
            anchor = result.motion.links[link].point(scene.drawn(scene.links[link].points[0]))
            q = path[turn][3 * index : 3 * index + 2]
            np.testing.assert_allclose(anchor.p[k], q, rtol=0.0, atol=1e-9)
    check_against_analyze(doc, result, every=max(samples // 4, 1))
    drawn = analyze(scene, ["position"])  # turn 0: the drawn pose, the start of both legs
    for name, point in doc["points"].items():
        np.testing.assert_allclose(drawn.points[name].position, point, rtol=0.0, atol=1e-14)


@pytest.mark.slow
def test_slider_triad_limits_are_the_folds_of_its_equations() -> None:
    """The sweep's limit positions (36 and 360 samples) equal the 50-digit folds to 1e-12 rad,
    each solved from the swept sample next to it."""
    doc = slider_triad()
    scene = parse_linkage(doc)
    coarse, fine = sweep(scene, 36, ["position"]), sweep(scene, 360, ["position"])
    np.testing.assert_allclose(coarse.limits, fine.limits, rtol=0.0, atol=1e-12)
    drawn = drawn_crank(doc)
    for k, limit in zip((0, -1), fine.limits, strict=True):
        turn = float(fine.driver_angle[k]) - drawn
        exact = reference_limit(doc, turn, swept_points(fine, k))
        assert limit - drawn == pytest.approx(exact, abs=1e-12)


@pytest.mark.slow
@pytest.mark.parametrize("index", [0, 4])
def test_limits_far_from_the_drawn_pose_whichever_way_the_crank_turns(index: int) -> None:
    """Two random triads of test_newton_continuation.py whose limit positions lie
    far from the drawn pose (triad 0: +2.04 rad, triad 4: -3.90 rad, more than half a turn): a
    sweep with the crank turning either way (omega +-2 rad/s) has the same limits, equal to the
    50-digit folds to 1e-12 rad (the path followed past the first reach, whichever leg met its
    limit first)."""
    doc = triads(TRIADS)[index]
    drawn = drawn_crank(doc)
    for omega in (2.0, -2.0):
        turning = {**doc, "drivers": [{"link": "crank", "omega": omega, "alpha": 0.0}]}
        result = sweep(parse_linkage(turning), 36, ["position"])
        assert not result.feasible
        low, high = sorted(result.limits)
        for limit, k in ((low, int(np.argmin(result.driver_angle))),
                         (high, int(np.argmax(result.driver_angle)))):  # fmt: skip
            start = swept_points(result, k)
            exact = reference_limit(doc, float(result.driver_angle[k]) - drawn, start)
            assert limit - drawn == pytest.approx(exact, abs=1e-12), (omega, limit)


def test_slider_triad_rates_equal_finite_differences() -> None:
    """/analyze of the slider triad 20 deg from its drawn pose: velocities and accelerations of
    P1, P2, P3 equal central differences of positions and velocities at +-1e-4 deg (truncation
    ~ 3e-12 relative; positions exact to ~1e-15), to 1e-6 relative."""
    omega = 2.0
    doc = {**slider_triad(), "drivers": [{"link": "crank", "omega": omega, "alpha": 0.0}]}
    angle, h = math.degrees(drawn_crank(doc)) + 20.0, 1e-4
    at = {d: analyze(parse_linkage(with_angle(doc, angle + d * h))) for d in (-1, 0, 1)}
    step = math.radians(h) / omega  # seconds between the two neighbours and the middle
    for name in UNKNOWN:
        before, middle, after = (at[d].points[name] for d in (-1, 0, 1))
        assert before.position is not None and after.position is not None
        assert before.velocity is not None and after.velocity is not None
        assert middle.velocity is not None and middle.acceleration is not None
        fd_v = (after.position - before.position) / (2 * step)
        fd_a = (after.velocity - before.velocity) / (2 * step)
        np.testing.assert_allclose(middle.velocity, fd_v, rtol=1e-6)
        np.testing.assert_allclose(middle.acceleration, fd_a, rtol=1e-6)


@pytest.mark.parametrize(
    ("turn", "refused"),
    [(2.0 * math.pi - 0.2, 2.0 * math.pi - 0.5), (0.5 - 2.0 * math.pi, 0.8 - 2.0 * math.pi),
     (0.0, 0.8), (0.0, -0.45)],
)  # fmt: skip
def test_a_turn_beyond_a_limit_is_reached_the_other_way_round(turn: float, refused: float) -> None:
    """The rocking triad (limits -0.391 and +0.717 rad from its drawn pose) asked at a turn past
    a limit but within the other one once reduced by a whole turn: posed there (the branch
    rule's "other way round"), equal to the 50-digit roots at the reduced turn and to /analyze
    at the reduced angle; a turn reduced past the other limit too is refused, as are turns just
    past either limit (0.8 and -0.45 rad), with the reason."""
    drawn = math.degrees(drawn_crank(TRIAD))
    reduced = turn - math.copysign(2.0 * math.pi, turn) if turn else 0.0
    far = analyze(parse_linkage(with_angle(TRIAD, drawn + math.degrees(turn))), ["position"])
    near = analyze(parse_linkage(with_angle(TRIAD, drawn + math.degrees(reduced))), ["position"])
    points = np.array([far.points[p].position for p in UNKNOWN])
    np.testing.assert_allclose(points, reference_points(TRIAD, reduced, points), atol=1e-12)
    np.testing.assert_allclose(
        points, np.array([near.points[p].position for p in UNKNOWN]), atol=1e-12
    )
    with pytest.raises(NotAssemblable, match="meets a limit position first"):
        analyze(parse_linkage(with_angle(TRIAD, drawn + math.degrees(refused))))


def _polynomial(coefficients: np.ndarray, s: float, derivative: int = 0) -> np.ndarray:
    """The derivative of order ``derivative`` at s of sum_j coefficients[j] s^j (vectors)."""
    poly = np.polynomial.polynomial
    return np.asarray(poly.polyval(s, poly.polyder(coefficients, derivative)))


def _leg(coefficients: np.ndarray, nodes: list[float], curvature: bool) -> continuation.Leg:
    """A leg through p(s) at the arclengths ``nodes``: positions, derivatives p' as tangents and,
    with ``curvature``, p'' as curvatures (the interpolants are Hermite's in s, whatever p)."""
    at = [[_polynomial(coefficients, s, d) for s in nodes] for d in (0, 1, 2)]
    kappa: list[np.ndarray | None] = list(at[2]) if curvature else [None] * len(nodes)
    return continuation.Leg(list(nodes), at[0], at[1], kappa)


def test_a_segments_middle_and_the_predictor_are_exact_for_polynomials() -> None:
    """``Leg.middle`` is the quintic Hermite interpolant's value at the middle of the last
    segment: exact for a quintic p(s) (and, with the curvatures estimated from the tangents, the
    cubic's: exact for a cubic); ``predict`` is the second-order Taylor step, exact for a
    quadratic, with its curvature estimated from the last two tangents where not known; and
    ``Leg.arrays`` estimates unknown curvatures exactly for a quadratic (linear tangents); with
    the curvatures of the last two nodes known, ``predict`` is the third-order step, kappa'
    their difference over the step: exact for a cubic."""
    rng = np.random.default_rng(8)
    quintic, cubic, quadratic = (rng.uniform(-2.0, 2.0, (n, 3)) for n in (6, 4, 3))
    s0, h = 0.3, 0.45
    for p, curvature in ((quintic, True), (cubic, False)):
        middle = _leg(p, [0.1, s0, s0 + h], curvature).middle()
        np.testing.assert_allclose(middle, _polynomial(p, s0 + h / 2), rtol=0.0, atol=1e-14)
    for nodes, curvature in (([s0], True), ([0.1, s0], False), ([-0.4, 0.1, s0], False)):
        predicted = continuation.predict(_leg(quadratic, nodes, curvature), h)
        np.testing.assert_allclose(predicted, _polynomial(quadratic, s0 + h), atol=1e-14)
    predicted = continuation.predict(_leg(cubic, [0.1, s0], True), h)
    np.testing.assert_allclose(predicted, _polynomial(cubic, s0 + h), atol=1e-14)
    kappa = _leg(quadratic, [-0.4, 0.1, s0, s0 + h], False).arrays(1)[3]
    np.testing.assert_allclose(kappa, np.tile(2.0 * quadratic[2], (3, 1)), atol=1e-13)


def test_a_new_nodes_arclength_is_that_of_the_arc_through_it() -> None:
    """``Leg.insert`` measures a segment on a path of curvature |kappa| as the circular arc
    on its chord c: s = c (1 + c^2 |kappa|^2 / 24), within (3/640) c^5 |kappa|^4 of the exact
    arc. Nodes on the unit circle 0.2 apart (chord 0.19967) after a node on a straight line
    (curvature 0: only the segment's own two ends count): the arc's length 0.2 to 2e-6."""
    angles = (0.0, 0.2, 0.4)
    x = [np.array([math.cos(a), math.sin(a)]) for a in angles]
    tau = [np.array([-math.sin(a), math.cos(a)]) for a in angles]
    kappa = [-xk for xk in x]
    line = x[0] - 0.2 * tau[0]
    leg = continuation.Leg([-0.2, 0.0], [line, x[0]], [tau[0], tau[0]], [np.zeros(2), kappa[0]])
    for k in (1, 2):
        leg.insert(k + 1, x[k], tau[k], kappa[k])
        assert leg.s[k + 1] - leg.s[k] == pytest.approx(0.2, abs=2e-6)


def translating_triad() -> Doc:
    """The rocking triad redrawn so that L2 and L3 are parallel to the crank and as long (the
    parallelograms O A P2 G2 and O A P3 G3): T and L1 translate with A, whatever the crank's
    turn, and the path is a straight line in the links' rotations (crank, L2 and L3 turn
    together, T and L1 not at all)."""
    doc: Doc = copy.deepcopy(TRIAD)
    points = doc["points"]
    A = np.array(points["A"], dtype=float)
    for tip, pivot in (("P2", "G2"), ("P3", "G3")):
        points[tip] = (np.array(points[pivot], dtype=float) + A).tolist()
    return doc


def test_a_translating_triad_turns_fully_with_its_coupler_translated() -> None:
    """The translating triad's points at every sample of a 36-sample sweep are their drawn
    positions moved by A's displacement (the closed form of a translation) to 1e-12 m, and
    their velocities A's (1e-9 relative): the crank turns fully. Its path is straight, so the
    predictor lands on it and the corrector takes no step (``Branch.extend`` divided by that
    zero move)."""
    doc = translating_triad()
    result = sweep(parse_linkage(doc), 36, ["position", "velocity"])
    assert result.feasible
    A = result.motion.points["A"]
    assert A.v is not None
    shift = A.p - np.array(doc["points"]["A"])
    for name in UNKNOWN:
        point = result.motion.points[name]
        assert point.v is not None
        np.testing.assert_allclose(point.p, doc["points"][name] + shift, rtol=0.0, atol=1e-12)
        np.testing.assert_allclose(point.v, A.v, rtol=0.0, atol=1e-9 * np.abs(A.v).max())


def first_fold(doc: Doc, sense: int) -> float:
    """The crank's turn at the first limit position met turning it in ``sense`` from the drawn
    pose: natural continuation on the triad's squared link lengths in P1, P2, P3 (steps of at
    most 1e-2 rad, each predicted linearly from the last two poses and closed by
    Newton-Raphson to 1e-13 m^2 within 1e-2 m of the prediction; halved where it does not
    close, down to 1e-7 rad), then the fold in 50 digits from the last pose
    (``reference_limit``). Independent of the solver's pseudo-arclength continuation."""
    drawn = {k: np.array(v, dtype=float) for k, v in doc["points"].items()}
    pairs = _links(doc)
    squared = np.array([(drawn[a] - drawn[b]) @ (drawn[a] - drawn[b]) for a, b in pairs])
    column = {name: 2 * k for k, name in enumerate(UNKNOWN)}

    def close(z: np.ndarray, turn: float) -> np.ndarray | None:
        c, s = math.cos(turn), math.sin(turn)
        at = {**drawn, "A": drawn["O"] + np.array([[c, -s], [s, c]]) @ (drawn["A"] - drawn["O"])}
        guess = z
        for _ in range(12):
            at |= {name: z[column[name] : column[name] + 2] for name in UNKNOWN}
            F = np.array([(at[a] - at[b]) @ (at[a] - at[b]) for a, b in pairs]) - squared
            if np.max(np.abs(F)) <= 1e-13:
                return z if np.max(np.abs(z - guess)) <= 1e-2 else None
            J = np.zeros((len(pairs), z.size))
            for row, (a, b) in enumerate(pairs):
                for name, side in ((a, 1.0), (b, -1.0)):
                    if name in column:
                        J[row, column[name] : column[name] + 2] = 2.0 * side * (at[a] - at[b])
            z = z - np.linalg.solve(J, F)
        return None

    z = np.concatenate([drawn[name] for name in UNKNOWN])
    previous, turn, step, last = z, 0.0, 1e-2, 0.0
    while step >= 1e-7:
        closed = close(z + (z - previous) * (step / last if last else 0.0), turn + sense * step)
        if closed is None:
            step /= 2.0
            continue
        previous, z, turn, last = z, closed, turn + sense * step, step
    return reference_limit(doc, turn, z.reshape(3, 2))


# Random triads (test_newton_continuation.triads, seed 14: numbers 14, 30, 914,
# 489, 658, 50 and 307, points rounded to 1e-6) whose path is easily followed past a limit
# position: onto a neighbouring strand of the equations' solutions, across two limit positions
# in one step (an S, its middle between them; a narrow S near the step's end; an S that only the
# step's first tangent shows), or with a corrector that went on where its steps did not
# contract; and two whose limits lie more than a turn apart.
FOLDED_TRIADS = {
    "a neighbouring strand": {
        "A": [-0.430253, 0.036583], "P1": [0.287808, 0.086376], "P2": [0.940573, 0.572657],
        "P3": [0.680595, 0.583156], "G2": [2.303849, 1.839343], "G3": [2.197473, -0.558392],
    },
    "an S": {
        "A": [0.262436, -0.210568], "P1": [1.090508, 0.987393], "P2": [1.321993, 0.750742],
        "P3": [1.690463, 1.089357], "G2": [1.867958, 1.515987], "G3": [2.068845, -0.15752],
    },
    "a narrow S": {
        "A": [0.373449, -0.050876], "P1": [0.744221, 0.880635], "P2": [0.34471, 0.620295],
        "P3": [0.570638, 1.037479], "G2": [2.14702, 1.221792], "G3": [1.088902, -1.144264],
    },
    "an S its first tangent shows": {
        "A": [0.034142, 0.288644], "P1": [1.636835, 0.26994], "P2": [1.275954, 0.799604],
        "P3": [1.135851, 0.038605], "G2": [1.776625, 1.439879], "G3": [1.970517, -0.07153],
    },
    "a corrector that must contract": {
        "A": [0.082644, -0.183428], "P1": [1.109792, 0.757776], "P2": [0.67889, 0.429424],
        "P3": [1.132662, 0.372174], "G2": [1.171368, 1.474349], "G3": [2.391489, -0.498889],
    },
    "a range wider than a turn": {
        "A": [-0.346333, -0.017599], "P1": [1.253653, 0.589456], "P2": [1.157239, 0.597191],
        "P3": [0.762273, 1.246077], "G2": [2.077144, 1.235374], "G3": [2.353222, -1.021928],
    },
    "a range wider than a turn, its upper limit near": {
        "A": [0.006964, 0.313029], "P1": [1.388362, 0.610616], "P2": [0.894664, -0.001645],
        "P3": [1.372408, 0.172899], "G2": [1.535886, 2.366826], "G3": [2.140691, -0.830231],
    },
}  # fmt: skip


def folded_triad(name: str) -> Doc:
    return {**TRIAD, "points": {"O": [0.0, 0.0], **FOLDED_TRIADS[name]}}


@pytest.mark.slow
@pytest.mark.parametrize("name", [name for name in FOLDED_TRIADS if "wider" not in name])
def test_limits_are_the_first_folds_met_from_the_drawn_pose(name: str) -> None:
    """The sweep's limit positions are the first folds met turning the crank either way from
    the drawn pose (``first_fold``: natural continuation, then the 50-digit fold), to 1e-12
    rad. Pseudo-arclength steps over a limit position are refused: one that lands on another
    strand (the orientation sign(det [dF/dx; tau]) changes) and one whose quintic's turn is not
    monotone (the path went back and forth; its quintic built from both ends' tangents, else
    the S of triad 489 passes: -2.6536 for -0.2658). They had given -0.3253 for the S's -0.3032,
    0.4986 for the narrow S's 0.0178, and a full turn for the first (limits -5.570 and 0.468); a
    corrector that does not stop where its steps stop contracting gives 3.4654 for
    triad 658's 3.4696."""
    doc = folded_triad(name)
    result = sweep(parse_linkage(doc), 36, ["position"])
    assert not result.feasible
    low, high = (limit - drawn_crank(doc) for limit in result.limits)
    assert low == pytest.approx(first_fold(doc, -1), abs=1e-12)
    assert high == pytest.approx(first_fold(doc, 1), abs=1e-12)


@pytest.mark.slow
def test_a_range_wider_than_a_turn_is_a_rocker_from_its_end() -> None:
    """A triad whose limit positions lie 6.40 rad apart (-0.0553 and +6.3485 from the drawn
    pose, the first folds either way: ``first_fold``): from turn 0 the crank turns through a
    whole turn before meeting a limit, but the pose there is not the drawn one (the path does
    not close), so it rocks: ``Branch.limits(0, 2 pi)``, and asked from -1 rad too, are the two
    folds to 1e-12 rad (before, from turn 0, a full turn that did not close)."""
    doc = folded_triad("a range wider than a turn")
    folds = [first_fold(doc, sense) for sense in (-1, 1)]
    for low in (0.0, -1.0):
        limits = continuation.Branch(parse_linkage(doc)).limits(low, 2.0 * math.pi)
        assert limits is not None
        np.testing.assert_allclose(limits, folds, rtol=0.0, atol=1e-12)


def test_a_whole_turn_closes_where_the_crank_turns_fully() -> None:
    """The full-turning triad of benchmarks/bench_newton.py: the pose after a whole turn is the
    drawn one (``Branch.closes``), and its sweep is a full revolution; the rocker of
    ``test_a_range_wider_than_a_turn_is_a_rocker_from_its_end`` does not close after a turn
    from its drawn pose."""
    from benchmarks.bench_newton import FULL_TURN

    assert continuation.Branch(parse_linkage(FULL_TURN)).closes(0.0)
    assert sweep(parse_linkage(FULL_TURN), 36, ["position"]).feasible
    rocker = parse_linkage(folded_triad("a range wider than a turn"))
    assert not continuation.Branch(rocker).closes(0.0)


def test_a_singular_bordered_system_is_solved_by_least_squares() -> None:
    """``bordered_solve`` falls back to least squares where [J; row] is singular: x + y = 2
    bordered by the same row has the minimum-norm solution (1, 1) (1e-15)."""
    J, row = np.array([[1.0, 1.0]]), np.array([1.0, 1.0])
    z = continuation.bordered_solve(J, row, np.array([2.0]), 2.0)
    np.testing.assert_allclose(z, [1.0, 1.0], rtol=0.0, atol=1e-15)


def slot_crank_triad() -> Doc:
    """The rocking triad with its crank a single point O (no drawn angle: its angle is read as
    0 at the drawn pose) carrying a slot at 45 deg through O, in which T's P1 slides instead of
    riding on L1; T, L2, L3 are a Newton group (limit positions -0.591 and +0.003 rad)."""
    doc: Doc = copy.deepcopy(TRIAD)
    del doc["links"]["L1"], doc["points"]["A"]
    doc["links"]["crank"] = {"points": ["O"]}
    doc["joints"] = [j for j in doc["joints"] if j["point"] not in ("A", "P1")]
    doc["joints"].append(
        {"type": "slider", "point": "P1", "links": ["crank", "T"], "axis": [1.0, 1.0]}
    )
    return doc


def test_a_law_past_a_limit_names_the_first_sample_past_it() -> None:
    """The slot-crank triad driven by the law -t from t = 0 to 1 s (11 samples, turns 0, -0.1,
    ..., -1 rad): the first sample past its limit position is -0.6 rad (natural continuation
    from the drawn pose reaches -0.58 and is lost before -0.6), and the message gives that
    sample's crank angle, -34.3775 deg (a crank of one point has angle 0 as drawn)."""
    doc = slot_crank_triad()
    scene = parse_linkage(doc)
    reference_poses(scene, np.array([-0.58]), ())
    with pytest.raises(AssertionError, match="lost the loop"):
        reference_poses(scene, np.array([-0.6]), ())
    driven = {**doc, "drivers": [{"link": "crank", "angle_law": "-t"}]}
    with pytest.raises(NotAssemblable) as caught:
        sweep_time(parse_linkage(driven), 0.0, 1.0, 11)
    (angle,) = re.findall(r"crank angle (\S+) deg", str(caught.value))
    assert float(angle) == pytest.approx(math.degrees(-0.6), abs=1e-3)
    assert "turning crank from its drawn pose either way meets a limit position first" in str(
        caught.value
    )


def test_a_tolerance_out_of_reach_is_reported_with_the_residual(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    """The rocking triad at 6 turns inside its limits (not the drawn pose, which closes exactly)
    with no Newton-Raphson iteration allowed (POLISH_ITERATIONS lowered to 0: a tolerance out of
    reach, as a user's 1e-20 was before the rounding floor of ``newton.residual_tolerance``):
    every sample is reached, those that do not start on a node of the path (refined around them)
    do not close to the default 1e-13 of the size, and the message gives the residual against
    that tolerance (3.1e-13 m), not a limit position."""
    monkeypatch.setattr(continuation, "POLISH_ITERATIONS", 0)
    scene = parse_linkage(TRIAD)
    turns = np.linspace(-0.3, 0.6, 6)
    inputs = [DriverInput(turns, np.zeros(6), np.zeros(6))]
    groups = continuation.Continuation(scene)
    motion = assemble(scene, build_plan(scene), inputs, 0, continuation=True, newton_groups=groups)
    assert not np.all(motion.feasible)
    (message,) = motion.failures
    assert message.startswith("Newton-Raphson did not close the loop of T, L1, L2, L3: residual")
    tolerance = float(re.findall(r"> tolerance (\S+) m", message)[0])
    assert tolerance == pytest.approx(1e-13 * scene.size, rel=1e-2)


def test_a_leg_of_one_segment_is_refined_like_any_other(monkeypatch: pytest.MonkeyPatch) -> None:
    """/analyze of the rocking triad 0.05 rad from its drawn pose follows its path one step
    (0.1 of arclength: the leg is a single segment) and, with the branch gap lowered to 1e-11 so
    that the sample (which starts some 1e-10 of the size from its root) has its segment split
    (``Branch.refine``; see test_continuation_branch.py), still poses P1, P2, P3 at the 50-digit
    roots to 1e-12 m."""
    monkeypatch.setattr(continuation, "BRANCH_GAP", 1e-11)
    turn = 0.05
    result = analyze(parse_linkage(with_angle(TRIAD, math.degrees(drawn_crank(TRIAD) + turn))))
    points = np.array([result.points[name].position for name in UNKNOWN])
    np.testing.assert_allclose(points, reference_points(TRIAD, turn, points), rtol=0.0, atol=1e-12)


# Random triads (seed 14 as above: numbers 122 and 450, points rounded to 1e-6) whose limit
# positions the fold search finds only from good trials.
LOCATED_TRIADS = {
    "triad 122": {
        "A": [0.169368, 0.249326], "P1": [1.315089, 0.941657], "P2": [0.866878, 0.844602],
        "P3": [1.212406, 1.190112], "G2": [1.433027, 1.413623], "G3": [1.255425, -1.046427],
    },
    "triad 450": {
        "A": [0.113967, 0.361143], "P1": [1.048473, 0.084138], "P2": [0.733714, 0.29598],
        "P3": [0.419476, -0.29773], "G2": [1.361347, 2.184668], "G3": [2.121344, -1.438174],
    },
}  # fmt: skip


@pytest.mark.slow
@pytest.mark.parametrize("name", list(LOCATED_TRIADS))
def test_limit_positions_are_located_on_their_strand_to_rounding(name: str) -> None:
    """``Branch.limits`` of random triads 122 and 450 equal the first folds met either way from
    the drawn pose (``first_fold``) to 1e-12 rad. The fold search corrects each trial from the
    node's second-order prediction x + s tau + s^2/2 kappa on the normal plane at s (from x + s
    tau, or with 3 s^2/2 kappa, or -s^2/2 kappa, triad 122's trials land on other points of that
    plane's section of the path: 0.07 to 0.93 rad off), starts from the node's Newton trial
    -g / g' (from another, triad 450's upper limit comes out 0.07 rad off) and takes Newton's
    steps with the slope per unit of the step (a wrong slope or arclength factor: 9e-3 and 0.07
    rad off)."""
    doc = {**TRIAD, "points": {"O": [0.0, 0.0], **LOCATED_TRIADS[name]}}
    limits = continuation.Branch(parse_linkage(doc)).limits(0.0, 2.0 * math.pi)
    assert limits is not None
    folds = [first_fold(doc, sense) for sense in (-1, 1)]
    np.testing.assert_allclose(limits, folds, rtol=0.0, atol=1e-12)


@pytest.mark.slow
def test_a_range_wider_than_a_turn_is_a_rocker_whichever_way_it_turns() -> None:
    """A triad whose limit positions lie 7.23 rad apart, -7.181 and +0.0447 from the drawn pose:
    asked from -2 pi to 0 (a sweep turning the crank backwards) it meets no limit within that
    whole turn, but the path does not close there, and asked from 0 to 2 pi it meets +0.0447:
    both ways ``Branch.limits`` gives the first folds either way (``first_fold``) to 1e-12 rad
    (before, turning backwards, a full turn that did not close)."""
    doc = folded_triad("a range wider than a turn, its upper limit near")
    folds = [first_fold(doc, sense) for sense in (-1, 1)]
    for low, high in ((-2.0 * math.pi, 0.0), (0.0, 2.0 * math.pi)):
        limits = continuation.Branch(parse_linkage(doc)).limits(low, high)
        assert limits is not None
        np.testing.assert_allclose(limits, folds, rtol=0.0, atol=1e-12)

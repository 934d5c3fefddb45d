"""A Newton group's sweep does not depend on how finely its path is refined (issue 8: mutation
testing found the path's refinement, ``Branch.refine``, reached by no test).

A sample's starting value is interpolated on the followed path; when its first Newton step is
longer than ``continuation.BRANCH_GAP`` of the size, the path segment holding it is split and the
sample solved again. With the default gap (1e-2) the interpolation is so good that no case we
know of splits a segment, so these tests lower the gap to 1e-8, which splits segments around
most samples several times over. The answer must not change: the same feasibility and limits, the
same pose at every sample (to 1e-12 m, rounding of the final Newton-Raphson polish), on the
rocking triad (two limit positions) at 36 and 360 samples (where samples fall inside a leg's last
segment) and the fully turning one at 36.

Also the branch rule with two and three drivers (the others turned first, one after the other),
each sample against an independent natural-continuation reference path, and the messages where
a driver cannot be turned or a pose is beyond a limit (the absolute crank angle, off the origin).
"""

from __future__ import annotations

import math
import re
from typing import Any

import numpy as np
import pytest

from benchmarks.bench_newton import FULL_TURN
from solver.analysis.instant import analyze
from solver.analysis.sweeps import Sweep, sweep
from solver.errors import NotAssemblable
from solver.model.scene import LinkageScene, parse_linkage
from solver.position import continuation
from solver.position.constraints import ConstraintSystem, States
from tests.solver.position.test_newton import TRIAD
from tests.solver.position.test_newton_continuation import three_crank_triad, two_driver_triad


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
    """The interpolant of each path segment (continuation._quintic, in u = (s - s_k) / h) takes
    each end node's position, tangent times h and curvature times h^2 (1e-12), so the samples
    start close enough for two Newton-Raphson iterations (the cubic through positions and
    tangents needed three) on both triads at 360 and 3600 samples."""
    branch = continuation.Branch(parse_linkage(FULL_TURN))
    branch.limits(0.0, 2.0 * math.pi)
    s, X, T, K = branch.legs[1].arrays()
    k = np.arange(s.size - 1)
    h = np.diff(s)[:, None]
    quintic = continuation._quintic((s, X, T, K), k)
    powers = np.arange(6.0)
    for u, end in ((0.0, k), (1.0, k + 1)):
        at = u ** np.maximum(powers - 2, 0)[:, None, None]
        value = continuation._horner(quintic, np.full((k.size, 1), u))
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
    2.2e-4 and 7e-7 on the path with every segment halved, ``Branch._halved``)."""
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
    """``Branch._halved`` adds a node at the middle of every segment of the full-turning triad's
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
    s, X, T, K = branch._halved(leg)
    assert X.shape[0] == 2 * followed[1].shape[0] - 1
    np.testing.assert_array_equal(X[::2], followed[1])
    assert np.all(np.diff(s) > 0.0) and np.all(np.diff(X[:, branch.free]) > 0.0)
    assert branch.bending is not None
    for x, tau, kappa in zip(X[1::2], T[1::2], K[1::2], strict=True):
        F, J = branch._f(x)
        assert np.linalg.norm(F) <= 1e-9
        assert np.linalg.norm(J @ tau) <= 1e-12 and abs(np.linalg.norm(tau) - 1.0) <= 1e-12
        bent = J @ kappa - branch.bending(x, tau)
        assert np.linalg.norm(bent) <= 1e-10 * np.linalg.norm(kappa)
        assert abs(tau @ kappa) <= 1e-10 * np.linalg.norm(kappa)
    rocking = continuation.Branch(parse_linkage(TRIAD))
    rocking.limits(0.0, 2.0 * math.pi)
    for each in rocking.legs.values():
        assert each.gap <= continuation.HALVING_RESIDUAL
        assert rocking._halved(each)[1].shape == each.arrays()[1].shape

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

"""Newton groups' batched polish (``continuation.solve_group``, ``_Polish``) and Newton-Raphson
(``solver/position/newton.py``) against independent values: tests added for the mutants that
survived
their first mutation run (issue 8).

Sources:

- 50-digit roots (mpmath) of the triad's length equations at the crank's turn
  (``test_continuation_mutants.reference_points``), as each link's (x, y, theta).
- The loop's residual recomputed from the links' motions, not by ``solver.position.constraints``:
every
  joint's point as each of its two links carries it, X = anchor + R(theta) (X0 - anchor0), and
  their gap (for a slider, the gap across the slot, turned with its guide).
- One Newton-Raphson step recomputed from that residual with a central-difference Jacobian.
- Central differences of the 50-digit roots in the crank's turn for the rates.
- Closed forms: a structure (no driver) rests at its drawing; a four-bar drawn with its crank,
  coupler and rocker on one line closes there (two tangent circles), where the group's Jacobian
  is exactly singular.
- A natural-continuation reference path (``test_continuation_branch._path_to``) for three
  drivers turning at once.
- The documented rules (docs/ARCHITECTURE.md, "Newton groups"): the tolerance's bounds
  1e-15 .. 1e-6 (``newton.TOLERANCE_BOUNDS``) and the residual within tolerance x size; the
  iteration cap; the polishing step taken only by a converged sample not already at rounding,
  and kept only where it lowers the residual, and none above the default tolerance; a sample
  accepted only within two first Newton steps of its start and with its first step under
  ``BRANCH_GAP`` of the size, else its path segment split and the sample solved again, at most
  ``MAX_REFINEMENTS`` times.
"""

from __future__ import annotations

import copy
import functools
import math
import re
from collections.abc import Callable, Mapping, Sequence
from typing import Any

import numpy as np
import pytest

from solver.analysis.instant import analyze
from solver.analysis.sweeps import sweep, sweep_time
from solver.errors import InvalidScene
from solver.kinematics.rigid import LinkMotion, PointMotion, fixed_link
from solver.model.scene import LinkageScene, parse_linkage
from solver.position import constraints, continuation, newton
from solver.position.continuation import Continuation, solve_group
from tests.solver.position.test_continuation_branch import _drawn_angle, _path_to, assert_follows
from tests.solver.position.test_continuation_mutants import UNKNOWN, reference_points, slider_triad
from tests.solver.position.test_newton import TRIAD
from tests.solver.position.test_newton_continuation import three_crank_triad

Doc = dict[str, Any]
GROUP = ("T", "L1", "L2", "L3")  # the triad's Newton group (the slider triad's lacks L3)
OMEGA, ALPHA = 2.0, 0.5  # the crank's rates in TRIAD


def joint_gaps(
    scene: LinkageScene, links: Mapping[str, LinkMotion], group: Sequence[str]
) -> np.ndarray:
    """Phi (M, rows) from the links' motions: at every joint of a link of ``group``, X_f - X_g,
    its point as carried by its two links (guide g = ``links[0]``, follower f); for a slider
    only the gap's component across the slot, the drawn axis turned with the guide. Motions of
    one sample broadcast against those of M."""
    rows = []
    for joint in scene.joints:
        if not set(joint.links) & set(group):
            continue
        drawn = scene.drawn(joint.point)
        guide, follower = (links[name].point(drawn).p for name in joint.links)
        gap = follower - guide
        if joint.axis is None:
            rows += [gap[:, 0], gap[:, 1]]
        else:
            turn, (ax, ay) = links[joint.links[0]].theta, joint.axis
            w = np.cos(turn) * ax - np.sin(turn) * ay, np.sin(turn) * ax + np.cos(turn) * ay
            rows.append(w[0] * gap[:, 1] - w[1] * gap[:, 0])
    return np.stack(rows, axis=1)


def loop_residual(
    scene: LinkageScene, links: Mapping[str, LinkMotion], group: Sequence[str]
) -> np.ndarray:
    """|Phi| at each sample (``joint_gaps``)."""
    return np.sqrt(np.sum(joint_gaps(scene, links, group) ** 2, axis=1))


def group_links(scene: LinkageScene, group: Sequence[str], q: np.ndarray) -> dict[str, LinkMotion]:
    """The group's links at (M, 3U) coordinates q: each link's first point (x, y) and its rotation
    theta from the drawing."""
    out = {}
    for k, link in enumerate(group):
        anchor0 = scene.drawn(scene.links[link].points[0])
        out[link] = LinkMotion(anchor0, PointMotion(q[:, 3 * k : 3 * k + 2]), q[:, 3 * k + 2])
    return out


def crank_and_ground(scene: LinkageScene, turns: np.ndarray) -> dict[str, LinkMotion]:
    """The known links of the triads' groups: the ground, and the crank about O at ``turns``
    (omega 2, alpha 0.5)."""
    samples = turns.size
    pivot = scene.drawn("O")
    still = PointMotion(
        np.tile(pivot, (samples, 1)), np.zeros((samples, 2)), np.zeros((samples, 2))
    )
    crank = LinkMotion(pivot, still, turns, np.full(samples, OMEGA), np.full(samples, ALPHA))
    return {"crank": crank, scene.ground: fixed_link(pivot, samples)}


def reference_coordinates(doc: Doc, group: Sequence[str], turn: float) -> np.ndarray:
    """The 50-digit roots at the crank's ``turn`` (started from the drawing) as each link's
    (x, y, theta): its first point, and the turn of the vector to its second point."""
    drawn = {name: np.array(p, dtype=float) for name, p in doc["points"].items()}
    start = np.array([drawn[p] for p in UNKNOWN])
    at = {**drawn, **dict(zip(UNKNOWN, reference_points(doc, turn, start), strict=True))}
    c, s = math.cos(turn), math.sin(turn)
    at["A"] = drawn["O"] + np.array([[c, -s], [s, c]]) @ (drawn["A"] - drawn["O"])
    q = []
    for link in group:
        first, second = doc["links"][link]["points"][:2]
        u, v = drawn[second] - drawn[first], at[second] - at[first]
        q += [*at[first], math.atan2(u[0] * v[1] - u[1] * v[0], u @ v)]
    return np.array(q)


def test_the_tolerance_must_lie_within_its_bounds() -> None:
    """``newton_tolerance``: None is the default 1e-13; 1e-15 and 1e-6 (the bounds) are taken
    as given; anything else, finite or not, is refused with the bounds named."""
    assert newton.newton_tolerance(None) == 1e-13
    for value in (1e-15, 1e-9, 1e-6):
        assert newton.newton_tolerance(value) == value
    for value in (9.9e-16, 1.01e-6, 1e-3, 0.0, -1e-10, math.nan, math.inf):
        with pytest.raises(InvalidScene, match=r"outside 1e-15 \.\. 1e-06 .* default 1e-13"):
            newton.newton_tolerance(value)


def test_a_structure_with_no_driver_rests_at_its_drawing() -> None:
    """The triad with its crank made part of the ground (A a ground point): a structure, no
    driver, its Newton group solved once at the drawn pose, where it closes by construction:
    every point where drawn (to 1e-15 m), at rest, no iteration, one sample."""
    doc: Doc = copy.deepcopy(TRIAD)
    doc["links"]["ground"]["points"] = ["O", "A", "G2", "G3"]
    del doc["links"]["crank"]
    doc["joints"] = [j for j in doc["joints"] if j["point"] not in ("O", "A")]
    doc["joints"].append({"type": "revolute", "point": "A", "links": ["ground", "L1"]})
    doc["drivers"] = []
    result = analyze(parse_linkage(doc))
    for name, drawn in doc["points"].items():
        point = result.points[name]
        np.testing.assert_allclose(point.position, drawn, rtol=0.0, atol=1e-15)
        np.testing.assert_array_equal(point.velocity, [0.0, 0.0])
        np.testing.assert_array_equal(point.acceleration, [0.0, 0.0])
        assert result.motion.points[name].p.shape == (1, 2)
    (report,) = result.diagnostics.newton
    assert report.iterations == 0 and report.converged.tolist() == [True]
    assert report.message == "Newton-Raphson closed the loop of T, L1, L2, L3"


def three_driver_triad() -> Doc:
    """The triad with both ground pivots on driven cranks (``three_crank_triad``), the
    second crank drawn 5 deg from its drawn angle and turning back at -0.5 rad/s, the third
    drawn -10 deg from it and turning at 0.3 rad/s: at t = 0 the second's turn is the larger."""
    doc = three_crank_triad(80.0)
    doc["drivers"][1] |= {"angle_deg": -85.0, "omega": -0.5}
    return doc


def test_three_drivers_turning_at_once_follow_the_branch_rule_at_every_instant() -> None:
    """Over t = 0 .. 0.5 s all three cranks turn, so every sample holds the second and third at
    turns of its own (a branch each; at t = 0 the second's, +5 deg, above the third's, -10 deg):
    each sample equals the reference path that turns the second crank, then the third, then the
    first to that sample's turns (1e-9 m); the report has every sample converged."""
    doc = three_driver_triad()
    scene = parse_linkage(doc)
    times = np.linspace(0.0, 0.5, 6)
    result = sweep_time(scene, 0.0, 0.5, times.size, ["position"])
    second = math.radians(-85.0) - _drawn_angle(doc, "H", "G2") - 0.5 * times
    third = math.radians(80.0) - _drawn_angle(doc, "J", "G3") + 0.3 * times
    reference = [
        _path_to(scene, [t2, t3], np.array([t1]))[0]
        for t1, t2, t3 in zip(times, second, third, strict=True)
    ]
    assert_follows(result, scene, reference)
    (report,) = result.motion.newton
    assert report.converged.tolist() == [True] * times.size


def coordinates(motions: Mapping[str, LinkMotion], group: Sequence[str]) -> np.ndarray:
    """(M, 3U): each link's anchor (x, y) and rotation theta, in the order of ``group``."""
    return np.concatenate(
        [np.column_stack([motions[link].anchor.p, motions[link].theta]) for link in group], axis=1
    )


def triad(name: str) -> tuple[Doc, tuple[str, ...]]:
    """The rocking triad (limits -0.391 and +0.717 rad) or the slider triad, and its group."""
    return (TRIAD, GROUP) if name == "triad" else (slider_triad(), GROUP[:3])


@pytest.mark.parametrize("name", ["triad", "slider triad"])
def test_samples_not_closed_within_the_iteration_cap_are_reported_with_the_numbers(
    name: str, monkeypatch: pytest.MonkeyPatch
) -> None:
    """The polish's iteration cap lowered to 1 (``POLISH_ITERATIONS``) and no refinement
    (``MAX_REFINEMENTS`` 0): after one Newton step from the path's starts, samples across the
    range are 1e-16 .. 1e-8 of the size off closing. Exactly those whose residual, recomputed
    from the returned motions, exceeds 1e-13 x size are not converged, and the message gives
    the worst residual (the recomputed one, to its 3 printed digits), that tolerance and
    1 iteration. (The triad is polished in its rotations, the slider triad in every link's
    (x, y, theta): ``newton_rotations`` and ``newton_raphson``.)"""
    doc, group = triad(name)
    scene = parse_linkage(doc)
    monkeypatch.setattr(continuation, "POLISH_ITERATIONS", 1)
    monkeypatch.setattr(continuation, "MAX_REFINEMENTS", 0)
    turns = np.linspace(-0.35, 0.7, 12)
    known = crank_and_ground(scene, turns)
    motions, report = solve_group(scene, group, known, [turns], 2, Continuation(scene))
    residual = loop_residual(scene, {**known, **motions}, group)
    tolerance = 1e-13 * scene.size
    assert report.converged.tolist() == (residual <= tolerance).tolist()
    assert 0 < np.count_nonzero(report.converged) < turns.size
    assert report.iterations == 1
    assert report.residual_norm == pytest.approx(np.max(residual), rel=1e-6)
    assert report.tolerance == pytest.approx(tolerance, rel=1e-15)
    found = re.fullmatch(
        rf"Newton-Raphson did not close the loop of {', '.join(group)}: residual (\S+) m > "
        r"tolerance (\S+) m after (\d+) iterations",
        report.message,
    )
    assert found is not None, report.message
    assert float(found[1]) == pytest.approx(np.max(residual), rel=5e-3)
    assert float(found[2]) == pytest.approx(tolerance, rel=5e-3)
    assert found[3] == "1"


def test_samples_that_never_settle_are_refined_at_most_max_refinements_times(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    """``BRANCH_GAP`` made negative: no first Newton step is ever short enough, so no sample
    settles. The path is refined around all three samples ``MAX_REFINEMENTS`` (12) times and no
    more; every sample is reported not converged, "could not follow the branch", though each
    closed its loop: equal to the 50-digit roots (1e-12 m)."""
    scene = parse_linkage(TRIAD)
    monkeypatch.setattr(continuation, "BRANCH_GAP", -1.0)
    turns = np.array([-0.3, 0.2, 0.6])
    groups = Continuation(scene)
    branch = groups.branch(())
    refined: list[np.ndarray] = []
    refine = branch.refine
    monkeypatch.setattr(branch, "refine", lambda ways: (refined.append(ways), refine(ways))[1])
    motions, report = solve_group(scene, GROUP, crank_and_ground(scene, turns), [turns], 2, groups)
    assert len(refined) == continuation.MAX_REFINEMENTS == 12
    for ways in refined:
        np.testing.assert_array_equal(ways, turns)
    assert report.converged.tolist() == [False] * 3
    assert report.message == (
        "Newton-Raphson could not follow the branch of T, L1, L2, L3 to every sample"
    )
    reference = np.array([reference_coordinates(TRIAD, GROUP, turn) for turn in turns])
    np.testing.assert_allclose(coordinates(motions, GROUP), reference, rtol=0.0, atol=1e-12)


def test_a_sample_beyond_the_limits_is_named_by_its_crank_angle() -> None:
    """The triad's group asked at turns 0.2, 0.9 and -0.1 rad: 0.9 lies past its upper limit
    (0.717 rad) and 0.9 - 2 pi past its lower (-0.391 rad), so that sample alone is not
    reached and not converged, and the message gives its crank angle, atan2(0.2, 0.3) + 0.9 rad
    in degrees (6 digits); the other two equal the 50-digit roots (1e-12 m)."""
    scene = parse_linkage(TRIAD)
    turns = np.array([0.2, 0.9, -0.1])
    known = crank_and_ground(scene, turns)
    motions, report = solve_group(scene, GROUP, known, [turns], 2, Continuation(scene))
    assert report.converged.tolist() == [True, False, True]
    angle = math.degrees(math.atan2(0.2, 0.3) + 0.9)
    assert report.message == (
        f"the loop of T, L1, L2, L3 cannot be closed at crank angle {angle:.6g} deg: turning "
        "crank from its drawn pose either way meets a limit position first"
    )
    reference = np.array([reference_coordinates(TRIAD, GROUP, turn) for turn in turns[[0, 2]]])
    np.testing.assert_allclose(coordinates(motions, GROUP)[[0, 2]], reference, rtol=0.0, atol=1e-12)


class _Path:
    """Stands in for ``Branch`` in ``_Polish.run``: every turn reached, each sample's start the
    drawn pose (the outcomes below do not depend on it), and the turns it is asked to refine
    around."""

    def __init__(self, scene: LinkageScene) -> None:
        self.width = 3 * len(scene.moving_links)
        self.refined: list[list[float]] = []

    def guesses(self, turns: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        return np.zeros((turns.size, self.width)), np.ones(turns.size, dtype=bool), turns

    def refine(self, turns: np.ndarray) -> None:
        self.refined.append(turns.tolist())


def outcomes_of_newton(
    first: np.ndarray, after: np.ndarray, attempts: list[int]
) -> Callable[..., tuple[np.ndarray, np.ndarray, int, np.ndarray, np.ndarray]]:
    """A stand-in for ``_Polish._newton``: each sample's (residual, first step, whole move) from
    ``first`` at the first attempt and from ``after`` at the others, q left at its start; the
    number of samples solved at each attempt is appended to ``attempts``."""

    def outcome(
        polish: continuation._Polish, todo: np.ndarray, q0: np.ndarray
    ) -> tuple[np.ndarray, np.ndarray, int, np.ndarray, np.ndarray]:
        rows = (after if attempts else first)[todo]
        attempts.append(todo.size)
        return q0, rows[:, 0], 1, rows[:, 1], rows[:, 2]

    return outcome


def test_a_sample_settles_only_near_its_start_with_a_short_first_step(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    """The rule of acceptance, fed Newton-Raphson's outcomes directly (``_Polish._newton``
    replaced): a sample settles where its residual is within tolerance x size, its whole move
    within two first steps (+ 1e-9 of the size, for a start already closed: first step 0), and
    its first step within ``BRANCH_GAP`` of the size; the others have their path refined around
    them and are solved again. Samples (residual in tolerances, first step and move in gaps):
    a (0.5, 0.5, 0.95), b (0.5, 0.5, 1.05) past two first steps, d (2, 0.5, 0.5) above
    tolerance, e (0.5, 2, 2) a long first step; and in sizes c (0.5, 0, 0.5e-9) and
    f (0.5, 0, 2e-9): one refinement around b, d, e and f, then (all closed) every sample
    settled. A sample that never settles is refined ``MAX_REFINEMENTS`` times."""
    scene = parse_linkage(TRIAD)
    size = scene.size
    tolerance, gap = 1e-13 * size, continuation.BRANCH_GAP * size
    first = np.array([
        (0.5 * tolerance, 0.5 * gap, 0.95 * gap),
        (0.5 * tolerance, 0.5 * gap, 1.05 * gap),
        (0.5 * tolerance, 0.0, 0.5e-9 * size),
        (2.0 * tolerance, 0.5 * gap, 0.5 * gap),
        (0.5 * tolerance, 2.0 * gap, 2.0 * gap),
        (0.5 * tolerance, 0.0, 2e-9 * size),
    ])  # fmt: skip
    closed = np.tile((0.5 * tolerance, 0.0, 0.0), (6, 1))
    never = closed.copy()
    never[2, 0] = 2.0 * tolerance
    system = constraints.constraint_system(scene, GROUP)
    turns = np.linspace(0.1, 0.6, 6)
    states = constraints.states(crank_and_ground(scene, turns), scene)
    for (start, then), refined, settled in (
        ((first, closed), [turns[[1, 3, 4, 5]].tolist()], [True] * 6),
        ((never, never), [[turns[2]]] * continuation.MAX_REFINEMENTS, [1, 1, 0, 1, 1, 1]),
    ):
        attempts: list[int] = []
        monkeypatch.setattr(
            continuation._Polish, "_newton", outcomes_of_newton(start, then, attempts)
        )
        polish = continuation._Polish(system, states, turns.size, Continuation(scene))
        path = _Path(scene)
        polish.run(np.arange(turns.size), path, turns)
        assert path.refined == refined
        assert attempts == [6] + [len(ways) for ways in refined]
        assert polish.settled.tolist() == [bool(k) for k in settled]


def test_a_samples_move_and_first_step_weigh_rotations_by_the_size() -> None:
    """``_Polish._newton`` from the 50-digit roots displaced by d (per link 2e-3 m in x,
    -1e-3 m in y, 1.5e-3 rad): back at the roots (1e-12), its whole move is the length of d
    with rotations times the size, sqrt(sum dx^2 + dy^2 + (size dtheta)^2) (1e-9 relative), its
    first step the same to first order in d (1e-2); one sample of the two alone, the same."""
    scene = parse_linkage(TRIAD)
    turns = np.array([0.3, -0.2])
    roots = np.array([reference_coordinates(TRIAD, GROUP, turn) for turn in turns])
    d = np.tile([2e-3, -1e-3, 1.5e-3], len(GROUP))
    length = math.sqrt(len(GROUP) * (2e-3**2 + 1e-3**2 + (1.5e-3 * scene.size) ** 2))
    system = constraints.constraint_system(scene, GROUP)
    states = constraints.states(crank_and_ground(scene, turns), scene)
    polish = continuation._Polish(system, states, turns.size, Continuation(scene))
    for todo in (np.arange(2), np.array([1])):
        q, _, _, first, moved = polish._newton(todo, roots[todo] + d)
        np.testing.assert_allclose(q, roots[todo], rtol=0.0, atol=1e-12)
        np.testing.assert_allclose(moved, length, rtol=1e-9)
        np.testing.assert_allclose(first, length, rtol=1e-2)


def scaled(doc: Doc, factor: float) -> Doc:
    """The same linkage drawn ``factor`` times larger."""
    return {**doc, "points": {name: [factor * x for x in p] for name, p in doc["points"].items()}}


@pytest.mark.parametrize("name", ["triad", "slider triad"])
@pytest.mark.parametrize(("tolerance", "factor"), [(None, 1.0), (None, 1e-3), (1e-6, 1.0)])
def test_the_reported_residual_is_the_loops_and_within_the_tolerance(
    name: str, tolerance: float | None, factor: float
) -> None:
    """A 36-sample sweep: the worst residual recomputed from the swept motions is the report's
    (to rounding, 4 eps x size) and within tolerance x size, every sample converged. At the
    default 1e-13 every sample takes the polishing step to rounding (4 eps x size), the linkage
    drawn at 1 m as at 1 mm (a polishing threshold of eps x size, not eps / size); at 1e-6 no
    sample takes one: each stays at the first Newton iterate within the tolerance, the worst
    above 1e-9 of the size (one more step would bring it to ~1e-13)."""
    doc, group = triad(name)
    scene = parse_linkage(scaled(doc, factor))
    result = sweep(scene, 36, ["position"], tolerance)
    (report,) = result.motion.newton
    residual = loop_residual(scene, result.motion.links, group)
    relative = newton.NEWTON_TOLERANCE if tolerance is None else tolerance
    rounding = 4.0 * newton.ROUNDING * scene.size
    assert report.relative_tolerance == relative
    assert report.tolerance == pytest.approx(relative * scene.size, rel=1e-15)
    assert report.converged.all() and report.message.startswith("Newton-Raphson closed")
    assert abs(report.residual_norm - np.max(residual)) <= rounding
    assert np.max(residual) <= relative * scene.size
    if tolerance is None:
        assert np.max(residual) <= rounding
    else:
        assert np.max(residual) > 1e-9 * scene.size


def triad_system(
    turns: np.ndarray,
) -> tuple[LinkageScene, constraints.ConstraintSystem, dict[str, constraints.States]]:
    """The triad's group with its crank at ``turns``: scene, equations and known links."""
    scene = parse_linkage(TRIAD)
    system = constraints.constraint_system(scene, GROUP)
    return scene, system, constraints.states(crank_and_ground(scene, turns), scene)


def newton_on(
    evaluation: str, turns: np.ndarray, start: np.ndarray, tolerance: float, **options: Any
) -> tuple[np.ndarray, np.ndarray, int, np.ndarray]:
    """Newton-Raphson on the triad's group at ``turns`` from ``start``: ``newton_rotations``
    (Phi by matrix products, steps in the rotations) or ``newton_raphson`` (the whole system)."""
    scene, system, known = triad_system(turns)
    if evaluation == "whole system":
        return newton.newton_raphson(system, known, start, tolerance, **options)
    form, rotations = system.linear, system.rotations(turns.size)
    assert form is not None and rotations is not None
    fixed = form.known_terms(known, turns.size, 0, None)[0]
    return newton.newton_rotations(form, rotations, fixed, start, scene.size, tolerance, **options)


def gaps_at(scene: LinkageScene, turn: float, q: np.ndarray) -> np.ndarray:
    """``joint_gaps`` of the triad's group at (K, 12) coordinates q, the crank at ``turn``."""
    links = {**crank_and_ground(scene, np.array([turn])), **group_links(scene, GROUP, q)}
    return joint_gaps(scene, links, GROUP)


def newton_step(scene: LinkageScene, turn: float, q: np.ndarray) -> np.ndarray:
    """q - J^-1 Phi(q): Phi the joints' gaps (``gaps_at``), J their central differences in each
    coordinate (step 1e-6: truncation ~1e-12 of J, rounding ~1e-10)."""
    h = 1e-6
    shifts = h * np.eye(q.size)
    ahead, behind = gaps_at(scene, turn, q + shifts), gaps_at(scene, turn, q - shifts)
    J = ((ahead - behind) / (2.0 * h)).T
    return q - np.linalg.solve(J, gaps_at(scene, turn, q[None])[0])


@pytest.mark.parametrize("evaluation", ["rotations", "whole system"])
def test_newton_raphson_stops_at_its_iteration_cap(evaluation: str) -> None:
    """From the 50-digit roots at two turns displaced by 2e-2 (m and rad), capped at one
    iteration: one iteration reported, each sample exactly one Newton step from its start
    (q1 = q0 - J^-1 Phi(q0), recomputed from the joints' gaps and their central differences,
    1e-9), its residual the gaps' at q1 (1e-9 relative), far above the tolerance, and the first
    step's length sqrt(dx^2 + dy^2 + (size dtheta)^2): no polishing step for a sample that has
    not converged."""
    turns = np.array([0.3, -0.2])
    roots = np.array([reference_coordinates(TRIAD, GROUP, turn) for turn in turns])
    start = roots + np.tile([2e-2, -2e-2, 2e-2], len(GROUP))
    scene = parse_linkage(TRIAD)
    tolerance = 1e-13 * scene.size
    q, residual, iterations, first = newton_on(
        evaluation, turns, start, tolerance, max_iterations=1
    )
    assert iterations == 1
    weights = np.tile([1.0, 1.0, scene.size], len(GROUP))
    for k, turn in enumerate(turns):
        step = newton_step(scene, turn, start[k])
        np.testing.assert_allclose(q[k], step, rtol=0.0, atol=1e-9)
        recomputed = np.linalg.norm(gaps_at(scene, turn, q[k : k + 1]))
        assert residual[k] == pytest.approx(recomputed, rel=1e-9)
        assert residual[k] > 1e6 * tolerance
        assert first[k] == pytest.approx(np.linalg.norm((start[k] - step) * weights), rel=1e-9)


@pytest.mark.parametrize("evaluation", ["rotations", "whole system"])
def test_each_sample_stops_at_its_first_iterate_within_the_tolerance(evaluation: str) -> None:
    """Tolerance 1e-6 x size, no polishing step: of the 50-digit roots displaced by 1e-9 (within
    the tolerance) and by 2e-2 (not), the first sample is returned exactly as it started (no
    step evaluated for it), its residual the gaps' there (1e-6 relative), while the second
    iterates to within the tolerance (its recomputed residual), and no further."""
    turns = np.array([0.3, -0.2])
    roots = np.array([reference_coordinates(TRIAD, GROUP, turn) for turn in turns])
    start = roots + np.outer([1e-9, 2e-2], np.tile([1.0, -1.0, 1.0], len(GROUP)))
    scene = parse_linkage(TRIAD)
    tolerance = 1e-6 * scene.size
    q, residual, iterations, _ = newton_on(evaluation, turns, start, tolerance, polish=False)
    np.testing.assert_array_equal(q[0], start[0])
    assert residual[0] == pytest.approx(np.linalg.norm(gaps_at(scene, 0.3, start[:1])), rel=1e-6)
    assert iterations >= 2
    recomputed = np.linalg.norm(gaps_at(scene, -0.2, q[1:]))
    assert residual[1] == pytest.approx(recomputed, rel=1e-6)
    assert 1e-10 * scene.size < recomputed <= tolerance


COLLINEAR_FOUR_BAR: Doc = {
    "kind": "linkage",
    "points": {"O": [0.0, 0.0], "B": [1.0, 0.0], "C": [2.0, 0.0], "D": [3.0, 0.0]},
    "links": {"ground": {"points": ["O", "D"], "ground": True}, "crank": {"points": ["O", "B"]},
              "coupler": {"points": ["B", "C"]}, "rocker": {"points": ["D", "C"]}},
    "joints": [{"type": "revolute", "point": p, "links": pair}
               for p, pair in (("O", ["ground", "crank"]), ("B", ["crank", "coupler"]),
                               ("C", ["coupler", "rocker"]), ("D", ["rocker", "ground"]))],
    "drivers": [{"link": "crank", "omega": 1.0, "alpha": 0.0}],
}  # fmt: skip


@pytest.mark.parametrize("evaluation", ["rotations", "whole system"])
def test_a_singular_sample_is_stepped_by_least_squares(evaluation: str) -> None:
    """A four-bar drawn with crank, coupler and rocker on one line (O, B, C, D at 0, 1, 2, 3 m)
    solved for its coupler and rocker with the crank as drawn: C = (2, 0) is where the circles
    |BC| = 1 and |DC| = 1 touch (a double root), and the group's Jacobian is exactly singular
    there (LU meets a zero pivot), so the step is the least-squares one, of least length. From
    the drawn pose with both links moved 1e-3 m along the line (no turn), that step is the move
    back (it is orthogonal to J's null vector, the links turning about B and D): one iteration,
    the drawn pose (1e-15 m), the residual rounding."""
    scene = parse_linkage(COLLINEAR_FOUR_BAR)
    group = ("coupler", "rocker")
    system = constraints.constraint_system(scene, group)
    known = constraints.states(crank_and_ground(scene, np.zeros(1)), scene)
    drawn = system.drawn()[None]
    start = drawn + np.array([[1e-3, 0.0, 0.0, 1e-3, 0.0, 0.0]])
    tolerance = 1e-13 * scene.size
    if evaluation == "whole system":
        q, residual, iterations, _ = newton.newton_raphson(system, known, start, tolerance)
    else:
        form, rotations = system.linear, system.rotations(1)
        assert form is not None and rotations is not None
        fixed = form.known_terms(known, 1, 0, None)[0]
        q, residual, iterations, _ = newton.newton_rotations(
            form, rotations, fixed, start, scene.size, tolerance
        )
    assert iterations == 1
    np.testing.assert_allclose(q, drawn, rtol=0.0, atol=1e-15)
    links = {**crank_and_ground(scene, np.zeros(1)), **group_links(scene, system.unknown, q)}
    assert residual[0] <= 4.0 * newton.ROUNDING * scene.size
    assert loop_residual(scene, links, group)[0] <= 4.0 * newton.ROUNDING * scene.size


@functools.cache
def reference_rates(name: str, turn: float) -> tuple[np.ndarray, np.ndarray]:
    """dq/dt and d2q/dt2 of the 50-digit roots (``reference_coordinates``) with the crank at
    ``turn`` turning at OMEGA, ALPHA: q' omega and q'' omega^2 + q' alpha, q' and q'' their
    central differences in the turn (step 1e-4 rad: truncation ~1e-9 of them, rounding of the
    roots 1e-16 / h^2 = 1e-8)."""
    doc, group = triad(name)
    h = 1e-4
    behind, at, ahead = (reference_coordinates(doc, group, turn + k * h) for k in (-1, 0, 1))
    slope, bend = (ahead - behind) / (2.0 * h), (ahead - 2.0 * at + behind) / (h * h)
    return slope * OMEGA, bend * OMEGA**2 + slope * ALPHA


def rates(motions: Mapping[str, LinkMotion], group: Sequence[str], order: int) -> np.ndarray | None:
    """(M, 3U) velocities (v, omega) or accelerations (a, alpha) of the group's links' anchors."""
    columns = []
    for link in group:
        motion = motions[link]
        point, turning = (
            (motion.anchor.v, motion.omega)
            if order == 1
            else (
                motion.anchor.a,
                motion.alpha,
            )
        )
        if point is None or turning is None:
            return None
        columns.append(np.column_stack([point, turning]))
    return np.concatenate(columns, axis=1)


@pytest.mark.parametrize(
    ("name", "evaluation"),
    [("slider triad", "joint by joint"), ("triad", "joint by joint"), ("triad", "no rotations")],
)
@pytest.mark.parametrize("order", [1, 2])
def test_rates_equal_central_differences_of_the_50_digit_roots(
    name: str, evaluation: str, order: int, monkeypatch: pytest.MonkeyPatch
) -> None:
    """Velocities (order 1) and accelerations (order 2) of the group at three turns, with the
    crank at omega 2, alpha 0.5 rad/s^2: equal to central differences of the 50-digit roots
    (1e-6 of the largest), positions to the roots (1e-12). The triad's group is evaluated
    joint by joint (``DENSE_UNKNOWNS`` lowered to 0, as for a group of more than 24 unknowns:
    Newton-Raphson on the whole system, rates from ``ConstraintSystem.evaluate``) or with its
    linear form but no equations in the rotations alone (``ConstraintSystem.rotations`` None:
    the linear form's b_a = -Phi_known'' + (K_c cos + K_s sin) omega^2); the slider triad has
    no linear form."""
    doc, group = triad(name)
    scene = parse_linkage(doc)
    if evaluation == "joint by joint":
        monkeypatch.setattr(constraints, "DENSE_UNKNOWNS", 0)
    else:
        monkeypatch.setattr(constraints.ConstraintSystem, "rotations", lambda system, m: None)
    turns = np.array([-0.15, 0.1, 0.4])
    known = crank_and_ground(scene, turns)
    motions, _ = solve_group(scene, group, known, [turns], order, Continuation(scene))
    reference = np.array([reference_coordinates(doc, group, turn) for turn in turns])
    np.testing.assert_allclose(coordinates(motions, group), reference, rtol=0.0, atol=1e-12)
    solved = rates(motions, group, order)
    assert solved is not None and (order == 2 or rates(motions, group, 2) is None)
    expected = np.array([reference_rates(name, turn)[order - 1] for turn in turns])
    np.testing.assert_allclose(solved, expected, rtol=0.0, atol=1e-6 * np.abs(expected).max())


@pytest.mark.parametrize("name", ["triad", "slider triad"])
@pytest.mark.parametrize(("shift", "tolerance"), [(1e4, None), (1e5, None), (30.0, 1e-15)])
def test_a_linkage_drawn_far_from_the_origin_closes_to_the_rounding_of_its_coordinates(
    name: str, shift: float, tolerance: float | None
) -> None:
    """The triads (3 m across) drawn 1e4 and 1e5 m from the origin (coordinates up to 1e6 m
    are allowed), or 30 m from it at the tightest tolerance, 1e-15: their positions are rounded
    to eps x 1e4 m = 2e-12 m, so no pose closes the loop to 1e-13 x 3 m (or 1e-15 x 3 m at
    30 m). Swept (36 samples), they are assembled all the same, every 5th sample equal to the
    50-digit roots to the rounding of the coordinates (16 eps x the largest), and the report
    states the tolerance worked to: tolerance x size, but no less than sqrt(rows) eps x the
    largest coordinate (the rounding of |Phi|), with the residual within it."""
    doc, group = triad(name)
    moved = {point: [x + shift, y - shift] for point, (x, y) in doc["points"].items()}
    doc = {**doc, "points": moved}
    scene = parse_linkage(doc)
    result = sweep(scene, 36, ["position"], tolerance)
    (report,) = result.motion.newton
    largest = max(abs(x) for point in moved.values() for x in point)
    rows = constraints.constraint_system(scene, group).rows
    relative = newton.NEWTON_TOLERANCE if tolerance is None else tolerance
    floor = math.sqrt(rows) * newton.ROUNDING * largest
    assert report.tolerance == pytest.approx(max(relative * scene.size, floor), rel=1e-12)
    assert report.converged.all() and report.residual_norm <= report.tolerance
    turns = result.driver_angle - math.atan2(0.2, 0.3)
    for k in range(0, 36, 5):
        swept = np.array([result.motion.points[p].p[k] for p in UNKNOWN])
        reference = reference_points(doc, float(turns[k]), swept)
        np.testing.assert_allclose(
            swept, reference, rtol=0.0, atol=16.0 * newton.ROUNDING * largest
        )


def test_the_polishing_step_is_kept_only_where_it_lowers_the_residual() -> None:
    """The triad drawn 1e4 m from the origin, started at its 50-digit roots at 12 turns (in
    doubles: residuals ~1e-12 m, the rounding of coordinates that large, within the tolerance
    but above eps x size, so each sample is given a polishing step): from there a step lowers
    the residual at some samples and raises it at others. With the step no residual is above
    the one without it, and a sample whose residual it did not lower is returned exactly as it
    started."""
    shift = 1e4
    doc = {**TRIAD, "points": {p: [x + shift, y - shift] for p, (x, y) in TRIAD["points"].items()}}
    scene = parse_linkage(doc)
    turns = np.linspace(-0.3, 0.6, 12)
    roots = np.array([reference_coordinates(doc, GROUP, turn) for turn in turns])
    system = constraints.constraint_system(scene, GROUP)
    known = constraints.states(crank_and_ground(scene, turns), scene)
    tolerance = newton.residual_tolerance(newton.NEWTON_TOLERANCE, system)
    plain, polished = (
        newton.newton_raphson(system, known, roots, tolerance, polish=polish)
        for polish in (False, True)
    )
    assert plain[2] == polished[2] == 0
    assert np.all(polished[1] <= plain[1])
    kept = polished[1] == plain[1]
    np.testing.assert_array_equal(polished[0][kept], roots[kept])
    assert 0 < np.count_nonzero(kept) < turns.size

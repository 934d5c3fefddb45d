"""Newton-Raphson to the last digit: poses next to singular poses against 50 digits, and the
batched polish of a Newton group (``continuation.solve_group``, ``continuation.Polish``) with the
rules of solver.position.newton.

Accuracy at poses given by ``angle_deg`` next to singular poses. Each linkage is drawn far
(0.3 ... 0.5 rad) from a dead centre or a change point and posed with ``angle_deg`` 1e-3 ...
1e-10 rad from it. The reference treats the double inputs as exact: the link lengths are the exact
distances between the drawn (float) coordinates, the crank stands at exactly radians(angle_deg),
and the pose (on the drawn branch) and its rates are solved in 50 digits, each family by its own
closed form (the rate equations of tests/solver/analysis/test_conditioning). A change-point
linkage is drawn from dyadic Pythagorean coordinates, so that its lengths satisfy the
change-point equality exactly and the pose really is that close to it.

The contract (as at a drawn pose): every pose whose true condition number is below 1e12 is
answered; the rates are right to 1e-9 (relative to the largest rate of their kind; alpha's scale
adds omega^2) where cond < 1e6 and to cond x 1e-15 above; the reported condition number is within
a factor 10 of the exact pose's; the reported position residual is below 1e-30 of the size (Phi
is evaluated in 40 digits, solver.position.polish). A change point 1e-10 rad away (h ~ 1e-10 L) is
below the rounding of the closed form's h^2, which snaps to 0: the polish restarts on either side.

The batched polish of a Newton group, against:

- 50-digit roots (mpmath) of the triad's length equations at the crank's turn
  (``test_continuation_branch.reference_points``), as each link's (x, y, theta);
- the loop's residual recomputed from the links' motions, not by ``solver.position.constraints``:
  every joint's point as each of its two links carries it, X = anchor + R(theta) (X0 - anchor0),
  and their gap (for a slider, the gap across the slot, turned with its guide);
- one Newton-Raphson step recomputed from that residual with a central-difference Jacobian;
- central differences of the 50-digit roots in the crank's turn for the rates;
- closed forms: a structure (no driver) rests at its drawing; a four-bar drawn with its crank,
  coupler and rocker on one line closes there (two tangent circles), where the group's Jacobian
  is exactly singular;
- a natural-continuation reference path (``test_continuation_branch._path_to``) for three
  drivers turning at once;
- the documented rules (docs/ARCHITECTURE.md, "Newton groups"): the tolerance's bounds
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

import mpmath as mp
import numpy as np
import pytest

from solver.analysis.instant import analyze
from solver.analysis.sweeps import sweep, sweep_time
from solver.errors import InvalidScene
from solver.kinematics.rigid import LinkMotion, PointMotion, fixed_link
from solver.model.scene import LinkageScene, parse_linkage
from solver.position import constraints, continuation, newton
from solver.position.continuation import Continuation, solve_group
from solver.teaching.presets import build_preset
from tests.dynamics_cases import five_bar_points, five_bar_topology
from tests.solver.analysis.test_conditioning import (
    ALPHA,
    OMEGA,
    _cross,
    _z,
    errors,
    exact_condition,
    four_bar_near_dead_centre,
    four_bar_rates,
    inverted_near_dead_centre,
    inverted_rates,
    slider_near_dead_centre,
    slider_rates,
)
from tests.solver.position.test_continuation_branch import (
    UNKNOWN,
    _drawn_angle,
    _path_to,
    assert_follows,
    reference_points,
    slider_triad,
)
from tests.solver.position.test_newton import TRIAD
from tests.solver.position.test_newton_continuation import three_crank_triad

mp.mp.dps = 50
Doc = dict[str, Any]
DISTANCES = ("1e-3", "1e-5", "1e-7", "1e-10")
RESIDUAL_BOUND = 1e-30  # of the size: Phi is evaluated in 40 digits


def _posed(doc: Doc, phi: Any) -> tuple[Doc, Any]:
    """``doc`` with angle_deg set to the float nearest phi (deg), and that angle exactly in rad."""
    angle_deg = float(mp.degrees(phi))
    doc["drivers"][0]["angle_deg"] = angle_deg
    return doc, mp.radians(mp.mpf(angle_deg))


def _with_points(doc: Doc, points: dict[str, Any]) -> Doc:
    """A copy of ``doc`` with mp points (for the rate references)."""
    exact = {name: [z.real, z.imag] for name, z in points.items()}
    return {**doc, "points": {**doc["points"], **exact}}


def _rounded(doc: Doc) -> Doc:
    """``doc`` with every coordinate rounded to float and no angle_deg: the exact pose, drawn."""
    out = {**doc, "points": {k: [float(x), float(y)] for k, (x, y) in doc["points"].items()}}
    out["drivers"] = [{k: v for k, v in d.items() if k != "angle_deg"} for d in doc["drivers"]]
    out["joints"] = [
        {**j, "axis": [float(a) for a in j["axis"]]} if "axis" in j else j for j in doc["joints"]
    ]
    return out


# --- exact poses from the double inputs -----------------------------------------------------------


def four_bar_pose(doc: Doc, phi: Any) -> Doc:
    """B = A + |AB| e^(i phi); C on the circles |BC|, |DC| on the drawn side of BD."""
    A, B0, C0, D = (_z(doc, p) for p in "ABCD")
    b, c = abs(C0 - B0), abs(C0 - D)
    B = A + abs(B0 - A) * mp.expj(phi)
    sign = mp.sign(_cross(D - B0, C0 - B0))
    d = abs(D - B)
    along = (d * d + b * b - c * c) / (2 * d)
    h = sign * mp.sqrt(b * b - along * along)
    return _with_points(doc, {"B": B, "C": B + mp.mpc(along, h) * (D - B) / d})


def slider_pose(doc: Doc, phi: Any) -> Doc:
    """B = |AB| e^(i phi); C on the guide y = C0_y at |BC| from B, on the drawn side of B."""
    A, B0, C0 = (_z(doc, p) for p in "ABC")
    rod, e = abs(C0 - B0), C0.imag
    B = A + abs(B0 - A) * mp.expj(phi)
    x = B.real + mp.sign(C0.real - B0.real) * mp.sqrt(rod * rod - (e - B.imag) ** 2)
    return _with_points(doc, {"B": B, "C": mp.mpc(x, e)})


def inverted_pose(doc: Doc, phi: Any) -> Doc:
    """A = O + |OA| e^(i phi) (O the crank's pivot); the lever's slot (drawn through A0 along the
    axis, at the signed offset e = u0 x (A0 - C) from its pivot C) turned to pass through A, on
    the drawn side."""
    pivot, A0, C = (_z(doc, p) for p in "OAC")
    slider = next(j for j in doc["joints"] if j["type"] == "slider")
    u0 = mp.mpc(*slider["axis"])
    u0 /= abs(u0)
    e = _cross(u0, A0 - C)
    A = pivot + abs(A0 - pivot) * mp.expj(phi)
    r = A - C
    lean = mp.asin(e / abs(r))
    drawn_r = A0 - C
    ahead = (u0.real * drawn_r.real + u0.imag * drawn_r.imag) > 0
    beta = mp.arg(r) - lean if ahead else mp.arg(r) - (mp.pi - lean)
    u = mp.expj(beta)
    D = C + (_z(doc, "D") - C) * u / u0  # the lever turned by u / u0
    joints = [{**j, "axis": [u.real, u.imag]} if j is slider else j for j in doc["joints"]]
    return {**_with_points(doc, {"A": A, "D": D}), "joints": joints}


# --- the families ---------------------------------------------------------------------------------


def _limit(g: Any, a: Any, reach: Any) -> Any:
    """The crank angle where |B - D| = reach (B = a e^(i t), D = (g, 0))."""
    return 2 * mp.asin(mp.sqrt((reach - abs(g - a)) * (reach + abs(g - a)) / (4 * a * g)))


def four_bar_dead_centre(distance: Any, side: int) -> tuple[Doc, Any]:
    doc = four_bar_near_dead_centre(mp.mpf("0.3"), side)
    A, B, C, D = (_z(doc, p) for p in "ABCD")
    return _posed(doc, side * (_limit(abs(D - A), abs(B - A), abs(C - B) + abs(C - D)) - distance))


def four_bar_change_point(distance: Any, side: int) -> tuple[Doc, Any]:
    """Ground AD = 1, crank AB = 25/32 (B drawn at (-7/32, 3/4)), coupler BC = 17/32 (C drawn at
    (1/4, 1)), rocker DC = 5/4: 1 + 25/32 = 17/32 + 5/4 exactly, so at crank pi (|BD| = 57/32)
    B, C and D lie on one line and the two assemblies of C meet."""
    doc = build_preset("four_bar", {"omega": OMEGA, "alpha": ALPHA})
    doc["points"] = dict(FOUR_BAR_CHANGE_POINT)
    doc["links"]["coupler"]["points"] = ["B", "C"]
    return _posed(doc, mp.pi + side * distance)


def slider_dead_centre(distance: Any, side: int) -> tuple[Doc, Any]:
    doc = slider_near_dead_centre(mp.mpf("0.3"), side)
    A, B, C = (_z(doc, p) for p in "ABC")
    a, rod, e = abs(B - A), abs(C - B), C.imag
    limit = mp.asin((e - rod) / a)
    return _posed(doc, limit + distance if side > 0 else -mp.pi - limit - distance)


def slider_change_point(distance: Any, side: int) -> tuple[Doc, Any]:
    """In-line, rod = crank = 5/8 (B drawn at (3/8, 1/2), C at (3/4, 0)): C passes through A at
    crank 90 deg."""
    doc = build_preset("slider_crank", {"offset": 0.0, "omega": OMEGA, "alpha": ALPHA})
    doc["points"] = {"A": [0.0, 0.0], "B": [0.375, 0.5], "C": [0.75, 0.0]}
    doc["links"]["coupler"]["points"] = ["B", "C"]
    return _posed(doc, mp.pi / 2 + side * distance)


def inverted_dead_centre(distance: Any, side: int) -> tuple[Doc, Any]:
    doc = inverted_near_dead_centre(mp.mpf("0.3"), side)
    pivot, A0, C = (_z(doc, p) for p in "OAC")
    slider = next(j for j in doc["joints"] if j["type"] == "slider")
    u0 = mp.mpc(*slider["axis"])
    e = abs(_cross(u0 / abs(u0), A0 - C))
    return _posed(doc, side * (_limit(abs(C - pivot), abs(A0 - pivot), e) + distance))


FOUR_BAR_CHANGE_POINT = {"A": [0.0, 0.0], "B": [-0.21875, 0.75], "C": [0.25, 1.0], "D": [1.0, 0.0]}

Family = tuple[Callable[[Any, int], tuple[Doc, Any]], Callable[[Doc, Any], Doc], Callable[..., Any]]
FAMILIES: dict[str, Family] = {
    "four_bar_dead_centre": (four_bar_dead_centre, four_bar_pose, four_bar_rates),
    "four_bar_change_point": (four_bar_change_point, four_bar_pose, four_bar_rates),
    "slider_dead_centre": (slider_dead_centre, slider_pose, slider_rates),
    "slider_change_point": (slider_change_point, slider_pose, slider_rates),
    "inverted_dead_centre": (inverted_dead_centre, inverted_pose, inverted_rates),
}


def measure(family: str, side: int, distance: str) -> tuple[float, float, float, float, float]:
    """(error, bound, reported cond, exact cond, residual / size) of one case."""
    make, pose, reference = FAMILIES[family]
    doc, phi = make(mp.mpf(distance), side)
    exact = pose(doc, phi)
    scene = parse_linkage(doc)
    result = analyze(scene, ["position", "velocity", "acceleration"])
    cond = result.diagnostics.condition_number
    assert cond is not None
    true_cond = exact_condition(_rounded(exact))
    err = errors(result, reference(exact))
    bound = 1e-9 if true_cond < 1e6 else true_cond * 1e-15
    return err, bound, cond, true_cond, result.diagnostics.position_residual / scene.size


@pytest.mark.parametrize("distance", DISTANCES)
@pytest.mark.parametrize("side", [1, -1], ids=["plus", "minus"])
@pytest.mark.parametrize("family", list(FAMILIES))
def test_posed_next_to_a_singular_pose(family: str, side: int, distance: str) -> None:
    err, bound, cond, true_cond, residual = measure(family, side, distance)
    assert true_cond < 1e12
    assert true_cond / 10.0 <= cond <= 10.0 * true_cond, (cond, true_cond)
    assert err <= bound, (err, bound, true_cond)
    assert residual <= RESIDUAL_BOUND, residual


def test_drawn_pose_is_not_polished() -> None:
    """At the drawn pose the drawn coordinates are the answer: nothing to polish, residual 0."""
    doc, _ = four_bar_dead_centre(mp.mpf("1e-3"), 1)
    del doc["drivers"][0]["angle_deg"]
    result = analyze(parse_linkage(doc), ["position"])
    assert result.diagnostics.position_residual == 0.0
    assert np.array_equal(result.points["C"].position, doc["points"]["C"])


@pytest.mark.parametrize("distance", ["1e-5", "1e-10"])
@pytest.mark.parametrize("family", list(FAMILIES))
def test_drawn_next_to_a_singular_pose_as_precise_as_posed(family: str, distance: str) -> None:
    """The exact pose next to a dead centre or change point, rounded and drawn (no angle_deg):
    its rates within the posed bound (1e-9, or cond x 1e-15 past cond 1e6) of the 50-digit
    rates of the drawn coordinates themselves, and the drawn coordinates answered unchanged."""
    make, pose, reference = FAMILIES[family]
    doc, phi = make(mp.mpf(distance), 1)
    drawn = _rounded(pose(doc, phi))
    result = analyze(parse_linkage(drawn), ["position", "velocity", "acceleration"])
    true_cond = exact_condition(drawn)
    bound = 1e-9 if true_cond < 1e6 else true_cond * 1e-15
    assert errors(result, reference(drawn)) <= bound
    assert result.diagnostics.position_residual == 0.0
    for name, point in drawn["points"].items():
        assert np.array_equal(result.points[name].position, point), name


# --- a triad (a Newton group) posed next to its limit positions -----------------------------------


def _triad_parts(doc: Doc) -> tuple[Any, ...]:
    """O, |OA|, A0 -> P1 length, the triangle's P1 -> P2 and P1 -> P3, G2, G3, |G2P2|, |G3P3|."""
    pivot, A0, P1, P2, P3, G2, G3 = (_z(doc, p) for p in ("O", "A", "P1", "P2", "P3", "G2", "G3"))
    return (
        pivot,
        abs(A0 - pivot),
        abs(P1 - A0),
        P2 - P1,
        P3 - P1,
        G2,
        G3,
        abs(P2 - G2),
        abs(P3 - G3),
    )


def _triad_closure(doc: Doc, phi: Any, x: Any) -> tuple[Any, Any, dict[str, Any]]:
    """The triad at crank angle phi with x = (angle of L1, turn psi of T): the two loop closures
    |P2 - G2|^2 - l2^2, |P3 - G3|^2 - l3^2, and the points."""
    pivot, a, l1, d2, d3, G2, G3, l2, l3 = _triad_parts(doc)
    A = pivot + a * mp.expj(phi)
    P1 = A + l1 * mp.expj(x[0])
    turn = mp.expj(x[1])
    P2, P3 = P1 + d2 * turn, P1 + d3 * turn
    points = {"A": A, "P1": P1, "P2": P2, "P3": P3}
    return abs(P2 - G2) ** 2 - l2 * l2, abs(P3 - G3) ** 2 - l3 * l3, points


def _triad_solve(doc: Doc, phi: Any, start: Any) -> tuple[Any, Any]:
    x = mp.findroot(lambda u, v: _triad_closure(doc, phi, (u, v))[:2], start)
    return x[0], x[1]


def triad_reference(doc: Doc, phi: Any, start: Any) -> tuple[Doc, dict[str, Any]]:
    """The exact pose (Newton in 50 digits from ``start``) and the rates of L1 and T from the
    implicit solution's derivatives d/dphi, d^2/dphi^2 (mpmath's numerical differentiation at
    raised precision): omega = x' Omega, alpha = x'' Omega^2 + x' Alpha."""
    x = _triad_solve(doc, phi, start)
    points = _triad_closure(doc, phi, x)[2]
    rates: dict[str, Any] = {"omega": {}, "alpha": {}}
    for k, link in enumerate(("L1", "T")):

        def angle(t: Any, k: int = k) -> Any:
            return _triad_solve(doc, t, x)[k]

        first, second = mp.diff(angle, phi, 1), mp.diff(angle, phi, 2)
        rates["omega"][link] = first * OMEGA
        rates["alpha"][link] = second * OMEGA**2 + first * ALPHA
    return _with_points(doc, points), rates


TRIAD_LIMITS = (mp.mpf("0.19680819239643638"), mp.mpf("1.3052330254995415"))  # rad, /sweep's


@pytest.mark.parametrize("distance", DISTANCES)
@pytest.mark.parametrize("limit", [0, 1], ids=["lower", "upper"])
def test_triad_posed_next_to_a_limit_position(limit: int, distance: str) -> None:
    """The triad of test_newton posed 1e-3 ... 1e-10 rad inside its limit positions
    (from /sweep; a fold, so the limits are exact to rounding): answered to the same contract."""
    doc = {**TRIAD, "drivers": [{"link": "crank", "omega": OMEGA, "alpha": ALPHA}]}
    phi = TRIAD_LIMITS[limit] + (1 - 2 * limit) * mp.mpf(distance)
    doc, phi = _posed(doc, phi)
    scene = parse_linkage(doc)
    result = analyze(scene, ["position", "velocity", "acceleration"])
    P1, A = (mp.mpc(*result.points[p].position) for p in ("P1", "A"))
    turn = mp.arg(mp.mpc(*result.points["P2"].position) - P1) - mp.arg(
        _z(doc, "P2") - _z(doc, "P1")
    )
    exact, rates = triad_reference(doc, phi, (mp.arg(P1 - A), turn))
    true_cond = exact_condition(_rounded(exact))
    cond = result.diagnostics.condition_number
    assert cond is not None and true_cond / 10.0 <= cond <= 10.0 * true_cond, (cond, true_cond)
    err = errors(result, rates)
    assert err <= (1e-9 if true_cond < 1e6 else true_cond * 1e-15), (err, true_cond)
    assert result.diagnostics.position_residual <= RESIDUAL_BOUND * scene.size


def _dot(u: Any, w: Any) -> Any:
    return u.real * w.real + u.imag * w.imag


@pytest.mark.parametrize(
    "angles", [(70.0, None), (None, -40.0), (70.0, -40.0)], ids=["first", "second", "both"]
)
def test_a_five_bar_posed_by_its_cranks_is_polished(angles: tuple[float | None, ...]) -> None:
    """A five-bar's dyad A-C-B touches neither the frame nor any link the polish holds but the
    two cranks (the frame's angle is not one of its equations: it was left unset, and a 40-digit
    cos of it raised a 500). Against the closed form in 50 digits: C on the circles about the
    turned A and B with the drawn |AC| and |BC|, on the drawn side of AB; v_C from
    (v_C - v_A).(C - A) = 0 and (v_C - v_B).(C - B) = 0."""
    points = five_bar_points()
    omegas = (3.0, -5.0)
    drivers: list[dict[str, Any]] = [
        {"link": link, "omega": w} | ({} if a is None else {"angle_deg": a})
        for link, w, a in zip(("crank1", "crank2"), omegas, angles, strict=True)
    ]
    scene = parse_linkage(
        {"kind": "linkage", "points": points, **five_bar_topology(), "drivers": drivers}
    )
    result = analyze(scene)
    with mp.workdps(50):
        z = {k: mp.mpc(*v) for k, v in points.items()}

        def turned(pivot: str, end: str, angle: float | None) -> Any:
            r = z[end] - z[pivot]
            return z[end] if angle is None else z[pivot] + abs(r) * mp.expj(mp.radians(angle))

        A, B = turned("O1", "A", angles[0]), turned("O2", "B", angles[1])
        rA, rB, d = abs(z["C"] - z["A"]), abs(z["C"] - z["B"]), abs(B - A)
        along = (rA**2 - rB**2 + d**2) / (2 * d)
        side = mp.sign(_cross(z["B"] - z["A"], z["C"] - z["A"]))
        C = A + (B - A) / d * (along + 1j * side * mp.sqrt(rA**2 - along**2))
        vA = 1j * omegas[0] * (A - z["O1"])
        vB = 1j * omegas[1] * (B - z["O2"])
        # (v_C - v_K).(C - K) = 0 for K = A, B: two real equations in v_C's x and y
        m = mp.matrix([[(C - K).real, (C - K).imag] for K in (A, B)])
        rhs = mp.matrix([_dot(vK, C - K) for K, vK in ((A, vA), (B, vB))])
        vC = mp.lu_solve(m, rhs)
    assert np.allclose(
        result.points["C"].position, [float(C.real), float(C.imag)], rtol=0, atol=1e-14
    )
    assert np.allclose(
        result.points["C"].velocity, [float(vC[0]), float(vC[1])], rtol=1e-12, atol=0
    )
    assert result.diagnostics.position_residual <= RESIDUAL_BOUND * scene.size


# ---- the batched polish of a Newton group and Newton-Raphson's rules -----------------------------

GROUP = ("T", "L1", "L2", "L3")  # the triad's Newton group (the slider triad's lacks L3)
TRIAD_OMEGA, TRIAD_ALPHA = 2.0, 0.5  # the crank's rates in TRIAD


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
    crank = LinkMotion(
        pivot, still, turns, np.full(samples, TRIAD_OMEGA), np.full(samples, TRIAD_ALPHA)
    )
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
    """Stands in for ``Branch`` in ``Polish.run``: every turn reached, each sample's start the
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
    """A stand-in for ``Polish.newton_raphson``: each sample's (residual, first step, whole move)
    from ``first`` at the first attempt and from ``after`` at the others, q left at its start; the
    number of samples solved at each attempt is appended to ``attempts``."""

    def outcome(
        polish: continuation.Polish, todo: np.ndarray, q0: np.ndarray
    ) -> tuple[np.ndarray, np.ndarray, int, np.ndarray, np.ndarray]:
        rows = (after if attempts else first)[todo]
        attempts.append(todo.size)
        return q0, rows[:, 0], 1, rows[:, 1], rows[:, 2]

    return outcome


def test_a_sample_settles_only_near_its_start_with_a_short_first_step(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    """The rule of acceptance, fed Newton-Raphson's outcomes directly (``Polish.newton_raphson``
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
            continuation.Polish, "newton_raphson", outcomes_of_newton(start, then, attempts)
        )
        polish = continuation.Polish(system, states, turns.size, Continuation(scene))
        path = _Path(scene)
        polish.run(np.arange(turns.size), path, turns)
        assert path.refined == refined
        assert attempts == [6] + [len(ways) for ways in refined]
        assert polish.settled.tolist() == [bool(k) for k in settled]


def test_a_samples_move_and_first_step_weigh_rotations_by_the_size() -> None:
    """``Polish.newton_raphson`` from the 50-digit roots displaced by d (per link 2e-3 m in x,
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
    polish = continuation.Polish(system, states, turns.size, Continuation(scene))
    for todo in (np.arange(2), np.array([1])):
        q, _, _, first, moved = polish.newton_raphson(todo, roots[todo] + d)
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
    ``turn`` turning at TRIAD_OMEGA, TRIAD_ALPHA: q' omega and q'' omega^2 + q' alpha, q' and q''
    their central differences in the turn (step 1e-4 rad: truncation ~1e-9 of them, rounding of the
    roots 1e-16 / h^2 = 1e-8)."""
    doc, group = triad(name)
    h = 1e-4
    behind, at, ahead = (reference_coordinates(doc, group, turn + k * h) for k in (-1, 0, 1))
    slope, bend = (ahead - behind) / (2.0 * h), (ahead - 2.0 * at + behind) / (h * h)
    return slope * TRIAD_OMEGA, bend * TRIAD_OMEGA**2 + slope * TRIAD_ALPHA


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


@pytest.mark.slow
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

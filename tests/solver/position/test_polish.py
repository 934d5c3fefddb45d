"""Accuracy at poses given by ``angle_deg`` next to singular poses (issue 14), against 50 digits.

Each linkage is drawn far (0.3 ... 0.5 rad) from a dead centre or a change point and posed with
``angle_deg`` 1e-3 ... 1e-10 rad from it. The reference treats the double inputs as exact: the
link lengths are the exact distances between the drawn (float) coordinates, the crank stands at
exactly radians(angle_deg), and the pose (on the drawn branch) and its rates are solved in 50
digits, each family by its own closed form (the rate equations of
tests/solver/analysis/test_conditioning).
A change-point linkage is drawn from dyadic Pythagorean coordinates, so that its lengths satisfy
the change-point equality exactly and the pose really is that close to it.

The contract (as at a drawn pose): every pose whose true condition number is below 1e12 is
answered; the rates are right to 1e-9 (relative to the largest rate of their kind; alpha's scale
adds omega^2) where cond < 1e6 and to cond x 1e-15 above; the reported condition number is within
a factor 10 of the exact pose's; the reported position residual is below 1e-30 of the size (Phi
is evaluated in 40 digits, solver.position.polish). A change point 1e-10 rad away (h ~ 1e-10 L) is
below
the rounding of the closed form's h^2, which snaps to 0: the polish restarts on either side.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

import mpmath as mp
import numpy as np
import pytest

from solver.analysis.instant import analyze
from solver.model.scene import parse_linkage
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
from tests.solver.position.test_newton import TRIAD

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

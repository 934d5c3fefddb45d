"""Extremes: four-bars next to a toggle and next to a dead centre, exactly at a dead centre, lengths
from 1e-4 m to 1e4 m and driver speeds from 1e-3 to 1e4 rad/s, change-point linkages swept through
their change points, a non-Grashof four-bar's limit positions, and a Newton-Raphson six-bar swept
over a limited range.

Reference values near the singular poses come from an independent closed form evaluated in
50-digit arithmetic (mpmath): the four-bar's velocity and acceleration equations (loop closure
differentiated once and twice, written with complex numbers, k x r = i r) solved exactly for the
pose the solver is given.

How accurate can the answer be near a dead centre? The solver re-closes the loop at the pose it is
given, and the closed form of a dyad next to tangency loses accuracy in proportion to the
condition number ``cond`` (the position of C moves by ~ cond eps L); the velocity equations then
amplify that relative error by ``cond`` again. So the stated accuracy is
``|error| <= 10 cond^2 eps`` relative to the size of the answer (the largest omega; for alpha,
the largest |alpha| + omega^2, since the acceleration equations carry omega^2 terms), with the
condition number the solver itself reports. Next to a toggle cond ~ 10 and the bound is ~ 1e-13.
"""

from __future__ import annotations

import copy
import json
import math
from pathlib import Path
from typing import Any

import mpmath as mp
import numpy as np
import pytest

from solver.analysis.instant import MAX_CONDITION_NUMBER, LinkageAnalysis, analyze
from solver.analysis.sweeps import sweep
from solver.errors import SingularConfiguration
from solver.model.scene import LinkageScene, parse_linkage
from tests.linkage_strategies import stephenson_six_bar

Doc = dict[str, Any]
EPS = float(np.finfo(float).eps)
REFERENCE = Path(__file__).resolve().parents[2] / "reference" / "seed-cases.json"
mp.mp.dps = 50


def _case(case_id: str) -> dict[str, Any]:
    cases = json.loads(REFERENCE.read_text())["cases"]
    case: dict[str, Any] = next(c for c in cases if c["id"] == case_id)
    return case


S000_T1 = _case("S000-T1")["requests"][0]


def four_bar(
    A: complex,
    B: complex,
    C: complex,
    D: complex,
    omega: float,
    alpha: float,
    angle_deg: float | None = None,
) -> Doc:
    """Crank AB, coupler BC, rocker DC, ground AD (the link names of S000-T1)."""
    driver: dict[str, float] = {"omega": omega, "alpha": alpha}
    if angle_deg is not None:
        driver["angle_deg"] = angle_deg
    return {
        "kind": "linkage",
        "points": {
            name: [float(mp.re(z)), float(mp.im(z))]
            for name, z in (("A", A), ("B", B), ("C", C), ("D", D))
        },
        "links": {
            "ground": {"points": ["A", "D"], "ground": True},
            "crank": {"points": ["A", "B"]},
            "coupler": {"points": ["B", "C"]},
            "rocker": {"points": ["D", "C"]},
        },
        "joints": [
            {"type": "revolute", "point": p, "links": pair}
            for p, pair in (
                ("A", ["ground", "crank"]),
                ("B", ["crank", "coupler"]),
                ("C", ["coupler", "rocker"]),
                ("D", ["rocker", "ground"]),
            )
        ],
        "drivers": [{"link": "crank", **driver}],
    }


def circles(P: Any, r_p: Any, Q: Any, r_q: Any, left: bool) -> Any:
    """The intersection of two circles left (or right) of P -> Q, in mpmath."""
    d = abs(Q - P)
    a = (d * d + r_p * r_p - r_q * r_q) / (2 * d)
    h = mp.sqrt(r_p * r_p - a * a)
    return P + mp.mpc(a, h if left else -h) * (Q - P) / d


def closed_form(doc: Doc, crank_angle: Any | None = None) -> dict[str, Any]:
    """The four-bar's exact (50-digit) rates at the drawn pose, or at ``crank_angle`` (rad) on the
    drawn branch. Velocity: omega2 (C - B) - omega3 (C - D) = -omega1 (B - A); acceleration:
    alpha2 (C - B) - alpha3 (C - D) = -i (-a_B + omega2^2 (C - B) - omega3^2 (C - D)), with
    a_B = (i alpha1 - omega1^2)(B - A): the loop closure differentiated, divided by i."""
    A, B, C, D = (mp.mpc(*doc["points"][p]) for p in "ABCD")
    omega1 = mp.mpf(doc["drivers"][0]["omega"])
    alpha1 = mp.mpf(doc["drivers"][0]["alpha"])
    if crank_angle is not None:
        left = mp.im((C - B) / (D - B)) > 0
        l1, l2, l3 = abs(B - A), abs(C - B), abs(C - D)
        B = A + l1 * mp.expj(crank_angle)
        C = circles(B, l2, D, l3, left)
    cb, cd, ba = C - B, C - D, B - A
    M = mp.matrix([[cb.real, -cd.real], [cb.imag, -cd.imag]])
    w2, w3 = mp.lu_solve(M, mp.matrix([-omega1 * ba.real, -omega1 * ba.imag]))
    a_B = (1j * alpha1 - omega1**2) * ba
    rhs = -1j * (-a_B + w2**2 * cb - w3**2 * cd)
    a2, a3 = mp.lu_solve(M, mp.matrix([rhs.real, rhs.imag]))
    return {
        "B": B,
        "C": C,
        "omega": (omega1, w2, w3),
        "alpha": (alpha1, a2, a3),
        "v_C": 1j * w3 * cd,
        "a_C": (1j * a3 - w3**2) * cd,
    }


def assert_within_condition_bound(result: LinkageAnalysis, exact: dict[str, Any]) -> float:
    """Compare omega, alpha, v_C, a_C with the closed form to 10 cond^2 eps (module doc)."""
    cond = result.diagnostics.condition_number
    assert cond is not None and cond < MAX_CONDITION_NUMBER
    bound = 10.0 * cond**2 * EPS
    omegas = [float(w) for w in exact["omega"]]
    alphas = [float(a) for a in exact["alpha"]]
    w_scale = max(map(abs, omegas))
    a_scale = max(map(abs, alphas)) + w_scale**2
    for name, w, a in zip(("coupler", "rocker"), omegas[1:], alphas[1:], strict=True):
        assert abs(result.links[name].omega - w) <= bound * w_scale, (name, w, cond)
        assert abs(result.links[name].alpha - a) <= bound * a_scale, (name, a, cond)
    v_C = complex(*result.points["C"].velocity)
    a_C = complex(*result.points["C"].acceleration)
    lever = float(abs(exact["C"] - mp.mpc(*result.points["D"].position)))
    assert abs(v_C - complex(exact["v_C"])) <= bound * w_scale * lever
    assert abs(a_C - complex(exact["a_C"])) <= bound * a_scale * lever
    return cond


# --- next to a toggle ----------------------------------------------------------------------------

# The seed-004 crank-rocker (l1 0.15, coupler 1.0, rocker 0.55, ground 1.0 m): at a toggle the
# crank and coupler are collinear (|AC| = l2 +- l1), the rocker is at an extreme and turns back:
# omega3 changes sign there. The velocity equations stay well conditioned (cond ~ 10).
TOGGLE = {
    "A": mp.mpc(0, 0),
    "D": mp.mpc(1, 0),
    "l1": mp.mpf("0.15"),
    "l2": mp.mpf(1),
    "l3": mp.mpf("0.55"),
}


def toggle_angle(extended: bool) -> Any:
    """The crank angle of the toggle: C on |AC| = l2 + l1 (extended) or l2 - l1 (folded)."""
    A, D, l1, l2, l3 = (TOGGLE[k] for k in ("A", "D", "l1", "l2", "l3"))
    C = circles(A, l2 + l1 if extended else l2 - l1, D, l3, True)
    return mp.arg(C - A) if extended else mp.arg(A - C)


def toggle_four_bar(angle: Any, angle_deg: float | None = None) -> Doc:
    A, D, l1, l2, l3 = (TOGGLE[k] for k in ("A", "D", "l1", "l2", "l3"))
    B = A + l1 * mp.expj(angle)
    return four_bar(A, B, circles(B, l2, D, l3, True), D, -2.0, 3.0, angle_deg)


@pytest.mark.parametrize("extended", [True, False], ids=["extended", "folded"])
@pytest.mark.parametrize("side", [1, -1], ids=["after", "before"])
def test_four_bar_1e_6_rad_from_a_toggle(extended: bool, side: int) -> None:
    """Drawn 1e-6 rad from the toggle: answers to 10 cond^2 eps of the closed form, and the
    rocker's tiny omega (~ 5e-7 rad/s, about to reverse) has the closed form's sign."""
    angle = toggle_angle(extended) + side * mp.mpf("1e-6")
    doc = toggle_four_bar(angle)
    exact = closed_form(doc)
    result = analyze(parse_linkage(doc))
    cond = assert_within_condition_bound(result, exact)
    assert cond < 100.0  # a toggle is not a dead centre of the crank-driven linkage
    w3 = float(exact["omega"][2])
    assert 1e-8 < abs(w3) < 1e-5
    assert math.copysign(1.0, result.links["rocker"].omega) == math.copysign(1.0, w3)


@pytest.mark.parametrize("extended", [True, False], ids=["extended", "folded"])
def test_four_bar_turned_to_1e_6_rad_from_a_toggle(extended: bool) -> None:
    """The same, reached with angle_deg from a pose drawn 60 deg away: positions to 10 cond eps L
    (the crank angle itself is only good to a few eps), rates to 10 cond^2 eps."""
    angle = toggle_angle(extended) + mp.mpf("1e-6")
    angle_deg = float(mp.degrees(angle))
    doc = toggle_four_bar(angle + mp.radians(60), angle_deg=angle_deg)
    result = analyze(parse_linkage(doc))
    exact = closed_form(doc, crank_angle=mp.radians(mp.mpf(angle_deg)))
    cond = assert_within_condition_bound(result, exact)
    for name in ("B", "C"):
        assert abs(complex(*result.points[name].position) - complex(exact[name])) <= (
            10 * cond * EPS * 2.0
        )


# --- next to a dead centre -----------------------------------------------------------------------

# S000-T1 (ground 2.5, crank 1, coupler 2, rocker sqrt(1.25) m) is a non-Grashof triple rocker:
# the crank stops where coupler and rocker are collinear, |BD| = l2 + l3, at
# cos(theta_lim) = (l1^2 + g^2 - (l2 + l3)^2) / (2 l1 g), theta_lim = 119.63 deg.
T1 = {
    "A": mp.mpc(0, 0),
    "D": mp.mpc("2.5", 0),
    "l1": mp.mpf(1),
    "l2": mp.mpf(2),
    "l3": mp.sqrt(mp.mpf("1.25")),
}
T1_LIMIT = mp.acos(
    (T1["l1"] ** 2 + T1["D"].real ** 2 - (T1["l2"] + T1["l3"]) ** 2) / (2 * T1["l1"] * T1["D"].real)
)


@pytest.mark.parametrize("inside", ["1e-6", "1e-9"])
def test_four_bar_drawn_just_inside_a_dead_centre(inside: str) -> None:
    """Drawn 1e-6 (and 1e-9) rad inside the limit position: the answer is computed, large as it is
    (omega2 ~ 500 rad/s for a crank at 2 rad/s), with cond ~ 1e4 (3e5) reported, and matches the
    closed form to 10 cond^2 eps (~ 2e-7 relative at 1e-6 rad)."""
    angle = T1_LIMIT - mp.mpf(inside)
    A, D, l1, l2, l3 = (T1[k] for k in ("A", "D", "l1", "l2", "l3"))
    B = A + l1 * mp.expj(angle)
    doc = four_bar(A, B, circles(B, l2, D, l3, True), D, -2.0, 3.0)
    exact = closed_form(doc)
    result = analyze(parse_linkage(doc))
    cond = assert_within_condition_bound(result, exact)
    assert cond > 1e3  # ill-conditioned, and said so
    assert abs(float(exact["omega"][1])) > 100.0


def test_four_bar_turned_to_1e_6_rad_inside_a_dead_centre() -> None:
    """S000-T1 as drawn, with angle_deg 1e-6 rad inside its limit position (the driver's angle
    is honoured on the drawn branch); rates to 10 cond^2 eps of the closed form there."""
    angle_deg = float(mp.degrees(T1_LIMIT - mp.mpf("1e-6")))
    doc = copy.deepcopy(S000_T1["body"]["scene"])
    doc["drivers"][0]["angle_deg"] = angle_deg
    result = analyze(parse_linkage(doc))
    exact = closed_form(doc, crank_angle=mp.radians(mp.mpf(angle_deg)))
    cond = assert_within_condition_bound(result, exact)
    assert cond > 1e3
    assert abs(complex(*result.points["C"].position) - complex(exact["C"])) <= (
        10 * cond * EPS * 3.0
    )


# --- at a dead centre ----------------------------------------------------------------------------

# Drawn exactly at a dead centre: coupler BC and rocker DC collinear, so the velocity equations
# have no solution for a moving crank (the driver cannot move the linkage there).
FOLDED_DEAD_CENTRE = four_bar(0j, 1 + 0j, 3 + 0j, 2 + 0j, 1.0, 0.0)  # rocker DC inside BC
# 3-4-5 triangle: B = (0, 3), D = (4, 0), C on segment BD with |BC| = 3, |CD| = 2, C = (2.4, 1.2)
# rounded to binary: collinear to within rounding only.
EXTENDED_DEAD_CENTRE = four_bar(0j, 3j, mp.mpc("2.4", "1.2"), 4 + 0j, -1.0, 0.5)


@pytest.mark.parametrize(
    "doc", [FOLDED_DEAD_CENTRE, EXTENDED_DEAD_CENTRE], ids=["folded", "extended"]
)
def test_exactly_at_a_dead_centre_is_a_singular_configuration(doc: Doc) -> None:
    """scene-v1: the velocity equations are singular (dead centre) -> SingularConfiguration,
    whose message names the dead centre, and whose condition number is beyond the threshold."""
    with pytest.raises(SingularConfiguration) as raised:
        analyze(parse_linkage(doc))
    assert "dead centre" in raised.value.message
    assert raised.value.condition_number > MAX_CONDITION_NUMBER


# --- lengths and speeds over many decades --------------------------------------------------------

# S000-T1 with every length times L and the crank at omega = -s, alpha: positions and poles scale
# by L; link omegas by s; velocities by s L. Accelerations are linear in (omega^2, alpha): with
# the reference at omega = -1, alpha = -1, a = L (omega^2 a_ref - (omega^2 + alpha) v_ref) and
# alpha_link = omega^2 (alpha_ref - omega_ref) - alpha omega_ref (the alpha part of the field is
# the unit-omega velocity field, -v_ref). The acceleration pole depends on alpha / omega^2 only,
# so it is compared when alpha = -omega^2 as in the reference. alpha is capped at the scene limit
# of 1e6 rad/s^2. Tolerance: the reference's own, 1e-6 of the group's largest magnitude.
LENGTHS = [1e-4, 1e-2, 1.0, 1e2, 1e4]
SPEEDS = [1e-3, 1.0, 1e4]


def _expected_s000_t1() -> dict[str, Any]:
    return {e["path"]: (np.array(e["value"], dtype=float), e["kind"]) for e in S000_T1["expected"]}


@pytest.mark.parametrize("length", LENGTHS)
@pytest.mark.parametrize("speed", SPEEDS)
def test_scaling_laws_over_decades(length: float, speed: float) -> None:
    """v ~ omega L and a ~ omega^2 L over lengths 1e-4..1e4 m and omega 1e-3..1e4 rad/s, against
    the reference values of S000-T1 (seed-cases.json) scaled by the laws above."""
    omega = -speed
    alpha = -(speed**2) if speed**2 <= 1e6 else 1e6
    doc = copy.deepcopy(S000_T1["body"]["scene"])
    doc["points"] = {k: [length * x, length * y] for k, (x, y) in doc["points"].items()}
    doc["drivers"][0] |= {"omega": omega, "alpha": alpha}
    result = analyze(parse_linkage(doc))
    ref = _expected_s000_t1()
    w2 = omega**2

    def expected(path: str) -> np.ndarray:
        value = ref[path][0]
        if path.endswith(".omega"):
            return -omega * value
        if path.endswith(".alpha"):
            w_ref = ref[path.replace(".alpha", ".omega")][0]
            return w2 * (value - w_ref) - alpha * w_ref
        if path.endswith(".velocity"):
            return -omega * length * value
        if path.endswith(".acceleration"):
            v_ref = ref[path.replace(".acceleration", ".velocity")][0]
            return length * (w2 * value - (w2 + alpha) * v_ref)
        return length * value  # poles

    def actual(path: str) -> np.ndarray:
        kind, name, field = path.split(".")
        item = result.links[name] if kind == "links" else result.points[name]
        return np.array(getattr(item, field), dtype=float)

    paths = [p for p in ref if not (p.endswith("acceleration_pole") and alpha != -w2)]
    values = {p: expected(p) for p in paths}
    groups: dict[str, float] = {}
    for p in paths:
        groups[ref[p][1]] = max(groups.get(ref[p][1], 0.0), float(np.max(np.abs(values[p]))))
    for p in paths:
        tolerance = 1e-6 * groups[ref[p][1]]
        assert np.all(np.abs(actual(p) - values[p]) <= tolerance), (p, actual(p), values[p])


# --- change points and limit positions -----------------------------------------------------------


def _change_point_four_bar(crossed: bool) -> Doc:
    """Ground 1, crank 0.4, coupler 1, rocker 0.4 m (s + l = p + q): drawn at 60 deg as a
    parallelogram (C = B + AD) or crossed (an anti-parallelogram, C on the other branch)."""
    A, D = mp.mpc(0, 0), mp.mpc(1, 0)
    B = mp.mpf("0.4") * mp.expj(mp.pi / 3)
    C = circles(B, mp.mpf(1), D, mp.mpf("0.4"), not crossed)
    return four_bar(A, B, C, D, 3.0, 0.0)


@pytest.mark.parametrize("samples", [360, 1001])
def test_parallelogram_stays_a_parallelogram_all_the_way_round(samples: int) -> None:
    """Continuation keeps the branch through the change points (crank at 0 and 180 deg,
    where all four links are collinear and both branches meet). With 360 samples the sweep lands
    on them (within rounding): they are reported in singular_samples. At every sample C - B =
    D - A (to 1e-9 m; near a change point the dyad is near tangency), the coupler does not turn
    and the rocker turns with the crank (to 1e-9 omega)."""
    scene = parse_linkage(_change_point_four_bar(crossed=False))
    result = sweep(scene, samples, ["position", "velocity", "acceleration"])
    assert result.feasible and result.limits == ()
    points, links = result.motion.points, result.motion.links
    side = points["C"].p - points["B"].p - np.array([1.0, 0.0])
    assert float(np.max(np.hypot(*side.T))) <= 1e-9
    assert float(np.max(np.abs(links["coupler"].omega))) <= 1e-9 * 3.0
    assert float(np.max(np.abs(links["rocker"].omega - 3.0))) <= 1e-9 * 3.0
    on_change_point = np.flatnonzero(np.abs(np.sin(result.driver_angle)) < 1e-9)
    assert set(result.singular_samples.tolist()) == set(on_change_point.tolist())
    if samples == 360:
        assert on_change_point.size == 2


@pytest.mark.parametrize("samples", [360, 1001])
def test_anti_parallelogram_stays_crossed_all_the_way_round(samples: int) -> None:
    """The crossed four-bar: A, B, D, C form an isosceles trapezoid whose parallel sides are AC
    and BD, so cross(C - A, D - B) = 0 at every sample (to 1e-9 m^2), which no parallelogram pose
    satisfies away from the change points. And C stays on its own branch: the two branches are
    mirror images in BD, 2 h apart with h the height of triangle BCD on the parallelogram side,
    h = 0.4 |sin(crank)| / |BD| >= 0.4 |sin(crank)| / 1.4, so |C - (B + AD)| >= 0.57 |sin(crank)|.
    """
    scene = parse_linkage(_change_point_four_bar(crossed=True))
    result = sweep(scene, samples, ["position", "velocity"])
    assert result.feasible
    p = result.motion.points
    ac, bd = p["C"].p - p["A"].p, p["D"].p - p["B"].p
    assert float(np.max(np.abs(ac[:, 0] * bd[:, 1] - ac[:, 1] * bd[:, 0]))) <= 1e-9
    parallelogram_gap = np.hypot(*(p["C"].p - p["B"].p - np.array([1.0, 0.0])).T)
    assert np.all(parallelogram_gap >= 0.57 * np.abs(np.sin(result.driver_angle)) - 1e-9)


def test_non_grashof_sweep_stops_at_its_limit_positions() -> None:
    """S000-T1 cannot turn fully: feasible false, two limits at +-theta_lim (closed form, to 1e-8
    rad), every sample strictly between them, and at each limit the dyad BCD is tangent: |BD| =
    l2 + l3 there (to 1e-12 relative), and the pose 1e-10 rad inside it has coupler and rocker
    collinear and extended (sine of the angle BCD below 1e-4: the dyad's height goes as the
    square root of the distance from the limit, ~ 1e-5 here)."""
    doc = S000_T1["body"]["scene"]
    result = sweep(parse_linkage(doc), 200, ["position"])
    assert result.feasible is False
    assert len(result.limits) == 2
    low, high = sorted(result.limits)
    limit = float(T1_LIMIT)
    assert abs(low + limit) <= 1e-8 and abs(high - limit) <= 1e-8
    assert np.all((result.driver_angle > low) & (result.driver_angle < high))
    reach = float(T1["l2"] + T1["l3"])
    for angle in (low, high):
        B = complex(math.cos(angle), math.sin(angle))
        assert abs(abs(2.5 - B) - reach) <= 1e-12 * reach
        posed = copy.deepcopy(doc)
        posed["drivers"][0]["angle_deg"] = math.degrees(angle - math.copysign(1e-10, angle))
        near = analyze(parse_linkage(posed), ["position"])
        B_, C_, D_ = (near.points[p].position for p in "BCD")
        u, w = B_ - C_, D_ - C_
        sine = abs(u[0] * w[1] - u[1] * w[0]) / (np.hypot(*u) * np.hypot(*w))
        assert sine <= 1e-4, (angle, sine)
        assert float(u @ w) < 0.0  # extended: C between B and D


def test_reported_limit_positions_can_be_posed() -> None:
    """A limit position that /sweep reports is a pose of the linkage (the dyad tangent): asking
    /analyze for the positions there must assemble, not answer not_assemblable (the velocity
    equations are singular there, the positions are not)."""
    doc = S000_T1["body"]["scene"]
    result = sweep(parse_linkage(doc), 20, ["position"])
    for angle in result.limits:
        posed = copy.deepcopy(doc)
        posed["drivers"][0]["angle_deg"] = math.degrees(angle)
        at_limit = analyze(parse_linkage(posed), ["position"])
        B, C, D = (at_limit.points[p].position for p in "BCD")
        assert abs(float(np.hypot(*(D - B))) - float(T1["l2"] + T1["l3"])) <= 1e-9
        u, w = B - C, D - C
        assert abs(u[0] * w[1] - u[1] * w[0]) <= 1e-5 * float(np.hypot(*u) * np.hypot(*w))


# --- a Newton-Raphson six-bar swept over a limited range -----------------------------------------

# A Stephenson six-bar driven by the dyad link X-Q: its four-bar loop has no driven link, so the
# solver closes crank, coupler, rocker and dyad_out together by Newton-Raphson. Its driver turns
# only between about -6.2 and +0.09 deg from the drawn pose. (Found by the six-bar strategy of
# tests/linkage_strategies.py.)
NEWTON_SIX_BAR: Doc = stephenson_six_bar(
    {
        "A": [0.0, 0.0],
        "B": [0.5, 0.0],
        "C": [0.5625, 0.24206145913796356],
        "D": [1.0, 0.0],
        "X": [1.0, 1.0],
        "Y": [0.25793854086203644, 0.0625],
        "Q": [1.4408680864789296, -0.11139407478282459],
    },
    {"link": "dyad_in", "omega": 1.0, "alpha": 0.0},
)


def _link_length_residual(scene: LinkageScene, positions: dict[str, np.ndarray]) -> float:
    worst = 0.0
    for link in scene.links.values():
        names = link.points
        for i, x in enumerate(names):
            for y in names[i + 1 :]:
                drawn = float(np.hypot(*(scene.drawn(y) - scene.drawn(x))))
                now = np.hypot(*(positions[y] - positions[x]).T)
                worst = max(worst, float(np.max(np.abs(now - drawn))))
    return worst


def test_newton_six_bar_sweeps_its_feasible_range() -> None:
    """The drawn pose assembles, so the sweep over the driver's feasible range must too (the
    sweep covers the feasible range, keeping the drawn branch): it reports the range, every sample
    closes the loop to 1e-12 of the size, and the samples bracket the drawn angle. 360 samples,
    the API's default."""
    scene = parse_linkage(NEWTON_SIX_BAR)
    analyze(scene)  # the drawn pose itself is fine
    result = sweep(scene, 360, ["position"])
    assert result.feasible is False and len(result.limits) == 2
    positions = {name: m.p for name, m in result.motion.points.items() if name in scene.points}
    assert _link_length_residual(scene, positions) <= 1e-12 * scene.size
    drawn = math.atan2(-0.11139407478282459 - 1.0, 1.4408680864789296 - 1.0)
    low, high = sorted(result.limits)
    assert low < drawn < high

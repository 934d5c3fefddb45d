"""Linkage synthesis (issue 26): closed forms (a known Grashof four-bar's three coupler poses give
it back, with its moving or its fixed pivots), Freudenstein's equation at the precision points,
the quick-return time ratio read from the returned scene's /sweep ``quick_return``, random tasks
reaching every position or saying why, the defects against what /sweep shows, and the
refusals with their reasons. Every linkage is read back through the public solver
(``solver.analyze``, ``solver.sweep``), never through the synthesis' own algebra."""

from __future__ import annotations

import copy
import math
from typing import Any

import numpy as np
import pytest

import solver
from solver.kinematics.four_bar import grashof_class
from solver.synthesis import chebyshev_spacing, circumcentre, crank_angle_difference, pole
from solver.synthesis.task import Pose

TOL = 1e-9


def xy(z: complex) -> list[float]:
    return [z.real, z.imag]


def point(body: Any, name: str) -> complex:
    x, y = body["scene"]["points"][name]
    return complex(x, y)


def four_bar_pose(
    A: complex, D: complex, a: float, b: float, c: float, theta: float
) -> tuple[complex, complex]:
    """B and C of the four-bar at crank angle theta, C to the left of B -> D (one assembly):
    the intersection of the circles |C - B| = b and |C - D| = c, written out here."""
    B = A + a * complex(math.cos(theta), math.sin(theta))
    BD = D - B
    e = abs(BD)
    along = (b * b - c * c + e * e) / (2.0 * e)
    height = math.sqrt(b * b - along * along)
    C = B + BD / e * complex(along, height)
    return B, C


def random_crank_rocker(rng: np.random.Generator) -> tuple[complex, complex, float, float, float]:
    while True:
        A = complex(*rng.uniform(-1.0, 1.0, 2))
        d = rng.uniform(1.0, 2.0)
        D = A + d * complex(math.cos(rng.uniform(0, 2 * math.pi)), math.sin(rng.uniform(0, 6)))
        d = abs(D - A)
        a, b, c = rng.uniform(0.15, 0.4) * d, rng.uniform(0.8, 1.4) * d, rng.uniform(0.6, 1.2) * d
        if grashof_class(d, a, b, c) == "Grashof crank-rocker":
            return A, D, a, b, c


def three_poses(rng: np.random.Generator) -> dict[str, Any]:
    """A random crank-rocker, a coupler point P, and the coupler's poses at three crank angles
    turning counter-clockwise."""
    A, D, a, b, c = random_crank_rocker(rng)
    offset = complex(rng.uniform(0.2, 0.8), rng.uniform(-0.5, 0.5))
    start = rng.uniform(0, 2 * math.pi)
    thetas = [start, start + rng.uniform(0.5, 1.5), start + rng.uniform(2.2, 3.5)]
    poses = []
    for theta in thetas:
        B, C = four_bar_pose(A, D, a, b, c, theta)
        u = (C - B) / abs(C - B)
        poses.append((B, C, B + b * offset * u, math.atan2(u.imag, u.real)))
    return {"A": A, "D": D, "poses": poses, "lengths": (a, b, c, abs(D - A))}


def motion_task(case: dict[str, Any], pivots: str) -> dict[str, Any]:
    poses = case["poses"]
    given = (
        [xy(poses[0][0]), xy(poses[0][1])] if pivots == "moving" else [xy(case["A"]), xy(case["D"])]
    )
    return {
        "task": "motion",
        "positions": [{"point": xy(P), "angle_deg": math.degrees(phi)} for _, _, P, phi in poses],
        f"{pivots}_pivots": given,
    }


@pytest.mark.parametrize("seed", range(8))
def test_three_positions_of_a_known_four_bar_give_it_back(seed: int) -> None:
    """Closed form: the centre points of B's and C's three places are the fixed pivots; the
    circle points of A and D are the moving pivots (the inverse problem)."""
    case = three_poses(np.random.default_rng(seed))
    size = max(case["lengths"])
    direct = solver.synthesize(motion_task(case, "moving"))
    assert abs(point(direct, "A") - case["A"]) < TOL * size
    assert abs(point(direct, "D") - case["D"]) < TOL * size
    inverse = solver.synthesize(motion_task(case, "fixed"))
    assert abs(point(inverse, "B") - case["poses"][0][0]) < TOL * size
    assert abs(point(inverse, "C") - case["poses"][0][1]) < TOL * size
    for body in (direct, inverse):
        assert body["defects"]["grashof"] is False and body["defects"]["branch"] is False
        assert body["defects"]["order"] is False
        assert body["dimensions"]["grashof"] == "Grashof crank-rocker"
        for check, (_, _, P, _) in zip(body["checks"], case["poses"], strict=True):
            assert check["reached"] and check["error"] < TOL * size
            # /analyze at the check's crank angle puts P where the task wants it.
            scene = copy.deepcopy(body.as_dict()["scene"])
            scene["drivers"][0]["angle_deg"] = check["driver_angle_deg"]
            at = solver.analyze(scene, ["position"])["points"]["P"]["position"]
            assert abs(complex(*at) - P) < TOL * size


def test_poles_and_circumcentre_closed_forms() -> None:
    """P12 is fixed by the rotation taking pose 1 to pose 2: a rotation of 90 deg about (1, 1)
    takes (2, 1) at 0 deg to (1, 2) at 90 deg; the circumcentre of (0,0), (2,0), (0,2) is
    (1, 1)."""
    P12 = pole(Pose(2 + 1j, 0.0), Pose(1 + 2j, math.pi / 2))
    assert P12 is not None and abs(P12 - (1 + 1j)) < 1e-15
    assert pole(Pose(0j, 0.3), Pose(1 + 1j, 0.3)) is None  # a translation has no pole
    centre = circumcentre(0j, 2 + 0j, 2j)
    assert centre is not None and abs(centre - (1 + 1j)) < 1e-15
    assert circumcentre(0j, 1 + 1j, 2 + 2j) is None


def test_two_positions_take_the_stated_points_of_the_bisectors() -> None:
    """Two positions: each fixed pivot on its perpendicular bisector, one chord from the
    midpoint (|AB1| = |AB2|, the crank turns 2 atan(1/2) = 53.13 deg), stated in words."""
    task = {
        "task": "motion",
        "positions": [{"point": [0, 0], "angle_deg": 0}, {"point": [1, 0.2], "angle_deg": 25}],
        "moving_pivots": [[-0.4, 0.1], [0.5, 0.2]],
    }
    body = solver.synthesize(task)
    places = body["construction"]["places"]
    A, D = point(body, "A"), point(body, "D")
    for fixed, name in ((A, "B"), (D, "C")):
        first, second = (complex(*p) for p in places[name])
        assert abs(abs(fixed - first) - abs(fixed - second)) < 1e-12
        assert abs(abs(fixed - 0.5 * (first + second)) - abs(second - first)) < 1e-12
    assert "53.13 deg" in body["construction"]["choices"][0]
    for check in body["checks"]:
        assert check["reached"] and check["error"] < TOL


TWO_POSITIONS = [{"point": [0, 0], "angle_deg": 0}, {"point": [1, 0.2], "angle_deg": 25}]


def offset_along_bisector(first: complex, second: complex, z: complex) -> float:
    """d with the foot of z at M + d n on the bisector of first -> second: numpy's dot of z - M
    with the unit normal n (the chord turned 90 deg counter-clockwise, to its left)."""
    chord = np.array([second.real - first.real, second.imag - first.imag])
    normal = np.array([-chord[1], chord[0]]) / np.linalg.norm(chord)
    middle = 0.5 * (first + second)
    return float(np.dot([z.real - middle.real, z.imag - middle.imag], normal))


@pytest.mark.parametrize("seed", range(8))
def test_two_positions_with_bisector_offsets_give_the_four_bar_back(seed: int) -> None:
    """Two poses of a known crank-rocker, its own fixed pivots' offsets along the bisectors
    (numpy): the answer is that four-bar (A, D to 1e-9 of its size), A and D equidistant from
    their moving pivot's two places, every position reached by /analyze at the checks' crank
    angles (B, C and P where the task puts them), and the choice stated with the numbers."""
    case = three_poses(np.random.default_rng(100 + seed))
    case["poses"] = case["poses"][:2]
    (B1, C1, _, _), (B2, C2, _, _) = case["poses"]
    offsets = [offset_along_bisector(B1, B2, case["A"]), offset_along_bisector(C1, C2, case["D"])]
    body = solver.synthesize(motion_task(case, "moving") | {"bisector_offsets": offsets})
    size = max(case["lengths"])
    A, D = point(body, "A"), point(body, "D")
    assert abs(A - case["A"]) < TOL * size and abs(D - case["D"]) < TOL * size
    assert abs(abs(A - B1) - abs(A - B2)) < TOL * size
    assert abs(abs(D - C1) - abs(D - C2)) < TOL * size
    assert f"dA = {offsets[0]:g} m" in body["construction"]["choices"][0]
    assert not any(body["defects"][k] for k in ("branch", "order", "grashof"))
    for check, (B, C, P, _) in zip(body["checks"], case["poses"], strict=True):
        assert check["reached"] and check["error"] < TOL * size
        scene = copy.deepcopy(body.as_dict()["scene"])
        scene["drivers"][0]["angle_deg"] = check["driver_angle_deg"]
        at = solver.analyze(scene, ["position"])["points"]
        for name, where in (("B", B), ("C", C), ("P", P)):
            assert abs(complex(*at[name]["position"]) - where) < TOL * size


@pytest.mark.parametrize("offsets", [[0.7, -0.3], [-1.2, 0.4], [0.0, 0.9]])
def test_bisector_offsets_place_the_pivots_at_midpoint_plus_offset_times_normal(
    offsets: list[float],
) -> None:
    """A = M_B + dA n_B and D = M_C + dD n_C (numpy: the chords' midpoints and their unit normals
    to the left), any sign, zero included."""
    task = {
        "task": "motion",
        "positions": TWO_POSITIONS,
        "moving_pivots": [[-0.4, 0.1], [0.5, 0.2]],
        "bisector_offsets": offsets,
    }
    body = solver.synthesize(task)
    places = body["construction"]["places"]
    for fixed, name, offset in (("A", "B", offsets[0]), ("D", "C", offsets[1])):
        first, second = (np.array(p) for p in places[name])
        chord = second - first
        normal = np.array([-chord[1], chord[0]]) / np.linalg.norm(chord)
        expected = 0.5 * (first + second) + offset * normal
        assert np.allclose(body["scene"]["points"][fixed], expected, rtol=0, atol=1e-12)


def freudenstein_task(function: str = "x^2", **more: Any) -> dict[str, Any]:
    return {
        "task": "function",
        "function": function,
        "x_range": [1, 2],
        "input_range_deg": [30, 120],
        "output_range_deg": [60, 150],
        **more,
    }


@pytest.mark.parametrize("function", ["x^2", "log(x)", "sqrt(x)", "exp(0.5*x)", "1/x", "x^3"])
def test_freudenstein_holds_at_the_precision_points(function: str) -> None:
    """K1 cos(theta_4) - K2 cos(theta_2) + K3 = cos(theta_2 - theta_4) at each precision point
    (to 1e-9), the lengths from the K's (K1 = d/a, K2 = d/c, K3 = (a^2 - b^2 + c^2 + d^2) /
    (2 a c)), and the returned scene's rocker at each precision crank angle, by /analyze."""
    body = solver.synthesize(freudenstein_task(function))
    k = body["freudenstein"]
    a, b, c, d = (k[n] for n in "abcd")
    assert k["K1"] == pytest.approx(d / a, rel=1e-12)
    assert k["K2"] == pytest.approx(d / c, rel=1e-12)
    assert k["K3"] == pytest.approx((a * a - b * b + c * c + d * d) / (2 * a * c), rel=1e-12)
    f = {"x^2": np.square, "log(x)": np.log, "sqrt(x)": np.sqrt, "1/x": np.reciprocal,
         "exp(0.5*x)": lambda x: np.exp(0.5 * x), "x^3": lambda x: x**3}[function]  # fmt: skip
    y0, yf = f(1.0), f(2.0)
    for p, check in zip(body["precision_points"], body["checks"], strict=True):
        t2, t4 = math.radians(p["input_angle_deg"]), math.radians(p["output_angle_deg"])
        assert p["y"] == pytest.approx(f(p["x"]), abs=1e-12)
        assert t2 == pytest.approx(math.radians(30 + 90 * (p["x"] - 1.0)), abs=1e-12)
        assert t4 == pytest.approx(math.radians(60 + 90 * (p["y"] - y0) / (yf - y0)), abs=1e-12)
        residual = k["K1"] * math.cos(t4) - k["K2"] * math.cos(t2) + k["K3"] - math.cos(t2 - t4)
        assert abs(residual) < TOL
        assert check["reached"] and check["error"] < TOL * abs(yf - y0)
        scene = copy.deepcopy(body.as_dict()["scene"])
        scene["drivers"][0]["angle_deg"] = check["driver_angle_deg"]
        rocker = solver.analyze(scene, ["position"])["links"]["rocker"]["angle"]
        flip = math.pi if c < 0 else 0.0
        assert abs(math.remainder(rocker - flip - t4, 2 * math.pi)) < TOL


def test_a_branch_defect_of_a_function_is_what_analyze_shows() -> None:
    """sin(x) over [1, 2] turns back at pi/2: Freudenstein's three points solve, but the middle
    one lies on the other assembly; /analyze at its crank angle shows the rocker that far off,
    and the defect and a sentence say so."""
    body = solver.synthesize(freudenstein_task("sin(x)"))
    assert body["defects"]["branch"] is True
    middle = body["checks"][1]
    assert not middle["reached"] and middle["output_angle_error_deg"] > 1.0
    scene = copy.deepcopy(body.as_dict()["scene"])
    scene["drivers"][0]["angle_deg"] = middle["driver_angle_deg"]
    rocker = solver.analyze(scene, ["position"])["links"]["rocker"]["angle"]
    flip = math.pi if body["freudenstein"]["c"] < 0 else 0.0
    wanted = math.radians(body["precision_points"][1]["output_angle_deg"])
    off = abs(math.remainder(rocker - flip - wanted, 2 * math.pi))
    assert math.degrees(off) == pytest.approx(middle["output_angle_error_deg"], abs=1e-9)
    assert any("branch defect: at x = 1.5" in w for w in body["warnings"])


def test_chebyshev_spacing_is_the_textbook_one() -> None:
    """x_j = (x0 + xf)/2 - (xf - x0)/2 cos((2j - 1) pi / 6) for three points (Norton, Design of
    Machinery, eq. 5.34): 1.0669873, 1.5, 1.9330127 over [1, 2]."""
    assert chebyshev_spacing(1.0, 2.0, 3) == pytest.approx(
        (1.5 - 0.5 * math.sqrt(3) / 2, 1.5, 1.5 + 0.5 * math.sqrt(3) / 2), abs=1e-15
    )
    body = solver.synthesize(freudenstein_task())
    assert [p["x"] for p in body["precision_points"]] == pytest.approx(
        [1.0669872981077806, 1.5, 1.9330127018922194], abs=1e-12
    )
    assert body["spacing"] == "chebyshev"


def test_given_precision_points_and_the_structural_error() -> None:
    """Given points are used as given; the structural error is zero at them and its maximum
    is the largest |y_generated - f(x)| over the sampled range."""
    body = solver.synthesize(freudenstein_task(precision_points=[1.1, 1.5, 1.9]))
    assert [p["x"] for p in body["precision_points"]] == [1.1, 1.5, 1.9]
    structural = body["structural_error"]
    errors = np.array(structural["error"], dtype=float)
    assert structural["max"] == pytest.approx(np.max(np.abs(errors)), rel=1e-12)
    x = np.array(structural["x"])
    for xp in (1.1, 1.5, 1.9):  # the error changes sign at each precision point
        k = int(np.searchsorted(x, xp))
        assert errors[k - 1] * errors[k] <= 1e-12
    assert structural["max"] > 0


def yoke(scene: dict[str, Any], rocker_angles: list[float]) -> dict[str, Any]:
    """The crank-rocker driving a ram by a Scotch yoke on the rocker's pin C: the ram slides
    across the mid-swing direction, so that it reverses exactly where the rocker does."""
    out = copy.deepcopy(scene)
    middle = math.atan2(sum(map(math.sin, rocker_angles)), sum(map(math.cos, rocker_angles)))
    out["points"]["R"] = list(out["points"]["C"])
    out["links"]["ram"] = {"points": ["R"]}
    out["joints"] += [
        {"type": "slider", "point": "C", "links": ["ram", "rocker"],
         "axis": [math.cos(middle), math.sin(middle)]},
        {"type": "prismatic", "point": "R", "links": ["ground", "ram"],
         "axis": [math.cos(middle - math.pi / 2), math.sin(middle - math.pi / 2)]},
    ]  # fmt: skip
    return out


@pytest.mark.parametrize(
    ("ratio", "swing"), [(1.25, 60.0), (1.5, 45.0), (1.0, 40.0), (1.2, 30.0), (2.0, 75.0)]
)
def test_quick_return_time_ratio_from_sweep(ratio: float, swing: float) -> None:
    """The returned crank-rocker's time ratio, read by /sweep's ``quick_return`` of a ram
    yoked to its rocker (the solver's own extremes), and its swing, by /analyze at the limit
    positions (where the rocker stands still)."""
    task = {"task": "quick_return", "time_ratio": ratio, "rocker_length": 0.1, "swing_deg": swing}
    body = solver.synthesize(task)
    assert body["dimensions"]["grashof"] == "Grashof crank-rocker"
    assert body["dimensions"]["rocker"] == pytest.approx(0.1, rel=1e-12)
    assert body["construction"]["alpha_deg"] == pytest.approx(
        180 * (ratio - 1) / (ratio + 1), abs=1e-12
    )
    angles = [math.radians(c["rocker_angle_deg"]) for c in body["checks"]]
    swept = solver.sweep(yoke(body.as_dict()["scene"], angles), 360, ["position"]).as_dict()
    ram = next(s for s in swept["sliders"] if s["point"] == "R")
    assert ram["quick_return"]["time_ratio"] == pytest.approx(ratio, abs=1e-9)
    assert abs(ram["quick_return"]["extreme_positions"][1]["displacement"]
               - ram["quick_return"]["extreme_positions"][0]["displacement"]) == pytest.approx(
        2 * 0.1 * math.sin(math.radians(swing) / 2), abs=1e-9 * 0.1
    )  # fmt: skip
    for check in body["checks"]:
        assert check["reached"] and check["error"] < TOL * 0.1
        assert abs(check["rocker_omega"]) < 1e-9
    assert body["swing_deg"] == pytest.approx(swing, abs=1e-7)
    assert not any(body["defects"][k] for k in ("branch", "order", "grashof"))


def test_quick_return_alpha_is_the_textbooks() -> None:
    """Norton, Design of Machinery, example 3-7: a time ratio of 1.25 with a 40 deg rocker swing
    is a crank turn of 200 deg forward and 160 deg back, alpha = 180 (Q - 1) / (Q + 1) = 20 deg.
    The returned scene's crank turns 200 deg counter-clockwise from its first limit position to
    the second, and its rocker swings 40 deg between them (both from /analyze)."""
    assert math.degrees(crank_angle_difference(1.25)) == pytest.approx(20.0, abs=1e-12)
    assert crank_angle_difference(1.0) == 0.0
    task = {"task": "quick_return", "time_ratio": 1.25, "rocker_length": 1.0, "swing_deg": 40}
    body = solver.synthesize(task)
    first, second = (c["driver_angle_deg"] for c in body["checks"])
    assert (second - first) % 360.0 == pytest.approx(200.0, abs=1e-9)
    scene = body.as_dict()["scene"]
    rocker = []
    for check in body["checks"]:
        posed = copy.deepcopy(scene)
        posed["drivers"][0]["angle_deg"] = check["driver_angle_deg"]
        rocker.append(solver.analyze(posed, ["position"])["links"]["rocker"]["angle"])
    swing = math.degrees(abs(math.remainder(rocker[1] - rocker[0], 2 * math.pi)))
    assert swing == pytest.approx(40.0, abs=1e-9)


def random_task(rng: np.random.Generator, count: int) -> dict[str, Any]:
    positions = [
        {"point": list(rng.uniform(-1, 1, 2)), "angle_deg": float(rng.uniform(-90, 90))}
        for _ in range(count)
    ]
    key = "moving_pivots" if rng.uniform() < 0.5 else "fixed_pivots"
    return {
        "task": "motion",
        "positions": positions,
        key: [list(rng.uniform(-2, 2, 2)) for _ in "ab"],
    }


@pytest.mark.parametrize("seed", range(30))
def test_random_tasks_reach_every_position_or_say_why(seed: int) -> None:
    """A random task is refused with a reason, or each position is reached by /analyze at its
    crank angle to 1e-9 of the linkage's size, or named unreached with a branch or Grashof
    defect and a sentence; the scene's link lengths are the stated dimensions."""
    rng = np.random.default_rng(1000 + seed)
    task = random_task(rng, 2 + seed % 2)
    try:
        body = solver.synthesize(task)
    except solver.InvalidScene as error:
        assert str(error)
        return
    scene = body.as_dict()["scene"]
    parsed = solver.parse_scene(scene)
    size = parsed.size
    pts = {k: complex(*v) for k, v in scene["points"].items()}
    assert abs(pts["B"] - pts["A"]) == pytest.approx(body["dimensions"]["crank"], rel=1e-12)
    assert abs(pts["C"] - pts["D"]) == pytest.approx(body["dimensions"]["rocker"], rel=1e-12)
    for check, wanted in zip(body["checks"], task["positions"], strict=True):
        posed = copy.deepcopy(scene)
        posed["drivers"][0]["angle_deg"] = check["driver_angle_deg"]
        at = complex(*solver.analyze(posed, ["position"])["points"]["P"]["position"])
        if check["reached"]:
            assert abs(at - complex(*wanted["point"])) < TOL * size
        else:
            assert body["defects"]["branch"] or body["defects"]["grashof"]
            assert body["warnings"]


@pytest.mark.parametrize("seed", range(12))
def test_defects_match_the_sweep(seed: int) -> None:
    """``grashof`` is /sweep's ``feasible`` negated; a reached position is passed by the swept
    coupler point (within one sample's travel), in the given order along the sweep (which
    turns in the driver's sense from the first position)."""
    rng = np.random.default_rng(2000 + seed)
    try:
        body = solver.synthesize(random_task(rng, 3))
    except solver.InvalidScene:
        return
    scene = body.as_dict()["scene"]
    swept = solver.sweep(scene, 3600, ["position"])
    assert body["defects"]["grashof"] is (not swept["feasible"])
    P = np.asarray(swept["points"]["P"]["position"])
    step = float(np.max(np.abs(np.diff(P[:, 0] + 1j * P[:, 1]))))
    passed = []
    for check in body["checks"]:
        target = complex(*check["point"]) if check["reached"] else None
        if target is None:
            continue
        distance = np.abs(P[:, 0] + 1j * P[:, 1] - target)
        assert float(distance.min()) <= step
        passed.append(int(np.argmin(distance)))
    if swept["feasible"] and not body["defects"]["order"]:
        assert passed == sorted(passed)


@pytest.mark.parametrize(
    ("task", "words"),
    [
        ({"task": "quick_return", "time_ratio": 0.8, "rocker_length": 0.1, "swing_deg": 60},
         "at least 1"),
        ({"task": "quick_return", "time_ratio": 20, "rocker_length": 0.1, "swing_deg": 10},
         "no crank-rocker has the time ratio 20"),
        ({"task": "quick_return", "time_ratio": 1.5, "rocker_length": 0.1, "swing_deg": 190},
         "0 < swing < 180"),
        ({"task": "motion", "positions": [{"point": [1, 0], "angle_deg": 0},
                                          {"point": [0, 1], "angle_deg": 90},
                                          {"point": [-1, 0], "angle_deg": 180}],
          "moving_pivots": [[0, 2], [1, 3]]}, "poles P12, P13, P23 coincide"),
        ({"task": "motion", "positions": [{"point": [0, 0], "angle_deg": 0},
                                          {"point": [1, 0], "angle_deg": 0},
                                          {"point": [2, 0], "angle_deg": 0}],
          "moving_pivots": [[0, 1], [1, 1]]}, "lie on one line"),
        ({"task": "motion", "positions": [{"point": [0, 0], "angle_deg": 0}],
          "moving_pivots": [[0, 1], [1, 1]]}, "2 or 3 positions"),
        ({"task": "motion", "positions": [{"point": [0, 0], "angle_deg": 0},
                                          {"point": [0, 0], "angle_deg": 0}],
          "fixed_pivots": [[0, 1], [1, 1]]}, "the same pose"),
        ({"task": "motion", "positions": [{"point": [0, 0], "angle_deg": 0},
                                          {"point": [1, 0], "angle_deg": 30}],
          "moving_pivots": [[0, 1], [1, 1]], "fixed_pivots": [[0, 1], [1, 1]]}, "not both"),
        ({"task": "motion", "positions": TWO_POSITIONS, "moving_pivots": [[0, 1], [1, 1]],
          "bisector_offsets": [0.1]}, "bisector_offsets: expected two numbers"),
        ({"task": "motion", "positions": TWO_POSITIONS, "moving_pivots": [[0, 1], [1, 1]],
          "bisector_offsets": [0.1, "a"]}, "bisector_offsets[1]: expected a number"),
        ({"task": "motion", "positions": TWO_POSITIONS, "moving_pivots": [[0, 1], [1, 1]],
          "bisector_offsets": [math.inf, 0.1]}, "not a finite number"),
        ({"task": "motion", "positions": TWO_POSITIONS, "fixed_pivots": [[0, 1], [1, 1]],
          "bisector_offsets": [0.1, 0.2]}, "they go with moving_pivots"),
        ({"task": "motion", "positions": [{"point": [0, 0], "angle_deg": 0},
                                          {"point": [1, 0.5], "angle_deg": 30},
                                          {"point": [2, 0.3], "angle_deg": 60}],
          "moving_pivots": [[-0.5, -0.2], [0.5, -0.3]], "bisector_offsets": [0.1, 0.2]},
         "the free choice of two positions only"),
        ({"task": "motion", "positions": TWO_POSITIONS, "moving_pivots": [[0, 1], [1, 1]],
          "bisector_offset": [0.1, 0.2]}, "did you mean bisector_offsets"),
        (freudenstein_task(precision_points=4), "give 3 (Chebyshev spacing)"),
        (freudenstein_task(precision_points=[1.2, 1.8]), "exactly 3 precision points"),
        (freudenstein_task(precision_points=[1.1, 1.5, 2.5]), "outside x_range"),
        (freudenstein_task("cos(2*pi*x)"), "the same value at both ends"),
        (freudenstein_task(x_range=[1, 1]), "the range is empty"),
        ({"task": "function", "function": "x", "x_range": [0, 1], "input_range_deg": [0, 90],
          "output_range_deg": [0, 90], "precision_point": 3}, "did you mean precision_points"),
        ({"task": "synthesise"}, "expected 'motion', 'function' or 'quick_return'"),
    ],
)  # fmt: skip
def test_refusals_say_why(task: dict[str, Any], words: str) -> None:
    with pytest.raises(solver.InvalidScene) as caught:
        solver.synthesize(task)
    assert words in str(caught.value)


@pytest.mark.parametrize(
    ("function", "position", "words"),
    [
        ("x^2 + t", 6, "written in x"),
        ("2x", 1, "write 2*x"),
        ("sqrt(x - 1.5)", 0, "not defined at x = 1"),
        ("__import__('os')", 0, "unknown name '__import__'"),
    ],
)
def test_the_function_is_parsed_safely_in_x(function: str, position: int, words: str) -> None:
    with pytest.raises(solver.InvalidExpression) as caught:
        solver.synthesize(freudenstein_task(function))
    assert caught.value.position == position
    assert words in caught.value.message
    assert caught.value.expression == function

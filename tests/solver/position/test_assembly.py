"""The assembly changes only at a true bifurcation (issue 8).

Linkages eps (relative to their longest link, 1e-3 ... 1e-12) away from a change point: four-bars
just inside and just outside the Grashof equality (a crank-rocker whose coupler and rocker come
near the extended line, one that comes near the folded line, a drag-link), slider-cranks whose rod
is eps longer (or shorter) than the crank plus the offset, and inverted slider-cranks whose pin
passes eps from the lever's pivot or from its slot's reach. Swept with 36, 360, 3600 and 36000
samples from random starting angles, each must stay on its drawn branch: every sample equals an
independent closed form on that branch (a different formula from the solver's: Heron's area for
the height of a dyad's triangle, half-angle formulas for the limits) to 1e-9 of the linkage's
size. Where the linkage cannot turn fully the sweep says feasible = false and gives the limit
positions of the closed form to 1e-9 rad. True change points still pass through: a kite (ground =
crank, coupler = rocker) keeps its deltoid shape through the pose where B falls on D.
"""

from __future__ import annotations

import math
import zlib
from collections.abc import Callable
from typing import Any

import numpy as np
import pytest

import solver
from solver.analysis.instant import analyze
from solver.analysis.sweeps import Sweep, sweep
from solver.model.scene import LinkageScene, parse_linkage
from solver.position.assembly import WARNING_MARGIN, candidate_intervals, candidate_minima, screen
from solver.teaching.presets import build_preset

SAMPLE_COUNTS = (36, 360, 3600, 36000)
EPSILONS = (1e-3, 1e-6, 1e-9, 1e-12)
TOLERANCE = 1e-9  # positions, relative to the scene's size; limits in rad
Doc = dict[str, Any]


def _xy(scene: LinkageScene, name: str) -> np.ndarray:
    return np.asarray(scene.drawn(name), dtype=float)


def _length(scene: LinkageScene, p: str, q: str) -> float:
    return float(np.hypot(*(_xy(scene, q) - _xy(scene, p))))


def _side(u: np.ndarray, w: np.ndarray) -> float:
    return 1.0 if float(u[0] * w[1] - u[1] * w[0]) >= 0.0 else -1.0


def _half_angle(d: float, g: float, a: float) -> float:
    """The crank angle at which |B - D| = d, B = a e^(i theta), D = (g, 0): from
    d^2 = (g - a)^2 + 4 a g sin^2(theta / 2), theta = 2 atan2(sqrt(d^2 - (g - a)^2),
    sqrt((g + a)^2 - d^2)) with each difference of squares factored."""
    low = max((d - abs(g - a)) * (d + abs(g - a)), 0.0)
    high = max((g + a - d) * (g + a + d), 0.0)
    return 2.0 * math.atan2(math.sqrt(low), math.sqrt(high))


# --- the closed forms on the drawn branch --------------------------------------------------------


def four_bar_C(scene: LinkageScene, theta: np.ndarray) -> np.ndarray:
    """C on the drawn side of B -> D: C = B + (a + i s h)(D - B)/d with h = 2 Area / d (Heron)."""
    A, B0, C0, D = (_xy(scene, p) for p in "ABCD")
    crank, b, c = _length(scene, "A", "B"), _length(scene, "B", "C"), _length(scene, "D", "C")
    side = _side(D - B0, C0 - B0)
    B = A + crank * np.stack((np.cos(theta), np.sin(theta)), axis=-1)
    e = D - B
    d = np.hypot(*e.T)
    along = (d * d + b * b - c * c) / (2.0 * d)
    heron = (b + c + d) * (b + c - d) * (d + b - c) * (d - b + c)
    h = np.sqrt(np.maximum(heron, 0.0)) / (2.0 * d)
    u = e / d[:, None]
    return B + along[:, None] * u + (side * h)[:, None] * np.stack((-u[:, 1], u[:, 0]), axis=-1)


def four_bar_limits(scene: LinkageScene) -> tuple[float, float]:
    """The limit crank angle (the window is around pi for the extended, 0 for the folded line)."""
    g, a = _length(scene, "A", "D"), _length(scene, "A", "B")
    b, c = _length(scene, "B", "C"), _length(scene, "D", "C")
    reach = b + c if a + g > b + c else abs(b - c)
    limit = _half_angle(reach, g, a)
    return (limit, -limit)


def slider_C(scene: LinkageScene, theta: np.ndarray) -> np.ndarray:
    """C on the guide y = e on the drawn side of B: x = B_x + s sqrt((l - |dy|)(l + |dy|))."""
    A, B0, C0 = (_xy(scene, p) for p in "ABC")
    crank, rod, e = _length(scene, "A", "B"), _length(scene, "B", "C"), float(C0[1])
    side = 1.0 if C0[0] >= B0[0] else -1.0
    bx, by = A[0] + crank * np.cos(theta), A[1] + crank * np.sin(theta)
    dy = np.abs(e - by)
    x = bx + side * np.sqrt(np.maximum((rod - dy) * (rod + dy), 0.0))
    return np.stack((x, np.full_like(x, e)), axis=-1)


def slider_limits(scene: LinkageScene) -> tuple[float, float]:
    """The limit crank angles, where B_y = e - rod (rod < crank + e, e >= 0): sin(theta) =
    -1 + (crank + e - rod) / crank, on either side of -90 deg (offset: the window around -90 deg)
    or of +-90 deg (in line: the crank swings between the two windows)."""
    crank, rod = _length(scene, "A", "B"), _length(scene, "B", "C")
    e = float(_xy(scene, "C")[1])
    one_plus_s = (crank + e - rod) / crank
    s = -1.0 + one_plus_s
    limit = math.atan2(s, math.sqrt(max(one_plus_s * (1.0 - s), 0.0)))
    return (limit, -limit) if e == 0.0 else (limit, -math.pi - limit)


def inverted_D(scene: LinkageScene, theta: np.ndarray) -> np.ndarray:
    """The lever's end D: the slot keeps its offset e from C and passes through A, on the drawn
    side: beta = atan2(r) - atan2(e, s sqrt((|r| - e)(|r| + e))),
    D = C + R(beta - beta0)(D0 - C)."""
    pivot, A0, C, D0 = (_xy(scene, p) for p in "OACD")
    joint = next(j for j in scene.joints if j.type == "slider")
    assert joint.axis is not None
    u0 = np.asarray(joint.axis, dtype=float)
    crank = _length(scene, "O", "A")
    r0 = A0 - C
    e = float(u0[0] * r0[1] - u0[1] * r0[0])
    side = 1.0 if float(u0 @ r0) >= 0.0 else -1.0
    A = pivot + crank * np.stack((np.cos(theta), np.sin(theta)), axis=-1)
    r = A - C
    length = np.hypot(*r.T)
    along = side * np.sqrt(np.maximum((length - abs(e)) * (length + abs(e)), 0.0))
    beta = np.arctan2(r[:, 1], r[:, 0]) - np.arctan2(e, along)
    turn = beta - math.atan2(u0[1], u0[0])
    c, s = np.cos(turn), np.sin(turn)
    d = D0 - C
    return C + np.stack((c * d[0] - s * d[1], s * d[0] + c * d[1]), axis=-1)


def inverted_limits(scene: LinkageScene) -> tuple[float, float]:
    """The limit crank angle, where |A - C| = |e| (the window around 0)."""
    g, a = _length(scene, "O", "C"), _length(scene, "O", "A")
    joint = next(j for j in scene.joints if j.type == "slider")
    assert joint.axis is not None
    r0 = _xy(scene, "A") - _xy(scene, "C")
    e = abs(float(joint.axis[0] * r0[1] - joint.axis[1] * r0[0]))
    limit = _half_angle(e, g, a)
    return (limit, -limit)


# --- the families --------------------------------------------------------------------------------


class Family:
    """A preset eps away from a change point: ``inside`` turns fully, outside has limits at
    ``limits`` (``window`` = the centre of the window it cannot pass, to draw start angles)."""

    def __init__(
        self,
        preset: str,
        values: Callable[[float], dict[str, float]],
        point: str,
        closed_form: Callable[[LinkageScene, np.ndarray], np.ndarray],
        limit: Callable[[LinkageScene], tuple[float, float]] | None,
        window: float,
        two_windows: bool = False,
    ) -> None:
        self.preset, self.values, self.point = preset, values, point
        self.closed_form, self.limit, self.window = closed_form, limit, window
        self.two_windows = two_windows


FAMILIES = {
    # crank-rocker, coupler and rocker near the extended line at crank 180 deg: b + c = g + a + eps
    "crank_rocker_extended": Family(
        "four_bar",
        lambda eps: {"ground": 1.0, "crank": 0.4, "coupler": 0.9, "rocker": 0.5 + eps},
        "C",
        four_bar_C,
        four_bar_limits,
        180.0,
    ),
    # crank-rocker, coupler and rocker near the folded line at crank 0: b - c = g - a - eps
    "crank_rocker_folded": Family(
        "four_bar",
        lambda eps: {"ground": 0.9, "crank": 0.4, "coupler": 1.0, "rocker": 0.5 + eps},
        "C",
        four_bar_C,
        four_bar_limits,
        0.0,
    ),
    # drag-link (double crank, the ground the shortest): b + c = a + g + eps
    "drag_link": Family(
        "four_bar",
        lambda eps: {"ground": 0.4, "crank": 1.0, "coupler": 0.9, "rocker": 0.5 + eps},
        "C",
        four_bar_C,
        four_bar_limits,
        180.0,
    ),
    # in-line slider-crank, rod = crank + eps (outside: windows at +-90 deg)
    "slider_crank_in_line": Family(
        "slider_crank",
        lambda eps: {"crank": 1.0, "rod": 1.0 + eps, "offset": 0.0},
        "C",
        slider_C,
        slider_limits,
        -90.0,
        two_windows=True,
    ),
    # offset slider-crank, rod = crank + offset + eps (outside: a window at -90 deg)
    "slider_crank_offset": Family(
        "slider_crank",
        lambda eps: {"crank": 0.8, "rod": 1.0 + eps, "offset": 0.2},
        "C",
        slider_C,
        slider_limits,
        -90.0,
    ),
    # inverted slider-crank, slot through the pivot: the pin passes eps from it (both sides turn)
    "inverted_through_pivot": Family(
        "inverted_slider_crank",
        lambda eps: {"crank": 1.0 + eps, "ground": 1.0, "lever": 1.5, "slot_offset": 0.0},
        "D",
        inverted_D,
        None,
        0.0,
    ),
    # inverted slider-crank with an offset slot: |CA| comes within eps of the offset
    "inverted_offset_slot": Family(
        "inverted_slider_crank",
        lambda eps: {"crank": 0.8 - eps, "ground": 1.0, "lever": 1.5, "slot_offset": 0.2},
        "D",
        inverted_D,
        inverted_limits,
        0.0,
    ),
}


def _doc(family: Family, eps: float, start_deg: float, assembly: float) -> Doc:
    values = {**family.values(eps), "crank_angle_deg": start_deg, "omega": 1.0}
    if family.preset != "inverted_slider_crank":
        values["assembly"] = assembly
    return build_preset(family.preset, values)


def _start(rng: np.random.Generator, family: Family, inside: bool) -> float:
    """A random starting angle, 30 deg or more from the window a linkage outside cannot pass."""
    if inside:
        return float(rng.uniform(-180.0, 180.0))
    if family.two_windows:  # between the windows at +-90 deg
        return float(rng.uniform(-60.0, 60.0))
    return (family.window + float(rng.uniform(30.0, 330.0)) + 180.0) % 360.0 - 180.0


def _wrapped(a: float, b: float) -> float:
    return abs(math.remainder(a - b, 2.0 * math.pi))


def check_family(family: Family, eps: float, inside: bool, seed: int) -> None:
    rng = np.random.default_rng(seed)
    for samples in SAMPLE_COUNTS:
        doc = _doc(family, eps if inside else -eps, _start(rng, family, inside), samples % 2)
        scene = parse_linkage(doc)
        result: Sweep = sweep(scene, samples, ["position"])
        expected = family.closed_form(scene, result.driver_angle)
        error = np.hypot(*(result.motion.points[family.point].p - expected).T)
        worst = int(np.argmax(error))
        assert error[worst] <= TOLERANCE * scene.size, (samples, worst, error[worst])
        if inside or family.limit is None:
            assert result.feasible and result.limits == (), samples
            continue
        assert result.feasible is False, samples
        limits = family.limit(scene)
        assert len(result.limits) == 2
        for found in result.limits:
            assert min(_wrapped(found, limit) for limit in limits) <= TOLERANCE, (samples, found)


@pytest.mark.parametrize("eps", EPSILONS)
@pytest.mark.parametrize("inside", [True, False], ids=["inside", "outside"])
@pytest.mark.parametrize("name", list(FAMILIES))
def test_branch_kept_next_to_a_change_point(name: str, inside: bool, eps: float) -> None:
    """Each family at 36 ... 36000 samples from random starts: on the drawn branch to 1e-9 of the
    size everywhere; outside the equality, feasible false and the closed form's limits."""
    if name == "inverted_through_pivot" and not inside:
        eps = -eps  # crank = ground - eps: the lever rocks instead of turning; both sides close
    check_family(FAMILIES[name], eps, inside, seed=zlib.crc32(f"{name} {inside} {eps}".encode()))


# --- true change points --------------------------------------------------------------------------


@pytest.mark.parametrize("samples", SAMPLE_COUNTS)
def test_kite_keeps_its_deltoid_shape_through_b_on_d(samples: int) -> None:
    """A kite (ground AD = crank AB = 1, coupler BC = rocker DC = 0.5): the crank swings between
    +-60 deg (|BD| = 1 = BC + DC) and passes B = D at 0, where C's two solutions are a whole
    circle. Drawn convex (C on the bisector of angle BAD, beyond BD), it must stay convex:
    C = (cos t/2, sin t/2) (cos t/2 + sqrt(0.25 - sin^2 t/2)) at crank angle t, to 1e-9 m."""
    values = {"ground": 1.0, "crank": 1.0, "coupler": 0.5, "rocker": 0.5, "crank_angle_deg": 30.0}
    for assembly in (0.0, 1.0):
        doc = build_preset("four_bar", {**values, "assembly": assembly})
        C = np.array(doc["points"]["C"])
        if np.hypot(*C) > 1.0:  # the convex kite
            break
    scene = parse_linkage(doc)
    result = sweep(scene, samples, ["position"])
    half = 0.5 * result.driver_angle
    reach = np.cos(half) + np.sqrt(np.maximum(0.25 - np.sin(half) ** 2, 0.0))
    expected = np.stack((np.cos(half), np.sin(half)), axis=-1) * reach[:, None]
    error = np.hypot(*(result.motion.points["C"].p - expected).T)
    assert float(error.max()) <= TOLERANCE
    assert result.feasible is False
    assert sorted(result.limits) == pytest.approx([-math.pi / 3, math.pi / 3], abs=TOLERANCE)
    assert result.driver_angle.min() < 0.0 < result.driver_angle.max()  # it passes B = D


# --- close approaches: said in words, with the numbers ----------------------------------------


def _near_crank_rocker(eps: float, angle_deg: float = 30.0) -> Doc:
    values = FAMILIES["crank_rocker_extended"].values(eps)
    return build_preset("four_bar", {**values, "crank_angle_deg": angle_deg, "omega": 1.0})


@pytest.mark.parametrize("samples", [36, 3600])
def test_sweep_warns_where_the_branches_nearly_meet(samples: int) -> None:
    """The crank-rocker 1e-4 inside the Grashof equality: the coupler and rocker come within
    m = b + c - (g + a) = 1e-4 m of the extended line at crank 180 deg (the closed form: |BD| is
    largest there). The sweep keeps its branch, reports that closest approach (to 1e-12 m and
    1e-6 rad) and says so in words with the numbers."""
    scene = parse_linkage(_near_crank_rocker(1e-4))
    result = sweep(scene, samples, ["position"])
    margin = _length(scene, "B", "C") + _length(scene, "D", "C") - 1.4
    assert len(result.close_approaches) == 1
    (approach,) = result.close_approaches
    assert approach.point == "C"
    assert abs(approach.margin - margin) <= 1e-12
    assert _wrapped(approach.driver_angle, math.pi) <= 1e-6
    (warning,) = result.warnings
    assert f"within {margin:.2g} m of a change point at 180.0 deg" in warning
    assert "clearance could switch assembly" in warning


def test_no_warning_far_from_a_change_point_or_at_one() -> None:
    """1e-2 of the size away: no close approach to report. A parallelogram meets its change
    points (the branches coincide): it passes through them, with nothing to warn about."""
    far = sweep(parse_linkage(_near_crank_rocker(0.05)), 360, ["position"])
    assert far.close_approaches == () and far.warnings == []
    values = {"ground": 1.0, "crank": 0.4, "coupler": 1.0, "rocker": 0.4, "crank_angle_deg": 60.0}
    parallelogram = build_preset("four_bar", {**values, "assembly": 0.0, "omega": 1.0})
    assert sweep(parse_linkage(parallelogram), 360, ["position"]).warnings == []


def test_analyze_warns_near_a_close_approach() -> None:
    """/analyze at crank 179 deg of the same linkage (margin there ~ 1e-4 + a g (1 - cos 1 deg)
    / ... < 1e-3 of the size): a warning and the closest approach in the diagnostics; at 90 deg
    the margin is large: no warning, the closest approach still reported."""
    near = analyze(parse_linkage(_near_crank_rocker(1e-4, 179.0)))
    assert near.diagnostics.closest_approach is not None
    point, margin = near.diagnostics.closest_approach
    assert point == "C" and 1e-4 < margin < 1e-3
    assert len(near.warnings) == 1 and f"within {margin:.2g} m" in near.warnings[0]
    far = analyze(parse_linkage(_near_crank_rocker(1e-4, 90.0)))
    assert far.warnings == () and far.diagnostics.closest_approach is not None


def test_sweep_warning_in_the_body() -> None:
    """The /sweep body (``as_dict()``, what HTTP sends) carries the warning (a top-level list of
    strings) and the closest approach in its diagnostics; /analyze near it carries its own."""
    body = solver.sweep(_near_crank_rocker(1e-4), 90).as_dict()
    assert len(body["warnings"]) == 1 and "change point at 180.0 deg" in body["warnings"][0]
    closest = body["diagnostics"]["closest_approach"]
    assert closest["point"] == "C" and closest["margin"] == pytest.approx(1e-4, rel=1e-6)
    assert closest["driver_angle_deg"] % 360.0 == pytest.approx(180.0, abs=1e-4)
    near = solver.analyze(_near_crank_rocker(1e-4, 179.0)).as_dict()
    assert len(near["warnings"]) == 1
    assert near["diagnostics"]["closest_approach"]["point"] == "C"


def test_time_sweep_warns_too() -> None:
    """A sweep over time (crank at 1 rad/s for one turn) finds the same close approach: 1e-4 m
    at crank 180 deg."""
    from solver.analysis.sweeps import sweep_time

    scene = parse_linkage(_near_crank_rocker(1e-4))
    result = sweep_time(scene, 0.0, 2.0 * math.pi, 100, ["position"])
    (approach,) = result.close_approaches
    assert approach.margin == pytest.approx(1e-4, rel=1e-6)
    assert _wrapped(approach.driver_angle, math.pi) <= 1e-6
    assert "change point at 180.0 deg" in result.warnings[0]


@pytest.mark.parametrize("fraction", [0.5, 2.0])
def test_warning_threshold_is_1e_3_of_the_size(fraction: float) -> None:
    """The same crank-rocker with its margin at 0.5e-3 and 2e-3 of its size: warned about below
    1e-3 of the size only (WARNING_MARGIN)."""
    size = parse_linkage(_near_crank_rocker(1e-3)).size
    scene = parse_linkage(_near_crank_rocker(fraction * 1e-3 * size))
    warned = sweep(scene, 360, ["position"]).warnings
    assert (len(warned) == 1) == (fraction < 1.0)


def _screened(margin: np.ndarray, rate: np.ndarray, size: float) -> list[int]:
    """The intervals ``screen`` gives a margin of one piece, its rates per sample step (one
    driver, unit steps), quick screen included."""
    path = [(0, np.arange(float(margin.size)), 1.0)]
    return [k for k, _ in screen(margin, [margin], [[rate]], path, size)]


@pytest.mark.parametrize("slope", [0.5, 1.0, 2.0, 4.0, 1e3])
@pytest.mark.parametrize("depth", [0.5, 1.5])
def test_interval_bound_finds_a_v_shaped_minimum(slope: float, depth: float) -> None:
    """A V-shaped margin (|d| at coincident centres) with its vertex between samples 20 and 21 at
    0.5 or 1.5 times the warning margin, every sample above it, its rates +-slope: the bound is
    the vertex itself (lines of the steepest rate from both ends meet there), so that interval
    is a candidate exactly when the vertex is below the threshold, however steep the V; the
    screen's quick test (min(m) - max |p| / 2 clears it) must not skip it."""
    size, w = 2.0, WARNING_MARGIN * 2.0
    k = np.arange(40)
    margin = depth * w + slope * w * np.abs(k - 20.5)
    rate = slope * w * np.sign(k - 20.5)  # dm/du at each sample, the same on both sides
    found = candidate_intervals(margin, rate[:-1], rate[1:], size)
    assert np.array_equal(found, [20] if depth < 1.0 else [])
    assert set(found) <= set(_screened(margin, rate, size))


@pytest.mark.parametrize("seed", range(12))
def test_interval_bound_finds_every_dip_of_its_class(seed: int) -> None:
    """Random margins m(u) = c + sum_i a_i cos(i u + phi_i) (i = 1..4; c puts the deepest dip at
    0.2 to 1.5 times the warning margin), 5 to 60 samples over a turn, with their rates (the
    derivative times the step): on each interval the closed form on a grid of 401 points gives
    the minimum and the steepest rate inside. Every interval whose minimum lies below the
    warning margin, no steeper inside than at an end, and which turns from falling to rising or
    has both samples clear of the threshold, is a candidate, and the screen's quick test skips
    none of them."""
    rng = np.random.default_rng(seed)
    size = float(rng.uniform(0.1, 10.0))
    floor = WARNING_MARGIN * size
    amplitude = size * rng.uniform(0.0, 0.05, 4) / np.arange(1, 5)
    phase = rng.uniform(0.0, 2.0 * np.pi, 4)
    order = np.arange(1, 5)[:, None]

    def waves(u: np.ndarray) -> np.ndarray:
        return (amplitude[:, None] * np.cos(order * u + phase[:, None])).sum(0)

    def dm(u: np.ndarray) -> np.ndarray:
        return -(amplitude[:, None] * order * np.sin(order * u + phase[:, None])).sum(0)

    depth = floor * float(rng.choice([0.2, 0.5, 0.9, 1.5]))
    lift = depth - waves(np.linspace(0.0, 2.0 * np.pi, 100001)).min()
    u = np.linspace(0.0, 2.0 * np.pi, int(rng.integers(5, 60)))
    step = u[1] - u[0]
    margin, rate = lift + waves(u), dm(u) * step
    found = candidate_intervals(margin, rate[:-1], rate[1:], size)
    assert set(found) <= set(_screened(margin, rate, size))
    for k in range(u.size - 1):
        inside = u[k] + step * np.linspace(0.0, 1.0, 401)
        p, q = rate[k], rate[k + 1]
        in_class = np.abs(dm(inside) * step).max() <= max(abs(p), abs(q))
        searched = p < 0.0 <= q or min(margin[k], margin[k + 1]) >= floor
        if (lift + waves(inside)).min() < floor and in_class and searched:
            assert k in found, (k, p, q)


def _unscreened_minima(margin: np.ndarray, size: float) -> np.ndarray:
    """The local minima whose bound m_k - max(m_k-1 - m_k, m_k+1 - m_k) dips below the warning
    margin, sample by sample (what candidate_minima finds, without its quick screen)."""
    m, before, after = margin[1:-1], margin[:-2], margin[2:]
    low = m - np.maximum(before - m, after - m)
    found = (m < before) & (m <= after) & (low < WARNING_MARGIN * size)
    return np.flatnonzero(found) + 1


@pytest.mark.parametrize("slope", [0.5, 1.0, 2.0, 4.0, 1e3])
def test_candidate_screen_never_skips_a_v_shaped_minimum(slope: float) -> None:
    """Every sample 1.5 to 2.5 times the warning margin above zero, the margin V-shaped between
    two samples (a steep slope, coarse samples): the bound says the minimum could dip below the
    threshold, and the quick screen (min(m) - max |dm| clears it) must not skip it."""
    size, w = 2.0, WARNING_MARGIN * 2.0
    k = np.arange(40)
    margin = 1.5 * w + slope * w * np.abs(k - 20.5)
    found = candidate_minima(margin, size)
    assert np.array_equal(found, _unscreened_minima(margin, size))
    assert (found.size > 0) == (1.5 * w + 0.5 * slope * w - slope * w < w)


@pytest.mark.parametrize("seed", range(5))
def test_candidate_screen_agrees_with_the_full_test(seed: int) -> None:
    """Random smooth margins with minima near and far from the threshold: the same candidates
    with and without the quick screen."""
    rng = np.random.default_rng(seed)
    u = np.linspace(0.0, 2.0 * np.pi, int(rng.integers(3, 400)))
    size = float(rng.uniform(0.1, 10.0))
    depth = WARNING_MARGIN * size * float(rng.choice([0.01, 0.5, 1.0, 2.0, 50.0]))
    margin = depth + size * float(rng.uniform(0.0, 0.3)) * (1.0 - np.cos(u - rng.uniform(0, 6)))
    assert np.array_equal(candidate_minima(margin, size), _unscreened_minima(margin, size))

"""Assembly over a cycle (solver.position.assembly, through solver.sweep and solver.analyze): the
assembly changes only at a true bifurcation, the rates of a sweep are those of the closed form,
and every close approach or refusal is found and named after its group.

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

A full-turn sweep's velocities, accelerations and link rates (the sweep trims its extra samples)
are checked against the same Heron closed form (``four_bar_C``) differentiated by central
differences in the crank angle, and a coupler point against the rigid-body rotation of the drawn
one. The closest approach of a group downstream of a group that switches branch at a true change
point (a parallelogram passing its change points, driving a dyad that comes within 2e-4 m of its
own) is evaluated between samples with the upstream group on the branch it has switched to, and
matches the closed form of the parallelogram; refusals (a linkage that cannot close) name the
first group that fails, its links, guide or slot.
"""

from __future__ import annotations

import math
import zlib
from collections.abc import Callable
from typing import Any

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import solver
from solver.analysis.instant import analyze
from solver.analysis.sweeps import Sweep, sweep
from solver.errors import NotAssemblable
from solver.model.scene import LinkageScene, parse_linkage
from solver.position.assembly import (
    WARNING_MARGIN,
    DriverInput,
    Motion,
    assemble,
    candidate_intervals,
    candidate_minima,
    coarse,
    path_steps,
    screen,
)
from solver.position.topology import TwoPointStep, build_plan
from solver.teaching.presets import build_preset
from tests.dynamics_cases import five_bars
from tests.linkage_strategies import linkages

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


# ---- a full-turn sweep's rates; close approaches and refusals named after their group ------------

ALL = ["position", "velocity", "acceleration"]


def _angle(p: np.ndarray) -> np.ndarray:
    return np.unwrap(np.arctan2(p[:, 1], p[:, 0]))


def test_full_turn_sweep_rates_match_the_differentiated_closed_form() -> None:
    """Crank-rocker (g 1, crank 0.4, coupler 0.9, rocker 0.7) driven at omega = 2 rad/s, 90
    samples over a full turn: C's velocity and acceleration are omega dC/dtheta and
    omega^2 d^2C/dtheta^2 of the closed form (central differences, step 1e-4: to 1e-6 m/s and
    1e-5 m/s^2); the rocker's omega and alpha likewise from its angle atan2(C - D); the coupler
    point P turns rigidly with BC (P - B = R(angle BC - angle B0C0)(P0 - B0), to 1e-9 m)."""
    omega = 2.0
    values = {"ground": 1.0, "crank": 0.4, "coupler": 0.9, "rocker": 0.7}
    doc = build_preset("four_bar", {**values, "crank_angle_deg": 30.0, "omega": omega})
    scene = parse_linkage(doc)
    body = solver.sweep(doc, 90, ALL).as_dict()
    assert body["feasible"] and len(body["driver_angle"]) == 90
    theta, h = np.asarray(body["driver_angle"]), 1e-4
    C = four_bar_C(scene, theta)
    ahead, behind = four_bar_C(scene, theta + h), four_bar_C(scene, theta - h)
    got = body["points"]["C"]
    np.testing.assert_allclose(got["position"], C, atol=1e-9)
    np.testing.assert_allclose(got["velocity"], omega * (ahead - behind) / (2 * h), atol=1e-6)
    second = omega**2 * (ahead - 2.0 * C + behind) / h**2
    np.testing.assert_allclose(got["acceleration"], second, atol=1e-5)

    D = np.array(doc["points"]["D"])
    phi = [_angle(X - D) for X in (C, ahead, behind)]
    rocker = body["links"]["rocker"]
    np.testing.assert_allclose(rocker["omega"], omega * (phi[1] - phi[2]) / (2 * h), atol=1e-6)
    alpha = omega**2 * (phi[1] - 2.0 * phi[0] + phi[2]) / h**2
    np.testing.assert_allclose(rocker["alpha"], alpha, atol=1e-5)

    B0, C0, P0 = (np.array(doc["points"][p]) for p in "BCP")
    B = body["points"]["B"]["position"]
    turn = _angle(C - B) - math.atan2(*(C0 - B0)[::-1])
    c, s = np.cos(turn), np.sin(turn)
    r = P0 - B0
    P = B + np.stack((c * r[0] - s * r[1], s * r[0] + c * r[1]), axis=-1)
    np.testing.assert_allclose(body["points"]["P"]["position"], P, atol=1e-9)


def _driving_a_dyad(
    points: dict[str, list[float]],
    pin: str,
    F: np.ndarray,
    radii: tuple[float, float],
    title: str,
) -> dict[str, Any]:
    """The four-bar A-B-C-D (crank AB at 1 rad/s) whose coupler point ``pin`` (C, or a point P
    of the coupler) drives a dyad pin-E-F: |pin E| = r1, |FE| = r2, F on the ground, E drawn on
    the left of pin -> F (the two circles' intersection)."""
    X = np.array(points[pin])
    r1, r2 = radii
    d_vec = F - X
    d = math.hypot(*d_vec)
    a = (r1 * r1 - r2 * r2 + d * d) / (2 * d)
    u = d_vec / d
    E = X + a * u + math.sqrt(r1 * r1 - a * a) * np.array([-u[1], u[0]])
    coupler = ["B", "C"] if pin == "C" else ["B", "C", pin]
    pairs = [("A", "ground", "crank"), ("B", "crank", "coupler"), ("C", "coupler", "rocker"),
             ("D", "rocker", "ground"), (pin, "rocker" if pin == "C" else "coupler", "arm"),
             ("E", "arm", "link"), ("F", "link", "ground")]  # fmt: skip
    return {
        "kind": "linkage",
        "title": title,
        "points": {**points, "E": E.tolist(), "F": F.tolist()},
        "links": {
            "ground": {"points": ["A", "D", "F"], "ground": True},
            "crank": {"points": ["A", "B"]},
            "coupler": {"points": coupler},
            "rocker": {"points": ["D", "C"]},
            "arm": {"points": [pin, "E"]},
            "link": {"points": ["F", "E"]},
        },
        "joints": [{"type": "revolute", "point": p, "links": [a, b]} for p, a, b in pairs],
        "drivers": [{"link": "crank", "omega": 1.0, "alpha": 0.0}],
    }


def _parallelogram_with_dyad(
    start_deg: float, gap: float, far_deg: float = -90.0
) -> dict[str, Any]:
    """Parallelogram A(0,0) B C D(1,0) (crank = rocker = 0.4, coupler = ground = 1), and a dyad
    C-E-F (|CE| = 1, |FE| = 0.9 + gap, F = D - 1.5 (cos f, sin f) on the ground, f = ``far_deg``:
    F = (1, 1.5) by default). On the parallelogram C = D + 0.4 (cos t, sin t), so |CF| is
    largest, |DF| + 0.4 = 1.9, at t = f: the dyad's closest approach is r1 + r2 - 1.9 = gap
    there."""
    t = math.radians(start_deg)
    B = [0.4 * math.cos(t), 0.4 * math.sin(t)]
    C = np.array([B[0] + 1.0, B[1]])
    F = np.array([1.0, 0.0]) - 1.5 * np.array(
        [math.cos(math.radians(far_deg)), math.sin(math.radians(far_deg))]
    )
    return _driving_a_dyad(
        {"A": [0.0, 0.0], "B": B, "C": C.tolist(), "D": [1.0, 0.0]},
        "C", F, (1.0, 0.9 + gap), "parallelogram driving a dyad",
    )  # fmt: skip


@pytest.mark.parametrize("start_deg", [60.0, 200.0])
def test_close_approach_downstream_of_a_switching_parallelogram(start_deg: float) -> None:
    """Swept with 100 samples (3.6 deg apart, none at -90 deg) from 60 deg (the approach comes
    after one switch) and from 200 deg (before any): the parallelogram passes its change points
    at 180 and 360 deg and stays a parallelogram (C = B + (1, 0) to 1e-9 m everywhere); the
    dyad's one close approach, between samples, is gap = 2e-4 m (to 1e-12 m) at crank -90 deg
    (to 1e-6 rad)."""
    gap = 2e-4
    result = sweep(parse_linkage(_parallelogram_with_dyad(start_deg, gap)), 100, ["position"])
    B, C = (result.motion.points[p].p for p in "BC")
    assert np.abs(C - B - np.array([1.0, 0.0])).max() <= 1e-9
    (approach,) = [a for a in result.close_approaches if a.point == "E"]
    assert abs(approach.margin - gap) <= 1e-12
    assert abs(math.remainder(approach.driver_angle + math.pi / 2, 2 * math.pi)) <= 1e-6


def _inverted(crank: float, drawn_deg: float) -> dict[str, Any]:
    values = {"crank": crank, "ground": 1.0, "lever": 1.5, "slot_offset": 0.2}
    return build_preset("inverted_slider_crank", {**values, "crank_angle_deg": drawn_deg})


def _refusal_from(doc: dict[str, Any], angle_deg: float) -> str:
    """The message of the refusal of a 36-sample sweep of ``doc`` started at ``angle_deg``."""
    doc["drivers"][0]["angle_deg"] = angle_deg
    with pytest.raises(NotAssemblable) as error:
        solver.sweep(doc, 36)
    return str(error.value.message)


def test_slotted_lever_that_cannot_close_says_why() -> None:
    """Inverted slider-crank (crank OA 0.9, ground OC 1, slot 0.2 m off the lever's pivot C)
    drawn at 180 deg, swept from 0 deg: there |CA| = 1 - 0.9 = 0.1 m < 0.2 m, so no slot of the
    lever passes through A, and the error says so with the offset."""
    assert _refusal_from(_inverted(0.9, 180.0), 0.0) == (
        "the linkage cannot be closed at the sweep's starting angle: |CA| is shorter than the "
        "offset 0.2 m of the slot of 'lever' from its pivot C"
    )


def test_slotted_lever_touching_within_rounding_at_1000_m_closes() -> None:
    """The inverted slider-crank at 1000 m (ground 1000, slot 200 m off C) with crank
    800 m + 1e-12 m, swept from 0 deg: |CA| - 200 = -1.0e-12 m there, 7e-16 of the linkage's
    size (1500 m), inside the coincidence tolerance (1e-13 of the size): the slot touches A, the
    linkage closes and the sweep is feasible. The margin compared with the tolerance is relative:
    in metres (-1e-12 < -1e-13) it would be refused."""
    s = 1e3
    values = {"crank": 0.8 * s + 1e-15 * s, "ground": s, "lever": 1.5 * s, "slot_offset": 0.2 * s}
    doc = build_preset("inverted_slider_crank", {**values, "crank_angle_deg": 90.0})
    doc["drivers"][0]["angle_deg"] = 0.0
    assert -2e-12 < (s - values["crank"]) - values["slot_offset"] < -1e-13
    assert solver.sweep(doc, 36)["feasible"]


def test_slotted_lever_close_approach_is_named_after_its_slot() -> None:
    """The same linkage with crank 0.8 - 1e-4: |CA| = 1 - crank is least at crank 0 deg, 1e-4 m
    more than the offset: the one close approach is the slot's, margin 1e-4 m (to 1e-12 m) at
    0 deg (to 1e-6 rad)."""
    result = sweep(parse_linkage(_inverted(0.8 - 1e-4, 90.0)), 100, ["position"])
    (approach,) = result.close_approaches
    assert approach.point == "the slot of 'lever'"
    assert approach.margin == pytest.approx((1.0 - (0.8 - 1e-4)) - 0.2, rel=0, abs=1e-12)
    assert math.remainder(approach.driver_angle, 2 * math.pi) == pytest.approx(0.0, abs=1e-6)
    assert abs(approach.margin - 1e-4) <= 1e-12
    assert abs(math.remainder(approach.driver_angle, 2 * math.pi)) <= 1e-6


@pytest.mark.parametrize("end", [4.5, 4.4])
def test_close_approach_of_an_accelerating_crank_found_at_its_angle(end: float) -> None:
    """A sweep over time (37 samples, t = 0 to ``end``) of the crank-rocker 1e-4 inside the
    Grashof equality, the crank accelerating (theta = 30 deg + 0.5 t + 0.4 t^2 / 2, so the
    samples are not evenly spaced in angle; 180 deg falls just before the nearest sample for
    end = 4.5 s, just after it for 4.4 s): between samples the drivers follow each interval's
    own step, and the closest approach, 1e-4 m (to 1e-10 m), is at crank 180 deg (the closed
    form: |BD| is largest there; to 1e-6 rad)."""
    from solver.analysis.sweeps import sweep_time

    values = {"ground": 1.0, "crank": 0.4, "coupler": 0.9, "rocker": 0.5 + 1e-4}
    doc = build_preset("four_bar", {**values, "crank_angle_deg": 30.0, "omega": 0.5})
    doc["drivers"][0]["alpha"] = 0.4
    result = sweep_time(parse_linkage(doc), 0.0, end, 37, ["position"])
    (approach,) = result.close_approaches
    assert abs(approach.margin - 1e-4) <= 1e-10
    assert abs(math.remainder(approach.driver_angle - math.pi, 2 * math.pi)) <= 1e-6


@pytest.mark.parametrize("samples", [2, 3, 4])
def test_close_approach_found_with_the_fewest_samples(samples: int) -> None:
    """The crank-rocker 1e-4 inside the Grashof equality swept with 2, 3 and 4 samples: the
    close approach (1e-4 m, to 1e-12 m, at crank 180 deg, to 1e-6 rad: the closed form) is
    found between them however few they are."""

    result = sweep(parse_linkage(_near_crank_rocker(1e-4)), samples, ["position"])
    (approach,) = result.close_approaches
    assert abs(approach.margin - 1e-4) <= 1e-12
    assert abs(math.remainder(approach.driver_angle - math.pi, 2 * math.pi)) <= 1e-6


def test_newton_group_that_cannot_close_is_refused_with_its_loop() -> None:
    """The triad of test_newton.py (drawn at crank 33.7 deg) rocks between its limit
    positions, 11.3 and 74.8 deg (its sweep's limits): analysed at 120 deg, where Newton-Raphson
    cannot close it, it is refused (never an unconverged answer), naming the loop that failed."""
    from tests.solver.position.test_newton import TRIAD, with_angle

    lower, upper = solver.sweep(TRIAD, 36).as_dict()["limits"]
    assert math.degrees(lower) < 33.7 < math.degrees(upper) < 120.0
    with pytest.raises(NotAssemblable) as error:
        solver.analyze(with_angle(TRIAD, 120.0))
    message = str(error.value.message)
    assert message.startswith("the linkage cannot be closed at crank angle 120 deg: ")
    assert "the loop of T, L1, L2, L3 cannot be closed at crank angle 120 deg" in message


@pytest.mark.parametrize("scale", [1.0, 1000.0, 1e-3])
def test_parallelogram_with_samples_on_its_change_points_at_any_scale(scale: float) -> None:
    """A parallelogram (ground = coupler = s, crank = rocker = 0.4 s) drawn at 60 deg and swept
    with 360 samples: two samples fall on its change points (180 and 360 deg), where the margin
    is rounding noise of either sign. It stays a parallelogram, C = B + (s, 0) to 1e-9 s, at
    s = 1, 1000 and 1e-3 m (the tolerance scales with the size)."""
    values = {"ground": scale, "crank": 0.4 * scale, "coupler": scale, "rocker": 0.4 * scale}
    doc = build_preset("four_bar", {**values, "crank_angle_deg": 60.0, "assembly": 0.0})
    result = sweep(parse_linkage(doc), 360, ["position"])
    B, C = (result.motion.points[p].p for p in "BC")
    assert np.abs(C - B - np.array([scale, 0.0])).max() <= 1e-9 * scale


def test_window_between_samples_where_the_linkage_cannot_close_is_refused() -> None:
    """The crank-rocker 1e-6 outside the Grashof equality (b + c = g + a - 1e-6) swept over
    time, crank at 30 deg + t rad, samples every 0.1 s: every sample closes, but at crank
    180 deg (t = pi - pi/6 = 2.618 s, between samples 26 and 27) |BD| = g + a exceeds b + c by
    1e-6 m (closed form); the sweep is refused with those numbers."""
    from solver.analysis.sweeps import sweep_time

    values = {"ground": 1.0, "crank": 0.4, "coupler": 0.9, "rocker": 0.5 - 1e-6}
    doc = build_preset("four_bar", {**values, "crank_angle_deg": 30.0, "omega": 1.0})
    with pytest.raises(NotAssemblable) as error:
        sweep_time(parse_linkage(doc), 0.0, 4.0, 41, ["position"])
    assert str(error.value.message) == (
        "the linkage cannot be closed during t = 0 .. 4 s: the loci of C fail to meet by "
        "1e-06 m between samples 26 and 27"
    )


def test_four_bar_that_cannot_close_names_its_links() -> None:
    """The crank-rocker with b + c = 1.39 < g + a = 1.4, swept from crank 180 deg, where
    |BD| = g + a = 1.4 m: refused, the message naming the dyad's point C through its links."""
    values = {"ground": 1.0, "crank": 0.4, "coupler": 0.9, "rocker": 0.49}
    doc = build_preset("four_bar", {**values, "crank_angle_deg": 30.0, "omega": 1.0})
    assert _refusal_from(doc, 180.0) == (
        "the linkage cannot be closed at the sweep's starting angle: "
        "|BD| = 1.4 m > |BC| + |DC| = 0.9 + 0.49 = 1.39 m"
    )


def test_slider_crank_closest_approach_in_the_analysis() -> None:
    """In-line slider-crank, rod = crank + 1e-4 = 1.0001 m, analysed at crank 89 deg: its
    circle-line group's margin is rod - |B_y| = 1.0001 - sin 89 deg (closed form, to 1e-12 m),
    reported as the closest approach of C."""
    values = {"crank": 1.0, "rod": 1.0001, "offset": 0.0, "crank_angle_deg": 89.0}
    closest = solver.analyze(build_preset("slider_crank", values)).as_dict()["diagnostics"]
    approach = closest["closest_approach"]
    assert approach["point"] == "C"
    assert abs(approach["margin"] - (1.0001 - math.sin(math.radians(89.0)))) <= 1e-12


def _parallelogram(start_deg: float) -> dict[str, Any]:
    """Parallelogram A(0,0) B C D(1,0), crank = rocker = 0.4, coupler = ground = 1, drawn (and
    swept from) crank ``start_deg``: C = B + (1, 0) there. Its change points are at 0 and
    180 deg, where B, C, A, D line up."""
    t = math.radians(start_deg)
    B = [0.4 * math.cos(t), 0.4 * math.sin(t)]
    doc = build_preset("four_bar", {"ground": 1.0, "crank": 0.4, "coupler": 1.0, "rocker": 0.4})
    doc["points"].update(B=B, C=[B[0] + 1.0, B[1]])
    del doc["points"]["P"]
    doc["links"]["coupler"]["points"] = ["B", "C"]
    doc["drivers"][0]["omega"] = 1.0
    return doc


@pytest.mark.parametrize(("samples", "start_deg"), [(36, 179.0), (360, 179.7), (3600, 179.96)])
def test_parallelogram_started_just_before_its_change_point_stays_one(
    samples: int, start_deg: float
) -> None:
    """The parallelogram drawn and swept from just before its change point at 180 deg (less
    than half a sample step before it: the margin's smallest sample is the first): it must stay
    a parallelogram, C = B + (1, 0) to 1e-9 m at every sample, as it does from any other start
    (test_parallelogram_with_samples_on_its_change_points_at_any_scale). Before the first sample
    was screened (``candidate_minima``) it took the anti-parallelogram after the first sample
    (|C - B - (1, 0)| up to 0.73 m)."""
    result = sweep(parse_linkage(_parallelogram(start_deg)), samples, ["position"])
    B, C = (result.motion.points[p].p for p in "BC")
    assert np.abs(C - B - np.array([1.0, 0.0])).max() <= 1e-9


def test_time_sweep_of_a_parallelogram_started_just_before_its_change_point() -> None:
    """The parallelogram drawn at crank 179 deg, swept over time (omega 1 rad/s, t = 0 .. 1 s,
    11 samples 5.7 deg apart; the change point at 180 deg is nearer the first sample than the
    second): a parallelogram at every sample, C = B + (1, 0) to 1e-9 m (0.51 m off before the
    first sample was screened)."""
    from solver.analysis.sweeps import sweep_time

    result = sweep_time(parse_linkage(_parallelogram(179.0)), 0.0, 1.0, 11, ["position"])
    B, C = (result.motion.points[p].p for p in "BC")
    assert np.abs(C - B - np.array([1.0, 0.0])).max() <= 1e-9


def test_parallelogram_started_just_after_its_change_point_stays_one() -> None:
    """The same parallelogram swept with 36 samples from 181 deg (the change point at 180 deg is
    now in the revolution's last interval, after its last kept sample) and from 90 deg: a
    parallelogram at every sample (C = B + (1, 0) to 1e-9 m)."""
    for start_deg in (181.0, 90.0):
        result = sweep(parse_linkage(_parallelogram(start_deg)), 36, ["position"])
        B, C = (result.motion.points[p].p for p in "BC")
        assert np.abs(C - B - np.array([1.0, 0.0])).max() <= 1e-9


@pytest.mark.parametrize("start_deg", [179.0, 181.0])
def test_close_approach_next_to_the_first_sample_is_reported(start_deg: float) -> None:
    """The crank-rocker 1e-4 inside the Grashof equality drawn and swept (36 samples) from 1 deg
    before or after its closest approach at 180 deg: the approach, 1e-4 m at 180 deg (closed
    form), must be reported as it is from 30 deg (test_close_approach_found_with_the_fewest_
    samples). Before the first and last samples were screened the sweep reported none."""

    result = sweep(parse_linkage(_near_crank_rocker(1e-4, start_deg)), 36, ["position"])
    (approach,) = result.close_approaches
    assert abs(approach.margin - 1e-4) <= 1e-12
    assert abs(math.remainder(approach.driver_angle - math.pi, 2 * math.pi)) <= 1e-6


# A crank-rocker (ground 1, crank 0.487, coupler 1.155, rocker 0.682) whose coupler point P
# (1.879 along BC, 0.165 to its left, from B) drives a dyad P-E-F, F = (-2.32, -2.595) on the
# ground: |PF| has two local maxima 37 deg apart (crank 30.3 and 353.3 deg), so the dyad's margin
# r1 + r2 - |PF| dips twice within two samples of a coarse sweep.
_DIPS = {"a": 0.487, "b": 1.155, "c": 0.682, "P": (1.879, 0.165), "F": (-2.32, -2.595)}


def _coupler_point(theta: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """B, C, P of the _DIPS four-bar at crank angles ``theta`` (C left of B -> D: Heron)."""
    a, b, c = _DIPS["a"], _DIPS["b"], _DIPS["c"]
    B = a * np.stack((np.cos(theta), np.sin(theta)), axis=-1)
    e = np.array([1.0, 0.0]) - B
    d = np.hypot(*e.T)
    along = (d * d + b * b - c * c) / (2.0 * d)
    h = np.sqrt((b + c + d) * (b + c - d) * (d + b - c) * (d - b + c)) / (2.0 * d)
    u = e / d[:, None]
    left = np.stack((-u[:, 1], u[:, 0]), axis=-1)
    C = B + along[:, None] * u + h[:, None] * left
    w = (C - B) / b
    along_p, left_p = _DIPS["P"]
    P = B + along_p * w + left_p * np.stack((-w[:, 1], w[:, 0]), axis=-1)
    return B, C, P


def _farthest() -> tuple[float, float]:
    """(crank angle, |PF|) where the coupler point is farthest from F: the closed form on a
    0.1 deg grid, then the root of d|PF|^2/dtheta (central differences, step 1e-5 rad) by
    Brent's method within a grid step (to about 1e-9 rad)."""
    from scipy.optimize import brentq

    def squared(t: float) -> float:
        gap = _coupler_point(np.array([t]))[2][0] - _DIPS["F"]
        return float(gap @ gap)

    def slope(t: float) -> float:
        return (squared(t + 1e-5) - squared(t - 1e-5)) / 2e-5

    grid = np.linspace(0.0, 2.0 * math.pi, 3601)
    k = int(np.argmax(np.hypot(*(_coupler_point(grid)[2] - _DIPS["F"]).T)))
    at = float(brentq(slope, grid[k - 1], grid[k + 1], xtol=1e-14))
    return at, math.sqrt(squared(at))


def _two_dips(gap: float, start_deg: float) -> dict[str, Any]:
    """The _DIPS six-bar drawn at crank ``start_deg``, r1 = r2 = (max |PF| + gap) / 2."""
    B, C, P = (x[0] for x in _coupler_point(np.array([math.radians(start_deg)])))
    r = 0.5 * (_farthest()[1] + gap)
    return _driving_a_dyad(
        {"A": [0.0, 0.0], "B": B.tolist(), "C": C.tolist(), "D": [1.0, 0.0], "P": P.tolist()},
        "P", np.array(_DIPS["F"]), (r, r), "a coupler point driving a dyad",
    )  # fmt: skip


def _deepest_dip_reported(samples: int, start_deg: float) -> None:
    """Swept from crank ``start_deg`` with ``samples`` samples, the one close approach is the
    deeper dip of E's margin: 1e-4 m (to 1e-14 m) where |PF| is largest (353.3 deg; to
    5e-8 rad: a minimum's place is known to about the square root of rounding)."""
    at, _ = _farthest()
    result = sweep(parse_linkage(_two_dips(1e-4, start_deg)), samples, ["position"])
    (approach,) = result.close_approaches
    assert approach.point == "E"
    assert abs(approach.margin - 1e-4) <= 1e-14
    assert abs(math.remainder(approach.driver_angle - at, 2 * math.pi)) <= 5e-8


def test_deeper_of_two_dips_is_reported() -> None:
    """36 samples (10 deg apart): the two dips of the margin (30.3 and 353.3 deg) are sampled
    minima of their own, and the deeper one, 1e-4 m, is the close approach reported."""
    _deepest_dip_reported(36, 104.0)


@pytest.mark.parametrize(
    ("samples", "start_deg"),
    [(15, 104.0), (15, 345.0), (8, 45.0), (9, 165.0), (11, 180.0), (12, 345.0), (13, 60.0),
     (18, 105.0), (9, 30.0), (16, 15.0)],
)  # fmt: skip
def test_deeper_of_two_dips_between_two_coarse_samples_is_reported(
    samples: int, start_deg: float
) -> None:
    """Both dips (37 deg apart) between two or three coarse samples, e.g. 15 samples 24 deg
    apart from 104 deg (344, 8 and 32 deg among them): the one sampled minimum, at 8 deg, lies
    near the maximum that parts the dips, so its neighbours' values alone do not say that the
    margin may dip below the threshold; the rates do (at 344 deg the margin falls at 0.18 m a
    step, into the interval that holds the deeper dip). The deeper, 1e-4 m at 353.3 deg, must
    be the approach reported, as with 36 samples (each of the first eight sweeps reported none,
    or the shallower dip, before the screen took the rates). With 9 samples from 30 deg the
    sample at 350 deg is 0.004 m, below the threshold, and the margin falls at both ends of the
    interval after it (into the shallow dip at 30.3 deg): no turn there, so the sampled minimum's
    intervals are searched by minimisation; with 16 from 15 deg the sample at 352.5 deg is
    0.0003 m and the margin rises steeply between it and the next, steeper than at either."""
    _deepest_dip_reported(samples, start_deg)


def test_dip_where_the_margin_falls_at_both_neighbours_is_found() -> None:
    """12 samples (30 deg apart) from 90 deg: the sampled minimum is at 0 deg, its neighbours at
    330 and 30 deg; the margin still falls at 30 deg (towards its second dip at 30.3 deg). The
    approach is the deeper dip (to 1e-14 m and 5e-8 rad)."""
    _deepest_dip_reported(12, 90.0)


@pytest.mark.parametrize(("samples", "start_deg"), [(15, 104.0), (11, 180.0), (12, 345.0)])
def test_change_point_next_to_a_second_dip_between_coarse_samples(
    samples: int, start_deg: float
) -> None:
    """The two-dip six-bar with r1 + r2 = max |PF| exactly (to rounding): the deeper dip is a
    change point, where E's two circles touch at 353.3 deg, and it lies between two coarse
    samples next to the shallow dip (30.3 deg, 0.033 m). The sweep must switch E's branch
    there, as a parallelogram does at its change points: E on the drawn side of P -> F (left)
    up to 353.3 deg and on the right after it, E = (P + F) / 2 + s sqrt(r^2 - |PF|^2 / 4) n
    with n the left normal of P -> F (closed form of P: Heron and the rigid coupler), to 1e-9 m
    at every sample; no close approach to warn about (the branches meet)."""
    at, _ = _farthest()
    doc = _two_dips(0.0, start_deg)
    result = sweep(parse_linkage(doc), samples, ["position"])
    theta = np.asarray(result.driver_angle)
    P = _coupler_point(theta)[2]
    to_F = np.array(_DIPS["F"]) - P
    d = np.hypot(*to_F.T)
    r = math.dist(doc["points"]["E"], doc["points"]["F"])
    passed = np.remainder(theta - theta[0], 2 * math.pi) > np.remainder(at - theta[0], 2 * math.pi)
    side = np.where(passed, -1.0, 1.0) * np.sqrt(r * r - d * d / 4.0) / d
    E = P + to_F / 2.0 + side[:, None] * np.stack((-to_F[:, 1], to_F[:, 0]), axis=-1)
    assert np.abs(result.motion.points["E"].p - E).max() <= 1e-9
    assert result.close_approaches == ()


def test_slider_crank_that_cannot_close_names_its_guide() -> None:
    """Offset slider-crank (crank 1, rod 1.5, guide y = 0.8 m in the ground) swept from crank
    -90 deg: B = (0, -1) lies 1.8 m from the guide, farther than the rod, 1.5 m: refused, the
    message naming the slot's link (hand values)."""
    values = {"crank": 1.0, "rod": 1.5, "offset": 0.8, "crank_angle_deg": 90.0}
    assert _refusal_from(build_preset("slider_crank", values), -90.0) == (
        "the linkage cannot be closed at the sweep's starting angle: the distance from B to "
        "the slot of C in 'ground' is 1.8 m > |BC| = 1.5 m"
    )


def test_time_sweep_of_a_parallelogram_past_its_change_point_after_the_first_sample() -> None:
    """The parallelogram drawn at crank 173 deg, swept over time (omega 1 rad/s, 37 samples over
    t = 0 .. 2 pi s, 10 deg apart): its change points at 180 and 360 deg lie 7 and 3 deg before
    samples 1 and 19. The drawn branch holds at the first sample, and the parallelogram stays
    one at every sample: C = B + (1, 0) to 1e-9 m."""
    from solver.analysis.sweeps import sweep_time

    result = sweep_time(parse_linkage(_parallelogram(173.0)), 0.0, 2 * math.pi, 37, ["position"])
    B, C = (result.motion.points[p].p for p in "BC")
    assert np.abs(C - B - np.array([1.0, 0.0])).max() <= 1e-9


@pytest.mark.parametrize("tolerance", [1e-6, 1e-15])
def test_newton_tolerance_asked_for_is_the_one_applied(tolerance: float) -> None:
    """The triad of test_newton.py swept (36 samples), and swept over time
    (t = 0 .. 0.1 s: crank 33.7 to 45.5 deg), with a Newton tolerance of 1e-6 and of 1e-15
    (the bounds): every Newton report states that relative tolerance, the absolute one
    tolerance * size, and a residual within it."""
    from solver.analysis.sweeps import sweep_time
    from tests.solver.position.test_newton import TRIAD

    scene = parse_linkage(TRIAD)
    swept = sweep(scene, 36, ["position"], tolerance).motion.newton
    timed = sweep_time(scene, 0.0, 0.1, 5, ["position"], tolerance).motion.newton
    assert swept and timed
    for report in swept + timed:
        assert report.relative_tolerance == tolerance
        assert report.tolerance == pytest.approx(tolerance * scene.size, rel=1e-12)
        assert report.residual_norm <= report.tolerance


def test_structure_without_drivers_is_analysed_at_its_drawn_pose() -> None:
    """A triangle truss (A(0,0), D(1,0) on the ground, E(0.3, 0.4) on two links, no degree of
    freedom, no driver): analysed at its drawn pose, at rest; the dyad's margin is
    |AE| + |DE| - |AD| = 0.5 + sqrt(0.65) - 1 (Pythagoras; to 1e-15 m)."""
    doc = {
        "kind": "linkage",
        "title": "truss",
        "points": {"A": [0.0, 0.0], "D": [1.0, 0.0], "E": [0.3, 0.4]},
        "links": {
            "ground": {"points": ["A", "D"], "ground": True},
            "l1": {"points": ["A", "E"]},
            "l2": {"points": ["D", "E"]},
        },
        "joints": [
            {"type": "revolute", "point": "A", "links": ["ground", "l1"]},
            {"type": "revolute", "point": "D", "links": ["ground", "l2"]},
            {"type": "revolute", "point": "E", "links": ["l1", "l2"]},
        ],
        "drivers": [],
    }
    body = solver.analyze(doc).as_dict()
    E = body["points"]["E"]
    assert E["position"] == pytest.approx([0.3, 0.4], abs=1e-15)
    assert E["velocity"] == [0.0, 0.0] and E["acceleration"] == [0.0, 0.0]
    approach = body["diagnostics"]["closest_approach"]
    assert approach["point"] == "E"
    assert abs(approach["margin"] - (0.5 + math.sqrt(0.65) - 1.0)) <= 1e-15


def test_full_turn_sweep_of_a_newton_group_keeps_its_report() -> None:
    """The triad of test_newton.py with its crank cut to |OA| = 0.018 m (A at
    (0.015, 0.01)) turns fully: swept with 36 samples, every sample closes the loop (each link's
    length and the ternary link's sides as drawn, to 1e-12 m: the constraints themselves), and
    the diagnostics keep the triad's Newton report, its residual within its tolerance."""
    from tests.solver.position.test_newton import TRIAD

    doc = {**TRIAD, "points": {**TRIAD["points"], "A": [0.015, 0.01]}}
    body = solver.sweep(doc, 36).as_dict()
    assert body["feasible"] and len(body["driver_angle"]) == 36
    xy = {p: np.asarray(body["points"][p]["position"]) for p in doc["points"]}
    for first, second in ("OA", ("A", "P1"), ("G2", "P2"), ("G3", "P3"), ("P1", "P2"),
                          ("P2", "P3"), ("P1", "P3")):  # fmt: skip
        drawn = math.dist(doc["points"][first], doc["points"][second])
        assert np.abs(np.hypot(*(xy[first] - xy[second]).T) - drawn).max() <= 1e-12
    (report,) = body["diagnostics"]["newton"]
    assert report["links"] == ["T", "L1", "L2", "L3"]
    assert report["residual_norm"] <= report["tolerance"]


def _circle_point(P: list[float], Q: list[float], r1: float, r2: float) -> list[float]:
    """The point X with |XP| = r1, |XQ| = r2 to the left of P -> Q."""
    p, q = np.array(P), np.array(Q)
    d = math.dist(P, Q)
    u = (q - p) / d
    along = (r1 * r1 - r2 * r2 + d * d) / (2.0 * d)
    return (p + along * u + math.sqrt(r1 * r1 - along * along) * np.array([-u[1], u[0]])).tolist()


def _crank_with_two_dyads(rocker: float = 0.5) -> dict[str, Any]:
    """Crank A(0,0)-B (0.4, drawn at 60 deg) driving two dyads: B-C-D (|BC| 0.8, |DC| =
    ``rocker``, D = (1, 0)) and B-E-G (|BE| 0.7, |GE| 0.6, G = (0.8, -0.6)). With rocker 0.5
    the first cannot close where |BD| > 1.3 (crank beyond 131.5 deg); the second cannot where
    |BG| > 1.3 (crank 94.6 to 191.6 deg)."""
    t = math.radians(60.0)
    B = [0.4 * math.cos(t), 0.4 * math.sin(t)]
    revolute = [("A", "ground", "crank"), ("B", "crank", "coupler"), ("C", "coupler", "rocker"),
                ("D", "rocker", "ground"), ("B", "crank", "arm"), ("E", "arm", "link"),
                ("G", "link", "ground")]  # fmt: skip
    return {
        "kind": "linkage",
        "title": "a crank driving two dyads",
        "points": {
            "A": [0.0, 0.0],
            "B": B,
            "C": _circle_point(B, [1.0, 0.0], 0.8, rocker),
            "D": [1.0, 0.0],
            "E": _circle_point([0.8, -0.6], B, 0.6, 0.7),
            "G": [0.8, -0.6],
        },
        "links": {
            "ground": {"points": ["A", "D", "G"], "ground": True},
            "crank": {"points": ["A", "B"]},
            "coupler": {"points": ["B", "C"]},
            "rocker": {"points": ["D", "C"]},
            "arm": {"points": ["B", "E"]},
            "link": {"points": ["G", "E"]},
        },
        "joints": [{"type": "revolute", "point": p, "links": [a, b]} for p, a, b in revolute],
        "drivers": [{"link": "crank", "omega": 1.0, "alpha": 0.0}],
    }


def _crank_point(degrees: float | np.ndarray) -> np.ndarray:
    t = np.radians(degrees)
    return 0.4 * np.stack((np.cos(t), np.sin(t)), axis=-1)


def test_two_groups_failing_at_one_pose_name_the_first() -> None:
    """The crank with two dyads analysed at crank 160 deg, where neither closes: refused with
    the first group's numbers only (|BD| from B = 0.4 (cos 160, sin 160) deg; the group after
    one that failed is not blamed)."""
    doc = _crank_with_two_dyads()
    doc["drivers"][0]["angle_deg"] = 160.0
    with pytest.raises(NotAssemblable) as error:
        solver.analyze(doc)
    BD = math.dist(_crank_point(160.0), (1.0, 0.0))
    assert str(error.value.message) == (
        f"the linkage cannot be closed at crank angle 160 deg: |BD| = {BD:.6g} m > "
        "|BC| + |DC| = 0.8 + 0.5 = 1.3 m"
    )


def test_two_groups_failing_at_different_samples_are_both_named() -> None:
    """The crank with two dyads swept over time, crank 60 deg + t rad, t = 0 .. 1.5 s in 16
    samples: B-C-D fails from 131.5 deg on, B-E-G from 94.6 deg on, where B-C-D still closes:
    both are named, each at its worst sample (|BD| and |BG| from the closed form of B)."""
    from solver.analysis.sweeps import sweep_time

    with pytest.raises(NotAssemblable) as error:
        sweep_time(parse_linkage(_crank_with_two_dyads()), 0.0, 1.5, 16, ["position"])
    B = _crank_point(60.0 + np.degrees(np.linspace(0.0, 1.5, 16)))
    BD = np.hypot(*(B - (1.0, 0.0)).T).max()
    BG = np.hypot(*(B - (0.8, -0.6)).T).max()
    assert str(error.value.message) == (
        f"the linkage cannot be closed during t = 0 .. 1.5 s: |BD| = {BD:.6g} m > |BC| + |DC| = "
        f"0.8 + 0.5 = 1.3 m; |BG| = {BG:.6g} m > |BE| + |GE| = 0.7 + 0.6 = 1.3 m"
    )


def test_newton_group_after_a_failing_dyad_is_not_blamed() -> None:
    """The triad of test_newton.py with a dyad A-E-G on its crank (|AE| 0.9,
    |GE| 0.87, G = (-1, -1)), which cannot close at crank 45 deg: |AG| = 1.77477 > 1.77 m (A at
    |OA| = sqrt 0.13 m, 45 deg). The dyad is solved first; the triad, which cannot follow its
    branch past the dyad's limit either, is not named."""
    from tests.solver.position.test_newton import TRIAD, with_angle

    doc = {
        **TRIAD,
        "points": {**TRIAD["points"], "G": [-1.0, -1.0]},
        "links": {
            **TRIAD["links"],
            "ground": {"points": ["O", "G2", "G3", "G"], "ground": True},
            "arm": {"points": ["A", "E"]},
            "link": {"points": ["G", "E"]},
        },
        "joints": TRIAD["joints"]
        + [
            {"type": "revolute", "point": "A", "links": ["crank", "arm"]},
            {"type": "revolute", "point": "E", "links": ["arm", "link"]},
            {"type": "revolute", "point": "G", "links": ["link", "ground"]},
        ],
    }
    doc["points"]["E"] = _circle_point([0.3, 0.2], [-1.0, -1.0], 0.9, 0.87)
    with pytest.raises(NotAssemblable) as error:
        solver.analyze(with_angle(doc, 45.0))
    A = math.sqrt(0.13) * np.array([math.cos(math.pi / 4), math.sin(math.pi / 4)])
    AG = math.dist(A, (-1.0, -1.0))
    assert str(error.value.message) == (
        f"the linkage cannot be closed at crank angle 45 deg: |AG| = {AG:.6g} m > "
        "|AE| + |GE| = 0.9 + 0.87 = 1.77 m"
    )


def test_group_at_its_dead_centre_is_not_blamed_for_the_next() -> None:
    """The crank with two dyads, rocker 0.6 (|BC| + |DC| = 1.4 = |AD| + |AB|), analysed at
    crank 180 deg: B-C-D is at its dead centre there (margin 0 to rounding: it closes), B-E-G
    cannot close, |BG| = sqrt(1.2^2 + 0.6^2) = 1.34164 > 1.3 m: refused naming B-E-G only."""
    doc = _crank_with_two_dyads(rocker=0.6)
    doc["drivers"][0]["angle_deg"] = 180.0
    with pytest.raises(NotAssemblable) as error:
        solver.analyze(doc)
    assert str(error.value.message) == (
        f"the linkage cannot be closed at crank angle 180 deg: |BG| = {math.sqrt(1.8):.6g} m > "
        "|BE| + |GE| = 0.7 + 0.6 = 1.3 m"
    )


def test_close_approach_just_after_an_upstream_switch() -> None:
    """The parallelogram driving a dyad, F = D - 1.5 (cos 182, sin 182 deg), so that |CF| is
    largest, |DF| + 0.4 = 1.9, at crank 182 deg, 2 deg after the parallelogram's change point;
    swept with 36 samples from 58 deg (samples at 178 and 188 deg). Between samples the
    parallelogram is taken on the branch it has switched to at 180 deg: the approach is
    gap = 2e-4 m (to 1e-12 m) at 182 deg (to 1e-6 rad), and C = B + (1, 0) throughout."""
    gap = 2e-4
    result = sweep(parse_linkage(_parallelogram_with_dyad(58.0, gap, 182.0)), 36, ["position"])
    B, C = (result.motion.points[p].p for p in "BC")
    assert np.abs(C - B - np.array([1.0, 0.0])).max() <= 1e-9
    (approach,) = [a for a in result.close_approaches if a.point == "E"]
    assert abs(approach.margin - gap) <= 1e-12
    assert abs(math.remainder(approach.driver_angle - math.radians(182.0), 2 * math.pi)) <= 1e-6


def _quick_return_with_a_block() -> dict[str, Any]:
    """The quick_return preset with its slider at C (a pin in a ground slot) replaced by a block
    that carries C only, in a prismatic joint with the ground (a link guided by the ground)."""
    doc = build_preset("quick_return", {})
    slider = next(j for j in doc["joints"] if j["type"] == "slider" and j["point"] == "C")
    guide, follower = slider["links"]
    doc["links"]["block"] = {"points": ["C"]}
    doc["joints"].remove(slider)
    doc["joints"] += [
        {"type": "revolute", "point": "C", "links": [follower, "block"]},
        {**slider, "type": "prismatic", "links": [guide, "block"]},
    ]
    return doc


@pytest.mark.parametrize("case", ["six-bar", "quick return", "quick return with a block"])
def test_position_sweep_whose_screen_took_velocities_returns_positions_only(case: str) -> None:
    """A position-only sweep of a linkage with a group on moving centres (a six-bar's second
    dyad, the quick return's slider on its lever) computes velocities at unit crank rate for
    the screen (``_Assembler.positions_only``): it must return what a run at order 0 gives,
    array for array (the ground's, its points' and a driver's pivot's zero rates kept, a link
    guided by the ground keeping the ground's; every other rate None), here the same assembly
    without continuation (the branches stay as drawn)."""
    doc = {
        "six-bar": _two_dips(0.2, 30.0),
        "quick return": build_preset("quick_return", {}),
        "quick return with a block": _quick_return_with_a_block(),
    }[case]
    scene = parse_linkage(doc)
    plan = build_plan(scene)
    theta = np.linspace(0.0, 2.0 * math.pi, 37)
    inputs = [DriverInput(theta, np.full(37, 2.0), np.zeros(37))]
    screened = assemble(scene, plan, inputs, 0, continuation=True)
    plain = assemble(scene, plan, inputs, 0)
    assert not screened.approaches or all(a.margin > 0.0 for a in screened.approaches)
    ours, theirs = arrays(screened), arrays(plain)
    assert list(ours) == list(theirs)
    for key, value in theirs.items():
        if value is None:
            assert ours[key] is None, key
        else:
            assert np.array_equal(ours[key], value), key


def _at_rest(doc: dict[str, Any]) -> dict[str, Any]:
    """The same linkage with its driver at rest (omega 0): a sweep's velocities are all 0, so
    the screen's rates come from a run at unit crank rate (``_Assembler.sensitivities``)."""
    return {**doc, "drivers": [{**doc["drivers"][0], "omega": 0.0}]}


def test_two_dips_with_the_crank_at_rest_are_screened_at_unit_rate() -> None:
    """The two-dip six-bar swept with 15 samples from 104 deg, velocities asked for with the
    crank at rest: the dip between the coarse samples is found from rates at unit crank rate
    (the velocities of the sweep, all 0, say nothing), the same approach as with the crank
    turning: 1e-4 m (to 1e-14 m) at 353.3 deg (to 5e-8 rad)."""
    at, _ = _farthest()
    doc = _at_rest(_two_dips(1e-4, 104.0))
    (approach,) = sweep(parse_linkage(doc), 15, ALL).close_approaches
    assert approach.point == "E" and abs(approach.margin - 1e-4) <= 1e-14
    assert abs(math.remainder(approach.driver_angle - at, 2 * math.pi)) <= 5e-8


def test_close_approach_past_a_switch_with_the_crank_at_rest() -> None:
    """The parallelogram driving a dyad (test_close_approach_downstream_of_a_switching_
    parallelogram), crank at rest, swept with 100 samples from 60 deg with velocities: the
    dyad's rates at unit crank rate are taken on the branches the sweep follows (the
    parallelogram switched at 180 deg): the approach is gap = 2e-4 m (to 1e-12 m) at -90 deg
    (to 1e-6 rad), and C = B + (1, 0) throughout (to 1e-9 m)."""
    result = sweep(parse_linkage(_at_rest(_parallelogram_with_dyad(60.0, 2e-4))), 100, ALL)
    B, C = (result.motion.points[p].p for p in "BC")
    assert np.abs(C - B - np.array([1.0, 0.0])).max() <= 1e-9
    (approach,) = result.close_approaches
    assert approach.point == "E" and abs(approach.margin - 2e-4) <= 1e-12
    assert abs(math.remainder(approach.driver_angle + math.pi / 2, 2 * math.pi)) <= 1e-6


@pytest.mark.parametrize("omega", [10.0, 0.0])
def test_lever_close_approach_ahead_of_a_dyad(omega: float) -> None:
    """Quick return (ground O2O4 0.3 m, slot 0.05 m off the lever's pivot O4, crank 0.25 - 1e-4
    m; rod 0.8 m to a ram at 0.4 m so that it turns fully), its crank turning or at rest: the
    lever's margin |O4A| - 0.05 is least with A straight below O2, 0.3 - crank - 0.05 = 1e-4 m
    (to 1e-12 m) at crank -90 deg (to 1e-6 rad, closed form), and it is that group's own margin
    and rate that are screened and searched there, not those of the ram's dyad solved after the
    lever (with the crank at rest its rates come from a run at unit crank rate)."""
    values = {"crank": 0.25 - 1e-4, "ground": 0.3, "slot_offset": 0.05, "rod": 0.8}
    doc = build_preset("quick_return", {**values, "ram_height": 0.4, "lever": 0.6})
    doc["drivers"][0]["omega"] = omega
    (approach,) = sweep(parse_linkage(doc), 36, ALL).close_approaches
    assert approach.point == "the slot of 'lever'"
    assert abs(approach.margin - (0.3 - (0.25 - 1e-4) - 0.05)) <= 1e-12
    assert abs(math.remainder(approach.driver_angle + math.pi / 2, 2 * math.pi)) <= 1e-6


def test_instant_centres_of_a_triad_at_rest() -> None:
    """The triad of test_newton.py with its crank at rest, analysed with poles: the
    instant centres are those of the pose differentiated at unit crank rate (a Newton group
    assembled without the caller's Continuation, which makes its own); each link turning about
    a ground pivot has its centre with the ground there: O, G2, G3 (to 1e-12 m)."""
    from tests.solver.position.test_newton import TRIAD

    body = solver.analyze(_at_rest(TRIAD), ["position", "poles"]).as_dict()
    centres = {frozenset(c["links"]): c["position"] for c in body["instant_centres"]}
    for link, pivot in (("crank", "O"), ("L2", "G2"), ("L3", "G3")):
        position = centres[frozenset((link, "ground"))]
        assert math.dist(position, TRIAD["points"][pivot]) <= 1e-12, link


def _folded_gap(doc: dict[str, Any]) -> float:
    """A four-bar's dyad margin d - |r1 - r2| at its least, with B on AD:
    (|AD| - |AB|) - (|BC| - |CD|), in the drawn lengths (the solver's)."""
    A, B, C, D = (np.array(doc["points"][p]) for p in "ABCD")
    return float(
        (np.linalg.norm(D - A) - np.linalg.norm(B - A))
        - (np.linalg.norm(C - B) - np.linalg.norm(D - C))
    )


@pytest.mark.parametrize("samples", [36, 360])
def test_a_piece_that_turns_above_the_other_is_no_approach(samples: int) -> None:
    """Four-bar ground 1000, crank 0.1, coupler 1000.2, rocker 0.5 m: |BD| = d runs over
    [999.9, 1000.1], so the dyad's two pieces are r1 + r2 - d in [0.6, 0.8] and
    d - |r1 - r2| = d - 999.7 in [0.2, 0.4], both under 1e-3 of the size (1000.3 m). The first
    turns (its minimum, 0.6 m, at crank 180 deg) where the second, 0.4 m, is the margin: no
    minimum of the margin there. The one approach is the second piece's, d_min - 999.7 = 0.2 m
    at crank 0 deg (closed form in the drawn lengths, which the preset's rounding puts 1e-10 m
    off the nominal ones: 1e-11 m; 1e-6 rad)."""
    doc = build_preset("four_bar", {"ground": 1e3, "crank": 0.1, "coupler": 1000.2, "rocker": 0.5})
    gap = _folded_gap(doc)
    assert abs(gap - 0.2) <= 1e-9
    (approach,) = sweep(parse_linkage(doc), samples, ["position"]).close_approaches
    assert approach.point == "C"
    assert abs(approach.margin - gap) <= 1e-11
    assert abs(math.remainder(approach.driver_angle, 2 * math.pi)) <= 1e-6


def _near_a_change_point(drawn_deg: float = 0.0) -> tuple[dict[str, Any], float]:
    """Four-bar ground 25, crank 10, coupler 30, rocker 15.01 m, drawn with the crank at
    ``drawn_deg``: |BD| is least, 15 m, with the crank at 0 deg, where the dyad's margin
    d - |r1 - r2| is least, 0.01 m (under 1e-3 of the size, 0.033 m). Returns the scene and that
    gap in its drawn lengths."""
    values = {"ground": 25.0, "crank": 10.0, "coupler": 30.0, "rocker": 15.01}
    doc = build_preset("four_bar", {**values, "crank_angle_deg": drawn_deg})
    gap = _folded_gap(doc)
    assert abs(gap - 0.01) <= 1e-12
    return doc, gap


@pytest.mark.parametrize(("samples", "omega"), [(36, 1.0), (90, 1.0), (360, 1.0), (360, -1.0)])
def test_a_linkage_drawn_at_its_closest_approach_is_warned_of_it(
    samples: int, omega: float
) -> None:
    """The four-bar ``_near_a_change_point`` drawn at its closest approach, swept a revolution
    either way: the approach is on the first sample (and on the closing one, the same pose),
    where the margin's rate is 0 at one copy and -2e-16 at the other, so neither interval beside
    it turns. It is warned of once, at 0 deg, with the gap in the drawn lengths (1e-12 m)."""
    doc, gap = _near_a_change_point()
    doc["drivers"][0]["omega"] = omega
    result = solver.sweep(doc, samples)
    (approach,) = result["diagnostics"]["close_approaches"]
    assert approach["point"] == "C"
    assert abs(approach["margin"] - gap) <= 1e-12
    assert abs(math.remainder(approach["driver_angle"], 2 * math.pi)) <= 1e-9
    assert len(result["warnings"]) == 1


@pytest.mark.parametrize(
    ("span", "samples", "at"),
    [
        ((0.0, math.pi), 19, [0.0]),
        ((-math.pi, 0.0), 17, [0.0]),
        ((-math.pi, 0.0), 3, [0.0]),  # steps of pi / 2: followed on a dense grid
        ((0.0, 2 * math.pi), 361, [0, 360]),
    ],
)
def test_a_time_sweep_from_or_to_the_closest_approach_is_warned_of_it(
    span: tuple[float, float], samples: int, at: list[float]
) -> None:
    """The same four-bar, crank angle = t rad: a time sweep starting or ending at the closest
    approach warns of it there (at its first or last sample, also where the steps are long
    enough to be followed on a dense grid); one over [0, 2 pi] passes it twice, at t = 0 and
    2 pi (0 and 360 deg), and warns of both."""
    doc, gap = _near_a_change_point()
    doc["drivers"] = [{"link": "crank", "angle_law": "t"}]
    found = solver.sweep_time(doc, list(span), samples)["diagnostics"]["close_approaches"]
    assert [a["driver_angle_deg"] for a in found] == pytest.approx(at, abs=1e-9)
    assert all(abs(a["margin"] - gap) <= 1e-12 for a in found)


def test_a_near_miss_between_samples_20_deg_apart_is_not_cleared_by_the_lipschitz_bound() -> None:
    """The four-bar ``_near_a_change_point`` drawn at 10 deg, crank angle = t rad over a turn
    in 18 steps of 20 deg: the samples beside the approach (crank at 0 deg) are at +-10 deg,
    where the margin is |BD| - 14.99 = sqrt(725 - 500 cos 10 deg) - 14.99 = 0.261 m. The
    group's Lipschitz bound G = |AB| x 20 deg = 3.49 m does not clear the threshold
    (0.261 - G / 2 < 0.033 m), so the interval is searched and the approach found: 0.01 m (the
    gap in the drawn lengths, 1e-12 m) at 0 deg (1e-9 rad)."""
    doc, gap = _near_a_change_point(10.0)
    doc["drivers"] = [{"link": "crank", "angle_law": "t"}]
    result = solver.sweep_time(doc, [0.0, 2 * math.pi], 19)
    (approach,) = result["diagnostics"]["close_approaches"]
    assert abs(approach["margin"] - gap) <= 1e-12
    assert abs(math.remainder(approach["driver_angle"], 2 * math.pi)) <= 1e-9


# The one executor: the same numbers whatever a run is asked for (issue 22: the compiled clone of
# the closed-form path is gone; these are the guarantees its bit-for-bit test held).


def arrays(motion: Motion) -> dict[str, Any]:
    """Every array of a motion by a path name (None where not computed)."""
    out: dict[str, Any] = {
        "margin": motion.margin,
        "converged": motion.converged,
        "gradient_sine": motion.gradient_sine,
    }
    for name, p in motion.points.items():
        out |= {f"{name}.p": p.p, f"{name}.v": p.v, f"{name}.a": p.a}
    for name, link in motion.links.items():
        out |= {
            f"{name}.anchor0": link.anchor0,
            f"{name}.anchor.p": link.anchor.p,
            f"{name}.anchor.v": link.anchor.v,
            f"{name}.anchor.a": link.anchor.a,
            f"{name}.theta": link.theta,
            f"{name}.omega": link.omega,
            f"{name}.alpha": link.alpha,
        }
    out |= {f"margin of {k}": m for k, m in motion.group_margins.items()}
    return out


def assert_same_bits(ours: dict[str, Any], theirs: dict[str, Any]) -> None:
    """The same arrays, compared as bytes (a last-bit difference or a -0.0 for a 0.0 fails);
    only those of ``theirs`` that are computed."""
    for key, value in theirs.items():
        if value is None:
            continue
        mine = np.asarray(ours[key])
        assert mine.shape == np.shape(value) and mine.dtype == np.asarray(value).dtype, key
        assert mine.tobytes() == np.ascontiguousarray(value).tobytes(), key


def inputs_for(doc: dict[str, Any], turns: np.ndarray, second: float = 0.0) -> list[DriverInput]:
    """The first driver turned by ``turns``, the others held at ``second``, their rates as
    given."""
    n = turns.size
    out = []
    for k, driver in enumerate(doc["drivers"]):
        theta = turns if k == 0 else np.full(n, second)
        rates = (np.full(n, float(driver.get("omega", 0.0))), np.full(n, driver.get("alpha", 0.0)))
        out.append(DriverInput(theta, *rates))
    return out


def check_one_computation(doc: dict[str, Any], turns: np.ndarray, second: float = 0.0) -> None:
    """A run at a lower order gives the positions (and velocities) of one at a higher, bit for
    bit; and where the branch search finds nothing to examine, every group closes and no driver
    steps so far that the continuation follows a denser grid, a run with continuation gives the
    numbers of one without: the screen and the orders asked for change what is computed, never
    how."""
    scene = parse_linkage(doc)
    plan = build_plan(scene)
    inputs = inputs_for(doc, turns, second)
    plain = {order: assemble(scene, plan, inputs, order) for order in (0, 1, 2)}
    for order in (0, 1):
        assert list(arrays(plain[order])) == list(arrays(plain[2]))
        assert_same_bits(arrays(plain[2]), arrays(plain[order]))
    if coarse(path_steps(inputs)):
        return
    full = assemble(scene, plan, inputs, 2, continuation=True)
    if full.failures or full.approaches or not np.all(full.feasible):
        return
    for order in (0, 1, 2):
        screened = assemble(scene, plan, inputs, order, continuation=True)
        assert list(arrays(plain[order])) == list(arrays(screened))
        assert_same_bits(arrays(screened), arrays(plain[order]))


def turns_with_the_drawn_pose(samples: int, start: float) -> np.ndarray:
    """A revolution from ``start`` with one sample at exactly 0 (the drawn pose)."""
    turns = start + 2.0 * math.pi * np.arange(samples) / samples
    turns[samples // 3] = 0.0
    return turns


@pytest.mark.slow
@settings(max_examples=12, deadline=None)
@given(linkages("four_bar"), st.floats(-math.pi, math.pi), st.sampled_from([7, 36, 361]))
def test_four_bars_one_computation(doc: dict[str, Any], start: float, samples: int) -> None:
    check_one_computation(doc, turns_with_the_drawn_pose(samples, start))
    check_one_computation(doc, start + 2.0 * math.pi * np.arange(samples) / samples)


@settings(max_examples=8, deadline=None)
@given(linkages("six_bar", newton=False), st.floats(-0.3, 0.3))
def test_six_bars_by_dyads_one_computation(doc: dict[str, Any], start: float) -> None:
    """Watt and Stephenson six-bars: dyads on moving centres, ternary links carrying points."""
    check_one_computation(doc, start + np.linspace(-0.05, 0.05, 41))


@settings(max_examples=8, deadline=None)
@given(five_bars(), st.floats(-0.2, 0.2))
def test_two_drivers_one_computation(doc: dict[str, Any], second: float) -> None:
    check_one_computation(doc, np.linspace(-0.05, 0.05, 21), second)


@pytest.mark.parametrize(
    "preset", ["four_bar", "slider_crank", "inverted_slider_crank", "quick_return"]
)
def test_every_group_type_one_computation(preset: str) -> None:
    """Drivers, RRR, RRP, RPR, two-point links and links guided by another, in one executor."""
    check_one_computation(build_preset(preset, {}), 2.0 * math.pi * np.arange(72) / 72)


def test_signed_zeros_at_rest_and_on_the_axes() -> None:
    """A crank at rest (every rate a signed zero) drawn along the axes, the ground at -0.0:
    the drawn pose and its rates come back as drawn, zeros with their signs as a plain run
    gives them."""
    doc = build_preset("four_bar", {"omega": 0.0, "alpha": 0.0, "crank_angle_deg": 90.0})
    doc["points"]["A"] = [-0.0, -0.0]
    turns = math.pi / 16.0 * np.arange(32)  # (on the axes every 8 samples)
    for omega in (0.0, -0.0):
        doc["drivers"][0]["omega"] = omega
        check_one_computation(doc, turns)
        scene = parse_linkage(doc)
        motion = assemble(scene, build_plan(scene), inputs_for(doc, turns), 2)
        assert np.array_equal(motion.points["C"].p[0], scene.drawn("C"))
        assert not motion.points["C"].v.any() and not motion.points["C"].a.any()


@pytest.mark.slow
def test_scene_memo_is_forgotten_with_the_scene() -> None:
    """What a run keeps on a scene (``LinkageScene.memo``: its plan) goes with the scene."""
    import gc
    import weakref

    scene = parse_linkage(build_preset("four_bar", {}))
    plan = build_plan(scene)
    assert build_plan(scene) is plan
    turns = np.linspace(0.0, 1.0, 5)
    assemble(scene, plan, inputs_for(build_preset("four_bar", {}), turns), 2, continuation=True)
    kept = weakref.ref(plan)
    del scene, plan
    gc.collect()
    assert kept() is None


@pytest.mark.parametrize("quantities", [["position"], ["position", "velocity"], ALL])
@pytest.mark.parametrize("preset", ["four_bar", "seed004", "quick_return"])
def test_links_through_a_located_point_take_it_as_located(
    preset: str, quantities: list[str]
) -> None:
    """Every link found from two points P, Q (after a dyad located Q, the assembler hands it Q
    as the dyad saw it): theta = atan2(r) - atan2(r0), omega = (r x v_rel) / |r|^2 and alpha =
    (r x a_rel) / |r|^2 with r = Q - P, v_rel = v_Q - v_P, a_rel = a_Q - a_P written out here
    in numpy on the sweep's own arrays agree bit for bit (the same operations: a stale or
    swapped view of Q would not), at 360 samples, for every order asked."""
    scene = parse_linkage(build_preset(preset, {"crank_angle_deg": 40.0, "alpha": 3.0}))
    motion = sweep(scene, 360, quantities).motion
    steps = [s for s in build_plan(scene).steps if isinstance(s, TwoPointStep)]
    assert steps
    for step in steps:
        P, Q, found = motion.points[step.first], motion.points[step.second], motion.links[step.link]
        rx, ry = Q.p[:, 0] - P.p[:, 0], Q.p[:, 1] - P.p[:, 1]
        r0 = scene.drawn(step.second) - scene.drawn(step.first)
        assert np.array_equal(found.theta, np.arctan2(ry, rx) - np.arctan2(r0[1], r0[0]))
        r2 = rx * rx + ry * ry
        for rate, (of_Q, of_P) in (("omega", (Q.v, P.v)), ("alpha", (Q.a, P.a))):
            if of_Q is None or of_P is None:
                assert getattr(found, rate) is None
                continue
            rel_x, rel_y = of_Q[:, 0] - of_P[:, 0], of_Q[:, 1] - of_P[:, 1]
            assert np.array_equal(getattr(found, rate), (rx * rel_y - ry * rel_x) / r2)

"""Tests of solver.analysis.events.find_event (``solver.find_event``, ``POST /api/v1/events``):
the occurrence-th instant after t = 0 at which a moving point M reaches a named point. It never
misses a crossing between samples and reports no_event when none occurs before t_max.

Sources of the expected times:

- the seed-003 reference cases (tests/reference/seed-cases.json; ERRATA.md, Seed 003: "Event times
  are right");
- closed forms (s = c t^2 on a circle: the k-th return to a point an arc beta past the start is at
  t_k = sqrt((R beta + 2 pi R (k - 1)) / c); uniform motion on a circle: t_k = (beta + 2 pi k) / w;
  a slot or an arc on a disc, two cranks turning about one pivot in opposite senses, a
  parallelogram through its change points), roots of fast laws to 50 digits (mpmath);
- an independent dense scan written here: s(t) - level sampled with at least 64 samples per period
  of the law, sign changes bracketed and bisected to 1e-13 s;
- scale invariance: the same scene in millimetres, metres and kilometres meets at the same times.

Tolerances: 1e-6 relative to max(1, t) (the rule of the reference cases for unit group t) with
``_assert_time``; the closed forms of the search's edges (second half) to 1e-9 relative to
max(1, t) with ``_assert_exact_time`` (1e-6 at a tangential touch, a double root), unless a test
says otherwise.
"""

from __future__ import annotations

import json
import math
from pathlib import Path
from typing import Any

import mpmath
import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

import solver
from solver.analysis import events
from solver.analysis.events import find_event
from solver.errors import LimitExceeded, NoEvent, NotAssemblable
from solver.model.scene import parse_linkage
from solver.teaching.presets import build_preset

CASES = Path(__file__).resolve().parents[2] / "reference" / "seed-cases.json"
T_RTOL = 1e-6  # event times: relative to max(1, t)


def _case(case_id: str) -> dict[str, Any]:
    cases = json.loads(CASES.read_text())["cases"]
    return next(c for c in cases if c["id"] == case_id)


def _event_time(doc: dict[str, Any], reaches: str, occurrence: int, t_max: float) -> float:
    return find_event(parse_linkage(doc), "M", reaches, occurrence, t_max).time


def _assert_time(got: float, want: float, what: str = "", rtol: float = T_RTOL) -> None:
    assert abs(got - want) <= rtol * max(1.0, abs(want)), f"{what}: got {got!r}, want {want!r}"


def disc(
    s_law: str,
    path: dict[str, Any],
    points: dict[str, list[float]],
    on_disc: list[str],
    angle_law: str = "0.7*t - 0.2*t^2",
    on_ground: tuple[str, ...] = (),
) -> dict[str, Any]:
    """A disc pivoted at O turning by ``angle_law``; M moves on ``path`` of the disc."""
    return {
        "kind": "linkage",
        "title": "disc",
        "points": {"O": [0.0, 0.0], **points},
        "links": {
            "ground": {"points": ["O", *on_ground], "ground": True},
            "disc": {"points": ["O", *on_disc]},
        },
        "joints": [{"type": "revolute", "point": "O", "links": ["ground", "disc"]}],
        "drivers": [{"link": "disc", "angle_law": angle_law}],
        "moving_points": [{"name": "M", "link": "disc", "path": path, "s_law": s_law}],
    }


def arc_disc(
    s_law: str,
    radius: float,
    center: tuple[float, float],
    start_angle: float,
    direction: str,
    target_arc: float,
    angle_law: str = "0.7*t - 0.2*t^2",
    target_on_ground: bool = False,
) -> dict[str, Any]:
    """M on a circle (centre C, start S) of the disc; target T lies ``target_arc`` metres along
    the path from S (in the path's direction) at the drawn pose."""
    turn = 1.0 if direction == "ccw" else -1.0
    cx, cy = center
    a = start_angle + turn * target_arc / radius
    pts = {
        "C": [cx, cy],
        "S": [cx + radius * math.cos(start_angle), cy + radius * math.sin(start_angle)],
        "T": [cx + radius * math.cos(a), cy + radius * math.sin(a)],
    }
    path = {"type": "arc", "center": "C", "start": "S", "direction": direction}
    if target_on_ground:
        return disc(s_law, path, pts, ["C", "S"], angle_law, on_ground=("T",))
    return disc(s_law, path, pts, ["C", "S", "T"], angle_law)


# --- reference cases ---


@pytest.mark.parametrize("case_id", ["S003-T1-translating-carrier", "S003-T2-rotating-carrier"])
def test_seed_003_event_times(case_id: str) -> None:
    """Source: seed-cases.json (events requests); tolerance 1e-6 relative to max(1, t)."""
    for request in _case(case_id)["requests"]:
        if request["endpoint"] != "POST /api/v1/events":
            continue
        e = request["body"]["event"]
        got = find_event(
            parse_linkage(request["body"]["scene"]),
            e["moving_point"],
            e["reaches"],
            e["occurrence"],
            e["t_max"],
        ).time
        (want,) = (x["value"] for x in request["expected"] if x["path"] == "time")
        _assert_time(got, want, f"{case_id} occurrence {e['occurrence']}")


def test_seed_003_event_times_closed_forms() -> None:
    """ERRATA.md, Seed 003: Task 1 t = sqrt(3) s (M reaches A after pi R); Task 2 t = (-1 +
    sqrt(1 + 16 R / 5)) / 6 s with R = 30 (cm) (M back at its start after 2 pi R)."""
    t1 = _case("S003-T1-translating-carrier")["requests"][2]["body"]
    t2 = _case("S003-T2-rotating-carrier")["requests"][2]["body"]
    _assert_time(_event_time(t1["scene"], "TARGET", 1, 60.0), math.sqrt(3.0), "Task 1")
    want = (-1 + math.sqrt(1 + 16 * 30 / 5)) / 6
    _assert_time(_event_time(t2["scene"], "S", 1, 60.0), want, "Task 2")


def test_occurrence_beyond_t_max_is_no_event() -> None:
    """Source: the S003 closed forms. Task 1 reaches A at sqrt(3) = 1.732 s: not by 1.7 s; it
    passes A again at 3 s (s = 3 pi R): not by 2.9 s. Task 2 returns to S for the 3rd time when
    0.2356 t + 0.7069 t^2 = 3 (2 pi 0.3), t = 2.67 s: not by 2.5 s."""
    t1 = _case("S003-T1-translating-carrier")["requests"][2]["body"]["scene"]
    t2 = _case("S003-T2-rotating-carrier")["requests"][2]["body"]["scene"]
    with pytest.raises(NoEvent):
        _event_time(t1, "TARGET", 1, 1.7)
    _assert_time(_event_time(t1, "TARGET", 1, 1.8), math.sqrt(3.0))
    # The k-th pass of A: 0.06 pi t^2 = 0.18 pi (2k - 1), t = sqrt(3 (2k - 1)).
    with pytest.raises(NoEvent):
        _event_time(t1, "TARGET", 2, 2.9)
    _assert_time(_event_time(t1, "TARGET", 2, 3.1), 3.0, "second pass")
    with pytest.raises(NoEvent):
        _event_time(t2, "S", 3, 2.5)
    third = (
        -0.23561944901923448
        + math.sqrt(0.23561944901923448**2 + 4 * 0.7068583470577035 * 3 * 2 * math.pi * 0.3)
    ) / (2 * 0.7068583470577035)
    _assert_time(_event_time(t2, "S", 3, 2.8), third, "third return")


# --- occurrences against closed forms ---


@pytest.mark.slow
@settings(max_examples=15, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(
    radius=st.floats(0.05, 2.0),
    c=st.floats(0.05, 5.0),
    beta=st.floats(0.1, 2 * math.pi - 0.1),
    direction=st.sampled_from(["cw", "ccw"]),
    start_angle=st.floats(-math.pi, math.pi),
    occurrences=st.lists(st.integers(1, 6), min_size=1, max_size=3, unique=True),
)
def test_kth_meeting_on_a_circle_matches_closed_form(
    radius: float,
    c: float,
    beta: float,
    direction: str,
    start_angle: float,
    occurrences: list[int],
) -> None:
    """s = c t^2 on a circle of radius R of a turning disc; target at an arc R beta past the
    start on the disc: t_k = sqrt((R beta + 2 pi R (k - 1)) / c). Tolerance 1e-9 relative to
    max(1, t): the level is exact up to rounding and is found by bracketing."""
    doc = arc_disc(f"{c!r}*t^2", radius, (0.3, -0.2), start_angle, direction, radius * beta)
    for k in occurrences:
        want = math.sqrt((radius * beta + 2 * math.pi * radius * (k - 1)) / c)
        t_max = 1.2 * math.sqrt((radius * beta + 2 * math.pi * radius * 5) / c) + 1.0
        _assert_time(_event_time(doc, "T", k, t_max), want, f"occurrence {k}", 1e-9)


def test_kth_return_to_the_start_skips_t_zero() -> None:
    """Target = the start S: M is there at t = 0, which does not count (spec: 'after t = 0');
    the k-th return of s = c t^2 is at sqrt(2 pi R k / c)."""
    radius, c = 0.4, 0.9
    doc = arc_disc(f"{c}*t^2", radius, (0.1, 0.5), 0.3, "cw", 1.0)
    for k in (1, 2, 3, 7):
        _assert_time(
            _event_time(doc, "S", k, 60.0),
            math.sqrt(2 * math.pi * radius * k / c),
            f"return {k}",
            1e-9,
        )


def test_meeting_on_a_line_and_behind_the_start() -> None:
    """A slot (line S -> L): s = c t^2 meets a point d ahead once at sqrt(d / c), never twice;
    s = -c t^2 meets a point d behind the start at sqrt(d / c). Tolerance 1e-9 relative."""
    pts = {
        "S": [0.2, 0.1],
        "L": [0.6, 0.4],
        "T": [0.2 + 0.8 * 0.6, 0.1 + 0.6 * 0.6],
        "U": [0.2 - 0.8 * 0.3, 0.1 - 0.6 * 0.3],
    }
    path = {"type": "line", "start": "S", "through": "L"}
    ahead = disc("0.5*t^2", path, pts, ["S", "L", "T", "U"])
    _assert_time(_event_time(ahead, "T", 1, 10.0), math.sqrt(0.6 / 0.5), "ahead", 1e-9)
    with pytest.raises(NoEvent):
        _event_time(ahead, "T", 2, 10.0)
    with pytest.raises(NoEvent):
        _event_time(ahead, "U", 1, 10.0)
    behind = disc("-0.5*t^2", path, pts, ["S", "L", "T", "U"])
    _assert_time(_event_time(behind, "U", 1, 10.0), math.sqrt(0.3 / 0.5), "behind", 1e-9)


# --- fast oscillation: no crossing missed ---


def _dense_crossings(s: Any, level: float, period: float, t_max: float, samples: int) -> np.ndarray:
    """Independent scan: every t in (0, t_max] with s(t) = level (+ k period), by sign changes on
    a dense grid refined by bisection (s is a numpy function of t)."""
    t = np.linspace(0.0, t_max, samples + 1)
    values = s(t)
    levels = [level + k * period for k in range(-3, 4)] if period else [level]
    found = []
    for lv in levels:
        g = values - lv
        idx = np.flatnonzero(np.sign(g[:-1]) * np.sign(g[1:]) < 0)
        lo, hi = t[idx], t[idx + 1]
        glo = s(lo) - lv
        for _ in range(80):
            mid = 0.5 * (lo + hi)
            gm = s(mid) - lv
            left = np.sign(gm) == np.sign(glo)
            lo, hi, glo = np.where(left, mid, lo), np.where(left, hi, mid), np.where(left, gm, glo)
        found.append(0.5 * (lo + hi))
        exact = t[1:][g[1:] == 0.0]
        found.append(exact)
    return np.sort(np.concatenate(found))


@pytest.mark.slow
@pytest.mark.parametrize(
    ("omega", "t_max"),
    [
        (40.0, 60.0),  # the brief's example: ~10 grid samples of find_event per period
        (40.0, 600.0),  # same law, longer search: fewer than one grid sample per period
        (400.0, 60.0),  # faster law: fewer than one grid sample per period
    ],
)
def test_fast_oscillating_law_every_crossing_found(omega: float, t_max: float) -> None:
    """s = 0.2 sin(omega t) on an arc (R = 0.3), target at s = 0.05 on the disc: every crossing
    in (0, t_max] counts. Compared with the independent dense scan (64 samples per period):
    the number of meetings (occurrence N exists, N + 1 is no_event) and the times of several
    occurrences (tolerance 1e-9 relative to max(1, t))."""
    radius, level = 0.3, 0.05
    law = f"0.2*sin({omega}*t)"
    doc = arc_disc(law, radius, (0.0, 0.3), 0.0, "ccw", level)
    samples = int(64 * omega * t_max / (2 * math.pi))
    want = _dense_crossings(
        lambda t: 0.2 * np.sin(omega * t), level, 2 * math.pi * radius, t_max, samples
    )
    n = want.size
    assert n == 2 * round(omega * t_max / (2 * math.pi)), "the dense scan itself"
    for k in sorted({1, 2, 3, n // 3, n // 2, n - 1, n}):
        _assert_time(
            _event_time(doc, "T", k, t_max), float(want[k - 1]), f"occurrence {k} of {n}", 1e-9
        )
    with pytest.raises(NoEvent):
        _event_time(doc, "T", n + 1, t_max)


# --- a law that turns back at the target (tangential touch) and turning points on the grid ---


def test_tangential_touch_counts_once_exact_level() -> None:
    """s = 0.125 (2t - t^2) on a slot turns back at s = 0.125 at t = 1, exactly where T lies
    (all numbers exact in binary): one meeting, t = 1 (tolerance 1e-6: a double root), no
    second one before t_max = 3."""
    pts = {"S": [0.25, 0.25], "L": [0.5, 0.25], "T": [0.375, 0.25]}
    doc = disc(
        "0.125*(2*t - t^2)", {"type": "line", "start": "S", "through": "L"}, pts, ["S", "L", "T"]
    )
    _assert_time(_event_time(doc, "T", 1, 3.0), 1.0, "touch")
    with pytest.raises(NoEvent):
        _event_time(doc, "T", 2, 3.0)


def test_tangential_touch_on_an_arc_counts_once() -> None:
    """s = (pi R / 2)(2t - t^2) on a circle of radius R turns back a quarter turn past the start,
    where T lies, at t = 1; before t_max = 2.5 it never reaches T again (s(2.5) = -1.25 pi R / 2
    is short of the next copy -3 pi R / 2). Tolerance 1e-6 (a double root)."""
    doc = arc_disc("0.3*pi/2*(2*t - t^2)", 0.3, (0.0, 0.3), 0.0, "ccw", 0.3 * math.pi / 2)
    _assert_time(_event_time(doc, "T", 1, 2.5), 1.0, "touch")
    with pytest.raises(NoEvent):
        _event_time(doc, "T", 2, 2.5)


def test_tangential_touch_with_decimal_coordinates_counts_once() -> None:
    """The same touch written as a student would: slot from S = (0.3, 0.3) through (0.5, 0.3),
    T = (0.4, 0.3) 0.1 m along it, s = 0.1 (2t - t^2) turns back at s = 0.1 at t = 1. In exact
    arithmetic M reaches T once (spec: the occurrence-th instant M coincides with T); the
    target's level 0.4 - 0.3 rounds to 0.1 + 3e-17, an error far below the solver's own
    on-path tolerance (1e-9 of the path's size). Tolerance 1e-6."""
    pts = {"S": [0.3, 0.3], "L": [0.5, 0.3], "T": [0.4, 0.3]}
    doc = disc(
        "0.1*(2*t - t^2)", {"type": "line", "start": "S", "through": "L"}, pts, ["S", "L", "T"]
    )
    _assert_time(_event_time(doc, "T", 1, 3.0), 1.0, "touch")


@pytest.mark.parametrize("turn_time", [1.0, 0.75])
def test_turning_point_exactly_on_the_search_grid(turn_time: float) -> None:
    """s = t^2 - 2 a t on a slot turns back at t = a; with t_max = 2a that instant is a sample
    of any uniform grid with an even number of intervals, where s' = 0 exactly. A target 0.5 a^2
    behind the start is met twice, at a (1 -+ sqrt(1/2)); the tangential touch at s = -a^2
    once, at t = a. Source: closed form; tolerance 1e-9 (1e-6 for the touch)."""
    a = turn_time
    pts = {"S": [0.0, 0.5], "L": [1.0, 0.5], "T": [-0.5 * a * a, 0.5], "U": [-a * a, 0.5]}
    doc = disc(
        f"t^2 - 2*{a!r}*t",
        {"type": "line", "start": "S", "through": "L"},
        pts,
        ["S", "L", "T", "U"],
    )
    _assert_time(_event_time(doc, "T", 1, 2 * a), a * (1 - math.sqrt(0.5)), "first", 1e-9)
    _assert_time(_event_time(doc, "T", 2, 2 * a), a * (1 + math.sqrt(0.5)), "second", 1e-9)
    _assert_time(_event_time(doc, "U", 1, 2 * a), a, "touch")


# --- targets off the path, targets off the carrier ---


def test_target_off_the_path_is_no_event() -> None:
    """A point of the carrier that is not on M's circle (1 % outside) or not on M's line."""
    doc = arc_disc("0.3*t", 0.3, (0.0, 0.3), 0.0, "ccw", 0.2)
    doc["points"]["T"] = [1.01 * 0.3 * math.cos(0.2 / 0.3), 0.3 + 1.01 * 0.3 * math.sin(0.2 / 0.3)]
    with pytest.raises(NoEvent):
        _event_time(doc, "T", 1, 60.0)
    pts = {"S": [0.2, 0.1], "L": [0.6, 0.4], "T": [0.5, 0.5]}
    line = disc("t", {"type": "line", "start": "S", "through": "L"}, pts, ["S", "L", "T"])
    with pytest.raises(NoEvent):
        _event_time(line, "T", 1, 60.0)


def _ground_point_case(
    rate_carrier: float, rate_path: float, quadratic: bool = False
) -> tuple[dict[str, Any], Any]:
    """M on a circle of radius R about the disc's pivot O (so its absolute path is that circle),
    a ground point G on the circle at angle beta = 2 from the start. M's absolute angle is
    phi(t) + s(t)/R; returns the document and t_k(k), the closed-form k-th meeting."""
    radius, beta = 0.3, 2.0
    pts = {"S": [radius, 0.0], "G": [radius * math.cos(beta), radius * math.sin(beta)]}
    path = {"type": "arc", "center": "O", "start": "S", "direction": "ccw"}
    if quadratic:  # total angle w t^2
        w = rate_carrier + rate_path
        doc = disc(
            f"{radius * rate_path!r}*t^2",
            path,
            pts,
            ["S"],
            f"{rate_carrier!r}*t^2",
            on_ground=("G",),
        )
        return doc, lambda k: math.sqrt((beta + 2 * math.pi * (k - 1)) / w)
    w = rate_carrier + rate_path
    doc = disc(
        f"{radius * rate_path!r}*t", path, pts, ["S"], f"{rate_carrier!r}*t", on_ground=("G",)
    )
    return doc, lambda k: (beta + 2 * math.pi * (k - 1)) / w


@pytest.mark.parametrize(
    ("rate_carrier", "rate_path", "quadratic"),
    [(0.0, 1.0, False), (0.5, 0.5, False), (-0.5, 1.5, False), (0.3, 0.2, True)],
    ids=["carrier-at-rest", "carrier-turning", "carrier-counter-turning", "accelerating"],
)
def test_target_off_the_carrier_found_by_distance(
    rate_carrier: float, rate_path: float, quadratic: bool
) -> None:
    """A ground point on M's absolute path: the first meetings (t <= 20 s) against the closed
    form; tolerance 1e-6 relative to max(1, t)."""
    doc, t_k = _ground_point_case(rate_carrier, rate_path, quadratic)
    n = max(k for k in range(1, 200) if t_k(k) <= 20.0)
    for k in sorted({1, 2, n}):
        _assert_time(_event_time(doc, "G", k, 20.0), t_k(k), f"meeting {k}")
    with pytest.raises(NoEvent):
        _event_time(doc, "G", n + 1, 20.0)


@pytest.mark.parametrize("t_max", [60.0, 200.0])
def test_target_off_the_carrier_every_meeting_found_up_to_t_max(t_max: float) -> None:
    """Carrier at rest, M once round its circle (R = 0.3 m) every 2 pi s, ground point G on the
    circle: meetings at t_k = 2 + 2 pi (k - 1) s. All of them up to the default t_max = 60 s
    (10 meetings) and up to 200 s (32) must be found; tolerance 1e-6 relative to max(1, t)."""
    doc, t_k = _ground_point_case(0.0, 1.0)
    n = max(k for k in range(1, 1000) if t_k(k) <= t_max)
    for k in sorted({n // 2, n - 1, n}):
        _assert_time(_event_time(doc, "G", k, t_max), t_k(k), f"meeting {k} of {n}")
    with pytest.raises(NoEvent):
        _event_time(doc, "G", n + 1, t_max)


# --- cost of a search ---


def test_first_occurrence_is_found_without_enumerating_the_later_ones() -> None:
    """S003 Task 2 asked for its first return with t_max = 1000 s (allowed: the limit is 1e6 s).
    The answer is t = 1.474810 s, as with t_max = 60 s; the search must not enumerate every
    later crossing first: 0.2356 t + 0.7069 t^2 passes S about 375 000 times by t = 1000 s, and
    finding each costs Brent's method about 10 evaluations of the law, more than the search's
    limit of MAX_SEARCH_SAMPLES = 1e6 evaluations (limit_exceeded)."""
    doc = _case("S003-T2-rotating-carrier")["requests"][2]["body"]["scene"]
    _assert_time(_event_time(doc, "S", 1, 1000.0), 1.4748096336326841, "first return")


@pytest.mark.slow
def test_a_search_stops_at_the_occurrence_inside_a_window() -> None:
    """s = 1000 t on a circle of radius 1 mm passes T (0.5 rad along it) every 2 pi mm / 1000
    m/s = 6.28 us, at t_k = (0.5 mm + 2 pi mm (k - 1)) / 1000 m/s (closed form); the first
    search window, t_max / 64 = 15.6 s long for t_max = 1000 s, holds 2.5 million of these
    crossings. The 1st and the 10 000th (the largest occurrence allowed) must be found without
    finding the others of that window first: 2.5 million crossings cost more evaluations of the
    law than the search's limit of MAX_SEARCH_SAMPLES = 1e6 (limit_exceeded). Tolerance 1e-9
    relative to max(1, t)."""
    R = 1e-3
    doc = arc_disc("1000*t", R, (0.3, -0.2), 0.4, "ccw", 0.5 * R)
    for k in (1, 10_000):
        want = (0.5 * R + 2.0 * math.pi * R * (k - 1)) / 1000.0
        _assert_time(_event_time(doc, "T", k, 1000.0), want, f"crossing {k}", 1e-9)


# --- where the event happens, meetings at t_max, bad requests ---


def test_event_position_is_the_target_where_it_is_at_that_time() -> None:
    """The event's position is where M and the target coincide: the target T of the disc turned
    by phi(t) = 0.7 t - 0.2 t^2 about O (closed form), to 1e-8 m; for a ground target G, G
    itself (to the coincidence tolerance, 1e-7 of the scene size)."""
    radius, c, beta = 0.4, 0.9, 1.3
    doc = arc_disc(f"{c}*t^2", radius, (0.3, -0.2), 0.5, "ccw", radius * beta)
    event = find_event(parse_linkage(doc), "M", "T", 2, 60.0)
    t = event.time
    _assert_time(t, math.sqrt((radius * beta + 2 * math.pi * radius) / c), "second meeting", 1e-9)
    phi = 0.7 * t - 0.2 * t * t
    T0 = doc["points"]["T"]
    want = [
        math.cos(phi) * T0[0] - math.sin(phi) * T0[1],
        math.sin(phi) * T0[0] + math.cos(phi) * T0[1],
    ]
    np.testing.assert_allclose(event.position, want, atol=1e-8)
    ground, _ = _ground_point_case(0.5, 0.5)
    scene = parse_linkage(ground)
    at_G = find_event(scene, "M", "G", 1, 20.0).position
    assert math.hypot(*(at_G - np.array(ground["points"]["G"]))) <= 1e-7 * scene.size


def test_meeting_exactly_at_t_max_counts() -> None:
    """0 < t <= t_max includes t_max: s = t^2 on a circle meets a target 1 m of arc ahead at
    t = 1 s, found with t_max = 1 s; M circling at 1 rad/s meets the ground point 2 rad ahead at
    t = 2 s, found with t_max = 2 s (the last sample of the distance grid)."""
    doc = arc_disc("t^2", 0.5, (0.1, 0.2), 0.3, "cw", 1.0)
    _assert_time(_event_time(doc, "T", 1, 1.0), 1.0, "on the carrier", 1e-9)
    ground, t_k = _ground_point_case(0.0, 1.0)
    _assert_time(_event_time(ground, "G", 1, 2.0), t_k(1), "off the carrier")


def test_bad_event_requests_are_refused() -> None:
    """Unknown names: invalid_scene; occurrence outside 1..10000 and t_max outside (0, 1e6] s:
    limit_exceeded (the bounds themselves are accepted)."""
    from solver.errors import InvalidScene, LimitExceeded

    scene = parse_linkage(arc_disc("t", 0.5, (0.1, 0.2), 0.3, "cw", 1.0))
    with pytest.raises(InvalidScene, match=r"event\.moving_point: unknown moving point 'N'"):
        find_event(scene, "N", "T", 1, 10.0)
    with pytest.raises(InvalidScene, match=r"event\.reaches: unknown point 'Q'"):
        find_event(scene, "M", "Q", 1, 10.0)
    for occurrence in (0, 10_001):
        with pytest.raises(LimitExceeded, match=r"event\.occurrence"):
            find_event(scene, "M", "T", occurrence, 10.0)
    for t_max in (0.0, -1.0, 1e6 * (1 + 1e-15)):
        with pytest.raises(LimitExceeded, match=r"event\.t_max"):
            find_event(scene, "M", "T", 1, t_max)
    assert find_event(scene, "M", "T", 1, 1e6).time == pytest.approx(1.0, rel=1e-9)
    # s = t on a circle of radius 0.5 meets T (1 m of arc ahead) at 1, 1 + pi, 1 + 2 pi s
    with pytest.raises(NoEvent, match=r"M reaches T 3 time\(s\) in 0 < t <= 10 s, not 10000"):
        find_event(scene, "M", "T", 10_000, 10.0)


# --- the edges of the search: slots and arcs on a disc, fast laws, the sample limit ---

EXACT_RTOL = 1e-9


def _time(doc: dict[str, Any], reaches: str, occurrence: int, t_max: float) -> float:
    return float(solver.find_event(doc, "M", reaches, occurrence, t_max)["time"])


def _assert_exact_time(got: float, want: float, what: str, rtol: float = EXACT_RTOL) -> None:
    assert abs(got - want) <= rtol * max(1.0, abs(want)), f"{what}: got {got!r}, want {want!r}"


def _disc(s_law: str, path: dict[str, Any], points: dict[str, list[float]]) -> dict[str, Any]:
    """A disc pivoted at O (turning by 0.7 t - 0.2 t^2) carrying ``points``; M moves on
    ``path`` of the disc by ``s_law``."""
    return {
        "kind": "linkage",
        "title": "disc",
        "points": {"O": [0.0, 0.0], **points},
        "links": {
            "ground": {"points": ["O"], "ground": True},
            "disc": {"points": ["O", *points]},
        },
        "joints": [{"type": "revolute", "point": "O", "links": ["ground", "disc"]}],
        "drivers": [{"link": "disc", "angle_law": "0.7*t - 0.2*t^2"}],
        "moving_points": [{"name": "M", "link": "disc", "path": path, "s_law": s_law}],
    }


def _slot(s_law: str, start: list[float], targets: dict[str, float]) -> dict[str, Any]:
    """M on a slot of the disc from ``start`` along +x; each target lies ``targets[name]``
    metres along the slot from the start (behind it if negative)."""
    x, y = start
    points = {"S": [x, y], "L": [x + 1.0, y]}
    points |= {name: [x + s, y] for name, s in targets.items()}
    return _disc(s_law, {"type": "line", "start": "S", "through": "L"}, points)


# --- is the target on M's path at all ---


@pytest.mark.parametrize(
    ("origin", "scale"),
    [((0.0, 0.0), 1e-3), ((0.0, 0.0), 1.0), ((1000.0, -1000.0), 1.0)],
    ids=["millimetres", "metres", "far-from-the-origin"],
)
def test_target_just_off_a_slot_is_never_reached(origin: tuple[float, float], scale: float) -> None:
    """A slot along +x from S; T lies 0.3 scale along it and 1e-7 scale m to its side (1e-7 of
    the scene's size, a hundred times the on-path tolerance, 1e-9 of the size): M never reaches
    it, at millimetre or metre scale, next to the origin or 1.4 km from it (the tolerance is
    relative to the scene's size, not to the coordinates). On the slot, T is met at
    s = 0.3 scale = scale t^2, t = sqrt(0.3) (closed form)."""
    x, y = origin[0] + 0.25 * scale, origin[1] + 0.25 * scale
    doc = _slot(f"{scale!r}*t^2", [x, y], {"T": 0.3 * scale})
    doc["points"]["O"] = list(origin)  # the disc's pivot, and L, at the slot's scale
    doc["points"]["L"] = [x + scale, y]
    _assert_exact_time(_time(doc, "T", 1, 3.0), math.sqrt(0.3), "on the slot")
    doc["points"]["T"][1] = y + 1e-7 * scale
    with pytest.raises(NoEvent, match=r"^T is 1e-0?\d+ m off the line along which M moves, so M"):
        _time(doc, "T", 1, 3.0)


@pytest.mark.parametrize("scale", [1e-3, 1.0, 1e3])
def test_target_just_off_an_arc_is_never_reached(scale: float) -> None:
    """M on a circle of radius R = 0.3 scale about C; T at 1 rad along it but 1e-7 R outside
    (a hundred times the on-path tolerance, 1e-9 R): never reached, at every
    scale; on the circle it is met where R t = R, t = 1 s (closed form, s = R t)."""
    R = 0.3 * scale
    C = [0.2 * scale, 0.5 * scale]

    def arc_doc(r_t: float) -> dict[str, Any]:
        points = {
            "C": C,
            "S": [C[0] + R, C[1]],
            "T": [C[0] + r_t * math.cos(1.0), C[1] + r_t * math.sin(1.0)],
        }
        path = {"type": "arc", "center": "C", "start": "S", "direction": "ccw"}
        return _disc(f"{R!r}*t", path, points)

    _assert_exact_time(_time(arc_doc(R), "T", 1, 3.0), 1.0, "on the arc")
    with pytest.raises(NoEvent, match=r"^T is not on the arc of M: \|CT\| = .* m, radius .* m$"):
        _time(arc_doc(R * (1 + 1e-7)), "T", 1, 3.0)


# --- turning points and tangential touches on M's carrier ---


def test_turning_point_on_a_sample_inside_a_search_window() -> None:
    """s = t^2 - t on a slot turns back at t = 1/2, where s' = 0 exactly. With t_max = 64 s the
    search windows are 1 s wide with 64 intervals, so t = 1/2 is the 33rd sample of the first
    window (not a window's end). A target at s = -1/4 + 1e-4 is met twice, at
    1/2 -+ 1e-2 s (closed form), both within one sample of the turning point."""
    doc = _slot("t^2 - t", [0.5, 0.5], {"T": -0.25 + 1e-4})
    _assert_exact_time(_time(doc, "T", 1, 64.0), 0.49, "first")
    _assert_exact_time(_time(doc, "T", 2, 64.0), 0.51, "second")
    with pytest.raises(NoEvent):
        _time(doc, "T", 3, 64.0)


@pytest.mark.parametrize(
    ("s_law", "target"),
    [("1e5*(2*t - t^2) - 99999.6", 0.4), ("99999.6 - 1e5*(2*t - t^2)", -0.4)],
    ids=["turns-back-ahead", "turns-back-behind"],
)
def test_tangential_touch_in_a_law_of_large_range(s_law: str, target: float) -> None:
    """s = +-(1e5 (2t - t^2) - 99999.6) comes from -+1e5 m and turns back at s(1) = +-0.4 m,
    exactly the target's s: in exact arithmetic M reaches the target once, at t = 1 s, and
    never again before t_max = 3 s (s(3) = -+4e5 m). In floating point s(1) carries the
    rounding of numbers of size 1e5: it stops 6e-12 m short of the target, 1.5e-11 of the
    target's s but far less than 1e-12 of the s the law covers on the way there (tens of metres
    in the search window). Tolerance 1e-6 (a double root)."""
    doc = _slot(s_law, [0.25, 0.25], {"T": target})
    _assert_exact_time(_time(doc, "T", 1, 3.0), 1.0, "touch", 1e-6)
    with pytest.raises(NoEvent):
        _time(doc, "T", 2, 3.0)


def test_tangential_touch_just_past_the_start_of_an_arc() -> None:
    """M on a circle of radius 1 m (the path's period 2 pi m), s = 1e-5 (2t - t^2) turns back
    1e-5 m past the start, where T lies (T at 1e-5 rad from S, S at 2 rad about the centre, so
    T's s has the rounding of angles of size 2, about 1e-16 m): one meeting, at t = 1 s, and
    none more by t_max = 2.5 s (s(2.5) = -1.25e-5 m, far from the next copy, -2 pi m)."""
    a0, beta = 2.0, 1e-5
    points = {
        "C": [0.3, -0.2],
        "S": [0.3 + math.cos(a0), -0.2 + math.sin(a0)],
        "T": [0.3 + math.cos(a0 + beta), -0.2 + math.sin(a0 + beta)],
    }
    path = {"type": "arc", "center": "C", "start": "S", "direction": "ccw"}
    doc = _disc(f"{beta!r}*(2*t - t^2)", path, points)
    _assert_exact_time(_time(doc, "T", 1, 2.5), 1.0, "touch", 1e-6)
    with pytest.raises(NoEvent):
        _time(doc, "T", 2, 2.5)


def test_near_touch_at_millimetre_scale_is_not_a_meeting() -> None:
    """A slot at millimetre scale, T 0.5 mm along it: s = 0.5e-3 (2t - t^2) reaches T at t = 1 s
    (a touch, counted once); s = 0.5e-3 (1 - 1e-9) (2t - t^2) turns back 5e-13 m short of T
    (1e-9 of the path travelled, a million times its rounding): M never reaches T."""
    reaches = _slot("0.5e-3*(2*t - t^2)", [1e-3, 1e-3], {"T": 0.5e-3})
    _assert_exact_time(_time(reaches, "T", 1, 3.0), 1.0, "touch", 1e-6)
    with pytest.raises(NoEvent):
        _time(reaches, "T", 2, 3.0)
    short = _slot("0.5e-3*(1 - 1e-9)*(2*t - t^2)", [1e-3, 1e-3], {"T": 0.5e-3})
    with pytest.raises(NoEvent):
        _time(short, "T", 1, 3.0)


def test_tangential_touch_from_above_on_an_arc_and_the_next_crossing() -> None:
    """M on a circle of radius R = 0.3 m (period 2 pi R): s = -(pi R / 2)(2t - t^2) goes back a
    quarter turn and turns there at t = 1 s, touching T, which lies three quarters of a turn
    ahead (the copy s = -pi R / 2 of its level 3 pi R / 2): the lowest s of the piece is the
    touch. Then M comes forward again and passes T's copy 3 pi R / 2 when
    2t - t^2 = -3, t = 3 s (closed form); the next copy, 7 pi R / 2, at 1 + sqrt 8 = 3.83 s,
    is past t_max = 3.5 s. Tolerance 1e-6 (the touch is a double root)."""
    R = 0.3
    doc = _disc(
        "-0.3*pi/2*(2*t - t^2)",
        {"type": "arc", "center": "C", "start": "S", "direction": "ccw"},
        {"C": [0.2, 0.5], "S": [0.2 + R, 0.5], "T": [0.2, 0.5 - R]},
    )
    _assert_exact_time(_time(doc, "T", 1, 3.5), 1.0, "touch", 1e-6)
    _assert_exact_time(_time(doc, "T", 2, 3.5), 3.0, "crossing after the touch", 1e-6)
    with pytest.raises(NoEvent):
        _time(doc, "T", 3, 3.5)


def test_a_falling_law_meets_the_copies_of_its_target_in_time_order() -> None:
    """M runs backwards round a circle of radius R = 0.3 m at 10 m/s (s = -10 t), so each
    search window of t_max / 64 = 0.94 s (t_max = 60 s) is one monotonic piece holding five
    copies of T's level (T 0.1 m along the circle); M meets T at
    t_k = (2 pi R k - 0.1) / 10 s (closed form), the copies 0.1 - 2 pi R k taken highest first.
    Checked: the 1st, 2nd, 5th and 6th (the first of the second window)."""
    R = 0.3
    points = {
        "C": [0.2, 0.5],
        "S": [0.2 + R, 0.5],
        "T": [0.2 + R * math.cos(0.1 / R), 0.5 + R * math.sin(0.1 / R)],
    }
    doc = _disc("-10*t", {"type": "arc", "center": "C", "start": "S", "direction": "ccw"}, points)
    for k in (1, 2, 5, 6):
        _assert_exact_time(
            _time(doc, "T", k, 60.0), (2 * math.pi * R * k - 0.1) / 10, f"meeting {k}"
        )


def _mp_root(f: Any, low: float, high: float) -> float:
    """The root of f in [low, high] (a sign change), by mpmath's Illinois method."""
    return float(mpmath.findroot(f, (mpmath.mpf(low), mpmath.mpf(high)), solver="illinois"))


def _fast_law_roots(scale: float = 1.0) -> tuple[float, float]:
    """The two t with 0.01 sin(1000 t) - t = 0.005 (mpmath roots either side of the peak at
    1.47 ms), times ``scale``: the crossings of the law run 1 / scale times faster."""
    mpmath.mp.dps = 40

    def s(t: Any) -> Any:
        return mpmath.mpf("0.01") * mpmath.sin(1000 * t) - t - mpmath.mpf("0.005")

    return scale * _mp_root(s, 0.0, 1.47e-3), scale * _mp_root(s, 1.47e-3, 3.14e-3)


def test_search_stops_at_the_occurrence_asked_for() -> None:
    """s = 0.01 sin(1000 t) - t on a slot rises to about 8.4 mm, crosses T at 5 mm twice on the
    way up and down, and then never again (its later peaks are 0.01 - t < 5 mm): the two
    crossings (``_fast_law_roots``, 1e-9) are found with t_max = 1e6 s, the largest allowed,
    without searching on to t_max (the law turns every 3 ms, so a search to 1e6 s would pass
    the sample limit)."""
    first, second = _fast_law_roots()
    doc = _slot("0.01*sin(1000*t) - t", [0.25, 0.25], {"T": 0.005})
    _assert_exact_time(_time(doc, "T", 1, 1e6), first, "first")
    _assert_exact_time(_time(doc, "T", 2, 1e6), second, "second")
    with pytest.raises(NoEvent):
        _time(doc, "T", 3, 1.0)


# t_max at which narrowing the search windows at the sampled turns of s'' alone misses both
# crossings of 0.01 sin(1000 t) - t = 5 mm, then a fixed random list (log-uniform in [1, 1e6] s,
# seed 2026; of it 6535, 8255, 32840 and 269700 s give no_event to that rule and 633500 s
# limit_exceeded), and two at which that rule finds them.
ALIASED_T_MAX = [99.0, 1234.5, 2.1e5]
RANDOM_T_MAX = [1.194, 11.85, 636.2, 6535.0, 8255.0, 32840.0, 269700.0, 633500.0]


@pytest.mark.parametrize("t_max", [*ALIASED_T_MAX, *RANDOM_T_MAX, 10.0, 1e6])
def test_crossings_of_a_fast_law_are_found_whatever_t_max(t_max: float) -> None:
    """The law of ``test_search_stops_at_the_occurrence_asked_for``: its two crossings
    (``_fast_law_roots``, near 0.59 and 2.32 ms, 1e-9) must not depend on t_max. Before the
    fix the windows' sampled turns of s'' (sin(1000 t) sampled every t_max / 4096 s, aliased)
    left the first window wide at these t_max and both crossings were missed."""
    first, second = _fast_law_roots()
    doc = _slot("0.01*sin(1000*t) - t", [0.25, 0.25], {"T": 0.005})
    _assert_exact_time(_time(doc, "T", 1, t_max), first, "first")
    _assert_exact_time(_time(doc, "T", 2, t_max), second, "second")


def _kth_swing(k: int) -> float:
    """The k-th t > 0 with 0.01 cos(3000 t) = -0.006: 3000 t = a + 2 pi m (k odd) or
    2 pi (m + 1) - a (k even), a = acos(-0.6), m = (k - 1) // 2 (closed form)."""
    a, m = math.acos(-0.6), (k - 1) // 2
    return (a + 2.0 * math.pi * m if k % 2 else 2.0 * math.pi * (m + 1) - a) / 3000.0


@pytest.mark.slow
@pytest.mark.parametrize(
    "t_max",
    [8.192 * math.pi, 33.82, 2094.0, 5631.0, 45090.0, 1.075, 642.1, 241700.0],
    ids=lambda t_max: f"{t_max:g}",
)
def test_every_swing_of_a_fast_cosine_law_is_counted_whatever_t_max(t_max: float) -> None:
    """s = 0.01 cos(3000 t) on a slot (period 2.1 ms) passes T at s = -6 mm twice a period, at
    the closed-form times of ``_kth_swing``: the 1st, 2nd, 3rd and 2001st (2.0951 s) must be
    found whatever t_max. Before the fix the first was reported at 0.034 s (t_max = 8.192 pi
    s: every sample of the first window a whole number of periods after the one before),
    0.141 s (33.82 s), 2.62 s (2094 s), 1.62 s (5631 s) or 35.4 s (45090 s): a silent wrong
    answer. The other three t_max (random, like the four before them: log-uniform in
    [1, 1e6] s, seed 7) were right before."""
    doc = _slot("0.01*cos(3000*t)", [0.25, 0.25], {"T": -0.006})
    for k in (1, 2, 3):
        _assert_exact_time(_time(doc, "T", k, t_max), _kth_swing(k), f"swing {k}")
    if t_max > _kth_swing(2001):
        _assert_exact_time(_time(doc, "T", 2001, t_max), _kth_swing(2001), "swing 2001")


@pytest.mark.parametrize("scale", [1e-3, 1e-6], ids=["millimetres", "micrometres"])
def test_crossings_of_a_fast_law_are_found_at_any_scale(scale: float) -> None:
    """The law of ``test_crossings_of_a_fast_law_are_found_whatever_t_max`` with its lengths
    scaled (the slot, T and s = scale (0.01 sin(1000 t) - t)): the same two crossings, the
    mpmath roots (1e-9), with t_max = 99 s (where the sampled turns of s'' alias) and 1e6 s (scale
    invariance). At these scales |s'| < 1 m/s and |s''| < 1 m/s^2 nearly everywhere, so a
    one-sign test of the rates' ranges must compare them with 0, not with a length."""
    doc = _slot(f"{scale!r}*(0.01*sin(1000*t) - t)", [0.25 * scale, 0.25 * scale], {})
    doc["points"]["L"] = [1.25 * scale, 0.25 * scale]
    doc["points"]["T"] = [(0.25 + 0.005) * scale, 0.25 * scale]
    doc["links"]["disc"]["points"].append("T")
    first, second = _fast_law_roots()
    for t_max in (99.0, 1e6):
        _assert_exact_time(_time(doc, "T", 1, t_max), first, f"first, t_max {t_max:g}")
        _assert_exact_time(_time(doc, "T", 2, t_max), second, f"second, t_max {t_max:g}")


@pytest.mark.parametrize("t_max", [99e-9, 1e-3])
def test_a_fast_law_a_billion_times_faster_crosses_a_billion_times_sooner(t_max: float) -> None:
    """s = 0.01 sin(1e12 t) - 1e9 t: the law of ``_fast_law_roots`` with time scaled by 1e-9,
    searched up to 99 ns and 1 ms (99 s and 1e6 s scaled). Its crossings are 1e-9 of the
    mpmath roots; on the carrier the times are resolved to 1e-15 max(1, t) s (Brent's
    tolerance), so they are checked to 1e-15 s."""
    doc = _slot("0.01*sin(1e12*t) - 1e9*t", [0.25, 0.25], {"T": 0.005})
    for k, want in enumerate(_fast_law_roots(1e-9), start=1):
        got = _time(doc, "T", k, t_max)
        assert abs(got - want) <= 1e-15, f"crossing {k}: got {got!r}, want {want!r}"


def test_too_fast_a_law_is_refused_when_the_samples_run_out(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    """s = 0.2 sin(1000 t) never reaches T (0.3 m along the slot); the search windows shrink
    until s' or s'' keeps one sign between two samples (59 ms, 52 deg of its phase between
    samples; twice as wide is tried after each), so up to t_max = 60 s it evaluates the law
    about 300 000 times (2000 windows of 65 samples, and Brent's method at its 19 000 turning
    points). With the limit lowered to 6500 evaluations the search is refused (limit_exceeded),
    with the limit and t_max in the message."""
    monkeypatch.setattr(events, "MAX_SEARCH_SAMPLES", 6500)
    doc = _slot("0.2*sin(1000*t)", [0.25, 0.25], {"T": 0.3})
    message = r"M moves too fast to search up to t_max = 60 s \(more than 6500 samples\)"
    with pytest.raises(LimitExceeded, match=message):
        _time(doc, "T", 1, 60.0)


@pytest.mark.slow
def test_the_sample_limit_counts_brents_evaluations(monkeypatch: pytest.MonkeyPatch) -> None:
    """s = 1000 t on a circle of radius 1 mm passes T (0.5 rad along it) every 6.28 us: 7958
    times by t_max = 0.05 s (closed form: (0.05 s x 1000 m/s - 0.5 mm) / 2 pi mm, rounded
    up), so occurrence 10 000 is no_event. The law is monotonic, so the 64 windows of 65
    samples are never narrowed (4160 samples); the crossings cost Brent's method about 10
    evaluations each. With the limit lowered to 20 000 evaluations the search is refused:
    the limit bounds all the work, not only the windows' samples."""
    R = 1e-3
    points = {
        "C": [0.3, -0.2],
        "S": [0.3 + R, -0.2],
        "T": [0.3 + R * math.cos(0.5), -0.2 + R * math.sin(0.5)],
    }
    doc = _disc("1000*t", {"type": "arc", "center": "C", "start": "S", "direction": "ccw"}, points)
    with pytest.raises(NoEvent, match=r"M reaches T 7958 time\(s\) in 0 < t <= 0.05 s"):
        _time(doc, "T", 10_000, 0.05)
    monkeypatch.setattr(events, "MAX_SEARCH_SAMPLES", 20_000)
    with pytest.raises(LimitExceeded, match=r"more than 20000 samples"):
        _time(doc, "T", 10_000, 0.05)


def test_the_limit_counts_each_window_and_its_pieces_ends(monkeypatch: pytest.MonkeyPatch) -> None:
    """s = 0.01 t never reaches T (2 m along the slot; s(64) = 0.64 m). s' = 0.01 > 0, so no
    window is narrowed: up to t_max = 64 s the search marches 64 windows of 1 s, each evaluated
    at its WINDOW + 1 = 65 samples and, as one monotonic piece, at its two ends (hand count).
    The limit is checked after each window's samples, last at 63 x 67 + 65 = 4286 evaluations:
    a limit of 4286 lets the search end (no_event), 4285 refuses it."""
    doc = _slot("0.01*t", [0.25, 0.25], {"T": 2.0})
    last_check = (events.WINDOW - 1) * (events.WINDOW + 3) + events.WINDOW + 1
    assert last_check == 4286
    monkeypatch.setattr(events, "MAX_SEARCH_SAMPLES", last_check)
    with pytest.raises(NoEvent, match=r"M reaches T 0 time\(s\)"):
        _time(doc, "T", 1, 64.0)
    monkeypatch.setattr(events, "MAX_SEARCH_SAMPLES", last_check - 1)
    with pytest.raises(LimitExceeded, match=r"more than 4285 samples"):
        _time(doc, "T", 1, 64.0)


def test_two_crossings_closer_than_the_resolution_are_one_meeting() -> None:
    """s = ((t - 1)^2 - 1e-10)(2e4 - t) on a slot crosses its start S at 1 -+ 1e-5 s and at
    2e4 s (closed form: the roots of the factors). Searched up to t_max = 1e6 s the answer is
    resolved to 1e-10 t_max = 1e-4 s, so the two crossings 2e-5 s apart are one meeting (at
    the first of them) and the second meeting is the one at 2e4 s (a search that stopped once
    it had two crossings would count them as one and answer no_event). Up to
    t_max = 10 s (resolution 1e-9 s) they are two meetings, and the only ones."""
    doc = _slot("((t - 1)^2 - 1e-10)*(2e4 - t)", [0.25, 0.25], {})
    _assert_exact_time(_time(doc, "S", 1, 1e6), 1.0 - 1e-5, "the pair, as one meeting")
    _assert_exact_time(_time(doc, "S", 2, 1e6), 2e4, "the root at 2e4 s")
    with pytest.raises(NoEvent, match=r"M reaches S 2 time\(s\)"):
        _time(doc, "S", 3, 1e6)
    _assert_exact_time(_time(doc, "S", 1, 10.0), 1.0 - 1e-5, "first up to 10 s")
    _assert_exact_time(_time(doc, "S", 2, 10.0), 1.0 + 1e-5, "second up to 10 s")
    with pytest.raises(NoEvent, match=r"M reaches S 2 time\(s\)"):
        _time(doc, "S", 3, 10.0)


def test_a_crossing_at_the_resolution_of_t_zero_is_the_start() -> None:
    """s = 1e-6 (t - 1e-7)(t - 5e5) on a slot from S: M is 5e-8 m ahead of S at
    t = 0 and crosses it at 1e-7 s and at 5e5 s. Searched up to t_max = 1e6 s, times are
    resolved to 1e-12 t_max = 1e-6 s, so the crossing at 1e-7 s is the start itself (t = 0
    does not count; reading of 'after t = 0'): the first meeting is the one at 5e5 s (closed
    form), and there is no second."""
    doc = _slot("1e-6*(t - 1e-7)*(t - 5e5)", [0.25, 0.25], {})
    _assert_exact_time(_time(doc, "S", 1, 1e6), 5e5, "the root at 5e5 s")
    with pytest.raises(NoEvent):
        _time(doc, "S", 2, 1e6)


# --- targets off M's carrier: the distance search ---


def _counter_rotating(
    delta: float, scale: float = 1.0, wide: float = 0.0, rate: float = 1.0
) -> dict[str, Any]:
    """Two cranks pivoted at O = (0.3, -0.2) scale: the arm turns at rate/2 and M runs round
    the arm's circle of radius R = 0.3 scale at rate/2 relative to it (so at ``rate`` in all);
    the wheel turns at -``rate`` and carries P, ``delta`` rad ahead of M's start, at radius
    R (1 + ``wide``). With wide = 0, M meets P where 2 rate t = delta + 2 pi (k - 1), at equal
    and opposite speeds; otherwise they pass R wide apart."""
    ox, oy, R, a0 = 0.3 * scale, -0.2 * scale, 0.3 * scale, 0.4
    r_p = R * (1.0 + wide)
    return {
        "kind": "linkage",
        "title": "two cranks turning in opposite senses",
        "points": {
            "O": [ox, oy],
            "S": [ox + R * math.cos(a0), oy + R * math.sin(a0)],
            "P": [ox + r_p * math.cos(a0 + delta), oy + r_p * math.sin(a0 + delta)],
        },
        "links": {
            "ground": {"points": ["O"], "ground": True},
            "arm": {"points": ["O", "S"]},
            "wheel": {"points": ["O", "P"]},
        },
        "joints": [
            {"type": "revolute", "point": "O", "links": ["ground", "arm"]},
            {"type": "revolute", "point": "O", "links": ["ground", "wheel"]},
        ],
        "drivers": [
            {"link": "arm", "angle_law": f"{0.5 * rate!r}*t"},
            {"link": "wheel", "angle_law": f"-{rate!r}*t"},
        ],
        "moving_points": [
            {
                "name": "M",
                "link": "arm",
                "path": {"type": "arc", "center": "O", "start": "S", "direction": "ccw"},
                "s_law": f"{0.5 * rate * R!r}*t",
            }
        ],
    }


@pytest.mark.parametrize("scale", [1e-3, 1.0, 1e3])
def test_counter_rotating_cranks_meet_at_the_closed_form_times(scale: float) -> None:
    """M and P (a point of another crank, moving) meet at t_k = (0.5 + 2 pi (k - 1)) / 2 s; the
    first at 0.25 s. The pivot is off the origin and the two speeds are equal and opposite at
    each meeting. Same times at every scale (scale invariance); t_max = 10 s holds four; the
    position is P's closed form, R (cos, sin)(a0 + 0.5 - t) about O, to 1e-9 of the scale."""
    doc = _counter_rotating(0.5, scale)
    for k in (1, 2, 4):
        _assert_exact_time(
            _time(doc, "P", k, 10.0), (0.5 + 2 * math.pi * (k - 1)) / 2, f"meeting {k}"
        )
    with pytest.raises(NoEvent):
        _time(doc, "P", 5, 10.0)
    event = solver.find_event(doc, "M", "P", 2, 10.0)
    angle = 0.4 + 0.5 - float(event["time"])
    want = scale * np.array([0.3 + 0.3 * math.cos(angle), -0.2 + 0.3 * math.sin(angle)])
    np.testing.assert_allclose(event["position"], want, rtol=0, atol=1e-9 * scale)


@pytest.mark.parametrize("scale", [1e-3, 1.0, 1e3])
def test_a_pass_wide_of_the_target_is_not_a_meeting_at_any_scale(scale: float) -> None:
    """The same cranks with P on a circle 1e-4 R wider than M's: at their closest M and P are
    1e-4 R = 3e-5 scale m apart, 5e-5 of the scene's size (far above the coincidence
    tolerance, 1e-7 of the size): no meeting, in millimetres, metres or kilometres."""
    with pytest.raises(NoEvent, match=r"M reaches P 0 time\(s\)"):
        _time(_counter_rotating(0.5, scale, wide=1e-4), "P", 1, 10.0)


def test_meetings_within_the_first_and_last_sample_of_the_distance_grid() -> None:
    """The distance is sampled at 4097 instants over [0, t_max]. With t_max = 4.096 s (a sample
    every 1 ms), a first meeting 0.7 ms after t = 0 (cranks 1.4 mrad apart) and a second one
    0.7 ms before t_max: both found, at (delta + 2 pi (k - 1)) / 2 (closed form)."""
    t_max = 4.096
    delta = 2 * 0.7e-3
    doc = _counter_rotating(delta)
    _assert_exact_time(_time(doc, "P", 1, t_max), 0.7e-3, "first, 0.7 ms after 0")
    t_2 = (0.5 + 2 * math.pi) / 2
    last = t_2 / (1.0 - 0.7 / 4096)  # t_max with t_2 0.7 sample-intervals before it
    _assert_exact_time(
        _time(_counter_rotating(0.5), "P", 2, last), t_2, "second, 0.7 ms before t_max"
    )


def test_meetings_nearer_the_ends_of_the_distance_grid_than_its_next_sample() -> None:
    """As above with the meetings 0.3 ms from t = 0 and from t_max (a sample every 1 ms):
    t_1 = 0.3 ms and t_2 = (0.5 + 2 pi) / 2 s must both be found (closed form)."""
    t_max = 4.096
    _assert_exact_time(_time(_counter_rotating(2 * 0.3e-3), "P", 1, t_max), 0.3e-3, "first")
    t_2 = (0.5 + 2 * math.pi) / 2
    last = t_2 / (1.0 - 0.3 / 4096)
    _assert_exact_time(_time(_counter_rotating(0.5), "P", 2, last), t_2, "second")


def test_fast_cranks_meet_within_a_bracket_of_one_sample_either_side() -> None:
    """The cranks at rate 1000 rad/s with P 4.6 rad ahead, t_max = 4.096 s (a distance sample
    every 1 ms): the relative angle psi = 2000 t - 4.6 rad advances 2 rad a sample, and
    |M - P| = 2 R |sin(psi / 2)| peaks pi rad (1.57 samples) either side of each meeting. The
    meetings t_k = (4.6 + 2 pi (k - 1)) / 2000 s (closed form; the first 0.3 sample after
    sample 2) are found only if the rate of approach is bracketed by the samples next to the
    nearest one: a wider bracket holds a peak, where the rate has the same sign."""
    doc = _counter_rotating(4.6, rate=1000.0)
    for k in (1, 2, 3, 10):
        _assert_exact_time(_time(doc, "P", k, 4.096), (4.6 + 2 * math.pi * (k - 1)) / 2000, f"{k}")


def test_cranks_a_billion_times_faster_meet_a_billion_times_sooner() -> None:
    """The cranks of ``test_counter_rotating_cranks_meet_at_the_closed_form_times`` at
    1e9 rad/s, searched up to t_max = 10 ns: they meet at t_k = (0.5 + 2 pi (k - 1)) / 2e9 s
    (closed form), checked to 1e-9 relative to t (the distance search resolves times to
    1e-15 t_max). The grid brackets a meeting within 5 ps, so Brent's method must be asked
    for a tolerance relative to t_max, not an absolute one."""
    doc = _counter_rotating(0.5, rate=1e9)
    for k in (1, 2, 4):
        want = (0.5 + 2 * math.pi * (k - 1)) / 2e9
        got = _time(doc, "P", k, 1e-8)
        assert abs(got - want) <= 1e-9 * want, f"meeting {k}: got {got!r}, want {want!r}"


@pytest.mark.slow
def test_fast_oscillation_far_from_a_ground_point_is_no_event() -> None:
    """M shakes along a slot in a burst, s = 0.01 sin(1000 t) exp(-50 (t - 5)^2) (period 6.3 ms,
    2.4 ms between the distance samples at t_max = 10 s), 0.3 m from a ground point G: the
    sampled distance has local minima between which its rate has one sign; M is never nearer G
    than 0.29 m, so there is no meeting (and no error)."""
    doc = _slot("0.01*sin(1000*t)*exp(-50*(t - 5)^2)", [0.3, 0.0], {})
    doc["points"]["G"] = [0.3, 0.3]
    doc["links"]["ground"]["points"].append("G")
    with pytest.raises(NoEvent, match=r"M reaches G 0 time\(s\)"):
        _time(doc, "G", 1, 10.0)


def _four_bar(B: list[float], C: list[float], G: list[float], s_law: str) -> dict[str, Any]:
    """A(0, 0), B, C, D(1, 0) drawn as given (the link lengths are the drawn distances); the crank
    AB turns at 1 rad/s from its drawn angle; M moves on a slot of the coupler from B through C
    by ``s_law``; G is a ground point."""
    doc = build_preset("four_bar", {})  # its links and joints; the points drawn as given
    doc["points"] = {"A": [0.0, 0.0], "B": B, "C": C, "D": [1.0, 0.0], "G": G}
    doc["links"]["ground"]["points"].append("G")
    doc["links"]["coupler"]["points"] = ["B", "C"]
    doc["drivers"] = [{"link": "crank", "angle_law": "t"}]
    doc["moving_points"] = [
        {
            "name": "M",
            "link": "coupler",
            "path": {"type": "line", "start": "B", "through": "C"},
            "s_law": s_law,
        }
    ]
    return doc


def test_search_past_the_reach_of_the_linkage_is_refused_with_its_reason() -> None:
    """Crank AB = 0.6, coupler BC = 0.5, rocker DC = 0.3, ground AD = 1 m, drawn with the crank
    at 0 deg: B = (0.6, 0), and C = (1, 0.3) closes the loop (|BD| = 0.4, a 0.3-0.4-0.5
    triangle). The loop closes only while |BD| <= 0.8 m, i.e. while the crank is within
    acos((0.36 + 1 - 0.64) / 1.2) = 53.1 deg of the ground line. Searching 10 s at 1 rad/s for
    a ground point is refused (not_assemblable), saying it happened while searching."""
    B = np.array([0.6, 0.0])
    C = [1.0, 0.3]
    doc = _four_bar(B.tolist(), C, [0.5, -2.0], "0.25")
    with pytest.raises(NotAssemblable, match=r"cannot be closed while searching for the event"):
        _time(doc, "G", 1, 10.0)


def test_meeting_on_the_carrier_where_the_linkage_cannot_close_is_refused() -> None:
    """The same four-bar (it closes only while the crank is within 53.1 deg of the ground line);
    M runs along the coupler at s = 0.5 t and reaches C (s = |BC| = 0.5) at t = 1 s, when the
    crank has turned 1 rad = 57.3 deg: the time is known without assembling, but there is no
    position, so the event is refused (not_assemblable) and the message gives the time."""
    doc = _four_bar([0.6, 0.0], [1.0, 0.3], [0.5, -2.0], "0.5*t")
    with pytest.raises(NotAssemblable, match=r"the linkage cannot be closed at t = 1 s: "):
        _time(doc, "C", 1, 10.0)


def _parallelogram(drawn_deg: float, G: list[float], s_law: str = "0.5") -> dict[str, Any]:
    """Crank AB = rocker DC = 0.4, coupler BC = ground AD = 1, drawn as a parallelogram
    (C = B + (1, 0)) with the crank at ``drawn_deg``. Followed continuously it stays one
    (through its change points at 0 and 180 deg), so the coupler translates and its middle,
    M at s = 0.5, is (0.5, 0) + 0.4 (cos, sin) theta: a circle."""
    t = math.radians(drawn_deg)
    B = [0.4 * math.cos(t), 0.4 * math.sin(t)]
    return _four_bar(B, [B[0] + 1.0, B[1]], G, s_law)


def _crossed(theta: float) -> np.ndarray:
    """The middle of the coupler of the same four-bar assembled crossed (an antiparallelogram)
    at crank angle theta: C reflected from B + (1, 0) across the line BD."""
    B = 0.4 * np.array([math.cos(theta), math.sin(theta)])
    u = (np.array([1.0, 0.0]) - B) / math.hypot(1.0 - B[0], B[1])
    w = np.array([1.0, 0.0])
    C = B + 2.0 * float(w @ u) * u - w
    return np.asarray(0.5 * (B + C))


def test_point_of_the_crossed_assembly_is_never_reached_by_the_parallelogram() -> None:
    """The parallelogram drawn at 60 deg, turned at 1 rad/s for 10 s, stays a parallelogram:
    M runs round the circle (0.5, 0) + 0.4 (cos, sin) theta. G is where M would be at crank
    270 deg if the linkage had switched to its crossed assembly after the change point at
    180 deg: 0.19 m off M's circle, so M never reaches G."""
    G = _crossed(math.radians(270.0))
    assert abs(math.hypot(G[0] - 0.5, G[1]) - 0.4) > 0.1  # G is off the parallelogram's circle
    with pytest.raises(NoEvent, match=r"M reaches G 0 time\(s\)"):
        _time(_parallelogram(60.0, G.tolist()), "G", 1, 10.0)


@pytest.mark.parametrize("t_max", [10.0, 7.0])
def test_parallelogram_meets_a_ground_point_past_its_change_point(t_max: float) -> None:
    """The parallelogram drawn at 60 deg, at 1 rad/s: M is at G = (0.5, 0) + 0.4 (cos, sin)
    200 deg when the crank has turned 140 deg, t = 140 pi / 180 s (closed form, 1e-6), past
    one change point (180 deg). By t_max = 10 s the crank passes three (633 deg), by 7 s two
    (461 deg): the branch at the meeting is that after one switch, not the one at t_max."""
    G = [0.5 + 0.4 * math.cos(math.radians(200.0)), 0.4 * math.sin(math.radians(200.0))]
    _assert_exact_time(_time(_parallelogram(60.0, G), "G", 1, t_max), math.radians(140.0), "", 1e-6)


def _event_position_on_the_parallelogram(drawn_deg: float, speed: float, t_max: float) -> None:
    """M runs along the coupler of the parallelogram drawn at ``drawn_deg`` at s = speed t and
    reaches C (s = 1) at t = 1 / speed (closed form); the crank, at 1 rad/s, is then at
    drawn_deg + 1 / speed rad, and C = (1, 0) + 0.4 (cos, sin) of that (to 1e-9 m)."""
    event = solver.find_event(
        _parallelogram(drawn_deg, [0.5, -2.0], f"{speed!r}*t"), "M", "C", 1, t_max
    )
    _assert_exact_time(float(event["time"]), 1.0 / speed, "time")
    theta = math.radians(drawn_deg) + 1.0 / speed
    want = [1.0 + 0.4 * math.cos(theta), 0.4 * math.sin(theta)]
    np.testing.assert_allclose(event["position"], want, rtol=0, atol=1e-9)


@pytest.mark.slow
@pytest.mark.parametrize(
    ("drawn_deg", "speed", "t_max"),
    [(60.0, 0.25, 10.0), (150.0, 0.25, 10.0), (60.0, 0.01, 1000.0), (60.0, 0.002, 1000.0)],
)
def test_event_position_past_the_change_point_is_on_the_parallelogram(
    drawn_deg: float, speed: float, t_max: float
) -> None:
    """``_event_position_on_the_parallelogram``: drawn at 60 deg, reaching C at t = 4 s (crank
    at 289 deg, past one change point); drawn at 150 deg (past 180 deg after 0.52 s, so the
    linkage must be followed from t = 0, not from some later instant); and after 100 and
    500 rad of the crank (32 and 159 change points), followed with the samples of the search
    (4096 over t_max = 1000 s)."""
    _event_position_on_the_parallelogram(drawn_deg, speed, t_max)


@pytest.mark.slow
@pytest.mark.parametrize("t_max", [1e4, 1e5])
def test_event_position_after_thousands_of_change_points(t_max: float) -> None:
    """``_event_position_on_the_parallelogram`` with s = 2e-4 t: C is reached at t = 5000 s,
    the crank past 1592 change points, followed on the search's grid (4096 samples over t_max:
    2.4 and 24 rad of the crank per sample), split into steps of at most
    ``assembly.MAX_DRIVER_STEP``. Followed at 24 rad a sample as it was, the position was that
    of the crossed assembly, 0.44 m off."""
    _event_position_on_the_parallelogram(60.0, 2e-4, t_max)


def test_a_groove_with_an_end_has_no_whole_turns_and_nothing_past_its_end() -> None:
    """On a groove of sweep 180 deg (seed 003 Task 1's semicircle) s = c t^2 reaches a target an
    arc R beta along it once, at sqrt(R beta / c); a second occurrence (a whole turn later on a
    circle) and a target past the end are no events."""
    radius, c, beta = 0.4, 0.9, 1.0
    doc = arc_disc(f"{c}*t^2", radius, (0.1, 0.5), 0.3, "cw", radius * beta)
    doc["moving_points"][0]["path"]["sweep_deg"] = 180
    _assert_time(_event_time(doc, "T", 1, 60.0), math.sqrt(radius * beta / c), "first", 1e-9)
    with pytest.raises(NoEvent):
        _event_time(doc, "T", 2, 60.0)
    beyond = arc_disc(f"{c}*t^2", radius, (0.1, 0.5), 0.3, "cw", radius * 4.0)
    beyond["moving_points"][0]["path"]["sweep_deg"] = 180
    with pytest.raises(NoEvent, match="past the end of the groove"):
        _event_time(beyond, "T", 1, 60.0)

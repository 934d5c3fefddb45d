"""Tests of solver.analysis.events.find_event: the occurrence-th instant after t = 0 at which a
moving point
M reaches a named point (scene-v1 ``POST /api/v1/events``; issue 3: "never misses a crossing
between samples ... reports no_event when none occurs before t_max").

Sources of the expected times:

- the seed-003 reference cases (tests/reference/seed-cases.json; ERRATA.md, Seed 003: "Event times
  are right");
- closed forms (s = c t^2 on a circle: the k-th return to a point an arc beta past the start is at
  t_k = sqrt((R beta + 2 pi R (k - 1)) / c); uniform motion on a circle: t_k = (beta + 2 pi k) / w);
- an independent dense scan written here: s(t) - level sampled with at least 64 samples per period
  of the law, sign changes bracketed and bisected to 1e-13 s.

Tolerances: 1e-6 relative to max(1, t) (the rule of the reference cases for unit group t) unless
a test says otherwise.
"""

from __future__ import annotations

import json
import math
import multiprocessing
from pathlib import Path
from typing import Any

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from solver.analysis.events import find_event
from solver.errors import NoEvent
from solver.model.scene import parse_linkage

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


def _event_in_child(
    doc: dict[str, Any], reaches: str, occurrence: int, t_max: float, conn: Any
) -> None:
    try:
        conn.send(("ok", _event_time(doc, reaches, occurrence, t_max)))
    except Exception as exc:  # reported to the parent
        conn.send(("error", f"{type(exc).__name__}: {exc}"))


def _event_time_within(
    doc: dict[str, Any], reaches: str, occurrence: int, t_max: float, bound: float
) -> float:
    """The event's time, computed in a forked child that is terminated after ``bound`` seconds
    (the test fails then), so that a slow search cannot hold up the suite."""
    ctx = multiprocessing.get_context("fork")
    parent, child = ctx.Pipe(duplex=False)
    process = ctx.Process(target=_event_in_child, args=(doc, reaches, occurrence, t_max, child))
    process.start()
    try:
        answered = parent.poll(bound)
        result = parent.recv() if answered else None
    finally:
        if process.is_alive():
            process.terminate()
        process.join(5.0)
    assert result is not None, f"find_event(t_max = {t_max:g} s, {occurrence}) took > {bound} s"
    assert result[0] == "ok", result[1]
    return float(result[1])


def test_first_occurrence_cost_does_not_grow_with_t_max() -> None:
    """S003 Task 2 asked for its first return with t_max = 1000 s (allowed: the limit is 1e6 s).
    The answer is t = 1.474810 s, as with t_max = 60 s; the search must not enumerate every
    later crossing first (0.2356 t + 0.7069 t^2 passes S about 375 000 times by t = 1000 s).
    Bound: 8 s (the t_max = 60 s search takes ~0.2 s)."""
    doc = _case("S003-T2-rotating-carrier")["requests"][2]["body"]["scene"]
    _assert_time(_event_time_within(doc, "S", 1, 1000.0, 8.0), 1.4748096336326841, "first return")


def test_a_search_stops_at_the_occurrence_inside_a_window() -> None:
    """s = 1000 t on a circle of radius 1 mm passes T (0.5 rad along it) every 2 pi mm / 1000
    m/s = 6.28 us, at t_k = (0.5 mm + 2 pi mm (k - 1)) / 1000 m/s (closed form); the first
    search window, t_max / 64 = 15.6 s long for t_max = 1000 s, holds 2.5 million of these
    crossings. The 1st and the 10 000th (the largest occurrence allowed) must be found without
    finding the others of that window first (before the fix they all were: more than a
    minute). Bound: 8 s each (about 0.1 s and 1 s here); tolerance 1e-9 relative to
    max(1, t)."""
    R = 1e-3
    doc = arc_disc("1000*t", R, (0.3, -0.2), 0.4, "ccw", 0.5 * R)
    for k in (1, 10_000):
        want = (0.5 * R + 2.0 * math.pi * R * (k - 1)) / 1000.0
        _assert_time(_event_time_within(doc, "T", k, 1000.0, 8.0), want, f"crossing {k}", 1e-9)


# --- where the event happens, meetings at t_max, bad requests (mutation testing, issue 8) ---


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

"""The linkage drawing as Linkage and MotionGen users expect it: zoom and pan (wheel, pinch,
drag on empty space, the buttons, the keys) kept across frames; a point's readout (position,
velocity, acceleration at the instant) and its path traced from the sweep already fetched; the
instant-centre layer with Kennedy's line of a chosen triple.

Checked against closed forms of the default four-bar (crank AB = 0.15 m about A at the origin,
240 rpm = 8 pi rad/s, no angular acceleration: |v_B| = 0.15 * 8 pi, |a_B| = 0.15 * (8 pi)^2)
and against properties that a wrong drawing would break (a point under the pointer stays under
it while zooming; the path of B is a circle about A; I_12, I_23, I_34, I_14 at the joints and I_13,
I_24 where Kennedy's lines cross). Real server, real CSP (conftest.app).
"""

from __future__ import annotations

import math
import re
from typing import Any

import pytest

from tests.browser.conftest import AppPage
from tests.browser.test_app import pause_and_wait, wait_analysed, wait_until

pytestmark = pytest.mark.browser

CRANK = 0.15  # m, the four-bar preset's crank AB
OMEGA = 8 * math.pi  # rad/s, its 240 rpm


def point_at(page: Any, name: str) -> tuple[float, float]:
    """The on-screen centre of point `name`'s circle in the drawing (CSS px)."""
    box = page.locator(f"#linkage circle[data-point='{name}']").bounding_box()
    assert box is not None, name
    return box["x"] + box["width"] / 2, box["y"] + box["height"] / 2


def zoom(page: Any) -> float:
    return float(page.get_attribute("#linkage", "data-zoom"))


def empty_spot(page: Any) -> tuple[float, float]:
    """A spot of the drawing with nothing under it (near its top-right corner)."""
    box = page.locator("#linkage").bounding_box()
    assert box is not None
    return box["x"] + box["width"] - 30, box["y"] + 30


def test_zoom_and_pan_move_the_picture_and_are_kept_across_frames(app: AppPage) -> None:
    app.page.set_viewport_size({"width": 1440, "height": 900})
    app.open()
    page = app.page
    pause_and_wait(page)
    assert zoom(page) == 1
    a0, d0 = point_at(page, "A"), point_at(page, "D")
    span0 = math.dist(a0, d0)
    # The button zooms about the middle by 1.25: the fixed pivots 1.25 times as far apart.
    page.click("#zoom-in")
    assert zoom(page) == 1.25
    assert math.dist(point_at(page, "A"), point_at(page, "D")) == pytest.approx(
        1.25 * span0, rel=0.01
    )
    # The wheel zooms about the pointer: the pivot under it stays there (within a pixel).
    a1 = point_at(page, "A")
    page.mouse.move(*a1)
    page.mouse.wheel(0, -200)
    wait_until(lambda: zoom(page) > 1.25, what="the wheel zooming")
    assert math.dist(point_at(page, "A"), a1) < 1.0
    z = zoom(page)
    # A drag on empty space pans: every point follows the hand by the same offset.
    a2, d2 = point_at(page, "A"), point_at(page, "D")
    x, y = empty_spot(page)
    page.mouse.move(x, y)
    page.mouse.down()
    page.mouse.move(x - 80, y + 50, steps=5)
    page.mouse.up()
    for before, now in ((a2, point_at(page, "A")), (d2, point_at(page, "D"))):
        assert now[0] - before[0] == pytest.approx(-80, abs=1.5)
        assert now[1] - before[1] == pytest.approx(50, abs=1.5)
    assert zoom(page) == z, "panning keeps the zoom"
    assert page.get_attribute("#play", "aria-pressed") == "false", "a pan is no crank drag"
    # The zoom and the pan are kept while the mechanism plays, frame after frame.
    a3, d3 = point_at(page, "A"), point_at(page, "D")
    instant = page.get_attribute("#linkage", "data-instant")
    page.click("#play")
    wait_until(lambda: page.get_attribute("#linkage", "data-instant") != instant, what="frames")
    assert math.dist(point_at(page, "A"), a3) < 0.5
    assert math.dist(point_at(page, "D"), d3) < 0.5
    assert zoom(page) == z
    pause_and_wait(page)
    # Keys: with the drawing focused the arrows pan; − zooms out; 0 fits the whole mechanism.
    page.focus("#linkage")
    before = point_at(page, "A")
    page.keyboard.press("ArrowRight")
    assert point_at(page, "A")[0] < before[0] - 10
    page.keyboard.press("-")
    assert zoom(page) == pytest.approx(z / 1.25, rel=1e-3)
    page.keyboard.press("0")
    assert zoom(page) == 1
    assert math.dist(point_at(page, "A"), a0) < 1.0
    assert math.dist(point_at(page, "D"), d0) < 1.0
    # And the Fit button after a zoom.
    page.click("#zoom-out")
    assert zoom(page) == 0.8
    page.click("#zoom-fit")
    assert math.dist(point_at(page, "A"), a0) < 1.0


def test_a_two_finger_pinch_zooms_about_the_fingers(app: AppPage) -> None:
    app.open()
    page = app.page
    pause_and_wait(page)
    a0, d0 = point_at(page, "A"), point_at(page, "D")
    x, y = empty_spot(page)
    x -= 200
    y += 40
    cdp = page.context.new_cdp_session(page)

    def touch(kind: str, spread: float) -> None:
        points = (
            []
            if kind == "touchEnd"
            else [
                {"x": x - spread, "y": y, "id": 1},
                {"x": x + spread, "y": y, "id": 2},
            ]
        )
        cdp.send("Input.dispatchTouchEvent", {"type": kind, "touchPoints": points})

    touch("touchStart", 40)
    for spread in (50, 60, 70, 80):
        touch("touchMove", spread)
    touch("touchEnd", 80)
    cdp.detach()
    wait_until(lambda: zoom(page) > 1.5, what="the pinch zooming")
    # The fingers spread from 80 to 160 px apart: twice the scale, about their midpoint.
    assert zoom(page) == pytest.approx(2.0, rel=0.02)
    span = math.dist(point_at(page, "A"), point_at(page, "D"))
    assert span == pytest.approx(2 * math.dist(a0, d0), rel=0.02)


def readout_numbers(page: Any, kind: str) -> list[float]:
    text: str = page.locator(f"#point-readout .readout-{kind}").inner_text()
    return [float(v) for v in re.findall(r"-?\d+(?:\.\d+)?(?:e-?\d+)?", text.split("=", 1)[1])]


def test_a_picked_point_reads_out_its_motion_and_traces_its_path(app: AppPage) -> None:
    app.open()
    page = app.page
    pause_and_wait(page)
    sweeps = sum("/sweep" in u for u in app.log.requests)
    # A tap on B (the crank's end: a tap turns nothing) reads it out at the analysed instant.
    page.mouse.click(*point_at(page, "B"))
    page.wait_for_function(
        "() => document.getElementById('point-readout').dataset.point === 'B'"
        " && document.getElementById('point-readout').dataset.instant === 'analysed'"
    )
    assert page.input_value("#readout-point") == "B"
    theta = float(page.get_attribute("#linkage", "data-analysed"))
    x, y = readout_numbers(page, "length")
    assert x == pytest.approx(CRANK * math.cos(theta), abs=6e-4)
    assert y == pytest.approx(CRANK * math.sin(theta), abs=6e-4)
    vx, vy, v = readout_numbers(page, "velocity")
    assert v == pytest.approx(CRANK * OMEGA, rel=5e-4)
    # v_B is perpendicular to AB, turning counter-clockwise: omega k x r_AB.
    assert vx == pytest.approx(-CRANK * OMEGA * math.sin(theta), abs=2e-3)
    assert vy == pytest.approx(CRANK * OMEGA * math.cos(theta), abs=2e-3)
    *_, a = readout_numbers(page, "acceleration")
    assert a == pytest.approx(CRANK * OMEGA**2, rel=5e-4)
    assert page.locator("#linkage .picked-point").count() == 1
    # Its path: a circle of radius AB about A, from the sweep already fetched.
    page.check("#readout-trace")
    page.wait_for_selector("#linkage polyline.added-trace[data-trace='B']")
    radii = page.evaluate(
        """() => { const svg = document.getElementById('linkage');
                   const a = svg.querySelector("circle[data-point='A']");
                   const [cx, cy] = [+a.getAttribute('cx'), +a.getAttribute('cy')];
                   const line = svg.querySelector("polyline[data-trace='B']");
                   return line.getAttribute('points').trim().split(' ')
                     .map((p) => p.split(',').map(Number))
                     .map(([x, y]) => Math.hypot(x - cx, y - cy)); }"""
    )
    assert len(radii) > 100
    assert max(radii) - min(radii) < 0.05, "B's path is a circle about A (viewBox px, rounding)"
    # A second path at once (C, picked in the menu: the keyboard's way), each removable.
    page.select_option("#readout-point", "C")
    page.check("#readout-trace")
    page.wait_for_selector("#linkage polyline[data-trace='C']")
    assert page.locator("#linkage polyline.added-trace").count() == 2
    # Both survive playing, zooming and the readout follows the sweep's samples while playing.
    page.click("#play")
    page.wait_for_function(
        "() => (document.getElementById('point-readout').dataset.instant || '')"
        ".startsWith('sample')"
    )
    page.click("#zoom-in")
    assert page.locator("#linkage polyline.added-trace").count() == 2
    pause_and_wait(page)
    page.uncheck("#readout-trace")
    assert page.locator("#linkage polyline.added-trace").count() == 1
    page.click("#clear-traces")
    assert page.locator("#linkage polyline.added-trace").count() == 0
    assert sum("/sweep" in u for u in app.log.requests) == sweeps, "no sweep asked for a path"
    # Hovering another point reads it out until the pointer leaves it.
    page.mouse.move(*point_at(page, "D"))
    page.wait_for_function("() => document.getElementById('point-readout').dataset.point === 'D'")
    page.mouse.move(*empty_spot(page))
    page.wait_for_function("() => document.getElementById('point-readout').dataset.point === 'C'")


def readout_values(page: Any, name: str) -> dict[str, list[float]]:
    """Point `name`'s readout at the analysed instant: r, v, a (SI) as the page holds them
    unrounded (`#point-readout[data-values]`, the server's numbers)."""
    page.select_option("#readout-point", name)
    page.wait_for_function(
        """(name) => { const d = document.getElementById('point-readout').dataset;
                       return d.point === name && d.instant === 'analysed'; }""",
        arg=name,
    )
    values: dict[str, list[float]] = page.evaluate(
        "() => JSON.parse(document.getElementById('point-readout').dataset.values)"
    )
    return values


def cross(a: list[float], b: list[float]) -> float:
    return a[0] * b[1] - a[1] * b[0]


def test_a_point_picked_on_the_coupler_moves_with_it(app: AppPage) -> None:
    """A click on the coupler between B and C adds that point of the coupler (swept and
    analysed by the server); its v and a are the rigid body's, v_P = v_B + omega x BP and
    a_P = a_B + alpha x BP - omega^2 BP, with omega and alpha from the readouts of B and C
    (0.05 %); its path keeps its distances to B's and C's; Remove point takes it away."""
    app.open()
    page = app.page
    pause_and_wait(page)
    sweeps = sum("/sweep" in u for u in app.log.requests)
    b, c = point_at(page, "B"), point_at(page, "C")
    page.mouse.click(b[0] + 0.4 * (c[0] - b[0]), b[1] + 0.4 * (c[1] - b[1]))
    page.wait_for_function(
        "() => [...document.getElementById('readout-point').options].some((o) => o.value === 'P1')"
    )
    wait_analysed(page)
    assert sum("/sweep" in u for u in app.log.requests) > sweeps, "the server sweeps the new point"
    p = readout_values(page, "P1")
    text = page.inner_text("#point-readout")
    bv, cv = readout_values(page, "B"), readout_values(page, "C")
    bc = [cv["r"][i] - bv["r"][i] for i in range(2)]
    bp = [p["r"][i] - bv["r"][i] for i in range(2)]
    # Where it was clicked: 0.4 of the way from B to C, on the line (a pixel's play).
    along = (bp[0] * bc[0] + bp[1] * bc[1]) / (bc[0] ** 2 + bc[1] ** 2)
    assert along == pytest.approx(0.4, abs=0.02)
    assert abs(cross(bc, bp)) / math.hypot(*bc) < 0.01 * math.hypot(*bc)
    # The coupler's omega and alpha from B and C, then P's velocity and acceleration.
    dv = [cv["v"][i] - bv["v"][i] for i in range(2)]
    omega = cross(bc, dv) / (bc[0] ** 2 + bc[1] ** 2)
    da = [cv["a"][i] - bv["a"][i] + omega**2 * bc[i] for i in range(2)]
    alpha = cross(bc, da) / (bc[0] ** 2 + bc[1] ** 2)
    v_p = [bv["v"][0] - omega * bp[1], bv["v"][1] + omega * bp[0]]
    a_p = [
        bv["a"][0] - alpha * bp[1] - omega**2 * bp[0],
        bv["a"][1] + alpha * bp[0] - omega**2 * bp[1],
    ]
    assert math.dist(p["v"], v_p) <= 5e-4 * math.hypot(*v_p)
    assert math.dist(p["a"], a_p) <= 5e-4 * math.hypot(*a_p)
    # The text says the same numbers, rounded to 4 digits.
    shown = float(re.findall(r"\|v\s*P1\s*\| = (-?[\d.]+(?:e-?\d+)?)", text)[0])
    assert shown == pytest.approx(math.hypot(*p["v"]), rel=5e-4)
    # Its path, traced at once, keeps its distances to B and C (viewBox px, rounding).
    page.wait_for_selector("#linkage polyline.added-trace[data-trace='P1']")
    for name in ("B", "C"):
        page.select_option("#readout-point", name)
        page.check("#readout-trace")
        page.wait_for_selector(f"#linkage polyline[data-trace='{name}']")
    distances = page.evaluate(
        """() => { const svg = document.getElementById('linkage');
                   const path = (n) => svg.querySelector(`polyline[data-trace='${n}']`)
                     .getAttribute('points').trim().split(' ').map((q) => q.split(',').map(Number));
                   const [p, b, c] = ['P1', 'B', 'C'].map(path);
                   return p.map((q, i) => [Math.hypot(q[0] - b[i][0], q[1] - b[i][1]),
                                           Math.hypot(q[0] - c[i][0], q[1] - c[i][1])]); }"""
    )
    assert len(distances) > 100
    for k in (0, 1):
        column = [d[k] for d in distances]
        assert max(column) - min(column) < 0.05, "P1 keeps its distance to B and to C"
    app.screenshot("point-on-link", ".view-panel")
    # Removable: it leaves the scene, the menu and the drawing.
    page.select_option("#readout-point", "P1")
    page.click("#remove-point")
    page.wait_for_function(
        "() => ![...document.getElementById('readout-point').options].some((o) => o.value === 'P1')"
    )
    assert page.locator("#linkage [data-trace='P1'], #linkage [data-point='P1']").count() == 0
    assert page.is_hidden("#remove-point")


def centre_at(page: Any, links: str) -> tuple[float, float] | None:
    loc = page.locator(f"#linkage g.centre[data-links='{links}'] circle")
    if not loc.count():
        return None
    box = loc.bounding_box()
    assert box is not None
    return box["x"] + box["width"] / 2, box["y"] + box["height"] / 2


def off_line(p: tuple[float, float], a: tuple[float, float], b: tuple[float, float]) -> float:
    """Distance (px) of p from the line through a and b."""
    cross = (b[0] - a[0]) * (p[1] - a[1]) - (b[1] - a[1]) * (p[0] - a[0])
    return abs(cross) / math.dist(a, b)


@pytest.mark.slow
def test_instant_centres_and_kennedys_line(app: AppPage) -> None:
    app.open()
    page = app.page
    pause_and_wait(page)
    page.check("#show-centres")
    page.wait_for_selector("#linkage g.centre")
    joints = {n: point_at(page, n) for n in "ABCD"}
    # The pin joints are the centres of the links they join.
    for links, joint in (
        ("ground crank", "A"),
        ("crank coupler", "B"),
        ("coupler rocker", "C"),
        ("rocker ground", "D"),
    ):
        at = centre_at(page, links) or centre_at(page, " ".join(reversed(links.split())))
        assert at is not None, links
        assert math.dist(at, joints[joint]) < 1.0, links
    # Six centres in all, each once: drawn, or listed in a note (outside the picture); a centre
    # with the ground where the velocity poles mark it (I_13 here) is the pole's.
    texts = page.locator(
        "#linkage .centre-label, #linkage .pole-velocity_pole .pole-label, #linkage .view-note"
    ).all_text_contents()
    names = [n for t in texts for n in re.findall("I[₀-₉]+", t)]
    assert sorted(names) == ["I₁₂", "I₁₃", "I₁₄", "I₂₃", "I₂₄", "I₃₄"]
    # I13 (ground-coupler) on lines AB and DC; I24 (crank-rocker) on lines AD and BC.
    i13 = centre_at(page, "ground coupler") or centre_at(page, "coupler ground")
    if i13:
        assert off_line(i13, joints["A"], joints["B"]) < 1.0
        assert off_line(i13, joints["D"], joints["C"]) < 1.0
    i24 = centre_at(page, "crank rocker") or centre_at(page, "rocker crank")
    if i24:
        assert off_line(i24, joints["A"], joints["D"]) < 1.0
        assert off_line(i24, joints["B"], joints["C"]) < 1.0
    # Kennedy's line of links 1, 2, 4 (ground, crank, rocker) through I12, I24, I14.
    page.select_option("#kennedy-triple", "ground,crank,rocker")
    page.wait_for_selector("#linkage .kennedy-line", state="attached")
    ends = page.evaluate(
        """() => { const l = document.querySelector('#linkage .kennedy-line');
                   const m = l.getScreenCTM();
                   const p = (x, y) => {
                     const q = new DOMPoint(x, y).matrixTransform(m); return [q.x, q.y]; };
                   return [p(+l.getAttribute('x1'), +l.getAttribute('y1')),
                           p(+l.getAttribute('x2'), +l.getAttribute('y2'))]; }"""
    )
    for name in ("A", "D"):
        assert off_line(joints[name], ends[0], ends[1]) < 1.0, name
    assert page.locator("#linkage g.kennedy-centre").count() >= 2
    # No name over another: the centres' names, the points' names, the poles' names.
    boxes = page.evaluate(
        """() => [...document.querySelectorAll(
                   '#linkage .centre-label, #linkage .point-label, #linkage .pole-label')]
                 .map((t) => t.getBoundingClientRect())
                 .filter((r) => r.width > 0)
                 .map((r) => [r.left + 2, r.top + 2, r.right - 2, r.bottom - 2])"""
    )
    for i, a in enumerate(boxes):
        for b in boxes[i + 1 :]:
            assert not (a[0] < b[2] and b[0] < a[2] and a[1] < b[3] and b[1] < a[3]), (a, b)
    # Shown only at the analysed instant, like the poles.
    page.click("#play")
    page.wait_for_function(
        "() => document.querySelector('#linkage .layer-centres')"
        ".getAttribute('visibility') === 'hidden'"
    )
    pause_and_wait(page)
    assert app.serious_accessibility_violations() == []


@pytest.mark.slow
@pytest.mark.parametrize(("width", "height"), [(1440, 900), (1024, 768), (390, 844)])
def test_navigation_tools_fit_every_viewport(app: AppPage, width: int, height: int) -> None:
    app.page.set_viewport_size({"width": width, "height": height})
    app.open()
    page = app.page
    pause_and_wait(page)
    page.check("#show-centres")
    page.select_option("#kennedy-triple", "ground,crank,coupler")
    page.click("#zoom-in")
    page.mouse.click(*point_at(page, "C"))
    page.check("#readout-trace")
    wait_analysed(page)
    assert page.evaluate("document.documentElement.scrollWidth - window.innerWidth") <= 0
    for sel in ("#zoom-in", "#zoom-out", "#zoom-fit", "#readout-point", "#point-readout"):
        box = page.locator(sel).bounding_box()
        assert box is not None and box["x"] >= 0 and box["x"] + box["width"] <= width, sel
    app.screenshot(f"linkage-navigation-{width}x{height}", ".view-panel")
    assert app.serious_accessibility_violations() == []

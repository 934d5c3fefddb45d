"""Gear trains in the browser (issue 25): the "Gear trains" group of the mechanism menu, the train
drawn to scale with its teeth marks turning at the server's speeds and the carrier turning, the
table of speeds equal to /analyze, a field edited in the page (and a refused one, with the
server's message beside it), the worked solution typeset by KaTeX, the way back to a linkage;
screenshots at 1440x900, 1024x768 and 390x844 with nothing overlapping or cut off, and axe-core
on the panel. Real server, Debian's Chromium, real CSP.
"""

from __future__ import annotations

import math
from typing import Any

import pytest

from tests.browser.conftest import AppPage, pause
from tests.browser.test_app import choose

PLANETARY = "gear:planetary_ring_fixed"


def open_gears(app: AppPage, value: str = PLANETARY) -> Any:
    app.open()
    page = app.page
    page.wait_for_selector(f"#preset option[value='{value}']", state="attached")
    choose(app, value)
    page.wait_for_selector("#gear-view .gear", state="attached")
    page.wait_for_selector("#gear-steps .step", state="attached")
    return page


def table(page: Any) -> dict[str, float]:
    rows = page.eval_on_selector_all(
        "#gear-speeds tbody tr",
        "(rows) => rows.map((r) =>"
        " [r.dataset.member, r.querySelector('[data-omega]').dataset.omega])",
    )
    return {name: float(omega) for name, omega in rows}


def turned(page: Any) -> tuple[float, float]:
    """The sun's drawn rotation (deg, screen sense) and the arm's bar direction (rad, model
    sense), read in one go."""
    sun, bar = page.evaluate(
        "() => [document.querySelector('#gear-view [data-member=\"sun\"] g')"
        ".getAttribute('transform'),"
        " ['x1', 'y1', 'x2', 'y2'].map((k) => +document.querySelector("
        "'#gear-view [data-member=\"arm\"] line').getAttribute(k))]"
    )
    degrees = float(sun.removeprefix("rotate(").removesuffix(")"))
    x1, y1, x2, y2 = bar
    return -math.radians(degrees), math.atan2(-(y2 - y1), x2 - x1)


def unwrap(a: float) -> float:
    return (a + math.pi) % (2 * math.pi) - math.pi


@pytest.mark.moving
def test_planetary_train_turns_at_the_server_speeds(app: AppPage) -> None:
    page = open_gears(app)
    status, scene = app.post("/presets/planetary_ring_fixed", {})
    assert status == 200
    status, body = app.post("/analyze", {"scene": scene})
    assert status == 200
    assert table(page) == {n: m["omega"] for n, m in body["members"].items()}
    assert page.is_hidden("#linkage") and page.is_visible("#gear-view")
    # The sun turns 100/20 = 5 times as fast as the arm (Shigley: N_s / (N_s + N_r) = 1/5).
    sun0, arm0 = turned(page)
    page.wait_for_timeout(400)
    sun1, arm1 = turned(page)
    d_sun, d_arm = unwrap(sun1 - sun0), unwrap(arm1 - arm0)
    assert d_arm > 0.01, "the carrier does not turn"
    assert d_sun / d_arm == pytest.approx(100.0 / 20.0, rel=0.02)
    # the worked solution, typeset without a failing step
    assert page.locator("#gear-steps .katex").count() > 5
    assert page.locator("#gear-steps .step-error").count() == 0
    assert "Tabular method, carrier arm" in page.inner_text("#gear-steps")


def test_with_reduced_motion_the_train_opens_still_and_its_button_says_play(
    app: AppPage,
) -> None:
    """A student whose system asks for reduced motion (every test not marked moving) gets the
    train still and a Play button; Play then turns it. The button read Pause over a still
    train, so that a click meant to pause it started it."""
    page = open_gears(app)
    assert page.get_attribute("#gear-play", "aria-pressed") == "false"
    assert page.inner_text("#gear-play") == "Play"
    still = page.inner_text("#gear-readout")
    page.wait_for_timeout(300)
    assert page.inner_text("#gear-readout") == still
    page.click("#gear-play")
    assert page.get_attribute("#gear-play", "aria-pressed") == "true"
    page.wait_for_function(
        "(t) => document.getElementById('gear-readout').textContent !== t", arg=still
    )


def test_a_field_edited_in_the_page_asks_the_server_again(app: AppPage) -> None:
    page = open_gears(app)
    page.fill("#gear-f-N_planet", "40")
    page.dispatch_event("#gear-f-N_planet", "change")
    page.wait_for_function(
        "() => document.querySelector('#gear-speeds [data-member=\"ring\"] td').textContent"
        " === '100 int.'"
    )
    # omega_arm = 100 x 20 / (20 + 100)
    assert table(page)["arm"] == pytest.approx(100 * 20 / 120, rel=1e-12)
    app.log.allow("status of 422")
    page.fill("#gear-f-N_sun", "3")
    page.dispatch_event("#gear-f-N_sun", "change")
    page.wait_for_function(
        "() => document.getElementById('gear-f-N_sun').getAttribute('aria-invalid') === 'true'"
    )
    assert "N_sun" in page.inner_text("#gear-f-N_sun-error")
    assert table(page)["arm"] == pytest.approx(100 * 20 / 120, rel=1e-12)  # the view kept
    choose(app, "preset:four_bar")
    page.wait_for_selector("#linkage .link", state="visible")
    assert page.is_hidden("#gear-train")


@pytest.mark.slow
@pytest.mark.parametrize(("width", "height"), [(1440, 900), (1024, 768), (390, 844)])
def test_screens_and_accessibility(app: AppPage, width: int, height: int) -> None:
    app.page.set_viewport_size({"width": width, "height": height})
    page = open_gears(app, "gear:two_stage_planetary")
    pause(page, "#gear-play")  # still, for the picture
    page.wait_for_timeout(300)
    app.screenshot(f"gears-{width}x{height}", None)
    # nothing wider than the screen, the drawing whole on it, no two labels on each other
    assert page.evaluate("() => document.documentElement.scrollWidth") <= width
    box = page.locator("#gear-view").bounding_box()
    assert box["x"] >= 0 and box["x"] + box["width"] <= width
    labels = page.eval_on_selector_all(
        "#gear-view text",
        "(ts) => ts.map((t) => { const b = t.getBoundingClientRect();"
        " return [b.left, b.top, b.right, b.bottom]; })",
    )
    for i, a in enumerate(labels):
        assert a[0] >= box["x"] - 1 and a[2] <= box["x"] + box["width"] + 1, "label cut off"
        for b in labels[i + 1 :]:
            apart = a[2] <= b[0] or b[2] <= a[0] or a[3] <= b[1] or b[3] <= a[1]
            assert apart, f"labels overlap: {a} {b}"
    assert not app.serious_accessibility_violations("#gear-train")

"""The Cams view in the browser (issue 24, static/js/cam-view.js): a cam chosen in the mechanism
menu turns and its follower moves (one /sweep, no request while it plays), the SVAJ diagrams and
the pressure-angle and curvature plots carry a cursor at the angle shown, the follower sits on the
server's contact point, a law edited in the segment table asks the server again and shows its
warning, a refused edit shows the server's words and keeps the view, the worked solution at the
angle shown is typeset by KaTeX; screenshots at 1440x900, 1024x768 and 390x844 with nothing cut
off or overlapping, and axe-core on the section. Real server, Debian's Chromium, real CSP.
"""

from __future__ import annotations

import math
from typing import Any

import pytest

from tests.browser.conftest import AppPage, overlapping_pairs, pause, shown_boxes
from tests.browser.test_app import choose

ROLLER = "cam:cam_roller_translating"


def open_cam(app: AppPage, value: str = ROLLER) -> Any:
    app.open()
    page = app.page
    page.wait_for_selector(f"#preset option[value='{value}']", state="attached")
    choose(app, value)
    page.wait_for_selector("#cam-drawing .cam path", state="attached")
    page.wait_for_selector("#cam-svaj .main-svg", state="attached")
    return page


def _transform(page: Any) -> str:
    value: str = page.get_attribute("#cam-drawing .cam", "transform")
    return value


@pytest.mark.moving
def test_the_cam_turns_and_the_follower_moves_without_requests(app: AppPage) -> None:
    page = open_cam(app)
    assert page.locator("#cam-app").is_visible() and not page.locator("#linkage").is_visible()
    first = (_transform(page), page.get_attribute("#cam-drawing .roller", "cy"))
    before = len(app.log.requests)
    page.wait_for_function(
        "(t) => document.querySelector('#cam-drawing .cam').getAttribute('transform') !== t",
        arg=first[0],
    )
    page.wait_for_timeout(500)
    second = (_transform(page), page.get_attribute("#cam-drawing .roller", "cy"))
    assert second != first
    assert len([u for u in app.log.requests[before:] if "/api/" in u]) == 0  # played back


@pytest.mark.moving
def test_space_plays_and_pauses_the_cam(app: AppPage) -> None:
    """Space drives the cam shown, as it drives a linkage (not the hidden linkage view)."""
    page = open_cam(app)
    page.focus("#cam-angle")
    for pressed in ("false", "true"):
        page.keyboard.press("Space")
        page.wait_for_function(
            "(p) => document.getElementById('cam-play').getAttribute('aria-pressed') === p",
            arg=pressed,
        )


def test_while_the_cam_turns_its_worked_solution_waits_for_a_pause(app: AppPage) -> None:
    """The worked solution is that of the angle shown: while the cam turns there is none, so a
    message stands in its place and in the typical mistakes' (whose numbers are an angle's), not
    the last angle's solution under a turning cam; paused again, the solution at the new angle."""
    page = open_cam(app)
    page.wait_for_selector("#cam-steps .step .katex", state="attached")
    solved = page.input_value("#cam-angle")
    page.click("#cam-play")
    page.wait_for_selector("#cam-steps .panel-message")
    assert page.locator("#cam-steps .step").count() == 0
    assert page.get_attribute("#cam-steps", "data-angle") is None
    assert page.locator("#cam-mistakes li").count() == 0
    page.wait_for_function("(a) => document.getElementById('cam-angle').value !== a", arg=solved)
    page.click("#cam-play")
    page.wait_for_selector("#cam-steps .step .katex", state="attached")
    assert page.get_attribute("#cam-steps", "data-angle") == page.input_value("#cam-angle")
    assert page.locator("#cam-mistakes li").count() > 0


def test_paused_at_an_angle_the_drawing_plots_and_solution_agree_with_the_server(
    app: AppPage,
) -> None:
    page = open_cam(app)
    pause(page, "#cam-play")
    page.fill("#cam-angle", "60")
    page.dispatch_event("#cam-angle", "input")
    page.wait_for_function("() => document.getElementById('cam-steps').dataset.angle === '60'")
    page.wait_for_selector("#cam-steps .step .katex", state="attached")
    assert page.locator("#cam-steps .step-error").count() == 0
    titles = page.locator("#cam-steps .step-title").all_inner_texts()
    assert "The pressure angle" in titles and "The radius of curvature" in titles
    status, built = app.post("/presets/cam_roller_translating", {})  # the defaults shown
    assert status == 200
    status, at = app.post("/analyze", {"scene": built, "angle_deg": 60})
    assert status == 200
    readout = page.inner_text("#cam-readout")
    assert "θ = 60°" in readout and f"{at['follower']['velocity']:.4g}" in readout
    # the contact dot is the server's contact point (mm), the roller r from it
    cx = float(page.get_attribute("#cam-drawing .contact", "cx"))
    cy = float(page.get_attribute("#cam-drawing .contact", "cy"))
    assert cx == pytest.approx(at["contact_point"][0] * 1000, abs=1e-6)
    assert cy == pytest.approx(at["contact_point"][1] * 1000, abs=1e-6)
    rx = float(page.get_attribute("#cam-drawing .roller", "cx"))
    ry = float(page.get_attribute("#cam-drawing .roller", "cy"))
    assert math.hypot(rx - cx, ry - cy) == pytest.approx(10.0, abs=1e-6)  # r_f = 10 mm
    # the plots: four SVAJ rows, the cursor at 60 deg on both figures
    assert page.evaluate("() => document.getElementById('cam-svaj').data.length") == 4
    for div in ("cam-svaj", "cam-geometry"):
        x0 = page.evaluate(f"() => document.getElementById('{div}').layout.shapes[0].x0")
        assert x0 == 60


def test_a_law_edited_in_the_table_asks_again_and_warns(app: AppPage) -> None:
    page = open_cam(app)
    assert "No warnings" in page.inner_text("#cam-warnings")
    page.select_option("#cam-segments tr[data-segment='0'] select", "harmonic")
    page.wait_for_function(
        "() => document.getElementById('cam-warnings').textContent.includes('discontinuous')"
    )
    assert "fundamental law" in page.inner_text("#cam-warnings")
    # a refused edit: the server's words, the view as it was
    app.log.allow("status of 422")
    lift = page.locator("#cam-segments tr[data-segment='2'] input[data-field='lift']")
    page.fill("#cam-f-base_radius", "-1")
    page.dispatch_event("#cam-f-base_radius", "change")
    page.wait_for_selector("#cam-edit-message:not([hidden])")
    assert "base_radius" in page.inner_text("#cam-edit-message")
    assert page.get_attribute("#cam-f-base_radius", "aria-invalid") == "true"
    assert lift.input_value() == "0.025"
    assert "discontinuous" in page.inner_text("#cam-warnings")


@pytest.mark.parametrize(
    "value",
    ["cam:cam_offset_knife", "cam:cam_flat_faced", "cam:cam_oscillating_roller"],
)
def test_every_cam_preset_draws(app: AppPage, value: str) -> None:
    page = open_cam(app, value)
    assert page.locator("#cam-drawing .follower").count() == 1
    assert page.evaluate("() => document.getElementById('cam-geometry').data.length") >= 2


def test_back_to_a_linkage(app: AppPage) -> None:
    page = open_cam(app)
    choose(app, "preset:four_bar")
    page.wait_for_selector("#linkage .link", state="visible")
    assert not page.locator("#cam-app").is_visible()


@pytest.mark.slow
@pytest.mark.parametrize(("width", "height"), [(1440, 900), (1024, 768), (390, 844)])
def test_screenshots_nothing_cut_off_or_overlapping_and_axe(
    app: AppPage, width: int, height: int
) -> None:
    app.page.set_viewport_size({"width": width, "height": height})
    page = open_cam(app)
    pause(page, "#cam-play")
    page.wait_for_selector("#cam-steps .step .katex", state="attached")
    app.screenshot(f"cams-{width}x{height}")
    assert page.evaluate("() => document.documentElement.scrollWidth <= window.innerWidth + 1")
    # the panels of the section do not overlap, and no control sticks out of its panel
    panels = shown_boxes(page, "#cam-app > .panel")
    assert not overlapping_pairs(panels), "panels overlap"
    form = shown_boxes(page, "#cam-form")[0]
    for box in shown_boxes(page, "#cam-form input, #cam-form select"):
        assert form[0] - 1 <= box[0] and box[2] <= form[2] + 1, (box, form)
    assert not app.serious_accessibility_violations("#cam-app")

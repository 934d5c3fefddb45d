"""The browser app, second edition (issue 13): fields that never lie, one crank angle, layout,
export, plots, notation. Driven in Debian's Chromium against the real server, like test_app.py.
"""

from __future__ import annotations

import json
from typing import Any

import pytest

from tests.browser.conftest import AppPage
from tests.browser.test_app import pause_and_wait, wait_analysed, wait_until

pytestmark = pytest.mark.browser


def edit(page: Any, selector: str, text: str) -> None:
    page.fill(selector, text)
    page.press(selector, "Tab")


# ---- fields that never lie -------------------------------------------------------------------


def test_an_error_clears_as_soon_as_the_field_holds_a_valid_value(app: AppPage) -> None:
    app.log.allow(r"status of 422")
    app.open()
    page = app.page
    pause_and_wait(page)
    edit(page, "#f-param_ground", "2.6")
    error = page.locator("#f-param_ground-error")
    error.wait_for(state="visible")
    assert "2.6" in error.inner_text() or "|" in error.inner_text()
    assert page.get_attribute("#f-param_ground", "aria-invalid") == "true"
    # Back to the value the server accepted before: no request needed, the error goes.
    edit(page, "#f-param_ground", "1")
    error.wait_for(state="hidden")
    assert page.get_attribute("#f-param_ground", "aria-invalid") is None


def test_a_decimal_comma_is_a_decimal_point(app: AppPage) -> None:
    app.open()
    page = app.page
    pause_and_wait(page)
    with page.expect_request(lambda r: r.url.endswith("/presets/four_bar")) as request:
        edit(page, "#f-param_crank", "0,2")
    assert json.loads(request.value.post_data or "{}")["crank"] == pytest.approx(0.2)
    wait_until(lambda: page.input_value("#f-param_crank") == "0.2", what="0,2 shown as 0.2")
    assert page.get_attribute("#f-param_crank", "aria-invalid") is None


@pytest.mark.parametrize("text", ["abc", "", "0.2.3", "1e"])
def test_unparseable_input_is_marked_invalid_without_a_request(app: AppPage, text: str) -> None:
    app.open()
    page = app.page
    pause_and_wait(page)
    before = len(app.log.requests)
    edit(page, "#f-param_crank", text)
    page.locator("#f-param_crank-error").wait_for(state="visible")
    assert page.get_attribute("#f-param_crank", "aria-invalid") == "true"
    assert "number" in page.inner_text("#f-param_crank-error").lower()
    page.wait_for_timeout(900)  # past the typing debounce
    assert not any("/presets/" in u for u in app.log.requests[before:])
    # A valid value clears it (0.15 is the value shown before: nothing to ask).
    edit(page, "#f-param_crank", "0.15")
    page.locator("#f-param_crank-error").wait_for(state="hidden")


# ---- one crank angle ---------------------------------------------------------------------------


def test_the_slider_is_the_one_crank_angle(app: AppPage) -> None:
    app.open()
    page = app.page
    pause_and_wait(page)
    assert page.locator("#f-param_crank_angle_deg").count() == 0, "no second crank angle"
    page.focus("#crank-angle")
    for _ in range(40):
        page.keyboard.press("ArrowRight")
    wait_analysed(page)
    angle = float(page.input_value("#crank-angle")) % 360
    with page.expect_request(lambda r: r.url.endswith("/presets/four_bar")) as request:
        edit(page, "#f-param_coupler", "1.05")
    body = json.loads(request.value.post_data or "{}")
    assert body["crank_angle_deg"] == pytest.approx(angle, abs=1e-6)
    wait_until(lambda: page.input_value("#f-param_coupler") == "1.05", what="the edit")
    wait_analysed(page)
    assert float(page.input_value("#crank-angle")) % 360 == pytest.approx(angle, abs=1e-6)
    # The printable page is the analysed instant's.
    with (
        page.expect_request(lambda r: r.url.endswith("/solution.html")) as printed,
        page.expect_popup(),
    ):
        page.click("#print-solution")
    scene = json.loads(printed.value.post_data or "{}")["scene"]
    assert scene["drivers"][0]["angle_deg"] % 360 == pytest.approx(angle, abs=1e-6)


# ---- layout ------------------------------------------------------------------------------------


def in_view(page: Any, selector: str) -> bool:
    """The element's whole box is inside the viewport as the page opens (no scrolling)."""
    inside: bool = page.evaluate(
        """(sel) => { const r = document.querySelector(sel).getBoundingClientRect();
                      return r.width > 0 && r.top >= 0 && r.left >= 0
                        && r.bottom <= innerHeight && r.right <= innerWidth; }""",
        selector,
    )
    return inside


def test_drawing_motion_controls_and_polygons_fit_one_laptop_screen(app: AppPage) -> None:
    app.page.set_viewport_size({"width": 1440, "height": 900})
    app.open()
    page = app.page
    page.wait_for_selector("#velocity-polygon .main-svg")
    for selector in (
        "#linkage",
        "#play",
        "#crank-angle",
        "#velocity-polygon",
        "#acceleration-polygon",
    ):
        assert in_view(page, selector), f"{selector} is not in view at 1440x900"
    assert page.evaluate("scrollY") == 0
    # The worked solution is a tab, not 8000 px below: the page stays short.
    assert page.evaluate("document.documentElement.scrollHeight") < 2000
    assert page.locator("#steps").is_hidden()
    page.click("#tab-solution")
    page.wait_for_selector("#steps .katex")
    assert page.locator("#plots").is_hidden()
    assert page.get_attribute("#tab-solution", "aria-selected") == "true"
    page.click("#tab-plots")
    assert page.locator("#plots .main-svg").first.is_visible()
    app.screenshot("laptop-1440x900-first-screen", None)


def test_drawing_and_its_controls_fit_a_tablet_screen(app: AppPage) -> None:
    app.page.set_viewport_size({"width": 1024, "height": 768})
    app.open()
    page = app.page
    for selector in ("#linkage", "#play", "#crank-angle"):
        assert in_view(page, selector), f"{selector} is not in view at 1024x768"
    assert page.evaluate("document.documentElement.scrollWidth - innerWidth") <= 0

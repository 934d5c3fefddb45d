"""The app on a 390x844 phone (issue 30): the drawing and the polygons come first, before the
controls, also after an input (they were ~4000 px down the page after every input, under the
controls); screenshot, axe-core on the page. Real server, Debian's Chromium."""

from __future__ import annotations

from typing import Any

import pytest

from tests.browser.conftest import AppPage, overlapping_pairs, shown_boxes
from tests.browser.test_app import pause_and_wait

pytestmark = pytest.mark.browser

TOPS = """() => Object.fromEntries(['.view-panel', '.polygons-panel', '.controls', '.tabs']
  .map((s) => { const r = document.querySelector(s).getBoundingClientRect();
                return [s, [r.top + window.scrollY, r.bottom + window.scrollY]]; }))"""


def order(page: Any) -> dict[str, list[float]]:
    boxes: dict[str, list[float]] = page.evaluate(TOPS)
    return boxes


def first_screen(page: Any, when: str) -> None:
    """The drawing, then the polygons right under it (the grid's gap), then the controls."""
    boxes = order(page)
    view, polygons, controls = boxes[".view-panel"], boxes[".polygons-panel"], boxes[".controls"]
    assert view[1] <= polygons[0] + 1, (when, boxes)
    assert polygons[1] <= controls[0] + 1, (when, boxes)
    assert polygons[0] - view[1] < 30, (when, boxes)


@pytest.mark.slow
def test_on_a_phone_the_drawing_and_the_polygons_come_first(app: AppPage) -> None:
    page = app.page
    page.set_viewport_size({"width": 390, "height": 844})
    app.open()
    pause_and_wait(page)
    first_screen(page, "opened")
    page.evaluate(
        """() => { const s = document.getElementById('crank-angle');
                   s.value = '120'; s.dispatchEvent(new Event('change')); }"""
    )
    page.wait_for_function(
        "() => Math.abs(+document.getElementById('linkage').dataset.analysed"
        " - 2 * Math.PI / 3) < 1e-9"
    )
    first_screen(page, "after an input")
    app.screenshot("phone-order-390x844")
    assert app.serious_accessibility_violations() == []


def test_on_a_phone_plotlys_toolbar_leaves_the_polygons_titles_clear(app: AppPage) -> None:
    """Each polygon's title sits under Plotly's toolbar, not behind it (the toolbar covered
    "[m/s]" of "Velocity polygon [m/s]" at 390 px)."""
    page = app.page
    page.set_viewport_size({"width": 390, "height": 844})
    app.open()
    pause_and_wait(page)
    for polygon in ("#velocity-polygon", "#acceleration-polygon"):
        page.hover(polygon)  # the toolbar shows
        page.wait_for_selector(f"{polygon} .modebar")
        title = shown_boxes(page, f"{polygon} .gtitle")
        toolbar = shown_boxes(page, f"{polygon} .modebar")
        assert title and toolbar, polygon
        assert not overlapping_pairs(title + toolbar), (polygon, title, toolbar)

"""The app on a 390x844 phone (issue 30): the drawing and the polygons come first, before the
controls, also after an input (they were ~4000 px down the page after every input, under the
controls); screenshot, axe-core on the page; the polygons' titles, tick labels and legends
clear of one another (also on a laptop and a tablet). Real server, Debian's Chromium."""

from __future__ import annotations

from typing import Any

import pytest

from tests.browser.conftest import AppPage, overlapping_pairs
from tests.browser.test_app import DETAIL_DONE, choose, pause_and_wait

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


# The boxes [left, top, right, bottom] (px) of the texts of a polygon (or its detail) around its
# axes, by kind: its legend (a polygon's, in HTML under the figure: its note and its entries), the
# tick labels of its axes and its title (plane-figure.js); and the figure's own box (a polygon's
# with its legend, or the detail's).
FIGURE_TEXTS = """(id) => {
    const div = document.getElementById(id);
    const legend = document.getElementById(`${id}-legend`);
    const box = (e) => { const r = e.getBoundingClientRect();
                         return [r.left, r.top, r.right, r.bottom]; };
    return [box(legend ? div.parentElement : div), {
        legend: legend ? [...legend.children].map(box) : [],
        'tick label': [...div.querySelectorAll('.tick-label')].map(box),
        title: [...div.querySelectorAll('.figure-title')].map(box),
    }];
}"""


def clashes(texts: dict[str, list[list[float]]]) -> list[tuple[str, str]]:
    """The kinds of every two boxes of different kinds that overlap (1 px of slack)."""
    kinds = list(texts)
    return [
        (k1, k2)
        for i, k1 in enumerate(kinds)
        for k2 in kinds[i + 1 :]
        for a in texts[k1]
        for b in texts[k2]
        if overlapping_pairs([a, b])
    ]


def figure_texts_clear(page: Any, div: str) -> dict[str, list[list[float]]]:
    """The texts of `div` (FIGURE_TEXTS), having checked that no two of different kinds overlap,
    that the title and the legend are not cut at the figure's left or right edge, and that the
    tick labels and the legend lie within the figure (the tick labels take fixed margins)."""
    frame, texts = page.evaluate(FIGURE_TEXTS, div)
    assert all(texts[k] for k in ("tick label", "title")), (div, texts)
    assert clashes(texts) == [], (div, texts)
    whole = texts["title"] + texts["legend"]
    cut = [b for b in whole if b[0] < frame[0] - 1 or b[2] > frame[2] + 1]
    assert cut == [], (div, frame, cut)
    inside = [b for b in texts["tick label"] + texts["legend"] if b[2] > b[0]]  # (drawn ones)
    cut = [b for b in inside if b[1] < frame[1] - 1 or b[3] > frame[3] + 1]
    assert cut == [], (div, frame, cut)
    return texts


@pytest.mark.slow
@pytest.mark.parametrize(("width", "height"), [(390, 844), (1024, 768), (1280, 800), (1440, 900)])
def test_the_polygons_legend_tick_labels_title_and_note_never_overlap(
    app: AppPage, width: int, height: int
) -> None:
    """Every planar linkage in the menu, both polygons and their details: the legend, the tick
    labels, the title and any note ("Coriolis = 0 at C (guide not turning)", in the legend) do
    not overlap one another; the title and the legend are whole. On a phone
    the legend was drawn on the x axis' tick labels (placed at a fraction, -0.08, of the axes'
    height: 7 px there), the acceleration polygon's title on its Coriolis note and the detail's
    title cut at the right; at 1024x768 the legend touched the tick labels; at 1280x800 the titles
    lay under Plotly's toolbar (the polygons were Plotly's then). Screenshots
    polygons-<preset>-<viewport>."""
    page = app.page
    page.set_viewport_size({"width": width, "height": height})
    app.open()
    values = page.eval_on_selector_all("#preset option", "(os) => os.map((o) => o.value)")
    planar = [v for v in values if v.split(":")[0] in ("preset", "example") and "spatial" not in v]
    assert len(planar) >= 11
    notes = details = 0
    for value in planar:
        choose(app, value)
        page.wait_for_selector("#linkage:not([hidden]) .link", state="attached")
        pause_and_wait(page)
        for div in ("velocity-polygon", "acceleration-polygon"):
            page.wait_for_function(DETAIL_DONE, arg=div)  # its last drawing done, its detail's too
            assert figure_texts_clear(page, div)["legend"], (value, div)
            notes += "Coriolis = 0" in (page.text_content(f"#{div}-legend") or "")
            if page.get_attribute(f"#{div}", "data-detail") == "shown":
                figure_texts_clear(page, f"{div}-detail")
                details += 1
        if value in ("preset:quick_return", "preset:four_bar"):
            app.screenshot(f"polygons-{value.split(':')[1]}-{width}x{height}", ".polygons-panel")
    assert notes >= 4, "the Coriolis notes were among the texts checked"
    assert details >= 4, "details were among the figures checked"

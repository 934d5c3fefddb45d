"""The browser app as a student uses it, driven in Debian's Chromium: opening the page, the
polygons and the worked solution, changing the mechanism, the share link, other kinds of scene;
fields that never lie, the one crank angle, the layout on a laptop and a tablet, exports, plots,
notation, units, drawing and editing.

Every test runs against the real server (the session's ``live_server``, tests/conftest.py) and
fails on any console error, page error or request to another host (conftest.app). Screenshots
land in test-artifacts/screenshots/ for a person to look at.
"""

from __future__ import annotations

import csv
import io
import json
import math
import time
from collections.abc import Callable
from pathlib import Path
from typing import Any

import pytest

from tests.browser.conftest import AppPage, pause

pytestmark = pytest.mark.browser


def wait_until(check: Callable[[], Any], timeout: float = 15.0, what: str = "condition") -> Any:
    """Poll `check` until it returns something truthy (the page works asynchronously)."""
    deadline = time.monotonic() + timeout
    while True:
        value = check()
        if value:
            return value
        if time.monotonic() > deadline:
            raise AssertionError(f"timed out waiting for {what}")
        time.sleep(0.1)


def links_svg(page: Any) -> str:
    html: str = page.evaluate("document.querySelector('#linkage .layer-links').innerHTML")
    return html


def plot_data(page: Any, div: str) -> str:
    """The traces of a Plotly div, as JSON (what the student sees, without styling)."""
    data: str = page.evaluate(
        """(id) => JSON.stringify((document.getElementById(id).data || [])
            .map((t) => ({name: t.name, x: t.x, y: t.y, text: t.text})))""",
        div,
    )
    return data


def pause_and_wait(page: Any) -> None:
    """Pause and wait until the analysed instant is the one shown and the cycle plots are the
    mechanism's shown."""
    pause(page)
    wait_analysed(page)
    wait_plotted(page)


def wait_analysed(page: Any) -> None:
    page.wait_for_function(
        """() => { const d = document.getElementById('linkage').dataset;
                   return d.analysed !== undefined && d.analysed === d.instant; }"""
    )


def wait_plotted(page: Any) -> None:
    """The cycle plots are the mechanism's shown: a new geometry's are drawn a moment after its
    instant (main.js, PLOTS_AFTER_MS), the plots ``aria-busy`` until then."""
    page.wait_for_selector("#plots:not([aria-busy])", state="attached")


def choose(app: AppPage, value: str) -> None:
    """Choose a source in the selector and wait until its drawing is the one on screen (the
    selector's data-shown; a linkage or spatial chain) or, for a cam or gear train, until the
    selector holds it."""
    app.page.select_option("#preset", value)
    drawn = value.split(":")[0] in ("preset", "example")
    shown = "p.dataset.shown === v" if drawn else "p.value === v"
    app.page.wait_for_function(
        f"(v) => {{ const p = document.getElementById('preset'); return {shown}; }}", arg=value
    )


# ---- opening the page ----------------------------------------------------------------------


@pytest.mark.moving
def test_page_opens_on_a_moving_four_bar_without_errors(app: AppPage) -> None:
    app.open()
    page = app.page
    assert page.input_value("#preset") == "preset:four_bar"
    assert page.get_attribute("#play", "aria-pressed") == "true"
    assert page.locator("#linkage .link").count() >= 3
    assert page.locator("#linkage .ground-pivot").count() == 2
    assert page.locator("#linkage .point-label").count() >= 4
    assert page.locator("#status[data-level='error']").count() == 0
    assert not page.evaluate("performance.getEntriesByName('first-frame').length === 0")
    path = app.screenshot("overview")
    assert path.exists()
    assert all(u.startswith(app.url) or u.startswith("data:") for u in app.log.requests)


@pytest.mark.moving
def test_linkage_svg_moves_between_frames_without_a_request_per_frame(app: AppPage) -> None:
    app.open()
    page = app.page
    first = links_svg(page)
    page.wait_for_timeout(250)
    second = links_svg(page)
    assert first != second, "the mechanism did not move between two frames"
    # Playing back is local: over two seconds of animation no new request is made.
    api_calls = [u for u in app.log.requests if "/api/v1/" in u]
    page.wait_for_timeout(2000)
    assert [u for u in app.log.requests if "/api/v1/" in u] == api_calls
    assert sum(u.endswith("/api/v1/sweep") for u in api_calls) == 1


def test_keyboard_turns_the_crank_and_pauses(app: AppPage) -> None:
    app.open()
    page = app.page
    page.focus("#crank-angle")
    page.keyboard.press("ArrowRight")  # the first key stops the animation
    assert page.get_attribute("#play", "aria-pressed") == "false"
    before = float(page.input_value("#crank-angle"))
    lo, hi = (float(page.get_attribute("#crank-angle", a) or 0) for a in ("min", "max"))
    key, step = ("ArrowLeft", -1) if before > (lo + hi) / 2 else ("ArrowRight", 1)
    page.keyboard.press(key)
    page.keyboard.press(key)
    after = float(page.input_value("#crank-angle"))
    assert after == pytest.approx(before + 2 * step, abs=1e-9), "one degree per arrow key"
    wait_analysed(page)
    # Space plays again (focus outside any field).
    page.focus("#linkage")
    page.evaluate("document.activeElement.blur()")
    page.keyboard.press(" ")
    assert page.get_attribute("#play", "aria-pressed") == "true"


# ---- polygons and worked solution ----------------------------------------------------------


def test_polygons_are_drawn_head_to_tail_with_equal_axes(app: AppPage) -> None:
    app.open()
    page = app.page
    pause_and_wait(page)
    page.wait_for_selector("#velocity-polygon .plane-figure")
    page.wait_for_selector("#acceleration-polygon .plane-figure")
    names = json.loads(
        page.evaluate(
            "JSON.stringify(document.getElementById('acceleration-polygon').data.map(t => t.name))"
        )
    )
    assert "absolute acceleration" in names
    assert "normal part −ω²r" in names and "tangential part α×r" in names
    for div in ("velocity-polygon", "acceleration-polygon"):
        anchor = page.evaluate(f"document.getElementById('{div}').layout.yaxis.scaleanchor")
        assert anchor == "x", "polygon axes must have equal scales"
    page.wait_for_function(
        "(document.getElementById('velocity-polygon').layout.annotations || []).length > 2"
    )
    labels = page.evaluate(
        "document.getElementById('velocity-polygon').layout.annotations.map((a) => a.text)"
    )
    assert "b" in labels and "c" in labels, "velocity tips are labelled like the points"
    app.screenshot("polygons", ".polygons-panel")
    app.screenshot("cycle-plots", ".plots-panel")


@pytest.mark.slow
def test_worked_solution_is_typeset_with_katex(app: AppPage) -> None:
    app.open()
    page = app.page
    pause_and_wait(page)
    page.click("#tab-solution")  # the worked solution has its own tab
    page.wait_for_selector("#steps .katex")
    assert page.locator("#steps .katex").count() >= 3
    page.wait_for_selector("#steps[data-typeset='done']")  # the first steps come first
    assert page.locator("#steps .step-error").count() == 0, "a step's LaTeX did not render"
    assert page.locator("#mistakes li").count() >= 1
    vector_text = page.inner_text("#steps")
    page.check("input[name='method'][value='loop']")
    wait_until(lambda: page.inner_text("#steps") != vector_text, what="the loop-method steps")
    page.wait_for_selector("#steps[data-method='loop'][data-typeset='done'] .katex")
    assert page.locator("#steps .step-error").count() == 0
    app.screenshot("worked-solution", ".solution-panel")


def test_a_closed_solution_tab_typesets_its_first_steps_only_until_opened(app: AppPage) -> None:
    """The worked solution of each instant comes with the analysis, but while its tab is closed
    only its first steps are typeset (those a reader sees at once on opening it); the rest
    follow when the tab is opened. Before, the whole solution (some ten thousand elements) was
    typeset behind the closed tab after every preset and edit."""
    app.open()
    page = app.page
    pause_and_wait(page)
    page.wait_for_selector("#steps[data-method] .step .katex", state="attached")
    page.wait_for_timeout(1500)  # three times the idle wait of a batch of later steps
    assert page.get_attribute("#steps", "data-typeset") == "partial"
    first = page.locator("#steps .step").count()
    assert first == 4
    page.click("#tab-solution")
    page.wait_for_selector("#steps[data-typeset='done']")
    assert page.locator("#steps .step").count() > first


def test_printable_page_opens_with_the_typeset_solution(app: AppPage) -> None:
    app.open()
    page = app.page
    pause_and_wait(page)
    page.click("#tab-solution")  # the worked solution has its own tab
    page.wait_for_selector("#steps .katex")
    with page.expect_popup() as popup:
        page.click("#print-solution")
    printable = popup.value
    printable.wait_for_selector(".katex")
    assert printable.locator(".katex").count() >= 3
    assert "Typical mistakes" in printable.inner_text("body")


# ---- changing the mechanism ------------------------------------------------------------------


@pytest.mark.slow
def test_choosing_a_preset_and_editing_a_length_update_every_view(app: AppPage) -> None:
    app.open()
    page = app.page
    pause_and_wait(page)
    before = (links_svg(page), plot_data(page, "velocity-polygon"), plot_data(page, "plots"))
    choose(app, "preset:slider_crank")
    wait_until(lambda: "slider" in page.inner_text("#view-title").lower(), what="the new title")
    page.wait_for_selector("#linkage .slider-block")
    page.wait_for_selector("#f-param_rod")
    pause_and_wait(page)
    after_preset = (links_svg(page), plot_data(page, "velocity-polygon"), plot_data(page, "plots"))
    for old, new, view in zip(before, after_preset, ("linkage", "polygon", "plots"), strict=True):
        assert old != new, f"the {view} view did not follow the preset"
    built = [u for u in app.log.requests if "/api/v1/presets/" in u]
    assert not built, f"a preset at its defaults comes with the listing, not {built}"
    steps_before = page.inner_text("#steps")
    # Edit the crank length: everything is asked again and redrawn.
    page.fill("#f-param_crank", "0.12")
    page.press("#f-param_crank", "Tab")
    wait_until(
        lambda: plot_data(page, "plots") != after_preset[2], what="the cycle plots to change"
    )
    assert any("/api/v1/presets/slider_crank" in u for u in app.log.requests), "built anew"
    pause_and_wait(page)
    wait_until(lambda: plot_data(page, "velocity-polygon") != after_preset[1], what="the polygons")
    assert links_svg(page) != after_preset[0]
    assert page.get_attribute("#f-param_crank", "aria-invalid") is None
    wait_until(lambda: page.inner_text("#steps") != steps_before, what="the new solution")
    app.screenshot("slider-crank-edited")


# Two edits of the crank length, the second one three frames after the first is drawn (its
# drawing and polygons marked analysed): the way a student steps a number field with the arrow
# keys. Both answers were fetched before (reused, no request), so the second is drawn at once.
EDIT_TWICE = """async ([first, second]) => {
  const $ = (id) => document.getElementById(id);
  const field = $('f-param_crank');
  const edit = (value) => {
    field.value = String(value);
    field.dispatchEvent(new Event('change', { bubbles: true }));
  };
  const frame = () => new Promise((resolve) => requestAnimationFrame(resolve));
  const plots = $('plots');
  plots.dataset.drawn = '0';
  plots.on('plotly_afterplot', () => {
    plots.dataset.drawn = String(Number(plots.dataset.drawn) + 1);
  });
  delete $('linkage').dataset.analysed;
  edit(first);
  while ($('linkage').dataset.analysed === undefined) await frame();
  for (let i = 0; i < 3; i++) await frame();
  edit(second);
}"""


def test_edits_in_quick_succession_plot_the_last_geometry_only(app: AppPage) -> None:
    """The cycle plots (Plotly, 50 to 100 ms of the page's time) of an edited geometry are drawn
    once no newer edit came for a moment (main.js, PLOTS_AFTER_MS): a value stepped past is
    never plotted, and the next edit is not kept waiting behind its plots (the field edit of
    docs/BENCHMARKS.md)."""
    app.open()
    page = app.page
    pause_and_wait(page)
    start = page.input_value("#f-param_crank")
    for value in ("0.13", start):  # each answer fetched once
        # (the crank angle is kept, so the analysed mark would read the same before the edit
        # lands: it is cleared, and wait_settled waits for the edited geometry and its plots)
        page.evaluate("() => { delete document.getElementById('linkage').dataset.analysed; }")
        page.fill("#f-param_crank", value)
        page.press("#f-param_crank", "Tab")
        app.wait_settled()
    at_start = plot_data(page, "plots")
    page.fill("#f-param_crank", "0.13")
    page.press("#f-param_crank", "Tab")
    wait_until(lambda: plot_data(page, "plots") != at_start, what="the plots of 0.13 m")
    app.wait_settled()
    at_013 = plot_data(page, "plots")
    page.evaluate(EDIT_TWICE, [start, "0.13"])
    app.wait_settled()
    page.wait_for_timeout(500)  # (a stale plot, if any, would be drawn by now)
    assert page.get_attribute("#plots", "data-drawn") == "1", "the value stepped past was plotted"
    assert plot_data(page, "plots") == at_013


def test_a_mechanism_without_a_sweep_is_analysed_as_drawn_with_no_stale_plots(
    app: AppPage,
) -> None:
    """A sweep that cannot be had (here /sweep unreachable, the rest of the server answering):
    the drawn pose is analysed and the page says there is no animation, and the cycle plots
    say there is no cycle rather than keep the previous mechanism's (main.js, commitPlanar:
    they are drawn from the track shown, which analyzeNow framed anew)."""
    app.log.allow(r"Failed to load resource")
    app.open()
    page = app.page
    pause_and_wait(page)
    assert plot_data(page, "plots") != "[]"
    four_bar_polygon = plot_data(page, "velocity-polygon")
    page.route("**/api/v1/sweep", lambda route: route.abort())
    choose(app, "preset:slider_crank")
    wait_plotted(page)
    assert "No animation" in page.inner_text("#view-message")
    assert "drawn pose is analysed" in page.inner_text("#view-message")
    wait_until(
        lambda: plot_data(page, "velocity-polygon") not in ("[]", four_bar_polygon),
        what="the slider-crank's velocity polygon",
    )
    message = page.locator("#plots-message")
    assert message.is_visible()
    assert message.inner_text() == "No sweep from the server, so there is no cycle to plot."
    assert plot_data(page, "plots") == "[]"


def test_non_assemblable_length_shows_the_servers_message_beside_the_field(
    app: AppPage,
) -> None:
    app.log.allow(r"status of 422")
    app.open()
    page = app.page
    pause_and_wait(page)
    ground_before = page.inner_html("#linkage .layer-ground")
    polygon_before = plot_data(page, "velocity-polygon")
    with page.expect_request(lambda r: r.url.endswith("/presets/four_bar")) as request:
        page.fill("#f-param_crank", "3")
        page.press("#f-param_crank", "Tab")
    # The preset is built posed at the analysed instant (one crank angle on the page).
    body = json.loads(request.value.post_data or "{}")
    assert body["crank"] == 3
    status, problem = app.post("/presets/four_bar", body)
    assert status == 422 and problem["code"] == "not_assemblable"
    error = page.locator("#f-param_crank-error")
    error.wait_for(state="visible")
    assert error.inner_text().strip() == problem["detail"]
    assert page.get_attribute("#f-param_crank", "aria-invalid") == "true"
    # The view is intact: same mechanism, still drawn and analysed.
    assert page.inner_html("#linkage .layer-ground") == ground_before
    assert page.locator("#linkage .link").count() >= 3
    assert plot_data(page, "velocity-polygon") == polygon_before
    app.screenshot("not-assemblable")
    # Correcting the value clears the message.
    page.fill("#f-param_crank", "0.2")
    page.press("#f-param_crank", "Tab")
    error.wait_for(state="hidden")


def test_units_switch_changes_the_display_only(app: AppPage) -> None:
    app.open()
    page = app.page
    pause_and_wait(page)
    app.wait_settled()
    assert float(page.input_value("#f-param_crank")) == pytest.approx(0.15)
    requests = len(app.log.requests)
    page.select_option("#units", "mm")
    assert float(page.input_value("#f-param_crank")) == pytest.approx(150)
    wait_until(lambda: "mm/s" in page.inner_text("#velocity-polygon"), what="mm/s in the polygon")
    assert "°" in page.inner_text("#crank-angle-value")
    asked = [u for u in app.log.requests[requests:] if "/api/v1/" in u]
    assert not asked, f"units are display only, yet the page asked for {asked}"


# ---- share link ----------------------------------------------------------------------------


@pytest.mark.slow
def test_share_link_restores_the_scene_and_the_view(app: AppPage) -> None:
    app.open()
    page = app.page
    choose(app, "preset:quick_return")
    page.wait_for_selector("#f-param_lever")
    page.wait_for_selector("#linkage .slider-block")
    page.fill("#f-param_lever", "0.65")
    page.press("#f-param_lever", "Tab")
    # The edit has landed (its geometry swept and drawn) before the pause: the field holds what
    # was typed at once, so its value says nothing of that.
    page.wait_for_function(
        "() => document.getElementById('linkage').dataset.edited === 'param:lever'"
    )
    assert page.input_value("#f-param_lever") == "0.65"
    pause_and_wait(page)
    page.focus("#crank-angle")
    for _ in range(20):
        page.keyboard.press("ArrowRight")
    wait_analysed(page)
    page.select_option("#units", "mm")
    page.check("#show-acceleration")
    page.click("#share")
    page.wait_for_function("() => (document.getElementById('share-url').value.includes('#s='))")
    url = page.input_value("#share-url")
    assert url.startswith(app.url) and "#s=" in url

    def view(p: Any) -> dict[str, Any]:
        state: dict[str, Any] = p.evaluate(
            """() => ({
                preset: document.getElementById('preset').value,
                units: document.getElementById('units').value,
                lever: document.getElementById('f-param_lever').value,
                angle: document.getElementById('crank-angle').value,
                playing: document.getElementById('play').getAttribute('aria-pressed'),
                acc: document.getElementById('show-acceleration').checked,
                instant: document.getElementById('linkage').dataset.instant,
                title: document.getElementById('view-title').textContent,
            })"""
        )
        return state

    shown = view(page)
    polygon = plot_data(page, "velocity-polygon")
    other = app.new_page()
    other.goto(url)
    # "attached", not visible: a link drawn exactly vertical has a zero-width box, which
    # Playwright counts as hidden.
    other.wait_for_selector("#linkage .link", state="attached")
    wait_analysed(other)
    other.wait_for_function(
        "() => (document.getElementById('velocity-polygon').data !== undefined)"
    )
    restored = view(other)
    assert restored == shown
    assert plot_data(other, "velocity-polygon") == polygon
    assert other.locator("#linkage .vector-acceleration").count() > 0
    other.screenshot(path=str(app.screenshot("share-source").parent / "share-restored.png"))


# ---- other kinds of scene --------------------------------------------------------------------


@pytest.mark.slow
def test_spatial_chain_example_renders(app: AppPage) -> None:
    app.open()
    page = app.page
    choose(app, "example:S002-spatial-arm.json")
    page.wait_for_selector("#spatial .body")
    assert page.locator("#linkage").is_hidden()
    labels = page.eval_on_selector_all(
        "#spatial .point-label", "(nodes) => nodes.map((n) => n.textContent)"
    )
    assert {"O2", "A", "B"} <= set(labels)
    assert page.locator("#spatial .joint-axis").count() == 3
    page.wait_for_selector("#spatial .vector-velocity")
    assert page.locator("#spatial-info li").count() >= 6
    note = page.text_content("#spatial .view-note")
    page.focus("#spatial")
    page.keyboard.press("ArrowLeft")
    turned = page.text_content("#spatial .view-note")
    assert turned != note, "arrow keys turn the view"
    app.screenshot("spatial-arm")
    # The camera travels in the share link too.
    page.click("#share")
    page.wait_for_function("() => (document.getElementById('share-url').value.includes('#s='))")
    other = app.new_page()
    other.goto(page.input_value("#share-url"))
    other.wait_for_selector("#spatial .body")
    assert other.text_content("#spatial .view-note") == turned
    assert other.input_value("#preset") == "example:S002-spatial-arm.json"


@pytest.mark.moving
def test_relative_motion_scene_animates_in_time(app: AppPage) -> None:
    app.open()
    page = app.page
    choose(app, "example:S003-T2-rotating-carrier.json")
    wait_until(lambda: "S003" in page.inner_text("#view-title"), what="the seed scene")
    page.wait_for_selector("#linkage .groove", state="attached")
    assert not page.is_disabled("#crank-angle"), page.inner_text("#view-message")
    assert page.inner_text("#crank-angle-label") == "Time"
    first = links_svg(page)
    page.wait_for_timeout(250)
    assert links_svg(page) != first
    app.screenshot("relative-motion")


@pytest.mark.parametrize(
    "example",
    [
        "S000-T1.json",
        "S000-T2.json",
        "S000-T3.json",
        "S000-T4.json",
        "S001-offset-slider-crank.json",
        "S003-T1-translating-carrier.json",
    ],
)
def test_seed_examples_open(app: AppPage, example: str) -> None:
    app.open()
    page = app.page
    choose(app, f"example:{example}")
    wait_until(
        lambda: example.split(".")[0][:7] in page.inner_text("#view-title"), what="the title"
    )
    page.wait_for_selector("#linkage .link", state="attached")
    pause_and_wait(page)
    page.wait_for_selector("#velocity-polygon .plane-figure")
    assert page.locator("#status[data-level='error']:not(:empty)").count() == 0


def test_tablet_layout_has_no_horizontal_scroll(app: AppPage) -> None:
    app.page.set_viewport_size({"width": 820, "height": 1180})
    app.open()
    page = app.page
    overflow = page.evaluate("document.documentElement.scrollWidth - window.innerWidth")
    assert overflow <= 0
    app.screenshot("tablet")


def test_dragging_the_crank_chooses_the_analysed_instant(app: AppPage) -> None:
    app.open()
    page = app.page
    page.wait_for_selector("#linkage .crank-handle")
    before = page.get_attribute("#linkage", "data-instant")
    # The handle moves while the page plays: under load it can leave the spot read from its box
    # before the press lands, and a press beside it is no drag. Three grabs; one must land.
    for _ in range(3):
        box = page.locator("#linkage .crank-handle").bounding_box()
        assert box is not None
        # The ring, not its centre: the joint's own circle there moves the joint (issue 13).
        x, y = box["x"] + 3, box["y"] + box["height"] / 2
        page.mouse.move(x, y)
        page.mouse.down()
        page.mouse.move(x - 25, y - 35, steps=6)
        page.mouse.up()
        if page.get_attribute("#play", "aria-pressed") == "false":
            break
    assert page.get_attribute("#play", "aria-pressed") == "false"
    wait_analysed(page)
    assert page.get_attribute("#linkage", "data-instant") != before


def test_invalid_time_law_points_at_the_character(app: AppPage) -> None:
    app.log.allow(r"status of 422")
    app.open()
    page = app.page
    choose(app, "example:S003-T2-rotating-carrier.json")
    page.wait_for_selector("#f-law_angle")
    page.fill("#f-law_angle", "2*t + import(3)")
    page.press("#f-law_angle", "Tab")
    error = page.locator("#f-law_angle-error")
    error.wait_for(state="visible")
    assert "import" in error.inner_text()
    caret = page.text_content("#f-law_angle-error .caret") or ""
    assert caret.splitlines()[-1] == " " * 6 + "^"
    assert page.locator("#linkage .link").count() >= 1


def test_close_approach_to_a_change_point_is_shown(app: AppPage) -> None:
    """Issue 8: a four-bar 1e-4 m inside the Grashof equality (rocker = crank + 1e-4 with ground
    = coupler) keeps its assembly, and the view says in words how close it came (the server's
    warning, shown as it is)."""
    app.open()
    page = app.page
    pause_and_wait(page)
    page.fill("#f-param_rocker", "0.1501")
    page.press("#f-param_rocker", "Tab")
    wait_until(
        lambda: "change point" in page.inner_text("#view-message"), what="the close-approach note"
    )
    assert "clearance could switch assembly" in page.inner_text("#view-message")


def test_seed_example_opens_at_the_books_pose(app: AppPage) -> None:
    """Issue 12: S000-T1 opens with the crank at 90 deg as drawn in the seed (not at the first
    sample of its sweep, a limit position of the rocking crank); motion reduced so it stays."""
    app.page.emulate_media(reduced_motion="reduce")
    app.open()
    page = app.page
    choose(app, "example:S000-T1.json")
    wait_until(lambda: "S000" in page.inner_text("#view-title"), what="the title")
    page.wait_for_selector("#linkage .link", state="attached")
    wait_analysed(page)
    instant = float(page.get_attribute("#linkage", "data-instant") or "nan")
    assert abs(instant - math.pi / 2) < 0.02, instant


def test_printable_solution_page_with_figures(app: AppPage) -> None:
    """Issue 12: the printable page shows the mechanism and the polygons beside the steps; every
    formula is typeset; in print the figures are black and white. Screenshotted."""
    page = app.page
    page.goto(f"{app.url}/api/v1/solution.html?preset=quick_return&crank=0.12")
    page.wait_for_function("() => (document.querySelectorAll('.math.pending').length === 0)")
    assert page.locator(".math.error").count() == 0
    assert page.locator("figure.figure svg").count() >= 3
    box = page.locator("figure.figure svg").first.bounding_box()
    assert box is not None and box["width"] > 100 and box["height"] > 50
    app.screenshot("solution-figures", "figure.figure >> nth=1")
    page.emulate_media(media="print")
    stroke = page.evaluate(
        "getComputedStyle(document.querySelector('figure.figure svg line[data-vector]')).stroke"
    )
    assert stroke in ("rgb(0, 0, 0)", "#000000"), stroke
    app.screenshot("solution-print")


# ---- fields that never lie -------------------------------------------------------------------


def edit(page: Any, selector: str, text: str) -> None:
    page.fill(selector, text)
    page.press(selector, "Tab")


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


@pytest.mark.slow
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
    page.click("#tab-solution")
    with (
        page.expect_request(lambda r: r.url.endswith("/solution.html")) as printed,
        page.expect_popup(),
    ):
        page.click("#print-solution")
    scene = json.loads(printed.value.post_data or "{}")["scene"]
    assert scene["drivers"][0]["angle_deg"] % 360 == pytest.approx(angle, abs=1e-6)


def test_an_edit_keeps_the_instant_exactly_and_asks_for_it_beside_the_sweep(
    app: AppPage,
) -> None:
    """A length edited at a crank angle set on the slider: the new mechanism is analysed at that
    very angle (not its interpolation in the new sweep, which differs in the last digits), and
    the instant's one /analyze is sent at once, before the sweep has answered (the preset is
    checked at that angle), not after it."""
    app.open()
    page = app.page
    pause_and_wait(page)
    start = page.get_attribute("#linkage", "data-analysed")
    page.focus("#crank-angle")
    for _ in range(7):
        page.keyboard.press("ArrowRight")
    # The drawing takes the slider's angle at its next frame: until then the start is both the
    # instant shown and the one analysed, so the wait is for another angle analysed as shown.
    page.wait_for_function(
        """(start) => { const d = document.getElementById('linkage').dataset;
                       return d.analysed !== start && d.analysed === d.instant; }""",
        arg=start,
    )
    analysed = page.get_attribute("#linkage", "data-analysed")
    events: list[str] = []
    app.listen("request", lambda r: events.append(f"ask {r.url.rsplit('/', 1)[-1]}"))
    app.listen("requestfinished", lambda r: events.append(f"got {r.url.rsplit('/', 1)[-1]}"))
    edit(page, "#f-param_crank", "0.051")
    page.wait_for_function("() => document.getElementById('linkage').dataset.edited")
    wait_analysed(page)
    assert page.get_attribute("#linkage", "data-analysed") == analysed
    asked = [e for e in events if e == "ask analyze"]
    assert len(asked) == 1, events
    assert events.index("ask analyze") < events.index("got sweep"), events


def test_a_mechanism_too_fine_for_its_first_sweep_is_shown_from_it_then_refined(
    app: AppPage,
) -> None:
    """The slider-guide extension's crank rocks, and near its limit positions the drawing needs
    more samples than the first sweep's: the mechanism is drawn and its start analysed from the
    first sweep (the /analyze sent before the finer sweep has answered), and the finer sweep then
    replaces the first at the same instant, exactly (no second /analyze; the analysed instant is
    the one shown), ``data-samples`` the last sweep asked for."""
    app.page.emulate_media(reduced_motion="reduce")  # a new mechanism stays at its start
    app.open()
    page = app.page
    events: list[str] = []
    samples: list[int] = []

    def asked(request: Any) -> None:
        name = request.url.rsplit("/", 1)[-1]
        if name == "sweep" and "forces" not in request.post_data_json.get("quantities", []):
            samples.append(request.post_data_json["samples"])
        events.append(f"ask {name}")

    app.listen("request", asked)
    app.listen("requestfinished", lambda r: events.append(f"got {r.url.rsplit('/', 1)[-1]}"))
    choose(app, "preset:slider_guide_extension")
    page.wait_for_selector("#linkage[data-samples]", state="attached")
    wait_analysed(page)
    assert len(samples) >= 2 and samples[-1] > samples[0], samples  # the premise: refined
    assert page.get_attribute("#linkage", "data-samples") == str(samples[-1])
    last_sweep = len(events) - 1 - events[::-1].index("got sweep")
    assert events.count("ask analyze") == 1, events
    assert events.index("ask analyze") < last_sweep, events
    wait_plotted(page)
    # The cycle plots name the crank's angle as the slider and the message do: the cursor at the
    # analysed instant, the x axis from the first to the last swept angle (not 2 pi away).
    page.wait_for_function(
        "() => (document.getElementById('plots').layout?.shapes || []).length > 0"
    )
    cursor, first, last = page.evaluate(
        """() => { const p = document.getElementById('plots');
                   const x = p.data[0].x;
                   return [p.layout.shapes[0].x0, x[0], x[x.length - 1]]; }"""
    )
    analysed = float(page.get_attribute("#linkage", "data-analysed") or "nan")
    assert cursor == analysed  # (the same number: data-analysed is its shortest round trip)
    stated = page.inner_text("#view-message")
    low, high = sorted((first, last))
    assert f"rocks between {low:.4g} rad and {high:.4g} rad" in stated, (stated, low, high)


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
    page.wait_for_selector("#velocity-polygon .plane-figure")
    for selector in (
        "#linkage",
        "#play",
        "#crank-angle",
        "#velocity-polygon",
        "#acceleration-polygon",
    ):
        assert in_view(page, selector), f"{selector} is not in view at 1440x900"
    assert page.evaluate("scrollY") == 0
    # The worked solution is a tab, not 8000 px below: the page stays short (the four-bar at its
    # 30 deg: the polygons with both their details and the cycle plots, about 2050 px).
    assert page.evaluate("document.documentElement.scrollHeight") < 2500
    assert page.locator("#steps").is_hidden()
    page.click("#tab-solution")
    page.wait_for_selector("#steps .katex")
    assert page.locator("#plots").is_hidden()
    assert page.get_attribute("#tab-solution", "aria-selected") == "true"
    page.click("#tab-plots")
    assert page.locator("#plots .main-svg").first.is_visible()
    # (the clicks scrolled the tabs into view: back at the top, the sticky controls column is
    # pictured where a student first sees it)
    page.evaluate("() => scrollTo(0, 0)")
    app.screenshot("laptop-1440x900-first-screen", None)


def test_drawing_and_its_controls_fit_a_tablet_screen(app: AppPage) -> None:
    app.page.set_viewport_size({"width": 1024, "height": 768})
    app.open()
    page = app.page
    for selector in ("#linkage", "#play", "#crank-angle"):
        assert in_view(page, selector), f"{selector} is not in view at 1024x768"
    assert page.evaluate("document.documentElement.scrollWidth - innerWidth") <= 0


# ---- export ------------------------------------------------------------------------------------


def download(page: Any, button: str) -> tuple[str, bytes]:
    """Open the export menu, click `button`, return (suggested file name, content)."""
    if not page.evaluate("document.getElementById('export-menu').open"):
        page.click("#export-menu summary")
    with page.expect_download() as info:
        page.click(button)
    path = info.value.path()
    return info.value.suggested_filename, Path(path).read_bytes()


def exported_scene(page: Any) -> dict[str, Any]:
    name, content = download(page, "#export-scene")
    assert name.endswith(".json")
    scene: dict[str, Any] = json.loads(content)
    return scene


def test_cycle_csv_holds_every_series_with_units_and_the_servers_numbers(app: AppPage) -> None:
    app.open()
    page = app.page
    pause_and_wait(page)
    page.select_option("#units", "mm")
    scene = exported_scene(page)
    name, content = download(page, "#export-csv")
    assert name.endswith("-cycle.csv")
    rows = list(csv.reader(io.StringIO(content.decode())))
    header, body = rows[0], rows[1:]
    assert header[0] == "angle of crank θ [deg]" and header[1] == "time t from θ = 0 [s]"
    assert "ω of rocker [rpm]" in header and "|v| of P [mm/s]" in header
    assert "transmission angle μ = ∠BCD [deg]" in header
    assert all(h.endswith("]") for h in header), "every column states its unit"
    assert len(body) == 242  # 241 samples from 0 deg, and 360 deg closing the turn
    angles = [float(r[0]) for r in body]
    assert angles[0] == pytest.approx(0, abs=1e-9) and angles[-1] == pytest.approx(360)
    assert angles == sorted(angles)
    # Against the server's own sweep of the same scene from 0 deg: rocker ω at each crank angle.
    scene["drivers"][0]["angle_deg"] = 0
    status, sweep = app.post(
        "/sweep", {"scene": scene, "samples": 241, "quantities": ["position", "velocity"]}
    )
    assert status == 200
    omega = {
        round(math.degrees(a) % 360, 6): w
        for a, w in zip(sweep["driver_angle"], sweep["links"]["rocker"]["omega"], strict=True)
    }
    column = header.index("ω of rocker [rpm]")
    for r in body:
        expected = omega[round(float(r[0]) % 360, 6)] * 60 / (2 * math.pi)
        assert float(r[column]) == pytest.approx(expected, rel=1e-12, abs=1e-12)


def test_instant_csv_is_the_analysed_instant(app: AppPage) -> None:
    app.open()
    page = app.page
    pause_and_wait(page)
    scene = exported_scene(page)
    angle = float(page.get_attribute("#linkage", "data-analysed") or "nan")
    _, content = download(page, "#export-instant-csv")
    rows = list(csv.reader(io.StringIO(content.decode())))
    assert rows[0] == ["object", "quantity", "x", "y", "magnitude", "unit"]
    assert rows[1][0] == "instant" and float(rows[1][4]) == pytest.approx(angle)
    scene["drivers"][0]["angle_deg"] = math.degrees(angle)
    status, analysis = app.post("/analyze", {"scene": scene})
    assert status == 200
    vp = next(r for r in rows if r[:2] == ["point P", "velocity"])
    assert [float(vp[2]), float(vp[3])] == pytest.approx(analysis["points"]["P"]["velocity"])
    assert vp[5] == "m/s"
    alpha = next(r for r in rows if r[:2] == ["link coupler", "alpha"])
    assert float(alpha[4]) == pytest.approx(analysis["links"]["coupler"]["alpha"])


@pytest.mark.parametrize(
    ("which", "fmt"),
    [("linkage", "png"), ("linkage", "svg"), ("velocity-polygon", "png"), ("plots", "svg")],
)
def test_figures_download_as_png_and_svg(app: AppPage, which: str, fmt: str) -> None:
    app.open()
    page = app.page
    pause_and_wait(page)
    page.wait_for_selector("#plots .main-svg")
    page.click("#export-menu summary")
    page.select_option("#export-figure-which", which)
    page.select_option("#export-figure-format", fmt)
    name, content = download(page, "#export-figure")
    assert name.endswith(f"-{which}.{fmt}")
    if fmt == "png":
        assert content[:8] == b"\x89PNG\r\n\x1a\n"
        width, height = int.from_bytes(content[16:20], "big"), int.from_bytes(content[20:24], "big")
        assert width >= 600 and height >= 300
    else:
        text = content.decode()
        assert "<svg" in text
        if which == "linkage":
            assert 'data-link="coupler"' in text and ">P</text>" in text


def test_scene_json_downloads_and_uploads(app: AppPage, tmp_path: Path) -> None:
    app.open()
    page = app.page
    pause_and_wait(page)
    scene = exported_scene(page)
    assert scene["kind"] == "linkage" and "coupler" in scene["links"]
    scene["title"] = "my own four-bar"
    scene["points"]["P"] = [scene["points"]["P"][0] + 0.1, scene["points"]["P"][1]]
    upload = tmp_path / "mine.json"
    upload.write_text(json.dumps(scene))
    page.set_input_files("#import-scene", str(upload))
    wait_until(lambda: page.inner_text("#view-title") == "my own four-bar", what="the upload")
    pause_and_wait(page)
    assert page.input_value("#preset") == "shared"
    assert float(page.input_value("#f-point_P_0")) == pytest.approx(scene["points"]["P"][0])


# ---- plots -------------------------------------------------------------------------------------


def plots_layout(page: Any) -> dict[str, Any]:
    layout: dict[str, Any] = page.evaluate(
        """() => { const d = document.getElementById('plots');
                   return {range: d.layout.xaxis.range, title: d.layout.xaxis.title.text,
                           traces: d.data.map((t) => ({name: t.name, x: t.x, y: t.y}))}; }"""
    )
    return layout


def test_plots_run_over_0_to_360_degrees_or_time(app: AppPage) -> None:
    app.open()
    page = app.page
    pause_and_wait(page)
    page.select_option("#units", "mm")
    wait_until(lambda: plots_layout(page)["range"] == [0, 360], what="0..360 deg")
    crank = next(t for t in plots_layout(page)["traces"] if t["name"] == "link crank")
    assert crank["x"][0] == pytest.approx(0, abs=1e-9) and crank["x"][-1] == pytest.approx(360)
    page.select_option("#plot-x", "time")
    wait_until(lambda: "time" in plots_layout(page)["title"], what="the time axis")
    x = plots_layout(page)["traces"][0]["x"]
    period = 2 * math.pi / 25.132741228718345
    assert min(x) == pytest.approx(0, abs=1e-9) and max(x) == pytest.approx(period, rel=1e-9)
    assert x == sorted(x)


def test_slider_plots_and_the_quick_return_time_ratio(app: AppPage) -> None:
    app.open()
    page = app.page
    choose(app, "preset:quick_return")
    page.wait_for_selector("#linkage .slider-block", state="attached")
    wait_until(lambda: page.input_value("#plot-point") == "slider:C", what="the ram's plots")
    names = [t["name"] for t in plots_layout(page)["traces"]]
    for q in ("position s", "velocity", "acceleration"):
        assert f"{q} of slider C along its guide" in names
    # Closed form: the lever's limit positions are where the crank is perpendicular to it,
    # cos(β/2) = crank/ground; the return stroke takes β of crank turn, the cut 360° − β.
    beta = 2 * math.acos(0.1 / 0.3)
    expected = (2 * math.pi - beta) / beta
    facts = wait_until(lambda: page.inner_text("#plot-facts"), what="the time ratio")
    ratio = float(facts.split("time ratio of C: ")[1].split(" ")[0])
    assert ratio == pytest.approx(expected, abs=2e-3)  # four digits shown


def test_transmission_angle_with_its_extremes_and_grashof_class(app: AppPage) -> None:
    app.open()
    page = app.page
    pause_and_wait(page)
    facts = wait_until(lambda: page.inner_text("#mechanism-facts"), what="Grashof class")
    assert "Grashof crank-rocker" in facts and "transmission angle μ = ∠BCD" in facts
    page.select_option("#units", "mm")
    wait_until(lambda: page.locator("#plot-point option[value='transmission:C']").count(), what="μ")
    page.select_option("#plot-point", "transmission:C")
    text = wait_until(lambda: page.inner_text("#plot-facts"), what="the extremes")
    # Closed form: extremes with the crank along the ground line, |BD| = ground ∓ crank.
    a, b, c, d = 0.15, 1.0, 0.55, 1.0
    mu = [math.degrees(math.acos((b * b + c * c - e * e) / (2 * b * c))) for e in (d - a, d + a)]
    lo = float(text.split("min ")[1].split(" ")[0])
    hi = float(text.split("max ")[1].split(" ")[0])
    assert lo == pytest.approx(mu[0], abs=0.01) and hi == pytest.approx(mu[1], abs=0.01)


# ---- notation and readable polygons ------------------------------------------------------------

# The boxes of the labels drawn in a figure (plane-figure.js: each on its box, a rect).
LABEL_BOXES = """(id) => [...document.getElementById(id).querySelectorAll('g.figure-label')]
    .map((g) => { const r = g.querySelector('rect').getBoundingClientRect();
                  return [g.dataset.text, r.left, r.top, r.right, r.bottom]; })"""

DETAIL_DONE = """(id) => { const d = document.getElementById(id).dataset.detail;
                          return d === 'shown' || d === 'none'; }"""

LABELS_PLACED = """(id) => (document.getElementById(id).layout?.annotations || [])
    .some((a) => String(a.name || '').startsWith('label:'))"""


def label_overlaps(page: Any, div: str, required: bool = True) -> list[tuple[str, str]]:
    boxes = page.evaluate(LABEL_BOXES, div)
    assert boxes or not required, f"no labels in {div}"
    clashes = []
    for i, a in enumerate(boxes):
        for b in boxes[i + 1 :]:
            if a[1] < b[3] and b[1] < a[3] and a[2] < b[4] and b[2] < a[4]:
                clashes.append((a[0], b[0]))
    return clashes


# Each arrow trace of relative and component vectors, and how its labels' text is recognised.
PART_LABELS = {
    "v relative to a point, ω×r": r"^v<sub>[^,<]+</sub>$",
    "normal part −ω²r": r"^a<sup>n</sup>",
    "tangential part α×r": r"^a<sup>t</sup>",
    "Coriolis 2ω×v_rel": r",Cor</sub>$",
    "relative velocity": r"^v<sub>[^<]+,rel</sub>$",
    "relative": r"^a<sub>[^<]+,rel</sub>$",
}

PART_COUNTS = """(args) => {
    const [id, patterns] = args;
    const div = document.getElementById(id);
    const labels = (div.layout.annotations || [])
        .filter((a) => String(a.name || '').startsWith('label:'));
    const out = {};
    for (const [trace, pattern] of Object.entries(patterns)) {
        const t = div.data.find((d) => d.name === trace);
        const arrows = t ? t.x.filter((x) => x === null).length : 0;
        const re = new RegExp(pattern);
        out[trace] = [arrows, labels.filter((a) => re.test(a.text)).length];
    }
    return out;
}"""


def unlabelled_parts(page: Any, div: str) -> dict[str, list[int]]:
    """Traces of relative/component vectors whose arrows and labels do not pair one to one."""
    counts: dict[str, list[int]] = page.evaluate(PART_COUNTS, [div, PART_LABELS])
    return {name: c for name, c in counts.items() if c[0] != c[1]}


@pytest.mark.slow
def test_no_two_polygon_labels_overlap_on_any_preset_or_seed_example(app: AppPage) -> None:
    app.open()
    page = app.page
    values = page.eval_on_selector_all("#preset option", "(os) => os.map((o) => o.value)")
    # the planar linkages (the cams', gear trains' and designer's entries have no polygons)
    planar = [v for v in values if v.split(":")[0] in ("preset", "example") and "spatial" not in v]
    assert len(planar) >= 11
    for value in planar:
        choose(app, value)
        page.wait_for_selector("#linkage:not([hidden]) .link", state="attached")
        pause_and_wait(page)
        for div in ("velocity-polygon", "acceleration-polygon"):
            page.wait_for_function(LABELS_PLACED, arg=div)
            assert label_overlaps(page, div) == [], f"{value}: labels overlap in {div}"
            assert unlabelled_parts(page, div) == {}, f"{value}: unlabelled vectors in {div}"
            # The detail at its own scale (polygon-detail.js), when the polygon needs one: "shown"
            # is set after its last draw, labels included (possibly none: no tip in its frame).
            page.wait_for_function(DETAIL_DONE, arg=div)
            if page.get_attribute(f"#{div}", "data-detail") == "shown":
                detail = f"{div}-detail"
                assert label_overlaps(page, detail, False) == [], f"{value}: in {detail}"
        if value == "preset:quick_return":
            app.screenshot("quick-return-polygons", ".polygons-panel")


def test_poles_and_images_never_share_a_name_with_a_point(app: AppPage) -> None:
    app.open()
    page = app.page
    pause_and_wait(page)  # the four-bar has a coupler point P: its image is p
    for div, pole in (
        ("velocity-polygon", "O<sub>v</sub>"),
        ("acceleration-polygon", "O<sub>a</sub>"),
    ):
        page.wait_for_function(LABELS_PLACED, arg=div)
        texts = page.evaluate(
            f"document.getElementById('{div}').layout.annotations.map(a => a.text)"
        )
        assert any(t.startswith(f"{pole} ≡ ") for t in texts), texts
        assert "p" in texts and not any(t.startswith("p ≡") for t in texts)
    # In the drawing, the coupler (link 3) has its poles I₁₃ and Γ₁₃, never a point's letter.
    page.wait_for_function(
        """() => document.querySelector('#linkage .pole')
                 || document.querySelector('#linkage .layer-notes').textContent.includes('Poles')"""
    )
    poles = page.eval_on_selector_all(
        "#linkage .pole-label", "(ts) => ts.map((t) => t.textContent)"
    )
    notes = page.text_content("#linkage .layer-notes") or ""
    names = set(poles) | {n for n in ("I₁₃", "Γ₁₃") if n in notes}
    assert {"I₁₃", "Γ₁₃"} <= names, (poles, notes)
    assert "coupler (3)" in page.eval_on_selector_all(
        "#linkage .link-label", "(ts) => ts.map((t) => t.textContent)"
    )


def test_magnitudes_table_beside_the_polygons(app: AppPage) -> None:
    app.open()
    page = app.page
    pause_and_wait(page)
    page.click("#magnitudes summary")
    row = page.locator("#polygon-table tr", has_text="P (p)")
    row.wait_for()
    cells = row.locator("td").all_inner_texts()
    angle = float(page.get_attribute("#linkage", "data-analysed") or "nan")
    scene = exported_scene(page)
    scene["drivers"][0]["angle_deg"] = math.degrees(angle)
    _, analysis = app.post("/analyze", {"scene": scene})
    v = analysis["points"]["P"]["velocity"]
    a = analysis["points"]["P"]["acceleration"]
    assert float(cells[0]) == pytest.approx(math.hypot(*v), rel=1e-3)
    assert float(cells[1]) == pytest.approx(math.hypot(*a), rel=1e-3)


# ---- units -------------------------------------------------------------------------------------


def test_units_switch_reaches_the_worked_solution(app: AppPage) -> None:
    app.open()
    page = app.page
    pause_and_wait(page)
    page.click("#tab-solution")
    app.wait_settled()
    assert page.locator("#steps .step-units").count() == 0
    requests = len(app.log.requests)
    page.select_option("#units", "mm")
    page.wait_for_selector("#steps .step-units")
    page.wait_for_selector("#steps[data-typeset='done']")  # every step, not only the first
    asked = [u for u in app.log.requests[requests:] if "/api/v1/" in u]
    assert not asked, f"no new request, yet the page asked for {asked}"
    # textContent: the steps out of sight are not laid out (content-visibility), so not in innerText
    text = page.text_content("#steps") or ""
    assert "mm/s" in text and "rpm" in text
    lines = page.locator("#steps .step-units").all_text_contents()
    line = next(t for t in lines if "v(B) = (" in t)
    shown = [float(x) for x in line.split("v(B) = (")[1].split(")")[0].split(", ")]
    angle = float(page.get_attribute("#linkage", "data-analysed") or "nan")
    scene = exported_scene(page)
    scene["drivers"][0]["angle_deg"] = math.degrees(angle)
    _, analysis = app.post("/analyze", {"scene": scene})
    expected = [1000 * c for c in analysis["points"]["B"]["velocity"]]
    assert shown == pytest.approx(expected, rel=1e-3)
    page.select_option("#units", "si")
    page.wait_for_function("() => (!document.querySelector('#steps .step-units'))")


# ---- draw and edit -----------------------------------------------------------------------------


def drag(page: Any, selector: str, dx: float, dy: float) -> None:
    box = page.locator(selector).bounding_box()
    assert box is not None
    x, y = box["x"] + box["width"] / 2, box["y"] + box["height"] / 2
    page.mouse.move(x, y)
    page.mouse.down()
    page.mouse.move(x + dx, y + dy, steps=8)
    page.mouse.up()


@pytest.mark.slow
def test_dragging_a_joint_changes_the_geometry_and_the_analysis_and_undo_restores(
    app: AppPage,
) -> None:
    app.open()
    page = app.page
    pause_and_wait(page)
    assert page.locator("#linkage [data-point]").count() >= 5
    polygon = plot_data(page, "velocity-polygon")
    ground = page.inner_html("#linkage .layer-ground")
    page.click("#edit-mode")  # joints move in Edit mode only (issue 30)
    drag(page, "#linkage [data-point='D']", 60, 0)
    wait_until(lambda: page.input_value("#preset") == "shared", what="an edited scene")
    page.wait_for_selector("#f-point_D_0")
    d_x = float(page.input_value("#f-point_D_0"))
    assert d_x > 1.05, "D moved right (the ground got longer)"
    assert page.inner_html("#linkage .layer-ground") != ground
    wait_analysed(page)
    wait_until(lambda: plot_data(page, "velocity-polygon") != polygon, what="a new analysis")
    # Snapped to the grid: a round coordinate.
    assert round(d_x * 1000) == pytest.approx(d_x * 1000, abs=1e-6)
    page.click("#undo")
    wait_until(lambda: page.input_value("#preset") == "preset:four_bar", what="undo")
    page.wait_for_selector("#f-param_ground")
    assert page.input_value("#f-param_ground") == "1"
    page.click("#redo")
    wait_until(lambda: page.input_value("#preset") == "shared", what="redo")


def sheet_click(page: Any, x: float, y: float) -> None:
    """Click the editor's sheet at world (x, y) m (its view: 400 px/m, origin at (120, 380))."""
    box = page.locator("#editor").bounding_box()
    assert box is not None
    scale = box["width"] / 1000
    page.mouse.click(box["x"] + (120 + 400 * x) * scale, box["y"] + (380 - 400 * y) * scale)


@pytest.mark.slow
def test_a_four_bar_drawn_from_scratch_analyses(app: AppPage) -> None:
    app.open()
    page = app.page
    page.click("#new-mechanism")
    page.wait_for_selector("#editor")
    assert page.locator("#linkage").is_hidden()
    corners = {"A": (0, 0), "B": (0, 0.1), "C": (0.6, 0.4), "D": (0.7, 0)}
    for x, y in corners.values():
        sheet_click(page, x, y)
    assert page.locator("#editor [data-point]").count() == 4
    page.check("input[name='editor-tool'][value='ground']")
    for name in "AD":
        sheet_click(page, *corners[name])
    page.check("input[name='editor-tool'][value='link']")
    for a, b in ("AB", "BC", "DC"):
        sheet_click(page, *corners[a])
        sheet_click(page, *corners[b])
        page.keyboard.press("Escape")
    assert page.get_attribute("#editor-dof", "data-f") == "1"
    assert "F = 3(n − 1) − 2j = 3·3 − 2·4 = 1" in page.inner_text("#editor-dof")
    page.click("#editor-done")  # no driver yet: explained, nothing sent
    assert "driver" in page.inner_text("#editor-message")
    page.check("input[name='editor-tool'][value='driver']")
    sheet_click(page, 0, 0.05)  # the middle of bar AB
    page.fill("#editor-title", "four-bar from scratch")
    page.click("#editor-done")
    wait_until(lambda: page.inner_text("#view-title") == "four-bar from scratch", what="it")
    assert page.locator("#editor-panel").is_hidden()
    page.wait_for_selector("#linkage .link", state="attached")
    pause_and_wait(page)
    page.wait_for_selector("#velocity-polygon .plane-figure")
    facts = wait_until(lambda: page.inner_text("#mechanism-facts"), what="Grashof class")
    assert "Grashof crank-rocker" in facts
    scene = exported_scene(page)
    assert scene["points"]["C"] == pytest.approx([0.6, 0.4])
    assert scene["drivers"][0]["link"] == "AB"
    assert {(j["point"], tuple(j["links"])) for j in scene["joints"]} == {
        ("A", ("ground", "AB")),
        ("B", ("AB", "BC")),
        ("C", ("BC", "DC")),
        ("D", ("ground", "DC")),
    }
    # Saved in the share link (asked for: the hash itself follows the view after a debounce).
    page.click("#share")
    page.wait_for_function("() => (document.getElementById('share-url').value.includes('#s='))")
    other = app.new_page()
    other.goto(page.input_value("#share-url"))
    other.wait_for_function(
        "() => (document.getElementById('view-title').textContent === 'four-bar from scratch')"
    )
    app.screenshot("four-bar-from-scratch")


def test_gruebler_count_explains_a_structure(app: AppPage) -> None:
    app.open()
    page = app.page
    page.click("#new-mechanism")
    for x, y in ((0, 0), (0.4, 0.3), (0.8, 0)):
        sheet_click(page, x, y)
    page.check("input[name='editor-tool'][value='ground']")
    sheet_click(page, 0, 0)
    sheet_click(page, 0.8, 0)
    page.check("input[name='editor-tool'][value='link']")
    for a, b in (((0, 0), (0.4, 0.3)), ((0.4, 0.3), (0.8, 0))):
        sheet_click(page, *a)
        sheet_click(page, *b)
        page.keyboard.press("Escape")
    assert page.get_attribute("#editor-dof", "data-f") == "0"
    assert "structure" in page.inner_text("#editor-dof")


# ---- groove scene ------------------------------------------------------------------------------


def test_groove_scene_draws_a_disc_and_a_groove_unlike_the_traced_path(app: AppPage) -> None:
    app.open()
    page = app.page
    choose(app, "example:S003-T2-rotating-carrier.json")
    page.wait_for_selector("#linkage circle.disc", state="attached")
    pause_and_wait(page)
    disc = page.eval_on_selector(
        "#linkage circle.disc",
        "(c) => [+c.getAttribute('cx'), +c.getAttribute('cy'), +c.getAttribute('r')]",
    )
    pivot = page.eval_on_selector(
        "#linkage [data-point='P']", "(c) => [+c.getAttribute('cx'), +c.getAttribute('cy')]"
    )
    assert disc[:2] == pytest.approx(pivot), "the disc turns about its pivot P"
    groove = page.eval_on_selector(
        "#linkage circle.groove",
        "(c) => [+c.getAttribute('cx'), +c.getAttribute('cy'), +c.getAttribute('r')]",
    )
    assert groove[2] < disc[2], "the groove lies on the disc"
    assert page.locator("#linkage .groove-channel").count() == 1
    styles = page.evaluate(
        """() => ['.groove', '.coupler-curve'].map((c) =>
            document.querySelector(`#linkage ${c}`).getAttribute('stroke-dasharray'))"""
    )
    assert styles[0] is None and styles[1], "the groove is a slot, the traced path is dashed"
    assert "groove" in page.inner_text("#legend")
    app.screenshot("groove-disc", ".view-panel")

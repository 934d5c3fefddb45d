"""The app's controls and layout where a student touches them.

Each test here failed before its fix: the motion controls gone after the editor, the crank's end
joint dragged as a joint, Space ignored on the crank slider, panels overlapping at common
window sizes, float noise in the drawing, the Exercises link landing on the instructor page.
Run against the real server under its Content-Security-Policy (conftest.app).
"""

from __future__ import annotations

from typing import Any

import pytest

from tests.browser.conftest import AppPage
from tests.browser.test_app import choose, pause_and_wait, wait_analysed, wait_until

pytestmark = pytest.mark.browser


def motion_visible(page: Any) -> bool:
    return all(page.locator(sel).is_visible() for sel in ("#play", "#crank-angle", "#speed"))


def test_motion_controls_stay_after_the_editor(app: AppPage) -> None:
    app.open()
    page = app.page
    assert motion_visible(page)
    page.click("#new-mechanism")
    page.wait_for_selector("#editor")
    assert motion_visible(page), "the motion controls are there while drawing"
    page.click("#editor-cancel")
    assert motion_visible(page), "and after Close"
    page.click("#new-mechanism")
    page.click("#editor-cancel")
    choose(app, "preset:slider_crank")
    app.wait_ready()
    assert motion_visible(page), "and after choosing a preset"
    # Play runs the mechanism again.
    pause_and_wait(page)
    before = page.get_attribute("#linkage", "data-instant")
    page.click("#play")
    wait_until(
        lambda: page.get_attribute("#linkage", "data-instant") != before, what="the crank turning"
    )


def crank_tip(page: Any) -> dict[str, float]:
    """The on-screen centre of the crank's end joint (the driver's handle point)."""
    box: dict[str, float] = page.evaluate(
        """() => { const h = document.querySelector('#linkage .crank-handle');
                   const r = h.getBoundingClientRect();
                   return {x: r.x + r.width / 2, y: r.y + r.height / 2}; }"""
    )
    return box


def test_pressing_the_crank_end_joint_turns_the_crank(app: AppPage) -> None:
    app.open()
    page = app.page
    pause_and_wait(page)
    crank = page.input_value("#f-param_crank")
    before = page.get_attribute("#linkage", "data-instant")
    tip = crank_tip(page)
    # The joint's own circle, right at its centre: it turns the crank, it does not move the joint.
    page.mouse.move(tip["x"], tip["y"])
    page.mouse.down()
    page.mouse.move(tip["x"] - 30, tip["y"] + 40, steps=8)
    page.mouse.up()
    wait_analysed(page)
    assert page.get_attribute("#linkage", "data-instant") != before, "the crank turned"
    assert page.input_value("#preset") == "preset:four_bar"
    assert page.input_value("#f-param_crank") == crank, "the geometry is unchanged"
    # In Edit mode the same press moves the joint (and the selector says the scene is edited).
    page.click("#edit-mode")
    assert page.get_attribute("#edit-mode", "aria-pressed") == "true"
    drag_point = page.locator("#linkage [data-point='D']").bounding_box()
    assert drag_point is not None
    x, y = drag_point["x"] + drag_point["width"] / 2, drag_point["y"] + drag_point["height"] / 2
    page.mouse.move(x, y)
    page.mouse.down()
    page.mouse.move(x + 60, y, steps=8)
    page.mouse.up()
    wait_until(lambda: page.input_value("#preset") == "shared", what="an edited scene")


def test_joints_off_the_driver_stay_in_turn_mode(app: AppPage) -> None:
    app.open()
    page = app.page
    pause_and_wait(page)
    # A joint off the driver (the fixed pivot D, which main let a press drag) in Turn mode:
    # nothing moves, the geometry is the preset's.
    box = page.locator("#linkage [data-point='D']").bounding_box()
    assert box is not None
    x, y = box["x"] + box["width"] / 2, box["y"] + box["height"] / 2
    page.mouse.move(x, y)
    page.mouse.down()
    page.mouse.move(x + 50, y + 20, steps=8)
    page.mouse.up()
    page.wait_for_timeout(400)
    assert page.input_value("#preset") == "preset:four_bar"


def test_space_plays_while_the_crank_slider_has_focus(app: AppPage) -> None:
    app.open()
    page = app.page
    pause_and_wait(page)
    page.focus("#crank-angle")
    page.keyboard.press("Space")
    assert page.get_attribute("#play", "aria-pressed") == "true"
    page.keyboard.press("Space")
    assert page.get_attribute("#play", "aria-pressed") == "false"


# ---- layout: no two panels overlap, nothing scrolls sideways ---------------------------------

VIEWPORTS = [(1440, 900), (1280, 800), (1024, 768), (390, 844)]

OVERLAPS = """() => {
  // Every shown panel of the page (the grid's children and the top bar), in viewport pixels.
  const shown = (e) => !e.closest('[hidden]') && e.getClientRects().length > 0;
  const panels = [document.querySelector('.topbar'),
                  ...document.querySelectorAll('main.layout > *')].filter(shown);
  const name = (e) => e.id || e.className;
  const found = [];
  for (let i = 0; i < panels.length; i++) {
    for (let j = i + 1; j < panels.length; j++) {
      const a = panels[i].getBoundingClientRect();
      const b = panels[j].getBoundingClientRect();
      const w = Math.min(a.right, b.right) - Math.max(a.left, b.left);
      const h = Math.min(a.bottom, b.bottom) - Math.max(a.top, b.top);
      const size = `${w.toFixed(0)}x${h.toFixed(0)} px`;
      if (w > 0.5 && h > 0.5) found.push(`${name(panels[i])} over ${name(panels[j])} (${size})`);
    }
  }
  return found;
}"""


def layout_defects(page: Any) -> list[str]:
    """Panels whose boxes intersect, at the top, in the middle and at the bottom of the page
    (sticky panels move as it scrolls), and a page wider than the window."""
    defects: list[str] = []
    height = page.evaluate("() => document.documentElement.scrollHeight - window.innerHeight")
    for y in sorted({0, height // 3, 2 * height // 3, height}):
        page.evaluate("(y) => window.scrollTo(0, y)", y)
        page.wait_for_timeout(50)
        defects += [f"at scroll {y}: {d}" for d in page.evaluate(OVERLAPS)]
    sideways = page.evaluate("() => document.documentElement.scrollWidth - window.innerWidth")
    if sideways > 0:
        defects.append(f"the page scrolls sideways by {sideways} px")
    page.evaluate("() => window.scrollTo(0, 0)")
    return defects


@pytest.mark.slow
@pytest.mark.parametrize(("width", "height"), VIEWPORTS)
def test_no_panels_overlap_and_nothing_scrolls_sideways(
    app: AppPage, width: int, height: int
) -> None:
    page = app.page
    page.set_viewport_size({"width": width, "height": height})
    app.open()
    pause_and_wait(page)
    defects = [f"four-bar, plots: {d}" for d in layout_defects(page)]
    page.click("#tab-solution")
    page.wait_for_selector("#steps[data-typeset='done'] .step")  # every step
    defects += [f"four-bar, worked solution: {d}" for d in layout_defects(page)]
    page.click("#tab-plots")
    page.click("#new-mechanism")
    defects += [f"editor: {d}" for d in layout_defects(page)]
    page.click("#editor-cancel")
    choose(app, "preset:seed004")
    page.wait_for_selector("#dynamics:not([hidden])")
    page.wait_for_function("() => document.getElementById('dynamics-plots').data !== undefined")
    pause_and_wait(page)
    defects += [f"dynamics: {d}" for d in layout_defects(page)]
    page.evaluate("() => document.getElementById('dynamics').scrollIntoView()")
    app.screenshot(f"seams-dynamics-{width}x{height}")
    assert not defects, defects


# ---- numbers: float noise is 0 ---------------------------------------------------------------


def test_a_coordinate_within_1e_12_of_the_drawing_scale_is_shown_as_0(app: AppPage) -> None:
    """seed004 at 270 deg: the coupler's velocity pole is at (-4.85e-41, 2.09) m from the server
    (the crank points straight down, so the pole lies on the y axis up to rounding). The note
    of poles outside the picture printed "-4.85e-41 m"; it says 0 m."""
    app.open()
    page = app.page
    choose(app, "preset:seed004")
    app.wait_ready()
    pause_and_wait(page)
    page.evaluate(
        """() => { const s = document.getElementById('crank-angle');
                   s.value = '270'; s.dispatchEvent(new Event('change')); }"""
    )
    page.wait_for_function(
        "() => document.getElementById('linkage').dataset.analysed !== undefined"
        " && Math.abs(+document.getElementById('linkage').dataset.analysed"
        " - 3 * Math.PI / 2) < 1e-9"
    )
    notes = page.eval_on_selector("#linkage .layer-notes", "(g) => g.textContent")
    assert "I₁₃ (0 m, 2.09 m)" in notes, notes
    assert "e-4" not in notes and "e-1" not in notes, notes


# ---- the student entry to the exercises ------------------------------------------------------


def test_the_exercises_link_opens_student_mode_with_a_type_chooser(app: AppPage) -> None:
    app.open()
    page = app.page
    page.click("a.exercises-link")
    page.wait_for_selector("#st-type option", state="attached")
    assert page.locator("#student").is_visible()
    assert page.locator("#instructor").is_hidden(), "a student lands on the student mode"
    assert page.locator("#st-type option").count() >= 3
    page.select_option("#st-type", index=1)
    chosen = page.eval_on_selector("#st-type", "(s) => s.value")
    page.click("#st-new")
    page.wait_for_function("() => document.getElementById('st-title').textContent !== ''")
    assert page.evaluate("() => location.hash").startswith(f"#id={chosen}")
    assert page.locator("#answer-rows input").count() >= 1
    assert page.locator("#st-type").is_visible(), "another exercise is one choice away"
    app.screenshot("seams-exercises-student")
    assert app.serious_accessibility_violations("#student") == []
    # An exercise opened from its link shows its own type and difficulty in the chooser, so that
    # "New exercise" gives another of the same kind.
    page.goto(f"{app.url}/exercises.html#id=four_bar_acceleration:challenging:3:0")
    page.wait_for_function(
        "() => document.getElementById('st-type').value === 'four_bar_acceleration'"
        " && document.getElementById('st-difficulty').value === 'challenging'"
    )
    assert "acceleration" in page.inner_text("#st-type-description")
    # The instructor page is one click away.
    page.click("#to-instructor")
    page.wait_for_selector("#instructor:not([hidden])")
    assert page.locator("#student").is_hidden()

"""Design a linkage in the browser (docs/SYNTHESIS.md "In the app"): three typed positions give
the server's linkage with its defects, warnings and checks shown, and the linkage drawn at a
position puts its coupler point on that position's handle; dragging a position (and moving one
with the keyboard) designs again; a refused task shows the server's reason beside the fields; the
function task draws the desired curve (checked against f(x) computed here) and the generated one
with the structural error; "Open in the analyser" opens the designed scene as a shared scene;
screenshots at 1440x900, 1024x768 and 390x844 with nothing overlapping or cut off, and axe-core on
the section. Real server, Debian's Chromium, real CSP.
"""

from __future__ import annotations

import math
import re
from typing import Any

import pytest

from tests.browser.conftest import AppPage, overlapping_pairs, shown_boxes
from tests.browser.test_app import choose

DESIGN = "design:linkage"


def open_designer(app: AppPage) -> Any:
    app.open()
    page = app.page
    page.wait_for_selector(f"#preset option[value='{DESIGN}']", state="attached")
    choose(app, DESIGN)
    wait_designs(page, 1)
    return page


def designs(page: Any) -> int:
    return int(page.get_attribute("#synthesis-app", "data-designs") or 0)


def wait_designs(page: Any, at_least: int) -> None:
    """Until the page shows its `at_least`-th design and asks nothing more."""
    page.wait_for_function(
        "(n) => { const r = document.getElementById('synthesis-app');"
        " return +(r.dataset.designs || 0) >= n && r.dataset.state === 'ready'; }",
        arg=at_least,
    )


def wait_settled(page: Any) -> None:
    page.wait_for_function(
        "() => ['ready', 'refused'].includes(document.getElementById('synthesis-app')"
        ".dataset.state)"
    )


def type_into(page: Any, values: dict[str, float | str]) -> None:
    """Each field typed and left (a change event), as a student does."""
    for field, value in values.items():
        page.fill(f"#{field}", str(value))
        page.press(f"#{field}", "Tab")


def motion_task(page: Any) -> dict[str, Any]:
    """The task as the page's fields hold it."""

    def num(field: str) -> float:
        return float(page.input_value(f"#{field}"))

    positions = [
        {
            "point": [num(f"syn-p{j}-x"), num(f"syn-p{j}-y")],
            "angle_deg": num(f"syn-p{j}-angle"),
        }
        for j in (1, 2, 3)
        if page.locator(f"#syn-p{j}-x").count()
    ]
    fixed = page.is_checked("input[name='syn-pivots'][value='fixed_pivots']")
    names = ("A", "D") if fixed else ("B", "C")
    pivots = [[num(f"syn-{n}-x"), num(f"syn-{n}-y")] for n in names]
    return {
        "task": "motion",
        "positions": positions,
        ("fixed_pivots" if fixed else "moving_pivots"): pivots,
    }


def shown_defects(page: Any) -> dict[str, bool]:
    rows = page.eval_on_selector_all(
        "#syn-defects li", "(li) => li.map((e) => [e.dataset.defect, e.dataset.present])"
    )
    return {name: present == "true" for name, present in rows}


def shown_lengths(page: Any) -> dict[str, float]:
    rows = page.eval_on_selector_all(
        "#syn-dimensions tbody tr",
        "(rows) => rows.map((r) => [r.querySelector('th').textContent,"
        " r.querySelector('td').textContent])",
    )
    return {name: float(v) for name, v in rows if name in ("ground", "crank", "coupler", "rocker")}


def centre(page: Any, selector: str) -> tuple[float, float]:
    box = page.locator(selector).bounding_box()
    return box["x"] + box["width"] / 2, box["y"] + box["height"] / 2


@pytest.mark.slow
def test_three_typed_positions_give_a_linkage_whose_defects_are_shown(app: AppPage) -> None:
    page = open_designer(app)
    assert page.is_hidden("#linkage") and page.is_visible("#syn-linkage")
    before = designs(page)
    type_into(
        page,
        {
            "syn-p1-x": 0, "syn-p1-y": 0, "syn-p1-angle": 0,
            "syn-p2-x": 0.8, "syn-p2-y": 0.4, "syn-p2-angle": 25,
            "syn-p3-x": 1.5, "syn-p3-y": 0.2, "syn-p3-angle": 50,
            "syn-B-x": -0.4, "syn-B-y": -0.3, "syn-C-x": 0.4, "syn-C-y": -0.35,
        },
    )  # fmt: skip
    wait_settled(page)
    assert designs(page) > before
    task = motion_task(page)
    assert task["positions"][1] == {"point": [0.8, 0.4], "angle_deg": 25.0}
    status, body = app.post("/synthesis", task)
    assert status == 200
    # The defects, warnings, lengths and checks on the page are the server's for this task.
    assert shown_defects(page) == {k: body["defects"][k] for k in ("branch", "order", "grashof")}
    shown_warnings = page.eval_on_selector_all(
        "#syn-warnings li.warning", "(l) => l.map((e) => e.textContent)"
    )
    assert shown_warnings == body["warnings"]
    for link, value in shown_lengths(page).items():
        assert value == pytest.approx(body["dimensions"][link], rel=1e-4)
    assert page.locator("#syn-checks tbody tr").count() == 3
    reached = page.eval_on_selector_all(
        "#syn-checks tbody tr", "(r) => r.map((e) => e.dataset.reached)"
    )
    assert reached == [str(c["reached"]).lower() for c in body["checks"]]
    # At each reached position the drawn coupler point P sits on the position's handle (the
    # sweep's P at the check's crank angle, interpolated: well under 2 px).
    for k, check in enumerate(body["checks"]):
        if not check["reached"]:
            continue
        page.click(f"#syn-goto [data-check='{k}']")
        page.wait_for_function(
            "() => document.getElementById('syn-play').getAttribute('aria-pressed') === 'false'"
        )
        p = centre(page, "#syn-linkage [data-point='P']")
        handle = centre(page, f"#syn-linkage [data-handle='P{k + 1}'] circle")
        assert math.dist(p, handle) < 2.0, (k, p, handle)
    # the worked solution of the design, typeset, with its construction figure
    page.wait_for_selector("#syn-steps .step .katex", state="attached")
    assert page.locator("#syn-steps .step-error").count() == 0
    assert page.locator("#syn-steps .step-figure svg").count() >= 1
    assert "poles" in page.inner_text("#syn-steps").lower()
    # The inverse problem from the design's own fixed pivots gives the same linkage back: the
    # fields take A and D from the design, and the lengths shown stay (to the digits shown).
    lengths = shown_lengths(page)
    count = designs(page)
    page.check("input[name='syn-pivots'][value='fixed_pivots']")
    wait_designs(page, count + 1)
    a = body["scene"]["points"]["A"]
    assert float(page.input_value("#syn-A-x")) == pytest.approx(a[0], abs=1e-12)
    assert float(page.input_value("#syn-A-y")) == pytest.approx(a[1], abs=1e-12)
    for link, value in shown_lengths(page).items():
        assert value == pytest.approx(lengths[link], rel=1e-4)
    assert page.locator("#syn-linkage [data-handle='A']").count() == 1


def test_dragging_a_position_or_moving_it_by_keyboard_updates_the_design(app: AppPage) -> None:
    page = open_designer(app)
    x3 = float(page.input_value("#syn-p3-x"))
    lengths = shown_lengths(page)
    count = designs(page)
    start = centre(page, "#syn-linkage [data-handle='P3'] circle")
    page.mouse.move(*start)
    page.mouse.down()
    for i in range(1, 6):
        page.mouse.move(start[0] + 8 * i, start[1] - 6 * i)
    page.mouse.up()
    wait_designs(page, count + 1)
    assert float(page.input_value("#syn-p3-x")) > x3
    status, body = app.post("/synthesis", motion_task(page))
    assert status == 200
    moved = shown_lengths(page)
    assert moved != lengths
    for link, value in moved.items():
        assert value == pytest.approx(body["dimensions"][link], rel=1e-4)
    # The keyboard: a handle takes focus, an arrow key moves it one grid step, Page Up turns it.
    count = designs(page)
    y2, angle2 = float(page.input_value("#syn-p2-y")), float(page.input_value("#syn-p2-angle"))
    page.focus("#syn-linkage [data-handle='P2']")
    page.keyboard.press("ArrowUp")
    page.keyboard.press("PageUp")
    wait_designs(page, count + 1)
    assert float(page.input_value("#syn-p2-y")) > y2
    assert float(page.input_value("#syn-p2-angle")) == angle2 + 5
    status, body = app.post("/synthesis", motion_task(page))
    assert status == 200
    for link, value in shown_lengths(page).items():
        assert value == pytest.approx(body["dimensions"][link], rel=1e-4)
    # the focus stays on the handle the student moved, after the drawing is rebuilt
    assert page.evaluate("() => document.activeElement.dataset.handle") == "P2"
    # Space plays the designed linkage (not the analyser's, hidden behind it)
    assert page.get_attribute("#syn-play", "aria-pressed") == "false"
    page.keyboard.press(" ")
    assert page.get_attribute("#syn-play", "aria-pressed") == "true"
    assert page.get_attribute("#play", "aria-pressed") == "false"


@pytest.mark.slow
def test_a_refused_task_shows_the_servers_reason_next_to_the_fields(app: AppPage) -> None:
    app.log.allow("status of 422")
    page = open_designer(app)
    count = designs(page)
    page.check("input[name='syn-task'][value='quick_return']")
    wait_designs(page, count + 1)
    type_into(page, {"syn-qr-time_ratio": 0.5})
    page.wait_for_function(
        "() => document.getElementById('synthesis-app').dataset.state === 'refused'"
    )
    status, body = app.post(
        "/synthesis",
        {"task": "quick_return", "time_ratio": 0.5, "rocker_length": 0.1, "swing_deg": 60},
    )
    assert status == 422
    assert page.inner_text("#syn-error").strip() == body["detail"]
    assert page.get_attribute("#syn-qr-time_ratio", "aria-invalid") == "true"
    assert page.get_attribute("#syn-qr-rocker_length", "aria-invalid") is None
    # the error sits in the form, under the fields it is about
    error, field = (
        page.locator("#syn-error").bounding_box(),
        page.locator("#syn-qr-time_ratio").bounding_box(),
    )
    form = page.locator("#syn-form").bounding_box()
    assert field["y"] < error["y"] < form["y"] + form["height"]
    # the last design stays drawn; a good value designs again and clears the message
    assert page.locator("#syn-linkage .link").count() == 3
    type_into(page, {"syn-qr-time_ratio": 1.4})
    wait_designs(page, count + 2)
    assert page.inner_text("#syn-error").strip() == ""
    assert page.get_attribute("#syn-qr-time_ratio", "aria-invalid") is None
    ratio = page.eval_on_selector_all(
        "#syn-dimensions tbody tr",
        "(rows) => rows.filter((r) => r.textContent.startsWith('time ratio'))"
        ".map((r) => r.querySelector('td').textContent)",
    )
    assert float(ratio[0]) == pytest.approx(1.4, rel=1e-5)
    app.screenshot("synthesis-quick-return-1440", "#synthesis-app")
    # Three positions that are rotations about one point: the poles coincide, said beside the
    # position fields.
    page.check("input[name='syn-task'][value='motion']")
    wait_settled(page)
    about = [
        (1.0, 0.0, 0.0),
        (math.cos(0.4), math.sin(0.4), 0.4),
        (math.cos(0.9), math.sin(0.9), 0.9),
    ]
    type_into(
        page,
        {f"syn-p{j + 1}-{k}": round(v if k != "angle" else math.degrees(a), 12)
         for j, (x, y, a) in enumerate(about) for k, v in (("x", x), ("y", y), ("angle", a))},
    )  # fmt: skip
    page.wait_for_function(
        "() => document.getElementById('synthesis-app').dataset.state === 'refused'"
    )
    status, body = app.post("/synthesis", motion_task(page))
    assert status == 422
    assert page.inner_text("#syn-error").strip() == body["detail"]
    assert "coincide" in body["detail"]
    assert page.get_attribute("#syn-p2-x", "aria-invalid") == "true"


def test_the_function_task_draws_the_desired_and_generated_curves(app: AppPage) -> None:
    page = open_designer(app)
    count = designs(page)
    page.check("input[name='syn-task'][value='function']")
    wait_designs(page, count + 1)
    type_into(page, {"syn-fn-function": "1/x"})
    wait_designs(page, count + 2)
    page.wait_for_function("() => document.getElementById('syn-error-plot').data?.length === 2")
    page.wait_for_function(
        "() => document.getElementById('syn-curves').layout?.title?.text?.includes('1/x')"
    )
    traces = page.evaluate(
        "() => document.getElementById('syn-curves').data.map((t) => ({name: t.name,"
        " x: Array.from(t.x), y: Array.from(t.y)}))"
    )
    desired, generated, points = traces
    # the desired curve is f(x) = 1/x, computed here
    assert len(desired["x"]) > 100
    for x, y in zip(desired["x"], desired["y"], strict=True):
        assert y == pytest.approx(1 / x, rel=1e-12)
    status, body = app.post(
        "/synthesis",
        {"task": "function", "function": "1/x", "x_range": [1, 2], "input_range_deg": [30, 120],
         "output_range_deg": [60, 150], "precision_points": 3, "ground_length": 1},
    )  # fmt: skip
    assert status == 200
    s = body["structural_error"]
    assert generated["y"] == pytest.approx(s["y_generated"], rel=1e-12)
    # the generated curve passes through the desired one at the precision points, and not
    # elsewhere: the largest gap is the structural error's maximum
    for p, x in zip(body["precision_points"], points["x"], strict=True):
        assert x == pytest.approx(p["x"], rel=1e-12)
    gap = max(
        abs(g - d) for g, d in zip(generated["y"], desired["y"], strict=True) if g is not None
    )
    assert gap == pytest.approx(s["max"], rel=1e-9)
    error = page.evaluate("() => Array.from(document.getElementById('syn-error-plot').data[0].y)")
    assert error == pytest.approx(s["error"], rel=1e-12)
    assert "Freudenstein" in page.inner_text("#syn-steps")
    app.screenshot("synthesis-function-1440", "#synthesis-app")


def test_open_in_the_analyser_loads_the_design_as_a_shared_scene(app: AppPage) -> None:
    page = open_designer(app)
    status, body = app.post("/synthesis", motion_task(page))
    assert status == 200
    page.click("#syn-open")
    page.wait_for_function("() => document.getElementById('preset').dataset.shown === 'shared'")
    app.wait_ready()
    assert page.is_hidden("#synthesis-app") and page.is_visible("#linkage")
    assert "linkage designer" in page.inner_text("#preset-description")
    # the analyser's point fields hold the designed scene's points
    for name, (x, y) in body["scene"]["points"].items():
        assert float(page.input_value(f"#f-point_{name}_0")) == pytest.approx(x, abs=1e-4)
        assert float(page.input_value(f"#f-point_{name}_1")) == pytest.approx(y, abs=1e-4)
    assert page.locator("#linkage .link").count() == 3


@pytest.mark.slow
@pytest.mark.parametrize(("width", "height"), [(1440, 900), (1024, 768), (390, 844)])
def test_screenshots_nothing_cut_off_or_overlapping_and_axe(
    app: AppPage, width: int, height: int
) -> None:
    app.page.set_viewport_size({"width": width, "height": height})
    page = open_designer(app)
    page.click("#syn-play")
    page.wait_for_selector("#syn-steps .step .katex", state="attached")
    app.screenshot(f"synthesis-{width}x{height}")
    assert page.evaluate("() => document.documentElement.scrollWidth <= window.innerWidth + 1")
    panels = shown_boxes(page, "#synthesis-app > .panel")
    assert not overlapping_pairs(panels), "panels overlap"
    form = shown_boxes(page, "#syn-form")[0]
    for box in shown_boxes(page, "#syn-form input, #syn-form button"):
        assert form[0] - 1 <= box[0] and box[2] <= form[2] + 1, (box, form)
    # the handles are inside the drawing
    drawing = shown_boxes(page, "#syn-linkage")[0]
    for box in shown_boxes(page, "#syn-linkage .syn-handles circle"):
        assert drawing[0] <= box[0] and box[2] <= drawing[2], (box, drawing)
        assert drawing[1] <= box[1] and box[3] <= drawing[3], (box, drawing)
    # the linkage's names keep clear of the given pivots' squares and their names ("B" off B1)
    names = shown_boxes(page, "#syn-linkage .point-label")
    handles = shown_boxes(page, "#syn-linkage .syn-pivot rect, #syn-linkage .syn-pivot-label")
    assert names and handles
    for name in names:
        for handle in handles:
            assert not overlapping_pairs([name, handle]), (name, handle)
    assert not app.serious_accessibility_violations("#synthesis-app")
    assert re.search(r"Grashof", page.inner_text("#syn-defects"))

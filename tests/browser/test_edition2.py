"""The browser app, second edition (issue 13): fields that never lie, one crank angle, layout,
export, plots, notation. Driven in Debian's Chromium against the real server, like test_app.py.
"""

from __future__ import annotations

import csv
import io
import json
import math
from pathlib import Path
from typing import Any

import pytest

from tests.browser.conftest import AppPage
from tests.browser.test_app import choose, pause_and_wait, plot_data, wait_analysed, wait_until

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
    page.click("#tab-solution")
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

LABEL_BOXES = """(id) => {
    const div = document.getElementById(id);
    const notes = div.layout.annotations || [];
    return [...div.querySelectorAll('g.annotation')]
        .filter((g) => String(notes[Number(g.dataset.index)]?.name || '').startsWith('label:'))
        .map((g) => { const r = g.querySelector('.annotation-text-g').getBoundingClientRect();
                      return [g.textContent, r.left, r.top, r.right, r.bottom]; });
}"""

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


def test_no_two_polygon_labels_overlap_on_any_preset_or_seed_example(app: AppPage) -> None:
    app.open()
    page = app.page
    values = page.eval_on_selector_all("#preset option", "(os) => os.map((o) => o.value)")
    planar = [v for v in values if "spatial" not in v]
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
    page.wait_for_selector("#steps .katex")
    assert page.locator("#steps .step-units").count() == 0
    requests = len(app.log.requests)
    page.select_option("#units", "mm")
    page.wait_for_selector("#steps .step-units")
    assert not any("/api/v1/" in u for u in app.log.requests[requests:]), "no new request"
    text = page.inner_text("#steps")
    assert "mm/s" in text and "rpm" in text
    line = next(t for t in page.locator("#steps .step-units").all_inner_texts() if "v(B) = (" in t)
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


def test_dragging_a_joint_changes_the_geometry_and_the_analysis_and_undo_restores(
    app: AppPage,
) -> None:
    app.open()
    page = app.page
    pause_and_wait(page)
    assert page.locator("#linkage [data-point]").count() >= 5
    polygon = plot_data(page, "velocity-polygon")
    ground = page.inner_html("#linkage .layer-ground")
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
    page.wait_for_selector("#velocity-polygon .main-svg")
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

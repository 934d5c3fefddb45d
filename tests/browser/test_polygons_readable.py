"""Readable polygons (issue 13): labelled relative and component vectors with their magnitudes,
and a detail at its own scale for polygons too elongated to read. Debian's Chromium against the
real server, like test_app.py.
"""

from __future__ import annotations

import math
from typing import Any
from xml.etree import ElementTree

import pytest

from tests.browser.conftest import AppPage, overlapping_pairs
from tests.browser.test_app import (
    DETAIL_DONE,
    LABELS_PLACED,
    choose,
    download,
    exported_scene,
    pause_and_wait,
)

pytestmark = pytest.mark.browser

ANCHORS = """(id) => Object.fromEntries((document.getElementById(id).layout.annotations || [])
    .filter((a) => String(a.name || '').startsWith('label:')).map((a) => [a.text, [a.x, a.y]]))"""


def analysed_instant(app: AppPage) -> dict[str, Any]:
    """/analyze of the scene shown, at the analysed instant (independent of /solution)."""
    page = app.page
    angle = float(page.get_attribute("#linkage", "data-analysed") or "nan")
    scene = exported_scene(page)
    scene["drivers"][0]["angle_deg"] = math.degrees(angle)
    status, analysis = app.post("/analyze", {"scene": scene})
    assert status == 200, analysis
    return analysis


def test_relative_and_component_vectors_are_labelled_at_their_midpoints(app: AppPage) -> None:
    """Four-bar, coupler segment B -> C: v_CB = ω₃ × r_BC from b, aⁿ_CB = −ω₃² r_BC from b,
    aᵗ_CB = α₃ × r_BC after it; the labels sit at the midpoints (1e-9 relative, the server's
    numbers drawn as they are), the table lists |v_CB| = |ω₃| |BC|, |aⁿ_CB| = ω₃² |BC| and
    |aᵗ_CB| = |α₃| |BC| (1e-3 relative: the table shows 4 significant digits)."""
    app.open()
    page = app.page
    pause_and_wait(page)
    for div in ("velocity-polygon", "acceleration-polygon"):
        page.wait_for_function(LABELS_PLACED, arg=div)
    a = analysed_instant(app)
    pts = a["points"]
    coupler = a["links"]["coupler"]
    w, al = coupler["omega"], coupler["alpha"]
    r = [pts["C"]["position"][i] - pts["B"]["position"][i] for i in (0, 1)]
    bc = math.hypot(*r)
    v_cb = [-w * r[1], w * r[0]]
    a_n = [-w * w * r[0], -w * w * r[1]]
    a_t = [-al * r[1], al * r[0]]
    v_b, a_b = pts["B"]["velocity"], pts["B"]["acceleration"]

    vel = page.evaluate(ANCHORS, "velocity-polygon")
    acc = page.evaluate(ANCHORS, "acceleration-polygon")
    mid = [v_b[i] + v_cb[i] / 2 for i in (0, 1)]
    assert vel["v<sub>CB</sub>"] == pytest.approx(mid, rel=1e-9, abs=1e-12)
    mid = [a_b[i] + a_n[i] / 2 for i in (0, 1)]
    assert acc["a<sup>n</sup><sub>CB</sub>"] == pytest.approx(mid, rel=1e-9, abs=1e-12)
    mid = [a_b[i] + a_n[i] + a_t[i] / 2 for i in (0, 1)]
    assert acc["a<sup>t</sup><sub>CB</sub>"] == pytest.approx(mid, rel=1e-9, abs=1e-12)

    page.click("#magnitudes summary")
    row = page.locator("#polygon-table tr", has_text="C rel. B")
    row.wait_for()
    assert "vCB, anCB, atCB" in row.locator("th").inner_text().replace("\n", "")
    cells = [float(c) for c in row.locator("td").all_inner_texts()]
    expected = [abs(w) * bc, w * w * bc, abs(al) * bc]
    assert cells == pytest.approx(expected, rel=1e-3)
    assert math.hypot(*v_cb) == pytest.approx(
        math.hypot(*(pts["C"]["velocity"][i] - v_b[i] for i in (0, 1))), rel=1e-9
    ), "the closed form agrees with the server's v_C − v_B"


def test_slider_parts_are_labelled_and_listed(app: AppPage) -> None:
    """Quick-return: the slotted lever's slider C has v_C,rel, a_C,rel and a_C,Cor labelled, and
    the table's |a_C,Cor| is 2 |ω_guide| |v_C,rel| (1e-3 relative)."""
    app.open()
    page = app.page
    choose(app, "preset:quick_return")  # its drawing shown (the first instant may come before)
    page.wait_for_selector("#linkage:not([hidden]) .link", state="attached")
    pause_and_wait(page)
    page.wait_for_function(LABELS_PLACED, arg="acceleration-polygon")
    texts = set(page.evaluate(ANCHORS, "acceleration-polygon"))
    a = analysed_instant(app)
    joint = next(j for j in a["joints"] if any(j.get("coriolis_acceleration") or [0]))
    p = joint["point"]
    assert {f"a<sub>{p},Cor</sub>", f"a<sub>{p},rel</sub>"} <= texts, texts
    assert f"v<sub>{p},rel</sub>" in set(page.evaluate(ANCHORS, "velocity-polygon"))
    page.click("#magnitudes summary")
    row = page.locator("#polygon-table tr", has_text=f"{p} Coriolis")
    row.wait_for()
    shown = float(row.locator("td").all_inner_texts()[-1])
    coriolis = 2 * abs(joint["omega_guide"]) * math.hypot(*joint["relative_velocity"])
    assert shown == pytest.approx(coriolis, rel=1e-3)


# ---- a detail at its own scale for elongated polygons ------------------------------------------

# Every drawn line segment of a figure, in data units and in the figure's pixels (read from the
# paths drawn: each trace's stroked paths, one a run of its points between nulls), with the axes'
# ranges and the title.
DRAWN = """(id) => {
    const div = document.getElementById(id);
    const runs = (points) => points.reduce((out, p) => {
        if (p === null) out.push([]); else out[out.length - 1].push(p);
        return out; }, [[]]).filter((r) => r.length);
    const segs = [];
    div.data.forEach((t, i) => {
        if (!String(t.mode || '').includes('lines') || t.visible === 'legendonly') return;
        const data = runs(t.x.map((x, j) => (x === null ? null : [x, t.y[j]])));
        const drawn = [...div.querySelectorAll(`.trace[data-index="${i}"] path[fill="none"]`)]
            .map((p) => [...p.getAttribute('d').matchAll(/[ML](-?[\\d.e-]+),(-?[\\d.e-]+)/g)]
                .map((m) => [Number(m[1]), Number(m[2])]));
        if (drawn.length !== data.length) throw new Error(`${id}: trace ${i} drawn otherwise`);
        data.forEach((run, r) => { for (let j = 0; j + 1 < run.length; j++) {
            segs.push([...run[j], ...run[j + 1], ...drawn[r][j], ...drawn[r][j + 1]]); } });
    });
    const title = div.querySelector('.figure-title');
    return {segs, x: div.layout.xaxis.range, y: div.layout.yaxis.range,
            title: title ? title.textContent.replace(/\\u200b/g, '') : ''};
}"""

CSS_CM = 96 / 2.54  # CSS px

SET_SLIDER = """(f) => { const e = document.getElementById('crank-angle');
    e.value = String(+e.min + f * (e.max - e.min));
    e.dispatchEvent(new Event('input', {bubbles: true}));
    e.dispatchEvent(new Event('change', {bubbles: true}));
    // The drawing takes the new instant at its next frame (main.js drawFrame): until then the
    // linkage's data-instant is still the old one, and equal to data-analysed.
    return new Promise((r) => requestAnimationFrame(() => requestAnimationFrame(r))); }"""


def set_instant(page: Any, fraction: float) -> None:
    """Move the crank-angle (or time) slider to `fraction` of its range and wait for the analysis
    of that instant and its polygons' details."""
    page.evaluate(SET_SLIDER, fraction)
    page.wait_for_function(
        """(f) => { const e = document.getElementById('crank-angle');
                   const d = document.getElementById('linkage').dataset;
                   return Math.abs(+e.value - (+e.min + f * (e.max - e.min))) < 1
                          && d.analysed === d.instant; }""",
        arg=fraction,
    )


def scale_in(title: str, prefix: str) -> float:
    """The value of "<prefix>1 cm = <value> <unit>" in a title."""
    return float(title.split(f"{prefix}1 cm = ")[1].split(" ")[0])


@pytest.mark.parametrize("scene", ["preset:quick_return", "example:S003-T2-rotating-carrier.json"])
def test_an_elongated_acceleration_polygon_gets_a_readable_detail_at_its_stated_scale(
    app: AppPage, scene: str
) -> None:
    """The rule (docs/FRONTEND.md): L the longest segment, s the shortest not under L/1000;
    a detail when s < L/12 (or a sliver with s < L/5). In the detail s is at least 20 px long
    (in the polygon it is not); the detail's "1 cm = X" and the polygon's "1 cm = Y" agree with
    the pixels of every segment, in both directions (1 %); the two scales differ."""
    app.open()
    page = app.page
    choose(app, scene)  # its drawing shown (the first instant may be analysed before that)
    page.wait_for_selector("#linkage:not([hidden]) .link", state="attached")
    pause_and_wait(page)
    set_instant(page, 0.35)
    page.wait_for_function(DETAIL_DONE, arg="acceleration-polygon")
    main = page.evaluate(DRAWN, "acceleration-polygon")
    lengths = [math.hypot(s[2] - s[0], s[3] - s[1]) for s in main["segs"]]
    longest = max(lengths)
    seen = [(n, i) for i, n in enumerate(lengths) if n >= 1e-3 * longest]
    shortest, k = min(seen)
    assert shortest < longest / 12, "this scene's acceleration polygon is elongated"
    assert page.get_attribute("#acceleration-polygon", "data-detail") == "shown"
    assert page.locator("#acceleration-polygon-detail").is_visible()
    page.wait_for_function(LABELS_PLACED, arg="acceleration-polygon-detail")
    detail = page.evaluate(DRAWN, "acceleration-polygon-detail")
    title = detail["title"]
    assert title.startswith("Acceleration detail (dashed box): 1 cm = "), title
    cm_detail = scale_in(title, "(dashed box): ")
    cm_main = scale_in(title, "polygon: ")
    assert cm_detail < cm_main / 1.5, "the detail is drawn larger"

    def px(seg: list[float]) -> float:
        return math.hypot(seg[6] - seg[4], seg[7] - seg[5])

    s_main, s_detail = main["segs"][k], detail["segs"][k]
    assert s_detail[:4] == s_main[:4], "the same segment in both figures"
    inside = lambda seg: all(  # noqa: E731
        detail["x"][0] <= x <= detail["x"][1] and detail["y"][0] <= y <= detail["y"][1]
        for x, y in ((seg[0], seg[1]), (seg[2], seg[3]))
    )
    assert inside(s_detail), "the shortest segment is in the detail"
    assert px(s_detail) >= 20 > px(s_main) * 1.4
    # The data-to-pixel map is linear past the ranges too: every segment checks the scale.
    assert len(detail["segs"]) >= 3
    for seg in detail["segs"]:
        length = math.hypot(seg[2] - seg[0], seg[3] - seg[1])
        assert px(seg) == pytest.approx(length / cm_detail * CSS_CM, rel=0.01)
    for seg in main["segs"]:
        length = math.hypot(seg[2] - seg[0], seg[3] - seg[1])
        assert px(seg) == pytest.approx(length / cm_main * CSS_CM, rel=0.01)
    boxes = page.evaluate(
        "() => document.getElementById('acceleration-polygon').layout.shapes.map((s) => s.type)"
    )
    assert boxes == ["rect"], "the detail's region is marked in the polygon"
    app.screenshot(f"detail-{scene.split(':')[1].split('.')[0]}", ".polygons-panel")


# The panels of a polygon as shown: the polygon with its legend (HTML, under it), and its detail.
PANEL_SIZES = """(id) => [id, `${id}-detail`].map((k) => document.getElementById(k))
    .filter((d) => !d.hidden && d.data).map((d) => {
        const legend = document.getElementById(`${d.id}-legend`);
        const b = (legend ? d.parentElement : d).getBoundingClientRect();
        return [b.width, b.height];
    })"""


def png_size(content: bytes) -> tuple[int, int]:
    assert content[:8] == b"\x89PNG\r\n\x1a\n"
    return int.from_bytes(content[16:20], "big"), int.from_bytes(content[20:24], "big")


def choose_figure(page: Any, div: str, fmt: str) -> None:
    """Open the export menu (it closes after each export) and choose a figure and a format."""
    if not page.evaluate("document.getElementById('export-menu').open"):
        page.click("#export-menu summary")
    page.select_option("#export-figure-which", div)
    page.select_option("#export-figure-format", fmt)


# Whether each polygon is drawn at its div's size (its SVG's), its detail done.
FITTED = """() => ['velocity-polygon', 'acceleration-polygon'].every((id) => {
    const div = document.getElementById(id);
    const svg = div.querySelector('svg.plane-figure');
    const style = getComputedStyle(div);
    return svg && Number(svg.getAttribute('width')) === Math.round(parseFloat(style.width))
        && Number(svg.getAttribute('height')) === Math.round(parseFloat(style.height))
        && ['shown', 'none'].includes(div.dataset.detail);
})"""


def test_the_polygons_are_drawn_again_at_their_size_when_the_window_changes(
    app: AppPage,
) -> None:
    """A polygon is drawn at its div's size (its labels placed for that plot area): a window
    made narrower (1440 to 1024 wide, the polygons move under the drawing) draws both again at
    their new size."""
    app.open()
    page = app.page
    pause_and_wait(page)
    page.wait_for_function(FITTED)
    wide = page.evaluate("() => document.getElementById('velocity-polygon').layout.width")
    page.set_viewport_size({"width": 1024, "height": 768})
    page.wait_for_function(
        f"() => document.getElementById('velocity-polygon').layout.width !== {wide}"
    )
    page.wait_for_function(FITTED)


# The visibility of each trace of a polygon named `name` (true, or 'legendonly' when hidden).
VISIBILITY = """([id, name]) => document.getElementById(id).data
    .filter((t) => t.legendgroup === name).map((t) => t.visible ?? true)"""


def test_a_legend_entry_hides_and_shows_its_traces(app: AppPage) -> None:
    """The polygons' legends are HTML under the figures (docs/FRONTEND.md): the note and one
    entry per group of traces, each a button that hides its traces and shows them again, as a
    click on Plotly's legend did; the four-bar's velocity legend lists its traces' names."""
    app.open()
    page = app.page
    pause_and_wait(page)
    page.wait_for_function(LABELS_PLACED, arg="velocity-polygon")
    names = page.locator("#velocity-polygon-legend button").all_inner_texts()
    traces = page.evaluate(
        """() => document.getElementById('velocity-polygon').data
            .filter((t) => t.showlegend !== false).map((t) => t.name)"""
    )
    assert names == traces and "absolute velocity" in names, (names, traces)
    entry = page.locator("#velocity-polygon-legend button", has_text="absolute velocity")
    shown = ["velocity-polygon", "absolute velocity"]
    assert page.evaluate(VISIBILITY, shown) == [True]
    drawn = "() => document.querySelectorAll('#velocity-polygon .trace').length"
    before = page.evaluate(drawn)
    entry.click()
    assert entry.get_attribute("aria-pressed") == "false"
    page.wait_for_function(f"(a) => ({VISIBILITY})(a).every((v) => v === 'legendonly')", arg=shown)
    assert page.evaluate(drawn) == before - 1, "the hidden trace is no longer drawn"
    entry.click()
    assert entry.get_attribute("aria-pressed") == "true"
    page.wait_for_function(f"(a) => ({VISIBILITY})(a).every((v) => v === true)", arg=shown)
    assert page.evaluate(drawn) == before


# The boxes of an exported SVG's x tick labels and of its legend's entries and note, as a viewer
# shows the image (the document put in the page for the measure, then removed).
EXPORTED_BOXES = """(svg) => {
    const host = document.createElement('div');
    host.style.cssText = 'position: absolute; left: 0; top: 0';
    host.innerHTML = svg;
    document.body.append(host);
    const box = (e) => { const r = e.getBoundingClientRect();
                         return [r.left, r.top, r.right, r.bottom]; };
    const out = [[...host.querySelectorAll('.xtick text')].map(box),
                 [...host.querySelectorAll('.legend .traces, .legend .legendtitletext')].map(box)];
    host.remove();
    return out;
}"""


@pytest.mark.slow
def test_polygon_export_includes_its_detail_panel_as_shown(app: AppPage) -> None:
    """The quick-return at 35 % of the turn: its acceleration polygon has a detail panel. The
    polygon's PNG and SVG hold the polygon and, under it, each panel shown on the page: the PNG
    is as wide as the polygon (magnified to 640 px at least, 2 px per CSS px) and as tall as the
    panels together; the SVG nests one document per panel, the detail at the polygon's height,
    with the detail's title and scale as the page shows them, and the polygon's legend (with the
    acceleration polygon's Coriolis note) clear of its x axis' tick labels (it was drawn over
    them)."""
    app.open()
    page = app.page
    choose(app, "preset:quick_return")
    page.wait_for_selector("#linkage .slider-block", state="attached")
    pause_and_wait(page)
    set_instant(page, 0.35)
    for div in ("velocity-polygon", "acceleration-polygon"):
        page.wait_for_function(DETAIL_DONE, arg=div)
    assert page.get_attribute("#acceleration-polygon", "data-detail") == "shown"
    title = page.evaluate(DRAWN, "acceleration-polygon-detail")["title"]
    scale = f"(dashed box): 1 cm = {title.split('(dashed box): 1 cm = ')[1].split(' ')[0]}"
    for div in ("velocity-polygon", "acceleration-polygon"):
        panels = page.evaluate(PANEL_SIZES, div)
        assert len(panels) == (2 if page.get_attribute(f"#{div}", "data-detail") == "shown" else 1)
        zoom = max(1.0, 640 / panels[0][0])
        heights = [round(h * zoom) for _, h in panels]
        choose_figure(page, div, "png")
        _, png = download(page, "#export-figure")
        assert png_size(png) == (2 * round(panels[0][0] * zoom), 2 * sum(heights)), (div, panels)
        choose_figure(page, div, "svg")
        _, svg = download(page, "#export-figure")
        root = ElementTree.fromstring(svg)
        nested = [e for e in root if e.tag.endswith("svg")]
        assert [float(e.get("y", "0")) for e in nested] == [0.0, *heights[:1]][: len(panels)]
        assert float(root.get("height", "0")) == sum(heights)
        text = "".join(root.itertext())
        assert (scale in text) == (div == "acceleration-polygon"), (div, scale)
        legend = page.locator(f"#{div}-legend button").all_inner_texts()
        assert legend and all(name in text for name in legend), (div, legend)
        ticks, entries = page.evaluate(EXPORTED_BOXES, svg.decode())
        assert ticks and entries, (div, ticks, entries)
        clashes = [(t, e) for t in ticks for e in entries if overlapping_pairs([t, e])]
        assert clashes == [], (div, clashes)


RANGES = """(id) => { const l = document.getElementById(id).layout;
    return [l.xaxis.range, l.yaxis.range, l.width - l.margin.l - l.margin.r,
            l.height - l.margin.t - l.margin.b]; }"""


def test_a_polygon_zooms_pans_and_fits_again(app: AppPage) -> None:
    """The velocity polygon (plane-figure.js): a wheel over it scrolls the page until it has the
    focus; then the wheel zooms about the pointer (the point under it stays there, equal scales
    kept), a mouse drag pans by as many pixels, and 0 or a double click fits it again; the
    figure's keys leave the drawing's zoom alone. Positions to 1e-9 of the span (the map is
    linear)."""
    app.open()
    page = app.page
    pause_and_wait(page)
    page.wait_for_function(FITTED)
    fitted = page.evaluate(RANGES, "velocity-polygon")
    (x0, x1), (y0, y1), w, h = fitted
    box = page.locator("#velocity-polygon").bounding_box()
    assert box is not None
    margin = page.evaluate("() => document.getElementById('velocity-polygon').layout.margin")
    # The pointer about a quarter into the plot area from its left and top (on a whole pixel:
    # a mouse event's coordinates are whole CSS pixels).
    at = (round(box["x"] + margin["l"] + w / 4), round(box["y"] + margin["t"] + h / 4))
    fx = (at[0] - box["x"] - margin["l"]) / w
    fy = (at[1] - box["y"] - margin["t"]) / h
    under = (x0 + fx * (x1 - x0), y1 - fy * (y1 - y0))
    page.mouse.move(*at)
    page.mouse.wheel(0, -300)  # not focused: the page's
    page.evaluate("() => new Promise((r) => requestAnimationFrame(() => requestAnimationFrame(r)))")
    assert page.evaluate(RANGES, "velocity-polygon") == fitted
    page.focus("#velocity-polygon")
    page.mouse.wheel(0, -300)
    page.wait_for_function(f"(id) => ({RANGES})(id)[0][1] < {x1}", arg="velocity-polygon")
    (a0, a1), (b0, b1), _, _ = page.evaluate(RANGES, "velocity-polygon")
    span = x1 - x0
    assert a1 - a0 < span / 1.5, "zoomed in"
    assert (b1 - b0) / h == pytest.approx((a1 - a0) / w, rel=1e-9), "equal scales"
    assert a0 + fx * (a1 - a0) == pytest.approx(under[0], abs=1e-9 * span)
    assert b1 - fy * (b1 - b0) == pytest.approx(under[1], abs=1e-9 * span)
    # A drag 60 px right and 30 px down moves the view by as many pixels.
    k = w / (a1 - a0)
    page.mouse.down()
    page.mouse.move(at[0] + 60, at[1] + 30, steps=3)
    page.mouse.up()
    (c0, _), (d0, _), _, _ = page.evaluate(RANGES, "velocity-polygon")
    assert c0 == pytest.approx(a0 - 60 / k, abs=1e-9 * span)
    assert d0 == pytest.approx(b0 + 30 / k, abs=1e-9 * span)
    zoom = page.get_attribute("#linkage", "data-zoom")
    page.keyboard.press("0")
    assert page.evaluate(RANGES, "velocity-polygon") == fitted
    page.keyboard.press("+")
    assert page.evaluate(RANGES, "velocity-polygon")[0][1] < x1
    assert page.get_attribute("#linkage", "data-zoom") == zoom, "the drawing keeps its zoom"
    page.dblclick("#velocity-polygon")
    assert page.evaluate(RANGES, "velocity-polygon") == fitted


# The tick labels of a polygon as drawn (plane-figure.js), and as Plotly draws them for the same
# size, margins and ranges (its own choice of ticks: the oracle the figure follows).
TICKS = """async (id) => {
    const div = document.getElementById(id);
    const l = div.layout;
    const ours = (axis) => [...div.querySelectorAll(`.tick-label[data-axis="${axis}"]`)]
        .map((t) => t.textContent);
    const probe = document.createElement('div');
    probe.style.cssText = 'position: absolute; left: -5000px; top: 0';
    document.body.append(probe);
    await Plotly.newPlot(probe, [], {width: l.width, height: l.height, margin: l.margin,
        xaxis: {range: l.xaxis.range}, yaxis: {range: l.yaxis.range}}, {staticPlot: true});
    const plotly = (axis) => [...probe.querySelectorAll(`.${axis}tick text`)]
        .map((t) => t.textContent);
    const out = {ours: [ours('x'), ours('y')], plotly: [plotly('x'), plotly('y')]};
    Plotly.purge(probe);
    probe.remove();
    return out;
}"""


@pytest.mark.parametrize("scene", ["preset:four_bar", "preset:quick_return"])
def test_a_polygons_ticks_are_those_plotly_would_draw(app: AppPage, scene: str) -> None:
    """Both polygons and a polygon zoomed in: the tick labels, values and text, are the ones
    Plotly draws on the same axes (a step of 1, 2 or 5 times a power of ten, as many as fit)."""
    app.open()
    page = app.page
    if scene != "preset:four_bar":
        choose(app, scene)
        page.wait_for_selector("#linkage:not([hidden]) .link", state="attached")
    pause_and_wait(page)
    page.wait_for_function(FITTED)
    for div in ("velocity-polygon", "acceleration-polygon"):
        ticks = page.evaluate(TICKS, div)
        assert all(len(axis) >= 3 for axis in ticks["ours"]), ticks
        assert ticks["ours"] == ticks["plotly"], (div, ticks)
    page.focus("#acceleration-polygon")
    for _ in range(3):
        page.keyboard.press("+")
    ticks = page.evaluate(TICKS, "acceleration-polygon")
    assert ticks["ours"] == ticks["plotly"], ticks

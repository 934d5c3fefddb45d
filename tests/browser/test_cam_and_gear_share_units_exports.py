"""The page's share link, units switch and exports for a cam and a gear train (js/cam-view.js,
js/gear-view.js through js/share.js, units.js and export.js): a link opens the same view (scene,
angle or time, playing, units) with the server's numbers, a broken one says why; the units switch
changes every follower, field and speed number by the linkage view's factor (checked against the
server's SI answer); the scene downloaded as JSON is accepted by the server and opens again from
the file; the CSV of the SVAJ table and of the speeds hold the server's numbers in the units
chosen. Screenshots at 1440x900, 1024x768 and 390x844, axe-core on the page. Real server, Debian's
Chromium, real CSP.
"""

from __future__ import annotations

import csv
import io
import json
import math
import re
from pathlib import Path
from typing import Any

import pytest

from tests.browser.conftest import AppPage, pause
from tests.browser.test_app import download
from tests.browser.test_cams import open_cam
from tests.browser.test_gears import open_gears, table

RPM = 60 / (2 * math.pi)  # rad/s -> rpm, the linkage view's factor
NUMBER = r"(-?\d+(?:\.\d+)?(?:e[-+]?\d+)?)"


def pause_cam_at(page: Any, angle: int) -> None:
    pause(page, "#cam-play")
    page.fill("#cam-angle", str(angle))
    page.dispatch_event("#cam-angle", "input")
    page.wait_for_function(
        "(a) => document.getElementById('cam-steps').dataset.angle === a", arg=str(angle)
    )


def readout_numbers(page: Any) -> dict[str, tuple[float, str]]:
    """The cam readout's s, v, a as (number, unit)."""
    text = page.inner_text("#cam-readout")
    found = re.findall(rf"([sva]) = {NUMBER} (\S+?),", text)
    return {name: (float(value), unit) for name, value, unit in found}


def type_in(page: Any, selector: str, value: str) -> None:
    """Type `value` into the field and commit it (one change event, as a user's Enter; no focus
    left behind whose blur would commit it again)."""
    page.eval_on_selector(
        selector,
        "(input, v) => { input.value = v; input.dispatchEvent(new Event('change')); }",
        value,
    )


def assert_shown(shown: tuple[float, str], si_value: float, unit: str) -> None:
    """A readout's number within its 4 significant digits of `si_value` (in `unit`'s scale)."""
    assert shown[0] == pytest.approx(si_value, rel=5e-4) and shown[1] == unit


def share_url(page: Any) -> str:
    page.evaluate("document.getElementById('share-url').value = ''")
    page.click("#share")
    page.wait_for_function("() => document.getElementById('share-url').value.includes('#s=')")
    url: str = page.input_value("#share-url")
    return url


@pytest.mark.slow
def test_a_cam_link_opens_the_same_edited_cam_at_the_same_angle(app: AppPage) -> None:
    page = open_cam(app)
    pause_cam_at(page, 100)
    type_in(page, "#cam-segments tr[data-segment='0'] input[data-field='lift']", "0.02")
    page.wait_for_function(
        "() => document.querySelector(\"#cam-segments tr[data-segment='2'] input\").value"
        " === '0.02'"
    )
    page.wait_for_function("() => document.getElementById('cam-steps').dataset.angle === '100'")
    before = page.inner_text("#cam-readout")
    url = share_url(page)
    other = app.new_page()
    other.goto(url)
    other.wait_for_function("() => document.getElementById('cam-steps').dataset.angle === '100'")
    assert other.inner_text("#cam-readout") == before
    assert other.get_attribute("#cam-play", "aria-pressed") == "false"
    assert other.input_value("#preset") == "cam:cam_roller_translating"
    lifts = other.eval_on_selector_all(
        "#cam-segments input[data-field='lift']", "(xs) => xs.map((x) => x.value)"
    )
    assert lifts == ["0.02", "0.02"]
    # the server's numbers for the edited scene at 100 deg
    status, built = app.post("/presets/cam_roller_translating", {})
    assert status == 200
    for segment in built["segments"]:
        if segment["type"] != "dwell":
            segment["lift"] = 0.02
    status, at = app.post("/analyze", {"scene": built, "angle_deg": 100})
    assert status == 200
    shown = readout_numbers(other)
    assert_shown(shown["s"], at["follower"]["displacement"], "m")
    assert_shown(shown["v"], at["follower"]["velocity"], "m/s")
    other.close()


@pytest.mark.moving
def test_a_gear_link_opens_the_same_train_paused_at_the_same_time(app: AppPage) -> None:
    page = open_gears(app)
    page.select_option("#units", "mm")
    type_in(page, "#gear-fields input[data-key='omega_sun']", "600")
    page.wait_for_function(
        "() => Math.abs(+document.querySelector(\"#gear-fields input[data-key='omega_sun']\")"
        ".dataset.si - 600 / (30 / Math.PI)) < 1e-9"
    )
    page.click("#gear-play")
    page.wait_for_function(
        "() => document.getElementById('gear-play').getAttribute('aria-pressed') === 'false'"
    )
    shown = (page.inner_text("#gear-readout"), page.inner_text("#gear-speeds"))
    url = share_url(page)
    other = app.new_page()
    other.goto(url)
    other.wait_for_selector("#gear-steps .step", state="attached")
    assert (other.inner_text("#gear-readout"), other.inner_text("#gear-speeds")) == shown
    assert other.get_attribute("#gear-play", "aria-pressed") == "false"
    assert other.input_value("#units") == "mm"
    assert other.input_value("#preset") == "gear:planetary_ring_fixed"
    field = other.locator("#gear-fields input[data-key='omega_sun']")
    assert float(field.input_value()) == pytest.approx(600, rel=1e-12)
    # the server's speeds for that input
    status, built = app.post("/presets/planetary_ring_fixed", {"omega_sun": 600 / RPM})
    assert status == 200
    status, speeds = app.post("/analyze", {"scene": built})
    assert status == 200
    for name, omega in table(other).items():
        assert omega == pytest.approx(speeds["members"][name]["omega"], rel=1e-12)
    other.close()


def test_a_link_to_a_refused_gear_train_says_why(app: AppPage) -> None:
    page = open_gears(app)
    url = share_url(page)
    status, built = app.post("/presets/planetary_ring_fixed", {})
    assert status == 200
    built["gears"]["ring"]["teeth"] = 0  # refused by the server
    token = page.evaluate(
        "async (scene) => (await import('/js/share.js')).encodeState({scene,"
        " source: {type: 'gear', name: 'planetary_ring_fixed', params: {}},"
        " view: {family: 'gear_trains', time: 0, playing: false, units: 'si'}})",
        built,
    )
    app.log.allow("status of 422")
    other = app.new_page()
    other.goto(url.split("#")[0] + f"#s={token}")
    other.wait_for_selector("#gear-message:not([hidden])")
    assert "cannot be shown" in other.inner_text("#gear-message")
    assert "teeth" in other.inner_text("#gear-message")
    assert "This link could not be opened" in other.inner_text("#status")
    other.close()


def test_the_units_switch_converts_the_cam_by_the_linkage_views_factors(app: AppPage) -> None:
    page = open_cam(app)
    pause_cam_at(page, 60)
    status, built = app.post("/presets/cam_roller_translating", {})
    assert status == 200
    status, at = app.post("/analyze", {"scene": built, "angle_deg": 60})
    assert status == 200
    si = readout_numbers(page)
    page.select_option("#units", "mm")
    page.wait_for_function(
        "() => document.getElementById('cam-readout').textContent.includes('mm')"
    )
    mm = readout_numbers(page)
    follower = at["follower"]
    assert_shown(mm["s"], follower["displacement"] * 1000, "mm")
    assert_shown(mm["v"], follower["velocity"] * 1000, "mm/s")
    assert_shown(mm["a"], follower["acceleration"] * 1000, "mm/s²")
    for name in "sva":
        assert mm[name][0] == pytest.approx(si[name][0] * 1000, rel=1e-3)
    assert "θ = 60°" in page.inner_text("#cam-readout")  # the cam angle stays in degrees
    # the fields: lengths in mm, the cam speed in rpm
    assert float(page.input_value("#cam-f-base_radius")) == pytest.approx(
        built["cam"]["base_radius"] * 1000, rel=1e-12
    )
    assert float(page.input_value("#cam-f-omega")) == pytest.approx(
        built["cam"]["omega"] * RPM, rel=1e-12
    )
    lift = page.locator("#cam-segments tr[data-segment='0'] input[data-field='lift']")
    assert float(lift.input_value()) == pytest.approx(25, rel=1e-12)
    # the plots: the s row in mm, its axis titled so
    svaj = page.evaluate(
        "() => { const d = document.getElementById('cam-svaj');"
        " return [d.data[0].y[60], d.layout.yaxis.title.text]; }"
    )
    assert svaj == [pytest.approx(follower["displacement"] * 1000, rel=1e-9), "s (mm)"]
    # a value typed in mm reaches the server in m
    type_in(page, "#cam-f-base_radius", "45")
    page.wait_for_function(
        "() => document.getElementById('cam-f-base_radius').dataset.si === '0.045'"
    )


def test_the_units_switch_converts_the_gear_speeds_to_rpm(app: AppPage) -> None:
    page = open_gears(app)
    omega = table(page)
    page.select_option("#units", "mm")
    page.wait_for_function(
        "() => document.getElementById('gear-speeds').textContent.includes('rpm')"
    )
    cells = page.eval_on_selector_all(
        "#gear-speeds tbody tr",
        "(rows) => rows.map((r) =>"
        " [r.dataset.member, r.querySelector('[data-omega]').textContent])",
    )
    for name, text in cells:
        assert float(text) == pytest.approx(omega[name] * RPM, rel=5e-4, abs=1e-9)
    field = page.locator("#gear-fields input[data-key='omega_sun']")
    assert float(field.input_value()) == pytest.approx(
        float(field.get_attribute("data-si") or "nan") * RPM, rel=1e-12
    )
    assert "[rpm]" in page.inner_text("#gear-fields")


def test_cam_exports_are_accepted_back_by_the_server_and_the_page(
    app: AppPage, tmp_path: Path
) -> None:
    page = open_cam(app)
    pause_cam_at(page, 60)
    page.select_option("#units", "mm")
    page.wait_for_function(
        "() => document.getElementById('cam-readout').textContent.includes('mm')"
    )
    name, content = download(page, "#export-scene")
    assert name.endswith(".json")
    scene = json.loads(content)
    status, at = app.post("/analyze", {"scene": scene, "angle_deg": 60})
    assert status == 200
    name, content = download(page, "#export-csv")
    assert name.endswith("-svaj.csv")
    rows = list(csv.reader(io.StringIO(content.decode())))
    header, body = rows[0], rows[1:]
    assert header[:5] == ["cam angle θ [deg]", "s [mm]", "v [mm/s]", "a [mm/s²]", "j [mm/s³]"]
    assert len(body) == 360
    row = next(r for r in body if float(r[0]) == pytest.approx(60))
    assert float(row[1]) == pytest.approx(at["follower"]["displacement"] * 1000, rel=1e-9)
    assert float(row[2]) == pytest.approx(at["follower"]["velocity"] * 1000, rel=1e-9)
    # the file opens again in the cam view
    scene["title"] = "My cam"
    path = tmp_path / "my-cam.json"
    path.write_text(json.dumps(scene))
    page.set_input_files("#import-scene", str(path))
    page.wait_for_function("() => document.getElementById('cam-title').textContent === 'My cam'")
    assert page.locator("#cam-app").is_visible()


def test_gear_exports_are_accepted_back_by_the_server_and_the_page(
    app: AppPage, tmp_path: Path
) -> None:
    page = open_gears(app)
    omega = table(page)
    name, content = download(page, "#export-scene")
    scene = json.loads(content)
    status, speeds = app.post("/analyze", {"scene": scene})
    assert status == 200
    name, content = download(page, "#export-csv")
    assert name.endswith("-speeds.csv")
    rows = list(csv.reader(io.StringIO(content.decode())))
    assert rows[0][3] == "ω [rad/s]"
    for row in rows[1:]:
        assert float(row[3]) == pytest.approx(speeds["members"][row[0]]["omega"], rel=1e-12)
        assert float(row[3]) == pytest.approx(omega[row[0]], rel=1e-12)
    scene["title"] = "My train"
    path = tmp_path / "my-train.json"
    path.write_text(json.dumps(scene))
    page.set_input_files("#import-scene", str(path))
    page.wait_for_function("() => document.getElementById('gear-title').textContent === 'My train'")
    assert set(table(page)) == set(omega)


@pytest.mark.slow
@pytest.mark.parametrize("size", [(1440, 900), (1024, 768), (390, 844)])
def test_the_topbar_tools_fit_with_a_cam_and_a_gear_train(
    app: AppPage, size: tuple[int, int]
) -> None:
    page = app.page
    page.set_viewport_size({"width": size[0], "height": size[1]})
    for opened, name in ((open_cam, "cam"), (open_gears, "gears")):
        opened(app)
        for tool in ("#units", "#share", "#export-menu summary"):
            assert page.locator(tool).is_visible()
        page.click("#export-menu summary")
        assert page.locator("#export-scene").is_visible()
        assert not page.locator("#export-instant-csv").is_visible()
        app.screenshot(f"{name}-tools-{size[0]}x{size[1]}")
        page.click("#export-menu summary")
        # The tools (the cam's and the train's views are axe's in test_cams and test_gears, at
        # the same sizes).
        assert app.serious_accessibility_violations(".topbar") == []

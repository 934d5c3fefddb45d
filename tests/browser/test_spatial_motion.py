"""The spatial arm in the browser (issue 13): it moves over time with Play and the time slider,
the drawn points are the sweep's, the lists and plots are filled, and editing a joint offset or a
link length re-analyses the chain as /analyze says. Real server, Debian's Chromium, real CSP."""

from __future__ import annotations

import copy
import json
import math
from pathlib import Path
from typing import Any

import numpy as np
import pytest

from tests.browser.conftest import AppPage, pause
from tests.browser.test_app import choose

EXAMPLES = Path(__file__).resolve().parents[2] / "server" / "examples"
ARM: dict[str, Any] = json.loads((EXAMPLES / "S002-spatial-arm.json").read_text())


def drawn_points(page: Any) -> dict[str, list[float]]:
    """World positions of the drawn points (data-position on each circle)."""
    pairs = page.eval_on_selector_all(
        "#spatial circle.point",
        "(nodes) => nodes.map((n) => [n.dataset.point, n.dataset.position])",
    )
    return {name: [float(x) for x in where.split(",")] for name, where in pairs}


def screen_points(page: Any) -> dict[str, tuple[float, float]]:
    pairs = page.eval_on_selector_all(
        "#spatial circle.point",
        "(nodes) => nodes.map((n) =>"
        " [n.dataset.point, +n.getAttribute('cx'), +n.getAttribute('cy')])",
    )
    return {name: (x, y) for name, x, y in pairs}


def open_arm(app: AppPage) -> Any:
    app.open()
    page = app.page
    choose(app, "example:S002-spatial-arm.json")
    page.wait_for_selector("#spatial circle.point[data-position]", state="attached")
    page.wait_for_function(
        "() => (document.getElementById('spatial').dataset.instant !== undefined)"
    )
    return page


def pause_at(page: Any, slider_value: int) -> float:
    """Pause, put the time slider at `slider_value` (0..1000), and return the instant shown."""
    pause(page)
    page.eval_on_selector(
        "#crank-angle",
        "(s, v) => { s.value = String(v); s.dispatchEvent(new Event('input', {bubbles: true}));"
        " s.dispatchEvent(new Event('change', {bubbles: true})); }",
        slider_value,
    )
    page.wait_for_timeout(300)
    return float(page.get_attribute("#spatial", "data-instant") or "nan")


def test_the_arm_moves_and_its_points_are_the_sweeps(app: AppPage) -> None:
    page = open_arm(app)
    assert page.locator("#play").is_visible()
    first = screen_points(page)
    page.wait_for_timeout(600)  # playing: the arm has moved
    if page.get_attribute("#play", "aria-pressed") == "true":
        assert screen_points(page) != first
    status, sweep = app.post(
        "/sweep",
        {
            "scene": ARM,
            "samples": 241,
            "quantities": ["position", "velocity", "acceleration"],
            "time_range": [0, 2 * math.pi],
        },
    )
    assert status == 200
    times = np.asarray(sweep["time"])
    moved = []
    for value in (250, 600):
        t = pause_at(page, value)
        i = int(np.argmin(np.abs(times - t)))
        assert abs(times[i] - t) < 1e-9, (t, times[i])  # the slider lands on a sample
        page.wait_for_function(
            "(t) => (document.getElementById('spatial').dataset.instant === String(t))", arg=t
        )
        shown = drawn_points(page)
        for name, where in shown.items():
            np.testing.assert_allclose(where, sweep["points"][name]["position"][i], atol=1e-12)
        moved.append(shown["B"])
    assert np.linalg.norm(np.subtract(moved[0], moved[1])) > 0.05
    # The worked solution is the chain's at the paused sample: its figure, and B's speed there.
    page.click("#tab-solution")
    page.wait_for_selector("#steps .step-figure svg line[data-vector='omega(3)']", state="attached")
    speed = float(np.linalg.norm(sweep["points"]["B"]["velocity"][i]))
    page.wait_for_function(
        "(s) => document.getElementById('steps').textContent.includes(s)",
        arg=f"B moves at a speed of {speed:.4g} m/s",
    )
    page.click("#tab-plots")
    assert page.locator("#spatial-info li").count() >= 6
    assert page.locator("#plots .main-svg").count() > 0
    traces = page.eval_on_selector("#plots", "(d) => d.data.map((t) => t.name)")
    assert any("|ω3|" in n for n in traces) and any("|vB|" in n for n in traces)
    app.screenshot("spatial-arm-moving")
    assert app.log.unexpected_errors() == []


def test_editing_a_length_changes_the_answer_as_analyze_says(app: AppPage) -> None:
    page = open_arm(app)
    pause_at(page, 0)
    length = page.locator("#spatial-length-2")  # body 3: O3 -> B, 0.2 m
    assert float(length.input_value()) == 0.2
    length.fill("0.5")
    length.press("Enter")
    page.wait_for_function(
        "() => { const b = document.querySelector('#spatial circle.point[data-point=\"B\"]');"
        " return b && Math.abs(+b.dataset.position.split(',')[0] - 0.5) < 1e-9; }"
    )
    pause_at(page, 0)
    scene = copy.deepcopy(ARM)
    scene["points"]["B"]["position"] = [0.5, *ARM["points"]["B"]["position"][1:]]
    status, expected = app.post("/analyze", {"scene": scene})
    assert status == 200
    page.wait_for_function(
        "() => [...document.querySelectorAll('#spatial-info li')]"
        ".some((li) => li.textContent.startsWith('vB'))"
    )
    items = page.eval_on_selector_all("#spatial-info li", "(n) => n.map((x) => x.textContent)")
    v_b = next(x for x in items if x.startswith("vB"))
    numbers = [float(x) for x in v_b.split("(")[1].split(")")[0].split(",")]
    np.testing.assert_allclose(numbers, expected["points"]["B"]["velocity"], rtol=1e-3, atol=1e-4)
    assert numbers != [-1.1196, -0.2, -0.69282]  # not the old chain's answer
    assert app.log.unexpected_errors() == []


def test_a_joint_offset_turns_the_chain(app: AppPage) -> None:
    page = open_arm(app)
    pause_at(page, 0)
    before = drawn_points(page)["B"]
    offset = page.locator("#spatial-offset-0")
    offset.fill("90")
    offset.press("Enter")
    page.wait_for_function(
        "() => { const b = document.querySelector('#spatial circle.point[data-point=\"B\"]');"
        " return b && Math.abs(+b.dataset.position.split(',')[1]) < 0.3; }"
    )
    pause_at(page, 0)
    after = drawn_points(page)["B"]
    # 90 deg about z: (x, y, z) -> (-y, x, z)
    np.testing.assert_allclose(after, [-before[1], before[0], before[2]], atol=1e-9)
    bad = page.locator("#spatial-length-0")
    bad.fill("abc")
    bad.press("Enter")
    assert bad.get_attribute("aria-invalid") == "true"
    assert app.log.unexpected_errors() == []


SHOWN = """() => ({
  instant: document.getElementById('spatial').dataset.instant,
  slider: document.getElementById('crank-angle').value,
  playing: document.getElementById('play').getAttribute('aria-pressed'),
  source: document.getElementById('preset').value,
  fields: [...document.querySelectorAll('#spatial-fields input')].map((i) => [i.id, i.value]),
  values: [...document.querySelectorAll('#spatial-info li')].map((li) => li.textContent),
})"""


def edit_field(page: Any, field: str, value: str) -> None:
    """Type `value` into a spatial field and wait for the chain drawn anew."""
    before = drawn_points(page)
    page.fill(field, value)
    page.press(field, "Enter")
    page.wait_for_function(
        "(b) => { const p = document.querySelector('#spatial circle.point[data-point=\"B\"]');"
        " return p && p.dataset.position !== b; }",
        arg=",".join(str(x) for x in before["B"]),
    )


@pytest.mark.slow
def test_share_link_of_an_edited_chain_restores_time_and_fields(app: AppPage) -> None:
    """An edited arm (offset of joint 1 and length of body 3), paused at slider 400 of 1000
    (t = 0.4 T), shared: the link opens at the same instant, with the same fields, the same
    values listed and the same drawn points (1e-12 m); editing the restored chain further gives
    what the same edit gives on the original page (the offsets are not applied twice)."""
    page = open_arm(app)
    edit_field(page, "#spatial-offset-0", "30")
    edit_field(page, "#spatial-length-2", "0.3")
    t = pause_at(page, 400)
    assert t > 0
    page.wait_for_function(
        "(t) => document.getElementById('spatial').dataset.instant === String(t)", arg=t
    )
    page.click("#share")
    page.wait_for_function("() => document.getElementById('share-url').value.includes('#s=')")
    url = page.input_value("#share-url")
    shown = page.evaluate(SHOWN)
    other = app.new_page()
    other.goto(url)
    other.wait_for_selector("#spatial circle.point[data-position]", state="attached")
    other.wait_for_function(
        "(t) => document.getElementById('spatial').dataset.instant === String(t)", arg=t
    )
    restored = other.evaluate(SHOWN)
    assert restored == shown
    assert ["spatial-offset-0", "30"] in restored["fields"]
    for name, where in drawn_points(other).items():
        np.testing.assert_allclose(where, drawn_points(page)[name], atol=1e-12)
    for p in (page, other):
        edit_field(p, "#spatial-offset-1", "45")
    assert other.evaluate(SHOWN) == page.evaluate(SHOWN)
    for name, where in drawn_points(other).items():
        np.testing.assert_allclose(where, drawn_points(page)[name], atol=1e-12)
    assert app.log.unexpected_errors() == []

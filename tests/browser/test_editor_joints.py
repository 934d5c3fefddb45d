"""The "New mechanism" editor beyond revolute joints (issue 13): a slider on a moving guide (a pin
in a slot of a moving link) and a prismatic joint, each with the axis the user gives; Gruebler's
count F = 3(n − 1) − 2j − j₂ with a pin in a slot counted as a two-degree joint; the analysis of
the drawn mechanism equals /analyze of the same scene written by hand. Debian's Chromium against
the real server, like test_app.py.
"""

from __future__ import annotations

import csv
import io
import math
from typing import Any

import pytest

from tests.browser.conftest import AppPage
from tests.browser.test_app import download, exported_scene, pause_and_wait, sheet_click, wait_until

pytestmark = pytest.mark.browser


def axis(deg: float) -> list[float]:
    a = math.radians(deg)
    return [round(math.cos(a), 12), round(math.sin(a), 12)]


def draw(app: AppPage, points: list[tuple[float, float]], fixed: str, bars: list[str]) -> None:
    """Open the editor and draw: points named A, B, … in click order, fixed pivots, bars."""
    page = app.page
    page.click("#new-mechanism")
    page.wait_for_selector("#editor")
    at = dict(zip("ABCDEFGH", points, strict=False))
    for x, y in points:
        sheet_click(page, x, y)
    page.check("input[name='editor-tool'][value='ground']")
    for name in fixed:
        sheet_click(page, *at[name])
    page.check("input[name='editor-tool'][value='link']")
    for a, b in bars:
        sheet_click(page, *at[a])
        sheet_click(page, *at[b])
        page.keyboard.press("Escape")


def sliding(page: Any, tool: str, guide: str, deg: str, xy: tuple[float, float]) -> None:
    """A slider or prismatic joint at the point at `xy`, in `guide`, along `deg`."""
    page.check(f"input[name='editor-tool'][value='{tool}']")
    page.select_option("#editor-guide", guide)
    page.fill("#editor-axis", deg)
    sheet_click(page, *xy)


def analyse(app: AppPage, title: str, driver_at: tuple[float, float]) -> None:
    page = app.page
    page.check("input[name='editor-tool'][value='driver']")
    sheet_click(page, *driver_at)
    page.fill("#editor-title", title)
    page.click("#editor-done")
    wait_until(lambda: page.inner_text("#view-title") == title, what="the drawn mechanism")
    page.wait_for_selector("#linkage .link", state="attached")
    pause_and_wait(page)


def assert_page_analysis_is(app: AppPage, by_hand: dict[str, Any]) -> None:
    """The analysed instant the page offers (its instant CSV, the server's numbers) equals
    /analyze of `by_hand` at the same driver angle: every point's v and a, every link's ω and α
    (1e-9 relative: the same computation, written out in full)."""
    page = app.page
    angle = float(page.get_attribute("#linkage", "data-analysed") or "nan")
    by_hand["drivers"][0]["angle_deg"] = math.degrees(angle)
    status, expected = app.post("/analyze", {"scene": by_hand})
    assert status == 200, expected
    _, content = download(page, "#export-instant-csv")
    rows = {(r[0], r[1]): r for r in csv.reader(io.StringIO(content.decode()))}
    checked = 0
    for name, q in expected["points"].items():
        for quantity in ("velocity", "acceleration"):
            row = rows[(f"point {name}", quantity)]
            assert [float(row[2]), float(row[3])] == pytest.approx(q[quantity], rel=1e-9, abs=1e-12)
            checked += 1
    for name, q in expected["links"].items():
        for quantity in ("omega", "alpha"):
            row = rows[(f"link {name}", quantity)]
            assert float(row[4]) == pytest.approx(q[quantity], rel=1e-9, abs=1e-12)
            checked += 1
    assert checked >= 10


def test_an_inverted_slider_crank_drawn_from_scratch(app: AppPage) -> None:
    """Crank AB about A; lever DC about D; B is a pin in a slot of the lever along 90 deg.
    Before the slot F = 3·2 − 2·2 = 2; with it (j₂ = 1) F = 3·2 − 2·2 − 1 = 1."""
    app.open()
    page = app.page
    draw(app, [(0.0, 0.0), (0.1, 0.1), (0.1, 0.4), (0.1, -0.2)], "AD", ["AB", "DC"])
    assert page.get_attribute("#editor-dof", "data-f") == "2"
    sliding(page, "slider", "DC", "90", (0.1, 0.1))
    assert page.get_attribute("#editor-dof", "data-f") == "1"
    assert "F = 3(n − 1) − 2j − j₂ = 3·2 − 2·2 − 1 = 1" in page.inner_text("#editor-dof")
    assert page.locator("#editor .editor-slider[data-guide='DC']").count() == 1
    app.screenshot("editor-inverted-slider-crank", "#editor-panel")
    analyse(app, "inverted slider-crank", (0.05, 0.05))
    by_hand = {
        "kind": "linkage",
        "title": "inverted slider-crank",
        "points": {"A": [0, 0], "B": [0.1, 0.1], "C": [0.1, 0.4], "D": [0.1, -0.2]},
        "links": {
            "ground": {"points": ["A", "D"], "ground": True},
            "AB": {"points": ["A", "B"]},
            "DC": {"points": ["D", "C"]},
        },
        "joints": [
            {"type": "revolute", "point": "A", "links": ["ground", "AB"]},
            {"type": "slider", "point": "B", "links": ["DC", "AB"], "axis": axis(90)},
            {"type": "revolute", "point": "D", "links": ["ground", "DC"]},
        ],
        "drivers": [{"link": "AB", "omega": 10, "alpha": 0}],
    }
    scene = exported_scene(page)
    key = lambda j: j["point"]  # noqa: E731
    assert sorted(scene["joints"], key=key) == sorted(by_hand["joints"], key=key)
    for name, xy in by_hand["points"].items():
        assert scene["points"][name] == pytest.approx(xy)
    assert_page_analysis_is(app, by_hand)
    # The lever turns: a Coriolis part at B, drawn and labelled in the acceleration polygon.
    page.wait_for_function(
        """() => (document.getElementById('acceleration-polygon').layout?.annotations || [])
                 .some((a) => a.text === 'a<sub>B,Cor</sub>')"""
    )


def test_a_scotch_yoke_with_a_prismatic_joint_drawn_from_scratch(app: AppPage) -> None:
    """Crank AB about A; the yoke CD slides on the ground along 0 deg (prismatic: it cannot
    turn) and B is a pin in the yoke's slot along 90 deg. j = 2 (revolute A, prismatic C),
    j₂ = 1: F = 3·2 − 2·2 − 1 = 1. The yoke translates: v_C = (−ω·AB·sin θ, 0)."""
    app.open()
    page = app.page
    draw(app, [(0.0, 0.0), (0.1, 0.1), (0.1, 0.3), (0.4, 0.3)], "A", ["AB", "CD"])
    sliding(page, "prismatic", "ground", "0", (0.1, 0.3))
    assert page.get_attribute("#editor-dof", "data-f") == "2"
    sliding(page, "slider", "CD", "90", (0.1, 0.1))
    assert page.get_attribute("#editor-dof", "data-f") == "1"
    assert "F = 3(n − 1) − 2j − j₂ = 3·2 − 2·2 − 1 = 1" in page.inner_text("#editor-dof")
    assert page.locator("#editor .editor-prismatic").count() == 2  # the two guide lines
    app.screenshot("editor-scotch-yoke", "#editor-panel")
    analyse(app, "Scotch yoke", (0.05, 0.05))
    by_hand = {
        "kind": "linkage",
        "title": "Scotch yoke",
        "points": {"A": [0, 0], "B": [0.1, 0.1], "C": [0.1, 0.3], "D": [0.4, 0.3]},
        "links": {
            "ground": {"points": ["A"], "ground": True},
            "AB": {"points": ["A", "B"]},
            "CD": {"points": ["C", "D"]},
        },
        "joints": [
            {"type": "revolute", "point": "A", "links": ["ground", "AB"]},
            {"type": "slider", "point": "B", "links": ["CD", "AB"], "axis": axis(90)},
            {"type": "prismatic", "point": "C", "links": ["ground", "CD"], "axis": axis(0)},
        ],
        "drivers": [{"link": "AB", "omega": 10, "alpha": 0}],
    }
    scene = exported_scene(page)
    key = lambda j: j["point"]  # noqa: E731
    assert sorted(scene["joints"], key=key) == sorted(by_hand["joints"], key=key)
    assert_page_analysis_is(app, by_hand)
    angle = float(page.get_attribute("#linkage", "data-analysed") or "nan")
    _, content = download(page, "#export-instant-csv")
    rows = csv.reader(io.StringIO(content.decode()))
    row = next(r for r in rows if r[:2] == ["point C", "velocity"])
    closed = [-10 * math.hypot(0.1, 0.1) * math.sin(angle), 0.0]
    assert [float(row[2]), float(row[3])] == pytest.approx(closed, rel=1e-9, abs=1e-12)


def test_gruebler_counts_a_slider_on_the_ground_as_a_pin_in_a_slot(app: AppPage) -> None:
    """Slider-crank: crank AB, rod BC, C in a slot of the ground: F = 3·2 − 2·2 − 1 = 1 (the
    editor counted the slot as a one-degree joint before, F = 0)."""
    app.open()
    page = app.page
    draw(app, [(0.0, 0.0), (0.1, 0.1), (0.5, 0.0)], "A", ["AB", "BC"])
    sliding(page, "slider", "ground", "0", (0.5, 0.0))
    assert page.get_attribute("#editor-dof", "data-f") == "1"


def test_the_quick_return_opens_in_the_editor_with_its_slot_in_the_lever(app: AppPage) -> None:
    """ "Start from the current mechanism" on the quick-return: the pin A in the lever's slot and
    the ram C on the ground's guide come back as they were (axes to 1e-12), F = 3·3 − 2·3 − 2 = 1,
    and the analysis equals /analyze of the preset's own scene (1e-9)."""
    app.open()
    page = app.page
    page.select_option("#preset", "preset:quick_return")
    page.wait_for_function(
        "() => document.getElementById('preset').value === 'preset:quick_return'"
    )
    pause_and_wait(page)
    original = exported_scene(page)
    page.click("#new-mechanism")
    page.click("#editor-from-current")
    assert page.get_attribute("#editor-dof", "data-f") == "1"
    assert "3·3 − 2·3 − 2 = 1" in page.inner_text("#editor-dof")
    assert page.locator("#editor .editor-slider[data-guide='lever']").count() == 1
    page.fill("#editor-title", "quick-return again")
    page.click("#editor-done")
    wait_until(lambda: page.inner_text("#view-title") == "quick-return again", what="it")
    page.wait_for_selector("#linkage .link", state="attached")
    pause_and_wait(page)
    scene = exported_scene(page)
    for a, b in zip(
        sorted(scene["joints"], key=lambda j: j["point"]),
        sorted(original["joints"], key=lambda j: j["point"]),
        strict=True,
    ):
        assert (a["type"], a["links"]) == (b["type"], b["links"])
        assert a.get("axis", [0, 0]) == pytest.approx(b.get("axis", [0, 0]), abs=1e-12)
    assert scene["drivers"][0]["omega"] == original["drivers"][0]["omega"]
    by_hand = {k: original[k] for k in ("kind", "points", "links", "joints", "drivers")}
    by_hand["drivers"] = [{k: v for k, v in original["drivers"][0].items() if k != "angle_deg"}]
    assert_page_analysis_is(app, by_hand)

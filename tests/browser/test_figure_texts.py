"""The texts of every figure at 1440 wide: none under 11 screen px (the mechanism's drawing with
its instant centres and joint forces, the balanced one beside the dynamics, the polar diagram,
the spatial chain, the editor's sheet, the designer's worked solution, the cam and the gear
train with theirs), and points named by a Greek letter spelled out written as the letter, as
the worked solution writes them (Γ, not Gamma). Real server, real CSP (conftest.app)."""

from __future__ import annotations

import json
from typing import Any

import pytest

from tests.browser.conftest import AppPage, pause
from tests.browser.test_app import choose, pause_and_wait, plot_data, wait_until

pytestmark = pytest.mark.browser

# Every shown text of an SVG figure: where it is, what it says, its size on screen (px).
TEXTS = """() => [...document.querySelectorAll('svg text')]
  .filter((t) => t.getBoundingClientRect().height > 0 && t.textContent.trim())
  .map((t) => {
    const svg = t.ownerSVGElement;
    const box = svg.viewBox.baseVal;
    const k = box && box.width ? svg.getBoundingClientRect().width / box.width : 1;
    let e = t;
    while (e && !e.id) e = e.parentElement;
    return { where: e ? e.id : '', text: t.textContent,
             px: parseFloat(getComputedStyle(t).fontSize) * k };
  })"""

NAMES = """async () => {
  const { pointName, imageName } = await import('/js/notation.js');
  return [['Gamma', 'omega1', 'B', 'O2', 'Gammas', 'Gamma123', 'alpha_1'].map(pointName),
          ['Gamma', 'B', 'Omega'].map(imageName)];
}"""


def small_texts(page: Any) -> list[dict[str, Any]]:
    texts: list[dict[str, Any]] = page.evaluate(TEXTS)
    assert texts, "no figure text on screen"
    return [t for t in texts if t["px"] < 11.0]


@pytest.mark.slow
def test_no_figure_text_is_under_11_px_at_1440_wide(app: AppPage) -> None:
    app.page.set_viewport_size({"width": 1440, "height": 900})
    app.open()
    page = app.page
    # Seed 004 with its dynamics and the balanced mechanism beside the polar diagram.
    choose(app, "preset:seed004")
    pause_and_wait(page)
    page.check("#show-centres")
    page.check("#dynamics-arrows")
    page.check("#dynamics-balance")
    page.wait_for_selector("#dynamics-balanced:not([hidden]) #balanced-linkage .link-label")
    page.wait_for_selector("#linkage .centre-label")
    page.wait_for_selector("#linkage .force-label")
    assert small_texts(page) == []
    point_labels = page.locator("#linkage .point-label").all_text_contents()
    assert "Γ" in point_labels and "Gamma" not in point_labels
    # The counterweights are the textbook's K (crank) and L (rocker).
    balanced = page.locator("#balanced-linkage .point-label").all_text_contents()
    assert {"K", "L", "Γ"} <= set(balanced)
    legend = {t["name"] for t in json.loads(plot_data(page, "dynamics-plots"))}
    assert "|F| at Γ" in legend and "|F| at Gamma" not in legend
    # The transmission angle names its vertex by the letter too (the loop's points A, B, Gamma,
    # as the server names them).
    facts = page.text_content("#mechanism-facts") or ""
    assert "μ = ∠ABΓ" in facts, facts
    # And the preset's description under the menu ("its pivot Γ through B", the API's "Gamma").
    description = page.text_content("#preset-description") or ""
    assert "pivot Γ" in description and "Gamma" not in description, description
    # So do the menus of points: the plotted quantity, the traced path, the point read.
    for menu in ("#plot-point", "#trace-point", "#readout-point"):
        names = page.locator(f"{menu} option").all_text_contents()
        assert any("Γ" in n for n in names) and not any("Gamma" in n for n in names), names
    # And the cycle plots' panel titles, Γ's velocity plotted.
    gamma = page.eval_on_selector_all(
        "#plot-point option",
        "(os) => os.find((o) => o.textContent.startsWith('Γ: velocity')).value",
    )
    page.select_option("#plot-point", gamma)
    titles = ("() => Object.entries(document.getElementById('plots').layout)"
              ".filter(([k]) => k.startsWith('yaxis')).map(([, a]) => a.title.text)")  # fmt: skip
    page.wait_for_function(f"() => ({titles})().some((t) => t.includes('Γ'))")
    assert not any("Gamma" in t for t in page.evaluate(titles)), page.evaluate(titles)
    for value, ready in [
        ("example:S002-spatial-arm.json", "#spatial .point-label"),
        ("design:linkage", "#syn-steps .step-figure svg text"),
    ]:
        choose(app, value)
        page.wait_for_selector(ready)
        assert small_texts(page) == [], value
    # The cam and the gear train, each with its worked solution's figures.
    choose(app, "cam:cam_roller_translating")
    pause(page, "#cam-play")
    page.wait_for_selector("#cam-steps .step")
    assert small_texts(page) == []
    choose(app, "gear:planetary_ring_fixed")
    page.wait_for_selector("#gear-view text")
    wait_until(lambda: page.locator("#gear-steps .step").count() > 0, what="the gear steps")
    assert small_texts(page) == []
    # The editor's sheet with a drawn point.
    choose(app, "preset:four_bar")
    page.click("#new-mechanism")
    box = page.locator("#editor").bounding_box()
    assert box is not None
    page.mouse.click(box["x"] + box["width"] / 3, box["y"] + box["height"] / 2)
    page.wait_for_selector("#editor .point-label")
    assert small_texts(page) == []


def test_a_greek_letter_spelled_out_is_written_as_the_letter(app: AppPage) -> None:
    app.open()
    assert app.page.evaluate(NAMES) == [
        ["Γ", "ω1", "B", "O2", "Gammas", "Gamma123", "alpha_1"],
        ["γ", "b", "ω"],
    ]

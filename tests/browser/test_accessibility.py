"""axe-core on every view a student or an instructor opens: no serious or critical violation
(contrast, names, keyboard-reachable scroll regions, ...) on the app with its plots, its worked
solution, the printable solution page and the exercises page, at the desktop and the phone size.
"""

from __future__ import annotations

import pytest

from tests.browser.conftest import AppPage
from tests.browser.test_app import pause_and_wait

SIZES = [(1440, 900), (390, 844)]


@pytest.mark.slow
@pytest.mark.parametrize(("width", "height"), SIZES)
def test_the_app_with_its_plots_and_its_worked_solution(
    app: AppPage, width: int, height: int
) -> None:
    app.page.set_viewport_size({"width": width, "height": height})
    app.open()
    pause_and_wait(app.page)
    assert not app.serious_accessibility_violations()
    app.page.click("#tab-solution")
    # Every step: behind the closed tab only the first ones were typeset.
    app.page.wait_for_selector("#steps[data-typeset='done'] .katex")
    # The formulas' glyphs (their colour is the text's, whatever the width) at the desktop size.
    assert not app.serious_accessibility_violations(formula_glyphs=width == 1440)


@pytest.mark.slow
def test_the_printable_solution_page(app: AppPage) -> None:
    app.page.goto(f"{app.url}/api/v1/solution.html?preset=four_bar")
    app.page.wait_for_selector(".katex")
    assert not app.serious_accessibility_violations()


@pytest.mark.parametrize(("width", "height"), SIZES)
def test_the_exercises_page(app: AppPage, width: int, height: int) -> None:
    app.page.set_viewport_size({"width": width, "height": height})
    app.page.goto(f"{app.url}/exercises.html#id=four_bar_acceleration:standard:3:0")
    app.page.wait_for_selector("#answer-rows tr")
    assert not app.serious_accessibility_violations()

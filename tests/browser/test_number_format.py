"""Numbers as a textbook prints them in every view (issue 30): the drawing's notes and readouts,
the tables, the dynamics panel, the cams, gears and designer views, in SI and in workshop units,
print no float noise (0.289999, 0.30000000000000004, 1e-17): every number goes through
static/js/units.js's one rounding rule (`fmt`, `typed`, `show`; tests/test_number_format.py).
Real server, Debian's Chromium.
"""

from __future__ import annotations

from typing import Any

import pytest

from tests.browser.conftest import AppPage
from tests.browser.test_app import choose
from tests.browser.test_cams import ROLLER
from tests.browser.test_gears import PLANETARY
from tests.browser.test_synthesis_mode import DESIGN, wait_designs
from tests.test_number_format import NOISE

SHOWN = """() => [document.body.innerText,
  ...[...document.querySelectorAll('input[type=text], input:not([type])')]
     .filter((i) => i.offsetParent !== null).map((i) => i.value)].join('\\n')"""


def noise(page: Any) -> list[str]:
    """The lines of the page's visible text and field values that print float noise."""
    text: str = page.evaluate(SHOWN)
    return [line for line in text.splitlines() if NOISE.search(line)]


@pytest.mark.slow
def test_no_view_prints_float_noise(app: AppPage) -> None:
    app.open()
    page = app.page
    found: dict[str, list[str]] = {}
    choose(app, "preset:seed004")
    page.wait_for_selector("#dynamics:not([hidden])")
    page.wait_for_function("() => document.getElementById('dynamics-info').textContent !== ''")
    page.evaluate(
        """() => { const s = document.getElementById('crank-angle');
                   s.value = '270'; s.dispatchEvent(new Event('change')); }"""
    )
    page.wait_for_function(
        "() => Math.abs(+document.getElementById('linkage').dataset.analysed"
        " - 3 * Math.PI / 2) < 1e-9"
    )
    found["seed004, SI"] = noise(page)
    page.select_option("#units", "mm")
    page.wait_for_function("() => document.body.innerText.includes(' mm')")
    found["seed004, mm"] = noise(page)
    page.select_option("#units", "si")
    for value, ready in (
        (ROLLER, "#cam-svaj .main-svg"),
        (PLANETARY, "#gear-steps .step"),
    ):
        choose(app, value)
        page.wait_for_selector(ready, state="attached")
        found[value] = noise(page)
    choose(app, DESIGN)
    wait_designs(page, 1)
    found[DESIGN] = noise(page)
    assert {k: v for k, v in found.items() if v} == {}

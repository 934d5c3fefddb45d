"""The names in the linkage drawing (points, links, poles) never overlap one another and never
cover a joint (static/js/drawing-labels.js), for every preset and every planar seed example, at
the analysed instant (poles shown) and at slider positions over the whole range, at 1440x1000 and
on a 390x844 phone (where the names are largest beside the links). Debian's Chromium against the
real server.
"""

from __future__ import annotations

import json
import urllib.request
from typing import Any

import pytest

from tests.browser.conftest import AppPage
from tests.browser.test_app import choose, pause_and_wait

pytestmark = pytest.mark.browser

# The boxes of every name and note shown (screen px, as the browser laid them out) and of every
# joint marker shown; a hidden layer (the poles while the pose is not the analysed one) is left out.
SHOWN = """() => {
  const shown = (el) => getComputedStyle(el).visibility !== 'hidden'
    && el.getAttribute('visibility') !== 'hidden';
  const box = (el) => {
    const b = el.getBoundingClientRect();
    return [b.left, b.top, b.right, b.bottom];
  };
  const svg = document.getElementById('linkage');
  return {
    instant: svg.dataset.instant,
    labels: [...svg.querySelectorAll('.point-label, .link-label, .pole-label, .view-note')]
      .filter(shown)
      .map((t) => ({ text: t.textContent, box: box(t) })),
    joints: [...svg.querySelectorAll('.layer-joints circle')].filter(shown)
      .map((c) => ({ name: c.dataset.point || 'moving point', box: box(c) })),
  };
}"""

STOPS = 8  # slider positions tried on each preset, evenly over its range


def overlap(a: list[float], b: list[float]) -> bool:
    return a[0] < b[2] and b[0] < a[2] and a[1] < b[3] and b[1] < a[3]


def clashes(view: dict[str, Any]) -> list[str]:
    """Every pair of names whose boxes intersect, and every name on a joint marker."""
    labels, out = view["labels"], []
    for i, a in enumerate(labels):
        out += [
            f"{a['text']} on {b['text']}" for b in labels[i + 1 :] if overlap(a["box"], b["box"])
        ]
        out += [
            f"{a['text']} on joint {j['name']}"
            for j in view["joints"]
            if overlap(a["box"], j["box"])
        ]
    return out


def sources(app: AppPage) -> list[str]:
    """Every preset and seed example the page draws, as the selector's values."""
    with urllib.request.urlopen(f"{app.url}/api/v1/presets", timeout=30) as response:
        presets = [f"preset:{p['name']}" for p in json.load(response)["presets"]]
    with urllib.request.urlopen(f"{app.url}/examples/index.json", timeout=30) as response:
        listed = json.load(response)["examples"]
    drawn = ("linkage", "spatial_chain")  # a gear train example is for the API (issue 25)
    examples = [f"example:{e['file']}" for e in listed if e.get("kind", "linkage") in drawn]
    return presets + examples


def move_slider(page: Any, stop: int) -> str:
    """The instant slider moved to stop k of STOPS over its range (an input event, as a dragged
    slider sends), and the frame drawn (two animation frames later): the value set."""
    value: str = page.evaluate(
        """([k, n]) => new Promise((done) => {
             const s = document.getElementById('crank-angle');
             const [lo, hi] = [Number(s.min), Number(s.max)];
             s.value = String(lo + ((hi - lo) * k) / n);
             s.dispatchEvent(new Event('input'));
             requestAnimationFrame(() => requestAnimationFrame(() => done(s.value)));
           })""",
        [stop, STOPS],
    )
    return value


@pytest.mark.slow
@pytest.mark.parametrize("viewport", [(1440, 1000), (390, 844)], ids=["1440x1000", "390x844"])
def test_names_in_the_drawing_never_overlap(app: AppPage, viewport: tuple[int, int]) -> None:
    app.page.set_viewport_size({"width": viewport[0], "height": viewport[1]})
    app.open()
    page = app.page
    found: dict[str, list[str]] = {}
    poles = 0
    for name in sources(app):
        choose(app, name)
        if page.locator("#linkage[hidden]").count():
            continue  # the spatial arm: no linkage drawing
        pause_and_wait(page)
        view = page.evaluate(SHOWN)
        assert any("(" in label["text"] for label in view["labels"]), "no link names shown"
        poles += sum(label["text"][0] in "IΓ" for label in view["labels"])
        found[f"{name} analysed"] = clashes(view)
        for stop in range(STOPS):
            value = move_slider(page, stop)
            found[f"{name} at stop {stop} (slider {value})"] = clashes(page.evaluate(SHOWN))
    assert not {k: v for k, v in found.items() if v}
    assert len(found) >= 14 * STOPS and poles >= 4, (len(found), poles)

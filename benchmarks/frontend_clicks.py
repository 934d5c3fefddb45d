"""Time from a click or a slider input to the drawn frame that shows its result, in headless
Chromium, against a baseline measured in the same run.

Starts the real app with uvicorn on a free loopback port, opens the page in Debian's Chromium at
1440x900, and measures each input in the page itself (no Playwright round trip inside the
interval): ``t0 = performance.now()``, the input is dispatched as the browser dispatches a user's
(a ``change`` on the select or the slider, a ``click`` on a tab), then every animation frame
checks the state the page signals when the result is drawn, and the time is taken once the
first frame that sees it has painted it (a task posted from that frame's animation callback runs
after its paint; before 2026-11-29 the time was taken at the next frame's callback, which also
counted the work the page does after the result is shown, such as a polygon's detail drawn after
the paint, and one more frame):

- baseline: a ``click`` on an element with no handler, until the next frame (the floor every
  input pays: one event and one frame);
- crank slider: a new crank angle until ``#linkage[data-analysed]`` is that angle (set once the
  drawing and the velocity and acceleration polygons of the instant are drawn);
- preset switch: another mechanism in the menu until ``#preset[data-shown]`` is it and
  ``#linkage[data-analysed]`` is set again (its drawing and polygons drawn);
- a field edit: the crank length of the four-bar until ``#linkage[data-analysed]`` is set again;
- method switch, with the worked solution shown: the other method until ``#steps[data-method]``
  is it (its first steps typeset);
- worked-solution tab: a click on the tab until its panel is shown with a typeset step.

Then every linkage preset of the menu, each visited once from the one before (its first visit,
nothing reused: the preset, its sweep and its instant fetched), and its worked-solution tab
opened once its solution is in; before each visit the page is let quiet (what the previous
mechanism does after its instant is shown, its cycle plots and dynamics, not counted in the
next), and with ``--pages N`` the round is made in N new pages (N first visits of each preset).

The page reuses an answer it has already fetched (api.js), so an input seen before costs no
request: the slider and the field are given a value not asked before at every input (each input
pays the server), and the table gives, beside the median and the worst, the first input of each
case (for the preset switch and the method: the first visit, before any answer is reused).

Usage: ``.venv/bin/python benchmarks/frontend_clicks.py [--repeat 7] [--pages 1]``. Each case is
run ``repeat`` times in the same page, alternating between two targets so that every input
changes something; the table gives the median, the worst and the first, and each median less the
baseline's.
"""

from __future__ import annotations

import argparse
import os
import statistics
import sys
from collections.abc import Callable
from pathlib import Path
from typing import Any

ROOT = Path(__file__).resolve().parents[1]
if str(ROOT) not in sys.path:  # run as `python benchmarks/frontend_clicks.py`
    sys.path.insert(0, str(ROOT))

from benchmarks.frontend_fps import ARGS, CHROMIUM  # noqa: E402
from server.local import serve_locally  # noqa: E402


def none(_: int) -> None:
    """No value (the baseline's click)."""
    return None


# In the page: dispatch the input named `kind` with `value`, then the ms to the paint of the first
# frame on which the page signals its result (rejects after 30 s).
TIME_INPUT = """([kind, value]) => new Promise((resolve, reject) => {
  const $ = (id) => document.getElementById(id);
  const linkage = $('linkage');
  let done;
  const t0 = performance.now();
  if (kind === 'baseline') {
    document.querySelector('footer').dispatchEvent(new MouseEvent('click', { bubbles: true }));
    done = () => true;
  } else if (kind === 'slider') {
    const s = $('crank-angle');
    s.value = String(value);
    s.dispatchEvent(new Event('input', { bubbles: true }));
    s.dispatchEvent(new Event('change', { bubbles: true }));
    done = () => Math.abs(+linkage.dataset.analysed - (value * Math.PI) / 180) < 1e-9;
  } else if (kind === 'preset') {
    delete linkage.dataset.analysed;
    const sel = $('preset');
    sel.value = value;
    sel.dispatchEvent(new Event('change', { bubbles: true }));
    done = () => sel.dataset.shown === value && linkage.dataset.analysed !== undefined;
  } else if (kind === 'field') {
    delete linkage.dataset.analysed;
    const field = $('f-param_crank');
    field.value = String(value);
    field.dispatchEvent(new Event('change', { bubbles: true }));
    done = () => linkage.dataset.analysed !== undefined;
  } else if (kind === 'method') {
    document.querySelector(`input[name="method"][value="${value}"]`).click();
    const steps = $('steps');
    done = () => steps.dataset.method === value && steps.querySelector('.step .katex') !== null;
  } else if (kind === 'tab') {
    $(value).click();
    done = value === 'tab-solution'
      ? () => !$('solution-panel').hidden && document.querySelector('#steps .step .katex') !== null
      : () => $('solution-panel').hidden;
  }
  const check = () => {
    if (done()) setTimeout(() => resolve(performance.now() - t0), 0);
    else if (performance.now() - t0 > 30000) reject(new Error(`${kind} ${value}: none in 30 s`));
    else requestAnimationFrame(check);
  };
  requestAnimationFrame(check);
})"""

# (label, kind, the value of the i-th timed input, the value of the i-th input back, not timed)
CASES: list[tuple[str, str, Callable[[int], Any], Callable[[int], Any]]] = [
    ("baseline: a click with no handler, to the next frame", "baseline", none, none),
    (
        "crank slider to a new angle (four-bar)",
        "slider",
        lambda i: 60 + 7 * i,
        lambda i: 200 + 7 * i,
    ),
    (
        "preset switch (four-bar <-> quick-return)",
        "preset",
        lambda i: "preset:quick_return",
        lambda i: "preset:four_bar",
    ),
    (
        "preset switch (four-bar <-> seed 004, with dynamics)",
        "preset",
        lambda i: "preset:seed004",
        lambda i: "preset:four_bar",
    ),
    (
        "a field edit: a new crank length (four-bar)",
        "field",
        lambda i: 0.12 + 0.001 * i,
        lambda i: 0.15,
    ),
    (
        "method switch, worked solution shown (four-bar)",
        "method",
        lambda i: "loop",
        lambda i: "vector",
    ),
    ("worked-solution tab (four-bar)", "tab", lambda i: "tab-solution", lambda i: "tab-plots"),
]


def measure(
    page: Any, kind: str, to: Callable[[int], Any], back: Callable[[int], Any], repeat: int
) -> list[float]:
    """The times of `repeat` inputs `to(i)` (each followed by one `back(i)`, not timed, so that
    every timed input changes the page)."""
    times = []
    for i in range(repeat):
        times.append(float(page.evaluate(TIME_INPUT, [kind, to(i)])))
        page.evaluate(TIME_INPUT, [kind, back(i)])
    return times


# The menu's linkage presets (their values, ``preset:<name>``).
PRESETS = """() => [...document.querySelectorAll('#preset option')]
  .map((o) => o.value).filter((v) => v.startsWith('preset:'))"""


def settle(page: Any, cdp: Any) -> None:
    """Wait until the page's main thread is quiet: under 10 ms of tasks in 250 ms (Chrome's
    ``TaskDuration``), so that what the previous mechanism does once its instant is shown (its
    cycle plots, its dynamics, the worked solution's later steps) is not counted in the next
    visit (at most 10 s)."""

    def busy() -> float:
        metrics = cdp.send("Performance.getMetrics")["metrics"]
        return float(next(m["value"] for m in metrics if m["name"] == "TaskDuration"))

    for _ in range(40):
        before = busy()
        page.wait_for_timeout(250)
        if busy() - before < 0.010:
            return


def every_preset(page: Any, cdp: Any) -> list[tuple[str, float, float]]:
    """Each linkage preset of the menu visited once from the one before (its first visit: no
    answer reused), the page quiet before it (``settle``), and then, once its worked solution
    is in (``#steps[data-method]``, cleared before the visit), the worked-solution tab opened:
    (preset, ms of the visit, ms of the tab)."""
    rows = []
    for value in page.evaluate(PRESETS):
        page.evaluate("() => { delete document.getElementById('steps').dataset.method; }")
        settle(page, cdp)
        visit = float(page.evaluate(TIME_INPUT, ["preset", value]))
        page.wait_for_function("() => document.getElementById('steps').dataset.method")
        tab = float(page.evaluate(TIME_INPUT, ["tab", "tab-solution"]))
        page.evaluate(TIME_INPUT, ["tab", "tab-plots"])
        rows.append((value.removeprefix("preset:"), visit, tab))
    return rows


def open_paused(browser: Any, url: str) -> tuple[Any, Any]:
    """A new page of the app at 1440x900, its first instant analysed, paused; and its CDP
    session (with the Performance domain on, for ``settle``)."""
    page = browser.new_page(viewport={"width": 1440, "height": 900})
    cdp = page.context.new_cdp_session(page)
    cdp.send("Performance.enable")
    page.goto(url)
    page.wait_for_function(
        "() => performance.getEntriesByName('first-frame').length > 0", timeout=60_000
    )
    page.wait_for_function("() => document.getElementById('linkage').dataset.analysed")
    if page.get_attribute("#play", "aria-pressed") == "true":
        page.click("#play")
    return page, cdp


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeat", type=int, default=7)
    parser.add_argument(
        "--pages", type=int, default=1, help="first visits of every preset: in as many new pages"
    )
    args = parser.parse_args()
    from playwright.sync_api import Error as PlaywrightError
    from playwright.sync_api import sync_playwright

    rows = []
    visits: dict[str, list[tuple[float, float]]] = {}
    with serve_locally() as url, sync_playwright() as pw:
        browser = pw.chromium.launch(executable_path=CHROMIUM, args=ARGS)
        page, cdp = open_paused(browser, url)
        for label, kind, to, back in CASES:
            if kind == "method":  # the method's result is the worked solution: shown
                page.evaluate(TIME_INPUT, ["tab", "tab-solution"])
            try:
                times = measure(page, kind, to, back, args.repeat)
            except PlaywrightError as err:  # a page without the signal waited on (an older app)
                print(f"{label}: {err}", file=sys.stderr)
                continue
            rows.append((label, statistics.median(times), max(times), times[0]))
        page.evaluate(TIME_INPUT, ["tab", "tab-plots"])
        for n in range(args.pages):
            if n:
                page.close()
                page, cdp = open_paused(browser, url)
            for name, visit, tab in every_preset(page, cdp):
                visits.setdefault(name, []).append((visit, tab))
        browser.close()
    base = rows[0][1]
    load = os.getloadavg()[0]
    print(
        f"click to drawn frame, headless Chromium 1440x900, {args.repeat} inputs per case "
        f"(median, worst, first); load average {load:.2f} on {os.cpu_count()} cores"
    )
    print()
    print(
        "| input | ms to the drawn frame (median / worst / first) | median less the baseline ms |"
    )
    print("|---|---:|---:|")
    for label, median, worst, first in rows:
        print(f"| {label} | {median:.0f} / {worst:.0f} / {first:.0f} | {median - base:.0f} |")
    print()
    print(
        "Every linkage preset of the menu, visited once from the one before (no answer reused), "
        f"in {args.pages} page(s) (median / worst):"
    )
    print()
    print("| preset | ms to the drawn frame (first visit) | worked-solution tab, ms |")
    print("|---|---:|---:|")
    for name, times in visits.items():
        v, t = [x[0] for x in times], [x[1] for x in times]
        print(
            f"| {name} | {statistics.median(v):.0f} / {max(v):.0f}"
            f" | {statistics.median(t):.0f} / {max(t):.0f} |"
        )
    every = [x for times in visits.values() for x in times]
    v, t = [x[0] for x in every], [x[1] for x in every]
    print(
        f"| all {len(every)} visits | {statistics.median(v):.0f} / {max(v):.0f}"
        f" | {statistics.median(t):.0f} / {max(t):.0f} |"
    )


if __name__ == "__main__":
    main()

"""Frame rate of the animation and time to the first drawn frame, in headless Chromium.

Starts the real app with uvicorn on a free loopback port, opens the page in Debian's Chromium,
and for each case measures:

- first frame: ``performance.mark('first-frame')`` (set by static/js/main.js when the mechanism is
  first drawn), in ms from navigation start; this includes fetching the presets, building the
  preset scene and the one sweep of the cycle;
- fps: requestAnimationFrame callbacks counted over ~3 s while the mechanism plays, with the
  longest frame and the number of frames over 20 ms.

Usage: ``.venv/bin/python benchmarks/frontend_fps.py [--seconds 3] [--repeat 3]``. Each case is
run ``repeat`` times in a fresh page; the table gives the median (and the worst) so that another
process stealing the CPU for a moment does not decide the result. Headless Chromium has no display
to sync to: fps here is the page's own rate under the headless compositor (at most ~60), not a
monitor's refresh rate.
"""

from __future__ import annotations

import argparse
import os
import statistics
import sys
from pathlib import Path
from typing import Any

ROOT = Path(__file__).resolve().parents[1]
if str(ROOT) not in sys.path:  # run as `python benchmarks/frontend_fps.py`
    sys.path.insert(0, str(ROOT))

from server.local import serve_locally  # noqa: E402

CHROMIUM = "/usr/bin/chromium"
ARGS = [
    "--headless=new",
    "--no-sandbox",
    "--disable-gpu",
    "--disable-quic",
    "--no-first-run",
    "--disable-background-networking",
    "--disable-component-update",
    "--disable-sync",
]

# (label, preset selector value or None for the default page, viewport)
CASES: list[tuple[str, str | None, tuple[int, int]]] = [
    ("four-bar (opening page), laptop", None, (1440, 1000)),
    ("four-bar (opening page), tablet", None, (820, 1180)),
    ("quick-return, laptop", "preset:quick_return", (1440, 1000)),
    ("seed S001 slider-crank, laptop", "example:S001-offset-slider-crank.json", (1440, 1000)),
]

COUNT_FRAMES = """(ms) => new Promise((resolve) => {
  const times = [];
  const t0 = performance.now();
  function step(t) {
    times.push(t);
    if (t - t0 < ms) requestAnimationFrame(step);
    else {
      const gaps = times.slice(1).map((x, i) => x - times[i]);
      resolve({
        frames: times.length - 1,
        seconds: (times[times.length - 1] - times[0]) / 1000,
        longest: Math.max(...gaps),
        over20: gaps.filter((g) => g > 20).length,
      });
    }
  }
  requestAnimationFrame(step);
})"""


def measure(
    browser: Any, url: str, case: tuple[str, str | None, tuple[int, int]], seconds: float
) -> dict[str, Any]:
    label, choice, (width, height) = case
    page = browser.new_page(viewport={"width": width, "height": height})
    page.goto(url)
    page.wait_for_function("performance.getEntriesByName('first-frame').length > 0", timeout=30_000)
    first = page.evaluate("performance.getEntriesByName('first-frame')[0].startTime")
    if choice:
        page.select_option("#preset", choice)
        page.wait_for_timeout(1500)
    page.wait_for_selector("#linkage .link", state="attached")
    # Let the first analysis, Plotly and KaTeX settle, then count frames while playing.
    page.wait_for_timeout(1500)
    playing = page.get_attribute("#play", "aria-pressed") == "true"
    result = page.evaluate(COUNT_FRAMES, seconds * 1000)
    page.close()
    return {
        "case": label,
        "first_frame_ms": first,
        "fps": result["frames"] / result["seconds"],
        "longest_ms": result["longest"],
        "over20": result["over20"],
        "playing": playing,
    }


def summarise(runs: list[dict[str, Any]]) -> dict[str, Any]:
    med = statistics.median
    return {
        "case": runs[0]["case"],
        "first_frame_ms": med(r["first_frame_ms"] for r in runs),
        "first_frame_worst": max(r["first_frame_ms"] for r in runs),
        "fps": med(r["fps"] for r in runs),
        "fps_worst": min(r["fps"] for r in runs),
        "longest_ms": med(r["longest_ms"] for r in runs),
        "over20": med(r["over20"] for r in runs),
        "playing": all(r["playing"] for r in runs),
    }


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--seconds", type=float, default=3.0)
    parser.add_argument("--repeat", type=int, default=3)
    args = parser.parse_args()
    from playwright.sync_api import sync_playwright

    rows = []
    with serve_locally() as url, sync_playwright() as pw:
        browser = pw.chromium.launch(executable_path=CHROMIUM, args=ARGS)
        for case in CASES:
            runs = [measure(browser, url, case, args.seconds) for _ in range(args.repeat)]
            rows.append(summarise(runs))
        browser.close()
    load = os.getloadavg()[0]
    print(
        f"frontend frame rate, headless Chromium, {args.seconds:g} s per run, "
        f"{args.repeat} runs per case (median, worst); load average {load:.2f} "
        f"on {os.cpu_count()} cores"
    )
    print()
    print(
        "| case | first frame ms (median / worst) | fps (median / worst) "
        "| longest frame ms (median) | frames > 20 ms (median) | playing |"
    )
    print("|---|---:|---:|---:|---:|---|")
    for r in rows:
        print(
            f"| {r['case']} | {r['first_frame_ms']:.0f} / {r['first_frame_worst']:.0f} "
            f"| {r['fps']:.1f} / {r['fps_worst']:.1f} | {r['longest_ms']:.1f} "
            f"| {r['over20']:.0f} | {'yes' if r['playing'] else 'no'} |"
        )


if __name__ == "__main__":
    main()

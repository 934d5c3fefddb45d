"""Fixtures for the browser tests: Debian's Chromium and a watched page of the real app.

The app is the session's one uvicorn on a free loopback port (``live_server`` in tests/conftest.py),
exactly as a student would reach it. Every page records its console errors, page errors and
request URLs; a test fails when the page logged an error it did not expect or asked any host
other than 127.0.0.1 for anything.
"""

from __future__ import annotations

import json
import re
import tempfile
import time
import urllib.error
import urllib.request
from collections.abc import Iterator
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import pytest
from axe_playwright_python.sync_playwright import Axe

ROOT = Path(__file__).resolve().parents[2]
CHROMIUM = Path("/usr/bin/chromium")
SCREENSHOTS = ROOT / "test-artifacts" / "screenshots"
CHROMIUM_ARGS = [
    "--headless=new",
    "--no-sandbox",
    "--disable-gpu",
    "--disable-quic",
    "--no-first-run",
    "--disable-background-networking",
    "--disable-component-update",
    "--disable-sync",
]


@pytest.fixture(scope="session")
def chromium() -> Iterator[Any]:
    """Debian's Chromium with a profile of its own for this worker's session (a browser context
    on disk), every test a new page of it. Unlike a fresh incognito context a test, the profile
    keeps V8's compiled code of the app's scripts between pages: from its third page on, a page
    parses none of them again (Plotly, KaTeX, 33 modules), about 0.65 s of CPU less an opening
    (2.6 -> 1.9 s, the app's first page at 1440x1000 and the 1.5 s after it). The app keeps
    nothing in the browser (no cookie, no storage), so what a page inherits from the ones before
    is the browser's caches only: that compiled code and the HTTP cache (the static files, and
    the GETs the server lets be cached: the presets' listing, the examples)."""
    if not CHROMIUM.exists():
        pytest.skip(
            "Debian's Chromium is not installed at /usr/bin/chromium (tests/run.sh installs it)"
        )
    from playwright.sync_api import sync_playwright

    pw = sync_playwright().start()
    profile = tempfile.TemporaryDirectory(prefix="chromium-profile-")
    context = pw.chromium.launch_persistent_context(
        profile.name,
        executable_path=str(CHROMIUM),
        args=CHROMIUM_ARGS,
        viewport={"width": 1440, "height": 1000},
    )
    try:
        yield context
    finally:
        context.close()
        pw.stop()
        profile.cleanup()


# The axe-core rules that can only report minor or moderate violations: the rule's own impact,
# where it states one, and that of every one of its checks is one of those (run in the page).
MINOR_RULES = """() => {
  const low = (impact) => impact === 'minor' || impact === 'moderate';
  const checks = axe._audit.data.checks;
  return axe._audit.rules
    .filter((rule) => {
      const ids = [...rule.any, ...rule.all, ...rule.none].map((c) => c.id || c);
      return (rule.impact == null || low(rule.impact)) && ids.length > 0
        && ids.every((id) => low(checks[id]?.impact));
    })
    .map((rule) => rule.id);
}"""


# axe-core on ``context`` (a selector, or the whole document) with the ``disabled`` rules off
# and every subtree that is not rendered (display: none) excluded, and those matching ``skipped``
# (a selector, or null); the serious and critical violations, each as "rule: node".
AXE_RUN = """async ([context, disabled, skipped]) => {
  const root = context ? document.querySelector(context) : document.body;
  const excluded = [];
  const walk = (element) => {
    for (const child of element.children) {
      if ((skipped && child.matches(skipped)) || getComputedStyle(child).display === 'none') {
        excluded.push(child);
      } else walk(child);
    }
  };
  walk(root);
  const options = {
    resultTypes: ['violations'],
    rules: Object.fromEntries(disabled.map((rule) => [rule, { enabled: false }])),
  };
  const scope = { include: [context ? root : document], exclude: excluded };
  const results = await axe.run(scope, options);
  return results.violations
    .filter((v) => v.impact === 'serious' || v.impact === 'critical')
    .flatMap((v) => v.nodes.map((node) => `${v.id}: ${JSON.stringify(node.target)}`));
}"""


@dataclass
class PageLog:
    """What one page did: console errors, uncaught errors, every URL it asked for, and the
    requests still waiting for their answer."""

    errors: list[str] = field(default_factory=list)
    requests: list[str] = field(default_factory=list)
    in_flight: set[Any] = field(default_factory=set)
    allowed: list[re.Pattern[str]] = field(default_factory=list)

    def allow(self, pattern: str) -> None:
        """Expect console errors matching `pattern` (e.g. the 422 of a rejected length)."""
        self.allowed.append(re.compile(pattern))

    def unexpected_errors(self) -> list[str]:
        return [e for e in self.errors if not any(p.search(e) for p in self.allowed)]

    def external_requests(self) -> list[str]:
        return [u for u in self.requests if not _is_local(u)]


def _is_local(url: str) -> bool:
    if url.startswith(("data:", "blob:", "about:")):
        return True
    return re.match(r"^https?://127\.0\.0\.1(:\d+)?/", url) is not None


def _watch(page: Any, log: PageLog) -> None:
    def on_console(msg: Any) -> None:
        if msg.type == "error":
            where = (msg.location or {}).get("url", "")
            log.errors.append(f"{msg.text} [{where}]")

    page.on("console", on_console)
    page.on("pageerror", lambda err: log.errors.append(f"page error: {err}"))

    def on_request(req: Any) -> None:
        log.requests.append(req.url)
        log.in_flight.add(req)

    page.on("request", on_request)
    page.on("requestfinished", lambda req: log.in_flight.discard(req))
    page.on("requestfailed", lambda req: log.in_flight.discard(req))


@dataclass
class AppPage:
    page: Any
    log: PageLog
    url: str  # the base URL of the app, http://127.0.0.1:<port>
    context: Any = None

    def post(self, path: str, body: Any) -> tuple[int, Any]:
        """POST `body` as JSON to /api/v1`path` straight to the server: (status, JSON answer)."""
        request = urllib.request.Request(
            f"{self.url}/api/v1{path}",
            data=json.dumps(body).encode(),
            headers={"Content-Type": "application/json"},
            method="POST",
        )
        try:
            with urllib.request.urlopen(request, timeout=30) as response:
                return response.status, json.load(response)
        except urllib.error.HTTPError as err:
            return err.code, json.load(err)

    def new_page(self) -> Any:
        """Another tab of the same browser, watched like the first."""
        page = self.context.new_page()
        page.set_default_timeout(20_000)
        _watch(page, self.log)
        return page

    def open(self, fragment: str = "") -> None:
        self.page.goto(f"{self.url}/{fragment}")
        self.wait_ready()

    def wait_ready(self) -> None:
        """The mechanism is drawn and the analysed instant's polygons are there."""
        self.page.wait_for_selector("#linkage .link, #spatial .body", state="attached")
        if self.page.locator("#linkage:not([hidden])").count():
            self.page.wait_for_function(
                "() => ("
                "document.getElementById('velocity-polygon').data !== undefined"
                " || !document.getElementById('polygon-message').hidden"
                ")"
            )

    def wait_settled(self) -> None:
        """Everything a planar mechanism's page asks the server for has come back: the worked
        solution shown is the analysed instant's, the cycle plots are the geometry's shown (not
        ``aria-busy``), the dynamics panel is drawn (or hidden) and no request is in flight.
        (The solution is asked for once the analysed instant is painted, the dynamics sweep once
        the plots are drawn: a test that counts the requests an action makes waits for this
        first.)"""
        self.page.wait_for_function(
            """() => { const $ = (id) => document.getElementById(id);
                       const analysed = $('linkage').dataset.analysed;
                       return analysed !== undefined && $('steps').dataset.instant === analysed
                         && !$('plots').hasAttribute('aria-busy')
                         && ($('dynamics').hidden
                             || $('dynamics-hodograph').dataset.note !== undefined); }"""
        )
        deadline = time.monotonic() + 15
        while self.log.in_flight:  # (Playwright hands over its events while it waits)
            waiting = [r.url for r in self.log.in_flight]
            assert time.monotonic() < deadline, f"requests still in flight: {waiting}"
            self.page.wait_for_timeout(50)

    def serious_accessibility_violations(
        self, context: str | None = None, *, formula_glyphs: bool = True
    ) -> list[str]:
        """axe-core (the version bundled with axe-playwright-python, run in the page) on the
        page or the element ``context``: each serious or critical violation as "rule: node"
        (empty when the page is clean).

        With ``formula_glyphs=False`` the glyphs of the typeset formulas are left out: KaTeX
        writes each formula twice, as MathML (what a screen reader reads, still checked) and as
        the glyphs a reader sees (``.katex-html``, aria-hidden, in the colour of the text around
        them). They are three quarters of a worked solution's elements (24,000 to 38,000 for
        seed 004's methods) and about half of axe's time on it (seed 004's static solution:
        13-14 s against 7.5-8.7 s). A test whose subject is not the formulas' contrast says so;
        test_accessibility.py checks them on the worked solution and the printable page.

        Two things are left out, neither of which can change the answer:

        - the rules that can only find minor or moderate violations (``MINOR_RULES``: a
          violation's impact is its worst failed check's), about a sixth of axe's time;
        - the subtrees that are not rendered (``display: none``: a closed tab, a view of another
          kind of mechanism; ``AXE_RUN``). Assistive technology does not reach them, axe's rules
          skip hidden nodes, and each is checked when it is shown by a test of its own. Walking
          them was about half of axe's time on a page holding a hidden worked solution (the
          cam at 1440x900: 2.2 to 2.6 s against 5.3 to 5.8 s)."""
        if not self.page.evaluate("() => typeof axe === 'object'"):
            self.page.evaluate(Axe().axe_script)
        unheeded: list[str] = self.page.evaluate(MINOR_RULES)
        skipped = None if formula_glyphs else ".katex-html"
        found: list[str] = self.page.evaluate(AXE_RUN, [context, unheeded, skipped])
        return found

    def screenshot(self, name: str, selector: str | None = None) -> Path:
        SCREENSHOTS.mkdir(parents=True, exist_ok=True)
        path = SCREENSHOTS / f"{name}.png"
        # A long page (a printable sheet with its solutions) takes seconds to paint on a loaded
        # machine: the picture is an artifact, not a check, so it gets a minute.
        if selector:
            self.page.locator(selector).screenshot(path=str(path), timeout=60_000)
        else:
            self.page.screenshot(path=str(path), full_page=True, timeout=60_000)
        return path


@pytest.fixture
def app(request: pytest.FixtureRequest, chromium: Any, live_server: str) -> Iterator[AppPage]:
    # The pages run under the server's Content-Security-Policy, as a student's do (a violation
    # is a console error, which fails the test). Predicates are written as functions: Playwright
    # evaluates a bare expression with eval when it polls, which the policy forbids.
    # They open paused, as the app opens for a student whose system asks for reduced motion
    # (docs/FRONTEND.md): a mechanism playing costs the browser about half a core for as long as
    # it plays (0.45-0.5 s of CPU a second, paused 0.07 s), which the other tests running beside
    # it would pay for. A test of the animation itself is marked `moving`.
    motion = "no-preference" if request.node.get_closest_marker("moving") else "reduce"
    page = chromium.new_page()
    page.emulate_media(reduced_motion=motion)
    page.set_default_timeout(20_000)
    log = PageLog()
    _watch(page, log)
    try:
        yield AppPage(page=page, log=log, url=live_server, context=chromium)
        external = log.external_requests()
        assert not external, f"requests to other hosts: {external}"
        unexpected = log.unexpected_errors()
        assert not unexpected, f"console or page errors: {unexpected}"
    finally:
        for opened in chromium.pages:  # this test's pages (its own tabs, popups)
            opened.close()


def pytest_terminal_summary(terminalreporter: Any) -> None:
    if SCREENSHOTS.exists() and any(SCREENSHOTS.iterdir()):
        terminalreporter.write_line(f"browser screenshots: {SCREENSHOTS}")


def pytest_configure(config: Any) -> None:
    config.addinivalue_line("markers", "browser: drives the page in headless Chromium")
    config.addinivalue_line(
        "markers", "moving: the page opens playing (the others open paused: reduced motion)"
    )


def pause(page: Any, play: str = "#play") -> None:
    """Stop the mechanism whose Play button is ``play`` if it moves (a test's page opens paused
    unless the test is marked moving): the linkage's ``#play``, the cam's ``#cam-play``, the
    gear train's ``#gear-play``."""
    if page.get_attribute(play, "aria-pressed") == "true":
        page.click(play)


def shown_boxes(page: Any, selector: str) -> list[list[float]]:
    """The screen boxes [left, top, right, bottom] (px) of the shown elements matching
    ``selector``."""
    found: list[list[float]] = page.evaluate(
        "(s) => [...document.querySelectorAll(s)].filter((e) => e.offsetParent !== null)"
        ".map((e) => { const r = e.getBoundingClientRect();"
        " return [r.left, r.top, r.right, r.bottom]; })",
        selector,
    )
    return found


def overlapping_pairs(
    boxes: list[list[float]], slack: float = 1.0
) -> list[tuple[list[float], ...]]:
    """Every pair of boxes that overlap by more than ``slack`` px (sub-pixel layout rounding)."""
    return [
        (a, b)
        for i, a in enumerate(boxes)
        for b in boxes[i + 1 :]
        if not (a[2] <= b[0] + slack or b[2] <= a[0] + slack or a[3] <= b[1] + slack
                or b[3] <= a[1] + slack)
    ]  # fmt: skip

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
from typing import TYPE_CHECKING, Any

import pytest
from axe_playwright_python.sync_playwright import Axe

if TYPE_CHECKING:
    from playwright.sync_api import ViewportSize

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


VIEWPORT: ViewportSize = {"width": 1440, "height": 1000}  # a test's page as it opens
BLANK_TIMEOUT = 10_000  # ms for the tab to leave a test's page for about:blank
TESTS_A_TAB = 10  # tests whose pages open in one tab before the next gets a new one (``Tab``)


@pytest.fixture(scope="session")
def chromium() -> Iterator[Any]:
    """Debian's Chromium with a profile of its own for this worker's session (a browser context
    on disk). Unlike a fresh incognito context a test, the profile keeps V8's compiled code of
    the app's scripts between pages: from its third page on, a page parses none of them again
    (Plotly, KaTeX, 33 modules), about 0.65 s of CPU less an opening (2.6 -> 1.9 s, the app's
    first page at 1440x1000 and the 1.5 s after it). The app keeps nothing in the browser (no
    cookie, no storage), so what a page inherits from the ones before is the browser's caches
    only: that compiled code and the HTTP cache (the static files, and the GETs the server lets
    be cached: the presets' listing, the examples)."""
    if not CHROMIUM.exists():
        pytest.skip(
            "Debian's Chromium is not installed at /usr/bin/chromium (tests/run.sh installs it)"
        )
    from playwright.sync_api import sync_playwright

    pw = sync_playwright().start()
    profile = tempfile.TemporaryDirectory(prefix="chromium-profile-")
    context = pw.chromium.launch_persistent_context(
        profile.name, executable_path=str(CHROMIUM), args=CHROMIUM_ARGS, viewport=VIEWPORT
    )
    try:
        yield context
    finally:
        context.close()
        pw.stop()
        profile.cleanup()


class Tab:
    """The browser tab the tests' pages open in, one per worker's session, as a student's tab
    goes from one page of the app to the next; a new tab every ``TESTS_A_TAB`` tests and after a
    test that failed (whatever state it left: a mouse button held, a page that hangs). A page
    opened in a tab that has shown the app costs the browser about half the CPU of one opened in
    a new tab, a new renderer process that Playwright attaches to anew (docs/FRONTEND.md,
    "Tests", has the measurements).

    Between two tests the tab is emptied (``leave``): the test's listeners (``AppPage.listen``)
    and routes are removed and it goes to about:blank, where a new tab starts, so every test
    opens its page into a new document."""

    def __init__(self, context: Any) -> None:
        self.context = context
        self.page: Any = None
        self.served = 0

    def take(self) -> Any:
        """The tab for the next test, a new one where ``leave`` (or a test, or a crash) closed
        the last."""
        if self.page is None or self.page.is_closed():
            self.page = self.context.new_page()
            self.served = 0
        self.served += 1
        return self.page

    def leave(self, failed: bool) -> None:
        """Remove the routes a test set on the tab and go to about:blank; close it instead after
        a failed test, after its ``TESTS_A_TAB``-th test, or where it cannot leave its page (one
        that hangs): the next test gets a new one."""
        if not failed and self.served < TESTS_A_TAB:
            try:
                self.page.unroute_all(behavior="ignoreErrors")
                self.page.goto("about:blank", timeout=BLANK_TIMEOUT)
                return
            except Exception:  # (whatever went wrong with that page, the next test's is new)
                pass
        self.page.close()


@pytest.fixture(scope="session")
def tab(chromium: Any) -> Tab:
    return Tab(chromium)


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


def _watch(page: Any, log: PageLog) -> list[tuple[str, Any]]:
    """Record what ``page`` does in ``log``; the (event, handler) pairs registered."""

    def on_console(msg: Any) -> None:
        if msg.type == "error":
            where = (msg.location or {}).get("url", "")
            log.errors.append(f"{msg.text} [{where}]")

    def on_request(req: Any) -> None:
        log.requests.append(req.url)
        log.in_flight.add(req)

    handlers = [
        ("console", on_console),
        ("pageerror", lambda err: log.errors.append(f"page error: {err}")),
        ("request", on_request),
        ("requestfinished", lambda req: log.in_flight.discard(req)),
        ("requestfailed", lambda req: log.in_flight.discard(req)),
    ]
    for event, handler in handlers:
        page.on(event, handler)
    return handlers


@dataclass
class AppPage:
    page: Any
    log: PageLog
    url: str  # the base URL of the app, http://127.0.0.1:<port>
    context: Any = None
    handlers: list[tuple[str, Any]] = field(default_factory=list)  # on ``page``, for this test

    def listen(self, event: str, handler: Any) -> None:
        """``page.on(event, handler)`` for this test only (removed when it ends: the tab is the
        next test's too)."""
        self.page.on(event, handler)
        self.handlers.append((event, handler))

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
def app(
    request: pytest.FixtureRequest, chromium: Any, tab: Tab, live_server: str
) -> Iterator[AppPage]:
    # The page runs under the server's Content-Security-Policy, as a student's does (a violation
    # is a console error, which fails the test). Predicates are written as functions: Playwright
    # evaluates a bare expression with eval when it polls, which the policy forbids.
    # It opens paused, as the app opens for a student whose system asks for reduced motion
    # (docs/FRONTEND.md): a mechanism playing costs the browser about half a core for as long as
    # it plays (0.45-0.5 s of CPU a second, paused 0.07 s), which the other tests running beside
    # it would pay for. A test of the animation itself is marked `moving`.
    motion = "no-preference" if request.node.get_closest_marker("moving") else "reduce"
    page = tab.take()
    failures = request.session.testsfailed  # (counted as each phase is reported: setup, call)
    page.set_viewport_size(VIEWPORT)
    page.emulate_media(media="null", reduced_motion=motion)
    page.set_default_timeout(20_000)
    log = PageLog()
    opened = AppPage(page=page, log=log, url=live_server, context=chromium)
    opened.handlers += _watch(page, log)
    try:
        yield opened
        external = log.external_requests()
        assert not external, f"requests to other hosts: {external}"
        unexpected = log.unexpected_errors()
        assert not unexpected, f"console or page errors: {unexpected}"
    finally:
        if not page.is_closed():
            for event, handler in opened.handlers:
                page.remove_listener(event, handler)
            tab.leave(request.session.testsfailed > failures)
        for other in chromium.pages:  # this test's own tabs and popups
            if other is not tab.page:
                other.close()


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

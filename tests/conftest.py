"""The live server every HTTP and browser test shares, and how the suite is split between
processes (solver tests need none of it).

``live_server`` starts the app the way a user does (server.local.serve_locally: ``python -m
uvicorn server.app:app`` from the repository root on a free loopback port), waits for GET /health,
yields the base URL and stops the process at the end of the session. It is the only server a
pytest process starts for the shared tests: the API tests and the browser tests share it. Its
output goes to test-artifacts/uvicorn-WORKER.log (WORKER: the pytest-xdist worker, gw0 or gw1,
or main without xdist). server.local uses the standard library only, so the solver tests run with
numpy, scipy and sympy installed and no web framework; the in-process ``client`` lives in
tests/server/conftest.py.

tests/run.sh runs the suite in two processes (pytest-xdist, ``-n 2 --dist loadgroup``). Every
test under tests/browser is one work unit (``BrowserTestsTogether``): one worker runs them all,
with one Chromium, while the other runs the solver and API tests, then both share what is left.
The tests marked ``serial`` (timed against servers of their own under load) are left out of that
run with ``--serial=skip`` and run after it, alone, with ``--serial=only``: mark them with
``pytest.mark.serial`` written in their module (``pytestmark = pytest.mark.serial`` or a
decorator), which is what ``--serial=only`` looks for before importing a module.
"""

from __future__ import annotations

import contextlib
import os
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import pytest
from xdist.scheduler import LoadGroupScheduling

from server.local import serve_locally

ROOT = Path(__file__).resolve().parents[1]
WORKER = os.environ.get("PYTEST_XDIST_WORKER", "main")
SERVER_LOG = ROOT / "test-artifacts" / f"uvicorn-{WORKER}.log"
# s for the server to answer GET /health: a few on a quiet machine; two workers each starting one
# while the other jobs of a loaded 2-core machine run took more than serve_locally's 40 s.
SERVER_START_TIMEOUT = 120.0
BROWSER_TESTS = "tests/browser/"  # the start of their node ids (relative to the root)


class BrowserTestsTogether(LoadGroupScheduling):  # type: ignore[misc]
    """pytest-xdist's ``loadgroup`` scheduling (a test is a work unit, tests of one
    ``xdist_group`` are one), with every browser test in one work unit, ``browser``.

    Done here rather than with ``xdist_group`` marks: pytest-xdist 3.8 groups by a suffix it
    writes into the node id (``...@browser``), which pytest 9.2's node ids no longer take, so the
    marks are silently ignored (pytest-dev/pytest-xdist#1386)."""

    def _split_scope(self, nodeid: str) -> str:
        if nodeid.startswith(BROWSER_TESTS):
            return "browser"
        scope: str = super()._split_scope(nodeid)
        return scope


@pytest.hookimpl(optionalhook=True)
def pytest_xdist_make_scheduler(config: pytest.Config, log: Any) -> Any:
    """``--dist loadgroup`` schedules with ``BrowserTestsTogether``; other modes are xdist's."""
    if config.getvalue("dist") != "loadgroup":
        return None
    return BrowserTestsTogether(config, log)


def pytest_addoption(parser: pytest.Parser) -> None:
    parser.addoption(
        "--serial",
        choices=("all", "skip", "only"),
        default="all",
        help="the tests marked serial: run them with the others (all, the default), leave them "
        "out (skip) or run only them (only); tests/run.sh runs skip in two processes, then only",
    )


def pytest_ignore_collect(collection_path: Path, config: pytest.Config) -> bool | None:
    """With ``--serial=only``, a test module whose text never says ``mark.serial`` is not
    collected at all (importing every module costs about half a minute; the serial tests are in
    a few). None: pytest decides as usual."""
    if config.getoption("serial") != "only" or not collection_path.name.startswith("test_"):
        return None
    if collection_path.suffix != ".py" or "mark.serial" in collection_path.read_text():
        return None
    return True


def pytest_collection_modifyitems(config: pytest.Config, items: list[pytest.Item]) -> None:
    """Keep or drop the ``serial`` tests as ``--serial`` says (dropped ones are deselected)."""
    serial = config.getoption("serial")
    if serial == "all":
        return
    keep: list[pytest.Item] = []
    dropped: list[pytest.Item] = []
    for item in items:
        wanted = (item.get_closest_marker("serial") is not None) == (serial == "only")
        (keep if wanted else dropped).append(item)
    if dropped:
        config.hook.pytest_deselected(items=dropped)
        items[:] = keep


@pytest.fixture(scope="session")
def live_server() -> Iterator[str]:
    SERVER_LOG.parent.mkdir(parents=True, exist_ok=True)
    with contextlib.ExitStack() as stack:
        log = stack.enter_context(SERVER_LOG.open("w+b"))
        try:
            base = stack.enter_context(serve_locally(log, timeout=SERVER_START_TIMEOUT))
        except RuntimeError as err:
            pytest.fail(f"{err}\n(log: {SERVER_LOG})", pytrace=False)
        yield base

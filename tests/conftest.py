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
test module is one work unit, handed out heaviest first (``ModulesHeaviestFirst``): each worker
runs browser modules with a Chromium of its own and its own live server, and both end on short
solver modules.

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
# A browser test takes about 20 times as long as the mean of the others (a CI run of main on
# 2026-11-29: 147 browser tests in 774 s, the other 3466 in about 980 s of the 2 x 876 s), a test
# marked slow about 40 times (10 s and more among that run's 80 slowest).
BROWSER_WEIGHT = 20
SLOW_WEIGHT = 40


class ModulesHeaviestFirst(LoadGroupScheduling):  # type: ignore[misc]
    """pytest-xdist's ``loadgroup`` scheduling with every test module one work unit (its
    module-scoped fixtures, a venv or a server, are built once, by one worker) and the units
    handed out heaviest first, so that the last ones to run are short and both workers end
    together (``cost``).

    Done here rather than with ``xdist_group`` marks: pytest-xdist 3.8 groups by a suffix it
    writes into the node id (``...@browser``), which pytest 9.2's node ids no longer take, so the
    marks are silently ignored (pytest-dev/pytest-xdist#1386)."""

    ordered = False

    def _split_scope(self, nodeid: str) -> str:
        return nodeid.split("::", 1)[0]

    def _assign_work_unit(self, node: Any) -> None:
        """Hand out the heaviest unit left (the queue is sorted once, before the first)."""
        if not self.ordered:
            queue = self.workqueue
            for scope in sorted(queue, key=lambda s: -cost(s, len(queue[s]))):
                queue.move_to_end(scope)
            self.ordered = True
        super()._assign_work_unit(node)


def cost(module: str, tests: int) -> int:
    """The expected time of running ``tests`` tests of ``module`` (its path from the root), in
    units of a mean solver test: a browser test counts ``BROWSER_WEIGHT``, another test 1, and
    every ``mark.slow`` written in the module ``SLOW_WEIGHT`` more (ModulesHeaviestFirst's
    order; an estimate from the node ids and the module's text: the controller, which orders
    the units, collects no test)."""
    if module.startswith(BROWSER_TESTS):
        return BROWSER_WEIGHT * tests
    path = ROOT / module
    slow = path.read_text().count("mark.slow") if path.suffix == ".py" else 0
    return tests + SLOW_WEIGHT * slow


@pytest.hookimpl(optionalhook=True)
def pytest_xdist_make_scheduler(config: pytest.Config, log: Any) -> Any:
    """``--dist loadgroup`` schedules with ``ModulesHeaviestFirst``; other modes are xdist's."""
    if config.getvalue("dist") != "loadgroup":
        return None
    return ModulesHeaviestFirst(config, log)


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

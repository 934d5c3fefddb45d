"""The live server every HTTP and browser test shares (solver tests need none of it).

``live_server`` starts the app the way a user does (server.local.serve_locally: ``python -m
uvicorn server.app:app`` from the repository root on a free loopback port), waits for GET /health,
yields the base URL and stops the process at the end of the session. It is the only server a
pytest process starts: the API tests and the browser tests share it. Its output goes to
test-artifacts/uvicorn-WORKER.log (WORKER: the pytest-xdist worker, or main). server.local uses
the standard library only, so the solver tests run with numpy, scipy and sympy installed and no
web framework; the in-process ``client`` lives in tests/server/conftest.py.
"""

from __future__ import annotations

import contextlib
import os
from collections.abc import Iterator
from pathlib import Path

import pytest

from server.local import serve_locally

ROOT = Path(__file__).resolve().parents[1]
# One log per pytest-xdist worker (tests/run.sh runs two): each worker starts its own server.
WORKER = os.environ.get("PYTEST_XDIST_WORKER", "main")
SERVER_LOG = ROOT / "test-artifacts" / f"uvicorn-{WORKER}.log"
BROWSER_TESTS = ROOT / "tests" / "browser"


def pytest_collection_modifyitems(items: list[pytest.Item]) -> None:
    """Every browser test in one pytest-xdist group (run with ``--dist loadgroup``): one Chromium
    at a time, in one worker, while the other worker runs the solver and API tests."""
    for item in items:
        if item.path.is_relative_to(BROWSER_TESTS):
            item.add_marker(pytest.mark.xdist_group("browser"))


@pytest.fixture(scope="session")
def live_server() -> Iterator[str]:
    SERVER_LOG.parent.mkdir(parents=True, exist_ok=True)
    with contextlib.ExitStack() as stack:
        log = stack.enter_context(SERVER_LOG.open("w+b"))
        try:
            base = stack.enter_context(serve_locally(log))
        except RuntimeError as err:
            pytest.fail(f"{err}\n(log: {SERVER_LOG})", pytrace=False)
        yield base

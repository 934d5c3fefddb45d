"""The live server every HTTP and browser test shares (solver tests need none of it).

``live_server`` starts the app the way a user does (server.local.serve_locally: ``python -m
uvicorn server.app:app`` from the repository root on a free loopback port), waits for GET /health,
yields the base URL and stops the process at the end of the session. It is the only server the
suite starts: the API tests and the browser tests share it. Its output goes to
test-artifacts/uvicorn.log. server.local uses the standard library only, so the solver tests run
with numpy, scipy and sympy installed and no web framework; the in-process ``client`` lives in
tests/server/conftest.py.
"""

from __future__ import annotations

import contextlib
from collections.abc import Iterator
from pathlib import Path

import pytest

from server.local import serve_locally

ROOT = Path(__file__).resolve().parents[1]
SERVER_LOG = ROOT / "test-artifacts" / "uvicorn.log"


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

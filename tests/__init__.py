"""Test suite. Hypothesis runs without per-example deadlines: timing is measured by the
benchmarks, never asserted in tests (a loaded CI machine would make deadlines flaky)."""

import asyncio
from collections.abc import Coroutine
from concurrent.futures import ThreadPoolExecutor
from typing import Any, TypeVar

from hypothesis import settings

T = TypeVar("T")

settings.register_profile("suite", deadline=None, derandomize=True, print_blob=True)
settings.load_profile("suite")


def run_apart(coroutine: Coroutine[Any, Any, T]) -> T:
    """``asyncio.run(coroutine)`` in a thread of its own: after the browser tests, Playwright's
    sync API leaves an event loop running in the main thread, where asyncio.run refuses."""
    with ThreadPoolExecutor(1) as thread:
        return thread.submit(asyncio.run, coroutine).result()

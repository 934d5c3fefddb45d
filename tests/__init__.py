"""Test suite. Hypothesis runs without per-example deadlines: timing is measured by the
benchmarks, never asserted in tests (a loaded CI machine would make deadlines flaky)."""

from hypothesis import settings

settings.register_profile("suite", deadline=None, derandomize=True, print_blob=True)
settings.load_profile("suite")

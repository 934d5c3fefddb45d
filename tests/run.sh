#!/usr/bin/env bash
# Set up everything the test suite needs on a fresh machine (Python 3.11, pip, apt), then run
# the whole suite: lint (ruff, mypy, hadolint) and pytest (solver, API over loopback, browser).
set -euo pipefail
cd "$(dirname "$0")/.."

SUDO=""
if [ "$(id -u)" != "0" ]; then SUDO="sudo"; fi

# Debian's own Python needs python3-venv for `python3 -m venv` (other builds have it).
if ! python3 -m venv .venv; then
  $SUDO apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq python3-venv >/dev/null
  python3 -m venv .venv
fi
.venv/bin/python -m pip install --quiet --upgrade pip
.venv/bin/python -m pip install --quiet -r requirements-test.lock -e '.[test]'

# The browser tests drive Debian's Chromium (no browser download works offline).
if [ ! -x /usr/bin/chromium ]; then
  $SUDO apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq chromium >/dev/null
fi

.venv/bin/ruff check solver server tests benchmarks
.venv/bin/ruff format --check solver server tests benchmarks
.venv/bin/mypy
.venv/bin/hadolint Dockerfile

# Dependency audit against the PyPI advisory service. Known vulnerabilities fail the run; an
# unreachable service, or pinned versions the service does not know, are reported, not fatal.
if audit=$(.venv/bin/pip-audit -r requirements-test.lock --no-deps --progress-spinner off 2>&1); then
  echo "pip-audit: no known vulnerabilities in requirements-test.lock"
  if grep -q "could not be audited" <<<"$audit"; then
    echo "pip-audit: WARNING: some pinned versions are unknown to the advisory service and were"
    echo "           NOT audited (a private or local package index?):"
    grep "could not be audited" <<<"$audit" | sed 's/^/           /'
  fi
elif grep -qiE "connection|timed out|max retries|name resolution|network" <<<"$audit"; then
  echo "pip-audit: WARNING: the advisory service could not be reached; the audit was SKIPPED"
else
  echo "$audit"
  exit 1
fi
.venv/bin/python -m pytest -p no:cacheprovider "$@"

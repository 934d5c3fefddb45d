#!/usr/bin/env bash
# Set up everything the test suite needs on a fresh machine (Python 3.11, pip, apt), then run
# the whole suite: lint (ruff, mypy, hadolint) and pytest (solver, API over loopback, browser).
set -euo pipefail
cd "$(dirname "$0")/.."

python3 -m venv .venv
.venv/bin/python -m pip install --quiet --upgrade pip
.venv/bin/python -m pip install --quiet -e '.[test]'

# The browser tests drive Debian's Chromium (no browser download works offline).
if [ ! -x /usr/bin/chromium ]; then
  SUDO=""
  if [ "$(id -u)" != "0" ]; then SUDO="sudo"; fi
  $SUDO apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq chromium >/dev/null
fi

.venv/bin/ruff check solver server tests benchmarks
.venv/bin/ruff format --check solver server tests benchmarks
.venv/bin/mypy
.venv/bin/hadolint Dockerfile
.venv/bin/python -m pytest -p no:cacheprovider "$@"

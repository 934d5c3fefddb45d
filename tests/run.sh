#!/usr/bin/env bash
# Set up everything the test suite needs on a fresh machine (Python 3.11, pip, apt), then run
# the whole suite: lint (ruff, mypy, hadolint) and pytest (solver, API over loopback, browser).
# Arguments go to pytest. CI runs every test, the ones marked `slow` included (the slowest, and
# those whose outcome depends on the machine's load); locally `bash tests/run.sh -m "not slow"`
# skips them (README, "Run the tests").
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

# The generated TypeScript client's test (tests/server/test_generated_clients.py) needs
# openapi-typescript and tsc, pinned in tests/clients/package-lock.json. Without npm, or with
# the npm registry unreachable, that one test is skipped, as said here. The install runs beside
# pip's (each mostly waits for downloads and the disk: about 4 s less on a fresh clone); its
# report is printed before pytest starts.
install_clients() {
  if ! command -v npm >/dev/null; then
    echo "npm: WARNING: no npm on this machine: the TypeScript client test is SKIPPED"
  elif [ ! -d tests/clients/node_modules ] || [ tests/clients/package-lock.json -nt tests/clients/node_modules ]; then
    if ! (cd tests/clients && timeout 300 npm ci --no-audit --no-fund --loglevel=error); then
      echo "npm: WARNING: tests/clients could not be installed: the TypeScript client test is SKIPPED"
    fi
  fi
}
npm_report=$(mktemp)
install_clients >"$npm_report" 2>&1 &
npm_pid=$!

# The same install as the README's: the lock with its hashes (pip itself included), then the
# project without dependencies (an editable install cannot be hashed). Without compiling every
# module of every package at install (--no-compile: 20 s less on a fresh clone here); Python
# compiles those the tests import when they are first imported, and keeps them.
.venv/bin/python -m pip install --quiet --require-hashes --no-compile -r requirements-test.lock
.venv/bin/python -m pip install --quiet --no-deps -e .

# The browser tests drive Debian's Chromium (no browser download works offline).
if [ ! -x /usr/bin/chromium ]; then
  $SUDO apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq chromium >/dev/null
fi

.venv/bin/ruff check solver server tests benchmarks
.venv/bin/ruff format --check solver server tests benchmarks
# mypy (about 14 s of one core on a fresh clone) beside the rest of the checks and the audits
# below, which mostly wait for the network; its report is printed, and a failure stops the run,
# before pytest starts.
mypy_report=$(mktemp)
.venv/bin/mypy >"$mypy_report" 2>&1 &
mypy_pid=$!
.venv/bin/lint-imports
.venv/bin/hadolint Dockerfile

# Dependency audit, offline: the locks against a copy of the PyPA advisory database
# (tests/advisories.py; docs/SERVING.md says how to get and refresh it). A known vulnerability
# in a pinned version fails the run. With no checkout and no network to clone one (CI), the
# audit reads the extract committed in tests/reference/advisories and says how old it is.
if [ ! -d "${ADVISORY_DATABASE:-.advisory-database}/vulns" ]; then
  timeout 120 git clone --quiet --depth 1 https://github.com/pypa/advisory-database .advisory-database \
    || export ADVISORY_DATABASE=tests/reference/advisories
fi
.venv/bin/python -m tests.advisories requirements.lock requirements-test.lock

# The same audit against PyPI's advisory service where it can be reached (it also knows the
# GitHub advisories). Unreachable, or pinned versions it does not know (a private or local
# package index), is reported as a warning: the offline audit above is the one that counts.
# The lock pins and hashes every package, so pip-audit reads it as written (--disable-pip)
# instead of resolving it with pip in a virtualenv of its own (5 s instead of 18 s here).
if audit=$(.venv/bin/pip-audit -r requirements-test.lock --no-deps --disable-pip --progress-spinner off 2>&1); then
  echo "pip-audit: no known vulnerabilities in requirements-test.lock"
  if grep -q "could not be audited" <<<"$audit"; then
    echo "pip-audit: WARNING: some pinned versions are unknown to the advisory service and were"
    echo "           NOT audited by it:"
    grep "could not be audited" <<<"$audit" | sed 's/^/           /'
  fi
elif grep -qiE "connection|timed out|max retries|name resolution|network" <<<"$audit"; then
  echo "pip-audit: WARNING: the advisory service could not be reached; SKIPPED"
else
  echo "$audit"
  exit 1
fi
mypy_status=0
wait "$mypy_pid" || mypy_status=$?
cat "$mypy_report"
rm -f "$mypy_report"
if [ "$mypy_status" != 0 ]; then exit "$mypy_status"; fi
wait "$npm_pid" || true
cat "$npm_report"
rm -f "$npm_report"

# Python keeps the modules it compiles (__pycache__, pytest's rewritten test modules among them)
# even where the environment says not to (PYTHONDONTWRITEBYTECODE, as in the Dockerfile): every
# process after the first (the live servers, their workers, the subprocesses some tests start,
# the second run) then reads them instead of compiling the solver and the server again.
unset PYTHONDONTWRITEBYTECODE

# pytest in two runs. First every test but those marked `serial`, in two processes (pytest-xdist,
# one per core of CI's two; each test module one unit, the heaviest first, so that both run
# browser modules, each with its own Chromium: tests/conftest.py); then the `serial` ones (timed
# against servers of their own under load) alone. Arguments go to both runs (`-m "not slow"`,
# `-x`, a folder, `-k ...`); a run that selects no test (pytest's exit status 5) is no failure
# unless neither run selects one. Without -x the second run goes ahead after a failure in the
# first (every failure is reported), and the script's status is the first run's failure.
pytest_run() {
  status=0
  .venv/bin/python -m pytest -p no:cacheprovider "$@" || status=$?
}
pytest_run -n 2 --dist loadgroup --serial=skip "$@"
first=$status
case " $* " in
  *" -x "* | *" --exitfirst "*) if [ "$first" != 0 ] && [ "$first" != 5 ]; then exit "$first"; fi ;;
esac
pytest_run --serial=only "$@"
second=$status
if [ "$first" = 5 ] && [ "$second" = 5 ]; then exit 5; fi
for s in "$first" "$second"; do
  if [ "$s" != 0 ] && [ "$s" != 5 ]; then exit "$s"; fi
done

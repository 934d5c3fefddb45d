"""The lock files hold everything the project needs (issue 15): the hashed install
(``pip install --require-hashes -r <lock>``, then the project with ``--no-deps``) installs
nothing else, so a requirement missing from a lock is missing from a fresh machine. The runtime
requirements (the library's and the ``[server]`` extra's) and, in the test lock, the ``[test]``
extra, each with everything they require in turn (read from the installed distributions'
metadata), must be pinned at a version their specifiers accept."""

from __future__ import annotations

import importlib.metadata as metadata
import tomllib
from pathlib import Path

import pytest
from packaging.requirements import Requirement
from packaging.utils import canonicalize_name

from tests import advisories

ROOT = Path(__file__).resolve().parents[1]
PROJECT = tomllib.loads((ROOT / "pyproject.toml").read_text())["project"]
# The app's runtime: the library's requirements and the ``[server]`` extra (both locks serve it).
RUNTIME = [
    Requirement(r) for r in (*PROJECT["dependencies"], *PROJECT["optional-dependencies"]["server"])
]
TEST = [Requirement(r) for r in PROJECT["optional-dependencies"]["test"]]


def unpinned(lock: Path, roots: list[Requirement]) -> list[str]:
    """Every requirement reachable from ``roots`` that ``lock`` does not pin at an accepted
    version, as 'name: why'."""
    pinned = {canonicalize_name(name): version for name, version in advisories.pins(lock).items()}
    problems, seen, todo = [], set(), list(roots)
    while todo:
        requirement = todo.pop()
        name = canonicalize_name(requirement.name)
        if requirement.marker is not None and not requirement.marker.evaluate({"extra": ""}):
            continue
        if name in seen:
            continue
        seen.add(name)
        version = pinned.get(name)
        if version is None:
            problems.append(f"{name}: not in {lock.name}")
            continue
        if not requirement.specifier.contains(version, prereleases=True):
            problems.append(f"{name}: {lock.name} pins {version}, {requirement} is required")
        try:
            todo += [Requirement(r) for r in metadata.requires(requirement.name) or []]
        except metadata.PackageNotFoundError:
            problems.append(f"{name}: pinned but not installed here, its requirements unread")
    return problems


@pytest.mark.parametrize(
    ("lock", "roots"),
    [("requirements.lock", RUNTIME), ("requirements-test.lock", RUNTIME + TEST)],
)
def test_the_lock_pins_every_requirement(lock: str, roots: list[Requirement]) -> None:
    assert unpinned(ROOT / lock, roots) == []


def test_a_requirement_missing_from_the_lock_is_found(tmp_path: Path) -> None:
    lock = tmp_path / "requirements.lock"
    kept = [
        line
        for line in (ROOT / "requirements-test.lock").read_text().splitlines(keepends=True)
        if not line.startswith("jsonschema==")
    ]
    lock.write_text("".join(kept))
    assert "jsonschema: not in requirements.lock" in unpinned(lock, TEST)

"""Offline dependency audit: the lock files against a local copy of the PyPA advisory database.

A pinned version ``v`` of package ``p`` is vulnerable when an advisory in
``<database>/vulns/<p>/*.yaml`` (OSV format, https://ossf.github.io/osv-schema/) lists ``v`` in
its ``versions`` or puts it inside one of its ``ECOSYSTEM`` ranges: ``introduced <= v < fixed``
or ``introduced <= v <= last_affected`` (an ``introduced`` with no end is open). Withdrawn
advisories are ignored. Package names are compared in PEP 503 form, versions by PEP 440
(``packaging``).

The database is a checkout of https://github.com/pypa/advisory-database (its ``vulns/``
folder is enough), outside git: ``.advisory-database/`` at the repository root or the folder in
``ADVISORY_DATABASE``. docs/SERVING.md says how to get and refresh it. Run from the root::

    python -m tests.advisories requirements.lock requirements-test.lock

prints the snapshot it read (commit and date when it is a git checkout, else its SNAPSHOT file)
and every vulnerable pin; the exit status is 1 if there is one, 2 if the database is missing or
does not cover every pinned package, else 0.

Where no checkout can be had (CI has no network to GitHub), the audit reads the extract committed
in ``tests/reference/advisories``: every advisory of one snapshot for the packages the locks pin,
and a SNAPSHOT file naming the snapshot and the packages it was extracted for. Refresh it from a
checkout with::

    python -m tests.advisories --extract tests/reference/advisories \\
        requirements.lock requirements-test.lock
"""

from __future__ import annotations

import argparse
import os
import shutil
import subprocess
import sys
from collections.abc import Iterable, Iterator
from dataclasses import dataclass
from datetime import UTC, datetime
from pathlib import Path
from typing import Any

import yaml
from packaging.utils import canonicalize_name
from packaging.version import InvalidVersion, Version

ROOT = Path(__file__).resolve().parents[1]
DEFAULT_DATABASE = ROOT / ".advisory-database"
EXTRACT = ROOT / "tests" / "reference" / "advisories"
STALE_DAYS = 90  # older snapshots are audited, with a warning that they miss recent advisories
SNAPSHOT = (
    "SNAPSHOT"  # an extract's provenance: "snapshot: <commit> of <date>", then "packages: ..."
)


@dataclass(frozen=True)
class Finding:
    package: str
    version: str
    advisory: str
    fixed: str  # the fixed versions the advisory names, or "no fix"

    def __str__(self) -> str:
        return f"{self.package}=={self.version}: {self.advisory} (fixed in {self.fixed})"


def pins(lock: Path) -> dict[str, str]:
    """``name==version`` lines of a lock file (comments, options and hashes skipped)."""
    found = {}
    for line in lock.read_text().splitlines():
        requirement = line.split("#", 1)[0].split(";", 1)[0].strip().rstrip("\\").strip()
        if "==" in requirement and not requirement.startswith("-"):
            name, version = requirement.split("==", 1)
            found[canonicalize_name(name.split("[", 1)[0])] = version.split()[0]
    return found


def _version(text: str) -> Version | None:
    try:
        return Version(text)
    except InvalidVersion:
        return None


def _in_range(version: Version, events: Iterable[dict[str, str]]) -> bool:
    """Whether ``version`` lies in one of the intervals an OSV range's events describe."""
    start: Version | None = None
    for event in events:
        if "introduced" in event:
            start = Version("0") if event["introduced"] == "0" else _version(event["introduced"])
        elif start is not None and ("fixed" in event or "last_affected" in event):
            end = _version(event.get("fixed") or event["last_affected"])
            inclusive = "last_affected" in event
            if (
                end is not None
                and start <= version
                and (version < end or (inclusive and version == end))
            ):
                return True
            start = None
    return start is not None and start <= version


def affects(advisory: dict[str, Any], package: str, version: str) -> bool:
    """Whether an OSV advisory covers ``package`` (PEP 503 name) at ``version``."""
    if advisory.get("withdrawn"):
        return False
    parsed = _version(version)
    for entry in advisory.get("affected") or []:
        if canonicalize_name(str(entry.get("package", {}).get("name", ""))) != package:
            continue
        listed = {str(v) for v in entry.get("versions") or []}
        if version in listed or (parsed is not None and parsed in map(_version, listed)):
            return True
        ranges = [r for r in entry.get("ranges") or [] if r.get("type") == "ECOSYSTEM"]
        if parsed is not None and any(_in_range(parsed, r.get("events") or []) for r in ranges):
            return True
    return False


def _fixed(advisory: dict[str, Any]) -> str:
    fixes = [
        str(event["fixed"])
        for entry in advisory.get("affected") or []
        for spread in entry.get("ranges") or []
        if spread.get("type") == "ECOSYSTEM"
        for event in spread.get("events") or []
        if "fixed" in event
    ]
    return ", ".join(fixes) or "no fix"


def _folders(database: Path) -> dict[str, Path]:
    return {canonicalize_name(p.name): p for p in (database / "vulns").iterdir() if p.is_dir()}


def audit(database: Path, locked: dict[str, str]) -> Iterator[Finding]:
    """Every advisory of the database that covers a pinned version."""
    folders = _folders(database)
    for package, version in sorted(locked.items()):
        folder = folders.get(package)
        for path in sorted(folder.glob("*.yaml")) if folder else []:
            advisory = yaml.safe_load(path.read_text())
            if affects(advisory, package, version):
                yield Finding(
                    package, version, str(advisory.get("id", path.stem)), _fixed(advisory)
                )


def snapshot(database: Path) -> str:
    """The database's git commit and date: a checkout's, an extract's from its SNAPSHOT file, or
    'not a git checkout'."""
    if (database / SNAPSHOT).is_file():
        return _snapshot_fields(database)["snapshot"] + " (an extract)"
    result = subprocess.run(
        ["git", "-C", str(database), "log", "-1", "--format=%H of %cI"],
        capture_output=True,
        text=True,
        check=False,
    )
    return result.stdout.strip() if result.returncode == 0 else "not a git checkout"


def _age_in_days(described: str) -> int | None:
    """Days since the date in ``snapshot()``'s description, if it names one."""
    try:
        taken = datetime.fromisoformat(described.split(" of ", 1)[1].split(" ", 1)[0])
    except (IndexError, ValueError):
        return None
    return (datetime.now(UTC) - taken).days


def _snapshot_fields(extract: Path) -> dict[str, str]:
    lines = (extract / SNAPSHOT).read_text().splitlines()
    return dict(line.split(": ", 1) for line in lines if ": " in line)


def extracted_for(extract: Path) -> set[str]:
    """The packages an extract holds every advisory of (none if it is a full checkout)."""
    if not (extract / SNAPSHOT).is_file():
        return set()
    return set(_snapshot_fields(extract)["packages"].split())


def extract(database: Path, into: Path, locked: dict[str, str]) -> None:
    """Copy the advisories of the pinned packages from a checkout into ``into``, with a SNAPSHOT
    file naming the checkout's commit and the packages (so that a package pinned later, with no
    advisory copied, is known to be missing rather than clean)."""
    folders = _folders(database)
    shutil.rmtree(into / "vulns", ignore_errors=True)
    for package in sorted(locked):
        if package in folders:
            shutil.copytree(folders[package], into / "vulns" / folders[package].name)
    (into / "vulns").mkdir(parents=True, exist_ok=True)
    (into / SNAPSHOT).write_text(
        f"snapshot: {snapshot(database)}\npackages: {' '.join(sorted(locked))}\n"
    )


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("locks", nargs="+", type=Path, help="lock files (name==version lines)")
    parser.add_argument(
        "--database",
        type=Path,
        default=Path(os.environ.get("ADVISORY_DATABASE") or DEFAULT_DATABASE),
        help="a checkout of pypa/advisory-database (default: $ADVISORY_DATABASE or "
        ".advisory-database)",
    )
    parser.add_argument(
        "--extract",
        type=Path,
        metavar="FOLDER",
        help="copy the pinned packages' advisories from --database into FOLDER instead of auditing",
    )
    args = parser.parse_args(argv)
    if not (args.database / "vulns").is_dir():
        print(f"advisories: no advisory database at {args.database} (see docs/SERVING.md)")
        return 2
    locked: dict[str, str] = {}
    for lock in args.locks:
        locked.update(pins(lock))
    if args.extract:
        extract(args.database, args.extract, locked)
        print(f"advisories: the advisories of {len(locked)} packages copied into {args.extract}")
        return 0
    covered = extracted_for(args.database)
    if covered and not covered >= set(locked):
        missing = ", ".join(sorted(set(locked) - covered))
        print(f"advisories: the extract at {args.database} does not cover {missing}; refresh it")
        return 2
    findings = list(audit(args.database, locked))
    print(
        f"advisories: {len(locked)} pinned packages checked against the PyPA advisory database "
        f"at {args.database} ({snapshot(args.database)}): {len(findings)} known vulnerabilities"
    )
    age = _age_in_days(snapshot(args.database))
    if age is not None and age > STALE_DAYS:
        print(
            f"advisories: WARNING: the snapshot is {age} days old: advisories published since are"
            " not checked (docs/SERVING.md says how to refresh it)"
        )
    for finding in findings:
        print(f"  VULNERABLE {finding}")
    return 1 if findings else 0


if __name__ == "__main__":
    sys.exit(main())

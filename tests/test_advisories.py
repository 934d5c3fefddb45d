"""The offline dependency audit (tests/advisories.py) against fake advisory databases: a known
vulnerability in a locked version must fail it, a fixed or unrelated one must not."""

from __future__ import annotations

from pathlib import Path
from typing import Any

import pytest
import yaml

from tests import advisories

ROOT = Path(__file__).resolve().parents[1]
LOCKS = [ROOT / "requirements.lock", ROOT / "requirements-test.lock"]


def advisory(name: str, events: list[dict[str, str]], **extra: Any) -> dict[str, Any]:
    ranges = [{"type": "ECOSYSTEM", "events": events}]
    return {"id": "FAKE-1", "affected": [{"package": {"name": name}, "ranges": ranges}], **extra}


def database(tmp_path: Path, folder: str, *entries: dict[str, Any]) -> Path:
    for index, entry in enumerate(entries):
        path = tmp_path / "vulns" / folder / f"FAKE-{index}.yaml"
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_text(yaml.safe_dump(entry))
    return tmp_path


def test_the_locks_pin_every_package_they_list() -> None:
    for lock in LOCKS:
        lines = [
            line
            for line in lock.read_text().splitlines()
            if line.strip() and not line.lstrip().startswith(("#", "--"))
        ]
        pinned = advisories.pins(lock)
        assert len(pinned) == len(lines) > 10
    assert advisories.pins(LOCKS[0])["numpy"]


def test_a_fake_advisory_on_a_locked_version_fails_the_audit(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    version = advisories.pins(LOCKS[0])["numpy"]
    fake = advisory("NumPy", [{"introduced": "0"}, {"fixed": f"{version}.post1"}])
    db = database(tmp_path, "numpy", fake)
    assert advisories.main([str(LOCKS[0]), "--database", str(db)]) == 1
    out = capsys.readouterr().out
    assert f"VULNERABLE numpy=={version}: FAKE-1 (fixed in {version}.post1)" in out


def test_a_fixed_advisory_passes(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    version = advisories.pins(LOCKS[0])["numpy"]
    fake = advisory("numpy", [{"introduced": "0"}, {"fixed": version}])
    db = database(tmp_path, "numpy", fake)
    assert advisories.main([str(LOCKS[0]), "--database", str(db)]) == 0
    assert "0 known vulnerabilities" in capsys.readouterr().out


def test_a_missing_database_is_reported_not_passed(tmp_path: Path) -> None:
    assert advisories.main([str(LOCKS[0]), "--database", str(tmp_path / "none")]) == 2


@pytest.mark.parametrize(
    ("events", "version", "hit"),
    [
        ([{"introduced": "0"}, {"fixed": "2.0"}], "1.9.9", True),
        ([{"introduced": "0"}, {"fixed": "2.0"}], "2.0", False),
        ([{"introduced": "1.5"}, {"fixed": "2.0"}], "1.4", False),
        ([{"introduced": "1.5"}, {"fixed": "2.0"}], "1.5", True),
        ([{"introduced": "1.0"}, {"last_affected": "1.2"}], "1.2", True),
        ([{"introduced": "1.0"}, {"last_affected": "1.2"}], "1.2.1", False),
        ([{"introduced": "3.0"}], "9.9", True),
        (
            [{"introduced": "0"}, {"fixed": "1.0"}, {"introduced": "2.0"}, {"fixed": "2.1"}],
            "1.5",
            False,
        ),
        (
            [{"introduced": "0"}, {"fixed": "1.0"}, {"introduced": "2.0"}, {"fixed": "2.1"}],
            "2.0.5",
            True,
        ),
        ([{"introduced": "0"}, {"fixed": "2.0"}], "2.0rc1", True),
    ],
)
def test_osv_ranges(events: list[dict[str, str]], version: str, hit: bool) -> None:
    assert advisories.affects(advisory("pkg", events), "pkg", version) is hit


def test_listed_versions_names_and_withdrawals() -> None:
    listed = {"id": "X", "affected": [{"package": {"name": "Some_Pkg"}, "versions": ["1.0"]}]}
    assert advisories.affects(listed, "some-pkg", "1.0")
    assert advisories.affects(listed, "some-pkg", "1.0.0")  # the same version by PEP 440
    assert not advisories.affects(listed, "some-pkg", "1.1")
    assert not advisories.affects(listed, "other", "1.0")
    assert not advisories.affects(
        {**listed, "withdrawn": "2024-01-01T00:00:00Z"}, "some-pkg", "1.0"
    )


def test_the_committed_extract_covers_every_pin_and_finds_nothing(
    capsys: pytest.CaptureFixture[str],
) -> None:
    """The audit CI runs without network: the extract must hold every package the locks pin (a
    dependency added to a lock without refreshing the extract fails here)."""
    locked = {**advisories.pins(LOCKS[0]), **advisories.pins(LOCKS[1])}
    assert advisories.extracted_for(advisories.EXTRACT) >= set(locked)
    assert advisories.main([*map(str, LOCKS), "--database", str(advisories.EXTRACT)]) == 0
    assert f"{len(locked)} pinned packages checked" in capsys.readouterr().out


def test_an_extract_keeps_the_pinned_packages_advisories_and_knows_what_it_lacks(
    tmp_path: Path,
) -> None:
    version = advisories.pins(LOCKS[0])["numpy"]
    full = database(tmp_path / "full", "NumPy", advisory("numpy", [{"introduced": "0"}]))
    database(tmp_path / "full", "unpinned-pkg", advisory("unpinned-pkg", [{"introduced": "0"}]))
    into = tmp_path / "extract"
    advisories.extract(full, into, {"numpy": version, "scipy": "1.0"})
    assert sorted(p.name for p in (into / "vulns").iterdir()) == ["NumPy"]
    assert advisories.extracted_for(into) == {"numpy", "scipy"}
    assert advisories.main([str(LOCKS[0]), "--database", str(into)]) == 2  # the lock pins more
    advisories.extract(full, into, advisories.pins(LOCKS[0]))
    assert advisories.main([str(LOCKS[0]), "--database", str(into)]) == 1  # numpy's advisory


def test_a_stale_snapshot_is_audited_with_a_warning(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    db = database(tmp_path, "numpy", advisory("numpy", [{"introduced": "0"}, {"fixed": "0.1"}]))
    (db / advisories.SNAPSHOT).write_text(
        "snapshot: abc of 2020-01-01T00:00:00+00:00\npackages: numpy\n"
    )
    assert advisories.main([str(LOCKS[0]), "--database", str(db)]) == 2  # covers numpy only
    pinned_numpy = tmp_path / "numpy.lock"
    pinned_numpy.write_text(f"numpy=={advisories.pins(LOCKS[0])['numpy']}\n")
    assert advisories.main([str(pinned_numpy), "--database", str(db)]) == 0
    out = capsys.readouterr().out
    assert "abc of 2020-01-01" in out and "days old" in out

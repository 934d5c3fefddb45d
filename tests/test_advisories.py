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

"""The app's example scenes are the one copy in server/examples, served at /examples."""

from __future__ import annotations

from pathlib import Path

from fastapi.testclient import TestClient

ROOT = Path(__file__).resolve().parents[2]
EXAMPLES = ROOT / "server" / "examples"


def test_the_apps_example_list_is_server_examples(client: TestClient) -> None:
    """/examples/index.json lists every scene of server/examples once, titled and described,
    and /examples/<file> is that file byte for byte; static/ keeps no copy."""
    listed = client.get("/examples/index.json").json()["examples"]
    files = [entry["file"] for entry in listed]
    assert sorted(files) == sorted(
        p.relative_to(EXAMPLES).as_posix() for p in EXAMPLES.rglob("*.json")
    )
    assert len(set(files)) == len(files) and "S000-T2-rounded.json" in files
    for entry in listed:
        assert entry["title"] and entry["description"], entry
        response = client.get(f"/examples/{entry['file']}")
        assert response.status_code == 200, entry
        assert response.content == (EXAMPLES / entry["file"]).read_bytes()
    assert client.get("/examples/S999.json").status_code == 404
    assert not (ROOT / "static" / "examples").exists()

"""Deployment (issue 28): workers from the container's CPU quota, gzip for large answers (a
static file's made once a version), ETag and Cache-Control on the deterministic GETs, the OpenAPI
document's ``servers``.

The answers that pass through the worker pool are checked over the real server on loopback
(server.local); the rest in process.
"""

from __future__ import annotations

import gzip
import json
import math
import os
import urllib.request
from collections.abc import Iterator
from pathlib import Path

import pytest
from fastapi.testclient import TestClient
from starlette.applications import Starlette

from server.app import GZIP_MINIMUM, create_app
from server.caching import PRIVATE, PUBLIC, weak_etag
from server.settings import Settings, cpu_quota, from_environment, usable_cores
from server.static_files import PrecompressedFiles, gzipped
from tests.server.test_errors import FOUR_BAR
from tests.server.test_serving import server

STATIC = Path(__file__).resolve().parents[2] / "static"
EXERCISE = "/api/v1/exercises/four_bar_velocity:standard:7:0"
BIG_SWEEP = {
    "scene": FOUR_BAR,
    "samples": 2000,
    "quantities": ["position", "velocity", "acceleration", "poles", "components"],
}
_opener = urllib.request.build_opener(urllib.request.ProxyHandler({}))


@pytest.fixture(scope="module")
def client() -> Iterator[TestClient]:
    with TestClient(create_app(Settings(workers=0)), raise_server_exceptions=False) as test:
        yield test


@pytest.fixture(scope="module")
def pooled() -> Iterator[str]:
    with server("deployment", KINEMATICS_WORKERS="1") as base:
        yield base


def raw(
    base: str, path: str, body: object = None, **headers: str
) -> tuple[int, dict[str, str], bytes]:
    """(status, headers, body bytes as sent: not decompressed)."""
    data = None if body is None else json.dumps(body).encode()
    request = urllib.request.Request(base + path, data=data, headers=headers)
    request.add_header("content-type", "application/json")
    try:
        with _opener.open(request, timeout=60) as response:
            return (
                response.status,
                {k.lower(): v for k, v in response.headers.items()},
                response.read(),
            )
    except urllib.error.HTTPError as error:
        return error.code, {k.lower(): v for k, v in error.headers.items()}, error.read()


# --- workers from the CPU quota ---------------------------------------------------------------


def test_the_cpu_quota_of_cgroup_v2(tmp_path: Path) -> None:
    (tmp_path / "cpu.max").write_text("150000 100000\n")
    assert cpu_quota(tmp_path) == 1.5
    assert usable_cores(tmp_path) == min(2, len(os.sched_getaffinity(0)))  # rounded up
    (tmp_path / "cpu.max").write_text("max 100000\n")
    assert cpu_quota(tmp_path) is None
    assert usable_cores(tmp_path) == len(os.sched_getaffinity(0))  # the CPU set alone


def test_the_cpu_quota_of_cgroup_v1(tmp_path: Path) -> None:
    v1 = tmp_path / "cpu,cpuacct"
    v1.mkdir()
    (v1 / "cpu.cfs_quota_us").write_text("50000\n")
    (v1 / "cpu.cfs_period_us").write_text("100000\n")
    assert cpu_quota(tmp_path) == 0.5
    assert usable_cores(tmp_path) == 1
    (v1 / "cpu.cfs_quota_us").write_text("-1\n")
    assert cpu_quota(tmp_path) is None
    assert cpu_quota(tmp_path / "nowhere") is None


def test_the_default_workers_are_the_usable_cores() -> None:
    assert Settings().workers == usable_cores()
    quota = cpu_quota()
    if quota is not None:  # this machine's own quota, if it has one
        assert Settings().workers <= max(1, math.ceil(quota))


# --- gzip --------------------------------------------------------------------------------------


def test_a_large_answer_from_a_worker_is_gzipped_and_a_small_one_not(pooled: str) -> None:
    status, headers, body = raw(pooled, "/api/v1/sweep", BIG_SWEEP, **{"accept-encoding": "gzip"})
    assert status == 200 and headers["content-encoding"] == "gzip"
    assert "accept-encoding" in headers["vary"].lower()
    _, plain_headers, plain = raw(pooled, "/api/v1/sweep", BIG_SWEEP)
    assert "content-encoding" not in plain_headers
    assert json.loads(gzip.decompress(body)) == json.loads(plain)
    assert len(body) < len(plain) / 2
    small = raw(
        pooled,
        "/api/v1/analyze",
        {"scene": FOUR_BAR, "quantities": ["position"]},
        **{"accept-encoding": "gzip"},
    )
    assert small[0] == 200 and len(small[2]) < GZIP_MINIMUM
    assert "content-encoding" not in small[1]


def test_refusals_stay_plain_problem_json_under_gzip(pooled: str) -> None:
    """413 from the budget and 422 are small: sent as they are, whatever the client accepts."""
    too_big = {"scene": FOUR_BAR, "samples": 100_000, "quantities": BIG_SWEEP["quantities"]}
    for body, code in ((too_big, 413), ({"scene": {}}, 422)):
        status, headers, answer = raw(pooled, "/api/v1/sweep", body, **{"accept-encoding": "gzip"})
        assert status == code
        assert "content-encoding" not in headers
        assert headers["content-type"].startswith("application/problem+json")
        assert json.loads(answer)["status"] == code


def test_a_static_file_is_gzipped_whole(client: TestClient) -> None:
    path = "/vendor/swagger-ui/swagger-ui-bundle.js"
    response = client.get(path, headers={"accept-encoding": "gzip"})
    assert response.status_code == 200 and response.headers["content-encoding"] == "gzip"
    assert response.content == (STATIC / path.lstrip("/")).read_bytes()  # decoded by httpx
    # from the copy compressed once (PrecompressedFiles), not compressed as it streams
    sent = _raw(client, path, **{"accept-encoding": "gzip"})[2]
    assert sent == gzip.compress(response.content, compresslevel=9, mtime=0)


def _raw(client: TestClient, path: str, **headers: str) -> tuple[int, dict[str, str], bytes]:
    """(status, headers, the body as sent: not decoded)."""
    with client.stream("GET", path, headers=headers) as response:
        return response.status_code, dict(response.headers), b"".join(response.iter_raw())


def test_a_static_file_is_compressed_once_a_version(tmp_path: Path) -> None:
    """PrecompressedFiles: the gzip sent is the file's level-9 copy, made on the first request
    and reused until the file changes; a client without gzip, a range, a small file or a font
    get the file as it is; the weak tag of the gzip revalidates to 304, which carries it."""
    app = Starlette()
    app.mount("/files", PrecompressedFiles(directory=tmp_path, minimum=GZIP_MINIMUM))
    script = tmp_path / "app.js"
    script.write_text("const x = 1;\n" * 1000)
    (tmp_path / "small.js").write_text("const y = 2;\n")
    (tmp_path / "font.woff2").write_bytes(bytes(range(256)) * 40)
    client = TestClient(app)
    made = gzipped.cache_info().misses
    for _ in range(2):
        status, headers, body = _raw(client, "/files/app.js", **{"accept-encoding": "gzip"})
        assert status == 200 and headers["content-encoding"] == "gzip"
        assert body == gzip.compress(script.read_bytes(), compresslevel=9, mtime=0)
        assert headers["vary"] == "Accept-Encoding" and headers["etag"].startswith('W/"')
    assert gzipped.cache_info().misses == made + 1  # compressed once for the two requests
    again = client.get("/files/app.js", headers={"if-none-match": headers["etag"]})
    assert again.status_code == 304 and again.content == b""
    # The 304 carries the tag and Vary the 200 would: the gzip's weak one, the file's own strong
    # one to a client without gzip (RFC 9110, 15.4.5).
    assert again.headers["etag"] == headers["etag"]
    assert again.headers["vary"] == "Accept-Encoding"
    strong = headers["etag"].removeprefix("W/")
    plain = client.get(
        "/files/app.js", headers={"if-none-match": strong, "accept-encoding": "identity"}
    )
    assert plain.status_code == 304 and plain.headers["etag"] == strong
    assert "vary" not in plain.headers
    script.write_text("let z = 3;\n" * 2000)  # a new version: compressed in turn
    assert _raw(client, "/files/app.js", **{"accept-encoding": "gzip"})[2] == gzip.compress(
        script.read_bytes(), compresslevel=9, mtime=0
    )
    for path, headers in (
        ("/files/app.js", {"accept-encoding": "identity"}),
        ("/files/small.js", {"accept-encoding": "gzip"}),
        ("/files/font.woff2", {"accept-encoding": "gzip"}),
    ):
        status, sent, body = _raw(client, path, **headers)
        assert status == 200 and "content-encoding" not in sent
        assert body == (tmp_path / path.removeprefix("/files/")).read_bytes()
    status, sent, body = _raw(
        client, "/files/app.js", **{"accept-encoding": "gzip", "range": "bytes=0-9"}
    )
    assert status == 206 and "content-encoding" not in sent and body == script.read_bytes()[:10]


# --- ETag and Cache-Control -------------------------------------------------------------------


@pytest.mark.parametrize(
    ("path", "policy"),
    [
        ("/api/v1/presets", PUBLIC),
        ("/api/v1/presets?family=cams", PUBLIC),
        ("/api/v1/exercises/types", PUBLIC),
        (EXERCISE, PRIVATE),
        ("/examples/S000-T1.json", PUBLIC),
    ],
)
def test_deterministic_gets_carry_an_etag_and_answer_304_to_it(
    client: TestClient, path: str, policy: str
) -> None:
    first = client.get(path)
    assert first.status_code == 200
    assert first.headers["cache-control"] == policy
    etag = first.headers["etag"]
    assert client.get(path).headers["etag"] == etag  # the same answer, the same tag
    again = client.get(path, headers={"if-none-match": etag})
    assert again.status_code == 304 and again.content == b""
    assert again.headers["etag"] == etag
    other = client.get(path, headers={"if-none-match": 'W/"something-else"'})
    assert other.status_code == 200 and other.content == first.content


def test_the_etag_is_the_bodys_hash_and_other_answers_carry_none(client: TestClient) -> None:
    listing = client.get("/api/v1/presets")
    assert listing.headers["etag"] == weak_etag(listing.content)
    assert "cache-control" not in client.post("/api/v1/presets/four_bar", json={}).headers
    unknown = client.get("/api/v1/exercises/no-such-id")
    assert unknown.status_code >= 400 and "etag" not in unknown.headers


def test_an_exercise_from_a_worker_is_tagged_and_revalidated(pooled: str) -> None:
    status, headers, _ = raw(pooled, EXERCISE)
    assert status == 200 and headers["cache-control"] == PRIVATE
    status, again, body = raw(pooled, EXERCISE, **{"if-none-match": headers["etag"]})
    assert status == 304 and body == b"" and again["etag"] == headers["etag"]


# --- OpenAPI servers ----------------------------------------------------------------------------


def test_the_openapi_document_names_its_server(client: TestClient) -> None:
    assert client.get("/api/v1/openapi.json").json()["servers"] == [
        {"url": "/", "description": "this server"}
    ]
    public = from_environment({"KINEMATICS_PUBLIC_URL": "https://kinematics.example.edu/"})
    document = TestClient(create_app(public)).get("/api/v1/openapi.json").json()
    assert document["servers"][0]["url"] == "https://kinematics.example.edu"
    with pytest.raises(ValueError, match="KINEMATICS_PUBLIC_URL"):
        from_environment({"KINEMATICS_PUBLIC_URL": "kinematics.example.edu"})

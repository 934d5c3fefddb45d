"""The front end's files, each gzipped once per version instead of once per request.

A first visit fetches about 1.7 MB of scripts and styles, 1.2 MB of it Plotly, which Starlette's
``GZipMiddleware`` compressed again for every new client as the file streamed (a first page
load took 0.137 s of the server's CPU, 0.095 s with the copies). ``PrecompressedFiles`` serves a
file's gzip from a copy made the first time it is asked for (in a thread, off the event loop)
and kept while the file's size and modification time stay the same: after an upgrade the new
version is compressed once in turn.

The copy is at level 9 (once per file, so its cost does not matter: Plotly 1.2 MB -> 0.40 MB,
where level 1 gave 0.45 MB). What ``StaticFiles`` does otherwise is kept: the 304 to an
``If-None-Match`` naming the file's tag (the gzip's tag is the same, weak, as the two bodies are
one file; the 304 carries the tag and ``Vary`` the 200 would), a ``Range`` request (answered
from the file as it is), HEAD, and the files not worth compressing (fonts and images, already
compressed, and files under the app's minimum for compression, ``minimum``).
"""

from __future__ import annotations

import functools
import gzip
import os
from os import PathLike
from pathlib import Path

import anyio.to_thread
from starlette.datastructures import Headers, MutableHeaders
from starlette.responses import FileResponse, Response
from starlette.staticfiles import StaticFiles
from starlette.types import Scope

COMPRESSIBLE = frozenset({".js", ".mjs", ".css", ".html", ".json", ".svg", ".txt", ".map"})
KEPT = 256  # files whose gzip is kept (the front end has about 70)


@functools.lru_cache(maxsize=KEPT)
def gzipped(path: str, modified_ns: int, size: int) -> bytes:
    """The gzip (level 9, no timestamp: the same bytes every time) of the file at ``path`` as it
    is at ``modified_ns`` with ``size`` bytes (the key that makes an edited file compressed
    again)."""
    return gzip.compress(Path(path).read_bytes(), compresslevel=9, mtime=0)


def mark_as_gzip_copy(headers: MutableHeaders) -> None:
    """Make a file's answer headers those of its gzip copy: the file's tag made weak (the copy and
    the file are the same version in two encodings) and ``Vary: Accept-Encoding``."""
    headers["etag"] = f"W/{headers['etag']}"
    headers.add_vary_header("Accept-Encoding")


class PrecompressedFiles(StaticFiles):
    """``StaticFiles`` that answers a GET accepting gzip from the file's compressed copy, for a
    file of ``minimum`` bytes or more."""

    def __init__(self, *, directory: Path, minimum: int) -> None:
        super().__init__(directory=directory)
        self.minimum = minimum

    def compressed(self, path: Path, stat: os.stat_result, scope: Scope) -> bool:
        """Whether the answer to this request for the file at ``path`` is its gzip copy: a GET
        accepting gzip, with no range, of a compressible file of ``minimum`` bytes or more."""
        request = Headers(scope=scope)
        return (
            scope["method"] == "GET"
            and "gzip" in request.get("accept-encoding", "")
            and "range" not in request
            and stat.st_size >= self.minimum
            and path.suffix in COMPRESSIBLE
        )

    def file_response(
        self, full_path: PathLike[str] | str, stat_result: os.stat_result, scope: Scope,
        status_code: int = 200,
    ) -> Response:  # fmt: skip
        """``StaticFiles``' answer; a 304 to a request the gzip copy answers carries that copy's
        tag and ``Vary``, as the 200 would (RFC 9110, 15.4.5)."""
        response = super().file_response(full_path, stat_result, scope, status_code)
        if response.status_code == 304 and self.compressed(Path(full_path), stat_result, scope):
            mark_as_gzip_copy(response.headers)
        return response

    async def get_response(self, path: str, scope: Scope) -> Response:
        response = await super().get_response(path, scope)
        if (
            not isinstance(response, FileResponse)
            or response.status_code != 200
            or response.stat_result is None
            or not self.compressed(Path(response.path), response.stat_result, scope)
        ):
            return response
        stat = response.stat_result
        body = await anyio.to_thread.run_sync(
            gzipped, str(response.path), stat.st_mtime_ns, stat.st_size
        )
        headers = MutableHeaders(raw=list(response.raw_headers))
        del headers["content-length"]  # (set again from the body)
        del headers["accept-ranges"]  # (a range is served from the file, uncompressed)
        mark_as_gzip_copy(headers)
        headers["content-encoding"] = "gzip"
        return Response(body, headers=dict(headers))

"""ETag and Cache-Control on the GETs whose answers depend on nothing but the request.

The presets' list, the exercise types, one exercise by its id (generated, never stored: the id
determines it) and the example scenes are the same for every client until the server is
upgraded. Their 200 answers get a weak ``ETag`` (the SHA-256 of the body, or the static file's
own tag) and ``Cache-Control`` (``CACHE_SECONDS``; ``private`` for an exercise, whose answer key
stays out of shared caches); a request whose ``If-None-Match`` names the tag is answered 304
without the body. Weak tags, because the gzip middleware may send the same body compressed.
"""

from __future__ import annotations

import hashlib

from starlette.datastructures import Headers, MutableHeaders
from starlette.types import ASGIApp, Message, Receive, Scope, Send

CACHE_SECONDS = 3600
API = "/api/v1"
PUBLIC = f"public, max-age={CACHE_SECONDS}"
PRIVATE = f"private, max-age={CACHE_SECONDS}"


def cache_control(path: str) -> str | None:
    """The Cache-Control of a GET of ``path``, None where answers are not cached."""
    if path in (f"{API}/presets", f"{API}/exercises/types") or path.startswith("/examples/"):
        return PUBLIC
    if path.startswith(f"{API}/exercises/") and path.count("/") == 4:  # /api/v1/exercises/{id}
        return PRIVATE
    return None


def weak_etag(body: bytes) -> str:
    """W/"<the first 32 hex digits of the SHA-256 of body>"."""
    return f'W/"{hashlib.sha256(body).hexdigest()[:32]}"'


def _matches(if_none_match: str, etag: str) -> bool:
    """Whether ``If-None-Match`` names ``etag`` (weak comparison, RFC 9110 13.1.2)."""
    opaque = etag.removeprefix("W/")
    tags = {tag.strip().removeprefix("W/") for tag in if_none_match.split(",")}
    return "*" in tags or opaque in tags


class Caching:
    """ASGI middleware: tags and cache headers on the answers of ``cache_control``'s paths."""

    def __init__(self, app: ASGIApp) -> None:
        self.app = app

    async def __call__(self, scope: Scope, receive: Receive, send: Send) -> None:
        policy = cache_control(scope["path"]) if scope["type"] == "http" else None
        if policy is None or scope["method"] != "GET":
            await self.app(scope, receive, send)
            return
        start: Message | None = None
        chunks: list[bytes] = []

        async def buffered(message: Message) -> None:
            nonlocal start
            if message["type"] == "http.response.start":
                start = message
                return
            if message["type"] != "http.response.body" or start is None:
                await send(message)
                return
            chunks.append(message.get("body", b""))
            if message.get("more_body", False):
                return
            await self._answer(scope, start, b"".join(chunks), policy, send)

        await self.app(scope, receive, buffered)

    @staticmethod
    async def _answer(scope: Scope, start: Message, body: bytes, policy: str, send: Send) -> None:
        headers = MutableHeaders(raw=list(start["headers"]))
        if start["status"] != 200:
            await send(start)
            await send({"type": "http.response.body", "body": body})
            return
        etag = headers.get("etag") or weak_etag(body)
        headers["etag"] = etag
        headers["cache-control"] = policy
        if _matches(Headers(scope=scope).get("if-none-match", ""), etag):
            for name in ("content-length", "content-type"):
                del headers[name]
            await send({"type": "http.response.start", "status": 304, "headers": headers.raw})
            await send({"type": "http.response.body", "body": b""})
            return
        await send({**start, "headers": headers.raw})
        await send({"type": "http.response.body", "body": body})

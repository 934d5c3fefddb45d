"""Strict JSON at the edge: bounded bodies, strict documents in, finite numbers out.

Python's json module accepts ``NaN``, ``Infinity``, duplicate keys (the last wins) and strings
that cannot be encoded, and a client could send a body of any size: this route class reads the
body with a byte limit and parses it with ``server.text.loads``, which refuses all of these as
``invalid_scene`` with the path of the offending value. Responses are serialised with orjson
after a check that every number is finite (a non-finite value in a response is a defect, never
sent as null).
"""

from __future__ import annotations

from collections.abc import Callable, Coroutine
from contextvars import ContextVar
from typing import Any

import numpy as np
import orjson
from fastapi import Request, Response
from fastapi.routing import APIRoute
from starlette.exceptions import HTTPException

from server import text
from solver.errors import InvalidScene

MAX_BODY_BYTES = 1_000_000
JSON_CONTENT_TYPE = (b"content-type", b"application/json")


class StrictJSONRequest(Request):
    """A request whose body is bounded and whose JSON has finite numbers only."""

    async def body(self) -> bytes:
        if not hasattr(self, "_body"):
            declared = self.headers.get("content-length", "")
            if declared.isdigit() and int(declared) > MAX_BODY_BYTES:
                raise HTTPException(
                    413, f"the body of {declared} bytes exceeds the limit of {MAX_BODY_BYTES} bytes"
                )
            chunks, size = [], 0
            async for chunk in self.stream():
                size += len(chunk)
                if size > MAX_BODY_BYTES:
                    raise HTTPException(
                        413, f"the body exceeds the limit of {MAX_BODY_BYTES} bytes"
                    )
                chunks.append(chunk)
            self._body = b"".join(chunks)
        return self._body

    async def json(self) -> Any:
        if not hasattr(self, "_json"):
            try:
                self._json = text.loads(await self.body())
            except InvalidScene as error:  # FastAPI would answer any other exception with 400
                raise HTTPException(422, error.message) from None
        return self._json


def is_json_media_type(content_type: str) -> bool:
    """Whether a Content-Type names JSON: application/json or application/<anything>+json,
    parameters (``; charset=utf-8``) aside, in any case."""
    media = content_type.split(";", 1)[0].strip().lower()
    kind, _, subtype = media.partition("/")
    return kind == "application" and (subtype == "json" or subtype.endswith("+json"))


# The request being answered, for endpoint wrappers (server.workers) that need its client.
CURRENT_REQUEST: ContextVar[Request] = ContextVar("CURRENT_REQUEST")


class StrictJSONRoute(APIRoute):
    """A route whose body, if it takes one, is strict JSON: a body sent under another declared
    media type (text/plain, a form) is 415 unsupported_media_type; one sent without a
    Content-Type is read as JSON."""

    def get_route_handler(self) -> Callable[[Request], Coroutine[Any, Any, Response]]:
        handler = super().get_route_handler()
        takes_body = self.body_field is not None

        async def strict(request: Request) -> Response:
            declared = request.headers.get("content-type")
            scope = request.scope
            if takes_body and declared is None:  # read as JSON, not as bytes
                scope = {**scope, "headers": [*scope["headers"], JSON_CONTENT_TYPE]}
            elif takes_body and declared is not None and not is_json_media_type(declared):
                raise HTTPException(
                    415,
                    f"the body is sent as {declared[:80]!r}; send it as application/json",
                )
            strict_request = StrictJSONRequest(scope, request.receive)
            CURRENT_REQUEST.set(strict_request)
            return await handler(strict_request)

        return strict


class NonFiniteResultError(RuntimeError):
    """The solver produced NaN or infinity: a defect, answered as a 500 problem."""


def _check_finite(value: Any, path: str) -> None:
    if isinstance(value, float):
        if value != value or value in (float("inf"), float("-inf")):
            raise NonFiniteResultError(f"non-finite value at {path}")
    elif isinstance(value, np.ndarray):
        if value.dtype.kind == "f" and not np.all(np.isfinite(value)):
            raise NonFiniteResultError(f"non-finite value in {path}")
    elif isinstance(value, dict):
        for key, item in value.items():
            _check_finite(item, f"{path}.{key}")
    elif isinstance(value, list | tuple):
        for index, item in enumerate(value):
            _check_finite(item, f"{path}[{index}]")


class FiniteJSONResponse(Response):
    """JSON via orjson (numpy arrays natively), after checking every number is finite."""

    media_type = "application/json"

    def render(self, content: Any) -> bytes:
        _check_finite(content, "response")
        return orjson.dumps(content, option=orjson.OPT_SERIALIZE_NUMPY)

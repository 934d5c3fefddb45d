"""Every error as RFC 9457 problem+json with a stable ``code``, from one place.

The solver's exceptions, the framework's validation errors, unknown routes and oversize bodies
all end here; an unexpected exception is answered as a 500 problem (and is a defect to fix).
"""

from __future__ import annotations

import logging
import re
from typing import Any

from fastapi import FastAPI, Request
from fastapi.exceptions import RequestValidationError
from fastapi.responses import JSONResponse
from starlette.exceptions import HTTPException

from solver.errors import InvalidExpression, KinematicsError, LimitExceeded, SingularConfiguration

PROBLEM = "application/problem+json"
TITLES = {
    "invalid_scene": "Invalid scene",
    "invalid_expression": "Invalid expression",
    "not_assemblable": "Linkage cannot be assembled",
    "singular_configuration": "Singular configuration (dead centre)",
    "limit_exceeded": "Request too large or too long",
    "busy": "Server busy",
    "too_many_requests": "Too many slow requests from one client",
    "request_timeout": "The request did not arrive in time",
    "no_event": "The event does not occur",
    "not_found": "Not found",
    "forbidden": "Not served to anyone",
    "not_configured": "Not configured on this server",
    "pdf_unavailable": "No PDF printer on this server",
    "method_not_allowed": "Method not allowed",
    "unsupported_media_type": "Unsupported media type",
    "internal_error": "Internal error",
}
log = logging.getLogger("kinematics")


def problem(status: int, code: str, detail: str, **extra: Any) -> JSONResponse:
    """The problem+json response; text that cannot be encoded (a lone surrogate echoed from the
    request) is written as its escape, e.g. \\udfff."""
    detail = detail.encode("utf-8", "backslashreplace").decode("utf-8")
    extra = {
        k: v.encode("utf-8", "backslashreplace").decode("utf-8") if isinstance(v, str) else v
        for k, v in extra.items()
    }
    body = {
        "type": f"/problems/{code}",
        "title": TITLES.get(code, code),
        "status": status,
        "detail": detail,
        "code": code,
        **extra,
    }
    return JSONResponse(body, status_code=status, media_type=PROBLEM)


class Unavailable(KinematicsError):
    """A part of the server that this installation lacks (a system program): 503, its own
    ``code``, the message saying what to install."""


def _status(error: KinematicsError) -> int:
    """413 for a request larger or longer than the server allows, 503 for a part the server
    lacks (``Unavailable``), 422 for the others."""
    if isinstance(error, Unavailable):
        return 503
    return 413 if isinstance(error, LimitExceeded) else 422


def solver_problem(error: KinematicsError) -> JSONResponse:
    """The problem for a solver error (here, or in a worker process)."""
    extra: dict[str, Any] = {}
    if isinstance(error, InvalidExpression):
        extra = {"position": error.position, "expression": error.expression}
    elif isinstance(error, SingularConfiguration):
        extra = {
            "condition_number": error.condition_number
            if error.condition_number < float("inf")
            else None
        }
    return problem(_status(error), error.code, error.message, **extra)


async def kinematics_error(_: Request, error: Exception) -> JSONResponse:
    assert isinstance(error, KinematicsError)
    return solver_problem(error)


def internal_problem() -> JSONResponse:
    return problem(500, "internal_error", "an unexpected error occurred; this is a defect")


def _location(loc: tuple[Any, ...]) -> str:
    parts = [str(p) for p in loc if p != "body"]
    return ".".join(parts) or "body"


async def validation_error(_: Request, error: Exception) -> JSONResponse:
    assert isinstance(error, RequestValidationError)
    messages = []
    for e in error.errors()[:10]:
        reason = e.get("ctx", {}).get("error", "")
        given = e.get("input")
        if isinstance(given, bool | int | float | str) and e["type"] != "missing":
            reason = reason or f"got {type(given).__name__} {str(given)[:40]!r}"
        messages.append(
            f"{_location(tuple(e['loc']))}: {e['msg']}" + (f" ({reason})" if reason else "")
        )
    return problem(422, "invalid_scene", "; ".join(messages) or "invalid request")


def allowed_methods(request: Request) -> str | None:
    """The methods the OpenAPI document gives the request's path, as a 405's ``Allow``: those of
    its concrete path if it has one, else of every templated path it matches (OpenAPI matches a
    concrete path before a templated one: ``/exercises/check`` is POST only, although GET
    ``/exercises/{exercise_id}`` would take it as an id); None for a path it does not name."""
    paths: dict[str, dict[str, Any]] = request.app.openapi()["paths"]
    path = request.url.path
    if path in paths:
        matching = [paths[path]]
    else:
        matching = [
            item
            for template, item in paths.items()
            if re.fullmatch(re.sub(r"\\\{[^/]+?\\\}", "[^/]+", re.escape(template)), path)
        ]
    methods = {method.upper() for item in matching for method in item}
    return ", ".join(sorted(methods)) or None


async def http_error(request: Request, error: Exception) -> JSONResponse:
    assert isinstance(error, HTTPException)
    code = {
        403: "forbidden",
        404: "not_found",
        405: "method_not_allowed",
        413: "limit_exceeded",
        415: "unsupported_media_type",
        503: "not_configured",
    }.get(error.status_code, "invalid_scene")
    response = problem(error.status_code, code, str(error.detail))
    response.headers.update(error.headers or {})  # a 405's Allow (the first route's methods)
    allow = allowed_methods(request) if error.status_code == 405 else None
    if allow is not None:  # every method of the path, as documented
        response.headers["Allow"] = allow
    return response


async def unexpected_error(_: Request, error: Exception) -> JSONResponse:
    log.exception("unexpected error", exc_info=error)
    return internal_problem()


def install(app: FastAPI) -> None:
    """Register the handlers: the single place where errors become responses."""
    app.add_exception_handler(KinematicsError, kinematics_error)
    app.add_exception_handler(RequestValidationError, validation_error)
    app.add_exception_handler(HTTPException, http_error)
    app.add_exception_handler(Exception, unexpected_error)

"""Solver results to HTTP responses: mechanical conversion, nothing computed here.

A result's ``as_dict()`` is the body (``solver.analysis.results``); the server takes it with the
sweep arrays kept as numpy arrays (``as_dict(arrays=True)``: orjson writes them natively, the same
bytes as the plain lists of ``as_dict()`` and several times faster, as is the finiteness check of
``server.edge`` on arrays). The body
is not validated against the route's response model: the model is published in the OpenAPI
document, and a contract test checks real responses against it.
"""

from __future__ import annotations

from fastapi.responses import JSONResponse

from server.edge import FiniteJSONResponse
from solver.analysis.results import Result


class ResultResponse(FiniteJSONResponse, JSONResponse):
    """orjson and the finiteness check of FiniteJSONResponse; a JSONResponse for FastAPI, which
    publishes a route's response model only for JSON response classes."""


def respond(result: Result) -> ResultResponse:
    """The 200 response of a solver result: its body, serialised by orjson."""
    return ResultResponse(result.as_dict(arrays=True))

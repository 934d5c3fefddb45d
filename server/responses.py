"""Solver results to HTTP responses: mechanical conversion, nothing computed here.

A result's ``as_dict()`` is the body (``solver.results``); it goes out through orjson, large
sweep arrays included, after the check that every number is finite (``server.edge``).
"""

from __future__ import annotations

from server.edge import FiniteJSONResponse
from solver.results import Result


def respond(result: Result) -> FiniteJSONResponse:
    """The 200 response of a solver result: its body, serialised by orjson."""
    return FiniteJSONResponse(result.as_dict())

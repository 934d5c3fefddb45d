"""POST /api/v1/analyze, POST /api/v1/sweep and POST /api/v1/events."""

from __future__ import annotations

from fastapi import APIRouter

import solver
from server.edge import StrictJSONRoute
from server.responses import ResultResponse, respond
from server.schemas import (
    PROBLEMS,
    AnalyzeRequest,
    AnalyzeResponse,
    EventResponse,
    EventsRequest,
    SweepRequest,
    SweepResponse,
    TimeSweepResponse,
)

router = APIRouter(
    tags=["kinematics"],
    route_class=StrictJSONRoute,
    default_response_class=ResultResponse,
    responses=PROBLEMS,
)


@router.post(
    "/analyze",
    summary="One instant: positions, velocities, accelerations, poles, slider components",
    response_model=AnalyzeResponse,
)
def analyze_route(request: AnalyzeRequest) -> ResultResponse:
    return respond(solver.analyze(request.scene, request.quantities, strict=request.strict))


@router.post(
    "/sweep",
    summary="The linkage over one revolution of its first driver (or its feasible range)",
    response_model=SweepResponse | TimeSweepResponse,
)
def sweep_route(request: SweepRequest) -> ResultResponse:
    if request.time_range is None:
        return respond(
            solver.sweep(
                request.scene,
                request.samples,
                request.quantities,
                strict=request.strict,
                speed_fluctuation=request.speed_fluctuation,
            )
        )
    return respond(
        solver.sweep_time(
            request.scene,
            request.time_range,
            request.samples,
            request.quantities,
            strict=request.strict,
        )
    )


@router.post(
    "/events",
    summary="The instant at which a moving point reaches a named point",
    response_model=EventResponse,
)
def events_route(request: EventsRequest) -> ResultResponse:
    e = request.event
    return respond(
        solver.find_event(
            request.scene, e.moving_point, e.reaches, e.occurrence, e.t_max, strict=request.strict
        )
    )

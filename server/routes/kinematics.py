"""POST /api/v1/analyze, POST /api/v1/sweep and POST /api/v1/events."""

from __future__ import annotations

from fastapi import APIRouter

from server.edge import FiniteJSONResponse, StrictJSONRoute
from server.responses import (
    analysis_response,
    spatial_response,
    sweep_response,
    time_sweep_response,
    vector,
)
from server.routes.scenes import parse_linkage_only, parse_scene
from server.schemas import AnalyzeRequest, EventsRequest, SweepRequest
from solver.analysis import analyze, normalise_quantities
from solver.errors import InvalidScene
from solver.events import find_event
from solver.scene import LinkageScene
from solver.spatial import analyze_spatial_chain
from solver.sweep import sweep, sweep_time

router = APIRouter(
    tags=["kinematics"], route_class=StrictJSONRoute, default_response_class=FiniteJSONResponse
)


@router.post(
    "/analyze",
    summary="One instant: positions, velocities, accelerations, poles, slider components",
)
def analyze_route(request: AnalyzeRequest) -> FiniteJSONResponse:
    scene = parse_scene(request.scene)
    if isinstance(scene, LinkageScene):
        result = analyze(scene, request.quantities, request.tolerance)
        return FiniteJSONResponse(analysis_response(result))
    wanted = normalise_quantities(request.quantities)
    return FiniteJSONResponse(spatial_response(analyze_spatial_chain(scene), wanted))


@router.post(
    "/sweep", summary="The linkage over one revolution of its first driver (or its feasible range)"
)
def sweep_route(request: SweepRequest) -> FiniteJSONResponse:
    scene = parse_linkage_only(request.scene, "/sweep")
    if request.time_range is None:
        result = sweep(scene, request.samples, request.quantities, request.tolerance)
        return FiniteJSONResponse(sweep_response(result))
    if len(request.time_range) != 2:
        raise InvalidScene("time_range: expected [t0, t1]")
    t0, t1 = request.time_range
    return FiniteJSONResponse(
        time_sweep_response(
            sweep_time(scene, t0, t1, request.samples, request.quantities, request.tolerance)
        )
    )


@router.post("/events", summary="The instant at which a moving point reaches a named point")
def events_route(request: EventsRequest) -> FiniteJSONResponse:
    scene = parse_linkage_only(request.scene, "/events")
    e = request.event
    event = find_event(scene, e.moving_point, e.reaches, e.occurrence, e.t_max)
    return FiniteJSONResponse(
        {
            "time": event.time,
            "position": vector(event.position),
            "moving_point": e.moving_point,
            "reaches": e.reaches,
            "occurrence": e.occurrence,
        }
    )

"""POST /api/v1/analyze, POST /api/v1/sweep and POST /api/v1/events.

Each runs in a worker process (``server.workers.WorkerRoute``); its cost is checked against the
budget (``server.budget``) in the server's process before it waits for a worker (``front_check``).
"""

from __future__ import annotations

from fastapi import APIRouter

import solver
from server import budget
from server.responses import ResultResponse, respond
from server.schemas import (
    PROBLEMS,
    AnalyzeAnswer,
    AnalyzeRequest,
    EventResponse,
    EventsRequest,
    SweepAnswer,
    SweepRequest,
)
from server.workers import WorkerRoute, front_check
from solver.analysis.work_estimate import SOLUTION_COST
from solver.cams import CamScene
from solver.model.scene import LinkageScene

router = APIRouter(
    tags=["kinematics"],
    route_class=WorkerRoute,
    default_response_class=ResultResponse,
    responses=PROBLEMS,
)


def analyze_cost(request: AnalyzeRequest) -> float:
    """The instant, and with ``polygons`` the vector method's steps they follow (built, not
    written: about half a solution's writing, counted as a whole one)."""
    extra = SOLUTION_COST if "polygons" in (request.quantities or ()) else 0.0
    return budget.read_instant(request.scene, request.strict, "/api/v1/analyze", extra)


@router.post(
    "/analyze",
    summary="One instant: positions, velocities, accelerations, poles, slider components",
    response_model=AnalyzeAnswer,
)
@front_check(analyze_cost)
def analyze_route(request: AnalyzeRequest) -> ResultResponse:
    read = solver.read_scene(request.scene, strict=request.strict)
    return respond(
        solver.analyze(
            read,
            request.quantities,
            tolerance=request.tolerance,
            angle_deg=request.angle_deg,
            input_torque=request.input_torque,
            statics=request.statics,
        )
    )


def sweep_cost(request: SweepRequest) -> float:
    read = solver.read_scene(request.scene, strict=request.strict)
    if isinstance(read.scene, LinkageScene):
        return budget.sweep(read.scene, request.samples, request.quantities, request.time_range)
    if isinstance(read.scene, CamScene):
        return budget.cam_sweep(read.scene, request.samples)
    if request.time_range is not None:  # a spatial chain moves in time only
        return budget.spatial_sweep(read.scene, request.samples, request.quantities)
    return 0.0  # refused by the solver


@router.post(
    "/sweep",
    summary="The linkage over one revolution of its first driver (or its feasible range), or "
    "the scene over a time range",
    response_model=SweepAnswer,
)
@front_check(sweep_cost)
def sweep_route(request: SweepRequest) -> ResultResponse:
    read = solver.read_scene(request.scene, strict=request.strict)
    if request.time_range is None:
        return respond(
            solver.sweep(
                read,
                request.samples,
                request.quantities,
                speed_fluctuation=request.speed_fluctuation,
                tolerance=request.tolerance,
                statics=request.statics,
            )
        )
    return respond(
        solver.sweep_time(
            read,
            request.time_range,
            request.samples,
            request.quantities,
            tolerance=request.tolerance,
            statics=request.statics,
        )
    )


def events_cost(request: EventsRequest) -> float:
    read = solver.read_scene(request.scene, strict=request.strict)
    e = request.event
    if isinstance(read.scene, LinkageScene):  # a spatial chain is refused by the solver
        return budget.event(read.scene, e.moving_point, e.t_max, e.reaches)
    return 0.0


@router.post(
    "/events",
    summary="The instant at which a moving point reaches a named point",
    response_model=EventResponse,
)
@front_check(events_cost)
def events_route(request: EventsRequest) -> ResultResponse:
    read = solver.read_scene(request.scene, strict=request.strict)
    e = request.event
    return respond(solver.find_event(read, e.moving_point, e.reaches, e.occurrence, e.t_max))

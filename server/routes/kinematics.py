"""POST /api/v1/analyze and POST /api/v1/sweep."""

from __future__ import annotations

from fastapi import APIRouter

from server.edge import FiniteJSONResponse, StrictJSONRoute
from server.responses import analysis_response, spatial_response, sweep_response
from server.routes.scenes import parse_linkage_only, parse_scene
from server.schemas import AnalyzeRequest, SweepRequest
from solver.analysis import analyze, normalise_quantities
from solver.scene import LinkageScene
from solver.spatial import analyze_spatial_chain
from solver.sweep import sweep

router = APIRouter(tags=["kinematics"], route_class=StrictJSONRoute,
                   default_response_class=FiniteJSONResponse)


@router.post("/analyze", summary="One instant: positions, velocities, accelerations, poles, "
             "slider components")
def analyze_route(request: AnalyzeRequest) -> FiniteJSONResponse:
    scene = parse_scene(request.scene)
    if isinstance(scene, LinkageScene):
        return FiniteJSONResponse(analysis_response(analyze(scene, request.quantities)))
    wanted = normalise_quantities(request.quantities)
    return FiniteJSONResponse(spatial_response(analyze_spatial_chain(scene), wanted))


@router.post("/sweep", summary="The linkage over one revolution of its first driver (or its "
             "feasible range)")
def sweep_route(request: SweepRequest) -> FiniteJSONResponse:
    scene = parse_linkage_only(request.scene, "/sweep")
    return FiniteJSONResponse(sweep_response(sweep(scene, request.samples, request.quantities)))
